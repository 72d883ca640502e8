// The planner's bars judged by rule (b) as built (toolpath/bar_check), with
// the walk the validator uses (layers/crossing): a bar resting on two pillar
// tops crosses the gap between them; a bar grazing the flank of a wide
// column it does not rest on leaves that column along its edge.
#include <gtest/gtest.h>

#include "support/stacks.hpp"
#include "toolpath/bar_check.hpp"
#include "toolpath/support_paths.hpp"

using namespace scaffold;

namespace {

// A bar at z 4.0 (printed on layers 20 and 21, z 4.2 and 4.4) from (20, 20)
// to (30, 20), on loops of outer radius 1 at its ends on layers 17-21; with
// `beside`, a loop of outer radius 2.5 on layers 17-19 whose edge passes
// 0.25 mm from the bar's near line (within rule (a)'s reach, 0.336 mm).
std::vector<std::size_t> unheld(bool beside) {
    Settings s;
    const layers::LayerStack st = test::empty_stack(6);
    plan::Scaffold sc;
    plan::Bridge br;
    br.x0 = 20, br.y0 = 20, br.x1 = 30, br.y1 = 20, br.z = 4.0;
    sc.bridges.push_back(br);
    toolpath::SupportPaths paths;
    for (int layer = 17; layer <= 21; ++layer) {
        toolpath::LayerPaths lp;
        lp.layer = layer;
        for (double x : {20.0, 30.0}) lp.paths.push_back({toolpath::loop(x, 20, 1.0, s.support_width), s.support_width});
        if (beside && layer <= 19) {
            const double y = 20 + s.support_width / 2 + 0.25 + 2.5;
            lp.paths.push_back({toolpath::loop(25, y, 2.5, s.support_width), s.support_width});
        }
        if (layer >= 20)
            for (auto& line : toolpath::bar_lines(br, s.support_width, s.pillar_radius))
                lp.paths.push_back({line, s.support_width});
        paths.layers.push_back(std::move(lp));
    }
    return toolpath::unheld_bars(sc, paths, st, s);
}

}  // namespace

TEST(BarCheck, BarAcrossTwoPillarTopsIsHeld) { EXPECT_TRUE(unheld(false).empty()); }

TEST(BarCheck, BarAlongTheFlankOfAColumnIsNotHeld) { EXPECT_EQ(unheld(true), std::vector<std::size_t>{0}); }
