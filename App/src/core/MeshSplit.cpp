// Decomposing a closed mesh (SlicePart.hpp, decompose_mesh): each branch of the centroidal axis
// that turned or split cut off its father's mesh at the section plane, the cut closed with a cap on
// both sides.
#include <Eigen/Eigenvalues>
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <iomanip>
#include <limits>
#include <map>
#include <optional>
#include <set>
#include <sstream>
#include <string>
#include <unordered_map>
#include <vector>

#include "mas/Angles.hpp"
#include "mas/Decompose.hpp"
#include "mas/Error.hpp"
#include "mas/Section.hpp"
#include "mas/SlicePart.hpp"

namespace mas {

namespace {

using Vec2 = Eigen::Vector2d;
using Vec3 = Eigen::Vector3d;

double cross2(const Vec2& a, const Vec2& b, const Vec2& c) {
    return (b - a).x() * (c - a).y() - (b - a).y() * (c - a).x();
}

// ---- ear clipping of polygons with holes -------------------------------------------------------

// A loop of global vertex indices with their 2-D points.
struct Loop {
    std::vector<int> index;
    std::vector<Vec2> point;
};

double loop_area(const Loop& loop) {
    double a = 0.0;
    for (std::size_t i = 0, n = loop.point.size(); i < n; ++i)
        a += loop.point[i].x() * loop.point[(i + 1) % n].y() -
             loop.point[(i + 1) % n].x() * loop.point[i].y();
    return 0.5 * a;
}

bool point_in_loop(const Loop& loop, const Vec2& p) {
    bool in = false;
    for (std::size_t i = 0, n = loop.point.size(), j = n - 1; i < n; j = i++) {
        const Vec2& a = loop.point[i];
        const Vec2& b = loop.point[j];
        if ((a.y() > p.y()) != (b.y() > p.y()) &&
            p.x() < (b.x() - a.x()) * (p.y() - a.y()) / (b.y() - a.y()) + a.x())
            in = !in;
    }
    return in;
}

bool segments_cross(const Vec2& a, const Vec2& b, const Vec2& c, const Vec2& d) {
    const double d1 = cross2(c, d, a), d2 = cross2(c, d, b);
    const double d3 = cross2(a, b, c), d4 = cross2(a, b, d);
    return ((d1 > 0 && d2 < 0) || (d1 < 0 && d2 > 0)) && ((d3 > 0 && d4 < 0) || (d3 < 0 && d4 > 0));
}

// Joins each hole (clockwise) into the outer loop (counter-clockwise) by a bridge from the hole's
// rightmost point to an outer point it sees, holes taken rightmost first (Eberly's construction).
// Returns false when no bridge is found (a degenerate section).
bool bridge_holes(Loop& outer, std::vector<Loop> holes) {
    std::sort(holes.begin(), holes.end(), [](const Loop& a, const Loop& b) {
        const auto xa =
            std::max_element(a.point.begin(), a.point.end(),
                             [](const Vec2& p, const Vec2& q) { return p.x() < q.x(); });
        const auto xb =
            std::max_element(b.point.begin(), b.point.end(),
                             [](const Vec2& p, const Vec2& q) { return p.x() < q.x(); });
        return xa->x() > xb->x();
    });
    for (std::size_t joined_count = 0; joined_count < holes.size(); ++joined_count) {
        const Loop& hole = holes[joined_count];
        std::size_t h = 0;
        for (std::size_t i = 1; i < hole.point.size(); ++i)
            if (hole.point[i].x() > hole.point[h].x()) h = i;
        const Vec2 m = hole.point[h];
        // The outer points in order of distance from m, the first whose segment to m crosses no
        // edge of the outer loop nor of any hole still to join (this one included) is the bridge.
        std::vector<std::size_t> order(outer.point.size());
        for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
        std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
            return (outer.point[a] - m).squaredNorm() < (outer.point[b] - m).squaredNorm();
        });
        auto clear = [&](const Vec2& a, const Vec2& b, const Loop& loop) {
            for (std::size_t i = 0, n = loop.point.size(); i < n; ++i)
                if (segments_cross(a, b, loop.point[i], loop.point[(i + 1) % n])) return false;
            return true;
        };
        std::size_t found = outer.point.size();
        for (std::size_t k : order) {
            const Vec2 o = outer.point[k];
            if (!clear(m, o, outer)) continue;
            bool blocked = false;
            for (std::size_t other = joined_count; other < holes.size() && !blocked; ++other)
                blocked = !clear(m, o, holes[other]);
            if (blocked) continue;
            // Leaving o into the polygon's inside: m within the angle of o's two edges.
            const std::size_t n = outer.point.size();
            const Vec2& prev = outer.point[(k + n - 1) % n];
            const Vec2& next = outer.point[(k + 1) % n];
            const bool convex = cross2(prev, o, next) > 0.0;
            const bool inside = convex ? cross2(prev, o, m) > 0.0 && cross2(o, next, m) > 0.0
                                       : !(cross2(prev, o, m) <= 0.0 && cross2(o, next, m) <= 0.0);
            if (!inside) continue;
            found = k;
            break;
        }
        if (found == outer.point.size()) return false;
        Loop joined;
        for (std::size_t i = 0; i <= found; ++i) {
            joined.index.push_back(outer.index[i]);
            joined.point.push_back(outer.point[i]);
        }
        for (std::size_t i = 0; i <= hole.point.size(); ++i) {
            const std::size_t j = (h + i) % hole.point.size();
            joined.index.push_back(hole.index[j]);
            joined.point.push_back(hole.point[j]);
        }
        for (std::size_t i = found; i < outer.point.size(); ++i) {
            joined.index.push_back(outer.index[i]);
            joined.point.push_back(outer.point[i]);
        }
        outer = std::move(joined);
    }
    return true;
}

// Triangles (counter-clockwise) covering a counter-clockwise simple polygon (bridged holes allowed:
// their two copies of a point are never tested against each other). False when it finds no ear.
bool ear_clip(const Loop& polygon, std::vector<Eigen::Vector3i>& out) {
    const std::size_t n0 = polygon.point.size();
    if (n0 < 3) return n0 == 0;
    std::vector<std::size_t> prev(n0), next(n0);
    for (std::size_t i = 0; i < n0; ++i) {
        prev[i] = (i + n0 - 1) % n0;
        next[i] = (i + 1) % n0;
    }
    auto is_ear = [&](std::size_t i) {
        const Vec2& a = polygon.point[prev[i]];
        const Vec2& b = polygon.point[i];
        const Vec2& c = polygon.point[next[i]];
        if (cross2(a, b, c) <= 0.0) return false;  // reflex or flat
        for (std::size_t j = next[next[i]]; j != prev[i]; j = next[j]) {
            const Vec2& p = polygon.point[j];
            if (p == a || p == b || p == c) continue;  // a bridge's other copy
            if (cross2(a, b, p) >= 0.0 && cross2(b, c, p) >= 0.0 && cross2(c, a, p) >= 0.0)
                return false;
        }
        return true;
    };
    std::size_t remaining = n0, i = 0, stalled = 0;
    while (remaining > 3) {
        if (is_ear(i)) {
            out.emplace_back(polygon.index[prev[i]], polygon.index[i], polygon.index[next[i]]);
            next[prev[i]] = next[i];
            prev[next[i]] = prev[i];
            --remaining;
            i = prev[i];
            stalled = 0;
        } else {
            // A flat corner (three points on a line) adds no area: drop it when nothing else does.
            if (++stalled > remaining) {
                std::size_t flat = n0;
                for (std::size_t j = next[i], k = 0; k < remaining; j = next[j], ++k)
                    if (std::abs(cross2(polygon.point[prev[j]], polygon.point[j],
                                        polygon.point[next[j]])) == 0.0) {
                        flat = j;
                        break;
                    }
                if (flat == n0) return false;
                out.emplace_back(polygon.index[prev[flat]], polygon.index[flat],
                                 polygon.index[next[flat]]);
                next[prev[flat]] = next[flat];
                prev[next[flat]] = prev[flat];
                --remaining;
                i = prev[flat];
                stalled = 0;
                continue;
            }
            i = next[i];
        }
    }
    out.emplace_back(polygon.index[prev[i]], polygon.index[i], polygon.index[next[i]]);
    return true;
}

