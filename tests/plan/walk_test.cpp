// METHOD's walk down a plan's pillars (plan/walk), with numbers worked out
// by hand. All on 0.2 mm layers, beads 0.45 mm wide, E = 3500 N/mm^2; a
// single-wall ring of outer radius r has I = pi rc^3 w, rc = r - 0.225:
//   r = 1.4: E I = 3500 pi 1.175^3 0.45 = 8026.83 N mm^2
//   r = 1.0: E I = 3500 pi 0.775^3 0.45 = 2303.22
//   r = 0.5: E I = 3500 pi 0.275^3 0.45 = 102.903
// A ring from a to b at lever t, summed at the layers' middles: (1/EI) x
// sum (t - z_mid)^2 0.2, which is the integral less 0.2^3 / 12 a layer.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "plan/braces.hpp"
#include "plan/obstacles.hpp"
#include "plan/walk.hpp"
#include "support/stacks.hpp"

using namespace scaffold;

namespace {

plan::Column ring(double x, double y, double z0, double z1, double r, plan::Base base = plan::Base::Bed) {
    plan::Column c;
    c.x0 = c.x1 = x;
    c.y0 = c.y1 = y;
    c.z0 = z0;
    c.z1 = c.hold_z = z1;
    c.radius = r;
    c.base = base;
    c.top = plan::Top::Bridge;
    return c;
}

struct WalkScene : ::testing::Test {
    Settings s;
    const layers::LayerStack st = test::empty_stack(45, 80);
    plan::Scaffold sc;
    // A: a 1.4 mm ring 20 mm tall from the bed. B: a 0.5 mm stub one layer
    // tall (4.8 to 5) on the model beside it. A bar at 5 from B's top to A.
    void tall_and_stub() {
        sc.columns.push_back(ring(30, 30, 0, 20, 1.4));
        sc.columns.push_back(ring(36, 30, 4.8, 5, 0.5, plan::Base::Model));
        sc.bridges.push_back({36, 30, 31.4, 30, 5, {}, 0, 0, false});
    }
    // Three rings 40 mm tall from the bed, 10 mm apart (METHOD's worked
    // brace), of these radii, tied at 20 mm.
    const std::vector<plan::BraceNode> tie_at_20{{20, {0, 1, 2}}};
    void triangle(double r0, double r1, double r2) {
        sc.columns.push_back(ring(30, 30, 0, 40, r0));
        sc.columns.push_back(ring(40, 30, 0, 40, r1));
        sc.columns.push_back(ring(35, 38.66, 0, 40, r2));
    }
};

}  // namespace

// Where the bar ties them (the island on the bar's first layer stands on
// both), the walk takes the stiffer *there*:
//   A at lever 5: (5^3/3 - 25 x 0.000667) / 8026.83 = 41.65 / 8026.83
//     = 0.0051888 mm/N, 192.7 N/mm;
//   B at lever 5: (0.2^3/3 - 0.000667) / 102.903 = 0.0020 / 102.903
//     = 1.9436e-5 mm/N, 51,452 N/mm: the walk leaves A for B.
// At A's top (20) that path is B's layer under a 15 mm lever and A's own
// part above the bar:
//   (15.2^3 - 15^3)/3 - 0.000667 = 45.6020 over 102.903 = 0.443162
//   (15^3/3 - 75 x 0.000667) = 1124.95 over 8026.83 = 0.140148
//   0.583303 mm/N: 1.714 N/mm, where A from the bed stands
//   (20^3/3 - 100 x 0.000667) / 8026.83 = 0.332211 mm/N, 3.010 N/mm.
TEST_F(WalkScene, TheWalkTakesTheStifferWhereTheyMeetNotAtTheTop) {
    tall_and_stub();
    const auto chains = plan::pillar_chains(sc);
    ASSERT_EQ(chains.size(), 2u);
    plan::PlanWalk walk(chains, {}, sc, st, s);
    EXPECT_NEAR(walk.path(0, 20).at(20), 0.583303, 1e-5);
    // On the bar's first layer (5.2): B's layer at lever 5.2, 0.3^2 x 0.2 /
    // 102.903 = 1.74922e-4, and A's layer at 5.2, 0.1^2 x 0.2 / 8026.83.
    EXPECT_NEAR(walk.path(0, 5.2).at(5.2), 1.74922e-4 + 2.4917e-7, 1e-9);
    const auto left = walk.departures(0, 20);
    ASSERT_EQ(left.size(), 1u);
    EXPECT_EQ(left[0].b, 1);
    EXPECT_EQ(left[0].bar, 0);
    EXPECT_NEAR(left[0].z, 5, 1e-9);
    // Below the bar the walk is A's own: nothing met there.
    EXPECT_NEAR(walk.path(0, 4).at(4), (64.0 / 3 - 20 * 0.2 * 0.2 * 0.2 / 12) / 8026.83, 1e-6);
    // Without the bar, A from the bed.
    sc.bridges.clear();
    plan::PlanWalk alone(chains, {}, sc, st, s);
    EXPECT_NEAR(alone.path(0, 20).at(20), 0.332211, 1e-5);
    EXPECT_TRUE(alone.departures(0, 20).empty());
}

