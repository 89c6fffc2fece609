// Progress reporting and cancellation of the long engine computations (Progress.hpp).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <utility>
#include <vector>

#include "mas/CentroidalAxis.hpp"
#include "mas/Decompose.hpp"
#include "mas/Error.hpp"
#include "mas/Paths.hpp"
#include "mas/Progress.hpp"
#include "mas/Shape.hpp"
#include "mas/SlicePart.hpp"
#include "test_parts.hpp"

namespace {

constexpr double kDeflection = 0.02;  // mm, tessellation of the test parts

using Reports = std::vector<std::pair<double, std::string>>;

mas::Progress recorder(Reports& reports) {
    return mas::Progress(
        [&reports](double f, const std::string& stage) { reports.emplace_back(f, stage); });
}

bool has_stage(const Reports& reports, const std::string& start) {
    for (const auto& r : reports)
        if (r.second.rfind(start, 0) == 0) return true;
    return false;
}

void expect_never_back_and_done(const Reports& reports) {
    ASSERT_FALSE(reports.empty());
    for (std::size_t i = 0; i < reports.size(); ++i) {
        EXPECT_GE(reports[i].first, 0.0) << "report " << i;
        EXPECT_LE(reports[i].first, 1.0) << "report " << i;
        if (i > 0) {
            EXPECT_GE(reports[i].first, reports[i - 1].first) << "report " << i;
        }
    }
    EXPECT_EQ(reports.back().first, 1.0);
}

struct Stop {};  // an exception of the caller's own, not an engine error

// The two posts on a plate (boxes: their meshes are exact), with its axis and decomposition.
struct TwoPosts {
    mas::Shape part = mas::test::two_posts();
    mas::CentroidalAxis axis;
    mas::Decomposition d;
    mas::SlicePartParams params;

    TwoPosts() {
        mas::TessellationParams tp;
        tp.deflection_mm = kDeflection;
        axis = mas::centroidal_axis(mas::tessellate(part, tp), {});
        d = mas::decompose(part, axis);
        params.tessellation.deflection_mm = kDeflection;
    }
};

}  // namespace

TEST(Progress, SpansReportTheirShareOfTheWholeAndNeverGoBack) {
    Reports r;
    const mas::Progress whole = recorder(r);
    const mas::Progress second = whole.span(0.5, 1.0, "second half");
    second(0.5);
    ASSERT_EQ(r.size(), 1u);
    EXPECT_DOUBLE_EQ(r.back().first, 0.75);
    EXPECT_EQ(r.back().second, "second half");
    // A span of a span, inheriting the stage; clamped to its share.
    const mas::Progress inner = second.span(0.0, 0.5);
    inner(2.0);
    EXPECT_DOUBLE_EQ(r.back().first, 0.75);
    EXPECT_EQ(r.back().second, "second half");
    inner(0.2);  // 0.55 < 0.75: what was reported stays
    EXPECT_DOUBLE_EQ(r.back().first, 0.75);
    second(1.0);
    EXPECT_DOUBLE_EQ(r.back().first, 1.0);
    whole.span(0.0, 0.1, "first tenth").check();  // no news: the fraction reported so far
    EXPECT_DOUBLE_EQ(r.back().first, 1.0);
    EXPECT_EQ(r.back().second, "first tenth");
    EXPECT_EQ(r.size(), 5u);
}

TEST(Progress, AnEmptyProgressReportsNothing) {
    const mas::Progress none;
    EXPECT_FALSE(none);
    none(0.5);
    none.check();
    none.span(0.2, 0.4, "x")(1.0);
    EXPECT_FALSE(mas::Progress(mas::Progress::Report{}));
}

TEST(Progress, AxisReportsTheVolumeSweptSoFar) {
    // A 10 x 20 x 30 box, step 2: the march takes plane k (at 0.001 + 2k) once the nodes below
    // it have swept 200 x (2.001 + 2 (k - 1)) of its 6000 mm^3.
    const auto mesh = mas::test::box_mesh(0, 0, 0, 10, 20, 30);
    mas::AxisParams params;
    params.step_mm = 2.0;
    Reports r;
    const auto axis = mas::centroidal_axis(mesh, params, recorder(r));
    ASSERT_EQ(axis.nodes.size(), 15u);
    expect_never_back_and_done(r);
    for (int k = 1; k < 15; ++k) {
        const double want = 200.0 * (2.001 + 2.0 * (k - 1)) / 6000.0;
        EXPECT_TRUE(std::any_of(r.begin(), r.end(),
                                [&](const auto& x) { return std::abs(x.first - want) < 1e-12; }))
            << "plane " << k;
    }
    // A report that throws stops the search, its exception unchanged.
    int calls = 0;
    EXPECT_THROW(mas::centroidal_axis(mesh, params, mas::Progress([&](double, const std::string&) {
                                          if (++calls == 5) throw Stop{};
                                      })),
                 Stop);
    EXPECT_EQ(calls, 5);
}

