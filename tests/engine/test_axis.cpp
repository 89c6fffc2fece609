// Centroidal axis (paper Sec. 3): exact expectations on parts with known axes, invariants over
// every test part, bad input.
#include <gtest/gtest.h>

#include <BRepAlgoAPI_Cut.hxx>
#include <BRepAlgoAPI_Fuse.hxx>
#include <BRepBuilderAPI_MakePolygon.hxx>
#include <BRepFilletAPI_MakeChamfer.hxx>
#include <BRepOffsetAPI_ThruSections.hxx>
#include <BRepPrimAPI_MakeBox.hxx>
#include <BRepPrimAPI_MakeCone.hxx>
#include <BRepPrimAPI_MakeCylinder.hxx>
#include <BRepPrimAPI_MakeSphere.hxx>
#include <BRepTools.hxx>
#include <Eigen/Geometry>
#include <StlAPI_Writer.hxx>
#include <TopExp.hxx>
#include <TopTools_IndexedMapOfShape.hxx>
#include <TopoDS.hxx>
#include <cmath>
#include <fstream>
#include <iomanip>
#include <map>
#include <set>
#include <sstream>

#include "mas/Angles.hpp"
#include "mas/CentroidalAxis.hpp"
#include "mas/Error.hpp"
#include "mas/Shape.hpp"
#include "test_parts.hpp"

using Eigen::Vector3d;
using mas::kPi;

namespace {

constexpr double kDeflection = 0.02;  // mm, for every tessellated test part
constexpr double kGrid = 1e-5;        // mm, the grid polygon Booleans snap to (PolygonBoolean.cpp)

using mas::test::from_occt;
using mas::test::fuse;
using mas::test::occ_box;

// A T: column [0,20]x[0,20]x[0,60] with a crossbar [-30,50]x[0,20]x[40,60] reaching both ways.
mas::Shape t_block() {
    return from_occt(fuse(occ_box(0, 0, 0, 20, 20, 60), occ_box(-30, 0, 40, 80, 20, 20)));
}

// A block [0,40]x[0,20]x[0,10] carrying a cylinder along X (radius 8, axis y = 10, z = 16, sunk
// 2 mm into the block) that reaches 30 mm past the block on both sides, x in [-30, 70].
TopoDS_Shape occ_cylinder_on_block() {
    const TopoDS_Shape cyl =
        BRepPrimAPI_MakeCylinder(gp_Ax2(gp_Pnt(-30, 10, 16), gp_Dir(1, 0, 0)), 8, 100).Shape();
    return fuse(occ_box(0, 0, 0, 40, 20, 10), cyl);
}

mas::TriangleMesh mesh_of(const mas::Shape& s, double deflection = kDeflection) {
    mas::TessellationParams p;
    p.deflection_mm = deflection;
    return mas::tessellate(s, p);
}

// Ray parity along a direction no test part's edges line up with.
bool inside(const mas::TriangleMesh& m, const Vector3d& p) {
    const Vector3d dir = Vector3d(1.0, 0.000123, 0.000457).normalized();
    int hits = 0;
    for (const auto& t : m.triangles) {
        const Vector3d a = m.vertices[t[0]], b = m.vertices[t[1]], c = m.vertices[t[2]];
        const Vector3d e1 = b - a, e2 = c - a, h = dir.cross(e2);
        const double det = e1.dot(h);
        if (std::abs(det) < 1e-14) continue;
        const Vector3d s = p - a;
        const double u = s.dot(h) / det;
        if (u < 0 || u > 1) continue;
        const Vector3d q = s.cross(e1);
        const double v = dir.dot(q) / det;
        if (v < 0 || u + v > 1) continue;
        if (e2.dot(q) / det > 0) ++hits;
    }
    return hits % 2 == 1;
}

// Branches that are children of `parent`, by direction.
std::vector<int> children(const mas::CentroidalAxis& a, int parent) {
    std::vector<int> out;
    for (std::size_t b = 0; b < a.branches.size(); ++b)
        if (a.branches[b].parent == parent) out.push_back(int(b));
    return out;
}

// Every axis must satisfy these, whatever the part.
void expect_invariants(const mas::CentroidalAxis& a, const mas::TriangleMesh& mesh,
                       bool centroids_inside = true) {
    ASSERT_FALSE(a.nodes.empty());
    // The branch structure is a forest rooted at the base (and where material the march from the
    // base cannot reach begins): parents come first, nodes belong to exactly the branch that lists
    // them.
    for (std::size_t b = 0; b < a.branches.size(); ++b) {
        const auto& br = a.branches[b];
        EXPECT_LT(br.parent, int(b));
        EXPECT_FALSE(br.nodes.empty());
        for (int n : br.nodes) EXPECT_EQ(a.nodes[std::size_t(n)].branch, int(b));
        if (br.parent < 0) {
            EXPECT_EQ(br.first_link, -1);
            // On a grid plane: the first at eps above the base, or a later one where the part
            // stands on a vertex or an edge and the sections below are a hair wide.
            const double k = (a.nodes[std::size_t(br.nodes.front())].offset -
                              (a.params.base_z_mm + a.params.eps_mm)) /
                             a.params.step_mm;
            EXPECT_NEAR(k, std::round(k), 1e-9);
            EXPECT_GE(k, -1e-9);
        } else {
            ASSERT_GE(br.first_link, 0);
            const auto& l = a.links[std::size_t(br.first_link)];
            EXPECT_EQ(l.end, br.nodes.front());
            EXPECT_EQ(a.nodes[std::size_t(l.start)].branch, br.parent);  // tied to its father
        }
    }
    // Each node but a root's first has exactly one incoming link; step links join nodes one step
    // apart along their march.
    std::map<int, int> incoming;
    for (const auto& l : a.links) {
        ++incoming[l.end];
        const auto& s = a.nodes[std::size_t(l.start)];
        const auto& e = a.nodes[std::size_t(l.end)];
        if (l.kind == mas::AxisLink::Kind::Step) {
            EXPECT_TRUE(s.normal.isApprox(e.normal));
            EXPECT_NEAR(e.offset - s.offset, a.params.step_mm, 1e-9);
        }
    }
    for (std::size_t n = 0; n < a.nodes.size(); ++n) {
        const bool root_start = a.branches[std::size_t(a.nodes[n].branch)].parent < 0 &&
                                a.branches[std::size_t(a.nodes[n].branch)].nodes.front() == int(n);
        EXPECT_EQ(incoming[int(n)], root_start ? 0 : 1) << "node " << n;
        // A node's slab starts on its plane, but for a march's first node: a root's at the base
        // plane, a turned branch's at Eq. 4's T, no more than a step (and eps) before its plane.
        const auto& node = a.nodes[n];
        const auto& branch = a.branches[std::size_t(node.branch)];
        const bool turned_start =
            branch.nodes.front() == int(n) && branch.parent >= 0 &&
            a.links[std::size_t(branch.first_link)].kind == mas::AxisLink::Kind::Connecting;
        if (root_start) {
            // From the base; or, material the march from the base cannot reach (hanging under a
            // bridge), from the grid plane below the one where it begins.
            if (node.slab_start != a.params.base_z_mm) {
                EXPECT_NEAR(node.slab_start, node.offset - a.params.step_mm, 1e-9) << "node " << n;
            }
        } else if (turned_start) {
            EXPECT_LE(node.slab_start, node.offset - a.params.eps_mm + 1e-9) << "node " << n;
            EXPECT_GE(node.slab_start, node.offset - a.params.eps_mm - a.params.step_mm - 1e-9)
                << "node " << n;
        } else {
            EXPECT_EQ(node.slab_start, node.offset) << "node " << n;
        }
        if (centroids_inside) {
            EXPECT_TRUE(inside(mesh, a.nodes[n].position))
                << "node " << n << " at " << a.nodes[n].position.transpose();
        }
    }
    // No region searched twice, none missed: the swept slabs fill the part's volume. Slabs use the
    // section at their lower plane, so each one is off by at most |A_next - A| x step / 2... x 2
    // bounded below by the change to the next node; sections are exact up to the deflection.
    double slab_error = 0.0;
    for (const auto& l : a.links)
        if (l.kind == mas::AxisLink::Kind::Step)
            slab_error +=
                std::abs(a.nodes[std::size_t(l.end)].area - a.nodes[std::size_t(l.start)].area) *
                a.params.step_mm;
    // A root starting above its first grid plane sweeps from the base with its first section:
    // off by at most that slab's whole volume.
    for (const auto& br : a.branches) {
        const auto& first = a.nodes[std::size_t(br.nodes.front())];
        if (br.parent < 0 && first.offset > a.params.base_z_mm + a.params.eps_mm + 1e-9)
            slab_error += first.area * first.thickness;
    }
    const double volume = mas::check_mesh(mesh).volume_mm3;
    EXPECT_NEAR(a.searched_volume_mm3, volume, slab_error + 1e-6 * volume);
}

// Whether `a` is the root and one branch turned off it along the unit `direction`.
::testing::AssertionResult turns_once(const mas::CentroidalAxis& a, const Vector3d& direction) {
    if (a.branches.size() != 2u)
        return ::testing::AssertionFailure() << a.branches.size() << " branches, not 2";
    const auto& b = a.branches[1];
    if (b.parent != 0) return ::testing::AssertionFailure() << "branch 1's parent is " << b.parent;
    if (!b.direction.isApprox(direction, 1e-12))
        return ::testing::AssertionFailure() << "branch 1 goes along " << b.direction.transpose()
                                             << ", not " << direction.transpose();
    return ::testing::AssertionSuccess();
}

// One branch up +Z of `count` nodes on the vertical through (x, y): on the planes at eps (0.001
// mm) and every step above it, each of section area `area` (within `area_tolerance`).
void expect_one_vertical_branch(const mas::CentroidalAxis& a, double x, double y, double step,
                                std::size_t count, double area, double area_tolerance) {
    ASSERT_EQ(a.branches.size(), 1u);
    EXPECT_TRUE(a.branches[0].direction.isApprox(Vector3d::UnitZ()));
    ASSERT_EQ(a.nodes.size(), count);
    for (std::size_t i = 0; i < a.nodes.size(); ++i) {
        EXPECT_NEAR((a.nodes[i].position - Vector3d(x, y, 0.001 + step * double(i))).norm(), 0.0,
                    1e-9);
        EXPECT_NEAR(a.nodes[i].area, area, area_tolerance);
    }
}

}  // namespace

TEST(CentroidalAxis, BoxIsOneVerticalBranchThroughItsCentre) {
    const auto mesh = mas::test::box_mesh(0, 0, 0, 10, 20, 30);
    mas::AxisParams p;
    p.step_mm = 2.0;
    const auto a = mas::centroidal_axis(mesh, p);
    // Planes at 0.001, 2.001, ..., 28.001.
    expect_one_vertical_branch(a, 5, 10, 2.0, 15, 200.0, 1e-9);
    EXPECT_EQ(a.links.size(), 14u);
    for (const auto& l : a.links) EXPECT_FALSE(l.is_break);
    EXPECT_NEAR(a.searched_volume_mm3, 6000.0, 1e-9);
    expect_invariants(a, mesh);
}

TEST(CentroidalAxis, CubeStandingOnAVertexIsSearchedFromItsFirstRealSection) {
    // A 10 mm cube on its corner, its main diagonal vertical. eps above the corner its section is
    // a triangle a few microns wide, which the section a step above outgrows on every side by far
    // more than Eq. 3's d (a sixth of the speck's size): the march used to end there, with one
    // node and the cube unsearched.
    auto mesh = mas::test::box_mesh(0, 0, 0, 10, 10, 10);
    const Eigen::Quaterniond turn =
        Eigen::Quaterniond::FromTwoVectors(Vector3d(1, 1, 1).normalized(), Vector3d::UnitZ());
    for (auto& v : mesh.vertices) v = turn * v;
    const auto a = mas::centroidal_axis(mesh);
    ASSERT_EQ(a.branches.size(), 1u);
    const double height = 10.0 * std::sqrt(3.0);
    EXPECT_EQ(a.nodes.size(),
              std::size_t(std::ceil((height - a.params.eps_mm) / a.params.step_mm - 1e-9)) - 1);
    EXPECT_GT(a.nodes.front().offset, a.params.eps_mm + a.params.step_mm / 2);
    EXPECT_EQ(a.nodes.front().slab_start, 0.0);  // sweeping the corner too
    for (const auto& node : a.nodes) {
        // Three-fold symmetry: on the diagonal. Up to the cube's three nearest corners the
        // sections are equilateral triangles, x + y + z = h sqrt(3): area (3 sqrt(3) / 2) h^2.
        EXPECT_NEAR(node.position.head<2>().norm(), 0.0, 1e-9) << node.position.transpose();
        if (node.offset < height / 3.0) {
            EXPECT_NEAR(node.area, 1.5 * std::sqrt(3.0) * node.offset * node.offset,
                        1e-9 * node.area);
        }
    }
    expect_invariants(a, mesh);
}

TEST(CentroidalAxis, AThinPinIsNoSpeck) {
    // A 0.3 mm pin 20 mm tall at a 1 mm step: a node per plane from eps up, not one slab.
    const auto mesh = mas::test::box_mesh(0, 0, 0, 0.3, 0.3, 20);
    mas::AxisParams p;
    p.step_mm = 1.0;
    const auto a = mas::centroidal_axis(mesh, p);
    ASSERT_EQ(a.nodes.size(), 20u);
    EXPECT_NEAR(a.nodes.front().offset, 0.001, 1e-12);
    expect_invariants(a, mesh);
}

TEST(CentroidalAxis, APinThinnerThanATwentiethOfTheStepAllTheWayUpIsMarchedFromItsBase) {
    // Every section of a 0.01 mm pin at a 1 mm step is a speck: the root used to skip them all to
    // the last plane, one node at the top whose slab stood for the whole pin.
    const auto mesh = mas::test::box_mesh(0, 0, 0, 0.01, 0.01, 20);
    mas::AxisParams p;
    p.step_mm = 1.0;
    const auto a = mas::centroidal_axis(mesh, p);
    // Planes at 0.001, 1.001, ..., 19.001.
    expect_one_vertical_branch(a, 0.005, 0.005, 1.0, 20, 1e-4, 1e-12);
    expect_invariants(a, mesh);
}

TEST(CentroidalAxis, ALeaningPinThinnerThanATwentiethOfTheStepIsOneNodeOverItsWholeHeight) {
    // The same pin leaning 0.3 mm sideways per mm of height: its sections a step apart do not
    // meet, and a march from its first would end at the second, most of the pin unsearched (the
    // decomposition then refused the axis as another part's). One node on the last plane, its slab
    // reaching down to the base, stands for it, as before upright pins were marched.
    auto mesh = mas::test::box_mesh(0, 0, 0, 0.01, 0.01, 20);
    for (auto& v : mesh.vertices) v.x() += 0.3 * v.z();
    mas::AxisParams p;
    p.step_mm = 1.0;
    const auto a = mas::centroidal_axis(mesh, p);
    ASSERT_EQ(a.nodes.size(), 1u);
    EXPECT_NEAR(a.nodes[0].offset, 19.001, 1e-12);
    EXPECT_EQ(a.nodes[0].slab_start, 0.0);
    EXPECT_NEAR(a.searched_volume_mm3, 0.002, 1e-12);
    expect_invariants(a, mesh);
    // Beside an upright pin too: the march would take the upright one and lose the leaning one.
    auto pins = mas::test::box_mesh(-5, 0, 0, 0.01, 0.01, 20);
    const int upright = int(pins.vertices.size());
    pins.vertices.insert(pins.vertices.end(), mesh.vertices.begin(), mesh.vertices.end());
    for (const auto& t : mesh.triangles)
        pins.triangles.push_back(t + Eigen::Vector3i::Constant(upright));
    const auto b = mas::centroidal_axis(pins, p);
    ASSERT_EQ(b.nodes.size(), 2u);
    for (const auto& node : b.nodes) {
        EXPECT_NEAR(node.offset, 19.001, 1e-12);
        EXPECT_EQ(node.slab_start, 0.0);
    }
    EXPECT_NEAR(b.searched_volume_mm3, 0.004, 1e-12);
    expect_invariants(b, pins);
}

