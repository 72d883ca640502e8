#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <optional>

#include "plan/pillars.hpp"
#include "support/stacks.hpp"
#include "toolpath/bar_check.hpp"
#include "toolpath/support_paths.hpp"

using namespace scaffold;

namespace {

plan::Column pillar(double x, double y, double top) {
    plan::Column c;
    c.x0 = c.x1 = x;
    c.y0 = c.y1 = y;
    c.z0 = 0;
    c.z1 = top;
    return c;
}

const toolpath::LayerPaths* at_layer(const toolpath::SupportPaths& p, int layer) {
    for (const auto& lp : p.layers)
        if (lp.layer == layer) return &lp;
    return nullptr;
}

}  // namespace

TEST(SupportPaths, CrossingLoopsArePrintedAsTheOutlineOfTheirUnion) {
    Settings s;
    const layers::LayerStack st = test::empty_stack(6);
    plan::Scaffold sc;
    // Two pillars 1.2 mm apart (loops of outer radius 1): their centre lines
    // cross. A third far away stays a loop of its own.
    sc.columns = {pillar(20, 20, 5), pillar(21.2, 20, 5), pillar(40, 40, 5)};
    const auto paths = toolpath::make_paths(sc, st, s);
    const auto* lp = at_layer(paths, 10);  // z = 2.2: above the feet, below the tips
    ASSERT_NE(lp, nullptr);
    ASSERT_EQ(lp->paths.size(), 2u);
    const double rc = plan::loop_shape(s.pillar_radius, s.support_width).centre_radius;
    int merged = 0;
    for (const auto& p : lp->paths) {
        ASSERT_GE(p.points.size(), 4u);
        EXPECT_NEAR(p.points.front().x, p.points.back().x, 1e-9);  // closed
        EXPECT_NEAR(p.points.front().y, p.points.back().y, 1e-9);
        if (p.points.front().x > 30) continue;
        ++merged;
        // Every vertex lies on one loop's polygon and not inside the other
        // loop: no bead is printed across the other pillar.
        for (const auto& v : p.points) {
            const double d0 = std::hypot(v.x - 20, v.y - 20), d1 = std::hypot(v.x - 21.2, v.y - 20);
            EXPECT_GE(std::max(d0, d1), rc * std::cos(3.15 / 8) - 1e-6);
            EXPECT_LE(std::min(d0, d1), rc + 1e-6);
            EXPECT_GE(std::min(d0, d1), rc * std::cos(3.15 / 8) - 1e-6) << v.x << ", " << v.y;
        }
        // It spans both pillars: as far left as the first loop, as far right
        // as the second.
        double x0 = 1e9, x1 = -1e9, l0 = 1e9, l1 = -1e9;
        for (const auto& v : p.points) x0 = std::min(x0, v.x), x1 = std::max(x1, v.x);
        for (const auto& v : toolpath::loop(20, 20, s.pillar_radius, s.support_width)) l0 = std::min(l0, v.x);
        for (const auto& v : toolpath::loop(21.2, 20, s.pillar_radius, s.support_width)) l1 = std::max(l1, v.x);
        EXPECT_NEAR(x0, l0, 1e-9);
        EXPECT_NEAR(x1, l1, 1e-9);
    }
    EXPECT_EQ(merged, 1);
}

TEST(SupportPaths, ALoopInsideARingIsNotSwallowedByTheRingsUnion) {
    // A connector inside a wide column's ring crosses a loop that crosses
    // the ring: the three were one union, the inner loop filled in, and on
    // the layer the ring moved off it the inner loop stood on nothing. The
    // ring merges with the loop crossing it; the inner loop stays a loop.
    Settings s;
    const layers::LayerStack st = test::empty_stack(6);
    plan::Scaffold sc;
    plan::Column wide = pillar(20, 20, 5), inner = pillar(21, 20, 5), beside = pillar(21.9, 20, 5);
    wide.radius = 2.0;
    wide.taper = 0.01;  // widened for the Standing rule: a single wall
    wide.hold_z = 5;
    inner.radius = beside.radius = 0.75;
    sc.columns = {wide, inner, beside};
    const auto paths = toolpath::make_paths(sc, st, s);
    const auto* lp = at_layer(paths, 10);
    ASSERT_NE(lp, nullptr);
    const double rc = plan::loop_shape(0.75, s.support_width).centre_radius;
    int inner_loops = 0;
    for (const auto& p : lp->paths) {
        bool on_inner = true;
        for (const auto& v : p.points) on_inner = on_inner && std::abs(std::hypot(v.x - 21, v.y - 20) - rc) < 1e-6;
        inner_loops += on_inner;
    }
    EXPECT_EQ(inner_loops, 1);
    EXPECT_EQ(lp->paths.size(), 2u);  // the inner loop, the outline of the ring and the loop beside
}

