#include <gtest/gtest.h>

#include "gcode/error.hpp"
#include "gcode/reader.hpp"
#include "gcode/settings.hpp"

using namespace scaffold;

namespace {
gcode::Program load(const std::string& name) { return gcode::read_file(std::string(SCAFFOLD_TEST_DATA) + "/dialects/" + name); }
}  // namespace

TEST(Config, PrusaSlicer) {
    auto p = load("prusaslicer25.gcode");
    EXPECT_EQ(p.dialect, gcode::Dialect::PrusaSlicer);
    Settings s = build_settings(p, {}, {});
    EXPECT_DOUBLE_EQ(s.nozzle_diameter, 0.4);
    EXPECT_DOUBLE_EQ(s.filament_diameter, 1.75);
    EXPECT_DOUBLE_EQ(s.layer_height, 0.2);
    EXPECT_DOUBLE_EQ(s.first_layer_height, 0.2);
    EXPECT_DOUBLE_EQ(s.retract_length, 2);
    EXPECT_DOUBLE_EQ(s.retract_speed_mm_s, 40);
    EXPECT_DOUBLE_EQ(s.travel_speed_mm_s, 130);
    EXPECT_DOUBLE_EQ(s.bed_max_x, 250);
    EXPECT_DOUBLE_EQ(s.bed_max_y, 210);
    EXPECT_DOUBLE_EQ(s.temperature, 210);
    EXPECT_DOUBLE_EQ(s.first_layer_temperature, 215);
    EXPECT_FALSE(s.relative_e);
    EXPECT_FALSE(s.firmware_retraction);
    EXPECT_FALSE(s.spiral_vase);
}

TEST(Config, Slic3rTrailer) {
    auto p = load("slic3r13.gcode");
    EXPECT_EQ(p.dialect, gcode::Dialect::Slic3r);
    Settings s = build_settings(p, {}, {});
    EXPECT_DOUBLE_EQ(s.retract_length, 2);
    EXPECT_DOUBLE_EQ(s.retract_speed_mm_s, 40);
    EXPECT_DOUBLE_EQ(s.travel_speed_mm_s, 130);
    EXPECT_DOUBLE_EQ(s.support_speed_mm_s, 60);
    EXPECT_DOUBLE_EQ(s.bed_max_y, 210);
    EXPECT_DOUBLE_EQ(s.filament_diameter, 1.75);
}

TEST(Config, CuraHeaderAndObservedRetraction) {
    auto p = load("cura413.gcode");
    EXPECT_EQ(p.dialect, gcode::Dialect::Cura);
    Settings s = build_settings(p, {}, {});
    EXPECT_DOUBLE_EQ(s.layer_height, 0.2);
    EXPECT_EQ(p.config.at("machine_gcode_flavor"), "Marlin");
    // The CLI-sliced file has no settings block: retraction is read off its moves.
    EXPECT_NEAR(s.retract_length, 6.5, 1e-6);
}

TEST(Config, CuraSetting3Block) {
    auto p = load("cura413-settings.gcode");
    Settings s = build_settings(p, {}, {});
    EXPECT_DOUBLE_EQ(s.layer_height, 0.16);
    EXPECT_DOUBLE_EQ(s.first_layer_height, 0.24);
    EXPECT_DOUBLE_EQ(s.retract_length, 6.5);
    EXPECT_DOUBLE_EQ(s.retract_lift, 0.3);
    EXPECT_DOUBLE_EQ(s.travel_speed_mm_s, 150);
    EXPECT_DOUBLE_EQ(s.support_speed_mm_s, 50);
    EXPECT_DOUBLE_EQ(s.nozzle_diameter, 0.6);
    EXPECT_DOUBLE_EQ(s.temperature, 205);
}

TEST(Config, OrcaSlicerBlock) {
    auto p = load("orcaslicer.gcode");
    EXPECT_EQ(p.dialect, gcode::Dialect::OrcaSlicer);
    Settings s = build_settings(p, {}, {});
    EXPECT_TRUE(s.relative_e);
    EXPECT_TRUE(p.saw_relative_e);
    EXPECT_TRUE(p.saw_arcs);
    EXPECT_DOUBLE_EQ(s.retract_lift, 0.4);
    EXPECT_DOUBLE_EQ(s.travel_speed_mm_s, 300);
    EXPECT_DOUBLE_EQ(s.support_speed_mm_s, 80);
    EXPECT_DOUBLE_EQ(s.bed_max_x, 256);
    EXPECT_DOUBLE_EQ(s.temperature, 220);
    EXPECT_DOUBLE_EQ(s.first_layer_temperature, 225);
    EXPECT_DOUBLE_EQ(s.bed_temperature, 55);
    EXPECT_FALSE(s.sequential_printing);
}

