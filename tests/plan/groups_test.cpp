#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>
#include <random>
#include <stdexcept>
#include <tuple>

#include "plan/groups.hpp"
#include "plan/planner.hpp"
#include "support/plan_scenes.hpp"

using namespace scaffold;

namespace {

using test::free_space;
using test::Xyz;

// Support points at (x, y, z) on 0.2 mm layers, in place_points' order (layer, y, x).
overhang::SupportPoints points_of(std::vector<Xyz> xyz) {
    std::sort(xyz.begin(), xyz.end(), [](const Xyz& a, const Xyz& b) {
        return std::make_tuple(a[2], a[1], a[0]) < std::make_tuple(b[2], b[1], b[0]);
    });
    return test::points_of(xyz);
}

// `n` random points in a 30 x 30 mm square at each x origin.
std::vector<Xyz> clusters(const std::vector<double>& origins, int n, unsigned seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> xy(0, 30), z(5, 40);
    std::vector<Xyz> out;
    for (double ox : origins)
        for (int i = 0; i < n; ++i) out.push_back({ox + xy(rng), xy(rng), 0.2 * std::round(z(rng) / 0.2)});
    return out;
}

using BridgeKey = std::tuple<double, double, double, double, double, std::vector<int>>;
using ColumnKey = std::tuple<double, double, double, double, double, double, double, int, int>;

// The plan as sorted geometry: the same structures in any order.
std::pair<std::vector<BridgeKey>, std::vector<ColumnKey>> geometry(const plan::Scaffold& sc) {
    std::vector<BridgeKey> b;
    for (const plan::Bridge& x : sc.bridges) b.emplace_back(x.x0, x.y0, x.x1, x.y1, x.z, x.points);
    std::vector<ColumnKey> c;
    for (const plan::Column& x : sc.columns)
        c.emplace_back(x.x0, x.y0, x.z0, x.x1, x.y1, x.z1, x.radius, static_cast<int>(x.base), x.point);
    std::sort(b.begin(), b.end());
    std::sort(c.begin(), c.end());
    return {b, c};
}

// Every group planned alone, on `threads` threads, and merged.
plan::Scaffold plan_in_groups(const overhang::SupportPoints& pts, const Settings& s, int threads) {
    const auto groups = plan::point_groups(pts, {}, plan::group_reach(s));
    std::vector<plan::GroupPlan> plans(groups.size());
    const plan::ModelView m = free_space();
    plan::for_each_group(
        groups.size(), plan::worker_count(groups.size(), threads), [&](std::size_t g) { return groups[g].index.size(); },
        [&](std::size_t g, int) {
            plans[g].points = plan::group_points(pts, groups[g]);
            plans[g].scaffold = plan::plan_scaffold(plans[g].points, m, s, 1);
        });
    overhang::SupportPoints merged;
    plan::Scaffold out = plan::merge_plans(pts, groups, plans, merged);
    EXPECT_EQ(merged.points.size(), pts.points.size());
    return out;
}

}  // namespace

TEST(GroupReach, CoversABarBetweenTwoCarriedPointsAndABrace) {
    Settings s;
    const double reach = plan::group_reach(s);
    EXPECT_GE(reach, std::hypot(s.bridge_max_length, 2 * s.bridge_max_offset));
    EXPECT_GE(reach, 20.0);
    s.bridge_max_length = 60;
    EXPECT_GE(plan::group_reach(s), std::hypot(60.0, 2 * s.bridge_max_offset));
}

TEST(PointGroups, NearPointsJoinFarOnesStayApartChainsJoin) {
    Settings s;
    const double r = plan::group_reach(s);
    // 0 and 1 within reach; 2 within reach of 1 only (a chain); 3 far away.
    overhang::SupportPoints p;
    p.points = {{0, 0, 5, 25}, {r * 0.9, 0, 5, 25}, {r * 1.8, 0, 5, 25}, {r * 5, 0, 5, 25}, {r * 5, r * 0.5, 6, 30}};
    const auto groups = plan::point_groups(p, {}, r);
    ASSERT_EQ(groups.size(), 2u);
    EXPECT_EQ(groups[0].index, (std::vector<int>{0, 1, 2}));
    EXPECT_EQ(groups[1].index, (std::vector<int>{3, 4}));
    // Just beyond reach: apart.
    p.points = {{0, 0, 5, 25}, {r + 0.01, 0, 5, 25}};
    EXPECT_EQ(plan::point_groups(p, {}, r).size(), 2u);
    EXPECT_TRUE(plan::point_groups({}, {}, r).empty());
}

