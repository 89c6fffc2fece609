// Adaptive multi-axis slicing of one sub-component (paper Sec. 4.2.2). See the header for the
// definitions (layer, thickness, VolDiff, support) and the reading of the paper.
#include "mas/Slicing.hpp"

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <optional>
#include <sstream>

#include "mas/Angles.hpp"
#include "mas/Error.hpp"

namespace mas {

namespace {

using Eigen::Vector2d;
using Eigen::Vector3d;

constexpr double kLengthTolerance = 1e-9;  // mm: slack on the thickness bounds (rounding only)
// Eq. 9's VolDiff of a layer that deposits the part exactly, but for the Booleans' rounding: the
// sections of a prism along the layer's normal are the same polygons at every height.
constexpr double kPrismDifference = 1e-6;

[[noreturn]] void invalid(const std::string& message) {
    throw Error(ErrorCode::InvalidArgument, message);
}

std::string mm(double x) { return format_number(x) + " mm"; }

double angle_deg(const Vector3d& a, const Vector3d& b) {
    return std::atan2(a.cross(b).norm(), a.dot(b)) * 180.0 / kPi;
}

// ---- the guide: the component's axis as a polyline, extended straight past both ends ----------

class Guide {
public:
    Guide(const ComponentSlicingInput& input, double eps_angle_deg) {
        for (std::size_t i = 0; i < input.guide.size(); ++i) {
            const Vector3d& p = input.guide[i];
            if (!p.allFinite()) invalid("the component's axis has a non-finite point");
            if (!points_.empty() && (p - points_.back()).norm() < 1e-9) continue;
            points_.push_back(p);
            nodes_.push_back(i < input.guide_nodes.size() ? input.guide_nodes[i] : -1);
        }
        if (points_.size() < 2) {
            const Vector3d p = points_.empty() ? input.base.origin : points_.front();
            const int node = nodes_.empty() ? -1 : nodes_.front();
            points_ = {p, p + input.base.normal};
            nodes_ = {node, node};
        }
        arc_.assign(points_.size(), 0.0);
        for (std::size_t i = 1; i < points_.size(); ++i)
            arc_[i] = arc_[i - 1] + (points_[i] - points_[i - 1]).norm();
        directions_ = segment_directions(eps_angle_deg);
    }

    double length() const { return arc_.back(); }

    // Segment i joins points i and i+1; s < 0 and s > length() run on along the end segments.
    std::size_t segment(double s) const {
        const auto it = std::upper_bound(arc_.begin(), arc_.end(), s);
        const std::size_t i = it == arc_.begin() ? 0 : std::size_t(it - arc_.begin()) - 1;
        return std::min(i, points_.size() - 2);
    }

    // The segment's direction; on a jump (below), its neighbours'.
    Vector3d direction(double s) const { return directions_[segment(s)]; }

    Vector3d point(double s) const {
        const std::size_t i = segment(s);
        return points_[i] + (s - arc_[i]) * direction(s);
    }

    // Whether the guide, past the segment at s, runs within `angle` degrees of `d` again: the
    // next segment does, or there is none (the guide ends there).
    bool runs_on_along(double s, const Vector3d& d, double angle) const {
        const std::size_t i = segment(s);
        if (i + 2 >= points_.size()) return true;
        return angle_deg((points_[i + 2] - points_[i + 1]).normalized(), d) < angle;
    }

    // The guide node nearest to arc length s (-1 when the guide came without node indices).
    int node_near(double s) const {
        std::size_t best = 0;
        for (std::size_t i = 1; i < arc_.size(); ++i)
            if (std::abs(arc_[i] - s) < std::abs(arc_[best] - s)) best = i;
        return nodes_[best];
    }

    // The arc length where the guide (with its extensions) crosses `plane`, the crossing nearest
    // to `hint`; nullopt when it never does (a guide parallel to the plane).
    std::optional<double> crossing(const Plane& plane, double hint) const {
        std::optional<double> best;
        const std::size_t n = points_.size();
        for (std::size_t i = 0; i + 1 < n; ++i) {
            const double d0 = plane.signed_distance(points_[i]);
            const double d1 = plane.signed_distance(points_[i + 1]);
            const double len = arc_[i + 1] - arc_[i];
            const bool first = i == 0, last = i + 2 == n;
            if (d0 == d1) continue;
            const double t = d0 / (d0 - d1);  // along the segment, may fall outside [0, 1]
            if ((t < 0.0 && !first) || (t > 1.0 && !last)) continue;
            const double s = arc_[i] + t * len;
            if (!best || std::abs(s - hint) < std::abs(*best - hint)) best = s;
        }
        return best;
    }

private:
    // Each segment's direction, but a jump's (Slicing.hpp): a segment running further sideways
    // than along the segments on both sides of it, which run within `eps_angle` of each other,
    // takes theirs. The sections changed shape there; the part does not go that way.
    std::vector<Vector3d> segment_directions(double eps_angle) const {
        std::vector<Vector3d> raw;
        for (std::size_t i = 0; i + 1 < points_.size(); ++i)
            raw.push_back((points_[i + 1] - points_[i]).normalized());
        std::vector<Vector3d> out = raw;
        for (std::size_t i = 1; i + 1 < raw.size(); ++i)
            if (angle_deg(raw[i - 1], raw[i + 1]) < eps_angle &&
                angle_deg(raw[i], raw[i - 1]) > 45.0 && angle_deg(raw[i], raw[i + 1]) > 45.0)
                out[i] = (raw[i - 1] + raw[i + 1]).normalized();
        return out;
    }

