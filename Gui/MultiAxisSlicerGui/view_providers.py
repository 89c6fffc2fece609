# SPDX-License-Identifier: LGPL-2.1-or-later
"""View providers of the Multi-Axis Slicer document objects."""

import MultiAxisSlicerGui
import MultiAxisSlicerGui.progress

# Any document with these objects in the GUI imports this module: their recomputes show progress.
MultiAxisSlicerGui.progress.install()

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


class _Editable:
    """Double-click (or EDIT_MENU_TEXT in the context menu) opens the object's panel in the task
    view: the module PANEL_MODULE of this package (edit(), open_panel(), close_panel()), by
    default its parameter panel (parameter_panel.py); the other edit modes (Transform, colours)
    stay FreeCAD's."""

    EDIT_MENU_TEXT = "Edit parameters..."
    PANEL_MODULE = "parameter_panel"

    def _panels(self):
        import importlib

        return importlib.import_module("MultiAxisSlicerGui." + self.PANEL_MODULE)

    def doubleClicked(self, vobj):
        return self._panels().edit(vobj.Object)

    def setupContextMenu(self, vobj, menu):
        import FreeCAD

        action = menu.addAction(self.EDIT_MENU_TEXT)
        name, doc = vobj.Object.Name, vobj.Object.Document.Name
        panels = self._panels()

        def edit():
            obj = FreeCAD.getDocument(doc).getObject(name)
            if obj is not None:
                panels.edit(obj)

        action.triggered.connect(edit)

    def setEdit(self, vobj, mode=0):
        if mode != 0:
            return None  # FreeCAD's own
        return self._panels().open_panel(vobj.Object)

    def unsetEdit(self, vobj, mode=0):
        if mode != 0:
            return None
        self._panels().close_panel()
        return True


class _LineStyled(_Stateless):
    """Tree icon and line style of an object drawn as lines: a subclass sets LINE_COLOR,
    LINE_WIDTH, ICON and, unless solid, DRAW_STYLE."""

    LINE_COLOR = (0.0, 0.0, 0.0)
    LINE_WIDTH = 1.0
    ICON = ""
    DRAW_STYLE = None

    def __init__(self, vobj):
        vobj.Proxy = self
        vobj.LineColor = self.LINE_COLOR
        vobj.LineWidth = self.LINE_WIDTH
        vobj.PointColor = self.LINE_COLOR
        vobj.PointSize = 1.0
        if self.DRAW_STYLE is not None:
            vobj.DrawStyle = self.DRAW_STYLE

    def attach(self, vobj):
        self.Object = vobj.Object

    def getIcon(self):
        return MultiAxisSlicerGui.icon_path(self.ICON)


class ViewProviderSections(_Editable, _LineStyled):
    """Tree icon and line style of a ``Sections`` object. The source stays as it is (visible, not
    claimed as a child): the sections are read against the part."""

    LINE_COLOR = SECTION_LINE_COLOR
    LINE_WIDTH = SECTION_LINE_WIDTH
    ICON = "Sections.svg"



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


class ViewProviderCentroidalAxis(_Editable, _Stateless):
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
                         "Draw the axis over the part it lies in and over other objects")
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
        # For this object's nodes only (the root is a separator): no depth test, so the axis shows
        # through what was drawn before it, and every fragment written at the nearest depth (a
        # depth range of [0, 0]), so that what is drawn after it (Components made later, which
        # come later in the scene) stays behind it.
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
        depth.range.setValue(0.0, 0.0 if on_top else 1.0)

    def updateData(self, obj, prop):
        if prop == "Shape" and obj.ViewObject is not None:
            self.colour_edges(obj.ViewObject)
            refresh_line_colours_later(obj.ViewObject)

    def onChanged(self, vobj, prop):
        if prop in ("LineColor", "LineColorArray", "BreakLineColor"):
            self.colour_edges(vobj)
        elif prop == "DrawOnTop":
            self.update_depth(vobj)
        elif prop == "Visibility" and vobj.Visibility:  # a hidden object is redrawn when shown
            refresh_line_colours_later(vobj)

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


# Sub-components: one distinct colour each, the root first (a qualitative palette, Tableau 10,
# with the grey left out so that no component looks like an ordinary FreeCAD solid, and the red,
# which marks what is wrong: unsupported regions, the axis' breaks).
COMPONENT_COLOURS = [
    (0.12, 0.47, 0.71),  # blue
    (1.00, 0.50, 0.05),  # orange
    (0.17, 0.63, 0.17),  # green
    (0.58, 0.40, 0.74),  # purple
    (0.55, 0.34, 0.29),  # brown
    (0.89, 0.47, 0.76),  # pink
    (0.74, 0.74, 0.13),  # olive
    (0.09, 0.75, 0.81),  # cyan
]


def component_colour(index):
    """The colour of component `index` (tree order); the palette repeats after eight."""
    return COMPONENT_COLOURS[index % len(COMPONENT_COLOURS)]


