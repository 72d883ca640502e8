#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <numbers>
#include <random>
#include <set>
#include <tuple>

#include "layers/layer_stack.hpp"
#include "plan/obstacles.hpp"
#include "plan/pillars.hpp"
#include "plan/planner.hpp"
#include "support/plan_scenes.hpp"
#include "support/stacks.hpp"

using namespace scaffold;

namespace {

using test::expect_same;
using test::free_space;
using test::points_of;
using test::Xyz;

// A wall |x - 20| <= 1 from the bed to z = 30 across all y.
constexpr double kHalf = 1.0, kTop = 30.0;
plan::ModelView wall_at_20() {
    plan::ModelView m = free_space();
    m.segment_clear = [](double z, double x0, double, double x1, double, double r) {
        return z > kTop || std::max(x0, x1) + r < 20 - kHalf || std::min(x0, x1) - r > 20 + kHalf;
    };
    m.disc_clear = [](double z, double x, double, double r) { return z > kTop || std::abs(x - 20) > kHalf + r; };
    m.model_top_below = [](double z, double x, double, double r) {
        return std::abs(x - 20) <= kHalf + r ? std::min(z, kTop) : 0.0;
    };
    return m;
}

bool crosses_x(const plan::Bridge& b, double x) { return (b.x0 - x) * (b.x1 - x) <= 0; }

// n points uniform over [0, xy_max]^2 at heights in [z_lo, z_hi] snapped to
// 0.2 mm layers, drawn x, y, z in turn from a generator seeded `seed`.
std::vector<Xyz> random_points(unsigned seed, int n, double xy_max, double z_lo, double z_hi) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> xy(0, xy_max), z(z_lo, z_hi);
    std::vector<Xyz> out;
    for (int i = 0; i < n; ++i) {
        const double x = xy(rng), y = xy(rng);
        out.push_back({x, y, 0.2 * std::round(z(rng) / 0.2)});
    }
    return out;
}

// Which structure holds each point: count of Contact tops naming it.
std::vector<int> holders(const plan::Scaffold& sc, std::size_t n) {
    std::vector<int> held(n, 0);
    for (const auto& c : sc.columns)
        if (c.top == plan::Top::Contact) {
            EXPECT_GE(c.point, 0);
            if (c.point >= 0) held[c.point]++;
        }
    return held;
}

using test::empty_stack;

const std::vector<Xyz> kReportPoints{{18, 24, 17}, {11, 15, 20}, {19, 9, 15}, {25, 20, 18}};

}  // namespace

TEST(PlannerScore, GainAndScoreByHand) {
    // gain = (k - 2) * z - length: 4 points on a 10 mm bridge at z = 12.
    EXPECT_DOUBLE_EQ(plan::bridge_gain(4, 12, 10), 14);   // 2 * 12 - 10
    // score = gain - k * l_max: l_max 6 gives 14 - 4 * 6 = -10 (scores may be negative).
    EXPECT_DOUBLE_EQ(plan::bridge_score(14, 4, 6), -10);
    EXPECT_DOUBLE_EQ(plan::bridge_gain(3, 15, 14), 1);    // the report's bridge: 1 * 15 - 14
    EXPECT_DOUBLE_EQ(plan::bridge_score(1, 3, 10), -29);  // 1 - 3 * 10
    // Two points never pay: (2 - 2) * z - length < 0.
    EXPECT_LT(plan::bridge_gain(2, 50, 5), 0);
    // Lean per layer: 0.5 * pillar radius at 0.2 mm (the reach there,
    // 0.2 * tan 55 + 0.225 = 0.511, is larger); the reach on 0.1 mm layers.
    Settings s;
    EXPECT_DOUBLE_EQ(plan::max_lean_per_layer(0.2, s), 0.5);
    EXPECT_NEAR(plan::max_lean_per_layer(0.1, s), 0.1 * std::tan(55 * M_PI / 180) + 0.225, 1e-12);
}

TEST(PlannerReport, FourPointExampleGivesTheReportsBridge) {
    // Tupek's appendix: points (18,24,17), (11,15,20), (19,9,15), (25,20,18);
    // the report's output is one bridge (11,20)-(25,20) at z 15 carrying all
    // but (19,9,15). Here the bar is one layer lower, z 14.8: a connector's
    // first loop stands centred on the bar (a 0.75 mm loop leaning 0.5 mm off
    // a 0.9 mm wide bar at once would overhang its side, METHOD's rule (a)),
    // so the lean starts one layer up. By hand, sweep line y = 20 (direction
    // 0, through (25,20)):
    //   ends (11,20) and (25,20): length 14, within 5..30;
    //   (25,20,18): 0 mm aside, 18 >= 14.8 + 2;  l = 0 + 3.2 = 3.2
    //   (18,24,17): 4 mm aside, 17 >= 16.8; the connector rises 17 - 15.2 =
    //               1.8 mm = 9 layers, one straight, then leans 4 / 8 = 0.5 mm
    //               a layer (the limit); l = 4 + 2.2 = 6.2
    //   (11,15,20): 5 mm aside, 20 >= 16.8;     l = 5 + 5.2 = 10.2
    //   (19,9,15):  11 mm aside: not carried.
    //   gain = (3 - 2) * 14.8 - 14 = 0.8; l_max = 10.2; score = 0.8 - 3 * 10.2 = -29.8.
    // Higher bars carry fewer points: at z 15 (18,24,17) would lean 4 mm over
    // 7 layers and drops out, and (2 - 2) * 15 - 14 < 0.
    Settings s;
    auto sc = plan::plan_scaffold(points_of(kReportPoints), free_space(), s);
    ASSERT_EQ(sc.bridges.size(), 1u);
    const auto& b = sc.bridges[0];
    EXPECT_NEAR(b.x0, 11, 1e-9);
    EXPECT_NEAR(b.y0, 20, 1e-9);
    EXPECT_NEAR(b.x1, 25, 1e-9);
    EXPECT_NEAR(b.y1, 20, 1e-9);
    EXPECT_NEAR(b.z, 14.8, 1e-9);
    EXPECT_NEAR(std::hypot(b.x1 - b.x0, b.y1 - b.y0), 14, 1e-9);
    EXPECT_NEAR(b.gain, 0.8, 1e-9);
    EXPECT_NEAR(b.score, -29.8, 1e-9);
    std::vector<int> carried = b.points;
    std::sort(carried.begin(), carried.end());
    EXPECT_EQ(carried, (std::vector<int>{0, 1, 3}));
    // Connectors from the bar top (15.2) to each carried point, from the
    // nearest point of the bar; pillars under (19,9) and under both ends.
    int connectors = 0, pillars = 0, end_pillars = 0;
    for (const auto& c : sc.columns) {
        if (c.base == plan::Base::Bridge) {
            ++connectors;
            EXPECT_NEAR(c.z0, 15.2, 1e-9);
            EXPECT_NEAR(c.y0, 20, 1e-9);
            EXPECT_NEAR(c.x0, c.x1, 1e-9);  // the nearest bar point is straight across
            EXPECT_EQ(c.top, plan::Top::Contact);
        } else {
            EXPECT_EQ(c.base, plan::Base::Bed);
            EXPECT_DOUBLE_EQ(c.z0, 0);
            EXPECT_EQ(c.x0, c.x1);
            ++pillars;
            if (c.top == plan::Top::Bridge) {
                ++end_pillars;
                EXPECT_NEAR(c.z1, 14.8, 1e-9);
            } else {
                EXPECT_EQ(c.point, 2);
            }
        }
    }
    EXPECT_EQ(connectors, 3);
    EXPECT_EQ(pillars, 3);
    EXPECT_EQ(end_pillars, 2);
    // The first greedy step alone finds the same bridge.
    std::vector<plan::Active> active;
    for (std::size_t i = 0; i < kReportPoints.size(); ++i)
        active.push_back({kReportPoints[i][0], kReportPoints[i][1], kReportPoints[i][2], static_cast<int>(i)});
    auto c = plan::best_bridge(active, free_space(), s);
    ASSERT_TRUE(c.has_value());
    EXPECT_NEAR(c->score, -29.8, 1e-9);
    EXPECT_EQ(c->carried, (std::vector<int>{0, 1, 3}));
}

