// Decomposition (paper Sec. 4.1) on OCCT: splitting faces found on the BREP, the father split by
// the face's plane with BRepAlgoAPI_Splitter, the other pieces fused back. See Decompose.hpp.
#include "mas/Decompose.hpp"

#include <BOPTools_AlgoTools.hxx>
#include <BRepAdaptor_Curve.hxx>
#include <BRepAdaptor_Surface.hxx>
#include <BRepAlgoAPI_Cut.hxx>
#include <BRepAlgoAPI_Fuse.hxx>
#include <BRepAlgoAPI_Splitter.hxx>
#include <BRepBndLib.hxx>
#include <BRepBuilderAPI_Copy.hxx>
#include <BRepBuilderAPI_MakeFace.hxx>
#include <BRepBuilderAPI_Transform.hxx>
#include <BRepCheck_Analyzer.hxx>
#include <BRepClass3d_SolidClassifier.hxx>
#include <BRepClass_FaceClassifier.hxx>
#include <BRepGProp.hxx>
#include <BRepTools.hxx>
#include <BRep_Builder.hxx>
#include <BRep_Tool.hxx>
#include <Bnd_Box.hxx>
#include <GProp_GProps.hxx>
#include <Geom2d_Curve.hxx>
#include <Geom_Curve.hxx>
#include <Geom_Surface.hxx>
#include <IntCurvesFace_ShapeIntersector.hxx>
#include <NCollection_DataMap.hxx>
#include <OSD_Parallel.hxx>
#include <Precision.hxx>
#include <ShapeFix_Shape.hxx>
#include <TopExp.hxx>
#include <TopExp_Explorer.hxx>
#include <TopTools_IndexedDataMapOfShapeListOfShape.hxx>
#include <TopTools_ListOfShape.hxx>
#include <TopTools_ShapeMapHasher.hxx>
#include <TopoDS.hxx>
#include <TopoDS_Compound.hxx>
#include <TopoDS_Face.hxx>
#include <TopoDS_Wire.hxx>
#include <algorithm>
#include <cmath>
#include <gp_Ax1.hxx>
#include <gp_Lin.hxx>
#include <gp_Trsf.hxx>
#include <limits>
#include <map>
#include <memory>
#include <optional>
#include <set>
#include <sstream>
#include <string>

#include "ShapeImpl.hpp"
#include "mas/Angles.hpp"
#include "mas/Mesh.hpp"
#include "mas/Section.hpp"
#include "mas/Slicing.hpp"

namespace mas {

namespace {

using Eigen::Vector3d;

Vector3d vec(const gp_Vec& v) { return {v.X(), v.Y(), v.Z()}; }
Vector3d vec(const gp_Pnt& p) { return {p.X(), p.Y(), p.Z()}; }
Vector3d vec(const gp_Dir& d) { return {d.X(), d.Y(), d.Z()}; }
gp_Pnt pnt(const Vector3d& v) { return {v.x(), v.y(), v.z()}; }

// What a decomposition asks OCCT again and again, kept while it runs (a KeptQueries scope, on its
// thread): each face's optimal box, and a classifier per component, both by shape (TShape and
// location: IsSame; orientation changes neither). Every branch's plan bounds every face of its
// father, mostly the same solid (the root, until a split takes a piece off), every split attempt
// bounds the father, and finding a branch's father classifies its node against each component;
// the optimal box of a curved face is dear, and a classifier prepares the solid's faces before its
// first point. A pipe bend with an end flange, upside down (46 branches over one torus), took 76 s
// to slice, 8 to 11 s with these kept; the corpora's 200 parts give the same G-code.
class Kept {
public:
    const Bnd_Box& face_box(const TopoDS_Face& face) {
        if (const Bnd_Box* known = boxes_.Seek(face)) return *known;
        Bnd_Box box;
        BRepBndLib::AddOptimal(face, box, Standard_False, Standard_False);
        return *boxes_.Bound(face, box);
    }

    // A classifier loaded with `solid` (its faces prepared once for every point asked).
    BRepClass3d_SolidClassifier& classifier(const TopoDS_Shape& solid) {
        if (const auto* known = classifiers_.Seek(solid)) return **known;
        return **classifiers_.Bound(solid, std::make_shared<BRepClass3d_SolidClassifier>(solid));
    }

