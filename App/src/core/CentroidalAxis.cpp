// Centroidal axis search (paper Sec. 3.2, Fig. 9): branch-first marches of cross-sections along
// +-X, +-Y, +-Z with swept-slab bookkeeping for B = B - Bs. See the header for the readings chosen.
#include "mas/CentroidalAxis.hpp"

#include <tbb/concurrent_vector.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>
#include <tbb/task_group.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>
#include <exception>
#include <map>
#include <memory>
#include <mutex>
#include <numeric>
#include <optional>
#include <sstream>
#include <thread>

#include "SectionGrid.hpp"
#include "mas/Angles.hpp"
#include "mas/Error.hpp"
#include "mas/Progress.hpp"
#include "mas/Section.hpp"
#include "mas/Slicing.hpp"

namespace mas {

namespace {

// The point of the region's boundary (outer loop or holes) nearest to `point`.
Eigen::Vector2d nearest_boundary_point(const Region2& region, const Eigen::Vector2d& point) {
    double best = std::numeric_limits<double>::infinity();
    Eigen::Vector2d nearest = point;
    auto edges = [&](const Polygon2& loop) {
        const auto& p = loop.points;
        for (std::size_t i = 0, j = p.size() - 1; i < p.size(); j = i++) {
            const Eigen::Vector2d e = p[i] - p[j];
            const double len2 = e.squaredNorm();
            const double t = len2 > 0.0 ? std::clamp((point - p[j]).dot(e) / len2, 0.0, 1.0) : 0.0;
            const Eigen::Vector2d q = p[j] + t * e;
            if ((q - point).norm() < best) {
                best = (q - point).norm();
                nearest = q;
            }
        }
    };
    edges(region.outer);
    for (const auto& h : region.holes) edges(h);
    return nearest;
}

// How far a flat underside may overhang the layer under it and still be laid by layers at
// slicing's defaults (Slicing.hpp: the thickest layer, 2 mm, times tan(overhang_angle), 45
// degrees): 2 mm. A collar reaching out no more than that all round (within a twentieth, more
// than a section's chords fall short of a round column) is a shoulder its column's layers lay.
double laid_overhang_mm() {
    const LayerParams defaults;
    return defaults.max_layer_mm * overhang_allowance(defaults);
}

}  // namespace

double extent_along(const Region2& region, const Eigen::Vector3d& normal, double offset,
                    const Eigen::Vector3d& dir) {
    const PlaneFrame frame(normal);
    const Plane plane{normal * offset, normal};
    double t = -std::numeric_limits<double>::infinity();
    for (const auto& q : region.outer.points) t = std::max(t, dir.dot(frame.to_3d(q, plane)));
    return t;
}

std::vector<std::size_t> merged_lowest_first(const CentroidalAxis& axis) {
    std::vector<std::size_t> merged;
    for (std::size_t b = 0; b < axis.branches.size(); ++b)
        if (axis.branches[b].merged_into >= 0 && !axis.branches[b].nodes.empty())
            merged.push_back(b);
    const auto last_along = [&](std::size_t b) {
        const AxisBranch& br = axis.branches[b];
        return br.direction.normalized().dot(axis.nodes[std::size_t(br.nodes.back())].position);
    };
    std::stable_sort(merged.begin(), merged.end(),
                     [&](std::size_t x, std::size_t y) { return last_along(x) < last_along(y); });
    return merged;
}

BridgeGap bridge_gap(const CentroidalAxis& axis, std::size_t b, std::size_t m,
                     const Eigen::Vector3d& D, const Eigen::Matrix3d& frame) {
    BridgeGap gap;
    const AxisBranch &br = axis.branches[b], &into = axis.branches[m];
    if (br.nodes.empty() || into.nodes.empty()) return gap;
    gap.to = br.nodes.back();
    const Eigen::Vector3d pb = axis.nodes[std::size_t(gap.to)].position;
    const double sb = D.dot(pb);
    for (const int n : into.nodes)
        if (gap.from < 0 || std::abs(D.dot(axis.nodes[std::size_t(n)].position) - sb) <
                                std::abs(D.dot(axis.nodes[std::size_t(gap.from)].position) - sb))
            gap.from = n;
    gap.across = pb - axis.nodes[std::size_t(gap.from)].position;
    gap.across -= D * D.dot(gap.across);
    for (int k = 0; k < 3; ++k) {
        const Eigen::Vector3d e = frame * Eigen::Vector3d::Unit(k);
        const Eigen::Vector3d w = e - D * D.dot(e);
        if (w.norm() < 0.5) continue;
        const Eigen::Vector3d way =
            gap.across.dot(w) >= 0.0 ? w.normalized() : Eigen::Vector3d(-w.normalized());
        if (gap.way.isZero() || way.dot(gap.across) > gap.way.dot(gap.across)) gap.way = way;
    }
    return gap;
}

Eigen::Vector3d bridge_direction(const Eigen::Vector3d& D, const Eigen::Vector3d& across,
                                 double max_tilt_deg,
                                 const std::function<double(const Eigen::Vector3d&)>& overhang) {
    const double along_D = overhang(D);
    if (!(along_D > 0.0)) return Eigen::Vector3d::Zero();
    Eigen::Vector3d d = Eigen::Vector3d::Zero();
    double least = 0.5 * along_D;
    for (const Eigen::Vector3d& way : {across, Eigen::Vector3d(-across)}) {
        const Eigen::Vector3d dw = (D + way).normalized();
        if (tilt_from_plate_deg(dw) > max_tilt_deg + 1e-9) continue;
        const double a = overhang(dw);
        if (d.isZero() ? a <= least : a < least - 1e-9 * (1.0 + least)) {
            d = dw;
            least = a;
        }
    }
    return d;
}

int bridge_node(const CentroidalAxis& axis, const Eigen::Vector3d& D, double s, double tol,
                const Eigen::Vector3d& middle) {
    int past = -1;
    for (const bool along : {true, false})
        for (std::size_t n = 0; n < axis.nodes.size() && (along || past < 0); ++n) {
            const AxisNode& node = axis.nodes[n];
            const double sn = D.dot(node.position);
            if (node.branch < 0 || sn <= s + tol || sn > s + 2.0 * axis.params.step_mm ||
                axis.branches[std::size_t(node.branch)].direction.normalized().isApprox(D, 1e-9) !=
                    along)
                continue;
            if (past < 0 || (node.position - middle).norm() <
                                (axis.nodes[std::size_t(past)].position - middle).norm())
                past = int(n);
        }
    return past;
}

double reach_along(const AxisNode& node, const Eigen::Vector3d& dir) {
    if (node.region.outer.points.empty()) return dir.dot(node.position);
    return extent_along(node.region, node.normal, node.offset, dir);
}

double distance_to_region(const Region2& region, const Eigen::Vector2d& point) {
    if (contains(region, point)) return 0.0;
    return (nearest_boundary_point(region, point) - point).norm();
}

namespace {

using Eigen::Vector2d;
using Eigen::Vector3d;

Vector3d axis_vector(int axis, double sign) {
    Vector3d v = Vector3d::Zero();
    v[axis] = sign;
    return v;
}

int axis_index(const Vector3d& n) {
    int a = 0;
    n.cwiseAbs().maxCoeff(&a);
    return a;
}

// The one of +-X, +-Y, +-Z closest in angle to v (paper Sec. 3.2.1).
Vector3d closest_axis(const Vector3d& v) {
    const int a = axis_index(v);
    return axis_vector(a, v[a] >= 0.0 ? 1.0 : -1.0);
}

// The four directions of +-X, +-Y, +-Z perpendicular to the march n, `first` first.
std::vector<Vector3d> sides_from(const Vector3d& first, const Vector3d& n) {
    std::vector<Vector3d> out{first};
    for (int a = 0; a < 3; ++a)
        for (double sign : {1.0, -1.0}) {
            const Vector3d d = axis_vector(a, sign);
            if (a != axis_index(n) && d != first) out.push_back(d);
        }
    return out;
}

// The regions split at {dir.p = t} (dir perpendicular to the frame's normal): the parts beyond,
// the parts behind. A region wholly on one side is passed on as it is, without a Boolean.
std::pair<Regions2, Regions2> split_at(Regions2 regions, const PlaneFrame& frame,
                                       const Vector3d& dir, double t) {
    const Vector2d d(dir.dot(frame.u), dir.dot(frame.v));  // +-(1, 0) or +-(0, 1)
    std::pair<Regions2, Regions2> out;
    for (auto& r : regions) {
        const Eigen::AlignedBox2d box = bounds(r);
        double lo = std::numeric_limits<double>::infinity(), hi = -lo;
        for (const auto& c : {box.min(), box.max()}) {
            lo = std::min(lo, d.dot(c));
            hi = std::max(hi, d.dot(c));
        }
        if (lo >= t) {
            out.first.push_back(std::move(r));
        } else if (hi <= t) {
            out.second.push_back(std::move(r));
        } else {
            // The half-plane, within a box around the region.
            const Vector2d pad = Vector2d::Constant(1.0 + box.diagonal().norm());
            Vector2d a = box.min() - pad, b = box.max() + pad;
            const int c = std::abs(d.x()) > 0.5 ? 0 : 1;
            if (d[c] > 0.0)
                a[c] = t;
            else
                b[c] = -t;
            const Region2 half{Polygon2{{a, {b.x(), a.y()}, b, {a.x(), b.y()}}}, {}};
            for (auto& piece : intersection({r}, {half})) out.first.push_back(std::move(piece));
            for (auto& piece : difference({r}, {half})) out.second.push_back(std::move(piece));
        }
    }
    return out;
}

// What one node has swept: its region extruded along `normal` over [h0, h1) (offsets n.p).
struct Slab {
    Vector3d normal;
    double h0 = 0.0, h1 = 0.0;
    Region2 region;  // PlaneFrame(normal) coordinates
    Eigen::AlignedBox3d box;
    int branch = -1;  // the branch whose node swept it (-1: not swept by a node)
};

// The 3-D box of `region` (PlaneFrame(n) coordinates, on the plane at offset `at` along n) swept
// along n over [h0, h1].
Eigen::AlignedBox3d slab_box(const Region2& region, const PlaneFrame& frame, double at, double h0,
                             double h1) {
    const Vector3d& n = frame.normal;
    const Plane plane{n * at, n};
    Eigen::AlignedBox3d box;
    for (const auto& q : region.outer.points) {
        const Vector3d p = frame.to_3d(q, plane);
        box.extend(p + n * (h0 - at));
        box.extend(p + n * (h1 - at));
    }
    return box;
}

// A slab cut by a perpendicular plane: the band [s0, s1] along the slab's axis `ia`, times the
// intervals `t` along the third axis `it`, all on the plane's coordinate `pib` along axis `ib`.
struct Strip {
    double s0 = 0.0, s1 = 0.0;
    std::vector<std::pair<double, double>> t;
};

Region2 oriented(Region2 r) {
    if (signed_area(r.outer) < 0.0) std::reverse(r.outer.points.begin(), r.outer.points.end());
    for (auto& h : r.holes)
        if (signed_area(h) > 0.0) std::reverse(h.points.begin(), h.points.end());
    return r;
}

struct StripAxes {
    int ia, ib, it;
    double pib;
};

StripAxes strip_axes(const Slab& s, const Vector3d& n, double c) {
    const int ib = axis_index(n), ia = axis_index(s.normal);
    return {ia, ib, 3 - ia - ib, c * n[ib]};
}

// The plane {n.p = c} is an axis-aligned line in the perpendicular slab's 2-D frame.
Strip perpendicular_strip(const Slab& s, const StripAxes& ax) {
    const PlaneFrame sf(s.normal);
    const int coord = std::abs(sf.u[ax.ib]) > 0.5 ? 0 : 1;
    const double line = ax.pib * (coord == 0 ? sf.u[ax.ib] : sf.v[ax.ib]);
    const double to_it = coord == 0 ? sf.v[ax.it] : sf.u[ax.it];  // 2-D other coordinate -> it
    const double a0 = s.h0 * s.normal[ax.ia], a1 = s.h1 * s.normal[ax.ia];
    Strip strip{std::min(a0, a1), std::max(a0, a1), {}};
    for (const auto& [w0, w1] : inside_intervals(s.region, coord, line))
        strip.t.emplace_back(std::min(w0 * to_it, w1 * to_it), std::max(w0 * to_it, w1 * to_it));
    std::sort(strip.t.begin(), strip.t.end());
    return strip;
}

// Outlines of stacked strips as few simple polygons: consecutive strips of one branch that each
// hold one interval overlapping the previous one form one band, whose sides run straight from
// each strip's start to the next one's (exact for prisms, closer to the true surface than a
// staircase elsewhere), simplified to `tolerance` like the sections. (Handing Clipper a rectangle
// per strip, all sharing edges, was most of the axis' cost on scanned meshes.)
Regions2 strips_to_regions(std::vector<Strip> strips, const StripAxes& ax, const PlaneFrame& frame,
                           double tolerance) {
    std::sort(strips.begin(), strips.end(),
              [](const Strip& a, const Strip& b) { return a.s0 < b.s0; });
    auto point = [&](double s, double t) {
        Vector3d p;
        p[ax.ia] = s;
        p[ax.it] = t;
        p[ax.ib] = ax.pib;
        return frame.to_2d(p);
    };
    Regions2 out;
    auto emit = [&](const std::vector<std::pair<double, double>>& left,
                    const std::vector<std::pair<double, double>>& right) {
        Polygon2 poly;
        for (const auto& [s, t] : left) poly.points.push_back(point(s, t));
        for (auto it = right.rbegin(); it != right.rend(); ++it)
            poly.points.push_back(point(it->first, it->second));
        if (signed_area(poly) < 0.0) std::reverse(poly.points.begin(), poly.points.end());
        out.push_back(Region2{simplify(poly, tolerance), {}});
    };
    // A corner within `tolerance` (in t) of the line from its side's corner before it to the
    // newest is not kept: the last corner moves on to the newest while the line's slope stays
    // within those that pass within the tolerance of every corner so dropped (intersected as they
    // come). Walls crossed by thousands of slabs, at a step of 0.01 mm, left runs of collinear
    // corners that simplify() below walks once per corner: a hub's axis took 74 s, now 3.7, a
    // crank's at 0.001 mm over 15 minutes; at the derived steps nothing changes.
    struct Side {
        std::vector<std::pair<double, double>> corners;  // (s, t)
        double lo = 0.0, hi = 0.0;  // the slopes from the corner before the last that pass
    };
    auto extend = [tolerance](Side& side, double s, double t) {
        auto& c = side.corners;
        const std::size_t n = c.size();
        if (n >= 2 && s > c[n - 2].first) {
            const auto [as, at] = c[n - 2];
            const double slope = (t - at) / (s - as);
            if (slope >= side.lo && slope <= side.hi) {
                side.lo = std::max(side.lo, (t - tolerance - at) / (s - as));
                side.hi = std::min(side.hi, (t + tolerance - at) / (s - as));
                c.back() = {s, t};
                return;
            }
        }
        if (n >= 1 && s > c[n - 1].first) {
            side.lo = (t - tolerance - c[n - 1].second) / (s - c[n - 1].first);
            side.hi = (t + tolerance - c[n - 1].second) / (s - c[n - 1].first);
        } else {
            side.lo = std::numeric_limits<double>::infinity();  // nothing merges into it
            side.hi = -side.lo;
        }
        c.emplace_back(s, t);
    };
    Side left, right;  // the open band's sides
    double last_s1 = 0.0, last_l = 0.0, last_r = 0.0;
    auto close_band = [&] {
        if (left.corners.empty()) return;
        extend(left, last_s1, last_l);
        extend(right, last_s1, last_r);
        emit(left.corners, right.corners);
        left.corners.clear();
        right.corners.clear();
    };
    for (const auto& strip : strips) {
        if (strip.t.size() != 1) {
            close_band();
            for (const auto& [l, r] : strip.t)
                emit({{strip.s0, l}, {strip.s1, l}}, {{strip.s0, r}, {strip.s1, r}});
            continue;
        }
        const auto [l, r] = strip.t.front();
        const bool continues = !left.corners.empty() && std::abs(strip.s0 - last_s1) <= 1e-9 &&
                               l < last_r && r > last_l;
        if (!continues) close_band();
        extend(left, strip.s0, l);
        extend(right, strip.s0, r);
        last_s1 = strip.s1;
        last_l = l;
        last_r = r;
    }
    close_band();
    return out;
}

// The part of slab `s` lying on the plane {n.p = c}, in PlaneFrame(n) coordinates. All normals
// are axis-aligned: a parallel slab gives its region, a perpendicular one rectangles.
Regions2 slab_cut(const Slab& s, const Vector3d& n, double c, const PlaneFrame& frame) {
    const double along = s.normal.dot(n);
    if (std::abs(along) <= 0.5) {
        const StripAxes ax = strip_axes(s, n, c);
        return strips_to_regions({perpendicular_strip(s, ax)}, ax, frame, 0.0);
    }
    const double h = along > 0 ? c : -c;  // the plane's offset in the slab's terms
    if (h < s.h0 || h >= s.h1) return {};
    if (along > 0) return {s.region};
    // Opposite normals: same plane, mirrored frame.
    const PlaneFrame from(s.normal);
    const Plane plane{s.normal * h, s.normal};
    auto reframe = [&](const Polygon2& p) {
        Polygon2 q;
        for (const auto& x : p.points) q.points.push_back(frame.to_2d(from.to_3d(x, plane)));
        return q;
    };
    Region2 r{reframe(s.region.outer), {}};
    for (const auto& h2 : s.region.holes) r.holes.push_back(reframe(h2));
    return {oriented(std::move(r))};
}

// A region's width on average, mm: twice its area over its outline (a long strip's width).
double mean_width(const Region2& r) { return 2.0 * area(r) / perimeter(r); }

// The regions larger than min_area, largest first (ties in their given order).
Regions2 keep_larger(Regions2 regions, double min_area) {
    std::vector<std::pair<double, std::size_t>> order;  // (area, index): each area computed once
    for (std::size_t i = 0; i < regions.size(); ++i) {
        const double a = area(regions[i]);
        if (a > min_area) order.emplace_back(a, i);
    }
    std::stable_sort(order.begin(), order.end(),
                     [](const auto& a, const auto& b) { return a.first > b.first; });
    Regions2 out;
    out.reserve(order.size());
    for (const auto& [a, i] : order) out.push_back(std::move(regions[i]));
    return out;
}

// `regions` opened by `width`: shrunk by it and grown back, which drops whatever is narrower than
// twice `width` (hairlines and slivers the Booleans leave along outlines) and keeps the rest.
Regions2 opening(const Regions2& regions, double width) {
    return mas::offset(mas::offset(regions, -width, JoinType::Miter), width, JoinType::Miter);
}

// `regions` with each region that joins larger pieces only through necks narrower than twice
// `width` split there: opened (opening()) and cut to that, where the opening leaves two or more
// pieces of over `min_area`; other regions as they are.
Regions2 split_at_necks(const Regions2& regions, double width, double min_area) {
    Regions2 out;
    for (const Region2& r : regions) {
        Regions2 opened = keep_larger(opening({r}, width), min_area);
        if (opened.size() < 2) {
            out.push_back(r);
            continue;
        }
        for (auto& piece : intersection({r}, opened)) out.push_back(std::move(piece));
    }
    return out;
}

// Ten units of the polygon Booleans' grid (PolygonBoolean.cpp snaps to 1e-5 mm): wider than
// anything their snapping leaves between two outlines that should coincide, far narrower than any
// feature the axis resolves.
constexpr double kHairline = 1e-4;  // mm

// How far past the section below, in planes' spacings, a steep limb's stick-out reaches
// (Search::classify, steep_limb): tan 56.3 degrees, a side sloping that far off the march, past
// the 45 degrees its layers lay untilted.
constexpr double kSteepLimb = 1.5;

// Per node, whether it is a root's first node.
std::vector<char> root_starts(std::size_t node_count, const std::vector<AxisBranch>& branches) {
    std::vector<char> out(node_count, 0);
    for (const auto& br : branches)
        if (br.parent < 0 && !br.nodes.empty()) out[std::size_t(br.nodes.front())] = 1;
    return out;
}

// How far the slabs' volume (the sum of area x thickness) may stray from the part's, below it
// (`short_of`) and above it (`over`). A slab takes the section at its lower plane over one step,
// so it is off by at most the section's change to the next node, and a branch's last slab by at
// most its own volume. A root's first slab also reaches down from its plane to where it starts
// (the base) with its node's section: off by up to that much more (a sphere at a step of 7 of its
// 20 mm sweeps 5536 mm^3 of 4183). Plus 5 % of the volume. A last slab cut short at the part's
// extent along its march is taken as exact below the part: it ends where the part does, unless its
// own material ends lower, where it can only sweep too much, by up to all of it (a wall whose peg
// rises past its top: the wall's last slab reaches the peg's top; that was 1008 mm^3 over a part
// of 20763, and the decomposition refused the part's own axis as another part's).
struct SweepSlack {
    double short_of = 0.0;
    double over = 0.0;
};

SweepSlack sweep_slack(const std::vector<AxisNode>& nodes, const std::vector<AxisLink>& links,
                       const std::vector<AxisBranch>& branches, double step, double volume) {
    const std::vector<char> root_start = root_starts(nodes.size(), branches);
    double slack = 0.05 * volume, cut_short = 0.0;
    std::vector<char> continues(nodes.size(), 0);
    for (const auto& l : links) {
        if (l.kind != AxisLink::Kind::Step) continue;
        continues[std::size_t(l.start)] = 1;
        slack += std::abs(nodes[std::size_t(l.end)].area - nodes[std::size_t(l.start)].area) * step;
    }
    for (std::size_t i = 0; i < nodes.size(); ++i) {
        const AxisNode& n = nodes[i];
        if (!continues[i]) (n.thickness >= step - 1e-9 ? slack : cut_short) += n.area * n.thickness;
        if (root_start[i]) slack += n.area * std::max(n.offset - n.slab_start, 0.0);
    }
    return {slack, slack + cut_short};
}

class Search {
public:
    // `derived_threshold`: the distance threshold was derived from the step, not given.
    // `volume`: the mesh's, mm^3. `checkpoint(searched_mm3)` is called now and then from this
    // thread with the volume swept so far; it may throw to stop the search.
    Search(const TriangleMesh& mesh, const AxisParams& params, bool derived_threshold,
           double volume, const std::function<void(double)>& checkpoint)
        : mesh_(mesh),
          p_(params),
          derived_threshold_(derived_threshold),
          volume_(volume),
          checkpoint_(checkpoint) {}

