// Centroidal axis (paper Sec. 3, Fig. 9): centroids of planar cross-sections marched along the
// part from its base, turning among +-X, +-Y, +-Z where the part turns, with branch topology.
//
// Readings of the paper chosen here (each tested in tests/engine/test_axis.cpp):
// - The six directions are the part's frame's (AxisParams::frame_deg): +-Z, and +-X and +-Y turned
//   about Z to line up with the part's sides (derive_axis_frame). The paper's are the document's,
//   and a part placed turned on the plate then turns between them: the L-block turned 30 degrees
//   had its arm marched along neither, split in two components beside the column's, and 75 mm^2
//   overhung in one layer (a mesh of it sliced at the defaults; 0 in its frame). The part is
//   turned into its frame, marched there as below, and its axis turned back (turned_about_z);
//   for a part square to the document's axes, or round, the frame is 0 and nothing changes. The
//   decomposition works in the axis' frame too (Decompose.hpp).
// - Every outer loop of a section is its own node (Sec. 3.1). A section region continues the
//   track of the lower region it overlaps most, projected along the march direction (Eq. 2).
//   A lower region overlapped by several upper regions splits: each becomes a new branch in the
//   same direction, child of the lower one's branch. An upper region overlapping several tracks
//   continues the one it overlaps most; the others end there, merged into it (merged_into). Upper
//   regions overlapping no lower region of the march belong to other geometry and are left to the
//   search that reaches them. An overlap no wider than 1e-4 mm (ten units of the polygon
//   Booleans' grid) along the shorter of the two outlines is none: it is a hairline the Booleans'
//   snapping left, such as the one U minus a turn's far pieces keeps along their outline.
// - Eq. 2 on a region U over its lower region(s) L: the parts of U - L, dA_k, whose centre G_k lies
//   farther than d outside L's external contour (2-D distance on the plane; a centre in L's hole
//   is inside it: a collar round a pipe is centred on the pipe, not 4 mm out of its wall) start
//   new branches, unless they are
//   bumps on a large section's surface (which made organic meshes sprout hundreds of branches):
//   centred and reaching no farther than an eighth of L's size (sqrt of its area) outside L. One
//   that reaches farther is an overhang growing out of the part, however near its centre: a
//   twisted blade leaving a hub at a small angle adds a long strip beside the last one at every
//   plane. d (Eq. 3) is `distance_threshold`; derived, it is twice the step but at most a sixth
//   of L's size. The step is half the thinnest wall, and on a thick part two steps can be more
//   than half what its lugs and bosses stick out (a 30 mm column with 8 mm bosses sticking out
//   10 mm: step 4.6 mm); those would stay in their father, their undersides overhanging. A sixth
//   is still past a bump's eighth. The rest of U continues the march. A stick-out touching two or
//   more lower regions is the bridge where tracks merge (the top of a hole), never a new branch.
//   A stick-out reaching out past L by more than half its size but centred near it, "along the
//   march", may be stick-outs a sliver joins: sections are simplified within a hundredth of the
//   step, so two sections of one wall can differ by twice that, and U - L keeps the sliver
//   between them along L's outline. It is split where necks narrower than a fiftieth of the step
//   join pieces larger than min_region_area (opened by a hundredth of the step), and each piece
//   is judged on its own. (Two blades a quarter turn apart round a hub, joined so at the part's
//   deflection, were marched with the hub: 74.6 mm^2 of their undersides hung.) So is a stick-out
//   that turns (far, a ledge or a steep limb, below): two blades' first slivers 62.7 degrees apart
//   round a hub, joined so, made one ledge that turned along +X, and the outer half of the blade
//   62.7 degrees round went along +X too, its layers overhanging 8.5 mm^2 each.
//   The new direction is the one of +-X, +-Y, +-Z closest to G_k - E, plus the step along the
//   march, E where the stick-out meets L. The paper's Sec. 3.2.1 says G_k - C, C the lower
//   centroid; that sends a lug sticking out sideways near the end of a long wall along the wall,
//   past the part, so its material is never searched. E is the centroid of what of L lies within
//   two hundredths of a step of the stick-out opened by one hundredth (unopened, a sliver U - L
//   keeps along L's outline drew E round L: a hub's straight blade 31 degrees off -X turned +Y);
//   where that meets L nowhere, the point of L's boundary nearest to G_k. (That point was E
//   before: a strip leaving a round hub aslant, as a twisted blade's lowest edge does, 7.4 mm to
//   one side of the blade's middle plane, is centred 15 degrees round from where it leaves, and
//   from that point a blade 30.5 degrees off +Y turned -X, whose march caught only its tip; the
//   rest hung in the hub's layers, 7.8 mm^2.) The first plane of the new branch is at Eq. 4's
//   location: the lower boundary's extent T along the new direction, plus eps. Where L reaches
//   past the section on the plane under it by no more than a plane's spacing, over a side of
//   that section running straight up (as far out on the plane under that, within a hundredth of
//   a step), what L holds past the side is the first sliver of what turns, its underside begun
//   between the planes: T is that side's extent, as for a steep limb (below), and the march
//   takes all of U past it that the stick-out is part of. (Four round arms rising 17.1 degrees
//   off a hub reached out far on the plane over their first slivers, 1.1 mm past its side in L;
//   cut past the slivers, the wedge of each root under the cut hung in the hub's layers, 10
//   mm^2 in one.) The new march's first section is what of U meets its share there, less the
//   pieces of the share within a step past T that U joins to L only further on (no piece of U
//   up to that step past T meets both the piece and L) while another piece is joined to L:
//   such a piece is no part of the march leaving L. (A crank's three legs round a gap, the last
//   running back beside the first past the riser's face: the march along the first leg took the
//   last one's section too and marched it towards its root, its end behind T stayed in the
//   riser, and the legs hung 410 to 693 mm^2 in the riser's layers. Left out, the march turns
//   into the second leg where it reaches it, and that one into the last, marched to its end. A
//   blade leaving a round hub aslant is joined to the hub behind T, and keeps its march.)
// - A stick-out that is no turn by its centre (centred near L, or a bridge between lower
//   regions) yet reaches out past L by more than `distance_threshold` and half L's size wraps
//   round L or spans past the regions it joins: a hub lying across the neck it stands on makes
//   one stick-out centred on the neck. It is shared out among the four sides as below, each
//   side's T taken over every lower region, and each share is judged as a stick-out of its own;
//   where it appears at once on a flat underside and spans no gap (a shelf through a column,
//   wider than it too), each share turns as a centred ledge's (below) does (the
//   shelf's 5 mm margins along a 30 mm column, centred within Eq. 3's threshold of it, stayed in
//   the column, overhanging: 180 mm^2). Reaching out less, it is the part widening (an organic
//   body at its shoulders), unless it is a ledge all round (below).
// - A ledge turns however near its centre (with a derived `distance_threshold` only; one given
//   is used as given): a stick-out not wrapping round L (above), meeting L along one stretch (not
//   spanning a gap, as a bore's ceiling closing a ring does), reaching out past L by more than a
//   step (an overhang steeper than 45 degrees over the step) and than a bump, or, out of the box
//   of the lower plane's whole section, than what layers at slicing's defaults lay (below) (a
//   6 mm lug on a 60 mm block, within its 7.5 mm bump, hung 4 mm past what its first layer laid;
//   a manifold block's boss reaching out 5.6 mm, under the block's 5.8 mm step, half its thinnest
//   wall, 23.8 mm^2; within the box, a pin hole's ceiling closing over the hole, built sideways
//   from each side, hung more than in the lug's layers), and appearing at once: under 10 % of
//   its area in the lower plane's whole section and, half a step up, over 90 % or up to 25 % (a
//   flat underside, or one tangent to the planes, below or above that plane; a side sloping out
//   over the whole step, however steeply, shows about half, and so is no ledge; a chamfer or
//   fillet under a ledge may show either, by where the planes fall, and the chamfers round a
//   boss' root and end hold some of it below its lowest line: 15 % of a chamfered manifold
//   block's 11.8 mm boss, which at a tenth stayed in the block's layers, 15 mm^2 overhanging in
//   one). A round underside across
//   the march (a boss on a wall, its axis square to the march) shows between a tenth and nine
//   tenths wherever the planes fall but near its lowest line, yet what of it the half plane holds
//   already reaches out three quarters as far as the stick-out does or more, as a flat one would
//   (a side sloping out reaches about half as far there): it appears at once too, when new (under
//   10 % in the lower plane) and centred at least a third of its reach out of L, as a prism
//   sticking out is (at half): its reach past E the way it would turn, where that is less than
//   its farthest point's distance from L (a boss' strip on a round body reaches farther at its
//   corners, where the body curves away: a valve body's boss, radius 9.3 on a body of 12.8,
//   cut 4 mm over its lowest line, reaches 5.7 mm along +X and 7.25 mm at its corners, centred
//   2.42 mm out; read by its corners, it stayed in the body's layers, 20 mm^2 overhanging).
//   (A 13 mm boss sticking out 6.7 mm from a 41 x 31 mm block stayed
//   in the block's layers: 28 mm^2 overhung in one layer. The third keeps stick-outs hugging L,
//   as an organic body's bulges do, even where a point of one reaches out: turned, CGAL's
//   armadillo grew 21 branches, 62 to 83, in 45 % more time.) Its first layer in the march would
//   hang in the air, and Eq. 3 by its centre (and G_k - E plus the step,
//   mostly along the march while the centre is within a step) kept a staircase's 5 mm steps in
//   the march at the derived step, 2.84 mm. It turns the closest of the four sides to G_k - E, or
//   to G_k - C when G_k lies inside L (an arm's underside wrapping round the web under it), C the
//   centroid of the lower region nearest G_k, and is shared out among the sides as below, each
//   share turning if it reaches out of the bump or of what layers at slicing's defaults lay
//   (below), whichever is less. Centred on C itself (a collar or a head all
//   round a rod), it goes no one way: reaching out past L by more than two bumps, or by more than
//   layers at slicing's defaults lay (2 mm thick at 45 degrees: 2 mm, give or take a twentieth for
//   the chords of a round column), it is shared out round L as a wide stick-out is, from the side
//   after the march's axis, each share turning if it reaches out of the bump or of what those
//   layers lay, whichever is less. (A collar sticking out 5 mm all round a 20 mm column stayed in
//   the column's layers: 328 mm^2 of its underside overhung in one layer.) What lies past no
//   side's T stays in the march: on a round rod, the collar's four lenses between the sides'
//   planes. Reaching out less, it is a shoulder, which the march lays (cut into four, a 2 mm
//   shoulder on a 12 mm shaft gave pieces tapering over the volumetric bound, and the lenses left
//   overhung more than the shoulder had).
// - How far a stick-out reaches out past L, for the ledges and wide stick-outs above, is read on
//   what of it is wider than twice the sections' simplification (opened by a hundredth of a
//   step): U - L can trail a hairline along a wall where a slab's cut and the section it was
//   taken from differ by microns. (On a bored valve body whose ports' bores cut its ring into
//   halves, the strip a half's wall adds over a bore's axis trailed one 4 microns wide 5 mm along
//   the slabs of the port's boss: read as a ledge reaching 5.3 mm out, it turned a march across
//   the ring's upper half, and the ports, split inside the body through the other bores, stayed
//   in the body's layers, 79.9 mm^2 hanging.) Only within the box of the lower plane's whole
//   section, where such walls are: out of it a stick-out hangs over nothing of the part and is
//   material however thin (a boss's first sliver, under a tenth of a millimetre wide 3 microns
//   over its lowest line at a 4.46 mm step, reaching 8.1 mm out of a block, was opened away, and
//   the boss stayed in the block's layers, 27.0 mm^2 hanging).
// - A ledge growing into a gap that closes by the next plane is a hole's ceiling, not a ledge:
//   where the part's section on the stick-out's plane holds material ahead of it the way it
//   would turn (within its span across that way, past its far end), and the next plane's section
//   covers at least half the gap between the two, the march keeps it, and lays it as the two
//   sides meet (a bridge, above). (A bored valve body's +-Y ports cut its ring, 6.3 mm thick,
//   into halves; a plane 0.07 mm under a bore's top, at a 1.72 mm step, found each half's wall
//   grown 2.7 mm towards the other over it, 1.5 mm apart. The march turned along +X there
//   started inside the ring and took the whole wall over the bore in its first section: the ring
//   was swept sideways in pieces, the +-X ports became branches inside the body, and the
//   decomposition left them in the body's layers, 82.6 mm^2 hanging in one.) A gap that stays
//   open, such as an inward lip's across a bore or an arm's end facing another column, leaves a
//   ledge a ledge; so does one that closes only further up (kept in the march where a gap 1.1
//   mm wide is covered two planes up, CGAL's armadillo scaled to 100 mm hung 29.9 mm^2 in its
//   worst layer against 11.3).
// - A steep limb turns too (with a derived `distance_threshold` only): a branch leaning out of
//   the march by more than 1.5 planes' spacing a plane (56 degrees). Its section moves on along
//   the way it leans, and U - L is a crescent round the end of it, centred inside L, so Eq. 3
//   never turns into it however far it goes (a branch leaning 70 degrees off a round column
//   overhung the column's layers by 8.5 mm^2 in one, 70 in all). A stick-out is one when it is
//   such a crescent: centred inside L and a quarter of L's size or more off its centroid C (a
//   cone or a ball widening all round is centred on C), new on the plane, reaching out past L by
//   more than 1.5 spacings, its limb already held in L by more than that past where it leaves the
//   march's section: its end moves on plane after plane, where a boss's round underside's end
//   stays where its first sliver was. A limb much thinner than what it leaves makes a crescent
//   wider than the round end of L it grows round, centred out of L though nearer than d: it is
//   one too where its end moves past L's, the way it leans, by more than 1.5 spacings on the
//   plane, where a round underside's end moves out by less and less as the round flattens. (A
//   branch of radius 5.5 leaning 63.8 degrees off a column of 10.7, its crescents centred 0.8
//   mm out of L, stayed in the column's layers until it parted from it: 4.4 mm^2 hanging in a
//   layer.) It turns the closest of the four sides to G_k - C, and its march starts at Eq. 4's
//   T on the section the limb leaves: going down from L through the regions under it, plane by
//   plane, while each reaches out along that side by more than a plane's spacing (45 degrees)
//   past the one under it, and one plane more where the last reaches out less past a side
//   running straight up: the limb's first sliver, its underside begun between the planes (cut
//   past such a sliver, 1.5 mm out of a column of radius 11.4, a branch leaning 68.9 degrees
//   left a wedge hanging 1.4 mm^2 in the column's layers). That march takes all of U beyond
//   there that the crescent is part of. (From L's own T, what L held of the limb stayed in the
//   march's layers, a wedge hanging under the cut.) It turns as a ledge's share does, where
//   the crescent reaches out of the bump or of what layers at slicing's defaults lay, or
//   however little where L holds no more than twice the crescent's reach of the limb past its
//   root (a limb leaning 62.6 degrees moves 1.77 mm a plane, under a 2 mm bump; an elephant's
//   belly, 11.6 mm out past its leg in L, is the body widening, and stays). It turns so however
//   far the crescent reaches past L, past the distance threshold and four bumps too, where a
//   stick-out is otherwise shared out round L, each share turning only where its centre lies
//   far (four round arms rising 15.5 degrees off a hub turned 23.6 mm out, a plane late, and
//   their roots hung 21 mm^2 in a layer of the hub's), provided its root lies past L's centroid
//   the way it leans (a rod standing on the rim of its end outgrows the sliver there past it:
//   the section growing, no limb).
//   Two limbs leaning apart (a fork) are steep from one spacing a plane on (45 degrees): the
//   march's layers lean after its centroids, which move towards neither, so short of kSteepLimb
//   each limb's underside overhung every layer (a solid wye with two laterals leaning 56.2
//   degrees off its riser: 3.5 mm^2 in each layer up to where they parted). Each must be such a
//   crescent reaching out past L by more than a spacing, held by L past its root by more than one
//   and by no more than four spacings (begun within the last three planes), and they must lean
//   opposite ways. A side long leaning out is no fork's limb: turned where the other side begins
//   to lean (CGAL's elephant's belly, 14 mm out past its root), its part was cut deep into the
//   body where the nozzle could not build it, and kept in the body it hung 23.1 mm^2 in a layer
//   where it hangs 15.5.
//   On organic meshes, whose limbs lean so, the axis has more branches and takes longer
//   (CGAL's armadillo: 125 branches where it had 62, about twice the time), and their slicing
//   leaves far less unsupported (the armadillo scaled to 100 mm: 80.7 to 11.3 mm^2 in its worst
//   layer, sliced in 8.6 s where it took 19.9).
// - A march in a new direction reaches only what lies beyond its T, so a stick-out is shared out
//   among the four sides of the lower section (the turn's direction first, then the others):
//   each side's share beyond that side's T whose centre still lies beyond the threshold starts a
//   march that way, from the same plane. T is the extent of the lower region nearest G_k: where
//   tracks merge, a stick-out off the far one of two piers is marched from that pier's face. What
//   lies beyond no side, or too close, stays with the march that found it: an inward lip over a
//   tube's bore (centred in the bore, inside the ring's external contour; no sideways march
//   could reach it), a C-shaped section's mouth filled. Where the stick-out appears at once on a
//   flat underside and spans no gap, the shares beside a far turn's own are judged as a
//   ledge's: each turns if it reaches out of the bump or of what layers at slicing's defaults
//   lay (2 mm), whichever is less, as a ledge's share does. (A web round the column an arm
//   leaves, a crank's round its shaft, hangs past the column's other sides from its first
//   layer: its 4 and 5 mm margins, within the threshold, stayed in the column and overhung
//   219 mm^2; a bracket plate's 6 mm margins on a 50 mm column, within its bump, 400 mm^2.)
// - A turned branch's first section is judged by Eq. 2 too, against the part's whole section
//   one plane behind it (whichever march swept that), but only where what it holds past that
//   appears at once: a ledge, as above, which turns and is shared out as one. A tier of an
//   inverted staircase overhanging the tier a sideways march turned up onto hangs 15 mm from
//   its first layer (520 mm^2 overhung, read whole as the paper's first sections are). A first
//   section cut across a sloping side grows past the one behind it as the march's sections do,
//   and is left to the march (read on every first section, CGAL's fandisk grew two branches
//   marching down from a sideways one, and its slabs 9 % less volume).
// - Beside a fin, T is where the stick-out begins. A web or gusset under an arm whose tip comes
//   within a step of the arm's end (flush, the common bracket) puts T at the tip: the march past
//   it found nothing, and the arm stayed in its father's layers, its underside beside the web
//   overhanging (a tee with 23 mm arms over 23 mm webs: 504 mm^2 in one layer); where it found a
//   sliver, the decomposition's cut could leave a piece too thin to build (a shelf over two
//   flush webs). When a share reaches less than a step past its side's T, begins more than a
//   step behind T, appears at once, and what of the lower region lies past where it begins is
//   fins (each within the plane's stick-out's span across the side, no wider across than half
//   of it nor than half the lower section, longer along the side than wide, with less area than
//   the share together), the march along that side starts where the share begins: the column's
//   face the web stands on. The share turns if it reaches out of the bump, as a ledge's does,
//   and takes with it the arm over the fin on that plane; the node below, whose slab swept the
//   fin's section up to that plane, ends it beyond the root where the arm's underside appears
//   (found by halving between the planes, to 1e-4 of a step) and below there sweeps the fin's
//   section at that height, out to the fin's tip, so the arm's sections are whole and their
//   centroids on its centre line. (With the notch over the fin, they sat up to half a
//   millimetre off it until the fin ended; the guide bent there and a bracket's last layers
//   tilted past the arm's end, beyond the volumetric bound.) The decomposition then cuts the arm
//   at that face, web and all (Decompose.hpp). A column's own material past that place is no
//   fin, and T stays: a round column's under a webbed arm, whose surface the stick-out meets
//   behind its extent (half the column across), or a 16 mm column's under an arm 40 mm wide,
//   whose flanks begin at the column's far side (for a march back along the arm, at the arm's
//   far end).
// - GetSweepBody / B = B - Bs (Sec. 3.2.4) as bookkeeping on the sections, not a solid Boolean:
//   each node sweeps a slab, its region extruded from its plane to the next one along the march
//   direction. Every later section first subtracts the slabs it crosses (all directions are
//   axis-aligned, so a slab meets a plane in its own region or in a union of rectangles). Search
//   is branch-first: a new branch is searched to its end before its father's march continues,
//   so the father's later sections no longer see the branch's material, and no part of the solid
//   is searched twice. The slabs' volumes (section area x thickness) add up to the part's volume
//   for prisms along the march (tested), and near it otherwise: by how much the sections change
//   within a slab (the example bracket: +5 %). A march subtracts
//   the slabs only from the regions whose box meets one of its tracks' boxes: it reads no others.
// - FindConnectingLink: a branch that turned is tied to the node of its father branch nearest to
//   its first node; a branch born of a split is tied to the lower node it split from.
// - C1 breaks (Sec. 3.2.3): a link whose direction turns more than `break_angle` from the link
//   that arrives at its start node, unless that link is itself a break (then the turn only
//   undoes the connector between two sections' centroids: one break, not two).
// - Section loops are simplified to step / 100 before any Boolean (corners kept: simplify()).
// - Marches in one direction all read the same sections, cut once on a grid (the part's lowest
//   offset along the direction + eps + k step): a turned branch starts at the first grid plane at
//   or past Eq. 4's location, at most one step on. Its first node's slab reaches back to T
//   (AxisNode::slab_start), so nothing between is left unswept; the decomposition's
//   section-plane cut is placed from T (Decompose.hpp). A stick-out ending before that plane (a
//   boss shorter than the way from T to the grid's next plane, or past its last) is one node on
//   Eq. 4's own plane, T + eps, off the grid, its slab from T to where it ends (the last offset
//   short of that plane where the section still holds material over the node's region, bisected
//   and snapped to the mesh's farthest vertex there). Only a stick-out whole, not a share of one
//   shared out among sides (an arm's end past the web under it, its flanks turning sideways),
//   which stays with the march it came from. Whole is also the one share of a stick-out that no
//   other side's share turns beside: what it leaves behind T stays with the march it came from,
//   as behind any turn's T (a boss on a round body, its corners between the body's curve and T;
//   a boss sticking out 5.1 mm under a 5.5 mm step stayed in a valve body's layers, 16.8 mm^2
//   hanging in one, until it was so). A share thinner on average than a tenth of the step
//   starts nothing there: that is what the Booleans leave along a face the sections'
//   simplification moved. Nor does one whose region on T + eps the part still holds on that
//   next plane, beyond the stick-out's slab: the part goes on past it there (a wye's lateral
//   leaving its riser at 53 degrees, its root a crescent beside the riser), and the march it
//   came from finds it again on later planes, further out (one node took one lateral's root and
//   lost the rest of it, 12 % of the part, and the axis was refused).
// - Several regions in the very first section (a part standing on several feet) each root a tree:
//   the result is a forest with one tree per foot.
// - Material the march from the base cannot reach, because it first appears in mid-air and joins
//   the rest only further up (a block hanging under a bridge, a box under a table top), is
//   searched after the search from the base, upward from each +Z grid plane where it overlaps
//   nothing on the plane below: it roots a tree of its own there, its first slab reaching back
//   one step. Built from there, its first layer rests on nothing (slicing reports it
//   unsupported). This is done only when the slabs fall short of the part's volume by more than
//   their own error, so that a part the search from the base covers keeps its axis; a hanging
//   piece within that error (a small hopper's cone under the ring its legs carry) stays
//   unsearched and is built with its father's component all the same. (Looked for everywhere,
//   it gave CGAL's armadillo 342 branches instead of 65, in three times the time.) Where that
//   still leaves material lost, what is left unswept is searched the same way from its own
//   underside: each piece of a +Z grid plane's B - Bs, over two steps wide (2 x area / outline;
//   the staircase of slabs along a slanting side leaves wedges up to a step wide), that overlaps
//   none of the plane below's. The depth-first search can go round a closed loop and sweep what
//   it meets from inside: on a braced frame whose two braces cross under the beam, clear of it,
//   the march went up one brace, down the other into the far post, and through both posts and
//   the beam over them along X, and the beam's middle, resting on the posts' material, not on
//   air, was never reached (89 % of the part swept: the axis was refused). It roots a tree of
//   its own along +Z from its underside. Only a part the first search leaves short takes this.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <functional>
#include <limits>
#include <string>
#include <vector>

