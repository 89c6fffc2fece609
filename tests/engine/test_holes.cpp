// Holes deposited solid and drilled afterwards (Holes.hpp): which holes are filled, by how much
// material, and that a part whose only overhang is a hole's ceiling is then built with every
// layer supported.
#include <gtest/gtest.h>

#include <BRepAdaptor_Curve.hxx>
#include <BRepAlgoAPI_Common.hxx>
#include <BRepAlgoAPI_Cut.hxx>
#include <BRepFilletAPI_MakeChamfer.hxx>
#include <BRepFilletAPI_MakeFillet.hxx>
#include <BRepPrimAPI_MakeSphere.hxx>
#include <BRepPrimAPI_MakeTorus.hxx>
#include <Eigen/Geometry>
#include <TopExp.hxx>
#include <TopTools_IndexedDataMapOfShapeListOfShape.hxx>
#include <TopTools_IndexedMapOfShape.hxx>
#include <TopoDS.hxx>
#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "mas/Angles.hpp"
#include "mas/CentroidalAxis.hpp"
#include "mas/Decompose.hpp"
#include "mas/Error.hpp"
#include "mas/Holes.hpp"
#include "mas/SlicePart.hpp"
#include "test_parts.hpp"

using Eigen::Vector3d;
using mas::kPi;
using mas::test::from_occt;
using mas::test::fuse;
using mas::test::occ_box;
using mas::test::occ_cylinder;

namespace {

TopoDS_Shape cut(const TopoDS_Shape& a, const TopoDS_Shape& b) {
    BRepAlgoAPI_Cut c(a, b);
    EXPECT_TRUE(c.IsDone());
    return c.Shape();
}

// A clevis ear: a plate [0,40]x[0,20]x[0,5] with an ear [10,30]x[6,14]x[5,50] standing on it. A
// pin hole of radius 4 goes through the ear along Y at x = 20, z = 20 (8 mm long, through the
// ear's two faces); `big_hole` adds one of radius 6 at z = 38, `vertical_hole` one of radius 3
// through the plate along Z at (5, 10).
TopoDS_Shape clevis_ear(bool big_hole, bool vertical_hole) {
    TopoDS_Shape s = fuse(occ_box(0, 0, 0, 40, 20, 5), occ_box(10, 6, 5, 20, 8, 45));
    s = cut(s, occ_cylinder({20, 0, 20}, Vector3d::UnitY(), 4.0, 20.0));
    if (big_hole) s = cut(s, occ_cylinder({20, 0, 38}, Vector3d::UnitY(), 6.0, 20.0));
    if (vertical_hole) s = cut(s, occ_cylinder({5, 10, -1}, Vector3d::UnitZ(), 3.0, 10.0));
    return s;
}

double volume(const mas::Shape& s) { return s.info().volume_mm3; }

// BREP volumes are exact up to OCCT's integration: a millionth of the part.
void expect_volume(double actual, double expected, double part) {
    EXPECT_NEAR(actual, expected, 1e-6 * part);
}

}  // namespace

TEST(Holes, AHorizontalPinHoleIsFilledAndAVerticalOneAndALargerOneStayOpen) {
    const mas::Shape part = from_occt(clevis_ear(true, true));
    const double before = volume(part);
    const mas::HoleFill f = mas::fill_holes(part, Vector3d::UnitZ(), 10.0, 45.0);
    ASSERT_EQ(f.holes.size(), 1u);
    EXPECT_TRUE(f.notes.empty());
    const mas::FilledHole& h = f.holes[0];
    EXPECT_EQ(h.component, -1);
    EXPECT_NEAR(std::abs(h.axis.y()), 1.0, 1e-12);
    EXPECT_NEAR(h.centre.x(), 20.0, 1e-9);
    EXPECT_NEAR(h.centre.y(), 10.0, 1e-9);
    EXPECT_NEAR(h.centre.z(), 20.0, 1e-9);
    EXPECT_NEAR(h.diameter_mm, 8.0, 1e-9);
    EXPECT_NEAR(h.length_mm, 8.0, 1e-9);  // the ear's thickness, not the tool's 20
    expect_volume(f.added_volume_mm3, kPi * 16.0 * 8.0, before);
    expect_volume(volume(f.solid), before + kPi * 16.0 * 8.0, before);
    EXPECT_EQ(f.solid.info().solids, 1);
    // The caller's part is not touched.
    EXPECT_DOUBLE_EQ(volume(part), before);
    // The larger hole is filled once the limit takes it: both at once.
    const mas::HoleFill both = mas::fill_holes(part, Vector3d::UnitZ(), 12.0, 45.0);
    ASSERT_EQ(both.holes.size(), 2u);
    EXPECT_TRUE(both.notes.empty());
    expect_volume(both.added_volume_mm3, kPi * (16.0 + 36.0) * 8.0, before);
    expect_volume(volume(both.solid), before + both.added_volume_mm3, before);
}

TEST(Holes, AHoleWithFilletedOrChamferedMouthsIsFilledMouthsAndAll) {
    // The clevis ear's pin hole (radius 4, through the ear's faces y = 6 and y = 14) with the
    // edges of its two mouths rounded (radius 1) or chamfered (1 mm): the blends go with the hole,
    // and closing it over extends the ear's faces across, leaving the ear as if never drilled
    // (4000 + 7200 mm^3). Defeaturing the wall alone extended nothing: the hole stayed open, after
    // 39 s on a filleted lug.
    const TopoDS_Shape ear = clevis_ear(false, false);
    const double solid_ear = 40.0 * 20.0 * 5.0 + 20.0 * 8.0 * 45.0;
    for (const bool chamfer : {false, true}) {
        SCOPED_TRACE(chamfer ? "chamfered" : "filleted");
        std::vector<TopoDS_Edge> mouths;
        TopTools_IndexedMapOfShape edges;
        TopExp::MapShapes(ear, TopAbs_EDGE, edges);
        for (int i = 1; i <= edges.Extent(); ++i) {
            const BRepAdaptor_Curve c(TopoDS::Edge(edges(i)));
            if (c.GetType() == GeomAbs_Circle && std::abs(c.Circle().Radius() - 4.0) < 1e-9)
                mouths.push_back(TopoDS::Edge(edges(i)));
        }
        ASSERT_EQ(mouths.size(), 2u);
        TopoDS_Shape blended;
        if (chamfer) {
            TopTools_IndexedDataMapOfShapeListOfShape edge_faces;
            TopExp::MapShapesAndAncestors(ear, TopAbs_EDGE, TopAbs_FACE, edge_faces);
            BRepFilletAPI_MakeChamfer mk(ear);
            for (const TopoDS_Edge& m : mouths)
                for (const TopoDS_Shape& f : edge_faces.FindFromKey(m))
                    if (BRepAdaptor_Surface(TopoDS::Face(f)).GetType() == GeomAbs_Plane)
                        mk.Add(1.0, 1.0, m, TopoDS::Face(f));
            blended = mk.Shape();
        } else {
            BRepFilletAPI_MakeFillet mk(ear);
            for (const TopoDS_Edge& m : mouths) mk.Add(1.0, m);
            blended = mk.Shape();
        }
        const mas::Shape part = from_occt(blended);
        const double before = volume(part);
        EXPECT_LT(before, solid_ear - kPi * 16.0 * 8.0);
        const mas::HoleFill f = mas::fill_holes(part, Vector3d::UnitZ(), 10.0, 45.0);
        for (const std::string& n : f.notes) ADD_FAILURE() << n;
        ASSERT_EQ(f.holes.size(), 1u);
        EXPECT_NEAR(f.holes[0].diameter_mm, 8.0, 1e-9);
        EXPECT_NEAR(f.holes[0].length_mm, 8.0, 1e-9);
        expect_volume(volume(f.solid), solid_ear, solid_ear);
        expect_volume(f.added_volume_mm3, solid_ear - before, solid_ear);
    }
}

