# SPDX-License-Identifier: LGPL-2.1-or-later
"""Adaptive multi-axis slicing through the scripting API (``MultiAxisSlicer.slice``) and the Layers
and Toolpath document objects, inside freecadcmd.

Run: freecadcmd -t TestMultiAxisSlicerSlice (tests/run_freecad_test.sh does it against the add-on
staged in the build tree). The parts are boxes and the L of the decomposition tests: their layers
are planar and parallel, so thicknesses and volumes are exact.
"""

import json
import math
import os
import shutil
import subprocess
import tempfile
import unittest

import FreeCAD
import Part

import MultiAxisSlicer as mas
import MultiAxisSlicer.features as features
import MultiAxisSlicerSurvey as survey
import MultiAxisSlicerTestSupport as support
from MultiAxisSlicerTestSupport import V, fc_mesh, l_block, rod_under_bar

REL = 1e-6  # relative volume tolerance
TOL = 1e-9  # mm: thicknesses of planar layers


def box_20_10_21():
    """21 mm high: ten 2 mm layers and a last one of 1 mm at the default max_layer."""
    return Part.makeBox(20, 10, 21)


class SliceTest(support.EngineTestCase):
    def check_box_layers(self, result):
        """The 20 x 10 x 21 box: 11 layers along +Z, 2 mm thick but the last, 1 mm."""
        self.assertEqual(len(result.layers), 11)
        self.assertEqual(len(result), 11)
        self.assertEqual(result.stats["layer_count"], 11)
        self.assertEqual(len(result.components), 1)
        self.assertEqual(result.components[0]["layer_count"], 11)
        for i, layer in enumerate(result.layers):
            want = 2.0 if i < 10 else 1.0
            self.assertEqual(layer.component, 0)
            self.assertVectorAlmostEqual(layer.normal, (0, 0, 1))
            self.assertAlmostEqual(layer.min_thickness, want, delta=TOL, msg="layer {}".format(i))
            self.assertAlmostEqual(layer.max_thickness, want, delta=TOL, msg="layer {}".format(i))
            self.assertAlmostEqual(layer.origin.z, min(2.0 * (i + 1), 21.0), delta=TOL)
            self.assertAlmostEqual(layer.area, 200.0, delta=200.0 * REL)
        self.assertAlmostEqual(result.stats["deposited_volume_mm3"], 4200.0, delta=4200.0 * REL)
        self.assertAlmostEqual(result.stats["part_volume_mm3"], 4200.0, delta=4200.0 * REL)
        self.assertEqual(result.stats["layers_over_volume_difference"], 0)

    def check_paths(self, result):
        """Every layer has deposit paths on its plane along its normal, travel before each."""
        for i, layer in enumerate(result.layers):
            paths = result.paths(i)
            deposits = [p for p in paths if p.deposit]
            self.assertTrue(deposits, "layer {} has no deposit path".format(i))
            for p in paths:
                self.assertIn(p.kind, ("travel", "contour", "infill", "centre_line"))
                self.assertEqual(p.deposit, p.kind != "travel")
                self.assertVectorAlmostEqual(p.tool_axis, layer.normal)
                self.assertEqual(len(p.thickness), len(p.points))
            for p in deposits:
                for q in p.points:
                    self.assertAlmostEqual((q - layer.origin).dot(layer.normal), 0.0, places=6)


class TestSliceApi(SliceTest):
    def test_box_is_eleven_layers_along_z(self):
        result = mas.slice(box_20_10_21())
        self.assertIsInstance(result, mas.SliceResult)
        self.assertEqual(result.kind, "solid")
        self.assertEqual(len(result.decomposition), 1)
        self.check_box_layers(result)
        self.check_paths(result)
        # The outline of every layer: one region, a 20 x 10 rectangle on its plane.
        for layer in result.layers:
            regions = layer.regions
            self.assertEqual(len(regions), 1)
            self.assertEqual(regions[0]["holes"], [])
            xs = [p.x for p in regions[0]["outer"]]
            ys = [p.y for p in regions[0]["outer"]]
            self.assertAlmostEqual(min(xs), 0.0, places=3)
            self.assertAlmostEqual(max(xs), 20.0, places=3)
            self.assertAlmostEqual(min(ys), 0.0, places=3)
            self.assertAlmostEqual(max(ys), 10.0, places=3)
        self.assertGreater(result.stats["deposit_length_mm"], 0.0)

    def test_a_layers_outline_length_counts_every_loop_holes_too(self):
        """``outline_length``: every loop of a layer, its holes' too (times the deflection, the
        strip hangs_past_strip() allows). A 20 x 10 block with a 6 x 4 square bore: 60 + 20 mm.
        The sections' corners sit on the 1e-5 mm grid: each of the 8 moves two edges by at most
        that much."""
        result = mas.slice(Part.makeBox(20, 10, 6).cut(Part.makeBox(6, 4, 8, V(7, 3, -1))))
        self.assertEqual(len(result.layers), 3)
        for layer in result.layers:
            self.assertEqual([len(r["holes"]) for r in layer.regions], [1])
            self.assertAlmostEqual(layer.outline_length, 80.0, delta=8 * 2 * 1e-5)
            self.assertEqual(layer.to_dict()["outline_length_mm"], layer.outline_length)

    def test_l_block_column_layers_go_up_and_arm_layers_go_out(self):
        result = mas.slice(l_block())
        self.assertEqual(len(result.components), 2)
        column, arm = result.components
        self.assertEqual((column["first_layer"], column["layer_count"]), (0, 30))  # 60 mm / 2
        self.assertEqual((arm["first_layer"], arm["layer_count"]), (30, 25))  # 50 mm / 2
        self.assertAlmostEqual(column["volume_mm3"], 24000.0, delta=24000.0 * REL)
        self.assertAlmostEqual(arm["volume_mm3"], 20000.0, delta=20000.0 * REL)
        for i, layer in enumerate(result.layers):
            if i < 30:  # the column, bottom to top
                self.assertEqual(layer.component, 0)
                self.assertVectorAlmostEqual(layer.normal, (0, 0, 1))
                self.assertAlmostEqual(layer.origin.z, 2.0 * (i + 1), delta=TOL)
            else:  # the arm, out from the column's face at x = 20
                self.assertEqual(layer.component, 1)
                self.assertVectorAlmostEqual(layer.normal, (1, 0, 0))
                self.assertAlmostEqual(layer.origin.x, 20.0 + 2.0 * (i - 29), delta=TOL)
                self.assertAlmostEqual(layer.area, 400.0, delta=400.0 * REL)
            self.assertAlmostEqual(layer.max_thickness, 2.0, delta=TOL)
        self.assertVectorAlmostEqual(result.layers[30].lower_origin, (20, 10, 50))
        self.assertAlmostEqual(result.stats["deposited_volume_mm3"], 44000.0,
                               delta=44000.0 * REL)
        self.check_paths(result)

    def test_a_column_cut_from_an_arm_over_a_gusset_is_built_square(self):
        """The column's axis nodes beside the arm hold its near end, out to the web's tip: the
        slicer moves them onto what the column kept, which it reads from the nodes' regions. Those
        cross to Python and back with the axis; without them the column leaned after the arm, its
        29 upper layers tilted (the command line's stayed square)."""
        with support.scratch_folder("mas_slice_gusset_") as folder:
            path = os.path.join(folder, "gusset.brep")
            gusset_bracket().exportBrep(path)
            result = mas.slice(gusset_bracket())
            column = result.components[0]
            self.assertEqual(column["layer_count"], 40)  # 80 mm at 2 mm
            for i in range(40):
                layer = result.layers[column["first_layer"] + i]
                self.assertVectorAlmostEqual(layer.normal, (0, 0, 1))
                self.assertAlmostEqual(layer.origin.z, 2.0 * (i + 1), delta=TOL)
            self.assertEqual(result.stats["worst_unsupported_area_mm2"], 0.0)
            cli = self.cli_json(folder, "slice", path)
            cli.pop("file")
            self.assertSameJson(cli, mas.slice(path).to_dict(), "slice")

    def test_a_given_decomposition_gives_the_same_result(self):
        parts = mas.decompose(l_block())
        given = mas.slice(l_block(), components=parts)
        self.assertIs(given.decomposition, parts)
        self.assertIs(given.axis, parts.axis)
        self.assertEqual(given.to_dict(), mas.slice(l_block()).to_dict())

    def test_no_component_is_thinner_than_a_layer(self):
        # A 4 x 4 column with a 1.8 mm stub on its side: with a 0.4 mm step the axis turns into
        # the stub, and decompose() alone makes it a component 1.8 mm deep along +X. No layer of
        # 2 mm or more fits that (the slicer stopped on it): slice() decomposes with
        # min_component_height = min_layer, and the stub stays in the column.
        part = Part.makeBox(4, 4, 30).fuse(Part.makeBox(1.8, 4, 4, V(4, 0, 20))).removeSplitter()
        alone = mas.decompose(part, step=0.4)
        self.assertEqual(len(alone), 2)
        self.assertAlmostEqual(alone[1].shape.BoundBox.XLength, 1.8, delta=1e-6)
        result = mas.slice(part, step=0.4, min_layer=2.0, max_layer=3.0)
        self.assertEqual(len(result.components), 1)
        self.assertEqual(result.decomposition.params["min_component_height_mm"], 2.0)
        notes = result.decomposition.notes
        self.assertEqual(len(notes), 1)
        self.assertIn("reaches only 1.8 mm", notes[0])
        self.assertAlmostEqual(result.stats["part_volume_mm3"], 480.0 + 28.8, delta=1e-6)

    def test_parameters_are_used(self):
        result = mas.slice(box_20_10_21(), max_layer=1.5, infill="none", contour_count=1,
                           bead_width=FreeCAD.Units.Quantity("1.2 mm"))
        self.assertEqual(len(result.layers), 14)  # 21 mm / 1.5
        self.assertEqual(result.params["bead_width"], 1.2)
        self.assertEqual(result.params["infill"], "none")
        for i in range(len(result.layers)):
            kinds = [p.kind for p in result.paths(i) if p.deposit]
            self.assertEqual(kinds, ["contour"])

    def test_a_mesh_is_sliced_as_one_component(self):
        result = mas.slice(fc_mesh(box_20_10_21()))
        self.assertEqual(result.kind, "mesh")
        self.assertIsNone(result.decomposition)
        self.check_box_layers(result)
        self.check_paths(result)
        with self.assertRaisesRegex(TypeError, "mesh"):
            mas.slice(fc_mesh(box_20_10_21()), components=mas.decompose(box_20_10_21()))

    def test_a_mesh_is_split_unless_kept_whole_and_a_solid_is_always_decomposed(self):
        split = mas.slice(fc_mesh(l_block(), 0.01))
        self.assertEqual(len(split.components), 2)
        self.assertEqual(split.stats["worst_unsupported_area_mm2"], 0.0)
        self.assertTrue(split.params["split_mesh"])
        whole = mas.slice(fc_mesh(l_block(), 0.01), split_mesh=False)
        self.assertEqual(len(whole.components), 1)
        self.assertFalse(whole.params["split_mesh"])
        self.assertAlmostEqual(whole.stats["worst_unsupported_area_mm2"], 48 * 20, places=6)
        with self.assertRaisesRegex(ValueError, "is a solid, which is always decomposed; "
                                                "split_mesh=False applies to a mesh"):
            mas.slice(l_block(), split_mesh=False)
        with self.assertRaisesRegex(TypeError, "split_mesh must be True or False"):
            mas.slice(fc_mesh(l_block(), 0.01), split_mesh="no")

    def test_to_dict_is_json_ready(self):
        result = mas.slice(l_block())
        data = result.to_dict()
        self.assertEqual(json.loads(json.dumps(data, allow_nan=False)), data)
        self.assertEqual(set(data),
                         {"kind", "params", "stats", "filled_holes", "notes", "build_order",
                          "sequence", "collisions", "components", "layers"})
        self.assertEqual(data["build_order"], [0, 1])  # the column, then the arm on it
        # Nothing to interleave: the column, then the arm, which clears the plate and column.
        self.assertEqual(data["sequence"], list(range(55)))
        self.assertEqual(data["collisions"], [])
        self.assertEqual(data["params"], dict(mas.SLICE_DEFAULTS))
        self.assertEqual(len(data["layers"]), 55)
        layer = data["layers"][30]
        self.assertEqual(layer["tool_axis"], layer["normal"])
        self.assertTrue(layer["paths"])
        self.assertEqual(layer["unfilled"], [])

    def test_a_tees_branch_is_built_after_the_pipe_above_its_junction(self):
        # The engine's test part: the branch's first layer is a ring at the pipe's side, whose
        # upper half rests on the pipe above the junction, a later component in tree order.
        tee = support.pipe_tee()
        axis = mas.centroidal_axis(tee, step=1.0, deflection=0.02)
        d = mas.decompose(tee, axis=axis)
        result = mas.slice(tee, axis=axis, components=d, deflection=0.02)
        branch = [i for i, c in enumerate(d) if c.build_direction.y > 0.999]
        self.assertEqual(len(branch), 1)
        order = result.build_order
        self.assertEqual(sorted(order), list(range(len(d))))
        self.assertEqual(order[0], 0)
        self.assertEqual(order[-1], branch[0])
        # The layers come component by component in that order.
        expected = []
        for c in order:
            expected += [c] * result.components[c]["layer_count"]
        self.assertEqual([layer.component for layer in result.layers], expected)
        first = result.layers[result.components[branch[0]]["first_layer"]]
        self.assertEqual(first.component, branch[0])
        # It waits for the pipe above in the deposition sequence too: every layer of the
        # component built before it is deposited before the branch's first.
        start = result.sequence.index(result.components[branch[0]]["first_layer"])
        self.assertEqual(sorted(result.layers[i].component for i in result.sequence[:start]),
                         sorted(c for c in order[:-1]
                                for _ in range(result.components[c]["layer_count"])))
        # Supported up to the two cuts' deflection along its outline (2 pi (10 + 8) mm long).
        self.assertLessEqual(first.unsupported_area, 2 * 3.141592653589793 * 18 * 0.02)

    def test_to_dict_matches_the_command_line_json(self):
        with support.scratch_folder("mas_slice_cli_") as folder:
            path = os.path.join(folder, "l.brep")
            l_block().exportBrep(path)
            cli = self.cli_json(folder, "slice", path)
            ours = mas.slice(path).to_dict()
            self.assertEqual(cli.pop("file"), path)
            self.assertSameJson(cli, ours, "slice")
            cli = self.cli_json(folder, "slice", path, "--max-layer", "1.5", "--infill",
                                "contour", "--bead-width", "1.2", "--contours", "1")
            ours = mas.slice(path, max_layer=1.5, infill="contour", bead_width=1.2,
                             contour_count=1).to_dict()
        cli.pop("file")
        self.assertSameJson(cli, ours, "slice")

    def test_solids_sharing_material_are_sliced_as_their_union(self):
        # The L given as its column and its arm: a Compound where a Union was meant, and the
        # CompSolid of Part's BooleanFragments. Each is sliced as the L-block, and left as it was.
        column, arm = Part.makeBox(20, 20, 60), Part.makeBox(50, 20, 20, V(20, 0, 40))
        fragments = Part.CompSolid(column.generalFuse([arm])[0].Solids)
        want = mas.slice(l_block())
        for shape in (Part.makeCompound([column, arm]), fragments):
            before = shape.exportBrepToString()
            result = mas.slice(shape)
            self.assertEqual(shape.exportBrepToString(), before)
            self.assertEqual(len(shape.Solids), 2)
            self.assertEqual([c["layer_count"] for c in result.components],
                             [c["layer_count"] for c in want.components])
            self.assertEqual(len(result.layers), len(want.layers))
            for got, layer in zip(result.layers, want.layers):
                self.assertVectorAlmostEqual(got.normal, layer.normal)
                self.assertVectorAlmostEqual(got.origin, layer.origin)
                self.assertAlmostEqual(got.area, layer.area, delta=layer.area * REL)
            self.assertAlmostEqual(result.stats["part_volume_mm3"], 20 * 20 * 60 + 50 * 20 * 20,
                                   delta=44000 * REL)

    def test_a_part_moved_on_the_plate_is_planned_the_same_moved(self):
        # No threshold may depend on where the part stands: the L (planar, exactly) and the column
        # with a rod and a bar (a curved face, its sideways components leaned and ordered round
        # the nozzle), moved 400 mm along X and -250 along Y, give the same plan moved.
        shift = V(400, -250, 0)
        for shape in (l_block(), rod_under_bar()):
            moved = shape.copy()
            moved.translate(shift)
            here, there = mas.slice(shape), mas.slice(moved)
            d = mas.deflection(shape)
            self.assertEqual(mas.deflection(moved), d)
            self.assertEqual([c["layer_count"] for c in there.components],
                             [c["layer_count"] for c in here.components])
            self.assertEqual(there.sequence, here.sequence)
            self.assertEqual(there.stats["colliding_layers"], 0)
            self.assertEqual(there.stats["leaned_layers"], here.stats["leaned_layers"])
            for i, (a, b) in enumerate(zip(here.layers, there.layers)):
                msg = "layer {}".format(i)
                self.assertEqual(b.component, a.component, msg)
                self.assertVectorAlmostEqual(b.normal, a.normal, places=9)
                self.assertLessEqual((b.origin - shift - a.origin).Length, d, msg)
                self.assertAlmostEqual(b.min_thickness, a.min_thickness, delta=d, msg=msg)
                self.assertAlmostEqual(b.max_thickness, a.max_thickness, delta=d, msg=msg)
                # Sections of the two tessellations differ by at most about d x perimeter.
                perimeter = sum((q - loop[k - 1]).Length
                                for loop in a.loops() for k, q in enumerate(loop))
                self.assertAlmostEqual(b.area, a.area, delta=d * perimeter, msg=msg)
                self.assertAlmostEqual(b.unsupported_area, a.unsupported_area,
                                       delta=d * perimeter, msg=msg)

    def test_a_round_boss_on_a_block_is_built_sideways_with_nothing_unsupported(self):
        # A 41 x 31 x 56 block with a boss of radius 7.77 sticking out 6.69 mm from its -X side,
        # its axis 11.98 mm over the plate (a manifold's port). Its section on the first plane
        # through it is centred within the distance threshold of the block, and its round
        # underside appears gradually between the planes; but what of it the plane half way
        # between holds already reaches the boss' end: a ledge, cut off at the block's face and
        # built along -X (CentroidalAxis.hpp). Kept in the block's layers, the first one through
        # it overhung 27 mm^2.
        part = Part.makeBox(41.0, 31.0, 56.0, V(-20.5, -15.5, 0)).fuse(
            Part.makeCylinder(7.77, 7.69, V(-19.5, 0, 11.98), V(-1, 0, 0)))
        result = mas.slice(part)
        self.assertEqual(len(result.components), 2)
        boss = result.decomposition.components[1]
        self.assertVectorAlmostEqual(boss.build_direction, (-1, 0, 0))
        self.assertAlmostEqual(boss.base_origin.x, -20.5, places=6)
        self.assertEqual(result.stats["colliding_layers"], 0)
        self.assertEqual(result.stats["worst_unsupported_area_mm2"], 0.0)

    def test_the_source_is_not_modified(self):
        shape = l_block()
        shape.Placement = FreeCAD.Placement(V(1, 2, 3), FreeCAD.Rotation())
        before = shape.exportBrepToString()
        result = mas.slice(shape)
        self.assertEqual(len(result.components), 2)
        self.assertEqual(shape.exportBrepToString(), before)


