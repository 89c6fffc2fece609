# SPDX-License-Identifier: LGPL-2.1-or-later
"""Workbench commands. Errors reach the user as a message, never as a traceback."""

import FreeCAD
import FreeCADGui

import MultiAxisSlicer as mas
import MultiAxisSlicerGui
import MultiAxisSlicerGui.progress

MultiAxisSlicerGui.progress.install()  # the commands' recomputes show progress and can be cancelled


def _selected_part():
    """The one selected object if it has a shape or a mesh (a link to a mesh object too), else
    None."""
    import MultiAxisSlicer.features as features

    return _selected_one(lambda o: o.isDerivedFrom("Mesh::Feature") or hasattr(o, "Shape")
                         or features.is_mesh_part(o))


# This workbench's results, which are no part to work on: their type -> what they are, in words.
_RESULTS = {
    "MultiAxisSlicer::Sections": "a Sections object (cross-sections)",
    "MultiAxisSlicer::CentroidalAxis": "a CentroidalAxis object",
    "MultiAxisSlicer::Decomposition": "a Decomposition object",
    "MultiAxisSlicer::Layers": "a Layers object",
    "MultiAxisSlicer::Toolpath": "a Toolpath object",
    "MultiAxisSlicer::MachineProgram": "a MachineProgram object (G-code)",
    "MultiAxisSlicer::BuildPreview": "a BuildPreview object",
}


def _part_problem(source, split=False):
    """None when the selected `source` can be the part a command works on; else why not, naming
    what to select. `split`: the command decomposes, which needs a BREP solid. A selection that
    can never work (a sketch, a lone face, two solids apart, a mesh to split, one of this
    workbench's results) is so refused before anything is made: the command used to leave an
    object failing for good."""
    kind = getattr(getattr(source, "Proxy", None), "Type", None)
    if kind in _RESULTS:
        return "'{}' is {}, not a part: select the solid or mesh it was made from.".format(
            source.Label, _RESULTS[kind])
    # A wait cursor and the status bar while it is checked: a scanned mesh of a million facets
    # takes seconds to reach the engine and be checked closed.
    with _Busy() as busy:
        busy.stage("Multi-Axis Slicer: checking '{}'...".format(source.Label))
        return _model_problem(source, split)


def _model_problem(source, split):
    """_part_problem() past its check for this workbench's results."""
    if "Touched" in source.State or "Invalid" in source.State:
        source.recompute(True)  # checked as it will be used (a new Part::Box has no shape yet)
        if "Invalid" in source.State:
            return "'{}' failed to recompute: {}".format(source.Label, source.getStatusString())
    try:
        model, part, what = mas._model(source)
        if model == "mesh":
            if split:
                return ("'{}' is a mesh: decomposing splits a BREP solid into solids. Make a "
                        "solid of it first (Part > Create shape from mesh, then Part > Convert to "
                        "solid) and select that, or slice the mesh (Slice), which splits it at "
                        "section planes.".format(source.Label))
            mas._require_engine().make_closed(part, what)
        else:
            part.single_solid(what)
    except (mas.EngineError, ValueError) as error:  # it names the object: "'Part': not a solid
        return str(error)  # (...)", "'Array' is 3 copies of the mesh 'Scan' (a link array) ..."
    return None


def _recompute_new(doc, before, also=()):
    """Recomputes the objects not in `before` (names), the objects `also`, and what they depend on;
    nothing else: a command computes its own objects. (A whole-document recompute also ran every
    other touched object, such as Layers whose recompute the user had cancelled: its progress
    dialog came up in the middle of an unrelated command, whose work its Cancel then undid.)"""
    objects = [o for o in doc.Objects if o.Name not in before] + list(also)
    if objects:
        doc.recompute(objects)


def _visibility(doc):
    """{object name: visible} of the document's objects, to restore after a cancel."""
    return {o.Name: o.ViewObject.Visibility for o in doc.Objects if o.ViewObject is not None}


def _undo_cancelled(doc, transaction, source, visibility):
    """The user cancelled the command's computation: nothing it made stays (the open transaction
    is aborted), the objects are shown as they were (`visibility`, from _visibility()), and the
    status bar says so; no error box."""
    doc.abortTransaction()
    for name, visible in visibility.items():
        obj = doc.getObject(name)
        if obj is not None and obj.ViewObject is not None:
            obj.ViewObject.Visibility = visible
    message = "{} of '{}' cancelled: nothing was made".format(transaction, source.Label)
    FreeCAD.Console.PrintMessage(message + "\n")
    # After FreeCAD's own "Recompute failed!", which it shows for the stopped recompute.
    from PySide import QtCore

    status = FreeCADGui.getMainWindow().statusBar()
    QtCore.QTimer.singleShot(0, lambda: status.showMessage(message, 10000))