TEST(Holes, ABlindHoleIsFilledWithItsBottom) {
    // 5 deep from the ear's face y = 6, flat-bottomed.
    TopoDS_Shape s = fuse(occ_box(0, 0, 0, 40, 20, 5), occ_box(10, 6, 5, 20, 8, 45));
    s = cut(s, occ_cylinder({20, 0, 20}, Vector3d::UnitY(), 4.0, 11.0));
    const mas::Shape part = from_occt(s);
    const mas::HoleFill f = mas::fill_holes(part, Vector3d::UnitZ(), 8.0, 45.0);
    ASSERT_EQ(f.holes.size(), 1u);
    EXPECT_NEAR(f.holes[0].length_mm, 5.0, 1e-9);
    EXPECT_NEAR(f.holes[0].centre.y(), 8.5, 1e-9);
    expect_volume(f.added_volume_mm3, kPi * 16.0 * 5.0, volume(part));
}

TEST(Holes, OnlyAHoleLeaningPastTheOverhangAngleIsFilled) {
    // Through holes of radius 3 in a 40 mm cube, leaning 30 and 60 degrees off Z in XZ.
    for (const double lean : {30.0, 60.0}) {
        const double a = lean * kPi / 180.0;
        const Vector3d axis(std::sin(a), 0.0, std::cos(a));
        const TopoDS_Shape cube = occ_box(0, 0, 0, 40, 40, 40);
        const TopoDS_Shape tool = occ_cylinder(Vector3d(20, 20, 20) - 40.0 * axis, axis, 3.0, 80.0);
        const mas::Shape part = from_occt(cut(cube, tool));
        const double hole = 40.0 * 40.0 * 40.0 - volume(part);
        const mas::HoleFill f = mas::fill_holes(part, Vector3d::UnitZ(), 6.0, 45.0);
        if (lean < 45.0) {
            EXPECT_TRUE(f.holes.empty()) << lean;
            EXPECT_DOUBLE_EQ(volume(f.solid), volume(part));
            // Built along X, the same hole leans 60 degrees off the build direction.
            const mas::HoleFill x = mas::fill_holes(part, Vector3d::UnitX(), 6.0, 45.0);
            ASSERT_EQ(x.holes.size(), 1u);
            EXPECT_GT(x.holes[0].axis.x(), 0.0);  // pointing along the build direction
            expect_volume(x.added_volume_mm3, hole, 64000.0);
        } else {
            ASSERT_EQ(f.holes.size(), 1u) << lean;
            EXPECT_NEAR(f.holes[0].axis.dot(axis), 1.0, 1e-12);
            EXPECT_NEAR(f.holes[0].centre.x(), 20.0, 1e-6);
            EXPECT_NEAR(f.holes[0].centre.z(), 20.0, 1e-6);
            expect_volume(f.added_volume_mm3, hole, 64000.0);
            expect_volume(volume(f.solid), 64000.0, 64000.0);
        }
    }
}

TEST(Holes, SlantedHolesAreClosedOverAllAtOnce) {
    // Two parallel through holes of radius 3 leaning 60 degrees off Z in XZ, at y = 12 and 28, in
    // a 40 mm cube: they leave its faces slanted, so no cylinder plugs them; OCCT's defeaturing
    // closes both over in one go.
    const double a = 60.0 * kPi / 180.0;
    const Vector3d axis(std::sin(a), 0.0, std::cos(a));
    TopoDS_Shape s = occ_box(0, 0, 0, 40, 40, 40);
    for (const double y : {12.0, 28.0})
        s = cut(s, occ_cylinder(Vector3d(20, y, 20) - 40.0 * axis, axis, 3.0, 80.0));
    const mas::Shape part = from_occt(s);
    const mas::HoleFill f = mas::fill_holes(part, Vector3d::UnitZ(), 6.0, 45.0);
    ASSERT_EQ(f.holes.size(), 2u);
    EXPECT_TRUE(f.notes.empty());
    EXPECT_NEAR(f.holes[0].centre.y() + f.holes[1].centre.y(), 40.0, 1e-6);
    expect_volume(f.added_volume_mm3, 64000.0 - volume(part), 64000.0);
    expect_volume(volume(f.solid), 64000.0, 64000.0);
}

TEST(Holes, AClosedCavityNoDrillReachesStaysOpenWithANote) {
    // A block [0,40]x[0,20]x[0,40] with a closed cylindrical cavity of radius 3 along X from
    // x = 10 to 30 at y = 10, z = 20: its walls and both ends qualify, but no drill gets in.
    const TopoDS_Shape block = occ_box(0, 0, 0, 40, 20, 40);
    const mas::Shape part =
        from_occt(cut(block, occ_cylinder({10, 10, 20}, Vector3d::UnitX(), 3.0, 20.0)));
    const mas::HoleFill f = mas::fill_holes(part, Vector3d::UnitZ(), 8.0, 45.0);
    EXPECT_TRUE(f.holes.empty());
    ASSERT_EQ(f.notes.size(), 1u);
    EXPECT_NE(f.notes[0].find("no drill of its diameter reaches it"), std::string::npos)
        << f.notes[0];
    EXPECT_NE(f.notes[0].find("6 mm across at (20, 10, 20)"), std::string::npos) << f.notes[0];
    EXPECT_DOUBLE_EQ(volume(f.solid), volume(part));
    // Opened to the block's side at x = 40, it is a blind hole 30 deep, drilled from there.
    const mas::Shape blind =
        from_occt(cut(block, occ_cylinder({10, 10, 20}, Vector3d::UnitX(), 3.0, 31.0)));
    const mas::HoleFill g = mas::fill_holes(blind, Vector3d::UnitZ(), 8.0, 45.0);
    ASSERT_EQ(g.holes.size(), 1u) << (g.notes.empty() ? "" : g.notes[0]);
    EXPECT_NEAR(g.holes[0].centre.x(), 25.0, 1e-9);
    EXPECT_NEAR(g.holes[0].length_mm, 30.0, 1e-9);
    expect_volume(g.added_volume_mm3, kPi * 9.0 * 30.0, 64000.0);
}

