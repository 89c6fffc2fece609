# SPDX-License-Identifier: LGPL-2.1-or-later
"""The workbench in the real FreeCAD GUI.

Run: xvfb-run -a freecad -t TestMultiAxisSlicerGui (tests/run_freecad_test.sh gui does it against
the add-on staged in the build tree). With MAS_SCREENSHOT_DIR set, saves PNGs of the 3D view there.
"""

import math
import os
import shutil
import subprocess
import tempfile
import textwrap
import time
import unittest

import FreeCAD
import FreeCADGui
import Part
from PySide import QtCore, QtGui

import MultiAxisSlicer as mas
import MultiAxisSlicerGui.progress as progress
import MultiAxisSlicerGui.view_providers as view_providers
import MultiAxisSlicerTestSupport

WORKBENCH = "MultiAxisSlicerWorkbench"
COMMAND = "MultiAxisSlicer_Sections"
AXIS_COMMAND = "MultiAxisSlicer_CentroidalAxis"
DECOMPOSE_COMMAND = "MultiAxisSlicer_Decompose"
SLICE_COMMAND = "MultiAxisSlicer_Slice"
PROGRAM_COMMAND = "MultiAxisSlicer_MachineProgram"
EXPORT_COMMAND = "MultiAxisSlicer_ExportGcode"
PREVIEW_COMMAND = "MultiAxisSlicer_BuildPreview"
TOOLBAR = "Multi-Axis Slicer"


def process_events():
    QtGui.QApplication.processEvents()


def error_boxes():
    """The workbench's error messages shown now."""
    return [b for b in FreeCADGui.getMainWindow().findChildren(QtGui.QMessageBox,
                                                                "MultiAxisSlicerError")
            if b.isVisible()]


def close_error_boxes():
    """Closes the workbench's error messages, shown or not (a test's leftovers)."""
    for box in FreeCADGui.getMainWindow().findChildren(QtGui.QMessageBox, "MultiAxisSlicerError"):
        box.close()


def drawn_box(obj):
    """The bounding box of what the 3D view draws of `obj` (Coin's, over its root node): empty
    when nothing of it is drawn."""
    from pivy import coin

    action = coin.SoGetBoundingBoxAction(coin.SbViewportRegion(100, 100))
    action.apply(obj.ViewObject.RootNode)
    return action.getBoundingBox()


def wait_for_components(decomposition, count, seconds=5.0):
    """Processes events until the decomposition has `count` component objects, or the time is up:
    they are synchronised after the recompute ends, by a timer that waits 50 ms while it runs."""
    import MultiAxisSlicer.features as features

    deadline = time.monotonic() + seconds
    while len(features.components_of(decomposition)) != count and time.monotonic() < deadline:
        process_events()
        time.sleep(0.01)


def save_screenshot(test, doc, name, see_through=True):
    """With MAS_SCREENSHOT_DIR set, saves the 3D view (the sources see-through unless told
    otherwise) and the whole main window there."""
    folder = os.environ.get("MAS_SCREENSHOT_DIR")
    if not folder:
        return
    os.makedirs(folder, exist_ok=True)
    FreeCADGui.Selection.clearSelection()
    if see_through:
        for o in doc.Objects:
            if not o.TypeId.startswith("Part::FeaturePython"):
                o.ViewObject.Transparency = 70  # the test's own document, for the picture only
    view = FreeCADGui.getDocument(doc.Name).ActiveView
    view.viewIsometric()
    view.fitAll()
    process_events()
    path = os.path.join(folder, name)
    view.saveImage(path, 1000, 750, "White")
    test.assertTrue(os.path.getsize(path) > 0)
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
        self.assertIn("Centroidal axis", texts)
        self.assertIn("Decompose", texts)
        self.assertIn("Slice", texts)
        for text in ("Centroidal axis", "Decompose", "Slice"):
            action = [a for a in toolbar.actions() if a.text() == text][0]
            self.assertFalse(action.icon().isNull(), text)
        menu = [m for m in FreeCADGui.getMainWindow().menuBar().actions() if m.text() == TOOLBAR]
        self.assertEqual(len(menu), 1)
        self.assertIn("Centroidal axis", [a.text() for a in menu[0].menu().actions()])
        self.assertIn("Decompose", [a.text() for a in menu[0].menu().actions()])
        self.assertIn("Slice", [a.text() for a in menu[0].menu().actions()])
        workbench = FreeCADGui.getWorkbench(WORKBENCH)
        self.assertTrue(workbench.Icon.endswith("MultiAxisSlicer.svg"))
        self.assertTrue(os.path.isfile(workbench.Icon), workbench.Icon)
        self.assertIn(TOOLBAR, workbench.listToolbars())
        self.assertIn(TOOLBAR, workbench.listMenus())

    def test_no_error_box_after_activation(self):
        self.assertEqual(error_boxes(), [])


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

    def test_cancel_in_the_progress_dialog_undoes_the_command(self):
        # Sections a hair apart take long: the recompute shows its progress and can be cancelled.
        undo = self.doc.UndoCount
        with Canceller(self, "Cutting") as canceller:
            FreeCADGui.Selection.addSelection(self.box)
            FreeCADGui.runCommand(COMMAND)
            process_events()
        self.assertEqual(canceller.clicks, 1)
        self.assertEqual([o.Name for o in self.doc.Objects], ["Box"])
        self.assertEqual(self.doc.UndoCount, undo)
        # The status bar says so, after FreeCAD's own "Recompute failed!" for the stopped one.
        process_events()
        self.assertEqual(FreeCADGui.getMainWindow().statusBar().currentMessage(),
                         "Cross-sections of 'Box' cancelled: nothing was made")
        # Recomputing an object runs it again, reporting as it goes.
        import MultiAxisSlicer.features as features

        obj = features.make_sections(self.box, step=0.01)
        with Canceller(self, "Cutting") as canceller:
            self.doc.recompute()
        self.assertEqual(canceller.clicks, 1)
        self.assertIn("cancelled by the user; recompute to run it again", obj.getStatusString())
        self.doc.recompute()
        self.assertTrue(obj.isValid(), obj.getStatusString())
        self.assertEqual(obj.SectionCount, 4000)

    def test_command_computes_its_own_object_only(self):
        # Another object waiting for a recompute (a slow one: 4000 sections) is left alone: a
        # whole-document recompute ran it inside the command, and a Cancel in its progress
        # dialog undid the command.
        import MultiAxisSlicer.features as features

        waiting = features.make_sections(self.box, step=0.01)
        self.assertIn("Touched", waiting.State)
        other = self.doc.addObject("Part::Box", "Other")
        other.Placement.Base = FreeCAD.Vector(100, 0, 0)  # not recomputed yet either
        FreeCADGui.Selection.addSelection(other)
        FreeCADGui.runCommand(COMMAND)
        process_events()
        new = [o for o in self.doc.Objects if o.Name not in ("Box", "Sections", "Other")]
        self.assertEqual(len(new), 1)
        self.assertTrue(new[0].isValid(), new[0].getStatusString())
        self.assertEqual(new[0].SectionCount, 2)  # the new box (its source), 10 mm / 5 mm
        self.assertNotIn("Touched", other.State)
        self.assertIn("Touched", waiting.State)
        self.assertEqual(waiting.SectionCount, 0)

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
        save_screenshot(self, self.doc, name)


def l_block():
    """Fig. 7's L: a 20 x 20 x 60 column with a 50 mm arm [20, 70] x [0, 20] x [40, 60]."""
    import Part

    column = Part.makeBox(20, 20, 60)
    arm = Part.makeBox(50, 20, 20, FreeCAD.Vector(20, 0, 40))
    return column.fuse(arm).removeSplitter()


def same_colour(a, b):
    return all(abs(x - y) <= 1.0 / 255 for x, y in zip(a[:3], b[:3]))  # stored in 8 bits


class TestCentroidalAxisCommand(unittest.TestCase):
    def setUp(self):
        FreeCADGui.activateWorkbench(WORKBENCH)
        self.doc = FreeCAD.newDocument("MasGuiAxis")
        self.part = self.doc.addObject("Part::Feature", "L")
        self.part.Shape = l_block()
        self.doc.recompute()
        FreeCADGui.Selection.clearSelection()
        process_events()

    def tearDown(self):
        FreeCADGui.Selection.clearSelection()
        close_error_boxes()
        FreeCAD.closeDocument(self.doc.Name)
        process_events()

    def command(self):
        return FreeCADGui.Command.get(AXIS_COMMAND)

    def run_command(self):
        FreeCADGui.Selection.addSelection(self.part)
        FreeCADGui.runCommand(AXIS_COMMAND)
        process_events()
        return self.doc.getObject("CentroidalAxis")

    def check_edge_colours(self, obj):
        """Ordinary links in LineColor, break links in BreakLineColor, one colour per edge."""
        vobj = obj.ViewObject
        colours = vobj.LineColorArray
        self.assertEqual(len(colours), len(obj.Shape.Edges))
        for i, colour in enumerate(colours):
            want = vobj.BreakLineColor if i >= obj.BreakEdgeStart else vobj.LineColor
            self.assertTrue(same_colour(colour, want), "edge {}: {} != {}".format(i, colour, want))

    def test_command_needs_one_selected_part(self):
        self.assertFalse(self.command().isActive())
        FreeCADGui.Selection.addSelection(self.part)
        self.assertTrue(self.command().isActive())

    def test_cancel_in_the_progress_dialog_undoes_the_command(self):
        undo = self.doc.UndoCount
        with Canceller(self, "Centroidal axis") as canceller:
            self.assertIsNone(self.run_command())
        self.assertEqual(canceller.clicks, 1)
        self.assertEqual([o.Name for o in self.doc.Objects], ["L"])
        self.assertEqual(self.doc.UndoCount, undo)
        obj = self.run_command()
        self.assertTrue(obj.isValid(), obj.getStatusString())

    def test_command_creates_an_axis_with_breaks_in_their_own_colour(self):
        before = self.part.Shape.exportBrepToString()
        obj = self.run_command()
        self.assertIsNotNone(obj, "the command made no CentroidalAxis object")
        self.assertTrue(obj.isValid(), obj.getStatusString())
        self.assertIs(obj.Source, self.part)
        self.assertEqual(obj.BranchCount, 2)  # derived step: the column and the arm
        self.assertEqual(obj.BreakCount, 1)
        self.assertEqual(self.part.Shape.exportBrepToString(), before)
        self.assertTrue(self.part.ViewObject.Visibility)
        vobj = obj.ViewObject
        self.assertTrue(vobj.Visibility)
        self.assertTrue(vobj.Proxy.getIcon().endswith("CentroidalAxis.svg"))
        self.assertTrue(os.path.isfile(vobj.Proxy.getIcon()))
        self.assertEqual(vobj.PointSize, view_providers.AXIS_POINT_SIZE)
        self.assertTrue(same_colour(vobj.LineColor, view_providers.AXIS_LINE_COLOR))
        self.assertTrue(same_colour(vobj.BreakLineColor, view_providers.AXIS_BREAK_COLOR))
        self.assertTrue(vobj.DrawOnTop)
        self.check_edge_colours(obj)
        self.assertIn("Centroidal axis", self.doc.UndoNames)

        obj.Step = 2.5  # more edges: the colours follow
        self.doc.recompute()
        process_events()
        self.assertEqual(obj.NodeCount, 44)
        self.check_edge_colours(obj)
        vobj.LineColor = (0.0, 0.6, 0.0)  # FreeCAD resets the per-edge colours; they come back
        process_events()
        self.check_edge_colours(obj)
        vobj.LineColor = view_providers.AXIS_LINE_COLOR
        process_events()
        save_screenshot(self, self.doc, "axis_l_block.png", see_through=False)
        save_screenshot(self, self.doc, "axis_l_block_see_through.png")

        self.doc.undo()
        process_events()
        self.assertIsNone(self.doc.getObject("CentroidalAxis"))

    def test_command_on_a_face_shows_the_engine_message(self):
        import Part

        self.part.Shape = Part.makePlane(10, 10)
        self.doc.recompute()
        undo = self.doc.UndoCount
        obj = self.run_command()
        self.assertIsNone(obj)  # refused before anything is made: it could never work
        self.assertEqual(self.doc.UndoCount, undo)
        boxes = error_boxes()
        self.assertEqual(len(boxes), 1)
        self.assertIn("Centroidal axis: 'L': not a solid (1 face, 0 solids)", boxes[0].text())
        for box in boxes:
            box.close()
        # One of this workbench's results is no part either: it names what to select.
        import MultiAxisSlicer.features as features

        self.part.Shape = l_block()
        self.doc.recompute()
        sections = features.make_sections(self.part)
        self.doc.recompute()
        FreeCADGui.Selection.clearSelection()
        FreeCADGui.Selection.addSelection(sections)
        FreeCADGui.runCommand(AXIS_COMMAND)
        process_events()
        self.assertIsNone(self.doc.getObject("CentroidalAxis"))
        boxes = error_boxes()
        self.assertEqual(len(boxes), 1)
        self.assertIn("'Sections' is a Sections object (cross-sections), not a part: select the "
                      "solid or mesh it was made from", boxes[0].text())

    def test_command_takes_solids_sharing_material_as_one_part_and_refuses_solids_apart(self):
        # The L drawn as its column and its arm in one compound (a Union was meant): its axis.
        column, arm = Part.makeBox(20, 20, 60), Part.makeBox(50, 20, 20, FreeCAD.Vector(20, 0, 40))
        self.part.Shape = Part.makeCompound([column, arm])
        self.doc.recompute()
        obj = self.run_command()
        self.assertIsNotNone(obj, "the command made no CentroidalAxis object")
        self.assertTrue(obj.isValid(), obj.getStatusString())
        self.assertEqual(obj.BranchCount, 2)
        self.assertEqual(obj.NodeCount, len(mas.centroidal_axis(l_block()).nodes))
        self.assertEqual(len(self.part.Shape.Solids), 2)  # the source stays as it was drawn
        self.doc.removeObject(obj.Name)
        # Two boxes 10 mm apart are two parts: refused before anything is made.
        self.part.Shape = Part.makeCompound([Part.makeBox(10, 10, 10),
                                             Part.makeBox(10, 10, 10, FreeCAD.Vector(20, 0, 0))])
        self.doc.recompute()
        FreeCADGui.Selection.clearSelection()
        undo = self.doc.UndoCount
        self.assertIsNone(self.run_command())
        self.assertEqual(self.doc.UndoCount, undo)
        boxes = error_boxes()
        self.assertEqual(len(boxes), 1)
        self.assertIn("Centroidal axis: 'L': 2 solids where one is expected", boxes[0].text())
        self.assertIn("2 bodies apart", boxes[0].text())
        for box in boxes:
            box.close()

    def axis_pixels(self):
        """Pixels of the 3D view (front view, fitted, white background) in the axis' LineColor."""
        view = FreeCADGui.getDocument(self.doc.Name).ActiveView
        view.viewFront()
        view.fitAll()
        process_events()
        folder = tempfile.mkdtemp(prefix="mas_gui_on_top_")
        try:
            path = os.path.join(folder, "view.png")
            view.saveImage(path, 400, 400, "White")
            image = QtGui.QImage(path)
        finally:
            shutil.rmtree(folder)
        want = [round(255 * c) for c in view_providers.AXIS_LINE_COLOR]
        count = 0
        for y in range(image.height()):
            for x in range(image.width()):
                pixel = QtGui.QColor(image.pixel(x, y))
                if all(abs(a - b) <= 24 for a, b in
                       zip((pixel.red(), pixel.green(), pixel.blue()), want)):
                    count += 1
        return count

    def test_the_axis_is_drawn_over_solids_made_after_it(self):
        """DrawOnTop: the axis shows through a solid added to the document after it, as the
        Components of a Decomposition are (later objects come later in the scene), here a copy
        of its part with the part itself hidden. Without DrawOnTop that solid hides the axis."""
        obj = self.run_command()
        self.assertTrue(obj.isValid(), obj.getStatusString())
        self.part.ViewObject.Visibility = False
        cover = self.doc.addObject("Part::Feature", "Cover")  # made after the axis
        cover.Shape = l_block()
        self.doc.recompute()
        process_events()
        # The column's run alone (40 mm of 60 at 400 pixels for about 75 mm) spans some 200
        # pixels, 3 pixels wide.
        self.assertGreater(self.axis_pixels(), 300)
        obj.ViewObject.DrawOnTop = False
        self.assertEqual(self.axis_pixels(), 0)
        obj.ViewObject.DrawOnTop = True
        self.assertGreater(self.axis_pixels(), 300)

    def test_view_settings_survive_save_and_reopen(self):
        obj = self.run_command()
        obj.Step = 2.5
        self.doc.recompute()
        vobj = obj.ViewObject
        vobj.BreakLineColor = (1.0, 0.5, 0.0)
        vobj.DrawOnTop = False
        self.assertEqual(vobj.Proxy._depth.function.getValue(), vobj.Proxy._depth.LESS)
        saved_and_reopened(self, "axis.FCStd")
        obj = self.doc.getObject("CentroidalAxis")
        self.part = self.doc.getObject("L")
        vobj = obj.ViewObject
        self.assertIsInstance(vobj.Proxy, view_providers.ViewProviderCentroidalAxis)
        self.assertTrue(same_colour(vobj.BreakLineColor, (1.0, 0.5, 0.0)))
        self.assertFalse(vobj.DrawOnTop)
        self.assertEqual(vobj.Proxy._depth.function.getValue(), vobj.Proxy._depth.LESS)
        self.check_edge_colours(obj)
        obj.Step = 5.0
        self.doc.recompute()
        process_events()
        self.check_edge_colours(obj)

    def test_a_document_made_without_the_gui_gets_its_colours(self):
        import MultiAxisSlicer.features as features

        folder = tempfile.mkdtemp(prefix="mas_gui_axis_")
        try:
            path = os.path.join(folder, "axis.FCStd")
            script = os.path.join(folder, "make.py")
            with open(script, "w") as f:
                f.write(textwrap.dedent("""
                    import FreeCAD, Part
                    import MultiAxisSlicer as mas
                    doc = FreeCAD.newDocument("Headless")
                    part = doc.addObject("Part::Feature", "L")
                    part.Shape = Part.makeBox(20, 20, 60).fuse(
                        Part.makeBox(50, 20, 20, FreeCAD.Vector(20, 0, 40))).removeSplitter()
                    mas.make_centroidal_axis(part, step=2.5)
                    doc.recompute()
                    doc.saveAs({!r})
                """.format(path)))
            result = subprocess.run(["freecadcmd", script], capture_output=True, text=True,
                                    timeout=120)
            self.assertTrue(os.path.isfile(path), result.stdout + result.stderr)
            doc = FreeCAD.openDocument(path)
            try:
                process_events()
                obj = doc.getObject("CentroidalAxis")
                self.assertIsInstance(obj.Proxy, features.CentroidalAxisFeature)
                self.assertIsInstance(obj.ViewObject.Proxy,
                                      view_providers.ViewProviderCentroidalAxis)
                self.check_edge_colours(obj)
            finally:
                FreeCAD.closeDocument(doc.Name)
        finally:
            shutil.rmtree(folder)