#include "mas/Mesh.hpp"
#include "mas/Polygon2.hpp"
#include "mas/Progress.hpp"

namespace mas {

struct AxisParams {
    // Distance between consecutive sections (paper: inc), mm. <= 0: derived from the part
    // (derive_axis_step): half its thinnest wall, within [diagonal / 2000, diagonal / 20], at most
    // half the part's height.
    double step_mm = 0.0;
    // A stick-out area whose centre lies farther than this outside the lower section starts a new
    // branch (paper: d), mm. <= 0: derived, twice the step ("much greater than the step", Sec.
    // 3.2.1), and at each section at most a sixth of the lower section's size (sqrt of its area);
    // CentroidalAxis::params reports twice the step.
    double distance_threshold_mm = 0.0;
    double eps_mm = 0.001;  // paper's epsilon: the first plane sits this far inside, mm
    double break_angle_deg =
        30.0;  // links turning more than this from their predecessor are breaks
    // Height of the plane the part stands on, mm. NaN: the part's lowest point. A part whose
    // lowest point is above this plane (by more than eps) does not touch it: an error.
    double base_z_mm = std::numeric_limits<double>::quiet_NaN();
    double min_region_area_mm2 = 1e-6;  // smaller section regions are slivers, ignored
    // The part's frame: the turn about +Z of the directions +-X and +-Y the march takes, degrees,
    // read modulo 90 into (-45, 45]. NaN: derived from the part (derive_axis_frame); 0: the
    // document's own X and Y, as the paper's.
    double frame_deg = std::numeric_limits<double>::quiet_NaN();
    std::size_t max_nodes = 200000;  // guard against runaway searches
};

struct AxisNode {
    Eigen::Vector3d position = Eigen::Vector3d::Zero();  // centroid of the region, mm
    Eigen::Vector3d normal = Eigen::Vector3d::UnitZ();   // the section plane's normal (march dir.)
    double area = 0.0;                                   // region area, mm^2 (after B - Bs)
    double offset = 0.0;                                 // normal . point on the plane, mm
    // Length of the slab this node sweeps along `normal`, mm. (Beyond a fin's root, the slab of
    // the node under an arm's underside ends at that underside, the reading above; `thickness`
    // stays the whole length.)
    double thickness = 0.0;
    // Where that slab starts along `normal` (normal . point), mm: the node's own plane, except
    // for a march's first node: a root's reaches down to the base plane (eps below; one step
    // below for a root of material hanging in mid-air), a turned branch's back from its grid
    // plane (or, a short stick-out's, from its plane off the grid) to Eq. 4's T (the lower
    // section's extent along the new direction), up to a step before `offset`.
    double slab_start = 0.0;
    int branch = -1;
    int incoming_link = -1;  // the link ending at this node, -1 for a root node
    Region2 region;          // the region in PlaneFrame(normal) coordinates
    // A point in the region's material, on its plane (interior_point()): unlike the centroid it
    // never lies in a hole (a pipe's bore) or outside a C's mouth. NaN when not known.
    Eigen::Vector3d interior = Eigen::Vector3d::Constant(std::numeric_limits<double>::quiet_NaN());