TEST(Holes, AHoleMeetingAnotherStaysOpenWithANote) {
    // A vertical bore of radius 3 from the top of the block down to z = 20 at x = 10, and a
    // horizontal one from its axis out through the side x = 40: OCCT's defeaturing does not
    // close a hole over where it opens into another.
    TopoDS_Shape s = occ_box(0, 0, 0, 40, 20, 40);
    s = cut(s, occ_cylinder({10, 10, 20}, Vector3d::UnitZ(), 3.0, 21.0));
    s = cut(s, occ_cylinder({10, 10, 20}, Vector3d::UnitX(), 3.0, 31.0));
    const mas::Shape part = from_occt(s);
    const mas::HoleFill f = mas::fill_holes(part, Vector3d::UnitZ(), 8.0, 45.0);
    EXPECT_TRUE(f.holes.empty());
    ASSERT_EQ(f.notes.size(), 1u);
    EXPECT_NE(f.notes[0].find("6 mm across at (25, 10, 20)"), std::string::npos) << f.notes[0];
    EXPECT_NE(f.notes[0].find("could not extend the faces around it"), std::string::npos)
        << f.notes[0];
    EXPECT_DOUBLE_EQ(volume(f.solid), volume(part));
    // With a plain through hole beside it, that one is filled all the same (all at once fails,
    // one at a time does not).
    const mas::Shape two =
        from_occt(cut(s, occ_cylinder({-1, 10, 8}, Vector3d::UnitX(), 2.0, 42.0)));
    const mas::HoleFill g = mas::fill_holes(two, Vector3d::UnitZ(), 8.0, 45.0);
    ASSERT_EQ(g.holes.size(), 1u);
    EXPECT_NEAR(g.holes[0].centre.x(), 20.0, 1e-9);
    EXPECT_NEAR(g.holes[0].centre.z(), 8.0, 1e-9);
    EXPECT_NEAR(g.holes[0].length_mm, 40.0, 1e-9);
    ASSERT_EQ(g.notes.size(), 1u);
    EXPECT_NE(g.notes[0].find("6 mm across at (25, 10, 20)"), std::string::npos) << g.notes[0];
    expect_volume(g.added_volume_mm3, kPi * 4.0 * 40.0, volume(two));
}

TEST(Holes, TwoBoresCrossingArePluggedTogether) {
    // A manifold's block [0,40]x[0,40]x[0,50] bored from two sides, as two ports' bores cross
    // inside it (survey seed 125, manifold 1): radius 3 along X at y = 18, z = 11 from x = 0 to
    // 16, and radius 4 along Y at x = 18, z = 14 from y = 0 to 20. Each opens into the other near
    // its blind end: neither is square-ended alone, and OCCT's defeaturing closes neither over
    // (on this block; on one 40 mm tall it does). Open, their ceilings overhang 9 mm^2.
    TopoDS_Shape s = occ_box(0, 0, 0, 40, 40, 50);
    s = cut(s, occ_cylinder({-1, 18, 11}, Vector3d::UnitX(), 3.0, 17.0));
    s = cut(s, occ_cylinder({18, -1, 14}, Vector3d::UnitY(), 4.0, 21.0));
    const mas::Shape part = from_occt(s);
    const mas::HoleFill f = mas::fill_holes(part, Vector3d::UnitZ(), 8.0, 45.0);
    EXPECT_TRUE(f.notes.empty()) << f.notes[0];
    ASSERT_EQ(f.holes.size(), 2u);
    for (const mas::FilledHole& h : f.holes) {
        if (std::abs(h.axis.x()) > 0.5) {
            EXPECT_NEAR(h.diameter_mm, 6.0, 1e-9);
            EXPECT_NEAR(h.length_mm, 16.0, 1e-9);
            EXPECT_NEAR((h.centre - Vector3d(8, 18, 11)).norm(), 0.0, 1e-9);
        } else {
            EXPECT_NEAR(h.diameter_mm, 8.0, 1e-9);
            EXPECT_NEAR(h.length_mm, 20.0, 1e-9);
            EXPECT_NEAR((h.centre - Vector3d(18, 10, 14)).norm(), 0.0, 1e-9);
        }
    }
    // Both plugged, the block is whole again: it gained exactly the bores.
    expect_volume(volume(f.solid), 80000.0, 80000.0);
    expect_volume(f.added_volume_mm3, 80000.0 - volume(part), 80000.0);
    // Sliced so, no layer overhangs.
    mas::TessellationParams tp;
    tp.deflection_mm = 0.02;
    const mas::CentroidalAxis axis = mas::centroidal_axis(mas::tessellate(part, tp), {});
    mas::SlicePartParams params;
    params.tessellation = tp;
    params.fill_holes_up_to_mm = 8.0;
    const mas::SlicedPart sliced = mas::slice_part(part, axis, mas::decompose(part, axis), params);
    EXPECT_EQ(sliced.stats.filled_holes, 2);
    for (const mas::Layer& l : sliced.layers)
        EXPECT_LE(l.unsupported_area_mm2, mas::negligible_unsupported_mm2(l.area_mm2));
    // One of them meeting a vertical bore of radius 4 (at x = 20, y = 12, not filled: it has no
    // ceiling) is not plugged, which would stick its cylinder into that bore: OCCT closes it
    // over, that bore's wall extended across its mouth. It adds the X bore's cylinder up to that
    // wall: 20 * 9 pi less the integral over its disc of sqrt(16 - dy^2), with dy = 3 sin(u).
    TopoDS_Shape t = occ_box(0, 0, 0, 40, 40, 40);
    t = cut(t, occ_cylinder({-1, 12, 18}, Vector3d::UnitX(), 3.0, 23.0));
    t = cut(t, occ_cylinder({20, 12, 10}, Vector3d::UnitZ(), 4.0, 31.0));
    const mas::HoleFill g = mas::fill_holes(from_occt(t), Vector3d::UnitZ(), 8.0, 45.0);
    EXPECT_TRUE(g.notes.empty()) << g.notes[0];
    ASSERT_EQ(g.holes.size(), 1u);
    EXPECT_NEAR(g.holes[0].length_mm, 20.0 - std::sqrt(7.0), 1e-9);
    double wall = 0.0;
    constexpr int n = 2000;
    for (int i = 0; i < n; ++i) {
        const double u = -0.5 * kPi + (i + 0.5) * kPi / n, c = 3.0 * std::cos(u);
        wall += 2.0 * c * std::sqrt(16.0 - 9.0 * std::sin(u) * std::sin(u)) * c * kPi / n;
    }
    expect_volume(g.added_volume_mm3, 20.0 * 9.0 * kPi - wall, 64000.0);
}