TEST(Config, SuperSlicerPercentFirstLayerAndFirmwareRetraction) {
    auto p = load("superslicer.gcode");
    EXPECT_EQ(p.dialect, gcode::Dialect::SuperSlicer);
    Settings s = build_settings(p, {}, {});
    EXPECT_DOUBLE_EQ(s.nozzle_diameter, 0.5);
    EXPECT_DOUBLE_EQ(s.filament_diameter, 2.85);
    EXPECT_NEAR(s.first_layer_height, 0.3, 1e-12);
    EXPECT_TRUE(s.firmware_retraction);
    EXPECT_TRUE(p.saw_firmware_retraction);
    EXPECT_DOUBLE_EQ(s.bed_max_x, 235);
}

TEST(Config, EnvironmentThenCommandLineOverride) {
    auto p = load("prusaslicer25.gcode");
    SettingMap env{{"retract_length", "1.5"}, {"travel_speed", "200"}};
    SettingMap cli{{"retract_length", "2.5"}, {"--xy-gap", "0.7"}};
    Settings s = build_settings(p, env, cli);
    EXPECT_DOUBLE_EQ(s.retract_length, 2.5);
    EXPECT_DOUBLE_EQ(s.travel_speed_mm_s, 200);
    EXPECT_DOUBLE_EQ(s.xy_gap, 0.7);
}

TEST(Config, BadNumbersAndRefusedModesAreReported) {
    auto p = load("prusaslicer25.gcode");
    EXPECT_THROW(build_settings(p, {}, {{"--xy-gap", "abc"}}), Error);
    EXPECT_THROW(build_settings(p, {{"nozzle_diameter", "x"}}, {}), Error);
    EXPECT_THROW(build_settings(p, {}, {{"--method", "magic"}}), Error);
    Settings vase = build_settings(p, {}, {{"spiral_vase", "1"}});
    EXPECT_TRUE(vase.spiral_vase);
    Settings seq = build_settings(p, {}, {{"complete_objects", "1"}});
    EXPECT_TRUE(seq.sequential_printing);
}

// Cura's delta and centred beds: machine_center_is_zero puts the origin in
// the middle of machine_width x machine_depth. A file that states no bed
// at all leaves the guess, marked as one.
TEST(Config, CentredCuraBedAndUnstatedBed) {
    const std::string body = "G28\nG1 Z0.2 F3000\nG1 X0 Y0 F3000\nG1 X10 Y0 E1 F1200\n";
    const auto centred = gcode::parse(";FLAVOR:Marlin\n;Generated with Cura_SteamEngine 4.13.1\n" + body +
                                          "; machine_width = 250\n; machine_depth = 200\n; machine_center_is_zero = True\n",
                                      "centred.gcode");
    Settings s = build_settings(centred, {}, {});
    EXPECT_TRUE(s.bed_stated);
    EXPECT_DOUBLE_EQ(s.bed_min_x, -125);
    EXPECT_DOUBLE_EQ(s.bed_max_x, 125);
    EXPECT_DOUBLE_EQ(s.bed_min_y, -100);
    EXPECT_DOUBLE_EQ(s.bed_max_y, 100);
    const auto plain = gcode::parse(";FLAVOR:Marlin\n;Generated with Cura_SteamEngine 4.13.1\n" + body +
                                        "; machine_width = 250\n; machine_depth = 200\n",
                                    "plain.gcode");
    s = build_settings(plain, {}, {});
    EXPECT_DOUBLE_EQ(s.bed_min_x, 0);
    EXPECT_DOUBLE_EQ(s.bed_max_x, 250);
    const auto none = gcode::parse(body, "none.gcode");
    EXPECT_FALSE(build_settings(none, {}, {}).bed_stated);
}

// Fuzzy skin, as PrusaSlicer and OrcaSlicer say it (where, how far) and as
// Cura does (whether, how far); off without a word.
TEST(Config, FuzzySkin) {
    const std::string body = "G28\nG1 Z0.2 F3000\nG1 X0 Y0 F3000\nG1 X10 Y0 E1 F1200\n";
    auto fuzz = [&](const std::string& config) {
        return build_settings(gcode::parse(body + config, "fuzzy.gcode"), {}, {}).fuzzy_skin_mm;
    };
    EXPECT_DOUBLE_EQ(fuzz("; fuzzy_skin = external\n; fuzzy_skin_thickness = 0.25\n"), 0.25);
    EXPECT_DOUBLE_EQ(fuzz("; fuzzy_skin = all\n"), 0.3);
    EXPECT_DOUBLE_EQ(fuzz("; fuzzy_skin = none\n; fuzzy_skin_thickness = 0.25\n"), 0);
    EXPECT_DOUBLE_EQ(fuzz("; magic_fuzzy_skin_enabled = True\n; magic_fuzzy_skin_thickness = 0.4\n"), 0.4);
    EXPECT_DOUBLE_EQ(fuzz("; magic_fuzzy_skin_enabled = False\n"), 0);
    EXPECT_DOUBLE_EQ(fuzz(""), 0);
}
