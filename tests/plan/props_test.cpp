// Props under bars that pass beside a column (METHOD's rule (b)), with
// numbers worked out by hand, and a scene judged by the bar check's walk.
#include <gtest/gtest.h>

#include <cmath>

#include "plan/obstacles.hpp"
#include "plan/props.hpp"
#include "support/stacks.hpp"
#include "toolpath/bar_check.hpp"
#include "toolpath/support_paths.hpp"

using namespace scaffold;

namespace {

plan::Column pillar(double x, double y, double z1, double r, plan::Top top) {
    plan::Column c;
    c.x0 = c.x1 = x;
    c.y0 = c.y1 = y;
    c.z1 = c.hold_z = z1;
    c.radius = r;
    c.top = top;
    return c;
}

// A 10 mm bar at z 4 along y = 30 on its two end pillars.
plan::Scaffold bar_on_pillars() {
    plan::Scaffold sc;
    sc.bridges.push_back({21, 30, 31, 30, 4.0, {}, 0, 0, false});
    sc.columns.push_back(pillar(21, 30, 4.0, 1.0, plan::Top::Bridge));
    sc.columns.push_back(pillar(31, 30, 4.0, 1.0, plan::Top::Bridge));
    return sc;
}

}  // namespace

// Centre 1.5 mm off the line, radius 1: beside (0.5 mm beyond the loop,
// within kBesideBar). 0.2 off: the line crosses the loop within its bead
// (0.2 <= 1 - 0.45), it rests on it. 3.5 off: 2.5 beyond the loop, clear.
TEST(Props, PassesBesideByTheCentreLineDistance) {
    const Settings s;
    const plan::Bridge bar{21, 30, 31, 30, 4.0, {}, 0, 0, false};
    EXPECT_NEAR(plan::passes_beside(pillar(26, 31.5, 8, 1.0, plan::Top::Contact), bar, s), 1.5, 1e-9);
    EXPECT_LT(plan::passes_beside(pillar(26, 30.2, 8, 1.0, plan::Top::Contact), bar, s), 0);
    EXPECT_LT(plan::passes_beside(pillar(26, 33.5, 8, 1.0, plan::Top::Contact), bar, s), 0);
    // Under the layers of the bar only if it reaches them.
    EXPECT_LT(plan::passes_beside(pillar(26, 31.5, 3.8, 1.0, plan::Top::Contact), bar, s), 0);
    // What the bar's ends stand on is no column beside it: the end pillar,
    // and one whose loop (r 1 + a bead) reaches the end, 1.2 mm off.
    EXPECT_LT(plan::passes_beside(pillar(21, 30, 4.0, 1.0, plan::Top::Bridge), bar, s), 0);
    EXPECT_LT(plan::passes_beside(pillar(31.5, 31.1, 8, 1.0, plan::Top::Contact), bar, s), 0);
}

// The prop leans 1.5 mm from the pillar's centre to the bar's line. A loop
// may shift min(0.5 x pillar radius 1, 0.2 tan 55 + 0.45 / 2 = 0.511) =
// 0.5 mm on a 0.2 mm layer, so it needs 3 layers: it stands on the
// pillar's loop at z 3.4 and reaches (26, 30) at z 4.0, the pillar's
// radius 1 all the way (a loop over the pillar's own).
TEST(Props, LeansOverTheFewestLayers) {
    const Settings s;
    const layers::LayerStack st = test::empty_stack(10);
    const plan::Obstacles obs{st, s};
    const plan::Column beside = pillar(26, 31.5, 8, 1.0, plan::Top::Contact);
    const plan::Bridge bar{21, 30, 31, 30, 4.0, {}, 0, 0, false};
    const std::vector<plan::Column> p = plan::prop_under({&beside}, bar, st, obs, s);
    ASSERT_EQ(p.size(), 1u);
    EXPECT_NEAR(p[0].z0, 3.4, 1e-9);
    EXPECT_NEAR(p[0].z1, 4.0, 1e-9);
    EXPECT_NEAR(p[0].x0, 26, 1e-9);
    EXPECT_NEAR(p[0].y0, 31.5, 1e-9);
    EXPECT_NEAR(p[0].x1, 26, 1e-9);
    EXPECT_NEAR(p[0].y1, 30, 1e-9);
    EXPECT_NEAR(p[0].radius, 1.0, 1e-9);
    EXPECT_EQ(p[0].base, plan::Base::Column);
    EXPECT_EQ(p[0].top, plan::Top::Bridge);
}

