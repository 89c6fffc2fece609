#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <limits>
#include <string>
#include <tuple>
#include <vector>

#include "mas/Error.hpp"
#include "mas/Mesh.hpp"
#include "test_parts.hpp"

using mas::ErrorCode;

namespace {

ErrorCode code_of(const std::function<void()>& f) {
    try {
        f();
    } catch (const mas::Error& e) {
        return e.code();
    }
    ADD_FAILURE() << "no mas::Error thrown";
    return ErrorCode::Cancelled;
}

// "code: message" of the mas::Error `f` throws ("", and a failure, when it throws none).
std::string error_of(const std::function<void()>& f) {
    try {
        f();
    } catch (const mas::Error& e) {
        return std::string(to_string(e.code())) + ": " + e.what();
    }
    ADD_FAILURE() << "no mas::Error thrown";
    return "";
}

std::string temp_file(const std::string& name, const std::string& text) {
    const std::string path = ::testing::TempDir() + name;
    std::ofstream(path) << text;
    return path;
}

}  // namespace

TEST(MeshCheck, BoxIsClosedWithExactVolume) {
    const auto r = mas::check_mesh(mas::test::box_mesh(1, 2, 3, 10, 20, 30));
    EXPECT_TRUE(r.closed());
    EXPECT_EQ(r.boundary_edges, 0u);
    EXPECT_NEAR(r.volume_mm3, 6000.0, 1e-9);
}

TEST(MeshCheck, MissingTriangleLeavesThreeBoundaryEdges) {
    auto m = mas::test::box_mesh(0, 0, 0, 1, 1, 1);
    m.triangles.pop_back();
    const auto r = mas::check_mesh(m);
    EXPECT_EQ(r.boundary_edges, 3u);
    EXPECT_FALSE(r.closed());
    EXPECT_EQ(code_of([&] { mas::require_closed_mesh(m, "box"); }), ErrorCode::OpenMesh);
}

TEST(MeshCheck, FlippedTriangleIsInconsistent) {
    auto m = mas::test::box_mesh(0, 0, 0, 1, 1, 1);
    std::swap(m.triangles[0][1], m.triangles[0][2]);
    EXPECT_EQ(mas::check_mesh(m).inconsistent_edges, 3u);
    EXPECT_EQ(code_of([&] { mas::require_closed_mesh(m, "box"); }), ErrorCode::OpenMesh);
}

TEST(MeshCheck, NanVertexIsRejectedByName) {
    auto m = mas::test::box_mesh(0, 0, 0, 1, 1, 1);
    m.vertices[3].x() = std::numeric_limits<double>::quiet_NaN();
    const std::string error = error_of([&] { mas::require_closed_mesh(m, "part.stl"); });
    EXPECT_EQ(error.rfind("non_finite_coordinate: ", 0), 0u) << error;
    EXPECT_NE(error.find("part.stl"), std::string::npos) << error;
}

TEST(MeshCheck, VolumesOfPartsFarFromTheOriginAreExact) {
    // Summed from the origin, the tetrahedra of a box 1e8 mm out are some 1e23 mm^3 each and
    // cancel to noise: a sphere there came out negative and was turned inside out. From one of
    // the mesh's own vertices the sums are the box's own size.
    auto far = mas::test::box_mesh(1e8, -1e8, 1e8, 10, 20, 30);
    EXPECT_NEAR(mas::check_mesh(far).volume_mm3, 6000.0, 1e-6);
    EXPECT_NEAR(mas::mesh_volume(far), 6000.0, 1e-6);
    const auto before = far.triangles;
    mas::require_closed_mesh(far, "far.stl");
    EXPECT_EQ(far.triangles, before);  // not flipped
    const auto s = mas::slice_mesh(far, mas::make_plane({0, 0, 1e8 + 15}, {0, 0, 1}));
    EXPECT_NEAR(s.area, 200.0, 1e-6);
}

