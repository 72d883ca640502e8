// METHOD's Standing rule, on scenes whose numbers are worked out by hand.
//
// The pillar of every test is a single-wall support ring of 2 mm outside
// diameter: a 96-gon of centre-line radius r = 0.775 mm, beads w = 0.45 mm
// wide. Each side is a thin rectangle, length l = 2 r sin(pi/96) = 0.050715,
// its middle d = r cos(pi/96) = 0.774585 from the centre. The ring is
// round, so I is half the trace of the summed second moments:
//   I = 96/2 (l w d^2 + l w^3/12 + w l^3/12)
//     = 48 (0.0136930 + 0.0003851 + 0.0000049) = 0.67598 mm^4
// (pi r^3 w + pi r w^3/12 for a smooth ring; the exact annulus 0.55..1.0
// would be 0.7135, the figure behind METHOD's "about 7.5" and "about 0.12":
// beads as rectangles do not widen outwards, so every k here is 5 % lower).
// E I = 3500 x 0.67598 = 2365.9 N mm^2. A uniform cantilever of height H
// clamped at its base has C = H^3 / (3 E I), and the running sums integrate
// each layer's slab exactly, so a ring from the bed to z = H has
//   k(H) = 3 E I / H^3 = 7097.8 / H^3 N/mm.
#include <gtest/gtest.h>

#include <cmath>

#include "check/printability.hpp"
#include "gcode/reader.hpp"
#include "support/synth.hpp"

using namespace scaffold;
using scaffold::testing::SynthGcode;

namespace {

constexpr double kRingR = 0.775;
constexpr double kThreeEI = 3 * 3500 * 0.67598;  // 7097.8 N mm^2

check::CheckReport run(const SynthGcode& g, double min_k = 2, const std::string* original = nullptr) {
    check::CheckOptions o;
    o.standing.min_stiffness = min_k;
    const auto out = gcode::parse(g.str(), "out.gcode");
    if (!original) return check::check(out, nullptr, o);
    const auto in = gcode::parse(*original, "in.gcode");
    return check::check(out, &in, o);
}

SynthGcode start() {
    SynthGcode g;
    g.width(0.45);
    return g;
}

void ring(SynthGcode& g, double cx, double cy) {
    g.type("Support material");
    g.circle(cx, cy, kRingR, 96);
}

// Rings at the given centres from the bed up to z = top (0.2 mm layers);
// `tie(g, z)` may add more on each layer.
template <class Tie>
SynthGcode rings(std::initializer_list<std::pair<double, double>> at, double top, Tie tie) {
    SynthGcode g = start();
    for (int l = 1; l * 0.2 <= top + 1e-9; ++l) {
        g.layer(0.2 * l);
        for (const auto& [x, y] : at) ring(g, x, y);
        tie(g, 0.2 * l);
    }
    return g;
}

// A support bar 1 mm wide from (x0, y0) to (x1, y1), on the rings' layers.
void bar(SynthGcode& g, double x0, double y0, double x1, double y1) {
    g.type("Support material");
    g.width(1.0);
    g.travel(x0, y0);
    g.extrude(x1, y1);
    g.width(0.45);
}

}  // namespace

TEST(Standing, RingOnTheBed) {
    // 10 mm: k = 7097.8 / 1000 = 7.10 N/mm, it stands (>= 2).
    auto r10 = run(rings({{100, 100}}, 10, [](SynthGcode&, double) {}));
    EXPECT_NEAR(r10.standing.added.weakest_k, 7.098, 0.03) << check::report_text(r10);
    EXPECT_EQ(r10.standing.added.under, 0);
    EXPECT_EQ(r10.standing.added.islands, 50);
    EXPECT_TRUE(r10.ok()) << check::report_text(r10);
    // 40 mm: k = 7097.8 / 64000 = 0.1109 N/mm at the top, 40 mm above the
    // bed; it falls under 2 N/mm at H = (7097.8 / 2)^(1/3) = 15.25 mm, so
    // the 124 layers above 15.2 mm fail.
    auto r40 = run(rings({{100, 100}}, 40, [](SynthGcode&, double) {}));
    const auto& s = r40.standing.added;
    EXPECT_NEAR(s.weakest_k, 0.1109, 0.0005) << check::report_text(r40);
    ASSERT_FALSE(s.weakest.empty());
    EXPECT_NEAR(s.weakest[0].z, 40, 1e-6);
    EXPECT_NEAR(s.weakest[0].height, 40, 1e-6);
    EXPECT_NEAR(s.weakest[0].x, 100, 0.01);
    EXPECT_EQ(s.weakest.size(), 1u);  // one column: listed once
    EXPECT_EQ(s.under, 124);
    // 124 loops of 96 x 0.050715 = 4.8686 mm, at (0.25 x 0.2 + pi 0.2^2 / 4)
    // / (pi 1.75^2 / 4) = 0.033849 mm of filament a mm: 20.43 mm.
    EXPECT_NEAR(s.under_filament_mm, 20.43, 0.05);
    EXPECT_FALSE(r40.ok());
    // --min-stiffness 0 reports the rule without failing.
    auto report_only = run(rings({{100, 100}}, 40, [](SynthGcode&, double) {}), 0);
    EXPECT_TRUE(report_only.ok()) << check::report_text(report_only);
    EXPECT_NEAR(report_only.standing.added.weakest_k, 0.1109, 0.0005);
}

