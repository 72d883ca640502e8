// Braces for METHOD's Standing rule: weak columns tied to two neighbours by
// bars in triangles, with numbers worked out by hand.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <set>
#include <vector>

#include "plan/braces.hpp"
#include "plan/candidates.hpp"
#include "plan/pillars.hpp"
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
// 40^3 / (3 x 2303.22) = 9.26 mm/N (0.108 N/mm), far under 2.5. A plain
// 2 mm ring stands 2.2 N/mm (the rule with the planner's tenth) up to h
// where (h^3 / 3 - 5 h x 0.2^3 / 12) / 2303.22 = 1 / 2.2, h = 14.64 mm:
// each is tied to the other two at 14.6 (the layer below), where it gives
// 0.450383 mm/N (2.2203 N/mm). The node there sums three such: it gives a
// third, 0.150128 mm/N, and what stands on it starts on that give: the
// next tie where 1 / (0.150128 + C(h)) = 2.2, C(h) = 0.304418, h = 12.80,
// at 27.40 (the bisection's 27.399), the layer below: 27.2. Each column's
// island just under it stands 1 / (0.150128 + 0.289486) = 2.2747 N/mm
// (tied 14.6 mm higher, at 29.2, it would stand 1 / (0.150128 + 0.450383)
// = 1.665, under 2); the 12.8 mm above, on that node's give (a third of
// 0.439614), 1 / (0.146538 + 0.303492) = 2.222 N/mm. Three bars a level,
// each from loop to loop (centre lines 0.775 mm from the centres), so 10 -
// 2 x 0.775 = 8.45 mm long: 6 bars, no helper column, fewer than the 9 of
// ties every 10 mm; the other two are braced by the same triangle.
TEST_F(BraceScene, ATriangleOfWeakColumnsIsTiedWhereTheyStopStanding) {
    sc.columns.push_back(plain(30, 30, 40));
    sc.columns.push_back(plain(40, 30, 40));
    sc.columns.push_back(plain(35, 30 + 10 * std::sqrt(3.0) / 2, 40));
    EXPECT_NEAR(1 / plan::chain_compliance(plan::pillar_chains(sc)[0], 40, sc, st, s), 0.108, 0.001);
    EXPECT_EQ(plan::add_braces(sc, st, obs, s, {}), 6);
    ASSERT_EQ(sc.bridges.size(), 6u);
    EXPECT_EQ(sc.columns.size(), 3u);
    for (const plan::Bridge& b : sc.bridges) {
        EXPECT_NEAR(std::hypot(b.x1 - b.x0, b.y1 - b.y0), 8.45, 1e-6);
        EXPECT_TRUE(std::abs(b.z - 14.6) < 1e-6 || std::abs(b.z - 27.2) < 1e-6) << b.z;
    }
    // A forbidden bar (one the bar check failed) is not placed again: the
    // same triangle is tied every 10 mm instead, at 10, 20 and 30 (its top
    // less 3 mm reaches 37): 9 bars.
    plan::Scaffold again;
    again.columns = sc.columns;
    const plan::Forbidden failed{{sc.bridges[0]}, {}};
    EXPECT_EQ(plan::add_braces(again, st, obs, s, failed), 9);
    EXPECT_EQ(again.columns.size(), 3u);
    for (const plan::Bridge& b : again.bridges) {
        EXPECT_FALSE(plan::near_forbidden(failed, b, 0.2)) << b.x0 << ", " << b.y0 << " z " << b.z;
        EXPECT_NEAR(std::hypot(b.x1 - b.x0, b.y1 - b.y0), 8.45, 1e-6);
        EXPECT_TRUE(std::abs(b.z - 10) < 1e-6 || std::abs(b.z - 20) < 1e-6 || std::abs(b.z - 30) < 1e-6) << b.z;
    }
}

// What a bar on a braced column costs includes the braces: add_braces
// names the plan's bars whose end is a braced column's top (the triangle
// above ties all three corners, so a bar from the first to the second is
// named), not a bar whose ends stand on no braced column, nor the braces.
TEST_F(BraceScene, TheBarsOnBracedColumnsAreNamed) {
    sc.columns.push_back(plain(30, 30, 40));
    sc.columns.push_back(plain(40, 30, 40));
    sc.columns.push_back(plain(35, 30 + 10 * std::sqrt(3.0) / 2, 40));
    sc.columns.push_back(plain(70, 70, 8));  // 8 mm: 3 x 2303.22 / 8^3 = 13.5 N/mm, stands alone
    sc.columns.push_back(plain(75, 70, 8));
    plan::Bridge on_braced, elsewhere;
    on_braced.x0 = 30, on_braced.y0 = 30, on_braced.x1 = 40, on_braced.y1 = 30, on_braced.z = 40;
    elsewhere.x0 = 70, elsewhere.y0 = 70, elsewhere.x1 = 75, elsewhere.y1 = 70, elsewhere.z = 8;
    sc.bridges = {elsewhere, on_braced};
    std::vector<std::size_t> braced;
    EXPECT_EQ(plan::add_braces(sc, st, obs, s, {}, nullptr, nullptr, &braced), 6);
    EXPECT_EQ(braced, std::vector<std::size_t>{1});
    for (std::size_t i = 2; i < sc.bridges.size(); ++i) EXPECT_TRUE(sc.bridges[i].brace);
}

