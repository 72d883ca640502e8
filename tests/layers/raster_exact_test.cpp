// The raster's fast paths (reciprocals, rows linear in j, windowed
// dilation) must set exactly the cells of the plain formulas they replace:
// golden outputs depend on every cell. These tests keep the plain formulas
// and compare on random and lattice-aligned input.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>

#include "layers/raster.hpp"

using scaffold::layers::BitGrid;
using scaffold::layers::CellBox;

namespace {

struct Interval {
    double lo = 1, hi = 0;
    bool empty() const { return hi < lo; }
    void unite(Interval o) {
        if (o.empty()) return;
        if (empty()) { *this = o; return; }
        lo = std::min(lo, o.lo);
        hi = std::max(hi, o.hi);
    }
};

Interval disc_row(double x, double y, double r, double cy) {
    double dy = cy - y;
    if (std::abs(dy) > r) return {};
    double h = std::sqrt(r * r - dy * dy);
    return {x - h, x + h};
}

Interval sorted(double a, double b) { return a <= b ? Interval{a, b} : Interval{b, a}; }

// The capsule row as first written: divisions throughout.
Interval capsule_row(double x0, double y0, double x1, double y1, double r, double cy) {
    Interval out = disc_row(x0, y0, r, cy);
    out.unite(disc_row(x1, y1, r, cy));
    double dx = x1 - x0, dy = y1 - y0;
    double len2 = dx * dx + dy * dy;
    if (len2 <= 0) return out;
    double len = std::sqrt(len2);
    double ry = cy - y0;
    constexpr double kInf = 1e300;
    Interval perp{-kInf, kInf};
    if (dy != 0) {
        perp = sorted(x0 + (dx * ry - r * len) / dy, x0 + (dx * ry + r * len) / dy);
    } else if (std::abs(ry) > r) {
        return out;
    }
    Interval along{-kInf, kInf};
    if (dx != 0) {
        along = sorted(x0 + (-ry * dy) / dx, x0 + (len2 - ry * dy) / dx);
    } else {
        double t = ry * dy;
        if (t < 0 || t > len2) return out;
    }
    Interval band{std::max(perp.lo, along.lo), std::min(perp.hi, along.hi)};
    out.unite(band);
    return out;
}

void reference_segment(BitGrid& g, double x0, double y0, double x1, double y1, double width) {
    double r = std::max(width * 0.5, g.cell() * 0.5);
    int j0 = std::max(0, g.row(std::min(y0, y1) - r));
    int j1 = std::min(g.height() - 1, g.row(std::max(y0, y1) + r));
    for (int j = j0; j <= j1; ++j) {
        Interval span = capsule_row(x0, y0, x1, y1, r, g.cy(j));
        if (span.empty()) continue;
        int i0 = static_cast<int>(std::ceil((span.lo - g.origin_x()) / g.cell() - 0.5));
        int i1 = static_cast<int>(std::floor((span.hi - g.origin_x()) / g.cell() - 0.5));
        g.set_row_span(j, i0, i1);
    }
}

BitGrid reference_dilated(const BitGrid& g, double r) {
    BitGrid out = g;
    double rc = r / g.cell();
    int R = static_cast<int>(std::floor(rc + 1e-9));
    if (R <= 0) return out;
    for (int j = 0; j < g.height(); ++j)
        for (int i = 0; i < g.width(); ++i) {
            if (!g.get(i, j)) continue;
            for (int d = -R; d <= R; ++d) {
                int h = static_cast<int>(std::floor(std::sqrt(std::max(0.0, rc * rc - d * d)) + 1e-9));
                out.set_row_span(j + d, i - h, i + h);
            }
        }
    return out;
}

bool same(const BitGrid& a, const BitGrid& b) { return a.same_shape(b) && a.words() == b.words(); }

// Coordinates as the layer stack holds them (float), some on the cell
// lattice or half-way between its lines, where rounding decides.
struct Gen {
    std::mt19937 rng{12345};
    double uniform(double a, double b) { return std::uniform_real_distribution<double>(a, b)(rng); }
    int pick(int n) { return std::uniform_int_distribution<int>(0, n - 1)(rng); }
    double coord(double origin, double cell, double span) {
        switch (pick(3)) {
        case 0: return static_cast<float>(uniform(0, span));
        case 1: return static_cast<float>(origin + std::round(uniform(0, span) / cell) * cell);
        default: return static_cast<float>(origin + (std::round(uniform(0, span) / cell) + 0.5) * cell);
        }
    }
    double width(double cell) {
        static constexpr double kWidths[] = {0.05, 0.1, 0.2, 0.4, 0.42, 0.45, 0.5, 1.0};
        if (pick(2)) return static_cast<float>(kWidths[pick(8)] * cell / 0.1);
        return static_cast<float>(uniform(0.02, 1.2) * cell / 0.1);
    }
};

}  // namespace

