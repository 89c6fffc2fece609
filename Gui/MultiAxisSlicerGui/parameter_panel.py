# SPDX-License-Identifier: LGPL-2.1-or-later
"""The parameter panel: a task panel that edits the inputs of one of this workbench's objects
(Sections, CentroidalAxis, Decomposition, Layers, MachineProgram) in one form, grouped as the
property editor groups them, lengths and angles in the user's units.

Double-clicking the object (or "Edit parameters..." in its context menu) opens it. Apply writes
the changed values and recomputes the object and everything that depends on it (a Layers
object's Toolpath and MachineProgram), then shows the result's figures, or the engine's message
naming the bad parameter, so that a process engineer can try values in turn. OK does the same
and closes, unless the object then fails (the message stays in the panel). Cancel puts
everything back as it was when the panel opened: the edit is one transaction, which Cancel
aborts, and the slicing or program computed before it is kept in memory, so nothing is computed
again. After OK the whole edit is one undo step. Undo while the panel is open takes back what
was applied (results too) and closes it. An edit or a command that opens its own undo step
meanwhile (a part's Transform, a toolbar command) keeps what was applied, one undo step of its
own; an edit that ends this one without (a sketch's) undoes it, as Cancel does. Long recomputes
show the progress dialog, with its Cancel, as every recompute here does.

The fields come from the object (``MultiAxisSlicer.features.parameters``): each feature lists its
inputs, so a new parameter appears here without a change to this module."""

import re

import FreeCAD
import FreeCADGui

import MultiAxisSlicerGui

# Quantity properties: edited in a Gui::QuantitySpinBox in this unit (shown in the user's units).
_QUANTITY_UNITS = {
    "App::PropertyLength": "mm",
    "App::PropertyDistance": "mm",
    "App::PropertyAngle": "deg",
}
# Fields range over +-this (1 km, 10^6 counts; angles over a turn), or the property's value if
# it is farther out (which the field must not clip): a spin box is as wide as its range's longest
# number, and wider ones pushed the panel past FreeCAD's task view.
_RANGE = 1e6
# The least a field shrinks to: room for a value as wide as these (its text, not its range's)
# and the spin box's arrows and frame; a row whose label leaves less goes under its label.
_FIELD_SAMPLES = {
    "App::PropertyLength": "-0000.00 mm",
    "App::PropertyDistance": "-0000.00 mm",
    "App::PropertyAngle": "-000.00 °",
    "App::PropertyFloat": "-000.0000",
    "App::PropertyInteger": "-000000",
    "App::PropertyVector": "-000.0000",  # each coordinate's box
}
_SPIN_BOX_EXTRA = 32  # pixels: arrows, frame and margins
# The property types a field edits; any other stays the property editor's.
_EDITABLE_TYPES = set(_QUANTITY_UNITS) | {
    "App::PropertyFloat", "App::PropertyInteger", "App::PropertyBool",
    "App::PropertyEnumeration", "App::PropertyVector"}

_open_panel = None  # the panel shown now, if any (for the tests and for unsetEdit)


def active_panel():
    """The ParameterPanel shown in the task view now, or None."""
    return _open_panel


def _label(prop, group=""):
    """A field's label: "NozzleTipDiameter" in the group "Nozzle" -> "Tip diameter", "MinLayer"
    -> "Min layer" (short: the task view is narrow)."""
    words = re.findall(r"[A-Z][a-z0-9]*|[a-z0-9]+", prop)
    if len(words) > 1 and words[0] == group:
        words = [words[1].capitalize()] + words[2:]
    return " ".join([words[0]] + [w.lower() for w in words[1:]]) if words else prop


def _expressions_of(expressions, prop):
    """The expressions (an object's ExpressionEngine) that set `prop` or a part of it: "MaxLayer"
    for the whole, ".Normal.x" for a vector's coordinate."""
    return [("{} = {}".format(path.lstrip("."), text) if path.lstrip(".") != prop else text)
            for path, text in expressions if path.lstrip(".").split(".")[0] == prop]


