#include <gtest/gtest.h>

#include "plan/cavities.hpp"
#include "plan/obstacles.hpp"
#include "plan/planner.hpp"
#include "support/stacks.hpp"

using namespace scaffold;
using scaffold::test::bead;

namespace {

// A cabin: walls around x 0..20, y 0..12 up to z 26, windows in both long
// walls (x 7..13, z 14..20), and, if asked, a roof on top (z 26.4).
layers::LayerStack cabin(bool roof) {
    return test::stack_of(
        roof ? 132 : 130,
        [](int i, layers::Layer& l) {
            const double z = 0.2 * (i + 1);
            if (z > 26 + 1e-9) {
                for (double x = 0.2; x < 20; x += 0.45) bead(l, x, 0, x, 12, gcode::Role::SolidInfill);
                return;
            }
            const bool window = z > 14 + 1e-9 && z <= 20 + 1e-9;
            for (double y : {0.0, 12.0}) {
                if (window) {
                    bead(l, 0, y, 7, y, gcode::Role::Perimeter);
                    bead(l, 13, y, 20, y, gcode::Role::Perimeter);
                } else {
                    bead(l, 0, y, 20, y, gcode::Role::Perimeter);
                }
            }
            bead(l, 0, 0, 0, 12, gcode::Role::Perimeter);
            bead(l, 20, 0, 20, 12, gcode::Role::Perimeter);
        },
        {-5, -5, 30, 20});
}

// The cabin in a hull: a ring of wall around it (x -10..30, y -8..20) up to
// z 10, open on top, and a roof 4 mm wider than the cabin all round.
layers::LayerStack cabin_in_a_hull() {
    layers::LayerStack st = cabin(true);
    for (layers::Layer& l : st.layers) {
        if (l.z <= 10 + 1e-9) {
            for (double y : {-8.0, 20.0}) bead(l, -10, y, 30, y, gcode::Role::Perimeter);
            for (double x : {-10.0, 30.0}) bead(l, x, -8, x, 20, gcode::Role::Perimeter);
        }
        if (l.z > 26 + 1e-9)
            for (double x = -3.8; x < 24; x += 0.45) bead(l, x, -4, x, 16, gcode::Role::SolidInfill);
    }
    st.bounds = {-15, -12, 35, 25};
    return st;
}

// A solid block (x 0..20, y 0..12, to z 10) and a slab over it (z 17..20),
// each a ring with sparse infill (a 3 mm grid: holes the ring encloses)
// between solid bottom and top layers; air between them.
layers::LayerStack block_and_slab() {
    return test::stack_of(
        100,
        [](int i, layers::Layer& l) {
            const double z = 0.2 * (i + 1);
            const bool block = z <= 10 + 1e-9, slab = z > 17 + 1e-9;
            if (!block && !slab) {
                bead(l, 40, 0, 41, 0, gcode::Role::Perimeter);  // something far away keeps the layer
                return;
            }
            const bool solid = (block && (z <= 1 + 1e-9 || z > 9 + 1e-9)) || (slab && (z <= 18 + 1e-9 || z > 19.4 + 1e-9));
            for (double y : {0.0, 12.0}) bead(l, 0, y, 20, y, gcode::Role::Perimeter);
            for (double x : {0.0, 20.0}) bead(l, x, 0, x, 12, gcode::Role::Perimeter);
            if (solid) {
                for (double y = 0.45; y < 12; y += 0.45) bead(l, 0, y, 20, y, gcode::Role::SolidInfill);
            } else {
                for (double x = 3; x < 20; x += 3) bead(l, x, 0, x, 12, gcode::Role::InternalInfill);
                for (double y = 3; y < 12; y += 3) bead(l, 0, y, 20, y, gcode::Role::InternalInfill);
            }
        },
        {-5, -5, 45, 20});
}

// The cavities of a stack (they keep nothing of the obstacles they are made from).
plan::Cavities cavities_of(const layers::LayerStack& st) {
    const plan::Obstacles obs(st, Settings{});
    return plan::Cavities(st, obs);
}

}  // namespace

