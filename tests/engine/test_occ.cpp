// Tests of the OCCT side of the engine: BREP text, shape checks, tessellation, file readers and the
// exact section, and the agreement of mesh sections with exact ones within the tessellation bound.
#include <gtest/gtest.h>
#include <unistd.h>

#include <BRepAlgoAPI_BuilderAlgo.hxx>
#include <BRepBuilderAPI_MakeEdge.hxx>
#include <BRepBuilderAPI_MakeFace.hxx>
#include <BRepGProp.hxx>
#include <BRepMesh_IncrementalMesh.hxx>
#include <BRepTools.hxx>
#include <BRep_Builder.hxx>
#include <GProp_GProps.hxx>
#include <IGESControl_Controller.hxx>
#include <IGESControl_Writer.hxx>
#include <STEPControl_Writer.hxx>
#include <Standard_Failure.hxx>
#include <StlAPI_Writer.hxx>
#include <TopExp_Explorer.hxx>
#include <TopTools_ListOfShape.hxx>
#include <TopoDS.hxx>
#include <TopoDS_CompSolid.hxx>
#include <TopoDS_Compound.hxx>
#include <TopoDS_Edge.hxx>
#include <TopoDS_Solid.hxx>
#include <array>
#include <atomic>
#include <cctype>
#include <cmath>
#include <csignal>
#include <filesystem>
#include <fstream>
#include <functional>
#include <gp_Pln.hxx>
#include <limits>
#include <sstream>
#include <string>
#include <thread>

#include "mas/Angles.hpp"
#include "mas/Error.hpp"
#include "mas/Section.hpp"
#include "mas/Shape.hpp"
#include "test_parts.hpp"

