// Private to the engine (never included by a public header): conversion between the engine's
// millimetre polygons and Clipper's integer paths. Coordinates are snapped to an integer grid of
// kScale units per mm.
#pragma once

#include <clipper.hpp>
#include <cmath>

#include "mas/Error.hpp"
#include "mas/Polygon2.hpp"

namespace mas::clipper_convert {

// 1e-5 mm grid: exact enough for any deposition geometry, and parts up to ~15 m stay inside
// Clipper's fast 32-bit-safe range (1.5e9 units) so its 64-bit products never overflow.
constexpr double kScale = 1e5;

inline ClipperLib::IntPoint to_int(const Eigen::Vector2d& p) {
    if (!p.allFinite())
        throw Error(ErrorCode::NonFiniteCoordinate,
                    "polygon point has NaN or infinite coordinates");
    constexpr double limit = 1e18;
    if (std::abs(p.x() * kScale) > limit || std::abs(p.y() * kScale) > limit)
        throw Error(ErrorCode::InvalidArgument, "polygon coordinates are too large");
    return {static_cast<ClipperLib::cInt>(std::llround(p.x() * kScale)),
            static_cast<ClipperLib::cInt>(std::llround(p.y() * kScale))};
}

inline Eigen::Vector2d to_mm(const ClipperLib::IntPoint& p) {
    return {double(p.X) / kScale, double(p.Y) / kScale};
}

inline ClipperLib::Path to_path(const Polygon2& polygon) {
    ClipperLib::Path path;
    path.reserve(polygon.points.size());
    for (const auto& p : polygon.points) path.push_back(to_int(p));
    return path;
}

// A region's loops with the orientation the region model implies (CCW outer, CW holes), whatever
// the caller stored, so that the non-zero fill rule reads holes as holes.
inline void append_paths(const Region2& region, ClipperLib::Paths& paths) {
    paths.push_back(to_path(region.outer));
    if (!ClipperLib::Orientation(paths.back())) ClipperLib::ReversePath(paths.back());
    for (const auto& h : region.holes) {
        paths.push_back(to_path(h));
        if (ClipperLib::Orientation(paths.back())) ClipperLib::ReversePath(paths.back());
    }
}

inline ClipperLib::Paths to_paths(const Regions2& regions) {
    ClipperLib::Paths paths;
    for (const auto& r : regions) append_paths(r, paths);
    return paths;
}

inline Polygon2 from_path(const ClipperLib::Path& path) {
    Polygon2 polygon;
    polygon.points.reserve(path.size());
    for (const auto& p : path) polygon.points.push_back(to_mm(p));
    return polygon;
}

// Whether Clipper nested a closed result as its loops lie: no hole larger than its outer loop
// (PolygonBoolean.cpp).
bool nested_right(const ClipperLib::PolyNode& node);

// The regions of a Boolean's or an offset's closed result (PolygonBoolean.cpp): each outer loop
// with its holes, islands inside holes regions of their own; nested again by containment where
// Clipper nested them wrongly (not nested_right).
Regions2 regions_of(const ClipperLib::PolyTree& tree);

}  // namespace mas::clipper_convert