class TestSliceProgress(SliceTest):
    """``progress=``: reports from the engine, and stopping it by raising."""

    def check_reports(self, reports):
        """Fractions in [0, 1], never going back, ending at 1."""
        self.assertTrue(reports)
        fractions = [f for f, _ in reports]
        for i, (a, b) in enumerate(zip(fractions, fractions[1:])):
            self.assertLessEqual(a, b, "report {} goes back".format(i + 1))
        self.assertGreaterEqual(fractions[0], 0.0)
        self.assertEqual(fractions[-1], 1.0)

    def test_slicing_reports_each_stage_up_to_one(self):
        reports = []
        result = mas.slice(l_block(), progress=lambda f, s: reports.append((f, s)))
        self.check_reports(reports)
        stages = [s for _, s in reports]
        # Decomposing (the first fifth), then the engine's slicing stages, in order.
        order = ["splitting at branch", "tessellating the components", "ordering the components",
                 "slicing component 0 (1 of 2)", "slicing component 1 (2 of 2)",
                 "planning the bead paths"]
        at = [next((i for i, s in enumerate(stages) if s.startswith(o)), None) for o in order]
        self.assertNotIn(None, at, dict(zip(order, at)))
        self.assertEqual(at, sorted(at))
        # Every report names its stage, the last ones too (the end of decomposing, and of all).
        self.assertNotIn("", stages)
        self.assertEqual(reports[-1], (1.0, "slicing"))
        # The first split and slicing take 70 % (five rounds would take the next 20, the part
        # sliced whole the last 10; the L needs neither); decomposing is its first fifth.
        ends = [f for f, s in reports if s == "decomposing"]
        self.assertEqual(len(ends), 1)
        self.assertAlmostEqual(ends[0], 0.14, places=12)
        split = [f for f, s in reports if s.startswith("splitting")]
        self.assertLessEqual(max(split), ends[0])
        self.assertGreaterEqual(min(f for f, s in reports if s.startswith("tessellating")),
                                ends[0])
        self.assertAlmostEqual(reports[-2][0], 0.7, places=12)
        # Reporting changes nothing in the result.
        self.assertEqual(result.to_dict(), mas.slice(l_block()).to_dict())

    def test_decomposing_and_slicing_a_mesh_report_too(self):
        reports = []
        d = mas.decompose(l_block(), progress=lambda f, s: reports.append((f, s)))
        self.assertEqual(len(d), 2)
        self.check_reports(reports)
        reports = []
        mas.slice(fc_mesh(box_20_10_21()), progress=lambda f, s: reports.append((f, s)))
        self.check_reports(reports)

    def test_raising_stops_the_work_and_is_raised_again(self):
        shape = l_block()
        before = shape.exportBrepToString()
        for stop_here, error in ((lambda f, s: f >= 0.1, mas.Cancelled),
                                 (lambda f, s: f >= 0.5, mas.Cancelled),
                                 (lambda f, s: s.startswith("planning"), KeyError)):
            calls = []

            def stop(fraction, stage):
                calls.append(fraction)
                if stop_here(fraction, stage):
                    raise error("stopped at {}".format(stage))

            with self.assertRaises(error) as raised:
                mas.slice(shape, progress=stop)
            self.assertIn("stopped at", str(raised.exception))
            self.assertLess(calls[-1], 1.0)  # not at the end: stopped on the way
        self.assertEqual(shape.exportBrepToString(), before)
        # The engine is left as it was: the same call then runs through.
        self.check_box_layers(mas.slice(box_20_10_21(), progress=lambda f, s: None))
        with self.assertRaises(mas.Cancelled):
            mas.decompose(shape, progress=lambda f, s: (_ for _ in ()).throw(mas.Cancelled()))

    def test_a_python_signal_handler_stops_the_engine_without_a_callback(self):
        # Ctrl-C in a script: Python's handlers run while the engine works, not once it is done.
        import signal
        import time

        class Alarm(Exception):
            pass

        def handler(signum, frame):
            raise Alarm()

        plate = Part.makeBox(100, 100, 4)
        posts = plate.fuse([Part.makeCylinder(3, 25, V(10 + 12 * i, 10 + 12 * j, 4))
                            for i in range(7) for j in range(7)]).removeSplitter()
        parts = mas.decompose(posts, min_component_height=0.5)
        start = time.perf_counter()
        self.assertEqual(len(mas.slice(posts, components=parts).components), 50)
        whole = time.perf_counter() - start  # some tenths of a second
        previous = signal.signal(signal.SIGALRM, handler)
        try:
            start = time.perf_counter()
            signal.setitimer(signal.ITIMER_REAL, whole / 10)
            with self.assertRaises(Alarm):
                mas.slice(posts, components=parts)
            stopped = time.perf_counter() - start
        finally:
            signal.setitimer(signal.ITIMER_REAL, 0)
            signal.signal(signal.SIGALRM, previous)
        # Stopped on the way (a handler that waited for the engine would run at its end), and
        # the engine runs through again.
        self.assertLess(stopped, whole / 2)
        self.assertEqual(len(mas.slice(posts, components=parts).components), 50)

    def test_a_progress_that_is_not_callable_is_named(self):
        for call in (mas.slice, mas.decompose):
            with self.assertRaisesRegex(TypeError, "progress must be None or callable"):
                call(l_block(), progress=5)


def gusset_bracket():
    """A 20 x 20 column 80 tall, an arm [20,70]x[0,20]x[60,80] at its top, a web 4 thick under
    it ([8,12] in y) from (x, z) = (20, 37) out to (43, 60)."""
    web = Part.Face(Part.makePolygon([V(20, 8, 60), V(43, 8, 60), V(20, 8, 37), V(20, 8, 60)]))
    column = Part.makeBox(20, 20, 80)
    return column.fuse([Part.makeBox(50, 20, 20, V(20, 0, 60)),
                        web.extrude(V(0, 4, 0))]).removeSplitter()


def block_with_pin_hole():
    """A 30 x 10 x 20 block with a horizontal hole of radius 4 along Y at x = 15, z = 10 and a
    vertical one of radius 2 at (5, 5): only the first has a ceiling."""
    return Part.makeBox(30, 10, 20).cut(Part.makeCylinder(4, 10, V(15, 0, 10), V(0, 1, 0))).cut(
        Part.makeCylinder(2, 20, V(5, 5, 0), V(0, 0, 1)))


class TestFillHoles(SliceTest):
    def test_a_filled_hole_leaves_every_layer_supported_and_is_listed_to_drill(self):
        part = block_with_pin_hole()
        volume = part.Volume
        open_ = mas.slice(part)
        # Open, a layer over the ceiling overhangs the bore by more than a negligible area.
        worst = open_.layers[open_.stats["worst_unsupported_layer"]]
        self.assertGreater(worst.unsupported_area, 1e-3 * worst.area)
        self.assertEqual(open_.filled_holes, [])
        self.assertEqual(open_.stats["filled_holes"], 0)
        result = mas.slice(part, fill_holes=8)
        self.assertEqual(result.params["fill_holes"], 8.0)
        self.assertEqual(result.stats["worst_unsupported_area_mm2"], 0.0)
        self.assertEqual(result.stats["worst_unsupported_layer"], -1)
        self.assertEqual(len(result.filled_holes), 1)
        self.assertEqual(result.notes, [])
        hole = result.filled_holes[0]
        self.assertIsInstance(hole, mas.FilledHole)
        self.assertEqual(hole.component, 0)
        self.assertVectorAlmostEqual(hole.centre, (15, 5, 10))
        self.assertAlmostEqual(abs(hole.axis.y), 1.0, places=12)
        self.assertAlmostEqual(hole.diameter, 8.0, places=9)
        self.assertAlmostEqual(hole.length, 10.0, places=9)
        filled = math.pi * 16.0 * 10.0
        self.assertEqual(result.stats["filled_holes"], 1)
        self.assertAlmostEqual(result.stats["filled_volume_mm3"], filled, delta=filled * REL)
        self.assertAlmostEqual(result.stats["part_volume_mm3"], volume, delta=volume * REL)
        d = result.to_dict()
        self.assertEqual(json.loads(json.dumps(d))["filled_holes"], [hole.to_dict()])
        self.assertEqual(d["notes"], [])
        self.assertEqual(part.Volume, volume)  # the caller's shape is not touched
        # Smaller than the hole: nothing is filled.
        self.assertEqual(mas.slice(part, fill_holes=7.9).filled_holes, [])

    def test_bad_fill_holes_is_named(self):
        box = box_20_10_21()
        with self.assertRaisesRegex(ValueError, "fill_holes"):
            mas.slice(box, fill_holes=-1.0)
        with self.assertRaisesRegex(ValueError, "fill_holes"):
            mas.slice(box, fill_holes=math.nan)
        with self.assertRaisesRegex(TypeError, "fill_holes"):
            mas.slice(box, fill_holes="8 mm")
        with self.assertRaisesRegex(ValueError, "mesh.*fill_holes needs a solid"):
            mas.slice(fc_mesh(box), fill_holes=8.0)


def close_posts():
    """Two 10 x 10 posts 60 tall, 10 mm apart, on a 60 x 30 x 5 plate: built one after the other,
    the second post's first layers would have the nozzle's cone meet the first post."""
    plate = Part.makeBox(60, 30, 5, V(-10, -10, 0))
    posts = Part.makeBox(10, 10, 60, V(0, 0, 5)).fuse(Part.makeBox(10, 10, 60, V(20, 0, 5)))
    return plate.fuse(posts).removeSplitter()


