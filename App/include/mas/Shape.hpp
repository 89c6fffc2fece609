// The OCCT side of the engine behind a plain handle: reading parts (BREP text, STEP, IGES, BREP,
// STL files), checking them, tessellating solids for the section kernel, and OCCT's exact section
// as the reference the mesh path is checked against. No OCCT type appears in this header.
#pragma once

#include <Eigen/Geometry>
#include <memory>
#include <string>
#include <vector>

#include "mas/Mesh.hpp"
#include "mas/Section.hpp"

namespace mas {

// What a shape is made of.
struct ShapeInfo {
    int solids = 0;
    int shells = 0;
    int faces = 0;
    int edges = 0;
    int free_faces = 0;  // faces not inside any solid
    int free_edges = 0;  // edges not inside any face
    double volume_mm3 = 0.0;
    Eigen::AlignedBox3d bounds;
};

// An immutable OCCT shape. Copies share the same geometry.
class Shape {
public:
    Shape();
    ~Shape();
    Shape(const Shape&);
    Shape& operator=(const Shape&);

    // BREP text as FreeCAD's Shape.exportBrepToString() writes it. Throws
    // Error(EmptyInput/ReadFailed).
    static Shape from_brep_string(const std::string& brep);
    std::string to_brep_string() const;

    bool is_null() const;
    ShapeInfo info() const;

    // Throws Error(NotASolid / MultipleSolids / EmptyInput) unless the shape holds exactly one
    // closed solid; `what` names the input in the message. Returns that solid. A lone closed shell
    // (some exporters write solids so) counts as the solid it bounds; an inside-out solid comes
    // back turned right side out. Several solids that share material (a CompSolid, a compound of a
    // plate and a post standing on it) are one body to deposit: their union comes back, coplanar
    // faces merged; solids apart, or meeting only along an edge or at a point, are MultipleSolids
    // (GeometryFailure if OCCT's fuse fails). Faces outside the solids are an error (NotASolid:
    // they may be material meant for the part); loose edges and vertices are left out.
    Shape single_solid(const std::string& what) const;

    struct Impl;
    const Impl& impl() const { return *impl_; }
    explicit Shape(std::shared_ptr<const Impl> impl);

private:
    std::shared_ptr<const Impl> impl_;
};

// Chordal deflection used to tessellate a solid before cutting it. The absolute deflection is the
// largest distance between a facet and the exact surface, so mesh sections differ from exact ones
// by at most about that much along their boundary.
struct TessellationParams {
    // mm; <= 0 means "derive from the part": 0.05% of the bounding-box diagonal, clamped to
    // [0.005, 0.1] mm (0.01 mm for a 20 mm diagonal, 0.1 mm for diagonals over 200 mm), and never
    // finer than kMinDeflectionRatio of the diagonal (parts over 10 m across).
    double deflection_mm = 0.0;
    double angular_deflection_rad = 0.35;  // ~20 degrees, bounds facet normals on tight curves
};

// A given deflection below this fraction of the part's bounding-box diagonal is InvalidArgument.
inline constexpr double kMinDeflectionRatio = 1e-5;

// params.deflection_mm, or the one derived from the part. Throws InvalidArgument for a deflection
// that is not finite or finer than kMinDeflectionRatio of the part's diagonal.
double effective_deflection(const Shape& solid, const TessellationParams& params);

// Tessellates one closed solid into a closed, outward-oriented, welded triangle mesh.
// Throws Error(NotASolid, ...) as single_solid() does, Error(GeometryFailure) if meshing fails.
TriangleMesh tessellate(const Shape& shape, const TessellationParams& params = {});

// A part read from a file or handed over by FreeCAD: either a BREP shape or a triangle mesh.
struct Model {
    enum class Kind { Solid, Mesh };
    Kind kind = Kind::Solid;
    Shape shape;        // for Kind::Solid
    TriangleMesh mesh;  // for Kind::Mesh (an STL or OFF file, a FreeCAD Mesh)
    std::string name;   // file name or caller-given name, for messages
};

// Reads .step/.stp, .iges/.igs, .brep/.brp (OCCT's readers), .stl (OCCT's RWStl, vertices welded)
// and .off. Throws Error(ReadFailed / EmptyInput / UnsupportedFormat / NonFiniteCoordinate).
Model read_model(const std::string& path);

// The closed triangle mesh the section kernel cuts for a model: the tessellation of a solid, or the
// checked mesh itself. Throws the errors of tessellate() and require_closed_mesh().
TriangleMesh model_mesh(const Model& model, const TessellationParams& params = {});

// OCCT's exact section (BRepAlgoAPI_Section, edges joined into wires, wires into faces, areas and
// centroids from BRepGProp): the reference for checking the mesh kernel, 13 to 23 times slower on
// the example bracket, about 500 times across a torus' tube. Loops are discretised with
// `loop_deflection_mm` for the 2-D regions. Areas and centroids are exact for sections bounded by
// lines, circles and ellipses; where OCCT can only trace the curves, they come from its face when
// that agrees with the discretised loops within perimeter x loop deflection, else from the loops.
std::vector<Section> exact_sections(const Shape& solid, const std::vector<Plane>& planes,
                                    double loop_deflection_mm = 0.01);

}  // namespace mas

namespace mas {

// Writes `shape` as a STEP file (AP214, millimetres). Throws Error(EmptyInput) for a null shape,
// Error(ReadFailed) when the file cannot be written.
void write_step(const Shape& shape, const std::string& path);

// OCCT's readers print progress and warnings to standard output through its default messenger.
// A command-line program whose standard output is data calls this once at start to drop them.
void silence_occt_console();

}  // namespace mas
