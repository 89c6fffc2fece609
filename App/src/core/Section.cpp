// The cross-section kernel. For each group of planes sharing a normal:
//   1. project every vertex on the normal once (h = n.v);
//   2. each facet finds the planes its [hmin, hmax) spans by binary search over the sorted plane
//      offsets (PrusaSlicer's slice_mesh; Minetto et al. 2017). Facets are bucketed by the first
//      plane they reach; planes are cut in fixed batches, in parallel, each batch gathering its
//      facets from the buckets into reused per-thread buffers: bounded memory, no locks, and a
//      result that does not depend on thread timing. Totals only (area, centroid) accumulate
//      straight from the crossings per (facet chunk, plane), with no segments stored;
//   3. per plane, segments are chained into loops through the mesh edges they cross (topological
//      keys, never by comparing coordinates), and loops are grouped into regions with holes.
// Degenerate case: a vertex exactly on a plane counts as above it (symbolic perturbation), so
// every crossed facet has exactly one edge going down and one going up through the plane, chains
// close on a closed mesh, and a facet lying in a plane is never cut: a horizontal face at exactly
// the height of a plane belongs to the slab below it.
// SectionGrid (SectionGrid.hpp) keeps steps 1 and 2 of a stack of planes, so that a caller that
// cuts them a few at a time (the centroidal axis' marches) pays for the whole mesh once; each of
// its cuts gives what slice_mesh gives for the same planes.
#include "mas/Section.hpp"

#include <tbb/blocked_range.h>
#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <memory>
#include <numeric>
#include <sstream>
#include <thread>

#include "SectionGrid.hpp"
#include "mas/Error.hpp"

