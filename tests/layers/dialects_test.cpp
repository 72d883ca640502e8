// Small synthetic reproductions of what real slicers' files do (the files
// themselves are in ../shared/corpus/wild, tested by cli.wild when present):
// each test builds the feature by hand so the suite keeps its meaning
// without them.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <string>

#include "gcode/reader.hpp"
#include "gcode/settings.hpp"
#include "layers/layer_stack.hpp"
#include "overhang/overhangs.hpp"
#include "support/synth.hpp"

using namespace scaffold;
using scaffold::testing::SynthGcode;

namespace {

struct Parsed {
    gcode::Program program;
    Settings settings;
    layers::LayerStack stack;
};

Parsed parse(const std::string& text, const SettingMap& options = {}) {
    Parsed p{gcode::parse(text, "t.gcode"), {}, {}};
    p.settings = build_settings(p.program, {}, options);
    p.stack = layers::build_layers(p.program, p.settings);
    return p;
}

// Everything but the config block's "; key = value" lines, as a slicer
// hands a file without its settings.
std::string without_config(const std::string& text) {
    std::string out;
    std::size_t pos = 0;
    while (pos < text.size()) {
        std::size_t nl = text.find('\n', pos);
        std::string line = text.substr(pos, nl - pos);
        if (!(line.rfind("; ", 0) == 0 && line.find(" = ") != std::string::npos)) out += line + "\n";
        pos = nl == std::string::npos ? text.size() : nl + 1;
    }
    return out;
}

// Absolute E, one extrusion per line, `e_per_mm` filament per mm.
std::string square_layers(int layers, double h, double e_per_mm, const std::string& hint) {
    std::string s = "M82\nG92 E0\n";
    double e = 0;
    for (int l = 1; l <= layers; ++l) {
        s += hint + "\nG1 Z" + std::to_string(h * l) + " F600\nG1 X10 Y10 F6000\n";
        const double pts[4][2] = {{30, 10}, {30, 30}, {10, 30}, {10, 10}};
        for (const auto& p : pts) {
            e += 20 * e_per_mm;
            s += "G1 X" + std::to_string(p[0]) + " Y" + std::to_string(p[1]) + " E" + std::to_string(e) + "\n";
        }
    }
    return s;
}

}  // namespace

// Bambu Studio / OrcaSlicer: firmware syntax in M1002, AMS commands, their
// feature and layer comments.
TEST(Dialects, BambuHeaderAndComments) {
    std::string text =
        "; HEADER_BLOCK_START\n; BambuStudio 01.07.06.92\n; HEADER_BLOCK_END\n"
        "M1002 gcode_claim_action : 2\nM1002 set_gcode_claim_speed_level : 5\nM624 AQAAAAAAAAA=\nM625\n"
        "M83\n; CHANGE_LAYER\n; Z_HEIGHT: 0.2\n; LAYER_HEIGHT: 0.2\n; FEATURE: Outer wall\n"
        "G1 Z0.2 F600\nG1 X10 Y10\nG1 X30 Y10 E1\nG1 X30 Y30 E1\n"
        "; CHANGE_LAYER\n; Z_HEIGHT: 0.4\n; LAYER_HEIGHT: 0.2\n; FEATURE: Bridge\n"
        "G1 Z0.4\nG1 X10 Y10 E1\n";
    Parsed p = parse(text);
    ASSERT_EQ(p.program.layer_hints.size(), 2u);
    EXPECT_NEAR(p.program.layer_hints[1].z, 0.4, 1e-9);
    ASSERT_EQ(p.stack.layers.size(), 2u);
    EXPECT_EQ(p.stack.layers[0].segments.front().role, gcode::Role::ExternalPerimeter);
    EXPECT_EQ(p.stack.layers[1].segments.front().role, gcode::Role::BridgeInfill);
}

