// The build sequence against the nozzle (see Nozzle.hpp).
#include "mas/Nozzle.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <memory>
#include <optional>
#include <string>
#include <unordered_map>

#include "mas/Angles.hpp"
#include "mas/Error.hpp"
#include "mas/Polygon2.hpp"

namespace mas {
namespace {

using Eigen::Vector2d;
using Eigen::Vector3d;

// The travel check's step along a move where it measures a near sample's clearance, in margins.
constexpr double kTravelStep = 0.05;
// The travel check's finer samples, where a sample counts: every margin / kFineSamples.
constexpr double kFineSamples = 8.0;

// The nozzle's shape in numbers, worked out once.
struct Shape {
    double standoff, tip, body;  // heights from the deposit point; radii
    double tan = 0.0;            // of the cone's half-angle (0: no cone)
    double cone_end, top;        // heights where the cone meets the body, and the body ends
    double grow;                 // 2 x margin: the samples' spacing plus the margin kept
    double grow_radially;        // grow / cos(cone angle): see grown()

    explicit Shape(const NozzleParams& p) : Shape(p, 2.0 * p.margin_mm) {}
    Shape(const NozzleParams& p, double growth)
        : standoff(p.standoff_mm),
          tip(0.5 * p.tip_diameter_mm),
          body(0.5 * p.body_diameter_mm),
          grow(growth) {
        const double cone = cone_length(p);
        if (cone > 0.0) tan = std::tan(p.cone_angle_deg * kPi / 180.0);
        cone_end = standoff + cone;
        top = cone_end + p.body_length_mm;
        grow_radially = grow * std::sqrt(1.0 + tan * tan);
    }
    // The radius at height h along the axis, h within the nozzle.
    double radius(double h) const {
        return std::min(body, tip + std::max(0.0, h - standoff) * tan);
    }
    // The radius of the nozzle grown by `grow` at height h: every point within `grow` of the
    // nozzle lies within it. (Off the cone's side by d, a point is d / cos further out and no
    // lower than d below; past the ends, d up or down and d out.) Negative outside its heights.
    // (Never past body + grow: the whole nozzle lies within the body's radius.)
    double grown(double h) const {
        if (h < standoff - grow || h > top + grow) return -1.0;
        return std::min(radius(std::clamp(h, standoff, top)) + grow_radially, body + grow);
    }
    // The signed distance of a point `rho` off the axis at height h from the nozzle's surface:
    // negative inside (how deep), positive outside.
    double clearance(double rho, double h) const {
        auto to_edge = [&](double r0, double h0, double r1, double h1) {
            const Eigen::Vector2d a(r0, h0), d(r1 - r0, h1 - h0), p(rho, h);
            const double t =
                std::clamp((p - a).dot(d) / std::max(d.squaredNorm(), 1e-300), 0.0, 1.0);
            return (a + t * d - p).norm();
        };
        // Its outline seen across the axis: the tip's face, the cone, the body's side, its end.
        const double edge =
            std::min({to_edge(0.0, standoff, tip, standoff), to_edge(tip, standoff, body, cone_end),
                      to_edge(body, cone_end, body, top), to_edge(body, top, 0.0, top)});
        const bool inside = h >= standoff && h <= top && rho <= radius(h);
        return inside ? -edge : edge;
    }
    // clearance() of point `p` from the nozzle with its tip at `tip` along the unit `axis`.
    double clearance(const Vector3d& p, const Vector3d& tip, const Vector3d& axis) const {
        const Vector3d d = p - tip;
        const double h = axis.dot(d);
        return clearance((d - h * axis).norm(), h);
    }
};

// Points every point of a layer's prism lies within `spacing` of (see Nozzle.hpp).
std::vector<Vector3d> prism_samples(const Layer& layer, double spacing) {
    std::vector<Vector3d> out;
    const Vector3d n = layer.plane.normal;
    const PlaneFrame top_frame(n), bottom_frame(layer.lower.normal);
    const double cos_tilt = std::max(0.05, std::abs(n.dot(layer.lower.normal)));
    const double along = spacing * cos_tilt;  // an edge's image on the lower plane is longer
    // The thickness is affine over the plane: greatest at a corner of the region.
    double deepest = layer.max_thickness_mm;
    for (const Region2& region : layer.regions)
        for (const Eigen::Vector2d& q : region.outer.points)
            deepest = std::max(deepest, layer.thickness_at(top_frame.to_3d(q, layer.plane)));
    const int levels = std::max(1, int(std::ceil(deepest / spacing)));
    auto down = [&](const Vector3d& top, double fraction) {
        return Vector3d(top - fraction * layer.thickness_at(top) * n);
    };
    // A face on the grid of rows `spacing` apart, each row's runs cut `spacing` apart.
    auto grid = [&](const Region2& region, const PlaneFrame& frame, const Plane& plane) {
        const Eigen::AlignedBox2d box = bounds(region);
        if (box.isEmpty()) return;
        const int rows = int(std::ceil(box.sizes().y() / spacing));
        for (int j = 0; j <= rows; ++j) {
            const double v = std::min(box.min().y() + j * spacing, box.max().y());
            for (const auto& [a, b] : inside_intervals(region, 1, v)) {
                const int pieces = std::max(1, int(std::ceil((b - a) / spacing)));
                for (int i = 0; i <= pieces; ++i)
                    out.push_back(frame.to_3d(Vector2d(a + (b - a) * i / pieces, v), plane));
            }
        }
    };
    for (const Region2& region : layer.regions) {
        Region2 bottom;
        auto walls = [&](const Polygon2& loop, Polygon2& bottom_loop) {
            const std::size_t count = loop.points.size();
            for (std::size_t k = 0; k < count; ++k) {
                const Vector3d a = top_frame.to_3d(loop.points[k], layer.plane);
                const Vector3d b = top_frame.to_3d(loop.points[(k + 1) % count], layer.plane);
                bottom_loop.points.push_back(bottom_frame.to_2d(down(a, 1.0)));
                const int pieces = std::max(1, int(std::ceil((b - a).norm() / along)));
                for (int i = 0; i < pieces; ++i) {
                    const Vector3d q = a + (b - a) * (double(i) / pieces);
                    for (int l = 0; l <= levels; ++l) out.push_back(down(q, double(l) / levels));
                }
            }
        };
        walls(region.outer, bottom.outer);
        for (const Polygon2& hole : region.holes) {
            bottom.holes.emplace_back();
            walls(hole, bottom.holes.back());
        }
        grid(region, top_frame, layer.plane);
        grid(bottom, bottom_frame, layer.lower);
    }
    return out;
}

// A deposit move of the layer being checked, in the tool axis' frame and in 3-D, with its ends'
// heights along the axis.
struct Segment {
    Vector2d a, b;
    Vector3d a3, b3;
    double ha = 0.0, hb = 0.0;
};

// The deposit moves of one layer, binned on a grid for "any within r of q". The tool axis is the
// paths' (the layer's normal: every deposit point at the plane's height along it), or `axis`
// leaned from it, when the moves are cut into pieces whose ends' heights differ by at most `step`.
class Sweep {
public:
    Sweep(const LayerToolpaths& paths, const Layer& layer, double reach)
        : Sweep(paths, layer, reach, paths.tool_axis.normalized(),
                std::numeric_limits<double>::infinity()) {}
    Sweep(const LayerToolpaths& paths, const Layer& layer, double reach, const Vector3d& axis,
          double step)
        : Sweep(deposit_moves(paths), reach, axis, step) {
        height_ = frame_.normal.dot(layer.plane.origin);
    }
    // Any moves (pairs of ends), with tool axis `axis`, cut by `step` as above.
    Sweep(const std::vector<std::pair<Vector3d, Vector3d>>& moves, double reach,
          const Vector3d& axis, double step)
        : frame_(axis) {
        auto add = [&](const Vector3d& a3, const Vector3d& b3) {
            const double ha = frame_.normal.dot(a3), hb = frame_.normal.dot(b3);
            const int pieces = std::isfinite(step) && std::abs(hb - ha) > step
                                   ? int(std::ceil(std::abs(hb - ha) / step))
                                   : 1;
            for (int i = 0; i < pieces; ++i) {
                const Vector3d p = a3 + (b3 - a3) * (double(i) / pieces);
                const Vector3d q = i + 1 == pieces ? b3 : a3 + (b3 - a3) * (double(i + 1) / pieces);
                segments_.push_back({frame_.to_2d(p), frame_.to_2d(q), p, q, frame_.normal.dot(p),
                                     frame_.normal.dot(q)});
                lo_ = std::min({lo_, segments_.back().ha, segments_.back().hb});
                hi_ = std::max({hi_, segments_.back().ha, segments_.back().hb});
            }
            box_.extend(frame_.to_2d(a3));
            box_.extend(frame_.to_2d(b3));
            box3_.extend(a3);
            box3_.extend(b3);
        };
        for (const auto& [a3, b3] : moves) add(a3, b3);
        if (segments_.empty()) return;
        const double extent = std::max(box_.sizes().maxCoeff(), 1e-9);
        cell_ = std::max({0.5 * reach, extent / 256.0, 1e-3});
        columns_ = int(extent / cell_) + 1;
        bins_.assign(std::size_t(columns_) * std::size_t(columns_), {});
        for (std::size_t s = 0; s < segments_.size(); ++s) {
            Eigen::AlignedBox2d b;
            b.extend(segments_[s].a);
            b.extend(segments_[s].b);
            const auto [i0, j0] = cell_of(b.min());
            const auto [i1, j1] = cell_of(b.max());
            for (int i = i0; i <= i1; ++i)
                for (int j = j0; j <= j1; ++j)
                    bins_[std::size_t(i) * std::size_t(columns_) + std::size_t(j)].push_back(
                        int(s));
        }
    }

