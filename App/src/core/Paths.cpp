// Deposition paths of one layer (see Paths.hpp): contours, raster or contour-parallel infill and
// centre-line passes of narrow pieces, ordered nearest-next. Everything runs on Clipper's integer
// grid (ClipperConvert.hpp).
//
// A region is worked level by level, with w the bead width and s = w (1 - overlap):
// - C_k, the room of level k, is the region inset by k s (C_0 is the region itself); L_k, where
//   the bead centres of level k run, is C_k inset by w/2. So the contour k of the header is the
//   outline of L_k for k < contour_count, and L_contour_count holds the infill's bead centres.
//   Insets use mitred joins: a rectangle's inset is the rectangle, and an inset of an inset equals
//   one inset by the sum.
// - T_k, the part of C_k that the beads of level k - 1 leave uncovered, is C_k inset by
//   overlap w (T_0 = C_0).
// - A piece of C_k whose L_k is empty is narrower than one bead: if its T_k is not empty too, it
//   gets centre lines. Where L_k is not empty, what of T_k lies outside L_k grown back by w/2 (plus
//   the arc tolerance, which swallows the grid's slivers) is a part too thin for the level's beads
//   (a thin tail, the tip of a corner sharper than 60 degrees): each such residue piece from
//   w x arc tolerance up gets centre lines too, or is listed in `unfilled`.
// - Raster: lines at every edge parallel to them and every local extreme of the loops across them
//   (so that no band is left beside such an edge), evenly spread in between at most s apart,
//   clipped to L_k (grown by a hair, so that a line along an edge stays whole). What their beads
//   leave of T_k (the gaps between line ends along an edge at a shallow angle) gets centre lines
//   where it is at least w/4 wide on average (its axis cut where it pinches below w/8); smaller
//   scallops are only reported from w^2 / 4 up.
// - Centre lines run along the piece's medial axis, from Boost.Polygon's segment Voronoi diagram
//   (the method PrusaSlicer uses for thin walls): the interior primary edges of the diagram of the
//   piece's boundary segments, without those between two segments that do not face each other
//   (more than 67.5 degrees from anti-parallel): those run into corners (a right angle or blunter),
//   not along the piece. The longest path of that graph (double-sweep Dijkstra) is one pass; a
//   cycle (a narrow ring) is a closed pass; what is left of the graph gives further passes while
//   they are at least min_feature_mm long. An open pass that runs into a wall of its room is
//   trimmed there by w/2 - r (r the axis' distance to the boundary there, at most a third of its
//   length), so that its round bead end reaches the wall instead of running past it: a strip l
//   long and t < w wide gets a pass l - w long (l - t before the trim). A piece whose axis is
//   shorter than min_feature_mm (a speck, a blob narrower than a bead in every direction) goes to
//   `unfilled`.
// - Order: regions nearest-next; in each, its contours then its infill, each nearest-next from
//   where the head is, a loop only after the loop of the level before that runs around it (the
//   nearest one of the same sense), and a centre line after the nearest loop of the level before.
#include "mas/Paths.hpp"

#include <algorithm>
#include <boost/polygon/point_data.hpp>
#include <boost/polygon/segment_data.hpp>
#include <boost/polygon/voronoi.hpp>
#include <clipper.hpp>
#include <cmath>
#include <deque>
#include <limits>
#include <queue>
#include <sstream>
#include <string>
#include <unordered_map>

#include "ClipperConvert.hpp"
#include "mas/Angles.hpp"
#include "mas/Error.hpp"

