// Slicing benchmark (issue 5): time of the adaptive multi-axis layers and the paths of every layer
// on parts about 100 mm tall with 0.5 - 2 mm layers (target: layers and paths under 1 s), and the
// quality comparison at the same maximum volumetric difference: layer count of our multi-axis
// adaptive slicing against planar adaptive slicing along Z (the whole part as one component) and
// planar uniform slicing along Z (the thickest uniform layer that is no worse than planar adaptive
// slicing), with the worst unsupported area of each. Run by hand: `build/bench/mas_bench_slice
// [examples/bracket.step]`. Last, slicing with holes deposited solid to drill (fill_holes) against
// slicing them open, on parts with horizontal holes: time, worst unsupported area, holes filled.
// The time table also gives the build sequence's (the layers checked against the nozzle,
// Nozzle.hpp: from its first report to the end of the slicing, in the run that reports) and the
// post-processor's (the G-code of the same layers, Gcode.hpp), each as a ratio to the slicing's;
// then the nozzle leaned where it collides (Nozzle.hpp) against kept coaxial (max_lean_deg 0): the
// build sequence's time, which the leaning adds to; then the G-code with its travel checked against
// the nozzle (Gcode.hpp, Nozzle.hpp's TravelCheck) against written unchecked: routes checked, taken
// round the part, still meeting something, and the post-processor's time.
#include <BRepAlgoAPI_Cut.hxx>
#include <BRepPrimAPI_MakeCone.hxx>
#include <BRepPrimAPI_MakeCylinder.hxx>
#include <BRepPrimAPI_MakeSphere.hxx>
#include <BRepPrimAPI_MakeTorus.hxx>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <exception>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include "bench_util.hpp"
#include "mas/Angles.hpp"
#include "mas/CentroidalAxis.hpp"
#include "mas/Decompose.hpp"
#include "mas/Gcode.hpp"
#include "mas/Holes.hpp"
#include "mas/SlicePart.hpp"

namespace {

using Eigen::Vector3d;
using mas::kPi;
using mas::bench::box;
using mas::bench::from_occt;
using mas::bench::fuse;
using mas::bench::time_ms;

TopoDS_Shape cylinder(const Vector3d& base, const Vector3d& axis, double r, double h) {
    return BRepPrimAPI_MakeCylinder(
               gp_Ax2(gp_Pnt(base.x(), base.y(), base.z()), gp_Dir(axis.x(), axis.y(), axis.z())),
               r, h)
        .Shape();
}

struct Part {
    std::string name;
    mas::Shape shape;
};

// Parts about 100 mm tall: nobody tuned the slicer for them.
std::vector<Part> parts() {
    std::vector<Part> out;
    // A pipe bend: a bar of radius 10 rising 40 mm, bending through a quarter circle of radius
    // 50 towards +X, running 30 mm along +X (100 mm tall).
    {
        TopoDS_Shape s = cylinder({0, 0, 0}, Vector3d::UnitZ(), 10, 40);
        const gp_Ax2 frame(gp_Pnt(50, 0, 40), gp_Dir(0, 1, 0), gp_Dir(-1, 0, 0));
        s = fuse(s, BRepPrimAPI_MakeTorus(frame, 50, 10, kPi / 2).Shape());
        s = fuse(s, cylinder({50, 0, 90}, Vector3d::UnitX(), 10, 30));
        out.push_back({"bend (r 10, R 50)", from_occt(s)});
    }
    // An L-bracket: a 30 x 30 x 100 column with a 60 mm arm at its top.
    out.push_back(
        {"L-block 100 mm", from_occt(fuse(box(0, 0, 0, 30, 30, 100), box(30, 0, 70, 60, 30, 30)))});
    // A lug on a wall: a 100 x 20 x 100 wall with a 40 mm boss sideways near its top.
    out.push_back(
        {"wall with boss", from_occt(fuse(box(0, 0, 0, 100, 20, 100),
                                          cylinder({50, 20, 70}, Vector3d::UnitY(), 12, 40)))});
    // A hub with two blades reaching sideways.
    {
        TopoDS_Shape s = cylinder({0, 0, 0}, Vector3d::UnitZ(), 20, 100);
        s = fuse(s, box(15, -4, 40, 60, 8, 50));
        s = fuse(s, box(-75, -4, 40, 60, 8, 50));
        out.push_back({"hub with two blades", from_occt(s)});
    }
    // A dome (radius 100, 100 mm tall) and a 100 mm frustum.
    out.push_back({"dome r 100",
                   from_occt(BRepPrimAPI_MakeSphere(gp_Pnt(0, 0, 0), 100, 0, kPi / 2).Shape())});
    out.push_back({"frustum r 50-20 h 100", from_occt(BRepPrimAPI_MakeCone(50, 20, 100).Shape())});
    return out;
}

struct Run {
    mas::SlicedPart result;
    double ms = 0.0;
};

// Worst VolDiff over the layers of a slicing, the last of each component left out (a dome's cap
// misses any bound whatever the thickness).
double worst_difference(const mas::SlicedPart& r) {
    double worst = 0.0;
    for (std::size_t i = 0; i + 1 < r.layers.size(); ++i)
        if (r.layers[i + 1].component == r.layers[i].component)
            worst = std::max(worst, r.layers[i].volume_difference);
    return worst;
}

// Uniform slicing along +Z at the same maximum volumetric difference as planar adaptive slicing:
// the thickest of max_layer, 3/4 of it, ... down to min_layer whose worst layer is no worse.
int uniform_count(const mas::ComponentMesh& whole, const mas::CentroidalAxis& axis,
                  const mas::SlicePartParams& params, const mas::SlicedPart& planar) {
    const double target = std::max(params.layers.max_volume_difference, worst_difference(planar));
    mas::SlicePartParams p = params;
    for (double t = params.layers.max_layer_mm;;
         t = std::max(params.layers.min_layer_mm, t - t / 4.0)) {
        // Every layer t thick (no volumetric bound to make it thinner) but the part's last,
        // fitted to what is left.
        p.layers.max_layer_mm = t;
        p.layers.max_volume_difference = 1e9;
        const mas::SlicedPart r = mas::slice_components({whole}, axis, p);
        if (worst_difference(r) <= target + 1e-12 || t <= params.layers.min_layer_mm)
            return r.stats.layer_count;
    }
}

}  // namespace