TEST(MeshCheck, CoordinatesBeyondTheRangeAreRejectedByName) {
    // A cube 1e301 mm on a side gave an infinite section area and a NaN centroid (invalid JSON,
    // exit status 0). Up to kMaxCoordinateMm (1e9 mm) from the origin along each axis is fine.
    auto far = mas::test::box_mesh(-1e9, 0, 0, 1, 1, 1);
    EXPECT_NO_THROW(mas::require_closed_mesh(far, "far.stl"));
    far = mas::test::box_mesh(0, 0, 0, 1, 1, 2e9);
    EXPECT_EQ(error_of([&] { mas::require_closed_mesh(far, "tall.stl"); }),
              "non_finite_coordinate: tall.stl: a vertex lies 2e+09 mm from the origin along an "
              "axis, beyond the 1e+09 mm (1000 km) the engine works within");
    auto huge = mas::test::box_mesh(0, 0, 0, 1e301, 1e301, 1e301);
    EXPECT_EQ(code_of([&] { mas::require_closed_mesh(huge, "huge"); }),
              ErrorCode::NonFiniteCoordinate);
}

TEST(MeshCheck, EmptyMeshIsEmptyInput) {
    mas::TriangleMesh m;
    EXPECT_EQ(code_of([&] { mas::require_closed_mesh(m, "x"); }), ErrorCode::EmptyInput);
    // Closed and consistent, but folded flat: its top lies on its bottom.
    auto flat = mas::test::box_mesh(0, 0, 0, 10, 10, 0);
    EXPECT_EQ(error_of([&] { mas::require_closed_mesh(flat, "flat.off"); }),
              "empty_input: flat.off: the mesh encloses no volume (0 mm^3 within a box 14.1421 "
              "mm across)");
    auto thin = mas::test::box_mesh(0, 0, 0, 1000, 1000, 1e-3);  // a foil still holds material
    EXPECT_NO_THROW(mas::require_closed_mesh(thin, "foil.off"));
}

TEST(MeshCheck, InsideOutMeshIsFlippedNotRejected) {
    auto m = mas::test::box_mesh(0, 0, 0, 2, 2, 2);
    for (auto& t : m.triangles) std::swap(t[1], t[2]);
    EXPECT_LT(mas::check_mesh(m).volume_mm3, 0.0);
    mas::require_closed_mesh(m, "box");
    EXPECT_NEAR(mas::check_mesh(m).volume_mm3, 8.0, 1e-12);
}

namespace {

// Boxes (x0, y0, z0, dx, dy, dz) as the shells of one mesh, those marked inward facing in.
mas::TriangleMesh shells(const std::vector<std::array<double, 6>>& boxes,
                         const std::vector<bool>& inward) {
    mas::TriangleMesh out;
    for (std::size_t b = 0; b < boxes.size(); ++b) {
        const auto& x = boxes[b];
        auto m = mas::test::box_mesh(x[0], x[1], x[2], x[3], x[4], x[5]);
        const int base = int(out.vertices.size());
        for (const auto& v : m.vertices) out.vertices.push_back(v);
        for (auto t : m.triangles) {
            if (inward[b]) std::swap(t[1], t[2]);
            out.triangles.push_back(t.array() + base);
        }
    }
    return out;
}

std::string shell_error(mas::TriangleMesh m) {
    try {
        mas::require_closed_mesh(m, "part.stl");
        mas::require_one_solid(m, "part.stl");
    } catch (const mas::Error& e) {
        EXPECT_EQ(e.code(), ErrorCode::NotASolid) << e.what();
        return e.what();
    }
    return "";
}

}  // namespace