TEST(PointGroups, OverhangRegionsGoToTheGroupOfTheirPoints) {
    Settings s;
    const double r = plan::group_reach(s);
    overhang::SupportPoints p;
    p.points = {{10, 10, 5, 25}, {10 + 3 * r, 10, 5, 25}};
    // Layer 25: a region under each point; layer 40: one under the second
    // point only (on a layer without points: the nearest point's).
    overhang::Overhangs o;
    for (int layer : {25, 40}) {
        overhang::OverhangLayer ol{layer, layers::BitGrid(0, 0, 4 * r + 20, 20, 0.5), 0};
        for (double x0 : {8.0, 8.0 + 3 * r}) {
            if (layer == 40 && x0 < 9) continue;
            for (int i = ol.cells.col(x0); i <= ol.cells.col(x0 + 4); ++i)
                for (int j = ol.cells.row(8); j <= ol.cells.row(12); ++j) ol.cells.set(i, j);
        }
        o.layers.push_back(std::move(ol));
    }
    const auto groups = plan::point_groups(p, o, r);
    ASSERT_EQ(groups.size(), 2u);
    const overhang::Overhangs a = plan::group_overhangs(o, groups[0]), b = plan::group_overhangs(o, groups[1]);
    ASSERT_EQ(a.layers.size(), 1u);
    EXPECT_EQ(a.layers[0].layer, 25);
    EXPECT_TRUE(a.layers[0].cells.get(a.layers[0].cells.col(10), a.layers[0].cells.row(10)));
    EXPECT_FALSE(a.layers[0].cells.get(a.layers[0].cells.col(10 + 3 * r), a.layers[0].cells.row(10)));
    ASSERT_EQ(b.layers.size(), 2u);
    EXPECT_EQ(b.layers[1].layer, 40);
    EXPECT_FALSE(b.layers[0].cells.get(b.layers[0].cells.col(10), b.layers[0].cells.row(10)));
    EXPECT_NEAR(a.area_mm2 + b.area_mm2, 3 * 9 * 9 * 0.25, 1e-9);
}

TEST(PointGroups, PointsOfDifferentObjectsDoNotJoinByDistance) {
    Settings s;
    const double r = plan::group_reach(s);
    overhang::SupportPoints p;
    // 10 mm apart, well within reach: 0 and 1 on object 0, 2 on object 1,
    // 3 on none found (joins either).
    p.points = {{0, 0, 5, 25}, {10, 0, 5, 25}, {20, 0, 5, 25}, {40, 0, 5, 25}};
    const auto apart = plan::point_groups(p, {}, r, {0, 0, 1, 1});
    ASSERT_EQ(apart.size(), 2u);
    EXPECT_EQ(apart[0].index, (std::vector<int>{0, 1}));
    EXPECT_EQ(apart[1].index, (std::vector<int>{2, 3}));
    EXPECT_EQ(plan::point_groups(p, {}, r).size(), 1u);  // no objects given: by distance alone
    EXPECT_EQ(plan::point_groups(p, {}, r, {0, 0, 1, -1}).size(), 1u);
}

TEST(PointGroups, JoinedKeepsPointsAndCellsInOrder) {
    plan::PointGroup a{{0, 3}, {{1, {{1, 1}}}, {4, {{2, 2}}}}};
    plan::PointGroup b{{1, 2, 5}, {{0, {{9, 9}}}, {4, {{3, 3}}}, {7, {{4, 4}}}}};
    const plan::PointGroup j = plan::joined(a, b);
    EXPECT_EQ(j.index, (std::vector<int>{0, 1, 2, 3, 5}));
    ASSERT_EQ(j.cells.size(), 4u);
    EXPECT_EQ(j.cells[0].first, 0);
    EXPECT_EQ(j.cells[1].first, 1);
    EXPECT_EQ(j.cells[2].first, 4);
    ASSERT_EQ(j.cells[2].second.size(), 2u);  // layer 4's cells of both
    EXPECT_EQ(j.cells[3].first, 7);
}