// PrusaSlicer's Prusa profiles: the intro line at Z 0.2 under a 0.3 mm
// first layer is start code, resting on the bed, no layer to support on.
TEST(Dialects, IntroLineBelowTheFirstLayerRestsOnTheBed) {
    SynthGcode g(0.3);
    g.raw("G1 Z0.2 F720");
    g.raw("G1 X60 Y-3 F1000");
    g.raw("G1 X100 Y-3 E12 F1000 ; intro line");
    g.raw("G92 E0");
    for (int l = 1; l <= 4; ++l) {
        g.layer(0.3 * l);
        g.filled_rect(100, 100, 110, 110);
    }
    Parsed p = parse(g.str());
    ASSERT_EQ(p.stack.layers.size(), 5u);
    EXPECT_TRUE(p.stack.layers[0].purge);
    EXPECT_TRUE(p.stack.layers[1].on_bed);
    EXPECT_FALSE(p.stack.layers[1].purge);
    EXPECT_TRUE(overhang::find_overhangs(p.stack, p.settings).layers.empty());
}

// Bambu's start code purges at Z 0.2, then draws a line at 0.3, then the
// first layer comes at 0.2: both purges are start code.
TEST(Dialects, StartCodeAtTwoHeightsBeforeTheFirstMarkedLayer) {
    std::string text = "M83\nG1 Z0.2\nG1 X10 Y0\nG1 X60 Y0 E3\nG1 Z0.3\nG1 X60 Y1\nG1 X10 Y1 E3\n" +
                       square_layers(3, 0.2, 0.033, ";LAYER_CHANGE");
    // square_layers writes absolute E after M82: the purge above is relative.
    Parsed p = parse(text);
    ASSERT_EQ(p.stack.layers.size(), 5u);
    EXPECT_TRUE(p.stack.layers[0].purge);
    EXPECT_TRUE(p.stack.layers[1].purge);
    EXPECT_TRUE(p.stack.layers[2].on_bed);
    EXPECT_EQ(p.stack.layers[3].below, 2);
}

// MatterControl with software levelling: Z follows the bed's mesh within
// each layer. Layers come from the comments, at their nominal heights.
TEST(Dialects, BedLevellingInTheFileLayersByComments) {
    std::string s = "M82\nG92 E0\n";
    double e = 0;
    for (int l = 0; l < 5; ++l) {
        s += "; LAYER:" + std::to_string(l) + "\n; LAYER_HEIGHT:0.2\n";
        for (int k = 0; k <= 40; ++k) {
            const double x = 10 + k * 0.5, z = 0.2 * (l + 1) + 0.02 * std::sin(k * 0.3) + 0.5;  // mesh offset
            e += 0.02;
            s += "G1 X" + std::to_string(x) + " Y20 Z" + std::to_string(z) + " E" + std::to_string(e) + "\n";
        }
    }
    Parsed p = parse(s);
    EXPECT_TRUE(p.stack.z_varies);
    ASSERT_EQ(p.stack.layers.size(), 5u);
    for (int l = 0; l < 5; ++l) EXPECT_NEAR(p.stack.layers[l].z, 0.2 * (l + 1), 1e-9) << l;
    EXPECT_FALSE(layers::z_motion(p.program).spiral());
}

// A spiral vase rises through its extrusions and never falls: recognised
// without any setting (Cura hands its scripts none).
TEST(Dialects, SpiralVaseRecognisedByRisingZ) {
    std::string s = "M82\nG92 E0\n;LAYER:0\n";
    double e = 0;
    for (int k = 0; k < 2000; ++k) {
        const double a = k * 2 * std::numbers::pi / 100;
        e += 0.03;
        s += "G1 X" + std::to_string(50 + 10 * std::cos(a)) + " Y" + std::to_string(50 + 10 * std::sin(a)) + " Z" +
             std::to_string(0.2 + k * 0.002) + " E" + std::to_string(e) + "\n";
    }
    Parsed p = parse(s);
    EXPECT_TRUE(layers::z_motion(p.program).spiral());
    EXPECT_FALSE(p.stack.z_varies);
    Parsed flat = parse(square_layers(5, 0.2, 0.033, ";LAYER_CHANGE"));
    EXPECT_FALSE(layers::z_motion(flat.program).spiral());
}