def saved_and_reopened(test, file_name):
    """Saves test.doc as `file_name` in a folder removed after the test, closes it and opens it
    again as test.doc, drawn."""
    folder = tempfile.mkdtemp(prefix="mas_gui_doc_")
    test.addCleanup(shutil.rmtree, folder, True)
    path = os.path.join(folder, file_name)
    test.doc.saveAs(path)
    FreeCAD.closeDocument(test.doc.Name)
    test.doc = FreeCAD.openDocument(path)
    process_events()


def features_of():
    import MultiAxisSlicer.features as features

    return features


class Canceller:
    """While open, every progress dialog whose text has `stage` in it shows at once and has its
    Cancel button clicked (mouse press and release sent through the application, as a user's
    click would be, so that an input filter would stop them). `clicks` counts the clicks."""

    def __init__(self, test, stage):
        self.test = test
        self.stage = stage
        self.clicks = 0

    def __enter__(self):
        self.saved = (progress.SHOW_AFTER, progress.INTERVAL)
        progress.SHOW_AFTER = progress.INTERVAL = 0.0
        self.timer = QtCore.QTimer()
        self.timer.timeout.connect(self.poke)
        self.timer.start(0)
        return self

    def poke(self):
        dialog = QtGui.QApplication.activeModalWidget()
        if not isinstance(dialog, QtGui.QProgressDialog) or self.stage not in \
                dialog.labelText() or dialog.wasCanceled():
            return
        button = dialog.findChild(QtGui.QPushButton)
        self.test.assertEqual(button.text(), "Cancel")
        centre = button.rect().center()
        for kind in (QtCore.QEvent.MouseButtonPress, QtCore.QEvent.MouseButtonRelease):
            QtGui.QApplication.sendEvent(button, QtGui.QMouseEvent(
                kind, centre, QtCore.Qt.LeftButton, QtCore.Qt.LeftButton, QtCore.Qt.NoModifier))
        self.clicks += 1

    def __exit__(self, *exc):
        self.timer.stop()
        progress.SHOW_AFTER, progress.INTERVAL = self.saved
        return False


class TestDecomposeCommand(unittest.TestCase):
    def setUp(self):
        FreeCADGui.activateWorkbench(WORKBENCH)
        self.doc = FreeCAD.newDocument("MasGuiDecompose")
        self.part = self.doc.addObject("Part::Feature", "L")
        self.part.Shape = l_block()
        self.doc.recompute()
        FreeCADGui.Selection.clearSelection()
        process_events()

    def tearDown(self):
        FreeCADGui.Selection.clearSelection()
        close_error_boxes()
        FreeCAD.closeDocument(self.doc.Name)
        process_events()

    def run_command(self, selected):
        FreeCADGui.Selection.addSelection(selected)
        FreeCADGui.runCommand(DECOMPOSE_COMMAND)
        process_events()
        return self.doc.getObject("Decomposition")

    def test_cancel_in_the_progress_dialog_undoes_the_command(self):
        names = [o.Name for o in self.doc.Objects]
        undo = self.doc.UndoCount
        with Canceller(self, "Decomposing") as canceller:
            self.assertIsNone(self.run_command(self.part))
        self.assertEqual(canceller.clicks, 1)
        self.assertEqual([o.Name for o in self.doc.Objects], names)
        self.assertEqual(self.doc.UndoCount, undo)
        self.assertTrue(self.part.ViewObject.Visibility)
        self.assertEqual(error_boxes(), [])
        # The same command then runs through.
        import MultiAxisSlicer.features as features

        decomposition = self.run_command(self.part)
        self.assertTrue(decomposition.isValid(), decomposition.getStatusString())
        self.assertEqual(len(features.components_of(decomposition)), 2)

    def check_colours(self, obj):
        """One palette colour per component, distinct; the compound's faces in the same ones."""
        import MultiAxisSlicer.features as features

        components = features.components_of(obj)
        colours = [tuple(c.ViewObject.ShapeColor[:3]) for c in components]
        for i, colour in enumerate(colours):
            self.assertTrue(same_colour(colour, view_providers.component_colour(i)), colour)
        for i in range(len(colours)):
            for j in range(i):
                self.assertFalse(same_colour(colours[i], colours[j]), (i, j))
        want = []
        # One child shape per component: a root on several feet is a compound of them.
        children = obj.Shape.childShapes()
        self.assertEqual(len(children), len(components))
        for i, child in enumerate(children):
            want += [view_providers.component_colour(i)] * len(child.Faces)
        got = obj.ViewObject.DiffuseColor
        self.assertEqual(len(got), len(want))
        for a, b in zip(got, want):
            self.assertTrue(same_colour(a, b), (a, b))
        return components

    def test_a_component_is_not_deleted_on_its_own(self):
        # Its decomposition would still hold (and slice) it: refused, with a message saying what
        # to do instead; with the decomposition selected too, everything goes.
        import MultiAxisSlicer.features as features

        decomposition = self.run_command(self.part)
        components = features.components_of(decomposition)
        self.assertEqual(len(components), 2)
        FreeCADGui.Selection.clearSelection()
        FreeCADGui.Selection.addSelection(components[1])
        FreeCADGui.runCommand("Std_Delete")
        process_events()
        self.assertEqual(len(features.components_of(decomposition)), 2)
        boxes = error_boxes()
        self.assertEqual(len(boxes), 1)
        self.assertIn("cannot be deleted on its own", boxes[0].text())
        for box in boxes:
            box.close()
        # Selected with its decomposition, it may go. (Std_Delete then asks about the
        # dependencies in a modal dialog: the view provider is asked directly.)
        FreeCADGui.Selection.clearSelection()
        FreeCADGui.Selection.addSelection(decomposition)
        FreeCADGui.Selection.addSelection(components[1])
        vobj = components[1].ViewObject
        self.assertTrue(vobj.Proxy.onDelete(vobj, []))
        FreeCADGui.Selection.clearSelection()
        self.assertFalse(vobj.Proxy.onDelete(vobj, []))

    def test_component_colours_stay_clear_of_the_reds_that_mark_faults(self):
        # A red component could not be told from the unsupported regions drawn over it, the
        # axis' breaks or the contour paths (the fourth colour was Tableau's red).
        reds = [view_providers.UNSUPPORTED_COLOUR, view_providers.AXIS_BREAK_COLOR,
                view_providers.TOOLPATH_COLOURS["ContourColor"][0]]
        for colour in view_providers.COMPONENT_COLOURS:
            for red in reds:
                self.assertGreater(math.dist(colour, red), 0.4, (colour, red))

    def test_command_needs_one_selected_part(self):
        self.assertFalse(FreeCADGui.Command.get(DECOMPOSE_COMMAND).isActive())
        FreeCADGui.Selection.addSelection(self.part)
        self.assertTrue(FreeCADGui.Command.get(DECOMPOSE_COMMAND).isActive())

    def test_command_creates_components_in_distinct_colours(self):
        before = self.part.Shape.exportBrepToString()
        obj = self.run_command(self.part)
        self.assertIsNotNone(obj, "the command made no Decomposition object")
        self.assertTrue(obj.isValid(), obj.getStatusString())
        self.assertIs(obj.Source, self.part)
        self.assertEqual(obj.ComponentCount, 2)
        components = self.check_colours(obj)
        self.assertEqual([c.Label for c in components], ["Component001", "Component002"])
        self.assertEqual(obj.ViewObject.Proxy.claimChildren(), components)
        for c in components:
            self.assertTrue(c.isValid(), c.getStatusString())
            self.assertTrue(c.ViewObject.Visibility)
            self.assertTrue(os.path.isfile(c.ViewObject.Proxy.getIcon()))
        self.assertFalse(obj.ViewObject.Visibility)  # the components show it
        self.assertTrue(obj.ViewObject.Proxy.getIcon().endswith("Decompose.svg"))
        self.assertFalse(self.part.ViewObject.Visibility)  # hidden, not changed
        self.assertEqual(self.part.Shape.exportBrepToString(), before)
        self.assertIn("Decompose", self.doc.UndoNames)
        save_screenshot(self, self.doc, "decompose_l_block.png", see_through=False)

        # A post on the arm, cut at the engine test's step: the GUI adds the third component
        # after the recompute.
        self.part.Shape = l_block().fuse(
            Part.makeBox(10, 20, 20, FreeCAD.Vector(50, 0, 60))).removeSplitter()
        obj.Step = 2.5
        self.doc.recompute()
        wait_for_components(obj, 3)
        self.assertEqual(obj.ComponentCount, 3)
        components = self.check_colours(obj)
        self.assertEqual([c.Label for c in components],
                         ["Component001", "Component002", "Component003"])
        self.doc.recompute()
        self.assertTrue(all(o.isValid() for o in self.doc.Objects))
        self.assertEqual(components[2].Parent, 1)  # the post stands on the arm
        save_screenshot(self, self.doc, "decompose_l_block_post.png", see_through=False)

        # A portal on two legs: its root is the legs apart, both in the root's colour, the
        # lintel (the bridge) in the next; the third Component object goes.
        self.part.Shape = Part.makeBox(8, 8, 30).fuse(
            [Part.makeBox(8, 8, 30, FreeCAD.Vector(42, 0, 0)),
             Part.makeBox(50, 8, 6, FreeCAD.Vector(0, 0, 30))]).removeSplitter()
        obj.Step = 0.0
        self.doc.recompute()
        wait_for_components(obj, 2)
        self.assertEqual(list(obj.Rules), ["root", "bridge"])
        components = self.check_colours(obj)
        self.assertEqual(len(components[0].Shape.Solids), 2)
        save_screenshot(self, self.doc, "decompose_portal.png", see_through=False)

    def test_undo_removes_everything(self):
        names = [o.Name for o in self.doc.Objects]
        obj = self.run_command(self.part)
        self.assertEqual(len(self.doc.Objects), len(names) + 3)
        self.doc.undo()
        process_events()
        self.assertEqual([o.Name for o in self.doc.Objects], names)

    def test_colours_survive_save_and_reopen_and_delete_takes_the_components(self):
        obj = self.run_command(self.part)
        components = features_of().components_of(obj)
        components[1].ViewObject.ShapeColor = (0.0, 0.0, 0.0)  # the user's choice is kept
        saved_and_reopened(self, "decomposition.FCStd")
        obj = self.doc.getObject("Decomposition")
        self.assertIsInstance(obj.ViewObject.Proxy, view_providers.ViewProviderDecomposition)
        components = features_of().components_of(obj)
        self.assertEqual(obj.ViewObject.Proxy.claimChildren(), components)
        self.assertTrue(same_colour(components[0].ViewObject.ShapeColor,
                                    view_providers.component_colour(0)))
        self.assertTrue(same_colour(components[1].ViewObject.ShapeColor, (0.0, 0.0, 0.0)))
        obj.touch()
        self.doc.recompute()
        process_events()
        self.assertEqual(len(features_of().components_of(obj)), 2)
        self.assertTrue(all(o.isValid() for o in self.doc.Objects))
        part = self.doc.getObject("L")
        self.assertFalse(part.ViewObject.Visibility)
        FreeCADGui.getDocument(self.doc.Name).getObject(obj.Name).Proxy.onDelete(
            obj.ViewObject, [])
        self.doc.removeObject(obj.Name)
        process_events()
        self.assertEqual([o.Name for o in self.doc.Objects], ["L"])
        self.assertTrue(part.ViewObject.Visibility)  # in view again

    def test_deleting_one_of_two_decompositions_leaves_the_part_hidden(self):
        # The other decomposition's components still show the part: showing it too would draw
        # the part over them. Deleting the last one shows it again.
        import MultiAxisSlicer.features as features

        first = self.run_command(self.part)
        FreeCADGui.Selection.clearSelection()
        self.part.ViewObject.Visibility = True  # the user looks at the part again
        self.run_command(self.part)
        second = [o for o in self.doc.Objects
                  if features.is_decomposition(o) and o is not first][0]
        self.assertTrue(second.isValid(), second.getStatusString())
        self.assertFalse(self.part.ViewObject.Visibility)
        for obj, shown in ((first, False), (second, True)):
            name = obj.Name
            self.assertTrue(obj.ViewObject.Proxy.onDelete(obj.ViewObject, []))
            self.doc.removeObject(name)
            process_events()
            self.assertEqual(self.part.ViewObject.Visibility, shown, name)
        self.assertEqual([o.Name for o in self.doc.Objects], ["L"])

    def test_a_document_made_without_the_gui_gets_its_colours(self):
        folder = tempfile.mkdtemp(prefix="mas_gui_dec_")
        try:
            path = os.path.join(folder, "decomposition.FCStd")
            script = os.path.join(folder, "make.py")
            with open(script, "w") as f:
                f.write(textwrap.dedent("""
                    import FreeCAD, Part
                    import MultiAxisSlicer as mas
                    doc = FreeCAD.newDocument("Headless")
                    part = doc.addObject("Part::Feature", "T")
                    part.Shape = Part.makeBox(20, 20, 60).fuse(Part.makeBox(
                        80, 20, 20, FreeCAD.Vector(-30, 0, 40))).removeSplitter()
                    mas.make_decomposition(part)
                    doc.recompute()
                    doc.saveAs({!r})
                """.format(path)))
            result = subprocess.run(["freecadcmd", script], capture_output=True, text=True,
                                    timeout=120)
            self.assertTrue(os.path.isfile(path), result.stdout + result.stderr)
            doc = FreeCAD.openDocument(path)
            try:
                process_events()
                obj = doc.getObject("Decomposition")
                self.assertIsInstance(obj.ViewObject.Proxy,
                                      view_providers.ViewProviderDecomposition)
                self.assertEqual(obj.ComponentCount, 3)
                self.check_colours(obj)
            finally:
                FreeCAD.closeDocument(doc.Name)
        finally:
            shutil.rmtree(folder)

    def test_command_on_a_centroidal_axis_uses_its_parameters(self):
        import MultiAxisSlicer as mas

        axis = mas.make_centroidal_axis(self.part, step=2.5)
        self.doc.recompute()
        obj = self.run_command(axis)
        self.assertIsNotNone(obj)
        self.assertTrue(obj.isValid(), obj.getStatusString())
        self.assertIs(obj.Axis, axis)
        self.assertEqual(obj.UsedStep.Value, 2.5)
        self.assertEqual(obj.ComponentCount, 2)
        self.check_colours(obj)

    def test_command_on_a_face_shows_the_engine_message(self):
        self.part.Shape = Part.makePlane(10, 10)
        self.doc.recompute()
        undo = self.doc.UndoCount
        obj = self.run_command(self.part)
        self.assertIsNone(obj)  # refused before anything is made: it could never work
        self.assertEqual(self.doc.UndoCount, undo)
        boxes = error_boxes()
        self.assertEqual(len(boxes), 1)
        self.assertIn("not a solid", boxes[0].text())
        self.assertTrue(self.part.ViewObject.Visibility)  # nothing replaced it

    def test_command_on_a_mesh_says_a_solid_is_needed(self):
        # A mesh (or an axis computed on one) cannot be split into solids: refused up front,
        # saying how to make a solid of it; the axis of the same mesh is fine.
        import Mesh
        import MultiAxisSlicer.features as features

        mesh = self.doc.addObject("Mesh::Feature", "Scan")
        mesh.Mesh = Mesh.Mesh(l_block().tessellate(0.01))
        self.doc.recompute()
        axis = features.make_centroidal_axis(mesh)
        self.doc.recompute()
        self.assertTrue(axis.isValid(), axis.getStatusString())
        undo = self.doc.UndoCount
        for selected in (mesh, axis):
            FreeCADGui.Selection.clearSelection()
            obj = self.run_command(selected)
            self.assertIsNone(obj, selected.Label)
            self.assertEqual(self.doc.UndoCount, undo)
            boxes = error_boxes()
            self.assertEqual(len(boxes), 1, selected.Label)
            self.assertIn("Decompose: 'Scan' is a mesh: decomposing splits a BREP solid",
                          boxes[0].text())
            self.assertIn("or slice the mesh (Slice), which splits it at section planes.",
                          boxes[0].text())
            boxes[0].close()

    def test_command_on_a_failing_axis_shows_the_axis_message(self):
        # FreeCAD leaves an object whose input failed touched and valid, without a word: the
        # command names the axis' error, and the part stays in view.
        import MultiAxisSlicer as mas

        axis = mas.make_centroidal_axis(self.part, step=1e6)
        self.doc.recompute()
        self.assertIn("Invalid", axis.State)
        obj = self.run_command(axis)
        self.assertIsNotNone(obj)
        self.assertEqual(obj.ComponentCount, 0)
        boxes = error_boxes()
        self.assertEqual(len(boxes), 1)
        self.assertIn("CentroidalAxis: ", boxes[0].text())
        self.assertIn("not smaller than the part's height", boxes[0].text())
        self.assertTrue(self.part.ViewObject.Visibility)


