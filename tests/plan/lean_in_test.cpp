#include <gtest/gtest.h>

#include <cmath>

#include "layers/layer_stack.hpp"
#include "plan/braces.hpp"
#include "plan/lean_in.hpp"
#include "plan/obstacles.hpp"
#include "plan/pillars.hpp"
#include "plan/stiffness.hpp"
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

// 0.2 mm layers to z 30.4, walls 4 mm apart (x 48 and 52, y 40..60) up
// to z 25: a slot under (50, 50).
layers::LayerStack slotted() {
    return test::stack_of(
        152,
        [](int, layers::Layer& l) {
            test::bead(l, 0, 0, 0.5, 0, gcode::Role::Perimeter);
            if (l.z > 25) return;
            test::bead(l, 48, 40, 48, 60, gcode::Role::Perimeter);
            test::bead(l, 52, 40, 52, 60, gcode::Role::Perimeter);
        },
        {-5, -5, 80, 80});
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

// METHOD's Standing rule: a lean-in whose pillar falls short looks on. The
// point (50, 50) is at z 30; below z 25 two walls 4 mm apart (x 48 and 52,
// bead edges 1.775 mm from x = 50) leave a pillar in the slot between them
// only its plain 2 mm ring and a little: r 1 needs 1 + 0.5 + 0.05 of room,
// so only centres within 0.225 mm of x = 50 fit, capped there at about
// 1.23 mm where a pillar 28 mm tall wants some 2.5 at its foot: 3 E I / h^3
// with a 1.0 mm centre line, E I = 3500 pi 0.45 = 4948, 28^3 = 21952: about
// 0.68 N/mm. The first lean-in found comes from such a pillar, 1 mm off the
// point at 45 degrees (the rings go out from 1 mm, 16 directions from +x),
// 0.64 N/mm as summed; out of the slot a pillar has the room to stand (the
// first: 2 mm off along +x, over the wall's top, stepping off it below),
// and the lean-in from it is taken.
TEST(LeanIn, ALeanInShortOfTheRuleLooksOnForOneThatStands) {
    Settings s;
    const auto st = slotted();
    const plan::Obstacles obs(st, s);
    const auto chain = plan::lean_in(50, 50, 150, st, obs, s);
    ASSERT_TRUE(chain.has_value());
    const plan::Column& lean = chain->back();
    EXPECT_NEAR(lean.x1, 50, 1e-9);
    EXPECT_NEAR(lean.y1, 50, 1e-9);
    EXPECT_GT(std::abs(lean.x0 - 50), 1.5);  // not from the slot
    plan::Scaffold sc;
    sc.columns = *chain;
    const auto chains = plan::pillar_chains(sc);
    ASSERT_EQ(chains.size(), 1u);
    EXPECT_GE(1 / plan::chain_compliance(chains[0], lean.z1, sc, st, s), plan::kGiveMargin * s.min_stiffness);
}

// A lean-in short of the rule as a thin column gets a wide one where it
// clears the model. On the bed only (--buildplate-only), under a point at
// z 20 a shelf (a disc 6.8 mm round the point, z 4 to 6) stops every
// pillar nearer than 8 mm, which steps off its edge: the lean covers 8 mm,
// shifting at most 0.8 (0.2 tan 55 + 0.225) = 0.4085 mm a layer, so over 20
// layers, 4 mm. As a 0.5 mm ring (E I = 3500 pi 0.275^3 0.45 = 102.9) that
// alone gives about 4^3 / 3 / 102.9 = 0.207 mm/N; as a 1 mm ring (E I =
// 2303.2), 0.0093.
TEST(LeanIn, ALeanInShortOfTheRuleLeansAsWideAsAPillarWhereItFits) {
    Settings s;
    s.buildplate_only = true;
    const auto st = test::stack_of(
        102,
        [](int, layers::Layer& l) {
            test::bead(l, 0, 0, 0.5, 0, gcode::Role::Perimeter);
            if (l.z <= 4 || l.z > 6) return;
            for (double y = 43.2; y <= 56.8; y += 0.45) {
                const double h = std::sqrt(std::max(0.0, 6.8 * 6.8 - (y - 50) * (y - 50)));
                test::bead(l, 50 - h, y, 50 + h, y);
            }
        },
        {-5, -5, 80, 80});
    const plan::Obstacles obs(st, s);
    const auto chain = plan::lean_in(50, 50, 100, st, obs, s);
    ASSERT_TRUE(chain.has_value());
    const plan::Column& lean = chain->back();
    EXPECT_GE(std::hypot(lean.x0 - 50, lean.y0 - 50), 7.9);
    EXPECT_NEAR(lean.radius, s.pillar_radius, 1e-9);
    EXPECT_NEAR(plan::column_radius_at(lean, lean.z1, s), s.tip_radius, 1e-9);  // its tip still necks down
    plan::Scaffold sc;
    sc.columns = *chain;
    const auto chains = plan::pillar_chains(sc);
    ASSERT_EQ(chains.size(), 1u);
    // Its pillar, capped where it steps off the shelf's edge, gives 0.483
    // mm/N, the wide lean 0.012 more: 2.02 N/mm, the rule met (not with the
    // planner's tenth more: no lean-in here has that). As a thin column the
    // same lean falls short, about 1 / (0.483 + 0.2) = 1.46.
    EXPECT_GE(1 / plan::chain_compliance(chains[0], lean.z1, sc, st, s), s.min_stiffness);
    sc.columns.back().radius = s.tip_radius;
    EXPECT_LT(1 / plan::chain_compliance(chains[0], lean.z1, sc, st, s), 1.6);
}

// METHOD's Standing rule, for a point no bridge carries: a pillar that the
// model caps all the way down stands short of it where a lean-in from a
// pillar in the open does not, and support_point takes the stiffer. Under a
// point at z 30, walls 4 mm apart up to z 25 (the scene above): the pillar
// straight down the slot is capped by them (its loop at most 4 / 2 - the
// gap - a bead, about 1.1 mm, where the rule wants it 3 mm and more near
// the bed): 0.663 N/mm as measured here. The lean-in's pillar stands beside
// the walls, as wide as the rule asks: 27.2 N/mm. Before, the capped pillar
// was taken.
TEST(LeanIn, APillarTheModelCapsGivesWayToALeanInThatStands) {
    Settings s;
    const auto st = slotted();
    const plan::Obstacles obs(st, s);
    auto stiffness = [&](const std::vector<plan::Column>& chain) {
        plan::Scaffold sc;
        sc.columns = chain;
        const auto chains = plan::pillar_chains(sc);
        EXPECT_EQ(chains.size(), 1u);
        return 1 / plan::chain_compliance(chains[0], chain.back().z1, sc, st, s);
    };
    const auto straight = plan::drop_pillar(50, 50, 150, plan::Top::Contact, st, obs, s, nullptr,
                                            plan::TipPlaces::UnderSheet);
    ASSERT_TRUE(straight.has_value());
    const double k_straight = stiffness(*straight);
    EXPECT_LT(k_straight, plan::kGiveMargin * s.min_stiffness);
    const auto taken = plan::support_point(50, 50, 150, st, obs, s, nullptr);
    ASSERT_TRUE(taken.has_value());
    EXPECT_GT(std::abs(taken->back().x0 - 50), 1.5);  // a lean-in, from beside the walls
    EXPECT_GE(stiffness(*taken), plan::kGiveMargin * s.min_stiffness);
}