    // Drops the classifier of a solid no longer asked (a father a split replaced).
    void forget(const TopoDS_Shape& solid) { classifiers_.UnBind(solid); }

private:
    NCollection_DataMap<TopoDS_Shape, Bnd_Box, TopTools_ShapeMapHasher> boxes_;
    NCollection_DataMap<TopoDS_Shape, std::shared_ptr<BRepClass3d_SolidClassifier>,
                        TopTools_ShapeMapHasher>
        classifiers_;
};

thread_local Kept* kept = nullptr;

class KeptQueries {
public:
    KeptQueries() : outer_(kept) { kept = &kept_; }
    ~KeptQueries() { kept = outer_; }
    KeptQueries(const KeptQueries&) = delete;
    KeptQueries& operator=(const KeptQueries&) = delete;

private:
    Kept kept_;
    Kept* outer_;
};

// OCCT's optimal box of `s`; of a face or solid within a KeptQueries scope, from its faces' kept
// boxes (the same box: AddOptimal updates the whole by each face's box in turn, and a solid has no
// edge or vertex outside its faces).
Eigen::AlignedBox3d bounds_of(const TopoDS_Shape& s) {
    Bnd_Box box;
    const TopAbs_ShapeEnum type = s.IsNull() ? TopAbs_SHAPE : s.ShapeType();
    if (kept && (type == TopAbs_SOLID || type == TopAbs_FACE)) {
        for (TopExp_Explorer x(s, TopAbs_FACE); x.More(); x.Next()) {
            const Bnd_Box& face = kept->face_box(TopoDS::Face(x.Current()));
            if (face.IsVoid()) continue;
            double x0, y0, z0, x1, y1, z1;
            face.Get(x0, y0, z0, x1, y1, z1);
            box.Update(x0, y0, z0, x1, y1, z1);
        }
    } else {
        BRepBndLib::AddOptimal(s, box, Standard_False, Standard_False);
    }
    if (box.IsVoid() && type == TopAbs_FACE) return {};  // (Get throws for any other)
    double x0, y0, z0, x1, y1, z1;
    box.Get(x0, y0, z0, x1, y1, z1);
    return {Vector3d(x0, y0, z0), Vector3d(x1, y1, z1)};
}

// Outward unit normal of a face at (u, v): the surface normal, turned for a reversed face.
bool face_normal(const TopoDS_Face& face, double u, double v, Vector3d& n) {
    BRepAdaptor_Surface s(face, Standard_False);
    gp_Pnt p;
    gp_Vec du, dv;
    s.D1(u, v, p, du, dv);
    const gp_Vec c = du.Crossed(dv);
    if (c.Magnitude() < 1e-12) return false;
    n = vec(c).normalized();
    if (face.Orientation() == TopAbs_REVERSED) n = -n;
    return true;
}

// The planar faces' data the criteria need.
struct PlanarFace {
    TopoDS_Face face;
    Vector3d normal;  // outward
    Vector3d point;   // on the plane
};

bool planar(const TopoDS_Face& face, PlanarFace& out) {
    BRepAdaptor_Surface s(face, Standard_False);
    if (s.GetType() != GeomAbs_Plane) return false;
    const gp_Pln pln = s.Plane();
    out.face = face;
    out.normal = vec(pln.Axis().Direction());
    if (face.Orientation() == TopAbs_REVERSED) out.normal = -out.normal;
    out.point = vec(pln.Location());
    return true;
}

// Criterion (2): does the planar face `f` of `solid` have a concave edge? At the edge's midpoint,
// d1 is the direction into f across the edge (perpendicular to the edge, in f's plane); the other
// face's outward normal n2 leans towards d1 at a concave edge. The signed angle
// atan2(n2.d1, n2.n1) is the interior angle minus 180 degrees.
bool has_concave_edge(const PlanarFace& f, const TopTools_IndexedDataMapOfShapeListOfShape& e2f,
                      double min_angle_rad) {
    for (TopExp_Explorer x(f.face, TopAbs_EDGE); x.More(); x.Next()) {
        const TopoDS_Edge& edge = TopoDS::Edge(x.Current());
        if (BRep_Tool::Degenerated(edge)) continue;
        const int idx = e2f.FindIndex(edge);
        if (idx == 0) continue;
        TopoDS_Face other;
        for (TopTools_ListOfShape::Iterator it(e2f(idx)); it.More(); it.Next())
            if (!it.Value().IsSame(f.face)) other = TopoDS::Face(it.Value());
        if (other.IsNull()) continue;  // a seam
        BRepAdaptor_Curve c(edge);
        const double t = 0.5 * (c.FirstParameter() + c.LastParameter());
        gp_Pnt p;
        gp_Vec tangent;
        c.D1(t, p, tangent);
        if (tangent.Magnitude() < 1e-12) continue;
        Vector3d T = vec(tangent).normalized();
        if (edge.Orientation() == TopAbs_REVERSED) T = -T;
        Vector3d d1 = f.normal.cross(T).normalized();
        // The face lies on the left of its edges seen from outside; check on the face itself, in
        // case of an unusual orientation, and turn d1 if the probe lands outside.
        const double probe =
            std::max(1e-4, 1e-3 * (c.LastParameter() - c.FirstParameter()) * tangent.Magnitude());
        BRepClass_FaceClassifier inside(f.face, pnt(vec(p) + probe * d1), 1e-7);
        if (inside.State() == TopAbs_OUT) d1 = -d1;
        // The other face's normal at the same point of the edge, from its pcurve.
        double f0, f1;
        const Handle(Geom2d_Curve) pc = BRep_Tool::CurveOnSurface(edge, other, f0, f1);
        if (pc.IsNull()) continue;
        const gp_Pnt2d uv = pc->Value(t);
        Vector3d n2;
        if (!face_normal(other, uv.X(), uv.Y(), n2)) continue;
        const double signed_angle = std::atan2(n2.dot(d1), n2.dot(f.normal));
        if (signed_angle > min_angle_rad) return true;
    }
    return false;
}

// Eq. 5's Proj_min and Proj_max of the face's outer wire along D (exact for an axis-aligned D,
// every march direction; see range_along).
void projection_range(const TopoDS_Face& face, const Vector3d& D, double& lo, double& hi) {
    range_along(bounds_of(BRepTools::OuterWire(face)), D, lo, hi);
}

using occ::solids_of;

// Whether any face or edge of `s` is only C0 (a kink inside one surface or curve). OCCT's
// Booleans expect C1 arguments; the splits of a C0 part (a tube swept along a helix, whose
// surface the sweep made C0) can pass the shape check and still mesh with edges shared by three
// triangles.
bool has_c0_geometry(const TopoDS_Shape& s) {
    for (TopExp_Explorer x(s, TopAbs_FACE); x.More(); x.Next()) {
        const Handle(Geom_Surface) surface = BRep_Tool::Surface(TopoDS::Face(x.Current()));
        if (!surface.IsNull() && surface->Continuity() == GeomAbs_C0) return true;
    }
    for (TopExp_Explorer x(s, TopAbs_EDGE); x.More(); x.Next()) {
        Standard_Real first, last;
        const Handle(Geom_Curve) curve = BRep_Tool::Curve(TopoDS::Edge(x.Current()), first, last);
        if (!curve.IsNull() && curve->Continuity() == GeomAbs_C0) return true;
    }
    return false;
}

// Whether an edge's curve on one of its faces strays from its 3-D curve by more than the edge's
// tolerance (what FreeCAD's Check geometry reports as BOPAlgo_InvalidCurveOnSurface; common where
// cylinders were fused: 54 of 142 survey parts have it). A split of such a part can also pass
// the shape check and mesh with edges shared by three triangles: two slanted pins on a column,
// whose cut-off upper column stopped slicing.
bool has_invalid_curve_on_surface(const TopoDS_Shape& s, const Progress& progress) {
    // BOPAlgo_ArgumentAnalyzer's test, stopping at the first fault (the analyzer goes through
    // every face and edge whatever it is told: 2 s on a part of 1275 faces) and between faces
    // checking for a cancel.
    for (TopExp_Explorer f(s, TopAbs_FACE); f.More(); f.Next()) {
        progress.check();
        const TopoDS_Face& face = TopoDS::Face(f.Current());
        for (TopExp_Explorer e(face, TopAbs_EDGE); e.More(); e.Next()) {
            const TopoDS_Edge& edge = TopoDS::Edge(e.Current());
            Standard_Real distance = 0.0, parameter = 0.0;
            try {
                if (BOPTools_AlgoTools::ComputeTolerance(face, edge, distance, parameter) &&
                    distance > BRep_Tool::Tolerance(edge))
                    return true;
            } catch (const Standard_Failure&) {
                return true;  // as the analyzer: a pair OCCT cannot measure counts as faulty
            }
        }
    }
    return false;
}

// Whether OCCT meshes `solid` into a closed surface at `deflection` mm, as slicing will; always
// true for `deflection` 0 (no check asked).
bool meshes_closed(const TopoDS_Shape& solid, double deflection) {
    if (deflection <= 0.0) return true;
    try {
        // A piece valid_solid() passed: no shape check again.
        occ::tessellate_solid(solid, deflection, TessellationParams{}.angular_deflection_rad,
                              "piece");
        return true;
    } catch (const Error&) {
        return false;
    }
}

// Which pieces of a split must mesh closed at `deflection` mm (slicing's, the part's; 0: none).
// On a part OCCT's Booleans do not promise to split soundly (C0 geometry, curves off their
// faces), every piece. On a sound part, a piece the split itself left so: a pipe bend lying on
// its side, cut across its torus, came out of the splitter with a C0 edge off its face, which
// passed the shape check and then meshed with an edge shared by three triangles, and slicing
// stopped there.
struct MeshCheck {
    double deflection = 0.0;
    bool every_piece = false;
};

// The piece's faces are scanned without a stop between them (valid_solid's attempts are the stops,
// each reported: one per face would flood a GUI with reports on a part of many faces).
bool meshes_as_needed(const TopoDS_Shape& solid, const MeshCheck& mesh) {
    if (mesh.deflection <= 0.0) return true;
    if (!mesh.every_piece && !has_c0_geometry(solid) &&
        !has_invalid_curve_on_surface(solid, Progress()))
        return true;
    return meshes_closed(solid, mesh.deflection);
}

// One solid of `piece` that OCCT's shape check accepts and that meshes closed as `mesh` asks, for
// a component: the piece with the seams between coplanar or co-cylindrical faces removed
// (`unified`, when already done), else the piece as the split left it, else what ShapeFix makes
// of it; false when none is one valid solid. (The splitter and the seam removal can leave a face
// whose wires the check rejects: a tee's pipe cut across its branch.) `progress` is checked
// before each attempt: on a C0 part each one meshes the piece.
bool valid_solid(const TopoDS_Shape& piece, TopoDS_Shape& out, const MeshCheck& mesh,
                 const Progress& progress, const TopoDS_Shape& unified = TopoDS_Shape()) {
    for (int attempt = 0; attempt < 3; ++attempt) {
        progress.check();
        try {
            TopoDS_Shape s = piece;
            if (attempt == 0) s = unified.IsNull() ? occ::unify(piece) : unified;
            if (attempt == 2) {
                // On a copy: ShapeFix mends tolerances in place, on what the piece shares with
                // the other pieces of the split.
                ShapeFix_Shape fix(BRepBuilderAPI_Copy(piece).Shape());
                fix.Perform();
                s = fix.Shape();
            }
            const auto solids = solids_of(s);
            if (solids.size() == 1 && BRepCheck_Analyzer(solids.front()).IsValid() &&
                meshes_as_needed(solids.front(), mesh)) {
                out = solids.front();
                return true;
            }
        } catch (const Standard_Failure&) {
            // No solid OCCT can check; the next attempt may be one.
        }
    }
    return false;
}

// Whether p lies inside the solid (farther than 1e-7 from its boundary). `keep`: by the solid's
// kept classifier within a KeptQueries scope, for the components, which are asked again and again
// (a split's pieces are asked once or twice, then dropped).
bool contains(const TopoDS_Shape& solid, const Vector3d& p, bool keep = false) {
    if (!keep || !kept)
        return BRepClass3d_SolidClassifier(solid, pnt(p), 1e-7).State() == TopAbs_IN;
    BRepClass3d_SolidClassifier& c = kept->classifier(solid);
    c.Perform(pnt(p), 1e-7);
    return c.State() == TopAbs_IN;
}

struct Child {
    TopoDS_Shape solid;
    TopoDS_Face base;
    Vector3d base_origin, base_normal;
    // Why the piece holding the point stayed in the father instead (empty when it did not).
    std::string kept_because;
    // Kept for reaching less than the least height past the plane: another plane near the
    // junction would not do better.
    bool too_short = false;
};

// What a father stands on, which no split may take from it: the root's footing on the build plate
// (its material at the part's lowest z), a child's base face.
struct Footing {
    bool root = true;
    double plate_z = 0.0;  // root: the plate's height
    // root: whether it may be left several solids apart, each standing on the plate (a bridge's
    // split of a part on several feet: a portal's legs without its lintel)
    bool feet = false;
    TopoDS_Face base;   // child: its base face
    Vector3d normal;    // child: the base face's outward normal
    double tol = 1e-6;  // mm
};

// A point strictly inside `face` (its centroid when that is inside, else the first inside point
// of a grid over its parameter range); false for a face too thin to find one.
bool point_inside(const TopoDS_Face& face, double tol, gp_Pnt& out) {
    GProp_GProps props;
    BRepGProp::SurfaceProperties(face, props);
    out = props.CentreOfMass();
    if (BRepClass_FaceClassifier(face, out, tol).State() == TopAbs_IN) return true;
    double u0, u1, v0, v1;
    BRepTools::UVBounds(face, u0, u1, v0, v1);
    const BRepAdaptor_Surface surface(face, Standard_False);
    constexpr int kGrid = 16;
    for (int i = 0; i < kGrid; ++i)
        for (int j = 0; j < kGrid; ++j) {
            const gp_Pnt2d uv(u0 + (u1 - u0) * (i + 0.5) / kGrid,
                              v0 + (v1 - v0) * (j + 0.5) / kGrid);
            if (BRepClass_FaceClassifier(face, uv, tol).State() != TopAbs_IN) continue;
            out = surface.Value(uv.X(), uv.Y());
            return true;
        }
    return false;
}

// Does `piece` (of a split father) hold any of the father's footing? For a child: has it a face
// on the base face's plane that is part of the base face? (The split divides faces, so each of
// the piece's faces lies within one face of the father: one inside point tells which.)
bool holds_footing(const TopoDS_Shape& piece, const Footing& f) {
    if (f.root) return bounds_of(piece).min().z() <= f.plate_z + f.tol;
    PlanarFace base;
    if (!planar(f.base, base)) return false;
    for (TopExp_Explorer x(piece, TopAbs_FACE); x.More(); x.Next()) {
        PlanarFace pf;
        if (!planar(TopoDS::Face(x.Current()), pf)) continue;
        if (pf.normal.dot(f.normal) < 1.0 - 1e-9) continue;
        if (std::abs(f.normal.dot(pf.point - base.point)) > f.tol) continue;
        gp_Pnt p;
        if (!point_inside(pf.face, f.tol, p)) continue;
        const TopAbs_State st = BRepClass_FaceClassifier(f.base, p, f.tol).State();
        if (st == TopAbs_IN || st == TopAbs_ON) return true;
    }
    return false;
}

// What is left of a split `father` as a component: one valid solid (valid_solid), or, for a root
// that may stand on several feet (Footing::feet) and falls apart, a compound of valid solids, each
// standing on the build plate. `unified`: the father with its seams removed, when already done.
bool valid_father(const TopoDS_Shape& father, const Footing& footing, TopoDS_Shape& out,
                  const MeshCheck& mesh, const Progress& progress,
                  const TopoDS_Shape& unified = TopoDS_Shape()) {
    if (!footing.root || !footing.feet) return valid_solid(father, out, mesh, progress, unified);
    const TopoDS_Shape u = unified.IsNull() ? occ::unify(father) : unified;
    const auto solids = solids_of(u);
    if (solids.size() < 2) return valid_solid(father, out, mesh, progress, u);
    BRep_Builder builder;
    TopoDS_Compound feet;
    builder.MakeCompound(feet);
    for (const TopoDS_Shape& s : solids) {
        TopoDS_Shape foot;
        if (!holds_footing(s, footing) || !valid_solid(s, foot, mesh, progress, s)) return false;
        builder.Add(feet, foot);
    }
    out = feet;
    return true;
}

// How far `s` reaches along the unit `n` beyond `point` (range_along: exact for an axis-aligned
// n, an upper bound otherwise).
double height_along(const TopoDS_Shape& s, const Vector3d& point, const Vector3d& n) {
    double lo, hi;
    range_along(bounds_of(s), n, lo, hi);
    return hi - n.dot(point);
}

// `first` fused with `tools` in OCCT's non-destructive mode (the inputs are kept: a father's
// other pieces, a child that may still go without the piece); false when OCCT fails.
bool fuse_kept(const TopoDS_Shape& first, const TopTools_ListOfShape& tools, TopoDS_Shape& out) {
    BRepAlgoAPI_Fuse fuse;
    TopTools_ListOfShape arguments;
    arguments.Append(first);
    fuse.SetArguments(arguments);
    fuse.SetTools(tools);
    fuse.SetNonDestructive(Standard_True);
    fuse.Build();
    if (!fuse.IsDone() || fuse.HasErrors()) return false;
    out = fuse.Shape();
    return true;
}

enum class SplitOutcome {
    Split,    // at least one child; the father is what is left
    NoChild,  // no piece qualified as a child: nothing changes
    Failed,   // OCCT failed
    Apart,    // the rest of the father would not be one solid
    Invalid,  // the rest of the father would be no valid solid
    Uncut,    // the plane leaves the father whole (it bounds it, or misses it)
};

// Splits `father` by the plane (point, normal n) and takes as children the pieces containing the
// `inner` points on the +n side (one each, a piece at most once; a point without a piece gets a
// null child) that reach at least `min_height` beyond the plane, hold at most `max_volume[k]`
// and none of the father's `footing`. Every other piece goes back into the father (fused, seams
// removed). With `joined`, a piece that then stands apart from the father's footing, on the
// father's side of the plane and joined to exactly one child, goes with that child instead, and
// `joined` counts them (set only on Split). `progress` is checked between the steps (OCCT's own
// calls run uninterrupted).
SplitOutcome split_by_plane(const TopoDS_Shape& father, const Footing& footing,
                            const Vector3d& point, const Vector3d& n,
                            const std::vector<Vector3d>& inner, double min_height,
                            const std::vector<double>& max_volume, const MeshCheck& mesh,
                            const Progress& progress, std::vector<Child>& children,
                            TopoDS_Shape& father_out, int* joined) {
    try {
        const Eigen::AlignedBox3d b = bounds_of(father);
        const double r = 2.0 * b.diagonal().norm() + 1.0;
        const Vector3d c = b.center();
        const Vector3d origin = c - n * n.dot(c - point);
        const gp_Pln pln(pnt(origin), gp_Dir(n.x(), n.y(), n.z()));
        const TopoDS_Face tool = BRepBuilderAPI_MakeFace(pln, -r, r, -r, r).Face();

        BRepAlgoAPI_Splitter splitter;
        TopTools_ListOfShape args, tools;
        // A copy: a failed split can leave the solid it was given altered, non-destructive mode
        // notwithstanding (a pipe cross whose side arms OCCT cannot cut then failed the shape
        // check as the root component).
        args.Append(BRepBuilderAPI_Copy(father).Shape());
        tools.Append(tool);
        splitter.SetArguments(args);
        splitter.SetTools(tools);
        splitter.SetNonDestructive(Standard_True);
        splitter.Build();
        if (!splitter.IsDone() || splitter.HasErrors()) return SplitOutcome::Failed;
        const auto pieces = solids_of(splitter.Shape());
        if (pieces.size() < 2) return SplitOutcome::Uncut;

        std::vector<bool> taken(pieces.size(), false);
        // Whether each piece holds some of the father's footing, worked out when first asked.
        std::vector<int> footed(pieces.size(), -1);
        const auto holds = [&](std::size_t i) {
            if (footed[i] < 0) footed[i] = holds_footing(pieces[i], footing) ? 1 : 0;
            return footed[i] == 1;
        };
        children.assign(inner.size(), Child{});
        const double tol = 1e-6 * (1.0 + b.diagonal().norm());
        // The base face: the child's face on the plane, facing -n, that lies under the branch's
        // first node; the largest one if none does. (A plane can cut a piece in several faces: a
        // half ring standing on its rim has one at each end, and the branch starts from one of
        // them.)
        const auto find_base = [&](std::size_t k, Child& child) {
            child.base = TopoDS_Face();
            const Vector3d under = inner[k] - n * n.dot(inner[k] - point);
            bool best_under = false;
            double best_area = 0.0;
            for (TopExp_Explorer x(child.solid, TopAbs_FACE); x.More(); x.Next()) {
                PlanarFace pf;
                if (!planar(TopoDS::Face(x.Current()), pf)) continue;
                if (pf.normal.dot(-n) < 1.0 - 1e-9) continue;
                if (std::abs(n.dot(pf.point - point)) > tol) continue;
                GProp_GProps fp;
                BRepGProp::SurfaceProperties(pf.face, fp);
                const TopAbs_State st = BRepClass_FaceClassifier(pf.face, pnt(under), tol).State();
                const bool is_under = st == TopAbs_IN || st == TopAbs_ON;
                if (best_under && !is_under) continue;
                if (best_under == is_under && fp.Mass() <= best_area) continue;
                best_under = is_under;
                best_area = fp.Mass();
                child.base = pf.face;
                child.base_origin = vec(fp.CentreOfMass());
                child.base_normal = pf.normal;
            }
            return !child.base.IsNull();
        };
        int found = 0;
        for (std::size_t k = 0; k < inner.size(); ++k) {
            std::size_t piece = pieces.size();
            for (std::size_t i = 0; i < pieces.size() && piece == pieces.size(); ++i)
                if (!taken[i] && contains(pieces[i], inner[k])) piece = i;
            if (piece == pieces.size()) continue;
            GProp_GProps props;
            BRepGProp::VolumeProperties(pieces[piece], props);
            if (n.dot(vec(props.CentreOfMass()) - point) <= 0.0) continue;
            // A sliver the plane cut off the father's end (the march found it on its last
            // plane) cannot be built on its own: it stays in the father, which builds it on top.
            // (Within the split's tolerance: a crank's web reaching exactly a thickest layer past
            // T round its shaft fell short of it by rounding.)
            const double height = height_along(pieces[piece], point, n);
            if (height < min_height - tol) {
                std::ostringstream why;
                why << "its piece reaches only " << height << " mm past the splitting plane, "
                    << "less than " << min_height
                    << " mm (the axis step, or a thickest layer for a branch that turned, or the "
                       "least component height): too thin to build "
                       "on its own";
                children[k].kept_because = why.str();
                children[k].too_short = true;
                continue;
            }
            // A piece far bigger than what the branch and its sub-branches swept is mostly other
            // branches' material: the whole plane of a sliver's split (a few hundredths of a mm2
            // the sections left beside a pipe tee's branch) would cut that branch in two.
            if (props.Mass() > max_volume[k]) {
                std::ostringstream why;
                why << "its piece would hold " << props.Mass() << " mm3, far more than the "
                    << max_volume[k] << " mm3 its march and sub-branches allow: mostly other "
                    << "branches' material";
                children[k].kept_because = why.str();
                continue;
            }
            // A split must not take what the father stands on. A piece on the build plate is
            // built up from it, with the root (a nozzle building it sideways would meet the
            // plate). A child's father must keep some of its base face: a piece may take part of
            // it (the upper half of a bar built along X, cut off to be built up on the lower
            // half), not all, or the father would be left with nothing to be built from.
            bool takes_footing = holds(piece);
            if (takes_footing && !footing.root)
                for (std::size_t i = 0; i < pieces.size() && takes_footing; ++i)
                    if (i != piece && !taken[i] && holds(i)) takes_footing = false;
            if (takes_footing) {
                children[k].kept_because = footing.root ? "its piece rests on the build plate"
                                                        : "its piece holds its father's base face";
                continue;
            }
            Child child;
            if (!valid_solid(pieces[piece], child.solid, mesh, progress)) {
                children[k].kept_because =
                    "its piece of the split is no valid solid (OCCT's check, or a closed mesh)";
                continue;
            }
            if (!find_base(k, child)) continue;
            taken[piece] = true;
            children[k] = child;
            ++found;
        }
        if (found == 0) return SplitOutcome::NoChild;

        TopTools_ListOfShape rest;
        for (std::size_t i = 0; i < pieces.size(); ++i)
            if (!taken[i]) rest.Append(pieces[i]);
        TopoDS_Shape father_new;
        if (rest.Extent() == 1) {
            father_new = rest.First();
        } else {
            const TopoDS_Shape first = rest.First();
            rest.RemoveFirst();
            if (!fuse_kept(first, rest, father_new)) return SplitOutcome::Failed;
        }
        TopoDS_Shape unified = occ::unify(father_new);
        int joins = 0;
        if (solids_of(unified).size() != 1 && !(footing.root && footing.feet)) {
            // The plane may cut off, on the father's side, material joined only to a child: an
            // S bracket's top plate, whose tail past the plane hangs from the part of it the
            // middle plate's child takes. Such a piece goes with that child (when asked), to be
            // taken from it by the later split of the branch it belongs to; what stands on the
            // father's footing stays the father.
            if (!joined) return SplitOutcome::Apart;
            TopoDS_Shape main;
            std::vector<TopoDS_Shape> orphans;
            for (const auto& s : solids_of(unified)) {
                if (holds_footing(s, footing)) {
                    if (!main.IsNull()) return SplitOutcome::Apart;
                    main = s;
                } else {
                    orphans.push_back(s);
                }
            }
            if (main.IsNull()) return SplitOutcome::Apart;
            std::vector<Child> grown = children;
            for (const auto& o : orphans) {
                progress.check();
                // Only material on the father's side: a piece reaching past the plane holds what
                // went back to the father from the child's side (a sibling's piece too short or
                // too big), other branches' material.
                double lo, hi;
                range_along(bounds_of(o), n, lo, hi);
                if (hi - n.dot(point) > tol) return SplitOutcome::Apart;
                // Joined to exactly one child.
                int to = -1;
                TopoDS_Shape fused, whole;
                for (std::size_t k = 0; k < grown.size(); ++k) {
                    if (grown[k].solid.IsNull()) continue;
                    TopTools_ListOfShape tool;
                    tool.Append(o);
                    TopoDS_Shape joined_shape;
                    if (!fuse_kept(grown[k].solid, tool, joined_shape)) return SplitOutcome::Failed;
                    const TopoDS_Shape u = occ::unify(joined_shape);
                    if (solids_of(u).size() != 1) continue;  // not touching this child
                    if (to >= 0) return SplitOutcome::Apart;
                    to = int(k);
                    fused = joined_shape;
                    whole = u;
                }
                if (to < 0) return SplitOutcome::Apart;
                Child& c = grown[std::size_t(to)];
                if (!valid_solid(fused, c.solid, mesh, progress, whole) ||
                    !find_base(std::size_t(to), c))
                    return SplitOutcome::Invalid;
                GProp_GProps props;
                BRepGProp::VolumeProperties(c.solid, props);
                if (props.Mass() > max_volume[std::size_t(to)]) return SplitOutcome::Apart;
            }
            children = std::move(grown);
            joins = int(orphans.size());
            father_new = main;
            unified = main;  // a solid of `unified`: its seams are already removed
        }
        progress.check();
        if (!valid_father(father_new, footing, father_out, mesh, progress, unified))
            return SplitOutcome::Invalid;
        if (joined) *joined = joins;
        return SplitOutcome::Split;
    } catch (const Standard_Failure&) {
        return SplitOutcome::Failed;  // a split OCCT cannot perform: the branches stay put
    }
}

// `shape`'s planar faces with outward normal `n` on the plane n.x = c (within tol).
TopoDS_Compound faces_on_plane(const TopoDS_Shape& shape, const Vector3d& n, double c, double tol) {
    BRep_Builder builder;
    TopoDS_Compound out;
    builder.MakeCompound(out);
    for (TopExp_Explorer x(shape, TopAbs_FACE); x.More(); x.Next()) {
        PlanarFace pf;
        if (planar(TopoDS::Face(x.Current()), pf) && pf.normal.dot(n) >= 1.0 - 1e-9 &&
            std::abs(n.dot(pf.point) - c) <= tol)
            builder.Add(out, pf.face);
    }
    return out;
}

// The vertex of the mesh lowest along d (the first of them).
Vector3d lowest_along(const TriangleMesh& m, const Vector3d& d) {
    double lowest = std::numeric_limits<double>::infinity();
    Vector3d at = Vector3d::Zero();
    for (const Vector3d& q : m.vertices)
        if (d.dot(q) < lowest) {
            lowest = d.dot(q);
            at = q;
        }
    return at;
}

// The origin of the base plane of a bridge's piece built along d from its lowest point `at` that
// way, its base on the plane D.x = s (D its father's build direction): at + a (D - w), w =
// sqrt(2) d - D the way along the gap, so that D.(..) = s and d.(..) stays d.at.
Vector3d diagonal_base_origin(const Vector3d& at, const Vector3d& D, const Vector3d& d, double s) {
    return at + (s - D.dot(at)) * (2.0 * D - std::sqrt(2.0) * d);
}

double area_of(const TopoDS_Shape& s) {
    GProp_GProps props;
    BRepGProp::SurfaceProperties(s, props);
    return props.Mass();
}

// What of a bridge's piece hangs on its splitting plane (normal D at offset s): its faces there,
// facing -D, less its father's faces there, facing +D (an OCCT cut of the coplanar faces: seams
// removed, the piece's underside is one face with what rests on the father, and a mesh of it need
// not part them).
TopoDS_Shape hanging_on_plane(const TopoDS_Shape& piece, const TopoDS_Shape& father,
                              const Vector3d& D, double s, double tol) {
    BRepAlgoAPI_Cut cut(faces_on_plane(piece, -D, -s, tol), faces_on_plane(father, D, s, tol));
    if (!cut.IsDone() || cut.HasErrors())
        throw Standard_Failure("the cut of a bridge's underside by its father's top failed");
    return cut.Shape();
}

// Calls f(a, b, c, area) for each triangle of the meshed piece `m` off its splitting plane (normal
// D at offset s, within tol) that leans past `overhang_deg` off the unit d (leans_past).
template <class F>
void for_each_leaning(const TriangleMesh& m, const Vector3d& d, double overhang_deg,
                      const Vector3d& D, double s, double tol, F&& f) {
    for (const Eigen::Vector3i& t : m.triangles) {
        const Vector3d &a = m.vertices[std::size_t(t[0])], &b = m.vertices[std::size_t(t[1])],
                       &c = m.vertices[std::size_t(t[2])];
        if (std::abs(D.dot(a) - s) <= tol && std::abs(D.dot(b) - s) <= tol &&
            std::abs(D.dot(c) - s) <= tol)
            continue;
        const Vector3d n = (b - a).cross(c - a);
        const double twice = n.norm();
        if (twice > 0.0 && leans_past(n / twice, d, overhang_deg)) f(a, b, c, 0.5 * twice);
    }
}

// The area of a bridge's piece that overhangs built along the unit `d`: of its meshed surface off
// the splitting plane, the triangles leaning past `overhang_deg` off d, and `hanging` (its
// underside on the plane that rests on nothing) where that leans so too.
double overhang_area(const TriangleMesh& m, const Vector3d& d, double overhang_deg,
                     const Vector3d& D, double s, double tol, double hanging) {
    double area = leans_past(-D, d, overhang_deg) ? hanging : 0.0;
    for_each_leaning(
        m, d, overhang_deg, D, s, tol,
        [&](const Vector3d&, const Vector3d&, const Vector3d&, double a) { area += a; });
    return area;
}

void check_params(const DecomposeParams& p) {
    if (!(p.face_angle_deg >= 0.0 && p.face_angle_deg < 90.0))
        throw Error(ErrorCode::InvalidArgument, "decompose: face angle must be in [0, 90) degrees");
    if (!(p.concave_angle_deg >= 0.0 && p.concave_angle_deg < 180.0))
        throw Error(ErrorCode::InvalidArgument,
                    "decompose: concave angle must be in [0, 180) degrees");
    if (!(p.projection_tolerance_mm >= 0.0 && std::isfinite(p.projection_tolerance_mm)))
        throw Error(ErrorCode::InvalidArgument,
                    "decompose: projection tolerance must be finite and not negative");
    if (!(p.min_component_height_mm >= 0.0 && std::isfinite(p.min_component_height_mm)))
        throw Error(ErrorCode::InvalidArgument,
                    "decompose: minimum component height must be finite and not negative");
    if (!(p.max_tilt_deg >= 90.0 && p.max_tilt_deg <= 180.0))
        throw Error(ErrorCode::InvalidArgument,
                    "decompose: max_tilt must be in [90, 180] degrees, got " +
                        format_number(p.max_tilt_deg));
    if (!(p.overhang_angle_deg > 0.0 && p.overhang_angle_deg < 90.0))
        throw Error(ErrorCode::InvalidArgument,
                    "decompose: overhang angle must be in (0, 90) degrees, got " +
                        format_number(p.overhang_angle_deg));
}

struct Work {
    TopoDS_Shape solid;
    Component c;
};

// Where a branch asks to be cut from its father, and by which plane.
struct Plan {
    Component::SplitRule rule = Component::SplitRule::PlanarFace;
    Vector3d point, normal;    // the splitting plane; normal . D > 0
    Vector3d pos_end;          // the branch's first node
    Vector3d inner;            // a point in the material of its first section
    bool by_own_face = false;  // a face chosen nearest the father's own face (over a gusset)
    bool turned = false;       // a section plane turned square to the branch's line (plan())
};

class Decomposer {
public:
    // `clearance`: how far past a branch's Eq. 4 extent T the section plane goes (see plan()).
    Decomposer(const CentroidalAxis& axis, const DecomposeParams& params, double clearance)
        : axis_(axis),
          params_(params),
          clearance_(clearance),
          cos_face_(std::cos(params.face_angle_deg * kPi / 180.0)),
          min_concave_(params.concave_angle_deg * kPi / 180.0) {}

