// Decomposition (paper Sec. 4.1): the part split into a tree of sub-components where its centroidal
// axis turns or branches, each with the base face it is built from and its build direction.
//
// Reading of the paper chosen here (each tested in tests/engine/test_decompose.cpp). It makes
// every sub-component buildable from its base face along its direction, with no unsupported
// overhang at the junction:
// - Axis branches are walked in tree order (a father branch first). Every non-root branch b
//   (turned, C1 break, or born of a split) asks for a cut between its father and itself. D is b's
//   march direction (axis-aligned), not the raw link vector: for a split the link is a sideways
//   connector between two centroids, and a cut perpendicular to D is what lets the child be built
//   along D on top of the father. Pos_start is the start of b's first link (the father's node),
//   Pos_end b's first node.
// - Candidate splitting faces, on the CURRENT father solid: planar faces (1) whose normal is within
//   face_angle_deg of +-D (the paper says L_pre; D is read instead, for the reason above), (2)
//   with a concave edge on their boundary (interior angle over 180 + concave_angle_deg degrees,
//   from the two faces' normals at the edge's midpoint), (3) meeting Eq. 5 along D: the outer
//   wire's Proj_min or Proj_max along D lies in [D.Pos_start, D.Pos_end] (+- projection_tolerance),
//   or, for a face whose outward normal points along +D (one the child can leave from), in
//   that span widened to take in the father's nodes from Pos_start's back along its march, each
//   reaching along D no further than the next one's (+- the tolerance), up to the first that
//   stops shrinking away from b once they have begun to: the father's sections beside b
//   can hold the near end of b's own material, which Eq. 4 left to the father, and their
//   centroids, Pos_start among them, then lie past the face b leaves from. A gusset under an
//   arm: the column's sections reach out to the web's tip, less far at each plane down the web,
//   and the column's face x = 20 lies behind their centroids (x = 21.4 beside the arm); cut past
//   the tip, the arm's underside beside the web overhung the column's layers. The walk stops
//   where a section reaches further than the next one (the father bulging towards b), and at a
//   section across D (past Pos_start's): where the father marches along D itself (two arms
//   forking out of a column's march, each born of a split along the column's direction), its
//   sections below lie under b, the trunk both arms stand on, not beside it. Walked down to the
//   plate's top, one arm took the whole stem, whose layers then tilted towards that arm and left
//   the other's root overhanging (257 mm^2 on a 45-degree Y): cut where the sections part, the
//   trunk stays in its father's layers. A face
//   facing away from b (a pocket's floor on the far side of a column leaning towards b, which
//   the walk reaches all the way down) would cut the father through;
//   and lying over the branch: seen along D, the face's box meets the branch's first section grown
//   by a step (else a face of another feature, parallel to D, may cut through the father).
//   The one whose plane lies nearest the junction (b's first plane minus half a step) wins;
//   where the walk found the father's own section (a gusset), the one nearest that section's
//   reach along D: b's march starts past the web's tip, and a face of the arm on the way (a
//   post's, a step's on its top) cut it partway, the stub over the web left in the father.
// - The father is split by the chosen face's whole plane. The child is the piece containing
//   Pos_end, on the +D side; every other piece goes back into the father (fused, seams removed).
//   "Containing Pos_end" is read with a point in the material of b's first section
//   (interior_point()), also when finding the father: a pipe's first section is a ring whose
//   centroid lies in the bore, in no solid. Each component is a solid OCCT's shape check accepts:
//   the piece with its seams removed, else as the split left it, else as ShapeFix makes it. On a
//   part with C0 faces or edges, or with edges whose curves stray off their faces (FreeCAD's
//   Check geometry: BOPAlgo_InvalidCurveOnSurface, common where cylinders were fused), which
//   OCCT's Booleans do not promise to split soundly, it must also mesh closed at the part's
//   default deflection (what slicing uses). So must a piece of a sound part that the split itself
//   left with such an edge or face (a pipe bend lying on its side, cut across the bend: a C0 edge
//   off its face, which the shape check passed and the mesh shared among three triangles).
//   (Meshing every piece of every part would add a quarter to the time of slicing some.) Once
//   every branch is handled, every child must mesh closed there too, whatever the part: a sound
//   part's split can still leave one that does not (a fork of two pipes off a riser, cut just
//   where one pipe's side touches the riser's: a 0.27 mm edge the mesh shared among four
//   triangles). Its branch is then kept in its father, with a note, and the pass done again.
//   (The children are meshed side by side: 15 % more time on a plate with 36 posts.)
//   The child's base face is its face on the plane under Pos_end (the largest one when none is:
//   a plane cuts a half ring standing on its rim in two faces, one at each end); build_direction
//   = minus its outward normal (Sec. 4.2.1), i.e. D for an exactly perpendicular face. The
//   L-block, seen along Y:
//
//          z ^   +------:-------------+
//            |   |      :    child    |   D = +X. The column's face x = 20 has normal +X (1),
//            |   |  o---:-->o  (arm)  |   a concave edge c with the arm's underside (2), and
//            |   |      c-------------+   Eq. 5 holds: 20 in [10, 20.001] (3). The plane x = 20
//            |   | root |                 (dotted) cuts; the arm's base face lies on it, outward
//            |   |      |                 normal -X: built along +X, on the column's side.
//            |   +------+                 o: Pos_start (column node), Pos_end (arm's 1st node)
//            +------------------> x
//
// - The piece stays in the father, with a note saying why, when it
//   - reaches less than one axis step (or min_component_height) past the plane: a sliver cut off
//     the father's end where its march found the split on its last plane (a hub's crown between
//     two blades), thinner than the axis can resolve and than a layer; the father builds it on
//     top. A branch that turned from its father's direction was found by how far its share
//     reaches out of the section it leaves, however thin along its own direction: its piece
//     need only reach a thickest layer at slicing's defaults (2 mm, whatever max_layer is
//     given), or the step if that is less (a clevis head's 3 mm margins past a rod, at a 5.5 mm
//     step), past Eq. 4's T, when every branch cut at that plane turned: past the plane, that
//     less the clearance a plane at T is moved by (a crank's web, 2 mm wider all round than the
//     shaft it stands on, reached 1.96 mm past the planes round the shaft, and stayed in the
//     shaft's layers, 47 mm^2 of it hanging in one);
//   - rests on the build plate, when the father is the root: material on the plate is built up
//     from it (a nozzle building it sideways would meet the plate), and the root must keep its
//     footing (a ring standing on its rim, whose axis comes round back to the plate);
//   - holds the father's base face, all that is left of it: a split may take part of it (the
//     upper half of a bar built along X, cut off to be built up on the lower half), never all;
//   - holds over four times what b and its sub-branches swept (plus two steps of b's first
//     section, plus that section swept back from where b's march began, Eq. 4's T, to the plane
//     when the plane lies behind it: a face the span widened over a gusset admitted): it is
//     mostly other branches' material (a sliver the sections left beside a pipe tee's branch
//     would cut the branch pipe in two with its plane);
//   - is no valid solid, whatever is tried;
//   - would leave the father, when it is a child itself, thinner along its build direction than
//     a child may be (the axis step or min_component_height): later splits of a closed loop's
//     rung (a ladder of two arms joined at their tips) carved it down to a slab no layer fits.
//   When the plane was a planar face's, the branch then tries the face nearest the junction, if
//   the refused one was chosen nearest the father's own section (where the walk crossed where
//   the father's march merged another, a portal's deck over two piers, that is the wrong
//   pier's), and then the section plane (below) once instead, unless its piece was too short;
//   it is noted only if that is refused too. A face's
//   whole plane can reach far past the branch: with two square arms meeting at a round column, the
//   side of one arm, nearest the other's junction, cuts the column off down to the plate; the
//   section plane at the column's extent cuts the arm alone.
// - A branch marching -Z (material hanging from what is above it: a hook's tip, a blade's half
//   under a disk, a collar's share under a horizontal arm) is not cut: its child would be built
//   downward, its nozzle under the part, past the machine's reach (max_tilt_deg; the default
//   machine's table tilts 100 degrees at most, Gcode.hpp, and the program refused such a
//   component). Its material stays in the father, built with the father's layers (overhanging
//   where it hangs), with a note. Its own sub-branches are cut from the father as any other's.
//   Nor is a planar face whose normal tilts past max_tilt_deg a splitting face (a drafted face
//   10 degrees off X builds its child 100 degrees from +Z).
// - Later siblings in the same father whose own choice is the same plane (posts on a plate) are
//   cut by the same split: the components are those of one split per sibling, for one Boolean.
// - No planar face meets the criteria (a round boss on a round body), or its split was refused:
//   the SectionPlane rule (our documented replacement for the paper's silhouette-edge method)
//   cuts at the plane perpendicular to D where b's march started: Eq. 4's extent T of the father's
//   section (b's first node's slab_start), plus a clearance of the axis' eps, the deflection of the
//   mesh T was measured on (CentroidalAxis::deflection_mm, else the part's default: a loop on a
//   curved face lies up to that far inside it) and step / 100 (the axis simplifies loops by that
//   much), but not past b's first plane less eps. That plane lies up to a step further on, where
//   the axis snapped the branch to its grid: cut there, the branch's material before it would stay
//   on the father as a stub whose underside overhangs (11 mm^2 in all under a crossbar through a
//   round column, against 0.4 cut at T). Over a gusset (the walk down the father's march above
//   found the father's own section, and it reaches less far than T by more than a step: the
//   gusset's tip), the plane is at the father's own extent plus the clearance instead, so that the
//   arm over the gusset goes with the branch, gusset and all, as a face's split at a square
//   column's side takes it; refused, the plane at T is tried. Either plane may still cross a face
//   of the father, over the branch (its first section grown by a step), that reaches a little
//   further (a round shank under a bolt's hex head, 0.013 mm past where b's first plane less eps
//   put it): the piece would keep a sliver of it down to the plate and be refused. The plane then
//   goes past every such face reaching no more than the clearance past it (exact, on the BREP's
//   faces; again while it crosses another), plus eps; where that takes it past b's first plane,
//   b's first node's material point is taken that far along D too. The same piece selection
//   follows. What lies between the father's surface and that plane (the lens of a round boss on a
//   round body) stays in the father.
// - A branch whose line runs off D about its father's direction is cut at a section plane turned
//   square to its line instead (a blade on a round hub 33 degrees off -X: the march takes the
//   nearest of +-X, +-Y, +-Z, and the plane square to D at T left a wedge of the blade up to 3 mm
//   deep in the hub, its underside overhanging the hub's layers, 21.6 mm^2 on a hub with five
//   blades). The line runs through the centroids of the branch's first six nodes (all, if fewer;
//   the last ones left out, down to three, where they are off the line or their areas differ: a
//   blade's tip cuts its last sections short, over two nodes on a blade 43 degrees off -X, where
//   leaving out only the last found no line, and a wedge of the blade hung 14.5 mm^2 in the hub's
//   layers, survey seed 150), lying on one within the clearance, less its component along the
//   father's direction (a branch leaning up out of a column keeps D); it is turned to when more
//   than 2 degrees and less than 60 off D, those nodes' section areas within 10 % of each other (a
//   wedge's centroids drift along a line too), and the line within max_tilt_deg of +Z. Rays cast
//   back along the line, from points along the first node's outline (spaced the larger of a tenth
//   of a step and a 64th of the outline) moved the clearance out of it, as far as the father's node
//   the branch links to, meet the father's faces facing the branch (a hit on the branch's own side,
//   met by a ray a little off the branch's line, counts for nothing); the plane lies the clearance
//   past the furthest hit, and the child is built along the line. What stays in the father is the
//   lens between its side and the plane (under half a millimetre deep beside a 6 mm blade on a 13
//   mm hub), as under a round boss. The plane square to D, above, is taken where the branch runs
//   along D, no ray meets the father, its first node carries no region or would not lie the
//   clearance in front of the turned plane, the turned plane's split is refused, or
//   DecomposeParams::square_branches lists it (as slicing does where the nozzle cannot build the
//   turned cuts' layers: a spiral stair's treads under a nozzle whose tip is 16 mm across,
//   SlicePart.hpp); its component says which
//   (Component::turned).
// - A branch turning off its father round a bend (a pipe's elbow: the father marches up a straight
//   riser, its centroids then drifting along D through the bend, and the branch marches along the
//   run) is cut at the bend's halfway plane instead (bend_plane()): square to F + D (F the
//   father's direction), through the corner where the riser's line meets the run's, which is the
//   plane through the bend's centre of curvature halfway round it, whatever the bend's radius.
//   The child is built along that bisector (Component::turned): its layers start at 45 degrees
//   and turn towards D as the thickness bounds let them (Slicing.hpp), and no face of the bend's
//   second half or of the run leans more than 45 degrees off them; the father's layers hold the
//   bend's first half, whose faces lean no more than 45 degrees off F. Cut square to D at T
//   (where the run's march began, near the bend's end), the father held nearly all of the bend,
//   and a hollow bend's bore ceiling (the inside of its outer wall, leaning past 45 degrees from
//   halfway round, which is why the plane lies there) hung in its layers: 7.0 mm^2 in one layer on
//   a survey part (seed 206), 45 of the 54 survey parts over the deflection's strip at seeds 161 to
//   224 were such bends. Only where the father's march past its straight run is the bend: branches
//   leaving it other than this one lie wholly in front of the plane (a valve body going on above a
//   port near its top is no bend: cut halfway, its top went with the port), and past the node the
//   branch links to, the march does not come back onto its straight run's line (a column going
//   on past a tapered arm, whose sloping root drew its centroids aside below the junction, is no
//   bend: cut halfway, the column kept the wedge under the arm's root, 3.3 mm^2 hanging in a
//   layer), nor do the branches it parts into there going on along its direction (a pipe lying
//   across a post, its bore parting the post's march into the pipe's walls: cut halfway, the
//   post kept the pipe's underside out to the planes, 50 mm^2 hanging in a layer). Refused (or
//   asked, square_branches, or turn_cuts false), the plane square to D at T.
// - The whole plane can cut off, on the father's side, material joined only to the child's
//   piece: an S bracket's middle plate, cut off its lower upright's face, takes with it the top
//   plate's tail past that face. Such a piece (wholly on the father's side, joined to exactly
//   one child, the grown child within its volume allowance) goes with the child, to be taken on
//   by the later split of the branch it belongs to (the top plate's, along +X). Once every branch
//   is handled, every component must lie in front of its base (checked on the solids' boxes:
//   exact along the axis-aligned directions, erring towards "behind" otherwise); if one does not,
//   the decomposition is done again without joining, and those splits are refused as leaving
//   their father in pieces. (Refused, the S bracket's middle plate stayed in the root, its
//   underside overhanging 750 mm^2.) The second pass's progress stages begin "again, leaving
//   cut-off tails in their fathers: ", its fraction staying where the first pass ended.
// - A split that OCCT cannot perform, or that leaves no piece containing Pos_end or a father in
//   several pieces or no valid solid, is skipped (a planar face's after the section plane's try):
//   the branch's material stays in its father, as it was (each split works on a copy: a failed
//   one can alter the solid it is given), and a note says so.
// - Branches of one direction that split around a hole and merge again beyond it (AxisBranch::
//   merged_into) make no cut: a wall with a hole through it is one sub-component. So do those
//   that split again before they merge (a merge between a branch's line, it and the branches it
//   split into in its direction, and another line split off its father's): a valve body's ring
//   broken by three ports' bores at three heights. Cut where the first two tracks parted, the
//   body's halves each held part of a bore, and neither could deposit it solid (fill_holes).
// - Bridges (not in the paper, whose six directions cannot build one): where such a merge closes
//   a gap with a flat underside (a handle's bar across two posts, a portal's lintel, the wall over
//   a window), that underside hangs over the gap in the first layer along D: 272 mm^2 under a
//   bar 8 mm wide across 34 mm, and no order of components or direction of the six avoids it
//   (built sideways from one post, the bar's last layers close the gap against the other's, where
//   the nozzle cannot reach). Branch b's track having merged into m's, both marching along D in
//   one component built along D, the component is split by the plane of its lowest face facing
//   -D within two steps past b's last node, over the gap (seen along D, the face's box meets the
//   segment from m's node nearest that plane to b's last node), and what lies past the plane (one
//   solid, the father left one solid and as tall as a step, as for any split; the root may be
//   left several solids, each standing on the plate: a portal's two legs, a table's legs) becomes
//   b's child (m's where b is the root's own branch: a part on several feet whose first foot's
//   track merged into another's), SplitRule::Bridge, built along the diagonal d = (D + g) /
//   sqrt 2, g the frame's direction square to D nearest the gap's, either way (bridge_gap,
//   CentroidalAxis.hpp): its underside, and its faces square to g, then
//   lean exactly 45 degrees off d, which slicing's layers lay at the default overhang angle (a
//   layer's allowance is its thickness x tan 45), and the nozzle, along d, stays clear of the
//   father's top beside the layer (its cone's lower side rises 15 degrees from its tip, 3.5 mm
//   over the deposit point at the defaults). It is kept only where, built along d, at most half
//   of the piece's surface leaning past DecomposeParams::overhang_angle_deg overhangs that
//   leaned so built along D (meshed at the part's default deflection, its faces off the plane;
//   on the plane, its underside less what rests on the father: an OCCT cut of its faces there by
//   the father's); of the two ways, the one leaving less, the way from m's track towards b's where
//   alike. Built from its lowest point along d, its first layers would be slivers growing from an
//   edge, far past the volumetric bound (0.01 mm^2 the first of a handle's bar): so the wedge of
//   it behind the plane square to d through the lowest point that way of its top (its faces
//   facing D), or of what of its underside hangs, or of a face of it leaning past the overhang
//   angle off D, whichever comes first, goes back to the father, on whose top it rests (its face
//   on that plane faces up, which the father's layers lay), and the piece starts there, its base
//   face on that plane (base_normal -d). The wedge must be one solid, rest wholly on the
//   father's top and lean nowhere past the overhang angle off D, and the father with it and the
//   piece without it must mesh closed (a plane through another window's corner left the piece an
//   edge four triangles shared); else the piece stays whole, its base plane square to d through
//   its lowest point, on the splitting plane (base_origin; base_normal -D, the splitting plane's).
//   The piece is found by the node marched along D past the plane nearest the gap's middle, else
//   by the nearest marched another way (a table's top, far wider than its legs, turned sideways
//   off them; a note that such a branch stayed in its father then names the bridge's component).
//   Bridges are cut the lowest first (two windows side by side: cut at the higher one first, the
//   band under it, holding the lower one's ceiling, was thinner than a step and stayed). A gap
//   the axis crossed sideways is a bridge too: a branch asked to stay in its father
//   (keep_branches; slicing asks where the nozzle cannot reach its own layers), marching square
//   to the build direction D of the component holding it, is cut at the highest flat face of
//   that component facing -D under its march (over the segment from its first node to its last,
//   above the component's base), g its direction, the piece found by its node past the plane
//   nearest its middle, where a gap lies under that face: the component's material reaches half
//   a step under it on both sides of the march's middle along g (an arm off a column's side,
//   resting on one, stays as asked). So is one marching along D whose first node lies within two
//   steps over such a face, g the first of the frame's directions square to D along which a gap
//   lies under its first node. Beams across the tops of two posts braced to each other: the
//   brace joins the posts' tracks under the beam, so no track merges over the gap; the march
//   crosses the beam along it from one post's top, or reaches it along the brace and rises
//   through it from over the gap. Built along its march, the beam's last layers close the gap
//   against the other post, or its first hangs over the gap. Those bridges are cut after the
//   merged tracks', the branch still listed as kept (Decomposition::kept_branches), so that
//   decomposing with those gives them again. Last, a piece cut off across its father's build
//   direction D and built on along D whose base hangs over a gap (more than half of its base
//   face resting on nothing, nothing of the father half a step under the face's centroid,
//   something on both sides of that point along the first of the frame's directions g square to
//   D; a pipe's end, its centroid in the bore, rests whole) is built along D + or - g as a
//   bridge's piece, where that leaves at most half of what overhangs along D, without the wedge
//   (its base plane square to the diagonal through its lowest point, on its base plane, as a
//   mesh's): a beam over two braces crossing under it, cut off at its underside along Z, its
//   first layer hanging between the posts. So is a piece built up along +Z (off a father built
//   along Z or not) whose flat faces facing -Z that hang along Z (its base's part resting on
//   nothing of the father, its faces off the base plane) have more than half its base face's
//   area, where nothing of the part lies half a step under their centroid and something does on
//   both sides of that point along g: a beam the axis rose into from a brace leaning under it
//   at less than 45 degrees, the brace and the far post built along the brace, the near post
//   beside the beam's end no father of it; a beam's middle slab cut off just under its underside
//   over the far post's top. A merged tracks' bridge is not cut where b is asked
//   to stay in its father, nor is any bridge where a component already cut off the father has
//   its base across the plane, or on a round underside (a bore's ceiling, an arch's round
//   intrados), which no plane's face spans. The father's children whose bases lie past the
//   plane become the bridge's. A mesh (decompose_mesh, SlicePart.hpp) gets its bridges over
//   flat facets, without the wedge.
// - Nor does a branch in its father's direction where the father's section split and every
//   other branch of that split ended on the plane it began on (one node, no sub-branches): a
//   sliver beside it, thinner than a step (the far end of a port another branch took, left under
//   the march's plane; a leaning branch's tip), not a fork's arm. The branch is the father's
//   march going on.
// - A piece's seams between faces on one surface are removed on a copy of it, and kept where
//   removing them widens a tolerance: cutting a ball on a pedestal round a circle across the
//   sphere's seam, OCCT 7.6 merged the circle's halves into one edge and widened the vertex it
//   kept to the circle's diameter, in place, on the vertex the father shared; the ball's other
//   sides' first nodes then classified as on the father, not in it, and stayed in the root. A
//   piece on which the seam removal throws (a piece of a torus: an eye bolt's ring, a hollow pipe
//   cross's side arms) is taken as the split left it.
// - Several roots (a part on several feet) share the one root component. Where a bridge's split
//   (above) takes what joins them, the root is left in several solids apart, each standing on
//   the build plate, as one component: built up from the plate along +Z, each of its layers holds
//   a region per foot (a portal's lintel on two legs, 240 mm^2 in its first layer along Z, is a
//   bridge's piece so, and nothing hangs). No other split may leave a component in pieces.
// - An axis marched in a frame turned about Z (AxisParams::frame_deg: a part placed turned on the
//   plate) is decomposed in that frame, where its directions are +-X, +-Y and +-Z as read above
//   (and Eq. 5's projections and the boxes exact): the part and the axis are turned into it, and
//   the components (solids, base faces, directions) turned back; the root's base_origin is the
//   centre of the bottom of its box as it lies. The frame is read off the axis' branch directions
//   (axis_frame_deg); an axis whose directions are of no one frame is an InvalidArgument.
#pragma once