def _summary(obj):
    """The figures of a computed `obj`, in a line or two of words."""
    kind = obj.Proxy.Type
    if kind == "MultiAxisSlicer::Sections":
        return "{} sections, {:.6g} mm² in all.".format(obj.SectionCount, obj.TotalArea.Value)
    if kind == "MultiAxisSlicer::CentroidalAxis":
        return "{} nodes in {} branch(es), {} C1 break(s); step {:.4g} mm, frame {:.4g}°.".format(
            obj.NodeCount, obj.BranchCount, obj.BreakCount, obj.UsedStep.Value,
            obj.UsedFrame.Value)
    if kind == "MultiAxisSlicer::Decomposition":
        return "{} sub-component(s); step {:.4g} mm.".format(obj.ComponentCount,
                                                             obj.UsedStep.Value)
    if kind == "MultiAxisSlicer::Layers":
        lines = ["{} layers in {} component(s), {:.4g} to {:.4g} mm thick.".format(
            obj.LayerCount, len(obj.ComponentLayerCounts), obj.MinThickness.Value,
            obj.MaxThickness.Value)]
        if obj.WorstUnsupportedLayer >= 0:
            lines.append("Worst unsupported area {:.4g} mm² (layer {}).".format(
                obj.WorstUnsupportedArea.Value, obj.WorstUnsupportedLayer))
        else:
            lines.append("Every layer rests on the one below.")
        lines.append("{} layer(s) with the nozzle leaned; {} whose nozzle meets what is "
                     "deposited.".format(obj.LeanedLayers, obj.CollidingLayers))
        return "\n".join(lines)
    if kind == "MultiAxisSlicer::MachineProgram":
        text = ("{} lines, {} deposit moves, {:.4g} min depositing; A {:.4g} to {:.4g}°.\n"
                "Travel: {} routes checked, {} taken round the part, {} meeting what is "
                "deposited.".format(obj.LineCount, obj.DepositMoves, obj.DepositTime,
                                    *(list(obj.ARange) or [0.0, 0.0]), obj.CheckedRoutes,
                                    obj.ReroutedTravels, obj.TravelCollisions))
        ranges = [list(getattr(obj, axis + "Range", [])) for axis in "XYZ"]
        if all(len(r) == 2 for r in ranges):  # recomputed since the ranges were added
            text += ("\nMachine: X {:.4g} to {:.4g}, Y {:.4g} to {:.4g}, Z {:.4g} to {:.4g} "
                     "mm{}.").format(*(v for r in ranges for v in r),
                                     " (within the travel limits)" if obj.CheckTravel else "")
        return text
    return "Computed."


def _text_width(box, sample):
    """The width a spin box needs to show `sample` whole."""
    return box.fontMetrics().horizontalAdvance(sample) + _SPIN_BOX_EXTRA


