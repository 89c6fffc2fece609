# SPDX-License-Identifier: LGPL-2.1-or-later
"""The post-processor from scripts (MultiAxisSlicer.gcode) and as a document object
(MachineProgram), in freecadcmd: the program, its figures, bad machine parameters."""

import math
import os
import tempfile
import unittest

import FreeCAD

import MultiAxisSlicer as mas
import MultiAxisSlicerTestSupport as support
from MultiAxisSlicerTestSupport import l_block


def table_turns(v, a_deg, c_deg):
    """Where the table at (A, C) turns a part vector: LinuxCNC's xyzac-trt-kins, Rx(A) Rz(C)."""
    a, c = math.radians(a_deg), math.radians(c_deg)
    x = math.cos(c) * v[0] - math.sin(c) * v[1]
    y = math.sin(c) * v[0] + math.cos(c) * v[1]
    return (x, math.cos(a) * y - math.sin(a) * v[2], math.sin(a) * y + math.cos(a) * v[2])


def deposit_moves(text):
    """[(x, y, z, a, c, f)] of the moves made with the deposition output on (M62 .. M63)."""
    state = {"X": 0.0, "Y": 0.0, "Z": 0.0, "A": 0.0, "C": 0.0, "F": 0.0}
    on, out = False, []
    for line in text.splitlines():
        line = line.split("(", 1)[0].split()
        if not line:
            continue
        if line[0] == "M62":
            on = True
        elif line[0] in ("M63", "M65"):
            on = False
        elif line[0] in ("G0", "G1"):
            for word in line[1:]:
                state[word[0]] = float(word[1:])
            if on:
                out.append(tuple(state[k] for k in "XYZACF"))
    return out


def without_plate_line(text):
    """A program without its header's line on the build plate (written when the plate is known)."""
    lines = text.splitlines(keepends=True)
    plate = [line for line in lines if line.startswith("(build plate: ")]
    assert len(plate) == 1, plate
    return "".join(line for line in lines if line not in plate)


class GcodeTest(support.EngineTestCase):
    @classmethod
    def setUpClass(cls):
        cls.result = mas.slice(l_block(), step=2.5)


