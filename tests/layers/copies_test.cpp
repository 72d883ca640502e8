// Exact copies on a plate (layers/copies): recognised from the beads alone,
// only where every bead of each copy is the first's moved; and the plate as
// the first copy sees it from every copy's place.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "layers/copies.hpp"
#include "support/stacks.hpp"

using namespace scaffold;
using test::bead;

namespace {

// A 10 x 10 mm box of walls with a diagonal infill bead, its lower left
// corner at (x, y); `shift` moves the infill bead's far end (a copy that
// differs), `reversed` prints it the other way round (the same bead).
void box(layers::Layer& l, double x, double y, double shift = 0, bool reversed = false) {
    bead(l, x, y, x + 10, y, gcode::Role::ExternalPerimeter);
    bead(l, x + 10, y, x + 10, y + 10, gcode::Role::ExternalPerimeter);
    bead(l, x + 10, y + 10, x, y + 10, gcode::Role::ExternalPerimeter);
    bead(l, x, y + 10, x, y, gcode::Role::ExternalPerimeter);
    if (reversed) bead(l, x + 9 + shift, y + 9, x + 1, y + 1, gcode::Role::InternalInfill);
    else bead(l, x + 1, y + 1, x + 9 + shift, y + 9, gcode::Role::InternalInfill);
}

layers::LayerStack plate(const std::vector<double>& xs, double shift_last = 0, bool reverse_last = false) {
    return test::stack_of(
        5,
        [&](int, layers::Layer& l) {
            for (std::size_t k = 0; k < xs.size(); ++k)
                box(l, xs[k], 20.25, k + 1 == xs.size() ? shift_last : 0, reverse_last && k + 1 == xs.size());
        },
        {0, 0, 200, 60});
}

}  // namespace

TEST(Copies, ThreeBoxesAreCopiesOfTheFirstWithTheirOffsets) {
    const auto c = layers::find_copies(plate({70.125, 10, 40.5}));
    ASSERT_TRUE(c.has_value());
    ASSERT_EQ(c->offsets.size(), 3u);
    // The first is the leftmost of the lowest; the others by x.
    EXPECT_DOUBLE_EQ(c->offsets[0].dx, 0);
    EXPECT_NEAR(c->offsets[1].dx, 30.5, 1e-4);
    EXPECT_NEAR(c->offsets[2].dx, 60.125, 1e-4);
    EXPECT_NEAR(c->offsets[1].dy, 0, 1e-4);
    // Its box holds the beads' widths: x 10 - 0.225 to 20 + 0.225.
    EXPECT_NEAR(c->prototype.min_x, 9.775, 1e-4);
    EXPECT_NEAR(c->prototype.max_x, 20.225, 1e-4);
    EXPECT_NEAR(c->prototype.min_y, 20.025, 1e-4);
    std::size_t beads = 0;
    for (const auto& layer : c->beads) beads += layer.size();
    EXPECT_EQ(beads, 5u * 5u);
}

TEST(Copies, ABeadPrintedTheOtherWayRoundIsTheSameBead) {
    EXPECT_TRUE(layers::find_copies(plate({10, 40}, 0, true)).has_value());
}

TEST(Copies, ABeadTenMicronsOffIsNoCopy) {
    EXPECT_TRUE(layers::find_copies(plate({10, 40}, 0.002)).has_value());  // within the file's rounding
    EXPECT_FALSE(layers::find_copies(plate({10, 40}, 0.01)).has_value());
}

TEST(Copies, ADifferentRoleIsNoCopy) {
    layers::LayerStack st = plate({10, 40});
    st.layers[2].segments.back().role = gcode::Role::SolidInfill;
    EXPECT_FALSE(layers::find_copies(st).has_value());
}

TEST(Copies, OneObjectOrCopiesTouchingAreNoPlateOfCopies) {
    std::string why;
    EXPECT_FALSE(layers::find_copies(plate({10}), &why).has_value());
    EXPECT_EQ(why, "one object");
    // 0.15 mm between the boxes' beads: one object.
    EXPECT_FALSE(layers::find_copies(plate({10, 20.6})).has_value());
    // 1.55 mm: two.
    EXPECT_TRUE(layers::find_copies(plate({10, 22})).has_value());
}

