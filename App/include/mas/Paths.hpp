// Deposition paths in one layer (the bead paths a deposition head follows, after the slicing of
// paper Sec. 4.2): contour passes offset from the layer's outline, then infill, in the layer's 2-D
// frame. Clipper (behind Polygon2.hpp) does the offsets and the clipping.
//
// Geometry, with w = bead_width_mm and s = w (1 - overlap) the distance between neighbouring bead
// centres:
// - Contour i (i = 0 .. contour_count - 1) runs along the region offset inwards by w/2 + i s: its
//   bead's outer edge lies on the outline for i = 0. Outer loops run counter-clockwise, holes'
//   contours clockwise (the same side of the bead faces the material every time).
// - Infill fills what is left: the region offset inwards by w/2 + contour_count s holds the bead
//   centres of the infill (so its first bead overlaps the innermost contour by `overlap`).
//   Raster: straight lines at most s apart at angle raster_angle_deg + layer_index x
//   raster_angle_step_deg to the frame's u axis, clipped to that area, one path per piece (a
//   line along every edge of the area parallel to them; the outermost lines overlap x w / 2
//   inside the area's extent across them when there are contours, on its edges when not; the
//   others spread evenly in between).
//   Contour-parallel: further offsets s apart until nothing is left.
// - A region (or what remains of one inside its contours) narrower than one bead, so that the
//   offset by w/2 leaves nothing, gets a single centre-line pass: an open polyline along its
//   middle (a closed one around a narrow ring). So does a thin part of a wider one that its
//   beads cannot enter (a tail narrower than a bead), and a gap the raster leaves at least w/4
//   wide (beside an edge at a shallow angle to the lines). Anything smaller still (no centre line
//   longer than min_feature_mm) is listed in LayerPaths2::unfilled, never silently dropped; only
//   slivers under w x arc_tolerance_mm and the raster's scallops under w^2 / 4 are left to
//   uncovered_area_mm2 alone.
// - Order: regions and the paths inside them go nearest-next from `start` (open paths may be
//   run in either direction); within a region the contours first, each loop only after the one
//   around it (so an outline's contours go outside in), then the infill. A closed contour (or any
//   closed path) starts (its seam) at its vertex closest to the direction seam_angle(layer_index)
//   from its own centroid, a golden-angle step per layer, so that seams do not stack up layer
//   after layer.
#pragma once
#include <Eigen/Core>
#include <vector>

#include "mas/Polygon2.hpp"
#include "mas/Progress.hpp"

namespace mas {

enum class InfillPattern {
    Raster,   // parallel lines, angle alternating from layer to layer
    Contour,  // contour-parallel offsets until the region is full
    None,     // contours only
};

// "raster", "contour", "none"; the inverse throws mas::Error(InvalidArgument) on another name.
const char* to_string(InfillPattern pattern);
InfillPattern infill_pattern_from_string(const char* name);

struct PathParams {
    double bead_width_mm = 1.0;  // width of one deposited bead, > 0
    double overlap = 0.15;       // fraction of a bead shared with its neighbour, in [0, 1)
    int contour_count = 2;       // contour passes around every outline, >= 0
    InfillPattern infill = InfillPattern::Raster;
    double raster_angle_deg = 0.0;        // raster direction of layer 0, to the frame's u axis
    double raster_angle_step_deg = 90.0;  // added to it for every following layer
    double min_feature_mm = 0.0;  // centre lines shorter than this are reported, not run; 0 = w/2
    double arc_tolerance_mm = 0.01;  // chordal tolerance of rounded offset corners
    // Also measure how much of each region the beads leave uncovered (LayerPaths2::
    // uncovered_area_mm2): the union of every deposit path thickened by w/2, subtracted from the
    // regions. Costs one Clipper offset of the open paths and one difference.
    bool measure_coverage = false;
};

inline constexpr double kMaxBeadWidthMm = 1000.0;

// Throws mas::Error(InvalidArgument) naming the parameter: a bead width that is not positive and
// finite or over kMaxBeadWidthMm, an overlap outside [0, 1), a negative contour count, a non-finite
// angle, a negative min_feature_mm or a non-positive arc tolerance.
void validate(const PathParams& params);

struct Path2 {
    enum class Kind {
        Contour,     // an offset of the outline (closed)
        Infill,      // a raster line or a contour-parallel infill loop
        CentreLine,  // the single pass along a region narrower than one bead (open; closed
                     // around a narrow ring)
    };
    Kind kind = Kind::Contour;
    int region = -1;      // index into the regions given to plan_layer_paths
    bool closed = false;  // a closed loop: the last point joins the first (not repeated)
    std::vector<Eigen::Vector2d> points;  // in deposition order, mm
};

const char* to_string(Path2::Kind kind);  // "contour", "infill", "centre_line"

// Something in a layer that gets no bead: a region, or a piece left inside its contours, that is
// too small even for a centre-line pass.
struct UnfilledFeature {
    int region = -1;
    double area_mm2 = 0.0;
    Eigen::Vector2d centroid = Eigen::Vector2d::Zero();
};

struct LayerPaths2 {
    std::vector<Path2>
        paths;  // deposition order; travel goes straight from one end to the next start
    std::vector<int> centre_line_regions;  // regions (indices) that got a centre-line pass
    std::vector<UnfilledFeature> unfilled;
    double deposit_length_mm = 0.0;    // along every path (closed ones including the closing edge)
    double travel_length_mm = 0.0;     // from `start` to the first path and between paths
    double uncovered_area_mm2 = -1.0;  // with params.measure_coverage; -1 when not measured
};

// Golden-angle seam direction for a layer, radians: layer_index x 137.5077... degrees, mod 2 pi.
double seam_angle(int layer_index);

// The paths of one layer whose deposited area is `regions` (a layer's regions in its plane
// frame). `layer_index` counts layers of the whole build and sets the raster angle and the seam;
// `start` is where the head is when the layer begins (the end of the previous layer's last path).
// Throws mas::Error(InvalidArgument) for invalid params (see validate). `progress` is checked
// between offset levels and while ordering (a fine bead on a large layer takes seconds), so that
// the caller may stop the work; it reports no fraction.
LayerPaths2 plan_layer_paths(const Regions2& regions, const PathParams& params, int layer_index,
                             const Eigen::Vector2d& start, const Progress& progress = {});

}  // namespace mas