TEST(RasterExact, SegmentsMatchThePlainFormula) {
    Gen gen;
    for (double cell : {0.1, 0.07, 0.15, 0.25}) {
        for (double origin : {0.0, -2.3137, 1.05}) {
            BitGrid fast(origin, origin, origin + 30, origin + 30, cell);
            BitGrid slow = fast;
            for (int n = 0; n < 4000; ++n) {
                double x0 = gen.coord(origin, cell, 30), y0 = gen.coord(origin, cell, 30);
                double x1 = x0, y1 = y0;
                switch (gen.pick(6)) {
                case 0: x1 = gen.coord(origin, cell, 30); break;                                   // horizontal
                case 1: y1 = gen.coord(origin, cell, 30); break;                                   // vertical
                case 2: { double t = gen.uniform(-8, 8); x1 = static_cast<float>(x0 + t); y1 = static_cast<float>(y0 + t); break; }
                case 3: y1 = static_cast<float>(y0 + gen.uniform(-1e-3, 1e-3)); x1 = gen.coord(origin, cell, 30); break;
                case 4: break;                                                                     // a dot
                default: x1 = gen.coord(origin, cell, 30); y1 = gen.coord(origin, cell, 30); break;
                }
                double w = gen.width(cell);
                fast.draw_segment(x0, y0, x1, y1, w);
                reference_segment(slow, x0, y0, x1, y1, w);
                if (n % 50 == 49) {
                    ASSERT_TRUE(same(fast, slow)) << "cell " << cell << " origin " << origin << " segment " << n;
                    fast.clear();
                    slow.clear();
                }
            }
        }
    }
}

TEST(RasterExact, DilationMatchesThePlainFormula) {
    Gen gen;
    for (double cell : {0.1, 0.07}) {
        // Widths across word borders (64 cells) and a grid edge at each side.
        BitGrid g(0, 0, 19.3, 12.1, cell);
        for (int n = 0; n < 40; ++n) {
            g.clear();
            for (int k = 0; k < 6; ++k)
                g.draw_segment(gen.uniform(-1, 20), gen.uniform(-1, 13), gen.uniform(-1, 20), gen.uniform(-1, 13),
                               gen.uniform(0.05, 0.6));
            // Mostly the overhang reach; sometimes far beyond a word (64 cells).
            const int kind = gen.pick(8);
            double r = kind == 0 ? gen.uniform(0, 8) : kind == 1 ? gen.uniform(12, 16) : gen.uniform(0, 0.6);
            BitGrid want = reference_dilated(g, r);
            ASSERT_TRUE(same(g.dilated(r), want)) << "r " << r;
            // Into a grid that already holds other cells, from a box.
            BitGrid into = g;
            into.clear();
            into.set(3, 3);
            want.set(3, 3);
            CellBox box = g.dilate_into(into, r, {0, 0, g.width() - 1, g.height() - 1});
            ASSERT_TRUE(same(into, want)) << "r " << r;
            EXPECT_TRUE(box.i0 == 0 && box.j0 == 0);
        }
    }
}

TEST(RasterExact, SureCellAgreesWithColAndRow) {
    Gen gen;
    BitGrid g(-2.3137, 1.05, 40, 40, 0.1);
    int sure = 0;
    for (int n = 0; n < 200000; ++n) {
        double x = gen.coord(g.origin_x(), 0.1, 40), y = gen.coord(g.origin_y(), 0.1, 40);
        int i, j;
        if (!g.sure_cell(x, y, i, j)) continue;
        ++sure;
        ASSERT_EQ(i, g.col(x));
        ASSERT_EQ(j, g.row(y));
    }
    EXPECT_GT(sure, 100000);
}

