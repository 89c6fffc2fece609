// Ear clipping of regions with holes and the prisms drawn from them (Triangulate.hpp).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>

#include "mas/Angles.hpp"
#include "mas/Mesh.hpp"
#include "mas/Triangulate.hpp"

using Eigen::Vector2d;
using Eigen::Vector3d;

namespace {

mas::Polygon2 rect(double x0, double y0, double x1, double y1) {
    return {{{x0, y0}, {x1, y0}, {x1, y1}, {x0, y1}}};
}

mas::Polygon2 reversed(mas::Polygon2 p) {
    std::reverse(p.points.begin(), p.points.end());
    return p;
}

mas::Polygon2 circle(Vector2d c, double r, int n) {
    mas::Polygon2 p;
    for (int i = 0; i < n; ++i)
        p.points.push_back(
            c + r * Vector2d(std::cos(2 * mas::kPi * i / n), std::sin(2 * mas::kPi * i / n)));
    return p;
}

double cross(const Vector2d& a, const Vector2d& b, const Vector2d& c) {
    return (b - a).x() * (c - a).y() - (b - a).y() * (c - a).x();
}

// Whether segments pq and rs cross at a point inside both (touching ends do not count).
bool cross_properly(const Vector2d& p, const Vector2d& q, const Vector2d& r, const Vector2d& s) {
    const double d1 = cross(p, q, r), d2 = cross(p, q, s), d3 = cross(r, s, p), d4 = cross(r, s, q);
    return ((d1 > 0 && d2 < 0) || (d1 < 0 && d2 > 0)) && ((d3 > 0 && d4 < 0) || (d3 < 0 && d4 > 0));
}

// The region's points in triangulate()'s numbering.
std::vector<Vector2d> points_of(const mas::Region2& region) {
    std::vector<Vector2d> pts = region.outer.points;
    for (const auto& h : region.holes) pts.insert(pts.end(), h.points.begin(), h.points.end());
    return pts;
}

// Checks `triangles` as a triangulation of `region` without added points: `expected` of them
// (when >= 0), each counter-clockwise with some area and its centroid inside the region, their
// areas adding up to the region's, none of their sides crossing the region's outline.
void expect_triangulates(const mas::Region2& region,
                         const std::vector<std::array<int, 3>>& triangles, int expected) {
    const std::vector<Vector2d> pts = points_of(region);
    if (expected >= 0) {
        EXPECT_EQ(int(triangles.size()), expected);
    }
    double sum = 0.0;
    std::vector<std::pair<Vector2d, Vector2d>> outline;
    std::vector<const mas::Polygon2*> loops{&region.outer};
    for (const auto& h : region.holes) loops.push_back(&h);
    for (const auto* loop : loops)
        for (std::size_t i = 0; i < loop->points.size(); ++i)
            outline.push_back({loop->points[i], loop->points[(i + 1) % loop->points.size()]});
    for (const auto& t : triangles) {
        for (int k : t) ASSERT_TRUE(k >= 0 && k < int(pts.size()));
        const Vector2d &a = pts[std::size_t(t[0])], &b = pts[std::size_t(t[1])],
                       &c = pts[std::size_t(t[2])];
        const double twice = cross(a, b, c);
        EXPECT_GT(twice, 0.0) << "a triangle clockwise or flat";
        sum += 0.5 * twice;
        EXPECT_TRUE(mas::contains(region, (a + b + c) / 3.0)) << "a triangle outside the region";
        for (const auto& [p, q] : {std::pair{a, b}, std::pair{b, c}, std::pair{c, a}})
            for (const auto& [r, s] : outline)
                EXPECT_FALSE(cross_properly(p, q, r, s)) << "a side crossing the outline";
    }
    EXPECT_NEAR(sum, mas::area(region), 1e-9 * std::abs(mas::signed_area(region.outer)));
}

}  // namespace