namespace mas {

Plane make_plane(const Eigen::Vector3d& origin, const Eigen::Vector3d& normal) {
    if (!origin.allFinite())
        throw Error(ErrorCode::InvalidArgument, "plane origin has NaN or infinite coordinates");
    if (!normal.allFinite())
        throw Error(ErrorCode::InvalidArgument, "plane normal has NaN or infinite coordinates");
    const double len = normal.norm();
    if (std::isinf(len)) {  // (1e300, 1e300, 1e300): scaled down first, it is a direction
        const Eigen::Vector3d scaled = normal / normal.cwiseAbs().maxCoeff();
        return Plane{origin, scaled / scaled.norm()};
    }
    if (!(len > 1e-12)) throw Error(ErrorCode::InvalidArgument, "plane normal is the zero vector");
    return Plane{origin, normal / len};
}

PlaneFrame::PlaneFrame(const Eigen::Vector3d& unit_normal) : normal(unit_normal) {
    // u: the global X axis made perpendicular to the normal, or Y when the normal is close to X.
    // Gives u = X, v = Y for a +Z normal, so 2-D coordinates of horizontal sections are (x, y).
    const Eigen::Vector3d helper =
        std::abs(unit_normal.x()) < 0.9 ? Eigen::Vector3d::UnitX() : Eigen::Vector3d::UnitY();
    u = (helper - unit_normal * unit_normal.dot(helper)).normalized();
    v = unit_normal.cross(u);
}

void finish_section(Section& section) {
    std::stable_sort(
        section.regions.begin(), section.regions.end(),
        [](const SectionRegion& a, const SectionRegion& b) { return a.area > b.area; });
    double total = 0.0;
    Eigen::Vector3d moment = Eigen::Vector3d::Zero();
    for (const auto& r : section.regions) {
        total += r.area;
        moment += r.area * r.centroid;
    }
    section.area = total;
    section.centroid = total > 0.0 ? Eigen::Vector3d(moment / total) : section.plane.origin;
}

std::vector<std::vector<Eigen::Vector3d>> Section::loops_3d(std::size_t region) const {
    const PlaneFrame f = frame();
    const SectionRegion& r = regions.at(region);
    std::vector<std::vector<Eigen::Vector3d>> loops;
    auto lift = [&](const Polygon2& p) {
        std::vector<Eigen::Vector3d> loop;
        loop.reserve(p.points.size());
        for (const auto& q : p.points) loop.push_back(f.to_3d(q, plane));
        loops.push_back(std::move(loop));
    };
    lift(r.shape.outer);
    for (const auto& h : r.shape.holes) lift(h);
    return loops;
}

namespace {

constexpr std::size_t kChunk = 16384;  // facets per work item

std::uint64_t edge_key(int a, int b) {
    const auto lo = static_cast<std::uint32_t>(std::min(a, b));
    const auto hi = static_cast<std::uint32_t>(std::max(a, b));
    return (std::uint64_t(lo) << 32) | hi;
}

// A segment of a section: it enters the facet through mesh edge `from` at 2-D point `p` and
// leaves through `to`, running counter-clockwise (material on its left) seen from above the plane.
// The point is computed while the facet's vertices are in cache; chaining needs only the keys.
struct Segment {
    std::uint64_t from, to;
    Eigen::Vector2d p;
};

// Where the plane at height d crosses the edge (a, b) of the mesh, in 2-D. Computed from the edge's
// endpoints in a fixed order (lower index first), so both facets sharing the edge produce the
// same point.
Eigen::Vector2d crossing(int a, int b, double d, const std::vector<double>& h,
                         const std::vector<Eigen::Vector2d>& uv) {
    if (a > b) std::swap(a, b);
    const double t = (d - h[std::size_t(a)]) / (h[std::size_t(b)] - h[std::size_t(a)]);
    return uv[std::size_t(a)] + t * (uv[std::size_t(b)] - uv[std::size_t(a)]);
}

// Open-addressing map from a segment's `from` key to its index, rebuilt per plane.
class KeyIndex {
public:
    void build(const Segment* segs, std::size_t n) {
        std::size_t cap = 16;
        while (cap < 2 * n) cap <<= 1;
        mask_ = cap - 1;
        slots_.assign(cap, Slot{0, -1});
        for (std::size_t i = 0; i < n; ++i) {
            std::size_t s = hash(segs[i].from) & mask_;
            while (slots_[s].index >= 0) s = (s + 1) & mask_;
            slots_[s] = {segs[i].from, static_cast<std::int64_t>(i)};
        }
    }
    // First not yet used segment starting at `key`, or -1.
    std::int64_t find(std::uint64_t key, const std::vector<char>& used) const {
        for (std::size_t s = hash(key) & mask_; slots_[s].index >= 0; s = (s + 1) & mask_)
            if (slots_[s].key == key && !used[std::size_t(slots_[s].index)]) return slots_[s].index;
        return -1;
    }

private:
    struct Slot {
        std::uint64_t key;
        std::int64_t index;
    };
    static std::size_t hash(std::uint64_t k) {
        k ^= k >> 33;
        k *= 0xff51afd7ed558ccdULL;
        k ^= k >> 33;
        return static_cast<std::size_t>(k);
    }
    std::vector<Slot> slots_;
    std::size_t mask_ = 0;
};

// Chains the segments of one plane into loops, then regions.
void build_regions(const Segment* segs, std::size_t n, const SliceParams& params, Section& out) {
    KeyIndex index;
    index.build(segs, n);
    std::vector<char> used(n, 0);
    std::vector<Polygon2> loops;
    const double merge2 = params.point_merge_tolerance_mm * params.point_merge_tolerance_mm;
    for (std::size_t start = 0; start < n; ++start) {
        if (used[start]) continue;
        Polygon2 loop;
        std::size_t cur = start;
        bool closed = false;
        while (true) {
            used[cur] = 1;
            const Eigen::Vector2d& p = segs[cur].p;
            if (loop.points.empty() || (p - loop.points.back()).squaredNorm() > merge2)
                loop.points.push_back(p);
            if (segs[cur].to == segs[start].from) {
                closed = true;
                break;
            }
            const std::int64_t next = index.find(segs[cur].to, used);
            if (next < 0) break;
            cur = static_cast<std::size_t>(next);
        }
        if (!closed) {
            ++out.open_chains;
            continue;
        }
        while (loop.points.size() > 1 &&
               (loop.points.front() - loop.points.back()).squaredNorm() <= merge2)
            loop.points.pop_back();
        if (loop.points.size() >= 3) loops.push_back(std::move(loop));
    }
    Regions2 regions = regions_from_loops(std::move(loops), params.min_loop_area_mm2);
    const PlaneFrame frame(out.plane.normal);
    out.regions.reserve(regions.size());
    for (auto& r : regions) {
        SectionRegion sr;
        sr.area = area(r);
        sr.centroid = frame.to_3d(centroid(r), out.plane);
        for (const auto& q : r.outer.points) sr.bounds.extend(frame.to_3d(q, out.plane));
        sr.shape = std::move(r);
        out.regions.push_back(std::move(sr));
    }
    finish_section(out);
}

// The crossing of facet t with the plane at height d, as a segment running from the edge where
// the facet goes down through the plane to the edge where it comes back up. Walking the facet's
// edges in order (CCW from outside), with an outward facet normal nt, n x nt points along the
// CCW section boundary, which runs from the "down" edge's crossing to the "up" edge's.
struct Crossing {
    int down_a, down_b, up_a, up_b;
};

Crossing cross_facet(const Eigen::Vector3i& t, double d, const std::vector<double>& h) {
    Crossing c{0, 0, 0, 0};
    for (int e = 0; e < 3; ++e) {
        const int a = t[e], b = t[(e + 1) % 3];
        const bool a_below = h[std::size_t(a)] < d, b_below = h[std::size_t(b)] < d;
        if (a_below == b_below) continue;
        if (b_below) {
            c.down_a = a;
            c.down_b = b;
        } else {
            c.up_a = a;
            c.up_b = b;
        }
    }
    return c;
}

// Every vertex's offset along `normal` and its coordinates in PlaneFrame(normal).
void project(const TriangleMesh& mesh, const Eigen::Vector3d& normal, std::vector<double>& h,
             std::vector<Eigen::Vector2d>& uv) {
    const PlaneFrame frame(normal);
    const std::size_t nv = mesh.vertices.size();
    h.resize(nv);
    uv.resize(nv);
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, nv, kChunk), [&](const auto& r) {
        for (std::size_t i = r.begin(); i != r.end(); ++i) {
            h[i] = normal.dot(mesh.vertices[i]);
            uv[i] = frame.to_2d(mesh.vertices[i]);
        }
    });
}

