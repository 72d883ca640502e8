#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

#include "layers/layer_stack.hpp"
#include "layers/raster.hpp"
#include "plan/obstacles.hpp"
#include "support/stacks.hpp"

using namespace scaffold;

namespace {

// Rasters of 0.1 mm cells, 13 x 9.7 mm (three words a row, two bands of
// rows), one per layer over more than one block of 64 layers: random discs
// and lines, single cells, an empty and a full layer.
std::vector<layers::BitGrid> random_rasters(int layers, unsigned seed, double width = 13.0) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> ux(-0.5, width + 0.5), uy(-0.5, 10.2), ur(0.0, 1.5);
    std::vector<layers::BitGrid> out;
    for (int l = 0; l < layers; ++l) {
        layers::BitGrid g(0, 0, width, 9.7, 0.1);
        if (l == 3) {
            for (int j = 0; j < g.height(); ++j) g.set_row_span(j, 0, g.width() - 1);
        } else if (l != 5) {
            int shapes = 1 + l % 7;
            for (int k = 0; k < shapes; ++k) {
                if (k % 3 == 0) g.draw_disc(ux(rng), uy(rng), ur(rng));
                else if (k % 3 == 1) g.draw_segment(ux(rng), uy(rng), ux(rng), uy(rng), 0.45);
                else g.set(static_cast<int>(ux(rng) * 10), static_cast<int>(uy(rng) * 10));
            }
        }
        out.push_back(std::move(g));
    }
    return out;
}

// Radii at and next to the distances between cell centres (k cells, the
// diagonals sqrt(a^2 + b^2) cells), and random ones.
std::vector<double> test_radii(std::mt19937& rng) {
    std::vector<double> r{0.0, 0.05, 0.1, 0.15, 0.2285, 0.5, 1.0, 1.5, 1.9, 2.5, 3.0};
    for (int a = 0; a <= 6; ++a)
        for (int b = a; b <= 6; ++b) {
            double d = 0.1 * std::hypot(a, b);
            r.push_back(d);
            r.push_back(std::nextafter(d, 0.0));
            r.push_back(std::nextafter(d, 1.0));
        }
    std::uniform_real_distribution<double> ur(0.0, 3.5);
    for (int k = 0; k < 20; ++k) r.push_back(ur(rng));
    return r;
}

// Query points: random, on cell borders, at cell centres, a hair off
// either, and a whole radius (give or take a hair) from a cell centre.
std::vector<std::pair<double, double>> test_points(std::mt19937& rng, double r, int n, double width = 13.0) {
    std::uniform_real_distribution<double> ux(-1.0, width + 1.0), uy(-1.0, 10.7);
    std::uniform_int_distribution<int> ui(-5, static_cast<int>(width * 10) + 5), uj(-5, 102), pick(0, 5);
    std::vector<std::pair<double, double>> p;
    for (int k = 0; k < n; ++k) {
        const int i = ui(rng), j = uj(rng);
        const double border_x = 0.1 * i, border_y = 0.1 * j, centre_x = 0.1 * (i + 0.5), centre_y = 0.1 * (j + 0.5);
        switch (pick(rng)) {
            case 0: p.push_back({ux(rng), uy(rng)}); break;
            case 1: p.push_back({border_x, border_y}); break;
            case 2: p.push_back({border_x, uy(rng)}); break;
            case 3: p.push_back({centre_x, centre_y}); break;
            case 4: p.push_back({std::nextafter(border_x, -1.0), std::nextafter(centre_y, 20.0)}); break;
            default: {
                // A cell centre exactly (or a hair beyond) r away.
                double a = std::uniform_real_distribution<double>(0, 6.283185307179586)(rng);
                double rr = k % 2 ? r : std::nextafter(r, 10.0);
                p.push_back({centre_x + rr * std::cos(a), centre_y + rr * std::sin(a)});
                if (k % 3 == 0) p.back() = {centre_x + rr, centre_y};  // along a row
            }
        }
    }
    return p;
}

struct Tally {
    long long decided = 0, unknown = 0;
};

// Every answer the lookup gives is the exact test's; counts the undecided.
void expect_like_exact(plan::DiscLookup::Layout layout, unsigned seed, Tally& tally, double width = 13.0) {
    const std::vector<layers::BitGrid> model = random_rasters(70, seed, width);
    std::mt19937 rng(seed + 1);
    std::size_t used = 0;
    for (double r : test_radii(rng)) {
        plan::DiscLookup lookup(model, r, layout);
        for (const auto& [x, y] : test_points(rng, r, 400, width)) {
            // The same point on a run of layers, as a column asks it.
            int l0 = std::uniform_int_distribution<int>(0, 69)(rng);
            for (int l = l0; l >= std::max(0, l0 - 6); --l) {
                plan::DiscLookup::LayerRange clear;
                const int a = lookup.lookup(l, x, y, std::size_t{1} << 30, used, clear);
                const bool meets = plan::disc_meets(model[l], x, y, r);
                if (a < 0) {
                    ++tally.unknown;
                    continue;
                }
                ++tally.decided;
                ASSERT_EQ(a == 0, meets) << "layer " << l << " at (" << x << ", " << y << ") r " << r;
                if (a == 1 && layout == plan::DiscLookup::Layout::Columns) {
                    // Every layer of the run it reports is clear too.
                    ASSERT_LE(clear.lo, l);
                    ASSERT_GE(clear.hi, l);
                    for (int m = clear.lo; m <= clear.hi; ++m)
                        ASSERT_FALSE(plan::disc_meets(model[m], x, y, r)) << "run " << clear.lo << ".." << clear.hi << " at " << m;
                }
            }
        }
    }
}

}  // namespace