TEST(RasterExact, AllSetAtMatchesThePlainLoop) {
    Gen gen;
    for (double cell : {0.1, 0.07}) {
        BitGrid g(-2.3137, 1.05, 30, 30, cell);
        int held = 0;
        for (int n = 0; n < 20000; ++n) {
            if (n % 1000 == 0) {
                // Random cells, dense so that some lines lie wholly on set
                // cells, sparse so that one cell off changes the answer.
                g.clear();
                const int dense = n % 2000 == 0 ? 97 : 60;
                for (int j = 0; j < g.height(); ++j)
                    for (int i = 0; i < g.width(); ++i)
                        if (gen.pick(100) < dense) g.set(i, j);
            }
            // Float ends as the layer stack holds them, on and between lattice lines.
            const float fx0 = static_cast<float>(gen.coord(g.origin_x(), cell, 32) - 1),
                        fy0 = static_cast<float>(gen.coord(g.origin_y(), cell, 30));
            float fx1 = static_cast<float>(fx0 + gen.uniform(-3, 3)), fy1 = static_cast<float>(fy0 + gen.uniform(-3, 3));
            if (gen.pick(4) == 0) fx1 = fx0;
            if (gen.pick(4) == 0) fy1 = static_cast<float>(gen.coord(g.origin_y(), cell, 30));
            const double dx = fx1 - fx0, dy = fy1 - fy0;
            const int steps = 1 + gen.pick(gen.pick(4) == 0 ? 40 : 3), begin = gen.pick(2);
            bool want = true;
            for (int i = begin; i <= steps && want; ++i) {
                const double t = static_cast<double>(i) / steps;
                want = g.get(g.col(fx0 + dx * t), g.row(fy0 + dy * t));
            }
            held += want;
            ASSERT_EQ(g.all_set_at(fx0, fy0, dx, dy, steps, begin), want) << "cell " << cell << " line " << n;
        }
        EXPECT_GT(held, 100);
    }
}

TEST(RasterExact, EnclosedIsTheFilledHolesUnderTheSeeds) {
    Gen gen;
    BitGrid g(0, 0, 15.1, 9.7, 0.1);
    int with_holes = 0;
    for (int n = 0; n < 30; ++n) {
        g.clear();
        // Rings (holes), open arcs and strokes, some touching the border.
        for (int k = 0; k < 5; ++k) {
            double cx = gen.uniform(0, 15), cy = gen.uniform(0, 10), rad = gen.uniform(0.5, 4);
            int sides = 3 + gen.pick(6), drawn = gen.pick(3) == 0 ? sides - 1 : sides;
            for (int e = 0; e < drawn; ++e) {
                double a0 = 2 * 3.14159265 * e / sides, a1 = 2 * 3.14159265 * (e + 1) / sides;
                g.draw_segment(cx + rad * std::cos(a0), cy + rad * std::sin(a0), cx + rad * std::cos(a1),
                               cy + rad * std::sin(a1), gen.uniform(0.1, 0.5));
            }
        }
        BitGrid seeds = g;
        seeds.clear();
        for (int k = 0; k < 400; ++k) seeds.set(gen.pick(g.width()), gen.pick(g.height()));
        BitGrid want = g.filled();
        want.subtract(g);
        want &= seeds;
        ASSERT_TRUE(same(g.enclosed(seeds), want)) << n;
        with_holes += want.any();
        // Seeds in a box, looked for in that box only (the floods still run
        // the whole grid).
        const CellBox box{gen.pick(g.width() / 2), gen.pick(g.height() / 2), g.width() / 2 + gen.pick(g.width() / 2),
                          g.height() / 2 + gen.pick(g.height() / 2)};
        BitGrid boxed = seeds, mask = seeds;
        mask.clear();
        for (int j = box.j0; j <= box.j1; ++j) mask.set_row_span(j, box.i0, box.i1);
        boxed &= mask;
        BitGrid want_boxed = want;
        want_boxed &= mask;
        ASSERT_TRUE(same(g.enclosed(boxed, box), want_boxed)) << n;
    }
    EXPECT_GT(with_holes, 10);
}

