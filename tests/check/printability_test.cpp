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

TEST(Check, PillarInsideTheSparseInfillCollides) {
    // A 20 mm hole of a part's sparse infill: a pillar in the middle keeps
    // clear of every bead but is inside the part. The same hole walled by
    // perimeters alone is a cavity of the model (a cup, a dome's inside):
    // the pillar keeps the gap, no collision.
    auto scene = [](const char* walls) {
        SynthGcode g;
        for (int l = 1; l <= 20; ++l) {
            g.layer(0.2 * l);
            g.type(walls);
            g.rect_outline(100, 100, 120, 120);
            g.type("Support material");
            g.rect_outline(109, 109, 111, 111);
        }
        return run(g);
    };
    auto infill = scene("Internal infill");
    EXPECT_FALSE(infill.ok());
    // 18 layers of the 2 mm square loop (the top two are its tips), a ring
    // between squares 2.45 and 1.55 mm across: 18 x (6.0025 - 2.4025) =
    // 64.8 mm^2, less the cells whose centres fall just outside.
    EXPECT_GT(infill.collision_mm2, 50.0);
    EXPECT_LE(infill.collision_mm2, 64.8);
    auto cavity = scene("External perimeter");
    EXPECT_EQ(cavity.collision_mm2, 0.0) << check::report_text(cavity);
}

