// Slicing every sub-component of a part and planning the paths of every layer (see SlicePart.hpp).
#include "mas/SlicePart.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <set>
#include <sstream>

#include "mas/Angles.hpp"
#include "mas/Error.hpp"

namespace mas {

bool inside_mesh(const TriangleMesh& mesh, const Eigen::Vector3d& point) {
    // Sum of the signed solid angles of the facets seen from the point (Van Oosterom & Strackee),
    // over 4 pi: 1 inside a closed outward-oriented mesh, 0 outside.
    double total = 0.0;
    for (const Eigen::Vector3i& t : mesh.triangles) {
        const Eigen::Vector3d a = mesh.vertices[std::size_t(t[0])] - point;
        const Eigen::Vector3d b = mesh.vertices[std::size_t(t[1])] - point;
        const Eigen::Vector3d c = mesh.vertices[std::size_t(t[2])] - point;
        const double la = a.norm(), lb = b.norm(), lc = c.norm();
        const double numerator = a.dot(b.cross(c));
        const double denominator = la * lb * lc + a.dot(b) * lc + b.dot(c) * la + c.dot(a) * lb;
        // On the facet itself the solid angle jumps between -2 pi and 2 pi: a point on the
        // surface counts as inside.
        if (std::abs(numerator) <= 1e-12 * la * lb * lc && denominator < 0.0) return true;
        total += 2.0 * std::atan2(numerator, denominator);
    }
    return total / (4.0 * kPi) > 0.5;
}

Plane build_plate(const TriangleMesh& mesh) {
    const Eigen::AlignedBox3d box = bounding_box(mesh);
    return make_plane({box.center().x(), box.center().y(), box.min().z()},
                      Eigen::Vector3d::UnitZ());
}

bool sliced_better(const SlicedPart& b, const SlicedPart& a) {
    if (b.stats.colliding_layers != a.stats.colliding_layers)
        return b.stats.colliding_layers < a.stats.colliding_layers;
    return b.stats.worst_unsupported_area_mm2 < a.stats.worst_unsupported_area_mm2 - 0.01;
}

namespace {

// The layers of a slicing that hang past a strip `strip_mm` wide along their outlines (what the
// sections of a mesh `strip_mm` off the surface can show on a part with nothing hanging): how
// many, and the one hanging furthest past it (-1 for none) and by how much (mm^2).
struct PastStrip {
    int layers = 0;
    int worst = -1;
    double excess = 0.0;
};
PastStrip past_strip(const SlicedPart& s, double strip_mm) {
    PastStrip out;
    for (std::size_t i = 0; i < s.layers.size(); ++i) {
        const Layer& l = s.layers[i];
        const double excess = l.unsupported_area_mm2 - perimeter(l.regions) * strip_mm;
        if (!(excess > 0.0)) continue;
        ++out.layers;
        if (excess > out.excess) {
            out.excess = excess;
            out.worst = int(i);
        }
    }
    return out;
}

}  // namespace

SlicedPart slice_clear_of_collisions(
    const std::function<SplitSliced(const std::vector<KeptBranch>& keep,
                                    const std::vector<int>& square, const Progress& progress)>&
        split,
    const std::function<SlicedPart(const Progress& progress)>& whole, bool avoid_collisions,
    const Progress& progress, SplitOutcome* outcome, double strip_mm) {
    const int rounds = avoid_collisions ? 5 : 1;
    std::vector<KeptBranch> keep;
    const auto kept = [&](int b) {
        return std::any_of(keep.begin(), keep.end(),
                           [&](const KeptBranch& k) { return k.branch == b; });
    };
    std::vector<int> square;
    std::vector<int> narrow;  // `square` with the colliding turned cuts only, tried besides
    SplitSliced parts;
    for (int round = 0;; ++round) {
        // The first round is most of the work (the rest, seldom needed, share a fifth; the part
        // sliced whole the last tenth).
        const double lo = round == 0 ? 0.0 : 0.7 + 0.2 * (round - 1) / (rounds - 1);
        const double hi = round == 0 ? 0.7 : 0.7 + 0.2 * round / (rounds - 1);
        if (narrow.empty()) {
            parts = split(keep, square, progress.span(lo, hi));
        } else {
            const double mid = 0.5 * (lo + hi);
            SplitSliced only = split(keep, narrow, progress.span(lo, mid));
            parts = split(keep, square, progress.span(mid, hi));
            if (sliced_better(only.sliced, parts.sliced)) {
                parts = std::move(only);
                square = std::move(narrow);
            }
            narrow.clear();
        }
        if (parts.sliced.stats.colliding_layers == 0 || parts.branches.size() == 1 ||
            round + 1 == rounds)
            break;
        std::set<int> branches;
        std::set<std::size_t> turned;  // the colliding components cut turned
        for (const NozzleCollision& c : parts.sliced.sequence.collisions) {
            const std::size_t component =
                std::size_t(parts.sliced.layers[std::size_t(c.layer)].component);
            if (component == 0) continue;
            branches.insert(parts.branches[component]);
            if (component < parts.turned.size() && parts.turned[component])
                turned.insert(component);
        }
        if (branches.empty()) break;
        // Where a cut turned square to its branch's line leaves the nozzle no way to some layers,
        // every such cut is made square to its branch's direction instead, as Sec. 3.2.1's
        // directions cut the part, and the rounds go on from there. (A spiral stair's treads, 30
        // degrees apart round a column and 8 mm apart up it: built along their own lines, the
        // nozzle at one tread's root met the tread under it. Squaring only those once cut the
        // next ones across their neighbours, and seven of twelve treads ended in the column's
        // layers.) Squaring only the colliding ones is tried besides, and taken only where it
        // slices better (sliced_better), which guards against that: the blades of a hub,
        // twisted 30 degrees about their lengths, all cut square to +-X or +-Y, left their roots
        // in the hub's layers, and one blade's layers still met something; it was kept in the
        // hub, its underside hanging 18.2 mm^2 in one layer. Squaring the one blade whose layers
        // met the plate left nothing hanging. (Both before a turned cut's guide ran through its
        // own sections, slice_components: that hub's blades then meet nothing, the stair's
        // treads 30 degrees apart neither; 20 degrees apart, some did until a lean was refused
        // only where the leaned nozzle itself comes near, Nozzle.cpp's FineSamples: leaned, it
        // clears the tread below. With a tip 16 mm across, not 10, some still meet it.)
        if (!turned.empty()) {
            std::vector<int> only = square;
            for (std::size_t c = 1; c < parts.turned.size(); ++c) {
                if (!parts.turned[c]) continue;
                square.push_back(parts.branches[c]);
                if (turned.count(c)) only.push_back(parts.branches[c]);
            }
            if (only.size() < square.size()) narrow = std::move(only);
            continue;
        }
        // A branch kept already (its bridge's layers, Decompose.hpp, out of reach too) is kept
        // as it is: with nothing new to keep, the split stands.
        bool more = false;
        for (int b : branches)
            if (!kept(b)) {
                keep.push_back({b,
                                "built on its own, its layers would meet the plate or what is "
                                "deposited before them"});
                more = true;
            }
        if (!more) break;
    }
    // Where a layer hangs past the strip (no order of the components rests it), the branch of its
    // component is kept in its father, and that split taken where its layers are in the nozzle's
    // way no more often, fewer hang past the strip or as many, and the worst by less: up to three
    // times, one branch at a time. (A braced frame whose beam became a bridge in the first round:
    // the brace, built on its own along -Y and never in the nozzle's way, hung 11 mm^2 in its
    // first layers, and a slab of the far post cut off along -Y 71 mm^2; kept in the posts'
    // layers, at most 1.8.)
    const bool hang_rounds = avoid_collisions && strip_mm > 0.0;
    PastStrip now;
    if (hang_rounds) now = past_strip(parts.sliced, strip_mm);
    for (int round = 0; hang_rounds && round < 3; ++round) {
        if (now.worst < 0 || parts.branches.size() == 1) break;
        const int component = parts.sliced.layers[std::size_t(now.worst)].component;
        if (component <= 0) break;
        const int b = parts.branches[std::size_t(component)];
        if (kept(b)) break;
        std::vector<KeptBranch> more = keep;
        std::ostringstream why;
        why << "built on its own, a layer of it would hang " << now.excess
            << " mm^2 past what the layer below holds (beyond a strip as wide as the deflection "
               "along its outline); kept in its father, less hangs";
        more.push_back({b, why.str()});
        const double lo = 0.9 + 0.05 * round / 3.0, hi = 0.9 + 0.05 * (round + 1) / 3.0;
        SplitSliced tried = split(more, square, progress.span(lo, hi));
        const PastStrip then = past_strip(tried.sliced, strip_mm);
        if (tried.sliced.stats.colliding_layers > parts.sliced.stats.colliding_layers ||
            then.layers > now.layers || !(then.excess < now.excess - 0.01))
            break;
        parts = std::move(tried);
        keep = std::move(more);
        now = then;
    }
    SlicedPart sliced = std::move(parts.sliced);
    if (avoid_collisions && parts.branches.size() > 1 && sliced.stats.colliding_layers > 0) {
        SlicedPart one = whole(progress.span(0.95, 1.0));
        if (one.stats.colliding_layers < sliced.stats.colliding_layers) {
            std::ostringstream note;
            note << "sliced as one component: built in " << parts.branches.size() << " components, "
                 << sliced.stats.colliding_layers
                 << " layer(s) would meet what is deposited before them, "
                 << one.stats.colliding_layers << " so";
            parts.notes.push_back(note.str());
            sliced = std::move(one);
            if (outcome) outcome->took_whole = true;
        }
    }
    std::vector<std::string> notes;
    for (const std::string& note : parts.notes) notes.push_back("decomposition: " + note);
    sliced.notes.insert(sliced.notes.begin(), notes.begin(), notes.end());
    if (outcome) {
        outcome->notes = std::move(parts.notes);
        outcome->made = std::move(parts.made);
    }
    progress.span(0.0, 1.0, "slicing")(1.0);
    return sliced;
}

SlicedPart slice_mesh_part(const TriangleMesh& mesh, const CentroidalAxis& axis,
                           const SlicePartParams& params, const Progress& progress) {
    if (params.fill_holes_up_to_mm != 0.0)
        throw Error(
            ErrorCode::InvalidArgument,
            "holes are filled on a solid's BREP: a mesh is sliced as it is (fill no holes)");
    const MeshReport report = check_mesh(mesh);
    if (!report.closed() || report.non_finite_vertices)
        throw Error(ErrorCode::OpenMesh,
                    "the part's mesh is not a closed surface: it cannot be sliced");
    check_axis_belongs(axis, bounding_box(mesh), report.volume_mm3, "slice");
    ComponentMesh root;
    root.mesh = mesh;
    root.base = build_plate(mesh);
    if (!params.split_mesh) return slice_components({root}, axis, params, progress);
    const auto split = [&](const std::vector<KeptBranch>& keep, const std::vector<int>& square,
                           const Progress& round) {
        MeshDecomposeParams split;
        split.min_component_height_mm = params.layers.min_layer_mm;
        split.max_tilt_deg = params.layers.max_tilt_deg;
        split.overhang_angle_deg = params.layers.overhang_angle_deg;
        split.keep_branches = keep;
        split.square_branches = square;
        MeshDecomposition parts = decompose_mesh(mesh, axis, split, round.span(0.0, 0.05));
        SplitSliced out;
        out.sliced = slice_components(parts.components, axis, params, round.span(0.05, 1.0));
        for (const ComponentMesh& c : parts.components) {
            out.branches.push_back(c.branch);
            out.turned.push_back(c.turned);
        }
        out.notes = std::move(parts.notes);
        return out;
    };
    const auto whole = [&](const Progress& p) { return slice_components({root}, axis, params, p); };
    return slice_clear_of_collisions(split, whole, params.avoid_collisions, progress);
}

namespace {

// Which meshes reach which components' bases: a mesh reaches a component's base when it comes
// within max_layer of the base plane (far more than the section's offset) and near the
// component's box: its section just below the plane helps only within the overhang allowance
// (sideways) of the first layer's footprint just above it (two offsets apart along the normal),
// which lies in the component's box. (Without the second test, each post built on a plate of 900
// made every other post's support stale: cubic work.)
class BaseReach {
public:
    BaseReach(const std::vector<ComponentMesh>& components, const LayerParams& params)
        : components_(components), params_(params) {
        const double reach = std::max(params.max_layer_mm,
                                      std::hypot(params.min_layer_mm * overhang_allowance(params),
                                                 2.0 * base_offset(params)));
        boxes_.resize(components.size());
        reach_of_.resize(components.size());
        for (std::size_t c = 0; c < components.size(); ++c) {
            boxes_[c] = bounding_box(components[c].mesh);
            reach_of_[c] = Eigen::AlignedBox3d(boxes_[c].min() - Eigen::Vector3d::Constant(reach),
                                               boxes_[c].max() + Eigen::Vector3d::Constant(reach));
        }
    }
    // Whether component `mesh`'s mesh reaches component `c`'s base.
    bool operator()(std::size_t mesh, std::size_t c) const {
        double lo, hi;  // heights above the base plane
        range_along(boxes_[mesh].translated(-components_[c].base.origin),
                    components_[c].base.normal.normalized(), lo, hi);
        return lo <= params_.max_layer_mm && hi >= -params_.max_layer_mm &&
               boxes_[mesh].intersects(reach_of_[c]);
    }

private:
    const std::vector<ComponentMesh>& components_;
    const LayerParams& params_;
    std::vector<Eigen::AlignedBox3d> boxes_, reach_of_;
};

}  // namespace

std::vector<int> build_order(const std::vector<ComponentMesh>& components,
                             const LayerParams& params, const Progress& progress) {
    const std::size_t n = components.size();
    std::vector<int> order;
    if (n == 0) return order;
    order.reserve(n);
    // A component's support can only change when a mesh reaching its base is built: only those
    // are cut again.
    const BaseReach reaches_base(components, params);
    std::vector<char> done(n, 0), stale(n, 1);
    std::vector<double> score(n, 0.0), tolerance(n, 0.0);
    auto take = [&](std::size_t c) {
        order.push_back(int(c));
        done[c] = 1;
        for (std::size_t k = 1; k < n; ++k)
            if (!done[k] && reaches_base(c, k)) stale[k] = 1;
    };
    take(0);
    while (order.size() < n) {
        // Of the components whose father is built, the one left least unsupported by what is;
        // the first in tree order among equals. As when slicing, a negligible unsupported area
        // counts as none.
        std::size_t best = n;
        for (std::size_t c = 1; c < n; ++c) {
            if (done[c] || !done[std::size_t(components[c].parent)]) continue;
            if (stale[c]) {
                progress.check();
                std::vector<const TriangleMesh*> near;
                for (std::size_t k = 0; k < n; ++k)
                    if (done[k] && reaches_base(k, c)) near.push_back(&components[k].mesh);
                const BaseSupport b =
                    base_support(components[c].mesh, components[c].base, near, params);
                tolerance[c] = negligible_unsupported_mm2(b.footprint_area_mm2);
                score[c] = b.unsupported_area_mm2 <= tolerance[c] ? 0.0 : b.unsupported_area_mm2;
                stale[c] = 0;
            }
            if (best == n || score[c] < score[best] - tolerance[c]) best = c;
        }
        take(best);
        progress(double(order.size()) / double(n));
    }
    progress(1.0);
    return order;
}

namespace {

// A guide point moved to the centroid of what of its node's region the component holds, on the
// node's plane, where the component lacks part of that region: the axis was marched through the
// whole part, and where a split took from a father part of what its nodes' sections held (a
// column whose sections held an arm's near end, out to the tip of the gusset under it, the arm cut
// off at the column's face), the nodes' centroids lie off the component's, and its layers would
// lean after material that is not theirs. What the component lacks counts when it is wider than
// the two tessellations' disagreement (the axis' deflection, twice, its simplification, step /
// 100, and a tenth of a micron): a sliver along a curved outline moves nothing. Material the
// node's region never held (another branch's, swept before, which a mesh sliced as one component
// still has) moves nothing either. Nodes without their region (an axis dict built by hand)
// stay.
void recentre_guide(const TriangleMesh& mesh, const CentroidalAxis& axis,
                    ComponentSlicingInput& input) {
    const double sliver =
        2.0 * std::max(axis.deflection_mm, 0.0) + axis.params.step_mm / 100.0 + 1e-4;
    std::vector<Plane> planes;
    for (const int n : input.guide_nodes) {
        const AxisNode& node = axis.nodes[std::size_t(n)];
        planes.push_back(make_plane(node.position, node.normal));
    }
    const std::vector<Section> sections = slice_mesh(mesh, planes);
    for (std::size_t i = 0; i < sections.size(); ++i) {
        const AxisNode& node = axis.nodes[std::size_t(input.guide_nodes[i])];
        if (node.region.outer.points.empty()) continue;
        Regions2 held;
        for (const SectionRegion& r : sections[i].regions) held.push_back(r.shape);
        const Regions2 lacked = difference({node.region}, held);
        if (lacked.empty() || offset(lacked, -0.5 * sliver, JoinType::Miter).empty()) continue;
        const Regions2 kept = intersection({node.region}, held);
        if (area(kept) > 0.0)
            input.guide[i] = sections[i].frame().to_3d(centroid(kept), sections[i].plane);
    }
}

// A component cut turned square to its branch's line (ComponentMesh::turned) is built along that
// line: its guide runs through the centroids of its sections square to the line, one through each
// of its nodes (those past its end, or no further along than the last, dropped), not through the
// nodes' own, marched along the nearest of the six directions. Those planes cut a blade's tip
// aslant: on a hub's blade 29 degrees off -Y, twisted 15 degrees about its length, the centroids
// of its last sections dropped 10 mm to its lowest corner, the layers tilted 3 degrees down after
// them, and the nozzle, leaned its 30 degrees off them, no longer cleared the plate: the blade was
// kept in the hub, 32 mm^2 of its underside hanging (survey seed 125, hub 4).
void guide_along_line(const TriangleMesh& mesh, const Eigen::Vector3d& along,
                      ComponentSlicingInput& input) {
    std::vector<Plane> planes;
    for (const Eigen::Vector3d& p : input.guide) planes.push_back(make_plane(p, along));
    const std::vector<Section> sections = slice_mesh(mesh, planes);
    std::vector<Eigen::Vector3d> guide;
    std::vector<int> nodes;
    for (std::size_t i = 0; i < sections.size(); ++i) {
        if (sections[i].empty()) continue;
        const Eigen::Vector3d& c = sections[i].centroid;
        if (!guide.empty() && (c - guide.back()).dot(along) <= 1e-9) continue;
        guide.push_back(c);
        nodes.push_back(input.guide_nodes[i]);
    }
    input.guide = std::move(guide);
    input.guide_nodes = std::move(nodes);
}

}  // namespace

SlicedPart slice_components(const std::vector<ComponentMesh>& components,
                            const CentroidalAxis& axis, const SlicePartParams& params,
                            const Progress& caller) {
    const Progress progress = caller.span(0.0, 1.0, "slicing");
    validate(params.layers);
    validate(params.paths);
    validate(params.nozzle);
    if (components.empty()) throw Error(ErrorCode::EmptyInput, "no component to slice");
    std::vector<double> volumes(components.size(), 0.0);
    Eigen::AlignedBox3d part_box;
    for (std::size_t c = 0; c < components.size(); ++c) {
        const ComponentMesh& comp = components[c];
        if (comp.parent >= int(c) || (c > 0 && comp.parent < 0) || (c == 0 && comp.parent != -1))
            throw Error(ErrorCode::InvalidArgument,
                        "component " + std::to_string(c) + " has father " +
                            std::to_string(comp.parent) +
                            ": components must come in tree order, the root first");
        const MeshReport report = check_mesh(comp.mesh);
        if (!report.closed() || report.non_finite_vertices)
            throw Error(ErrorCode::OpenMesh, "component " + std::to_string(c) +
                                                 "'s mesh is not a closed surface: it cannot be "
                                                 "sliced");
        volumes[c] = report.volume_mm3;
        validate(params.layers, comp.mesh, "component " + std::to_string(c));
        part_box.extend(bounding_box(comp.mesh));
    }
    validate(params.nozzle, part_box.isEmpty() ? 0.0 : part_box.diagonal().norm(), "the part");
    SlicedPart out;
    out.components.resize(components.size());
    out.build_order =
        build_order(components, params.layers, progress.span(0.0, 0.05, "ordering the components"));
    // Each component's share of the layers' 80 % is its share of the volume.
    double total_volume = 0.0;
    for (double v : volumes) total_volume += std::max(v, 0.0);
    double sliced_volume = 0.0;
    std::vector<const TriangleMesh*> built;
    for (const int ci : out.build_order) {
        const std::size_t c = std::size_t(ci);
        const ComponentMesh& comp = components[c];
        ComponentSlicingInput input;
        input.component = int(c);
        input.mesh = &comp.mesh;
        input.base = comp.base;
        if (comp.parent >= 0) input.support_meshes = built;
        // A bridge's piece whose branch marches across its father's build direction (the axis
        // crossed the gap sideways, Decompose.hpp) is built straight along its diagonal: its
        // layers turned after the march stood square to the gap at its far end, the nozzle
        // level over the far post. One whose branch marches on along it (merged tracks going on
        // past the gap: a chair's back over its top) turns after it, as any component.
        const AxisBranch* branch = comp.branch >= 0 && comp.branch < int(axis.branches.size())
                                       ? &axis.branches[std::size_t(comp.branch)]
                                       : nullptr;
        const bool across = branch && comp.bridge && comp.parent >= 0 &&
                            std::abs(branch->direction.normalized().dot(
                                components[std::size_t(comp.parent)].base.normal)) < std::sqrt(0.5);
        if (branch && !across) {
            for (int n : branch->nodes) {
                if (n < 0 || n >= int(axis.nodes.size()))
                    throw Error(ErrorCode::InvalidArgument,
                                "the axis' branch " + std::to_string(comp.branch) + " names node " +
                                    std::to_string(n) + ", which it lacks");
                // The node is the component's when its section's material is: a ring's
                // centroid lies in the bore, outside every component.
                const AxisNode& node = axis.nodes[std::size_t(n)];
                if (!inside_mesh(comp.mesh, node.material_point())) continue;
                input.guide.push_back(node.position);
                input.guide_nodes.push_back(n);
            }
            if (comp.turned)
                guide_along_line(comp.mesh, input.base.normal, input);
            else
                recentre_guide(comp.mesh, axis, input);
        }
        ComponentLayers& record = out.components[c];
        record.component = int(c);
        record.first_layer = int(out.layers.size());
        record.guide_nodes = int(input.guide.size());
        record.volume_mm3 = volumes[c];
        const double share = total_volume > 0.0 ? std::max(volumes[c], 0.0) / total_volume
                                                : 1.0 / double(components.size());
        const std::string stage = "slicing component " + std::to_string(c) + " (" +
                                  std::to_string(built.size() + 1) + " of " +
                                  std::to_string(components.size()) + ")";
        std::vector<Layer> layers = slice_component(
            input, params.layers,
            progress.span(0.05 + 0.8 * sliced_volume, 0.05 + 0.8 * (sliced_volume + share), stage));
        sliced_volume += share;
        record.layer_count = int(layers.size());
        for (Layer& l : layers) out.layers.push_back(std::move(l));
        out.stats.part_volume_mm3 += record.volume_mm3;
        built.push_back(&comp.mesh);
    }

    SliceStats& s = out.stats;
    s.layer_count = int(out.layers.size());
    s.min_thickness_mm = std::numeric_limits<double>::infinity();
    s.max_thickness_mm = 0.0;
    Eigen::Vector3d head = Eigen::Vector3d::Zero();  // where the previous layer's paths ended
    bool has_head = false;
    out.toolpaths.reserve(out.layers.size());
    const Progress paths_progress = progress.span(0.85, 0.9, "planning the bead paths");
    // Rasters and seams at their angles to the part's sides, in the frame its axis marched in.
    const double part_frame = axis_frame_deg(axis, "slice");
    for (std::size_t i = 0; i < out.layers.size(); ++i) {
        paths_progress(double(i) / double(out.layers.size()));
        const Layer& l = out.layers[i];
        s.min_thickness_mm = std::min(s.min_thickness_mm, l.min_thickness_mm);
        s.max_thickness_mm = std::max(s.max_thickness_mm, l.max_thickness_mm);
        s.deposited_volume_mm3 += l.volume_mm3;
        s.material_volume_mm3 += l.material_volume_mm3;
        s.max_volume_difference = std::max(s.max_volume_difference, l.volume_difference);
        if (!l.meets_volume_difference) ++s.layers_over_volume_difference;
        if (l.unsupported_area_mm2 > s.worst_unsupported_area_mm2) {
            s.worst_unsupported_area_mm2 = l.unsupported_area_mm2;
            s.worst_unsupported_layer = int(i);
        }
        LayerToolpaths paths = plan_toolpaths(
            l, int(i), params.paths, has_head ? std::optional<Eigen::Vector3d>(head) : std::nullopt,
            paths_progress, part_frame);
        for (auto it = paths.paths.rbegin(); it != paths.paths.rend(); ++it)
            if (!it->points.empty()) {
                head = it->points.back();
                has_head = true;
                break;
            }
        s.deposit_length_mm += paths.deposit_length_mm;
        s.travel_length_mm += paths.travel_length_mm;
        s.centre_line_passes += int(paths.centre_line_regions.size());
        s.unfilled_features += int(paths.unfilled.size());
        out.toolpaths.push_back(std::move(paths));
    }
    if (out.layers.empty()) s.min_thickness_mm = 0.0;

    SequenceInput sequence;
    sequence.layers = &out.layers;
    sequence.toolpaths = &out.toolpaths;
    sequence.start_order = out.build_order;
    sequence.plate = components.front().base;
    out.plate = sequence.plate;
    sequence.parent.resize(components.size());
    sequence.waits_for.resize(components.size());
    // A component waits for its father (the layers of it it may rest on: plan_build_sequence),
    // and for all of the earlier components its first layer rests on:
    // those whose mesh reaching its base leaves less of it unsupported than its father alone
    // (an arm and the pieces shared out beside it, past its column); not for a neighbour that
    // merely comes near (two posts side by side, which may then go up together).
    const BaseReach reaches_base(components, params.layers);
    const Progress waits = progress.span(0.9, 0.92, "finding what each component rests on");
    for (std::size_t k = 0; k < out.build_order.size(); ++k) {
        waits(double(k) / double(out.build_order.size()));
        const std::size_t c = std::size_t(out.build_order[k]);
        const int father = components[c].parent;
        sequence.parent[c] = father;
        if (father < 0) continue;
        std::vector<int> near;
        for (std::size_t e = 0; e < k; ++e) {
            const int earlier = out.build_order[e];
            if (earlier != father && reaches_base(std::size_t(earlier), c)) near.push_back(earlier);
        }
        if (near.empty()) continue;
        const ComponentMesh& comp = components[c];
        std::vector<const TriangleMesh*> below = {&components[std::size_t(father)].mesh};
        const BaseSupport alone = base_support(comp.mesh, comp.base, below, params.layers);
        const double tolerance = negligible_unsupported_mm2(alone.footprint_area_mm2);
        if (alone.unsupported_area_mm2 <= tolerance) continue;  // the father carries it all
        for (int e : near) below.push_back(&components[std::size_t(e)].mesh);
        const BaseSupport together = base_support(comp.mesh, comp.base, below, params.layers);
        if (together.unsupported_area_mm2 >= alone.unsupported_area_mm2 - tolerance) continue;
        // They carry it: each that carries any of it (many thin posts under a slab may each
        // carry less than the noise the together test allows for) is waited for.
        below.resize(1);
        std::vector<int>& waits_for = sequence.waits_for[c];
        for (int e : near) {
            below.push_back(&components[std::size_t(e)].mesh);
            const BaseSupport b = base_support(comp.mesh, comp.base, below, params.layers);
            below.pop_back();
            if (b.unsupported_area_mm2 <
                alone.unsupported_area_mm2 - 1e-9 * alone.footprint_area_mm2)
                waits_for.push_back(e);
        }
        if (waits_for.empty()) waits_for = near;
    }
    out.sequence = plan_build_sequence(sequence, params.nozzle,
                                       progress.span(0.92, 1.0, "ordering the layers"));
    // The paths were planned in the layers' order: each layer's first travel starts where the
    // layer before it in the sequence ends instead (the layer's own paths stay as planned).
    has_head = false;
    s.travel_length_mm = 0.0;
    for (const int i : out.sequence.layers) {
        LayerToolpaths& t = out.toolpaths[std::size_t(i)];
        t.tool_axis = out.sequence.tool_axes[std::size_t(i)];
        if (!t.paths.empty() && !t.paths.front().deposit()) {
            const ToolPath& lead = t.paths.front();
            t.travel_length_mm -= (lead.points.back() - lead.points.front()).norm();
            t.paths.erase(t.paths.begin());
        }
        if (t.paths.empty()) continue;
        const Eigen::Vector3d start = t.paths.front().points.front();
        if (has_head && (head - start).norm() > 0.0) {
            t.travel_length_mm += (start - head).norm();
            t.paths.insert(t.paths.begin(), travel_move(head, start));
        }
        t.travel_length_mm = std::max(t.travel_length_mm, 0.0);
        s.travel_length_mm += t.travel_length_mm;
        head = t.paths.back().points.back();
        has_head = true;
    }
    s.colliding_layers = int(out.sequence.collisions.size());
    s.component_switches = out.sequence.component_switches;
    s.leaned_layers = out.sequence.leaned_layers;
    progress(1.0);
    return out;
}

}  // namespace mas
