// Adaptive multi-axis slicing of one sub-component into "3-D" layers (paper Sec. 4.2): each layer
// lies between two planes that need not be parallel, its direction follows the centroidal axis and
// its thickness adapts to the geometry within [min_layer, max_layer] and the volumetric bound.
//
// A layer, and how the paper is read where it is vague (each tested in tests/engine/
// test_slicing.cpp):
// - Layer k lies between its lower plane L (the previous layer's top, or the base plane for the
//   first) and its upper plane U (the slice Sec. 4.2.2 chooses). It deposits its REGION: the
//   component's section just above L, swept along U's normal n up to U (the lower region, as the
//   issue defines it; what rests on the layer below is exactly what that layer's top offers).
//   The layer records U as its plane: the tool axis is n (unless the nozzle leans, Nozzle.hpp),
//   and its regions are the lower region projected along n onto U, in PlaneFrame(n) coordinates.
//   The root's first region, on the build plate, also takes the section min_layer / 2 above the
//   plate (their union): a planar slicer's mid-layer section. The plate carries what starts that
//   low (a bottom face a hundredth of a mm off flat, a recess that shallow, filled), however
//   small beside the footprint. Eq. 9's samples, from an eighth of the layer up, need not see
//   what it fills.
// - Thickness at a point x of the lower region is its distance to U along n, (U.origin - x).n;
//   the layer's min/max thickness are taken over the region's outline points (the thickness is
//   linear, so the extremes lie on the outline). Eq. 9's bounds apply to both, so consecutive
//   planes never cross inside the region.
// - VolDiff (Eq. 9) for non-parallel layers: vol(P xor M) / vol(P), where P is the deposited prism
//   (the region swept from L to U along n) and M the part's material between L and U. It is
//   integrated over planes with normal n at `volume_samples` heights (midpoints of equal slabs)
//   between the lowest point of L over the region and U: at each, P's section is the region's
//   projection and M's the component's section, both cut by the half-plane where L lies below
//   that height; area(A xor B) = area(A) + area(B) - 2 area(A and B). 0 means the layer deposits
//   exactly the part; it is exact for parallel layers of prismatic parts.
// - Sec. 4.2.2's search: from P_lower (the guide point on L) try P_upper at arc length delta
//   further along the guide (the polyline of the component's axis nodes, those whose section's
//   material lies in it, since a pipe's centroids lie in its bore; a component cut turned square
//   to its branch's line, through its own sections' centroids square to the line, SlicePart.hpp;
//   extended straight past both ends), direction D_upper = the guide's direction there (the link),
//   plane through P_upper normal to D (a plane parallel to L goes exactly delta above it). Accept
//   when Eq. 9 holds and the next layer's footprint (the component's section on U) is supported by
//   this layer (below, with min_layer's allowance; then thickened, "counting on the next layer").
//   Else D = normalise(D + D_lower) until the angle to D_lower is below eps_angle, then
//   delta -= delta / 4, from max_layer down to min_layer. Where a face of the part square to L
//   (a ceiling's underside, a floor's or a step's top) lies between min_layer and max_layer
//   above L, the first such face is tried too, and no delta that would cross it or put the plane
//   less than min_layer below it: a layer across a ceiling lays the walls only (the section just
//   above L) and never the ceiling above its underside, which Eq. 9's sampled sections may not
//   see (a 0.5 mm ceiling over a closed box's cavity went missing, one layer flagged); one
//   across a floor lays the section below into the space above it. Turns under eps_angle / 10,
//   or moving the plane less than a tenth of min_layer across the layer below (centroid noise), are
//   ignored. So is a jog of the guide (its next segment runs within eps_angle of D_lower again)
//   where the part is a prism along D_lower over the first delta tried: the parallel layer there,
//   if it deposits the part exactly (VolDiff within rounding) with the next layer supported, is
//   taken before any tilted one (a pocket in a plate's top moves the centroids, not the part).
//   A jump of the guide, a segment running further sideways than along the segments on both
//   sides of it, which run within eps_angle of each other, is read as running their way: the
//   sections changed shape within a step, the part does not go across. A chair's top, a bridge
//   built along its diagonal, ends at its back, the same march along Z, whose sections hold only
//   the back's: the centroid moves 16 mm across the top in one step up, and layers turning after
//   it (up to 84.5 degrees off Z) laid the back across its side, 72 to 148 mm^2 hanging in each
//   of six (tests/data/chair_back_jump.brep); read so, the back is laid in the top's layers.
//   Where the guide turns on, a bend begins: the layers start turning as before. Every D tilting
//   more than max_tilt_deg from the build plate's +Z (the machine's reach) is turned back
//   towards +Z onto it, in the plane of D and Z: where the guide turns further (a return bend's
//   far leg), the layers stop at the reach. The paper prefers a thinner tilted layer to a thick
//   parallel one: that is what lets the layers follow a bend.
// - Where no direction between D_upper and D_lower meets both at any delta (a tilt the thickness
//   bounds forbid, an overhang of the part's own such as the ceiling of a horizontal hole), the
//   layer keeps D_lower: the thickest parallel layer that meets both, else, of those that meet
//   Eq. 9, the one leaving the next footprint least unsupported, the thickest among equals
//   (planar adaptive slicing; its unsupported area is reported). A wall just past the overhang
//   angle overhangs every layer by (its slope - 1) x the thickness below, so it gets thin
//   layers, as adaptive slicers thin theirs on shallow walls, not thick ones that leave ledges.
//   Unless a tilted candidate met Eq. 9 and leaves less of the next footprint unsupported per mm
//   of height (over its mean thickness) than that parallel layer: then the tilted one. This is
//   where the guide leans along a wall past the overhang angle (an arm leaning 60 degrees off a
//   column, which the axis marches through in Z): no tilt the thickness bounds allow makes the
//   next layer supported at once, and parallel layers would overhang all the way up, but each
//   tilt leaves less, until the layers lie square to the arm. Per mm, not per layer: a wedge
//   leaves more in all than a thin parallel layer just by being thicker on one side.
// - Where even min_layer along D_lower breaks the volumetric bound (the cap of a dome), the layer
//   is kept at min_layer and flagged (meets_volume_difference = false); with `strict` that is an
//   error instead. The thickness bounds are hard.
// - Ending: U never leaves above it a height no layers can fill: less than min_layer, or, when
//   max_layer < 2 min_layer, a height between k max_layer and (k + 1) min_layer. It moves up onto
//   the top of the material (the last layer, if that stays within the bounds), up to the fillable
//   height just below, or down to the one just above. The last layer is therefore thinner than
//   min_layer only when less than min_layer of the component remains above the one before it; a
//   component thinner than min_layer is an error.
// - Support (the point of the method): a layer's footprint on the layer below (its lower region,
//   which lies on the lower layer's top) must lie within the lower layer's region grown by the
//   overhang allowance: where the layer is t thick, t x tan(overhang_angle), so a wedge layer's
//   thick side may reach further than its thin side (unsupported_regions_sloped; the candidates
//   are compared with min_layer's allowance all round). unsupported_area_mm2 is what lies
//   outside. The first layer of a child is checked against what was deposited before
//   it (its father and the components built earlier, see SlicePart.hpp's build order), their
//   sections just below the base face; the root's first layer stands on the build plate.
// - Counting on the next layer: the search checks the next footprint with min_layer's allowance,
//   the thinnest the next layer can be, which alone would thin every layer beside a wall leaning
//   off the build direction (a wall flaring 30 degrees: at most 0.87 mm, where a next layer as
//   thick would support 2 mm), whatever Eq. 9 allows. So, where the search's layer follows the
//   guide (the guide within eps_angle of its normal at the thicker plane) and a thicker one along
//   the same normal meets Eq. 9 and leaves the next footprint supported by a next layer no
//   thicker than its own thinnest, the thickest such is taken instead; the next layer must then
//   be at least as thick as the thinnest of Sec. 4.2.2's thicknesses that supports that
//   footprint, or rest on this one all the same (by the reported sloped check). A layer turning
//   with the guide is never thickened: the layers turn as before (a pipe bend's last layers lay
//   26 degrees short of its run's axis when thickened). Where the next layer cannot rest on it
//   (the part's top, a face square to the layers, Eq. 9), this layer is chosen again: as the
//   search alone chooses it, where it need not rest on a thickness the layer under it counted on,
//   else below its thickness (and so back down while the layers counted on the next). Where that
//   steps back more than 4 x (layers + 8) times, or leaves a layer unsupported past the negligible
//   area (the part's own overhangs: a bore's ceiling) where counting changed any layer, the
//   component is sliced again without counting on the next layer, and the layers counting chose
//   are kept only where they leave no more unsupported at worst and in all (a pillow block's
//   bore: thicker layers under its ceiling left 65 mm^2 in one layer, 44 without).
#pragma once
#include <Eigen/Core>
#include <cstddef>
#include <functional>
#include <string>
#include <vector>

