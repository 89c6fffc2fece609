# SPDX-License-Identifier: LGPL-2.1-or-later
"""The centroidal axis through the scripting API and the CentroidalAxis document object, inside
freecadcmd.

Run: freecadcmd -t TestMultiAxisSlicerAxis (tests/run_freecad_test.sh does it against the add-on
staged in the build tree). The parts are planar, so their tessellation is exact and the expected
values are those of the engine's own test (tests/engine/test_axis.cpp).
"""

import json
import math
import os
import shutil
import subprocess
import tempfile
import unittest

import FreeCAD
import Mesh
import Part

import MultiAxisSlicer as mas
import MultiAxisSlicer.features as features
import MultiAxisSlicerTestSupport as support
from MultiAxisSlicerTestSupport import V, box_10_20_30, fc_mesh, l_block

EPS = 0.001  # mm, the default eps: a march's first plane lies this far inside the part
# The arm's first node is 0.001 mm past the column, the column node it hangs on 0.001 mm above
# z = 50: the connecting link turns a hair more than 90 degrees from the column.
L_BREAK_TURN = 90.0 + math.degrees(math.atan2(0.001, 10.001))


def open_box_mesh():
    mesh = fc_mesh(box_10_20_30())
    mesh.removeFacets([0])
    return mesh


class AxisTest(support.EngineTestCase):
    def check_l_block_axis(self, axis):
        """The engine test's expectations for the L at step 2.5 mm."""
        self.assertEqual(len(axis.branches), 2)
        column, arm = axis.branches
        self.assertEqual(column.parent, -1)
        self.assertVectorAlmostEqual(column.direction, (0, 0, 1))
        self.assertEqual(len(column.nodes), 24)
        for i in column.nodes:
            node = axis.nodes[i]
            self.assertAlmostEqual(node.position.x, 10.0, places=6)
            self.assertAlmostEqual(node.position.y, 10.0, places=6)
            self.assertAlmostEqual(node.area, 400.0, delta=1e-3)
            self.assertEqual(node.branch, 0)
        # The arm: +X from just past the column, on its centre line y = 10, z = 50.
        self.assertEqual(arm.parent, 0)
        self.assertEqual(arm.depth, 1)
        self.assertVectorAlmostEqual(arm.direction, (1, 0, 0))
        self.assertEqual(len(arm.nodes), 20)
        self.assertAlmostEqual(axis.nodes[arm.nodes[0]].position.x, 20.0 + EPS, places=9)
        for i in arm.nodes:
            node = axis.nodes[i]
            self.assertAlmostEqual(node.position.y, 10.0, places=6)
            self.assertAlmostEqual(node.position.z, 50.0, places=6)
            self.assertAlmostEqual(node.area, 400.0, places=6)
            self.assertVectorAlmostEqual(node.normal, (1, 0, 0))
            self.assertEqual(node.branch, 1)
        # One C1 break: the link tying the arm to the column node at the arm's height.
        breaks = axis.break_links()
        self.assertEqual(len(breaks), 1)
        tie = axis.links[arm.first_link]
        self.assertIs(breaks[0], tie)
        self.assertEqual(tie.kind, "connecting")
        self.assertEqual(tie.end, arm.nodes[0])
        self.assertEqual(tie.start, arm.parent_node)
        self.assertIn(tie.start, column.nodes)
        self.assertAlmostEqual(axis.nodes[tie.start].position.z, 50.0 + EPS, places=9)
        self.assertAlmostEqual(tie.turn, L_BREAK_TURN, places=6)
        self.assertEqual(len(axis.links), len(axis.nodes) - 1)  # a tree
        self.assertAlmostEqual(axis.searched_volume, 20 * 20 * 60 + 50 * 20 * 20, delta=1e-3)


