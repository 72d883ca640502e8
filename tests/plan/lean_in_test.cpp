#include <gtest/gtest.h>

#include <cmath>

#include "layers/layer_stack.hpp"
#include "plan/lean_in.hpp"
#include "plan/obstacles.hpp"
#include "plan/pillars.hpp"
#include "support/stacks.hpp"

using namespace scaffold;

namespace {

// 0.2 mm layers to z 10, a wall (x 44..48.5, y 40..60) on every layer.
layers::LayerStack walled() {
    return test::stack_of(
        50,
        [](int, layers::Layer& l) {
            for (double x = 44.225; x < 48.5; x += 0.45) test::bead(l, x, 40, x, 60);
        },
        {30, 30, 70, 70});
}

}  // namespace

TEST(LeanIn, AThinColumnLeansFromAPillarToThePointAsFarAsALoopMayShift) {
    Settings s;
    const auto st = walled();
    const plan::Obstacles obs(st, s);
    auto chain = plan::lean_in(50, 50, 45, st, obs, s);
    ASSERT_TRUE(chain.has_value());
    ASSERT_GE(chain->size(), 2u);
    const plan::Column& lean = chain->back();
    const plan::Column& under = (*chain)[chain->size() - 2];
    EXPECT_EQ(lean.top, plan::Top::Contact);
    EXPECT_EQ(lean.base, plan::Base::Column);
    EXPECT_NEAR(lean.x1, 50, 1e-9);  // the point has room for its own tip
    EXPECT_NEAR(lean.y1, 50, 1e-9);
    EXPECT_NEAR(lean.z1, st.layers[44].z, 1e-9);
    // It stands on the pillar's top: same place, same (tip) radius.
    EXPECT_NEAR(under.x1, lean.x0, 1e-9);
    EXPECT_NEAR(under.y1, lean.y0, 1e-9);
    EXPECT_NEAR(under.z1, lean.z0, 1e-9);
    EXPECT_NEAR(plan::column_radius_at(under, under.z1, s), plan::column_radius_at(lean, lean.z0 + 0.2, s), 1e-9);
    const double d = std::hypot(lean.x1 - lean.x0, lean.y1 - lean.y0);
    EXPECT_GE(d, 1.0 - 1e-9);
    // The first loop centred on the pillar, then at most loop_shift_limit a
    // layer, and clear of the wall (the gap, the tip's clearance at the top).
    double px = lean.x0, py = lean.y0;
    for (double z = lean.z0 + 0.2; z <= lean.z1 + 1e-6; z += 0.2) {
        double x, y;
        plan::column_centre_at(lean, z, x, y);
        if (z < lean.z0 + 0.3) {
            EXPECT_NEAR(x, lean.x0, 1e-9);
            EXPECT_NEAR(y, lean.y0, 1e-9);
        }
        EXPECT_LE(std::hypot(x - px, y - py), plan::loop_shift_limit(0.2, s) + 1e-9);
        const int l = static_cast<int>(std::lround(z / 0.2)) - 1;
        EXPECT_TRUE(obs.disc_clear(l, x, y, plan::column_radius_at(lean, z, s) + plan::clearance_at(lean, z, s)))
            << "z " << z;
        px = x;
        py = y;
    }
    // The pillar reaches the bed, clear of the wall.
    EXPECT_EQ(chain->front().base, plan::Base::Bed);
}

TEST(LeanIn, NothingWhenThePointsOwnContactHasNoRoomAndNoSheetIsBeside) {
    Settings s;
    const auto st = walled();
    const plan::Obstacles obs(st, s);
    // Inside the wall: no tip fits at the point nor beside it.
    EXPECT_FALSE(plan::lean_in(46, 50, 45, st, obs, s).has_value());
}