class TestSliceSequence(SliceTest):
    def test_close_posts_are_built_together(self):
        result = mas.slice(close_posts())
        self.assertEqual(sorted(result.sequence), list(range(len(result.layers))))
        self.assertEqual(result.collisions, [])
        self.assertEqual(result.stats["colliding_layers"], 0)
        posts = [c for c in result.build_order[1:]]
        self.assertEqual(len(posts), 2)
        components = [result.layers[i].component for i in result.sequence]
        # The plate, then the first post until it would block the second, the second until it
        # would block the first, and so on: the posts go up together, in turns.
        self.assertEqual(components[0], 0)
        runs = [components[0]]
        for c in components[1:]:
            if c != runs[-1]:
                runs.append(c)
        self.assertGreaterEqual(len(runs), 4)
        self.assertEqual(runs, [0] + [posts[k % 2] for k in range(len(runs) - 1)])
        self.assertEqual(result.stats["component_switches"], len(runs) - 1)
        # Each component's layers in their own order.
        for c in range(len(result.components)):
            mine = [i for i in result.sequence if result.layers[i].component == c]
            self.assertEqual(mine, sorted(mine))
        # The first post is left just before its next layer would come into the nozzle grown
        # by twice the margin at the second post's first layer: its outer contour runs 0.5 mm
        # inside the post, 10.5 mm from the first, which the grown cone (5 + (h - 10) tan 30 +
        # 4 / cos 30 mm across) reaches 11.526 mm above it.
        first_run = [i for i in result.sequence[:components.index(posts[1])]
                     if result.layers[i].component == posts[0]]
        base = result.layers[result.components[posts[1]]["first_layer"]].origin.z
        reach = 10.0 + (10.5 - 5.0 - 4.0 / math.cos(math.radians(30))) / math.tan(
            math.radians(30))
        self.assertLess(result.layers[first_run[-1]].origin.z - base, reach)
        self.assertGreaterEqual(result.layers[first_run[-1] + 1].origin.z - base, reach)
        # The program deposits them in that order, naming the layers by their index.
        program = result.gcode()
        named = [int(line.split()[1].rstrip(",")) for line in program.text.splitlines()
                 if line.startswith("(layer ")]
        self.assertEqual(named, result.sequence)

    def test_a_wide_nozzle_sideways_near_the_plate_is_reported(self):
        # The L's arm is deposited sideways at z 40 to 60: a coaxial 100 mm body reaches 50 mm
        # below the tool axis, under the plate for every arm layer (deposit points below z = 52).
        # Kept as decomposed (avoid_collisions=False), those layers are reported.
        result = mas.slice(l_block(), nozzle_body_diameter=100.0, nozzle_max_lean=0.0,
                           avoid_collisions=False)
        arm = [i for i, layer in enumerate(result.layers) if layer.component == 1]
        self.assertEqual(len(result.decomposition), 2)
        self.assertEqual(result.notes, [])
        self.assertEqual([c.layer for c in result.collisions], arm)
        self.assertEqual(result.stats["colliding_layers"], len(arm))
        for c in result.collisions:
            self.assertEqual(c.obstacle_layer, -1)
            self.assertAlmostEqual(c.obstacle.z, 0.0, places=9)
            self.assertLess(c.nozzle_at.z, 52.0)
            self.assertIsInstance(c.nozzle_at, FreeCAD.Vector)
        self.assertIn("meets the plate", repr(result.collisions[0]))
        self.assertEqual(result.to_dict()["collisions"][0]["obstacle_layer"], -1)
        # Without the plate as an obstacle, or with the default 50 mm body, nothing collides.
        self.assertEqual(result.leaned_layers(), [])
        self.assertEqual(mas.slice(l_block(), nozzle_body_diameter=100.0, nozzle_max_lean=0.0,
                                   check_plate=False).collisions, [])
        self.assertEqual(mas.slice(l_block(), nozzle_max_lean=0.0).collisions, [])

    def test_a_branch_whose_layers_the_nozzle_cannot_reach_stays_in_its_father(self):
        # The same nozzle, and by default: the arm, built on its own, would have the nozzle meet
        # the plate at each of its layers, so it stays in the column, which builds it up along
        # +Z (its underside then overhangs: the price of a nozzle that fits).
        result = mas.slice(l_block(), nozzle_body_diameter=100.0, nozzle_max_lean=0.0)
        self.assertEqual(result.stats["colliding_layers"], 0)
        self.assertEqual(len(result.decomposition), 1)
        self.assertEqual(result.decomposition[0].volume, result.stats["part_volume_mm3"])
        self.assertEqual({tuple(layer.normal) for layer in result.layers}, {(0.0, 0.0, 1.0)})
        arm = result.axis.branches[1]
        self.assertEqual(arm.direction, FreeCAD.Vector(1, 0, 0))
        self.assertEqual(result.notes, [
            "decomposition: branch 1 (along 1,0,0): built on its own, its layers would meet the "
            "plate or what is deposited before them; its material stays in component 0"])
        self.assertEqual(result.decomposition.notes, [result.notes[0][len("decomposition: "):]])
        self.assertEqual(result.decomposition.kept_branches, [1])
        self.assertEqual(result.decomposition.params["keep_branches"], (1,))
        # decompose() keeping that branch gives the same decomposition.
        again = mas.decompose(l_block(), axis=result.axis, min_component_height=0.5,
                              keep_branches=result.decomposition.kept_branches)
        self.assertEqual([c.to_dict() for c in again], [c.to_dict() for c in result.decomposition])
        self.assertEqual(again.params, result.decomposition.params)
        self.assertEqual(again.notes, ["branch 1 (along 1,0,0): kept in its father, as asked "
                                       "(keep_branches); its material stays in component 0"])
        # Sliced again with it, the layers are the same.
        self.assertEqual(mas.slice(l_block(), components=again, nozzle_body_diameter=100.0,
                                   nozzle_max_lean=0.0).to_dict()["layers"],
                         result.to_dict()["layers"])

    def test_a_decomposition_given_slices_its_turned_cuts_as_slice_does(self):
        # The survey's hub 4 at seed 125: six blades twisted 15 degrees, each cut square to its
        # own line and built along it to its tip (the engine's SlicePart.hpp). Sliced again with
        # that decomposition given, the components keep their turned cuts and the layers are the
        # same; guided by the axis' nodes, the blades' last layers tilted after their tips.
        hub, _ = survey.part("hub with blades", 4, 125)
        result = mas.slice(hub)
        self.assertEqual(result.notes, [])
        self.assertEqual(result.collisions, [])
        turned = [k for k, c in enumerate(result.decomposition) if c.turned]
        self.assertEqual(len(turned), 6)
        for k in turned:
            direction = result.decomposition[k].build_direction
            for layer in (layer for layer in result.layers if layer.component == k):
                self.assertLess((layer.normal - direction).Length, 1e-9, k)
        again = mas.slice(hub, components=result.decomposition)
        self.assertEqual(again.to_dict()["layers"], result.to_dict()["layers"])

    def test_a_blade_whose_tip_is_cut_short_over_two_nodes_is_cut_square_to_its_line(self):
        # The survey's hub 6 at seed 150: five blades, one 43.3 degrees off -X (223.3 degrees
        # round), marched along -X. Its tip cuts the last two sections short (areas 82 and 28 %
        # of the others'): its line is fit through its first four nodes, the last two left out
        # (Decompose.hpp). Leaving out only the last found no line, the cut stayed square to -X,
        # and the wedge of the blade it left in the hub hung 14.5 mm^2 in the hub's layer.
        hub, _ = survey.part("hub with blades", 6, 150)
        result = mas.slice(hub)
        self.assertEqual(result.collisions, [])
        d = result.decomposition
        self.assertEqual(len(d), 6)
        self.assertTrue(all(c.turned for c in list(d)[1:]))
        blade = [c for c in d if c.turned and abs(math.degrees(math.atan2(
            c.build_direction.y, c.build_direction.x)) % 360.0 - 223.3) < 0.1]
        self.assertEqual(len(blade), 1)
        deflection = mas.deflection(hub)
        for i, layer in enumerate(result.layers):
            self.assertLessEqual(layer.unsupported_area,
                                 survey.support_tolerance(layer, deflection), i)

    def test_a_blade_marched_along_the_farther_direction_is_cut_square_to_its_line(self):
        # The survey's hub 5 at seed 130: six blades, one 308.7 degrees round, 51.3 degrees off
        # +X and 38.7 off -Y. Its march along -Y broke off after six nodes and a branch along +X
        # took it on: its line runs 51 degrees off that branch's direction, under the 60 a turned
        # cut allows (Decompose.hpp). Allowed only 45, the cut stayed square to +X; the wedge it
        # left in the hub and the slivers each of its layers left along its side hung up to 6.0
        # mm^2.
        hub, _ = survey.part("hub with blades", 5, 130)
        result = mas.slice(hub)
        self.assertEqual(result.collisions, [])
        d = result.decomposition
        blade = [c for c in d if c.turned and abs(math.degrees(math.atan2(
            c.build_direction.y, c.build_direction.x)) % 360.0 - 308.7) < 0.1]
        self.assertEqual(len(blade), 1)
        self.assertAlmostEqual(blade[0].volume, max(c.volume for c in list(d)[1:]),
                               delta=blade[0].volume * 1e-3)
        deflection = mas.deflection(hub)
        for i, layer in enumerate(result.layers):
            self.assertLessEqual(layer.unsupported_area,
                                 survey.support_tolerance(layer, deflection), i)

    def test_a_spiral_stairs_treads_are_built_along_their_lines_the_nozzle_leaned(self):
        # A spiral stair (support.spiral_stair): its treads between +-X and +-Y are cut square to
        # their own lines, where the nozzle at a tread's root, coaxial, meets the tread under it
        # (the engine's Slicing.ASpiralStairsTreads...); leaned, it clears it, and no cut is made
        # square to its branch's direction instead (decomposition.square_branches).
        stair = support.spiral_stair()
        result = mas.slice(stair)
        self.assertEqual(result.stats["colliding_layers"], 0)
        self.assertGreater(result.stats["leaned_layers"], 0)
        d = result.decomposition
        first = mas.decompose(stair, axis=result.axis, min_component_height=0.5)
        turned = sorted(c.branch for c in first if c.turned)
        self.assertEqual(len(turned), 5)
        self.assertEqual(d.square_branches, [])
        self.assertEqual(d.kept_branches, [])
        self.assertEqual(sorted(c.branch for c in d if c.turned), turned)
        # Asked to (square_branches), decompose() cuts them square to their directions, along
        # +-X or +-Y, and says so in its parameters; slice() slices that decomposition.
        squared = mas.decompose(stair, axis=result.axis, min_component_height=0.5,
                                square_branches=turned)
        self.assertEqual(squared.square_branches, turned)
        self.assertEqual(squared.params["square_branches"], tuple(turned))
        for c in squared:
            self.assertFalse(c.turned, c.branch)
            if c.branch in turned:
                v = c.build_direction
                self.assertAlmostEqual(abs(v.x) + abs(v.y), 1.0, places=12)
                self.assertAlmostEqual(v.z, 0.0, places=12)
        again = mas.slice(stair, components=squared)
        self.assertEqual(again.decomposition.square_branches, turned)

    def test_an_order_leaving_a_leaning_nozzle_its_way_is_found(self):
        # The rod under the bar, both built sideways along +X: coaxial, the rod's nozzle meets the
        # plate; leaned 20 degrees up it clears it, but meets the bar where the bar is deposited
        # first, which the order taken without leans did (4 of the rod's layers collided). Ordered
        # again without the pairs a lean clears, the rod goes first, leaned, and the bar after it,
        # leaned too where its coaxial nozzle would reach down to the rod (its layers nearest the
        # column).
        result = mas.slice(support.rod_under_bar())
        self.assertEqual(result.notes, [])
        self.assertEqual(result.collisions, [])
        self.assertEqual(len(result.decomposition), 3)
        column, rod, bar = ([i for i, layer in enumerate(result.layers) if layer.component == c]
                            for c in range(3))
        leaned = result.leaned_layers()
        self.assertEqual(leaned[:len(rod)], rod)
        self.assertGreater(len(leaned), len(rod))
        self.assertEqual(leaned[len(rod):], bar[:len(leaned) - len(rod)])
        for i in leaned:
            self.assertGreater(result.tool_axis(i).z, 0.0)
        for i in rod:
            self.assertAlmostEqual(math.degrees(result.tool_axis(i).getAngle(
                result.layers[i].normal)), 20.0, places=9)
        self.assertLess(max(result.sequence.index(i) for i in rod),
                        min(result.sequence.index(i) for i in bar))
        self.assertEqual(result.stats["worst_unsupported_area_mm2"], 0.0)
        # The program's travel, checked on its own against the same nozzle, meets nothing either.
        program = result.gcode()
        self.assertEqual(program.stats["travel_collisions"], [])
        self.assertGreater(program.stats["checked_routes"], 0)

    def test_blades_low_over_the_plate_are_each_built_sideways_leaned_off_it(self):
        # Six blades round a hub, 4 mm over the plate: each blade's layers must lean up off the
        # plate, and the first layer of the second blade marched along +Y (the blades at 60 and
        # 120 degrees both are, their roots 10 mm apart) met the first blade's layers leaned,
        # where coaxial it missed them: the order put the first blade first, and collision rounds
        # then kept the four blades marched along +-Y in the hub (579 mm^2 unsupported under
        # them). Ordered with each such layer before what its leaned nozzle meets, every blade is
        # built on its own.
        hub = support.hub_with_six_blades()
        result = mas.slice(hub)
        self.assertEqual(result.notes, [])
        self.assertEqual(len(result.components), 7)
        self.assertEqual([c.parent for c in result.decomposition], [-1, 0, 0, 0, 0, 0, 0])
        self.assertEqual(result.collisions, [])
        self.assertEqual(result.gcode().stats["travel_collisions"], [])
        # Every layer rests on the one below (within the strip the mesh's deflection leaves).
        deflection = mas.deflection(hub)
        for i, layer in enumerate(result.layers):
            self.assertLessEqual(layer.unsupported_area,
                                 survey.support_tolerance(layer, deflection), i)
        # Every blade layer leans 30 degrees up: leaned t degrees from its horizontal normal, the
        # rim where the cone meets the body (25 mm out, 10 + 20 / tan 30 along the axis) is
        # 4 + that sin t - 25 cos t over the plate at the blade's foot, under the 2 mm margin at
        # 25 degrees (0.21 mm), over it at 30 (4.67).
        cone_end = 10.0 + 20.0 / math.tan(math.radians(30.0))
        rim = {t: 4.0 + cone_end * math.sin(math.radians(t)) - 25.0 * math.cos(math.radians(t))
               for t in (25.0, 30.0)}
        self.assertLess(rim[25.0], 2.0)
        self.assertGreaterEqual(rim[30.0], 2.0)
        for i, layer in enumerate(result.layers):
            if layer.component == 0:
                self.assertEqual(result.tool_axis(i), layer.normal)
                continue
            self.assertAlmostEqual(layer.normal.z, 0.0, places=6)
            self.assertAlmostEqual(math.degrees(result.tool_axis(i).getAngle(layer.normal)),
                                   30.0, places=6)
            self.assertGreater(result.tool_axis(i).z, 0.49)

    def test_the_nozzle_leans_clear_of_the_plate(self):
        # Allowed to lean (30 degrees by default), the 100 mm body clears the plate at every arm
        # layer: leaned t degrees up from +X, the rim where the cone meets the body (50 mm out,
        # 10 + 45 / tan 30 along the axis) is z + that sin t - 50 cos t high. The lowest deposit
        # point of each arm layer (about 41 mm up) needs 10 degrees, not 5.
        result = mas.slice(l_block(), nozzle_body_diameter=100.0)
        arm = [i for i, layer in enumerate(result.layers) if layer.component == 1]
        self.assertEqual(result.collisions, [])
        self.assertEqual(result.leaned_layers(), arm)
        self.assertEqual(result.stats["leaned_layers"], len(arm))
        self.assertEqual(result.stats["colliding_layers"], 0)
        cone_end = 10.0 + 45.0 / math.tan(math.radians(30.0))
        for i, layer in enumerate(result.layers):
            axis = result.tool_axis(i)
            self.assertIsInstance(axis, FreeCAD.Vector)
            for path in result.paths(i):
                self.assertEqual(path.tool_axis, axis)
            if i not in arm:
                self.assertEqual(axis, layer.normal)
                continue
            low = min(p.z for path in result.paths(i) if path.deposit for p in path.points)
            rim = [low + cone_end * math.sin(math.radians(t)) - 50.0 * math.cos(math.radians(t))
                   for t in (5.0, 10.0)]
            self.assertLess(rim[0], 2.0)
            self.assertGreaterEqual(rim[1], 2.0)
            self.assertAlmostEqual((axis - FreeCAD.Vector(math.cos(math.radians(10.0)), 0.0,
                                                          math.sin(math.radians(10.0)))).Length,
                                   0.0, places=12)
            self.assertEqual(result.to_dict()["layers"][i]["tool_axis"], list(axis))
        # The program turns the table 80 degrees for the arm, not 90.
        program = result.gcode()
        a_words = {round(float(w[1:]), 4) for line in program.text.splitlines()
                   if not line.startswith("(") for w in line.split() if w.startswith("A")}
        self.assertIn(-80.0, a_words)
        self.assertNotIn(-90.0, a_words)
        # Allowed 7 degrees (tried: 5 and 7), the arm collides as coaxial.
        self.assertEqual([c.layer for c in mas.slice(l_block(), nozzle_body_diameter=100.0,
                                                     nozzle_max_lean=7.0,
                                                     avoid_collisions=False).collisions], arm)

    def test_the_notes_say_what_hangs_and_stays_in_its_father(self):
        # A collar at an arm's end: its share under the arm would be built straight down, past
        # max_tilt (100 degrees); it stays in the arm, and slice() says so when it decomposes.
        part = Part.makeBox(30, 30, 60, V(-15, -15, 0)).fuse(Part.makeBox(40, 16, 16, V(15, -8, 32)))
        part = part.fuse(Part.makeBox(5, 24, 24, V(49, -12, 28))).removeSplitter()
        result = mas.slice(part, step=2.0)
        self.assertEqual(len(result.notes), 1, result.notes)
        self.assertTrue(result.notes[0].startswith("decomposition: branch "), result.notes[0])
        self.assertIn("past max_tilt (100 degrees): the machine cannot reach it; its material "
                      "stays in component 1", result.notes[0])
        self.assertEqual(["decomposition: " + n for n in result.decomposition.notes], result.notes)
        self.assertEqual(len(result.decomposition), 5)
        # A machine reaching 180 degrees, the plate no obstacle, builds it: six components,
        # nothing to say.
        unbounded = mas.slice(part, step=2.0, max_tilt=180.0, check_plate=False)
        self.assertEqual((len(unbounded.decomposition), unbounded.notes), (6, []))
        # With the plate there, the nozzle would come up through it under the collar: it stays.
        plate = mas.slice(part, step=2.0, max_tilt=180.0)
        self.assertEqual((len(plate.decomposition), plate.stats["colliding_layers"]), (5, 0))
        self.assertEqual(len(plate.notes), 1, plate.notes)
        self.assertIn("(along 0,0,-1): built on its own, its layers would meet the plate or what "
                      "is deposited before them; its material stays in component 1",
                      plate.notes[0])
        self.assertEqual(mas.slice(part, step=2.0, max_tilt=180.0,
                                   avoid_collisions=False).stats["colliding_layers"], 2)
        # With the decomposition given, its notes stay on it.
        again = mas.slice(part, components=result.decomposition)
        self.assertEqual(again.notes, [])

    def test_bad_nozzle_parameters_are_named(self):
        box = box_20_10_21()
        for error, text, kwargs in (
                (ValueError, "nozzle_margin must be a positive", dict(nozzle_margin=0.0)),
                (ValueError, r"nozzle_margin must be at most half nozzle_standoff \(5.0 mm\), "
                             r"got 2.6", dict(nozzle_standoff=5.0, nozzle_margin=2.6)),
                (ValueError, "nozzle_standoff must be 0 or more", dict(nozzle_standoff=-1.0)),
                (ValueError, r"nozzle_body_diameter must be at least nozzle_tip_diameter "
                             r"\(10.0 mm\), got 8.0", dict(nozzle_body_diameter=8.0)),
                (ValueError, "nozzle_cone_angle", dict(nozzle_cone_angle=90.0)),
                (ValueError, "nozzle_body_length", dict(nozzle_body_length=math.inf)),
                (ValueError, "nozzle_tip_diameter", dict(nozzle_tip_diameter=math.nan)),
                (TypeError, "nozzle_margin", dict(nozzle_margin="2 mm")),
                (TypeError, "check_plate", dict(check_plate="yes")),
                (ValueError, r"nozzle_max_lean must lie within \[0, 90\) degrees, got 90.0",
                 dict(nozzle_max_lean=90.0)),
                (ValueError, "nozzle_max_lean", dict(nozzle_max_lean=-1.0)),
                (ValueError, "nozzle_max_lean", dict(nozzle_max_lean=math.nan)),
                (TypeError, "nozzle_max_lean", dict(nozzle_max_lean="30 deg")),
                (ValueError, r"max_tilt must be in \[90, 180\] degrees, got 180.5",
                 dict(max_tilt=180.5)),
                (ValueError, "max_tilt", dict(max_tilt=math.nan))):
            with self.assertRaisesRegex(error, text, msg=str(kwargs)):
                mas.slice(box, **kwargs)
        # At least 5e-4 of the part's diagonal, sqrt(941) mm: the checks sample that far apart.
        e = self.assertRaisesEngineError("invalid_argument", mas.slice, box, nozzle_margin=0.01)
        self.assertEqual(str(e), "the nozzle's margin 0.01 mm is too small for the part, 30.6757 "
                                 "mm across: the collision checks sample what is deposited that "
                                 "far apart; the least is 0.0153379 mm")
        # At most 1e5 margins from the deposit point to the body's end (the travel check turns the
        # table in steps that move it a margin at most).
        e = self.assertRaisesEngineError("invalid_argument", mas.slice, box, nozzle_standoff=1e9)
        self.assertTrue(str(e).startswith("the nozzle's body ends 1e+09 mm from its deposit point, "
                                          "more than 100000 times its margin (2 mm)"), str(e))
        # One diameter: no cone, whatever its angle.
        result = mas.slice(box, nozzle_body_diameter=10.0, nozzle_cone_angle=0.0)
        self.assertEqual(result.collisions, [])


