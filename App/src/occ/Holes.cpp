// Round holes found on the BREP and filled with OCCT's defeaturing (see Holes.hpp).
#include "mas/Holes.hpp"

#include <BRepAdaptor_Curve.hxx>
#include <BRepAdaptor_Surface.hxx>
#include <BRepAlgoAPI_Common.hxx>
#include <BRepAlgoAPI_Cut.hxx>
#include <BRepAlgoAPI_Defeaturing.hxx>
#include <BRepAlgoAPI_Fuse.hxx>
#include <BRepBndLib.hxx>
#include <BRepCheck_Analyzer.hxx>
#include <BRepClass3d_SolidClassifier.hxx>
#include <BRepGProp.hxx>
#include <BRepPrimAPI_MakeCylinder.hxx>
#include <BRepTools.hxx>
#include <BRep_Tool.hxx>
#include <Bnd_Box.hxx>
#include <GProp_GProps.hxx>
#include <Precision.hxx>
#include <TopExp.hxx>
#include <TopExp_Explorer.hxx>
#include <TopTools_IndexedDataMapOfShapeListOfShape.hxx>
#include <TopTools_IndexedMapOfShape.hxx>
#include <TopTools_ListOfShape.hxx>
#include <TopoDS.hxx>
#include <TopoDS_Face.hxx>
#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

#include "ShapeImpl.hpp"
#include "mas/Angles.hpp"
#include "mas/Mesh.hpp"

namespace mas {

namespace {

using Eigen::Vector3d;

Vector3d vec(const gp_Pnt& p) { return {p.X(), p.Y(), p.Z()}; }
Vector3d vec(const gp_Dir& d) { return {d.X(), d.Y(), d.Z()}; }

// One round hole: its wall's faces (and its bottom's, when blind) and its axis line.
struct Hole {
    Vector3d point = Vector3d::Zero();  // on the axis
    Vector3d axis = Vector3d::UnitZ();  // unit
    double radius = 0.0;
    double lo = 0.0, hi = 0.0;    // extent along the axis from `point`, bottom included
    double wlo = 0.0, whi = 0.0;  // its wall's
    double turn = 0.0;            // angle the wall's faces span around the axis, radians
    std::vector<TopoDS_Face> faces;
    // Fillets or chamfers round its mouths (among `faces`, and within [lo, hi]): each within
    // `radius` of the axis between lo and hi along it.
    struct Blend {
        double lo = 0.0, hi = 0.0, radius = 0.0;
    };
    std::vector<Blend> blends;