// Triangles covering the regions the loops bound (outer loops counter-clockwise, holes clockwise,
// each hole inside the smallest outer loop holding it); false when the loops are degenerate.
bool triangulate(std::vector<Loop> loops, std::vector<Eigen::Vector3i>& out) {
    std::vector<Loop> outers, holes;
    for (Loop& l : loops) {
        const double a = loop_area(l);
        if (a > 0.0)
            outers.push_back(std::move(l));
        else if (a < 0.0)
            holes.push_back(std::move(l));
        else
            return false;
    }
    std::vector<std::vector<Loop>> holes_of(outers.size());
    for (Loop& h : holes) {
        std::size_t best = outers.size();
        double best_area = 0.0;
        for (std::size_t o = 0; o < outers.size(); ++o) {
            const double a = loop_area(outers[o]);
            if (point_in_loop(outers[o], h.point.front()) &&
                (best == outers.size() || a < best_area)) {
                best = o;
                best_area = a;
            }
        }
        if (best == outers.size()) return false;
        holes_of[best].push_back(std::move(h));
    }
    for (std::size_t o = 0; o < outers.size(); ++o) {
        if (!bridge_holes(outers[o], std::move(holes_of[o]))) return false;
        if (!ear_clip(outers[o], out)) return false;
    }
    return true;
}

// ---- splitting a closed mesh by a plane -------------------------------------------------------

std::uint64_t edge_key(int a, int b) {
    if (a > b) std::swap(a, b);
    return (std::uint64_t(std::uint32_t(a)) << 32) | std::uint32_t(b);
}

struct UnionFind {
    std::vector<int> parent;
    explicit UnionFind(std::size_t n) : parent(n) {
        for (std::size_t i = 0; i < n; ++i) parent[i] = int(i);
    }
    int find(int i) {
        while (parent[i] != i) i = parent[i] = parent[parent[i]];
        return i;
    }
    void join(int a, int b) { parent[find(a)] = find(b); }
};

// Where the ray from `origin` along `dir` meets triangle t of the mesh (Moller-Trumbore): true,
// with how far along it in `dist` (in units of |dir|; negative behind the origin).
bool ray_meets(const TriangleMesh& mesh, const Eigen::Vector3i& t, const Vec3& origin,
               const Vec3& dir, double& dist) {
    const Vec3& a = mesh.vertices[std::size_t(t[0])];
    const Vec3 e1 = mesh.vertices[std::size_t(t[1])] - a, e2 = mesh.vertices[std::size_t(t[2])] - a;
    const Vec3 p = dir.cross(e2);
    const double det = e1.dot(p);
    if (det == 0.0) return false;
    const Vec3 s = origin - a;
    const double u = s.dot(p) / det;
    if (u < 0.0 || u > 1.0) return false;
    const Vec3 q = s.cross(e1);
    const double v = dir.dot(q) / det;
    if (v < 0.0 || u + v > 1.0) return false;
    dist = e2.dot(q) / det;
    return true;
}

// The nearest triangle the ray from `origin` along `dir` meets (t > 0), -1 for none.
int first_hit(const TriangleMesh& mesh, const Vec3& origin, const Vec3& dir) {
    int best = -1;
    double best_t = std::numeric_limits<double>::infinity();
    for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
        double dist = 0.0;
        if (ray_meets(mesh, mesh.triangles[t], origin, dir, dist) && dist > 0.0 && dist < best_t) {
            best_t = dist;
            best = int(t);
        }
    }
    return best;
}

// Where the ray from `origin` along the unit `dir` meets the mesh's facets within (0, length]:
// distance and the facet's unit normal (outward on a closed mesh facing out).
void ray_hits(const TriangleMesh& mesh, const Vec3& origin, const Vec3& dir, double length,
              std::vector<RayHit>& hits) {
    for (const auto& t : mesh.triangles) {
        double dist = 0.0;
        if (!ray_meets(mesh, t, origin, dir, dist) || dist <= 0.0 || dist > length) continue;
        const Vec3& a = mesh.vertices[std::size_t(t[0])];
        const Vec3 normal =
            (mesh.vertices[std::size_t(t[1])] - a).cross(mesh.vertices[std::size_t(t[2])] - a);
        if (normal.norm() > 0.0) hits.push_back({dist, normal.normalized()});
    }
}

// Drops the vertices no triangle uses.
TriangleMesh compacted(const std::vector<Vec3>& vertices,
                       const std::vector<Eigen::Vector3i>& triangles) {
    TriangleMesh out;
    std::vector<int> remap(vertices.size(), -1);
    out.triangles.reserve(triangles.size());
    for (const Eigen::Vector3i& t : triangles) {
        Eigen::Vector3i r;
        for (int k = 0; k < 3; ++k) {
            int& m = remap[t[k]];
            if (m < 0) {
                m = int(out.vertices.size());
                out.vertices.push_back(vertices[t[k]]);
            }
            r[k] = m;
        }
        out.triangles.push_back(r);
    }
    return out;
}

// Each edge of the mesh (edge_key) and the triangles on either side of it (-1 for none).
std::unordered_map<std::uint64_t, std::array<int, 2>> edge_triangles(const TriangleMesh& mesh) {
    std::unordered_map<std::uint64_t, std::array<int, 2>> edges;
    edges.reserve(mesh.triangles.size() * 2);
    for (std::size_t t = 0; t < mesh.triangles.size(); ++t)
        for (int k = 0; k < 3; ++k) {
            auto& e =
                edges
                    .try_emplace(edge_key(mesh.triangles[t][k], mesh.triangles[t][(k + 1) % 3]),
                                 std::array<int, 2>{-1, -1})
                    .first->second;
            (e[0] < 0 ? e[0] : e[1]) = int(t);
        }
    return edges;
}

// Where the mesh's edges cross a plane (`d`: each vertex's signed distance from it), each point
// made once and added to `vertices`, shared by the triangles on either side.
class Crossings {
public:
    Crossings(const TriangleMesh& mesh, const std::vector<double>& d, std::vector<Vec3>& vertices)
        : mesh_(mesh), d_(d), vertices_(vertices) {}
    int at(int a, int b) {
        const auto [it, added] = made_.try_emplace(edge_key(a, b), int(vertices_.size()));
        if (added) {
            const int lo = std::min(a, b), hi = std::max(a, b);
            const double s = d_[lo] / (d_[lo] - d_[hi]);
            vertices_.push_back(mesh_.vertices[lo] + s * (mesh_.vertices[hi] - mesh_.vertices[lo]));
        }
        return it->second;
    }
    // Cuts triangle `tri`, one vertex alone on its side of the plane and none on it (`above`:
    // how many lie above): its pieces go to `up` and `down`. Returns the piece above's edge
    // along the plane (from, to).
    std::pair<int, int> cut(const Eigen::Vector3i& tri, int above, std::vector<Eigen::Vector3i>& up,
                            std::vector<Eigen::Vector3i>& down) {
        int r = 0;
        for (int k = 0; k < 3; ++k)
            if ((d_[tri[k]] > 0.0) == (above == 1)) r = k;
        const int i0 = tri[r], i1 = tri[(r + 1) % 3], i2 = tri[(r + 2) % 3];
        const int x01 = at(i0, i1), x20 = at(i2, i0);
        std::vector<Eigen::Vector3i>& lone = above == 1 ? up : down;
        std::vector<Eigen::Vector3i>& pair = above == 1 ? down : up;
        lone.emplace_back(i0, x01, x20);
        pair.emplace_back(x01, i1, i2);
        pair.emplace_back(x01, i2, x20);
        return above == 1 ? std::pair{x01, x20} : std::pair{x20, x01};
    }

private:
    const TriangleMesh& mesh_;
    const std::vector<double>& d_;
    std::vector<Vec3>& vertices_;
    std::unordered_map<std::uint64_t, int> made_;
};