class TestSliceBadInput(SliceTest):
    def test_bad_parameters_are_named(self):
        box = box_20_10_21()
        for error, name, kwargs in (
                (ValueError, "min_layer", dict(min_layer=3.0, max_layer=2.0)),
                (ValueError, "min_layer", dict(min_layer=0.0)),
                (ValueError, "bead_width", dict(bead_width=0.0)),
                (ValueError, "bead_width", dict(bead_width=-1.0)),
                (ValueError, "infill", dict(infill="bogus")),
                (ValueError, "max_volume_difference", dict(max_volume_difference=0.0)),
                (TypeError, "contour_count", dict(contour_count=1.5)),
                (TypeError, "bead_width", dict(bead_width="wide")),
                (TypeError, "unknown parameter.*layer_height", dict(layer_height=1.0))):
            with self.assertRaisesRegex(error, name, msg=str(kwargs)):
                mas.slice(box, **kwargs)
        # Messages as they read: an integer too large for the engine is out of range, not "not an
        # integer"; a fraction is a fraction (it read "a number of fraction").
        with self.assertRaises(mas.EngineError) as caught:
            mas.slice(box, volume_samples=10 ** 30)
        self.assertEqual(str(caught.exception),
                         "volume_samples is out of range, got " + str(10 ** 30))
        with self.assertRaises(TypeError) as caught:
            mas.slice(box, max_volume_difference="x")
        self.assertEqual(str(caught.exception),
                         "max_volume_difference must be a number (a fraction), got 'x'")

    def test_none_and_faces_are_rejected(self):
        with self.assertRaisesRegex(TypeError, "None"):
            mas.slice(None)
        e = self.assertRaisesEngineError("not_a_solid", mas.slice, Part.makePlane(10, 10))
        self.assertIn("Face", str(e))
        with self.assertRaisesRegex(TypeError, "Decomposition"):
            mas.slice(box_20_10_21(), components=[])

    def test_axis_parameters_beside_a_given_axis_or_decomposition_are_refused(self):
        # They would be ignored: the decomposition carries the axis it was made with (a step
        # beside it used to be dropped without a word).
        box = box_20_10_21()
        axis = mas.centroidal_axis(box, step=3.0)
        with self.assertRaisesRegex(ValueError, "an axis is given.*step"):
            mas.slice(box, axis=axis, step=2.0)
        components = mas.decompose(box, axis=axis)
        with self.assertRaisesRegex(ValueError, "a decomposition .* given.*break_angle, step"):
            mas.slice(box, components=components, step=2.0, break_angle=20)
        self.assertIs(mas.slice(box, components=components).axis, axis)


class TestUnsupportedRegions(SliceTest):
    def test_a_shelf_sliced_as_a_mesh_shows_where_its_first_layer_stands_on_nothing(self):
        """A 10 x 10 stem 10 tall under a 30 x 10 slab 2 thick, as one mesh component along Z:
        the slab's first layer reaches 20 mm past the stem. What of it lies outside the stem grown
        by the allowance (its thickness x tan 45) is exactly a rectangle on the stem's top."""
        shelf = Part.makeBox(10, 10, 10).fuse(Part.makeBox(30, 10, 2, V(0, 0, 10)))
        result = mas.slice(fc_mesh(shelf.removeSplitter()), split_mesh=False)
        flagged = [(i, layer) for i, layer in enumerate(result.layers) if layer.unsupported_regions]
        self.assertEqual(len(flagged), 1)
        i, layer = flagged[0]
        self.assertAlmostEqual(layer.lower_origin.z, 10.0, delta=TOL)
        t = layer.min_thickness
        self.assertAlmostEqual(layer.unsupported_area, (20.0 - t) * 10.0, delta=1e-3)
        (region,) = layer.unsupported_regions
        self.assertEqual(region["holes"], [])
        box = FreeCAD.BoundBox()
        for p in region["outer"]:
            self.assertIsInstance(p, FreeCAD.Vector)
            box.add(p)
        for got, want in ((box.XMin, 10.0 + t), (box.XMax, 30.0), (box.YMin, 0.0),
                          (box.YMax, 10.0), (box.ZMin, 10.0), (box.ZMax, 10.0)):
            self.assertAlmostEqual(got, want, delta=1e-4)
        face = Part.Face(Part.makePolygon(region["outer"] + region["outer"][:1]))
        self.assertAlmostEqual(face.Area, layer.unsupported_area, delta=1e-6)
        # The same in the JSON layout; every other layer has none.
        d = result.to_dict()["layers"]
        self.assertEqual(d[i]["unsupported_regions"],
                         [{"outer": [[p.x, p.y, p.z] for p in region["outer"]], "holes": []}])
        self.assertEqual([k for k, l in enumerate(d) if l["unsupported_regions"]], [i])
        json.dumps(d)


    def test_a_disc_on_a_stem_is_unsupported_on_a_ring_drawn_as_a_face_with_a_hole(self):
        """A disc of radius 15, 2 thick, on a stem of radius 5 and 10 tall, as one mesh component:
        the disc's first layer stands on nothing outside the stem grown by its thickness t, a ring
        from 5 + t to 15, up to the deflection along both circles."""
        deflection = 0.05
        mushroom = Part.makeCylinder(5, 10).fuse(Part.makeCylinder(15, 2, V(0, 0, 10)))
        result = mas.slice(fc_mesh(mushroom.removeSplitter(), deflection), split_mesh=False)
        flagged = [i for i, layer in enumerate(result.layers) if layer.unsupported_regions]
        self.assertEqual(len(flagged), 1)
        layer = result.layers[flagged[0]]
        t = layer.min_thickness
        self.assertAlmostEqual(layer.lower_origin.z, 10.0, delta=TOL)
        (region,) = layer.unsupported_regions
        self.assertEqual(len(region["holes"]), 1)
        ring = math.pi * (15.0 ** 2 - (5.0 + t) ** 2)
        self.assertAlmostEqual(layer.unsupported_area, ring,
                               delta=2 * math.pi * (15.0 + 5.0 + t) * deflection)
        # The Layers object's face for it: the ring, hole and all.
        child = features.layers_shape(result).childShapes()[flagged[0]]
        (face,) = child.Faces
        self.assertTrue(face.isValid())
        self.assertEqual(len(face.Wires), 2)
        self.assertAlmostEqual(face.Area, layer.unsupported_area, delta=1e-6)
        self.assertAlmostEqual(face.BoundBox.ZMin, 10.0, delta=TOL)
        self.assertAlmostEqual(face.BoundBox.ZMax, 10.0, delta=TOL)


class SliceObjectTest(SliceTest):
    def setUp(self):
        self.doc = FreeCAD.newDocument("MasSlice")
        self.part = self.doc.addObject("Part::Feature", "Box")
        self.part.Shape = box_20_10_21()
        self.doc.recompute()
        self.folder = tempfile.mkdtemp(prefix="mas_slice_doc_")

    def tearDown(self):
        for name in list(FreeCAD.listDocuments()):
            if name.startswith("MasSlice"):
                FreeCAD.closeDocument(name)
        shutil.rmtree(self.folder)

    def make(self, source=None, **params):
        decomposition = mas.make_decomposition(source or self.part)
        layers, toolpath = mas.make_slice(decomposition, **params)
        self.doc.recompute()
        return decomposition, layers, toolpath

    def make_coaxial_wide_l(self):
        """The L sliced with a coaxial nozzle 100 mm across: every arm layer meets the plate."""
        part = self.doc.addObject("Part::Feature", "L")
        part.Shape = l_block()
        self.doc.recompute()
        return self.make(part, nozzle_body_diameter=100.0, nozzle_max_lean=0.0)

    def reopened(self, file_name):
        """Saves the document as `file_name` in the test's folder, closes it and opens it again
        (tearDown closes it); returns its Layers object."""
        path = os.path.join(self.folder, file_name)
        self.doc.saveAs(path)
        FreeCAD.closeDocument(self.doc.Name)
        self.doc = FreeCAD.openDocument(path)
        return self.doc.getObject("Layers")

    def check_box_objects(self, layers, toolpath):
        self.assertTrue(layers.isValid(), layers.getStatusString())
        self.assertTrue(toolpath.isValid(), toolpath.getStatusString())
        self.assertEqual(layers.Proxy.Type, "MultiAxisSlicer::Layers")
        self.assertEqual(toolpath.Proxy.Type, "MultiAxisSlicer::Toolpath")
        self.assertEqual(layers.LayerCount, 11)
        self.assertEqual(len(layers.Shape.childShapes()), 11)  # one sub-compound per layer
        self.assertEqual(len(layers.Shape.Wires), 11)  # one loop each
        self.assertTrue(all(w.isClosed() for w in layers.Shape.Wires))
        self.assertEqual(layers.Shape.Faces, [])  # no unsupported region
        self.assertEqual(list(layers.LayerUnsupportedAreas), [0.0] * 11)
        self.assertEqual(list(layers.LayerComponents), [0] * 11)
        self.assertEqual(list(layers.ComponentLayerCounts), [11])
        for got, want in zip(layers.LayerMaxThicknesses, [2.0] * 10 + [1.0]):
            self.assertAlmostEqual(got, want, delta=TOL)
        for got, want in zip(layers.LayerMinThicknesses, [2.0] * 10 + [1.0]):
            self.assertAlmostEqual(got, want, delta=TOL)
        for n in layers.LayerNormals:
            self.assertVectorAlmostEqual(n, (0, 0, 1))
        self.assertAlmostEqual(layers.MinThickness.Value, 1.0, delta=TOL)
        self.assertAlmostEqual(layers.MaxThickness.Value, 2.0, delta=TOL)
        self.assertAlmostEqual(layers.DepositedVolume.Value, 4200.0, delta=4200.0 * REL)
        self.assertAlmostEqual(layers.PartVolume.Value, 4200.0, delta=4200.0 * REL)
        self.assertEqual(layers.LayersOverVolumeDifference, 0)
        self.assertEqual(layers.WorstUnsupportedLayer, -1)
        bb = layers.Shape.BoundBox
        self.assertAlmostEqual(bb.ZMin, 2.0, places=6)
        self.assertAlmostEqual(bb.ZMax, 21.0, places=6)
        # The paths: contours and raster infill, no travel unless asked.
        self.assertFalse(toolpath.Shape.isNull())
        self.assertGreater(len(toolpath.Shape.Edges), 0)
        self.assertEqual(len(toolpath.Shape.childShapes()), len(features.PATH_KINDS))
        contours, infill, centre_lines, travel = toolpath.PathCounts
        self.assertEqual(contours, 2 * 11)  # two contours per layer
        self.assertGreater(infill, 0)
        self.assertEqual(travel, 0)
        self.assertEqual(toolpath.PathCount, contours + infill + centre_lines)
        self.assertGreater(toolpath.PathLength.Value, 0.0)
        self.assertGreater(toolpath.TravelLength.Value, 0.0)
        self.assertEqual(toolpath.UnfilledFeatures, 0)
        wires = toolpath.Shape.Wires
        self.assertAlmostEqual(sum(w.Length for w in wires), toolpath.PathLength.Value,
                               delta=1e-6 * toolpath.PathLength.Value)


class TestKeepingUnreachableBranches(SliceObjectTest):
    """A Decomposition's KeepBranches, and keep_unreachable_branches() setting them where the
    Layers' nozzle cannot reach some layers."""

    def test_kept_branches_stay_in_their_fathers_and_are_saved(self):
        part = self.doc.addObject("Part::Feature", "L")
        part.Shape = l_block()
        decomposition = mas.make_decomposition(part, keep_branches=[1])
        self.assertEqual(list(decomposition.KeepBranches), [1])
        self.assertEqual(decomposition.ComponentCount, 1)
        self.assertEqual(len(features.components_of(decomposition)), 1)
        self.assertEqual(list(decomposition.Notes), [
            "branch 1 (along 1,0,0): kept in its father, as asked (keep_branches); its "
            "material stays in component 0"])
        decomposition.KeepBranches = []
        self.doc.recompute()
        self.assertEqual(decomposition.ComponentCount, 2)
        decomposition.KeepBranches = [7]
        self.doc.recompute()
        self.assertIn("there is no branch 7 to keep in its father", features.failure(decomposition))
        names = [o.Name for o in self.doc.Objects]
        for bad in ("1", [1.5], [True]):
            with self.assertRaisesRegex(TypeError, "keep_branches"):
                mas.make_decomposition(part, keep_branches=bad)
        self.assertEqual([o.Name for o in self.doc.Objects], names)
        decomposition.KeepBranches = [1]
        self.doc.recompute()
        self.reopened("kept.FCStd")
        self.assertEqual(list(self.doc.getObject("Decomposition").KeepBranches), [1])

    def test_the_arm_the_nozzle_cannot_reach_goes_into_the_column(self):
        decomposition, layers, toolpath = self.make_coaxial_wide_l()
        arm = list(layers.ComponentLayerCounts)[1]
        self.assertEqual(layers.CollidingLayers, arm)
        # The slicing that keeps the arm is done once, in keep_unreachable_branches: the objects
        # take its result without decomposing or slicing again.
        calls = []
        for name in ("decompose", "slice"):
            original = getattr(features.mas, name)
            self.addCleanup(setattr, features.mas, name, original)
            setattr(features.mas, name,
                    lambda *a, _f=original, _n=name, **k: calls.append(_n) or _f(*a, **k))
        self.assertEqual(features.keep_unreachable_branches(layers), [1])
        self.assertEqual(calls, [])
        self.assertEqual(list(decomposition.KeepBranches), [1])
        self.assertEqual(decomposition.ComponentCount, 1)
        self.assertEqual(len(features.components_of(decomposition)), 1)
        self.assertIn("built on its own, its layers would meet the plate", decomposition.Notes[0])
        for obj in (decomposition, layers, toolpath):
            self.assertIsNone(features.failure(obj))
        self.assertEqual(layers.CollidingLayers, 0)
        self.assertEqual(list(layers.ComponentLayerCounts), [layers.LayerCount])
        # What slice() gives when it decomposes the L itself.
        expected = mas.slice(l_block(), nozzle_body_diameter=100.0, nozzle_max_lean=0.0)
        self.assertEqual(list(layers.LayerOrigins), [v.origin for v in expected.layers])
        # Nothing more to keep.
        self.assertEqual(features.keep_unreachable_branches(layers), [])
        self.assertEqual(list(decomposition.KeepBranches), [1])
        # Reopened and recomputed from its properties, the same.
        origins = list(layers.LayerOrigins)
        del calls[:]
        layers = self.reopened("kept_arm.FCStd")
        decomposition = self.doc.getObject("Decomposition")
        decomposition.touch()
        self.doc.recompute()
        self.assertEqual(calls, ["decompose", "slice"])
        self.assertIsNone(features.failure(layers))
        self.assertEqual(list(layers.LayerOrigins), origins)
        self.assertEqual(layers.CollidingLayers, 0)

    def test_turned_cuts_the_nozzle_cannot_reach_are_made_square_and_saved(self):
        # The spiral stair with a nozzle whose tip is 16 mm across (10 by default): leaned as far
        # as it may (30 degrees), it still meets the tread under some treads' roots where they
        # are cut square to their lines. Those cuts are made square to their branches'
        # directions, and where the nozzle still meets something their branches are kept.
        part = self.doc.addObject("Part::Feature", "Stair")
        part.Shape = support.spiral_stair()
        self.doc.recompute()
        decomposition, layers, toolpath = self.make(part, nozzle_tip_diameter=16.0)
        self.assertGreater(layers.CollidingLayers, 0)
        added = features.keep_unreachable_branches(layers)
        square, kept = list(decomposition.SquareBranches), list(decomposition.KeepBranches)
        self.assertGreater(len(square), 0)
        self.assertEqual(added, sorted(set(square) | set(kept)))
        for obj in (decomposition, layers, toolpath):
            self.assertIsNone(features.failure(obj))
        self.assertEqual(layers.CollidingLayers, 0)
        self.assertEqual(features.keep_unreachable_branches(layers), [])
        # Reopened and recomputed from its properties, the same within the tessellation's
        # deflection: a turned tread's guide runs through the centroids of its sections square
        # to its line (the engine's SlicePart.hpp), cut from the tessellation of its solid, which
        # is made anew from the part read back from its BREP text (15 digits): 5.8e-7 mm at most.
        origins = list(layers.LayerOrigins)
        deflection = mas.deflection(part.Shape)
        layers = self.reopened("squared.FCStd")
        decomposition = self.doc.getObject("Decomposition")
        self.assertEqual(list(decomposition.SquareBranches), square)
        decomposition.touch()
        self.doc.recompute()
        self.assertIsNone(features.failure(layers))
        self.assertEqual(len(layers.LayerOrigins), len(origins))
        for got, expected in zip(layers.LayerOrigins, origins):
            self.assertLess((got - expected).Length, deflection)
        self.assertEqual(layers.CollidingLayers, 0)

    def test_a_hanging_brace_goes_into_the_posts_layers(self):
        # The survey's braced frame 6 at seed 3 (the engine's truss_brace_under_beam.brep): the
        # Decomposition builds the brace along X with the far post, whose side hangs past the
        # deflection's strip in some layers, none in the nozzle's way. Kept in the posts' layers,
        # as slice() keeps it, nothing hangs so.
        part = self.doc.addObject("Part::Feature", "Truss")
        part.Shape = survey.part("truss", 6, 3)[0]
        self.doc.recompute()
        decomposition, layers, toolpath = self.make(part)
        deflection = mas.deflection(part.Shape)
        self.assertEqual(layers.CollidingLayers, 0)
        self.assertTrue(features.hangs_past_strip(features.slice_result(layers), deflection))
        self.assertEqual(features.keep_unreachable_branches(layers), [3])
        self.assertEqual(list(decomposition.KeepBranches), [3])
        self.assertEqual(len([n for n in decomposition.Notes if n.startswith("branch 3 ") and
                              "a layer of it would hang" in n]), 1)
        for obj in (decomposition, layers, toolpath):
            self.assertIsNone(features.failure(obj))
        self.assertFalse(features.hangs_past_strip(features.slice_result(layers), deflection))
        self.assertEqual(layers.CollidingLayers, 0)
        expected = mas.slice(part.Shape)
        self.assertEqual(list(layers.LayerOrigins), [v.origin for v in expected.layers])
        self.assertEqual(features.keep_unreachable_branches(layers), [])

    def test_nothing_changes_where_the_nozzle_reaches_every_layer(self):
        decomposition, layers, _ = self.make()
        self.assertEqual(features.keep_unreachable_branches(layers), [])
        self.assertEqual(list(decomposition.KeepBranches), [])
        mesh = self.doc.addObject("Mesh::Feature", "Scan")
        mesh.Mesh = fc_mesh(box_20_10_21())
        mesh_layers, _ = mas.make_slice(mesh, name="MeshLayers", toolpath_name="MeshToolpath")
        self.doc.recompute()
        with self.assertRaisesRegex(TypeError, "slices a mesh"):
            features.keep_unreachable_branches(mesh_layers)