class _CancelWatch:
    """Tells whether the user cancelled a recompute from the progress dialog since it was made."""

    def __init__(self):
        self.count = MultiAxisSlicerGui.progress.cancel_count()

    def cancelled(self):
        return MultiAxisSlicerGui.progress.cancel_count() != self.count


def _selected_one(check):
    """The one selected object if check(object), else None."""
    if FreeCAD.ActiveDocument is None:
        return None
    selection = FreeCADGui.Selection.getSelection()
    if len(selection) == 1 and check(selection[0]):
        return selection[0]
    return None


def _active(select):
    """A command's IsActive: whether select() finds its input."""
    try:
        return select() is not None
    except Exception:  # IsActive runs on every GUI update: never let it raise
        return False


class _PartCommand:
    """A command making one parametric object over the selected input (a solid or mesh unless
    select() says otherwise), in one transaction (undo removes it). A subclass sets NAME,
    TRANSACTION, ICON, TOOLTIP and defines make()."""

    NAME = ""
    TRANSACTION = ""  # also the menu text
    ICON = ""
    TOOLTIP = ""
    NO_SELECTION = "Select one solid or mesh first."

    def GetResources(self):
        return {
            "Pixmap": MultiAxisSlicerGui.icon_path(self.ICON),
            "MenuText": self.TRANSACTION,
            "ToolTip": self.TOOLTIP,
        }

    def select(self):
        """The selected input, None when the selection holds none."""
        return _selected_part()

    def IsActive(self):
        return _active(self.select)

    def make(self, source, doc):
        raise NotImplementedError

    def input_problem(self, source):
        """Why the selected `source` can be no input (None when it can): see _part_problem."""
        return _part_problem(source)

    def Activated(self):
        source = self.select()
        if source is None:
            MultiAxisSlicerGui.show_error(self.NO_SELECTION)
            return
        if not mas.engine_available():
            MultiAxisSlicerGui.show_error(mas.engine_missing_message())
            return
        problem = self.input_problem(source)
        if problem is not None:
            MultiAxisSlicerGui.show_error("{}: {}".format(self.TRANSACTION, problem))
            return
        doc = source.Document
        watch = _CancelWatch()
        visibility = _visibility(doc)
        before = {o.Name for o in doc.Objects}
        doc.openTransaction(self.TRANSACTION)
        try:
            obj = self.make(source, doc)
            if not watch.cancelled():  # else no more work
                _recompute_new(doc, before)
        except Exception as error:  # creating the object failed: leave nothing behind
            doc.abortTransaction()
            MultiAxisSlicerGui.show_error(
                "{} of '{}' failed: {}".format(self.TRANSACTION, source.Label, error))
            return
        if watch.cancelled():
            _undo_cancelled(doc, self.TRANSACTION, source, visibility)
            return
        doc.commitTransaction()
        import MultiAxisSlicer.features as features

        message = features.failure(obj)
        if message is not None:  # the object stays so that its parameters (or input) can be fixed
            MultiAxisSlicerGui.show_error(message)
            return
        self.made(obj)

    def made(self, obj):
        """After the object is made and computed (not when it failed)."""


class SectionsCommand(_PartCommand):
    """Cross-sections of the selected solid or mesh, as a parametric Sections object."""

    NAME = "MultiAxisSlicer_Sections"
    TRANSACTION = "Cross-sections"
    ICON = "Sections.svg"
    TOOLTIP = ("Cut the selected solid or closed mesh by parallel planes "
               "(a parametric Sections object: set Normal, Step, Deflection)")

    def make(self, source, doc):
        import MultiAxisSlicer.features as features

        return features.make_sections(source, doc=doc)


class CentroidalAxisCommand(_PartCommand):
    """The centroidal axis of the selected solid or mesh, as a parametric CentroidalAxis object.
    Computing it takes milliseconds at the derived step; a small given step may take long, and
    the recompute then shows its progress with Cancel, like every object's here."""

    NAME = "MultiAxisSlicer_CentroidalAxis"
    TRANSACTION = "Centroidal axis"
    ICON = "CentroidalAxis.svg"
    TOOLTIP = ("Centroidal axis of the selected solid or closed mesh: section centroids from its "
               "base up, branching where the part branches, C1 breaks in red (a parametric "
               "CentroidalAxis object: set Step, DistanceThreshold, BreakAngle, Deflection)")

    def make(self, source, doc):
        import MultiAxisSlicer.features as features

        return features.make_centroidal_axis(source, doc=doc)