TEST(Standing, SolidBlock) {
    // A 10 x 10 mm block of support 10 mm tall: its section is at least
    // the square's b^4/12 = 833 mm^4 (the beads overlap by a tenth and
    // stand 0.225 mm out: at most (10.45^4/12) / 0.9 = 1103 mm^4), so
    // k = 3 E I / H^3 lies between 8750 and 11600 N/mm.
    SynthGcode g = start();
    for (int l = 1; l <= 50; ++l) {
        g.layer(0.2 * l);
        g.type("Support material");
        g.filled_rect(100, 100, 110, 110);
    }
    auto r = run(g);
    EXPECT_GT(r.standing.added.weakest_k, 8750) << check::report_text(r);
    EXPECT_LT(r.standing.added.weakest_k, 11600);
    EXPECT_EQ(r.standing.added.under, 0);
}

TEST(Standing, PillarOnTheModelAndFloating) {
    // A 10 mm model block, a ring on its top from z 10.2 to 20.0: a base on
    // the model, 10 mm of ring above it, k = 7.10 N/mm as on the bed. A
    // second ring starts at the same height 10 mm beside the block, over
    // nothing: floating, k = 0.
    SynthGcode g = start();
    for (int l = 1; l <= 100; ++l) {
        g.layer(0.2 * l);
        if (l <= 50) {
            g.type("External perimeter");
            g.filled_rect(100, 100, 110, 110);
        } else {
            ring(g, 105, 105);
            ring(g, 125, 105);
        }
    }
    auto r = run(g);
    const auto& s = r.standing.added;
    EXPECT_EQ(s.floating, 1) << check::report_text(r);
    EXPECT_EQ(s.islands, 100);
    EXPECT_EQ(s.under, 50);  // every layer of the floating ring
    ASSERT_GE(s.weakest.size(), 2u);
    EXPECT_TRUE(s.weakest[0].floating);
    EXPECT_NEAR(s.weakest[0].x, 125, 0.01);
    EXPECT_NEAR(s.weakest[1].x, 105, 0.01);
    EXPECT_NEAR(s.weakest[1].k, 7.098, 0.03);
    EXPECT_NEAR(s.weakest[1].height, 10, 1e-6);
    EXPECT_EQ(s.weakest_k, 0);
    EXPECT_NEAR(s.weakest_standing_k, 7.098, 0.03);  // the ring on the model
    EXPECT_FALSE(r.ok());
}

TEST(Standing, RingInsideACupFloats) {
    // The same ring inside a 20 x 20 mm cup (walls only): the hole under it
    // is far larger than 4 mm^2, so it does not stand on the model.
    SynthGcode g = start();
    for (int l = 1; l <= 60; ++l) {
        g.layer(0.2 * l);
        if (l <= 50) {
            g.type("External perimeter");
            g.rect_outline(95, 95, 115, 115);
        } else {
            ring(g, 105, 105);
        }
    }
    auto r = run(g);
    EXPECT_EQ(r.standing.added.floating, 1) << check::report_text(r);
    EXPECT_EQ(r.standing.added.under, 10);
}

