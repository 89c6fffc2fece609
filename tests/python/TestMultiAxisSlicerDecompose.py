# SPDX-License-Identifier: LGPL-2.1-or-later
"""Decomposition into sub-components through the scripting API and the Decomposition document
object, inside freecadcmd.

Run: freecadcmd -t TestMultiAxisSlicerDecompose (tests/run_freecad_test.sh does it against the
add-on staged in the build tree). The parts and expected values are those of the engine's own
test (tests/engine/test_decompose.cpp): the cuts are planes of planar faces, so volumes are exact.
"""

import json
import math
import os
import shutil
import struct
import subprocess
import tempfile
import unittest

import FreeCAD
import Mesh
import Part

import MultiAxisSlicer as mas
import MultiAxisSlicerTestSupport as support
from MultiAxisSlicerTestSupport import V, l_block, t_block
import MultiAxisSlicer.features as features

REL = 1e-6  # relative volume tolerance: OCCT's volumes of exact planar solids


def assert_box(test, shape, lo, hi, tol=1e-6):
    bb = shape.BoundBox
    got = ((bb.XMin, bb.YMin, bb.ZMin), (bb.XMax, bb.YMax, bb.ZMax))
    for a, b in zip(got[0] + got[1], tuple(lo) + tuple(hi)):
        test.assertAlmostEqual(a, b, delta=tol, msg="{} != {}".format(got, (lo, hi)))


def portal():
    """Two legs 8 x 8 x 30 standing 34 mm apart on the plate, a lintel 50 x 8 x 6 on them."""
    return Part.makeBox(8, 8, 30).fuse(
        [Part.makeBox(8, 8, 30, V(42, 0, 0)), Part.makeBox(50, 8, 6, V(0, 0, 30))]).removeSplitter()


class DecomposeTest(support.EngineTestCase):
    def check_l_block(self, d):
        """The column is the root, the arm its child built +X from the base face x = 20."""
        self.assertEqual(len(d), 2)
        root, arm = d
        self.assertEqual((root.parent, root.rule, root.branch, root.break_link),
                         (-1, "root", 0, -1))
        self.assertIsNone(root.base_face)
        self.assertVectorAlmostEqual(root.build_direction, (0, 0, 1))
        assert_box(self, root.shape, (0, 0, 0), (20, 20, 60))
        self.assertAlmostEqual(root.volume, 24000.0, delta=24000.0 * REL)
        self.assertEqual((arm.parent, arm.rule, arm.branch), (0, "planar_face", 1))
        self.assertEqual(arm.break_link, d.axis.branches[1].first_link)
        self.assertIsInstance(arm.shape, Part.Solid)
        self.assertTrue(arm.shape.isValid())
        assert_box(self, arm.shape, (20, 0, 40), (70, 20, 60))
        self.assertAlmostEqual(arm.volume, 20000.0, delta=20000.0 * REL)
        self.assertAlmostEqual(arm.shape.Volume, 20000.0, delta=20000.0 * REL)
        self.assertIsInstance(arm.build_direction, FreeCAD.Vector)
        self.assertVectorAlmostEqual(arm.build_direction, (1, 0, 0), places=12)
        self.assertVectorAlmostEqual(arm.base_normal, (-1, 0, 0), places=12)
        self.assertIsInstance(arm.base_face, Part.Face)
        assert_box(self, arm.base_face, (20, 0, 40), (20, 20, 60))
        self.assertAlmostEqual(arm.base_face.Area, 400.0, delta=400.0 * REL)
        self.assertVectorAlmostEqual(arm.base_origin, (20, 10, 50))
        self.check_volumes_add_up(d, 44000.0)

    def check_volumes_add_up(self, d, part_volume):
        self.assertAlmostEqual(d.part_volume, part_volume, delta=part_volume * REL)
        self.assertAlmostEqual(sum(c.volume for c in d), part_volume, delta=part_volume * REL)
        self.assertAlmostEqual(sum(c.shape.Volume for c in d), part_volume,
                               delta=part_volume * REL)
        for i, c in enumerate(d):  # tree order, the root first
            self.assertLess(c.parent, i)