TEST(CentroidalAxis, ARodLeaningOnTheRimOfItsEndIsOneBranchUpItsLength) {
    // A round rod 100 mm long leaning sideways stands on a point of its end's rim: eps above the
    // base its section is a sliver, which a step up the section has outgrown to one side. That
    // read as the rod turning, and the marches across it took the rod's length in their first
    // sections. Leaning 0.3 mm a mm (17 degrees), 1 mm across: a -X branch at its foot and +-Y
    // ones at its middle; 4 mm across, the same, the march from the base one node. Leaning 0.1 mm
    // a mm, 6 mm across: the march ended there, two thirds of the rod unsearched (the
    // decomposition refused the axis as another part's). The root starts at the next plane, its
    // slab reaching down to the base, and marches up the rod.
    for (const auto& [radius, lean] : {std::pair{0.5, 0.3}, {2.0, 0.3}, {3.0, 0.1}}) {
        SCOPED_TRACE(radius);
        const Vector3d axis = Vector3d(lean, 0.0, 1.0).normalized();
        const auto mesh = mesh_of(mas::test::cylinder({0, 0, 0}, axis, radius, 100.0));
        const auto a = mas::centroidal_axis(mesh);
        ASSERT_EQ(a.branches.size(), 1u);
        EXPECT_TRUE(a.branches[0].direction.isApprox(Vector3d::UnitZ()));
        const auto& first = a.nodes[std::size_t(a.branches[0].nodes.front())];
        EXPECT_NEAR(first.offset, a.params.base_z_mm + a.params.eps_mm + a.params.step_mm, 1e-9);
        EXPECT_EQ(first.slab_start, a.params.base_z_mm);
        // Between the ends' rims (each rising radius x the sine of the lean either side of the
        // end's centre) a section is a whole ellipse, centred on the rod's axis.
        const double rim = radius * std::sqrt(1.0 - axis.z() * axis.z());
        std::size_t whole = 0;
        for (const auto& node : a.nodes) {
            if (node.offset < rim || node.offset > 100.0 * axis.z() - rim) continue;
            ++whole;
            EXPECT_NEAR((node.position - node.offset / axis.z() * axis).norm(), 0.0, kDeflection)
                << node.position.transpose();
        }
        EXPECT_GE(double(whole), (100.0 * axis.z() - 2.0 * rim) / a.params.step_mm - 1.0);
        expect_invariants(a, mesh);
    }
}

TEST(CentroidalAxis, AThinLegOrPadUnderAPartKeepsItsFirstSection) {
    // At a 1 mm step a leg 0.05 x 0.5 mm is narrower than a tenth of the step and less than a step
    // across, as a rim's point is, but it is still there half a step up: the root starts on it,
    // eps above the base, not at the box it carries (whose first slab, reaching down to the base,
    // would stand for the legs: a box on three legs 5 mm tall was one node over them, searched
    // twice over; a box on one pad 1 mm tall became one component, its first layer hanging).
    mas::AxisParams p;
    p.step_mm = 1.0;
    const auto pad =
        from_occt(fuse(occ_box(5, 5, 0, 0.05, 0.5, 1.01), occ_box(0, 0, 1, 10, 10, 10)));
    TopoDS_Shape legs = occ_box(0, 0, 5, 10, 10, 5);
    for (const auto& [x, y] : {std::pair{1.0, 1.0}, {8.0, 1.0}, {5.0, 8.0}})
        legs = fuse(legs, occ_box(x, y, 0, 0.05, 0.5, 5.01));
    for (const auto& [part, feet] : {std::pair{pad, 1}, {from_occt(legs), 3}}) {
        const auto mesh = mesh_of(part);
        const auto a = mas::centroidal_axis(mesh, p);
        int on_feet = 0;
        for (const auto& b : a.branches) {
            if (b.parent >= 0) continue;
            const auto& first = a.nodes[std::size_t(b.nodes.front())];
            EXPECT_NEAR(first.offset, 0.001, 1e-12);
            EXPECT_NEAR(first.area, 0.025, 1e-6);
            ++on_feet;
        }
        EXPECT_EQ(on_feet, feet);
        expect_invariants(a, mesh);
    }
}

TEST(CentroidalAxis, AWedgeStandingOnItsKnifeEdgeIsMarchedUpFromIt) {
    // A wedge 20 mm long and 20 tall, its faces 5 degrees off the vertical, standing on its edge:
    // eps above the base its section is a strip 0.00017 mm wide, which the march reads as
    // overlapping nothing above it (a hairline): the axis was one node, the wedge unsearched, and
    // it was not sliced. At 5.8 degrees the strip lies at the march's limit, either side of it as
    // the Booleans round (so it stayed one node where the speck was taken at the limit itself);
    // 11 degrees is near the speck's. The root starts a step up, its slab reaching down to the
    // base. Sections are rectangles across the wedge, centred over the edge's middle.
    for (const double degrees : {5.0, 5.8, 11.0}) {
        SCOPED_TRACE(degrees);
        const double half = 20.0 * std::tan(degrees * kPi / 180.0);
        const auto mesh = mesh_of(from_occt(
            mas::test::occ_prism({{0, 0, 0}, {half, 0, 20}, {-half, 0, 20}}, {0, 20, 0})));
        const auto a = mas::centroidal_axis(mesh);
        ASSERT_EQ(a.branches.size(), 1u);
        const double step = a.params.step_mm;
        const auto planes = std::size_t(std::floor((20.0 - 0.001) / step));  // above plane 0
        ASSERT_EQ(a.nodes.size(), planes);
        EXPECT_EQ(a.nodes[0].slab_start, 0.0);
        for (std::size_t i = 0; i < a.nodes.size(); ++i) {
            const auto& node = a.nodes[i];
            const double z = 0.001 + step * double(i + 1);
            EXPECT_NEAR((node.position - Vector3d(0, 10, z)).norm(), 0.0, kGrid) << "node " << i;
            // 40 mm of outline, each point snapped within a grid unit.
            EXPECT_NEAR(node.area, 40.0 * half / 20.0 * z, 40.0 * kGrid) << "node " << i;
        }
        expect_invariants(a, mesh);
    }
}

TEST(CentroidalAxis, ConeStandingOnItsTipIsSearched) {
    // No section at all eps above the tip (a disc 0.001 mm across is a sliver): the axis used to
    // be empty. Nodes on the cone's axis, areas pi r^2 within perimeter x deflection.
    const auto mesh = mesh_of(from_occt(BRepPrimAPI_MakeCone(0.0, 10.0, 20.0).Shape()));
    const auto a = mas::centroidal_axis(mesh);
    ASSERT_EQ(a.branches.size(), 1u);
    EXPECT_GT(a.nodes.size(), 20u);
    for (const auto& node : a.nodes) {
        const double r = node.offset / 2.0;
        EXPECT_NEAR(node.position.head<2>().norm(), 0.0, kDeflection);
        EXPECT_NEAR(node.area, kPi * r * r, 2.0 * kPi * r * kDeflection);
    }
    expect_invariants(a, mesh);
}

TEST(CentroidalAxis, LBlockRisesThenTurnsIntoTheArm) {
    const auto mesh = mesh_of(mas::test::l_block());
    mas::AxisParams p;
    p.step_mm = 2.5;
    const auto a = mas::centroidal_axis(mesh, p);
    ASSERT_EQ(a.branches.size(), 2u);
    // The column: +Z all the way up, on its centre line, 20 x 20 even beside the arm.
    const auto& column = a.branches[0];
    EXPECT_TRUE(column.direction.isApprox(Vector3d::UnitZ()));
    EXPECT_EQ(column.nodes.size(), 24u);
    for (int n : column.nodes) {
        EXPECT_NEAR(a.nodes[n].position.x(), 10.0, 1e-6);
        EXPECT_NEAR(a.nodes[n].position.y(), 10.0, 1e-6);
        EXPECT_NEAR(a.nodes[n].area, 400.0, 1e-3);
    }
    // The arm: +X from just past the column, on the arm's centre line (y = 10, z = 50).
    const auto& arm = a.branches[1];
    EXPECT_EQ(arm.parent, 0);
    EXPECT_TRUE(arm.direction.isApprox(Vector3d::UnitX()));
    EXPECT_NEAR(a.nodes[arm.nodes.front()].position.x(), 20.001, 1e-9);
    // Its first slab reaches back to the column's face, Eq. 4's T.
    EXPECT_NEAR(a.nodes[arm.nodes.front()].slab_start, 20.0, 1e-9);
    EXPECT_EQ(arm.nodes.size(), 20u);
    for (int n : arm.nodes) {
        EXPECT_NEAR(a.nodes[n].position.y(), 10.0, 1e-6);
        EXPECT_NEAR(a.nodes[n].position.z(), 50.0, 1e-6);
        EXPECT_NEAR(a.nodes[n].area, 400.0, 1e-6);
    }
    // Tied to the column node at the arm's height by a C1 break.
    const auto& tie = a.links[arm.first_link];
    EXPECT_EQ(tie.kind, mas::AxisLink::Kind::Connecting);
    EXPECT_TRUE(tie.is_break);
    // 90 degrees, but for eps: the arm's first plane is 0.001 mm past the column, the column's
    // node 0.001 mm above z = 50.
    EXPECT_NEAR(tie.turn_deg, 90.0 + std::atan2(0.001, 10.001) * 180.0 / kPi, 1e-9);
    EXPECT_NEAR(a.nodes[tie.start].position.z(), 50.001, 1e-9);
    int breaks = 0;
    for (const auto& l : a.links) breaks += l.is_break;
    EXPECT_EQ(breaks, 1);
    expect_invariants(a, mesh);
}

// The mesh's vertices turned by `degrees` about +Z (exactly what the turned part tessellates to).
mas::TriangleMesh turned_mesh(mas::TriangleMesh mesh, double degrees) {
    const Eigen::Matrix3d r = Eigen::AngleAxisd(degrees * kPi / 180.0, Vector3d::UnitZ()).matrix();
    for (auto& v : mesh.vertices) v = r * v;
    return mesh;
}

TEST(CentroidalAxis, TheFrameLinesUpWithThePartsSidesWhenTheyAgreeOnOne) {
    const auto box = mas::test::box_mesh(5, 5, 0, 30, 20, 10);
    // Square to the document's axes: 0 exactly, the paper's frame.
    EXPECT_EQ(mas::derive_axis_frame(box), 0.0);
    // Turned on the plate: the turn, modulo 90 degrees into (-45, 45].
    EXPECT_NEAR(mas::derive_axis_frame(turned_mesh(box, 30.0)), 30.0, 1e-9);
    EXPECT_NEAR(mas::derive_axis_frame(turned_mesh(box, 60.0)), -30.0, 1e-9);
    EXPECT_NEAR(mas::derive_axis_frame(turned_mesh(box, -100.0)), -10.0, 1e-9);
    // Half way between, the votes straddle the ends of (-45, 45]: either end is the one frame.
    EXPECT_NEAR(std::abs(mas::derive_axis_frame(turned_mesh(box, 45.0))), 45.0, 1e-9);
    EXPECT_NEAR(std::abs(mas::derive_axis_frame(turned_mesh(box, -45.0))), 45.0, 1e-9);
    // Under kAxisFrameMinDeg: the document's frame.
    EXPECT_EQ(mas::derive_axis_frame(turned_mesh(box, 0.5)), 0.0);
    EXPECT_NEAR(mas::derive_axis_frame(turned_mesh(box, 1.5)), 1.5, 1e-9);
    // A round part's facets face every way: no frame.
    EXPECT_EQ(mas::derive_axis_frame(mesh_of(mas::test::cylinder({0, 0, 0}, {0, 0, 1}, 10, 30))),
              0.0);
    // Two sets of sides (a wedge tapering 6 degrees either side of X, turned 20 degrees): no one
    // frame lines both up, and either would turn the march off the other.
    const TopoDS_Shape wedge = mas::test::occ_prism({{0, -10, 0},
                                                     {60, -10 + 60 * std::tan(6 * kPi / 180), 0},
                                                     {60, 10 - 60 * std::tan(6 * kPi / 180), 0},
                                                     {0, 10, 0}},
                                                    {0, 0, 30});
    EXPECT_EQ(mas::derive_axis_frame(turned_mesh(mesh_of(from_occt(wedge)), 20.0)), 0.0);
    // A round column with a fin 3 mm out: the fin's sides (a tenth of the weight, with the
    // column's facets facing their way) are the ones that agree. Those facets, anywhere in the 2
    // degrees, pull the mean by less than that (0.16 degrees here).
    const auto finned = mesh_of(
        from_occt(fuse(mas::test::to_occt(mas::test::cylinder({0, 0, 0}, {0, 0, 1}, 10, 30)),
                       occ_box(9, -0.5, 0, 4, 1, 30))));
    EXPECT_NEAR(mas::derive_axis_frame(turned_mesh(finned, 25.0)), 25.0, 2.0);
}

TEST(CentroidalAxis, AnLBlockTurnedOnThePlateGivesTheLBlocksAxisTurned) {
    // The L-block placed 30 degrees round: its arm leaves the column between +X and +Y. The
    // frame is derived from its sides, and the axis is the L-block's, turned.
    mas::AxisParams p;
    p.step_mm = 2.5;
    const auto square = mas::centroidal_axis(mesh_of(mas::test::l_block()), p);
    const auto mesh = mesh_of(mas::test::turned_about_z(mas::test::l_block(), 30.0));
    const auto a = mas::centroidal_axis(mesh, p);
    EXPECT_NEAR(a.params.frame_deg, 30.0, 1e-9);
    EXPECT_EQ(square.params.frame_deg, 0.0);
    const auto expected = mas::turned_about_z(square, 30.0);
    ASSERT_EQ(a.branches.size(), 2u);
    ASSERT_EQ(a.nodes.size(), expected.nodes.size());
    ASSERT_EQ(a.links.size(), expected.links.size());
    const Vector3d along(std::cos(kPi / 6), std::sin(kPi / 6), 0.0);
    EXPECT_TRUE(a.branches[1].direction.isApprox(along, 1e-12)) << a.branches[1].direction;
    EXPECT_TRUE(a.branches[0].direction.isApprox(Vector3d::UnitZ(), 1e-12));
    for (std::size_t i = 0; i < a.nodes.size(); ++i) {
        SCOPED_TRACE("node " + std::to_string(i));
        // Within the tessellations' difference (both within kDeflection of the same faces,
        // which are planar: the same section outlines up to the Booleans' grid).
        EXPECT_NEAR((a.nodes[i].position - expected.nodes[i].position).norm(), 0.0, kGrid);
        EXPECT_NEAR(a.nodes[i].area, expected.nodes[i].area, 1e-3);
        EXPECT_TRUE(a.nodes[i].normal.isApprox(expected.nodes[i].normal, 1e-12));
        EXPECT_NEAR(a.nodes[i].offset, expected.nodes[i].offset, 1e-9);
        EXPECT_EQ(a.nodes[i].branch, expected.nodes[i].branch);
        // The region, in the turned normal's frame, lies round the node's centroid.
        const mas::PlaneFrame frame(a.nodes[i].normal);
        EXPECT_NEAR(mas::area(a.nodes[i].region), a.nodes[i].area, 1e-3);
        EXPECT_NEAR((mas::centroid(a.nodes[i].region) - frame.to_2d(a.nodes[i].position)).norm(),
                    0.0, 1e-6);
    }
    // The arm's nodes lie on its centre line, turned: (x, 10, 50) for x past the column.
    const Eigen::Matrix3d r = Eigen::AngleAxisd(kPi / 6, Vector3d::UnitZ()).matrix();
    for (int n : a.branches[1].nodes) {
        const Vector3d back = r.transpose() * a.nodes[std::size_t(n)].position;
        EXPECT_NEAR(back.y(), 10.0, 1e-6);
        EXPECT_NEAR(back.z(), 50.0, 1e-6);
        EXPECT_GT(back.x(), 20.0);
    }
    expect_invariants(a, mesh);

    // In the document's frame (the paper's), no branch marches along the arm: it leaves the
    // column between +X and +Y.
    p.frame_deg = 0.0;
    const auto document = mas::centroidal_axis(mesh, p);
    EXPECT_EQ(document.params.frame_deg, 0.0);
    for (const auto& b : document.branches) EXPECT_FALSE(b.direction.isApprox(along, 1e-3));

    // Turned back, the directions lie on the axes again, exactly.
    const auto back = mas::turned_about_z(a, -30.0);
    EXPECT_EQ(back.branches[1].direction, Vector3d::UnitX());
    EXPECT_NEAR(back.params.frame_deg, 0.0, 1e-12);
    EXPECT_NEAR(mas::axis_frame_deg(a, "test"), 30.0, 1e-9);
    EXPECT_EQ(mas::axis_frame_deg(square, "test"), 0.0);
}