    std::vector<Vector3d> points_;
    std::vector<int> nodes_;
    std::vector<double> arc_;
    std::vector<Vector3d> directions_;  // per segment (segment_directions())
};

// ---- regions between frames ---------------------------------------------------------------------

// A section's regions turned into 3-D loops lying on `plane` (the section may have been cut a hair
// above it), plus the points of every outer loop, for thickness extremes.
struct PlanarRegions {
    Plane plane;
    std::vector<std::vector<std::vector<Vector3d>>> loops;  // per region: outer, then holes
    std::vector<Vector3d> outline;                          // every outer-loop point
    double area = 0.0;
    bool empty() const { return loops.empty(); }
};

PlanarRegions planar_regions(const Section& section, const Plane& plane) {
    PlanarRegions out;
    out.plane = plane;
    const PlaneFrame frame(section.plane.normal);
    // Points of the section's plane, moved onto `plane` along the section's normal.
    const double denom = plane.normal.dot(section.plane.normal);
    auto lift = [&](const Vector2d& q) {
        const Vector3d x = frame.to_3d(q, section.plane);
        return Vector3d(x - section.plane.normal * (plane.signed_distance(x) / denom));
    };
    for (const SectionRegion& section_region : section.regions) {
        // Collinear points a hair apart (a plane just above a vertex cuts the facets around it
        // close together) carry nothing: drop them within the Boolean grid.
        const Region2 shape = simplify(section_region.shape, 1e-5);
        std::vector<std::vector<Vector3d>> loops;
        auto add = [&](const Polygon2& p, bool outer) {
            std::vector<Vector3d> loop;
            loop.reserve(p.points.size());
            for (const Vector2d& q : p.points) loop.push_back(lift(q));
            if (outer) out.outline.insert(out.outline.end(), loop.begin(), loop.end());
            loops.push_back(std::move(loop));
        };
        add(shape.outer, true);
        for (const Polygon2& h : shape.holes) add(h, false);
        out.loops.push_back(std::move(loops));
        out.area += section_region.area;
    }
    return out;
}

// How far the outline of `regions` reaches from `p` across their plane: the farthest a layer's
// plane tilting about p moves over them, per unit of the tilt's sine.
double reach_from(const PlanarRegions& regions, const Vector3d& p) {
    double r = 0.0;
    const Vector3d& n = regions.plane.normal;
    for (const Vector3d& q : regions.outline) {
        const Vector3d v = q - p;
        r = std::max(r, (v - v.dot(n) * n).norm());
    }
    return r;
}

// The regions seen along `normal`: 2-D coordinates in PlaneFrame(normal). Orientation is kept as
// long as the regions' plane faces the same way (normal . plane normal > 0).
Regions2 project(const PlanarRegions& regions, const PlaneFrame& frame) {
    Regions2 out;
    out.reserve(regions.loops.size());
    for (const auto& loops : regions.loops) {
        Region2 r;
        for (std::size_t k = 0; k < loops.size(); ++k) {
            Polygon2 p;
            p.points.reserve(loops[k].size());
            for (const Vector3d& x : loops[k]) p.points.push_back(frame.to_2d(x));
            if (k == 0)
                r.outer = std::move(p);
            else
                r.holes.push_back(std::move(p));
        }
        out.push_back(std::move(r));
    }
    return out;
}

// The part of the plane (frame coordinates of PlaneFrame(D)) where plane L lies below height h
// along D, as a polygon covering `box` (grown): {q : height_L(q) < h}. nullopt: all of it.
std::optional<Regions2> below_height(const Plane& lower, const PlaneFrame& frame, double h,
                                     const Eigen::AlignedBox2d& box) {
    // height_L(q) = (n_L . o_L - n_L . (u q.x + v q.y)) / (n_L . D) = c - g . q
    const double nd = lower.normal.dot(frame.normal);
    const double c = lower.normal.dot(lower.origin) / nd;
    const Vector2d g(lower.normal.dot(frame.u) / nd, lower.normal.dot(frame.v) / nd);
    if (g.norm() < 1e-12) {
        if (c < h) return std::nullopt;
        return Regions2{};
    }
    // Keep c - g.q < h, i.e. g.q > c - h: clip the box (Sutherland-Hodgman on one half-plane).
    const double margin = 1.0 + box.diagonal().norm();
    const Vector2d lo = box.min() - Vector2d::Constant(margin);
    const Vector2d hi = box.max() + Vector2d::Constant(margin);
    const std::vector<Vector2d> corners = {lo, {hi.x(), lo.y()}, hi, {lo.x(), hi.y()}};
    std::vector<Vector2d> kept;
    const double limit = c - h;
    for (std::size_t i = 0; i < 4; ++i) {
        const Vector2d& a = corners[i];
        const Vector2d& b = corners[(i + 1) % 4];
        const double fa = g.dot(a) - limit, fb = g.dot(b) - limit;
        if (fa > 0.0) kept.push_back(a);
        if ((fa > 0.0) != (fb > 0.0)) kept.push_back(a + (b - a) * (fa / (fa - fb)));
    }
    if (kept.size() < 3) return Regions2{};
    return Regions2{Region2{Polygon2{kept}, {}}};
}

Eigen::AlignedBox2d bounds_of(const Regions2& regions) {
    Eigen::AlignedBox2d box;
    for (const Region2& r : regions) box.extend(bounds(r));
    return box;
}

// ---- one candidate plane ------------------------------------------------------------------------

struct Candidate {
    Plane upper;
    double along = 0.0;      // arc length of P_upper on the guide
    double delta = 0.0;      // the search's thickness it was tried at
    bool thickened = false;  // chosen over the search's own, counting on the next layer (choose())
    bool final = false;      // U lies on the top of the material: nothing is left above it
    double min_thickness = 0.0, max_thickness = 0.0;
    double volume = 0.0, material = 0.0, difference = 0.0;
    Regions2 region;                // the lower region seen along U's normal
    PlanarRegions next;             // the section just above U: the next layer's region, on U
    double unsupported_next = 0.0;  // of `next` outside `region` grown by min_layer's allowance
    // The thickness the next layer must have to support `next`, where min_layer's does not
    // (count_on_the_next(); 0: none).
    double promise = 0.0;
    bool thickness_ok = false;
};

// Unsupported area of c's next footprint that counts as none.
double tolerance_of(const Candidate& c) {
    return negligible_unsupported_mm2(std::max(c.next.area, 1e-9));
}

// Whether a layer leaves more of its footprint unsupported than counts as none.
bool hangs(const Layer& l) {
    return l.unsupported_area_mm2 > negligible_unsupported_mm2(l.area_mm2);
}

// Where the slicer stands before choosing a layer: the region it rests on (on the lower plane,
// whose normal is D_lower), the guide's arc length there, and the thickness the layer below
// counted on this one having (0: none; see run()).
struct Ground {
    PlanarRegions lower;
    double s_lower = 0.0;
    double promised = 0.0;
};

// What the meshes deposited before a component give its first layer to stand on: their sections
// just below its base plane (Eq. 6's offset), one layer with `base` as its top.
Layer support_below(const std::vector<const TriangleMesh*>& support, const Plane& base,
                    double offset) {
    Layer below;
    below.plane = base;
    below.lower = make_plane(base.origin - offset * base.normal, base.normal);
    for (const TriangleMesh* mesh : support) {
        Regions2 cut;
        for (const SectionRegion& r : slice_mesh(*mesh, below.lower).regions)
            cut.push_back(r.shape);
        below.regions = below.regions.empty() ? std::move(cut) : union_of(below.regions, cut);
    }
    return below;
}

class ComponentSlicer {
public:
    ComponentSlicer(const ComponentSlicingInput& input, const LayerParams& params,
                    double volume_mm3, const Progress& progress)
        : input_(input),
          params_(params),
          progress_(progress),
          volume_(volume_mm3),
          guide_(input, params.eps_angle_deg) {
        offset_ = base_offset(params);
        allowance_ = overhang_allowance(params);
    }

    std::vector<Layer> run();

private:
    // `d`, turned towards the build plate's normal (+Z) onto max_tilt where it tilts further
    // (in the plane of d and Z; straight down, in the plane of `fallback` and Z).
    Vector3d within_reach(const Vector3d& d, const Vector3d& fallback) const {
        if (tilt_from_plate_deg(d) <= params_.max_tilt_deg) return d;
        const double limit = params_.max_tilt_deg * kPi / 180.0;
        Vector3d side(d.x(), d.y(), 0.0);
        if (side.norm() < 1e-6) side = Vector3d(fallback.x(), fallback.y(), 0.0);
        if (side.norm() < 1e-6) side = Vector3d::UnitX();
        return std::cos(limit) * Vector3d::UnitZ() + std::sin(limit) * side.normalized();
    }

