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