// Planes at heights d with lo < d <= hi cut a facet spanning [lo, hi] (a vertex on a plane is
// above it): [first, last) in the ascending `offsets`.
void facet_planes(const Eigen::Vector3i& t, const std::vector<double>& h,
                  const std::vector<double>& offsets, std::size_t& first, std::size_t& last) {
    const double a = h[std::size_t(t[0])], b = h[std::size_t(t[1])], c = h[std::size_t(t[2])];
    const double lo = std::min({a, b, c}), hi = std::max({a, b, c});
    first = std::size_t(std::upper_bound(offsets.begin(), offsets.end(), lo) - offsets.begin());
    last = std::size_t(std::upper_bound(offsets.begin(), offsets.end(), hi) - offsets.begin());
}

// Planes per batch of the region path: see slice_group.
constexpr std::size_t kBatch = 64;

// Slices the mesh by planes that all share `normal`; `offsets[k]` is n.origin of plane
// `which[k]`, sorted ascending. Every step is parallel and its result independent of thread
// timing: facets in fixed chunks, planes in fixed batches.
void slice_group(const TriangleMesh& mesh, const Eigen::Vector3d& normal,
                 const std::vector<double>& offsets, const std::vector<std::size_t>& which,
                 const SliceParams& params, const std::function<void()>& check_cancel,
                 std::vector<Section>& out) {
    const PlaneFrame frame(normal);
    const std::size_t nv = mesh.vertices.size();
    std::vector<double> h;
    std::vector<Eigen::Vector2d> uv;
    project(mesh, normal, h, uv);

    const std::size_t nt = mesh.triangles.size();
    const std::size_t np = offsets.size();
    // Fewer, larger chunks when there are very many planes, so that the (chunk, plane) tables
    // stay under ~16 M entries.
    const std::size_t chunk = std::max<std::size_t>(
        kChunk, std::size_t(double(nt) * double(std::max<std::size_t>(np, 1)) / 16e6) + 1);
    const std::size_t nchunks = (nt + chunk - 1) / chunk;
    auto plane_range = [&](const Eigen::Vector3i& t, std::size_t& first, std::size_t& last) {
        facet_planes(t, h, offsets, first, last);
    };
    auto for_chunks = [&](const auto& body) {
        tbb::parallel_for(tbb::blocked_range<std::size_t>(0, nchunks, 1), [&](const auto& r) {
            for (std::size_t c = r.begin(); c != r.end(); ++c)
                body(c, c * chunk, std::min(nt, (c + 1) * chunk));
        });
    };

    if (!params.build_regions) {
        // Totals only: area and first moments per (chunk, plane) straight from the crossings
        // (Green's theorem about a fixed point near the part), no segments stored, no chaining.
        const Eigen::Vector2d ref = nv > 0 ? uv.front() : Eigen::Vector2d::Zero();
        std::vector<Eigen::Vector3d> acc(nchunks * np, Eigen::Vector3d::Zero());
        for_chunks([&](std::size_t c, std::size_t begin, std::size_t end) {
            Eigen::Vector3d* row = acc.data() + c * np;
            for (std::size_t i = begin; i < end; ++i) {
                const Eigen::Vector3i& t = mesh.triangles[i];
                std::size_t first, last;
                plane_range(t, first, last);
                for (std::size_t k = first; k < last; ++k) {
                    const Crossing x = cross_facet(t, offsets[k], h);
                    const Eigen::Vector2d a = crossing(x.down_a, x.down_b, offsets[k], h, uv) - ref;
                    const Eigen::Vector2d b = crossing(x.up_a, x.up_b, offsets[k], h, uv) - ref;
                    const double cr = a.x() * b.y() - b.x() * a.y();
                    row[k] += Eigen::Vector3d(cr, (a.x() + b.x()) * cr, (a.y() + b.y()) * cr);
                }
            }
        });
        check_cancel();
        tbb::parallel_for(tbb::blocked_range<std::size_t>(0, np, 64), [&](const auto& r) {
            for (std::size_t k = r.begin(); k != r.end(); ++k) {
                Eigen::Vector3d sum = Eigen::Vector3d::Zero();
                for (std::size_t c = 0; c < nchunks; ++c) sum += acc[c * np + k];
                Section& s = out[which[k]];
                s.area = 0.5 * sum.x();
                s.centroid = sum.x() != 0.0
                                 ? frame.to_3d(ref + sum.tail<2>() / (3.0 * sum.x()), s.plane)
                                 : s.plane.origin;
            }
        });
        return;
    }

    // Regions: planes go in batches of kBatch, each batch on its own thread with reusable
    // buffers, so memory stays bounded and is touched once (allocating and first touching all
    // segments at once, 64 MB for 1000 planes through 1M facets, cost more than the cutting).
    // A batch's facets come from buckets by the first plane each facet reaches, plus the few
    // facets spanning more than kBatch planes, which every batch checks. (SectionGrid::cut
    // reproduces the order of a single batch's segments: keep the two in step.)
    std::vector<std::uint32_t> first_plane(nt), last_plane(nt);
    for_chunks([&](std::size_t, std::size_t begin, std::size_t end) {
        for (std::size_t i = begin; i < end; ++i) {
            std::size_t first, last;
            plane_range(mesh.triangles[i], first, last);
            first_plane[i] = std::uint32_t(first);
            last_plane[i] = std::uint32_t(last);
        }
    });
    check_cancel();
    std::vector<std::size_t> bucket_start(np + 2, 0);
    std::vector<std::uint32_t> long_facets;
    for (std::size_t i = 0; i < nt; ++i) {
        if (first_plane[i] >= last_plane[i]) continue;
        if (last_plane[i] - first_plane[i] > kBatch)
            long_facets.push_back(std::uint32_t(i));
        else
            ++bucket_start[first_plane[i] + 2];
    }
    for (std::size_t k = 2; k < bucket_start.size(); ++k) bucket_start[k] += bucket_start[k - 1];
    std::vector<std::uint32_t> bucket(bucket_start.back());
    for (std::size_t i = 0; i < nt; ++i)
        if (first_plane[i] < last_plane[i] && last_plane[i] - first_plane[i] <= kBatch)
            bucket[bucket_start[first_plane[i] + 1]++] = std::uint32_t(i);
    // bucket_start[k] .. bucket_start[k + 1] now hold the facets whose first plane is k.

    struct Buffers {
        std::vector<std::vector<Segment>> per_plane = std::vector<std::vector<Segment>>(kBatch);
    };
    tbb::enumerable_thread_specific<Buffers> buffers;
    const std::size_t nbatches = (np + kBatch - 1) / kBatch;
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, nbatches, 1), [&](const auto& r) {
        Buffers& buf = buffers.local();
        for (std::size_t batch = r.begin(); batch != r.end(); ++batch) {
            const std::size_t k0 = batch * kBatch, k1 = std::min(np, k0 + kBatch);
            for (auto& v : buf.per_plane) v.clear();
            auto cut = [&](std::uint32_t i) {
                const Eigen::Vector3i& t = mesh.triangles[i];
                const std::size_t from = std::max<std::size_t>(first_plane[i], k0);
                const std::size_t to = std::min<std::size_t>(last_plane[i], k1);
                for (std::size_t k = from; k < to; ++k) {
                    const Crossing x = cross_facet(t, offsets[k], h);
                    buf.per_plane[k - k0].push_back(
                        Segment{edge_key(x.down_a, x.down_b), edge_key(x.up_a, x.up_b),
                                crossing(x.down_a, x.down_b, offsets[k], h, uv)});
                }
            };
            // Short facets reaching this batch start at most kBatch planes before it.
            const std::size_t lo = k0 > kBatch ? k0 - kBatch : 0;
            for (std::size_t j = bucket_start[lo]; j < bucket_start[k1]; ++j)
                if (last_plane[bucket[j]] > k0) cut(bucket[j]);
            for (std::uint32_t i : long_facets)
                if (first_plane[i] < k1 && last_plane[i] > k0) cut(i);
            for (std::size_t k = k0; k < k1; ++k) {
                const auto& v = buf.per_plane[k - k0];
                build_regions(v.data(), v.size(), params, out[which[k]]);
            }
            if (batch % 4 == 0) check_cancel();
        }
    });
}

