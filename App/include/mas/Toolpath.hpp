// Deposition paths of one layer in 3-D: the 2-D bead paths of Paths.hpp laid on the layer's plane,
// each point with the tool axis (the layer's normal, unless the nozzle leans: Nozzle.hpp) and the
// deposit thickness under it, joined by travel moves. The input of the build sequence and the
// post-processor.
#pragma once
#include <Eigen/Core>
#include <optional>
#include <vector>

#include "mas/Paths.hpp"
#include "mas/Slicing.hpp"

namespace mas {

struct ToolPath {
    enum class Kind { Travel, Contour, Infill, CentreLine };
    Kind kind = Kind::Travel;
    int region = -1;                      // the layer region it belongs to (-1 for travel)
    std::vector<Eigen::Vector3d> points;  // mm, on the layer's plane; closed loops repeat the start
    std::vector<double> thickness_mm;     // deposit thickness under each point (see Layer)
    bool deposit() const { return kind != Kind::Travel; }
};

// "travel", "contour", "infill", "centre_line".
const char* to_string(ToolPath::Kind kind);

// A travel move from `from` to `to` (nothing deposited under it).
ToolPath travel_move(const Eigen::Vector3d& from, const Eigen::Vector3d& to);

struct LayerToolpaths {
    // Every point's: the layer's normal (the build sequence may lean it, Nozzle.hpp).
    Eigen::Vector3d tool_axis = Eigen::Vector3d::UnitZ();
    std::vector<ToolPath> paths;            // in order: a travel move before every deposit path
    std::vector<int> centre_line_regions;   // regions narrower than a bead: one centre-line pass
    std::vector<UnfilledFeature> unfilled;  // too small even for that (2-D, layer frame)
    double deposit_length_mm = 0.0;
    double travel_length_mm = 0.0;
    double uncovered_area_mm2 = -1.0;  // -1 unless params.measure_coverage
};

// The paths of `layer`; `layer_index` counts layers over the whole build (raster angle, seam).
// `from` is where the head is (the previous layer's last point): the first travel starts there;
// without it the layer starts at its first deposit path. `progress`: as plan_layer_paths'.
// `frame_deg` is the part's frame (CentroidalAxis::params.frame_deg, axis_frame_deg()): the paths
// are planned in the layer's plane frame (PlaneFrame) of the part turned by -frame_deg about Z,
// and turned back, so that rasters and seams keep their angles to the part's sides, and the paths
// of a part placed turned on the plate are its paths turned (0: the document's frame, the layer's
// own). Throws mas::Error(InvalidArgument) for a frame that is not finite.
LayerToolpaths plan_toolpaths(const Layer& layer, int layer_index, const PathParams& params,
                              const std::optional<Eigen::Vector3d>& from = std::nullopt,
                              const Progress& progress = {}, double frame_deg = 0.0);

}  // namespace mas
