// Tessellation of one closed solid into the welded, outward-oriented triangle mesh the section
// kernel cuts (BRepMesh_IncrementalMesh, faces stitched through their shared edges).
#include <BRepBndLib.hxx>
#include <BRepBuilderAPI_Copy.hxx>
#include <BRepMesh_IncrementalMesh.hxx>
#include <BRep_Tool.hxx>
#include <Bnd_Box.hxx>
#include <IMeshData_Status.hxx>
#include <IMeshTools_Parameters.hxx>
#include <Poly_PolygonOnTriangulation.hxx>
#include <Poly_Triangulation.hxx>
#include <TopExp.hxx>
#include <TopExp_Explorer.hxx>
#include <TopLoc_Location.hxx>
#include <TopTools_IndexedMapOfShape.hxx>
#include <TopoDS.hxx>
#include <TopoDS_Edge.hxx>
#include <TopoDS_Face.hxx>
#include <TopoDS_Vertex.hxx>
#include <algorithm>
#include <cmath>
#include <optional>
#include <sstream>
#include <vector>

#include "ShapeImpl.hpp"

namespace mas {

namespace {

double bbox_diagonal(const TopoDS_Shape& s) {
    Bnd_Box box;
    BRepBndLib::AddOptimal(s, box, Standard_False, Standard_False);
    if (box.IsVoid()) return 0.0;
    return std::sqrt(box.SquareExtent());
}

Eigen::Vector3d to_eigen(const gp_Pnt& p) { return {p.X(), p.Y(), p.Z()}; }

// Collects the faces' triangulations into one mesh whose vertices are shared exactly where the
// faces share topology. BRepMesh discretises every edge once and records, per face, which nodes of
// that face's triangulation lie on it (BRep_Tool::PolygonOnTriangulation, in edge-parameter order),
// so node k of edge E is one global vertex whichever face it is seen from, and an edge's end nodes
// are its TopoDS_Vertex. The seam of a cylinder maps both of its sides onto one set of vertices,
// and a degenerated edge (a sphere's pole) collapses onto its vertex; the triangles that collapse
// with it are dropped. Returns nothing when the face meshes disagree about an edge (a node count
// or position that does not match), so the caller can fall back to welding by distance.
std::optional<TriangleMesh> weld_by_topology(const TopoDS_Shape& shape, double tolerance) {
    TopTools_IndexedMapOfShape vertex_map, edge_map;
    TopExp::MapShapes(shape, TopAbs_VERTEX, vertex_map);
    TopExp::MapShapes(shape, TopAbs_EDGE, edge_map);
    std::vector<int> vertex_node(vertex_map.Extent() + 1, -1);
    std::vector<std::vector<int>> edge_nodes(edge_map.Extent() + 1);
    TriangleMesh mesh;

    // The global vertex for a node first seen at `p`; later sightings must agree on the position
    // within `tol` (this catches a polygon read backwards, not rounding).
    auto claim = [&](int& slot, const Eigen::Vector3d& p, double tol) {
        if (slot < 0) {
            slot = static_cast<int>(mesh.vertices.size());
            mesh.vertices.push_back(p);
            return true;
        }
        return (mesh.vertices[slot] - p).norm() <= tol;
    };

    for (TopExp_Explorer fx(shape, TopAbs_FACE); fx.More(); fx.Next()) {
        const TopoDS_Face& face = TopoDS::Face(fx.Current());
        TopLoc_Location loc;
        const Handle(Poly_Triangulation)& tri = BRep_Tool::Triangulation(face, loc);
        if (tri.IsNull()) return std::nullopt;
        const gp_Trsf trsf = loc.Transformation();
        auto node = [&](int i) { return to_eigen(tri->Node(i).Transformed(trsf)); };
        std::vector<int> global(tri->NbNodes() + 1, -1);

        for (TopExp_Explorer ex(face, TopAbs_EDGE); ex.More(); ex.Next()) {
            const TopoDS_Edge& edge = TopoDS::Edge(ex.Current());
            // The orientation of `edge` picks the side of a seam (the polygon on each side).
            const Handle(Poly_PolygonOnTriangulation)& poly =
                BRep_Tool::PolygonOnTriangulation(edge, tri, loc);
            if (poly.IsNull()) return std::nullopt;
            const int n = poly->NbNodes();
            if (n < 2) return std::nullopt;
            TopoDS_Vertex first, last;  // at the start and the end of the edge's parameter range
            TopExp::Vertices(TopoDS::Edge(edge.Oriented(TopAbs_FORWARD)), first, last);
            if (first.IsNull() || last.IsNull()) return std::nullopt;
            const bool degenerated = BRep_Tool::Degenerated(edge);
            // Imported parts may carry loose edge and vertex tolerances; nodes agree within them.
            const double tol =
                std::max(tolerance, 2.0 * std::max(BRep_Tool::Tolerance(edge),
                                                   BRep_Tool::MaxTolerance(edge, TopAbs_VERTEX)));
            std::vector<int>& inner = edge_nodes[edge_map.FindIndex(edge)];
            if (inner.empty()) inner.assign(n, -1);
            if (static_cast<int>(inner.size()) != n) return std::nullopt;
            const bool reversed = poly->HasParameters() && poly->Parameter(1) > poly->Parameter(n);
            for (int k = 1; k <= n; ++k) {
                const int local = poly->Node(k);
                if (local < 1 || local > tri->NbNodes()) return std::nullopt;
                const int along = reversed ? n + 1 - k : k;  // position in parameter order
                int* slot;
                if (degenerated || along == 1)
                    slot = &vertex_node[vertex_map.FindIndex(first)];
                else if (along == n)
                    slot = &vertex_node[vertex_map.FindIndex(last)];
                else
                    slot = &inner[along - 1];
                // Positions are only compared for real edges: a degenerated edge's nodes may sit
                // apart in the triangulation's UV space while being one point in 3-D.
                if (!claim(*slot, node(local), tol) && !degenerated) return std::nullopt;
                if (global[local] >= 0 && global[local] != *slot) return std::nullopt;
                global[local] = *slot;
            }
        }
        for (int i = 1; i <= tri->NbNodes(); ++i)
            if (global[i] < 0) {
                global[i] = static_cast<int>(mesh.vertices.size());
                mesh.vertices.push_back(node(i));
            }
        // Triangles follow the surface's parametric normal: flip them on reversed faces so that
        // every facet faces out of the solid.
        const bool flip = face.Orientation() == TopAbs_REVERSED;
        for (int t = 1; t <= tri->NbTriangles(); ++t) {
            int a, b, c;
            tri->Triangle(t).Get(a, b, c);
            if (flip) std::swap(b, c);
            const Eigen::Vector3i g(global[a], global[b], global[c]);
            if (g[0] == g[1] || g[1] == g[2] || g[2] == g[0]) continue;  // collapsed at a pole
            mesh.triangles.push_back(g);
        }
    }
    return mesh;
}

// The fallback: every face's nodes on their own, then merged by distance.
TriangleMesh weld_by_distance(const TopoDS_Shape& shape, double tolerance) {
    TriangleMesh mesh;
    for (TopExp_Explorer fx(shape, TopAbs_FACE); fx.More(); fx.Next()) {
        const TopoDS_Face& face = TopoDS::Face(fx.Current());
        TopLoc_Location loc;
        const Handle(Poly_Triangulation)& tri = BRep_Tool::Triangulation(face, loc);
        if (tri.IsNull()) continue;
        const gp_Trsf trsf = loc.Transformation();
        const int base = static_cast<int>(mesh.vertices.size()) - 1;  // nodes are 1-based
        for (int i = 1; i <= tri->NbNodes(); ++i)
            mesh.vertices.push_back(to_eigen(tri->Node(i).Transformed(trsf)));
        const bool flip = face.Orientation() == TopAbs_REVERSED;
        for (int t = 1; t <= tri->NbTriangles(); ++t) {
            int a, b, c;
            tri->Triangle(t).Get(a, b, c);
            if (flip) std::swap(b, c);
            mesh.triangles.emplace_back(base + a, base + b, base + c);
        }
    }
    weld_vertices(mesh, tolerance);
    return mesh;
}

}  // namespace

double effective_deflection(const Shape& solid, const TessellationParams& params) {
    const double d = params.deflection_mm;
    if (!std::isfinite(d))
        throw Error(ErrorCode::InvalidArgument, "tessellation deflection must be a finite number");
    try {
        const double diagonal = bbox_diagonal(occ::occt(solid));
        if (!(diagonal > 0.0))
            throw Error(ErrorCode::EmptyInput, "tessellation input: the shape has no extent");
        if (d > 0.0) {
            // Finer than this, the facets of curved faces would run into the millions (and OCCT
            // spends minutes and gigabytes on them) for no section worth having.
            if (d < kMinDeflectionRatio * diagonal) {
                std::ostringstream msg;
                msg << "tessellation deflection " << d << " mm is too fine for a part " << diagonal
                    << " mm across: at least " << kMinDeflectionRatio * diagonal << " mm ("
                    << kMinDeflectionRatio << " of its diagonal)";
                throw Error(ErrorCode::InvalidArgument, msg.str());
            }
            return d;
        }
        // Over 10 m across, the 0.1 mm cap would be finer than the floor: the floor then.
        return std::max(std::clamp(5e-4 * diagonal, 0.005, 0.1), kMinDeflectionRatio * diagonal);
    } catch (const Standard_Failure& e) {
        throw Error(ErrorCode::GeometryFailure, occ::failure_message("tessellation input", e));
    }
}

TriangleMesh occ::tessellate(const Shape& shape, const TessellationParams& params,
                             const std::string& what) {
    const double angle = params.angular_deflection_rad;
    if (!std::isfinite(angle) || !(angle > 0.0))
        throw Error(ErrorCode::InvalidArgument,
                    "tessellation angular deflection must be a positive number of radians");
    const Shape solid = shape.single_solid(what);
    return tessellate_solid(occ::occt(solid), effective_deflection(solid, params), angle, what);
}

TriangleMesh occ::tessellate_solid(const TopoDS_Shape& solid, double deflection, double angle,
                                   const std::string& what) {
    TriangleMesh mesh;
    try {
        // Meshing stores triangulations in the faces it meshes: work on a copy (without any mesh
        // the shape already carries), so that Shape stays immutable and an old, coarser mesh is
        // never reused.
        BRepBuilderAPI_Copy copy(solid, Standard_True, Standard_False);
        const TopoDS_Shape work = copy.Shape();
        IMeshTools_Parameters mp;
        mp.Deflection = deflection;
        mp.Angle = angle;
        mp.Relative = Standard_False;
        mp.InParallel = Standard_True;
        BRepMesh_IncrementalMesh mesher(work, mp);
        if (!mesher.IsDone() || (mesher.GetStatusFlags() & IMeshData_Failure) != 0)
            throw Error(ErrorCode::GeometryFailure,
                        what + ": OCCT could not mesh some faces of the solid");

        const double diagonal = bbox_diagonal(work);
        // Nodes of one edge seen from two faces are copies of one point: 1e-6 of the part's size
        // only absorbs rounding, it never merges distinct nodes of a fine mesh.
        const double tolerance = std::max(1e-6 * diagonal, 1e-9);
        std::optional<TriangleMesh> welded = weld_by_topology(work, tolerance);
        if (welded && check_mesh(*welded).closed())
            mesh = std::move(*welded);
        else
            mesh = weld_by_distance(work, tolerance);
    } catch (const Standard_Failure& e) {
        throw Error(ErrorCode::GeometryFailure, occ::failure_message(what, e));
    }
    try {
        require_closed_mesh(mesh, what);
    } catch (const Error& e) {
        if (e.code() != ErrorCode::OpenMesh) throw;
        // The solid itself is closed (single_solid checked it): the gaps are in OCCT's meshing,
        // which happens on faulty geometry (faces that meet without sharing their edges).
        const MeshReport r = check_mesh(mesh);
        std::string defects;
        auto count = [&](std::size_t n, const char* kind) {
            if (n == 0) return;
            defects += (defects.empty() ? "" : ", ") + std::to_string(n) + " " + kind;
        };
        count(r.boundary_edges, "open edges");
        count(r.non_manifold_edges, "edges shared by more than two triangles");
        count(r.inconsistent_edges, "edges between oppositely oriented triangles");
        throw Error(ErrorCode::GeometryFailure,
                    what + ": OCCT's tessellation of the solid has " + defects +
                        "; its faces may not join properly (check it with Part, Check geometry) "
                        "or another deflection may mesh it");
    }
    // Closed is not enough: OCCT's shape check passes solids whose faces mesh far off their
    // surfaces (a cylinder whose seam is a B-spline and whose top and bottom circles are split
    // at different places, left by a fuse and Part's Refine shape: its side meshed into a cone, a
    // third of the volume, at any deflection), and every section cut from such a mesh is wrong.
    // Each mesh point lies within the deflection of the surface, so the volumes differ by at most
    // the area times the deflection; twice that is allowed (OCCT keeps the deflection at the nodes
    // it places, not everywhere).
    double area = 0.0;
    for (const auto& t : mesh.triangles)
        area +=
            0.5 * (mesh.vertices[std::size_t(t[1])] - mesh.vertices[std::size_t(t[0])])
                      .cross(mesh.vertices[std::size_t(t[2])] - mesh.vertices[std::size_t(t[0])])
                      .norm();
    double exact = 0.0;
    try {
        exact = std::abs(occ::volume_of(solid));
    } catch (const Standard_Failure& e) {
        throw Error(ErrorCode::GeometryFailure, occ::failure_message(what, e));
    }
    const double meshed = std::abs(mesh_volume(mesh));
    const double allowed = 2.0 * area * deflection + 1e-9 * exact;
    if (std::abs(meshed - exact) > allowed) {
        std::ostringstream msg;
        msg << what << ": OCCT's tessellation of the solid encloses " << meshed
            << " mm^3 where the solid holds " << exact << " mm^3, more apart than its " << area
            << " mm^2 of surface at the deflection (" << deflection << " mm) allow (" << allowed
            << " mm^3): some of its faces mesh off their surfaces, which OCCT's shape check does "
               "not catch; model those faces again (or try another deflection)";
        throw Error(ErrorCode::GeometryFailure, msg.str());
    }
    return mesh;
}

TriangleMesh tessellate(const Shape& shape, const TessellationParams& params) {
    return occ::tessellate(shape, params, "tessellation input");
}

}  // namespace mas