    CentroidalAxis run(double base_z) {
        Task root;
        root.direction = Vector3d::UnitZ();
        root.start = base_z + p_.eps_mm;
        root.slab_start = base_z;
        search(root, 0);
        search_unreached();
        connect_turned_branches();
        mark_breaks();
        CentroidalAxis axis;
        axis.nodes = std::move(nodes_);
        axis.links = std::move(links_);
        axis.branches = std::move(branches_);
        axis.params = p_;
        axis.sections_cut = sections_cut_;
        for (const auto& s : slabs_) axis.searched_volume_mm3 += area(s.region) * (s.h1 - s.h0);
        return axis;
    }

private:
    // Material the march from the base never reaches, because it first appears in mid-air and
    // joins the rest only further up: a block hanging under a bridge, a box under a table top.
    // B - Bs still holds it when the search ends. Where a region of a +Z grid plane overlaps no
    // region of the plane below (its bottom), what is unswept of it is searched upward from there,
    // each plane's pieces together (so that the prongs of a hanging U can merge), and roots a tree
    // of its own (as a second foot on the plate does); built from there, its first layer rests on
    // nothing, which slicing reports as unsupported. A piece must be wider than a tenth of a step
    // (2 x area / outline), not a hairline of the Booleans. Only when the slabs fall short of the
    // part's volume by more than their own error (sweep_slack, tested once: every root found adds
    // to it), so that a part the search from the base covers keeps its axis. (Looked for on every
    // part, even only where a region's box meets no box below, it turned CGAL's armadillo's 65
    // branches into 342, and took three times as long: a hanging piece within the slabs' error,
    // such as a small hopper's cone under the ring its legs carry, stays unsearched.)
    void search_unreached() {
        for (const bool of_unswept : {false, true}) {
            if (volume_ - searched_ <=
                sweep_slack(nodes_, links_, branches_, p_.step_mm, volume_).short_of)
                return;
            search_unreached(of_unswept);
        }
    }

    // One pass of it. `of_unswept`: the bottoms are those of the material left unswept, not of
    // the part's sections: a piece of a +Z grid plane's B - Bs that overlaps none of the plane
    // below's. Taken only where the first pass leaves material lost: a march round a closed loop
    // (a braced frame's brace up from one post, down the other's, which it then sweeps sideways
    // from inside, and the beam's middle with it, resting on the posts, which no march reaches)
    // left 11 % of a part unsearched, and the axis was refused. Parts the first pass covers keep
    // their axes. A piece must be wider than two steps: the staircase a march's slabs leave along
    // a slanting side is left unswept in wedges up to a step wide (that brace's left 164 of them).
    void search_unreached(bool of_unswept) {
        Grid& g = grid(Vector3d::UnitZ());
        Regions2 left_below;  // of_unswept: B - Bs on plane k - 1
        if (of_unswept) {
            cut_chunk(g, 0);
            left_below = unswept(g, 0, nullptr);
        }
        for (std::size_t k = 1; k < g.count; ++k) {
            checkpoint_(searched_);
            cut_chunk(g, k - 1);
            cut_chunk(g, k);
            std::vector<Eigen::AlignedBox2d> bottoms;  // of the regions in mid-air
            Regions2 left;
            if (of_unswept) {
                left = unswept(g, k, nullptr);
                for (const auto& r : left) {
                    const Eigen::AlignedBox2d box = bounds(r);
                    Regions2 below;
                    for (const auto& l : left_below)
                        if (bounds(l).intersects(box)) below.push_back(l);
                    if (below.empty() || area(intersection({r}, below)) <= p_.min_region_area_mm2)
                        bottoms.push_back(box);
                }
            } else {
                for (std::size_t i = 0; i < g.regions[k].size(); ++i) {
                    const Eigen::AlignedBox2d& box = g.bounds2[k][i];
                    const Regions2 below = regions_near(g, k - 1, box);
                    if (below.empty() ||
                        area(intersection({g.regions[k][i]}, below)) <= p_.min_region_area_mm2)
                        bottoms.push_back(box);
                }
            }
            // A search's first nodes sweep its pieces from plane k - 1 to k + 1: plane k once
            // more, for what the march left of it.
            if (!bottoms.empty() &&
                search_upward(g, k, bottoms, (of_unswept ? 2.0 : 0.1) * p_.step_mm)) {
                --k;
                if (of_unswept) left_below = unswept(g, k, nullptr);
            } else {
                left_below = std::move(left);
            }
        }
    }

    // One march: a direction, its first plane, and where it comes from.
    struct Task {
        Vector3d direction;
        double start = 0.0;       // offset of the first plane
        double slab_start = 0.0;  // the first node sweeps from here (Eq. 4's T, or the base)
        int parent_branch = -1;
        int father_node = -1;  // lower node the stick-out was found over (-1 for the root)
        // The march's share of the stick-out dA_k, swept between the lower and the upper plane;
        // none for the root, which takes every region of its first section.
        std::vector<Slab> constraints;
        // The share is the whole stick-out (none of it shared out to other sides or left to the
        // march it came from).
        bool whole = false;
    };
    struct Track {
        int branch;
        int node;
        Regions2 region;  // the node's region, alone in a list as the Booleans take it
        Eigen::AlignedBox2d box;
        double outline = 0.0;  // the region's perimeter, holes included, mm
    };

    // The sections of one of the six directions, cut once on a fixed grid: planes at
    // lo + eps + k step, lo the mesh's lowest offset along the direction. Every march in that
    // direction reads them, so the kernel's batch path does all the cutting.
    struct Grid {
        Vector3d normal;
        double origin = 0.0;  // offset of plane 0
        double hi = 0.0;      // the mesh's highest offset along the normal
        // Per plane: its regions, simplified to step / 100 (the axis is a coarse descriptor;
        // Booleans on faceted loops with hundreds of points were most of its cost), largest
        // first, and their 3-D boxes grown by a hair. Corners are kept, so exact outlines stay
        // exact. `bounds2` holds each region's 2-D box, in the order of `regions`.
        std::vector<Regions2> regions;
        std::vector<std::vector<Eigen::AlignedBox3d>> boxes;
        std::vector<std::vector<Eigen::AlignedBox2d>> bounds2;
        std::size_t count = 0;
        // Per chunk of kGridChunk planes: kUncut, kCutting or kCut (either thread may cut it),
        // and whether the search has used it yet (sections_cut counts those).
        std::vector<std::atomic<int>> chunk_state;
        std::vector<char> chunk_used;
        std::unique_ptr<SectionGrid> sections;  // the mesh prepared for cutting these planes
        // For half_plane(), on the search's thread only: the section half a step above each
        // plane, once cut (empty until a ledge is first looked for).
        std::vector<std::unique_ptr<Regions2>> half_regions;
        bool ready = false;
    };
    static constexpr std::size_t kGridChunk = 16;

    // Section regions of grid plane k minus everything already swept (B - Bs): those whose box
    // meets one of `near` (every region when it is null), largest first.
    Regions2 unswept(Grid& g, std::size_t k, const std::vector<Eigen::AlignedBox2d>* near) {
        cut_chunk(g, k);
        count_chunk(g, k);
        PlaneSweep sweep = swept_on(g, k, slabs_.size());
        return gather(g, k, sweep, near);
    }

    // sections_cut counts the chunks of planes the search reaches, whichever thread cut them
    // (a Lookahead may cut one a march then never reaches).
    void count_chunk(Grid& g, std::size_t k) {
        const std::size_t chunk = k / kGridChunk;
        if (g.chunk_used[chunk]) return;
        g.chunk_used[chunk] = 1;
        sections_cut_ += std::min(g.count, (chunk + 1) * kGridChunk) - chunk * kGridChunk;
    }

    // B - Bs on one grid plane, region by region. A march reads only the regions whose box meets
    // one of its tracks' boxes (the others overlap none of its tracks and are left to the search
    // that reaches them), so only those are worked out: on scanned meshes, where a plane cuts many
    // limbs, that is under half of the Boolean work. Each region minus the swept pieces near it is
    // the region's share of the whole plane minus everything swept.
    struct PlaneSweep {
        Regions2 swept;  // what the slabs take from the plane near its regions
        std::vector<Eigen::AlignedBox2d> swept_boxes;
        std::vector<Regions2> left;  // per region: what is left of it, once done
        std::vector<char> done;
    };

    static bool meets(const Eigen::AlignedBox2d& box,
                      const std::vector<Eigen::AlignedBox2d>* near) {
        if (!near) return true;
        for (const auto& b : *near)
            if (box.intersects(b)) return true;
        return false;
    }

    // The swept pieces on grid plane k, already cut, from the first `slab_count` slabs: safe to
    // run on another thread while the march adds nodes (see Lookahead). Only slabs whose box meets
    // a region's box can take anything away: a march's slabs far along another direction are
    // skipped without being cut.
    PlaneSweep swept_on(const Grid& g, std::size_t k, std::size_t slab_count) const {
        return swept_across(g.normal, offset(g, k), g.regions[k], g.boxes[k], g.bounds2[k],
                            slab_count);
    }

    // The same on the plane at offset c along n, given its regions, their 3-D boxes (grown by a
    // hair) and their 2-D boxes.
    PlaneSweep swept_across(const Vector3d& n, double c, const Regions2& regions,
                            const std::vector<Eigen::AlignedBox3d>& boxes,
                            const std::vector<Eigen::AlignedBox2d>& bounds2,
                            std::size_t slab_count) const {
        PlaneSweep out;
        if (regions.empty()) return out;
        const PlaneFrame frame(n);
        Regions2& swept = out.swept;
        std::map<int, std::pair<StripAxes, std::vector<Strip>>> strips;  // per branch
        Eigen::AlignedBox3d all;  // of every region: most slabs miss it
        for (const auto& box : boxes) all.extend(box);
        for (std::size_t i = 0; i < slab_count; ++i) {
            const Slab& slab = slabs_[i];
            if (!slab.box.intersects(all)) continue;
            bool meets = false;
            for (const auto& box : boxes) meets = meets || slab.box.intersects(box);
            if (!meets) continue;
            if (std::abs(slab.normal.dot(n)) > 0.5) {
                for (auto& r : slab_cut(slab, n, c, frame)) swept.push_back(std::move(r));
                continue;
            }
            const StripAxes ax = strip_axes(slab, n, c);
            auto& group = strips.try_emplace(slab.branch, ax, std::vector<Strip>{}).first->second;
            group.second.push_back(perpendicular_strip(slab, ax));
        }
        for (auto& [branch, group] : strips)
            for (auto& r : strips_to_regions(std::move(group.second), group.first, frame, 1e-9))
                swept.push_back(std::move(r));
        // Only what overlaps a region's 2-D box can take anything away from it.
        Regions2 kept;
        for (auto& r : swept) {
            const Eigen::AlignedBox2d b = bounds(r);
            if (!meets(b, &bounds2)) continue;
            kept.push_back(std::move(r));
            out.swept_boxes.push_back(b);
        }
        swept = std::move(kept);
        out.left.resize(regions.size());
        out.done.assign(regions.size(), 0);
        return out;
    }

    // Works out the regions of plane k that meet one of `near` and are not done yet.
    void subtract_near(const Grid& g, std::size_t k, PlaneSweep& sweep,
                       const std::vector<Eigen::AlignedBox2d>* near) const {
        subtract_near(g.regions[k], g.bounds2[k], sweep, near);
    }
    void subtract_near(const Regions2& regions, const std::vector<Eigen::AlignedBox2d>& boxes,
                       PlaneSweep& sweep, const std::vector<Eigen::AlignedBox2d>* near) const {
        for (std::size_t i = 0; i < sweep.done.size(); ++i) {
            if (sweep.done[i] || !meets(boxes[i], near)) continue;
            if (sweep.swept.empty()) {
                sweep.left[i] = {regions[i]};
            } else {
                // Through the Boolean even when no swept piece is near this region, as every
                // region of a plane with something swept is (the Boolean snaps its points).
                Regions2 cut;
                for (std::size_t j = 0; j < sweep.swept.size(); ++j)
                    if (sweep.swept_boxes[j].intersects(boxes[i])) cut.push_back(sweep.swept[j]);
                sweep.left[i] = difference({regions[i]}, cut);
            }
            sweep.done[i] = 1;
        }
    }