class _Field:
    """One property's editor: widget, load(obj) shows the property's value, read() the value to
    write, changed() whether the user changed it."""

    def __init__(self, obj, prop):
        from PySide import QtGui

        self.prop = prop
        type_id = obj.getTypeIdOfProperty(prop)
        self.type_id = type_id
        if type_id in _QUANTITY_UNITS:
            self.widget = FreeCADGui.UiLoader().createWidget("Gui::QuantitySpinBox")
            self.widget.setProperty("unit", _QUANTITY_UNITS[type_id])
            self.shown = lambda: float(self.widget.property("rawValue"))
        elif type_id == "App::PropertyFloat":
            self.widget = QtGui.QDoubleSpinBox()
            self.widget.setDecimals(4)
            self.shown = self.widget.value
        elif type_id == "App::PropertyInteger":
            self.widget = QtGui.QSpinBox()
            self.shown = self.widget.value
        elif type_id == "App::PropertyBool":
            self.widget = QtGui.QCheckBox()
            self.shown = self.widget.isChecked
        elif type_id == "App::PropertyEnumeration":
            self.widget = QtGui.QComboBox()
            self.widget.addItems(obj.getEnumerationsOfProperty(prop))
            self.shown = self.widget.currentText
        elif type_id == "App::PropertyVector":
            self.widget = QtGui.QWidget()
            column = QtGui.QVBoxLayout(self.widget)  # three in a row would not fit narrow
            column.setContentsMargins(0, 0, 0, 0)
            self.boxes = []
            for axis in "xyz":
                box = QtGui.QDoubleSpinBox()
                box.setDecimals(4)
                box.setPrefix(axis + "  ")
                box.setMinimumWidth(_text_width(box, axis + "  " + _FIELD_SAMPLES[type_id]))
                column.addWidget(box)
                self.boxes.append(box)
            self.shown = lambda: tuple(b.value() for b in self.boxes)
        else:
            raise TypeError("no editor for {} ({})".format(prop, type_id))
        if type_id in _FIELD_SAMPLES and type_id != "App::PropertyVector":
            self.widget.setMinimumWidth(_text_width(self.widget, _FIELD_SAMPLES[type_id]))
        self.widget.setObjectName(prop)
        self.widget.setToolTip(obj.getDocumentationOfProperty(prop))
        self.load(obj)

    def load(self, obj):
        """Shows the property's value now: when the panel opens, and after each Apply (a property
        may hold other than what was written, as an angle kept within a turn, or an expression
        may have set it)."""
        value = getattr(obj, self.prop)
        self.value = value  # what the property held (a vector's unchanged coordinates stay it)
        number = getattr(value, "Value", value)
        if isinstance(number, bool) or not isinstance(number, (int, float)):
            limit = _RANGE
        else:
            limit = max(_RANGE, abs(number))
        if self.type_id in _QUANTITY_UNITS:
            low, high = -limit, limit
            if self.type_id == "App::PropertyLength":
                low = 0.0  # the property refuses a negative value
            elif self.type_id == "App::PropertyAngle":
                # The property keeps its value within a turn (400° would be written as 360°
                # without a word).
                low, high = -360.0, 360.0
            self.widget.setProperty("minimum", low)
            self.widget.setProperty("maximum", high)
            self.widget.setProperty("rawValue", number)
        elif self.type_id == "App::PropertyFloat":
            self.widget.setRange(-limit, limit)
            self.widget.setValue(value)
        elif self.type_id == "App::PropertyInteger":
            self.widget.setRange(-min(int(limit), 2 ** 31 - 1), min(int(limit), 2 ** 31 - 1))
            self.widget.setValue(value)
        elif self.type_id == "App::PropertyBool":
            self.widget.setChecked(bool(value))
        elif self.type_id == "App::PropertyEnumeration":
            self.widget.setCurrentIndex(self.widget.findText(value))
        else:
            for box, coordinate in zip(self.boxes, (value.x, value.y, value.z)):
                box.setRange(-max(_RANGE, abs(coordinate)), max(_RANGE, abs(coordinate)))
                box.setValue(coordinate)
        self.written = self.shown()  # what the field showed when loaded, or last wrote

    def read(self):
        """The value to write: what the field shows; of a vector, the coordinates the user left
        as they were keep the property's own (not rounded to the field's decimals)."""
        if self.type_id != "App::PropertyVector":
            return self.shown()
        return FreeCAD.Vector(*(old if new == was else new for new, was, old in zip(
            self.shown(), self.written, (self.value.x, self.value.y, self.value.z))))

    def changed(self):
        """Whether the user changed the field since it was loaded. Compared with what the field
        showed, not with the property: a value finer than the field's decimals (0.123456 shown
        as 0.1235) is never written back rounded."""
        return self.shown() != self.written


