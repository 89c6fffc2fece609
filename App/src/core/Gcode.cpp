// The post-processor (see Gcode.hpp).
#include "mas/Gcode.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <limits>
#include <memory>
#include <optional>
#include <sstream>

#include "mas/Angles.hpp"
#include "mas/Error.hpp"

namespace mas {
namespace {

// rad: a tool axis this close to +Z or -Z keeps C (finer than the 1e-4 degree of an A word).
constexpr double kPoleTilt = 1e-7;
constexpr double kThicknessStep = 0.05;  // pieces of a deposit move: t changes by this ratio - 1
constexpr double kArcStepDeg = 10.0;     // the longest step of a route around the sphere
constexpr double kSamePoint = 1e-6;      // mm: a path starting where the last ended continues it
constexpr double kLimitSlack = 1e-9;     // degrees: rounding past a limit still reaches it
constexpr double kMinFeed = 0.1;         // mm/min: F words are written to a tenth
constexpr double kMaxFeed = 1e6;         // mm/min: 16 m/s, past any deposition head

std::string fixed(double value, int decimals) {
    char buffer[64];
    std::snprintf(buffer, sizeof buffer, "%.*f", decimals, value);
    std::string s = buffer;
    // "-0.0000" is 0.
    if (s.front() == '-' && s.find_first_not_of("-0.") == std::string::npos) s.erase(0, 1);
    return s;
}

std::string vector_text(Eigen::Vector3d v) {
    v += Eigen::Vector3d::Zero();  // -0 reads as 0
    return format_number(v.x()) + " " + format_number(v.y()) + " " + format_number(v.z());
}

// The G-code text and the machine's modal state; words that did not change are left out, X Y Z
// excepted.
class Program {
public:
    Program(GcodeStats& stats, const MachineParams& machine) : stats_(stats), machine_(machine) {}

    // Where the moves from here on are made ("at layer 3 (component 1)"), as errors name it.
    void at(std::string what) { at_ = std::move(what); }
    // The first move past a finite travel limit of each axis: where, as at() named it.
    const std::array<std::string, 3>& past_limits() const { return past_; }

    void line(const std::string& text) {
        out_ << text << '\n';
        ++stats_.lines;
    }
    // RS274NGC comments do not nest: brackets stand for parentheses inside one.
    void comment(std::string text) {
        std::replace(text.begin(), text.end(), '(', '[');
        std::replace(text.begin(), text.end(), ')', ']');
        line("(" + text + ")");
    }

    // G0 to `p` with the table at `angles`.
    void rapid(const Eigen::Vector3d& p, const TableAngles& angles) {
        if (started_) stats_.rapid_length_mm += (p - position_).norm();
        move("G0", p, words(p), angles, std::string());
    }
    // G1 to `p` at `feed` mm/min, the table where it is; false, and no line, where `p` reads as
    // the point the nozzle is at (points of a path closer than the words' 1e-4 mm).
    bool feed(const Eigen::Vector3d& p, double feed_mm_min) {
        std::array<std::string, 3> xyz = words(p);
        if (started_ && xyz == xyz_words_) {
            position_ = p;
            return false;
        }
        move("G1", p, std::move(xyz), angles_, fixed(feed_mm_min, 1));
        return true;
    }

    const Eigen::Vector3d& position() const { return position_; }
    const TableAngles& angles() const { return angles_; }
    std::string text() const { return out_.str(); }

private:
    static std::array<std::string, 3> words(const Eigen::Vector3d& p) {
        return {fixed(p.x(), 4), fixed(p.y(), 4), fixed(p.z(), 4)};
    }

    // `xyz`: words(p), made once by the caller.
    void move(const char* code, const Eigen::Vector3d& p, std::array<std::string, 3> xyz,
              const TableAngles& angles, const std::string& feed) {
        xyz_words_ = std::move(xyz);
        std::string s = code;
        s += " X" + xyz_words_[0] + " Y" + xyz_words_[1] + " Z" + xyz_words_[2];
        const std::string a = fixed(angles.a_deg, 4), c = fixed(angles.c_deg, 4);
        const bool turns = !started_ || a != a_word_ || c != c_word_;
        if (a != a_word_ || !started_) s += " A" + a;
        if (c != c_word_ || !started_) s += " C" + c;
        if (!feed.empty() && feed != f_word_) {
            s += " F" + feed;
            f_word_ = feed;
        }
        if (turns && started_) ++stats_.reorientations;
        if (!started_) {
            stats_.a_min_deg = stats_.a_max_deg = angles.a_deg;
            stats_.c_min_deg = stats_.c_max_deg = angles.c_deg;
        }
        follow_joints(p, angles);
        stats_.a_min_deg = std::min(stats_.a_min_deg, angles.a_deg);
        stats_.a_max_deg = std::max(stats_.a_max_deg, angles.a_deg);
        stats_.c_min_deg = std::min(stats_.c_min_deg, angles.c_deg);
        stats_.c_max_deg = std::max(stats_.c_max_deg, angles.c_deg);
        a_word_ = a;
        c_word_ = c;
        angles_ = angles;
        position_ = p;
        started_ = true;
        line(s);
    }

    // The machine's joints along the move from where the tip is to `p` (the table to `angles`),
    // every kJointStepDeg of A and of C where it turns; from `p` alone for the first move, which
    // starts the ranges.
    void follow_joints(const Eigen::Vector3d& p, const TableAngles& angles) {
        const double da = angles.a_deg - angles_.a_deg, dc = angles.c_deg - angles_.c_deg;
        const int steps =
            !started_ ? 0
                      : static_cast<int>(
                            std::ceil(std::max(std::abs(da), std::abs(dc)) / kJointStepDeg - 1e-9));
        for (int k = steps > 0 ? 1 : 0; k <= steps; ++k) {
            const double s = steps > 0 ? static_cast<double>(k) / steps : 1.0;
            const Eigen::Vector3d j =
                k == steps
                    ? machine_position(p, angles, machine_)
                    : machine_position(position_ + s * (p - position_),
                                       {angles_.a_deg + s * da, angles_.c_deg + s * dc}, machine_);
            stats_.machine_min = started_ ? stats_.machine_min.cwiseMin(j) : j;
            stats_.machine_max = started_ ? stats_.machine_max.cwiseMax(j) : j;
            for (int axis = 0; axis < 3; ++axis)
                if (past_[axis].empty() &&
                    (j[axis] < machine_.travel_min[axis] || j[axis] > machine_.travel_max[axis]))
                    past_[axis] = at_;
        }
    }

