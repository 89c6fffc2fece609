// The post-processor (Gcode.hpp): table angles, deposition switching, feeds and travel routes,
// read back from the program text by a small reader of the words it writes.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "mas/Angles.hpp"
#include "mas/Error.hpp"
#include "mas/Gcode.hpp"
#include "mas/SlicePart.hpp"
#include "test_parts.hpp"

namespace {

using Eigen::Vector3d;
using mas::kPi;
constexpr double kDeg = mas::kDegree;
// The program writes X Y Z A C with 4 decimals: a read-back value is within half a unit of that.
constexpr double kWord = 0.5e-4 + 1e-12;
constexpr double kInfinity() { return std::numeric_limits<double>::infinity(); }

// Where the table at (a, c) turns a part vector: LinuxCNC's xyzac-trt-kins, Rx(a) Rz(c).
Vector3d turned(const Vector3d& v, double a_deg, double c_deg) {
    return (Eigen::AngleAxisd(a_deg * kDeg, Vector3d::UnitX()) *
            Eigen::AngleAxisd(c_deg * kDeg, Vector3d::UnitZ()))
               .toRotationMatrix() *
           v;
}

struct Move {
    bool rapid = false;
    Vector3d p = Vector3d::Zero();
    double a = 0.0, c = 0.0, f = 0.0;
    bool depositing = false;  // the deposition output is on during this move
    int line = 0;
};

struct Read {
    std::vector<Move> moves;
    int m62 = 0, m63 = 0, m65 = 0;
    bool ended = false;
    std::string first_motion_line;
};

// The moves of a program as a controller runs them: modal words carried over, M62/M63 taking
// effect with the next move.
Read read_program(const std::string& text) {
    Read r;
    std::istringstream in(text);
    std::string line;
    Move state;
    bool on = false;
    int number = 0;
    while (std::getline(in, line)) {
        ++number;
        const auto open = line.find('(');
        if (open != std::string::npos) line.erase(open);
        std::istringstream words(line);
        std::string w;
        bool motion = false, rapid = false;
        while (words >> w) {
            const char letter = w[0];
            const double value = std::stod(w.substr(1));
            switch (letter) {
                case 'G':
                    if (value == 0.0 || value == 1.0) {
                        motion = true;
                        rapid = value == 0.0;
                    }
                    break;
                case 'M':
                    if (value == 62.0) {
                        on = true;
                        ++r.m62;
                    } else if (value == 63.0) {
                        on = false;
                        ++r.m63;
                    } else if (value == 65.0) {
                        on = false;
                        ++r.m65;
                    } else if (value == 2.0) {
                        r.ended = true;
                    }
                    break;
                case 'X':
                    state.p.x() = value;
                    break;
                case 'Y':
                    state.p.y() = value;
                    break;
                case 'Z':
                    state.p.z() = value;
                    break;
                case 'A':
                    state.a = value;
                    break;
                case 'C':
                    state.c = value;
                    break;
                case 'F':
                    state.f = value;
                    break;
                default:
                    break;
            }
        }
        if (motion) {
            state.rapid = rapid;
            state.depositing = on;
            state.line = number;
            r.moves.push_back(state);
        }
    }
    return r;
}

mas::ToolPath path(mas::ToolPath::Kind kind, std::vector<Vector3d> points,
                   std::vector<double> thickness) {
    mas::ToolPath p;
    p.kind = kind;
    p.points = std::move(points);
    p.thickness_mm = std::move(thickness);
    return p;
}

// A square loop of side 10 at height z around (x0, y0), 1 mm thick.
mas::GcodeLayer square_layer(int component, double x0, double y0, double z) {
    mas::GcodeLayer l;
    l.component = component;
    const std::vector<Vector3d> loop = {
        {x0, y0, z}, {x0 + 10, y0, z}, {x0 + 10, y0 + 10, z}, {x0, y0 + 10, z}, {x0, y0, z}};
    l.paths.push_back(path(mas::ToolPath::Kind::Contour, loop, std::vector<double>(5, 1.0)));
    l.outline = loop;
    l.max_thickness_mm = 1.0;
    return l;
}

// A layer deposited along +Y on the plane y = y0 (a side arm), one straight bead along X.
mas::GcodeLayer side_layer(int component, double y0) {
    mas::GcodeLayer l;
    l.component = component;
    l.tool_axis = Vector3d::UnitY();
    l.paths.push_back(path(mas::ToolPath::Kind::Infill, {{2, y0, 5}, {8, y0, 5}}, {1.0, 1.0}));
    l.outline = {{0, y0, 0}, {10, y0, 0}, {10, y0, 10}, {0, y0, 10}};
    l.max_thickness_mm = 1.0;
    return l;
}

using mas::test::error_of;

TEST(TableAngles, TurnEveryReachableAxisToTheNozzleWithinTheLimits) {
    const mas::MachineParams m;  // A -100 to 50
    std::mt19937 random(7);
    std::uniform_real_distribution<double> tilt(0.0, 100.0), turn(-180.0, 180.0);
    for (int i = 0; i < 500; ++i) {
        const double t = tilt(random) * kDeg, c = turn(random) * kDeg;
        const Vector3d n(std::sin(t) * std::cos(c), std::sin(t) * std::sin(c), std::cos(t));
        mas::TableAngles a;
        ASSERT_TRUE(mas::table_angles(n, m, 0.0, 0.0, a)) << n.transpose();
        EXPECT_LE((turned(n, a.a_deg, a.c_deg) - Vector3d::UnitZ()).norm(), 1e-12);
        EXPECT_GE(a.a_deg, m.a_min_deg);
        EXPECT_LE(a.a_deg, m.a_max_deg);
        // Past A's 50 degrees only the negative tilt reaches.
        if (t / kDeg > 50.0) {
            EXPECT_LT(a.a_deg, -50.0);
        }
    }
}

TEST(TableAngles, ExactSolutionsAndTheNearestOfTwo) {
    const mas::MachineParams m;
    mas::TableAngles a;
    // Vertical: no tilt, C stays where it was.
    ASSERT_TRUE(mas::table_angles(Vector3d::UnitZ(), m, 0.0, 37.0, a));
    EXPECT_EQ(a.a_deg, 0.0);
    EXPECT_EQ(a.c_deg, 37.0);
    // +Y needs 90 degrees: beyond A's 50, so -90 with C turned half round.
    ASSERT_TRUE(mas::table_angles(Vector3d::UnitY(), m, 0.0, 0.0, a));
    EXPECT_NEAR(a.a_deg, -90.0, 1e-12);
    EXPECT_NEAR(std::abs(a.c_deg), 180.0, 1e-12);  // as near as each other
    // 30 degrees towards -X: (30, -90) or (-30, 90); the nearer to the previous angles wins.
    const Vector3d n(-0.5, 0.0, std::sqrt(0.75));
    ASSERT_TRUE(mas::table_angles(n, m, 0.0, -80.0, a));
    EXPECT_NEAR(a.a_deg, 30.0, 1e-12);
    EXPECT_NEAR(a.c_deg, -90.0, 1e-12);
    ASSERT_TRUE(mas::table_angles(n, m, 0.0, 80.0, a));
    EXPECT_NEAR(a.a_deg, -30.0, 1e-12);
    EXPECT_NEAR(a.c_deg, 90.0, 1e-12);
    // C follows the previous C round and round rather than unwinding.
    ASSERT_TRUE(mas::table_angles(n, m, 0.0, 700.0, a));
    EXPECT_NEAR(a.c_deg, 630.0, 1e-9);
    EXPECT_NEAR(a.a_deg, 30.0, 1e-12);
    // -Z needs 180 degrees: out of reach; a table that tilts +-180 reaches it.
    EXPECT_FALSE(mas::table_angles(-Vector3d::UnitZ(), m, 0.0, 0.0, a));
    mas::MachineParams wide;
    wide.a_min_deg = -180.0;
    wide.a_max_deg = 180.0;
    ASSERT_TRUE(mas::table_angles(-Vector3d::UnitZ(), wide, 0.0, 0.0, a));
    EXPECT_NEAR(std::abs(a.a_deg), 180.0, 1e-12);
    // C limited to +-90: the solution whose C fits is taken even when A is farther.
    mas::MachineParams narrow;
    narrow.c_min_deg = -90.0;
    narrow.c_max_deg = 90.0;
    const Vector3d back(0.0, -0.5, std::sqrt(0.75));  // C = 180 or 0
    ASSERT_TRUE(mas::table_angles(back, narrow, 30.0, 0.0, a));
    EXPECT_NEAR(a.a_deg, -30.0, 1e-12);
    EXPECT_NEAR(a.c_deg, 0.0, 1e-12);
}

TEST(TableAngles, LimitsHoldUpToRoundingAndPolesKeepC) {
    // An axis exactly at C's lower limit, as atan2 rounds it (-127.00000000000001).
    const double t = 30.0 * kDeg, c = -127.0 * kDeg;
    const Vector3d n(std::sin(t) * std::sin(c), std::sin(t) * std::cos(c), std::cos(t));
    mas::MachineParams m;
    m.c_min_deg = -127.0;
    m.c_max_deg = -107.0;
    mas::TableAngles a;
    ASSERT_TRUE(mas::table_angles(n, m, 0.0, -120.0, a));
    EXPECT_EQ(a.c_deg, -127.0);
    EXPECT_NEAR(a.a_deg, 30.0, 1e-12);
    // Within 1e-7 rad of +Z (below an A word's 1e-4 degree) C stays where it was.
    ASSERT_TRUE(mas::table_angles(Vector3d(1e-8, -1e-8, 1.0).normalized(), m, 0.0, -110.0, a));
    EXPECT_EQ(a.a_deg, 0.0);
    EXPECT_EQ(a.c_deg, -110.0);
    // ... and of -Z, on a table that tilts half round: any C, so the one it had.
    mas::MachineParams wide;
    wide.a_min_deg = -180.0;
    wide.a_max_deg = 180.0;
    ASSERT_TRUE(mas::table_angles(Vector3d(1e-9, 0, -1).normalized(), wide, 0.0, 77.0, a));
    EXPECT_EQ(std::abs(a.a_deg), 180.0);
    EXPECT_EQ(a.c_deg, 77.0);
    // A previous C outside the limits (a table turned by hand): a vertical axis brings it in.
    mas::MachineParams tight;
    tight.c_min_deg = -10.0;
    tight.c_max_deg = 10.0;
    ASSERT_TRUE(mas::table_angles(Vector3d::UnitZ(), tight, 0.0, 400.0, a));
    EXPECT_EQ(a.c_deg, 10.0);
}

TEST(Gcode, DepositsEveryPathPointInOrderWithTheOutputOnAndTheTableTurnedToItsAxis) {
    // Two layers of a square tower (component 0), then a side arm deposited along +Y
    // (component 1).
    std::vector<mas::GcodeLayer> layers = {square_layer(0, 0, 0, 1), square_layer(0, 0, 0, 2),
                                           side_layer(1, 11)};
    mas::MachineParams m;
    m.max_feed_ratio = 1.0;
    mas::GcodeStats stats;
    const std::string text = mas::write_gcode(layers, m, &stats);
    const Read r = read_program(text);
    EXPECT_TRUE(r.ended);
    EXPECT_EQ(r.m62, 3);  // one per layer: each layer's loop is one path
    EXPECT_EQ(r.m63, 3);
    EXPECT_EQ(r.m65, 2);
    // The nozzle's length offset stays in force: the kinematics' tool-centre point is its tip.
    EXPECT_EQ(text.find("G49"), std::string::npos);
    EXPECT_EQ(text.find("G43"), std::string::npos);

    // The deposit moves, in order, end exactly at the paths' points after their first.
    std::vector<Vector3d> expected;
    std::vector<Vector3d> axes;
    for (const auto& l : layers)
        for (const auto& p : l.paths)
            for (std::size_t k = 1; k < p.points.size(); ++k) {
                expected.push_back(p.points[k]);
                axes.push_back(l.tool_axis);
            }
    std::vector<Move> deposits;
    for (const Move& mv : r.moves)
        if (mv.depositing) deposits.push_back(mv);
    ASSERT_EQ(deposits.size(), expected.size());
    EXPECT_EQ(stats.deposit_moves, static_cast<int>(expected.size()));
    for (std::size_t k = 0; k < deposits.size(); ++k) {
        EXPECT_FALSE(deposits[k].rapid) << "line " << deposits[k].line;
        EXPECT_LE((deposits[k].p - expected[k]).cwiseAbs().maxCoeff(), kWord) << k;
        EXPECT_LE((turned(axes[k], deposits[k].a, deposits[k].c) - Vector3d::UnitZ()).norm(), 1e-6)
            << k;
        EXPECT_EQ(deposits[k].f, 600.0);
    }
    // Each path starts with the output off at its first point, reached at G1.
    for (std::size_t k = 1; k < r.moves.size(); ++k)
        if (r.moves[k].depositing && !r.moves[k - 1].depositing) {
            EXPECT_FALSE(r.moves[k - 1].rapid);
            EXPECT_NEAR(r.moves[k - 1].f, 600.0, 0.0);
        }
    EXPECT_NEAR(stats.deposit_length_mm, 40.0 + 40.0 + 6.0, 1e-12);
    EXPECT_NEAR(stats.deposit_time_min, 86.0 / 600.0, 1e-15);
    EXPECT_EQ(stats.feed_limited_moves, 0);
    EXPECT_NEAR(stats.a_min_deg, -90.0, 1e-12);
    EXPECT_NEAR(stats.a_max_deg, 0.0, 0.0);
}

TEST(Gcode, TravelsBetweenComponentsRoundASphereClearOfEverythingDeposited) {
    std::vector<mas::GcodeLayer> layers = {square_layer(0, 0, 0, 1), square_layer(0, 0, 0, 2),
                                           side_layer(1, 11)};
    mas::MachineParams m;
    m.clearance_mm = 3.0;
    const Read r = read_program(mas::write_gcode(layers, m));
    // The moves between the tower's last deposit and the arm's first.
    std::size_t last0 = 0, first1 = 0;
    for (std::size_t k = 0; k < r.moves.size(); ++k)
        if (r.moves[k].depositing) {
            if (r.moves[k].a == 0.0) last0 = k;
            if (r.moves[k].a != 0.0 && first1 == 0) first1 = k;
        }
    ASSERT_GT(first1, last0 + 3);
    std::vector<Vector3d> material;
    for (const auto& l : layers)
        for (const Vector3d& q : l.outline) material.push_back(q);
    // Out along +Z from the tower's top, round the sphere, in along +Y to the arm: every point
    // of the route before the approach keeps more than the clearance from the material, and the
    // table turns only on the sphere.
    const Move& out = r.moves[last0 + 1];
    EXPECT_TRUE(out.rapid);
    EXPECT_NEAR(out.p.x(), r.moves[last0].p.x(), kWord);
    EXPECT_NEAR(out.p.y(), r.moves[last0].p.y(), kWord);
    EXPECT_GT(out.p.z(), 2.0 + m.clearance_mm);
    EXPECT_EQ(out.a, 0.0);
    for (const auto& l : layers)
        for (const auto& p : l.paths)
            for (const Vector3d& q : p.points) material.push_back(q);
    // The route's straight moves from the way out on, sampled, keep the clearance from every
    // point deposited (the arm's too, to come), and the table turns on the sphere, neither on
    // the way out nor on the way in.
    double top = -1e300;
    for (std::size_t k = last0 + 1; k + 2 < first1; ++k) {
        const Move& mv = r.moves[k];
        EXPECT_TRUE(mv.rapid) << "line " << mv.line;
        for (int j = k == last0 + 1 ? 20 : 0; j <= 20; ++j) {
            const Vector3d at = r.moves[k - 1].p + (mv.p - r.moves[k - 1].p) * (j / 20.0);
            for (const Vector3d& q : material)
                EXPECT_GT((at - q).norm(), m.clearance_mm) << "line " << mv.line;
        }
        top = std::max(top, mv.p.z());
    }
    EXPECT_EQ(r.moves[last0 + 1].a, 0.0);
    EXPECT_EQ(r.moves[first1 - 3].a, -90.0);
    // Level at the sphere's top, the nozzle standing along its radius: C turns only there, and A
    // only on the way down (the tower's own A is level already).
    std::size_t highest = last0 + 1;
    for (std::size_t k = last0 + 1; k + 2 < first1; ++k) {
        if (r.moves[k].p.z() > r.moves[highest].p.z()) highest = k;
        if (r.moves[k].c != r.moves[k - 1].c) {
            EXPECT_EQ(r.moves[k].a, 0.0) << "line " << r.moves[k].line;
            EXPECT_EQ(r.moves[k - 1].a, 0.0) << "line " << r.moves[k].line;
        }
    }
    EXPECT_EQ(r.moves[highest].a, 0.0);
    for (std::size_t k = highest + 1; k + 2 < first1; ++k)
        EXPECT_LE(r.moves[k].a, r.moves[k - 1].a) << "line " << r.moves[k].line;
    EXPECT_EQ(r.moves[first1 - 2].a, -90.0);
    EXPECT_GT(top, out.p.z());
    const Move& approach = r.moves[first1 - 2];
    const Move& plunge = r.moves[first1 - 1];
    EXPECT_TRUE(approach.rapid);
    EXPECT_FALSE(plunge.rapid);
    EXPECT_LE((approach.p - Vector3d(2, 11 + 3, 5)).cwiseAbs().maxCoeff(), kWord);
    EXPECT_LE((plunge.p - Vector3d(2, 11, 5)).cwiseAbs().maxCoeff(), kWord);
    EXPECT_NEAR(approach.a, -90.0, kWord);
    // Between the tower's two layers: straight up by the clearance and over.
    for (std::size_t k = 0; k < last0; ++k)
        if (r.moves[k].depositing && !r.moves[k + 1].depositing) {
            EXPECT_LE((r.moves[k + 1].p - (r.moves[k].p + Vector3d(0, 0, 3))).norm(), 2 * kWord);
            break;
        }
}

TEST(Gcode, ARouteRoundALargePartStaysOutsideItsSphereBetweenWaypoints) {
    // Two beads 2 m apart: the sphere round them has a radius of about 1 m, where a chord of 10
    // degrees sags 3.8 mm inside its ends, more than the thickness and clearance (3 mm).
    mas::GcodeLayer a, b;
    a.paths.push_back(path(mas::ToolPath::Kind::Infill, {{0, 0, 1}, {10, 0, 1}}, {1, 1}));
    a.max_thickness_mm = 1.0;
    b = a;
    b.component = 1;
    b.paths[0].points = {{2000, 0, 1}, {2010, 0, 1}};
    const Read r = read_program(mas::write_gcode({a, b}, mas::MachineParams()));
    const Vector3d centre(1005, 0, 1);
    const double bound = 1005.0 + 1.0 + 2.0;  // the farthest point, its thickness, clearance
    std::size_t last = 0, first = 0;
    for (std::size_t k = 0; k < r.moves.size(); ++k)
        if (r.moves[k].depositing && r.moves[k].p.x() < 100) last = k;
    for (first = last + 1; !r.moves[first].depositing;) ++first;
    // Out (last + 1) onto the sphere, round it, in from it (first - 3) to the approach (first -
    // 2), down to the bead (first - 1): every point of every move on the sphere.
    ASSERT_GT(first, last + 5);
    for (std::size_t k = last + 2; k <= first - 3; ++k)
        for (int j = 0; j <= 50; ++j) {
            const Vector3d at = r.moves[k - 1].p + (r.moves[k].p - r.moves[k - 1].p) * (j / 50.0);
            EXPECT_GE((at - centre).norm(), bound - 2 * kWord) << "line " << r.moves[k].line;
        }
}

TEST(Gcode, FeedFollowsTheThicknessWithinItsRange) {
    // One bead 20 mm long whose deposit thickens from 0.5 to 2 mm (a tilted layer), and one at
    // 0.1 mm, too thin for the range.
    mas::GcodeLayer l;
    l.paths.push_back(path(mas::ToolPath::Kind::Infill, {{0, 0, 1}, {20, 0, 1}}, {0.5, 2.0}));
    l.paths.push_back(path(mas::ToolPath::Kind::Infill, {{0, 5, 1}, {20, 5, 1}}, {0.1, 0.1}));
    l.outline = {{0, 0, 1}, {20, 0, 1}, {20, 5, 1}, {0, 5, 1}};
    l.max_thickness_mm = 2.0;
    mas::MachineParams m;
    m.reference_thickness_mm = 1.0;
    m.max_feed_ratio = 4.0;
    mas::GcodeStats stats;
    const Read r = read_program(mas::write_gcode({l}, m, &stats));
    std::vector<Move> first, second;
    for (const Move& mv : r.moves)
        if (mv.depositing) (mv.p.y() == 0.0 ? first : second).push_back(mv);
    // Pieces changing the thickness by a ratio of at most 1.05: ceil(ln 4 / ln 1.05) = 29.
    ASSERT_EQ(first.size(), 29u);
    Vector3d from(0, 0, 1);
    double t_from = 0.5;
    for (const Move& mv : first) {
        // Along the bead, thickness is linear in x: 0.5 + 1.5 x / 20; x is read to kWord.
        const double t_to = 0.5 + 1.5 * mv.p.x() / 20.0;
        EXPECT_LE(t_to / t_from, 1.05 + 1.5 / 20.0 * kWord / t_from) << mv.p.x();
        const double mid = 0.5 * (t_from + t_to);
        // F is written to 0.1; the feed's slope in x times x's rounding.
        EXPECT_NEAR(mv.f, 600.0 * 1.0 / mid, 0.05 + 600.0 / (mid * mid) * 1.5 / 20.0 * kWord)
            << mv.p.x();
        from = mv.p;
        t_from = t_to;
    }
    EXPECT_NEAR(from.x(), 20.0, kWord);
    // 0.1 mm would need 6000 mm/min: held at 4 x 600.
    ASSERT_EQ(second.size(), 1u);
    EXPECT_EQ(second[0].f, 2400.0);
    EXPECT_EQ(stats.feed_limited_moves, 1);
    EXPECT_EQ(stats.deposit_moves, static_cast<int>(first.size() + second.size()));
    // From 0.1 to 2 mm: held at the top feed until the thickness reaches 0.25 (x = 1.5789 mm),
    // then ceil(ln 8 / ln 1.05) = 43 pieces.
    mas::GcodeLayer tail;
    tail.paths.push_back(path(mas::ToolPath::Kind::Infill, {{0, 0, 1}, {20, 0, 1}}, {0.1, 2.0}));
    tail.max_thickness_mm = 2.0;
    mas::GcodeStats tail_stats;
    std::vector<Move> tail_moves;
    for (const Move& mv : read_program(mas::write_gcode({tail}, m, &tail_stats)).moves)
        if (mv.depositing) tail_moves.push_back(mv);
    ASSERT_EQ(tail_moves.size(), 44u);
    EXPECT_NEAR(tail_moves[0].p.x(), 20.0 * 0.15 / 1.9, kWord);
    EXPECT_EQ(tail_moves[0].f, 2400.0);
    EXPECT_EQ(tail_stats.feed_limited_moves, 1);
    EXPECT_NEAR(tail_moves.back().p.x(), 20.0, kWord);
    EXPECT_NEAR(tail_moves.back().f, 600.0 / (2.0 / std::pow(8.0, 0.5 / 43.0)), 0.05);
    // Thicknesses apart by rounding only: one move.
    mas::GcodeLayer flat;
    flat.paths.push_back(
        path(mas::ToolPath::Kind::Infill, {{0, 0, 1}, {14, 0, 1}}, {0.6328125, 0.632812500000004}));
    flat.max_thickness_mm = 0.7;
    mas::GcodeStats flat_stats;
    mas::write_gcode({flat}, m, &flat_stats);
    EXPECT_EQ(flat_stats.deposit_moves, 1);
    // A derived reference is half-way between the thinnest and thickest deposit.
    m.reference_thickness_mm = 0.0;
    mas::GcodeStats derived;
    mas::write_gcode({l}, m, &derived);
    EXPECT_NEAR(derived.reference_thickness_mm, 0.5 * (0.1 + 2.0), 1e-15);
}

TEST(Gcode, BadInputNamesTheProblem) {
    std::vector<mas::GcodeLayer> layers = {square_layer(0, 0, 0, 1), square_layer(0, 0, 0, 2)};
    mas::GcodeLayer under = square_layer(3, 0, 0, 3);
    under.tool_axis = -Vector3d::UnitZ();
    layers.push_back(under);
    EXPECT_EQ(error_of([&] { mas::write_gcode(layers, mas::MachineParams()); }),
              "unreachable_orientation: layer 2 (component 3): its tool axis (0 0 -1) needs the "
              "table tilted 180 degrees one way or the other, beyond A's limits -100 to 50");
    // A hair past A's limit reads as past it (arms 10 degrees below the horizontal, as the
    // centroids give them).
    layers.back().tool_axis = Vector3d(0.0858269, -0.981059, -0.173658).normalized();
    EXPECT_EQ(error_of([&] { mas::write_gcode(layers, mas::MachineParams()); }),
              "unreachable_orientation: layer 2 (component 3): its tool axis (0.0858269 "
              "-0.981059 -0.173658) needs the table tilted 100.0006 degrees one way or the "
              "other, beyond A's limits -100 to 50");
    // Within A's reach but not C's: the message names C and the angles it needs.
    mas::MachineParams narrow;
    narrow.c_min_deg = 0.0;
    narrow.c_max_deg = 10.0;
    layers.back().tool_axis = Vector3d::UnitX();  // A -90, C 270; or A 90 (beyond 50), C 90
    EXPECT_EQ(error_of([&] { mas::write_gcode(layers, narrow); }),
              "unreachable_orientation: layer 2 (component 3): its tool axis (1 0 0) needs C at "
              "270 degrees (plus a multiple of 360), beyond C's limits 0 to 10");
    layers.pop_back();

    auto bad = [&](auto set) {
        mas::MachineParams m;
        set(m);
        return error_of([&] { mas::write_gcode(layers, m); });
    };
    EXPECT_EQ(bad([](auto& m) { m.a_max_deg = -200; }),
              "invalid_argument: machine: A's limits must be finite with min < max, got -100 to "
              "-200 degrees");
    EXPECT_EQ(bad([](auto& m) { m.c_min_deg = NAN; }),
              "invalid_argument: machine: C's limits must be finite with min < max, got nan to "
              "36000 degrees");
    EXPECT_EQ(bad([](auto& m) { m.feed_mm_min = 0; }),
              "invalid_argument: machine: feed must be > 0 mm/min, got 0");
    EXPECT_EQ(bad([](auto& m) { m.reference_thickness_mm = -1; }),
              "invalid_argument: machine: reference thickness must be >= 0 mm (0: derived), got "
              "-1");
    EXPECT_EQ(bad([](auto& m) { m.max_feed_ratio = 0.5; }),
              "invalid_argument: machine: max feed ratio must be >= 1, got 0.5");
    EXPECT_EQ(bad([](auto& m) { m.feed_mm_min = 1e-300; }),
              "invalid_argument: machine: the feed range, feed / max feed ratio to feed x max "
              "feed ratio, must lie within 0.1 to 1e+06 mm/min, got 2.5e-301 to 4e-300");
    EXPECT_EQ(bad([](auto& m) { m.max_feed_ratio = 1e4; }),
              "invalid_argument: machine: the feed range, feed / max feed ratio to feed x max "
              "feed ratio, must lie within 0.1 to 1e+06 mm/min, got 0.06 to 6e+06");
    EXPECT_EQ(bad([](auto& m) { m.clearance_mm = INFINITY; }),
              "invalid_argument: machine: clearance must be > 0 mm, got inf");
    EXPECT_EQ(bad([](auto& m) { m.deposit_output = 64; }),
              "invalid_argument: machine: the deposition output must be a digital output 0 to "
              "63, got 64");
    EXPECT_EQ(bad([](auto& m) {
                  m.travel_min.y() = 10;
                  m.travel_max.y() = 10;
              }),
              "invalid_argument: machine: Y's travel limits must have min < max, got 10 to 10 mm");
    EXPECT_EQ(bad([](auto& m) { m.travel_max.z() = NAN; }),
              "invalid_argument: machine: Z's travel limits must have min < max, got -inf to nan "
              "mm");
    EXPECT_EQ(bad([](auto& m) { m.travel_min.x() = INFINITY; }),
              "invalid_argument: machine: X's travel limits must have min < max, got inf to inf "
              "mm");
    EXPECT_EQ(bad([](auto& m) { m.work_offset.z() = NAN; }),
              "invalid_argument: machine: the work offset's Z must be a finite length within "
              "1e+09 mm, got nan");
    EXPECT_EQ(bad([](auto& m) { m.rot_point.x() = -INFINITY; }),
              "invalid_argument: machine: the rot point's X must be a finite length within 1e+09 "
              "mm, got -inf");
    EXPECT_EQ(bad([](auto& m) { m.rot_offset_z_mm = 2e9; }),
              "invalid_argument: machine: the rot offset's Z must be a finite length within 1e+09 "
              "mm, got 2e+09");
    EXPECT_EQ(bad([](auto& m) { m.tool_length_mm = NAN; }),
              "invalid_argument: machine: the tool length must be a finite length within 1e+09 "
              "mm, got nan");

    EXPECT_EQ(error_of([] { mas::write_gcode({}, mas::MachineParams()); }),
              "empty_input: G-code: no layer has a path to deposit");
    // Layers narrower than a bead: sliced, with no path in any of them.
    std::vector<mas::GcodeLayer> pathless = {square_layer(0, 0, 0, 1), square_layer(0, 0, 0, 2)};
    for (auto& l : pathless) l.paths.clear();
    EXPECT_EQ(error_of([&] { mas::write_gcode(pathless, mas::MachineParams()); }),
              "empty_input: G-code: no layer has a path to deposit: none of the 2 layers holds a "
              "bead path (regions too narrow for the bead are listed as the slice's unfilled "
              "features; a smaller bead width may fill them)");
    pathless.pop_back();
    EXPECT_EQ(error_of([&] { mas::write_gcode(pathless, mas::MachineParams()); }),
              "empty_input: G-code: no layer has a path to deposit: its one layer holds no bead "
              "path (regions too narrow for the bead are listed as the slice's unfilled features; "
              "a smaller bead width may fill them)");
    std::vector<mas::GcodeLayer> skewed = {square_layer(0, 0, 0, 1)};
    skewed[0].tool_axis = Vector3d(0, 0, 2);
    EXPECT_EQ(error_of([&] { mas::write_gcode(skewed, mas::MachineParams()); }),
              "invalid_argument: layer 0 (component 0): its tool axis (0 0 2) is not a unit "
              "vector");
    skewed = {square_layer(0, 0, 0, 1)};
    skewed[0].paths[0].thickness_mm.pop_back();
    EXPECT_EQ(error_of([&] { mas::write_gcode(skewed, mas::MachineParams()); }),
              "invalid_argument: layer 0 (component 0): a path has 5 points and 4 thicknesses");
    skewed = {square_layer(0, 0, 0, 1)};
    skewed[0].paths[0].thickness_mm[3] = -0.5;
    EXPECT_EQ(error_of([&] { mas::write_gcode(skewed, mas::MachineParams()); }),
              "invalid_argument: layer 0 (component 0): a path's thickness -0.5 mm is negative");
    skewed = {square_layer(0, 0, 0, 1)};
    skewed[0].paths[0].points[2].x() = NAN;
    EXPECT_EQ(error_of([&] { mas::write_gcode(skewed, mas::MachineParams()); }),
              "non_finite_coordinate: layer 0 (component 0): a path point or its thickness is "
              "not finite");
}

TEST(Gcode, APathStartingWhereTheLastEndedGoesOnAndEmptyLayersAreSkipped) {
    // Layer 0: two paths, the second starting where the first ends; then a layer with nothing to
    // run (a single point, a zero-length path), then layer 2 of the same component.
    mas::GcodeLayer l0;
    l0.paths.push_back(path(mas::ToolPath::Kind::Contour, {{0, 0, 1}, {10, 0, 1}}, {1, 1}));
    l0.paths.push_back(path(mas::ToolPath::Kind::Infill, {{10, 0, 1}, {10, 10, 1}}, {1, 1}));
    l0.max_thickness_mm = 1.0;
    mas::GcodeLayer empty;
    empty.paths.push_back(path(mas::ToolPath::Kind::CentreLine, {{5, 5, 2}}, {1}));
    empty.paths.push_back(path(mas::ToolPath::Kind::Infill, {{5, 5, 2}, {5, 5, 2}}, {1, 1}));
    empty.max_thickness_mm = 1.0;
    mas::GcodeLayer l2 = square_layer(0, 0, 0, 2);
    const std::string text = mas::write_gcode({l0, empty, l2}, mas::MachineParams());
    const Read r = read_program(text);
    EXPECT_EQ(r.m62, 2);  // layer 0 in one run, layer 2 in another
    EXPECT_EQ(r.m63, 2);
    EXPECT_EQ(text.find("(layer 1,"), std::string::npos);
    EXPECT_NE(text.find("(layer 2,"), std::string::npos);
    std::vector<Move> deposits;
    for (const Move& mv : r.moves)
        if (mv.depositing) deposits.push_back(mv);
    ASSERT_EQ(deposits.size(), 2u + 4u);
    EXPECT_LE((deposits[1].p - Vector3d(10, 10, 1)).norm(), kWord);
    // Layer 0 to layer 2: up by the clearance from (10, 10, 1), over to (0, 0, 2) + 2, down.
    std::size_t k = 0;
    while (!(r.moves[k].depositing && !r.moves[k + 1].depositing)) ++k;
    EXPECT_LE((r.moves[k + 1].p - Vector3d(10, 10, 3)).norm(), kWord);
    EXPECT_LE((r.moves[k + 2].p - Vector3d(0, 0, 4)).norm(), kWord);
    EXPECT_LE((r.moves[k + 3].p - Vector3d(0, 0, 2)).norm(), kWord);
    // The layer's name comes after the last one's deposition stopped.
    EXPECT_LT(text.find("M63"), text.find("(layer 2,"));
}

TEST(Gcode, PointsCloserThanTheWordsResolveMakeNoMove) {
    // 3e-5 mm apart: both read (10.0000, 0.0000, 1.0000).
    mas::GcodeLayer l;
    l.paths.push_back(path(mas::ToolPath::Kind::Contour,
                           {{0, 0, 1}, {10, 0, 1}, {10, 3e-5, 1}, {10, 10, 1}}, {1, 1, 1, 1}));
    l.max_thickness_mm = 1.0;
    mas::GcodeStats stats;
    const Read r = read_program(mas::write_gcode({l}, mas::MachineParams(), &stats));
    std::vector<Move> deposits;
    for (const Move& mv : r.moves)
        if (mv.depositing) deposits.push_back(mv);
    ASSERT_EQ(deposits.size(), 2u);
    EXPECT_EQ(stats.deposit_moves, 2);
    EXPECT_NEAR(stats.deposit_length_mm, 20.0, 1e-12);  // the tiny step counted all the same
    EXPECT_LE((deposits[1].p - Vector3d(10, 10, 1)).norm(), kWord);
}

TEST(Gcode, CancelsBetweenLayers) {
    std::vector<mas::GcodeLayer> layers = {square_layer(0, 0, 0, 1), square_layer(0, 0, 0, 2)};
    int calls = 0;
    const mas::Progress progress([&](double, const std::string&) {
        if (++calls == 2) throw mas::Error(mas::ErrorCode::Cancelled, "stop");
    });
    EXPECT_EQ(error_of([&] { mas::write_gcode(layers, mas::MachineParams(), nullptr, progress); }),
              "cancelled: stop");
}

TEST(Gcode, ASlicedLBlockDepositsEveryPathOfEveryLayer) {
    // The L-block's arm is built sideways: the table turns to every layer's normal, and every
    // deposit point of the slicer is reached, in build order.
    mas::TessellationParams tp;
    tp.deflection_mm = 0.05;
    const mas::Shape part = mas::test::l_block();
    const mas::CentroidalAxis axis = mas::centroidal_axis(mas::tessellate(part, tp));
    const mas::Decomposition d = mas::decompose(part, axis);
    mas::SlicePartParams p;
    p.tessellation = tp;
    const mas::SlicedPart sliced = mas::slice_part(part, axis, d, p);
    ASSERT_GE(sliced.components.size(), 2u);
    const std::vector<mas::GcodeLayer> layers = mas::gcode_layers(sliced);
    mas::GcodeStats stats;
    const Read r = read_program(mas::write_gcode(layers, mas::MachineParams(), &stats));
    std::vector<Vector3d> expected, axes;
    double length = 0.0;
    for (const auto& l : layers)
        for (const auto& path : l.paths) {
            if (!path.deposit()) continue;
            for (std::size_t k = 1; k < path.points.size(); ++k) {
                if ((path.points[k] - path.points[k - 1]).norm() < 1e-9) continue;
                expected.push_back(path.points[k]);
                axes.push_back(l.tool_axis);
                length += (path.points[k] - path.points[k - 1]).norm();
            }
        }
    // Pieces of a move end on it: the expected points are the ends of runs of moves.
    std::size_t e = 0;
    bool turned_away = false;
    for (const Move& mv : r.moves) {
        if (!mv.depositing) continue;
        ASSERT_LT(e, expected.size());
        EXPECT_LE((turned(axes[e], mv.a, mv.c) - Vector3d::UnitZ()).norm(), 1e-5);
        turned_away = turned_away || mv.a != 0.0;
        if ((mv.p - expected[e]).cwiseAbs().maxCoeff() <= kWord) ++e;
    }
    EXPECT_EQ(e, expected.size());
    EXPECT_TRUE(turned_away);
    EXPECT_NEAR(stats.deposit_length_mm, length, 1e-6 * length);
    EXPECT_NEAR(stats.deposit_length_mm, sliced.stats.deposit_length_mm,
                1e-9 * sliced.stats.deposit_length_mm);
}

// Gives `l` its prism: the polygons `loops` (each an outer boundary, on the plane of normal `n`
// through their points) swept down `thickness` along n.
void set_prism(mas::GcodeLayer& l, const Vector3d& n,
               const std::vector<std::vector<Vector3d>>& loops, double thickness) {
    l.prism = mas::test::flat_layer(l.component, n, loops, thickness);
    l.outline.clear();
    for (const auto& loop : loops) l.outline.insert(l.outline.end(), loop.begin(), loop.end());
    l.max_thickness_mm = thickness;
}

// The rectangle [x0, x1] x [y0, y1] at height z, counter-clockwise from above.
std::vector<Vector3d> rectangle(double x0, double y0, double x1, double y1, double z) {
    return {{x0, y0, z}, {x1, y0, z}, {x1, y1, z}, {x0, y1, z}};
}

// The tool axis the table at (a, c) turns up to the nozzle (+Z): its inverse applied to +Z.
Vector3d axis_at(double a_deg, double c_deg) {
    return (Eigen::AngleAxisd(a_deg * kDeg, Vector3d::UnitX()) *
            Eigen::AngleAxisd(c_deg * kDeg, Vector3d::UnitZ()))
               .toRotationMatrix()
               .transpose() *
           Vector3d::UnitZ();
}

// The least clearance (mas::test::nozzle_clearance) of `surface` from the nozzle along the
// program's moves [first, last], each from the move before it, X Y Z A C in proportion, sampled
// every 0.1 mm and 0.05 degrees.
double least_clearance(const mas::NozzleParams& p, const Read& r, std::size_t first,
                       std::size_t last, const std::vector<Vector3d>& surface) {
    double least = INFINITY;
    for (std::size_t k = std::max<std::size_t>(first, 1); k <= last; ++k) {
        const Move &a = r.moves[k - 1], &b = r.moves[k];
        const int steps =
            std::max({1, int(std::ceil((b.p - a.p).norm() / 0.1)),
                      int(std::ceil((std::abs(b.a - a.a) + std::abs(b.c - a.c)) / 0.05))});
        for (int i = 0; i <= steps; ++i) {
            const double s = double(i) / steps;
            const Vector3d tip = a.p + s * (b.p - a.p);
            const Vector3d axis = axis_at(a.a + s * (b.a - a.a), a.c + s * (b.c - a.c));
            for (const Vector3d& q : surface)
                least = std::min(least, mas::test::nozzle_clearance(p, tip, axis, q));
        }
    }
    return least;
}

// Points of the box [x0, x1] x [y0, y1] x [z0, z1]'s surface, every `step` mm or closer.
std::vector<Vector3d> box_surface(double x0, double y0, double z0, double x1, double y1, double z1,
                                  double step) {
    std::vector<Vector3d> out;
    auto count = [&](double length) { return std::max(1, int(std::ceil(length / step))); };
    const int nx = count(x1 - x0), ny = count(y1 - y0), nz = count(z1 - z0);
    for (int i = 0; i <= nx; ++i)
        for (int j = 0; j <= ny; ++j)
            for (int k = 0; k <= nz; ++k)
                if (i == 0 || i == nx || j == 0 || j == ny || k == 0 || k == nz)
                    out.emplace_back(x0 + (x1 - x0) * i / nx, y0 + (y1 - y0) * j / ny,
                                     z0 + (z1 - z0) * k / nz);
    return out;
}

// A wall 30 mm tall (component 0) between the two paths of a later layer of component 1: the
// way between them over the wall at the clearance would drive the nozzle through it; the program
// goes round the part instead, which keeps the margin (the nozzle's own shape, checked here).
TEST(Gcode, AWayWithinAComponentThatMeetsADepositedLayerGoesRoundThePart) {
    mas::GcodeLayer wall;
    wall.index = 0;
    wall.component = 0;
    wall.paths.push_back(
        path(mas::ToolPath::Kind::Contour, {{0, -18, 30}, {0, 18, 30}}, {30.0, 30.0}));
    set_prism(wall, Vector3d::UnitZ(), {rectangle(-2, -20, 2, 20, 30)}, 30.0);
    mas::GcodeLayer pads;
    pads.index = 1;
    pads.component = 1;
    pads.paths.push_back(path(mas::ToolPath::Kind::Contour, {{-35, -5, 2}, {-35, 5, 2}}, {2, 2}));
    pads.paths.push_back(path(mas::ToolPath::Kind::Contour, {{35, 5, 2}, {35, -5, 2}}, {2, 2}));
    set_prism(pads, Vector3d::UnitZ(), {rectangle(-37, -6, -33, 6, 2), rectangle(33, -6, 37, 6, 2)},
              2.0);
    const std::vector<mas::GcodeLayer> layers = {wall, pads};
    const mas::TravelNozzle nozzle{mas::NozzleParams(), {Vector3d::Zero(), Vector3d::UnitZ()}};
    const mas::MachineParams m;
    mas::GcodeStats stats;
    const std::string text = mas::write_gcode(layers, m, &stats, {}, &nozzle);
    EXPECT_EQ(stats.checked_routes, 4);  // to the wall, to the pads, between them, off the part
    EXPECT_EQ(stats.rerouted_travels, 1);
    EXPECT_TRUE(stats.travel_collisions.empty());
    EXPECT_NE(text.find("(the way within the component meets layer 0: round the part instead)"),
              std::string::npos);
    const std::vector<Vector3d> surface = box_surface(-2, -20, 0, 2, 20, 30, 0.5);
    // The moves from the first pad's end to the second's start.
    auto between_pads = [](const Read& r) {
        std::size_t end = 0, start = 0;
        for (std::size_t k = 0; k < r.moves.size(); ++k) {
            if (r.moves[k].depositing && r.moves[k].p.x() < -30) end = k;
            if (r.moves[k].depositing && r.moves[k].p.x() > 30 && start == 0) start = k;
        }
        return std::pair{end + 1, start - 1};
    };
    const Read r = read_program(text);
    const auto [first, last] = between_pads(r);
    ASSERT_LT(first, last);
    double top = -INFINITY;
    for (std::size_t k = first; k <= last; ++k) top = std::max(top, r.moves[k].p.z());
    EXPECT_GT(top, 60.0);  // over the sphere round the part
    // Within the margin's sampling: the wall's surface every 0.5 mm is within 0.36 mm of all of it.
    EXPECT_GE(least_clearance(nozzle.params, r, first, last, surface),
              nozzle.params.margin_mm - 0.36);
    // Unchecked, the way goes straight over at the clearance, through the wall.
    const Read direct = read_program(mas::write_gcode(layers, m));
    const auto [d0, d1] = between_pads(direct);
    EXPECT_EQ(d1 - d0, 2u);  // up, across, down
    EXPECT_LT(least_clearance(nozzle.params, direct, d0, d1, surface), 0.0);
}

// A sideways layer 10 mm over the plate: the nozzle's body lies 15 mm under it, whichever way it
// goes. Every route is kept and reported: into the layer, between its paths (round the part it
// meets the plate too), and off the part.
TEST(Gcode, ARouteMeetingSomethingEvenRoundThePartIsReported) {
    mas::GcodeLayer side;
    side.index = 7;
    side.tool_axis = Vector3d::UnitX();
    side.paths.push_back(path(mas::ToolPath::Kind::Infill, {{0, -10, 10}, {0, -4, 10}}, {1, 1}));
    side.paths.push_back(path(mas::ToolPath::Kind::Infill, {{0, 4, 10}, {0, 10, 10}}, {1, 1}));
    set_prism(side, Vector3d::UnitX(), {{{0, -10, 8}, {0, 10, 8}, {0, 10, 12}, {0, -10, 12}}}, 1.0);
    const mas::TravelNozzle nozzle{mas::NozzleParams(), {Vector3d::Zero(), Vector3d::UnitZ()}};
    mas::GcodeStats stats;
    const std::string text = mas::write_gcode({side}, mas::MachineParams(), &stats, {}, &nozzle);
    EXPECT_EQ(stats.checked_routes, 3);
    EXPECT_EQ(stats.rerouted_travels, 0);
    ASSERT_EQ(stats.travel_collisions.size(), 3u);
    for (std::size_t k = 0; k < 3; ++k) {
        const mas::TravelCollision& c = stats.travel_collisions[k];
        EXPECT_EQ(c.layer, k < 2 ? 7 : -1);
        EXPECT_EQ(c.obstacle_layer, -1);
        EXPECT_NEAR(c.obstacle.z(), 0.0, 1e-9);
        // The body's lowest point, 25 mm under the tip, is what comes within the margin.
        EXPECT_LT(c.nozzle_at.z() - 25.0, 2.0);
    }
    auto count = [&](const std::string& what) {
        std::size_t n = 0;
        for (std::size_t at = text.find(what); at != std::string::npos;
             at = text.find(what, at + 1))
            ++n;
        return n;
    };
    EXPECT_EQ(count("(warning: on the way to layer 7 the nozzle meets the build plate near "), 2u);
    EXPECT_EQ(count("(warning: on the way off the part the nozzle meets the build plate near "),
              1u);
    // Unchecked, the same program without the warnings (and without the line saying where the
    // build plate is, which only a program given the plate says).
    std::string unchecked = mas::write_gcode({side}, mas::MachineParams());
    std::string stripped;
    std::istringstream lines(text);
    for (std::string line; std::getline(lines, line);)
        if (line.rfind("(warning:", 0) != 0 && line.rfind("(build plate:", 0) != 0)
            stripped += line + "\n";
    EXPECT_EQ(stripped, unchecked);
}

// Off the part the table turns level on the way to the sphere's top: the sliced L-block's last
// layer, at the end of its arm reaching +X, would leave the nozzle lying along +X at the top,
// its cone within the margin of the arm's end; level, it keeps clear, and the check meets
// nothing on the whole program.
TEST(Gcode, OffThePartTheTableTurnsLevel) {
    mas::TessellationParams tp;
    tp.deflection_mm = 0.05;
    const mas::Shape part = mas::test::l_block();
    const mas::CentroidalAxis axis = mas::centroidal_axis(mas::tessellate(part, tp));
    mas::SlicePartParams p;
    p.tessellation = tp;
    const mas::SlicedPart sliced = mas::slice_part(part, axis, mas::decompose(part, axis), p);
    const mas::TravelNozzle nozzle{p.nozzle, sliced.plate};
    mas::GcodeStats stats;
    const Read r = read_program(
        mas::write_gcode(mas::gcode_layers(sliced), mas::MachineParams(), &stats, {}, &nozzle));
    EXPECT_TRUE(stats.travel_collisions.empty());
    EXPECT_EQ(stats.rerouted_travels, 0);
    std::size_t last = 0;
    for (std::size_t k = 0; k < r.moves.size(); ++k)
        if (r.moves[k].depositing) last = k;
    ASSERT_NEAR(r.moves[last].a, -90.0, kWord);  // the arm's end, deposited along +X
    EXPECT_EQ(r.moves.back().a, 0.0);
    for (std::size_t k = last + 2; k < r.moves.size(); ++k)
        EXPECT_LE(std::abs(r.moves[k].a), std::abs(r.moves[k - 1].a)) << "line " << r.moves[k].line;
    // The arm [20, 70] x [0, 20] x [40, 60]: the route off it keeps the margin.
    EXPECT_GE(least_clearance(p.nozzle, r, last + 1, r.moves.size() - 1,
                              box_surface(20, 0, 40, 70, 20, 60, 0.5)),
              p.nozzle.margin_mm - 0.36);
}

// The machine's joints (Gcode.hpp, "The machine's X Y Z travel"): the part's point moved by the
// work offset, turned by C about the vertical line through the rot point, tilted by A about the
// line along X through the rot point's y and z plus the offsets, the tool length on Z.
TEST(Gcode, MachinePositionTurnsThePartAboutTheTablesAxes) {
    mas::MachineParams m;
    m.work_offset = {100, 50, -20};
    m.tool_length_mm = 30;
    EXPECT_EQ(mas::machine_position({1, 2, 3}, {0, 0}, m), Vector3d(101, 52, 13));
    m = mas::MachineParams();
    m.rot_point = {10, 0, 7};  // C's axis: x = 10, y = 0 (the rot point's z is A's)
    EXPECT_LE((mas::machine_position({20, 0, 0}, {0, 90}, m) - Vector3d(10, 10, 0)).norm(), 1e-12);
    m = mas::MachineParams();
    m.rot_point = {0, 0, 2};
    m.rot_offset_y_mm = 5;  // A's axis: y = 5, z = 2 + 3
    m.rot_offset_z_mm = 3;
    // 10 mm over A's axis, tilted 90 degrees: 10 mm towards -Y of it.
    EXPECT_LE((mas::machine_position({0, 5, 15}, {90, 0}, m) - Vector3d(0, -5, 5)).norm(), 1e-12);
    // C's axis stays where the rot point puts it however the A axis is offset.
    EXPECT_LE((mas::machine_position({0, 0, 5}, {0, 180}, m) - Vector3d(0, 0, 5)).norm(), 1e-12);
}

// The joints' ranges are those of the moves the program makes (the first from its end), and a
// limit the program passes is an error naming the axis, the range, the limit and the layer.
TEST(Gcode, TheMachinesTravelIsReportedAndCheckedAgainstItsLimits) {
    // A square tower (A 0, C 0 throughout): the joints are the program's points moved by G54 and
    // the tool length, and its moves are straight in them.
    std::vector<mas::GcodeLayer> layers = {square_layer(0, 0, 0, 1), square_layer(0, 0, 0, 2)};
    mas::MachineParams m;
    m.work_offset = {100, 50, -20};
    m.tool_length_mm = 30;
    mas::GcodeStats stats;
    const std::string text = mas::write_gcode(layers, m, &stats);
    EXPECT_EQ(text.find("machine travel checked"), std::string::npos);  // no limits given
    const Read r = read_program(text);
    Vector3d lo = r.moves.front().p, hi = lo;
    for (const Move& mv : r.moves) {
        ASSERT_EQ(mv.a, 0.0);
        ASSERT_EQ(mv.c, 0.0);
        lo = lo.cwiseMin(mv.p);
        hi = hi.cwiseMax(mv.p);
    }
    const Vector3d shift(100, 50, 10);
    EXPECT_LE((stats.machine_min - (lo + shift)).cwiseAbs().maxCoeff(), kWord);
    EXPECT_LE((stats.machine_max - (hi + shift)).cwiseAbs().maxCoeff(), kWord);
    EXPECT_NEAR(stats.machine_min.x(), 100.0, kWord);  // the square's sides
    EXPECT_NEAR(stats.machine_max.y(), 60.0, kWord);
    EXPECT_NEAR(stats.machine_min.z(), 11.0, kWord);  // the first layer's plane, 1 + 10
    // Limits met exactly pass; the header says what was checked.
    mas::MachineParams limited = m;
    limited.travel_min = stats.machine_min;
    limited.travel_max = stats.machine_max;
    mas::GcodeStats again;
    const std::string checked = mas::write_gcode(layers, limited, &again);
    EXPECT_EQ(again.machine_max, stats.machine_max);
    EXPECT_NE(checked.find("(machine travel checked: X 100 to 110, Y 50 to 60, Z 11 to "),
              std::string::npos);
    // Past them, an error: the sphere's top is the highest point, reached on the way to the
    // first layer.
    limited.travel_max.z() -= 0.01;
    limited.travel_min.x() = -kInfinity();
    limited.travel_max.x() = kInfinity();
    EXPECT_EQ(error_of([&] { mas::write_gcode(layers, limited); }),
              "out_of_travel: the program leaves the machine's travel (G54 at (100 50 -20)): it "
              "takes Z from 11 to " +
                  mas::format_number(stats.machine_max.z(), 7) + " mm, beyond the Z limits 11 to " +
                  mas::format_number(stats.machine_max.z() - 0.01) +
                  ", first at layer 0 (component 0); move the part on the table (the work offset) "
                  "or slice it otherwise");
    // Two axes past their limits, one limit only: each named.
    limited = m;
    limited.travel_max.x() = 105;
    limited.travel_min.y() = 55;
    EXPECT_EQ(error_of([&] { mas::write_gcode(layers, limited); }),
              "out_of_travel: the program leaves the machine's travel (G54 at (100 50 -20)): it "
              "takes X from 100 to 110 mm, above the greatest X 105, first at layer 0 (component "
              "0); it takes Y from 50 to 60 mm, below the least Y 55, first at layer 0 (component "
              "0); move the part on the table (the work offset) or slice it otherwise");
}

// Where the table turns, the joints move on arcs: the range is taken along them, not only at the
// moves' ends.
TEST(Gcode, TheMachinesTravelFollowsTheTableAsItTurns) {
    std::vector<mas::GcodeLayer> layers = {square_layer(0, 0, 0, 1), square_layer(0, 0, 0, 2),
                                           side_layer(1, 11)};
    mas::MachineParams m;
    m.work_offset = {-40, 30, 25};
    m.rot_point = {5, -10, 8};
    m.rot_offset_y_mm = 20;
    m.rot_offset_z_mm = 10;
    mas::GcodeStats stats;
    const Read r = read_program(mas::write_gcode(layers, m, &stats));
    // The joints along every move, XYZAC in proportion, 4000 points a move; and at its ends only.
    Vector3d lo = Vector3d::Constant(1e300), hi = -lo, lo_ends = lo, hi_ends = hi;
    double reach = 0.0;  // the farthest the joints come from the axes
    for (std::size_t k = 0; k < r.moves.size(); ++k) {
        const Move& b = r.moves[k];
        const Move& a = k ? r.moves[k - 1] : b;
        for (int i = 0; i <= 4000; ++i) {
            const double s = i / 4000.0;
            const Vector3d j = mas::machine_position(
                a.p + s * (b.p - a.p), {a.a + s * (b.a - a.a), a.c + s * (b.c - a.c)}, m);
            lo = lo.cwiseMin(j);
            hi = hi.cwiseMax(j);
            reach = std::max(reach, (j - Vector3d(5, -10, 8)).norm() + 30.0);
        }
        const Vector3d j = mas::machine_position(b.p, {b.a, b.c}, m);
        lo_ends = lo_ends.cwiseMin(j);
        hi_ends = hi_ends.cwiseMax(j);
    }
    // Within the words' rounding (a position's 0.5e-4 mm, an angle's 0.5e-4 degrees at the reach),
    // and 1e-5 of the reach between the engine's samples.
    const double tol = kWord + reach * (0.5e-4 * kDeg + 1e-5);
    EXPECT_LE((stats.machine_min - lo).cwiseAbs().maxCoeff(), tol);
    EXPECT_LE((stats.machine_max - hi).cwiseAbs().maxCoeff(), tol);
    // The arcs reach past the moves' ends here: ends alone would miss it.
    EXPECT_GT((lo_ends - lo).maxCoeff() + (hi - hi_ends).maxCoeff(), 10 * tol);
}

// Where nothing is met, the check changes nothing in the program.
TEST(Gcode, WhereNothingIsMetTheCheckedProgramIsTheSame) {
    std::vector<mas::GcodeLayer> layers = {square_layer(0, 0, 0, 1), square_layer(0, 0, 0, 2),
                                           square_layer(1, 100, 0, 1)};
    set_prism(layers[0], Vector3d::UnitZ(), {rectangle(0, 0, 10, 10, 1)}, 1.0);
    set_prism(layers[1], Vector3d::UnitZ(), {rectangle(0, 0, 10, 10, 2)}, 1.0);
    set_prism(layers[2], Vector3d::UnitZ(), {rectangle(100, 0, 110, 10, 1)}, 1.0);
    const mas::TravelNozzle nozzle{mas::NozzleParams(), {Vector3d::Zero(), Vector3d::UnitZ()}};
    mas::GcodeStats stats;
    // The same program, but for the line that says where the build plate is (only a program given
    // the plate knows it).
    const std::string plate_line =
        "(build plate: the part stands on its plane Z0; set G54's Z on the plate's surface)\n";
    std::string checked = mas::write_gcode(layers, mas::MachineParams(), &stats, {}, &nozzle);
    const std::size_t at = checked.find(plate_line);
    ASSERT_NE(at, std::string::npos);
    checked.erase(at, plate_line.size());
    EXPECT_EQ(checked, mas::write_gcode(layers, mas::MachineParams()));
    EXPECT_EQ(stats.checked_routes, 4);
    EXPECT_EQ(stats.rerouted_travels, 0);
    EXPECT_TRUE(stats.travel_collisions.empty());
    mas::TravelNozzle bad = nozzle;
    bad.params.body_length_mm = 0.0;
    EXPECT_EQ(error_of([&] { mas::write_gcode(layers, mas::MachineParams(), nullptr, {}, &bad); }),
              "invalid_argument: the nozzle's body length must be > 0 mm, got 0");
    // The clearance at most 1e4 margins (20 m at the default 2 mm) where the travel is checked:
    // the check walks the routes in fractions of a margin (1e9 mm ran past a minute). Without a
    // check, any.
    mas::MachineParams far;
    far.clearance_mm = 20000.0;
    EXPECT_EQ(error_of([&] { mas::write_gcode(layers, far, nullptr, {}, &nozzle); }), "no error");
    far.clearance_mm = 20000.5;
    EXPECT_EQ(error_of([&] { mas::write_gcode(layers, far, nullptr, {}, &nozzle); }),
              "invalid_argument: machine: clearance 20000.5 mm is more than 10000 times the "
              "nozzle's margin (2 mm): the travel check walks the routes in fractions of a margin");
    far.clearance_mm = 1e9;
    EXPECT_EQ(error_of([&] { mas::write_gcode(layers, far); }), "no error");
}

// A part modelled off the plane Z = 0 keeps its coordinates in the program, so the header says
// where it stands and how the work offset takes that: a part standing at Z 7.5 (modelled above the
// origin) has G54's Z 7.5 mm below the plate's surface, one centred on its origin (standing at
// Z -10) 10 mm above it. The moves are the part's coordinates whatever the plate.
TEST(Gcode, TheHeaderSaysWhereThePartStandsAndHowG54TakesIt) {
    auto header = [](double z, const Vector3d& normal = Vector3d::UnitZ()) {
        std::vector<mas::GcodeLayer> layers = {square_layer(0, 0, 0, z + 1.0)};
        set_prism(layers[0], Vector3d::UnitZ(), {rectangle(0, 0, 10, 10, z + 1.0)}, 1.0);
        const mas::TravelNozzle nozzle{mas::NozzleParams(), {Vector3d(3, 4, z), normal}};
        const std::string text =
            mas::write_gcode(layers, mas::MachineParams(), nullptr, {}, &nozzle);
        std::istringstream in(text);
        std::string line, plate = "no build plate line", rest;
        while (std::getline(in, line))
            if (line.rfind("(build plate:", 0) == 0)
                plate = line;
            else
                rest += line + "\n";
        // Standing on a plane of Z, nothing is met on the way: the program is the one written
        // without the plate but for that line.
        if (normal == Vector3d::UnitZ()) {
            EXPECT_EQ(rest, mas::write_gcode(layers, mas::MachineParams()));
        }
        return plate;
    };
    EXPECT_EQ(header(7.5),
              "(build plate: the part stands on its plane Z7.5; set G54's Z 7.5 mm below the "
              "plate's surface)");
    EXPECT_EQ(header(-10.0),
              "(build plate: the part stands on its plane Z-10; set G54's Z 10 mm above the "
              "plate's surface)");
    EXPECT_EQ(header(-0.0),
              "(build plate: the part stands on its plane Z0; set G54's Z on the plate's surface)");
    // To the 4 decimals of the program's words: a curved underside whose lowest point lies 6
    // microns over the plane the part was placed on by a loose box, and noise at zero.
    EXPECT_EQ(header(0.00619372),
              "(build plate: the part stands on its plane Z0.0062; set G54's Z 0.0062 mm below "
              "the plate's surface)");
    EXPECT_EQ(header(-3e-13),
              "(build plate: the part stands on its plane Z0; set G54's Z on the plate's surface)");
    // A plate the slicing never gives (it stands the part on Z): said as the plane it is.
    EXPECT_EQ(header(2.0, Vector3d::UnitX()),
              "(build plate: the plane through 3 4 2 square to 1 0 0 in the part's coordinates)");
    // Without the plate nothing is said of it.
    std::vector<mas::GcodeLayer> layers = {square_layer(0, 0, 0, 1.0)};
    EXPECT_EQ(mas::write_gcode(layers, mas::MachineParams()).find("build plate"),
              std::string::npos);
}

// A wall 10 mm tall (component 0), and beside it two layers of component 1, the second leaned 30
// degrees towards the wall: between them the table tilts (A 0 to -30), the nozzle swinging towards
// the wall's edge. At every distance the way is taken round the part, or reported (nearer, the
// second layer itself meets the wall), only where the nozzle comes within twice the margin, the
// step and the finer pieces' allowance (4.3 mm) of the wall, by its own shape; and some of the
// distances tried bring it between that and the 6.1 mm within which the coarse pieces alone would
// have met it.
TEST(Gcode, ATurningWayIsJudgedInFinerPiecesBeforeItGoesRoundThePart) {
    const mas::NozzleParams p;
    const mas::TravelNozzle nozzle{p, {Vector3d::Zero(), Vector3d::UnitZ()}};
    const Vector3d n2(0.0, -0.5, std::sqrt(0.75));
    const std::vector<Vector3d> surface = box_surface(-10, -10, 0, 10, 10, 10, 0.5);
    int in_band = 0, met = 0;
    // The nozzle comes nearest where the second layer is deposited: 4.05 + (y0 - 29.75) / 2 mm.
    for (const double y0 : {24.0, 27.0, 29.0, 30.0, 30.5, 31.0, 31.25, 31.5, 32.0}) {
        mas::GcodeLayer wall;
        wall.index = 0;
        wall.paths.push_back(
            path(mas::ToolPath::Kind::Contour, {{-5, 0, 10}, {5, 0, 10}}, {10.0, 10.0}));
        set_prism(wall, Vector3d::UnitZ(), {rectangle(-10, -10, 10, 10, 10)}, 10.0);
        mas::GcodeLayer first;
        first.index = 1;
        first.component = 1;
        first.paths.push_back(
            path(mas::ToolPath::Kind::Contour, {{-2, y0, 2}, {2, y0, 2}}, {2.0, 2.0}));
        set_prism(first, Vector3d::UnitZ(), {rectangle(-4, y0 - 2, 4, y0 + 2, 2)}, 2.0);
        mas::GcodeLayer second;
        second.index = 2;
        second.component = 1;
        second.tool_axis = n2;
        second.paths.push_back(
            path(mas::ToolPath::Kind::Contour, {{2, y0, 2.5}, {-2, y0, 2.5}}, {0.5, 0.5}));
        second.prism = first.prism;  // not deposited before the way checked here
        const std::vector<mas::GcodeLayer> layers = {wall, first, second};
        mas::GcodeStats stats;
        mas::write_gcode(layers, mas::MachineParams(), &stats, {}, &nozzle);
        // The way between the two layers, unchecked: the retract, the tilt, the plunge.
        const Read r = read_program(mas::write_gcode(layers, mas::MachineParams()));
        std::size_t end = 0, start = 0;
        for (std::size_t k = 0; k < r.moves.size(); ++k) {
            if (r.moves[k].depositing && r.moves[k].a == 0.0 && r.moves[k].p.y() > 1.0) end = k;
            if (r.moves[k].depositing && r.moves[k].a != 0.0 && start == 0) start = k;
        }
        ASSERT_EQ(start, end + 4) << y0;
        EXPECT_NEAR(r.moves[start].a, -30.0, kWord);
        const double least = least_clearance(p, r, end + 1, start - 1, surface);
        if (stats.rerouted_travels > 0 || !stats.travel_collisions.empty()) {
            ++met;
            EXPECT_LT(least, 2.15 * p.margin_mm + 0.41) << y0;
        } else {
            EXPECT_GE(least, p.margin_mm - 0.36) << y0;
        }
        if (least > 2.15 * p.margin_mm + 0.41 && least < 6.1) ++in_band;
    }
    EXPECT_GT(met, 0);
    EXPECT_GT(in_band, 0);
}

// A margin of half the standoff: every way out of a layer starts with the nozzle's face 2 margins
// over it, which the check's grown nozzle counts; leaving along the tool axis, it keeps the margin
// and is not reported, on a tower and round to a second component. The routes keep it, by the
// nozzle's own shape.
TEST(Gcode, AWayOutAlongTheToolAxisIsNotReportedAgainstTheLayerItLeaves) {
    std::vector<mas::GcodeLayer> layers = {square_layer(0, 0, 0, 1), square_layer(0, 0, 0, 2),
                                           square_layer(0, 0, 0, 3), square_layer(1, 60, 0, 1)};
    for (int k = 0; k < 3; ++k)
        set_prism(layers[std::size_t(k)], Vector3d::UnitZ(), {rectangle(0, 0, 10, 10, k + 1.0)},
                  1.0);
    set_prism(layers[3], Vector3d::UnitZ(), {rectangle(60, 0, 70, 10, 1)}, 1.0);
    mas::TravelNozzle nozzle{mas::NozzleParams(), {Vector3d::Zero(), Vector3d::UnitZ()}};
    nozzle.params.margin_mm = 5.0;
    mas::GcodeStats stats;
    const std::string text = mas::write_gcode(layers, mas::MachineParams(), &stats, {}, &nozzle);
    EXPECT_EQ(stats.checked_routes, 5);
    EXPECT_EQ(stats.rerouted_travels, 0);
    EXPECT_TRUE(stats.travel_collisions.empty());
    const Read r = read_program(text);
    std::vector<Vector3d> surface = box_surface(0, 0, 0, 10, 10, 3, 0.5);
    for (const Vector3d& q : box_surface(60, 0, 0, 70, 10, 1, 0.5)) surface.push_back(q);
    // Every move off the paths after the tower's first layer, against the tower and the pad.
    std::size_t first_off = 0;
    for (std::size_t k = 1; k < r.moves.size() && first_off == 0; ++k)
        if (r.moves[k - 1].depositing && !r.moves[k].depositing) first_off = k;
    double least = INFINITY;
    for (std::size_t k = first_off; k < r.moves.size(); ++k)
        if (!r.moves[k].depositing)
            least = std::min(least, least_clearance(nozzle.params, r, k, k, surface));
    EXPECT_GE(least, nozzle.params.margin_mm - 0.36);
}

}  // namespace
