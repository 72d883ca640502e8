// Detection and point placement on hand-built layer stacks: no reader in
// the way, so each test names exactly the geometry it judges.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "layers/layer_stack.hpp"
#include "overhang/overhangs.hpp"

using namespace scaffold;

namespace {

layers::Layer make_layer(double z, double height, int below, bool on_bed = false) {
    layers::Layer l;
    l.z = z;
    l.height = height;
    l.below = below;
    if (below >= 0) l.beneath = {below};  // the layer named, as the stack builds it for one Z grid
    l.on_bed = on_bed;
    return l;
}

void line(layers::Layer& l, double x0, double y0, double x1, double y1, gcode::Role role = gcode::Role::SolidInfill) {
    l.segments.push_back({static_cast<float>(x0), static_cast<float>(y0), static_cast<float>(x1),
                          static_cast<float>(y1), 0.45f, role, static_cast<std::uint32_t>(l.segments.size())});
}

// Solid: horizontal lines 0.4 mm apart.
void solid(layers::Layer& l, double x0, double y0, double x1, double y1) {
    for (double y = y0 + 0.2; y < y1; y += 0.4) line(l, x0 + 0.2, y, x1 - 0.2, y);
}

layers::LayerStack stack_of(std::vector<layers::Layer> ls) {
    layers::LayerStack st;
    st.layers = std::move(ls);
    st.bounds = {1e9, 1e9, -1e9, -1e9};
    for (const auto& l : st.layers)
        for (const auto& s : l.segments) {
            st.bounds.min_x = std::min({st.bounds.min_x, double(s.x0), double(s.x1)});
            st.bounds.min_y = std::min({st.bounds.min_y, double(s.y0), double(s.y1)});
            st.bounds.max_x = std::max({st.bounds.max_x, double(s.x0), double(s.x1)});
            st.bounds.max_y = std::max({st.bounds.max_y, double(s.y0), double(s.y1)});
        }
    return st;
}

// A square ring of perimeter with sparse lines inside (4 mm apart), and a
// gap in the ring's left wall if `open`.
void sparse_box(layers::Layer& l, double x0, double y0, double x1, double y1, bool open) {
    line(l, x0, y0, x1, y0);
    line(l, x1, y0, x1, y1);
    line(l, x1, y1, x0, y1);
    if (open) {
        line(l, x0, y1, x0, (y0 + y1) / 2 + 1);
        line(l, x0, (y0 + y1) / 2 - 1, x0, y0);
    } else {
        line(l, x0, y1, x0, y0);
    }
    for (double x = x0 + 4; x < x1 - 1; x += 4) line(l, x, y0, x, y1, gcode::Role::InternalInfill);
}

}  // namespace

TEST(OverhangStack, BedLayersNeverOverhang) {
    auto purge = make_layer(0.3, 0.3, -1, true);
    line(purge, 0, 0, 0, 40);
    auto first = make_layer(0.2, 0.2, -1, true);
    solid(first, 10, 10, 40, 40);
    auto st = stack_of({purge, first});
    Settings s;
    auto o = overhang::find_overhangs(st, s);
    EXPECT_TRUE(o.layers.empty());
    EXPECT_EQ(o.area_mm2, 0);
}

TEST(OverhangStack, JudgedAgainstTheLayerNamedBelow) {
    // Layer 2 is twice as wide as layer 1 but exactly as wide as layer 0.
    auto l0 = make_layer(0.2, 0.2, -1, true);
    solid(l0, 0, 0, 20, 10);
    auto l1 = make_layer(0.4, 0.2, 0);
    solid(l1, 0, 0, 10, 10);
    auto l2 = make_layer(0.6, 0.2, 1);
    solid(l2, 0, 0, 20, 10);
    Settings s;
    auto over_l1 = overhang::find_overhangs(stack_of({l0, l1, l2}), s);
    ASSERT_EQ(over_l1.layers.size(), 1u);
    EXPECT_EQ(over_l1.layers[0].layer, 2);
    EXPECT_NEAR(over_l1.area_mm2, 100, 10);  // the 10 x 10 mm half beyond layer 1
    l2.below = 0;
    l2.beneath = {0};
    auto over_l0 = overhang::find_overhangs(stack_of({l0, l1, l2}), s);
    EXPECT_TRUE(over_l0.layers.empty());
    // Both layers beneath (objects on Z grids of their own): their union holds it.
    l2.below = 1;
    l2.beneath = {1, 0};
    auto over_both = overhang::find_overhangs(stack_of({l0, l1, l2}), s);
    EXPECT_TRUE(over_both.layers.empty());
}