class TestGcodeApi(GcodeTest):
    def test_every_deposit_point_with_the_table_turned_to_its_layer(self):
        program = mas.gcode(self.result)
        self.assertIsInstance(program, mas.GcodeProgram)
        self.assertEqual(program.machine, mas.MACHINE_DEFAULTS)
        moves = deposit_moves(program.text)
        self.assertEqual(len(moves), program.stats["deposit_moves"])
        expected = []
        for i, layer in enumerate(self.result.layers):
            for path in self.result.paths(i):
                if not path.deposit:
                    continue
                points = path.points
                for a, b in zip(points, points[1:]):
                    if (b - a).Length > 1e-9:
                        expected.append((b, layer.normal))
        # Every layer is 2 mm thick: no move is cut in pieces for its feed, one move per point.
        self.assertEqual(len(moves), len(expected))
        for (x, y, z, a, c, _f), (point, normal) in zip(moves, expected):
            self.assertAlmostEqual(table_turns(normal, a, c)[2], 1.0, places=6)
            self.assertLessEqual(max(abs(x - point.x), abs(y - point.y), abs(z - point.z)),
                                 0.5e-4 + 1e-9)
        self.assertEqual(program.stats["a_range_deg"], (-90.0, 0.0))
        self.assertAlmostEqual(program.stats["deposit_length_mm"],
                               self.result.stats["deposit_length_mm"], places=6)
        self.assertEqual(program.stats["lines"], len(program.text.splitlines()))
        self.assertEqual(str(program), program.text)
        # The result's build plate (the L-block stands on Z = 0) is said in the header.
        self.assertIn("(build plate: the part stands on its plane Z0; set G54's Z on the plate's "
                      "surface)", program.text.splitlines()[:6])

    def test_the_same_program_as_the_command_line(self):
        """Scripting and the command line run one engine on the same layers: the same text."""
        with support.scratch_folder("mas_gcode_") as folder:
            part = os.path.join(folder, "l.brep")
            l_block().exportBrep(part)
            result = mas.slice(part, step=2.5)
            ngc = os.path.join(folder, "l.ngc")
            self.cli_json(folder, "slice", part, "--step", "2.5", "--gcode", ngc, "--feed", "750",
                          "--clearance", "4")
            with open(ngc) as f:
                self.assertEqual(result.gcode(feed=750, clearance=4).text, f.read())

    def test_write_and_machine_parameters(self):
        Q = FreeCAD.Units.Quantity
        program = self.result.gcode(feed=Q("15 mm/s"), max_feed_ratio=1, deposit_output=5,
                                    a_min=Q("-120 deg"), a_max=120, clearance=Q("0.5 cm"))
        self.assertEqual(program.machine["feed"], 900.0)  # a quantity in its own unit
        self.assertEqual(program.machine["clearance"], 5.0)
        self.assertEqual(program.machine["a_min"], -120.0)
        self.assertEqual({m[5] for m in deposit_moves(program.text)}, {900.0})
        self.assertIn("M62 P5", program.text)
        with self.assertRaisesRegex(TypeError, "feed must be .* a velocity quantity, got a length"):
            self.result.gcode(feed=Q("900 mm"))
        with self.assertRaisesRegex(TypeError, "a_max must be .* an angle quantity, got a length"):
            self.result.gcode(a_max=Q("5 mm"))
        with support.scratch_folder("mas_gcode_") as folder:
            path = os.path.join(folder, "l.ngc")
            program.write(path)
            with open(path) as f:
                self.assertEqual(f.read(), program.text)
            self.assertEqual(os.listdir(folder), ["l.ngc"])
            missing = os.path.join(folder, "missing", "l.ngc")
            with self.assertRaises(FileNotFoundError) as caught:
                program.write(missing)
            self.assertEqual(caught.exception.filename, missing)  # not the temporary file's
            self.assertIn("No such file or directory: '{}'".format(missing), str(caught.exception))
            self.assertEqual(os.listdir(folder), ["l.ngc"])
            # Permissions: a new file's follow the umask, an existing file keeps its own.
            umask = os.umask(0o022)
            try:
                os.remove(path)
                program.write(path)
                self.assertEqual(os.stat(path).st_mode & 0o777, 0o644)
                os.chmod(path, 0o640)
                program.write(path)
                self.assertEqual(os.stat(path).st_mode & 0o777, 0o640)
            finally:
                os.umask(umask)
            # Through a symbolic link the file it names is written; a folder is refused.
            link = os.path.join(folder, "link.ngc")
            os.symlink(path, link)
            with open(path, "w") as f:
                f.write("old")
            program.write(link)
            self.assertTrue(os.path.islink(link))
            with open(path) as f:
                self.assertEqual(f.read(), program.text)
            with self.assertRaisesRegex(IsADirectoryError, "is a folder"):
                program.write(folder)
            with self.assertRaisesRegex(IsADirectoryError, "is a folder"):
                program.write(os.path.join(folder, "l.ngc") + os.sep)
            self.assertEqual(sorted(os.listdir(folder)), ["l.ngc", "link.ngc"])

    def test_progress_and_cancel(self):
        # Reports come at most every 10 ms (and at the end): few on a fast program.
        seen = []
        self.result.gcode(progress=lambda f, stage: seen.append(f))
        self.assertTrue(seen)
        self.assertEqual(seen, sorted(seen))
        self.assertEqual(seen[-1], 1.0)

        def stop(fraction, stage):
            raise mas.Cancelled("enough")

        with self.assertRaisesRegex(mas.Cancelled, "enough"):
            self.result.gcode(progress=stop)

    def test_the_machines_travel_is_reported_and_checked(self):
        """The joints' ranges (xyzac-trt-kins with the work offset, pivot and tool length) hold
        every move's end; limits at those ranges pass, and a limit the program passes is an
        error naming the axis, its range and the layer."""
        Q = FreeCAD.Units.Quantity
        place = dict(work_offset_x=Q("-2 cm"), work_offset_y=35, work_offset_z=-60,
                     rot_point_x=5, rot_point_y=-10, rot_point_z=8, rot_offset_y=20,
                     rot_offset_z=10, tool_length=40)
        program = self.result.gcode(**place)
        self.assertEqual(program.machine["work_offset_x"], -20.0)
        self.assertIsNone(program.machine["z_max"])
        self.assertNotIn("machine travel checked", program.text)
        s = program.stats

        def joints(x, y, z, a_deg, c_deg):
            # The world point turned by C about the vertical line through the rot point, tilted
            # by A about the line along X through its y and z plus the offsets.
            a, c = math.radians(a_deg), math.radians(c_deg)
            wx, wy, wz = x - 20, y + 35, z - 60
            dx, dy = wx - 5, wy + 10
            xc, yc = math.cos(c) * dx - math.sin(c) * dy + 5, math.sin(c) * dx + math.cos(c) * dy - 10
            ya, za = -10 + 20, 8 + 10
            return (xc, math.cos(a) * (yc - ya) - math.sin(a) * (wz - za) + ya,
                    math.sin(a) * (yc - ya) + math.cos(a) * (wz - za) + za + 40)

        state = {"X": 0.0, "Y": 0.0, "Z": 0.0, "A": 0.0, "C": 0.0}
        ends = []
        for line in program.text.splitlines():
            words = line.split("(", 1)[0].split()
            if words and words[0] in ("G0", "G1"):
                for word in words[1:]:
                    if word[0] in state:
                        state[word[0]] = float(word[1:])
                ends.append(joints(*(state[k] for k in "XYZAC")))
        # The words' rounding: 0.5e-4 mm, and 0.5e-4 degrees at up to 300 mm from the axes.
        tol = 0.5e-4 + 300 * math.radians(0.5e-4)
        for axis, name in enumerate("xyz"):
            lo, hi = s[name + "_range_mm"]
            self.assertLessEqual(lo, min(e[axis] for e in ends) + tol)
            self.assertGreaterEqual(hi, max(e[axis] for e in ends) - tol)
        # The arm is built along +X, the table tilted 90 degrees: Z's range is not the part's
        # height plus the offsets.
        self.assertEqual(s["a_range_deg"][0], -90.0)
        limits = dict(x_min=s["x_range_mm"][0], x_max=s["x_range_mm"][1],
                      y_min=s["y_range_mm"][0], y_max=s["y_range_mm"][1],
                      z_min=s["z_range_mm"][0], z_max=s["z_range_mm"][1])
        checked = self.result.gcode(**place, **limits)
        self.assertEqual(checked.stats["z_range_mm"], s["z_range_mm"])
        self.assertIn("(machine travel checked: X ", checked.text)
        e = self.assertRaisesEngineError("out_of_travel", self.result.gcode, **place,
                                         **dict(limits, z_max=s["z_range_mm"][1] - 1))
        self.assertRegex(str(e), r"^the program leaves the machine's travel \(G54 "
                         r"at \(-20 35 -60\)\): it takes Z from \S+ to \S+ mm, beyond the Z "
                         r"limits \S+ to \S+, first (at layer \d+ \(component \d+\)|on the way off "
                         r"the part); move the part on the table")
        self.assertNotIn("takes X", str(e))
        # A limit of its own: the others stay unchecked.
        self.assertRaisesEngineError("out_of_travel", self.result.gcode, **place,
                                     x_max=s["x_range_mm"][1] - 1)
        self.result.gcode(**place, x_max=s["x_range_mm"][1] + 1e-6, y_min=float("-inf"))
        self.assertRaisesEngineError("invalid_argument", self.result.gcode, z_min=5, z_max=5)
        self.assertRaisesEngineError("invalid_argument", self.result.gcode, x_max=math.nan)
        self.assertRaisesEngineError("invalid_argument", self.result.gcode,
                                     work_offset_y=math.inf)
        with self.assertRaisesRegex(TypeError, "tool_length must be .* a length quantity, got an "
                                    "angle"):
            self.result.gcode(tool_length=Q("3 deg"))
        with self.assertRaisesRegex(TypeError, "x_min must be a number"):
            self.result.gcode(x_min="far")

    def test_bad_machine_parameters(self):
        e = self.assertRaisesEngineError("unreachable_orientation", self.result.gcode, a_min=-45,
                                         a_max=45)
        self.assertIn("component 1", str(e))
        self.assertIn("tilted 90 degrees", str(e))
        self.assertRaisesEngineError("invalid_argument", self.result.gcode, feed=0)
        self.assertRaisesEngineError("invalid_argument", self.result.gcode, a_min=10, a_max=0)
        self.assertRaisesEngineError("invalid_argument", self.result.gcode, clearance=math.nan)
        # The travel is checked against the slice's nozzle: at most 1e4 of its margins (2 mm).
        e = self.assertRaisesEngineError("invalid_argument", self.result.gcode, clearance=1e9)
        self.assertIn("clearance 1e+09 mm is more than 10000 times the nozzle's margin (2 mm)",
                      str(e))
        self.assertRaisesEngineError("invalid_argument", self.result.gcode, deposit_output=64)
        e = self.assertRaisesEngineError("invalid_argument", self.result.gcode,
                                         deposit_output=2**40)
        self.assertIn("digital output 0 to 63, got 1099511627776", str(e))
        e = self.assertRaisesEngineError("invalid_argument", self.result.gcode, feed=1e-300)
        self.assertIn("feed range", str(e))
        with self.assertRaisesRegex(TypeError, "unknown machine parameter.*fed"):
            self.result.gcode(fed=10)
        with self.assertRaisesRegex(TypeError, "feed must be a number"):
            self.result.gcode(feed="fast")
        with self.assertRaisesRegex(TypeError, "deposit_output must be an integer"):
            self.result.gcode(deposit_output=1.5)
        with self.assertRaisesRegex(TypeError, "needs a SliceResult"):
            mas.gcode(l_block())
        with self.assertRaisesRegex(TypeError, "progress"):
            self.result.gcode(progress=3)
        # The engine's own layer: no bools for numbers; the machine defaults when not given.
        engine = mas._engine
        layers = self.result._data["layers"]
        self.assertRaisesEngineError("invalid_argument", engine.write_gcode, layers,
                                     {"deposit_output": True})
        broken = [dict(layers[0], component=True)]
        self.assertRaisesEngineError("invalid_argument", engine.write_gcode, broken)
        # The same program but for the header's build plate, which the engine is not given here.
        self.assertEqual(engine.write_gcode(layers)["text"],
                         without_plate_line(mas.gcode(self.result).text))



