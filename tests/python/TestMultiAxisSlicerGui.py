# SPDX-License-Identifier: LGPL-2.1-or-later
"""The workbench in the real FreeCAD GUI.

Run: xvfb-run -a freecad -t TestMultiAxisSlicerGui (tests/run_freecad_test.sh gui does it against
the add-on staged in the build tree). With MAS_SCREENSHOT_DIR set, saves PNGs of the 3D view there.
"""

import os
import shutil
import subprocess
import tempfile
import textwrap
import unittest

import FreeCAD
import FreeCADGui
from PySide import QtCore, QtGui

import MultiAxisSlicer as mas
import MultiAxisSlicerGui.view_providers as view_providers

WORKBENCH = "MultiAxisSlicerWorkbench"
COMMAND = "MultiAxisSlicer_Sections"
TOOLBAR = "Multi-Axis Slicer"


def process_events():
    QtGui.QApplication.processEvents()


class TestWorkbench(unittest.TestCase):
    def setUp(self):
        self.assertIn(WORKBENCH, FreeCADGui.listWorkbenches())
        FreeCADGui.activateWorkbench(WORKBENCH)
        process_events()

    def test_workbench_is_active_with_its_toolbar(self):
        self.assertEqual(FreeCADGui.activeWorkbench().name(), WORKBENCH)
        self.assertTrue(mas.engine_available(), mas.engine_missing_message())
        toolbar = FreeCADGui.getMainWindow().findChild(QtGui.QToolBar, TOOLBAR)
        self.assertIsNotNone(toolbar, "no toolbar named " + TOOLBAR)
        self.assertTrue(toolbar.isVisible())
        texts = [a.text() for a in toolbar.actions()]
        self.assertIn("Cross-sections", texts)
        workbench = FreeCADGui.getWorkbench(WORKBENCH)
        self.assertTrue(workbench.Icon.endswith("MultiAxisSlicer.svg"))
        self.assertTrue(os.path.isfile(workbench.Icon), workbench.Icon)
        self.assertIn(TOOLBAR, workbench.listToolbars())
        self.assertIn(TOOLBAR, workbench.listMenus())

    def test_no_error_box_after_activation(self):
        boxes = FreeCADGui.getMainWindow().findChildren(QtGui.QMessageBox, "MultiAxisSlicerError")
        self.assertEqual([b for b in boxes if b.isVisible()], [])


class TestSectionsCommand(unittest.TestCase):
    def setUp(self):
        FreeCADGui.activateWorkbench(WORKBENCH)
        self.doc = FreeCAD.newDocument("MasGui")
        self.box = self.doc.addObject("Part::Box", "Box")
        self.box.Length, self.box.Width, self.box.Height = 20, 30, 40
        self.doc.recompute()
        FreeCADGui.Selection.clearSelection()
        process_events()

    def tearDown(self):
        FreeCADGui.Selection.clearSelection()
        FreeCAD.closeDocument(self.doc.Name)
        process_events()

    def command(self):
        return FreeCADGui.Command.get(COMMAND)

    def test_command_needs_one_selected_part(self):
        self.assertFalse(self.command().isActive())
        FreeCADGui.Selection.addSelection(self.box)
        self.assertTrue(self.command().isActive())

    def test_command_creates_a_sections_object_on_the_selected_box(self):
        before = self.box.Shape.exportBrepToString()
        FreeCADGui.Selection.addSelection(self.box)
        FreeCADGui.runCommand(COMMAND)
        process_events()

        obj = self.doc.getObject("Sections")
        self.assertIsNotNone(obj, "the command made no Sections object")
        self.assertTrue(obj.isValid(), obj.getStatusString())
        self.assertIs(obj.Source, self.box)
        self.assertEqual(obj.SectionCount, 8)  # 40 mm / 5 mm
        self.assertAlmostEqual(obj.TotalArea.Value, 8 * 600.0, places=6)
        self.assertEqual(len(obj.Shape.Wires), 8)
        self.assertEqual(self.box.Shape.exportBrepToString(), before)
        self.assertTrue(self.box.ViewObject.Visibility)
        vobj = obj.ViewObject
        self.assertTrue(vobj.Visibility)
        for got, want in zip(vobj.LineColor[:3], view_providers.SECTION_LINE_COLOR):
            self.assertAlmostEqual(got, want, delta=1.0 / 255)  # colours are stored in 8 bits
        self.assertTrue(vobj.Proxy.getIcon().endswith("Sections.svg"))
        self.assertIn("Cross-sections", self.doc.UndoNames)
        self.save_screenshot("sections_box.png")

        self.doc.undo()
        process_events()
        self.assertIsNone(self.doc.getObject("Sections"))

    def test_oblique_sections_of_a_part_with_a_hole(self):
        import Part

        part = self.doc.addObject("Part::Feature", "Holed")
        part.Shape = Part.makeBox(40, 30, 20).cut(
            Part.makeCylinder(8, 20, FreeCAD.Vector(20, 15, 0)))
        part.Placement.Base = FreeCAD.Vector(40, 0, 0)
        self.doc.recompute()
        FreeCADGui.Selection.addSelection(part)
        FreeCADGui.runCommand(COMMAND)
        process_events()
        obj = self.doc.getObject("Sections")
        self.assertIsNotNone(obj)
        obj.Normal = FreeCAD.Vector(1, 0, 1)
        obj.Step = 3.0
        self.doc.recompute()
        self.assertTrue(obj.isValid(), obj.getStatusString())
        self.assertGreater(obj.SectionCount, 10)
        self.assertGreater(len(obj.Shape.Wires), obj.SectionCount)  # holes give extra loops
        self.save_screenshot("sections_oblique.png")

    def save_screenshot(self, name):
        """The 3D view with the sources see-through, and the whole main window."""
        folder = os.environ.get("MAS_SCREENSHOT_DIR")
        if not folder:
            return
        os.makedirs(folder, exist_ok=True)
        FreeCADGui.Selection.clearSelection()
        for o in self.doc.Objects:
            if not o.TypeId.startswith("Part::FeaturePython"):
                o.ViewObject.Transparency = 70  # the test's own document, for the picture only
        view = FreeCADGui.getDocument(self.doc.Name).ActiveView
        view.viewIsometric()
        view.fitAll()
        process_events()
        path = os.path.join(folder, name)
        view.saveImage(path, 1000, 750, "White")
        self.assertTrue(os.path.getsize(path) > 0)
        # The whole window, with the 3D view pasted in: under Xvfb a widget grab leaves the OpenGL
        # view blank.
        window = os.path.join(folder, "window_" + name)
        main = FreeCADGui.getMainWindow()
        picture = main.grab()
        viewer = view.graphicsView()
        corner = viewer.mapTo(main, QtCore.QPoint(0, 0))
        view.saveImage(window, viewer.width(), viewer.height(), "White")
        painter = QtGui.QPainter(picture)
        painter.drawImage(corner, QtGui.QImage(window))
        painter.end()
        picture.save(window)
        FreeCAD.Console.PrintMessage("screenshots: {}, {}\n".format(path, window))