class TestDecomposeApi(DecomposeTest):
    def test_box_is_one_root_component(self):
        d = mas.decompose(Part.makeBox(10, 20, 30), step=2.0)
        self.assertEqual(len(d), 1)
        self.assertEqual(d[0].rule, "root")
        self.assertEqual(d.children(-1), [0])
        self.check_volumes_add_up(d, 6000.0)

    def test_l_block_arm_is_a_child_built_plus_x_from_the_column_side(self):
        d = mas.decompose(l_block(), step=2.5)
        self.check_l_block(d)
        self.assertEqual(d.axis.params["step_mm"], 2.5)
        self.assertEqual(d.children(0), [1])
        self.assertEqual([c.rule for c in d], ["root", "planar_face"])  # iteration
        self.assertIs(d[-1], d.components[1])

    def test_t_crossbar_arms_are_built_plus_x_and_minus_x(self):
        d = mas.decompose(t_block(), step=2.5)
        self.assertEqual(len(d), 3)
        assert_box(self, d[0].shape, (0, 0, 0), (20, 20, 60))
        directions = sorted(round(c.build_direction.x) for c in d[1:])
        self.assertEqual(directions, [-1, 1])
        for c in d[1:]:
            self.assertEqual(c.parent, 0)
            self.assertEqual(c.rule, "planar_face")
            self.assertAlmostEqual(c.volume, 12000.0, delta=12000.0 * REL)
            if c.build_direction.x > 0:
                assert_box(self, c.shape, (20, 0, 40), (50, 20, 60))
                assert_box(self, c.base_face, (20, 0, 40), (20, 20, 60))
            else:
                assert_box(self, c.shape, (-30, 0, 40), (0, 20, 60))
                assert_box(self, c.base_face, (0, 0, 40), (0, 20, 60))
        self.check_volumes_add_up(d, 24000.0 + 2 * 12000.0)
        # No two components overlap.
        for i in range(len(d)):
            for j in range(i):
                self.assertAlmostEqual(d[i].shape.common(d[j].shape).Volume, 0.0, delta=1e-6)

    def test_a_pipe_tees_branch_is_built_along_itself(self):
        # The engine's test part (test_decompose.cpp): the branch's first section is a ring whose
        # centroid lies in the bore. The axis carries a point in each node's material across to
        # the decomposition, which finds the branch's father and piece by it.
        tee = support.pipe_tee()
        axis = mas.centroidal_axis(tee, step=1.0, deflection=0.02)
        d = mas.decompose(tee, axis=axis)
        branch = [c for c in d if c.build_direction.y > 0.999]
        self.assertEqual(len(branch), 1, [c.build_direction for c in d])
        self.assertEqual(branch[0].parent, 0)
        bb = branch[0].shape.BoundBox
        self.assertLess(bb.YMin, 15.0)
        assert_box(self, branch[0].shape, (-10, bb.YMin, 25), (10, 35, 45))
        self.check_volumes_add_up(d, tee.Volume)

    def test_a_precomputed_axis_gives_the_same_components(self):
        axis = mas.centroidal_axis(l_block(), step=2.5)
        d = mas.decompose(l_block(), axis=axis)
        self.assertIs(d.axis, axis)
        self.check_l_block(d)
        computed = mas.decompose(l_block(), step=2.5)
        self.assertEqual(d.to_dict(), computed.to_dict())
        # An axis of the mesh of the same part is an axis of that part too.
        mesh_axis = mas.centroidal_axis(Mesh.Mesh(l_block().tessellate(0.05)), step=2.5)
        self.check_l_block(mas.decompose(l_block(), axis=mesh_axis))

    def test_an_axis_of_another_part_is_rejected(self):
        axis = mas.centroidal_axis(Part.makeBox(10, 10, 10), step=2.0)
        e = self.assertRaisesEngineError("invalid_argument", mas.decompose, l_block(), axis=axis)
        self.assertIn("different part", str(e))
        moved = Part.makeBox(10, 10, 10, V(50, 0, 0))
        e = self.assertRaisesEngineError("invalid_argument", mas.decompose, moved, axis=axis)
        self.assertIn("different part", str(e))

    def test_a_malformed_axis_is_named(self):
        axis = mas.centroidal_axis(l_block(), step=2.5)
        axis.branches[1].parent = 1  # its own father
        e = self.assertRaisesEngineError("invalid_argument", mas.decompose, l_block(), axis=axis)
        self.assertIn("malformed", str(e))

    def test_axis_and_axis_parameters_together_are_refused(self):
        axis = mas.centroidal_axis(l_block(), step=2.5)
        with self.assertRaisesRegex(ValueError, "step"):
            mas.decompose(l_block(), axis=axis, step=2.5)
        with self.assertRaisesRegex(TypeError, "CentroidalAxis"):
            mas.decompose(l_block(), axis=axis.to_dict())

    def test_decomposition_parameters(self):
        # Criterion (2) needs more than the L's 90 degree concave edge: the fallback cuts at the
        # plane where the arm's march started, x = 20; without the fallback the L stays whole.
        d = mas.decompose(l_block(), step=2.5, concave_angle=95.0)
        self.assertEqual([c.rule for c in d], ["root", "section_plane"])
        self.assertEqual(d.notes, [])
        assert_box(self, d[1].shape, (20, 0, 40), (70, 20, 60))
        d = mas.decompose(l_block(), step=2.5, concave_angle=95.0, section_plane_fallback=False)
        self.assertEqual(len(d), 1)
        # The arm got no cut: said, with why and where its material stayed.
        self.assertEqual(len(d.notes), 1)
        self.assertIn("fallback is off", d.notes[0])
        self.assertIn("stays in component 0", d.notes[0])
        self.assertEqual(d.params["section_plane_fallback"], False)
        for name, kwargs in (("face_angle", dict(face_angle=90.0)),
                             ("face_angle", dict(face_angle=float("nan"))),
                             ("concave_angle", dict(concave_angle=-1.0)),
                             ("projection_tolerance", dict(projection_tolerance=-0.1)),
                             ("min_component_height", dict(min_component_height=-1.0)),
                             ("min_component_height", dict(min_component_height=float("inf"))),
                             ("step", dict(step=0.0))):
            with self.assertRaisesRegex(ValueError, name, msg=str(kwargs)):
                mas.decompose(l_block(), **kwargs)
        d = mas.decompose(l_block(), step=FreeCAD.Units.Quantity("2.5 mm"),
                          face_angle=FreeCAD.Units.Quantity("5 deg"))
        self.assertEqual(d.params["face_angle_deg"], 5.0)
        self.assertEqual(len(d), 2)
        # The arm reaches 50 mm past its cut: not a component when 60 are needed.
        d = mas.decompose(l_block(), step=2.5, min_component_height=FreeCAD.Units.Quantity("6 cm"))
        self.assertEqual(len(d), 1)
        self.assertIn("reaches only 50 mm", d.notes[0])

    def test_kept_branches_stay_in_their_fathers(self):
        axis = mas.centroidal_axis(l_block(), step=2.5)
        d = mas.decompose(l_block(), axis=axis, keep_branches=[1, 1])
        self.assertEqual(len(d), 1)
        self.assertEqual(d.kept_branches, [1])
        self.assertEqual(d.params["keep_branches"], (1,))
        self.assertEqual(d.notes, ["branch 1 (along 1,0,0): kept in its father, as asked "
                                   "(keep_branches); its material stays in component 0"])
        self.assertEqual(d[0].volume, d.part_volume)
        plain = mas.decompose(l_block(), axis=axis)
        self.assertEqual((len(plain), plain.kept_branches, plain.params["keep_branches"]),
                         (2, [], ()))
        for bad in ("1", 1, [1.0], [True], None):
            with self.assertRaisesRegex(TypeError, "keep_branches", msg=repr(bad)):
                mas.decompose(l_block(), axis=axis, keep_branches=bad)
        for bad, message in ((0, "branch 0 is the axis' root"), (2, "there is no branch 2")):
            with self.assertRaises(mas.EngineError) as e:
                mas.decompose(l_block(), axis=axis, keep_branches=[bad])
            self.assertEqual(e.exception.code, "invalid_argument")
            self.assertIn(message, str(e.exception))

    def test_a_branch_between_the_directions_is_cut_square_to_its_line_unless_asked(self):
        # The L marched in a frame turned 30 degrees: its arm, along X, runs 30 degrees off the
        # frame's X. Its cut is turned square to its line (Component.turned) and it is built
        # along X; asked (square_branches), it is cut square to the frame's X. Either way
        # decompose() with the result's kept and squared branches gives it again.
        axis = mas.centroidal_axis(l_block(), step=2.5, frame=30.0)
        turned = mas.decompose(l_block(), axis=axis)
        self.assertEqual((turned.square_branches, turned.params["square_branches"]), ([], ()))
        self.assertEqual([c.turned for c in turned][:2], [False, True])
        self.assertEqual(turned[1].rule, "section_plane")
        self.assertLess((turned[1].build_direction - V(1, 0, 0)).Length, 1e-6)
        self.assertTrue(turned[1].to_dict()["turned"])
        squared = mas.decompose(l_block(), axis=axis, square_branches=[1, 1])
        self.assertEqual((squared.square_branches, squared.params["square_branches"]), ([1], (1,)))
        self.assertFalse(squared[1].turned)
        self.assertLess((squared[1].build_direction - V(math.cos(math.pi / 6), 0.5, 0)).Length,
                        1e-12)
        self.assertFalse(squared[1].to_dict()["turned"])
        again = mas.decompose(l_block(), axis=axis, keep_branches=squared.kept_branches,
                              square_branches=squared.square_branches)
        self.assertEqual([c.to_dict() for c in again], [c.to_dict() for c in squared])
        # turn_cuts=False turns none: as every branch were asked.
        unturned = mas.decompose(l_block(), axis=axis, turn_cuts=False)
        self.assertEqual((unturned.params["turn_cuts"], turned.params["turn_cuts"]), (False, True))
        self.assertEqual([c.to_dict() for c in unturned], [c.to_dict() for c in squared])
        with self.assertRaisesRegex(TypeError, "turn_cuts"):
            mas.decompose(l_block(), axis=axis, turn_cuts="no")
        for bad in ("1", 1, [1.0], [True], None):
            with self.assertRaisesRegex(TypeError, "square_branches", msg=repr(bad)):
                mas.decompose(l_block(), axis=axis, square_branches=bad)
        for bad in (0, len(axis.branches)):
            with self.assertRaises(mas.EngineError) as e:
                mas.decompose(l_block(), axis=axis, square_branches=[bad])
            self.assertEqual(e.exception.code, "invalid_argument")
            self.assertIn("there is no branch {} to cut square".format(bad), str(e.exception))

    def test_a_round_boss_is_cut_at_the_extent_of_the_body_it_leaves(self):
        # A boss (radius 6, along X) on a cylinder (radius 20): no planar face to split at, so the
        # section-plane fallback cuts where the boss' march started, Eq. 4's T (x = 20, measured on
        # the mesh), plus eps, the axis' deflection and step / 100, not at its first grid plane
        # (about x = -19.95 + 14 x 3 = 22.05 with a 3 mm step), which left the father a 2 mm stub.
        part = Part.makeCylinder(20, 40).fuse(Part.makeCylinder(6, 40, V(0, 0, 20), V(1, 0, 0)))
        for deflection in (0.02, 0.1):
            axis = mas.centroidal_axis(part, step=3.0, deflection=deflection)
            self.assertEqual(axis.params["deflection_mm"], deflection)
            d = mas.decompose(part, axis=axis)
            self.assertEqual([c.rule for c in d], ["root", "section_plane"])
            first = axis.nodes[axis.branches[d[1].branch].nodes[0]]
            cut = first.slab_start + 0.001 + deflection + 0.03
            self.assertGreater(first.offset - cut, 1.9)
            self.assertGreaterEqual(cut, 20.0)
            self.assertLessEqual(cut, 20.031 + deflection)
            face = d[1].base_face.BoundBox
            self.assertAlmostEqual(face.XMin, cut, delta=1e-7)
            self.assertAlmostEqual(face.XMax, cut, delta=1e-7)
            self.assertAlmostEqual(d[1].volume, math.pi * 36 * (40 - cut), delta=1e-3)

    def test_a_handles_bar_is_a_bridge_built_along_a_diagonal(self):
        # Two posts on a plate, a bar across their tops: the bar is cut off at its underside and
        # built along the diagonal between +Z and the way across the gap (either way along X).
        handle = Part.makeBox(60, 20, 5).fuse(
            [Part.makeBox(8, 8, 30, V(5, 6, 5)), Part.makeBox(8, 8, 30, V(47, 6, 5)),
             Part.makeBox(50, 8, 6, V(5, 6, 35))]).removeSplitter()
        d = mas.decompose(handle, step=2.0)
        self.assertEqual([c.rule for c in d], ["root", "bridge"])
        assert_box(self, d[1].shape, (5, 6, 35), (55, 14, 41))
        direction = d[1].build_direction
        self.assertAlmostEqual(abs(direction.x), math.sqrt(0.5), places=12)
        self.assertAlmostEqual(direction.y, 0.0, places=12)
        self.assertAlmostEqual(direction.z, math.sqrt(0.5), places=12)
        self.assertEqual(d.to_dict()["components"][1]["rule"], "bridge")

    def test_a_portal_on_two_legs_is_a_bridge_its_root_the_legs_apart(self):
        # Nothing joins the legs below: without the lintel the root is the two legs, a compound
        # of two solids each standing on the plate.
        d = mas.decompose(portal())
        self.assertEqual([c.rule for c in d], ["root", "bridge"])
        root = d[0].shape
        self.assertEqual(root.ShapeType, "Compound")
        self.assertEqual(len(root.Solids), 2)
        for leg in root.Solids:
            self.assertTrue(leg.isValid())
            self.assertAlmostEqual(leg.BoundBox.ZMin, 0.0, delta=1e-9)
        self.assertAlmostEqual(root.Volume, 2 * 8 * 8 * 30 + 144, delta=1e-6)
        self.assertEqual(d[1].shape.ShapeType, "Solid")
        assert_box(self, d[1].shape, (0, 0, 30), (50, 8, 36))

    def test_document_object_and_file_inputs(self):
        folder = tempfile.mkdtemp(prefix="mas_dec_")
        doc = FreeCAD.newDocument("MasDecInputs")
        try:
            part = doc.addObject("Part::Feature", "L")
            part.Shape = l_block()
            self.check_l_block(mas.decompose(part, step=2.5))
            path = os.path.join(folder, "l.brep")
            l_block().exportBrep(path)
            self.check_l_block(mas.decompose(path, step=2.5))
        finally:
            FreeCAD.closeDocument(doc.Name)
            shutil.rmtree(folder)

    def test_to_dict_is_json_ready(self):
        d = mas.decompose(l_block(), step=2.5)
        data = d.to_dict()
        self.assertEqual(json.loads(json.dumps(data, allow_nan=False)), data)
        self.assertEqual(set(data), {"kind", "part_volume_mm3", "axis", "components", "notes"})
        self.assertEqual(data["notes"], [])
        self.assertEqual(data["axis"], {"step_mm": 2.5, "nodes": 44, "branches": 2})
        self.assertEqual(len(data["components"]), 2)
        for c in data["components"]:
            self.assertEqual(set(c), {"parent", "build_direction", "base_origin", "base_normal",
                                      "branch", "break_link", "rule", "turned",
                                      "volume_mm3", "has_base_face"})
        arm = data["components"][1]
        self.assertEqual(arm["parent"], 0)
        self.assertEqual(arm["rule"], "planar_face")
        self.assertTrue(arm["has_base_face"])
        self.assertFalse(data["components"][0]["has_base_face"])
        self.assertAlmostEqual(arm["volume_mm3"], 20000.0, delta=20000.0 * REL)

    def test_to_dict_matches_the_command_line_json(self):
        with support.scratch_folder("mas_dec_cli_") as folder:
            path = os.path.join(folder, "t.brep")
            t_block().exportBrep(path)
            cli = self.cli_json(folder, "decompose", path, "--step", "2.5")
            ours = mas.decompose(path, step=2.5).to_dict()
        self.assertEqual(cli.pop("file"), path)
        self.assertSameJson(cli, ours, "decomposition")


