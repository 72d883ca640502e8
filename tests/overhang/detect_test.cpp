#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "check/printability.hpp"
#include "gcode/reader.hpp"
#include "layers/layer_stack.hpp"
#include "overhang/overhangs.hpp"
#include "support/synth.hpp"

using namespace scaffold;
using scaffold::testing::SynthGcode;

namespace {

struct Found {
    layers::LayerStack stack;
    overhang::Overhangs overhangs;
    overhang::SupportPoints points;
};

Found detect(const SynthGcode& g, const SettingMap& options = {}) {
    auto p = gcode::parse(g.str(), "synth");
    Settings s = build_settings(p, {}, options);
    Found f;
    f.stack = layers::build_layers(p, s);
    f.overhangs = overhang::find_overhangs(f.stack, s);
    f.points = overhang::place_points(f.overhangs, f.stack, s);
    return f;
}

// Every overhang cell within the point radius of a point of its layer.
void expect_covered(const Found& f, double radius) {
    for (const auto& ol : f.overhangs.layers) {
        const auto& g = ol.cells;
        for (int j = 0; j < g.height(); ++j)
            for (int i = 0; i < g.width(); ++i) {
                if (!g.get(i, j)) continue;
                bool covered = false;
                for (const auto& p : f.points.points)
                    if (p.layer == ol.layer && std::hypot(p.x - g.cx(i), p.y - g.cy(j)) <= radius + 1e-9) covered = true;
                ASSERT_TRUE(covered) << "cell " << g.cx(i) << "," << g.cy(j) << " layer " << ol.layer;
            }
    }
}

SynthGcode chamfer(double offset_per_layer, double layer_height = 0.2) {
    SynthGcode g(layer_height);
    for (int l = 1; l <= 20; ++l) {
        g.layer(layer_height * l);
        g.filled_rect(100, 100, 110 + offset_per_layer * (l - 1), 112);
    }
    return g;
}

double offset_for(double angle_deg, double layer_height) {
    return layer_height * std::tan(angle_deg * std::numbers::pi / 180);
}

// Two towers with a gap from x = 105 to x = 105 + gap, then a deck over both
// whose first layer is `lines` of the given role, drawn by `line`.
template <class Line>
SynthGcode towers_and_deck(double gap, const char* role, Line line) {
    SynthGcode g;
    const double x1 = 110 + gap;
    for (int l = 1; l <= 24; ++l) {
        g.layer(0.2 * l);
        if (l <= 20) {
            g.filled_rect(100, 100, 105, 110);
            g.filled_rect(105 + gap, 100, x1, 110);
        } else if (l == 21) {
            g.type(role);
            for (double y = 100.3; y < 109.95; y += 0.4) line(g, 100.3, x1 - 0.3, y);
        } else {
            g.type("Solid infill");
            g.filled_rect(100, 100, x1, 110);
        }
    }
    return g;
}

// A straight line printed as many short moves, as slicers write bridges
// that cross other paths or were fitted from arcs.
void line_in_moves(SynthGcode& g, double xa, double xb, double y) {
    g.travel(xa, y);
    for (double x = xa + 0.7; x < xb; x += 0.7) g.extrude(x, y);
    g.extrude(xb, y);
}

// A wavy line: every move turns by about 40 degrees, so no straight piece.
void wavy_line(SynthGcode& g, double xa, double xb, double y) {
    g.travel(xa, y);
    int k = 0;
    for (double x = xa + 0.7; x < xb; x += 0.7) g.extrude(x, y + (++k % 2 ? 0.125 : -0.125));
    g.extrude(xb, y);
}

SynthGcode deck(const char* role, double gap = 8) {
    SynthGcode g;  // two towers `gap` mm apart, then a deck across both
    for (int l = 1; l <= 25; ++l) {
        g.layer(0.2 * l);
        if (l <= 20) {
            g.filled_rect(100, 100, 105, 110);
            g.filled_rect(105 + gap, 100, 110 + gap, 110);
        } else {
            g.type(l == 21 ? role : "Solid infill");
            g.filled_rect(100, 100, 110 + gap, 110);
        }
    }
    return g;
}

// Straight on the towers, and over the 8 mm gap a shallow arc (1 mm
// sagitta, 12 moves of about 4 deg each; the whole arc turns 50 deg).
void arc_line(SynthGcode& g, double xa, double xb, double y) {
    const double a0 = 104.5, a1 = 113.5;
    const double c = a1 - a0, h = 1.0, r = (c * c / 4 + h * h) / (2 * h);
    const double half = std::asin(c / 2 / r), cx = (a0 + a1) / 2, cy = y + h - r;
    g.travel(xa, y);
    g.extrude(a0, y);
    for (int k = 1; k <= 12; ++k) {
        double a = std::numbers::pi / 2 + half - 2 * half * k / 12;
        g.extrude(cx + r * std::cos(a), cy + r * std::sin(a));
    }
    g.extrude(xb, y);
}

}  // namespace