// Closes the two sides of a cut with one cap on the plane (`frame`'s): `cap_next` maps each
// vertex of the outline to the next along the cap (the piece above's edges run the other way),
// its outer loops clockwise seen from above. The cap goes to `down` facing up and to `up` facing
// down; `cap_count` receives its triangles. False, with why (`none`: no outline at all;
// `open`: loops the triangulation cannot close).
bool close_with_cap(std::map<int, int> cap_next, const std::vector<Vec3>& vertices,
                    const PlaneFrame& frame, std::vector<Eigen::Vector3i>& up,
                    std::vector<Eigen::Vector3i>& down, std::size_t& cap_count, const char* none,
                    const char* open, std::string& why) {
    std::vector<Loop> loops;
    while (!cap_next.empty()) {
        Loop loop;
        int v = cap_next.begin()->first;
        while (true) {
            const auto it = cap_next.find(v);
            if (it == cap_next.end()) break;
            loop.index.push_back(v);
            loop.point.push_back(frame.to_2d(vertices[v]));
            v = it->second;
            cap_next.erase(it);
        }
        if (v != loop.index.front()) {
            why = "the cut's outline does not close";
            return false;
        }
        std::reverse(loop.index.begin(), loop.index.end());  // counter-clockwise outer loops
        std::reverse(loop.point.begin(), loop.point.end());
        loops.push_back(std::move(loop));
    }
    if (loops.empty()) {
        why = none;
        return false;
    }
    std::vector<Eigen::Vector3i> cap;  // facing up: the below piece's
    if (!triangulate(std::move(loops), cap)) {
        why = open;
        return false;
    }
    for (const Eigen::Vector3i& t : cap) {
        down.push_back(t);
        up.emplace_back(t[0], t[2], t[1]);
    }
    cap_count = cap.size();
    return true;
}

}  // namespace

bool split_mesh(const TriangleMesh& mesh, const Plane& plane, const Eigen::Vector3d& inside,
                TriangleMesh& above, TriangleMesh& below, std::string& why, double* cut_offset) {
    const std::size_t nv = mesh.vertices.size(), nt = mesh.triangles.size();
    const Vec3 n = plane.normal;
    // Off every vertex: a vertex on the plane would leave slivers of no area on one side.
    double offset = n.dot(plane.origin);
    double scale = 1.0;
    for (const Vec3& v : mesh.vertices) scale = std::max(scale, v.cwiseAbs().maxCoeff());
    std::vector<double> d(nv);
    for (int attempt = 0;; ++attempt) {
        double nearest = std::numeric_limits<double>::infinity();
        for (std::size_t v = 0; v < nv; ++v) {
            d[v] = n.dot(mesh.vertices[v]) - offset;
            nearest = std::min(nearest, std::abs(d[v]));
        }
        if (nearest > 1e-12 * scale) break;
        if (attempt == 8) {
            why = "vertices lie on the cutting plane";
            return false;
        }
        offset += 1e-7 * scale;
    }
    if (n.dot(inside) - offset <= 0.0) {
        why = "its first section lies behind the cutting plane";
        return false;
    }
    // The triangles above the plane (wholly or in part), joined where they share an edge with an
    // end above it: each class is one connected piece of the surface above the plane.
    UnionFind classes(nt);
    for (const auto& [key, tris] : edge_triangles(mesh)) {
        const int a = int(key >> 32), b = int(key & 0xffffffffu);
        if ((d[a] > 0.0 || d[b] > 0.0) && tris[0] >= 0 && tris[1] >= 0)
            classes.join(tris[0], tris[1]);
    }
    // The piece holding `inside`: the first surface a ray from it meets, away from the plane
    // (slightly askew, off edges and vertices that lie square to the plane).
    const PlaneFrame frame(n);
    const Vec3 dir = (n + 1.234567e-3 * frame.u + 0.7654321e-3 * frame.v).normalized();
    const int hit = first_hit(mesh, inside, dir);
    if (hit < 0) {
        why = "its first section is not inside the mesh";
        return false;
    }
    const int piece = classes.find(hit);
    // The piece's triangles go above, cut where they cross the plane; the rest, whole, below.
    std::vector<Vec3> vertices = mesh.vertices;
    Crossings crossings(mesh, d, vertices);
    std::vector<Eigen::Vector3i> up, down;
    // The above piece's open edges along the plane, ordered: the loops, their first points and
    // so the cap's triangles do not depend on a hash table's order.
    std::map<int, int> cap_next;
    bool branching = false;
    for (std::size_t t = 0; t < nt; ++t) {
        const Eigen::Vector3i& tri = mesh.triangles[t];
        const int ups = int(d[tri[0]] > 0.0) + int(d[tri[1]] > 0.0) + int(d[tri[2]] > 0.0);
        if (ups == 0 || classes.find(int(t)) != piece) {
            down.push_back(tri);
            continue;
        }
        if (ups == 3) {
            up.push_back(tri);
            continue;
        }
        // The cap runs the above piece's edge along the plane the other way.
        const auto [from, to] = crossings.cut(tri, ups, up, down);
        branching |= !cap_next.emplace(to, from).second;
    }
    if (branching) {
        why = "the cut meets itself";
        return false;
    }
    std::size_t cap_count = 0;
    if (!close_with_cap(std::move(cap_next), vertices, frame, up, down, cap_count,
                        "the plane does not cut it", "its section on the plane could not be closed",
                        why))
        return false;
    above = compacted(vertices, up);
    below = compacted(vertices, down);
    if (cut_offset) *cut_offset = offset;
    return true;
}