int run(int argc, char** argv) {
    std::vector<Part> all = parts();
    if (argc > 1) {
        mas::Model m = mas::read_model(argv[1]);
        all.insert(all.begin(), {argv[1], m.shape});
    }
    mas::SlicePartParams params;  // 0.5 - 2 mm layers, VolDiff 0.1, 1 mm bead, 2 contours
    std::printf(
        "# %u hardware threads; layers %.2f - %.2f mm, max volume difference %.2f, bead "
        "%.2f mm, %d contours, raster infill; median of 3 runs\n",
        std::thread::hardware_concurrency(), params.layers.min_layer_mm, params.layers.max_layer_mm,
        params.layers.max_volume_difference, params.paths.bead_width_mm,
        params.paths.contour_count);
    std::printf("\n## Time (ms): axis and decomposition apart; layers+paths is the target\n");
    std::printf("%-24s %6s %5s %7s %9s %9s %9s %8s %9s %8s %8s %9s %8s %9s %8s %8s\n", "part",
                "height", "comps", "layers", "axis", "decompose", "layers", "+paths", "reporting",
                "reports", "sequence", "seq/slice", "switches", "collided", "G-code", "G/slice");
    struct Row {
        std::string name;
        int ours = 0, planar = 0, uniform = 0;
        double ours_unsupported = 0, planar_unsupported = 0;
        int ours_over = 0, planar_over = 0;
    };
    std::vector<Row> rows;
    struct Lean {
        std::string name;
        int coaxial_collided, collided, leaned;
        double coaxial_ms, leaned_ms;
    };
    std::vector<Lean> leans;
    struct Travel {
        std::string name;
        int routes, rerouted, collisions;
        double unchecked_ms, checked_ms;
    };
    std::vector<Travel> travels;
    for (const Part& p : all) {
        mas::TessellationParams tp;
        mas::TriangleMesh mesh = mas::tessellate(p.shape, tp);
        const Eigen::AlignedBox3d bounds = mas::bounding_box(mesh);  // tight, unlike OCCT's
        const double height = bounds.sizes().z();
        mas::CentroidalAxis axis;
        const double axis_ms = time_ms(3, [&] { axis = mas::centroidal_axis(mesh, {}); });
        mas::Decomposition d;
        const double dec_ms = time_ms(3, [&] { d = mas::decompose(p.shape, axis); });
        mas::SlicedPart r;
        // Layers alone (paths of an empty layer list cost nothing): slice with paths, then
        // subtract the path planning measured on the same layers.
        const double total_ms = time_ms(3, [&] { r = mas::slice_part(p.shape, axis, d, params); });
        const double paths_ms = time_ms(3, [&] {
            for (std::size_t i = 0; i < r.layers.size(); ++i)
                mas::plan_toolpaths(r.layers[i], int(i), params.paths);
        });
        // The same with a Progress that counts its reports (what a GUI's callback costs beyond
        // its own work), as a ratio to the run without.
        long reports = 0;
        using Clock = std::chrono::steady_clock;
        Clock::time_point sequence_start;
        bool in_sequence = false;
        const mas::Progress counting([&](double, const std::string& stage) {
            ++reports;
            if (!in_sequence && stage.rfind("checking the nozzle", 0) == 0) {
                in_sequence = true;
                sequence_start = Clock::now();
            }
        });
        // Three runs with it: the whole slicing's time, and the build sequence's (from its first
        // report to the end of the slicing), each the median.
        auto counted = [&](const mas::SlicePartParams& with, mas::SlicedPart& into,
                           double& sequence) {
            std::vector<double> runs;
            const double ms = time_ms(3, [&] {
                in_sequence = false;
                into = mas::slice_part(p.shape, axis, d, with, counting);
                runs.push_back(in_sequence ? std::chrono::duration<double, std::milli>(
                                                 Clock::now() - sequence_start)
                                                 .count()
                                           : 0.0);
            });
            std::sort(runs.begin(), runs.end());
            sequence = runs[runs.size() / 2];
            return ms;
        };
        double sequence_ms = 0.0;
        const double reporting_ms = counted(params, r, sequence_ms);
        // The post-processor on the same layers, default machine.
        std::size_t gcode_bytes = 0;
        const double gcode_ms = time_ms(3, [&] {
            gcode_bytes = mas::write_gcode(mas::gcode_layers(r), mas::MachineParams()).size();
        });
        std::printf(
            "%-24s %6.1f %5zu %7zu %9.1f %9.1f %9.1f %8.1f %8.3fx %8ld %8.1f %8.3fx %8d %9d %8.1f "
            "%8.3fx\n",
            p.name.c_str(), height, d.components.size(), r.layers.size(), axis_ms, dec_ms,
            total_ms - paths_ms, total_ms, reporting_ms / total_ms, reports / 3, sequence_ms,
            sequence_ms / total_ms, r.stats.component_switches, r.stats.colliding_layers, gcode_ms,
            gcode_ms / total_ms);
        if (gcode_bytes == 0) std::printf("  (no G-code written)\n");
        // The same with the travel checked against the slicing's nozzle and plate.
        const mas::TravelNozzle nozzle{params.nozzle, r.plate};
        mas::GcodeStats travel;
        const double checked_ms = time_ms(3, [&] {
            mas::write_gcode(mas::gcode_layers(r), mas::MachineParams(), &travel, {}, &nozzle);
        });
        travels.push_back({p.name, travel.checked_routes, travel.rerouted_travels,
                           int(travel.travel_collisions.size()), gcode_ms, checked_ms});
        // The nozzle kept coaxial (the paper's): the build sequence's time and collisions.
        mas::SlicePartParams coaxial_params = params;
        coaxial_params.nozzle.max_lean_deg = 0.0;
        mas::SlicedPart coaxial;
        double coaxial_ms = 0.0;
        counted(coaxial_params, coaxial, coaxial_ms);
        leans.push_back({p.name, coaxial.stats.colliding_layers, r.stats.colliding_layers,
                         r.stats.leaned_layers, coaxial_ms, sequence_ms});

        // Planar adaptive along Z: the whole part as one component, a straight +Z guide.
        mas::ComponentMesh whole;
        whole.mesh = mesh;
        whole.base = mas::build_plate(mesh);
        whole.branch = -1;
        mas::SlicePartParams planar_params = params;  // plain adaptive slicing: Eq. 9 alone
        planar_params.layers.require_support = false;
        const mas::SlicedPart planar = mas::slice_components({whole}, axis, planar_params);
        Row row;
        row.name = p.name;
        row.ours = r.stats.layer_count;
        row.planar = planar.stats.layer_count;
        row.uniform = uniform_count(whole, axis, planar_params, planar);
        row.ours_unsupported = r.stats.worst_unsupported_area_mm2;
        row.planar_unsupported = planar.stats.worst_unsupported_area_mm2;
        row.ours_over = r.stats.layers_over_volume_difference;
        row.planar_over = planar.stats.layers_over_volume_difference;
        rows.push_back(row);
    }
    std::printf(
        "\n## The nozzle leaned where it collides (up to %.0f degrees) against kept coaxial: "
        "colliding layers, leaned layers, the build sequence's time (ms, median of 3, as above)\n",
        params.nozzle.max_lean_deg);
    std::printf("%-24s %9s %9s %7s %10s %10s %8s\n", "part", "coax coll", "lean coll", "leaned",
                "coaxial", "leaned", "ratio");
    for (const Lean& l : leans)
        std::printf("%-24s %9d %9d %7d %10.1f %10.1f %7.3fx\n", l.name.c_str(), l.coaxial_collided,
                    l.collided, l.leaned, l.coaxial_ms, l.leaned_ms, l.leaned_ms / l.coaxial_ms);
    std::printf(
        "\n## The G-code's travel checked against the nozzle against unchecked: routes checked, "
        "taken round the part, still meeting something; the post-processor's time (ms, median of "
        "3)\n");
    std::printf("%-24s %7s %9s %9s %10s %10s %8s\n", "part", "routes", "rerouted", "meeting",
                "unchecked", "checked", "ratio");
    for (const Travel& t : travels)
        std::printf("%-24s %7d %9d %9d %10.1f %10.1f %7.2fx\n", t.name.c_str(), t.routes,
                    t.rerouted, t.collisions, t.unchecked_ms, t.checked_ms,
                    t.checked_ms / t.unchecked_ms);
    std::printf("\n## Layer count at the same maximum volumetric difference (%.2f)\n",
                params.layers.max_volume_difference);
    std::printf("%-24s %8s %8s %8s %10s %10s %14s %14s\n", "part", "ours", "planarZ", "uniform",
                "ours/plZ", "ours/unif", "unsupp ours", "unsupp planZ");
    for (const Row& r : rows)
        std::printf("%-24s %8d %8d %8d %10.2f %10.2f %11.2f mm2 %11.2f mm2\n", r.name.c_str(),
                    r.ours, r.planar, r.uniform, double(r.ours) / r.planar,
                    double(r.ours) / r.uniform, r.ours_unsupported, r.planar_unsupported);
    std::printf(
        "\n(ours: sub-components along their own axes; planarZ: adaptive, one component "
        "along +Z; uniform: +Z, the thickest uniform layer no worse than planarZ. Layers of a "
        "multi-axis build are not all comparable in area: the count is a proxy for build "
        "time, as in Yang et al. 2003.)\n");

    // Holes to drill: parts whose only overhangs are the ceilings of horizontal holes.
    std::vector<Part> holed;
    if (argc > 1) holed.push_back(all.front());
    {
        // A clevis: a 60 x 40 x 6 plate with two 20 x 8 x 40 ears, a 10 mm pin hole through each.
        TopoDS_Shape s = box(0, 0, 0, 60, 40, 6);
        for (const double y : {5.0, 27.0})
            s = fuse(s, BRepAlgoAPI_Cut(box(20, y, 6, 20, 8, 40),
                                        cylinder({30, y - 1, 32}, Vector3d::UnitY(), 5, 10))
                            .Shape());
        holed.push_back({"clevis, 2 pin holes", from_occt(s)});
    }
    for (const int n : {3, 6}) {
        // A 100 x 20 x 100 wall with n x n horizontal holes 6 mm across through it along Y.
        TopoDS_Shape s = box(0, 0, 0, 100, 20, 100);
        for (int i = 0; i < n; ++i)
            for (int k = 0; k < n; ++k)
                s = BRepAlgoAPI_Cut(s, cylinder({100.0 * (i + 0.5) / n, -1, 100.0 * (k + 0.5) / n},
                                                Vector3d::UnitY(), 3, 22))
                        .Shape();
        holed.push_back({"wall, " + std::to_string(n * n) + " holes", from_occt(s)});
    }
    std::printf(
        "\n## Holes to drill: slicing with fill_holes = 12 mm against with the holes open\n");
    std::printf("%-24s %6s %10s %10s %7s %10s %14s %14s\n", "part", "holes", "open ms", "filled ms",
                "ratio", "fill ms", "unsupp open", "unsupp filled");
    for (const Part& p : holed) {
        mas::TessellationParams tp;
        const mas::CentroidalAxis axis = mas::centroidal_axis(mas::tessellate(p.shape, tp), {});
        const mas::Decomposition d = mas::decompose(p.shape, axis);
        mas::SlicePartParams fill = params;
        fill.fill_holes_up_to_mm = 12.0;
        mas::SlicedPart open, filled;
        const double open_ms =
            time_ms(3, [&] { open = mas::slice_part(p.shape, axis, d, params); });
        const double filled_ms =
            time_ms(3, [&] { filled = mas::slice_part(p.shape, axis, d, fill); });
        // The filling alone, component by component.
        const double fill_ms = time_ms(3, [&] {
            for (const mas::Component& c : d.components)
                mas::fill_holes(c.solid, c.build_direction, 12.0, params.layers.overhang_angle_deg,
                                p.shape);
        });
        std::printf("%-24s %6d %10.1f %10.1f %6.2fx %10.1f %10.2f mm2 %10.2f mm2\n", p.name.c_str(),
                    filled.stats.filled_holes, open_ms, filled_ms, filled_ms / open_ms, fill_ms,
                    open.stats.worst_unsupported_area_mm2, filled.stats.worst_unsupported_area_mm2);
    }
    return 0;
}

// A part file it cannot read (or any error) is named, not an abort.
int main(int argc, char** argv) {
    try {
        return run(argc, argv);
    } catch (const std::exception& e) {
        std::fprintf(stderr, "mas_bench_slice: %s\n", e.what());
        return 1;
    }
}