class ViewProviderDecomposition(_Editable, _Stateless):
    """Tree icon and colours of a ``Decomposition`` object. Its Component objects are its children
    in the tree (Component001, ... in tree order) and are what the 3D view shows; the object's own
    compound is hidden by default and, when shown, coloured per component with DiffuseColor (one
    colour per face, the component's). After a recompute that changes the number of components,
    the Component objects are added or removed (outside the recompute, on the next event loop
    turn)."""

    def __init__(self, vobj):
        vobj.Proxy = self  # calls attach()
        vobj.Visibility = False
        self.colour_faces(vobj)

    def attach(self, vobj):
        self.Object = vobj.Object

    def claimChildren(self):
        import MultiAxisSlicer.features as features

        obj = getattr(self, "Object", None)
        if obj is None:
            return []
        try:
            return features.components_of(obj)
        except Exception:  # an object being deleted or restored
            return []

    def onDelete(self, vobj, subelements):
        """Deleting the decomposition deletes its components (they only show its solids) and
        shows the part again, which the Decompose command hid, unless another decomposition of
        it is left: its components still show the part."""
        import MultiAxisSlicer.features as features

        obj = vobj.Object
        for c in features.components_of(obj):
            obj.Document.removeObject(c.Name)
        source = features.decomposed_part(obj)
        others = [o for o in obj.Document.Objects if o is not obj
                  and features.is_decomposition(o) and features.decomposed_part(o) is source]
        if source is not None and source.ViewObject is not None and not others:
            source.ViewObject.Visibility = True
        return True

    def updateData(self, obj, prop):
        if prop == "Shape" and obj.ViewObject is not None:
            self.colour_faces(obj.ViewObject)
        elif prop == "ComponentCount":
            self._sync_later(obj)

    @staticmethod
    def _sync_later(obj):
        doc = obj.Document
        if getattr(doc, "Restoring", False) or getattr(doc, "Transacting", False):
            return  # opening a file or undoing: the objects come back by themselves
        name, doc_name = obj.Name, doc.Name
        from PySide import QtCore

        def sync():
            import FreeCAD
            import MultiAxisSlicer.features as features

            d = FreeCAD.listDocuments().get(doc_name)
            o = d.getObject(name) if d is not None else None
            if o is None or getattr(d, "Transacting", False) or "Invalid" in o.State:
                return
            if getattr(d, "Recomputing", False):
                # The recompute that changed the count goes on (the objects after it report
                # progress, which lets this timer fire): objects can be neither added nor removed
                # until it ends.
                QtCore.QTimer.singleShot(50, sync)
                return
            if len(features.components_of(o)) == o.ComponentCount:
                return
            # Into the transaction still open, if any (a command's); else an undo step of its own
            # that says what it is.
            own = not d.HasPendingTransaction
            if own:
                d.openTransaction("Components of '{}'".format(o.Label))
            try:
                features.sync_components(o)
            finally:
                if own:
                    d.commitTransaction()

        QtCore.QTimer.singleShot(0, sync)

    @staticmethod
    def colour_faces(vobj):
        obj = vobj.Object
        if obj is None or "ComponentCount" not in obj.PropertiesList:
            return
        colours = []
        # One child shape per component (a root on several feet: a compound of its solids).
        shape = obj.Shape
        for i, component in enumerate(shape.childShapes() if not shape.isNull() else []):
            colours += [component_colour(i)] * len(component.Faces)
        if colours and not _same_colours(vobj.DiffuseColor, colours):
            vobj.DiffuseColor = colours

    def getIcon(self):
        return MultiAxisSlicerGui.icon_path("Decompose.svg")


class ViewProviderComponent(_Stateless):
    """Tree icon and colour of a ``Component`` object: its ShapeColor is its index's colour."""

    def __init__(self, vobj):
        vobj.Proxy = self
        self.colour(vobj)

    def attach(self, vobj):
        self.Object = vobj.Object

    def updateData(self, obj, prop):
        if (prop == "Index" and obj.ViewObject is not None
                and not getattr(obj.Document, "Restoring", False)):  # keep a saved colour
            self.colour(obj.ViewObject)

    @staticmethod
    def colour(vobj):
        obj = vobj.Object
        if obj is None or "Index" not in obj.PropertiesList:
            return
        vobj.ShapeColor = component_colour(obj.Index)

    def onDelete(self, vobj, subelements):
        """A component only shows one solid of its decomposition, which would still slice it and
        bring it back on its next recompute: deleting it alone is refused, saying so. With its
        Decomposition it goes (the Decomposition's own delete takes its components)."""
        import FreeCADGui

        decomposition = getattr(vobj.Object, "Decomposition", None)
        if decomposition is None or decomposition in FreeCADGui.Selection.getSelection():
            return True
        MultiAxisSlicerGui.show_error(
            "'{}' is one sub-component of '{}' and cannot be deleted on its own: the "
            "decomposition would still hold it (and slice it). Hide it, change the "
            "decomposition's parameters, or delete the decomposition.".format(
                vobj.Object.Label, decomposition.Label))
        return False

    def getIcon(self):
        return MultiAxisSlicerGui.icon_path("Decompose.svg")


