#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "SectionGrid.hpp"
#include "mas/Angles.hpp"
#include "mas/Error.hpp"
#include "mas/Section.hpp"
#include "mas/Shape.hpp"
#include "test_parts.hpp"

using Eigen::Vector3d;
using mas::kPi;

namespace {

mas::Plane plane(double ox, double oy, double oz, double nx, double ny, double nz) {
    return mas::make_plane({ox, oy, oz}, {nx, ny, nz});
}

void expect_near(const Vector3d& a, const Vector3d& b, double tol) {
    EXPECT_LE((a - b).norm(), tol)
        << "got (" << a.transpose() << "), want (" << b.transpose() << ")";
}

// A tessellated solid and the deflection it was meshed with.
struct Meshed {
    mas::TriangleMesh mesh;
    double deflection;
};

Meshed mesh_of(const mas::Shape& s) {
    mas::TessellationParams p;
    p.deflection_mm = 0.02;
    return {mas::tessellate(s, p), p.deflection_mm};
}

}  // namespace

TEST(SectionExactMesh, HorizontalPlaneThroughBoxGivesFootprint) {
    const auto m = mas::test::box_mesh(0, 0, 0, 10, 20, 30);
    const auto s = mas::slice_mesh(m, plane(0, 0, 7, 0, 0, 1));
    ASSERT_EQ(s.regions.size(), 1u);
    EXPECT_TRUE(s.regions[0].shape.holes.empty());
    EXPECT_NEAR(s.area, 200.0, 1e-9);
    expect_near(s.centroid, {5, 10, 7}, 1e-12);
    EXPECT_GT(mas::signed_area(s.regions[0].shape.outer), 0.0);  // CCW seen from above
    EXPECT_EQ(s.open_chains, 0u);
    EXPECT_NEAR(s.regions[0].bounds.min().z(), 7.0, 1e-12);
    expect_near(s.regions[0].bounds.max(), {10, 20, 7}, 1e-12);
}

TEST(SectionExactMesh, SidewaysPlaneThroughBox) {
    const auto m = mas::test::box_mesh(0, 0, 0, 10, 20, 30);
    for (double sign : {1.0, -1.0}) {
        const auto s = mas::slice_mesh(m, plane(3, 0, 0, sign, 0, 0));
        ASSERT_EQ(s.regions.size(), 1u);
        EXPECT_NEAR(s.area, 600.0, 1e-9);
        expect_near(s.centroid, {3, 10, 15}, 1e-12);
        EXPECT_GT(mas::signed_area(s.regions[0].shape.outer), 0.0);
    }
}

TEST(SectionExactMesh, TiltedPlaneThroughBoxCentre) {
    // Tilted 30 degrees about X: the section is a 10 x (20 / cos 30) rectangle as long as it
    // stays between the top and bottom faces (10 tan 30 = 5.8 < 15).
    const auto m = mas::test::box_mesh(0, 0, 0, 10, 20, 30);
    const double a = kPi / 6;
    const auto s = mas::slice_mesh(m, plane(5, 10, 15, 0, std::sin(a), std::cos(a)));
    ASSERT_EQ(s.regions.size(), 1u);
    EXPECT_NEAR(s.area, 10.0 * 20.0 / std::cos(a), 1e-9);
    expect_near(s.centroid, {5, 10, 15}, 1e-9);
}

TEST(SectionExactMesh, PlaneOnAFaceBelongsToTheSlabBelow) {
    const auto m = mas::test::box_mesh(0, 0, 0, 10, 20, 30);
    EXPECT_TRUE(mas::slice_mesh(m, plane(0, 0, 0, 0, 0, 1)).empty());  // bottom: nothing below
    EXPECT_NEAR(mas::slice_mesh(m, plane(0, 0, 30, 0, 0, 1)).area, 200.0, 1e-9);  // top: all
    EXPECT_TRUE(mas::slice_mesh(m, plane(0, 0, 30.001, 0, 0, 1)).empty());
}

