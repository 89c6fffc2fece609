// The build sequence against the nozzle (Nozzle.hpp, the paper's Eq. 10): the nozzle's shape, the
// collisions it finds, and the order it gives, on layers whose geometry makes every expectation
// exact; and on sliced parts, checked against the nozzle's own (not grown) shape.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <functional>
#include <optional>
#include <random>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "mas/Angles.hpp"
#include "mas/Error.hpp"
#include "mas/Gcode.hpp"
#include "mas/Nozzle.hpp"
#include "mas/SlicePart.hpp"
#include "test_parts.hpp"

using mas::kPi;

namespace {

using Eigen::Vector2d;
using Eigen::Vector3d;
const double kTan30 = std::tan(kPi / 6.0);

// A layer of component `c`: the rectangle with corners `a`, `b` (3-D, on a plane of normal `n`
// through them), deposited down to the plane `thickness` below; one deposit path of `path`'s
// points on it.
struct Built {
    std::vector<mas::Layer> layers;
    std::vector<mas::LayerToolpaths> paths;
};

void add_layer(Built& built, int c, const Vector3d& n, const std::vector<Vector3d>& corners,
               double thickness, const std::vector<Vector3d>& path) {
    built.layers.push_back(mas::test::flat_layer(c, n, {corners}, thickness));
    mas::LayerToolpaths t;
    t.tool_axis = n;
    mas::ToolPath p;
    p.kind = mas::ToolPath::Kind::Contour;
    p.points = path;
    p.thickness_mm.assign(path.size(), thickness);
    t.paths.push_back(p);
    built.paths.push_back(t);
}

// A horizontal square layer [x0, x1] x [y0, y1], its top at z, 1 mm thick, deposited at its centre.
void add_square(Built& built, int c, double x0, double y0, double x1, double y1, double z) {
    add_layer(built, c, Vector3d::UnitZ(), {{x0, y0, z}, {x1, y0, z}, {x1, y1, z}, {x0, y1, z}},
              1.0, {{0.5 * (x0 + x1), 0.5 * (y0 + y1), z}});
}

mas::SequenceInput input(const Built& built, std::vector<int> parent,
                         std::vector<int> start_order) {
    mas::SequenceInput in;
    in.layers = &built.layers;
    in.toolpaths = &built.paths;
    in.waits_for.assign(parent.size(), {});
    in.parent = std::move(parent);
    in.start_order = std::move(start_order);
    in.plate = {Vector3d::Zero(), Vector3d::UnitZ()};
    return in;
}

// The nozzle as the paper's: coaxial, never leaned; with the plate or without.
mas::NozzleParams coaxial(bool plate = true) {
    mas::NozzleParams p;
    p.max_lean_deg = 0.0;
    p.check_plate = plate;
    return p;
}

std::string error_of(const std::function<void()>& f) {
    try {
        f();
    } catch (const mas::Error& e) {
        return e.what();
    }
    return "";
}

TEST(Nozzle, ShapeAndGrowth) {
    const mas::NozzleParams p;  // standoff 10, tip 10, 30 degrees, body 50 x 200, margin 2
    EXPECT_NEAR(mas::cone_length(p), 20.0 / kTan30, 1e-12);
    const double cos30 = std::sqrt(3.0) / 2.0;
    EXPECT_NEAR(mas::near_miss_mm(p), 4.0 * std::hypot(1.0, 1.0 / cos30), 1e-12);
    const Vector3d tip(1, 2, 3), axis = Vector3d(1, 2, 2).normalized();
    // A unit vector across the axis.
    const Vector3d across = axis.cross(Vector3d::UnitX()).normalized();
    auto at = [&](double h, double r) { return Vector3d(tip + h * axis + r * across); };
    // Grown by twice the margin: 4 mm up and down, 4 / cos 30 degrees across.
    const double grow = 4.0 / cos30, cone_end = 10.0 + 20.0 / kTan30;
    const double top = cone_end + 200.0;
    const double e = 1e-9;
    // Heights: from the standoff less 4 to the body's end plus 4.
    EXPECT_TRUE(mas::in_grown_nozzle(p, tip, axis, at(6.0 + e, 0)));
    EXPECT_FALSE(mas::in_grown_nozzle(p, tip, axis, at(6.0 - e, 0)));
    EXPECT_TRUE(mas::in_grown_nozzle(p, tip, axis, at(top + 4.0 - e, 0)));
    EXPECT_FALSE(mas::in_grown_nozzle(p, tip, axis, at(top + 4.0 + e, 0)));
    // Radii: the tip's face below it, the cone widening, the body.
    EXPECT_TRUE(mas::in_grown_nozzle(p, tip, axis, at(9.0, 5.0 + grow - e)));
    EXPECT_FALSE(mas::in_grown_nozzle(p, tip, axis, at(9.0, 5.0 + grow + e)));
    EXPECT_TRUE(mas::in_grown_nozzle(p, tip, axis, at(20.0, 5.0 + 10 * kTan30 + grow - e)));
    EXPECT_FALSE(mas::in_grown_nozzle(p, tip, axis, at(20.0, 5.0 + 10 * kTan30 + grow + e)));
    // The body's, and the cone's near it, grow by 4 alone: the nozzle is no wider than its body.
    EXPECT_TRUE(mas::in_grown_nozzle(p, tip, axis, at(cone_end + 50, 29.0 - e)));
    EXPECT_FALSE(mas::in_grown_nozzle(p, tip, axis, at(cone_end + 50, 29.0 + e)));
    EXPECT_TRUE(mas::in_grown_nozzle(p, tip, axis, at(cone_end - 1, 29.0 - e)));
    EXPECT_FALSE(mas::in_grown_nozzle(p, tip, axis, at(cone_end - 1, 29.0 + e)));
    EXPECT_TRUE(mas::in_grown_nozzle(p, tip, axis, at(cone_end - 10, 25 - 10 * kTan30 + grow - e)));
    EXPECT_FALSE(
        mas::in_grown_nozzle(p, tip, axis, at(cone_end - 10, 25 - 10 * kTan30 + grow + e)));
    // Nothing below the standoff: the deposit point's own neighbourhood is free.
    EXPECT_FALSE(mas::in_grown_nozzle(p, tip, axis, tip));
    // A nozzle of one diameter has no cone and grows by twice the margin all round.
    mas::NozzleParams straight = p;
    straight.body_diameter_mm = straight.tip_diameter_mm;
    straight.cone_angle_deg = 0.0;
    mas::validate(straight);
    EXPECT_EQ(mas::cone_length(straight), 0.0);
    EXPECT_NEAR(mas::near_miss_mm(straight), 4.0 * std::sqrt(2.0), 1e-12);
    EXPECT_TRUE(mas::in_grown_nozzle(straight, tip, axis, at(100.0, 9.0 - e)));
    EXPECT_FALSE(mas::in_grown_nozzle(straight, tip, axis, at(100.0, 9.0 + e)));
}

TEST(Nozzle, BadParametersAreNamed) {
    auto message = [](auto change) {
        mas::NozzleParams p;
        change(p);
        return error_of([&] { mas::validate(p); });
    };
    EXPECT_EQ(message([](auto& p) { p.standoff_mm = -1; }),
              "the nozzle's standoff must be >= 0 mm, got -1");
    EXPECT_EQ(message([](auto& p) { p.tip_diameter_mm = 0; }),
              "the nozzle's tip diameter must be > 0 mm, got 0");
    EXPECT_EQ(message([](auto& p) { p.body_diameter_mm = 8; }),
              "the nozzle's body diameter must be at least its tip diameter (10 mm), got 8");
    EXPECT_EQ(message([](auto& p) { p.body_length_mm = 0; }),
              "the nozzle's body length must be > 0 mm, got 0");
    EXPECT_EQ(message([](auto& p) { p.cone_angle_deg = 90; }),
              "the nozzle's cone angle (half-angle) must lie between 0 and 90 degrees, got 90");
    EXPECT_EQ(message([](auto& p) { p.margin_mm = std::nan(""); }),
              "the nozzle's margin must be > 0 mm, got nan");
    EXPECT_EQ(message([](auto& p) { p.standoff_mm = INFINITY; }),
              "the nozzle's standoff must be >= 0 mm, got inf");
    EXPECT_EQ(message([](auto& p) { p.standoff_mm = 3.9; }),
              "the nozzle's margin must be at most half its standoff (3.9 mm), got 2");
    EXPECT_EQ(message([](auto& p) { p.standoff_mm = 4.0; }), "");
    EXPECT_EQ(message([](auto& p) { p.max_lean_deg = -5; }),
              "the nozzle's greatest lean must lie within [0, 90) degrees, got -5");
    EXPECT_EQ(message([](auto& p) { p.max_lean_deg = 90; }),
              "the nozzle's greatest lean must lie within [0, 90) degrees, got 90");
    EXPECT_EQ(message([](auto& p) { p.max_lean_deg = std::nan(""); }),
              "the nozzle's greatest lean must lie within [0, 90) degrees, got nan");
    EXPECT_EQ(message([](auto& p) { p.max_lean_deg = 0; }), "");
    // The body's end's rim at most 1e5 margins from the deposit point: the travel check cuts the
    // table's turns so that it moves at most a margin a step (at the defaults it lies 245.9 mm
    // off). A 1e9 mm standoff, or a cone of 1e-6 degrees (1.1e9 mm long), cut one turn of a
    // crank's program into 1.7 GB of steps in 8 s.
    const std::string beyond =
        " mm from its deposit point, more than 100000 times its margin (2 mm): the travel check "
        "cuts the table's turns into steps that move it at most a margin; shorten the nozzle or "
        "widen the margin";
    EXPECT_EQ(message([](auto& p) { p.body_length_mm = 199900; }), "");  // 199944.6 mm
    EXPECT_EQ(message([](auto& p) { p.body_length_mm = 200000; }),
              "the nozzle's body ends 200045" + beyond);
    EXPECT_EQ(message([](auto& p) { p.standoff_mm = 1e9; }),
              "the nozzle's body ends 1e+09" + beyond);
    EXPECT_EQ(message([](auto& p) { p.cone_angle_deg = 1e-6; }),
              "the nozzle's body ends 1.14592e+09" + beyond);
    EXPECT_EQ(message([](auto& p) { p.body_diameter_mm = 1e300; }),
              "the nozzle's body ends 1e+300" + beyond);
}

// Two posts on a plate, 10 mm apart: built one after the other, the second post's first layer
// would have the nozzle's cone meet the first post's top. The sequence builds the first post up
// to the layer below the one that would, then the second, then the rest of the first.
TEST(Nozzle, BrothersAreBuiltTogetherJustShortOfACollision) {
    Built b;
    add_square(b, 0, -10, -10, 50, 20, 1.0);  // the plate: component 0
    for (int k = 0; k < 40; ++k) add_square(b, 1, 0, 0, 10, 10, 2.0 + k);
    for (int k = 0; k < 40; ++k) add_square(b, 2, 20, 0, 30, 10, 2.0 + k);
    const mas::BuildSequence s = mas::plan_build_sequence(input(b, {-1, 0, 0}, {0, 1, 2}), {});
    // Post 2's first deposit point (25, 5, 2) is 15 mm across from post 1. The grown cone
    // (5 + (h - 10) tan 30 + 4 / cos 30) is 15 mm wide 19.320 mm above it (the samples on post 1's
    // edge, 2 mm apart, at 15.033 mm: 19.377): post 1's layer with its top at z = 22 is the
    // first to block it. Post 2 then goes up to z = 41 (it would block post 1's next layer, at
    // 22, from z = 41.38 on) and post 1 finishes.
    std::vector<int> expected = {0};
    for (int k = 0; k < 20; ++k) expected.push_back(1 + k);
    for (int k = 0; k < 40; ++k) expected.push_back(41 + k);
    for (int k = 20; k < 40; ++k) expected.push_back(1 + k);
    EXPECT_EQ(s.layers, expected);
    EXPECT_TRUE(s.collisions.empty());
    EXPECT_EQ(s.component_switches, 3);
    EXPECT_EQ(s.interrupted_components, 1);
}

TEST(Nozzle, AComponentGoesFirstWhenTheEarlierWouldBlockIt) {
    // Component 1 is first in the start order, but its layer lies 29 mm above component 2's
    // deposit point, 7 mm across: in component 2's nozzle. Component 2 goes first.
    Built b;
    add_square(b, 0, -10, -10, 50, 20, 1.0);
    add_square(b, 1, 0, 0, 10, 10, 31.0);
    add_square(b, 2, 12, 0, 22, 10, 2.0);
    const mas::BuildSequence s = mas::plan_build_sequence(input(b, {-1, 0, 0}, {0, 1, 2}), {});
    EXPECT_EQ(s.layers, (std::vector<int>{0, 2, 1}));
    EXPECT_TRUE(s.collisions.empty());
}

// A 10 x 10 column of 1 mm layers (tops z = 1 ... 40) and a ledge beside it, [10, 20] x [0, 10]
// with its top at z = 20, deposited at its centre, under a nozzle whose tip (10 across) stands
// 1 mm off the deposit point (margin 0.5). The ledge's box grown by the thickest layer (1 mm) meets
// the column's layers up to the one with its top at z = 22: the ledge may rest on those, and they
// come before it, though its nozzle meets the two above z = 20 (each 5 mm across from the deposit
// point, within the tip). The column's layers above do not touch it: they and the ledge are
// ordered like brothers' layers, and the next one, 2 to 3 mm above the deposit point, would lie
// in its nozzle: the ledge goes first. (Waiting for the whole column, the ledge's nozzle met the
// column's top layers.)
TEST(Nozzle, AChildWaitsForTheLayersOfItsFatherItMayRestOnAndNoMore) {
    Built b;
    for (int k = 0; k < 40; ++k) add_square(b, 0, 0, 0, 10, 10, 1.0 + k);
    add_square(b, 1, 10, 0, 20, 10, 20.0);
    mas::NozzleParams p = coaxial(false);
    p.standoff_mm = 1.0;
    p.margin_mm = 0.5;
    const mas::BuildSequence s = mas::plan_build_sequence(input(b, {-1, 0}, {0, 1}), p);
    std::vector<int> expected;
    for (int k = 0; k < 22; ++k) expected.push_back(k);
    expected.push_back(40);
    for (int k = 22; k < 40; ++k) expected.push_back(k);
    EXPECT_EQ(s.layers, expected);
    ASSERT_EQ(s.collisions.size(), 1u);
    EXPECT_EQ(s.collisions[0].layer, 40);
    EXPECT_EQ(s.collisions[0].obstacle_layer, 21);  // top at z = 22, 1 to 2 mm up: in the tip
    EXPECT_EQ(s.component_switches, 2);
    EXPECT_EQ(s.interrupted_components, 1);
    // Waiting for all of its father, it comes last, and meets the column's top layers.
    mas::SequenceInput whole = input(b, {-1, 0}, {0, 1});
    whole.waits_for[1] = {0};
    const mas::BuildSequence w = mas::plan_build_sequence(whole, p);
    EXPECT_EQ(w.layers.back(), 40);
    ASSERT_EQ(w.collisions.size(), 1u);
    EXPECT_GT(w.collisions[0].obstacle_layer, 21);
}

// A post standing on a ledge 4 mm from the column the ledge leaves (the post's grandfather), as
// sliced parts have them: the post touches none of the column's layers, and goes up with the
// column, each discontinued just before the other's nozzle would meet it. Built after the whole
// column (the paper's "a child cannot be built until its father has been deposited", taken down
// the tree), the post's upper layers have the nozzle's cone meet the column's top.
TEST(Nozzle, APostOnALedgeGoesUpWithTheColumnTheLedgeLeaves) {
    Built b;
    for (int k = 0; k < 40; ++k) add_square(b, 0, 0, 0, 10, 10, 1.0 + k);   // 0 .. 39
    add_square(b, 1, 10, 0, 20, 10, 20.0);                                  // 40
    for (int k = 0; k < 20; ++k) add_square(b, 2, 14, 3, 18, 7, 21.0 + k);  // 41 .. 60
    const mas::SequenceInput in = input(b, {-1, 0, 1}, {0, 1, 2});
    const mas::BuildSequence s = mas::plan_build_sequence(in, coaxial());
    // The grown nozzle (from 6 mm up, 5 + 4 / cos 30 = 9.62 mm across its axis there) holds a
    // layer of the other 6 mm or more above the deposit point: the post's (6 mm from the column)
    // holds the column's layers 6 mm above it, the column's (9 mm from the post) the post's. The
    // ledge's (5 mm from the column) holds the column's from z = 26 on: the column goes up to
    // z = 25, then the ledge, the column's layer at 26, the post to 32 (its next one would lie in
    // the column's nozzle at 27), the column to 38, the post to its top, and the column's last two.
    std::vector<int> expected;
    auto column = [&](int from, int to) {
        for (int z = from; z <= to; ++z) expected.push_back(z - 1);
    };
    auto post = [&](int from, int to) {
        for (int z = from; z <= to; ++z) expected.push_back(20 + z);
    };
    column(1, 25);
    expected.push_back(40);
    column(26, 26);
    post(21, 32);
    column(27, 38);
    post(33, 40);
    column(39, 40);
    EXPECT_EQ(s.layers, expected);
    EXPECT_TRUE(s.collisions.empty());
    EXPECT_EQ(s.component_switches, 6);
    EXPECT_EQ(s.interrupted_components, 2);
    // Waiting for all of the column, the post collides with it.
    mas::SequenceInput whole = in;
    whole.waits_for[2] = {0};
    const mas::BuildSequence w = mas::plan_build_sequence(whole, coaxial());
    EXPECT_FALSE(w.collisions.empty());
    for (const mas::NozzleCollision& c : w.collisions) {
        EXPECT_GE(c.layer, 41);
        EXPECT_LT(c.obstacle_layer, 40);
    }
}

TEST(Nozzle, CollisionsNoOrderAvoidsAreReported) {
    {
        // One component whose second layer's nozzle meets its first, 29 mm above and 7 across.
        Built b;
        add_square(b, 0, 12, 0, 22, 10, 31.0);
        add_square(b, 0, 0, 0, 10, 10, 2.0);
        const mas::BuildSequence s = mas::plan_build_sequence(input(b, {-1}, {0}), coaxial());
        EXPECT_EQ(s.layers, (std::vector<int>{0, 1}));
        ASSERT_EQ(s.collisions.size(), 1u);
        EXPECT_EQ(s.collisions[0].layer, 1);
        EXPECT_EQ(s.collisions[0].obstacle_layer, 0);
        EXPECT_EQ(s.collisions[0].nozzle_at, Vector3d(5, 5, 2));
        const Vector3d q = s.collisions[0].obstacle;
        EXPECT_TRUE(q.x() >= 12 && q.x() <= 22 && q.y() >= 0 && q.y() <= 10 && q.z() >= 30 &&
                    q.z() <= 31)
            << q.transpose();
        EXPECT_TRUE(mas::in_grown_nozzle({}, Vector3d(5, 5, 2), Vector3d::UnitZ(), q));
    }
    {
        // Of two layers in the way, the one coming deeper into the nozzle is reported: a square
        // 7 mm across, grazed by the cone's side, and a smaller one right above on the axis.
        Built b;
        add_square(b, 0, 12, 0, 22, 10, 31.0);
        add_square(b, 0, 3, 3, 7, 7, 41.0);
        add_square(b, 0, 0, 0, 10, 10, 2.0);
        const mas::BuildSequence s = mas::plan_build_sequence(input(b, {-1}, {0}), coaxial());
        ASSERT_EQ(s.collisions.size(), 1u);
        EXPECT_EQ(s.collisions[0].layer, 2);
        EXPECT_EQ(s.collisions[0].obstacle_layer, 1);  // not the lower-numbered graze
        // Its deepest sample: on the axis (the face grid's middle), over the deposit point.
        EXPECT_EQ(s.collisions[0].nozzle_at, Vector3d(5, 5, 2));
        const Vector3d q = s.collisions[0].obstacle;
        EXPECT_NEAR(std::hypot(q.x() - 5, q.y() - 5), 0.0, 1e-9) << q.transpose();
    }
    {
        // A near miss under the tip's face (3.5 mm below it, in the grown band) and a square
        // cutting 1 mm into the body: the one inside the nozzle is reported.
        Built b;
        add_square(b, 0, 3, 3, 7, 7, 8.5);
        add_square(b, 0, 29, 0, 39, 10, 60.0);
        add_square(b, 0, 0, 0, 10, 10, 2.0);
        b.paths[2].paths[0].points = {{5, 5, 2}};
        const mas::BuildSequence s = mas::plan_build_sequence(input(b, {-1}, {0}), coaxial());
        ASSERT_EQ(s.collisions.size(), 1u);
        EXPECT_EQ(s.collisions[0].obstacle_layer, 1);
        EXPECT_NEAR(s.collisions[0].obstacle.x(), 29.0, 1e-9);
    }
    {
        // Two layers facing each other 20 mm apart, each in the other's nozzle: a cycle. The
        // first in the start order goes first, and the second collides with it.
        Built b;
        add_layer(b, 0, Vector3d::UnitX(), {{0, 0, 1}, {0, 10, 1}, {0, 10, 11}, {0, 0, 11}}, 1.0,
                  {{0, 5, 6}});
        add_layer(b, 1, -Vector3d::UnitX(), {{20, 0, 1}, {20, 10, 1}, {20, 10, 11}, {20, 0, 11}},
                  1.0, {{20, 5, 6}});
        const mas::NozzleParams no_plate = coaxial(false);
        // Two roots: neither waits for the other.
        const mas::BuildSequence s = mas::plan_build_sequence(input(b, {-1, -1}, {0, 1}), no_plate);
        EXPECT_EQ(s.layers, (std::vector<int>{0, 1}));
        ASSERT_EQ(s.collisions.size(), 1u);
        EXPECT_EQ(s.collisions[0].layer, 1);
        EXPECT_EQ(s.collisions[0].obstacle_layer, 0);
        EXPECT_EQ(s.collisions[0].nozzle_at, Vector3d(20, 5, 6));
    }
    {
        // A layer deposited sideways (+X) 6 mm above the plate: the body's rim reaches 19 mm
        // under the plate, first where the cone meets the body.
        Built b;
        add_layer(b, 0, Vector3d::UnitX(), {{5, 0, 1}, {5, 10, 1}, {5, 10, 11}, {5, 0, 11}}, 1.0,
                  {{5, 5, 6}});
        const mas::BuildSequence s = mas::plan_build_sequence(input(b, {-1}, {0}), coaxial());
        ASSERT_EQ(s.collisions.size(), 1u);
        EXPECT_EQ(s.collisions[0].layer, 0);
        EXPECT_EQ(s.collisions[0].obstacle_layer, -1);
        EXPECT_EQ(s.collisions[0].nozzle_at, Vector3d(5, 5, 6));
        EXPECT_NEAR((s.collisions[0].obstacle - Vector3d(5 + 10 + 20 / kTan30, 5, 0)).norm(), 0,
                    1e-12);
        const mas::NozzleParams no_plate = coaxial(false);
        EXPECT_TRUE(mas::plan_build_sequence(input(b, {-1}, {0}), no_plate).collisions.empty());
        // Raised so that the rim stays the margin above the plate, it does not collide.
        Built high;
        add_layer(high, 0, Vector3d::UnitX(), {{5, 0, 22}, {5, 10, 22}, {5, 10, 32}, {5, 0, 32}},
                  1.0, {{5, 5, 27 + 1e-9}});
        EXPECT_TRUE(mas::plan_build_sequence(input(high, {-1}, {0}), coaxial()).collisions.empty());
        Built low = high;
        low.paths[0].paths[0].points[0].z() = 27 - 1e-9;
        EXPECT_EQ(mas::plan_build_sequence(input(low, {-1}, {0}), coaxial()).collisions.size(), 1u);
    }
}

TEST(Nozzle, EverythingWithinTheMarginIsFound) {
    // A nozzle of one diameter (radius 5) depositing at the origin along +Z, and a wall whose
    // face lies d mm from its side, 20 to 60 mm up: found within the margin (2 mm), and past the
    // near miss (4 sqrt 2 mm) not.
    mas::NozzleParams straight;
    straight.body_diameter_mm = straight.tip_diameter_mm = 10.0;
    auto collides = [&](double d) {
        Built b;
        add_layer(b, 0, -Vector3d::UnitX(),
                  {{5 + d, -10, 20}, {5 + d, 10, 20}, {5 + d, 10, 60}, {5 + d, -10, 60}}, 1.0,
                  {{5 + d, 0, 40}});
        add_square(b, 0, -5, -5, 5, 5, 0.0);
        b.paths[1].paths[0].points = {{0, 0, 0}};
        mas::NozzleParams no_plate = straight;
        no_plate.check_plate = false;
        no_plate.max_lean_deg = 0.0;
        return mas::plan_build_sequence(input(b, {-1}, {0}), no_plate).collisions.size();
    };
    for (double d : {-0.5, 0.0, 0.01, 1.0, 1.99, 2.0}) EXPECT_EQ(collides(d), 1u) << d;
    EXPECT_EQ(collides(4.0 * std::sqrt(2.0) + 1e-9), 0u);
    EXPECT_EQ(collides(10.0), 0u);
}

TEST(Nozzle, WaitsAndBadInput) {
    Built b;
    add_square(b, 0, -10, -10, 50, 20, 1.0);
    add_square(b, 1, 0, 0, 10, 10, 2.0);
    add_square(b, 2, 40, 0, 50, 10, 2.0);
    mas::SequenceInput in = input(b, {-1, 0, 0}, {0, 1, 2});
    in.waits_for[1] = {2};
    EXPECT_EQ(mas::plan_build_sequence(in, {}).layers, (std::vector<int>{0, 2, 1}));
    in.waits_for[2] = {1};
    EXPECT_EQ(error_of([&] { mas::plan_build_sequence(in, {}); }), "component 1 waits for itself");
    mas::SequenceInput lost = input(b, {-1, 0, 0}, {0, 1});
    EXPECT_EQ(error_of([&] { mas::plan_build_sequence(lost, {}); }),
              "the start order must name every component once");
    Built apart = b;
    apart.layers[1].component = 2;
    apart.layers[2].component = 1;
    add_square(apart, 2, 0, 0, 10, 10, 3.0);
    EXPECT_EQ(error_of([&] {
                  mas::plan_build_sequence(input(apart, {-1, 0, 0}, {0, 1, 2}), {});
              }),
              "component 2's layers do not lie together");
    Built stranger = b;
    stranger.layers[2].component = 3;
    EXPECT_EQ(error_of([&] {
                  mas::plan_build_sequence(input(stranger, {-1, 0, 0}, {0, 1, 2}), {});
              }),
              "layer 2 names component 3, which the part lacks");
    mas::NozzleParams bad;
    bad.margin_mm = 0;
    EXPECT_EQ(error_of([&] {
                  mas::plan_build_sequence(input(b, {-1, 0, 0}, {0, 1, 2}), bad);
              }),
              "the nozzle's margin must be > 0 mm, got 0");
    // The layers' outlines span 60 x 30 x 1 mm: the margin must be at least 5e-4 of that
    // diagonal, the spacing of the samples the checks take.
    EXPECT_NEAR(mas::layers_size(b.layers), std::sqrt(4501.0), 1e-12);
    bad.margin_mm = 0.0335;
    EXPECT_EQ(error_of([&] {
                  mas::plan_build_sequence(input(b, {-1, 0, 0}, {0, 1, 2}), bad);
              }),
              "the nozzle's margin 0.0335 mm is too small for the layers, 67.0895 mm across: the "
              "collision checks sample what is deposited that far apart; the least is "
              "0.0335447 mm");
    EXPECT_EQ(error_of([&] { mas::TravelCheck(b.layers, bad, in.plate); }),
              "the nozzle's margin 0.0335 mm is too small for the layers, 67.0895 mm across: the "
              "collision checks sample what is deposited that far apart; the least is "
              "0.0335447 mm");
    bad.margin_mm = 0.034;
    EXPECT_EQ(error_of([&] {
                  mas::plan_build_sequence(input(b, {-1, 0, 0}, {0, 1, 2}), bad);
              }),
              "");
    // Cancelling.
    const mas::Progress cancel([](double, const std::string&) {
        throw mas::Error(mas::ErrorCode::Cancelled, "cancelled");
    });
    EXPECT_EQ(error_of([&] {
                  mas::plan_build_sequence(input(b, {-1, 0, 0}, {0, 1, 2}), {}, cancel);
              }),
              "cancelled");
}

// The nozzle's own shape (not grown) against an axis-aligned box, with a vertical axis at `p`:
// they meet when some height within both has the box's footprint within the nozzle's radius.
bool vertical_nozzle_meets_box(const mas::NozzleParams& n, const Vector3d& p,
                               const Eigen::AlignedBox3d& box) {
    const double top = n.standoff_mm + mas::cone_length(n) + n.body_length_mm;
    const double lo = std::max(n.standoff_mm, box.min().z() - p.z());
    const double hi = std::min(top, box.max().z() - p.z());
    if (lo > hi) return false;
    const double r =
        std::min(0.5 * n.body_diameter_mm, 0.5 * n.tip_diameter_mm + (hi - n.standoff_mm) * kTan30);
    const Eigen::AlignedBox2d foot(box.min().head<2>(), box.max().head<2>());
    return foot.exteriorDistance(Vector2d(p.head<2>())) <= r;
}

// A 60 x 30 x 5 plate with two 10 x 10 posts `height` tall on it, `gap` apart along X, as the
// plate and its two children.
std::vector<mas::ComponentMesh> posts_on_a_plate(double gap, double height) {
    using mas::test::box_mesh;
    std::vector<mas::ComponentMesh> comps(3);
    comps[0].mesh = box_mesh(-10, -10, 0, 60, 30, 5);
    comps[0].base = {Vector3d::Zero(), Vector3d::UnitZ()};
    comps[1].mesh = box_mesh(0, 0, 5, 10, 10, height);
    comps[2].mesh = box_mesh(10 + gap, 0, 5, 10, 10, height);
    for (int c : {1, 2}) {
        comps[std::size_t(c)].parent = 0;
        comps[std::size_t(c)].base = {Vector3d(0, 0, 5), Vector3d::UnitZ()};
    }
    return comps;
}

// Two 10 x 10 posts 60 tall, 10 mm apart on a plate, sliced: the sequence builds them together,
// and no deposit point has the nozzle meet a layer deposited before it, while the components'
// own order (one post, then the other) would.
TEST(Nozzle, SlicedPostsAreInterleavedWithoutCollisions) {
    const std::vector<mas::ComponentMesh> comps = posts_on_a_plate(10.0, 60.0);
    mas::CentroidalAxis axis;
    mas::SlicePartParams params;
    params.layers.min_layer_mm = 0.5;
    params.layers.max_layer_mm = 2.0;
    params.paths.bead_width_mm = 2.0;
    const mas::SlicedPart part = mas::slice_components(comps, axis, params);
    const std::vector<int>& order = part.sequence.layers;
    ASSERT_EQ(order.size(), part.layers.size());
    EXPECT_TRUE(part.sequence.collisions.empty());
    EXPECT_EQ(part.stats.colliding_layers, 0);
    EXPECT_GE(part.sequence.interrupted_components, 1);
    auto prism = [&](int i) {
        const mas::Layer& l = part.layers[std::size_t(i)];
        Eigen::AlignedBox3d box;
        for (const auto& loop : l.loops_3d(0))
            for (const Vector3d& q : loop) {
                box.extend(q);
                box.extend(Vector3d(q - l.thickness_at(q) * l.plane.normal));
            }
        return box;
    };
    // Whether depositing `x` after the layers `before` has the nozzle meet one of them, at any
    // deposit point (moves are checked at 0.1 mm steps: the posts' edges are 10 mm from any
    // point that could meet them, the test's margin).
    auto meets = [&](int x, const std::vector<int>& before) {
        for (const mas::ToolPath& path : part.toolpaths[std::size_t(x)].paths) {
            if (!path.deposit()) continue;
            for (std::size_t k = 0; k + 1 < path.points.size(); ++k) {
                const Vector3d a = path.points[k], d = path.points[k + 1] - a;
                const int steps = std::max(1, int(std::ceil(d.norm() / 0.1)));
                for (int i = 0; i <= steps; ++i)
                    for (int y : before)
                        if (vertical_nozzle_meets_box(params.nozzle, a + d * (double(i) / steps),
                                                      prism(y)))
                            return true;
            }
        }
        return false;
    };
    std::vector<int> done;
    for (int x : order) {
        EXPECT_FALSE(meets(x, done)) << "layer " << x;
        done.push_back(x);
    }
    // Component by component, the second post's first layer would meet the first post.
    const mas::ComponentLayers& first = part.components[std::size_t(part.build_order[1])];
    const mas::ComponentLayers& second = part.components[std::size_t(part.build_order[2])];
    std::vector<int> whole_first;
    for (int k = 0; k < first.layer_count; ++k) whole_first.push_back(first.first_layer + k);
    EXPECT_TRUE(meets(second.first_layer, whole_first));
    // Each layer's first move is a travel from where the layer before it in the sequence ended,
    // and the travel figures add up.
    double travel = 0.0;
    for (std::size_t k = 0; k < order.size(); ++k) {
        const mas::LayerToolpaths& t = part.toolpaths[std::size_t(order[k])];
        double length = 0.0;
        for (const mas::ToolPath& path : t.paths)
            if (!path.deposit()) length += (path.points.back() - path.points.front()).norm();
        EXPECT_NEAR(t.travel_length_mm, length, 1e-9);
        travel += length;
        if (k == 0) {
            EXPECT_TRUE(t.paths.front().deposit());
            continue;
        }
        const mas::LayerToolpaths& before = part.toolpaths[std::size_t(order[k - 1])];
        ASSERT_FALSE(t.paths.front().deposit()) << "layer " << order[k];
        EXPECT_EQ(t.paths.front().points.front(), before.paths.back().points.back());
        EXPECT_EQ(t.paths.front().points.back(), t.paths[1].points.front());
    }
    EXPECT_NEAR(part.stats.travel_length_mm, travel, 1e-9 * travel);
    // The program deposits the layers in the sequence's order.
    const std::vector<mas::GcodeLayer> g = mas::gcode_layers(part);
    ASSERT_EQ(g.size(), order.size());
    for (std::size_t k = 0; k < g.size(); ++k) {
        EXPECT_EQ(g[k].index, order[k]);
        EXPECT_EQ(g[k].component, part.layers[std::size_t(order[k])].component);
    }
    // Its comments name each layer by the part's number, in the sequence's order.
    std::istringstream program(mas::write_gcode(g, {}));
    std::vector<int> named;
    for (std::string line; std::getline(program, line);)
        if (line.rfind("(layer ", 0) == 0) named.push_back(std::stoi(line.substr(7)));
    EXPECT_EQ(named, order);
}

// Posts 1.5 mm apart come within reach of each other's base, but neither rests on the other:
// neither waits for the other, and they go up together without a collision (waiting for the
// first post, the second's first layer would have the nozzle's tip meet it all the way up).
TEST(Nozzle, NeighboursAPostDoesNotRestOnAreNotWaitedFor) {
    const std::vector<mas::ComponentMesh> comps = posts_on_a_plate(1.5, 40.0);
    mas::SlicePartParams params;
    params.paths.bead_width_mm = 2.0;
    const mas::SlicedPart part = mas::slice_components(comps, mas::CentroidalAxis(), params);
    EXPECT_TRUE(part.sequence.collisions.empty());
    EXPECT_GE(part.sequence.component_switches, 3);
}

// The height above the plane (through the origin, normal `up`) of the nozzle's lowest point, the
// nozzle standing at `p` along unit `axis`: its rims (the tip's face, where the cone meets the
// body, the body's end) walked round in steps of 0.01 degrees.
double lowest_above(const mas::NozzleParams& n, const Vector3d& p, const Vector3d& axis,
                    const Vector3d& up) {
    const Vector3d u = axis.unitOrthogonal(), v = axis.cross(u);
    const double cone_end = n.standoff_mm + mas::cone_length(n);
    double lowest = INFINITY;
    for (const auto& [h, r] : {std::pair{n.standoff_mm, 0.5 * n.tip_diameter_mm},
                               std::pair{cone_end, 0.5 * n.body_diameter_mm},
                               std::pair{cone_end + n.body_length_mm, 0.5 * n.body_diameter_mm}})
        for (int k = 0; k < 36000; ++k) {
            const double a = k * kPi / 18000.0;
            lowest =
                std::min(lowest, up.dot(p + h * axis + r * (std::cos(a) * u + std::sin(a) * v)));
        }
    return lowest;
}

// The least clearance from the nozzle standing at `p` along unit `axis` of the cube `half` either
// side of `centre`, sampled on a grid of `step`.
double least_clearance_of_cube(const mas::NozzleParams& n, const Vector3d& p, const Vector3d& axis,
                               const Vector3d& centre, double half, double step) {
    double best = INFINITY;
    for (double dx = -half; dx <= half + 1e-9; dx += step)
        for (double dy = -half; dy <= half + 1e-9; dy += step)
            for (double dz = -half; dz <= half + 1e-9; dz += step)
                best = std::min(
                    best, mas::test::nozzle_clearance(n, p, axis, centre + Vector3d(dx, dy, dz)));
    return best;
}

// Leaned by `degrees` from unit `n` towards `towards` (across n).
Vector3d leaned(const Vector3d& n, const Vector3d& towards, double degrees) {
    const double t = degrees * kPi / 180.0;
    const Vector3d d = (towards - n.dot(towards) * n).normalized();
    return std::cos(t) * n + std::sin(t) * d;
}

// A layer deposited sideways (+X) 6 mm above the plate: the coaxial nozzle's body reaches 19 mm
// under it. The nozzle leans up, by the least of 5, 10, ... degrees that keeps its lowest point
// the margin above the plate: 25 (at 20 its rim is 2.2 mm under the plate; at 25, 2.2 above).
TEST(Nozzle, ASidewaysLayerNearThePlateLeansUpJustEnough) {
    auto sideways = [](double z) {
        Built b;
        add_layer(b, 0, Vector3d::UnitX(),
                  {{5, 0, z - 5}, {5, 10, z - 5}, {5, 10, z + 5}, {5, 0, z + 5}}, 1.0, {{5, 5, z}});
        return b;
    };
    const mas::NozzleParams p;  // leans up to 30 degrees
    const Vector3d n = Vector3d::UnitX(), up = Vector3d::UnitZ();
    // The expectation, from the nozzle's rims walked round: the least lean clearing the plate.
    double expected = 0.0;
    for (double theta = 5.0; theta <= 30.0 && expected == 0.0; theta += 5.0)
        if (lowest_above(p, Vector3d(5, 5, 6), leaned(n, up, theta), up) >= p.margin_mm)
            expected = theta;
    ASSERT_EQ(expected, 25.0);
    EXPECT_LT(lowest_above(p, Vector3d(5, 5, 6), leaned(n, up, 20.0), up), -2.0);
    const Built b = sideways(6.0);
    const mas::BuildSequence s = mas::plan_build_sequence(input(b, {-1}, {0}), p);
    EXPECT_TRUE(s.collisions.empty());
    EXPECT_EQ(s.leaned_layers, 1);
    ASSERT_EQ(s.tool_axes.size(), 1u);
    EXPECT_NEAR((s.tool_axes[0] - leaned(n, up, 25.0)).norm(), 0.0, 1e-12);
    // Allowed at most 22 degrees (tried: 5, 10, 15, 20, 22), or coaxial, it collides as before.
    for (double most : {22.0, 0.0}) {
        mas::NozzleParams q = p;
        q.max_lean_deg = most;
        const mas::BuildSequence t = mas::plan_build_sequence(input(b, {-1}, {0}), q);
        ASSERT_EQ(t.collisions.size(), 1u) << most;
        EXPECT_EQ(t.collisions[0].obstacle_layer, -1);
        EXPECT_EQ(t.leaned_layers, 0);
        EXPECT_EQ(t.tool_axes[0], n);
    }
    // At 27 degrees it takes 25 all the same; at 1 mm above the plate even 30 does not clear.
    mas::NozzleParams q = p;
    q.max_lean_deg = 27.0;
    EXPECT_NEAR(
        (mas::plan_build_sequence(input(b, {-1}, {0}), q).tool_axes[0] - leaned(n, up, 25.0))
            .norm(),
        0.0, 1e-12);
    EXPECT_LT(lowest_above(p, Vector3d(5, 5, 1), leaned(n, up, 30.0), up), p.margin_mm);
    const mas::BuildSequence low = mas::plan_build_sequence(input(sideways(1.0), {-1}, {0}), p);
    EXPECT_EQ(low.collisions.size(), 1u);
    EXPECT_EQ(low.tool_axes[0], n);
    // Leans that would bring the nozzle near the layer's own plane are not tried. With a 60 degree
    // cone, past 30 degrees its lower side sinks towards the plane: at 45 it would clear the
    // plate at 6 mm, but its rim would pass 2.5 mm under the layer's plane, into what the layer
    // deposits; allowed 45, it tries up to 25 and none clears.
    mas::NozzleParams wide = p;
    wide.cone_angle_deg = 60.0;
    wide.max_lean_deg = 45.0;
    const Vector3d at(5, 5, 6), lean45 = leaned(n, up, 45.0);
    EXPECT_GE(lowest_above(wide, at, lean45, up), wide.margin_mm);
    EXPECT_NEAR(lowest_above(wide, at, lean45, n) - 5.0,
                (10 + 20 / std::sqrt(3.0) - 25) / std::sqrt(2.0), 1e-6);
    const mas::BuildSequence w = mas::plan_build_sequence(input(b, {-1}, {0}), wide);
    EXPECT_EQ(w.collisions.size(), 1u);
    EXPECT_EQ(w.tool_axes[0], n);
    // So with a standoff of 4 mm: past 20.4 degrees the tip's face comes within the margin of the
    // plane (4 cos - 5 sin < 2); 25 would clear the plate at 10 mm (20 would not), but is not
    // tried.
    mas::NozzleParams short_standoff = p;
    short_standoff.standoff_mm = 4.0;
    const Vector3d high(5, 5, 10);
    EXPECT_GE(lowest_above(short_standoff, high, leaned(n, up, 25.0), up), p.margin_mm);
    EXPECT_LT(lowest_above(short_standoff, high, leaned(n, up, 20.0), up), p.margin_mm);
    EXPECT_LT(lowest_above(short_standoff, high, leaned(n, up, 25.0), n) - 5.0, p.margin_mm);
    const mas::BuildSequence h =
        mas::plan_build_sequence(input(sideways(10.0), {-1}, {0}), short_standoff);
    EXPECT_EQ(h.collisions.size(), 1u);
    EXPECT_EQ(h.tool_axes[0], n);
}

// A slab [40, 120] x [-20, 30] x [40, 41] (component 0) and a sideways layer on x = 5, 10 x 10 mm
// from 1 mm over the plate (component 1, along +X, deposited at (5, 5, 6)).
Built slab_over_sideways_layer() {
    Built b;
    add_square(b, 0, 40, -20, 120, 30, 41.0);
    add_layer(b, 1, Vector3d::UnitX(), {{5, 0, 1}, {5, 10, 1}, {5, 10, 11}, {5, 0, 11}}, 1.0,
              {{5, 5, 6}});
    return b;
}

// A lean is refused where the leaned nozzle would meet a layer deposited before: a slab 40 mm up
// over the sideways layer's nozzle, clear of the coaxial body (its top 31 mm up) but in the way
// of any nozzle leaned up; the slab is the layer's father, deposited before it whatever the
// order. The layer keeps its normal and its collision with the plate.
TEST(Nozzle, ALeanIsRefusedWhereTheLeanedNozzleMeetsADepositedLayer) {
    Built b = slab_over_sideways_layer();
    const mas::NozzleParams p;
    const mas::BuildSequence s = mas::plan_build_sequence(input(b, {-1, 0}, {0, 1}), p);
    EXPECT_EQ(s.layers, (std::vector<int>{0, 1}));
    ASSERT_EQ(s.collisions.size(), 1u);
    EXPECT_EQ(s.collisions[0].layer, 1);
    EXPECT_EQ(s.collisions[0].obstacle_layer, -1);
    EXPECT_EQ(s.tool_axes[1], Vector3d::UnitX());
    EXPECT_EQ(s.leaned_layers, 0);
    // The slab is what refuses it: the lean that cleared the plate meets it (the body's top
    // side passes 40 mm up 40 mm out), while the coaxial nozzle keeps clear of it.
    const Vector3d at(5, 5, 6), lean25 = leaned(Vector3d::UnitX(), Vector3d::UnitZ(), 25.0);
    EXPECT_LT(mas::test::nozzle_clearance(p, at, lean25, Vector3d(60, 5, 40.5)), 0.0);
    for (double x = 40; x <= 120; x += 1)
        for (double y = -20; y <= 30; y += 1)
            EXPECT_GT(mas::test::nozzle_clearance(p, at, Vector3d::UnitX(), Vector3d(x, y, 40)),
                      p.margin_mm);
    // Without the slab it leans.
    b.layers.erase(b.layers.begin());
    b.paths.erase(b.paths.begin());
    b.layers[0].component = 0;
    EXPECT_EQ(mas::plan_build_sequence(input(b, {-1}, {0}), p).leaned_layers, 1);
}

// A lean is refused only where the leaned nozzle itself comes near a deposited layer, not wherever
// the nozzle grown by two margins might, nor wherever a sample every margin might stand for: a
// block 0.5 mm across beside the tip of the sideways layer's nozzle leaned 25 degrees (the least
// that clears the plate), 7 mm along its axis and 7.7 mm off it, lies in the grown nozzle (from 2
// margins under the tip's face, the tip's radius plus 2 margins / cos 30 across) and within (2 +
// 0.05) margins of the nozzle (4.04 mm from the tip's rim at its centre), which refused the lean
// before the finer samples, but more than (1 + 1/8 + 0.05) margins from it: the layer leans 25
// degrees. Moved to 8.5 mm along the axis and 6 mm off it, within the margin of the nozzle leaned
// 25 and 30 degrees, it refuses both, and the layer keeps its collision.
TEST(Nozzle, ALeanIsRefusedOnlyWhereTheNozzleItselfComesNear) {
    const mas::NozzleParams p;
    const Vector3d n = Vector3d::UnitX(), up = Vector3d::UnitZ(), at(5, 5, 6);
    const Vector3d axis = leaned(n, up, 25.0), off = leaned(up, -n, 25.0);  // across the axis
    ASSERT_NEAR(axis.dot(off), 0.0, 1e-12);
    auto centre = [&](double along, double across) { return at + along * axis + across * off; };
    auto with_block = [&](const Vector3d& c) {
        Built b;
        add_layer(b, 0, up,
                  {{c.x() - 0.25, 4.75, c.z() + 0.25},
                   {c.x() + 0.25, 4.75, c.z() + 0.25},
                   {c.x() + 0.25, 5.25, c.z() + 0.25},
                   {c.x() - 0.25, 5.25, c.z() + 0.25}},
                  0.5, {{c.x(), 5, c.z() + 0.25}});
        add_layer(b, 1, n, {{5, 0, 1}, {5, 10, 1}, {5, 10, 11}, {5, 0, 11}}, 1.0, {at});
        return b;
    };
    // The least clearance of the block's prism from the nozzle at `a`, on a 0.05 mm grid.
    auto least = [&](const Vector3d& c, const Vector3d& a) {
        return least_clearance_of_cube(p, at, a, c, 0.25, 0.05);
    };
    const double tip = 5.0, grown_tip = tip + 2.0 * p.margin_mm / std::cos(kPi / 6.0);
    const double counted = (1.0 + 1.0 / 8.0 + 0.05) * p.margin_mm;
    const Vector3d far = centre(7.0, 7.7);
    EXPECT_GE(7.0, p.standoff_mm - 2.0 * p.margin_mm);
    EXPECT_LE(7.7, grown_tip);
    EXPECT_NEAR(mas::test::nozzle_clearance(p, at, axis, far), std::hypot(2.7, 3.0), 1e-9);
    EXPECT_LT(least(far, axis), 2.05 * p.margin_mm);
    EXPECT_GT(least(far, axis), counted);
    const mas::BuildSequence s =
        mas::plan_build_sequence(input(with_block(far), {-1, 0}, {0, 1}), p);
    EXPECT_EQ(s.layers, (std::vector<int>{0, 1}));
    EXPECT_TRUE(s.collisions.empty());
    EXPECT_EQ(s.leaned_layers, 1);
    EXPECT_NEAR((s.tool_axes[1] - axis).norm(), 0.0, 1e-12);
    const Vector3d near = centre(8.5, 6.0);
    EXPECT_LT(least(near, axis), p.margin_mm);
    EXPECT_LT(least(near, leaned(n, up, 30.0)), p.margin_mm);
    const mas::BuildSequence t =
        mas::plan_build_sequence(input(with_block(near), {-1, 0}, {0, 1}), p);
    ASSERT_EQ(t.collisions.size(), 1u);
    EXPECT_EQ(t.collisions[0].layer, 1);
    EXPECT_EQ(t.collisions[0].obstacle_layer, -1);
    EXPECT_EQ(t.tool_axes[1], n);
}

// A sideways layer (+X, deposited at (5, 5, 20)) whose coaxial nozzle's body reaches under the
// plate, and a block 1 mm across deposited before it at `offset` from that point, beside the cone
// of every nozzle leaned up off the plate (as a crank's last leg, built back past its riser, has
// the riser there).
Built sideways_layer_beside_block(const Vector3d& offset) {
    const Vector3d at(5, 5, 20), c = at + offset;
    Built b;
    add_layer(b, 0, Vector3d::UnitZ(),
              {{c.x() - 0.5, c.y() - 0.5, c.z() + 0.5},
               {c.x() + 0.5, c.y() - 0.5, c.z() + 0.5},
               {c.x() + 0.5, c.y() + 0.5, c.z() + 0.5},
               {c.x() - 0.5, c.y() + 0.5, c.z() + 0.5}},
              1.0, {{c.x(), c.y(), c.z() + 0.5}});
    add_layer(b, 1, Vector3d::UnitX(), {{5, 0, 15}, {5, 10, 15}, {5, 10, 25}, {5, 0, 25}}, 1.0,
              {at});
    return b;
}

// For sideways_layer_beside_block(offset), the block on +Y's side: the first lean, in the order
// tried, that clears the plate and the block (more than 1.2 margins from it, where the engine
// refuses within (1 + 1/8 + 0.05) margins of a sample every eighth of a margin), by the nozzle's
// rims and the block's clearance on a 0.1 mm grid: 5, 10, ... degrees, each up, then every 22.5
// degrees round n from up, -Y's side (away from the block) first, as far as -Y and +Y (none below
// the horizontal). `ways`, when given, replaces those directions (up first).
std::optional<Vector3d> first_lean_clearing_block(const mas::NozzleParams& p,
                                                  const Vector3d& offset,
                                                  std::vector<Vector3d> ways = {}) {
    const Vector3d n = Vector3d::UnitX(), up = Vector3d::UnitZ(), y = Vector3d::UnitY();
    const Vector3d at(5, 5, 20);
    if (ways.empty()) {
        ways = {up};
        for (int k = 1; k <= 4; ++k) {
            const double phi = k * kPi / 8.0;
            ways.push_back(std::cos(phi) * up - std::sin(phi) * y);
            ways.push_back(std::cos(phi) * up + std::sin(phi) * y);
        }
    }
    for (double theta = 5.0; theta <= p.max_lean_deg; theta += 5.0)
        for (const Vector3d& d : ways) {
            const Vector3d a = leaned(n, d, theta);
            if (lowest_above(p, at, a, up) >= p.margin_mm &&
                least_clearance_of_cube(p, at, a, at + offset, 0.5, 0.1) > 1.2 * p.margin_mm)
                return a;
        }
    return std::nullopt;
}

// Where every lean up is refused, the nozzle leans round n as well: the block 12 mm out, 8 mm to
// the layer's +Y side and 4 mm up. No lean up clears both the plate and the block; the first lean
// that does, in the order tried, is 15 degrees half way between up and -Y, away from the block,
// and the engine takes exactly that. Without the block it leans up, the least lean, as before.
TEST(Nozzle, ALayerWhoseLeanUpIsBlockedLeansRoundTheNormal) {
    const mas::NozzleParams p;
    const Vector3d n = Vector3d::UnitX(), up = Vector3d::UnitZ(), y = Vector3d::UnitY();
    const Vector3d at(5, 5, 20), offset(12, 8, 4);
    Built b = sideways_layer_beside_block(offset);
    EXPECT_LT(lowest_above(p, at, n, up), p.margin_mm);
    EXPECT_FALSE(first_lean_clearing_block(p, offset, {up}));  // no lean up clears both
    const std::optional<Vector3d> expected = first_lean_clearing_block(p, offset);
    ASSERT_TRUE(expected);
    ASSERT_NEAR((*expected - leaned(n, up - y, 15.0)).norm(), 0.0, 1e-12);
    const mas::BuildSequence s = mas::plan_build_sequence(input(b, {-1, 0}, {0, 1}), p);
    EXPECT_EQ(s.layers, (std::vector<int>{0, 1}));
    EXPECT_TRUE(s.collisions.empty());
    EXPECT_EQ(s.leaned_layers, 1);
    EXPECT_NEAR((s.tool_axes[1] - *expected).norm(), 0.0, 1e-12);
    // Without the block: up, by the least lean that clears the plate (10 degrees).
    b.layers.erase(b.layers.begin());
    b.paths.erase(b.paths.begin());
    b.layers[0].component = 0;
    EXPECT_GE(lowest_above(p, at, leaned(n, up, 10.0), up), p.margin_mm);
    const mas::BuildSequence t = mas::plan_build_sequence(input(b, {-1}, {0}), p);
    EXPECT_NEAR((t.tool_axes[0] - leaned(n, up, 10.0)).norm(), 0.0, 1e-12);
}

// The ways round the normal are tried every 22.5 degrees, not only every 45: the block 15 mm out,
// 4 mm to +Y and 6 mm up, closer beside the layer than above. No lean up to 30 degrees up, half way
// between up and -Y or +Y, or towards -Y or +Y clears both the plate and the block (a crank's last
// leg beside its riser kept its collision so, and the leg hung 210 mm^2 in its father's layers);
// 25 degrees, 67.5 degrees round from up towards -Y, does, and the engine takes exactly that.
TEST(Nozzle, ALeanBetweenTheFortyFiveDegreeWaysClearsABlockCloseBeside) {
    const mas::NozzleParams p;
    const Vector3d n = Vector3d::UnitX(), up = Vector3d::UnitZ(), y = Vector3d::UnitY();
    const Vector3d offset(15, 4, 6);
    EXPECT_FALSE(first_lean_clearing_block(p, offset, {up, up - y, up + y, -y, y}));
    const std::optional<Vector3d> expected = first_lean_clearing_block(p, offset);
    ASSERT_TRUE(expected);
    const double phi = 3.0 * kPi / 8.0;
    ASSERT_NEAR((*expected - leaned(n, std::cos(phi) * up - std::sin(phi) * y, 25.0)).norm(), 0.0,
                1e-12);
    const mas::BuildSequence s =
        mas::plan_build_sequence(input(sideways_layer_beside_block(offset), {-1, 0}, {0, 1}), p);
    EXPECT_EQ(s.layers, (std::vector<int>{0, 1}));
    EXPECT_TRUE(s.collisions.empty());
    EXPECT_EQ(s.leaned_layers, 1);
    EXPECT_NEAR((s.tool_axes[1] - *expected).norm(), 0.0, 1e-12);
}

// The order leaves a layer that meets the plate the lean that clears it: the slab and the sideways
// layer above, neither waiting for the other, the slab first in the start order. Coaxial, the
// layer's nozzle misses the slab, so the first order puts the slab first, and the lean that
// clears the plate (25 degrees) meets it. Ordered again with the layer before what that lean
// meets, the layer goes first, leaned, and nothing collides (the slab's nozzle points away).
TEST(Nozzle, ALayerThatMustLeanOffThePlateGoesBeforeWhatItsLeanedNozzleMeets) {
    const Built b = slab_over_sideways_layer();
    const mas::NozzleParams p;
    const Vector3d n = Vector3d::UnitX(), up = Vector3d::UnitZ(), at(5, 5, 6);
    const mas::BuildSequence s = mas::plan_build_sequence(input(b, {-1, -1}, {0, 1}), p);
    EXPECT_EQ(s.layers, (std::vector<int>{1, 0}));
    EXPECT_TRUE(s.collisions.empty());
    EXPECT_EQ(s.leaned_layers, 1);
    EXPECT_NEAR((s.tool_axes[1] - leaned(n, up, 25.0)).norm(), 0.0, 1e-12);
    EXPECT_EQ(s.tool_axes[0], up);
    // Why: coaxial, the layer's nozzle meets the plate and not the slab; leaned 25 degrees it
    // clears the plate and meets the slab; the slab's nozzle, pointing up from 41 mm, meets
    // nothing.
    EXPECT_LT(lowest_above(p, at, n, up), p.margin_mm);
    EXPECT_GE(lowest_above(p, at, leaned(n, up, 25.0), up), p.margin_mm);
    EXPECT_LT(mas::test::nozzle_clearance(p, at, leaned(n, up, 25.0), Vector3d(60, 5, 40.5)), 0.0);
    for (double x = 40; x <= 120; x += 1)
        for (double y = -20; y <= 30; y += 1)
            EXPECT_GT(mas::test::nozzle_clearance(p, at, n, Vector3d(x, y, 40)), p.margin_mm);
    // The paper's coaxial nozzle never leans: the start order stands, and the plate is met.
    const mas::BuildSequence c = mas::plan_build_sequence(input(b, {-1, -1}, {0, 1}), coaxial());
    EXPECT_EQ(c.layers, (std::vector<int>{0, 1}));
    ASSERT_EQ(c.collisions.size(), 1u);
    EXPECT_EQ(c.collisions[0].layer, 1);
    EXPECT_EQ(c.collisions[0].obstacle_layer, -1);
}

// The deposit moves are checked all along, leaned too: a sideways layer whose path runs from 6 to
// 60 mm up leans 25 degrees to clear the plate at its foot, but there its tip's rim would pass a
// slab standing 6 to 7 mm off the layer's plane (deposited before it, its father), which no lean
// up to 30 degrees clears. The lean is refused and the layer keeps its collision with the plate.
TEST(Nozzle, ALeanIsCheckedAlongTheWholePathAgainstLayersOffItsPlane) {
    Built b;
    add_layer(b, 0, Vector3d::UnitX(), {{12, -10, 0.5}, {12, 20, 0.5}, {12, 20, 16}, {12, -10, 16}},
              1.0, {{12, 5, 8}});
    add_layer(b, 1, Vector3d::UnitX(), {{5, 0, 1}, {5, 10, 1}, {5, 10, 61}, {5, 0, 61}}, 1.0,
              {{5, 5, 6}, {5, 5, 60}});
    const mas::NozzleParams p;
    const Vector3d n = Vector3d::UnitX(), up = Vector3d::UnitZ();
    const mas::BuildSequence s = mas::plan_build_sequence(input(b, {-1, 0}, {0, 1}), p);
    ASSERT_EQ(s.layers, (std::vector<int>{0, 1}));
    EXPECT_EQ(s.tool_axes[1], n);
    bool layer_1_collides = false;
    for (const mas::NozzleCollision& c : s.collisions)
        if (c.layer == 1) {
            layer_1_collides = true;
            EXPECT_EQ(c.obstacle_layer, -1);
            EXPECT_EQ(c.nozzle_at, Vector3d(5, 5, 6));
        }
    EXPECT_TRUE(layer_1_collides);
    // At 25 and 30 degrees the nozzle at the path's foot comes into the slab (x 11 to 12, up to
    // z = 16), which stands off the plane x = 5; half-way up the path it is clear of it.
    auto least = [&](const Vector3d& at, double theta) {
        double c = INFINITY;
        for (double y = -10; y <= 20 + 1e-9; y += 0.25)
            for (double z = 0.5; z <= 16 + 1e-9; z += 0.25)
                for (double x : {11.0, 12.0})
                    c = std::min(c, mas::test::nozzle_clearance(p, at, leaned(n, up, theta),
                                                                Vector3d(x, y, z)));
        return c;
    };
    for (double theta : {25.0, 30.0}) {
        EXPECT_LT(least(Vector3d(5, 5, 6), theta), 0.0) << theta;
        EXPECT_GT(least(Vector3d(5, 5, 33), theta), p.margin_mm) << theta;
        EXPECT_GE(lowest_above(p, Vector3d(5, 5, 6), leaned(n, up, theta), up), p.margin_mm);
    }
    // Without the slab the layer leans 25 degrees.
    Built alone;
    alone.layers = {b.layers[1]};
    alone.paths = {b.paths[1]};
    alone.layers[0].component = 0;
    const mas::BuildSequence a = mas::plan_build_sequence(input(alone, {-1}, {0}), p);
    EXPECT_TRUE(a.collisions.empty());
    EXPECT_NEAR((a.tool_axes[0] - leaned(n, up, 25.0)).norm(), 0.0, 1e-12);
}

// A lean away from the obstacle may not turn the nozzle further from the plate's normal than the
// layer's normal is, past the horizontal: a sideways layer 100 mm up under its father's slab (its
// body meets the slab 18 mm above) would clear it leaned 15 degrees down, but the machine that
// reaches +X might not reach 105 degrees from +Z. It keeps its normal and its collision.
TEST(Nozzle, ALeanAwayNeverTurnsTheNozzleFurtherUnderTheHorizontal) {
    Built b;
    add_square(b, 0, 0, -20, 60, 30, 119.0);
    add_layer(b, 1, Vector3d::UnitX(), {{5, 0, 95}, {5, 10, 95}, {5, 10, 105}, {5, 0, 105}}, 1.0,
              {{5, 5, 100}});
    const mas::NozzleParams p;
    const Vector3d n = Vector3d::UnitX(), up = Vector3d::UnitZ(), at(5, 5, 100);
    const mas::BuildSequence s = mas::plan_build_sequence(input(b, {-1, 0}, {0, 1}), p);
    ASSERT_EQ(s.collisions.size(), 1u);
    EXPECT_EQ(s.collisions[0].layer, 1);
    EXPECT_EQ(s.collisions[0].obstacle_layer, 0);
    EXPECT_EQ(s.tool_axes[1], n);
    EXPECT_EQ(s.leaned_layers, 0);
    // Leaned 15 degrees down the nozzle would keep clear of the slab; coaxial it does not.
    auto least = [&](const Vector3d& axis) {
        double c = INFINITY;
        for (double x = 0; x <= 60 + 1e-9; x += 0.5)
            for (double y = -20; y <= 30 + 1e-9; y += 0.5)
                c = std::min(c, mas::test::nozzle_clearance(p, at, axis, Vector3d(x, y, 118)));
        return c;
    };
    EXPECT_LT(least(n), p.margin_mm);
    EXPECT_GT(least(leaned(n, -up, 15.0)), p.margin_mm);
}

// A layer whose nozzle meets one of its own component's layers above it, 7 mm across: the nozzle
// leans away from it, just enough. The leaned nozzle keeps the margin from that layer's prism
// (checked with the nozzle's own shape at 0.1 mm over its surface); 5 degrees less would come
// within (2 + 0.05) margins of it, the most a refused lean may come (plus the 0.1 mm grid's
// reach).
TEST(Nozzle, ANozzleLeansAwayFromTheLayerItMeets) {
    Built b;
    add_square(b, 0, 12, 0, 22, 10, 31.0);
    add_square(b, 0, 0, 0, 10, 10, 2.0);
    const mas::NozzleParams p;
    const mas::BuildSequence s = mas::plan_build_sequence(input(b, {-1}, {0}), p);
    ASSERT_TRUE(s.collisions.empty());
    EXPECT_EQ(s.leaned_layers, 1);
    EXPECT_EQ(s.tool_axes[0], Vector3d::UnitZ());
    const Vector3d axis = s.tool_axes[1], at(5, 5, 2);
    const double lean = std::acos(axis.z()) * 180.0 / kPi;
    EXPECT_NEAR(std::remainder(lean, 5.0), 0.0, 1e-9) << lean;
    EXPECT_GT(lean, 1.0);
    EXPECT_LT(axis.x(), -0.9 * std::sin(lean * kPi / 180.0));  // away: -X
    auto least = [&](const Vector3d& a) {
        double c = INFINITY;
        for (double x = 12; x <= 22 + 1e-9; x += 0.1)
            for (double y = 0; y <= 10 + 1e-9; y += 0.1)
                for (double z : {30.0, 31.0})
                    c = std::min(c, mas::test::nozzle_clearance(p, at, a, Vector3d(x, y, z)));
        for (double z = 30; z <= 31 + 1e-9; z += 0.1)
            for (double t = 0; t <= 10 + 1e-9; t += 0.1)
                for (const Vector3d& q : {Vector3d(12, t, z), Vector3d(22, t, z),
                                          Vector3d(12 + t, 0, z), Vector3d(12 + t, 10, z)})
                    c = std::min(c, mas::test::nozzle_clearance(p, at, a, q));
        return c;
    };
    EXPECT_GE(least(axis), p.margin_mm);
    const Vector3d across = Vector3d(axis.x(), axis.y(), 0).normalized();
    EXPECT_LT(least(leaned(Vector3d::UnitZ(), across, lean - 5.0)), 2.05 * p.margin_mm + 0.1)
        << lean;
}

// A sideways arm 20 mm thick, 8 mm over the plate, on a column, sliced: every arm layer leans
// up by the least of 5, 10, ... degrees that keeps the nozzle's lowest point the margin above the
// plate at every deposit point; every nozzle keeps the margin above its own layer's plane; the
// machine program turns the table to the leaned axes.
TEST(Nozzle, ASlicedLowArmLeansClearOfThePlate) {
    using mas::test::box_mesh;
    std::vector<mas::ComponentMesh> comps(2);
    comps[0].mesh = box_mesh(0, 0, 0, 20, 20, 40);
    comps[0].base = {Vector3d::Zero(), Vector3d::UnitZ()};
    comps[1].mesh = box_mesh(20, 0, 8, 50, 20, 20);
    comps[1].base = {Vector3d(20, 0, 0), Vector3d::UnitX()};
    comps[1].parent = 0;
    mas::SlicePartParams params;
    params.paths.bead_width_mm = 2.0;
    const mas::SlicedPart part = mas::slice_components(comps, mas::CentroidalAxis(), params);
    const mas::NozzleParams& p = params.nozzle;
    const Vector3d up = Vector3d::UnitZ();
    EXPECT_TRUE(part.sequence.collisions.empty());
    int arm_layers = 0;
    for (std::size_t i = 0; i < part.layers.size(); ++i) {
        SCOPED_TRACE("layer " + std::to_string(i));
        const mas::Layer& l = part.layers[i];
        const Vector3d axis = part.toolpaths[i].tool_axis;
        EXPECT_EQ(axis, part.sequence.tool_axes[i]);
        if (l.component == 0) {
            EXPECT_EQ(axis, l.plane.normal);
            continue;
        }
        ++arm_layers;
        // The lowest deposit point decides the lean.
        double low = INFINITY;
        Vector3d lowest_point;
        for (const mas::ToolPath& path : part.toolpaths[i].paths)
            if (path.deposit())
                for (const Vector3d& q : path.points)
                    if (q.z() < low) low = q.z(), lowest_point = q;
        double expected = 0.0;
        for (double theta = 5.0; theta <= 30.0 && expected == 0.0; theta += 5.0)
            if (lowest_above(p, lowest_point, leaned(l.plane.normal, up, theta), up) >= p.margin_mm)
                expected = theta;
        ASSERT_GT(expected, 0.0);
        EXPECT_NEAR((axis - leaned(l.plane.normal, up, expected)).norm(), 0.0, 1e-12) << expected;
        for (const mas::ToolPath& path : part.toolpaths[i].paths)
            if (path.deposit())
                for (const Vector3d& q : path.points) {
                    EXPECT_GE(lowest_above(p, q, axis, up) + 1e-9, p.margin_mm);
                    // The nozzle keeps the margin above the layer's own plane.
                    EXPECT_GE(lowest_above(p, q, axis, l.plane.normal) -
                                  l.plane.normal.dot(l.plane.origin) + 1e-9,
                              p.margin_mm);
                    break;  // one point per path: the rims are walked round 108000 times each
                }
    }
    EXPECT_EQ(part.stats.leaned_layers, arm_layers);
    EXPECT_GT(arm_layers, 10);
    // Coaxial, every arm layer meets the plate.
    mas::SlicePartParams paper = params;
    paper.nozzle.max_lean_deg = 0.0;
    const mas::SlicedPart coaxial_part = mas::slice_components(comps, mas::CentroidalAxis(), paper);
    EXPECT_EQ(int(coaxial_part.sequence.collisions.size()), arm_layers);
    // The program turns the table to each layer's leaned axis.
    const std::vector<mas::GcodeLayer> g = mas::gcode_layers(part);
    for (const mas::GcodeLayer& layer : g)
        EXPECT_EQ(layer.tool_axis, part.toolpaths[std::size_t(layer.index)].tool_axis);
    mas::GcodeStats stats;
    mas::write_gcode(g, {}, &stats);
    EXPECT_GT(stats.deposit_moves, 0);
}

// A block [-10, 10] x [-10, 10] x [0, 10] as one layer, deposited at its top's centre.
Built block() {
    Built b;
    add_layer(b, 0, Vector3d::UnitZ(), {{-10, -10, 10}, {10, -10, 10}, {10, 10, 10}, {-10, 10, 10}},
              10.0, {{0, 0, 10}});
    return b;
}

// A move across the block with the nozzle upright, its tip's face `gap` over the block's top, is
// met within the margin and passed where the nozzle keeps the margin, an eighth of it and the step
// (2.35 mm) from every point of the block (twice the margin and the step, 4.1 mm, before the
// samples that count were looked at again every eighth of a margin round them); only once the
// block is deposited. The plate is exact.
TEST(TravelCheck, AMoveIsJudgedByTheNozzlesClearance) {
    const Built b = block();
    const mas::NozzleParams p = coaxial();
    mas::TravelCheck check(b.layers, p, {Vector3d::Zero(), Vector3d::UnitZ()});
    auto across = [&](double gap) {
        return check.meets({{Vector3d(-30, 0, gap), Vector3d(30, 0, gap), Vector3d::UnitZ(), 0.0}});
    };
    EXPECT_FALSE(across(1.0));  // nothing deposited yet, and the plate 11 mm under the tip's face
    check.deposited(0);
    const auto hit = across(1.9);
    ASSERT_TRUE(hit);
    EXPECT_EQ(hit->obstacle_layer, 0);
    EXPECT_NEAR(hit->obstacle.z(), 10.0, 1e-9);  // on the block's top, under the tip's face
    EXPECT_LE(hit->obstacle.head<2>().cwiseAbs().maxCoeff(), 10.0 + 1e-9);
    EXPECT_NEAR(hit->nozzle_at.y(), 0.0, 1e-12);
    EXPECT_NEAR(hit->nozzle_at.z(), 1.9, 1e-12);
    EXPECT_LT(mas::test::nozzle_clearance(p, hit->nozzle_at, Vector3d::UnitZ(), hit->obstacle),
              2.35 + 1e-9);
    EXPECT_FALSE(across(2.4));
    EXPECT_FALSE(across(4.15));
    EXPECT_FALSE(across(30.0));
    // Lying on its side (+X), 100 mm off the block, the body's lowest point is 25 mm under the
    // tip: at 26.9 mm up it comes 1.9 mm from the plate, at 27.1 mm 2.1.
    auto sideways = [&](double z) {
        return check.meets({{Vector3d(100, -20, z), Vector3d(100, 20, z), Vector3d::UnitX(), 0.0}});
    };
    const auto plate = sideways(26.9);
    ASSERT_TRUE(plate);
    EXPECT_EQ(plate->obstacle_layer, -1);
    EXPECT_NEAR(plate->obstacle.z(), 0.0, 1e-9);
    EXPECT_FALSE(sideways(27.1));
    mas::NozzleParams no_plate = p;
    no_plate.check_plate = false;
    mas::TravelCheck unchecked(b.layers, no_plate, {Vector3d::Zero(), Vector3d::UnitZ()});
    EXPECT_FALSE(
        unchecked.meets({{Vector3d(100, -20, 10), Vector3d(100, 20, 10), Vector3d::UnitX(), 0.0}}));
}

// The nozzle leaning 30 degrees over the block, its tip's rim lowest at (1, 1), between the points
// of the block's top where its samples lie (every 2 mm): at 1.9 mm it is met, though the nearest
// sample lies 2.15 mm from the nozzle (only a sample as far as twice the margin can stand for the
// surface it stands over); at 4.2 mm (beyond twice the margin and the step of everything) passed.
TEST(TravelCheck, TheSurfaceBetweenSamplesCounts) {
    const Built b = block();
    const mas::NozzleParams p = coaxial(false);
    mas::TravelCheck check(b.layers, p, {Vector3d::Zero(), Vector3d::UnitZ()});
    check.deposited(0);
    const double t = kPi / 6.0;
    const Vector3d axis(0.0, -std::sin(t), std::cos(t));
    // The tip's face: its centre 10 mm up the axis, its rim 5 mm round it; the lowest rim point
    // lies across the axis straight down, 5 sin 30 mm under the centre.
    const Vector3d down = (-Vector3d::UnitZ() + axis.z() * axis).normalized();
    const Vector3d lowest_from_tip = 10.0 * axis + 5.0 * down;
    auto over = [&](double gap) {
        const Vector3d tip = Vector3d(1, 1, 10 + gap) - lowest_from_tip;
        double nearest_sample = INFINITY;  // of the grid the block's top is sampled on
        for (int i = -5; i <= 5; ++i)
            for (int j = -5; j <= 5; ++j)
                nearest_sample =
                    std::min(nearest_sample,
                             mas::test::nozzle_clearance(p, tip, axis, Vector3d(2 * i, 2 * j, 10)));
        return std::pair{check.meets({{tip, tip, axis, 0.0}}), nearest_sample};
    };
    const auto [met, nearest] = over(1.9);
    EXPECT_GT(nearest, p.margin_mm + 0.1);
    ASSERT_TRUE(met);
    EXPECT_EQ(met->obstacle_layer, 0);
    EXPECT_FALSE(over(4.2).first);
}

// A margin of half the standoff: leaving the block's top along the tool axis, the nozzle's face
// stands 2 margins over it, within what the grown nozzle counts (and what the samples every margin
// counted), though it keeps the margin: passed, whether or not the move is marked as leaving the
// layer (along_layer, not checked against it). A move across the top with the face 0.9 margins
// over it is met, after one along the layer too; so is one in a layer counted as deposited for one
// check (also), unless it goes along it.
TEST(TravelCheck, TheLayerAMoveLeavesAlongItsAxisIsNotCheckedAgainst) {
    const Built b = block();
    mas::NozzleParams p = coaxial(false);
    p.margin_mm = 5.0;
    mas::TravelCheck check(b.layers, p, {Vector3d::Zero(), Vector3d::UnitZ()});
    const Vector3d up = Vector3d::UnitZ();
    const mas::NozzleMove out{Vector3d(0, 0, 10), Vector3d(0, 0, 15), up, 0.0, 0};
    mas::NozzleMove unmarked = out;
    unmarked.along_layer = -1;
    const mas::NozzleMove across{Vector3d(0, 0, 4.5), Vector3d(5, 0, 4.5), up, 0.0, -1};
    mas::NozzleMove across_marked = across;
    across_marked.along_layer = 0;
    EXPECT_FALSE(check.meets({across}));  // not deposited
    EXPECT_TRUE(check.meets({across}, 0));
    EXPECT_FALSE(check.meets({across_marked}, 0));
    EXPECT_FALSE(check.meets({unmarked}, 0));
    check.deposited(0);
    EXPECT_FALSE(check.meets({unmarked}));
    EXPECT_FALSE(check.meets({out}));
    EXPECT_TRUE(check.meets({out, across}));
    EXPECT_EQ(error_of([&] {
                  check.meets({{Vector3d::Zero(), Vector3d::UnitX(), up, 0.0, 3}});
              }),
              "travel move 0 names layer 3, which the travel check lacks (it has 1)");
    EXPECT_EQ(error_of([&] { check.meets({out}, 2); }),
              "the travel check's extra layer names layer 2, which the travel check lacks (it has "
              "1)");
    EXPECT_EQ(error_of([&] {
                  check.meets({{Vector3d::Zero(), Vector3d::UnitX(), up, 1e-4, 0}});
              }),
              "travel move 0 turns its tool axis: it cannot go along a layer's");
}

// Random moves round the block, some with the table still, some turning the tool axis by up to
// max_turn_rad() about a random direction: every move passed keeps the margin from the block by
// the nozzle's own shape (the block's surface sampled every 0.5 mm, the moves every 0.1 mm: within
// 0.41 mm), and a move met comes within the margin, an eighth of it and the step of it (a turning
// move, twice its allowance more, up to two margins: the nozzle along its first axis is judged,
// which the turning one lies within the allowance of).
TEST(TravelCheck, EveryMovePassedKeepsTheMargin) {
    const Built b = block();
    mas::NozzleParams p = coaxial(false);
    mas::TravelCheck check(b.layers, p, {Vector3d::Zero(), Vector3d::UnitZ()});
    check.deposited(0);
    std::vector<Vector3d> surface;
    for (double u = -10; u <= 10 + 1e-9; u += 0.5)
        for (double v = -10; v <= 10 + 1e-9; v += 0.5) {
            surface.emplace_back(u, v, 10);
            surface.emplace_back(u, v, 0);
            if (v <= 0.0 + 1e-9) {
                const double z = v + 10;
                surface.emplace_back(u, -10, z);
                surface.emplace_back(u, 10, z);
                surface.emplace_back(-10, u, z);
                surface.emplace_back(10, u, z);
            }
        }
    std::mt19937 rng(20261202);
    std::uniform_real_distribution<double> uniform(-1.0, 1.0);
    const double tol = 0.41, m = p.margin_mm;
    int met = 0, passed = 0;
    for (int trial = 0; trial < 60; ++trial) {
        Vector3d axis(0.6 * uniform(rng), 0.6 * uniform(rng), 1.0);
        axis.normalize();
        const Vector3d from(25 * uniform(rng), 25 * uniform(rng), 10 + 8 * uniform(rng));
        const Vector3d to = from + Vector3d(8 * uniform(rng), 8 * uniform(rng), 3 * uniform(rng));
        const double turn = trial % 2 ? check.max_turn_rad() : 0.0;
        const double allowance =
            turn * std::hypot(p.standoff_mm + mas::cone_length(p) + p.body_length_mm,
                              0.5 * p.body_diameter_mm);
        const Vector3d about =
            axis.cross(Vector3d(uniform(rng), uniform(rng), uniform(rng))).normalized();
        double least = INFINITY;
        const int steps = int(std::ceil((to - from).norm() / 0.1));
        for (int i = 0; i <= steps; ++i) {
            const double s = double(i) / steps;
            const Vector3d a = Eigen::AngleAxisd(s * turn, about) * axis;
            for (const Vector3d& q : surface)
                least =
                    std::min(least, mas::test::nozzle_clearance(p, from + s * (to - from), a, q));
        }
        const auto hit = check.meets({{from, to, axis, turn}});
        if (hit) {
            ++met;
            EXPECT_LT(least, (1.175 * m + 2.0 * allowance) + tol) << trial;
        } else {
            ++passed;
            EXPECT_GE(least, m - tol) << trial;
        }
    }
    EXPECT_GT(met, 5);
    EXPECT_GT(passed, 5);
}

// The nozzle lying on its side (+X), turning down by a twentieth of max_turn_rad() (a piece of the
// G-code's finer pass) onto a pose whose body's lowest point is 2.05 mm over the plate (a margin
// and 2.5 %) as its tip comes down 0.05 mm: judged by its first axis alone, within the margin and
// the allowance (0.1 mm) of the plate, it is reported; given its last axis, the plate is judged
// from both ends and the move passes. A pose 1.95 mm over the plate is reported either way (given
// its last axis, at the move's end). 2.01 mm over it, both ends keep the margin, but between them
// the bound from both ends does not: the nozzle along either axis, less the allowance in
// proportion to the way, is lowest where the two bounds cross, s = (low0 - low1 + a) / 2a of the
// way (low: the lowest rim's height from the tip, the cone's end's on the first axis), and there
// it is reported.
TEST(TravelCheck, ATurningMoveIsJudgedAgainstThePlateFromBothEnds) {
    const Built b = block();
    const mas::NozzleParams p = coaxial();
    mas::TravelCheck check(b.layers, p, {Vector3d::Zero(), Vector3d::UnitZ()});
    const double turn = check.max_turn_rad() / 20.0;
    // Tilted up about -Y: its body's end higher at the start.
    const Vector3d first = Eigen::AngleAxisd(turn, -Vector3d::UnitY()) * Vector3d::UnitX();
    EXPECT_GT(first.z(), 0.0);
    auto down_onto = [&](double clearance, bool given) {
        const Vector3d to(100, 0, 25.0 + clearance);
        mas::NozzleMove move{to + Vector3d(0, 0, 0.05), to, first, turn};
        if (given) move.to_axis = Vector3d::UnitX();
        return check.meets({move});
    };
    EXPECT_TRUE(down_onto(2.05, false));
    EXPECT_FALSE(down_onto(2.05, true));
    for (const bool given : {false, true}) {
        const auto hit = down_onto(1.95, given);
        ASSERT_TRUE(hit) << given;
        EXPECT_EQ(hit->obstacle_layer, -1);
        EXPECT_NEAR(hit->obstacle.z(), 0.0, 1e-9);
    }
    const auto end = down_onto(1.95, true);
    EXPECT_NEAR((end->nozzle_at - Vector3d(100, 0, 26.95)).norm(), 0.0, 1e-9);
    const double cone_end = p.standoff_mm + mas::cone_length(p), body = 0.5 * p.body_diameter_mm;
    const double a = turn * std::hypot(cone_end + p.body_length_mm, body);
    const double low0 = cone_end * first.z() - body * first.x(), low1 = -body;
    const double s = (low0 - low1 + a) / (2.0 * a);
    ASSERT_GT(s, 0.0);
    ASSERT_LT(s, 1.0);
    const auto between = down_onto(2.01, true);
    ASSERT_TRUE(between);
    EXPECT_EQ(between->obstacle_layer, -1);
    EXPECT_NEAR((between->nozzle_at - Vector3d(100, 0, 25.0 + 2.01 + 0.05 * (1.0 - s))).norm(), 0.0,
                1e-9);
}

// Random moves near the plate, the nozzle lying within 40 degrees of its side, each turning by up
// to max_turn_rad() about a random direction, its last axis given: every move passed keeps the
// margin from the plate (the nozzle's lowest rim point taken every 1/400 of the way), and a move
// met comes within the margin and its allowance (L x its turn) of it. (Judged by the first axis
// alone, within the margin and the allowance, moves met came up to nearly twice the allowance
// further.)
TEST(TravelCheck, EveryTurningMovePassedKeepsTheMarginFromThePlate) {
    const Built b = block();
    const mas::NozzleParams p = coaxial();
    mas::TravelCheck check(b.layers, p, {Vector3d::Zero(), Vector3d::UnitZ()});
    const double m = p.margin_mm, turn = check.max_turn_rad();
    const double cone_end = p.standoff_mm + mas::cone_length(p);
    const double allowance =
        turn * std::hypot(cone_end + p.body_length_mm, 0.5 * p.body_diameter_mm);
    // The lowest point of the nozzle: a rim of the tip's face, of the cone's end or of the body's.
    auto lowest = [&](const Vector3d& tip, const Vector3d& a) {
        const double side = std::sqrt(std::max(0.0, 1.0 - a.z() * a.z()));
        double z = INFINITY;
        for (const auto& [h, r] :
             {std::pair{p.standoff_mm, 0.5 * p.tip_diameter_mm},
              std::pair{cone_end, 0.5 * p.body_diameter_mm},
              std::pair{cone_end + p.body_length_mm, 0.5 * p.body_diameter_mm}})
            z = std::min(z, tip.z() + h * a.z() - r * side);
        return z;
    };
    std::mt19937 rng(20261205);
    std::uniform_real_distribution<double> uniform(-1.0, 1.0);
    int met = 0, passed = 0;
    for (int trial = 0; trial < 400; ++trial) {
        const double heading = kPi * uniform(rng), tilt = 40.0 * mas::kDegree * uniform(rng);
        const Vector3d axis(std::cos(heading) * std::cos(tilt), std::sin(heading) * std::cos(tilt),
                            std::sin(tilt));
        const Vector3d about =
            axis.cross(Vector3d(uniform(rng), uniform(rng), uniform(rng))).normalized();
        const double by = turn * (0.5 + 0.5 * std::abs(uniform(rng)));
        const Vector3d to_axis = Eigen::AngleAxisd(by, about) * axis;
        const Vector3d from(200 * uniform(rng), 200 * uniform(rng), 0.0);
        const Vector3d to = from + Vector3d(5 * uniform(rng), 5 * uniform(rng), 2 * uniform(rng));
        // Its tip at a height where the nozzle along its first axis comes within a few mm of the
        // plate.
        const Vector3d lift(0, 0, m - lowest(from, axis) + 6.0 * uniform(rng));
        double least = INFINITY;
        for (int i = 0; i <= 400; ++i) {
            const double s = i / 400.0;
            least = std::min(least, lowest(from + lift + s * (to - from),
                                           Eigen::AngleAxisd(s * by, about) * axis));
        }
        mas::NozzleMove move{from + lift, to + lift, axis, by};
        move.to_axis = to_axis;
        if (check.meets({move})) {
            ++met;
            // Within the bound from both ends, which lies no more than its own allowance (L x
            // its turn) under the nozzle.
            EXPECT_LT(least, m + allowance / turn * by + 1e-9) << trial;
        } else {
            ++passed;
            EXPECT_GE(least, m - 1e-9) << trial;
        }
    }
    EXPECT_GT(met, 50);
    EXPECT_GT(passed, 50);
}

TEST(TravelCheck, BadMovesAreNamed) {
    const Built b = block();
    mas::TravelCheck check(b.layers, coaxial(), {Vector3d::Zero(), Vector3d::UnitZ()});
    const double turn = check.max_turn_rad();
    // The body's end's rim lies 245.9 mm from the deposit point (244.64 = 10 + 34.64 + 200 along
    // the axis, 25 across): a turn moves it 2 mm per 0.00813 rad.
    EXPECT_NEAR(turn, 2.0 / std::hypot(10.0 + 20.0 / kTan30 + 200.0, 25.0), 1e-12);
    EXPECT_EQ(error_of([&] {
                  check.meets({{Vector3d::Zero(), Vector3d::UnitX(), Vector3d::UnitZ(), 2 * turn}});
              }),
              "travel move 0 turns its tool axis by " + mas::format_number(2 * turn) +
                  " rad, where a move may turn it by 0 to " + mas::format_number(turn) + " rad");
    EXPECT_EQ(error_of([&] {
                  check.meets({{Vector3d::Zero(), Vector3d::UnitX(), Vector3d::UnitZ(), 0.0},
                               {Vector3d::Zero(), Vector3d(NAN, 0, 0), Vector3d::UnitZ(), 0.0}});
              }),
              "travel move 1 needs finite ends and a unit axis");
    EXPECT_EQ(error_of([&] {
                  check.meets({{Vector3d::Zero(), Vector3d::UnitX(), Vector3d(0, 0, 2), 0.0}});
              }),
              "travel move 0 needs finite ends and a unit axis");
    mas::NozzleMove turned{Vector3d::Zero(), Vector3d::UnitX(), Vector3d::UnitZ(), turn};
    turned.to_axis = Vector3d(0, 0, 2);
    EXPECT_EQ(error_of([&] { check.meets({turned}); }),
              "travel move 0's end axis must be a unit vector");
    turned.to_axis = Eigen::AngleAxisd(2 * turn, Vector3d::UnitX()) * Vector3d::UnitZ();
    EXPECT_EQ(error_of([&] { check.meets({turned}); }),
              "travel move 0's end axis lies " + mas::format_number(2 * turn) +
                  " rad from its axis, past its turn of " + mas::format_number(turn) + " rad");
    turned.to_axis = Eigen::AngleAxisd(turn, Vector3d::UnitX()) * Vector3d::UnitZ();
    EXPECT_FALSE(check.meets({turned}));
    EXPECT_EQ(error_of([&] { check.deposited(1); }), "the travel check has no layer 1 (it has 1)");
    mas::NozzleParams bad = coaxial();
    bad.margin_mm = -1;
    EXPECT_EQ(error_of([&] { mas::TravelCheck(b.layers, bad, {}); }),
              "the nozzle's margin must be > 0 mm, got -1");
}

}  // namespace