namespace mas {

namespace {

using clipper_convert::kScale;
using clipper_convert::to_int;
using clipper_convert::to_mm;
using ClipperLib::cInt;
using ClipperLib::IntPoint;
using ClipperLib::Path;
using ClipperLib::Paths;

// As mas::offset: a mitre reaches at most 2 x the offset (corners sharper than 60 degrees are
// squared off).
constexpr double kMiterLimit = 2.0;
constexpr double kMaxFacingDeviation = 3 * kPi / 8;  // medial-axis edges kept (see top of file)
// Raster lines per infill piece: guards a tiny bead spacing. Ordering the lines' segments takes
// time growing with their square: 10000 lines (a 1 m piece at a 0.1 mm spacing) take a second.
constexpr std::size_t kMaxRasterLines = 10000;
constexpr int kMaxLevels = 10000;  // offset levels per region: guards a tiny bead width
constexpr int kMaxCentreLinesPerPiece = 32;

[[noreturn]] void invalid(const std::string& message) {
    throw Error(ErrorCode::InvalidArgument, message);
}

// ---- pieces: connected polygons with holes on Clipper's grid ------------------------------------

// loops[0] is the outer loop (positive orientation), the others its holes (negative).
struct Piece {
    Paths loops;
};
using Pieces = std::vector<Piece>;

void split(const ClipperLib::PolyNode& node, Pieces& out) {
    for (const ClipperLib::PolyNode* child : node.Childs) {
        if (child->IsOpen()) continue;
        Piece piece;
        if (child->Contour.size() >= 3) piece.loops.push_back(child->Contour);
        for (const ClipperLib::PolyNode* hole : child->Childs) {
            if (!piece.loops.empty() && hole->Contour.size() >= 3)
                piece.loops.push_back(hole->Contour);
            split(*hole, out);  // islands inside the hole
        }
        if (!piece.loops.empty()) out.push_back(std::move(piece));
    }
}

// A closed result's pieces, as Clipper nested them; where it nested them wrongly, nested again
// by containment as mas::difference's regions are (clipper_convert::regions_of), their
// coordinates through millimetres and back unchanged (the grid's integers, well inside double's
// exact range).
Pieces pieces_of(const ClipperLib::PolyTree& tree) {
    Pieces out;
    if (clipper_convert::nested_right(tree)) {
        split(tree, out);
        return out;
    }
    for (const Region2& region : clipper_convert::regions_of(tree)) {
        if (region.outer.points.size() < 3) continue;
        Piece piece;
        piece.loops.push_back(clipper_convert::to_path(region.outer));
        for (const auto& hole : region.holes)
            if (hole.points.size() >= 3) piece.loops.push_back(clipper_convert::to_path(hole));
        out.push_back(std::move(piece));
    }
    return out;
}

Paths loops_of(const Pieces& pieces) {
    Paths out;
    for (const auto& p : pieces) out.insert(out.end(), p.loops.begin(), p.loops.end());
    return out;
}

// Grows (delta > 0) or insets (delta < 0) closed loops with mitred corners.
Pieces offset_pieces(const Paths& loops, double delta_mm, double arc_units) {
    if (loops.empty()) return {};
    ClipperLib::ClipperOffset off(kMiterLimit, arc_units);
    off.AddPaths(loops, ClipperLib::jtMiter, ClipperLib::etClosedPolygon);
    ClipperLib::PolyTree tree;
    off.Execute(tree, delta_mm * kScale);
    return pieces_of(tree);
}

// True when some loop encloses area (Clipper's Execute fails on input with none).
bool any_loop(const Paths& loops) {
    return std::any_of(loops.begin(), loops.end(),
                       [](const Path& l) { return l.size() >= 3 && ClipperLib::Area(l) != 0.0; });
}

Pieces boolean(ClipperLib::ClipType type, const Paths& a, const Paths& b) {
    if (!any_loop(a)) return {};
    ClipperLib::Clipper clipper;
    clipper.StrictlySimple(true);
    clipper.AddPaths(a, ClipperLib::ptSubject, true);
    if (!b.empty()) clipper.AddPaths(b, ClipperLib::ptClip, true);
    ClipperLib::PolyTree tree;
    if (!clipper.Execute(type, tree, ClipperLib::pftNonZero, ClipperLib::pftNonZero))
        throw Error(ErrorCode::GeometryFailure, "polygon Boolean operation failed");
    return pieces_of(tree);
}

double area_mm2(const Paths& loops) {
    double a = 0.0;
    for (const auto& l : loops) a += ClipperLib::Area(l);
    return a / (kScale * kScale);
}

// Area and centroid of loops (several pieces possibly).
UnfilledFeature feature(int region, const Paths& loops) {
    UnfilledFeature f;
    f.region = region;
    f.area_mm2 = area_mm2(loops);
    Eigen::Vector2d moment = Eigen::Vector2d::Zero();
    double total = 0.0;
    Eigen::Vector2d mean = Eigen::Vector2d::Zero();
    std::size_t count = 0;
    for (const auto& l : loops) {
        const Polygon2 p = clipper_convert::from_path(l);
        const double a = signed_area(p);
        moment += a * centroid(p);
        total += a;
        for (const auto& q : p.points) mean += q;
        count += p.points.size();
    }
    f.centroid = std::abs(total) > 0.0
                     ? Eigen::Vector2d(moment / total)
                     : Eigen::Vector2d(mean / double(std::max<std::size_t>(count, 1)));
    return f;
}

// ---- settings -----------------------------------------------------------------------------------

struct Settings {
    double w = 1.0;        // bead width, mm
    double s = 1.0;        // distance between neighbouring bead centres, mm
    double overlap = 0.0;  // fraction of a bead shared with its neighbour
    double tol = 0.01;     // arc tolerance, mm
    double arc_units = 1e3;
    double min_feature = 0.5;
    double residue_min_area = 0.01;  // mm^2
    double edge_eps = 1e-3;          // raster clip area grown by this, mm
    int contour_count = 0;
    InfillPattern infill = InfillPattern::Raster;
    double raster_angle = 0.0;  // rad
    double seam = 0.0;          // rad
};

// ---- seams --------------------------------------------------------------------------------------

// Rotates a closed loop so that it starts at the vertex whose direction from the loop's centroid
// is closest to `angle`.
void place_seam(std::vector<Eigen::Vector2d>& points, double angle) {
    if (points.size() < 2) return;
    const Eigen::Vector2d c = centroid(Polygon2{points});
    const Eigen::Vector2d d(std::cos(angle), std::sin(angle));
    std::size_t best = 0;
    double best_cos = -std::numeric_limits<double>::infinity();
    for (std::size_t i = 0; i < points.size(); ++i) {
        const Eigen::Vector2d v = points[i] - c;
        const double n = v.norm();
        const double cs = n > 0.0 ? v.dot(d) / n : -2.0;
        if (cs > best_cos + 1e-12) {
            best_cos = cs;
            best = i;
        }
    }
    std::rotate(points.begin(), points.begin() + std::ptrdiff_t(best), points.end());
}

Path2 make_loop(const Path& loop, bool hole, Path2::Kind kind, int region, double seam) {
    Path2 p;
    p.kind = kind;
    p.region = region;
    p.closed = true;
    p.points.reserve(loop.size());
    for (const auto& q : loop) p.points.push_back(to_mm(q));
    const double a = signed_area(Polygon2{p.points});
    if ((a < 0.0) != hole) std::reverse(p.points.begin(), p.points.end());
    place_seam(p.points, seam);
    return p;
}

double polyline_length(const std::vector<Eigen::Vector2d>& pts, bool closed) {
    double len = 0.0;
    for (std::size_t i = 1; i < pts.size(); ++i) len += (pts[i] - pts[i - 1]).norm();
    if (closed && pts.size() > 2) len += (pts.front() - pts.back()).norm();
    return len;
}

// ---- centre lines: the medial axis of a narrow piece --------------------------------------------

namespace bp = boost::polygon;
using VSegment = bp::segment_data<int>;
using VPoint = bp::point_data<int>;
using VDiagram = bp::voronoi_diagram<double>;

struct Site {
    bool segment = false;
    Eigen::Vector2d a, b;  // a point site is a
};

double distance_to(const Site& site, const Eigen::Vector2d& p) {
    if (!site.segment) return (p - site.a).norm();
    const Eigen::Vector2d e = site.b - site.a;
    const double len2 = e.squaredNorm();
    const double t = len2 > 0.0 ? std::clamp((p - site.a).dot(e) / len2, 0.0, 1.0) : 0.0;
    return (site.a + t * e - p).norm();
}

struct AxisEdge {
    int a = -1, b = -1;
    std::vector<Eigen::Vector2d> points;  // from node a to node b, grid units (local)
    double length = 0.0;
    bool used = false;
};

struct AxisGraph {
    std::vector<Eigen::Vector2d> node_position;
    std::vector<double> node_radius;         // distance to the piece's boundary, grid units
    std::vector<std::vector<int>> incident;  // edge indices
    std::vector<AxisEdge> edges;
};

struct AxisLine {
    std::vector<Eigen::Vector2d> points;  // grid units (local)
    bool closed = false;
    double r_front = 0.0, r_back = 0.0;
    double length = 0.0;
    double width = 0.0;  // twice the mean distance to the boundary along the line
};

// Even-odd test against every loop of the piece (local grid units).
bool inside_loops(const std::vector<std::vector<Eigen::Vector2d>>& loops,
                  const Eigen::Vector2d& q) {
    bool in = false;
    for (const auto& p : loops) {
        for (std::size_t i = 0, j = p.size() - 1; i < p.size(); j = i++) {
            if ((p[i].y() > q.y()) != (p[j].y() > q.y())) {
                const double x =
                    p[j].x() + (q.y() - p[j].y()) * (p[i].x() - p[j].x()) / (p[i].y() - p[j].y());
                if (q.x() < x) in = !in;
            }
        }
    }
    return in;
}

// Samples the parabolic Voronoi edge between a point site and a segment site, from v0 to v1, so
// that the chords stay within `tol` (grid units) of the arc.
std::vector<Eigen::Vector2d> parabola(const Site& point, const Site& segment,
                                      const Eigen::Vector2d& v0, const Eigen::Vector2d& v1,
                                      double tol) {
    const Eigen::Vector2d e = segment.b - segment.a;
    const double len = e.norm();
    if (len <= 0.0) return {v0, v1};
    const Eigen::Vector2d u = e / len;
    Eigen::Vector2d n(-u.y(), u.x());
    double py = (point.a - segment.a).dot(n);
    if (py < 0.0) {
        n = -n;
        py = -py;
    }
    if (py < 1e-9) return {v0, v1};
    const double px = (point.a - segment.a).dot(u);
    const double x0 = (v0 - segment.a).dot(u), x1 = (v1 - segment.a).dot(u);
    const double step = std::sqrt(8.0 * py * std::max(tol, 1e-6));
    const int count = std::clamp(int(std::ceil(std::abs(x1 - x0) / step)), 1, 64);
    std::vector<Eigen::Vector2d> out;
    out.reserve(std::size_t(count) + 1);
    out.push_back(v0);
    for (int i = 1; i < count; ++i) {
        const double x = x0 + (x1 - x0) * double(i) / double(count);
        const double y = ((x - px) * (x - px) + py * py) / (2.0 * py);
        out.push_back(segment.a + x * u + y * n);
    }
    out.push_back(v1);
    return out;
}

AxisGraph medial_axis(const std::vector<std::vector<Eigen::Vector2d>>& loops,
                      const std::vector<VSegment>& segments, double tol_units,
                      double min_width_units) {
    VDiagram vd;
    bp::construct_voronoi(segments.begin(), segments.end(), &vd);

    auto site_of = [&](const VDiagram::cell_type& cell) {
        const VSegment& seg = segments[cell.source_index()];
        const Eigen::Vector2d a(double(bp::x(bp::low(seg))), double(bp::y(bp::low(seg))));
        const Eigen::Vector2d b(double(bp::x(bp::high(seg))), double(bp::y(bp::high(seg))));
        Site site;
        if (cell.contains_segment()) {
            site.segment = true;
            site.a = a;
            site.b = b;
        } else {
            site.a = cell.source_category() == bp::SOURCE_CATEGORY_SEGMENT_START_POINT ? a : b;
        }
        return site;
    };

    AxisGraph g;
    std::unordered_map<const VDiagram::vertex_type*, int> ids;
    auto node = [&](const VDiagram::vertex_type* v, double r) {
        auto it = ids.find(v);
        if (it != ids.end()) return it->second;
        const int id = int(g.node_position.size());
        ids.emplace(v, id);
        g.node_position.emplace_back(v->x(), v->y());
        g.node_radius.push_back(r);
        g.incident.emplace_back();
        return id;
    };
    const double facing = -std::cos(kMaxFacingDeviation);
    for (const auto& e : vd.edges()) {
        if (!e.is_primary() || !e.is_finite() || e.twin() < &e) continue;
        const Site s0 = site_of(*e.cell()), s1 = site_of(*e.twin()->cell());
        if (s0.segment && s1.segment) {
            const Eigen::Vector2d d0 = (s0.b - s0.a).normalized(), d1 = (s1.b - s1.a).normalized();
            if (d0.dot(d1) > facing) continue;  // not facing each other: a corner's bisector
        }
        const Eigen::Vector2d v0(e.vertex0()->x(), e.vertex0()->y());
        const Eigen::Vector2d v1(e.vertex1()->x(), e.vertex1()->y());
        std::vector<Eigen::Vector2d> pts;
        if (e.is_curved())
            pts = s0.segment ? parabola(s1, s0, v0, v1, tol_units)
                             : parabola(s0, s1, v0, v1, tol_units);
        else
            pts = {v0, v1};
        const Eigen::Vector2d mid =
            pts.size() > 2 ? pts[pts.size() / 2] : Eigen::Vector2d(0.5 * (v0 + v1));
        if (!inside_loops(loops, mid)) continue;
        // An end outside the piece (off its boundary) would mean a diagram the input broke.
        const double r0 = distance_to(s0, v0), r1 = distance_to(s0, v1);
        if ((r0 > 2.0 && !inside_loops(loops, v0)) || (r1 > 2.0 && !inside_loops(loops, v1)))
            continue;
        if (r0 + r1 < min_width_units) continue;  // narrower than asked for
        AxisEdge edge;
        edge.a = node(e.vertex0(), r0);
        edge.b = node(e.vertex1(), r1);
        if (edge.a == edge.b) continue;
        edge.length = polyline_length(pts, false);
        edge.points = std::move(pts);
        g.incident[std::size_t(edge.a)].push_back(int(g.edges.size()));
        g.incident[std::size_t(edge.b)].push_back(int(g.edges.size()));
        g.edges.push_back(std::move(edge));
    }
    return g;
}

// Farthest node from `from` over unused edges: distances and the edge each node was reached by.
int farthest(const AxisGraph& g, int from, std::vector<double>& dist, std::vector<int>& via) {
    const double inf = std::numeric_limits<double>::infinity();
    dist.assign(g.node_position.size(), inf);
    via.assign(g.node_position.size(), -1);
    using Item = std::pair<double, int>;
    std::priority_queue<Item, std::vector<Item>, std::greater<Item>> queue;
    dist[std::size_t(from)] = 0.0;
    queue.push({0.0, from});
    int best = from;
    while (!queue.empty()) {
        const auto [d, n] = queue.top();
        queue.pop();
        if (d > dist[std::size_t(n)]) continue;
        if (d > dist[std::size_t(best)]) best = n;
        for (int ei : g.incident[std::size_t(n)]) {
            const AxisEdge& e = g.edges[std::size_t(ei)];
            if (e.used) continue;
            const int m = e.a == n ? e.b : e.a;
            const double dm = d + e.length;
            if (dm < dist[std::size_t(m)]) {
                dist[std::size_t(m)] = dm;
                via[std::size_t(m)] = ei;
                queue.push({dm, m});
            }
        }
    }
    return best;
}

void append_edge(const AxisEdge& e, bool forward, std::vector<Eigen::Vector2d>& out) {
    const std::size_t start = out.empty() ? 0 : 1;  // the joint point is already there
    if (forward)
        out.insert(out.end(), e.points.begin() + std::ptrdiff_t(start), e.points.end());
    else
        out.insert(out.end(), e.points.rbegin() + std::ptrdiff_t(start), e.points.rend());
}

// Passes along the axis graph: the longest path (or a cycle) of each connected part, repeatedly,
// while they are at least `min_length` long. `longest` receives the longest found.
std::vector<AxisLine> axis_lines(AxisGraph& g, double min_length, double& longest) {
    std::vector<AxisLine> lines;
    std::vector<double> dist;
    std::vector<int> via;
    auto unused_degree = [&](int n) {
        int d = 0;
        for (int ei : g.incident[std::size_t(n)]) d += g.edges[std::size_t(ei)].used ? 0 : 1;
        return d;
    };
    for (std::size_t seed = 0; seed < g.edges.size();) {
        if (g.edges[seed].used) {
            ++seed;
            continue;
        }
        // The connected part of the seed edge.
        std::vector<int> nodes, stack{g.edges[seed].a};
        std::vector<char> seen(g.node_position.size(), 0);
        seen[std::size_t(stack.back())] = 1;
        while (!stack.empty()) {
            const int n = stack.back();
            stack.pop_back();
            nodes.push_back(n);
            for (int ei : g.incident[std::size_t(n)]) {
                const AxisEdge& e = g.edges[std::size_t(ei)];
                if (e.used) continue;
                const int m = e.a == n ? e.b : e.a;
                if (!seen[std::size_t(m)]) {
                    seen[std::size_t(m)] = 1;
                    stack.push_back(m);
                }
            }
        }
        auto mark_part_used = [&] {
            for (int n : nodes)
                for (int ei : g.incident[std::size_t(n)]) g.edges[std::size_t(ei)].used = true;
        };
        AxisLine line;
        // Runs edge ei of the axis from node n onto the line; returns the node it ends at.
        auto take_edge = [&](int ei, int n) {
            AxisEdge& e = g.edges[std::size_t(ei)];
            const bool forward = e.a == n;
            append_edge(e, forward, line.points);
            line.length += e.length;
            line.width +=
                e.length * (g.node_radius[std::size_t(e.a)] + g.node_radius[std::size_t(e.b)]);
            e.used = true;
            return forward ? e.b : e.a;
        };
        const bool cycle =
            std::all_of(nodes.begin(), nodes.end(), [&](int n) { return unused_degree(n) == 2; });
        if (cycle) {
            line.closed = true;
            int n = nodes.front(), prev_edge = -1;
            for (std::size_t k = 0; k < nodes.size(); ++k) {
                int next_edge = -1;
                for (int ei : g.incident[std::size_t(n)])
                    if (ei != prev_edge && !g.edges[std::size_t(ei)].used) next_edge = ei;
                if (next_edge < 0) break;
                n = take_edge(next_edge, n);
                prev_edge = next_edge;
            }
            if (line.points.size() > 1) line.points.pop_back();  // back at the start
        } else {
            int start = nodes.front();
            for (int n : nodes)
                if (unused_degree(n) == 1) {
                    start = n;
                    break;
                }
            const int a = farthest(g, start, dist, via);
            const int b = farthest(g, a, dist, via);
            std::vector<int> chain;
            for (int n = b; n != a;) {
                const int ei = via[std::size_t(n)];
                chain.push_back(ei);
                const AxisEdge& e = g.edges[std::size_t(ei)];
                n = e.a == n ? e.b : e.a;
            }
            std::reverse(chain.begin(), chain.end());
            int n = a;
            for (int ei : chain) n = take_edge(ei, n);
            line.r_front = g.node_radius[std::size_t(a)];
            line.r_back = g.node_radius[std::size_t(b)];
        }
        if (line.length > 0.0) line.width /= line.length;
        longest = std::max(longest, line.length);
        if (line.length < min_length || line.points.size() < 2) {
            mark_part_used();  // its longest path is too short: so is everything else in it
            continue;
        }
        lines.push_back(std::move(line));
        if (int(lines.size()) >= kMaxCentreLinesPerPiece) break;
    }
    return lines;
}

// Cuts `length` off the front of an open polyline.
void trim_front(std::vector<Eigen::Vector2d>& pts, double length) {
    while (length > 0.0 && pts.size() >= 2) {
        const double seg = (pts[1] - pts[0]).norm();
        if (seg > length) {
            pts[0] += (pts[1] - pts[0]) * (length / seg);
            return;
        }
        length -= seg;
        pts.erase(pts.begin());
    }
}

// Centre lines of a narrow piece, in mm, at least `min_width` wide on average, along the parts of
// its medial axis at least half that wide (the axis is cut where the piece pinches, between two
// scallops of a raster's ends); `axis_length` receives the longest axis path (mm).
std::vector<AxisLine> centre_lines(const Piece& piece, const Settings& set, double min_width,
                                   double& axis_length) {
    axis_length = 0.0;
    // Boost.Polygon wants segments that meet only at their ends: near-duplicate points dropped,
    // then a strictly simple union (no vertex touching another loop's edge).
    Paths loops = piece.loops;
    ClipperLib::CleanPolygons(loops);
    {
        ClipperLib::Clipper clipper;
        clipper.StrictlySimple(true);
        clipper.AddPaths(loops, ClipperLib::ptSubject, true);
        Paths simple;
        if (!clipper.Execute(ClipperLib::ctUnion, simple, ClipperLib::pftNonZero,
                             ClipperLib::pftNonZero))
            return {};
        loops = std::move(simple);
    }
    loops.erase(
        std::remove_if(loops.begin(), loops.end(), [](const Path& l) { return l.size() < 3; }),
        loops.end());
    if (loops.empty()) return {};
    // Local integer frame for Boost.Polygon (32-bit coordinates).
    cInt min_x = loops.front().front().X, min_y = loops.front().front().Y;
    cInt max_x = min_x, max_y = min_y;
    for (const auto& l : loops)
        for (const auto& p : l) {
            min_x = std::min(min_x, p.X);
            min_y = std::min(min_y, p.Y);
            max_x = std::max(max_x, p.X);
            max_y = std::max(max_y, p.Y);
        }
    if (max_x - min_x > (cInt(1) << 30) || max_y - min_y > (cInt(1) << 30))
        invalid("a narrow region is too long for its centre line (over 10 m)");
    std::vector<VSegment> segments;
    std::vector<std::vector<Eigen::Vector2d>> local;
    for (const auto& l : loops) {
        local.emplace_back();
        for (const auto& p : l) local.back().emplace_back(double(p.X - min_x), double(p.Y - min_y));
        for (std::size_t i = 0; i < l.size(); ++i) {
            const IntPoint& p = l[i];
            const IntPoint& q = l[(i + 1) % l.size()];
            if (p == q) continue;
            segments.emplace_back(VPoint(int(p.X - min_x), int(p.Y - min_y)),
                                  VPoint(int(q.X - min_x), int(q.Y - min_y)));
        }
    }
    AxisGraph graph =
        medial_axis(local, segments, 0.25 * set.tol * kScale, 0.5 * min_width * kScale);
    double longest = 0.0;
    std::vector<AxisLine> lines = axis_lines(graph, set.min_feature * kScale, longest);
    axis_length = longest / kScale;
    const Eigen::Vector2d origin{double(min_x), double(min_y)};
    for (auto& line : lines) {
        for (auto& p : line.points) p = (p + origin) / kScale;
        line.length = polyline_length(line.points, line.closed);
        line.r_front /= kScale;
        line.r_back /= kScale;
        line.width /= kScale;
    }
    return lines;
}

double distance_to_loop(const Eigen::Vector2d& q, const std::vector<Eigen::Vector2d>& loop) {
    double best = std::numeric_limits<double>::infinity();
    for (std::size_t i = 0; i < loop.size(); ++i) {
        const Eigen::Vector2d a = loop[i], e = loop[(i + 1) % loop.size()] - a;
        const double len2 = e.squaredNorm();
        const double t = len2 > 0.0 ? std::clamp((q - a).dot(e) / len2, 0.0, 1.0) : 0.0;
        best = std::min(best, (a + t * e - q).norm());
    }
    return best;
}

// Trims an open centre line at each end that runs into a wall of its room (`walls`, mm): by
// w/2 - r, r the axis' distance to the boundary there, so that the bead's round end reaches the
// wall instead of running past it (at most a third of the line each). An end that runs into what
// the other beads already cover (a residue's cut) is left alone: its bead joins theirs.
void trim_ends(AxisLine& line, const std::vector<std::vector<Eigen::Vector2d>>& walls,
               const Settings& set) {
    if (line.closed || line.points.size() < 2) return;
    const double cap = line.length / 3.0;
    for (int end = 0; end < 2; ++end) {
        const double r = end == 0 ? line.r_front : line.r_back;
        const Eigen::Vector2d p = line.points[0];
        const Eigen::Vector2d dir = (p - line.points[1]).normalized();
        const Eigen::Vector2d ahead = p + r * dir;  // where the axis meets the boundary
        double wall = std::numeric_limits<double>::infinity();
        for (const auto& loop : walls) wall = std::min(wall, distance_to_loop(ahead, loop));
        if (dir.allFinite() && wall <= 0.5 * r + set.tol)
            trim_front(line.points, std::clamp(0.5 * set.w - r, 0.0, cap));
        std::reverse(line.points.begin(), line.points.end());
    }
    line.length = polyline_length(line.points, false);
}

// Beads: every path thickened by `half` with round joins and ends, as one union.
Paths thicken(const std::vector<Path2>& paths, double half, double arc_units) {
    ClipperLib::ClipperOffset off(kMiterLimit, arc_units);
    for (const auto& p : paths) {
        Path path;
        for (const auto& q : p.points) path.push_back(to_int(q));
        off.AddPath(path, ClipperLib::jtRound,
                    p.closed ? ClipperLib::etClosedLine : ClipperLib::etOpenRound);
    }
    Paths beads;
    off.Execute(beads, half * kScale);
    return beads;
}

// ---- one region, level by level -----------------------------------------------------------------

// A path with its level and, for a loop or a centre line, the loop one level further out that it
// runs inside (index in the same group): it is deposited only after that one.
struct Item {
    Path2 path;
    int level = 0;
    int parent = -1;
};

struct RegionPlan {
    int region = -1;
    int contour_count = 0;
    std::vector<Item> contours;  // contour levels (with their centre lines), deposited first
    std::vector<Item> infill;    // infill levels
    bool centre_line = false;