TEST(Progress, DecompositionReportsBranchByBranchUpToOne) {
    const auto part = mas::test::two_posts();
    mas::TessellationParams tp;
    tp.deflection_mm = kDeflection;
    const auto axis = mas::centroidal_axis(mas::tessellate(part, tp), {});
    Reports r;
    const auto d = mas::decompose(part, axis, {}, recorder(r));
    EXPECT_EQ(d.components.size(), 3u);
    expect_never_back_and_done(r);
    EXPECT_GE(r.size(), axis.branches.size());
    // Within the split that cuts both posts off: when it starts, as the other post is tried for
    // the same plane (one report per sibling tried: 400 posts ran 8 s without one), once the
    // siblings sharing its plane are known, before each of the two posts' pieces is checked
    // (each valid at once), and before and as the rest of the plate is.
    const long in_split = std::count_if(
        r.begin(), r.end(), [](const auto& x) { return x.second == "splitting at branch 1 of 3"; });
    EXPECT_EQ(in_split, 7);
}

TEST(Progress, SlicingReportsEveryStageInOrderUpToOne) {
    const TwoPosts p;
    const mas::Decomposition& d = p.d;
    ASSERT_EQ(d.components.size(), 3u);
    Reports r;
    const mas::SlicedPart sliced = mas::slice_part(p.part, p.axis, d, p.params, recorder(r));
    expect_never_back_and_done(r);
    // Every layer reports once as it is laid, besides the checks between candidate planes.
    EXPECT_GE(r.size(), sliced.layers.size());
    // The stages, in this order.
    const std::vector<std::string> stages = {"tessellating the components",
                                             "ordering the components",
                                             "slicing component 0 (1 of 3)",
                                             "slicing component",
                                             "planning the bead paths",
                                             "finding what each component rests on",
                                             "checking the nozzle against the layers",
                                             "ordering the layers"};
    std::size_t at = 0;
    for (const std::string& stage : stages) {
        while (at < r.size() && r[at].second.rfind(stage, 0) != 0) ++at;
        EXPECT_LT(at, r.size()) << "no stage \"" << stage << "\" after the one before";
    }
    EXPECT_TRUE(has_stage(r, "slicing component 1 ("));
    EXPECT_TRUE(has_stage(r, "slicing component 2 ("));
    // Each component's layers fill its share by volume: the plate's ends where the posts' begin.
    double plate_done = 0.0;
    for (const auto& x : r)
        if (x.second.rfind("slicing component 0", 0) == 0) plate_done = x.first;
    const double share =
        d.components[0].volume_mm3 /
        (d.components[0].volume_mm3 + d.components[1].volume_mm3 + d.components[2].volume_mm3);
    EXPECT_NEAR(plate_done, 0.1 + 0.9 * (0.05 + 0.8 * share), 1e-9);
}

TEST(Progress, AnExceptionFromTheReportStopsSlicingUnchanged) {
    const TwoPosts p;
    // Stopped in each stage in turn; the same call then runs to its end.
    for (const std::string stage :
         {"tessellating", "ordering", "slicing component 2", "planning", "checking the nozzle"}) {
        int after = 0;
        EXPECT_THROW(mas::slice_part(p.part, p.axis, p.d, p.params,
                                     mas::Progress([&](double, const std::string& s) {
                                         if (s.rfind(stage, 0) == 0 && ++after == 2) throw Stop{};
                                     })),
                     Stop)
            << stage;
        EXPECT_EQ(after, 2) << stage;
    }
    Reports r;
    const mas::SlicedPart sliced = mas::slice_part(p.part, p.axis, p.d, p.params, recorder(r));
    EXPECT_GT(sliced.layers.size(), 0u);
    expect_never_back_and_done(r);
}

TEST(Progress, OneLayersPathsCanBeStoppedWhileTheyArePlanned) {
    // A 100 x 100 mm layer at a 0.05 mm bead: 2400 raster lines, ordered nearest-next. A layer's
    // paths were planned without a report (the example bracket at a 0.01 mm bead: 5 s in its
    // first layer, the GUI with no dialog and no Cancel).
    mas::Region2 square;
    square.outer.points = {{0, 0}, {100, 0}, {100, 100}, {0, 100}};
    mas::PathParams params;
    params.bead_width_mm = 0.05;
    int checks = 0;
    EXPECT_THROW(mas::plan_layer_paths({square}, params, 0, {0, 0},
                                       mas::Progress([&](double f, const std::string&) {
                                           EXPECT_EQ(f, 0.0);  // checks, no fraction
                                           if (++checks == 20) throw Stop{};
                                       })),
                 Stop);
    EXPECT_EQ(checks, 20);
    // Without a caller the paths are the same as with one that lets them run.
    int all = 0;
    const mas::LayerPaths2 checked = mas::plan_layer_paths(
        {square}, params, 0, {0, 0}, mas::Progress([&](double, const std::string&) { ++all; }));
    EXPECT_GT(all, 40);
    const mas::LayerPaths2 plain = mas::plan_layer_paths({square}, params, 0, {0, 0});
    ASSERT_EQ(checked.paths.size(), plain.paths.size());
    EXPECT_EQ(checked.deposit_length_mm, plain.deposit_length_mm);
}
