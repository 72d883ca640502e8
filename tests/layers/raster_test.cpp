#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "layers/raster.hpp"

using scaffold::layers::BitGrid;

TEST(Raster, ThickSegmentCoversItsCapsule) {
    BitGrid g(0, 0, 20, 20, 0.1);
    // Off the cell lattice, so the count is not an aliasing accident.
    g.draw_segment(5.013, 10.037, 15.013, 10.037, 0.5);
    // Area of a 10 x 0.5 capsule: 5 + pi * 0.0625.
    double area = static_cast<double>(g.count()) * g.cell_area();
    EXPECT_NEAR(area, 5 + std::numbers::pi * 0.0625, 0.15);
    EXPECT_TRUE(g.get(g.col(10), g.row(10.2)));
    EXPECT_FALSE(g.get(g.col(10), g.row(10.35)));
    EXPECT_FALSE(g.get(g.col(4.6), g.row(10)));
}

TEST(Raster, DiagonalSegmentAndDisc) {
    BitGrid g(0, 0, 20, 20, 0.1);
    g.draw_segment(2.013, 2.041, 12.013, 13.041, 0.4);
    double len = std::hypot(10, 11);
    EXPECT_NEAR(static_cast<double>(g.count()) * g.cell_area(), len * 0.4 + std::numbers::pi * 0.04, 0.2);
    BitGrid d(0, 0, 20, 20, 0.1);
    d.draw_disc(10.021, 10.047, 3);
    EXPECT_NEAR(static_cast<double>(d.count()) * d.cell_area(), std::numbers::pi * 9, 0.3);
}

TEST(Raster, DilationGrowsByTheRadius) {
    BitGrid g(0, 0, 20, 20, 0.1);
    g.set(100, 100);
    BitGrid d = g.dilated(1.0);
    EXPECT_NEAR(static_cast<double>(d.count()) * d.cell_area(), std::numbers::pi, 0.15);
    EXPECT_TRUE(d.get(110, 100));
    EXPECT_FALSE(d.get(111, 100));
    EXPECT_TRUE(d.get(107, 107));   // 0.99 mm away
    EXPECT_FALSE(d.get(108, 108));  // 1.13 mm away
}

TEST(Raster, FilledAndEnclosedAgree) {
    BitGrid g(0, 0, 30, 30, 0.1);
    // A closed square ring with a gap in a second ring.
    g.draw_segment(5, 5, 15, 5, 0.4);
    g.draw_segment(15, 5, 15, 15, 0.4);
    g.draw_segment(15, 15, 5, 15, 0.4);
    g.draw_segment(5, 15, 5, 5, 0.4);
    g.draw_segment(18, 18, 28, 18, 0.4);
    g.draw_segment(28, 18, 28, 28, 0.4);
    g.draw_segment(28, 28, 18, 28, 0.4);  // open on the left side
    BitGrid f = g.filled();
    EXPECT_TRUE(f.get(f.col(10), f.row(10)));    // inside the closed ring
    EXPECT_FALSE(f.get(f.col(23), f.row(23)));   // inside the open one: reachable
    EXPECT_FALSE(f.get(f.col(2), f.row(2)));
    BitGrid seeds(0, 0, 30, 30, 0.1);
    seeds.draw_disc(10, 10, 2);
    seeds.draw_disc(23, 23, 2);
    seeds.draw_disc(2, 25, 1);
    BitGrid in = g.enclosed(seeds);
    BitGrid expect = seeds;
    expect &= f;
    EXPECT_EQ(in.count(), expect.count());
    EXPECT_TRUE(in.get(in.col(10), in.row(10)));
    EXPECT_FALSE(in.get(in.col(23), in.row(23)));
    EXPECT_FALSE(in.get(in.col(2), in.row(25)));
}

TEST(Raster, WideGridsCrossWordBoundaries) {
    BitGrid g(0, 0, 40, 4, 0.1);  // 400 cells a row: 7 words
    g.draw_segment(1, 0.5, 39, 0.5, 0.3);
    g.draw_segment(1, 3.5, 39, 3.5, 0.3);
    g.draw_segment(1, 0.5, 1, 3.5, 0.3);
    g.draw_segment(39, 0.5, 39, 3.5, 0.3);
    BitGrid f = g.filled();
    for (double x = 2; x < 38.5; x += 0.7) EXPECT_TRUE(f.get(f.col(x), f.row(2))) << x;
    EXPECT_FALSE(f.get(f.col(39.8), f.row(2)));
}

// A crop holds the box's cells (widened to whole words) at its offsets, and
// the holes filled() finds in a crop with a free cell around the material
// are the whole grid's: two rings 12 mm apart on a 30 mm grid, one closed.
TEST(Raster, ACropFillsAsTheWholeGridDoes) {
    BitGrid g(0, 0, 30, 30, 0.1);
    g.draw_segment(8, 6, 16, 6, 0.45);
    g.draw_segment(16, 6, 16, 14, 0.45);
    g.draw_segment(16, 14, 8, 14, 0.45);
    g.draw_segment(8, 14, 8, 6, 0.45);    // closed
    g.draw_segment(20, 20, 26, 20, 0.45);
    g.draw_segment(26, 20, 26, 26, 0.45);
    g.draw_segment(26, 26, 20, 26, 0.45);  // open on the left
    const scaffold::layers::CellBox box{g.col(7.7), g.row(5.7), g.col(26.3), g.row(26.3)};  // the beads' cells
    int i_off = -1, j_off = -1;
    const BitGrid c = g.crop(box.grown(1), i_off, j_off);
    EXPECT_EQ(i_off % 64, 0);
    EXPECT_LE(i_off, box.i0 - 1);
    EXPECT_EQ(j_off, box.j0 - 1);
    EXPECT_EQ(c.count(), g.count());  // every set cell is in the crop
    BitGrid back = g.empty_like();
    back.or_crop(c, i_off, j_off);  // and goes back where it came from
    for (int j = 0; j < g.height(); ++j)
        for (int i = 0; i < g.width(); ++i) ASSERT_EQ(back.get(i, j), g.get(i, j)) << i << " " << j;
    const BitGrid whole = g.filled(), part = c.filled();
    long inside = 0;
    for (int j = 0; j < g.height(); ++j)
        for (int i = 0; i < g.width(); ++i) {
            const bool in_crop = i >= i_off && i < i_off + c.width() && j >= j_off && j < j_off + c.height();
            ASSERT_EQ(in_crop ? part.get(i - i_off, j - j_off) : g.get(i, j), whole.get(i, j)) << i << " " << j;
            inside += whole.get(i, j) && !g.get(i, j);
        }
    // The closed ring's inside: about (8 - 0.45) x (8 - 0.45) mm at 0.01 mm^2 a cell.
    EXPECT_NEAR(static_cast<double>(inside), 7.55 * 7.55 / 0.01, 200);
}