    // The highest point of the material along unit d.
    double top_along(const Vector3d& d) const {
        double top = -std::numeric_limits<double>::infinity();
        for (const Vector3d& v : input_.mesh->vertices) top = std::max(top, v.dot(d));
        return top;
    }

    // The offsets along unit d of the material's faces square to d (triangles whose normal is
    // within a hundredth of a degree of +-d), ascending, each once. Kept for the last d asked.
    const std::vector<double>& flat_offsets(const Vector3d& d) const {
        if (flat_dir_ && flat_dir_->isApprox(d, 1e-12)) return flats_;
        flats_.clear();
        const TriangleMesh& m = *input_.mesh;
        const double square = std::cos(0.01 * kPi / 180.0);
        for (const auto& t : m.triangles) {
            const Vector3d& a = m.vertices[std::size_t(t[0])];
            const Vector3d n =
                (m.vertices[std::size_t(t[1])] - a).cross(m.vertices[std::size_t(t[2])] - a);
            const double len = n.norm();
            if (len > 0.0 && std::abs(n.dot(d)) >= square * len) flats_.push_back(a.dot(d));
        }
        std::sort(flats_.begin(), flats_.end());
        flats_.erase(std::unique(flats_.begin(), flats_.end(),
                                 [](double x, double y) { return y - x <= 1e-9; }),
                     flats_.end());
        flat_dir_ = d;
        return flats_;
    }

    // Sec. 4.2.2's thicknesses: max_layer, then a quarter less each time down to min_layer.
    std::vector<double> search_thicknesses() const {
        std::vector<double> out;
        for (double delta = params_.max_layer_mm;;) {
            out.push_back(delta);
            if (delta <= params_.min_layer_mm) break;
            delta = std::max(params_.min_layer_mm, delta - delta / 4.0);
        }
        return out;
    }

    // The thicknesses Sec. 4.2.2 tries above `lower`, thickest first: max_layer, then a quarter
    // less each time down to min_layer (the search's own), and in between those putting a plane
    // parallel to the lower one onto a face square to it. A layer deposits the section just above
    // its lower plane, swept to its upper one: across a ceiling (the top over a closed box's
    // cavity, a shelf's underside) it lays the walls only, and the ceiling above its underside is
    // never laid; across a floor (the cavity's, a step's top) it lays the section below into the
    // space above. The volumetric bound may not even see it: its sections can all fall on one side
    // of a face near a plane (a 0.5 mm ceiling over a 49 mm cavity lost 1200 of the box's
    // 7351 mm^3, one layer flagged; a 20 mm cube's first layer filled 0.125 mm of its cavity). So
    // where a plane can fall on such a face, the first above the lower plane, none crosses it, and
    // none falls less than min_layer below it, which would leave the next layer no choice but to.
    std::vector<double> deltas(const PlanarRegions& lower) const {
        const double min_layer = params_.min_layer_mm, max_layer = params_.max_layer_mm;
        std::vector<double> out = search_thicknesses();
        const Vector3d& d = lower.plane.normal;
        const double from = d.dot(lower.plane.origin);
        const std::vector<double>& flats = flat_offsets(d);
        const auto first = std::lower_bound(flats.begin(), flats.end(), from + min_layer - 1e-9);
        if (first != flats.end() && *first - from <= max_layer + 1e-9) {
            const double face = *first;
            out.erase(std::remove_if(
                          out.begin(), out.end(),
                          [&](double delta) { return from + delta > face - min_layer + 1e-9; }),
                      out.end());
            out.push_back(std::clamp(face - from, min_layer, max_layer));
        }
        std::sort(out.begin(), out.end(), std::greater<double>());
        out.erase(
            std::unique(out.begin(), out.end(), [](double x, double y) { return x - y <= 1e-9; }),
            out.end());
        return out;
    }

    PlanarRegions section_above(const Plane& plane) const {
        const Plane cut = make_plane(plane.origin + offset_ * plane.normal, plane.normal);
        return planar_regions(slice_mesh(*input_.mesh, cut), plane);
    }

    // The root's first region: the section just above the build plate, and with it what the part
    // holds half a thinnest layer above the plate, as a planar slicer's section at the middle of
    // its first layer would. The plate carries it all: a bottom face a hundredth of a mm off
    // flat (a CAD model's step, a face tilted by rounding), or a recess in it no deeper, is
    // laid or filled by the first layer instead of hanging in the second (half of a block whose
    // bottom was stepped 0.01 mm was left out of the first layer, 720 mm^2 unsupported above
    // it). (Eq. 9's samples, from an eighth of the layer up, need not see what it fills.) A
    // section just above the plate that is empty stays so: no material at the base is an error.
    PlanarRegions first_above_plate(const Plane& base) const {
        const Vector3d& n = base.normal;
        std::vector<Section> cut =
            slice_mesh(*input_.mesh, {make_plane(base.origin + offset_ * n, n),
                                      make_plane(base.origin + 0.5 * params_.min_layer_mm * n, n)});
        Regions2 at_plate, above;
        for (const SectionRegion& r : cut[0].regions) at_plate.push_back(r.shape);
        for (const SectionRegion& r : cut[1].regions) above.push_back(r.shape);
        // Regions2 share one PlaneFrame(n): the two sections' planes differ in offset only.
        // Nothing beside the section at the plate but the Booleans' rounding: that section as
        // it is. (Not a share of the footprint: a post beside a 200 mm block, 0.1 mm off the
        // plate, is 36 mm^2 and must be laid all the same.)
        if (cut[0].empty() || area(difference(above, at_plate)) <= 1e-9 * cut[0].area)
            return planar_regions(cut[0], base);
        Section both;
        both.plane = cut[0].plane;
        for (Region2& r : union_of(at_plate, above)) {
            SectionRegion region;
            region.area = area(r);
            region.shape = std::move(r);
            both.area += region.area;
            both.regions.push_back(std::move(region));
        }
        return planar_regions(both, base);
    }

    void thickness_range(const PlanarRegions& lower, const Plane& upper, double& tmin,
                         double& tmax) const {
        tmin = std::numeric_limits<double>::infinity();
        tmax = -tmin;
        for (const Vector3d& x : lower.outline) {
            const double t = -upper.signed_distance(x);
            tmin = std::min(tmin, t);
            tmax = std::max(tmax, t);
        }
    }

