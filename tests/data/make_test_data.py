# Regenerates the CAD fixtures in tests/data (run from the repository root):
#   freecadcmd tests/data/make_test_data.py
# box_10x20x30.step   box [0,10]x[0,20]x[0,30]
# l_block.brep        paper Fig. 7: column [0,20]x[0,20]x[0,60] + arm [20,70]x[0,20]x[40,60]
# l_block.iges        the same
# cylinder_r10_h40.stp  cylinder of radius 10, height 40 on the XY plane, axis Z through (0,0)
# two_boxes.step       see the end of this file
import os

import FreeCAD
import Part

here = os.path.join(os.getcwd(), "tests", "data")
V = FreeCAD.Vector

Part.makeBox(10, 20, 30).exportStep(os.path.join(here, "box_10x20x30.step"))
l_block = Part.makeBox(20, 20, 60).fuse(Part.makeBox(50, 20, 20, V(20, 0, 40))).removeSplitter()
l_block = l_block.Solids[0]
l_block.exportBrep(os.path.join(here, "l_block.brep"))
l_block.exportIges(os.path.join(here, "l_block.iges"))
Part.makeCylinder(10, 40).exportStep(os.path.join(here, "cylinder_r10_h40.stp"))
print("test data written to", here)

# two_boxes.step       two separate boxes in one file (several solids where one is expected)
two = Part.makeCompound([Part.makeBox(10, 10, 10), Part.makeBox(10, 10, 10, V(20, 0, 0))])
two.exportStep(os.path.join(here, "two_boxes.step"))

# faulty_elbow.step     a hollow pipe elbow whose inner tube starts 0.5 mm off the inner torus:
# a valid OCCT solid whose tessellation by BRepMesh is not closed (a bad-input case)
path_r = 40
outer = Part.makeTorus(path_r, 10, V(0, 0, 0), V(0, 1, 0), 0, 360, 90)
outer = Part.makeCylinder(10, 40, V(path_r, 0, -40), V(0, 0, 1)).fuse(outer)
outer = outer.fuse(Part.makeCylinder(10, 40, V(0, 0, path_r), V(-1, 0, 0)))
inner = Part.makeTorus(path_r, 7, V(0, 0, 0), V(0, 1, 0), 0, 360, 90)
inner = inner.fuse(Part.makeCylinder(7, 41, V(path_r, 0, -40.5), V(0, 0, 1)))
inner = inner.fuse(Part.makeCylinder(7, 41, V(0.5, 0, path_r), V(-1, 0, 0)))
outer.cut(inner).removeSplitter().exportStep(os.path.join(here, "faulty_elbow.step"))

# coil_c0.step          a tube swept along two turns of a helix (radius 20, pitch 15) with a tilted
# circle, on a pad: its surfaces are only C0, which OCCT's Booleans do not promise to split
# soundly; a split piece may pass OCCT's check and still mesh with non-manifold edges
helix = Part.makeHelix(15, 30, 20)
profile = Part.Wire(Part.makeCircle(3, V(20, 0, 0), V(0, 1, 0.2387)))
coil = Part.Wire(helix).makePipeShell([profile], True, True)
coil = coil.fuse(Part.makeCylinder(6, 3, V(20, 0, -3))).removeSplitter()
coil.Solids[0].exportStep(os.path.join(here, "coil_c0.step"))

# pins_on_column.step   a column of radius 8 with two pins of radius 2.5 reaching 30 mm out of it:
# one level at z = 32 towards 190 degrees, one rising 35 degrees at z = 48.5 towards 242.5
# degrees. A valid solid whose fused cylinders' edges have curves off their faces (FreeCAD's Check
# geometry: BOPAlgo_InvalidCurveOnSurface); a split of it passed OCCT's shape check and meshed
# with an edge shared by three triangles
import math


def pin(z, azimuth, elevation):
    a, e = math.radians(azimuth), math.radians(elevation)
    return Part.makeCylinder(2.5, 30, V(0, 0, z),
                             V(math.cos(a) * math.cos(e), math.sin(a) * math.cos(e), math.sin(e)))


