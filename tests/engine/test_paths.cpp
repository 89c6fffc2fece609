#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <iostream>
#include <set>

#include "mas/Angles.hpp"
#include "mas/Error.hpp"
#include "mas/Paths.hpp"

namespace {

using mas::kPi;

mas::Polygon2 rect(double x0, double y0, double x1, double y1) {
    return {{{x0, y0}, {x1, y0}, {x1, y1}, {x0, y1}}};
}

mas::Polygon2 reversed(mas::Polygon2 p) {
    std::reverse(p.points.begin(), p.points.end());
    return p;
}

mas::Polygon2 disc(double cx, double cy, double r, int n = 128) {
    mas::Polygon2 p;
    for (int i = 0; i < n; ++i) {
        const double a = 2.0 * kPi * i / n;
        p.points.emplace_back(cx + r * std::cos(a), cy + r * std::sin(a));
    }
    return p;
}

mas::Regions2 one(const mas::Polygon2& outer, std::vector<mas::Polygon2> holes = {}) {
    for (auto& h : holes) h = reversed(h);
    return {mas::Region2{outer, holes}};
}

mas::Regions2 rectangle() { return one(rect(0, 0, 20, 10)); }
mas::Regions2 plate_with_hole() { return one(rect(0, 0, 30, 30), {rect(10, 10, 20, 20)}); }
mas::Regions2 l_shape() { return one({{{0, 0}, {20, 0}, {20, 8}, {8, 8}, {8, 20}, {0, 20}}}); }
mas::Regions2 round_plate() { return one(disc(0, 0, 10)); }

mas::PathParams exact_params() {  // w = 1, no overlap, one contour
    mas::PathParams p;
    p.bead_width_mm = 1.0;
    p.overlap = 0.0;
    p.contour_count = 1;
    return p;
}

std::vector<const mas::Path2*> of_kind(const mas::LayerPaths2& lp, mas::Path2::Kind kind) {
    std::vector<const mas::Path2*> out;
    for (const auto& p : lp.paths)
        if (p.kind == kind) out.push_back(&p);
    return out;
}

double signed_area(const mas::Path2& p) { return mas::signed_area(mas::Polygon2{p.points}); }

double length(const mas::Path2& p) {
    double len = 0.0;
    for (std::size_t i = 1; i < p.points.size(); ++i) len += (p.points[i] - p.points[i - 1]).norm();
    if (p.closed && p.points.size() > 2) len += (p.points.front() - p.points.back()).norm();
    return len;
}

bool near(const Eigen::Vector2d& a, const Eigen::Vector2d& b, double tol = 1e-9) {
    return (a - b).norm() <= tol;
}

// Every path, sampled along its segments every w/8, stays inside the regions grown by w/2 (plus
// the arc tolerance of the rounded growth): no bead centre leaves the part by more than half a
// bead, so no bead crosses a hole or the outline.
void expect_within_half_bead(const mas::Regions2& regions, const mas::LayerPaths2& lp,
                             const mas::PathParams& params) {
    const double w = params.bead_width_mm, tol = params.arc_tolerance_mm;
    const auto grown = mas::offset(regions, 0.5 * w + tol, mas::JoinType::Round, tol);
    auto inside = [&](const Eigen::Vector2d& q) {
        return std::any_of(grown.begin(), grown.end(),
                           [&](const mas::Region2& r) { return mas::contains(r, q); });
    };
    for (const auto& p : lp.paths) {
        const std::size_t n = p.points.size();
        const std::size_t segments = p.closed ? n : n - 1;
        for (std::size_t i = 0; i < segments; ++i) {
            const Eigen::Vector2d a = p.points[i], b = p.points[(i + 1) % n];
            const int steps = std::max(1, int(std::ceil((b - a).norm() / (w / 8))));
            for (int k = 0; k <= steps; ++k) {
                const Eigen::Vector2d q = a + (b - a) * (double(k) / steps);
                ASSERT_TRUE(inside(q))
                    << mas::to_string(p.kind) << " path of region " << p.region
                    << " leaves the region at (" << q.x() << ", " << q.y() << ")";
            }
        }
    }
}

}  // namespace