    // What is left of the regions of plane k that meet one of `near`, largest first.
    Regions2 gather(const Grid& g, std::size_t k, PlaneSweep& sweep,
                    const std::vector<Eigen::AlignedBox2d>* near) const {
        subtract_near(g, k, sweep, near);
        Regions2 out;
        for (std::size_t i = 0; i < sweep.done.size(); ++i)
            if (meets(g.bounds2[k][i], near))
                for (auto& r : sweep.left[i]) out.push_back(std::move(r));
        if (sweep.swept.empty()) return out;  // the plane's own regions, already in order
        return keep_larger(std::move(out), p_.min_region_area_mm2);
    }

    // Whether a root's first section is too small to start a march: a sliver, or a speck less than
    // a twentieth of a step across (what eps above a vertex or a tip cuts). A step above it the
    // part's flanks have outgrown it on every side by far more than its size, which Eq. 3 (d at
    // most a sixth of the lower section's size) reads as a stick-out far outside it: the march
    // would end there. A thin stem or pin is wider than that at any sensible step, and kept. Or a
    // hairline, however long: what eps above a knife edge cuts (a wedge standing on its edge),
    // which the march reads as overlapping nothing above it where the overlap is no more than
    // kHairline times its outline (search, `owner`): the march would end at once, the part
    // unsearched (a wedge 20 mm long and 20 tall, its faces 5 degrees off the vertical, was one
    // node, and not sliced). Twice that here, 2 x area / outline up to 4e-4 mm, so that a strip
    // near the march's limit, which the Booleans' rounding puts either side of it, is a speck
    // (wedges at 5.75 to 5.95 degrees stayed one node at the limit itself): at the default eps, a
    // wedge whose faces are within 11.3 degrees of the vertical (21.8 for one face, the other
    // upright).
    bool speck(const Region2& r) const {
        return area(r) <= std::max(p_.min_region_area_mm2, 2.0 * kHairline * perimeter(r)) ||
               bounds(r).diagonal().norm() < p_.step_mm / 20.0;
    }

    // A march starting at a fin's root (classify) takes the arm over the fin, which the node
    // below, on the last plane under the arm's underside, swept up to the plane above it with the
    // fin's section: the arm's sections would have a notch over the fin up to there, and their
    // centroids sit off its centre line until the fin ends (the last node's did not: the guide
    // bent there, and a bracket's last layers tilted past the arm's end, beyond the volumetric
    // bound). That node's slab gives the arm back: beyond the fin's root it ends at the arm's
    // underside.
    struct Release {
        int node;            // the node below the plane where the arm appeared
        Vector3d side;       // the fin march's direction
        double root = 0.0;   // where it starts (offset along side)
        Regions2 stick_out;  // the arm's share on the plane above, present from the underside up
    };

    // Ends the slab of the node the releases `rs` name (one node, each release a side), beyond
    // each one's root along its side, where its stick-out appears: the highest height between
    // the node's plane and the next one of g (plane k) where under half of it lies in the part's
    // section, to a ten-thousandth of a step; below there, beyond the root, the slab sweeps the
    // fin's section at that height. Between the march's planes (no Lookahead reading the slabs).
    void release(const std::vector<Release>& rs, Grid& g, std::size_t k) {
        const std::size_t index = node_slab_[std::size_t(rs.front().node)];
        const Slab slab = slabs_[index];
        const PlaneFrame frame(g.normal);
        const double lo = std::max(slab.h0, offset(g, k - 1));
        if (!(slab.h1 > lo)) return;
        const auto cut_at = [&](double height) {
            Regions2 cut;
            for (const auto& region : g.sections->cut_at(height).regions)
                cut.push_back(region.shape);
            return cut;
        };
        const auto add = [&](Region2 region, double h0, double h1) {
            const Eigen::AlignedBox3d box = slab_box(region, frame, lo, h0, h1);
            slabs_.push_back(Slab{slab.normal, h0, h1, std::move(region), box, slab.branch});
        };
        Regions2 rest{slab.region};
        double lowest = slab.h1;
        std::vector<std::pair<Regions2, double>> ends;  // per release: beyond its root, underside
        for (const auto& r : rs) {
            auto [beyond, behind] = split_at(std::move(rest), frame, r.side, r.root);
            rest = std::move(behind);
            if (beyond.empty()) continue;
            const double half = 0.5 * area(r.stick_out);
            double absent = lo, present = slab.h1;
            while (present - absent > 1e-4 * p_.step_mm) {
                const double mid = 0.5 * (absent + present);
                (area(intersection(cut_at(mid), r.stick_out)) >= half ? present : absent) = mid;
            }
            // The fin reaches further under the underside than on the node's plane (a gusset's
            // slope): the slab takes that too, with the fin's section just under the underside
            // (the section's regions beyond the root that meet the slab's there, not another
            // column's), or the arm's last sections, past the fin's tip on the node's plane,
            // would hold the fin's end under them and their centroids sit below the centre line.
            Regions2 fin;
            for (auto& piece : split_at(cut_at(absent), frame, r.side, r.root).first)
                if (area(intersection({piece}, beyond)) > p_.min_region_area_mm2)
                    fin.push_back(std::move(piece));
            for (auto& piece : difference(fin, beyond))
                if (area(piece) > p_.min_region_area_mm2) {
                    searched_ += area(piece) * (absent - lo);
                    add(std::move(piece), lo, absent);
                }
            for (const auto& piece : beyond) searched_ -= area(piece) * (slab.h1 - absent);
            lowest = std::min(lowest, absent);
            ends.emplace_back(std::move(beyond), absent);
        }
        if (ends.empty()) return;
        slabs_[index].h1 = lowest;
        for (auto& piece : rest) add(std::move(piece), lowest, slab.h1);
        for (auto& [beyond, absent] : ends)
            if (absent > lowest)
                for (auto& piece : beyond) add(std::move(piece), lowest, absent);
    }

    int new_branch(const Vector3d& dir, int parent, int parent_node) {
        AxisBranch b;
        b.direction = dir;
        b.parent = parent;
        b.parent_node = parent_node;
        b.depth = parent >= 0 ? branches_[parent].depth + 1 : 0;
        branches_.push_back(b);
        return static_cast<int>(branches_.size()) - 1;
    }

    int add_node(const Region2& region, const Vector3d& n, double offset, double slab_from,
                 double slab_to, int branch) {
        if (nodes_.size() >= p_.max_nodes)
            throw Error(ErrorCode::GeometryFailure,
                        "centroidal axis: more than " + std::to_string(p_.max_nodes) +
                            " nodes; the step is too small for this part");
        const PlaneFrame frame(n);
        const Plane plane{n * offset, n};
        AxisNode node;
        node.position = frame.to_3d(centroid(region), plane);
        node.interior = frame.to_3d(interior_point(region), plane);
        node.normal = n;
        node.area = area(region);
        node.offset = offset;
        node.thickness = slab_to - slab_from;
        searched_ += node.area * node.thickness;
        node.slab_start = slab_from;
        node.branch = branch;
        node.region = region;
        const Eigen::AlignedBox3d box = slab_box(region, frame, offset, slab_from, slab_to);
        node_slab_.push_back(slabs_.size());
        slabs_.push_back(Slab{n, slab_from, slab_to, region, box, branch});
        nodes_.push_back(std::move(node));
        const int id = static_cast<int>(nodes_.size()) - 1;
        branches_[branch].nodes.push_back(id);
        return id;
    }

    int add_link(int start, int end, AxisLink::Kind kind) {
        links_.push_back(AxisLink{start, end, kind, false, 0.0});
        const int id = static_cast<int>(links_.size()) - 1;
        nodes_[end].incoming_link = id;
        return id;
    }

    // The grid of direction n: its planes are laid out at once, their sections cut on demand in
    // chunks of kGridChunk planes (a short branch along X needs a few of X's planes, not all).
    Grid& grid(const Vector3d& n) {
        const int key = 2 * axis_index(n) + (n[axis_index(n)] > 0 ? 0 : 1);
        Grid& g = grids_[std::size_t(key)];
        if (g.ready) return g;
        double lo = std::numeric_limits<double>::infinity(), hi = -lo;
        for (const auto& v : mesh_.vertices) {
            lo = std::min(lo, n.dot(v));
            hi = std::max(hi, n.dot(v));
        }
        if (key == 4) lo = p_.base_z_mm;  // +Z: the base plane the part stands on
        g.normal = n;
        g.origin = lo + p_.eps_mm;
        g.hi = hi;
        g.count =
            static_cast<std::size_t>(std::max(0.0, std::floor((hi - g.origin) / p_.step_mm))) + 1;
        g.regions.resize(g.count);
        g.boxes.resize(g.count);
        g.bounds2.resize(g.count);
        const std::size_t chunks = (g.count + kGridChunk - 1) / kGridChunk;
        g.chunk_state = std::vector<std::atomic<int>>(chunks);  // all kUncut
        g.chunk_used.assign(chunks, 0);
        std::vector<Plane> planes(g.count);
        for (std::size_t i = 0; i < g.count; ++i) planes[i] = Plane{n * offset(g, i), n};
        g.sections = std::make_unique<SectionGrid>(mesh_, std::move(planes));
        g.ready = true;
        return g;
    }

    enum : int { kUncut, kCutting, kCut };

    // A plane's section as the search reads it (Grid): its regions simplified to step / 100,
    // largest first, their 3-D boxes grown by a hair, and their 2-D boxes.
    void read_section(const Section& section, Regions2& regions,
                      std::vector<Eigen::AlignedBox3d>& boxes,
                      std::vector<Eigen::AlignedBox2d>& bounds2) const {
        Regions2 rs;
        boxes.clear();
        for (const auto& r : section.regions) {
            rs.push_back(simplify(r.shape, p_.step_mm / 100.0));
            Eigen::AlignedBox3d box = r.bounds;
            box.min().array() -= 1e-6;
            box.max().array() += 1e-6;
            boxes.push_back(box);
        }
        regions = keep_larger(std::move(rs), p_.min_region_area_mm2);
        bounds2.clear();
        for (const auto& r : regions) bounds2.push_back(bounds(r));
    }

    // B - Bs on the plane of g's direction at offset c, which need not be one of the grid's:
    // what is left of its section once everything swept is taken away, largest first.
    Regions2 unswept_at(Grid& g, double c) {
        Regions2 regions;
        std::vector<Eigen::AlignedBox3d> boxes;
        std::vector<Eigen::AlignedBox2d> bounds2;
        read_section(g.sections->cut_at(c), regions, boxes, bounds2);
        PlaneSweep sweep = swept_across(g.normal, c, regions, boxes, bounds2, slabs_.size());
        subtract_near(regions, bounds2, sweep, nullptr);
        Regions2 out;
        for (auto& left : sweep.left)
            for (auto& r : left) out.push_back(std::move(r));
        return keep_larger(std::move(out), p_.min_region_area_mm2);
    }

    // Cuts the chunk of grid planes holding plane k, unless it is cut already; waits if the
    // other thread is cutting it. `on_search`: called from the search's own thread, the only
    // one where cancellation may be checked.
    void cut_chunk(Grid& g, std::size_t k, bool on_search = true) {
        const std::size_t chunk = k / kGridChunk;
        const std::size_t first = chunk * kGridChunk, last = std::min(g.count, first + kGridChunk);
        std::atomic<int>& state = g.chunk_state[chunk];
        for (;;) {
            int uncut = kUncut;
            if (state.compare_exchange_strong(uncut, kCutting, std::memory_order_acq_rel)) break;
            if (uncut == kCut) return;
            std::this_thread::yield();  // being cut by the other thread
        }
        try {
            if (on_search) checkpoint_(searched_);
            // Each plane's regions simplified as soon as it is cut, in parallel. Isolated: while
            // waiting for its planes this thread must not pick up a Lookahead's task, which
            // could wait for this very chunk.
            tbb::this_task_arena::isolate([&] {
                g.sections->cut(first, last, [&](std::size_t i, Section& section) {
                    read_section(section, g.regions[i], g.boxes[i], g.bounds2[i]);
                });
            });
        } catch (...) {
            state.store(kUncut, std::memory_order_release);
            throw;
        }
        state.store(kCut, std::memory_order_release);
    }

    double offset(const Grid& g, std::size_t k) const { return g.origin + double(k) * p_.step_mm; }

    // The regions of grid plane j (cut) whose boxes meet `box`, in the plane's order.
    static Regions2 regions_near(const Grid& g, std::size_t j, const Eigen::AlignedBox2d& box) {
        Regions2 out;
        for (std::size_t i = 0; i < g.regions[j].size(); ++i)
            if (g.bounds2[j][i].intersects(box)) out.push_back(g.regions[j][i]);
        return out;
    }

    // Whether stick-out `da` meets the lower regions in more than one place: it spans a gap
    // between them or between two ends of one of them (a bore's ceiling closing a ring the bore
    // broke open), as a bridge does. A ledge meets them along one stretch.
    bool spans_a_gap(const Region2& da, const Regions2& lower) const {
        const Regions2 grown = mas::offset({da}, p_.step_mm / 100.0, JoinType::Miter);
        int contacts = 0;
        for (const auto& piece : intersection(grown, lower))
            if (area(piece) > p_.min_region_area_mm2) ++contacts;
        return contacts > 1;
    }

    // Whether stick-out `da` of grid plane k, turning the way `way` (a unit vector of the planes'
    // frame), grows into a gap of the part's section that closes by the next plane: the part's
    // section at plane k holds material ahead of it that way, across from it (within its span
    // across `way`, past where it ends along it), and the section of plane k + 1 covers at least
    // half the gap between the two. That is a hole's ceiling (a bore across the march, whose
    // sides grow towards each other near its top) or an arch's crown, not material leaving the
    // part: the march lays it as the two sides meet (a bridge, spans_a_gap()). Turned, the march
    // along `way` started inside the part and took the whole wall above the hole in its first
    // section (a valve body's bore, 8.3 mm across, in a ring 6.3 mm thick: the ring was swept
    // sideways in pieces, the bosses left in the body's layers, 82.6 mm^2 hanging in one). An
    // inward lip or a boss facing another part across a gap that stays open is still a ledge.
    bool closes_a_gap(const Region2& da, const Vector2d& way, Grid& g, std::size_t k) {
        if (k + 1 >= g.count) return false;
        const Vector2d across(-way.y(), way.x());
        double front = -std::numeric_limits<double>::infinity();
        double lo = std::numeric_limits<double>::infinity(), hi = -lo;
        for (const auto& q : da.outer.points) {
            front = std::max(front, way.dot(q));
            lo = std::min(lo, across.dot(q));
            hi = std::max(hi, across.dot(q));
        }
        // The band from `s0` to `s1` along `way`, over da's span across it.
        const auto band = [&](double s0, double s1) {
            Region2 r;
            for (const auto& [s, t] : {std::pair{s0, lo}, {s1, lo}, {s1, hi}, {s0, hi}})
                r.outer.points.push_back(s * way + t * across);
            return r;
        };
        Eigen::AlignedBox2d all;
        for (const auto& b : g.bounds2[k]) all.extend(b);
        const double hair = p_.step_mm / 100.0;
        const Region2 beyond = band(front + hair, front + hair + all.diagonal().norm());
        const Regions2 ahead = intersection({beyond}, regions_near(g, k, bounds(beyond)));
        if (area(ahead) <= p_.min_region_area_mm2) return false;
        double other = std::numeric_limits<double>::infinity();  // where the material ahead begins
        for (const auto& r : ahead)
            for (const auto& q : r.outer.points) other = std::min(other, way.dot(q));
        if (!(other > front + hair)) return false;
        const Region2 gap = band(front, other);
        cut_chunk(g, k + 1);
        return area(intersection({gap}, regions_near(g, k + 1, bounds(gap)))) >= 0.5 * area(gap);
    }

    // How stick-out `da` of plane k over plane k - 1 comes about between them: whether it is new
    // (nearly none of it, a tenth, in plane k - 1's section: the whole section, every march's)
    // and, if so, what of it the section half a step up holds.
    struct Emergence {
        bool is_new = false;
        Regions2 half;       // da's part in the half plane's section (only when new)
        double share = 0.0;  // its area over da's
        // Appearing at once: new, and half a step up nearly all of it or nearly none (a flat
        // underside below or above the half plane; where a side sloping out over the whole step
        // grows the section, about half of it). Nearly all is nine tenths; nearly none a quarter,
        // as the chamfers or fillets round a boss' root and end hold some of it below its lowest
        // line (15 % of a chamfered block's boss, half a step under a plane 0.09 mm over it).
        bool at_once() const { return is_new && (share >= 0.9 || share <= 0.25); }
    };
    Emergence emergence(const Region2& da, Grid& g, std::size_t k) {
        Emergence e;
        const double a = area(da);
        if (!(a > 0.0) || k == 0) return e;
        const Eigen::AlignedBox2d box = bounds(da);
        if (area(intersection({da}, regions_near(g, k - 1, box))) > 0.1 * a) return e;
        Regions2 half;
        for (const auto& r : half_plane(g, k))
            if (bounds(r).intersects(box)) half.push_back(r);
        e.is_new = true;
        e.half = intersection({da}, half);
        e.share = area(e.half) / a;
        return e;
    }
    bool appears_at_once(const Region2& da, Grid& g, std::size_t k) {
        return emergence(da, g, k).at_once();
    }

    // The regions of the section half a step above plane k - 1 (between it and plane k), cut
    // once. Cut from the grid's own preparation of the mesh, from the facets reaching the plane
    // (a grid of half planes, prepared as the sections' grid is, cost more than the axis' own
    // Booleans on CGAL's armadillo).
    const Regions2& half_plane(Grid& g, std::size_t k) {
        if (g.half_regions.empty()) g.half_regions.resize(g.count);
        std::unique_ptr<Regions2>& half = g.half_regions[k - 1];
        if (!half) {
            const Section section = g.sections->cut_at(offset(g, k - 1) + 0.5 * p_.step_mm);
            half = std::make_unique<Regions2>();
            for (const auto& r : section.regions)
                half->push_back(simplify(r.shape, p_.step_mm / 100.0));
        }
        return *half;
    }