class TestAxisOfABox(AxisTest):
    def test_engine_is_available(self):
        self.assertTrue(mas.engine_available(), mas.engine_missing_message())

    def test_box_axis_is_one_vertical_branch_through_its_centre(self):
        axis = mas.centroidal_axis(box_10_20_30(), step=2.0)
        self.assertEqual(len(axis.branches), 1)
        [branch] = axis.branches
        self.assertEqual(branch.parent, -1)
        self.assertEqual(branch.parent_node, -1)
        self.assertEqual(branch.first_link, -1)
        self.assertIsInstance(branch.direction, FreeCAD.Vector)
        self.assertVectorAlmostEqual(branch.direction, (0, 0, 1))
        # Planes at z = 3.001, 5.001, ..., 31.001 on the line through the box's centre (6, 12).
        self.assertEqual(len(axis.nodes), 15)
        self.assertEqual(branch.nodes, list(range(15)))
        for i, node in enumerate(axis.nodes):
            self.assertIsInstance(node.position, FreeCAD.Vector)
            self.assertVectorAlmostEqual(node.position, (6, 12, 3 + EPS + 2.0 * i))
            self.assertVectorAlmostEqual(node.normal, (0, 0, 1))
            self.assertAlmostEqual(node.area, 200.0, places=9)  # the footprint
            self.assertAlmostEqual(node.offset, 3 + EPS + 2.0 * i, places=9)
            self.assertEqual(node.branch, 0)
        self.assertAlmostEqual(axis.nodes[0].thickness, 2.0 + EPS, places=9)  # from the base
        self.assertAlmostEqual(axis.nodes[-1].thickness, 2.0 - EPS, places=9)  # to the top
        self.assertEqual(len(axis.links), 14)
        for i, link in enumerate(axis.links):
            self.assertEqual((link.start, link.end), (i, i + 1))
            self.assertEqual(link.kind, "step")
            self.assertFalse(link.is_break)
            self.assertAlmostEqual(link.turn, 0.0, places=9)
        self.assertEqual(axis.break_links(), [])
        self.assertAlmostEqual(axis.searched_volume, 6000.0, places=9)
        self.assertEqual(axis.kind, "solid")
        self.assertEqual(axis.params["step_mm"], 2.0)
        self.assertEqual(axis.params["distance_threshold_mm"], 4.0)
        self.assertEqual(axis.params["eps_mm"], EPS)
        self.assertEqual(axis.params["break_angle_deg"], 30.0)
        self.assertEqual(axis.params["base_z_mm"], 3.0)
        self.assertEqual(axis.params["deflection_mm"], mas.deflection(box_10_20_30()))

    def test_derived_step_and_threshold(self):
        # The box's thinnest wall is its 10 x 20 section (2 x area / perimeter = 6.67 mm); half
        # of it is more than diagonal / 20, which caps the step.
        axis = mas.centroidal_axis(box_10_20_30())
        step = math.sqrt(10 ** 2 + 20 ** 2 + 30 ** 2) / 20.0
        self.assertAlmostEqual(axis.params["step_mm"], step, places=12)
        self.assertAlmostEqual(axis.params["distance_threshold_mm"], 2.0 * step, places=12)
        self.assertEqual(len(axis.nodes), math.floor((30.0 - EPS) / step) + 1)
        mesh = mas.to_engine_mesh(box_10_20_30())
        self.assertAlmostEqual(mas._engine.derive_axis_step(mesh), step, places=12)

    def test_explicit_parameters_are_used(self):
        axis = mas.centroidal_axis(box_10_20_30(), step=5.0, distance_threshold=7.0, eps=0.01,
                                   break_angle=45.0, base_z=3.0, deflection=0.05, frame=100.0)
        # frame is read modulo 90 degrees: 100 is 10
        self.assertEqual(set(axis.params), {"step_mm", "distance_threshold_mm", "eps_mm",
                                            "break_angle_deg", "base_z_mm", "frame_deg",
                                            "deflection_mm"})
        self.assertEqual({k: v for k, v in axis.params.items() if k != "frame_deg"},
                         {"step_mm": 5.0, "distance_threshold_mm": 7.0, "eps_mm": 0.01,
                          "break_angle_deg": 45.0, "base_z_mm": 3.0, "deflection_mm": 0.05})
        self.assertAlmostEqual(axis.params["frame_deg"], 10.0, places=12)
        self.assertAlmostEqual(axis.nodes[0].position.z, 3.01, places=9)
        for node in axis.nodes:  # marched in the turned frame and turned back: the centre line
            self.assertAlmostEqual(node.position.x, 6.0, places=9)
            self.assertAlmostEqual(node.position.y, 12.0, places=9)
        self.assertEqual(len(axis.nodes), 6)

    def test_quantities_are_accepted(self):
        axis = mas.centroidal_axis(box_10_20_30(), step=FreeCAD.Units.Quantity("2 mm"),
                                   break_angle=FreeCAD.Units.Quantity("45 deg"))
        self.assertEqual(axis.params["step_mm"], 2.0)
        self.assertEqual(axis.params["break_angle_deg"], 45.0)