#include "mas/Mesh.hpp"
#include "mas/Polygon2.hpp"
#include "mas/Progress.hpp"
#include "mas/Section.hpp"

namespace mas {

struct LayerParams {
    double min_layer_mm = 0.5;           // thinnest deposit anywhere on a layer, > 0
    double max_layer_mm = 2.0;           // thickest deposit the machine forms, >= min_layer_mm
    double max_volume_difference = 0.1;  // Eq. 9's VolDiff_pre, a fraction of the layer's volume
    double eps_angle_deg = 1.0;  // Sec. 4.2.2's epsilon: stop averaging directions below this
    // Eq. 6's Delta: the first region is the section this far above the base plane, mm. 0: 1e-3 x
    // min_layer_mm.
    double initial_offset_mm = 0.0;
    double overhang_angle_deg = 45.0;  // support allowance = thickness x tan(this), degrees
    int volume_samples = 4;            // sections per layer for VolDiff, >= 1
    // The most a layer's normal (the tool axis) tilts from the build plate's normal (+Z), degrees,
    // in [90, 180]: the machine's reach. The default machine's table tilts A from -100 to 50
    // degrees (Gcode.hpp): 100. 180 sets no limit.
    double max_tilt_deg = 100.0;
    bool strict = false;  // a layer that cannot meet max_volume_difference is an error
    // Accept a plane only when the next layer's footprint is supported (see above). False: Eq. 9
    // alone, as in plain adaptive slicing (the benchmark's planar baselines).
    bool require_support = true;
    std::size_t max_layers = 100000;  // per component: guard against runaway slicing
};

// Eq. 6's Delta: how far above a plane its section is cut, mm (initial_offset_mm, or 1e-3 x
// min_layer_mm when that is 0).
double base_offset(const LayerParams& params);
// tan(overhang_angle): how far a layer may overhang the one below per mm of its thickness.
double overhang_allowance(const LayerParams& params);
// How far `direction` tilts from the build plate's normal (+Z), degrees in [0, 180]: what
// max_tilt_deg bounds (a layer's normal here, a child's build direction in Decompose.hpp).
double tilt_from_plate_deg(const Eigen::Vector3d& direction);
// Whether a face with outward unit normal n, built along the unit d, leans out from it past
// `overhang_deg` (n.d < -sin(overhang)). A face leaning exactly that far is supported (a layer's
// allowance is its thickness x tan(overhang)): a millionth of slack.
bool leans_past(const Eigen::Vector3d& n, const Eigen::Vector3d& d, double overhang_deg);

// The largest max_layer_mm accepted (a kilometre): thicker, adding it to a plane's offset would
// lose the part's height to rounding.
inline constexpr double kMaxLayerLimitMm = 1e6;

// Throws mas::Error(InvalidArgument) naming the parameter (min_layer > max_layer, a non-positive
// or NaN length, max_layer over kMaxLayerLimitMm, a volume difference not > 0, an angle out of
// range, volume_samples < 1).
void validate(const LayerParams& params);

// The thinnest min_layer_mm a component takes, as a fraction of its bounding-box diagonal.
inline constexpr double kMinLayerFraction = 1e-6;

// Throws mas::Error(InvalidArgument) when min_layer_mm is below kMinLayerFraction of `mesh`'s
// bounding-box diagonal: a layer a millionth of the part is no deposit, and one near the rounding
// of its coordinates stalls the slicer (1e-15 mm on a 30 mm box ran 51 s to the 100000-layer
// limit; 1e-12 left a 1e-13 mm layer). A 1.5 m plate takes 0.01 mm. `what` names the mesh in the
// message ("component 2").
void validate(const LayerParams& params, const TriangleMesh& mesh, const std::string& what);

// One sub-component to slice.
struct ComponentSlicingInput {
    int component = 0;                   // index recorded in its layers
    const TriangleMesh* mesh = nullptr;  // the component, closed
    Plane base;  // on the base face (root: the build plate); normal = build direction, inward
    // The component's centroidal axis: node positions in marching order and their node indices
    // (the layers' axis_node). Fewer than two points: a straight line through the base origin (or
    // the single point) along the build direction.
    std::vector<Eigen::Vector3d> guide;
    std::vector<int> guide_nodes;
    // What is deposited before it (its father and any component built earlier), for checking
    // its first layer's support; empty for the root, which stands on the build plate.
    std::vector<const TriangleMesh*> support_meshes;
};

struct Layer {
    int component = -1;
    Plane plane;       // upper plane U: the layer's top; normal = tool axis (unless leaned), unit
    Plane lower;       // the plane it is deposited on (the layer below's top, or the base plane)
    Regions2 regions;  // the deposited region on `plane`, PlaneFrame(plane.normal) coordinates
    double area_mm2 = 0.0;          // of `regions`
    double min_thickness_mm = 0.0;  // over the region
    double max_thickness_mm = 0.0;
    double volume_mm3 = 0.0;           // deposited prism, integrated like VolDiff
    double material_volume_mm3 = 0.0;  // the part's material between the planes, integrated
    double volume_difference = 0.0;    // vol(prism xor material) / vol(prism)
    bool meets_volume_difference = true;
    double unsupported_area_mm2 = 0.0;  // footprint outside the support below (see header)
    // Where that is: the footprint's part outside the support, on `lower`, in
    // PlaneFrame(lower.normal) coordinates; its area is unsupported_area_mm2. Empty when supported.
    Regions2 unsupported;
    int axis_node = -1;  // the guide node nearest to axis_point, -1 when the guide has none
    Eigen::Vector3d axis_point = Eigen::Vector3d::Zero();  // P_upper, on the guide
    int tries = 0;  // candidate planes evaluated before this one was accepted