TEST(MeshCheck, ShellsMustBoundOneSolid) {
    // Solids: two bodies apart; a box with a cavity (its shell facing in); an island in the
    // cavity (facing out again).
    EXPECT_EQ(shell_error(shells({{0, 0, 0, 10, 10, 10}, {20, 0, 0, 10, 10, 10}}, {0, 0})), "");
    EXPECT_EQ(shell_error(shells({{0, 0, 0, 10, 10, 10}, {2, 2, 2, 6, 6, 6}}, {0, 1})), "");
    EXPECT_EQ(shell_error(shells({{0, 0, 0, 10, 10, 10}, {2, 2, 2, 6, 6, 6}, {4, 4, 4, 2, 2, 2}},
                                 {0, 1, 0})),
              "");
    // Not: two boxes overlapping (sliced as 2000 mm^3 of which 1750 exist), one inside another
    // facing the same way, a body on its own inside out.
    EXPECT_NE(shell_error(shells({{0, 0, 0, 10, 10, 10}, {7.5, 0, 0, 10, 10, 10}}, {0, 0}))
                  .find("lies inside another but faces out (overlapping shells, or a cavity"),
              std::string::npos);
    EXPECT_NE(shell_error(shells({{0, 0, 0, 10, 10, 10}, {2, 2, 2, 6, 6, 6}}, {0, 0}))
                  .find("shell 2 (12 triangles, facing out) lies inside another"),
              std::string::npos);
    EXPECT_NE(shell_error(shells({{0, 0, 0, 10, 10, 10}, {20, 0, 0, 1, 1, 1}}, {0, 1}))
                  .find("faces in (inside out)"),
              std::string::npos);
    // An island in a cavity touching it at one corner: a tetrahedron with a vertex of its own on
    // the cavity's corner (2, 2, 2). A point there is on the cavity, not inside or outside it.
    auto island = shells({{0, 0, 0, 10, 10, 10}, {2, 2, 2, 6, 6, 6}}, {0, 1});
    const int base = int(island.vertices.size());
    for (const Eigen::Vector3d& v : {Eigen::Vector3d(2, 2, 2), Eigen::Vector3d(5, 3, 3),
                                     Eigen::Vector3d(3, 5, 3), Eigen::Vector3d(3, 3, 5)})
        island.vertices.push_back(v);
    for (const Eigen::Vector3i& t : {Eigen::Vector3i(0, 2, 1), Eigen::Vector3i(0, 1, 3),
                                     Eigen::Vector3i(0, 3, 2), Eigen::Vector3i(1, 2, 3)})
        island.triangles.push_back(t.array() + base);
    // Facing out: the box less the cavity plus the tetrahedron, 1000 - 216 + 20 / 6 mm^3.
    ASSERT_NEAR(mas::check_mesh(island).volume_mm3, 784.0 + 20.0 / 6.0, 1e-9);
    EXPECT_EQ(shell_error(island), "");
    // Two cubes overlapping at a corner, in a 5 mm cube: no facet centre of either lies in the
    // other, but a corner does (sliced as 2000 mm^3 of which 1875 exist, the overlap twice).
    EXPECT_NE(shell_error(shells({{0, 0, 0, 10, 10, 10}, {5, 5, 5, 10, 10, 10}}, {0, 0}))
                  .find("lies inside another but faces out (overlapping shells"),
              std::string::npos);
}

TEST(MeshCheck, CubesTouchingAlongAnEdgeAreNonManifold) {
    // Two unit cubes sharing only the edge x = y = 1, z in [0,1]: welded, each cube's two faces
    // at that edge make it an edge of four triangles (Mesh.hpp: non-manifold, more than two), and
    // no closed surface. Every other edge is used twice, consistently.
    auto m = shells({{0, 0, 0, 1, 1, 1}, {1, 1, 0, 1, 1, 1}}, {0, 0});
    EXPECT_EQ(mas::weld_vertices(m, 1e-9), 2u);  // the shared edge's two ends
    const auto r = mas::check_mesh(m);
    EXPECT_EQ(r.non_manifold_edges, 1u);
    EXPECT_EQ(r.boundary_edges, 0u);
    EXPECT_EQ(r.inconsistent_edges, 0u);
    EXPECT_FALSE(r.closed());
    EXPECT_EQ(code_of([&] { mas::require_closed_mesh(m, "cubes"); }), ErrorCode::OpenMesh);
}

TEST(MeshWeld, TriangleSoupBecomesClosed) {
    const auto indexed = mas::test::box_mesh(0, 0, 0, 1, 1, 1);
    mas::TriangleMesh soup;
    for (const auto& t : indexed.triangles) {
        const int base = static_cast<int>(soup.vertices.size());
        for (int k = 0; k < 3; ++k) soup.vertices.push_back(indexed.vertices[t[k]]);
        soup.triangles.emplace_back(base, base + 1, base + 2);
    }
    EXPECT_FALSE(mas::check_mesh(soup).closed());
    EXPECT_EQ(mas::weld_vertices(soup, 1e-9), 36u - 8u);
    EXPECT_TRUE(mas::check_mesh(soup).closed());
}