// The planes with their normals made unit (make_plane), and their indices grouped by normal:
// planes whose normals, once normalised, are equal (to 1e-12) are cut as one grid. Each group lists
// its planes in their given order.
std::vector<Plane> unit_planes(const std::vector<Plane>& planes) {
    std::vector<Plane> out(planes.size());
    for (std::size_t i = 0; i < planes.size(); ++i)
        out[i] = make_plane(planes[i].origin, planes[i].normal);
    return out;
}

std::vector<std::vector<std::size_t>> group_by_normal(const std::vector<Plane>& unit) {
    std::vector<std::vector<std::size_t>> groups;
    std::vector<char> done(unit.size(), 0);
    for (std::size_t i = 0; i < unit.size(); ++i) {
        if (done[i]) continue;
        std::vector<std::size_t>& which = groups.emplace_back();
        for (std::size_t j = i; j < unit.size(); ++j)
            if (!done[j] && (unit[j].normal - unit[i].normal).squaredNorm() < 1e-24) {
                which.push_back(j);
                done[j] = 1;
            }
    }
    return groups;
}

}  // namespace

std::vector<Section> slice_mesh(const TriangleMesh& mesh, const std::vector<Plane>& planes,
                                const SliceParams& params,
                                const std::function<void()>& throw_on_cancel) {
    if (mesh.vertices.size() >= (std::size_t(1) << 32))
        throw Error(ErrorCode::InvalidArgument,
                    "meshes with 2^32 vertices or more are not supported");
    std::vector<Section> out(planes.size());
    // Cancellation is checked on the calling thread only (callers may hold a Python lock).
    const auto caller = std::this_thread::get_id();
    const std::function<void()> check_cancel = [&] {
        if (throw_on_cancel && std::this_thread::get_id() == caller) throw_on_cancel();
    };

    const std::vector<Plane> checked = unit_planes(planes);
    for (std::size_t i = 0; i < planes.size(); ++i) {
        out[i].plane = checked[i];
        out[i].centroid = checked[i].origin;
    }
    for (const std::vector<std::size_t>& which : group_by_normal(checked)) {
        const Eigen::Vector3d n = checked[which.front()].normal;
        std::vector<double> offsets(which.size());
        for (std::size_t k = 0; k < which.size(); ++k) offsets[k] = n.dot(checked[which[k]].origin);
        std::vector<std::size_t> order(which.size());
        std::iota(order.begin(), order.end(), 0);
        std::stable_sort(order.begin(), order.end(),
                         [&](std::size_t a, std::size_t b) { return offsets[a] < offsets[b]; });
        std::vector<double> sorted_offsets(which.size());
        std::vector<std::size_t> sorted_which(which.size());
        for (std::size_t k = 0; k < order.size(); ++k) {
            sorted_offsets[k] = offsets[order[k]];
            sorted_which[k] = which[order[k]];
        }
        // Several planes at the same height each get their own (identical) section: dedupe by
        // slicing the distinct heights and copying.
        std::vector<double> unique_offsets;
        std::vector<std::size_t> unique_which;
        std::vector<std::pair<std::size_t, std::size_t>> copies;  // (to, from)
        for (std::size_t k = 0; k < sorted_offsets.size(); ++k) {
            if (!unique_offsets.empty() && sorted_offsets[k] == unique_offsets.back()) {
                copies.emplace_back(sorted_which[k], unique_which.back());
                continue;
            }
            unique_offsets.push_back(sorted_offsets[k]);
            unique_which.push_back(sorted_which[k]);
        }
        slice_group(mesh, n, unique_offsets, unique_which, params, check_cancel, out);
        for (const auto& [to, from] : copies) {
            const Plane p = out[to].plane;
            out[to] = out[from];
            out[to].plane = p;
        }
    }
    return out;
}