def _edge_colours(shape, colours):
    """One colour per edge of a compound of sub-compounds: every edge of sub-compound i in
    colours[i] (edges in the order FreeCAD lists them: sub-compound by sub-compound)."""
    if shape.isNull():  # not computed yet
        return []
    out = []
    for child, colour in zip(shape.childShapes(), colours):
        out += [colour] * len(child.Edges)
    return out


def refresh_line_colours_later(vobj):
    """Sets LineColorArray again once the event loop turns, so that it colours the line set FreeCAD
    drew for the current Shape.

    FreeCAD 0.20 copies LineColorArray into the 3D view's line set as the set is at that moment
    and leaves the entries past its edges uninitialised; a proxy's updateData runs before the
    view provider redraws the set for a new Shape, and a hidden object is redrawn only when shown.
    Colours set from updateData alone would thus colour the previous shape's edges."""
    obj = vobj.Object
    if obj is None or obj.Document is None:
        return
    doc_name, name = obj.Document.Name, obj.Name
    from PySide import QtCore

    def refresh():
        import FreeCAD

        doc = FreeCAD.listDocuments().get(doc_name)
        o = doc.getObject(name) if doc is not None else None
        if o is None or o.ViewObject is None or getattr(doc, "Restoring", False):
            return
        colours = o.ViewObject.LineColorArray
        if len(colours) > 1:
            o.ViewObject.LineColorArray = colours

    QtCore.QTimer.singleShot(0, refresh)


def _set_line_colours(vobj, colours):
    """LineColorArray = colours (one colour: all alike), unless it holds them already (which also
    ends the round trip when FreeCAD resets the array after a LineColor change)."""
    if not colours:
        return
    if all(c == colours[0] for c in colours):
        colours = [colours[0]]
    if not _same_colours(vobj.LineColorArray, colours):
        vobj.LineColorArray = colours


class _EdgeColoured(_Stateless):
    """Colours per edge through LineColorArray (``colour_edges``, of the subclass), set again
    whenever the Shape, a colour property (``COLOUR_PROPERTIES``) or the visibility changes, and
    once a reopened document is drawn (see refresh_line_colours_later)."""

    COLOUR_PROPERTIES = ("LineColor", "LineColorArray")

    def attach(self, vobj):
        self.Object = vobj.Object
        refresh_line_colours_later(vobj)  # a reopened document: once its view is drawn

    def updateData(self, obj, prop):
        if prop == "Shape" and obj.ViewObject is not None:
            self.colour_edges(obj.ViewObject)
            refresh_line_colours_later(obj.ViewObject)

    def onChanged(self, vobj, prop):
        if prop in self.COLOUR_PROPERTIES:
            self.colour_edges(vobj)
        elif prop == "Visibility" and vobj.Visibility:  # a hidden object is redrawn when shown
            refresh_line_colours_later(vobj)


# Layers: the outlines in their component's colour (the Component objects' palette); the only
# faces, where a layer stands on nothing, filled and outlined in ShapeColor, plain red. Most such
# regions are slivers along an overhanging edge, which only their outline makes visible.
LAYERS_LINE_WIDTH = 2.0
UNSUPPORTED_COLOUR = (1.0, 0.0, 0.0)


def layer_edge_colours(shape, components, unsupported_colour):
    """One colour per edge of a Layers object's Shape: each sub-compound's outline edges in its
    component's colour, then the edges of its faces (the unsupported regions, which come after
    the outline wires) in `unsupported_colour`."""
    if shape.isNull():  # not computed yet
        return []
    out = []
    for child, component in zip(shape.childShapes(), components):
        unsupported = sum(len(f.Edges) for f in child.Faces)
        out += [component_colour(component)] * (len(child.Edges) - unsupported)
        out += [unsupported_colour] * unsupported
    return out


# Holes deposited solid, to drill afterwards (the Layers' FillHoles): each drawn as its axis and
# a circle of its diameter at each end, in DrillColor.
DRILL_COLOUR = (0.0, 0.0, 0.0)  # black: no component's colour
DRILL_LINE_WIDTH = 3.0
DRILL_CIRCLE_SEGMENTS = 32
COLLISION_COLOUR = (1.0, 0.0, 1.0)  # magenta: no component's colour, nor red or black
COLLISION_LINE_WIDTH = 3.0
COLLISION_POINT_SIZE = 9.0
_COLLISION_PROPERTIES = ("CollisionPoints", "CollisionNozzlePoints")
_DRILL_PROPERTIES = ("FilledHoleCentres", "FilledHoleAxes", "FilledHoleDiameters",
                     "FilledHoleLengths")


