#pragma once
// Support points and an empty model for the planner's tests, in plain numbers.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <tuple>
#include <vector>

#include "overhang/overhangs.hpp"
#include "plan/candidates.hpp"
#include "plan/scaffold.hpp"

namespace scaffold::test {

using Xyz = std::array<double, 3>;

// Support points at (x, y, z), z being the bottom of their overhang layer
// (0.2 mm layers), in the order given.
inline overhang::SupportPoints points_of(const std::vector<Xyz>& xyz) {
    overhang::SupportPoints p;
    for (auto [x, y, z] : xyz) p.points.push_back({x, y, z, static_cast<int>(std::lround(z / 0.2))});
    return p;
}

// No model, 0.2 mm layers up to 80 mm.
inline plan::ModelView free_space() {
    plan::ModelView m;
    for (int i = 1; i <= 400; ++i) m.layer_tops.push_back(0.2 * i);
    return m;
}

// Two plans alike, bar by bar and column by column (gtest expectations).
inline void expect_same(const plan::Scaffold& a, const plan::Scaffold& b) {
    ASSERT_EQ(a.bridges.size(), b.bridges.size());
    ASSERT_EQ(a.columns.size(), b.columns.size());
    for (std::size_t i = 0; i < a.bridges.size(); ++i) {
        const auto &x = a.bridges[i], &y = b.bridges[i];
        EXPECT_EQ(std::tie(x.x0, x.y0, x.x1, x.y1, x.z, x.points, x.gain, x.score),
                  std::tie(y.x0, y.y0, y.x1, y.y1, y.z, y.points, y.gain, y.score)) << "bridge " << i;
    }
    for (std::size_t i = 0; i < a.columns.size(); ++i) {
        const auto &x = a.columns[i], &y = b.columns[i];
        EXPECT_EQ(std::tie(x.x0, x.y0, x.z0, x.x1, x.y1, x.z1, x.radius, x.base, x.top, x.point, x.contact_z,
                           x.foot_radius, x.raft_size),
                  std::tie(y.x0, y.y0, y.z0, y.x1, y.y1, y.z1, y.radius, y.base, y.top, y.point, y.contact_z,
                           y.foot_radius, y.raft_size)) << "column " << i;
    }
    EXPECT_EQ(a.dropped_points, b.dropped_points);
}

}  // namespace scaffold::test
