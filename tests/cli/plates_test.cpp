// The whole pipeline on a plate of objects far enough apart to be planned
// as independent groups: the same output for any thread count, and each
// object the support it gets alone. And a plate of exact copies: one copy
// planned, its plan moved to the others.
#include <gtest/gtest.h>
#include <spdlog/logger.h>
#include <spdlog/sinks/ringbuffer_sink.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <memory>
#include <string>
#include <vector>

#include "cli/pipeline.hpp"
#include "support/synth.hpp"

using namespace scaffold;

namespace {

// Mushrooms (a cap of radius 6 on a stem of radius 2.5) at these x, y 105
// (or `y`); the last one's cap `last_cap` wide when given.
std::string mushrooms(const std::vector<double>& xs, double last_cap = 6.0, double y = 105) {
    scaffold::testing::SynthGcode g;
    for (int l = 1; l <= 20; ++l) {
        const double z = 0.2 * l;
        g.layer(z);
        g.type("External perimeter");
        for (std::size_t k = 0; k < xs.size(); ++k)
            g.filled_disc(xs[k], y, z > 3.0 + 1e-9 ? (k + 1 == xs.size() ? last_cap : 6.0) : 2.5);
    }
    return g.str();
}

// The support's extrusions (end points, 3 decimals as written) whose x lies
// in [x0, x1), moved by -x0.
std::vector<std::pair<long, long>> support_moves(const std::string& out, double x0, double x1, double y0 = 0) {
    std::vector<std::pair<long, long>> moves;
    bool support = false;
    std::size_t at = 0;
    while (at < out.size()) {
        std::size_t end = out.find('\n', at);
        if (end == std::string::npos) end = out.size();
        const std::string line = out.substr(at, end - at);
        at = end + 1;
        if (line.rfind(";TYPE:", 0) == 0) support = line == ";TYPE:Support material";
        if (!support || line.rfind("G1 X", 0) != 0 || line.find(" E") == std::string::npos) continue;
        const double x = std::strtod(line.c_str() + 4, nullptr);
        const double y = std::strtod(line.c_str() + line.find(" Y") + 2, nullptr);
        if (x >= x0 && x < x1) moves.emplace_back(std::lround((x - x0) * 1000), std::lround((y - y0) * 1000));
    }
    return moves;
}

struct Planned {
    std::string out;
    std::vector<std::string> log;
};

// A second thread joins at once (by default after 2 s: never on plates
// this light), with its own caches over the first's model rasters.
Planned run(std::string in, int threads, bool plan_copies = false) {
    auto sink = std::make_shared<spdlog::sinks::ringbuffer_sink_mt>(200);
    spdlog::logger log("plates", sink);
    log.set_level(spdlog::level::debug);
    Planned r;
    cli::Request req;
    req.input = req.output = "plate.gcode";
    req.input_text = &in;
    req.output_text = &r.out;
    req.threads = threads;
    req.second_thread_after_s = 0;
    req.plan_copies = plan_copies;
    cli::run(req, log);
    r.log = sink->last_formatted();
    return r;
}

double support_mm(const std::string& out) {
    const std::string key = "; scaffold: support filament used [mm] = ";
    const auto at = out.find(key);
    return at == std::string::npos ? -1 : std::strtod(out.c_str() + at + key.size(), nullptr);
}

bool same_moved(std::vector<std::pair<long, long>> a, std::vector<std::pair<long, long>> b) {
    if (a.size() != b.size()) return false;
    std::sort(a.begin(), a.end());
    std::sort(b.begin(), b.end());
    for (std::size_t i = 0; i < a.size(); ++i)
        if (std::abs(a[i].first - b[i].first) > 1 || std::abs(a[i].second - b[i].second) > 1) return false;
    return true;
}

bool said(const Planned& r, const std::string& what) {
    for (const std::string& line : r.log)
        if (line.find(what) != std::string::npos) return true;
    return false;
}

}  // namespace

TEST(Plates, SameOutputForAnyThreadCount) {
    const std::string plate = mushrooms({30, 110, 190});
    const Planned one = run(plate, 1), two = run(plate, 2), again = run(plate, 2);
    EXPECT_TRUE(said(one, "in 3 independent groups, planned on 1 threads"));
    EXPECT_TRUE(said(two, "in 3 independent groups, planned on 2 threads"));
    EXPECT_GT(support_mm(one.out), 0);
    EXPECT_EQ(one.out, two.out);
    EXPECT_EQ(two.out, again.out);
}

TEST(Plates, EachObjectGetsTheSupportItGetsAlone) {
    const double alone = support_mm(run(mushrooms({110}), 2).out);
    const double three = support_mm(run(mushrooms({30, 110, 190}), 2).out);
    ASSERT_GT(alone, 0);
    EXPECT_NEAR(three, 3 * alone, 0.02 * 3 * alone);
}