def drill_polylines(centres, axes, diameters, lengths, segments=DRILL_CIRCLE_SEGMENTS):
    """Per hole to drill, three polylines as lists of FreeCAD.Vector: its axis from end to end,
    then a closed circle of its diameter square to the axis at each end (segments + 1 points,
    the first repeated last)."""
    import math

    import FreeCAD

    out = []
    for c, a, d, length in zip(centres, axes, diameters, lengths):
        a = FreeCAD.Vector(a)
        if a.Length == 0.0:
            continue
        a.normalize()
        # Two unit vectors square to the axis.
        helper = FreeCAD.Vector(1, 0, 0) if abs(a.x) < 0.9 else FreeCAD.Vector(0, 1, 0)
        u = a.cross(helper)
        u.normalize()
        v = a.cross(u)
        ends = [c - a * (0.5 * length), c + a * (0.5 * length)]
        out.append(ends)
        for e in ends:
            out.append([e + u * (0.5 * d * math.cos(2 * math.pi * k / segments))
                        + v * (0.5 * d * math.sin(2 * math.pi * k / segments))
                        for k in range(segments + 1)])
    return out


def _overlay_switch(vobj):
    """A switch added to an object's root node for its overlays (below), on while the object is
    shown: FreeCAD hides an object by the switch of its display modes only, and what else its root
    node holds was drawn still (a hidden Layers object's holes to drill and collisions)."""
    from pivy import coin

    switch = coin.SoSwitch()
    _show_overlays(switch, vobj.Visibility)
    vobj.RootNode.addChild(switch)
    return switch


def _show_overlays(switch, shown):
    from pivy import coin

    switch.whichChild = coin.SO_SWITCH_ALL if shown else coin.SO_SWITCH_NONE


def _overlay(vobj, switch, colour_property, default, doc, line_width, point_size=None):
    """Lines drawn over an object's Shape in one colour, whatever the lights and the display mode:
    (separator, SoBaseColor, SoCoordinate3, SoLineSet), added to `switch` (its _overlay_switch(),
    so that they hide with it). The colour is the view property `colour_property`, added with
    `default` if the object lacks it (new, or from a document saved before it)."""
    from pivy import coin

    if colour_property not in vobj.PropertiesList:
        vobj.addProperty("App::PropertyColor", colour_property, "Object Style", doc)
        setattr(vobj, colour_property, default)
    separator = coin.SoSeparator()
    light = coin.SoLightModel()  # the colour as it is, whatever the lights
    light.model = coin.SoLightModel.BASE_COLOR
    colour = coin.SoBaseColor()
    style = coin.SoDrawStyle()
    style.lineWidth = line_width
    if point_size is not None:
        style.pointSize = point_size
    points = coin.SoCoordinate3()
    lines = coin.SoLineSet()
    for node in (light, colour, style, points, lines):
        separator.addChild(node)
    switch.addChild(separator)
    return separator, colour, points, lines


def _overlay_colour(vobj, colour_property, default):
    """The colour of an overlay (above): its view property, or `default` while it is missing."""
    return (tuple(getattr(vobj, colour_property))[:3]
            if colour_property in vobj.PropertiesList else default)