TEST(DiscLookup, ColumnsAnswerAsTheExactTestDoes) {
    Tally t;
    for (unsigned seed : {1u, 2u, 3u}) expect_like_exact(plan::DiscLookup::Layout::Columns, seed, t);
    // Undecided only near the edge of a disc or outside the grid: a small
    // share, even of points picked mostly there.
    EXPECT_GT(t.decided, 3 * t.unknown) << t.decided << " decided, " << t.unknown << " not";
}

// 40 mm: seven words a row, two blocks across (the second one narrower).
TEST(DiscLookup, ColumnsAnswerAsTheExactTestDoesAcrossBlocks) {
    Tally t;
    expect_like_exact(plan::DiscLookup::Layout::Columns, 11u, t, 40.0);
    EXPECT_GT(t.decided, 3 * t.unknown) << t.decided << " decided, " << t.unknown << " not";
}

TEST(DiscLookup, PerLayerAnswersAsTheExactTestDoes) {
    Tally t;
    for (unsigned seed : {4u, 5u}) expect_like_exact(plan::DiscLookup::Layout::PerLayer, seed, t);
    EXPECT_GT(t.decided, 3 * t.unknown) << t.decided << " decided, " << t.unknown << " not";
}

TEST(DiscLookup, OverTheBudgetItDefersToTheExactTest) {
    const std::vector<layers::BitGrid> model = random_rasters(3, 7);
    plan::DiscLookup lookup(model, 1.0, plan::DiscLookup::Layout::Columns);
    std::size_t used = 0;
    EXPECT_EQ(lookup.lookup(1, 6.0, 5.0, 1000, used), -1);
    EXPECT_EQ(used, 0u);
    EXPECT_GE(lookup.lookup(1, 6.0, 5.0, std::size_t{1} << 30, used), 0);
    EXPECT_GT(used, 0u);
    // Outside the grid: unknown, never a guess.
    EXPECT_EQ(lookup.lookup(1, -3.0, 5.0, std::size_t{1} << 30, used), -1);
}

// The Obstacles as the planner uses them: columns walked down at a few
// radii (their lookups get built), then other radii and points, answered
// through the nearest column's lookup, the remembered clear runs and the
// exact test; all must answer as the exact test does.
TEST(DiscLookup, ObstaclesAnswerAsTheExactTestDoes) {
    std::mt19937 rng(11);
    std::uniform_real_distribution<double> ux(0, 40), uy(0, 30);
    const layers::LayerStack st = test::stack_of(
        150,
        [&](int, layers::Layer& l) {
            for (int k = 0; k < 4; ++k) {
                const double x0 = ux(rng), y0 = uy(rng);
                test::bead(l, x0, y0, x0 + 3.0, y0 + 1.0, gcode::Role::Perimeter);
            }
        },
        {0, 0, 43, 31});
    Settings s;
    const plan::Obstacles obs(st, s);
    long long asked = 0, blocked = 0;
    auto check = [&](int l, double x, double y, double r) {
        const bool fast = obs.disc_clear(l, x, y, r);
        ++asked;
        blocked += !fast;
        ASSERT_EQ(fast, obs.disc_clear_exact(l, x, y, r)) << "layer " << l << " at (" << x << ", " << y << ") r " << r;
    };
    const double column_radii[] = {1.5, 1.9, 1.0, 1.25};
    for (int pass = 0; pass < 2; ++pass)
        for (int k = 0; k < 300; ++k) {
            const double x = ux(rng), y = uy(rng);
            for (double r : column_radii)
                for (int l = 149; l >= 0; l -= 1 + k % 3) check(l, x, y, r);
        }
    std::vector<std::pair<double, double>> points = test_points(rng, 1.2, 3000);
    std::uniform_real_distribution<double> ur(0, 3);
    for (const auto& [x0, y0] : points) {
        // Spread over this stack's 43 x 31 mm (test_points' are 13 x 9.7).
        const double x = x0 * 3, y = y0 * 3;
        const double r = ur(rng);
        for (int l = 0; l < 150; l += 7) {
            check(l, x, y, r);
            check(l, x, y, 1.5);
        }
    }
    // Radii first counted without an entry of their own (kTrackAfter
    // queries), then tracked, then given a lookup (kFastAfter): each stage
    // answers as the exact test.
    for (double r : {0.77, 0.83, 2.2})
        for (int k = 0; k < 5000; ++k) check(k % 150, ux(rng), uy(rng), r);
    EXPECT_GT(blocked, asked / 20);  // the model is really in the way of some
}