class TestAxisProgress(AxisTest):
    def test_progress_reports_the_volume_swept_and_a_raise_stops_it(self):
        reports, stages = [], set()
        axis = mas.centroidal_axis(box_10_20_30(), step=2.0,
                                   progress=lambda f, s: (reports.append(f), stages.add(s)))
        self.assertEqual(len(axis.nodes), 15)
        self.assertEqual(reports[-1], 1.0)
        self.assertEqual(reports, sorted(reports))
        self.assertGreater(len(reports), 1)
        self.assertEqual(stages, {"centroidal axis"})  # every report names its stage

        def stop(fraction, stage):
            raise mas.Cancelled("enough")

        with self.assertRaisesRegex(mas.Cancelled, "enough"):
            mas.centroidal_axis(box_10_20_30(), step=2.0, progress=stop)
        with self.assertRaisesRegex(TypeError, "progress must be"):
            mas.centroidal_axis(box_10_20_30(), progress=3)


class TestAxisOfAnLBlock(AxisTest):
    def test_l_block_rises_then_turns_into_the_arm(self):
        self.check_l_block_axis(mas.centroidal_axis(l_block(), step=2.5))

    def test_mesh_of_the_l_block_gives_the_same_axis(self):
        from_shape = mas.centroidal_axis(l_block(), step=2.5)
        axis = mas.centroidal_axis(fc_mesh(l_block()), step=2.5)
        self.assertEqual(axis.kind, "mesh")
        self.assertEqual(axis.params["deflection_mm"], 0.0)
        self.check_l_block_axis(axis)
        self.assertEqual(len(axis.nodes), len(from_shape.nodes))
        for a, b in zip(axis.nodes, from_shape.nodes):
            self.assertVectorAlmostEqual(a.position, b.position, places=6)

    def test_document_object_and_file_inputs(self):
        folder = tempfile.mkdtemp(prefix="mas_axis_")
        doc = FreeCAD.newDocument("MasAxisInputs")
        try:
            part = doc.addObject("Part::Feature", "L")
            part.Shape = l_block()
            self.check_l_block_axis(mas.centroidal_axis(part, step=2.5))
            path = os.path.join(folder, "l.brep")
            l_block().exportBrep(path)
            self.check_l_block_axis(mas.centroidal_axis(path, step=2.5))
        finally:
            FreeCAD.closeDocument(doc.Name)
            shutil.rmtree(folder)

    def test_to_dict_is_json_ready_and_matches_the_attributes(self):
        axis = mas.centroidal_axis(l_block(), step=2.5)
        d = axis.to_dict()
        self.assertEqual(json.loads(json.dumps(d, allow_nan=False)), d)
        self.assertEqual(set(d), {"kind", "triangles", "deflection_mm", "params",
                                  "searched_volume_mm3", "nodes", "links", "branches"})
        self.assertEqual(set(d["params"]), {"step_mm", "distance_threshold_mm", "eps_mm",
                                            "break_angle_deg", "base_z_mm", "frame_deg"})
        self.assertEqual(d["params"]["step_mm"], 2.5)
        self.assertEqual(d["deflection_mm"], axis.params["deflection_mm"])
        self.assertEqual(d["searched_volume_mm3"], axis.searched_volume)
        self.assertEqual(len(d["nodes"]), 44)
        self.assertEqual(set(d["nodes"][0]), {"position", "normal", "area_mm2", "offset_mm",
                                              "thickness_mm", "slab_start_mm", "branch"})
        self.assertEqual(set(d["links"][0]), {"start", "end", "kind", "is_break", "turn_deg"})
        self.assertEqual(set(d["branches"][0]), {"parent", "direction", "nodes", "parent_node",
                                                 "first_link", "depth", "merged_into"})
        self.assertEqual([b["merged_into"] for b in d["branches"]], [-1, -1])
        for node, n in zip(axis.nodes, d["nodes"]):
            self.assertEqual(n["position"], [node.position.x, node.position.y, node.position.z])
            self.assertEqual(n["area_mm2"], node.area)
            self.assertEqual(n["slab_start_mm"], node.slab_start)
        arm = d["branches"][1]
        # The arm's first plane is x = 20.001; its slab reaches back to the column's face (T).
        first = d["nodes"][arm["nodes"][0]]
        self.assertAlmostEqual(first["offset_mm"], 20.001, delta=1e-9)
        self.assertAlmostEqual(first["slab_start_mm"], 20.0, delta=1e-9)
        self.assertEqual(arm["direction"], [1.0, 0.0, 0.0])
        self.assertEqual(arm["parent"], 0)
        self.assertEqual(d["links"][arm["first_link"]]["kind"], "connecting")
        self.assertTrue(d["links"][arm["first_link"]]["is_break"])

    def test_to_dict_matches_the_command_line_json(self):
        with support.scratch_folder("mas_axis_cli_") as folder:
            path = os.path.join(folder, "l.brep")
            l_block().exportBrep(path)
            cli = self.cli_json(folder, "axis", path, "--step", "2.5")
            ours = mas.centroidal_axis(path, step=2.5).to_dict()
        self.assertEqual(cli.pop("file"), path)
        self.assertSameJson(cli, ours, "axis")

    def test_solids_sharing_material_give_their_unions_axis(self):
        # The L as its column and its arm sunk 5 mm into it, given as one compound.
        two = Part.makeCompound([Part.makeBox(20, 20, 60), Part.makeBox(55, 20, 20, V(15, 0, 40))])
        axis = mas.centroidal_axis(two, step=2.5)
        self.check_l_block_axis(axis)
        self.assertEqual(axis.to_dict(), mas.centroidal_axis(l_block(), step=2.5).to_dict())