// A stiffer column from the bed ties in the other way: B a 1 mm ring from
// the bed to 5 is 2303.22 / 41.65 = 55.3 N/mm at 5, under A's 192.7: the
// walk stays on A, whose top is as from the bed.
TEST_F(WalkScene, AWeakerColumnMetDoesNotTakeTheWalk) {
    sc.columns.push_back(ring(30, 30, 0, 20, 1.4));
    sc.columns.push_back(ring(36, 30, 0, 5, 1.0));
    sc.bridges.push_back({36, 30, 31.4, 30, 5, {}, 0, 0, false});
    plan::PlanWalk walk(plan::pillar_chains(sc), {}, sc, st, s);
    EXPECT_NEAR(walk.path(0, 20).at(20), 0.332211, 1e-5);
    EXPECT_TRUE(walk.departures(0, 20).empty());
}

// METHOD's worked brace: three 1 mm rings 40 mm tall tied in a triangle at
// 20 mm. Each at 20: (20^3/3 - 100 x 0.000667) / 2303.22 = 1.157770 mm/N,
// 0.86373 N/mm. The node's give is 1 / (3 x 0.86373) = 0.385923; above it
// each part is a 20 mm ring again, 1.157770: 1.543693 mm/N at the top,
// 0.648 N/mm (about 0.7, METHOD), against 40^3/3 / 2303.22 = 9.26 alone.
TEST_F(WalkScene, ABraceNodeStartsTheWalkAfresh) {
    triangle(1.0, 1.0, 1.0);
    const std::vector<plan::BraceNode>& nodes = tie_at_20;
    plan::PlanWalk walk(plan::pillar_chains(sc), nodes, sc, st, s);
    EXPECT_NEAR(walk.path(0, 40).at(40), 1.543693, 1e-5);
    EXPECT_NEAR(1 / walk.path(2, 40).at(40), 0.6478, 1e-4);
    EXPECT_TRUE(walk.departures(0, 40).empty());
    // A twig among them (a quarter of the strongest's k or less) makes no node.
    plan::Scaffold twig = sc;
    twig.columns[2].radius = 0.5;  // 102.903 / 2666.6 = 0.0386 N/mm at 20, under 0.216
    plan::PlanWalk walked(plan::pillar_chains(twig), nodes, twig, st, s);
    EXPECT_GT(walked.path(0, 40).at(40), 9.0);  // the stiffest, a plain 40 mm ring: 9.26
}