TEST(Triangulate, ConvexAndConcaveOutlinesEitherWayRound) {
    const mas::Region2 square{rect(0, 0, 10, 10), {}};
    expect_triangulates(square, mas::triangulate(square), 2);
    // An L given clockwise: 6 points, 4 triangles.
    const mas::Region2 l{reversed({{{0, 0}, {20, 0}, {20, 5}, {5, 5}, {5, 30}, {0, 30}}}), {}};
    expect_triangulates(l, mas::triangulate(l), 4);
    // A comb of ten teeth: 4 + 4 x 10 points, every tooth's inner corners reflex.
    mas::Polygon2 comb{{{0, 0}, {100, 0}, {100, 10}}};
    for (int k = 9; k >= 0; --k)
        for (const Vector2d& q : {Vector2d(10 * k + 8, 10), Vector2d(10 * k + 8, 40),
                                  Vector2d(10 * k + 2, 40), Vector2d(10 * k + 2, 10)})
            comb.points.push_back(q);
    comb.points.push_back({0, 10});
    const mas::Region2 c{comb, {}};
    expect_triangulates(c, mas::triangulate(c), int(comb.points.size()) - 2);
}

TEST(Triangulate, HolesAreJoinedToTheOutlineAndLeftUncovered) {
    // One hole, given counter-clockwise: 8 points, 1 hole, 8 triangles.
    const mas::Region2 one{rect(0, 0, 10, 10), {rect(4, 4, 6, 6)}};
    expect_triangulates(one, mas::triangulate(one), 8);
    // Three holes in a row, two with their right sides at the same x: a later hole joins an
    // earlier one's ring.
    const mas::Region2 three{rect(0, 0, 40, 10),
                             {reversed(rect(2, 2, 8, 8)), rect(12, 2, 20, 4),
                              reversed(rect(14, 6, 20, 8)), circle({30, 5}, 3, 24)}};
    const int n = 4 + 4 + 4 + 4 + 24;
    expect_triangulates(three, mas::triangulate(three), n + 2 * 4 - 2);
    // A ring: a circle of 200 points round an off-centre hole of 100.
    const mas::Region2 ring{circle({0, 0}, 20, 200), {circle({5, -3}, 8, 100)}};
    expect_triangulates(ring, mas::triangulate(ring), 300 + 2 - 2);
}

TEST(Triangulate, AReflexCornerHidingTheFirstOutlinePointIsBridgedToInstead) {
    // A square with a slot cut down from its top to just over the hole's right point: the ray
    // to the right from the hole meets the right side, whose top end the slot hides.
    const mas::Region2 r{
        {{{0, 0}, {40, 0}, {40, 40}, {22, 40}, {22, 10.5}, {21, 10.5}, {21, 40}, {0, 40}}},
        {rect(2, 8, 6, 10)}};
    expect_triangulates(r, mas::triangulate(r), 8 + 4 + 2 - 2);
}

TEST(Triangulate, RepeatedPointsCountOnceAndDegenerateLoopsAddNothing) {
    const mas::Region2 repeated{{{{0, 0}, {0, 0}, {10, 0}, {10, 10}, {10, 10}, {0, 10}, {0, 0}}},
                                {}};
    const auto t = mas::triangulate(repeated);
    expect_triangulates(repeated, t, 2);
    for (const auto& tri : t)
        for (int k : tri) EXPECT_TRUE(k == 0 || k == 2 || k == 3 || k == 5) << k;
    EXPECT_TRUE(mas::triangulate(mas::Region2{{{{0, 0}, {1, 1}}}, {}}).empty());
    EXPECT_TRUE(mas::triangulate(mas::Region2{{{{0, 0}, {1, 1}, {2, 2}, {3, 3}}}, {}}).empty());
    EXPECT_TRUE(mas::triangulate(mas::Region2{}).empty());
    // A flat hole is no hole: the square's two triangles.
    const mas::Region2 flat_hole{rect(0, 0, 10, 10), {{{{2, 2}, {4, 4}, {6, 6}}}}};
    expect_triangulates({rect(0, 0, 10, 10), {}}, mas::triangulate(flat_hole), 2);
    // Points along a side: covered all the same.
    const mas::Region2 sides{{{{0, 0}, {5, 0}, {10, 0}, {10, 5}, {10, 10}, {0, 10}}}, {}};
    expect_triangulates(sides, mas::triangulate(sides), 4);
}