TEST(Paths, RectangleContourIsTheRectangleInsetByHalfABead) {
    const auto lp = mas::plan_layer_paths(rectangle(), exact_params(), 0, {0, 0});
    const auto contours = of_kind(lp, mas::Path2::Kind::Contour);
    ASSERT_EQ(contours.size(), 1u);
    const mas::Path2& c = *contours[0];
    EXPECT_TRUE(c.closed);
    EXPECT_EQ(c.region, 0);
    ASSERT_EQ(c.points.size(), 4u);  // mitred inset: still a rectangle, no extra corner points
    EXPECT_DOUBLE_EQ(signed_area(c), 19.0 * 9.0);  // counter-clockwise, 19 x 9
    for (const Eigen::Vector2d& corner : {Eigen::Vector2d(0.5, 0.5), Eigen::Vector2d(19.5, 0.5),
                                          Eigen::Vector2d(19.5, 9.5), Eigen::Vector2d(0.5, 9.5)})
        EXPECT_TRUE(std::any_of(c.points.begin(), c.points.end(),
                                [&](const Eigen::Vector2d& p) { return near(p, corner); }))
            << "corner " << corner.transpose();
    EXPECT_TRUE(lp.unfilled.empty());
    EXPECT_TRUE(lp.centre_line_regions.empty());
    EXPECT_EQ(lp.uncovered_area_mm2, -1.0);  // not measured
}

TEST(Paths, RasterLinesAreOneStepApartAndTurnBetweenLayers) {
    // Infill bead centres fill the rectangle inset by w/2 + 1 x s = 1.5: [1.5, 18.5] x [1.5, 8.5],
    // which takes lines exactly s = 1 apart, the outer ones on its edges. Their ends run a quarter
    // bead further, into the contour's bead: [1.25, 18.75] and [1.25, 8.75].
    const mas::PathParams params = exact_params();
    const double edge = 0.1 * params.arc_tolerance_mm + 1e-9;  // the clip area is grown by this
    const double reach = 0.25 * params.bead_width_mm;
    const auto layer0 = mas::plan_layer_paths(rectangle(), params, 0, {0, 0});
    const auto lines0 = of_kind(layer0, mas::Path2::Kind::Infill);
    ASSERT_EQ(lines0.size(), 8u);  // y = 1.5, 2.5, ..., 8.5
    std::set<long> ys;
    for (const mas::Path2* p : lines0) {
        EXPECT_FALSE(p->closed);
        ASSERT_GE(p->points.size(), 2u);
        const Eigen::Vector2d a = p->points.front(), b = p->points.back();
        EXPECT_NEAR(a.y(), b.y(), 1e-9);  // angle 0: along u
        EXPECT_NEAR(std::min(a.x(), b.x()), 1.5 - reach, edge);
        EXPECT_NEAR(std::max(a.x(), b.x()), 18.5 + reach, edge);
        ys.insert(std::lround(a.y() * 10));
    }
    EXPECT_EQ(ys, (std::set<long>{15, 25, 35, 45, 55, 65, 75, 85}));

    const auto layer1 = mas::plan_layer_paths(rectangle(), params, 1, {0, 0});
    const auto lines1 = of_kind(layer1, mas::Path2::Kind::Infill);
    ASSERT_EQ(lines1.size(), 18u);  // x = 1.5, ..., 18.5
    std::set<long> xs;
    for (const mas::Path2* p : lines1) {
        const Eigen::Vector2d a = p->points.front(), b = p->points.back();
        EXPECT_NEAR(a.x(), b.x(), 1e-9);  // angle 90: along v
        EXPECT_NEAR(std::min(a.y(), b.y()), 1.5 - reach, edge);
        EXPECT_NEAR(std::max(a.y(), b.y()), 8.5 + reach, edge);
        xs.insert(std::lround(a.x() * 10));
    }
    ASSERT_EQ(xs.size(), 18u);
    EXPECT_EQ(*xs.begin(), 15);
    EXPECT_EQ(*xs.rbegin(), 185);

    // Layer 2 is back at 0 degrees.
    const auto lines2 =
        of_kind(mas::plan_layer_paths(rectangle(), params, 2, {0, 0}), mas::Path2::Kind::Infill);
    ASSERT_EQ(lines2.size(), 8u);
    EXPECT_NEAR(lines2[0]->points.front().y(), lines2[0]->points.back().y(), 1e-9);
}

