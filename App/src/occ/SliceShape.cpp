// Slicing a BREP part: its sub-components, holes filled when asked (Holes.hpp), tessellated with
// the part's deflection, then sliced as meshes (see SlicePart.hpp).
#include <cmath>
#include <sstream>
#include <string>

#include "ShapeImpl.hpp"
#include "mas/Error.hpp"
#include "mas/SlicePart.hpp"

namespace mas {

namespace {

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
        Shape solid = c.solid;
        if (params.fill_holes_up_to_mm != 0.0) {
            const double count = double(decomposition.components.size());
            HoleFill f = fill_holes(c.solid, c.build_direction, params.fill_holes_up_to_mm,
                                    params.layers.overhang_angle_deg, part,
                                    tessellating.span(double(i) / count, double(i + 1) / count));
            for (FilledHole& h : f.holes) {
                h.component = int(i);
                filled.push_back(h);
            }
            filled_volume += f.added_volume_mm3;
            for (const std::string& note : f.notes) notes.push_back(what + ": " + note);
            solid = f.solid;
        }
        ComponentMesh m;
        m.mesh = occ::tessellate(solid, tessellation, what);
        m.parent = c.parent;
        m.branch = c.branch < 0 ? 0 : c.branch;
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
    const DecomposeParams& dp = decompose_params;
    const auto run = [&](const std::vector<KeptBranch>& keep, const Progress& round,
                         Decomposition& into) {
        DecomposeParams p = dp;
        p.keep_branches.insert(p.keep_branches.end(), keep.begin(), keep.end());
        into = decompose(part, axis, p, round.span(0.0, 0.2));
        return slice_part(part, axis, into, params, round.span(0.2, 1.0));
    };
    Decomposition split_one, whole_one;
    const auto split = [&](const std::vector<KeptBranch>& keep, const Progress& round) {
        SplitSliced out;
        out.sliced = run(keep, round, split_one);
        for (const Component& c : split_one.components) out.branches.push_back(c.branch);
        out.notes = split_one.notes;
        return out;
    };
    const auto whole = [&](const Progress& p) {
        std::vector<KeptBranch> all;
        for (std::size_t b = 1; b < axis.branches.size(); ++b)
            all.push_back({int(b), "the part is sliced as one component"});
        return run(all, p, whole_one);
    };
    SplitOutcome outcome;
    SlicedPart out =
        slice_clear_of_collisions(split, whole, params.avoid_collisions, progress, &outcome);
    decomposition = outcome.took_whole ? std::move(whole_one) : std::move(split_one);
    // The notes said with the result's (the split's, and why the part is sliced whole).
    decomposition.notes = std::move(outcome.notes);
    return out;
}

}  // namespace mas
