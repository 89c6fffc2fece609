// The cross-section kernel. For each group of planes sharing a normal:
//   1. project every vertex on the normal once (h = n.v);
//   2. each facet finds the planes its [hmin, hmax) spans by binary search over the sorted plane
//      offsets and emits one segment per plane (PrusaSlicer's slice_mesh; Minetto et al. 2017);
//      facets are processed in fixed chunks, counted first and then written into one array, so
//      the work is parallel, needs no locks and the result does not depend on thread timing;
//   3. per plane, segments are chained into loops through the mesh edges they cross (topological
//      keys, never by comparing coordinates), and loops are grouped into regions with holes.
// Degenerate case: a vertex exactly on a plane counts as above it (symbolic perturbation), so
// every crossed facet has exactly one edge going down and one going up through the plane, chains
// close on a closed mesh, and a facet lying in a plane is never cut: a horizontal face at exactly
// the height of a plane belongs to the slab below it.
#include "mas/Section.hpp"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <numeric>
#include <thread>

#include "mas/Error.hpp"

namespace mas {

Plane make_plane(const Eigen::Vector3d& origin, const Eigen::Vector3d& normal) {
    if (!origin.allFinite())
        throw Error(ErrorCode::InvalidArgument, "plane origin has NaN or infinite coordinates");
    if (!normal.allFinite())
        throw Error(ErrorCode::InvalidArgument, "plane normal has NaN or infinite coordinates");
    const double len = normal.norm();
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

// A segment of a section: it enters the facet through mesh edge `from` and leaves through `to`,
// running counter-clockwise (material on its left) seen from above the plane.
struct Segment {
    std::uint64_t from, to;
};

// Where the plane at height d crosses the edge (a, b) of the mesh, in 2-D. Computed from the edge's
// endpoints in a fixed order, so both facets sharing the edge produce the same point.
Eigen::Vector2d crossing(std::uint64_t key, double d, const std::vector<double>& h,
                         const std::vector<Eigen::Vector2d>& uv) {
    const auto a = static_cast<std::size_t>(key >> 32);
    const auto b = static_cast<std::size_t>(key & 0xffffffffu);
    const double t = (d - h[a]) / (h[b] - h[a]);
    return uv[a] + t * (uv[b] - uv[a]);
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
void build_regions(const Segment* segs, std::size_t n, double d, const std::vector<double>& h,
                   const std::vector<Eigen::Vector2d>& uv, const SliceParams& params,
                   Section& out) {
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
            const Eigen::Vector2d p = crossing(segs[cur].from, d, h, uv);
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
    double total = 0.0;
    Eigen::Vector3d moment = Eigen::Vector3d::Zero();
    out.regions.reserve(regions.size());
    for (auto& r : regions) {
        SectionRegion sr;
        sr.area = area(r);
        sr.centroid = frame.to_3d(centroid(r), out.plane);
        for (const auto& q : r.outer.points) sr.bounds.extend(frame.to_3d(q, out.plane));
        sr.shape = std::move(r);
        total += sr.area;
        moment += sr.area * sr.centroid;
        out.regions.push_back(std::move(sr));
    }
    std::stable_sort(
        out.regions.begin(), out.regions.end(),
        [](const SectionRegion& a, const SectionRegion& b) { return a.area > b.area; });
    out.area = total;
    out.centroid = total > 0.0 ? Eigen::Vector3d(moment / total) : out.plane.origin;
}

// Area and centroid of one plane straight from its segments (Green's theorem), no chaining.
void totals_from_segments(const Segment* segs, std::size_t n, double d,
                          const std::vector<double>& h, const std::vector<Eigen::Vector2d>& uv,
                          Section& out) {
    if (n == 0) {
        out.centroid = out.plane.origin;
        return;
    }
    const Eigen::Vector2d ref = crossing(segs[0].from, d, h, uv);
    double area2 = 0.0;
    Eigen::Vector2d m = Eigen::Vector2d::Zero();
    for (std::size_t i = 0; i < n; ++i) {
        const Eigen::Vector2d a = crossing(segs[i].from, d, h, uv) - ref;
        const Eigen::Vector2d b = crossing(segs[i].to, d, h, uv) - ref;
        const double c = a.x() * b.y() - b.x() * a.y();
        area2 += c;
        m += (a + b) * c;
    }
    out.area = 0.5 * area2;
    const PlaneFrame frame(out.plane.normal);
    out.centroid =
        area2 != 0.0 ? frame.to_3d(ref + m / (3.0 * area2), out.plane) : out.plane.origin;
}

// Slices the mesh by planes that all share `normal`; `offsets[k]` is n.origin of plane
// `which[k]`, sorted ascending.
void slice_group(const TriangleMesh& mesh, const Eigen::Vector3d& normal,
                 const std::vector<double>& offsets, const std::vector<std::size_t>& which,
                 const SliceParams& params, const std::function<void()>& check_cancel,
                 std::vector<Section>& out) {
    const PlaneFrame frame(normal);
    const std::size_t nv = mesh.vertices.size();
    std::vector<double> h(nv);
    std::vector<Eigen::Vector2d> uv(nv);
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, nv, kChunk), [&](const auto& r) {
        for (std::size_t i = r.begin(); i != r.end(); ++i) {
            h[i] = normal.dot(mesh.vertices[i]);
            uv[i] = frame.to_2d(mesh.vertices[i]);
        }
    });

    const std::size_t nt = mesh.triangles.size();
    const std::size_t np = offsets.size();
    // Chunks of facets; fewer, larger ones when there are very many planes, so that the
    // (chunk, plane) count table stays under ~16 M entries.
    const std::size_t chunk = std::max<std::size_t>(
        kChunk, std::size_t(double(nt) * double(std::max<std::size_t>(np, 1)) / 16e6) + 1);
    const std::size_t nchunks = (nt + chunk - 1) / chunk;
    // Planes at heights d with hmin < d <= hmax cut the facet (a vertex on a plane is above it).
    auto plane_range = [&](const Eigen::Vector3i& t, std::size_t& first, std::size_t& last) {
        const double a = h[t[0]], b = h[t[1]], c = h[t[2]];
        const double lo = std::min({a, b, c}), hi = std::max({a, b, c});
        first = std::size_t(std::upper_bound(offsets.begin(), offsets.end(), lo) - offsets.begin());
        last = std::size_t(std::upper_bound(offsets.begin(), offsets.end(), hi) - offsets.begin());
    };

    // Pass 1: how many segments each chunk gives each plane.
    std::vector<std::uint32_t> counts(nchunks * np, 0);
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, nchunks, 1), [&](const auto& r) {
        for (std::size_t c = r.begin(); c != r.end(); ++c) {
            std::uint32_t* row = counts.data() + c * np;
            const std::size_t end = std::min(nt, (c + 1) * chunk);
            for (std::size_t i = c * chunk; i < end; ++i) {
                std::size_t first, last;
                plane_range(mesh.triangles[i], first, last);
                for (std::size_t k = first; k < last; ++k) ++row[k];
            }
        }
    });
    check_cancel();
    // Where each (plane, chunk) block starts: planes outermost, chunks in order inside.
    std::vector<std::size_t> plane_begin(np + 1, 0);
    std::vector<std::size_t> cursor(nchunks * np);
    std::size_t total = 0;
    for (std::size_t k = 0; k < np; ++k) {
        plane_begin[k] = total;
        for (std::size_t c = 0; c < nchunks; ++c) {
            cursor[c * np + k] = total;
            total += counts[c * np + k];
        }
    }
    plane_begin[np] = total;
    counts.clear();
    counts.shrink_to_fit();

    // Pass 2: write the segments.
    std::vector<Segment> segs(total);
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, nchunks, 1), [&](const auto& r) {
        for (std::size_t c = r.begin(); c != r.end(); ++c) {
            std::size_t* cur = cursor.data() + c * np;
            const std::size_t end = std::min(nt, (c + 1) * chunk);
            for (std::size_t i = c * chunk; i < end; ++i) {
                const Eigen::Vector3i& t = mesh.triangles[i];
                std::size_t first, last;
                plane_range(t, first, last);
                for (std::size_t k = first; k < last; ++k) {
                    const double d = offsets[k];
                    // Walking the facet's edges in order (CCW from outside), one goes from above
                    // to below the plane ("down") and one from below to above ("up"). With an
                    // outward facet normal nt, n x nt points along the CCW section boundary,
                    // which runs from the down edge's crossing to the up edge's.
                    std::uint64_t down = 0, up = 0;
                    for (int e = 0; e < 3; ++e) {
                        const int a = t[e], b = t[(e + 1) % 3];
                        const bool a_below = h[a] < d, b_below = h[b] < d;
                        if (a_below == b_below) continue;
                        if (b_below)
                            down = edge_key(a, b);
                        else
                            up = edge_key(a, b);
                    }
                    segs[cur[k]++] = Segment{down, up};
                }
            }
        }
    });
    check_cancel();

    // Pass 3: per plane, loops and regions (or totals only).
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, np, 1), [&](const auto& r) {
        for (std::size_t k = r.begin(); k != r.end(); ++k) {
            Section& s = out[which[k]];
            const Segment* first = segs.data() + plane_begin[k];
            const std::size_t n = plane_begin[k + 1] - plane_begin[k];
            if (params.build_regions)
                build_regions(first, n, offsets[k], h, uv, params, s);
            else
                totals_from_segments(first, n, offsets[k], h, uv, s);
            if (k % 64 == 0) check_cancel();
        }
    });
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

    // Group planes by (exactly equal, once normalised) normal.
    std::vector<Plane> checked(planes.size());
    for (std::size_t i = 0; i < planes.size(); ++i) {
        checked[i] = make_plane(planes[i].origin, planes[i].normal);
        out[i].plane = checked[i];
        out[i].centroid = checked[i].origin;
    }
    std::vector<char> done(planes.size(), 0);
    for (std::size_t i = 0; i < planes.size(); ++i) {
        if (done[i]) continue;
        const Eigen::Vector3d n = checked[i].normal;
        std::vector<std::size_t> which;
        for (std::size_t j = i; j < planes.size(); ++j)
            if (!done[j] && (checked[j].normal - n).squaredNorm() < 1e-24) {
                which.push_back(j);
                done[j] = 1;
            }
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

std::vector<Plane> parallel_planes(const TriangleMesh& mesh, const Eigen::Vector3d& normal,
                                   double step_mm) {
    if (!std::isfinite(step_mm) || !(step_mm > 0.0))
        throw Error(
            ErrorCode::InvalidArgument,
            "step must be a positive number of millimetres (got " + std::to_string(step_mm) + ")");
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
    if (count > 1e7)
        throw Error(ErrorCode::InvalidArgument, "step " + std::to_string(step_mm) +
                                                    " mm would give more than 10 million planes");
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

}  // namespace mas
