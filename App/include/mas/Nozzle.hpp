// The build sequence against the nozzle (paper Sec. 4.2.3, Eq. 10): the order the layers are
// deposited in, so that the nozzle never meets what is already deposited, with the collisions no
// order avoids reported layer by layer.
//
// How the paper is read, and the choices made (each tested in tests/engine/test_nozzle.cpp):
// - The nozzle, along the tool axis n (the layer's normal) from the deposit point p: nothing for
//   the first standoff_mm (the powder or wire stream and the beam or arc, which may pass close to
//   anything), then the tip, a cone frustum tip_diameter_mm across at its face widening at
//   cone_angle_deg (half-angle) until it is body_diameter_mm across, then the body, a cylinder of
//   that diameter body_length_mm long. Eq. 10 writes B_dep ∩ B_tip ∩ B_body = ∅; it is read as the
//   union: neither the tip nor the body may meet B_dep.
// - What is deposited: every layer's prism, its regions on its plane swept back along its normal
//   down to its lower plane (the paper's "sweeping the slicing layer"), and the build plate, the
//   plane the part stands on (unbounded: the table is taken to reach past the part).
// - A layer x collides with a layer y deposited before it when the nozzle, anywhere along x's
//   deposit paths (every point of every segment), comes within margin_mm of y's prism. y's
//   surface is sampled so that every point of it lies within margin_mm of a sample (its outline
//   at its top, its bottom and levels between, its top and bottom faces on a grid), and a sample
//   counts when it lies in the nozzle grown by g = 2 margin_mm (heights standoff - g to the
//   body's end + g, radius R(h) + g / cos(cone_angle) but no more than the body's + g, which
//   holds every point within g of the nozzle). So every collision is found, and a reported one
//   comes within near_miss_mm(params) = g sqrt(1 + 1 / cos^2(cone_angle)) of the nozzle (6.1 mm at
//   the defaults). The standoff must be at least g, or the grown tip would reach into the layer it
//   deposits on.
//   The plate is exact: the nozzle's lowest point comes within margin_mm of it.
// - The order (Sec. 4.2.3: a child waits for its father; brothers switch when a collision would
//   occur, "discontinued just before a collision happens"). The paper's child waits for all of
//   its father; what it rests on is the father's layers next to it, and a post on a ledge a few
//   mm from the column the ledge leaves, built after the whole column, has the nozzle meet the
//   column's top all the way up. So a component starts once every component it must wait for
//   (`waits_for`: the earlier components its first layer rests on, SlicePart.hpp's build order)
//   is complete, and its father's layers it may rest on are deposited: up to the last one whose
//   prism's box comes within the part's thickest layer of the box of the component's own layers
//   (all of them when none does); the same holds down the tree (a component does not start before
//   its father may). A layer y of one component and a layer x of another, neither of which comes
//   first by those rules, give x before y when y's prism would lie in x's nozzle: so a father's
//   layers above those its child may rest on go up with the child, as brothers' layers do. The
//   layers are then taken one by one: the same component's next layer while nothing it would
//   block is still to come; otherwise, of the components that may go on, the first in
//   `start_order` whose next layer blocks nothing to come. When none may go on (the constraints
//   form a cycle), the next layer that blocks the fewest layers to come is taken (then the first
//   in `start_order`): those layers collide. (A heuristic: another order might leave fewer.)
// - A layer whose nozzle meets its own component's earlier layers, or a layer of another that
//   comes first by the rules above, collides whatever the order; so does one whose nozzle meets
//   the plate. Each colliding layer is reported once, with one obstacle: the plate, else the layer
//   that comes deepest into the nozzle itself (the least signed distance from the nozzle's
//   surface, negative inside, of any of its samples over the deposit point nearest it), at that
//   sample and point.
// - Leaning the nozzle (not in the paper; a 5-axis CAM's "tilt the tool to avoid a collision"). A
//   sideways arm near the plate has a coaxial nozzle's body reach under the plate, whatever the
//   order. The layer stays as it is, and its paths; only the tool axis a leans from the layer's
//   normal n by an angle theta, one axis for the whole layer, where that clears what the coaxial
//   nozzle met. Tried for each colliding layer once the order is set: theta = 5, 10, ... degrees up
//   to max_lean_deg (and max_lean_deg itself), each towards the plate's normal, away from the
//   reported obstacle (across n, from the obstacle towards the deposit point), then the other ways
//   round n every 22.5 degrees from the first of those, nearest it first (a crank's last leg built
//   back along -X past its riser: leaned up off the plate, the nozzle still comes within the margin
//   of what is deposited, and it leans half way between up and away from the riser; one 6.3 mm
//   beside its riser found no lean clear every 45 degrees, and leans 67.5 degrees round from up,
//   away from the riser, by 25); the first that clears is taken: the least lean, towards the
//   plate's normal before away from the obstacle before the others; a lean turning the axis further
//   from the plate's normal than the layer's normal is, past the horizontal, is not taken (a
//   machine reaching the normal might not reach it). A lean clears when along every deposit path
//   the nozzle keeps margin_mm from the plate (exact) and from every layer deposited before it:
//   those lying wholly under the layer's plane cannot come near, since only leans keeping the whole
//   nozzle margin_mm above that plane are tried (standoff cos theta - tip sin theta >= margin, and
//   theta + cone_angle < 90 degrees, so that the cone's lower side still rises); the others are
//   tested as above, with the deposit moves cut into pieces whose heights along a differ by at most
//   margin_mm and each piece given the grown radius at its lowest point, and, as the travel check
//   below, a sample the grown nozzle may hold counts only when the nozzle itself, its tip taken
//   every 0.05 margin_mm along the moves, comes within 2.05 margin_mm of it, and then only where
//   it, or one of the layer's finer samples within 1.125 margin_mm of it, comes within 1.175
//   margin_mm (so no lean is taken that comes within the margin, and one is refused only when it
//   comes within 1.175 margin_mm: the grown nozzle alone reached 9.3 mm at the defaults, beside the
//   tip, where a blade's first layer leaned off the plate refused every lean beside a neighbouring
//   blade's root and was kept in the hub; a sample's count alone refused the leans a crank's last
//   leg needed beside its riser, 231 mm^2 of it hanging in its father's layers, and those that
//   built a spiral stair's treads along their lines). A lean changes no other layer's check: a
//   later layer's nozzle meets this one's prism, whatever its axis. Where no lean clears, the layer
//   keeps its normal and its collision. max_lean_deg = 0 keeps the nozzle coaxial, as the paper's.
// - The order is found with coaxial nozzles, and the leans after it; it can leave a lean no way (a
//   rod built sideways under a bar: leaned up off the plate, the rod's nozzle meets the bar where
//   the bar's layers came first). Where layers still collide, the layers are ordered again (the
//   same rules) without the pairs "x before y" that x's nozzle would clear leaned towards the
//   plate's normal (by any of the leans above that also keeps it off the plate; y's own rule
//   stands), the leans tried again on that order, and that sequence is kept when fewer layers
//   collide. The order can also be what leaves a layer no lean the other way: two blades built
//   sideways off a hub, 10 mm apart at their roots, both low over the plate, so that every layer
//   must lean up off it; coaxial, the second blade's first layer missed the first blade, whose
//   layers then came first, and leaned it met them (a collision round then kept both blades in
//   the hub, 602 mm^2 unsupported under them). Where layers still collide, they are ordered again
//   with, for each layer x whose coaxial nozzle meets the plate, the pairs "x before y" for the
//   layers y (of other components, not before or after x whatever the order) that x's nozzle
//   meets at the lean keeping it off the plate that meets fewest (the least lean among equals),
//   the leans tried again, and that sequence is kept when fewer layers collide.
// - Travel (not in the paper, which checks the deposit moves only): the post-processor's moves off
//   the paths (Gcode.hpp: retracts, moves between paths and layers, the routes round the part) are
//   checked against the same nozzle by TravelCheck: along every move the nozzle keeps margin_mm
//   from the plate (exact where the table keeps still and at the ends of a piece along which it
//   turns, below) and from every layer deposited before it, the layer under way excepted (its
//   paths lie on its plane, which the nozzle keeps the margin above: the tip stays on or above the
//   plane along the tool axis), and so is the layer a move leaves or comes back to
//   along its tool axis from a deposit point on it (NozzleMove::along_layer; standoff >= 2 margins
//   and the leans' rule keep the nozzle the margin above its plane there, which a check with the
//   grown nozzle might not tell). The moves along which the table keeps still are
//   binned as the leans' are (cut into pieces whose heights along the axis are at most margin_mm
//   apart, each given the grown radius at its lowest point); a move along which the table turns is
//   cut into pieces along which the tool axis turns by at most max_turn_rad() = margin_mm / L (L:
//   the distance from the deposit point to the rim of the body's end, the nozzle's farthest
//   point), so that every point of the nozzle stays within an allowance a = L x turn <= margin_mm
//   of the nozzle along the piece's first axis, which is tested grown by a more (from the plate it
//   keeps a more). Where the piece's last axis is given (NozzleMove::to_axis), the plate is judged
//   from both ends instead, exactly there: at a fraction s of the way the nozzle lies within a x s
//   of the nozzle along the first axis and within a x (1 - s) of the nozzle along the last, the
//   tip where it is, so its lowest point lies no lower than the higher of those two nozzles'
//   lowest points, less s a and (1 - s) a; the piece passes where that keeps the margin all the
//   way. (Judged by the first axis alone, a nozzle turning down onto a layer's tool axis that the
//   sequence had passed 2.05 mm over the plate, a margin and 2.5 %, was reported as meeting the
//   plate on the way.) A sample in the grown nozzle counts only when the nozzle along the
//   first axis, its tip taken every 0.05 margin_mm along the move, comes within 2.05 margin_mm + a
//   of it, and then only where it, or one of the layer's finer samples, every margin_mm / 8,
//   within 1.125 margin_mm of it, comes within 1.175 margin_mm + a (every point of the surface
//   within the margin of the nozzle lies within a margin of a sample, and within an eighth of one
//   of a finer sample near it). So no move is passed that comes within the margin, and one is
//   reported only when it comes within 1.175 margin_mm + 2a of a deposited layer's surface (2.35 mm
//   at the defaults with the table still, at most 6.35 turning; 4.1 and 8.1 before the finer
//   samples: a wall's two shelves 1.9 mm apart, the upper built out first, had 44 routes onto its
//   first layers reported, the nozzle's face 4 mm from the lower shelf, twice the margin).
#pragma once
#include <Eigen/Core>
#include <memory>
#include <optional>
#include <vector>