    // B - Bs of the planes a march reaches next, worked out on another thread while the march
    // handles the current plane: the Booleans of the two are most of the axis' time, and each
    // plane's B - Bs needs only the slabs swept before it. It stays valid while only the march's
    // own nodes are added (each node's slab ends at the next plane, so it takes nothing from the
    // planes ahead); a branch searched from the march sweeps across them, so the march calls
    // restart() before searching one and the planes ahead are worked out afresh afterwards.
    // The results are the ones unswept() would give: same slabs, same order, same Booleans. The
    // other thread works out the regions near the march's tracks as they were when it last took
    // a plane; take() works out any others its tracks now meet.
    class Lookahead {
    public:
        Lookahead(Search& search, Grid& g, std::size_t from)
            : s_(search), g_(g), from_(from), slots_(new Slot[g.count - from]) {}
        Lookahead(const Lookahead&) = delete;
        Lookahead& operator=(const Lookahead&) = delete;
        ~Lookahead() { stop(); }

        // unswept(g, k, &near) for k = from, from + 1, ... in turn.
        Regions2 take(std::size_t k, const std::vector<Eigen::AlignedBox2d>& near) {
            s_.cut_chunk(g_, k);
            s_.count_chunk(g_, k);
            {
                const std::lock_guard<std::mutex> lock(near_mutex_);
                near_ = near;
            }
            const std::size_t end = std::min(g_.count, k + kAhead);
            if (!started_) {
                slab_count_ = s_.slabs_.size();
                started_ = true;
            }
            end_.store(end, std::memory_order_release);
            bool idle = false;
            if (end > k + 1 && running_.compare_exchange_strong(idle, true))
                tasks_.run([this, k] { run(k + 1); });
            // Ours unless the other thread has it; while it works on it, help with the next.
            Slot& slot = at(k);
            if (!claim(slot, kMine)) {
                for (std::size_t j = k + 1; j < end; ++j) {
                    if (slot.state.load(std::memory_order_acquire) == kDone) break;
                    if (claim(at(j), kMine)) fill(at(j), j, true);
                }
                while (slot.state.load(std::memory_order_acquire) != kDone)
                    std::this_thread::yield();
            } else {
                fill(slot, k, true);
            }
            if (slot.error) std::rethrow_exception(slot.error);
            return s_.gather(g_, k, slot.result, &near);
        }

        // Before a branch is searched from plane k: forget the planes after k.
        void restart(std::size_t k) {
            stop();
            for (std::size_t j = k + 1; j < end_.load(std::memory_order_relaxed); ++j) {
                Slot& slot = at(j);
                slot.state.store(kFree, std::memory_order_relaxed);
                slot.result = PlaneSweep{};
                slot.error = nullptr;
            }
            started_ = false;
        }

    private:
        enum : int { kFree, kTheirs, kMine, kDone };
        struct Slot {
            std::atomic<int> state{kFree};
            PlaneSweep result;
            std::exception_ptr error;
        };
        static constexpr std::size_t kAhead = 8;  // planes worked out ahead of the march

        Slot& at(std::size_t k) { return slots_[k - from_]; }
        static bool claim(Slot& slot, int who) {
            int free = kFree;
            return slot.state.compare_exchange_strong(free, who, std::memory_order_acq_rel);
        }
        void fill(Slot& slot, std::size_t k, bool on_search) {
            try {
                s_.cut_chunk(g_, k, on_search);
                slot.result = s_.swept_on(g_, k, slab_count_);
                std::vector<Eigen::AlignedBox2d> near;
                {
                    const std::lock_guard<std::mutex> lock(near_mutex_);
                    near = near_;
                }
                s_.subtract_near(g_, k, slot.result, &near);
            } catch (...) {
                slot.error = std::current_exception();
            }
            slot.state.store(kDone, std::memory_order_release);
        }
        // On the other thread: the free planes from k on, in order, until told to stop or out
        // of planes it may read.
        void run(std::size_t k) {
            for (;;) {
                for (; !stop_.load(std::memory_order_acquire) &&
                       k < end_.load(std::memory_order_acquire);
                     ++k)
                    if (claim(at(k), kTheirs)) fill(at(k), k, false);
                running_.store(false, std::memory_order_release);
                // The march may have moved end_ on just before running_ dropped.
                bool idle = false;
                if (stop_.load(std::memory_order_acquire) ||
                    k >= end_.load(std::memory_order_acquire) ||
                    !running_.compare_exchange_strong(idle, true))
                    return;
            }
        }
        void stop() {
            stop_.store(true, std::memory_order_release);
            tasks_.wait();
            stop_.store(false, std::memory_order_release);
        }

        Search& s_;
        Grid& g_;
        const std::size_t from_;
        std::unique_ptr<Slot[]> slots_;  // per plane from from_ on
        std::size_t slab_count_ = 0;     // the slabs B - Bs subtracts: those before the march
        bool started_ = false;
        std::atomic<std::size_t> end_{0};  // the other thread may take planes before this one
        std::atomic<bool> stop_{false}, running_{false};
        tbb::task_group tasks_;
        // The march's track boxes when it last took a plane: the regions to work out ahead.
        std::mutex near_mutex_;
        std::vector<Eigen::AlignedBox2d> near_;
    };

    // Eq. 2 on a turned branch's first section too, against the part's whole section one plane
    // behind it (what lies there, whichever march swept it): what hangs past that (a stair's
    // tier overhanging the tier the march turned up onto) is a stick-out like any other, and
    // may turn again. Returns what the branch keeps (all of `region`, unless something turns);
    // the branches leaving it are queued in `children`, with branch `b` their father.
    Regions2 first_pieces(const Region2& region, Grid& g, std::size_t k0, int b, int father_node,
                          std::vector<Task>& children) {
        cut_chunk(g, k0 - 1);
        const Eigen::AlignedBox2d box = bounds(region);
        const Regions2 below = regions_near(g, k0 - 1, box);
        Regions2 out = difference({region}, below);
        if (area(out) <= p_.min_region_area_mm2 || below.empty()) return {region};
        // Only what hangs at once (on a flat underside, as a ledge): a first section cut across
        // a sloping side grows past the one behind it as the march's next sections would, and
        // Eq. 2 there is left to the march. (Read on every first section, CGAL's fandisk grew
        // two branches marching down from a sideways one, and its slabs 9 % less volume.)
        out.erase(std::remove_if(out.begin(), out.end(),
                                 [&](const Region2& da) {
                                     return area(da) <= p_.min_region_area_mm2 ||
                                            !appears_at_once(da, g, k0);
                                 }),
                  out.end());
        if (out.empty()) return {region};
        const std::size_t queued = children.size(), released = releases_.size();
        // The children hang from b (the piece kept first, the largest; connect_turned_branches
        // ties each to b's nearest node, since father_node is the father march's).
        const Track track{b, father_node, {region}, box, perimeter(region)};
        Regions2 pieces = keep_larger(classify(region, out, below, track, g, k0, children),
                                      p_.min_region_area_mm2);
        // Nothing left to march on, or a fin's arm to give back from a node of another
        // direction's march: the section stays whole, as the paper's first section is.
        if (pieces.empty() || releases_.size() != released) {
            children.resize(queued);
            releases_.resize(released);
            return {region};
        }
        return pieces;
    }

    // Searches upward, as a root, from the pieces of +Z grid plane k's B - Bs that meet `bottoms`
    // and are wider than `width` (2 x area / outline) and no speck: whether a node came of it.
    bool search_upward(Grid& g, std::size_t k, const std::vector<Eigen::AlignedBox2d>& bottoms,
                       double width) {
        Task task;
        task.direction = Vector3d::UnitZ();
        task.start = offset(g, k);
        task.slab_start = offset(g, k - 1);
        for (Region2& r : unswept(g, k, &bottoms))
            if (!speck(r) && mean_width(r) > width)
                task.constraints.push_back(Slab{
                    task.direction, offset(g, k - 1), offset(g, k) + p_.step_mm, std::move(r), {}});
        if (task.constraints.empty()) return false;
        const std::size_t before = nodes_.size();
        search(task, 0);
        return nodes_.size() > before;
    }

    void search(const Task& task, int depth) {
        if (depth > 1000)
            throw Error(ErrorCode::GeometryFailure, "centroidal axis: branches nested too deep");
        const Vector3d n = task.direction;
        Grid& g = grid(n);
        // Eq. 4's location, moved up to the next plane of the grid (at most one step on; the
        // first node's slab reaches back to T, so nothing between is left unswept).
        const double first_k = std::ceil((task.start - g.origin) / p_.step_mm - 1e-9);
        const bool turned = !task.constraints.empty();
        if (first_k >= double(g.count) && !(turned && task.start < g.hi)) return;
        std::size_t k0 = static_cast<std::size_t>(std::max(0.0, first_k));
        const std::size_t count = g.count;
        auto offset_of = [&](std::size_t k) { return offset(g, k); };
        auto slab_end = [&](std::size_t k) { return std::min(offset_of(k + 1), g.hi); };

        // First section: the regions the stick-out reaches (every region for the root).
        Regions2 first;
        if (turned) {
            const PlaneFrame frame(n);
            // The regions of a section at offset `at` that meet the stick-out's slab there.
            const auto reaching = [&](const auto& section, double at) {
                Regions2 reach;
                for (const auto& c : task.constraints)
                    for (auto& r : slab_cut(c, n, at, frame)) reach.push_back(std::move(r));
                std::vector<Eigen::AlignedBox2d> near;
                for (const auto& r : reach) near.push_back(bounds(r));
                Regions2 out = section(near);
                out.erase(std::remove_if(out.begin(), out.end(),
                                         [&](const Region2& r) {
                                             return area(intersection({r}, reach)) <=
                                                    p_.min_region_area_mm2;
                                         }),
                          out.end());
                return out;
            };
            if (k0 < count)
                first = reaching([&](const auto& near) { return unswept(g, k0, &near); },
                                 offset_of(k0));
            if (first.empty()) {
                // The stick-out ends before the grid's next plane past Eq. 4's T: a boss
                // sticking out 5.1 mm from a block, its step 5.6 mm, the grid's last plane 0.5
                // mm behind the block's face. Its march is one node on the paper's own first
                // plane, T + eps, off the grid, its slab reaching from T to where the stick-out
                // ends. (Its share had left the march it came from, and no march swept
                // it: the boss stayed in the block's layers, its round underside overhanging 13.7
                // mm^2 in one.) Only a stick-out that is the share whole: a part of one shared
                // out among sides, such as an arm's end past the tip of the web under it while
                // its flanks turn sideways, is left to the march it came from, as before (a
                // node there took the arm's whole section, the flanks became its children and
                // were merged back into it, their layers colliding, and the arm's root over the
                // column hung 160 mm^2). Nor a share thinner on average than a tenth of the
                // step, as the root's first slivers are: what the Booleans leave along a face
                // the sections' simplification moves (a hundredth of the step), no stick-out.
                double a = 0.0, outline = 0.0;
                for (const auto& c : task.constraints) {
                    a += area(c.region);
                    outline += perimeter(c.region);
                }
                if (!task.whole || !(2.0 * a > p_.step_mm / 10.0 * outline)) return;
                // The slab ends where the stick-out does: the highest offset, short of that next
                // plane or the part's end, where the section still holds material over the
                // region (bisected to a ten-thousandth of a step, as release() finds an
                // underside), then the mesh's farthest vertex over the region's box within that
                // last bracket (exact where the stick-out ends on a face square to n). Not the
                // farthest vertex over the box alone: other material in its footprint, short of
                // that plane, would stretch the slab over it.
                const double to = k0 < count ? offset_of(k0) : g.hi;
                const Regions2 regions =
                    reaching([&](const auto&) { return unswept_at(g, task.start); }, task.start);
                const auto holds = [&](const Region2& region, double at) {
                    Regions2 cut;
                    for (const auto& r : g.sections->cut_at(at).regions) cut.push_back(r.shape);
                    return area(intersection(cut, {region})) > p_.min_region_area_mm2;
                };
                // Material over the region on that next plane, out of the stick-out's slab, is
                // the part going on past it elsewhere: a wye's lateral leaving its riser at 53
                // degrees, whose crescent beside the riser reaches less than a step past T. The
                // march it came from finds it again on its later planes, further out. (One node
                // with a slab to the next plane took one lateral's root and lost the rest of it:
                // 12 % of the part unswept, and the axis refused.)
                if (k0 < count)
                    for (const auto& region : regions)
                        if (holds(region, to)) return;
                for (const auto& region : regions) {
                    double present = task.start, absent = to;
                    // Short of the last plane none holds its region there (above).
                    if (k0 >= count && holds(region, absent)) present = absent;
                    while (absent - present > 1e-4 * p_.step_mm) {
                        const double mid = 0.5 * (present + absent);
                        (holds(region, mid) ? present : absent) = mid;
                    }
                    Eigen::AlignedBox2d box = bounds(region);
                    box.min().array() -= p_.step_mm / 100.0;
                    box.max().array() += p_.step_mm / 100.0;
                    double end = present;
                    for (const Vector3d& v : mesh_.vertices) {
                        const double h = n.dot(v);
                        if (h > end && h <= absent && box.contains(frame.to_2d(v))) end = h;
                    }
                    add_node(region, n, task.start, task.slab_start, end,
                             new_branch(n, task.parent_branch, task.father_node));
                }
                return;
            }
        } else {
            // The root. A part standing on a vertex or a tip has, eps above its base, a speck of
            // a section (or none), and the march would end a step above it, the part unsearched.
            // The root starts at the first plane with more than specks, its first slab still
            // reaching down to the base. A part whose every section is a speck (a pin thinner
            // than a twentieth of the step all the way up) is marched from its first section at
            // least half as large as its largest (not a sliver at its end) when every speck from
            // there on meets one below it, as an upright pin's do: else (a leaning pin, whose
            // march would end at the first section clear of the one below, beside an upright one
            // or not) one node on the last plane, its slab reaching down to the base, stands for
            // each speck there.
            const auto specks = [&](const Regions2& rs) {
                return std::all_of(rs.begin(), rs.end(),
                                   [&](const Region2& r) { return speck(r); });
            };
            const std::size_t k_base = k0;
            first = unswept(g, k0, nullptr);
            std::vector<Regions2> seen;  // the planes' specks, from k_base on
            while (k0 + 1 < count && specks(first)) {
                seen.push_back(std::move(first));
                first = unswept(g, ++k0, nullptr);
            }
            if (specks(first) && !seen.empty()) {
                seen.push_back(first);
                double largest = 0.0;
                for (const auto& rs : seen) largest = std::max(largest, area(rs));
                std::size_t i = 0;
                while (area(seen[i]) < 0.5 * largest) ++i;
                bool stacked = true;  // every speck meets one on the plane below
                for (std::size_t j = i + 1; j < seen.size() && stacked; ++j)
                    for (const Region2& r : seen[j])
                        if (area(intersection({r}, seen[j - 1])) <= p_.min_region_area_mm2) {
                            stacked = false;
                            break;
                        }
                if (stacked) {
                    k0 = k_base + i;
                    first = std::move(seen[i]);
                }
            }
            // A part standing on a point of a rim (a round rod leaning on its end) has, eps above
            // its base, a sliver of a section: narrower on average (twice its area over its
            // outline) than a tenth of the step, and less than a step across, where a face resting
            // on the base gives its footprint, as wide as the part's thinnest wall (twice the
            // derived step), and an edge resting on it a strip as long as the edge. A step above
            // it the section has outgrown the sliver to one side by far more than the sliver's
            // size, which Eq. 3 (d at most a sixth of the lower section's size) reads as the part
            // turning, and the marches across it that the turn's shares start took the rod's
            // length in their first sections: a rod 1 mm across leaning 17 degrees grew a -X
            // branch at its foot and +-Y ones at its middle, its volume searched 1.14 times; a rod
            // 6 mm across leaning 6 degrees lost two thirds of its volume. So the root starts
            // above such a sliver too, at the next plane, its first slab still reaching down to
            // the base, where the part has outgrown the sliver half a step above it and that
            // plane has more than slivers. A sliver still there half a step up is no rim's point
            // but a thin leg, pad or wall, which keeps its first section. (Skipped up to the first
            // plane with more, a 0.05 mm wall 100 mm tall under a cap, at a 1 mm step, became one
            // node whose slab stood for the wall, searched 50 times over; a 10 mm box on a 0.05 x
            // 0.5 mm pad 1 mm tall, which the march from the pad turns into and builds sideways,
            // became one component whose first layer hung 85 mm^2.) A ring standing on its rim,
            // its first section a strip as long as the ring is deep, still turns both ways round
            // the ring; and so does a rod at a step no longer than the sliver is across.
            const auto slivers = [&](const Regions2& rs) {
                return std::all_of(rs.begin(), rs.end(), [&](const Region2& r) {
                    return speck(r) || (mean_width(r) <= p_.step_mm / 10.0 &&
                                        bounds(r).diagonal().norm() < p_.step_mm);
                });
            };
            if (!specks(first) && slivers(first) && k0 + 1 < count &&
                !slivers(half_plane(g, k0 + 1))) {
                Regions2 above = unswept(g, k0 + 1, nullptr);
                if (!slivers(above)) {
                    ++k0;
                    first = std::move(above);
                }
            }
        }
        std::vector<Track> tracks;
        std::vector<Task> hanging;  // branches leaving the first section
        for (const auto& region : first) {
            const int b = new_branch(n, task.parent_branch, task.father_node);
            Regions2 pieces{region};
            if (task.parent_branch >= 0 && k0 > 0)  // a turned branch, not a root in mid-air
                pieces = first_pieces(region, g, k0, b, task.father_node, hanging);
            for (std::size_t i = 0; i < pieces.size(); ++i) {
                const int piece_branch =
                    i == 0 ? b : new_branch(n, task.parent_branch, task.father_node);
                const int node = add_node(pieces[i], n, offset_of(k0), task.slab_start,
                                          slab_end(k0), piece_branch);
                tracks.push_back({piece_branch, node, {}, bounds(pieces[i]), perimeter(pieces[i])});
                tracks.back().region.push_back(std::move(pieces[i]));
            }
        }
        for (const auto& child : hanging) search(child, depth + 1);

        Lookahead ahead(*this, g, k0 + 1);
        for (std::size_t k = k0 + 1; k < count && !tracks.empty(); ++k) {
            checkpoint_(searched_);
            // Each upper region alone in a list, as the Booleans take it (no copies).
            std::vector<Eigen::AlignedBox2d> near;
            for (const auto& t : tracks) near.push_back(t.box);
            std::vector<Regions2> upper;
            for (auto& r : ahead.take(k, near)) {
                upper.emplace_back();
                upper.back().push_back(std::move(r));
            }
            // Each upper region continues the track it overlaps most (Eq. 2's projection).
            // The overlap is read off U - L (area(U) - area(U - L)), which Eq. 2 needs anyway:
            // one Boolean per pair instead of two.
            std::vector<int> owner(upper.size(), -1);
            std::vector<std::vector<int>> overlapping(upper.size());
            std::vector<Regions2> stick_out(upper.size());
            for (std::size_t j = 0; j < upper.size(); ++j) {
                // An overlap no wider than the Booleans' snapping along the shorter outline is
                // none: the hairlines a turn's U - far leaves along the outlines it took away (the
                // far pieces' edges are off U's by a grid unit) would otherwise carry a march to
                // whatever they touch (a blade's unswept tip, which the decomposition then cut
                // off lengthwise).
                const double outline = perimeter(upper[j].front());
                double best = p_.min_region_area_mm2;
                const Eigen::AlignedBox2d box = bounds(upper[j].front());
                const double upper_area = area(upper[j]);
                for (std::size_t t = 0; t < tracks.size(); ++t) {
                    if (!box.intersects(tracks[t].box)) continue;
                    Regions2 d = difference(upper[j], tracks[t].region);
                    const double a = upper_area - area(d);
                    if (a <= std::max(p_.min_region_area_mm2,
                                      kHairline * std::min(outline, tracks[t].outline)))
                        continue;
                    overlapping[j].push_back(static_cast<int>(t));
                    if (overlapping[j].size() == 1) stick_out[j] = std::move(d);
                    if (a > best) {
                        best = a;
                        owner[j] = static_cast<int>(t);
                    }
                }
                if (overlapping[j].size() > 1) {  // merging tracks: U minus all of them
                    Regions2 lower;
                    for (int o : overlapping[j])
                        lower.push_back(tracks[std::size_t(o)].region.front());
                    stick_out[j] = difference(upper[j], lower);
                }
            }
            // A track that overlaps an upper region owned by another track merges into it.
            for (std::size_t j = 0; j < upper.size(); ++j)
                for (int o : overlapping[j])
                    if (o != owner[j] && owner[j] >= 0)
                        branches_[std::size_t(tracks[std::size_t(o)].branch)].merged_into =
                            tracks[std::size_t(owner[j])].branch;
            std::vector<Track> next;
            std::vector<Task> children;
            for (std::size_t t = 0; t < tracks.size(); ++t) {
                Regions2 pieces;
                for (std::size_t j = 0; j < upper.size(); ++j) {
                    if (owner[j] != static_cast<int>(t)) continue;
                    Regions2 lower;
                    for (int o : overlapping[j])
                        lower.push_back(tracks[std::size_t(o)].region.front());
                    for (auto& piece :
                         classify(upper[j].front(), stick_out[j], lower, tracks[t], g, k, children))
                        pieces.push_back(std::move(piece));
                }
                pieces = keep_larger(std::move(pieces), p_.min_region_area_mm2);
                const int lower_node = tracks[t].node;
                for (std::size_t i = 0; i < pieces.size(); ++i) {
                    // One piece continues the branch; several mean the branch splits.
                    const int b = pieces.size() == 1 ? tracks[t].branch
                                                     : new_branch(n, tracks[t].branch, lower_node);
                    const int node =
                        add_node(pieces[i], n, offset_of(k), offset_of(k), slab_end(k), b);
                    const int link = add_link(lower_node, node, AxisLink::Kind::Step);
                    if (branches_[b].first_link < 0 && branches_[b].nodes.size() == 1)
                        branches_[b].first_link = link;
                    next.push_back({b, node, {}, bounds(pieces[i]), perimeter(pieces[i])});
                    next.back().region.push_back(std::move(pieces[i]));
                }
            }
            tracks = std::move(next);
            // Branch-first: every branch found here is searched to its end before this march
            // goes on, so that the march's later sections no longer see its material.
            std::vector<Release> releases;
            releases.swap(releases_);
            if (!children.empty()) ahead.restart(k);
            std::stable_sort(releases.begin(), releases.end(),
                             [](const Release& a, const Release& b) { return a.node < b.node; });
            for (std::size_t i = 0; i < releases.size();) {
                std::size_t j = i;
                std::vector<Release> one_node;
                while (j < releases.size() && releases[j].node == releases[i].node)
                    one_node.push_back(std::move(releases[j++]));
                release(one_node, g, k);
                i = j;
            }
            for (const auto& child : children) search(child, depth + 1);
        }
    }