// A slicer nests copies by their outlines: their boxes may overlap. An L
// and the same L moved into its corner.
TEST(Copies, CopiesWhoseBoxesOverlapAreCopies) {
    auto ell = [](layers::Layer& l, double x, double y) {
        bead(l, x, y, x + 20, y, gcode::Role::ExternalPerimeter);
        bead(l, x, y, x, y + 20, gcode::Role::ExternalPerimeter);
    };
    const layers::LayerStack st = test::stack_of(
        3, [&](int, layers::Layer& l) { ell(l, 10, 10); ell(l, 13, 13); }, {0, 0, 60, 60});
    const auto c = layers::find_copies(st);
    ASSERT_TRUE(c.has_value());
    ASSERT_EQ(c->offsets.size(), 2u);
    EXPECT_NEAR(c->offsets[1].dx, 3, 1e-4);
    // The first copy's beads are its own, though the other's lie in its box.
    ASSERT_EQ(c->beads[1].size(), 2u);
    EXPECT_EQ(c->beads[1][0], 0u);
    EXPECT_EQ(c->beads[1][1], 1u);
    const layers::LayerStack first = layers::first_copy(st, *c);
    EXPECT_EQ(first.layers[1].segments.size(), 2u);
}

TEST(Copies, ASkirtOrAWipeTowerBelongsToNoCopy) {
    layers::LayerStack st = plate({10, 40});
    bead(st.layers[0], 5, 15, 60, 15, gcode::Role::Skirt);
    EXPECT_TRUE(layers::find_copies(st).has_value());
    // A wipe tower beside them neither.
    for (auto& l : st.layers) bead(l, 80, 20, 90, 20, gcode::Role::WipeTower);
    EXPECT_TRUE(layers::find_copies(st).has_value());
    // The slicer's own support: no plate of copies.
    bead(st.layers[1], 12, 25, 13, 25, gcode::Role::Support);
    EXPECT_FALSE(layers::find_copies(st).has_value());
}

// Three in a row 20 mm apart: the first has a neighbour on its right only,
// the last on its left only; seen from every copy at once, the first has
// both, each the first's beads moved 20 mm, and nothing past the window.
TEST(Copies, TheFirstSeesANeighbourOnEachSideItHasFromAnyCopy) {
    const layers::LayerStack st = plate({10, 30, 50});
    const auto c = layers::find_copies(st);
    ASSERT_TRUE(c.has_value());
    const layers::LayerStack seen = layers::seen_from_every_copy(st, *c, 22);
    ASSERT_EQ(seen.layers.size(), st.layers.size());
    EXPECT_DOUBLE_EQ(seen.layers[3].z, st.layers[3].z);
    // Window: x 9.775 - 22 to 20.225 + 22.
    EXPECT_NEAR(seen.bounds.min_x, -12.225, 1e-4);
    EXPECT_NEAR(seen.bounds.max_x, 42.225, 1e-4);
    std::vector<double> lefts;  // each box's left wall x
    for (const layers::Segment& s : seen.layers[3].segments)
        if (s.role == gcode::Role::ExternalPerimeter && s.x0 == s.x1 && s.y0 > s.y1) lefts.push_back(s.x0);
    std::sort(lefts.begin(), lefts.end());
    ASSERT_EQ(lefts.size(), 3u);  // those at -30 and +40 lie past the window: not drawn
    EXPECT_NEAR(lefts[0], -10, 1e-4);
    EXPECT_NEAR(lefts[1], 10, 1e-4);
    EXPECT_NEAR(lefts[2], 30, 1e-4);
    // Each moved bead once, however many copies see it there.
    EXPECT_EQ(seen.layers[3].segments.size(), 3u * 5u);
}

// The objects are compared with the first on several threads: the same
// copies, and where two differ the same one named (the lowest), on any
// number of threads.
TEST(Copies, TheSameAnswerOnAnyNumberOfThreads) {
    auto row = [](std::vector<int> differing) {
        return test::stack_of(
            4,
            [&](int, layers::Layer& l) {
                for (int k = 0; k < 6; ++k)
                    box(l, 10 + 15 * k, 20.25, std::count(differing.begin(), differing.end(), k) ? 0.5 : 0);
            },
            {0, 0, 200, 60});
    };
    const layers::LayerStack same = row({});
    const auto one = layers::find_copies(same, nullptr, 1);
    ASSERT_TRUE(one.has_value());
    ASSERT_EQ(one->offsets.size(), 6u);
    const layers::LayerStack differ = row({3, 5});
    for (int threads : {1, 2, 3, 8}) {
        SCOPED_TRACE(threads);
        const auto many = layers::find_copies(same, nullptr, threads);
        ASSERT_TRUE(many.has_value());
        for (std::size_t k = 0; k < 6; ++k) {
            EXPECT_EQ(many->offsets[k].dx, one->offsets[k].dx);
            EXPECT_EQ(many->offsets[k].dy, one->offsets[k].dy);
        }
        std::string why;
        EXPECT_FALSE(layers::find_copies(differ, &why, threads).has_value());
        EXPECT_EQ(why, "object 4 of 6 is no exact copy of the first");
    }
}
