# SPDX-License-Identifier: LGPL-2.1-or-later
"""Multi-Axis Slicer's FreeCAD GUI: commands, view providers and icons.

Depends on the scripting API (the MultiAxisSlicer package), never the reverse. Importing this
package is cheap and needs no GUI; `commands` and `view_providers` need FreeCADGui.
"""

import os

# <add-on root>/Gui/MultiAxisSlicerGui/__init__.py -> <add-on root>/Resources/icons
ICON_DIR = os.path.join(
    os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__)))),
    "Resources",
    "icons",
)


UI_DIR = os.path.join(os.path.dirname(ICON_DIR), "ui")


def ui_path(name):
    """Full path of a Qt Designer form in Resources/ui, e.g. ui_path("ParameterPanel.ui")."""
    return os.path.join(UI_DIR, name)


def icon_path(name):
    """Full path of an icon in Resources/icons, e.g. icon_path("Sections.svg")."""
    return os.path.join(ICON_DIR, name)


def show_error(message, title="Multi-Axis Slicer"):
    """Reports an error to the user: always on the report view / console, and in a non-modal
    message box when the GUI is up (non-modal so that scripted and test runs never block)."""
    import FreeCAD

    FreeCAD.Console.PrintError(message.rstrip("\n") + "\n")
    if not FreeCAD.GuiUp:
        return
    import FreeCADGui
    from PySide import QtCore, QtGui

    box = QtGui.QMessageBox(QtGui.QMessageBox.Critical, title, message, QtGui.QMessageBox.Ok,
                            FreeCADGui.getMainWindow())
    box.setObjectName("MultiAxisSlicerError")
    box.setAttribute(QtCore.Qt.WA_DeleteOnClose)
    box.setModal(False)
    box.show()