class ViewProviderLayers(_Editable, _EdgeColoured):
    """Tree icon and colours of a ``Layers`` object: every layer's outline in its component's
    colour (``component_colour``, as the Component objects), per edge through LineColorArray. The
    object's Shape holds one sub-compound per layer and LayerComponents names each one's
    component. FreeCAD resets LineColorArray when LineColor changes: the colours are rebuilt
    then. The decomposition stays as it is. The Shape's faces mark where a layer is unsupported:
    ShapeColor (red by default) fills and outlines them. The holes deposited solid to drill
    afterwards (FillHoles) are drawn as their axes and end circles in DrillColor, from the
    object's FilledHole* properties, in every display mode; the layers whose nozzle meets what is
    deposited as a line in CollisionColor from the deposit point to the obstacle's point, and
    that point, from its Collision*Points properties."""

    COLOUR_PROPERTIES = _EdgeColoured.COLOUR_PROPERTIES + ("ShapeColor",)

    def __init__(self, vobj):
        vobj.LineWidth = LAYERS_LINE_WIDTH
        vobj.PointSize = 1.0
        vobj.ShapeColor = UNSUPPORTED_COLOUR
        vobj.Proxy = self  # calls attach()
        self.colour_edges(vobj)

    def attach(self, vobj):
        from pivy import coin

        super().attach(vobj)
        self.overlays = _overlay_switch(vobj)
        (self.drills, self.drill_colour, self.drill_points,
         self.drill_lines) = _overlay(vobj, self.overlays, "DrillColor", DRILL_COLOUR,
                                      "Colour of the holes deposited solid, to drill afterwards",
                                      DRILL_LINE_WIDTH)
        self.update_drills(vobj)
        (self.collisions, self.collision_colour, self.collision_points,
         self.collision_lines) = _overlay(vobj, self.overlays, "CollisionColor", COLLISION_COLOUR,
                                          "Colour of the collisions: from where the nozzle stands "
                                          "to what it meets", COLLISION_LINE_WIDTH,
                                          COLLISION_POINT_SIZE)
        self.collision_marks = coin.SoPointSet()  # the obstacles' points
        self.collisions.addChild(self.collision_marks)
        self.update_collisions(vobj)

    def update_collisions(self, vobj):
        """The collision markers from the object's Collision*Points and CollisionColor: a line
        from each colliding layer's deposit point to the obstacle's point, and that point."""
        if getattr(self, "collisions", None) is None:
            return
        obj = vobj.Object
        self.collision_colour.rgb.setValue(*_overlay_colour(vobj, "CollisionColor",
                                                            COLLISION_COLOUR))
        pairs = []
        if obj is not None and all(p in obj.PropertiesList for p in _COLLISION_PROPERTIES):
            pairs = list(zip(obj.CollisionNozzlePoints, obj.CollisionPoints))
        self.collision_lines.numVertices.setNum(0)
        self.collision_points.point.setNum(0)
        self.collision_marks.startIndex = 0
        self.collision_marks.numPoints = 0
        if pairs:
            # The obstacles' points first (the point set), then each line's two ends.
            points = [(b.x, b.y, b.z) for _, b in pairs]
            for a, b in pairs:
                points += [(a.x, a.y, a.z), (b.x, b.y, b.z)]
            self.collision_points.point.setValues(0, len(points), points)
            self.collision_marks.numPoints = len(pairs)
            self.collision_lines.startIndex = len(pairs)
            self.collision_lines.numVertices.setValues(0, len(pairs), [2] * len(pairs))

    def update_drills(self, vobj):
        """The drill markers from the object's FilledHole* properties and DrillColor."""
        if getattr(self, "drills", None) is None:
            return
        obj = vobj.Object
        self.drill_colour.rgb.setValue(*_overlay_colour(vobj, "DrillColor", DRILL_COLOUR))
        lines = []
        if obj is not None and all(p in obj.PropertiesList for p in _DRILL_PROPERTIES):
            lines = drill_polylines(obj.FilledHoleCentres, obj.FilledHoleAxes,
                                    obj.FilledHoleDiameters, obj.FilledHoleLengths)
        points = [(p.x, p.y, p.z) for line in lines for p in line]
        self.drill_lines.numVertices.setNum(0)
        self.drill_points.point.setNum(0)
        if points:
            self.drill_points.point.setValues(0, len(points), points)
            self.drill_lines.numVertices.setValues(0, len(lines), [len(line) for line in lines])

    def updateData(self, obj, prop):
        super().updateData(obj, prop)
        if prop in _DRILL_PROPERTIES and obj.ViewObject is not None:
            self.update_drills(obj.ViewObject)
        if prop in _COLLISION_PROPERTIES and obj.ViewObject is not None:
            self.update_collisions(obj.ViewObject)

    def onChanged(self, vobj, prop):
        super().onChanged(vobj, prop)
        if prop == "Visibility" and getattr(self, "overlays", None) is not None:
            _show_overlays(self.overlays, vobj.Visibility)
        if prop == "DrillColor":
            self.update_drills(vobj)
        if prop == "CollisionColor":
            self.update_collisions(vobj)

    @staticmethod
    def colour_edges(vobj):
        obj = vobj.Object
        if obj is None or "LayerComponents" not in obj.PropertiesList:
            return  # still being set up or restored
        _set_line_colours(vobj, layer_edge_colours(obj.Shape, obj.LayerComponents,
                                                   tuple(vobj.ShapeColor)[:3]))

    def onDelete(self, vobj, subelements):
        """Deleting the layers shows the components they were sliced from again (the Slice
        command hid them, and the part), or the mesh they were sliced from."""
        import MultiAxisSlicer.features as features

        decomposition = getattr(vobj.Object, "Decomposition", None)
        shown = features.components_of(decomposition) if decomposition is not None else []
        mesh = features.sliced_mesh(vobj.Object) if vobj.Object is not None else None
        if mesh is not None:
            shown.append(mesh)
        for o in shown:
            if o.ViewObject is not None:
                o.ViewObject.Visibility = True
        return True

    def getIcon(self):
        return MultiAxisSlicerGui.icon_path("Slice.svg")


# Toolpath: one colour per kind of path, in the order of the object's sub-compounds (contour,
# infill, centre line, travel); none of them a component's colour, so that paths and layer outlines
# shown together stay apart.
TOOLPATH_COLOURS = {
    "ContourColor": ((0.65, 0.0, 0.0), "Colour of the contour paths"),  # dark red
    "InfillColor": ((0.0, 0.5, 0.45), "Colour of the infill paths"),  # teal
    "CentreLineColor": ((0.85, 0.0, 0.85), "Colour of the centre-line paths"),  # magenta
    "TravelColor": ((0.6, 0.6, 0.6), "Colour of the travel moves (ShowTravel)"),  # grey
}
TOOLPATH_COLOUR_ORDER = ("ContourColor", "InfillColor", "CentreLineColor", "TravelColor")
TOOLPATH_LINE_WIDTH = 1.0


