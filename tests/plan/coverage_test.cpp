#include <gtest/gtest.h>

#include <cmath>

#include "layers/layer_stack.hpp"
#include "overhang/overhangs.hpp"
#include "plan/coverage.hpp"
#include "plan/lean_in.hpp"
#include "plan/obstacles.hpp"
#include "plan/pillars.hpp"
#include "support/stacks.hpp"

using namespace scaffold;

namespace {

// 0.2 mm layers to z 6; on layer 20 (z 4.2) a floating sheet 10 x 2 mm (lines
// along x at y 99.2..100.8), nothing under it; a speck far away keeps every
// layer non-empty.
layers::LayerStack floating_sheet() {
    return test::stack_of(
        30,
        [](int i, layers::Layer& l) {
            test::bead(l, 10, 10, 10.5, 10, gcode::Role::Perimeter);
            if (i == 20)
                for (double y = 99.2; y < 100.9; y += 0.4) test::bead(l, 100, y, 110, y);
        },
        {5, 5, 120, 120});
}

// The sheet's overhang (layer 20), the only one.
overhang::Overhangs sheet_overhang(const layers::LayerStack& st, const Settings& s) {
    overhang::Overhangs all = overhang::find_overhangs(st, s);
    EXPECT_EQ(all.layers.size(), 1u);
    EXPECT_EQ(all.layers.at(0).layer, 20);
    return all;
}

plan::Column tip_at(double x, double y) {
    plan::Column c;
    c.x0 = c.x1 = x;
    c.y0 = c.y1 = y;
    c.z0 = 0;
    c.z1 = 4.0;
    c.contact_z = 4.0;
    c.top = plan::Top::Contact;
    return c;
}

}  // namespace

TEST(Coverage, ATipHoldsThePointRadiusOfTheSheetItLiesUnder) {
    Settings s;
    const auto st = floating_sheet();
    const plan::Obstacles obs(st, s);
    const overhang::Overhangs over = sheet_overhang(st, s);
    ASSERT_EQ(over.layers.size(), 1u);
    EXPECT_NEAR(over.area_mm2, 10.4 * 2.05, 1.5);
    // A tip under the sheet's left end: the right end, more than 3.5 mm
    // (the point radius) from it, is left.
    plan::Scaffold one;
    one.columns.push_back(tip_at(101, 100));
    const overhang::Overhangs left = plan::unheld_by_tips(over, one, st, obs, s);
    ASSERT_EQ(left.layers.size(), 1u);
    EXPECT_GT(left.area_mm2, 5.0);
    EXPECT_LT(left.area_mm2, over.area_mm2 - 5.0);
    const layers::BitGrid& g = left.layers[0].cells;
    EXPECT_FALSE(g.get(g.col(101), g.row(100)));
    EXPECT_TRUE(g.get(g.col(109), g.row(100)));
    // The same tip 1.5 mm beside the sheet touches none of it: it holds nothing.
    plan::Scaffold beside;
    beside.columns.push_back(tip_at(101, 98.0 - 0.6));
    EXPECT_NEAR(plan::unheld_by_tips(over, beside, st, obs, s).area_mm2, over.area_mm2, 1e-9);
    // A tip under each end holds it all.
    plan::Scaffold two = one;
    two.columns.push_back(tip_at(108, 100));
    EXPECT_TRUE(plan::unheld_by_tips(over, two, st, obs, s).layers.empty());
}

TEST(Coverage, WhatATipLeavesGetsAPointAndAPillar) {
    Settings s;
    const auto st = floating_sheet();
    const plan::Obstacles obs(st, s);
    const overhang::Overhangs over = sheet_overhang(st, s);
    overhang::SupportPoints points;
    points.points.push_back({101, 100, 4.0, 20});
    plan::Scaffold sc;
    sc.columns.push_back(tip_at(101, 100));
    sc.columns.back().point = 0;
    const std::size_t added = plan::cover_unheld(sc, points, over, st, obs, s, plan::kBranchSteer, 3);
    EXPECT_GE(added, 1u);
    EXPECT_EQ(points.points.size(), 1 + added);
    EXPECT_TRUE(sc.dropped_points.empty());
    for (std::size_t i = 1; i < points.points.size(); ++i) {
        EXPECT_EQ(points.points[i].layer, 20);
        EXPECT_GT(points.points[i].x, 104.5);
    }
    for (const auto& c : sc.columns) EXPECT_LT(c.point, static_cast<int>(points.points.size()));
    EXPECT_TRUE(plan::unheld_by_tips(over, sc, st, obs, s).layers.empty());
    EXPECT_TRUE(sc.uncovered.empty());  // all of the sheet held: nothing to tell the user
}

