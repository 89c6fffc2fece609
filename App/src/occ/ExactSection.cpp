// OCCT's exact cross-sections of a solid (BRepAlgoAPI_Section, edges joined into wires and wires
// into faces, areas and centroids from BRepGProp): the reference the mesh section kernel is checked
// against. The result is a mas::Section filled the way slice_mesh() fills it.
#include <BOPAlgo_Tools.hxx>
#include <BOPTools_AlgoTools3D.hxx>
#include <BRepAdaptor_Curve.hxx>
#include <BRepAlgoAPI_Section.hxx>
#include <BRepClass3d_SolidClassifier.hxx>
#include <BRepGProp.hxx>
#include <BRepTools.hxx>
#include <BRepTools_WireExplorer.hxx>
#include <BRep_Builder.hxx>
#include <BRep_Tool.hxx>
#include <GCPnts_QuasiUniformDeflection.hxx>
#include <GProp_GProps.hxx>
#include <IntTools_Context.hxx>
#include <Precision.hxx>
#include <TopExp.hxx>
#include <TopExp_Explorer.hxx>
#include <TopTools_IndexedDataMapOfShapeListOfShape.hxx>
#include <TopoDS.hxx>
#include <TopoDS_Compound.hxx>
#include <TopoDS_Face.hxx>
#include <TopoDS_Iterator.hxx>
#include <TopoDS_Wire.hxx>
#include <algorithm>
#include <cmath>
#include <gp_Pln.hxx>

#include "ShapeImpl.hpp"