TEST(OverhangDetect, ShelfFoundAtItsFirstLayerAndCovered) {
    SynthGcode g;
    for (int l = 1; l <= 30; ++l) {
        g.layer(0.2 * l);
        g.filled_rect(100, 100, 110, 110);
        if (l > 20) g.filled_rect(110, 100, 120, 110);
    }
    Found f = detect(g);
    ASSERT_FALSE(f.overhangs.layers.empty());
    EXPECT_NEAR(f.stack.layers[f.overhangs.layers.front().layer].z, 4.2, 1e-6);
    EXPECT_EQ(f.overhangs.layers.size(), 1u);  // the layers above rest on the first shelf layer
    EXPECT_GT(f.overhangs.area_mm2, 80);       // about 10 x 10 mm, less what the wall holds
    EXPECT_LT(f.overhangs.area_mm2, 105);
    EXPECT_GE(f.points.points.size(), 4u);
    for (const auto& p : f.points.points) {
        EXPECT_NEAR(p.z, 4.0, 1e-6);
        EXPECT_GT(p.x, 110);  // on the shelf, over air
    }
    expect_covered(f, 3.5);
}

// A bead is held where its centre line is within reach of the layer
// below's footprint (METHOD.md's rule, which scaffold-check applies with
// h*tan(55 deg) + half a cell; detection uses half a cell less so raster
// alignment never decides). The footprint reaches half a bead past the wall's
// centre line, so at 0.45 mm beads and 0.2 mm layers walls up to about 66 deg
// print unsupported: a 45 deg chamfer gets no points, a 72 deg one does.
TEST(OverhangDetect, ChamferAt45DegreesNeedsNothingAt72DegreesItDoes) {
    Found a = detect(chamfer(0.2 * std::tan(45 * std::numbers::pi / 180)));
    EXPECT_TRUE(a.points.points.empty()) << a.points.points.size() << " points at 45 deg";
    Found c = detect(chamfer(0.2 * std::tan(72 * std::numbers::pi / 180)));
    EXPECT_GE(c.points.points.size(), 10u);
    expect_covered(c, 3.5);
}

// METHOD's rule (b): any straight bead spans up to --max-bridge (10 mm)
// between held ends, a slicer-marked bridge up to 30 mm.
TEST(OverhangDetect, MarkedBridgeHeldUnmarkedSpanIsNot) {
    Found marked = detect(deck("Bridge infill", 15));
    EXPECT_TRUE(marked.points.points.empty()) << marked.points.points.size();
    Found short_plain = detect(deck("Solid infill", 8));
    EXPECT_TRUE(short_plain.points.points.empty()) << short_plain.points.points.size();
    Found plain = detect(deck("Solid infill", 15));
    EXPECT_GE(plain.points.points.size(), 2u);
    for (const auto& p : plain.points.points) {
        EXPECT_GT(p.x, 105);
        EXPECT_LT(p.x, 120);
    }
    // --max-bridge 5: the 8 mm unmarked span is too long.
    Found tight_plain = detect(deck("Solid infill", 8), {{"--max-bridge", "5"}});
    EXPECT_GE(tight_plain.points.points.size(), 2u);
}