TEST(GroupPlans, SideBySideRenumbersEachPartsPointsToTheJoinedGroups) {
    // Points 0..5 (x = index); group a holds 0, 3, 4, group b 1, 5: joined,
    // 0 1 3 4 5. a's plan added one point (its local 3), b's one (local 2).
    overhang::SupportPoints all;
    for (int i = 0; i < 6; ++i) all.points.push_back({static_cast<double>(i), 0, 1, 5});
    const plan::PointGroup a{{0, 3, 4}, {}}, b{{1, 5}, {}};
    const plan::PointGroup whole = plan::joined(a, b);
    auto plan_of = [&](const plan::PointGroup& g, double added_x) {
        plan::GroupPlan p;
        p.points = plan::group_points(all, g);
        p.points.points.push_back({added_x, 1, 1, 5});
        const int n = static_cast<int>(g.index.size());
        for (int i = 0; i <= n; ++i) {  // a column under each point, the added one's last
            plan::Column c;
            c.x0 = c.x1 = p.points.points[static_cast<std::size_t>(i)].x;
            c.point = i;
            p.scaffold.columns.push_back(c);
        }
        plan::Bridge bar;
        bar.points = {0, n};  // the group's first point and its added one
        p.scaffold.bridges.push_back(bar);
        p.scaffold.dropped_points = {n - 1};
        return p;
    };
    const plan::GroupPlan both = plan::side_by_side(all, whole, {a, b}, {plan_of(a, 10), plan_of(b, 20)});
    // The joined group's points (0 1 3 4 5), then a's added, then b's.
    std::vector<double> xs;
    for (const overhang::SupportPoint& p : both.points.points) xs.push_back(p.x);
    EXPECT_EQ(xs, (std::vector<double>{0, 1, 3, 4, 5, 10, 20}));
    // Every column still stands under the point it holds.
    ASSERT_EQ(both.scaffold.columns.size(), 7u);
    for (const plan::Column& c : both.scaffold.columns)
        EXPECT_EQ(both.points.points[static_cast<std::size_t>(c.point)].x, c.x0);
    ASSERT_EQ(both.scaffold.bridges.size(), 2u);
    EXPECT_EQ(both.scaffold.bridges[0].points, (std::vector<int>{0, 5}));  // a: point 0 and its added (x 10)
    EXPECT_EQ(both.scaffold.bridges[1].points, (std::vector<int>{1, 6}));  // b: point 1 and its added (x 20)
    EXPECT_EQ(both.scaffold.dropped_points, (std::vector<int>{3, 4}));      // a's 4 (position 3), b's 5 (position 4)
    // A part's point the whole does not hold is a caller's error.
    EXPECT_THROW(plan::side_by_side(all, a, {a, b}, {plan_of(a, 10), plan_of(b, 20)}), std::logic_error);
}

TEST(PlansApart, TwoBeadsBeyondEachEdge) {
    Settings s;  // support width 0.45, pillar radius 1
    auto column = [](double x, double y, double z0, double z1) {
        plan::Scaffold sc;
        plan::Column c;
        c.x0 = c.x1 = x;
        c.y0 = c.y1 = y;
        c.z0 = z0;
        c.z1 = z1;
        c.radius = 1.0;
        sc.columns.push_back(c);
        return sc;
    };
    // Each loop reaches 1 + 0.45 = 1.45 mm: apart from 1.45 + 1.45 + 2 = 4.9 mm.
    const plan::Scaffold a = column(0, 0, 0, 10);
    EXPECT_TRUE(plan::plans_apart(a, column(5.0, 0, 0, 10), s));
    EXPECT_FALSE(plan::plans_apart(a, column(4.8, 0, 0, 10), s));
    EXPECT_FALSE(plan::plans_apart(column(4.8, 0, 0, 10), a, s));
    // 1 mm apart but one stands 2 mm above the other's top: apart.
    EXPECT_TRUE(plan::plans_apart(a, column(1.0, 0, 12, 20), s));
    EXPECT_TRUE(plan::plans_apart(a, column(1.0, 0, 10.4, 20), s));  // one above the other
    plan::Scaffold above;
    above.bridges.push_back({1, 0, 11, 0, 10.2, {}, 0, 0, false});
    EXPECT_FALSE(plan::plans_apart(a, above, s));  // a bar within half a mm of its top rests on it
    above.bridges[0].z = 10.6;
    EXPECT_TRUE(plan::plans_apart(a, above, s));
    // A flared foot (radius 2.5, 2.5 mm high): other loops there may meet
    // it (loops near the bed that meet only stiffen each other), a bar keeps
    // clear of it by 2.95 + 1.45 + 2 = 6.4 mm.
    plan::Scaffold footed = column(0, 0, 0, 10);
    footed.columns[0].foot_radius = 2.5;
    EXPECT_TRUE(plan::plans_apart(footed, column(5.0, 0, 0, 10), s));  // the feet 5 < 6.4 apart, the loops 5 >= 4.9
    EXPECT_FALSE(plan::plans_apart(footed, column(4.8, 0, 2.6, 10), s));  // above the feet, 4.8 < 4.9
    plan::Scaffold low_bar;
    low_bar.bridges.push_back({-5, 6.3, 5, 6.3, 1.0, {}, 0, 0, false});
    EXPECT_FALSE(plan::plans_apart(footed, low_bar, s));
    low_bar.bridges[0].y0 = low_bar.bridges[0].y1 = 6.5;
    EXPECT_TRUE(plan::plans_apart(footed, low_bar, s));
    // A bar at z 5 from (0, 0) to (10, 0): its lines reach 0.45 + 1 (into
    // the columns past its ends) = 1.45 mm; a column beside its middle.
    plan::Scaffold bar;
    bar.bridges.push_back({0, 0, 10, 0, 5.0, {}, 0, 0, false});
    EXPECT_FALSE(plan::plans_apart(bar, column(5, 4.8, 0, 6), s));
    EXPECT_TRUE(plan::plans_apart(bar, column(5, 5.0, 0, 6), s));
    EXPECT_TRUE(plan::plans_apart(bar, column(5, 1.0, 6, 9), s));  // starts 0.6 mm above the bar's top
    // A slanted column whose line crosses the bar's: touching.
    plan::Scaffold slant = column(5, -8, 0, 6);
    slant.columns[0].y1 = 8;
    EXPECT_FALSE(plan::plans_apart(bar, slant, s));
    EXPECT_TRUE(plan::plans_apart({}, bar, s));
    // Tapered (0.3 mm per mm below z 10): radius 4 at the bed, 1.6 at z 8.
    // Judged in 2 mm slices, the top one (z 8 to 10) reaches 1.6 + 0.45 =
    // 2.05: a bar at z 9 keeps clear from 2.05 + 1.45 + 2 = 5.5 mm, though
    // the foot reaches 4.45.
    plan::Scaffold tapered = column(0, 0, 0, 10);
    tapered.columns[0].taper = 0.3;
    tapered.columns[0].hold_z = 10;
    plan::Scaffold high;
    high.bridges.push_back({-5, 5.6, 5, 5.6, 9.0, {}, 0, 0, false});
    EXPECT_TRUE(plan::plans_apart(tapered, high, s));
    high.bridges[0].y0 = high.bridges[0].y1 = 5.4;
    EXPECT_FALSE(plan::plans_apart(tapered, high, s));
    high.bridges[0].z = 1.0;
    high.bridges[0].y0 = high.bridges[0].y1 = 7.8;  // beside the foot: 4.45 + 1.45 + 2 = 7.9
    EXPECT_FALSE(plan::plans_apart(tapered, high, s));
    // Rafts (7 mm squares, reaching 4.95 to their corners) on the bed may
    // meet each other, not a bar.
    plan::Scaffold r1 = column(0, 0, 0, 10), r2 = column(6.5, 0, 0, 10);
    r1.columns[0].raft_size = r2.columns[0].raft_size = 7;
    EXPECT_TRUE(plan::plans_apart(r1, r2, s));
    plan::Scaffold bed_bar;
    bed_bar.bridges.push_back({-5, 8.3, 5, 8.3, 0.0, {}, 0, 0, false});  // 4.95 + 1.45 + 2 = 8.4
    EXPECT_FALSE(plan::plans_apart(r1, bed_bar, s));
}