class ParameterPanel:
    """The task panel (see the module's documentation) editing the object `edited`; `shown` is
    the object whose double-click opened it (a Toolpath opens its Layers object's panel)."""

    def __init__(self, edited, shown=None):
        import MultiAxisSlicer.features as features

        self.obj = edited
        self.shown = shown if shown is not None else edited
        self.doc = edited.Document
        self.form = FreeCADGui.PySideUic.loadUi(MultiAxisSlicerGui.ui_path("ParameterPanel.ui"))
        self.form.setWindowTitle("{} parameters".format(edited.Label))
        self.form.setWindowIcon(self.shown.ViewObject.Icon)
        intro = "Parameters of '{}'.".format(edited.Label)
        if self.shown is not edited:
            intro += " Its paths ('{}') are planned with its layers.".format(self.shown.Label)
        self.form.intro.setText(intro + " Apply recomputes it and what depends on it.")
        self.fields = []
        from PySide import QtGui

        expressions = edited.ExpressionEngine
        for group, props in features.parameters(edited):
            box = QtGui.QGroupBox(group)
            layout = QtGui.QFormLayout(box)
            layout.setRowWrapPolicy(QtGui.QFormLayout.WrapLongRows)  # narrow: field under label
            for prop in props:
                if edited.getTypeIdOfProperty(prop) not in _EDITABLE_TYPES:
                    continue
                field = _Field(edited, prop)
                bound = _expressions_of(expressions, prop)
                if bound:  # the expression sets it (or a coordinate of it) at every recompute
                    field.widget.setEnabled(False)
                    field.widget.setToolTip("Set by the expression {} (the property editor "
                                            "edits it)".format(", ".join(bound)))
                layout.addRow(_label(prop, group), field.widget)
                self.fields.append(field)
            self.form.groups.layout().addWidget(box)
        self.form.apply.clicked.connect(self.apply)
        self.show_result()
        self._begin()
        self.watch = _UndoWatch(self)
        FreeCAD.addDocumentObserver(self.watch)

    def _begin(self):
        """Opens the edit's transaction. Everything the edit changes is one transaction: OK
        commits it (one undo step), Cancel aborts it; the results computed before it are put
        back with the properties."""
        import MultiAxisSlicer.features as features

        objects = self._family()
        self.remembered = features.remembered_results(objects)
        self.computed = {o.Name for o in objects if features.failure(o) is None}
        self.opened = {f.prop: getattr(self.obj, f.prop) for f in self.fields}
        self.doc.openTransaction("Edit '{}'".format(self.obj.Label))
        # The application's transaction (name, id): Undo or Redo, another object's edit or a
        # command beginning (which commits it, as FreeCAD does) can end it before OK or Cancel.
        self.transaction = FreeCAD.getActiveTransaction()
        self.applied = False  # whether Apply wrote a value (recorded in the transaction)

    def _family(self):
        """The edited object and everything made from it."""
        return [self.obj] + self.obj.InListRecursive

    def field(self, prop):
        """The editor of `prop` (for scripts and tests)."""
        return next(f for f in self.fields if f.prop == prop)

    def show_result(self, message=None):
        """The result's figures, or `message` / the object's failure in red."""
        import MultiAxisSlicer.features as features

        problem = message or features.failure(self.obj)
        if problem is None:
            text, style = _summary(self.obj), ""
        else:
            text, style = problem, "color: #c00000"
        self.form.result.setText(text)
        self.form.result.setStyleSheet(style)

    def apply(self):
        """Writes the changed fields and recomputes the object and what depends on it. Returns
        whether it is computed (False too when a property refused a value: shown in the panel)."""
        import MultiAxisSlicer.features as features

        if not self.ours():
            # A command run with the panel open committed the edit's transaction: what was
            # applied before stays, its own undo step; from here the edit is a new one.
            FreeCAD.Console.PrintMessage(
                "Multi-Axis Slicer: what was applied to '{}' before was committed by another "
                "command (Undo takes it back); Cancel now takes back what is applied from "
                "here.\n".format(self.obj.Label))
            self._begin()
        changed = [f for f in self.fields if f.changed()]
        for field in changed:
            try:
                setattr(self.obj, field.prop, field.read())
            except Exception as error:  # a property's own constraint
                self.show_result("{}: {}".format(field.prop, error))
                return False
            self.applied = True
        if changed or features.failure(self.obj) is not None:
            self.doc.recompute([self.obj])
            # A decomposition's Component objects follow its count now, within the edit (the
            # view provider's timer would make them an undo step of their own after OK), before
            # what depends on them is recomputed (a component left over would fail meanwhile).
            for o in self._family():
                if (features.is_decomposition(o) and o.isValid() and
                        len(features.components_of(o)) != o.ComponentCount):
                    features.sync_components(o)
            self.doc.recompute(self.obj.InListRecursive)
        for field in self.fields:  # as the properties hold them now (expressions, limits)
            field.load(self.obj)
        self.show_result()
        return features.failure(self.obj) is None

    # The task dialog's interface (FreeCADGui.Control). Apply is the panel's own button, with the
    # result it shows: with it among OK and Cancel, FreeCAD's button row is wider than a narrow
    # combo view, which then hides the fields' right-hand side.
    def getStandardButtons(self):
        from PySide import QtGui

        return int(QtGui.QDialogButtonBox.Ok | QtGui.QDialogButtonBox.Cancel)

    def accept(self):
        if not self.apply():
            return False  # the message stays in the panel: fix the value, or Cancel
        if self.ours():
            self.doc.commitTransaction()
            FreeCAD.closeActiveTransaction()
        self._close()
        return True

    def reject(self):
        self.undo_edit()
        self._close()
        return True

    def ours(self):
        """Whether the edit's transaction is still the application's active one (never close
        another's: aborting it would take back an edit the user began since)."""
        return self.transaction is not None and FreeCAD.getActiveTransaction() == self.transaction

    def undo_edit(self):
        """Cancel's work: aborts the edit's transaction and puts the results back. When
        something else ended the transaction first, what it recorded is no longer this panel's
        to undo (see ended)."""
        self._finish()
        if not self.ours():
            if self.applied:
                FreeCAD.Console.PrintMessage(
                    "Multi-Axis Slicer: the edit of '{}' had ended already; what was applied "
                    "stays (Undo takes it back).\n".format(self.obj.Label))
            return
        self.doc.abortTransaction()
        # With nothing recorded the document had no transaction to abort, and the application's
        # stayed open: the recompute below would go into it, and become an undo step. (The
        # abort is FreeCAD's, application-wide: it takes back what was changed in another
        # document meanwhile too.)
        FreeCAD.closeActiveTransaction(True)
        if self.ours():
            # FreeCAD takes no abort while it removes the edited object (an Undo of its
            # creation, a script's removeObject end the edit): the transaction is closed once
            # that is done, committed: what it holds (a removal, what was applied) stays, one
            # undo step; after an Undo it holds nothing.
            from PySide import QtCore

            transaction = self.transaction

            def drop():  # not a bound method: its panel would not be kept alive for it
                if FreeCAD.getActiveTransaction() == transaction:
                    FreeCAD.closeActiveTransaction()

            QtCore.QTimer.singleShot(0, drop)
            return
        self._put_back()

    def _put_back(self):
        """The properties are back as they were at open: so are the results."""
        import MultiAxisSlicer.features as features

        features.restore_results(self.remembered)
        # The objects that were computed when the panel opened are made so again, when the abort
        # left one touched, from the results put back, without computing them anew (all of
        # them: one recomputed touches those made from it); those that were not stay as they
        # were.
        objects = [o for o in self._family() if o.Name in self.computed]
        if any("Touched" in o.State or not o.isValid() for o in objects):
            self.doc.recompute(objects)

    def ended(self, undone):
        """Undo or Redo in the document ended the edit (the undo watch): an Undo that took back
        what was applied puts the results back too; the panel closes either way, its fields no
        longer what the properties hold."""
        if _open_panel is not self:
            return
        self._finish()
        if self.ours():  # nothing was recorded: Undo or Redo went to the steps before
            FreeCAD.closeActiveTransaction(True)
        try:  # the Undo took back what was applied (not a later step, then undone)
            taken = undone and self.applied and all(
                getattr(self.obj, prop) == value for prop, value in self.opened.items())
        except Exception:  # the object is gone
            taken = False
        if taken:
            self._put_back()
        FreeCAD.Console.PrintMessage("Multi-Axis Slicer: {} ended the edit of '{}'{}.\n".format(
            "Undo" if undone else "Redo", self.obj.Label,
            " and took back what was applied" if taken else ""))
        self._close()

    def _finish(self):
        """The panel is no longer the open one."""
        global _open_panel
        if _open_panel is self:
            _open_panel = None  # so that unsetEdit does not undo it
        if self.watch is not None:
            FreeCAD.removeDocumentObserver(self.watch)
            self.watch = None

    def _close(self):
        self._finish()
        if self.form is None and FreeCADGui.Control.activeDialog():
            return  # a script closed this panel's dialog: the one shown now is another's
        gui_doc = FreeCADGui.getDocument(self.doc.Name)
        if gui_doc is not None:
            gui_doc.resetEdit()  # whichever view is active (getInEdit() sees the 3D view only)
        FreeCADGui.Control.closeDialog()