class TestLayersOfAMesh(SliceObjectTest):
    """A Layers object over a mesh object (Source in place of Decomposition): the mesh sliced as
    one component, as ``mas.slice`` slices a mesh."""

    def add_mesh(self, shape, name="Scan"):
        import Mesh

        obj = self.doc.addObject("Mesh::Feature", name)
        obj.Mesh = Mesh.Mesh(shape.tessellate(0.01))
        self.doc.recompute()
        return obj

    def test_a_mesh_object_is_sliced_as_one_component(self):
        scan = self.add_mesh(box_20_10_21())
        before = scan.Mesh.Topology
        layers, toolpath = mas.make_slice(scan)
        self.assertIs(layers.Source, scan)
        self.assertIsNone(layers.Decomposition)
        self.assertIn(scan, layers.OutList)
        self.doc.recompute()
        self.check_box_objects(layers, toolpath)
        self.assertEqual(layers.Proxy._result[1].kind, "mesh")
        self.assertEqual(scan.Mesh.Topology, before)  # the mesh is read, never changed
        self.assertNotIn("Touched", scan.State)
        # The same as the scripting API slicing the mesh, and its program too.
        program = mas.make_machine_program(layers)
        self.doc.recompute()
        self.assertTrue(program.isValid(), program.getStatusString())
        expected = mas.slice(scan.Mesh)
        self.assertEqual(expected.to_dict(), features.slice_result(layers).to_dict())
        self.assertEqual(program.LineCount, expected.gcode().stats["lines"])

    def test_an_l_as_a_mesh_is_split_as_the_api_and_the_solid_split_it(self):
        scan = self.add_mesh(l_block())
        layers, toolpath = mas.make_slice(scan, max_layer=1.5)
        self.doc.recompute()
        self.assertTrue(toolpath.isValid(), toolpath.getStatusString())
        expected = mas.slice(scan.Mesh, max_layer=1.5)
        self.assertEqual(features.slice_result(layers).to_dict(), expected.to_dict())
        # The column up, the arm out along +X from the column's face (the solid is split at the
        # face, the mesh at the section plane a clearance past it): nothing stands on nothing.
        column, arm = layers.ComponentLayerCounts
        self.assertEqual(list(layers.LayerComponents), [0] * column + [1] * arm)
        for i, n in enumerate(layers.LayerNormals):
            self.assertVectorAlmostEqual(n, (0, 0, 1) if i < column else (1, 0, 0))
        self.assertEqual(layers.WorstUnsupportedArea.Value, 0.0)
        solid = mas.slice(l_block(), max_layer=1.5)
        self.assertEqual([c["layer_count"] for c in solid.components][1], arm)
        self.assertAlmostEqual(layers.DepositedVolume.Value, solid.stats["deposited_volume_mm3"],
                               delta=1e-6 * solid.stats["deposited_volume_mm3"])
        # SplitMesh off: one component along +Z, the arm's first layer standing on nothing.
        self.assertEqual(layers.getGroupOfProperty("SplitMesh"), "Layers")
        layers.SplitMesh = False
        self.doc.recompute()
        whole = mas.slice(scan.Mesh, max_layer=1.5, split_mesh=False)
        self.assertEqual(list(layers.ComponentLayerCounts), [len(whole.layers)])
        self.assertEqual(layers.WorstUnsupportedArea.Value,
                         whole.stats["worst_unsupported_area_mm2"])
        self.assertGreater(layers.WorstUnsupportedArea.Value, 100.0)

    def test_a_link_to_a_mesh_object_is_sliced_where_the_link_shows_it(self):
        # An App::Link to the L's mesh object, turned 90 degrees about Z and moved (the mesh's own
        # placement overridden, LinkTransform off): sliced as the mesh placed as the link shows
        # it (to rounding: the link's matrix is not the placement's), as the scripting API
        # slices the link; moving the link moves the layers; a reopened document slices it again.
        scan = self.add_mesh(l_block())
        scan.Placement.Base = FreeCAD.Vector(300, 0, 0)
        link = self.doc.addObject("App::Link", "ScanLink")
        link.LinkedObject = scan
        link.Placement = FreeCAD.Placement(FreeCAD.Vector(0, 50, 0),
                                           FreeCAD.Rotation(FreeCAD.Vector(0, 0, 1), 90))
        self.doc.recompute()

        def shown(**params):  # the mesh in its own coordinates, placed by the link, sliced
            mesh = scan.Mesh.copy()
            mesh.Placement = link.Placement
            return mas.slice(mesh, **params)

        def same(result, expected):
            self.assertEqual([layer.component for layer in result.layers],
                             [layer.component for layer in expected.layers])
            for got, want in zip(result.layers, expected.layers):
                self.assertVectorAlmostEqual(got.origin, want.origin, places=6)
                self.assertVectorAlmostEqual(got.normal, want.normal, places=9)
                self.assertAlmostEqual(got.unsupported_area, want.unsupported_area, places=6)

        self.assertTrue(features.is_mesh_part(link))
        layers, toolpath = mas.make_slice(link, max_layer=1.5)
        self.assertIs(layers.Source, link)
        self.doc.recompute()
        self.assertTrue(toolpath.isValid(), toolpath.getStatusString())
        expected = shown(max_layer=1.5)
        same(features.slice_result(layers), expected)
        self.assertEqual(mas.slice(link, max_layer=1.5).to_dict(),
                         features.slice_result(layers).to_dict())
        # The column along +Z, the arm along +X turned to +Y: nothing stands on nothing.
        column, arm = layers.ComponentLayerCounts
        self.assertGreater(arm, 0)
        self.assertVectorAlmostEqual(layers.LayerNormals[column], (0, 1, 0))
        self.assertEqual(layers.WorstUnsupportedArea.Value, 0.0)
        link.Placement.Base = FreeCAD.Vector(0, 80, 0)
        self.doc.recompute()
        same(features.slice_result(layers), shown(max_layer=1.5))
        self.assertAlmostEqual(features.slice_result(layers).layers[0].origin.y,
                               expected.layers[0].origin.y + 30.0, places=6)
        layers = self.reopened("MasSliceMeshLink.FCStd")
        link, scan = self.doc.getObject("ScanLink"), self.doc.getObject("Scan")
        self.assertIs(layers.Source, link)
        layers.MaxLayer = 2.0
        self.doc.recompute()
        self.assertTrue(layers.isValid(), layers.getStatusString())
        same(features.slice_result(layers), shown())

    def test_avoid_collisions_keeps_a_piece_the_nozzle_cannot_reach_in_its_father(self):
        # A coaxial nozzle 100 mm across would meet the plate at each of the arm's layers.
        scan = self.add_mesh(l_block())
        layers, _ = mas.make_slice(scan, nozzle_body_diameter=100.0, nozzle_max_lean=0.0)
        self.doc.recompute()
        self.assertTrue(layers.AvoidCollisions)
        self.assertEqual((layers.CollidingLayers, len(layers.ComponentLayerCounts)), (0, 1))
        layers.AvoidCollisions = False
        self.doc.recompute()
        column, arm = layers.ComponentLayerCounts
        self.assertEqual(list(layers.CollisionLayers), list(range(column, column + arm)))

    def test_the_layers_follow_the_mesh(self):
        import Mesh

        scan = self.add_mesh(box_20_10_21())
        layers, toolpath = mas.make_slice(scan)
        self.doc.recompute()
        self.assertEqual(layers.LayerCount, 11)
        # Another mesh of as many points and facets, the same volume and area: 10 x 20, not 20 x
        # 10. FreeCAD 0.20 marks the object changed only when told (see the README).
        scan.Mesh = Mesh.Mesh(Part.makeBox(10, 20, 21).tessellate(0.01))
        scan.touch()
        self.doc.recompute()
        self.assertTrue(toolpath.isValid(), toolpath.getStatusString())
        self.assertEqual(layers.LayerCount, 11)
        bb = layers.Shape.BoundBox
        self.assertAlmostEqual(bb.XLength, 10.0, delta=TOL)
        self.assertAlmostEqual(bb.YLength, 20.0, delta=TOL)
        self.assertAlmostEqual(toolpath.Shape.BoundBox.YLength, 20.0, delta=1.0)
        scan.Mesh = Mesh.Mesh(Part.makeBox(10, 20, 15).tessellate(0.01))
        scan.touch()
        self.doc.recompute()
        self.assertEqual(layers.LayerCount, 8)  # 15 mm: seven of 2 mm, one of 1 mm
        self.assertAlmostEqual(layers.PartVolume.Value, 3000.0, delta=3000.0 * REL)
        layers.MaxLayer = 3.0
        self.doc.recompute()
        self.assertEqual(layers.LayerCount, 5)
        self.assertEqual(toolpath.PathCounts[0], 2 * 5)

    def test_the_layers_follow_a_mesh_turned_over_in_its_own_box(self):
        # The L turned 180 degrees about Y and moved back into its box: as many points and facets,
        # the same volume, area, box and placement, which was all the remembered result was keyed
        # by, and the Layers object kept the upright L's layers.
        scan = self.add_mesh(l_block())
        layers, toolpath = mas.make_slice(scan)
        self.doc.recompute()
        upright = features.slice_result(layers).to_dict()
        turned = scan.Mesh.copy()
        box = turned.BoundBox
        turned.transform(FreeCAD.Matrix(-1, 0, 0, box.XMin + box.XMax, 0, 1, 0, 0,
                                        0, 0, -1, box.ZMin + box.ZMax, 0, 0, 0, 1))
        self.assertEqual((turned.CountPoints, turned.CountFacets),
                         (scan.Mesh.CountPoints, scan.Mesh.CountFacets))
        self.assertTrue(turned.BoundBox.isInside(box) and box.isInside(turned.BoundBox))
        scan.Mesh = turned
        scan.touch()
        self.doc.recompute()
        self.assertTrue(toolpath.isValid(), toolpath.getStatusString())
        expected = mas.slice(turned).to_dict()
        self.assertNotEqual(expected, upright)
        self.assertEqual(features.slice_result(layers).to_dict(), expected)
        self.assertEqual(layers.LayerCount, len(expected["layers"]))

    def test_the_objects_made_from_the_layers_take_its_result_without_reading_the_mesh(self):
        # The mesh's fingerprint reads every point and facet (40 ms on a 75000-facet mesh): the
        # Layers object takes it when it is recomputed; its Toolpath, BuildPreview (each step)
        # and MachineProgram take its result as it is.
        scan = self.add_mesh(box_20_10_21())
        layers, toolpath = mas.make_slice(scan)
        preview = mas.make_build_preview(layers)
        program = mas.make_machine_program(layers)
        self.doc.recompute()
        taken = []
        fingerprint = features._mesh_fingerprint
        features._mesh_fingerprint = lambda obj: taken.append(obj.Name) or fingerprint(obj)
        try:
            preview.Step = 3
            toolpath.touch()
            program.touch()
            self.doc.recompute()
            self.assertEqual(taken, [])
            layers.MaxLayer = 3.0
            self.doc.recompute()
            self.assertEqual(taken, ["Scan"])
        finally:
            features._mesh_fingerprint = fingerprint
        for obj in (layers, toolpath, preview, program):
            self.assertTrue(obj.isValid(), obj.getStatusString())
        self.assertEqual(layers.LayerCount, 7)  # 21 mm in 3 mm layers
        self.assertEqual(toolpath.PathCounts[0], 2 * 7)
        self.assertEqual(program.LineCount, features.slice_result(layers).gcode().stats["lines"])

    def test_a_bad_source_marks_the_object_with_the_message(self):
        scan = self.add_mesh(box_20_10_21())
        layers, toolpath = mas.make_slice(scan)
        self.doc.recompute()
        self.check_box_objects(layers, toolpath)
        layers.Source = self.part  # a solid: through a Decomposition
        self.doc.recompute()
        self.assertEqual(layers.getStatusString(),
                         "Layers: Source 'Box' is not a mesh: a solid is sliced through a "
                         "Decomposition object (set Decomposition, not Source or Axis)")
        decomposition = mas.make_decomposition(self.part)
        layers.Source = scan
        layers.Decomposition = decomposition
        self.doc.recompute()
        self.assertEqual(layers.getStatusString(),
                         "Layers: both Decomposition 'Decomposition' and Source 'Scan' are set: a "
                         "Layers object slices a decomposition or a mesh, not both")
        layers.Decomposition = None
        layers.Deflection = 0.05
        self.doc.recompute()
        self.assertIn("'Scan' is a mesh, sliced as it is; Deflection applies to solids only",
                      layers.getStatusString())
        layers.Deflection = 0.0
        layers.FillHoles = 5.0
        self.doc.recompute()
        self.assertIn("'Scan' is a mesh, sliced as it is; FillHoles needs a solid",
                      layers.getStatusString())
        layers.FillHoles = 0.0
        import Mesh

        points, facets = scan.Mesh.Topology
        scan.Mesh = Mesh.Mesh([[points[i] for i in f] for f in facets[:-1]])  # open
        scan.touch()
        self.doc.recompute()
        self.assertIn("Invalid", layers.State)
        self.assertIn("'Scan'", layers.getStatusString())
        self.assertIn("3 boundary edges", layers.getStatusString())
        scan.Mesh = Mesh.Mesh(box_20_10_21().tessellate(0.01))
        scan.touch()
        self.doc.recompute()
        self.check_box_objects(layers, toolpath)

    def test_the_axis_object_of_a_mesh_gives_the_axis_its_parameters(self):
        scan = self.add_mesh(l_block())
        axis = mas.make_centroidal_axis(scan, step=2.5)
        self.doc.recompute()
        layers, toolpath = mas.make_slice(axis)
        self.assertIs(layers.Axis, axis)
        self.assertIsNone(layers.Source)
        self.assertIsNone(layers.Decomposition)
        self.doc.recompute()
        self.assertTrue(toolpath.isValid(), toolpath.getStatusString())
        got = features.slice_result(layers).to_dict()
        self.assertEqual(got, mas.slice(scan.Mesh, step=2.5).to_dict())
        self.assertNotEqual(got, mas.slice(scan.Mesh).to_dict())  # the step tells
        self.assertEqual(features.sliced_mesh(layers), scan)
        axis.Step = 3.0
        axis.BreakAngle = 40.0
        self.doc.recompute()
        self.assertTrue(toolpath.isValid(), toolpath.getStatusString())
        self.assertEqual(features.slice_result(layers).to_dict(),
                         mas.slice(scan.Mesh, step=3.0, break_angle=40.0).to_dict())
        layers.Source = scan  # both may be set, the axis over the mesh
        self.doc.recompute()
        self.assertTrue(layers.isValid(), layers.getStatusString())

    def test_bad_axis_links_are_named(self):
        scan = self.add_mesh(l_block())
        other = self.add_mesh(box_20_10_21(), "Other")
        axis = mas.make_centroidal_axis(scan)
        layers, toolpath = mas.make_slice(axis)
        self.doc.recompute()
        self.assertTrue(toolpath.isValid(), toolpath.getStatusString())
        for links, message in (
                (dict(Source=other), "Layers: Axis 'CentroidalAxis' belongs to 'Scan', not to "
                                     "the Source 'Other'"),
                (dict(Decomposition=mas.make_decomposition(self.part)),
                 "Layers: both Decomposition 'Decomposition' and Axis 'CentroidalAxis' are set: a "
                 "Layers object slices a decomposition or a mesh, not both"),
                (dict(Axis=other), "Layers: Axis 'Other' is not a CentroidalAxis object"),
                (dict(Axis=mas.make_centroidal_axis(self.part, name="BoxAxis")),
                 "Layers: Axis' Source 'Box' is not a mesh: a solid is sliced through a "
                 "Decomposition object (set Decomposition, not Source or Axis)")):
            for prop, value in links.items():
                setattr(layers, prop, value)
            self.doc.recompute()
            self.assertEqual(layers.getStatusString(), message)
            layers.Source = layers.Decomposition = None
            layers.Axis = axis
        self.doc.recompute()
        self.assertTrue(toolpath.isValid(), toolpath.getStatusString())
        with self.assertRaisesRegex(TypeError, "'BoxAxis' is not over a mesh but over 'Box'"):
            mas.make_slice(self.doc.getObject("BoxAxis"))

    def test_make_rejects_what_a_mesh_cannot_take_before_adding_anything(self):
        scan = self.add_mesh(box_20_10_21())
        names = [o.Name for o in self.doc.Objects]
        with self.assertRaisesRegex(ValueError, "'Scan' is a mesh, sliced as it is; deflection"):
            mas.make_slice(scan, deflection=0.05)
        with self.assertRaisesRegex(ValueError, "'Scan' is a mesh, sliced as it is; fill_holes"):
            mas.make_slice(scan, fill_holes=5.0)
        self.assertEqual([o.Name for o in self.doc.Objects], names)

    def test_save_reopen_recompute_and_undo(self):
        scan = self.add_mesh(box_20_10_21())
        self.doc.UndoMode = 1
        names = [o.Name for o in self.doc.Objects]
        self.doc.openTransaction("Slice")
        layers, toolpath = mas.make_slice(scan, max_layer=1.5)
        self.doc.recompute()
        self.doc.commitTransaction()
        self.assertEqual(layers.LayerCount, 14)
        self.doc.undo()
        self.assertEqual([o.Name for o in self.doc.Objects], names)
        self.doc.redo()
        layers = self.reopened("MasSliceMesh.FCStd")
        toolpath = self.doc.getObject("Toolpath")
        self.assertIs(layers.Source, self.doc.getObject("Scan"))
        self.assertIsNone(layers.Decomposition)
        self.assertEqual(layers.LayerCount, 14)
        self.assertEqual(len(layers.Shape.Wires), 14)
        self.assertIsNone(getattr(layers.Proxy, "_result", None))
        toolpath.ShowTravel = True  # the slicing is redone on demand
        self.doc.recompute()
        self.assertTrue(toolpath.isValid(), toolpath.getStatusString())
        self.assertGreater(toolpath.PathCounts[3], 0)
        layers.MaxLayer = 2.0
        toolpath.ShowTravel = False
        self.doc.recompute()
        self.check_box_objects(layers, toolpath)


