# SPDX-License-Identifier: LGPL-2.1-or-later
"""The scripting API and the Sections document object, inside freecadcmd.

Run: freecadcmd -t TestMultiAxisSlicerApi (tests/run_freecad_test.sh does it against the add-on
staged in the build tree). Expected values are exact for planar parts; for curved parts the bound
comes from the tessellation deflection the API reports.
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
from MultiAxisSlicerTestSupport import V, box_10_20_30, fc_mesh


class TestSectionsOfPlanarParts(support.EngineTestCase):
    def test_engine_is_available(self):
        self.assertTrue(mas.engine_available(), mas.engine_missing_message())
        self.assertEqual(mas.engine_missing_message(), "")

    def test_box_sections_along_z_have_exact_area_and_centroid(self):
        result = mas.sections(box_10_20_30(), normal=(0, 0, 1), step=5.0)
        self.assertEqual(len(result), 6)  # 30 mm / 5 mm, each plane in the middle of its slab
        for i, s in enumerate(result):
            z = 3 + 2.5 + 5 * i
            self.assertVectorAlmostEqual(s.origin, (0, 0, z))
            self.assertVectorAlmostEqual(s.normal, (0, 0, 1))
            self.assertAlmostEqual(s.area, 200.0, places=9)
            self.assertVectorAlmostEqual(s.centroid, (6, 12, z))
            self.assertEqual(s.open_chains, 0)
            self.assertEqual(len(s.regions), 1)
            region = s.regions[0]
            self.assertAlmostEqual(region.area, 200.0, places=9)
            self.assertEqual(region.holes, [])
            self.assertVectorAlmostEqual(region.bounds[0], (1, 2, z))
            self.assertVectorAlmostEqual(region.bounds[1], (11, 22, z))
            self.assertIsInstance(s.centroid, FreeCAD.Vector)
            self.assertIsInstance(region.outer[0], FreeCAD.Vector)
            for p in region.outer:
                self.assertAlmostEqual(p.z, z, places=9)

    def test_progress_is_reported_every_tenth_of_the_planes_and_a_raise_stops_it(self):
        reports = []
        result = mas.sections(box_10_20_30(), step=0.005,
                              progress=lambda f, s: reports.append((f, s)))
        self.assertEqual(len(result), 6000)
        self.assertEqual(reports, [(600 * k / 6000, "cutting 6000 sections") for k in range(1, 11)])
        # Up to 2000 planes in one call, reported at the end.
        few = []
        mas.sections(box_10_20_30(), step=0.025, progress=lambda f, s: few.append(f))
        self.assertEqual(few, [1.0])
        # The same sections as cut all at once.
        whole = mas.sections(box_10_20_30(), step=0.005)
        self.assertEqual([s.origin for s in result], [s.origin for s in whole])
        self.assertEqual([s.area for s in result], [s.area for s in whole])

        def stop(fraction, stage):
            raise mas.Cancelled("enough")

        with self.assertRaisesRegex(mas.Cancelled, "enough"):
            mas.sections(box_10_20_30(), step=0.005, progress=stop)
        with self.assertRaisesRegex(TypeError, "progress must be"):
            mas.sections(box_10_20_30(), progress="yes")

    def test_a_step_giving_over_100000_planes_is_named(self):
        with self.assertRaisesRegex(mas.EngineError, "too small.*more than 100000"):
            mas.sections(box_10_20_30(), step=1e-4)

    def test_box_sections_along_x_have_exact_area(self):
        result = mas.sections(box_10_20_30(), normal=(1, 0, 0), step=2.5)
        self.assertEqual(len(result), 4)
        for s in result:
            self.assertAlmostEqual(s.area, 600.0, places=9)
            self.assertAlmostEqual(s.centroid.y, 12.0, places=9)
            self.assertAlmostEqual(s.centroid.z, 18.0, places=9)

    def test_oblique_plane_through_box_centre(self):
        # The plane y + z = 29 through the centre (6, 12, 17) crosses the box's whole 20 mm in y:
        # a 10 x 20*sqrt(2) rectangle.
        s = mas.section(box_10_20_30(), origin=(6, 12, 17), normal=(0, 1, 1))
        self.assertAlmostEqual(s.area, 200.0 * math.sqrt(2.0), places=9)
        self.assertVectorAlmostEqual(s.centroid, (6, 12, 17))
        self.assertVectorAlmostEqual(s.normal, (0, math.sqrt(0.5), math.sqrt(0.5)))

    def test_plane_missing_the_part_gives_an_empty_section(self):
        s = mas.section(box_10_20_30(), origin=(0, 0, 100), normal=(0, 0, 1))
        self.assertTrue(s.empty())
        self.assertEqual(s.area, 0.0)
        self.assertEqual(s.regions, [])

    def test_box_with_a_square_hole_has_one_region_with_one_hole(self):
        part = Part.makeBox(20, 20, 10).cut(Part.makeBox(6, 6, 10, V(7, 7, 0)))
        s = mas.section(part, origin=(0, 0, 5), normal=(0, 0, 1))
        self.assertEqual(len(s.regions), 1)
        self.assertEqual(len(s.regions[0].holes), 1)
        self.assertEqual(len(s.regions[0].loops), 2)
        self.assertAlmostEqual(s.area, 400.0 - 36.0, places=9)
        self.assertVectorAlmostEqual(s.centroid, (10, 10, 5))

    def test_to_dict_is_json_ready(self):
        s = mas.section(box_10_20_30(), origin=(0, 0, 10), normal=(0, 0, 1))
        d = json.loads(json.dumps(s.to_dict()))
        self.assertEqual(d["origin"], [0.0, 0.0, 10.0])
        self.assertAlmostEqual(d["area"], 200.0, places=9)
        self.assertEqual(len(d["regions"]), 1)
        self.assertEqual(d["regions"][0]["holes"], [])
        self.assertEqual(len(d["regions"][0]["outer"][0]), 3)
        self.assertEqual(d["regions"][0]["bounds"]["max"], [11.0, 22.0, 10.0])

    def test_exact_sections_agree_with_mesh_sections_on_a_box(self):
        shape = box_10_20_30()
        planes = mas.parallel_planes(shape, normal=(0, 0, 1), step=10.0)
        exact = mas.exact_sections(shape, planes)
        mesh = mas.sections(shape, normal=(0, 0, 1), step=10.0)
        self.assertEqual(len(exact), 3)
        for e, m in zip(exact, mesh):
            self.assertAlmostEqual(e.area, 200.0, places=6)
            self.assertAlmostEqual(e.area, m.area, places=6)
            self.assertVectorAlmostEqual(e.centroid, m.centroid, places=6)


class TestSectionsOfCurvedParts(support.EngineTestCase):
    def test_cylinder_sections_lie_within_the_deflection_bound(self):
        r, h = 10.0, 20.0
        cylinder = Part.makeCylinder(r, h)
        d = mas.deflection(cylinder)
        self.assertGreater(d, 0.0)
        exact_area = math.pi * r * r
        # Section loops are polygons inscribed in the circle, each edge within d of it: the area
        # is short by at most perimeter x d, never larger, and the centroid stays within d.
        for s in mas.sections(cylinder, normal=(0, 0, 1), step=4.0):
            self.assertLessEqual(s.area, exact_area + 1e-9)
            self.assertGreaterEqual(s.area, exact_area - 2 * math.pi * r * d)
            self.assertLess(math.hypot(s.centroid.x, s.centroid.y), d)

    def test_explicit_deflection_is_used_and_bounds_the_error(self):
        r = 10.0
        cylinder = Part.makeCylinder(r, 20.0)
        self.assertEqual(mas.deflection(cylinder, 0.05), 0.05)
        s = mas.section(cylinder, origin=(0, 0, 10), normal=(0, 0, 1), deflection=0.05)
        self.assertGreaterEqual(s.area, math.pi * r * r - 2 * math.pi * r * 0.05)
        self.assertLessEqual(s.area, math.pi * r * r + 1e-9)

    def test_exact_section_of_a_cylinder_is_exact(self):
        cylinder = Part.makeCylinder(10.0, 20.0)
        [s] = mas.exact_sections(cylinder, [((0, 0, 10), (0, 0, 1))])
        self.assertAlmostEqual(s.area, math.pi * 100.0, places=6)
        self.assertVectorAlmostEqual(s.centroid, (0, 0, 10), places=6)


class TestInputs(support.EngineTestCase):
    def test_mesh_input_gives_the_same_sections_as_the_shape(self):
        shape = box_10_20_30()
        from_shape = mas.sections(shape, step=5.0)
        from_mesh = mas.sections(fc_mesh(shape), step=5.0)
        self.assertEqual(len(from_mesh), len(from_shape))
        for a, b in zip(from_shape, from_mesh):
            self.assertAlmostEqual(a.area, b.area, places=9)
            self.assertVectorAlmostEqual(a.centroid, b.centroid)

    def test_document_objects_are_cut_where_they_are_placed(self):
        doc = FreeCAD.newDocument("MasApiObjects")
        try:
            box = doc.addObject("Part::Box", "Box")
            box.Length, box.Width, box.Height = 10, 20, 30
            box.Placement.Base = V(100, 0, 0)
            mesh = doc.addObject("Mesh::Feature", "Mesh")
            mesh.Mesh = fc_mesh(Part.makeBox(10, 20, 30))
            mesh.Placement.Base = V(0, 100, 0)
            doc.recompute()
            s = mas.section(box, origin=(0, 0, 15), normal=(0, 0, 1))
            self.assertAlmostEqual(s.area, 200.0, places=9)
            self.assertVectorAlmostEqual(s.centroid, (105, 10, 15))
            s = mas.section(mesh, origin=(0, 0, 15), normal=(0, 0, 1))
            self.assertAlmostEqual(s.area, 200.0, places=9)
            self.assertVectorAlmostEqual(s.centroid, (5, 110, 15))
        finally:
            FreeCAD.closeDocument(doc.Name)

    def test_objects_in_groups_are_cut_where_the_view_shows_them(self):
        # The plate is the document's XY plane: an object inside an App::Part, or a feature
        # inside a Body inside one, is cut with its groups' placements applied, as drawn. The
        # group here stands the 10 x 20 x 30 box on its side: turned 90 degrees about Y, it
        # reaches 30 along X from x = 100 and hangs 10 below z = 5.
        doc = FreeCAD.newDocument("MasApiGroups")
        try:
            group = doc.addObject("App::Part", "Group")
            group.Placement = FreeCAD.Placement(V(100, 0, 5), FreeCAD.Rotation(V(0, 1, 0), 90))
            box = doc.addObject("Part::Box", "Box")
            box.Length, box.Width, box.Height = 10, 20, 30
            group.addObject(box)
            body = doc.addObject("PartDesign::Body", "Body")
            group.addObject(body)
            body.Placement.Base = V(0, 50, 0)
            feature = doc.addObject("PartDesign::AdditiveBox", "BodyBox")
            body.addObject(feature)
            feature.Length, feature.Width, feature.Height = 10, 20, 30
            mesh = doc.addObject("Mesh::Feature", "Mesh")
            mesh.Mesh = fc_mesh(Part.makeBox(10, 20, 30))
            group.addObject(mesh)
            mesh.Placement.Base = V(0, 100, 0)

            def add_link(name, target, y):  # in the group, moved y along Y
                link = doc.addObject("App::Link", name)
                link.LinkedObject = target
                group.addObject(link)
                link.Placement.Base = V(0, y, 0)
                return link

            link = add_link("Link", box, 150)
            # A link to the mesh (its placement the link's, the mesh's own overridden), and a link
            # to that link.
            mesh_link = add_link("MeshLink", mesh, 200)
            chained = add_link("Chained", mesh_link, 250)
            doc.recompute()
            placements = [o.Placement for o in (group, box, body, feature, mesh, link)]
            # y of each copy's middle; every one spans x 100..130, z -5..5.
            for obj, y in ((box, 10), (body, 60), (feature, 60), (mesh, 110), (link, 160),
                           (mesh_link, 210), (chained, 260)):
                s = mas.section(obj, origin=(0, 0, 0), normal=(0, 0, 1))
                self.assertAlmostEqual(s.area, 600.0, places=6, msg=obj.Name)
                self.assertVectorAlmostEqual(s.centroid, (115, y, 0))
                self.assertAlmostEqual(mas.sections(obj, step=2.0)[0].origin.z, -4.0, places=9)
            self.assertEqual([o.Placement for o in (group, box, body, feature, mesh, link)],
                             placements)  # none moved
            self.assertEqual(box.Shape.BoundBox.ZMax, 30.0)
            self.assertEqual(mesh.Mesh.BoundBox.YMin, 100.0)
            self.assertIsInstance(mas._model(mesh_link)[1], mas._engine.Mesh)  # sliced as one
            # With LinkTransform, the mesh's own placement too: 100 + 300 along Y.
            mesh_link.LinkTransform = True
            mesh_link.Placement.Base = V(0, 300, 0)
            doc.recompute()
            s = mas.section(mesh_link, origin=(0, 0, 0), normal=(0, 0, 1))
            self.assertAlmostEqual(s.area, 600.0, places=6)
            self.assertVectorAlmostEqual(s.centroid, (115, 410, 0))
            # An array of links is no one part, nor is a link to one.
            mesh_link.ElementCount = 2
            doc.recompute()
            with self.assertRaisesRegex(ValueError, "'MeshLink' is 2 copies of the mesh 'Mesh'"):
                mas.section(mesh_link, origin=(0, 0, 0), normal=(0, 0, 1))
            with self.assertRaisesRegex(ValueError,
                                        "'Chained' links to 2 copies of the mesh 'Mesh'"):
                mas.section(chained, origin=(0, 0, 0), normal=(0, 0, 1))
        finally:
            FreeCAD.closeDocument(doc.Name)

    def test_files_are_read_by_extension(self):
        shape = box_10_20_30()
        folder = tempfile.mkdtemp(prefix="mas_api_")
        try:
            brep = os.path.join(folder, "box.brep")
            stl = os.path.join(folder, "box.stl")
            shape.exportBrep(brep)
            fc_mesh(shape).write(stl)
            self.assertIsInstance(mas.read(brep), mas._engine.Shape)
            self.assertIsInstance(mas.read(stl), mas._engine.Mesh)
            for path in (brep, stl):
                s = mas.section(path, origin=(0, 0, 10), normal=(0, 0, 1))
                self.assertAlmostEqual(s.area, 200.0, places=5)
                self.assertVectorAlmostEqual(s.centroid, (6, 12, 10), places=5)
        finally:
            shutil.rmtree(folder)

    def test_compound_of_one_solid_is_accepted(self):
        s = mas.section(Part.makeCompound([box_10_20_30()]), (0, 0, 10), (0, 0, 1))
        self.assertAlmostEqual(s.area, 200.0, places=9)

    def test_a_mesh_reaches_the_engine_point_for_point(self):
        # Its Topology (placement applied) read point by point: as vectors, tuples, lists or
        # anything with x, y and z, the same vertices and triangles as the flat arrays give.
        mesh = fc_mesh(Part.makeCylinder(5, 20))
        mesh.Placement = FreeCAD.Placement(V(3, -4, 1), FreeCAD.Rotation(V(0, 0, 1), 30))
        points, facets = mesh.Topology
        flat = mas._engine.Mesh.from_arrays([c for p in points for c in (p.x, p.y, p.z)],
                                            [i for f in facets for i in f])
        self.assertEqual(mas.to_engine_mesh(mesh).vertices(),
                         mas._engine.make_closed(flat).vertices())

        class Point:
            def __init__(self, p):
                self.x, self.y, self.z = p.x, p.y, p.z

        for given in (points, [tuple(p) for p in points], [list(p) for p in points],
                      [Point(p) for p in points]):
            got = mas._engine.Mesh.from_topology(given, [list(f) for f in facets])
            self.assertEqual(got.vertices(), flat.vertices())
            self.assertEqual(got.triangles(), flat.triangles())

    def test_a_meshs_topology_is_read_once(self):
        # Reading Mesh.Topology makes a Python object of every point and facet: telling a mesh
        # from other input once read it all for nothing, doubling what a mesh took to arrive.
        points, facets = fc_mesh(box_10_20_30()).Topology

        class CountingMesh:
            reads = 0
            CountFacets = len(facets)

            @property
            def Topology(self):
                CountingMesh.reads += 1
                return points, facets

        mesh = mas.to_engine_mesh(CountingMesh())
        self.assertEqual(CountingMesh.reads, 1)
        self.assertEqual(mesh.triangle_count(), 12)
        s = mas.section(CountingMesh(), (0, 0, 10), (0, 0, 1))
        self.assertAlmostEqual(s.area, 200.0, places=9)
        self.assertEqual(CountingMesh.reads, 2)

    def test_inside_out_mesh_is_flipped_in_a_copy(self):
        mesh = fc_mesh(box_10_20_30())
        mesh.flipNormals()
        before = mesh.Topology
        s = mas.section(mesh, (0, 0, 10), (0, 0, 1))
        self.assertAlmostEqual(s.area, 200.0, places=9)
        self.assertEqual(mesh.Topology, before)


class TestBadInput(support.EngineTestCase):
    def test_none_is_a_type_error(self):
        with self.assertRaisesRegex(TypeError, "None"):
            mas.sections(None)

    def test_unsupported_type_is_a_type_error(self):
        with self.assertRaisesRegex(TypeError, "int"):
            mas.sections(42)

    def test_face_is_not_a_solid(self):
        e = self.assertRaisesEngineError("not_a_solid", mas.sections, Part.makePlane(10, 10))
        self.assertIn("not a solid", str(e))
        self.assertIn("Face", str(e))

    def test_wire_is_not_a_solid(self):
        wire = Part.makePolygon([V(0, 0, 0), V(10, 0, 0), V(10, 10, 0), V(0, 0, 0)])
        self.assertRaisesEngineError("not_a_solid", mas.sections, wire)

    def test_open_shell_is_not_a_solid(self):
        shell = Part.Shell(box_10_20_30().Faces[:5])
        self.assertRaisesEngineError("not_a_solid", mas.sections, shell)

    def test_compound_of_two_solids_is_rejected(self):
        two = Part.makeCompound([Part.makeBox(1, 1, 1), Part.makeBox(1, 1, 1, V(5, 0, 0))])
        e = self.assertRaisesEngineError("multiple_solids", mas.sections, two)
        self.assertIn("2 solids", str(e))

    def test_faces_beside_the_solid_are_rejected_loose_edges_left_out(self):
        box = box_10_20_30()
        lid = Part.makePlane(10, 20, V(0, 0, 30))
        e = self.assertRaisesEngineError(
            "not_a_solid", mas.centroidal_axis, Part.makeCompound([box, lid])
        )
        self.assertIn("one solid and 1 face outside it", str(e))
        line = Part.makeLine(V(20, 0, 0), V(20, 0, 30))
        s = mas.section(Part.makeCompound([box, line]), (0, 0, 10), (0, 0, 1))
        self.assertAlmostEqual(s.area, 200.0, places=9)

    def test_null_shape_is_empty_input(self):
        self.assertRaisesEngineError("empty_input", mas.sections, Part.Shape())

    def test_open_mesh_is_rejected(self):
        mesh = fc_mesh(box_10_20_30())
        mesh.removeFacets([0])
        e = self.assertRaisesEngineError("open_mesh", mas.sections, mesh)
        self.assertIn("boundary edges", str(e))

    def test_empty_mesh_is_empty_input(self):
        self.assertRaisesEngineError("empty_input", mas.sections, Mesh.Mesh())

    def test_nan_vertex_is_a_non_finite_coordinate(self):
        nan = float("nan")
        with self.assertRaises(mas.EngineError) as cm:
            mas._engine.Mesh.from_arrays([0, 0, 0, 1, 0, 0, 0, nan, 0], [0, 1, 2])
        self.assertEqual(cm.exception.code, "non_finite_coordinate")
        self.assertIn("vertex 2", str(cm.exception))

    def test_malformed_arrays_are_invalid_arguments(self):
        make = mas._engine.Mesh.from_arrays
        self.assertRaisesEngineError("invalid_argument", make, [0, 0], [])
        self.assertRaisesEngineError("invalid_argument", make, [0, 0, 0], [0, 0])
        self.assertRaisesEngineError("invalid_argument", make, [0, 0, 0], [0, 0, 5])
        self.assertRaisesEngineError("invalid_argument", make, ["x", 0, 0], [])

    def test_malformed_topology_is_named(self):
        make = mas._engine.Mesh.from_topology
        nan = float("nan")
        points = [(0, 0, 0), (1, 0, 0), (0, 1, 0)]
        for bad, word in (([(0, 0, 0), (1, 0)], "points[1] is not 3 numbers"),
                          ([(0, 0, 0), "abc"], "points[1] is not 3 numbers"),
                          ([(0, 0, 0), object()], "but 'object'"),
                          ([(0, 0, 0), (1, "y", 0)], "points[1] is not 3 numbers"),
                          (42, "points must be a sequence")):
            e = self.assertRaisesEngineError("invalid_argument", make, bad, [])
            self.assertIn(word, str(e))
        for bad, word in (([(0, 1)], "facets[0] is not 3 vertex indices"),
                          ([(0, 1, 2), 7], "facets[1] is not 3 vertex indices"),
                          ([(0, 1, 3)], "facets[0][2] = 3 is not a vertex index (there are 3"),
                          ([(0, -1, 2)], "facets[0][1] = -1"),
                          ([(0, 1.5, 2)], "facets[0][1] is not an integer but 'float'")):
            e = self.assertRaisesEngineError("invalid_argument", make, points, bad)
            self.assertIn(word, str(e))
        e = self.assertRaisesEngineError("non_finite_coordinate", make,
                                         points + [V(0, nan, 0)], [(0, 1, 3)])
        self.assertIn("vertex 3", str(e))

    def test_bad_step_is_a_value_error(self):
        for step in (0, -1.0, float("nan"), float("inf")):
            with self.assertRaisesRegex(ValueError, "step"):
                mas.sections(box_10_20_30(), step=step)
        with self.assertRaisesRegex(TypeError, "step"):
            mas.sections(box_10_20_30(), step="1")

    def test_bad_normal_is_a_value_or_type_error(self):
        with self.assertRaisesRegex(ValueError, "zero vector"):
            mas.sections(box_10_20_30(), normal=(0, 0, 0))
        with self.assertRaisesRegex(ValueError, "NaN"):
            mas.sections(box_10_20_30(), normal=(0, float("nan"), 1))
        with self.assertRaisesRegex(TypeError, "normal"):
            mas.sections(box_10_20_30(), normal=(0, 1))
        with self.assertRaisesRegex(ValueError, "origin"):
            mas.section(box_10_20_30(), origin=(0, 0, float("nan")), normal=(0, 0, 1))

    def test_bad_deflection_is_a_value_error(self):
        with self.assertRaisesRegex(ValueError, "deflection"):
            mas.sections(box_10_20_30(), deflection=-0.1)

    def test_empty_inputs_read_as_they_are(self):
        # They read "the shape: the shape is empty" and "': no such file".
        self.assertEqual(str(self.assertRaisesEngineError("empty_input", mas.sections,
                                                          Part.Shape())), "the shape is empty")
        self.assertEqual(str(self.assertRaisesEngineError("read_failed", mas.sections, "")),
                         "no file name given (an empty path)")

    def test_a_normal_whose_length_overflows_is_still_a_direction(self):
        # (1e300, 1e300, 1e300) came out of parallel_planes() as the zero vector, and sections()
        # called it one.
        box = box_10_20_30()
        for origin, normal in mas.parallel_planes(box, normal=(1e300, 1e300, 1e300), step=10.0):
            for c in normal:
                self.assertAlmostEqual(c, 1 / math.sqrt(3), places=15)
        along = mas.sections(box, normal=(1e300, 1e300, 1e300), step=10.0)
        diagonal = mas.sections(box, normal=(1, 1, 1), step=10.0)
        self.assertEqual([s.area for s in along], [s.area for s in diagonal])

    def test_engine_checks_planes_too(self):
        mesh = mas.to_engine_mesh(box_10_20_30())
        planes = mas._engine.parallel_planes
        self.assertRaisesEngineError("invalid_argument", planes, mesh, (0, 0, 0), 1.0)
        self.assertRaisesEngineError("invalid_argument", planes, mesh, (0, 0, 1), 0.0)
        self.assertRaisesEngineError("invalid_argument", mas._engine.slice, mesh,
                                     [((0, 0, float("nan")), (0, 0, 1))])

    def test_sections_that_would_hold_too_many_points_are_refused_before_cutting(self):
        # A 10 x 20 x 30 box of 12 facets, cut every 10 mm: each plane crosses 8 facets, 24 loop
        # points in all, counted without cutting.
        box = box_10_20_30()
        mesh = mas.to_engine_mesh(box)
        planes = mas._engine.parallel_planes(mesh, (0, 0, 1), 10.0)
        self.assertEqual(mas._engine.section_point_counts(mesh, planes), [8, 8, 8])
        self.assertEqual(len(mas._parallel_sections(box, (0, 0, 1), 10.0, None, None, 24,
                                                    "a test keeps")), 3)
        with self.assertRaises(mas.EngineError) as caught:
            mas._parallel_sections(box, (0, 0, 1), 10.0, None, None, 23, "a test keeps")
        self.assertEqual(caught.exception.code, "invalid_argument")
        self.assertEqual(str(caught.exception),
                         "step 10 mm is too small for this part: its 3 sections would hold 24 loop "
                         "points, more than the 23 a test keeps; use a larger step")
        # sections() keeps MAX_SECTION_POINTS: a 1 mm disc of 20 mm cut every 0.01 um would
        # hold some 100 million, refused at once, not after gigabytes.
        disc = Part.makeCylinder(10, 1)
        with self.assertRaises(mas.EngineError) as caught:
            mas.sections(disc, step=1e-5, deflection=0.001)
        self.assertRegex(str(caught.exception),
                         r"^step 1e-05 mm is too small for this part: its 100000 sections would "
                         r"hold \d+ loop points, more than the 10000000 sections\(\) keeps; use a "
                         r"larger step$")

    def test_files_the_engine_cannot_read(self):
        self.assertRaisesEngineError("read_failed", mas.sections, "/nonexistent/part.step")
        folder = tempfile.mkdtemp(prefix="mas_api_")
        try:
            path = os.path.join(folder, "part.xyz")
            with open(path, "w") as f:
                f.write("1 2 3\n")
            self.assertRaisesEngineError("unsupported_format", mas.sections, path)
            # A damaged STEP file (an entity a vertex refers to is missing) crashed FreeCAD in
            # OCCT's translator; FreeCAD goes on, and so does the engine.
            path = os.path.join(folder, "damaged.step")
            box = Part.makeBox(10, 20, 30)
            box.exportStep(path)
            with open(path) as f:
                lines = f.read().split("\n")
            point = next(i for i, line in enumerate(lines) if "CARTESIAN_POINT" in line
                         and "(10.,0.,0.)" in line)
            with open(path, "w") as f:
                f.write("\n".join(lines[:point] + lines[point + 1:]))
            self.assertRaisesEngineError("empty_input", mas.sections, path)
            self.assertEqual(len(mas.sections(box, step=10.0)), 3)
        finally:
            shutil.rmtree(folder)

    def test_exact_sections_need_a_solid(self):
        with self.assertRaisesRegex(TypeError, "mesh"):
            mas.exact_sections(fc_mesh(box_10_20_30()), [((0, 0, 10), (0, 0, 1))])
        with self.assertRaisesRegex(TypeError, "pair"):
            mas.exact_sections(box_10_20_30(), [(0, 0, 10)])


class TestSourceIsNeverModified(support.EngineTestCase):
    def test_shapes_are_unchanged(self):
        for shape in (box_10_20_30(), Part.makeCylinder(5, 10), Part.makePlane(10, 10)):
            shape.Placement = FreeCAD.Placement(V(1, 2, 3), FreeCAD.Rotation(V(1, 1, 0), 30))
            before = shape.exportBrepToString()
            matrix = shape.Placement.toMatrix().A
            try:
                mas.sections(shape, normal=(1, 0, 1), step=2.0)
                mas.deflection(shape)
                mas.exact_sections(shape, [((0, 0, 5), (0, 0, 1))])
            except mas.EngineError:
                pass  # the plane: not a solid
            self.assertEqual(shape.exportBrepToString(), before)
            self.assertEqual(shape.Placement.toMatrix().A, matrix)

    def test_meshes_are_unchanged(self):
        mesh = fc_mesh(box_10_20_30())
        before = mesh.Topology
        mas.sections(mesh, step=3.0)
        self.assertEqual(mesh.Topology, before)


class TestWithoutFreeCAD(support.EngineTestCase):
    """The package in a plain Python 3.11 script: with the engine (tuples instead of vectors) and
    without it (importing works, the functions name the build command)."""

    def test_plain_python_uses_tuples(self):
        with support.scratch_folder("mas_plain_") as folder:
            result = support.run_plain_python(folder, """
            import sys
            assert "FreeCAD" not in sys.modules
            import MultiAxisSlicer as mas
            v = [0,0,0, 1,0,0, 1,1,0, 0,1,0, 0,0,1, 1,0,1, 1,1,1, 0,1,1]
            t = [0,2,1, 0,3,2, 4,5,6, 4,6,7, 0,1,5, 0,5,4, 1,2,6, 1,6,5, 2,3,7, 2,7,6, 3,0,4, 3,4,7]
            [s] = mas.sections(mas._engine.Mesh.from_arrays(v, t), step=1.0)
            print("RESULT", s.area, s.centroid, type(s.centroid).__name__)
            """)
        self.assertEqual(result.returncode, 0, result.stderr)
        self.assertIn("RESULT 1.0 (0.5, 0.5, 0.5) tuple", result.stdout)

    def test_missing_engine_names_the_build_command(self):
        folder = tempfile.mkdtemp(prefix="mas_noengine_")
        try:
            package = os.path.join(folder, "MultiAxisSlicer")
            os.mkdir(package)
            for name in os.listdir(os.path.dirname(mas.__file__)):
                if name.endswith(".py"):
                    shutil.copy(os.path.join(os.path.dirname(mas.__file__), name), package)
            result = support.run_plain_python(folder, """
                import MultiAxisSlicer as mas
                assert not mas.engine_available()
                try:
                    mas.sections("part.step")
                except mas.EngineUnavailableError as e:
                    print("MESSAGE", e)
            """, path_entry=folder)
        finally:
            shutil.rmtree(folder)
        self.assertEqual(result.returncode, 0, result.stderr)
        self.assertIn("MESSAGE", result.stdout)
        self.assertIn("./tools/setup.sh install", result.stdout)
        self.assertIn("_engine", result.stdout)


class TestSectionsObject(support.EngineTestCase):
    def setUp(self):
        self.doc = FreeCAD.newDocument("MasSections")
        self.box = self.doc.addObject("Part::Box", "Box")
        self.box.Length, self.box.Width, self.box.Height = 10, 20, 30
        self.doc.recompute()
        self.folder = tempfile.mkdtemp(prefix="mas_doc_")

    def tearDown(self):
        for name in list(FreeCAD.listDocuments()):
            if name.startswith("MasSections"):
                FreeCAD.closeDocument(name)
        shutil.rmtree(self.folder)

    def check_box_sections(self, obj, count):
        self.assertTrue(obj.isValid(), obj.getStatusString())
        self.assertEqual(obj.SectionCount, count)
        self.assertAlmostEqual(obj.TotalArea.Value, 200.0 * count, places=6)
        self.assertEqual(len(obj.Shape.Wires), count)
        for wire in obj.Shape.Wires:
            self.assertTrue(wire.isClosed())
        self.assertEqual(obj.Shape.Faces, [])
        self.assertEqual(obj.Shape.Solids, [])
        bb = obj.Shape.BoundBox
        self.assertAlmostEqual(bb.XLength, 10.0, places=9)
        self.assertAlmostEqual(bb.YLength, 20.0, places=9)

    def test_recompute_cuts_the_source(self):
        obj = mas.make_sections(self.box)
        self.assertEqual(obj.Step.Value, 5.0)
        self.assertEqual(obj.Deflection.Value, 0.0)
        self.assertEqual(obj.Normal, V(0, 0, 1))
        self.doc.recompute()
        self.check_box_sections(obj, 6)
        self.assertAlmostEqual(obj.Shape.BoundBox.ZMin, 2.5, places=9)
        self.assertAlmostEqual(obj.Shape.BoundBox.ZMax, 27.5, places=9)

    def test_changing_a_property_recomputes(self):
        obj = mas.make_sections(self.box)
        self.doc.recompute()
        obj.Step = 10.0
        self.doc.recompute()
        self.check_box_sections(obj, 3)
        obj.Normal = V(1, 0, 0)  # the box is 10 mm long in x: one 10 mm slab
        self.doc.recompute()
        self.assertEqual(obj.SectionCount, 1)
        self.assertAlmostEqual(obj.TotalArea.Value, 600.0, places=6)
        self.assertAlmostEqual(obj.Shape.BoundBox.XMin, 5.0, places=9)

    def test_source_is_not_modified(self):
        before = self.box.Shape.exportBrepToString()
        obj = mas.make_sections(self.box)
        self.doc.recompute()
        self.assertTrue(obj.isValid())
        self.assertEqual(self.box.Shape.exportBrepToString(), before)
        self.assertNotIn("Touched", self.box.State)
        self.assertEqual(self.box.InList, [obj])

    def test_mesh_source(self):
        mesh = self.doc.addObject("Mesh::Feature", "Mesh")
        mesh.Mesh = fc_mesh(Part.makeBox(10, 20, 30))
        obj = mas.make_sections(mesh, step=10.0)
        self.doc.recompute()
        self.check_box_sections(obj, 3)

    def test_bad_arguments_add_nothing(self):
        names = [o.Name for o in self.doc.Objects]
        for kwargs in (dict(normal=(0, 0, 0)), dict(step=-1.0), dict(step=float("nan")),
                       dict(deflection=-1.0)):
            with self.assertRaises(ValueError, msg=kwargs):
                mas.make_sections(self.box, **kwargs)
        # A shape, a file name or a class where the document object belongs (AttributeError:
        # 'str' object has no attribute 'Document', a traceback from inside the function).
        for make in (mas.make_sections, mas.make_centroidal_axis, mas.make_decomposition):
            for source, kind in ((self.box.Shape, "Solid"), ("box.step", "str"),
                                 (Part.Shape, "type")):
                with self.assertRaises(TypeError) as caught:
                    make(source)
                self.assertEqual(
                    str(caught.exception),
                    "{}() needs a document object as its source (a Part or Mesh object; "
                    "MultiAxisSlicer's functions take shapes, meshes and files), got {}".format(
                        make.__name__, kind))
        self.assertEqual([o.Name for o in self.doc.Objects], names)

    def test_save_close_reopen_recompute(self):
        obj = mas.make_sections(self.box, normal=(0, 0, 1), step=10.0, deflection=0.02)
        self.doc.recompute()
        path = os.path.join(self.folder, "sections.FCStd")
        self.doc.saveAs(path)
        FreeCAD.closeDocument(self.doc.Name)

        doc = FreeCAD.openDocument(path)
        obj = doc.getObject("Sections")
        self.assertIsNotNone(obj)
        self.assertIsInstance(obj.Proxy, features.SectionsFeature)
        self.assertIs(obj.Source, doc.getObject("Box"))
        self.assertEqual(obj.Step.Value, 10.0)
        self.assertEqual(obj.Deflection.Value, 0.02)
        self.assertEqual(obj.SectionCount, 3)
        self.assertEqual(len(obj.Shape.Wires), 3)  # the shape is saved with the document
        obj.touch()
        doc.recompute()
        self.check_box_sections(obj, 3)
        obj.Step = 5.0
        doc.recompute()
        self.check_box_sections(obj, 6)
        doc.save()  # saving a restored proxy works too

    def test_undo_removes_the_object(self):
        self.doc.UndoMode = 1
        self.doc.openTransaction("Cross-sections")
        obj = mas.make_sections(self.box)
        self.doc.recompute()
        self.doc.commitTransaction()
        name = obj.Name
        self.assertIsNotNone(self.doc.getObject(name))
        self.doc.undo()
        self.assertIsNone(self.doc.getObject(name))
        self.assertIsNotNone(self.doc.getObject("Box"))
        self.doc.redo()
        self.assertIsNotNone(self.doc.getObject(name))

    def test_failing_recompute_marks_the_object_with_the_engine_message(self):
        face = self.doc.addObject("Part::Feature", "Face")
        face.Shape = Part.makePlane(10, 10)
        obj = mas.make_sections(face)
        self.doc.recompute()
        self.assertIn("Invalid", obj.State)
        self.assertFalse(obj.isValid())
        self.assertIn("not a solid", obj.getStatusString())
        self.assertIn("Face", obj.getStatusString())
        # FreeCAD keeps running and the object recovers once its input is fixed.
        obj.Source = self.box
        self.doc.recompute()
        self.check_box_sections(obj, 6)

    def test_bad_parameter_marks_the_object(self):
        obj = mas.make_sections(self.box)
        obj.Normal = V(0, 0, 0)
        self.doc.recompute()
        self.assertIn("Invalid", obj.State)
        self.assertIn("zero vector", obj.getStatusString())

    def test_a_step_too_fine_to_draw_marks_the_object(self):
        """A Sections object draws at most MAX_DRAWN_SECTION_POINTS loop points (some 2 GB):
        every 0.2 um through a 10 mm cylinder is refused before anything is cut."""
        cylinder = self.doc.addObject("Part::Feature", "Cylinder")
        cylinder.Shape = Part.makeCylinder(10, 10)
        obj = mas.make_sections(cylinder, step=2e-4)
        self.doc.recompute()
        self.assertIn("Invalid", obj.State)
        self.assertRegex(obj.getStatusString(),
                         r"Step 0.0002 mm is too small for this part: its 50000 sections would "
                         r"hold \d+ loop points, more than the 2000000 a Sections object draws; "
                         r"use a larger Step")
        obj.Step = 0.5
        self.doc.recompute()
        self.assertTrue(obj.isValid(), obj.getStatusString())
        self.assertEqual(obj.SectionCount, 20)

    def test_missing_source_marks_the_object(self):
        obj = mas.make_sections(self.box)
        obj.Source = None
        self.doc.recompute()
        self.assertIn("Invalid", obj.State)
        self.assertIn("Source is not set", obj.getStatusString())
        # Named once ("Sections: Sections: Source is not set" before).
        import MultiAxisSlicer.features as features
        self.assertEqual(features.failure(obj), "Sections: Source is not set")

    def test_failing_recompute_prints_the_message_without_a_traceback(self):
        script = support.write_dedented(self.folder, "fail.py", """
            import FreeCAD, Part
            import MultiAxisSlicer as mas
            doc = FreeCAD.newDocument("Fail")
            face = doc.addObject("Part::Feature", "Face")
            face.Shape = Part.makePlane(10, 10)
            obj = mas.make_sections(face)
            doc.recompute()
            print("STATE", obj.State)
        """)
        result = subprocess.run(["freecadcmd", script], capture_output=True, text=True, timeout=120)
        output = result.stdout + result.stderr
        self.assertIn("STATE ['Invalid']", output.replace("'Touched', ", ""))
        self.assertIn("not a solid", output)
        self.assertNotIn("Traceback", output)


if __name__ == "__main__":
    unittest.main()