class ViewProviderToolpath(_Editable, _EdgeColoured):
    """Tree icon and colours of a ``Toolpath`` object: contours, infill, centre lines and travel
    moves each in their own colour (view properties ContourColor, InfillColor, CentreLineColor,
    TravelColor), per edge through LineColorArray. The object's Shape holds one sub-compound per
    kind, in that order."""

    COLOUR_PROPERTIES = _EdgeColoured.COLOUR_PROPERTIES + TOOLPATH_COLOUR_ORDER

    def __init__(self, vobj):
        for prop in TOOLPATH_COLOUR_ORDER:
            colour, doc = TOOLPATH_COLOURS[prop]
            vobj.addProperty("App::PropertyColor", prop, "Object Style", doc)
            setattr(vobj, prop, colour)
        vobj.LineWidth = TOOLPATH_LINE_WIDTH
        vobj.PointSize = 1.0
        vobj.Proxy = self  # calls attach()
        self.colour_edges(vobj)

    @staticmethod
    def colour_edges(vobj):
        obj = vobj.Object
        if obj is None or "PathCounts" not in obj.PropertiesList or not all(
                p in vobj.PropertiesList for p in TOOLPATH_COLOUR_ORDER):
            return  # still being set up or restored
        colours = [tuple(getattr(vobj, p))[:3] for p in TOOLPATH_COLOUR_ORDER]
        _set_line_colours(vobj, _edge_colours(obj.Shape, colours))

    def getIcon(self):
        return MultiAxisSlicerGui.icon_path("Toolpath.svg")


# MachineProgram: the moves made with the deposition off, dashed, in a blue no component gets.
PROGRAM_LINE_COLOR = (0.2, 0.3, 0.75)
PROGRAM_LINE_WIDTH = 1.0


class ViewProviderMachineProgram(_Editable, _LineStyled):
    """Tree icon and line style of a ``MachineProgram`` object: its travel moves (retracts,
    approaches, routes round the part), dashed."""

    LINE_COLOR = PROGRAM_LINE_COLOR
    LINE_WIDTH = PROGRAM_LINE_WIDTH
    ICON = "MachineProgram.svg"
    DRAW_STYLE = "Dashed"


# BuildPreview: the layers deposited in their component's colour, every other layer of a component
# a shade darker so that the layers show as bands, the step's layer in a yellow no component
# gets, the nozzle in a light grey, or in CollisionColor's magenta where it meets what is
# deposited.
BUILD_PREVIEW_COLOURS = {
    "CurrentLayerColor": ((1.0, 0.85, 0.0), "Colour of the layer being deposited at the step"),
    "NozzleColor": ((0.75, 0.75, 0.78), "Colour of the nozzle"),
    "CollisionColor": (COLLISION_COLOUR,
                       "Colour of the nozzle where it meets what is deposited (a layer no order "
                       "or lean clears)"),
    "PathColor": ((0.1, 0.1, 0.1), "Colour of the step's deposit paths"),
    "UnsupportedColor": (UNSUPPORTED_COLOUR,
                         "Colour of where the step's layer stands on nothing (seen through it)"),
    "PlateColor": ((0.45, 0.47, 0.5), "Colour of the build plate (see-through)"),
}
BUILD_PREVIEW_BAND_SHADE = 0.8
# The step's layer is drawn this transparent: what it stands on, and where it stands on nothing,
# show through it.
BUILD_PREVIEW_CURRENT_TRANSPARENCY = 0.4
# The plate so: the part's underside shows through it from below.
BUILD_PREVIEW_PLATE_TRANSPARENCY = 0.6
BUILD_PREVIEW_PATH_WIDTH = 1.5
# More layers than this to draw anew show the wait cursor.
BUILD_PREVIEW_QUIET_LAYERS = 100


class _WaitCursor:
    """The wait cursor while a block runs, if `shown`."""

    def __init__(self, shown):
        self.shown = shown

    def __enter__(self):
        if self.shown:
            from PySide import QtCore, QtGui

            QtGui.QApplication.setOverrideCursor(QtCore.Qt.WaitCursor)
        return self

    def __exit__(self, *exc):
        if self.shown:
            from PySide import QtGui

            QtGui.QApplication.restoreOverrideCursor()
        return False


def build_preview_layer_colours(components, current, shade=BUILD_PREVIEW_BAND_SHADE):
    """The colour of each layer a BuildPreview shows, from its ShownComponents (deposition order,
    the step's layer last): each in its component's colour, every second layer of a component
    (counted in that order) `shade` times as bright; the step's layer `current`."""
    seen = {}
    colours = []
    for component in components[:-1]:
        count = seen.get(component, 0)
        seen[component] = count + 1
        colour = component_colour(component)
        colours.append(colour if count % 2 == 0 else tuple(x * shade for x in colour))
    return colours + [tuple(current)] if components else []


