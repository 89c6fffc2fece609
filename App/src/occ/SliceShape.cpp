// Slicing a BREP part: its sub-components, holes filled when asked (Holes.hpp), tessellated with
// the part's deflection, then sliced as meshes (see SlicePart.hpp).
#include <BRepClass3d_SolidClassifier.hxx>
#include <algorithm>
#include <any>
#include <cmath>
#include <gp_Pnt.hxx>
#include <optional>
#include <sstream>
#include <string>

#include "ShapeImpl.hpp"
#include "mas/Angles.hpp"
#include "mas/Error.hpp"
#include "mas/Holes.hpp"
#include "mas/SlicePart.hpp"

namespace mas {

namespace {

// The solids of a component: one, or a root's feet (Decompose.hpp), each its own Shape.
std::vector<Shape> feet_of(const Shape& component) {
    std::vector<Shape> out;
    for (const TopoDS_Shape& solid : occ::solids_of(occ::occt(component)))
        out.push_back(occ::wrap(solid));
    if (out.size() < 2) return {component};  // as it is (single_solid() says what is wrong)
    return out;
}

// `more` added to `mesh` (its own vertices: the two share none).
void append(TriangleMesh& mesh, const TriangleMesh& more) {
    const int offset = int(mesh.vertices.size());
    mesh.vertices.insert(mesh.vertices.end(), more.vertices.begin(), more.vertices.end());
    for (const Eigen::Vector3i& t : more.triangles)
        mesh.triangles.push_back(t + Eigen::Vector3i::Constant(offset));
}

// The decomposition must be of this part: its components fill the part's volume (within a
// thousandth: they are cut from it by Booleans) and lie within its box. Returns that volume, mm^3.
double check_components(const Shape& part, const Decomposition& decomposition) {
    const TopoDS_Shape& whole = occ::occt(part);
    double volume = occ::volume_of(whole);
    Eigen::AlignedBox3d box = occ::tight_bounds(whole);
    const double reach = 1e-3 * box.diagonal().norm();
    box.min().array() -= reach;
    box.max().array() += reach;
    double sum = 0.0;
    try {
        for (const Component& c : decomposition.components) {
            const TopoDS_Shape& s = occ::occt(c.solid);
            sum += occ::volume_of(s);
            if (!box.contains(occ::tight_bounds(s)))
                throw Error(ErrorCode::InvalidArgument,
                            "slice: the decomposition is of another part (its components reach "
                            "outside this part's box)");
        }
    } catch (const Standard_Failure& e) {
        throw Error(ErrorCode::GeometryFailure, occ::failure_message("slice: a component", e));
    }
    // OCCT's default quadrature is off by up to 4e-3 on pieces of a torus (an eye bolt's ring
    // cut in three: 3233.74 mm^3 for 3229.87): integrated adaptively before they are refused.
    if (std::abs(sum - volume) > 1e-3 * volume) {
        try {
            volume = occ::precise_volume_of(whole, 1e-6);
            sum = 0.0;
            for (const Component& c : decomposition.components)
                sum += occ::precise_volume_of(occ::occt(c.solid), 1e-6);
        } catch (const Standard_Failure& e) {
            throw Error(ErrorCode::GeometryFailure, occ::failure_message("slice: a component", e));
        }
    }
    if (std::abs(sum - volume) > 1e-3 * volume) {
        std::ostringstream msg;
        msg << "slice: the decomposition is of another part (its components hold " << sum
            << " mm^3, this part " << volume << " mm^3)";
        throw Error(ErrorCode::InvalidArgument, msg.str());
    }
    return volume;
}

// Whether the split that made `child`, a component of `part`, cut `hole` lengthwise: at one of
// three stations along the hole (its middle and a quarter of its length from each end), the
// material round its wall lies on both sides of the child's base plane, and the child holds some
// of it but not all. The hole is then whole in no component, where fill_holes() finds only whole
// holes. Read at 16 points round each station, a fiftieth of the radius (at most 0.05 mm) outside
// the wall; points outside the part (a mouth, a slot across the wall) count for neither.
bool cuts_lengthwise(const Component& child, const TopoDS_Shape& part, const FilledHole& hole) {
    const Eigen::Vector3d& a = hole.axis;
    const Eigen::Vector3d e1 =
        (std::abs(a.x()) < 0.9 ? Eigen::Vector3d::UnitX() : Eigen::Vector3d::UnitY())
            .cross(a)
            .normalized();
    const Eigen::Vector3d e2 = a.cross(e1);
    const double radius = 0.5 * hole.diameter_mm;
    const double ring = radius + std::min(0.02 * radius, 0.05);
    const double tolerance = 1e-6;
    std::optional<BRepClass3d_SolidClassifier> in_child, in_part;
    const auto inside = [](std::optional<BRepClass3d_SolidClassifier>& c, const TopoDS_Shape& s,
                           const Eigen::Vector3d& p) {
        if (!c) c.emplace(s);
        c->Perform(gp_Pnt(p.x(), p.y(), p.z()), 1e-7);
        return c->State() == TopAbs_IN;
    };
    for (const double t : {-0.25, 0.0, 0.25}) {
        const Eigen::Vector3d centre = hole.centre + a * (t * hole.length_mm);
        std::vector<Eigen::Vector3d> points;
        bool below = false, above = false;
        for (int k = 0; k < 16; ++k) {
            const double angle = 2.0 * kPi * k / 16.0;
            points.push_back(centre + ring * (std::cos(angle) * e1 + std::sin(angle) * e2));
            const double side = child.base_normal.dot(points.back() - child.base_origin);
            below = below || side > tolerance;
            above = above || side < -tolerance;
        }
        if (!below || !above) continue;  // the plane passes beside the hole here
        bool held = false, elsewhere = false;
        for (const Eigen::Vector3d& p : points) {
            if (inside(in_child, occ::occt(child.solid), p))
                held = true;
            else if (inside(in_part, part, p))
                elsewhere = true;
            if (held && elsewhere) return true;
        }
    }
    return false;
}

// The branches of `d`'s children (the root has no split) that cut one of `holes` lengthwise
// (cuts_lengthwise), each with the first such hole: (branch, hole index). The first `upright`
// holes lean no more than `overhang_deg` off +Z, the root's build direction: they count only for
// a child built along a direction they lean more than that off, which fills them.
std::vector<std::pair<int, std::size_t>> branches_cutting(const Decomposition& d,
                                                          const TopoDS_Shape& part,
                                                          const std::vector<FilledHole>& holes,
                                                          std::size_t upright,
                                                          double overhang_deg) {
    std::vector<std::pair<int, std::size_t>> out;
    for (std::size_t c = 1; c < d.components.size(); ++c)
        for (std::size_t h = 0; h < holes.size(); ++h) {
            if (h < upright &&
                !leans_over(holes[h].axis, d.components[c].build_direction, overhang_deg))
                continue;
            if (cuts_lengthwise(d.components[c], part, holes[h])) {
                out.emplace_back(d.components[c].branch, h);
                break;
            }
        }
    return out;
}

}  // namespace

SlicedPart slice_part(const Shape& solid, const CentroidalAxis& axis,
                      const Decomposition& decomposition, const SlicePartParams& params,
                      const Progress& progress) {
    if (decomposition.components.empty())
        throw Error(ErrorCode::EmptyInput, "the decomposition has no component to slice");
    if (!(params.fill_holes_up_to_mm >= 0.0) || !std::isfinite(params.fill_holes_up_to_mm))
        throw Error(ErrorCode::InvalidArgument,
                    "fill_holes_up_to_mm, the largest hole diameter to fill, must be >= 0 mm and "
                    "finite, got " +
                        format_number(params.fill_holes_up_to_mm));
    const Shape part = solid.single_solid("the part");
    const double part_volume = check_components(part, decomposition);
    // One deflection for every component: the part's, so that a face shared by a father and its
    // child is approximated alike on both sides.
    TessellationParams tessellation = params.tessellation;
    tessellation.deflection_mm = effective_deflection(part, params.tessellation);
    std::vector<ComponentMesh> meshes;
    meshes.reserve(decomposition.components.size());
    const Progress tessellating = progress.span(0.0, 0.1,
                                                params.fill_holes_up_to_mm != 0.0
                                                    ? "filling holes, tessellating the components"
                                                    : "tessellating the components");
    std::vector<FilledHole> filled;
    std::vector<std::string> notes;
    double filled_volume = 0.0;
    for (std::size_t i = 0; i < decomposition.components.size(); ++i) {
        const Component& c = decomposition.components[i];
        tessellating(double(i) / double(decomposition.components.size()));
        const std::string what = "component " + std::to_string(i);
        ComponentMesh m;
        // Each of its solids: one, but for a root standing on several feet (Decompose.hpp).
        const std::vector<Shape> feet = feet_of(c.solid);
        for (std::size_t k = 0; k < feet.size(); ++k) {
            Shape solid = feet[k];
            if (params.fill_holes_up_to_mm != 0.0) {
                const double count = double(decomposition.components.size() * feet.size());
                const double at = double(i * feet.size() + k);
                HoleFill f = fill_holes(solid, c.build_direction, params.fill_holes_up_to_mm,
                                        params.layers.overhang_angle_deg, part,
                                        tessellating.span(at / count, (at + 1.0) / count));
                for (FilledHole& h : f.holes) {
                    h.component = int(i);
                    filled.push_back(h);
                }
                filled_volume += f.added_volume_mm3;
                for (const std::string& note : f.notes) notes.push_back(what + ": " + note);
                solid = f.solid;
            }
            append(m.mesh, occ::tessellate(solid, tessellation, what));
        }
        m.parent = c.parent;
        m.branch = c.branch < 0 ? 0 : c.branch;
        m.turned = c.turned;
        m.bridge = c.rule == Component::SplitRule::Bridge;
        // The root stands on the build plate; a child on its base face.
        m.base = c.parent < 0 ? build_plate(m.mesh) : make_plane(c.base_origin, c.build_direction);
        meshes.push_back(std::move(m));
    }
    SlicedPart out = slice_components(meshes, axis, params, progress.span(0.1, 1.0));
    out.stats.part_volume_mm3 = part_volume;
    out.stats.filled_holes = int(filled.size());
    out.stats.filled_volume_mm3 = filled_volume;
    out.filled_holes = std::move(filled);
    out.notes = std::move(notes);
    return out;
}

SlicedPart slice_solid_part(const Shape& solid, const CentroidalAxis& axis,
                            const DecomposeParams& decompose_params, const SlicePartParams& params,
                            Decomposition& decomposition, const Progress& progress) {
    const Shape part = solid.single_solid("slice");
    // The decomposition's parameters with the branches a round keeps and squares besides.
    const auto asked = [&](const std::vector<KeptBranch>& keep, const std::vector<int>& square) {
        DecomposeParams p = decompose_params;
        p.overhang_angle_deg = params.layers.overhang_angle_deg;
        p.keep_branches.insert(p.keep_branches.end(), keep.begin(), keep.end());
        p.square_branches.insert(p.square_branches.end(), square.begin(), square.end());
        return p;
    };
    const auto run = [&](const std::vector<KeptBranch>& keep, const std::vector<int>& square,
                         const Progress& round, Decomposition& into) {
        into = decompose(part, axis, asked(keep, square), round.span(0.0, 0.2));
        return slice_part(part, axis, into, params, round.span(0.2, 1.0));
    };
    // The holes slicing would fill, read on the whole part built along +Z, as its root is. A
    // split that cuts one lengthwise leaves it whole in no component, so that none fills it (the
    // pin hole of a lug whose round top the axis turned sideways round: its ceiling overhung).
    // First those a sideways component fills, upright ones, read along X and Y: a split across
    // an arm built along +X, 0.05 mm into the last of three upright holes in it, left the hole
    // whole in neither piece and open, the arm's end layer hanging 13.9 mm^2 over its far side.
    std::vector<FilledHole> holes;
    if (params.fill_holes_up_to_mm > 0.0) {
        const double overhang = params.layers.overhang_angle_deg;
        for (const Eigen::Vector3d& way : {Eigen::Vector3d(1, 0, 0), Eigen::Vector3d(0, 1, 0)})
            for (FilledHole& h :
                 holes_to_fill(part, way, params.fill_holes_up_to_mm, overhang, part)) {
                const bool upright = !leans_over(h.axis, Eigen::Vector3d::UnitZ(), overhang);
                const bool seen = std::any_of(holes.begin(), holes.end(), [&](const FilledHole& o) {
                    return (o.centre - h.centre).norm() <= 1e-6 * (1.0 + h.centre.norm()) &&
                           std::abs(o.axis.dot(h.axis)) >= 1.0 - 1e-9;
                });
                if (upright && !seen) holes.push_back(std::move(h));
            }
    }
    const std::size_t upright = holes.size();
    if (params.fill_holes_up_to_mm > 0.0)
        for (FilledHole& h :
             holes_to_fill(part, Eigen::Vector3d::UnitZ(), params.fill_holes_up_to_mm,
                           params.layers.overhang_angle_deg, part))
            holes.push_back(std::move(h));
    Decomposition whole_one;
    const auto split = [&](const std::vector<KeptBranch>& keep, const std::vector<int>& square,
                           const Progress& round) {
        SplitSliced out;
        Decomposition split_one;
        out.sliced = run(keep, square, holes.empty() ? round : round.span(0.0, 0.5), split_one);
        std::vector<std::string> open;  // the holes left open, where keeping branches is worse
        if (!holes.empty()) {
            // The branches whose splits cut such a hole are kept in their fathers (and those of
            // their sub-branches that then cut one, split from there), and that slicing is taken
            // where it leaves fewer layers in the nozzle's way, or as many and less unsupported
            // at worst.
            const Progress again = round.span(0.5, 1.0);
            std::vector<KeptBranch> more = keep;
            std::vector<std::size_t> cut_holes;  // the hole each branch kept so cuts
            std::size_t cutting_as_asked = 0;    // of them, those the split as asked made
            Decomposition d;
            const Decomposition* last = &split_one;
            for (std::size_t r = 1; r < axis.branches.size(); ++r) {
                const std::size_t had = more.size();
                for (const auto& [branch, h] :
                     branches_cutting(*last, occ::occt(part), holes, upright,
                                      params.layers.overhang_angle_deg)) {
                    if (std::any_of(more.begin(), more.end(),
                                    [&](const KeptBranch& m) { return m.branch == branch; }))
                        continue;
                    more.push_back({branch, "its split cuts " + describe(holes[h]) +
                                                " along its length, which left whole is "
                                                "deposited solid and drilled"});
                    cut_holes.push_back(h);
                }
                if (more.size() == had) break;
                if (last == &split_one) cutting_as_asked = cut_holes.size();
                d = decompose(part, axis, asked(more, square), again.span(0.0, 0.2));
                last = &d;
            }
            if (last != &split_one) {
                SlicedPart kept = slice_part(part, axis, d, params, again.span(0.2, 1.0));
                if (sliced_better(kept, out.sliced)) {
                    out.sliced = std::move(kept);
                    split_one = std::move(d);
                } else {
                    // Said of each branch whose split, made as asked, cuts a hole, which stays
                    // open.
                    std::ostringstream why;
                    why << ", which stays open: with every such branch kept in its father, "
                        << kept.stats.colliding_layers
                        << " layer(s) would be in the nozzle's way and "
                        << kept.stats.worst_unsupported_area_mm2
                        << " mm^2 unsupported at worst, against "
                        << out.sliced.stats.colliding_layers << " and "
                        << out.sliced.stats.worst_unsupported_area_mm2;
                    for (std::size_t k = 0; k < cutting_as_asked; ++k)
                        open.push_back("branch " + std::to_string(more[keep.size() + k].branch) +
                                       ": its split cuts " + describe(holes[cut_holes[k]]) +
                                       " along its length" + why.str());
                }
            }
        }
        out.notes = split_one.notes;
        out.notes.insert(out.notes.end(), open.begin(), open.end());
        for (const Component& c : split_one.components) {
            out.branches.push_back(c.branch);
            out.turned.push_back(c.turned);
        }
        out.made = std::move(split_one);
        return out;
    };
    const auto whole = [&](const Progress& p) {
        std::vector<KeptBranch> all;
        for (std::size_t b = 1; b < axis.branches.size(); ++b)
            all.push_back({int(b), "the part is sliced as one component"});
        return run(all, {}, p, whole_one);
    };
    SplitOutcome outcome;
    SlicedPart out =
        slice_clear_of_collisions(split, whole, params.avoid_collisions, progress, &outcome,
                                  effective_deflection(part, params.tessellation));
    decomposition = outcome.took_whole ? std::move(whole_one)
                                       : std::any_cast<Decomposition&&>(std::move(outcome.made));
    // The notes said with the result's (the split's, and why the part is sliced whole).
    decomposition.notes = std::move(outcome.notes);
    return out;
}

}  // namespace mas