    // The splitting plane for branch b on the father solid `fs` (edge-face map `e2f`): the
    // criteria's face nearest the father's own face over a gusset (`attempt` 0) or nearest the
    // junction (0 without a gusset, or 1), else (or with `attempt` 2) the section plane, turned
    // square to a branch running off D (not with `attempt` 3); false for none.
    bool plan(std::size_t b, const TopoDS_Shape& fs,
              const TopTools_IndexedDataMapOfShapeListOfShape& e2f, Plan& out,
              int attempt = 0) const {
        const AxisBranch& br = axis_.branches[b];
        const AxisLink& link = axis_.links[std::size_t(br.first_link)];
        const Vector3d D = br.direction.normalized();
        const Vector3d pos_start = axis_.nodes[std::size_t(link.start)].position;
        const AxisNode& first = axis_.nodes[std::size_t(br.nodes.front())];
        out.pos_end = first.position;
        out.inner = first.material_point();
        double lo_span = std::min(D.dot(pos_start), D.dot(out.pos_end));
        double hi_span = std::max(D.dot(pos_start), D.dot(out.pos_end));
        const double tol = params_.projection_tolerance_mm;
        const double junction = first.offset - 0.5 * axis_.params.step_mm;
        double best = std::numeric_limits<double>::infinity();
        PlanarFace chosen;
        // The branch's first section, seen along D (the node's plane has normal D), grown by a
        // step: a splitting face must lie over it. Without this, the side face of one blade on a
        // hub, parallel to another blade's branch, cut the hub in half.
        // An axis handed over without its regions (a dict built by hand) gives a square around
        // the centroid with the section's area, half again as wide.
        const PlaneFrame frame(first.normal);
        Eigen::AlignedBox2d reach = bounds(first.region);
        if (first.region.outer.points.empty()) {
            const Eigen::Vector2d c = frame.to_2d(first.position);
            const Eigen::Vector2d half = Eigen::Vector2d::Constant(0.75 * std::sqrt(first.area));
            reach = Eigen::AlignedBox2d(c - half, c + half);
        }
        reach.min().array() -= axis_.params.step_mm;
        reach.max().array() += axis_.params.step_mm;
        // Eq. 5's span, widened to take in the father's nodes from pos_start back along its march
        // while they reach no further towards the branch, up to the first that stops shrinking
        // away from it (criterion (3) in Decompose.hpp: a gusset). A face only the widened span
        // admits must face the branch.
        const double lo_eq5 = lo_span, hi_eq5 = hi_span;
        // Where the walk found the father's own section (how far it reaches along D), if it
        // did: over a gusset, the face to cut at is the one nearest it, not the junction.
        double own_face = std::numeric_limits<double>::quiet_NaN();
        const int fb = axis_.nodes[std::size_t(link.start)].branch;
        if (fb >= 0 && std::size_t(fb) < axis_.branches.size()) {
            const std::vector<int>& march = axis_.branches[std::size_t(fb)].nodes;
            auto k = std::find(march.begin(), march.end(), link.start);
            double next = std::numeric_limits<double>::infinity();
            bool shrinking = false;
            for (; k != march.end(); --k) {
                const AxisNode& n = axis_.nodes[std::size_t(*k)];
                // A section across D lies under the branch, not beside it: where the father
                // marches along D itself (two arms forking out of a column's march), its sections
                // below are the trunk both arms stand on, not the branch's near end.
                if (*k != link.start && std::abs(n.normal.dot(D)) > 0.5) break;
                const double e = reach_along(n, D);
                if (e > next + tol) break;  // reaching further back: bulging towards the branch
                lo_span = std::min(lo_span, D.dot(n.position));
                hi_span = std::max(hi_span, D.dot(n.position));
                if (std::isfinite(next)) {
                    if (e < next - tol) {
                        shrinking = true;
                    } else if (shrinking) {
                        own_face = e;
                        break;  // shrunk down to the father's own section
                    }
                }
                next = e;
                if (k == march.begin()) break;
            }
        }
        // Retried after a planar face's split was refused: nearest the junction, then the
        // section plane only.
        const bool by_own_face = attempt == 0 && !std::isnan(own_face);
        const double near_to = by_own_face ? own_face : junction;
        if (attempt < 2) {
            for (TopExp_Explorer x(fs, TopAbs_FACE); x.More(); x.Next()) {
                PlanarFace pf;
                if (!planar(TopoDS::Face(x.Current()), pf)) continue;
                if (std::abs(pf.normal.dot(D)) < cos_face_) continue;  // (1)
                // The child would be built along the face's normal: within the machine's reach.
                if (tilt_from_plate_deg(pf.normal.dot(D) > 0.0 ? pf.normal : Vector3d(-pf.normal)) >
                    params_.max_tilt_deg + 1e-9)
                    continue;
                double lo, hi;
                projection_range(pf.face, D, lo, hi);
                const auto in_span = [&](double v, double from, double to) {
                    return v >= from - tol && v <= to + tol;
                };
                if (!in_span(lo, lo_eq5, hi_eq5) && !in_span(hi, lo_eq5, hi_eq5) &&
                    (pf.normal.dot(D) <= 0.0 ||
                     (!in_span(lo, lo_span, hi_span) && !in_span(hi, lo_span, hi_span))))
                    continue;  // (3)
                const Eigen::AlignedBox3d box = bounds_of(pf.face);
                Eigen::AlignedBox2d across;
                for (int corner = 0; corner < 8; ++corner)
                    across.extend(frame.to_2d(box.corner(Eigen::AlignedBox3d::CornerType(corner))));
                if (!across.intersects(reach)) continue;                 // over the branch
                if (!has_concave_edge(pf, e2f, min_concave_)) continue;  // (2)
                // Nearest the junction; over a gusset, nearest the father's own face first (the
                // branch's march starts past the web's tip, and a face of the arm on the way,
                // a post's or a step's, would cut it partway, its stub over the web left in
                // the father, overhanging). Where the walk down the father crossed where its
                // march merged another (a portal's deck over two piers), that face may be the
                // wrong pier's: its split is refused, and the junction's face is tried.
                const double d = std::abs(D.dot(pf.point) - near_to);
                if (d < best) {
                    best = d;
                    chosen = pf;
                }
            }
        }
        if (!chosen.face.IsNull()) {
            out.rule = Component::SplitRule::PlanarFace;
            out.by_own_face = by_own_face;
            out.point = chosen.point;
            out.normal = chosen.normal.dot(D) > 0 ? chosen.normal : -chosen.normal;
            return true;
        }
        if (!params_.section_plane_fallback) return false;
        out.rule = Component::SplitRule::SectionPlane;
        // Where the march started, Eq. 4's T, plus the clearance: the first node's grid plane can
        // lie up to a step further on, and the material between, left in the father, would be a
        // stub of the branch hanging off it (a crossbar through a round column).
        double at = std::min(first.offset - axis_.params.eps_mm, first.slab_start + clearance_);
        // Over a gusset whose father has no planar face to cut at (a round column), the father's
        // own section, where the walk down its march stopped shrinking, reaches less far than T
        // (the gusset's tip) by more than a step: the plane goes past it instead, so that the arm
        // over the gusset goes with the branch, gusset and all, as a face's split takes it (cut at
        // T, it stayed in the column's layers, its underside beside the gusset overhanging). When
        // that split is refused, the plane at T is tried.
        out.by_own_face = false;
        if (by_own_face && own_face + clearance_ < first.slab_start - axis_.params.step_mm) {
            at = own_face + clearance_;
            out.by_own_face = true;
        }
        // A branch running off D (a blade on a hub between -X and +Y): the plane square to its
        // line, just past the father's surface beside it (Decompose.hpp), unless the child would
        // then be built past the machine's reach. Worked out once per father solid: each later
        // sibling asks again while one split is planned.
        const bool may_turn = params_.turn_cuts && attempt < 3 && !out.by_own_face;
        Vector3d along;
        const bool lined = may_turn && branch_line(axis_, b, clearance_, along);
        if (lined && tilt_from_plate_deg(along) <= params_.max_tilt_deg + 1e-9) {
            const auto key = std::make_pair(b, fs.TShape().get());
            auto known = turned_.find(key);
            if (known == turned_.end()) {
                Plan plan = out;
                if (!turn_square(b, fs, along, plan)) plan.turned = false;
                known = turned_.emplace(key, std::make_pair(fs, plan)).first;
            }
            if (known->second.second.turned) {
                out = known->second.second;
                return true;
            }
        }
        // A branch turning off its father round a bend: the bend's halfway plane, the child
        // built along the bisector of its direction and its father's (Decompose.hpp), unless
        // that is past the machine's reach.
        Vector3d bend_point, bisector;
        if (may_turn && !lined &&
            bend_plane(axis_, b, clearance_, out.inner, bend_point, bisector) &&
            tilt_from_plate_deg(bisector) <= params_.max_tilt_deg + 1e-9) {
            out.point = bend_point;
            out.normal = bisector;
            out.turned = true;
            return true;
        }
        const double cut = past_slivers(fs, D, at, frame, reach);
        out.point = D * cut;
        out.normal = D;
        // Where the plane moved past the first node's plane, the node's material, moved along
        // the branch past it (by no more than twice the clearance), lies in the piece.
        if (cut > at && D.dot(out.inner) < cut + clearance_)
            out.inner += D * (cut + clearance_ - D.dot(out.inner));
        return true;
    }