pins = Part.makeCylinder(8, 80).fuse([pin(32, 190, 0), pin(48.5, 242.5, 35)]).removeSplitter()
pins.Solids[0].exportStep(os.path.join(here, "pins_on_column.step"))

# pipe_cross.step       a hollow four-way pipe cross (outer radius 14, bore 10) along +-X and +-Z,
# moved 250 mm down before its seams are removed, then put back on z = 0: OCCT cannot split it at
# its side arms, and its failed attempts used to alter the father they were given (the root then
# failed OCCT's shape check, and slicing stopped)
arms, bores = [], []
for d in (V(1, 0, 0), V(-1, 0, 0), V(0, 0, 1), V(0, 0, -1)):
    length = 60 if d.z < 0 else 55
    arms.append(Part.makeCylinder(14, length, V(0, 0, 60), d))
    bores.append(Part.makeCylinder(10, length + 2, V(0, 0, 60) - d, d))
cross = arms[0]
for arm in arms[1:]:
    cross = cross.fuse(arm)
cross = cross.removeSplitter()
for bore in bores:
    cross = cross.cut(bore)
cross.translate(V(0, 0, -250))
cross = cross.removeSplitter()
cross.translate(V(0, 0, -cross.BoundBox.ZMin))
cross.exportStep(os.path.join(here, "pipe_cross.step"))

# arm_collar.brep   a column [-15,15]^2 x [0,60] with an arm [15,55] x [-8,8] x [32,48] ending in
# a collar [49,54] x [-12,12] x [28,52]: the collar's share under the arm hangs (not built down)
collar = Part.makeBox(30, 30, 60, V(-15, -15, 0)).fuse(Part.makeBox(40, 16, 16, V(15, -8, 32)))
collar = collar.fuse(Part.makeBox(5, 24, 24, V(49, -12, 28))).removeSplitter()
collar.Solids[0].exportBrep(os.path.join(here, "arm_collar.brep"))

# bend_on_side.step   a hollow pipe on a flange lying on its side: flange radius 24, 8 thick, bore
# radius 7; a tube (outer radius 10) to 28 mm; a 135-degree bend of radius 30 towards +X; then
# turned 90 degrees about X and put on z = 0. A sound solid (FreeCAD's Check geometry passes), but
# its split across the bend came out of OCCT's splitter with a C0 edge off its face, which passed
# the shape check and meshed with an edge shared by three triangles: slicing stopped there
bend_face = Part.Face(Part.Wire(Part.makeCircle(10, V(0, 0, 28), V(0, 0, 1))))
bend_face = bend_face.cut(Part.Face(Part.Wire(Part.makeCircle(7, V(0, 0, 28), V(0, 0, 1))))).Faces[0]
bend = Part.makeCylinder(24, 8).cut(Part.makeCylinder(7, 10, V(0, 0, -1)))
stem = Part.makeCylinder(10, 20, V(0, 0, 8)).cut(Part.makeCylinder(7, 22, V(0, 0, 7)))
bend = bend.fuse(stem).fuse(bend_face.revolve(V(30, 0, 28), V(0, 1, 0), 135)).Solids[0]
bend.rotate(V(0, 0, 0), V(1, 0, 0), 90)
bend.translate(V(0, 0, -bend.BoundBox.ZMin))
bend.exportStep(os.path.join(here, "bend_on_side.step"))

# hub_twisted_blades.brep  the survey's hub with blades 6 (tests/python/MultiAxisSlicerSurvey.py,
# seed 39): a hub of radius 9.37 mm, 32.3 tall, with six blades 3.06 mm thick and 13.74 wide
# twisted 30 degrees; a plane grazing one blade's tip made its derived step 0.056 mm
import sys  # noqa: E402

sys.path.insert(0, os.path.join(os.getcwd(), "tests", "python"))
import MultiAxisSlicerSurvey  # noqa: E402