class DecomposeCommand(_PartCommand):
    """The sub-components of the selected solid (or of a selected CentroidalAxis object's source,
    following that axis' parameters), as a parametric Decomposition object with one Component
    object per sub-component, in distinct colours. The source is hidden, not changed."""

    NAME = "MultiAxisSlicer_Decompose"
    TRANSACTION = "Decompose"
    ICON = "Decompose.svg"
    TOOLTIP = ("Split the selected solid into sub-components where its centroidal axis turns or "
               "branches, each built from its base face along its own direction (a parametric "
               "Decomposition object with Component001, ...; select a CentroidalAxis object to "
               "use its parameters)")

    def input_problem(self, source):
        import MultiAxisSlicer.features as features

        if features.is_centroidal_axis(source):  # its source is the part
            if source.Source is None:
                return "the CentroidalAxis object '{}' has no Source.".format(source.Label)
            return _part_problem(source.Source, split=True)
        return _part_problem(source, split=True)

    def make(self, source, doc, min_component_height=0.0):
        import MultiAxisSlicer.features as features

        if features.is_centroidal_axis(source):
            obj = features.make_decomposition(None, axis=source, doc=doc,
                                              min_component_height=min_component_height)
            part = source.Source
        else:
            obj = features.make_decomposition(source, doc=doc,
                                              min_component_height=min_component_height)
            part = source
        if features.failure(obj) is None and part is not None and part.ViewObject is not None:
            part.ViewObject.Visibility = False  # the components take its place in the view
        return obj


class _Busy:
    """Feedback between the stages of a command: a wait cursor and a status-bar message. Within a
    stage the object's recompute shows its own progress dialog, with Cancel (progress.py), which
    replaces the status-bar progress bar the command used to step once per stage."""

    def __init__(self):
        self.watch = None

    def __enter__(self):
        from PySide import QtCore, QtGui

        self.watch = _CancelWatch()
        QtGui.QApplication.setOverrideCursor(QtCore.Qt.WaitCursor)
        return self

    def stage(self, message):
        """Shows `message` in the status bar and repaints."""
        FreeCADGui.getMainWindow().statusBar().showMessage(message)
        FreeCAD.Console.PrintLog("Multi-Axis Slicer: {}\n".format(message))
        FreeCADGui.updateGui()

    def cancelled(self):
        """Whether the user cancelled a recompute since this began."""
        return self.watch.cancelled()

    def __exit__(self, *exc):
        from PySide import QtGui

        FreeCADGui.getMainWindow().statusBar().clearMessage()
        QtGui.QApplication.restoreOverrideCursor()
        return False