    // One candidate plane. `count_on_next`: count_on_the_next() too.
    Candidate evaluate(const PlanarRegions& lower, const Vector3d& d, const Vector3d& p_upper,
                       double along, double delta, bool count_on_next) const;
    // The layer above `at`: search()'s, among thicknesses below `cap` (none left, or no layer
    // fits below it: nullopt), then, `counting`, thickened where it may count on the next layer
    // (Slicing.hpp); `below` is the layer under it (null for the first), `index` its index.
    std::optional<Candidate> choose(const Ground& at, const Layer* below, const Plane& base,
                                    std::size_t index, bool counting, double cap, int& tries) const;
    // Sec. 4.2.2's search proper, with min_layer's allowance for the next layer; each candidate
    // it evaluates is noted in `tried`.
    struct Tried {
        Vector3d normal;
        double delta = 0.0;
        bool meets_eq9 = false;  // and the thickness bounds
    };
    std::optional<Candidate> search(const Ground& at, std::size_t index, double cap,
                                    std::vector<Tried>& tried, int& tries) const;
    // The layers above `at`, `counting` on the next layer or not (Slicing.hpp); nullopt where
    // counting stepped back too often. `counted`, when given, is set where counting changed
    // anything (a layer thickened, or counting on the next); where not, the layers are those
    // chosen without counting.
    std::optional<std::vector<Layer>> build(const Plane& base, Ground at, bool counting,
                                            bool* counted = nullptr) const;
    // Where min_layer's allowance leaves c.next unsupported but one of c's thinnest does: the
    // thinnest of Sec. 4.2.2's thicknesses above min_layer that supports it, c.promise (else 0).
    void count_on_the_next(Candidate& c) const;
    Layer make_layer(const Candidate& c, const Ground& at, const Plane& base, const Layer* below,
                     int tries) const;