// A pillar whose loop starts one layer under the bar has no room to lean
// 1.5 mm: no prop. Stacked on a piece below, the prop stands on that one.
TEST(Props, StandsOnThePieceBelowWhereTheTopPieceIsShort) {
    const Settings s;
    const layers::LayerStack st = test::empty_stack(10);
    const plan::Obstacles obs{st, s};
    const plan::Bridge bar{21, 30, 31, 30, 4.0, {}, 0, 0, false};
    plan::Column lower = pillar(26, 31.5, 3.8, 1.0, plan::Top::Column);
    plan::Column upper = pillar(26, 31.5, 8, 1.0, plan::Top::Contact);
    upper.z0 = 3.8;
    upper.base = plan::Base::Column;
    EXPECT_TRUE(plan::prop_under({&upper}, bar, st, obs, s).empty());
    const std::vector<plan::Column> p = plan::prop_under({&upper, &lower}, bar, st, obs, s);
    ASSERT_EQ(p.size(), 1u);
    EXPECT_NEAR(p[0].z0, 3.4, 1e-9);
}

// The model within the gap of the prop's path: none.
TEST(Props, KeepsTheGapToTheModel) {
    const Settings s;
    const layers::LayerStack st = test::stack_of(
        50, [](int i, layers::Layer& l) {
            test::bead(l, 0, 0, 0.5, 0, gcode::Role::Perimeter);
            if (i >= 17 && i <= 19) test::bead(l, 24, 29.2, 28, 29.2, gcode::Role::Perimeter);  // z 3.6 to 4.0
        },
        {-5, -5, 60, 60});
    const plan::Obstacles obs{st, s};
    const plan::Column beside = pillar(26, 31.5, 8, 1.0, plan::Top::Contact);
    const plan::Bridge bar{21, 30, 31, 30, 4.0, {}, 0, 0, false};
    EXPECT_TRUE(plan::prop_under({&beside}, bar, st, obs, s).empty());
}

// The scene as the pipeline judges it (the bunny's, sliced by PrusaSlicer,
// at z 7): an 11.1 mm bar, and 2.1 mm from its end a pillar whose centre
// lies 1.45 mm off its line. The bar's bead leaves its end pillar and runs
// along the edge of the one beside, which holds it there within reach
// without the bead crossing onto it: rule (b) holds neither that stretch
// nor the gap before it. With the prop the bar crosses the prop's loop,
// and is held. So is it where the pillar stands 0.9 mm off (the line
// crosses its loop) or 2.2 mm off (out of reach).
TEST(Props, HoldTheBarAsBuilt) {
    const Settings s;
    const layers::LayerStack st = test::empty_stack(12);
    const plan::Obstacles obs{st, s};
    auto scene = [](double off) {
        plan::Scaffold sc;
        sc.bridges.push_back({13.95, 13.95, 13.95, 25.05, 7.0, {}, 0, 0, false});
        sc.columns.push_back(pillar(13.95, 13.95, 7.0, 1.0, plan::Top::Bridge));
        sc.columns.push_back(pillar(13.95, 25.05, 7.0, 1.0, plan::Top::Bridge));
        sc.columns.push_back(pillar(13.95 + off, 16.05, 8.6, 0.75, plan::Top::Contact));
        return sc;
    };
    auto unheld = [&](const plan::Scaffold& sc) {
        return toolpath::unheld_bars(sc, toolpath::make_paths(sc, st, s, &obs), st, s).size();
    };
    EXPECT_EQ(unheld(scene(0.9)), 0u);
    EXPECT_EQ(unheld(scene(2.2)), 0u);
    plan::Scaffold sc = scene(1.45);
    ASSERT_EQ(unheld(sc), 1u);
    EXPECT_EQ(plan::prop_bars(sc, {0}, st, obs, s), 1);
    ASSERT_EQ(sc.columns.size(), 4u);
    EXPECT_EQ(unheld(sc), 0u);
    // A pillar whose first loop lies on the layer under the bar has no
    // room for a prop: the bar stays unheld (the pipeline plans again).
    plan::Scaffold late = scene(1.45);
    late.columns.back().z0 = 6.8;
    late.columns.back().base = plan::Base::Model;
    ASSERT_EQ(unheld(late), 1u);
    EXPECT_EQ(plan::prop_bars(late, {0}, st, obs, s), 0);
}

// A prop that would pass beside another bar is not added.
TEST(Props, NoneBesideAnotherBar) {
    const Settings s;
    const layers::LayerStack st = test::empty_stack(10);
    const plan::Obstacles obs{st, s};
    plan::Scaffold sc = bar_on_pillars();
    sc.columns.push_back(pillar(26, 31.5, 8, 1.0, plan::Top::Contact));
    // A bar at z 3.6 along x = 27.5, on pillars of its own: the prop's
    // centre there, (26, 31), lies 1.5 mm off its line.
    sc.bridges.push_back({27.5, 25, 27.5, 36, 3.6, {}, 0, 0, false});
    sc.columns.push_back(pillar(27.5, 25, 3.6, 1.0, plan::Top::Bridge));
    sc.columns.push_back(pillar(27.5, 36, 3.6, 1.0, plan::Top::Bridge));
    EXPECT_EQ(plan::prop_bars(sc, {0}, st, obs, s), 0);
}