// A pillar hung on a bar (a connector, base Bridge) goes on down through
// what the bar is on: C (1 mm, 5.4 to 12) stands on the bar of
// tall_and_stub, which rests on A and on B's top; the walk from C takes the
// stiffer at the bar, B: at C's top (12), B's layer under a 7 mm lever,
// ((7.2^3 - 7^3)/3 - 0.000667) / 102.903 = 10.0820 / 102.903 = 0.097976,
// C's own 6.6 mm ((6.6^3/3 - 33 x 0.000667) / 2303.22 = 0.041602), and
// between them the bar's two layers (5.2 and 5.4), where C has no loop of
// its own: two 0.45 mm lines side by side, 4.6 mm long and 1 mm more for
// their reach into the pillars, bent about the bar's axis, I = 5.6 x
// 0.9^3 / 12 = 0.3402, E I = 1190.7, at levers 6.9 and 6.7 (the layers'
// middles): 0.2 x (6.9^2 + 6.7^2) / 1190.7 = 0.015537. In all 0.155115
// mm/N (0.139578 without the bar's layers, which the validator counts).
TEST_F(WalkScene, AConnectorOnABarWalksDownWhatTheBarIsOn) {
    tall_and_stub();
    sc.columns.push_back(ring(33, 30, 5.4, 12, 1.0, plan::Base::Bridge));
    const auto chains = plan::pillar_chains(sc);
    ASSERT_EQ(chains.size(), 2u);  // C is no pillar of pillar_chains: the walk adds it, as pillar 2
    plan::PlanWalk walk(chains, {}, sc, st, s);
    EXPECT_NEAR(walk.path(2, 12).at(12), 0.155115, 1e-5);
}

// add_braces reports the bar a column stands short of the rule by, where
// it stands from its own base: A (3.01 N/mm alone) walked by B, 1.71.
TEST_F(WalkScene, ABarThatTakesAStandingColumnsWalkShortOfTheRuleIsReported) {
    tall_and_stub();
    const plan::Obstacles obs{st, s};
    std::vector<std::size_t> short_of_rule;
    plan::add_braces(sc, st, obs, s, {}, &short_of_rule);
    ASSERT_EQ(short_of_rule.size(), 1u);
    EXPECT_EQ(short_of_rule[0], 0u);
    // At --min-stiffness 1.5 the walk's 1.71 stands: nothing reported.
    s.min_stiffness = 1.5;
    plan::Scaffold again;
    again.columns = {sc.columns[0], sc.columns[1]};
    again.bridges = {sc.bridges[0]};
    short_of_rule.clear();
    plan::add_braces(again, st, obs, s, {}, &short_of_rule);
    EXPECT_TRUE(short_of_rule.empty());
}

// A pillar whose loops touch a corner's on the node's first layer is on the
// node's island there (METHOD: what stands on the node starts afresh): D, a
// 1 mm ring from the bed to 30 beside corner 0 of ABraceNodeStartsTheWalkAfresh
// (centres 1.9 mm apart: loops within a cell). Their loops touch on every
// layer, so each layer's island is both, its section both rings' (the test
// below): corner 0 stands 1 / (1.157770 / 2) = 1.727460 N/mm at 20, the
// node 1.727460 + 2 x 0.863730 = 3.454920, giving 0.289443 mm/N; above it
// D's 10 mm, both rings again, (10^3/3 - 50 x 0.000667) / 2303.22 / 2 =
// 0.072355: 0.361798 mm/N at 30. Walked from its base, apart,
// (30^3/3 - 150 x 0.000667) / 2303.22 = 8999.9 / 2303.22 = 3.907529 mm/N.
TEST_F(WalkScene, APillarTouchingACornerOnTheTieStandsOnTheNode) {
    triangle(1.0, 1.0, 1.0);
    sc.columns.push_back(ring(30, 28.1, 0, 30, 1.0));
    const auto chains = plan::pillar_chains(sc);
    ASSERT_EQ(chains.size(), 4u);
    ASSERT_TRUE(plan::rings_touch(chains[0], chains[3], sc, s, 20.2));
    plan::PlanWalk walk(chains, tie_at_20, sc, st, s);
    EXPECT_NEAR(walk.path(3, 30).at(30), 0.361798, 1e-5);
    EXPECT_NEAR(walk.node_below(3, 30), 20, 1e-9);
    // Just over the node, as it reaches the node's layer from below: from
    // the bed, both rings, (20.4^3/3 - 102 x 0.000667) / 2303.22 / 2 =
    // 1.228636 / 2 = 0.614318.
    EXPECT_NEAR(walk.path_from_below(3, 20, 20.4).at(20.4), 0.614318, 1e-5);
    // Moved 3 mm off corner 0 it touches nothing: its own way down.
    sc.columns[3].y0 = sc.columns[3].y1 = 27;
    plan::PlanWalk apart(plan::pillar_chains(sc), tie_at_20, sc, st, s);
    EXPECT_NEAR(apart.path(3, 30).at(30), 3.907529, 1e-5);
    EXPECT_EQ(apart.node_below(3, 30), -std::numeric_limits<double>::infinity());
}