# Run by a second FreeCAD GUI, on a copy of the add-on without the compiled engine.
NO_ENGINE_TEST = """
import unittest

import FreeCAD
import FreeCADGui
from PySide import QtGui


class TestNoEngine(unittest.TestCase):
    def test_activation_and_command_say_how_to_build(self):
        import MultiAxisSlicer
        self.assertFalse(MultiAxisSlicer.engine_available())
        FreeCADGui.activateWorkbench("MultiAxisSlicerWorkbench")
        QtGui.QApplication.processEvents()
        main = FreeCADGui.getMainWindow()
        boxes = [b for b in main.findChildren(QtGui.QMessageBox, "MultiAxisSlicerError")
                 if b.isVisible()]
        self.assertEqual(len(boxes), 1)
        self.assertIn("./tools/setup.sh install", boxes[0].text())
        self.assertIsNotNone(main.findChild(QtGui.QToolBar, "Multi-Axis Slicer"))
        doc = FreeCAD.newDocument("NoEngine")
        box = doc.addObject("Part::Box", "Box")
        doc.recompute()
        FreeCADGui.Selection.addSelection(box)
        FreeCADGui.runCommand("MultiAxisSlicer_Sections")
        QtGui.QApplication.processEvents()
        self.assertEqual([o.Name for o in doc.Objects], ["Box"])
        print("NO ENGINE MESSAGE:", boxes[0].text())
"""


class TestWithoutEngine(unittest.TestCase):
    """An add-on installed from sources only (what the Addon Manager does): the workbench loads,
    says how to build the engine and never shows a traceback."""

    def test_missing_engine_is_reported_without_a_traceback(self):
        import MultiAxisSlicerGui

        source = os.path.dirname(os.path.dirname(MultiAxisSlicerGui.ICON_DIR))
        home = tempfile.mkdtemp(prefix="mas_noengine_home_")
        try:
            addon = os.path.join(home, ".local", "share", "FreeCAD", "Mod", "MultiAxisSlicer")
            os.makedirs(os.path.join(addon, "App", "MultiAxisSlicer"))
            for name in ("Init.py", "InitGui.py", "package.xml", "metadata.txt"):
                shutil.copy(os.path.join(source, name), addon)
            shutil.copytree(os.path.dirname(os.path.abspath(__file__)),
                            os.path.join(addon, "tests"),
                            ignore=shutil.ignore_patterns("__pycache__"))
            shutil.copytree(os.path.join(source, "Resources"), os.path.join(addon, "Resources"))
            shutil.copytree(os.path.join(source, "Gui", "MultiAxisSlicerGui"),
                            os.path.join(addon, "Gui", "MultiAxisSlicerGui"),
                            ignore=shutil.ignore_patterns("__pycache__"))
            package = os.path.join(source, "App", "MultiAxisSlicer")
            for name in os.listdir(package):
                if name.endswith(".py"):
                    shutil.copy(os.path.join(package, name),
                                os.path.join(addon, "App", "MultiAxisSlicer"))
            with open(os.path.join(addon, "tests", "TestMasNoEngine.py"), "w") as f:
                f.write(textwrap.dedent(NO_ENGINE_TEST))
            env = dict(os.environ, HOME=home, XDG_DATA_HOME=os.path.join(home, ".local", "share"),
                       XDG_CONFIG_HOME=os.path.join(home, ".config"),
                       XDG_CACHE_HOME=os.path.join(home, ".cache"))
            result = subprocess.run(["freecad", "-t", "TestMasNoEngine"], env=env, text=True,
                                    stdout=subprocess.PIPE, stderr=subprocess.STDOUT, timeout=300)
        finally:
            shutil.rmtree(home)
        output = result.stdout
        self.assertEqual(result.returncode, 0, output)
        self.assertIn("NO ENGINE MESSAGE:", output)
        self.assertIn("Ran 1 test", output)
        self.assertNotIn("Traceback", output)


if __name__ == "__main__":
    unittest.main()
