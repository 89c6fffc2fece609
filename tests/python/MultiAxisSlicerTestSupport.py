# SPDX-License-Identifier: LGPL-2.1-or-later
"""What the freecadcmd test modules share: test parts, assertions, running plain Python."""

import contextlib
import json
import os
import shutil
import subprocess
import tempfile
import textwrap
import unittest

import FreeCAD
import Mesh
import Part

import MultiAxisSlicer as mas

V = FreeCAD.Vector


def box_10_20_30():
    """A 10 x 20 x 30 mm box with its corner at (1, 2, 3)."""
    return Part.makeBox(10, 20, 30, V(1, 2, 3))


def l_block():
    """Fig. 7's L: a 20 x 20 x 60 column with a 50 mm arm [20, 70] x [0, 20] x [40, 60] at its
    top, one solid with no seam faces."""
    return Part.makeBox(20, 20, 60).fuse(Part.makeBox(50, 20, 20, V(20, 0, 40))).removeSplitter()


def rod_under_bar():
    """A 16 x 16 x 48 column with a round rod (radius 7, 40 long) reaching +X at z = 20 and a
    6 x 6 bar 52 long reaching +X above it at z = 39 to 45. Built sideways (the default nozzle),
    the rod's nozzle meets the plate unless leaned up, and leaned up it meets the bar unless the
    rod comes first."""
    column = Part.makeBox(16, 16, 48, V(-8, -8, 0))
    return column.fuse([Part.makeCylinder(7, 40, V(0, 0, 20), V(1, 0, 0)),
                        Part.makeBox(52, 6, 6, V(0, -3, 39))]).removeSplitter()


def hub_with_six_blades():
    """A round hub (radius 8.5, 30 tall) with six flat blades 60 degrees apart, the first along +X,
    each 5 thick and 22 tall (z = 4 to 26), reaching 30 past the hub: low over the plate, so that
    a nozzle building a blade sideways must lean up off the plate."""
    solid = Part.makeCylinder(8.5, 30)
    for i in range(6):
        blade = Part.makeBox(34.25, 5, 22, V(4.25, -2.5, 4))
        blade.rotate(V(0, 0, 0), V(0, 0, 1), 60.0 * i)
        solid = solid.fuse(blade)
    return solid.removeSplitter()


def spiral_stair(treads=6):
    """A spiral stair: treads 45 long, 18 wide and 4 thick off a round column (radius 10), 20
    degrees round and 8 mm up from one to the next, the first along +X at z = 6 (the engine's
    Slicing.ASpiralStairsTreadsAreBuiltAlongTheirLinesTheNozzleLeanedOffTheTreadBelow). Cut
    square to their own lines, the treads between +-X and +-Y leave a coaxial nozzle no way to
    their roots; leaned, it reaches them."""
    solid = Part.makeCylinder(10, 8.0 * treads + 10.0)
    for i in range(treads):
        tread = Part.makeBox(45, 18, 4, V(0, -9, 8.0 * i + 6))
        tread.rotate(V(0, 0, 0), V(0, 0, 1), 20.0 * i)
        solid = solid.fuse(tread)
    return solid.removeSplitter()


def pipe_tee():
    """A pipe of radius 10 with a bore of 8, 60 tall along Z, and a branch of the same pipe
    reaching +Y from its axis at z = 35, 35 long (the engine's test_parts.hpp)."""
    outer = Part.makeCylinder(10, 60).fuse(Part.makeCylinder(10, 35, V(0, 0, 35), V(0, 1, 0)))
    bore = Part.makeCylinder(8, 62, V(0, 0, -1)).fuse(
        Part.makeCylinder(8, 36, V(0, 0, 35), V(0, 1, 0)))
    return outer.cut(bore)


def t_block():
    """A T: column [0,20]x[0,20]x[0,60], crossbar [-30,50]x[0,20]x[40,60] reaching both ways."""
    return Part.makeBox(20, 20, 60).fuse(
        Part.makeBox(80, 20, 20, V(-30, 0, 40))).removeSplitter()


def sliced_l_block_document(name):
    """A new document `name` holding the L block ("L"), its Decomposition and its Layers and
    Toolpath objects, computed: (doc, part, decomposition, layers, toolpath)."""
    doc = FreeCAD.newDocument(name)
    part = doc.addObject("Part::Feature", "L")
    part.Shape = l_block()
    doc.recompute()
    decomposition = mas.make_decomposition(part)
    layers, toolpath = mas.make_slice(decomposition)
    doc.recompute()
    return doc, part, decomposition, layers, toolpath


def fc_mesh(shape, deflection=0.1):
    return Mesh.Mesh(shape.tessellate(deflection))


class EngineTestCase(unittest.TestCase):
    def assertVectorAlmostEqual(self, a, b, places=9):
        for i in range(3):
            self.assertAlmostEqual(a[i], b[i], places=places, msg="{} != {}".format(a, b))

    def assertRaisesEngineError(self, code, func, *args, **kwargs):
        """Asserts func(*args, **kwargs) raises EngineError `code` with a message; returns it."""
        with self.assertRaises(mas.EngineError) as cm:
            func(*args, **kwargs)
        self.assertEqual(cm.exception.code, code, str(cm.exception))
        self.assertTrue(str(cm.exception), "an engine error needs a message")
        return cm.exception

    def assertSameJson(self, a, b, where):
        """Equal JSON-ready data; floats to 1e-12 relative (the program prints 15 digits)."""
        if isinstance(a, dict):
            self.assertEqual(set(a), set(b), where)
            for k in a:
                self.assertSameJson(a[k], b[k], where + "." + k)
        elif isinstance(a, list):
            self.assertEqual(len(a), len(b), where)
            for i, (x, y) in enumerate(zip(a, b)):
                self.assertSameJson(x, y, "{}[{}]".format(where, i))
        elif isinstance(a, float) or isinstance(b, float):
            self.assertAlmostEqual(a, b, delta=1e-12 * max(1.0, abs(b)), msg=where)
        else:
            self.assertEqual(a, b, where)

    def cli_json(self, folder, *args):
        """Runs the add-on's multiaxis-slicer with `args` and --json into `folder`; returns the
        parsed output."""
        addon = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(mas.__file__))))
        program = os.path.join(addon, "multiaxis-slicer")
        self.assertTrue(os.path.isfile(program), "no command-line program at " + program)
        out = os.path.join(folder, "out.json")
        result = subprocess.run([program, *args, "--json", out], capture_output=True, text=True,
                                timeout=120)
        self.assertEqual(result.returncode, 0, result.stderr)
        with open(out) as f:
            return json.load(f)


@contextlib.contextmanager
def scratch_folder(prefix):
    folder = tempfile.mkdtemp(prefix=prefix)
    try:
        yield folder
    finally:
        shutil.rmtree(folder)


def write_dedented(folder, name, text):
    """Writes `text`, dedented, to folder/name and returns the path."""
    path = os.path.join(folder, name)
    with open(path, "w") as f:
        f.write(textwrap.dedent(text))
    return path


def run_plain_python(folder, script, path_entry=None):
    """Runs `script` (dedented) from `folder` with FreeCAD's interpreter but without FreeCAD,
    `path_entry` (default: the add-on's App folder) on the path; returns the CompletedProcess."""
    path = write_dedented(folder, "script.py", script)
    if path_entry is None:
        path_entry = os.path.dirname(os.path.dirname(os.path.abspath(mas.__file__)))
    env = dict(os.environ, PYTHONPATH=path_entry)
    return subprocess.run(["/usr/bin/python3.11", path], env=env, capture_output=True, text=True,
                          timeout=120)