hub, _ = MultiAxisSlicerSurvey.part("hub with blades", 6, 39)
hub.exportBrep(os.path.join(here, "hub_twisted_blades.brep"))

# hub_four_blades.brep  the survey's hub with blades 5 (seed 65): a hub of radius 13.5, 23.3 tall,
# with four flat blades 4.78 thick and 12.4 tall at 1.3, 98.6, 188.4 and 272.5 degrees; at its
# deflection a sliver of the hub's outline joined two of them into one stick-out
hub4, _ = MultiAxisSlicerSurvey.part("hub with blades", 5, 65)
hub4.exportBrep(os.path.join(here, "hub_four_blades.brep"))

# hub_blades_graze.brep  the survey's hub with blades 0 (seed 283): a hub of radius 8.02, 36.6
# tall, with a bore and six blades 5.59 thick and 27.8 wide twisted 30 degrees; planes near the
# blades' corners cut strips 0.08 to 0.92 mm wide which the blades only taper or widen from, and
# taken for walls they made its derived step 0.05 mm
hub6, _ = MultiAxisSlicerSurvey.part("hub with blades", 0, 283)
hub6.exportBrep(os.path.join(here, "hub_blades_graze.brep"))

# cylinder_meshed_off.brep  a cylinder of radius 8, 20 tall, as Part's Refine shape left it after
# fusing it with a 45-degree revolve of its top disc about a line beside it (which adds nothing):
# one valid solid (OCCT's shape check passes) whose side, seamed by a B-spline, with its top and
# bottom circles split at different places, OCCT meshes into about a third of its 4021 mm^3, at
# any deflection
disc = Part.Face(Part.Wire(Part.makeCircle(8, V(0, 0, 20))))
odd = Part.makeCylinder(8, 20).fuse(disc.revolve(V(30, 0, 20), V(0, 1, 0), -45)).removeSplitter()
odd.exportBrep(os.path.join(here, "cylinder_meshed_off.brep"))

# hub_blade_near_plate.brep  the survey's hub with blades 3 (seed 84): a hub of radius 11.09, 23.0
# tall, bored, with five blades 3.05 mm thick and 16.96 wide twisted 30 degrees; built along its
# own line, one blade's layers met the build plate, and every turned cut was made square
hub5, _ = MultiAxisSlicerSurvey.part("hub with blades", 3, 84)
hub5.exportBrep(os.path.join(here, "hub_blade_near_plate.brep"))

# pipe_bend_classifier.brep  the survey's pipe bend 3 (seed 198): hollow, radius 10.15 with a 7.01
# bore, a 27.24 mm bend: OCCT's solid classifier calls the point (16.5924, 8.51982, 65.7732), 1.5 mm
# inside the bend's wall, out (and the points 0.5 mm either side of it along Y in)
bend, _ = MultiAxisSlicerSurvey.part("pipe bend", 3, 198)
bend.exportBrep(os.path.join(here, "pipe_bend_classifier.brep"))

# chair_back_jump.brep  the survey's chair 1 (seed 2): four legs 7.40 square and 31.99 tall under
# a top 33.24 x 36.02 x 5.96, a back 3.44 thick and 24.69 tall standing on the top's far edge,
# turned a quarter about Z. The top is a bridge built along its diagonal; the back's sections
# follow the top's along Z, their centroid 16.3 mm across the top, and layers turning after that
# jump laid the back from its side
chair, _ = MultiAxisSlicerSurvey.part("chair", 1, 2)
chair.exportBrep(os.path.join(here, "chair_back_jump.brep"))

# truss_braced_beam.brep  the survey's braced frame 4 (seed 3), across Y: two posts 8.47 square
# 26.21 apart on a plate, a beam 8.47 square across their tops (underside z = 61.08) and a round
# brace 2.83 in radius from low on one post to the other's top (59.4 degrees). The brace joins the
# posts' tracks under the beam, and the axis crosses the beam sideways from one post's top: no
# merged tracks, so no bridge, and built along the beam its last layers met the other post
truss, _ = MultiAxisSlicerSurvey.part("truss", 4, 3)
truss.exportBrep(os.path.join(here, "truss_braced_beam.brep"))