TEST(Holes, ADrillMustFitAllTheWayIn) {
    // From the face y = 0 of a block [0,40]x[0,20]x[0,40], along Y at x = 20, z = 20: an entry
    // 9.2 mm across and 5 deep, then a chamber 10 mm across 5 deeper. The entry is a hole a drill
    // makes; the chamber is not: a 10 mm drill would widen the entry.
    TopoDS_Shape s = occ_box(0, 0, 0, 40, 20, 40);
    s = cut(s, occ_cylinder({20, -1, 20}, Vector3d::UnitY(), 4.6, 6.0));
    s = cut(s, occ_cylinder({20, 5, 20}, Vector3d::UnitY(), 5.0, 5.0));
    const mas::Shape part = from_occt(s);
    const mas::HoleFill f = mas::fill_holes(part, Vector3d::UnitZ(), 12.0, 45.0);
    ASSERT_EQ(f.holes.size(), 1u);
    EXPECT_NEAR(f.holes[0].diameter_mm, 9.2, 1e-9);
    EXPECT_NEAR(f.holes[0].length_mm, 5.0, 1e-9);
    ASSERT_EQ(f.notes.size(), 1u);
    EXPECT_NE(f.notes[0].find("the hole 10 mm across at (20, 7.5, 20)"), std::string::npos)
        << f.notes[0];
    EXPECT_NE(f.notes[0].find("no drill of its diameter reaches it"), std::string::npos)
        << f.notes[0];
    expect_volume(f.added_volume_mm3, kPi * 4.6 * 4.6 * 5.0, volume(part));
}

TEST(Holes, AGrooveRoundAPostIsNoHole) {
    // A ring groove 10 mm across and 5 deep into the face y = 0, round a post 4 mm across: its
    // outer wall is a concave cylinder all the way round, but a 10 mm drill would take the post.
    TopoDS_Shape s = occ_box(0, 0, 0, 40, 20, 40);
    s = cut(s, occ_cylinder({20, -1, 20}, Vector3d::UnitY(), 5.0, 6.0));
    s = fuse(s, occ_cylinder({20, 0, 20}, Vector3d::UnitY(), 2.0, 5.0));
    const mas::Shape part = from_occt(s);
    const mas::HoleFill f = mas::fill_holes(part, Vector3d::UnitZ(), 12.0, 45.0);
    EXPECT_TRUE(f.holes.empty());
    ASSERT_EQ(f.notes.size(), 1u);
    EXPECT_NE(f.notes[0].find("it holds material"), std::string::npos) << f.notes[0];
    EXPECT_DOUBLE_EQ(volume(f.solid), volume(part));
}

TEST(Holes, AGrooveRoundAHollowBossOrAPinOffTheAxisIsNoHole) {
    // A ring groove 10 mm across and 5 deep into the face y = 0 round a boss 8 mm across with a
    // bore 6 mm across: the groove holds the boss's ring (no drill makes it), the bore is a
    // blind hole a 6 mm drill makes.
    TopoDS_Shape s = occ_box(0, 0, 0, 40, 20, 40);
    s = cut(s, occ_cylinder({20, -1, 20}, Vector3d::UnitY(), 5.0, 6.0));
    s = fuse(s, occ_cylinder({20, 0, 20}, Vector3d::UnitY(), 4.0, 5.0));
    s = cut(s, occ_cylinder({20, -1, 20}, Vector3d::UnitY(), 3.0, 6.0));
    const mas::Shape part = from_occt(s);
    const mas::HoleFill f = mas::fill_holes(part, Vector3d::UnitZ(), 12.0, 45.0);
    ASSERT_EQ(f.holes.size(), 1u);
    EXPECT_NEAR(f.holes[0].diameter_mm, 6.0, 1e-9);
    ASSERT_EQ(f.notes.size(), 1u);
    EXPECT_NE(f.notes[0].find("the hole 10 mm across"), std::string::npos) << f.notes[0];
    EXPECT_NE(f.notes[0].find("it holds material"), std::string::npos) << f.notes[0];
    expect_volume(f.added_volume_mm3, kPi * 9.0 * 5.0, volume(part));
    // A pocket 10 mm across and 5 deep with a pin 1.2 mm across standing in it, 3.7 mm off its
    // axis: no drill makes it either.
    TopoDS_Shape p = occ_box(0, 0, 0, 40, 20, 40);
    p = cut(p, occ_cylinder({20, -1, 20}, Vector3d::UnitY(), 5.0, 6.0));
    p = fuse(p, occ_cylinder({23.7, 0, 20}, Vector3d::UnitY(), 0.6, 5.0));
    const mas::HoleFill g = mas::fill_holes(from_occt(p), Vector3d::UnitZ(), 12.0, 45.0);
    EXPECT_TRUE(g.holes.empty());
    ASSERT_EQ(g.notes.size(), 1u);
    EXPECT_NE(g.notes[0].find("it holds material"), std::string::npos) << g.notes[0];
}

TEST(Holes, AHoleThroughABallIsClosedOverAlongItsCurvedMouths) {
    // A ball 30 mm across with a hole 6 mm across through it along X, 1 mm off its centre: the
    // mouths lie on the sphere, whose face the hole only goes through (no bottom of it), and the
    // faces rebuilt across them bulge past the rims.
    const TopoDS_Shape ball = BRepPrimAPI_MakeSphere(gp_Pnt(0, 0, 0), 15.0).Shape();
    const mas::Shape part =
        from_occt(cut(ball, occ_cylinder({-20, 0, 1}, Vector3d::UnitX(), 3.0, 40.0)));
    const double hole = 4.0 / 3.0 * kPi * 15.0 * 15.0 * 15.0 - volume(part);
    const mas::HoleFill f = mas::fill_holes(part, Vector3d::UnitZ(), 6.0, 45.0);
    ASSERT_EQ(f.holes.size(), 1u) << (f.notes.empty() ? "" : f.notes[0]);
    EXPECT_NEAR(f.holes[0].centre.x(), 0.0, 1e-6);
    EXPECT_NEAR(f.holes[0].centre.z(), 1.0, 1e-6);
    expect_volume(f.added_volume_mm3, hole, volume(part));
}

TEST(Holes, AChannelWithASlotAlongItIsNoHoleEvenWhereARibCrossesIt) {
    // A channel of radius 4 along X through a block [0,40]x[0,20]x[0,20] at y = z = 10, open
    // upwards through a slot 3 mm wide, and a rib x in [18, 22] across both: each stretch of wall
    // goes only part of the way round, together more than once. Filling would close the slot too.
    TopoDS_Shape s = occ_box(0, 0, 0, 40, 20, 20);
    s = cut(s, occ_cylinder({-1, 10, 10}, Vector3d::UnitX(), 4.0, 42.0));
    s = cut(s, occ_box(-1, 8.5, 10, 42, 3, 11));
    s = fuse(s, occ_box(18, 0, 0, 4, 20, 20));
    const mas::Shape part = from_occt(s);
    const mas::HoleFill f = mas::fill_holes(part, Vector3d::UnitZ(), 12.0, 45.0);
    EXPECT_TRUE(f.holes.empty());
    EXPECT_TRUE(f.notes.empty());
    EXPECT_DOUBLE_EQ(volume(f.solid), volume(part));
}

