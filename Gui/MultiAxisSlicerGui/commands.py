# SPDX-License-Identifier: LGPL-2.1-or-later
"""Workbench commands. Errors reach the user as a message, never as a traceback."""

import FreeCAD
import FreeCADGui

import MultiAxisSlicer as mas
import MultiAxisSlicerGui


def _selected_part():
    """The one selected object if it has a shape or a mesh, else None."""
    if FreeCAD.ActiveDocument is None:
        return None
    selection = FreeCADGui.Selection.getSelection()
    if len(selection) != 1:
        return None
    obj = selection[0]
    if obj.isDerivedFrom("Mesh::Feature") or hasattr(obj, "Shape"):
        return obj
    return None


class SectionsCommand:
    """Cross-sections of the selected solid or mesh, as a parametric Sections object."""

    NAME = "MultiAxisSlicer_Sections"
    TRANSACTION = "Cross-sections"

    def GetResources(self):
        return {
            "Pixmap": MultiAxisSlicerGui.icon_path("Sections.svg"),
            "MenuText": "Cross-sections",
            "ToolTip": "Cut the selected solid or closed mesh by parallel planes "
                       "(a parametric Sections object: set Normal, Step, Deflection)",
        }

    def IsActive(self):
        try:
            return _selected_part() is not None
        except Exception:  # IsActive runs on every GUI update: never let it raise
            return False

    def Activated(self):
        source = _selected_part()
        if source is None:
            MultiAxisSlicerGui.show_error("Select one solid or mesh first.")
            return
        if not mas.engine_available():
            MultiAxisSlicerGui.show_error(mas.engine_missing_message())
            return
        import MultiAxisSlicer.features as features

        doc = source.Document
        doc.openTransaction(self.TRANSACTION)
        try:
            obj = features.make_sections(source, doc=doc)
            doc.recompute()
        except Exception as error:  # creating the object failed: leave nothing behind
            doc.abortTransaction()
            MultiAxisSlicerGui.show_error(
                "Cross-sections of '{}' failed: {}".format(source.Label, error))
            return
        doc.commitTransaction()
        if not obj.isValid():  # the object stays so that its parameters can be fixed
            MultiAxisSlicerGui.show_error("{}: {}".format(obj.Label, obj.getStatusString()))


FreeCADGui.addCommand(SectionsCommand.NAME, SectionsCommand())