def rectangle(x0, y0, x1, y1, z):
    return [(x0, y0, z), (x1, y0, z), (x1, y1, z), (x0, y1, z)]


def layer_dict(component, origin_z, thickness, regions, paths):
    """A layer as slice_part() gives it, horizontal: its top at origin_z, `thickness` deep."""
    return {"component": component, "tool_axis": (0, 0, 1), "max_thickness_mm": thickness,
            "origin": (0, 0, origin_z), "normal": (0, 0, 1),
            "lower_origin": (0, 0, origin_z - thickness), "lower_normal": (0, 0, 1),
            "regions": [{"outer": r, "holes": []} for r in regions],
            "paths": [{"kind": "contour", "points": p, "thickness_mm": [thickness] * len(p)}
                      for p in paths]}


class TestTravelCheck(GcodeTest):
    # A wall 30 mm tall, then a layer of another component with a pad each side of it.
    WALL = layer_dict(0, 30.0, 30.0, [rectangle(-2, -20, 2, 20, 30)], [[(0, -18, 30), (0, 18, 30)]])
    PADS = layer_dict(1, 2.0, 2.0, [rectangle(-37, -6, -33, 6, 2), rectangle(33, -6, 37, 6, 2)],
                      [[(-35, -5, 2), (-35, 5, 2)], [(35, 5, 2), (35, -5, 2)]])
    PLATE = ((0, 0, 0), (0, 0, 1))

    def test_a_way_over_a_deposited_wall_goes_round_the_part(self):
        engine = mas._engine
        checked = engine.write_gcode([self.WALL, self.PADS], {}, None, {}, self.PLATE)
        s = checked["stats"]
        self.assertEqual((s["checked_routes"], s["rerouted_travels"], s["travel_collisions"]),
                         (4, 1, []))
        self.assertIn("(the way within the component meets layer 0: round the part instead)",
                      checked["text"])
        # Between the pads the nozzle rises over the sphere round the part.
        text = checked["text"]
        between = text[text.index("X-35.0000 Y5.0000"):text.index("X35.0000 Y5.0000 Z2.0000")]
        tops = [float(w[1:]) for w in between.split() if w.startswith("Z")]
        self.assertGreater(max(tops), 60.0)
        unchecked = engine.write_gcode([self.WALL, self.PADS])
        self.assertEqual((unchecked["stats"]["checked_routes"],
                          unchecked["stats"]["rerouted_travels"]), (0, 0))
        self.assertNotIn("round the part instead", unchecked["text"])
        # A nozzle 80 mm across, widening at 80 degrees, reaches the wall from over the pads,
        # whichever way it goes: reported.
        wide = engine.write_gcode([self.WALL, self.PADS], {}, None,
                                  {"nozzle_body_diameter": 80.0, "nozzle_cone_angle": 80.0},
                                  self.PLATE)["stats"]
        self.assertGreater(len(wide["travel_collisions"]), 0)
        for c in wide["travel_collisions"]:
            self.assertEqual(c["obstacle_layer"], 0)
            self.assertEqual(len(c["nozzle_at"]), 3)

    def test_a_route_down_onto_a_layer_lying_just_clear_of_the_plate_is_not_reported(self):
        # A column's layer along +Z, then a layer built sideways off its -X face along -X, its
        # lowest path 27.05 mm up: the nozzle lying on its side there keeps 2.05 mm (the margin and
        # 2.5 %) under its body (25 mm round the axis). The route comes down the sphere round the
        # part turning the table from A 0 to A -90, ending with the nozzle on its side at the
        # height of that path. Judged by each turning piece's first axis within its allowance
        # (0.1 mm), the last piece of that route and the first of the route off the part were
        # reported as meeting the plate; judged from both their ends, they pass. 1.95 mm over the plate (at 26.95), the routes to that layer and off the part
        # from it are reported, the plate met.
        engine = mas._engine
        column = layer_dict(0, 30.0, 30.0, [rectangle(-2, -6, 2, 6, 30)],
                            [[(0, -5, 30), (0, 5, 30)]])

        def sideways(z):
            return {"component": 1, "tool_axis": (-1, 0, 0), "max_thickness_mm": 1.0,
                    "origin": (-3, 0, 0), "normal": (-1, 0, 0),
                    "lower_origin": (-2, 0, 0), "lower_normal": (-1, 0, 0),
                    "regions": [{"outer": [(-3, -5, z), (-3, -5, 29), (-3, 5, 29), (-3, 5, z)],
                                 "holes": []}],
                    "paths": [{"kind": "contour", "points": [(-3, -4, z), (-3, 4, z)],
                               "thickness_mm": [1.0, 1.0]}]}

        clear = engine.write_gcode([column, sideways(27.05)], {}, None, {}, self.PLATE)
        self.assertEqual(clear["stats"]["travel_collisions"], [])
        self.assertIn("A-90.0000", clear["text"])
        # 2.03 mm over the plate (the margin and 1.5 %) the bound of the finer pass's last piece
        # dips under the margin between its ends by up to half its allowance (0.1 mm); cut finer
        # again where it does, that piece passes too.
        closer = engine.write_gcode([column, sideways(27.03)], {}, None, {}, self.PLATE)
        self.assertEqual(closer["stats"]["travel_collisions"], [])
        met = engine.write_gcode([column, sideways(26.95)], {}, None, {}, self.PLATE)
        collisions = met["stats"]["travel_collisions"]
        self.assertEqual([(c["layer"], c["obstacle_layer"]) for c in collisions],
                         [(1, -1), (-1, -1)])
        for c in collisions:
            self.assertAlmostEqual(c["obstacle"][2], 0.0, places=9)

    def test_gcode_checks_against_the_results_nozzle_and_plate(self):
        program = mas.gcode(self.result)
        s = program.stats
        self.assertEqual(s["checked_routes"], program.text.count("M62 P0") + 1)
        self.assertEqual((s["rerouted_travels"], s["travel_collisions"]), (0, []))
        # A result without its plate (from before the plate was kept) is written unchecked.
        data = dict(self.result._data)
        del data["plate_origin"], data["plate_normal"]
        old = mas.SliceResult(data, self.result.params, self.result.axis, None, "solid")
        self.assertIsNone(old.plate)
        self.assertEqual(mas.gcode(old).stats["checked_routes"], 0)
        self.assertEqual(mas.gcode(old).text, without_plate_line(program.text))

    def test_bad_nozzle_or_plate(self):
        engine = mas._engine
        layers = [self.WALL, self.PADS]
        self.assertRaisesEngineError("invalid_argument", engine.write_gcode, layers, {}, None,
                                     {"nozzle_margin": -1.0}, self.PLATE)
        self.assertRaisesEngineError("invalid_argument", engine.write_gcode, layers, {}, None,
                                     {"nozzle_width": 1.0}, self.PLATE)
        self.assertRaisesEngineError("invalid_argument", engine.write_gcode, layers, {}, None,
                                     {}, None)
        self.assertRaisesEngineError("invalid_argument", engine.write_gcode, layers, {}, None,
                                     {}, ((0, 0, 0), (0, 0, 2)))
        broken = [dict(self.WALL, lower_normal=(0, 0, float("nan"))), self.PADS]
        self.assertRaisesEngineError("invalid_argument", engine.write_gcode, broken, {}, None,
                                     {}, self.PLATE)
        # A layer without its planes cannot be checked; one whose lower plane lies over its top
        # or across it is no prism.
        bare = dict(self.WALL)
        del bare["lower_normal"]
        e = self.assertRaisesEngineError("invalid_argument", engine.write_gcode, [bare, self.PADS],
                                         {}, None, {}, self.PLATE)
        self.assertIn("lower_normal", str(e))
        self.assertEqual(engine.write_gcode([bare, self.PADS])["stats"]["checked_routes"], 0)
        over = dict(self.WALL, lower_origin=(0, 0, 31))
        e = self.assertRaisesEngineError("invalid_argument", engine.write_gcode, [over, self.PADS],
                                         {}, None, {}, self.PLATE)
        self.assertIn("above its top", str(e))
        across = dict(self.WALL, lower_normal=(1, 0, 0))
        e = self.assertRaisesEngineError("invalid_argument", engine.write_gcode,
                                         [across, self.PADS], {}, None, {}, self.PLATE)
        self.assertIn("must face the way its top does", str(e))
        # The plate alone means nothing; as a list it is taken.
        e = self.assertRaisesEngineError("invalid_argument", engine.write_gcode, layers, {}, None,
                                         None, self.PLATE)
        self.assertIn("give the nozzle too", str(e))
        self.assertEqual(
            engine.write_gcode(layers, {}, None, {}, [[0, 0, 0], [0, 0, 1]])["text"],
            engine.write_gcode(layers, {}, None, {}, self.PLATE)["text"])