TEST(Triangulate, RandomStarsWithHoles) {
    // Star-shaped outlines of 5 to 120 points at radii 10 to 30 round the origin, with up to
    // four round holes of 6 to 40 points inside radius 10 (apart from each other).
    std::mt19937 rng(7);
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    for (int trial = 0; trial < 300; ++trial) {
        mas::Region2 region;
        const int n = 5 + int(unit(rng) * 116);
        for (int i = 0; i < n; ++i) {
            const double a = 2 * mas::kPi * (i + 0.8 * unit(rng)) / n;
            const double r = 10 + 20 * unit(rng);
            region.outer.points.push_back(r * Vector2d(std::cos(a), std::sin(a)));
        }
        const int holes = int(unit(rng) * 5);
        std::vector<std::pair<Vector2d, double>> placed;
        for (int h = 0; h < holes; ++h) {
            const Vector2d c(-6 + 12 * unit(rng), -6 + 12 * unit(rng));
            const double r = 0.5 + 2.0 * unit(rng);
            if (c.norm() + r > 9.5) continue;
            bool apart = true;
            for (const auto& [pc, pr] : placed) apart = apart && (c - pc).norm() > r + pr + 0.1;
            if (!apart) continue;
            placed.push_back({c, r});
            region.holes.push_back(circle(c, r, 6 + int(unit(rng) * 35)));
        }
        int points = n;
        for (const auto& h : region.holes) points += int(h.points.size());
        SCOPED_TRACE("trial " + std::to_string(trial));
        expect_triangulates(region, mas::triangulate(region),
                            points + 2 * int(region.holes.size()) - 2);
    }
}

TEST(Triangulate, CrossingLoopsStillEnd) {
    // No section has them, but the drawing must not hang on one: random loops of 4 to 60 points
    // crossing themselves, with a hole crossing the outline. At most n + 2h - 2 triangles, each
    // naming points of the region.
    std::mt19937 rng(5);
    std::uniform_real_distribution<double> coord(-10.0, 10.0);
    for (int trial = 0; trial < 200; ++trial) {
        mas::Region2 region;
        const int n = 4 + trial % 57;
        for (int i = 0; i < n; ++i) region.outer.points.push_back({coord(rng), coord(rng)});
        if (trial % 2) region.holes.push_back(rect(5, 5, 15, 6));
        const int points = n + 4 * int(region.holes.size());
        const auto triangles = mas::triangulate(region);
        EXPECT_LE(int(triangles.size()), points + 2 * int(region.holes.size()) - 2);
        for (const auto& t : triangles)
            for (int k : t) EXPECT_TRUE(k >= 0 && k < points);
    }
    // Nor on points no section has: not finite, or far beyond the others.
    const double nan = std::numeric_limits<double>::quiet_NaN();
    for (const Vector2d& odd : {Vector2d(nan, 1), Vector2d(1e300, -1e300)}) {
        mas::Region2 region{{{{0, 0}, {10, 0}, odd, {10, 10}, {0, 10}}}, {rect(2, 2, 4, 4)}};
        EXPECT_LE(mas::triangulate(region).size(), 9u);
    }
}