TEST(SectionExactMesh, PlaneThroughVerticesOfAnOctahedron) {
    // Every crossing point is a mesh vertex: chains must still close, with the equatorial square.
    mas::TriangleMesh m;
    m.vertices = {{1, 0, 0}, {0, 1, 0}, {-1, 0, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
    for (int i = 0; i < 4; ++i) {
        m.triangles.emplace_back(i, (i + 1) % 4, 4);
        m.triangles.emplace_back((i + 1) % 4, i, 5);
    }
    ASSERT_TRUE(mas::check_mesh(m).closed());
    const auto s = mas::slice_mesh(m, plane(0, 0, 0, 0, 0, 1));
    ASSERT_EQ(s.regions.size(), 1u);
    EXPECT_EQ(s.regions[0].shape.outer.points.size(), 4u);
    EXPECT_NEAR(s.area, 2.0, 1e-12);
    EXPECT_EQ(s.open_chains, 0u);
}

TEST(SectionBatch, ManyPlanesInAnyOrderMatchOneByOne) {
    const auto m = mas::test::box_mesh(0, 0, 0, 10, 20, 30);
    std::vector<mas::Plane> planes = {plane(0, 0, 20, 0, 0, 1), plane(0, 0, 5, 0, 0, 1),
                                      plane(4, 0, 0, 1, 0, 0),  plane(0, 0, 5, 0, 0, 1),
                                      plane(0, 0, 99, 0, 0, 1), plane(0, 7, 0, 0, 2, 0)};
    const auto batch = mas::slice_mesh(m, planes);
    ASSERT_EQ(batch.size(), planes.size());
    for (std::size_t i = 0; i < planes.size(); ++i) {
        const auto one = mas::slice_mesh(m, planes[i]);
        EXPECT_DOUBLE_EQ(batch[i].area, one.area) << i;
        expect_near(batch[i].centroid, one.centroid, 1e-12);
        expect_near(batch[i].plane.origin, planes[i].origin, 0.0);
    }
    EXPECT_TRUE(batch[4].empty());
    EXPECT_NEAR(batch[5].area, 300.0, 1e-9);
    EXPECT_NEAR(batch[5].plane.normal.norm(), 1.0, 1e-15);
}

TEST(SectionGrid, CutAtAnyOffsetIsSliceMeshsSection) {
    // The axis cuts planes between a grid's own (a ledge's half-step test) from the facets that
    // reach them: the same section as slice_mesh's, between the grid's planes, on one, below and
    // above them all, and through the torus' equator and its lowest vertices, which lie on the
    // plane (a vertex on it counts as above: the plane at z = -5 cuts nothing).
    const auto torus = mesh_of(mas::test::torus(20.0, 5.0)).mesh;
    std::vector<mas::Plane> planes;
    for (int i = 0; i < 5; ++i) planes.push_back(plane(0, 0, -4.0 + 2.0 * i, 0, 0, 1));
    const mas::SectionGrid grid(torus, planes);
    for (double z : {-4.5, -3.0, -2.0, 0.0, 0.7, 3.999, 5.5, -5.0, -6.0}) {
        SCOPED_TRACE(z);
        const mas::Section at = grid.cut_at(z);
        const mas::Section want = mas::slice_mesh(torus, plane(0, 0, z, 0, 0, 1));
        ASSERT_EQ(at.regions.size(), want.regions.size());
        EXPECT_DOUBLE_EQ(at.area, want.area);
        expect_near(at.centroid, want.centroid, 1e-9);
        expect_near(at.plane.origin, want.plane.origin, 0.0);
        for (std::size_t r = 0; r < at.regions.size(); ++r) {
            EXPECT_DOUBLE_EQ(at.regions[r].area, want.regions[r].area);
            EXPECT_EQ(at.regions[r].shape.holes.size(), want.regions[r].shape.holes.size());
        }
    }
    EXPECT_TRUE(grid.cut_at(-5.0).empty());
    EXPECT_TRUE(grid.cut_at(5.5).empty());
    EXPECT_EQ(grid.cut_at(0.0).regions.size(), 1u);  // the annulus
    EXPECT_EQ(grid.cut_at(0.0).regions[0].shape.holes.size(), 1u);
}

TEST(SectionBatch, TotalsOnlyModeAgreesWithRegions) {
    const auto part = mesh_of(mas::test::plate_with_hole());
    const auto planes = mas::parallel_planes(part.mesh, {0, 0, 1}, 1.0);
    mas::SliceParams totals;
    totals.build_regions = false;
    const auto a = mas::slice_mesh(part.mesh, planes);
    const auto b = mas::slice_mesh(part.mesh, planes, totals);
    for (std::size_t i = 0; i < planes.size(); ++i) {
        EXPECT_NEAR(a[i].area, b[i].area, 1e-9 * a[i].area);
        expect_near(a[i].centroid, b[i].centroid, 1e-9);
        EXPECT_TRUE(b[i].regions.empty());
    }
}

TEST(SectionBatch, CancelStopsTheWork) {
    const auto m = mas::test::box_mesh(0, 0, 0, 1, 1, 1);
    const auto planes = mas::parallel_planes(m, {0, 0, 1}, 0.01);
    try {
        mas::slice_mesh(m, planes, {}, [] { throw mas::Error(mas::ErrorCode::Cancelled, "stop"); });
        FAIL() << "not cancelled";
    } catch (const mas::Error& e) {
        EXPECT_EQ(e.code(), mas::ErrorCode::Cancelled);
    }
}

TEST(SectionPointCounts, CountWhatEachPlaneCutsWithoutCutting) {
    // A 12-facet box: a plane across it crosses the 8 facets of four sides, one point each. A
    // vertex on a plane counts as above it: the bottom (z = 0) is not cut, the top (z = 10) is,
    // as slice_mesh() cuts them. Duplicates count for each plane.
    const auto box = mas::test::box_mesh(0, 0, 0, 10, 10, 10);
    const std::vector<mas::Plane> planes = {plane(0, 0, 5, 0, 0, 1),  plane(0, 0, 0, 0, 0, 1),
                                            plane(0, 0, 10, 0, 0, 1), plane(0, 0, 12, 0, 0, 1),
                                            plane(3, 0, 0, 2, 0, 0),  plane(0, 0, 5, 0, 0, 1)};
    EXPECT_EQ(mas::section_point_counts(box, planes), (std::vector<std::size_t>{8, 0, 8, 0, 8, 8}));
    EXPECT_TRUE(mas::slice_mesh(box, planes[1]).empty());
    EXPECT_FALSE(mas::slice_mesh(box, planes[2]).empty());

    // On a tessellated sphere, along two normals at once: the points of every loop slice_mesh()
    // builds, outer loops and holes.
    const auto sphere = mesh_of(mas::test::sphere(10.0)).mesh;
    std::vector<mas::Plane> mixed = mas::parallel_planes(sphere, {1, 2, 3}, 0.7);
    for (const auto& p : mas::parallel_planes(sphere, {0, 0, 1}, 1.3)) mixed.push_back(p);
    const auto counts = mas::section_point_counts(sphere, mixed);
    const auto sections = mas::slice_mesh(sphere, mixed);
    ASSERT_EQ(counts.size(), mixed.size());
    std::size_t total = 0;
    for (std::size_t i = 0; i < mixed.size(); ++i) {
        std::size_t points = 0;
        for (const auto& r : sections[i].regions) {
            points += r.shape.outer.points.size();
            for (const auto& hole : r.shape.holes) points += hole.points.size();
        }
        EXPECT_EQ(counts[i], points) << "plane " << i;
        total += counts[i];
    }
    EXPECT_GT(total, 1000u);
}

TEST(SectionPlanes, ParallelPlanesSitInTheMiddleOfTheirSlabs) {
    const auto m = mas::test::box_mesh(0, 0, 0, 10, 10, 10);
    const auto planes = mas::parallel_planes(m, {0, 0, 2}, 2.5);
    ASSERT_EQ(planes.size(), 4u);
    EXPECT_NEAR(planes[0].origin.z(), 1.25, 1e-12);
    EXPECT_NEAR(planes[3].origin.z(), 8.75, 1e-12);
    const auto partial = mas::parallel_planes(m, {0, 0, 1}, 3.0);  // 3 full slabs + 1 mm left over
    ASSERT_EQ(partial.size(), 4u);
    EXPECT_NEAR(partial[3].origin.z(), 9.5, 1e-12);
}

TEST(SectionErrors, BadPlanesAndStepsAreNamed) {
    const auto m = mas::test::box_mesh(0, 0, 0, 1, 1, 1);
    const double nan = std::numeric_limits<double>::quiet_NaN();
    auto expect_invalid = [](const std::function<void()>& f, const std::string& word) {
        try {
            f();
            ADD_FAILURE() << "no error for " << word;
        } catch (const mas::Error& e) {
            EXPECT_EQ(e.code(), mas::ErrorCode::InvalidArgument);
            EXPECT_NE(std::string(e.what()).find(word), std::string::npos) << e.what();
        }
    };
    expect_invalid([&] { mas::slice_mesh(m, mas::Plane{{0, 0, 0}, {0, 0, 0}}); }, "zero vector");
    expect_invalid([&] { mas::slice_mesh(m, mas::Plane{{0, 0, nan}, {0, 0, 1}}); }, "NaN");
    expect_invalid([&] { mas::parallel_planes(m, {0, 0, 1}, 0.0); }, "step");
    expect_invalid([&] { mas::parallel_planes(m, {0, 0, 1}, -1.0); }, "step");
    // The value is shown as given, however small (not as std::to_string's "-0.000000").
    expect_invalid([&] { mas::parallel_planes(m, {0, 0, 1}, -2.5e-7); }, "(got -2.5e-07)");
    expect_invalid([&] { mas::parallel_planes(m, {0, 0, 1}, nan); }, "step");
    expect_invalid([&] { mas::parallel_planes(m, {0, 0, 0}, 1.0); }, "zero vector");
    expect_invalid([&] { mas::make_plane({0, 0, 0}, {1e-13, 0, 0}); }, "zero vector");
    // A normal whose length overflows is still a direction (it came out as the zero vector).
    const Vector3d diagonal = Vector3d::Ones().normalized();
    expect_near(mas::make_plane({0, 0, 0}, {1e300, 1e300, 1e300}).normal, diagonal, 1e-15);
    expect_near(mas::parallel_planes(m, {1e300, 1e300, 1e300}, 0.5).front().normal, diagonal,
                1e-15);
    expect_near(mas::make_plane({0, 0, 0}, {0, -1e308, 0}).normal, {0, -1, 0}, 0.0);
    // 1 mm / 1e-5 mm is exactly the limit; a hair less is over it, named before any is cut.
    EXPECT_EQ(mas::parallel_planes(m, {0, 0, 1}, 1.0 / double(mas::kMaxParallelPlanes)).size(),
              mas::kMaxParallelPlanes);
    expect_invalid([&] { mas::parallel_planes(m, {0, 0, 1}, 0.99e-5); }, "too small");
    expect_invalid([&] { mas::parallel_planes(m, {0, 0, 1}, 1e-12); }, "100000");
}

// ---- tessellated parts (mesh kernel on OCCT's tessellation) -------------------------------------

TEST(SectionParts, LBlockColumnThenArm) {
    const auto part = mesh_of(mas::test::l_block());
    const auto column = mas::slice_mesh(part.mesh, plane(0, 0, 20, 0, 0, 1));
    ASSERT_EQ(column.regions.size(), 1u);
    EXPECT_NEAR(column.area, 400.0, 1e-6);
    expect_near(column.centroid, {10, 10, 20}, 1e-9);
    const auto arm = mas::slice_mesh(part.mesh, plane(0, 0, 50, 0, 0, 1));
    ASSERT_EQ(arm.regions.size(), 1u);
    EXPECT_NEAR(arm.area, 70.0 * 20.0, 1e-6);
    expect_near(arm.centroid, {35, 10, 50}, 1e-9);
    const auto across_arm = mas::slice_mesh(part.mesh, plane(45, 0, 0, 1, 0, 0));
    EXPECT_NEAR(across_arm.area, 400.0, 1e-6);
    expect_near(across_arm.centroid, {45, 10, 50}, 1e-9);
}

TEST(SectionParts, PlateWithHoleHasOneOuterLoopAndOneHole) {
    const auto part = mesh_of(mas::test::plate_with_hole());
    const auto s = mas::slice_mesh(part.mesh, plane(0, 0, 5, 0, 0, 1));
    ASSERT_EQ(s.regions.size(), 1u);
    ASSERT_EQ(s.regions[0].shape.holes.size(), 1u);
    EXPECT_LT(mas::signed_area(s.regions[0].shape.holes[0]), 0.0);
    // The hole is an inscribed polygon of the r = 8 circle, at most `deflection` inside it:
    // the plate's area is exact minus up to perimeter x deflection, never more than exact.
    const double r = 8.0, exact = 60.0 * 40.0 - kPi * r * r;
    EXPECT_GE(s.area, exact - 1e-9);
    EXPECT_LE(s.area, exact + 2 * kPi * r * part.deflection);
    const double hole_area = -mas::signed_area(s.regions[0].shape.holes[0]);
    const Eigen::Vector2d hole_c = mas::centroid(s.regions[0].shape.holes[0]);
    EXPECT_LE((hole_c - Eigen::Vector2d(30, 20)).norm(), part.deflection);
    EXPECT_GE(hole_area, kPi * r * r - 2 * kPi * r * part.deflection);
}

TEST(SectionParts, TwoPostsGiveTwoRegions) {
    const auto part = mesh_of(mas::test::two_posts());
    const auto s = mas::slice_mesh(part.mesh, plane(0, 0, 15, 0, 0, 1));
    ASSERT_EQ(s.regions.size(), 2u);
    std::vector<double> xs = {s.regions[0].centroid.x(), s.regions[1].centroid.x()};
    std::sort(xs.begin(), xs.end());
    EXPECT_NEAR(xs[0], 5.0, 1e-9);
    EXPECT_NEAR(xs[1], 35.0, 1e-9);
    EXPECT_NEAR(s.regions[0].area, 100.0, 1e-9);
    EXPECT_NEAR(s.regions[1].area, 100.0, 1e-9);
    const auto base = mas::slice_mesh(part.mesh, plane(0, 0, 2.5, 0, 0, 1));
    ASSERT_EQ(base.regions.size(), 1u);
    EXPECT_NEAR(base.area, 400.0, 1e-9);
}

TEST(SectionParts, CylinderAcrossAndTiltedWithinDeflection) {
    const double r = 10.0, h = 40.0;
    const auto part = mesh_of(mas::test::cylinder({0, 0, 0}, {0, 0, 1}, r, h));
    const double d = part.deflection;
    const auto s = mas::slice_mesh(part.mesh, plane(0, 0, 20, 0, 0, 1));
    ASSERT_EQ(s.regions.size(), 1u);
    // Inscribed polygon: never larger than the disc, smaller by at most perimeter x deflection.
    EXPECT_LE(s.area, kPi * r * r + 1e-9);
    EXPECT_GE(s.area, kPi * r * r - 2 * kPi * r * d);
    expect_near(s.centroid, {0, 0, 20}, d);
    // Tilted 40 degrees: an ellipse with semi-axes r and r / cos a; along the major axis the
    // facets' radial error d shows up as d / cos a in the plane.
    const double a = 40.0 * kPi / 180.0;
    const auto t = mas::slice_mesh(part.mesh, plane(0, 0, 20, std::sin(a), 0, std::cos(a)));
    ASSERT_EQ(t.regions.size(), 1u);
    const double major = r / std::cos(a), exact = kPi * r * major;
    EXPECT_LE(t.area, exact + 1e-9);
    EXPECT_GE(t.area, exact - 2 * kPi * major * d / std::cos(a));
    expect_near(t.centroid, {0, 0, 20}, d / std::cos(a));
}

TEST(SectionParts, TorusThroughItsHoleGivesAnAnnulusAndAcrossTwoDiscs) {
    const double R = 30.0, r = 8.0;
    const auto part = mesh_of(mas::test::torus(R, r));
    const double d = part.deflection;
    const auto mid = mas::slice_mesh(part.mesh, plane(0, 0, 0.0001, 0, 0, 1));
    ASSERT_EQ(mid.regions.size(), 1u);
    ASSERT_EQ(mid.regions[0].shape.holes.size(), 1u);
    const double annulus = kPi * ((R + r) * (R + r) - (R - r) * (R - r));
    EXPECT_NEAR(mid.area, annulus, 2 * kPi * (2 * R) * d + 1e-3);
    const auto across = mas::slice_mesh(part.mesh, plane(0, 0, 0, 0, 1, 0));
    ASSERT_EQ(across.regions.size(), 2u);
    EXPECT_LE(across.area, 2 * kPi * r * r + 1e-9);
    EXPECT_GE(across.area, 2 * kPi * r * r - 2 * 2 * kPi * r * d);
    expect_near(across.centroid, {0, 0, 0}, d);
}
