// Braces for METHOD's Standing rule: weak columns tied to two neighbours by
// bars in triangles, with numbers worked out by hand.
#include <gtest/gtest.h>

#include <cmath>

#include "plan/braces.hpp"
#include "plan/candidates.hpp"
#include "plan/planner.hpp"
#include "plan/stiffness.hpp"
#include "support/stacks.hpp"

using namespace scaffold;

namespace {

// A plain straight column (no taper, neck, foot or raft) from the bed to z1.
plan::Column plain(double x, double y, double z1) {
    plan::Column c;
    c.x0 = c.x1 = x;
    c.y0 = c.y1 = y;
    c.z1 = c.hold_z = z1;
    c.radius = 1.0;
    c.top = plan::Top::Bridge;
    return c;
}

}  // namespace

// A 15 mm plain 2 mm ring on 0.2 mm layers: the sum over layers of (15 -
// z_mid)^2 0.2 is 1125 - 75 x 0.2^3 / 12 = 1124.95 (the midpoint rule);
// over E I = 3500 x 0.658063 = 2303.22: 0.488425 mm/N, 2.0474 N/mm.
TEST(Braces, ChainComplianceByLayers) {
    Settings s;
    const layers::LayerStack st = test::empty_stack(40, 80);
    plan::Scaffold sc;
    sc.columns.push_back(plain(30, 30, 15));
    const auto chains = plan::pillar_chains(sc);
    ASSERT_EQ(chains.size(), 1u);
    EXPECT_NEAR(plan::chain_compliance(chains[0], 15, sc, st, s), 0.488425, 1e-6);
}

// Pieces stacked on one another (a pillar that stepped aside) are one
// pillar; a connector on a bar, or a branch landing elsewhere, is none.
TEST(Braces, PillarChainsFollowTheirPieces) {
    plan::Scaffold sc;
    sc.columns.push_back(plain(30, 30, 10));
    plan::Column step = plain(30, 30, 10.2);
    step.z0 = 10;
    step.x1 = 30.3;
    step.base = plan::Base::Column;
    sc.columns.push_back(step);
    plan::Column up = plain(30.3, 30, 20);
    up.z0 = 10.2;
    up.base = plan::Base::Column;
    sc.columns.push_back(up);
    plan::Column connector = plain(40, 40, 25);
    connector.z0 = 20.4;
    connector.base = plan::Base::Bridge;
    sc.columns.push_back(connector);
    const auto chains = plan::pillar_chains(sc);
    ASSERT_EQ(chains.size(), 1u);
    EXPECT_EQ(chains[0].pieces.size(), 3u);
    EXPECT_DOUBLE_EQ(chains[0].top, 20);
}

// 0.2 mm layers to 45 mm, no model near, an empty plan.
struct BraceScene : ::testing::Test {
    Settings s;
    const layers::LayerStack st = test::empty_stack(45, 80);
    const plan::Obstacles obs{st, s};
    plan::Scaffold sc;
};

// Three plain 40 mm columns 10 mm apart in a triangle: each alone is
// 40^3 / (3 x 2303.22) = 9.26 mm/N (0.108 N/mm), far under 2.5. Each is
// tied to the other two at 10, 20 and 30 mm (its top less 3 mm reaches
// 37): three bars a level, each from loop to loop (centre lines 0.775 mm
// from the centres), so 10 - 2 x 0.775 = 8.45 mm long, three levels: 9
// bars, no helper column; the other two are braced by the same triangle.
TEST_F(BraceScene, ATriangleOfWeakColumnsIsTiedEveryTenMillimetres) {
    sc.columns.push_back(plain(30, 30, 40));
    sc.columns.push_back(plain(40, 30, 40));
    sc.columns.push_back(plain(35, 30 + 10 * std::sqrt(3.0) / 2, 40));
    EXPECT_NEAR(1 / plan::chain_compliance(plan::pillar_chains(sc)[0], 40, sc, st, s), 0.108, 0.001);
    EXPECT_EQ(plan::add_braces(sc, st, obs, s, {}), 9);
    ASSERT_EQ(sc.bridges.size(), 9u);
    EXPECT_EQ(sc.columns.size(), 3u);
    for (const plan::Bridge& b : sc.bridges) {
        EXPECT_NEAR(std::hypot(b.x1 - b.x0, b.y1 - b.y0), 8.45, 1e-6);
        EXPECT_TRUE(std::abs(b.z - 10) < 1e-6 || std::abs(b.z - 20) < 1e-6 || std::abs(b.z - 30) < 1e-6) << b.z;
    }
    // A forbidden bar (one the bar check failed) is not placed again: the
    // columns are tied in another triangle (with a helper), without it.
    plan::Scaffold again;
    again.columns = sc.columns;
    EXPECT_GE(plan::add_braces(again, st, obs, s, {sc.bridges[0]}), 9);
    for (const plan::Bridge& b : again.bridges)
        EXPECT_FALSE(plan::near_forbidden({sc.bridges[0]}, b, 0.2)) << b.x0 << ", " << b.y0 << " z " << b.z;
}

