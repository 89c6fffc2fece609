// Holes filled for deposition and drilled afterwards. A round hole whose axis leans more than the
// overhang angle off a component's build direction has a ceiling: every layer across it overhangs
// the bore below (the paper's method removes overhangs by changing the build direction, and no
// direction suits both a hole and the body it goes through). What a process engineer does about
// it is what slicing does with SlicePartParams::fill_holes_up_to_mm: deposit the hole solid and
// drill it on the machine afterwards, as every deposited part is finished anyway.
//
// A hole is read on the BREP, never on a mesh:
// - its wall: the component's cylindrical faces that are concave (the material lies outside the
//   cylinder: the face's outward normal points at the axis) with a diameter up to the limit, on
//   one axis line with one radius (a cylinder split at a seam or by a decomposition plane), whose
//   extents along the axis overlap or touch: coaxial holes apart (a clevis's two lugs) are two,
//   and a wall a slot or a rib interrupts is pieces. A piece is a hole when its faces go all the
//   way round (a concave fillet, a slot's round end or a hole a plane cut lengthwise does not);
// - its bottom, when blind: a plane, a cone or a sphere no wider than the hole all of whose edges
//   the wall's faces share (a flat bottom, a drill point, a ball end; a sphere or torus the hole
//   goes through has only its seams for other edges, and is no bottom);
// - the blends round its mouths: faces, not planar, sharing an edge with its wall, lying outside
//   its radius and within twice it, and no more than its radius past an end of the wall (the
//   fillets or chamfers of the edges where it meets the faces it goes through, a countersink).
//   They are filled with it, the faces the hole goes through extended across them (drilled, its
//   mouths are finished again); its length takes them in;
// - it is filled when its axis makes more than overhang_angle_deg with the build direction (a
//   hole along the build direction has walls, no ceiling, and is deposited as it is), and when a
//   drill makes it: the whole part has no material within its wall (a post or a hollow boss in a
//   ring groove, a pin, a rib across a channel), nor, beyond one of its ends, within its radius (a
//   closed cavity, a chamber behind a narrower entry, a stretch of channel between two bends).
//   Read exactly, with one Boolean for all of a component's holes: the part in common with probe
//   cylinders 0.01 mm (at most 1 % of the radius) inside each hole, one along its wall and one from
//   each end out past the part, each piece of the common traced to its probe by the Boolean's
//   history. Nor is one filled whose lower end along the build direction opens into a bore that
//   goes on past it, left open (round a bend, or widening): its plug would end there in a face
//   across that bore, hanging over it (opens_into_bore_below() in Holes.cpp: just past that end
//   the part's material rings the hole's radius all round and none lies within it, read with
//   OCCT's point classifier; the end of the whole part's hole where the component holds a piece
//   of one, so that the pieces of a bore a split cuts across are filled or left open alike).
//   Otherwise it stays open with a note. A pipe's straight bore up to the diameter is a hole too,
//   and so is where a branch's bore pierces the wall of the pipe it leaves.
// A hole that is a plain cylinder (its wall ends in circles square to its axis, its bottom, if any,
// is flat) is filled by fusing that cylinder in: all such holes in one Boolean, which adds exactly
// the cylinders (their union). So is one whose wall's other edges all lie on the wall of another
// hole so filled: two ports' bores crossing in a manifold's block, each opening into the other near
// its blind end, which OCCT's defeaturing closed neither over (33.6 mm^2 of their ceilings overhung
// at survey seed 125). Not one opening into a bore left open (along the build direction, or too
// wide): its cylinder would stick into that bore. Any other (leaving a slanted face, opening into a
// bore left open) is closed over with OCCT's BRepAlgoAPI_Defeaturing, which removes its faces and
// extends the faces it went through across it: all at once, else, if that fails or leaves one open,
// one at a time. That is kept only when the result is one valid solid that gained material, no more
// than the holes' cylinders hold, lost none of the component and gained none outside the cylinders,
// open-ended (a face rebuilt across a mouth in a curved face bulges past the rim; Booleans); a hole
// OCCT does not fill so stays open with a note saying why. About 5 ms a hole on a wall with 36
// holes (bench/bench_slice.cpp); defeaturing takes some 60 ms a hole there. A counterbore is a hole
// of its own (a cylinder); a countersink's cone within twice the hole's radius is a blend of it.
// The blends' cylinders (their widest radius, over their extent) are allowed to gain material
// too. Without them, defeaturing the wall alone left a filleted ear's mouths as grooves, and on
// a filleted lug failed after 39 s.
#pragma once

#include <Eigen/Core>
#include <string>
#include <vector>

#include "mas/Progress.hpp"
#include "mas/Shape.hpp"

namespace mas {

struct FilledHole {
    int component = -1;  // set by slicing; fill_holes() leaves -1
    // Middle of the hole's extent along its axis (its wall's and bottom's), mm; the axis is a
    // unit vector, pointing along the build direction where it is not perpendicular to it.
    Eigen::Vector3d centre = Eigen::Vector3d::Zero();
    Eigen::Vector3d axis = Eigen::Vector3d::UnitX();
    double diameter_mm = 0.0;
    double length_mm = 0.0;  // its extent along the axis
};

// "the hole D mm across at (x, y, z)": how notes name a hole.
std::string describe(const FilledHole& hole);

// Whether a hole along `axis` leans more than `overhang_angle_deg` off `direction` (both unit
// vectors, either way along them), within 1e-9 rad: the holes fill_holes() and holes_to_fill()
// take for that build direction.
bool leans_over(const Eigen::Vector3d& axis, const Eigen::Vector3d& direction,
                double overhang_angle_deg);

struct HoleFill {
    Shape solid;                     // the component with its holes filled (the input if none)
    std::vector<FilledHole> holes;   // the holes filled, in the solid's face order
    std::vector<std::string> notes;  // one per hole that qualified and stayed open, saying why
    double added_volume_mm3 = 0.0;   // material the fills added (exact, from the BREP)
};

// Fills the holes of `solid` (one closed solid) up to `max_diameter_mm` across whose axis leans
// more than `overhang_angle_deg` off `build_direction`, where a drill reaches them from outside
// `part` (the whole part `solid` is a component of, one solid as Shape::single_solid returns it;
// null: `solid` itself). max_diameter_mm 0 fills none and returns `solid` as it is. `progress`
// is checked before each Boolean and each hole filled alone (Progress.hpp): what it throws leaves
// fill_holes. Throws Error(InvalidArgument) for a negative or non-finite diameter, an angle
// outside [0, 90) or a zero or non-finite direction, Error(GeometryFailure) when OCCT fails, and
// the errors of Shape::single_solid. The input is not modified.
HoleFill fill_holes(const Shape& solid, const Eigen::Vector3d& build_direction,
                    double max_diameter_mm, double overhang_angle_deg, const Shape& part = Shape(),
                    const Progress& progress = {});

// The holes fill_holes() would fill, found and checked the same way (a drill reaches them) but
// not filled: what it fills unless OCCT fails to. Nothing is changed. Throws as fill_holes().
std::vector<FilledHole> holes_to_fill(const Shape& solid, const Eigen::Vector3d& build_direction,
                                      double max_diameter_mm, double overhang_angle_deg,
                                      const Shape& part = Shape(), const Progress& progress = {});

}  // namespace mas