TEST(PlannerReport, SameBridgeThroughTheRealObstacles) {
    Settings s;
    auto st = empty_stack(25);
    plan::Obstacles obs(st, s);
    auto pts = points_of(kReportPoints);
    for (auto& p : pts.points) p.z = st.layers[p.layer].z - 0.2;  // the layer grid's own z
    for (const auto& sc : {plan::plan_scaffold(pts, obs, s), plan::plan_scaffold(pts, st, obs, s)}) {
        ASSERT_EQ(sc.bridges.size(), 1u);
        EXPECT_NEAR(sc.bridges[0].z, 14.8, 1e-6);
        EXPECT_NEAR(sc.bridges[0].gain, 0.8, 1e-6);
        EXPECT_EQ(sc.bridges[0].points.size(), 3u);
        EXPECT_TRUE(sc.dropped_points.empty());
        auto held = holders(sc, pts.points.size());
        EXPECT_EQ(held, (std::vector<int>{1, 1, 1, 1}));
    }
}

TEST(PlannerModel, NoBridgeThroughAWall) {
    // Two rows of points along y = 20, left and right of a wall at x = 20.
    std::vector<Xyz> xyz{{5, 20, 20}, {10, 20, 20}, {15, 20, 20}, {25, 20, 20}, {30, 20, 20}, {35, 20, 20}};
    Settings s;
    auto pts = points_of(xyz);
    // Without the wall the best bridge spans both rows (30 mm, 6 points:
    // gain 4 * 18 - 30 = 42 against 1 * 18 - 10 = 8 for one row).
    auto open = plan::plan_scaffold(pts, free_space(), s);
    ASSERT_FALSE(open.bridges.empty());
    EXPECT_TRUE(crosses_x(open.bridges[0], 20));
    // With it, no bridge crosses, and each row gets its own.
    auto walled = plan::plan_scaffold(pts, wall_at_20(), s);
    EXPECT_EQ(walled.bridges.size(), 2u);
    for (const auto& b : walled.bridges)
        EXPECT_FALSE(crosses_x(b, 20)) << "bridge from x " << b.x0 << " to " << b.x1 << " at z " << b.z;
    // Nothing comes within the gap of the wall on any layer.
    for (const auto& c : walled.columns)
        for (double z = c.z0 + 0.2; z <= c.z1 + 1e-9; z += 0.2) {
            double x, y;
            plan::column_centre_at(c, z, x, y);
            EXPECT_GT(std::abs(x - 20), 1 + c.radius) << "column at x " << x << " z " << z;
        }
    EXPECT_EQ(holders(walled, xyz.size()), std::vector<int>(xyz.size(), 1));
}

// A bar's clearance is sampled along its line at fixed places (shared by
// every bar on that line and height) and at its two ends, never past them:
// a row whose last point is 17.45, 1.5 mm (pillar radius and gap) plus
// 0.05 short of the wall's face at 19, gets its bar; a sample on the
// line's grid past that end (17.6) would have blocked it. One more point
// at 17.65 and the bar to it is blocked: the row's bar stops at 17.45.
TEST(PlannerModel, ABarEndingJustShortOfTheGapIsClear) {
    Settings s;
    const auto sc = plan::plan_scaffold(points_of({{7.45, 20, 20}, {12.45, 20, 20}, {17.45, 20, 20}}), wall_at_20(), s);
    ASSERT_EQ(sc.bridges.size(), 1u);
    EXPECT_NEAR(std::max(sc.bridges[0].x0, sc.bridges[0].x1), 17.45, 1e-9);
    const auto more =
        plan::plan_scaffold(points_of({{7.45, 20, 20}, {12.45, 20, 20}, {17.45, 20, 20}, {17.65, 20, 20}}), wall_at_20(), s);
    for (const plan::Bridge& b : more.bridges) EXPECT_LT(std::max(b.x0, b.x1), 17.5) << b.x0 << " -> " << b.x1;
}