class TestSliceCommand(unittest.TestCase):
    def setUp(self):
        FreeCADGui.activateWorkbench(WORKBENCH)
        self.doc = FreeCAD.newDocument("MasGuiSlice")
        self.part = self.doc.addObject("Part::Feature", "L")
        self.part.Shape = l_block()
        self.doc.recompute()
        FreeCADGui.Selection.clearSelection()
        process_events()

    def tearDown(self):
        FreeCADGui.Selection.clearSelection()
        close_error_boxes()
        FreeCAD.closeDocument(self.doc.Name)
        process_events()

    def run_command(self, selected):
        FreeCADGui.Selection.addSelection(selected)
        FreeCADGui.runCommand(SLICE_COMMAND)
        process_events()
        return self.doc.getObject("Layers"), self.doc.getObject("Toolpath")

    def check_rendered_colours(self, obj):
        """The 3D view's line set is coloured with LineColorArray (FreeCAD 0.20 leaves garbage
        there when the array is set before the line set is redrawn for a new Shape)."""
        from pivy import coin

        process_events()
        want = obj.ViewObject.LineColorArray
        search = coin.SoSearchAction()
        search.setType(coin.SoMaterial.getClassTypeId())
        search.setInterest(coin.SoSearchAction.ALL)
        search.apply(obj.ViewObject.RootNode)
        materials = [search.getPaths().get(i).getTail()
                     for i in range(search.getPaths().getLength())]
        lines = [m for m in materials if m.diffuseColor.getNum() == len(want)]
        self.assertTrue(lines, "no line material with {} colours".format(len(want)))
        got = [lines[0].diffuseColor[i].getValue() for i in range(len(want))]
        for i, (a, b) in enumerate(zip(got, want)):
            self.assertTrue(same_colour(a, b), "{} edge {} drawn in {}, not {}".format(
                obj.Label, i, a, b))

    def check_colours(self, layers, toolpath):
        """Layer outlines in their component's colour, the unsupported regions' outlines in the
        Layers' ShapeColor, paths in their kind's, edge by edge."""
        want = []
        for layer, component in zip(layers.Shape.childShapes(), layers.LayerComponents):
            unsupported = [e for f in layer.Faces for e in f.Edges]
            for edge in layer.Edges:
                want.append(layers.ViewObject.ShapeColor
                            if any(edge.isSame(e) for e in unsupported) else
                            view_providers.component_colour(component))
        got = layers.ViewObject.LineColorArray
        self.assertEqual(len(got), len(want))
        for i, (a, b) in enumerate(zip(got, want)):
            self.assertTrue(same_colour(a, b), "layer edge {}: {} != {}".format(i, a, b))
        vobj = toolpath.ViewObject
        want = []
        for group, prop in zip(toolpath.Shape.childShapes(),
                               view_providers.TOOLPATH_COLOUR_ORDER):
            want += [getattr(vobj, prop)] * len(group.Edges)
        got = vobj.LineColorArray
        self.assertEqual(len(got), len(want))
        for i, (a, b) in enumerate(zip(got, want)):
            self.assertTrue(same_colour(a, b), "path edge {}: {} != {}".format(i, a, b))
        for obj in (layers, toolpath):
            if obj.ViewObject.Visibility:
                self.check_rendered_colours(obj)

    def test_command_needs_one_selected_part(self):
        self.assertFalse(FreeCADGui.Command.get(SLICE_COMMAND).isActive())
        FreeCADGui.Selection.addSelection(self.part)
        self.assertTrue(FreeCADGui.Command.get(SLICE_COMMAND).isActive())

    def test_slicing_a_decomposition_whose_part_changed_brings_its_components_along(self):
        # The command recomputes the decomposition (its part changed since) and its Component
        # objects with it, not only the layers and paths it makes.
        import MultiAxisSlicer.features as features

        decomposition = mas.make_decomposition(self.part)
        self.doc.recompute()
        shape = l_block()
        shape.scale(2.0)
        self.part.Shape = shape
        layers, toolpath = self.run_command(decomposition)
        self.assertTrue(toolpath.isValid(), toolpath.getStatusString())
        components = features.components_of(decomposition)
        self.assertEqual(len(components), decomposition.ComponentCount)
        for c, volume in zip(components, decomposition.Volumes):
            self.assertNotIn("Touched", c.State, c.Label)
            self.assertAlmostEqual(c.Shape.Volume, volume, delta=1e-6 * volume)
        self.assertAlmostEqual(sum(decomposition.Volumes), shape.Volume,
                               delta=1e-6 * shape.Volume)

    def test_command_slices_a_selected_decomposition(self):
        decomposition = mas.make_decomposition(self.part)
        self.doc.recompute()
        before = self.part.Shape.exportBrepToString()
        names = [o.Name for o in self.doc.Objects]
        layers, toolpath = self.run_command(decomposition)
        self.assertIsNotNone(layers, "the command made no Layers object")
        self.assertIsNotNone(toolpath, "the command made no Toolpath object")
        self.assertEqual(error_boxes(), [])
        self.assertTrue(layers.isValid(), layers.getStatusString())
        self.assertTrue(toolpath.isValid(), toolpath.getStatusString())
        self.assertIs(layers.Decomposition, decomposition)
        self.assertIs(toolpath.Layers, layers)
        self.assertEqual(list(layers.ComponentLayerCounts), [30, 25])
        self.assertEqual(list(layers.BuildOrder), [0, 1])
        self.assertEqual(layers.LayerCount, 55)
        self.assertGreater(toolpath.PathCount, 55)
        self.assertIsNone(QtGui.QApplication.overrideCursor())  # the wait cursor is gone
        self.assertEqual(self.part.Shape.exportBrepToString(), before)
        self.assertTrue(layers.ViewObject.Visibility)
        self.assertTrue(toolpath.ViewObject.Visibility)
        self.assertTrue(layers.ViewObject.Proxy.getIcon().endswith("Slice.svg"))
        self.assertTrue(os.path.isfile(layers.ViewObject.Proxy.getIcon()))
        self.assertTrue(os.path.isfile(toolpath.ViewObject.Proxy.getIcon()))
        import MultiAxisSlicer.features as features

        for c in features.components_of(decomposition):  # the layers take their place
            self.assertFalse(c.ViewObject.Visibility)
        self.assertFalse(self.part.ViewObject.Visibility)
        self.check_colours(layers, toolpath)
        self.assertIn("Slice", self.doc.UndoNames)
        save_screenshot(self, self.doc, "slice_l_block.png", see_through=False)

        # Parameters and view settings: the colours follow.
        layers.MaxLayer = 1.5
        toolpath.ShowTravel = True
        self.doc.recompute()
        process_events()
        self.assertTrue(layers.isValid(), layers.getStatusString())
        self.assertGreater(toolpath.PathCounts[3], 0)
        self.check_colours(layers, toolpath)
        layers.ViewObject.LineColor = (0.0, 0.0, 0.0)  # FreeCAD resets the per-edge colours
        toolpath.ViewObject.TravelColor = (0.0, 0.8, 0.0)
        process_events()
        self.check_colours(layers, toolpath)

        self.doc.undo()  # one step takes both
        process_events()
        self.assertEqual([o.Name for o in self.doc.Objects], names)

    def test_command_slices_a_selected_mesh_as_one_component(self):
        # A closed mesh cannot be decomposed (that needs a BREP solid): it is sliced as it is, as
        # the scripting API and the command line slice one, in one undo step; the layers take its
        # place in the view until they are deleted.
        import Mesh
        import MultiAxisSlicer.features as features

        scan = self.doc.addObject("Mesh::Feature", "Scan")
        scan.Mesh = Mesh.Mesh(Part.makeBox(20, 10, 21).tessellate(0.01))
        self.doc.recompute()
        topology = scan.Mesh.Topology
        names = [o.Name for o in self.doc.Objects]
        layers, toolpath = self.run_command(scan)
        self.assertEqual(error_boxes(), [])
        self.assertTrue(toolpath.isValid(), toolpath.getStatusString())
        self.assertIs(layers.Source, scan)
        self.assertIsNone(layers.Decomposition)
        self.assertEqual([o.Name for o in self.doc.Objects], names + [layers.Name, toolpath.Name])
        self.assertEqual(layers.LayerCount, 11)  # 21 mm: ten of 2 mm, one of 1 mm
        self.assertEqual(list(layers.LayerComponents), [0] * 11)
        self.assertEqual(scan.Mesh.Topology, topology)
        self.assertFalse(scan.ViewObject.Visibility)
        self.assertTrue(layers.ViewObject.Visibility)
        # One component, nothing unsupported: every outline in the first component's colour.
        (colour,) = layers.ViewObject.LineColorArray
        self.assertTrue(same_colour(colour, view_providers.component_colour(0)))
        self.assertIsNone(QtGui.QApplication.overrideCursor())
        self.assertIn("Slice", self.doc.UndoNames)
        self.doc.undo()  # one step takes both
        process_events()
        self.assertEqual([o.Name for o in self.doc.Objects], names)
        self.assertTrue(scan.ViewObject.Visibility)
        # Deleting the layers shows the mesh again (the view provider is asked as Std_Delete
        # asks it, without its modal question about the Toolpath depending on them).
        layers, toolpath = self.run_command(scan)
        self.assertFalse(scan.ViewObject.Visibility)
        self.doc.removeObject(toolpath.Name)
        self.assertTrue(layers.ViewObject.Proxy.onDelete(layers.ViewObject, []))
        self.doc.removeObject(layers.Name)
        process_events()
        self.assertEqual([o.Name for o in self.doc.Objects], names)
        self.assertTrue(scan.ViewObject.Visibility)

    def test_a_meshs_layers_survive_save_and_reopen_and_make_a_program(self):
        # The L as a mesh: split into the column and the arm, each in its colour.
        import Mesh

        scan = self.doc.addObject("Mesh::Feature", "Scan")
        scan.Mesh = Mesh.Mesh(self.part.Shape.tessellate(0.01))
        self.doc.recompute()
        layers, toolpath = self.run_command(scan)
        self.assertTrue(toolpath.isValid(), toolpath.getStatusString())
        self.assertEqual(len(layers.ComponentLayerCounts), 2)
        self.assertEqual(layers.Shape.Faces, [])  # nothing stands on nothing
        self.check_colours(layers, toolpath)
        save_screenshot(self, self.doc, "slice_mesh_l_block.png", see_through=False)
        count = layers.LayerCount
        saved_and_reopened(self, "mesh_slice.FCStd")
        scan = self.doc.getObject("Scan")
        layers, toolpath = self.doc.getObject("Layers"), self.doc.getObject("Toolpath")
        self.assertIs(layers.Source, scan)
        self.assertIsInstance(layers.ViewObject.Proxy, view_providers.ViewProviderLayers)
        self.assertEqual(layers.LayerCount, count)
        self.assertFalse(scan.ViewObject.Visibility)
        self.check_colours(layers, toolpath)
        FreeCADGui.Selection.clearSelection()
        FreeCADGui.Selection.addSelection(layers)
        FreeCADGui.runCommand(PROGRAM_COMMAND)  # the slicing is redone on demand
        process_events()
        program = self.doc.getObject("MachineProgram")
        self.assertIsNotNone(program)
        self.assertEqual(error_boxes(), [])
        self.assertTrue(program.isValid(), program.getStatusString())
        self.assertGreater(program.DepositMoves, count)

    def test_command_on_the_axis_of_a_mesh_slices_the_mesh_along_it(self):
        # As a selected axis of a solid is decomposed with its parameters, the mesh of a selected
        # axis is sliced along an axis with them.
        import Mesh
        import MultiAxisSlicer.features as features

        scan = self.doc.addObject("Mesh::Feature", "Scan")
        scan.Mesh = Mesh.Mesh(self.part.Shape.tessellate(0.01))
        axis = mas.make_centroidal_axis(scan, step=2.5)
        self.doc.recompute()
        layers, toolpath = self.run_command(axis)
        self.assertEqual(error_boxes(), [])
        self.assertTrue(toolpath.isValid(), toolpath.getStatusString())
        self.assertIs(layers.Axis, axis)
        self.assertIsNone(layers.Source)
        self.assertEqual(features.slice_result(layers).to_dict(),
                         mas.slice(scan.Mesh, step=2.5).to_dict())
        self.assertFalse(scan.ViewObject.Visibility)
        self.doc.removeObject(toolpath.Name)
        self.assertTrue(layers.ViewObject.Proxy.onDelete(layers.ViewObject, []))
        self.assertTrue(scan.ViewObject.Visibility)

    def test_command_slices_a_selected_link_to_a_mesh_where_the_link_shows_it(self):
        # An App::Link to a mesh object (which has no Shape of its own in FreeCAD 0.20) is sliced
        # as the mesh the link shows, moved 40 mm along Y; a link array of the mesh is refused,
        # named, before anything is made.
        import Mesh

        scan = self.doc.addObject("Mesh::Feature", "Scan")
        scan.Mesh = Mesh.Mesh(Part.makeBox(20, 10, 21).tessellate(0.01))
        link = self.doc.addObject("App::Link", "ScanLink")
        link.LinkedObject = scan
        link.Placement.Base = FreeCAD.Vector(0, 40, 0)
        self.doc.recompute()
        layers, toolpath = self.run_command(link)
        self.assertEqual(error_boxes(), [])
        self.assertTrue(toolpath.isValid(), toolpath.getStatusString())
        self.assertIs(layers.Source, link)
        self.assertEqual(layers.LayerCount, 11)
        bb = layers.Shape.BoundBox
        self.assertAlmostEqual(bb.YMin, 40.0, delta=0.01)
        self.assertAlmostEqual(bb.YMax, 50.0, delta=0.01)
        self.assertFalse(link.ViewObject.Visibility)
        self.doc.undo()
        process_events()
        link.ElementCount = 3
        self.doc.recompute()
        names = [o.Name for o in self.doc.Objects]
        layers, toolpath = self.run_command(link)
        self.assertIsNone(layers)
        self.assertEqual([o.Name for o in self.doc.Objects], names)
        boxes = error_boxes()
        self.assertEqual(len(boxes), 1)
        self.assertIn("'ScanLink' is 3 copies of the mesh 'Scan' (a link array)", boxes[0].text())

    def test_command_on_an_open_mesh_names_the_problem(self):
        import Mesh

        points, facets = Mesh.Mesh(Part.makeBox(20, 10, 21).tessellate(0.01)).Topology
        scan = self.doc.addObject("Mesh::Feature", "Scan")
        scan.Mesh = Mesh.Mesh([[points[i] for i in f] for f in facets[:-1]])
        self.doc.recompute()
        undo = self.doc.UndoCount
        names = [o.Name for o in self.doc.Objects]
        # While the mesh reaches the engine and is checked (seconds for a million-facet scan), a
        # wait cursor and the status bar say so; neither is left when the message comes up.
        from unittest import mock

        seen, model = [], mas._model

        def checked(*args, **kwargs):
            cursor = QtGui.QApplication.overrideCursor()
            seen.append((cursor.shape() if cursor is not None else None,
                         FreeCADGui.getMainWindow().statusBar().currentMessage()))
            return model(*args, **kwargs)

        with mock.patch.object(mas, "_model", checked):
            layers, toolpath = self.run_command(scan)
        self.assertTrue(seen)  # (_model takes a Mesh::Feature's Mesh by calling itself)
        self.assertEqual(set(seen),
                         {(QtCore.Qt.WaitCursor, "Multi-Axis Slicer: checking 'Scan'...")})
        self.assertIsNone(QtGui.QApplication.overrideCursor())
        self.assertNotIn("checking", FreeCADGui.getMainWindow().statusBar().currentMessage())
        self.assertIsNone(layers)  # refused before anything is made
        self.assertEqual([o.Name for o in self.doc.Objects], names)
        self.assertEqual(self.doc.UndoCount, undo)
        boxes = error_boxes()
        self.assertEqual(len(boxes), 1)
        self.assertIn("Slice: 'Scan'", boxes[0].text())
        self.assertIn("3 boundary edges", boxes[0].text())
        self.assertTrue(scan.ViewObject.Visibility)

    def test_unsupported_regions_are_drawn_in_red_where_layers_bridge_a_hole(self):
        """A block with a horizontal hole: the layers closing over its ceiling stand partly on
        nothing. Those regions are the Layers' faces, filled and outlined in ShapeColor (red), and
        follow a change of ShapeColor."""
        self.part.Shape = Part.makeBox(30, 10, 20).cut(
            Part.makeCylinder(4, 10, FreeCAD.Vector(15, 0, 10), FreeCAD.Vector(0, 1, 0)))
        self.doc.recompute()
        layers, toolpath = self.run_command(self.part)
        self.assertTrue(layers.isValid(), layers.getStatusString())
        self.assertGreater(len(layers.Shape.Faces), 0)
        self.assertTrue(same_colour(layers.ViewObject.ShapeColor,
                                    view_providers.UNSUPPORTED_COLOUR))
        self.assertIn(view_providers.UNSUPPORTED_COLOUR,
                      [tuple(c)[:3] for c in layers.ViewObject.LineColorArray])
        self.check_colours(layers, toolpath)
        toolpath.ViewObject.Visibility = False
        save_screenshot(self, self.doc, "slice_unsupported.png", see_through=False)
        layers.ViewObject.ShapeColor = (0.0, 0.0, 1.0)
        process_events()
        self.check_colours(layers, toolpath)

    def test_holes_to_drill_are_drawn_as_their_axes_and_end_circles(self):
        """With FillHoles, the block's pin hole is deposited solid: no red region is left, and
        the hole to drill shows as its axis and a circle of its diameter at each end, in
        DrillColor. Without it, nothing of the kind is drawn."""
        self.part.Shape = Part.makeBox(30, 10, 20).cut(
            Part.makeCylinder(4, 10, FreeCAD.Vector(15, 0, 10), FreeCAD.Vector(0, 1, 0)))
        self.doc.recompute()
        layers, toolpath = self.run_command(self.part)
        proxy = layers.ViewObject.Proxy
        self.assertEqual(proxy.drill_points.point.getNum(), 0)
        self.assertTrue(same_colour(layers.ViewObject.DrillColor, view_providers.DRILL_COLOUR))
        layers.FillHoles = 8.0
        self.doc.recompute()
        process_events()
        self.assertTrue(layers.isValid(), layers.getStatusString())
        self.assertEqual(layers.FilledHoleCount, 1)
        self.assertEqual(len(layers.Shape.Faces), 0)  # nothing unsupported left
        segments = view_providers.DRILL_CIRCLE_SEGMENTS
        self.assertEqual([proxy.drill_lines.numVertices[i] for i in range(3)],
                         [2, segments + 1, segments + 1])
        points = [FreeCAD.Vector(*proxy.drill_points.point[i].getValue())
                  for i in range(proxy.drill_points.point.getNum())]
        self.assertEqual(len(points), 2 * segments + 4)
        ends = sorted(points[:2], key=lambda p: p.y)
        for got, want in zip(ends, (FreeCAD.Vector(15, 0, 10), FreeCAD.Vector(15, 10, 10))):
            self.assertLess((got - want).Length, 1e-5)
        for p in points[2:]:  # on the circles of radius 4 round the axis, at y = 0 or 10
            self.assertAlmostEqual(math.hypot(p.x - 15, p.z - 10), 4.0, places=5)
            self.assertLess(min(abs(p.y), abs(p.y - 10)), 1e-5)
        layers.ViewObject.DrillColor = (0.0, 0.8, 0.0)
        process_events()
        self.assertTrue(same_colour(proxy.drill_colour.rgb[0].getValue(), (0.0, 0.8, 0.0)))
        # Hidden, the layers draw nothing, their holes to drill neither (they were drawn still).
        self.assertFalse(drawn_box(layers).isEmpty())
        layers.ViewObject.Visibility = False
        process_events()
        self.assertTrue(drawn_box(layers).isEmpty())
        layers.ViewObject.Visibility = True
        process_events()
        self.assertFalse(drawn_box(layers).isEmpty())
        toolpath.ViewObject.Visibility = False
        save_screenshot(self, self.doc, "slice_holes_to_drill.png", see_through=False)
        layers.FillHoles = 0.0
        self.doc.recompute()
        process_events()
        self.assertEqual(proxy.drill_points.point.getNum(), 0)
        self.assertGreater(len(layers.Shape.Faces), 0)

    def test_collisions_are_drawn_from_the_nozzle_to_what_it_meets(self):
        """A coaxial nozzle with a 100 mm body deposits the L's arm sideways 40 to 60 mm above the
        plate: every arm layer's nozzle meets the plate, drawn as a line in CollisionColor from
        its deposit point to the plate and a point there. Leaned (NozzleMaxLean) or with
        CheckPlate off, none collides and nothing is drawn."""
        layers, toolpath = self.run_command(self.part)
        proxy = layers.ViewObject.Proxy
        self.assertEqual(proxy.collision_lines.numVertices.getNum(), 0)
        self.assertTrue(same_colour(layers.ViewObject.CollisionColor,
                                    view_providers.COLLISION_COLOUR))
        layers.NozzleBodyDiameter = 100.0
        layers.NozzleMaxLean = 0.0
        self.doc.recompute()
        process_events()
        self.assertTrue(layers.isValid(), layers.getStatusString())
        count = layers.CollidingLayers
        self.assertEqual(count, layers.ComponentLayerCounts[1])  # every arm layer
        self.assertEqual([proxy.collision_lines.numVertices[i] for i in range(count)],
                         [2] * count)
        self.assertEqual(proxy.collision_marks.numPoints.getValue(), count)
        self.assertEqual(proxy.collision_lines.startIndex.getValue(), count)
        points = [FreeCAD.Vector(*proxy.collision_points.point[i].getValue())
                  for i in range(proxy.collision_points.point.getNum())]
        self.assertEqual(len(points), 3 * count)
        for k in range(count):
            obstacle, start, end = points[k], points[count + 2 * k], points[count + 2 * k + 1]
            self.assertLess((obstacle - layers.CollisionPoints[k]).Length, 1e-5)
            self.assertLess((start - layers.CollisionNozzlePoints[k]).Length, 1e-5)
            self.assertLess((end - obstacle).Length, 1e-9)
            self.assertAlmostEqual(obstacle.z, 0.0, places=5)  # on the plate
        toolpath.ViewObject.Visibility = False
        save_screenshot(self, self.doc, "slice_collisions.png", see_through=False)
        layers.ViewObject.CollisionColor = (0.0, 0.0, 1.0)
        process_events()
        self.assertTrue(same_colour(proxy.collision_colour.rgb[0].getValue(), (0.0, 0.0, 1.0)))
        for prop, value in (("NozzleMaxLean", 30.0), ("CheckPlate", False)):
            setattr(layers, prop, value)
            self.doc.recompute()
            process_events()
            self.assertEqual(layers.CollidingLayers, 0, prop)
            self.assertEqual(proxy.collision_lines.numVertices.getNum(), 0, prop)
            self.assertEqual(proxy.collision_points.point.getNum(), 0, prop)
        self.assertEqual(layers.LeanedLayers, 0)  # nothing to clear without the plate

    def test_command_on_a_solid_decomposes_it_first(self):
        layers, toolpath = self.run_command(self.part)
        self.assertIsNotNone(layers)
        self.assertTrue(toolpath.isValid(), toolpath.getStatusString())
        decomposition = self.doc.getObject("Decomposition")
        self.assertIs(layers.Decomposition, decomposition)
        self.assertEqual(decomposition.ComponentCount, 2)
        # No sub-component thinner than the layers.
        self.assertEqual(decomposition.MinComponentHeight.Value, layers.MinLayer.Value)
        self.assertFalse(self.part.ViewObject.Visibility)  # hidden, not changed
        self.check_colours(layers, toolpath)
        toolpath.ViewObject.Visibility = False
        save_screenshot(self, self.doc, "slice_l_block_layers.png", see_through=False)
        toolpath.ViewObject.Visibility = True
        layers.ViewObject.Visibility = False
        save_screenshot(self, self.doc, "slice_l_block_toolpath.png", see_through=False)
        layers.ViewObject.Visibility = True
        self.check_colours(layers, toolpath)
        self.doc.undo()
        process_events()
        self.assertEqual([o.Name for o in self.doc.Objects], ["L"])

    def test_command_on_a_solid_builds_a_branch_the_nozzle_cannot_reach_in_its_father(self):
        # A machine whose nozzle is 100 mm across and never leans: built sideways on its own, the
        # L's arm would have it meet the plate at every layer. The command keeps the arm in the
        # column (KeepBranches), as slice() would, in one undo step.
        import MultiAxisSlicer.features as features

        nozzle = dict(nozzle_body_diameter=100.0, nozzle_max_lean=0.0)
        for name, value in nozzle.items():
            self.addCleanup(mas.SLICE_DEFAULTS.__setitem__, name, mas.SLICE_DEFAULTS[name])
            mas.SLICE_DEFAULTS[name] = value
        layers, toolpath = self.run_command(self.part)
        self.assertEqual(error_boxes(), [])
        decomposition = layers.Decomposition
        for obj in (decomposition, layers, toolpath):
            self.assertIsNone(features.failure(obj))
        self.assertEqual(layers.NozzleBodyDiameter.Value, 100.0)
        self.assertEqual(list(decomposition.KeepBranches), [1])
        self.assertEqual(decomposition.ComponentCount, 1)
        components = features.components_of(decomposition)
        self.assertEqual(len(components), 1)
        self.assertEqual([c.ViewObject.Visibility for c in components], [False])
        self.assertEqual(layers.CollidingLayers, 0)
        expected = mas.slice(self.part.Shape, **nozzle)
        self.assertEqual(expected.decomposition.kept_branches, [1])
        self.assertEqual(list(layers.LayerOrigins), [layer.origin for layer in expected.layers])
        self.assertIsNone(QtGui.QApplication.overrideCursor())
        toolpath.ViewObject.Visibility = False
        save_screenshot(self, self.doc, "slice_l_block_arm_kept.png", see_through=False)
        self.doc.undo()
        process_events()
        self.assertEqual([o.Name for o in self.doc.Objects], ["L"])
        self.assertTrue(self.part.ViewObject.Visibility)
        # Cancelled while it splits the part again, the command is undone.
        undo = self.doc.UndoCount
        with Canceller(self, "Keeping unreachable branches") as canceller:
            self.run_command(self.part)
        self.assertEqual(canceller.clicks, 1)
        self.assertEqual([o.Name for o in self.doc.Objects], ["L"])
        self.assertEqual(self.doc.UndoCount, undo)
        self.assertEqual(error_boxes(), [])
        self.assertTrue(self.part.ViewObject.Visibility)
        # Where splitting it again fails, the first split stays, its collisions reported.
        def fails(layers):
            raise mas.EngineError("decompose: OCCT could not split the part")

        self.addCleanup(setattr, features, "keep_unreachable_branches",
                        features.keep_unreachable_branches)
        features.keep_unreachable_branches = fails
        layers, toolpath = self.run_command(self.part)
        self.assertEqual(error_boxes(), [])
        self.assertEqual(list(layers.Decomposition.KeepBranches), [])
        self.assertEqual(layers.Decomposition.ComponentCount, 2)
        self.assertGreater(layers.CollidingLayers, 0)
        self.assertIsNone(features.failure(toolpath))

    def test_command_on_a_solid_builds_a_hanging_branch_in_its_father(self):
        # The survey's braced frame 6 at seed 3: decomposed, its brace is built along X with the
        # far post, whose side hangs past the deflection's strip in some layers, none in the
        # nozzle's way. The command keeps the brace in the posts' layers, as slice() does.
        import MultiAxisSlicer.features as features
        import MultiAxisSlicerSurvey

        self.part.Shape = MultiAxisSlicerSurvey.part("truss", 6, 3)[0]
        self.doc.recompute()
        layers, toolpath = self.run_command(self.part)
        self.assertEqual(error_boxes(), [])
        decomposition = layers.Decomposition
        for obj in (decomposition, layers, toolpath):
            self.assertIsNone(features.failure(obj))
        self.assertEqual(list(decomposition.KeepBranches), [3])
        self.assertEqual(layers.CollidingLayers, 0)
        expected = mas.slice(self.part.Shape)
        self.assertEqual(expected.decomposition.kept_branches, [3])
        self.assertEqual(list(layers.LayerOrigins), [layer.origin for layer in expected.layers])
        self.assertFalse(features.hangs_past_strip(features.slice_result(layers),
                                                   mas.deflection(self.part.Shape)))

    def test_command_on_a_face_shows_the_engine_message(self):
        self.part.Shape = Part.makePlane(10, 10)
        self.doc.recompute()
        undo = self.doc.UndoCount
        layers, toolpath = self.run_command(self.part)
        self.assertIsNone(layers)  # refused before anything is made
        self.assertEqual([o.Name for o in self.doc.Objects], ["L"])
        self.assertEqual(self.doc.UndoCount, undo)
        boxes = error_boxes()
        self.assertEqual(len(boxes), 1)
        self.assertIn("not a solid", boxes[0].text())
        self.assertIsNone(QtGui.QApplication.overrideCursor())

    def test_deleting_the_layers_shows_the_components_again(self):
        import MultiAxisSlicer.features as features

        layers, toolpath = self.run_command(self.part)
        components = features.components_of(layers.Decomposition)
        self.assertEqual([c.ViewObject.Visibility for c in components], [False, False])
        self.doc.removeObject(toolpath.Name)
        self.assertTrue(layers.ViewObject.Proxy.onDelete(layers.ViewObject, []))
        self.doc.removeObject(layers.Name)
        process_events()
        self.assertEqual([c.ViewObject.Visibility for c in components], [True, True])

    def test_components_follow_a_source_change_that_the_layers_recompute_after(self):
        # The Decomposition's new count asks for its components to be synchronised once events
        # are processed; the Layers after it in the same recompute process events as they report
        # (every report here): the synchronisation waits for the recompute's end instead of
        # failing in it, which left a component broken for good.

        import MultiAxisSlicer.features as features

        decomposition = features.make_decomposition(self.part)
        features.make_slice(decomposition)
        self.doc.recompute()
        process_events()
        self.assertEqual(len(features.components_of(decomposition)), 2)
        saved = progress.INTERVAL
        progress.INTERVAL = 0.0
        try:
            self.doc.openTransaction("Shorten")
            self.part.Shape = Part.makeBox(20, 20, 30)
            self.doc.commitTransaction()
            self.doc.recompute()
        finally:
            progress.INTERVAL = saved
        self.assertEqual(decomposition.ComponentCount, 1)
        wait_for_components(decomposition, 1)
        self.assertEqual(len(features.components_of(decomposition)), 1)
        self.assertEqual([(o.Name, o.getStatusString()) for o in self.doc.Objects
                          if not o.isValid()], [])
        # Its own undo step, named; the next one takes the source back.
        self.assertEqual(self.doc.UndoNames[:2], ["Components of 'Decomposition'", "Shorten"])

    def test_command_on_a_failing_axis_shows_the_axis_message(self):
        import MultiAxisSlicer as mas

        axis = mas.make_centroidal_axis(self.part, step=1e6)
        self.doc.recompute()
        layers, toolpath = self.run_command(axis)
        self.assertIsNone(layers)  # nothing to slice: the decomposition's axis failed
        boxes = error_boxes()
        self.assertEqual(len(boxes), 1)
        self.assertIn("CentroidalAxis: ", boxes[0].text())
        self.assertIn("not smaller than the part's height", boxes[0].text())
        self.assertTrue(self.part.ViewObject.Visibility)

    def test_cancel_in_the_progress_dialog_undoes_the_command(self):
        before = self.part.Shape.exportBrepToString()
        names = [o.Name for o in self.doc.Objects]
        undo = self.doc.UndoCount
        for stage in ("Decomposing", "Slicing"):  # the solid is decomposed first
            cancels = progress.cancel_count()
            with Canceller(self, stage) as canceller:
                self.run_command(self.part)
            self.assertEqual(canceller.clicks, 1, stage)
            self.assertEqual(progress.cancel_count(), cancels + 1, stage)
            # Nothing the command made stays, the part is shown as before, no error box.
            self.assertEqual([o.Name for o in self.doc.Objects], names, stage)
            self.assertEqual(self.doc.UndoCount, undo, stage)
            self.assertTrue(self.part.ViewObject.Visibility, stage)
            self.assertEqual(error_boxes(), [], stage)
            self.assertEqual(self.part.Shape.exportBrepToString(), before, stage)
            self.assertIsNone(QtGui.QApplication.overrideCursor(), stage)
            self.assertEqual(QtGui.QApplication.activeModalWidget(), None, stage)
        # The same command then runs through.
        layers, toolpath = self.run_command(self.part)
        self.assertTrue(toolpath.isValid(), toolpath.getStatusString())
        self.assertEqual(layers.LayerCount, 55)

    def test_a_cancelled_recompute_marks_the_object_and_the_next_one_runs(self):
        layers, toolpath = self.run_command(mas.make_decomposition(self.part))
        self.assertTrue(toolpath.isValid(), toolpath.getStatusString())
        layers.MaxLayer = 1.5
        with Canceller(self, "Slicing 'Layers'") as canceller:
            self.doc.recompute()
        self.assertEqual(canceller.clicks, 1)
        self.assertIn("Invalid", layers.State)
        self.assertIn("cancelled by the user", layers.getStatusString())
        self.assertEqual(error_boxes(), [])
        self.doc.recompute()
        self.assertTrue(layers.isValid(), layers.getStatusString())
        self.assertTrue(toolpath.isValid(), toolpath.getStatusString())
        self.assertGreater(layers.LayerCount, 55)

    def test_a_failing_layers_object_shows_its_message(self):
        decomposition = mas.make_decomposition(self.part)
        layers, toolpath = mas.make_slice(decomposition)
        layers.MinLayer = 3.0
        self.doc.recompute()
        self.assertIn("Invalid", layers.State)
        self.assertIn("MinLayer", layers.getStatusString())
        layers.MinLayer = 0.5
        self.doc.recompute()
        process_events()
        self.assertTrue(toolpath.isValid(), toolpath.getStatusString())
        self.check_colours(layers, toolpath)

    def test_colours_survive_save_and_reopen(self):
        self.run_command(mas.make_decomposition(self.part))
        saved_and_reopened(self, "slice.FCStd")
        layers, toolpath = self.doc.getObject("Layers"), self.doc.getObject("Toolpath")
        self.assertIsInstance(layers.ViewObject.Proxy, view_providers.ViewProviderLayers)
        self.assertIsInstance(toolpath.ViewObject.Proxy, view_providers.ViewProviderToolpath)
        self.check_colours(layers, toolpath)
        toolpath.ShowTravel = True  # the slicing is redone on demand
        self.doc.recompute()
        process_events()
        self.assertTrue(toolpath.isValid(), toolpath.getStatusString())
        self.check_colours(layers, toolpath)


    def test_a_document_made_without_the_gui_gets_its_colours(self):
        folder = tempfile.mkdtemp(prefix="mas_gui_slice_")
        try:
            path = os.path.join(folder, "slice.FCStd")
            script = os.path.join(folder, "make.py")
            with open(script, "w") as f:
                f.write(textwrap.dedent("""
                    import FreeCAD, Part
                    import MultiAxisSlicer as mas
                    doc = FreeCAD.newDocument("Headless")
                    part = doc.addObject("Part::Feature", "L")
                    part.Shape = Part.makeBox(20, 20, 60).fuse(
                        Part.makeBox(50, 20, 20, FreeCAD.Vector(20, 0, 40))).removeSplitter()
                    mas.make_slice(mas.make_decomposition(part), show_travel=True)
                    doc.recompute()
                    doc.saveAs({!r})
                """.format(path)))
            result = subprocess.run(["freecadcmd", script], capture_output=True, text=True,
                                    timeout=120)
            self.assertTrue(os.path.isfile(path), result.stdout + result.stderr)
            doc = FreeCAD.openDocument(path)
            try:
                process_events()
                layers, toolpath = doc.getObject("Layers"), doc.getObject("Toolpath")
                self.assertIsInstance(layers.ViewObject.Proxy, view_providers.ViewProviderLayers)
                self.assertIsInstance(toolpath.ViewObject.Proxy,
                                      view_providers.ViewProviderToolpath)
                self.assertEqual(layers.LayerCount, 55)
                self.assertGreater(toolpath.PathCounts[3], 0)
                self.check_colours(layers, toolpath)
            finally:
                FreeCAD.closeDocument(doc.Name)
        finally:
            shutil.rmtree(folder)