class TestLayersObject(SliceObjectTest):
    def test_make_slice_on_a_box_decomposition(self):
        decomposition, layers, toolpath = self.make()
        self.assertIs(layers.Decomposition, decomposition)
        self.assertIs(toolpath.Layers, layers)
        self.assertIn(decomposition, layers.OutList)
        self.assertIn(layers, toolpath.OutList)
        self.assertEqual(layers.MinLayer.Value, 0.5)
        self.assertEqual(layers.MaxLayer.Value, 2.0)
        self.assertEqual(layers.Infill, "raster")
        self.assertEqual(layers.getEnumerationsOfProperty("Infill"), ["raster", "contour", "none"])
        self.assertEqual(layers.ContourCount, 2)
        self.assertEqual(layers.Deflection.Value, 0.0)
        self.assertFalse(toolpath.ShowTravel)
        self.check_box_objects(layers, toolpath)
        self.assertEqual(layers.getGroupOfProperty("BeadWidth"), "Paths")
        self.assertEqual(layers.getGroupOfProperty("MaxLayer"), "Layers")
        self.assertIn("ReadOnly", layers.getEditorMode("LayerCount"))

    def test_parameters_given_to_make_slice_are_used(self):
        decomposition, layers, toolpath = self.make(max_layer=1.5, bead_width=1.2,
                                                    infill="none", contour_count=1,
                                                    show_travel=True, deflection=0.02)
        self.assertTrue(layers.isValid(), layers.getStatusString())
        self.assertEqual(layers.MaxLayer.Value, 1.5)
        self.assertEqual(layers.BeadWidth.Value, 1.2)
        self.assertEqual(layers.Deflection.Value, 0.02)
        self.assertEqual(layers.LayerCount, 14)
        self.assertEqual(list(toolpath.PathCounts[:3]), [14, 0, 0])  # one contour per layer
        self.assertGreater(toolpath.PathCounts[3], 0)  # travel shown

    def test_changing_parameters_recomputes(self):
        decomposition, layers, toolpath = self.make()
        paths = toolpath.PathCount
        layers.MaxLayer = 1.5
        self.doc.recompute()
        self.assertTrue(layers.isValid(), layers.getStatusString())
        self.assertEqual(layers.LayerCount, 14)
        self.assertEqual(len(layers.Shape.Wires), 14)
        self.assertGreater(toolpath.PathCount, paths)  # the toolpath follows
        self.assertEqual(toolpath.PathCounts[0], 2 * 14)
        layers.MaxLayer = 3.0
        self.doc.recompute()
        self.assertEqual(layers.LayerCount, 7)
        self.assertEqual(toolpath.PathCounts[0], 2 * 7)
        layers.Infill = "none"
        self.doc.recompute()
        self.assertEqual(list(toolpath.PathCounts), [14, 0, 0, 0])
        toolpath.ShowTravel = True
        self.doc.recompute()
        self.assertGreater(toolpath.PathCounts[3], 0)
        self.assertEqual(len(toolpath.Shape.childShapes()[3].Wires), toolpath.PathCounts[3])
        self.assertEqual(toolpath.UncoveredArea.Value, 0.0)  # not measured
        layers.MeasureCoverage = True
        self.doc.recompute()
        self.assertTrue(toolpath.isValid(), toolpath.getStatusString())
        self.assertGreaterEqual(toolpath.UncoveredArea.Value, 0.0)
        self.assertTrue(layers.Proxy._result[1].params["measure_coverage"])

    def test_source_changes_flow_through_the_decomposition(self):
        decomposition, layers, toolpath = self.make()
        self.part.Shape = l_block()
        self.doc.recompute()
        features.sync_components(decomposition)
        self.doc.recompute()
        self.assertTrue(layers.isValid(), layers.getStatusString())
        self.assertEqual(list(layers.ComponentLayerCounts), [30, 25])
        self.assertEqual(list(layers.BuildOrder), [0, 1])
        self.assertEqual(list(layers.LayerComponents), [0] * 30 + [1] * 25)
        for i, n in enumerate(layers.LayerNormals):
            self.assertVectorAlmostEqual(n, (0, 0, 1) if i < 30 else (1, 0, 0))
        self.assertEqual(len(layers.Shape.childShapes()), 55)
        arm = layers.Shape.childShapes()[30]
        self.assertAlmostEqual(arm.BoundBox.XMin, 22.0, places=6)
        self.assertAlmostEqual(arm.BoundBox.XMax, 22.0, places=6)
        self.assertTrue(toolpath.isValid(), toolpath.getStatusString())
        self.assertGreater(toolpath.Shape.BoundBox.XMax, 60.0)

    def test_the_decomposition_is_not_computed_again(self):
        calls = []
        decompose = mas.decompose

        def counting(*args, **kwargs):
            calls.append(args)
            return decompose(*args, **kwargs)

        mas.decompose = counting
        try:
            decomposition = mas.make_decomposition(self.part)
            self.assertEqual(len(calls), 1)
            layers, toolpath = mas.make_slice(decomposition)
            self.doc.recompute()
            self.check_box_objects(layers, toolpath)
            self.assertEqual(len(calls), 1)  # the Decomposition object's result is reused
            decomposition.FaceAngle = 5.0
            self.doc.recompute()
            self.assertEqual(len(calls), 2)
            self.check_box_objects(layers, toolpath)
        finally:
            mas.decompose = decompose

    def test_the_source_is_not_modified(self):
        before = self.part.Shape.exportBrepToString()
        decomposition, layers, toolpath = self.make()
        self.assertTrue(toolpath.isValid())
        self.assertEqual(self.part.Shape.exportBrepToString(), before)
        self.assertNotIn("Touched", self.part.State)
        self.assertNotIn("Touched", decomposition.State)

    def test_unsupported_regions_are_faces_over_a_holes_ceiling_and_are_saved(self):
        """A 30 x 10 x 20 block with a horizontal hole of radius 4 along Y at x = 15, z = 10: no
        direction builds its ceiling on what is below, so the layers bridging it are unsupported
        there. The Layers object shows each such region as a face in its layer's sub-compound, on
        the plane the layer is deposited on, within the hole's upper half."""
        self.part.Shape = Part.makeBox(30, 10, 20).cut(
            Part.makeCylinder(4, 10, V(15, 0, 10), V(0, 1, 0)))
        _decomposition, layers, _toolpath = self.make()
        self.assertTrue(layers.isValid(), layers.getStatusString())
        result = features.slice_result(layers)
        areas = [layer.unsupported_area for layer in result.layers]
        self.assertEqual(list(layers.LayerUnsupportedAreas), areas)
        self.assertEqual(layers.WorstUnsupportedArea.Value, max(areas))
        self.assertGreater(max(areas), 0.0)
        self.assertEqual(len(layers.Shape.Faces),
                         sum(len(layer.unsupported_regions) for layer in result.layers))
        for i, (child, layer) in enumerate(zip(layers.Shape.childShapes(), result.layers)):
            self.assertAlmostEqual(sum(f.Area for f in child.Faces), areas[i],
                                   delta=1e-9 + 1e-6 * areas[i], msg="layer {}".format(i))
            for f in child.Faces:
                bb = f.BoundBox
                self.assertGreaterEqual(bb.XMin, 11.0 - 1e-6)
                self.assertLessEqual(bb.XMax, 19.0 + 1e-6)
                self.assertGreaterEqual(bb.ZMin, 10.0)
                self.assertLessEqual(bb.ZMax, 14.0)
                for v in f.Vertexes:
                    self.assertAlmostEqual((v.Point - layer.lower_origin).dot(layer.lower_normal),
                                           0.0, places=9)
        faces = len(layers.Shape.Faces)
        path = os.path.join(self.folder, "hole.FCStd")
        self.doc.saveAs(path)
        FreeCAD.closeDocument(self.doc.Name)
        doc = FreeCAD.openDocument(path)
        layers = doc.getObject("Layers")
        self.assertEqual(len(layers.Shape.Faces), faces)
        self.assertEqual(list(layers.LayerUnsupportedAreas), areas)

    def test_fill_holes_deposits_a_holes_ceiling_solid_lists_it_and_is_saved(self):
        self.part.Shape = block_with_pin_hole()
        _decomposition, layers, _toolpath = self.make(fill_holes=8.0)
        self.assertTrue(layers.isValid(), layers.getStatusString())
        self.assertEqual(layers.FillHoles.Value, 8.0)
        self.assertEqual(layers.FilledHoleCount, 1)
        self.assertEqual(list(layers.FilledHoleComponents), [0])
        self.assertVectorAlmostEqual(layers.FilledHoleCentres[0], (15, 5, 10))
        self.assertAlmostEqual(abs(layers.FilledHoleAxes[0].y), 1.0, places=12)
        self.assertAlmostEqual(layers.FilledHoleDiameters[0], 8.0, places=9)
        self.assertAlmostEqual(layers.FilledHoleLengths[0], 10.0, places=9)
        filled = math.pi * 16.0 * 10.0
        self.assertAlmostEqual(layers.FilledVolume.Value, filled, delta=filled * REL)
        self.assertEqual(layers.Shape.Faces, [])  # no unsupported region left
        self.assertEqual(layers.WorstUnsupportedArea.Value, 0.0)
        path = os.path.join(self.folder, "filled.FCStd")
        self.doc.saveAs(path)
        FreeCAD.closeDocument(self.doc.Name)
        doc = FreeCAD.openDocument(path)
        layers = doc.getObject("Layers")
        self.assertEqual(layers.FillHoles.Value, 8.0)
        self.assertEqual(layers.FilledHoleCount, 1)
        self.assertVectorAlmostEqual(layers.FilledHoleCentres[0], (15, 5, 10))
        # Back to open holes: the ceiling overhangs again and nothing is to drill.
        layers.FillHoles = 0.0
        doc.recompute()
        self.assertTrue(layers.isValid(), layers.getStatusString())
        self.assertEqual(layers.FilledHoleCount, 0)
        self.assertEqual(list(layers.FilledHoleCentres), [])
        self.assertEqual(layers.FilledVolume.Value, 0.0)
        self.assertGreater(layers.WorstUnsupportedArea.Value, 0.0)
        self.assertGreater(len(layers.Shape.Faces), 0)

    def test_save_close_reopen_recompute(self):
        decomposition, layers, toolpath = self.make(max_layer=1.5, infill="contour")
        self.assertEqual(layers.LayerCount, 14)
        path = os.path.join(self.folder, "slice.FCStd")
        self.doc.saveAs(path)
        FreeCAD.closeDocument(self.doc.Name)

        doc = FreeCAD.openDocument(path)
        layers, toolpath = doc.getObject("Layers"), doc.getObject("Toolpath")
        self.assertIsInstance(layers.Proxy, features.LayersFeature)
        self.assertIsInstance(toolpath.Proxy, features.ToolpathFeature)
        self.assertIs(layers.Decomposition, doc.getObject("Decomposition"))
        self.assertIs(toolpath.Layers, layers)
        self.assertEqual(layers.MaxLayer.Value, 1.5)
        self.assertEqual(layers.Infill, "contour")
        self.assertEqual(layers.LayerCount, 14)
        self.assertEqual(list(layers.BuildOrder), [0])
        self.assertEqual(len(layers.Shape.Wires), 14)  # the shapes are saved with the document
        self.assertGreater(len(toolpath.Shape.Edges), 0)
        self.assertIsNone(getattr(layers.Proxy, "_result", None))  # the result is not saved
        # The toolpath recomputes on its own: the slicing is redone on demand.
        toolpath.ShowTravel = True
        doc.recompute()
        self.assertTrue(toolpath.isValid(), toolpath.getStatusString())
        self.assertGreater(toolpath.PathCounts[3], 0)
        layers.MaxLayer = 2.0
        doc.recompute()
        self.assertEqual(layers.LayerCount, 11)
        self.assertTrue(toolpath.isValid(), toolpath.getStatusString())
        doc.save()  # saving restored proxies works too

    def test_max_tilt_is_a_property_and_old_documents_keep_the_tilt_unbounded(self):
        decomposition, layers, toolpath = self.make()
        self.assertEqual((decomposition.MaxTilt.Value, layers.MaxTilt.Value), (100.0, 100.0))
        self.assertEqual(layers.getGroupOfProperty("MaxTilt"), "Layers")
        layers.MaxTilt = 80.0
        self.doc.recompute()
        self.assertFalse(layers.isValid())
        self.assertIn("MaxTilt must be in [90, 180] degrees, got 80", layers.getStatusString())
        layers.MaxTilt = 100.0
        self.doc.recompute()
        self.assertTrue(layers.isValid(), layers.getStatusString())
        # Saved before the property: computed with the tilt unbounded, and kept so on reopening.
        decomposition.removeProperty("MaxTilt")
        layers.removeProperty("MaxTilt")
        name = decomposition.Name
        layers = self.reopened("MasSliceOldTilt.FCStd")
        decomposition = self.doc.getObject(name)
        self.assertEqual((decomposition.MaxTilt.Value, layers.MaxTilt.Value), (180.0, 180.0))
        self.assertEqual(layers.LayerCount, 11)

    def test_old_documents_keep_their_cuts_square_to_the_directions(self):
        # Six blades 60 degrees apart: four run between +-X and +-Y, their cuts turned square to
        # their lines (TurnCuts). A document saved before the turned cuts opens with TurnCuts
        # off: recomputed, its cuts stay square to the directions its KeepBranches were found for.
        part = self.doc.addObject("Part::Feature", "Hub")
        part.Shape = support.hub_with_six_blades()
        decomposition = mas.make_decomposition(part)
        self.assertTrue(decomposition.TurnCuts)

        def off_directions(obj):
            return sum(1 for d in obj.BuildDirections
                       if abs(abs(d.x) + abs(d.y) + abs(d.z) - 1.0) > 1e-9)

        self.assertEqual(off_directions(decomposition), 4)
        decomposition.removeProperty("TurnCuts")
        name = decomposition.Name
        self.reopened("MasOldCuts.FCStd")
        decomposition = self.doc.getObject(name)
        self.assertFalse(decomposition.TurnCuts)
        decomposition.touch()
        self.doc.recompute()
        self.assertIsNone(features.failure(decomposition))
        self.assertEqual(off_directions(decomposition), 0)
        decomposition.TurnCuts = True
        self.doc.recompute()
        self.assertEqual(off_directions(decomposition), 4)

    def test_undo_removes_both_objects(self):
        self.doc.UndoMode = 1
        decomposition = mas.make_decomposition(self.part)
        names = [o.Name for o in self.doc.Objects]
        self.doc.openTransaction("Slice")
        layers, toolpath = mas.make_slice(decomposition)
        self.doc.recompute()
        self.doc.commitTransaction()
        self.assertEqual(len(self.doc.Objects), len(names) + 2)
        self.doc.undo()
        self.assertEqual([o.Name for o in self.doc.Objects], names)
        self.doc.redo()
        layers, toolpath = self.doc.getObject("Layers"), self.doc.getObject("Toolpath")
        self.assertIs(toolpath.Layers, layers)
        self.assertEqual(layers.LayerCount, 11)

    def test_the_sequence_and_its_collisions_are_properties_and_are_saved(self):
        decomposition, layers, toolpath = self.make_coaxial_wide_l()
        self.assertTrue(layers.isValid(), layers.getStatusString())
        self.assertEqual(layers.getGroupOfProperty("NozzleBodyDiameter"), "Nozzle")
        self.assertEqual(layers.NozzleBodyDiameter.Value, 100.0)
        self.assertEqual(layers.NozzleConeAngle.Value, 30.0)
        self.assertEqual(layers.getGroupOfProperty("NozzleMaxLean"), "Nozzle")
        self.assertEqual(layers.NozzleMaxLean.Value, 0.0)
        self.assertTrue(layers.CheckPlate)
        arm = [i for i, c in enumerate(layers.LayerComponents) if c == 1]
        self.assertEqual(list(layers.Sequence), list(range(layers.LayerCount)))
        self.assertEqual(layers.ComponentSwitches, 1)
        self.assertEqual(layers.LeanedLayers, 0)
        self.assertEqual(list(layers.LayerToolAxes), list(layers.LayerNormals))
        self.assertEqual(layers.CollidingLayers, len(arm))
        self.assertEqual(list(layers.CollisionLayers), arm)
        self.assertEqual(list(layers.CollisionObstacles), [-1] * len(arm))
        self.assertEqual(len(layers.CollisionPoints), len(arm))
        self.assertTrue(all(abs(p.z) < 1e-9 for p in layers.CollisionPoints))
        self.assertIn("ReadOnly", layers.getEditorMode("CollidingLayers"))
        layers = self.reopened("MasSliceCollisions.FCStd")
        self.assertEqual(layers.NozzleBodyDiameter.Value, 100.0)
        self.assertEqual(layers.CollidingLayers, len(arm))
        self.assertEqual(list(layers.Sequence), list(range(layers.LayerCount)))
        # Allowed to lean, the arm's layers lean 10 degrees up and clear the plate.
        layers.NozzleMaxLean = 30.0
        self.doc.recompute()
        self.assertTrue(layers.isValid(), layers.getStatusString())
        self.assertEqual(layers.CollidingLayers, 0)
        self.assertEqual(layers.LeanedLayers, len(arm))
        for i, (axis, normal) in enumerate(zip(layers.LayerToolAxes, layers.LayerNormals)):
            if i in arm:
                self.assertAlmostEqual(axis.getAngle(normal), math.radians(10.0), places=9)
                self.assertGreater(axis.z, 0.17)
            else:
                self.assertEqual(axis, normal)
        layers.NozzleMaxLean = 0.0
        layers.CheckPlate = False
        self.doc.recompute()
        self.assertTrue(layers.isValid(), layers.getStatusString())
        self.assertEqual(layers.CollidingLayers, 0)
        self.assertEqual(list(layers.CollisionLayers), [])
        layers.NozzleMargin = 0.0
        self.doc.recompute()
        self.assertIn("Invalid", layers.State)
        self.assertEqual(layers.getStatusString(),
                         "NozzleMargin must be a positive number of millimetres, got 0.0")

    def test_a_document_saved_before_the_nozzle_could_lean_keeps_it_coaxial(self):
        # The L with a 100 mm body, computed coaxially and saved without the lean's properties,
        # as documents were: reopened, NozzleMaxLean is 0 and the tool axes are the normals, so
        # what it shows (25 arm layers meeting the plate) stays what it computes.
        decomposition, layers, toolpath = self.make_coaxial_wide_l()
        arm = [i for i, c in enumerate(layers.LayerComponents) if c == 1]
        self.assertEqual(layers.CollidingLayers, len(arm))
        for prop in ("NozzleMaxLean", "LeanedLayers", "LayerToolAxes"):
            layers.removeProperty(prop)
        layers = self.reopened("MasSliceBeforeLean.FCStd")
        self.assertEqual(layers.NozzleMaxLean.Value, 0.0)
        self.assertEqual(layers.LeanedLayers, 0)
        self.assertEqual(list(layers.LayerToolAxes), list(layers.LayerNormals))
        self.assertEqual(len(layers.LayerToolAxes), layers.LayerCount)
        layers.touch()
        self.doc.recompute()
        self.assertTrue(layers.isValid(), layers.getStatusString())
        self.assertEqual(layers.CollidingLayers, len(arm))
        self.assertEqual(layers.LeanedLayers, 0)
        # A new object leans by default.
        self.assertEqual(mas.make_slice(layers.Decomposition, name="Again")[0].NozzleMaxLean.Value,
                         30.0)

    def test_bad_parameters_mark_the_object_with_the_message(self):
        decomposition, layers, toolpath = self.make()
        layers.MinLayer = 3.0  # more than MaxLayer
        self.doc.recompute()
        self.assertIn("Invalid", layers.State)
        # In the properties' names, as the property editor shows them (not "min_layer").
        self.assertEqual(layers.getStatusString(),
                         "need 0 < MinLayer <= MaxLayer, got MinLayer 3.0 and MaxLayer 2.0 mm")
        layers.MinLayer = 0.5
        layers.BeadWidth = 0.0
        self.doc.recompute()
        self.assertIn("Invalid", layers.State)
        self.assertIn("BeadWidth must be a positive, finite number", layers.getStatusString())
        layers.BeadWidth = -1.0  # a length property keeps it at 0
        self.doc.recompute()
        self.assertIn("BeadWidth must be a positive, finite number", layers.getStatusString())
        layers.BeadWidth = 1.0
        # A mesh's, which the panel does not show for a Decomposition and slicing leaves alone
        # (the scripting API's advice on slice()'s split_mesh was the object's message).
        layers.SplitMesh = False
        self.doc.recompute()
        self.check_box_objects(layers, toolpath)
        layers.SplitMesh = True
        layers.Decomposition = None
        self.doc.recompute()
        self.assertEqual(layers.getStatusString(),
                         "Layers: neither Decomposition nor Source is set")
        layers.Decomposition = self.part
        self.doc.recompute()
        self.assertIn("not a Decomposition object", layers.getStatusString())
        toolpath.Layers = decomposition
        self.doc.recompute()
        self.assertIn("not a Layers object", toolpath.getStatusString())
        # Both recover once their inputs are fixed.
        layers.Decomposition = decomposition
        toolpath.Layers = layers
        self.doc.recompute()
        self.check_box_objects(layers, toolpath)

    def test_make_rejects_bad_parameters_before_adding_anything(self):
        decomposition = mas.make_decomposition(self.part)
        names = [o.Name for o in self.doc.Objects]
        for error, name, kwargs in (
                (ValueError, "min_layer", dict(min_layer=3.0, max_layer=2.0)),
                (ValueError, "bead_width", dict(bead_width=0.0)),
                (ValueError, "bead_width", dict(bead_width=-1.0)),
                (ValueError, "bead_width must be a positive, finite", dict(bead_width=math.inf)),
                (ValueError, "infill", dict(infill="bogus")),
                (ValueError, "min_feature", dict(min_feature=-1.0)),
                (ValueError, "fill_holes", dict(fill_holes=-1.0)),
                (ValueError, "deflection", dict(deflection=-0.1)),
                (TypeError, "unknown parameter.*layer_height", dict(layer_height=1.0))):
            with self.assertRaisesRegex(error, name, msg=str(kwargs)):
                mas.make_slice(decomposition, **kwargs)
        with self.assertRaisesRegex(TypeError, "Decomposition object"):
            mas.make_slice(self.part)
        self.assertEqual([o.Name for o in self.doc.Objects], names)

    def test_failing_recompute_prints_the_message_without_a_traceback(self):
        script = support.write_dedented(self.folder, "fail.py", """
            import FreeCAD, Part
            import MultiAxisSlicer as mas
            doc = FreeCAD.newDocument("Fail")
            box = doc.addObject("Part::Feature", "Box")
            box.Shape = Part.makeBox(20, 10, 21)
            layers, toolpath = mas.make_slice(mas.make_decomposition(box))
            layers.MinLayer = 3.0
            doc.recompute()
            print("STATES", layers.State, toolpath.State)
            other, _ = mas.make_slice(mas.make_decomposition(box))
            other.Decomposition = box
            doc.recompute()
            print("OTHER", other.State)
        """)
        result = subprocess.run(["freecadcmd", script], capture_output=True, text=True, timeout=120)
        output = result.stdout + result.stderr
        self.assertIn("STATES ['Invalid']", output.replace("'Touched', ", ""))
        self.assertIn("OTHER ['Invalid']", output.replace("'Touched', ", ""))
        self.assertIn("need 0 < MinLayer <= MaxLayer", output)
        self.assertIn("not a Decomposition object", output)
        self.assertNotIn("Traceback", output)


