// The footprint METHOD's base-on-the-model test reads: small holes filled,
// large regions open, whatever order the cells are asked in.
#include <gtest/gtest.h>

#include "check/footprint.hpp"

using namespace scaffold;

namespace {

// A 40 x 40 cell grid with a corridor one cell wide along row 20, walled on
// rows 19 and 21 from column 5 to 35 and closed at column 5; open at its
// right end when `open_end`, else closed at column 35 too (a 29-cell hole).
check::Footprint corridor(bool open_end) {
    check::Footprint f;
    f.grid = layers::BitGrid(0, 0, 4, 4, 0.1);
    for (int i = 5; i <= 35; ++i) {
        f.grid.set(i, 19);
        f.grid.set(i, 21);
    }
    f.grid.set(5, 20);
    if (!open_end) f.grid.set(35, 20);
    f.state.assign(static_cast<std::size_t>(f.grid.width()) * f.grid.height(), 0);
    f.limit = 30;
    return f;
}

}  // namespace

TEST(Footprint, ASmallHoleIsFilledAndTheModelCovers) {
    check::Footprint f = corridor(false);
    EXPECT_TRUE(f.covers(6, 20));    // the 29 cells inside
    EXPECT_TRUE(f.covers(20, 19));   // a wall
    EXPECT_FALSE(f.covers(37, 30));  // outside
}

TEST(Footprint, ACorridorOpenToALargeRegionIsNoHole) {
    check::Footprint f = corridor(true);
    EXPECT_FALSE(f.covers(6, 20));
}

TEST(Footprint, ACorridorStaysOpenWhenItsMouthWasFoundOpenFirst) {
    // The first flood, from beside the corridor's mouth, stops at the limit
    // after taking the mouth's cells; the second, from the closed end, must
    // not take those cells for walls (30 cells: a hole by its count alone).
    // figure.slic3r13: a connector inside a column's loop was found standing
    // on the model so, and the column's top walked down it at 1.1 N/mm.
    check::Footprint f = corridor(true);
    EXPECT_FALSE(f.covers(37, 20));
    EXPECT_EQ(f.state[static_cast<std::size_t>(20) * 40 + 34], 2);  // the mouth, found open
    EXPECT_FALSE(f.covers(6, 20));
}
