# SPDX-License-Identifier: LGPL-2.1-or-later
"""Feedback and Cancel while the engine decomposes or slices in the GUI.

The document objects (MultiAxisSlicer.features) report their recomputes through
``MultiAxisSlicer.progress.reporting()``; ``install()`` makes that a ``ProgressDialog``: nothing for a
recompute shorter than ``SHOW_AFTER`` seconds (the window still repaints), then a modal dialog with
the stage, a bar and a Cancel button. Cancel stops the engine at its next report (at most a layer
or a split away); the object then fails with "cancelled by the user", its inputs untouched, and a
recompute runs it again. The commands instead undo what they created (commands.py).

Events are processed from the engine's reports, on the GUI thread (the engine reports from the
thread that called it): at most every ``INTERVAL`` seconds, and without user input until the modal
dialog is up, so that nothing but Cancel can reach the document while it recomputes.
"""

import time

import MultiAxisSlicer.progress as _progress
from PySide import QtCore, QtGui

SHOW_AFTER = 0.5  # s: a recompute quicker than this shows no dialog
INTERVAL = 0.05  # s between two rounds of event processing
_RANGE = 1000  # the bar's steps

_cancels = 0  # how many recomputes the user cancelled in this session


def cancel_count():
    """How many recomputes were cancelled from the dialog so far (a command compares it before
    and after a recompute to tell a cancel from a failure)."""
    return _cancels


class ProgressDialog:
    """A progress callback (``progress(fraction, stage)``) for one computation, used as a context
    manager around it. Raises ``MultiAxisSlicer.Cancelled`` from the callback once the user pressed
    Cancel."""

    def __init__(self, title):
        self.title = title
        self.dialog = None
        self.start = 0.0
        self.last = 0.0

    def __enter__(self):
        self.start = self.last = time.monotonic()
        return self

    def __call__(self, fraction, stage):
        if self.dialog is not None and self.dialog.wasCanceled():
            self._cancelled()
        now = time.monotonic()
        if now - self.last < INTERVAL:
            return
        self.last = now
        app = QtGui.QApplication.instance()
        if self.dialog is None:
            if now - self.start < SHOW_AFTER:
                app.processEvents(QtCore.QEventLoop.ExcludeUserInputEvents)
                return
            self._show()
        self.dialog.setLabelText("{}\n{}".format(self.title, stage) if stage else self.title)
        self.dialog.setValue(int(round(min(max(fraction, 0.0), 1.0) * _RANGE)))
        app.processEvents()
        if self.dialog.wasCanceled():
            self._cancelled()

    def _show(self):
        import FreeCADGui

        dialog = QtGui.QProgressDialog(self.title, "Cancel", 0, _RANGE, FreeCADGui.getMainWindow())
        dialog.setObjectName("MultiAxisSlicerProgress")
        dialog.setWindowTitle("Multi-Axis Slicer")
        dialog.setWindowModality(QtCore.Qt.ApplicationModal)
        dialog.setMinimumDuration(0)
        dialog.setAutoClose(False)
        dialog.setAutoReset(False)
        dialog.setMinimumWidth(360)  # the stage's text changes: no jumping size
        dialog.show()
        # A command may have set the wait cursor: Cancel takes an ordinary pointer.
        QtGui.QApplication.setOverrideCursor(QtCore.Qt.ArrowCursor)  # until __exit__
        self.dialog = dialog

    def _cancelled(self):
        global _cancels
        _cancels += 1
        raise _progress.Cancelled("cancelled by the user; recompute to run it again")

    def __exit__(self, *exc):
        if self.dialog is not None:
            QtGui.QApplication.restoreOverrideCursor()
            self.dialog.close()
            self.dialog.deleteLater()
            self.dialog = None
        return False


def install():
    """Makes the document objects' recomputes report to a ProgressDialog (idempotent)."""
    _progress.set_reporter(ProgressDialog)
