// Cross-sections of a closed triangle mesh by planes of any orientation (the kernel under the
// centroidal axis, paper Sec. 3, and the layers, Sec. 4.2). Planes that share a normal are cut in
// one pass: each facet finds the range of planes its extent spans by binary search (PrusaSlicer's
// slice_mesh, Minetto et al. 2017) instead of testing every facet against every plane.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <functional>
#include <vector>

#include "mas/Mesh.hpp"
#include "mas/Polygon2.hpp"

namespace mas {

// A plane through `origin` with unit `normal`; the side the normal points to is "above".
struct Plane {
    Eigen::Vector3d origin = Eigen::Vector3d::Zero();   // mm
    Eigen::Vector3d normal = Eigen::Vector3d::UnitZ();  // unit length

    double signed_distance(const Eigen::Vector3d& p) const { return normal.dot(p - origin); }
};

// Throws mas::Error(InvalidArgument) on a zero or non-finite normal or a non-finite origin;
// returns the plane with its normal normalised.
Plane make_plane(const Eigen::Vector3d& origin, const Eigen::Vector3d& normal);

// The 2-D frame of every plane with a given normal: 2-D coordinates of a point are (p.u, p.v),
// independent of the plane's origin, so sections on parallel planes share coordinates and
// "projecting the upper section onto the lower one" (paper Eq. 2) is the identity in 2-D.
// (u, v, normal) is right-handed, so CCW in 2-D is CCW seen from above the plane.
struct PlaneFrame {
    Eigen::Vector3d u, v, normal;

    explicit PlaneFrame(const Eigen::Vector3d& unit_normal);
    Eigen::Vector2d to_2d(const Eigen::Vector3d& p) const { return {p.dot(u), p.dot(v)}; }
    // The 3-D point with 2-D coordinates `q` lying on `plane`.
    Eigen::Vector3d to_3d(const Eigen::Vector2d& q, const Plane& plane) const {
        return u * q.x() + v * q.y() + normal * normal.dot(plane.origin);
    }
};

// One connected piece of a cross-section: an outer loop (CCW seen from above) with its holes.
struct SectionRegion {
    Region2 shape;                                       // in the plane's PlaneFrame coordinates
    double area = 0.0;                                   // mm^2, outer minus holes
    Eigen::Vector3d centroid = Eigen::Vector3d::Zero();  // area centroid, on the plane
    Eigen::AlignedBox3d bounds;                          // of the outer loop, in 3-D
};

// Everything a plane cuts out of the mesh.
struct Section {
    Plane plane;
    std::vector<SectionRegion> regions;                  // largest area first
    double area = 0.0;                                   // total, mm^2
    Eigen::Vector3d centroid = Eigen::Vector3d::Zero();  // of all regions together; origin if empty
    std::size_t open_chains = 0;  // segment chains that did not close (0 on a closed mesh)

    bool empty() const { return regions.empty(); }
    PlaneFrame frame() const { return PlaneFrame(plane.normal); }
    // The 3-D loops of a region: outer first, then its holes.
    std::vector<std::vector<Eigen::Vector3d>> loops_3d(std::size_t region) const;
};

// Orders a section's regions largest first and sets its total area and centroid from them (the
// plane's origin when it has none). Both the mesh kernel and the exact path end with it.
void finish_section(Section& section);

struct SliceParams {
    // Build loops and regions (outer loops with holes). When false only each section's total area
    // and centroid are computed, straight from the segments (Green's theorem), which is cheaper.
    bool build_regions = true;
    // Loops whose |area| is below this are dropped (slivers from a plane grazing a facet).
    double min_loop_area_mm2 = 1e-9;
    // Merge consecutive loop points closer than this.
    double point_merge_tolerance_mm = 1e-7;
};

// Cuts `mesh` with every plane; result[i] belongs to planes[i]. Planes may have any normals: planes
// with the same normal are cut together. `mesh` must be closed (see require_closed_mesh); a vertex
// lying exactly on a plane counts as above it, so a horizontal facet lying on a plane is never cut.
// `throw_on_cancel` is called now and then from the calling thread and may throw to stop the work.
std::vector<Section> slice_mesh(const TriangleMesh& mesh, const std::vector<Plane>& planes,
                                const SliceParams& params = {},
                                const std::function<void()>& throw_on_cancel = {});

Section slice_mesh(const TriangleMesh& mesh, const Plane& plane, const SliceParams& params = {});

// How many points the section of `mesh` by each plane holds (before points closer than the merge
// tolerance are merged): the plane's crossings with the mesh's facets, counted without cutting, in
// O(V log P); result[i] belongs to planes[i]. slice_mesh() keeps about 35 bytes per point: callers
// that keep or draw many sections check the total first (the Python sections()), or cut a few
// million points at a time (the command line's `sections`).
std::vector<std::size_t> section_point_counts(const TriangleMesh& mesh,
                                              const std::vector<Plane>& planes);

// The most planes parallel_planes() gives: their sections would take gigabytes.
inline constexpr std::size_t kMaxParallelPlanes = 100000;

// Planes with unit `normal` across the mesh's whole extent along it, `step_mm` apart, each in the
// middle of its slab: at min + (i + 1/2) step for i = 0 .. floor((max - min) / step) - 1, plus one
// more in the middle of a remaining partial slab. Throws mas::Error(InvalidArgument) on a step that
// is not positive and finite, a zero normal, or a step so small that it would give more than
// kMaxParallelPlanes planes (caught before any is cut).
std::vector<Plane> parallel_planes(const TriangleMesh& mesh, const Eigen::Vector3d& normal,
                                   double step_mm);

}  // namespace mas