TEST(Standing, TwoPillarsTiedByOneBarGainNothing) {
    // Two 40 mm rings 10 mm apart tied by a bar at z 20.0 and 20.2: two
    // columns along one line are no brace, the tops stand as one ring
    // alone (0.1109 N/mm; the bar layers' section is far stiffer, and two
    // layers of it change the sum by under 1 %).
    auto r = run(rings({{100, 100}, {110, 100}}, 40, [](SynthGcode& g, double z) {
        if (z > 19.9 && z < 20.3) bar(g, 100 + kRingR, 100, 110 - kRingR, 100);
    }));
    const auto& s = r.standing.added;
    EXPECT_EQ(s.braces, 0) << check::report_text(r);
    EXPECT_NEAR(s.weakest_k, 0.1109, 0.0011);
}

TEST(Standing, ThreePillarsTiedInATriangleBrace) {
    // Rings at (100, 100), (120, 100) and (100, 120), 40 mm tall, tied by
    // bars along the triangle's sides at z 20.0 and 20.2. At the node each
    // column (the bed to 19.8) has, loaded at z 20,
    //   C = (20^3 - 0.2^3) / (3 E I) = 7999.99 / 7097.8 = 1.1271, k = 0.8872,
    // the node k_b = 3 x 0.8872 = 2.6617 N/mm; above it each ring from 20.2
    // to 40 adds 19.8^3 / (3 E I) = 1.0936 (the node's two layers, a section
    // of hundreds of mm^4, add under 0.001), so at the top
    //   k = 1 / (1 / 2.6617 + 1.0936) = 0.681 N/mm
    // (METHOD's 1 / (1 / (3 x 0.94) + 1 / 0.94) = 0.70 with the annulus's I).
    auto r = run(rings({{100, 100}, {120, 100}, {100, 120}}, 40, [](SynthGcode& g, double z) {
        if (z < 19.9 || z > 20.3) return;
        bar(g, 100 + kRingR, 100, 120 - kRingR, 100);
        bar(g, 120 - 0.55, 100 + 0.55, 100 + 0.55, 120 - 0.55);
        bar(g, 100, 120 - kRingR, 100, 100 + kRingR);
    }));
    const auto& s = r.standing.added;
    EXPECT_EQ(s.braces, 1) << check::report_text(r);
    EXPECT_NEAR(s.weakest_k, 0.681, 0.005) << check::report_text(r);
    ASSERT_FALSE(s.weakest.empty());
    EXPECT_NEAR(s.weakest[0].z, 40, 1e-6);
    EXPECT_NEAR(s.weakest[0].height, 20.2, 1e-6);  // above the node's own slab, 19.8 to 20.0
}

TEST(Standing, ATieWithATwigJoinsTheColumnsAboveIt) {
    // Two rings at (100, 100) and (120, 100) and a thin one at (100, 120)
    // (centre line 0.375 mm: I about (0.375 / 0.775)^3 = 0.113 of a ring's),
    // 40 mm tall, tied in a triangle at 10 and at 20 mm. At 10 the thin one
    // stands about 0.113 x 7.10 = 0.80 N/mm against 7.10: a twig, no node,
    // and the bars join the three into one island. At 20, followed down the
    // stiffest path below 10, it would stand 1 / ((20^3 - 10^3) / 7097.8 +
    // (10^3 / 3) / (0.113 x 2365.9)) = 0.45 N/mm against 0.887, over a
    // quarter: counted as a node were the columns distinct there. They met
    // at 10 (METHOD: columns that meet lower down are one column), so no
    // brace. The weakest is the thin ring's top, following the stiffest path
    // down from the tie at 20: its 48-gon of beads has I = 24 (l w d^2 +
    // l w^3 / 12 + w l^3 / 12) with l = 0.75 sin(pi/48) = 0.049052, d =
    // 0.375 cos(pi/48) = 0.374197: 0.083226 mm^4, E I = 291.29. From 40
    // down to 20.2, 19.8^3 / (3 x 291.29) = 8.882 mm/N; the two layers of
    // the tie, hundreds of mm^4, nothing; a ring from 19.8 to the bed,
    // (40^3 - 20.2^3) / 3 / 2365.9 = 7.856 (the stiffest path at 10 is a
    // ring's too), less its two layers in the tie at 10 (lever about 30:
    // 2 x 0.2 x 30^2 / 2365.9 = 0.152): k = 1 / 16.586 = 0.0603 N/mm.
    auto r = run(rings({{100, 100}, {120, 100}}, 40, [](SynthGcode& g, double z) {
        g.type("Support material");
        g.circle(100, 120, 0.375, 48);
        const bool tie = (z > 9.9 && z < 10.3) || (z > 19.9 && z < 20.3);
        if (!tie) return;
        bar(g, 100 + kRingR, 100, 120 - kRingR, 100);
        bar(g, 120 - 0.55, 100 + 0.55, 100 + 0.3, 120 - 0.3);
        bar(g, 100, 120 - 0.375, 100, 100 + kRingR);
    }));
    EXPECT_EQ(r.standing.added.braces, 0) << check::report_text(r);
    EXPECT_NEAR(r.standing.added.weakest_k, 0.0603, 0.0003) << check::report_text(r);
    ASSERT_FALSE(r.standing.added.weakest.empty());
    EXPECT_NEAR(r.standing.added.weakest[0].x, 100, 0.5);
    EXPECT_NEAR(r.standing.added.weakest[0].y, 120, 0.5);
    EXPECT_NEAR(r.standing.added.weakest[0].height, 40, 1e-6);
}

