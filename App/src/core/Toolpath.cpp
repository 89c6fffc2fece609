// Deposition paths of a layer in 3-D (see Toolpath.hpp).
#include "mas/Toolpath.hpp"

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

LayerToolpaths plan_toolpaths(const Layer& layer, int layer_index, const PathParams& params,
                              const std::optional<Eigen::Vector3d>& from,
                              const Progress& progress) {
    const PlaneFrame frame(layer.plane.normal);
    const Eigen::Vector2d start =
        from
            ? frame.to_2d(*from)
            : (layer.regions.empty() ? Eigen::Vector2d::Zero()
                                     : Eigen::Vector2d(layer.regions.front().outer.points.front()));
    const LayerPaths2 planned =
        plan_layer_paths(layer.regions, params, layer_index, start, progress);

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