class TestDecomposeBadInput(DecomposeTest):
    def test_none_and_unsupported_types_are_type_errors(self):
        with self.assertRaisesRegex(TypeError, "None"):
            mas.decompose(None)
        with self.assertRaisesRegex(TypeError, "int"):
            mas.decompose(42)

    def test_a_mesh_cannot_be_decomposed(self):
        with self.assertRaises(TypeError) as caught:
            mas.decompose(Mesh.Mesh(l_block().tessellate(0.1)))
        self.assertEqual(str(caught.exception),
                         "decompose() splits a BREP solid (Part.Shape, STEP, IGES or BREP file); a "
                         "mesh cannot be split into solids (slice() splits a mesh into mesh pieces "
                         "as it slices it)")
        with self.assertRaisesRegex(TypeError, "; box.off, a mesh, cannot be split into solids"):
            with support.scratch_folder("mas_dec_") as folder:
                path = os.path.join(folder, "box.off")
                Mesh.Mesh(Part.makeBox(1, 2, 3).tessellate(0.1)).write(path)
                mas.decompose(path)

    def test_face_is_not_a_solid(self):
        e = self.assertRaisesEngineError("not_a_solid", mas.decompose, Part.makePlane(10, 10))
        self.assertIn("Face", str(e))

    def test_two_solids_are_rejected(self):
        two = Part.makeCompound([l_block(), Part.makeBox(5, 5, 5, V(100, 0, 0))])
        e = self.assertRaisesEngineError("multiple_solids", mas.decompose, two)
        self.assertIn("2 solids", str(e))

    def test_engine_checks_its_inputs(self):
        solid = mas._engine.Shape.from_brep_string(l_block().exportBrepToString())
        axis = mas.centroidal_axis(l_block(), step=2.5)._engine_dict()
        e = self.assertRaisesEngineError("invalid_argument", mas._engine.decompose, solid,
                                         {"nodes": []})
        self.assertIn("links", str(e))
        broken = dict(axis, links=[dict(axis["links"][0], kind="sideways")] + axis["links"][1:])
        e = self.assertRaisesEngineError("invalid_argument", mas._engine.decompose, solid, broken)
        self.assertIn("kind", str(e))
        self.assertRaisesEngineError("invalid_argument", mas._engine.decompose, solid, axis,
                                     face_angle=float("nan"))
        nan_start = dict(axis, nodes=[dict(axis["nodes"][0], slab_start=float("nan"))]
                         + axis["nodes"][1:])
        e = self.assertRaisesEngineError("invalid_argument", mas._engine.decompose, solid,
                                         nan_start)
        self.assertIn("nodes'][0]", str(e))
        bad_deflection = dict(axis, params=dict(axis["params"], deflection_mm=-1.0))
        e = self.assertRaisesEngineError("invalid_argument", mas._engine.decompose, solid,
                                         bad_deflection)
        self.assertIn("deflection_mm", str(e))
        # A node naming a branch the axis lacks (the decomposition walks a node's branch).
        start = axis["links"][0]["start"]
        far = dict(axis, nodes=[dict(n, branch=50000000) if i == start else n
                                for i, n in enumerate(axis["nodes"])])
        e = self.assertRaisesEngineError("invalid_argument", mas._engine.decompose, solid, far)
        self.assertIn("node {} names branch 50000000".format(start), str(e))
        # A node's region is bytes only the engine reads: anything else it could not have
        # written is named.
        self.assertIsInstance(axis["nodes"][0]["region"], bytes)
        nan = struct.pack("=8d", 1, 3, 0, 0, 1, 0, float("nan"), 1)
        for region, says in (("text", "bytes"), (b"abc", "cut short"),
                             (struct.pack("=2d", 1, 3), "not a region"),
                             (axis["nodes"][0]["region"] + struct.pack("=d", 0), "not a region"),
                             (nan, "NaN")):
            bad = dict(axis, nodes=[dict(axis["nodes"][0], region=region)] + axis["nodes"][1:])
            e = self.assertRaisesEngineError("invalid_argument", mas._engine.decompose, solid,
                                             bad)
            self.assertIn("nodes'][0]['region']", str(e))
            self.assertIn(says, str(e))
        self.assertEqual(len(mas._engine.decompose(solid, axis)["components"]), 2)

    def test_the_source_is_not_modified(self):
        shape = t_block()
        shape.Placement = FreeCAD.Placement(V(1, 2, 3), FreeCAD.Rotation())
        before = shape.exportBrepToString()
        d = mas.decompose(shape, step=2.5)
        self.assertEqual(len(d), 3)
        self.assertEqual(shape.exportBrepToString(), before)


