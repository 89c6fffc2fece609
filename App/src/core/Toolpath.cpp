// Deposition paths of a layer in 3-D (see Toolpath.hpp).
#include "mas/Toolpath.hpp"

#include <Eigen/Geometry>
#include <cmath>

#include "mas/Angles.hpp"
#include "mas/Error.hpp"

namespace mas {

const char* to_string(ToolPath::Kind kind) {
    switch (kind) {
        case ToolPath::Kind::Travel:
            return "travel";
        case ToolPath::Kind::Contour:
            return "contour";
        case ToolPath::Kind::Infill:
            return "infill";
        case ToolPath::Kind::CentreLine:
            return "centre_line";
    }
    return "travel";
}

ToolPath travel_move(const Eigen::Vector3d& from, const Eigen::Vector3d& to) {
    ToolPath travel;
    travel.points = {from, to};
    travel.thickness_mm = {0.0, 0.0};
    return travel;
}

namespace {

// The in-plane angle (radians, from frame.u towards frame.v) of the u axis that frame.normal's
// plane frame has in the part's frame: PlaneFrame of the normal turned by -frame_deg about Z, its
// u turned back. (A vertical layer's is 0 or 180 degrees: its u is horizontal in either frame.)
double part_frame_turn(const PlaneFrame& frame, double frame_deg) {
    const Eigen::AngleAxisd turn(frame_deg * kPi / 180.0, Eigen::Vector3d::UnitZ());
    const Eigen::Vector3d u = turn * PlaneFrame(turn.inverse() * frame.normal).u;
    return std::atan2(u.dot(frame.v), u.dot(frame.u));
}

// `regions` (2-D, in a frame) rotated by `into`: their coordinates in the frame turned by its
// inverse.
Regions2 turned_in_plane(const Regions2& regions, const Eigen::Rotation2Dd& into) {
    Regions2 out = regions;
    for (Region2& r : out) {
        for (Eigen::Vector2d& q : r.outer.points) q = into * q;
        for (Polygon2& h : r.holes)
            for (Eigen::Vector2d& q : h.points) q = into * q;
    }
    return out;
}

}  // namespace

LayerToolpaths plan_toolpaths(const Layer& layer, int layer_index, const PathParams& params,
                              const std::optional<Eigen::Vector3d>& from, const Progress& progress,
                              double frame_deg) {
    if (!std::isfinite(frame_deg))
        throw Error(ErrorCode::InvalidArgument,
                    "plan_toolpaths: the part's frame must be a finite angle, got " +
                        format_number(frame_deg));
    const PlaneFrame frame(layer.plane.normal);
    const Eigen::Vector2d start =
        from
            ? frame.to_2d(*from)
            : (layer.regions.empty() ? Eigen::Vector2d::Zero()
                                     : Eigen::Vector2d(layer.regions.front().outer.points.front()));
    // Planned in the layer's frame turned into the part's (rasters and seams at their angles to
    // its sides), then turned back; in the document's frame, as they are.
    const double angle = frame_deg == 0.0 ? 0.0 : part_frame_turn(frame, frame_deg);
    LayerPaths2 planned;
    if (angle == 0.0) {
        planned = plan_layer_paths(layer.regions, params, layer_index, start, progress);
    } else {
        const Eigen::Rotation2Dd into(-angle), back(angle);
        planned = plan_layer_paths(turned_in_plane(layer.regions, into), params, layer_index,
                                   into * start, progress);
        for (Path2& p : planned.paths)
            for (Eigen::Vector2d& q : p.points) q = back * q;
        for (UnfilledFeature& f : planned.unfilled) f.centroid = back * f.centroid;
    }

    LayerToolpaths out;
    out.tool_axis = layer.plane.normal;
    out.centre_line_regions = planned.centre_line_regions;
    out.unfilled = planned.unfilled;
    out.deposit_length_mm = planned.deposit_length_mm;
    out.uncovered_area_mm2 = planned.uncovered_area_mm2;
    auto lift = [&](const Eigen::Vector2d& q, ToolPath& path) {
        const Eigen::Vector3d p = frame.to_3d(q, layer.plane);
        path.points.push_back(p);
        path.thickness_mm.push_back(layer.thickness_at(p));
    };
    bool has_head = from.has_value();
    Eigen::Vector3d head = from.value_or(Eigen::Vector3d::Zero());
    for (const Path2& p : planned.paths) {
        if (p.points.empty()) continue;
        ToolPath path;
        switch (p.kind) {
            case Path2::Kind::Contour:
                path.kind = ToolPath::Kind::Contour;
                break;
            case Path2::Kind::Infill:
                path.kind = ToolPath::Kind::Infill;
                break;
            case Path2::Kind::CentreLine:
                path.kind = ToolPath::Kind::CentreLine;
                break;
        }
        path.region = p.region;
        for (const Eigen::Vector2d& q : p.points) lift(q, path);
        if (p.closed && p.points.size() > 1) lift(p.points.front(), path);
        if (has_head && (head - path.points.front()).norm() > 0.0) {
            out.travel_length_mm += (path.points.front() - head).norm();
            out.paths.push_back(travel_move(head, path.points.front()));
        }
        head = path.points.back();
        has_head = true;
        out.paths.push_back(std::move(path));
    }
    return out;
}

}  // namespace mas
