// Private to the engine (never included by a public header): sections on a fixed stack of parallel
// planes, cut a few planes at a time. slice_mesh pays for the whole mesh on every call (every
// vertex projected, every facet's plane range searched); a march that needs its planes a chunk at a
// time (the centroidal axis) pays that once here, and each cut then costs only the facets it meets.
#pragma once

#include <cstdint>
#include <functional>
#include <vector>

#include "mas/Section.hpp"

namespace mas {

class SectionGrid {
public:
    // `planes` must share one normal and come in ascending order along it (ties allowed);
    // throws mas::Error(InvalidArgument) otherwise. `mesh` must outlive the grid.
    SectionGrid(const TriangleMesh& mesh, std::vector<Plane> planes,
                const SliceParams& params = {});

    std::size_t size() const { return planes_.size(); }

    // The sections of planes [first, last), the same (loops, their starting points, regions, their
    // order) as slice_mesh(mesh, those planes, params) gives. Planes are cut in parallel; `each`,
    // if given, is then called once per section, from any thread, with the plane's index in the
    // grid, so that callers can post-process sections in parallel too.
    std::vector<Section> cut(std::size_t first, std::size_t last,
                             const std::function<void(std::size_t, Section&)>& each = {}) const;

    // The section of the plane at `offset` along the grid's normal, any offset (between the
    // grid's planes, say), cut from the facets that reach it: the same regions as slice_mesh
    // gives on that plane. One scan of the facets' plane ranges, no preparation; on the calling
    // thread alone.
    Section cut_at(double offset) const;

private:
    std::uint32_t upper_bound(double x) const;  // heights_ at or below x

    const TriangleMesh& mesh_;
    SliceParams params_;
    std::vector<Plane> planes_;             // normalised as slice_mesh does (make_plane)
    std::vector<double> heights_;           // the distinct plane offsets, ascending
    std::vector<std::uint32_t> height_of_;  // per plane: its index in heights_
    std::vector<double> h_;                 // per vertex: offset along the normal
    std::vector<Eigen::Vector2d> uv_;       // per vertex: PlaneFrame coordinates
    // Per facet: the distinct heights [first, last) it crosses (slice_mesh's plane range).
    std::vector<std::uint32_t> first_, last_;
    // Facets crossing at least one height, by first height and then index: bucket_start_[j] ..
    // bucket_start_[j + 1] of bucket_. Facets crossing more than kShort heights are also listed
    // in long_, by index.
    std::vector<std::uint32_t> bucket_start_, bucket_, long_;
    static constexpr std::uint32_t kShort = 8;
};

}  // namespace mas