class TestTravelShape(support.EngineTestCase):
    def test_moves_with_the_deposition_off_as_one_polyline_per_run(self):
        import MultiAxisSlicer.features as features

        text = "\n".join([
            "(a comment G0 X99)", "G21 G90", "M65 P0",
            "G0 X0 Y0 Z10 A0 C0", "G0 X1 Y0 Z2", "G1 X1 Y0 Z0 F600",  # run 1: 3 points
            "M62 P0", "G1 X5 Y0 Z0", "G1 X5 Y5 Z0", "M63 P0",        # deposits
            "G0 X5 Y5 Z2", "G0 X9 Y9 Z2 A-90 C180", "M65 P0", "M2"])  # run 2: from (5, 5, 0)
        shape = features.program_travel_shape(text)
        wires = shape.Wires
        self.assertEqual(len(wires), 2)
        self.assertEqual([tuple(v.Point) for v in wires[0].OrderedVertexes],
                         [(0, 0, 10), (1, 0, 2), (1, 0, 0)])
        self.assertEqual([tuple(v.Point) for v in wires[1].OrderedVertexes],
                         [(5, 5, 0), (5, 5, 2), (9, 9, 2)])


class TestMachineProgramObject(support.EngineTestCase):
    def setUp(self):
        (self.doc, self.part, self.decomposition, self.layers,
         self.toolpath) = support.sliced_l_block_document("MasGcode")
        self.folder = tempfile.mkdtemp(prefix="mas_gcode_doc_")

    def tearDown(self):
        import shutil

        for name in list(FreeCAD.listDocuments()):
            if name.startswith("MasGcode"):
                FreeCAD.closeDocument(name)
        shutil.rmtree(self.folder)

    def test_the_program_of_the_layers_with_its_figures_and_export(self):
        import MultiAxisSlicer.features as features

        program_obj = mas.make_machine_program(self.toolpath, feed=750)  # a Toolpath stands in
        self.assertIs(program_obj.Layers, self.layers)
        self.doc.recompute()
        self.assertTrue(program_obj.isValid(), program_obj.getStatusString())
        self.assertEqual(program_obj.Proxy.Type, "MultiAxisSlicer::MachineProgram")
        self.assertEqual(program_obj.Feed, 750.0)
        self.assertEqual(program_obj.AMin.Value, -100.0)
        expected = features.slice_result(self.layers).gcode(feed=750)
        self.assertEqual(program_obj.LineCount, expected.stats["lines"])
        self.assertEqual(program_obj.DepositMoves, expected.stats["deposit_moves"])
        self.assertEqual(list(program_obj.ARange), [-90.0, 0.0])
        self.assertAlmostEqual(program_obj.DepositLength.Value,
                               self.toolpath.PathLength.Value, delta=1e-6)
        self.assertAlmostEqual(program_obj.DepositTime,
                               expected.stats["deposit_time_min"], places=9)
        self.assertGreater(len(program_obj.Shape.Wires), self.layers.LayerCount)
        # The travel, checked against the Layers' nozzle: every route, none meeting anything.
        self.assertEqual(program_obj.CheckedRoutes, expected.stats["checked_routes"])
        self.assertEqual(program_obj.CheckedRoutes, expected.text.count("M62 P0") + 1)
        self.assertEqual(program_obj.ReroutedTravels, 0)
        self.assertEqual(program_obj.TravelCollisions, 0)
        path = os.path.join(self.folder, "l.ngc")
        features.export_gcode(program_obj, path)
        with open(path) as f:
            self.assertEqual(f.read(), expected.text)
        self.assertEqual(program_obj.Name, "MachineProgram")
        # The layers are read, never changed.
        self.assertNotIn("Touched", self.layers.State)

    def test_a_machine_that_cannot_reach_marks_the_object_until_fixed(self):
        import MultiAxisSlicer.features as features

        program_obj = mas.make_machine_program(self.layers)
        self.doc.recompute()
        program_obj.AMin = -45
        program_obj.AMax = 45
        self.doc.recompute()
        self.assertIn("Invalid", program_obj.State)
        status = program_obj.getStatusString()
        self.assertIn("component 1", status)
        self.assertIn("beyond AMin and AMax -45 to 45", status)
        with self.assertRaisesRegex(ValueError, "AMin and AMax"):
            features.export_gcode(program_obj, os.path.join(self.folder, "x.ngc"))
        self.assertEqual(os.listdir(self.folder), [])
        program_obj.AMin = -100
        program_obj.Feed = 0
        self.doc.recompute()
        self.assertIn("Invalid", program_obj.State)
        self.assertIn("Feed must be > 0", program_obj.getStatusString())
        program_obj.Feed = 600
        program_obj.DepositOutput = 2**40
        self.doc.recompute()
        self.assertIn("DepositOutput must be a digital output 0 to 63",
                      program_obj.getStatusString())
        program_obj.DepositOutput = 0
        program_obj.Clearance = 1e9  # the margin is the Layers object's
        self.doc.recompute()
        self.assertIn("Clearance 1e+09 mm is more than 10000 times the Layers' NozzleMargin (2 "
                      "mm)", program_obj.getStatusString())
        program_obj.Clearance = 2.0
        self.doc.recompute()
        self.assertTrue(program_obj.isValid(), program_obj.getStatusString())
        self.assertEqual(list(program_obj.ARange), [-90.0, 0.0])

    def test_the_machines_travel_on_the_object(self):
        """The travel limits as properties: off by default, the ranges reported; checked, a
        limit passed marks the object naming its properties; limits from a script check those
        given only; all of it survives save and reopen."""
        import MultiAxisSlicer.features as features

        program_obj = mas.make_machine_program(self.layers, work_offset_z=-150, tool_length=60)
        self.doc.recompute()
        self.assertTrue(program_obj.isValid(), program_obj.getStatusString())
        self.assertFalse(program_obj.CheckTravel)
        result = features.slice_result(self.layers, computed=True)
        stats = result.gcode(work_offset_z=-150, tool_length=60).stats
        for prop, name in (("XRange", "x_range_mm"), ("YRange", "y_range_mm"),
                           ("ZRange", "z_range_mm")):
            self.assertEqual(tuple(getattr(program_obj, prop)), stats[name])
        # The defaults when checked are LinuxCNC's sample machine's (its joints), where the
        # arm, tilted 90 degrees about A's axis, reaches past Y's least.
        self.assertEqual((program_obj.YMin.Value, program_obj.ZMax.Value), (-100, 120))
        program_obj.CheckTravel = True
        self.doc.recompute()
        self.assertIn("Invalid", program_obj.State)
        self.assertIn("it takes Y from {:g} to".format(stats["y_range_mm"][0]),
                      program_obj.getStatusString())
        self.assertIn("beyond YMin and YMax -100 to 100", program_obj.getStatusString())
        # Limits round the ranges pass; one a millimetre inside fails.
        for axis in "XYZ":
            lo, hi = stats[axis.lower() + "_range_mm"]
            setattr(program_obj, axis + "Min", lo - 1e-9)
            setattr(program_obj, axis + "Max", hi + 1e-9)
        self.doc.recompute()
        self.assertTrue(program_obj.isValid(), program_obj.getStatusString())
        program_obj.ZMin = stats["z_range_mm"][0] + 1
        self.doc.recompute()
        self.assertIn("Invalid", program_obj.State)
        status = program_obj.getStatusString()
        self.assertIn("it takes Z from", status)
        self.assertNotIn("it takes Y", status)
        with self.assertRaisesRegex(ValueError, "leaves the machine's travel"):
            features.export_gcode(program_obj, os.path.join(self.folder, "x.ngc"))
        program_obj.ZMax = program_obj.ZMin.Value
        self.doc.recompute()
        self.assertIn("ZMin and ZMax must have min < max", program_obj.getStatusString())
        program_obj.CheckTravel = False
        self.doc.recompute()
        self.assertTrue(program_obj.isValid(), program_obj.getStatusString())
        # From a script: the limits given are checked, the others none.
        scripted = mas.make_machine_program(self.layers, name="Scripted", work_offset_z=-150,
                                            tool_length=60, z_max=stats["z_range_mm"][1] - 1)
        self.assertTrue(scripted.CheckTravel)
        self.assertEqual(scripted.XMin.Value, -math.inf)
        self.assertEqual(scripted.YMax.Value, math.inf)
        self.doc.recompute()
        self.assertIn("it takes Z from", scripted.getStatusString())
        self.assertRegex(scripted.getStatusString(), r"above ZMax \S+, first ")
        self.assertNotIn("it takes X", scripted.getStatusString())
        scripted.ZMax = stats["z_range_mm"][1]
        self.doc.recompute()
        self.assertTrue(scripted.isValid(), scripted.getStatusString())
        path = os.path.join(self.folder, "travel.FCStd")
        self.doc.saveAs(path)
        FreeCAD.closeDocument(self.doc.Name)
        doc = FreeCAD.openDocument(path)
        try:
            scripted = doc.getObject("Scripted")
            self.assertTrue(scripted.CheckTravel)
            self.assertEqual(scripted.XMin.Value, -math.inf)
            self.assertEqual(scripted.ZMax.Value, stats["z_range_mm"][1])
            self.assertEqual(tuple(scripted.ZRange), stats["z_range_mm"])
            self.assertEqual(doc.getObject("MachineProgram").WorkOffsetZ.Value, -150)
        finally:
            FreeCAD.closeDocument(doc.Name)

    def test_save_reopen_export_and_undo(self):
        import MultiAxisSlicer.features as features

        self.doc.UndoMode = 1
        names = [o.Name for o in self.doc.Objects]
        self.doc.openTransaction("Machine program")
        program_obj = mas.make_machine_program(self.layers, clearance=5, deposit_output=2)
        self.doc.recompute()
        self.doc.commitTransaction()
        before = features.machine_program(program_obj).text
        lines = program_obj.LineCount
        routes = program_obj.CheckedRoutes
        self.assertGreater(routes, 0)
        path = os.path.join(self.folder, "program.FCStd")
        self.doc.saveAs(path)
        FreeCAD.closeDocument(self.doc.Name)

        doc = FreeCAD.openDocument(path)
        program_obj = doc.getObject("MachineProgram")
        self.assertIsInstance(program_obj.Proxy, features.MachineProgramFeature)
        self.assertIs(program_obj.Layers, doc.getObject("Layers"))
        self.assertEqual(program_obj.Clearance.Value, 5.0)
        self.assertEqual(program_obj.DepositOutput, 2)
        self.assertEqual(program_obj.LineCount, lines)
        self.assertEqual(program_obj.CheckedRoutes, routes)
        self.assertEqual(program_obj.TravelCollisions, 0)
        self.assertGreater(len(program_obj.Shape.Edges), 0)  # saved with the document
        self.assertIsNone(getattr(program_obj.Proxy, "_program", None))  # the text is not
        out = os.path.join(self.folder, "after.ngc")
        features.export_gcode(program_obj, out)  # written anew, the slicing redone on demand
        with open(out) as f:
            self.assertEqual(f.read(), before)
        doc.save()

        doc.UndoMode = 1
        doc.openTransaction("Machine program")
        again = mas.make_machine_program(doc.getObject("Layers"), name="Second")
        doc.recompute()
        doc.commitTransaction()
        self.assertTrue(again.isValid(), again.getStatusString())
        doc.undo()
        self.assertIsNone(doc.getObject("Second"))
        self.assertEqual(sorted(o.Name for o in doc.Objects), sorted(names + ["MachineProgram"]))

    def test_a_program_saved_before_the_travel_check_reopens_and_recomputes_it(self):
        program_obj = mas.make_machine_program(self.layers)
        self.doc.recompute()
        routes = program_obj.CheckedRoutes
        for name in ("CheckedRoutes", "ReroutedTravels", "TravelCollisions"):
            program_obj.removeProperty(name)
        path = os.path.join(self.folder, "old_program.FCStd")
        self.doc.saveAs(path)
        FreeCAD.closeDocument(self.doc.Name)
        doc = FreeCAD.openDocument(path)
        try:
            program_obj = doc.getObject("MachineProgram")
            # Computed without the check: none checked, until it is computed again.
            self.assertEqual((program_obj.CheckedRoutes, program_obj.ReroutedTravels,
                              program_obj.TravelCollisions), (0, 0, 0))
            program_obj.touch()
            doc.recompute()
            self.assertTrue(program_obj.isValid(), program_obj.getStatusString())
            self.assertEqual(program_obj.CheckedRoutes, routes)
        finally:
            FreeCAD.closeDocument(doc.Name)

    def test_a_program_whose_layers_changed_is_not_exported_until_recomputed(self):
        import MultiAxisSlicer.features as features

        program_obj = mas.make_machine_program(self.layers)
        self.doc.recompute()
        lines = program_obj.LineCount
        self.layers.MaxLayer = 3.0
        path = os.path.join(self.folder, "l.ngc")
        with self.assertRaisesRegex(ValueError, "not recomputed since 'Layers' changed"):
            features.export_gcode(program_obj, path)
        self.assertEqual(os.listdir(self.folder), [])
        self.doc.recompute()
        self.assertTrue(program_obj.isValid(), program_obj.getStatusString())
        self.assertLess(program_obj.LineCount, lines)  # fewer, thicker layers
        program = features.export_gcode(program_obj, path)
        self.assertEqual(program.stats["lines"], program_obj.LineCount)

    def test_bad_arguments(self):
        with self.assertRaisesRegex(TypeError, "needs a Layers or Toolpath object"):
            mas.make_machine_program(self.part)
        with self.assertRaisesRegex(ValueError, "reference_thickness must be a non-negative"):
            mas.make_machine_program(self.layers, reference_thickness=-1)
        with self.assertRaisesRegex(ValueError, "clearance must be a positive"):
            mas.make_machine_program(self.layers, clearance=0)
        self.toolpath.Layers = None
        with self.assertRaisesRegex(ValueError, "the Toolpath 'Toolpath' has no Layers"):
            mas.make_machine_program(self.toolpath)
        with self.assertRaisesRegex(TypeError, "unknown machine parameter"):
            mas.make_machine_program(self.layers, speed=3)
        with self.assertRaisesRegex(ValueError, "a_min must be between -360 and 360"):
            mas.make_machine_program(self.layers, a_min=-400)
        self.assertEqual([o.Name for o in self.doc.Objects if o.Name.startswith("Machine")], [])


if __name__ == "__main__":
    unittest.main()
