// Ear clipping of regions with holes, and the prisms drawn from them. See Triangulate.hpp.
#include "mas/Triangulate.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <utility>

namespace mas {

namespace {

using Eigen::Vector2d;

// Twice the signed area of the triangle (a, b, c): > 0 when counter-clockwise.
double cross(const Vector2d& a, const Vector2d& b, const Vector2d& c) {
    return (b.x() - a.x()) * (c.y() - a.y()) - (b.y() - a.y()) * (c.x() - a.x());
}

// The indices (into the loop) of a loop's distinct points: a point repeating the one before it,
// or a last point repeating the first, is left out.
std::vector<int> distinct_points(const Polygon2& loop) {
    std::vector<int> kept;
    const auto& p = loop.points;
    for (int i = 0; i < int(p.size()); ++i)
        if (kept.empty() || p[std::size_t(i)] != p[std::size_t(kept.back())]) kept.push_back(i);
    while (kept.size() > 1 && p[std::size_t(kept.back())] == p[std::size_t(kept.front())])
        kept.pop_back();
    return kept;
}

// The loop's distinct points (their indices into it) turned counter-clockwise when `ccw`, else
// clockwise (repeated points add no area: signed_area() of the whole loop says which way it
// turns); none when there are under three or they enclose no area.
std::vector<int> turned_points(const Polygon2& loop, bool ccw) {
    std::vector<int> order = distinct_points(loop);
    const double area = order.size() < 3 ? 0.0 : signed_area(loop);
    if (area == 0.0) return {};
    if ((area > 0.0) != ccw) std::reverse(order.begin(), order.end());
    return order;
}

// The region's loops as rings of points in a linked list: the outer one counter-clockwise, the
// holes clockwise (material on the left of every edge), each point knowing its index in the
// region's numbering.
class Rings {
public:
    struct Node {
        Vector2d p;
        int index;  // in the region's numbering
        int prev, next;
        bool cut = false;  // clipped off the ring
    };

    std::vector<Node> nodes;

    // Adds the loop whose first point is numbered `base`, turned to `ccw`; the ring's first node,
    // or -1 when the loop has under three distinct points or no area.
    int add(const Polygon2& loop, int base, bool ccw) {
        const std::vector<int> order = turned_points(loop, ccw);
        if (order.empty()) return -1;
        const int first = int(nodes.size());
        const int n = int(order.size());
        for (int k = 0; k < n; ++k)
            nodes.push_back({loop.points[std::size_t(order[std::size_t(k)])],
                             base + order[std::size_t(k)], first + (k + n - 1) % n,
                             first + (k + 1) % n, false});
        return first;
    }

    // A copy of node `i`, linked to nothing yet.
    int clone(int i) {
        nodes.push_back(nodes[std::size_t(i)]);
        return int(nodes.size()) - 1;
    }

    void link(int a, int b) {
        nodes[std::size_t(a)].next = b;
        nodes[std::size_t(b)].prev = a;
    }