TEST(Holes, CoaxialHolesApartAreTwoHoles) {
    // Two lugs [10,30]x[0,8]x[0,30] and [10,30]x[22,30]x[0,30] on a plate, one pin hole of
    // radius 4 along Y through both at x = 20, z = 20: two holes of 8, not one of 30.
    TopoDS_Shape s = occ_box(0, 0, -5, 40, 30, 5);
    s = fuse(s, occ_box(10, 0, 0, 20, 8, 30));
    s = fuse(s, occ_box(10, 22, 0, 20, 8, 30));
    s = cut(s, occ_cylinder({20, -1, 20}, Vector3d::UnitY(), 4.0, 32.0));
    const mas::Shape part = from_occt(s);
    const mas::HoleFill f = mas::fill_holes(part, Vector3d::UnitZ(), 8.0, 45.0);
    ASSERT_EQ(f.holes.size(), 2u);
    for (const mas::FilledHole& h : f.holes) EXPECT_NEAR(h.length_mm, 8.0, 1e-9);
    EXPECT_NEAR(f.holes[0].centre.y() + f.holes[1].centre.y(), 30.0, 1e-9);
    expect_volume(f.added_volume_mm3, 2.0 * kPi * 16.0 * 8.0, volume(part));
}

TEST(Holes, AConcaveFilletIsNoHole) {
    // An L of two boxes with a fillet of radius 2 in its inside corner along Y: a quarter of a
    // concave cylinder lying across the build direction.
    TopoDS_Shape s = fuse(occ_box(0, 0, 0, 20, 10, 5), occ_box(0, 0, 0, 5, 10, 20));
    s = fuse(s, occ_box(5, 0, 5, 2, 10, 2));
    s = cut(s, occ_cylinder({7, -1, 7}, Vector3d::UnitY(), 2.0, 12.0));
    const mas::Shape part = from_occt(s);
    const mas::HoleFill f = mas::fill_holes(part, Vector3d::UnitZ(), 10.0, 45.0);
    EXPECT_TRUE(f.holes.empty());
    EXPECT_TRUE(f.notes.empty());
    EXPECT_DOUBLE_EQ(volume(f.solid), volume(part));
}

TEST(Holes, ABoreIntoABoreIsFilledHoweverLargeThePartItIsMeasuredIn) {
    // A valve body drawn at random (the survey's, seed 44, 2): a round body with a blind bore down
    // it from z = 4 and three ports, each bored into it. Its upper part, from z = 12.7553 and
    // within the planes that cut its ports off (as an older decomposition left it), holds the
    // +Y port's bore whole: a hole along Y, 9.36 mm across, opening into the central bore, which
    // OCCT's defeaturing closes over by extending that bore's wall across its mouth. That adds
    // nothing outside the hole's cylinder; measured as the difference of the part's volume
    // outside the cylinder after and before (10033 mm^3 each, integrated to about 1e-7 of that),
    // it added 0.0038 mm^3, over the tolerance, and the hole stayed open.
    const TopoDS_Shape whole = mas::test::survey_valve_body_44_2().shape();
    const double x0 = -12.7753, y0 = -12.7817, y1 = 12.7837, z0 = 12.7553;
    BRepAlgoAPI_Common upper(whole, occ_box(x0, y0, z0, 100, y1 - y0, 100));
    ASSERT_TRUE(upper.IsDone());
    const mas::Shape part = from_occt(whole), solid = from_occt(upper.Shape());
    const mas::HoleFill f = mas::fill_holes(solid, Vector3d::UnitZ(), 16.0, 45.0, part);
    int along_y = 0;
    for (const mas::FilledHole& h : f.holes) {
        if (std::abs(std::abs(h.axis.y()) - 1.0) > 1e-9) continue;
        ++along_y;
        EXPECT_NEAR(h.diameter_mm, 9.361050822457926, 1e-6);
        EXPECT_NEAR(h.centre.z(), 18.591670945151595, 1e-6);
    }
    EXPECT_EQ(along_y, 1);
    for (const std::string& note : f.notes)
        EXPECT_EQ(note.find("outside it"), std::string::npos) << note;
    // It added material, no more than the hole's cylinder holds from the body's axis to y1.
    const double r = 9.361050822457926 / 2;
    EXPECT_GT(f.added_volume_mm3, 0.0);
    EXPECT_LT(f.added_volume_mm3, kPi * r * r * y1);
}

TEST(Holes, CancellingStopsTheFill) {
    const mas::Shape part = from_occt(clevis_ear(true, false));
    int calls = 0;
    const mas::Progress cancel([&](double, const std::string&) {
        ++calls;
        throw mas::Error(mas::ErrorCode::Cancelled, "stop");
    });
    try {
        mas::fill_holes(part, Vector3d::UnitZ(), 12.0, 45.0, mas::Shape(), cancel);
        FAIL() << "not cancelled";
    } catch (const mas::Error& e) {
        EXPECT_EQ(e.code(), mas::ErrorCode::Cancelled);
    }
    EXPECT_EQ(calls, 1);
    // With no hole to fill, it is never asked.
    mas::fill_holes(part, Vector3d::UnitZ(), 0.0, 45.0, mas::Shape(), cancel);
    mas::fill_holes(part, Vector3d::UnitY(), 12.0, 45.0, mas::Shape(), cancel);  // along them
    EXPECT_EQ(calls, 1);
}

TEST(Holes, BadArgumentsAreNamed) {
    const mas::Shape part = from_occt(clevis_ear(false, false));
    auto message = [&](double d, double angle, const Vector3d& dir) {
        try {
            mas::fill_holes(part, dir, d, angle);
        } catch (const mas::Error& e) {
            EXPECT_EQ(e.code(), mas::ErrorCode::InvalidArgument);
            return std::string(e.what());
        }
        return std::string("no error");
    };
    EXPECT_NE(message(-1.0, 45.0, Vector3d::UnitZ()).find("diameter"), std::string::npos);
    EXPECT_NE(message(std::nan(""), 45.0, Vector3d::UnitZ()).find("diameter"), std::string::npos);
    EXPECT_NE(message(8.0, 90.0, Vector3d::UnitZ()).find("overhang angle"), std::string::npos);
    EXPECT_NE(message(8.0, 45.0, Vector3d::Zero()).find("build direction"), std::string::npos);
    // 0 fills nothing.
    const mas::HoleFill none = mas::fill_holes(part, Vector3d::UnitZ(), 0.0, 45.0);
    EXPECT_TRUE(none.holes.empty());
    EXPECT_DOUBLE_EQ(volume(none.solid), volume(part));
}