TEST(Paths, RasterRunsBackAndForthWithOneStepBetweenLines) {
    // Nearest-next with reversible open paths: after a line the head steps s to the next one.
    const mas::PathParams params = exact_params();
    const auto lp = mas::plan_layer_paths(rectangle(), params, 0, {0, 0});
    ASSERT_EQ(lp.paths.size(), 9u);
    EXPECT_EQ(lp.paths[0].kind, mas::Path2::Kind::Contour);  // contours before infill
    for (std::size_t i = 2; i < lp.paths.size(); ++i) {
        EXPECT_EQ(lp.paths[i].kind, mas::Path2::Kind::Infill);
        EXPECT_NEAR((lp.paths[i].points.front() - lp.paths[i - 1].points.back()).norm(), 1.0, 1e-9);
    }
}

TEST(Paths, HoleContourRunsClockwiseAroundTheHole) {
    mas::PathParams params;
    params.bead_width_mm = 1.0;
    params.contour_count = 2;
    // Layer 1: seams at the corners towards 137.5 degrees, (0.5, 29.5) and (9.5, 20.5).
    const auto lp = mas::plan_layer_paths(plate_with_hole(), params, 1, {0, 30});
    const auto contours = of_kind(lp, mas::Path2::Kind::Contour);
    ASSERT_EQ(contours.size(), 4u);  // outer and hole, two levels each
    EXPECT_TRUE(near(contours[0]->points.front(), {0.5, 29.5}));
    EXPECT_TRUE(near(contours[2]->points.front(), {9.5, 20.5}));
    // Outline by outline, each contour right after the one around it: from (0, 30) the outer
    // contour 0 (29 x 29, CCW), its contour 1 (s = 0.85 further in), then the hole's (CW: the hole
    // grown by w/2 = 11 x 11, mitred, then by another 0.85).
    EXPECT_DOUBLE_EQ(signed_area(*contours[0]), 29.0 * 29.0);
    EXPECT_NEAR(signed_area(*contours[1]), 27.3 * 27.3, 1e-6);
    EXPECT_DOUBLE_EQ(signed_area(*contours[2]), -11.0 * 11.0);
    EXPECT_NEAR(signed_area(*contours[3]), -12.7 * 12.7, 1e-6);
    const mas::Path2& hole = *contours[2];
    ASSERT_EQ(hole.points.size(), 4u);
    for (const auto& p : hole.points)
        EXPECT_TRUE(std::abs(std::abs(p.x() - 15.0) - 5.5) < 1e-9 &&
                    std::abs(std::abs(p.y() - 15.0) - 5.5) < 1e-9)
            << p.transpose();
    expect_within_half_bead(plate_with_hole(), lp, params);  // nothing crosses the hole
}

TEST(Paths, RasterRunsAlongEdgesParallelToIt) {
    // Plate with hole, two contours, overlap 0.15: infill bead centres in [2.2, 27.8]^2 minus the
    // hole grown to [7.8, 22.2]^2. Lines lie along the hole's top and bottom edges (no band is
    // left beside them), the outermost ones overlap w / 2 = 0.075 inside, none more than s apart.
    mas::PathParams params;
    params.measure_coverage = true;
    const auto lp = mas::plan_layer_paths(plate_with_hole(), params, 0, {0, 0});
    std::set<long> ys;  // in 1e-5 mm
    for (const mas::Path2* p : of_kind(lp, mas::Path2::Kind::Infill)) {
        EXPECT_NEAR(p->points.front().y(), p->points.back().y(), 1e-9);
        ys.insert(std::lround(p->points.front().y() * 1e5));
    }
    for (long y : {227500L, 780000L, 2220000L, 2772500L}) EXPECT_EQ(ys.count(y), 1u) << y;
    EXPECT_EQ(*ys.begin(), 227500L);
    EXPECT_EQ(*ys.rbegin(), 2772500L);
    long previous = *ys.begin();
    for (long y : ys) {
        EXPECT_LE(y - previous, 85000L);
        previous = y;
    }
    EXPECT_TRUE(of_kind(lp, mas::Path2::Kind::CentreLine).empty());  // no gap to fill
    EXPECT_LT(lp.uncovered_area_mm2, 0.01 * mas::area(plate_with_hole()));
}

TEST(Paths, OutlineOrientationAsGivenDoesNotMatter) {
    // Outer stored clockwise and hole counter-clockwise: read by their nesting all the same.
    const mas::Regions2 regions{mas::Region2{reversed(rect(0, 0, 30, 30)), {rect(10, 10, 20, 20)}}};
    const auto lp = mas::plan_layer_paths(regions, exact_params(), 0, {0, 0});
    const auto contours = of_kind(lp, mas::Path2::Kind::Contour);
    ASSERT_EQ(contours.size(), 2u);
    double areas[2] = {signed_area(*contours[0]), signed_area(*contours[1])};
    std::sort(areas, areas + 2);
    EXPECT_DOUBLE_EQ(areas[0], -11.0 * 11.0);
    EXPECT_DOUBLE_EQ(areas[1], 29.0 * 29.0);
}