TEST(Standing, ThreePillarsInARowAreNoBrace) {
    // The same three rings on one line, tied at 20 mm: they can all bend
    // across the line together; no brace, each top as a ring alone.
    auto r = run(rings({{100, 100}, {110, 100}, {120, 100}}, 40, [](SynthGcode& g, double z) {
        if (z > 19.9 && z < 20.3) bar(g, 100 + kRingR, 100, 120 - kRingR, 100);
    }));
    EXPECT_EQ(r.standing.added.braces, 0) << check::report_text(r);
    EXPECT_NEAR(r.standing.added.weakest_k, 0.1109, 0.0011);
}

TEST(Standing, TravelOverFreshSupport) {
    // A ring at (110, 100) printed first on each of 5 layers, then the
    // model at (130, 100). Travels from the ring away to (110, 112), to
    // (100, 100) and through the ring to the model cross it on every layer;
    // lifted 0.2 mm they do not; leaving the ring without coming back is
    // no crossing.
    auto scene = [](int how) {
        SynthGcode g = start();
        for (int l = 1; l <= 5; ++l) {
            g.layer(0.2 * l);
            g.type("External perimeter");
            g.filled_rect(95, 95, 99, 105);  // the model's first piece, left of the ring
            ring(g, 110, 100);
            g.type("External perimeter");
            if (how == 0) {
                g.travel(110, 112);  // leaves the ring, then comes back over it
                g.travel(100, 100);
                g.travel(130, 100);
            } else if (how == 1) {
                g.raw("G1 Z" + std::to_string(0.2 * l + 0.2) + " F7800");  // lifted 0.2 mm
                g.travel(100, 100);
                g.travel(130, 100);
                g.raw("G1 Z" + std::to_string(0.2 * l) + " F7800");
            } else {
                g.travel(110, 112);  // from the ring straight away: leaves, never comes back
                g.travel(130, 112);
            }
            g.extrude(131, 100);
            g.extrude(131, 101);
        }
        return run(g, 0);
    };
    auto crossed = scene(0);
    EXPECT_EQ(crossed.standing.added.travels, 5) << check::report_text(crossed);
    ASSERT_FALSE(crossed.standing.added.first_travels.empty());
    EXPECT_NEAR(crossed.standing.added.first_travels[0].z, 0.2, 1e-6);
    // It first comes within 0.2 mm of the ring's outer edge (x 110 - 1.0).
    EXPECT_NEAR(crossed.standing.added.first_travels[0].x, 108.8, 0.15);
    EXPECT_EQ(crossed.standing.added.weak_travels, 0);  // a 1 mm ring: k = 7097.8 N/mm
    // METHOD: no travel may cross fresh support: a failure, however stiff.
    EXPECT_FALSE(crossed.ok());
    ASSERT_FALSE(crossed.failures.empty());
    EXPECT_NE(crossed.failures.back().find("5 travels cross fresh support"), std::string::npos) << crossed.failures.back();
    const auto lifted = scene(1), away = scene(2);
    EXPECT_EQ(lifted.standing.added.travels, 0);
    EXPECT_EQ(away.standing.added.travels, 0);
    EXPECT_TRUE(lifted.ok()) << check::report_text(lifted);
    EXPECT_TRUE(away.ok()) << check::report_text(away);
}