TEST(Holes, AFilledPinHoleLeavesEveryLayerOfTheClevisEarSupported) {
    const mas::Shape part = from_occt(clevis_ear(false, true));
    mas::TessellationParams tp;
    tp.deflection_mm = 0.02;
    const mas::CentroidalAxis axis = mas::centroidal_axis(mas::tessellate(part, tp), {});
    const mas::Decomposition d = mas::decompose(part, axis);
    mas::SlicePartParams params;
    params.tessellation = tp;
    const mas::SlicedPart open = mas::slice_part(part, axis, d, params);
    params.fill_holes_up_to_mm = 8.0;
    const mas::SlicedPart filled = mas::slice_part(part, axis, d, params);
    // Open, the layers across the top of the pin hole overhang its bore.
    EXPECT_GT(open.stats.worst_unsupported_area_mm2, 1.0);
    EXPECT_EQ(open.stats.filled_holes, 0);
    EXPECT_TRUE(open.filled_holes.empty());
    // Filled, none does; the vertical hole in the plate stays.
    for (const mas::Layer& l : filled.layers)
        EXPECT_LE(l.unsupported_area_mm2, mas::negligible_unsupported_mm2(l.area_mm2));
    ASSERT_EQ(filled.filled_holes.size(), 1u);
    EXPECT_EQ(filled.stats.filled_holes, 1);
    const mas::FilledHole& h = filled.filled_holes[0];
    EXPECT_GE(h.component, 0);
    EXPECT_NEAR(h.diameter_mm, 8.0, 1e-9);
    EXPECT_NEAR(h.centre.z(), 20.0, 1e-9);
    const double exact = volume(part);
    expect_volume(filled.stats.filled_volume_mm3, kPi * 16.0 * 8.0, exact);
    EXPECT_DOUBLE_EQ(filled.stats.part_volume_mm3, open.stats.part_volume_mm3);
    // The deposit holds the hole's material: the components' meshes gained it, less what the
    // tessellation's inscribed facets lose on the part's other round faces.
    double open_volume = 0.0, filled_volume = 0.0;
    for (const mas::ComponentLayers& c : open.components) open_volume += c.volume_mm3;
    for (const mas::ComponentLayers& c : filled.components) filled_volume += c.volume_mm3;
    EXPECT_NEAR(filled_volume - open_volume, kPi * 16.0 * 8.0, 2.0 * kPi * 4.0 * 8.0 * 0.02);
}

TEST(Holes, TheHolesToFillAreTheHolesFilledWithNothingChanged) {
    // The ear's pin holes of radius 4 and 6 along Y qualify; the plate's along Z does not.
    const mas::Shape part = from_occt(clevis_ear(true, true));
    const double before = volume(part);
    const std::vector<mas::FilledHole> found =
        mas::holes_to_fill(part, Vector3d::UnitZ(), 16.0, 45.0);
    const mas::HoleFill f = mas::fill_holes(part, Vector3d::UnitZ(), 16.0, 45.0);
    ASSERT_EQ(found.size(), 2u);
    ASSERT_EQ(f.holes.size(), 2u);
    for (const mas::FilledHole& h : found) {
        const auto same = std::find_if(f.holes.begin(), f.holes.end(), [&](const auto& g) {
            return (g.centre - h.centre).norm() < 1e-9 && g.axis.isApprox(h.axis, 1e-12) &&
                   std::abs(g.diameter_mm - h.diameter_mm) < 1e-9 &&
                   std::abs(g.length_mm - h.length_mm) < 1e-9;
        });
        EXPECT_NE(same, f.holes.end()) << h.centre.transpose();
    }
    EXPECT_DOUBLE_EQ(volume(part), before);
    // Up to 10 mm across, the big hole (12) is left out; 0 finds none; bad arguments are named.
    ASSERT_EQ(mas::holes_to_fill(part, Vector3d::UnitZ(), 10.0, 45.0).size(), 1u);
    EXPECT_TRUE(mas::holes_to_fill(part, Vector3d::UnitZ(), 0.0, 45.0).empty());
    EXPECT_THROW(mas::holes_to_fill(part, Vector3d::UnitZ(), -1.0, 45.0), mas::Error);
    EXPECT_THROW(mas::holes_to_fill(part, Vector3d::Zero(), 8.0, 45.0), mas::Error);
}

namespace {

// A clevis of the survey's (seed 59, lug 6): a plate 47.9 x 20.04 x 8.61 with two lugs 17 wide
// and 6.47 thick at y = -+5.01, each rising 18.47 mm into a round top (radius 8.5 round the
// axis along Y at z = 27.09) with a pin hole 8.5 mm across along Y.
TopoDS_Shape survey_clevis() {
    const double width = 47.90498085673977, depth = 20.03944918403345, plate = 8.614288156716757,
                 thickness = 6.472653569636782, height = 18.472378679611452,
                 lug = 16.99162874999689;
    TopoDS_Shape s = occ_box(-width / 2, -depth / 2, 0, width, depth, plate);
    for (const double y : {-depth / 4, depth / 4}) {
        TopoDS_Shape upright =
            fuse(occ_box(-lug / 2, y - thickness / 2, plate, lug, thickness, height),
                 occ_cylinder({0, y - thickness / 2, plate + height}, Vector3d::UnitY(), lug / 2,
                              thickness));
        upright = cut(upright, occ_cylinder({0, y - thickness / 2 - 1, plate + height},
                                            Vector3d::UnitY(), lug / 4, thickness + 2));
        s = fuse(s, upright);
    }
    return s;
}

// Slicing `part` meshed at `deflection` with its holes up to 16 mm filled: its axis, the slicing
// parameters and the decomposition's (no component lower than a layer).
struct FillingHoles {
    mas::CentroidalAxis axis;
    mas::SlicePartParams params;
    mas::DecomposeParams decompose;
};

FillingHoles filling_holes(const mas::Shape& part, double deflection,
                           const mas::AxisParams& axis_params = {}) {
    FillingHoles f;
    f.params.tessellation.deflection_mm = deflection;
    f.params.fill_holes_up_to_mm = 16.0;
    f.axis = mas::centroidal_axis(mas::tessellate(part, f.params.tessellation), axis_params);
    f.decompose.min_component_height_mm = f.params.layers.min_layer_mm;
    return f;
}

}  // namespace

