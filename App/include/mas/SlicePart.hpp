// Slicing a whole part (paper Sec. 4.2): every sub-component of its decomposition, in tree order,
// into adaptive "3-D" layers along its own axis (Slicing.hpp), and the deposition paths of every
// layer (Toolpath.hpp), with the statistics a process engineer checks first.
#pragma once
#include <Eigen/Core>
#include <any>
#include <functional>
#include <string>
#include <vector>

#include "mas/CentroidalAxis.hpp"
#include "mas/Decompose.hpp"
#include "mas/Holes.hpp"
#include "mas/Mesh.hpp"
#include "mas/Nozzle.hpp"
#include "mas/Paths.hpp"
#include "mas/Progress.hpp"
#include "mas/Shape.hpp"
#include "mas/Slicing.hpp"
#include "mas/Toolpath.hpp"

namespace mas {

struct SlicePartParams {
    LayerParams layers;
    PathParams paths;
    TessellationParams tessellation;  // for the components' meshes (slice_part only)
    NozzleParams nozzle;              // the build sequence's (Nozzle.hpp)
    // slice_part only: round holes up to this diameter (mm) whose axis leans more than
    // layers.overhang_angle_deg off their component's build direction are deposited solid, to be
    // drilled afterwards (Holes.hpp). 0 fills none.
    double fill_holes_up_to_mm = 0.0;
    // slice_mesh_part only: the mesh is decomposed (decompose_mesh); false slices it as one
    // component.
    bool split_mesh = true;
    // slice_mesh_part and slice_solid_part: where the nozzle cannot reach some layers of a
    // component, its branch is kept in its father (slice_clear_of_collisions); false slices the
    // first decomposition as it is, those layers listed in the sequence's collisions.
    bool avoid_collisions = true;
};

// One sub-component as a closed mesh, the input of slice_components.
struct ComponentMesh {
    TriangleMesh mesh;
    int parent = -1;  // father component, -1 for the root
    Plane base;       // on its base face (root: the build plate), normal = build direction
    int branch = 0;   // the axis branch it follows
    // Cut square to its branch's line, which runs between the six directions, or at a bend's
    // halfway plane (Decompose.hpp's Component::turned), not square to the branch's direction.
    bool turned = false;
    // A bridge's piece (Decompose.hpp, decompose_mesh), built along a diagonal from its lowest
    // point that way. Where its branch marches across its father's build direction (a beam the
    // axis crossed sideways), its layers are not turned after the branch's nodes: built along
    // the diagonal towards the far post, they turned after the march until they stood square to
    // the beam, the nozzle level over that post.
    bool bridge = false;
};

struct ComponentLayers {
    int component = -1;
    int first_layer = 0;  // index into SlicedPart::layers
    int layer_count = 0;
    // Axis nodes of its branch whose section's material (AxisNode::material_point) lies in it,
    // followed by its layers.
    int guide_nodes = 0;
    double volume_mm3 = 0.0;  // of its mesh
};

struct SliceStats {
    int layer_count = 0;
    double min_thickness_mm = 0.0, max_thickness_mm = 0.0;  // over every layer
    double part_volume_mm3 = 0.0;           // the part (its meshes; slice_part: the exact solid)
    double deposited_volume_mm3 = 0.0;      // sum of the layers' prisms
    double material_volume_mm3 = 0.0;       // sum of the part's material between layer planes
    double max_volume_difference = 0.0;     // the largest layer VolDiff
    int layers_over_volume_difference = 0;  // kept at min_layer although over the bound
    double worst_unsupported_area_mm2 = 0.0;
    int worst_unsupported_layer = -1;
    double deposit_length_mm = 0.0, travel_length_mm = 0.0;
    int centre_line_passes = 0;      // regions narrower than a bead, run as one centre line
    int unfilled_features = 0;       // too small even for that: listed per layer
    int colliding_layers = 0;        // layers whose nozzle meets deposited material (Nozzle.hpp)
    int component_switches = 0;      // in the sequence: consecutive layers of two components
    int leaned_layers = 0;           // layers deposited with the nozzle leaned (Nozzle.hpp)
    int filled_holes = 0;            // holes deposited solid, to be drilled (slice_part only)
    double filled_volume_mm3 = 0.0;  // the material that adds (exact, from the BREP)
};

struct SlicedPart {
    std::vector<Layer> layers;  // component by component in build order, each bottom to top
    // One per layer, its first travel from where the layer before it in `sequence` ends, its
    // tool axis the sequence's (the layer's normal, or the nozzle leaned from it).
    std::vector<LayerToolpaths> toolpaths;
    std::vector<ComponentLayers> components;  // indexed by component
    std::vector<int> build_order;             // the components in the order they start
    // The layers in the order they are deposited (Nozzle.hpp): build_order's components, a
    // component left for another where going on would block the nozzle's way to that one's
    // layers; and the layers whose nozzle still meets what is deposited.
    BuildSequence sequence;
    Plane plate;  // the build plate the sequence was checked against (the root's base)
    // slice_part with fill_holes_up_to_mm: the holes deposited solid, to be drilled afterwards,
    // component by component; and a note for each hole that qualified and stayed open.
    std::vector<FilledHole> filled_holes;
    std::vector<std::string> notes;
    SliceStats stats;
};

// The order the components are deposited in: the root first, then, again and again, of the
// components whose father is already built, the one whose first layer is left least unsupported by
// everything built so far (base_support), the first in tree order among equals (within a
// thousandth of its footprint). A side branch leaving a pipe that continues above it (a tee) thus
// waits for the pipe above, whose material its first layer also rests on; without such a
// difference the order is the tree's. Only support is weighed: the nozzle's reach past built
// components (Eq. 10) is not.
std::vector<int> build_order(const std::vector<ComponentMesh>& components,
                             const LayerParams& params, const Progress& progress = {});

// Slices components given as meshes (a mesh part is one root component). `axis` is the part's
// centroidal axis: component c follows the nodes of branch components[c].branch whose section's
// material (AxisNode::material_point) lies inside its mesh. A node whose region (AxisNode::region)
// the component lacks part of, wider than the tessellations' disagreement (twice the axis'
// deflection, plus step / 100 and 0.1 micron), is moved to the centroid of the part it holds, on
// its plane: where a split took from a father part of its nodes' sections (a column cut from the
// arm whose near end, out to the tip of a gusset, its sections held), the father's layers follow
// its own material, not what went to the child. Material a node's region never held (another
// branch's, which a mesh sliced as one component keeps) moves nothing. A component cut turned
// square to its branch's line (ComponentMesh::turned) follows, instead, the centroids of its own
// sections square to that line (its build direction), one through each such node, dropping those
// past its end or no further along the line than the one before: it is built along the line to
// its tip, which the nodes, marched along the nearest of the six directions, cut aslant (a twisted
// blade's centroids dropped to its tip's lowest corner, and its layers tilted after them). So does
// one cut at a bend's halfway plane, square to its build direction (the bisector): the centroids
// of its sections square to that run along the pipe's run beyond the bend, and its layers turn
// from the base's 45 degrees towards it (Slicing.hpp), as far as the thickness bounds and the
// guide let them (the sections near the run's end, cut short by it, draw the guide back up: a
// survey bend's last layers lie 20 degrees off the run). They are started in build_order(); each
// child's first layer is checked against everything built before it. Then the layers' sequence
// against params.nozzle (plan_build_sequence): a component waits for its father's layers it may
// rest on and for the components before it in build_order that its first layer rests on (those
// that, reaching its base, leave less of it unsupported than its father alone); the plate is the
// root's base. `progress` (Progress.hpp) follows the build order (a few per cent), the components'
// layers (each its share by volume, reported after every layer and checked between candidate
// planes), the paths (layer by layer), what each component rests on and the sequence (the last
// tenth), and reaches 1 when done. Throws as slice_component, and InvalidArgument for a component
// whose parent is not before it.
SlicedPart slice_components(const std::vector<ComponentMesh>& components,
                            const CentroidalAxis& axis, const SlicePartParams& params,
                            const Progress& progress = {});

// Decomposing a closed mesh, which has no faces to split at (Decompose.hpp): every branch of the
// axis that turned or split from its father asks for a cut at Decompose.hpp's section plane,
// perpendicular to the branch's direction at Eq. 4's T plus the axis' clearance (eps, deflection,
// step / 100; not past the branch's first plane less eps). The component holding the branch's
// first section (AxisNode::material_point) is split there: the child is the connected piece of its
// surface above the plane that a ray from that point (away from the plane) meets, closed with a
// cap triangulated on the plane; the rest, closed with the same cap, stays the father. As in
// Decompose.hpp, the piece stays in the father, with a note, when the branch is built past
// max_tilt_deg from +Z, when the piece reaches less than min_component_height or the step past
// the plane (a branch that turned: the step, at most 2 mm, the thickest layer at slicing's
// defaults), rests on the build plate (comes within min_component_height, at least eps, of it:
// the root builds it up), would take all of its father's base or leave the father thinner than
// that along its build direction, holds over four times what the branch and its sub-branches
// swept (plus two steps of its first section), or either piece is no closed solid. A branch
// running between the six directions (branch_line(), Decompose.hpp: a blade on a hub) is cut
// first at the plane turned square to its line, the clearance past the father's surface beside it
// (turned_plane(), rays cast at the father's facets), its first section's material point moved
// along the line past that plane if it lies behind; where that cut is refused for any of the
// reasons above, or square_branches lists the branch, at the plane square to its direction. A
// branch turning off its father round a bend (bend_plane(), Decompose.hpp: a pipe's elbow) is cut
// first at the bend's halfway plane, built along the bisector of its direction and its father's;
// refused, or asked (square_branches), at the plane square to its direction. The root stands on
// build_plate() and follows branch 0. Then its bridges (Decompose.hpp): where two of the axis'
// tracks along D merge in one component built along D over flat facets facing -D, it is split at
// their plane (kept there, the facets the piece's underside, the cap only where the two touch)
// and the piece, ComponentMesh::bridge, is built along the diagonal from its lowest point that
// way (no wedge), as a solid's is kept or refused; its father may be left in bodies apart, each
// standing on its base (MeshSplit.cpp, bridges()).
struct MeshDecomposeParams {
    double min_component_height_mm = 0.0;
    double max_tilt_deg = 100.0;
    std::vector<KeptBranch> keep_branches;  // branches not cut off, whatever they are
    // Branches cut square to their directions, never to their lines (DecomposeParams).
    std::vector<int> square_branches;
    // Slicing's overhang angle: how far a bridge's facets may lean off its direction (degrees).
    double overhang_angle_deg = 45.0;
};
struct MeshDecomposition {
    std::vector<ComponentMesh> components;  // tree order: a father before its children
    std::vector<std::string> notes;         // why a branch got no component of its own
};
MeshDecomposition decompose_mesh(const TriangleMesh& mesh, const CentroidalAxis& axis,
                                 const MeshDecomposeParams& params = {},
                                 const Progress& progress = {});

// Splits the closed mesh at `plane`: `above` is the connected piece of its surface above the plane
// that holds `inside` (a point inside the mesh, above the plane), `below` all the rest, each closed
// with one cap on the plane, facing out of it. The plane is moved along its normal by up to a
// millionth of the part's size when a vertex lies on it; `cut_offset` receives where it cut
// (normal . point). False, with `why`, when it cannot: `inside` is not above the plane or in the
// mesh, or the cut's outline does not close or cannot be triangulated.
bool split_mesh(const TriangleMesh& mesh, const Plane& plane, const Eigen::Vector3d& inside,
                TriangleMesh& above, TriangleMesh& below, std::string& why,
                double* cut_offset = nullptr);

// A closed mesh sliced on its build_plate(), decomposed by decompose_mesh() with min_layer_mm as
// the least component height and the layers' max_tilt_deg (unless params.split_mesh is false: one
// component following the axis' first branch), in the rounds of slice_clear_of_collisions (below)
// that keep the branches of components some of whose layers the nozzle cannot reach in their
// fathers. Throws InvalidArgument for fill_holes_up_to_mm > 0: holes are read on a BREP.
SlicedPart slice_mesh_part(const TriangleMesh& mesh, const CentroidalAxis& axis,
                           const SlicePartParams& params, const Progress& progress = {});

// A part decomposed and sliced, for slice_clear_of_collisions: the slicing, the axis branch each
// of its components came from (the root's first), whether its cut was turned square to its
// branch's line (Component::turned, ComponentMesh::turned), and the decomposition's notes.
struct SplitSliced {
    SlicedPart sliced;
    std::vector<int> branches;
    std::vector<char> turned;
    std::vector<std::string> notes;
    // Whatever else `split` made of the part (a solid's Decomposition), handed back with the
    // split slice_clear_of_collisions takes (SplitOutcome::made): a round may split it twice.
    std::any made;
};

// The rounds slice_mesh_part and slice_solid_part share. `split` decomposes the part, keeping the
// branches it is given in their fathers and cutting those it is given square to their directions
// (DecomposeParams::square_branches), and slices it (given the first 70 % of `progress`).
// Unless `avoid_collisions` is false: where some layers would meet what is deposited before them
// (no order or lean clears them, Nozzle.hpp), and one of their components (not the root) was cut
// turned square to its branch's line (Component::turned), every component so cut is cut square to
// its branch's direction next; where only some of them hold such layers, squaring those alone is
// tried too, and taken where it slices better (sliced_better). Else their branches are kept too,
// each saying so. The part is split and sliced again, up to five times in all (the next 20 %).
// Then, given `strip_mm` (a solid's deflection; a mesh, sliced as it is, gets 0 and none of this),
// where a layer hangs past a strip that wide along its outlines (what sections of a mesh that far
// off the surface can show on a part with nothing hanging), the branch of the component holding
// the one hanging furthest past it is kept in its father, saying so, and that split taken where
// no more of its layers are in the nozzle's way, no more hang past the strip and the worst hangs
// past it by less (by more than a hundredth of a mm^2); up to three times, one branch at a time,
// stopping at the first split not taken (the next 5 %). With layers still in the way, `whole`
// slices it as one component (the last 5 %), kept when fewer of its layers are, with a note. The
// decomposition's notes come first in the result's, each "decomposition: ...".
struct SplitOutcome {
    bool took_whole = false;         // the part sliced as one component was kept
    std::vector<std::string> notes;  // the decomposition's notes, without the "decomposition: "
    std::any made;                   // the SplitSliced::made of the split taken
};
// Whether slicing `b` leaves fewer layers in the nozzle's way than `a`, or as many and less
// unsupported at worst (by more than a hundredth of a mm^2).
bool sliced_better(const SlicedPart& b, const SlicedPart& a);

SlicedPart slice_clear_of_collisions(
    const std::function<SplitSliced(const std::vector<KeptBranch>& keep,
                                    const std::vector<int>& square, const Progress& progress)>&
        split,
    const std::function<SlicedPart(const Progress& progress)>& whole, bool avoid_collisions,
    const Progress& progress, SplitOutcome* outcome = nullptr, double strip_mm = 0.0);

// A solid decomposed (decompose() with `decompose_params`, its kept branches among those kept;
// the first fifth of each round) and sliced (slice_part), in the rounds of
// slice_clear_of_collisions: what the command line's and the Python API's slice do with a solid
// (with the layers' min_layer_mm as the least component height and their max_tilt_deg, so that
// every component fits a layer and the machine's reach). Sliced as one component, it is
// decomposed with every branch kept. With fill_holes_up_to_mm, a split that would cut a hole it
// fills along its length (holes_to_fill() on the whole part along +Z, and the upright ones along
// X and Y, which count for a sub-component built along a direction they lean over
// overhang_angle_deg off; the split's plane through the material round the hole, the
// sub-component holding some of it but not all), leaving it
// whole in no component, is not made where that helps: in each round the branches of such splits
// are kept in their fathers, and those of their sub-branches that then cut one, and that
// decomposition is sliced too (the second half of the round) and taken when it leaves fewer layers
// in the nozzle's way, or as many and less unsupported at worst (by over 0.01 mm^2); otherwise a
// note names each hole left open and both outcomes.
// `decomposition` receives the decomposition sliced (decompose() with its kept_branches gives it
// again); its notes are the result's "decomposition: ..." ones. Throws as decompose() and
// slice_part().
SlicedPart slice_solid_part(const Shape& solid, const CentroidalAxis& axis,
                            const DecomposeParams& decompose_params, const SlicePartParams& params,
                            Decomposition& decomposition, const Progress& progress = {});

// The decomposition's components, their holes filled when params.fill_holes_up_to_mm asks it,
// tessellated with params.tessellation (the first tenth of `progress`), then slice_components. A
// root on several feet (Decompose.hpp) is filled and tessellated solid by solid, into one mesh.
// stats.part_volume_mm3 is the exact solid's volume, before any hole is filled.
SlicedPart slice_part(const Shape& solid, const CentroidalAxis& axis,
                      const Decomposition& decomposition, const SlicePartParams& params,
                      const Progress& progress = {});

// The plane a root component stands on: through the mesh's lowest point, under the centre of its
// box, normal +Z. (The mesh's box, not an OCCT bounding box, which may be looser than the solid.)
Plane build_plate(const TriangleMesh& mesh);

// Whether `point` lies inside the closed mesh (generalised winding number above one half).
bool inside_mesh(const TriangleMesh& mesh, const Eigen::Vector3d& point);

}  // namespace mas