TEST(Standing, TheOriginalsSupportIsReportedApart) {
    // The 40 mm ring as the original's own support (the file against
    // itself): judged the same way, reported apart, no failure.
    SynthGcode g = rings({{100, 100}}, 40, [](SynthGcode&, double) {});
    const std::string text = g.str();
    auto r = run(g, 2, &text);
    EXPECT_TRUE(r.ok()) << check::report_text(r);
    EXPECT_EQ(r.standing.added.islands, 0);
    EXPECT_NEAR(r.standing.original.weakest_k, 0.1109, 0.0005);
    EXPECT_EQ(r.standing.original.under, 124);
}

TEST(Standing, PathSkipsSupportOfAnotherHeightBeside) {
    // Slicers print support on layer heights of their own: a ring on the
    // 0.2 mm grid to z 10, and 10 mm away a small block printed only at
    // z 5.1 (on the bed's layers below it, 0.1 mm layers from 4.9). The
    // nearest lower layer holding support under the ring at 5.2 is 5.0,
    // not 5.1: the ring stands as before, k = 7.10 N/mm at its top.
    SynthGcode g = start();
    for (int l = 1; l <= 50; ++l) {
        g.layer(0.2 * l);
        ring(g, 100, 100);
        if (l == 25) {
            g.type("Support material");
            g.filled_rect(110, 98, 112, 102);
            g.layer(5.1);
            g.type("Support material");
            g.filled_rect(110, 98, 112, 102);
        }
        if (l <= 24) {
            g.type("Support material");
            g.filled_rect(110, 98, 112, 102);
        }
    }
    auto r = run(g);
    EXPECT_EQ(r.standing.added.floating, 0) << check::report_text(r);
    EXPECT_NEAR(r.standing.added.weakest_k, 7.098, 0.03) << check::report_text(r);
}

TEST(Standing, TravelOverWeakSupport) {
    // The 40 mm ring (0.1109 N/mm at its top): on its last layer a travel
    // leaves it, then crosses it from (100, 105) to (100, 95) before a model
    // bead: one travel over fresh support, and over an island under 2 N/mm.
    auto r = run(rings({{100, 100}}, 40, [](SynthGcode& g, double z) {
        if (z < 39.9) return;
        g.travel(100, 105);
        g.travel(100, 95);
        g.type("External perimeter");
        g.extrude(101, 95);
    }));
    EXPECT_EQ(r.standing.added.travels, 1) << check::report_text(r);
    EXPECT_EQ(r.standing.added.weak_travels, 1);
    ASSERT_EQ(r.standing.added.first_travels.size(), 1u);
    EXPECT_NEAR(r.standing.added.first_travels[0].y, 101.2, 0.15);  // 0.2 mm beyond the wall's outer edge at 101.0
}

TEST(Standing, TravelClearanceIsMeasuredExactly) {
    // A model bead at y 90, a support bead 0.4 mm wide along y = y0 (its
    // edge at y0 + 0.2), a model bead at y 105 (a new chain), then a travel
    // down to a point `gap` above the support's edge and back up: it comes
    // within METHOD's 0.2 mm and leaves again at 0.19 and 0.195 mm, not at
    // 0.205 or 0.21 mm, wherever the bead lies against a raster's 0.1 mm
    // cells (the raster this replaced missed some and invented others).
    auto scene = [](double y0, double gap) {
        SynthGcode g = start();
        g.layer(0.2);
        g.type("External perimeter");
        g.travel(100, 90);  // fixes the bounds, and any raster's cells with them
        g.extrude(110, 90);
        g.type("Support material");
        g.width(0.4);
        g.travel(100, y0);
        g.extrude(110, y0);
        g.type("External perimeter");
        g.travel(100, 105);
        g.extrude(110, 105);
        g.travel(104, 103);
        g.travel(105, y0 + 0.2 + gap);
        g.travel(106, 103);
        g.extrude(107, 103);
        return run(g, 0);
    };
    for (double y0 : {100.0, 100.02, 100.04, 100.06, 100.08}) {
        EXPECT_EQ(scene(y0, 0.19).standing.added.travels, 1) << y0;
        EXPECT_EQ(scene(y0, 0.195).standing.added.travels, 1) << y0;
        EXPECT_EQ(scene(y0, 0.205).standing.added.travels, 0) << y0;
        EXPECT_EQ(scene(y0, 0.21).standing.added.travels, 0) << y0;
    }
}