TEST(PlannerModel, NoBridgeThroughAWallOfTheRealObstacles) {
    // The same rows, the wall now drawn into the layers (1 mm wide at x = 20, up to z 30).
    auto st = empty_stack(32);
    for (auto& l : st.layers)
        if (l.z <= 30 + 1e-9) l.segments.push_back({20, -5, 20, 60, 1.0f, gcode::Role::Perimeter, 0});
    Settings s;
    plan::Obstacles obs(st, s);
    std::vector<Xyz> xyz{{5, 20, 20}, {10, 20, 20}, {15, 20, 20}, {25, 20, 20}, {30, 20, 20}, {35, 20, 20}};
    auto pts = points_of(xyz);
    for (auto& p : pts.points) p.z = st.layers[p.layer].z - 0.2;
    for (const auto& sc : {plan::plan_scaffold(pts, obs, s), plan::plan_scaffold(pts, st, obs, s)}) {
        EXPECT_EQ(sc.bridges.size(), 2u);
        for (const auto& b : sc.bridges) EXPECT_FALSE(crosses_x(b, 20)) << "bridge from x " << b.x0 << " to " << b.x1;
        EXPECT_EQ(holders(sc, xyz.size()), std::vector<int>(xyz.size(), 1));
    }
}

TEST(PlannerModel, PillarStandsOnTheModelBelow) {
    Settings s;
    auto sc = plan::plan_scaffold(points_of({{20, 5, 40}, {60, 5, 40}}), wall_at_20(), s);
    ASSERT_EQ(sc.columns.size(), 2u);
    for (const auto& c : sc.columns) {
        if (c.x0 == 20) {
            EXPECT_EQ(c.base, plan::Base::Model);
            EXPECT_DOUBLE_EQ(c.z0, 30);
            EXPECT_EQ(c.raft_size, 0);
        } else {
            EXPECT_EQ(c.base, plan::Base::Bed);
            EXPECT_DOUBLE_EQ(c.z0, 0);
        }
    }
}

TEST(PlannerModel, ConnectorsLeanAtMostHalfThePillarRadiusPerLayer) {
    // One sweep direction (lines along x). A (0,0,20), B (12,0,20), C (6,4,20):
    // on the line y = 0 C is 4 mm aside. With pillar radius 1 a connector may
    // lean 0.5 mm a layer = 2.5 mm per mm of rise, so C needs a rise of 1.6 mm,
    // plus one straight 0.2 mm layer on the bar (the first loop stands centred
    // on it): bar at most 20 - 0.4 - 0.2 - 1.6 = 17.8, below the 2 mm drop.
    // gain 1 * 17.8 - 12 = 5.8, l_max 4 + 2.2 = 6.2, score 5.8 - 18.6 = -12.8.
    // With radius 0.5: 0.25 mm a layer, 1.25 mm per mm, a rise of 3.2 mm:
    // bar at 20 - 0.4 - 0.2 - 3.2 = 16.2, gain 4.2, l_max 4 + 3.8 = 7.8,
    // score -19.2. (The line y = 4 through C gives the same numbers with A
    // and B aside.)
    Settings s;
    s.sweep_directions = 1;
    std::vector<plan::Active> a{{0, 0, 20, 0}, {12, 0, 20, 1}, {6, 4, 20, 2}};
    auto c = plan::best_bridge(a, free_space(), s);
    ASSERT_TRUE(c.has_value());
    EXPECT_NEAR(c->z, 17.8, 1e-9);
    EXPECT_NEAR(c->score, -12.8, 1e-9);
    EXPECT_EQ(c->carried.size(), 3u);
    s.pillar_radius = 0.5;
    c = plan::best_bridge(a, free_space(), s);
    ASSERT_TRUE(c.has_value());
    EXPECT_NEAR(c->z, 16.2, 1e-9);
    EXPECT_NEAR(c->gain, 4.2, 1e-9);
    EXPECT_NEAR(c->score, -19.2, 1e-9);
    s = Settings{};
    // Every connector of a bigger plan keeps the limit, and its first loop
    // is centred on the bar (a loop is wider than the bar: one leaning off
    // it at once overhangs the bar's side).
    std::mt19937 rng(5);
    std::uniform_real_distribution<double> xy(0, 50), z(5, 30);
    std::vector<Xyz> xyz;
    for (int i = 0; i < 150; ++i) xyz.push_back({xy(rng), xy(rng), 0.2 * std::round(z(rng) / 0.2)});
    auto sc = plan::plan_scaffold(points_of(xyz), free_space(), s);
    double steepest = 0;
    int leaning = 0;
    for (const auto& col : sc.columns)
        if (col.base == plan::Base::Bridge) {
            int layers = static_cast<int>(std::lround((col.z1 - col.z0) / 0.2));
            ASSERT_GT(layers, 0);
            double x, y;
            plan::column_centre_at(col, col.z0 + 0.2, x, y);
            EXPECT_NEAR(x, col.x0, 1e-9);
            EXPECT_NEAR(y, col.y0, 1e-9);
            const double dist = std::hypot(col.x1 - col.x0, col.y1 - col.y0);
            if (dist == 0) continue;
            ++leaning;
            ASSERT_GT(layers, 1);
            plan::column_centre_at(col, col.z0 + 0.4, x, y);
            EXPECT_NEAR(std::hypot(x - col.x0, y - col.y0), dist / (layers - 1), 1e-9);
            double lean = dist / (layers - 1);
            EXPECT_LE(lean, plan::kMaxLeanPerLayer * s.pillar_radius + 1e-9);
            steepest = std::max(steepest, lean);
        }
    EXPECT_GT(leaning, 5);
    EXPECT_GT(steepest, 0.3);  // the limit is reached for, not avoided
}

TEST(PlannerPillars, FarApartPointsAllGetPillars) {
    Settings s;
    auto pts = points_of({{0, 0, 10}, {50, 0, 10}, {0, 50, 10}, {50, 50, 10}, {100, 0, 30}});
    auto sc = plan::plan_scaffold(pts, free_space(), s);
    EXPECT_TRUE(sc.bridges.empty());
    ASSERT_EQ(sc.columns.size(), pts.points.size());
    for (const auto& c : sc.columns) {
        EXPECT_EQ(c.base, plan::Base::Bed);
        EXPECT_EQ(c.top, plan::Top::Contact);
        EXPECT_EQ(c.x0, c.x1);
        EXPECT_EQ(c.y0, c.y1);
        EXPECT_NEAR(c.z1, pts.points[c.point].z, 1e-9);
    }
    EXPECT_EQ(holders(sc, pts.points.size()), std::vector<int>(pts.points.size(), 1));
}