TEST(Plates, ObjectsWithinReachArePlannedApartWhereTheirPlansStayApart) {
    // 25 mm apart, within a bar's reach: each object its own group all the
    // same, and each the support it gets alone.
    const Planned two = run(mushrooms({100, 125}), 2), one = run(mushrooms({100, 125}), 1);
    EXPECT_TRUE(said(two, "in 2 independent groups"));
    EXPECT_FALSE(said(two, "came close"));
    EXPECT_EQ(two.out, one.out);
    const double alone = support_mm(run(mushrooms({110}), 2).out);
    ASSERT_GT(alone, 0);
    EXPECT_NEAR(support_mm(two.out), 2 * alone, 0.02 * 2 * alone);
}

TEST(Plates, ObjectsWhosePlansComeCloseArePlannedAsOne) {
    // Caps 2 mm apart (two objects), the columns under their facing edges
    // closer than kPlansApart: joined in one group, whose first round is
    // the parts' plans side by side, braced, made into paths and checked as
    // one. They hold (nothing of one stands in the other's way): no bridge
    // search of the whole. (Of sixty random pairs of caps and planks 0.5 to
    // 3.5 mm apart at 8 to 18 mm, the 25 whose plans came close all held
    // side by side: no synthetic scene here falls back to the search of
    // the whole.)
    const Planned r = run(mushrooms({100, 114}), 2);
    EXPECT_TRUE(said(r, "in 2 independent groups"));
    EXPECT_TRUE(said(r, "plans of 2 groups came close: planned again as 1"));
    EXPECT_TRUE(said(r, "the parts' plans side by side hold: not planned again"));
    EXPECT_FALSE(said(r, "the joined group planned whole"));
    EXPECT_GT(support_mm(r.out), 0);
    EXPECT_EQ(r.out, run(mushrooms({100, 114}), 1).out);
}

TEST(Plates, ExactCopiesArePlannedOnceAndTheirPlanMoved) {
    // 30 mm apart: within a bar's reach, one group when planned whole.
    const Planned r = run(mushrooms({30, 60, 90}), 1, true);
    EXPECT_TRUE(said(r, "3 exact copies: one planned"));
    const auto first = support_moves(r.out, 15, 45), second = support_moves(r.out, 45, 75),
               third = support_moves(r.out, 75, 105);
    ASSERT_GT(first.size(), 20u);
    // The same extrusions (in an order of their own: a layer's paths are
    // ordered over the whole plate), each 30 mm on, within the written
    // decimals' rounding.
    EXPECT_TRUE(same_moved(first, second));
    EXPECT_TRUE(same_moved(first, third));
    // And each copy as much support as a mushroom alone (its neighbours,
    // 18 mm off, are in no column's way).
    const double alone = support_mm(run(mushrooms({60}), 1).out);
    EXPECT_NEAR(support_mm(r.out), 3 * alone, 0.02 * 3 * alone);
}

TEST(Plates, APlateWithADifferentObjectOrWholePlateIsPlannedWhole) {
    EXPECT_FALSE(said(run(mushrooms({30, 60, 90}, 5.5), 1, true), "exact copies"));
    EXPECT_FALSE(said(run(mushrooms({30, 60, 90}), 1, false), "exact copies"));
}

// The plan is made in the model's own frame (layers/frame.hpp): moved on the
// bed by a part of a cell (0.1 mm), a model gets the same support, moved.
// Planned on the bed's own lattice, a mushroom moved 0.037 mm right and
// 0.071 mm up had other support.
TEST(Plates, AModelGetsTheSameSupportWhereverItStands) {
    const Planned here = run(mushrooms({110}), 1);
    const auto moves = support_moves(here.out, 90, 130);
    ASSERT_GT(moves.size(), 20u);
    for (const auto& [dx, dy] : {std::pair{0.037, 0.071}, std::pair{-0.05, 0.05}, std::pair{20.013, -30.006}}) {
        const Planned there = run(mushrooms({110 + dx}, 6.0, 105 + dy), 1);
        EXPECT_TRUE(same_moved(moves, support_moves(there.out, 90 + dx, 130 + dx, dy))) << dx << ", " << dy;
        EXPECT_EQ(support_mm(here.out), support_mm(there.out)) << dx << ", " << dy;
    }
}

// A copy on a plate is planned as the model alone on the bed is: the same
// extrusions, moved (no skirt here, and the neighbours 30 mm off are in no
// column's way).
TEST(Plates, ACopyGetsTheSupportOfTheModelAlone) {
    const Planned plate = run(mushrooms({30, 60, 90}), 1, true);
    ASSERT_TRUE(said(plate, "3 exact copies: one planned"));
    const Planned alone = run(mushrooms({60.043}), 1);
    const auto one = support_moves(alone.out, 45.043, 75.043);
    ASSERT_GT(one.size(), 20u);
    EXPECT_TRUE(same_moved(one, support_moves(plate.out, 15, 45)));
    EXPECT_TRUE(same_moved(one, support_moves(plate.out, 75, 105)));
}