TEST(Check, SupportPrintedTwiceIsMeasured) {
    // The same 2 mm support square twice per layer (two paths, a travel
    // between) beside a cube: the second retraces the first.
    auto build = [](bool twice) {
        SynthGcode g;
        for (int l = 1; l <= 5; ++l) {
            g.layer(0.2 * l);
            g.type("External perimeter");
            g.filled_rect(100, 100, 110, 110);
            g.type("Support material");
            g.rect_outline(120, 120, 122, 122);
            if (twice) g.rect_outline(120, 120, 122, 122);
        }
        return run(g);
    };
    auto once = build(false), two = build(true);
    EXPECT_LT(once.support_overlap_mm2, 0.05);
    // A 2 mm square's outline is 8 mm of bead; its core (half of 0.45 mm)
    // is about 1.8 mm^2 a layer, 5 layers.
    EXPECT_GT(two.support_overlap_mm2, 5.0);
    EXPECT_LT(two.support_overlap_mm2, 12.0);
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

namespace {

// The cube with a short untyped bead beside it inserted before every layer
// change but the first; `restore_e` puts the E register back afterwards.
std::string cube_with_inserts(bool restore_e) {
    std::string text = cube(10).str(), out, last_e = "0";
    std::size_t pos = 0;
    int layer = 0;
    while (pos < text.size()) {
        std::size_t nl = text.find('\n', pos);
        std::string line = text.substr(pos, nl - pos + 1);
        if (line == ";LAYER_CHANGE\n" && layer++ > 0) {
            out += "G92 E0\nG1 X120 Y105 F7800\nG1 X121 Y105 E0.05\nG1 X121 Y106 E0.1\n";
            if (restore_e) out += "G92 E" + last_e + "\n";
        }
        if (line.rfind("G1 ", 0) == 0 && line.find(" E") != std::string::npos)
            last_e = line.substr(line.find(" E") + 2, line.find_first_of(" \n", line.find(" E") + 2) - line.find(" E") - 2);
        out += line;
        pos = nl + 1;
    }
    return out;
}

}  // namespace

TEST(Check, InsertedLinesCountAsSupport) {
    auto i = gcode::parse(cube(10).str(), "in.gcode");
    auto o = gcode::parse(cube_with_inserts(true), "out.gcode");
    auto r = check::check(o, &i, {});
    EXPECT_TRUE(r.model_unchanged) << check::report_text(r);
    EXPECT_EQ(r.model_moves_changed, 0);
    // 9 inserts of 0.05 + 0.05 mm of filament, none of it the model's.
    EXPECT_NEAR(r.support_filament_mm, 0.9, 1e-4);
    EXPECT_NEAR(r.model_filament_mm, i.moves.empty() ? 0 : check::check(i, nullptr, {}).model_filament_mm, 1e-3);
}

TEST(Check, InsertWithoutRestoringStateChangesTheModel) {
    // Same text for every model line, but the E register is left at 0.1: the
    // next model bead would push (or pull) the whole difference.
    auto i = gcode::parse(cube(10).str(), "in.gcode");
    auto o = gcode::parse(cube_with_inserts(false), "out.gcode");
    auto r = check::check(o, &i, {});
    EXPECT_EQ(r.model_lines_missing, 0);
    EXPECT_GE(r.model_moves_changed, 9);  // at least the first E move after each insert
    EXPECT_FALSE(r.model_unchanged);
    EXPECT_FALSE(r.ok());
}

TEST(Check, ShortMoveWithLargeEIsAJump) {
    SynthGcode g = cube(5);
    g.raw("G1 X100.1 Y100 E200 F1800");  // 0.1 mm of motion, ~150 mm of filament
    auto r = run(g);
    EXPECT_EQ(r.e_jumps, 1) << check::report_text(r);
    EXPECT_FALSE(r.ok());
    // A prime that gives back a retraction is no jump.
    SynthGcode p = cube(5);
    p.raw("G1 E-5 F2100");
    p.raw("G1 X100 Y101 F7800");
    p.raw("G1 E0 F2100");
    EXPECT_EQ(run(p).e_jumps, 0);
}

TEST(Check, CircleOverhangIsNoStraightBridge) {
    // A 10 x 30 tower, then a 96-gon loop of radius 12 around its centre: it
    // rests on the tower over two 10 mm arcs and crosses air over two arcs
    // of 27 mm. Each side turns 3.75 deg, but the arcs turn 131 deg: no
    // straight span, so they are unheld (about 2 x 27 mm x 0.45 mm).
    SynthGcode g;
    for (int l = 1; l <= 20; ++l) {
        g.layer(0.2 * l);
        g.type("External perimeter");
        g.filled_rect(120, 90, 130, 120);
    }
    g.layer(4.2);
    g.type("Overhang perimeter");
    g.circle(125, 105, 12);
    auto r = run(g);
    EXPECT_FALSE(r.ok());
    EXPECT_GT(r.unheld_model_mm2, 18);
    EXPECT_LT(r.unheld_model_mm2, 27);
    ASSERT_FALSE(r.worst_unheld.empty());
    EXPECT_NEAR(r.worst_unheld[0].z, 4.2, 1e-6);
}

TEST(Check, SkirtEnclosesNothing) {
    // A 2 mm square with a skirt loop 10 mm around it, then a 10 mm square on
    // top: the skirt must not fill the space inside it.
    SynthGcode g;
    g.layer(0.2);
    g.type("Skirt/Brim");
    g.rect_outline(105, 95, 125, 115);
    g.type("External perimeter");
    g.filled_rect(114, 104, 116, 106);
    g.layer(0.4);
    g.filled_rect(110, 100, 120, 110);
    auto r = run(g);
    EXPECT_FALSE(r.ok());
    // 10.45 x 10.45 mm^2 of bead printed; what lies within reach of the
    // 2 mm square (about 3 x 3 mm) is held.
    EXPECT_GT(r.unheld_model_mm2, 95);
    EXPECT_LT(r.unheld_model_mm2, 105);
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

// METHOD's rule (b): an unmarked straight bead spans a gap between held
// ends up to --max-bridge (10 mm); a marked bridge up to 30 mm.
TEST(Check, UnmarkedSpanHeldUpToMaxBridge) {
    auto short_plain = run(towers_and_deck(8, "Solid infill"));
    EXPECT_TRUE(short_plain.ok()) << check::report_text(short_plain);
    auto long_plain = run(towers_and_deck(15, "Solid infill"));
    EXPECT_FALSE(long_plain.ok());
    EXPECT_GT(long_plain.unheld_model_mm2, 20);
    auto long_marked = run(towers_and_deck(15, "Bridge infill"));
    EXPECT_TRUE(long_marked.ok()) << check::report_text(long_marked);
    check::CheckOptions tight;
    tight.max_bridge = 5;
    auto out = gcode::parse(towers_and_deck(8, "Solid infill").str(), "out.gcode");
    EXPECT_FALSE(check::check(out, nullptr, tight).ok());
}

// The top of a round hole (a benchy's hawse hole): a short straight piece
// between two corner moves that turn off it. The corners are held within a
// dangling end, so the piece is held at both ends and spans the hole.
TEST(Check, StraightPieceBetweenHeldCornersSpans) {
    SynthGcode g;
    for (int l = 1; l <= 21; ++l) {
        g.layer(0.2 * l);
        g.type("External perimeter");
        if (l <= 20) {
            g.filled_rect(100, 100, 105, 110);
            g.filled_rect(109, 100, 114, 110);
        } else {
            // Corner pieces 0.3 mm long leave the towers' edges at a slant.
            g.travel(104.6, 105);
            g.extrude(104.9, 105.3);
            g.extrude(108.7, 105.3);  // straight over the 4 mm hole
            g.extrude(109.0, 105);
        }
    }
    auto r = run(g);
    EXPECT_TRUE(r.ok()) << check::report_text(r);
}

// The slicer's purge before the first layer is its own business: a large E
// without motion there is reported, not failed; the same in the print fails.
TEST(Check, StartCodePurgeIsNoFailure) {
    SynthGcode g;
    g.raw("G1 Z0.3 F600");
    g.raw("G1 E20 F300 ; prime blob");
    g.raw("G92 E0");
    for (int l = 1; l <= 5; ++l) {
        g.layer(0.2 * l);
        g.type("External perimeter");
        g.filled_rect(100, 100, 110, 110);
    }
    auto r = run(g);
    EXPECT_TRUE(r.ok()) << check::report_text(r);
    EXPECT_EQ(r.start_code_problems, 1);
    EXPECT_EQ(r.e_jumps, 0);
    SynthGcode mid = g;
    mid.raw("G1 E500 F300");  // far past what the layers extruded
    auto bad = run(mid);
    EXPECT_FALSE(bad.ok());
    EXPECT_EQ(bad.e_jumps, 1);
}

// With --original, what the original did itself on lines the edit left
// alone is reported apart; only what the edit added or broke fails.
TEST(Check, OriginalsOwnProblemsAreNoFailure) {
    SynthGcode g = cube(6);
    g.raw("G1 E500 F300");  // a flush after the print, far past what the layers extruded
    const std::string original = g.str();
    auto alone = run(g);
    EXPECT_FALSE(alone.ok());
    auto compared = run(g, &original);
    EXPECT_TRUE(compared.ok()) << check::report_text(compared);
    EXPECT_EQ(compared.original_problems, 1);
}

namespace {

// A 2 x 2 mm sheet at layer 11 (z 2.2) with nothing beneath it and a
// support pillar (a small filled square, layers 1..10) at (px, 102); the
// sheet's next layer reaches out over the pillar where it stands beside it.
SynthGcode sheet_on_a_tip(double px) {
    SynthGcode g;
    for (int l = 1; l <= 12; ++l) {
        g.layer(0.2 * l);
        g.type("External perimeter");
        g.filled_rect(80, 100, 90, 110);  // a tower that keeps the layers going
        if (l <= 10) {
            g.type("Support material");
            g.filled_rect(px - 0.4, 101.6, px + 0.4, 102.4);
        } else {
            g.type("Solid infill");
            g.filled_rect(103, 101, l == 11 || px < 105 ? 105 : 107, 103);
        }
    }
    return g;
}

}  // namespace

// METHOD's rule (c): a tip holds the sheet that rests on it, 3.5 mm around;
// a tip that touches the model only a layer higher holds nothing below it.
TEST(Check, TipHoldsOnlyTheSheetRestingOnIt) {
    auto under = run(sheet_on_a_tip(104));
    EXPECT_EQ(under.unheld_model_mm2, 0) << check::report_text(under);
    // Beside the first sheet, under the second only: all of the first sheet
    // lies within 3.5 mm of it, but it rests on nothing.
    auto beside = run(sheet_on_a_tip(106.2));
    EXPECT_FALSE(beside.ok());
    ASSERT_FALSE(beside.worst_unheld.empty());
    EXPECT_NEAR(beside.worst_unheld[0].z, 2.2, 1e-6);
}

// A tool change's purge (Bambu's M620..M621 flush of the old filament) is
// the slicer's own: reported apart, not failed.
TEST(Check, ToolChangePurgeIsNoFailure) {
    SynthGcode g = cube(5);
    g.raw("M620 S1A");
    g.raw("T1");
    g.raw("G1 E500 F300 ; flush");
    g.raw("M621 S1A");
    auto r = run(g);
    EXPECT_TRUE(r.ok()) << check::report_text(r);
    EXPECT_EQ(r.start_code_problems, 1);
    EXPECT_EQ(r.e_jumps, 0);
}

// A file sliced with support on: the slicer's support stands on a layer of
// air over the model and within the XY gap of a wall. Those faults are the
// original's: with --original they are reported apart, and the model it
// holds (the sheet across the contact gap) is held.
TEST(Check, SlicersOwnSupportFaultsAreTheOriginals) {
    const SynthGcode g = scaffold::testing::on_slicer_support("Support material");
    auto alone = run(g);
    EXPECT_FALSE(alone.ok());
    EXPECT_GT(alone.unheld_support_mm2, 10);
    EXPECT_GT(alone.collision_mm2, 0);
    EXPECT_EQ(alone.unheld_model_mm2, 0) << check::report_text(alone);
    const std::string original = g.str();
    auto compared = run(g, &original);
    EXPECT_TRUE(compared.ok()) << check::report_text(compared);
    EXPECT_GT(compared.original_unheld_support_mm2, 10);
    EXPECT_GT(compared.original_collision_mm2, 0);
    EXPECT_EQ(compared.unheld_support_mm2, 0);
    EXPECT_EQ(compared.collision_mm2, 0);
    // Without the original, scaffold's own output says what it added (its
    // header and blocks): the rest of the support is the slicer's.
    const std::string header = "; scaffold 0.1.0 (post-processed supports)\n";
    auto marked = check::check(gcode::parse(header + original, "out.gcode"), nullptr, {});
    EXPECT_TRUE(marked.ok()) << check::report_text(marked);
    EXPECT_GT(marked.original_unheld_support_mm2, 10);
    // ... and what it added in mid-air still fails.
    SynthGcode more = g;
    more.layer(3.4);
    more.raw("; scaffold: support for the layer at Z3.4");
    more.type("Support material");
    more.travel(130, 130);
    more.extrude(136, 130);
    more.raw("; scaffold: end");
    auto floating = check::check(gcode::parse(header + more.str(), "out.gcode"), nullptr, {});
    EXPECT_FALSE(floating.ok());
    EXPECT_GT(floating.unheld_support_mm2, 2);
}

// PrusaSlicer before 2.2 writes no ;LAYER_CHANGE; Prusa's profiles put
// ;BEFORE_LAYER_CHANGE before each layer. The intro line at the first
// layer's own height, before the first of them, is start code.
TEST(Check, IntroLineBeforeTheFirstBeforeLayerChangeIsStartCode) {
    std::string s = "; generated by PrusaSlicer 2.1.1\nG90\nM83\nG92 E0\nG1 X5 Y5 F1000\nG1 Z0.2\n";
    s += "G1 X60 E9 F1000 ; intro line\nG1 X100 E12.5 F1000 ; intro line\nG92 E0\nG1 Z10\n";
    for (int l = 1; l <= 5; ++l) {
        const std::string z = std::to_string(0.2 * l);
        s += ";BEFORE_LAYER_CHANGE\nG92 E0.0\n;" + z + "\nG1 Z" + z + " F7800\n;AFTER_LAYER_CHANGE\n";
        for (int k = 0; k < 22; ++k) {
            const std::string y = std::to_string(100 + 0.45 * k);
            s += "G1 X100 Y" + y + " F3000\nG1 X110 Y" + y + " E0.37 F1500\n";
        }
    }
    s += "; layer_height = 0.2\n; first_layer_height = 0.2\n; nozzle_diameter = 0.4\n; filament_diameter = 1.75\n";
    s += "; bed_shape = 0x0,250x0,250x210,0x210\n";
    auto r = check::check(gcode::parse(s, "prusa21.gcode"), nullptr, {});
    EXPECT_TRUE(r.ok()) << check::report_text(r);
    EXPECT_EQ(r.start_code_problems, 2);
    EXPECT_EQ(r.e_jumps, 0);
}


// A file that states no bed (CuraEngine's command line writes none) is
// judged on a guess: 250 x 210 from the origin, grown to hold the slicer's
// own extrusions and 10 mm around them. A delta's cube around the origin
// with a 2 mm support ring beside it passes; the same ring 30 mm off, at
// x -55 (under the guess and past the margin), is outside the bed.
TEST(Check, AnUnstatedBedHoldsTheSlicersOwnExtrusions) {
    auto unstated = [](double ring_x) {
        SynthGcode g;
        for (int l = 1; l <= 3; ++l) {
            g.layer(0.2 * l);
            g.type("External perimeter");
            g.filled_rect(-20, -5, -10, 5);
            if (ring_x != 0) {
                g.type("Support material");
                g.circle(ring_x, 0, 0.775, 24);
            }
        }
        std::string text = g.str();
        const std::size_t at = text.find("; bed_shape = ");
        text.erase(at, text.find('\n', at) + 1 - at);
        return text;
    };
    const std::string in = unstated(0);
    for (double x : {-24.0, -55.0}) {
        const std::string out_text = unstated(x);
        const auto out = gcode::parse(out_text, "out.gcode");
        const auto orig = gcode::parse(in, "in.gcode");
        const check::CheckReport r = check::check(out, &orig, {});
        if (x == -24.0) EXPECT_EQ(r.outside_bed, 0) << check::report_text(r);
        else EXPECT_GT(r.outside_bed, 0) << check::report_text(r);
    }
}

// METHOD reports unheld area per model, and the tolerance for raster noise
// is per model too: two cubes 30 mm apart are two models, each with a
// 0.4 mm bead on layer 21 floating 0.5 mm off its side (beyond the 0.34 mm
// a layer reaches out, within the 1 mm that joins a footprint: part of the
// cube's model; every unheld cell counted: no speck rule). Each speck is
// a capsule of 0.4 x 0.45 + pi 0.225^2 = 0.339 mm^2 (a little more in 0.1
// mm cells): the file holds more than the 0.5 mm^2 tolerance, no model does.
// Both specks beside one cube: that model holds them all and fails.
TEST(Check, TheUnheldToleranceIsPerModel) {
    auto plate = [](bool beside_one) {
        SynthGcode g;
        for (int l = 1; l <= 21; ++l) {
            g.layer(0.2 * l);
            g.type("External perimeter");
            g.filled_rect(100, 100, 110, 110);
            g.filled_rect(140, 100, 150, 110);
            if (l == 21) {
                g.travel(110.95, 104.8);
                g.extrude(110.95, 105.2);
                const double x = beside_one ? 110.95 : 150.95, y = beside_one ? 107.7 : 104.7;
                g.travel(x, y);
                g.extrude(x, y + 0.4);
            }
        }
        return g;
    };
    check::CheckOptions o;
    o.min_region_mm2 = 0;
    auto run_with = [&](const SynthGcode& g) { return check::check(gcode::parse(g.str(), "out.gcode"), nullptr, o); };
    const auto two = run_with(plate(false));
    EXPECT_EQ(two.models, 2);
    EXPECT_NEAR(two.unheld_regions_mm2, 2 * 0.339, 0.08);
    EXPECT_NEAR(two.unheld_worst_model_mm2, two.unheld_regions_mm2 / 2, 0.02);
    EXPECT_TRUE(two.ok()) << check::report_text(two);
    const auto one = run_with(plate(true));
    EXPECT_EQ(one.models, 2);
    EXPECT_NEAR(one.unheld_worst_model_mm2, one.unheld_regions_mm2, 1e-9);
    EXPECT_GT(one.unheld_worst_model_mm2, 0.5);
    EXPECT_FALSE(one.ok());
    ASSERT_FALSE(one.failures.empty());
    EXPECT_NE(one.failures.front().find("on one of 2 models"), std::string::npos) << one.failures.front();
}