TEST(PlannerPillars, EveryPointHeldByExactlyOneStructure) {
    // A random cloud dense enough for many bridges, some stacked.
    std::mt19937 rng(7);
    std::uniform_real_distribution<double> xy(0, 60), z(5, 40);
    std::vector<Xyz> xyz;
    for (int i = 0; i < 200; ++i) {
        double x = xy(rng), y = xy(rng);
        xyz.push_back({x, y, 0.2 * std::round(z(rng) / 0.2)});
    }
    Settings s;
    auto pts = points_of(xyz);
    auto sc = plan::plan_scaffold(pts, free_space(), s);
    EXPECT_GT(sc.bridges.size(), 10u);
    EXPECT_EQ(holders(sc, xyz.size()), std::vector<int>(xyz.size(), 1));
    // Each bridge's points are exactly the connectors standing on it, and
    // each bridge end is held by one column (a pillar or a connector from a
    // lower bridge) whose top meets it.
    std::size_t carried = 0;
    for (const auto& b : sc.bridges) {
        carried += b.points.size();
        EXPECT_GT(b.gain, 0);
        double len = std::hypot(b.x1 - b.x0, b.y1 - b.y0);
        EXPECT_GE(len, 5 - 1e-9);
        EXPECT_LE(len, 30 + 1e-9);
        for (auto [ex, ey] : {std::pair{b.x0, b.y0}, std::pair{b.x1, b.y1}}) {
            int held = 0;
            for (const auto& c : sc.columns)
                held += c.top == plan::Top::Bridge && std::abs(c.x1 - ex) < 1e-9 && std::abs(c.y1 - ey) < 1e-9 &&
                        std::abs(c.z1 - b.z) < 1e-9;
            EXPECT_GE(held, 1) << "end (" << ex << ", " << ey << ") at z " << b.z;
        }
        for (int p : b.points) EXPECT_GE(pts.points[p].z, b.z + 2 - 1e-9);
    }
    std::size_t connectors = 0;
    for (const auto& c : sc.columns) connectors += c.base == plan::Base::Bridge && c.top == plan::Top::Contact;
    EXPECT_EQ(carried, connectors);
}

TEST(PlannerDeterminism, AnyThreadCountGivesTheSamePlan) {
    // Enough points that a step's dirty seeds are split over threads; the
    // wall makes the bars and the ends ask the model (behind the lock).
    const std::vector<Xyz> xyz = random_points(5, 300, 60, 5, 40);
    Settings s;
    for (const plan::ModelView& m : {free_space(), wall_at_20()}) {
        auto one = plan::plan_scaffold(points_of(xyz), m, s, 1);
        EXPECT_GT(one.bridges.size(), 5u);
        for (int threads : {2, 4}) expect_same(one, plan::plan_scaffold(points_of(xyz), m, s, threads));
    }
}

TEST(PlannerDeterminism, ThreadsAskingTheModelThroughCachesOfTheirOwnGiveTheSamePlan) {
    // The pipeline's search on the real obstacles (a wall 1 mm wide at x 30
    // up to z 20, and a block the pillars step around), its extra threads
    // each asking an Obstacles::another: the plan of one thread, on the
    // first plan and on one made again without a bar (resumed).
    auto st = empty_stack(45, 70);
    for (auto& l : st.layers) {
        if (l.z <= 20 + 1e-9) l.segments.push_back({30, -5, 30, 65, 1.0f, gcode::Role::Perimeter, 0});
        if (l.z <= 6 + 1e-9) l.segments.push_back({10, 40, 20, 40, 3.0f, gcode::Role::Perimeter, 0});
    }
    Settings s;
    const plan::Obstacles obs(st, s);
    std::mt19937 rng(7);
    std::uniform_real_distribution<double> xy(2, 58);
    std::uniform_int_distribution<int> layer(30, 60);
    overhang::SupportPoints pts;
    for (int i = 0; i < 200; ++i) {
        const int l = layer(rng);
        pts.points.push_back({xy(rng), xy(rng), st.layers[l].z, l});
    }
    const auto another = obs.another(), third = obs.another();
    for (const std::vector<const plan::Obstacles*>& helpers :
         {std::vector<const plan::Obstacles*>{another.get()}, std::vector<const plan::Obstacles*>{another.get(), third.get()}}) {
        plan::BridgeReplay alone, with;
        plan::Forbidden forbidden;
        const plan::Scaffold one = plan::plan_scaffold(pts, st, obs, s, forbidden, nullptr, nullptr, &alone);
        ASSERT_GT(one.bridges.size(), 10u);
        expect_same(one, plan::plan_scaffold(pts, st, obs, s, forbidden, nullptr, nullptr, &with, helpers));
        forbidden.bars.push_back(one.bridges[one.bridges.size() / 2]);
        const plan::Scaffold again = plan::plan_scaffold(pts, st, obs, s, forbidden, nullptr, nullptr, &alone);
        expect_same(again, plan::plan_scaffold(pts, st, obs, s, forbidden, nullptr, nullptr, &with, helpers));
        EXPECT_GT(with.offers_replayed, 0);
    }
}