TEST(SupportPaths, ACrowdOfCrossingLoopsGivesClosedPaths) {
    // Thirty pillars crowded into 3 x 3 mm (near-coincident loops, loops
    // meeting at a point, chains): every path stays a closed ring and
    // every pillar's centre lies inside some printed outline's box.
    Settings s;
    const layers::LayerStack st = test::empty_stack(6);
    plan::Scaffold sc;
    unsigned seed = 7;
    auto next = [&seed] { seed = seed * 1103515245u + 12345u; return (seed >> 8) % 1000 / 1000.0; };
    for (int i = 0; i < 30; ++i) {
        plan::Column c = pillar(20 + 3 * next(), 20 + 3 * next(), 5);
        c.radius = 0.5 + 0.8 * next();
        sc.columns.push_back(c);
    }
    sc.columns.push_back(pillar(30, 30, 5));
    sc.columns.push_back(pillar(30.000001, 30, 5));  // a retrace, left out
    const auto paths = toolpath::make_paths(sc, st, s);
    const auto* lp = at_layer(paths, 10);
    ASSERT_NE(lp, nullptr);
    for (const auto& p : lp->paths) {
        ASSERT_GE(p.points.size(), 4u);
        EXPECT_NEAR(p.points.front().x, p.points.back().x, 1e-9);
        EXPECT_NEAR(p.points.front().y, p.points.back().y, 1e-9);
    }
    for (const auto& c : sc.columns) {
        bool inside = false;
        for (const auto& p : lp->paths) {
            double x0 = 1e9, x1 = -1e9, y0 = 1e9, y1 = -1e9;
            for (const auto& v : p.points) x0 = std::min(x0, v.x), x1 = std::max(x1, v.x), y0 = std::min(y0, v.y), y1 = std::max(y1, v.y);
            inside = inside || (c.x0 > x0 && c.x0 < x1 && c.y0 > y0 && c.y0 < y1);
        }
        EXPECT_TRUE(inside) << c.x0 << ", " << c.y0;
    }
    EXPECT_LT(lp->paths.size(), 20u);  // the crowd merged
}

TEST(SupportPaths, ASpurOnlyFromARoundLoop) {
    // A bar at z 3 passing 1.3 mm beside a lone pillar at (30, 20) and
    // beside two crossing pillars at (20, 20) and (21.2, 20), printed as
    // the outline of their union. The lone loop gets a spur under the bar
    // on the layer beneath it (z 3.0); the outline gets none: a spur from
    // the circle about its vertices' mean would stand off it, on nothing.
    Settings s;
    const layers::LayerStack st = test::empty_stack(6);
    plan::Scaffold sc;
    sc.columns = {pillar(20, 20, 5), pillar(21.2, 20, 5), pillar(30, 20, 5)};
    sc.bridges.push_back({10, 21.3, 35, 21.3, 3.0, {}, 0, 0});
    const auto paths = toolpath::make_paths(sc, st, s);
    const auto* lp = at_layer(paths, 14);  // z = 3.0
    ASSERT_NE(lp, nullptr);
    int spurs = 0;
    for (const auto& p : lp->paths) {
        if (p.points.size() != 2 || p.kind != toolpath::PathKind::Pillar) continue;
        ++spurs;
        EXPECT_NEAR(p.points.front().x, 30, 1e-6);  // straight out from the lone loop
        EXPECT_GT(p.points.back().y, p.points.front().y);
    }
    EXPECT_EQ(spurs, 1);
}

// The spur of ASpurOnlyFromARoundLoop, with another pillar's loop beneath
// its far end (a column up to z 2.8 at (31.2, 22)): the spur would be held
// at both ends and not between them, a run rule (b) holds only where it
// leaves each end across the footprint's edge, and this one meets the
// other loop along its edge. It is left out; without that pillar it stays.
TEST(SupportPaths, NoSpurWhereItWouldNotBeHeld) {
    Settings s;
    const layers::LayerStack st = test::empty_stack(6);
    auto spurs_under_bar = [&](const std::vector<plan::Column>& columns, bool& candidate_held) {
        plan::Scaffold sc;
        sc.columns = columns;
        sc.bridges.push_back({10, 21.3, 35, 21.3, 3.0, {}, 0, 0});
        const auto paths = toolpath::make_paths(sc, st, s);
        std::vector<toolpath::LayerPaths> below;  // printed before z 3.0
        for (const auto& lp : paths.layers)
            if (lp.layer < 14) below.push_back(lp);
        // The spur add_spurs makes: from the loop's centre line to 0.3 mm past
        // the bar's far line.
        const double rc = plan::loop_shape(s.pillar_radius, s.support_width).centre_radius;
        candidate_held = toolpath::segment_held({30, 20 + rc}, {30, 21.3 + s.support_width / 2 + 0.3}, 14, below, st, s);
        int n = 0;
        const auto* lp = at_layer(paths, 14);
        if (lp)
            for (const auto& p : lp->paths) n += p.points.size() == 2 && p.kind == toolpath::PathKind::Pillar;
        return n;
    };
    bool held = false;
    EXPECT_EQ(spurs_under_bar({pillar(30, 20, 5)}, held), 1);
    EXPECT_TRUE(held);
    EXPECT_EQ(spurs_under_bar({pillar(30, 20, 5), pillar(31.2, 22, 2.8)}, held), 0);
    EXPECT_FALSE(held);
}