TEST(OverhangStack, SkinOverSparseInfillIsHeldOverAnOpenBoxIsNot) {
    Settings s;
    s.max_bridge = 1;  // enclosure alone, not rule (b)'s spans over the 4 mm holes
    for (bool open : {false, true}) {
        auto l0 = make_layer(0.2, 0.2, -1, true);
        solid(l0, 0, 0, 20, 20);
        auto l1 = make_layer(0.4, 0.2, 0);
        sparse_box(l1, 0, 0, 20, 20, open);
        auto l2 = make_layer(0.6, 0.2, 1);
        solid(l2, 0, 0, 20, 20);
        auto st = stack_of({l0, l1, l2});
        auto o = overhang::find_overhangs(st, s);
        if (!open) {
            EXPECT_TRUE(o.layers.empty()) << o.area_mm2 << " mm^2 over closed sparse infill";
            continue;
        }
        // Through the gap the first hole (x 0..4, between the wall and the
        // first sparse line) reaches the outside: the skin over it, less
        // what the wall and the line hold, is overhang; the other holes are
        // still closed.
        ASSERT_EQ(o.layers.size(), 1u);
        EXPECT_EQ(o.layers[0].layer, 2);
        EXPECT_GT(o.area_mm2, 50);
        EXPECT_LT(o.area_mm2, 80);
        auto p = overhang::place_points(o, st, s);
        EXPECT_GE(p.points.size(), 2u);
        for (const auto& pt : p.points) {
            EXPECT_GT(pt.x, 0);
            EXPECT_LT(pt.x, 4);
        }
    }
}

TEST(OverhangStack, AreaIsTheKeptCells) {
    auto l0 = make_layer(0.2, 0.2, -1, true);
    solid(l0, 0, 0, 10, 10);
    auto l1 = make_layer(0.4, 0.2, 0);
    solid(l1, 0, 0, 30, 10);
    auto l2 = make_layer(0.6, 0.2, 1);
    solid(l2, 0, 0, 30, 10);
    auto o = overhang::find_overhangs(stack_of({l0, l1, l2}), Settings{});
    ASSERT_EQ(o.layers.size(), 1u);  // layer 2 rests on layer 1
    const auto& ol = o.layers[0];
    EXPECT_DOUBLE_EQ(ol.area_mm2, static_cast<double>(ol.cells.count()) * ol.cells.cell_area());
    EXPECT_DOUBLE_EQ(o.area_mm2, ol.area_mm2);
    EXPECT_NEAR(o.area_mm2, 200, 12);
    // Beads are held where their centre line is within reach of layer 0's
    // material (lines to x = 9.8, 0.45 wide, so material to 10.025; reach
    // 0.2 tan(55 deg) + half a cell = 0.336): the overhang starts at the
    // first unheld sample past x = 10.36, never over layer 0's lines.
    double min_x = 1e9;
    for (int j = 0; j < ol.cells.height(); ++j)
        for (int i = 0; i < ol.cells.width(); ++i)
            if (ol.cells.get(i, j)) min_x = std::min(min_x, ol.cells.cx(i));
    EXPECT_GT(min_x, 10.3);
    EXPECT_LT(min_x, 10.45);
}