TEST(Paths, NoRegionsGiveNoPathsAndBadCoordinatesThrow) {
    mas::PathParams params;
    params.measure_coverage = true;
    const auto lp = mas::plan_layer_paths({}, params, 0, {0, 0});
    EXPECT_TRUE(lp.paths.empty());
    EXPECT_EQ(lp.deposit_length_mm, 0.0);
    EXPECT_EQ(lp.travel_length_mm, 0.0);
    EXPECT_EQ(lp.uncovered_area_mm2, 0.0);
    // A degenerate outline (two points, or all on a line) has no area and gets nothing.
    const mas::Regions2 degenerate{mas::Region2{{{{0, 0}, {5, 0}}}, {}},
                                   mas::Region2{{{{0, 0}, {5, 0}, {10, 0}}}, {}}};
    const auto none = mas::plan_layer_paths(degenerate, params, 0, {0, 0});
    EXPECT_TRUE(none.paths.empty());
    EXPECT_TRUE(none.unfilled.empty());
    EXPECT_NEAR(none.uncovered_area_mm2, 0.0, 1e-12);
    auto bad = rectangle();
    bad[0].outer.points[1].x() = std::nan("");
    try {
        mas::plan_layer_paths(bad, params, 0, {0, 0});
        ADD_FAILURE() << "no error";
    } catch (const mas::Error& e) {
        EXPECT_EQ(e.code(), mas::ErrorCode::NonFiniteCoordinate);
    }
    EXPECT_THROW(mas::plan_layer_paths(rectangle(), params, 0, {INFINITY, 0}), mas::Error);
}

TEST(Paths, EveryPathStaysWithinHalfABeadOfItsRegion) {
    for (const auto& regions : {rectangle(), plate_with_hole(), l_shape(), round_plate()})
        for (auto pattern :
             {mas::InfillPattern::Raster, mas::InfillPattern::Contour, mas::InfillPattern::None})
            for (int layer = 0; layer < 3; ++layer) {
                mas::PathParams params;
                params.infill = pattern;
                params.raster_angle_step_deg = 67.0;  // slanted rasters too
                const auto lp = mas::plan_layer_paths(regions, params, layer, {-5, -5});
                EXPECT_FALSE(lp.paths.empty());
                expect_within_half_bead(regions, lp, params);
            }
}

TEST(Paths, DefaultOverlapLeavesUnderOnePercentUncovered) {
    struct Case {
        const char* name;
        mas::Regions2 regions;
    };
    for (const auto& c :
         {Case{"rectangle", rectangle()}, Case{"plate with hole", plate_with_hole()},
          Case{"L shape", l_shape()}, Case{"disc", round_plate()}})
        for (auto pattern : {mas::InfillPattern::Raster, mas::InfillPattern::Contour})
            for (int layer = 0; layer < 2; ++layer) {
                mas::PathParams params;  // w = 1, overlap 0.15, two contours
                params.infill = pattern;
                params.measure_coverage = true;
                const auto lp = mas::plan_layer_paths(c.regions, params, layer, {0, 0});
                const double a = mas::area(c.regions);
                EXPECT_GE(lp.uncovered_area_mm2, 0.0);
                EXPECT_LT(lp.uncovered_area_mm2, 0.01 * a)
                    << c.name << ", " << mas::to_string(pattern) << " infill, layer " << layer;
                EXPECT_TRUE(lp.unfilled.empty()) << c.name;
            }
}