// A twig at a node (under a quarter of the strongest's k) makes no node:
// the walk goes on down the stiffest of the three there, and says so.
// Corner 1 a 1.4 mm ring: (20^3/3 - 100 x 0.000667) / 8026.83 = 0.332211
// mm/N, 3.010 N/mm at 20; corner 0 (1 mm) 0.8637, the 0.5 mm twig 0.0386,
// under 0.25 x 3.010. From corner 0's top (40) the walk leaves for corner 1
// at 20, by no bar; that is where its way down changes, as at a node.
TEST_F(WalkScene, ATwigsNodeIsADepartureToTheStiffest) {
    triangle(1.0, 1.4, 0.5);
    plan::PlanWalk walk(plan::pillar_chains(sc), tie_at_20, sc, st, s);
    const auto left = walk.departures(0, 40);
    ASSERT_EQ(left.size(), 1u);
    EXPECT_EQ(left[0].b, 1);
    EXPECT_EQ(left[0].bar, -1);
    EXPECT_NEAR(left[0].z, 20, 1e-9);
    EXPECT_NEAR(walk.node_below(0, 40), 20, 1e-9);
    // At 40: corner 1's layers under a 20..40 mm lever plus corner 0's own
    // 20 mm, ((40^3 - 20^3)/3 - 100 x 0.000667) / 8026.83 = 2.325531 and
    // 1.157770: 3.483301 mm/N.
    EXPECT_NEAR(walk.path(0, 40).at(40), 3.483301, 1e-5);
}

// Where two pillars' loops touch, the validator's island on those layers is
// both loops, and its section at least the sum of theirs (two rings side by
// side, bent about the line through their centres). A, a 2 mm ring from
// the bed to 20, and B, another 1.9 mm beside it to 10: from the bed to 10
// the walk counts E I = 2 x 2303.22, above it A's own: (20^3 - 10^3) / 3 -
// 50 x 0.2^3 / 12 = 2333.30 over 4606.44, and 10^3 / 3 - 50 x 0.2^3 / 12 =
// 333.30 over 2303.22: 0.506530 + 0.144710 = 0.651240 mm/N, 1.5355 N/mm at
// A's top, where A alone (as the walk had it, and the planner warned of
// the shuttle's columns so at 1.24 N/mm where the validator found 2.13)
// stands 0.8637 (METHOD's 20 mm ring).
TEST_F(WalkScene, LoopsTouchingAreOneSectionWhereTheyTouch) {
    sc.columns.push_back(ring(30, 30, 0, 20, 1.0));
    sc.columns.push_back(ring(31.9, 30, 0, 10, 1.0));
    const auto chains = plan::pillar_chains(sc);
    ASSERT_EQ(chains.size(), 2u);
    const auto meets = plan::column_meetings(chains, sc, st, s);
    ASSERT_EQ(meets.size(), 1u);
    EXPECT_NEAR(meets[0].z, 0.2, 1e-9);
    EXPECT_NEAR(meets[0].until, 10.0, 1e-9);
    plan::PlanWalk walk(chains, {}, sc, st, s);
    EXPECT_NEAR(walk.path(0, 20).at(20), 0.651240, 1e-5);
}