Section slice_mesh(const TriangleMesh& mesh, const Plane& plane, const SliceParams& params) {
    return slice_mesh(mesh, std::vector<Plane>{plane}, params).front();
}

std::vector<std::size_t> section_point_counts(const TriangleMesh& mesh,
                                              const std::vector<Plane>& planes) {
    // A facet crosses the plane at height d when min h < d <= max h (a vertex on the plane counts
    // as above it): the sorted planes upper_bound(min h) .. upper_bound(max h) - 1. Each facet
    // adds one to that range of a difference array.
    const std::vector<Plane> checked = unit_planes(planes);
    std::vector<std::size_t> counts(planes.size(), 0);
    for (const std::vector<std::size_t>& which : group_by_normal(checked)) {  // as slice_mesh
        const Eigen::Vector3d n = checked[which.front()].normal;
        std::vector<std::pair<double, std::size_t>> sorted;  // (height, plane)
        for (const std::size_t j : which) sorted.emplace_back(n.dot(checked[j].origin), j);
        std::sort(sorted.begin(), sorted.end());
        std::vector<double> heights(sorted.size());
        for (std::size_t k = 0; k < sorted.size(); ++k) heights[k] = sorted[k].first;
        std::vector<std::size_t> rank(mesh.vertices.size());  // planes at or below the vertex
        for (std::size_t v = 0; v < mesh.vertices.size(); ++v)
            rank[v] = std::size_t(
                std::upper_bound(heights.begin(), heights.end(), n.dot(mesh.vertices[v])) -
                heights.begin());
        std::vector<std::ptrdiff_t> diff(sorted.size() + 1, 0);
        for (const Eigen::Vector3i& t : mesh.triangles) {
            const std::size_t a = rank[std::size_t(t[0])], b = rank[std::size_t(t[1])],
                              c = rank[std::size_t(t[2])];
            ++diff[std::min({a, b, c})];
            --diff[std::max({a, b, c})];
        }
        std::ptrdiff_t running = 0;
        for (std::size_t k = 0; k < sorted.size(); ++k) {
            running += diff[k];
            counts[sorted[k].second] = std::size_t(running);
        }
    }
    return counts;
}