    static bool same_plane(const Plan& a, const Plan& b, double tol) {
        return a.rule == b.rule && a.normal.dot(b.normal) > 1.0 - 1e-12 &&
               std::abs(a.normal.dot(b.point - a.point)) < tol;
    }

private:
    // The section plane turned square to branch b's line `along` (branch_line()), the clearance
    // past the father's surface beside the branch's first section (turned_plane(), the rays cast
    // at the father's faces).
    // On a round hub, the lens between its side and the plane stays in it, as under a round
    // boss. False (the plane square to D is taken) where the first node carries no region, no ray
    // meets the father, or the plane would not leave the first node's centroid the clearance in
    // front of it.
    bool turn_square(std::size_t b, const TopoDS_Shape& fs, const Vector3d& along,
                     Plan& out) const {
        const AxisBranch& br = axis_.branches[b];
        const AxisNode& first = axis_.nodes[std::size_t(br.nodes.front())];
        IntCurvesFace_ShapeIntersector rays;
        rays.Load(fs, Precision::Confusion());
        const double cut = turned_plane(
            axis_, b, along, clearance_,
            [&](const Vector3d& from, const Vector3d& direction, double length,
                std::vector<RayHit>& hits) {
                rays.Perform(gp_Lin(pnt(from), gp_Dir(direction.x(), direction.y(), direction.z())),
                             0.0, length);
                if (rays.IsDone())
                    for (int h = 1; h <= rays.NbPnt(); ++h)
                        hits.push_back({rays.WParameter(h), facing(rays, h)});
            },
            out.inner);
        if (!std::isfinite(cut)) return false;
        out.normal = along;
        out.point = first.position + along * (cut - along.dot(first.position));
        out.by_own_face = false;
        out.turned = true;
        return true;
    }

    // The outward unit normal of the solid's face at a ray's `hit`-th point (zero where the face
    // has none).
    static Vector3d facing(IntCurvesFace_ShapeIntersector& rays, int hit) {
        const TopoDS_Face& face = rays.Face(hit);
        const BRepAdaptor_Surface surface(face);
        gp_Pnt p;
        gp_Vec du, dv;
        surface.D1(rays.UParameter(hit), rays.VParameter(hit), p, du, dv);
        const gp_Vec n = du.Crossed(dv);
        if (n.Magnitude() < 1e-12) return Vector3d::Zero();
        const Vector3d unit = Vector3d(n.X(), n.Y(), n.Z()).normalized();
        return face.Orientation() == TopAbs_REVERSED ? Vector3d(-unit) : unit;
    }