    Vector3d centre() const { return point + 0.5 * (lo + hi) * axis; }
    // The volume of its cylinder over its extent, and of the rings round it out to its mouths'
    // blends' radii over theirs: at least what filling it adds.
    double cylinder_volume() const {
        double v = kPi * radius * radius * (hi - lo);
        for (const Blend& b : blends)
            v += kPi * (b.radius * b.radius - radius * radius) * (b.hi - b.lo);
        return v;
    }
    void extend(double t) {
        lo = std::min(lo, t);
        hi = std::max(hi, t);
    }
    // Widens [lo, hi] to the face's extent along the axis: that of its edges, each sampled and
    // its extremes refined by golden section (a wall's edge where it meets a slanted face is an
    // ellipse, whose UV box is loose).
    void extend(const TopoDS_Face& face) {
        for (TopExp_Explorer e(face, TopAbs_EDGE); e.More(); e.Next()) {
            const TopoDS_Edge& edge = TopoDS::Edge(e.Current());
            if (BRep_Tool::Degenerated(edge)) continue;
            const BRepAdaptor_Curve c(edge);
            const double t0 = c.FirstParameter(), t1 = c.LastParameter();
            auto along = [&](double t) { return (vec(c.Value(t)) - point).dot(axis); };
            constexpr int n = 32;
            for (const double sense : {1.0, -1.0}) {
                int best = 0;
                for (int i = 1; i <= n; ++i)
                    if (sense * along(t0 + (t1 - t0) * i / n) >
                        sense * along(t0 + (t1 - t0) * best / n))
                        best = i;
                double a = t0 + (t1 - t0) * std::max(best - 1, 0) / n;
                double b = t0 + (t1 - t0) * std::min(best + 1, n) / n;
                const double g = 0.5 * (std::sqrt(5.0) - 1.0);
                for (int k = 0; k < 80 && b - a > 1e-14 * (1.0 + std::abs(b)); ++k) {
                    const double x = b - g * (b - a), y = a + g * (b - a);
                    if (sense * along(x) > sense * along(y))
                        b = y;
                    else
                        a = x;
                }
                extend(along(0.5 * (a + b)));
                extend(along(t0 + (t1 - t0) * best / n));
            }
        }
    }
    // Whether `other` (a hole's wall or part of it) lies on this one's axis line with its radius.
    bool same(const Vector3d& p, const Vector3d& a, double r, double tol) const {
        if (std::abs(r - radius) > tol || a.cross(axis).norm() > 1e-7) return false;
        const Vector3d d = p - point;
        return (d - d.dot(axis) * axis).norm() <= tol;
    }
};

// "the hole D mm across at (x, y, z)".
std::string hole_at(double diameter, const Vector3d& c) {
    std::ostringstream s;
    s << "the hole " << diameter << " mm across at (" << c.x() << ", " << c.y() << ", " << c.z()
      << ")";
    return s.str();
}

std::string describe(const Hole& h) {
    std::ostringstream s;
    s << hole_at(2.0 * h.radius, h.centre()) << " along (" << h.axis.x() << ", " << h.axis.y()
      << ", " << h.axis.z() << ")";
    return s.str();
}

// leans_over() with the angle in radians.
bool leans_over_rad(const Vector3d& axis, const Vector3d& direction, double overhang_rad) {
    return std::acos(std::min(1.0, std::abs(axis.dot(direction)))) > overhang_rad + 1e-9;
}

// The holes of `solid` that qualify (Holes.hpp), in face order, less those `skip` names.
std::vector<Hole> find_holes(const TopoDS_Shape& solid, const Vector3d& direction,
                             double max_diameter, double overhang_rad,
                             const std::vector<Hole>& skip) {
    TopTools_IndexedMapOfShape faces;
    TopExp::MapShapes(solid, TopAbs_FACE, faces);
    // The concave cylindrical faces that qualify, each with its extent along its axis, grouped by
    // axis line and radius.
    struct Wall {
        int face = 0;
        double lo = 0.0, hi = 0.0, turn = 0.0;
    };
    std::vector<Hole> lines;               // one per axis line and radius: point, axis, radius
    std::vector<std::vector<Wall>> walls;  // per line
    for (int i = 1; i <= faces.Extent(); ++i) {
        const TopoDS_Face face = TopoDS::Face(faces(i));
        BRepAdaptor_Surface s(face, Standard_True);
        if (s.GetType() != GeomAbs_Cylinder) continue;
        const gp_Cylinder cyl = s.Cylinder();
        const double r = cyl.Radius();
        if (2.0 * r > max_diameter * (1.0 + 1e-9)) continue;
        double u0, u1, v0, v1;
        BRepTools::UVBounds(face, u0, u1, v0, v1);
        const Vector3d p0 = vec(cyl.Location()), a = vec(cyl.Axis().Direction());
        // Concave: the outward normal at the face's middle points at the axis.
        gp_Pnt p;
        gp_Vec du, dv;
        s.D1(0.5 * (u0 + u1), 0.5 * (v0 + v1), p, du, dv);
        Vector3d n(du.Crossed(dv).X(), du.Crossed(dv).Y(), du.Crossed(dv).Z());
        if (face.Orientation() == TopAbs_REVERSED) n = -n;
        const Vector3d radial = vec(p) - p0 - (vec(p) - p0).dot(a) * a;
        if (n.dot(radial) >= 0.0) continue;
        if (!leans_over_rad(a, direction, overhang_rad)) continue;
        const double tol = 1e-4 + BRep_Tool::Tolerance(face);
        std::size_t k = 0;
        while (k < lines.size() && !lines[k].same(p0, a, r, tol)) ++k;
        if (k == lines.size()) {
            Hole h;
            h.point = p0;
            h.axis = a;
            h.radius = r;
            lines.push_back(h);
            walls.emplace_back();
        }
        Hole extent = lines[k];
        extent.lo = std::numeric_limits<double>::infinity();
        extent.hi = -extent.lo;
        extent.extend(face);
        walls[k].push_back({i, extent.lo, extent.hi, u1 - u0});
    }
    // A hole is a run of walls along its line whose extents overlap or touch: coaxial holes apart
    // (two lugs of a clevis) are two, and a wall a slot or rib interrupts is two pieces, each of
    // which must go round on its own.
    std::vector<Hole> holes;
    std::vector<int> hole_of(std::size_t(faces.Extent()) + 1, -1);
    for (std::size_t k = 0; k < lines.size(); ++k) {
        std::vector<Wall>& w = walls[k];
        std::sort(w.begin(), w.end(), [](const Wall& a, const Wall& b) { return a.lo < b.lo; });
        for (std::size_t i = 0; i < w.size(); ++i) {
            if (i == 0 || w[i].lo > holes.back().whi + 1e-4) {
                Hole h = lines[k];
                h.wlo = h.lo = w[i].lo;
                h.whi = h.hi = w[i].hi;
                holes.push_back(h);
            }
            Hole& h = holes.back();
            h.whi = h.hi = std::max(h.whi, w[i].hi);
            h.turn += w[i].turn;
            h.faces.push_back(TopoDS::Face(faces(w[i].face)));
            hole_of[std::size_t(w[i].face)] = int(holes.size()) - 1;
        }
    }
    // A blind hole's bottom: a face all of whose edges it shares with one hole's wall.
    TopTools_IndexedDataMapOfShapeListOfShape edge_faces;
    TopExp::MapShapesAndAncestors(solid, TopAbs_EDGE, TopAbs_FACE, edge_faces);
    for (int i = 1; i <= faces.Extent(); ++i) {
        if (hole_of[std::size_t(i)] >= 0) continue;
        int owner = -1;
        bool bottom = true;
        for (TopExp_Explorer e(faces(i), TopAbs_EDGE); e.More() && bottom; e.Next()) {
            const TopoDS_Edge& edge = TopoDS::Edge(e.Current());
            if (BRep_Tool::Degenerated(edge)) continue;
            for (const TopoDS_Shape& f : edge_faces.FindFromKey(e.Current())) {
                if (f.IsSame(faces(i))) continue;
                const int k = hole_of[std::size_t(faces.FindIndex(f))];
                if (k < 0 || (owner >= 0 && k != owner)) bottom = false;
                owner = k;
            }
        }
        if (!bottom || owner < 0) continue;
        Hole& h = holes[std::size_t(owner)];
        // A flat bottom, a drill point's cone or a ball end's sphere no wider than the hole: a
        // sphere or torus the hole merely goes through has its seams for other edges.
        const BRepAdaptor_Surface bs(TopoDS::Face(faces(i)), Standard_False);
        if (bs.GetType() != GeomAbs_Plane && bs.GetType() != GeomAbs_Cone &&
            !(bs.GetType() == GeomAbs_Sphere && bs.Sphere().Radius() <= h.radius * (1.0 + 1e-6)))
            continue;
        h.faces.push_back(TopoDS::Face(faces(i)));
        h.extend(h.faces.back());
    }
    // A blend round a mouth: a face, not planar, sharing an edge with a hole's wall, lying outside
    // the wall's radius and within twice it, and no more than that radius past one of the wall's
    // ends (a fillet or a chamfer of the edge where the hole meets a face it goes through). It
    // goes with the hole: defeaturing the wall alone cannot extend that face across the mouth
    // (it took 39 s to fail on a filleted lug's pin hole; with the fillets, 0.05 s to close it),
    // and the hole drilled, its mouths are finished again.
    for (int i = 1; i <= faces.Extent(); ++i) {
        if (hole_of[std::size_t(i)] >= 0) continue;
        const TopoDS_Face face = TopoDS::Face(faces(i));
        if (BRepAdaptor_Surface(face, Standard_False).GetType() == GeomAbs_Plane) continue;
        int owner = -1;
        for (TopExp_Explorer e(face, TopAbs_EDGE); e.More() && owner != -2; e.Next()) {
            if (BRep_Tool::Degenerated(TopoDS::Edge(e.Current()))) continue;
            for (const TopoDS_Shape& f : edge_faces.FindFromKey(e.Current())) {
                const int k = f.IsSame(face) ? -1 : hole_of[std::size_t(faces.FindIndex(f))];
                if (k >= 0) owner = (owner == -1 || owner == k) ? k : -2;
            }
        }
        if (owner < 0) continue;
        Hole& h = holes[std::size_t(owner)];
        bool listed = false;
        for (const TopoDS_Face& f : h.faces) listed = listed || f.IsSame(face);
        if (listed) continue;
        // Its extent along the axis and from it, on its edges (sampled).
        double a0 = std::numeric_limits<double>::infinity(), a1 = -a0, r0 = a0, r1 = 0.0;
        for (TopExp_Explorer e(face, TopAbs_EDGE); e.More(); e.Next()) {
            const TopoDS_Edge& edge = TopoDS::Edge(e.Current());
            if (BRep_Tool::Degenerated(edge)) continue;
            const BRepAdaptor_Curve c(edge);
            constexpr int n = 32;
            for (int j = 0; j <= n; ++j) {
                const Vector3d d = vec(c.Value(c.FirstParameter() +
                                               (c.LastParameter() - c.FirstParameter()) * j / n)) -
                                   h.point;
                const double along = d.dot(h.axis), from = (d - along * h.axis).norm();
                a0 = std::min(a0, along);
                a1 = std::max(a1, along);
                r0 = std::min(r0, from);
                r1 = std::max(r1, from);
            }
        }
        const double tol = 1e-4 + BRep_Tool::Tolerance(face);
        const bool past_hi = a0 >= h.whi - tol && a1 <= h.whi + h.radius + tol;
        const bool past_lo = a1 <= h.wlo + tol && a0 >= h.wlo - h.radius - tol;
        if (!(past_hi || past_lo) || r0 < h.radius - tol || r1 > 2.0 * h.radius + tol) continue;
        h.faces.push_back(face);
        h.blends.push_back({a0, a1, r1});
        h.extend(a0);
        h.extend(a1);
    }
    // Only a wall that goes all the way round is a hole: a concave fillet, a slot's round end or
    // a hole a plane cut lengthwise is not.
    std::vector<Hole> out;
    for (const Hole& h : holes) {
        if (h.turn < 2.0 * kPi - 1e-6) continue;
        bool skipped = false;
        for (const Hole& s : skip)
            if (s.same(h.point, h.axis, h.radius, 1e-4) && (s.centre() - h.centre()).norm() < 1e-4)
                skipped = true;
        if (!skipped) out.push_back(h);
    }
    return out;
}

TopoDS_Shape make_cylinder(const Vector3d& base, const Vector3d& axis, double radius,
                           double length) {
    return BRepPrimAPI_MakeCylinder(
               gp_Ax2(gp_Pnt(base.x(), base.y(), base.z()), gp_Dir(axis.x(), axis.y(), axis.z())),
               radius, length)
        .Shape();
}

// What a drill would meet. Within the hole's wall, material means no drill makes it (a post in
// a ring groove, a rib across a channel); beyond an end, material blocks that end (a narrower
// entry, a wall across it, a closed cavity's ends). Exact, with one Boolean for all the holes:
// the whole part in common with, per hole, three probe cylinders a hair inside its radius: one
// along its wall, one from each end out past the part. Each piece of material in common goes
// to the probes it came from (the Boolean's history). IntoOpenBore is no drill's matter: a hole a
// drill makes whose plug would hang (fill_access()).
enum class Access { Drillable, HoldsMaterial, Unreachable, IntoOpenBore };

std::vector<Access> access(const TopoDS_Shape& whole, const std::vector<Hole>& holes) {
    struct Probe {
        std::size_t hole;
        int side;  // 0: along the wall, +1 / -1: beyond the upper / lower end
        Vector3d base;
        double radius, length;
    };
    // mm off the hole's wall and ends, well within a drill's tolerance, and far enough for OCCT's
    // Booleans not to meet nearly coincident surfaces.
    const double gap = 1e-2;
    Bnd_Box part_box;
    BRepBndLib::Add(whole, part_box);
    double x0, y0, z0, x1, y1, z1;
    part_box.Get(x0, y0, z0, x1, y1, z1);
    const Eigen::AlignedBox3d bounds(Vector3d(x0, y0, z0), Vector3d(x1, y1, z1));
    std::vector<Probe> probes;
    std::vector<TopoDS_Shape> probe_shapes;
    TopTools_ListOfShape args, tools;
    args.Append(whole);
    for (std::size_t i = 0; i < holes.size(); ++i) {
        const Hole& h = holes[i];
        const double r = h.radius - std::min(gap, 1e-2 * h.radius);
        const double along = h.whi - h.wlo - 2.0 * gap;
        if (along > 0.0) probes.push_back({i, 0, h.point + (h.wlo + gap) * h.axis, r, along});
        // The part's extent along the axis: a probe reaches past it, no further.
        double first, last;
        range_along(bounds.translated(-h.point), h.axis, first, last);
        if (last > h.hi + gap)
            probes.push_back({i, 1, h.point + (h.hi + gap) * h.axis, r, last + 1.0 - h.hi - gap});
        if (first < h.lo - gap)
            probes.push_back(
                {i, -1, h.point + (first - 1.0) * h.axis, r, h.lo - gap - first + 1.0});
    }
    for (const Probe& p : probes) {
        probe_shapes.push_back(make_cylinder(p.base, holes[p.hole].axis, p.radius, p.length));
        tools.Append(probe_shapes.back());
    }
    std::vector<Access> out(holes.size(), Access::Drillable);
    BRepAlgoAPI_Common common;
    common.SetArguments(args);
    common.SetTools(tools);
    common.SetRunParallel(Standard_False);
    common.SetToFillHistory(Standard_True);
    common.Build();
    if (!common.IsDone() || common.HasErrors()) {
        std::fill(out.begin(), out.end(), Access::Unreachable);  // unknown: leave them open
        return out;
    }
    // A probe meets material when pieces of it are in the common: itself, whole (not split, not
    // deleted), or the pieces it was split into.
    const double tiny = 1e-9 * occ::volume_of(whole) + 1e-12;
    std::vector<char> hit(probes.size(), 0);
    for (std::size_t k = 0; k < probes.size(); ++k) {
        const TopoDS_Shape& probe = probe_shapes[k];
        if (common.IsDeleted(probe)) continue;
        const TopTools_ListOfShape& pieces = common.Modified(probe);
        double in = 0.0;
        if (pieces.IsEmpty()) {
            in = occ::volume_of(probe);
        } else {
            for (const TopoDS_Shape& piece : pieces) in += occ::volume_of(piece);
        }
        hit[k] = in > tiny;
    }
    std::vector<char> plus(holes.size(), 0), minus(holes.size(), 0);
    for (std::size_t k = 0; k < probes.size(); ++k) {
        if (!hit[k]) continue;
        const std::size_t i = probes[k].hole;
        if (probes[k].side == 0) out[i] = Access::HoldsMaterial;
        (probes[k].side > 0 ? plus : minus)[i] = probes[k].side != 0;
    }
    for (std::size_t i = 0; i < holes.size(); ++i)
        if (out[i] == Access::Drillable && plus[i] && minus[i]) out[i] = Access::Unreachable;
    return out;
}

// Whether the hole's lower end (along `direction`, the build direction; none when the hole lies
// square to it) opens into a bore that goes on past it: just past that end the part's material
// rings the hole's radius all round, and within it there is none. That is a bore going on round a
// bend, or widening in a taper, left open (no round hole, or one too wide or built along). The
// hole's plug would end there in a face across that bore, hanging over it (a pipe's leaning
// straight bore, plugged above its bend's open bore: the layers tilt after the pipe, and the plug's
// end hung 2.5 to 7.9 mm^2 in each of 12 layers). A blind end (its bottom), a mouth onto the
// outside, a counterbore or a bore it pierces has no such ring. The end is that of the one of
// `whole_holes` (the whole part's, found as the component's are) that holds the hole, where a
// component holds a piece of one: a split across a lateral's straight bore leaves the bore going
// on past the piece's end, the same hole, which its own end decides for every piece (a wye's
// lateral split in two kept one piece open, the other plugged). Read on the BREP: points 0.05 r
// (at most 0.1 mm) past the end, eight on a ring that much outside the radius and five within
// half of it, classified against the whole part (`in_whole`).
bool opens_into_bore_below(BRepClass3d_SolidClassifier& in_whole,
                           const std::vector<Hole>& whole_holes, const Hole& piece,
                           const Vector3d& direction) {
    const Hole* h = &piece;
    const double mid = 0.5 * (piece.lo + piece.hi);
    for (const Hole& w : whole_holes)
        if (w.same(piece.point, piece.axis, piece.radius, 1e-4)) {
            // w's extent along the piece's axis (the same line, either way along it).
            const double at = (w.point - piece.point).dot(piece.axis);
            const double sense = w.axis.dot(piece.axis);
            const double a = at + sense * w.lo, b = at + sense * w.hi;
            if (std::min(a, b) <= mid + 1e-4 && std::max(a, b) >= mid - 1e-4) h = &w;
        }
    const double up = h->axis.dot(direction);
    if (std::abs(up) <= 1e-9) return false;
    const auto state = [&](const Vector3d& p) {
        in_whole.Perform(gp_Pnt(p.x(), p.y(), p.z()), Precision::Confusion());
        return in_whole.State();
    };
    const double s = std::min(0.05 * h->radius, 0.1);
    const Vector3d centre = h->point + (up > 0.0 ? h->lo - s : h->hi + s) * h->axis;
    const Vector3d u = h->axis.unitOrthogonal(), v = h->axis.cross(u);
    bool ringed = state(centre) == TopAbs_OUT;
    for (int k = 0; k < 8 && ringed; ++k) {
        const double t = k * kPi / 4.0;
        const Vector3d radial = std::cos(t) * u + std::sin(t) * v;
        ringed = state(centre + (h->radius + s) * radial) == TopAbs_IN &&
                 (k % 2 == 1 || state(centre + 0.5 * h->radius * radial) == TopAbs_OUT);
    }
    return ringed;
}

// Which of `holes` a fill takes (Drillable) and, for each other, why not: access(), then, of those
// a drill makes, the ones whose lower end opens into a bore left open (IntoOpenBore).
// `whole_holes` are the whole part's holes, found as the component's are.
std::vector<Access> fill_access(const TopoDS_Shape& whole, const std::vector<Hole>& holes,
                                const std::vector<Hole>& whole_holes, const Vector3d& direction) {
    std::vector<Access> out = access(whole, holes);
    BRepClass3d_SolidClassifier in_whole(whole);
    for (std::size_t i = 0; i < holes.size(); ++i)
        if (out[i] == Access::Drillable &&
            opens_into_bore_below(in_whole, whole_holes, holes[i], direction))
            out[i] = Access::IntoOpenBore;
    return out;
}

// The one solid of `shape`, when it has exactly one and OCCT's check accepts it; else null.
TopoDS_Shape single_valid_solid(const TopoDS_Shape& shape) {
    TopoDS_Shape result;
    int solids = 0;
    for (TopExp_Explorer e(shape, TopAbs_SOLID); e.More(); e.Next(), ++solids) result = e.Current();
    if (solids != 1 || !BRepCheck_Analyzer(result).IsValid()) return {};
    return result;
}

// The holes' cylinders grown by `grow` all round and `far` past both ends, and their mouths'
// blends' cylinders grown by `grow` (their widest radius, over their extent), as Boolean tools.
TopTools_ListOfShape cylinders(const std::vector<Hole>& holes, double grow, double far) {
    TopTools_ListOfShape out;
    for (const Hole& h : holes) {
        out.Append(make_cylinder(h.point + (h.lo - far) * h.axis, h.axis, h.radius + grow,
                                 h.hi - h.lo + 2.0 * far));
        for (const Hole::Blend& b : h.blends)
            out.Append(make_cylinder(h.point + (b.lo - grow) * h.axis, h.axis, b.radius + grow,
                                     b.hi - b.lo + 2.0 * grow));
    }
    return out;
}

double volume_of_cut(const TopoDS_Shape& shape, const TopTools_ListOfShape& tools) {
    TopTools_ListOfShape args;
    args.Append(shape);
    BRepAlgoAPI_Cut cut;
    cut.SetArguments(args);
    cut.SetTools(tools);
    cut.SetRunParallel(Standard_False);
    cut.Build();
    if (!cut.IsDone() || cut.HasErrors()) return -1.0;
    return occ::volume_of(cut.Shape());
}

// Whether `after` holds all of `before` and adds material only within the holes' cylinders
// (open-ended: a face rebuilt across a hole's mouth in a curved face bulges past its rim): what
// OCCT's defeaturing did is closing the holes over, nothing else. Both are measured as what is
// left of one solid cut by the other (and the cylinders), a volume as small as what it
// measures, not as the difference of two volumes of the whole part, whose integration errors
// (1e-7 of it) exceed the tolerance: a bored valve body of 10034 mm^3 showed 0.0042 mm^3
// "outside" a radial bore that the direct cut finds none of.
bool only_closes_over(const TopoDS_Shape& before, const TopoDS_Shape& after,
                      const std::vector<Hole>& holes, double volume, std::string& why) {
    double most = 0.0;
    for (const Hole& h : holes) most += h.cylinder_volume();
    const double tol = 1e-6 * most + 1e-9 * volume + 1e-9;
    Bnd_Box box;
    BRepBndLib::Add(before, box);
    TopTools_ListOfShape result;
    result.Append(after);
    const double lost = volume_of_cut(before, result);
    TopTools_ListOfShape around = cylinders(holes, 1e-4, std::sqrt(box.SquareExtent()) + 1.0);
    around.Append(before);
    const double added_outside = volume_of_cut(after, around);
    if (lost < 0.0 || added_outside < 0.0) {
        why = "OCCT could not compare the part before and after closing it over";
        return false;
    }
    if (lost > tol) {
        why = "closing it over took " + format_number(lost) + " mm^3 off the part";
        return false;
    }
    if (added_outside > tol) {
        why = "closing it over added " + format_number(added_outside) + " mm^3 outside it";
        return false;
    }
    return true;
}

// `solid` with the faces of `holes` removed, or a null shape and why not.
TopoDS_Shape fill(const TopoDS_Shape& solid, double volume, const std::vector<Hole>& holes,
                  double& added, std::string& why) {
    try {
        BRepAlgoAPI_Defeaturing df;
        df.SetShape(solid);
        double most = 0.0;  // the holes' cylinders
        for (const Hole& h : holes) {
            for (const TopoDS_Face& f : h.faces) df.AddFaceToRemove(f);
            most += h.cylinder_volume();
        }
        df.SetRunParallel(Standard_False);
        df.SetToFillHistory(Standard_False);
        df.Build();
        if (!df.IsDone() || df.HasErrors()) {
            why = "OCCT could not close it over (BRepAlgoAPI_Defeaturing failed)";
            return {};
        }
        const TopoDS_Shape result = single_valid_solid(df.Shape());
        if (result.IsNull()) {
            why = "closing it over left no single valid solid";
            return {};
        }
        added = occ::volume_of(result) - volume;
        if (std::abs(added) <= 1e-9 * volume) {
            why =
                "OCCT's defeaturing could not extend the faces around it across it (as where it "
                "opens into another hole)";
            return {};
        }
        if (!(added > 0.0) || added > most * (1.0 + 1e-6) + 1e-9) {
            std::ostringstream s;
            s << "closing it over changed the volume by " << added << " mm^3, not within (0, "
              << most << "] as its cylinder allows";
            why = s.str();
            return {};
        }
        if (!only_closes_over(solid, result, holes, volume, why)) return {};
        return result;
    } catch (const Standard_Failure& f) {
        why = occ::failure_message("OCCT failed closing it over", f);
        return {};
    }
}

// Whether point p lies on the wall of `other` (its cylinder between lo and hi), within tol.
bool on_wall(const Hole& other, const Vector3d& p, double tol) {
    const Vector3d d = p - other.point;
    const double t = d.dot(other.axis);
    return t >= other.lo - tol && t <= other.hi + tol &&
           std::abs((d - t * other.axis).norm() - other.radius) <= tol;
}

// Whether the hole is a plain cylinder between lo and hi: its wall's edges are lines along the axis
// (seams) and circles of its radius square to it at lo or hi, and its bottom, if any, is flat at
// one of them. That is a hole drilled square through faces (or a cut) square to its axis, the
// commonest kind; its plug is that cylinder. An edge may also lie on the wall of one of `others`,
// holes plugged with it: where it opens into one of them (two ports' bores crossing in a
// manifold's block), its cylinder borders the other's, filled too.
bool square_ended(const Hole& hole, const std::vector<const Hole*>& others) {
    const double tol = 1e-6 * (1.0 + hole.hi - hole.lo + hole.radius);
    auto at_end = [&](const Vector3d& p) {
        const double t = (p - hole.point).dot(hole.axis);
        return std::abs(t - hole.lo) <= tol || std::abs(t - hole.hi) <= tol;
    };
    // The edge sampled at 17 points, each on the wall of one of `others`.
    auto into_other = [&](const BRepAdaptor_Curve& c, const TopoDS_Edge& edge) {
        if (others.empty()) return false;
        const double t0 = c.FirstParameter(), t1 = c.LastParameter();
        constexpr int n = 16;
        for (int i = 0; i <= n; ++i) {
            const Vector3d p = vec(c.Value(t0 + (t1 - t0) * i / n));
            bool on = false;
            for (const Hole* o : others)
                on = on ||
                     on_wall(*o, p,
                             BRep_Tool::Tolerance(edge) + 1e-6 * (1.0 + o->hi - o->lo + o->radius));
            if (!on) return false;
        }
        return true;
    };
    for (const TopoDS_Face& face : hole.faces) {
        BRepAdaptor_Surface s(face, Standard_False);
        if (s.GetType() == GeomAbs_Plane) {
            if (vec(s.Plane().Axis().Direction()).cross(hole.axis).norm() > 1e-9) return false;
        } else if (s.GetType() != GeomAbs_Cylinder) {
            return false;
        }
        for (TopExp_Explorer e(face, TopAbs_EDGE); e.More(); e.Next()) {
            const TopoDS_Edge& edge = TopoDS::Edge(e.Current());
            if (BRep_Tool::Degenerated(edge)) continue;
            const BRepAdaptor_Curve c(edge);
            bool square = false;
            if (c.GetType() == GeomAbs_Line) {
                square = vec(c.Line().Direction()).cross(hole.axis).norm() <= 1e-9;
            } else if (c.GetType() == GeomAbs_Circle) {
                const gp_Circ circle = c.Circle();
                const Vector3d d = vec(circle.Location()) - hole.point;
                square = std::abs(circle.Radius() - hole.radius) <= tol &&
                         vec(circle.Axis().Direction()).cross(hole.axis).norm() <= 1e-9 &&
                         at_end(vec(circle.Location())) &&
                         (d - d.dot(hole.axis) * hole.axis).norm() <= tol;
            }
            if (!square && !into_other(c, edge)) return false;
        }
    }
    return true;
}

// Which of `holes` are plugged by their cylinders: the most that are square-ended (above), each
// allowed to open into the others so chosen. (Two bores crossing are each square-ended only with
// the other: neither alone.)
std::vector<char> pluggable(const std::vector<Hole>& holes) {
    std::vector<char> in(holes.size(), 1);
    for (bool changed = true; changed;) {
        changed = false;
        for (std::size_t i = 0; i < holes.size(); ++i) {
            if (!in[i]) continue;
            std::vector<const Hole*> others;
            for (std::size_t j = 0; j < holes.size(); ++j)
                if (j != i && in[j]) others.push_back(&holes[j]);
            if (!square_ended(holes[i], others)) {
                in[i] = 0;
                changed = true;
            }
        }
    }
    return in;
}

// `solid` with the square-ended `holes` filled by fusing their cylinders in, or a null shape and
// why not.
TopoDS_Shape plug(const TopoDS_Shape& solid, double volume, const std::vector<Hole>& holes,
                  double& added, std::string& why) {
    try {
        TopTools_ListOfShape args, tools;
        args.Append(solid);
        double most = 0.0;
        for (const Hole& h : holes) {
            tools.Append(make_cylinder(h.point + h.lo * h.axis, h.axis, h.radius, h.hi - h.lo));
            most += h.cylinder_volume();
        }
        BRepAlgoAPI_Fuse fuse;
        fuse.SetArguments(args);
        fuse.SetTools(tools);
        fuse.SetRunParallel(Standard_False);
        fuse.SetToFillHistory(Standard_False);
        fuse.Build();
        if (!fuse.IsDone() || fuse.HasErrors()) {
            why = "OCCT could not fuse their plugs in";
            return {};
        }
        // In place: the holes left, found on `solid`, are closed over in the result by their
        // faces, which OCCT's defeaturing takes as they are (fill_all).
        const double before = occ::max_tolerance(fuse.Shape());
        const TopoDS_Shape unified = occ::unify_in_place(fuse.Shape());
        if (occ::widened(unified, before)) {
            why = "removing the seams round their plugs widened a tolerance past " +
                  format_number(occ::kUnifiedToleranceMm) + " mm";
            return {};
        }
        const TopoDS_Shape result = single_valid_solid(unified);
        if (result.IsNull()) {
            why = "fusing their plugs in left no single valid solid";
            return {};
        }
        added = occ::volume_of(result) - volume;
        if (!(added > 0.0) || added > most * (1.0 + 1e-6) + 1e-9) {
            why = "fusing their plugs in changed the volume by more than their cylinders hold";
            return {};
        }
        return result;
    } catch (const Standard_Failure& f) {
        why = occ::failure_message("OCCT failed fusing their plugs in", f);
        return {};
    }
}

FilledHole filled_hole(const Hole& hole, const Vector3d& direction) {
    FilledHole f;
    f.axis = hole.axis.dot(direction) < 0.0 ? -hole.axis : hole.axis;
    f.centre = hole.centre();
    f.diameter_mm = 2.0 * hole.radius;
    f.length_mm = hole.hi - hole.lo;
    return f;
}

// fill_holes() past its checks: `out.solid` is the component, `whole` the part.
void fill_all(HoleFill& out, const Vector3d& direction, double max_diameter, double overhang_rad,
              const TopoDS_Shape& whole, const Progress& progress) {
    TopoDS_Shape solid = occ::occt(out.solid);
    std::vector<Hole> holes = find_holes(solid, direction, max_diameter, overhang_rad, {});
    if (holes.empty()) return;
    // The whole part's holes, read once: the component's own where it is the whole part.
    const std::vector<Hole> whole_holes =
        whole.IsSame(solid) ? holes : find_holes(whole, direction, max_diameter, overhang_rad, {});
    std::vector<Hole> kept_open;
    // The holes a fill takes; for each other one a note says why, and it is kept open.
    auto fillable = [&](std::vector<Hole> found) {
        if (found.empty()) return found;
        progress.check();
        const std::vector<Access> a = fill_access(whole, found, whole_holes, direction);
        std::vector<Hole> out_holes;
        for (std::size_t i = 0; i < found.size(); ++i) {
            if (a[i] == Access::Drillable) {
                out_holes.push_back(std::move(found[i]));
                continue;
            }
            out.notes.push_back(
                describe(found[i]) + " stays open: " +
                (a[i] == Access::HoldsMaterial
                     ? "it holds material (a post or a rib in it): no drill makes it"
                 : a[i] == Access::Unreachable
                     ? "no drill of its diameter reaches it along its axis from outside the part"
                     : "its lower end opens into a bore that goes on past it (round a bend, or "
                       "widening) and stays open: its plug would end there in a face across "
                       "that bore, hanging over it"));
            kept_open.push_back(std::move(found[i]));
        }
        return out_holes;
    };
    holes = fillable(std::move(holes));
    if (holes.empty()) return;
    double volume = occ::volume_of(solid);
    // Square-ended holes get their cylinders fused in, in one Boolean: far quicker than OCCT's
    // defeaturing, which closes holes over by rebuilding the faces around each.
    std::vector<Hole> square, other;
    const std::vector<char> plugged = pluggable(holes);
    for (std::size_t i = 0; i < holes.size(); ++i)
        (plugged[i] ? square : other).push_back(std::move(holes[i]));
    if (!square.empty()) {
        progress.check();
        double added = 0.0;
        std::string why;
        const TopoDS_Shape filled = plug(solid, volume, square, added, why);
        if (filled.IsNull()) {
            other.insert(other.end(), square.begin(), square.end());
        } else {
            for (const Hole& h : square) out.holes.push_back(filled_hole(h, direction));
            out.added_volume_mm3 += added;
            solid = filled;
            volume += added;
        }
    }
    holes = std::move(other);
    const std::vector<Hole> checked_holes = holes;
    // The others all at once, kept when none of them is left: one defeaturing instead of one a
    // hole, each on the whole solid.
    if (holes.size() > 1) {
        progress.check();
        double added = 0.0;
        std::string why;
        const TopoDS_Shape filled = fill(solid, volume, holes, added, why);
        if (!filled.IsNull() &&
            find_holes(filled, direction, max_diameter, overhang_rad, kept_open).empty()) {
            for (const Hole& h : holes) out.holes.push_back(filled_hole(h, direction));
            out.added_volume_mm3 += added;
            out.solid = occ::wrap(filled);
            return;
        }
    }
    // Else one at a time, each found again on the last result (a fill rebuilds the faces around
    // it), to tell those OCCT fills from those it does not. A round fills a hole, which takes its
    // faces away, or keeps one open: the bound is a guard.
    if (!holes.empty()) {
        TopTools_IndexedMapOfShape faces;
        TopExp::MapShapes(solid, TopAbs_FACE, faces);
        for (int round = 0; round <= 2 * faces.Extent(); ++round) {
            const std::vector<Hole> left =
                find_holes(solid, direction, max_diameter, overhang_rad, kept_open);
            if (left.empty()) break;
            // Checked already, unless a fill changed it.
            bool checked = false;
            for (const Hole& h : checked_holes)
                if (h.same(left.front().point, left.front().axis, left.front().radius, 1e-4) &&
                    (h.centre() - left.front().centre()).norm() < 1e-4)
                    checked = true;
            const std::vector<Hole> one =
                checked ? std::vector<Hole>{left.front()} : fillable({left.front()});
            if (one.empty()) continue;
            progress.check();
            const Hole& hole = one.front();
            double added = 0.0;
            std::string why;
            const TopoDS_Shape filled = fill(solid, volume, {hole}, added, why);
            if (filled.IsNull()) {
                out.notes.push_back(describe(hole) + " stays open: " + why);
                kept_open.push_back(hole);
                continue;
            }
            out.holes.push_back(filled_hole(hole, direction));
            out.added_volume_mm3 += added;
            solid = filled;
            volume += added;
        }
    }
    if (!out.holes.empty()) out.solid = occ::wrap(solid);
}

// fill_holes()'s and holes_to_fill()'s checks of their arguments; the unit build direction.
Vector3d checked_direction(const Eigen::Vector3d& build_direction, double max_diameter_mm,
                           double overhang_angle_deg) {
    if (!(max_diameter_mm >= 0.0) || !std::isfinite(max_diameter_mm))
        throw Error(ErrorCode::InvalidArgument,
                    "the largest hole to fill must be a diameter >= 0 mm, got " +
                        format_number(max_diameter_mm));
    if (!(overhang_angle_deg >= 0.0 && overhang_angle_deg < 90.0))
        throw Error(ErrorCode::InvalidArgument,
                    "the overhang angle must lie in [0, 90) degrees, got " +
                        format_number(overhang_angle_deg));
    const double length = build_direction.norm();
    if (!(length > 0.0) || !std::isfinite(length))
        throw Error(ErrorCode::InvalidArgument, "the build direction must be a non-zero vector");
    return build_direction / length;
}

}  // namespace

std::string describe(const FilledHole& hole) { return hole_at(hole.diameter_mm, hole.centre); }

bool leans_over(const Eigen::Vector3d& axis, const Eigen::Vector3d& direction,
                double overhang_angle_deg) {
    return leans_over_rad(axis, direction, overhang_angle_deg * kPi / 180.0);
}

std::vector<FilledHole> holes_to_fill(const Shape& input, const Eigen::Vector3d& build_direction,
                                      double max_diameter_mm, double overhang_angle_deg,
                                      const Shape& part, const Progress& progress) {
    const Vector3d direction =
        checked_direction(build_direction, max_diameter_mm, overhang_angle_deg);
    std::vector<FilledHole> out;
    if (max_diameter_mm == 0.0) return out;
    const Shape solid = input.single_solid("the component");
    try {
        const double overhang_rad = overhang_angle_deg * kPi / 180.0;
        const TopoDS_Shape component = occ::occt(solid);
        const std::vector<Hole> found =
            find_holes(component, direction, max_diameter_mm, overhang_rad, {});
        if (found.empty()) return out;
        progress.check();
        const TopoDS_Shape whole = part.is_null() ? component : occ::occt(part);
        const std::vector<Access> a =
            fill_access(whole, found,
                        whole.IsSame(component)
                            ? found
                            : find_holes(whole, direction, max_diameter_mm, overhang_rad, {}),
                        direction);
        for (std::size_t i = 0; i < found.size(); ++i)
            if (a[i] == Access::Drillable) out.push_back(filled_hole(found[i], direction));
    } catch (const Standard_Failure& f) {
        throw Error(ErrorCode::GeometryFailure,
                    occ::failure_message("OCCT failed finding the component's holes", f));
    }
    return out;
}

HoleFill fill_holes(const Shape& input, const Eigen::Vector3d& build_direction,
                    double max_diameter_mm, double overhang_angle_deg, const Shape& part,
                    const Progress& progress) {
    const Vector3d direction =
        checked_direction(build_direction, max_diameter_mm, overhang_angle_deg);
    HoleFill out;
    out.solid = input;
    if (max_diameter_mm == 0.0) return out;
    out.solid = input.single_solid("the component");
    try {
        fill_all(out, direction, max_diameter_mm, overhang_angle_deg * kPi / 180.0,
                 part.is_null() ? occ::occt(out.solid) : occ::occt(part), progress);
    } catch (const Standard_Failure& f) {
        throw Error(ErrorCode::GeometryFailure,
                    occ::failure_message("OCCT failed filling the component's holes", f));
    }
    return out;
}

}  // namespace mas