// Cura 4.9 and earlier escape the settings' newlines twice.
TEST(Dialects, CuraSettingsEscapedTwice) {
    std::string s = square_layers(2, 0.2, 0.033, ";LAYER:0");
    s += ";SETTING_3 {\"global_quality\": \"[general]\\\\nversion = 4\\\\n[values]\\\\nmagic_spiralize = True\\\\nmat\n";
    s += ";SETTING_3 erial_diameter = 2.85\\\\n\\\\n\"}\n";
    Parsed p = parse(s);
    EXPECT_TRUE(p.settings.spiral_vase);
    EXPECT_EQ(p.program.config.at("material_diameter"), "2.85");
}

// Layer comments of Simplify3D, Kiri:Moto and KISSlicer are layer hints.
TEST(Dialects, LayerCommentsOfOtherSlicers) {
    for (const char* hint : {"; layer 1, Z = 0.300", ";; --- layer 0 (0.250 @ 0.255) ---",
                             "; BEGIN_LAYER_OBJECT z=0.263 z_thickness=0.263"}) {
        Parsed p = parse(square_layers(3, 0.2, 0.033, hint));
        EXPECT_EQ(p.program.layer_hints.size(), 3u) << hint;
    }
    Parsed k = parse(square_layers(2, 0.263, 0.033, "; BEGIN_LAYER_OBJECT z=0.263 z_thickness=0.263"));
    EXPECT_NEAR(k.program.layer_hints[0].height, 0.263, 1e-9);
}

// KISSlicer slices each object on a Z grid of its own: A at 0.263, 0.526,
// B at 0.278, 0.556. B's first layer rests on the bed (its stated height
// reaches it), and A's second layer stands on A's first, not on B's.
TEST(Dialects, ObjectsOnZGridsOfTheirOwn) {
    std::string s = "M82\nG92 E0\n";
    double e = 0;
    auto square = [&](double x0, double z, double h) {
        s += "; BEGIN_LAYER_OBJECT z=" + std::to_string(z) + " z_thickness=" + std::to_string(h) + "\n";
        s += "G1 Z" + std::to_string(z) + "\nG1 X" + std::to_string(x0) + " Y10\n";
        for (double y = 10.2; y < 20; y += 0.4) {
            e += 10 * 0.033;
            s += "G1 X" + std::to_string(x0 + 10) + " Y" + std::to_string(y) + " E" + std::to_string(e) + "\n";
            s += "G1 X" + std::to_string(x0) + " Y" + std::to_string(y + 0.2) + "\n";
        }
    };
    for (int l = 1; l <= 4; ++l) {
        square(10, 0.263 * l, 0.263);
        square(40, 0.278 * l, 0.278);
    }
    Parsed p = parse(s);
    ASSERT_EQ(p.stack.layers.size(), 8u);
    EXPECT_TRUE(p.stack.layers[0].on_bed);
    EXPECT_TRUE(p.stack.layers[1].on_bed);
    EXPECT_FALSE(p.stack.layers[2].on_bed);
    const auto& a2 = p.stack.layers[2];  // A at 0.526: beneath are A at 0.263 and B at 0.278
    EXPECT_NE(std::find(a2.beneath.begin(), a2.beneath.end(), 0), a2.beneath.end());
    EXPECT_TRUE(overhang::find_overhangs(p.stack, p.settings).layers.empty());
}

