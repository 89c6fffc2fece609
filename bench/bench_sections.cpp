// Cross-section kernel benchmark (issue 2): the mesh kernel against OCCT's exact section on the
// same solid, and against scanning every facet for every plane, all in one run so that the
// ratios hold on a noisy shared machine. Run by hand: `build/bench/mas_bench [DATA_DIR]`, where
// DATA_DIR holds CGAL's OFF meshes (tools/fetch_bench_data.sh puts them in build/bench-data).
#include <tbb/info.h>

#include <BRepAlgoAPI_Cut.hxx>
#include <BRepAlgoAPI_Fuse.hxx>
#include <BRepAlgoAPI_Section.hxx>
#include <BRepBuilderAPI_MakeFace.hxx>
#include <BRepBuilderAPI_MakePolygon.hxx>
#include <BRepMesh_IncrementalMesh.hxx>
#include <BRepPrimAPI_MakeBox.hxx>
#include <BRepPrimAPI_MakeCylinder.hxx>
#include <BRepPrimAPI_MakeTorus.hxx>
#include <BRepTools.hxx>
#include <BRep_Builder.hxx>
#include <BRep_Tool.hxx>
#include <Poly_Triangulation.hxx>
#include <TopExp_Explorer.hxx>
#include <TopoDS.hxx>
#include <TopoDS_Compound.hxx>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <functional>
#include <gp_Pln.hxx>
#include <sstream>
#include <string>
#include <vector>

#include "bench_util.hpp"
#include "mas/Angles.hpp"
#include "mas/Section.hpp"
#include "mas/Shape.hpp"
#include "mas/Triangulate.hpp"

using mas::kPi;