TEST(SupportPaths, AHoleNarrowerThanABeadIsNotPrinted) {
    // Three crossing loops around a point each just misses: their union's
    // centre lines leave a hole a few hundredths of a mm across there,
    // which the beads around it cover. Only the union's outline is printed.
    Settings s;
    const layers::LayerStack st = test::empty_stack(6);
    const double rc = plan::loop_shape(s.pillar_radius, s.support_width).centre_radius, d = rc + 0.02;
    plan::Scaffold sc;
    for (int k = 0; k < 3; ++k) {
        const double a = 2 * std::numbers::pi * k / 3 + 0.3;
        sc.columns.push_back(pillar(20 + d * std::cos(a), 20 + d * std::sin(a), 5));
    }
    const auto paths = toolpath::make_paths(sc, st, s);
    const auto* lp = at_layer(paths, 10);
    ASSERT_NE(lp, nullptr);
    EXPECT_EQ(lp->paths.size(), 1u);
}

// Six loops in a ring, each crossing its neighbours (centres 1.4 mm from
// the middle, 1.4 mm apart; centre-line radius 0.775): their union has a
// hole about 0.6 mm across. Standing on the bed, the hole's outline is
// printed on every layer (it stands on the one below). Where the six close
// in from a tight cluster below (centres 0.5 mm from the middle: no hole,
// the union's outline 1.275 mm out), the hole's outline would stand 0.65
// mm inside that outline, over the hollow of the union below, more than the
// 0.41 mm a loop may reach out: it is not printed, here nor above.
TEST(SupportPaths, AHoleOutlineOnlyWhereTheLayerBelowHoldsIt) {
    Settings s;
    const layers::LayerStack st = test::empty_stack(6);
    auto ring_of = [](double d, double z0, double z1) {
        std::vector<plan::Column> out;
        for (int k = 0; k < 6; ++k) {
            const double a = 2 * std::numbers::pi * k / 6;
            plan::Column c = pillar(20 + d * std::cos(a), 20 + d * std::sin(a), z1);
            c.z0 = z0;
            if (z0 > 0) c.base = plan::Base::Column;
            out.push_back(c);
        }
        return out;
    };
    plan::Scaffold from_bed;
    from_bed.columns = ring_of(1.4, 0, 5);
    const auto bed_paths = toolpath::make_paths(from_bed, st, s);
    for (int l : {10, 12})
        ASSERT_EQ(at_layer(bed_paths, l)->paths.size(), 2u) << "layer " << l;  // outline and hole
    plan::Scaffold closing;
    closing.columns = ring_of(0.5, 0, 2.0);
    for (const plan::Column& c : ring_of(1.4, 2.0, 5)) closing.columns.push_back(c);
    const auto paths = toolpath::make_paths(closing, st, s);
    for (int l : {10, 12})
        ASSERT_EQ(at_layer(paths, l)->paths.size(), 1u) << "layer " << l;  // the outline only
}

// A column on a raft whose top is at z 0.8, its first layer `gap` above:
// 0.2 mm layers (the print's nominal height) after the gap.
namespace {

toolpath::SupportPaths on_raft(double gap, plan::Base base = plan::Base::Model) {
    Settings s;
    s.layer_height = 0.2;
    std::vector<double> zs = {0.3, 0.55, 0.8};
    for (int k = 0; k < 6; ++k) zs.push_back(0.8 + gap + 0.2 * k);
    const layers::LayerStack st = test::stack_at(zs, [](int, layers::Layer&) {}, {0, 0, 60, 60});
    plan::Scaffold sc;
    plan::Column c = pillar(30, 30, zs.back());
    c.base = base;
    c.z0 = base == plan::Base::Bed ? 0 : 0.8;
    sc.columns = {c};
    return toolpath::make_paths(sc, st, s);
}

}  // namespace