TEST(Paths, NarrowStripGetsOneCentreLineAlongItsMiddle) {
    // 10 x 0.6 strip, w = 1: the medial axis runs y = 0.3 from x = 0.3 to 9.7; trimmed by
    // w/2 - 0.3 at both ends so that the bead's round ends reach the strip's ends: 10 - w long.
    mas::PathParams params;
    params.bead_width_mm = 1.0;
    params.measure_coverage = true;
    const auto regions = one(rect(0, 0, 10, 0.6));
    const auto lp = mas::plan_layer_paths(regions, params, 0, {0, 0});
    ASSERT_EQ(lp.paths.size(), 1u);
    const mas::Path2& p = lp.paths[0];
    EXPECT_EQ(p.kind, mas::Path2::Kind::CentreLine);
    EXPECT_FALSE(p.closed);
    EXPECT_NEAR(length(p), 9.0, 1e-6);
    for (const auto& q : p.points) EXPECT_NEAR(q.y(), 0.3, 1e-9);
    EXPECT_NEAR(p.points.front().x(), 0.5, 1e-6);  // nearest end first from (0, 0)
    EXPECT_EQ(lp.centre_line_regions, std::vector<int>{0});
    EXPECT_TRUE(lp.unfilled.empty());
    EXPECT_NEAR(lp.deposit_length_mm, 9.0, 1e-6);
    EXPECT_NEAR(lp.travel_length_mm, std::hypot(0.5, 0.3), 1e-6);
    // The bead covers the strip but its four corners: (0.5^2 + 0.3^2)^0.5 > w/2 from the ends.
    EXPECT_LT(lp.uncovered_area_mm2, 0.02 * 6.0);
}

TEST(Paths, SpeckTooSmallForAPassIsReportedUnfilled) {
    auto regions = rectangle();
    regions.push_back(one(rect(30, 5, 30.1, 5.1))[0]);
    const auto lp = mas::plan_layer_paths(regions, exact_params(), 0, {0, 0});
    ASSERT_EQ(lp.unfilled.size(), 1u);
    EXPECT_EQ(lp.unfilled[0].region, 1);
    EXPECT_NEAR(lp.unfilled[0].area_mm2, 0.01, 1e-9);
    EXPECT_NEAR(lp.unfilled[0].centroid.x(), 30.05, 1e-9);
    EXPECT_NEAR(lp.unfilled[0].centroid.y(), 5.05, 1e-9);
    EXPECT_TRUE(lp.centre_line_regions.empty());
    for (const auto& p : lp.paths) EXPECT_EQ(p.region, 0);
}

TEST(Paths, ThinTailOfAWideRegionGetsACentreLine) {
    // A 10 x 10 square with a 0.6 mm wide tail 8 mm long on its right: the contour cannot enter
    // the tail, which gets its own centre-line pass instead of being lost.
    const mas::Regions2 regions =
        one({{{0, 0}, {10, 0}, {10, 4.7}, {18, 4.7}, {18, 5.3}, {10, 5.3}, {10, 10}, {0, 10}}});
    mas::PathParams params;
    params.measure_coverage = true;
    const auto lp = mas::plan_layer_paths(regions, params, 0, {0, 0});
    const auto lines = of_kind(lp, mas::Path2::Kind::CentreLine);
    ASSERT_EQ(lines.size(), 1u);
    EXPECT_EQ(lp.centre_line_regions, std::vector<int>{0});
    for (const auto& q : lines[0]->points) {
        EXPECT_NEAR(q.y(), 5.0, 1e-6);
        EXPECT_GT(q.x(), 10.0);
    }
    // Its far end stops w/2 short of the tail's end.
    double far = 0.0;
    for (const auto& q : lines[0]->points) far = std::max(far, q.x());
    EXPECT_NEAR(far, 17.5, 1e-6);
    EXPECT_GT(length(*lines[0]), 6.0);
    EXPECT_LT(lp.uncovered_area_mm2, 0.01 * mas::area(regions));
    expect_within_half_bead(regions, lp, params);
}

TEST(Paths, ThinStripLeftInsideTheContoursGetsACentreLine) {
    // 20 x 2.5, w = 1, overlap 0.15, two contours: contour 0 at inset 0.5; the room of level 1
    // (inset 0.85) is 0.8 wide, too narrow for contour 1, so a centre line runs along y = 1.25
    // from x = 1.25 to 18.75, trimmed by w/2 - 0.4 at each end.
    mas::PathParams params;
    const auto lp = mas::plan_layer_paths(one(rect(0, 0, 20, 2.5)), params, 0, {0, 0});
    ASSERT_EQ(of_kind(lp, mas::Path2::Kind::Contour).size(), 1u);
    const auto lines = of_kind(lp, mas::Path2::Kind::CentreLine);
    ASSERT_EQ(lines.size(), 1u);
    EXPECT_NEAR(length(*lines[0]), 17.3, 1e-6);
    for (const auto& q : lines[0]->points) EXPECT_NEAR(q.y(), 1.25, 1e-9);
    EXPECT_TRUE(of_kind(lp, mas::Path2::Kind::Infill).empty());
    EXPECT_EQ(lp.paths.back().kind, mas::Path2::Kind::CentreLine);  // after the contour
}

