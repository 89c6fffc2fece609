# SPDX-License-Identifier: LGPL-2.1-or-later
"""The build preview's panel: steps a BuildPreview object through its Layers object's deposition
sequence, so that a process engineer can watch the part grow layer by layer in the order it is
deposited, the nozzle at each layer along its tool axis (leaned where the sequence leans it, in
CollisionColor where it meets what is deposited).

Double-clicking the object (or "Step through the build..." in its context menu) opens it; the Build
preview command opens it on the object it makes. A slider and a spin box choose the step (the slider
moves the preview when it is let go, or by the keyboard a step at a time), Play walks through the
steps to the last, Show nozzle, Show paths and Show plate show or hide the nozzle, the step's
deposit paths and the build plate, and three buttons go to the step before or after whose layer the
nozzle leans for or collides at, and to the layer that stands most on nothing. Each step is the
object's Step property written and the object recomputed: the slicing is the Layers object's, kept
in memory, and each layer's solid and triangles are made once, so a step costs little more than the
drawing. Stepping is not recorded for Undo (a walk through a few hundred layers would bury the undo
steps before it); the property editor's Step is."""

import FreeCADGui

import MultiAxisSlicerGui

# Play: the time each step is shown for.
PLAY_INTERVAL_MS = 300

_open_panel = None  # the panel shown now, if any (for the tests and for unsetEdit)


def active_panel():
    """The BuildPreviewPanel shown in the task view now, or None."""
    return _open_panel


def summary(obj):
    """What the computed BuildPreview object `obj` shows, in words."""
    text = "Step {} of {}: layer {} of component {}".format(
        obj.ShownStep, obj.StepCount, obj.Layer, obj.Component)
    lean = obj.Lean.Value
    if lean >= 0.05:
        text += ", the nozzle leaned {:.1f}° from the layer's normal to clear".format(lean)
    if obj.Collides:
        text += "; its nozzle meets {}".format(
            "the build plate" if obj.CollisionObstacle == -1
            else "layer {}".format(obj.CollisionObstacle))
    if obj.UnsupportedArea.Value >= 0.005:
        text += "; {:.2f} mm² of it stands on nothing".format(obj.UnsupportedArea.Value)
    return text + "."


