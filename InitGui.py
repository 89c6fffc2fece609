# SPDX-License-Identifier: LGPL-2.1-or-later
# Multi-Axis Slicer add-on, GUI side. FreeCAD exec()s this file after Init.py (which put App/ and
# Gui/ on sys.path); names defined at the top level here are not visible inside the class, so its
# methods import what they use.

import FreeCAD
import FreeCADGui


class MultiAxisSlicerWorkbench(Workbench):  # noqa: F821 (Workbench comes from FreeCAD's GUI init)
    """Multi-Axis Slicer: cross-sections of solids and meshes, towards multi-axis build plans."""

    MenuText = "Multi-Axis Slicer"
    ToolTip = ("Cross-sections, centroidal axis, decomposition, multi-axis layers and paths of "
               "solids and meshes, and their 5-axis G-code")

    def __init__(self):
        import MultiAxisSlicerGui

        self.__class__.Icon = MultiAxisSlicerGui.icon_path("MultiAxisSlicer.svg")

    def Initialize(self):
        import MultiAxisSlicerGui.commands as commands

        names = [commands.SectionsCommand.NAME, commands.CentroidalAxisCommand.NAME,
                 commands.DecomposeCommand.NAME, commands.SliceCommand.NAME,
                 commands.BuildPreviewCommand.NAME, commands.MachineProgramCommand.NAME,
                 commands.ExportGcodeCommand.NAME]
        self.appendToolbar("Multi-Axis Slicer", names)
        self.appendMenu("Multi-Axis Slicer", names)

    def Activated(self):
        # The Addon Manager only clones the sources: say how to build the engine, once per session.
        import MultiAxisSlicer

        if not MultiAxisSlicer.engine_available() and not getattr(self, "_engine_reported", False):
            import MultiAxisSlicerGui

            self._engine_reported = True
            MultiAxisSlicerGui.show_error(MultiAxisSlicer.engine_missing_message())

    def GetClassName(self):
        return "Gui::PythonWorkbench"


FreeCADGui.addWorkbench(MultiAxisSlicerWorkbench())

import importlib.util  # noqa: E402

if importlib.util.find_spec("TestMultiAxisSlicerGui") is not None:  # tests/ is installed
    FreeCAD.__unit_test__ += ["TestMultiAxisSlicerGui"]