    // T was measured on the mesh, whose chords lie inside a curved face by up to the deflection:
    // a plane at `at` along D (one of +-X, +-Y, +-Z) can cross a face of the father that reaches
    // only a little further (a round shank under a bolt's hex head, its side reaching 0.013 mm
    // past), and the piece past it would keep that sliver of the face's material down to wherever
    // the face runs (the plate). The plane goes past every face it crosses that reaches no further
    // than the clearance past it, over the branch (its first section grown by a step, `reach` in
    // `frame`, as for a splitting face; not the stub another branch's cut left elsewhere): to the
    // furthest such reach (exact, on the BREP), plus eps. (A face reaching less than a micron past
    // it is the plane's own: a round column's side where T was found exactly.)
    double past_slivers(const TopoDS_Shape& fs, const Vector3d& D, double at,
                        const PlaneFrame& frame, const Eigen::AlignedBox2d& reach) const {
        std::vector<std::pair<double, double>> faces;  // (lo, hi) along D, over the branch
        for (TopExp_Explorer ex(fs, TopAbs_FACE); ex.More(); ex.Next()) {
            const Eigen::AlignedBox3d box = bounds_of(ex.Current());
            if (box.isEmpty()) continue;
            Eigen::AlignedBox2d across;
            for (int corner = 0; corner < 8; ++corner)
                across.extend(frame.to_2d(box.corner(Eigen::AlignedBox3d::CornerType(corner))));
            if (!across.intersects(reach)) continue;
            faces.emplace_back(std::min(D.dot(box.min()), D.dot(box.max())),
                               std::max(D.dot(box.min()), D.dot(box.max())));
        }
        // Until the plane crosses no such face (moved, it may cross another).
        double out = at;
        for (bool moved = true; moved;) {
            moved = false;
            for (const auto& [lo, hi] : faces)
                if (lo < out && hi > out + 1e-6 && hi <= out + clearance_) {
                    out = hi + axis_.params.eps_mm;
                    moved = true;
                }
        }
        return out;
    }