TEST(CentroidalAxis, AnAxisWhoseBranchesAreOfTwoFramesIsNamed) {
    mas::AxisParams p;
    p.step_mm = 2.5;
    auto a = mas::centroidal_axis(mesh_of(mas::test::l_block()), p);
    a.branches[1].direction = Vector3d(std::cos(0.2), std::sin(0.2), 0.0);
    a.branches.push_back(a.branches[1]);
    a.branches.back().direction = Vector3d::UnitY();
    try {
        mas::axis_frame_deg(a, "decompose");
        FAIL() << "no error";
    } catch (const mas::Error& e) {
        EXPECT_EQ(e.code(), mas::ErrorCode::InvalidArgument);
        EXPECT_NE(std::string(e.what()).find("decompose: the axis' branch directions are not those "
                                             "of one frame"),
                  std::string::npos)
            << e.what();
    }
    // A turn given as infinity is refused; one past 45 degrees is read modulo 90.
    p.frame_deg = std::numeric_limits<double>::infinity();
    EXPECT_THROW(mas::centroidal_axis(mesh_of(mas::test::l_block()), p), mas::Error);
    p.frame_deg = 90.0;
    EXPECT_EQ(mas::centroidal_axis(mesh_of(mas::test::l_block()), p).params.frame_deg, 0.0);
}

TEST(CentroidalAxis, TBranchesBothWaysFromOneFatherNode) {
    const auto mesh = mesh_of(t_block());
    mas::AxisParams p;
    p.step_mm = 2.5;
    const auto a = mas::centroidal_axis(mesh, p);
    const auto kids = children(a, 0);
    ASSERT_EQ(kids.size(), 2u);
    std::set<double> xs;
    for (int b : kids) {
        const auto& br = a.branches[b];
        EXPECT_NEAR(std::abs(br.direction.x()), 1.0, 0.0);
        xs.insert(br.direction.x());
        for (int n : br.nodes) {
            EXPECT_NEAR(a.nodes[n].position.y(), 10.0, 1e-6);
            EXPECT_NEAR(a.nodes[n].position.z(), 50.0, 1e-6);
        }
        EXPECT_EQ(br.nodes.size(), 12u);  // 30 mm of arm at 2.5 mm
    }
    EXPECT_EQ(xs, (std::set<double>{-1.0, 1.0}));
    EXPECT_EQ(a.links[a.branches[kids[0]].first_link].start,
              a.links[a.branches[kids[1]].first_link].start);
    expect_invariants(a, mesh);
}

TEST(CentroidalAxis, CylinderOnABlockTurnsIntoPlusAndMinusX) {
    const auto mesh = mesh_of(from_occt(occ_cylinder_on_block()));
    mas::AxisParams p;
    p.step_mm = 1.0;
    const auto a = mas::centroidal_axis(mesh, p);
    const auto kids = children(a, 0);
    ASSERT_EQ(kids.size(), 2u);
    std::set<double> dirs;
    for (int b : kids) {
        const auto& br = a.branches[b];
        dirs.insert(br.direction.x());
        EXPECT_NEAR(br.direction.norm(), 1.0, 0.0);
        // Where the cylinder leaves the block: x = 40 going +X, x = 0 going -X.
        const double start = a.nodes[br.nodes.front()].position.x();
        EXPECT_NEAR(start, br.direction.x() > 0 ? 40.001 : -0.001, 1e-9);
        EXPECT_EQ(br.nodes.size(), 30u);
        // On the cylinder's axis, within the tessellation's deflection.
        for (int n : br.nodes) {
            EXPECT_NEAR(a.nodes[n].position.y(), 10.0, kDeflection);
            EXPECT_NEAR(a.nodes[n].position.z(), 16.0, kDeflection);
        }
    }
    EXPECT_EQ(dirs, (std::set<double>{-1.0, 1.0}));
    // The block's march goes on up through the cylinder's middle, x in [0, 40] (to within the
    // polygon Booleans' 1e-5 mm grid).
    for (int n : a.branches[0].nodes) EXPECT_NEAR(a.nodes[n].position.x(), 20.0, kGrid);
    EXPECT_EQ(a.branches[0].nodes.size(), 24u);  // up to the cylinder's top, z = 24
    expect_invariants(a, mesh);
}

namespace {

// A thick column [0,30]^2 x [0,60] with two square lugs 8 x 8 that stick out 12 mm: along +X at
// z in [16,24] and along -X at z in [36,44], both at y in [11,19]. With a 4 mm step, the first
// plane through a lug finds it centred 6 mm outside the column: within twice the step, beyond a
// sixth of the column's 30 mm size.
mas::Shape column_with_short_lugs() {
    return from_occt(fuse(fuse(occ_box(0, 0, 0, 30, 30, 60), occ_box(30, 11, 16, 12, 8, 8)),
                          occ_box(-12, 11, 36, 12, 8, 8)));
}

}  // namespace

TEST(CentroidalAxis, ShortLugsOnAThickColumnBranchAtTheDerivedThreshold) {
    const auto mesh = mesh_of(column_with_short_lugs());
    mas::AxisParams p;
    p.step_mm = 4.0;  // the distance threshold is derived: 8 mm, at most 30 / 6 = 5 mm here
    const auto a = mas::centroidal_axis(mesh, p);
    EXPECT_EQ(a.params.distance_threshold_mm, 8.0);
    ASSERT_EQ(a.branches.size(), 3u);
    std::set<double> dirs;
    for (int b : children(a, 0)) {
        const auto& br = a.branches[std::size_t(b)];
        const double dir = br.direction.x();
        ASSERT_TRUE(br.direction.isApprox(Vector3d(dir, 0, 0))) << br.direction.transpose();
        dirs.insert(dir);
        // From the column's face (x = 30 or x = 0), on the lug's centre line, 8 x 8 throughout.
        EXPECT_NEAR(a.nodes[std::size_t(br.nodes.front())].slab_start, dir > 0 ? 30.0 : -0.0, 1e-9);
        for (int n : br.nodes) {
            EXPECT_NEAR(a.nodes[std::size_t(n)].position.y(), 15.0, 1e-6);
            EXPECT_NEAR(a.nodes[std::size_t(n)].position.z(), dir > 0 ? 20.0 : 40.0, 1e-6);
            EXPECT_NEAR(a.nodes[std::size_t(n)].area, 64.0, 1e-6);
        }
    }
    EXPECT_EQ(dirs, (std::set<double>{-1.0, 1.0}));
    expect_invariants(a, mesh);
    // A threshold given is used as given: at 8 mm the lugs are no branches.
    p.distance_threshold_mm = 8.0;
    const auto given = mas::centroidal_axis(mesh, p);
    EXPECT_EQ(given.branches.size(), 1u);
    expect_invariants(given, mesh);
}

TEST(CentroidalAxis, ALugCentredWithinTheThresholdTurnsForItsFlatUnderside) {
    // The column above with a lug sticking out 9 mm instead of 12: [30,39]x[11,19]x[16,24]. With
    // a 4 mm step the derived d is min(8, 30 / 6) = 5 mm (CentroidalAxis.hpp, Eq. 3); the lug's
    // section on z = 16.001 is centred 4.5 mm outside the column, within d. But it appears at
    // once (nothing of it on z = 12.001 nor half a step up, on z = 14.001) and reaches 9 mm past
    // the column, more than a step and than the bump distance (an eighth of the size, 3.75 mm):
    // a ledge, whose underside the march could not lay. It turns +X from the column's face
    // (Eq. 4's T, x = 30), its sections on x = 32.001 and 36.001 (the +X grid's planes past T):
    // 8 x 8, on the lug's centre line. The column keeps its 30 x 30 sections, the lug swept
    // from them.
    const auto mesh =
        mesh_of(from_occt(fuse(occ_box(0, 0, 0, 30, 30, 60), occ_box(30, 11, 16, 9, 8, 8))));
    mas::AxisParams p;
    p.step_mm = 4.0;
    const auto a = mas::centroidal_axis(mesh, p);
    EXPECT_EQ(a.params.distance_threshold_mm, 8.0);
    ASSERT_EQ(a.branches.size(), 2u);
    ASSERT_EQ(a.branches[0].nodes.size(), 15u);  // z = 0.001 ... 56.001
    for (int n : a.branches[0].nodes) {
        const auto& node = a.nodes[std::size_t(n)];
        EXPECT_NEAR(node.area, 900.0, 1e-6) << "z = " << node.offset;
        EXPECT_NEAR(node.position.x(), 15.0, kGrid) << "z = " << node.offset;
        EXPECT_NEAR(node.position.y(), 15.0, kGrid);
    }
    const auto& lug = a.branches[1];
    EXPECT_EQ(lug.parent, 0);
    EXPECT_TRUE(lug.direction.isApprox(Vector3d::UnitX(), 1e-12)) << lug.direction.transpose();
    ASSERT_EQ(lug.nodes.size(), 2u);
    EXPECT_NEAR(a.nodes[std::size_t(lug.nodes.front())].slab_start, 30.0, 1e-9);
    for (std::size_t i = 0; i < 2; ++i) {
        const auto& node = a.nodes[std::size_t(lug.nodes[i])];
        EXPECT_NEAR(node.offset, 32.001 + 4.0 * double(i), 1e-9);
        EXPECT_NEAR(node.area, 64.0, 1e-6);
        EXPECT_NEAR(node.position.y(), 15.0, kGrid);
        EXPECT_NEAR(node.position.z(), 20.0, kGrid);
    }
    expect_invariants(a, mesh);

    // A threshold given is used as given, ledges and all (Eq. 3 alone): at 5 mm the lug is no
    // turn, and the planes through it, z = 16.001 and 20.001, carry column and lug: 900 + 72
    // mm^2, centroid x = (900 x 15 + 72 x 34.5) / 972.
    p.distance_threshold_mm = 5.0;
    const auto given = mas::centroidal_axis(mesh, p);
    ASSERT_EQ(given.branches.size(), 1u);
    ASSERT_EQ(given.nodes.size(), 15u);
    for (const auto& node : given.nodes) {
        const bool in_lug = node.offset > 16.0 && node.offset < 24.0;
        EXPECT_NEAR(node.area, in_lug ? 972.0 : 900.0, 1e-6) << "z = " << node.offset;
        EXPECT_NEAR(node.position.x(), in_lug ? (900.0 * 15.0 + 72.0 * 34.5) / 972.0 : 15.0, kGrid)
            << "z = " << node.offset;
        EXPECT_NEAR(node.position.y(), 15.0, kGrid);
    }
    expect_invariants(given, mesh);
}

TEST(CentroidalAxis, ACollarAllRoundAColumnTurnsEachWayFromTheColumnsFaces) {
    // A column [-10,10]^2 x [0,70] with a collar [-15,15]^2 x [40,50]. With a 4 mm step, the
    // collar's section on z = 40.001 sticks out 5 mm all round, centred on the column's centroid:
    // no turn by Eq. 3 and no way out of it. It appears at once (nothing of it on z = 36.001 nor
    // on 38.001) and reaches past the column by 7.07 mm, more than a step (4) and the bump
    // (2.5 mm), less than wide (4 bumps, 10 mm): a ledge all round, shared out among the
    // column's sides, +X and -X first (their shares 30 mm across, corners and all), then +Y and
    // -Y (20 mm across). Each turns from the column's face (Eq. 4's T, 10 mm out) and has one
    // node, on its grid's plane 13.001 mm out, centred on the collar's mid-height. The column
    // keeps its 20 x 20 sections, the collar swept from them. (It stayed in the column's march,
    // its underside overhanging 5 mm all round.) The same with a bore [-4,4]^2 all through the
    // column (a collar round a pipe): Eq. 2 reads the sections on their external contours, so the
    // collar's centre, in the bore, is centred inside the column, not 4 mm out of its material
    // (where, near by Eq. 3 once shared out, it stayed in the march: 137 mm^2 of a pipe port's end
    // collar overhung in one layer).
    for (const bool bore : {false, true}) {
        SCOPED_TRACE(bore ? "pipe" : "column");
        TopoDS_Shape part =
            fuse(occ_box(-10, -10, 0, 20, 20, 70), occ_box(-15, -15, 40, 30, 30, 10));
        if (bore) part = BRepAlgoAPI_Cut(part, occ_box(-4, -4, -1, 8, 8, 72)).Shape();
        const auto mesh = mesh_of(from_occt(part));
        mas::AxisParams p;
        p.step_mm = 4.0;
        const auto a = mas::centroidal_axis(mesh, p);
        ASSERT_EQ(a.branches.size(), 5u);
        ASSERT_EQ(a.branches[0].nodes.size(), 18u);  // z = 0.001 ... 68.001
        for (int n : a.branches[0].nodes) {
            const auto& node = a.nodes[std::size_t(n)];
            EXPECT_NEAR(node.area, bore ? 336.0 : 400.0, 1e-6) << "z = " << node.offset;
            EXPECT_NEAR(node.position.head<2>().norm(), 0.0, kGrid) << "z = " << node.offset;
        }
        const std::vector<Vector3d> sides = {Vector3d::UnitX(), -Vector3d::UnitX(),
                                             Vector3d::UnitY(), -Vector3d::UnitY()};
        for (std::size_t b = 1; b < 5; ++b) {
            SCOPED_TRACE("branch " + std::to_string(b));
            const auto& br = a.branches[b];
            EXPECT_EQ(br.parent, 0);
            EXPECT_TRUE(br.direction.isApprox(sides[b - 1], 1e-12)) << br.direction.transpose();
            ASSERT_EQ(br.nodes.size(), 1u);
            const auto& node = a.nodes[std::size_t(br.nodes.front())];
            EXPECT_NEAR(node.slab_start, 10.0, 1e-9);
            EXPECT_NEAR(node.offset, 13.001, 1e-9);
            EXPECT_NEAR(node.area, b < 3 ? 300.0 : 200.0, 1e-6);
            EXPECT_NEAR((node.position - (13.001 * sides[b - 1] + Vector3d(0, 0, 45))).norm(), 0.0,
                        kGrid)
                << node.position.transpose();
        }
        expect_invariants(a, mesh, !bore);  // a pipe's centroid is in its bore
    }
}

TEST(CentroidalAxis, ACranksWebSharedOutRoundARoundShaftLeavesTheShaftsMarchWhole) {
    // A round shaft (radius 10) to z = 50 with a web z = 40..50 round it: a boss of radius 14,
    // tapering to radius 9 round (50, 0), with a pin (radius 6) on its end. The web turns +X at
    // its first plane and is shared out round the shaft beside that (a ledge's shares: -X, +Y,
    // -Y). What is left of the plane is the boss's disc within the shaft's square [-10,10]^2, and
    // hairlines of the Booleans along the shares' split lines, a micron wide and 50 mm long.
    const double k = 0.1, c = std::sqrt(1.0 - k * k);  // the tangents' normal: (k, +-c)
    TopoDS_Shape part = fuse(mas::test::occ_cylinder({0, 0, 0}, Vector3d::UnitZ(), 10, 50),
                             mas::test::occ_cylinder({0, 0, 40}, Vector3d::UnitZ(), 14, 10));
    part = fuse(part, mas::test::occ_cylinder({50, 0, 40}, Vector3d::UnitZ(), 9, 10));
    part = fuse(part, mas::test::occ_prism({{14 * k, 14 * c, 40},
                                            {50 + 9 * k, 9 * c, 40},
                                            {50 + 9 * k, -9 * c, 40},
                                            {14 * k, -14 * c, 40}},
                                           {0, 0, 10}));
    part = fuse(part, mas::test::occ_cylinder({50, 0, 50}, Vector3d::UnitZ(), 6, 12));
    const auto mesh = mesh_of(from_occt(part));
    const auto a = mas::centroidal_axis(mesh, mas::AxisParams{});
    // The shaft's march goes on whole past the web's first plane to its top; branching off it,
    // the web's four shares, the pin off the +X one. (Kept as regions, the two hairlines split
    // the march in three there, and the decomposition cut the shaft across the web: the same
    // crank drawn in FreeCAD then overhung 1138 mm^2 in the shaft's layers.)
    const std::vector<std::pair<int, Vector3d>> expected = {
        {-1, Vector3d::UnitZ()}, {0, Vector3d::UnitX()}, {1, Vector3d::UnitZ()},
        {0, -Vector3d::UnitX()}, {0, Vector3d::UnitY()}, {0, -Vector3d::UnitY()}};
    ASSERT_EQ(a.branches.size(), expected.size());
    for (std::size_t b = 0; b < expected.size(); ++b) {
        SCOPED_TRACE("branch " + std::to_string(b));
        EXPECT_EQ(a.branches[b].parent, expected[b].first);
        EXPECT_TRUE(a.branches[b].direction.isApprox(expected[b].second, 1e-12));
    }
    const auto& root = a.branches[0].nodes;
    EXPECT_GT(a.nodes[std::size_t(root.back())].offset, 50.0 - a.params.step_mm);
    expect_invariants(a, mesh, true);
}