    void add(int level, Path2 path) {
        (level < contour_count ? contours : infill).push_back({std::move(path), level, -1});
    }
};

// Centre lines for a narrow piece of a room whose boundary is `walls`, or an unfilled entry
// (described by `report`) when it has none and the area of `report` is at least
// `report_min_area`. Lines narrower on average than `min_mean_width` (twice their mean distance
// to the boundary) are left out.
void narrow_piece(const Piece& piece, const Paths& report, const Paths& walls,
                  double report_min_area, double min_mean_width, int level, const Settings& set,
                  RegionPlan& plan, std::vector<UnfilledFeature>& unfilled) {
    double axis = 0.0;
    std::vector<AxisLine> lines = centre_lines(piece, set, min_mean_width, axis);
    lines.erase(std::remove_if(lines.begin(), lines.end(),
                               [&](const AxisLine& l) { return l.width < min_mean_width; }),
                lines.end());
    if (!lines.empty()) {
        std::vector<std::vector<Eigen::Vector2d>> wall_mm;
        for (const auto& l : walls) wall_mm.push_back(clipper_convert::from_path(l).points);
        for (auto& line : lines) trim_ends(line, wall_mm, set);
    }
    if (lines.empty()) {
        UnfilledFeature f = feature(plan.region, report);
        if (f.area_mm2 >= report_min_area) unfilled.push_back(f);
        return;
    }
    for (auto& line : lines) {
        Path2 p;
        p.kind = Path2::Kind::CentreLine;
        p.region = plan.region;
        p.closed = line.closed;
        p.points = std::move(line.points);
        if (p.closed) place_seam(p.points, set.seam);
        plan.add(level, std::move(p));
    }
    plan.centre_line = true;
}

// Where the raster lines of a piece go, across them (t = p . n, mm). Every edge parallel to the
// lines (within 0.06 degrees), and every other local extreme of a loop in t (a hole's top and
// bottom, a notch), gets a line, so that no band is left beside such an edge; between these the
// lines spread evenly, at most s apart. With contours, the outermost lines lie overlap w / 2 inside
// the piece's extent (so that they cross even a rounded piece in a proper chord while their beads
// still reach the innermost contour's); without, on its edges. Extremes closer than s / 2 to the
// previous one are merged into it.
std::vector<double> raster_positions(const Piece& piece, const Eigen::Vector2d& n, double t0,
                                     double t1, const Settings& set) {
    const double margin =
        set.contour_count > 0 ? std::min(0.5 * set.overlap * set.w, 0.5 * (t1 - t0)) : 0.0;
    const double lo = t0 + margin, hi = t1 - margin;
    if (hi - lo <= 1e-9) return {0.5 * (t0 + t1)};
    if ((hi - lo) / set.s > double(kMaxRasterLines))
        invalid("the bead spacing " + format_number(set.s) + " mm (bead_width_mm " +
                format_number(set.w) + " x (1 - overlap " + format_number(set.overlap) +
                ")) is too small for a region " + format_number(hi - lo) + " mm across: over " +
                std::to_string(kMaxRasterLines) + " raster lines");
    std::vector<double> extremes{lo, hi};
    for (const auto& loop : piece.loops) {
        const std::size_t m = loop.size();
        for (std::size_t i = 0; i < m; ++i) {
            const double tp = to_mm(loop[(i + m - 1) % m]).dot(n), ti = to_mm(loop[i]).dot(n),
                         tn = to_mm(loop[(i + 1) % m]).dot(n);
            const double edge = (to_mm(loop[(i + 1) % m]) - to_mm(loop[i])).norm();
            if ((ti >= tp && ti >= tn) || (ti <= tp && ti <= tn) ||
                std::abs(tn - ti) <= 1e-3 * edge)  // a local extreme, or an edge along the lines
                extremes.push_back(std::clamp(ti, lo, hi));
        }
    }
    std::sort(extremes.begin(), extremes.end());
    std::vector<double> kept{lo};
    for (const double e : extremes) {
        if (e >= hi) break;
        if (e - kept.back() >= 0.5 * set.s) kept.push_back(e);
    }
    if (kept.size() > 1 && hi - kept.back() < 0.5 * set.s) kept.pop_back();
    kept.push_back(hi);
    std::vector<double> out;
    for (std::size_t i = 0; i + 1 < kept.size(); ++i) {
        const double len = kept[i + 1] - kept[i];
        const int steps = std::max(1, int(std::ceil(len / set.s - 1e-9)));
        for (int k = 0; k < steps; ++k) out.push_back(kept[i] + len * double(k) / double(steps));
    }
    out.push_back(hi);
    return out;
}

// Raster lines over the infill pieces (their bead-centre area), one path per clipped piece.
std::vector<Path2> raster(const Pieces& infill, const Settings& set, int region) {
    std::vector<Path2> out;
    const Eigen::Vector2d d(std::cos(set.raster_angle), std::sin(set.raster_angle));
    const Eigen::Vector2d n(-d.y(), d.x());
    for (const Piece& piece : infill) {
        double t0 = std::numeric_limits<double>::infinity(), t1 = -t0, u0 = t0, u1 = -t0;
        for (const auto& q : piece.loops.front()) {
            const Eigen::Vector2d p = to_mm(q);
            t0 = std::min(t0, p.dot(n));
            t1 = std::max(t1, p.dot(n));
            u0 = std::min(u0, p.dot(d));
            u1 = std::max(u1, p.dot(d));
        }
        const std::vector<double> ts = raster_positions(piece, n, t0, t1, set);
        // The clip area is grown by a hair so that a line lying on an edge of it (an exact fit)
        // is kept whole. With contours around it, by a quarter bead more: a raster bead's round
        // end then runs into the innermost contour's bead, so that the scallops between
        // neighbouring line ends are filled (slicers' infill/perimeter overlap).
        const double reach = set.edge_eps + (set.contour_count > 0 ? 0.25 * set.w : 0.0);
        ClipperLib::Clipper clipper;
        clipper.AddPaths(loops_of(offset_pieces(piece.loops, reach, set.arc_units)),
                         ClipperLib::ptClip, true);
        for (const double t : ts) {
            const Eigen::Vector2d a = t * n + (u0 - set.w) * d, b = t * n + (u1 + set.w) * d;
            clipper.AddPath(Path{to_int(a), to_int(b)}, ClipperLib::ptSubject, false);
        }
        ClipperLib::PolyTree tree;
        if (!clipper.Execute(ClipperLib::ctIntersection, tree, ClipperLib::pftNonZero,
                             ClipperLib::pftNonZero))
            throw Error(ErrorCode::GeometryFailure, "clipping raster lines failed");
        Paths open;
        ClipperLib::OpenPathsFromPolyTree(tree, open);
        // Pieces shorter than the arc tolerance are a line grazing a corner of the area; they are
        // dropped unless the piece would get nothing else. (What a piece's lines leave is the
        // caller's gap fill.)
        std::vector<Path2> lines;
        Path2 longest;
        double longest_length = 0.0;
        for (const auto& o : open) {
            Path2 p;
            p.kind = Path2::Kind::Infill;
            p.region = region;
            p.closed = false;
            for (const auto& q : o) p.points.push_back(to_mm(q));
            const double len = polyline_length(p.points, false);
            if (len >= set.tol)
                lines.push_back(std::move(p));
            else if (len > longest_length) {
                longest_length = len;
                longest = std::move(p);
            }
        }
        if (lines.empty() && longest_length > 0.0) lines.push_back(std::move(longest));
        for (auto& l : lines) out.push_back(std::move(l));
    }
    return out;
}

RegionPlan plan_region(const Region2& region, int index, const Settings& set,
                       std::vector<UnfilledFeature>& unfilled, const Progress& progress) {
    RegionPlan plan;
    plan.region = index;
    plan.contour_count = set.contour_count;
    Paths input;
    clipper_convert::append_paths(region, input);
    struct Work {
        Piece piece;
        int level;
    };
    std::deque<Work> queue;
    for (auto& p : boolean(ClipperLib::ctUnion, input, {})) queue.push_back({std::move(p), 0});
    // Levels go on until the region is used up (contour-parallel infill) or to contour_count:
    // refuse up front what would take more than kMaxLevels offsets.
    const Eigen::AlignedBox2d box = bounds(region);
    if (!box.isEmpty()) {
        const double across = box.sizes().minCoeff() / (2.0 * set.s) + 2.0;
        const double levels = set.infill == InfillPattern::Contour
                                  ? across
                                  : std::min(across, double(set.contour_count) + 1.0);
        if (levels > double(kMaxLevels))
            invalid("the bead spacing " + format_number(set.s) + " mm (bead_width_mm " +
                    format_number(set.w) + " x (1 - overlap " + format_number(set.overlap) +
                    ")) is too small for a region " + format_number(box.sizes().minCoeff()) +
                    " mm across: over " + std::to_string(kMaxLevels) + " offset levels");
    }
    while (!queue.empty()) {
        progress.check();
        Work work = std::move(queue.front());
        queue.pop_front();
        const int level = work.level;
        const bool infill_level = level >= set.contour_count;
        if (infill_level && set.infill == InfillPattern::None) continue;
        const Pieces centres = offset_pieces(work.piece.loops, -0.5 * set.w, set.arc_units);
        const Paths uncovered =
            level == 0 || set.overlap == 0.0
                ? work.piece.loops
                : loops_of(offset_pieces(work.piece.loops, -set.overlap * set.w, set.arc_units));
        if (centres.empty()) {  // narrower than one bead
            if (!uncovered.empty())
                narrow_piece(work.piece, uncovered, work.piece.loops, 0.0, 0.0, level, set, plan,
                             unfilled);
            continue;
        }
        if (infill_level && set.infill == InfillPattern::Raster) {
            // What the raster's beads leave of the room (thin bands beside edges parallel to
            // the lines, the gaps between line ends along a slanted edge) gets centre lines
            // where it is long enough and on average at least w/4 wide (a bead there fills more
            // than it doubles); the rest is the raster's scallops, reported only from w^2 / 4
            // up (the coverage measure counts them all).
            std::vector<Path2> lines = raster(centres, set, index);
            progress.check();
            if (!uncovered.empty()) {
                const Paths beads = thicken(lines, 0.5 * set.w, set.arc_units);
                progress.check();
                for (const Piece& r : boolean(ClipperLib::ctDifference, uncovered, beads))
                    if (area_mm2(r.loops) >= set.residue_min_area)
                        narrow_piece(r, r.loops, uncovered, 0.25 * set.w * set.w, 0.25 * set.w,
                                     level, set, plan, unfilled);
            }
            for (auto& l : lines) plan.add(level, std::move(l));
            continue;
        }
        if (!uncovered.empty()) {  // thin parts the beads of this level do not reach
            const Pieces reach =
                offset_pieces(loops_of(centres), 0.5 * set.w + set.tol, set.arc_units);
            for (const Piece& r : boolean(ClipperLib::ctDifference, uncovered, loops_of(reach)))
                if (area_mm2(r.loops) >= set.residue_min_area)
                    narrow_piece(r, r.loops, uncovered, set.residue_min_area, 0.0, level, set, plan,
                                 unfilled);
        }
        const Path2::Kind kind = infill_level ? Path2::Kind::Infill : Path2::Kind::Contour;
        for (const Piece& c : centres)
            for (std::size_t i = 0; i < c.loops.size(); ++i)
                plan.add(level, make_loop(c.loops[i], i > 0, kind, index, set.seam));
        for (auto& next : offset_pieces(work.piece.loops, -set.s, set.arc_units))
            queue.push_back({std::move(next), level + 1});
    }
    return plan;
}

// ---- order --------------------------------------------------------------------------------------

// Distance from `pos` to where the path would start; `reverse` when an open path is better run
// from its end.
double entry(const Path2& p, const Eigen::Vector2d& pos, bool& reverse) {
    const double to_front = (p.points.front() - pos).norm();
    reverse = false;
    if (p.closed) return to_front;
    const double to_back = (p.points.back() - pos).norm();
    reverse = to_back < to_front;
    return std::min(to_front, to_back);
}

// Links every loop and centre line of level k > 0 to the nearest loop of level k - 1 (of the same
// sense, outer or hole, for a loop): the loop around it, to be deposited before it.
void link_parents(std::vector<Item>& items) {
    std::vector<int> sense(items.size(), 0);  // +1 outer loop, -1 hole loop, 0 not a loop
    int max_level = 0;
    for (std::size_t i = 0; i < items.size(); ++i) {
        const Path2& p = items[i].path;
        if (p.closed && p.kind != Path2::Kind::CentreLine)
            sense[i] = signed_area(Polygon2{p.points}) > 0.0 ? 1 : -1;
        max_level = std::max(max_level, items[i].level);
    }
    std::vector<std::vector<int>> loops_at(std::size_t(max_level) + 1);
    for (std::size_t i = 0; i < items.size(); ++i)
        if (sense[i] != 0) loops_at[std::size_t(items[i].level)].push_back(int(i));
    for (std::size_t i = 0; i < items.size(); ++i) {
        Item& it = items[i];
        const bool centre_line = it.path.kind == Path2::Kind::CentreLine;
        if (it.level == 0 || (sense[i] == 0 && !centre_line)) continue;  // raster lines: none
        double best = std::numeric_limits<double>::infinity();
        for (int j : loops_at[std::size_t(it.level - 1)]) {
            if (!centre_line && sense[std::size_t(j)] != sense[i]) continue;
            const double d =
                distance_to_loop(it.path.points.front(), items[std::size_t(j)].path.points);
            if (d < best) {
                best = d;
                it.parent = j;
            }
        }
    }
}

// Nearest entry among the items that may go next (their parent loop done).
double nearest_entry(const std::vector<Item>& items, const std::vector<char>& done,
                     const Eigen::Vector2d& pos, std::size_t& best, bool& best_reverse) {
    double best_d = std::numeric_limits<double>::infinity();
    for (std::size_t i = 0; i < items.size(); ++i) {
        if (done[i] || (items[i].parent >= 0 && !done[std::size_t(items[i].parent)])) continue;
        bool reverse = false;
        const double d = entry(items[i].path, pos, reverse);
        if (d < best_d) {
            best_d = d;
            best = i;
            best_reverse = reverse;
        }
    }
    return best_d;
}

// Greedy nearest-next over one group, every loop after its parent; appends to `out` and moves
// `pos` to the last path's end.
void order_group(std::vector<Item> items, Eigen::Vector2d& pos, std::vector<Path2>& out,
                 const Progress& progress) {
    std::vector<char> done(items.size(), 0);
    for (std::size_t k = 0; k < items.size(); ++k) {
        if (k % 64 == 0) progress.check();  // each pick scans every item left
        std::size_t best = 0;
        bool reverse = false;
        nearest_entry(items, done, pos, best, reverse);
        done[best] = 1;
        Path2& p = items[best].path;
        if (reverse) std::reverse(p.points.begin(), p.points.end());
        pos = p.closed ? p.points.front() : p.points.back();
        out.push_back(std::move(p));
    }
}

}  // namespace

// ---- public -------------------------------------------------------------------------------------

const char* to_string(InfillPattern pattern) {
    switch (pattern) {
        case InfillPattern::Raster:
            return "raster";
        case InfillPattern::Contour:
            return "contour";
        case InfillPattern::None:
            return "none";
    }
    return "unknown";
}

InfillPattern infill_pattern_from_string(const char* name) {
    const std::string s = name ? name : "";
    if (s == "raster") return InfillPattern::Raster;
    if (s == "contour") return InfillPattern::Contour;
    if (s == "none") return InfillPattern::None;
    invalid("unknown infill pattern '" + s + "' (expected raster, contour or none)");
}

const char* to_string(Path2::Kind kind) {
    switch (kind) {
        case Path2::Kind::Contour:
            return "contour";
        case Path2::Kind::Infill:
            return "infill";
        case Path2::Kind::CentreLine:
            return "centre_line";
    }
    return "unknown";
}

void validate(const PathParams& p) {
    if (!(p.bead_width_mm > 0.0) || !std::isfinite(p.bead_width_mm))
        invalid("bead_width_mm must be positive and finite, got " + format_number(p.bead_width_mm));
    // Beads are offsets on the Booleans' integer grid (a micron): a metre is far past any torch.
    if (p.bead_width_mm > kMaxBeadWidthMm)
        invalid("bead_width_mm must be at most " + format_number(kMaxBeadWidthMm) + " mm, got " +
                format_number(p.bead_width_mm));
    if (!(p.overlap >= 0.0 && p.overlap < 1.0))
        invalid("overlap must be in [0, 1), got " + format_number(p.overlap));
    if (p.contour_count < 0)
        invalid("contour_count must be >= 0, got " + std::to_string(p.contour_count));
    if (p.infill != InfillPattern::Raster && p.infill != InfillPattern::Contour &&
        p.infill != InfillPattern::None)
        invalid("infill must be raster, contour or none, got " + std::to_string(int(p.infill)));
    if (!std::isfinite(p.raster_angle_deg))
        invalid("raster_angle_deg must be finite, got " + format_number(p.raster_angle_deg));
    if (!std::isfinite(p.raster_angle_step_deg))
        invalid("raster_angle_step_deg must be finite, got " +
                format_number(p.raster_angle_step_deg));
    if (!(p.min_feature_mm >= 0.0) || !std::isfinite(p.min_feature_mm))
        invalid("min_feature_mm must be >= 0 and finite, got " + format_number(p.min_feature_mm));
    if (!(p.arc_tolerance_mm > 0.0) || !std::isfinite(p.arc_tolerance_mm))
        invalid("arc_tolerance_mm must be positive and finite, got " +
                format_number(p.arc_tolerance_mm));
}

double seam_angle(int layer_index) {
    const double golden = kPi * (3.0 - std::sqrt(5.0));  // 137.5077... degrees
    double a = std::fmod(double(layer_index) * golden, 2.0 * kPi);
    if (a < 0.0) a += 2.0 * kPi;
    return a;
}

LayerPaths2 plan_layer_paths(const Regions2& regions, const PathParams& params, int layer_index,
                             const Eigen::Vector2d& start, const Progress& progress) {
    validate(params);
    if (!start.allFinite())
        throw Error(ErrorCode::NonFiniteCoordinate, "start point has NaN or infinite coordinates");
    Settings set;
    set.w = params.bead_width_mm;
    set.overlap = params.overlap;
    set.s = set.w * (1.0 - params.overlap);
    set.tol = params.arc_tolerance_mm;
    set.arc_units = set.tol * kScale;
    set.min_feature = params.min_feature_mm > 0.0 ? params.min_feature_mm : 0.5 * set.w;
    set.residue_min_area = set.tol * set.w;
    set.edge_eps = std::max(0.1 * set.tol, 10.0 / kScale);
    set.contour_count = params.contour_count;
    set.infill = params.infill;
    set.raster_angle =
        (params.raster_angle_deg + double(layer_index) * params.raster_angle_step_deg) * kPi /
        180.0;
    set.seam = seam_angle(layer_index);

    LayerPaths2 out;
    std::vector<RegionPlan> plans;
    for (std::size_t i = 0; i < regions.size(); ++i) {
        RegionPlan plan = plan_region(regions[i], int(i), set, out.unfilled, progress);
        if (plan.centre_line) out.centre_line_regions.push_back(int(i));
        link_parents(plan.contours);
        link_parents(plan.infill);
        if (!plan.contours.empty() || !plan.infill.empty()) plans.push_back(std::move(plan));
    }

    // Regions nearest-next (by the nearest entry of their first group), then their contours and
    // their infill, each nearest-next with every loop after the one around it.
    Eigen::Vector2d pos = start;
    std::vector<char> done(plans.size(), 0);
    for (std::size_t k = 0; k < plans.size(); ++k) {
        std::size_t best = 0;
        double best_d = std::numeric_limits<double>::infinity();
        for (std::size_t i = 0; i < plans.size(); ++i) {
            if (done[i]) continue;
            const auto& first = plans[i].contours.empty() ? plans[i].infill : plans[i].contours;
            std::size_t item = 0;
            bool reverse = false;
            const double d =
                nearest_entry(first, std::vector<char>(first.size(), 0), pos, item, reverse);
            if (d < best_d) {
                best_d = d;
                best = i;
            }
        }
        done[best] = 1;
        order_group(std::move(plans[best].contours), pos, out.paths, progress);
        order_group(std::move(plans[best].infill), pos, out.paths, progress);
    }

    pos = start;
    for (const auto& p : out.paths) {
        out.travel_length_mm += (p.points.front() - pos).norm();
        out.deposit_length_mm += polyline_length(p.points, p.closed);
        pos = p.closed ? p.points.front() : p.points.back();
    }

    if (params.measure_coverage) {
        // Every bead as its path thickened by w/2 with round ends, subtracted from the regions.
        const Paths beads = thicken(out.paths, 0.5 * set.w, set.arc_units);
        const Paths area = clipper_convert::to_paths(regions);
        out.uncovered_area_mm2 = 0.0;
        if (any_loop(area)) {
            ClipperLib::Clipper clipper;
            clipper.AddPaths(area, ClipperLib::ptSubject, true);
            clipper.AddPaths(beads, ClipperLib::ptClip, true);
            Paths left;
            if (!clipper.Execute(ClipperLib::ctDifference, left, ClipperLib::pftNonZero,
                                 ClipperLib::pftNonZero))
                throw Error(ErrorCode::GeometryFailure, "measuring the uncovered area failed");
            out.uncovered_area_mm2 = area_mm2(left);
        }
    }
    return out;
}

}  // namespace mas