class BuildPreviewPanel:
    """The task panel (see the module's documentation) of the BuildPreview object `obj`."""

    def __init__(self, obj):
        from PySide import QtCore, QtGui

        self.obj = obj
        self.doc = obj.Document
        self.form = QtGui.QWidget()
        self.form.setWindowTitle("Build preview: {}".format(obj.Label))
        self.form.setWindowIcon(QtGui.QIcon(MultiAxisSlicerGui.icon_path("BuildPreview.svg")))
        layout = QtGui.QVBoxLayout(self.form)
        self.info = QtGui.QLabel()
        self.info.setWordWrap(True)
        self.info.setObjectName("info")
        layout.addWidget(self.info)
        row = QtGui.QHBoxLayout()
        self.slider = QtGui.QSlider(QtCore.Qt.Horizontal)
        self.slider.setObjectName("slider")
        self.slider.setTracking(False)  # moves the preview when let go: each step is drawn anew
        self.slider.setToolTip("The step of the deposition sequence shown")
        self.spin = QtGui.QSpinBox()
        self.spin.setObjectName("step")
        self.spin.setKeyboardTracking(False)
        self.spin.setToolTip("The step of the deposition sequence shown")
        row.addWidget(self.slider, 1)
        row.addWidget(self.spin)
        layout.addLayout(row)
        # Two buttons a row at most: FreeCAD's task view is narrow, and a wider row pushed the
        # panel past it.
        self.play = QtGui.QPushButton("Play")
        self.play.setObjectName("play")
        self.play.setCheckable(True)
        self.play.setToolTip("Walk through the steps to the last")
        self.worst = QtGui.QPushButton("Max overhang")
        self.worst.setObjectName("worst")
        self.worst.setToolTip("The step whose layer stands most on nothing")
        self.previous = QtGui.QPushButton("< Previous")
        self.previous.setObjectName("previous_flagged")
        self.previous.setToolTip("The step before this one whose layer the nozzle leans for or "
                                 "collides at")
        self.next = QtGui.QPushButton("Next >")
        self.next.setObjectName("next_flagged")
        self.next.setToolTip("The step after this one whose layer the nozzle leans for or "
                             "collides at")
        self.nozzle = QtGui.QCheckBox("Show nozzle")
        self.nozzle.setObjectName("nozzle")
        self.paths = QtGui.QCheckBox("Show paths")
        self.paths.setObjectName("paths")
        self.paths.setToolTip("The step's deposit paths on its layer")
        self.plate = QtGui.QCheckBox("Show plate")
        self.plate.setObjectName("plate")
        self.plate.setToolTip("The build plate the part stands on")
        grid = QtGui.QGridLayout()
        grid.addWidget(self.play, 0, 0)
        grid.addWidget(self.worst, 0, 1)
        grid.addWidget(QtGui.QLabel("Leaned or colliding layer:"), 1, 0, 1, 2)
        grid.addWidget(self.previous, 2, 0)
        grid.addWidget(self.next, 2, 1)
        grid.addWidget(self.nozzle, 3, 0)
        grid.addWidget(self.paths, 3, 1)
        grid.addWidget(self.plate, 4, 0)
        layout.addLayout(grid)
        layout.addStretch(1)
        self.timer = QtCore.QTimer(self.form)
        self.timer.setInterval(PLAY_INTERVAL_MS)
        self.timer.timeout.connect(self.advance)
        self.load()
        self.slider.valueChanged.connect(self.go)
        self.slider.sliderMoved.connect(self._show_number)
        self.spin.valueChanged.connect(self.go)
        self.play.toggled.connect(self.toggle_play)
        self.nozzle.toggled.connect(self.show_nozzle)
        self.paths.toggled.connect(self.show_paths)
        self.plate.toggled.connect(self.show_plate)
        self.previous.clicked.connect(lambda: self.go_flagged(-1))
        self.next.clicked.connect(lambda: self.go_flagged(1))
        self.worst.clicked.connect(self.go_worst)

    def alive(self):
        """Whether the object is still in its document (an Undo of its creation removes it)."""
        try:
            return self.doc.getObject(self.obj.Name) is self.obj
        except Exception:
            return False

    def _gone(self):
        """True, the panel closed, when its object is no longer in its document."""
        if self.alive():
            return False
        self.close()
        return True

    def load(self):
        """The controls as the object stands: its steps, the step shown, its summary."""
        import MultiAxisSlicer.features as features

        count = self.obj.StepCount
        for widget in (self.slider, self.spin):
            widget.blockSignals(True)
            widget.setRange(1 if count else 0, count)
            widget.setValue(self.obj.ShownStep)
            widget.setEnabled(count > 0)
            widget.blockSignals(False)
        for box, shown in ((self.nozzle, self.obj.ShowNozzle), (self.paths, self.obj.ShowPaths),
                           (self.plate, self.obj.ShowPlate)):
            box.blockSignals(True)
            box.setChecked(shown)
            box.blockSignals(False)
        self.play.setEnabled(count > 1)
        step = self.obj.ShownStep
        flagged = list(self.obj.FlaggedSteps)
        self.previous.setEnabled(any(k < step for k in flagged))
        self.next.setEnabled(any(k > step for k in flagged))
        self.worst.setEnabled(self.obj.WorstStep > 0)
        problem = features.failure(self.obj)
        self.info.setText(summary(self.obj) if problem is None else problem)
        self.info.setStyleSheet("" if problem is None else "color: #c00000")

    def _show_number(self, step):
        self.spin.blockSignals(True)
        self.spin.setValue(step)
        self.spin.blockSignals(False)

    def _set(self, prop, value):
        """Writes a property and recomputes the object; closes the panel if the object is gone."""
        if self._gone():
            return False
        if getattr(self.obj, prop) != value or "Touched" in self.obj.State:
            setattr(self.obj, prop, value)
            self.doc.recompute([self.obj])  # and the Layers object, if changed since
        self.load()
        return True

    def go(self, step):
        """Shows step `step` (1 to StepCount)."""
        return self._set("Step", int(step))

    def go_flagged(self, direction):
        """Shows the nearest step before (direction -1) or after (1) the one shown whose layer
        the nozzle leans for or collides at; False when there is none."""
        if self._gone():
            return False
        step = self.obj.ShownStep
        steps = [k for k in self.obj.FlaggedSteps if (k - step) * direction > 0]
        if not steps:
            return False
        return self.go(max(steps) if direction < 0 else min(steps))

    def go_worst(self):
        """Shows the step whose layer stands most on nothing; False when every layer rests on the
        one below."""
        if self._gone():
            return False
        return self.obj.WorstStep > 0 and self.go(self.obj.WorstStep)

    def show_nozzle(self, shown):
        return self._set("ShowNozzle", bool(shown))

    def show_paths(self, shown):
        return self._set("ShowPaths", bool(shown))

    def show_plate(self, shown):
        return self._set("ShowPlate", bool(shown))

    def toggle_play(self, playing):
        if not playing:
            self.timer.stop()
            return
        if self.obj.ShownStep >= self.obj.StepCount:
            self.go(1)  # from the start again
        self.timer.start()

    def advance(self):
        """Play: the next step; stops at the last."""
        if self._gone():
            return  # closed, its timer stopped
        if self.obj.ShownStep >= self.obj.StepCount:
            self.play.setChecked(False)
            return
        if self.go(self.obj.ShownStep + 1) and "Invalid" in self.obj.State:
            self.play.setChecked(False)

    def getStandardButtons(self):
        from PySide import QtGui

        return int(QtGui.QDialogButtonBox.Close)

    def accept(self):
        self.close()
        return True

    def reject(self):
        self.close()
        return True

    def _finish(self):
        """The panel is no longer the open one."""
        global _open_panel
        try:
            self.timer.stop()
        except RuntimeError:  # its form was deleted with the task dialog
            pass
        if _open_panel is self:
            _open_panel = None

    def close(self):
        was_open = _open_panel is self
        self._finish()
        if not was_open:
            return  # closed already (the edit ended: its object removed, the document closed)
        if self.form is None and FreeCADGui.Control.activeDialog():
            return  # a script closed this panel's dialog: the one shown now is another's
        gui_doc = FreeCADGui.getDocument(self.doc.Name)
        if gui_doc is not None:
            gui_doc.resetEdit()
        FreeCADGui.Control.closeDialog()