class SliceCommand(_PartCommand):
    """Adaptive multi-axis layers and bead paths of a selected Decomposition object (or of a
    selected solid, decomposed first as the Decompose command does, or of a closed mesh, split at
    section planes, or of the CentroidalAxis object of one, whose parameters its axis takes), as a
    parametric Layers object (outlines coloured by component) and a Toolpath object (paths coloured
    by kind), in one transaction. Slicing can take a while: the status bar says which stage runs,
    and a progress dialog shows how far it is; its Cancel undoes the whole command."""

    NAME = "MultiAxisSlicer_Slice"
    TRANSACTION = "Slice"
    ICON = "Slice.svg"
    TOOLTIP = ("Slice the selected Decomposition (or solid, decomposed first; or closed mesh, "
               "split at section planes) into adaptive multi-axis layers, each component along "
               "its own build direction, and plan the bead paths in every layer (parametric "
               "Layers and Toolpath objects: set MinLayer, MaxLayer, BeadWidth, Infill, ...)")

    def Activated(self):
        import MultiAxisSlicer.features as features

        source = _selected_part()
        if source is None:
            MultiAxisSlicerGui.show_error(
                "Select one Decomposition object, one solid or one closed mesh first.")
            return
        if not mas.engine_available():
            MultiAxisSlicerGui.show_error(mas.engine_missing_message())
            return
        # A mesh (or the axis of one, whose parameters it then takes) is split as it is sliced: a
        # mesh cannot be decomposed into solids.
        mesh = source if features.is_mesh_part(source) else None
        if features.is_centroidal_axis(source) and features.is_mesh_part(source.Source):
            mesh = source.Source
        if features.is_decomposition(source):
            problem = None
        elif mesh is not None:
            problem = _part_problem(mesh)
        else:
            problem = DecomposeCommand().input_problem(source)
        if problem is not None:
            MultiAxisSlicerGui.show_error("{}: {}".format(self.TRANSACTION, problem))
            return
        doc = source.Document
        visibility = _visibility(doc)
        before = {o.Name for o in doc.Objects}
        doc.openTransaction(self.TRANSACTION)
        try:
            with _Busy() as busy:
                failed = self._slice(source, mesh, doc, before, busy)
                cancelled = busy.cancelled()
        except Exception as error:  # creating the objects failed: leave nothing behind
            doc.abortTransaction()
            MultiAxisSlicerGui.show_error(
                "{} of '{}' failed: {}".format(self.TRANSACTION, source.Label, error))
            return
        if cancelled:
            _undo_cancelled(doc, self.TRANSACTION, source, visibility)
            return
        doc.commitTransaction()
        if failed is not None:  # the objects stay so that their parameters can be fixed
            MultiAxisSlicerGui.show_error(failed)

    @staticmethod
    def _slice(source, mesh, doc, before, busy):
        """Makes and computes the command's objects in the open transaction; returns what failed,
        or None. `mesh`: the mesh object `source` is or is the axis of, else None. A mesh is split
        as it is sliced (Layers' SplitMesh); a solid is decomposed first, into a Decomposition
        object, and where some layers would meet the plate or what is deposited before them, the
        branches of their components are kept in their fathers (its KeepBranches), or cut square
        to their directions where their cuts were turned square to their lines (its
        SquareBranches), as slice() does. A Decomposition object selected is sliced as it is."""
        import MultiAxisSlicer.features as features

        decomposed_here = False
        if mesh is not None:
            busy.stage("Slicing the mesh '{}'...".format(mesh.Label))
            sliced, part = source, mesh
        else:
            if features.is_decomposition(source):
                decomposition = source
                busy.stage("Using the decomposition '{}'".format(source.Label))
                if "Touched" in decomposition.State:  # changed since: as it is now
                    decomposition.recompute(True)
            else:
                busy.stage("Decomposing '{}'...".format(source.Label))
                # No sub-component thinner than the layers (the default MinLayer).
                decomposition = DecomposeCommand().make(source, doc,
                                                        mas.SLICE_DEFAULTS["min_layer"])
                decomposed_here = True
            if features.failure(decomposition) is not None:  # a cancelled one too
                return features.failure(decomposition)
            busy.stage("Slicing '{}' into layers...".format(source.Label))
            sliced, part = decomposition, features.decomposition_inputs(decomposition)[0]
        layers, toolpath = features.make_slice(sliced, doc=doc)
        doc.recompute([layers])  # one stage at a time, for the feedback
        if (decomposed_here and features.failure(layers) is None and
                features.has_unreachable_or_hanging(layers)):
            # As slice() does: the branches whose own layers the nozzle cannot reach are built
            # in their fathers (the decomposition's KeepBranches), or first cut square to their
            # directions (its SquareBranches), and those whose layers hang where less would
            # hang so, the part split again.
            busy.stage("Building in their fathers the branches the nozzle cannot reach or that "
                       "hang...")
            try:
                features.keep_unreachable_branches(layers)
            except mas.Cancelled:
                return None  # the command is undone
            except mas.EngineError as error:  # the first split stays, its collisions reported
                FreeCAD.Console.PrintWarning(
                    "{}: the branches the nozzle cannot reach could not be kept in their fathers: "
                    "{}\n".format(layers.Label, error))
        components = features.components_of(decomposition) if mesh is None else []
        if features.failure(layers) is None:
            busy.stage("Drawing the bead paths...")
            doc.recompute([toolpath])
        if not busy.cancelled():  # else nothing is kept: no more work
            # The decomposition's components too: they follow it when it changed.
            _recompute_new(doc, before, components)
        failed = features.failure(layers) or features.failure(toolpath)
        if failed is None:  # the layers take the part's place in the view
            for o in [part] + components:
                if o.ViewObject is not None:
                    o.ViewObject.Visibility = False
        return failed


class _LayersCommand(_PartCommand):
    """A command making one object over a selected Layers (or Toolpath) object."""

    NO_SELECTION = "Select one Layers or Toolpath object first."

    def select(self):
        import MultiAxisSlicer.features as features

        return _selected_one(lambda o: features.is_layers(o) or features.is_toolpath(o))

    def input_problem(self, source):
        return None  # any Layers or Toolpath: a failing one marks the new object with its message