std::vector<Plane> parallel_planes(const TriangleMesh& mesh, const Eigen::Vector3d& normal,
                                   double step_mm) {
    if (!std::isfinite(step_mm) || !(step_mm > 0.0))
        throw Error(
            ErrorCode::InvalidArgument,
            "step must be a positive number of millimetres (got " + format_number(step_mm) + ")");
    const Plane unit = make_plane(Eigen::Vector3d::Zero(), normal);
    if (mesh.vertices.empty()) throw Error(ErrorCode::EmptyInput, "the mesh has no vertices");
    double lo = std::numeric_limits<double>::infinity(), hi = -lo;
    for (const auto& v : mesh.vertices) {
        const double h = unit.normal.dot(v);
        lo = std::min(lo, h);
        hi = std::max(hi, h);
    }
    const double extent = hi - lo;
    const double count = std::ceil(extent / step_mm - 1e-9);
    if (count > double(kMaxParallelPlanes)) {
        std::ostringstream msg;
        msg << "step " << step_mm << " mm is too small: it would cut the part's " << extent
            << " mm extent with " << count << " planes, more than " << kMaxParallelPlanes;
        throw Error(ErrorCode::InvalidArgument, msg.str());
    }
    std::vector<Plane> planes;
    const auto n = static_cast<std::size_t>(std::max(1.0, count));
    planes.reserve(n);
    for (std::size_t i = 0; i < n; ++i) {
        const double top = std::min(hi, lo + (double(i) + 1.0) * step_mm);
        const double mid = 0.5 * (lo + double(i) * step_mm + top);
        planes.push_back(Plane{unit.normal * mid, unit.normal});
    }
    return planes;
}