// Two triangles sharing a corner, tied at the same height, would print as
// one island of five columns, which METHOD judges from its own centroid
// (Cura's four bunnies: no brace there, 1.36 N/mm above). Five plain 40 mm
// columns: triangle (30, 30), (40, 30), (35, 38.66) and one on the right
// sharing (40, 30); every weak column tied, and at each height the brace
// bars that touch (2 x 0.45 + 0.3 mm between centre lines, or ending at
// one column) are one triangle's three.
TEST_F(BraceScene, TrianglesTiedAtOneHeightDoNotTouch) {
    const double h = 10 * std::sqrt(3.0) / 2;
    for (const auto& [x, y] : std::vector<std::pair<double, double>>{{30, 30}, {40, 30}, {35, 30 + h}, {50, 30}, {45, 30 + h}})
        sc.columns.push_back(plain(x, y, 40));
    EXPECT_GT(plan::add_braces(sc, st, obs, s, {}), 0);
    std::vector<const plan::Bridge*> braces;
    for (const plan::Bridge& b : sc.bridges) braces.push_back(&b);
    auto end_near = [&](const plan::Bridge& a, const plan::Bridge& b) {
        for (const auto& [ax, ay] : {std::pair{a.x0, a.y0}, std::pair{a.x1, a.y1}})
            for (const auto& [bx, by] : {std::pair{b.x0, b.y0}, std::pair{b.x1, b.y1}})
                if (std::hypot(ax - bx, ay - by) < 2 * 0.775 + 0.1) return true;  // both at one column's loop
        return false;
    };
    for (const plan::Bridge* a : braces) {
        int touching = 0;
        for (const plan::Bridge* b : braces)
            if (b != a && std::abs(a->z - b->z) < 1e-6 && end_near(*a, *b)) ++touching;
        EXPECT_LE(touching, 2) << "bar at z " << a->z << " from (" << a->x0 << ", " << a->y0 << ")";
    }
    // Both triangles are tied: the middle column is a corner of each.
    std::set<double> heights;
    for (const plan::Bridge* b : braces) heights.insert(b->z);
    EXPECT_GE(heights.size(), 3u);
}