// Under an overhang, above a part's top: the holes of either part's sparse
// infill lie behind its solid skin, no hollow the bar is in.
TEST(Cavities, InfillHolesBehindASkinAreNoHollow) {
    const plan::Cavities c = cavities_of(block_and_slab());
    EXPECT_FALSE(c.trapped(10, 6, 13, plan::Cavities::kReach));
    EXPECT_FALSE(c.bar_trapped(1, 6, 19, 6, 13));
}

TEST(Cavities, InsideARoofedHollowIsTrapped) {
    const plan::Cavities roofed = cavities_of(cabin(true)), open = cavities_of(cabin(false));
    EXPECT_TRUE(roofed.trapped(10, 6, 17, plan::Cavities::kReach));
    EXPECT_FALSE(open.trapped(10, 6, 17, plan::Cavities::kReach));   // a cup: lifted out
    EXPECT_FALSE(roofed.trapped(10, 0, 17, plan::Cavities::kReach)); // in the wall's plane (the window)
    EXPECT_FALSE(roofed.trapped(25, 6, 17, plan::Cavities::kReach)); // beside the cabin
    EXPECT_FALSE(roofed.trapped(10, 6, 27, plan::Cavities::kReach)); // above the roof
    EXPECT_TRUE(roofed.bar_trapped(10, 0, 10, 12, 17));
    EXPECT_FALSE(open.bar_trapped(10, 0, 10, 12, 17));
    EXPECT_FALSE(roofed.bar_trapped(-3, 0, -3, 12, 17));
}

// Two points under each window's lintel: without a roof the best bridge
// runs across the cabin from window to window; under a roof it would be
// trapped inside, and each window's points get pillars on its sill.
TEST(Cavities, NoBridgeAcrossARoofedCabin) {
    Settings s;
    overhang::SupportPoints pts;
    for (double y : {0.0, 12.0})
        for (double x : {9.0, 11.0}) pts.points.push_back({x, y, 20.0, 100});
    for (bool roof : {false, true}) {
        const layers::LayerStack st = cabin(roof);
        plan::Obstacles obs(st, s);
        const plan::Scaffold sc = plan::plan_scaffold(pts, st, obs, s);
        EXPECT_TRUE(sc.dropped_points.empty());
        if (!roof) {
            ASSERT_EQ(sc.bridges.size(), 1u);
            EXPECT_LT(std::min(sc.bridges[0].y0, sc.bridges[0].y1), 2);
            EXPECT_GT(std::max(sc.bridges[0].y0, sc.bridges[0].y1), 10);
        } else {
            EXPECT_TRUE(sc.bridges.empty());
        }
    }
}

// Beside the cabin under its roof's lip, inside the hull's ring lower down:
// the lip is met first going up, the way out sideways is open.
TEST(Cavities, UnderALipBesideTheCabinIsOpen) {
    const plan::Cavities c = cavities_of(cabin_in_a_hull());
    EXPECT_TRUE(c.trapped(10, 6, 17, plan::Cavities::kReach));
    EXPECT_FALSE(c.trapped(10, -2.5, 17, plan::Cavities::kReach));
    EXPECT_FALSE(c.bar_trapped(2, -2.5, 18, -2.5, 17));
}


// The layers mapped on 1, 2 or 3 threads give the same map: every answer
// over the cabin in its hull, at every height, the same.
TEST(Cavities, TheSameMapOnAnyNumberOfThreads) {
    const layers::LayerStack st = cabin_in_a_hull();
    const plan::Obstacles obs(st, Settings{});
    const plan::Cavities one(st, obs, 1), two(st, obs, 2), three(st, obs, 3);
    int trapped = 0;
    for (double z = 0.1; z < 40; z += 0.5)
        for (double y = -4; y < 19; y += 0.5)
            for (double x = -4; x < 44; x += 0.5) {
                const bool a = one.trapped(x, y, z, plan::Cavities::kReach);
                trapped += a;
                ASSERT_EQ(two.trapped(x, y, z, plan::Cavities::kReach), a) << x << " " << y << " " << z;
                ASSERT_EQ(three.trapped(x, y, z, plan::Cavities::kReach), a) << x << " " << y << " " << z;
            }
    EXPECT_GT(trapped, 0);  // the cabin's hollow is in it
}