SectionGrid::SectionGrid(const TriangleMesh& mesh, std::vector<Plane> planes,
                         const SliceParams& params)
    : mesh_(mesh), params_(params), planes_(std::move(planes)) {
    if (mesh.vertices.size() >= (std::size_t(1) << 32) ||
        mesh.triangles.size() >= (std::size_t(1) << 32))
        throw Error(ErrorCode::InvalidArgument,
                    "meshes with 2^32 vertices or facets or more are not supported");
    if (planes_.empty()) return;
    for (auto& p : planes_) p = make_plane(p.origin, p.normal);
    const Eigen::Vector3d n = planes_.front().normal;
    height_of_.reserve(planes_.size());
    for (const auto& p : planes_) {
        // Exactly one normal: slice_mesh measures every offset along its group's first normal.
        if (p.normal != n)
            throw Error(ErrorCode::InvalidArgument, "section grid: planes must share one normal");
        const double d = n.dot(p.origin);
        if (!heights_.empty() && d < heights_.back())
            throw Error(ErrorCode::InvalidArgument, "section grid: planes must be in order");
        if (heights_.empty() || d != heights_.back()) heights_.push_back(d);
        height_of_.push_back(std::uint32_t(heights_.size() - 1));
    }
    project(mesh, n, h_, uv_);
    // slice_mesh's plane range of a facet, upper_bound(min h) to upper_bound(max h), from its
    // vertices' (upper_bound is monotonic): one search per vertex instead of two per facet.
    std::vector<std::uint32_t> above(h_.size());
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, h_.size(), kChunk), [&](const auto& r) {
        for (std::size_t i = r.begin(); i != r.end(); ++i) above[i] = upper_bound(h_[i]);
    });
    const std::size_t nt = mesh.triangles.size();
    first_.resize(nt);
    last_.resize(nt);
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, nt, kChunk), [&](const auto& r) {
        for (std::size_t i = r.begin(); i != r.end(); ++i) {
            const Eigen::Vector3i& t = mesh.triangles[i];
            const std::uint32_t a = above[std::size_t(t[0])], b = above[std::size_t(t[1])],
                                c = above[std::size_t(t[2])];
            first_[i] = std::min({a, b, c});
            last_[i] = std::max({a, b, c});
        }
    });
    bucket_start_.assign(heights_.size() + 2, 0);
    for (std::size_t i = 0; i < nt; ++i)
        if (first_[i] < last_[i]) ++bucket_start_[first_[i] + 2];
    for (std::size_t k = 2; k < bucket_start_.size(); ++k) bucket_start_[k] += bucket_start_[k - 1];
    bucket_.resize(bucket_start_.back());
    for (std::size_t i = 0; i < nt; ++i)
        if (first_[i] < last_[i]) bucket_[bucket_start_[first_[i] + 1]++] = std::uint32_t(i);
    bucket_start_.pop_back();
    for (std::size_t i = 0; i < nt; ++i)
        if (last_[i] - first_[i] > kShort) long_.push_back(std::uint32_t(i));
}

std::uint32_t SectionGrid::upper_bound(double x) const {
    // std::upper_bound over heights_, started from a guess: grids are close to uniform, so the
    // guess is off by a step or two, and a binary search's unpredictable branches cost more
    // than the rest of the preparation.
    const std::size_t n = heights_.size();
    const double span = heights_.back() - heights_.front();
    std::size_t k = 0;
    if (n > 1 && span > 0.0) {
        const double guess = (x - heights_.front()) / span * double(n - 1);
        if (guess > 0.0) k = guess < double(n) ? std::size_t(guess) : n;  // NaN: 0
    }
    // The first height h with x < h, with std::upper_bound's comparison.
    while (k < n && !(x < heights_[k])) ++k;
    while (k > 0 && x < heights_[k - 1]) --k;
    return std::uint32_t(k);
}

Section SectionGrid::cut_at(double offset) const {
    Section s;
    if (planes_.empty()) return s;
    const Eigen::Vector3d n = planes_.front().normal;
    s.plane = make_plane(n * offset, n);
    s.centroid = s.plane.origin;
    // A facet crosses the plane when some vertex lies below it and some at or above (slice_mesh's
    // convention): then its plane range [first_, last_] holds upper_bound(offset).
    const std::uint32_t j = upper_bound(offset);
    std::vector<Segment> segs;
    for (std::size_t i = 0; i < first_.size(); ++i) {
        if (first_[i] > j || last_[i] < j) continue;
        const Eigen::Vector3i& t = mesh_.triangles[i];
        const double a = h_[std::size_t(t[0])], b = h_[std::size_t(t[1])],
                     c = h_[std::size_t(t[2])];
        if (!(std::min({a, b, c}) < offset && std::max({a, b, c}) >= offset)) continue;
        const Crossing x = cross_facet(t, offset, h_);
        segs.push_back(Segment{edge_key(x.down_a, x.down_b), edge_key(x.up_a, x.up_b),
                               crossing(x.down_a, x.down_b, offset, h_, uv_)});
    }
    build_regions(segs.data(), segs.size(), params_, s);
    return s;
}