namespace mas {
namespace {

namespace fs = std::filesystem;
using Eigen::Vector3d;

// Passes when `f` throws mas::Error with `code` and a message containing `word`; fails on any
// other outcome, in particular on an OCCT Standard_Failure escaping the engine.
::testing::AssertionResult throws_error(const std::function<void()>& f, ErrorCode code,
                                        const std::string& word) {
    try {
        f();
    } catch (const Error& e) {
        const std::string message = e.what();
        if (e.code() != code)
            return ::testing::AssertionFailure() << "code " << to_string(e.code()) << " instead of "
                                                 << to_string(code) << ": " << message;
        if (message.find(word) == std::string::npos)
            return ::testing::AssertionFailure() << "message lacks '" << word << "': " << message;
        return ::testing::AssertionSuccess() << message;
    } catch (const Standard_Failure& e) {
        return ::testing::AssertionFailure()
               << "Standard_Failure escaped: " << e.GetMessageString();
    } catch (const std::exception& e) {
        return ::testing::AssertionFailure() << "std::exception escaped: " << e.what();
    } catch (...) {
        return ::testing::AssertionFailure() << "an unknown exception escaped";
    }
    return ::testing::AssertionFailure() << "nothing was thrown";
}

double exact_volume(const Shape& s) {
    GProp_GProps props;
    BRepGProp::VolumeProperties(test::to_occt(s), props);
    return props.Mass();
}

double exact_surface_area(const Shape& s) {
    GProp_GProps props;
    BRepGProp::SurfaceProperties(test::to_occt(s), props);
    return props.Mass();
}

// ---- Shape: BREP text, info, single_solid ------------------------------------------------------

TEST(OccShape, BrepRoundTripPreservesVolume) {
    const Shape original = test::l_block();

    const Shape copy = Shape::from_brep_string(original.to_brep_string());

    const double expected = 20.0 * 20.0 * 60.0 + 50.0 * 20.0 * 20.0;
    EXPECT_NEAR(original.info().volume_mm3, expected, 1e-9 * expected);
    EXPECT_NEAR(copy.info().volume_mm3, expected, 1e-9 * expected);
    EXPECT_EQ(copy.info().faces, original.info().faces);
}

TEST(OccShape, InfoCountsTheTopologyOfABox) {
    const Shape box = test::box(1, 2, 3, 10, 20, 30);

    const ShapeInfo info = box.info();

    EXPECT_EQ(info.solids, 1);
    EXPECT_EQ(info.shells, 1);
    EXPECT_EQ(info.faces, 6);
    EXPECT_EQ(info.edges, 12);
    EXPECT_EQ(info.free_faces, 0);
    EXPECT_EQ(info.free_edges, 0);
    EXPECT_NEAR(info.volume_mm3, 6000.0, 1e-9);
    EXPECT_TRUE(info.bounds.min().isApprox(Vector3d(1, 2, 3), 1e-9));
    EXPECT_TRUE(info.bounds.max().isApprox(Vector3d(11, 22, 33), 1e-9));
}

TEST(OccShape, InfoCountsAFaceAsFree) {
    const ShapeInfo info = test::single_face().info();

    EXPECT_EQ(info.solids, 0);
    EXPECT_EQ(info.faces, 1);
    EXPECT_EQ(info.free_faces, 1);
    EXPECT_EQ(info.free_edges, 0);
    EXPECT_EQ(info.volume_mm3, 0.0);
}

TEST(OccShape, SingleSolidReturnsTheSolidOfACompound) {
    const Shape solid = test::cylinder(Vector3d::Zero(), Vector3d::UnitZ(), 5, 10);

    const Shape one = solid.single_solid("cylinder");

    EXPECT_NEAR(one.info().volume_mm3, kPi * 25 * 10, 1e-9 * kPi * 250);
    EXPECT_EQ(one.info().solids, 1);
}

TEST(OccShape, SingleSolidRejectsAFace) {
    const Shape face = test::single_face();

    EXPECT_TRUE(throws_error([&] { face.single_solid("part"); }, ErrorCode::NotASolid,
                             "part: not a solid (1 face, 0 solids)"));
}

TEST(OccShape, SingleSolidRejectsTwoSolidsApart) {
    const Shape boxes = test::two_boxes();  // 10 mm between them

    EXPECT_TRUE(throws_error([&] { boxes.single_solid("part"); }, ErrorCode::MultipleSolids,
                             "part: 2 solids where one is expected"));
    EXPECT_TRUE(throws_error([&] { boxes.single_solid("part"); }, ErrorCode::MultipleSolids,
                             "these make 2 bodies apart"));
}

TopoDS_Compound compound_of(const std::vector<TopoDS_Shape>& shapes) {
    BRep_Builder b;
    TopoDS_Compound c;
    b.MakeCompound(c);
    for (const auto& s : shapes) b.Add(c, s);
    return c;
}

int count_of(const TopoDS_Shape& s, TopAbs_ShapeEnum type) {
    int n = 0;
    for (TopExp_Explorer x(s, type); x.More(); x.Next()) ++n;
    return n;
}

TEST(OccShape, SingleSolidFusesSolidsThatShareMaterial) {
    // A plate with a post standing on it and a post sunk 3 mm into it, given as a compound (Part's
    // Compound where Union was meant): one body, the union, its faces merged where coplanar.
    const Shape compound = test::from_occt(
        compound_of({test::occ_box(0, 0, 0, 40, 30, 5), test::occ_box(5, 5, 5, 10, 10, 20),
                     test::occ_box(25, 10, 2, 8, 8, 13)}));
    ASSERT_EQ(compound.info().solids, 3);
    const Shape fused = compound.single_solid("part");
    EXPECT_EQ(fused.info().solids, 1);
    EXPECT_NEAR(fused.info().volume_mm3, 40 * 30 * 5 + 10 * 10 * 20 + 8 * 8 * 10, 1e-6);
    // The plate's 6 faces, each post's 4 sides and top.
    EXPECT_EQ(fused.info().faces, 6 + 5 + 5);
    EXPECT_TRUE(fused.info().bounds.isApprox(
        Eigen::AlignedBox3d(Vector3d(0, 0, 0), Vector3d(40, 30, 25)), 1e-9));
    // The source is not changed.
    EXPECT_EQ(compound.info().solids, 3);
    EXPECT_NEAR(compound.info().volume_mm3, 6000 + 2000 + 8 * 8 * 13, 1e-6);
}

TEST(OccShape, SingleSolidFusesACompSolidIntoTheSolidItBounds) {
    // Two boxes stacked, split by the General Fuse into solids sharing the face between them and
    // kept as a CompSolid (FreeCAD's BooleanFragments in CompSolid mode): one 10 x 10 x 20 box.
    BRepAlgoAPI_BuilderAlgo fragments;
    TopTools_ListOfShape arguments;
    arguments.Append(test::occ_box(0, 0, 0, 10, 10, 10));
    arguments.Append(test::occ_box(0, 0, 10, 10, 10, 10));
    fragments.SetArguments(arguments);
    fragments.Build();
    ASSERT_TRUE(fragments.IsDone());
    BRep_Builder b;
    TopoDS_CompSolid cs;
    b.MakeCompSolid(cs);
    for (TopExp_Explorer x(fragments.Shape(), TopAbs_SOLID); x.More(); x.Next())
        b.Add(cs, x.Current());
    ASSERT_EQ(count_of(cs, TopAbs_SOLID), 2);
    ASSERT_EQ(count_of(cs, TopAbs_FACE), 12);  // the shared face twice, once in each solid

    const Shape fused = test::from_occt(cs).single_solid("part");
    EXPECT_EQ(fused.info().solids, 1);
    EXPECT_EQ(fused.info().faces, 6);
    EXPECT_NEAR(fused.info().volume_mm3, 2000.0, 1e-9);
}

TEST(OccShape, SingleSolidRejectsSolidsMeetingAlongAnEdgeOnly) {
    // Two cubes sharing an edge hold no material in common: two bodies, not a part.
    const Shape edge_to_edge = test::from_occt(
        compound_of({test::occ_box(0, 0, 0, 10, 10, 10), test::occ_box(10, 0, 10, 10, 10, 10)}));

    EXPECT_TRUE(throws_error([&] { edge_to_edge.single_solid("part"); }, ErrorCode::MultipleSolids,
                             "part: 2 solids where one is expected; solids that share material are "
                             "fused into one, and these make 2 bodies apart (or meeting only along "
                             "an edge or at a point)"));
}

TEST(OccShape, SingleSolidNamesFacesBesideSeveralSolids) {
    const Shape shape = test::from_occt(
        compound_of({test::occ_box(0, 0, 0, 10, 10, 10), test::occ_box(0, 0, 10, 10, 10, 10),
                     test::to_occt(test::single_face())}));

    EXPECT_TRUE(throws_error([&] { shape.single_solid("part"); }, ErrorCode::NotASolid,
                             "part: 2 solids and 1 face outside them"));
}

TEST(OccShape, SingleSolidRejectsFacesBesideTheSolidAndLeavesOutLooseEdges) {
    // A compound of a box and things beside it: once the faces were dropped without a word.
    const auto compound = [](std::vector<TopoDS_Shape> extra) {
        extra.insert(extra.begin(), test::to_occt(test::box(0, 0, 0, 10, 10, 10)));
        return test::from_occt(compound_of(extra));
    };
    const TopoDS_Shape face = test::to_occt(test::single_face());
    const TopoDS_Shape edge = BRepBuilderAPI_MakeEdge(gp_Pnt(20, 0, 0), gp_Pnt(30, 0, 0)).Edge();
    EXPECT_TRUE(throws_error([&] { compound({face}).single_solid("part"); }, ErrorCode::NotASolid,
                             "part: one solid and 1 face outside it"));
    EXPECT_TRUE(throws_error(
        [&] {
            compound({face, edge}).single_solid("p");
        },
        ErrorCode::NotASolid, "p: one solid and 1 face outside it"));
    const TopoDS_Shape lid =
        BRepBuilderAPI_MakeFace(gp_Pln(gp_Pnt(0, 0, 10), gp_Dir(0, 0, 1)), 0, 5, 0, 5).Face();
    EXPECT_TRUE(throws_error(
        [&] {
            compound({face, lid}).single_solid("part");
        },
        ErrorCode::NotASolid, "part: one solid and 2 faces outside it"));
    // A loose edge (an axis, a sketch line) holds no material: the box alone comes back.
    const Shape solid = compound({edge}).single_solid("part");
    EXPECT_EQ(solid.info().solids, 1);
    EXPECT_EQ(solid.info().edges, 12);
    EXPECT_NEAR(solid.info().volume_mm3, 1000.0, 1e-9);
}

TEST(OccShape, SingleSolidRejectsAnOpenShell) {
    const Shape shell = test::open_box_shell(0, 0, 0, 10, 10, 10);

    // The missing top face leaves its four edges used by one face each.
    EXPECT_TRUE(throws_error([&] { shell.single_solid("part"); }, ErrorCode::NotASolid,
                             "part: an open shell, not a closed solid (4 boundary edges)"));
}

TEST(OccShape, SingleSolidNamesAnOpenShellInsideASolid) {
    // The open shell above made the one shell of a solid: it is no closed solid either, and the
    // message says why as it does for the shell alone, rather than OCCT's shape check's "an
    // invalid solid" (Shape.hpp: exactly one closed solid).
    const TopoDS_Shape open = test::to_occt(test::open_box_shell(0, 0, 0, 10, 10, 10));
    TopExp_Explorer x(open, TopAbs_SHELL);
    ASSERT_TRUE(x.More());
    BRep_Builder b;
    TopoDS_Solid solid;
    b.MakeSolid(solid);
    b.Add(solid, TopoDS::Shell(x.Current()));
    const Shape s = test::from_occt(solid);
    ASSERT_EQ(s.info().solids, 1);

    EXPECT_TRUE(throws_error([&] { s.single_solid("part"); }, ErrorCode::NotASolid,
                             "part: an open shell, not a closed solid (4 boundary edges)"));
}

TEST(OccShape, SingleSolidWrapsAClosedShellIntoASolid) {
    const Shape shell = test::box_shell(0, 0, 0, 10, 20, 30);
    ASSERT_EQ(shell.info().solids, 0);

    const Shape solid = shell.single_solid("part");

    EXPECT_EQ(solid.info().solids, 1);
    EXPECT_NEAR(solid.info().volume_mm3, 6000.0, 1e-9);
}

TEST(OccShape, SingleSolidTurnsAnInsideOutSolidRightSideOut) {
    const Shape inside_out =
        test::from_occt(test::to_occt(test::box(0, 0, 0, 10, 10, 10)).Reversed());
    ASSERT_NEAR(inside_out.info().volume_mm3, -1000.0, 1e-9);

    const Shape solid = inside_out.single_solid("part");

    EXPECT_NEAR(solid.info().volume_mm3, 1000.0, 1e-9);
    EXPECT_NEAR(
        exact_sections(inside_out, {make_plane(Vector3d(0, 0, 5), Vector3d::UnitZ())})[0].area,
        100.0, 1e-9);
    EXPECT_NEAR(mesh_volume(tessellate(inside_out)), 1000.0, 1e-9);
}

TEST(OccShape, SingleSolidOfANullShapeIsEmptyInput) {
    EXPECT_TRUE(throws_error([] { Shape().single_solid("part"); }, ErrorCode::EmptyInput, "empty"));
}

TEST(OccShape, FromBrepStringRejectsEmptyText) {
    EXPECT_TRUE(throws_error([] { Shape::from_brep_string(""); }, ErrorCode::EmptyInput, "empty"));
    EXPECT_TRUE(
        throws_error([] { Shape::from_brep_string(" \n\t"); }, ErrorCode::EmptyInput, "empty"));
}

TEST(OccShape, FromBrepStringRejectsGarbage) {
    EXPECT_TRUE(throws_error([] { Shape::from_brep_string("solid cube\nfacet normal 0 0 1\n"); },
                             ErrorCode::ReadFailed, "not OCCT BREP data"));
}

// OCCT's BREP reader loops forever on some cuts and crashes on others (a null curve) unless its
// stream is guarded: cut the text everywhere, including inside curves and the topology.
TEST(OccShape, FromBrepStringRejectsTextCutAnywhere) {
    for (const Shape& part : {test::l_block(), test::torus(20, 5)}) {
        const std::string full = part.to_brep_string();
        // Every cut before the last token's final character; the whitespace after it is optional.
        const std::size_t last = full.find_last_not_of(" \r\n");
        const std::size_t step = full.size() / 200 + 1;
        for (std::size_t n = 0; n <= last; n += n + step > last && n < last ? last - n : step) {
            const std::string cut = full.substr(0, n);
            const ErrorCode code = n < 2 ? ErrorCode::EmptyInput : ErrorCode::ReadFailed;
            ASSERT_TRUE(throws_error([&] { Shape::from_brep_string(cut); }, code, "BREP"))
                << "cut at " << n << " of " << full.size();
        }
    }
}

TEST(OccShape, BrepOfANullShapeIsEmptyInput) {
    const std::string text = Shape().to_brep_string();

    EXPECT_TRUE(
        throws_error([&] { Shape::from_brep_string(text); }, ErrorCode::EmptyInput, "no shape"));
}

// ---- Tessellation ------------------------------------------------------------------------------

TEST(OccTessellate, EffectiveDeflectionIsDerivedFromTheBoundingBox) {
    TessellationParams automatic;
    TessellationParams explicit_d;
    explicit_d.deflection_mm = 0.02;
    TessellationParams negative;
    negative.deflection_mm = -1.0;
    const Shape mid = test::box(0, 0, 0, 10, 10, 10);  // diagonal 17.32 mm
    const Shape large = test::box(0, 0, 0, 300, 300, 300);
    const Shape small = test::box(0, 0, 0, 1, 1, 1);

    EXPECT_NEAR(effective_deflection(mid, automatic), 5e-4 * std::sqrt(300.0), 1e-12);
    EXPECT_DOUBLE_EQ(effective_deflection(large, automatic), 0.1);
    EXPECT_DOUBLE_EQ(effective_deflection(small, automatic), 0.005);
    EXPECT_DOUBLE_EQ(effective_deflection(mid, explicit_d), 0.02);
    EXPECT_DOUBLE_EQ(effective_deflection(mid, negative), effective_deflection(mid, automatic));
    // A deflection finer than 1e-5 of the diagonal would take minutes and gigabytes: named.
    TessellationParams fine;
    fine.deflection_mm = 1.001e-5 * std::sqrt(300.0);
    EXPECT_DOUBLE_EQ(effective_deflection(mid, fine), fine.deflection_mm);
    fine.deflection_mm = 0.999e-5 * std::sqrt(300.0);
    EXPECT_TRUE(throws_error([&] { effective_deflection(mid, fine); }, ErrorCode::InvalidArgument,
                             "is too fine for a part"));
    EXPECT_TRUE(throws_error([&] { tessellate(mid, fine); }, ErrorCode::InvalidArgument,
                             "tessellation deflection"));
    // Over 10 m across, the derived deflection is the floor, not the 0.1 mm cap below it.
    const Shape huge = test::box(0, 0, 0, 20000, 10000, 10000);
    EXPECT_NEAR(effective_deflection(huge, automatic), 1e-5 * std::sqrt(6e8), 1e-9);
    TessellationParams derived;
    derived.deflection_mm = effective_deflection(huge, automatic);
    EXPECT_NO_THROW(effective_deflection(huge, derived));
}

TEST(OccTessellate, NonFiniteDeflectionIsInvalidArgument) {
    const Shape box = test::box(0, 0, 0, 10, 10, 10);
    const double inf = std::numeric_limits<double>::infinity();
    for (const double bad : {std::nan(""), inf, -inf}) {
        TessellationParams p;
        p.deflection_mm = bad;
        EXPECT_TRUE(throws_error([&] { effective_deflection(box, p); }, ErrorCode::InvalidArgument,
                                 "deflection"));
        EXPECT_TRUE(
            throws_error([&] { tessellate(box, p); }, ErrorCode::InvalidArgument, "deflection"));
    }
    TessellationParams angle;
    angle.angular_deflection_rad = 0.0;
    EXPECT_TRUE(throws_error([&] { tessellate(box, angle); }, ErrorCode::InvalidArgument,
                             "angular deflection"));
}

TEST(OccTessellate, BoxMeshIsWeldedIntoEightVertices) {
    const Shape box = test::box(0, 0, 0, 10, 20, 30);

    const TriangleMesh mesh = tessellate(box);

    EXPECT_EQ(mesh.vertices.size(), 8u);
    EXPECT_EQ(mesh.triangles.size(), 12u);
    EXPECT_NEAR(mesh_volume(mesh), 6000.0, 1e-9);
}

// Closed, outward, exactly welded (Euler characteristic 2 - 2 genus) and within the volume bound
// the deflection gives: every facet lies within d of the surface, so the volume between the two
// is at most (surface area) x d.
TEST(OccTessellate, EveryTestPartGivesAClosedWeldedMeshWithinTheDeflectionBound) {
    struct Part {
        const char* name;
        Shape shape;
        int genus;
    };
    const std::vector<Part> parts = {
        {"box", test::box(0, 0, 0, 10, 20, 30), 0},
        {"cylinder", test::cylinder(Vector3d(1, 2, 3), Vector3d(1, 1, 1).normalized(), 7, 15), 0},
        {"sphere", test::sphere(12), 0},
        {"torus", test::torus(20, 5), 1},
        {"l_block", test::l_block(), 0},
        {"plate_with_hole", test::plate_with_hole(), 1},
        {"two_posts", test::two_posts(), 0},
    };
    for (const Part& part : parts) {
        SCOPED_TRACE(part.name);
        TessellationParams params;
        params.deflection_mm = 0.02;

        TriangleMesh mesh = tessellate(part.shape, params);

        const MeshReport report = check_mesh(mesh);
        EXPECT_TRUE(report.closed());
        EXPECT_EQ(report.degenerate_triangles, 0u);
        const long euler = long(report.vertices) - long(report.triangles) / 2;  // V - E + F
        EXPECT_EQ(euler, 2 - 2 * part.genus);
        const double exact = exact_volume(part.shape);
        EXPECT_GT(report.volume_mm3, 0.0);
        EXPECT_LE(std::abs(report.volume_mm3 - exact),
                  exact_surface_area(part.shape) * params.deflection_mm);
    }
}

// The inscribed polygon of a circle of radius r whose chords stay within d of it loses less than
// 2 pi r d of area, so a cylinder of height h loses between 0 and 2 pi r d h of volume.
TEST(OccTessellate, CylinderVolumeLossIsBoundedByTheDeflection) {
    const double r = 10.0, h = 20.0;
    const Shape cylinder = test::cylinder(Vector3d::Zero(), Vector3d::UnitZ(), r, h);
    for (const double d : {0.1, 0.02, 0.005}) {
        SCOPED_TRACE(d);
        TessellationParams params;
        params.deflection_mm = d;

        const TriangleMesh mesh = tessellate(cylinder, params);

        const double loss = kPi * r * r * h - mesh_volume(mesh);
        EXPECT_GT(loss, 0.0);
        EXPECT_LE(loss, 2.0 * kPi * r * d * h);
    }
}

TEST(OccTessellate, AFinerDeflectionGivesAFinerMeshOfTheSameShape) {
    // Meshing works on a copy: an earlier coarse tessellation must not stick to the shape.
    const Shape sphere = test::sphere(10);
    TessellationParams coarse, fine;
    coarse.deflection_mm = 0.5;
    fine.deflection_mm = 0.01;

    const TriangleMesh first = tessellate(sphere, coarse);
    const TriangleMesh second = tessellate(sphere, fine);
    const TriangleMesh again = tessellate(sphere, coarse);

    EXPECT_GT(second.triangles.size(), 4 * first.triangles.size());
    EXPECT_EQ(again.triangles.size(), first.triangles.size());
    EXPECT_EQ(sphere.to_brep_string(), test::sphere(10).to_brep_string());
}

TEST(OccTessellate, RejectsShapesThatAreNotOneSolid) {
    EXPECT_TRUE(
        throws_error([] { tessellate(test::single_face()); }, ErrorCode::NotASolid, "not a solid"));
    EXPECT_TRUE(
        throws_error([] { tessellate(test::two_boxes()); }, ErrorCode::MultipleSolids, "2 solids"));
    EXPECT_TRUE(throws_error([] { tessellate(test::open_box_shell(0, 0, 0, 1, 1, 1)); },
                             ErrorCode::NotASolid, "open shell"));
}

// ---- Reading files -----------------------------------------------------------------------------

class OccReadModel : public ::testing::Test {
protected:
    void SetUp() override {
        const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
        dir_ = fs::temp_directory_path() /
               ("mas_occ_" + std::to_string(::getpid()) + "_" + info->name());
        fs::remove_all(dir_);
        fs::create_directories(dir_);
    }
    void TearDown() override { fs::remove_all(dir_); }