TEST(Holes, ASplitThatWouldCutAPinHoleLengthwiseIsNotMadeWhereTheHoleIsFilled) {
    // At a step of 4.45 mm the axis splits round each pin hole (a track each side), and its
    // planes pass over the lugs' round tops before the tracks meet again. Decomposed as the axis
    // asks, each top is cut off across its hole (z = 26.7, 0.4 mm under its axis): each hole
    // whole in no component, none filled, a top's layer unsupported. Those splits are not made
    // where the holes are filled: each lug is one component, its hole filled, every layer
    // supported. (At the derived step, 3.13 mm, the tracks meet over the holes and each lug is
    // one component anyway. Before a hole's ceiling was kept in the march, CentroidalAxis.hpp,
    // the axis turned sideways over each ceiling there, closing over the hole from each side,
    // and the decomposition cut the tops at z = 25.)
    const mas::Shape part = from_occt(survey_clevis());
    mas::AxisParams ap;
    ap.step_mm = 4.45;
    auto [axis, params, dp] = filling_holes(part, mas::effective_deflection(part, {}), ap);
    // The decomposition the axis asks for cuts the holes.
    const mas::Decomposition asked = mas::decompose(part, axis, dp);
    EXPECT_GT(asked.components.size(), 3u);
    // At the derived step it does not: the plate and the two lugs.
    const FillingHoles derived = filling_holes(part, mas::effective_deflection(part, {}));
    EXPECT_EQ(mas::decompose(part, derived.axis, derived.decompose).components.size(), 3u);
    const mas::SlicedPart cut_open = mas::slice_part(part, axis, asked, params);
    EXPECT_TRUE(cut_open.filled_holes.empty());
    double worst = 0.0;
    for (const mas::Layer& l : cut_open.layers)
        worst =
            std::max(worst, l.unsupported_area_mm2 - mas::negligible_unsupported_mm2(l.area_mm2));
    EXPECT_GT(worst, 1.0);
    // Sliced whole with its holes filled: the plate and the two lugs.
    mas::Decomposition d;
    const mas::SlicedPart sliced = mas::slice_solid_part(part, axis, dp, params, d);
    ASSERT_EQ(d.components.size(), 3u);
    ASSERT_EQ(sliced.filled_holes.size(), 2u);
    EXPECT_NE(sliced.filled_holes[0].component, sliced.filled_holes[1].component);
    for (const mas::FilledHole& h : sliced.filled_holes) {
        EXPECT_NEAR(h.diameter_mm, 16.99162874999689 / 2, 1e-9);
        EXPECT_GT(h.component, 0);
    }
    for (const mas::Layer& l : sliced.layers)
        EXPECT_LE(l.unsupported_area_mm2, mas::negligible_unsupported_mm2(l.area_mm2));
    EXPECT_EQ(sliced.stats.colliding_layers, 0);
    // The notes name the branches kept so, each with its hole.
    int named = 0;
    for (const std::string& note : sliced.notes)
        if (note.find("its split cuts the hole 8.49581 mm across") != std::string::npos) ++named;
    EXPECT_GE(named, 2);
    EXPECT_EQ(int(d.kept_branches.size()), named);
    // Without filling, no split is refused for the holes: the round tops are cut off as the axis
    // asks (a branch whose layers the nozzle could not reach kept, as ever).
    params.fill_holes_up_to_mm = 0.0;
    mas::Decomposition open;
    const mas::SlicedPart unfilled = mas::slice_solid_part(part, axis, dp, params, open);
    EXPECT_GT(open.components.size(), 3u);
    for (const std::string& note : unfilled.notes)
        EXPECT_EQ(note.find("cuts the hole"), std::string::npos) << note;
}

TEST(Holes, ASplitThatWouldCutAnUprightHoleInAnArmBuiltSidewaysIsNotMade) {
    // An L bracket: a column 16.39 mm square and 50.19 tall, an arm 22.61 long along +X at its
    // top (6.67 thick), with three upright holes 6.62 mm across through the arm, the last 0.5 mm
    // from its end. The arm is built along +X, where the upright holes need filling; the axis
    // splits round each hole, and the decomposition it asks for cuts the arm's end off at x =
    // 31.97, 0.05 mm into the last hole (its wall from x = 31.92): that hole is then whole in
    // neither piece and stays open, and the end layer hangs over its far side (13.9 mm^2). The
    // holes a split must not cut were read along +Z, the root's direction, where upright holes
    // need no filling. Now that split is not made: all three holes are filled in the arm, the
    // notes naming the last, and every layer is supported.
    const double w = 16.38530710667973, h = 50.18970504490862, t = 6.673008768610355,
                 length = 22.611465502404414, r = 3.311485285808114;
    TopoDS_Shape s = fuse(occ_box(0, 0, 0, w, w, h), occ_box(0, 0, h - t, w + length, w, t));
    for (int i = 0; i < 3; ++i)
        s = cut(s, occ_cylinder({w + (i + 0.5) * length / 3.0, w / 2.0, h - t - 1.0},
                                Vector3d::UnitZ(), r, t + 2.0));
    const mas::Shape part = from_occt(s);
    const auto [axis, params, dp] = filling_holes(part, mas::effective_deflection(part, {}));
    // Decomposed as the axis asks, the arm's end is a component of its own, cut through the
    // last hole, which neither piece fills.
    const mas::Decomposition asked = mas::decompose(part, axis, dp);
    ASSERT_EQ(asked.components.size(), 3u);
    EXPECT_EQ(mas::slice_part(part, axis, asked, params).filled_holes.size(), 2u);
    mas::Decomposition d;
    const mas::SlicedPart sliced = mas::slice_solid_part(part, axis, dp, params, d);
    ASSERT_EQ(d.components.size(), 2u);  // the column and the arm
    EXPECT_TRUE(d.components[1].build_direction.isApprox(Vector3d::UnitX(), 1e-12));
    ASSERT_EQ(sliced.filled_holes.size(), 3u);
    for (const mas::FilledHole& hole : sliced.filled_holes) {
        EXPECT_EQ(hole.component, 1);
        EXPECT_NEAR(hole.diameter_mm, 2.0 * r, 1e-6);
    }
    int named = 0;
    for (const std::string& note : sliced.notes)
        if (note.find("its split cuts the hole 6.62297 mm across at (35.2282, 8.19265, 46.8532) "
                      "along its length") != std::string::npos)
            ++named;
    EXPECT_GE(named, 1);
    for (const mas::Layer& l : sliced.layers)
        EXPECT_LE(l.unsupported_area_mm2, mas::negligible_unsupported_mm2(l.area_mm2));
}

TEST(Holes, AnArmWhoseSplitCutsAHoleIsStillCutOffWhereKeepingItWouldLeaveMoreUnsupported) {
    // The L-block (a 20 mm column 60 tall, an arm 50 long along +X at its top, z = 40 to 60) with
    // a hole 6 mm across along Y through the arm's root, on the plane x = 20 where the arm is cut
    // off. Kept in the column to keep the hole whole, the arm would be built in the column's
    // layers, its 50 x 20 underside hanging: it is cut off all the same, and the note says why the
    // hole stays open.
    const mas::Shape part =
        from_occt(cut(fuse(occ_box(0, 0, 0, 20, 20, 60), occ_box(20, 0, 40, 50, 20, 20)),
                      occ_cylinder({20, -1, 50}, Vector3d::UnitY(), 3.0, 22.0)));
    const auto [axis, params, dp] = filling_holes(part, 0.02);
    mas::Decomposition d;
    const mas::SlicedPart sliced = mas::slice_solid_part(part, axis, dp, params, d);
    ASSERT_EQ(d.components.size(), 2u);
    EXPECT_TRUE(d.components[1].build_direction.isApprox(Vector3d::UnitX(), 1e-12));
    EXPECT_NEAR(d.components[1].base_origin.x(), 20.0, 1e-9);
    EXPECT_TRUE(d.kept_branches.empty());
    EXPECT_TRUE(sliced.filled_holes.empty());
    EXPECT_LT(sliced.stats.worst_unsupported_area_mm2, 100.0);
    int open = 0;
    for (const std::string& note : sliced.notes)
        if (note.find("its split cuts the hole 6 mm across at (20, 10, 50) along its length, "
                      "which stays open: with every such branch kept in its father") !=
            std::string::npos)
            ++open;
    EXPECT_EQ(open, 1);
}

