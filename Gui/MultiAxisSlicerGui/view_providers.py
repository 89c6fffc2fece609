# SPDX-License-Identifier: LGPL-2.1-or-later
"""View providers of the Multi-Axis Slicer document objects."""

import MultiAxisSlicerGui

# Sections are drawn as lines over the part: a colour that stands out from FreeCAD's grey solids.
SECTION_LINE_COLOR = (1.0, 0.45, 0.0)  # orange
SECTION_LINE_WIDTH = 2.0


class _Stateless:
    """A view provider proxy with nothing to save (colours are view properties): 0.20.2 calls
    __getstate__/__setstate__, 0.21.2 and later dumps/loads."""

    def __getstate__(self):
        return None

    def __setstate__(self, state):
        return None

    def dumps(self):
        return None

    def loads(self, state):
        return None


class ViewProviderSections(_Stateless):
    """Tree icon and line style of a ``Sections`` object. The source stays as it is (visible, not
    claimed as a child): the sections are read against the part."""

    def __init__(self, vobj):
        vobj.Proxy = self
        vobj.LineColor = SECTION_LINE_COLOR
        vobj.LineWidth = SECTION_LINE_WIDTH
        vobj.PointColor = SECTION_LINE_COLOR
        vobj.PointSize = 1.0

    def attach(self, vobj):
        self.Object = vobj.Object

    def getIcon(self):
        return MultiAxisSlicerGui.icon_path("Sections.svg")



# The centroidal axis: nodes as dots, links as lines, C1 breaks in red. It lies inside its part,
# so by default it is drawn over it (DrawOnTop).
AXIS_LINE_COLOR = (0.0, 0.33, 0.85)  # blue
AXIS_BREAK_COLOR = (0.9, 0.0, 0.0)  # red
AXIS_POINT_COLOR = (0.0, 0.0, 0.0)  # black
AXIS_LINE_WIDTH = 3.0
AXIS_POINT_SIZE = 6.0


def _same_colours(a, b):
    """Colour lists equal to within their 8-bit storage (FreeCAD keeps r, g, b and alpha)."""
    return len(a) == len(b) and all(
        abs(x - y) <= 1.0 / 512 for ca, cb in zip(a, b) for x, y in zip(ca[:3], cb[:3]))


class ViewProviderCentroidalAxis(_Stateless):
    """Tree icon and style of a ``CentroidalAxis`` object: nodes as points (PointColor,
    PointSize), links as lines (LineColor, LineWidth), C1 break links in BreakLineColor.

    Break links are coloured per edge with the Part view provider's LineColorArray (0.20.2 has it
    and keeps it across recomputes): the object's Shape lists the ordinary links first and the
    breaks from edge BreakEdgeStart on. FreeCAD resets LineColorArray to one colour when LineColor
    changes, so the array is rebuilt whenever either changes. The source stays as it is."""

    def __init__(self, vobj):
        vobj.addProperty("App::PropertyColor", "BreakLineColor", "Object Style",
                         "Colour of the links that are C1 breaks")
        vobj.BreakLineColor = AXIS_BREAK_COLOR
        vobj.addProperty("App::PropertyBool", "DrawOnTop", "Object Style",
                         "Draw the axis over the part it lies in")
        vobj.DrawOnTop = True
        vobj.LineColor = AXIS_LINE_COLOR
        vobj.LineWidth = AXIS_LINE_WIDTH
        vobj.PointColor = AXIS_POINT_COLOR
        vobj.PointSize = AXIS_POINT_SIZE
        vobj.Proxy = self  # calls attach()
        self.colour_edges(vobj)

    def attach(self, vobj):
        from pivy import coin

        self.Object = vobj.Object
        # Depth test off for this object's nodes only (the root is a separator): drawn after the
        # part, the axis shows through it.
        self._depth = coin.SoDepthBuffer()
        self._depth.function = coin.SoDepthBuffer.ALWAYS
        vobj.RootNode.insertChild(self._depth, 0)
        self.update_depth(vobj)

    def update_depth(self, vobj):
        depth = getattr(self, "_depth", None)
        if depth is None:
            return
        on_top = vobj.DrawOnTop if "DrawOnTop" in vobj.PropertiesList else True
        depth.function = depth.ALWAYS if on_top else depth.LESS

    def updateData(self, obj, prop):
        if prop == "Shape" and obj.ViewObject is not None:
            self.colour_edges(obj.ViewObject)

    def onChanged(self, vobj, prop):
        if prop in ("LineColor", "LineColorArray", "BreakLineColor"):
            self.colour_edges(vobj)
        elif prop == "DrawOnTop":
            self.update_depth(vobj)

    @staticmethod
    def colour_edges(vobj):
        """LineColorArray: LineColor for the ordinary links, BreakLineColor for the breaks."""
        obj = vobj.Object
        if (obj is None or "BreakEdgeStart" not in obj.PropertiesList
                or "BreakLineColor" not in vobj.PropertiesList):
            return  # still being set up or restored
        edges = len(obj.Shape.Edges)
        first_break = min(max(obj.BreakEdgeStart, 0), edges)
        line, broken = tuple(vobj.LineColor), tuple(vobj.BreakLineColor)
        if first_break == edges:  # no breaks: one colour
            colours = [line]
        else:
            colours = [line] * first_break + [broken] * (edges - first_break)
        if not _same_colours(vobj.LineColorArray, colours):  # also ends the LineColor round trip
            vobj.LineColorArray = colours

    def getIcon(self):
        return MultiAxisSlicerGui.icon_path("CentroidalAxis.svg")