    // Eq. 2 on one upper region over its lower region(s), given U - L: returns what continues
    // this march and queues a new branch for every stick-out whose centre lies beyond the
    // distance threshold, and for every ledge.
    Regions2 classify(const Region2& upper, const Regions2& stick_out, const Regions2& lower,
                      const Track& track, Grid& planes, std::size_t k,
                      std::vector<Task>& children) {
        if (stick_out.empty()) return {upper};  // Eq. 2: empty, same direction
        const Vector3d& n = planes.normal;
        const double lower_offset = offset(planes, k - 1), upper_offset = offset(planes, k);
        const PlaneFrame frame(n);
        const Plane upper_plane{n * upper_offset, n};
        // Far: centred "much greater than the step" (d) outside L, and not a bump on a large
        // section's surface: a stick-out centred within an eighth of L's size, reaching no
        // farther than that, is one. One that reaches farther is an overhang growing out of the
        // part however near its centre stays (the underside of a blade leaving a hub at a small
        // angle adds a long strip beside the last one at every plane).
        const double size = std::sqrt(area(lower));
        const double bump = size / 8.0;
        // Eq. 3's d. Derived (twice the step), it is at most a sixth of L's size: on a thick part
        // the step, half its thinnest wall, is a large part of a section, and two steps can be
        // more than half what a lug or boss sticks out (a 10 mm boss on a 30 mm column, step
        // 4.6 mm), which would leave it in its father, its underside overhanging. Given, it is
        // used as given.
        const double d = derived_threshold_ ? std::min(p_.distance_threshold_mm, size / 6.0)
                                            : p_.distance_threshold_mm;
        // How far `piece`'s outline reaches outside every lower region, as far as it matters:
        // the farthest of its points not skipped, or the first found farther than `upto`. A
        // point within `within` of the last point of L found nearest to an earlier one is within
        // `within` of L, and skipped: along a stick-out hugging L only every few points need the
        // search through L's edges. Exact wherever it exceeds `within`.
        const auto reach = [&](const Regions2& piece, double within, double upto) {
            double farthest = 0.0;
            for (const auto& r : piece) {
                bool witness_known = false;
                Vector2d witness = Vector2d::Zero();  // a point of L (boundary or inside)
                for (const auto& q : r.outer.points) {
                    if (witness_known && (q - witness).norm() <= within) continue;
                    double to_lower = std::numeric_limits<double>::infinity();
                    for (const auto& l : lower) {
                        if (contains(l, q)) {
                            to_lower = 0.0;
                            witness = q;
                            break;
                        }
                        const Vector2d b = nearest_boundary_point(l, q);
                        const double d = (b - q).norm();
                        if (d < to_lower) {
                            to_lower = d;
                            witness = b;
                        }
                    }
                    farthest = std::max(farthest, to_lower);
                    if (farthest > upto) return farthest;
                    witness_known = true;
                }
            }
            return farthest;
        };
        // Whether any point of `piece`'s outline lies farther than `limit` outside every lower
        // region.
        const auto reaches = [&](const Regions2& piece, double limit) {
            return reach(piece, limit, limit) > limit;
        };
        const auto is_far = [&](const Regions2& piece, double centre_distance) {
            if (centre_distance <= d) return false;
            return centre_distance > bump || reaches(piece, bump);
        };
        // Across a march along `side` (perpendicular to n): the span of `regions`' outer loops
        // along and across it.
        const auto spans = [&](const Regions2& regions, const Vector3d& side) {
            const Vector2d along(side.dot(frame.u), side.dot(frame.v));
            const Vector2d across(-along.y(), along.x());
            Eigen::AlignedBox2d box;  // (along, across)
            for (const auto& r : regions)
                for (const auto& q : r.outer.points)
                    box.extend(Vector2d(along.dot(q), across.dot(q)));
            return box;
        };
        // Where a march along `side` starts when `piece` lies beside a fin of the lower regions
        // `from`: `piece` reaches less than a step past their extent T along side (the march
        // from T would find a sliver of it at most) and begins more than a step behind T, and
        // what of `from` lies past where it begins is fins under the stick-out: each within the
        // stick-out's span across side (all of this plane's), no wider across than half of it
        // nor than half `from`, and longer along side than wide, with less area than `piece`
        // together. With the stick-out appearing at once (the caller
        // asks), that is a web or gusset under an arm's flat underside, ending at the arm's end:
        // the march starts at the face the web stands on (the column's), where the arm does.
        // A column's own material past that place is no fin: a round column's, whose surface
        // the stick-out meets behind its extent, or a narrow column's under an arm more than
        // twice as wide, whose flanks begin at its far side (or at the arm's far end, for a
        // march back along the arm).
        const auto fin_root = [&](const Regions2& piece, const Regions2& from, const Vector3d& side,
                                  double t) -> std::optional<double> {
            if (piece.empty()) return std::nullopt;
            const Eigen::AlignedBox2d own = spans(piece, side);
            if (own.max().x() - t >= p_.step_mm || t - own.min().x() < p_.step_mm)
                return std::nullopt;
            const double root = own.min().x();
            const Regions2 fins = split_at(from, frame, side, root).first;
            const Eigen::AlignedBox2d out = spans(stick_out, side), whole = spans(from, side);
            const double tolerance = p_.step_mm / 100.0;
            double fin_area = 0.0;
            for (const auto& f : fins) {
                const Eigen::AlignedBox2d box = spans({f}, side);
                const double across = box.sizes().y();
                if (box.min().y() < out.min().y() - tolerance ||
                    box.max().y() > out.max().y() + tolerance ||
                    across > 0.5 * std::min(out.sizes().y(), whole.sizes().y()) ||
                    box.sizes().x() < across)
                    return std::nullopt;
                fin_area += area(f);
            }
            if (fins.empty() || fin_area >= area(piece)) return std::nullopt;
            return root;
        };
        Regions2 far;
        // The box of the lower plane's whole section (for the ledges' limit, below), and what
        // layers at slicing's defaults lay (a twentieth over, for a round column's chords).
        Eigen::AlignedBox2d whole_lower;
        for (const auto& b : planes.bounds2[k - 1]) whole_lower.extend(b);
        whole_lower.min().array() -= p_.step_mm / 100.0;
        whole_lower.max().array() += p_.step_mm / 100.0;
        const double laid = 1.05 * laid_overhang_mm();
        // A wide stick-out found along the march, or one turning, is split at its necks and its
        // pieces judged each (below), after the stick-outs given: they are kept here.
        Regions2 split;
        // The pieces of `r` that necks narrower than twice a hundredth of the step join, each
        // smaller than `r` (none where it has no such neck).
        const auto necked = [&](const Region2& r) {
            const double whole = area(r);
            Regions2 pieces;
            for (auto& piece : split_at_necks({r}, p_.step_mm / 100.0, p_.min_region_area_mm2))
                if (area(piece) < whole - p_.min_region_area_mm2)
                    pieces.push_back(std::move(piece));
            return pieces;
        };
        // This plane's stick-outs reaching out past L by more than a plane's spacing (45
        // degrees), centred a quarter of L's size or more off the centroid of the lower region
        // nearest to them (a collar widening all round leans no one way): each with the way it
        // leans out of that region, from its centroid, as a steep limb turns (forks, in
        // steep_limb below).
        struct Leaning {
            Vector3d way;
            const Region2* piece;
            const Region2* lower;
        };
        std::optional<std::vector<Leaning>> leaning_found;  // found when a fork is first asked
        const auto leaning = [&]() -> const std::vector<Leaning>& {
            if (leaning_found) return *leaning_found;
            leaning_found.emplace();
            const double spacing = upper_offset - lower_offset;
            for (const auto& piece : stick_out) {
                if (area(piece) <= p_.min_region_area_mm2 || !reaches({piece}, spacing)) continue;
                const Vector2d g = centroid(piece);
                const Region2* nearest = &track.region.front();
                double best = std::numeric_limits<double>::infinity();
                for (const auto& l : lower) {
                    const double d_l = distance_to_region(l, g);
                    if (d_l < best) {
                        best = d_l;
                        nearest = &l;
                    }
                }
                const Vector2d c = centroid(*nearest);
                if ((g - c).norm() >= size / 4.0)  // centred off C, as a steep limb is
                    leaning_found->push_back(
                        {closest_axis(frame.to_3d(g, upper_plane) - frame.to_3d(c, upper_plane)),
                         &piece, nearest});
            }
            return *leaning_found;
        };
        for (std::size_t next = 0; next < stick_out.size() + split.size(); ++next) {
            // Not used past a piece appended to `split` (which may move its regions).
            const Region2& da =
                next < stick_out.size() ? stick_out[next] : split[next - stick_out.size()];
            if (area(da) <= p_.min_region_area_mm2) continue;
            const Vector2d g = centroid(da);
            std::optional<Emergence> how;  // emergence(da), once asked
            const auto emerged = [&]() -> const Emergence& {
                if (!how) how = emergence(da, planes, k);
                return *how;
            };
            const auto at_once = [&] { return emerged().at_once(); };
            double dist = std::numeric_limits<double>::infinity();
            Vector2d exit = g;  // where the stick-out leaves the lower section
            const Region2* left = &track.region.front();  // the lower region it leaves
            for (const auto& l : lower) {
                // On L's external contour (Eq. 2): a stick-out centred in L's hole (a collar round
                // a pipe) is centred inside L, not far out of it.
                Region2 filled;
                if (!l.holes.empty()) filled.outer = l.outer;
                const Region2& outline = l.holes.empty() ? l : filled;
                const double d = distance_to_region(outline, g);
                if (d < dist) {
                    dist = d;
                    exit = nearest_boundary_point(outline, g);
                    left = &l;
                }
            }
            bool turn = is_far({da}, dist);
            // Material spanning between two lower regions (over a hole, where tracks merge) is
            // a bridge that joins them, not a part turning away.
            if (turn && lower.size() > 1) {
                const Regions2 grown = mas::offset({da}, p_.step_mm / 100.0, JoinType::Miter);
                int touched = 0;
                for (const auto& l : lower)
                    if (area(intersection(grown, {l})) > p_.min_region_area_mm2) ++touched;
                if (touched > 1) turn = false;
            }
            Vector3d dir = n;
            bool along = false;  // far, but still along the march
            if (turn) {
                // The turn follows the way the stick-out leaves the lower section: from where it
                // meets it to G. Where it meets it is the centroid of what of L lies within two
                // hundredths of a step of the stick-out opened by one (a sliver U - L keeps along
                // L's outline would draw it round L), or, where that meets L nowhere, the nearest
                // point of L's boundary to G. (The paper's G - C sends a lug near the end of a
                // long wall along the wall, past the part, and its material is never searched.
                // From the nearest point, a twisted blade's lowest edge, leaving a round hub
                // aslant and centred 15 degrees round from where it leaves, turned a march 59.5
                // degrees off the blade.)
                const double w = p_.step_mm / 100.0;
                const Regions2 contact =
                    intersection(mas::offset(opening({da}, w), 2.0 * w, JoinType::Miter), lower);
                const Vector2d from = area(contact) > 0.0 ? centroid(contact) : exit;
                dir = closest_axis(frame.to_3d(g, upper_plane) - frame.to_3d(from, upper_plane) +
                                   n * (upper_offset - lower_offset));
                along = std::abs(dir.dot(n)) > 0.5;
                turn = !along;
            }
            // Reaching out past every lower region by more than half their size: wrapping round
            // the lower section (below). With a derived threshold, how far it reaches is read
            // down to the ledge's limit at once: more than a step and than a bump, or than what
            // layers at slicing's defaults lay (a twentieth over, for a round column's chords).
            // (Past the bump alone, a 6 mm lug on a 60 mm block stayed in its layers, its first
            // layer hanging 4 mm past what they lay.) Out of the box of the lower plane's whole
            // section, hanging over nothing of the part, more than a step and than a bump, or than
            // what those layers lay: a thick part's step, half its thinnest wall, can be more than
            // they lay (a manifold block's boss reaching out 5.6 mm, under its 5.8 mm step, stayed
            // in the block's layers, 23.8 mm^2 hanging). Within it (a hole's ceiling closing over
            // it), always more than a step: built sideways from each side of a lug's pin hole, its
            // ceiling hung more than it does in the lug's layers (6.1 and 6.3 mm^2 became 11.9 and
            // 7.2 on two lugs).
            const double wide_limit = std::max(p_.distance_threshold_mm, 4.0 * bump);
            const double ledge_limit = whole_lower.contains(bounds(da))
                                           ? std::max(p_.step_mm, std::min(bump, laid))
                                           : std::min(std::max(p_.step_mm, bump), laid);
            const double matters =
                derived_threshold_ ? std::min(ledge_limit, wide_limit) : wide_limit;
            double out_of_lower = turn ? 0.0 : reach({da}, matters, wide_limit);
            // Read on what is wider than twice the sections' simplification (step / 100): U - L
            // can trail a hairline along a wall where a slab's cut and the section it is taken
            // from differ by microns, and its far end is no material reaching out. (Where a bore
            // across a ring narrows over its axis, the strip its wall adds, 0.14 mm wide, trailed
            // one 4 microns wide for 5 mm along the slabs of the bore's boss: read as a ledge
            // reaching 5.3 mm out, it turned a march across the ring's upper half, and the
            // decomposition, its cut through the bores refused, left the bosses in the body.)
            // Within the box of the lower plane's whole section only, where such walls are: out of
            // it, hanging over nothing of the part, a stick-out is material however thin. (A
            // boss's first sliver under its lowest line, 0.09 mm wide and reaching 8.1 mm out of
            // a block at a 4.46 mm step, was opened away, and the boss stayed in the block's
            // layers, 27.0 mm^2 hanging in one.)
            if (out_of_lower > matters && whole_lower.contains(bounds(da))) {
                const double w = p_.step_mm / 100.0;
                out_of_lower = reach(opening({da}, w), matters, wide_limit);
            }
            const bool wide = out_of_lower > wide_limit;
            // A ledge: material that appears at once between the planes (on an underside flat
            // along the march, or tangent to its planes), reaching out past the lower section by
            // more than the ledge's limit (above; a step: steeper than 45 degrees over it), not
            // round it. Near or not, the march cannot lay it (its first layer would hang in the
            // air), so it turns the way it leaves the lower section, without Eq. 3's test of its
            // centre.
            // Only with a derived threshold: one given is used as given. (Kept in the march, a
            // staircase's 5 mm steps left 88 mm^2 and a cube's 6 mm lip 142 mm^2 unsupported.)
            // Material spanning a gap is a bridge, as above.
            // A round underside across the march (a boss on a wall, its axis square to the march)
            // appears gradually across it, so at_once() holds only where the planes fall near its
            // lowest line; but what of it the half plane holds already reaches out nearly as far
            // as the stick-out does (three quarters of it at least), as a flat underside does,
            // while a side sloping out over the step reaches out there about half as far. (A boss
            // 25 mm across on a round body 48 mm across reaches out farther at the corners of
            // wider sections: 0.89 of it, half a step up from near its lowest line.) Its first
            // layer hangs all the same. (A 13 mm boss sticking out 6.7 mm from a 41 x 31 mm block
            // stayed in the block's layers: 28 mm^2 overhung in one layer.) Only centred a third
            // of its reach out of L or more, as a prism sticking out is (at half): a stick-out
            // hugging L, as an organic body's bulges do, stays even where a point of it reaches
            // out (turned, CGAL's armadillo grew 21 branches, 62 to 83, in 45 % more time). Its
            // reach for that is how far past E it goes the way it would turn (the direction
            // closest to G_k - E), where that is less than its farthest point's distance from L:
            // a wide strip of a boss on a round body reaches farther out at its corners, where
            // the body curves away, than along the boss. (A valve body's boss, radius 9.3 on a
            // body of 12.8, sticking out 5.7 mm: a plane 4 mm over its lowest line cuts a strip
            // reaching out 5.7 mm along the boss and 7.25 mm at its corners, centred 2.42 mm out;
            // it stayed in the body's layers, 20 mm^2 overhanging.)
            const auto reaches_out_at_once = [&] {
                double out = out_of_lower;
                if (dist > 0.0) {
                    const Vector3d way3 =
                        closest_axis(frame.to_3d(g, upper_plane) - frame.to_3d(exit, upper_plane));
                    const Vector2d way(way3.dot(frame.u), way3.dot(frame.v));
                    double along_way = 0.0;
                    for (const auto& q : da.outer.points)
                        along_way = std::max(along_way, way.dot(q - exit));
                    out = std::min(out, along_way);
                }
                return dist >= out / 3.0 && emerged().is_new &&
                       reaches(emerged().half, 0.75 * out_of_lower);
            };
            // A steep limb: a branch leaning out of the march by more than kSteepLimb planes'
            // spacing a plane. Its section moves on along the way it leans, and U - L is a crescent
            // round the end of it, centred inside L (Eq. 3's distance 0), so Eq. 3 never turns
            // into it however far it goes, and its underside hangs in the march's layers. (A
            // branch leaning 70 degrees off a round column, 1.13 mm apart, moves 3.1 mm a plane:
            // its underside overhung the column's layers by 8.5 mm^2 in one, 70 in all.) It is a
            // crescent centred inside L, reaching out of it by more than that, new on this plane
            // (not in the section below), centred a quarter of L's size or more off L's centroid C
            // (a cone or a ball widening all round is centred on C), whose limb L already holds
            // by more than that past where it leaves the march's section (below): its end moves
            // on plane after plane. (A boss's round underside does not: its end stays where its
            // first sliver was, and a sliver is centred out of L. Turned from its first sliver, a
            // valve body's boss was marched from there and its split refused.) A limb much
            // thinner than what it leaves moves on as far, but its crescent, wider than the
            // narrow end of L it grows round, is centred out of L, though nearer it than Eq. 3's
            // d: then its end must also move past L's, the way it leans, by more than that on
            // this plane. (A branch of radius 5.5 leaning 63.8 degrees off a column of 10.7, 6.6
            // mm a 3.26 mm spacing, its crescents centred 0.8 mm out of L, stayed in the column's
            // layers until it parted from it, 4.4 mm^2 hanging in one. A round underside's end
            // moves out by less plane after plane as the round flattens: a hub lying across a
            // post, 2.3 then 1.3 mm a 1.5 mm spacing, and L held it 2.28 mm past the post's
            // side; turned there, one blade below it was cut in two.) The march turns
            // from C, as a ledge centred inside L does, and starts where the limb leaves the
            // march's section (limb_root): Eq. 4's T on the section found going down from L
            // through the regions under it, plane by plane, while each reaches out along the
            // turn's way by more than a plane's spacing (45 degrees) past the one under it, and
            // one plane more where the last reaches out less past a side running straight up
            // (as far out on the plane under that, within a hundredth of a step): the limb's
            // first sliver, its underside begun between the planes. (A branch leaning 68.9
            // degrees off a column of radius 11.4 reached 1.5 mm past it on the plane over its
            // underside's start, at a 3.51 mm step; cut there, the wedge between hung 1.4 mm^2
            // in the column's layers.) From L's own T, what L holds of the limb stayed in the
            // march's layers, a wedge hanging under the cut (8.5 mm^2 in one layer of a survey
            // part, as before); going down only while the limb grew steeper than kSteepLimb, the
            // first sliver of another, 54 degrees, did (2.6 mm^2).
            const double spacing = upper_offset - lower_offset;
            const double steep = kSteepLimb * spacing;
            // The regions of plane j that overlap `at` and their extent along `side`.
            const auto under = [&](const Regions2& at, std::size_t j, const Vector3d& side) {
                cut_chunk(planes, j);
                Eigen::AlignedBox2d box;
                for (const auto& r : at) box.extend(bounds(r));
                std::pair<Regions2, double> out{{}, -std::numeric_limits<double>::infinity()};
                for (auto& r : regions_near(planes, j, box)) {
                    if (area(intersection({r}, at)) <= p_.min_region_area_mm2) continue;
                    out.second = std::max(out.second, extent_along(r, n, offset(planes, j), side));
                    out.first.push_back(std::move(r));
                }
                return out;
            };
            // Where `at`, regions of plane j whose extent along `side` is `t`, reaches past the
            // regions under it by less than a plane's spacing: the extent of those below where
            // that is a limb's first sliver over a side that runs straight up under it (the plane
            // below that reaches out as far, within a hundredth of a step): the limb's underside
            // began between the planes, already past 45 degrees, and the sliver is its start,
            // not a gentler root. Otherwise `t`.
            const auto sliver_root = [&](const Regions2& below, std::size_t j, const Vector3d& side,
                                         double t, double t_below) {
                const double tolerance = p_.step_mm / 100.0;
                if (t - t_below <= tolerance || j < 2) return t;
                const auto [under_that, t_under] = under(below, j - 2, side);
                return !under_that.empty() && std::abs(t_below - t_under) <= tolerance ? t_below
                                                                                       : t;
            };
            // From L, whose extent along `side` is `t`.
            const auto limb_root = [&](const Region2& from, const Vector3d& side, double t) {
                Regions2 at{from};
                for (std::size_t j = k - 1; j > 0; --j) {
                    auto [below, t_below] = under(at, j - 1, side);
                    if (below.empty()) break;
                    if (t - t_below <= spacing) return sliver_root(below, j, side, t, t_below);
                    t = t_below;
                    at = std::move(below);
                }
                return t;
            };
            // For a steep limb: limb_root() along the turn's way, and how far L holds the limb
            // past it (L's extent that way less the root).
            double root = 0.0, held = 0.0;
            // How far `from`, whose extent along `way` is `end`, holds a limb leaning that way
            // past where it leaves the march's section.
            const auto hold = [&](const Region2& from, const Vector3d& way, double end) {
                return end - limb_root(from, way, end);
            };
            // A fork: two limbs leaning apart, each reaching out past L by more than a plane's
            // spacing (45 degrees) and begun within the last three planes (held by L past its
            // root by more than a spacing and by no more than four: a limb leaning 45 to 56
            // degrees grows 1 to kSteepLimb spacings a plane).
            // The march's layers lean as its centroids move, towards neither limb, so each limb's
            // underside overhangs every layer (a solid wye with two laterals leaning 56.2
            // degrees off its riser hung 3.5 mm^2 in each of its layers up to where they parted,
            // 101 mm^2 in all): each is a steep limb from a spacing a plane on. A side that has
            // long leaned out (an elephant's belly, a body widening over its legs) is none: taken
            // for one where the other side began to lean, CGAL's elephant's belly was cut deep
            // into its body, where the nozzle could not build it, and kept in the body it hung
            // 23.1 mm^2 in a layer where it hangs 15.5.
            const auto fresh = [&](double h) { return h > spacing && h <= 4.0 * spacing; };
            const auto opposed = [&](const Vector3d& way) {
                for (const auto& other : leaning())
                    if (other.piece != &da && other.way.dot(way) < -0.5) return true;
                return false;
            };
            const auto forked = [&](const Vector3d& way) {
                for (const auto& other : leaning()) {
                    if (other.piece == &da || other.way.dot(way) > -0.5) continue;
                    if (fresh(hold(*other.lower, other.way,
                                   extent_along(*other.lower, n, lower_offset, other.way))))
                        return true;
                }
                return false;
            };
            const auto steep_limb = [&] {
                const Vector2d c = centroid(*left);
                if ((g - c).norm() < size / 4.0) return false;
                const Vector3d way =
                    closest_axis(frame.to_3d(g, upper_plane) - frame.to_3d(c, upper_plane));
                const double end = extent_along(*left, n, lower_offset, way);  // L's, that way
                // Given that the crescent reaches out past L by more than `limit`.
                const auto limb_at = [&](double limit) {
                    if (!emerged().is_new) return false;
                    if (dist > 0.0 && extent_along(da, n, upper_offset, way) - end <= limit)
                        return false;
                    root = limb_root(*left, way, end);
                    held = end - root;
                    return held > limit;
                };
                // However far it reaches past L: wide too (past the distance threshold and four
                // bumps), where a stick-out is otherwise shared out round L, each share turning
                // only where its centre lies far (four round arms rising 15.5 degrees off a hub,
                // reaching 11.2 and 14.8 mm past the section below at a 5.6 mm step, turned a
                // plane late, 23.6 mm out, and their roots hung 21 mm^2 in a layer of the hub's),
                // where its root lies past L's centroid the way it leans: a rod standing on the
                // rim of its end outgrows the sliver there past it, the section growing, no limb.
                // A fork's limbs, within it only.
                if (reaches({da}, steep) && limb_at(steep))
                    return !wide || root > way.dot(frame.to_3d(c, upper_plane));
                // A fork's limb, the cheap tests first: another stick-out, and one leaning the
                // other way.
                if (wide || stick_out.size() < 2 || !reaches({da}, spacing) || !opposed(way))
                    return false;
                return limb_at(spacing) && fresh(held) && forked(way);
            };
            bool ledge = false, limb = false;
            if (derived_threshold_ && !turn &&
                ((!wide && out_of_lower > ledge_limit && (at_once() || reaches_out_at_once())) ||
                 (limb = steep_limb())) &&
                !spans_a_gap(da, lower)) {
                // Out of L from E, or, centred inside L (an arm's underside round the web under
                // it), from L's centroid C (the paper's G_k - C). Centred on C itself (a head or
                // a collar all round a rod), it goes no one way: reaching out more than two
                // bumps, it wraps round L (below), and its shares turn as a ledge's; less, it is
                // a shoulder, which the march lays (split into four pieces, a shaft's 2 mm
                // shoulder on a 12 mm rod tapered over the volumetric bound and overhung more).
                const Vector2d from = dist > 0.0 ? exit : centroid(*left);
                const Vector3d out = frame.to_3d(g, upper_plane) - frame.to_3d(from, upper_plane);
                if (out.norm() > p_.step_mm / 100.0) {
                    const Vector3d way = closest_axis(out);
                    if (closes_a_gap(da, Vector2d(way.dot(frame.u), way.dot(frame.v)), planes, k)) {
                        limb = false;  // a hole's ceiling: the march lays it
                    } else {
                        dir = way;
                        turn = ledge = true;
                    }
                } else {
                    ledge = out_of_lower > 2.0 * bump || out_of_lower > 1.05 * laid_overhang_mm();
                }
            }
            // Turning, it may be stick-outs of several features that such a sliver joins (below):
            // each is judged on its own. (Two blades of a hub 62.7 degrees apart, their first
            // slivers joined along the hub's outline, made one ledge centred between them that
            // turned along +X; shared out by sides, the outer half of the blade 62.7 degrees
            // round went along +X too, and its layers overhung 8.5 mm^2 each.)
            if ((turn || ledge) && next < stick_out.size()) {
                Regions2 pieces = necked(da);
                if (pieces.size() > 1) {
                    for (auto& piece : pieces) split.push_back(std::move(piece));
                    continue;
                }
            }
            if (!turn && !ledge && (along || !wide)) {
                // Far but along the march; or near, or a bridge, and not wide. Wide and along,
                // its centre near L, it may be stick-outs that a sliver along L's outline joins:
                // sections are simplified within step / 100, so two sections of one wall can
                // differ by twice that, and U - L keeps the sliver between them (two blades a
                // quarter turn apart round a hub, their joint centre near the hub: neither turned,
                // 74.6 mm^2 overhanging). Split where such necks join larger pieces, each piece is
                // judged on its own.
                if (along && wide)
                    for (auto& piece : necked(da)) split.push_back(std::move(piece));
                continue;
            }
            // Otherwise (not a turn, yet reaching out past every lower region by more than half
            // their size) the stick-out wraps round the lower section or spans past the regions
            // it joins: a hub lying across the neck it stands on, whose two ends make one
            // stick-out centred on the neck. Its shares beyond the lower section's sides may each
            // turn. (Reaching out less, it is the part widening, as an organic body does at its
            // shoulders: turned, CGAL's armadillo grew 35 branches and took twice as long.)
            const bool around = !turn;
            // Wrapping round L on a flat underside (a shelf through a column, wider than it),
            // its shares turn as a ledge's too: what reaches out of the bump past a side. So do
            // those of a far stick-out on a flat underside beside the turn's own: a crank's web
            // round the shaft it leaves hangs past the shaft's other sides from its first layer.
            if (!ledge && derived_threshold_ && at_once() && !spans_a_gap(da, lower)) ledge = true;
            // A march in a new direction starts at Eq. 4's T, the lower boundary's extent along
            // it, and reaches only what lies beyond. The stick-out is shared out among the four
            // sides of the lower section, the turn's own first: each side's share beyond its T
            // whose centre still lies beyond the threshold starts a march that way. What lies
            // beyond no side, or too close, stays with this march. (Handing the whole stick-out to
            // one march lost the rest: an inward lip, centred in the bore it narrows, went to a
            // march starting outside the part; CGAL's turbine.off lost 8 % of its volume so.)
            Regions2 rest{da};
            const std::vector<Vector3d> sides =
                sides_from(around ? axis_vector((axis_index(n) + 1) % 3, 1.0) : dir, n);
            // The first side's march, and how many this stick-out starts (whole, below).
            const std::size_t children_before = children.size();
            std::optional<std::size_t> front_child;
            for (const Vector3d& side : sides) {
                if (rest.empty()) break;
                // Beyond the extent of the lower region it leaves (where tracks merge, not
                // necessarily this track's: a cornice on the far pier of a portal, whose march
                // would otherwise start at the near pier's face and never reach it, its slab lost
                // all the same); around the lower section, beyond every lower region's.
                double t_max = extent_along(*left, n, lower_offset, side);
                if (around)
                    for (const auto& l : lower)
                        t_max = std::max(t_max, extent_along(l, n, lower_offset, side));
                // Beside a fin of the lower section (a web under an arm, its tip flush with the
                // arm's end), the march from T would find nothing: it starts where the stick-out
                // does, at the face the fin stands on, which is then T.
                const std::optional<double> fin =
                    fin_root(rest, around ? lower : Regions2{*left}, side, t_max);
                const bool at_fin = fin.has_value() && at_once();
                if (at_fin) t_max = fin.value();
                // A steep limb's march starts at its root and takes all of U beyond it that the
                // crescent is part of: from there the crescent is far ahead of its first plane.
                const bool limb_side = limb && side == sides.front();
                if (limb_side) t_max = root;
                // So does a far turn's where what L holds past the plane under it is the first
                // sliver of what turns, over a side running straight up (sliver_root()): its
                // march starts at that side. (Four round arms rising 17.1 degrees off a hub,
                // reaching out far on the plane over their first slivers, 1.1 mm past its side in
                // L, were cut there, and the wedge of each root under the cut hung in the hub's
                // layers, 10 mm^2 in one.)
                bool sliver = false;
                if (turn && !ledge && !limb && !at_fin && side == sides.front() && k > 1) {
                    auto [below, t_below] = under({*left}, k - 2, side);
                    if (!below.empty() && t_max - t_below <= spacing) {
                        const double t = sliver_root(below, k - 1, side, t_max, t_below);
                        sliver = t < t_max;
                        t_max = t;
                    }
                }
                const bool at_root = limb_side || sliver;
                auto [share, behind] = split_at(std::move(rest), frame, side, t_max);
                rest = std::move(behind);
                if (at_root) {
                    Regions2 limb_share;
                    for (auto& piece : split_at({upper}, frame, side, t_max).first)
                        if (area(intersection({piece}, share)) > p_.min_region_area_mm2)
                            limb_share.push_back(std::move(piece));
                    if (!limb_share.empty()) share = std::move(limb_share);
                }
                if (share.empty()) continue;
                // Whole: nothing of the stick-out left behind T (to this march, or to other
                // sides); or, after the loop, the only march it starts (below).
                const bool whole = side == sides.front() && area(rest) <= p_.min_region_area_mm2;
                if (area(share) <= p_.min_region_area_mm2) continue;
                const Vector2d g_share = centroid(share);
                double d_share = std::numeric_limits<double>::infinity();
                for (const auto& l : lower)
                    d_share = std::min(d_share, distance_to_region(l, g_share));
                // A ledge's or a fin's share turns wherever it reaches out of the bump (a ledge's,
                // out of what the layers lay, if less: hanging from its first layer, a bracket
                // plate's 6 mm margins past a 50 mm column beside its arm stayed in the column,
                // within its 6.25 mm bump, and overhung 400 mm^2); any other only when far. A
                // steep limb's reaches out of L by its crescent alone, a plane's growth: it turns
                // however far that is where L holds no more than twice as much of the limb past
                // its root, its section beyond the root the limb's own. (A branch leaning 62.6
                // degrees, 1.77 mm a plane under a 2 mm bump, stayed in the column's layers, 3.3
                // mm^2 hanging in one. An elephant's belly, 11.6 mm out past its leg in L and
                // 1.2 mm further a plane, is the body widening: turned along it, its underside
                // hung in the leg's layers, 45 mm^2 in one.)
                const bool young =
                    limb_side &&
                    held <= 2.0 * reach({da}, 0.0, std::numeric_limits<double>::infinity());
                const double out_of = ledge ? std::min(bump, laid_overhang_mm()) : bump;
                if (!young && (ledge || at_fin ? !reaches(share, out_of) : !is_far(share, d_share)))
                    continue;
                // Eq. 4: the new march starts just beyond the lower boundary's extent T.
                Task child;
                child.direction = side;
                child.start = t_max + p_.eps_mm;
                child.slab_start = t_max;
                child.parent_branch = track.branch;
                child.father_node = track.node;
                child.whole = whole;
                if (at_fin) {
                    // The arm over the fin goes to the new march too (and the node below gives
                    // back what its slab took of it: release()).
                    releases_.push_back(Release{track.node, side, t_max, share});
                    for (auto& r : split_at({upper}, frame, side, t_max).first)
                        far.push_back(std::move(r));
                }
                // The new march keeps the regions of its first section that meet its share
                // swept from the lower plane to one step above the upper one: a strip one plane
                // thick could miss a region that starts a hair above the plane on a faceted
                // surface. Not where the share, within a step past T, parts into pieces some of
                // which U joins to L only further on (U up to the band's end holds no piece
                // meeting both): those are no part of the march leaving L. (A crank's three legs
                // round a gap, the last running back past the riser's face beside it: the march
                // along the first leg took the last one's section on its first plane too and
                // marched it towards its root, its end behind the riser's face left in the riser,
                // and the legs stayed in the riser's layers, 654 mm^2 hanging in one. Left out,
                // the march turns into the second leg where it reaches it, and that one into the
                // last. A piece U joins to L behind T, a blade leaving a round hub aslant, stays:
                // judged on its distance from L instead, the blade lost its march.)
                Regions2 first_share = share;
                if (!at_fin && !limb_side && !sliver) {
                    const double band_end = t_max + p_.eps_mm + 1.01 * p_.step_mm;
                    Regions2 band = split_at(share, frame, side, band_end).second;
                    if (band.size() > 1) {
                        const Regions2 from = around ? lower : Regions2{*left};
                        Regions2 joined;  // the pieces of U up to the band's end meeting L
                        for (auto& r : split_at({upper}, frame, side, band_end).second)
                            if (area(intersection({r}, from)) > p_.min_region_area_mm2)
                                joined.push_back(std::move(r));
                        Regions2 apart;
                        for (auto& piece : band)
                            if (area(intersection({piece}, joined)) <= p_.min_region_area_mm2)
                                apart.push_back(std::move(piece));
                        if (!apart.empty() && apart.size() < band.size())
                            first_share = difference(share, apart);
                    }
                }
                for (auto& r : first_share)
                    child.constraints.push_back(
                        Slab{n, lower_offset, upper_offset + p_.step_mm, std::move(r), {}});
                for (auto& r : share) far.push_back(std::move(r));
                if (side == sides.front()) front_child = children.size();
                children.push_back(std::move(child));
            }
            // The first side's share is the stick-out's whole share too where no other side's
            // share of it turns: what it leaves behind T stays with this march, as behind any
            // turn's T. (A boss on a round body: between the body's curve and the plane square
            // to the boss at its extent, T, its corners hold some of the stick-out, and a boss
            // sticking out 5.1 mm, under a 5.5 mm step, whose march is one node (search()),
            // stayed in a valve body's layers, its round underside hanging 16.8 mm^2 in one.)
            // Another side's turning is an arm's end past the web under it while its flanks
            // turn sideways (search()).
            if (front_child && children.size() == children_before + 1)
                children[*front_child].whole = true;
        }
        if (far.empty()) return {upper};
        // What is left holds hairlines of the Booleans along the shares' split lines (a micron
        // wide, a share's side long): no region, though over the least area. Kept, two of them
        // split a crank's march where its web's shares left its round shaft, and the
        // decomposition cut the shaft across the web.
        Regions2 kept = difference({upper}, far);
        kept.erase(std::remove_if(kept.begin(), kept.end(),
                                  [&](const Region2& r) {
                                      return 2.0 * area(r) < p_.step_mm / 100.0 * perimeter(r);
                                  }),
                   kept.end());
        return kept;
    }