namespace {

// A survey elbow (seed 2, #4): a flange of radius 19.63, 4 thick; a pipe of radius 10.45 rising
// 29.07 from it, bending 55.53 degrees towards +X round a radius of 23.32, then running 16.28
// straight on. Its bore, of radius 7.63, starts 1 mm above the plate and runs out at the pipe's
// end; `bend_bore` false leaves the riser's and the bend's bore out: the run's is then blind,
// its bottom where the bend ends.
TopoDS_Shape survey_elbow(bool bend_bore) {
    const double r = 10.45165232520106, bend = 23.316967882719084,
                 lean = 55.527644095763534 * kPi / 180.0, rise = 29.06748862107859,
                 run = 16.281793749870346, flange = 19.634641275285023, bore = 7.625218880339685;
    const Vector3d end(bend - bend * std::cos(lean), 0.0, 4.0 + rise + bend * std::sin(lean));
    const Vector3d along(std::sin(lean), 0.0, std::cos(lean));
    const gp_Ax2 frame(gp_Pnt(bend, 0, 4.0 + rise), gp_Dir(0, 1, 0), gp_Dir(-1, 0, 0));
    TopoDS_Shape s = fuse(occ_cylinder({0, 0, 0}, Vector3d::UnitZ(), flange, 4.0),
                          occ_cylinder({0, 0, 4}, Vector3d::UnitZ(), r, rise));
    s = fuse(s, BRepPrimAPI_MakeTorus(frame, bend, r, lean).Shape());
    s = fuse(s, occ_cylinder(end, along, r, run));
    if (bend_bore) {
        s = cut(s, occ_cylinder({0, 0, 3}, Vector3d::UnitZ(), bore, rise + 1.0));
        s = cut(s, BRepPrimAPI_MakeTorus(frame, bend, bore, lean).Shape());
    }
    return cut(s, occ_cylinder(end, along, bore, run + 1.0));
}

}  // namespace

TEST(Holes, ALeaningBoreWhoseBendsBoreGoesOnBelowItStaysOpen) {
    // The run's straight bore leans 55.5 degrees off +Z: a hole to fill, which a drill reaches
    // from the pipe's end. Below it the bend's bore goes on, open (no round hole). Plugged, the
    // run's bore ended in a disc across the bend's bore, square to the run; the layers tilt after
    // the pipe (30 degrees), and over them the disc hung 2.5 to 7.9 mm^2 in each of 12 layers.
    // Now the bore stays open with a note: it is built as the bend's is, every layer supported.
    const mas::Shape elbow = from_occt(survey_elbow(true));
    const mas::HoleFill f = mas::fill_holes(elbow, Vector3d::UnitZ(), 16.0, 45.0);
    EXPECT_TRUE(f.holes.empty());
    EXPECT_DOUBLE_EQ(volume(f.solid), volume(elbow));
    ASSERT_EQ(f.notes.size(), 1u);
    EXPECT_NE(f.notes[0].find("the hole 15.2504 mm across at (16.8307, 0, 56.8978)"),
              std::string::npos)
        << f.notes[0];
    EXPECT_NE(f.notes[0].find("its lower end opens into a bore that goes on past it"),
              std::string::npos)
        << f.notes[0];
    EXPECT_TRUE(mas::holes_to_fill(elbow, Vector3d::UnitZ(), 16.0, 45.0).empty());
    // Where the bore ends there (its bottom a disc where the bend ends), it is a blind hole,
    // filled as before.
    const mas::Shape blind = from_occt(survey_elbow(false));
    const mas::HoleFill g = mas::fill_holes(blind, Vector3d::UnitZ(), 16.0, 45.0);
    ASSERT_EQ(g.holes.size(), 1u) << (g.notes.empty() ? "" : g.notes[0]);
    EXPECT_NEAR(g.holes[0].diameter_mm, 15.250437760679370, 1e-9);
    EXPECT_NEAR(g.holes[0].length_mm, 16.281793749870346, 1e-6);
    EXPECT_EQ(mas::holes_to_fill(blind, Vector3d::UnitZ(), 16.0, 45.0).size(), 1u);
    // A straight bore a split cuts across goes on past its piece's end too, but as the same hole,
    // whose own lower end decides: a block [0,60]x[0,20]x[0,40] bored through along a line leaning
    // 60 degrees through (30, 10, 20), its mouths on the block's sides x = 0 (at z = 2.7) and x =
    // 60 (z = 37.3), and the piece of it above z = 20. Its piece of the bore is filled, as the
    // whole bore is.
    const Vector3d lean(std::sin(kPi / 3.0), 0.0, std::cos(kPi / 3.0));
    const TopoDS_Shape block =
        cut(occ_box(0, 0, 0, 60, 20, 40),
            occ_cylinder(Vector3d(30, 10, 20) - 60.0 * lean, lean, 3.0, 120.0));
    BRepAlgoAPI_Common upper(block, occ_box(-1, -1, 20, 62, 22, 21));
    ASSERT_TRUE(upper.IsDone());
    const mas::Shape whole = from_occt(block), piece = from_occt(upper.Shape());
    EXPECT_EQ(mas::fill_holes(whole, Vector3d::UnitZ(), 16.0, 45.0).holes.size(), 1u);
    const mas::HoleFill p = mas::fill_holes(piece, Vector3d::UnitZ(), 16.0, 45.0, whole);
    ASSERT_EQ(p.holes.size(), 1u) << (p.notes.empty() ? "" : p.notes[0]);
    EXPECT_NEAR(p.holes[0].diameter_mm, 6.0, 1e-9);
    EXPECT_EQ(mas::holes_to_fill(piece, Vector3d::UnitZ(), 16.0, 45.0, whole).size(), 1u);

    const auto [axis, params, dp] = filling_holes(elbow, mas::effective_deflection(elbow, {}));
    mas::Decomposition d;
    const mas::SlicedPart sliced = mas::slice_solid_part(elbow, axis, dp, params, d);
    EXPECT_TRUE(sliced.filled_holes.empty());
    int named = 0;
    for (const std::string& note : sliced.notes)
        if (note.find("opens into a bore that goes on past it") != std::string::npos) ++named;
    EXPECT_EQ(named, 1);
    for (const mas::Layer& l : sliced.layers)
        EXPECT_LE(l.unsupported_area_mm2, mas::negligible_unsupported_mm2(l.area_mm2));
}

TEST(Holes, AMeshCannotHaveItsHolesFilled) {
    const mas::TriangleMesh mesh = mas::test::box_mesh(0, 0, 0, 10, 10, 10);
    const mas::CentroidalAxis axis = mas::centroidal_axis(mesh, {});
    mas::SlicePartParams params;
    params.fill_holes_up_to_mm = 5.0;
    try {
        mas::slice_mesh_part(mesh, axis, params);
        FAIL() << "no error";
    } catch (const mas::Error& e) {
        EXPECT_EQ(e.code(), mas::ErrorCode::InvalidArgument);
        EXPECT_NE(std::string(e.what()).find("BREP"), std::string::npos);
    }
    const mas::Shape part = from_occt(clevis_ear(false, false));
    const mas::CentroidalAxis a = mas::centroidal_axis(mas::tessellate(part, {}), {});
    const mas::Decomposition d = mas::decompose(part, a);
    params.fill_holes_up_to_mm = -2.0;
    EXPECT_THROW(mas::slice_part(part, a, d, params), mas::Error);
}
