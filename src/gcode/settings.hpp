#pragma once
// One immutable struct of every setting, built once: the slicer's config
// block in the file, then SLIC3R_* environment variables, then the command
// line. Every stage takes it by const reference.
#include <map>
#include <string>

#include "gcode/program.hpp"

namespace scaffold {

enum class Method { Scaffold, Pillars, None };

struct Settings {
    // --- printer and material (from the slicer) ---
    double nozzle_diameter = 0.4;
    double filament_diameter = 1.75;  // E's unit: 2/sqrt(pi) when E is volumetric (mm^3)
    // Volumetric E: the filament the spool holds (the file's stated diameter,
    // else 1.75 mm), for totals and reports in mm of filament.
    double spool_diameter = 1.75;
    double layer_height = 0.2;
    double first_layer_height = 0.2;
    bool relative_e = false;          // the config's setting; the reader tracks M82/M83
    bool firmware_retraction = false;
    double retract_length = 0.8;      // mm of filament
    double retract_speed_mm_s = 35;
    double deretract_speed_mm_s = 0;  // 0 = same as retract
    double retract_lift = 0;          // z-hop mm
    double retract_before_travel = 2; // retract only for travels longer than this
    double travel_speed_mm_s = 130;
    double support_speed_mm_s = 60;
    double bridge_speed_mm_s = 60;
    double first_layer_speed_mm_s = 30;
    double bridge_fan_percent = 100;
    double bed_min_x = 0, bed_min_y = 0, bed_max_x = 250, bed_max_y = 210;
    bool bed_stated = false;          // the file gives its bed (else the box above is a guess)
    double temperature = 210, first_layer_temperature = 215, bed_temperature = 60;
    double slicer_max_bridge = 10;    // bridge limit for slicer-marked bridges
    bool spiral_vase = false;
    double fuzzy_skin_mm = 0;         // fuzzy skin's jitter, mm (0 = off)
    bool sequential_printing = false;

    // --- detection ---
    double resolution = 0.1;          // raster cell mm
    double overhang_angle_deg = 55;
    // METHOD's rule (b): a straight bead spans an unheld run between held
    // ends up to max_bridge (any bead: slicers print unmarked skin lines
    // across such gaps), a slicer-marked bridge up to marked_bridge_limit.
    double max_bridge = 10;
    double marked_bridge_limit = 30;
    double min_overhang_area = 1.0;   // mm^2
    double point_spacing = 5.0;       // mm
    double point_radius = 3.5;        // mm a point holds around itself

    // --- support geometry ---
    Method method = Method::Scaffold;
    double xy_gap = 0.5;
    int top_gap_layers = 0;
    double pillar_radius = 1.0;
    double tip_radius = 0.5;
    double tip_length = 2.0;
    double foot_radius = 2.5;
    double foot_height = 2.5;
    double raft_size = 7.0;
    double slenderness = 20.0;        // max pillar height / diameter
    double min_stiffness = 2.0;       // N/mm at every support island's top (METHOD's Standing rule); 0: not sized for it
    double modulus = 3500.0;          // N/mm^2, the filament's Young's modulus (PLA)
    double support_width = 0.45;      // extrusion width of support lines
    bool buildplate_only = false;

    // --- scaffolding planner (Dumas / Tupek constants) ---
    double bridge_min_length = 5.0;
    double bridge_max_length = 30.0;
    double bridge_min_drop = 2.0;     // point at least this far above the bridge
    double bridge_max_offset = 5.0;   // point at most this far sideways
    double bridge_height_step = 1.0;
    int sweep_directions = 8;

    // --- program ---
    std::string source;               // where the config came from, for the header
    std::string filament_note;        // set when the file's extrusion overrode the stated diameter
};

// Raw key/value settings in priority order; later layers override earlier.
using SettingMap = std::map<std::string, std::string>;

// Collects SLIC3R_* environment variables as lower-case keys (hook mode).
SettingMap settings_from_environment();

// Builds the struct from the file's config, the environment and overrides.
// Throws scaffold::Error for values that cannot be numbers.
Settings build_settings(const gcode::Program& program, const SettingMap& environment,
                        const SettingMap& overrides);

}  // namespace scaffold