    // The 3-D loops of region r on `plane`: outer first, then holes.
    std::vector<std::vector<Eigen::Vector3d>> loops_3d(std::size_t r) const;
    // The same for region r of `unsupported`, on `lower`.
    std::vector<std::vector<Eigen::Vector3d>> unsupported_loops_3d(std::size_t r) const;
    // Deposit thickness (distance along plane.normal down to `lower`) under a point of `plane`.
    double thickness_at(const Eigen::Vector3d& point_on_plane) const;
};

// Slices one component. Throws mas::Error: InvalidArgument for bad params, a null mesh, a base
// plane with no material above it, a component thinner than min_layer_mm along its build
// direction or built further than max_tilt_deg from +Z; OpenMesh for a mesh that is not a closed
// surface; GeometryFailure when strict and a layer misses the volumetric bound; whatever `progress`
// throws (see Progress.hpp: checked between candidate planes; after each layer, the material sliced
// so far over the mesh's volume).
std::vector<Layer> slice_component(const ComponentSlicingInput& input, const LayerParams& params,
                                   const Progress& progress = {});

// Unsupported area up to this counts as none, for a footprint of `footprint_mm2`: a thousandth of
// it, the noise between two cuts of the tessellation. The slicer's support check and the build
// order both use it.
inline double negligible_unsupported_mm2(double footprint_mm2) { return 1e-3 * footprint_mm2; }

// What of a component would stand on nothing when it is started: its footprint, the section just
// above its base plane (Eq. 6's offset), and the part of it outside the sections of `support` (the
// meshes deposited before it) just below the plane, grown by min_layer x tan(overhang_angle).
// What the build order minimises.
struct BaseSupport {
    double footprint_area_mm2 = 0.0;
    double unsupported_area_mm2 = 0.0;
};
BaseSupport base_support(const TriangleMesh& component, const Plane& base,
                         const std::vector<const TriangleMesh*>& support,
                         const LayerParams& params);

// The part of `upper`'s footprint outside `lower`'s region grown by `allowance_mm`: upper's region
// moved back along its own normal onto its lower plane (lower's top), then both seen along
// lower's normal; in PlaneFrame(lower.plane.normal) coordinates. The support check above, exposed
// for tests and for checking any two layers; unsupported_area is its area.
Regions2 unsupported_regions(const Layer& upper, const Layer& lower, double allowance_mm);
double unsupported_area(const Layer& upper, const Layer& lower, double allowance_mm);

// The thickness bands of unsupported_regions_sloped, mm.
inline constexpr double kSlopedAllowanceBandMm = 0.05;

// The support check the slicer reports: unsupported_regions with the allowance following the
// upper layer's thickness along its footprint. Where the layer is t thick, its footprint is
// supported within t x slope (tan(overhang_angle)) of the lower region: a layer between two
// planes that are not parallel (a wedge) may overhang more on its thick side than on its thin
// one, as a wall leaning at the overhang angle does. The thickness is taken in bands of
// kSlopedAllowanceBandMm, each at its thinnest, so the allowance falls short of the local one by
// less than kSlopedAllowanceBandMm x slope; it is never less than the min thickness x slope.
Regions2 unsupported_regions_sloped(const Layer& upper, const Layer& lower, double slope);

}  // namespace mas
