#include "test_parts.hpp"

#include <BRepAlgoAPI_Cut.hxx>
#include <BRepAlgoAPI_Fuse.hxx>
#include <BRepBndLib.hxx>
#include <BRepBuilderAPI_MakeFace.hxx>
#include <BRepBuilderAPI_MakePolygon.hxx>
#include <BRepBuilderAPI_Transform.hxx>
#include <BRepPrimAPI_MakeBox.hxx>
#include <BRepPrimAPI_MakeCylinder.hxx>
#include <BRepPrimAPI_MakePrism.hxx>
#include <BRepPrimAPI_MakeSphere.hxx>
#include <BRepPrimAPI_MakeTorus.hxx>
#include <BRepTools.hxx>
#include <BRep_Builder.hxx>
#include <Bnd_Box.hxx>
#include <TopExp_Explorer.hxx>
#include <TopoDS.hxx>
#include <TopoDS_Compound.hxx>
#include <TopoDS_Shell.hxx>
#include <algorithm>
#include <cmath>
#include <gp_Ax2.hxx>
#include <gp_Pln.hxx>
#include <gp_Trsf.hxx>
#include <sstream>

#include "mas/Angles.hpp"
#include "mas/Error.hpp"
#include "mas/Polygon2.hpp"

namespace mas::test {

std::string error_of(const std::function<void()>& f) {
    try {
        f();
    } catch (const Error& e) {
        return std::string(to_string(e.code())) + ": " + e.what();
    }
    return "no error";
}

Shape from_occt(const TopoDS_Shape& s) {
    std::ostringstream out;
    BRepTools::Write(s, out);
    return Shape::from_brep_string(out.str());
}

TopoDS_Shape to_occt(const Shape& shape) {
    std::istringstream in(shape.to_brep_string());
    TopoDS_Shape s;
    BRep_Builder builder;
    BRepTools::Read(s, in, builder);
    return s;
}

TopoDS_Shape occ_box(double x0, double y0, double z0, double dx, double dy, double dz) {
    return BRepPrimAPI_MakeBox(gp_Pnt(x0, y0, z0), dx, dy, dz).Shape();
}

TopoDS_Shape occ_cylinder(const Eigen::Vector3d& base, const Eigen::Vector3d& axis, double r,
                          double h) {
    return BRepPrimAPI_MakeCylinder(
               gp_Ax2(gp_Pnt(base.x(), base.y(), base.z()), gp_Dir(axis.x(), axis.y(), axis.z())),
               r, h)
        .Shape();
}

TopoDS_Shape fuse(const TopoDS_Shape& a, const TopoDS_Shape& b) {
    BRepAlgoAPI_Fuse f(a, b);
    f.SimplifyResult();
    return f.Shape();
}

TopoDS_Shape ValveBody::shape() const {
    TopoDS_Shape body =
        occ_cylinder(Eigen::Vector3d::Zero(), Eigen::Vector3d::UnitZ(), radius, height);
    TopoDS_Shape bores =
        occ_cylinder(Eigen::Vector3d(0, 0, 4), Eigen::Vector3d::UnitZ(), radius / 2, height - 4);
    for (const ValvePort& p : ports) {
        body =
            fuse(body, occ_cylinder(Eigen::Vector3d(0, 0, p.z), p.out, p.radius, radius + p.reach));
        bores = fuse(bores, occ_cylinder(Eigen::Vector3d(0, 0, p.z), p.out, p.radius / 2,
                                         radius + p.reach + 1));
    }
    return BRepAlgoAPI_Cut(body, bores).Shape();
}

ValveBody survey_valve_body_44_2() {
    return {
        12.733402002719357,
        40.47687456363066,
        {{-Eigen::Vector3d::UnitY(), 5.118019116592789, 18.54138671998311, 14.28576659735294},
         {Eigen::Vector3d::UnitY(), 9.361050822457926, 17.75910751014773, 18.591670945151595},
         {-Eigen::Vector3d::UnitX(), 9.222047330533757, 6.430422215651301, 17.047264395745707}}};
}

TopoDS_Shape occ_prism(const std::vector<Eigen::Vector3d>& outline,
                       const Eigen::Vector3d& extrusion) {
    BRepBuilderAPI_MakePolygon polygon;
    for (const auto& p : outline) polygon.Add(gp_Pnt(p.x(), p.y(), p.z()));
    polygon.Close();
    return BRepPrimAPI_MakePrism(BRepBuilderAPI_MakeFace(polygon.Wire()).Face(),
                                 gp_Vec(extrusion.x(), extrusion.y(), extrusion.z()))
        .Shape();
}

Shape box(double x0, double y0, double z0, double dx, double dy, double dz) {
    return from_occt(occ_box(x0, y0, z0, dx, dy, dz));
}

TriangleMesh box_mesh(double x0, double y0, double z0, double dx, double dy, double dz) {
    TriangleMesh m;
    for (int i = 0; i < 8; ++i)
        m.vertices.emplace_back(x0 + (i & 1 ? dx : 0), y0 + (i & 2 ? dy : 0),
                                z0 + (i & 4 ? dz : 0));
    // Corner index bits: 1 = +x, 2 = +y, 4 = +z. Each face as two CCW triangles seen from outside.
    const int quads[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4},
                             {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
    for (const auto& q : quads) {
        m.triangles.emplace_back(q[0], q[1], q[2]);
        m.triangles.emplace_back(q[0], q[2], q[3]);
    }
    return m;
}

Shape cylinder(const Eigen::Vector3d& base, const Eigen::Vector3d& axis, double radius,
               double height) {
    const gp_Ax2 ax(gp_Pnt(base.x(), base.y(), base.z()), gp_Dir(axis.x(), axis.y(), axis.z()));
    return from_occt(BRepPrimAPI_MakeCylinder(ax, radius, height).Shape());
}

Shape l_block() {
    return from_occt(fuse(occ_box(0, 0, 0, 20, 20, 60), occ_box(20, 0, 40, 50, 20, 20)));
}

Shape turned_about_z(const Shape& shape, double degrees) {
    gp_Trsf turn;
    turn.SetRotation(gp_Ax1(gp_Pnt(0, 0, 0), gp_Dir(0, 0, 1)), degrees * kPi / 180.0);
    return from_occt(BRepBuilderAPI_Transform(to_occt(shape), turn, Standard_True).Shape());
}

Shape plate_with_hole() {
    const TopoDS_Shape plate = occ_box(0, 0, 0, 60, 40, 10);
    const TopoDS_Shape hole =
        BRepPrimAPI_MakeCylinder(gp_Ax2(gp_Pnt(30, 20, -1), gp_Dir(0, 0, 1)), 8, 12).Shape();
    return from_occt(BRepAlgoAPI_Cut(plate, hole).Shape());
}

Shape gusset_bracket() {
    const TopoDS_Shape web = occ_prism({{20, 8, 60}, {43, 8, 60}, {20, 8, 37}}, {0, 4, 0});
    const TopoDS_Shape l = fuse(occ_box(0, 0, 0, 20, 20, 80), occ_box(20, 0, 60, 50, 20, 20));
    return from_occt(fuse(l, web));
}

Shape gusset_tee(double arm) {
    const TopoDS_Shape webs = fuse(occ_prism({{20, 8, 60}, {43, 8, 60}, {20, 8, 37}}, {0, 4, 0}),
                                   occ_prism({{0, 8, 60}, {-23, 8, 60}, {0, 8, 37}}, {0, 4, 0}));
    const TopoDS_Shape tee =
        fuse(occ_box(0, 0, 0, 20, 20, 80), occ_box(-arm, 0, 60, 20 + 2 * arm, 20, 20));
    return from_occt(fuse(tee, webs));
}

Shape staircase() {
    TopoDS_Shape stairs = occ_box(0, 0, 0, 20, 20, 10);
    for (int i = 1; i < 4; ++i) stairs = fuse(stairs, occ_box(5.0 * i, 0, 10.0 * i, 20, 20, 10));
    return from_occt(stairs);
}

Shape two_posts() {
    const TopoDS_Shape base = occ_box(0, 0, 0, 40, 10, 5);
    const TopoDS_Shape posts = fuse(occ_box(0, 0, 5, 10, 10, 25), occ_box(30, 0, 5, 10, 10, 25));
    return from_occt(fuse(base, posts));
}

Shape arch_with_pendant() {
    const TopoDS_Shape legs = fuse(occ_box(0, 0, 0, 10, 20, 40), occ_box(50, 0, 0, 10, 20, 40));
    const TopoDS_Shape beam = fuse(occ_box(0, 0, 40, 60, 20, 10), occ_box(20, 0, 15, 20, 20, 25));
    return from_occt(fuse(legs, beam));
}

Shape handle_on_plate() {
    const TopoDS_Shape posts = fuse(occ_box(5, 6, 5, 8, 8, 30), occ_box(47, 6, 5, 8, 8, 30));
    return from_occt(fuse(occ_box(0, 0, 0, 60, 20, 5), fuse(posts, occ_box(5, 6, 35, 50, 8, 6))));
}

Shape wall_with_window() {
    return from_occt(
        BRepAlgoAPI_Cut(occ_box(0, 0, 0, 60, 6, 45), occ_box(20, -1, 15, 20, 8, 12)).Shape());
}

Shape portal_on_two_legs() {
    const TopoDS_Shape legs = fuse(occ_box(0, 0, 0, 8, 8, 30), occ_box(42, 0, 0, 8, 8, 30));
    return from_occt(fuse(legs, occ_box(0, 0, 30, 50, 8, 6)));
}

Shape table_on_three_legs() {
    TopoDS_Shape s = fuse(occ_box(0, 0, 0, 4, 4, 31), occ_box(61, 0, 0, 4, 4, 31));
    s = fuse(s, occ_box(30.5, 20, 0, 4, 4, 31));
    return from_occt(fuse(s, occ_box(0, 0, 31, 65, 24, 7)));
}

Shape pipe_tee() {
    auto pipe = [](const gp_Ax2& axis, double r, double h) {
        return BRepPrimAPI_MakeCylinder(axis, r, h).Shape();
    };
    const gp_Ax2 up(gp_Pnt(0, 0, 0), gp_Dir(0, 0, 1)), side(gp_Pnt(0, 0, 35), gp_Dir(0, 1, 0));
    const TopoDS_Shape outer = fuse(pipe(up, 10, 60), pipe(side, 10, 35));
    const TopoDS_Shape bore =
        fuse(pipe(gp_Ax2(gp_Pnt(0, 0, -1), gp_Dir(0, 0, 1)), 8, 62), pipe(side, 8, 36));
    return from_occt(BRepAlgoAPI_Cut(outer, bore).Shape());
}

Shape pipe_bend(double radius, double bore, double rise, double bend_radius, double run,
                double flange) {
    const double z0 = 4.0;
    const auto channel = [&](double r) {
        const gp_Ax2 bend(gp_Pnt(bend_radius, 0, z0 + rise), gp_Dir(0, 1, 0), gp_Dir(-1, 0, 0));
        TopoDS_Shape s = occ_cylinder({0, 0, z0 - 1}, Eigen::Vector3d::UnitZ(), r, rise + 1);
        s = fuse(s, BRepPrimAPI_MakeTorus(bend, bend_radius, r, kPi / 2).Shape());
        return fuse(s, occ_cylinder({bend_radius, 0, z0 + rise + bend_radius},
                                    Eigen::Vector3d::UnitX(), r, run + 1));
    };
    TopoDS_Shape s = fuse(occ_cylinder({0, 0, 0}, Eigen::Vector3d::UnitZ(), radius + flange, z0),
                          channel(radius));
    if (bore > 0.0) s = BRepAlgoAPI_Cut(s, channel(bore)).Shape();
    return from_occt(s);
}

Shape torus(double major_radius, double minor_radius) {
    return from_occt(
        BRepPrimAPI_MakeTorus(gp_Ax2(gp_Pnt(0, 0, 0), gp_Dir(0, 0, 1)), major_radius, minor_radius)
            .Shape());
}

Shape single_face() {
    return from_occt(
        BRepBuilderAPI_MakeFace(gp_Pln(gp_Pnt(0, 0, 0), gp_Dir(0, 0, 1)), 0, 10, 0, 10).Face());
}

Shape two_boxes() {
    BRep_Builder b;
    TopoDS_Compound c;
    b.MakeCompound(c);
    b.Add(c, occ_box(0, 0, 0, 10, 10, 10));
    b.Add(c, occ_box(20, 0, 0, 10, 10, 10));
    return from_occt(c);
}

Shape sphere(double radius) {
    return from_occt(BRepPrimAPI_MakeSphere(gp_Pnt(0, 0, 0), radius).Shape());
}

namespace {

// The box's faces in a new shell, all but the one lying on z = `skip_z` (NaN keeps all six).
TopoDS_Shell shell_of_box(double x0, double y0, double z0, double dx, double dy, double dz,
                          double skip_z) {
    BRep_Builder b;
    TopoDS_Shell shell;
    b.MakeShell(shell);
    const TopoDS_Shape solid = occ_box(x0, y0, z0, dx, dy, dz);
    for (TopExp_Explorer x(solid, TopAbs_FACE); x.More(); x.Next()) {
        Bnd_Box box;
        BRepBndLib::Add(x.Current(), box);
        double a0, b0, c0, a1, b1, c1;
        box.Get(a0, b0, c0, a1, b1, c1);
        if (std::abs(c0 - skip_z) < 1e-3 && std::abs(c1 - skip_z) < 1e-3) continue;
        b.Add(shell, x.Current());
    }
    return shell;
}

}  // namespace

Shape box_shell(double x0, double y0, double z0, double dx, double dy, double dz) {
    return from_occt(shell_of_box(x0, y0, z0, dx, dy, dz, std::nan("")));
}

Shape open_box_shell(double x0, double y0, double z0, double dx, double dy, double dz) {
    return from_occt(shell_of_box(x0, y0, z0, dx, dy, dz, z0 + dz));
}

Layer flat_layer(int component, const Eigen::Vector3d& n,
                 const std::vector<std::vector<Eigen::Vector3d>>& loops, double thickness) {
    Layer l;
    l.component = component;
    l.plane = {loops.front().front(), n};
    l.lower = {loops.front().front() - thickness * n, n};
    const PlaneFrame frame(n);
    for (const auto& loop : loops) {
        Polygon2 outer;
        for (const Eigen::Vector3d& q : loop) outer.points.push_back(frame.to_2d(q));
        if (signed_area(outer) < 0) std::reverse(outer.points.begin(), outer.points.end());
        l.regions.push_back({outer, {}});
    }
    l.min_thickness_mm = l.max_thickness_mm = thickness;
    return l;
}

double nozzle_clearance(const NozzleParams& n, const Eigen::Vector3d& p,
                        const Eigen::Vector3d& axis, const Eigen::Vector3d& q) {
    const double h = axis.dot(q - p), rho = (q - p - h * axis).norm();
    const double s = n.standoff_mm, tip = 0.5 * n.tip_diameter_mm, body = 0.5 * n.body_diameter_mm;
    const double cone_end = s + cone_length(n), top = cone_end + n.body_length_mm;
    const std::vector<Eigen::Vector2d> outline = {
        {0, s}, {tip, s}, {body, cone_end}, {body, top}, {0, top}};
    double d = INFINITY;
    for (std::size_t k = 0; k + 1 < outline.size(); ++k) {
        const Eigen::Vector2d a = outline[k], e = outline[k + 1] - a, x(rho, h);
        const double t = std::clamp((x - a).dot(e) / e.squaredNorm(), 0.0, 1.0);
        d = std::min(d, (a + t * e - x).norm());
    }
    const double radius = h <= cone_end ? tip + (h - s) * (body - tip) / (cone_end - s) : body;
    return h >= s && h <= top && rho <= radius ? -d : d;
}

TriangleMesh data_mesh(const std::string& name, double* deflection) {
    const Model model = read_model(std::string(MAS_TEST_DATA) + "/" + name);
    TessellationParams tp;
    tp.deflection_mm = effective_deflection(model.shape, tp);
    if (deflection) *deflection = tp.deflection_mm;
    return tessellate(model.shape, tp);
}

}  // namespace mas::test