// The same box with its vertices listed backwards, its triangles reversed in order and each one's
// corners turned round: in canonical order both are the same mesh, vertices sorted by x, y, z,
// each triangle starting at its least vertex with its turn (the outward orientation) kept.
TEST(MeshOrder, TheSameSurfaceInAnyOrderComesOutTheSame) {
    const mas::TriangleMesh box = mas::test::box_mesh(0, 0, 0, 10, 20, 30);
    mas::TriangleMesh scrambled;
    const int nv = int(box.vertices.size());
    scrambled.vertices.assign(box.vertices.rbegin(), box.vertices.rend());
    for (std::size_t k = box.triangles.size(); k-- > 0;) {
        const Eigen::Vector3i& t = box.triangles[k];
        const Eigen::Vector3i back(nv - 1 - t[0], nv - 1 - t[1], nv - 1 - t[2]);
        scrambled.triangles.push_back(k % 3 == 0   ? back
                                      : k % 3 == 1 ? Eigen::Vector3i(back[1], back[2], back[0])
                                                   : Eigen::Vector3i(back[2], back[0], back[1]));
    }
    mas::TriangleMesh a = box, b = scrambled;
    mas::canonical_order(a);
    mas::canonical_order(b);
    EXPECT_EQ(a.vertices, b.vertices);
    EXPECT_EQ(a.triangles, b.triangles);
    for (std::size_t k = 1; k < a.vertices.size(); ++k) {
        const Eigen::Vector3d& p = a.vertices[k - 1];
        const Eigen::Vector3d& q = a.vertices[k];
        EXPECT_TRUE(std::tie(p.x(), p.y(), p.z()) < std::tie(q.x(), q.y(), q.z()));
    }
    for (const Eigen::Vector3i& t : a.triangles) EXPECT_TRUE(t[0] < t[1] && t[0] < t[2]);
    EXPECT_TRUE(std::is_sorted(a.triangles.begin(), a.triangles.end(),
                               [](const Eigen::Vector3i& x, const Eigen::Vector3i& y) {
                                   return std::tie(x[0], x[1], x[2]) < std::tie(y[0], y[1], y[2]);
                               }));
    EXPECT_TRUE(mas::check_mesh(a).closed());
    EXPECT_DOUBLE_EQ(mas::mesh_volume(a), 6000.0);  // still facing out
}

TEST(ReadOff, ReadsQuadsAsTriangles) {
    const auto path = temp_file(
        "quad.off", "OFF\n# a unit square\n4 1 0\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n4 0 1 2 3\n");
    const auto m = mas::read_off(path);
    EXPECT_EQ(m.vertices.size(), 4u);
    EXPECT_EQ(m.triangles.size(), 2u);
}

TEST(ReadOff, BadFilesNameTheProblem) {
    EXPECT_EQ(code_of([] { mas::read_off("/nonexistent/x.off"); }), ErrorCode::ReadFailed);
    EXPECT_EQ(code_of([] { mas::read_off(temp_file("empty.off", "")); }), ErrorCode::EmptyInput);
    EXPECT_EQ(code_of([] { mas::read_off(temp_file("trunc.off", "OFF\n4 1 0\n0 0 0\n1 0 0\n")); }),
              ErrorCode::ReadFailed);
    EXPECT_EQ(
        code_of([] {
            mas::read_off(temp_file("nan.off", "OFF\n3 1 0\n0 0 0\nnan 0 0\n0 1 0\n3 0 1 2\n"));
        }),
        ErrorCode::NonFiniteCoordinate);
}

// error_of() reading `text` as an OFF file.
std::string message_of(const std::string& text) {
    return error_of([&] { mas::read_off(temp_file("bad.off", text)); });
}