    bool empty() const { return segments_.empty(); }
    const PlaneFrame& frame() const { return frame_; }
    double height() const { return height_; }  // the plane's, along the tool axis
    double lowest() const { return lo_; }      // the deposit points' least height along it
    double highest() const { return hi_; }     // and greatest
    const Eigen::AlignedBox2d& box() const { return box_; }
    const Eigen::AlignedBox3d& box3() const { return box3_; }  // of the deposit points
    const std::vector<Segment>& segments() const { return segments_; }
    // The moves as cut, in 3-D.
    std::vector<std::pair<Vector3d, Vector3d>> moves() const {
        std::vector<std::pair<Vector3d, Vector3d>> out;
        out.reserve(segments_.size());
        for (const Segment& s : segments_) out.emplace_back(s.a3, s.b3);
        return out;
    }

    // A deposit point within `r` of `q` (2-D), in 3-D, and its distance: the first found, or
    // with `nearest` the nearest; nullopt when none is.
    struct Hit {
        Vector3d at;
        double distance;
    };
    std::optional<Hit> near(const Vector2d& q, double r, bool nearest = false) const {
        if (segments_.empty() || box_.exteriorDistance(q) > r) return std::nullopt;
        std::optional<Hit> best;
        double limit = r * r;
        visit(q, r, [&](const Segment& seg) {
            const auto [t, d2] = closest(seg, q);
            if (d2 > limit) return false;
            best = Hit{Vector3d(seg.a3 + t * (seg.b3 - seg.a3)), std::sqrt(d2)};
            limit = d2;
            return !nearest;
        });
        return best;
    }

    // Whether the nozzle grown as `shape` says, with its deposit point anywhere along the moves,
    // may hold the point at `q` (2-D) and height `h` along the axis: each piece taken at its
    // lowest point, where its grown radius is greatest (the radius never shrinks up the nozzle),
    // so that none that does is missed.
    bool may_hold(const Vector2d& q, double h, const Shape& shape) const {
        const double low = shape.standoff - shape.grow, high = shape.top + shape.grow;
        if (segments_.empty() || h - lo_ < low || h - hi_ > high) return false;
        const double r = shape.grown(std::min(h - lo_, high));
        if (box_.exteriorDistance(q) > r) return false;
        bool held = false;
        visit(q, r, [&](const Segment& seg) {
            const double above = h - std::min(seg.ha, seg.hb);
            if (above < low || h - std::max(seg.ha, seg.hb) > high) return false;
            const double reach = shape.grown(std::min(above, high));
            held = closest(seg, q).second <= reach * reach;
            return held;
        });
        return held;
    }

private:
    // The deposit moves of `paths` (a path of one point, a move to itself).
    static std::vector<std::pair<Vector3d, Vector3d>> deposit_moves(const LayerToolpaths& paths) {
        std::vector<std::pair<Vector3d, Vector3d>> out;
        for (const ToolPath& path : paths.paths) {
            if (!path.deposit() || path.points.empty()) continue;
            const std::size_t count = path.points.size();
            for (std::size_t k = 0; k + 1 < std::max<std::size_t>(count, 2); ++k)
                out.emplace_back(path.points[k], path.points[std::min(k + 1, count - 1)]);
        }
        return out;
    }
    // Calls `f` with each move binned within r of q (some farther) until it returns true.
    template <class F>
    void visit(const Vector2d& q, double r, F&& f) const {
        const auto [i0, j0] = cell_of(q - Vector2d::Constant(r));
        const auto [i1, j1] = cell_of(q + Vector2d::Constant(r));
        for (int i = i0; i <= i1; ++i)
            for (int j = j0; j <= j1; ++j)
                for (int s : bins_[std::size_t(i) * std::size_t(columns_) + std::size_t(j)])
                    if (f(segments_[std::size_t(s)])) return;
    }
    // The parameter along `seg` of its point nearest q (2-D), and that point's squared distance.
    static std::pair<double, double> closest(const Segment& seg, const Vector2d& q) {
        const Vector2d d = seg.b - seg.a;
        const double len2 = d.squaredNorm();
        const double t = len2 > 0.0 ? std::clamp((q - seg.a).dot(d) / len2, 0.0, 1.0) : 0.0;
        return {t, (seg.a + t * d - q).squaredNorm()};
    }
    std::pair<int, int> cell_of(const Vector2d& p) const {
        auto clampi = [&](double x) {
            return std::clamp(int(std::floor(x / cell_)), 0, columns_ - 1);
        };
        return {clampi(p.x() - box_.min().x()), clampi(p.y() - box_.min().y())};
    }

    PlaneFrame frame_;
    double height_ = 0.0;
    double lo_ = std::numeric_limits<double>::infinity();
    double hi_ = -std::numeric_limits<double>::infinity();
    std::vector<Segment> segments_;
    Eigen::AlignedBox2d box_;
    Eigen::AlignedBox3d box3_;
    double cell_ = 1.0;
    int columns_ = 1;
    std::vector<std::vector<int>> bins_;
};

struct Conflict {
    int x = -1, y = -1;  // y's prism (or the plate, -1) lies in x's nozzle
    Vector3d at = Vector3d::Zero(), obstacle = Vector3d::Zero();
};

// What is cheap to know of every layer: a sphere round its prism and its prism's corners.
// Each layer's samples (prism_samples, every `spacing`), made when first needed and kept while
// they fit a budget (a large part's would not all fit in memory): past it, all are dropped and
// made again as needed.
class PrismSamples {
public:
    PrismSamples(const std::vector<Layer>& layers, double spacing)
        : layers_(layers), spacing_(spacing), samples_(layers.size()) {}