// A sheet 10 mm long (layer 20, z 4.2) over two walls 1.4 mm apart and 22 mm
// long (layers 0-19, their faces 0.95 mm apart): the strip over the slot between them is out of the
// walls' reach, and no tip fits in the slot (a tip 1 mm across and the
// 0.5 mm gap each side need 2 mm; its contact alone 1.1). A tip beside the walls stands on the bed
// but lies under none of the sheet: METHOD's rule (c) counts it for
// nothing. The points added for what is left get no such pillar: they are
// dropped, and nothing is added (before, every round stood up more
// columns beside the walls that held nothing: 24 points here; 1.6 mm of
// filament on bear.slic3r13 at --min-overhang-area 0).
TEST(Coverage, APointAddedForTheSheetGetsNoTipBesideIt) {
    Settings s;
    const auto st = test::stack_of(
        30,
        [](int i, layers::Layer& l) {
            test::bead(l, 10, 10, 10.5, 10, gcode::Role::Perimeter);
            if (i < 20) {
                test::bead(l, 94, 99.3, 116, 99.3, gcode::Role::Perimeter);
                test::bead(l, 94, 100.7, 116, 100.7, gcode::Role::Perimeter);
            }
            if (i == 20)
                for (double y = 99.2; y < 100.9; y += 0.4) test::bead(l, 100, y, 110, y);
        },
        {5, 5, 120, 120});
    const plan::Obstacles obs(st, s);
    overhang::Overhangs over = overhang::find_overhangs(st, s);
    ASSERT_EQ(over.layers.size(), 1u);
    ASSERT_EQ(over.layers[0].layer, 20);
    EXPECT_GT(over.area_mm2, 0.5);
    // No tip under the sheet, none leaning in, only one beside the walls.
    EXPECT_FALSE(plan::drop_pillar(105, 100, 20, plan::Top::Contact, st, obs, s, nullptr, plan::TipPlaces::UnderSheet));
    EXPECT_FALSE(plan::lean_in(105, 100, 20, st, obs, s));
    const auto beside = plan::drop_pillar(105, 100, 20, plan::Top::Contact, st, obs, s, nullptr, plan::TipPlaces::Beside);
    ASSERT_TRUE(beside);
    plan::Scaffold with_beside;
    with_beside.columns = *beside;
    EXPECT_NEAR(plan::unheld_by_tips(over, with_beside, st, obs, s).area_mm2, over.area_mm2, 1e-9);
    // What tips leave gets points, but no pillar beside.
    overhang::SupportPoints points;
    plan::Scaffold sc;
    const std::size_t added = plan::cover_unheld(sc, points, over, st, obs, s, plan::kBranchSteer, 3);
    EXPECT_EQ(added, 0u);
    EXPECT_TRUE(points.points.empty());
    EXPECT_TRUE(sc.columns.empty());
    // ...and are kept as places on the sheet no tip holds (said to the
    // user): the points the last round put on what is left, each on the
    // sheet (its lines 100..110 at y 99.2..100.8, 0.4 mm wide) and at the
    // sheet's layer's height (layer 20 of 0.2 mm layers: z 4.2), not the
    // point's own (its tip's, under the sheet).
    const overhang::SupportPoints last = overhang::place_points(plan::unheld_by_tips(over, sc, st, obs, s), st, s);
    ASSERT_FALSE(last.points.empty());
    ASSERT_EQ(sc.uncovered.size(), last.points.size());
    for (std::size_t i = 0; i < last.points.size(); ++i) {
        const plan::Xyz& u = sc.uncovered[i];
        EXPECT_EQ(u.x, last.points[i].x);
        EXPECT_EQ(u.y, last.points[i].y);
        EXPECT_NEAR(u.z, 4.2, 1e-9);
        EXPECT_GE(u.x, 99.8);
        EXPECT_LE(u.x, 110.2);
        EXPECT_GE(u.y, 99.0);
        EXPECT_LE(u.y, 101.0);
    }
}