TEST(ForEachGroup, RunsEveryGroupOnceAndPassesTheFirstErrorOn) {
    for (int workers : {1, 2, 3}) {
        std::vector<std::atomic<int>> ran(7);
        plan::for_each_group(7, workers, [](std::size_t g) { return g % 3; }, [&](std::size_t g, int w) {
            EXPECT_LT(w, workers);
            ++ran[g];
        });
        for (auto& r : ran) EXPECT_EQ(r.load(), 1);
        EXPECT_THROW(plan::for_each_group(
                         5, workers, [](std::size_t) { return 1; },
                         [](std::size_t g, int) {
                             if (g == 1 || g == 3) throw std::runtime_error(std::to_string(g));
                         }),
                     std::runtime_error);
        try {
            plan::for_each_group(5, workers, [](std::size_t) { return 1; }, [](std::size_t g, int) {
                if (g == 1 || g == 3) throw std::runtime_error(std::to_string(g));
            });
        } catch (const std::runtime_error& e) {
            EXPECT_STREQ(e.what(), "1");
        }
    }
}

TEST(GroupPlans, SamePlanOnAnyThreadCountAndAsTheWholePlate) {
    Settings s;
    // Three clusters farther apart than the reach, plus one point between
    // the last two that joins them.
    const double r = plan::group_reach(s);
    std::vector<Xyz> xyz = clusters({0, 30 + 1.5 * r, 60 + 3 * r, 90 + 4.2 * r}, 40, 7);
    const overhang::SupportPoints pts = points_of(xyz);
    const auto groups = plan::point_groups(pts, {}, r);
    ASSERT_EQ(groups.size(), 4u);
    const plan::Scaffold one = plan_in_groups(pts, s, 1);
    EXPECT_GT(one.bridges.size(), 8u);
    for (int threads : {2, 3}) test::expect_same(one, plan_in_groups(pts, s, threads));
    // The groups planned apart build what the whole plate's plan builds.
    EXPECT_EQ(geometry(one), geometry(plan::plan_scaffold(pts, free_space(), s, 1)));
}