    const std::vector<Vector3d>& of(std::size_t y) {
        if (!samples_[y]) {
            if (kept_ > kBudget) {
                for (auto& kept : samples_) kept.reset();
                kept_ = 0;
            }
            samples_[y] =
                std::make_unique<std::vector<Vector3d>>(prism_samples(layers_[y], spacing_));
            kept_ += samples_[y]->size();
        }
        return *samples_[y];
    }

private:
    static constexpr std::size_t kBudget = 4000000;  // samples kept at once
    const std::vector<Layer>& layers_;
    double spacing_;
    std::vector<std::unique_ptr<std::vector<Vector3d>>> samples_;
    std::size_t kept_ = 0;
};

struct LayerBounds {
    Eigen::AlignedBox3d box;
    Vector3d centre = Vector3d::Zero();
    double radius = 0.0;
    std::vector<Vector3d> corners;  // every outline point at its top and bottom
};

LayerBounds layer_bounds(const Layer& layer) {
    LayerBounds b;
    const Vector3d n = layer.plane.normal;
    Eigen::AlignedBox3d box;
    for (std::size_t r = 0; r < layer.regions.size(); ++r)
        for (const auto& loop : layer.loops_3d(r))
            for (const Vector3d& p : loop) {
                b.corners.push_back(p);
                b.corners.push_back(p - layer.thickness_at(p) * n);
                box.extend(b.corners.end()[-2]);
                box.extend(b.corners.back());
            }
    if (b.corners.empty()) return b;
    b.box = box;
    b.centre = box.center();
    for (const Vector3d& p : b.corners) b.radius = std::max(b.radius, (p - b.centre).norm());
    return b;
}

// What walk_tips' visitor returns to end the walk.
constexpr double kStopWalk = -1.0;

// Walks the tips along `moves` (one tool axis, the table still), taken every kTravelStep margins
// along each, whose nozzle `shape` may come within `below` of `q`: only the stretches of the moves
// whose tip lies within the body's radius and `below` of q across the axis (the tips of a stretch
// lie in a line, evenly spaced). `visit(tip, c, spacing, starts)` is given each with q's
// clearance c (Shape::clearance) from the nozzle there, the distance between the stretch's tips
// and whether the tip does not follow the last one visited in its stretch, and returns how far
// past it the tips of its stretch are passed over (0: none; kStopWalk ends the walk). A point's
// clearance changes no faster than the nozzle moves: where only clearances under some value
// count, none can within (c - that value) of the tip.
template <typename Visit>
void walk_tips(const Shape& shape, double margin,
               const std::vector<std::pair<Vector3d, Vector3d>>& moves, const Vector3d& axis,
               const Vector3d& q, double below, Visit&& visit) {
    const double step = kTravelStep * margin;
    const double r = shape.body + below;
    auto across = [&](const Vector3d& v) { return Vector3d(v - axis.dot(v) * axis); };
    for (const auto& [a, b] : moves) {
        // |across(a + t (b - a) - q)|^2 <= r^2: t within [t0, t1].
        const Vector3d p = across(a - q), d = across(b - a);
        const double dd = d.squaredNorm(), pd = p.dot(d), pp = p.squaredNorm() - r * r;
        double t0 = 0.0, t1 = 1.0;
        if (dd > 1e-18) {
            const double disc = pd * pd - dd * pp;
            if (disc < 0.0) continue;
            const double root = std::sqrt(disc);
            t0 = std::max(0.0, (-pd - root) / dd);
            t1 = std::min(1.0, (-pd + root) / dd);
            if (t0 > t1) continue;
        } else if (pp > 0.0) {
            continue;
        }
        const Vector3d from = a + t0 * (b - a), to = a + t1 * (b - a);
        const int pieces = std::max(1, int(std::ceil((to - from).norm() / step)));
        const double spacing = (to - from).norm() / pieces;
        bool starts = true;
        for (int i = 0; i <= pieces;) {
            const Vector3d tip = from + (to - from) * (double(i) / pieces);
            const double pass = visit(tip, shape.clearance(q, tip, axis), spacing, starts);
            if (pass < 0.0) return;
            const double skipped = spacing > 0.0 ? pass / spacing : double(pieces);  // tips
            starts = skipped >= 1.0;
            i = skipped < double(pieces - i) ? i + int(skipped) + 1 : pieces + 1;
        }
    }
}

// How near the nozzle `shape` (its real outline) along `moves` comes to a sample `q` of a prism,
// the tip taken every kTravelStep margins along each (walk_tips): within half that step of the
// least clearance over the whole moves, since the nozzle moves rigidly. Within `counts` of it the
// sample counts; within `near` (< counts), q itself, a point of the prism, is met, and `tip` is
// where the tip is then.
enum class Nearness { apart, counts, near };
Nearness how_near(const Shape& shape, double margin,
                  const std::vector<std::pair<Vector3d, Vector3d>>& moves, const Vector3d& axis,
                  const Vector3d& q, double counts, double near, Vector3d& tip) {
    Nearness out = Nearness::apart;
    walk_tips(shape, margin, moves, axis, q, counts,
              [&](const Vector3d& at, double c, double, bool) {
                  if (c < near) {
                      out = Nearness::near;
                      tip = at;
                      return kStopWalk;
                  }
                  if (c < counts) out = Nearness::counts;
                  return c - (out == Nearness::counts ? near : counts);
              });
    return out;
}

// Each layer's samples every margin / kFineSamples, binned in cubes a margin wide: made for a
// layer when one of its samples (PrismSamples, every margin) first counts, and kept while they fit
// a budget, as PrismSamples' are. Every point of a layer's surface within the margin of the nozzle
// lies within a margin of a sample, which counts (within 2 margins and the step), and within an
// eighth of a margin of a fine sample near it, which comes within a margin and an eighth (and the
// step) of the nozzle: only where such a fine sample does is a sample's count kept.
class FineSamples {
public:
    FineSamples(const std::vector<Layer>& layers, double margin)
        : layers_(layers), margin_(margin), fine_(layers.size()) {}

    // A fine sample of layer y within a margin and an eighth of `q` that the nozzle `shape` along
    // `moves` (tool axis `axis`) comes within `counts` of, and where the tip is then. `cleared`
    // marks the fine samples found clear of those moves, for the next sample of y asked with the
    // same moves and counts (empty at first): the tips walked for q take in every tip within the
    // body's radius and counts of them across the axis, the only ones that can come so near.
    // The moves are walked once, for q, keeping the tips where q comes within counts and a
    // margin and an eighth. A point's clearance changes no faster than the point moves, or the
    // nozzle: a fine sample's is at least q's less their distance apart, and along a stretch of
    // tips it cannot come under `counts` within (its clearance - counts) of a tip; only the tips
    // left are tried.
    std::optional<std::pair<Vector3d, Vector3d>> hit(
        std::size_t y, const Vector3d& q, const Shape& shape,
        const std::vector<std::pair<Vector3d, Vector3d>>& moves, const Vector3d& axis,
        double counts, std::vector<char>& cleared) {
        const double m = margin_, r = m * (1.0 + 1.0 / kFineSamples);
        struct Tip {
            Vector3d at;
            double clearance;  // q's
        };
        struct Stretch {
            std::size_t begin = 0, end = 0;
            double spacing = 0.0, least = std::numeric_limits<double>::infinity();  // q's
        };
        std::vector<Tip> tips;
        std::vector<Stretch> stretches;  // runs of tips where q's clearance is under counts + r
        const double wanted = counts + r;
        bool open = false;
        walk_tips(shape, m, moves, axis, q, wanted,
                  [&](const Vector3d& tip, double c, double spacing, bool starts) {
                      if (c >= wanted) {
                          open = false;
                          return c - wanted;
                      }
                      if (starts || !open) stretches.push_back({tips.size(), tips.size(), spacing});
                      open = true;
                      tips.push_back({tip, c});
                      stretches.back().end = tips.size();
                      stretches.back().least = std::min(stretches.back().least, c);
                      return 0.0;
                  });
        if (stretches.empty()) return std::nullopt;
        const Fine& f = of(y);
        cleared.resize(f.points.size(), 0);
        const Eigen::Array3d c = cube_of(q);
        for (int i = -2; i <= 2; ++i)
            for (int j = -2; j <= 2; ++j)
                for (int k = -2; k <= 2; ++k) {
                    const auto cell = f.cells.find(key(c + Eigen::Array3d(i, j, k)));
                    if (cell == f.cells.end()) continue;
                    for (const std::size_t s : cell->second) {
                        const Vector3d& p = f.points[s];
                        const double apart = (p - q).norm();
                        if (apart > r || cleared[s]) continue;
                        for (const Stretch& stretch : stretches) {
                            if (stretch.least - apart >= counts) continue;
                            for (std::size_t u = stretch.begin; u < stretch.end;) {
                                double least = tips[u].clearance - apart;  // p's is no less
                                if (least < counts) {
                                    least = shape.clearance(p, tips[u].at, axis);
                                    if (least < counts) return std::pair{tips[u].at, p};
                                }
                                const double clear = (least - counts) / stretch.spacing;  // tips
                                u = clear < double(stretch.end - u) ? u + std::size_t(clear) + 1
                                                                    : stretch.end;
                            }
                        }
                        cleared[s] = 1;
                    }
                }
        return std::nullopt;
    }

private:
    struct Fine {
        std::vector<Vector3d> points;
        std::unordered_map<std::int64_t, std::vector<std::size_t>> cells;
    };
    static constexpr std::size_t kBudget = 4000000;  // fine samples kept at once

    // The cube a margin wide holding q, as whole numbers, and its key in `cells`.
    Eigen::Array3d cube_of(const Vector3d& q) const { return (q / margin_).array().floor(); }
    static std::int64_t key(const Eigen::Array3d& cube) {
        const auto wrap = [](double v) { return std::int64_t(v) & 0x1FFFFF; };
        return (wrap(cube.x()) << 42) | (wrap(cube.y()) << 21) | wrap(cube.z());
    }

    const Fine& of(std::size_t y) {
        if (!fine_[y]) {
            if (kept_ > kBudget) {
                for (auto& kept : fine_) kept.reset();
                kept_ = 0;
            }
            auto f = std::make_unique<Fine>();
            f->points = prism_samples(layers_[y], margin_ / kFineSamples);
            for (std::size_t i = 0; i < f->points.size(); ++i)
                f->cells[key(cube_of(f->points[i]))].push_back(i);
            kept_ += f->points.size();
            fine_[y] = std::move(f);
        }
        return *fine_[y];
    }