namespace {

using mas::bench::from_occt;
using mas::bench::time_ms;

// A closed torus mesh with nu x nv quads (2 nu nv triangles), axis along Z.
mas::TriangleMesh torus_mesh(double R, double r, int nu, int nv) {
    mas::TriangleMesh m;
    m.vertices.reserve(std::size_t(nu) * nv);
    for (int i = 0; i < nu; ++i)
        for (int j = 0; j < nv; ++j) {
            const double u = 2 * kPi * i / nu, v = 2 * kPi * j / nv;
            m.vertices.emplace_back((R + r * std::cos(v)) * std::cos(u),
                                    (R + r * std::cos(v)) * std::sin(u), r * std::sin(v));
        }
    auto id = [&](int i, int j) { return ((i + nu) % nu) * nv + (j + nv) % nv; };
    for (int i = 0; i < nu; ++i)
        for (int j = 0; j < nv; ++j) {
            m.triangles.emplace_back(id(i, j), id(i + 1, j), id(i + 1, j + 1));
            m.triangles.emplace_back(id(i, j), id(i + 1, j + 1), id(i, j + 1));
        }
    return m;
}

std::vector<mas::Plane> planes_across(const mas::TriangleMesh& m, const Eigen::Vector3d& n,
                                      int count) {
    // parallel_planes' mid-slab rule with the step that gives `count` planes.
    double lo = 1e300, hi = -1e300;
    for (const auto& v : m.vertices) {
        lo = std::min(lo, n.dot(v));
        hi = std::max(hi, n.dot(v));
    }
    return mas::parallel_planes(m, n, (hi - lo) / count);
}

// Every facet against every plane: the scan CuraEngine does, for the ratio only.
double brute_force_area(const mas::TriangleMesh& m, const std::vector<mas::Plane>& planes) {
    double sum = 0.0;
    for (const auto& p : planes) {
        const mas::PlaneFrame f(p.normal);
        const double d = p.normal.dot(p.origin);
        for (const auto& t : m.triangles) {
            const double h[3] = {p.normal.dot(m.vertices[t[0]]) - d,
                                 p.normal.dot(m.vertices[t[1]]) - d,
                                 p.normal.dot(m.vertices[t[2]]) - d};
            Eigen::Vector2d q[2];
            int k = 0;
            for (int e = 0; e < 3 && k < 2; ++e) {
                const double a = h[e], b = h[(e + 1) % 3];
                if ((a < 0) == (b < 0)) continue;
                const Eigen::Vector3d x =
                    m.vertices[t[e]] +
                    (a / (a - b)) * (m.vertices[t[(e + 1) % 3]] - m.vertices[t[e]]);
                q[k++] = f.to_2d(x);
            }
            if (k == 2) sum += q[0].x() * q[1].y() - q[1].x() * q[0].y();
        }
    }
    return sum;
}

std::size_t segments(const std::vector<mas::Section>& s) {
    std::size_t n = 0;
    for (const auto& x : s)
        for (const auto& r : x.regions) {
            n += r.shape.outer.points.size();
            for (const auto& h : r.shape.holes) n += h.points.size();
        }
    return n;
}

void report_mesh(const std::string& name, const mas::TriangleMesh& mesh, int nplanes, int runs,
                 bool brute) {
    const auto planes = planes_across(mesh, {0, 0, 1}, nplanes);
    mas::SliceParams totals;
    totals.build_regions = false;
    std::vector<mas::Section> out;
    const double t_regions = time_ms(runs, [&] { out = mas::slice_mesh(mesh, planes); });
    const double t_totals = time_ms(runs, [&] { mas::slice_mesh(mesh, planes, totals); });
    const double tp = double(mesh.triangles.size()) * double(planes.size());
    std::printf(
        "%-22s %9zu tris %5zu planes | regions %8.2f ms (%9.0f sections/s, %.4f ns/tri-plane, "
        "%zu loop points) | totals only %8.2f ms",
        name.c_str(), mesh.triangles.size(), planes.size(), t_regions,
        1e3 * planes.size() / t_regions, 1e6 * t_regions / tp, segments(out), t_totals);
    if (brute) {
        const double t_brute = time_ms(1, [&] { brute_force_area(mesh, planes); });
        std::printf(" | every facet x every plane %9.1f ms (x%.0f)", t_brute, t_brute / t_totals);
    }
    std::printf("\n");
}

// OCCT's exact section of a polyhedral solid: each mesh triangle a planar face. Only a few planes
// (it is slow); reported per plane.
double exact_ms_per_plane_polyhedral(const mas::TriangleMesh& mesh, int nplanes) {
    BRep_Builder b;
    TopoDS_Compound c;
    b.MakeCompound(c);
    for (const auto& t : mesh.triangles) {
        const auto& p0 = mesh.vertices[t[0]];
        const auto& p1 = mesh.vertices[t[1]];
        const auto& p2 = mesh.vertices[t[2]];
        BRepBuilderAPI_MakePolygon poly(gp_Pnt(p0.x(), p0.y(), p0.z()),
                                        gp_Pnt(p1.x(), p1.y(), p1.z()),
                                        gp_Pnt(p2.x(), p2.y(), p2.z()), true);
        if (!poly.IsDone()) continue;
        BRepBuilderAPI_MakeFace face(poly.Wire(), true);
        if (face.IsDone()) b.Add(c, face.Face());
    }
    const auto planes = planes_across(mesh, {0, 0, 1}, nplanes);
    const double t = time_ms(1, [&] {
        for (const auto& p : planes) {
            BRepAlgoAPI_Section s(c,
                                  gp_Pln(gp_Pnt(p.origin.x(), p.origin.y(), p.origin.z()),
                                         gp_Dir(p.normal.x(), p.normal.y(), p.normal.z())),
                                  Standard_False);
            s.Approximation(Standard_False);
            s.Build();
        }
    });
    return t / double(planes.size());
}

// A bracket: base plate with two holes, an upright with a hole, a round boss (16 faces); with
// `extra` it also gets a slot, two more holes and a second boss (about 30 faces).
TopoDS_Shape bracket(bool extra) {
    TopoDS_Shape s = BRepPrimAPI_MakeBox(gp_Pnt(0, 0, 0), 80, 40, 10).Shape();
    s = BRepAlgoAPI_Fuse(s, BRepPrimAPI_MakeBox(gp_Pnt(0, 0, 10), 12, 40, 50).Shape()).Shape();
    for (double x : {35.0, 65.0})
        s = BRepAlgoAPI_Cut(
                s,
                BRepPrimAPI_MakeCylinder(gp_Ax2(gp_Pnt(x, 20, -1), gp_Dir(0, 0, 1)), 5, 12).Shape())
                .Shape();
    s = BRepAlgoAPI_Cut(
            s, BRepPrimAPI_MakeCylinder(gp_Ax2(gp_Pnt(-1, 20, 40), gp_Dir(1, 0, 0)), 6, 14).Shape())
            .Shape();
    s = BRepAlgoAPI_Fuse(
            s, BRepPrimAPI_MakeCylinder(gp_Ax2(gp_Pnt(50, 20, 10), gp_Dir(0, 0, 1)), 8, 15).Shape())
            .Shape();
    if (!extra) return s;
    s = BRepAlgoAPI_Cut(s, BRepPrimAPI_MakeBox(gp_Pnt(20, 5, -1), 8, 6, 12).Shape()).Shape();
    for (double y : {8.0, 32.0})
        s = BRepAlgoAPI_Cut(
                s,
                BRepPrimAPI_MakeCylinder(gp_Ax2(gp_Pnt(72, y, -1), gp_Dir(0, 0, 1)), 3, 12).Shape())
                .Shape();
    s = BRepAlgoAPI_Fuse(
            s, BRepPrimAPI_MakeCylinder(gp_Ax2(gp_Pnt(30, 30, 10), gp_Dir(0, 0, 1)), 5, 20).Shape())
            .Shape();
    s = BRepAlgoAPI_Fuse(s, BRepPrimAPI_MakeBox(gp_Pnt(66, 0, 10), 14, 4, 12).Shape()).Shape();
    return s;
}

void report_exact_vs_mesh(const std::string& name, const mas::Shape& solid, int nplanes, int runs) {
    const auto info = solid.info();
    const mas::TriangleMesh probe = mas::tessellate(solid);
    const auto planes = planes_across(probe, {0, 0, 1}, nplanes);
    const double t_mesh = time_ms(runs, [&] {
        const auto m = mas::tessellate(solid);  // tessellation included
        mas::slice_mesh(m, planes);
    });
    const double t_tess = time_ms(runs, [&] { mas::tessellate(solid); });
    const double t_exact = time_ms(1, [&] { mas::exact_sections(solid, planes); });
    std::printf(
        "%-22s %3d faces %4zu planes | mesh path %7.2f ms (tessellation %6.2f ms, %zu tris,"
        " deflection %.3f mm) | exact %8.1f ms (%.2f ms/plane) | exact/mesh x%.0f\n",
        name.c_str(), info.faces, planes.size(), t_mesh, t_tess, probe.triangles.size(),
        mas::effective_deflection(solid, {}), t_exact, t_exact / planes.size(), t_exact / t_mesh);
}

// A wobbly circle of n points (radius r to 0.8 r when `wobble`) round c, counter-clockwise.
mas::Polygon2 round_loop(const Eigen::Vector2d& c, double r, int n, bool wobble) {
    mas::Polygon2 p;
    for (int i = 0; i < n; ++i) {
        const double a = 2.0 * mas::kPi * i / n;
        const double k =
            wobble ? 0.8 + 0.2 * (0.5 + 0.5 * std::sin(37.0 * a) * std::cos(11.0 * a)) : 1.0;
        p.points.push_back(c + k * r * Eigen::Vector2d(std::cos(a), std::sin(a)));
    }
    return p;
}

// The triangles of a region as the build preview draws a layer: the engine's ear clipping against
// OCCT making the face on its plane and meshing it (BRepMesh, what drew a layer before).
void report_triangles(const char* name, const mas::Region2& region) {
    std::size_t ours = 0, theirs = 0;
    const double t_ours = time_ms(7, [&] { ours = mas::triangulate(region).size(); });
    const auto wire = [](const mas::Polygon2& p) {
        BRepBuilderAPI_MakePolygon poly;
        for (const auto& q : p.points) poly.Add(gp_Pnt(q.x(), q.y(), 0.0));
        poly.Close();
        return poly.Wire();
    };
    const double t_occt = time_ms(7, [&] {
        BRepBuilderAPI_MakeFace make(gp_Pln(gp::Origin(), gp::DZ()), wire(region.outer));
        for (const auto& h : region.holes) {
            mas::Polygon2 cw = h;  // a hole's wire turns the other way
            std::reverse(cw.points.begin(), cw.points.end());
            make.Add(wire(cw));
        }
        const TopoDS_Face face = make.Face();
        BRepMesh_IncrementalMesh mesh(face, 0.1);
        TopLoc_Location loc;
        const Handle(Poly_Triangulation) t = BRep_Tool::Triangulation(face, loc);
        theirs = t.IsNull() ? 0 : std::size_t(t->NbTriangles());
    });
    std::printf(
        "%-28s ours %8.3f ms (%5zu triangles) | OCCT face + BRepMesh %8.3f ms (%5zu): x%.0f\n",
        name, t_ours, ours, t_occt, theirs, t_occt / t_ours);
}

}  // namespace