#include "mas/Progress.hpp"
#include "mas/Section.hpp"
#include "mas/Slicing.hpp"
#include "mas/Toolpath.hpp"

namespace mas {

// A coaxial deposition nozzle (laser powder DED; the defaults are of that class). All in mm and
// degrees.
struct NozzleParams {
    double standoff_mm = 10.0;       // deposit point to the tip's face, along the tool axis; >= 0
    double tip_diameter_mm = 10.0;   // the tip's face; > 0, <= body_diameter_mm
    double cone_angle_deg = 30.0;    // half-angle of the tip's cone; in (0, 90) unless no cone
    double body_diameter_mm = 50.0;  // the body's cylinder
    double body_length_mm = 200.0;   // > 0
    double margin_mm = 2.0;          // clearance kept from deposited material; > 0, <= standoff / 2
    bool check_plate = true;         // the build plate is an obstacle too
    double max_lean_deg = 30.0;      // the most the tool axis leans from the normal; [0, 90)
};

// The farthest the nozzle may reach from its deposit point (the body's end's rim), in margins. The
// travel check cuts the table's turns into steps that move that point at most a margin, so their
// count grows with it: a 1e9 mm standoff, body diameter or cone (a cone angle of 1e-6 degrees)
// made a crank's G-code take 1.7 GB in 8 s cutting one turn. At the defaults it is 123.
inline constexpr double kMaxNozzleReachInMargins = 1e5;

// Throws mas::Error(InvalidArgument) naming the first parameter out of its range (and a nozzle
// reaching further than kMaxNozzleReachInMargins margins).
void validate(const NozzleParams& params);

// The least margin_mm for deposits `size` mm across (their bounding box's diagonal), as a fraction
// of it. The checks sample what is deposited margin_mm apart (above), so that their work and memory
// grow as (size / margin_mm)^2 a layer: 1e-6 mm took 6 GB in a minute in the travel check of a
// 68 mm Z of sheet, and 1.6 GB in 30 s in the sequence of a 90 mm hub. At this least a flat layer
// 100 mm square on a 150 mm part takes 3.6 million samples, and the default margin suits parts up
// to 4 m across.
inline constexpr double kMinMarginFraction = 5e-4;

// validate(params), and throws mas::Error(InvalidArgument) when margin_mm is less than
// kMinMarginFraction of `size`, with the least it may be; `what` names the deposits ("the part").
void validate(const NozzleParams& params, double size, const std::string& what);

// The diagonal of the box round the layers' regions on their planes, mm (0 for none).
double layers_size(const std::vector<Layer>& layers);

// The tip's cone length along the axis (0 when tip and body are one diameter).
double cone_length(const NozzleParams& params);
// The farthest a reported collision can be from a true one (see above).
double near_miss_mm(const NozzleParams& params);
// Whether `point` lies within the nozzle grown as above, the nozzle's deposit point at `tip` with
// unit tool axis `axis`.
bool in_grown_nozzle(const NozzleParams& params, const Eigen::Vector3d& tip,
                     const Eigen::Vector3d& axis, const Eigen::Vector3d& point);

struct NozzleCollision {
    int layer = -1;           // the layer being deposited
    int obstacle_layer = -1;  // the deposited layer the nozzle meets; -1 for the build plate
    Eigen::Vector3d nozzle_at = Eigen::Vector3d::Zero();  // the deposit point where it does
    Eigen::Vector3d obstacle = Eigen::Vector3d::Zero();   // the obstacle's point it comes near
};

struct BuildSequence {
    std::vector<int> layers;                  // every layer index once, in deposition order
    std::vector<NozzleCollision> collisions;  // one per colliding layer, in sequence order
    int component_switches = 0;               // consecutive layers of different components
    int interrupted_components = 0;           // components left unfinished for another and resumed
    // Per layer (by index): its tool axis, the layer's normal or the nozzle leaned from it.
    std::vector<Eigen::Vector3d> tool_axes;
    int leaned_layers = 0;  // layers whose tool axis leans from their normal
};

struct SequenceInput {
    const std::vector<Layer>* layers = nullptr;  // grouped by component, each bottom to top
    const std::vector<LayerToolpaths>* toolpaths = nullptr;  // one per layer
    std::vector<int> parent;                  // per component: its father, -1 for the root
    std::vector<std::vector<int>> waits_for;  // per component: others to complete first
    std::vector<int> start_order;             // every component once: the preferred order
    Plane plate;                              // the build plate (normal up)
};

// One move of the nozzle off the deposit paths: its tip straight from `from` to `to`, its tool axis
// (unit) `axis` at `from` and turning by at most `turn_rad` from it on the way, to `to_axis` (unit)
// at `to` where that is given (zero: not given; see "Travel" for what the check makes of it), the
// tool axis at each point of the way within turn_rad times the fraction of the way from `axis`,
// and within turn_rad times the fraction left from `to_axis`, as when the table's angles turn in
// proportion. `along_layer`: a layer the move leaves or comes back to along its tool axis, between
// a deposit point on it and over it (the table still): it is not checked against that layer, which
// lies under its plane, the nozzle the margin above it (see "Travel").
struct NozzleMove {
    Eigen::Vector3d from = Eigen::Vector3d::Zero(), to = Eigen::Vector3d::Zero();
    Eigen::Vector3d axis = Eigen::Vector3d::UnitZ();
    double turn_rad = 0.0;
    int along_layer = -1;
    Eigen::Vector3d to_axis = Eigen::Vector3d::Zero();
};

// What a move meets: a deposited layer (-1: the build plate), its point near the nozzle, and the
// tip's point on the move nearest it.
struct TravelHit {
    int obstacle_layer = -1;
    Eigen::Vector3d nozzle_at = Eigen::Vector3d::Zero(), obstacle = Eigen::Vector3d::Zero();
};

// The travel moves against the nozzle (see "Travel" above), as layers are deposited one by one.
class TravelCheck {
public:
    // `layers`: every layer's prism (kept by reference: it must outlive the check), none deposited
    // yet. Throws InvalidArgument for bad params.
    TravelCheck(const std::vector<Layer>& layers, const NozzleParams& params, const Plane& plate);
    ~TravelCheck();
    TravelCheck(const TravelCheck&) = delete;
    TravelCheck& operator=(const TravelCheck&) = delete;

    // Layer `k` is deposited: the moves after this are checked against it too.
    void deposited(std::size_t k);
    // Something the nozzle meets along `moves` (of the first run of them that meets something);
    // nullopt when it keeps clear. `also`: a layer counted as deposited for these moves alone (-1:
    // none). Throws InvalidArgument for a move turning by more than max_turn_rad(), a to_axis
    // given that is not unit or lies further than turn_rad from its axis, or a layer named that the
    // check lacks.
    std::optional<TravelHit> meets(const std::vector<NozzleMove>& moves, int also = -1) const;
    // The most a move's tool axis may turn (radians).
    double max_turn_rad() const;

private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

// Throws InvalidArgument for bad params or an inconsistent input (a component's layers not
// together, a father or wait that cannot come first); `progress` is reported while the layers
// are compared and may cancel.
BuildSequence plan_build_sequence(const SequenceInput& input, const NozzleParams& params,
                                  const Progress& progress = {});

}  // namespace mas