class TestAxisBadInput(AxisTest):
    def test_none_and_unsupported_types_are_type_errors(self):
        with self.assertRaisesRegex(TypeError, "None"):
            mas.centroidal_axis(None)
        with self.assertRaisesRegex(TypeError, "int"):
            mas.centroidal_axis(42)

    def test_face_is_not_a_solid(self):
        e = self.assertRaisesEngineError("not_a_solid", mas.centroidal_axis,
                                         Part.makePlane(10, 10))
        self.assertIn("Face", str(e))

    def test_two_solids_apart_are_rejected(self):
        two = Part.makeCompound([box_10_20_30(), Part.makeBox(5, 5, 5, V(50, 0, 0))])
        e = self.assertRaisesEngineError("multiple_solids", mas.centroidal_axis, two)
        self.assertIn("2 solids", str(e))
        self.assertIn("2 bodies apart", str(e))

    def test_open_mesh_is_rejected(self):
        e = self.assertRaisesEngineError("open_mesh", mas.centroidal_axis, open_box_mesh())
        self.assertIn("boundary edges", str(e))

    def test_bad_step_is_a_value_error(self):
        for step in (0, -1.0, float("nan"), float("inf")):
            with self.assertRaisesRegex(ValueError, "step"):
                mas.centroidal_axis(box_10_20_30(), step=step)
        with self.assertRaisesRegex(TypeError, "step"):
            mas.centroidal_axis(box_10_20_30(), step="1")

    def test_step_not_smaller_than_the_part_is_named(self):
        e = self.assertRaisesEngineError("invalid_argument", mas.centroidal_axis, box_10_20_30(),
                                         step=40.0)
        self.assertIn("height", str(e))
        self.assertIn("40", str(e))

    def test_other_bad_parameters_are_value_errors(self):
        nan = float("nan")
        cases = [("distance_threshold", dict(distance_threshold=nan)),
                 ("distance_threshold", dict(distance_threshold=-1.0)),
                 ("eps", dict(eps=0.0)), ("eps", dict(eps=nan)),
                 ("break_angle", dict(break_angle=nan)), ("break_angle", dict(break_angle=200.0)),
                 ("break_angle", dict(break_angle=-1.0)),
                 ("base_z", dict(base_z=nan)), ("base_z", dict(base_z=float("-inf"))),
                 ("frame", dict(frame=nan)), ("frame", dict(frame=float("inf"))),
                 ("deflection", dict(deflection=-0.1))]
        for name, kwargs in cases:
            with self.assertRaisesRegex(ValueError, name, msg=str(kwargs)):
                mas.centroidal_axis(box_10_20_30(), **kwargs)

    def test_part_not_standing_on_its_base_plane(self):
        e = self.assertRaisesEngineError("invalid_argument", mas.centroidal_axis, box_10_20_30(),
                                         base_z=0.0)
        self.assertIn("does not stand on its base plane", str(e))
        self.assertEqual(mas.centroidal_axis(box_10_20_30(), base_z=3.0).params["base_z_mm"], 3.0)

    def test_engine_rejects_nan_parameters(self):
        mesh = mas.to_engine_mesh(box_10_20_30())
        nan = float("nan")
        for name in ("step", "distance_threshold", "eps", "break_angle", "min_region_area"):
            e = self.assertRaisesEngineError("invalid_argument", mas._engine.centroidal_axis, mesh,
                                             **{name: nan})
            self.assertIn(name, str(e))
        self.assertRaisesEngineError("invalid_argument", mas._engine.centroidal_axis, mesh,
                                     base_z=float("inf"))
        e = self.assertRaisesEngineError("invalid_argument", mas._engine.centroidal_axis, mesh,
                                         frame=float("-inf"))
        self.assertIn("frame must be a finite angle", str(e))
        self.assertRaisesEngineError("invalid_argument", mas._engine.centroidal_axis, mesh,
                                     eps=-1.0)

    def test_inputs_are_not_modified(self):
        shape = l_block()
        shape.Placement = FreeCAD.Placement(V(1, 2, 3), FreeCAD.Rotation())
        before = shape.exportBrepToString()
        mas.centroidal_axis(shape, step=2.5)
        self.assertEqual(shape.exportBrepToString(), before)
        mesh = fc_mesh(l_block())
        topology = mesh.Topology
        mas.centroidal_axis(mesh, step=2.5)
        self.assertEqual(mesh.Topology, topology)


