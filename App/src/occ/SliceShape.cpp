// Slicing a BREP part: its sub-components tessellated with the part's deflection, then sliced as
// meshes (see SlicePart.hpp).
#include <string>

#include "ShapeImpl.hpp"
#include "mas/Error.hpp"
#include "mas/SlicePart.hpp"

namespace mas {

SlicedPart slice_part(const Shape& solid, const CentroidalAxis& axis,
                      const Decomposition& decomposition, const SlicePartParams& params,
                      const Progress& progress) {
    if (decomposition.components.empty())
        throw Error(ErrorCode::EmptyInput, "the decomposition has no component to slice");
    const Shape part = solid.single_solid("the part");
    // One deflection for every component: the part's, so that a face shared by a father and its
    // child is approximated alike on both sides.
    TessellationParams tessellation = params.tessellation;
    tessellation.deflection_mm = effective_deflection(part, params.tessellation);
    std::vector<ComponentMesh> meshes;
    meshes.reserve(decomposition.components.size());
    const Progress tessellating = progress.span(0.0, 0.1, "tessellating the components");
    for (std::size_t i = 0; i < decomposition.components.size(); ++i) {
        const Component& c = decomposition.components[i];
        tessellating(double(i) / double(decomposition.components.size()));
        ComponentMesh m;
        m.mesh = occ::tessellate(c.solid, tessellation, "component " + std::to_string(i));
        m.parent = c.parent;
        m.branch = c.branch < 0 ? 0 : c.branch;
        // The root stands on the build plate; a child on its base face.
        m.base = c.parent < 0 ? build_plate(m.mesh) : make_plane(c.base_origin, c.build_direction);
        meshes.push_back(std::move(m));
    }
    SlicedPart out = slice_components(meshes, axis, params, progress.span(0.1, 1.0));
    out.stats.part_volume_mm3 = part.info().volume_mm3;
    return out;
}

}  // namespace mas