// A column with no neighbour gets two helper columns up to its top tie,
// 10 or 12 mm away, 60 degrees apart: an equilateral triangle.
TEST_F(BraceScene, ALoneWeakColumnGetsTwoHelpers) {
    sc.columns.push_back(plain(40, 40, 40));
    EXPECT_EQ(plan::add_braces(sc, st, obs, s, {}), 9);
    const auto chains = plan::pillar_chains(sc);
    ASSERT_EQ(chains.size(), 3u);
    for (int k = 1; k < 3; ++k) {
        EXPECT_NEAR(chains[k].top, 30, 1e-6);  // the top tie's height: the bar rests on it
        const plan::Column& h = sc.columns[chains[k].pieces.front()];
        const double d = std::hypot(h.x0 - 40, h.y0 - 40);
        EXPECT_TRUE(std::abs(d - 10) < 1e-6 || std::abs(d - 12) < 1e-6) << d;
    }
}

// A column already stiff enough is left alone: 10 mm stands 6.9 N/mm, and
// the rule off ties nothing.
TEST_F(BraceScene, StiffColumnsAndTheRuleOffTieNothing) {
    sc.columns.push_back(plain(40, 40, 12));
    EXPECT_EQ(plan::add_braces(sc, st, obs, s, {}), 0);
    plan::Scaffold tall;
    tall.columns.push_back(plain(40, 40, 40));
    s.min_stiffness = 0;
    EXPECT_EQ(plan::add_braces(tall, st, obs, s, {}), 0);
}

// A column under a bar end leaves its connectors their give. A 13 mm plain
// ring: (13^3 / 3 - 65 x 0.2^3 / 12) / 2303.22 = 732.29 / 2303.22 =
// 0.31794 mm/N, 3.145 N/mm alone, over the 2.5 aimed at. With 0.2 mm/N of
// connectors on it, 1 / 0.51794 = 1.931 N/mm: under 1.1 x 2 = 2.2, tied at
// 10 mm (one level: three bars, two helpers). With 0.1 mm/N, 2.393: left alone.
TEST_F(BraceScene, AColumnThatLeavesItsConnectorsTooLittleIsBraced) {
    plan::Column c = plain(40, 40, 13);
    sc.columns.push_back(c);
    EXPECT_NEAR(plan::chain_compliance(plan::pillar_chains(sc)[0], 13, sc, st, s), 0.31794, 1e-5);
    sc.columns[0].give = 0.2;
    EXPECT_EQ(plan::add_braces(sc, st, obs, s, {}), 3);
    for (const plan::Bridge& b : sc.bridges) EXPECT_NEAR(b.z, 10, 1e-6);
    plan::Scaffold light;
    c.give = 0.1;
    light.columns.push_back(c);
    EXPECT_EQ(plan::add_braces(light, st, obs, s, {}), 0);
}

// What stands above the top tie starts afresh there. A thin 22 mm column
// (outer radius 0.6 mm: centre line 0.375, I = pi 0.375^3 0.45 = 0.074551
// mm^4, E I = 260.93) tied every 10 mm only at 10 would leave 12 mm above:
// (12^3 / 3 - 60 x 0.2^3 / 12) / 260.93 = 575.96 / 260.93 = 2.2073 mm/N,
// 0.453 N/mm, under 1.1 x 2. So it is tied at 19 mm (its top less 3) too:
// two levels of three bars, the remaining 3 mm some 29 N/mm.
TEST_F(BraceScene, AThinColumnIsTiedNearItsTopWhereThePartAboveWouldBend) {
    plan::Column c = plain(40, 40, 22);
    c.radius = 0.6;
    sc.columns.push_back(c);
    EXPECT_NEAR(plan::chain_compliance(plan::pillar_chains(sc)[0], 22, sc, st, s, 10), 2.2073, 1e-4);
    EXPECT_EQ(plan::add_braces(sc, st, obs, s, {}), 6);
    int at10 = 0, at19 = 0;
    for (const plan::Bridge& b : sc.bridges) {
        at10 += std::abs(b.z - 10) < 1e-6;
        at19 += std::abs(b.z - 19) < 1e-6;
    }
    EXPECT_EQ(at10, 3);
    EXPECT_EQ(at19, 3);
    // A 2 mm column leaves 575.96 / 2303.22 = 0.25007 mm/N above 10 mm
    // (4.0 N/mm): tied at 10 alone (with the 22 mm from the bed far weaker).
    plan::Scaffold wide;
    wide.columns.push_back(plain(40, 40, 22));
    EXPECT_NEAR(plan::chain_compliance(plan::pillar_chains(wide)[0], 22, wide, st, s, 10), 0.25007, 1e-5);
    EXPECT_EQ(plan::add_braces(wide, st, obs, s, {}), 3);
}
