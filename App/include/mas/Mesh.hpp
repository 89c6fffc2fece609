// Triangle meshes: the indexed triangle set every cross-section is cut from, and its checks.
// Core stage (Eigen only): the OCCT side tessellates solids into this, the readers fill it from
// files.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <string>
#include <vector>

namespace mas {

// An indexed triangle set. Triangles are counter-clockwise seen from outside (outward normals), as
// OCCT's tessellation of a solid and a well-formed STL give them; vertices are shared between
// triangles so that edges are topological (the slicer chains section segments through shared
// edges).
struct TriangleMesh {
    std::vector<Eigen::Vector3d> vertices;   // mm
    std::vector<Eigen::Vector3i> triangles;  // indices into vertices, CCW seen from outside

    bool empty() const { return triangles.empty(); }
};

// What check_mesh() found. A closed (watertight, 2-manifold, consistently oriented) mesh has
// boundary_edges == non_manifold_edges == inconsistent_edges == 0.
struct MeshReport {
    std::size_t vertices = 0;
    std::size_t triangles = 0;
    std::size_t non_finite_vertices = 0;   // vertices with a NaN or infinite coordinate
    std::size_t degenerate_triangles = 0;  // triangles with a repeated vertex index
    std::size_t boundary_edges = 0;        // edges used by one triangle only (holes)
    std::size_t non_manifold_edges = 0;    // edges used by more than two triangles
    std::size_t inconsistent_edges = 0;  // edges traversed in the same direction by both triangles
    double volume_mm3 = 0.0;  // signed volume (divergence theorem); > 0 for outward normals

    bool closed() const {
        return boundary_edges == 0 && non_manifold_edges == 0 && inconsistent_edges == 0;
    }
};

MeshReport check_mesh(const TriangleMesh& mesh);

// The signed volume of the tetrahedron (origin, a, b, c): summed over a closed mesh's triangles,
// the volume it bounds (divergence theorem), > 0 for outward normals.
inline double tetra_volume(const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                           const Eigen::Vector3d& c) {
    return a.dot(b.cross(c)) / 6.0;
}

// The apex the mesh's volume sums take their tetrahedra from: one of its own vertices (none: the
// origin). From the origin, a part far from it sums large terms that cancel: a sphere of radius
// 10 at 1e7 mm came out at 942527 mm^3 for 4189, and at 1e8 mm negative (taken for inside out).
inline Eigen::Vector3d volume_apex(const TriangleMesh& mesh) {
    return mesh.vertices.empty() ? Eigen::Vector3d::Zero() : mesh.vertices.front();
}

// The signed volume a closed mesh bounds (check_mesh's volume_mm3, without the edge checks).
double mesh_volume(const TriangleMesh& mesh);

// The farthest a vertex may lie from the origin along an axis, mm (1000 km). There a double still
// resolves 1.2e-7 mm, two orders finer than the 1e-5 mm grid of the polygon Booleans; far beyond,
// coordinates lose the grid, and areas overflow (a cube of 1e301 mm gave an infinite area and a
// NaN centroid).
inline constexpr double kMaxCoordinateMm = 1e9;

// Throws mas::Error (EmptyInput, NonFiniteCoordinate, OpenMesh) unless the mesh is a closed,
// consistently oriented surface with finite coordinates within kMaxCoordinateMm of the origin.
// `what` names the input in the message.
// A closed mesh with inward normals (negative volume) is flipped in place rather than rejected.
void require_closed_mesh(TriangleMesh& mesh, const std::string& what);

// For a closed mesh given as a mesh (a file, a script's), after require_closed_mesh: throws
// mas::Error(NotASolid) unless its shells bound one solid, outer shells facing out and a cavity's
// shell facing in (overlapping shells, a shell inside another of the same orientation, one inside
// out on its own). A tessellated BREP solid is one by construction and is not checked.
void require_one_solid(const TriangleMesh& mesh, const std::string& what);

// Puts a mesh given as a mesh in one order whatever order it came in: vertices sorted by their
// coordinates (x, then y, then z), each triangle starting at its least vertex (its turn kept),
// triangles sorted. The same surface written with its facets or their corners in another order
// (another exporter, a shuffled STL) then slices the same: sums over facets in another order
// differ in their last bits, and a choice near its threshold (a layer's thickness, whether a
// region is supported) can go the other way on it (a U handle's mesh, shuffled: 38 or 40 layers).
void canonical_order(TriangleMesh& mesh);

// Merges vertices closer than `tolerance_mm` (STL and OFF soups repeat vertices per triangle) and
// drops triangles that collapse. Returns the number of vertices removed.
std::size_t weld_vertices(TriangleMesh& mesh, double tolerance_mm);

Eigen::AlignedBox3d bounding_box(const TriangleMesh& mesh);

// The range [lo, hi] of a box's points along `direction` (unit): exact for an axis-aligned
// direction, bounds otherwise (a box's corners bound any direction's range).
void range_along(const Eigen::AlignedBox3d& box, const Eigen::Vector3d& direction, double& lo,
                 double& hi);

// Geomview OFF reader (the CGAL data sets used by the benchmarks): OFF, and [ST][C][N]OFF, whose
// texture coordinates, colours and normals after each vertex's three coordinates on its line are
// ignored; not binary OFF, nor [4][n]OFF. Polygons with more than three corners are fanned into
// triangles. Throws mas::Error(ReadFailed / EmptyInput / NonFiniteCoordinate).
TriangleMesh read_off(const std::string& path);

// Writes the mesh as a binary STL (coordinates rounded to float, zero facet normals, which
// readers recompute from the corners' order). Throws mas::Error(WriteFailed) naming the path.
void write_stl(const TriangleMesh& mesh, const std::string& path);

}  // namespace mas