// Geomview's variants carry more per vertex on its line: colours (COFF, as CGAL's and MeshLab's
// files with colours), normals (NOFF), texture coordinates (ST...): the same mesh as plain OFF.
TEST(ReadOff, VerticesWithColoursNormalsOrTextureCoordinatesReadAsPlainOff) {
    const std::string faces = "3 0 1 2 255 0 0\n3 0 3 1\n3 1 3 2\n3 2 3 0\n";
    const auto plain =
        mas::read_off(temp_file("plain.off", "OFF\n4 4 0\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n" + faces));
    const std::vector<std::pair<std::string, std::string>> variants = {
        {"COFF", "0 0 0 255 0 0 255\n1 0 0 0 255 0 255\n0 1 0 0 0 255 255\n0 0 1 9 9 9 9\n"},
        {"COFF", "0 0 0 1.0 0.5 0.0 1.0\n1 0 0 0 1 0 1\n0 1 0 0 0 1 1\n0 0 1 .2 .2 .2 1\n"},
        {"NOFF", "0 0 0 -1 -1 -1\n1 0 0 1 0 0\n0 1 0 0 1 0\n0 0 1 0 0 1\n"},
        {"CNOFF",
         "0 0 0 -1 -1 -1 1 0 0 1\n1 0 0 1 0 0 1 0 0 1\n0 1 0 0 1 0 1 0 0 1\n"
         "0 0 1 0 0 1 1 0 0 1\n"},
        {"STCOFF",
         "0 0 0 0.5 0.5 1 0 0 1\n1 0 0 1 0 1 0 0 1\n0 1 0 0 1 1 0 0 1\n"
         "0 0 1 1 1 1 0 0 1\n"},
    };
    for (const auto& [header, vertices] : variants) {
        SCOPED_TRACE(header);
        const auto m =
            mas::read_off(temp_file("variant.off", header + "\n4 4 0\n" + vertices + faces));
        EXPECT_EQ(m.vertices, plain.vertices);
        EXPECT_EQ(m.triangles, plain.triangles);
    }
    const std::string path = ::testing::TempDir() + "bad.off";
    EXPECT_EQ(message_of("4OFF\n4 4 0\n"),
              "read_failed: " + path +
                  ": not an OFF file (header '4OFF': vertices of other than three coordinates)");
    EXPECT_EQ(message_of("OFF BINARY\n"),
              "read_failed: " + path +
                  ": a binary OFF file: only OFF as text is read (save it as ASCII)");
    EXPECT_EQ(message_of("NCOFF\n4 4 0\n"),
              "read_failed: " + path + ": not an OFF file (header 'NCOFF')");
    EXPECT_EQ(message_of("PLY\n"), "read_failed: " + path + ": not an OFF file (header 'PLY')");
}

TEST(ReadOff, CountsTheFileCannotHoldAreRefusedBeforeAnythingIsAllocated) {
    // A file of a few bytes announcing 10^11 vertices or faces, or a face of 2 x 10^9 corners,
    // used to reserve them: std::bad_alloc, or 8 GB zeroed for the corners. Every vertex takes
    // at least three numbers, every face four, every corner one.
    const std::string path = ::testing::TempDir() + "bad.off";
    EXPECT_EQ(message_of("OFF\n100000000000 1 0\n0 0 0\n"),
              "read_failed: " + path +
                  ": truncated OFF file: it announces 100000000000 vertices and holds at most 1");
    EXPECT_EQ(message_of("OFF\n3 100000000000 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n"),
              "read_failed: " + path +
                  ": truncated OFF file: it announces 100000000000 faces and holds at most 1");
    EXPECT_EQ(message_of("OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n2000000000 0 1 2\n"),
              "read_failed: " + path +
                  ": truncated OFF file: a face announces 2000000000 corners and the file holds "
                  "at most 4 more numbers");
}

TEST(ReadOff, EveryNumberIsReadWholeAndNamedWhenBad) {
    const std::string path = ::testing::TempDir() + "bad.off";
    // Text after a number was ignored: "1x" read as 1.
    EXPECT_EQ(message_of("OFF\n3 1 0\n0 0 0\n1 0 0\n0 1x 0\n3 0 1 2\n"),
              "read_failed: " + path + ": bad vertex coordinate '1x'");
    EXPECT_EQ(message_of("OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1.5 2\n"),
              "read_failed: " + path + ": bad vertex index '1.5' in a face");
    EXPECT_EQ(message_of("OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 3\n"),
              "read_failed: " + path + ": bad vertex index '3' in a face (3 vertices)");
    EXPECT_EQ(message_of("OFF\nthree 1 0\n"), "read_failed: " + path + ": bad OFF counts line");
    // A coordinate past a double's range is named (the message named its vertex's x).
    EXPECT_EQ(message_of("OFF\n3 1 0\n0 0 0\n1 0 0\n0 1e400 0\n3 0 1 2\n"),
              "non_finite_coordinate: " + path +
                  ": vertex coordinate '1e400' is beyond the range of a number");
    // One below it is a coordinate of 0 (or next to it), not an error.
    const auto m =
        mas::read_off(temp_file("tiny.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1e-400 0\n3 0 1 2\n"));
    EXPECT_LT(std::abs(m.vertices[2].y()), 1e-300);
}