std::vector<Section> SectionGrid::cut(
    std::size_t first, std::size_t last,
    const std::function<void(std::size_t, Section&)>& each) const {
    if (first > last || last > planes_.size())
        throw Error(ErrorCode::InvalidArgument, "section grid: plane range out of bounds");
    std::vector<Section> out;
    if (first == last) return out;
    const std::size_t u0 = height_of_[first], u1 = std::size_t(height_of_[last - 1]) + 1;
    if (u1 - u0 > kBatch || !params_.build_regions) {
        // Beyond one batch slice_mesh orders segments differently: let it do the work.
        out = slice_mesh(mesh_,
                         std::vector<Plane>(planes_.begin() + std::ptrdiff_t(first),
                                            planes_.begin() + std::ptrdiff_t(last)),
                         params_);
    } else {
        // slice_mesh cuts these planes in one batch whose facets come ordered by the first of
        // its planes they cross, then by index: first every facet already crossing height u0
        // (by index), then those starting at u0 + 1, u0 + 2, ... (bucket_ order). Chains start
        // at the first segment, so the same order gives the same loops.
        std::vector<std::uint32_t> facets;
        const std::size_t from = u0 > kShort ? u0 - kShort : 0;
        for (std::size_t j = bucket_start_[from]; j < bucket_start_[u0 + 1]; ++j) {
            const std::uint32_t i = bucket_[j];
            if (last_[i] > u0 && last_[i] - first_[i] <= kShort) facets.push_back(i);
        }
        for (std::uint32_t i : long_)
            if (first_[i] <= u0 && last_[i] > u0) facets.push_back(i);
        std::sort(facets.begin(), facets.end());
        facets.insert(facets.end(), bucket_.begin() + std::ptrdiff_t(bucket_start_[u0 + 1]),
                      bucket_.begin() + std::ptrdiff_t(bucket_start_[u1]));
        // Dealt to the heights each crosses, keeping that order.
        std::vector<std::vector<std::uint32_t>> per_height(u1 - u0);
        for (std::uint32_t i : facets)
            for (std::size_t u = std::max<std::size_t>(first_[i], u0),
                             end = std::min<std::size_t>(last_[i], u1);
                 u < end; ++u)
                per_height[u - u0].push_back(i);

        out.resize(last - first);
        // Each distinct height is cut into the section of its first plane in the range.
        std::vector<std::size_t> which(u1 - u0);
        for (std::size_t k = last; k-- > first;) which[height_of_[k] - u0] = k - first;
        tbb::parallel_for(tbb::blocked_range<std::size_t>(u0, u1, 1), [&](const auto& r) {
            std::vector<Segment> segs;
            for (std::size_t u = r.begin(); u != r.end(); ++u) {
                const double d = heights_[u];
                segs.clear();
                for (std::uint32_t i : per_height[u - u0]) {
                    const Crossing x = cross_facet(mesh_.triangles[i], d, h_);
                    segs.push_back(Segment{edge_key(x.down_a, x.down_b), edge_key(x.up_a, x.up_b),
                                           crossing(x.down_a, x.down_b, d, h_, uv_)});
                }
                Section& s = out[which[u - u0]];
                s.plane = planes_[first + which[u - u0]];
                s.centroid = s.plane.origin;
                build_regions(segs.data(), segs.size(), params_, s);
            }
        });
        // Planes at a height already cut get a copy, with their own plane.
        for (std::size_t k = first; k < last; ++k) {
            const std::size_t from_k = which[height_of_[k] - u0];
            if (from_k == k - first) continue;
            out[k - first] = out[from_k];
            out[k - first].plane = planes_[k];
        }
    }
    if (each)
        tbb::parallel_for(tbb::blocked_range<std::size_t>(0, out.size(), 1), [&](const auto& r) {
            for (std::size_t k = r.begin(); k != r.end(); ++k) each(first + k, out[k]);
        });
    return out;
}

}  // namespace mas
