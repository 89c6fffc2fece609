// Private to the OCCT side of the engine: the TopoDS_Shape behind mas::Shape, and the helpers the
// files in App/src/occ share (wrapping a TopoDS_Shape, turning Standard_Failure into mas::Error).
#pragma once

#include <Eigen/Geometry>
#include <Standard_ErrorHandler.hxx>
#include <Standard_Failure.hxx>
#include <TopoDS_Shape.hxx>
#include <csignal>
#include <istream>
#include <string>
#include <vector>

// OCCT turns a fatal signal into a long jump to the nearest OCC_CATCH_SIGNALS only in code built
// with this (Debian's OCCT is): the engine's OCCT files are (CMakeLists.txt).
#if !defined(OCC_CONVERT_SIGNALS)
#error "App/src/occ is compiled with OCC_CONVERT_SIGNALS"
#endif

#include "mas/Error.hpp"
#include "mas/Shape.hpp"

namespace mas {

struct Shape::Impl {
    TopoDS_Shape shape;
};

namespace occ {

// A Shape owning `shape`. The TopoDS_Shape is never modified afterwards: code that needs to change
// it (meshing attaches triangulations to faces) works on a BRepBuilderAPI_Copy.
Shape wrap(const TopoDS_Shape& shape);

inline const TopoDS_Shape& occt(const Shape& shape) { return shape.impl().shape; }

// The tight bounds of a shape's geometry (BRepBndLib::Add would widen them by the tolerances);
// an empty box for a shape with no geometry.
Eigen::AlignedBox3d tight_bounds(const TopoDS_Shape& shape);

// The volume of a shape's solids, mm^3 (BRepGProp).
double volume_of(const TopoDS_Shape& shape);

// The solids of a shape, in the order TopExp_Explorer meets them.
std::vector<TopoDS_Shape> solids_of(const TopoDS_Shape& shape);

// The same integrated adaptively to within `relative` of it (slower). OCCT's default quadrature is
// off by up to 4e-3 on pieces of a torus.
double precise_volume_of(const TopoDS_Shape& shape, double relative);

// The largest tolerance of `shape`'s vertices and edges, mm.
double max_tolerance(const TopoDS_Shape& shape);

// How far removing seams may widen a tolerance (unless the shape's own was over a tenth of it),
// mm. Merging the two halves of the circle a plane cuts round a sphere (across its seam) into one
// edge, OCCT 7.6's unifier left the one vertex it kept as wide as the circle (27 mm on a 15 mm
// ball), and every point near it classified as on the solid, not in it.
constexpr double kUnifiedToleranceMm = 1e-4;

// Whether `unified`, made from a shape whose largest tolerance was `before`, has one wider than
// kUnifiedToleranceMm and ten times `before`.
bool widened(const TopoDS_Shape& unified, double before);

// `shape` with the seams between faces (and edges) on one surface (curve) removed (OCCT's
// ShapeUpgrade_UnifySameDomain). Made on a copy: the unifier widens in place the tolerance of the
// vertices it keeps, which `shape` may share with other shapes (the other pieces of a split).
// `shape` itself where the result is widened() or OCCT fails.
TopoDS_Shape unify(const TopoDS_Shape& shape);

// The same made on `shape` itself, with no check: the faces it leaves untouched are `shape`'s,
// for a caller that looks up in the result faces it found on `shape`.
TopoDS_Shape unify_in_place(const TopoDS_Shape& shape);

// While any is alive (on any thread), OCCT's handlers for the fatal signals (SIGSEGV, SIGBUS,
// SIGFPE, SIGILL; OSD::SetSignal) replace the process's; every other signal keeps its handler
// (Ctrl-C stays Python's or the shell's). The last one to die puts the process's back. Each also
// turns its thread's floating-point traps off while alive, and back on after.
class SignalHandlers {
public:
    SignalHandlers();
    ~SignalHandlers();
    SignalHandlers(const SignalHandlers&) = delete;
    SignalHandlers& operator=(const SignalHandlers&) = delete;

private:
    int traps_ = 0;
};

// work(), with a fatal signal on this thread within it (an access violation: OCCT's readers and
// checkers dereference what a damaged file lacks, a STEP entity's missing reference, a BREP
// plane's zero direction) thrown as a Standard_Failure (Standard_AccessViolation, ...) instead of
// ending the process, FreeCAD with it. The jump out of OCCT skips destructors: what work() had
// built is leaked, and a fault inside the allocator could leave its lock held. A fatal signal on
// another thread meanwhile makes OCCT end the process (exit(1)), as the signal would have.
template <class Work>
auto catching_signals(Work&& work) -> decltype(work()) {
    const SignalHandlers handlers;
    OCC_CATCH_SIGNALS
    return work();
}

// "<what>: <OCCT's message>", with a fallback when OCCT gives none.
std::string failure_message(const std::string& what, const Standard_Failure& failure);

// Reads BREP text; `what` names the input in messages. Throws Error(EmptyInput / ReadFailed).
TopoDS_Shape read_brep(std::istream& in, const std::string& what);

// tessellate() with `what` naming the input in its messages (model_mesh() passes the file name).
TriangleMesh tessellate(const Shape& shape, const TessellationParams& params,
                        const std::string& what);

// The same for a solid known to be one valid closed solid (single_solid() passed it: no check
// again), at `deflection` mm and `angle` radians as given.
TriangleMesh tessellate_solid(const TopoDS_Shape& solid, double deflection, double angle,
                              const std::string& what);

}  // namespace occ
}  // namespace mas