class ViewProviderBuildPreview(_Editable, _Stateless):
    """Tree icon and drawing of a ``BuildPreview`` object (an App::FeaturePython with a Shape): its
    Shape drawn here, shaded, each layer's triangles made once (by the object from the layer's
    regions, ``layer_triangles``; for a Shape read from a file, from its faces' corners,
    ``shape_triangles``) and kept while its prism is, so that a step redraws only what changed
    (Part's view provider tessellated every face of the Shape anew at each step: seconds on a part
    of a thousand layers), the step's layer see-through, the step's deposit paths as lines over it,
    and where it stands on nothing under it, and the build plate see-through, behind the first
    layer's underside on it. Colours: ``build_preview_layer_colours`` and the view properties
    CurrentLayerColor, NozzleColor, CollisionColor, PathColor, UnsupportedColor and PlateColor.
    Double-click (or "Step through the build..." in the context menu) opens its panel
    (build_preview.py): a slider over the sequence's steps, with play."""

    COLOUR_PROPERTIES = tuple(BUILD_PREVIEW_COLOURS)
    EDIT_MENU_TEXT = "Step through the build..."
    PANEL_MODULE = "build_preview"

    def __init__(self, vobj):
        self._add_colours(vobj)
        vobj.Proxy = self  # calls attach()

    @staticmethod
    def _add_colours(vobj):
        """The colour properties the view provider lacks (new, or saved before one was added)."""
        for prop, (colour, doc) in BUILD_PREVIEW_COLOURS.items():
            if prop not in vobj.PropertiesList:
                vobj.addProperty("App::PropertyColor", prop, "Object Style", doc)
                setattr(vobj, prop, colour)

    def attach(self, vobj):
        from pivy import coin

        self._add_colours(vobj)
        self.Object = vobj.Object
        self.geometries = {}  # a prism's hashCode() -> (the prism, its triangles' node)
        self.materials = {}  # colour -> SoMaterial
        self.shown = []  # the colours drawn: each layer's, then the nozzle's (if shown)
        self.root = coin.SoSeparator()
        hints = coin.SoShapeHints()
        # Lit on both sides (Coin lights both only for a known ordering and an unknown shape
        # type): a layer's triangles face outwards, and a face seen from behind (inside a
        # layer, at a tie in depth along an edge; the plate from below) is not left black.
        hints.vertexOrdering = coin.SoShapeHints.COUNTERCLOCKWISE
        hints.shapeType = coin.SoShapeHints.UNKNOWN_SHAPE_TYPE
        hints.creaseAngle = 0.0  # flat: a prism's walls and faces keep their edges
        self.root.addChild(hints)
        offset = coin.SoPolygonOffset()  # the faces a little back: the paths on them show
        self.root.addChild(offset)
        self.layer_nodes = coin.SoSeparator()
        self.nozzle_node = coin.SoSeparator()
        self.root.addChild(self.layer_nodes)
        self.root.addChild(self.nozzle_node)
        # Where the step's layer stands on nothing: faces on the plane below it, drawn in front of
        # the layer's bottom face there.
        self.unsupported_node = coin.SoSeparator()
        front = coin.SoPolygonOffset()
        front.factor = -1.0
        front.units = -1.0
        self.unsupported_colour = coin.SoMaterial()
        self.unsupported_faces = coin.SoSeparator()
        for node in (front, self.unsupported_colour, self.unsupported_faces):
            self.unsupported_node.addChild(node)
        self.root.addChild(self.unsupported_node)
        # The plate: drawn further back than the layers, whose first ones lie on it.
        self.plate_node = coin.SoSeparator()
        back = coin.SoPolygonOffset()
        back.factor = 2.0
        back.units = 2.0
        self.plate_colour = coin.SoMaterial()
        self.plate_colour.transparency.setValue(BUILD_PREVIEW_PLATE_TRANSPARENCY)
        self.plate_faces = coin.SoSeparator()
        for node in (back, self.plate_colour, self.plate_faces):
            self.plate_node.addChild(node)
        self.root.addChild(self.plate_node)
        paths = coin.SoSeparator()
        light = coin.SoLightModel()
        light.model = coin.SoLightModel.BASE_COLOR
        style = coin.SoDrawStyle()
        style.lineWidth = BUILD_PREVIEW_PATH_WIDTH
        self.path_colour = coin.SoBaseColor()
        self.path_points = coin.SoCoordinate3()
        self.path_lines = coin.SoLineSet()
        for node in (light, style, self.path_colour, self.path_points, self.path_lines):
            paths.addChild(node)
        self.root.addChild(paths)
        vobj.addDisplayMode(self.root, "Shaded")
        self.update(vobj)

    def getDisplayModes(self, vobj):
        return ["Shaded"]

    def getDefaultDisplayMode(self):
        return "Shaded"

    def setDisplayMode(self, mode):
        return mode

    def updateData(self, obj, prop):
        if prop == "Shape" and obj.ViewObject is not None:
            self.update(obj.ViewObject)

    def onChanged(self, vobj, prop):
        if prop in self.COLOUR_PROPERTIES:
            self.update(vobj)

    def _material(self, colour, transparency=0.0):
        from pivy import coin

        node = self.materials.get((colour, transparency))
        if node is None:
            node = self.materials[(colour, transparency)] = coin.SoMaterial()
            node.diffuseColor.setValue(*colour)
            node.transparency.setValue(transparency)
        return node

    @staticmethod
    def _triangles(shape, mesh=None, polygonal=False):
        """A node drawing `shape`'s faces as triangles: `mesh` ((points, triangles)) when given,
        else ``shape_triangles(shape, polygonal=polygonal)``."""
        from pivy import coin

        import MultiAxisSlicer.features as features

        points, triangles = mesh or features.shape_triangles(shape, polygonal=polygonal)
        node = coin.SoSeparator()
        coordinates = coin.SoCoordinate3()
        faces = coin.SoIndexedFaceSet()
        if points:
            coordinates.point.setValues(0, len(points), points)
            index = [i for t in triangles for i in (t[0], t[1], t[2], -1)]
            faces.coordIndex.setValues(0, len(index), index)
        node.addChild(coordinates)
        node.addChild(faces)
        return node

    def update(self, vobj):
        """The drawing from the object's Shape, ShownComponents and Collides and the colours."""
        obj = vobj.Object
        if (getattr(self, "layer_nodes", None) is None or obj is None
                or "ShownComponents" not in obj.PropertiesList
                or not all(p in vobj.PropertiesList for p in BUILD_PREVIEW_COLOURS)):
            return  # still being set up or restored
        self.layer_nodes.removeAllChildren()
        self.nozzle_node.removeAllChildren()
        self.unsupported_faces.removeAllChildren()
        self.plate_faces.removeAllChildren()
        self.path_lines.numVertices.setNum(0)
        self.path_points.point.setNum(0)
        self.shown = []
        shape = obj.Shape
        parts = shape.childShapes() if not shape.isNull() and shape.ShapeType == "Compound" else []
        components = list(obj.ShownComponents)
        # (Five parts: saved before the plate was; it is drawn from the next recompute.)
        if len(parts) not in (5, 6) or len(parts[0].childShapes()) != len(components) - 1:
            return  # not computed (or failed before its Shape was made)
        colour = {p: tuple(getattr(vobj, p))[:3] for p in BUILD_PREVIEW_COLOURS}
        prisms = parts[0].childShapes() + [parts[1]]
        keys = [prism.hashCode() for prism in prisms]
        new = [(key, prism) for key, prism in zip(keys, prisms)
               if key not in self.geometries or not self.geometries[key][0].isSame(prism)]
        # Each layer's triangles as the object made them from its regions (the engine's), or, for
        # a Shape restored from a file, from its faces' corners (a thousand layers take a second
        # or two so, about 30 microseconds a face: the wait cursor says so).
        made = getattr(getattr(obj, "Proxy", None), "prism_triangles", None)
        with _WaitCursor(len(new) > BUILD_PREVIEW_QUIET_LAYERS):
            for key, prism in new:
                self.geometries[key] = (prism, self._triangles(prism, made and made(prism),
                                                               polygonal=True))
        used = set(keys)
        colours = build_preview_layer_colours(components, colour["CurrentLayerColor"])
        for k, (key, layer_colour) in enumerate(zip(keys, colours)):
            self.layer_nodes.addChild(self._material(
                layer_colour, BUILD_PREVIEW_CURRENT_TRANSPARENCY if k == len(keys) - 1 else 0.0))
            self.layer_nodes.addChild(self.geometries[key][1])
            self.shown.append(layer_colour)
        # The layers of a slicing done since, or of steps no longer shown after many: dropped.
        if len(self.geometries) > 2 * max(obj.StepCount, len(used)):
            self.geometries = {k: v for k, v in self.geometries.items() if k in used}
        if parts[2].Faces:
            nozzle_colour = colour["CollisionColor" if obj.Collides else "NozzleColor"]
            self.nozzle_node.addChild(self._material(nozzle_colour))
            self.nozzle_node.addChild(self._triangles(parts[2]))
            self.shown.append(nozzle_colour)
        self.unsupported_colour.diffuseColor.setValue(*colour["UnsupportedColor"])
        if parts[4].Faces:
            self.unsupported_faces.addChild(self._triangles(parts[4], polygonal=True))
        self.plate_colour.diffuseColor.setValue(*colour["PlateColor"])
        if len(parts) > 5 and parts[5].Faces:
            self.plate_faces.addChild(self._triangles(parts[5], polygonal=True))
        lines = []
        for wire in parts[3].Wires:
            points = [v.Point for v in wire.OrderedVertexes]
            if wire.isClosed():
                points.append(points[0])
            lines.append([(p.x, p.y, p.z) for p in points])
        self.path_colour.rgb.setValue(*colour["PathColor"])
        if lines:
            points = [p for line in lines for p in line]
            self.path_points.point.setValues(0, len(points), points)
            self.path_lines.numVertices.setValues(0, len(lines), [len(line) for line in lines])

    def onDelete(self, vobj, subelements):
        """The Layers object and its Toolpaths, hidden by the Build preview command, are shown
        again when no other preview of them is left."""
        import MultiAxisSlicer.features as features

        obj = vobj.Object
        layers = getattr(obj, "Layers", None)
        if layers is None or any(features.is_build_preview(o) and o is not obj
                                 for o in layers.InList):
            return True
        for o in features.layers_and_toolpaths(layers):
            if o.ViewObject is not None:
                o.ViewObject.Visibility = True
        return True

    def getIcon(self):
        return MultiAxisSlicerGui.icon_path("BuildPreview.svg")
