// Test parts with known geometry, built with OCCT primitives and handed to the engine as BREP text
// (the same border FreeCAD uses), plus exact triangle meshes for the core-only tests.
#pragma once

#include <Eigen/Core>
#include <TopoDS_Shape.hxx>
#include <functional>
#include <string>
#include <vector>

#include "mas/Mesh.hpp"
#include "mas/Nozzle.hpp"
#include "mas/Polygon2.hpp"
#include "mas/Shape.hpp"

namespace mas::test {

// What `f` throws as mas::Error, "code: message" ("invalid_argument: min_layer ..."), or "no
// error".
std::string error_of(const std::function<void()>& f);

// Axis-aligned box [x0, x0 + dx] x [y0, y0 + dy] x [z0, z0 + dz].
Shape box(double x0, double y0, double z0, double dx, double dy, double dz);
// Exact 12-triangle mesh of the same box, outward oriented.
TriangleMesh box_mesh(double x0, double y0, double z0, double dx, double dy, double dz);
// Cylinder of `radius` and `height` whose base centre is `base` and axis `axis` (unit).
Shape cylinder(const Eigen::Vector3d& base, const Eigen::Vector3d& axis, double radius,
               double height);
// Paper Fig. 7: a 20 x 20 x 60 column on z = 0 with a 50 x 20 x 20 arm on its top reaching +X:
// column [0,20]x[0,20]x[0,60], arm [20,70]x[0,20]x[40,60].
Shape l_block();
// `shape` turned by `degrees` about the +Z axis through the origin (a part placed turned on the
// plate).
Shape turned_about_z(const Shape& shape, double degrees);
// The L-block's column 80 tall with the arm at its top, a gusset under the arm: column
// [0,20]x[0,20]x[0,80], arm [20,70]x[0,20]x[60,80], web 4 thick ([8,12] in y), its triangle
// (x, z) = (20, 60), (43, 60), (20, 37) against the column's face and the arm's underside.
Shape gusset_bracket();
// The gusset bracket's column with an arm `arm` mm long each way at its top, [-arm, 0] and
// [20, 20 + arm] in x, each over a web 4 thick ([8,12] in y) and 23 mm long and deep against the
// column's face.
Shape gusset_tee(double arm);
// Four 20 x 20 x 10 tiers, each 5 mm further along +X than the one below it:
// [5i, 20 + 5i] x [0, 20] x [10i, 10i + 10] for i = 0 .. 3. Every tier's +X end overhangs.
Shape staircase();
// 60 x 40 x 10 plate [0,60]x[0,40]x[0,10] with a vertical through hole of radius 8 at (30, 20).
Shape plate_with_hole();
// Two 10 x 10 posts on one 40 x 10 x 5 base plate [0,40]x[0,10]x[0,5]: posts
// [0,10]x[0,10]x[5,30] and [30,40]x[0,10]x[5,30]; one solid, two regions above z = 5.
Shape two_posts();
// An arch with a block hanging under its beam: legs [0,10]x[0,20]x[0,40] and [50,60]x[0,20]x[0,40],
// beam [0,60]x[0,20]x[40,50], block [20,40]x[0,20]x[15,40]. The block first appears at z = 15, in
// mid-air, and joins the rest only at the beam.
Shape arch_with_pendant();
// A handle on a plate: plate [0,60]x[0,20]x[0,5], posts [5,13]x[6,14]x[5,35] and
// [47,55]x[6,14]x[5,35], a bar [5,55]x[6,14]x[35,41] across their tops (a closed loop, its
// underside bridging the 34 mm between the posts).
Shape handle_on_plate();
// A wall [0,60]x[0,6]x[0,45] standing on its edge, a window [20,40] x [15,27] through it (its
// ceiling bridging 20 mm).
Shape wall_with_window();
// A portal on two legs with nothing joining them below: legs [0,8]x[0,8]x[0,30] and
// [42,50]x[0,8]x[0,30] standing on z = 0, a lintel [0,50]x[0,8]x[30,36] across their tops.
Shape portal_on_two_legs();
// A table on three legs, 4 x 4 x 31 at (0, 0), (61, 0) and (30.5, 20), under a top
// [0,65]x[0,24]x[31,38] (far wider than the legs: the axis turns it sideways off them).
Shape table_on_three_legs();
// A pipe tee: a pipe of radius 10 with a bore of 8, 60 tall on z = 0 along Z, and a branch of the
// same pipe reaching +Y from its axis at z = 35, 35 long.
Shape pipe_tee();
// The survey's pipe bend (tests/python/MultiAxisSlicerSurvey.py): a flange of radius radius +
// flange, 4 tall, on z = 0; a round riser of `radius` up to z = 4 + rise; a quarter torus bending
// it towards +X round the centre (bend_radius, 0, 4 + rise); a run along +X from x = bend_radius,
// run + 1 long. With bore > 0, a channel of that radius runs the same way from z = 3 (inside the
// flange) out of the run's end.
Shape pipe_bend(double radius, double bore, double rise, double bend_radius, double run,
                double flange);
// Torus with its axis along Z through the origin.
Shape torus(double major_radius, double minor_radius);
// A shape made of one planar face (not a solid) and a compound of two disjoint boxes.
Shape single_face();
Shape two_boxes();
// Sphere of `radius` centred on the origin (two poles: degenerated edges).
Shape sphere(double radius);
// The six faces of box(x0, .., dz) as a closed shell with no solid around it, and the same shell
// with its top face (z = z0 + dz) left out: an open shell.
Shape box_shell(double x0, double y0, double z0, double dx, double dy, double dz);
Shape open_box_shell(double x0, double y0, double z0, double dx, double dy, double dz);

// A layer of `component` whose regions are the polygons `loops` (each an outer boundary, on the
// plane of normal `n` through the first one's first point), deposited `thickness` deep along n.
Layer flat_layer(int component, const Eigen::Vector3d& n,
                 const std::vector<std::vector<Eigen::Vector3d>>& loops, double thickness);

// The nozzle's own shape, independently of Nozzle.cpp: the signed distance of `q` from the nozzle
// standing at `p` along unit `axis` (negative inside), from its outline across the axis (the tip's
// face, the cone, the body's side and end).
double nozzle_clearance(const NozzleParams& n, const Eigen::Vector3d& p,
                        const Eigen::Vector3d& axis, const Eigen::Vector3d& q);

// Between the engine's Shape and OCCT, through BREP text as FreeCAD hands shapes over.
Shape from_occt(const TopoDS_Shape& shape);
TopoDS_Shape to_occt(const Shape& shape);
// OCCT building blocks for composite test parts: a box as box() above, a cylinder of radius `r`
// and height `h` whose base centre is `base` and axis `axis` (unit), and a fusion with the seams
// between coplanar faces removed.
TopoDS_Shape occ_box(double x0, double y0, double z0, double dx, double dy, double dz);
TopoDS_Shape occ_cylinder(const Eigen::Vector3d& base, const Eigen::Vector3d& axis, double r,
                          double h);
TopoDS_Shape fuse(const TopoDS_Shape& a, const TopoDS_Shape& b);
// The planar polygon through `outline` (closed back to its first point) swept along `extrusion`.
TopoDS_Shape occ_prism(const std::vector<Eigen::Vector3d>& outline,
                       const Eigen::Vector3d& extrusion);

// A bored valve body of the survey's (MultiAxisSlicerSurvey.valve_body): a round body standing on
// the plate, a blind bore down it from z = 4 at half its radius, and round ports along `out`
// (+-X, +-Y) at height `z` reaching `reach` past its side, each bored into it at half its radius.
struct ValvePort {
    Eigen::Vector3d out;
    double radius, reach, z;
};
struct ValveBody {
    double radius, height;
    std::vector<ValvePort> ports;
    TopoDS_Shape shape() const;
};
// The survey's valve body 2 at seed 44: three ports whose bores into the central one break the
// body's ring at three heights.
ValveBody survey_valve_body_44_2();

// tests/data/`name`, read (read_model) and tessellated at its effective deflection, returned in
// `deflection` when given.
TriangleMesh data_mesh(const std::string& name, double* deflection = nullptr);

}  // namespace mas::test
