// Decomposition benchmark (issue 4): time of mas::decompose on plates carrying a grid of posts
// (each post a split branch cut at the plate's top face) and sideways lugs, from a few faces to
// about 200. The axis is computed once beforehand and timed apart. Target: < 1 s at 200 faces.
// Run by hand: `build/bench/mas_bench_decompose`.
#include <BRepAlgoAPI_Fuse.hxx>
#include <BRepPrimAPI_MakeBox.hxx>
#include <BRepTools.hxx>
#include <TopTools_ListOfShape.hxx>
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <functional>
#include <sstream>
#include <vector>

#include "mas/CentroidalAxis.hpp"
#include "mas/Decompose.hpp"
#include "mas/Shape.hpp"

namespace {

using Clock = std::chrono::steady_clock;

double time_ms(int runs, const std::function<void()>& f) {
    std::vector<double> t;
    for (int i = 0; i < runs; ++i) {
        const auto start = Clock::now();
        f();
        t.push_back(std::chrono::duration<double, std::milli>(Clock::now() - start).count());
    }
    std::sort(t.begin(), t.end());
    return t[t.size() / 2];
}

mas::Shape from_occt(const TopoDS_Shape& s) {
    std::ostringstream out;
    BRepTools::Write(s, out);
    return mas::Shape::from_brep_string(out.str());
}

TopoDS_Shape box(double x0, double y0, double z0, double dx, double dy, double dz) {
    return BRepPrimAPI_MakeBox(gp_Pnt(x0, y0, z0), dx, dy, dz).Shape();
}

// A 10 n x 10 n x 5 plate with n x n posts 4 x 4 x 10 on its top, one per 10 mm cell, fused in
// one Boolean: 6 + 5 n^2 faces.
mas::Shape posts_on_plate(int n) {
    TopTools_ListOfShape args, tools;
    args.Append(box(0, 0, 0, 10.0 * n, 10.0 * n, 5));
    for (int i = 0; i < n; ++i)
        for (int j = 0; j < n; ++j) tools.Append(box(10.0 * i + 3, 10.0 * j + 3, 5, 4, 4, 10));
    BRepAlgoAPI_Fuse fuse;
    fuse.SetArguments(args);
    fuse.SetTools(tools);
    fuse.Build();
    fuse.SimplifyResult();
    return from_occt(fuse.Shape());
}

}  // namespace

int main() {
    std::printf("%-16s %6s %6s | %10s | %12s %10s\n", "part", "faces", "comps", "axis ms",
                "decompose ms", "ms/comp");
    for (int n : {1, 2, 3, 4, 5, 6}) {
        const mas::Shape part = posts_on_plate(n);
        mas::TessellationParams tp;
        tp.deflection_mm = 0.02;
        const auto mesh = mas::tessellate(part, tp);
        mas::AxisParams ap;
        ap.step_mm = 1.0;
        mas::CentroidalAxis axis;
        const double axis_ms = time_ms(3, [&] { axis = mas::centroidal_axis(mesh, ap); });
        mas::Decomposition d;
        const double ms = time_ms(3, [&] { d = mas::decompose(part, axis); });
        char name[32];
        std::snprintf(name, sizeof name, "%dx%d posts", n, n);
        std::printf("%-16s %6d %6zu | %10.1f | %12.1f %10.2f\n", name, part.info().faces,
                    d.components.size(), axis_ms, ms, ms / double(d.components.size()));
    }
    return 0;
}