class TestMachineProgramCommands(unittest.TestCase):
    def setUp(self):
        FreeCADGui.activateWorkbench(WORKBENCH)
        (self.doc, self.part, self.decomposition, self.layers,
         self.toolpath) = MultiAxisSlicerTestSupport.sliced_l_block_document("MasGuiProgram")
        self.folder = tempfile.mkdtemp(prefix="mas_gui_gcode_")
        self.dialog = QtGui.QFileDialog.getSaveFileName
        FreeCADGui.Selection.clearSelection()
        process_events()

    def tearDown(self):
        QtGui.QFileDialog.getSaveFileName = self.dialog
        FreeCADGui.Selection.clearSelection()
        close_error_boxes()
        FreeCAD.closeDocument(self.doc.Name)
        shutil.rmtree(self.folder)
        process_events()

    def answer_save_dialog(self, path):
        """The next save dialog answers `path` ("" for Cancel) and records its suggestion."""
        asked = []

        def answer(parent, caption, suggestion, filters):
            asked.append(suggestion)
            return path, filters.split(";;")[0]

        QtGui.QFileDialog.getSaveFileName = answer
        return asked

    def test_toolbar_has_both_commands_with_icons(self):
        toolbar = FreeCADGui.getMainWindow().findChild(QtGui.QToolBar, TOOLBAR)
        actions = {a.text(): a for a in toolbar.actions()}
        for text in ("Machine program", "Export G-code..."):
            self.assertIn(text, actions)
            self.assertFalse(actions[text].icon().isNull(), text)

    def test_program_from_the_selected_toolpath_exported_and_undone(self):
        import MultiAxisSlicer.features as features

        self.doc.UndoMode = 1
        names = [o.Name for o in self.doc.Objects]
        self.assertFalse(FreeCADGui.Command.get(PROGRAM_COMMAND).isActive())
        FreeCADGui.Selection.addSelection(self.toolpath)
        self.assertTrue(FreeCADGui.Command.get(PROGRAM_COMMAND).isActive())
        self.assertFalse(FreeCADGui.Command.get(EXPORT_COMMAND).isActive())
        FreeCADGui.runCommand(PROGRAM_COMMAND)
        process_events()
        program_obj = self.doc.getObject("MachineProgram")
        self.assertIsNotNone(program_obj, "the command made no MachineProgram object")
        self.assertEqual(error_boxes(), [])
        self.assertTrue(program_obj.isValid(), program_obj.getStatusString())
        self.assertIs(program_obj.Layers, self.layers)
        self.assertEqual(list(program_obj.ARange), [-90.0, 0.0])
        self.assertTrue(program_obj.ViewObject.Proxy.getIcon().endswith("MachineProgram.svg"))
        self.assertTrue(os.path.isfile(program_obj.ViewObject.Proxy.getIcon()))
        self.assertEqual(program_obj.ViewObject.DrawStyle, "Dashed")
        save_screenshot(self, self.doc, "machine_program_l_block.png", see_through=False)

        FreeCADGui.Selection.clearSelection()
        FreeCADGui.Selection.addSelection(program_obj)
        self.assertTrue(FreeCADGui.Command.get(EXPORT_COMMAND).isActive())
        path = os.path.join(self.folder, "l.ngc")
        asked = self.answer_save_dialog(path)
        FreeCADGui.runCommand(EXPORT_COMMAND)
        process_events()
        # An unsaved document suggests the home folder.
        self.assertEqual(asked, [os.path.join(os.path.expanduser("~"), "MachineProgram.ngc")])
        self.assertEqual(error_boxes(), [])
        with open(path) as f:
            self.assertEqual(f.read(), features.machine_program(program_obj).text)
        self.answer_save_dialog("")  # Cancel writes nothing
        FreeCADGui.runCommand(EXPORT_COMMAND)
        process_events()
        self.assertEqual(os.listdir(self.folder), ["l.ngc"])
        self.assertNotIn("Export", " ".join(self.doc.UndoNames))  # exporting changes nothing

        self.doc.undo()
        process_events()
        self.assertEqual([o.Name for o in self.doc.Objects], names)

    def test_export_recomputes_a_program_whose_layers_changed(self):
        obj = mas.make_machine_program(self.layers)
        self.doc.recompute()
        lines = obj.LineCount
        self.layers.MaxLayer = 3.0  # not recomputed yet
        FreeCADGui.Selection.addSelection(obj)
        path = os.path.join(self.folder, "l.ngc")
        self.answer_save_dialog(path)
        FreeCADGui.runCommand(EXPORT_COMMAND)
        process_events()
        self.assertEqual(error_boxes(), [])
        self.assertNotIn("Touched", self.layers.State)
        self.assertLess(obj.LineCount, lines)
        with open(path) as f:
            self.assertEqual(len(f.read().splitlines()), obj.LineCount)

    def test_a_machine_that_cannot_reach_shows_its_message_and_exports_nothing(self):
        obj = mas.make_machine_program(self.layers, a_min=-45, a_max=45)
        self.doc.recompute()
        self.assertIn("Invalid", obj.State)
        FreeCADGui.Selection.addSelection(obj)
        path = os.path.join(self.folder, "l.ngc")
        asked = self.answer_save_dialog(path)
        FreeCADGui.runCommand(EXPORT_COMMAND)
        process_events()
        self.assertEqual(asked, [])  # refused before asking for a file
        boxes = error_boxes()
        self.assertEqual(len(boxes), 1)
        self.assertIn("beyond AMin and AMax -45 to 45", boxes[0].text())
        self.assertEqual(os.listdir(self.folder), [])