TEST(CentroidalAxis, AShoulderAllRoundAColumnStaysInItsMarch) {
    // A rod of radius 6 to z = 60 with a collar on z in [30, 40]. At a 1 mm step, a collar of
    // radius 8 reaches past the rod by 2 mm: more than a step and a bump (1.33 mm), less than two
    // bumps, and no more than layers at slicing's defaults lay (2 mm thick, 45 degrees): a
    // shoulder, which the rod's march lays. Of radius 8.5 it reaches 2.5 mm and turns each way.
    // (Cut into four, the 2 mm shoulder gave pieces tapering over the volumetric bound, and the
    // lenses between them left 9 mm^2 unsupported where the rod's layers left 0.1.)
    mas::AxisParams p;
    p.step_mm = 1.0;
    for (const double collar : {8.0, 8.5}) {
        SCOPED_TRACE("collar radius " + std::to_string(collar));
        const auto mesh = mesh_of(
            from_occt(fuse(mas::test::occ_cylinder({0, 0, 0}, Vector3d::UnitZ(), 6, 60),
                           mas::test::occ_cylinder({0, 0, 30}, Vector3d::UnitZ(), collar, 10))));
        const auto a = mas::centroidal_axis(mesh, p);
        EXPECT_EQ(a.branches.size(), collar < 8.2 ? 1u : 5u);
        expect_invariants(a, mesh);
    }
}

TEST(CentroidalAxis, ALugOnASlopingUndersideIsNoLedge) {
    // The lug above with its underside sloping from the column's face at z = 12 to its end at
    // z = 16 (x = 30 + 9 (z - 12) / 4): on z = 16.001 the stick-out is the same 9 x 8 section,
    // centred 4.5 mm out, within the derived d = 5 mm. But it grows over the step: half a step
    // down, on z = 14.001, half of it is there (out to x = 34.5). A side sloping out, however
    // steeply, is no ledge (an organic body's flanks are such, on every plane): the lug stays in
    // the column, one branch, the planes z = 16.001 and 20.001 carrying column and lug.
    const TopoDS_Shape lug =
        mas::test::occ_prism({{30, 11, 12}, {39, 11, 16}, {39, 11, 24}, {30, 11, 24}}, {0, 8, 0});
    const auto mesh = mesh_of(from_occt(fuse(occ_box(0, 0, 0, 30, 30, 60), lug)));
    mas::AxisParams p;
    p.step_mm = 4.0;
    const auto a = mas::centroidal_axis(mesh, p);
    ASSERT_EQ(a.branches.size(), 1u);
    ASSERT_EQ(a.nodes.size(), 15u);
    for (const auto& node : a.nodes) {
        if (node.offset < 16.0 || node.offset > 24.0) continue;
        EXPECT_NEAR(node.area, 972.0, 1e-6) << "z = " << node.offset;
        EXPECT_NEAR(node.position.x(), (900.0 * 15.0 + 72.0 * 34.5) / 972.0, kGrid);
    }
    expect_invariants(a, mesh);
}

TEST(CentroidalAxis, ARoundBossOnAWallTurnsThoughItsUndersideAppearsGradually) {
    // The 30 mm column above with a round boss instead of the lug, faceted as an octagon so that
    // its sections are exact: circumradius 4, a vertex at its lowest line z = 17, axis y = 15,
    // z = 21, along +X from inside the column out to x = 39 (9 mm past its face). With a 4 mm
    // step the first plane through the boss is z = 20.001, 3 mm over its lowest line, where its
    // section (a strip 7.17 mm wide) is centred 4.5 mm outside the column, within the derived
    // d = 5 mm. Half a step down, on z = 18.001, 68 % of that strip is there (4.84 mm wide): the
    // underside appears gradually, no flat ledge. But that narrower strip already reaches the
    // boss' end, 9 mm out, as a flat underside would (a side sloping out reaches about half as
    // far there: the sloping lug above), and the strip's centre is more than a third of that
    // out: a ledge, which turns +X from the column's face. Its sections on x = 32.001 and 36.001
    // are the boss' octagons (2 sqrt(2) r^2), on its axis. (Kept in the column, its first layer
    // hangs.)
    std::vector<Vector3d> octagon;
    for (int i = 0; i < 8; ++i) {
        const double t = (-90.0 + 45.0 * i) * kPi / 180.0;
        octagon.emplace_back(29.0, 15.0 + 4.0 * std::cos(t), 21.0 + 4.0 * std::sin(t));
    }
    const auto mesh = mesh_of(
        from_occt(fuse(occ_box(0, 0, 0, 30, 30, 60), mas::test::occ_prism(octagon, {10, 0, 0}))));
    mas::AxisParams p;
    p.step_mm = 4.0;
    const auto a = mas::centroidal_axis(mesh, p);
    ASSERT_EQ(a.branches.size(), 2u);
    ASSERT_EQ(a.branches[0].nodes.size(), 15u);  // z = 0.001 ... 56.001
    for (int n : a.branches[0].nodes) {
        const auto& node = a.nodes[std::size_t(n)];
        EXPECT_NEAR(node.area, 900.0, 1e-6) << "z = " << node.offset;
        EXPECT_NEAR(node.position.x(), 15.0, kGrid) << "z = " << node.offset;
        EXPECT_NEAR(node.position.y(), 15.0, kGrid) << "z = " << node.offset;
    }
    const auto& boss = a.branches[1];
    EXPECT_EQ(boss.parent, 0);
    EXPECT_TRUE(boss.direction.isApprox(Vector3d::UnitX(), 1e-12)) << boss.direction.transpose();
    ASSERT_EQ(boss.nodes.size(), 2u);
    EXPECT_NEAR(a.nodes[std::size_t(boss.nodes.front())].slab_start, 30.0, 1e-9);
    for (std::size_t i = 0; i < 2; ++i) {
        const auto& node = a.nodes[std::size_t(boss.nodes[i])];
        EXPECT_NEAR(node.offset, 32.001 + 4.0 * double(i), 1e-9);
        EXPECT_NEAR(node.area, 2.0 * std::sqrt(2.0) * 16.0, 1e-6);
        EXPECT_NEAR(node.position.y(), 15.0, kGrid);
        EXPECT_NEAR(node.position.z(), 21.0, kGrid);
    }
    expect_invariants(a, mesh);
}

TEST(CentroidalAxis, AChamferedRoundBossTurnsThoughTheHalfPlaneHoldsItsChamfers) {
    // A manifold block of the survey's (seed 40, 4), 58.8 x 42.7 x 41.2, with its +X boss (radius
    // 5.88, its axis at z = 28.49, sticking out 5.65 mm), every edge chamfered 1 mm. At the step
    // its whole part derives (1.081 mm), the first plane through the boss, z = 22.70, is 0.09 mm
    // over its lowest line; half a step down lie only the chamfers round its root and its end,
    // 15 % of the stick-out (none without them): no more than a quarter of it is "nearly none",
    // as a flat or round underside over the half plane gives. The boss turns +X. (At a tenth, it
    // stayed in the block's layers: 15 mm^2 overhung in one.)
    const double w = 58.76818614554969, d = 42.74319908081503, h = 41.167231600854734;
    const double r = 5.876777609993383, reach = 5.64505685172693, z = 28.48529065076532,
                 along = -2.971411621274493;
    const TopoDS_Shape block =
        fuse(mas::test::occ_box(-w / 2, -d / 2, 0, w, d, h),
             mas::test::occ_cylinder({w / 2 - 1, along, z}, Vector3d::UnitX(), r, reach + 1));
    BRepFilletAPI_MakeChamfer chamfer(block);
    TopTools_IndexedMapOfShape edges;
    TopExp::MapShapes(block, TopAbs_EDGE, edges);
    for (int i = 1; i <= edges.Extent(); ++i) chamfer.Add(1.0, TopoDS::Edge(edges(i)));
    const auto mesh = mesh_of(from_occt(chamfer.Shape()));
    mas::AxisParams p;
    p.step_mm = 1.0808622874318918;
    const auto a = mas::centroidal_axis(mesh, p);
    ASSERT_TRUE(turns_once(a, Vector3d::UnitX()));
    const auto& boss = a.branches[1];
    ASSERT_GE(boss.nodes.size(), 2u);
    for (const int i : boss.nodes) {
        const auto& node = a.nodes[std::size_t(i)];
        EXPECT_GT(node.offset, w / 2);
        EXPECT_NEAR(node.position.y(), along, kDeflection);
        EXPECT_NEAR(node.position.z(), z, kDeflection);
    }
    expect_invariants(a, mesh);
}

TEST(CentroidalAxis, AWideRoundBossOnARoundBodyTurns) {
    // A round body (radius 24) with a boss of radius 12.3 along +Y, its axis at z = 21.3, ending
    // at y = 28.4 (4.4 mm past the body). Step 2.6 mm: the first plane through the boss, z =
    // 10.401, is 1.4 mm over its lowest line; its section there (11.4 mm wide) reaches out of the
    // body's 4.97 mm at its corners, where the body curves away, and is centred 2.3 mm out, within
    // the derived d = 5.2 mm. Half a step down, 0.1 mm over the lowest line, the boss' section is
    // a strip 3.2 mm wide reaching out 4.44 mm: 0.89 of the whole, the corners nearer the body.
    // The boss turns +Y from the body's extent; its sections on y = 25.401 and 28.001 are its
    // discs, on its axis. (Kept in the body's layers, its first layer hangs.)
    const auto mesh = mesh_of(
        from_occt(fuse(mas::test::occ_cylinder({0, 0, 0}, Vector3d::UnitZ(), 24, 45),
                       mas::test::occ_cylinder({0, 20, 21.3}, Vector3d::UnitY(), 12.3, 8.4))));
    mas::AxisParams p;
    p.step_mm = 2.6;
    const auto a = mas::centroidal_axis(mesh, p);
    ASSERT_TRUE(turns_once(a, Vector3d::UnitY()));
    EXPECT_EQ(a.branches[0].nodes.size(), 18u);  // z = 0.001 ... 44.201
    const auto& boss = a.branches[1];
    ASSERT_EQ(boss.nodes.size(), 2u);
    // T is the tessellated body's extent along +Y: the circle's, less at most the deflection.
    const auto& first = a.nodes[std::size_t(boss.nodes.front())];
    EXPECT_LE(first.slab_start, 24.0);
    EXPECT_GE(first.slab_start, 24.0 - kDeflection);
    EXPECT_GT(first.offset, first.slab_start);
    EXPECT_LE(first.offset, first.slab_start + p.eps_mm + p.step_mm);
    // Each section is the boss' disc, short of the circle by at most its perimeter times the
    // deflection and the simplification (step / 100), centred on its axis.
    const double r = 12.3, disc = kPi * r * r;
    for (std::size_t i = 0; i < 2; ++i) {
        const auto& node = a.nodes[std::size_t(boss.nodes[i])];
        EXPECT_NEAR(node.offset, first.offset + p.step_mm * double(i), 1e-9);
        EXPECT_LE(node.area, disc);
        EXPECT_GE(node.area, disc - 2.0 * kPi * r * (kDeflection + p.step_mm / 100.0));
        EXPECT_NEAR(node.position.x(), 0.0, kDeflection);
        EXPECT_NEAR(node.position.z(), 21.3, kDeflection);
    }
    expect_invariants(a, mesh);
}

TEST(CentroidalAxis, ADeepStripOfABossOnARoundBodyTurnsByHowFarItGoesOut) {
    // A valve body of the survey's (seed 54, 4) in round figures: a round body (radius 12.8) with
    // a boss of radius 9.3 along +X, its axis at z = 41, ending at x = 18.5 (5.7 mm past the
    // body). Step 4.46 mm: the first plane through the boss, z = 35.681, is 3.98 mm over its
    // lowest line, where its section is a strip 15.3 mm wide; half a step down, 1.75 mm over
    // that line, the strip is 10.9 mm wide, two thirds of the whole: it appears gradually. That
    // narrower strip reaches the boss' end, as a flat underside would. The whole strip, centred
    // 2.42 mm out of the body, reaches 5.7 mm past it along +X, the way it leaves it, but 7.25
    // mm out at its corners, where the body curves away. Centred a third of 5.7 mm out or more,
    // it turns +X; read by its corners, it stayed in the body's layers, its first layer hanging
    // (20 mm^2 in the survey's part). Its sections are the boss' discs, on its axis.
    const double radius = 12.8, r = 9.3, z = 41.0, end = 18.5;
    const auto mesh = mesh_of(from_occt(
        fuse(mas::test::occ_cylinder({0, 0, 0}, Vector3d::UnitZ(), radius, 60),
             mas::test::occ_cylinder({radius - 3, 0, z}, Vector3d::UnitX(), r, end - radius + 3))));
    mas::AxisParams p;
    p.step_mm = 4.46;
    const auto a = mas::centroidal_axis(mesh, p);
    ASSERT_TRUE(turns_once(a, Vector3d::UnitX()));
    EXPECT_EQ(a.branches[0].nodes.size(), 14u);  // z = 0.001 ... 57.981
    const auto& boss = a.branches[1];
    ASSERT_GE(boss.nodes.size(), 1u);
    // T is the tessellated body's extent along +X: the circle's, less at most the deflection.
    const auto& first = a.nodes[std::size_t(boss.nodes.front())];
    EXPECT_LE(first.slab_start, radius);
    EXPECT_GE(first.slab_start, radius - kDeflection);
    EXPECT_GT(first.offset, first.slab_start);
    EXPECT_LE(first.offset, first.slab_start + p.eps_mm + p.step_mm);
    const double disc = kPi * r * r;
    for (const int i : boss.nodes) {
        const auto& node = a.nodes[std::size_t(i)];
        EXPECT_LT(node.offset, end);
        EXPECT_LE(node.area, disc);
        EXPECT_GE(node.area, disc - 2.0 * kPi * r * (kDeflection + p.step_mm / 100.0));
        EXPECT_NEAR(node.position.y(), 0.0, kDeflection);
        EXPECT_NEAR(node.position.z(), z, kDeflection);
    }
    expect_invariants(a, mesh);
}