TEST(OverhangDetect, MushroomCapGetsPointsAllRoundTheStem) {
    SynthGcode g;
    for (int l = 1; l <= 30; ++l) {
        g.layer(0.2 * l);
        g.filled_disc(110, 105, l > 20 ? 8.0 : 2.5);
    }
    Found f = detect(g);
    int quadrant[4] = {0, 0, 0, 0};
    for (const auto& p : f.points.points) {
        EXPECT_GT(std::hypot(p.x - 110, p.y - 105), 2.5);
        quadrant[(p.x > 110 ? 1 : 0) + (p.y > 105 ? 2 : 0)]++;
    }
    for (int q = 0; q < 4; ++q) EXPECT_GE(quadrant[q], 1) << "quadrant " << q;
    expect_covered(f, 3.5);
}

TEST(OverhangDetect, SmallRegionsAreDroppedAndOutputIsDeterministic) {
    SynthGcode g;
    for (int l = 1; l <= 10; ++l) {
        g.layer(0.2 * l);
        g.filled_rect(100, 100, 110, 110);
        if (l > 5) g.filled_rect(110, 100, 110.6, 101.2);  // 0.6 x 1.2 mm tab: under 1 mm^2
    }
    Found f = detect(g);
    EXPECT_TRUE(f.points.points.empty());
    Found a = detect(chamfer(0.5)), b = detect(chamfer(0.5));
    ASSERT_EQ(a.points.points.size(), b.points.points.size());
    for (std::size_t i = 0; i < a.points.points.size(); ++i) {
        EXPECT_EQ(a.points.points[i].x, b.points.points[i].x);
        EXPECT_EQ(a.points.points[i].y, b.points.points[i].y);
        EXPECT_EQ(a.points.points[i].layer, b.points.points[i].layer);
    }
}

// A steep wall on thick layers, where METHOD.md's bead rule says it does
// not print (scaffold-check fails it unsupported): at 0.3 mm layers a bead's
// centre line is held up to 0.225 + 0.3 tan(55) + 0.05 = 0.70 mm past the
// centre line of the 0.45 mm bead below (its edge, the reach, half a cell);
// a 70 deg wall steps 0.3 tan(70) = 0.82 mm, a 65 deg one 0.64 (held).
TEST(OverhangDetect, ChamferAt70DegreesOnThickLayersGetsPoints) {
    EXPECT_TRUE(detect(chamfer(offset_for(65, 0.3), 0.3)).points.points.empty());
    SynthGcode g = chamfer(offset_for(70, 0.3), 0.3);
    Found f = detect(g);
    EXPECT_GE(f.points.points.size(), 10u);
    expect_covered(f, 3.5);
    for (const auto& p : f.points.points) EXPECT_GT(p.x, 110);  // on the sloping side
    auto program = gcode::parse(g.str(), "synth");
    EXPECT_GT(check::check(program, nullptr, check::CheckOptions{}).unheld_regions_mm2, 10);
}

// Detection against the validator over a sweep of wall angles at 0.2 mm
// layers: whatever scaffold-check finds unheld, detection has points for
// (never less support than needed); walls at or under the overhang angle get
// none; and once an angle needs points every steeper one does. A bead's
// centre line is held up to 0.225 + 0.2 tan(55) + 0.05 = 0.56 mm past the one
// below: walls up to 70.4 deg print.
TEST(OverhangDetect, ChamferSweepAgreesWithTheValidator) {
    bool needed_before = false;
    for (double deg = 40; deg <= 76; deg += 3) {
        SynthGcode g = chamfer(offset_for(deg, 0.2));
        Found f = detect(g);
        auto program = gcode::parse(g.str(), "synth");
        double unheld = check::check(program, nullptr, check::CheckOptions{}).unheld_regions_mm2;
        bool needs = !f.points.points.empty();
        if (unheld > 0) {
            EXPECT_TRUE(needs) << deg << " deg: validator finds " << unheld << " mm^2 unheld, no points";
        }
        if (deg <= 55) {
            EXPECT_FALSE(needs) << deg << " deg";
        }
        if (deg >= 73) {
            EXPECT_GT(unheld, 0) << deg << " deg";
        }
        if (needed_before) {
            EXPECT_TRUE(needs) << deg << " deg";
        }
        needed_before = needed_before || needs;
        if (needs) expect_covered(f, 3.5);
    }
}