def wait_for_no_transaction(seconds=5.0):
    """Processes events until no transaction is open, or the time is up (a parameter panel
    closes its transaction by a timer once FreeCAD is done removing the edited object); returns
    the one still open, if any."""
    deadline = time.monotonic() + seconds
    while FreeCAD.getActiveTransaction() is not None and time.monotonic() < deadline:
        process_events()
        time.sleep(0.01)
    return FreeCAD.getActiveTransaction()


def task_buttons():
    """The task view's OK and Cancel buttons of the dialog shown now, and the parameter panel's
    own Apply: {name: button}."""
    import MultiAxisSlicerGui.parameter_panel as parameter_panel

    names = {QtGui.QDialogButtonBox.Ok: "ok", QtGui.QDialogButtonBox.Cancel: "cancel"}
    for box in FreeCADGui.getMainWindow().findChildren(QtGui.QDialogButtonBox):
        buttons = {names[b]: box.button(b) for b in names if box.button(b) is not None}
        if len(buttons) == 2 and all(b.isVisible() for b in buttons.values()):
            panel = parameter_panel.active_panel()
            if panel is not None and panel.form.apply.isVisible():
                buttons["apply"] = panel.form.apply
            return buttons
    return {}


class TestBuildPreviewCommand(unittest.TestCase):
    def setUp(self):
        FreeCADGui.activateWorkbench(WORKBENCH)
        (self.doc, self.part, self.decomposition, self.layers,
         self.toolpath) = MultiAxisSlicerTestSupport.sliced_l_block_document("MasGuiPreview")
        FreeCADGui.Selection.clearSelection()
        process_events()

    def tearDown(self):
        from MultiAxisSlicerGui import build_preview

        panel = build_preview.active_panel()
        if panel is not None:
            panel.reject()
        FreeCADGui.Selection.clearSelection()
        close_error_boxes()
        FreeCAD.closeDocument(self.doc.Name)
        process_events()

    @staticmethod
    def colours_of(preview):
        """The colours the view draws, rounded: each layer's, then the nozzle's."""
        return [tuple(round(x, 2) for x in c) for c in preview.ViewObject.Proxy.shown]

    def drawn_triangles(self, preview):
        """The triangles the view draws (its layers', the nozzle's and the plate's)."""
        from pivy import coin

        proxy = preview.ViewObject.Proxy
        count = 0
        for group in (proxy.layer_nodes, proxy.nozzle_node, proxy.plate_faces):
            for i in range(group.getNumChildren()):
                node = group.getChild(i)
                if isinstance(node, coin.SoSeparator):
                    count += node.getChild(1).coordIndex.getNum() // 4
        return count

    def test_the_command_makes_a_preview_and_its_panel_steps_through_the_build(self):
        import MultiAxisSlicer.features as features
        from MultiAxisSlicerGui import build_preview

        self.doc.UndoMode = 1
        names = [o.Name for o in self.doc.Objects]
        toolbar = FreeCADGui.getMainWindow().findChild(QtGui.QToolBar, TOOLBAR)
        texts = [a.text() for a in toolbar.actions()]
        # After Slice, before the machine program: what one looks at before writing G-code.
        self.assertEqual(texts.index("Build preview"), texts.index("Slice") + 1)
        self.assertEqual(texts.index("Machine program"), texts.index("Build preview") + 1)
        action = toolbar.actions()[texts.index("Build preview")]
        self.assertFalse(action.icon().isNull())
        menu = [m for m in FreeCADGui.getMainWindow().menuBar().actions() if m.text() == TOOLBAR]
        self.assertIn("Build preview", [a.text() for a in menu[0].menu().actions()])
        self.assertFalse(FreeCADGui.Command.get(PREVIEW_COMMAND).isActive())
        FreeCADGui.Selection.addSelection(self.toolpath)  # a Toolpath stands for its Layers
        self.assertTrue(FreeCADGui.Command.get(PREVIEW_COMMAND).isActive())
        FreeCADGui.runCommand(PREVIEW_COMMAND)
        process_events()
        preview = self.doc.getObject("BuildPreview")
        self.assertIsNotNone(preview, "the command made no BuildPreview object")
        self.assertEqual(error_boxes(), [])
        self.assertTrue(preview.isValid(), preview.getStatusString())
        self.assertIs(preview.Layers, self.layers)
        # It takes the place of the layers and the paths in the view.
        self.assertFalse(self.layers.ViewObject.Visibility)
        self.assertFalse(self.toolpath.ViewObject.Visibility)
        self.assertTrue(preview.ViewObject.Proxy.getIcon().endswith("BuildPreview.svg"))
        self.assertTrue(os.path.isfile(preview.ViewObject.Proxy.getIcon()))
        result = features.slice_result(self.layers)
        count = len(result.sequence)
        # The whole build, and its panel open on it.
        self.assertEqual((preview.StepCount, preview.ShownStep), (count, count))
        panel = build_preview.active_panel()
        self.assertIsNotNone(panel, "the panel did not open")
        self.assertIs(panel.obj, preview)
        self.assertEqual((panel.slider.minimum(), panel.slider.maximum()), (1, count))
        self.assertEqual(panel.spin.value(), count)
        self.assertTrue(panel.nozzle.isChecked())

        # A step of the arm's: the layers so far in their components' colours, the step's
        # yellow, the nozzle grey.
        arm = [i for i in result.sequence if result.layers[i].component == 1]
        step = list(result.sequence).index(arm[2]) + 1
        panel.spin.setValue(step)
        self.assertEqual((preview.Step, preview.ShownStep, preview.Layer), (step, step, arm[2]))
        self.assertEqual(panel.slider.value(), step)
        self.assertIn("Step {} of {}: layer {} of component 1".format(step, count, arm[2]),
                      panel.info.text())
        # Drawn: every layer in its component's colour, every second one of a component a shade
        # darker, the step's yellow, the nozzle grey; the triangles of every face.
        self.assertEqual(preview.ViewObject.TypeId, "Gui::ViewProviderPythonFeature")
        components = list(preview.ShownComponents)
        want, seen = [], {}
        for component in components[:-1]:
            colour = view_providers.component_colour(component)
            seen[component] = seen.get(component, -1) + 1
            want.append(colour if seen[component] % 2 == 0 else tuple(0.8 * x for x in colour))
        want += [(1.0, 0.85, 0.0), (0.75, 0.75, 0.78)]
        self.assertEqual(self.colours_of(preview), [tuple(round(x, 2) for x in c) for c in want])
        self.assertEqual(self.drawn_triangles(preview),
                         len(features.shape_triangles(preview.Shape)[1]))
        self.assertGreaterEqual(self.drawn_triangles(preview), 2 * len(preview.Shape.Faces))
        # The step's deposit paths, a line each, over its layer.
        proxy = preview.ViewObject.Proxy
        wires = preview.Shape.childShapes()[3].Wires
        self.assertGreater(len(wires), 0)
        self.assertEqual(proxy.path_lines.numVertices.getNum(), len(wires))
        self.assertEqual(sum(proxy.path_lines.numVertices[i] for i in range(len(wires))),
                         sum(len(w.OrderedVertexes) + w.isClosed() for w in wires))
        self.assertTrue(panel.paths.isChecked())
        panel.paths.setChecked(False)
        self.assertFalse(preview.ShowPaths)
        self.assertEqual(proxy.path_lines.numVertices.getNum(), 0)
        panel.paths.setChecked(True)
        self.assertEqual(proxy.path_lines.numVertices.getNum(), len(wires))
        # The build plate under it, see-through, in PlateColor: two triangles, on z = 0.
        plate = preview.Shape.childShapes()[5].Faces
        self.assertEqual(len(plate), 1)
        self.assertEqual(proxy.plate_faces.getNumChildren(), 1)
        drawn = proxy.plate_faces.getChild(0)
        self.assertEqual(drawn.getChild(1).coordIndex.getNum(), 2 * 4)
        corners = [drawn.getChild(0).point[i].getValue() for i in range(4)]
        self.assertEqual({round(c[2], 9) for c in corners}, {0.0})
        self.assertAlmostEqual(min(c[0] for c in corners), plate[0].BoundBox.XMin, places=4)
        self.assertAlmostEqual(max(c[1] for c in corners), plate[0].BoundBox.YMax, places=4)
        self.assertEqual(tuple(round(x, 2) for x in proxy.plate_colour.diffuseColor[0].getValue()),
                         tuple(round(x, 2) for x in preview.ViewObject.PlateColor[:3]))
        self.assertAlmostEqual(proxy.plate_colour.transparency[0],
                               view_providers.BUILD_PREVIEW_PLATE_TRANSPARENCY, places=6)
        self.assertTrue(panel.plate.isChecked())
        panel.plate.setChecked(False)
        self.assertFalse(preview.ShowPlate)
        self.assertEqual(proxy.plate_faces.getNumChildren(), 0)
        panel.plate.setChecked(True)
        self.assertEqual(proxy.plate_faces.getNumChildren(), 1)
        save_screenshot(self, self.doc, "build_preview_l_block.png", see_through=False)

        # Play walks on a step at a time and stops at the last.
        panel.slider.setValue(count - 1)
        self.assertEqual(preview.ShownStep, count - 1)
        panel.play.setChecked(True)
        self.assertTrue(panel.timer.isActive())
        panel.advance()
        self.assertEqual((preview.ShownStep, panel.spin.value()), (count, count))
        panel.advance()
        self.assertFalse(panel.play.isChecked())
        self.assertFalse(panel.timer.isActive())
        # The nozzle hidden: it is not drawn.
        panel.nozzle.setChecked(False)
        self.assertFalse(preview.ShowNozzle)
        self.assertEqual(preview.Shape.childShapes()[2].Faces, [])
        self.assertEqual(len(self.colours_of(preview)), count)
        self.assertEqual(preview.ViewObject.Proxy.nozzle_node.getNumChildren(), 0)
        # Stepping is not recorded for Undo: one step, the command's.
        self.assertEqual(self.doc.UndoNames[0], "Build preview")
        panel.reject()
        process_events()
        self.assertIsNone(build_preview.active_panel())
        self.assertIsNone(FreeCADGui.Control.activeDialog() or None)
        # Double-click opens it again.
        preview.ViewObject.Proxy.doubleClicked(preview.ViewObject)
        process_events()
        self.assertIsNotNone(build_preview.active_panel())
        self.assertEqual(build_preview.active_panel().spin.value(), count)
        # Undo removes the object, which ends its edit: the panel closes.
        panel = build_preview.active_panel()
        self.doc.undo()
        process_events()
        self.assertEqual([o.Name for o in self.doc.Objects], names)
        self.assertIsNone(build_preview.active_panel())
        self.assertIsNone(FreeCADGui.Control.activeDialog() or None)
        self.assertFalse(panel.go(1))  # a step asked of it then does nothing
        self.assertTrue(self.layers.ViewObject.Visibility)  # in view again
        self.assertTrue(self.toolpath.ViewObject.Visibility)

    def test_a_reopened_preview_is_drawn_as_saved(self):
        import MultiAxisSlicer.features as features

        folder = tempfile.mkdtemp(prefix="mas_gui_preview_")
        self.addCleanup(shutil.rmtree, folder)
        preview = mas.make_build_preview(self.layers, step=5)
        self.doc.recompute()
        drawn = self.colours_of(preview)
        self.assertEqual(len(drawn), 5 + 1)  # five layers and the nozzle
        path = os.path.join(folder, "preview.FCStd")
        self.doc.saveAs(path)
        FreeCAD.closeDocument(self.doc.Name)
        self.doc = FreeCAD.openDocument(path)
        process_events()
        preview = self.doc.getObject("BuildPreview")
        self.assertEqual(preview.ViewObject.TypeId, "Gui::ViewProviderPythonFeature")
        self.assertNotIn("Touched", preview.State)  # drawn from its saved Shape, nothing redone
        self.assertEqual(self.colours_of(preview), drawn)
        self.assertEqual(self.drawn_triangles(preview),
                         len(features.shape_triangles(preview.Shape)[1]))

    def test_a_document_made_without_the_gui_opens_as_the_commands_leave_it(self):
        """FreeCAD 0.20 opens every object of a document saved by freecadcmd hidden: the main
        job's document opened empty. Each of the workbench's objects is shown as its command
        leaves it: the preview, the program, the axis and the sections; not the layers and paths
        the preview shows, nor the components the layers show, nor the decomposition."""
        folder = tempfile.mkdtemp(prefix="mas_gui_headless_")
        self.addCleanup(shutil.rmtree, folder)
        path = os.path.join(folder, "headless.FCStd")
        script = os.path.join(folder, "make.py")
        with open(script, "w") as f:
            f.write(textwrap.dedent("""
                import FreeCAD
                import MultiAxisSlicer as mas
                import MultiAxisSlicerTestSupport as support
                doc, part, decomposition, layers, toolpath = support.sliced_l_block_document(
                    "Headless")
                mas.make_sections(part, doc=doc)
                mas.make_centroidal_axis(part, doc=doc)
                mas.make_machine_program(layers, doc=doc)
                mas.make_build_preview(layers, step=20, doc=doc)
                doc.recompute()
                doc.saveAs({!r})
            """.format(path)))
        result = subprocess.run(["freecadcmd", script], capture_output=True, text=True,
                                timeout=300)
        self.assertTrue(os.path.isfile(path), result.stdout + result.stderr)
        doc = FreeCAD.openDocument(path)
        self.addCleanup(FreeCAD.closeDocument, doc.Name)
        process_events()
        shown = {o.Name: o.ViewObject.Visibility for o in doc.Objects}
        self.assertEqual(shown, {
            "L": False, "Decomposition": False, "Component": False, "Component001": False,
            "Layers": False, "Toolpath": False, "Sections": True, "CentroidalAxis": True,
            "MachineProgram": True, "BuildPreview": True})
        preview = doc.getObject("BuildPreview")
        self.assertEqual(len(self.colours_of(preview)), 20 + 1)  # drawn from its saved Shape
        self.assertFalse(drawn_box(preview).isEmpty())

    def test_every_object_draws_something_shown_and_nothing_hidden(self):
        """FreeCAD hides an object by its display modes' switch: whatever else a view provider
        hangs in its root node (overlays) must follow (a hidden Layers object drew its holes to
        drill and its collisions)."""
        mas.make_sections(self.part, doc=self.doc)
        mas.make_centroidal_axis(self.part, doc=self.doc)
        mas.make_machine_program(self.layers, doc=self.doc)
        mas.make_build_preview(self.layers, step=10, doc=self.doc)
        self.layers.NozzleBodyDiameter = 100.0  # collisions to draw: a wide coaxial nozzle
        self.layers.NozzleMaxLean = 0.0
        self.doc.recompute()
        self.assertGreater(self.layers.CollidingLayers, 0)
        for obj in self.doc.Objects:
            obj.ViewObject.Visibility = True
            process_events()
            self.assertFalse(drawn_box(obj).isEmpty(), obj.Name)
            obj.ViewObject.Visibility = False
            process_events()
            self.assertTrue(drawn_box(obj).isEmpty(), obj.Name)

    def test_where_the_step_stands_on_nothing_shows_through_it(self):
        import MultiAxisSlicer.features as features

        # A cone widening 60 degrees from the vertical: its layers overhang.
        cone = self.doc.addObject("Part::Feature", "Cone")
        cone.Shape = Part.makeCone(5, 5 + 10 * math.sqrt(3), 10)
        self.doc.recompute()
        layers, _toolpath = mas.make_slice(mas.make_decomposition(cone), name="ConeLayers",
                                           toolpath_name="ConePaths")
        preview = mas.make_build_preview(layers)
        self.doc.recompute()
        self.assertGreater(preview.WorstStep, 0)
        preview.Step = preview.WorstStep
        self.doc.recompute()
        proxy = preview.ViewObject.Proxy
        self.assertEqual(proxy.unsupported_faces.getNumChildren(), 1)
        faces = proxy.unsupported_faces.getChild(0).getChild(1)
        self.assertEqual(faces.coordIndex.getNum() // 4,
                         len(features.shape_triangles(preview.Shape.childShapes()[4])[1]))
        self.assertEqual(tuple(round(x, 2) for x in proxy.unsupported_colour.diffuseColor[0]
                               .getValue()), view_providers.UNSUPPORTED_COLOUR)
        # The step's layer is see-through, the others not.
        materials = [proxy.layer_nodes.getChild(i) for i in range(
            0, proxy.layer_nodes.getNumChildren(), 2)]
        self.assertEqual([round(m.transparency[0], 2) for m in materials],
                         [0.0] * (len(materials) - 1) + [0.4])
        preview.Step = 1  # resting on the plate: nothing to show
        self.doc.recompute()
        self.assertEqual(proxy.unsupported_faces.getNumChildren(), 0)

    def test_a_colliding_layer_shows_its_nozzle_in_the_collision_colour(self):
        self.layers.NozzleBodyDiameter = 100.0
        self.layers.NozzleMaxLean = 0.0
        self.doc.recompute()
        self.assertGreater(self.layers.CollidingLayers, 0)
        layer = self.layers.CollisionLayers[0]
        preview = mas.make_build_preview(
            self.layers, step=list(self.layers.Sequence).index(layer) + 1)
        self.doc.recompute()
        self.assertTrue(preview.Collides)
        self.assertEqual(self.colours_of(preview)[-1], view_providers.COLLISION_COLOUR)
        preview.ViewObject.CollisionColor = (0.0, 1.0, 0.0)
        self.assertEqual(self.colours_of(preview)[-1], (0.0, 1.0, 0.0))
        from MultiAxisSlicerGui import build_preview

        self.assertTrue(build_preview.summary(preview).endswith("its nozzle meets the build "
                                                                "plate."))
        # The panel's buttons go from one colliding layer's step to the next; no layer
        # overhangs, so there is no worst one to go to.
        flagged = [k + 1 for k, i in enumerate(self.layers.Sequence)
                   if i in self.layers.CollisionLayers]
        self.assertEqual(list(preview.FlaggedSteps), flagged)
        build_preview.edit(preview)
        process_events()
        panel = build_preview.active_panel()
        panel.go(1)
        self.assertFalse(panel.previous.isEnabled())
        self.assertFalse(panel.worst.isEnabled())
        self.assertFalse(panel.go_worst())
        for want in flagged:
            self.assertTrue(panel.next.isEnabled())
            panel.next.click()
            self.assertEqual(preview.ShownStep, want)
            self.assertTrue(preview.Collides)
        self.assertFalse(panel.next.isEnabled())
        panel.previous.click()
        self.assertEqual(preview.ShownStep, flagged[-2])
        panel.reject()
        process_events()
        # Deleting the last preview of the layers shows them again; one of two, not yet.
        second = mas.make_build_preview(self.layers, name="Second")
        self.doc.recompute()
        self.layers.ViewObject.Visibility = False
        for obj in (preview, second):
            self.assertTrue(obj.ViewObject.Proxy.onDelete(obj.ViewObject, []))
            self.assertEqual(self.layers.ViewObject.Visibility, obj is second)
            self.doc.removeObject(obj.Name)