#include <Eigen/Core>
#include <functional>
#include <string>
#include <vector>

#include "mas/CentroidalAxis.hpp"
#include "mas/Progress.hpp"
#include "mas/Shape.hpp"

namespace mas {

// A branch of the axis left in its father's component whatever it qualifies for, and why (the
// decomposition's note on it ends with this).
struct KeptBranch {
    int branch = -1;  // a branch of the axis other than its root (0)
    std::string why;
};

// Throws InvalidArgument ("<caller>: ...") when a kept branch is the axis' root or one it lacks.
void check_kept_branches(const std::vector<KeptBranch>& kept, const CentroidalAxis& axis,
                         const std::string& caller);
// The same for branches asked to be cut square to their directions (square_branches).
void check_square_branches(const std::vector<int>& square, const CentroidalAxis& axis,
                           const std::string& caller);

// Branch b's line, where it runs off its direction D about its father's direction by more than 2
// degrees and less than 60 (a blade on a hub between -X and +Y, marched along the nearer, or
// along the farther, where the march along the nearer broke off within a few nodes: a blade 51
// degrees off +X, marched 6 nodes along -Y and then along +X, was cut square to +X, and its wedge
// and the slivers each layer left along its side hung up to 6 mm^2; survey seed 130): the
// unit direction of the line through the centroids of its first six nodes (all, if fewer; the
// last ones left out, down to three, where they are off the line or their areas differ: a blade's
// tip cuts its last sections short), lying on one within `tolerance_mm`, their section areas within
// 10 % of each other (a wedge's centroids drift along a line too), less its component along the
// father's direction (a branch leaning up out of a column keeps D), pointing along D. False
// otherwise (also for the root, a branch without nodes or link, or one the axis lacks). A solid's
// decomposition and a mesh's turn a section plane square to it (above; SlicePart.hpp).
bool branch_line(const CentroidalAxis& axis, std::size_t b, double tolerance_mm,
                 Eigen::Vector3d& along);

// Where a ray meets a father's surface: how far along it, and the surface's outward unit normal.
struct RayHit {
    double distance = 0.0;
    Eigen::Vector3d normal = Eigen::Vector3d::Zero();
};
// cast(from, direction, length, hits) adds to `hits` where the ray from `from` along the unit
// `direction` meets the father's surface within `length` (in any order).
using RayCast = std::function<void(const Eigen::Vector3d& from, const Eigen::Vector3d& direction,
                                   double length, std::vector<RayHit>& hits)>;

// Where the section plane turned square to branch b's line `along` (branch_line()) lies: its
// offset along `along`, `clearance_mm` past how far the father's surface reaches beside the
// branch. Rays are cast back along the line from points along its first node's outline, spaced
// the larger of a tenth of a step and a 64th of the outline (a square blade's outline has its
// corners alone, where a round hub's side is furthest from its middle), each moved `clearance_mm`
// out of it, as far as the father's node the branch links to; each ray's nearest hit on a face
// facing the branch (normal . along at least 0.1: not the branch's own side, met by a ray a little
// off its line, nor a face the ray leaves the father by) counts, the furthest along `along`. NaN
// where nothing counts, the first node carries no region, or its centroid would not lie the
// clearance in front of the plane. `inner`, a point in the first section's material, is moved
// along the line to the clearance in front of the plane where it lies behind that.
double turned_plane(const CentroidalAxis& axis, std::size_t b, const Eigen::Vector3d& along,
                    double clearance_mm, const RayCast& cast, Eigen::Vector3d& inner);

// Where branch b turns off its father's march round a bend (a pipe's elbow), the plane halfway
// round it: its normal bisects the father's direction F and b's direction D (square to each
// other), and it passes through the corner where the father's straight run meets b's line.
// The father's run: walking back from the node b links to, the first three nodes in a row whose
// centroids lie level along D (within step / 100; two could be a drift turning back); b's line:
// the first three of its nodes in a row whose centroids lie level along F. On a bend of any
// radius that corner and the bend's centre of curvature lie on the same plane square to F + D.
// False (cut square to D at Eq. 4's T, as before) unless F and D are square to each other, both
// runs are found, the father's run's last section lies wholly `clearance_mm` behind the plane
// (its straight part is not cut), the father's march ends no further along F than b's sections
// reach, plus a step (a column going on past the branch, a tee, is cut at T), no node of the
// father's march past the one b links to lies back on its straight run's line (within step /
// 100 along D: a column going on past the branch as high as it reaches, its centroids drawn
// towards b only where they held b's root, such as a tapered arm's), nor does any node of a
// branch that the march parts into at that node going on along F (a pipe's walls over the bore
// of a pipe lying across a post), every other branch
// leaving the father's march past its run (and their sub-branches: the bend's own material where
// a Z plane cuts it in two) has its centroids the clearance in front of the plane and reaches
// no further along F than b's sections, plus a step (a valve body going on past a port near its
// top, other ports, are not the bend's), and `inner` (a point in b's first section) lies the
// clearance in front of it. `point` and `normal` receive the plane (normal along F + D); the
// caller checks that the child, built along it, is within the machine's reach.
bool bend_plane(const CentroidalAxis& axis, std::size_t b, double clearance_mm,
                const Eigen::Vector3d& inner, Eigen::Vector3d& point, Eigen::Vector3d& normal);

struct DecomposeParams {
    // Criterion (1): a splitting face's normal is within this angle of +-D, degrees.
    double face_angle_deg = 10.0;
    // Criterion (2): an edge is concave when the solid's interior angle there exceeds 180 degrees
    // by more than this, degrees (tangent edges, e.g. of fillets, are not concave).
    double concave_angle_deg = 1.0;
    // Criterion (3): slack on Eq. 5's interval [D.Pos_start, D.Pos_end], mm.
    double projection_tolerance_mm = 0.01;
    // Cut at the plane where a branch's march started when no planar face qualifies, or when
    // the split at the one that does is refused.
    bool section_plane_fallback = true;
    // A child must reach at least this far past its splitting plane, mm, and at least one axis
    // step (a turned branch: a thickest layer at slicing's defaults, or the step if less, past
    // Eq. 4's T, less the clearance the plane lies past T); a
    // thinner piece stays in its father. Slicing sets its min_layer here, so that no component
    // is too thin for a layer.
    double min_component_height_mm = 0.0;
    // The most a child's build direction may tilt from the build plate's +Z, degrees, in
    // [90, 180]: the machine's reach (LayerParams::max_tilt_deg; slicing sets its own here). A
    // branch marching further (straight down, -Z, below 180) is not cut, and a planar face whose
    // normal tilts further is no splitting face (the section plane, normal to the branch's
    // direction, is tried instead).
    double max_tilt_deg = 100.0;
    // Branches not cut off (their material stays in their fathers' components, a note saying
    // why; their sub-branches are cut from there as usual): what slicing asks for when a
    // branch's own component would leave the nozzle no way to some of its layers (SlicePart.hpp).
    std::vector<KeptBranch> keep_branches;
    // Branches cut at the section plane square to their direction D, never turned square to their
    // line (above): what slicing asks for first when the nozzle has no way to some layers of a
    // turned cut's component (SlicePart.hpp). Each must be a branch of the axis other than its
    // root, else InvalidArgument.
    std::vector<int> square_branches;
    // False: no section plane is turned square to a branch's line, as every branch were in
    // square_branches (what a FreeCAD document saved before the turned cuts keeps).
    bool turn_cuts = true;
    // Slicing's overhang angle (LayerParams::overhang_angle_deg), degrees in (0, 90): what of a
    // bridge's piece overhangs built along a direction (bridges, above). Slicing sets its own.
    double overhang_angle_deg = 45.0;
};

struct Component {
    enum class SplitRule {
        Root,          // the part's base component (what remains after every split)
        PlanarFace,    // cut at the plane of a face meeting the three criteria
        SectionPlane,  // fallback: cut at the plane where the branch's march started
        Bridge,        // a bridge's piece, cut at its underside, built along a diagonal (above)
    };
    // One closed solid; for a root left on several feet apart by a bridge's split (above), a
    // compound of closed solids, each standing on the build plate.
    Shape solid;
    int parent = -1;  // index of the father component, -1 for the root
    // Unit; the reverse of base_normal, but for a bridge's piece (SplitRule::Bridge) starting at
    // its underside, built along a diagonal half way between -base_normal and the way across its
    // gap.
    Eigen::Vector3d build_direction = Eigen::Vector3d::UnitZ();
    bool has_base_face = false;  // false for the root (it stands on the build plate)
    Shape base_face;             // the child's planar face on the splitting plane; null for root
    // A point on the base face (its centroid; for a bridge's piece starting at its underside, its
    // lowest point along build_direction, which slicing starts from) and its outward unit normal,
    // mm. For the root: the centre of the bottom of its bounding box and -build_direction.
    Eigen::Vector3d base_origin = Eigen::Vector3d::Zero();
    Eigen::Vector3d base_normal = -Eigen::Vector3d::UnitZ();
    int branch = -1;      // the axis branch that made this component (the root's: 0)
    int break_link = -1;  // that branch's first link (the break, turn or split), -1 for the root
    SplitRule rule = SplitRule::Root;
    // Cut at a section plane turned square to its branch's line, or at a bend's halfway plane
    // (above), not square to the branch's direction: its build_direction is that plane's normal.
    bool turned = false;
    double volume_mm3 = 0.0;
};

// "root", "planar_face", "section_plane", "bridge": the names the CLI and the Python API use.
const char* to_string(Component::SplitRule rule);

struct Decomposition {
    std::vector<Component> components;  // tree order: a father before its children; [0] is root
    // One line per branch that asked for a cut and got none (no splitting plane, a split OCCT
    // could not perform, no piece holding the branch, a piece too thin or holding what its father
    // stands on, a child that would be built downward), saying why and where its material stayed.
    std::vector<std::string> notes;
    // The branches DecomposeParams::keep_branches asked to keep that were kept so (the others
    // got no cut for other reasons, or none was asked of them), in increasing order.
    std::vector<int> kept_branches;
    // DecomposeParams::square_branches, in increasing order, each once: decomposing with them (and
    // kept_branches) gives this decomposition again.
    std::vector<int> square_branches;
};

// Splits `solid` along `axis` (computed for this solid). Throws mas::Error: NotASolid /
// MultipleSolids / EmptyInput as Shape::single_solid, InvalidArgument for bad parameters, a kept
// branch the axis lacks (or its root, branch 0), or an axis computed for a different part,
// GeometryFailure when OCCT fails on the input itself, whatever `progress` throws (Progress.hpp:
// reported branch by branch, checked before each split). The input shape is never modified.
Decomposition decompose(const Shape& solid, const CentroidalAxis& axis,
                        const DecomposeParams& params = {}, const Progress& progress = {});

}  // namespace mas