class _UndoWatch:
    """A document observer: Undo or Redo in the edited document while the panel is open ends
    the edit (FreeCAD commits the open transaction first; an Undo then takes it back). The panel
    closes once the undo is done."""

    def __init__(self, panel):
        self.panel = panel

    def slotUndoDocument(self, doc):
        self._ended(doc, True)

    def slotRedoDocument(self, doc):
        self._ended(doc, False)

    def _ended(self, doc, undone):
        from PySide import QtCore

        panel = self.panel
        if doc.Name == panel.doc.Name and _open_panel is panel:
            QtCore.QTimer.singleShot(0, lambda: panel.ended(undone))


def _say_task_open(obj):
    """The message for an edit asked for while a task is open in the task view."""
    MultiAxisSlicerGui.show_error(
        "Finish the task open in the task view (OK or Cancel), then edit '{}'.".format(obj.Label))


def edited_object(obj):
    """The object whose parameters `obj`'s panel edits: itself, or a Toolpath's Layers object."""
    import MultiAxisSlicer.features as features

    if features.is_toolpath(obj):
        return obj.Layers
    return obj


def edit(obj):
    """Double-click and "Edit parameters...": opens the parameter panel of `obj` in edit mode.
    With a panel or another task open, says so and leaves it as it is (FreeCAD's setEdit would
    end the open edit first, which undoes an edit applied and not yet confirmed)."""
    panel = _open_panel
    if panel is not None and (panel.form is None or not FreeCADGui.Control.activeDialog()):
        # A script closed the task dialog without OK or Cancel (FreeCAD sets the form of a
        # dialog it deleted to None): the edit ends as by Cancel.
        close_panel()
        gui_doc = FreeCADGui.getDocument(panel.doc.Name)
        if gui_doc is not None and not FreeCADGui.Control.activeDialog():
            gui_doc.resetEdit()
        panel = None
    if panel is not None and panel.obj is edited_object(obj):
        return True  # its panel is open already
    if panel is not None or FreeCADGui.Control.activeDialog():
        _say_task_open(obj)
        return True
    FreeCADGui.getDocument(obj.Document.Name).setEdit(obj.Name, 0)
    return True