// Cura's raft: 0.55 mm from the raft's top to the model's first layer, more
// than 1.5 layers of 0.2: one bond halfway, z 1.075, 0.275 mm high, its
// loop the column's first, listed just before that layer's own entry.
TEST(SupportPaths, AColumnOverAWideGapIsBondedToWhatItStandsOn) {
    const auto paths = on_raft(0.55);
    ASSERT_GE(paths.layers.size(), 2u);
    const auto& bond = paths.layers[0];
    ASSERT_TRUE(bond.bond());
    EXPECT_EQ(bond.layer, 3);
    EXPECT_NEAR(bond.bond_z, 1.075, 1e-9);
    EXPECT_NEAR(bond.bond_height, 0.275, 1e-9);
    EXPECT_FALSE(paths.layers[1].bond());
    EXPECT_EQ(paths.layers[1].layer, 3);
    ASSERT_EQ(bond.paths.size(), paths.layers[1].paths.size());
    EXPECT_EQ(bond.paths[0].points.size(), paths.layers[1].paths[0].points.size());
    EXPECT_DOUBLE_EQ(bond.paths[0].points[0].x, paths.layers[1].paths[0].points[0].x);
    EXPECT_NEAR(toolpath::printed_z(bond, layers::LayerStack{}), 1.075, 1e-9);
    for (std::size_t i = 2; i < paths.layers.size(); ++i) EXPECT_FALSE(paths.layers[i].bond());
}

// A 0.7 mm gap, over three layers of 0.2: no bond. A bond would become the
// layer right under the model's first, which rests on the raft only as the
// layer right under it (support counts as "layer L-1" within three layers).
TEST(SupportPaths, NoBondOverAGapOfMoreThanThreeLayers) {
    for (const auto& lp : on_raft(0.7).layers) EXPECT_FALSE(lp.bond());
    int bonds = 0;
    for (const auto& lp : on_raft(0.6).layers) bonds += lp.bond();
    EXPECT_EQ(bonds, 1);
}

// 0.3 mm (1.5 layers, PrusaSlicer's raft contact) needs none.
TEST(SupportPaths, NoBondWithinOneAndAHalfLayers) {
    for (const auto& lp : on_raft(0.3).layers) EXPECT_FALSE(lp.bond());
}

// A column on the bed beside the raft is printed on the raft's layers and
// crosses the same gap to the model's first layer: bonded from its loop at
// 0.8. Never on its own first layer, 0.3 above the bed.
TEST(SupportPaths, AColumnBesideTheRaftIsBondedAcrossTheSameGap) {
    const auto paths = on_raft(0.55, plan::Base::Bed);
    int bonds = 0;
    for (const auto& lp : paths.layers)
        if (lp.bond()) {
            ++bonds;
            EXPECT_EQ(lp.layer, 3);
            EXPECT_NEAR(lp.bond_z, 1.075, 1e-9);
        }
    EXPECT_EQ(bonds, 1);
    ASSERT_FALSE(paths.layers.empty());
    EXPECT_FALSE(paths.layers.front().bond());
    EXPECT_EQ(paths.layers.front().layer, 0);
}

// Cura prints the model's second layer over a raft a little lower than its
// first (1.13 after 1.15). The bond goes under the lower, halfway from the
// raft's 0.65 to 1.13, before the first, for both columns: one reaching
// 1.53, a tip reaching only 1.13. Each still prints its loop on the layers
// it reaches, as the model does.
TEST(SupportPaths, ABondGoesUnderTheLowerOfTwoLayersPrintedOutOfOrder) {
    Settings s;
    s.layer_height = 0.2;
    const layers::LayerStack st = test::stack_at(
        {0.3, 0.45, 0.55, 0.65, 1.15, 1.13, 1.33, 1.53},
        [](int i, layers::Layer& l) {
            if (i == 5) {  // 1.13 lies on the raft's 0.65
                l.below = 3;
                l.height = 1.13 - 0.65;
                l.beneath = {3};
            }
        },
        {0, 0, 60, 60});
    plan::Scaffold sc;
    plan::Column tall = pillar(30, 30, 1.53), tip = pillar(40, 30, 1.13);
    tall.base = tip.base = plan::Base::Model;
    tall.z0 = tip.z0 = 0.65;
    sc.columns = {tall, tip};
    const auto paths = toolpath::make_paths(sc, st, s);
    ASSERT_EQ(paths.layers.size(), 5u);  // the bond, 1.15, 1.13, 1.33, 1.53
    const auto& bond = paths.layers[0];
    ASSERT_TRUE(bond.bond());
    EXPECT_EQ(bond.layer, 4);
    EXPECT_NEAR(bond.bond_z, 0.89, 1e-9);
    EXPECT_NEAR(bond.bond_height, 0.24, 1e-9);
    EXPECT_EQ(bond.paths.size(), 2u);
    EXPECT_EQ(paths.layers[1].layer, 4);
    EXPECT_EQ(paths.layers[1].paths.size(), 1u);  // the tip does not reach 1.15
    EXPECT_EQ(paths.layers[2].layer, 5);
    EXPECT_EQ(paths.layers[2].paths.size(), 2u);
    for (std::size_t i = 1; i < paths.layers.size(); ++i) EXPECT_FALSE(paths.layers[i].bond());
}

