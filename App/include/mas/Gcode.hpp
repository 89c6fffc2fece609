// The post-processor: a sliced part's deposition paths as a 5-axis G-code program, in LinuxCNC's
// RS274NGC dialect, for a machine whose nozzle stays vertical (machine +Z) while a tilting rotary
// table turns the part under it: A tilts the table about X, C turns the part about the table's
// normal (LinuxCNC's xyzac-trt-kins).
//
// How it reads the machine, and the choices made (each tested in tests/engine/test_gcode.cpp,
// against LinuxCNC's own kinematics module in tests/engine/test_linuxcnc_kins.cpp, and through
// LinuxCNC's rs274 interpreter in tests/cli/test_cli.py):
// - Coordinates. X Y Z are the part's own coordinates in mm: the nozzle tip's position in the
//   table's frame, which is what a controller with tool-centre-point kinematics takes
//   (xyzac-trt-kins moves the joints so that the tip follows them whatever A and C are). Set the
//   work offset (G54) so that the part's origin is where the part sits on the table, and have the
//   nozzle's tool length offset in force (G43), which xyzac-trt-kins reads for its tool-centre
//   point: the program leaves tool length compensation as it finds it. A and C are in degrees.
//   Given the build plate (a TravelNozzle), the header says the plane the part stands on and how
//   far from the plate's surface G54's Z goes: a part modelled centred on its origin or above it
//   keeps its own Z, which an operator setting G54 on the plate's surface would miss.
// - Orientation. Each layer is deposited with its tool axis n (Nozzle.hpp), turned to machine +Z:
//   towards the nozzle, which points down. xyzac-trt-kins maps a part vector v to Rx(A) Rz(C) v, so
//   with the tilt theta = atan2(hypot(n.x, n.y), n.z) in [0, 180] degrees, n needs either
//   A = theta, C = atan2(n.x, n.y), or A = -theta, C + 180. Of the solutions within the limits (to
//   1e-9 degrees, then held to them), the one nearest the previous (A, C) is taken (the sum of
//   both moves), C moved by the multiple of 360 that brings it nearest the previous C within its
//   limits. Within 1e-7 rad of +Z or -Z (finer than an A word's 1e-4 degrees) C is free: it keeps
//   its previous value. A layer no solution reaches is an error (unreachable_orientation) naming
//   the layer, its tool axis and what it needs: the tilt beyond A's limits, or the C beyond C's.
// - Deposition. A deposit path runs at G1 with the deposition output on: M62 P<n> switches it
//   with the start of the path's first move, M63 P<n> off with the start of the retract after it.
//   M65 P<n> switches it off at once at the start and at the end of the program. A path starting
//   where the last one ended (within 1 micron, the table as it is) goes on without a stop. A path
//   of one point, or of points all in one place, is not run; a layer of such paths is skipped.
// - Feed. A constant powder or wire rate builds a bead the thicker the slower the nozzle moves, so
//   where the deposit under a path is t thick (a tilted layer's thickness varies across it) the
//   feed is F = feed x reference / t, kept within [feed / max_feed_ratio, feed x max_feed_ratio]
//   (moves held at a bound are counted). A move along which t changes is cut where t enters and
//   leaves [reference / ratio, reference x ratio] and, between, into pieces whose ends differ by a
//   ratio of at most 1.05 (at most ln(ratio^2) / ln 1.05 pieces: 57 at ratio 4), each at the feed
//   of its middle. max_feed_ratio = 1 keeps the feed constant.
// - Travel, within a layer and between layers of one component: G0 back along the tool axis by
//   `clearance_mm`, G0 to `clearance_mm` along the next tool axis from the next path's start
//   (turning the table on the way), G1 down to it at the feed. Both ends lie above the plane on top
//   of the last layer deposited, so the whole move does (the component's own material lies under
//   it; another component's, and the nozzle's body, are the travel check's, below).
// - Travel between components, and to the first and from the last layer: out along the tool axis
//   to a sphere round everything the program deposits (every layer's outline and path points, as
//   deep under them as the layer reaches) plus `clearance_mm`, along that sphere's meridians over
//   its top (G0 steps of at most 10 degrees; the steps' ends lie on a sphere 1 / cos 5 degrees
//   larger, so that no step cuts inside), and in along the next tool axis. A tool axis pointing
//   below the horizontal (a layer tilted past 90 degrees) is levelled for the way out and in, its
//   Z dropped: along it, the nozzle's body, reaching back along the axis, sank lower than where it
//   deposited (a cane bent over 135 degrees, its last layers tilted 97 degrees, 57 mm up: the
//   body's far end came within the margin of the plate 240 mm out); levelled, the way still
//   moves away from the layer's plane. On the way up the table
//   turns level (A to 0, or the nearest A within its limits, in proportion to the way), at the top
//   C turns, on the way down A turns to the next layer's: at the top the nozzle stands along the
//   sphere's radius, out of it (turning in proportion over the whole way, a nozzle lying on its
//   side at the top reaches down the sphere's side towards the part's edge: on 9 of 181 parts
//   tried, 34 routes were reported, 18 of them driving the nozzle into the part). The meridians
//   keep the route's height between its two ends and the sphere's top; a tool axis tilted past 90
//   degrees from low material can still take it below the build plate's level. The first move
//   goes to the sphere's top from wherever the machine is, the table level.
// - The travel against the nozzle (given a TravelNozzle: the slicing's nozzle and build plate, and
//   each layer's prism). Every route above but the first move to the sphere's top (from wherever
//   the machine is) is checked, the plunge at the feed included, against the plate and the layers
//   deposited before it (Nozzle.hpp's TravelCheck; the table turning as it does, A and C in
//   proportion along each move). Where the way from one path to the next within a component
//   would meet something, it goes round the sphere instead, when that way keeps clear (a comment
//   says so). A route that meets something all the same is kept (the shorter one), preceded by a
//   comment naming what it meets, and reported (GcodeStats::travel_collisions). A route along
//   which the table turns and which meets something is checked again with each turning piece
//   that meets something on its own cut into pieces turning 20 times less (an allowance of at
//   most margin / 20, Nozzle.hpp; the others keep the margin already, and refining only those
//   costs the coil's program 2.4 times less): a route is taken round the part or
//   reported only where the nozzle comes within 1.275 margins of a deposited layer's surface
//   (2.55 mm at the defaults), or within the margin of the plate where the table keeps still and at
//   both ends of a piece along which it turns, within 1.0001 margins between them (each turning
//   piece judged from both its ends, NozzleMove::to_axis: a route turning down onto a layer that
//   the sequence passed a margin and 2.5 % over the plate was reported as meeting it; and a
//   piece still meeting something with both its ends clear cut 20 times finer again, twice at
//   most: at 1.05 margins, one onto a layer 1.5 % over them was reported). The moves
//   out of a layer and back to it along its tool axis are not checked against that layer
//   (NozzleMove::along_layer); round the part between two paths of one layer, that layer counts,
//   all of it, on the rest of the way.
//   The deposit moves are the build sequence's to check (plan_build_sequence).
// - The machine's X Y Z travel (not in the paper). Where the joints go depends on where the part
//   sits and where the table pivots, so the check takes both: the work offset (G54: where the
//   part's origin lies in the machine's frame, A and C at 0), xyzac-trt-kins' pivot (its HAL pins
//   x-rot-point, y-rot-point, z-rot-point, y-offset, z-offset) and the tool length (its
//   tool-offset pin, motion.tooloffset.z). machine_position() is its inverse kinematics: the
//   part's point p, in the world frame w = p + work offset, turned by C about the vertical line
//   through (x-rot-point, y-rot-point) and tilted by A about the line along X through
//   (y-rot-point + y-offset, z-rot-point + z-offset), plus the tool length on Z (tested against
//   the module with its pins set). Every move is followed, the first (from wherever the machine
//   is) from its end: where the table keeps still the joints move straight, where it turns they
//   are taken every kJointStepDeg of A and of C: between two of them a joint strays from the
//   chord by some 1e-5 of its distance from the axes (the sagitta of a half-degree turn, 9.5e-6,
//   and the turn times the move's step over 4). The joints' ranges are reported
//   (GcodeStats) whether or not limits are given; a program taking a joint past a finite limit is
//   an error (OutOfTravel) naming the axis, the range the program needs, the limits, and the layer
//   at whose moves it first goes past them.
#pragma once
#include <Eigen/Core>
#include <limits>
#include <string>
#include <vector>