    const std::vector<Layer>& layers_;
    double margin_;
    std::vector<std::unique_ptr<Fine>> fine_;
    std::size_t kept_ = 0;
};

// The box holding the nozzle anywhere along the sweep's moves, and everything within `shape.grow`
// of it: the hull of the grown nozzle's rims at its lowest height, where the cone meets the body
// and at its top holds the nozzle grown (both are convex, and at each of those heights the rims
// are the wider).
Eigen::AlignedBox3d reach_box(const Sweep& sweep, const Shape& shape) {
    const Vector3d n = sweep.frame().normal;
    const Vector3d across = (Vector3d::Ones() - n.cwiseProduct(n)).cwiseMax(0.0).cwiseSqrt();
    const double reach = shape.grown(shape.top);
    Eigen::AlignedBox3d nozzle;
    for (const auto& [h, r] :
         {std::pair{shape.standoff - shape.grow, shape.grown(shape.standoff)},
          std::pair{shape.cone_end, reach}, std::pair{shape.top + shape.grow, reach}}) {
        nozzle.extend(Vector3d(h * n - r * across));
        nozzle.extend(Vector3d(h * n + r * across));
    }
    return Eigen::AlignedBox3d(sweep.box3().min() + nozzle.min(),
                               sweep.box3().max() + nozzle.max());
}

// The nozzle's lowest point along `up` (unit) with its tool axis `n`, from its deposit point: on
// the rim of the tip's face, where the cone meets the body, or of the body's end.
Vector3d lowest_point(const Shape& shape, const Vector3d& up, const Vector3d& n) {
    const double side = std::sqrt(std::max(0.0, 1.0 - n.dot(up) * n.dot(up)));
    Vector3d sideways = up - n.dot(up) * n;  // towards up, across the axis
    sideways = sideways.norm() > 1e-12 ? sideways.normalized() : Vector3d::Zero();
    double lowest = std::numeric_limits<double>::infinity();
    Vector3d offset = Vector3d::Zero();
    for (double h : {shape.standoff, shape.cone_end, shape.top}) {
        const double r = shape.radius(h);
        const double z = h * n.dot(up) - r * side;
        if (z < lowest) {
            lowest = z;
            offset = h * n - r * sideways;
        }
    }
    return offset;
}

// The point of `plate` under `p`.
Vector3d onto_plate(const Plane& plate, const Vector3d& p) {
    const Vector3d up = plate.normal.normalized();
    return p - up.dot(p - plate.origin) * up;
}

// Where the nozzle, along the sweep's moves with its tool axis, comes within `keep` of the plate
// (exact): the move's end where it does, and the plate's point under the nozzle's lowest point.
std::optional<std::pair<Vector3d, Vector3d>> plate_hit(const Sweep& sweep, const Shape& shape,
                                                       const Plane& plate, double keep) {
    const Vector3d up = plate.normal.normalized();
    const Vector3d offset = lowest_point(shape, up, sweep.frame().normal);
    const double lowest = up.dot(offset);
    for (const Segment& s : sweep.segments())
        for (const Vector3d& p : {s.a3, s.b3})
            if (up.dot(p - plate.origin) + lowest < keep)
                return std::pair{p, onto_plate(plate, p + offset)};
    return std::nullopt;
}

// Where the nozzle, its tip straight from `from` to `to` while its tool axis turns from `axis` to
// `to_axis`, every point of it within `allowance` x s of the nozzle along `axis` and within
// `allowance` x (1 - s) of the nozzle along `to_axis` at the fraction s of the way (NozzleMove),
// may come within `keep` of the plate: the tip's point there, and the plate's point under the
// lowest point of the nearer bound. At s its lowest point lies no lower than the higher of
// h0(s) = height(s) + low0 - allowance s and h1(s) = height(s) + low1 - allowance (1 - s), both
// linear in s, whose upper envelope is least at an end or where they cross.
std::optional<std::pair<Vector3d, Vector3d>> turning_plate_hit(
    const Vector3d& from, const Vector3d& to, const Vector3d& axis, const Vector3d& to_axis,
    double allowance, const Shape& shape, const Plane& plate, double keep) {
    const Vector3d up = plate.normal.normalized();
    const Vector3d off0 = lowest_point(shape, up, axis), off1 = lowest_point(shape, up, to_axis);
    const double z0 = up.dot(from - plate.origin), dz = up.dot(to - from);
    const auto h0 = [&](double s) { return z0 + s * dz + up.dot(off0) - allowance * s; };
    const auto h1 = [&](double s) { return z0 + s * dz + up.dot(off1) - allowance * (1.0 - s); };
    std::vector<double> at = {0.0, 1.0};
    // h0 - h1 = low0 - low1 - allowance (2 s - 1): zero at s = (low0 - low1 + allowance) / 2a.
    if (allowance > 0.0) {
        const double s = (up.dot(off0 - off1) + allowance) / (2.0 * allowance);
        if (s > 0.0 && s < 1.0) at.push_back(s);
    }
    for (const double s : at) {
        if (std::max(h0(s), h1(s)) >= keep) continue;
        const Vector3d p = from + s * (to - from);
        return std::pair{p, onto_plate(plate, p + (h0(s) >= h1(s) ? off0 : off1))};
    }
    return std::nullopt;
}

}  // namespace

void validate(const NozzleParams& p) {
    auto fail = [](const std::string& what, double value) {
        throw Error(ErrorCode::InvalidArgument, what + ", got " + format_number(value));
    };
    auto finite = [](double x) { return std::isfinite(x); };
    if (!(p.standoff_mm >= 0.0) || !finite(p.standoff_mm))
        fail("the nozzle's standoff must be >= 0 mm", p.standoff_mm);
    if (!(p.tip_diameter_mm > 0.0) || !finite(p.tip_diameter_mm))
        fail("the nozzle's tip diameter must be > 0 mm", p.tip_diameter_mm);
    if (!(p.body_diameter_mm >= p.tip_diameter_mm) || !finite(p.body_diameter_mm))
        fail("the nozzle's body diameter must be at least its tip diameter (" +
                 format_number(p.tip_diameter_mm) + " mm)",
             p.body_diameter_mm);
    if (!(p.body_length_mm > 0.0) || !finite(p.body_length_mm))
        fail("the nozzle's body length must be > 0 mm", p.body_length_mm);
    if (p.body_diameter_mm > p.tip_diameter_mm &&
        (!(p.cone_angle_deg > 0.0 && p.cone_angle_deg < 90.0)))
        fail("the nozzle's cone angle (half-angle) must lie between 0 and 90 degrees",
             p.cone_angle_deg);
    if (!finite(p.cone_angle_deg))
        fail("the nozzle's cone angle must be a number", p.cone_angle_deg);
    if (!(p.margin_mm > 0.0) || !finite(p.margin_mm))
        fail("the nozzle's margin must be > 0 mm", p.margin_mm);
    // The check grows the nozzle by twice the margin (see Nozzle.hpp): with a smaller standoff
    // the grown tip would reach below the deposit point, into the layer it is deposited on.
    if (!(p.standoff_mm >= 2.0 * p.margin_mm))
        fail("the nozzle's margin must be at most half its standoff (" +
                 format_number(p.standoff_mm) + " mm)",
             p.margin_mm);
    if (!(p.max_lean_deg >= 0.0 && p.max_lean_deg < 90.0))
        fail("the nozzle's greatest lean must lie within [0, 90) degrees", p.max_lean_deg);
    // A turn of the tool axis moves the body's end's rim, the nozzle's farthest point from its
    // deposit point, by the turn times that distance; the travel check cuts every turn of the
    // table into steps that move it at most the margin (TravelCheck::max_turn_rad()).
    const double reach =
        std::hypot(p.standoff_mm + cone_length(p) + p.body_length_mm, 0.5 * p.body_diameter_mm);
    if (!(reach <= kMaxNozzleReachInMargins * p.margin_mm))
        throw Error(ErrorCode::InvalidArgument,
                    "the nozzle's body ends " + format_number(reach) +
                        " mm from its deposit point, more than " +
                        format_number(kMaxNozzleReachInMargins) + " times its margin (" +
                        format_number(p.margin_mm) +
                        " mm): the travel check cuts the table's turns into steps that move it at "
                        "most a margin; shorten the nozzle or widen the margin");
}

void validate(const NozzleParams& p, double size, const std::string& what) {
    validate(p);
    const double least = kMinMarginFraction * size;
    if (p.margin_mm < least)
        throw Error(ErrorCode::InvalidArgument,
                    "the nozzle's margin " + format_number(p.margin_mm) + " mm is too small for " +
                        what + ", " + format_number(size) +
                        " mm across: the collision checks sample what is deposited that far "
                        "apart; the least is " +
                        format_number(least) + " mm");
}

double layers_size(const std::vector<Layer>& layers) {
    Eigen::AlignedBox3d box;
    for (const Layer& layer : layers)
        for (std::size_t r = 0; r < layer.regions.size(); ++r)
            for (const auto& loop : layer.loops_3d(r))
                for (const Vector3d& q : loop) box.extend(q);
    return box.isEmpty() ? 0.0 : box.diagonal().norm();
}

double cone_length(const NozzleParams& p) {
    const double widening = 0.5 * (p.body_diameter_mm - p.tip_diameter_mm);
    return widening > 0.0 ? widening / std::tan(p.cone_angle_deg * kPi / 180.0) : 0.0;
}

double near_miss_mm(const NozzleParams& p) {
    const Shape shape(p);
    return std::hypot(shape.grow, shape.grow_radially);
}

bool in_grown_nozzle(const NozzleParams& p, const Vector3d& tip, const Vector3d& axis,
                     const Vector3d& point) {
    const Vector3d d = point - tip;
    const double h = axis.dot(d);
    const double r = Shape(p).grown(h);
    return r >= 0.0 && (d - h * axis).squaredNorm() <= r * r;
}

BuildSequence plan_build_sequence(const SequenceInput& in, const NozzleParams& params,
                                  const Progress& progress) {
    validate(params);
    if (!in.layers || !in.toolpaths || in.toolpaths->size() != in.layers->size())
        throw Error(ErrorCode::InvalidArgument, "the build sequence needs every layer's paths");
    validate(params, layers_size(*in.layers), "the layers");
    const std::vector<Layer>& layers = *in.layers;
    const std::size_t count = layers.size(), comps = in.parent.size();
    auto bad = [](const std::string& what) { throw Error(ErrorCode::InvalidArgument, what); };
    if (in.waits_for.size() != comps) bad("the build sequence needs every component's waits");
    // Each component's layers, bottom to top, and whether they lie together.
    std::vector<std::vector<int>> of(comps);
    for (std::size_t i = 0; i < count; ++i) {
        const int c = layers[i].component;
        if (c < 0 || std::size_t(c) >= comps)
            bad("layer " + std::to_string(i) + " names component " + std::to_string(c) +
                ", which the part lacks");
        if (!of[std::size_t(c)].empty() && of[std::size_t(c)].back() != int(i) - 1)
            bad("component " + std::to_string(c) + "'s layers do not lie together");
        of[std::size_t(c)].push_back(int(i));
    }
    // The layers' boxes, and each component's (of its layers' prisms).
    std::vector<LayerBounds> bounds(count);
    std::vector<Eigen::AlignedBox3d> component_box(comps);
    double thickest = 0.0;
    for (std::size_t i = 0; i < count; ++i) {
        bounds[i] = layer_bounds(layers[i]);
        if (!bounds[i].corners.empty())
            component_box[std::size_t(layers[i].component)].extend(bounds[i].box);
        thickest = std::max(thickest, layers[i].max_thickness_mm);
    }
    // need[p][c]: how many of p's layers (bottom first) must be deposited before c's first, -1
    // when c does not wait for p. A component waits for every layer of a component in its
    // `waits_for`, and for its father's layers up to the last one coming within the thickest
    // layer of its own layers' box (those it may rest on; all of them when none comes so near).
    // The father's layers above those and the child are then ordered like brothers' layers.
    // Transitively: c cannot start before a component it waits for starts.
    std::vector<std::vector<std::pair<int, int>>> preds(comps);  // (p, layers of p), direct
    for (std::size_t c = 0; c < comps; ++c) {
        std::vector<int> ps;
        if (in.parent[c] >= 0) ps.push_back(in.parent[c]);
        for (int w : in.waits_for[c]) ps.push_back(w);
        for (int p : ps)
            if (p < 0 || std::size_t(p) >= comps || std::size_t(p) == c)
                bad("component " + std::to_string(c) + " waits for component " + std::to_string(p) +
                    ", which cannot come before it");
        for (std::size_t k = 0; k < ps.size(); ++k) {
            const std::vector<int>& mine = of[std::size_t(ps[k])];
            int n = int(mine.size());
            if (k == 0 && in.parent[c] >= 0 && !component_box[c].isEmpty()) {
                const Eigen::AlignedBox3d near(
                    component_box[c].min() - Vector3d::Constant(thickest + 1e-9),
                    component_box[c].max() + Vector3d::Constant(thickest + 1e-9));
                int last = -1;
                for (std::size_t j = 0; j < mine.size(); ++j) {
                    const LayerBounds& b = bounds[std::size_t(mine[j])];
                    if (!b.corners.empty() && b.box.intersects(near)) last = int(j);
                }
                if (last >= 0) n = last + 1;
            }
            preds[c].emplace_back(ps[k], n);
        }
    }
    std::vector<std::vector<int>> need(comps, std::vector<int>(comps, -1));
    for (std::size_t c = 0; c < comps; ++c) {
        std::vector<int> stack = {int(c)}, seen(comps, 0);
        while (!stack.empty()) {
            const std::size_t q = std::size_t(stack.back());  // c waits for q to start
            stack.pop_back();
            for (const auto& [p, n] : preds[q]) {
                const std::size_t pp = std::size_t(p);
                need[pp][c] = std::max(need[pp][c], n);
                if (!seen[pp]) {
                    seen[pp] = 1;
                    stack.push_back(p);
                }
            }
        }
    }
    for (std::size_t c = 0; c < comps; ++c)
        if (need[c][c] >= 0) bad("component " + std::to_string(c) + " waits for itself");
    // Where layer i lies in its component's order.
    std::vector<int> index(count, 0);
    for (const std::vector<int>& mine : of)
        for (std::size_t j = 0; j < mine.size(); ++j) index[std::size_t(mine[j])] = int(j);
    std::vector<int> rank(comps, int(comps));
    for (std::size_t k = 0; k < in.start_order.size(); ++k) {
        const int c = in.start_order[k];
        if (c < 0 || std::size_t(c) >= comps || rank[std::size_t(c)] != int(comps))
            bad("the start order must name every component once");
        rank[std::size_t(c)] = int(k);
    }
    if (in.start_order.size() != comps) bad("the start order must name every component once");

    // The pairs: each layer x against every layer y that may lie in its nozzle.
    const Shape shape(params);
    const double m = params.margin_mm;
    const double reach = shape.grown(shape.top);  // of the grown nozzle, sideways
    PrismSamples samples(layers, m);
    FineSamples fine(layers, m);  // where a sample counts for a lean
    // Where layer y's prism lies seen from x's paths (`sweep` is x's): its corners' lowest and
    // highest heights above x's plane along the tool axis, and how far across the axis its
    // corners' box lies from the paths' (the prism lies within its corners' hull).
    struct Extent {
        double lo, hi, gap;
    };
    auto extent = [&](const Sweep& sweep, std::size_t y) {
        const Vector3d n = sweep.frame().normal;
        Extent e{std::numeric_limits<double>::infinity(), -std::numeric_limits<double>::infinity(),
                 0.0};
        Eigen::AlignedBox2d across;
        for (const Vector3d& p : bounds[y].corners) {
            e.lo = std::min(e.lo, n.dot(p) - sweep.height());
            e.hi = std::max(e.hi, n.dot(p) - sweep.height());
            across.extend(sweep.frame().to_2d(p));
        }
        e.gap = (across.min() - sweep.box().max())
                    .array()
                    .max((sweep.box().min() - across.max()).array())
                    .max(0.0)
                    .matrix()
                    .norm();
        return e;
    };
    // Whether layer y's prism lies in x's grown nozzle (`sweep` is x's): where, if it does.
    auto meets = [&](const Sweep& sweep, std::size_t x, std::size_t y) -> std::optional<Conflict> {
        const Vector3d n = sweep.frame().normal;
        const LayerBounds& b = bounds[y];
        if (b.corners.empty()) return std::nullopt;
        const double centre_h = n.dot(b.centre) - sweep.height();
        if (centre_h + b.radius < shape.standoff - shape.grow ||
            centre_h - b.radius > shape.top + shape.grow)
            return std::nullopt;
        if (sweep.box().exteriorDistance(sweep.frame().to_2d(b.centre)) > b.radius + reach)
            return std::nullopt;
        // Below the tip, or off to the side, it misses.
        const Extent e = extent(sweep, y);
        if (e.hi < shape.standoff - shape.grow || e.gap > reach) return std::nullopt;
        for (const Vector3d& q : samples.of(y)) {
            const double r = shape.grown(n.dot(q) - sweep.height());
            if (r < 0.0) continue;
            if (const auto hit = sweep.near(sweep.frame().to_2d(q), r))
                return Conflict{int(x), int(y), hit->at, q};
        }
        return std::nullopt;
    };
    // Of the layers `met` (each known to be in x's grown nozzle), the one coming deepest into the
    // nozzle itself: the least clearance (Shape::clearance) of any of its samples from the nozzle
    // over its nearest deposit point, with that sample and point. Layers are visited from the
    // deepest they could come (their corners' heights and distance off the paths bound it), and
    // passed over, like samples, once they cannot beat the deepest found.
    auto deepest = [&](const Sweep& sweep, std::size_t x, const std::vector<int>& met) {
        const Vector3d n = sweep.frame().normal;
        std::vector<std::pair<double, int>> bound;  // the least clearance a layer can have
        for (int y : met) {
            const Extent e = extent(sweep, std::size_t(y));
            bound.emplace_back(
                -std::min({shape.body - e.gap, e.hi - shape.standoff, shape.top - e.lo}), y);
        }
        std::sort(bound.begin(), bound.end());
        double best = std::numeric_limits<double>::infinity();
        Conflict where{int(x), -1, Vector3d::Zero(), Vector3d::Zero()};
        for (const auto& [least, y] : bound) {
            if (least >= best) break;
            for (const Vector3d& q : samples.of(std::size_t(y))) {
                const double h = n.dot(q) - sweep.height();
                const double r = shape.grown(h);
                if (r < 0.0) continue;
                const double could =
                    h < shape.standoff || h > shape.top
                        ? std::max(shape.standoff - h, h - shape.top)
                        : -std::min({shape.radius(h), h - shape.standoff, shape.top - h});
                if (could >= best) continue;
                const auto hit = sweep.near(sweep.frame().to_2d(q), r, true);
                if (!hit) continue;
                const double c = shape.clearance(hit->distance, h);
                if (c < best) {
                    best = c;
                    where = Conflict{int(x), y, hit->at, q};
                }
            }
        }
        return where;
    };
    const Vector3d up = in.plate.normal.normalized();
    // Where the nozzle meets the plate along x's moves (`sweep` is x's, with its tool axis).
    auto plate_meets = [&](const Sweep& sweep, std::size_t x) -> std::optional<Conflict> {
        if (const auto hit = plate_hit(sweep, shape, in.plate, m))
            return Conflict{int(x), -1, hit->first, hit->second};
        return std::nullopt;
    };
    std::vector<std::optional<Conflict>> plate(count);    // where x's nozzle meets the plate
    std::vector<std::vector<int>> unavoidable_of(count);  // x -> the layers y met whatever
    std::vector<std::vector<int>> blocks(count);          // x -> the layers y to come after it
    const Progress pairs = progress.span(0.0, 0.9, "checking the nozzle against the layers");
    for (std::size_t x = 0; x < count; ++x) {
        pairs(double(x) / double(std::max<std::size_t>(count, 1)));
        const Sweep sweep((*in.toolpaths)[x], layers[x], reach);
        if (sweep.empty()) continue;
        const int cx = layers[x].component;
        if (params.check_plate) plate[x] = plate_meets(sweep, x);
        const Eigen::AlignedBox3d reachable = reach_box(sweep, shape);
        for (std::size_t y = 0; y < count; ++y) {
            if (y == x) continue;
            const int cy = layers[y].component;
            if (!component_box[std::size_t(cy)].intersects(reachable)) {
                y = std::size_t(of[std::size_t(cy)].back());  // none of its layers: the next
                continue;
            }
            if (bounds[y].corners.empty() || !bounds[y].box.intersects(reachable)) continue;
            bool unavoidable;
            if (cx == cy) {
                if (y > x) continue;
                unavoidable = true;
            } else if (index[y] < need[std::size_t(cy)][std::size_t(cx)]) {
                unavoidable = true;  // y is deposited before x's component starts
            } else if (index[x] < need[std::size_t(cx)][std::size_t(cy)]) {
                continue;  // and x before y's
            } else {
                unavoidable = false;
            }
            // The plate is reported before any layer: whichever layers it meets whatever the
            // order need not be known.
            if (unavoidable && plate[x]) continue;
            if (!meets(sweep, x, y)) continue;
            if (unavoidable) {
                unavoidable_of[x].push_back(int(y));
            } else {
                blocks[x].push_back(int(y));
            }
        }
    }

    // The leans tried: 5, 10, ... degrees and the greatest, each keeping the whole nozzle the
    // margin above the layer's plane.
    std::vector<double> leans;
    const double cone_deg = shape.tan > 0.0 ? params.cone_angle_deg : 0.0;
    for (double step = 5.0;; step += 5.0) {
        const double theta = std::min(step, params.max_lean_deg);
        if (theta <= 0.0) break;
        const double t = theta * kPi / 180.0;
        if (params.standoff_mm * std::cos(t) - shape.tip * std::sin(t) < m ||
            theta + cone_deg >= 90.0)
            break;
        leans.push_back(theta);
        if (theta >= params.max_lean_deg) break;
    }
    // The axes x's nozzle may lean to, in the order tried: by each lean from its layer's normal n,
    // towards the plate's normal, then across n towards `away` (from an obstacle to the nozzle),
    // then, `all_round`, the other ways round n every 22.5 degrees from the first of those, nearest
    // it first (on `away`'s side first among equals); none further from the plate's normal than n
    // is, past the horizontal: the machine may not reach it where it reached the normal.
    auto lean_axes = [&](std::size_t x, const std::optional<Vector3d>& away, bool all_round) {
        const Vector3d n = (*in.toolpaths)[x].tool_axis.normalized();
        std::vector<Vector3d> towards;  // across n
        std::vector<Vector3d> from = {up};
        if (away) from.push_back(*away);
        auto add = [&](const Vector3d& d) {
            for (const Vector3d& t : towards)
                if (t.dot(d) > 1.0 - 1e-9) return;
            towards.push_back(d);
        };
        for (const Vector3d& v : from) {
            const Vector3d across = v - n.dot(v) * n;
            if (across.norm() >= 1e-9) add(across.normalized());
        }
        if (all_round && !towards.empty()) {
            const Vector3d d0 = towards.front();
            Vector3d side = n.cross(d0).normalized();
            if (towards.size() > 1 && towards[1].dot(side) < 0.0) side = -side;
            // Every 22.5 degrees: at a 30-degree lean, neighbouring axes 11 degrees apart, nearer
            // the leans' own 5-degree steps (every 45, 22 apart: a crank's last leg close beside
            // its riser found none of those clear, and one between two is).
            constexpr int kHalfRound = 8;
            for (int k = 1; k <= kHalfRound; ++k) {
                const double phi = k * kPi / kHalfRound;
                add((std::cos(phi) * d0 + std::sin(phi) * side).normalized());
                if (k < kHalfRound) add((std::cos(phi) * d0 - std::sin(phi) * side).normalized());
            }
        }
        const double steepest = std::max(std::acos(std::clamp(n.dot(up), -1.0, 1.0)), kPi / 2.0);
        std::vector<Vector3d> axes;
        for (double theta : leans) {
            const double t = theta * kPi / 180.0;
            for (const Vector3d& d : towards) {
                const Vector3d axis = (std::cos(t) * n + std::sin(t) * d).normalized();
                if (axis != n && std::acos(std::clamp(axis.dot(up), -1.0, 1.0)) <= steepest + 1e-12)
                    axes.push_back(axis);
            }
        }
        return axes;
    };
    // Whether x's nozzle leaned (`sweep`, with its tool axis; `reachable`, its reach_box; `moves`,
    // its deposit moves) may come within the margin of layer y's prism: as TravelCheck's, a sample
    // the grown nozzle may hold counts only when the nozzle, its tip taken every kTravelStep
    // margins along the moves, comes within (2 + kTravelStep) margins of it.
    auto leaned_meets = [&](const Sweep& sweep, const Eigen::AlignedBox3d& reachable,
                            const std::vector<std::pair<Vector3d, Vector3d>>& moves, std::size_t x,
                            std::size_t y) {
        const LayerBounds& b = bounds[y];
        if (b.corners.empty() || !b.box.intersects(reachable)) return false;
        const Plane& top = layers[x].plane;
        if (std::all_of(b.corners.begin(), b.corners.end(),
                        [&](const Vector3d& c) { return top.normal.dot(c - top.origin) <= 0.0; }))
            return false;  // wholly under x's plane, which the nozzle keeps the margin above
        const Vector3d& axis = sweep.frame().normal;
        const double centre = axis.dot(b.centre);
        if (centre + b.radius - sweep.lowest() < shape.standoff - shape.grow ||
            centre - b.radius - sweep.highest() > shape.top + shape.grow)
            return false;
        const double counts = (2.0 + kTravelStep) * m;
        const double fine_counts = (1.0 + 1.0 / kFineSamples + kTravelStep) * m;
        // A sample met itself refuses the lean at once; the finer samples round those that
        // count are looked at only when none is.
        std::vector<Vector3d> counted;
        for (const Vector3d& q : samples.of(y)) {
            if (!sweep.may_hold(sweep.frame().to_2d(q), axis.dot(q), shape)) continue;
            Vector3d tip;
            const Nearness r = how_near(shape, m, moves, axis, q, counts, fine_counts, tip);
            if (r == Nearness::near) return true;
            if (r == Nearness::counts) counted.push_back(q);
        }
        std::vector<char> cleared;  // y's fine samples clear of the moves
        return std::any_of(counted.begin(), counted.end(), [&](const Vector3d& q) {
            return fine.hit(y, q, shape, moves, axis, fine_counts, cleared).has_value();
        });
    };
    // The sequence, ordered by `order_by` (x -> the layers y to come after it: `blocks`, or some
    // of them): the order, the collisions it leaves (every layer of `blocks[x]` put before x) and
    // the leans that clear them.
    const auto sequence = [&](const std::vector<std::vector<int>>& order_by) {
        std::vector<int> pending(count, 0);  // y: layers x to come before it, left
        for (const std::vector<int>& ys : order_by)
            for (int y : ys) ++pending[std::size_t(y)];
        BuildSequence out;
        out.layers.reserve(count);
        std::vector<std::size_t> next(comps, 0);  // per component: its layers taken
        std::vector<char> left(comps, 0);         // left unfinished for another
        std::vector<int> position(count, -1);
        auto complete = [&](std::size_t c) { return next[c] >= of[c].size(); };
        // Per component: the components whose layers it waits for that are not yet deposited.
        std::vector<int> waiting(comps, 0);
        for (std::size_t p = 0; p < comps; ++p)
            for (std::size_t c = 0; c < comps; ++c) waiting[c] += need[p][c] > 0;
        std::vector<int> open;  // may go on: every layer waited for deposited, layers left
        for (std::size_t c = 0; c < comps; ++c)
            if (waiting[c] == 0 && !complete(c)) open.push_back(int(c));
        int current = -1;
        const Progress order = progress.span(0.9, 0.95, "ordering the layers");
        while (out.layers.size() < count) {
            order(double(out.layers.size()) / double(count));
            if (open.empty()) bad("the components' waits form a cycle");
            // How many layers still to come component c's next layer would block.
            auto blocking = [&](int c) {
                return pending[std::size_t(of[std::size_t(c)][next[std::size_t(c)]])];
            };
            int pick = -1;
            auto better = [&](int a, int b) {  // b is better than a, among ready ones
                return a < 0 || rank[std::size_t(b)] < rank[std::size_t(a)];
            };
            if (current >= 0 && !complete(std::size_t(current)) && blocking(current) == 0)
                pick = current;
            if (pick < 0)
                for (int c : open)
                    if (blocking(c) == 0 && better(pick, c)) pick = c;
            if (pick < 0)  // a cycle: the layer that blocks the fewest still to come
                for (int c : open)
                    if (pick < 0 || blocking(c) < blocking(pick) ||
                        (blocking(c) == blocking(pick) && better(pick, c)))
                        pick = c;
            const std::size_t c = std::size_t(pick);
            if (current >= 0 && current != pick) {
                ++out.component_switches;
                if (!complete(std::size_t(current))) left[std::size_t(current)] = 1;
            }
            current = pick;
            const int x = of[c][next[c]++];
            position[std::size_t(x)] = int(out.layers.size());
            out.layers.push_back(x);
            for (int y : order_by[std::size_t(x)]) --pending[std::size_t(y)];
            if (complete(c)) open.erase(std::find(open.begin(), open.end(), pick));
            for (std::size_t d = 0; d < comps; ++d)
                if (need[c][d] == int(next[c]) && --waiting[d] == 0 && !complete(d))
                    open.push_back(int(d));
        }
        for (std::size_t c = 0; c < comps; ++c) out.interrupted_components += left[c];

        // The collisions: per layer, the plate, else of the layers it meets (whatever the order, or
        // put before it all the same) the one that comes deepest into its nozzle.
        std::vector<std::optional<Conflict>> worst = plate;
        for (std::size_t x = 0; x < count; ++x) {
            if (worst[x]) continue;
            std::vector<int> met = unavoidable_of[x];
            for (int y : blocks[x])
                if (position[std::size_t(y)] < position[x]) met.push_back(y);
            if (met.empty()) continue;
            std::sort(met.begin(), met.end());
            const Sweep sweep((*in.toolpaths)[x], layers[x], reach);
            worst[x] = deepest(sweep, x, met);
        }

        // Leaning the nozzle where it collides (see Nozzle.hpp): whether the nozzle along x's moves
        // with tool axis `axis` keeps clear of the plate and of every layer deposited before x.
        auto clears = [&](std::size_t x, const Vector3d& axis) {
            const Sweep sweep((*in.toolpaths)[x], layers[x], reach, axis, m);
            if (params.check_plate && plate_meets(sweep, x)) return false;
            const Eigen::AlignedBox3d reachable = reach_box(sweep, shape);
            const auto moves = sweep.moves();
            for (std::size_t y = 0; y < count; ++y)
                if (position[y] < position[x] && leaned_meets(sweep, reachable, moves, x, y))
                    return false;
            return true;
        };
        out.tool_axes.resize(count);
        for (std::size_t x = 0; x < count; ++x) out.tool_axes[x] = (*in.toolpaths)[x].tool_axis;
        order(1.0);
        const Progress leaning = progress.span(0.95, 1.0, "leaning the nozzle where it collides");
        for (std::size_t x = 0; x < count && !leans.empty(); ++x) {
            if (!worst[x]) continue;
            leaning(double(x) / double(count));
            for (const Vector3d& axis : lean_axes(x, worst[x]->at - worst[x]->obstacle, true)) {
                if (!clears(x, axis)) continue;
                out.tool_axes[x] = axis;
                worst[x].reset();
                ++out.leaned_layers;
                break;
            }
        }

        for (int x : out.layers)
            if (worst[std::size_t(x)]) {
                const Conflict& k = *worst[std::size_t(x)];
                out.collisions.push_back({k.x, k.y, k.at, k.obstacle});
            }
        return out;
    };
    BuildSequence out = sequence(blocks);
    std::vector<std::vector<int>> basis = blocks;  // what ordered `out`
    // Where layers still collide, the order may be what left them no lean (a rod built sideways
    // under a bar: the bar's layers came first, and the rod's nozzle, leaned up off the plate, met
    // them). Ordered again without the pairs x's nozzle clears leaned towards the plate's normal
    // (by a lean that keeps it off the plate too), it is kept when fewer layers collide.
    if (!out.collisions.empty() && !leans.empty()) {
        std::vector<std::vector<int>> relaxed(count);
        bool changed = false;
        for (std::size_t x = 0; x < count; ++x) {
            if (blocks[x].empty()) continue;
            std::vector<Sweep> leaned;  // x's nozzle at each lean that keeps off the plate
            for (const Vector3d& axis : lean_axes(x, std::nullopt, false)) {
                Sweep sweep((*in.toolpaths)[x], layers[x], reach, axis, m);
                if (!params.check_plate || !plate_meets(sweep, x))
                    leaned.push_back(std::move(sweep));
            }
            for (int y : blocks[x]) {
                const bool avoided = std::any_of(leaned.begin(), leaned.end(), [&](const Sweep& s) {
                    return !meets(s, x, std::size_t(y));
                });
                if (avoided)
                    changed = true;
                else
                    relaxed[x].push_back(y);
            }
        }
        if (changed) {
            BuildSequence again = sequence(relaxed);
            if (again.collisions.size() < out.collisions.size()) {
                out = std::move(again);
                basis = std::move(relaxed);
            }
        }
    }
    // Where layers still collide, the order may be what left a layer that meets the plate no lean
    // (two blades built sideways off a hub, 10 mm apart at their roots: the first blade's layers
    // came first, and the second's first layer, leaned up off the plate, met them, where coaxial
    // it missed them). Ordered again with the pairs "x before y" for the layers y that such a
    // layer x's nozzle would meet at the lean that keeps it off the plate and meets fewest
    // (the least lean among equals), it is kept when fewer layers collide.
    if (!out.collisions.empty() && !leans.empty()) {
        std::vector<std::vector<int>> tightened = std::move(basis);
        bool changed = false;
        for (std::size_t x = 0; x < count; ++x) {
            if (!plate[x]) continue;
            const int cx = layers[x].component;
            std::optional<std::vector<int>> fewest;
            for (const Vector3d& axis : lean_axes(x, std::nullopt, false)) {
                const Sweep sweep((*in.toolpaths)[x], layers[x], reach, axis, m);
                if (params.check_plate && plate_meets(sweep, x)) continue;
                const Eigen::AlignedBox3d reachable = reach_box(sweep, shape);
                const auto moves = sweep.moves();
                std::vector<int> met;
                for (std::size_t y = 0; y < count; ++y) {
                    const int cy = layers[y].component;
                    if (cy == cx || index[y] < need[std::size_t(cy)][std::size_t(cx)] ||
                        index[x] < need[std::size_t(cx)][std::size_t(cy)])
                        continue;  // its own, or before or after x whatever the order
                    if (leaned_meets(sweep, reachable, moves, x, y)) met.push_back(int(y));
                }
                if (!fewest || met.size() < fewest->size()) fewest = std::move(met);
                if (fewest->empty()) break;
            }
            if (!fewest) continue;
            std::vector<int>& after = tightened[x];
            for (int y : *fewest)
                if (std::find(after.begin(), after.end(), y) == after.end()) {
                    after.push_back(y);
                    changed = true;
                }
        }
        if (changed) {
            BuildSequence again = sequence(tightened);
            if (again.collisions.size() < out.collisions.size()) out = std::move(again);
        }
    }
    progress(1.0);
    return out;
}

// The travel check (see Nozzle.hpp, "Travel").
struct TravelCheck::Impl {
    const std::vector<Layer>& layers;
    NozzleParams params;
    Plane plate;
    Shape shape;  // grown by 2 margins, as the deposit moves' check
    std::vector<LayerBounds> bounds;
    std::vector<int> done;  // the layers deposited, in order
    std::vector<char> is_done;
    mutable PrismSamples samples;  // of the deposited layers, as plan_build_sequence's
    mutable FineSamples fine;      // where a sample counts