// Two columns whose loops are nearly one (centres 0.1 mm apart, radii 1.0
// and 1.3: 0.4 mm apart at most, within a 0.2 mm layer's reach): one loop
// is printed, and it is the wider, the stiffer column's, whichever comes
// first in the plan.
TEST(SupportPaths, OfTwoLoopsNearlyOneTheWiderIsPrinted) {
    Settings s;
    const layers::LayerStack st = test::empty_stack(6);
    plan::Column narrow = pillar(30, 30, 5), wide = pillar(30.1, 30, 5);
    wide.radius = 1.3;
    plan::Scaffold sc;
    sc.columns = {narrow, wide};
    const auto paths = toolpath::make_paths(sc, st, s);
    const auto* lp = at_layer(paths, 10);  // z 2.2: above the feet, below the tips
    ASSERT_NE(lp, nullptr);
    ASSERT_EQ(lp->paths.size(), 1u);
    double far = 0;
    for (const auto& p : lp->paths.front().points) far = std::max(far, std::hypot(p.x - 30.1, p.y - 30));
    EXPECT_NEAR(far, plan::loop_shape(1.3, s.support_width).centre_radius, 1e-9);
}

namespace {

// A wide column (outer radius 1.6) up to `wide_top`, ending as `wide_end`,
// and a narrow one (0.6) standing on it from `narrow_from` to z 4, both
// at (30, 30), on 0.2 mm layers (layer l's top at 0.2 (l + 1)).
plan::Scaffold narrow_on_wide(double wide_top, plan::Top wide_end, double narrow_from) {
    plan::Column wide = pillar(30, 30, wide_top), narrow = pillar(30, 30, 4);
    wide.radius = 1.6;
    wide.top = wide_end;
    narrow.radius = 0.6;
    narrow.z0 = narrow_from;
    narrow.base = plan::Base::Column;
    plan::Scaffold sc;
    sc.columns = {wide, narrow};
    return sc;
}

// A layer's bridged paths (the spokes: no bars in these scenes).
std::vector<const toolpath::Path*> bridges_at(const toolpath::SupportPaths& paths, int layer) {
    std::vector<const toolpath::Path*> out;
    if (const auto* lp = at_layer(paths, layer))
        for (const auto& p : lp->paths)
            if (p.kind == toolpath::PathKind::Bridge) out.push_back(&p);
    return out;
}

// Each spoke runs from the narrow loop's centre line out to the wide one's.
void expect_spokes(const std::vector<const toolpath::Path*>& spokes, double rc_in, double rc_out) {
    EXPECT_EQ(spokes.size(), 4u);
    for (const toolpath::Path* p : spokes) {
        ASSERT_EQ(p->points.size(), 2u);
        EXPECT_TRUE(p->bridge);
        EXPECT_NEAR(std::hypot(p->points[0].x - 30, p->points[0].y - 30), rc_in, 1e-9);
        EXPECT_NEAR(std::hypot(p->points[1].x - 30, p->points[1].y - 30), rc_out, 1e-9);
    }
}

}  // namespace

// A narrow column standing on a wide one (a branch on a trunk widened
// after it was placed) would start with a loop over the trunk's hollow: its
// first loop meets nothing on the layer below, so METHOD's Standing rule
// finds it no way down (a floating island). While the trunk's loop
// encloses it, the trunk carries it and its loops are left out (the test
// below); its first loop, at its top's last three layers (z 3.6, layer
// 17), gets four bridged spokes out to the trunk's loop, making the two
// loops one island. By hand: the trunk's loop (outer radius 1.6, 0.45 mm
// beads) has its centre line at 1.375, the branch's (0.6) at 0.375; the
// beads' edges are 1.375 - 0.375 - 0.45 = 0.55 mm apart, so each spoke
// runs 1.0 mm, from 0.375 to 1.375 off the centre. On the next layer the
// branch's own loop holds it: no spokes.
// A thin pillar standing inside a wide one's ring, beads apart: its loops
// there would be an island of their own, standing on their own thin way
// down (METHOD's Standing rule), inside a stiffer ring. They are left out
// while the ring encloses this layer's loop and the next; from its top's
// last three layers (z 4.6, layer 22) the thin loop is printed, its first
// over the ring's hollow, spoked out to the ring. By hand: the ring's
// centre line at 1.3 - 0.225 = 1.075, the thin loop's at 0.275 around the
// same centre, so its bead's outer edge is at 0.5 and the ring's inner
// edge at 0.85: 0.35 mm of air, more than the 0.1 mm cell the validator
// counts as touching.
TEST(SupportPaths, ALoopInsideAnotherIsLeftOutWhileTheWiderEnclosesIt) {
    Settings s;
    const layers::LayerStack st = test::empty_stack(6);
    plan::Scaffold sc;
    plan::Column wide = pillar(20, 20, 5), thin = pillar(20, 20, 5);
    wide.radius = 1.3;
    thin.radius = 0.5;
    sc.columns = {wide, thin};
    const auto paths = toolpath::make_paths(sc, st, s);
    for (int l : {10, 21}) {
        const auto* lp = at_layer(paths, l);
        ASSERT_NE(lp, nullptr);
        EXPECT_EQ(lp->paths.size(), 1u) << "layer " << l;
    }
    const auto* first = at_layer(paths, 22);
    ASSERT_NE(first, nullptr);
    EXPECT_EQ(first->paths.size(), 6u);  // the ring, the thin loop, four spokes
    const auto spokes = bridges_at(paths, 22);
    EXPECT_EQ(spokes.size(), 4u);
    for (const toolpath::Path* p : spokes) {
        ASSERT_EQ(p->points.size(), 2u);
        EXPECT_NEAR(std::hypot(p->points[0].x - 20, p->points[0].y - 20), 0.275, 1e-9);
        EXPECT_NEAR(std::hypot(p->points[1].x - 20, p->points[1].y - 20), 1.075, 1e-9);
    }
    const auto* next = at_layer(paths, 23);
    ASSERT_NE(next, nullptr);
    EXPECT_EQ(next->paths.size(), 2u);
    // Touching the ring (0.6 mm off: its bead reaches 1.1, over the ring's
    // inner edge) it is no island of its own: printed on every layer.
    sc.columns[1].x0 = sc.columns[1].x1 = 20.6;
    const auto touching = toolpath::make_paths(sc, st, s);
    const auto* lp = at_layer(touching, 10);
    ASSERT_NE(lp, nullptr);
    EXPECT_EQ(lp->paths.size(), 2u);
}