int main(int argc, char** argv) {
    const std::string data = argc > 1 ? argv[1] : "build/bench-data";
    std::printf("mas_bench: %d hardware threads used by TBB; medians of repeated runs\n\n",
                tbb::info::default_concurrency());

    std::printf("== mesh kernel: 1000 planes along Z (and every facet x every plane) ==\n");
    const auto torus = torus_mesh(40.0, 12.0, 1000, 500);
    report_mesh("torus 1M (synthetic)", torus, 1000, 7, true);
    for (const char* name :
         {"bunny00", "fandisk_large", "armadillo", "refined_elephant", "turbine"}) {
        try {
            auto mesh = mas::read_off(data + "/" + name + ".off");
            mas::require_closed_mesh(mesh, name);
            report_mesh(name, mesh, 1000, 7, false);
        } catch (const std::exception& e) {
            std::printf("%-22s skipped: %s\n", name, e.what());
        }
    }

    std::printf("\n== mesh path (tessellation included) vs OCCT exact section, same solid ==\n");
    report_exact_vs_mesh("bracket", from_occt(bracket(false)), 100, 5);
    report_exact_vs_mesh("bracket+ (~30 faces)", from_occt(bracket(true)), 100, 5);
    report_exact_vs_mesh("torus R40 r12", from_occt(BRepPrimAPI_MakeTorus(40, 12).Shape()), 100, 5);

    std::printf("\n== OCCT exact section of a CGAL mesh as polyhedral BREP (2 planes) ==\n");
    for (const char* name : {"fandisk_large"}) {
        try {
            auto mesh = mas::read_off(data + "/" + name + ".off");
            mas::require_closed_mesh(mesh, name);
            const auto planes = planes_across(mesh, {0, 0, 1}, 1000);
            const double t_mesh = time_ms(5, [&] { mas::slice_mesh(mesh, planes); });
            const double exact = exact_ms_per_plane_polyhedral(mesh, 2);
            std::printf("%-22s exact %.1f ms/plane vs mesh %.4f ms/plane: x%.0f\n", name, exact,
                        t_mesh / planes.size(), exact / (t_mesh / planes.size()));
        } catch (const std::exception& e) {
            std::printf("%-22s skipped: %s\n", name, e.what());
        }
    }

    std::printf("\n== a layer's triangles for drawing: ear clipping vs OCCT's face and mesh ==\n");
    for (const int n : {50, 1000, 3000}) {
        const std::string name = "circle of " + std::to_string(n);
        report_triangles(name.c_str(), {round_loop({0, 0}, 50, n, false), {}});
    }
    report_triangles("wobbly circle of 3000", {round_loop({0, 0}, 50, 3000, true), {}});
    report_triangles("ring of 3000 round 1500",
                     {round_loop({0, 0}, 50, 3000, false), {round_loop({5, 0}, 20, 1500, false)}});
    mas::Region2 plate{round_loop({0, 0}, 50, 400, false), {}};
    for (int i = -2; i <= 2; ++i)
        for (int j = -2; j <= 2; ++j)
            plate.holes.push_back(round_loop({12.0 * i, 12.0 * j}, 4, 40, false));
    report_triangles("disc of 400, 25 holes of 40", plate);
    return 0;
}