// draw_layer over polylines as slicers write them: segments chained end to
// start (some not), lengths 0.01-5 mm at any angle, steep and flat ones,
// repeated points, widths changing or not along a chain. Its cells must be
// those of each segment drawn on its own, and of the plain formula.
TEST(RasterExact, PolylinesMatchSegmentsDrawnAlone) {
    Gen gen;
    using scaffold::layers::Layer;
    using scaffold::layers::Segment;
    for (double cell : {0.1, 0.07, 0.15}) {
        for (double origin : {0.0, -2.3137, 1.05}) {
            BitGrid fast(origin, origin, origin + 30, origin + 30, cell);
            BitGrid alone = fast, slow = fast;
            for (int n = 0; n < 60; ++n) {
                Layer layer;
                float x = static_cast<float>(gen.coord(origin, cell, 30)), y = static_cast<float>(gen.coord(origin, cell, 30));
                float w = static_cast<float>(gen.width(cell));
                for (int k = 0; k < 80; ++k) {
                    if (gen.pick(15) == 0) {  // a jump: the next segment starts elsewhere
                        x = static_cast<float>(gen.coord(origin, cell, 30)), y = static_cast<float>(gen.coord(origin, cell, 30));
                    }
                    if (gen.pick(3) == 0) w = static_cast<float>(gen.width(cell));
                    const double len = 0.01 * std::pow(500.0, gen.uniform(0, 1));
                    double angle = gen.uniform(0, 2 * 3.14159265358979);
                    switch (gen.pick(8)) {
                    case 0: angle = gen.pick(4) * 3.14159265358979 / 2; break;           // axis-parallel
                    case 1: angle = 3.14159265358979 / 2 + gen.uniform(-1e-3, 1e-3); break;  // steep
                    case 2: angle = gen.uniform(-1e-3, 1e-3); break;                      // flat
                    default: break;
                    }
                    float x1 = static_cast<float>(x + len * std::cos(angle)), y1 = static_cast<float>(y + len * std::sin(angle));
                    if (gen.pick(20) == 0) x1 = x, y1 = y;  // a repeated point
                    if (x1 < origin - 1 || x1 > origin + 31) x1 = static_cast<float>(x - len * std::cos(angle));
                    if (y1 < origin - 1 || y1 > origin + 31) y1 = static_cast<float>(y - len * std::sin(angle));
                    Segment s;
                    s.x0 = x, s.y0 = y, s.x1 = x1, s.y1 = y1, s.width = w;
                    layer.segments.push_back(s);
                    x = x1, y = y1;
                }
                draw_layer(fast, layer);
                for (const Segment& s : layer.segments) {
                    alone.draw_segment(s.x0, s.y0, s.x1, s.y1, s.width);
                    reference_segment(slow, s.x0, s.y0, s.x1, s.y1, s.width);
                }
                ASSERT_TRUE(same(fast, alone)) << "cell " << cell << " origin " << origin << " polyline " << n;
                ASSERT_TRUE(same(fast, slow)) << "cell " << cell << " origin " << origin << " polyline " << n;
                fast.clear();
                alone.clear();
                slow.clear();
            }
        }
    }
}

TEST(RasterExact, ASegmentDrawnInStepsIsTheSegment) {
    // Detection draws an unheld stretch of a segment as one line from its
    // first to its last sample, where it used to draw one line per 0.1 mm
    // sample step: the same cells, checked here on random segments split at
    // the samples the detector takes (x0 + dx * i / n).
    Gen gen;
    for (double cell : {0.1, 0.07, 0.15}) {
        for (double origin : {0.0, -2.3137, 1.05}) {
            BitGrid whole(origin, origin, origin + 30, origin + 30, cell);
            BitGrid steps = whole;
            for (int n = 0; n < 3000; ++n) {
                double x0 = gen.coord(origin, cell, 30), y0 = gen.coord(origin, cell, 30);
                double x1 = gen.coord(origin, cell, 30), y1 = gen.coord(origin, cell, 30);
                if (gen.pick(3) == 0) y1 = y0;  // axis-parallel ones too
                const double w = gen.width(cell), dx = x1 - x0, dy = y1 - y0;
                const int k = std::max(1, static_cast<int>(std::ceil(std::hypot(dx, dy) / cell)));
                // A stretch from sample a to sample b of the k + 1 samples.
                const int a = gen.pick(k), b = a + 1 + gen.pick(k - a);
                auto at = [&](int i, double& x, double& y) {
                    double t = static_cast<double>(i) / k;
                    x = x0 + dx * t;
                    y = y0 + dy * t;
                };
                double xa, ya, xb, yb;
                at(a, xa, ya);
                at(b, xb, yb);
                whole.draw_segment(xa, ya, xb, yb, w);
                for (int i = a + 1; i <= b; ++i) {
                    double xp, yp, xq, yq;
                    at(i - 1, xp, yp);
                    at(i, xq, yq);
                    steps.draw_segment(xp, yp, xq, yq, w);
                }
                if (n % 50 == 49) {
                    ASSERT_TRUE(same(whole, steps)) << "cell " << cell << " origin " << origin << " segment " << n;
                    whole.clear();
                    steps.clear();
                }
            }
        }
    }
}