// A column that narrows in one layer (a wide piece ends, a narrow one
// stands on it: a tip's neck) starts the narrow loop over the wide piece's
// hollow with no loop around it on its own layer: its spokes reach out over
// the wide loop of the layer below and rest on it. By hand as above: the
// narrow loop's centre line at 0.375, the wide one's (below) at 1.375.
TEST(SupportPaths, ALoopNarrowerInOneLayerIsSpokedOverTheLoopBelow) {
    Settings s;
    const layers::LayerStack st = test::empty_stack(6);
    // The wide piece ends at full width (no tip's neck) at layer 14's top;
    // the narrow one's first loop is on layer 15 (z 3.2).
    const auto paths = toolpath::make_paths(narrow_on_wide(3.0, plan::Top::Column, 3.0), st, s);
    expect_spokes(bridges_at(paths, 15), 0.375, 1.375);
    for (const auto& lp : paths.layers)
        if (lp.layer != 15) {
            EXPECT_TRUE(bridges_at(paths, lp.layer).empty()) << "layer " << lp.layer;
        }
}

namespace {

// What the pipeline prints for a plate of copies whose supports all stand
// apart: one copy's paths placed at every offset; nothing where two meet.
std::optional<toolpath::SupportPaths> copied_paths(const toolpath::SupportPaths& one,
                                                   const std::vector<toolpath::Point>& offsets, double apart,
                                                   const toolpath::TravelClear& clear) {
    if (toolpath::copy_clusters(one, offsets, apart).size() != offsets.size()) return std::nullopt;
    std::vector<toolpath::PlacedPaths> parts;
    for (const toolpath::Point& o : offsets) parts.push_back({&one, o});
    return toolpath::placed_paths(parts, clear);
}

// Each layer's paths as text, in a fixed order (order aside).
std::vector<std::string> layer_shapes(const toolpath::SupportPaths& p) {
    std::vector<std::string> out;
    for (const auto& lp : p.layers)
        for (const auto& path : lp.paths) {
            std::string t = std::to_string(lp.layer) + " " + std::to_string(static_cast<int>(path.kind)) + ":";
            for (const auto& q : path.points) t += std::to_string(std::lround(q.x * 1e4)) + "," + std::to_string(std::lround(q.y * 1e4)) + " ";
            out.push_back(std::move(t));
        }
    std::sort(out.begin(), out.end());
    return out;
}

}  // namespace

