// Polygon Booleans and offsets through Clipper (Debian libpolyclipping, Clipper 6.4). Coordinates
// are snapped to an integer grid of kScale units per mm; results come back as regions with holes.
#include <clipper.hpp>
#include <cmath>

#include "ClipperConvert.hpp"
#include "mas/Error.hpp"
#include "mas/Polygon2.hpp"

namespace mas {

namespace {

using clipper_convert::from_path;
using clipper_convert::kScale;
using clipper_convert::to_paths;

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
    // One Clipper per thread, cleared before each use: its internal lists keep their memory,
    // which saves many allocations on the axis' thousands of small Booleans. (A Clipper's
    // result does not depend on what it did before; Clear() drops all its paths.)
    thread_local ClipperLib::Clipper clipper;
    clipper.Clear();
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