#include "mas/Progress.hpp"
#include "mas/SlicePart.hpp"
#include "mas/Toolpath.hpp"

namespace mas {

inline constexpr double kInfiniteTravel = std::numeric_limits<double>::infinity();

// The step (degrees of A and of C) at which the joints are followed where the table turns.
inline constexpr double kJointStepDeg = 0.25;

struct MachineParams {
    // Travel limits of the table's axes, degrees (LinuxCNC's sample xyzac-trt.ini).
    double a_min_deg = -100.0, a_max_deg = 50.0;
    double c_min_deg = -36000.0, c_max_deg = 36000.0;
    double feed_mm_min =
        600.0;  // deposition feed where the deposit is reference_thickness_mm thick
    // 0: half-way between the thinnest and the thickest deposit of the program.
    double reference_thickness_mm = 0.0;
    double max_feed_ratio = 4.0;  // the feed stays within [feed / ratio, feed x ratio]; >= 1
    double clearance_mm = 2.0;    // retract along the tool axis, and the margin of the sphere; > 0
    int deposit_output = 0;       // the digital output (M62/M63/M65 P) that switches deposition
    // The X Y Z travel, mm in the machine's frame (the joints: where the nozzle's gauge line goes,
    // the tool length above its tip). Infinite (the default): not checked.
    Eigen::Vector3d travel_min = Eigen::Vector3d::Constant(-kInfiniteTravel);
    Eigen::Vector3d travel_max = Eigen::Vector3d::Constant(kInfiniteTravel);
    Eigen::Vector3d work_offset = Eigen::Vector3d::Zero();  // G54, mm
    Eigen::Vector3d rot_point = Eigen::Vector3d::Zero();    // xyzac-trt-kins' x/y/z-rot-point, mm
    double rot_offset_y_mm = 0.0, rot_offset_z_mm = 0.0;    // its y-offset and z-offset pins
    double tool_length_mm = 0.0;  // its tool-offset pin: the nozzle's tool length offset
};

// Throws mas::Error(InvalidArgument) naming the first parameter out of its range; the feed range
// [feed / max_feed_ratio, feed x max_feed_ratio] must lie within [0.1, 1e6] mm/min.
void validate(const MachineParams& params);

// What the post-processor reads of one layer.
struct GcodeLayer {
    int index = -1;  // the part's layer number, named in comments and errors (-1: its place here)
    int component = 0;
    Eigen::Vector3d tool_axis = Eigen::Vector3d::UnitZ();  // unit length
    std::vector<ToolPath> paths;                           // travel moves are not followed
    std::vector<Eigen::Vector3d> outline;  // every point of its regions' loops, on its plane
    double max_thickness_mm = 0.0;         // the deposit under its plane reaches no deeper
    // What it deposits, for the travel check: its regions on its plane down to its lower plane
    // (plane, lower and regions are read; no regions: nothing).
    Layer prism;
};

// The nozzle and build plate the travel is checked against (the slicing's).
struct TravelNozzle {
    NozzleParams params;
    Plane plate;
};

// A route between paths (or off the part) along which the nozzle meets what is deposited.
struct TravelCollision {
    int layer = -1;           // the layer it leads to (as named in the program); -1: off the part
    int obstacle_layer = -1;  // the deposited layer it meets (as named), -1 for the build plate
    Eigen::Vector3d nozzle_at = Eigen::Vector3d::Zero();  // the tip's point on the route
    Eigen::Vector3d obstacle = Eigen::Vector3d::Zero();   // the obstacle's point near the nozzle
};

// The layers of a sliced part, in their sequence (SlicedPart::sequence; in their order when it
// does not name every layer), each with its prism.
std::vector<GcodeLayer> gcode_layers(const SlicedPart& part);

// The table's angles (degrees) that turn `tool_axis` (unit length) to machine +Z, nearest to
// (previous_a, previous_c) as above; false when no solution lies within the limits.
struct TableAngles {
    double a_deg = 0.0, c_deg = 0.0;
};
bool table_angles(const Eigen::Vector3d& tool_axis, const MachineParams& params, double previous_a,
                  double previous_c, TableAngles& out);

// The machine's X Y Z joints (mm) with the nozzle tip at `p` (the part's frame) and the table at
// `angles`: xyzac-trt-kins' inverse kinematics with the params' work offset, pivot and tool length
// (above).
Eigen::Vector3d machine_position(const Eigen::Vector3d& p, const TableAngles& angles,
                                 const MachineParams& params);

struct GcodeStats {
    int lines = 0;
    int deposit_moves = 0;  // G1 moves with deposition on (none to where the nozzle is, to 1e-4)
    int feed_limited_moves = 0;  // of those, held at a bound of the feed range
    int reorientations = 0;      // moves that turn the table
    double a_min_deg = 0.0, a_max_deg = 0.0, c_min_deg = 0.0, c_max_deg = 0.0;  // used
    double deposit_length_mm = 0.0;
    double deposit_time_min = 0.0;  // the deposit moves at their feeds
    double rapid_length_mm = 0.0;   // of the tool tip, in the part's frame
    double reference_thickness_mm = 0.0;
    // The machine's X Y Z joints the program takes (machine_position()), least and greatest; the
    // first move's start (wherever the machine is) not counted.
    Eigen::Vector3d machine_min = Eigen::Vector3d::Zero(), machine_max = Eigen::Vector3d::Zero();
    // With a TravelNozzle: the routes checked, those taken round the part because the way within
    // the component would meet something, and those meeting something all the same.
    int checked_routes = 0;
    int rerouted_travels = 0;
    std::vector<TravelCollision> travel_collisions;
};

// With a travel check, the clearance may be at most this many of the nozzle's margins: the check
// walks the routes in steps of a twentieth of a margin where they pass near a deposited layer, and
// the retracts and the sphere's meridians grow with the clearance (a clearance of 1e9 mm ran past
// a minute on a hub of four blades; 1e4 mm, 5000 margins, took 2 s on a crank).
inline constexpr double kMaxClearanceInMargins = 1e4;

// The program. Throws InvalidArgument for bad params (the nozzle's too, and a clearance over
// kMaxClearanceInMargins of its margins) or a layer without a unit
// tool axis, EmptyInput when no layer deposits anything, Error(UnreachableOrientation) and
// Error(OutOfTravel) as above.
// `progress` is reported per layer and may cancel. `nozzle`: the travel is checked against it
// (null: not checked).
std::string write_gcode(const std::vector<GcodeLayer>& layers, const MachineParams& params,
                        GcodeStats* stats = nullptr, const Progress& progress = {},
                        const TravelNozzle* nozzle = nullptr);

}  // namespace mas
