// The rule-(b) piece walk the detector, the planner's bar check and the
// validator share (layers/crossing): hand-made beads beneath, one straight
// piece sampled and walked, for each case of issue 23. Layers 0.2 mm, beads
// 0.45 mm: rule (a)'s reach is 0.2 tan 55 + 0.05 = 0.336 mm.
// (tests/overhang/bridge_rule_test.cpp runs the same cases through the
// detector and the validator as G-code.)
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <vector>

#include "layers/crossing.hpp"
#include "layers/raster.hpp"

using namespace scaffold;

namespace {

constexpr double kWidth = 0.45, kReach = 0.2 * 1.4281480067421144 + 0.05, kCell = 0.1;

// The layer beneath: its beads (the footprint) and rule (a)'s reach of them.
struct Beneath {
    layers::BitGrid footprint{90, 90, 150, 130, kCell}, held{90, 90, 150, 130, kCell};
    void bead(double x0, double y0, double x1, double y1) {
        footprint.draw_segment(x0, y0, x1, y1, kWidth);
        held.draw_segment(x0, y0, x1, y1, kWidth + 2 * kReach);
    }
    // A filled rectangle of beads along x, centres on its edges.
    void rect(double x0, double y0, double x1, double y1) {
        for (double y = y0; y < y1 + 1e-9; y += kWidth) bead(x0, y, x1, y);
        bead(x0, y1, x1, y1);
    }
    // One straight piece x0,y0 -> x1,y1 walked; ends_held: the path turns
    // there into a piece held within a dangling end (the callers' corners).
    bool piece_held(double x0, double y0, double x1, double y1, double max_span, bool ends_held = false) const {
        layers::Segment sg;
        sg.x0 = static_cast<float>(x0), sg.y0 = static_cast<float>(y0);
        sg.x1 = static_cast<float>(x1), sg.y1 = static_cast<float>(y1);
        std::vector<layers::PieceSample> p;
        layers::sample_segment(sg, 0, held, kCell, p);
        if (ends_held) p.front().held = p.back().held = true;
        layers::hold_runs(p, footprint, max_span);
        for (const auto& q : p)
            if (!q.held) return false;
        return true;
    }
};

// Two towers x 100-105 and (105 + gap)-(110 + gap), y 100 to 100 + depth.
Beneath towers(double gap, double depth = 10) {
    Beneath b;
    b.rect(100, 100, 105, 100 + depth);
    b.rect(105 + gap, 100, 110 + gap, 100 + depth);
    return b;
}

}  // namespace

TEST(Crossing, SamplesAtMostACellApartWithArcLength) {
    Beneath b = towers(6);
    layers::Segment sg;
    sg.x0 = 101, sg.y0 = 105, sg.x1 = 102, sg.y1 = 105;
    std::vector<layers::PieceSample> p;
    layers::sample_segment(sg, 7, b.held, kCell, p);
    sg.x0 = 102, sg.x1 = 102.25f;
    layers::sample_segment(sg, 8, b.held, kCell, p);
    ASSERT_EQ(p.size(), 11u + 3u);  // the second segment starts at the first's end
    EXPECT_NEAR(p.back().s, 1.25, 1e-6);
    EXPECT_EQ(p.front().seg, 7u);
    EXPECT_EQ(p.back().seg, 8u);
    for (const auto& q : p) EXPECT_TRUE(q.held);
}

// A skin line crossing a 6 mm slot at 90 degrees: held (10 mm --max-bridge).
TEST(Crossing, SkinLineAcrossASlotIsHeld) { EXPECT_TRUE(towers(6).piece_held(101, 105, 115, 105, 10)); }

// The same kind of line at 20 degrees to the slot's edges, with length no
// object (a 30 mm limit): it leaves each held end along the edge.
TEST(Crossing, SkinLineAt20DegreesToTheEdgeIsNotHeld) {
    // From x 104 on one tower to x 112 on the other, 20 degrees off the y
    // axis (the edges): 17.5 mm over the slot, towers 28 mm deep to hold it.
    const Beneath b = towers(6, 28);
    const double a = 20 * std::numbers::pi / 180;
    EXPECT_FALSE(b.piece_held(104, 101.5, 112, 101.5 + 8 / std::tan(a), 30));
    // The 90-degree line across the same slot is held.
    EXPECT_TRUE(b.piece_held(101, 105, 115, 105, 30));
}

// A wall 0.8 mm outside the wall beneath (y 99.2 over a rectangle whose
// bottom beads run at y 100) for 5 mm between corners held by the pieces
// beyond them: a wall along the edge, no bridge. The walk takes no role, so
// the same wall marked "Overhang perimeter" (a wall too, the same 10 mm
// limit) is judged alike; within a bridge limit of 30 mm it is not held either.
TEST(Crossing, WallOutsideTheWallBelowIsNotHeld) {
    Beneath b;
    b.rect(100, 100, 105, 103);
    EXPECT_FALSE(b.piece_held(100, 99.2, 105, 99.2, 10, true));
    EXPECT_FALSE(b.piece_held(100, 99.2, 105, 99.2, 30, true));
    // Its corners alone: dangling ends of 0.8 mm, held.
    EXPECT_TRUE(b.piece_held(100, 103, 100, 99.2, 10));
}

// Bridge infill may span 30 mm: across a 25 mm gap it is held; an unmarked
// bead (10 mm) is not.
TEST(Crossing, BridgeInfillAcross25mmIsHeld) {
    EXPECT_TRUE(towers(25).piece_held(101, 105, 134, 105, 30));
    EXPECT_FALSE(towers(25).piece_held(101, 105, 134, 105, 10));
}

// The top of a hawse hole: the wall's straight piece across the 4 mm hole
// between two short slanted corner moves (held within a dangling end) leaves
// the towers' edges at 90 degrees: held.
TEST(Crossing, HawseHoleTopIsHeld) { EXPECT_TRUE(towers(4).piece_held(104.9, 105.3, 108.7, 105.3, 10, true)); }

// A dangling end: held up to 1 mm from its last held sample, not beyond.
TEST(Crossing, DanglingEndUpTo1mm) {
    Beneath b = towers(6);
    EXPECT_TRUE(b.piece_held(104, 105, 105.8, 105, 10));   // 0.8 mm past the footprint's reach
    EXPECT_FALSE(b.piece_held(104, 105, 107.5, 105, 10));  // 2 mm past it
}