TEST(CentroidalAxis, ABossReachingOutLessThanAThickPartsStepTurnsWhereLayersCannotLayIt) {
    // A manifold block of the survey's (seed 64, 7) in round figures: a block 44 x 60 x 53 with a
    // boss along -Y, its axis at x = -3.3, z = 38, sticking out 5.6 mm, faceted as a 16-gon of
    // circumradius 6.9 with a vertex at its lowest line (its sections exact). The block's step is
    // large, 5.8 mm (its other bosses', which set it, left out here): the first plane through the
    // boss, z = 34.801, is 3.7 mm over its lowest line. The boss reaches out less than a step, so
    // it was no ledge, as a side sloping out at 45 degrees over the step would reach a step; but
    // it appears as a round underside does, what of it the half plane holds reaching its end, and
    // reaches far past what layers at slicing's defaults lay (2 mm): its first layer hung (23.8
    // mm^2 in the survey's part). It turns -Y from the block's face; its section is the 16-gon
    // (8 r^2 sin 22.5 degrees), on its axis.
    const double r = 6.9, x = -3.3, z = 38.0, reach = 5.6;
    std::vector<Vector3d> polygon;
    for (int i = 0; i < 16; ++i) {
        const double t = (-90.0 + 22.5 * i) * kPi / 180.0;
        polygon.emplace_back(x + r * std::cos(t), -29.0, z + r * std::sin(t));
    }
    const auto mesh = mesh_of(from_occt(fuse(mas::test::occ_box(-22, -30, 0, 44, 60, 53),
                                             mas::test::occ_prism(polygon, {0, -(reach + 1), 0}))));
    mas::AxisParams p;
    p.step_mm = 5.8;
    const auto a = mas::centroidal_axis(mesh, p);
    ASSERT_TRUE(turns_once(a, -Vector3d::UnitY()));
    const auto& boss = a.branches[1];
    ASSERT_EQ(boss.nodes.size(), 1u);
    const auto& node = a.nodes[std::size_t(boss.nodes.front())];
    EXPECT_NEAR(node.slab_start, 30.0, 1e-9);
    EXPECT_GT(node.offset, 30.0);
    EXPECT_LT(node.offset, 30.0 + reach);
    EXPECT_NEAR(node.area, 8.0 * r * r * std::sin(kPi / 8.0), 1e-6);
    EXPECT_NEAR(node.position.x(), x, kGrid);
    EXPECT_NEAR(node.position.z(), z, kGrid);
    expect_invariants(a, mesh);
}

TEST(CentroidalAxis, AStickOutEndingBeforeTheGridsNextPlaneIsOneNodeOnEq4sPlane) {
    // A block 37 x 36 x 40 with two bosses 3 mm long, faceted as 16-gons of circumradius 5 with
    // a vertex at their lowest lines (their sections exact): along +X at y = 18, z = 12, and
    // along -Y at x = 18.5, z = 19; and an arm on its top reaching 15 mm along +X. Step 5: along
    // +X the grid's planes lie at x = 35.001 and 40.001, so past the block's face, T = 37, the
    // first one lies past the boss's end (the arm's march starts there); along -Y the grid's
    // last plane lies 0.999 mm inside the block, the boss past it. Each boss is a ledge (its
    // first layer would hang), and turns; its march had no plane through it, and its share, taken
    // from the block's march, was swept by none: the bosses stayed in the block, their undersides
    // hanging (13.7 mm^2 in one layer of a survey manifold's, seed 112, 7). Each is one node on
    // Eq. 4's own plane, T + eps: its section the 16-gon, on its axis, its slab from T to the
    // boss's end.
    const double r = 5.0, reach = 3.0;
    std::vector<Vector3d> along_x, along_y;
    for (int i = 0; i < 16; ++i) {
        const double t = (-90.0 + 22.5 * i) * kPi / 180.0;
        along_x.emplace_back(36.0, 18.0 + r * std::cos(t), 12.0 + r * std::sin(t));
        along_y.emplace_back(18.5 + r * std::cos(t), 1.0, 19.0 + r * std::sin(t));
    }
    TopoDS_Shape part = fuse(occ_box(0, 0, 0, 37, 36, 40), occ_box(37, 14, 34, 15, 8, 6));
    part = fuse(part, mas::test::occ_prism(along_x, {reach + 1, 0, 0}));
    part = fuse(part, mas::test::occ_prism(along_y, {0, -(reach + 1), 0}));
    const auto mesh = mesh_of(from_occt(part));
    mas::AxisParams p;
    p.step_mm = 5.0;
    const auto a = mas::centroidal_axis(mesh, p);
    const double polygon = 8.0 * r * r * std::sin(kPi / 8.0);
    const auto boss = [&](const Vector3d& direction) -> const mas::AxisNode* {
        const mas::AxisNode* found = nullptr;
        for (const auto& b : a.branches) {
            if (!b.direction.isApprox(direction, 1e-12) || b.nodes.size() != 1) continue;
            const auto& node = a.nodes[std::size_t(b.nodes.front())];
            if (std::abs(node.area - polygon) > 1e-6) continue;
            EXPECT_EQ(found, nullptr) << "two bosses along " << direction.transpose();
            EXPECT_EQ(b.parent, 0);
            found = &node;
        }
        return found;
    };
    const mas::AxisNode* x = boss(Vector3d::UnitX());
    ASSERT_NE(x, nullptr);
    EXPECT_NEAR(x->slab_start, 37.0, 1e-9);
    EXPECT_NEAR(x->offset, 37.0 + p.eps_mm, 1e-9);
    EXPECT_NEAR(x->position.x(), 37.0 + p.eps_mm, 1e-9);
    EXPECT_NEAR(x->position.y(), 18.0, kGrid);
    EXPECT_NEAR(x->position.z(), 12.0, kGrid);
    EXPECT_NEAR(x->thickness, reach, 1e-9);  // to the boss's end, short of the grid's next plane
    const mas::AxisNode* y = boss(-Vector3d::UnitY());
    ASSERT_NE(y, nullptr);
    EXPECT_NEAR(y->slab_start, 0.0, 1e-9);
    EXPECT_NEAR(y->offset, p.eps_mm, 1e-9);
    EXPECT_NEAR(y->position.y(), -p.eps_mm, 1e-9);
    EXPECT_NEAR(y->position.x(), 18.5, kGrid);
    EXPECT_NEAR(y->position.z(), 19.0, kGrid);
    EXPECT_NEAR(y->thickness, reach, 1e-9);  // to the boss's end, the part's
    // The arm's march along +X, from the block's face, still has its planes.
    bool arm = false;
    for (const auto& b : a.branches)
        arm = arm || (b.direction.isApprox(Vector3d::UnitX(), 1e-12) && b.nodes.size() == 3);
    EXPECT_TRUE(arm);
    expect_invariants(a, mesh);
}

TEST(CentroidalAxis, AShortBossOnARoundBodyIsOneNodeThoughItsCornersLieBehindT) {
    // A round valve body of the survey's (seed 256, 5) in round figures: a body 43.75 tall,
    // faceted as a 32-gon of circumradius 23.68 with a vertex at -Y (its sections exact), with a
    // boss along -Y sticking out 5.12 mm past that vertex, its axis at z = 23.6, faceted as a
    // 16-gon of circumradius 6.91 with a vertex at its lowest line. Step 5.9: the
    // first plane through the boss, z = 17.701, finds it a ledge (its first layer would hang)
    // turning -Y from T, the body's extent; the grid's planes along -Y lie 0.16 mm into the body
    // and past the boss's end, so its march is one node on Eq. 4's plane, T + eps. Between the
    // body's facets and T the boss's corners hold a share of the stick-out (1.3 mm^2 here), which
    // stays with the body's march as it does behind any turn's T; no other side's share turns.
    // Before, the boss was one node only where nothing lay behind T, and stayed in the body's
    // layers, its round underside hanging 16.8 mm^2 in one. Its section is the 16-gon, on its
    // axis, its slab from T to the boss's end.
    const double radius = 23.68, r = 6.914, z = 23.603, reach = 5.118;
    std::vector<Vector3d> body, boss;
    for (int i = 0; i < 32; ++i) {
        const double t = (-90.0 + 11.25 * i) * kPi / 180.0;
        body.emplace_back(radius * std::cos(t), radius * std::sin(t), 0.0);
    }
    for (int i = 0; i < 16; ++i) {
        const double t = (-90.0 + 22.5 * i) * kPi / 180.0;
        boss.emplace_back(r * std::cos(t), -radius + 1.0, z + r * std::sin(t));
    }
    const auto mesh = mesh_of(from_occt(fuse(mas::test::occ_prism(body, {0, 0, 43.75}),
                                             mas::test::occ_prism(boss, {0, -(reach + 1.0), 0}))));
    mas::AxisParams p;
    p.step_mm = 5.9;
    const auto a = mas::centroidal_axis(mesh, p);
    ASSERT_TRUE(turns_once(a, -Vector3d::UnitY()));
    const auto& branch = a.branches[1];
    ASSERT_EQ(branch.nodes.size(), 1u);
    const auto& node = a.nodes[std::size_t(branch.nodes.front())];
    EXPECT_NEAR(node.slab_start, radius, 1e-9);  // T: the body's extent along -Y
    EXPECT_NEAR(node.offset, radius + p.eps_mm, 1e-9);
    EXPECT_NEAR(node.slab_start + node.thickness, radius + reach, 1e-9);  // to the boss's end
    EXPECT_NEAR(node.area, 8.0 * r * r * std::sin(kPi / 8.0), 1e-6);
    EXPECT_NEAR(node.position.x(), 0.0, kGrid);
    EXPECT_NEAR(node.position.z(), z, kGrid);
    expect_invariants(a, mesh);
}
TEST(CentroidalAxis, AWyesLateralsCrescentsBesideTheRiserLeaveItsMarchTheLateralsWhole) {
    // A solid wye fitting of the survey's (seed 293, 7): a riser of radius 8.43, 56.93 tall, with
    // two laterals of radius 5.89, 37.48 long, leaving its axis at z = 22.71 leaning 53.07
    // degrees to +X and -X. Step 2.608 (its part's). The plane at z = 26.08 finds each lateral's
    // root as a crescent beside the riser, reaching less than a step past T (the riser's extent):
    // the grid's next plane along the lateral, past T, cuts none of the crescent's slab. That is
    // no boss ending there: the lateral goes on past that plane, above the crescent's slab. The
    // riser's march finds each lateral again further out and turns there, both laterals alike.
    // (A one-node march took each crescent with a slab to that plane, and one lateral was lost:
    // the march swept 88 % of the part and the axis was refused.)
    const double radius = 8.427064774768324, height = 56.9309477130183, r = 5.8888230996516135,
                 length = 37.48196865948428, z = 22.712999990453923;
    const double lean = 53.07286021113223 * kPi / 180.0;
    TopoDS_Shape s = mas::test::occ_cylinder({0, 0, 0}, Vector3d::UnitZ(), radius, height);
    for (const double side : {1.0, -1.0})
        s = fuse(s, mas::test::occ_cylinder({0, 0, z}, {side * std::sin(lean), 0, std::cos(lean)},
                                            r, length));
    const auto mesh = mesh_of(from_occt(s));
    mas::AxisParams p;
    p.step_mm = 2.60803276817715;
    const auto a = mas::centroidal_axis(mesh, p);
    std::vector<int> laterals;
    for (std::size_t b = 0; b < a.branches.size(); ++b)
        if (a.branches[b].parent >= 0) laterals.push_back(int(b));
    ASSERT_EQ(laterals.size(), 2u);
    const auto& plus = a.branches[std::size_t(laterals[0])];
    const auto& minus = a.branches[std::size_t(laterals[1])];
    const Vector3d dirs[2] = {plus.direction, minus.direction};
    EXPECT_TRUE((dirs[0] == Vector3d::UnitX() && dirs[1] == -Vector3d::UnitX()) ||
                (dirs[0] == -Vector3d::UnitX() && dirs[1] == Vector3d::UnitX()));
    // Each marches its lateral out to its end face, whose farthest point along X is
    // length sin(lean) + r cos(lean) from the axis: 33.5 mm, a step's reach short of it at most.
    const double end = length * std::sin(lean) + r * std::cos(lean);
    for (const auto* b : {&plus, &minus}) {
        EXPECT_GE(b->nodes.size(), 8u);
        const auto& last = a.nodes[std::size_t(b->nodes.back())];
        EXPECT_GT(last.offset, end - p.step_mm);
        EXPECT_LT(last.offset, end);
    }
    EXPECT_EQ(plus.nodes.size(), minus.nodes.size());
    expect_invariants(a, mesh);
}
TEST(CentroidalAxis, APinHolesCeilingIsNoLedgeUnderAThickPartsStep) {
    // A lug of the survey's (seed 39, 6): a plate 45.1 x 29.1 x 8.3, an upright 15.1 wide and 7.7
    // thick rising 33.5 mm into a round top round the axis along Y at z = 41.9, with a pin hole of
    // radius 3.76. Step 3.235 mm (its part's): the tracks round the hole each grow over its
    // ceiling towards the other, reaching out up to 3.2 mm, under a step but past what layers at
    // slicing's defaults lay (2 mm). They lie within the box of the lower plane's whole section,
    // closing over the hole, which the lug's layers bridge: no ledge. (Built sideways from each
    // side of the hole, the ceiling hung 7.2 mm^2, against 6.3 in the lug's layers, at
    // fill_holes 0.) Every branch marches +Z.
    const double width = 45.142389711647276, depth = 29.0543419362087, plate = 8.323501312739785,
                 thickness = 7.713077362882807, height = 33.53678896548037,
                 lug = 15.055709692984657;
    TopoDS_Shape s =
        fuse(fuse(mas::test::occ_box(-width / 2, -depth / 2, 0, width, depth, plate),
                  mas::test::occ_box(-lug / 2, -thickness / 2, plate, lug, thickness, height)),
             mas::test::occ_cylinder({0, -thickness / 2, plate + height}, Vector3d::UnitY(),
                                     lug / 2, thickness));
    BRepAlgoAPI_Cut hole(s, mas::test::occ_cylinder({0, -thickness / 2 - 1, plate + height},
                                                    Vector3d::UnitY(), lug / 4, thickness + 2));
    ASSERT_TRUE(hole.IsDone());
    const auto mesh = mesh_of(from_occt(hole.Shape()));
    mas::AxisParams p;
    p.step_mm = 3.23498939781159;
    const auto a = mas::centroidal_axis(mesh, p);
    ASSERT_GT(a.branches.size(), 1u);  // the tracks round the hole
    for (const auto& b : a.branches)
        EXPECT_TRUE(b.direction.isApprox(Vector3d::UnitZ(), 1e-12)) << b.direction.transpose();
    expect_invariants(a, mesh);
}

TEST(CentroidalAxis, BladesASliverOfTheHubsOutlineJoinsEachTurn) {
    // tests/data/hub_four_blades.brep, a hub of the survey's (seed 65, hub 5): radius 13.5, 23.3
    // tall, with four flat blades 4.78 thick and 12.4 tall reaching 24.1 mm past it, at 1.3,
    // 98.6, 188.4 and 272.5 degrees. At the part's deflection (0.054 mm) and step (3.70 mm), the
    // blades appear together on the plane z = 7.408; the hub's outline there, simplified within a
    // hundredth of the step with the blades on it, differs from the one below, and U - L keeps a
    // sliver along the quarter of it between the blades at 1.3 and 272.5 degrees, which joins
    // them into one stick-out centred near the hub ("along the march"): neither turned, and the
    // hub's layers left 74.6 mm^2 of their undersides hanging. Split at that neck, each blade
    // turns its way. (On a mesh of it 0.02 mm fine, nothing joins them.)
    const mas::Model model = mas::read_model(std::string(MAS_TEST_DATA) + "/hub_four_blades.brep");
    mas::TessellationParams tp;
    tp.deflection_mm = mas::effective_deflection(model.shape, tp);
    EXPECT_NEAR(tp.deflection_mm, 0.0545, 1e-4);
    const auto mesh = mas::tessellate(model.shape, tp);
    const auto a = mas::centroidal_axis(mesh);
    EXPECT_NEAR(a.params.step_mm, 3.7035, 1e-4);
    ASSERT_EQ(a.branches.size(), 5u);
    std::vector<Vector3d> directions;
    for (std::size_t b = 1; b < a.branches.size(); ++b) {
        EXPECT_EQ(a.branches[b].parent, 0);
        directions.push_back(a.branches[b].direction);
    }
    for (const Vector3d& d : std::vector<Vector3d>{Vector3d(1, 0, 0), Vector3d(0, 1, 0),
                                                   Vector3d(-1, 0, 0), Vector3d(0, -1, 0)})
        EXPECT_EQ(std::count_if(directions.begin(), directions.end(),
                                [&](const Vector3d& e) { return e.isApprox(d, 1e-12); }),
                  1)
            << d.transpose();
    // Each blade's first section, past the hub's extent, is the blade's: 4.78 x 12.36 over the
    // cosine of the blade's angle off the march (its faces are flat: exact up to the Booleans'
    // grid along its outline), at the blades' middle height.
    const double t = 4.775833226583146, w = 12.355678089042078;
    for (std::size_t b = 1; b < a.branches.size(); ++b) {
        const Vector3d& d = a.branches[b].direction;
        const double off = d.x() > 0.5    ? 1.2788113058242112
                           : d.y() > 0.5  ? 98.649263806147 - 90.0
                           : d.x() < -0.5 ? 188.39900849153966 - 180.0
                                          : 272.4641643706914 - 270.0;
        const auto& node = a.nodes[std::size_t(a.branches[b].nodes.front())];
        EXPECT_NEAR(node.area, t * w / std::cos(off * kPi / 180.0), 1e-3) << d.transpose();
        EXPECT_NEAR(node.position.z(), 23.331406662934725 / 2, 1e-3);
    }
}