class TestDecomposeWithoutFreeCAD(DecomposeTest):
    def test_plain_python_gives_engine_shapes_and_brep_text(self):
        with support.scratch_folder("mas_plain_dec_") as folder:
            path = os.path.join(folder, "l.brep")
            l_block().exportBrep(path)
            result = support.run_plain_python(folder, """
                import json, sys
                assert "FreeCAD" not in sys.modules
                import MultiAxisSlicer as mas
                d = mas.decompose({!r}, step=2.5)
                arm = d[1]
                print("RESULT", len(d), arm.build_direction, type(arm.shape).__name__,
                      "CASCADE Topology" in arm.brep, arm.base_face_brep is not None,
                      round(arm.volume, 6))
                json.dumps(d.to_dict())
            """.format(path))
        self.assertEqual(result.returncode, 0, result.stderr)
        self.assertIn("RESULT 2 (1.0, 0.0, -0.0) Shape True True 20000.0", result.stdout)


class TestDecompositionObject(DecomposeTest):
    def setUp(self):
        self.doc = FreeCAD.newDocument("MasDec")
        self.part = self.doc.addObject("Part::Feature", "L")
        self.part.Shape = l_block()
        self.doc.recompute()
        self.folder = tempfile.mkdtemp(prefix="mas_dec_doc_")

    def tearDown(self):
        for name in list(FreeCAD.listDocuments()):
            if name.startswith("MasDec"):
                FreeCAD.closeDocument(name)
        shutil.rmtree(self.folder)

    def check_l_block_objects(self, obj):
        self.assertTrue(obj.isValid(), obj.getStatusString())
        self.assertEqual(obj.Proxy.Type, "MultiAxisSlicer::Decomposition")
        self.assertEqual(obj.ComponentCount, 2)
        self.assertEqual(list(obj.ComponentParents), [-1, 0])
        self.assertEqual(list(obj.Rules), ["root", "planar_face"])
        self.assertEqual(list(obj.Turned), [False, False])
        self.assertVectorAlmostEqual(obj.BuildDirections[1], (1, 0, 0))
        self.assertVectorAlmostEqual(obj.BaseOrigins[1], (20, 10, 50))
        self.assertAlmostEqual(obj.Volumes[1], 20000.0, delta=20000.0 * REL)
        self.assertAlmostEqual(obj.PartVolume.Value, 44000.0, delta=44000.0 * REL)
        self.assertEqual(len(obj.Shape.Solids), 2)
        self.assertAlmostEqual(obj.Shape.Volume, 44000.0, delta=44000.0 * REL)
        components = features.components_of(obj)
        self.assertEqual([c.Label for c in components], ["Component001", "Component002"])
        self.assertEqual([c.Index for c in components], [0, 1])
        for c in components:
            self.assertTrue(c.isValid(), c.getStatusString())
            self.assertIs(c.Decomposition, obj)
        root, arm = components
        assert_box(self, root.Shape, (0, 0, 0), (20, 20, 60))
        assert_box(self, arm.Shape, (20, 0, 40), (70, 20, 60))
        self.assertEqual((root.Parent, arm.Parent), (-1, 0))
        self.assertEqual(arm.Rule, "planar_face")
        self.assertVectorAlmostEqual(arm.BuildDirection, (1, 0, 0))
        self.assertAlmostEqual(arm.Volume.Value, 20000.0, delta=20000.0 * REL)
        return components

    def test_make_computes_the_decomposition_and_its_components(self):
        obj = mas.make_decomposition(self.part)
        self.assertEqual(obj.FaceAngle.Value, 10.0)
        self.assertTrue(obj.SectionPlaneFallback)
        self.assertIs(obj.Source, self.part)
        self.assertIsNone(obj.Axis)
        self.doc.recompute()
        self.check_l_block_objects(obj)
        self.assertEqual(obj.UsedStep.Value, mas.decompose(l_block()).axis.params["step_mm"])

    def test_axis_object_parameters_are_used(self):
        axis = mas.make_centroidal_axis(self.part, step=2.5)
        self.doc.recompute()
        obj = mas.make_decomposition(None, axis=axis)
        self.doc.recompute()
        self.check_l_block_objects(obj)
        self.assertEqual(obj.UsedStep.Value, 2.5)
        self.assertIn(axis, obj.OutList)
        axis.Step = 5.0
        self.doc.recompute()
        self.assertEqual(obj.UsedStep.Value, 5.0)
        self.check_l_block_objects(obj)

    def test_the_source_is_not_modified(self):
        before = self.part.Shape.exportBrepToString()
        obj = mas.make_decomposition(self.part)
        self.doc.recompute()
        self.assertTrue(obj.isValid())
        self.assertEqual(self.part.Shape.exportBrepToString(), before)
        self.assertNotIn("Touched", self.part.State)

    def test_source_changes_flow_into_the_components(self):
        obj = mas.make_decomposition(self.part)
        self.doc.recompute()
        self.part.Shape = t_block()
        self.doc.recompute()
        self.assertEqual(obj.ComponentCount, 3)
        components = features.sync_components(obj)  # outside the recompute
        self.assertEqual([c.Label for c in components],
                         ["Component001", "Component002", "Component003"])
        self.doc.recompute()
        for c in components:
            self.assertTrue(c.isValid(), c.getStatusString())
            self.assertAlmostEqual(c.Volume.Value, obj.Volumes[c.Index], places=6)
        self.part.Shape = Part.makeBox(20, 20, 60)
        self.doc.recompute()
        self.assertEqual(obj.ComponentCount, 1)
        self.assertIn("Invalid", components[2].State)  # until synchronised
        self.assertIn("now has 1 component(s)", components[2].getStatusString())
        self.assertEqual(len(features.sync_components(obj)), 1)
        self.doc.recompute()
        self.assertEqual([c.Label for c in features.components_of(obj)], ["Component001"])
        self.assertTrue(all(o.isValid() for o in self.doc.Objects))

    def test_a_source_in_a_group_is_split_where_the_view_shows_it(self):
        # The L in an App::Part that raises it 100: its components are the L's as drawn. Moving
        # the group marks the object for recompute, and the components follow: the result kept
        # in memory is not reused for a source placed elsewhere.
        group = self.doc.addObject("App::Part", "Group")
        group.addObject(self.part)
        group.Placement.Base = V(0, 0, 100)
        self.doc.recompute()
        obj = mas.make_decomposition(self.part)
        self.doc.recompute()
        for base, moved_to in ((V(0, 0, 100), V(0, -30, 7)), (V(0, -30, 7), None)):
            self.assertTrue(obj.isValid(), obj.getStatusString())
            self.assertEqual(obj.ComponentCount, 2)
            root, arm = features.components_of(obj)
            assert_box(self, root.Shape, base, base + V(20, 20, 60))
            assert_box(self, arm.Shape, base + V(20, 0, 40), base + V(70, 20, 60))
            self.assertVectorAlmostEqual(obj.BaseOrigins[1], base + V(20, 10, 50))
            if moved_to is None:
                break
            self.assertNotIn("Touched", obj.State)
            group.Placement.Base = moved_to
            self.assertIn("Touched", obj.State)
            self.doc.recompute()
        assert_box(self, self.part.Shape, (0, 0, 0), (70, 20, 60))

    def test_a_removed_component_made_anew_and_brought_back_by_undo_is_one_again(self):
        # A script removes a Component object, sync_components() makes it anew, and an undo
        # brings the removed one back: two objects for component 0, both labelled Component001.
        self.doc.UndoMode = 1
        obj = mas.make_decomposition(self.part)
        self.doc.recompute()
        root, arm = self.check_l_block_objects(obj)
        self.doc.openTransaction("Remove")
        self.doc.removeObject(root.Name)
        self.doc.commitTransaction()
        self.doc.recompute()
        made = features.sync_components(obj)[0]
        self.assertEqual((made.Index, made.Label), (0, "Component001"))
        self.doc.undo()
        self.doc.recompute()
        self.assertEqual([c.Index for c in features.components_of(obj)], [0, 0, 1])
        self.assertEqual(len(features.sync_components(obj)), 2)
        self.doc.recompute()
        root, arm = self.check_l_block_objects(obj)
        # Of two for one component, the one labelled as the component is kept, whichever comes
        # first.
        root.Label = "Renamed"
        renamed = root.Name
        twin = self.doc.addObject("Part::FeaturePython", "Component")
        features.ComponentFeature(twin)
        twin.Decomposition = obj
        twin.Index = 0
        twin.Label = "Component001"
        self.doc.recompute()
        self.assertEqual([c.Name for c in features.sync_components(obj)], [twin.Name, arm.Name])
        self.assertIsNone(self.doc.getObject(renamed))
        self.doc.recompute()
        self.check_l_block_objects(obj)

    def test_a_link_round_in_a_circle_marks_the_object(self):
        # A Decomposition's Source set to one of its own Component objects: FreeCAD only logs
        # that the graph is no longer acyclic, and the Decomposition was computed, valid, from
        # its own output.
        obj = mas.make_decomposition(self.part)
        self.doc.recompute()
        root, _arm = self.check_l_block_objects(obj)
        layers, _toolpath = mas.make_slice(obj)
        self.doc.recompute()
        for o in (obj, layers):  # without a circle, what FreeCAD's OutListRecursive gives
            self.assertEqual(sorted(d.Name for d in features.depends_on(o)),
                             sorted(d.Name for d in o.OutListRecursive))
        obj.Source = root
        self.doc.recompute()
        self.assertIn("Invalid", obj.State)
        self.assertEqual(obj.getStatusString(),
                         "Source 'Component001' is made from this object: the links go round in "
                         "a circle (undo the link that closed it)")
        self.assertEqual(obj.ComponentCount, 2)  # the last result stands
        # What the panels and commands read of it (FreeCAD's OutListRecursive raises on a circle).
        self.assertEqual(features.failure(obj), "Decomposition: " + obj.getStatusString())
        self.assertEqual(features.depends_on(obj), [root])  # and root on obj, not repeated
        obj.Source = obj
        self.doc.recompute()
        self.assertEqual(obj.getStatusString(), "Source is this object itself: link another object")
        self.assertEqual(features.failure(obj), "Decomposition: " + obj.getStatusString())
        obj.Source = self.part
        self.doc.recompute()
        self.check_l_block_objects(obj)

    def test_min_component_height_keeps_a_short_child_in_its_father(self):
        obj = mas.make_decomposition(self.part)
        self.assertEqual(obj.MinComponentHeight.Value, 0.0)  # one axis step
        self.doc.recompute()
        self.assertEqual(obj.ComponentCount, 2)
        obj.MinComponentHeight = 60.0  # the arm reaches 50 mm past its cut
        self.doc.recompute()
        self.assertTrue(obj.isValid(), obj.getStatusString())
        self.assertEqual(obj.ComponentCount, 1)
        self.assertIn("reaches only 50 mm", obj.Notes[0])
        self.assertEqual(len(features.sync_components(obj)), 1)
        short = mas.make_decomposition(self.part,
                                       min_component_height=FreeCAD.Units.Quantity("6 cm"))
        self.assertEqual(short.MinComponentHeight.Value, 60.0)
        self.assertEqual(short.ComponentCount, 1)

    def test_save_close_reopen_recompute(self):
        obj = mas.make_decomposition(self.part, face_angle=5.0, deflection=0.02,
                                     min_component_height=1.5)
        self.doc.recompute()
        path = os.path.join(self.folder, "decomposition.FCStd")
        self.doc.saveAs(path)
        FreeCAD.closeDocument(self.doc.Name)

        doc = FreeCAD.openDocument(path)
        obj = doc.getObject("Decomposition")
        self.assertIsInstance(obj.Proxy, features.DecompositionFeature)
        self.assertIs(obj.Source, doc.getObject("L"))
        self.assertEqual(obj.FaceAngle.Value, 5.0)
        self.assertEqual(obj.Deflection.Value, 0.02)
        self.assertEqual(obj.MinComponentHeight.Value, 1.5)
        self.assertEqual(len(obj.Shape.Solids), 2)  # saved with the document
        for c in features.components_of(obj):
            self.assertIsInstance(c.Proxy, features.ComponentFeature)
        obj.touch()
        doc.recompute()
        self.check_l_block_objects(obj)
        doc.save()

    def test_a_root_on_two_legs_is_one_component_object_of_two_solids(self):
        # The Decomposition's compound holds one child shape per component: the root's is a
        # compound of its legs, shown by one Component object, before and after saving.
        part = self.doc.addObject("Part::Feature", "Portal")
        part.Shape = portal()
        self.doc.recompute()
        obj = mas.make_decomposition(part)
        self.doc.recompute()

        def check(obj):
            self.assertTrue(obj.isValid(), obj.getStatusString())
            self.assertEqual(obj.ComponentCount, 2)
            self.assertEqual(list(obj.Rules), ["root", "bridge"])
            self.assertEqual(len(obj.Shape.childShapes()), 2)
            self.assertEqual(len(obj.Shape.Solids), 3)
            root, lintel = features.components_of(obj)
            self.assertTrue(root.isValid(), root.getStatusString())
            self.assertEqual(len(root.Shape.Solids), 2)
            self.assertAlmostEqual(root.Shape.Volume, 2 * 8 * 8 * 30 + 144, delta=1e-6)
            self.assertAlmostEqual(root.Volume.Value, 2 * 8 * 8 * 30 + 144, delta=1e-6)
            self.assertEqual(lintel.Rule, "bridge")
            self.assertEqual(len(lintel.Shape.Solids), 1)
            assert_box(self, lintel.Shape, (0, 0, 30), (50, 8, 36))

        check(obj)
        name = obj.Name
        path = os.path.join(self.folder, "portal.FCStd")
        self.doc.saveAs(path)
        FreeCAD.closeDocument(self.doc.Name)
        doc = FreeCAD.openDocument(path)
        obj = doc.getObject(name)
        check(obj)
        obj.touch()
        doc.recompute()
        check(obj)

    def test_turned_cuts_are_listed_and_shown_on_their_components(self):
        # Six blades 60 degrees apart round a hub, the first along +X: the four between +-X and
        # +-Y are cut square to their own lines and built along them, listed in Turned, each
        # Component saying so; with TurnCuts off none is. Saved and reopened, the same.
        hub = self.doc.addObject("Part::Feature", "Hub")
        hub.Shape = support.hub_with_six_blades()
        self.doc.recompute()
        obj = mas.make_decomposition(hub)
        self.doc.recompute()
        self.assertTrue(obj.isValid(), obj.getStatusString())
        self.assertEqual(obj.ComponentCount, 7)
        between = [abs(d.x) + abs(d.y) + abs(d.z) > 1.0 + 1e-9 for d in obj.BuildDirections]
        self.assertEqual(sum(between), 4)
        self.assertEqual(list(obj.Turned), between)
        self.assertEqual([c.Turned for c in features.components_of(obj)], between)
        path = os.path.join(self.folder, "MasDecTurned.FCStd")  # closed by tearDown
        self.doc.saveAs(path)
        FreeCAD.closeDocument(self.doc.Name)
        self.doc = FreeCAD.openDocument(path)
        obj = self.doc.getObject("Decomposition")
        self.assertEqual(list(obj.Turned), between)
        self.assertEqual([c.Turned for c in features.components_of(obj)], between)
        obj.TurnCuts = False
        self.doc.recompute()
        self.assertTrue(obj.isValid(), obj.getStatusString())
        self.assertEqual(list(obj.Turned), [False] * obj.ComponentCount)
        self.assertEqual([c.Turned for c in features.components_of(obj)],
                         [False] * obj.ComponentCount)

    def test_undo_removes_everything_the_command_made(self):
        self.doc.UndoMode = 1
        names = [o.Name for o in self.doc.Objects]
        self.doc.openTransaction("Decompose")
        obj = mas.make_decomposition(self.part)
        self.doc.recompute()
        self.doc.commitTransaction()
        self.assertEqual(len(self.doc.Objects), len(names) + 3)
        self.doc.undo()
        self.assertEqual([o.Name for o in self.doc.Objects], names)
        self.doc.redo()
        obj = self.doc.getObject("Decomposition")
        self.assertEqual(len(features.components_of(obj)), 2)

    def test_bad_sources_mark_the_object_without_components(self):
        face = self.doc.addObject("Part::Feature", "Face")
        face.Shape = Part.makePlane(10, 10)
        obj = mas.make_decomposition(face)
        self.doc.recompute()
        self.assertIn("Invalid", obj.State)
        self.assertIn("not a solid", obj.getStatusString())
        self.assertEqual(features.components_of(obj), [])
        mesh = self.doc.addObject("Mesh::Feature", "LMesh")
        mesh.Mesh = Mesh.Mesh(l_block().tessellate(0.1))
        obj.Source = mesh
        self.doc.recompute()
        self.assertIn("Invalid", obj.State)
        self.assertIn("BREP solid", obj.getStatusString())
        axis = mas.make_centroidal_axis(self.part)
        obj.Source = None
        self.doc.recompute()
        self.assertIn("Source is not set", obj.getStatusString())
        obj.Axis = self.part
        self.doc.recompute()
        self.assertIn("not a CentroidalAxis", obj.getStatusString())
        obj.Axis = axis
        obj.Source = face
        self.doc.recompute()
        self.assertIn("belongs to 'L', not to the Source 'Face'", obj.getStatusString())
        obj.Source = None  # recovers, the axis' Source is used
        self.doc.recompute()
        self.assertTrue(obj.isValid(), obj.getStatusString())
        self.assertEqual(obj.ComponentCount, 2)

    def test_make_rejects_bad_parameters_before_adding_anything(self):
        names = [o.Name for o in self.doc.Objects]
        with self.assertRaisesRegex(ValueError, "face_angle"):
            mas.make_decomposition(self.part, face_angle=95.0)
        with self.assertRaisesRegex(TypeError, "CentroidalAxis"):
            mas.make_decomposition(self.part, axis=self.part)
        self.assertEqual([o.Name for o in self.doc.Objects], names)

    def test_failing_recompute_prints_the_message_without_a_traceback(self):
        script = support.write_dedented(self.folder, "fail.py", """
            import FreeCAD, Mesh, Part
            import MultiAxisSlicer as mas
            doc = FreeCAD.newDocument("Fail")
            face = doc.addObject("Part::Feature", "Face")
            face.Shape = Part.makePlane(10, 10)
            a = mas.make_decomposition(face)
            mesh = doc.addObject("Mesh::Feature", "Mesh")
            mesh.Mesh = Mesh.Mesh(Part.makeBox(10, 10, 10).tessellate(0.1))
            b = mas.make_decomposition(mesh)
            doc.recompute()
            print("STATES", a.State, b.State)
        """)
        result = subprocess.run(["freecadcmd", script], capture_output=True, text=True, timeout=120)
        output = result.stdout + result.stderr
        self.assertIn("STATES ['Invalid'] ['Invalid']", output.replace("'Touched', ", ""))
        self.assertIn("not a solid", output)
        self.assertIn("BREP solid", output)
        self.assertNotIn("Traceback", output)


if __name__ == "__main__":
    unittest.main()