TEST(Paths, NarrowRingGetsAClosedCentreLine) {
    // A 0.6 mm wall around a 10 mm hole: its middle is a closed loop of radius 5.3.
    const auto regions = one(disc(0, 0, 5.6), {disc(0, 0, 5.0)});
    mas::PathParams params;
    const auto lp = mas::plan_layer_paths(regions, params, 0, {0, 0});
    ASSERT_EQ(lp.paths.size(), 1u);
    const mas::Path2& p = lp.paths[0];
    EXPECT_EQ(p.kind, mas::Path2::Kind::CentreLine);
    EXPECT_TRUE(p.closed);
    // Between the 128-gons' in- and circumradii (a sagitta of 5.6 (1 - cos(pi / 128)) apart).
    const double sagitta = 5.6 * (1 - std::cos(kPi / 128));
    for (const auto& q : p.points) EXPECT_NEAR(q.norm(), 5.3, sagitta + 1e-6);
    EXPECT_NEAR(length(p), 2 * kPi * 5.3, 0.01);
    EXPECT_EQ(lp.centre_line_regions, std::vector<int>{0});
}

TEST(Paths, SeamsMoveFromLayerToLayer) {
    // Square 10 x 10: contour 0 is the square inset by 0.5, corners at 45, 135, 225, 315 degrees
    // from its centre. The seam is the corner closest to the golden-angle direction of the layer:
    // 137.5 -> 135, 275 -> 315, 52.5 -> 45 degrees (layer 0, at 0 degrees, ties 45 and 315).
    const auto regions = one(rect(0, 0, 10, 10));
    std::vector<Eigen::Vector2d> seams;
    for (int layer = 0; layer < 4; ++layer) {
        const auto lp = mas::plan_layer_paths(regions, mas::PathParams{}, layer, {5, 5});
        ASSERT_FALSE(lp.paths.empty());
        ASSERT_EQ(lp.paths[0].kind, mas::Path2::Kind::Contour);
        seams.push_back(lp.paths[0].points.front());
    }
    const Eigen::Vector2d c(5, 5);
    EXPECT_TRUE(near(seams[1], c + Eigen::Vector2d(-4.5, 4.5)));
    EXPECT_TRUE(near(seams[2], c + Eigen::Vector2d(4.5, -4.5)));
    EXPECT_TRUE(near(seams[3], c + Eigen::Vector2d(4.5, 4.5)));
    EXPECT_TRUE(near(seams[0], c + Eigen::Vector2d(4.5, 4.5)) ||
                near(seams[0], c + Eigen::Vector2d(4.5, -4.5)));
    for (int layer = 1; layer < 4; ++layer) EXPECT_FALSE(near(seams[layer], seams[layer - 1]));
    EXPECT_NEAR(mas::seam_angle(1), 137.50776405003785 * kPi / 180, 1e-12);
    EXPECT_NEAR(mas::seam_angle(3), 3 * 137.50776405003785 * kPi / 180 - 2 * kPi, 1e-12);
}

TEST(Paths, NearestNextBeginsWithTheRegionNearTheHead) {
    mas::Regions2 regions = one(rect(0, 0, 10, 10));
    regions.push_back(one(rect(30, 0, 40, 10))[0]);
    const auto lp = mas::plan_layer_paths(regions, mas::PathParams{}, 0, {41, 5});
    ASSERT_FALSE(lp.paths.empty());
    std::size_t first_of_0 = lp.paths.size();
    for (std::size_t i = 0; i < lp.paths.size(); ++i)
        if (lp.paths[i].region == 0) {
            first_of_0 = i;
            break;
        }
    ASSERT_LT(first_of_0, lp.paths.size());
    EXPECT_GT(first_of_0, 0u);
    for (std::size_t i = 0; i < lp.paths.size(); ++i)
        EXPECT_EQ(lp.paths[i].region, i < first_of_0 ? 1 : 0) << "path " << i;
}

TEST(Paths, DepositAndTravelLengthsAddUp) {
    const Eigen::Vector2d start(-3, 4);
    const auto lp = mas::plan_layer_paths(plate_with_hole(), mas::PathParams{}, 1, start);
    double deposit = 0.0, travel = 0.0;
    Eigen::Vector2d pos = start;
    for (const auto& p : lp.paths) {
        deposit += length(p);
        travel += (p.points.front() - pos).norm();
        pos = p.closed ? p.points.front() : p.points.back();
    }
    EXPECT_NEAR(lp.deposit_length_mm, deposit, 1e-9);
    EXPECT_NEAR(lp.travel_length_mm, travel, 1e-9);
    EXPECT_GT(deposit, 0.0);
    EXPECT_NEAR(lp.travel_length_mm - (lp.paths[0].points.front() - start).norm(),
                travel - (lp.paths[0].points.front() - start).norm(), 1e-9);
}