    GcodeStats& stats_;
    const MachineParams& machine_;
    std::string at_;
    std::array<std::string, 3> past_;
    std::ostringstream out_;
    Eigen::Vector3d position_ = Eigen::Vector3d::Zero();
    TableAngles angles_;
    std::array<std::string, 3> xyz_words_;  // of the last move
    std::string a_word_, c_word_, f_word_;
    bool started_ = false;
};

// The sphere every route between components keeps to.
struct Sphere {
    Eigen::Vector3d centre = Eigen::Vector3d::Zero();
    double radius = 0.0;

    // Where the ray from `q` (inside) along the unit `direction` leaves the sphere.
    Eigen::Vector3d exit(const Eigen::Vector3d& q, const Eigen::Vector3d& direction) const {
        const Eigen::Vector3d d = q - centre;
        const double b = d.dot(direction);
        const double c = d.squaredNorm() - radius * radius;
        return q + direction * (-b + std::sqrt(std::max(0.0, b * b - c)));
    }
};

// The way between a layer with tool axis `axis` (unit) and the sphere: along the axis, levelled
// where it points below the horizontal, so that the nozzle's body, reaching back along the axis,
// sinks no lower than where it deposits (a cane bent over 135 degrees, its last layers tilted 97
// degrees: out along their axis, the body's far end came within the margin of the plate 240 mm
// out). Along it the tip still leaves the layer's plane, by sin(tilt) of each mm.
Eigen::Vector3d way_out(const Eigen::Vector3d& axis) {
    const Eigen::Vector3d level(axis.x(), axis.y(), 0.0);
    return axis.z() < 0.0 && level.norm() > 1e-9 ? Eigen::Vector3d(level.normalized()) : axis;
}

// Unit vectors from `from` to `to` along the great circle through them, at most kArcStepDeg
// apart, `to` included, `from` not.
std::vector<Eigen::Vector3d> arc(const Eigen::Vector3d& from, const Eigen::Vector3d& to) {
    const double angle = std::acos(std::clamp(from.dot(to), -1.0, 1.0));
    std::vector<Eigen::Vector3d> out;
    if (angle < 1e-12) return out;
    Eigen::Vector3d ortho = to - from * from.dot(to);
    if (ortho.norm() < 1e-12) {  // opposite: any great circle
        ortho = from.unitOrthogonal();
    }
    ortho.normalize();
    const int steps = std::max(1, static_cast<int>(std::ceil(angle / (kArcStepDeg * kDegree))));
    for (int i = 1; i < steps; ++i) {
        const double phi = angle * i / steps;
        out.push_back(from * std::cos(phi) + ortho * std::sin(phi));
    }
    out.push_back(to);
    return out;
}

// A deposit path the nozzle runs along: two points or more, not all in one place.
bool runs(const ToolPath& path) {
    for (std::size_t k = 1; k < path.points.size(); ++k)
        if ((path.points[k] - path.points[k - 1]).norm() >= kSamePoint * 1e-3) return true;
    return false;
}

// Where a deposit move whose thickness goes linearly from t0 to t1 is cut for its feed, as
// fractions of its length, the last 1: where the thickness enters [t_lo, t_hi] (beyond it the feed
// is at a bound), at most a ratio of 1 + kThicknessStep apart within it, and where it leaves.
std::vector<double> feed_cuts(double t0, double t1, double t_lo, double t_hi) {
    std::vector<double> out;
    const double c0 = std::clamp(t0, t_lo, t_hi), c1 = std::clamp(t1, t_lo, t_hi);
    // Part of the move lies within the range, its thickness changing by more than rounding
    // (thicknesses 1e-15 apart cut a move at an arbitrary point, both pieces at one feed).
    if (std::abs(c1 - c0) > 1e-9 * std::max(c0, c1)) {
        auto at = [&](double t) { return (t - t0) / (t1 - t0); };
        if (at(c0) > 1e-12) out.push_back(at(c0));
        const int n = std::max(
            1, static_cast<int>(
                   std::ceil(std::abs(std::log(c1 / c0)) / std::log1p(kThicknessStep) - 1e-9)));
        for (int k = 1; k <= n; ++k)
            out.push_back(at(c0 * std::pow(c1 / c0, static_cast<double>(k) / n)));
    }
    if (out.empty() || out.back() < 1.0 - 1e-12)
        out.push_back(1.0);
    else
        out.back() = 1.0;
    return out;
}

// A point the nozzle's tip goes to, with the table's angles there; `along`: the layer (its place
// in the program's layers) whose tool axis the move to it follows from or to a deposit point on
// it, the table still (NozzleMove::along_layer), -1 for none.
struct Waypoint {
    Eigen::Vector3d p;
    TableAngles a;
    int along = -1;
};

// A route whose table turns and meets something is checked again with pieces turning this many
// times less: its allowance (Nozzle.hpp, "Travel") at most margin / kFinerTurn. Pieces still
// meeting something are cut finer again, up to kFinerPasses times in all.
constexpr double kFinerTurn = 20.0;
constexpr int kFinerPasses = 3;

// The tool axis the table at `a` turns to machine +Z: Rx(A) Rz(C) maps it there.
Eigen::Vector3d axis_of(const TableAngles& a) {
    const double sa = std::sin(a.a_deg * kDegree);
    return {sa * std::sin(a.c_deg * kDegree), sa * std::cos(a.c_deg * kDegree),
            std::cos(a.a_deg * kDegree)};
}

// The table's angles at either end of a travel move.
struct AngleSpan {
    TableAngles from, to;
};

// The move from `p` (table at `a`) to `q` (at `b`), A, C and the tip in proportion, as moves for
// the travel check, appended to `out`: one when the table keeps still, else pieces along which
// the axis turns by at most `max_turn` (rad). Along a piece it turns by no more than its change of
// A plus its change of C times the greatest |sin A| on the way (the axis' speeds). `spans`, when
// given, gets each move's angles at its ends.
void turning_moves(const Eigen::Vector3d& p, const TableAngles& a, const Eigen::Vector3d& q,
                   const TableAngles& b, double max_turn, int along, std::vector<NozzleMove>& out,
                   std::vector<AngleSpan>* spans = nullptr) {
    const double da = b.a_deg - a.a_deg, dc = b.c_deg - a.c_deg;
    if (da == 0.0 && dc == 0.0) {
        out.push_back({p, q, axis_of(a), 0.0, along});
        if (spans) spans->push_back({a, b});
        return;
    }
    const double lo = std::min(a.a_deg, b.a_deg), hi = std::max(a.a_deg, b.a_deg);
    const bool past_90 = (lo <= 90.0 && hi >= 90.0) || (lo <= -90.0 && hi >= -90.0);
    const double sin_max =
        past_90 ? 1.0
                : std::max(std::abs(std::sin(lo * kDegree)), std::abs(std::sin(hi * kDegree)));
    const double turn = (std::abs(da) + std::abs(dc) * sin_max) * kDegree;
    const int pieces = std::max(1, static_cast<int>(std::ceil(turn / max_turn - 1e-9)));
    for (int k = 0; k < pieces; ++k) {
        const double s0 = static_cast<double>(k) / pieces;
        const double s1 = static_cast<double>(k + 1) / pieces;
        const TableAngles at{a.a_deg + s0 * da, a.c_deg + s0 * dc};
        const TableAngles end =
            k + 1 == pieces ? b : TableAngles{a.a_deg + s1 * da, a.c_deg + s1 * dc};
        out.push_back({p + s0 * (q - p), k + 1 == pieces ? q : Eigen::Vector3d(p + s1 * (q - p)),
                       axis_of(at), std::min(turn / pieces, max_turn), -1, axis_of(end)});
        if (spans) spans->push_back({at, end});
    }
}

// The number a layer is named by: its index in the part, else its place in the program's layers.
int layer_index(std::size_t place, const GcodeLayer& layer) {
    return layer.index >= 0 ? layer.index : int(place);
}

std::string layer_number(std::size_t place, const GcodeLayer& layer) {
    return "layer " + std::to_string(layer_index(place, layer));
}

std::string layer_name(std::size_t place, const GcodeLayer& layer) {
    return layer_number(place, layer) + " (component " + std::to_string(layer.component) + ")";
}

}  // namespace

Eigen::Vector3d machine_position(const Eigen::Vector3d& p, const TableAngles& angles,
                                 const MachineParams& m) {
    const Eigen::Vector3d w = p + m.work_offset;
    // C about the vertical line through the rot point.
    const double c = angles.c_deg * kDegree, a = angles.a_deg * kDegree;
    const double x = w.x() - m.rot_point.x(), y = w.y() - m.rot_point.y();
    const double xc = x * std::cos(c) - y * std::sin(c) + m.rot_point.x();
    const double yc = x * std::sin(c) + y * std::cos(c) + m.rot_point.y();
    // A about the line along X through (rot point y + y-offset, rot point z + z-offset).
    const double ya = m.rot_point.y() + m.rot_offset_y_mm, za = m.rot_point.z() + m.rot_offset_z_mm;
    const double dy = yc - ya, dz = w.z() - za;
    return {xc, dy * std::cos(a) - dz * std::sin(a) + ya,
            dy * std::sin(a) + dz * std::cos(a) + za + m.tool_length_mm};
}

void validate(const MachineParams& p) {
    auto fail = [](const std::string& what) { throw Error(ErrorCode::InvalidArgument, what); };
    auto finite = [](double v) { return std::isfinite(v); };
    if (!finite(p.a_min_deg) || !finite(p.a_max_deg) || !(p.a_min_deg < p.a_max_deg))
        fail("machine: A's limits must be finite with min < max, got " +
             format_number(p.a_min_deg) + " to " + format_number(p.a_max_deg) + " degrees");
    if (!finite(p.c_min_deg) || !finite(p.c_max_deg) || !(p.c_min_deg < p.c_max_deg))
        fail("machine: C's limits must be finite with min < max, got " +
             format_number(p.c_min_deg) + " to " + format_number(p.c_max_deg) + " degrees");
    if (!finite(p.feed_mm_min) || !(p.feed_mm_min > 0.0))
        fail("machine: feed must be > 0 mm/min, got " + format_number(p.feed_mm_min));
    if (!finite(p.reference_thickness_mm) || !(p.reference_thickness_mm >= 0.0))
        fail("machine: reference thickness must be >= 0 mm (0: derived), got " +
             format_number(p.reference_thickness_mm));
    if (!finite(p.max_feed_ratio) || !(p.max_feed_ratio >= 1.0))
        fail("machine: max feed ratio must be >= 1, got " + format_number(p.max_feed_ratio));
    // F words carry a tenth of a mm/min: a slower feed would read F0.0, which controllers refuse.
    const double f_lo = p.feed_mm_min / p.max_feed_ratio, f_hi = p.feed_mm_min * p.max_feed_ratio;
    if (!(f_lo >= kMinFeed) || !(f_hi <= kMaxFeed))
        fail(
            "machine: the feed range, feed / max feed ratio to feed x max feed ratio, must lie "
            "within " +
            format_number(kMinFeed) + " to " + format_number(kMaxFeed) + " mm/min, got " +
            format_number(f_lo) + " to " + format_number(f_hi));
    if (!finite(p.clearance_mm) || !(p.clearance_mm > 0.0))
        fail("machine: clearance must be > 0 mm, got " + format_number(p.clearance_mm));
    if (p.deposit_output < 0 || p.deposit_output > 63)
        fail("machine: the deposition output must be a digital output 0 to 63, got " +
             std::to_string(p.deposit_output));
    for (int axis = 0; axis < 3; ++axis) {
        const double lo = p.travel_min[axis], hi = p.travel_max[axis];
        // Infinite: not checked; NaN fails the comparison.
        if (!(lo < hi) || lo == kInfiniteTravel || hi == -kInfiniteTravel)
            fail(std::string("machine: ") + "XYZ"[axis] +
                 "'s travel limits must have min < max, got " + format_number(lo) + " to " +
                 format_number(hi) + " mm");
    }
    const auto place = [&](const std::string& what, double v) {
        if (!(std::abs(v) <= kMaxCoordinateMm))
            fail("machine: " + what + " must be a finite length within " +
                 format_number(kMaxCoordinateMm) + " mm, got " + format_number(v));
    };
    for (int axis = 0; axis < 3; ++axis) {
        place(std::string("the work offset's ") + "XYZ"[axis], p.work_offset[axis]);
        place(std::string("the rot point's ") + "XYZ"[axis], p.rot_point[axis]);
    }
    place("the rot offset's Y", p.rot_offset_y_mm);
    place("the rot offset's Z", p.rot_offset_z_mm);
    place("the tool length", p.tool_length_mm);
}

std::vector<GcodeLayer> gcode_layers(const SlicedPart& part) {
    std::vector<GcodeLayer> out;
    out.reserve(part.layers.size());
    const bool sequenced = part.sequence.layers.size() == part.layers.size();
    for (std::size_t k = 0; k < part.layers.size(); ++k) {
        const std::size_t i = sequenced ? std::size_t(part.sequence.layers[k]) : k;
        const Layer& layer = part.layers[i];
        GcodeLayer g;
        g.index = int(i);
        g.component = layer.component;
        g.tool_axis = i < part.toolpaths.size() ? part.toolpaths[i].tool_axis : layer.plane.normal;
        if (i < part.toolpaths.size()) g.paths = part.toolpaths[i].paths;
        for (std::size_t r = 0; r < layer.regions.size(); ++r)
            for (const auto& loop : layer.loops_3d(r))
                g.outline.insert(g.outline.end(), loop.begin(), loop.end());
        g.max_thickness_mm = layer.max_thickness_mm;
        g.prism.component = layer.component;
        g.prism.plane = layer.plane;
        g.prism.lower = layer.lower;
        g.prism.regions = layer.regions;
        g.prism.max_thickness_mm = layer.max_thickness_mm;
        out.push_back(std::move(g));
    }
    return out;
}

namespace {

// The table's solutions for `n` within A's limits (C not yet fitted to its own): (A, C) pairs.
// At a pole (n within kPoleTilt of +Z or -Z) C is free and stays at `previous_c`.
std::vector<TableAngles> a_solutions(const Eigen::Vector3d& n, const MachineParams& p,
                                     double previous_c) {
    const double r = std::hypot(n.x(), n.y());
    const double tilt_rad = std::atan2(r, n.z());
    const bool up = tilt_rad < kPoleTilt, down = kPi - tilt_rad < kPoleTilt;
    const double tilt = up ? 0.0 : down ? 180.0 : tilt_rad / kDegree;
    const double c0 = up || down ? previous_c : std::atan2(n.x(), n.y()) / kDegree;
    std::vector<TableAngles> out;
    for (const double sign : {1.0, -1.0}) {
        if (up && sign < 0.0) break;
        const double a = sign * tilt;
        if (a < p.a_min_deg - kLimitSlack || a > p.a_max_deg + kLimitSlack) continue;
        out.push_back(
            {std::clamp(a, p.a_min_deg, p.a_max_deg), sign > 0.0 || down ? c0 : c0 + 180.0});
    }
    return out;
}

// `c` + 360 k nearest `previous_c` within C's limits, else false.
bool fit_c(double c, double previous_c, const MachineParams& p, double& out) {
    double k = std::round((previous_c - c) / 360.0);
    if (c + 360.0 * k > p.c_max_deg + kLimitSlack)
        k = std::floor((p.c_max_deg + kLimitSlack - c) / 360.0);
    if (c + 360.0 * k < p.c_min_deg - kLimitSlack)
        k = std::ceil((p.c_min_deg - kLimitSlack - c) / 360.0);
    const double cc = c + 360.0 * k;
    if (cc > p.c_max_deg + kLimitSlack || cc < p.c_min_deg - kLimitSlack) return false;
    out = std::clamp(cc, p.c_min_deg, p.c_max_deg);
    return true;
}

}  // namespace

bool table_angles(const Eigen::Vector3d& n, const MachineParams& p, double previous_a,
                  double previous_c, TableAngles& out) {
    const double tilt_rad = std::atan2(std::hypot(n.x(), n.y()), n.z());
    const bool pole = tilt_rad < kPoleTilt || kPi - tilt_rad < kPoleTilt;
    bool found = false;
    double best = std::numeric_limits<double>::infinity();
    for (const TableAngles& s : a_solutions(n, p, previous_c)) {
        double c = 0.0;
        if (pole)  // C is free: it stays, within its limits
            c = std::clamp(previous_c, p.c_min_deg, p.c_max_deg);
        else if (!fit_c(s.c_deg, previous_c, p, c))
            continue;
        const double cost = std::abs(s.a_deg - previous_a) + std::abs(c - previous_c);
        if (cost < best) {
            best = cost;
            out = {s.a_deg, c};
            found = true;
        }
    }
    return found;
}

std::string write_gcode(const std::vector<GcodeLayer>& layers, const MachineParams& params,
                        GcodeStats* stats_out, const Progress& progress,
                        const TravelNozzle* nozzle) {
    validate(params);
    if (nozzle) {
        validate(nozzle->params);
        if (!(params.clearance_mm <= kMaxClearanceInMargins * nozzle->params.margin_mm))
            throw Error(ErrorCode::InvalidArgument,
                        "machine: clearance " + format_number(params.clearance_mm) +
                            " mm is more than " + format_number(kMaxClearanceInMargins) +
                            " times the nozzle's margin (" +
                            format_number(nozzle->params.margin_mm) +
                            " mm): the travel check walks the routes in fractions of a margin");
    }
    // What the program deposits, and where.
    std::vector<std::size_t> used;
    std::vector<double> deepest(layers.size(), 0.0);  // how far under its plane a layer reaches
    double t_min = std::numeric_limits<double>::infinity(), t_max = 0.0;
    Eigen::Vector3d lo = Eigen::Vector3d::Constant(std::numeric_limits<double>::infinity());
    Eigen::Vector3d hi = -lo;
    for (std::size_t i = 0; i < layers.size(); ++i) {
        const GcodeLayer& layer = layers[i];
        const Eigen::Vector3d& n = layer.tool_axis;
        if (!n.allFinite() || std::abs(n.norm() - 1.0) > 1e-6)
            throw Error(ErrorCode::InvalidArgument, layer_name(i, layer) + ": its tool axis (" +
                                                        vector_text(n) + ") is not a unit vector");
        if (!std::isfinite(layer.max_thickness_mm) || layer.max_thickness_mm < 0.0)
            throw Error(ErrorCode::InvalidArgument, layer_name(i, layer) + ": its thickness " +
                                                        format_number(layer.max_thickness_mm) +
                                                        " mm is not >= 0");
        deepest[i] = layer.max_thickness_mm;
        bool deposits = false;
        for (const ToolPath& path : layer.paths) {
            if (!path.deposit()) continue;
            if (path.thickness_mm.size() != path.points.size())
                throw Error(ErrorCode::InvalidArgument,
                            layer_name(i, layer) + ": a path has " +
                                std::to_string(path.points.size()) + " points and " +
                                std::to_string(path.thickness_mm.size()) + " thicknesses");
            for (std::size_t k = 0; k < path.points.size(); ++k) {
                const double t = path.thickness_mm[k];
                if (!path.points[k].allFinite() || !std::isfinite(t))
                    throw Error(
                        ErrorCode::NonFiniteCoordinate,
                        layer_name(i, layer) + ": a path point or its thickness is not finite");
                if (t < 0.0)
                    throw Error(ErrorCode::InvalidArgument,
                                layer_name(i, layer) + ": a path's thickness " + format_number(t) +
                                    " mm is negative");
            }
            if (!runs(path)) continue;
            for (std::size_t k = 0; k < path.points.size(); ++k) {
                lo = lo.cwiseMin(path.points[k]);
                hi = hi.cwiseMax(path.points[k]);
                t_min = std::min(t_min, path.thickness_mm[k]);
                t_max = std::max(t_max, path.thickness_mm[k]);
                deepest[i] = std::max(deepest[i], path.thickness_mm[k]);
            }
            deposits = true;
        }
        for (const Eigen::Vector3d& q : layer.outline) {
            if (!q.allFinite())
                throw Error(ErrorCode::NonFiniteCoordinate,
                            layer_name(i, layer) + ": an outline point is not finite");
        }
        if (!deposits) continue;
        for (const Eigen::Vector3d& q : layer.outline) {
            lo = lo.cwiseMin(q);
            hi = hi.cwiseMax(q);
        }
        used.push_back(i);
    }
    if (used.empty()) {
        // Layers without paths: their regions are narrower than the bead paths fill (a part
        // smaller than a bead), listed by slicing as unfilled features.
        std::string why = "G-code: no layer has a path to deposit";
        if (!layers.empty())
            why += (layers.size() == 1 ? std::string(": its one layer holds no bead path")
                                       : ": none of the " + std::to_string(layers.size()) +
                                             " layers holds a bead path") +
                   " (regions too narrow for the bead are listed as the slice's unfilled "
                   "features; a smaller bead width may fill them)";
        throw Error(ErrorCode::EmptyInput, why);
    }

    GcodeStats stats;
    const double reference = params.reference_thickness_mm > 0.0
                                 ? params.reference_thickness_mm
                                 : std::max(0.5 * (t_min + t_max), 1e-9);
    stats.reference_thickness_mm = reference;
    const bool by_thickness = params.max_feed_ratio > 1.0;
    const double f_lo = params.feed_mm_min / params.max_feed_ratio;
    const double f_hi = params.feed_mm_min * params.max_feed_ratio;
    // Thicknesses beyond these give a feed at a bound.
    const double t_lo = reference / params.max_feed_ratio, t_hi = reference * params.max_feed_ratio;

    // The sphere the routes between components keep outside: everything deposited (each layer's
    // outline and path points, and as deep under them as it reaches) plus the clearance, grown so
    // that the chords of its kArcStepDeg steps stay outside that.
    Sphere sphere;
    sphere.centre = 0.5 * (lo + hi);
    double bound = 0.0;
    for (const std::size_t i : used) {
        const GcodeLayer& layer = layers[i];
        auto reach = [&](const Eigen::Vector3d& q) {
            bound = std::max(bound, (q - sphere.centre).norm() + deepest[i] + params.clearance_mm);
        };
        for (const Eigen::Vector3d& q : layer.outline) reach(q);
        for (const ToolPath& path : layer.paths)
            if (path.deposit())
                for (const Eigen::Vector3d& q : path.points) reach(q);
    }
    sphere.radius = bound / std::cos(0.5 * kArcStepDeg * kDegree);
    const Eigen::Vector3d top = Eigen::Vector3d::UnitZ();

    // The table's angles of every layer used, checked before a line is written.
    std::vector<TableAngles> angles(layers.size());
    {
        TableAngles previous{std::clamp(0.0, params.a_min_deg, params.a_max_deg),
                             std::clamp(0.0, params.c_min_deg, params.c_max_deg)};
        for (const std::size_t i : used) {
            const GcodeLayer& layer = layers[i];
            if (!table_angles(layer.tool_axis, params, previous.a_deg, previous.c_deg, angles[i])) {
                const Eigen::Vector3d& n = layer.tool_axis;
                const double tilt = std::atan2(std::hypot(n.x(), n.y()), n.z()) / kDegree;
                const std::vector<TableAngles> within_a = a_solutions(n, params, previous.c_deg);
                std::string why;
                if (within_a.empty()) {
                    why = "needs the table tilted " + format_number(tilt, 7) +
                          " degrees one way or the other, beyond A's limits " +
                          format_number(params.a_min_deg) + " to " +
                          format_number(params.a_max_deg);
                } else {
                    why = "needs C at";
                    for (std::size_t k = 0; k < within_a.size(); ++k) {
                        double c = std::fmod(within_a[k].c_deg, 360.0);
                        if (c < 0.0) c += 360.0;
                        why += (k ? " or " : " ") + format_number(c, 6);
                    }
                    why += " degrees (plus a multiple of 360), beyond C's limits " +
                           format_number(params.c_min_deg) + " to " +
                           format_number(params.c_max_deg);
                }
                throw Error(
                    ErrorCode::UnreachableOrientation,
                    layer_name(i, layer) + ": its tool axis (" + vector_text(n) + ") " + why);
            }
            previous = angles[i];
        }
    }

    Program g(stats, params);
    const std::string out_n = " P" + std::to_string(params.deposit_output);
    int component_count = 0;
    {
        std::vector<int> seen;
        for (const std::size_t i : used)
            if (std::find(seen.begin(), seen.end(), layers[i].component) == seen.end())
                seen.push_back(layers[i].component);
        component_count = static_cast<int>(seen.size());
    }
    g.comment("Multi-Axis Slicer: " + std::to_string(used.size()) + " layers of " +
              std::to_string(component_count) + " components");
    g.comment("machine: tilting rotary table XYZAC, LinuxCNC xyzac-trt-kins, A " +
              format_number(params.a_min_deg) + " to " + format_number(params.a_max_deg) +
              " deg, C " + format_number(params.c_min_deg) + " to " +
              format_number(params.c_max_deg) + " deg");
    g.comment("X Y Z: the part's coordinates in mm; set G54 to the part's origin on the table");
    const bool travel_checked = (params.travel_min.array() > -kInfiniteTravel).any() ||
                                (params.travel_max.array() < kInfiniteTravel).any();
    if (travel_checked) {
        std::string limits;
        for (int axis = 0; axis < 3; ++axis)
            limits += std::string(axis ? ", " : "") + "XYZ"[axis] + " " +
                      format_number(params.travel_min[axis]) + " to " +
                      format_number(params.travel_max[axis]);
        g.comment("machine travel checked: " + limits + " mm, for G54 at (" +
                  vector_text(params.work_offset) + "), the table's rot point at (" +
                  vector_text(params.rot_point) + "), its y and z offsets " +
                  format_number(params.rot_offset_y_mm) + " " +
                  format_number(params.rot_offset_z_mm) + ", tool length " +
                  format_number(params.tool_length_mm));
    }
    if (nozzle) {
        // Where the part stands: a part modelled off the plane Z = 0 (centred on its origin, or
        // above it) has its program's Z as modelled, so the work offset must take the difference.
        const Plane& plate = nozzle->plate;
        if ((plate.normal - Eigen::Vector3d::UnitZ()).norm() <= 1e-9) {
            // To the program's resolution (its words have 4 decimals); -0 reads as 0.
            const double z = std::round(plate.origin.z() * 1e4) / 1e4 + 0.0;
            const std::string level = format_number(z);
            g.comment("build plate: the part stands on its plane Z" + level + "; set G54's Z " +
                      (level == "0" ? std::string("on the plate's surface")
                                    : format_number(std::abs(z)) + " mm " +
                                          (z > 0.0 ? "below" : "above") + " the plate's surface"));
        } else {
            g.comment("build plate: the plane through " + vector_text(plate.origin) +
                      " square to " + vector_text(plate.normal) + " in the part's coordinates");
        }
    }
    g.comment("the nozzle tip is the tool-centre point: its length offset must be in force");
    g.comment("deposition: digital output" + out_n + ", feed " + format_number(params.feed_mm_min) +
              " mm/min at " + format_number(reference, 4) + " mm thick, within " +
              format_number(f_lo) + " to " + format_number(f_hi) + " mm/min");
    g.line("G21 G90 G94 G17 G40 G54");
    g.line("G64 P0.01");
    g.line("M65" + out_n);

    // Around the sphere over its top from `from` (on it) to `to` (on it): the waypoints after
    // `from`. On the way up the table turns level from `start` (A to 0, or the nearest A within
    // its limits, in proportion to the way), at the top C turns to its end, on the way down A turns
    // to `to_angles`: at the top the nozzle stands along the sphere's radius, out of it, where one
    // lying on its side would reach down the sphere's side towards the part.
    const double level_a = std::clamp(0.0, params.a_min_deg, params.a_max_deg);
    const Eigen::Vector3d summit = sphere.centre + sphere.radius * top;
    auto round_the_top = [&](const Eigen::Vector3d& from, const TableAngles& start,
                             const Eigen::Vector3d& to, const TableAngles& to_angles,
                             std::vector<Waypoint>& way) {
        const std::vector<Eigen::Vector3d> up = arc((from - sphere.centre) / sphere.radius, top);
        const std::vector<Eigen::Vector3d> down = arc(top, (to - sphere.centre) / sphere.radius);
        for (std::size_t k = 0; k < up.size(); ++k) {
            const double s = static_cast<double>(k + 1) / static_cast<double>(up.size());
            way.push_back({k + 1 == up.size()
                               ? summit
                               : Eigen::Vector3d(sphere.centre + sphere.radius * up[k]),
                           {start.a_deg + s * (level_a - start.a_deg), start.c_deg}});
        }
        if (up.empty() && start.a_deg != level_a) way.push_back({from, {level_a, start.c_deg}});
        if (start.c_deg != to_angles.c_deg)
            way.push_back({way.empty() ? from : way.back().p, {level_a, to_angles.c_deg}});
        for (std::size_t k = 0; k < down.size(); ++k) {
            const double s = static_cast<double>(k + 1) / static_cast<double>(down.size());
            way.push_back({k + 1 == down.size()
                               ? to
                               : Eigen::Vector3d(sphere.centre + sphere.radius * down[k]),
                           {level_a + s * (to_angles.a_deg - level_a), to_angles.c_deg}});
        }
        if (down.empty() && to_angles.a_deg != level_a) way.push_back({to, to_angles});
    };
    // From `from` (the table at `from_angles`, the last tool axis `back`) to the clearance over `s`
    // (the table at `to_angles`, tool axis `n`): out along `back` to the sphere, round its top and
    // in along n.
    // `left`, `next`: the layers (places) the route leaves and goes to.
    auto round_the_part = [&](const Eigen::Vector3d& from, const TableAngles& from_angles,
                              const Eigen::Vector3d& back, int left, const Eigen::Vector3d& s,
                              const Eigen::Vector3d& n, const TableAngles& to_angles, int next) {
        std::vector<Waypoint> way;
        const Eigen::Vector3d out = sphere.exit(from, way_out(back));
        way.push_back({out, from_angles, left});
        round_the_top(out, from_angles, sphere.exit(s, way_out(n)), to_angles, way);
        way.push_back({Eigen::Vector3d(s + n * params.clearance_mm), to_angles, next});
        return way;
    };

    // The travel check: each layer's prism, deposited as the program goes.
    std::vector<Layer> prisms;
    std::unique_ptr<TravelCheck> check;
    if (nozzle) {
        prisms.reserve(layers.size());
        for (const GcodeLayer& layer : layers) prisms.push_back(layer.prism);
        check = std::make_unique<TravelCheck>(prisms, nozzle->params, nozzle->plate);
    }
    // What the nozzle meets from where it is along `way` (G0) and then, when `plunge`, down to it
    // at the feed along layer `next`'s tool axis; `also`: a layer counted as deposited for it
    // (TravelCheck::meets). Where the table turns, a route met is checked again with each piece
    // that turns the table and meets something on its own cut kFinerTurn times finer; a piece
    // passed on its own keeps the margin already, and the moves with the table still are judged
    // as before. (Cutting the whole route finer cost some 20 times its turns, and could report a
    // piece passed coarse, within 2.15 margins but clear of one.) While a finer piece still meets
    // something and both its ends keep clear, it is cut finer again, kFinerPasses times in all:
    // a piece's bound may fall short of its ends by half its allowance between them
    // (turning_plate_hit), and a layer built sideways 2.03 mm over the plate, under a 2 mm
    // margin, had the last piece of the way down onto it reported as meeting the plate (a
    // survey's angle bracket, seed 185). The last pass's allowance is margin / kFinerTurn^3
    // (0.25 microns at 2 mm). A piece meeting something at an end does so however fine.
    auto meets = [&](const std::vector<Waypoint>& way, const std::optional<Eigen::Vector3d>& plunge,
                     int next, int also) -> std::optional<TravelHit> {
        std::vector<NozzleMove> moves;
        std::vector<AngleSpan> spans;
        Eigen::Vector3d p = g.position();
        TableAngles a = g.angles();
        auto add = [&](const Eigen::Vector3d& q, const TableAngles& b, int along) {
            turning_moves(p, a, q, b, check->max_turn_rad(), along, moves, &spans);
            p = q;
            a = b;
        };
        for (const Waypoint& w : way) add(w.p, w.a, w.along);
        if (plunge) add(*plunge, a, next);
        std::optional<TravelHit> hit = check->meets(moves, also);
        const bool turns = std::any_of(moves.begin(), moves.end(),
                                       [](const NozzleMove& move) { return move.turn_rad != 0.0; });
        if (!hit || !turns) return hit;
        // Whether the nozzle standing at either end of a turning piece keeps clear.
        const auto ends_clear = [&](const NozzleMove& move) {
            const NozzleMove at_from{move.from, move.from, move.axis, 0.0, -1};
            const Eigen::Vector3d last =
                move.to_axis == Eigen::Vector3d::Zero() ? move.axis : move.to_axis;
            const NozzleMove at_to{move.to, move.to, last, 0.0, -1};
            return !check->meets({at_from}, also) && !check->meets({at_to}, also);
        };
        double max_turn = check->max_turn_rad();
        for (int pass = 0; pass < kFinerPasses; ++pass) {
            max_turn /= kFinerTurn;
            std::vector<NozzleMove> finer;
            std::vector<AngleSpan> finer_spans;
            bool cut = false;
            for (std::size_t k = 0; k < moves.size(); ++k) {
                const NozzleMove& move = moves[k];
                if (move.turn_rad == 0.0) {
                    finer.push_back(move);
                    finer_spans.push_back(spans[k]);
                } else if (check->meets({move}, also)) {
                    // After the first pass, only a piece whose ends both keep clear.
                    if (pass > 0 && !ends_clear(move)) {
                        finer.push_back(move);
                        finer_spans.push_back(spans[k]);
                        continue;
                    }
                    turning_moves(move.from, spans[k].from, move.to, spans[k].to, max_turn, -1,
                                  finer, &finer_spans);
                    cut = true;
                }
            }
            hit = check->meets(finer, also);
            if (!hit || !cut) return hit;
            moves = std::move(finer);
            spans = std::move(finer_spans);
        }
        return hit;
    };
    // A layer (its place, -1 for none) as named; what a hit meets, in words.
    auto name_of = [&](int i) {
        return i < 0 ? -1 : layer_index(std::size_t(i), layers[std::size_t(i)]);
    };
    auto obstacle_of = [&](const TravelHit& hit) {
        const int y = hit.obstacle_layer;
        return y < 0 ? std::string("the build plate")
                     : layer_number(std::size_t(y), layers[std::size_t(y)]);
    };
    // Reports what the route into layer `i` (-1: off the part) meets.
    auto report = [&](int i, const TravelHit& hit) {
        stats.travel_collisions.push_back(
            {name_of(i), name_of(hit.obstacle_layer), hit.nozzle_at, hit.obstacle});
        g.comment("warning: on the way " +
                  (i < 0 ? std::string("off the part")
                         : "to " + layer_number(std::size_t(i), layers[std::size_t(i)])) +
                  " the nozzle meets " + obstacle_of(hit) + " near " + vector_text(hit.obstacle));
    };
    auto rapid_along = [&](const std::vector<Waypoint>& way) {
        for (const Waypoint& w : way) g.rapid(w.p, w.a);
    };

    bool depositing = false;
    auto stop_deposit = [&] {
        if (!depositing) return;
        g.line("M63" + out_n);
        depositing = false;
    };

    int previous_component = 0;
    bool first = true;
    for (std::size_t u = 0; u < used.size(); ++u) {
        const std::size_t i = used[u];
        progress(static_cast<double>(u) / static_cast<double>(used.size()));
        if (check && u > 0) check->deposited(used[u - 1]);
        const GcodeLayer& layer = layers[i];
        const Eigen::Vector3d& n = layer.tool_axis;
        const TableAngles& a = angles[i];
        bool first_path = true;
        for (const ToolPath& path : layer.paths) {
            if (!path.deposit() || !runs(path)) continue;
            const Eigen::Vector3d& s = path.points.front();
            const Eigen::Vector3d approach = s + n * params.clearance_mm;
            const bool new_component =
                first_path && !first && layer.component != previous_component;
            const bool continues = !first && !new_component &&
                                   (g.position() - s).norm() <= kSamePoint &&
                                   g.angles().a_deg == a.a_deg && g.angles().c_deg == a.c_deg;
            if (first_path) {
                g.at("at " + layer_name(i, layer));
                if (!continues) stop_deposit();  // the last layer's end before this one's name
                g.comment(layer_number(i, layer) + ", component " +
                          std::to_string(layer.component) + ": tool axis " + vector_text(n) +
                          ", A " + format_number(a.a_deg, 8) + " C " + format_number(a.c_deg, 8));
            }
            if (!continues) {
                stop_deposit();
                // The layer the tip is on, and the tool axis it leaves along: the one before, or
                // this one between its paths.
                const std::size_t left = first_path && !first ? used[u - 1] : i;
                const Eigen::Vector3d& back = layers[left].tool_axis;
                std::vector<Waypoint> way;
                if (first) {
                    // From the sphere's top down to the first path.
                    g.comment(
                        "first to the top of a sphere clear of the part: start above the part");
                    g.rapid(summit, {level_a, a.c_deg});
                    round_the_top(summit, g.angles(), sphere.exit(s, way_out(n)), a, way);
                    way.push_back({approach, a, int(i)});
                } else if (new_component) {
                    // Out along the tool axis the last layer was deposited with, round the sphere.
                    way =
                        round_the_part(g.position(), g.angles(), back, int(left), s, n, a, int(i));
                } else {
                    way = {{g.position() + back * params.clearance_mm, g.angles(), int(left)},
                           {approach, a}};
                }
                if (check) {
                    ++stats.checked_routes;
                    std::optional<TravelHit> hit = meets(way, s, int(i), -1);
                    if (hit && !first && !new_component) {
                        // Round the sphere the tip leaves the layer's plane: the layer under way
                        // counts, all of it, but where the tip leaves it or comes back to it.
                        std::vector<Waypoint> round = round_the_part(g.position(), g.angles(), back,
                                                                     int(left), s, n, a, int(i));
                        if (!meets(round, s, int(i), first_path ? -1 : int(i))) {
                            g.comment("the way within the component meets " + obstacle_of(*hit) +
                                      ": round the part instead");
                            way = std::move(round);
                            hit.reset();
                            ++stats.rerouted_travels;
                        }
                    }
                    if (hit) report(int(i), *hit);
                }
                rapid_along(way);
                g.feed(s, params.feed_mm_min);
                first = false;
            }
            first_path = false;
            if (!depositing) {
                g.line("M62" + out_n);
                depositing = true;
            }
            for (std::size_t k = 1; k < path.points.size(); ++k) {
                const Eigen::Vector3d& p0 = path.points[k - 1];
                const Eigen::Vector3d& p1 = path.points[k];
                const double length = (p1 - p0).norm();
                if (length < kSamePoint * 1e-3) continue;
                const double t0 = path.thickness_mm[k - 1], t1 = path.thickness_mm[k];
                const std::vector<double> ends =
                    by_thickness ? feed_cuts(t0, t1, t_lo, t_hi) : std::vector<double>{1.0};
                double from_s = 0.0;
                for (const double to_s : ends) {
                    double f = params.feed_mm_min;
                    if (by_thickness) {
                        const double t = t0 + 0.5 * (from_s + to_s) * (t1 - t0);
                        f = t > 0.0 ? params.feed_mm_min * reference / t
                                    : std::numeric_limits<double>::infinity();
                        if (f < f_lo * (1.0 - 1e-12) || f > f_hi * (1.0 + 1e-12))
                            ++stats.feed_limited_moves;
                        f = std::clamp(f, f_lo, f_hi);
                    }
                    if (g.feed(p0 + to_s * (p1 - p0), f)) ++stats.deposit_moves;
                    stats.deposit_length_mm += (to_s - from_s) * length;
                    stats.deposit_time_min += (to_s - from_s) * length / f;
                    from_s = to_s;
                }
            }
        }
        previous_component = layer.component;
    }
    // Out to the sphere and up to its top, the table turning level on the way.
    stop_deposit();
    g.at("on the way off the part");
    std::vector<Waypoint> way;
    const Eigen::Vector3d out = sphere.exit(g.position(), way_out(layers[used.back()].tool_axis));
    way.push_back({out, g.angles(), int(used.back())});
    round_the_top(out, g.angles(), summit, {level_a, g.angles().c_deg}, way);
    if (check) {
        check->deposited(used.back());
        ++stats.checked_routes;
        if (const auto hit = meets(way, std::nullopt, -1, -1)) report(-1, *hit);
    }
    rapid_along(way);
    g.line("M65" + out_n);
    g.line("M2");
    std::string beyond;
    for (int axis = 0; axis < 3; ++axis) {
        const std::string& where = g.past_limits()[std::size_t(axis)];
        if (where.empty()) continue;
        const double lo = params.travel_min[axis], hi = params.travel_max[axis];
        const std::string name(1, "XYZ"[axis]);
        const std::string limits =
            lo == -kInfiniteTravel  ? "above the greatest " + name + " " + format_number(hi)
            : hi == kInfiniteTravel ? "below the least " + name + " " + format_number(lo)
                                    : "beyond the " + name + " limits " + format_number(lo) +
                                          " to " + format_number(hi);
        beyond += std::string(beyond.empty() ? "" : "; ") + "it takes " + name + " from " +
                  format_number(stats.machine_min[axis], 7) + " to " +
                  format_number(stats.machine_max[axis], 7) + " mm, " + limits + ", first " + where;
    }
    if (!beyond.empty())
        throw Error(ErrorCode::OutOfTravel,
                    "the program leaves the machine's travel (G54 at (" +
                        vector_text(params.work_offset) + ")): " + beyond +
                        "; move the part on the table (the work offset) or slice it otherwise");
    progress(1.0);
    if (stats_out) *stats_out = stats;
    return g.text();
}

}  // namespace mas