TEST(OverhangDetect, MarkedBridgeSplitIntoShortMovesIsHeld) {
    Found split = detect(towers_and_deck(15, "Bridge infill", line_in_moves));
    EXPECT_TRUE(split.points.points.empty()) << split.points.points.size() << " points";
    // The same lines unmarked are an overhang over the gap (over 10 mm).
    Found plain = detect(towers_and_deck(15, "Solid infill", line_in_moves));
    EXPECT_GE(plain.points.points.size(), 2u);
    for (const auto& p : plain.points.points) {
        EXPECT_GT(p.x, 105);
        EXPECT_LT(p.x, 120);
    }
    expect_covered(plain, 3.5);
}

TEST(OverhangDetect, MarkedBridgeTooLongOrNotStraightGetsPoints) {
    // 32 mm between the towers: over the 30 mm limit of a marked bridge.
    Found longer = detect(towers_and_deck(32, "Bridge infill", line_in_moves));
    EXPECT_GE(longer.points.points.size(), 2u);
    expect_covered(longer, 3.5);
    // Within the limit but turning at every move: no straight span to hold it.
    Found wavy = detect(towers_and_deck(8, "Bridge infill", wavy_line));
    EXPECT_GE(wavy.points.points.size(), 2u);
    expect_covered(wavy, 3.5);
    for (const auto& p : wavy.points.points) {
        EXPECT_GT(p.x, 105);
        EXPECT_LT(p.x, 113);
    }
}

// Straight means within 10 deg of the piece's first direction, as the
// validator has it: a curved marked bridge whose moves each turn only 4 deg
// is no straight span, so its middle is overhang.
TEST(OverhangDetect, MarkedBridgeThatCurvesGetsPoints) {
    Found arc = detect(towers_and_deck(8, "Bridge infill", arc_line));
    std::size_t on_bridge = 0;
    for (const auto& p : arc.points.points) {
        if (std::abs(p.z - 4.0) > 1e-6) continue;
        ++on_bridge;
        EXPECT_GT(p.x, 105);
        EXPECT_LT(p.x, 113);
    }
    EXPECT_GE(on_bridge, 2u);
    expect_covered(arc, 3.5);
}

// A skirt loop holds what lies on it but encloses nothing: the air between
// the skirt and a small first layer is no filled footprint for the wider
// second layer (as scaffold-check has it).
TEST(OverhangDetect, SkirtEnclosesNothing) {
    SynthGcode g;
    g.layer(0.2);
    g.type("Skirt/Brim");
    g.rect_outline(94, 94, 116, 116);
    g.type("External perimeter");
    g.filled_rect(103, 103, 107, 107);
    for (int l = 2; l <= 6; ++l) {
        g.layer(0.2 * l);
        g.type("External perimeter");
        g.filled_rect(100, 100, 110, 110);
    }
    Found f = detect(g);
    ASSERT_EQ(f.overhangs.layers.size(), 1u);
    EXPECT_EQ(f.overhangs.layers[0].layer, 1);
    EXPECT_GT(f.overhangs.area_mm2, 60);  // 100 mm^2 less the 4 x 4 mm block and its reach
    EXPECT_GE(f.points.points.size(), 4u);
    expect_covered(f, 3.5);
}

// The slicer's own support holds the model resting on it across its contact
// gap (METHOD's three layers, rule (c)); that it stands on a layer of air
// itself is the slicer's choice, not scaffold's to support. Typed as model,
// the same beads overhang on both counts.
TEST(OverhangDetect, SlicersOwnSupportHoldsAndNeedsNothing) {
    const Found with = detect(scaffold::testing::on_slicer_support("Support material"));
    EXPECT_TRUE(with.points.points.empty()) << with.points.points.size() << " points, the first at layer "
                                            << with.points.points.front().layer;
    const Found as_model = detect(scaffold::testing::on_slicer_support("Solid infill"));
    bool floor = false, sheet = false;
    for (const auto& p : as_model.points.points) {
        floor |= p.layer == 6;  // layer 7, 0-based
        sheet |= p.layer == 14;
    }
    EXPECT_TRUE(floor);
    EXPECT_TRUE(sheet);
}
