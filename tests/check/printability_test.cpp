#include <gtest/gtest.h>

#include <cmath>

#include "check/printability.hpp"
#include "gcode/reader.hpp"
#include "support/synth.hpp"

using namespace scaffold;
using scaffold::testing::SynthGcode;

namespace {

check::CheckReport run(const SynthGcode& g, const std::string* original_text = nullptr) {
    auto out = gcode::parse(g.str(), "out.gcode");
    if (!original_text) return check::check(out, nullptr, {});
    auto orig = gcode::parse(*original_text, "in.gcode");
    return check::check(out, &orig, {});
}

SynthGcode cube(int layers = 20) {
    SynthGcode g;
    for (int l = 1; l <= layers; ++l) {
        g.layer(0.2 * l);
        g.type("External perimeter");
        g.filled_rect(100, 100, 110, 110);
    }
    return g;
}

// Two 5 x 10 towers `gap` mm apart, then a deck across both at layer 21.
SynthGcode towers_and_deck(double gap, const char* deck_role) {
    SynthGcode g;
    for (int l = 1; l <= 22; ++l) {
        g.layer(0.2 * l);
        if (l <= 20) {
            g.type("External perimeter");
            g.filled_rect(100, 100, 105, 110);
            g.filled_rect(105 + gap, 100, 110 + gap, 110);
        } else {
            g.type(deck_role);
            // Straight lines across the gap, each held by both towers.
            for (double y = 100.5; y < 110; y += 0.45) {
                g.travel(101, y);
                g.extrude(109 + gap, y);
            }
        }
    }
    return g;
}

}  // namespace

TEST(Check, CubePasses) {
    auto r = run(cube());
    EXPECT_TRUE(r.ok()) << check::report_text(r);
    EXPECT_EQ(r.unheld_model_mm2, 0);
    EXPECT_EQ(r.layers, 20);
    EXPECT_GT(r.model_filament_mm, 0);
}

TEST(Check, FloatingExtrusionFails) {
    SynthGcode g = cube();
    g.layer(4.2);
    g.type("External perimeter");
    g.filled_rect(100, 100, 110, 110);
    g.filled_rect(115, 100, 125, 110);  // 5 mm beside the cube, nothing under it
    auto r = run(g);
    EXPECT_FALSE(r.ok());
    EXPECT_GT(r.unheld_regions_mm2, 80);
    ASSERT_FALSE(r.worst_unheld.empty());
    EXPECT_NEAR(r.worst_unheld[0].z, 4.2, 1e-6);
    EXPECT_NEAR(r.worst_unheld[0].x, 120, 1.0);
}

TEST(Check, ShortMarkedBridgePassesLongSpanFails) {
    auto ok = run(towers_and_deck(10, "Bridge infill"));
    EXPECT_TRUE(ok.ok()) << check::report_text(ok);
    auto bad = run(towers_and_deck(40, "Bridge infill"));
    EXPECT_FALSE(bad.ok());
    EXPECT_GT(bad.unheld_regions_mm2, 100);
}

TEST(Check, PillarThroughTheModelCollides) {
    SynthGcode g;
    for (int l = 1; l <= 20; ++l) {
        g.layer(0.2 * l);
        g.type("External perimeter");
        g.filled_rect(100, 100, 110, 110);
        g.type("Support material");
        g.rect_outline(109, 104, 111, 106);  // straddles the cube's wall
    }
    auto r = run(g);
    EXPECT_FALSE(r.ok());
    EXPECT_GT(r.collision_mm2, 1.0);
}

TEST(Check, EJumpFails) {
    SynthGcode g = cube(5);
    g.raw("G1 E50 F2400");  // 45+ mm of filament pushed without motion
    auto r = run(g);
    EXPECT_FALSE(r.ok());
    EXPECT_EQ(r.e_jumps, 1);
}

TEST(Check, ChangedModelLineFails) {
    SynthGcode a = cube(5);
    std::string original = a.str();
    std::string changed = original;
    std::size_t at = changed.find("G1 X110.000 Y100.000");
    ASSERT_NE(at, std::string::npos);
    changed.replace(at, 20, "G1 X110.500 Y100.000");
    auto out = gcode::parse(changed, "out.gcode");
    auto orig = gcode::parse(original, "in.gcode");
    auto r = check::check(out, &orig, {});
    EXPECT_FALSE(r.model_unchanged);
    EXPECT_FALSE(r.ok());
    // The same file against itself is unchanged and passes.
    auto same = check::check(orig, &orig, {});
    EXPECT_TRUE(same.model_unchanged);
    EXPECT_TRUE(same.ok()) << check::report_text(same);
}

TEST(Check, InsertedLinesCountAsSupport) {
    SynthGcode a = cube(10);
    std::string original = a.str();
    // A pillar beside the cube, inserted without any role comment.
    SynthGcode b = cube(10);
    std::string text = b.str();
    std::string out;
    std::size_t pos = 0;
    int layer = 0;
    while (pos < text.size()) {
        std::size_t nl = text.find('\n', pos);
        std::string line = text.substr(pos, nl - pos + 1);
        if (line == ";LAYER_CHANGE\n" && layer++ > 0)
            out += "G1 X120 Y105 F7800\nG1 X121 Y105 E0.05\nG1 X121 Y106 E0.1\n";
        out += line;
        pos = nl + 1;
    }
    auto o = gcode::parse(out, "out.gcode");
    auto i = gcode::parse(original, "in.gcode");
    auto r = check::check(o, &i, {});
    EXPECT_TRUE(r.model_unchanged);
    EXPECT_GT(r.support_filament_mm, 0.1);
}

TEST(Check, TrapezoidTimeOfOneMove) {
    // 100 mm at F6000 (100 mm/s), 1000 mm/s^2: accelerate 0.1 s over 5 mm,
    // cruise 90 mm in 0.9 s, decelerate 0.1 s: 1.1 s.
    auto p = gcode::parse("M204 S1000\nG1 X0 Y0 F6000\nG1 X100 Y0 F6000\n", "t");
    EXPECT_NEAR(check::estimate_print_time(p), 1.1, 1e-6);
    // Too short to reach speed: a triangle, 2 * sqrt(d / a).
    auto q = gcode::parse("M204 S1000\nG1 X0 Y0 F6000\nG1 X4 Y0 F6000\n", "t");
    EXPECT_NEAR(check::estimate_print_time(q), 2 * std::sqrt(4.0 / 1000), 1e-6);
    // Two collinear halves take as long as the whole: no stop between them.
    auto h = gcode::parse("M204 S1000\nG1 X0 Y0 F6000\nG1 X50 Y0 F6000\nG1 X100 Y0 F6000\n", "t");
    EXPECT_NEAR(check::estimate_print_time(h), 1.1, 1e-6);
    // A right-angle corner slows to the junction speed sqrt(a*jd*s/(1-s)), s = sin(45 deg).
    auto c = gcode::parse("M204 S1000\nG1 X0 Y0 F6000\nG1 X50 Y0 F6000\nG1 X50 Y50 F6000\n", "t");
    double s45 = std::sqrt(0.5), vj = std::sqrt(1000 * 0.013 * s45 / (1 - s45));
    double leg = (100 - 0) / 1000.0 + (100 - vj) / 1000.0 + (50 - (1e4 / 2000) - (1e4 - vj * vj) / 2000) / 100;
    EXPECT_NEAR(check::estimate_print_time(c), 2 * leg, 1e-6);
}