// Support extrusion follows the model's own lines, not a guessed diameter.
TEST(Dialects, FilamentDiameterFromTheModelsLines) {
    for (double d : {1.75, 2.85}) {
        SynthGcode g(0.2, 0.45, d);
        for (int l = 1; l <= 8; ++l) {
            g.layer(0.2 * l);
            g.filled_rect(100, 100, 120, 120);
        }
        Parsed stated = parse(g.str());
        EXPECT_DOUBLE_EQ(stated.settings.filament_diameter, d);
        EXPECT_TRUE(stated.settings.filament_note.empty()) << stated.settings.filament_note;
        Parsed bare = parse(without_config(g.str()));
        EXPECT_DOUBLE_EQ(bare.settings.filament_diameter, d);
        EXPECT_DOUBLE_EQ(bare.settings.spool_diameter, d);
        EXPECT_EQ(bare.settings.filament_note.empty(), d == 1.75) << bare.settings.filament_note;
        // A stated diameter the lines contradict (2.65x the area) gives way.
        Parsed wrong = parse(g.str(), {{"filament_diameter", d == 1.75 ? "2.85" : "1.75"}});
        EXPECT_DOUBLE_EQ(wrong.settings.filament_diameter, d);
        EXPECT_FALSE(wrong.settings.filament_note.empty());
    }
    // Volumetric E (Cura UltiGCode, M200): mm^3, a "diameter" of area 1.
    SynthGcode v(0.2, 0.45, 2 / std::sqrt(std::numbers::pi));
    for (int l = 1; l <= 8; ++l) {
        v.layer(0.2 * l);
        v.filled_rect(100, 100, 120, 120);
    }
    Parsed vol = parse(without_config(v.str()));
    EXPECT_NEAR(std::numbers::pi * vol.settings.filament_diameter * vol.settings.filament_diameter / 4, 1.0, 1e-9);
    // Totals and reports stay in mm of the spool's filament: the stated one,
    // else 1.75 mm.
    EXPECT_DOUBLE_EQ(vol.settings.spool_diameter, 1.75);
    Parsed vol285 = parse(without_config(v.str()), {{"filament_diameter", "2.85"}});
    EXPECT_NEAR(std::numbers::pi * vol285.settings.filament_diameter * vol285.settings.filament_diameter / 4, 1.0, 1e-9);
    EXPECT_DOUBLE_EQ(vol285.settings.spool_diameter, 2.85);
}

// RepRapFirmware's G10 P0 S195 R160 sets temperatures: no firmware retraction.
TEST(Dialects, RepRapToolSettingIsNoRetraction) {
    Parsed p = parse("G10 P0 S195 R160\nM83\n" + square_layers(2, 0.2, 0.033, ";LAYER_CHANGE").substr(4));
    EXPECT_FALSE(p.program.saw_firmware_retraction);
    Parsed fw = parse("G10\nG11\n" + square_layers(2, 0.2, 0.033, ";LAYER_CHANGE"));
    EXPECT_TRUE(fw.program.saw_firmware_retraction);
}

// Relative E with no M83 in the file (the firmware's default): recognised
// by E stepping back on half the beads when read as absolute.
TEST(Dialects, RelativeEWithoutM83) {
    SynthGcode g;
    for (int l = 1; l <= 6; ++l) {
        g.layer(0.2 * l);
        g.filled_rect(100, 100, 110, 110);
    }
    // The same file with relative E: each E word becomes its step.
    const std::string abs_text = g.str();
    std::string rel;
    double last = 0;
    std::size_t pos = 0;
    while (pos < abs_text.size()) {
        std::size_t nl = abs_text.find('\n', pos);
        std::string line = abs_text.substr(pos, nl - pos);
        pos = nl + 1;
        if (line.rfind("M82", 0) == 0) continue;
        std::size_t e = line.find(" E");
        if (line.rfind("G92", 0) == 0 && e != std::string::npos) {
            last = std::stod(line.substr(e + 2));
            continue;
        }
        if (line.rfind("G1", 0) == 0 && e != std::string::npos) {
            std::size_t end = line.find(' ', e + 1);
            const double v = std::stod(line.substr(e + 2, end == std::string::npos ? std::string::npos : end - e - 2));
            line = line.substr(0, e) + " E" + std::to_string(v - last) + (end == std::string::npos ? "" : line.substr(end));
            last = v;
        }
        rel += line + "\n";
    }
    Parsed a = parse(abs_text), b = parse(rel), c = parse("M83\n" + rel);
    EXPECT_FALSE(a.program.relative_e_at_start);
    EXPECT_TRUE(b.program.relative_e_at_start);
    EXPECT_FALSE(c.program.relative_e_at_start);  // said so: nothing to guess
    ASSERT_EQ(a.program.moves.size(), b.program.moves.size());
    for (std::size_t i = 0; i < a.program.moves.size(); ++i) {
        EXPECT_EQ(a.program.moves[i].kind, b.program.moves[i].kind) << i;
        EXPECT_NEAR(a.program.moves[i].e, b.program.moves[i].e, 1e-5) << i;
    }
}