TEST(CentroidalAxis, AShortLugOnAThickBlockTurnsWhereLayersCannotLayIt) {
    // A 60 mm block with a lug [60,66]x[26,34]x[20,28] (flat underside), step 2 mm given. On
    // z = 20.001 the lug appears at once, centred 3 mm out, within the derived d = min(4, 60 / 6)
    // = 4 mm, and reaches 6 mm past the block: less than the bump distance (an eighth of the
    // section's size, 7.5 mm), but three times what layers at slicing's defaults lay (2 mm thick at
    // 45 degrees: 2 mm). Its first layer would hang 4 mm past that: a ledge, turned +X from the
    // block's face, its 8 x 8 sections on its centre line.
    const auto mesh =
        mesh_of(from_occt(fuse(occ_box(0, 0, 0, 60, 60, 60), occ_box(60, 26, 20, 6, 8, 8))));
    mas::AxisParams p;
    p.step_mm = 2.0;
    const auto a = mas::centroidal_axis(mesh, p);
    ASSERT_TRUE(turns_once(a, Vector3d::UnitX()));
    const auto& lug = a.branches[1];
    ASSERT_FALSE(lug.nodes.empty());
    EXPECT_NEAR(a.nodes[std::size_t(lug.nodes.front())].slab_start, 60.0, 1e-9);
    for (int n : lug.nodes) {
        const auto& node = a.nodes[std::size_t(n)];
        EXPECT_NEAR(node.area, 64.0, 1e-6) << "x = " << node.offset;
        EXPECT_NEAR(node.position.y(), 30.0, kGrid);
        EXPECT_NEAR(node.position.z(), 24.0, kGrid);
    }
    for (int n : a.branches[0].nodes)
        EXPECT_NEAR(a.nodes[std::size_t(n)].area, 3600.0, 1e-6) << a.nodes[std::size_t(n)].offset;
    expect_invariants(a, mesh);
}

TEST(CentroidalAxis, ACorniceOnTheFarPierOfAPortalIsMarchedFromThatPiersFace) {
    // Piers A [0,20] and B [30,40] (x) under a deck [0,46] x [0,30] x [20,30]: the deck's 6 mm
    // cornice [40,46] overhangs B's outer face. Where the piers' tracks merge into the deck, the
    // deck continues A's track; the cornice, a ledge, leaves B's section. Its march starts at B's
    // face (x = 40, Eq. 4's T of the region it leaves), and its sections past it hold the cornice
    // alone, 30 x 10 on its centre line. (Started at A's face, x = 20, its first section held none
    // of it: a march that never reached it, its slab taken from the deck's march all the same.)
    const auto mesh =
        mesh_of(from_occt(fuse(fuse(occ_box(0, 0, 0, 20, 30, 20), occ_box(30, 0, 0, 10, 30, 20)),
                               occ_box(0, 0, 20, 46, 30, 10))));
    const auto a = mas::centroidal_axis(mesh, {});
    int cornice = -1;
    for (std::size_t b = 0; b < a.branches.size(); ++b)
        if (a.branches[b].direction.isApprox(Vector3d::UnitX(), 1e-12)) cornice = int(b);
    ASSERT_GE(cornice, 0);
    const auto& nodes = a.branches[std::size_t(cornice)].nodes;
    ASSERT_FALSE(nodes.empty());
    EXPECT_NEAR(a.nodes[std::size_t(nodes.front())].slab_start, 40.0, 1e-9);
    EXPECT_LE(a.nodes[std::size_t(nodes.front())].offset, 40.0 + a.params.step_mm);
    for (int n : nodes) {
        const auto& node = a.nodes[std::size_t(n)];
        EXPECT_GT(node.offset, 40.0);
        EXPECT_NEAR(node.area, 300.0, 1e-6);
        EXPECT_NEAR(node.position.y(), 15.0, kGrid);
        EXPECT_NEAR(node.position.z(), 25.0, kGrid);
    }
    expect_invariants(a, mesh);
}

TEST(CentroidalAxis, AnArmEndingAtItsGussetsTipIsMarchedFromTheColumnsFace) {
    // Column [0,20]^2 x [0,80], arm [20,43] x [0,20] x [60,80], and under it a web 4 thick
    // ([8,12] in y) whose tip meets the arm's end: (x, z) = (20, 60), (43, 60), (20, 37). Step
    // 3.5: on z = 59.501 the web reaches x = 42.501; on z = 63.001 the arm's underside appears at
    // once round it, a ledge turned +X (from the section's centroid, its centre lying on the web).
    // Eq. 4's T is the web's tip, and past it lies 0.499 mm of the arm, less than a step: the
    // march from there found nothing and the arm stayed in the column's layers, its underside
    // beside the web overhanging. Past the column's face, x = 20, where the stick-out begins,
    // the section below holds only the web, a fin under it: the march starts there.
    const TopoDS_Shape web =
        mas::test::occ_prism({{20, 8, 60}, {43, 8, 60}, {20, 8, 37}}, {0, 4, 0});
    const auto mesh = mesh_of(
        from_occt(fuse(fuse(occ_box(0, 0, 0, 20, 20, 80), occ_box(20, 0, 60, 23, 20, 20)), web)));
    // Step 3.3 too: the web reaches x = 42.401 on z = 59.401, and the arm's last plane, x = 42.901,
    // lies past that, over the web's end under the arm's underside.
    for (const double step : {3.5, 3.3}) {
        SCOPED_TRACE("step " + std::to_string(step));
        mas::AxisParams p;
        p.step_mm = step;
        const auto a = mas::centroidal_axis(mesh, p);
        ASSERT_TRUE(turns_once(a, Vector3d::UnitX()));
        const auto& arm = a.branches[1];
        EXPECT_NEAR(a.nodes[std::size_t(arm.nodes.front())].slab_start, 20.0, kGrid);
        // The +X grid's planes past x = 20 (0.001 + i step). Each holds the arm's 20 x 20
        // section, on its centre line. The column's node under the arm's underside, whose slab
        // swept the web's section up to the next plane, ends it beyond x = 20 where the
        // underside appears (found by halving, to 1e-4 of a step: at most that much web, 4 mm
        // wide, is left under it), and sweeps the web's section there below it, out to the
        // web's tip; the node above holds the column alone. (Kept, the notch over the web put
        // the arm's centroids 0.47 mm below its centre line, but not those past the web's tip
        // on the column's plane, which held the web's end under the arm instead: the guide
        // bent there.)
        const double first = std::ceil(20.0 / step);
        ASSERT_EQ(arm.nodes.size(), std::size_t(std::ceil((43.0 - 0.001) / step) - first));
        const double hair = 4.0 * 1e-4 * step;
        for (std::size_t i = 0; i < arm.nodes.size(); ++i) {
            const auto& node = a.nodes[std::size_t(arm.nodes[i])];
            EXPECT_NEAR(node.offset, 0.001 + step * (first + double(i)), 1e-9);
            EXPECT_GE(node.area, 400.0 - 1e-6) << "x = " << node.offset;
            EXPECT_LE(node.area, 400.0 + hair) << "x = " << node.offset;
            EXPECT_NEAR(node.position.y(), 10.0, kGrid);
            EXPECT_NEAR(node.position.z(), 70.0, hair * 10.0 / 400.0 + kGrid);
        }
        for (int n : a.branches[0].nodes) {
            const auto& node = a.nodes[std::size_t(n)];
            if (node.offset > 60.0) {
                EXPECT_NEAR(node.area, 400.0, 1e-6) << "z = " << node.offset;
                EXPECT_NEAR(node.position.x(), 10.0, kGrid) << "z = " << node.offset;
            }
        }
        expect_invariants(a, mesh);
    }
}

TEST(CentroidalAxis, ArmsOnGussetsAtTwoHeightsBesideAnotherColumnAreMarchedWhole) {
    // Column A [0,20]^2 x [0,100] and column B [60,80] x [0,20] x [0,80] on a plate [0,80] x
    // [0,20] x [0,5]; on A two arms [20,43] x [0,20], z in [40,55] and [85,100], each over a web
    // 4 thick ([8,12] in y) whose tip meets the arm's end: (x, z) = (20, 40), (43, 40), (20, 17)
    // and the same 45 higher. Each arm is marched from A's face, its node below giving back what
    // its slab took of the arm (the slab of that node, not of the node with the same index among
    // the slabs: the first release adds slabs, and the second arm kept its notch, 297 mm^2 of
    // 300), and sweeping the web's end under the arm. B's nodes keep their whole sections.
    const TopoDS_Shape web1 =
        mas::test::occ_prism({{20, 8, 40}, {43, 8, 40}, {20, 8, 17}}, {0, 4, 0});
    const TopoDS_Shape web2 =
        mas::test::occ_prism({{20, 8, 85}, {43, 8, 85}, {20, 8, 62}}, {0, 4, 0});
    TopoDS_Shape part = fuse(occ_box(0, 0, 0, 80, 20, 5), occ_box(0, 0, 0, 20, 20, 100));
    part = fuse(fuse(part, occ_box(60, 0, 0, 20, 20, 80)), occ_box(20, 0, 40, 23, 20, 15));
    part = fuse(fuse(fuse(part, occ_box(20, 0, 85, 23, 20, 15)), web1), web2);
    const auto mesh = mesh_of(from_occt(part));
    mas::AxisParams p;
    p.step_mm = 3.3;
    const auto a = mas::centroidal_axis(mesh, p);
    const double hair = 4.0 * 1e-4 * p.step_mm;
    std::vector<double> arms;  // their centre lines' heights
    for (const auto& b : a.branches) {
        if (!b.direction.isApprox(Vector3d::UnitX(), 1e-12)) continue;
        const double z = a.nodes[std::size_t(b.nodes.front())].position.z();
        arms.push_back(z);
        const double centre = z < 70.0 ? 47.5 : 92.5;
        EXPECT_NEAR(a.nodes[std::size_t(b.nodes.front())].slab_start, 20.0, kGrid);
        for (int n : b.nodes) {
            const auto& node = a.nodes[std::size_t(n)];
            EXPECT_GE(node.area, 300.0 - 1e-6) << "x = " << node.offset << ", arm at " << centre;
            EXPECT_LE(node.area, 300.0 + hair) << "x = " << node.offset << ", arm at " << centre;
            EXPECT_NEAR(node.position.y(), 10.0, kGrid);
            EXPECT_NEAR(node.position.z(), centre, hair * 7.5 / 300.0 + kGrid);
        }
    }
    ASSERT_EQ(arms.size(), 2u);
    EXPECT_NE(arms[0] < 70.0, arms[1] < 70.0);
    // B's nodes above the plate: its whole 20 x 20 section, none swept by A's arms' nodes.
    int b_nodes = 0;
    for (const auto& node : a.nodes) {
        if (!node.normal.isApprox(Vector3d::UnitZ(), 1e-12) || node.offset < 6.0 ||
            node.position.x() < 50.0)
            continue;
        ++b_nodes;
        EXPECT_NEAR(node.area, 400.0, 1e-6) << "z = " << node.offset;
        EXPECT_NEAR(node.position.x(), 70.0, kGrid) << "z = " << node.offset;
    }
    EXPECT_EQ(b_nodes,
              int(std::ceil((80.0 - 0.001) / p.step_mm)) - int(std::ceil(6.0 / p.step_mm)));
    expect_invariants(a, mesh);
}

TEST(CentroidalAxis, AStickOutLessThanAStepSidewaysIsNoTurn) {
    // A 4 x 4 column [0,4]^2 x [0,20] widening at z = 10 by a ledge [4,5.5]x[0,4]x[10,20], step 2.
    // On the plane z = 10.001 the ledge is centred 0.75 mm outside the column: past the derived
    // d (a sixth of the column's 4 mm size, 0.67) and the bump distance (an eighth, 0.5), so it is
    // far. Its direction is the axis nearest G - E plus the step along the march
    // (CentroidalAxis.hpp: the 3-D vector between sections a step apart), (0.75, 0, 2): +Z, still
    // along the march, so no turn. One branch, whose nodes move onto the wider section: 4 x 4 up
    // to z = 10, 5.5 x 4 centred on x = 2.75 above.
    const auto mesh =
        mesh_of(from_occt(fuse(occ_box(0, 0, 0, 4, 4, 20), occ_box(0, 0, 10, 5.5, 4, 10))));
    mas::AxisParams p;
    p.step_mm = 2.0;
    const auto a = mas::centroidal_axis(mesh, p);
    ASSERT_EQ(a.branches.size(), 1u);
    ASSERT_EQ(a.nodes.size(), 10u);  // z = 0.001 ... 18.001
    for (const auto& node : a.nodes) {
        const bool wide = node.offset > 10.0;
        EXPECT_NEAR(node.area, wide ? 22.0 : 16.0, 1e-9) << "z = " << node.offset;
        EXPECT_NEAR(node.position.x(), wide ? 2.75 : 2.0, kGrid) << "z = " << node.offset;
        EXPECT_NEAR(node.position.y(), 2.0, kGrid);
    }
    expect_invariants(a, mesh);
}

TEST(CentroidalAxis, TwoPostsOnAPlateAreTwoBranches) {
    const auto mesh = mesh_of(mas::test::two_posts());
    mas::AxisParams p;
    p.step_mm = 1.0;
    const auto a = mas::centroidal_axis(mesh, p);
    const auto kids = children(a, 0);
    ASSERT_EQ(kids.size(), 2u);
    std::vector<double> xs;
    for (int b : kids) {
        const auto& br = a.branches[b];
        EXPECT_TRUE(br.direction.isApprox(Vector3d::UnitZ()));
        const auto& first = a.nodes[br.nodes.front()];
        xs.push_back(first.position.x());
        EXPECT_NEAR(first.area, 100.0, 1e-6);
        // Split from the plate's last node, one step below.
        const auto& tie = a.links[br.first_link];
        EXPECT_EQ(tie.kind, mas::AxisLink::Kind::Step);
        EXPECT_EQ(tie.start, a.branches[0].nodes.back());
    }
    std::sort(xs.begin(), xs.end());
    EXPECT_NEAR(xs[0], 5.0, kGrid);
    EXPECT_NEAR(xs[1], 35.0, kGrid);
    expect_invariants(a, mesh);
}

namespace {

// The roots of `a` whose first node lies above z = 1 (material hanging in mid-air), by height.
std::vector<int> hanging_roots(const mas::CentroidalAxis& a) {
    std::vector<int> out;
    for (std::size_t b = 0; b < a.branches.size(); ++b)
        if (a.branches[b].parent < 0 && a.nodes[a.branches[b].nodes.front()].offset > 1.0)
            out.push_back(int(b));
    std::sort(out.begin(), out.end(), [&](int x, int y) {
        return a.nodes[a.branches[x].nodes.front()].offset <
               a.nodes[a.branches[y].nodes.front()].offset;
    });
    return out;
}

}  // namespace