class TestBuildPreviewObject(SliceObjectTest):
    """The BuildPreview object: the build after a step of the Layers' sequence, the nozzle at the
    step's layer along its tool axis."""

    def make_preview(self, shape, step=0, **params):
        part = self.doc.addObject("Part::Feature", "Part")
        part.Shape = shape
        self.doc.recompute()
        _decomposition, layers, toolpath = self.make(part, **params)
        preview = mas.make_build_preview(layers, step=step)
        self.doc.recompute()
        self.assertTrue(preview.isValid(), preview.getStatusString())
        return layers, toolpath, preview

    def check_nozzle(self, solids, point, axis, layers):
        """The nozzle's tip (a cone frustum) and body (a cylinder) from the Layers' nozzle,
        standing `standoff` off `point` along `axis` (unit)."""
        standoff, tip_r = layers.NozzleStandoff.Value, layers.NozzleTipDiameter.Value / 2
        body_r, body_l = layers.NozzleBodyDiameter.Value / 2, layers.NozzleBodyLength.Value
        cone_l = (body_r - tip_r) / math.tan(math.radians(layers.NozzleConeAngle.Value))
        self.assertEqual(len(solids), 2)
        tip, body = solids
        volumes = (math.pi * cone_l * (tip_r ** 2 + tip_r * body_r + body_r ** 2) / 3,
                   math.pi * body_r ** 2 * body_l)
        for solid, volume, centre in ((tip, volumes[0], None),
                                      (body, volumes[1], standoff + cone_l + body_l / 2)):
            self.assertAlmostEqual(solid.Volume, volume, delta=volume * REL)
            com = solid.CenterOfMass - point
            along = com.dot(axis)
            self.assertLess((com - axis * along).Length, 1e-6)  # on the tool axis
            if centre is not None:
                self.assertAlmostEqual(along, centre, places=6)
        # The tip's face standoff along the axis, the body from where the cone ends.
        rims = [(e.Curve.Center - point).dot(axis) for e in tip.Edges
                if isinstance(e.Curve, Part.Circle)]
        self.assertAlmostEqual(min(rims), standoff, places=6)
        self.assertAlmostEqual(max(rims), standoff + cone_l, places=6)

    def test_each_step_shows_the_layers_deposited_so_far_and_the_nozzle_on_its_layer(self):
        layers, _toolpath, preview = self.make_preview(l_block(), step=1)
        result = features.slice_result(layers)
        sequence = list(result.sequence)
        self.assertEqual(preview.Proxy.Type, "MultiAxisSlicer::BuildPreview")
        self.assertEqual(preview.StepCount, len(sequence))
        for step in (1, 2, len(sequence) // 2, len(sequence), 0):
            preview.Step = step
            self.doc.recompute()
            self.assertTrue(preview.isValid(), preview.getStatusString())
            shown = step or len(sequence)
            index = sequence[shown - 1]
            layer = result.layers[index]
            self.assertEqual(preview.ShownStep, shown)
            self.assertEqual((preview.Layer, preview.Component), (index, layer.component))
            self.assertEqual(list(preview.ShownComponents),
                             [result.layers[i].component for i in sequence[:shown]])
            deposited, current, nozzle, paths, unsupported, _plate = preview.Shape.childShapes()
            self.assertEqual(unsupported.Faces, [])  # the L's layers all rest on the layer below
            self.assertEqual(len(deposited.childShapes()), shown - 1)
            # Each layer a prism: its regions on its plane swept back along its normal by its
            # thickness (the L's layers are parallel: exact).
            for i, prism in zip(sequence[:shown - 1], deposited.childShapes()):
                area = sum(Part.Face(Part.makePolygon(r["outer"] + r["outer"][:1])).Area
                           for r in result.layers[i].regions)
                self.assertAlmostEqual(prism.Volume, area * result.layers[i].max_thickness,
                                       delta=area * REL)
            heights = [(v.Point - layer.origin).dot(layer.normal) for v in current.Vertexes]
            self.assertAlmostEqual(max(heights), 0.0, places=6)  # its top on its plane
            self.assertAlmostEqual(min(heights), -layer.max_thickness, places=6)
            first = next(p for p in result.paths(index) if p.deposit)
            self.assertVectorAlmostEqual(preview.NozzlePoint, first.points[0])
            self.assertVectorAlmostEqual(preview.ToolAxis, result.tool_axis(index))
            self.assertFalse(preview.Collides)
            self.assertEqual(preview.CollisionObstacle, -2)
            self.check_nozzle(nozzle.Solids, preview.NozzlePoint, preview.ToolAxis, layers)
            # The step's deposit paths, one polyline each, in the nozzle's order, on its plane.
            deposits = [p for p in result.paths(index) if p.deposit]
            wires = paths.Wires
            self.assertEqual(len(wires), len(deposits))
            for wire, path in zip(wires, deposits):
                self.assertVectorAlmostEqual(wire.OrderedVertexes[0].Point, path.points[0])
                length = sum((b - a).Length for a, b in zip(path.points, path.points[1:]))
                self.assertAlmostEqual(wire.Length, length, delta=1e-9 * max(1.0, length))
            for v in paths.Vertexes:
                self.assertAlmostEqual((v.Point - layer.origin).dot(layer.normal), 0.0,
                                       places=6)
        # Nothing leaned or colliding, every layer resting on the one below.
        self.assertEqual(list(preview.FlaggedSteps), [])
        self.assertEqual((preview.WorstStep, preview.UnsupportedArea.Value), (0, 0.0))
        # ShowNozzle and ShowPaths off: the layers only.
        preview.ShowNozzle = False
        preview.ShowPaths = False
        self.doc.recompute()
        self.assertEqual(preview.Shape.childShapes()[2].Solids, [])
        self.assertEqual(preview.Shape.childShapes()[3].Edges, [])
        self.assertEqual(len(preview.Shape.Solids), len(sequence))
        # The layers are read, never changed; their result is reused, not computed again.
        self.assertNotIn("Touched", layers.State)
        self.assertIs(features.slice_result(layers), result)

    def test_a_leaned_layer_shows_its_nozzle_along_the_tool_axis(self):
        layers, _toolpath, preview = self.make_preview(rod_under_bar())
        result = features.slice_result(layers)
        leaned = result.leaned_layers()
        self.assertTrue(leaned)  # the rod's nozzle is leaned up off the plate
        index = leaned[0]
        preview.Step = list(result.sequence).index(index) + 1
        self.doc.recompute()
        layer = result.layers[index]
        axis = FreeCAD.Vector(result.tool_axis(index))
        self.assertEqual(preview.Layer, index)
        self.assertVectorAlmostEqual(preview.ToolAxis, axis)
        self.assertAlmostEqual(preview.Lean.Value,
                               math.degrees(axis.getAngle(FreeCAD.Vector(layer.normal))),
                               places=6)
        self.assertGreater(preview.Lean.Value, 1.0)
        self.assertEqual(list(preview.FlaggedSteps),  # the steps of the leaned layers
                         [k + 1 for k, i in enumerate(result.sequence) if i in leaned])
        self.assertIn(preview.ShownStep, preview.FlaggedSteps)
        self.check_nozzle(preview.Shape.childShapes()[2].Solids, preview.NozzlePoint, axis,
                          layers)

    def test_a_colliding_layer_shows_its_nozzle_where_it_meets_what_is_deposited(self):
        _decomposition, layers, _toolpath = self.make_coaxial_wide_l()
        result = features.slice_result(layers)
        collision = result.collisions[0]
        preview = mas.make_build_preview(layers, step=list(result.sequence).index(
            collision.layer) + 1)
        self.doc.recompute()
        self.assertTrue(preview.isValid(), preview.getStatusString())
        self.assertTrue(preview.Collides)
        self.assertEqual(preview.CollisionObstacle, collision.obstacle_layer)
        self.assertEqual(preview.CollisionObstacle, -1)  # the plate
        self.assertVectorAlmostEqual(preview.NozzlePoint, collision.nozzle_at)
        colliding = {c.layer for c in result.collisions}
        self.assertEqual(list(preview.FlaggedSteps),
                         [k + 1 for k, i in enumerate(result.sequence) if i in colliding])
        nozzle = preview.Shape.childShapes()[2]
        self.check_nozzle(nozzle.Solids, preview.NozzlePoint, preview.ToolAxis, layers)
        # The body, 100 mm across and horizontal along the arm, reaches under the plate.
        self.assertLess(nozzle.BoundBox.ZMin, 0.0)

    def test_the_worst_overhang_is_the_step_whose_layer_stands_most_on_nothing(self):
        # A cone widening 60 degrees from the vertical: every layer overhangs the one below,
        # more as it widens.
        layers, _toolpath, preview = self.make_preview(Part.makeCone(5, 5 + 10 * math.sqrt(3), 10))
        result = features.slice_result(layers)
        areas = [result.layers[i].unsupported_area for i in result.sequence]
        self.assertGreater(max(areas), 0.0)
        self.assertEqual(preview.WorstStep, areas.index(max(areas)) + 1)
        preview.Step = preview.WorstStep
        self.doc.recompute()
        self.assertEqual(preview.UnsupportedArea.Value, max(areas))
        self.assertEqual(preview.UnsupportedArea.Value, layers.WorstUnsupportedArea.Value)
        # Where it stands on nothing, faces on the plane below it (the cone's are parallel).
        layer = result.layers[preview.Layer]
        faces = preview.Shape.childShapes()[4].Faces
        self.assertGreater(len(faces), 0)
        self.assertAlmostEqual(sum(f.Area for f in faces), max(areas), delta=1e-6 * max(areas))
        for v in preview.Shape.childShapes()[4].Vertexes:
            self.assertAlmostEqual((v.Point - layer.origin).dot(layer.normal),
                                   -layer.max_thickness, places=6)

    def test_the_plate_lies_under_the_whole_build_on_the_plane_the_part_stands_on(self):
        # The L turned 30 degrees about Z and standing 7 mm up: the plate at z = 7, square to
        # the document's X and Y, covering every layer's outline with a margin all round.
        l_turned = l_block()
        l_turned.rotate(V(0, 0, 0), V(0, 0, 1), 30.0)
        l_turned.translate(V(3, -4, 7))
        layers, _toolpath, preview = self.make_preview(l_turned, step=1)
        result = features.slice_result(layers)
        self.assertAlmostEqual(result.plate[0].z, 7.0, places=9)
        self.assertVectorAlmostEqual(result.plate[1], V(0, 0, 1))
        outline = [p for layer in result.layers for loop in layer.loops() for p in loop]
        lo = V(min(p.x for p in outline), min(p.y for p in outline), 0)
        hi = V(max(p.x for p in outline), max(p.y for p in outline), 0)
        # The L's outline: its box, turned (the layers' loops are the mesh's sections).
        box = l_turned.BoundBox
        deflection = layers.Deflection.Value or mas.deflection(l_turned)
        for got, want in ((lo.x, box.XMin), (lo.y, box.YMin), (hi.x, box.XMax), (hi.y, box.YMax)):
            self.assertAlmostEqual(got, want, delta=deflection)
        grow = max(5.0, 0.1 * max(hi.x - lo.x, hi.y - lo.y))
        self.assertGreater(grow, 5.0)  # a tenth of the turned L's 71 mm along X
        for step in (1, 0):  # the same plate at every step
            preview.Step = step
            self.doc.recompute()
            plate = preview.Shape.childShapes()[5]
            self.assertEqual(len(plate.Faces), 1)
            face = plate.Faces[0]
            self.assertEqual(len(face.Vertexes), 4)
            b = face.BoundBox
            self.assertAlmostEqual(b.ZMin, 7.0, places=9)
            self.assertAlmostEqual(b.ZMax, 7.0, places=9)
            for got, want in ((b.XMin, lo.x - grow), (b.YMin, lo.y - grow),
                              (b.XMax, hi.x + grow), (b.YMax, hi.y + grow)):
                self.assertAlmostEqual(got, want, places=6)
            self.assertAlmostEqual(face.Area, (hi.x - lo.x + 2 * grow) * (hi.y - lo.y + 2 * grow),
                                   places=6)
        # ShowPlate off: no plate; the rest as it was.
        solids = len(preview.Shape.Solids)
        preview.ShowPlate = False
        self.doc.recompute()
        self.assertEqual(preview.Shape.childShapes()[5].Faces, [])
        self.assertEqual(len(preview.Shape.Solids), solids)
        self.assertFalse(mas.make_build_preview(layers, show_plate=False).ShowPlate)

    def test_a_small_part_gets_a_plate_5_mm_wider_all_round(self):
        layers, _toolpath, preview = self.make_preview(Part.makeBox(10, 8, 4))
        face = preview.Shape.childShapes()[5].Faces[0]
        b = face.BoundBox
        result = features.slice_result(layers)
        outline = [p for layer in result.layers for loop in layer.loops() for p in loop]
        self.assertAlmostEqual(b.XMin, min(p.x for p in outline) - 5.0, places=9)
        self.assertAlmostEqual(b.XMax, max(p.x for p in outline) + 5.0, places=9)
        self.assertAlmostEqual(b.YMin, min(p.y for p in outline) - 5.0, places=9)
        self.assertAlmostEqual(b.YMax, max(p.y for p in outline) + 5.0, places=9)
        self.assertAlmostEqual(b.ZMax, 0.0, places=9)

    @staticmethod
    def enclosed_volume(points, triangles):
        """The volume triangles facing outwards enclose (divergence theorem)."""
        pts = [V(*p) for p in points]
        return sum(pts[a].dot(pts[b].cross(pts[c])) for a, b, c in triangles) / 6.0

    def check_layer_triangles(self, result, indices):
        """layer_triangles() of each layer in `indices` against layer_prism(): a closed surface
        (each edge once each way) round the same volume, its points on the layer's plane or its
        greatest thickness below, as many triangles as OCCT's tessellation of the prism. The
        prism's faces drawn from their corners (a Shape read from a file) and by OCCT: facing
        outwards, round the same volume."""
        for i in indices:
            layer = result.layers[i]
            points, triangles = features.layer_triangles(layer)
            prism = features.layer_prism(layer)
            pts = [V(*p) for p in points]
            volume = self.enclosed_volume(points, triangles)
            self.assertAlmostEqual(volume, prism.Volume, delta=1e-9 * prism.Volume)
            for polygonal in (True, False):
                drawn = features.shape_triangles(prism, polygonal=polygonal)
                self.assertAlmostEqual(self.enclosed_volume(*drawn), prism.Volume,
                                       delta=1e-9 * prism.Volume)
                self.assertEqual(len(drawn[1]), len(triangles))
            edges = [(t[k], t[(k + 1) % 3]) for t in triangles for k in range(3)]
            self.assertEqual(len(set(edges)), len(edges))
            self.assertEqual(set(edges), {(b, a) for a, b in edges})
            used = {k for t in triangles for k in t}
            for k in used:
                height = (pts[k] - layer.origin).dot(layer.normal)
                self.assertTrue(abs(height) < 1e-9 or abs(height + layer.max_thickness) < 1e-9,
                                height)
            self.assertEqual(len(triangles), len(features.shape_triangles(prism)[1]))

    def test_the_engine_draws_each_layer_as_its_prism(self):
        # A ring (a hole in every layer) and the L turned 30 degrees (its arm's layers on
        # planes square to the arm).
        ring = Part.makeCylinder(10, 12).cut(Part.makeCylinder(6, 14, V(0, 0, -1)))
        result = mas.slice(ring)
        self.assertTrue(all(r["holes"] for layer in result.layers for r in layer.regions))
        self.check_layer_triangles(result, range(len(result.layers)))
        l_turned = l_block()
        l_turned.rotate(V(0, 0, 0), V(0, 0, 1), 30.0)
        result = mas.slice(l_turned)
        arm = [i for i, layer in enumerate(result.layers) if abs(layer.normal.z) < 1e-9]
        self.assertTrue(arm)
        self.check_layer_triangles(result, arm[:3] + [0, len(result.layers) - 1])

    def test_the_view_gets_the_engine_s_triangles_for_the_object_s_own_prisms_only(self):
        layers, _toolpath, preview = self.make_preview(l_block(), step=3)
        result = features.slice_result(layers)
        deposited, current = preview.Shape.childShapes()[:2]
        for prism, index in zip(deposited.childShapes() + [current], result.sequence[:3]):
            self.assertEqual(preview.Proxy.prism_triangles(prism),
                             features.layer_triangles(result.layers[index]))
        # A prism it did not make (the same layer's, made again; one read from a file): none.
        self.assertIsNone(preview.Proxy.prism_triangles(
            features.layer_prism(result.layers[result.sequence[0]])))
        self.reopened("preview_triangles.FCStd")
        preview = self.doc.getObject("BuildPreview")
        self.assertIsNone(preview.Proxy.prism_triangles(preview.Shape.childShapes()[1]))

    def test_a_region_s_face_is_made_on_its_plane_whichever_way_its_loops_turn(self):
        # A 10 x 10 square round a 2 x 2 hole, on a plane tilted 30 degrees about X.
        normal = V(0, -math.sin(math.pi / 6), math.cos(math.pi / 6))
        u, w = V(1, 0, 0), normal.cross(V(1, 0, 0))
        origin = V(3, 4, 5)

        def square(x0, y0, x1, y1):
            return [origin + u * x + w * y for x, y in ((x0, y0), (x1, y0), (x1, y1), (x0, y1))]

        for outer in (square(0, 0, 10, 10), square(0, 0, 10, 10)[::-1]):
            for hole in (square(4, 4, 6, 6), square(4, 4, 6, 6)[::-1]):
                face = features._region_face({"outer": outer, "holes": [hole]}, origin, normal)
                self.assertIsInstance(face, Part.Face)
                self.assertTrue(face.isValid())
                self.assertAlmostEqual(face.Area, 96.0, places=9)
                self.assertVectorAlmostEqual(face.normalAt(0, 0), normal)
                prism = face.extrude(normal * -2)
                self.assertTrue(prism.isValid())
                self.assertAlmostEqual(prism.Volume, 192.0, places=9)
        self.assertIsNone(features._region_face({"outer": outer[:2], "holes": []}, origin,
                                                normal))

    def test_the_engine_s_drawing_refuses_a_bad_plane_or_depth(self):
        engine = mas._require_engine()
        region = [{"outer": [(0, 0, 0), (1, 0, 0), (0, 1, 0)], "holes": []}]
        points, triangles = engine.prism_mesh(region, (0, 0, 0), (0, 0, 2), 1.0)
        self.assertEqual((len(points), len(triangles)), (6, 2 + 6))
        for depth in (0.0, -1.0, float("nan"), float("inf")):
            with self.assertRaisesRegex(mas.EngineError, "depth must be a positive number"):
                engine.prism_mesh(region, (0, 0, 0), (0, 0, 1), depth)
        with self.assertRaisesRegex(mas.EngineError, "normal"):
            engine.prism_mesh(region, (0, 0, 0), (0, 0, 0), 1.0)
        with self.assertRaisesRegex(mas.EngineError, "outer"):
            engine.prism_mesh([{"holes": []}], (0, 0, 0), (0, 0, 1), 1.0)
        # A face's corners: a 10 x 10 square round a 2 x 2 hole on a plane tilted about X, the
        # triangles counter-clockwise seen from the normal given.
        normal = V(0, -0.6, 0.8)
        u, w = V(1, 0, 0), normal.cross(V(1, 0, 0))
        loops = [[u * x + w * y for x, y in ((0, 0), (10, 0), (10, 10), (0, 10))],
                 [u * x + w * y for x, y in ((4, 4), (4, 6), (6, 6), (6, 4))]]
        for n in (normal, -normal):
            triangles = engine.triangulate(loops, n)
            self.assertEqual(len(triangles), 8)
            pts = loops[0] + loops[1]
            turns = [(pts[b] - pts[a]).cross(pts[c] - pts[a]) for a, b, c in triangles]
            self.assertAlmostEqual(sum(t.dot(n) for t in turns) / 2.0, 96.0, places=9)
            self.assertTrue(all(t.dot(n) > 0.0 for t in turns))
        with self.assertRaisesRegex(mas.EngineError, "normal"):
            engine.triangulate(loops, (0, 0, 0))
        with self.assertRaisesRegex(mas.EngineError, r"loops\[1\] has a point that is not finite"):
            engine.triangulate([loops[0], [(float("inf"), 0, 0)] * 3], normal)
        with self.assertRaisesRegex(mas.EngineError,
                                    r"regions\[0\]\['outer'\] has a point that is not finite"):
            engine.prism_mesh([{"outer": [(0, 0, 0), (1, float("nan"), 0), (0, 1, 0)],
                                "holes": []}], (0, 0, 0), (0, 0, 1), 1.0)

    def test_a_step_past_the_sequence_is_named_until_fixed(self):
        layers, _toolpath, preview = self.make_preview(box_20_10_21())
        preview.Step = 12
        self.doc.recompute()
        self.assertIn("Invalid", preview.State)
        self.assertIn("Step must be 0 (the last) to 11 (the layers of 'Layers'), got 12",
                      preview.getStatusString())
        preview.Step = -1
        self.doc.recompute()
        self.assertIn("got -1", preview.getStatusString())
        preview.Step = 11
        self.doc.recompute()
        self.assertTrue(preview.isValid(), preview.getStatusString())
        self.assertEqual(preview.ShownStep, 11)
        # Layers changed under it: fewer steps; a Step within them is shown.
        layers.MaxLayer = 3.0
        self.doc.recompute()
        self.assertIn("Invalid", preview.State)
        self.assertIn("to 7 (the layers", preview.getStatusString())
        preview.Step = 0
        self.doc.recompute()
        self.assertTrue(preview.isValid(), preview.getStatusString())
        self.assertEqual((preview.StepCount, preview.ShownStep), (7, 7))

    def test_survives_save_and_reopen_and_undo_removes_it(self):
        self.doc.UndoMode = 1
        layers, _toolpath, _first = self.make_preview(l_block(), step=5)
        self.doc.openTransaction("Build preview")
        preview = mas.make_build_preview(layers, step=7, name="Second")
        self.doc.recompute()
        self.doc.commitTransaction()
        solids = len(preview.Shape.Solids)
        self.assertEqual(solids, 7 + 2)
        self.reopened("preview.FCStd")
        preview = self.doc.getObject("Second")
        self.assertIsInstance(preview.Proxy, features.BuildPreviewFeature)
        self.assertIs(preview.Layers, self.doc.getObject("Layers"))
        self.assertEqual((preview.Step, preview.ShownStep), (7, 7))
        self.assertEqual(len(preview.Shape.Solids), solids)  # saved with the document
        preview.Step = 8
        self.doc.recompute()  # the slicing redone on demand
        self.assertTrue(preview.isValid(), preview.getStatusString())
        self.assertEqual(len(preview.Shape.Solids), 8 + 2)
        self.doc.UndoMode = 1
        self.doc.openTransaction("Build preview")
        mas.make_build_preview(self.doc.getObject("Layers"), name="Third")
        self.doc.recompute()
        self.doc.commitTransaction()
        self.doc.undo()
        self.assertIsNone(self.doc.getObject("Third"))
        self.assertIsNotNone(self.doc.getObject("Second"))

    def test_bad_arguments(self):
        _decomposition, layers, toolpath = self.make()
        with self.assertRaisesRegex(TypeError, "needs a Layers or Toolpath object"):
            mas.make_build_preview(self.part)
        for step in (-1, 1.5, True, "3"):
            with self.assertRaisesRegex(ValueError, "step must be a whole number"):
                mas.make_build_preview(layers, step=step)
        self.assertIs(mas.make_build_preview(toolpath).Layers, layers)  # a Toolpath stands in
        toolpath.Layers = None
        with self.assertRaisesRegex(ValueError, "the Toolpath 'Toolpath' has no Layers"):
            mas.make_build_preview(toolpath)
        with self.assertRaisesRegex(ValueError, "zero vector"):
            features.nozzle_solids(10, 10, 30, 50, 200, V(0, 0, 0), V(0, 0, 0))
        with self.assertRaisesRegex(ValueError, "cone angle must be between 0 and 90"):
            features.nozzle_solids(10, 10, 0, 50, 200, V(0, 0, 0), V(0, 0, 1))
        body = features.nozzle_solids(10, 20, 0, 20, 50, V(0, 0, 0), V(0, 0, 2))  # no cone
        self.assertEqual(len(body), 1)
        self.assertAlmostEqual(body[0].Volume, math.pi * 100 * 50, delta=1e-6)
        self.assertAlmostEqual(body[0].BoundBox.ZMin, 10.0, places=9)
        # Nozzles slicing takes whose cone or tip OCCT cannot make (Part.OCCDomainError "creation
        # of cone failed" in the preview's recompute): a tip 1e-9 mm across is drawn as a point, a
        # cone 1e-7 mm long as a flat step to the body.
        tip, body = features.nozzle_solids(10, 1e-9, 30, 50, 200, V(0, 0, 0), V(0, 0, 1))
        cone_length = (25.0 - 0.5e-9) / math.tan(math.radians(30.0))  # the tip as given
        self.assertAlmostEqual(tip.Volume, math.pi * 25 ** 2 * cone_length / 3.0, delta=1e-6)
        self.assertAlmostEqual(body.BoundBox.ZMin, 10.0 + cone_length, places=9)
        # As wide as the body, any angle (slicing takes one); a body narrower than can be drawn.
        self.assertEqual(len(features.nozzle_solids(10, 1e-4, 0.0, 1e-4, 200, V(0, 0, 0),
                                                    V(0, 0, 1))), 0)
        self.assertEqual(len(features.nozzle_solids(10, 1e-4, 30, 1e-3, 200, V(0, 0, 0),
                                                    V(0, 0, 1))), 2)
        for tip_diameter, angle in ((49.9999999, 30.0), (10.0, 89.9999999)):
            body = features.nozzle_solids(10, tip_diameter, angle, 50, 200, V(0, 0, 0),
                                          V(0, 0, 1))
            self.assertEqual(len(body), 1)
            self.assertAlmostEqual(body[0].Volume, math.pi * 25 ** 2 * 200, delta=1e-6)
            self.assertAlmostEqual(body[0].BoundBox.ZMin, 10.0, places=9)
        preview = self.doc.getObject("BuildPreview")
        layers.NozzleTipDiameter = 1e-9
        self.doc.recompute()
        self.assertTrue(layers.isValid(), layers.getStatusString())
        self.assertTrue(preview.isValid(), preview.getStatusString())
        preview.Layers = None
        self.doc.recompute()
        self.assertIn("Layers is not set", preview.getStatusString())


if __name__ == "__main__":
    unittest.main()
