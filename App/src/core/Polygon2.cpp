// Plain polygon maths (areas, centroids, containment, grouping loops into regions); the Booleans
// and offsets that need Clipper are in PolygonBoolean.cpp.
#include "mas/Polygon2.hpp"

#include <algorithm>
#include <cmath>

#include "mas/Angles.hpp"

namespace mas {

double signed_area(const Polygon2& polygon) {
    const auto& p = polygon.points;
    const std::size_t n = p.size();
    if (n < 3) return 0.0;
    // Shoelace relative to the first point: keeps precision for polygons far from the origin.
    double twice = 0.0;
    for (std::size_t i = 1; i + 1 < n; ++i) {
        const Eigen::Vector2d a = p[i] - p[0], b = p[i + 1] - p[0];
        twice += a.x() * b.y() - a.y() * b.x();
    }
    return 0.5 * twice;
}

namespace {

// Area-weighted first moment relative to `ref`, and the signed area.
void moments(const Polygon2& polygon, const Eigen::Vector2d& ref, double& area2,
             Eigen::Vector2d& moment6) {
    const auto& p = polygon.points;
    const std::size_t n = p.size();
    for (std::size_t i = 0; i < n; ++i) {
        const Eigen::Vector2d a = p[i] - ref, b = p[(i + 1) % n] - ref;
        const double c = a.x() * b.y() - b.x() * a.y();
        area2 += c;
        moment6 += (a + b) * c;
    }
}

}  // namespace

Eigen::Vector2d centroid(const Polygon2& polygon) {
    if (polygon.points.empty()) return Eigen::Vector2d::Zero();
    const Eigen::Vector2d ref = polygon.points.front();
    double area2 = 0.0;
    Eigen::Vector2d m = Eigen::Vector2d::Zero();
    moments(polygon, ref, area2, m);
    if (area2 == 0.0) return ref;
    return ref + m / (3.0 * area2);
}

double area(const Region2& region) {
    double a = std::abs(signed_area(region.outer));
    for (const auto& h : region.holes) a -= std::abs(signed_area(h));
    return a;
}

double area(const Regions2& regions) {
    double a = 0.0;
    for (const auto& r : regions) a += area(r);
    return a;
}

double perimeter(const Polygon2& polygon) {
    const auto& p = polygon.points;
    if (p.size() < 2) return 0.0;
    // The closing edge first, then the rest in order (the sum the axis' figures were taken with).
    double length = 0.0;
    for (std::size_t i = 0, j = p.size() - 1; i < p.size(); j = i++) length += (p[i] - p[j]).norm();
    return length;
}

double perimeter(const Region2& region) {
    double length = perimeter(region.outer);
    for (const auto& h : region.holes) length += perimeter(h);
    return length;
}

double perimeter(const Regions2& regions) {
    double length = 0.0;
    for (const auto& r : regions) length += perimeter(r);
    return length;
}

Eigen::Vector2d centroid(const Regions2& regions) {
    double a = 0.0;
    Eigen::Vector2d moment = Eigen::Vector2d::Zero();
    for (const auto& r : regions) {
        const double ar = area(r);
        a += ar;
        moment += ar * centroid(r);
    }
    return a > 0.0 ? Eigen::Vector2d(moment / a) : Eigen::Vector2d::Zero();
}

Eigen::Vector2d centroid(const Region2& region) {
    if (region.outer.points.empty()) return Eigen::Vector2d::Zero();
    const Eigen::Vector2d ref = region.outer.points.front();
    double area2 = 0.0;
    Eigen::Vector2d m = Eigen::Vector2d::Zero();
    // Outer counted positive and holes negative whatever their stored orientation.
    auto add = [&](const Polygon2& p, double sign) {
        double a2 = 0.0;
        Eigen::Vector2d mm = Eigen::Vector2d::Zero();
        moments(p, ref, a2, mm);
        const double s = (a2 >= 0.0 ? 1.0 : -1.0) * sign;
        area2 += s * a2;
        m += s * mm;
    };
    add(region.outer, 1.0);
    for (const auto& h : region.holes) add(h, -1.0);
    if (area2 == 0.0) return ref;
    return ref + m / (3.0 * area2);
}

Eigen::AlignedBox2d bounds(const Region2& region) {
    Eigen::AlignedBox2d box;
    for (const auto& p : region.outer.points) box.extend(p);
    return box;
}

namespace {

// Even-odd crossing test; points on the boundary may go either way.
bool inside(const Polygon2& polygon, const Eigen::Vector2d& q) {
    const auto& p = polygon.points;
    bool in = false;
    for (std::size_t i = 0, j = p.size() - 1; i < p.size(); j = i++) {
        if ((p[i].y() > q.y()) != (p[j].y() > q.y())) {
            const double x =
                p[j].x() + (q.y() - p[j].y()) * (p[i].x() - p[j].x()) / (p[i].y() - p[j].y());
            if (q.x() < x) in = !in;
        }
    }
    return in;
}

}  // namespace

bool contains(const Region2& region, const Eigen::Vector2d& point) {
    if (region.outer.points.size() < 3 || !inside(region.outer, point)) return false;
    for (const auto& h : region.holes)
        if (h.points.size() >= 3 && inside(h, point)) return false;
    return true;
}

std::vector<std::pair<double, double>> inside_intervals(const Region2& region, int coord,
                                                        double value) {
    const int other = 1 - coord;
    std::vector<double> xs;
    auto cross = [&](const Polygon2& loop) {
        const auto& p = loop.points;
        if (p.size() < 3) return;
        for (std::size_t i = 0, j = p.size() - 1; i < p.size(); j = i++) {
            if ((p[i][coord] > value) == (p[j][coord] > value)) continue;
            const double t = (value - p[j][coord]) / (p[i][coord] - p[j][coord]);
            xs.push_back(p[j][other] + t * (p[i][other] - p[j][other]));
        }
    };
    cross(region.outer);
    for (const auto& h : region.holes) cross(h);
    std::sort(xs.begin(), xs.end());
    std::vector<std::pair<double, double>> out;
    for (std::size_t i = 0; i + 1 < xs.size(); i += 2)
        if (xs[i + 1] > xs[i]) out.emplace_back(xs[i], xs[i + 1]);
    return out;
}

Eigen::Vector2d interior_point(const Region2& region) {
    const Eigen::AlignedBox2d box = bounds(region);
    if (box.isEmpty()) return Eigen::Vector2d::Zero();
    if (region.outer.points.size() < 3) return centroid(region);
    // The middle of the widest inside span of a horizontal line, through the centroid first (a
    // compact region's middle), else through the box's middle.
    auto widest_span = [&](double y, Eigen::Vector2d& out) {
        double best = 0.0;
        for (const auto& [x0, x1] : inside_intervals(region, 1, y))
            if (x1 - x0 > best) {
                best = x1 - x0;
                out = {0.5 * (x0 + x1), y};
            }
        return best > 0.0;
    };
    Eigen::Vector2d p = centroid(region);
    if (widest_span(p.y(), p)) return p;
    if (widest_span(box.center().y(), p)) return p;
    return centroid(region);
}

namespace {

double segment_distance(const Eigen::Vector2d& p, const Eigen::Vector2d& a,
                        const Eigen::Vector2d& b) {
    const Eigen::Vector2d e = b - a;
    const double len2 = e.squaredNorm();
    const double t = len2 > 0.0 ? std::clamp((p - a).dot(e) / len2, 0.0, 1.0) : 0.0;
    return (a + t * e - p).norm();
}

}  // namespace

Polygon2 simplify(const Polygon2& polygon, double tolerance_mm) {
    const auto& p = polygon.points;
    const std::size_t n = p.size();
    if (n <= 3 || !(tolerance_mm > 0.0)) return polygon;
    // Start at a corner (the sharpest turn), so the walk never begins inside a run to drop.
    const double cos_limit = std::cos(15.0 * kPi / 180.0);
    auto turn_cos = [&](const Eigen::Vector2d& a, const Eigen::Vector2d& b,
                        const Eigen::Vector2d& c) {
        const Eigen::Vector2d u = b - a, v = c - b;
        const double nu = u.norm(), nv = v.norm();
        return nu > 0.0 && nv > 0.0 ? u.dot(v) / (nu * nv) : 1.0;
    };
    std::size_t start = 0;
    double sharpest = 2.0;
    for (std::size_t i = 0; i < n; ++i) {
        const double c = turn_cos(p[(i + n - 1) % n], p[i], p[(i + 1) % n]);
        if (c < sharpest) {
            sharpest = c;
            start = i;
        }
    }
    Polygon2 out;
    out.points.push_back(p[start]);
    std::size_t run_begin = 1;  // first dropped point of the current run, as an offset from start
    for (std::size_t k = 1; k < n; ++k) {
        const Eigen::Vector2d& cur = p[(start + k) % n];
        const Eigen::Vector2d& next = p[(start + k + 1) % n];
        bool drop = turn_cos(out.points.back(), cur, next) >= cos_limit;
        for (std::size_t j = run_begin; drop && j <= k; ++j)
            drop = segment_distance(p[(start + j) % n], out.points.back(), next) <= tolerance_mm;
        if (!drop) {
            out.points.push_back(cur);
            run_begin = k + 1;
        }
    }
    if (out.points.size() < 3) return polygon;
    return out;
}

Region2 simplify(const Region2& region, double tolerance_mm) {
    Region2 out{simplify(region.outer, tolerance_mm), {}};
    for (const auto& h : region.holes) out.holes.push_back(simplify(h, tolerance_mm));
    return out;
}

Regions2 regions_from_loops(std::vector<Polygon2> loops, double min_area_mm2) {
    struct Outer {
        std::size_t loop;
        double area;
        Eigen::AlignedBox2d box;
    };
    std::vector<Outer> outers;
    std::vector<std::size_t> holes;
    std::vector<double> areas(loops.size());
    for (std::size_t i = 0; i < loops.size(); ++i) {
        areas[i] = signed_area(loops[i]);
        if (std::abs(areas[i]) <= min_area_mm2 || loops[i].points.size() < 3) continue;
        if (areas[i] > 0.0) {
            Eigen::AlignedBox2d box;
            for (const auto& p : loops[i].points) box.extend(p);
            outers.push_back({i, areas[i], box});
        } else {
            holes.push_back(i);
        }
    }
    // Smallest outer first, so the first one containing a hole is the innermost.
    std::sort(outers.begin(), outers.end(),
              [](const Outer& a, const Outer& b) { return a.area < b.area; });
    Regions2 regions(outers.size());
    for (std::size_t k = 0; k < outers.size(); ++k)
        regions[k].outer = std::move(loops[outers[k].loop]);
    for (std::size_t h : holes) {
        const Eigen::Vector2d probe = loops[h].points.front();
        for (std::size_t k = 0; k < outers.size(); ++k) {
            // A hole cannot be bigger than its outer loop, nor stick out of its box.
            if (-areas[h] > outers[k].area || !outers[k].box.contains(probe)) continue;
            if (inside(regions[k].outer, probe)) {
                regions[k].holes.push_back(std::move(loops[h]));
                break;
            }
        }
    }
    std::reverse(regions.begin(), regions.end());  // largest first
    return regions;
}

}  // namespace mas
