// Private to the OCCT side of the engine: the TopoDS_Shape behind mas::Shape, and the helpers the
// files in App/src/occ share (wrapping a TopoDS_Shape, turning Standard_Failure into mas::Error).
#pragma once

#include <Eigen/Geometry>
#include <Standard_Failure.hxx>
#include <TopoDS_Shape.hxx>
#include <istream>
#include <string>

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

// `shape` with the seams between faces (and edges) on one surface (curve) removed.
TopoDS_Shape unify(const TopoDS_Shape& shape);

// "<what>: <OCCT's message>", with a fallback when OCCT gives none.
std::string failure_message(const std::string& what, const Standard_Failure& failure);

// Reads BREP text; `what` names the input in messages. Throws Error(EmptyInput / ReadFailed).
TopoDS_Shape read_brep(std::istream& in, const std::string& what);

// tessellate() with `what` naming the input in its messages (model_mesh() passes the file name).
TriangleMesh tessellate(const Shape& shape, const TessellationParams& params,
                        const std::string& what);

}  // namespace occ
}  // namespace mas