    const Vector2d& p(int i) const { return nodes[std::size_t(i)].p; }
    int next(int i) const { return nodes[std::size_t(i)].next; }
    int prev(int i) const { return nodes[std::size_t(i)].prev; }
};

// Whether q lies in the counter-clockwise triangle (a, b, c) or on its sides.
bool in_triangle(const Vector2d& a, const Vector2d& b, const Vector2d& c, const Vector2d& q) {
    return cross(a, b, q) >= 0.0 && cross(b, c, q) >= 0.0 && cross(c, a, q) >= 0.0;
}

// Whether the direction from node `a` to q lies in the material's corner at a (between its
// edges, on their left; on one of them counts).
bool faces(const Rings& r, int a, const Vector2d& q) {
    const Vector2d &p = r.p(r.prev(a)), &pa = r.p(a), &n = r.p(r.next(a));
    const bool left_of_in = cross(p, pa, q) >= 0.0, left_of_out = cross(pa, n, q) >= 0.0;
    return cross(p, pa, n) > 0.0 ? left_of_in && left_of_out : left_of_in || left_of_out;
}

// The point M sees of the ring through `outer` past the edge its ray to the right meets at x =
// `cross_x`, whose end furthest right is `candidate`: the candidate, unless reflex points lie in
// the triangle (M, crossing, candidate), and then the one of those nearest the ray's direction
// (then the nearest to M).
int nearest_hiding(const Rings& r, int outer, const Vector2d& mp, double cross_x, int candidate) {
    const Vector2d crossing(cross_x, mp.y()), cp = r.p(candidate);
    int seen = candidate;
    double best_tan = std::numeric_limits<double>::infinity(), best_d = best_tan;
    int i = outer;
    do {
        const Vector2d& q = r.p(i);
        if (i != candidate && q.x() >= mp.x() && q != mp &&
            cross(r.p(r.prev(i)), q, r.p(r.next(i))) < 0.0 &&
            (cp.y() < mp.y() ? in_triangle(mp, cp, crossing, q)
                             : in_triangle(mp, crossing, cp, q))) {
            const double dx = q.x() - mp.x();
            const double t =
                dx > 0.0 ? std::abs(q.y() - mp.y()) / dx : std::numeric_limits<double>::infinity();
            const double d = (q - mp).squaredNorm();
            if (t < best_tan || (t == best_tan && d < best_d)) {
                best_tan = t;
                best_d = d;
                seen = i;
            }
        }
        i = r.next(i);
    } while (i != outer);
    return seen;
}

// Joins the hole ring starting at `hole` to the ring through `outer` by a bridge from the hole's
// rightmost point to an outer point it sees (see the header); false when no edge of the outer
// ring crosses the ray to its right (a hole outside the outer loop: left out).
bool bridge(Rings& r, int outer, int hole) {
    int m = hole;
    for (int i = r.next(hole); i != hole; i = r.next(i))
        if (r.p(i).x() > r.p(m).x() || (r.p(i).x() == r.p(m).x() && r.p(i).y() < r.p(m).y())) m = i;
    const Vector2d mp = r.p(m);
    // The nearest crossing of the ray mp + t (1, 0), t >= 0, with an edge going up (material on
    // its left, so the ray meets it from inside), and that edge's endpoint furthest right.
    double best_x = std::numeric_limits<double>::infinity();
    int candidate = -1;
    int i = outer;
    do {
        const int j = r.next(i);
        const Vector2d &a = r.p(i), &b = r.p(j);
        if (a.y() <= mp.y() && b.y() >= mp.y() && a.y() != b.y()) {
            const double x = a.x() + (mp.y() - a.y()) * (b.x() - a.x()) / (b.y() - a.y());
            if (x >= mp.x() && x < best_x) {
                best_x = x;
                // Through a point: that point; else the edge's end furthest right.
                candidate = a.y() == mp.y() ? i : b.y() == mp.y() ? j : a.x() > b.x() ? i : j;
                if (x == mp.x()) break;  // on the edge: it sees its endpoint along it
            }
        }
        i = j;
    } while (i != outer);
    if (candidate < 0) return false;
    // Through a point, the ray sees it; else a reflex point inside the triangle (mp, crossing,
    // candidate) hides the candidate.
    int seen =
        r.p(candidate).y() == mp.y() ? candidate : nearest_hiding(r, outer, mp, best_x, candidate);
    // A point the ring passes more than once (an earlier bridge's end) is joined where the
    // material it lies in faces M.
    if (!faces(r, seen, mp)) {
        i = outer;
        do {
            if (r.p(i) == r.p(seen) && faces(r, i, mp)) {
                seen = i;
                break;
            }
            i = r.next(i);
        } while (i != outer);
    }
    // ... seen -> m -> (the hole round to m) -> m' -> seen' -> (what followed seen) ...
    const int m2 = r.clone(m), s2 = r.clone(seen);
    const int m_prev = r.prev(m), s_next = r.next(seen);
    r.link(seen, m);
    r.link(m_prev, m2);
    r.link(m2, s2);
    r.link(s2, s_next);
    return true;
}

// Twice the signed area of the corner at node i (> 0: convex).
double corner(const Rings& r, int i) { return cross(r.p(r.prev(i)), r.p(i), r.p(r.next(i))); }

// The ring's corners that are not convex (reflex or straight) in a uniform grid over their box,
// for the ear test: a point of the ring inside an ear's triangle means one of these inside it,
// and clipping an ear never turns a convex corner reflex (its angles only shrink). A test then
// looks at the few points in the cells the triangle's box covers, where looking at every point
// of the ring made ear clipping quadratic (12 ms for 3000 points, 0.4 s for a ring of 15000).
class Reflex {
public:
    Reflex(const Rings& r, int start) {
        int i = start;
        do {
            if (corner(r, i) <= 0.0) {
                points_.push_back(i);
                box_.extend(r.p(i));
            }
            i = r.next(i);
        } while (i != start);
        if (points_.empty()) return;
        side_ = std::max(1, int(std::ceil(std::sqrt(double(points_.size())))));
        const Vector2d size = box_.sizes();
        scale_ = {size.x() > 0.0 ? side_ / size.x() : 0.0, size.y() > 0.0 ? side_ / size.y() : 0.0};
        // Buckets as one array: first_[c] .. first_[c + 1] in cells_ hold cell c's nodes.
        first_.assign(std::size_t(side_ * side_ + 1), 0);
        for (const int k : points_) ++first_[std::size_t(cell(r.p(k)) + 1)];
        for (std::size_t c = 1; c < first_.size(); ++c) first_[c] += first_[c - 1];
        cells_.resize(points_.size());
        std::vector<int> fill(first_.begin(), first_.end() - 1);
        for (const int k : points_) cells_[std::size_t(fill[std::size_t(cell(r.p(k)))]++)] = k;
    }