// A plate's exact copies print one copy's paths moved, on each layer in
// the order make_paths gives a layer (nearest first over all copies): the
// paths make_paths gives the copies' plans together. Every travel from a
// copy to another is asked of `clear`.
TEST(SupportPaths, CopiesStandingApartPrintOneCopysPathsMoved) {
    Settings s;
    const layers::LayerStack st = test::empty_stack(6);
    plan::Scaffold one;
    one.columns = {pillar(20, 20, 5), pillar(30, 20, 5)};
    plan::Bridge bar;
    bar.x0 = 20, bar.y0 = 20, bar.x1 = 30, bar.y1 = 20, bar.z = 5;
    one.bridges = {bar};
    const toolpath::SupportPaths paths = toolpath::make_paths(one, st, s);
    ASSERT_FALSE(paths.layers.empty());
    // Two copies 25 mm apart along y: 22.55 mm between their beads.
    const std::vector<toolpath::Point> offsets{{0, 0}, {0, 25}};
    int asked = 0;  // travels from one copy to the other asked
    const auto copied = copied_paths(paths, offsets, 1.0, [&](int, const toolpath::Point& a, const toolpath::Point& b, double) {
        asked += std::abs(a.y - b.y) > 15;
        return false;
    });
    ASSERT_TRUE(copied.has_value());
    ASSERT_EQ(copied->layers.size(), paths.layers.size());
    int changes = 0;  // travels from one copy to the other
    for (std::size_t i = 0; i < paths.layers.size(); ++i) {
        const auto& a = paths.layers[i];
        const auto& m = copied->layers[i];
        EXPECT_EQ(m.layer, a.layer);
        ASSERT_EQ(m.paths.size(), 2 * a.paths.size());
        // Printed in make_paths' order over both copies' paths.
        std::vector<toolpath::Path> both;
        for (double dy : {0.0, 25.0})
            for (toolpath::Path p : a.paths) {
                for (auto& pt : p.points) pt.y += dy;
                both.push_back(p);
            }
        const std::vector<std::size_t> order = toolpath::printing_order(both);
        for (std::size_t k = 0; k < order.size(); ++k) {
            EXPECT_EQ(m.paths[k].points.front().x, both[order[k]].points.front().x);
            EXPECT_EQ(m.paths[k].points.front().y, both[order[k]].points.front().y);
            const bool other = k > 0 && (order[k] < a.paths.size()) != (order[k - 1] < a.paths.size());
            changes += other;
            if (other) {
                EXPECT_TRUE(m.paths[k].retract);  // clear said no
            }
        }
    }
    EXPECT_EQ(asked, changes);
    EXPECT_GE(changes, static_cast<int>(paths.layers.size()));  // at least once a layer: every layer has paths
    // The same paths, order aside, as the two copies' plans made together.
    plan::Scaffold both = one;
    for (plan::Column c : one.columns) {
        c.y0 += 25, c.y1 += 25;
        both.columns.push_back(c);
    }
    bar.y0 += 25, bar.y1 += 25;
    both.bridges.push_back(bar);
    EXPECT_EQ(layer_shapes(*copied), layer_shapes(toolpath::make_paths(both, st, s)));
    // A travel between copies that clear lets go unretracted.
    const auto free = copied_paths(paths, offsets, 1.0, [](int, const auto&, const auto&, double) { return true; });
    ASSERT_TRUE(free.has_value());
    int freed = 0;
    for (const auto& lp : free->layers)
        for (std::size_t k = 1; k < lp.paths.size(); ++k)
            if ((lp.paths[k].points.front().y > 30) != (lp.paths[k - 1].points.front().y > 30)) {
                EXPECT_FALSE(lp.paths[k].retract);
                ++freed;
            }
    EXPECT_EQ(freed, changes);
}

// Copies whose supports come within `apart` of each other are no copies
// for this: their loops may merge, retrace or hold each other's spurs. They
// are clustered, and each cluster made together.
TEST(SupportPaths, CopiesWhoseSupportsMeetAreNotMoved) {
    Settings s;
    const layers::LayerStack st = test::empty_stack(6);
    plan::Scaffold one;
    one.columns = {pillar(20, 20, 5)};
    const toolpath::SupportPaths paths = toolpath::make_paths(one, st, s);
    // Loops 2 mm wide: 2.5 mm apart leaves 0.5 mm between the beads.
    EXPECT_FALSE(copied_paths(paths, {{0, 0}, {2.5, 0}}, 1.0, {}).has_value());
    EXPECT_FALSE(copied_paths(paths, {{0, 0}, {30, 30}, {31.5, 32}}, 1.0, {}).has_value());
    // 5 mm apart leaves 3 mm: moved.
    EXPECT_TRUE(copied_paths(paths, {{0, 0}, {5, 0}}, 1.0, {}).has_value());
    // Clustered, joined through each other: at x 0, 30 (alone), 2.5 (meets
    // the first) and 5 (meets the third only); 3.5 mm apart, all meet.
    using Clusters = std::vector<std::vector<std::size_t>>;
    EXPECT_EQ(toolpath::copy_clusters(paths, {{0, 0}, {30, 0}, {2.5, 0}, {5, 0}}, 1.0), (Clusters{{0, 2, 3}, {1}}));
    EXPECT_EQ(toolpath::copy_clusters(paths, {{0, 0}, {5, 0}, {10, 0}}, 1.0), (Clusters{{0}, {1}, {2}}));
    EXPECT_EQ(toolpath::copy_clusters(paths, {{0, 0}, {5, 0}, {10, 0}}, 3.5), (Clusters{{0, 1, 2}}));
}

