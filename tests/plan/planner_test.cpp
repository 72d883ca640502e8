#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "layers/layer_stack.hpp"
#include "plan/obstacles.hpp"
#include "plan/pillars.hpp"
#include "plan/planner.hpp"

using namespace scaffold;

namespace {

// 0.2 mm layers up to `top`, each with a speck of model far away so the
// obstacle raster has bounds; nothing near the points.
layers::LayerStack empty_stack(double top) {
    layers::LayerStack st;
    int n = static_cast<int>(std::lround(top / 0.2));
    for (int i = 0; i < n; ++i) {
        layers::Layer l;
        l.z = 0.2 * (i + 1);
        l.height = 0.2;
        l.below = i - 1;
        l.on_bed = i == 0;
        l.segments.push_back({0, 0, 0.5f, 0, 0.45f, gcode::Role::Perimeter, 0});
        st.layers.push_back(l);
    }
    st.bounds = {-5, -5, 60, 60};
    return st;
}

std::vector<double> tops_of(const layers::LayerStack& st) {
    std::vector<double> t;
    for (const auto& l : st.layers) t.push_back(l.z);
    return t;
}

overhang::SupportPoints points_at(const layers::LayerStack& st, std::vector<std::array<double, 3>> xyz) {
    overhang::SupportPoints p;
    for (auto [x, y, z] : xyz) {
        int layer = static_cast<int>(std::lround(z / 0.2));  // the layer whose bottom is z
        p.points.push_back({x, y, st.layers[layer].z - 0.2, layer});
    }
    return p;
}

}  // namespace

TEST(Planner, GainAndScoreByHand) {
    // 4 points on a bridge 10 mm long at z = 12: gain (4-2)*12 - 10 = 14.
    EXPECT_DOUBLE_EQ(plan::bridge_gain(4, 12, 10), 14);
    // l_max 6: score 14 - 4*6 = -10 (scores may be negative).
    EXPECT_DOUBLE_EQ(plan::bridge_score(14, 4, 6), -10);
    // Two points never pay: (2-2)*z - len < 0.
    EXPECT_LT(plan::bridge_gain(2, 50, 5), 0);
}

TEST(Planner, ReportFourPointExampleYieldsOneBridgeForThreePoints) {
    // Tupek's appendix: points (18,24,17), (11,15,20), (19,9,15), (25,20,18).
    auto st = empty_stack(25);
    Settings s;
    std::vector<plan::Active> active{{18, 24, 17, 0}, {11, 15, 20, 1}, {19, 9, 15, 2}, {25, 20, 18, 3}};
    auto c = plan::best_bridge(active, tops_of(st), s);
    ASSERT_EQ(c.carried.size(), 3u);
    double len = std::hypot(c.x1 - c.x0, c.y1 - c.y0);
    EXPECT_GE(len, 5 - 1e-9);
    EXPECT_LE(len, 30 + 1e-9);
    // Gain by hand from what was chosen: (3 - 2) * z - length.
    EXPECT_NEAR(c.gain, c.z - len, 1e-9);
    EXPECT_GT(c.gain, 0);
    // Every carried point is at least 2 mm above the bar's top and within 5 mm of it.
    for (int i : c.carried) {
        EXPECT_GE(active[i].z - c.z - 0.4, 2 - 1e-9);
        double dx = c.x1 - c.x0, dy = c.y1 - c.y0;
        double t = std::clamp(((active[i].x - c.x0) * dx + (active[i].y - c.y0) * dy) / (dx * dx + dy * dy), 0.0, 1.0);
        EXPECT_LE(std::hypot(active[i].x - c.x0 - t * dx, active[i].y - c.y0 - t * dy), 5 + 1e-9);
    }
    // The whole plan: one bridge, the fourth point on its own pillar.
    auto pts = points_at(st, {{18, 24, 17}, {11, 15, 20}, {19, 9, 15}, {25, 20, 18}});
    plan::Obstacles obs(st, s);
    auto sc = plan::plan_scaffold(pts, st, obs, s);
    ASSERT_EQ(sc.bridges.size(), 1u);
    EXPECT_EQ(sc.bridges[0].points.size(), 3u);
    EXPECT_TRUE(sc.dropped_points.empty());
}

TEST(Planner, NoBridgeThroughTheModelAndEveryPointHeldOnce) {
    // Two rows of points 20 mm high either side of a wall at x = 20.
    auto st = empty_stack(25);
    for (auto& l : st.layers)
        if (l.z <= 12.0 + 1e-9) l.segments.push_back({20, -5, 20, 60, 1.0f, gcode::Role::Perimeter, 0});
    std::vector<std::array<double, 3>> xyz;
    for (double y = 10; y <= 40; y += 5) {
        xyz.push_back({10, y, 20});
        xyz.push_back({30, y, 20});
    }
    Settings s;
    auto pts = points_at(st, xyz);
    plan::Obstacles obs(st, s);
    auto sc = plan::plan_scaffold(pts, st, obs, s);
    EXPECT_GE(sc.bridges.size(), 1u);
    for (const auto& b : sc.bridges) {
        bool crosses = (b.x0 - 20) * (b.x1 - 20) <= 0;
        EXPECT_FALSE(crosses && b.z <= 12.0) << "bridge from x " << b.x0 << " to " << b.x1 << " at z " << b.z;
    }
    // Each point is held by exactly one column top (a pillar or a connector).
    std::vector<int> held(pts.points.size(), 0);
    for (const auto& c : sc.columns)
        if (c.point >= 0 && c.top == plan::Top::Contact) held[c.point]++;
    for (std::size_t i = 0; i < held.size(); ++i) EXPECT_EQ(held[i], 1) << "point " << i;
}

TEST(Planner, FarApartPointsGetPillarsAndPlansAreDeterministic) {
    auto st = empty_stack(25);
    Settings s;
    auto pts = points_at(st, {{0, 0, 10}, {50, 0, 10}, {0, 50, 10}, {50, 50, 10}});
    plan::Obstacles obs(st, s);
    auto sc = plan::plan_scaffold(pts, st, obs, s);
    EXPECT_TRUE(sc.bridges.empty());
    int tops = 0;
    for (const auto& c : sc.columns) tops += c.top == plan::Top::Contact;
    EXPECT_EQ(tops, 4);
    // Same input, same plan; shuffled input, same bridges.
    std::vector<std::array<double, 3>> grid;
    for (double x = 5; x <= 30; x += 5)
        for (double y = 5; y <= 30; y += 5) grid.push_back({x, y, 12 + 0.2 * std::fmod(x + y, 3.0)});
    auto a = plan::plan_scaffold(points_at(st, grid), st, obs, s);
    auto b = plan::plan_scaffold(points_at(st, grid), st, obs, s);
    ASSERT_EQ(a.bridges.size(), b.bridges.size());
    ASSERT_EQ(a.columns.size(), b.columns.size());
    for (std::size_t i = 0; i < a.bridges.size(); ++i) {
        EXPECT_EQ(a.bridges[i].x0, b.bridges[i].x0);
        EXPECT_EQ(a.bridges[i].z, b.bridges[i].z);
    }
    for (std::size_t i = 0; i < a.columns.size(); ++i) EXPECT_EQ(a.columns[i].x1, b.columns[i].x1);
    EXPECT_GE(a.bridges.size(), 1u);
}