    // Whether a corner of the ring that is not convex (nor clipped), other than copies of the
    // triangle's corners, lies in the counter-clockwise triangle (a, b, c) or on its sides.
    bool any_in(const Rings& r, const Vector2d& a, const Vector2d& b, const Vector2d& c) const {
        if (points_.empty()) return false;
        const Eigen::AlignedBox2d t(a.cwiseMin(b).cwiseMin(c), a.cwiseMax(b).cwiseMax(c));
        if (!t.intersects(box_)) return false;
        const auto [x0, y0] = index(t.min());
        const auto [x1, y1] = index(t.max());
        for (int y = y0; y <= y1; ++y)
            for (int x = x0; x <= x1; ++x) {
                const int c0 = first_[std::size_t(y * side_ + x)];
                const int c1 = first_[std::size_t(y * side_ + x + 1)];
                for (int k = c0; k < c1; ++k) {
                    const int i = cells_[std::size_t(k)];
                    const Vector2d& q = r.p(i);
                    if (r.nodes[std::size_t(i)].cut || !t.contains(q) || q == a || q == b ||
                        q == c || corner(r, i) > 0.0)
                        continue;
                    if (in_triangle(a, b, c, q)) return true;
                }
            }
        return false;
    }

private:
    std::pair<int, int> index(const Vector2d& q) const {
        // (Clamped before it is made an int: a point off the box, or not finite, is at its edge.)
        const auto clamp = [&](double v) { return v >= 1.0 ? int(std::min(v, side_ - 1.0)) : 0; };
        return {clamp((q.x() - box_.min().x()) * scale_.x()),
                clamp((q.y() - box_.min().y()) * scale_.y())};
    }
    int cell(const Vector2d& q) const {
        const auto [x, y] = index(q);
        return y * side_ + x;
    }