    // FindConnectingLink: a turned branch's first node links to the nearest node of its father
    // branch (the father's march may have gone on past the place the turn was found).
    void connect_turned_branches() {
        for (auto& b : branches_) {
            if (b.parent < 0 || b.nodes.empty() || b.first_link >= 0) continue;
            const int first = b.nodes.front();
            int best = b.parent_node;
            double best_d = std::numeric_limits<double>::infinity();
            for (int f : branches_[std::size_t(b.parent)].nodes) {
                const double d =
                    (nodes_[std::size_t(f)].position - nodes_[std::size_t(first)].position).norm();
                if (d < best_d) {
                    best_d = d;
                    best = f;
                }
            }
            b.parent_node = best;
            b.first_link = add_link(best, first, AxisLink::Kind::Connecting);
        }
    }

    // Links are made in search order, so a link's predecessor is always marked before it.
    void mark_breaks() {
        const double limit = p_.break_angle_deg;
        std::vector<int> order(links_.size());
        std::iota(order.begin(), order.end(), 0);
        // Predecessors first: by the depth of the link's start node in the node tree.
        std::vector<int> depth(nodes_.size(), -1);
        std::function<int(int)> node_depth = [&](int n) -> int {
            if (depth[std::size_t(n)] >= 0) return depth[std::size_t(n)];
            const int in = nodes_[std::size_t(n)].incoming_link;
            return depth[std::size_t(n)] =
                       in < 0 ? 0 : node_depth(links_[std::size_t(in)].start) + 1;
        };
        for (std::size_t n = 0; n < nodes_.size(); ++n) node_depth(int(n));
        std::stable_sort(order.begin(), order.end(), [&](int a, int b) {
            return depth[std::size_t(links_[std::size_t(a)].start)] <
                   depth[std::size_t(links_[std::size_t(b)].start)];
        });
        for (int li : order) {
            AxisLink& l = links_[std::size_t(li)];
            const int pred = nodes_[std::size_t(l.start)].incoming_link;
            if (pred < 0) continue;
            const AxisLink& p = links_[std::size_t(pred)];
            const Vector3d a =
                nodes_[std::size_t(p.end)].position - nodes_[std::size_t(p.start)].position;
            const Vector3d b =
                nodes_[std::size_t(l.end)].position - nodes_[std::size_t(l.start)].position;
            if (a.norm() == 0.0 || b.norm() == 0.0) continue;
            const double cosang = std::clamp(a.normalized().dot(b.normalized()), -1.0, 1.0);
            l.turn_deg = std::acos(cosang) * 180.0 / kPi;
            // A link right after a break only turns back from the connector between two
            // sections' centroids (a split's lower node to a post's first node, say): one break.
            l.is_break = l.turn_deg > limit && !p.is_break;
        }
    }