TEST(Triangulate, RandomPlatesWithHolesOnAGrid) {
    // Plates perforated by up to 12 square-cornered holes and triangles with corners on a 1 mm
    // grid: rays from one hole run along other holes' sides and through their corners, and
    // through the ends of bridges already made.
    std::mt19937 rng(11);
    std::uniform_int_distribution<int> coord(1, 38), size(1, 8), kind(0, 2);
    for (int trial = 0; trial < 300; ++trial) {
        mas::Region2 region{rect(0, 0, 40, 40), {}};
        std::vector<Eigen::AlignedBox2d> taken;
        const int tries = 1 + trial % 12;
        for (int h = 0; h < tries; ++h) {
            const int x = coord(rng), y = coord(rng), w = size(rng), t = size(rng);
            if (x + w > 39 || y + t > 39) continue;
            const Eigen::AlignedBox2d box(Vector2d(x, y), Vector2d(x + w, y + t));
            bool apart = true;
            for (const auto& b : taken)
                apart = apart && !b.intersects(Eigen::AlignedBox2d(box.min() - Vector2d(1, 1),
                                                                   box.max() + Vector2d(1, 1)));
            if (!apart) continue;
            taken.push_back(box);
            const int k = kind(rng);
            if (k == 0) {
                region.holes.push_back(rect(x, y, x + w, y + t));
            } else {  // a right triangle, its right angle at one of the box's corners
                const Vector2d a(x, y), b(x + w, y), c(x + w, y + t), d(x, y + t);
                region.holes.push_back(k == 1 ? mas::Polygon2{{a, b, d}}
                                              : mas::Polygon2{{b, c, d}});
            }
        }
        int points = 4;
        for (const auto& h : region.holes) points += int(h.points.size());
        SCOPED_TRACE("trial " + std::to_string(trial));
        expect_triangulates(region, mas::triangulate(region),
                            points + 2 * int(region.holes.size()) - 2);
    }
}

TEST(Triangulate, PrismMeshIsClosedAndHoldsTheRegionsTimesTheDepth) {
    // An L with a hole and a square beside it, on a plane tilted 30 degrees, 1.5 deep.
    const mas::Regions2 regions{
        {reversed({{{0, 0}, {20, 0}, {20, 5}, {5, 5}, {5, 30}, {0, 30}}}), {rect(1, 10, 4, 20)}},
        {rect(30, 0, 40, 10), {}}};
    const Vector3d normal(0.0, -std::sin(mas::kPi / 6), std::cos(mas::kPi / 6));
    const mas::Plane plane{Vector3d(3, -2, 7), normal};
    const double depth = 1.5;
    const mas::TriangleMesh m = mas::prism_mesh(regions, plane, depth);
    const mas::MeshReport report = mas::check_mesh(m);
    EXPECT_TRUE(report.closed()) << report.boundary_edges << " boundary, "
                                 << report.non_manifold_edges << " non-manifold, "
                                 << report.inconsistent_edges << " inconsistent edges";
    EXPECT_EQ(report.degenerate_triangles, 0u);
    EXPECT_NEAR(report.volume_mm3, mas::area(regions) * depth, 1e-9 * mas::area(regions) * depth);
    EXPECT_NEAR(mas::area(regions), 20 * 5 + 5 * 25 - 3 * 10 + 100, 1e-12);
    // Every vertex on the plane or depth below it; the top's in the order of the region's points.
    const std::size_t top = regions[0].outer.points.size() + regions[0].holes[0].points.size();
    ASSERT_EQ(m.vertices.size(), 2 * top + 2 * 4);
    for (std::size_t i = 0; i < m.vertices.size(); ++i) {
        const double h = plane.signed_distance(m.vertices[i]);
        const bool upper = i < top || (i >= 2 * top && i < 2 * top + 4);
        EXPECT_NEAR(h, upper ? 0.0 : -depth, 1e-12) << i;
    }
    const mas::PlaneFrame frame(normal);
    EXPECT_LT((frame.to_2d(m.vertices[1]) - regions[0].outer.points[1]).norm(), 1e-12);
    // Nothing for nothing.
    EXPECT_TRUE(mas::prism_mesh({mas::Region2{}}, plane, depth).empty());
}