TEST(CentroidalAxis, MaterialHangingUnderABridgeRootsATreeWhereItBegins) {
    // The block under the arch's beam first appears at z = 15, beside no section below it: the
    // march from the base never reaches it (the legs' tracks meet the beam, which it hangs from).
    // It used to be left out, a quarter of the part unswept, and the decomposition then took the
    // axis for another part's. It is searched up from its first grid plane, 15.001 at a 2.5 mm
    // step, to the last one below the beam, 37.501: a root of its own, its first slab reaching
    // back to the plane before.
    const auto mesh = mesh_of(mas::test::arch_with_pendant());
    mas::AxisParams p;
    p.step_mm = 2.5;
    const auto a = mas::centroidal_axis(mesh, p);
    const auto hanging = hanging_roots(a);
    ASSERT_EQ(hanging.size(), 1u);
    const auto& br = a.branches[std::size_t(hanging[0])];
    EXPECT_TRUE(br.direction.isApprox(Vector3d::UnitZ()));
    ASSERT_EQ(br.nodes.size(), 10u);
    for (std::size_t i = 0; i < br.nodes.size(); ++i) {
        const auto& node = a.nodes[std::size_t(br.nodes[i])];
        EXPECT_NEAR(node.offset, 15.001 + 2.5 * double(i), 1e-9);
        EXPECT_NEAR(node.position.x(), 30.0, kGrid);
        EXPECT_NEAR(node.position.y(), 10.0, kGrid);
        EXPECT_NEAR(node.area, 400.0, 1e-6);
    }
    EXPECT_NEAR(a.nodes[std::size_t(br.nodes.front())].slab_start, 12.501, 1e-9);
    expect_invariants(a, mesh);
}

TEST(CentroidalAxis, BlocksHangingAtTwoHeightsAreBothSearched) {
    // Legs [0,10] and [70,80] (x 20 y, 40 tall), a beam [0,80] x [0,20] x [40,50] and two blocks
    // hanging from it, [15,30] from z = 15 and [50,65] from z = 25. Once the first block was
    // found, the slabs' error had grown past what was still missing and the second was left out.
    const auto part =
        from_occt(fuse(fuse(fuse(occ_box(0, 0, 0, 10, 20, 40), occ_box(70, 0, 0, 10, 20, 40)),
                            occ_box(0, 0, 40, 80, 20, 10)),
                       fuse(occ_box(15, 0, 15, 15, 20, 25), occ_box(50, 0, 25, 15, 20, 15))));
    const auto mesh = mesh_of(part);
    mas::AxisParams p;
    p.step_mm = 2.5;
    const auto a = mas::centroidal_axis(mesh, p);
    const auto hanging = hanging_roots(a);
    ASSERT_EQ(hanging.size(), 2u);
    const double first_plane[] = {15.001, 25.001}, centre[] = {22.5, 57.5};
    for (int h : {0, 1}) {
        const auto& node = a.nodes[a.branches[std::size_t(hanging[h])].nodes.front()];
        EXPECT_NEAR(node.offset, first_plane[h], 1e-9);
        EXPECT_NEAR(node.position.x(), centre[h], kGrid);
        EXPECT_NEAR(node.position.y(), 10.0, kGrid);
        EXPECT_NEAR(node.area, 300.0, 1e-6);
    }
    expect_invariants(a, mesh);
}

TEST(CentroidalAxis, ASplitIsOneC1BreakNotTwo) {
    // The two posts at a 1 mm step. Each post's first link runs from the plate's last node,
    // (20, 5, 4.001), to the post's first, (5, 5, 5.001) or (35, 5, 5.001): 15 mm sideways for
    // 1 mm up, a turn of atan(15) = 86.2 degrees from the plate's +Z march, a C1 break (Sec.
    // 3.2.3). The post's next link turns as far back to +Z, but only undoes that connector
    // (CentroidalAxis.hpp: a link after a break is none): two breaks in all, one per post.
    const auto mesh = mesh_of(mas::test::two_posts());
    mas::AxisParams p;
    p.step_mm = 1.0;
    const auto a = mas::centroidal_axis(mesh, p);
    const double connector_turn = std::atan(15.0) * 180.0 / kPi;
    int breaks = 0;
    for (const auto& l : a.links) breaks += l.is_break;
    EXPECT_EQ(breaks, 2);
    const auto kids = children(a, 0);
    ASSERT_EQ(kids.size(), 2u);
    for (int b : kids) {
        const auto& br = a.branches[std::size_t(b)];
        const auto& tie = a.links[std::size_t(br.first_link)];
        EXPECT_TRUE(tie.is_break);
        EXPECT_NEAR(tie.turn_deg, connector_turn, 1e-3);
        ASSERT_GE(br.nodes.size(), 2u);
        const auto& back = a.links[std::size_t(a.nodes[std::size_t(br.nodes[1])].incoming_link)];
        EXPECT_FALSE(back.is_break);
        EXPECT_NEAR(back.turn_deg, connector_turn, 1e-3);
    }
}

TEST(CentroidalAxis, BrepAndStlOfOnePartGiveOneAxisWithinTheDeflection) {
    const TopoDS_Shape occ = occ_cylinder_on_block();
    const auto fine = mesh_of(from_occt(occ), 0.01);
    // The same geometry through an STL file, tessellated coarser by another path.
    const std::string stl = ::testing::TempDir() + "cylinder_on_block.stl";
    {
        mas::TessellationParams tp;
        tp.deflection_mm = 0.05;
        const auto coarse = mas::tessellate(from_occt(occ), tp);
        std::ofstream out(stl);
        out << "solid part\n";
        for (const auto& t : coarse.triangles) {
            out << "facet normal 0 0 0\nouter loop\n";
            for (int k = 0; k < 3; ++k) {
                const auto& v = coarse.vertices[t[k]];
                out << "vertex " << std::setprecision(17) << v.x() << " " << v.y() << " " << v.z()
                    << "\n";
            }
            out << "endloop\nendfacet\n";
        }
        out << "endsolid part\n";
    }
    const auto from_stl = mas::model_mesh(mas::read_model(stl));
    mas::AxisParams p;
    p.step_mm = 1.0;
    const auto a = mas::centroidal_axis(fine, p), b = mas::centroidal_axis(from_stl, p);
    ASSERT_EQ(a.branches.size(), b.branches.size());
    ASSERT_EQ(a.nodes.size(), b.nodes.size());
    // Branches matched by direction (their order may follow tiny area differences).
    for (const auto& ba : a.branches) {
        int match = 0;
        for (const auto& bb : b.branches) {
            if (!ba.direction.isApprox(bb.direction) || ba.nodes.size() != bb.nodes.size())
                continue;
            ++match;
            for (std::size_t i = 0; i < ba.nodes.size(); ++i)
                EXPECT_LE((a.nodes[ba.nodes[i]].position - b.nodes[bb.nodes[i]].position).norm(),
                          0.01 + 0.05);
        }
        EXPECT_EQ(match, 1);
    }
}

TEST(CentroidalAxis, DerivedStepIsHalfTheThinnestWallWithinClamps) {
    // 200 x 100 x 10 plate: its thinnest sections are the 100 x 10 strips, 2A/P = 2000/220.
    const auto plate = mas::test::box_mesh(0, 0, 0, 200, 100, 10);
    const double wall = 2.0 * 1000.0 / 220.0;
    EXPECT_NEAR(mas::derive_axis_step(plate), wall / 2.0, 1e-9);
    const auto a = mas::centroidal_axis(plate);
    EXPECT_NEAR(a.params.step_mm, wall / 2.0, 1e-9);
    EXPECT_NEAR(a.params.distance_threshold_mm, wall, 1e-9);
    // A 0.2 mm wire 400 mm long: held at diagonal / 2000; a cube: at most diagonal / 20.
    const auto wire = mas::test::box_mesh(0, 0, 0, 0.2, 0.2, 400);
    EXPECT_NEAR(mas::derive_axis_step(wire), std::sqrt(0.08 + 160000.0) / 2000.0, 1e-12);
    const auto cube = mas::test::box_mesh(0, 0, 0, 10, 10, 10);
    EXPECT_NEAR(mas::derive_axis_step(cube), std::sqrt(300.0) / 20.0, 1e-12);
    // Lying flat, thinner than diagonal / 2000: at most half the height, so that the axis of a
    // 100 x 100 x 0.05 shim (once "step 0.0707 mm is not smaller than the part's height") and
    // of the wire lying down are computed at their derived step.
    const auto shim = mas::test::box_mesh(0, 0, 0, 100, 100, 0.05);
    EXPECT_NEAR(mas::derive_axis_step(shim), 0.025, 1e-12);
    const auto s = mas::centroidal_axis(shim);
    ASSERT_EQ(s.nodes.size(), 2u);
    EXPECT_NEAR(s.nodes[1].position.z(), 0.026, 1e-12);
    for (const auto& node : s.nodes) EXPECT_NEAR(node.area, 10000.0, 1e-6);
    const auto lying = mas::test::box_mesh(0, 0, 0, 400, 0.2, 0.2);
    EXPECT_NEAR(mas::derive_axis_step(lying), 0.1, 1e-12);
    EXPECT_NO_THROW(mas::centroidal_axis(lying));
}

TEST(CentroidalAxis, DerivedStepIsNotTakenFromAPlaneGrazingAnEdge) {
    // tests/data/hub_twisted_blades.brep: six blades 3.06 mm thick and 13.74 wide, twisted 30
    // degrees, round a hub. A plane across a blade cuts a strip about 2A/P = 2.5 mm wide; one of
    // the X planes grazes another blade's tip face, nearly along it, and cuts a 0.05 mm strip.
    // Taken for the thinnest wall, that made the step diagonal / 2000 (0.056 mm) and the axis
    // 3600 nodes. The step is half a wall as thick as the blades, give or take the half again a
    // strip that goes on may thicken by.
    const auto mesh = mas::test::data_mesh("hub_twisted_blades.brep");
    const double t = 3.063852014180396, w = 13.73836330961673;
    const double blade = 2.0 * t * w / (2.0 * (t + w));
    const double step = mas::derive_axis_step(mesh);
    EXPECT_LE(step, blade / 2.0);
    EXPECT_GE(step, blade / 2.0 / 1.5);
    const auto a = mas::centroidal_axis(mesh);
    EXPECT_DOUBLE_EQ(a.params.step_mm, step);
    EXPECT_LT(a.nodes.size(), 400u);
    expect_invariants(a, mesh);
}

TEST(CentroidalAxis, AStripTheBladesOnlyTaperToIsNoWall) {
    // tests/data/hub_blades_graze.brep: six blades 5.59 mm thick and 27.8 wide, twisted 30
    // degrees, round a hub with a bore. Planes near the blades' corners, where a blade tapers to
    // its edge, cut strips 0.6 to 0.92 mm wide: the planes their width further on cut 0.11 to
    // 0.14 mm there, and back 1.1 to 1.7 mm. A wall goes on at its thickness, within half as
    // thick again either way. Taken for walls for going on thinner, they let a 0.08 mm graze
    // count (within an eighth of them): the step was diagonal / 2000 (0.05 mm), the axis 4362
    // nodes, and four of the six blades stayed in the hub's layers, 112 mm^2 hanging in one. The
    // first walls are cuts across the blades now, and the strips taken are those within an
    // eighth of them: the step is at least half of an eighth of a blade's cut, 2A/P.
    const auto mesh = mas::test::data_mesh("hub_blades_graze.brep");
    const double t = 5.5921970847627245, w = 27.782716740278985;
    const double blade = 2.0 * t * w / (2.0 * (t + w));
    const double step = mas::derive_axis_step(mesh);
    EXPECT_GE(step, blade / 8.0 / 2.0);
    EXPECT_LE(step, blade / 2.0);
    const auto a = mas::centroidal_axis(mesh);
    EXPECT_DOUBLE_EQ(a.params.step_mm, step);
    expect_invariants(a, mesh, false);  // the hub's bore holds its centroids
}

TEST(CentroidalAxis, WhatAMarchRoundALoopLeavesUnreachedIsSearchedFromItsUnderside) {
    // tests/data/truss_beam_unreached.brep: two posts 9.26 square 23.39 apart on a plate, a beam
    // across their tops and two braces crossing under it, clear of the beam. At the derived step
    // the march goes up one brace, down the other into the far post, and through both posts (and
    // the beam over them) along X from inside; no march reaches the beam's middle, whose
    // underside rests on the posts' material, not on air, so the search for what hangs in mid-air
    // did not take it either, and the axis was refused: 89 % of the part swept. Where material
    // is still lost, what is left unswept is searched upward from its own underside: the beam's
    // middle is a root along +Z from the first plane over its underside to its top.
    const auto mesh = mas::test::data_mesh("truss_beam_unreached.brep");
    const double post = 9.255708650256704, gap = 23.39282870169506;
    const double underside = 54.59013471380901 + 2.0, top = underside + post;
    const auto a = mas::centroidal_axis(mesh);
    const double step = a.params.step_mm;
    const double volume = mas::mesh_volume(mesh);
    EXPECT_GT(a.searched_volume_mm3, 0.95 * volume);
    int beam = -1;
    for (std::size_t b = 1; b < a.branches.size(); ++b) {
        const auto& br = a.branches[b];
        const auto& first = a.nodes[std::size_t(br.nodes.front())];
        if (br.parent < 0 && first.position.z() > underside && first.position.x() > post &&
            first.position.x() < post + gap)
            beam = int(b);
    }
    ASSERT_GE(beam, 0);
    const auto& br = a.branches[std::size_t(beam)];
    EXPECT_TRUE(br.direction.isApprox(Vector3d::UnitZ(), 1e-12));
    const auto& first = a.nodes[std::size_t(br.nodes.front())];
    EXPECT_LE(first.position.z(), underside + step);
    EXPECT_NEAR(first.position.y(), post / 2.0, 1e-6);
    EXPECT_GE(first.area, (gap - 2.0 * step) * post);
    EXPECT_LE(first.area, (gap + 2.0 * step) * post);
    const auto& last = a.nodes[std::size_t(br.nodes.back())];
    EXPECT_GE(last.position.z(), top - step);
    EXPECT_LT(last.position.z(), top);
    expect_invariants(a, mesh);
}

TEST(CentroidalAxisErrors, BadParametersAndPlacementAreNamed) {
    const auto mesh = mas::test::box_mesh(0, 0, 5, 10, 10, 10);
    auto expect_error_on = [&](const mas::TriangleMesh& m, const std::string& word,
                               mas::AxisParams p = {}) {
        try {
            mas::centroidal_axis(m, p);
            ADD_FAILURE() << "no error for " << word;
        } catch (const mas::Error& e) {
            EXPECT_EQ(e.code(), mas::ErrorCode::InvalidArgument);
            EXPECT_NE(std::string(e.what()).find(word), std::string::npos) << e.what();
        }
    };
    auto expect_error = [&](mas::AxisParams p, const std::string& word) {
        try {
            mas::centroidal_axis(mesh, p);
            ADD_FAILURE() << "no error for " << word;
        } catch (const mas::Error& e) {
            EXPECT_EQ(e.code(), mas::ErrorCode::InvalidArgument);
            EXPECT_NE(std::string(e.what()).find(word), std::string::npos) << e.what();
        }
    };
    mas::AxisParams p;
    p.step_mm = 12.0;
    expect_error(p, "height");
    p = {};
    p.step_mm = std::nan("");
    expect_error(p, "finite");
    p = {};
    p.eps_mm = -1.0;
    expect_error(p, "eps");
    p = {};
    p.break_angle_deg = 270.0;
    expect_error(p, "break angle");
    p = {};
    p.base_z_mm = 0.0;  // the box floats 5 mm above it
    expect_error(p, "does not stand on its base plane");
    p.base_z_mm = 5.0;
    EXPECT_NO_THROW(mas::centroidal_axis(mesh, p));
    EXPECT_THROW(mas::centroidal_axis(mas::TriangleMesh{}), mas::Error);
    // A step that would take more sections across the part than the axis may have nodes is named
    // before the grids are allocated (1e-9 mm on this 10 mm box would take gigabytes): the limit
    // is exactly max_nodes sections across the part's largest extent.
    p = {};
    p.max_nodes = 1000;
    p.step_mm = 10.0 / 999.0;
    EXPECT_NO_THROW(mas::centroidal_axis(mesh, p));
    p.step_mm = 10.0 / 1001.0;
    expect_error(p, "too small for this part");
    p = {};
    p.step_mm = 1e-9;
    expect_error(p, "200000");
    p = {};
    p.eps_mm = 10.0;  // the first plane would lie on the box's top
    expect_error(p, "eps 10 mm is not smaller than the part's height");
    // A part drawn in metres: no section reaches the sliver area. An empty axis is an error.
    expect_error_on(mas::test::box_mesh(0, 0, 0, 5e-4, 5e-4, 0.01), "no section of the part");
}

