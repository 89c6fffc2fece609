// Polygon Booleans and offsets through Clipper (Debian libpolyclipping, Clipper 6.4). Coordinates
// are snapped to an integer grid of kScale units per mm; results come back as regions with holes.
#include <clipper.hpp>
#include <cmath>
#include <limits>

#include "mas/Error.hpp"
#include "mas/Polygon2.hpp"

namespace mas {

namespace {

// 1e-5 mm grid: exact enough for any deposition geometry, and parts up to ~15 m stay inside
// Clipper's fast 32-bit-safe range (1.5e9 units) so its 64-bit products never overflow.
constexpr double kScale = 1e5;

ClipperLib::IntPoint to_int(const Eigen::Vector2d& p) {
    if (!p.allFinite())
        throw Error(ErrorCode::NonFiniteCoordinate,
                    "polygon point has NaN or infinite coordinates");
    constexpr double limit = 1e18;
    if (std::abs(p.x() * kScale) > limit || std::abs(p.y() * kScale) > limit)
        throw Error(ErrorCode::InvalidArgument, "polygon coordinates are too large");
    return {static_cast<ClipperLib::cInt>(std::llround(p.x() * kScale)),
            static_cast<ClipperLib::cInt>(std::llround(p.y() * kScale))};
}

ClipperLib::Path to_path(const Polygon2& polygon) {
    ClipperLib::Path path;
    path.reserve(polygon.points.size());
    for (const auto& p : polygon.points) path.push_back(to_int(p));
    return path;
}

ClipperLib::Paths to_paths(const Regions2& regions) {
    ClipperLib::Paths paths;
    for (const auto& r : regions) {
        paths.push_back(to_path(r.outer));
        // Force the orientation the region model implies (CCW outer, CW holes), whatever the
        // caller stored, so that the non-zero fill rule reads holes as holes.
        if (!ClipperLib::Orientation(paths.back())) ClipperLib::ReversePath(paths.back());
        for (const auto& h : r.holes) {
            paths.push_back(to_path(h));
            if (ClipperLib::Orientation(paths.back())) ClipperLib::ReversePath(paths.back());
        }
    }
    return paths;
}

Polygon2 from_path(const ClipperLib::Path& path) {
    Polygon2 polygon;
    polygon.points.reserve(path.size());
    for (const auto& p : path)
        polygon.points.emplace_back(double(p.X) / kScale, double(p.Y) / kScale);
    return polygon;
}

// Outer nodes of a PolyTree with their holes; islands inside holes become regions of their own.
void collect(const ClipperLib::PolyNode& node, Regions2& out) {
    for (const ClipperLib::PolyNode* child : node.Childs) {
        if (child->IsHole()) continue;
        Region2 region;
        region.outer = from_path(child->Contour);
        for (const ClipperLib::PolyNode* hole : child->Childs) {
            region.holes.push_back(from_path(hole->Contour));
            collect(*hole, out);  // islands inside the hole
        }
        out.push_back(std::move(region));
    }
}

Regions2 run(ClipperLib::ClipType type, const Regions2& a, const Regions2& b) {
    ClipperLib::Clipper clipper;
    clipper.AddPaths(to_paths(a), ClipperLib::ptSubject, true);
    clipper.AddPaths(to_paths(b), ClipperLib::ptClip, true);
    ClipperLib::PolyTree tree;
    if (!clipper.Execute(type, tree, ClipperLib::pftNonZero, ClipperLib::pftNonZero))
        throw Error(ErrorCode::GeometryFailure, "polygon Boolean operation failed");
    Regions2 out;
    collect(tree, out);
    return out;
}

}  // namespace

Regions2 intersection(const Regions2& a, const Regions2& b) {
    if (a.empty() || b.empty()) return {};
    return run(ClipperLib::ctIntersection, a, b);
}

Regions2 difference(const Regions2& a, const Regions2& b) {
    if (a.empty()) return {};
    return run(ClipperLib::ctDifference, a, b);
}

Regions2 union_of(const Regions2& a, const Regions2& b) { return run(ClipperLib::ctUnion, a, b); }

Regions2 offset(const Regions2& regions, double delta_mm, JoinType join, double arc_tolerance_mm) {
    if (!std::isfinite(delta_mm))
        throw Error(ErrorCode::InvalidArgument, "offset distance must be a finite number");
    if (!(arc_tolerance_mm > 0.0) || !std::isfinite(arc_tolerance_mm))
        throw Error(ErrorCode::InvalidArgument, "arc tolerance must be positive");
    const ClipperLib::JoinType jt = join == JoinType::Miter    ? ClipperLib::jtMiter
                                    : join == JoinType::Square ? ClipperLib::jtSquare
                                                               : ClipperLib::jtRound;
    ClipperLib::ClipperOffset off(2.0, arc_tolerance_mm * kScale);
    off.AddPaths(to_paths(regions), jt, ClipperLib::etClosedPolygon);
    ClipperLib::PolyTree tree;
    off.Execute(tree, delta_mm * kScale);
    Regions2 out;
    collect(tree, out);
    return out;
}

}  // namespace mas
