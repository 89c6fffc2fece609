# SPDX-License-Identifier: LGPL-2.1-or-later
"""View providers of the Multi-Axis Slicer document objects."""

import MultiAxisSlicerGui

# Sections are drawn as lines over the part: a colour that stands out from FreeCAD's grey solids.
SECTION_LINE_COLOR = (1.0, 0.45, 0.0)  # orange
SECTION_LINE_WIDTH = 2.0


class ViewProviderSections:
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

    # Nothing to save (colours are view properties). 0.20.2 calls __getstate__/__setstate__,
    # 0.21.2 and later dumps/loads.
    def __getstate__(self):
        return None

    def __setstate__(self, state):
        return None

    def dumps(self):
        return None

    def loads(self, state):
        return None