TEST(Paths, RasterWithoutContoursFillsARectangle) {
    mas::PathParams params;
    params.contour_count = 0;
    params.measure_coverage = true;
    const auto lp = mas::plan_layer_paths(rectangle(), params, 0, {0, 0});
    EXPECT_TRUE(of_kind(lp, mas::Path2::Kind::Contour).empty());
    // Bead centres in [0.5, 19.5] x [0.5, 9.5]; without contours the outermost lines lie on its
    // edges, the others spread evenly: 9 / 0.85 -> 11 steps of 9 / 11, 12 lines.
    const auto lines = of_kind(lp, mas::Path2::Kind::Infill);
    ASSERT_EQ(lines.size(), 12u);
    std::vector<double> ys;
    for (const mas::Path2* p : lines) ys.push_back(p->points.front().y());
    std::sort(ys.begin(), ys.end());
    EXPECT_NEAR(ys.front(), 0.5, 1e-9);
    EXPECT_NEAR(ys.back(), 9.5, 1e-9);
    for (std::size_t i = 1; i < ys.size(); ++i)
        EXPECT_NEAR(ys[i] - ys[i - 1], 9.0 / 11, 1e-5);  // on the 1e-5 mm grid
    EXPECT_LT(lp.uncovered_area_mm2, 0.01 * 200.0);
}

TEST(Paths, ContourParallelInfillFillsWithNestedLoops) {
    // 10 x 10, w = 1, overlap 0.15, one contour: infill loops at insets 0.5 + 0.85 (1 + j), squares
    // of side 9 - 1.7 (1 + j) for j = 0 .. 4 (7.3, 5.6, 3.9, 2.2, 0.5).
    mas::PathParams params;
    params.contour_count = 1;
    params.infill = mas::InfillPattern::Contour;
    params.measure_coverage = true;
    const auto lp = mas::plan_layer_paths(one(rect(0, 0, 10, 10)), params, 0, {0, 0});
    const auto loops = of_kind(lp, mas::Path2::Kind::Infill);
    ASSERT_EQ(loops.size(), 5u);
    for (std::size_t j = 0; j < loops.size(); ++j) {
        EXPECT_TRUE(loops[j]->closed);
        const double side = 9.0 - 1.7 * double(j + 1);
        EXPECT_NEAR(signed_area(*loops[j]), side * side, 1e-6) << j;  // outermost first
        for (const auto& q : loops[j]->points) {
            EXPECT_NEAR(std::abs(q.x() - 5.0), side / 2, 1e-9);
            EXPECT_NEAR(std::abs(q.y() - 5.0), side / 2, 1e-9);
        }
    }
    EXPECT_LT(lp.uncovered_area_mm2, 0.01 * 100.0);
    EXPECT_TRUE(lp.unfilled.empty());
    EXPECT_TRUE(lp.centre_line_regions.empty());
}

TEST(Paths, NoInfillLeavesOnlyContours) {
    mas::PathParams params;
    params.infill = mas::InfillPattern::None;
    const auto lp = mas::plan_layer_paths(plate_with_hole(), params, 0, {0, 0});
    EXPECT_EQ(lp.paths.size(), 4u);
    for (const auto& p : lp.paths) EXPECT_EQ(p.kind, mas::Path2::Kind::Contour);
}

TEST(Paths, ValidateNamesTheBadParameter) {
    auto expect_invalid = [](const mas::PathParams& p, const std::string& name) {
        try {
            mas::validate(p);
            ADD_FAILURE() << "no error for " << name;
        } catch (const mas::Error& e) {
            EXPECT_EQ(e.code(), mas::ErrorCode::InvalidArgument);
            EXPECT_NE(std::string(e.what()).find(name), std::string::npos) << e.what();
        }
        EXPECT_THROW(mas::plan_layer_paths(rectangle(), p, 0, {0, 0}), mas::Error);
    };
    // 1e300 overflowed the Booleans' integer grid ("Coordinate outside allowed range").
    for (double w : {0.0, -1.0, std::nan(""), 1e300, 1001.0}) {
        mas::PathParams p;
        p.bead_width_mm = w;
        expect_invalid(p, "bead_width_mm");
    }
    for (double o : {1.0, -0.1}) {
        mas::PathParams p;
        p.overlap = o;
        expect_invalid(p, "overlap");
    }
    mas::PathParams p;
    p.contour_count = -1;
    expect_invalid(p, "contour_count");
    p = {};
    p.raster_angle_deg = INFINITY;
    expect_invalid(p, "raster_angle_deg");
    p = {};
    p.min_feature_mm = -1;
    expect_invalid(p, "min_feature_mm");
    p = {};
    p.arc_tolerance_mm = 0;
    expect_invalid(p, "arc_tolerance_mm");
    EXPECT_NO_THROW(mas::validate(mas::PathParams{}));
}