class MachineProgramCommand(_LayersCommand):
    """The 5-axis G-code of a selected Layers (or Toolpath) object, as a parametric
    MachineProgram object (the machine's limits, feed and clearance as properties), in one
    transaction. A program the machine cannot run (a layer whose tool axis the table cannot turn
    to the nozzle) leaves the object marked with the message, so that the limits can be fixed."""

    NAME = "MultiAxisSlicer_MachineProgram"
    TRANSACTION = "Machine program"
    ICON = "MachineProgram.svg"
    TOOLTIP = ("Write the 5-axis G-code that deposits the selected Layers (or Toolpath) on a "
               "tilting rotary table (LinuxCNC, XYZAC): a parametric MachineProgram object; set "
               "AMin, AMax, Feed, Clearance, ..., then Export G-code")

    def make(self, source, doc):
        import MultiAxisSlicer.features as features

        return features.make_machine_program(source, doc=doc)


class BuildPreviewCommand(_LayersCommand):
    """The build of a selected Layers (or Toolpath) object step by step in its deposition order,
    as a parametric BuildPreview object (the layers deposited so far and the nozzle at the step's
    layer), in one transaction; its panel opens on it to step through the build."""

    NAME = "MultiAxisSlicer_BuildPreview"
    TRANSACTION = "Build preview"
    ICON = "BuildPreview.svg"
    TOOLTIP = ("Step through the build of the selected Layers (or Toolpath) in its deposition "
               "order: the layers deposited so far and the nozzle at the step's layer, along its "
               "tool axis (a parametric BuildPreview object)")

    def make(self, source, doc):
        import MultiAxisSlicer.features as features

        preview = features.make_build_preview(source, doc=doc)
        # The preview takes the place of the layers and paths in the view.
        for o in features.layers_and_toolpaths(preview.Layers):
            if o.ViewObject is not None:
                o.ViewObject.Visibility = False
        return preview

    def made(self, obj):
        from MultiAxisSlicerGui import build_preview

        build_preview.edit(obj)


class ExportGcodeCommand:
    """Writes the program of a selected MachineProgram object to a file the user names (.ngc),
    after recomputing it if it or its layers changed since. Adds nothing to the document."""

    NAME = "MultiAxisSlicer_ExportGcode"
    MENU_TEXT = "Export G-code..."

    def GetResources(self):
        return {
            "Pixmap": MultiAxisSlicerGui.icon_path("ExportGcode.svg"),
            "MenuText": self.MENU_TEXT,
            "ToolTip": "Write the selected MachineProgram's G-code to a file (.ngc)",
        }

    def IsActive(self):
        import MultiAxisSlicer.features as features

        return _active(lambda: _selected_one(features.is_machine_program))

    def Activated(self):
        import MultiAxisSlicer.features as features
        from PySide import QtGui

        obj = _selected_one(features.is_machine_program)
        if obj is None:
            MultiAxisSlicerGui.show_error("Select one MachineProgram object first.")
            return
        if any("Touched" in o.State for o in [obj] + features.depends_on(obj)):
            obj.recompute(True)  # changed since (the program or its layers): as it is now
        problem = features.failure(obj)
        if problem is not None:
            MultiAxisSlicerGui.show_error("Export G-code: " + problem)
            return
        import os

        folder = os.path.dirname(obj.Document.FileName) or os.path.expanduser("~")
        name = "".join(c if c.isalnum() or c in "-_." else "_" for c in obj.Label) + ".ngc"
        path, _filter = QtGui.QFileDialog.getSaveFileName(
            FreeCADGui.getMainWindow(), "Export G-code", os.path.join(folder, name),
            "G-code (*.ngc *.nc *.gcode);;All files (*)")
        if not path:
            return
        try:
            program = features.export_gcode(obj, path)
        except Exception as error:
            MultiAxisSlicerGui.show_error("Export G-code to '{}' failed: {}".format(path, error))
            return
        message = "G-code written to {} ({} lines)".format(path, program.stats["lines"])
        FreeCAD.Console.PrintMessage(message + "\n")
        FreeCADGui.getMainWindow().statusBar().showMessage(message, 10000)


FreeCADGui.addCommand(SectionsCommand.NAME, SectionsCommand())
FreeCADGui.addCommand(CentroidalAxisCommand.NAME, CentroidalAxisCommand())
FreeCADGui.addCommand(DecomposeCommand.NAME, DecomposeCommand())
FreeCADGui.addCommand(SliceCommand.NAME, SliceCommand())
FreeCADGui.addCommand(MachineProgramCommand.NAME, MachineProgramCommand())
FreeCADGui.addCommand(ExportGcodeCommand.NAME, ExportGcodeCommand())
FreeCADGui.addCommand(BuildPreviewCommand.NAME, BuildPreviewCommand())
