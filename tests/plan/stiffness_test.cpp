// The planner's column sizing for METHOD's Standing rule, against numbers
// worked out by hand (E = 3500 N/mm^2, beads 0.45 mm wide).
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "plan/stiffness.hpp"

using namespace scaffold;

namespace {
constexpr double kE = 3500, kW = 0.45;
}

// A 2 mm ring: centre line 1 - 0.225 = 0.775 mm; I = pi 0.775^3 0.45 =
// pi x 0.465484 x 0.45 = pi x 0.209468 = 0.658063 mm^4.
TEST(Stiffness, RingInertia) {
    EXPECT_NEAR(plan::ring_inertia(1.0, kW), 0.658063, 1e-6);
    // Loops narrower than 0.75 of a bead keep loop_shape's floor (w / 4).
    EXPECT_NEAR(plan::ring_inertia(0.3, kW), std::numbers::pi * std::pow(0.1125, 3) * kW, 1e-12);
}

// METHOD's scale: a single-wall ring of 2 mm stands at 2 N/mm up to about
// 15 mm, one of 5 mm up to about 44 mm. C = h^3 / (3 E I):
// 15^3 / (3 x 3500 x 0.658063) = 3375 / 6909.66 = 0.48845 mm/N, 2.047 N/mm;
// 5 mm: I = pi 2.275^3 0.45 = 16.6447, 44^3 / (3 x 3500 x 16.6447) =
// 85184 / 174769 = 0.48741 mm/N, 2.052 N/mm.
TEST(Stiffness, StraightRingsAsMethodSays) {
    EXPECT_NEAR(1 / plan::ring_compliance(1.0, 0, 15, 0, 15, kW, kE), 2.047, 0.001);
    EXPECT_NEAR(1 / plan::ring_compliance(2.5, 0, 44, 0, 44, kW, kE), 2.052, 0.001);
    // A part of the column: from 5 to 15 mm under a top at 15 the lever
    // arms run 0..10: 1000 / 6909.68 = 0.14472 mm/N.
    EXPECT_NEAR(plan::ring_compliance(1.0, 0, 15, 5, 15, kW, kE), 0.14472, 1e-5);
}

// The cone's closed form against the integral summed in 10^5 slices.
TEST(Stiffness, TaperedRingIsTheIntegral) {
    const double r = 1.0, taper = 0.05, top = 40;
    double sum = 0;
    const int n = 100000;
    for (int i = 0; i < n; ++i) {
        const double h = (i + 0.5) * top / n, rc = r - kW / 2 + taper * h;
        sum += h * h / (kE * std::numbers::pi * rc * rc * rc * kW) * top / n;
    }
    EXPECT_NEAR(plan::ring_compliance(r, taper, top, 0, top, kW, kE), sum, 1e-6 * sum);
    // Widening pays: the straight 40 mm ring gives 64000 / 6909.68 = 9.26 mm/N
    // (0.108 N/mm); 0.05 mm per mm, 2 mm wider at the base, gives 0.62 mm/N.
    EXPECT_NEAR(plan::ring_compliance(r, 0, top, 0, top, kW, kE), 9.2624, 1e-3);
    EXPECT_LT(sum, 0.65);
}

TEST(Stiffness, LeastTaperForTheTarget) {
    // 10 mm stands straight: 1000 / 6909.68 = 0.1447 mm/N < 1 / 2.5.
    EXPECT_EQ(plan::taper_for(1.0, 10, 2.5, 0, kW, kE), 0.0);
    // 30 mm needs a taper, and the one found gives the target exactly.
    const double t = plan::taper_for(1.0, 30, 2.5, 0, kW, kE);
    EXPECT_GT(t, 0.04);
    EXPECT_LT(t, 0.05);
    EXPECT_NEAR(plan::ring_compliance(1.0, t, 30, 0, 30, kW, kE), 0.4, 1e-6);
    // With 0.2 mm/N standing on it (a connector), the column may give 0.2.
    const double t2 = plan::taper_for(1.0, 30, 2.5, 0.2, kW, kE);
    EXPECT_GT(t2, t);
    EXPECT_NEAR(plan::ring_compliance(1.0, t2, 30, 0, 30, kW, kE), 0.2, 1e-6);
    // Out of reach: the widest taper allowed.
    EXPECT_EQ(plan::taper_for(1.0, 30, 2.5, 0.4, kW, kE), plan::kMaxTaper);
    EXPECT_EQ(plan::taper_for(1.0, 30, 0, 0, kW, kE), 0.0);  // the rule off
}