TEST(OverhangPoints, EveryRegionCoveredByPointsOnItsCells) {
    // Hand-drawn overhang cells: a wide square, a thin strip, a ring and an
    // L, on layer 1 of a two-layer stack.
    auto l0 = make_layer(0.2, 0.2, -1, true);
    line(l0, 0, 0, 80, 80);
    auto l1 = make_layer(0.5, 0.3, 0);
    line(l1, 0, 0, 80, 80);
    auto st = stack_of({l0, l1});
    Settings s;
    layers::BitGrid g = layers::make_grid(st, s.resolution, 2.0);
    auto rect = [&](double x0, double y0, double x1, double y1) {
        for (double y = y0; y < y1; y += 0.05) g.draw_segment(x0, y, x1, y, 0.1);
    };
    rect(2, 2, 32, 32);       // 30 x 30 mm
    rect(40, 2, 60, 2.5);     // 20 x 0.5 mm strip
    rect(40, 10, 41, 30);     // L: a 1 x 20 mm leg ...
    rect(40, 10, 60, 11);     // ... and a 20 x 1 mm foot
    for (double r = 6; r < 7; r += 0.05)  // ring of radius 6..7 around (60, 60)
        for (int k = 0; k < 720; ++k) {
            double a = k * std::numbers::pi / 360;
            g.set(g.col(60 + r * std::cos(a)), g.row(60 + r * std::sin(a)));
        }
    overhang::Overhangs o;
    o.layers.push_back({1, g, static_cast<double>(g.count()) * g.cell_area()});
    o.area_mm2 = o.layers[0].area_mm2;
    auto pts = overhang::place_points(o, st, s);
    const auto& P = pts.points;
    ASSERT_FALSE(P.empty());
    for (std::size_t k = 0; k < P.size(); ++k) {
        EXPECT_EQ(P[k].layer, 1);
        EXPECT_NEAR(P[k].z, 0.2, 1e-12);
        EXPECT_TRUE(g.get(g.col(P[k].x), g.row(P[k].y))) << "point off the cells at " << P[k].x << "," << P[k].y;
        if (k) {
            EXPECT_TRUE(P[k - 1].y < P[k].y || (P[k - 1].y == P[k].y && P[k - 1].x < P[k].x)) << "unsorted at " << k;
        }
    }
    for (int j = 0; j < g.height(); ++j)
        for (int i = 0; i < g.width(); ++i) {
            if (!g.get(i, j)) continue;
            bool covered = false;
            for (const auto& p : P) covered = covered || std::hypot(p.x - g.cx(i), p.y - g.cy(j)) <= s.point_radius;
            ASSERT_TRUE(covered) << g.cx(i) << "," << g.cy(j);
        }
    auto in = [&](double x0, double y0, double x1, double y1) {
        int n = 0;
        for (const auto& p : P) n += p.x >= x0 && p.x <= x1 && p.y >= y0 && p.y <= y1;
        return n;
    };
    EXPECT_GE(in(40, 2, 60, 2.5), 2);  // 20 mm strip: at least two points
    EXPECT_GE(in(53, 53, 67, 67), 4);  // ring
    // The 30 x 30 mm square: at least one point per 5 mm bin it touches
    // (7 x 7, the bins are fixed in space), and not one per cell.
    int square = in(2, 2, 32, 32);
    EXPECT_GE(square, 36);
    EXPECT_LE(square, 2 * 8 * 8);
}

TEST(OverhangPoints, SmallRegionStillGetsOnePoint) {
    auto l0 = make_layer(0.2, 0.2, -1, true);
    line(l0, 0, 0, 20, 20);
    auto l1 = make_layer(0.4, 0.2, 0);
    line(l1, 0, 0, 20, 20);
    auto st = stack_of({l0, l1});
    Settings s;
    layers::BitGrid g = layers::make_grid(st, s.resolution, 2.0);
    g.draw_disc(12.5, 12.5, 0.6);  // about 1.1 mm^2, inside one 5 mm bin
    overhang::Overhangs o;
    o.layers.push_back({1, g, static_cast<double>(g.count()) * g.cell_area()});
    auto pts = overhang::place_points(o, st, s);
    ASSERT_EQ(pts.points.size(), 1u);
    EXPECT_NEAR(pts.points[0].x, 12.5, 0.1);
    EXPECT_NEAR(pts.points[0].y, 12.5, 0.1);
    EXPECT_TRUE(g.get(g.col(pts.points[0].x), g.row(pts.points[0].y)));
}