TEST(PlannerForbidden, BarsLeftOutBySearchAreNeverOfferedNorPlanned) {
    // Bars an earlier plan could not hold (here: any bar reaching x 25 to
    // 35 below z 12) turned down as offered (bar_trapped alone), or left
    // out by the search itself (ModelView::bar_forbidden): the second way
    // offers none of them, and neither plans one. (The two plans may
    // differ: a span whose shorter span inside it is forbidden is no
    // longer passed over for it.)
    const std::vector<Xyz> xyz = random_points(3, 60, 60, 5, 20);
    Settings s;
    auto no_bar = [](double z, double x0, double, double x1, double) {
        return z < 12 && std::max(x0, x1) >= 25 && std::min(x0, x1) <= 35;
    };
    int offered_lazy = 0, offered_left_out = 0;
    plan::ModelView lazy = free_space(), left_out = free_space();
    lazy.bar_trapped = [&](double z, double x0, double y0, double x1, double y1) {
        const bool t = no_bar(z, x0, y0, x1, y1);
        offered_lazy += t;
        return t;
    };
    left_out.bar_trapped = [&](double z, double x0, double y0, double x1, double y1) {
        const bool t = no_bar(z, x0, y0, x1, y1);
        offered_left_out += t;
        return t;
    };
    left_out.bar_forbidden = no_bar;
    const plan::Scaffold a = plan::plan_scaffold(points_of(xyz), lazy, s, 1);
    const plan::Scaffold b = plan::plan_scaffold(points_of(xyz), left_out, s, 1);
    EXPECT_GT(offered_lazy, 0);
    EXPECT_EQ(offered_left_out, 0);
    for (const plan::Scaffold* sc : {&a, &b}) {
        EXPECT_GT(sc->bridges.size(), 5u);
        for (const plan::Bridge& br : sc->bridges) EXPECT_FALSE(no_bar(br.z, br.x0, br.y0, br.x1, br.y1));
    }
}

TEST(PlannerDeterminism, SameInputTwiceAndShuffledGiveTheSamePlan) {
    std::mt19937 rng(11);
    std::uniform_real_distribution<double> xy(0, 50), z(5, 30);
    std::vector<Xyz> xyz;
    for (int i = 0; i < 120; ++i) xyz.push_back({xy(rng), xy(rng), 0.2 * std::round(z(rng) / 0.2)});
    // A grid with equal heights, where ties between bridges are everywhere.
    for (double x = 70; x <= 100; x += 5)
        for (double y = 0; y <= 30; y += 5) xyz.push_back({x, y, 20});
    Settings s;
    auto a = plan::plan_scaffold(points_of(xyz), free_space(), s);
    auto b = plan::plan_scaffold(points_of(xyz), free_space(), s);
    EXPECT_GT(a.bridges.size(), 5u);
    expect_same(a, b);

    // Shuffled: the same plan once point indices are mapped back.
    std::vector<int> perm(xyz.size());
    for (std::size_t i = 0; i < perm.size(); ++i) perm[i] = static_cast<int>(i);
    std::shuffle(perm.begin(), perm.end(), std::mt19937(3));
    std::vector<Xyz> shuffled;
    for (int i : perm) shuffled.push_back(xyz[i]);
    auto c = plan::plan_scaffold(points_of(shuffled), free_space(), s);
    for (auto& br : c.bridges) {
        for (int& p : br.points) p = perm[p];
    }
    for (auto& col : c.columns)
        if (col.point >= 0) col.point = perm[col.point];
    for (int& p : c.dropped_points) p = perm[p];
    std::sort(c.dropped_points.begin(), c.dropped_points.end());
    expect_same(a, c);
}

TEST(PlannerSearch, IncrementalSearchAgreesWithAFreshOneAtEveryStep) {
    // The search keeps each seed's best and recomputes only seeds whose
    // window changed; after every greedy step its answer must equal a search
    // built from scratch on the points still active.
    std::mt19937 rng(23);
    std::uniform_real_distribution<double> xy(0, 70), z(5, 40);
    Settings s;
    const plan::ModelView m = free_space();
    plan::BridgeSearch search(m, s);
    for (int i = 0; i < 150; ++i) search.add({xy(rng), xy(rng), 0.2 * std::round(z(rng) / 0.2), i});
    int steps = 0;
    while (auto c = search.best()) {
        std::vector<plan::Active> alive;
        std::vector<int> id_of;
        for (int id = 0; id < search.size(); ++id)
            if (search.alive(id)) {
                alive.push_back(search.active(id));
                id_of.push_back(id);
            }
        auto fresh = plan::best_bridge(alive, m, s);
        ASSERT_TRUE(fresh.has_value()) << "step " << steps;
        EXPECT_EQ(std::tie(c->x0, c->y0, c->x1, c->y1, c->z, c->score),
                  std::tie(fresh->x0, fresh->y0, fresh->x1, fresh->y1, fresh->z, fresh->score)) << "step " << steps;
        std::vector<int> carried;
        for (int i : fresh->carried) carried.push_back(id_of[i]);
        EXPECT_EQ(c->carried, carried) << "step " << steps;
        for (int id : c->carried) search.remove(id);
        search.add({c->x0, c->y0, c->z, -1});
        search.add({c->x1, c->y1, c->z, -1});
        ++steps;
    }
    EXPECT_GT(steps, 15);
}

// A span blocked at its height is tried a step lower (bridge_height_step),
// counting the points a bar there carries: four points on y = 10, two at
// z 20 and two at z 17. The best bar carries all four; with bars at its
// height blocked, the one offered is the same span a step lower, still
// carrying all four, scored for that height (l_max up to the z 20 points).
// (The bars carry a point from 2 mm under it: heights 18 and 15, and at 18
// only two points.)
TEST(PlannerSearch, ABlockedSpanIsTriedAStepLowerWithWhatItCarriesThere) {
    Settings s;
    const plan::ModelView open = free_space();
    plan::BridgeSearch unblocked(open, s);
    const double xs[4] = {10, 14, 18, 22}, zs[4] = {20, 20, 17, 17};
    for (int i = 0; i < 4; ++i) unblocked.add({xs[i], 10, zs[i], i});
    const auto top = unblocked.best();
    ASSERT_TRUE(top);
    ASSERT_EQ(top->carried.size(), 4u);
    const double z_top = top->z;
    EXPECT_NEAR(z_top, 15, 1e-9);
    plan::ModelView m = free_space();
    // A bar at z fills the layers up to kBarThickness above it.
    m.segment_clear = [z_top](double z, double, double, double, double, double) { return !(z > z_top && z <= z_top + 1); };
    plan::BridgeSearch search(m, s);
    for (int i = 0; i < 4; ++i) search.add({xs[i], 10, zs[i], i});
    const auto lower = search.best();
    ASSERT_TRUE(lower);
    const double z2 = m.snap_down(z_top - s.bridge_height_step);
    EXPECT_NEAR(lower->z, z2, 1e-9);
    EXPECT_EQ(std::tie(lower->x0, lower->x1), std::tie(top->x0, top->x1));
    EXPECT_EQ(lower->carried, top->carried);
    const double len = top->x1 - top->x0;
    EXPECT_DOUBLE_EQ(lower->gain, plan::bridge_gain(4, z2, len));
    EXPECT_DOUBLE_EQ(lower->score, plan::bridge_score(plan::bridge_gain(4, z2, len), 4, 20 - z2));
}