namespace {

// "+X" for an axis' direction; "0.866,0.5,0" for one of a turned frame's (AxisParams::frame_deg).
std::string direction_name(const Vec3& d) {
    const char* names[] = {"X", "Y", "Z"};
    int k = 0;
    d.cwiseAbs().maxCoeff(&k);
    if (std::abs(std::abs(d[k]) - 1.0) <= 1e-9) return std::string(d[k] < 0 ? "-" : "+") + names[k];
    std::ostringstream text;
    text << std::setprecision(3) << d.x() << "," << d.y() << "," << d.z();
    return text.str();
}

double lowest_along(const TriangleMesh& mesh, const Vec3& n) {
    double lo = std::numeric_limits<double>::infinity();
    for (const Vec3& v : mesh.vertices) lo = std::min(lo, n.dot(v));
    return lo;
}

double highest_along(const TriangleMesh& mesh, const Vec3& n) {
    double hi = -std::numeric_limits<double>::infinity();
    for (const Vec3& v : mesh.vertices) hi = std::max(hi, n.dot(v));
    return hi;
}

// Splits the closed mesh at the plane n.x = offset through flat facets of it (a bridge's
// underside), keeping the vertices within `tol` of the plane on it (split_mesh moves the plane off
// them, which would leave the underside in a sheet a ten-millionth thick on one side). `above` is
// the connected piece above the plane holding `inside`, with the facets on the plane facing -n
// that border it (its underside, hanging over the gap); `below` is the rest. Where they touch
// (the father's top under the piece) each is closed by the same cap on the plane, the last
// `cap` triangles of `above`. False, with why, as split_mesh.
bool split_on_face(const TriangleMesh& mesh, const Vec3& n, double offset, double tol,
                   const Vec3& inside, TriangleMesh& above, TriangleMesh& below,
                   std::size_t& cap_count, std::string& why) {
    const std::size_t nv = mesh.vertices.size(), nt = mesh.triangles.size();
    std::vector<double> d(nv);
    for (std::size_t v = 0; v < nv; ++v) {
        d[v] = n.dot(mesh.vertices[v]) - offset;
        if (std::abs(d[v]) <= tol) d[v] = 0.0;
    }
    if (n.dot(inside) - offset <= tol) {
        why = "its material point lies behind the cutting plane";
        return false;
    }
    // Above the plane: a triangle with a vertex above it, or lying on it facing -n. One within
    // `tol` of the plane standing on its edge (a sliver of a side face an earlier cut a
    // hundred-thousandth of a mm above the plane left: a portal's lintel reaching past its legs)
    // goes with the side most of its neighbours are on; left below, it stood alone in a loop of
    // no area, which the cap cannot close.
    std::vector<char> up_side(nt, 0);
    std::vector<std::size_t> on_edge;
    for (std::size_t t = 0; t < nt; ++t) {
        const Eigen::Vector3i& tri = mesh.triangles[t];
        const Vec3 &a = mesh.vertices[tri[0]], &b = mesh.vertices[tri[1]],
                   &c = mesh.vertices[tri[2]];
        const bool flat = d[tri[0]] == 0.0 && d[tri[1]] == 0.0 && d[tri[2]] == 0.0;
        const Vec3 normal = (b - a).cross(c - a);
        up_side[t] =
            flat ? normal.dot(n) < 0.0 : d[tri[0]] > 0.0 || d[tri[1]] > 0.0 || d[tri[2]] > 0.0;
        if (flat && std::abs(normal.dot(n)) <= 0.5 * normal.norm()) on_edge.push_back(t);
    }
    const auto edges = edge_triangles(mesh);
    bool changed = !on_edge.empty();
    for (int pass = 0; changed && pass < 8; ++pass) {
        changed = false;
        for (const std::size_t t : on_edge) {
            const Eigen::Vector3i& tri = mesh.triangles[t];
            int ups = 0;
            for (int k = 0; k < 3; ++k) {
                const auto& across = edges.at(edge_key(tri[k], tri[(k + 1) % 3]));
                const int other = across[0] == int(t) ? across[1] : across[0];
                ups += other >= 0 && up_side[std::size_t(other)];
            }
            if (char(ups >= 2) != up_side[t]) {
                up_side[t] = ups >= 2;
                changed = true;
            }
        }
    }
    UnionFind classes(nt);
    for (const auto& [key, tris] : edges)
        if (tris[0] >= 0 && tris[1] >= 0 && up_side[std::size_t(tris[0])] &&
            up_side[std::size_t(tris[1])])
            classes.join(tris[0], tris[1]);
    const PlaneFrame frame(n);
    const Vec3 dir = (n + 1.234567e-3 * frame.u + 0.7654321e-3 * frame.v).normalized();
    const int hit = first_hit(mesh, inside, dir);
    if (hit < 0 || !up_side[std::size_t(hit)]) {
        why = "its material point is not inside the mesh above the plane";
        return false;
    }
    const int piece = classes.find(hit);
    std::vector<Vec3> vertices = mesh.vertices;
    Crossings crossings(mesh, d, vertices);
    std::vector<Eigen::Vector3i> up, down;
    for (std::size_t t = 0; t < nt; ++t) {
        const Eigen::Vector3i& tri = mesh.triangles[t];
        if (!up_side[t] || classes.find(int(t)) != piece) {
            down.push_back(tri);
            continue;
        }
        int below_count = 0, above_count = 0;
        for (int k = 0; k < 3; ++k) {
            below_count += d[tri[k]] < 0.0;
            above_count += d[tri[k]] > 0.0;
        }
        if (below_count == 0) {
            up.push_back(tri);
            continue;
        }
        if (below_count + above_count == 3) {
            crossings.cut(tri, above_count, up, down);  // as split_mesh cuts
            continue;
        }
        // One vertex on the plane, one above, one below: cut from the one on it.
        int r = 0;
        for (int k = 0; k < 3; ++k)
            if (d[tri[k]] == 0.0) r = k;
        const int i0 = tri[r], i1 = tri[(r + 1) % 3], i2 = tri[(r + 2) % 3];
        const int x = crossings.at(i1, i2);
        (d[i1] > 0.0 ? up : down).emplace_back(i0, i1, x);
        (d[i2] > 0.0 ? up : down).emplace_back(i0, x, i2);
    }
    // The piece's open edges (all on the plane on a closed mesh): its cap runs them the other way.
    std::set<std::pair<int, int>> directed;
    for (const Eigen::Vector3i& t : up)
        for (int k = 0; k < 3; ++k) directed.emplace(t[k], t[(k + 1) % 3]);
    std::map<int, int> cap_next;
    for (const auto& [a, b] : directed) {
        if (directed.count({b, a})) continue;
        if (!cap_next.emplace(b, a).second) {
            why = "the cut meets itself";
            return false;
        }
    }
    if (!close_with_cap(std::move(cap_next), vertices, frame, up, down, cap_count,
                        "the piece does not touch what is under the plane",
                        "its contact with the father on the plane could not be closed", why))
        return false;
    above = compacted(vertices, up);
    below = compacted(vertices, down);
    return true;
}

// The area of `mesh`'s triangles but its last `skip` leaning past `overhang_deg` off the unit
// `way` (leans_past, Slicing.hpp).
double overhang_of(const TriangleMesh& mesh, std::size_t skip, const Vec3& way,
                   double overhang_deg) {
    double area = 0.0;
    for (std::size_t t = 0; t + skip < mesh.triangles.size(); ++t) {
        const Eigen::Vector3i& tri = mesh.triangles[t];
        const Vec3 c = (mesh.vertices[tri[1]] - mesh.vertices[tri[0]])
                           .cross(mesh.vertices[tri[2]] - mesh.vertices[tri[0]]);
        if (c.norm() > 0.0 && leans_past(c.normalized(), way, overhang_deg)) area += 0.5 * c.norm();
    }
    return area;
}

// Whether every piece of `mesh` (its vertices joined by its triangles) reaches back along the
// unit `n` to `most` (n . point <= most).
bool every_shell_down_to(const TriangleMesh& mesh, const Vec3& n, double most) {
    UnionFind shells(mesh.vertices.size());
    for (const Eigen::Vector3i& t : mesh.triangles) {
        shells.join(t[0], t[1]);
        shells.join(t[0], t[2]);
    }
    std::unordered_map<int, double> lowest;
    for (std::size_t v = 0; v < mesh.vertices.size(); ++v) {
        const double h = n.dot(mesh.vertices[v]);
        const auto [it, added] = lowest.try_emplace(shells.find(int(v)), h);
        if (!added) it->second = std::min(it->second, h);
    }
    for (const auto& [shell, h] : lowest)
        if (h > most) return false;
    return true;
}

// The first component whose mesh holds `p`, -1 for none.
int holding(const MeshDecomposition& d, const Vec3& p) {
    for (std::size_t c = 0; c < d.components.size(); ++c)
        if (bounding_box(d.components[c].mesh).contains(p) && inside_mesh(d.components[c].mesh, p))
            return int(c);
    return -1;
}

// A branch kept in a component, and why (decompose_mesh's notes).
struct Kept {
    std::size_t branch;
    int component;
    std::string why;
};

// Bridges (Decompose.hpp), on a mesh: where branch b's track merged into m's, both marching along
// D in one component built along D, over flat facets facing -D within two steps past b's last
// node over the gap, the component is split at their plane (split_on_face), and the piece past it
// becomes b's child (m's where b made the component), built along the diagonal d = (D + g) /
// sqrt 2, g the frame's direction square to D nearest the gap's, either way, where that leaves
// at most half of the piece's facets leaning past the overhang angle that lean so along D (its cap
// on the father excepted); the way leaving less, from m's track towards b's where alike. The
// piece starts at its lowest point along d (no wedge goes back to the father: a mesh has no faces
// to find the piece's top by). Refused, as any split of decompose_mesh, where the piece would not
// reach a step past the plane, rest on the plate, leave the father thinner than a step, or either
// piece not be a closed solid (the piece is one body: the piece of the surface holding the point
// past the plane, and its cap); the father may be left in several bodies apart, each standing on
// its base (the root: on the plate; a portal's legs, posts cut off a plate). Lowest first; the
// piece goes right after its father, the father's children whose bases lie past the plane its
// own, and the components in `notes` after it move on.
void bridges(MeshDecomposition& out, const CentroidalAxis& axis, const MeshDecomposeParams& params,
             const Eigen::AlignedBox3d& box, double plate_tol, std::vector<Kept>& notes,
             const Progress& progress) {
    const double step = axis.params.step_mm;
    const double tol = 1e-6 * (1.0 + box.diagonal().norm());
    const double min_reach = std::max(params.min_component_height_mm, step);
    const Eigen::Matrix3d frame =
        Eigen::AngleAxisd(axis.params.frame_deg * kPi / 180.0, Vec3::UnitZ()).matrix();
    for (const std::size_t b : merged_lowest_first(axis)) {
        progress.check();
        const AxisBranch& br = axis.branches[b];
        const std::size_t m = std::size_t(br.merged_into);
        const Vec3 D = br.direction.normalized();
        if (axis.branches[m].nodes.empty() ||
            !axis.branches[m].direction.normalized().isApprox(D, 1e-9))
            continue;
        // The gap (bridge_gap) and the component holding both tracks there, found by their
        // material (a branch whose split was refused may since have gone with its brother's
        // piece: a window's jamb).
        const BridgeGap gap = bridge_gap(axis, b, m, D, frame);
        if (!(gap.across.norm() > step)) continue;
        const Vec3 pb = axis.nodes[std::size_t(gap.to)].position;
        const double sb = D.dot(pb);
        const int c = holding(out, axis.nodes[std::size_t(gap.to)].material_point());
        if (c < 0 || c != holding(out, axis.nodes[std::size_t(gap.from)].material_point()) ||
            !out.components[std::size_t(c)].base.normal.isApprox(D, 1e-9))
            continue;
        const std::size_t owner = out.components[std::size_t(c)].branch == int(b) ? m : b;
        if (out.components[std::size_t(c)].branch == int(owner)) continue;
        // The plane: the lowest of the flat facets facing -D within two steps past b's last node
        // that span the gap: every point of the segment across it a quarter step under their plane
        // that lies outside the mesh (the gap), seen along D, lies on one of them, and one does.
        // (A round hole's wall has a facet facing -D too, narrower than the hole under it: a Z
        // bracket's bolt hole, marched across, was taken for a bridge.)
        const TriangleMesh& fm = out.components[std::size_t(c)].mesh;
        const Vec3 pa = pb - gap.across;
        const PlaneFrame across(D);
        std::map<double, std::vector<std::array<Vec2, 3>>> flats;  // by offset along D
        for (const Eigen::Vector3i& t : fm.triangles) {
            const Vec3 &p0 = fm.vertices[t[0]], &p1 = fm.vertices[t[1]], &p2 = fm.vertices[t[2]];
            const Vec3 normal = (p1 - p0).cross(p2 - p0);
            if (!(normal.norm() > 0.0) || normal.normalized().dot(-D) < 1.0 - 1e-9) continue;
            const double sf = D.dot(p0);
            if (std::abs(D.dot(p1) - sf) > tol || std::abs(D.dot(p2) - sf) > tol) continue;
            if (sf <= sb + tol || sf > sb + 2.0 * step) continue;
            auto near = flats.lower_bound(sf - tol);
            if (near == flats.end() || near->first > sf + tol)
                near = flats.emplace(sf, std::vector<std::array<Vec2, 3>>{}).first;
            near->second.push_back({across.to_2d(p0), across.to_2d(p1), across.to_2d(p2)});
        }
        const auto on_facet = [&](const std::vector<std::array<Vec2, 3>>& facets, const Vec2& q) {
            for (const auto& f : facets) {
                const double a = cross2(f[0], f[1], q), b = cross2(f[1], f[2], q),
                             e = cross2(f[2], f[0], q);
                const double slack =
                    tol * ((f[1] - f[0]).norm() + (f[2] - f[1]).norm() + (f[0] - f[2]).norm());
                if ((a >= -slack && b >= -slack && e >= -slack) ||
                    (a <= slack && b <= slack && e <= slack))
                    return true;
            }
            return false;
        };
        std::optional<double> s;
        for (const auto& [sf, facets] : flats) {
            bool gap = false, spanned = true;
            for (int i = 0; i <= 64 && spanned; ++i) {
                Vec3 q = pa + (pb - pa) * (double(i) / 64.0);
                q += D * (sf - 0.25 * step - D.dot(q));
                if (inside_mesh(fm, q)) continue;
                gap = true;
                spanned = on_facet(facets, across.to_2d(q));
            }
            if (gap && spanned) {
                s = sf;
                break;
            }
        }
        if (!s) continue;
        const int past = bridge_node(axis, D, *s, tol, 0.5 * (pa + pb) + D * (*s - sb));
        if (past < 0) continue;
        TriangleMesh above, below;
        std::size_t cap = 0;
        std::string why;
        if (!split_on_face(fm, D, *s, tol, axis.nodes[std::size_t(past)].material_point(), above,
                           below, cap, why))
            continue;
        const ComponentMesh& father = out.components[std::size_t(c)];
        const double base_offset = D.dot(father.base.origin);
        const double plate = out.components.front().base.origin.z() + std::max(plate_tol, tol);
        if (highest_along(above, D) - *s < min_reach - tol ||
            lowest_along(above, Vec3::UnitZ()) <= plate ||
            highest_along(below, D) - base_offset < min_reach)
            continue;
        // The father may be left in pieces apart, each standing on its base (the root: on the
        // plate): a portal's legs, or posts cut off a plate at a section plane.
        if (!every_shell_down_to(below, D, c == 0 ? plate : base_offset + std::max(tol, 1e-6)))
            continue;
        const MeshReport above_report = check_mesh(above), below_report = check_mesh(below);
        if (!above_report.closed() || !below_report.closed() || !(above_report.volume_mm3 > 0.0) ||
            !(below_report.volume_mm3 > 0.0))
            continue;
        try {
            require_one_solid(above, "piece");
            require_one_solid(below, "piece");
        } catch (const Error&) {
            continue;
        }
        const Vec3 d = bridge_direction(D, gap.way, params.max_tilt_deg, [&](const Vec3& way) {
            return overhang_of(above, cap, way, params.overhang_angle_deg);
        });
        if (d.isZero()) continue;
        const auto kept = std::find_if(params.keep_branches.begin(), params.keep_branches.end(),
                                       [&](const KeptBranch& k) { return k.branch == int(owner); });
        if (kept != params.keep_branches.end()) {
            notes.push_back({owner, c, kept->why});
            continue;
        }
        Vec3 at = above.vertices.front();
        for (const Vec3& q : above.vertices)
            if (d.dot(q) < d.dot(at)) at = q;
        ComponentMesh child;
        child.parent = c;
        child.base = make_plane(at, d);
        child.branch = int(owner);
        child.bridge = true;
        const int to = c + 1;
        for (ComponentMesh& o : out.components)
            if (o.parent >= to) ++o.parent;
        for (Kept& k : notes)
            if (k.component >= to) ++k.component;
        out.components[std::size_t(c)].mesh = std::move(below);
        child.mesh = std::move(above);
        out.components.insert(out.components.begin() + to, std::move(child));
        for (std::size_t i = std::size_t(to) + 1; i < out.components.size(); ++i)
            if (out.components[i].parent == c && D.dot(out.components[i].base.origin) > *s + tol)
                out.components[i].parent = to;
    }
}

// The node branch `br`'s first link starts at (on its father's march, where it turns or splits
// off), -1 where the axis has none.
int junction(const CentroidalAxis& axis, const AxisBranch& br) {
    if (br.first_link < 0 || std::size_t(br.first_link) >= axis.links.size()) return -1;
    const int start = axis.links[std::size_t(br.first_link)].start;
    return start >= 0 && std::size_t(start) < axis.nodes.size() ? start : -1;
}

// The branch whose march node `start` (a junction) lies on, -1 where there is none.
int march_of(const CentroidalAxis& axis, int start) {
    const int fb = start >= 0 ? axis.nodes[std::size_t(start)].branch : -1;
    return fb >= 0 && std::size_t(fb) < axis.branches.size() ? fb : -1;
}

}  // namespace