TEST(CentroidalAxisErrors, AStepEqualToThePartsHeightIsNotSmallerThanIt) {
    // The step must be smaller than the part's height (CentroidalAxis.cpp's message, "not smaller
    // than the part's height"): a 10 mm box at a 10 mm step is refused, as at 12 mm above.
    mas::AxisParams p;
    p.step_mm = 10.0;
    try {
        mas::centroidal_axis(mas::test::box_mesh(0, 0, 0, 10, 10, 10), p);
        ADD_FAILURE() << "no error";
    } catch (const mas::Error& e) {
        EXPECT_EQ(e.code(), mas::ErrorCode::InvalidArgument);
        EXPECT_NE(std::string(e.what()).find("step 10 mm is not smaller than the part's height"),
                  std::string::npos)
            << e.what();
    }
}

TEST(CentroidalAxisErrors, AMarchThatLosesWhatIsThinnerThanTheStepGivenIsNamed) {
    // A 1 mm square pin leaning 0.3 mm a mm, 30 mm tall, under a 10 mm block: at a 10 mm step
    // its sections a step apart do not meet, and the march from its foot ends at the next plane,
    // the pin and the block unswept. The axis was returned all the same, and the decomposition
    // refused it as another part's. The error names the step, what was swept, and a smaller step.
    const auto mesh = mesh_of(from_occt(
        fuse(mas::test::occ_prism({{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}}, {9, 0, 30}),
             occ_box(4, -4.5, 29, 10, 10, 5))));
    mas::AxisParams p;
    p.step_mm = 10.0;
    const std::string error = mas::test::error_of([&] { mas::centroidal_axis(mesh, p); });
    EXPECT_EQ(
        error.rfind("invalid_argument: centroidal axis: the march at a step of 10 mm swept ", 0),
        0u)
        << error;
    const double derived = mas::derive_axis_step(mesh);
    EXPECT_NE(error.find(" mm^3 of the part's " + mas::format_number(529.0, 4) + " ("),
              std::string::npos)
        << error;
    EXPECT_NE(error.find("): what is thinner than the step was lost; give a smaller step, such as "
                         "the one derived from the part, " +
                         mas::format_number(derived) + " mm (a step of 0 derives it)"),
              std::string::npos)
        << error;
    // At that step the march sweeps it all (within the first slabs' eps: 0.05 mm^3).
    EXPECT_NEAR(mas::centroidal_axis(mesh).searched_volume_mm3, 529.0, 0.1);
}

TEST(CentroidalAxisErrors, APartMoreThanEpsAboveItsBasePlaneDoesNotStandOnIt) {
    // AxisParams::base_z_mm: a part whose lowest point lies above the base plane by more than eps
    // (0.001 mm) does not touch it. A box floating 0.002 mm above z = 0 is an error; 0.0005 mm
    // below its bottom, within eps, the plane is the part's base.
    const auto mesh = mas::test::box_mesh(0, 0, 0.002, 10, 10, 10);
    mas::AxisParams p;
    p.base_z_mm = 0.0;
    try {
        mas::centroidal_axis(mesh, p);
        ADD_FAILURE() << "no error";
    } catch (const mas::Error& e) {
        EXPECT_EQ(e.code(), mas::ErrorCode::InvalidArgument);
        EXPECT_NE(std::string(e.what()).find("does not stand on its base plane z = 0 mm"),
                  std::string::npos)
            << e.what();
    }
    p.base_z_mm = 0.0015;
    const auto a = mas::centroidal_axis(mesh, p);
    EXPECT_EQ(a.params.base_z_mm, 0.0015);
    EXPECT_NEAR(a.nodes.front().offset, 0.0015 + p.eps_mm, 1e-12);
}

TEST(CentroidalAxis, DerivedStepIgnoresTinySectionsOfRoundedTips) {
    // A 100 x 10 x 10 bar with a ball of radius 4 sitting half out of its top face. The plane
    // nearest the ball's top cuts a disc of radius 1.8 (the old rule's step: 0.9), but the walls
    // are the bar's 100 x 10 strips: half of their 2A/P = 2000 / 220. Strips crossing the ball
    // carry its bump, whose arc adds relatively more perimeter than area: their 2A/P is lower,
    // by under 1% here (arc of a 4 mm ball on a 220 mm perimeter).
    BRepPrimAPI_MakeSphere ball(gp_Pnt(50, 5, 10), 4.0);
    const auto mesh = mesh_of(from_occt(fuse(occ_box(0, 0, 0, 100, 10, 10), ball.Shape())));
    const double strip = 2000.0 / 220.0 / 2.0;
    EXPECT_LE(mas::derive_axis_step(mesh), strip + 1e-9);
    EXPECT_GE(mas::derive_axis_step(mesh), 0.99 * strip);
}

TEST(CentroidalAxis, LugNearTheEndOfALongWallTurnsTheWayItSticksOut) {
    // A standing wall [0,80]x[0,10]x[0,40] with a lug [10,25]x[10,30]x[30,40] on its +Y face near
    // one end. From the wall's centroid (40, 5) the lug's centre (17.5, 20) lies mostly along -X,
    // which would send the search past the end of the wall; the lug leaves the wall through its
    // +Y face, so the branch goes +Y, on the lug's centre line.
    const auto mesh =
        mesh_of(from_occt(fuse(occ_box(0, 0, 0, 80, 10, 40), occ_box(10, 10, 30, 15, 20, 10))));
    mas::AxisParams p;
    p.step_mm = 2.0;
    const auto a = mas::centroidal_axis(mesh, p);
    const auto kids = children(a, 0);
    ASSERT_EQ(kids.size(), 1u);
    const auto& lug = a.branches[std::size_t(kids[0])];
    EXPECT_TRUE(lug.direction.isApprox(Vector3d::UnitY()));
    EXPECT_EQ(lug.nodes.size(), 10u);  // y = 10.001 ... 28.001
    for (int n : lug.nodes) {
        EXPECT_NEAR(a.nodes[std::size_t(n)].position.x(), 17.5, kGrid);
        EXPECT_NEAR(a.nodes[std::size_t(n)].position.z(), 35.0, kGrid);
        EXPECT_NEAR(a.nodes[std::size_t(n)].area, 150.0, 1e-6);
    }
    expect_invariants(a, mesh);
}

TEST(CentroidalAxis, TwistedBladeLeavingAHubTurnsIntoItsLength) {
    // A hub (radius 12, 40 tall) with a blade 30 x 3 reaching +X from x = 8 to 60, twisted 40
    // degrees along its length (ruled between its end sections, centred at z = 20). Its underside
    // leaves the hub at a small angle: every plane of the +Z march adds a strip up to ~9 mm
    // longer than the last beside it, whose centre stays within the "bump" distance (an eighth of
    // the hub's size) of the lower section. It reaches far past it, though: an overhang, and a
    // turn. (Taken for bumps, the whole blade was built upwards, unsupported.)
    auto end_section = [](double x, double degrees) {
        const double c = std::cos(degrees * kPi / 180.0), s = std::sin(degrees * kPi / 180.0);
        BRepBuilderAPI_MakePolygon poly;
        for (const auto& [y, z] : {std::pair{-1.5, -15.0}, {1.5, -15.0}, {1.5, 15.0}, {-1.5, 15.0}})
            poly.Add(gp_Pnt(x, y * c - z * s, 20.0 + y * s + z * c));
        poly.Close();
        return poly.Wire();
    };
    BRepOffsetAPI_ThruSections loft(Standard_True, Standard_True);
    loft.AddWire(end_section(8.0, 0.0));
    loft.AddWire(end_section(60.0, 40.0));
    loft.Build();
    ASSERT_TRUE(loft.IsDone());
    const auto mesh =
        mesh_of(from_occt(fuse(BRepPrimAPI_MakeCylinder(12, 40).Shape(), loft.Shape())));
    mas::AxisParams p;
    p.step_mm = 0.45;
    const auto a = mas::centroidal_axis(mesh, p);
    int blade = -1;
    for (int b : children(a, 0))
        if (a.branches[std::size_t(b)].direction.isApprox(Vector3d::UnitX())) blade = b;
    ASSERT_GE(blade, 0) << "no +X branch from the hub";
    const auto& nodes = a.branches[std::size_t(blade)].nodes;
    // The blade's march starts at the hub's side (Eq. 4's T, at most a step on) and goes to its
    // tip, one node a step.
    EXPECT_LE(a.nodes[std::size_t(nodes.front())].position.x(), 12.0 + p.step_mm + 1e-9);
    EXPECT_GE(a.nodes[std::size_t(nodes.back())].position.x(), 60.0 - p.step_mm);
    expect_invariants(a, mesh);
}

TEST(CentroidalAxis, HubLyingAcrossItsNeckTurnsBothWays) {
    // A neck [-5,5]x[-1,1]x[0,30] carrying a hub along X (radius 8, axis at z = 30) from x = -20
    // to 20. Where the +Z march meets the hub's underside, the stick-out is the hub's section
    // (wider than the neck) less the neck: one piece round the neck, centred on it, reaching 15 mm
    // past it both ways. Its ends beyond the neck's sides turn, one march each way along the
    // hub's axis. (By its centre it was no turn, and the hub's ends were built upwards from their
    // undersides.)
    const auto mesh = mesh_of(from_occt(fuse(
        occ_box(-5, -1, 0, 10, 2, 30),
        BRepPrimAPI_MakeCylinder(gp_Ax2(gp_Pnt(-20, 0, 30), gp_Dir(1, 0, 0)), 8, 40).Shape())));
    mas::AxisParams p;
    p.step_mm = 1.5;
    const auto a = mas::centroidal_axis(mesh, p);
    for (double sign : {1.0, -1.0}) {
        SCOPED_TRACE(sign > 0 ? "+X" : "-X");
        int end = -1;
        for (int b : children(a, 0))
            if (a.branches[std::size_t(b)].direction.isApprox(sign * Vector3d::UnitX())) end = b;
        ASSERT_GE(end, 0);
        const auto& nodes = a.branches[std::size_t(end)].nodes;
        // From the neck's side (x = 5, at most a step on) to the hub's end, on the hub's axis
        // up to the deflection once past the first plane (which may still cut the neck).
        EXPECT_LE(sign * a.nodes[std::size_t(nodes.front())].position.x(), 5.0 + p.step_mm);
        EXPECT_GE(sign * a.nodes[std::size_t(nodes.back())].position.x(), 20.0 - p.step_mm);
        for (std::size_t i = 1; i < nodes.size(); ++i) {
            const auto& node = a.nodes[std::size_t(nodes[i])];
            EXPECT_NEAR(node.position.y(), 0.0, kDeflection);
            EXPECT_NEAR(node.position.z(), 30.0, kDeflection);
        }
    }
    expect_invariants(a, mesh);
}

TEST(CentroidalAxis, InwardLipOfATubeStaysWithItsMarch) {
    // A tube (radius 30, bore 25) standing on its rim, its top 10 mm a lip reaching in to a bore
    // of 10. Over the tube's ring the lip's sections stick out inwards: an annulus whose centre
    // lies in the bore, inside the lower ring's external contour (Eq. 2), 25 mm from its material.
    // It lies beyond no side of that section, so no march in another direction could reach it: it
    // is no turn, the march goes on with it.
    // (Taken for a turn it went to a march starting past the tube's outside, and the whole lip
    // was never searched.)
    const TopoDS_Shape tube =
        BRepAlgoAPI_Cut(
            BRepAlgoAPI_Cut(BRepPrimAPI_MakeCylinder(30, 40).Shape(),
                            BRepPrimAPI_MakeCylinder(25, 30).Shape())
                .Shape(),
            BRepPrimAPI_MakeCylinder(gp_Ax2(gp_Pnt(0, 0, 29), gp_Dir(0, 0, 1)), 10, 12).Shape())
            .Shape();
    const auto mesh = mesh_of(from_occt(tube));
    mas::AxisParams p;
    p.step_mm = 2.0;
    const auto a = mas::centroidal_axis(mesh, p);
    ASSERT_EQ(a.branches.size(), 1u);
    ASSERT_EQ(a.nodes.size(), 20u);  // z = 0.001 ... 38.001
    for (const auto& node : a.nodes) {
        const double r_in = node.position.z() < 30.0 ? 25.0 : 10.0;
        // Inscribed polygons: each circle's area is short by at most its perimeter x deflection.
        const double exact = kPi * (30.0 * 30.0 - r_in * r_in);
        EXPECT_NEAR(node.area, exact, 2.0 * kPi * (30.0 + r_in) * kDeflection)
            << "z = " << node.position.z();
        EXPECT_NEAR(node.position.x(), 0.0, kDeflection);
        EXPECT_NEAR(node.position.y(), 0.0, kDeflection);
    }
    expect_invariants(a, mesh, false);  // a ring's centroid is in its bore
}

TEST(CentroidalAxis, TracksSplitAroundAHoleRecordWhereTheyMerge) {
    // A 12 x 40 wall on a plate with a horizontal hole (radius 6, along X, at y = 20, z = 30): the
    // wall's sections split in two around the hole and join again above it.
    const TopoDS_Shape wall = fuse(occ_box(0, 0, 0, 60, 40, 10), occ_box(0, 0, 10, 12, 40, 40));
    const TopoDS_Shape hole =
        BRepPrimAPI_MakeCylinder(gp_Ax2(gp_Pnt(-1, 20, 30), gp_Dir(1, 0, 0)), 6, 14).Shape();
    const auto mesh = mesh_of(from_occt(BRepAlgoAPI_Cut(wall, hole).Shape()));
    mas::AxisParams p;
    p.step_mm = 2.0;
    const auto a = mas::centroidal_axis(mesh, p);
    const auto kids = children(a, 0);
    ASSERT_EQ(kids.size(), 2u);
    const auto& first = a.branches[std::size_t(kids[0])];
    const auto& second = a.branches[std::size_t(kids[1])];
    EXPECT_TRUE(first.direction.isApprox(Vector3d::UnitZ()));
    EXPECT_TRUE(second.direction.isApprox(Vector3d::UnitZ()));
    // One of them ends where they join, merged into the other, which goes on to the top; the
    // material bridging the hole's top joins them (no sideways branch, no further split).
    const bool first_goes_on = first.merged_into < 0;
    EXPECT_EQ(first_goes_on ? second.merged_into : first.merged_into,
              first_goes_on ? kids[0] : kids[1]);
    EXPECT_EQ(first_goes_on ? first.merged_into : second.merged_into, -1);
    EXPECT_EQ(a.branches.size(), 3u);
    const auto& on = first_goes_on ? first : second;
    EXPECT_NEAR(a.nodes[std::size_t(on.nodes.back())].position.z(), 48.001, 1e-9);
    EXPECT_EQ(a.branches[0].merged_into, -1);
    expect_invariants(a, mesh, false);  // beside the hole, a section's centroid is in the hole
}

TEST(CentroidalAxis, IsTheSameRunAfterRun) {
    // The march works planes out ahead on a second thread: the result must not depend on timing.
    const TopoDS_Shape part =
        fuse(fuse(occ_box(0, 0, 0, 60, 40, 10), occ_box(0, 0, 10, 12, 40, 50)),
             BRepPrimAPI_MakeCylinder(gp_Ax2(gp_Pnt(40, 20, 10), gp_Dir(0, 0, 1)), 8, 30).Shape());
    const auto mesh = mesh_of(from_occt(part));
    mas::AxisParams p;
    p.step_mm = 0.5;
    const auto first = mas::centroidal_axis(mesh, p);
    for (int run = 0; run < 10; ++run) {
        const auto again = mas::centroidal_axis(mesh, p);
        ASSERT_EQ(again.nodes.size(), first.nodes.size());
        ASSERT_EQ(again.links.size(), first.links.size());
        ASSERT_EQ(again.branches.size(), first.branches.size());
        for (std::size_t i = 0; i < first.nodes.size(); ++i) {
            EXPECT_EQ(again.nodes[i].position, first.nodes[i].position) << i;
            EXPECT_EQ(again.nodes[i].area, first.nodes[i].area) << i;
            EXPECT_EQ(again.nodes[i].branch, first.nodes[i].branch) << i;
        }
        for (std::size_t b = 0; b < first.branches.size(); ++b)
            EXPECT_EQ(again.branches[b].merged_into, first.branches[b].merged_into) << b;
        EXPECT_EQ(again.sections_cut, first.sections_cut);
        EXPECT_EQ(again.searched_volume_mm3, first.searched_volume_mm3);
    }
}
