// What the benchmark programs share: wall-clock medians and OCCT shapes handed to the engine.
#pragma once

#include <BRepAlgoAPI_Fuse.hxx>
#include <BRepPrimAPI_MakeBox.hxx>
#include <BRepTools.hxx>
#include <algorithm>
#include <chrono>
#include <functional>
#include <sstream>
#include <vector>

#include "mas/Shape.hpp"

namespace mas::bench {

// The middle value (the upper one of the two middle values for an even count).
inline double median(std::vector<double> t) {
    std::sort(t.begin(), t.end());
    return t[t.size() / 2];
}

// Median wall time of `runs` calls, in milliseconds.
inline double time_ms(int runs, const std::function<void()>& f) {
    std::vector<double> t;
    for (int i = 0; i < runs; ++i) {
        const auto start = std::chrono::steady_clock::now();
        f();
        t.push_back(
            std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start)
                .count());
    }
    return median(std::move(t));
}

inline Shape from_occt(const TopoDS_Shape& s) {
    std::ostringstream out;
    BRepTools::Write(s, out);
    return Shape::from_brep_string(out.str());
}

inline TopoDS_Shape box(double x0, double y0, double z0, double dx, double dy, double dz) {
    return BRepPrimAPI_MakeBox(gp_Pnt(x0, y0, z0), dx, dy, dz).Shape();
}

inline TopoDS_Shape fuse(const TopoDS_Shape& a, const TopoDS_Shape& b) {
    BRepAlgoAPI_Fuse f(a, b);
    f.SimplifyResult();
    return f.Shape();
}

}  // namespace mas::bench
