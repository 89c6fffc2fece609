// CGAL's mean-curvature-flow skeleton of a mesh, timed: the comparison for bench_axis.cpp. Kept
// apart from every OCCT header, whose Handle macro breaks CGAL's.
#include <CGAL/Simple_cartesian.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/extract_mean_curvature_flow_skeleton.h>

#include <chrono>

#include "mas/Mesh.hpp"

double cgal_skeleton_ms(const mas::TriangleMesh& mesh, std::size_t& skeleton_vertices) {
    using K = CGAL::Simple_cartesian<double>;
    using SurfaceMesh = CGAL::Surface_mesh<K::Point_3>;
    SurfaceMesh sm;
    std::vector<SurfaceMesh::Vertex_index> v;
    v.reserve(mesh.vertices.size());
    for (const auto& p : mesh.vertices) v.push_back(sm.add_vertex(K::Point_3(p.x(), p.y(), p.z())));
    for (const auto& t : mesh.triangles) sm.add_face(v[t[0]], v[t[1]], v[t[2]]);
    CGAL::Mean_curvature_flow_skeletonization<SurfaceMesh>::Skeleton skeleton;
    const auto start = std::chrono::steady_clock::now();
    CGAL::extract_mean_curvature_flow_skeleton(sm, skeleton);
    const auto end = std::chrono::steady_clock::now();
    skeleton_vertices = boost::num_vertices(skeleton);
    return std::chrono::duration<double, std::milli>(end - start).count();
}