    // Where the node's section has material: `interior`, or the centroid for an axis that does
    // not carry it. (The centroid lies in the bore of a pipe's ring and outside a C's mouth, in
    // no solid.)
    Eigen::Vector3d material_point() const { return interior.allFinite() ? interior : position; }
};

struct AxisLink {
    enum class Kind {
        Step,        // consecutive nodes of one march (also from a lower node to a split branch)
        Connecting,  // FindConnectingLink: father-branch node to the first node of a turned branch
    };
    int start = -1, end = -1;  // node indices
    Kind kind = Kind::Step;
    bool is_break = false;  // C1 break: turns more than break_angle from the preceding link
    double turn_deg = 0.0;  // angle to the link arriving at `start` (0 for a root's first link)
};

struct AxisBranch {
    int parent = -1;  // father branch, -1 for a root
    Eigen::Vector3d direction = Eigen::Vector3d::UnitZ();
    std::vector<int> nodes;  // in marching order
    int parent_node = -1;    // the father's node the first node links to (-1 for a root)
    int first_link = -1;     // that link
    int depth = 0;           // 0 for roots
    // The branch that went on with this one's material where their sections merged (two tracks
    // split around a hole and joined again above it), -1 when it never merged.
    int merged_into = -1;
};

struct CentroidalAxis {
    std::vector<AxisNode> nodes;
    std::vector<AxisLink> links;
    std::vector<AxisBranch> branches;
    AxisParams params;                 // with derived values filled in
    double searched_volume_mm3 = 0.0;  // sum of the swept slabs' volumes (area x length)
    // Chordal deflection of the tessellation the sections were cut from, mm; 0 when not known (a
    // mesh taken as it is). Set by whoever tessellated: section loops on curved faces lie up to
    // this far inside the solid's surface, and so may an extent such as Eq. 4's T.
    double deflection_mm = 0.0;
    std::size_t sections_cut = 0;  // planes cut from the mesh, for the record
};

// Half the part's thinnest wall (the paper's inc is the smallest distance between two surfaces
// that do not meet; half of it cuts every wall at least twice). A wall is measured as
// 2 x area / perimeter (the width of a long strip) of the elongated regions (P^2 / A >= 21, about
// 3:1 and thinner) among sections along X, Y and Z (16 planes each); compact regions count only
// when no section has an elongated one, since a plane grazing a rounded tip cuts a tiny disc that
// says nothing about wall thickness. Nor does a plane grazing an edge along it (two surfaces that
// meet): the thinnest strip confirmed as a wall (the planes its width, at least diagonal / 200,
// either side cut a region where it lies within 1.5 times as thick or as thin: a wall goes on at
// its thickness, a wedge's edge only thinner) sets how thin a strip may be and count, an eighth
// of it, and the thinnest strip that counts is the wall. Clamped to
// [diagonal / 2000, diagonal / 20], then at most half the part's height (z extent), which the
// march's step must stay under. centroidal_axis() derives it on the part turned into its frame
// (AxisParams::frame_deg), where the sections along X and Y cut its walls square.
double derive_axis_step(const TriangleMesh& mesh);

// The turn about +Z (degrees, in (-45, 45]) that lines the march's directions up with the part's
// sides: Sec. 3.2.1 turns among +-X, +-Y, +-Z, which are the document's, and a bracket placed 30
// degrees round on the plate has its arm leave the column between +X and +Y, marched along
// neither (its decomposition's cut and build direction 30 degrees off the arm, its underside
// overhanging). Each facet votes for its normal's azimuth modulo 90 degrees, weighted by its area
// times the square of its normal's horizontal part (a flat side square to the plate counts
// whole, a floor nothing); the votes are binned by half a degree and the 2 degrees holding the
// most weight are the sides' (their weighted mean, read on the circle). It is the frame when it
// holds at least kAxisFrameAgreement of all the weight (a round part's facets spread evenly, a
// fiftieth in any 2 degrees) and at least twice what any other 2 degrees apart from them hold
// (those round 0, or a second set of sides: a web tapering symmetrically about X has one at +-6
// degrees, and either frame would turn the march off the other side), and it turns by at least
// kAxisFrameMinDeg; otherwise 0, the document's frame (the paper's, and what a part drawn square
// to its axes keeps exactly).
inline constexpr double kAxisFrameAgreement = 0.1;
inline constexpr double kAxisFrameMinDeg = 1.0;
double derive_axis_frame(const TriangleMesh& mesh);

// `axis` turned by `degrees` about the +Z axis through the origin (nodes, their regions, normals
// and material points, branch directions; params.frame_deg turned too): what centroidal_axis()
// gives for a part turned so. Directions within 1e-12 of an axis are put on it.
CentroidalAxis turned_about_z(const CentroidalAxis& axis, double degrees);

// The frame `axis` was marched in (params.frame_deg is not needed): the turn about +Z, modulo 90
// degrees into (-45, 45], of its horizontal branch directions; 0 when it has none. Throws
// InvalidArgument ("<caller>: ...") when they are not one frame's (an axis no centroidal_axis()
// gives).
double axis_frame_deg(const CentroidalAxis& axis, const std::string& caller);

// Throws mas::Error: InvalidArgument for bad parameters (a step that is not positive and finite,
// or not smaller than the part's height, or so small that more than max_nodes sections would cross
// the part; an eps not smaller than the part's height), InvalidArgument when the part does not
// touch base_z or no section of it is larger than min_region_area_mm2 (an empty axis) or when the
// march swept less of the part's volume than the slabs' error allows (what is thinner than a step
// given, whose sections a step apart do not meet, is lost: the message names the step and a
// smaller one), EmptyInput for an empty mesh, Cancelled via throw_on_cancel. `mesh` must be closed.
//
// A part standing on a vertex or a tip (a cube on its corner, a cone on its tip) has, eps above its
// base, a speck of a section or none; a step above, its flanks have outgrown the speck on every
// side by far more than its size, which Eq. 3 would read as a stick-out far outside it, ending
// the march. The root starts at the first grid plane with a section over min_region_area_mm2 and
// at least a twentieth of a step across, its first slab reaching down to the base. So does a part
// standing on a point of a rim (a round rod leaning on its end), whose section there is a sliver:
// narrower on average (2 x area / outline) than a tenth of the step and less than a step across;
// the root starts at the next plane where the part has outgrown the sliver half a step above it
// (a thin leg or pad keeps its first section). A part on an edge or a line, such as a cylinder or
// a torus lying down, has a long section and starts at eps; but a knife edge whose faces are
// within 11.3 degrees of the vertical cuts a hairline there (2 x area / outline up to 4e-4 mm at
// the default eps), which the march would read as overlapping nothing above it: a speck too.
// A part with no such section (a pin thinner than a twentieth of the step all the way up) starts
// at its first section at least half as large as its largest when each section from there on
// meets the one below it (an upright pin); else (a leaning pin, whose sections a step apart do
// not meet) one node on the last plane, its slab reaching down to the base, stands for it.
CentroidalAxis centroidal_axis(const TriangleMesh& mesh, const AxisParams& params = {},
                               const std::function<void()>& throw_on_cancel = {});

// The same, reporting to `progress` (Progress.hpp) the volume swept so far over the part's, as
// the march takes each plane, and 1 when done; its Report may throw to stop the search.
CentroidalAxis centroidal_axis(const TriangleMesh& mesh, const AxisParams& params,
                               const Progress& progress);

// Throws mas::Error(InvalidArgument), its message starting with `caller` ("decompose"), unless
// `axis` is well formed (links and branches point at nodes that exist, fathers come first, slabs
// start where their nodes' planes allow) and belongs to the part whose bounding box is `box` and
// volume `volume_mm3`: its nodes inside the box grown by a step, its swept volume the part's
// within 5 % plus what the slabs' approximation can be off by. Decomposing a solid and slicing a
// mesh check the axis they are given with it.
void check_axis_belongs(const CentroidalAxis& axis, const Eigen::AlignedBox3d& box,
                        double volume_mm3, const std::string& caller);

// Eq. 4's T: how far the outer loop of `region` (in PlaneFrame(normal) coordinates, on the plane
// {normal . p = offset}) reaches along `dir`, the greatest dir . p over its points; -infinity for
// an empty region.
double extent_along(const Region2& region, const Eigen::Vector3d& normal, double offset,
                    const Eigen::Vector3d& dir);

// How far a node's section reaches along `dir`: extent_along() of its region, or its centroid's
// projection for an axis handed over without regions (a dict built by hand).
double reach_along(const AxisNode& node, const Eigen::Vector3d& dir);

// The branches whose tracks merged into others' (AxisBranch::merged_into, with nodes), ordered by
// how far their last nodes lie along their directions, lowest first (ties in index order): the
// order bridges are cut in.
std::vector<std::size_t> merged_lowest_first(const CentroidalAxis& axis);

// Where branch b's track merged into m's (AxisBranch::merged_into), both along the unit D: the
// bridge's gap (Decompose.hpp, bridges), from m's node whose plane is nearest b's last node's
// (`from`, a node index) to that node (`to`), square to D (`across`), and the direction among the
// frame's X, Y, Z (`frame` turns them: the axis' frame_deg about +Z) square to D nearest `across`
// (`way`, unit).
struct BridgeGap {
    int from = -1, to = -1;
    Eigen::Vector3d across = Eigen::Vector3d::Zero();
    Eigen::Vector3d way = Eigen::Vector3d::Zero();
};
BridgeGap bridge_gap(const CentroidalAxis& axis, std::size_t b, std::size_t m,
                     const Eigen::Vector3d& D, const Eigen::Matrix3d& frame);

// A bridge's build direction: of the diagonals (D + way) / sqrt 2, way = `across` then -`across`
// (BridgeGap::way), those within `max_tilt_deg` of +Z (tilt_from_plate_deg), the one whose
// `overhang` (the piece's area leaning past the overhang angle built that way, mm^2) is least and
// at most half of overhang(D); the first where alike. Zero where none is, or where nothing
// overhangs along D.
Eigen::Vector3d bridge_direction(const Eigen::Vector3d& D, const Eigen::Vector3d& across,
                                 double max_tilt_deg,
                                 const std::function<double(const Eigen::Vector3d&)>& overhang);

// A point in a bridge's material past its splitting plane {D . p = s}: the node within two steps
// past it, marched along D (the merged track's, or its sub-branches'), nearest `middle` (the gap's
// middle on the plane); else the nearest marched another way there (a table's top, far wider
// than its legs, turned sideways off them). -1 for none.
int bridge_node(const CentroidalAxis& axis, const Eigen::Vector3d& D, double s, double tol,
                const Eigen::Vector3d& middle);

// Distance from a point to a region in the same 2-D frame: 0 inside, else to the nearest edge of
// the outer loop (holes count as outside: a point in a hole is at its distance to the hole edge).
double distance_to_region(const Region2& region, const Eigen::Vector2d& point);

}  // namespace mas