    const TriangleMesh& mesh_;
    AxisParams p_;
    bool derived_threshold_;
    double volume_;  // the mesh's, mm^3
    const std::function<void(double)>& checkpoint_;
    double searched_ = 0.0;  // the nodes' slabs so far, mm^3
    std::vector<AxisNode> nodes_;
    std::vector<AxisLink> links_;
    std::vector<AxisBranch> branches_;
    // Grown by the march while a Lookahead reads the ones already there from another thread.
    tbb::concurrent_vector<Slab> slabs_;
    std::vector<std::size_t> node_slab_;  // per node: its slab's index in slabs_
    std::vector<Release> releases_;       // found on the plane a march is at, not yet made
    std::array<Grid, 6> grids_;
    std::size_t sections_cut_ = 0;
};

}  // namespace

double derive_axis_step(const TriangleMesh& mesh) {
    const Eigen::AlignedBox3d box = bounding_box(mesh);
    const double diag = box.diagonal().norm();
    if (!(diag > 0.0)) throw Error(ErrorCode::EmptyInput, "the part has no extent");
    // A strip: an elongated region, its width 2A/P, where it was cut.
    struct Strip {
        int axis;
        double offset, width;
        Eigen::AlignedBox2d box;
    };
    std::vector<Strip> strips;
    std::vector<std::unique_ptr<SectionGrid>> grids;
    // A wall shows as an elongated region (a strip); a compact one (a disc, a square) is a wall
    // only when nothing elongated is cut at all: a plane grazing a rounded tip cuts a tiny compact
    // region whose 2A/P says nothing about how thick the part is there.
    double compact = std::numeric_limits<double>::infinity();
    for (int axis = 0; axis < 3; ++axis) {
        const Vector3d n = axis_vector(axis, 1.0);
        const double lo = box.min()[axis], hi = box.max()[axis];
        std::vector<Plane> planes;
        for (int i = 0; i < 16; ++i)
            planes.push_back(Plane{n * (lo + (i + 0.5) * (hi - lo) / 16), n});
        // A grid cuts its planes in parallel (slice_mesh would build their 16 sections on one
        // thread, as one batch).
        grids.push_back(std::make_unique<SectionGrid>(mesh, std::move(planes)));
        for (const auto& s : grids.back()->cut(0, 16))
            for (const auto& r : s.regions) {
                const double per = perimeter(r.shape);
                if (!(per > 0.0 && r.area > 0.0)) continue;
                const double width = 2.0 * r.area / per;
                // P^2 / A is 4 pi for a disc, 16 for a square, 21.3 for a 3:1 rectangle.
                if (per * per / r.area >= 21.0)
                    strips.push_back({axis, n.dot(s.plane.origin), width, bounds(r.shape)});
                else
                    compact = std::min(compact, width);
            }
    }
    // A strip is a wall when the plane its width (at least diagonal / 200) further on or back
    // cuts, where it lies, a region within half as thick again or as thin: a wall goes on beyond
    // its section at its thickness. A plane grazing an edge along it (a twisted blade's lowest
    // edge, a blade's tip, a lying cylinder's top) cuts a strip as thin as it comes, which the
    // part widens from or ends at: it says nothing about the walls. (A blade's tip face nearly
    // along the planes widens slowly: a 0.05 mm strip went on as thin 0.05 mm further.) Nor does
    // a wedge's corner, which goes on only thinner, to its edge. The thinnest strips are tried in
    // turn, up to 32, until one is a wall; those thinner than an eighth of it are grazes, and the
    // thinnest of the others is taken (a strip that does not go on yet comes within that, as a
    // round shaft's cut near its side, still counts). Without a wall among them, the thinnest
    // strip is taken. (A hub's blades twisted 30 degrees: a 0.05 mm graze made the step diagonal /
    // 2000, 0.056 mm, and its axis 3600 nodes; a 2.0 mm strip across a blade makes it 1.0 mm. On
    // another hub, strips 0.6 to 0.9 mm wide at the blades' corners, taken for walls for going on
    // thinner, let a 0.08 mm graze count: step 0.05 mm, 4362 nodes; 0.32 mm and 691 now.)
    std::sort(strips.begin(), strips.end(),
              [](const Strip& a, const Strip& b) { return a.width < b.width; });
    const auto goes_on = [&](const Strip& s) {
        const double further = std::max(s.width, diag / 200.0);
        for (const double side : {-1.0, 1.0})
            for (const auto& r :
                 grids[std::size_t(s.axis)]->cut_at(s.offset + side * further).regions) {
                const double per = perimeter(r.shape);
                if (!(per > 0.0 && bounds(r.shape).intersects(s.box))) continue;
                const double width = 2.0 * r.area / per;
                if (width <= 1.5 * s.width && 1.5 * width >= s.width) return true;
            }
        return false;
    };
    double wall = strips.empty() ? std::numeric_limits<double>::infinity() : strips[0].width;
    for (std::size_t i = 0; i < std::min<std::size_t>(strips.size(), 32); ++i)
        if (goes_on(strips[i])) {
            for (const Strip& s : strips)
                if (s.width >= strips[i].width / 8.0) {
                    wall = s.width;
                    break;
                }
            break;
        }
    double width = std::isfinite(wall) ? wall : compact;
    if (!std::isfinite(width)) width = diag / 10.0;
    // The march needs a step under the height: a part lying flat thinner than diagonal / 2000 (a
    // 100 x 100 x 0.05 mm shim) would otherwise fail on its derived step.
    const double height = box.max().z() - box.min().z();
    return std::min(std::clamp(width / 2.0, diag / 2000.0, diag / 20.0), height / 2.0);
}

namespace {

// `degrees` modulo 90 into (-45, 45].
double frame_angle(double degrees) {
    double a = std::fmod(degrees, 90.0);
    if (a > 45.0) a -= 90.0;
    if (a <= -45.0) a += 90.0;
    return a;
}

// `v` with components under 1e-12 put to 0 (a direction turned back into its frame lies on an
// axis again, exactly).
Vector3d onto_axes(Vector3d v) {
    for (int i = 0; i < 3; ++i)
        if (std::abs(v[i]) < 1e-12) v[i] = 0.0;
    return v.normalized();
}

// atan2(y, x) in degrees within 0.001 degree, without the library's cost (a rational
// approximation of atan on [0, 1], folded into the quadrants).
double quick_atan2_deg(double y, double x) {
    const double ax = std::abs(x), ay = std::abs(y);
    const double big = std::max(ax, ay);
    if (!(big > 0.0)) return 0.0;
    const double a = std::min(ax, ay) / big, s = a * a;
    double r = (((-0.0464964749 * s + 0.15931422) * s - 0.327622764) * s + 1.0) * a;
    if (ay > ax) r = 1.5707963267948966 - r;
    if (x < 0.0) r = kPi - r;
    return (y < 0.0 ? -r : r) / kDegree;
}

}  // namespace

double derive_axis_frame(const TriangleMesh& mesh) {
    // Votes: per facet, n = (b - a) x (c - a) (|n| twice its area), h2 = nx^2 + ny^2, weight
    // area x h2 / |n|^2 = h2 / (2 |n|), for phi = atan2(ny, nx) modulo 90 degrees, read as 4 phi
    // on the circle: the direction of (nx + i ny)^4. Binned by half a degree of phi.
    constexpr int kBins = 180;
    constexpr int kWindow = 4;  // 2 degrees
    struct Votes {
        std::array<double, kBins> weight{};
        std::array<double, kBins> c{}, s{};  // per bin: sum of w (cos 4 phi, sin 4 phi)
        double total = 0.0;
    };
    // In a fixed number of pieces, each on its own, added up in order: the same sums whatever
    // the threads (the frame is a function of the mesh), at about half the time on two cores
    // (0.8 ms for a 75000-facet scan). A small mesh's pieces go one after the other: starting
    // threads would cost more than its votes (0.1 ms against a few microseconds for a box).
    constexpr std::size_t kPieces = 8;
    std::array<Votes, kPieces> pieces;
    const std::size_t count = mesh.triangles.size();
    const auto vote = [&](std::size_t piece) {
        Votes& v = pieces[piece];
        const std::size_t end = count * (piece + 1) / kPieces;
        for (std::size_t i = count * piece / kPieces; i < end; ++i) {
            const auto& t = mesh.triangles[i];
            const Vector3d& a = mesh.vertices[std::size_t(t[0])];
            const Vector3d n =
                (mesh.vertices[std::size_t(t[1])] - a).cross(mesh.vertices[std::size_t(t[2])] - a);
            const double h2 = n.x() * n.x() + n.y() * n.y();
            if (!(h2 > 0.0)) continue;
            const double len = std::sqrt(h2 + n.z() * n.z());
            if (!std::isfinite(len)) continue;
            // (nx + i ny)^2 = (p, q), ^4 = (p^2 - q^2, 2 p q), of length h2^2.
            const double p = n.x() * n.x() - n.y() * n.y(), q = 2.0 * n.x() * n.y();
            const double c4 = p * p - q * q, s4 = 2.0 * p * q;
            const auto bin =
                std::size_t(int(std::floor((quick_atan2_deg(s4, c4) + 180.0) / 2.0)) % kBins);
            const double w = h2 / (2.0 * len);
            const double scale = w / (h2 * h2);
            v.weight[bin] += w;
            v.c[bin] += scale * c4;
            v.s[bin] += scale * s4;
            v.total += w;
        }
    };
    if (count < 20000) {
        for (std::size_t piece = 0; piece < kPieces; ++piece) vote(piece);
    } else {
        tbb::parallel_for(std::size_t(0), kPieces, vote);
    }
    Votes all;
    for (const Votes& v : pieces) {
        for (int k = 0; k < kBins; ++k) {
            all.weight[std::size_t(k)] += v.weight[std::size_t(k)];
            all.c[std::size_t(k)] += v.c[std::size_t(k)];
            all.s[std::size_t(k)] += v.s[std::size_t(k)];
        }
        all.total += v.total;
    }
    const auto& bins = all.weight;
    const double total = all.total;
    if (!(total > 0.0)) return 0.0;
    const auto window = [&](int first) {
        double w = 0.0;
        for (int k = 0; k < kWindow; ++k) w += bins[std::size_t((first + k) % kBins)];
        return w;
    };
    int best = 0;
    for (int i = 1; i < kBins; ++i)
        if (window(i) > window(best)) best = i;
    const double peak = window(best);
    // Any other 2 degrees, apart from the peak's: those round 0 (a part square to the document's
    // axes but for some sides), or a second set of sides (a web tapering symmetrically about X).
    double other = 0.0;
    for (int i = 0; i < kBins; ++i) {
        const int apart = std::abs(i - best);
        if (std::min(apart, kBins - apart) >= kWindow) other = std::max(other, window(i));
    }
    if (peak < kAxisFrameAgreement * total || other >= 0.5 * peak) return 0.0;
    double mc = 0.0, ms = 0.0;
    for (int k = 0; k < kWindow; ++k) {
        mc += all.c[std::size_t((best + k) % kBins)];
        ms += all.s[std::size_t((best + k) % kBins)];
    }
    const double frame = frame_angle(std::atan2(ms, mc) / 4.0 / kDegree);
    return std::abs(frame) < kAxisFrameMinDeg ? 0.0 : frame;
}

CentroidalAxis turned_about_z(const CentroidalAxis& axis, double degrees) {
    const Eigen::Matrix3d r = Eigen::AngleAxisd(degrees * kDegree, Vector3d::UnitZ()).matrix();
    CentroidalAxis out = axis;
    for (auto& node : out.nodes) {
        const PlaneFrame from(node.normal);
        const Plane plane{node.normal * node.offset, node.normal};
        node.position = r * node.position;
        node.normal = onto_axes(r * node.normal);
        if (node.interior.allFinite()) node.interior = r * node.interior;
        const PlaneFrame to(node.normal);
        const auto turn = [&](Polygon2& poly) {
            for (auto& q : poly.points) q = to.to_2d(r * from.to_3d(q, plane));
        };
        turn(node.region.outer);
        for (auto& hole : node.region.holes) turn(hole);
    }
    for (auto& branch : out.branches) branch.direction = onto_axes(r * branch.direction);
    const double was = std::isfinite(axis.params.frame_deg) ? axis.params.frame_deg : 0.0;
    out.params.frame_deg = frame_angle(was + degrees);
    return out;
}

double axis_frame_deg(const CentroidalAxis& axis, const std::string& caller) {
    std::optional<double> frame;
    for (const auto& branch : axis.branches) {
        const Vector3d& d = branch.direction;
        if (std::hypot(d.x(), d.y()) < 1e-6 * d.norm()) continue;  // along +-Z
        const double a = frame_angle(std::atan2(d.y(), d.x()) / kDegree);
        if (!frame) {
            frame = a;
        } else if (std::abs(frame_angle(a - *frame)) > 1e-6) {
            throw Error(ErrorCode::InvalidArgument,
                        caller + ": the axis' branch directions are not those of one frame (" +
                            format_number(*frame) + " and " + format_number(a) +
                            " degrees about Z)");
        }
    }
    // An axis turned back into its frame has its directions on the axes again (onto_axes).
    return frame && std::abs(*frame) > 1e-9 ? *frame : 0.0;
}

namespace {

CentroidalAxis compute_axis_in_frame(const TriangleMesh& mesh, const AxisParams& params,
                                     const std::function<void(double)>& checkpoint);

// `checkpoint(fraction)` is called now and then with the volume swept so far over the part's
// (at most 0.99: the slabs may sweep a little more than the volume); it may throw to stop. The
// part is turned into its frame (AxisParams::frame_deg), marched there, and its axis turned back.
CentroidalAxis compute_axis(const TriangleMesh& mesh, const AxisParams& params,
                            const std::function<void(double)>& checkpoint) {
    if (mesh.empty()) throw Error(ErrorCode::EmptyInput, "centroidal axis: the mesh is empty");
    if (std::isinf(params.frame_deg))
        throw Error(ErrorCode::InvalidArgument,
                    "centroidal axis: the frame must be a finite angle in degrees (NaN: derived "
                    "from the part)");
    const double frame =
        std::isnan(params.frame_deg) ? derive_axis_frame(mesh) : frame_angle(params.frame_deg);
    AxisParams p = params;
    p.frame_deg = 0.0;
    if (frame == 0.0) return compute_axis_in_frame(mesh, p, checkpoint);
    const Eigen::Matrix3d back = Eigen::AngleAxisd(-frame * kDegree, Vector3d::UnitZ()).matrix();
    TriangleMesh turned = mesh;
    for (auto& v : turned.vertices) v = back * v;
    return turned_about_z(compute_axis_in_frame(turned, p, checkpoint), frame);
}

CentroidalAxis compute_axis_in_frame(const TriangleMesh& mesh, const AxisParams& params,
                                     const std::function<void(double)>& checkpoint) {
    AxisParams p = params;
    auto positive = [](double v) { return std::isfinite(v) && v > 0.0; };
    if (!std::isfinite(p.step_mm) || !std::isfinite(p.distance_threshold_mm))
        throw Error(ErrorCode::InvalidArgument,
                    "centroidal axis: step and distance threshold must be finite");
    if (!positive(p.eps_mm))
        throw Error(ErrorCode::InvalidArgument, "centroidal axis: eps must be positive");
    if (!std::isfinite(p.break_angle_deg) || p.break_angle_deg < 0.0 || p.break_angle_deg > 180.0)
        throw Error(ErrorCode::InvalidArgument,
                    "centroidal axis: break angle must be between 0 and 180 degrees");
    if (!(p.min_region_area_mm2 >= 0.0))
        throw Error(ErrorCode::InvalidArgument,
                    "centroidal axis: minimum region area must be >= 0");
    const Eigen::AlignedBox3d box = bounding_box(mesh);
    const double height = box.max().z() - box.min().z();
    if (p.step_mm <= 0.0) p.step_mm = derive_axis_step(mesh);
    if (p.step_mm >= height) {
        std::ostringstream msg;
        msg << "centroidal axis: step " << p.step_mm << " mm is not smaller than the part's height "
            << height << " mm";
        throw Error(ErrorCode::InvalidArgument, msg.str());
    }
    // Each direction's grid holds a plane per step across the part: a step so small that one
    // march could pass more planes than the axis may have nodes is named before any is allocated
    // (a 10 mm part at 1e-7 mm would take tens of gigabytes).
    const double planes = box.sizes().maxCoeff() / p.step_mm;
    if (planes > double(p.max_nodes)) {
        std::ostringstream msg;
        msg << "centroidal axis: step " << p.step_mm
            << " mm is too small for this part: across its " << box.sizes().maxCoeff()
            << " mm it would take " << planes << " sections, more than " << p.max_nodes
            << " (the most nodes an axis may have)";
        throw Error(ErrorCode::InvalidArgument, msg.str());
    }
    if (p.eps_mm >= height) {
        std::ostringstream msg;
        msg << "centroidal axis: eps " << p.eps_mm << " mm is not smaller than the part's height "
            << height << " mm";
        throw Error(ErrorCode::InvalidArgument, msg.str());
    }
    const bool derived_threshold = p.distance_threshold_mm <= 0.0;
    if (derived_threshold) p.distance_threshold_mm = 2.0 * p.step_mm;
    double base = box.min().z();
    if (std::isfinite(p.base_z_mm)) {
        if (std::abs(base - p.base_z_mm) > p.eps_mm) {
            std::ostringstream msg;
            msg << "centroidal axis: the part does not stand on its base plane z = " << p.base_z_mm
                << " mm (its lowest point is at z = " << base << " mm)";
            throw Error(ErrorCode::InvalidArgument, msg.str());
        }
        base = p.base_z_mm;
    }
    p.base_z_mm = base;
    const double volume = std::abs(mesh_volume(mesh));
    const std::function<void(double)> swept = [&](double searched) {
        checkpoint(volume > 0.0 ? std::min(searched / volume, 0.99) : 0.0);
    };
    CentroidalAxis axis = Search(mesh, p, derived_threshold, volume, swept).run(base);
    if (axis.nodes.empty()) {
        std::ostringstream msg;
        msg << "centroidal axis: no section of the part has an area over " << p.min_region_area_mm2
            << " mm^2 (its box is " << box.sizes().x() << " x " << box.sizes().y() << " x "
            << box.sizes().z() << " mm: lengths are in millimetres)";
        throw Error(ErrorCode::InvalidArgument, msg.str());
    }
    // A march that lost material is no axis of the part: a part thinner than a step given, which
    // no plane's section carries on to the next (a round rod 1 mm across and 30 long leaning 17
    // degrees under a 10 mm block, at a 10 mm step, was swept 3 % of it), is named here with the
    // remedy, where the decomposition would refuse the axis as another part's (check_axis_belongs,
    // the same slack). A march that sweeps too much (a region searched twice) is left to that.
    const double slack =
        sweep_slack(axis.nodes, axis.links, axis.branches, p.step_mm, volume).short_of;
    if (axis.searched_volume_mm3 < volume - slack) {
        std::ostringstream msg;
        msg << "centroidal axis: the march at a step of " << format_number(p.step_mm)
            << " mm swept " << format_number(axis.searched_volume_mm3, 4) << " mm^3 of the part's "
            << format_number(volume, 4) << " ("
            << format_number(100.0 * axis.searched_volume_mm3 / volume, 2) << " %): ";
        if (params.step_mm > 0.0) {
            msg << "what is thinner than the step was lost; give a smaller step";
            const double derived = derive_axis_step(mesh);
            if (derived < p.step_mm)
                msg << ", such as the one derived from the part, " << format_number(derived)
                    << " mm (a step of 0 derives it)";
        } else {
            msg << "some of it was lost at the step derived from the part; give a smaller step";
        }
        throw Error(ErrorCode::InvalidArgument, msg.str());
    }
    return axis;
}

}  // namespace

CentroidalAxis centroidal_axis(const TriangleMesh& mesh, const AxisParams& params,
                               const std::function<void()>& throw_on_cancel) {
    return compute_axis(mesh, params, [&](double) {
        if (throw_on_cancel) throw_on_cancel();
    });
}

CentroidalAxis centroidal_axis(const TriangleMesh& mesh, const AxisParams& params,
                               const Progress& progress) {
    const Progress marching = progress.span(0.0, 1.0, "centroidal axis");
    // The fraction done is the volume swept over the part's; 1 only when done.
    CentroidalAxis axis = compute_axis(mesh, params, marching);
    marching(1.0);
    return axis;
}

void check_axis_belongs(const CentroidalAxis& axis, const Eigen::AlignedBox3d& box, double volume,
                        const std::string& caller) {
    const std::string what =
        caller + ": the axis was computed for a different part than the one given";
    if (axis.nodes.empty() || axis.branches.empty())
        throw Error(ErrorCode::InvalidArgument, caller + ": the centroidal axis is empty");
    // Indices first: everything below follows them.
    const auto node_ok = [&](int n) { return n >= 0 && std::size_t(n) < axis.nodes.size(); };
    for (const auto& l : axis.links)
        if (!node_ok(l.start) || !node_ok(l.end))
            throw Error(ErrorCode::InvalidArgument, caller + ": the axis has a dangling link");
    for (std::size_t i = 0; i < axis.nodes.size(); ++i)
        if (axis.nodes[i].branch < -1 || axis.nodes[i].branch >= int(axis.branches.size()))
            throw Error(ErrorCode::InvalidArgument,
                        caller + ": the axis' node " + std::to_string(i) + " names branch " +
                            std::to_string(axis.nodes[i].branch) + ", which it lacks");
    for (std::size_t b = 0; b < axis.branches.size(); ++b) {
        const auto& br = axis.branches[b];
        bool ok = br.parent < int(b) && !br.nodes.empty() &&
                  std::all_of(br.nodes.begin(), br.nodes.end(), node_ok) &&
                  br.first_link < int(axis.links.size());
        if (ok && br.parent >= 0)
            ok = br.first_link >= 0 && axis.links[std::size_t(br.first_link)].end == br.nodes[0];
        if (!ok)
            throw Error(ErrorCode::InvalidArgument,
                        caller + ": the axis' branch " + std::to_string(b) +
                            " is malformed (a father after it, no nodes or a dangling link)");
    }
    // A node's slab starts on its plane, or (a march's first node) at most a step and eps before;
    // a root's first node's at the base plane, however far below (a part standing on a tip).
    const double slab_tol = 1e-9 * (1.0 + box.diagonal().norm());
    const std::vector<char> root_start = root_starts(axis.nodes.size(), axis.branches);
    for (std::size_t i = 0; i < axis.nodes.size(); ++i) {
        const auto& n = axis.nodes[i];
        const bool from_base =
            root_start[i] && std::abs(n.slab_start - axis.params.base_z_mm) <= slab_tol;
        if (!(n.slab_start <= n.offset + slab_tol &&
              (from_base ||
               n.slab_start >= n.offset - axis.params.step_mm - axis.params.eps_mm - slab_tol)))
            throw Error(ErrorCode::InvalidArgument,
                        caller + ": the axis' node " + std::to_string(i) +
                            " is malformed (its slab starts past its plane, or more than a step "
                            "and eps before it)");
    }
    if (!(std::isfinite(axis.deflection_mm) && axis.deflection_mm >= 0.0))
        throw Error(ErrorCode::InvalidArgument,
                    caller + ": the axis' deflection must be a non-negative number of mm");
    const double grow = std::max(axis.params.step_mm, 0.0) + 1e-6;
    const Eigen::AlignedBox3d grown(box.min() - Vector3d::Constant(grow),
                                    box.max() + Vector3d::Constant(grow));
    for (const auto& n : axis.nodes)
        if (!grown.contains(n.position))
            throw Error(ErrorCode::InvalidArgument,
                        what + " (a node lies outside the part's bounding box)");
    // The slabs approximate the part's volume (sweep_slack).
    const SweepSlack slack =
        sweep_slack(axis.nodes, axis.links, axis.branches, axis.params.step_mm, volume);
    if (axis.searched_volume_mm3 < volume - slack.short_of ||
        axis.searched_volume_mm3 > volume + slack.over)
        throw Error(ErrorCode::InvalidArgument,
                    what + " (it sweeps " + format_number(axis.searched_volume_mm3, 10) +
                        " mm^3, the part has " + format_number(volume, 10) + " mm^3)");
}

}  // namespace mas