void check_kept_branches(const std::vector<KeptBranch>& kept, const CentroidalAxis& axis,
                         const std::string& caller) {
    for (const KeptBranch& k : kept) {
        if (k.branch == 0)
            throw Error(ErrorCode::InvalidArgument,
                        caller + ": branch 0 is the axis' root, which has no father to stay in");
        if (k.branch < 0 || k.branch >= int(axis.branches.size()))
            throw Error(ErrorCode::InvalidArgument,
                        caller + ": there is no branch " + std::to_string(k.branch) +
                            " to keep in its father (the axis has " +
                            std::to_string(axis.branches.size()) + " branches, 0 its root)");
    }
}

bool branch_line(const CentroidalAxis& axis, std::size_t b, double tolerance_mm, Vec3& along) {
    // Below 2 degrees, the stub a plane square to D leaves in the father is less than 3.5 % of
    // the branch's section's width deep.
    constexpr double kOffLineDeg = 2.0;
    if (b >= axis.branches.size()) return false;
    const AxisBranch& br = axis.branches[b];
    if (br.parent < 0 || std::size_t(br.parent) >= axis.branches.size() || br.first_link < 0 ||
        std::size_t(br.first_link) >= axis.links.size() || br.nodes.size() < 3)
        return false;
    const Vec3 D = br.direction.normalized();
    const std::size_t most = std::min<std::size_t>(br.nodes.size(), 6);
    Vec3 line = Vec3::Zero();
    for (std::size_t n = most; n >= 3; --n) {
        Vec3 mean = Vec3::Zero();
        double least = std::numeric_limits<double>::infinity(), largest = 0.0;
        for (std::size_t i = 0; i < n; ++i) {
            const AxisNode& node = axis.nodes[std::size_t(br.nodes[i])];
            mean += node.position;
            least = std::min(least, node.area);
            largest = std::max(largest, node.area);
        }
        if (!(largest <= 1.1 * least)) continue;
        mean /= double(n);
        Eigen::Matrix3d spread = Eigen::Matrix3d::Zero();
        for (std::size_t i = 0; i < n; ++i) {
            const Vec3 d = axis.nodes[std::size_t(br.nodes[i])].position - mean;
            spread += d * d.transpose();
        }
        const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> solver(spread);
        const Vec3 fit = solver.eigenvectors().col(2);  // the largest eigenvalue's
        bool straight = fit.allFinite();
        for (std::size_t i = 0; i < n && straight; ++i) {
            const Vec3 d = axis.nodes[std::size_t(br.nodes[i])].position - mean;
            straight = (d - fit.dot(d) * fit).norm() <= tolerance_mm;
        }
        if (straight) {
            line = fit.dot(D) < 0.0 ? Vec3(-fit) : fit;
            break;
        }
    }
    if (line.isZero()) return false;
    const int fb = march_of(axis, junction(axis, br));
    const Vec3 F = axis.branches[std::size_t(fb >= 0 ? fb : br.parent)].direction.normalized();
    line -= line.dot(F) * F;
    if (line.norm() < 1e-9) return false;
    line.normalize();
    const double off = std::acos(std::clamp(line.dot(D), -1.0, 1.0)) * 180.0 / kPi;
    if (off <= kOffLineDeg || off >= 60.0) return false;
    along = line;
    return true;
}