    const ComponentSlicingInput& input_;
    const LayerParams& params_;
    const Progress& progress_;
    double volume_ = 0.0;  // the mesh's: the layers' material over it is the progress
    Guide guide_;
    double offset_ = 0.0;                       // Eq. 6's Delta
    double allowance_ = 1.0;                    // tan(overhang angle)
    mutable std::optional<Vector3d> flat_dir_;  // flat_offsets()' last d, and its offsets
    mutable std::vector<double> flats_;
};

Candidate ComponentSlicer::evaluate(const PlanarRegions& lower, const Vector3d& d,
                                    const Vector3d& p_upper, double along, double delta,
                                    bool count_on_next) const {
    Candidate c;
    c.along = along;
    c.delta = delta;
    if (angle_deg(d, lower.plane.normal) < 1e-9) {
        // Parallel to the lower plane: exactly delta above it (the guide may lean a little
        // against d, which must not eat into the thickness), where the guide crosses that plane.
        const double offset = d.dot(lower.plane.origin) + delta;
        c.upper = make_plane(p_upper + (offset - d.dot(p_upper)) * d, d);
        if (const auto s = guide_.crossing(c.upper, along)) c.along = *s;
    } else {
        c.upper = make_plane(p_upper, d);
    }
    const double min_layer = params_.min_layer_mm, max_layer = params_.max_layer_mm;
    // Past 80 degrees from the lower plane's normal a layer is a sliver standing on its edge.
    if (d.dot(lower.plane.normal) < std::cos(80.0 * kPi / 180.0)) return c;
    double tmin = 0.0, tmax = 0.0;
    thickness_range(lower, c.upper, tmin, tmax);

    // Ending: never leave above U a height no layers can fill, one thinner than min_layer or
    // (when max_layer < 2 min_layer) one between k max_layer and (k + 1) min_layer. A height a
    // takes at least ceil(a / max_layer) layers, which fit when that many min_layers do.
    const double above = top_along(d) - d.dot(c.upper.origin);
    const auto fillable = [&](double a) {
        return std::abs(a) <= kLengthTolerance ||
               (a > 0.0 && std::ceil(a / max_layer - 1e-9) * min_layer <= a + kLengthTolerance);
    };
    // U moved by `shift` along d, and P_upper with it: where the guide crosses U, or (a guide
    // parallel to U) as far along the guide as the shift takes it.
    const auto move_upper = [&](double shift) {
        c.upper = make_plane(c.upper.origin + shift * d, d);
        tmin += shift;
        tmax += shift;
        if (const auto s = guide_.crossing(c.upper, along))
            c.along = *s;
        else
            c.along = along + shift / std::max(d.dot(guide_.direction(along)), 0.1);
    };
    if (above < -kLengthTolerance) {
        // U lies past the top of the material: down onto it, the last layer (thinner than
        // min_layer only when less than that was left).
        move_upper(above);
        c.final = true;
    } else if (!fillable(above)) {
        // Moving U up by `shift` thickens this layer and leaves above - shift. In turn: up onto
        // the top (the last layer), up to the fillable height just below (k max_layer), down to
        // the one just above ((k + 1) min_layer, k = floor(above / max_layer)), else a thin last
        // layer where less than min_layer is left in all.
        const double k = std::floor(above / max_layer);
        const double up_to_top = above, up = above - k * max_layer;
        const double down = above - (k + 1.0) * min_layer;
        auto fits = [&](double shift) {
            return tmax + shift <= max_layer + kLengthTolerance &&
                   tmin + shift >= min_layer - kLengthTolerance;
        };
        // None fits: U stays, and what is left ends in a thin last layer.
        double shift = 0.0;
        if (fits(up_to_top)) {
            shift = up_to_top;
            c.final = true;
        } else if (k >= 1.0 && fits(up)) {
            shift = up;
        } else if (fits(down)) {
            shift = down;
        } else if (tmax + up_to_top <= max_layer + kLengthTolerance) {
            shift = up_to_top;
            c.final = true;
        }
        move_upper(shift);
    }
    c.min_thickness = tmin;
    c.max_thickness = tmax;
    c.thickness_ok = tmax <= max_layer + kLengthTolerance &&
                     (tmin >= min_layer - kLengthTolerance || (c.final && tmin > 0.0));
    if (!c.thickness_ok) return c;

    // VolDiff by sections normal to d between the lowest point of L over the region and U.
    const PlaneFrame frame(d);
    c.region = project(lower, frame);
    const double h_top = d.dot(c.upper.origin);
    double h_low = h_top - tmax;
    const int k = params_.volume_samples;
    std::vector<Plane> planes;
    planes.reserve(std::size_t(k) + 1);
    for (int i = 0; i < k; ++i)
        planes.push_back(make_plane(d * (h_low + (i + 0.5) * (h_top - h_low) / k), d));
    if (!c.final) planes.push_back(make_plane(c.upper.origin + offset_ * d, d));
    const std::vector<Section> sections = slice_mesh(*input_.mesh, planes);
    const double slab = (h_top - h_low) / k;
    const Eigen::AlignedBox2d box = bounds_of(c.region);
    double sym = 0.0;
    for (int i = 0; i < k; ++i) {
        Regions2 a = c.region, b;
        for (const SectionRegion& r : sections[std::size_t(i)].regions) b.push_back(r.shape);
        Eigen::AlignedBox2d all = box;
        all.extend(bounds_of(b));
        const double h = d.dot(planes[std::size_t(i)].origin);
        if (const auto above_lower = below_height(lower.plane, frame, h, all)) {
            a = intersection(a, *above_lower);
            b = intersection(b, *above_lower);
        }
        const double area_a = area(a), area_b = area(b);
        const double common = (area_a > 0.0 && area_b > 0.0) ? area(intersection(a, b)) : 0.0;
        c.volume += area_a * slab;
        c.material += area_b * slab;
        sym += (area_a + area_b - 2.0 * common) * slab;
    }
    c.difference =
        c.volume > 0.0 ? std::max(0.0, sym) / c.volume : std::numeric_limits<double>::infinity();
    if (!c.final) {
        c.next = planar_regions(sections.back(), c.upper);
        if (c.next.empty()) c.final = true;
    }
    if (!c.next.empty()) {
        const Regions2 grown = offset(c.region, min_layer * allowance_);
        c.unsupported_next = area(difference(project(c.next, frame), grown));
        if (count_on_next) count_on_the_next(c);
    }
    return c;
}

void ComponentSlicer::count_on_the_next(Candidate& c) const {
    const double min_layer = params_.min_layer_mm, tmin = c.min_thickness;
    const double tolerance = tolerance_of(c);
    if (c.final || c.next.empty() || c.unsupported_next <= tolerance ||
        tmin <= min_layer + kLengthTolerance)
        return;
    const Regions2 next = project(c.next, PlaneFrame(c.upper.normal));
    const auto supports = [&](double thickness) {
        return area(difference(next, offset(c.region, thickness * allowance_))) <= tolerance;
    };
    if (!supports(tmin)) return;
    c.promise = tmin;
    std::vector<double> ladder = search_thicknesses();
    std::reverse(ladder.begin(), ladder.end());
    for (const double t : ladder) {
        if (t <= min_layer + kLengthTolerance) continue;
        if (t >= tmin - kLengthTolerance) break;
        if (supports(t)) {
            c.promise = t;
            return;
        }
    }
}

std::vector<Layer> ComponentSlicer::run() {
    const Plane base = make_plane(input_.base.origin, input_.base.normal);
    PlanarRegions lower =
        input_.support_meshes.empty() ? first_above_plate(base) : section_above(base);
    if (lower.empty())
        invalid("component " + std::to_string(input_.component) +
                ": no material just above its base plane (a base face that does not lie on the "
                "component, a build direction pointing away from it, or a mesh whose surface "
                "crosses itself there)");
    const double height = top_along(base.normal) - base.normal.dot(base.origin);
    if (height < params_.min_layer_mm - kLengthTolerance)
        invalid("component " + std::to_string(input_.component) + " is only " + mm(height) +
                " tall along its build direction, less than min_layer (" +
                mm(params_.min_layer_mm) +
                "): no layer fits; lower min_layer (lengths are in millimetres: scale a part "
                "drawn in metres or inches to millimetres)");

    const double base_tilt = tilt_from_plate_deg(base.normal);
    if (base_tilt > params_.max_tilt_deg + 1e-9)
        invalid("component " + std::to_string(input_.component) + " is built along (" +
                format_number(base.normal.x() + 0.0) + ", " +  // + 0: -0 prints as 0
                format_number(base.normal.y() + 0.0) + ", " + format_number(base.normal.z() + 0.0) +
                "), " + format_number(base_tilt) +
                " degrees from the build plate's normal, past max_tilt (" +
                format_number(params_.max_tilt_deg) +
                " degrees): the machine cannot reach it (decompose with the same max_tilt)");
    // Counting on the next layer (Slicing.hpp): kept where nothing is left unsupported or where
    // it changed nothing, else compared with the layers chosen without it.
    std::vector<Layer> layers;
    const Ground ground{std::move(lower), guide_.crossing(base, 0.0).value_or(0.0), 0.0};
    if (params_.require_support) {
        bool counted = false;
        if (std::optional<std::vector<Layer>> counting = build(base, ground, true, &counted)) {
            if (!counted || std::none_of(counting->begin(), counting->end(), hangs))
                return *counting;
            layers = std::move(*counting);
        }
    }
    std::vector<Layer> plain = *build(base, ground, false);
    if (layers.empty()) return plain;
    // Kept where it leaves no more unsupported than the layers chosen without it, at worst and in
    // all (within rounding).
    const auto worst_and_all = [](const std::vector<Layer>& ls) {
        double worst = 0.0, all = 0.0;
        for (const Layer& l : ls) {
            worst = std::max(worst, l.unsupported_area_mm2);
            all += l.unsupported_area_mm2;
        }
        return std::pair{worst, all};
    };
    const auto [worst_a, all_a] = worst_and_all(layers);
    const auto [worst_b, all_b] = worst_and_all(plain);
    const auto within = [](double a, double b) { return a <= b + 1e-9 * std::max(1.0, b); };
    return within(worst_a, worst_b) && within(all_a, all_b) ? layers : plain;
}

std::optional<std::vector<Layer>> ComponentSlicer::build(const Plane& base, Ground at,
                                                         bool counting, bool* counted) const {
    if (counted) *counted = false;
    std::vector<Layer> layers;
    double material = 0.0;        // of the layers so far
    std::vector<Ground> grounds;  // where each layer was chosen
    std::vector<double> deltas;   // and the thickness its search was at
    // How layer i is chosen again: below this thickness, or (plain) without counting on the next.
    std::vector<double> caps;
    std::vector<bool> plain;
    std::size_t backtracks = 0;
    const auto go_back = [&]() {
        // Layer k, counting on the next in vain: where it need not rest on a thickness the layer
        // under it counted on, as the search alone chooses it; else thinner.
        const std::size_t k = layers.size() - 1;
        caps.resize(k + 1, std::numeric_limits<double>::infinity());
        plain.resize(k + 1, false);
        if (grounds[k].promised > 0.0)
            caps[k] = deltas[k];
        else
            plain[k] = true;
        material -= layers.back().material_volume_mm3;
        layers.pop_back();
        deltas.pop_back();
        at = std::move(grounds.back());
        grounds.pop_back();
    };
    while (!at.lower.empty()) {
        if (layers.size() >= params_.max_layers)
            invalid("component " + std::to_string(input_.component) + " needs more than " +
                    std::to_string(params_.max_layers) + " layers");
        const std::size_t i = layers.size();
        const Layer* below = layers.empty() ? nullptr : &layers.back();
        const double cap = i < caps.size() ? caps[i] : std::numeric_limits<double>::infinity();
        const bool count = counting && !(i < plain.size() && plain[i]);
        int tries = 0;
        std::optional<Candidate> chosen = choose(at, below, base, i, count, cap, tries);
        Layer layer;
        if (chosen) layer = make_layer(*chosen, at, base, below, tries);
        if (at.promised > 0.0 && (!chosen || hangs(layer))) {
            // The layer below counted on this one in vain (or this one has no thinner choice
            // left): choose that one again (go_back). A search this long gives up counting.
            if (++backtracks > 4 * (layers.size() + 8)) return std::nullopt;
            go_back();
            continue;
        }
        if (!chosen) {
            chosen =
                choose(at, below, base, i, false, std::numeric_limits<double>::infinity(), tries);
            layer = make_layer(*chosen, at, base, below, tries);
        }
        const Candidate& c = *chosen;
        material += layer.material_volume_mm3;
        layers.push_back(std::move(layer));
        grounds.push_back(at);
        deltas.push_back(c.delta);
        // count_on_the_next() sets a promise only where the next footprint needs one.
        const bool promises = c.promise > 0.0;
        if (counted && (c.thickened || promises)) *counted = true;
        if (c.final) break;
        progress_(volume_ > 0.0 ? material / volume_ : 0.0);
        at = Ground{c.next, c.along, promises ? c.promise : 0.0};
    }
    return layers;
}

Layer ComponentSlicer::make_layer(const Candidate& c, const Ground& at, const Plane& base,
                                  const Layer* below, int tries) const {
    Layer layer;
    layer.component = input_.component;
    layer.plane = c.upper;
    layer.lower = at.lower.plane;
    layer.regions = c.region;
    layer.area_mm2 = area(layer.regions);
    layer.min_thickness_mm = c.min_thickness;
    layer.max_thickness_mm = c.max_thickness;
    layer.volume_mm3 = c.volume;
    layer.material_volume_mm3 = c.material;
    layer.volume_difference = c.difference;
    layer.meets_volume_difference = c.difference <= params_.max_volume_difference;
    layer.axis_point = guide_.point(c.along);
    layer.axis_node = guide_.node_near(c.along);
    layer.tries = tries;
    if (below) {
        layer.unsupported = unsupported_regions_sloped(layer, *below, allowance_);
    } else if (!input_.support_meshes.empty()) {
        // The first layer of a child rests on what was deposited before it, just below the
        // base face.
        layer.unsupported = unsupported_regions_sloped(
            layer, support_below(input_.support_meshes, base, offset_), allowance_);
    }
    layer.unsupported_area_mm2 = area(layer.unsupported);
    return layer;
}

std::optional<Candidate> ComponentSlicer::search(const Ground& at, std::size_t index, double cap,
                                                 std::vector<Tried>& tried, int& tries) const {
    const double eps_angle = params_.eps_angle_deg;
    const Vector3d& d_lower = at.lower.plane.normal;
    std::optional<Candidate> accepted, fallback, any_fit;
    // Of the tilted candidates that meet Eq. 9 but leave the next layer unsupported, the one
    // leaving least per mm of height (the first, thickest, of equals).
    std::optional<Candidate> tilted;
    auto meets_eq9 = [&](const Candidate& c) {
        return c.thickness_ok && c.difference <= params_.max_volume_difference;
    };
    // Layers of different thickness are compared by what they leave unsupported per mm of
    // height built (over the mean thickness: the prism's volume over its region's area), so
    // that a wedge is not judged worse than a thin parallel layer for being thicker on one
    // side.
    auto mean_thickness = [](const Candidate& c) {
        return std::max(c.volume / std::max(area(c.region), 1e-12), 1e-9);
    };
    auto unsupported_rate = [&](const Candidate& c) {
        return c.unsupported_next / mean_thickness(c);
    };
    auto rate_tolerance = [&](const Candidate& c) { return tolerance_of(c) / mean_thickness(c); };
    auto supported = [&](const Candidate& c) {
        return !params_.require_support || c.unsupported_next <= tolerance_of(c);
    };
    auto note = [&](const Candidate& c) {
        tried.push_back({c.upper.normal, c.delta, meets_eq9(c)});
    };
    // Sec. 4.2.2: from delta = max_layer, the guide's direction at P_upper, averaged with
    // D_lower until Eq. 9 holds (and the next layer is supported) or the two are within
    // eps_angle, then a shorter delta.
    std::vector<double> thicknesses = deltas(at.lower);
    thicknesses.erase(std::remove_if(thicknesses.begin(), thicknesses.end(),
                                     [&](double t) { return t >= cap - kLengthTolerance; }),
                      thicknesses.end());
    if (thicknesses.empty()) return std::nullopt;
    for (const double delta : thicknesses) {
        if (accepted) break;
        const double along = at.s_lower + delta;
        const Vector3d p_upper = guide_.point(along);
        Vector3d d = guide_.direction(along);
        // A guide doubling back, or turning by less than a tenth of eps_angle, or by so little
        // that the plane moves less than a tenth of min_layer across the layer below (centroid
        // noise: a disc's shares taken round its stem left its centroid 3 microns off the
        // stem's, and the 0.2 degree tilt laid the disc's underside in two layers, both over
        // nothing): keep the lower direction.
        d = within_reach(d, d_lower);
        const double turn = angle_deg(d, d_lower);
        if (d.dot(d_lower) <= 0.0 || turn < 0.1 * eps_angle ||
            std::sin(turn * kPi / 180.0) * reach_from(at.lower, p_upper) <
                0.1 * params_.min_layer_mm)
            d = d_lower;
        // Where the part is a prism along D_lower over the first thickness tried (the
        // thickest, or up to the first face square to L), the parallel layer deposits it
        // exactly. If the guide then runs on along D_lower (its next segment within
        // eps_angle), its turn was a jog: the sections changed shape, not the part's
        // direction (a pocket sunk in a plate's top moved the centroids 0.6 mm aside, and the
        // layers tilted 1.8 degrees, the last ones wedges 0.9 mm proud of the top). Where it
        // turns on, a bend begins above the prism, and the layers start turning as before,
        // thinner if need be (a hollow bend's riser, ended by a thick parallel layer, left
        // the bend's layers 6 degrees short of it and 1.9 mm^2 hanging).
        if (delta == thicknesses.front() && angle_deg(d, d_lower) >= 1e-9 &&
            guide_.runs_on_along(along, d_lower, eps_angle)) {
            progress_.check();
            ++tries;
            Candidate c = evaluate(at.lower, d_lower, p_upper, along, delta, false);
            note(c);
            if (meets_eq9(c) && supported(c) && c.difference <= kPrismDifference) {
                accepted = std::move(c);
                break;
            }
        }
        for (;;) {
            progress_.check();
            ++tries;
            const bool parallel = angle_deg(d, d_lower) < 1e-9;
            Candidate c = evaluate(at.lower, d, p_upper, along, delta, false);
            note(c);
            if (meets_eq9(c) && supported(c)) {
                accepted = std::move(c);
                break;
            }
            if (c.thickness_ok && !any_fit) any_fit = c;  // the last resort, below
            if (!parallel && meets_eq9(c) &&
                (!tilted || unsupported_rate(c) < unsupported_rate(*tilted) - rate_tolerance(c)))
                tilted = c;
            if (parallel || angle_deg(d, d_lower) < eps_angle) break;
            d = within_reach((d + d_lower).normalized(), d_lower);
        }
    }
    // Nothing met both (a tilt the thickness bounds forbid, an overhang of the part's own, a
    // dome's cap): planar adaptive along D_lower, the thickest layer that meets Eq. 9 with
    // the next layer supported, else the thickest that meets Eq. 9, else min_layer flagged.
    if (!accepted) {
        std::optional<Candidate> eq9_only;
        for (const double delta : thicknesses) {
            progress_.check();
            ++tries;
            const double along = at.s_lower + delta;
            Candidate c = evaluate(at.lower, d_lower, guide_.point(along), along, delta, false);
            note(c);
            if (meets_eq9(c) && supported(c)) {
                accepted = std::move(c);
                break;
            }
            // Thick to thin: a thinner layer replaces a thicker one only when it leaves the
            // next layer less unsupported (a wall slightly past the overhang angle is built
            // in thin layers, as adaptive slicers do, rather than in thick ones that overhang).
            if (meets_eq9(c) &&
                (!eq9_only || c.unsupported_next < eq9_only->unsupported_next - tolerance_of(c)))
                eq9_only = c;
            if (c.thickness_ok) fallback = std::move(c);
        }
        // A wall past the overhang angle that the guide leans along (an arm leaning 60
        // degrees off a column): no single tilt makes the next layer supported, but tilting
        // gets there layer by layer. A tilted layer replaces the parallel one when it leaves
        // less unsupported per mm of height (a wedge leaves more in all than a thin parallel
        // layer, being thicker, but the layers after it leave less).
        if (!accepted && tilted &&
            (!eq9_only ||
             unsupported_rate(*tilted) < unsupported_rate(*eq9_only) - rate_tolerance(*tilted)))
            accepted = std::move(tilted);
        if (!accepted && eq9_only) accepted = std::move(eq9_only);
        // No parallel layer fits the thickness bounds at all, but a tilted one did.
        if (!accepted && !fallback && any_fit) fallback = std::move(any_fit);
    }
    if (!accepted) {
        // Below a cap (chosen again, run()), no error: the caller steps back further.
        if (std::isfinite(cap) && (!fallback || params_.strict)) return std::nullopt;
        if (!fallback)
            invalid("component " + std::to_string(input_.component) + ": no layer between " +
                    mm(params_.min_layer_mm) + " and " + mm(params_.max_layer_mm) +
                    " fits above the plane through (" + format_number(at.lower.plane.origin.x()) +
                    ", " + format_number(at.lower.plane.origin.y()) + ", " +
                    format_number(at.lower.plane.origin.z()) +
                    "); the layer thickness bounds are too narrow for this part");
        if (params_.strict) {
            std::ostringstream s;
            s << "component " << input_.component << ", layer " << index + 1 << ": even a "
              << mm(params_.min_layer_mm) << " layer differs from the part by "
              << fallback->difference * 100.0 << " % of its volume, over max_volume_difference ("
              << params_.max_volume_difference * 100.0 << " %)";
            throw Error(ErrorCode::GeometryFailure, s.str());
        }
        accepted = std::move(fallback);
    }
    return accepted;
}

std::optional<Candidate> ComponentSlicer::choose(const Ground& at, const Layer* below,
                                                 const Plane& base, std::size_t index,
                                                 bool counting, double cap, int& tries) const {
    std::vector<Tried> tried;
    std::optional<Candidate> found = search(at, index, cap, tried, tries);
    if (!found || (!counting && at.promised <= 0.0)) return found;
    // The search's layer, thicker along the same normal where the next layer can be counted on
    // to support what it leaves (see run()), and where it rests on the layer below, which may
    // have counted on this one: the thickest such, else the search's.
    // Its own footprint: supported by the layer below with this one's sloped allowance (the
    // check the layer reports), where that layer counted on it being at.promised thick.
    auto rests = [&](const Candidate& c) {
        return at.promised <= 0.0 || below == nullptr ||
               c.min_thickness >= at.promised - kLengthTolerance ||
               !hangs(make_layer(c, at, base, below, 0));
    };
    const Vector3d d = found->upper.normal;
    for (const double delta : deltas(at.lower)) {
        if (delta >= cap - kLengthTolerance) continue;
        if (delta <= found->delta + kLengthTolerance) break;
        const double along = at.s_lower + delta;
        // Not where the guide turns away from d: the layers turn with it, not thicken.
        if (angle_deg(guide_.direction(along), d) > params_.eps_angle_deg) continue;
        // Nor where the search found this layer past the thickness or volumetric bounds.
        if (std::any_of(tried.begin(), tried.end(), [&](const Tried& t) {
                return !t.meets_eq9 && std::abs(t.delta - delta) <= kLengthTolerance &&
                       (t.normal - d).norm() <= 1e-12;
            }))
            continue;
        progress_.check();
        ++tries;
        Candidate c = evaluate(at.lower, d, guide_.point(along), along, delta, counting);
        const bool next = c.unsupported_next <= tolerance_of(c) || c.promise > 0.0;
        if (c.thickness_ok && c.difference <= params_.max_volume_difference && next && rests(c)) {
            c.thickened = true;
            return c;
        }
    }
    // The search's own layer may count on the next too.
    if (counting) count_on_the_next(*found);
    return found;
}

}  // namespace

void validate(const LayerParams& p) {
    auto positive = [](double x, const char* name) {
        if (!(std::isfinite(x) && x > 0.0))
            invalid(std::string(name) + " must be a positive, finite number, got " +
                    format_number(x));
    };
    positive(p.min_layer_mm, "min_layer");
    positive(p.max_layer_mm, "max_layer");
    // Layer planes are placed by adding a thickness to an offset: beyond this, the sum would lose
    // the part's whole height to rounding (1e300 gave one layer 32 mm thick on a 30 mm box).
    if (p.max_layer_mm > kMaxLayerLimitMm)
        invalid("max_layer must be at most " + mm(kMaxLayerLimitMm) + ", got " +
                mm(p.max_layer_mm));
    if (p.min_layer_mm > p.max_layer_mm)
        invalid("min_layer (" + mm(p.min_layer_mm) + ") is greater than max_layer (" +
                mm(p.max_layer_mm) + ")");
    positive(p.max_volume_difference, "max_volume_difference");
    if (!(p.eps_angle_deg > 0.0 && p.eps_angle_deg < 90.0))
        invalid("eps_angle must be in (0, 90) degrees, got " + format_number(p.eps_angle_deg));
    if (!(std::isfinite(p.initial_offset_mm) && p.initial_offset_mm >= 0.0 &&
          p.initial_offset_mm < p.min_layer_mm))
        invalid("initial_offset must be in [0, min_layer) mm, got " +
                format_number(p.initial_offset_mm));
    if (!(p.overhang_angle_deg >= 0.0 && p.overhang_angle_deg < 90.0))
        invalid("overhang_angle must be in [0, 90) degrees, got " +
                format_number(p.overhang_angle_deg));
    if (!(p.max_tilt_deg >= 90.0 && p.max_tilt_deg <= 180.0))
        invalid("max_tilt must be in [90, 180] degrees, got " + format_number(p.max_tilt_deg));
    if (p.volume_samples < 1 || p.volume_samples > 64)
        invalid("volume_samples must be in [1, 64], got " + std::to_string(p.volume_samples));
    if (p.max_layers < 1) invalid("max_layers must be at least 1");
}

double base_offset(const LayerParams& params) {
    return params.initial_offset_mm > 0.0 ? params.initial_offset_mm : 1e-3 * params.min_layer_mm;
}

double overhang_allowance(const LayerParams& params) {
    return std::tan(params.overhang_angle_deg * kPi / 180.0);
}

double tilt_from_plate_deg(const Eigen::Vector3d& direction) {
    return std::atan2(Vector2d(direction.x(), direction.y()).norm(), direction.z()) * 180.0 / kPi;
}

bool leans_past(const Eigen::Vector3d& n, const Eigen::Vector3d& d, double overhang_deg) {
    return n.dot(d) < -std::sin(overhang_deg * kPi / 180.0) - 1e-6;
}

void validate(const LayerParams& p, const TriangleMesh& mesh, const std::string& what) {
    validate(p);
    const Eigen::AlignedBox3d box = bounding_box(mesh);
    const double size = box.isEmpty() ? 0.0 : box.diagonal().norm();
    if (p.min_layer_mm < kMinLayerFraction * size)
        invalid("min_layer " + mm(p.min_layer_mm) + " is too small for " + what + ", " + mm(size) +
                " across: less than a millionth of its size; the least is " +
                mm(kMinLayerFraction * size));
}

namespace {

// A region's loops (outer first, then holes) in 3-D, on `plane`, from PlaneFrame(plane.normal)
// coordinates.
std::vector<std::vector<Vector3d>> region_loops_3d(const Region2& region, const Plane& plane) {
    const PlaneFrame frame(plane.normal);
    std::vector<std::vector<Vector3d>> loops;
    auto add = [&](const Polygon2& p) {
        std::vector<Vector3d> loop;
        loop.reserve(p.points.size());
        for (const Vector2d& q : p.points) loop.push_back(frame.to_3d(q, plane));
        loops.push_back(std::move(loop));
    };
    add(region.outer);
    for (const Polygon2& h : region.holes) add(h);
    return loops;
}

}  // namespace

std::vector<std::vector<Vector3d>> Layer::loops_3d(std::size_t r) const {
    return region_loops_3d(regions.at(r), plane);
}

std::vector<std::vector<Vector3d>> Layer::unsupported_loops_3d(std::size_t r) const {
    return region_loops_3d(unsupported.at(r), lower);
}

double Layer::thickness_at(const Vector3d& point_on_plane) const {
    return lower.normal.dot(point_on_plane - lower.origin) / lower.normal.dot(plane.normal);
}

Regions2 unsupported_regions(const Layer& upper, const Layer& lower, double allowance_mm) {
    // The upper layer's footprint: its region moved back along its normal onto its lower plane
    // (which is the lower layer's top), then seen along the lower layer's normal.
    const PlaneFrame up(upper.plane.normal), down(lower.plane.normal);
    const double denom = upper.lower.normal.dot(upper.plane.normal);
    Regions2 footprint;
    footprint.reserve(upper.regions.size());
    auto move = [&](const Polygon2& p) {
        Polygon2 out;
        out.points.reserve(p.points.size());
        for (const Vector2d& q : p.points) {
            const Vector3d x = up.to_3d(q, upper.plane);
            const Vector3d on_lower =
                x - upper.plane.normal * (upper.lower.signed_distance(x) / denom);
            out.points.push_back(down.to_2d(on_lower));
        }
        return out;
    };
    for (const Region2& r : upper.regions) {
        Region2 f{move(r.outer), {}};
        for (const Polygon2& h : r.holes) f.holes.push_back(move(h));
        footprint.push_back(std::move(f));
    }
    const Regions2 support =
        allowance_mm > 0.0 ? offset(lower.regions, allowance_mm) : lower.regions;
    return difference(footprint, support);
}

double unsupported_area(const Layer& upper, const Layer& lower, double allowance_mm) {
    return area(unsupported_regions(upper, lower, allowance_mm));
}

Regions2 unsupported_regions_sloped(const Layer& upper, const Layer& lower, double slope) {
    const double t0 = std::max(0.0, upper.min_thickness_mm), t1 = upper.max_thickness_mm;
    Regions2 out = unsupported_regions(upper, lower, t0 * slope);
    if (out.empty() || !(slope > 0.0) || !(t1 - t0 > kSlopedAllowanceBandMm)) return out;
    // The thickness over the footprint, t = a + b.q: affine in the footprint's 2-D coordinates q
    // (PlaneFrame(lower.plane.normal)), whose points lie on the upper layer's lower plane.
    const PlaneFrame down(lower.plane.normal);
    const Plane& base = upper.lower;
    auto thickness = [&](const Vector2d& q) {
        const Vector3d in_frame = down.u * q.x() + down.v * q.y();
        const Vector3d on_base = in_frame + down.normal * (base.signed_distance(in_frame) /
                                                           -base.normal.dot(down.normal));
        return -upper.plane.signed_distance(on_base);
    };
    const double a = thickness(Vector2d::Zero());
    const Vector2d b(thickness(Vector2d::UnitX()) - a, thickness(Vector2d::UnitY()) - a);
    if (!(b.norm() > 1e-12)) return out;
    const Vector2d g = b.normalized(), side(-g.y(), g.x());
    Eigen::AlignedBox2d box = bounds_of(out);
    for (const Region2& r : lower.regions) box.extend(bounds(r));
    const double reach = box.diagonal().norm() + t1 * slope + 1.0;
    const Vector2d centre = box.center();
    const double along_far = g.dot(centre) + reach, across = side.dot(centre);
    // Band k: where the layer is at least t_k thick, the lower region grown by t_k x slope
    // supports it. Each band takes its thinnest thickness, so the allowance falls short of the
    // local one by less than a band's width x slope.
    const int bands = int(std::ceil((t1 - t0) / kSlopedAllowanceBandMm));
    for (int k = 1; k <= bands && !out.empty(); ++k) {
        const double tk = t0 + (t1 - t0) * k / bands;
        const double along = (tk - a) / b.norm();
        if (along >= along_far) break;
        Region2 thick;
        for (const auto& [s, w] :
             {std::pair{along, -reach}, {along_far, -reach}, {along_far, reach}, {along, reach}})
            thick.outer.points.push_back(g * s + side * (across + w));
        out = difference(out, intersection(offset(lower.regions, tk * slope), {thick}));
    }
    return out;
}

BaseSupport base_support(const TriangleMesh& component, const Plane& base,
                         const std::vector<const TriangleMesh*>& support,
                         const LayerParams& params) {
    validate(params);
    const Plane plane = make_plane(base.origin, base.normal);
    const double offset = base_offset(params);
    Layer first;
    first.plane = make_plane(plane.origin + offset * plane.normal, plane.normal);
    first.lower = plane;
    for (const SectionRegion& r : slice_mesh(component, first.plane).regions)
        first.regions.push_back(r.shape);
    BaseSupport out;
    if (first.regions.empty()) return out;
    out.footprint_area_mm2 = area(first.regions);
    out.unsupported_area_mm2 = unsupported_area(first, support_below(support, plane, offset),
                                                params.min_layer_mm * overhang_allowance(params));
    return out;
}

std::vector<Layer> slice_component(const ComponentSlicingInput& input, const LayerParams& params,
                                   const Progress& progress) {
    validate(params);
    if (!input.mesh || input.mesh->triangles.empty())
        invalid("component " + std::to_string(input.component) + " has no mesh to slice");
    const MeshReport report = check_mesh(*input.mesh);
    if (report.boundary_edges || report.non_manifold_edges || report.inconsistent_edges ||
        report.non_finite_vertices)
        throw Error(ErrorCode::OpenMesh,
                    "component " + std::to_string(input.component) +
                        "'s mesh is not a closed surface: it cannot be sliced");
    if (!input.base.origin.allFinite() || !input.base.normal.allFinite() ||
        input.base.normal.norm() < 1e-12)
        invalid("component " + std::to_string(input.component) +
                " has a non-finite or zero base plane");
    validate(params, *input.mesh, "component " + std::to_string(input.component));
    ComponentSlicingInput checked = input;
    checked.base = make_plane(input.base.origin, input.base.normal);
    ComponentSlicer slicer(checked, params, report.volume_mm3, progress);
    std::vector<Layer> layers = slicer.run();
    progress(1.0);
    return layers;
}

}  // namespace mas