def edit(obj):
    """Double-click and "Step through the build...": opens the panel of `obj` in edit mode. With
    a task open, says so and leaves it as it is."""
    panel = _open_panel
    if panel is not None and panel.obj is obj and FreeCADGui.Control.activeDialog():
        return True  # its panel is open already
    if FreeCADGui.Control.activeDialog():
        MultiAxisSlicerGui.show_error(
            "Finish the task open in the task view, then step through '{}'.".format(obj.Label))
        return True
    FreeCADGui.getDocument(obj.Document.Name).setEdit(obj.Name, 0)
    return True


def open_panel(obj):
    """Shows the panel of `obj` in the task view (the view provider's setEdit). Returns False,
    saying why, when another task is open."""
    global _open_panel
    if FreeCADGui.Control.activeDialog():
        MultiAxisSlicerGui.show_error(
            "Finish the task open in the task view, then step through '{}'.".format(obj.Label))
        return False
    _open_panel = BuildPreviewPanel(obj)
    FreeCADGui.Control.showDialog(_open_panel)
    return True


def close_panel():
    """The edit ends (the view provider's unsetEdit): the panel closes if still open."""
    panel = _open_panel
    if panel is None:
        return
    panel._finish()
    if panel.form is not None:  # else a script closed it, and the dialog shown is another's
        FreeCADGui.Control.closeDialog()