double turned_plane(const CentroidalAxis& axis, std::size_t b, const Vec3& along,
                    double clearance_mm, const RayCast& cast, Vec3& inner) {
    const double none = std::numeric_limits<double>::quiet_NaN();
    if (b >= axis.branches.size()) return none;
    const AxisBranch& br = axis.branches[b];
    const int start = junction(axis, br);
    if (br.nodes.empty() || start < 0) return none;
    const AxisNode& first = axis.nodes[std::size_t(br.nodes.front())];
    const std::vector<Vec2>& outline = first.region.outer.points;
    if (outline.size() < 3) return none;
    const AxisNode& junction = axis.nodes[std::size_t(start)];
    const PlaneFrame frame(first.normal);
    const std::size_t count = outline.size();
    const double spacing =
        std::max(0.1 * axis.params.step_mm, perimeter(first.region.outer) / 64.0);
    double furthest = -std::numeric_limits<double>::infinity();
    std::vector<RayHit> hits;
    for (std::size_t i = 0; i < count; ++i) {
        const Vec2& p = outline[i];
        const Vec2 edge = outline[(i + 1) % count] - p;
        const double length = edge.norm();
        if (length < 1e-12) continue;
        const Vec2 outward = Vec2(edge.y(), -edge.x()) / length;  // the outline is anticlockwise
        const int pieces = std::max(1, int(std::ceil(length / spacing)));
        for (int k = 0; k <= pieces; ++k) {
            const Vec2 q = p + edge * (double(k) / pieces) + clearance_mm * outward;
            const Vec3 from = frame.u * q.x() + frame.v * q.y() + first.normal * first.offset;
            const double reach = along.dot(from - junction.position);
            if (reach <= 0.0) continue;
            hits.clear();
            cast(from, -along, reach, hits);
            std::sort(hits.begin(), hits.end(),
                      [](const RayHit& x, const RayHit& y) { return x.distance < y.distance; });
            for (const RayHit& hit : hits)
                if (hit.normal.dot(along) >= 0.1) {
                    furthest = std::max(furthest, along.dot(from) - hit.distance);
                    break;
                }
        }
    }
    if (!std::isfinite(furthest)) return none;
    const double at = furthest + clearance_mm;
    if (along.dot(first.position) < at + clearance_mm) return none;
    if (along.dot(inner) < at + clearance_mm)
        inner += along * (at + clearance_mm - along.dot(inner));
    return at;
}