    std::string path(const std::string& name) const { return (dir_ / name).string(); }
    std::string write_text(const std::string& name, const std::string& text) const {
        std::ofstream(path(name), std::ios::binary) << text;
        return path(name);
    }
    static std::string read_text(const std::string& p) {
        std::ifstream in(p, std::ios::binary);
        std::ostringstream s;
        s << in.rdbuf();
        return s.str();
    }
    std::string write_step(const std::string& name, const Shape& shape) const {
        STEPControl_Writer writer;
        EXPECT_EQ(writer.Transfer(test::to_occt(shape), STEPControl_AsIs), IFSelect_RetDone);
        EXPECT_EQ(writer.Write(path(name).c_str()), IFSelect_RetDone);
        return path(name);
    }

    fs::path dir_;
};

TEST_F(OccReadModel, ReadsAStepFile) {
    const std::string file = write_step("part.step", test::l_block());

    const Model model = read_model(file);

    EXPECT_EQ(model.kind, Model::Kind::Solid);
    EXPECT_EQ(model.name, "part.step");
    EXPECT_NEAR(model.shape.single_solid(model.name).info().volume_mm3, 44000.0, 1e-6 * 44000);
}

// OCCT writes IGES as loose trimmed surfaces by default (mode 0) or as a B-rep solid (mode 1);
// both must come back as one solid.
TEST_F(OccReadModel, ReadsAnIgesFileWrittenAsSurfacesOrAsASolid) {
    IGESControl_Controller::Init();
    const Shape cylinder = test::cylinder(Vector3d::Zero(), Vector3d::UnitZ(), 5, 10);
    for (const int mode : {0, 1}) {
        SCOPED_TRACE(mode);
        IGESControl_Writer writer("MM", mode);
        ASSERT_TRUE(writer.AddShape(test::to_occt(cylinder)));
        writer.ComputeModel();
        const std::string file = path("part" + std::to_string(mode) + ".igs");
        ASSERT_TRUE(writer.Write(file.c_str()));

        const Model model = read_model(file);

        EXPECT_EQ(model.kind, Model::Kind::Solid);
        const double v = model.shape.single_solid(model.name).info().volume_mm3;
        EXPECT_NEAR(v, kPi * 25 * 10, 1e-6 * kPi * 250);
    }
}

TEST_F(OccReadModel, ReadsABrepFileWhateverTheCaseOfItsExtension) {
    ASSERT_TRUE(BRepTools::Write(test::to_occt(test::two_posts()), path("part.BRep").c_str()));

    const Model model = read_model(path("part.BRep"));

    EXPECT_EQ(model.kind, Model::Kind::Solid);
    EXPECT_NEAR(model.shape.info().volume_mm3, 40 * 10 * 5 + 2 * 10 * 10 * 25, 1e-9);
}

TEST_F(OccReadModel, ReadsAnStlFileIntoAWeldedClosedMesh) {
    TopoDS_Shape box = test::to_occt(test::box(0, 0, 0, 10, 20, 30));
    BRepMesh_IncrementalMesh(box, 0.1);
    StlAPI_Writer writer;
    ASSERT_TRUE(writer.Write(box, path("box.stl").c_str()));

    const Model model = read_model(path("box.stl"));
    const TriangleMesh mesh = model_mesh(model);

    EXPECT_EQ(model.kind, Model::Kind::Mesh);
    EXPECT_EQ(mesh.vertices.size(), 8u);  // STL repeats corners per facet; RWStl merges them
    EXPECT_EQ(mesh.triangles.size(), 12u);
    EXPECT_NEAR(mesh_volume(mesh), 6000.0, 1e-6);
}

TEST_F(OccReadModel, ReadsAnOffFile) {
    // A unit cube as six quads, counter-clockwise seen from outside.
    const std::string file = write_text("cube.off",
                                        "OFF\n8 6 0\n"
                                        "0 0 0\n1 0 0\n0 1 0\n1 1 0\n0 0 1\n1 0 1\n0 1 1\n1 1 1\n"
                                        "4 0 2 3 1\n4 4 5 7 6\n4 0 1 5 4\n"
                                        "4 2 6 7 3\n4 0 4 6 2\n4 1 3 7 5\n");

    const TriangleMesh mesh = model_mesh(read_model(file));

    EXPECT_EQ(mesh.triangles.size(), 12u);
    EXPECT_NEAR(mesh_volume(mesh), 1.0, 1e-12);
}

TEST_F(OccReadModel, MissingFileIsReadFailedNamingThePath) {
    const std::string file = path("nowhere.step");

    EXPECT_TRUE(throws_error([&] { read_model(file); }, ErrorCode::ReadFailed, file));
}

TEST_F(OccReadModel, EmptyFileIsEmptyInput) {
    for (const char* name : {"empty.step", "empty.stl", "empty.brep"}) {
        const std::string file = write_text(name, "");
        EXPECT_TRUE(throws_error([&] { read_model(file); }, ErrorCode::EmptyInput, "empty"))
            << name;
    }
}

TEST_F(OccReadModel, TruncatedStepIsReadFailed) {
    const std::string full = read_text(write_step("full.step", test::l_block()));
    const std::string file = write_text("cut.step", full.substr(0, full.size() / 2));

    EXPECT_TRUE(throws_error([&] { read_model(file); }, ErrorCode::ReadFailed, "STEP"));
}

// OCCT's readers accept truncated IGES and STL files (and its IGES translator then crashes on a
// B-rep file): every format is cut at many places and must give ReadFailed, nothing else.
TEST_F(OccReadModel, FilesCutAnywhereAreReadFailed) {
    IGESControl_Controller::Init();
    const TopoDS_Shape part = test::to_occt(test::plate_with_hole());
    {
        STEPControl_Writer writer;
        writer.Transfer(part, STEPControl_AsIs);
        ASSERT_EQ(writer.Write(path("part.step").c_str()), IFSelect_RetDone);
    }
    for (const int mode : {0, 1}) {
        IGESControl_Writer writer("MM", mode);
        writer.AddShape(part);
        writer.ComputeModel();
        ASSERT_TRUE(writer.Write(path("part" + std::to_string(mode) + ".igs").c_str()));
    }
    ASSERT_TRUE(BRepTools::Write(part, path("part.brep").c_str()));
    TopoDS_Shape meshed = part;
    BRepMesh_IncrementalMesh(meshed, 0.5);
    StlAPI_Writer stl;
    ASSERT_TRUE(stl.Write(meshed, path("ascii.stl").c_str()));
    stl.ASCIIMode() = Standard_False;
    ASSERT_TRUE(stl.Write(meshed, path("binary.stl").c_str()));

    for (const char* name :
         {"part.step", "part0.igs", "part1.igs", "part.brep", "ascii.stl", "binary.stl"}) {
        SCOPED_TRACE(name);
        const std::string full = read_text(path(name));
        ASSERT_NO_THROW(model_mesh(read_model(path(name))));
        const std::string ext = fs::path(name).extension().string();
        for (int i = 1; i < 20; ++i) {
            const std::size_t n = full.size() * i / 20;
            const std::string file = write_text("cut" + ext, full.substr(0, n));
            EXPECT_TRUE(throws_error([&] { read_model(file); }, ErrorCode::ReadFailed, file))
                << "cut at " << n << " of " << full.size();
        }
    }
}

// Damaged files that OCCT's translator and shape check dereference into the void (an access
// violation, which ended the process, FreeCAD with it): errors naming the file instead.
TEST_F(OccReadModel, DamagedFilesAreErrorsNotCrashes) {
    // A STEP entity that a vertex refers to is missing.
    std::string step = read_text(std::string(MAS_TEST_DATA) + "/box_10x20x30.step");
    const std::size_t at = step.find("\n#176 = CARTESIAN_POINT");
    ASSERT_NE(at, std::string::npos);
    step.erase(at + 1, step.find('\n', at + 1) - at);
    const std::string step_file = write_text("missing_point.step", step);
    EXPECT_TRUE(throws_error([&] { model_mesh(read_model(step_file)); }, ErrorCode::EmptyInput,
                             "only damaged entities"));
    // A BREP plane whose directions are zero vectors.
    std::istringstream brep(read_text(std::string(MAS_TEST_DATA) + "/l_block.brep"));
    std::string damaged;
    int line_number = 0;
    for (std::string line; std::getline(brep, line);)
        damaged +=
            (++line_number == 73 ? std::string("1 27.3 0 37.6 -0 -1 -0 0 0 -1 -0 -0 0 ") : line) +
            "\n";
    const std::string brep_file = write_text("zero_direction.brep", damaged);
    EXPECT_TRUE(throws_error([&] { model_mesh(read_model(brep_file)); }, ErrorCode::NotASolid,
                             "zero_direction.brep: an invalid solid"));
}

// A valid solid whose faces OCCT meshes far off their surfaces (tests/data/make_test_data.py: a
// cylinder whose side meshed into about a third of its volume) is named, not cut into wrong
// sections.
TEST_F(OccReadModel, ASolidWhoseFacesMeshOffTheirSurfacesIsNamed) {
    const std::string file = std::string(MAS_TEST_DATA) + "/cylinder_meshed_off.brep";
    const Model model = read_model(file);
    const Shape solid = model.shape.single_solid("test");
    EXPECT_NEAR(solid.info().volume_mm3, kPi * 8 * 8 * 20, 1e-6);
    EXPECT_TRUE(
        throws_error([&] { model_mesh(model); }, ErrorCode::GeometryFailure,
                     "cylinder_meshed_off.brep: OCCT's tessellation of the solid encloses "));
    EXPECT_TRUE(throws_error([&] { model_mesh(model); }, ErrorCode::GeometryFailure,
                             " mm^3 where the solid holds 4021.24 mm^3"));
    // At any deflection.
    for (const double d : {0.005, 0.1, 1.0}) {
        TessellationParams params;
        params.deflection_mm = d;
        EXPECT_TRUE(throws_error([&] { tessellate(solid, params); }, ErrorCode::GeometryFailure,
                                 "some of its faces mesh off their surfaces"))
            << d;
    }
    // A cylinder of the same size meshes within its bound
    // (CylinderVolumeLossIsBoundedByTheDeflection).
    EXPECT_NO_THROW(tessellate(test::cylinder(Vector3d::Zero(), Vector3d::UnitZ(), 8, 20)));
}

// Catching OCCT's signals borrows the process's handlers of the fatal signals only while a read
// runs, on any thread: Ctrl-C's handler is never taken, and every handler is back afterwards,
// however the reads on several threads interleave. (OCCT's STEP parser keeps global state: reads
// on several threads garbled each other until they were made to take turns.)
TEST_F(OccReadModel, ReadingLeavesTheProcessSignalHandlersAsTheyWere) {
    std::string step = read_text(std::string(MAS_TEST_DATA) + "/box_10x20x30.step");
    const std::string good = write_text("good.step", step);
    const std::size_t at = step.find("\n#176 = CARTESIAN_POINT");
    ASSERT_NE(at, std::string::npos);
    step.erase(at + 1, step.find('\n', at + 1) - at);
    const std::string damaged = write_text("damaged.step", step);

    struct sigaction mine = {}, before_int = {}, before_segv = {}, now = {};
    mine.sa_handler = [](int) {};
    sigemptyset(&mine.sa_mask);
    ASSERT_EQ(sigaction(SIGINT, &mine, &before_int), 0);
    ASSERT_EQ(sigaction(SIGSEGV, &mine, &before_segv), 0);
    std::atomic<bool> int_taken{false};
    std::vector<std::thread> readers;
    for (int t = 0; t < 4; ++t)
        readers.emplace_back([&] {
            for (int i = 0; i < 5; ++i) {
                EXPECT_NO_THROW(read_model(good));
                EXPECT_THROW(read_model(damaged), mas::Error);
                struct sigaction during = {};
                sigaction(SIGINT, nullptr, &during);
                if (during.sa_handler != mine.sa_handler) int_taken = true;
            }
        });
    for (auto& r : readers) r.join();
    EXPECT_FALSE(int_taken);
    sigaction(SIGINT, nullptr, &now);
    EXPECT_EQ(now.sa_handler, mine.sa_handler);
    sigaction(SIGSEGV, nullptr, &now);
    EXPECT_EQ(now.sa_handler, mine.sa_handler);
    sigaction(SIGINT, &before_int, nullptr);
    sigaction(SIGSEGV, &before_segv, nullptr);
}

TEST_F(OccReadModel, GarbageFilesAreReadFailed) {
    const std::string garbage = "this is not a CAD file\n\x01\x02\x03 at all\n";
    for (const char* name : {"junk.step", "junk.igs", "junk.brep"}) {
        const std::string file = write_text(name, garbage);
        EXPECT_TRUE(throws_error([&] { read_model(file); }, ErrorCode::ReadFailed, file)) << name;
    }
}

TEST_F(OccReadModel, UnknownExtensionIsUnsupportedFormat) {
    const std::string file = write_text("part.obj", "v 0 0 0\n");

    EXPECT_TRUE(throws_error([&] { read_model(file); }, ErrorCode::UnsupportedFormat, ".obj"));
}

namespace {

// An ASCII STL of the unit cube's 12 facets (CCW from outside), facet number `skip` left out and,
// when `nan_text` is given, the z coordinate of corner (1, 1, 1) written as that text.
std::string cube_stl(int skip, const char* nan_text = nullptr) {
    const int quads[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4},
                             {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
    std::ostringstream s;
    s << "solid cube\n";
    int facet = 0;
    for (const auto& q : quads)
        for (const auto& t : {std::array<int, 3>{q[0], q[1], q[2]}, {q[0], q[2], q[3]}}) {
            if (facet++ == skip) continue;
            s << " facet normal 0 0 0\n  outer loop\n";
            for (int c : t) {
                s << "   vertex " << (c & 1) << ' ' << ((c >> 1) & 1) << ' ';
                if (c == 7 && nan_text != nullptr)
                    s << nan_text;
                else
                    s << ((c >> 2) & 1);
                s << '\n';
            }
            s << "  endloop\n endfacet\n";
        }
    s << "endsolid cube\n";
    return s.str();
}

}  // namespace

TEST_F(OccReadModel, StlWithANanCoordinateIsNonFinite) {
    const std::string file = write_text("nan.stl", cube_stl(-1, "nan"));

    EXPECT_TRUE(throws_error([&] { read_model(file); }, ErrorCode::NonFiniteCoordinate, "NaN"));
}

// Some exporters write the keywords in capitals ("SOLID", "FACET NORMAL", "ENDSOLID"): the same
// cube, as its lower-case file reads (a NaN in capitals named as one too).
TEST_F(OccReadModel, StlKeywordsAreReadInAnyCase) {
    const auto upper = [](std::string text) {
        for (char& c : text) c = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
        return text;
    };
    const Model lower = read_model(write_text("lower.stl", cube_stl(-1)));
    const Model capitals = read_model(write_text("capitals.stl", upper(cube_stl(-1))));
    ASSERT_EQ(capitals.kind, Model::Kind::Mesh);
    ASSERT_EQ(capitals.mesh.triangles.size(), 12u);
    EXPECT_EQ(capitals.mesh.vertices, lower.mesh.vertices);
    EXPECT_EQ(capitals.mesh.triangles, lower.mesh.triangles);
    EXPECT_NEAR(mesh_volume(model_mesh(capitals)), 1.0, 1e-12);
    EXPECT_TRUE(throws_error([&] { read_model(write_text("nan.stl", upper(cube_stl(-1, "nan")))); },
                             ErrorCode::NonFiniteCoordinate, "NaN"));
    // Cut before ENDSOLID: still truncated.
    std::string cut = upper(cube_stl(-1));
    cut.resize(cut.rfind("ENDSOLID"));
    EXPECT_TRUE(throws_error([&] { read_model(write_text("cut.stl", cut)); }, ErrorCode::ReadFailed,
                             "no 'endsolid'"));
}

TEST_F(OccReadModel, StlWithAMissingTriangleIsAnOpenMesh) {
    const std::string file = write_text("open.stl", cube_stl(5));
    const Model model = read_model(file);
    ASSERT_EQ(model.mesh.triangles.size(), 11u);

    EXPECT_TRUE(throws_error([&] { model_mesh(model); }, ErrorCode::OpenMesh, "3 boundary edges"));
}

TEST_F(OccReadModel, ModelMeshNamesTheFileWhenASolidFileHoldsTwoSolids) {
    const Model model = read_model(write_step("pair.stp", test::two_boxes()));

    EXPECT_TRUE(
        throws_error([&] { model_mesh(model); }, ErrorCode::MultipleSolids, "pair.stp: 2 solids"));
}

TEST_F(OccReadModel, ModelMeshTessellatesASolidFile) {
    const Model model = read_model(write_step("box.step", test::box(0, 0, 0, 10, 20, 30)));

    const TriangleMesh mesh = model_mesh(model);

    EXPECT_EQ(mesh.triangles.size(), 12u);
    EXPECT_NEAR(mesh_volume(mesh), 6000.0, 1e-6);
}

// ---- Exact sections ----------------------------------------------------------------------------

TEST(OccExactSection, BoxAtMidHeightHasTheExactRectangle) {
    const Shape box = test::box(1, 2, 3, 10, 20, 30);

    const Section s = exact_sections(box, {make_plane(Vector3d(0, 0, 18), Vector3d::UnitZ())})[0];

    ASSERT_EQ(s.regions.size(), 1u);
    EXPECT_NEAR(s.area, 200.0, 1e-9 * 200.0);
    EXPECT_LE((s.centroid - Vector3d(6, 12, 18)).norm(), 1e-9);
    EXPECT_EQ(s.open_chains, 0u);
    const SectionRegion& r = s.regions[0];
    EXPECT_EQ(r.shape.outer.points.size(), 4u);
    EXPECT_GT(signed_area(r.shape.outer), 0.0);  // counter-clockwise seen from above
    EXPECT_NEAR(signed_area(r.shape.outer), 200.0, 1e-9);
    EXPECT_TRUE(r.bounds.min().isApprox(Vector3d(1, 2, 18), 1e-9));
    EXPECT_TRUE(r.bounds.max().isApprox(Vector3d(11, 22, 18), 1e-9));
}

TEST(OccExactSection, PlateSectionHasItsHoleClockwise) {
    const Shape plate = test::plate_with_hole();

    const Section s =
        exact_sections(plate, {make_plane(Vector3d(0, 0, 5), Vector3d::UnitZ())}, 0.001)[0];

    const double expected = 60.0 * 40.0 - kPi * 64.0;
    ASSERT_EQ(s.regions.size(), 1u);
    ASSERT_EQ(s.regions[0].shape.holes.size(), 1u);
    EXPECT_NEAR(s.area, expected, 1e-9 * expected);
    EXPECT_LE((s.centroid - Vector3d(30, 20, 5)).norm(), 1e-9);
    EXPECT_LT(signed_area(s.regions[0].shape.holes[0]), 0.0);
    // The discretised hole is inscribed in the circle, within the loop deflection of it.
    const double hole = -signed_area(s.regions[0].shape.holes[0]);
    EXPECT_LT(hole, kPi * 64.0);
    EXPECT_GT(hole, kPi * 64.0 - 2 * kPi * 8 * 0.001);
}

TEST(OccExactSection, TwoPostsGiveTwoRegionsLargestFirst) {
    const Shape posts = test::two_posts();

    const Section s = exact_sections(posts, {make_plane(Vector3d(0, 0, 20), Vector3d::UnitZ())})[0];

    ASSERT_EQ(s.regions.size(), 2u);
    EXPECT_NEAR(s.regions[0].area, 100.0, 1e-9);
    EXPECT_NEAR(s.regions[1].area, 100.0, 1e-9);
    EXPECT_NEAR(s.area, 200.0, 1e-9);
    EXPECT_LE((s.centroid - Vector3d(20, 5, 20)).norm(), 1e-9);
}

// The plane of the arm's underside meets the column inside and the arm on its face: the exact
// section is the closed solid's, their union, one 70 x 20 rectangle. (The mesh kernel gives the
// slab below such a plane instead, the column alone.)
TEST(OccExactSection, PlaneOnAFaceGivesOneRegionWithTheCutBesideIt) {
    const Shape l_block = test::l_block();

    const Section s =
        exact_sections(l_block, {make_plane(Vector3d(0, 0, 40), Vector3d::UnitZ())})[0];

    ASSERT_EQ(s.regions.size(), 1u);
    EXPECT_TRUE(s.regions[0].shape.holes.empty());
    EXPECT_NEAR(s.area, 1400.0, 1e-9 * 1400.0);
    EXPECT_NEAR(signed_area(s.regions[0].shape.outer), 1400.0, 1e-9 * 1400.0);
    EXPECT_LE((s.centroid - Vector3d(35, 10, 40)).norm(), 1e-9);
}

TEST(OccExactSection, ObliquePlaneCutsACylinderInAnEllipse) {
    const double r = 5.0, tilt = 30.0 * kPi / 180.0;
    const Shape cylinder = test::cylinder(Vector3d::Zero(), Vector3d::UnitZ(), r, 40);
    const Vector3d normal(std::sin(tilt), 0.0, std::cos(tilt));

    const Section s = exact_sections(cylinder, {make_plane(Vector3d(0, 0, 20), normal)})[0];

    const double expected = kPi * r * r / std::cos(tilt);
    ASSERT_EQ(s.regions.size(), 1u);
    EXPECT_NEAR(s.area, expected, 1e-9 * expected);
    EXPECT_LE((s.centroid - Vector3d(0, 0, 20)).norm(), 1e-9);
}

TEST(OccExactSection, PlaneAcrossATorusTubeOffItsAxisHasTheIntegratedAreaAndCentroids) {
    // The plane x = c (c < R - r) cuts the tube in two ovals whose boundary OCCT can only trace.
    // With rho = R + r sin(t) the distance from the axis, each oval's area is
    // 2 r^2 * integral of cos^2(t) rho / sqrt(rho^2 - c^2) over t in [-pi/2, pi/2], and its
    // moment about y = 0 is pi r^2 R, so its centroid lies at y = +-pi r^2 R / area. The traced
    // loops are held to the loop deflection (0.01 mm, exact_sections' default): an area within
    // perimeter x deflection, a centroid within the deflection. (OCCT's face for one oval once
    // came out 73.70 mm2 for 78.57, its centroid 0.65 mm off; fitting B-splines to the traces
    // instead put a helical sweep's section 5 % short.)
    const double major = 20.0, minor = 5.0, deflection = 0.01;
    const Shape torus = test::torus(major, minor);
    for (const double c : {0.5, 4.0}) {
        SCOPED_TRACE(c);
        const int n = 20000;
        double area = 0.0;
        for (int i = 0; i < n; ++i) {
            const double t = -kPi / 2 + (i + 0.5) * kPi / n;
            const double rho = major + minor * std::sin(t);
            area += 2.0 * minor * minor * std::cos(t) * std::cos(t) * rho /
                    std::sqrt(rho * rho - c * c) * (kPi / n);
        }
        const double y = kPi * minor * minor * major / area;

        const Section s = exact_sections(torus, {make_plane(Vector3d(c, 0, 0), Vector3d::UnitX())},
                                         deflection)[0];

        ASSERT_EQ(s.regions.size(), 2u);
        for (const auto& region : s.regions) {
            // A convex oval's perimeter is at most its bounding box's.
            const Vector3d size = region.bounds.sizes();
            const double perimeter = 2.0 * (size.y() + size.z());
            EXPECT_NEAR(region.area, area, perimeter * deflection);
            EXPECT_NEAR(region.centroid.x(), c, 1e-9);
            EXPECT_NEAR(std::abs(region.centroid.y()), y, deflection);
            EXPECT_NEAR(region.centroid.z(), 0.0, deflection);
        }
        EXPECT_NEAR(s.regions[0].centroid.y() + s.regions[1].centroid.y(), 0.0, 2.0 * deflection);
    }
}

TEST(OccExactSection, PlanesAlongAHelicalSweepAgreeWithAFineMesh) {
    // The test coil (a tube of radius 3 swept along a helix of pitch 15, a B-spline surface): a
    // horizontal plane cuts it almost along the tube, in a long oval OCCT traces. Its exact area
    // and a fine mesh's differ by at most perimeter x (mesh deflection + loop deflection), the
    // perimeter at most the bounding box's. (Fitting B-splines to the traces put it 5 % short:
    // 225.1 mm2 for 236.9 at z = 18.133.)
    const Model coil = read_model(std::string(MAS_TEST_DATA) + "/coil_c0.step");
    const double mesh_deflection = 0.005, loop_deflection = 0.01;
    TessellationParams params;
    params.deflection_mm = mesh_deflection;
    const TriangleMesh mesh = tessellate(coil.shape, params);
    for (const double z : {18.133, 26.586}) {
        SCOPED_TRACE(z);
        const Plane plane = make_plane(Vector3d(0, 0, z), Vector3d::UnitZ());
        const Section exact = exact_sections(coil.shape, {plane}, loop_deflection)[0];
        const Section cut = slice_mesh(mesh, plane);
        ASSERT_EQ(exact.regions.size(), cut.regions.size());
        ASSERT_FALSE(exact.regions.empty());
        double perimeter = 0.0, across = 0.0;
        for (const auto& r : exact.regions) {
            const Vector3d size = r.bounds.sizes();
            perimeter += 2.0 * (size.x() + size.y());
            across = std::max(across, r.bounds.diagonal().norm());
        }
        // The loops differ by a band at most perimeter x deflection in area, each point of it at
        // most `across` from the centroid: so much moment, over the area, moves the centroid.
        const double band = perimeter * (mesh_deflection + loop_deflection);
        EXPECT_GT(exact.area, 200.0);
        EXPECT_NEAR(exact.area, cut.area, band);
        EXPECT_LE((exact.centroid - cut.centroid).norm(), band * across / exact.area);
    }
}

TEST(OccExactSection, PlaneMissingTheSolidGivesAnEmptySection) {
    const Shape box = test::box(0, 0, 0, 10, 10, 10);
    const Vector3d origin(0, 0, 50);

    const Section s = exact_sections(box, {make_plane(origin, Vector3d::UnitZ())})[0];

    EXPECT_TRUE(s.empty());
    EXPECT_EQ(s.area, 0.0);
    EXPECT_EQ(s.centroid, origin);
}

TEST(OccExactSection, RejectsBadPlanesAndNonSolids) {
    const Shape box = test::box(0, 0, 0, 10, 10, 10);
    const Plane zero{Vector3d::Zero(), Vector3d::Zero()};
    const Plane nan{Vector3d(std::nan(""), 0, 0), Vector3d::UnitZ()};

    EXPECT_TRUE(
        throws_error([&] { exact_sections(box, {zero}); }, ErrorCode::InvalidArgument, "normal"));
    EXPECT_TRUE(
        throws_error([&] { exact_sections(box, {nan}); }, ErrorCode::InvalidArgument, "origin"));
    EXPECT_TRUE(throws_error([&] { exact_sections(box, {Plane{}}, 0.0); },
                             ErrorCode::InvalidArgument, "deflection"));
    EXPECT_TRUE(throws_error([&] { exact_sections(test::single_face(), {Plane{}}); },
                             ErrorCode::NotASolid, "not a solid"));
}

// Mesh sections against exact ones. Where the plane crosses the surface at right angles, the mesh
// section's boundary stays within the deflection d of the exact one, so the areas differ by at
// most perimeter x d and the centroids by at most d; on a convex section the mesh's chords lie
// inside, so its area is not larger.
struct Expectation {
    Plane plane;
    double perimeter;  // of the exact section, mm
    bool convex;
};

void expect_mesh_agrees_with_exact(const Shape& solid, const std::vector<Expectation>& cases,
                                   double d) {
    TessellationParams params;
    params.deflection_mm = d;
    const TriangleMesh mesh = tessellate(solid, params);
    std::vector<Plane> planes;
    for (const auto& c : cases) planes.push_back(c.plane);

    const std::vector<Section> exact = exact_sections(solid, planes);
    const std::vector<Section> cut = slice_mesh(mesh, planes);

    for (std::size_t i = 0; i < cases.size(); ++i) {
        SCOPED_TRACE(i);
        ASSERT_FALSE(exact[i].empty());
        EXPECT_EQ(cut[i].regions.size(), exact[i].regions.size());
        EXPECT_EQ(cut[i].open_chains, 0u);
        EXPECT_LE(std::abs(cut[i].area - exact[i].area), cases[i].perimeter * d);
        if (cases[i].convex) {
            EXPECT_LE(cut[i].area, exact[i].area);
        }
        EXPECT_LE((cut[i].centroid - exact[i].centroid).norm(), d);
    }
}

TEST(OccExactSection, MeshSectionsOfACylinderAgreeWithinTheDeflection) {
    const double r = 10.0;
    const Shape cylinder = test::cylinder(Vector3d(3, -2, 0), Vector3d::UnitZ(), r, 30);
    std::vector<Expectation> cases;
    for (const double z : {0.7, 7.5, 15.0, 29.3})
        cases.push_back({make_plane(Vector3d(0, 0, z), Vector3d::UnitZ()), 2 * kPi * r, true});

    for (const double d : {0.1, 0.01}) {
        SCOPED_TRACE(d);
        expect_mesh_agrees_with_exact(cylinder, cases, d);
    }
}

TEST(OccExactSection, MeshSectionsOfATorusAgreeWithinTheDeflection) {
    const double major = 20.0, minor = 5.0;
    const Shape torus = test::torus(major, minor);
    // Both planes meet the surface at right angles: the equator plane cuts an annulus (outer
    // circle convex, inner one concave), planes through the axis cut two discs.
    const std::vector<Expectation> cases = {
        {make_plane(Vector3d::Zero(), Vector3d::UnitZ()), 4 * kPi * major, false},
        {make_plane(Vector3d::Zero(), Vector3d::UnitX()), 4 * kPi * minor, true},
        {make_plane(Vector3d::Zero(), Vector3d(1, 2, 0)), 4 * kPi * minor, true},
    };

    for (const double d : {0.1, 0.01}) {
        SCOPED_TRACE(d);
        expect_mesh_agrees_with_exact(torus, cases, d);
    }
}

}  // namespace
}  // namespace mas