class TestAxisWithoutFreeCAD(AxisTest):
    def test_plain_python_uses_tuples(self):
        with support.scratch_folder("mas_plain_axis_") as folder:
            result = support.run_plain_python(folder, """
                import json, sys
                assert "FreeCAD" not in sys.modules
                import MultiAxisSlicer as mas
                v = [0,0,0, 1,0,0, 1,1,0, 0,1,0, 0,0,4, 1,0,4, 1,1,4, 0,1,4]
                t = [0,2,1, 0,3,2, 4,5,6, 4,6,7, 0,1,5, 0,5,4, 1,2,6, 1,6,5, 2,3,7, 2,7,6,
                     3,0,4, 3,4,7]
                axis = mas.centroidal_axis(mas._engine.Mesh.from_arrays(v, t), step=1.0)
                n = axis.nodes[1]
                print("RESULT", len(axis.nodes), n.position, type(n.position).__name__,
                      axis.branches[0].direction)
                json.dumps(axis.to_dict())
            """)
        self.assertEqual(result.returncode, 0, result.stderr)
        self.assertIn("RESULT 4 (0.5, 0.5, 1.001) tuple (0.0, 0.0, 1.0)", result.stdout)


class TestCentroidalAxisObject(AxisTest):
    def setUp(self):
        self.doc = FreeCAD.newDocument("MasAxis")
        self.part = self.doc.addObject("Part::Feature", "L")
        self.part.Shape = l_block()
        self.doc.recompute()
        self.folder = tempfile.mkdtemp(prefix="mas_axis_doc_")

    def tearDown(self):
        for name in list(FreeCAD.listDocuments()):
            if name.startswith("MasAxis"):
                FreeCAD.closeDocument(name)
        shutil.rmtree(self.folder)

    def check_l_block_object(self, obj):
        """The L at Step 2.5 mm: 44 nodes, 43 links of which the last edge is the break."""
        self.assertTrue(obj.isValid(), obj.getStatusString())
        self.assertEqual(obj.Proxy.Type, "MultiAxisSlicer::CentroidalAxis")
        self.assertEqual(obj.NodeCount, 44)
        self.assertEqual(obj.BranchCount, 2)
        self.assertEqual(obj.BreakCount, 1)
        self.assertEqual(obj.UsedStep.Value, 2.5)
        self.assertEqual(obj.UsedDistanceThreshold.Value, 5.0)
        self.assertAlmostEqual(obj.SearchedVolume.Value, 44000.0, delta=1e-3)
        edges = obj.Shape.Edges
        self.assertEqual(len(edges), 43)
        self.assertEqual(obj.BreakEdgeStart, 42)  # ordinary links first, then the break
        tie = edges[obj.BreakEdgeStart]
        ends = sorted((tuple(round(c, 9) for c in v.Point) for v in tie.Vertexes))
        self.assertEqual(ends, [(10.0, 10.0, 50.0 + EPS), (20.0 + EPS, 10.0, 50.0)])
        for edge in edges[:obj.BreakEdgeStart]:  # step links: one step apart
            self.assertAlmostEqual(edge.Length, 2.5, places=6)
        self.assertEqual(len(obj.Shape.Vertexes), 44 + 2 * 43)  # nodes, then the edges' ends
        self.assertEqual(obj.Shape.Faces, [])
        bb = obj.Shape.BoundBox
        self.assertAlmostEqual(bb.XMin, 10.0, places=6)
        self.assertAlmostEqual(bb.ZMin, EPS, places=9)

    def test_recompute_computes_the_axis(self):
        obj = mas.make_centroidal_axis(self.part, step=2.5)
        self.assertEqual(obj.Epsilon.Value, EPS)
        self.assertEqual(obj.BreakAngle.Value, 30.0)
        self.assertEqual(obj.DistanceThreshold.Value, 0.0)
        self.assertEqual(obj.Deflection.Value, 0.0)
        self.doc.recompute()
        self.check_l_block_object(obj)

    def test_default_step_is_derived_and_changing_it_recomputes(self):
        obj = mas.make_centroidal_axis(self.part)
        self.assertEqual(obj.Step.Value, 0.0)
        self.doc.recompute()
        self.assertTrue(obj.isValid(), obj.getStatusString())
        diagonal = math.sqrt(70 ** 2 + 20 ** 2 + 60 ** 2)
        self.assertAlmostEqual(obj.UsedStep.Value, diagonal / 20.0, places=9)
        self.assertEqual(obj.BranchCount, 2)
        coarse = obj.NodeCount
        obj.Step = 2.5
        self.doc.recompute()
        self.assertNotEqual(obj.NodeCount, coarse)
        self.check_l_block_object(obj)

    def test_a_derived_threshold_lets_a_thick_columns_short_lugs_branch(self):
        # A column [0,30]^2 x [0,60] with 8 x 8 lugs sticking out 12 mm along +X (z 16..24) and -X
        # (z 36..44), step 4: each lug's first section is centred 6 mm out, within twice the step
        # (8 mm) but past a sixth of the column's 30 mm size, the most a derived threshold is.
        column = Part.makeBox(30, 30, 60).fuse(Part.makeBox(12, 8, 8, V(30, 11, 16)))
        column = column.fuse(Part.makeBox(12, 8, 8, V(-12, 11, 36))).removeSplitter()
        part = self.doc.addObject("Part::Feature", "LuggedColumn")
        part.Shape = column
        obj = mas.make_centroidal_axis(part, step=4.0)
        self.doc.recompute()
        self.assertTrue(obj.isValid(), obj.getStatusString())
        self.assertEqual(obj.DistanceThreshold.Value, 0.0)
        self.assertEqual(obj.UsedDistanceThreshold.Value, 8.0)
        self.assertEqual(obj.BranchCount, 3)
        # The same 8 mm given is used as given: the lugs stay with the column.
        obj.DistanceThreshold = 8.0
        self.doc.recompute()
        self.assertTrue(obj.isValid(), obj.getStatusString())
        self.assertEqual(obj.BranchCount, 1)

    def test_source_is_not_modified(self):
        before = self.part.Shape.exportBrepToString()
        obj = mas.make_centroidal_axis(self.part, step=2.5)
        self.doc.recompute()
        self.assertTrue(obj.isValid())
        self.assertEqual(self.part.Shape.exportBrepToString(), before)
        self.assertNotIn("Touched", self.part.State)
        self.assertEqual(self.part.InList, [obj])

    def test_a_source_in_a_group_is_computed_where_the_view_shows_it(self):
        # An App::Part turning the L 90 degrees about Z and raising it 100: the object's axis is
        # the one of the L as drawn (the group's placement applied), not of its shape in the
        # group's own frame. Moving the group (turning the L onto its side) marks the object for
        # recompute, and the recompute moves the axis along; and back again.
        group = self.doc.addObject("App::Part", "Group")
        group.addObject(self.part)
        raised = FreeCAD.Placement(V(0, 0, 100), FreeCAD.Rotation(V(0, 0, 1), 90))
        on_its_side = FreeCAD.Placement(V(5, 0, 0), FreeCAD.Rotation(V(0, 1, 0), 90))
        group.Placement = raised
        self.doc.recompute()
        before = self.part.Shape.exportBrepToString()
        obj = mas.make_centroidal_axis(self.part, step=2.5)
        self.doc.recompute()

        for moved_to in (on_its_side, raised, None):
            self.assertTrue(obj.isValid(), obj.getStatusString())
            drawn = self.part.Shape.copy()
            drawn.Placement = group.Placement.multiply(drawn.Placement)
            expected = mas.centroidal_axis(drawn, step=2.5)
            self.assertEqual(obj.NodeCount, len(expected.nodes))
            self.assertEqual(obj.BranchCount, len(expected.branches))
            nodes = [v.Point for v in obj.Shape.Vertexes[:obj.NodeCount]]
            for got, node in zip(nodes, expected.nodes):
                self.assertVectorAlmostEqual(got, node.position)
            self.assertAlmostEqual(obj.Shape.BoundBox.ZMin, drawn.BoundBox.ZMin + EPS, places=9)
            if moved_to is None:
                break
            self.assertNotIn("Touched", obj.State)
            group.Placement = moved_to
            self.assertIn("Touched", obj.State)
            self.doc.recompute()
        self.assertEqual(self.part.Shape.exportBrepToString(), before)
        # Opened again, the group's placement is read back, which moves nothing: the object is
        # as it was saved, not marked for recompute.
        path, name = os.path.join(self.folder, "group.FCStd"), obj.Name
        self.doc.saveAs(path)
        FreeCAD.closeDocument(self.doc.Name)
        doc = FreeCAD.openDocument(path)
        self.assertNotIn("Touched", doc.getObject(name).State)
        self.assertEqual(doc.getObject(name).Source, doc.getObject("L"))

    def test_mesh_source(self):
        mesh = self.doc.addObject("Mesh::Feature", "LMesh")
        mesh.Mesh = fc_mesh(l_block())
        obj = mas.make_centroidal_axis(mesh, step=2.5)
        self.doc.recompute()
        self.check_l_block_object(obj)

    def test_save_close_reopen_recompute(self):
        obj = mas.make_centroidal_axis(self.part, step=2.5, distance_threshold=6.0,
                                       break_angle=40.0, deflection=0.02)
        self.doc.recompute()
        path = os.path.join(self.folder, "axis.FCStd")
        self.doc.saveAs(path)
        FreeCAD.closeDocument(self.doc.Name)

        doc = FreeCAD.openDocument(path)
        obj = doc.getObject("CentroidalAxis")
        self.assertIsNotNone(obj)
        self.assertIsInstance(obj.Proxy, features.CentroidalAxisFeature)
        self.assertIs(obj.Source, doc.getObject("L"))
        self.assertEqual(obj.Step.Value, 2.5)
        self.assertEqual(obj.DistanceThreshold.Value, 6.0)
        self.assertEqual(obj.BreakAngle.Value, 40.0)
        self.assertEqual(obj.Deflection.Value, 0.02)
        self.assertEqual(obj.NodeCount, 44)
        self.assertEqual(len(obj.Shape.Edges), 43)  # the shape is saved with the document
        obj.touch()
        doc.recompute()
        self.assertTrue(obj.isValid(), obj.getStatusString())
        self.assertEqual(obj.NodeCount, 44)
        self.assertEqual(obj.BreakCount, 1)
        obj.Step = 5.0
        doc.recompute()
        self.assertEqual(obj.NodeCount, 12 + 10)  # column z < 60, arm x in (20, 70)
        doc.save()  # saving a restored proxy works too

    def test_the_frame_is_the_parts_unless_the_documents_is_asked_for(self):
        # The L placed 30 degrees round: "Part" (the default) marches its arm along itself,
        # "Document" along the document's X and Y (the arm leaves between them). Both survive
        # saving; a document saved before the property existed gets "Part".
        turned = self.doc.addObject("Part::Feature", "Turned")
        shape = l_block()
        shape.rotate(V(0, 0, 0), V(0, 0, 1), 30)
        turned.Shape = shape
        obj = mas.make_centroidal_axis(turned, step=2.5)
        self.assertEqual(obj.Frame, "Part")
        self.assertEqual(obj.getEnumerationsOfProperty("Frame"), ["Part", "Document"])
        self.doc.recompute()
        self.assertTrue(obj.isValid(), obj.getStatusString())
        self.assertAlmostEqual(obj.UsedFrame.Value, 30.0, places=9)
        self.assertEqual((obj.BranchCount, obj.NodeCount), (2, 44))
        other = mas.make_centroidal_axis(turned, step=2.5, frame="Document")
        self.doc.recompute()
        self.assertTrue(other.isValid(), other.getStatusString())
        self.assertEqual(other.UsedFrame.Value, 0.0)
        self.assertNotEqual((other.BranchCount, other.NodeCount), (2, 44))
        with self.assertRaises(ValueError):
            mas.make_centroidal_axis(turned, frame="Sideways")
        # A Decomposition made with either axis object decomposes in its frame: the arm cut off
        # and built along itself, or not.
        for axis_obj, arm_along_itself in ((obj, True), (other, False)):
            parts = mas.make_decomposition(turned, axis=axis_obj)
            self.doc.recompute()
            self.assertTrue(parts.isValid(), parts.getStatusString())
            along = V(math.cos(math.radians(30)), math.sin(math.radians(30)), 0)
            built = parts.BuildDirections
            self.assertEqual(any(d.isEqual(along, 1e-9) for d in built), arm_along_itself,
                             built)
        other.removeProperty("Frame")  # as a document saved before it existed
        names = obj.Name, other.Name
        path = os.path.join(self.folder, "frame.FCStd")
        self.doc.saveAs(path)
        FreeCAD.closeDocument(self.doc.Name)
        doc = FreeCAD.openDocument(path)
        self.assertEqual(doc.getObject(names[0]).Frame, "Part")
        restored = doc.getObject(names[1])
        self.assertEqual(restored.Frame, "Part")
        restored.Frame = "Document"
        doc.recompute()
        self.assertTrue(restored.isValid(), restored.getStatusString())
        self.assertEqual(restored.UsedFrame.Value, 0.0)

    def test_undo_removes_the_object(self):
        self.doc.UndoMode = 1
        self.doc.openTransaction("Centroidal axis")
        obj = mas.make_centroidal_axis(self.part, step=2.5)
        self.doc.recompute()
        self.doc.commitTransaction()
        name = obj.Name
        self.assertIsNotNone(self.doc.getObject(name))
        self.doc.undo()
        self.assertIsNone(self.doc.getObject(name))
        self.assertIsNotNone(self.doc.getObject("L"))
        self.doc.redo()
        self.assertIsNotNone(self.doc.getObject(name))

    def test_face_source_marks_the_object_with_the_engine_message(self):
        face = self.doc.addObject("Part::Feature", "Face")
        face.Shape = Part.makePlane(10, 10)
        obj = mas.make_centroidal_axis(face)
        self.doc.recompute()
        self.assertIn("Invalid", obj.State)
        self.assertIn("not a solid", obj.getStatusString())
        self.assertIn("Face", obj.getStatusString())
        # FreeCAD keeps running and the object recovers once its input is fixed.
        obj.Source = self.part
        obj.Step = 2.5
        self.doc.recompute()
        self.check_l_block_object(obj)

    def test_open_mesh_source_marks_the_object(self):
        mesh = self.doc.addObject("Mesh::Feature", "Open")
        mesh.Mesh = open_box_mesh()
        obj = mas.make_centroidal_axis(mesh)
        self.doc.recompute()
        self.assertIn("Invalid", obj.State)
        self.assertIn("boundary edges", obj.getStatusString())

    def test_bad_parameters_mark_the_object(self):
        obj = mas.make_centroidal_axis(self.part)
        obj.Step = 100.0
        self.doc.recompute()
        self.assertIn("Invalid", obj.State)
        self.assertIn("height", obj.getStatusString())
        obj.Step = 2.5
        obj.Epsilon = 0.0
        self.doc.recompute()
        self.assertIn("Invalid", obj.State)
        self.assertEqual(obj.getStatusString(),
                         "Epsilon must be a positive number of millimetres, got 0.0")
        obj.Epsilon = 0.001
        # A label in the message stays as the user typed it; only parameter names are renamed.
        self.part.Label = "step eps deflection"
        self.part.Shape = Part.makePlane(10, 10)
        self.doc.recompute()
        self.assertIn("Invalid", obj.State)
        self.assertTrue(obj.getStatusString().startswith("'step eps deflection': not a solid"),
                        obj.getStatusString())
        obj.Source = None
        self.doc.recompute()
        self.assertIn("Source is not set", obj.getStatusString())

    def test_make_rejects_bad_parameters_before_adding_anything(self):
        names = [o.Name for o in self.doc.Objects]
        with self.assertRaisesRegex(ValueError, "step"):
            mas.make_centroidal_axis(self.part, step=-1.0)
        with self.assertRaisesRegex(ValueError, "break_angle"):
            mas.make_centroidal_axis(self.part, break_angle=181.0)
        self.assertEqual([o.Name for o in self.doc.Objects], names)

    def test_failing_recompute_prints_the_message_without_a_traceback(self):
        script = support.write_dedented(self.folder, "fail.py", """
            import FreeCAD, Mesh, Part
            import MultiAxisSlicer as mas
            doc = FreeCAD.newDocument("Fail")
            face = doc.addObject("Part::Feature", "Face")
            face.Shape = Part.makePlane(10, 10)
            a = mas.make_centroidal_axis(face)
            mesh = doc.addObject("Mesh::Feature", "Open")
            m = Mesh.Mesh(Part.makeBox(10, 10, 10).tessellate(0.1))
            m.removeFacets([0])
            mesh.Mesh = m
            b = mas.make_centroidal_axis(mesh)
            doc.recompute()
            print("STATES", a.State, b.State)
        """)
        result = subprocess.run(["freecadcmd", script], capture_output=True, text=True, timeout=120)
        output = result.stdout + result.stderr
        self.assertIn("STATES ['Invalid'] ['Invalid']", output.replace("'Touched', ", ""))
        self.assertIn("not a solid", output)
        self.assertIn("boundary edges", output)
        self.assertNotIn("Traceback", output)


if __name__ == "__main__":
    unittest.main()