# truss_beam_off_brace.brep  the survey's braced frame 6 (seed 2), across X: two posts 9.56 square
# 26.15 apart on a plate, a beam 9.56 square across their tops (underside z = 40.28) and a round
# brace 2.88 in radius from low on one post to the other's top (42.4 degrees). The axis reaches
# the beam along the brace and marches up through it along Z from over the gap: built on its own
# along Z its first layer hung, and kept in the posts' layers it hung 201 mm^2
truss, _ = MultiAxisSlicerSurvey.part("truss", 6, 2)
truss.exportBrep(os.path.join(here, "truss_beam_off_brace.brep"))

# truss_crossed_braces.brep  the survey's braced frame 7 (seed 2), across X: two posts 9.85
# square 49.33 apart on a plate, a beam 9.85 square across their tops (underside z = 51.49) and
# two round braces crossing under it, each from low on one post to the other's top. The beam is
# cut off at its underside and built along Z: its first layer hung 441 mm^2 between the posts
truss, _ = MultiAxisSlicerSurvey.part("truss", 7, 2)
truss.exportBrep(os.path.join(here, "truss_crossed_braces.brep"))

# truss_brace_under_beam.brep  the survey's braced frame 6 (seed 3), across X: two posts 7.84
# square 44.17 apart on a plate, a beam 7.84 square across their tops (underside z = 33.13) and a
# round brace from low on one post to the other's top (23.7 degrees). The axis marches the brace
# along X into the far post and rises into the beam from the brace: the beam, cut off at its
# underside and built along Z off the brace's component, hung 305 mm^2 in its first layer
truss, _ = MultiAxisSlicerSurvey.part("truss", 6, 3)
truss.exportBrep(os.path.join(here, "truss_brace_under_beam.brep"))

# truss_shallow_brace.brep  the survey's braced frame 5 (seed 323), across X: two posts 8.65 wide
# 36.27 apart on a plate, a beam across their tops (underside z = 34.19) and a round brace from
# low on one post to the other's top (28.2 degrees). The beam, cut off at its underside and built
# along Z, hung 138 mm^2 in its first layer, and slicing kept it in the posts' layers
truss, _ = MultiAxisSlicerSurvey.part("truss", 5, 323)
truss.exportBrep(os.path.join(here, "truss_shallow_brace.brep"))

# crank_returning_leg.brep  the survey's crank 3 (seed 4): a riser 6.56 square on a plate 26.24
# square and 3 thick, then legs 6.56 square at z 26.47 to 33.03 along +X (to x = 27.17), +Y (to
# y = 19.92) and -X back beside the first, its end (x = -4.79) past the riser, 10.08 from it. The
# axis marched the first leg and the last one's section beside it along +X from the riser's face,
# the last leg's end behind that face stayed in the riser, every split was refused as leaving the
# riser in pieces, and the legs, in the riser's Z layers, hung 410 mm^2 in one
crank, _ = MultiAxisSlicerSurvey.part("crank", 3, 4)
crank.exportBrep(os.path.join(here, "crank_returning_leg.brep"))

# truss_beam_unreached.brep  the survey's braced frame 1 (seed 403), across X: two posts 9.26
# square 23.39 apart on a plate, a beam 9.26 square across their tops (underside z = 56.59) and
# two round braces 2.38 in radius crossing under it, each from low on one post to just under the
# other's top, clear of the beam. At the derived step the march went up a brace, down the other
# into the far post and along X through both posts and the beam over them from inside; the beam's
# middle, between them, was never reached, and the axis was refused (89 % of the part swept)
truss, _ = MultiAxisSlicerSurvey.part("truss", 1, 403)
truss.exportBrep(os.path.join(here, "truss_beam_unreached.brep"))