// A fourth column printed as one with the first (another point's pillar
// down the same way: same base, same loops, 0.2 mm taller) is tied by the
// same triangle: above the top tie, its 11 mm stand 3 x 2303.22 / 11^3 =
// 5.19 N/mm afresh. The same 6 bars, not 6 more lying on them 0.01 mm
// apart (which the bar check found not held as built, on a plate's bunny).
TEST_F(BraceScene, AColumnPrintedAsOneWithACornerIsTiedByItsTriangle) {
    sc.columns.push_back(plain(30, 30, 40));
    sc.columns.push_back(plain(40, 30, 40));
    sc.columns.push_back(plain(35, 30 + 10 * std::sqrt(3.0) / 2, 40));
    plan::Scaffold three = sc;
    ASSERT_EQ(plan::add_braces(three, st, obs, s, {}), 6);
    sc.columns.push_back(plain(30, 30, 40.2));
    EXPECT_EQ(plan::add_braces(sc, st, obs, s, {}), 6);
    ASSERT_EQ(sc.bridges.size(), three.bridges.size());
    for (std::size_t i = 0; i < sc.bridges.size(); ++i) {
        EXPECT_DOUBLE_EQ(sc.bridges[i].x0, three.bridges[i].x0);
        EXPECT_DOUBLE_EQ(sc.bridges[i].y1, three.bridges[i].y1);
        EXPECT_DOUBLE_EQ(sc.bridges[i].z, three.bridges[i].z);
    }
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

// The helpers dropped are kept in the answers a plan made again passes in:
// the same plan again asks for no drop, and gets the same bars and helpers.
// The answers are what it goes by: with each one turned to "no pillar
// there", the same call has to look further round for its helpers.
TEST_F(BraceScene, HelpersDroppedOnceAreTakenFromTheAnswersAfter) {
    sc.columns.push_back(plain(40, 40, 40));
    plan::Scaffold again = sc, believed = sc;
    plan::BraceAnswers answers;
    EXPECT_EQ(plan::add_braces(sc, st, obs, s, {}, nullptr, &answers), 9);
    const std::size_t asked = answers.helpers.size();
    EXPECT_GE(asked, 2u);
    EXPECT_EQ(plan::add_braces(again, st, obs, s, {}, nullptr, &answers), 9);
    EXPECT_EQ(answers.helpers.size(), asked);
    ASSERT_EQ(again.columns.size(), sc.columns.size());
    for (std::size_t i = 0; i < sc.columns.size(); ++i) {
        EXPECT_EQ(again.columns[i].x0, sc.columns[i].x0);
        EXPECT_EQ(again.columns[i].y0, sc.columns[i].y0);
        EXPECT_EQ(again.columns[i].z1, sc.columns[i].z1);
    }
    for (std::size_t i = 0; i < sc.bridges.size(); ++i) EXPECT_EQ(again.bridges[i].x1, sc.bridges[i].x1);
    for (auto& [key, drop] : answers.helpers) drop.reset();
    plan::add_braces(believed, st, obs, s, {}, nullptr, &answers);
    EXPECT_GT(answers.helpers.size(), asked);
}

// A helper stands clear of the plan's other columns: one on a stub where the
// first helper would go (10 mm east of W) would be that stub's column, met
// at the bed, and the triangle no node (METHOD). A 5 mm stub stands 3 x
// 2303.22 / 5^3 = 55 N/mm (no brace of its own) and reaches no tie (no
// partner). Both helpers then keep their loops a bead (0.4 mm) off the
// stub's: centres more than 1 + 1 + 0.4 mm apart.
TEST_F(BraceScene, AHelperKeepsClearOfTheOtherColumns) {
    sc.columns.push_back(plain(40, 40, 40));
    sc.columns.push_back(plain(50, 40, 5));
    EXPECT_EQ(plan::add_braces(sc, st, obs, s, {}), 9);
    const auto chains = plan::pillar_chains(sc);
    ASSERT_EQ(chains.size(), 4u);
    for (int k = 2; k < 4; ++k) {
        const plan::Column& h = sc.columns[chains[k].pieces.front()];
        EXPECT_GT(std::hypot(h.x0 - 50, h.y0 - 40), 2.4) << h.x0 << ", " << h.y0;
        EXPECT_NEAR(chains[k].top, 30, 1e-6);
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

// Each part between two ties stands by itself on the node below it, and
// what stands above the top tie starts afresh there. A thin 22 mm column
// (outer radius 0.6 mm: centre line 0.375, I = pi 0.375^3 0.45 = 0.074551
// mm^4, E I = 260.93) stands 2.2 N/mm up to 7.0 mm: (7^3 / 3 - 35 x 0.2^3 /
// 12) / 260.93 = 0.43809 mm/N, 2.283 N/mm (at 7.2: 2.098). Tied every 10
// mm, its lowest 10 mm would stand 0.78 N/mm. So it is tied at 7.0; the
// node there gives a third of 0.43809, 0.14603 mm/N, and the part above
// stands 2.2 on it up to 13.2 mm: 1 / (0.14603 + (6.2^3 / 3 - 31 x 0.2^3 /
// 12) / 260.93 = 0.30438) = 2.2202 N/mm. On the node at 13.2 (giving
// 0.15014) the 8.8 mm above would stand 0.98 N/mm (above a tie at 10, the
// 12 mm would give (12^3 / 3 - 60 x 0.2^3 / 12) / 260.93 = 2.2073 mm/N), so
// it is tied at 19 mm (its top less 3) too, where its island stands
// 1 / (0.15014 + 0.24918) = 2.504 N/mm: three levels of three bars, the
// remaining 3 mm 1 / (0.13310 + 0.03445) = 5.97 N/mm.
TEST_F(BraceScene, AThinColumnIsTiedWhereItsPartsStandAndNearItsTop) {
    plan::Column c = plain(40, 40, 22);
    c.radius = 0.6;
    sc.columns.push_back(c);
    const auto thin = plan::pillar_chains(sc);
    EXPECT_NEAR(plan::chain_compliance(thin[0], 22, sc, st, s, 10), 2.2073, 1e-4);
    EXPECT_NEAR(plan::chain_compliance(thin[0], 7, sc, st, s), 0.43809, 1e-5);
    EXPECT_NEAR(plan::chain_compliance(thin[0], 13.2, sc, st, s, 7), 0.30438, 1e-5);
    EXPECT_EQ(plan::add_braces(sc, st, obs, s, {}), 9);
    int at7 = 0, at13 = 0, at19 = 0;
    for (const plan::Bridge& b : sc.bridges) {
        at7 += std::abs(b.z - 7) < 1e-6;
        at13 += std::abs(b.z - 13.2) < 1e-6;
        at19 += std::abs(b.z - 19) < 1e-6;
    }
    EXPECT_EQ(at7, 3);
    EXPECT_EQ(at13, 3);
    EXPECT_EQ(at19, 3);
    // A 2 mm column leaves 575.96 / 2303.22 = 0.25007 mm/N above 10 mm
    // (4.0 N/mm): tied at 10 alone (with the 22 mm from the bed far weaker).
    plan::Scaffold wide;
    wide.columns.push_back(plain(40, 40, 22));
    EXPECT_NEAR(plan::chain_compliance(plan::pillar_chains(wide)[0], 22, wide, st, s, 10), 0.25007, 1e-5);
    EXPECT_EQ(plan::add_braces(wide, st, obs, s, {}), 3);
}

// METHOD's brace, walked as the validator walks it. Three plain 2 mm
// columns 40 mm tall, 10 mm apart in a triangle, tied at 20 mm: each
// stands (20^3 / 3 - 100 x 0.2^3 / 12) / 2303.22 = 1.157770 mm/N there,
// 0.863730 N/mm; the node 3 x 0.863730 = 2.591189 N/mm, give 0.385923
// mm/N; the top bends the same 1.157770 above it: 1 / 1.543693 = 0.6478
// N/mm (METHOD: "about 0.7", against 0.108 alone).
TEST_F(BraceScene, ATriangleTiedOnceIsANodeUnlessTwoOfItsColumnsAreOneOrOneIsATwig) {
    sc.columns.push_back(plain(30, 30, 40));
    sc.columns.push_back(plain(40, 30, 40));
    sc.columns.push_back(plain(35, 30 + 10 * std::sqrt(3.0) / 2, 40));
    auto stiffness = [&](const plan::Scaffold& scene, const std::vector<double>& levels = {20.0}) {
        const auto chains = plan::pillar_chains(scene);
        const auto meets = plan::column_meetings(chains, scene, st, s);
        return plan::tied_stiffness({&chains[0], &chains[1], &chains[2]}, {0, 1, 2}, levels, 0.0, meets,
                                    static_cast<int>(chains.size()), scene, st, s);
    };
    EXPECT_NEAR(plan::chain_compliance(plan::pillar_chains(sc)[0], 20, sc, st, s), 1.157770, 1e-6);
    EXPECT_NEAR(stiffness(sc), 0.64779, 1e-4);
    // Two of them carry one bar of the plan at 5 mm: one column from there
    // (METHOD), so the tie makes no node; the top follows the stiffest
    // path down, the column's own: (40^3 / 3 - 200 x 0.2^3 / 12) / 2303.22
    // = 9.26212 mm/N, 0.10797 N/mm.
    plan::Scaffold joined = sc;
    joined.bridges.push_back({40, 30, 35, 30 + 10 * std::sqrt(3.0) / 2, 5.0, {}, 0, 0, false});
    const auto meets = plan::column_meetings(plan::pillar_chains(joined), joined, st, s);
    ASSERT_EQ(meets.size(), 1u);
    EXPECT_EQ(meets[0].a, 1);
    EXPECT_EQ(meets[0].b, 2);
    EXPECT_DOUBLE_EQ(meets[0].z, 5.0);
    EXPECT_FALSE(plan::distinct_columns(meets, 3, {0, 1, 2}, -1e300, 20));
    EXPECT_TRUE(plan::distinct_columns(meets, 3, {0, 1, 2}, 10, 20));  // a node at 10 made them apart
    EXPECT_NEAR(stiffness(joined), 0.10797, 1e-4);
    // A twig: one of them 1.2 mm across (E I = 260.93) stands 0.0978 N/mm
    // at 20, under a quarter (with the planner's tenth: 0.275) of 0.8637.
    plan::Scaffold twig = sc;
    twig.columns[1].radius = 0.6;
    EXPECT_NEAR(stiffness(twig), 0.10797, 1e-4);
    // Tied at 10 and 20 mm: at 10 the twig (0.0978 x 8 = 0.782 N/mm against
    // 8 x 0.8637 = 6.91) makes no node, and the tie joins the three into one
    // island; above it they are columns that meet lower down, one column
    // (METHOD), so the tie at 20 is no node either, whatever their k there:
    // the top still follows the stiffest path down, 0.10797 N/mm.
    EXPECT_NEAR(stiffness(twig, {10.0, 20.0}), 0.10797, 1e-4);
    // Without the twig both ties are nodes, and the top stands far more.
    EXPECT_GT(stiffness(sc, {10.0, 20.0}), 5 * 0.10797);
    // The least of the three at a tie, each on the layer under its bars:
    // tied once at 20, 0.863730 N/mm each. Tied at 14.6 and 29.2 (see the
    // triangle above): 2.2203 at 14.6, then 1 / (0.150128 + 0.450383) =
    // 1.6652 at 29.2, on the node's give; at 14.6 and 27.2, 2.2747 at 27.2,
    // so the least is 14.6's.
    auto weakest = [&](const std::vector<double>& levels) {
        const auto chains = plan::pillar_chains(sc);
        const auto joins = plan::column_meetings(chains, sc, st, s);
        double corner = 0;
        plan::tied_stiffness({&chains[0], &chains[1], &chains[2]}, {0, 1, 2}, levels, 0.0, joins,
                             static_cast<int>(chains.size()), sc, st, s, {}, &corner);
        return corner;
    };
    EXPECT_NEAR(weakest({20.0}), 0.863730, 1e-5);
    EXPECT_NEAR(weakest({14.6, 29.2}), 1.6652, 1e-4);
    EXPECT_NEAR(weakest({14.6, 27.2}), 2.2203, 1e-4);
}

// The same triangle tied at 20 mm, where the first column is tied already
// at 10 mm by a triangle of its own: the validator may walk it down
// through that node, where it stands up to 1 / ((10^3 / 3 - 50 x 0.2^3 /
// 12) / 2303.22) = 1 / 0.144710 = 6.9104 N/mm at 20 (a node that does not
// give), and the others' 0.8637 each are under the planner's share of it
// (0.275 x 6.9104 = 1.900): twigs beside a trunk, no node (METHOD). The top
// then follows the stiffest path down the planner knows, its own: 0.10797
// N/mm, where without that earlier tie it counted on 0.6478. A tie above
// 20 mm is no way down for the tie at 20.
TEST_F(BraceScene, AColumnTiedAlreadyLowerDownMakesTheOthersTwigsAtATieAbove) {
    sc.columns.push_back(plain(30, 30, 40));
    sc.columns.push_back(plain(40, 30, 40));
    sc.columns.push_back(plain(35, 30 + 10 * std::sqrt(3.0) / 2, 40));
    const auto chains = plan::pillar_chains(sc);
    const auto meets = plan::column_meetings(chains, sc, st, s);
    auto stiffness = [&](const std::vector<double>* earlier) {
        return plan::tied_stiffness({&chains[0], &chains[1], &chains[2]}, {0, 1, 2}, {20.0}, 0.0, meets,
                                    static_cast<int>(chains.size()), sc, st, s, {earlier, nullptr, nullptr});
    };
    EXPECT_NEAR(plan::chain_compliance(chains[0], 20, sc, st, s, 10), 0.144710, 1e-6);
    EXPECT_NEAR(stiffness(nullptr), 0.64779, 1e-4);
    const std::vector<double> at_10{10.0}, at_30{30.0};
    EXPECT_NEAR(stiffness(&at_10), 0.10797, 1e-4);
    EXPECT_NEAR(stiffness(&at_30), 0.64779, 1e-4);
}

// A column under a bar end inside a square tube of model (12 mm outside,
// walls at 34 and 46 mm): a helper 10 or 12 mm away stands outside it and
// no bar crosses the wall, so no triangle ties the column. It is dropped
// again as wide as fits at any share of the rule's taper.
namespace {

// A square tube of model, walls at lo and hi on both axes, 45 mm tall.
layers::LayerStack square_tube(double lo, double hi) {
    return test::stack_of(
        225,
        [=](int, layers::Layer& l) {
            test::bead(l, lo, lo, hi, lo, gcode::Role::Perimeter);
            test::bead(l, hi, lo, hi, hi, gcode::Role::Perimeter);
            test::bead(l, hi, hi, lo, hi, gcode::Role::Perimeter);
            test::bead(l, lo, hi, lo, lo, gcode::Role::Perimeter);
        },
        {-5, -5, 80, 80});
}

}  // namespace

struct TubeScene : ::testing::Test {
    Settings s;
    const layers::LayerStack st = square_tube(34, 46);
    const plan::Obstacles obs{st, s};
    plan::Scaffold sc;
};

// The plain 40 mm column stands 0.108 N/mm. Room inside: 6 - 0.225 (the
// wall's half bead) - 0.5 (the gap) = 5.275 mm of radius, more than the
// full taper asks: the least taper whose column gives 1 / 2.5 mm/N at 40
// mm, r(z) = 1 + t (40 - z) on a centre line 0.225 inside it,
// integral of (40 - z)^2 / (3500 pi 0.45 (0.775 + t (40 - z))^3) dz over
// 0..40 = 0.4: t = 0.05527 (found by bisection, by hand in Python), a base
// 3.21 mm in radius. The column that replaces it stands over the rule
// with the planner's tenth (2.2), its neck at the top giving a little of
// the 2.5.
// Loops are rings: one inside another, clear of its inner edge, is no
// meeting (the validator's islands of the two stay apart). A 3 mm loop
// with its second wall (support width 0.45: beads from 3 - 1.9 x 0.45 =
// 2.145 to 3) round a 1 mm one: touching where the small one's outer edge
// comes within a cell (0.1) of 2.145.
TEST_F(BraceScene, ALoopInsideAnotherClearOfItMeetsNothing) {
    auto meetings = [&](double dx) {
        plan::Scaffold scene;
        scene.columns.push_back(plain(30, 30, 10));
        scene.columns.back().radius = 3.0;
        scene.columns.push_back(plain(30 + dx, 30, 10));
        return plan::column_meetings(plan::pillar_chains(scene), scene, st, s).size();
    };
    EXPECT_EQ(meetings(0.0), 0u);   // 0 + 1 + 0.1 < 2.145
    EXPECT_EQ(meetings(1.0), 0u);   // 2.1 < 2.145
    EXPECT_EQ(meetings(1.1), 1u);   // 2.2: the beads touch
    EXPECT_EQ(meetings(4.0), 1u);   // beside it, 4 <= 3 + 1 + 0.1
    EXPECT_EQ(meetings(4.2), 0u);   // apart
}

TEST_F(TubeScene, AWeakColumnNoTriangleTiesIsDroppedAgainAsWideAsFits) {
    sc.columns.push_back(plain(40, 40, 40));
    EXPECT_NEAR(1 / plan::chain_compliance(plan::pillar_chains(sc)[0], 40, sc, st, s), 0.108, 0.001);
    EXPECT_EQ(plan::add_braces(sc, st, obs, s, {}), 0);
    EXPECT_TRUE(sc.bridges.empty());
    const auto chains = plan::pillar_chains(sc);
    ASSERT_EQ(chains.size(), 1u);
    const plan::Column& foot = sc.columns[chains[0].pieces.front()];
    const plan::Column& top = sc.columns[chains[0].pieces.back()];
    EXPECT_NEAR(foot.taper, 0.05527, 2e-4);
    EXPECT_EQ(top.top, plan::Top::Bridge);
    EXPECT_DOUBLE_EQ(top.z1, 40);
    EXPECT_DOUBLE_EQ(top.x1, 40);
    EXPECT_DOUBLE_EQ(top.y1, 40);
    EXPECT_GE(1 / plan::chain_compliance(chains[0], 40, sc, st, s), 2.2);
}

// The bar a weak column holds is reported only where the column still
// falls short once widened. In the tube above it is widened to stand over
// 2.2 N/mm: nothing reported. In a tube 4.4 mm across (walls at 37.8 and
// 42.2) the widest loop keeps 0.225 (the wall's half bead) + 0.5 (gap) +
// 0.05 (half a cell) from the wall, less the up to half a cell by which
// the model's raster falls short of a bead's edge: outer radii of 1.48 to
// 1.50 mm found, centre line 1.265, I = pi 1.265^3 0.45 = 2.862, and 40 mm
// tall 3 E I / 40^3 = 0.4695 N/mm (a little less: the taper, 0.0553 a mm,
// reaches the cap only 8.9 mm below the top, where the 1 mm ring starts):
// widened (0.108 before), still short of 2, and its bar is reported so
// that the plan is made again without it.
TEST_F(TubeScene, OnlyABarOnAColumnStillShortOfTheRuleIsReported) {
    sc.columns.push_back(plain(40, 40, 40));
    sc.bridges.push_back({40, 40, 44, 40, 40, {0}, 0, 0, false});
    std::vector<std::size_t> short_of_rule;
    plan::add_braces(sc, st, obs, s, {}, &short_of_rule);
    EXPECT_TRUE(short_of_rule.empty());

    const layers::LayerStack narrow = square_tube(37.8, 42.2);
    const plan::Obstacles tight(narrow, s);
    plan::Scaffold in_tight;
    in_tight.columns.push_back(plain(40, 40, 40));
    in_tight.bridges.push_back({40, 40, 44, 40, 40, {0}, 0, 0, false});
    plan::add_braces(in_tight, narrow, tight, s, {}, &short_of_rule);
    EXPECT_EQ(short_of_rule, std::vector<std::size_t>{0});
    const auto chains = plan::pillar_chains(in_tight);
    ASSERT_EQ(chains.size(), 1u);
    const double k = 1 / plan::chain_compliance(chains[0], 40, in_tight, narrow, s);
    for (int i : chains[0].pieces) {
        const plan::Column& c = in_tight.columns[static_cast<std::size_t>(i)];
        if (c.z1 <= 30) {
            EXPECT_NEAR(plan::column_radius_at(c, (c.z0 + c.z1) / 2, s), 1.49, 0.03);
        }
    }
    EXPECT_GT(k, 0.108);
    EXPECT_NEAR(k, 0.465, 0.01);
    // Asked without the list, the same plan is made.
    plan::Scaffold unasked;
    unasked.columns.push_back(plain(40, 40, 40));
    unasked.bridges.push_back({40, 40, 44, 40, 40, {0}, 0, 0, false});
    plan::add_braces(unasked, narrow, tight, s, {});
    EXPECT_EQ(unasked.columns.size(), in_tight.columns.size());
}

// The same column with a stiff one beside it, loops touching up to 30 mm:
// one island there (METHOD: columns that meet lower down are one column),
// so the validator walks the weak column's top down its own loop to 30 mm,
// then down the stiffer. A plain ring 3 mm in radius (centre line 2.775,
// I = pi 2.775^3 0.45 = 30.209) with the second wall the toolpaths give it
// (at 3 - 0.9 x 0.45, centre line 2.370, I = 18.820): E I = 3500 x 49.029
// = 171,601, so (40^3 - 10^3) / 3 / 171,601 = 0.12238 mm/N below 30 for
// a load at 40 (the sum by layers differs by under 0.1 %); the 2 mm ring
// above 30 gives 10^3 / 3 / 2303.22 = 0.14473: 3.74 N/mm, over 2.2: the
// column is left as it is.
TEST_F(TubeScene, AColumnThatMetAStifferOneLowerDownIsLeftAsItIs) {
    sc.columns.push_back(plain(40, 40, 40));
    plan::Column wide = plain(43.5, 40, 30);
    wide.radius = 3.0;
    sc.columns.push_back(wide);
    const plan::Scaffold before = sc;
    const auto chains = plan::pillar_chains(sc);
    ASSERT_EQ(chains.size(), 2u);
    EXPECT_NEAR(plan::chain_compliance(chains[1], 40, sc, st, s), 0.12238, 0.0002);
    EXPECT_NEAR(plan::chain_compliance(chains[0], 40, sc, st, s, 30), 0.14473, 0.0002);
    EXPECT_EQ(plan::add_braces(sc, st, obs, s, {}), 0);
    ASSERT_EQ(sc.columns.size(), before.columns.size());
    EXPECT_DOUBLE_EQ(sc.columns[0].taper, 0);
    EXPECT_DOUBLE_EQ(sc.columns[0].radius, 1.0);
    // Without it, the same column is widened (the test above).
    plan::Scaffold alone;
    alone.columns.push_back(plain(40, 40, 40));
    plan::add_braces(alone, st, obs, s, {});
    EXPECT_GT(alone.columns[0].taper, 0);
}

// The same column as a trunk: a branch stands on its loop at 20 mm. A way
// down that stepped elsewhere would leave the branch in the air: the
// column is left as it is (weak: the validator reports it).
TEST_F(TubeScene, AColumnABranchStandsOnIsLeftAsItIs) {
    sc.columns.push_back(plain(40, 40, 40));
    plan::Column branch = plain(40.4, 40, 30);
    branch.z0 = 20;
    branch.base = plan::Base::Column;
    branch.top = plan::Top::Contact;
    sc.columns.push_back(branch);
    ASSERT_EQ(plan::pillar_chains(sc).size(), 1u);  // the branch is no pillar of its own
    EXPECT_EQ(plan::add_braces(sc, st, obs, s, {}), 0);
    ASSERT_EQ(sc.columns.size(), 2u);
    EXPECT_DOUBLE_EQ(sc.columns[0].taper, 0);
    EXPECT_DOUBLE_EQ(sc.columns[0].z1, 40);
}

// Where no triangle ties a column at its levels, its top tie is tried
// lower. A plain 2 mm column 16 mm tall stands 3 x 2303.22 / 16^3 = 1.687
// N/mm (less the midpoint rule's sliver), under 2.2, by itself up to 14.64
// mm: its fewest ties are one at 13 (its top less 3), its ties every 10 mm
// one at 10. A band of model 3 mm around it from 9.8 to 13.8 mm leaves no
// bar out of it at either (the column itself keeps 3 - 0.225 - 1 = 1.78
// mm from the band). Tried 1, 2 and 3 mm lower (12 and 11 are still in the
// band; 9, 8 and 7 under it), the cheapest is two helpers up to 7 mm,
// the 9 mm above standing 3 x 2303.22 / 9^3 = 9.5 N/mm; before, no tie at
// all (and the column dropped again wider, as in the tube below).
TEST(Braces, ATieBlockedAtItsLevelsIsTriedLower) {
    Settings s;
    const layers::LayerStack st = test::stack_of(
        225,
        [](int, layers::Layer& l) {
            test::bead(l, 0, 0, 0.5, 0, gcode::Role::Perimeter);
            if (l.z < 9.8 || l.z > 13.8) return;
            for (int k = 0; k < 24; ++k) {
                const double a = k * std::numbers::pi / 12, b = (k + 1) * std::numbers::pi / 12;
                test::bead(l, 40 + 3 * std::cos(a), 40 + 3 * std::sin(a), 40 + 3 * std::cos(b), 40 + 3 * std::sin(b),
                           gcode::Role::Perimeter);
            }
        },
        {-5, -5, 80, 80});
    const plan::Obstacles obs{st, s};
    plan::Scaffold sc;
    sc.columns.push_back(plain(40, 40, 16));
    EXPECT_NEAR(1 / plan::chain_compliance(plan::pillar_chains(sc)[0], 16, sc, st, s), 1.687, 0.002);
    EXPECT_EQ(plan::add_braces(sc, st, obs, s, {}), 3);
    for (const plan::Bridge& b : sc.bridges) EXPECT_NEAR(b.z, 7, 1e-6);
    const auto chains = plan::pillar_chains(sc);
    ASSERT_EQ(chains.size(), 3u);
    EXPECT_NEAR(chains[1].top, 7, 1e-6);
    EXPECT_NEAR(chains[2].top, 7, 1e-6);
    EXPECT_GT(1 / plan::chain_compliance(chains[0], 16, sc, st, s, 7), 9.4);
}

// A partner is braced by another's triangle only where the ties make its
// own top stand. A 15 mm column A (2.047 N/mm, under the planner's 2.5)
// beside two tips' columns B and C 40 mm tall: A is tied to them where it
// stops standing 2.2 N/mm, its top less 3 mm, 12 mm. The node there holds
// A's top, but B's and C's stand 28 mm above it: each column's k at 12 is
// 1 / ((12^3 / 3 - 60 x 0.2^3 / 12) / 2303.22) = 1 / 0.250075 = 3.9988,
// the node's give 1 / (3 x 3.9988) = 0.083358, and 28 mm of ring above it
// (28^3 / 3 - 140 x 0.2^3 / 12) / 2303.22 = 3.176977: 1 / 3.260335 =
// 0.3067 N/mm. Neither is counted as braced: each is looked at as a weak
// column of its own, tied again only above 12 mm, where a plain helper from
// the bed is a twig beside a column standing on that node; so no triangle
// ties them, and they are named short of the rule with the walk's figure
// (they were counted as braced, and the run said nothing).
TEST_F(BraceScene, APartnerLeftShortByAnothersTriangleIsNotCountedAsBraced) {
    sc.columns.push_back(plain(30, 30, 15));
    plan::Column b = plain(40, 30, 40), c = plain(35, 30 + 10 * std::sqrt(3.0) / 2, 40);
    b.top = c.top = plan::Top::Contact;
    sc.columns.push_back(b);
    sc.columns.push_back(c);
    EXPECT_NEAR(1 / plan::chain_compliance(plan::pillar_chains(sc)[0], 15, sc, st, s), 2.047, 0.001);
    std::vector<plan::ShortColumn> weak;
    EXPECT_EQ(plan::add_braces(sc, st, obs, s, {}, nullptr, nullptr, nullptr, &weak), 3);
    for (const plan::Bridge& br : sc.bridges) EXPECT_NEAR(br.z, 12, 1e-9);
    EXPECT_EQ(sc.columns.size(), 3u);
    ASSERT_EQ(weak.size(), 2u);
    std::set<std::pair<double, double>> at;
    for (const plan::ShortColumn& w : weak) {
        at.insert({w.x, w.y});
        EXPECT_NEAR(w.z, 40, 1e-9);
        EXPECT_NEAR(w.k, 0.3067, 0.0001);
    }
    EXPECT_EQ(at, (std::set<std::pair<double, double>>{{40, 30}, {35, 30 + 10 * std::sqrt(3.0) / 2}}));
}