    Impl(const std::vector<Layer>& l, const NozzleParams& p, const Plane& pl)
        : layers(l),
          params(p),
          plate(pl),
          shape(p),
          is_done(l.size(), 0),
          samples(l, p.margin_mm),
          fine(l, p.margin_mm) {
        bounds.reserve(layers.size());
        for (const Layer& layer : layers) bounds.push_back(layer_bounds(layer));
    }

    // The farthest any point of the nozzle lies from its deposit point: the body's end's rim. A
    // turn of the tool axis by t moves no point of it further than t times this.
    double length() const { return std::hypot(shape.top, shape.body); }
    double max_turn() const { return params.margin_mm / length(); }

    // What the nozzle along the sweep's `moves` (its tool axis, that of their first point where
    // it turns by up to `allowance` / length()) meets: the plate within the margin and
    // the allowance (the margin, judged from both ends, where the one turning move's last axis
    // `to_axis` is given), or a sample of a deposited layer in the nozzle grown by 2 margins and
    // the allowance, which counts only when the nozzle along the first axis comes within 2
    // margins, the step and the allowance of it.
    std::optional<TravelHit> check(const std::vector<std::pair<Vector3d, Vector3d>>& moves,
                                   const Sweep& sweep, double allowance, int skip, int also,
                                   const std::optional<Vector3d>& to_axis) const {
        const double m = params.margin_mm;
        const Shape grown(params, 2.0 * m + allowance);
        if (sweep.empty()) return std::nullopt;
        if (params.check_plate) {
            const auto hit = to_axis ? turning_plate_hit(moves.front().first, moves.front().second,
                                                         sweep.frame().normal, *to_axis, allowance,
                                                         grown, plate, m)
                                     : plate_hit(sweep, grown, plate, m + allowance);
            if (hit) return TravelHit{-1, hit->first, hit->second};
        }
        const Eigen::AlignedBox3d box = reach_box(sweep, grown);
        const Vector3d a = sweep.frame().normal;
        const double low = grown.standoff - grown.grow, high = grown.top + grown.grow;
        auto layers_to_check = [&](auto&& visit) {
            for (const int yi : done)
                if (yi != skip && visit(yi)) return true;
            return also >= 0 && also != skip && !is_done[std::size_t(also)] && visit(also);
        };
        std::optional<TravelHit> found;
        layers_to_check([&](int yi) {
            const std::size_t y = std::size_t(yi);
            const LayerBounds& b = bounds[y];
            if (b.corners.empty() || !b.box.intersects(box)) return false;
            const double centre = a.dot(b.centre);
            if (centre + b.radius - sweep.lowest() < low ||
                centre - b.radius - sweep.highest() > high)
                return false;
            // The prism lies within its corners' hull: wholly under the grown tip, it is missed.
            if (std::all_of(b.corners.begin(), b.corners.end(),
                            [&](const Vector3d& c) { return a.dot(c) - sweep.lowest() < low; }))
                return false;
            const double counts = (2.0 + kTravelStep) * m + allowance;
            const double fine_counts = (1.0 + 1.0 / kFineSamples + kTravelStep) * m + allowance;
            std::vector<char> cleared;  // y's fine samples clear of the moves
            for (const Vector3d& q : samples.of(y)) {
                const Vector2d q2 = sweep.frame().to_2d(q);
                if (!sweep.may_hold(q2, a.dot(q), grown)) continue;
                // Whether it counts (the finer samples say where the nozzle is), or is met itself.
                Vector3d tip;
                const Nearness r = how_near(shape, m, moves, a, q, counts, fine_counts, tip);
                if (r == Nearness::apart) continue;
                if (r == Nearness::near) {
                    found = TravelHit{yi, tip, q};
                    return true;
                }
                if (const auto hit = fine.hit(y, q, shape, moves, a, fine_counts, cleared)) {
                    found = TravelHit{yi, hit->first, hit->second};
                    return true;
                }
            }
            return false;
        });
        return found;
    }
};

TravelCheck::TravelCheck(const std::vector<Layer>& layers, const NozzleParams& params,
                         const Plane& plate) {
    validate(params, layers_size(layers), "the layers");
    impl_ = std::make_unique<Impl>(layers, params, plate);
}

TravelCheck::~TravelCheck() = default;

void TravelCheck::deposited(std::size_t k) {
    if (k >= impl_->layers.size())
        throw Error(ErrorCode::InvalidArgument, "the travel check has no layer " +
                                                    std::to_string(k) + " (it has " +
                                                    std::to_string(impl_->layers.size()) + ")");
    if (impl_->is_done[k]) return;
    impl_->is_done[k] = 1;
    impl_->done.push_back(int(k));
}

double TravelCheck::max_turn_rad() const { return impl_->max_turn(); }

std::optional<TravelHit> TravelCheck::meets(const std::vector<NozzleMove>& moves, int also) const {
    const Impl& c = *impl_;
    auto named = [&](int layer, const std::string& what) {
        if (layer < -1 || layer >= int(c.layers.size()))
            throw Error(ErrorCode::InvalidArgument, what + " names layer " + std::to_string(layer) +
                                                        ", which the travel check lacks (it has " +
                                                        std::to_string(c.layers.size()) + ")");
    };
    named(also, "the travel check's extra layer");
    const double m = c.params.margin_mm;
    const double reach = c.shape.grown(c.shape.top);
    for (std::size_t k = 0; k < moves.size(); ++k) {
        const NozzleMove& move = moves[k];
        if (!move.from.allFinite() || !move.to.allFinite() || !move.axis.allFinite() ||
            std::abs(move.axis.norm() - 1.0) > 1e-6)
            throw Error(ErrorCode::InvalidArgument,
                        "travel move " + std::to_string(k) + " needs finite ends and a unit axis");
        named(move.along_layer, "travel move " + std::to_string(k));
        if (move.along_layer >= 0 && move.turn_rad != 0.0)
            throw Error(ErrorCode::InvalidArgument,
                        "travel move " + std::to_string(k) +
                            " turns its tool axis: it cannot go along a layer's");
        if (!(move.turn_rad >= 0.0 && move.turn_rad <= c.max_turn() * (1.0 + 1e-9)))
            throw Error(ErrorCode::InvalidArgument, "travel move " + std::to_string(k) +
                                                        " turns its tool axis by " +
                                                        format_number(move.turn_rad) +
                                                        " rad, where a move may turn it by 0 to " +
                                                        format_number(c.max_turn()) + " rad");
        if (move.to_axis != Vector3d::Zero()) {
            if (!move.to_axis.allFinite() || std::abs(move.to_axis.norm() - 1.0) > 1e-6)
                throw Error(ErrorCode::InvalidArgument, "travel move " + std::to_string(k) +
                                                            "'s end axis must be a unit vector");
            const double apart =
                std::atan2(move.axis.cross(move.to_axis).norm(), move.axis.dot(move.to_axis));
            if (apart > move.turn_rad * (1.0 + 1e-9) + 1e-12)
                throw Error(ErrorCode::InvalidArgument,
                            "travel move " + std::to_string(k) + "'s end axis lies " +
                                format_number(apart) + " rad from its axis, past its turn of " +
                                format_number(move.turn_rad) + " rad");
        }
    }
    // Runs of moves along which the table keeps still, one axis and along_layer each, and each
    // turning move alone.
    for (std::size_t k = 0; k < moves.size();) {
        std::size_t end = k + 1;
        if (moves[k].turn_rad == 0.0)
            while (end < moves.size() && moves[end].turn_rad == 0.0 &&
                   moves[end].axis == moves[k].axis &&
                   moves[end].along_layer == moves[k].along_layer)
                ++end;
        std::vector<std::pair<Vector3d, Vector3d>> run;
        for (std::size_t j = k; j < end; ++j) run.emplace_back(moves[j].from, moves[j].to);
        // Every point of the nozzle stays within length() x turn of the nozzle along the first
        // axis.
        const double allowance = c.length() * moves[k].turn_rad;
        const Sweep sweep(run, reach + allowance, moves[k].axis, m);
        std::optional<Vector3d> to_axis;
        if (moves[k].turn_rad != 0.0 && moves[k].to_axis != Vector3d::Zero())
            to_axis = moves[k].to_axis.normalized();
        if (auto hit = c.check(run, sweep, allowance, moves[k].along_layer, also, to_axis))
            return hit;
        k = end;
    }
    return std::nullopt;
}

}  // namespace mas