TEST(PlannerSearch, APointNoConnectorReachesIsNoLongerCountedOnThatLine) {
    // Four points on the line y = 10, 4 mm apart: the best bar carries all
    // four. Once no connector reaches point 1 from it, no bar on that line at
    // that height may count point 1 again (without the rule the spans 10-18
    // and 14-22 would, one rejection after another).
    Settings s;
    const plan::ModelView m = free_space();
    plan::BridgeSearch search(m, s);
    for (int i = 0; i < 4; ++i) search.add({10.0 + 4 * i, 10, 20, i});
    auto first = search.best();
    ASSERT_TRUE(first);
    ASSERT_EQ(first->carried.size(), 4u);
    search.no_connector(1, *first);
    search.reject(*first);
    int offered = 0;
    while (auto c = search.best()) {
        const bool on_line = std::abs(c->y0 - 10) < 1e-9 && std::abs(c->y1 - 10) < 1e-9;
        if (on_line && std::abs(c->z - first->z) < 1e-9) {
            EXPECT_EQ(std::count(c->carried.begin(), c->carried.end(), 1), 0) << c->x0 << " - " << c->x1;
        }
        search.reject(*c);
        ASSERT_LT(++offered, 200);
    }
    EXPECT_GT(offered, 0);  // the lower bars were still offered
}

// A bar turned down is not offered again by any seed on its line: the
// search asks its table of rejected bars only at heights where the line
// (direction, offset) may hold one. Six points on a diagonal, 3 mm apart
// (each seed's offset across the line computed from its own point, so they
// differ in the last bits), and six on a horizontal line: every bar offered
// is rejected, and none comes back. (A search that misses a rejected bar
// on its line offers it again and again: best() never returns, and the
// test fails by its timeout.)
TEST(PlannerSearch, ARejectedBarIsNotOfferedAgainFromAnyPointOnItsLine) {
    Settings s;
    const plan::ModelView m = free_space();
    plan::BridgeSearch search(m, s);
    for (int i = 0; i < 6; ++i) search.add({10.0 + 3 * std::numbers::sqrt2 / 2 * i, 50.0 + 3 * std::numbers::sqrt2 / 2 * i, 20, i});
    for (int i = 0; i < 6; ++i) search.add({30.0 + 3 * i, 10.0, 18, 6 + i});
    std::set<std::array<long, 5>> offered;
    auto um = [](double v) { return std::lround(v * 1000); };
    int diagonal = 0;
    while (auto c = search.best()) {
        std::array<long, 5> key{um(c->x0), um(c->y0), um(c->x1), um(c->y1), um(c->z)};
        if (std::make_pair(key[2], key[3]) < std::make_pair(key[0], key[1])) {
            std::swap(key[0], key[2]);
            std::swap(key[1], key[3]);
        }
        ASSERT_TRUE(offered.insert(key).second) << "offered again: (" << c->x0 << ", " << c->y0 << ") -> (" << c->x1
                                                << ", " << c->y1 << ") z " << c->z;
        diagonal += std::abs((c->y1 - c->y0) - (c->x1 - c->x0)) < 1e-6 && c->y0 > 40;
        search.reject(*c);
        ASSERT_LT(offered.size(), 2000u);
    }
    EXPECT_GT(diagonal, 10);  // many bars along the diagonal, from its several seeds
    EXPECT_GT(offered.size(), 20u);
}

// A bar that failed as built is not taken again, nor one next to it (ends
// within 1 mm), nor one along its line (ends within 0.5 mm of it, within
// 5 degrees, over half the shorter's length): the bull's belly bar came
// back six rounds running as (114.05, 108.65) -> (131.55, 108.65), then
// (115.35 ..), (.. 130.35), (109.65 ..), its ends 1.2 to 4.4 mm apart.
TEST(PlannerForbidden, NeitherTheSameBarNorOneAlongItsLine) {
    auto bar = [](double x0, double y0, double x1, double y1, double z) {
        plan::Bridge b;
        b.x0 = x0, b.y0 = y0, b.x1 = x1, b.y1 = y1, b.z = z;
        return b;
    };
    const plan::Forbidden failed{{bar(114.05, 108.65, 131.55, 108.65, 6.6)}, {}};
    EXPECT_TRUE(plan::near_forbidden(failed, bar(114.5, 108.9, 131.2, 108.2, 6.6), 0.2));   // ends within 1 mm
    EXPECT_TRUE(plan::near_forbidden(failed, bar(131.55, 108.65, 114.05, 108.65, 6.8), 0.2));  // reversed, a layer up
    for (const plan::Bridge& b : {bar(115.35, 108.65, 131.55, 108.65, 6.6), bar(114.05, 108.65, 130.35, 108.65, 6.6),
                                  bar(109.65, 108.65, 131.55, 108.65, 6.8), bar(120.0, 108.85, 126.0, 108.75, 6.6)})
        EXPECT_TRUE(plan::near_forbidden(failed, b, 0.2)) << b.x0 << " -> " << b.x1;
    // Not along it: 1.2 mm beside, 10 degrees off (2.6 mm over 15), a third
    // of it (6 of an 18 mm bar overlap), or 0.6 mm higher.
    EXPECT_FALSE(plan::near_forbidden(failed, bar(114.05, 109.85, 131.55, 109.85, 6.6), 0.2));
    EXPECT_FALSE(plan::near_forbidden(failed, bar(116.0, 108.65, 131.0, 111.30, 6.6), 0.2));
    EXPECT_FALSE(plan::near_forbidden(failed, bar(125.55, 108.65, 143.55, 108.65, 6.6), 0.2));
    EXPECT_FALSE(plan::near_forbidden(failed, bar(115.35, 108.65, 131.55, 108.65, 7.2), 0.2));
}