// A file with no comments at all (no roles, no layer comments, no config)
// and one with thumbnails (long base64 comment lines) before the header.
TEST(Dialects, NoCommentsAndThumbnails) {
    std::string bare = square_layers(6, 0.2, 0.033, "");
    Parsed p = parse(bare);
    EXPECT_EQ(p.stack.layers.size(), 6u);
    EXPECT_TRUE(p.program.layer_hints.empty());
    std::string thumb = "; thumbnail begin 300x300 4096\n";
    for (int k = 0; k < 50; ++k) thumb += "; " + std::string(78, 'A') + "\n";
    thumb += "; thumbnail end\n";
    Parsed t = parse(thumb + square_layers(6, 0.2, 0.033, ";LAYER_CHANGE"));
    EXPECT_EQ(t.stack.layers.size(), 6u);
    EXPECT_TRUE(t.stack.layers[0].on_bed);
}

// Bed levelling baked into the file: the mesh is read off the model's own
// moves, and support spliced into such a file follows it.
TEST(Dialects, SupportFollowsTheBedMeshOfALevelledFile) {
    auto offset = [](double x, double y) { return 0.5 + 0.02 * (x - 100) - 0.01 * (y - 100); };
    std::string s = "M82\nG92 E0\n";
    double e = 0;
    for (int l = 0; l < 8; ++l) {
        s += "; LAYER:" + std::to_string(l) + "\n; LAYER_HEIGHT:0.2\n";
        const double zn = 0.2 * (l + 1);
        for (double y = 100; y <= 110; y += 0.5) {
            const double xa = (static_cast<int>(y * 2) % 2) ? 140 : 100, xb = xa == 100 ? 140 : 100;
            s += "G1 X" + std::to_string(xa) + " Y" + std::to_string(y) + " Z" + std::to_string(zn + offset(xa, y)) + " F6000\n";
            for (int k = 1; k <= 8; ++k) {
                const double x = xa + (xb - xa) * k / 8;
                e += 5 * 0.033;
                s += "G1 X" + std::to_string(x) + " Y" + std::to_string(y) + " Z" + std::to_string(zn + offset(x, y)) + " E" +
                     std::to_string(e) + " F1800\n";
            }
        }
    }
    Parsed p = parse(s);
    ASSERT_TRUE(p.stack.z_varies);
    ASSERT_FALSE(p.stack.mesh.empty());
    for (double x : {102.0, 120.0, 138.0})
        for (double y : {101.0, 109.0}) EXPECT_NEAR(p.stack.mesh.at(x, y), offset(x, y), 0.03) << x << "," << y;
    // Beside the model (a pillar's loop 1 mm past its edge) the tilt goes on.
    for (double x : {99.0, 141.0})
        for (double y : {99.0, 111.0}) EXPECT_NEAR(p.stack.mesh.at(x, y), offset(x, y), 0.02) << x << "," << y;
    // Further out (a foot 5 mm past the edge) it goes on at the plane fitted
    // to all the moves: here the bed's own tilt, 0.02 and -0.01 mm per mm.
    EXPECT_NEAR(p.stack.mesh.tilt_x, 0.02, 1e-4);
    EXPECT_NEAR(p.stack.mesh.tilt_y, -0.01, 1e-4);
    EXPECT_NEAR(p.stack.mesh.at(146, 105) - p.stack.mesh.at(144, 105), 2 * 0.02, 1e-9);
    EXPECT_NEAR(p.stack.mesh.at(120, 95) - p.stack.mesh.at(120, 93), -2 * 0.01, 1e-9);
}

