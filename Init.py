# SPDX-License-Identifier: LGPL-2.1-or-later
# Multi-Axis Slicer add-on, App side: runs at every FreeCAD start, with or without the GUI.
#
# FreeCAD puts only the add-on folder on sys.path and exec()s this file without __file__, inside a
# function: top-level names here are that function's locals, invisible to functions defined here.
# So everything happens in one self-contained function.


def _multi_axis_slicer_init():
    import os
    import sys

    import FreeCAD

    # The add-on root is the sys.path entry holding both InitGui.py and the scripting package.
    # FreeCAD inserted it at the front just before running this file, so the first match is ours.
    root = None
    for entry in sys.path:
        if not isinstance(entry, str) or not entry:
            continue
        if os.path.isfile(os.path.join(entry, "InitGui.py")) and os.path.isfile(
            os.path.join(entry, "App", "MultiAxisSlicer", "__init__.py")
        ):
            root = os.path.normpath(os.path.abspath(entry))
            break
    if root is None:
        FreeCAD.Console.PrintError(
            "Multi-Axis Slicer: add-on folder not found on sys.path; the workbench is disabled\n"
        )
        return
    # import MultiAxisSlicer (App/), MultiAxisSlicerGui (Gui/), and the test modules (tests/ of an
    # installed or staged add-on; a source checkout keeps them in tests/python/, not on the path).
    tests = os.path.join(root, "tests")
    has_tests = os.path.isfile(os.path.join(tests, "TestMultiAxisSlicerApi.py"))
    paths = ([tests] if has_tests else []) + [os.path.join(root, "Gui"), os.path.join(root, "App")]
    for path in paths:
        if path not in sys.path:
            sys.path.insert(0, path)
    if has_tests:
        FreeCAD.__unit_test__ += ["TestMultiAxisSlicerApi", "TestMultiAxisSlicerAxis",
                                  "TestMultiAxisSlicerDecompose", "TestMultiAxisSlicerSlice",
                                  "TestMultiAxisSlicerGcode", "TestMultiAxisSlicerSurvey"]


_multi_axis_slicer_init()
del _multi_axis_slicer_init