// A place a bar failed beside (bunny, z 6.4: a line at x 15.16 passed the
// loop of a column at (13.95, 13.95), its edge 14.48): no bar within 1 mm of
// it, within three layers of that bar; one further off, or higher, may.
TEST(PlannerForbidden, NoBarPassesNearAPlaceABarFailedBeside) {
    auto bar = [](double x0, double y0, double x1, double y1, double z) {
        plan::Bridge b;
        b.x0 = x0, b.y0 = y0, b.x1 = x1, b.y1 = y1, b.z = z;
        return b;
    };
    const plan::Forbidden failed{{}, {{14.55, 14.35, 6.4}}};
    // 0.95 mm off at z 6.4; 0.3 mm off three layers up (6.8: the bunny's
    // next plan); across it at 6.0; ending 0.6 mm short of it.
    for (const plan::Bridge& b : {bar(15.50, 12.0, 15.50, 18.0, 6.4), bar(14.25, 10.0, 14.25, 20.0, 7.0),
                                  bar(10.0, 10.0, 20.0, 20.0, 5.8), bar(14.55, 14.95, 14.55, 20.0, 6.4)})
        EXPECT_TRUE(plan::near_forbidden(failed, b, 0.2)) << b.x0 << ", " << b.y0 << " z " << b.z;
    // 1.05 mm off; four layers up (7.2) or down (5.6); ending 1.1 mm short.
    for (const plan::Bridge& b : {bar(15.60, 12.0, 15.60, 18.0, 6.4), bar(14.25, 10.0, 14.25, 20.0, 7.2),
                                  bar(14.25, 10.0, 14.25, 20.0, 5.6), bar(14.55, 15.45, 14.55, 20.0, 6.4)})
        EXPECT_FALSE(plan::near_forbidden(failed, b, 0.2)) << b.x0 << ", " << b.y0 << " z " << b.z;
}

// The search asks ForbiddenLookup (the forbidden sorted by height, boxes
// compared first) of every candidate: it answers as near_forbidden does.
// Bars and places on a 0.1 mm grid of heights, queries near them (ends a
// few mm off, some along their lines) at heights up to 1 mm away.
TEST(PlannerForbidden, TheLookupAnswersAsTheListDoes) {
    std::mt19937 rng(7);
    std::uniform_real_distribution<double> xy(0, 40), off(-1.5, 1.5), t(-0.3, 1.3);
    std::uniform_int_distribution<int> layer(20, 60), dz(-10, 10);
    const double h = 0.1;
    plan::Forbidden forbidden;
    for (int i = 0; i < 40; ++i) {
        plan::Bridge b;
        b.x0 = xy(rng), b.y0 = xy(rng), b.x1 = xy(rng), b.y1 = xy(rng), b.z = layer(rng) * h;
        forbidden.bars.push_back(b);
        forbidden.places.push_back({xy(rng), xy(rng), layer(rng) * h});
    }
    const plan::ForbiddenLookup lookup(forbidden, h);
    int near = 0, queries = 0;
    for (int i = 0; i < 20000; ++i) {
        plan::Bridge q;
        const plan::Bridge& f = forbidden.bars[static_cast<std::size_t>(i) % forbidden.bars.size()];
        if (i % 3 == 0) {  // along f's line, a stretch of it, a little aside
            const double a = t(rng), b = t(rng);
            q.x0 = f.x0 + (f.x1 - f.x0) * a + off(rng) * 0.4, q.y0 = f.y0 + (f.y1 - f.y0) * a + off(rng) * 0.4;
            q.x1 = f.x0 + (f.x1 - f.x0) * b + off(rng) * 0.4, q.y1 = f.y0 + (f.y1 - f.y0) * b + off(rng) * 0.4;
        } else if (i % 3 == 1) {  // its ends moved
            q.x0 = f.x0 + off(rng), q.y0 = f.y0 + off(rng), q.x1 = f.x1 + off(rng), q.y1 = f.y1 + off(rng);
        } else {
            q.x0 = xy(rng), q.y0 = xy(rng), q.x1 = xy(rng), q.y1 = xy(rng);
        }
        q.z = f.z + dz(rng) * h;
        const bool expected = plan::near_forbidden(forbidden, q, h);
        ASSERT_EQ(lookup(q), expected) << "(" << q.x0 << ", " << q.y0 << ") -> (" << q.x1 << ", " << q.y1 << ") z " << q.z;
        near += expected;
        ++queries;
    }
    // Both answers well represented.
    EXPECT_GT(near, queries / 10);
    EXPECT_LT(near, queries * 9 / 10);
    EXPECT_FALSE(plan::ForbiddenLookup({}, h)(forbidden.bars[0]));
}