// The paths' volume, length x width x height: on a 0.2 mm layer a 3-4-5
// line 0.5 wide is 5 x 0.5 x 0.2 = 0.5 mm^3 and a second segment back to
// (0, 4) adds 3 x 0.5 x 0.2 = 0.3; a bond 0.1 mm high, 10 mm of 0.4 wide,
// is 0.4 whatever its layer's height. 1.2 mm^3.
TEST(SupportPaths, VolumeIsLengthTimesWidthTimesHeight) {
    const layers::LayerStack st = test::empty_stack(2);
    ASSERT_NEAR(st.layers[3].height, 0.2, 1e-9);
    toolpath::SupportPaths paths;
    toolpath::LayerPaths plain;
    plain.layer = 3;
    plain.paths.push_back({{{0, 0}, {3, 4}, {0, 4}}, 0.5});
    paths.layers.push_back(plain);
    toolpath::LayerPaths bond;
    bond.layer = 5;
    bond.bond_z = 0.95;
    bond.bond_height = 0.1;
    bond.paths.push_back({{{10, 10}, {20, 10}}, 0.4});
    paths.layers.push_back(bond);
    EXPECT_NEAR(toolpath::paths_volume(paths, st), 1.2, 1e-12);
    toolpath::move_paths(paths, 7, -3);
    EXPECT_NEAR(toolpath::paths_volume(paths, st), 1.2, 1e-12);
}

// The printing order: nearest first from the last path's end, ties to the
// lower index, on places as written. Many paths (a plate's layer) are
// searched in a grid: the same order as comparing all, on a lattice of
// exact ties (3 mm apart, every start twice) and on scattered starts.
TEST(SupportPaths, PrintingOrderIsNearestFirstWithTiesToTheLowerIndex) {
    auto brute = [](const std::vector<toolpath::Path>& paths) {
        auto w = [](double v) { return std::round(v * 1000) / 1000; };
        std::vector<std::size_t> out;
        std::vector<bool> used(paths.size(), false);
        toolpath::Point at = paths[0].points.front();
        for (std::size_t n = 0; n < paths.size(); ++n) {
            std::size_t best = 0;
            double best_d = 1e300;
            for (std::size_t i = 0; i < paths.size(); ++i) {
                if (used[i]) continue;
                const double dx = w(paths[i].points.front().x) - w(at.x), dy = w(paths[i].points.front().y) - w(at.y);
                if (dx * dx + dy * dy < best_d) best_d = dx * dx + dy * dy, best = i;
            }
            used[best] = true;
            at = paths[best].points.back();
            out.push_back(best);
        }
        return out;
    };
    std::vector<toolpath::Path> lattice, scattered;
    for (int copy = 0; copy < 2; ++copy)
        for (int i = 0; i < 12; ++i)
            for (int j = 0; j < 10; ++j)
                lattice.push_back({{{3.0 * i, 3.0 * j}, {3.0 * i + 1, 3.0 * j}}, 0.45});
    std::uint32_t seed = 12345;
    auto next = [&] { return (seed = seed * 1664525u + 1013904223u) / 4294967296.0; };
    for (int i = 0; i < 300; ++i) {
        const double x = 200 * next(), y = 120 * next();
        scattered.push_back({{{x, y}, {x + 4 * next() - 2, y + 4 * next() - 2}}, 0.45});
    }
    for (const auto* paths : {&lattice, &scattered}) {
        const std::vector<std::size_t> order = toolpath::printing_order(*paths);
        EXPECT_EQ(order, brute(*paths));
        EXPECT_EQ(order.front(), 0u);
    }
    // The nearest: from (0, 0) -> (1, 0), the start at (0, 0) again (the
    // other copy's, index 120) before the one at (3, 0).
    EXPECT_EQ(toolpath::printing_order(lattice)[1], 120u);
}

// Parts of a plate made once and moved: two clusters of two copies each,
// the second cluster's paths those of the first moved by its offset; the
// same paths, order aside, as make_paths of all four.
TEST(SupportPaths, ClustersMadeOnceAndMovedAreThePlatesPaths) {
    Settings s;
    const layers::LayerStack st = test::empty_stack(6);
    auto pair_at = [](double x) {
        plan::Scaffold p;
        p.columns = {pillar(x, 20, 5), pillar(x + 2.5, 20, 5)};
        return p;
    };
    const toolpath::SupportPaths first = toolpath::make_paths(pair_at(20), st, s);
    const auto placed = toolpath::placed_paths({{&first, {0, 0}}, {&first, {30, 0}}}, {});
    plan::Scaffold all = pair_at(20);
    for (const plan::Column& c : pair_at(50).columns) all.columns.push_back(c);
    EXPECT_EQ(layer_shapes(placed), layer_shapes(toolpath::make_paths(all, st, s)));
    for (const auto& lp : placed.layers)
        for (const auto& p : lp.paths) EXPECT_TRUE(p.retract);  // no clear: every travel retracts
}