    std::vector<int> points_;
    Eigen::AlignedBox2d box_;
    int side_ = 0;
    Vector2d scale_ = Vector2d::Zero();
    std::vector<int> first_, cells_;
};

// Whether the corner at `b` is an ear of the ring: convex, and no other point of the ring (but
// copies of its corners, which bridges make) in its triangle.
bool is_ear(const Rings& r, const Reflex& reflex, int b) {
    const int a = r.prev(b), c = r.next(b);
    return corner(r, b) > 0.0 && !reflex.any_in(r, r.p(a), r.p(b), r.p(c));
}

}  // namespace

std::vector<std::array<int, 3>> triangulate(const Region2& region) {
    Rings r;
    const int outer = r.add(region.outer, 0, true);
    std::vector<std::array<int, 3>> out;
    if (outer < 0) return out;
    int count = int(r.nodes.size());
    // Holes, rightmost first.
    std::vector<std::pair<double, int>> holes;
    int base = int(region.outer.points.size());
    for (const Polygon2& h : region.holes) {
        const int before = int(r.nodes.size());
        const int first = r.add(h, base, false);
        base += int(h.points.size());
        if (first < 0) continue;
        double right = -std::numeric_limits<double>::infinity();
        for (int i = before; i < int(r.nodes.size()); ++i) right = std::max(right, r.p(i).x());
        holes.push_back({right, first});
    }
    std::sort(holes.begin(), holes.end(),
              [](const auto& a, const auto& b) { return a.first > b.first; });
    for (const auto& [right, first] : holes) {
        const int before = int(r.nodes.size());
        int n = 1;
        for (int i = r.next(first); i != first; i = r.next(i)) ++n;
        if (bridge(r, outer, first)) count += n + int(r.nodes.size()) - before;
    }

    out.reserve(std::size_t(std::max(count - 2, 0)));
    // Clipping: each ear cut off, then its neighbours tried first. `stop` is where a whole turn
    // round the ring without an ear ends; `stage` what is done then (see the header).
    int at = outer, stop = outer, stage = 0;
    std::optional<Reflex> reflex;
    while (count > 2) {
        // (Made again after a remedy, which may turn a corner any way.)
        if (!reflex) reflex.emplace(r, at);
        const int a = r.prev(at), c = r.next(at);
        const Vector2d &pa = r.p(a), &pb = r.p(at), &pc = r.p(c);
        bool cut = false, drop = false;
        if (stage == 0) {
            cut = is_ear(r, *reflex, at);
        } else if (stage == 1) {
            drop = cross(pa, pb, pc) == 0.0;
        } else {
            cut = cross(pa, pb, pc) > 0.0 || stage == 3;
        }
        if (cut || drop) {
            if (cut)
                out.push_back({r.nodes[std::size_t(a)].index, r.nodes[std::size_t(at)].index,
                               r.nodes[std::size_t(c)].index});
            r.link(a, c);
            r.nodes[std::size_t(at)].cut = true;
            --count;
            at = stop = c;
            if (stage > 0) reflex.reset();
            stage = 0;
            continue;
        }
        at = c;
        if (at == stop) ++stage;  // a whole turn without an ear: on to the next remedy
        if (stage > 3) break;     // (cannot happen: stage 3 cuts whatever it meets)
    }
    return out;
}

TriangleMesh prism_mesh(const Regions2& regions, const Plane& plane, double depth_mm) {
    TriangleMesh mesh;
    const PlaneFrame frame(plane.normal);
    const Eigen::Vector3d back = -plane.normal * depth_mm;
    for (const Region2& region : regions) {
        const std::vector<std::array<int, 3>> faces = triangulate(region);
        if (faces.empty()) continue;
        std::vector<const Polygon2*> loops{&region.outer};
        for (const Polygon2& h : region.holes) loops.push_back(&h);
        const int top = int(mesh.vertices.size());
        int n = 0;
        for (const Polygon2* loop : loops)
            for (const Vector2d& q : loop->points) {
                mesh.vertices.push_back(frame.to_3d(q, plane));
                ++n;
            }
        const int bottom = top + n;
        for (int i = 0; i < n; ++i)
            mesh.vertices.push_back(mesh.vertices[std::size_t(top + i)] + back);
        for (const auto& t : faces) {
            mesh.triangles.emplace_back(top + t[0], top + t[1], top + t[2]);
            mesh.triangles.emplace_back(bottom + t[0], bottom + t[2], bottom + t[1]);
        }
        // The walls: along each edge with the material on its left (seen from above), the
        // triangles (top i, bottom i, bottom j) and (top i, bottom j, top j) face outwards.
        int base = 0;
        for (std::size_t k = 0; k < loops.size(); ++k) {
            const Polygon2& loop = *loops[k];
            const std::vector<int> order = turned_points(loop, k == 0);
            for (std::size_t e = 0; e < order.size(); ++e) {
                const int i = base + order[e], j = base + order[(e + 1) % order.size()];
                mesh.triangles.emplace_back(top + i, bottom + i, bottom + j);
                mesh.triangles.emplace_back(top + i, bottom + j, top + j);
            }
            base += int(loop.points.size());
        }
    }
    return mesh;
}

}  // namespace mas