    const CentroidalAxis& axis_;
    const DecomposeParams& params_;
    double clearance_;
    double cos_face_, min_concave_;
    // turn_square()'s plans by branch and father solid (turned false for none), each with the
    // solid, held so that its address is not reused for another while the Decomposer lives (only
    // branches running off D have one).
    mutable std::map<std::pair<std::size_t, const void*>, std::pair<TopoDS_Shape, Plan>> turned_;
};

// `shape` turned by `degrees` about the +Z axis through the origin, its geometry moved (no
// location left on it).
TopoDS_Shape turned_about_z(const TopoDS_Shape& shape, double degrees) {
    gp_Trsf turn;
    turn.SetRotation(gp_Ax1(gp_Pnt(0.0, 0.0, 0.0), gp_Dir(0.0, 0.0, 1.0)), degrees * kPi / 180.0);
    return BRepBuilderAPI_Transform(shape, turn, Standard_True).Shape();
}

}  // namespace

// An axis marched in a frame turned about Z (AxisParams::frame_deg) is decomposed in that frame:
// the part and the axis are turned into it, where the branches' directions are +-X, +-Y and +-Z
// as the reading above has them (Eq. 5's projections and the boxes are exact along those), and
// the components turned back.
Decomposition decompose(const Shape& input, const CentroidalAxis& world_axis,
                        const DecomposeParams& params, const Progress& caller) {
    const Progress progress = caller.span(0.0, 1.0, "decomposing");
    check_params(params);
    const Shape checked = input.single_solid("decompose");
    check_kept_branches(params.keep_branches, world_axis, "decompose");
    check_square_branches(params.square_branches, world_axis, "decompose");
    const double frame = axis_frame_deg(world_axis, "decompose");
    std::optional<CentroidalAxis> turned_axis;
    if (frame != 0.0) turned_axis = turned_about_z(world_axis, -frame);
    const CentroidalAxis& axis = turned_axis ? *turned_axis : world_axis;
    const Eigen::Matrix3d to_world =
        Eigen::AngleAxisd(frame * kPi / 180.0, Vector3d::UnitZ()).matrix();
    const KeptQueries keep;
    // The part, checked once for every pass. Work on a copy: OCCT's algorithms must never touch
    // the caller's shape (and each split works on a copy of its father: a pass leaves it as it
    // is).
    TopoDS_Shape solid;
    Eigen::AlignedBox3d box;
    double default_deflection = 0.0;
    MeshCheck mesh;
    try {
        solid = frame != 0.0 ? turned_about_z(occ::occt(checked), -frame)
                             : BRepBuilderAPI_Copy(occ::occt(checked)).Shape();
        box = bounds_of(solid);
        check_axis_belongs(axis, box, occ::volume_of(solid), "decompose");
        // The part's default deflection: what slicing tessellates with unless told otherwise.
        default_deflection = effective_deflection(checked, TessellationParams{});
        // A part with C0 geometry, or with curves off their faces, which OCCT's Booleans do not
        // promise to split soundly: every component must also mesh closed at the deflection
        // slicing uses by default, the part's. (Checked on every part, meshing each piece would
        // add a quarter to the time of slicing a flanged bend or a flat torus.)
        const Progress checking = progress.span(0.0, 0.0, "checking edges against their faces");
        const bool unsound =
            has_c0_geometry(solid) || has_invalid_curve_on_surface(solid, checking);
        mesh.deflection = default_deflection;
        mesh.every_piece = unsound;
    } catch (const Standard_Failure& e) {
        throw Error(ErrorCode::GeometryFailure, occ::failure_message("decompose", e));
    }
    const double plane_tol = 1e-6 * (1.0 + box.diagonal().norm());
    // One pass over the branches. With `join_orphans`, a split's pieces cut off on the father's
    // side but joined only to a child go with that child (split_by_plane), counted in `joins`.
    std::set<int> kept_asked;  // the branches keep_branches kept, this pass
    // Branches whose component did not mesh closed at the part's deflection in an earlier pass
    // (below): kept in their fathers.
    std::vector<KeptBranch> unmeshed;
    const auto pass = [&](bool join_orphans, std::vector<Work>& work,
                          std::vector<std::string>& notes, int& joins) {
        try {
            Work root;
            root.solid = solid;
            root.c.branch = 0;
            root.c.build_direction = axis.branches.front().direction.normalized();
            root.c.base_normal = -root.c.build_direction;
            root.c.base_origin = Vector3d(box.center().x(), box.center().y(), box.min().z());
            work.push_back(root);

            // T was measured on a section of the mesh: on a curved face up to the tessellation's
            // deflection inside the solid, and up to the step / 100 the axis simplifies loops by.
            const double deflection =
                axis.deflection_mm > 0.0 ? axis.deflection_mm : default_deflection;
            const double clearance = axis.params.eps_mm + deflection + 0.01 * axis.params.step_mm;
            const Decomposer decomposer(axis, params, clearance);
            const std::size_t nb = axis.branches.size();
            // The most a branch's component may hold: four times what it and its sub-branches swept
            // (a split plane short of where the march began adds the material between), plus two
            // steps of its first section.
            std::vector<double> max_volume(nb, 0.0);
            for (const auto& node : axis.nodes)
                if (node.branch >= 0 && std::size_t(node.branch) < nb)
                    max_volume[std::size_t(node.branch)] += node.area * node.thickness;
            for (std::size_t b = nb; b-- > 1;)
                if (axis.branches[b].parent >= 0)
                    max_volume[std::size_t(axis.branches[b].parent)] += max_volume[b];
            for (std::size_t b = 0; b < nb; ++b)
                max_volume[b] = 4.0 * max_volume[b] +
                                2.0 * axis.params.step_mm *
                                    axis.nodes[std::size_t(axis.branches[b].nodes.front())].area;
            // A split at a face behind where the branch's march began (Eq. 5's span widened over a
            // gusset, Decompose.hpp) takes the material between as well: at most the branch's first
            // section swept back from T to the face.
            const auto allowance = [&](std::size_t b, const Plan& plan) {
                const AxisBranch& br = axis.branches[b];
                const AxisNode& first = axis.nodes[std::size_t(br.nodes.front())];
                const double behind = first.slab_start - br.direction.normalized().dot(plan.point);
                return max_volume[b] + first.area * std::max(0.0, behind);
            };
            // The component holding each branch's material; -1 until the branch is handled.
            std::vector<int> holder(nb, -1);
            const auto splits = [&](std::size_t b) {
                const AxisBranch& br = axis.branches[b];
                return br.parent >= 0 && br.first_link >= 0 && !br.nodes.empty();
            };
            // The father component of branch b: its parent branch's holder, or whichever component
            // now holds b's first node (an earlier whole-plane split may have moved it), newest
            // first; -1 for none. Where no component is found to hold the first node's material
            // point, its next two nodes' are tried: OCCT's classifier can call a point inside
            // a solid out (a bent pipe's wall cut 67 degrees round its bend, 1.5 mm inside the
            // wall, was out, and 0.5 mm either side of it in: the pipe's run, marched along
            // +X from there, stayed in the riser's layers, 9.6 mm^2 hanging in one).
            const auto father_of = [&](std::size_t b) {
                const int h = holder[std::size_t(axis.branches[b].parent)];
                const std::vector<int>& nodes = axis.branches[b].nodes;
                for (std::size_t i = 0; i < std::min<std::size_t>(nodes.size(), 3); ++i) {
                    const Vector3d p = axis.nodes[std::size_t(nodes[i])].material_point();
                    if (h >= 0 && contains(work[std::size_t(h)].solid, p, true)) return h;
                    for (int k = int(work.size()) - 1; k >= 0; --k)
                        if (contains(work[std::size_t(k)].solid, p, true)) return k;
                }
                return -1;
            };

            // What a father component stands on, which a split must leave it: the root its footing
            // on the plate, a child its base face.
            const auto footing_of = [&](const Component& fc) {
                Footing footing;
                footing.root = !fc.has_base_face;
                footing.plate_z = box.min().z();
                if (fc.has_base_face) footing.base = TopoDS::Face(occ::occt(fc.base_face));
                footing.normal = fc.base_normal;
                footing.tol = std::max(plane_tol, axis.params.eps_mm);
                return footing;
            };

            // Whether branch x has a father and marches as it does.
            const auto marches_as_father = [&](int x) {
                const AxisBranch& bx = axis.branches[std::size_t(x)];
                return bx.parent >= 0 &&
                       bx.direction.isApprox(axis.branches[std::size_t(bx.parent)].direction);
            };
            // Whether branch x is b or comes of it through branches marching as their fathers do
            // (the tracks b's split into where holes broke its sections again).
            const auto in_line = [&](int x, int b) {
                for (; x != b; x = axis.branches[std::size_t(x)].parent)
                    if (!marches_as_father(x)) return false;
                return true;
            };
            // Tracks that split around a hole and join again beyond it (the axis records the merge)
            // are one feature with a hole in it, not sub-components: they stay in their father.
            // So are tracks that split again before they join: a merge between b's line and
            // another split off b's father's (a valve body's ring, broken by two ports' bores
            // into two tracks, one of them by a third into two more, all joining above: cut
            // where the first two parted, the body's upper half lost its bores' lower halves to
            // its lower one, and neither held them whole to be deposited solid).
            const auto rejoins = [&](std::size_t b) {
                const AxisBranch& br = axis.branches[b];
                if (br.merged_into >= 0) return true;
                for (std::size_t o = 0; o < axis.branches.size(); ++o) {
                    const int into = axis.branches[o].merged_into;
                    if (into < 0) continue;
                    if (into == int(b)) return true;
                    const bool from_line = in_line(int(o), int(b));
                    if (from_line == in_line(into, int(b))) continue;
                    if (in_line(from_line ? into : int(o), br.parent)) return true;
                }
                return false;
            };

            // A track the father's march goes on in, where its section split and every other track
            // of the split ended on the plane it began on (one node, no sub-branches): a sliver
            // the march found on one plane (a boss' far end an earlier branch took, a leaning
            // branch's tip, under the plane), thinner than a step, not a fork's arm. It stays in
            // its father: cut off where the sliver parted, a valve body's upper half took the
            // upper half of a port's bore, and neither half held the bore whole to be deposited
            // solid (16.5 mm^2 unsupported under its ceiling).
            std::vector<int> sub_branches(nb, 0);
            for (const auto& br : axis.branches)
                if (br.parent >= 0) ++sub_branches[std::size_t(br.parent)];
            const auto goes_on = [&](std::size_t b) {
                const AxisBranch& br = axis.branches[b];
                bool beside = false;
                for (std::size_t o = 0; o < nb; ++o) {
                    const AxisBranch& other = axis.branches[o];
                    if (o == b || other.parent != br.parent ||
                        other.parent_node != br.parent_node ||
                        !other.direction.isApprox(br.direction))
                        continue;
                    if (other.nodes.size() != 1 || sub_branches[o] != 0) return false;
                    beside = true;
                }
                return beside;
            };
            // Each branch that is its father going on (either of the above): no cut. Worked out
            // once, as it depends on the axis alone (each branch and each sibling grouped with it
            // asks).
            std::vector<char> father_goes_on(nb, 0);
            for (std::size_t b = 0; b < nb; ++b)
                father_goes_on[b] = marches_as_father(int(b)) && (rejoins(b) || goes_on(b));

            // A child built along b's direction would tilt past the machine's reach (straight down,
            // -Z, at the default): b is not cut, its material stays in its father.
            const auto beyond_reach = [&](std::size_t b) {
                return tilt_from_plate_deg(axis.branches[b].direction) > params.max_tilt_deg + 1e-9;
            };

            // Asked to stay in its father (DecomposeParams::keep_branches): why, else null.
            const auto kept_by_caller = [&](std::size_t b) -> const KeptBranch* {
                for (const KeptBranch& k : params.keep_branches)
                    if (k.branch == int(b)) return &k;
                return nullptr;
            };
            // That, or kept because its component did not mesh closed in an earlier pass.
            const auto asked_to_keep = [&](std::size_t b) -> const KeptBranch* {
                if (const KeptBranch* k = kept_by_caller(b)) return k;
                for (const KeptBranch& k : unmeshed)
                    if (k.branch == int(b)) return &k;
                return nullptr;
            };

            // Written out at the end of the pass: a bridge's piece, inserted after its father,
            // moves the components after it, and may take a noted branch's material.
            struct Kept {
                std::size_t branch;
                std::string why;
                int kept_in;
            };
            std::vector<Kept> kept_notes;
            const auto note = [&](std::size_t b, const std::string& why, int kept_in) {
                kept_notes.push_back({b, why, kept_in});
            };
            // Branches whose split at a planar face was refused (its piece took the father's
            // footing, reached other branches' material, or was no valid solid; not one too short,
            // which a plane near the junction cannot lengthen): a face chosen nearest the father's
            // own face over a gusset gives way to the face nearest the junction, and that to the
            // section plane at Eq. 4's T; a section plane past the father's own section over a
            // gusset gives way to the one at T. (The side face of one of two square arms meeting at
            // a round column, chosen for the other, cuts through the column down to the plate: that
            // arm stayed in the root, overhanging.) A section plane turned square to the branch's
            // line gives way to the one square to its direction. Per branch: 0 to 3, as plan()
            // takes it (3 from the start for DecomposeParams::square_branches).
            std::vector<int> attempt(nb, 0);
            for (const int b : params.square_branches) attempt[std::size_t(b)] = 3;
            const auto retry = [&](std::size_t g, const Plan& p) {
                if (p.turned && attempt[g] < 3) {
                    attempt[g] = 3;  // the section plane square to D
                    holder[g] = -1;
                    return true;
                }
                if (attempt[g] >= 2) return false;
                if (p.rule == Component::SplitRule::SectionPlane) {
                    if (!p.by_own_face) return false;
                    attempt[g] = 2;  // at T (no planar face was found the first time either)
                } else if (p.by_own_face && attempt[g] == 0)
                    attempt[g] = 1;
                else if (params.section_plane_fallback)
                    attempt[g] = 2;
                else
                    return false;
                holder[g] = -1;
                return true;
            };
            for (std::size_t b = 0; b < nb; ++b) {
                if (holder[b] >= 0) continue;  // cut with an earlier sibling
                // Done again (without joining, or keeping the branches whose components did not
                // mesh closed), the pass says so: its fractions stay where the first pass left
                // them (a report never goes back), while its branches start over.
                const Progress at = progress.span(
                    double(b) / double(nb), double(b + 1) / double(nb),
                    std::string(unmeshed.empty() ? ""
                                                 : "again, keeping in their fathers the branches "
                                                   "whose components do not mesh closed: ") +
                        (join_orphans ? "" : "again, leaving cut-off tails in their fathers: ") +
                        "splitting at branch " + std::to_string(b) + " of " + std::to_string(nb));
                at(0.0);
                if (!splits(b)) {
                    holder[b] = 0;
                    continue;
                }
                if (father_goes_on[b]) {
                    holder[b] = std::max(holder[std::size_t(axis.branches[b].parent)], 0);
                    continue;
                }
                const int father = father_of(b);
                if (father < 0) {
                    holder[b] = std::max(holder[std::size_t(axis.branches[b].parent)], 0);
                    note(b, "its first node lies in no component", holder[b]);
                    continue;
                }
                holder[b] = father;
                if (const KeptBranch* k = asked_to_keep(b)) {
                    if (kept_by_caller(b)) kept_asked.insert(int(b));
                    note(b, k->why, father);
                    continue;
                }
                if (beyond_reach(b)) {
                    std::ostringstream why;
                    why << "it would be built " << tilt_from_plate_deg(axis.branches[b].direction)
                        << " degrees from the build plate's +Z, past max_tilt ("
                        << params.max_tilt_deg << " degrees): the machine cannot reach it";
                    note(b, why.str(), father);
                    continue;
                }
                const TopoDS_Shape fs = work[std::size_t(father)].solid;
                TopTools_IndexedDataMapOfShapeListOfShape e2f;
                TopExp::MapShapesAndAncestors(fs, TopAbs_EDGE, TopAbs_FACE, e2f);
                Plan p;
                if (!decomposer.plan(b, fs, e2f, p, attempt[b])) {
                    note(b,
                         params.section_plane_fallback
                             ? "no splitting plane could be placed"
                             : "no planar face meets the three criteria and the section-plane "
                               "fallback is off",
                         father);
                    continue;
                }

                // Later siblings in the same father that choose the same plane are cut in the same
                // split: one Boolean instead of one per sibling (a plate with many posts), with the
                // components each would get from its own split of the reduced father.
                std::vector<std::size_t> group{b};
                std::vector<Vector3d> inner{p.inner};
                std::vector<double> most{allowance(b, p)};
                for (std::size_t c = b + 1; c < nb; ++c) {
                    // Each sibling classifies a point in the father and scans its faces.
                    at.check();
                    if (holder[c] >= 0 || !splits(c) || father_goes_on[c] || asked_to_keep(c) ||
                        beyond_reach(c))
                        continue;
                    const int cp = axis.branches[c].parent;
                    if (holder[std::size_t(cp)] < 0) continue;  // a child of an unhandled branch
                    if (std::find(group.begin(), group.end(), std::size_t(cp)) != group.end())
                        continue;
                    if (father_of(c) != father) continue;
                    Plan q;
                    if (!decomposer.plan(c, fs, e2f, q, attempt[c]) ||
                        !Decomposer::same_plane(p, q, plane_tol))
                        continue;
                    group.push_back(c);
                    inner.push_back(q.inner);
                    most.push_back(allowance(c, q));
                }
                at.check();

                const Component& fc = work[std::size_t(father)].c;
                const Footing footing = footing_of(fc);
                std::vector<Child> children;
                TopoDS_Shape father_new;
                // A sliver the father's march found on its last plane (a branch born of a split,
                // going on as its father went) must reach a step past the plane, which the axis
                // cannot resolve below. A branch that turned was found by how far its share reaches
                // out of the section it leaves, however thin it is along its own direction (a 3 mm
                // margin of a clevis's head past the rod under it): it need only hold a thickest
                // layer at slicing's defaults past Eq. 4's T, less the clearance the plane lies
                // past T (a crank's web 2 mm wider than its shaft reached 1.96 mm past the plane).
                // So when every branch cut at this plane turned.
                const auto turned_off_father = [&](std::size_t c) {
                    const int father_branch = axis.branches[c].parent;
                    return father_branch >= 0 &&
                           axis.branches[c].direction.dot(
                               axis.branches[std::size_t(father_branch)].direction) < 0.5;
                };
                const double step_height =
                    std::max(axis.params.step_mm, params.min_component_height_mm);
                const double min_height =
                    std::all_of(group.begin(), group.end(), turned_off_father)
                        ? std::max(
                              std::min(axis.params.step_mm, LayerParams{}.max_layer_mm) - clearance,
                              params.min_component_height_mm)
                        : step_height;
                int joins_here = 0;
                SplitOutcome outcome =
                    split_by_plane(fs, footing, p.point, p.normal, inner, min_height, most, mesh,
                                   at, children, father_new, join_orphans ? &joins_here : nullptr);
                // A child's father must stay as tall as a child must be: later splits of a ladder's
                // rung (a closed loop) carved it down to a 0.07 mm slab no layer fits. (A step, as
                // for a branch born of a split: the father is what a march went on through.)
                bool thinned = false;
                if (outcome == SplitOutcome::Split && fc.has_base_face &&
                    height_along(father_new, fc.base_origin, fc.build_direction) < step_height) {
                    thinned = true;
                    outcome = SplitOutcome::Invalid;
                }
                if (outcome == SplitOutcome::Split) joins += joins_here;
                if (outcome != SplitOutcome::Split && outcome != SplitOutcome::NoChild) {
                    // The siblings that would have shared the split try their own in turn (and
                    // note their own outcome).
                    const char* why =
                        thinned
                            ? "the split at the chosen plane would leave its father thinner along "
                              "its build direction than the axis step (or the least component "
                              "height)"
                        : outcome == SplitOutcome::Failed
                            ? "OCCT could not split its father at the chosen plane"
                        : outcome == SplitOutcome::Uncut
                            ? "the chosen plane leaves its father whole (as where a closed "
                              "loop's other branch took its piece)"
                        : outcome == SplitOutcome::Apart
                            ? "the split at the chosen plane would leave its father in pieces"
                            : "the split at the chosen plane would leave its father no valid solid "
                              "(OCCT's check, or a closed mesh)";
                    if (retry(b, p))
                        --b;  // once more, at the next plane (b > 0: the root never splits)
                    else
                        note(b, why, father);
                    continue;
                }
                if (outcome == SplitOutcome::Split) {
                    if (kept) kept->forget(work[std::size_t(father)].solid);  // asked no more
                    work[std::size_t(father)].solid = father_new;
                }
                bool again = false;  // b itself tries the section plane
                for (std::size_t k = 0; k < group.size(); ++k) {
                    const std::size_t g = group[k];
                    if (!children[k].kept_because.empty()) {
                        // A sibling's retry comes in its own pass, later in this loop.
                        // A turned plane lies past T: the one square to D may leave a piece
                        // long enough.
                        if ((!children[k].too_short || p.turned) && retry(g, p)) {
                            again = again || g == b;
                            continue;
                        }
                        holder[g] = father;
                        note(g, children[k].kept_because, father);
                        continue;
                    }
                    if (children[k].solid.IsNull()) {
                        // No piece of its own: left for its own pass (its material may now sit in a
                        // sibling's piece or back in the father).
                        if (k > 0)
                            holder[g] = -1;
                        else if (retry(g, p))
                            again = true;
                        else
                            note(g, "the split left no piece holding its first node", father);
                        continue;
                    }
                    Work child;
                    child.solid = children[k].solid;
                    child.c.parent = father;
                    child.c.branch = int(g);
                    child.c.break_link = axis.branches[g].first_link;
                    child.c.rule = p.rule;
                    child.c.turned = p.turned;
                    child.c.has_base_face = true;
                    child.c.base_face = occ::wrap(children[k].base);
                    child.c.base_origin = children[k].base_origin;
                    child.c.base_normal = children[k].base_normal;
                    child.c.build_direction = -children[k].base_normal;
                    holder[g] = int(work.size());
                    work.push_back(child);
                }
                if (again) --b;  // once more at the section plane (b > 0: the root never splits)
            }

            // Faces within this of a bridge's splitting plane lie on it.
            const double on_plane = 10.0 * plane_tol;
            // A bridge's piece resting on `father` at the plane D.x = s: its mesh and what of its
            // underside hangs there; nullopt where OCCT cannot mesh it closed or compare its
            // underside with the father's top.
            struct Resting {
                TriangleMesh mesh;
                TopoDS_Shape hangs;
                double hanging = 0.0;  // the area of `hangs`
            };
            const auto resting = [&](const TopoDS_Shape& piece, const TopoDS_Shape& father,
                                     const Vector3d& D, double s) -> std::optional<Resting> {
                try {
                    Resting r;
                    r.mesh = occ::tessellate_solid(piece, default_deflection,
                                                   TessellationParams{}.angular_deflection_rad,
                                                   "a bridge's piece");
                    r.hangs = hanging_on_plane(piece, father, D, s, on_plane);
                    r.hanging = area_of(r.hangs);
                    return r;
                } catch (const Error&) {
                } catch (const Standard_Failure&) {
                }
                return std::nullopt;
            };
            // The diagonal such a piece is built along: D + or - g, where that leaves at most half
            // of what overhangs built along D, the way with less (bridge_direction); zero for
            // none. (The frame is turned about +Z only: a tilt from +Z is the same in the world.)
            const auto diagonal = [&](const Resting& r, const Vector3d& D, const Vector3d& g,
                                      double s) {
                return bridge_direction(D, g, params.max_tilt_deg, [&](const Vector3d& way) {
                    return overhang_area(r.mesh, way, params.overhang_angle_deg, D, s, on_plane,
                                         r.hanging);
                });
            };
            // Cuts the bridge of branch `owner`, whose material lies in component h built along D,
            // at the plane D.x = s (`on` a point of it) over a gap whose way across, square to D,
            // is g; `past` is a node in the bridge's material past the plane. False where it is
            // not cut (the reasons below), or, `asked`, where owner is asked to stay in its
            // father.
            const auto bridge_at = [&](const int h, const std::size_t owner, const Vector3d& D,
                                       const Vector3d& g, const double s, const Vector3d& on,
                                       const int past, const bool asked) -> bool {
                const TopoDS_Shape& fs = work[std::size_t(h)].solid;
                // No component already cut off the father may straddle the plane.
                bool straddles = false;
                for (const Work& w : work) {
                    if (w.c.parent != h || !w.c.has_base_face) continue;
                    double lo, hi;
                    range_along(bounds_of(occ::occt(w.c.base_face)), D, lo, hi);
                    straddles = straddles || (lo < s - plane_tol && hi > s + plane_tol);
                }
                if (straddles) return false;
                const Component& fc = work[std::size_t(h)].c;
                // A root on several feet (a portal's legs, a table's) may be left in several
                // solids, each standing on the plate: the span's underside hangs however they
                // are built (Decompose.hpp).
                Footing footing = footing_of(fc);
                footing.feet = true;
                const double step_height =
                    std::max(axis.params.step_mm, params.min_component_height_mm);
                std::vector<Child> children;
                TopoDS_Shape father_new;
                const Vector3d inner = axis.nodes[std::size_t(past)].material_point();
                if (split_by_plane(fs, footing, on, D, {inner}, step_height,
                                   {std::numeric_limits<double>::infinity()}, mesh, progress,
                                   children, father_new, nullptr) != SplitOutcome::Split ||
                    children.front().solid.IsNull())
                    return false;
                if (fc.has_base_face &&
                    height_along(father_new, fc.base_origin, fc.build_direction) < step_height)
                    return false;
                // Built along the diagonal (diagonal()), from m towards b where alike. (A piece
                // OCCT cannot mesh closed, or whose underside it cannot compare with its father's
                // top, stays in the father.)
                const std::optional<Resting> rest =
                    resting(children.front().solid, father_new, D, s);
                if (!rest) return false;
                const TriangleMesh& piece = rest->mesh;
                const Vector3d d = diagonal(*rest, D, g, s);
                if (d.isZero()) return false;
                // Asked to stay in its father (once it would be cut): said so, as for any branch.
                if (const KeptBranch* k = asked ? asked_to_keep(owner) : nullptr) {
                    if (kept_by_caller(owner)) kept_asked.insert(int(owner));
                    note(owner, k->why, h);
                    return false;
                }
                Work child;
                child.solid = children.front().solid;
                child.c.parent = h;
                child.c.branch = int(owner);
                child.c.break_link = axis.branches[owner].first_link;
                child.c.rule = Component::SplitRule::Bridge;
                child.c.has_base_face = true;
                child.c.build_direction = d;
                // The wedge between the splitting plane and the plane square to d through the
                // lowest point that way of the piece's top (its faces facing D), or of what of
                // its underside hangs, or of a face of it overhanging along D, whichever comes
                // first, goes to the father, on whose top it rests (built along D, its face on
                // that plane faces up): built along d, its layers would grow from an edge, the
                // first ones slivers far past the volumetric bound (the first of a handle's bar:
                // 0.01 mm^2). The piece then starts on that plane, its base face there
                // (base_normal -d). Where the wedge is not one solid resting wholly on the father
                // and leaning nowhere past the overhang angle off D, where the two would not mesh
                // closed, or where OCCT fails, the piece stays whole, its base plane square to d
                // through its lowest point, on the splitting plane (base_normal -D).
                const TopoDS_Shape whole = children.front().solid;
                std::optional<double> top;
                const auto lowest_of = [&](const TopoDS_Shape& shape) {
                    for (TopExp_Explorer v(shape, TopAbs_VERTEX); v.More(); v.Next()) {
                        const double dv = d.dot(vec(BRep_Tool::Pnt(TopoDS::Vertex(v.Current()))));
                        if (!top || dv < *top) top = dv;
                    }
                };
                for (TopExp_Explorer x(whole, TopAbs_FACE); x.More(); x.Next()) {
                    PlanarFace pf;
                    if (planar(TopoDS::Face(x.Current()), pf) && pf.normal.dot(D) >= 1.0 - 1e-9)
                        lowest_of(pf.face);
                }
                lowest_of(rest->hangs);
                // and of the faces of it that would overhang along D off the plane (the ceiling
                // of another window's top, where the plane passes through that window).
                for_each_leaning(
                    piece, D, params.overhang_angle_deg, D, s, on_plane,
                    [&](const Vector3d& p0, const Vector3d& p1, const Vector3d& p2, double) {
                        for (const Vector3d* q : {&p0, &p1, &p2})
                            if (!top || d.dot(*q) < *top) top = d.dot(*q);
                    });
                const Vector3d at = lowest_along(piece, d);
                const double lowest = d.dot(at);
                bool wedged = false;
                if (top && *top > lowest + on_plane) {
                    // The wedge is no component: nothing it stands on is the split's to keep.
                    Footing none;
                    none.plate_z = -std::numeric_limits<double>::infinity();
                    std::vector<Child> front;
                    TopoDS_Shape wedge, fused, father_grown;
                    const Vector3d on = at + d * (*top - lowest);
                    // A point of the piece past the plane: its centre of mass, else the node
                    // inside the bridge found above.
                    GProp_GProps props;
                    BRepGProp::VolumeProperties(whole, props);
                    Vector3d inside = vec(props.CentreOfMass());
                    if (!(d.dot(inside) > *top) || !contains(whole, inside)) inside = inner;
                    if (d.dot(inside) > *top &&
                        split_by_plane(whole, none, on, d, {inside}, 0.0,
                                       {std::numeric_limits<double>::infinity()}, mesh, progress,
                                       front, wedge, nullptr) == SplitOutcome::Split &&
                        !front.front().solid.IsNull()) {
                        TopTools_ListOfShape tool;
                        tool.Append(wedge);
                        try {
                            // Nothing of it may overhang in the father's layers: its underside
                            // on the plane rests on the father's top, and no other face of it
                            // leans past the overhang angle off D (the ceiling of another
                            // window's top, where the plane passes through it).
                            const TriangleMesh w = occ::tessellate_solid(
                                wedge, default_deflection,
                                TessellationParams{}.angular_deflection_rad, "a bridge's wedge");
                            const double w_hangs =
                                area_of(hanging_on_plane(wedge, father_new, D, s, on_plane));
                            if (overhang_area(w, D, params.overhang_angle_deg, D, s, on_plane,
                                              w_hangs) <= 1e-6 * (1.0 + area_of(wedge)) &&
                                fuse_kept(father_new, tool, fused) &&
                                valid_father(fused, footing, father_grown, mesh, progress) &&
                                // Both must mesh closed, as every component must (below): a
                                // plane through another window's corner left the piece an
                                // edge its mesh shared among four triangles.
                                meshes_closed(front.front().solid, default_deflection) &&
                                meshes_closed(father_grown, default_deflection)) {
                                father_new = father_grown;
                                child.solid = front.front().solid;
                                child.c.base_face = occ::wrap(front.front().base);
                                child.c.base_origin = front.front().base_origin;
                                child.c.base_normal = front.front().base_normal;
                                wedged = true;
                            }
                        } catch (const Standard_Failure&) {
                        } catch (const Error&) {
                        }
                    }
                }
                if (!wedged) {
                    child.c.base_face = occ::wrap(children.front().base);
                    child.c.base_origin = diagonal_base_origin(at, D, d, s);
                    child.c.base_normal = -D;
                }
                if (kept) kept->forget(work[std::size_t(h)].solid);
                work[std::size_t(h)].solid = father_new;
                // Right after its father (tree order), the father's children resting on what it
                // took now its own.
                const int to = h + 1;
                for (Work& w : work)
                    if (w.c.parent >= to) ++w.c.parent;
                for (int& x : holder)
                    if (x >= to) ++x;
                // A branch noted as kept in the father whose material the piece took (a table's
                // top, turned sideways off its legs and left in the root) is kept in the piece.
                for (Kept& k : kept_notes)
                    if (k.kept_in >= to)
                        ++k.kept_in;
                    else if (k.kept_in == h && !axis.branches[k.branch].nodes.empty() &&
                             contains(child.solid,
                                      axis.nodes[std::size_t(axis.branches[k.branch].nodes.front())]
                                          .material_point()))
                        k.kept_in = to;
                work.insert(work.begin() + to, child);
                for (std::size_t i = std::size_t(to) + 1; i < work.size(); ++i)
                    if (work[i].c.parent == h && work[i].c.has_base_face &&
                        D.dot(work[i].c.base_origin) > s + plane_tol)
                        work[i].c.parent = to;
                holder[owner] = to;
                return true;
            };
            // The level along D of a flat face of component h facing -D over the segment from pa
            // to pb (its box, seen along D, meets it), past lo and at most hi: the lowest such
            // face, or the highest.
            const auto underside = [&](int h, const Vector3d& D, double lo, double hi,
                                       const Vector3d& pa, const Vector3d& pb,
                                       bool lowest) -> std::optional<double> {
                std::optional<double> s;
                for (TopExp_Explorer x(work[std::size_t(h)].solid, TopAbs_FACE); x.More();
                     x.Next()) {
                    PlanarFace pf;
                    if (!planar(TopoDS::Face(x.Current()), pf) || pf.normal.dot(-D) < 1.0 - 1e-9)
                        continue;
                    const double sf = D.dot(pf.point);
                    if (sf <= lo || sf > hi || (s && (lowest ? sf >= *s : sf <= *s))) continue;
                    Eigen::AlignedBox3d fb = bounds_of(pf.face);
                    fb.min().array() -= plane_tol;
                    fb.max().array() += plane_tol;
                    bool over = false;
                    for (int i = 0; i <= 64 && !over; ++i) {
                        Vector3d q = pa + (pb - pa) * (double(i) / 64.0);
                        q += D * (sf - D.dot(q));
                        over = fb.contains(q);
                    }
                    if (over) s = sf;
                }
                return s;
            };
            // Bridges (Decompose.hpp): where branch b's track merged into m's, both marching
            // along D in one component built along D, over a flat underside spanning the gap.
            // The lowest first along D: a piece cut off at a higher one would leave the band
            // under it, with the lower bridge, too thin to cut off (two windows side by side).
            for (const std::size_t b : merged_lowest_first(axis)) {
                const AxisBranch& br = axis.branches[b];
                const std::size_t m = std::size_t(br.merged_into);
                const Vector3d D = br.direction.normalized();
                const int h = holder[b];
                if (h < 0 || h != holder[m] || axis.branches[m].nodes.empty() ||
                    !axis.branches[m].direction.normalized().isApprox(D, 1e-9) ||
                    !work[std::size_t(h)].c.build_direction.isApprox(D, 1e-9))
                    continue;
                // The branch the piece is of: b, but m where b made the component itself (a part
                // on several feet whose root branch, 0, merged into another foot's track).
                const std::size_t owner = work[std::size_t(h)].c.branch == int(b) ? m : b;
                if (work[std::size_t(h)].c.branch == int(owner)) continue;
                progress.check();
                // The gap (bridge_gap: from m's node on the plane of b's last node, or the nearest
                // to it, to b's, square to D) and the nearest of the frame's directions across it.
                const BridgeGap gap = bridge_gap(axis, b, m, D, Eigen::Matrix3d::Identity());
                const Vector3d& v = gap.across;
                if (!(v.norm() > axis.params.step_mm)) continue;
                const Vector3d pb = axis.nodes[std::size_t(gap.to)].position;
                const double sb = D.dot(pb);
                const Vector3d& g = gap.way;
                // The splitting plane: the lowest flat underside within two steps past b's last
                // node.
                const Vector3d pa = pb - v;
                const std::optional<double> s =
                    underside(h, D, sb + plane_tol, sb + 2.0 * axis.params.step_mm, pa, pb, true);
                if (!s) continue;
                // A point in the bridge's material (bridge_node).
                const int past =
                    bridge_node(axis, D, *s, plane_tol, 0.5 * (pa + pb) + D * (*s - sb));
                if (past < 0) continue;
                bridge_at(h, owner, D, g, *s, pb + D * (*s - sb), past, true);
            }
            // Whether `solid` holds points on both sides of `under` along `way` (sampled in 64
            // steps to its box's ends): a span over a gap at `under` rests there.
            const auto spans_gap = [&](const TopoDS_Shape& solid, const Vector3d& under,
                                       const Vector3d& way) {
                double from, to;
                range_along(bounds_of(solid), way, from, to);
                const auto rests = [&](double end) {
                    for (int i = 1; i <= 64; ++i)
                        if (contains(solid,
                                     under + way * ((end - way.dot(under)) * double(i) / 64.0)))
                            return true;
                    return false;
                };
                return rests(from) && rests(to);
            };
            // The first of the frame's directions square to D along which `solid` spans a gap at
            // `under` (spans_gap), zero for none.
            const auto gap_way = [&](const TopoDS_Shape& solid, const Vector3d& under,
                                     const Vector3d& D) -> Vector3d {
                for (int e = 0; e < 3; ++e)
                    if (std::abs(D[e]) < 1e-9 && spans_gap(solid, under, Vector3d::Unit(e)))
                        return Vector3d::Unit(e);
                return Vector3d::Zero();
            };
            // Bridges the axis marched across sideways, or into from over the gap (Decompose.hpp):
            // branch b, asked to stay in its father (slicing asks where the nozzle cannot reach
            // its own component's layers: they close a gap against what is deposited, or start
            // over it), marching square to the build direction D of the component holding it
            // over a flat underside facing -D under its march (the highest such face below its
            // nodes and above the component's base), or along D from within two steps over one,
            // cut there as a bridge across the gap, where the component's material reaches under
            // that face on both sides of the march. Beams across two posts braced to each other:
            // the brace joins the posts' tracks below the beam, and the march goes on from one
            // post's top across the beam, or up through it from the brace. (Still kept as asked:
            // decomposed with keep_branches, the same branches give the same bridges.)
            for (std::size_t b = 1; b < nb; ++b) {
                const KeptBranch* k = kept_by_caller(b);
                const int h = holder[b];
                const AxisBranch& br = axis.branches[b];
                if (!k || h < 0 || br.nodes.empty()) continue;
                const Vector3d D = work[std::size_t(h)].c.build_direction;
                const Vector3d m = br.direction.normalized();
                const bool along = m.isApprox(D, 1e-9);
                const Vector3d pa = axis.nodes[std::size_t(br.nodes.front())].position;
                const Vector3d pb = along ? pa : axis.nodes[std::size_t(br.nodes.back())].position;
                if (!along &&
                    (std::abs(m.dot(D)) > 1e-9 || !(m.dot(pb - pa) > axis.params.step_mm)))
                    continue;
                progress.check();
                double base, top;
                range_along(bounds_of(work[std::size_t(h)].solid), D, base, top);
                const std::optional<double> s =
                    underside(h, D, base + plane_tol, std::min(D.dot(pa), D.dot(pb)) - plane_tol,
                              pa, pb, false);
                if (!s || (along && *s < D.dot(pa) - 2.0 * axis.params.step_mm)) continue;
                // A gap: the component's material reaches under the plane (half a step under it)
                // on both sides of the march's middle along g, where a span rests; an arm off a
                // column's side, resting on one, is no bridge. g: the march's direction; for a
                // march along D, the first of the frame's directions square to D along which
                // the span rests on both sides.
                const Vector3d middle = 0.5 * (pa + pb);
                const Vector3d under =
                    middle + D * (*s - 0.5 * axis.params.step_mm - D.dot(middle));
                const TopoDS_Shape& hs = work[std::size_t(h)].solid;
                const Vector3d g = !along ? (spans_gap(hs, under, m) ? m : Vector3d::Zero())
                                          : gap_way(hs, under, D);
                if (g.isZero()) continue;
                // The piece: b's node past the plane nearest the gap's middle.
                int past = -1;
                for (const int n : br.nodes) {
                    const Vector3d& q = axis.nodes[std::size_t(n)].position;
                    if (D.dot(q) > *s + plane_tol &&
                        (past < 0 || (q - middle).norm() <
                                         (axis.nodes[std::size_t(past)].position - middle).norm()))
                        past = n;
                }
                if (past < 0 || !bridge_at(h, b, D, g, *s, pa + D * (*s - D.dot(pa)), past, false))
                    continue;
                kept_notes.erase(std::remove_if(kept_notes.begin(), kept_notes.end(),
                                                [&](const Kept& x) { return x.branch == b; }),
                                 kept_notes.end());
            }
            // Pieces whose base hangs over a gap (Decompose.hpp): a piece cut off across its
            // build direction D that hangs over a gap is built along the diagonal D + or - g as a
            // bridge's piece, g the first of the frame's directions square to D along which the
            // gap lies, where that leaves at most half of what overhangs along D. Without the
            // wedge, its base plane square to the diagonal through its lowest point, on its base
            // plane (as a mesh's). It hangs over a gap:
            // - built on along its father's D, where more than half of its base face rests on
            //   nothing of the father, nothing of the father lies half a step under its base
            //   origin and something does on both sides of that point along g: a beam cut off at
            //   its underside over two braces crossing under it, its first layer along D hanging
            //   between the posts;
            // - else, built up along +Z (off a father built along Z or not), where its flat faces
            //   facing -Z that hang along Z (its base's part resting on nothing of the father, and
            //   its faces off the base plane) have more than half its base face's area, nothing
            //   of the part lies half a step under their centroid and something does on both
            //   sides of that point along g. A beam the axis rose into from a brace leaning under
            //   it, the brace and the far post built along the brace (the near post, beside the
            //   beam's end, is no father of it); a beam's middle slab cut off above the far
            //   post's top, the posts' side slabs cut off along +-Y, its underside hanging just
            //   over the base plane. (Not the round underside of a brace, which no span rests.)
            for (std::size_t c = 1; c < work.size(); ++c) {
                Work& w = work[c];
                if (w.c.parent < 0 || w.c.rule == Component::SplitRule::Bridge || w.c.turned ||
                    !w.c.has_base_face)
                    continue;
                const TopoDS_Shape& father = work[std::size_t(w.c.parent)].solid;
                const Vector3d D = w.c.build_direction;
                const bool on_father =
                    work[std::size_t(w.c.parent)].c.build_direction.isApprox(D, 1e-9);
                if (!(-w.c.base_normal).isApprox(D, 1e-9) ||
                    !(on_father || D.isApprox(Vector3d::UnitZ(), 1e-9)))
                    continue;
                progress.check();
                const double s = D.dot(w.c.base_origin);
                const double base_area = area_of(occ::occt(w.c.base_face));
                // gap_way() where `around` holds nothing at `under` itself.
                const auto gap_at = [&](const TopoDS_Shape& around, const Vector3d& under) {
                    return contains(around, under) ? Vector3d::Zero() : gap_way(around, under, D);
                };
                std::optional<Resting> rest;
                Vector3d g = Vector3d::Zero();
                if (on_father) {
                    g = gap_at(father, w.c.base_origin - 0.5 * axis.params.step_mm * D);
                    if (!g.isZero()) rest = resting(w.solid, father, D, s);
                    // Its base hangs mostly (a pipe's end rests whole on its father, its centroid
                    // in the bore between its walls).
                    if (!rest || !(rest->hanging > 0.5 * base_area)) g = Vector3d::Zero();
                }
                if (g.isZero() && D.isApprox(Vector3d::UnitZ(), 1e-9)) {
                    if (!rest) rest = resting(w.solid, father, D, s);
                    if (!rest) continue;
                    // What overhangs built along D: its area and centroid.
                    double area = 0.0;
                    Vector3d moment = Vector3d::Zero();
                    if (rest->hanging > 0.0) {
                        GProp_GProps hp;
                        BRepGProp::SurfaceProperties(rest->hangs, hp);
                        area += hp.Mass();
                        moment += hp.Mass() * vec(hp.CentreOfMass());
                    }
                    for_each_leaning(
                        rest->mesh, D, params.overhang_angle_deg, D, s, on_plane,
                        [&](const Vector3d& p0, const Vector3d& p1, const Vector3d& p2, double a) {
                            if (!((p1 - p0).cross(p2 - p0).normalized().dot(-D) > 1.0 - 1e-9))
                                return;
                            area += a;
                            moment += a * (p0 + p1 + p2) / 3.0;
                        });
                    if (!(area > 0.5 * base_area)) continue;
                    g = gap_at(solid, moment / area - 0.5 * axis.params.step_mm * D);
                }
                if (g.isZero()) continue;
                const Vector3d d = diagonal(*rest, D, g, s);
                if (d.isZero()) continue;
                const Vector3d at = lowest_along(rest->mesh, d);
                w.c.base_origin = diagonal_base_origin(at, D, d, s);
                w.c.rule = Component::SplitRule::Bridge;
                w.c.build_direction = d;
            }
            for (const Kept& k : kept_notes) {
                const Vector3d d = to_world * axis.branches[k.branch].direction;
                std::ostringstream line;
                line << "branch " << k.branch << " (along " << d.x() << "," << d.y() << "," << d.z()
                     << "): " << k.why << "; its material stays in component " << k.kept_in;
                notes.push_back(line.str());
            }
        } catch (const Standard_Failure& e) {
            throw Error(ErrorCode::GeometryFailure, occ::failure_message("decompose", e));
        }
    };
    std::vector<Work> work;
    std::vector<std::string> notes;  // branches that asked for a cut and got none
    int joins = 0;
    const auto fresh_pass = [&](bool join_orphans) {
        work.clear();
        notes.clear();
        kept_asked.clear();
        joins = 0;
        pass(join_orphans, work, notes, joins);
    };
    for (;;) {
        fresh_pass(true);
        // A piece that went with a child must end in a component that builds it. Without joining
        // every component lies in front of its base (each split's pieces lie on their side of the
        // plane, and later splits only take from them); with it, that is checked (on the solids'
        // boxes: exact along the axis-aligned directions, else erring on the side of "behind").
        // If one reaches behind its base, the pass is done again without joining: those splits
        // are refused as leaving their father in pieces.
        bool in_front = true;
        try {
            for (const auto& w : work) {
                if (joins == 0) break;
                // A bridge's piece lies in front of the base plane through its lowest point.
                if (!w.c.has_base_face || w.c.rule == Component::SplitRule::Bridge) continue;
                double lo, hi;
                range_along(bounds_of(w.solid), w.c.build_direction, lo, hi);
                const double tol = 1e-6 * (1.0 + (hi - lo));
                if (lo < w.c.build_direction.dot(w.c.base_origin) - tol) in_front = false;
            }
        } catch (const Standard_Failure& e) {
            throw Error(ErrorCode::GeometryFailure, occ::failure_message("decompose", e));
        }
        if (!in_front) fresh_pass(false);
        // Every child must mesh closed at the part's deflection, which slicing tessellates it at:
        // a sound part's split can leave one that passes OCCT's shape check and still does not (a
        // fork of two pipes leaning 54 degrees off a riser, cut just where one pipe's side
        // touches the riser's: a 0.27 mm edge the mesh shared among four triangles, and slicing
        // stopped there). Its branch is then kept in its father, and the pass done again. (The
        // root, which every split leaves, is slicing's to report.)
        // The components are meshed side by side (each meshing a copy of its own solid), the
        // check for a cancel before and after. On a part whose every piece was meshed
        // (MeshCheck::every_piece), each child already passed this very check in valid_solid().
        if (mesh.every_piece) break;
        const Progress meshing = progress.span(1.0, 1.0, "meshing the components to check them");
        meshing.check();
        std::vector<char> closed(work.size(), 1);
        OSD_Parallel::For(1, int(work.size()), [&](int i) {
            closed[std::size_t(i)] = meshes_closed(work[std::size_t(i)].solid, mesh.deflection);
        });
        meshing.check();
        const std::size_t before = unmeshed.size();
        for (std::size_t i = 1; i < work.size(); ++i)
            if (!closed[i])
                unmeshed.push_back({work[i].c.branch,
                                    "its component does not mesh into a closed surface at the "
                                    "part's deflection (" +
                                        format_number(mesh.deflection) +
                                        " mm), which slicing tessellates it at"});
        if (unmeshed.size() == before) break;
    }

    Decomposition out;
    try {
        for (auto& w : work) {
            if (frame != 0.0) {
                w.solid = turned_about_z(w.solid, frame);
                w.c.build_direction = to_world * w.c.build_direction;
                w.c.base_normal = to_world * w.c.base_normal;
                if (w.c.has_base_face) {
                    w.c.base_face = occ::wrap(turned_about_z(occ::occt(w.c.base_face), frame));
                    w.c.base_origin = to_world * w.c.base_origin;
                } else {
                    const Eigen::AlignedBox3d root_box = bounds_of(w.solid);
                    w.c.base_origin =
                        Vector3d(root_box.center().x(), root_box.center().y(), root_box.min().z());
                }
            }
            w.c.solid = occ::wrap(w.solid);
            w.c.volume_mm3 = occ::volume_of(w.solid);
            out.components.push_back(w.c);
        }
        out.notes = std::move(notes);
        out.kept_branches.assign(kept_asked.begin(), kept_asked.end());
        const std::set<int> square(params.square_branches.begin(), params.square_branches.end());
        out.square_branches.assign(square.begin(), square.end());
    } catch (const Standard_Failure& e) {
        throw Error(ErrorCode::GeometryFailure, occ::failure_message("decompose", e));
    }
    progress(1.0);
    return out;
}

const char* to_string(Component::SplitRule rule) {
    switch (rule) {
        case Component::SplitRule::Root:
            return "root";
        case Component::SplitRule::PlanarFace:
            return "planar_face";
        case Component::SplitRule::SectionPlane:
            return "section_plane";
        case Component::SplitRule::Bridge:
            return "bridge";
    }
    return "unknown";
}

}  // namespace mas
