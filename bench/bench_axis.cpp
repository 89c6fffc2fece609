// Centroidal axis benchmark (issue 3): axis time on the test parts (tessellation included) and on
// CGAL's closed meshes, side by side in one run with CGAL's mean-curvature-flow skeleton, the
// medial-axis-class skeleton the paper's centroidal axis is meant to beat. Run by hand:
// `build/bench/mas_bench_axis build/bench-data` (tools/setup.sh bench does everything). Times are
// medians: of 5 runs for the axis, of 3 for CGAL.
#include <BRepAlgoAPI_Fuse.hxx>
#include <BRepPrimAPI_MakeBox.hxx>
#include <BRepPrimAPI_MakeCylinder.hxx>
#include <BRepTools.hxx>
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <functional>
#include <sstream>
#include <string>
#include <vector>

#include "bench_util.hpp"
#include "mas/CentroidalAxis.hpp"
#include "mas/Shape.hpp"

#ifdef MAS_HAVE_CGAL
// In its own file: CGAL and OCCT headers cannot meet (OCCT's Handle macro).
double cgal_skeleton_ms(const mas::TriangleMesh& mesh, std::size_t& skeleton_vertices);
#endif

namespace {

using mas::bench::box;
using mas::bench::from_occt;
using mas::bench::fuse;
using mas::bench::time_ms;

void report(const std::string& name, const mas::TriangleMesh& mesh, double tessellation_ms,
            bool with_cgal) {
    mas::CentroidalAxis axis;
    const double ms = time_ms(5, [&] { axis = mas::centroidal_axis(mesh); });
    int breaks = 0;
    for (const auto& l : axis.links) breaks += l.is_break;
    std::printf(
        "%-18s %7zu tris | axis %7.2f ms (+ tessellation %6.2f ms) step %.3f mm: %5zu nodes, %4zu "
        "branches, %3d breaks, %5zu sections",
        name.c_str(), mesh.triangles.size(), ms, tessellation_ms, axis.params.step_mm,
        axis.nodes.size(), axis.branches.size(), breaks, axis.sections_cut);
#ifdef MAS_HAVE_CGAL
    if (with_cgal) {
        // Median of three runs, as ours is of five: a single CGAL run on a shared 2-core machine
        // varied from 1.6 to 2.3 s.
        std::size_t sv = 0;
        std::vector<double> runs;
        for (int i = 0; i < 3; ++i) runs.push_back(cgal_skeleton_ms(mesh, sv));
        const double cgal = mas::bench::median(std::move(runs));
        std::printf(" | CGAL skeleton %8.1f ms (%zu vertices): x%.0f", cgal, sv,
                    cgal / (ms + tessellation_ms));
    }
#else
    (void)with_cgal;
#endif
    std::printf("\n");
}

}  // namespace

int main(int argc, char** argv) {
    const std::string data = argc > 1 ? argv[1] : "build/bench-data";
#ifndef MAS_HAVE_CGAL
    std::printf("(built without CGAL: install libcgal-dev and reconfigure for the comparison)\n");
#endif
    std::printf("== test parts: axis including tessellation (target < 50 ms each) ==\n");
    const std::vector<std::pair<std::string, TopoDS_Shape>> parts = {
        {"box", box(0, 0, 0, 10, 20, 30)},
        {"L-block", fuse(box(0, 0, 0, 20, 20, 60), box(20, 0, 40, 50, 20, 20))},
        {"T-block", fuse(box(0, 0, 0, 20, 20, 60), box(-30, 0, 40, 80, 20, 20))},
        {"cylinder on block",
         fuse(box(0, 0, 0, 40, 20, 10),
              BRepPrimAPI_MakeCylinder(gp_Ax2(gp_Pnt(-30, 10, 16), gp_Dir(1, 0, 0)), 8, 100)
                  .Shape())},
        {"two posts",
         fuse(box(0, 0, 0, 40, 10, 5), fuse(box(0, 0, 5, 10, 10, 25), box(30, 0, 5, 10, 10, 25)))},
    };
    for (const auto& [name, occ] : parts) {
        const mas::Shape shape = from_occt(occ);
        mas::TriangleMesh mesh;
        const double tess = time_ms(5, [&] { mesh = mas::tessellate(shape); });
        report(name, mesh, tess, true);
    }
    // A step set far below the derived one: the march's planes cross thousands of slabs of the
    // marches before (the swept bands, CentroidalAxis.cpp's strips_to_regions), which once grew
    // as the square of the planes or worse (a crank at 0.001 mm ran past 15 minutes).
    std::printf("\n== fine steps set by hand: axis without tessellation ==\n");
    for (const auto& [name, occ] : {parts[1], parts[3]}) {
        const mas::TriangleMesh mesh = mas::tessellate(from_occt(occ));
        for (const double step : {0.1, 0.02}) {
            mas::AxisParams p;
            p.step_mm = step;
            mas::CentroidalAxis axis;
            const double ms = time_ms(3, [&] { axis = mas::centroidal_axis(mesh, p); });
            std::printf("%-18s step %5.3f mm: axis %9.2f ms, %6zu nodes, %4zu branches\n",
                        name.c_str(), step, ms, axis.nodes.size(), axis.branches.size());
        }
    }
    std::printf(
        "\n== CGAL meshes: centroidal axis vs CGAL mean-curvature skeleton (target x100) ==\n");
    for (const char* name : {"bunny00", "fandisk_large", "armadillo"}) {
        try {
            // As the command line and the scripting API take a mesh: checked, then in canonical
            // order (its vertices sorted by coordinates, its facets by vertex), which also cuts
            // its sections 7 to 12 % faster than in the file's order (neighbours lie together).
            auto mesh = mas::read_off(data + "/" + name + ".off");
            mas::require_closed_mesh(mesh, name);
            mas::canonical_order(mesh);
            report(name, mesh, 0.0, true);
        } catch (const std::exception& e) {
            std::printf("%-18s skipped: %s\n", name, e.what());
        }
    }
    return 0;
}