bool bend_plane(const CentroidalAxis& axis, std::size_t b, double clearance_mm, const Vec3& inner,
                Vec3& point, Vec3& normal) {
    if (b >= axis.branches.size()) return false;
    const AxisBranch& br = axis.branches[b];
    const int start = junction(axis, br);
    const int fb = march_of(axis, start);
    if (br.parent < 0 || br.nodes.size() < 3 || fb < 0) return false;
    const std::vector<int>& march = axis.branches[std::size_t(fb)].nodes;
    const Vec3 F = axis.branches[std::size_t(fb)].direction.normalized();
    const Vec3 D = br.direction.normalized();
    if (std::abs(F.dot(D)) > 1e-9) return false;
    const auto node = [&](int i) -> const AxisNode& { return axis.nodes[std::size_t(i)]; };
    const double level = axis.params.step_mm / 100.0;
    // The father's straight run, back from the junction.
    const auto at = std::find(march.begin(), march.end(), start);
    if (at == march.end()) return false;
    // Three nodes in a row level along `d` (two steps, not one that merely turns back).
    const auto straight = [&](int a, int m, int c, const Vec3& d) {
        const double x = d.dot(node(m).position);
        return std::abs(d.dot(node(a).position) - x) <= level &&
               std::abs(d.dot(node(c).position) - x) <= level;
    };
    std::ptrdiff_t run = at - march.begin();
    while (run >= 2 && !straight(march[std::size_t(run)], march[std::size_t(run - 1)],
                                 march[std::size_t(run - 2)], D))
        --run;
    if (run < 2) return false;
    const AxisNode& last_straight = node(march[std::size_t(run)]);
    // The father's march past its straight run is the bend. Other branches leaving it (and
    // their sub-branches) are the bend's own material, wholly in front of the plane below: the
    // rest of a valve body above a port, a column going on past an arm, are not.
    const std::set<int> bend(march.begin() + run + 1, march.end());
    // The march going on past the junction back on its straight run's line is a column the
    // branch leaves, however high it goes, not a bend. (A column going on as high as an arm off
    // its side whose underside slopes up 31 degrees to its tip, the arm's root drifting the
    // column's centroids below the junction, was taken for one: cut at the 45-degree plane
    // through the corner, the column kept the wedge under the arm's root, its underside leaning
    // 59 degrees off the column's layers, 3.3 mm^2 hanging in one.)
    const auto on_line = [&](int i) {
        return std::abs(D.dot(node(i).position) - D.dot(last_straight.position)) <= level;
    };
    for (auto i = at + 1; i != march.end(); ++i)
        if (on_line(*i)) return false;
    // So is a march that parts at the junction into branches going on along F, back on that
    // line: a pipe lying across a post, whose bore parts the post's march into the pipe's walls
    // over the bore, and whose ends, turned from there, were cut at the 45-degree planes through
    // its middle: the post kept the pipe's underside out to them (50 mm^2 hanging in a layer).
    for (std::size_t c = 0; c < axis.branches.size(); ++c) {
        const AxisBranch& on = axis.branches[c];
        if (c == b || on.parent != fb || junction(axis, on) != start ||
            on.direction.normalized().dot(F) < 1.0 - 1e-9)
            continue;
        if (std::any_of(on.nodes.begin(), on.nodes.end(), on_line)) return false;
    }
    const auto leaves_bend = [&](std::size_t c) {
        for (int x = int(c); x >= 0; x = axis.branches[std::size_t(x)].parent) {
            const AxisBranch& up = axis.branches[std::size_t(x)];
            if (std::size_t(x) == b) return false;  // one of b's own sub-branches
            if (bend.count(junction(axis, up))) return true;
        }
        return false;
    };
    // The branch's line.
    std::size_t settled = 2;
    while (settled < br.nodes.size() &&
           !straight(br.nodes[settled - 2], br.nodes[settled - 1], br.nodes[settled], F))
        ++settled;
    if (settled >= br.nodes.size()) return false;
    const Vec3 first = node(br.nodes.front()).position;
    const Vec3 corner = first + D * (D.dot(last_straight.position) - D.dot(first)) +
                        F * (F.dot(node(br.nodes[settled]).position) - F.dot(first));
    const Vec3 n = (F + D).normalized();
    const double plane = n.dot(corner);
    if (reach_along(last_straight, n) > plane - clearance_mm) return false;
    double reached = -std::numeric_limits<double>::infinity();
    for (const int i : br.nodes) reached = std::max(reached, reach_along(node(i), F));
    if (reach_along(node(march.back()), F) > reached + axis.params.step_mm) return false;
    for (std::size_t c = 0; c < axis.branches.size(); ++c)
        if (c != b && leaves_bend(c))
            for (const int i : axis.branches[c].nodes)
                if (n.dot(node(i).position) < plane + clearance_mm ||
                    reach_along(node(i), F) > reached + axis.params.step_mm)
                    return false;
    if (n.dot(inner) < plane + clearance_mm) return false;
    point = corner;
    normal = n;
    return true;
}

void check_square_branches(const std::vector<int>& square, const CentroidalAxis& axis,
                           const std::string& caller) {
    for (const int b : square)
        if (b <= 0 || b >= int(axis.branches.size()))
            throw Error(ErrorCode::InvalidArgument,
                        caller + ": there is no branch " + std::to_string(b) +
                            " to cut square to its direction (the axis has " +
                            std::to_string(axis.branches.size()) +
                            " branches, 0 its root, which is not cut)");
}

