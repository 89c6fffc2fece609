// Polygon Booleans and offsets through Clipper (Debian libpolyclipping, Clipper 6.4). Coordinates
// are snapped to an integer grid of kScale units per mm; results come back as regions with holes.
#include <algorithm>
#include <clipper.hpp>
#include <cmath>
#include <numeric>

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

// Every contour under `node`.
void gather(const ClipperLib::PolyNode& node, std::vector<Polygon2>& loops) {
    for (const ClipperLib::PolyNode* child : node.Childs) {
        loops.push_back(from_path(child->Contour));
        gather(*child, loops);
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
    return clipper_convert::regions_of(tree);
}

}  // namespace

// Clipper 6.4 can nest its result wrongly on near-degenerate input: a difference leaving a
// hairline of 4e-6 mm^2 beside a 299 mm^2 region came back as that hairline, an outer loop,
// holding the region as its hole (the region's area then negative: the axis' march over a hub
// with twisted blades ended there, a quarter of the part unsearched). Nested right: no hole
// larger than its outer loop, at any depth (read on the tree's integer areas).
bool clipper_convert::nested_right(const ClipperLib::PolyNode& node) {
    for (const ClipperLib::PolyNode* child : node.Childs) {
        if (child->IsHole()) continue;
        const double outer = std::abs(ClipperLib::Area(child->Contour));
        for (const ClipperLib::PolyNode* hole : child->Childs)
            if (std::abs(ClipperLib::Area(hole->Contour)) > outer || !nested_right(*hole))
                return false;
    }
    return true;
}

// Otherwise the tree is nested again by containment: a loop inside an even number of larger
// loops is an outer loop (made counter-clockwise), inside an odd number a hole (clockwise) of
// the smallest of them. A loop is inside another when most of up to 9 of its vertices, spread
// along it, are (a vertex on the other's outline may go either way).
Regions2 clipper_convert::regions_of(const ClipperLib::PolyTree& tree) {
    Regions2 out;
    if (nested_right(tree)) {
        collect(tree, out);
        return out;
    }
    std::vector<Polygon2> loops;
    gather(tree, loops);
    const std::size_t n = loops.size();
    std::vector<double> size(n);
    std::vector<Eigen::AlignedBox2d> box(n);
    for (std::size_t i = 0; i < n; ++i) {
        size[i] = std::abs(signed_area(loops[i]));
        for (const auto& p : loops[i].points) box[i].extend(p);
    }
    std::vector<std::size_t> order(n);
    std::iota(order.begin(), order.end(), std::size_t(0));
    std::stable_sort(order.begin(), order.end(),
                     [&](std::size_t a, std::size_t b) { return size[a] > size[b]; });
    const auto within = [&](std::size_t inner, std::size_t outer) {
        if (!box[outer].contains(box[inner])) return false;
        const auto& pts = loops[inner].points;
        const std::size_t samples = std::min<std::size_t>(pts.size(), 9);
        const Region2 holder{loops[outer], {}};
        std::size_t in = 0;
        for (std::size_t s = 0; s < samples; ++s)
            in += contains(holder, pts[s * pts.size() / samples]);
        return 2 * in > samples;
    };
    std::vector<int> depth(n, 0), region(n, -1);
    std::vector<std::size_t> parent(n, n);
    for (std::size_t k = 0; k < n; ++k)
        for (std::size_t m = k; m-- > 0;)  // the smallest larger loop holding it
            if (within(order[k], order[m])) {
                parent[order[k]] = order[m];
                depth[order[k]] = depth[order[m]] + 1;
                break;
            }
    out.clear();
    for (const std::size_t i : order) {  // a loop's parent before it
        Polygon2 loop = std::move(loops[i]);
        const bool hole = depth[i] % 2 == 1;
        if ((signed_area(loop) < 0.0) != hole) std::reverse(loop.points.begin(), loop.points.end());
        if (hole) {
            out[std::size_t(region[parent[i]])].holes.push_back(std::move(loop));
        } else {
            region[i] = int(out.size());
            out.push_back(Region2{std::move(loop), {}});
        }
    }
    return out;
}

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
    return clipper_convert::regions_of(tree);
}

}  // namespace mas