TEST(Paths, ABeadTooSmallForTheRegionIsRefusedUpFront) {
    const auto plate = one(rect(0, 0, 100, 100));
    mas::PathParams params;
    params.bead_width_mm = 1e-3;  // contour-parallel: ~59000 offset levels
    params.infill = mas::InfillPattern::Contour;
    EXPECT_THROW(mas::plan_layer_paths(plate, params, 0, {0, 0}), mas::Error);
    auto expect_refused = [&](const mas::PathParams& p, const std::string& words) {
        try {
            mas::plan_layer_paths(plate, p, 0, {0, 0});
            ADD_FAILURE() << "no error";
        } catch (const mas::Error& e) {
            EXPECT_EQ(e.code(), mas::ErrorCode::InvalidArgument);
            EXPECT_NE(std::string(e.what()).find(words), std::string::npos) << e.what();
        }
    };
    params.infill = mas::InfillPattern::Raster;
    // Ordering the segments of n lines takes time growing as n^2: at most 10000 lines. A 0.01 mm
    // bead at the default overlap (0.15) spaces them 0.0085 mm apart: ~11700 across 100 mm.
    params.bead_width_mm = 0.01;
    expect_refused(params, "bead_width_mm 0.01 x (1 - overlap 0.15)) is too small for a region");
    // The spacing is what counts: a 1 mm bead overlapping its neighbour all but entirely.
    params.bead_width_mm = 1.0;
    params.overlap = 0.9999;
    expect_refused(params, "(1 - overlap 0.9999)) is too small");
}

TEST(Paths, InfillPatternNamesRoundTrip) {
    for (auto pattern :
         {mas::InfillPattern::Raster, mas::InfillPattern::Contour, mas::InfillPattern::None})
        EXPECT_EQ(mas::infill_pattern_from_string(mas::to_string(pattern)), pattern);
    try {
        mas::infill_pattern_from_string("bogus");
        ADD_FAILURE() << "no error";
    } catch (const mas::Error& e) {
        EXPECT_EQ(e.code(), mas::ErrorCode::InvalidArgument);
        EXPECT_NE(std::string(e.what()).find("bogus"), std::string::npos);
    }
    EXPECT_STREQ(mas::to_string(mas::Path2::Kind::CentreLine), "centre_line");
}

TEST(Paths, LargePlateWithHolesPlansQuickly) {
    // 100 x 100 mm with five holes, default parameters: a few hundred paths. Not timed as a
    // pass/fail criterion (the machine is shared), but printed: well under 50 ms is expected.
    const auto regions =
        one(rect(0, 0, 100, 100), {rect(10, 10, 30, 30), rect(70, 10, 90, 30), disc(50, 50, 12),
                                   rect(10, 70, 30, 90), disc(80, 80, 9)});
    mas::PathParams params;
    const auto t0 = std::chrono::steady_clock::now();
    const auto lp = mas::plan_layer_paths(regions, params, 0, {0, 0});
    const double ms =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
    std::cout << "[ plan ] 100 x 100 mm, 5 holes: " << lp.paths.size() << " paths in " << ms
              << " ms\n";
    EXPECT_EQ(of_kind(lp, mas::Path2::Kind::Contour).size(), 12u);  // 6 loops x 2 contours
    EXPECT_GT(of_kind(lp, mas::Path2::Kind::Infill).size(), 100u);
    // Nearest-next keeps travel a small fraction of the deposit.
    EXPECT_LT(lp.travel_length_mm, 0.1 * lp.deposit_length_mm);
    params.measure_coverage = true;
    EXPECT_LT(mas::plan_layer_paths(regions, params, 1, {0, 0}).uncovered_area_mm2,
              0.01 * mas::area(regions));
}