// The search asks any_near once per seed and height before asking the
// lookup about each span there: it must never say "none" where some bar in
// the box is forbidden. The bull's belly bar (6.6 mm, 0.2 mm layers: its
// window is 1.5 layers, its box grown by 1 mm) is near a box reaching to
// within 1 mm of it at 6.6 to 6.8 mm, not one 1.1 mm off, nor 2 layers up.
TEST(PlannerForbidden, NoneNearOnlyWhereNoBarInTheBoxIsForbidden) {
    plan::Bridge belly;
    belly.x0 = 114.05, belly.y0 = 108.65, belly.x1 = 131.55, belly.y1 = 108.65, belly.z = 6.6;
    const plan::ForbiddenLookup one(plan::Forbidden{{belly}, {}}, 0.2);
    EXPECT_TRUE(one.any_near(6.6, 100, 100, 120, 108.0));  // its box reaches 107.65
    EXPECT_TRUE(one.any_near(6.8, 132.5, 100, 140, 120));  // 0.95 mm past its end, a layer up
    EXPECT_FALSE(one.any_near(6.6, 100, 100, 120, 107.55));  // 1.1 mm short of it
    EXPECT_FALSE(one.any_near(7.0, 100, 100, 140, 120));     // two layers up
    EXPECT_FALSE(one.any_near(6.6, 0, 0, 100, 100));
    const plan::ForbiddenLookup place(plan::Forbidden{{}, {{14.55, 14.35, 6.4}}}, 0.2);
    EXPECT_TRUE(place.any_near(7.0, 15.5, 10, 20, 20));    // 0.95 mm off, three layers up
    EXPECT_FALSE(place.any_near(7.2, 15.5, 10, 20, 20));   // four layers up
    EXPECT_FALSE(place.any_near(6.4, 15.65, 10, 20, 20));  // 1.1 mm off

    // Random forbidden bars and places, random boxes; bars in each box at
    // heights near theirs: where the lookup forbids one, any_near says so.
    std::mt19937 rng(11);
    std::uniform_real_distribution<double> xy(0, 60), size(1, 30), u(0, 1);
    std::uniform_int_distribution<int> layer(20, 60), dz(-6, 6);
    const double h = 0.1;
    plan::Forbidden forbidden;
    for (int i = 0; i < 30; ++i) {
        plan::Bridge b;
        b.x0 = xy(rng), b.y0 = xy(rng), b.x1 = b.x0 + size(rng) - 15, b.y1 = b.y0 + size(rng) - 15, b.z = layer(rng) * h;
        forbidden.bars.push_back(b);
        forbidden.places.push_back({xy(rng), xy(rng), layer(rng) * h});
    }
    const plan::ForbiddenLookup lookup(forbidden, h);
    int boxes_none = 0, forbidden_in_box = 0;
    for (int i = 0; i < 3000; ++i) {
        const double x_lo = xy(rng), y_lo = xy(rng), x_hi = x_lo + size(rng), y_hi = y_lo + size(rng);
        const double z = forbidden.bars[static_cast<std::size_t>(i) % forbidden.bars.size()].z + dz(rng) * h;
        const bool maybe = lookup.any_near(z, x_lo, y_lo, x_hi, y_hi);
        boxes_none += !maybe;
        for (int j = 0; j < 40; ++j) {
            plan::Bridge q;
            q.x0 = x_lo + (x_hi - x_lo) * u(rng), q.y0 = y_lo + (y_hi - y_lo) * u(rng);
            q.x1 = x_lo + (x_hi - x_lo) * u(rng), q.y1 = y_lo + (y_hi - y_lo) * u(rng), q.z = z;
            if (!lookup(q)) continue;
            ++forbidden_in_box;
            ASSERT_TRUE(maybe) << "box (" << x_lo << ", " << y_lo << ") - (" << x_hi << ", " << y_hi << ") z " << z;
        }
    }
    // Both kinds of box well represented: the filter saves lookups and is tried.
    EXPECT_GT(boxes_none, 300);
    EXPECT_GT(forbidden_in_box, 300);
}

// The lowest bar whose connector meets METHOD's Standing rule as the
// planner holds it (half of what the whole may give: 0.5 / (2 x 1.25) =
// 0.2 mm/N). A 0.75 mm stick of 0.45 mm beads: rc = 0.525, E I = 3500 pi
// 0.525^3 0.45 = 715.992; a stick H tall gives H^3 / (3 E I) at its top.
// Under it the bar's own two layers, bent about its long axis: offered on
// the longest bar (30 mm, 31 with its reach into the pillars), two 0.45 mm
// lines side by side, I = 31 x 0.9^3 / 12 = 1.883250, E I = 6591.375, give
// ((H + 0.4)^3 - H^3) / (3 x 6591.375). Both together 0.2 mm/N at H =
// 7.49994 (the stick alone: 7.5455), so the bar carries a point at z 22.97
// from 22.97 - 7.49994 - 0.4 = 15.07006 up. With 0.1 mm/N standing on the
// point already, H = 5.94276: from 16.62724. With 0.2 mm/N, none: no stick
// is left any give.
TEST(Candidates, TheLowestBarThatCarriesAPointByItsConnectorsGive) {
    Settings s;
    plan::Active a{30, 30, 22.97, 0};
    EXPECT_NEAR(plan::lowest_carrying_bar(a, s), 15.070058, 1e-5);
    a.give = 0.1;
    EXPECT_NEAR(plan::lowest_carrying_bar(a, s), 16.627235, 1e-5);
    a.give = 0.2;
    EXPECT_GT(plan::lowest_carrying_bar(a, s), 22.97 - 0.4 - 1e-6);
    s.min_stiffness = 0;  // the rule off: any bar
    EXPECT_EQ(plan::lowest_carrying_bar(a, s), 0);
}

// Five points in a row at z 30, each with 0.19 mm/N standing on it
// already (a bar end's connectors), the model in the way of a bar on every
// layer above z 27 (so the highest bar is at 26, its layers 26.2 and 26.4;
// at 27 and 28 they are blocked): a connector may then give 0.01 mm/N, a
// stick 2.7305 mm tall over the longest bar's two layers (the test above),
// so only a bar from 30 - 2.7305 - 0.4 = 26.8695 up carries them; the bar at 26 (connectors 3.6 mm: 3.6^3 / 2147.98 =
// 0.0217 mm/N) is not offered (before, it was, carrying all five, and each
// connector was turned down in turn). With the rule off, that bar.
TEST(Candidates, NoBarIsOfferedForPointsItsConnectorsCannotHold) {
    Settings s;
    s.sweep_directions = 1;
    plan::ModelView m = free_space();
    m.segment_clear = [](double z, double, double, double, double, double) { return z <= 27 + 1e-9; };
    std::vector<plan::Active> a;
    for (int i = 0; i < 5; ++i) a.push_back({3.0 * i, 0, 30, -1, 30, 0.19});
    EXPECT_NEAR(plan::lowest_carrying_bar(a[0], s), 26.8695, 1e-3);
    EXPECT_FALSE(plan::best_bridge(a, m, s).has_value());
    s.min_stiffness = 0;
    const auto c = plan::best_bridge(a, m, s);
    ASSERT_TRUE(c.has_value());
    EXPECT_NEAR(c->z, 26, 1e-9);
    EXPECT_EQ(c->carried.size(), 5u);
}