namespace mas {

namespace {

Eigen::Vector3d to_eigen(const gp_Pnt& p) { return {p.X(), p.Y(), p.Z()}; }

// The wire as a closed polyline (last point not repeated), in the plane's 2-D frame. Edges are
// walked in wire order on the face and each is discretised within `deflection` along its direction.
Polygon2 discretise(const TopoDS_Wire& wire, const TopoDS_Face& face, const PlaneFrame& frame,
                    double deflection) {
    Polygon2 loop;
    int walked = 0;
    for (BRepTools_WireExplorer x(wire, face); x.More(); x.Next(), ++walked) {
        const TopoDS_Edge& edge = x.Current();
        if (BRep_Tool::Degenerated(edge)) continue;
        const BRepAdaptor_Curve curve(edge);
        GCPnts_QuasiUniformDeflection points(curve, deflection);
        if (!points.IsDone() || points.NbPoints() < 2)
            throw Error(ErrorCode::GeometryFailure,
                        "exact section: OCCT cannot discretise an edge within loop_deflection " +
                            format_number(deflection) + " mm");
        std::vector<Eigen::Vector2d> along;
        along.reserve(points.NbPoints());
        for (int i = 1; i <= points.NbPoints(); ++i)
            along.push_back(frame.to_2d(to_eigen(points.Value(i))));
        if (edge.Orientation() == TopAbs_REVERSED) std::reverse(along.begin(), along.end());
        along.pop_back();  // the next edge starts there
        loop.points.insert(loop.points.end(), along.begin(), along.end());
    }
    // The explorer stops early on a wire whose edges do not chain; the loop would be wrong.
    int edges = 0;
    for (TopExp_Explorer x(wire, TopAbs_EDGE); x.More(); x.Next()) ++edges;
    if (walked != edges)
        throw Error(ErrorCode::GeometryFailure, "exact section: a section wire does not chain");
    return loop;
}

// Orients a loop: counter-clockwise for an outer boundary, clockwise for a hole.
void orient(Polygon2& loop, bool outer) {
    if ((signed_area(loop) > 0.0) != outer) std::reverse(loop.points.begin(), loop.points.end());
}

// WiresToFaces splits the plane by the wires: it returns every bounded cell, the disc inside a
// hole as well as the ring around it. A cell belongs to the section when a point inside it lies
// in the solid, or on its boundary for a plane lying on a planar face of the solid.
std::vector<TopoDS_Face> material_cells(const TopoDS_Shape& wires,
                                        BRepClass3d_SolidClassifier& inside,
                                        const Handle(IntTools_Context) & context) {
    std::vector<TopoDS_Face> cells;
    TopoDS_Shape faces;
    if (!BOPAlgo_Tools::WiresToFaces(wires, faces)) return cells;  // no closed wire
    for (TopExp_Explorer fx(faces, TopAbs_FACE); fx.More(); fx.Next()) {
        const TopoDS_Face& face = TopoDS::Face(fx.Current());
        gp_Pnt probe;
        gp_Pnt2d probe_uv;
        if (BOPTools_AlgoTools3D::PointInFace(face, probe, probe_uv, context) != 0)
            throw Error(ErrorCode::GeometryFailure,
                        "exact section: no point found inside a section cell");
        inside.Perform(probe, Precision::Confusion());
        if (inside.State() != TopAbs_OUT) cells.push_back(face);
    }
    return cells;
}

Section section_by(const TopoDS_Shape& solid, BRepClass3d_SolidClassifier& inside,
                   const Plane& plane, double deflection) {
    Section out;
    out.plane = plane;
    out.centroid = plane.origin;
    const PlaneFrame frame(plane.normal);

    const gp_Pln pln(gp_Pnt(plane.origin.x(), plane.origin.y(), plane.origin.z()),
                     gp_Dir(plane.normal.x(), plane.normal.y(), plane.normal.z()));
    BRepAlgoAPI_Section section(solid, pln, Standard_False);
    // Keep the exact intersection curves (lines, circles, ellipses), and OCCT's traced points as
    // they are where it can only trace (fitting B-splines to them lost 5 % of a helical sweep's
    // section); never touch the argument (Shape is shared and immutable; the Boolean may grow
    // tolerances).
    section.Approximation(Standard_False);
    section.SetNonDestructive(Standard_True);
    section.Build();
    if (!section.IsDone() || section.HasErrors())
        throw Error(ErrorCode::GeometryFailure, "exact section: OCCT's section algorithm failed");

    BRep_Builder builder;
    TopoDS_Compound edges;
    builder.MakeCompound(edges);
    int edge_count = 0;
    for (TopExp_Explorer x(section.Shape(), TopAbs_EDGE); x.More(); x.Next(), ++edge_count)
        builder.Add(edges, x.Current());
    if (edge_count == 0) return out;  // the plane misses the solid

    // The section's edges already share their vertices (they come out of one Boolean).
    TopoDS_Shape wires;
    if (BOPAlgo_Tools::EdgesToWires(edges, wires, Standard_True) != 0)
        throw Error(ErrorCode::GeometryFailure, "exact section: cannot join the section edges");
    for (TopoDS_Iterator w(wires); w.More(); w.Next())
        if (w.Value().ShapeType() == TopAbs_WIRE && !BRep_Tool::IsClosed(w.Value()))
            ++out.open_chains;
    const Handle(IntTools_Context) context = new IntTools_Context;
    std::vector<TopoDS_Face> cells = material_cells(wires, inside, context);

    // A plane lying on a planar face of the solid gets that face as a cell "on" the solid beside
    // the cells inside it (the L-block's column and arm at the arm's underside): drop the edges
    // two such cells share and build the cells again, so that one region is one face.
    TopTools_IndexedDataMapOfShapeListOfShape cells_of_edge;
    for (const TopoDS_Face& f : cells)
        TopExp::MapShapesAndAncestors(f, TopAbs_EDGE, TopAbs_FACE, cells_of_edge);
    bool shared = false;
    TopoDS_Compound outline;
    builder.MakeCompound(outline);
    for (int i = 1; i <= cells_of_edge.Extent(); ++i) {
        if (cells_of_edge(i).Extent() > 1)
            shared = true;
        else
            builder.Add(outline, cells_of_edge.FindKey(i));
    }
    if (shared) {
        TopoDS_Shape merged;
        if (BOPAlgo_Tools::EdgesToWires(outline, merged, Standard_True) != 0)
            throw Error(ErrorCode::GeometryFailure, "exact section: cannot join the section edges");
        cells = material_cells(merged, inside, context);
    }

    for (const TopoDS_Face& face : cells) {
        SectionRegion region;
        const TopoDS_Wire outer = BRepTools::OuterWire(face);
        for (TopoDS_Iterator w(face); w.More(); w.Next()) {
            if (w.Value().ShapeType() != TopAbs_WIRE) continue;
            const TopoDS_Wire& wire = TopoDS::Wire(w.Value());
            Polygon2 loop = discretise(wire, face, frame, deflection);
            const bool is_outer = wire.IsSame(outer);
            orient(loop, is_outer);
            if (is_outer)
                region.shape.outer = std::move(loop);
            else
                region.shape.holes.push_back(std::move(loop));
        }
        // Area and centroid from OCCT's face: exact for lines, circles and ellipses. But the face
        // OCCT builds on loops it could only trace can be wrong (across a torus' tube, off its
        // axis, one oval came out 73.70 mm2 for 78.57, its centroid 0.65 mm off; fitting
        // B-splines to the traces instead put a helical sweep's section 5 % short). The loops
        // discretised within `deflection` bound the true area to perimeter x deflection: a face
        // farther off is not taken, the loops' own area and centroid are.
        GProp_GProps props;
        BRepGProp::SurfaceProperties(face, props);
        const double loops_area = area(region.shape);
        if (std::abs(std::abs(props.Mass()) - loops_area) <= perimeter(region.shape) * deflection) {
            region.area = std::abs(props.Mass());
            region.centroid = to_eigen(props.CentreOfMass());
        } else {
            region.area = loops_area;
            region.centroid = frame.to_3d(centroid(region.shape), plane);
        }
        region.bounds = occ::tight_bounds(outer);  // of the exact outer boundary
        out.regions.push_back(std::move(region));
    }
    finish_section(out);
    return out;
}

}  // namespace

std::vector<Section> exact_sections(const Shape& solid, const std::vector<Plane>& planes,
                                    double loop_deflection_mm) {
    if (!std::isfinite(loop_deflection_mm) || !(loop_deflection_mm > 0.0))
        throw Error(ErrorCode::InvalidArgument,
                    "exact section: the loop deflection must be a positive number of millimetres");
    std::vector<Plane> checked;
    checked.reserve(planes.size());
    for (const Plane& p : planes) checked.push_back(make_plane(p.origin, p.normal));
    const Shape one = solid.single_solid("exact section input");
    std::vector<Section> out;
    out.reserve(checked.size());
    try {
        BRepClass3d_SolidClassifier inside(occ::occt(one));
        for (const Plane& p : checked)
            out.push_back(section_by(occ::occt(one), inside, p, loop_deflection_mm));
    } catch (const Standard_Failure& e) {
        throw Error(ErrorCode::GeometryFailure, occ::failure_message("exact section", e));
    }
    return out;
}

}  // namespace mas