MeshDecomposition decompose_mesh(const TriangleMesh& mesh, const CentroidalAxis& axis,
                                 const MeshDecomposeParams& params, const Progress& progress) {
    check_kept_branches(params.keep_branches, axis, "decompose_mesh");
    check_square_branches(params.square_branches, axis, "decompose_mesh");
    MeshDecomposition out;
    ComponentMesh root;
    root.mesh = mesh;
    root.base = build_plate(mesh);
    out.components.push_back(std::move(root));
    const std::size_t nb = axis.branches.size();
    if (nb == 0) return out;
    const double step = axis.params.step_mm;
    const Eigen::AlignedBox3d box = bounding_box(mesh);
    const double tol = 1e-9 * std::max(1.0, box.diagonal().norm()) + 1e-9;
    const double plate_tol = std::max(axis.params.eps_mm, params.min_component_height_mm);
    // What each branch and its sub-branches swept (section area x slab length).
    std::vector<double> swept(nb, 0.0);
    for (const AxisNode& node : axis.nodes)
        if (node.branch >= 0) swept[node.branch] += node.area * node.thickness;
    for (std::size_t b = nb; b-- > 1;)
        if (axis.branches[b].parent >= 0) swept[axis.branches[b].parent] += swept[b];
    std::vector<int> component_of(nb, 0);  // where each branch's material went
    const double cos_tilt = std::cos(params.max_tilt_deg * kPi / 180.0);
    // Written out at the end: a bridge's piece, inserted after its father, moves the components
    // after it, and may take a noted branch's material.
    std::vector<Kept> kept_notes;
    for (std::size_t b = 0; b < nb; ++b) {
        progress(double(b) / double(nb));
        const AxisBranch& branch = axis.branches[b];
        if (branch.parent < 0 || branch.nodes.empty()) continue;
        component_of[b] = component_of[branch.parent];
        const Vec3 dir = branch.direction.normalized();
        // A branch that turned is found by how far it reaches out of the section it leaves,
        // however thin along its own direction: its piece need only hold a thickest layer at
        // slicing's defaults past Eq. 4's T, less the clearance the cut leaves past T
        // (Decompose.hpp).
        const bool turned = dir.dot(axis.branches[branch.parent].direction.normalized()) < 0.5;
        // Eq. 4's T (where the branch's march began) plus the clearance the axis' loops need,
        // not past the branch's first plane (Decompose.hpp's section plane).
        const double clearance = axis.params.eps_mm + axis.deflection_mm + step / 100.0;
        const double min_reach =
            std::max(params.min_component_height_mm,
                     turned ? std::min(step, LayerParams{}.max_layer_mm) - clearance : step);
        const AxisNode& first = axis.nodes[branch.nodes.front()];
        const Vec3 inside = first.material_point();
        const auto kept = std::find_if(params.keep_branches.begin(), params.keep_branches.end(),
                                       [&](const KeptBranch& k) { return k.branch == int(b); });
        // The component holding its first section: its father's, else the one it went to.
        int father = -1;
        for (int pass = 0; pass < 2 && father < 0; ++pass)
            for (std::size_t c = 0; c < out.components.size() && father < 0; ++c) {
                if ((pass == 0) != (int(c) == component_of[branch.parent])) continue;
                const TriangleMesh& m = out.components[c].mesh;
                if (bounding_box(m).contains(inside) && inside_mesh(m, inside)) father = int(c);
            }
        auto note = [&](const std::string& why) {
            kept_notes.push_back({b, std::max(father, component_of[branch.parent]), why});
        };
        if (father < 0) {
            note("its first section lies in no component");
            continue;
        }
        component_of[b] = father;
        if (kept != params.keep_branches.end()) {
            note(kept->why);
            continue;
        }
        if (dir.z() < cos_tilt - 1e-12) {
            note("built along it, its layers would tilt past max_tilt from +Z");
            continue;
        }
        const double offset =
            std::min(first.slab_start + clearance, first.offset - axis.params.eps_mm);
        ComponentMesh& from = out.components[father];
        // Cuts the father at the plane of normal `n` at `at` (n . point), the branch's piece
        // holding `in`: true when made (the child added), else false with why not.
        const auto cut_off = [&](const Vec3& n, double at, const Vec3& in, std::string& why) {
            TriangleMesh above, below;
            double cut = at;
            if (!split_mesh(from.mesh, make_plane(n * at, n), in, above, below, why, &cut)) {
                why = "the section plane cannot split it: " + why;
                return false;
            }
            // Within a millionth of the part's size (a piece reaching exactly that far falls
            // short of it by rounding).
            const double reach = highest_along(above, n) - cut;
            if (reach < min_reach - 1e-6 * (1.0 + box.diagonal().norm())) {
                std::ostringstream text;
                text << std::setprecision(3) << "its piece reaches " << reach
                     << " mm past the cut, less than " << min_reach;
                why = text.str();
                return false;
            }
            // Within a thinnest layer of the plate (a mesh's facets under a round body lying on
            // it may stand a chordal deviation above it), the piece stands on it.
            if (father == 0 && lowest_along(above, Vec3::UnitZ()) <=
                                   from.base.origin.z() + std::max(plate_tol, tol)) {
                why = "its piece rests on the build plate, from which the root builds it up";
                return false;
            }
            const Vec3& base_normal = from.base.normal;
            const double base_offset = base_normal.dot(from.base.origin);
            if (lowest_along(below, base_normal) > base_offset + 1e-6) {
                why = "its piece would take all of the base its component is built from";
                return false;
            }
            // Cut where its component begins (a branch born of a split whose brother's cut took
            // their common plane with it, both legs meeting again above a window), the father
            // would keep a sliver no layer fits.
            const double left = highest_along(below, base_normal) - base_offset;
            if (left < min_reach) {
                std::ostringstream text;
                text << std::setprecision(3) << "its component would keep only " << left
                     << " mm along its build direction, less than " << min_reach;
                why = text.str();
                return false;
            }
            const double bound = 4.0 * (swept[b] + 2.0 * step * first.area);
            if (mesh_volume(above) > bound) {
                why =
                    "its piece holds over four times what the branch swept: mostly other "
                    "material";
                return false;
            }
            const MeshReport above_report = check_mesh(above), below_report = check_mesh(below);
            bool solid = above_report.closed() && below_report.closed() &&
                         above_report.volume_mm3 > 0.0 && below_report.volume_mm3 > 0.0;
            if (solid) {
                try {
                    require_one_solid(above, "piece");
                    require_one_solid(below, "piece");
                } catch (const Error&) {
                    solid = false;
                }
            }
            if (!solid) {
                why = "its pieces would not be closed solids";
                return false;
            }
            from.mesh = std::move(below);
            ComponentMesh child;
            child.mesh = std::move(above);
            child.parent = father;
            child.base = make_plane(in - (n.dot(in) - cut) * n, n);
            child.branch = int(b);
            component_of[b] = int(out.components.size());
            out.components.push_back(std::move(child));
            return true;
        };
        // A branch running between the six directions (a blade on a hub): first at the plane
        // square to its line, just past the father's surface beside it (Decompose.hpp), its first
        // node's material moved along the line past it if it lies behind; that refused, or
        // asked (square_branches), at the plane square to its direction.
        std::string why;
        Vec3 along;
        const bool square = std::find(params.square_branches.begin(), params.square_branches.end(),
                                      int(b)) != params.square_branches.end();
        const bool lined = branch_line(axis, b, clearance, along);
        if (!square && lined && along.z() >= cos_tilt - 1e-12) {
            const TriangleMesh& father_mesh = from.mesh;
            Vec3 in = inside;
            const double at = turned_plane(
                axis, b, along, clearance,
                [&](const Vec3& origin, const Vec3& direction, double length,
                    std::vector<RayHit>& hits) {
                    ray_hits(father_mesh, origin, direction, length, hits);
                },
                in);
            if (std::isfinite(at)) {
                if (cut_off(along, at, in, why)) {
                    out.components.back().turned = true;
                    continue;
                }
            }
        }
        // A branch turning off its father round a bend: at the bend's halfway plane, built
        // along the bisector of its direction and its father's; that refused, square to D.
        Vec3 point, normal;
        if (!square && !lined && bend_plane(axis, b, clearance, inside, point, normal) &&
            normal.z() >= cos_tilt - 1e-12 && cut_off(normal, normal.dot(point), inside, why)) {
            out.components.back().turned = true;
            continue;
        }
        if (!cut_off(dir, offset, inside, why)) note(why);
    }
    bridges(out, axis, params, box, plate_tol, kept_notes, progress);
    for (Kept& k : kept_notes) {
        // Where its material is now: a later split may have taken it (a jamb whose split was
        // refused, taken with the wall over a window by its brother's).
        const AxisBranch& kb = axis.branches[k.branch];
        const int now =
            kb.nodes.empty()
                ? -1
                : holding(out, axis.nodes[std::size_t(kb.nodes.front())].material_point());
        if (now >= 0) k.component = now;
        std::ostringstream text;
        text << "branch " << k.branch << " ("
             << direction_name(axis.branches[k.branch].direction.normalized())
             << ") stays in component " << k.component << ": " << k.why;
        out.notes.push_back(text.str());
    }
    progress(1.0);
    return out;
}

}  // namespace mas