class TestParameterPanel(unittest.TestCase):
    """Double-clicking one of the workbench's objects edits its parameters in a task panel."""

    def setUp(self):
        import MultiAxisSlicer.features as features
        import MultiAxisSlicerGui.parameter_panel as parameter_panel

        self.features = features
        self.panels = parameter_panel
        FreeCADGui.activateWorkbench(WORKBENCH)
        (self.doc, self.part, self.decomposition, self.layers,
         self.toolpath) = MultiAxisSlicerTestSupport.sliced_l_block_document("MasGuiPanel")
        self.gui_doc = FreeCADGui.getDocument(self.doc.Name)
        process_events()

    def tearDown(self):
        if FreeCADGui.Control.activeDialog():
            self.press("cancel")
        close_error_boxes()
        FreeCAD.closeDocument(self.doc.Name)
        process_events()

    def open(self, obj):
        """Double-clicks `obj` (its view provider's handler, as the tree calls it)."""
        self.assertTrue(obj.ViewObject.Proxy.doubleClicked(obj.ViewObject))
        process_events()
        panel = self.panels.active_panel()
        self.assertIsNotNone(panel, "no panel for " + obj.Label)
        self.assertTrue(FreeCADGui.Control.activeDialog())
        return panel

    def press(self, name):
        buttons = task_buttons()
        self.assertIn(name, buttons, "no {} button in the task view".format(name))
        buttons[name].click()
        process_events()

    def applied(self, obj, prop, value):
        """Opens the panel of `obj`, sets the field of `prop` to `value` and presses Apply."""
        panel = self.open(obj)
        self.set_field(panel, prop, value)
        self.press("apply")
        return panel

    def set_field(self, panel, prop, value):
        widget = panel.field(prop).widget
        if isinstance(widget, QtGui.QAbstractSpinBox) and not isinstance(
                widget, (QtGui.QSpinBox, QtGui.QDoubleSpinBox)):
            widget.setProperty("rawValue", value)  # a Gui::QuantitySpinBox
        else:
            widget.setValue(value)

    def test_double_click_shows_the_layers_parameters_in_their_groups(self):
        panel = self.open(self.layers)
        titles = [b.title() for b in panel.form.groups.findChildren(QtGui.QGroupBox)]
        self.assertEqual(titles, ["Layers", "Paths", "Nozzle"])
        want = [p for _, props in self.features.parameters(self.layers) for p in props]
        self.assertEqual([f.prop for f in panel.fields], want)
        self.assertIn("NozzleMaxLean", want)
        self.assertNotIn("Decomposition", want)  # the link is the property editor's
        self.assertNotIn("LayerCount", want)  # a result
        for field in panel.fields:  # each shows the property's value
            value = getattr(self.layers, field.prop)
            if isinstance(value, str):
                self.assertEqual(field.read(), value)
            else:
                self.assertAlmostEqual(field.read(), getattr(value, "Value", value), 4,
                                       msg=field.prop)
            self.assertFalse(field.changed(), field.prop)
        self.assertEqual(panel.field("MaxLayer").widget.property("unit"), "mm")
        self.assertEqual(panel.field("NozzleConeAngle").widget.property("unit"), "°")
        self.assertEqual(panel.field("Infill").read(), self.layers.Infill)
        self.assertTrue(panel.field("CheckPlate").read())
        self.assertIn("{} layers in 2 component(s)".format(self.layers.LayerCount),
                      panel.form.result.text())
        self.assertEqual(self.gui_doc.getInEdit().Object, self.layers)

    def test_the_layers_of_a_mesh_offer_no_deflection_nor_holes_to_fill(self):
        # A mesh is not tessellated and has no BREP holes: the two would only fail. SplitMesh and
        # AvoidCollisions are a mesh's only (a Decomposition is sliced as it is).
        import Mesh

        scan = self.doc.addObject("Mesh::Feature", "Scan")
        scan.Mesh = Mesh.Mesh(self.part.Shape.tessellate(0.01))
        layers, toolpath = mas.make_slice(scan, name="MeshLayers", toolpath_name="MeshPaths")
        self.doc.recompute()
        self.assertIsNone(self.features.failure(toolpath))
        panel = self.open(layers)
        props = [f.prop for f in panel.fields]
        of_solid = [p for _, group in self.features.parameters(self.layers) for p in group]
        self.assertNotIn("SplitMesh", of_solid)
        self.assertNotIn("AvoidCollisions", of_solid)
        want = [p for p in of_solid if p not in ("Deflection", "FillHoles")]
        self.assertEqual([p for p in props if p not in ("SplitMesh", "AvoidCollisions")], want)
        self.assertIn("SplitMesh", props)
        self.assertIn("AvoidCollisions", props)
        self.assertIn("MaxLayer", props)
        count = layers.LayerCount
        self.set_field(panel, "MaxLayer", layers.MaxLayer.Value / 2)
        self.press("ok")
        self.assertIsNone(self.features.failure(layers))
        self.assertGreater(layers.LayerCount, count)

    def test_apply_recomputes_the_layers_and_their_paths_and_ok_is_one_undo_step(self):
        before = (self.layers.MaxLayer.Value, self.layers.LayerCount, self.toolpath.PathCount)
        program = mas.make_machine_program(self.layers)
        self.doc.recompute()
        lines = program.LineCount
        undo_steps = self.doc.UndoCount
        panel = self.open(self.layers)
        self.set_field(panel, "MaxLayer", before[0] / 2)
        self.set_field(panel, "MinLayer", self.layers.MinLayer.Value / 2)
        self.press("apply")
        self.assertEqual(self.layers.MaxLayer.Value, before[0] / 2)
        self.assertGreater(self.layers.LayerCount, before[1])
        for obj in (self.layers, self.toolpath, program):  # what depends on it follows
            self.assertIsNone(self.features.failure(obj), obj.Label)
        self.assertGreater(self.toolpath.PathCount, before[2])
        self.assertGreater(program.LineCount, lines)
        self.assertIn("{} layers".format(self.layers.LayerCount), panel.form.result.text())
        self.assertIs(self.panels.active_panel(), panel)  # Apply keeps it open
        self.press("ok")
        self.assertIsNone(self.panels.active_panel())
        self.assertFalse(FreeCADGui.Control.activeDialog())
        self.assertIsNone(self.gui_doc.getInEdit())
        self.assertEqual(self.doc.UndoCount, undo_steps + 1)
        self.assertEqual(self.doc.UndoNames[0], "Edit 'Layers'")
        self.doc.undo()
        self.assertEqual(self.layers.MaxLayer.Value, before[0])
        self.assertEqual(self.layers.LayerCount, before[1])
        self.assertEqual(self.toolpath.PathCount, before[2])
        self.assertEqual(program.LineCount, lines)

    def test_only_the_fields_the_user_changed_are_written(self):
        # Values finer than the fields show, and one beyond their usual range.
        self.layers.MaxVolumeDifference = 0.123456
        self.layers.Deflection = 0.01234
        program = mas.make_machine_program(self.layers, c_min=-1e9, c_max=1e9)
        self.doc.recompute()
        panel = self.open(self.layers)
        self.set_field(panel, "BeadWidth", self.layers.BeadWidth.Value * 1.5)
        self.press("ok")
        self.assertIsNone(self.features.failure(self.layers))
        self.assertEqual(self.layers.MaxVolumeDifference, 0.123456)
        self.assertEqual(self.layers.Deflection.Value, 0.01234)
        panel = self.open(program)
        self.assertEqual(panel.field("CMin").read(), -1e9)  # shown as it is, not clipped
        self.set_field(panel, "Feed", program.Feed * 2)
        self.press("ok")
        self.assertIsNone(self.features.failure(program))
        self.assertEqual((program.CMin, program.CMax), (-1e9, 1e9))

    def test_cancel_puts_everything_back_without_computing_again(self):
        before = {p: getattr(self.layers, p) for p in ("BeadWidth", "LayerCount", "LayerOrigins",
                                                       "Shape")}
        paths = self.toolpath.PathCount
        result = self.features.slice_result(self.layers)
        undo_steps = self.doc.UndoCount
        panel = self.open(self.toolpath)  # the paths' parameters are the Layers object's
        self.assertIs(panel.obj, self.layers)
        self.assertIn("Toolpath", panel.form.intro.text())
        self.set_field(panel, "BeadWidth", before["BeadWidth"].Value * 2)
        self.press("apply")
        self.assertLess(self.toolpath.PathCount, paths)
        self.assertIsNot(self.features.slice_result(self.layers), result)
        self.press("cancel")
        self.assertIsNone(self.panels.active_panel())
        self.assertEqual(self.layers.BeadWidth, before["BeadWidth"])
        self.assertEqual(self.layers.LayerCount, before["LayerCount"])
        self.assertEqual(self.layers.LayerOrigins, before["LayerOrigins"])
        self.assertEqual(len(self.layers.Shape.Edges), len(before["Shape"].Edges))
        box = lambda b: (b.XMin, b.YMin, b.ZMin, b.XMax, b.YMax, b.ZMax)
        self.assertEqual(box(self.layers.Shape.BoundBox), box(before["Shape"].BoundBox))
        self.assertEqual(self.toolpath.PathCount, paths)
        for obj in (self.layers, self.toolpath):
            self.assertIsNone(self.features.failure(obj), obj.Label)
        # The slicing from before the edit is what the objects hold again, not a new one.
        self.assertIs(self.features.slice_result(self.layers), result)
        self.assertEqual(self.doc.UndoCount, undo_steps)

    def test_a_refused_value_is_named_in_the_panel_and_ok_keeps_it_open(self):
        panel = self.open(self.layers)
        self.set_field(panel, "MinLayer", self.layers.MaxLayer.Value + 1)
        self.press("ok")
        self.assertIs(self.panels.active_panel(), panel)
        text = panel.form.result.text()
        self.assertIn("MinLayer", text)
        self.assertIn("MaxLayer", text)
        self.assertIn("color", panel.form.result.styleSheet())
        self.press("cancel")
        self.assertIsNone(self.features.failure(self.layers))
        self.assertIsNone(self.features.failure(self.toolpath))

    def test_a_tilt_the_machine_cannot_reach_is_named_in_the_program_panel(self):
        program = mas.make_machine_program(self.layers)
        self.doc.recompute()
        panel = self.open(program)
        self.assertEqual([f.prop for f in panel.fields],
                         ["AMin", "AMax", "CMin", "CMax", "Feed", "ReferenceThickness",
                          "MaxFeedRatio", "Clearance", "DepositOutput", "WorkOffsetX",
                          "WorkOffsetY", "WorkOffsetZ", "RotPointX", "RotPointY", "RotPointZ",
                          "RotOffsetY", "RotOffsetZ", "ToolLength", "CheckTravel", "XMin", "XMax",
                          "YMin", "YMax", "ZMin", "ZMax"])
        titles = [b.title() for b in panel.form.groups.findChildren(QtGui.QGroupBox)]
        self.assertEqual(titles, ["Machine", "Machine travel"])
        self.assertIn("{} lines".format(program.LineCount), panel.form.result.text())
        self.assertIn("Machine: X {:.4g} to {:.4g}, ".format(*program.XRange),
                      panel.form.result.text())
        self.set_field(panel, "AMin", -45)
        self.set_field(panel, "AMax", 45)
        self.press("apply")
        self.assertIn("beyond AMin and AMax -45 to 45", panel.form.result.text())
        self.press("cancel")
        self.assertIsNone(self.features.failure(program))
        self.assertEqual(program.AMin.Value, mas.MACHINE_DEFAULTS["a_min"])
        # The travel checked: a ZMax under the part's top is named.
        panel = self.open(program)
        panel.field("CheckTravel").widget.setChecked(True)
        self.set_field(panel, "ZMax", program.ZRange[1] - 1)
        self.press("apply")
        self.assertIn("it takes Z from", panel.form.result.text())
        self.press("cancel")
        self.assertIsNone(self.features.failure(program))
        self.assertFalse(program.CheckTravel)
        # Limits a script left infinite (none) stay none through the panel.
        scripted = mas.make_machine_program(self.layers, name="Scripted",
                                            z_max=program.ZRange[1] + 1)
        self.doc.recompute()
        panel = self.open(scripted)
        self.set_field(panel, "Feed", 700)
        self.press("ok")
        self.assertEqual(scripted.Feed, 700)
        self.assertLessEqual(scripted.XMin.Value, -1e300)
        self.assertGreaterEqual(scripted.YMax.Value, 1e300)
        self.assertIsNone(self.features.failure(scripted))

    def test_the_axis_sections_and_decomposition_show_their_own_parameters(self):
        axis = mas.make_centroidal_axis(self.part)
        sections = mas.make_sections(self.part)
        self.doc.recompute()
        for obj, props, figure in (
                (axis, ["Step", "DistanceThreshold", "Epsilon", "BreakAngle", "Frame",
                        "Deflection"],
                 "frame 0°."),
                (sections, ["Normal", "Step", "Deflection"], "sections"),
                (self.decomposition, ["Step", "Deflection", "FaceAngle", "ConcaveAngle",
                                      "SectionPlaneFallback", "MinComponentHeight", "MaxTilt"],
                 "2 sub-component(s)")):
            panel = self.open(obj)
            self.assertEqual([f.prop for f in panel.fields], props)
            self.assertIn(figure, panel.form.result.text())
            self.press("cancel")
        panel = self.open(sections)
        panel.field("Normal").boxes[0].setValue(1.0)
        panel.field("Normal").boxes[2].setValue(0.0)
        count = sections.SectionCount
        self.press("ok")
        self.assertEqual(sections.Normal, FreeCAD.Vector(1, 0, 0))
        self.assertNotEqual(sections.SectionCount, count)  # the L is 70 long in X, 60 in Z

    def test_a_decomposition_edit_brings_its_components_and_cancel_takes_them_back(self):
        names = [c.Name for c in self.features.components_of(self.decomposition)]
        self.assertEqual(len(names), 2)
        panel = self.open(self.decomposition)
        self.set_field(panel, "MinComponentHeight", 100.0)  # more than the arm reaches
        self.press("apply")
        wait_for_components(self.decomposition, 1)
        self.assertEqual(self.decomposition.ComponentCount, 1)
        self.assertEqual(len(self.features.components_of(self.decomposition)), 1)
        self.assertEqual(len(self.layers.ComponentLayerCounts), 1)  # sliced as it is now
        self.assertIn("1 sub-component(s)", panel.form.result.text())
        self.press("cancel")
        wait_for_components(self.decomposition, 2)
        self.assertEqual([c.Name for c in self.features.components_of(self.decomposition)],
                         names)
        self.assertEqual(len(self.layers.ComponentLayerCounts), 2)
        for obj in [self.decomposition, self.layers, self.toolpath] + [
                self.doc.getObject(n) for n in names]:
            self.assertIsNone(self.features.failure(obj), obj.Label)

    def test_an_edit_ended_otherwise_is_undone(self):
        max_layer = self.layers.MaxLayer.Value
        undo_steps = self.doc.UndoCount
        panel = self.applied(self.layers, "MaxLayer", max_layer / 2)
        self.gui_doc.resetEdit()  # as a script, or the document closing, ends it
        process_events()
        self.assertIsNone(self.panels.active_panel())
        self.assertFalse(FreeCADGui.Control.activeDialog())
        self.assertEqual(self.layers.MaxLayer.Value, max_layer)
        self.assertFalse(self.doc.HasPendingTransaction)
        self.assertEqual(self.doc.UndoCount, undo_steps)
        self.open(self.layers)  # the document closes with the panel open: no error
        FreeCAD.closeDocument(self.doc.Name)
        process_events()
        self.assertIsNone(self.panels.active_panel())
        self.assertFalse(FreeCADGui.Control.activeDialog())
        self.doc = FreeCAD.newDocument("MasGuiPanel")  # for tearDown

    def test_a_double_click_elsewhere_keeps_the_edit_open(self):
        max_layer = self.layers.MaxLayer.Value
        panel = self.applied(self.layers, "MaxLayer", max_layer / 2)
        # FreeCAD's setEdit would end the open edit first, undoing what was applied.
        self.assertTrue(self.toolpath.ViewObject.Proxy.doubleClicked(self.toolpath.ViewObject))
        self.assertTrue(self.decomposition.ViewObject.Proxy.doubleClicked(
            self.decomposition.ViewObject))
        process_events()
        self.assertIs(self.panels.active_panel(), panel)
        self.assertEqual(self.layers.MaxLayer.Value, max_layer / 2)
        boxes = error_boxes()
        # The Toolpath's panel is this one: no message; the decomposition's is another.
        self.assertEqual(len(boxes), 1)
        self.assertIn("Finish the task open in the task view", boxes[0].text())
        self.assertIn("'Decomposition'", boxes[0].text())
        self.press("ok")
        self.assertEqual(self.layers.MaxLayer.Value, max_layer / 2)

    def test_every_field_shows_whole_in_a_narrow_combo_view(self):
        main = FreeCADGui.getMainWindow()
        dock = next(d for d in main.findChildren(QtGui.QDockWidget)
                    if d.objectName() == "Combo View")
        main.resizeDocks([dock], [250], QtCore.Qt.Horizontal)
        process_events()
        sections = mas.make_sections(self.part)  # a vector field too
        self.doc.recompute()
        for obj in (self.layers, sections):
            panel = self.open(obj)
            process_events()
            widgets = [panel.form.apply] + list(task_buttons().values())
            for field in panel.fields:
                widgets += field.boxes if hasattr(field, "boxes") else [field.widget]
                for text in field.widget.findChildren(QtGui.QLineEdit):  # its value fits
                    self.assertLessEqual(text.fontMetrics().horizontalAdvance(text.text()),
                                         text.width(), field.prop)
            view = next(a for a in main.findChildren(QtGui.QScrollArea)
                        if a.isVisible() and a.isAncestorOf(panel.form)).viewport()
            edge = view.mapToGlobal(QtCore.QPoint(view.width(), 0)).x()
            for widget in widgets:  # not cut off by the task view's right-hand edge
                self.assertLessEqual(widget.mapToGlobal(QtCore.QPoint(widget.width(), 0)).x(),
                                     edge, widget.objectName() or widget.text())
            self.press("cancel")

    def test_undo_with_the_panel_open_takes_back_what_was_applied_and_closes_it(self):
        before = (self.layers.MaxLayer.Value, self.layers.LayerCount, self.toolpath.PathCount)
        result = self.features.slice_result(self.layers)
        undo_steps = self.doc.UndoCount
        panel = self.applied(self.layers, "MaxLayer", before[0] / 2)
        self.assertGreater(self.layers.LayerCount, before[1])
        FreeCADGui.runCommand("Std_Undo")  # Ctrl+Z, the panel open
        process_events()
        # The fields would no longer show what the properties hold, and nothing would record
        # what Apply or OK did next: the panel is closed.
        self.assertIsNone(self.panels.active_panel())
        self.assertFalse(FreeCADGui.Control.activeDialog())
        self.assertIsNone(self.gui_doc.getInEdit())
        self.assertIsNone(FreeCAD.getActiveTransaction())
        self.assertEqual((self.layers.MaxLayer.Value, self.layers.LayerCount,
                          self.toolpath.PathCount), before)
        self.assertIs(self.features.slice_result(self.layers), result)  # not computed again
        for obj in (self.layers, self.toolpath):
            self.assertEqual(obj.State, ["Up-to-date"], obj.Label)
        self.assertEqual(self.doc.UndoCount, undo_steps)
        self.assertEqual(self.doc.RedoNames[0], "Edit 'Layers'")

    def test_an_undo_that_removes_the_edited_object_leaves_no_transaction_open(self):
        self.doc.openTransaction("Make program")
        program = mas.make_machine_program(self.layers)
        self.doc.commitTransaction()
        self.doc.recompute()
        name = program.Name
        self.open(program)
        FreeCADGui.runCommand("Std_Undo")  # takes the program away, its panel open
        process_events()
        self.assertIsNone(self.doc.getObject(name))
        self.assertIsNone(self.panels.active_panel())
        self.assertFalse(FreeCADGui.Control.activeDialog())
        self.assertIsNone(wait_for_no_transaction())  # nothing done later goes into it
        self.assertEqual(list(self.doc.RedoNames), ["Make program"])

    def test_a_script_removing_the_edited_object_keeps_the_removal(self):
        max_layer = self.layers.MaxLayer.Value
        self.applied(self.layers, "MaxLayer", max_layer / 2)
        self.doc.removeObject(self.toolpath.Name)
        self.doc.removeObject(self.layers.Name)  # ends the edit
        process_events()
        self.assertIsNone(self.panels.active_panel())
        self.assertIsNone(wait_for_no_transaction())
        self.assertEqual((self.doc.getObject("Layers"), self.doc.getObject("Toolpath")),
                         (None, None))  # not brought back by an abort
        self.assertEqual(self.doc.UndoNames[0], "Edit 'Layers'")
        self.doc.undo()
        self.assertEqual(self.doc.getObject("Layers").MaxLayer.Value, max_layer)

    def test_another_edit_beginning_keeps_what_was_applied_and_its_own_transaction(self):
        max_layer = self.layers.MaxLayer.Value
        undo_steps = self.doc.UndoCount
        panel = self.applied(self.layers, "MaxLayer", max_layer / 2)
        # As a double-click on the part in the tree does: FreeCAD opens the part's edit
        # transaction (which commits the panel's), then ends the panel's edit.
        FreeCAD.setActiveTransaction("Edit L")
        self.layers.ViewObject.Proxy.unsetEdit(self.layers.ViewObject, 0)
        process_events()
        self.assertIsNone(self.panels.active_panel())
        self.assertFalse(FreeCADGui.Control.activeDialog())
        self.assertEqual(self.layers.MaxLayer.Value, max_layer / 2)
        self.assertEqual(FreeCAD.getActiveTransaction()[0], "Edit L")  # not aborted
        self.part.Label = "Moved L"
        FreeCAD.closeActiveTransaction()
        self.gui_doc.resetEdit()
        self.assertEqual(list(self.doc.UndoNames[:2]), ["Edit L", "Edit 'Layers'"])
        self.assertEqual(self.doc.UndoCount, undo_steps + 2)
        self.doc.undo()
        self.doc.undo()
        self.assertEqual((self.part.Label, self.layers.MaxLayer.Value), ("L", max_layer))

    def test_a_part_edit_keeps_what_was_applied_and_a_sketch_edit_undoes_it(self):
        max_layer = self.layers.MaxLayer.Value
        sketch = self.doc.addObject("Sketcher::SketchObject", "Sketch")
        self.doc.recompute()

        def end_other_edit():
            self.gui_doc.resetEdit()
            process_events()
            if FreeCADGui.Control.activeDialog():
                FreeCADGui.Control.closeDialog()
            process_events()

        self.applied(self.layers, "MaxLayer", max_layer / 2)
        # The part's placement edit opens its own undo step first: the panel's is committed.
        self.assertTrue(self.part.ViewObject.doubleClicked())
        process_events()
        self.assertIsNone(self.panels.active_panel())
        self.assertEqual(self.layers.MaxLayer.Value, max_layer / 2)
        self.assertEqual(self.doc.UndoNames[0], "Edit 'Layers'")
        end_other_edit()
        self.applied(self.layers, "MaxLayer", max_layer / 4)
        # A sketch's edit joins the panel's transaction, and ends the panel's edit in it: undone.
        self.assertTrue(sketch.ViewObject.doubleClicked())
        process_events()
        self.assertIsNone(self.panels.active_panel())
        self.assertEqual(self.layers.MaxLayer.Value, max_layer / 2)
        end_other_edit()
        self.assertIsNone(FreeCAD.getActiveTransaction())

    def test_a_command_run_with_the_panel_open_keeps_what_was_applied_before_it(self):
        import PartGui  # noqa: F401 (Part_Box)

        max_layer = self.layers.MaxLayer.Value
        panel = self.applied(self.layers, "MaxLayer", max_layer / 2)
        applied = self.features.slice_result(self.layers)
        FreeCADGui.runCommand("Part_Box")  # its undo step commits the panel's edit
        process_events()
        self.assertIs(self.panels.active_panel(), panel)
        self.set_field(panel, "MaxLayer", max_layer / 4)
        self.press("apply")  # recorded: a new edit
        self.press("cancel")
        self.assertEqual(self.layers.MaxLayer.Value, max_layer / 2)
        self.assertIs(self.features.slice_result(self.layers), applied)
        self.assertIsNone(FreeCAD.getActiveTransaction())
        self.assertEqual(self.doc.UndoNames[1], "Edit 'Layers'")  # under the box's
        self.doc.undo()
        self.doc.undo()
        self.assertEqual(self.layers.MaxLayer.Value, max_layer)
        self.assertIsNone(self.doc.getObject("Box"))

    def test_undo_of_a_later_step_keeps_what_was_applied_and_its_results(self):
        import PartGui  # noqa: F401 (Part_Box)

        max_layer = self.layers.MaxLayer.Value
        self.applied(self.layers, "MaxLayer", max_layer / 2)
        applied = self.features.slice_result(self.layers)
        FreeCADGui.runCommand("Part_Box")
        process_events()
        FreeCADGui.runCommand("Std_Undo")  # takes the box back, not the edit
        process_events()
        self.assertIsNone(self.panels.active_panel())
        self.assertIsNone(self.doc.getObject("Box"))
        self.assertEqual(self.layers.MaxLayer.Value, max_layer / 2)
        self.assertIs(self.features.slice_result(self.layers), applied)  # not the old one

    def test_a_panel_closed_by_a_script_leaves_the_next_task_alone(self):
        self.doc.openTransaction("Rename")
        self.part.Label = "Renamed"
        self.doc.commitTransaction()
        self.open(self.layers)
        FreeCADGui.Control.closeDialog()  # neither OK nor Cancel
        process_events()

        class OtherTask:  # another add-on's
            def __init__(self):
                self.form = QtGui.QLabel("another task")
                self.rejected = False

            def reject(self):
                self.rejected = True
                FreeCADGui.Control.closeDialog()
                return True

        other = OtherTask()
        FreeCADGui.Control.showDialog(other)
        process_events()
        FreeCADGui.runCommand("Std_Undo")  # would end the closed panel's edit
        process_events()
        self.assertTrue(FreeCADGui.Control.activeDialog())  # the other task stays
        self.assertEqual(self.part.Label, "L")
        self.assertTrue(self.decomposition.ViewObject.Proxy.doubleClicked(
            self.decomposition.ViewObject))  # says to finish the other task first
        process_events()
        self.assertTrue(FreeCADGui.Control.activeDialog())
        self.assertIsNone(self.panels.active_panel())
        self.press("cancel")
        self.assertTrue(other.rejected)

    def test_a_dialog_closed_by_a_script_is_cancelled_at_the_next_edit(self):
        max_layer = self.layers.MaxLayer.Value
        panel = self.applied(self.layers, "MaxLayer", max_layer / 2)
        FreeCADGui.Control.closeDialog()  # neither OK nor Cancel
        process_events()
        panel = self.open(self.decomposition)  # no task is open: no "finish it first"
        self.assertIs(panel.obj, self.decomposition)
        self.assertEqual(self.layers.MaxLayer.Value, max_layer)
        self.assertIsNone(self.features.failure(self.layers))
        self.press("cancel")
        self.assertFalse(self.doc.HasPendingTransaction)

    def test_fields_show_what_the_properties_hold_after_apply(self):
        self.layers.setExpression("MaxLayer", "MinLayer * 4")
        self.doc.recompute()
        panel = self.open(self.layers)
        self.set_field(panel, "MinLayer", self.layers.MinLayer.Value / 2)
        self.press("apply")
        self.assertEqual(panel.field("MaxLayer").read(), self.layers.MaxLayer.Value)
        self.assertFalse([f.prop for f in panel.fields if f.changed()])  # none written again
        # An angle property keeps its value within a turn: the field does too, rather than
        # showing 400 degrees for the 360 the property would hold.
        field = panel.field("RasterAngle")
        self.assertEqual((field.widget.property("minimum"), field.widget.property("maximum")),
                         (-360.0, 360.0))
        self.set_field(panel, "RasterAngle", 400.0)
        self.press("apply")
        self.assertEqual(field.read(), self.layers.RasterAngle.Value)

    def test_a_vector_keeps_the_coordinates_left_alone_as_they_were(self):
        sections = mas.make_sections(self.part)
        sections.Normal = FreeCAD.Vector(0.123456, 0.0, 1.0)
        self.doc.recompute()
        panel = self.open(sections)
        panel.field("Normal").boxes[1].setValue(0.5)
        self.press("ok")
        self.assertEqual(tuple(sections.Normal), (0.123456, 0.5, 1.0))

    def test_cancel_leaves_an_object_changed_before_as_it_was(self):
        # Changed in the property editor, not recomputed: Cancel neither computes nor records it.
        self.layers.MaxLayer = self.layers.MaxLayer.Value / 2
        count, undo_steps = self.layers.LayerCount, self.doc.UndoCount
        self.open(self.layers)
        self.press("cancel")
        self.assertEqual(self.layers.LayerCount, count)
        self.assertIn("Touched", self.layers.State)
        self.assertEqual(self.doc.UndoCount, undo_steps)
        self.assertFalse(self.doc.HasPendingTransaction)

    def test_ok_on_a_decomposition_is_one_undo_step_with_its_components(self):
        names = [c.Name for c in self.features.components_of(self.decomposition)]
        undo_steps = self.doc.UndoCount
        panel = self.open(self.decomposition)
        self.set_field(panel, "MinComponentHeight", 100.0)
        self.press("ok")
        wait_for_components(self.decomposition, 1, seconds=1.0)  # no timer adds a step
        self.assertEqual(len(self.features.components_of(self.decomposition)), 1)
        self.assertEqual(self.doc.UndoCount, undo_steps + 1)
        self.assertEqual(self.doc.UndoNames[0], "Edit 'Decomposition'")
        self.doc.undo()
        process_events()
        self.assertEqual(self.decomposition.ComponentCount, 2)
        self.assertEqual([c.Name for c in self.features.components_of(self.decomposition)],
                         names)

    def test_a_parameter_set_by_an_expression_is_not_edited_here(self):
        self.layers.setExpression("MaxLayer", "MinLayer * 4")
        self.doc.recompute()
        panel = self.open(self.layers)
        field = panel.field("MaxLayer")
        self.assertFalse(field.widget.isEnabled())
        self.assertIn("MinLayer * 4", field.widget.toolTip())
        self.assertTrue(panel.field("MinLayer").widget.isEnabled())
        self.press("cancel")
        sections = mas.make_sections(self.part)
        sections.setExpression("Normal.x", "0.5")  # one coordinate
        self.doc.recompute()
        panel = self.open(sections)
        self.assertFalse(panel.field("Normal").widget.isEnabled())
        self.assertIn("Normal.x = 0.5", panel.field("Normal").widget.toolTip())
        self.assertTrue(panel.field("Step").widget.isEnabled())

    def test_context_menu_edits_the_parameters(self):
        menu = QtGui.QMenu()
        self.layers.ViewObject.Proxy.setupContextMenu(self.layers.ViewObject, menu)
        actions = [a for a in menu.actions() if a.text() == "Edit parameters..."]
        self.assertEqual(len(actions), 1)
        actions[0].trigger()
        process_events()
        self.assertIs(self.panels.active_panel().obj, self.layers)
        # A second panel while one is open is refused with a message, not stacked.
        program = mas.make_machine_program(self.layers)
        self.doc.recompute()
        self.assertFalse(self.panels.open_panel(program))
        self.assertIs(self.panels.active_panel().obj, self.layers)


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