// Sequential printing (complete objects) without its setting: one object up
// to 4 mm, then the next from the bed. Objects side by side on their own Z
// grids (KISSlicer) or a levelled bed's offsets never come back this far.
TEST(Dialects, SequentialPrintingRecognisedByZ) {
    SynthGcode seq(0.2, 0.45, 1.75);
    for (int object = 0; object < 2; ++object)
        for (int l = 1; l <= 20; ++l) {
            seq.layer(0.2 * l);
            seq.filled_rect(100 + 30 * object, 100, 110 + 30 * object, 110);
        }
    EXPECT_TRUE(layers::z_motion(parse(seq.str()).program).restarts);
    SynthGcode together(0.2, 0.45, 1.75);
    for (int l = 1; l <= 20; ++l) {
        together.layer(0.2 * l);
        together.filled_rect(100, 100, 110, 110);
        together.filled_rect(130, 100, 140, 110);
    }
    EXPECT_FALSE(layers::z_motion(parse(together.str()).program).restarts);
}

namespace {

// The role of each extruding move, in order.
std::vector<gcode::Role> extrusion_roles(const Parsed& p) {
    std::vector<gcode::Role> roles;
    for (const auto& m : p.program.moves)
        if (m.kind == gcode::MoveKind::Extrude) roles.push_back(m.role);
    return roles;
}

}  // namespace

// Simplify3D names each feature in a comment line of its own, from 4.1 on
// after the word "feature".
TEST(Dialects, Simplify3DFeatureComments) {
    std::string s = "; G-Code generated by Simplify3D(R) Version 4.1.2\n;   layerHeight,0.2\nM82\nG92 E0\n";
    s += "; layer 1, Z = 0.2\nG1 Z0.2\nG1 X10 Y10\n";
    const char* features[] = {"outer perimeter", "feature support", "bridge", "feature dense support", "gap fill"};
    double e = 0;
    for (int k = 0; k < 5; ++k) {
        s += std::string("; ") + features[k] + "\n";
        e += 0.3;
        s += "G1 X" + std::to_string(20 + 10 * k) + " Y10 E" + std::to_string(e) + "\n";
    }
    EXPECT_EQ(extrusion_roles(parse(s)), (std::vector<gcode::Role>{gcode::Role::ExternalPerimeter, gcode::Role::Support, gcode::Role::BridgeInfill,
                                               gcode::Role::SupportInterface, gcode::Role::SolidInfill}));
}

// Kiri:Moto writes "; feature <type>" on each change of type: its walls
// ("shells") are walls, which hole seeds stay out of (read as unknown, a
// benchy's cabin walls filled the cabin), its support is support, and a
// type not known ends the one before.
TEST(Dialects, KiriMotoFeatureComments) {
    std::string s = "; Generated by Kiri:Moto 3.8.3\nM83\n;; --- layer 0 (0.250 @ 0.250) ---\nG1 Z0.25\nG1 X10 Y10\n";
    for (const char* f : {"shells", "support", "sparse infill", "solid fill", "brim", "sparse"}) {
        s += std::string("; feature ") + f + "\n";
        s += "G1 X20 Y10 E0.3\nG1 X10 Y10\n";
    }
    EXPECT_EQ(extrusion_roles(parse(s)),
              (std::vector<gcode::Role>{gcode::Role::Perimeter, gcode::Role::Support, gcode::Role::InternalInfill,
                                        gcode::Role::SolidInfill, gcode::Role::Skirt, gcode::Role::Unknown}));
}

// KISSlicer names each path in a comment: its support and raft are support.
TEST(Dialects, KisslicerPathComments) {
    std::string s = "; KISSlicer - FREE version 2 a 2.0.6 Win64\nM83\n; BEGIN_LAYER_OBJECT z=0.263 z_thickness=0.263\nG1 Z0.263\nG1 X10 Y10\n";
    for (const char* f : {"'Perimeter Path', 20.0 [feed mm/s], 30.0 [head mm/s]", "'Support (may Stack) Path'",
                          "'Destring/Wipe/Jump Path', 1.0 [feed mm/s]", "'Support Interface Path', 1.9 [feed mm/s]"}) {
        s += std::string("; ") + f + "\n";
        s += "G1 X20 Y10 E0.3\nG1 X10 Y10\n";
    }
    EXPECT_EQ(extrusion_roles(parse(s)), (std::vector<gcode::Role>{gcode::Role::ExternalPerimeter, gcode::Role::Support, gcode::Role::Unknown,
                                               gcode::Role::SupportInterface}));
}