def open_panel(obj):
    """Shows the parameter panel of `obj` (see edited_object) in the task view (the view
    provider's setEdit). Returns False, saying why, when it cannot: another task is open, or there
    is nothing to edit."""
    global _open_panel
    import MultiAxisSlicer.features as features

    if FreeCADGui.Control.activeDialog():
        _say_task_open(obj)
        return False
    edited = edited_object(obj)
    if edited is None or not features.parameters(edited):
        MultiAxisSlicerGui.show_error("'{}' has no parameters to edit{}.".format(
            obj.Label, ": its Layers link is not set" if edited is None else ""))
        return False
    _open_panel = ParameterPanel(edited, obj)
    FreeCADGui.Control.showDialog(_open_panel)
    return True


def close_panel():
    """The edit ends (the view provider's unsetEdit). When neither OK nor Cancel ended it (the
    document closes, a script resets the edit, another object's edit begins in it, as a
    sketch's), the edit is undone as by Cancel, and the panel closed: an open transaction left
    behind would take in whatever is done next. When another object's edit opened its own
    transaction first (a part's Transform), FreeCAD has committed the edit's: what was applied
    stays, one undo step, and the other edit's transaction is left to it. When the edited object
    is being removed (a script, an Undo of its creation), FreeCAD takes no abort: the removal
    and what was applied stay, one undo step (undo_edit). After OK or Cancel there is nothing
    left to do."""
    panel = _open_panel
    if panel is None:
        return
    try:
        panel.undo_edit()
    except Exception as error:  # the document is going away
        FreeCAD.Console.PrintLog("Multi-Axis Slicer: edit left: {}\n".format(error))
    if panel.form is not None:  # else a script closed it, and the dialog shown is another's
        FreeCADGui.Control.closeDialog()
