#pragma once
// scaffold-check: an independent printability validator. It sees only
// G-code (never the planner), simulates deposition layer by layer on bit
// rasters and applies the rule of METHOD.md: a bead is held by (a) the filled
// layer beneath within the overhang angle, (b) a straight bridged span held
// at both ends, or (c) a support contact tip within the point radius.
#include <string>
#include <vector>

#include "check/standing.hpp"
#include "gcode/program.hpp"
#include "gcode/settings.hpp"

namespace scaffold::check {

struct CheckOptions {
    double overhang_angle_deg = 55;
    double xy_gap = 0.5;
    double point_radius = 3.5;
    // Straight spans held at both ends (METHOD's rule (b)): up to
    // bridge_limit for support and the slicer's marked bridges, up to
    // max_bridge for any other bead (< 0: the file's setting, else 10).
    double bridge_limit = 30;
    double max_bridge = -1;
    double dangling_end = 1.0;     // mm, unheld ends this short are held
    double resolution = 0.1;
    // Unheld area allowed per model (METHOD reports unheld area per model;
    // a plate's objects are the pieces of its model footprint,
    // layers::ObjectMap), for raster noise: a centre-line sample that falls
    // just outside the reach marks a bead stretch of one sample (0.1 mm x
    // 0.45 mm = 0.045 mm^2); 0.5 mm^2 is about a 1 mm stretch of one bead,
    // far below any real overhang (the corpus inputs have 36 to 1145 mm^2).
    double tolerance_mm2 = 0.5;
    // METHOD's speck rule, as the detector's --min-overhang-area applies it:
    // a lone unheld region smaller than this that continues no unheld region
    // a layer or two above or below does not count. 0: every cell counts.
    double min_region_mm2 = 1.0;
    int worst = 5;                 // worst layers listed
    StandingOptions standing;      // METHOD's second rule (check/standing.hpp)
};

struct LayerIssue {
    int layer = 0;
    double z = 0;
    double area_mm2 = 0;
    double x = 0, y = 0;           // centre of the issue's cells
};

struct CheckReport {
    std::string file;
    int layers = 0;
    double unheld_model_mm2 = 0;
    double unheld_support_mm2 = 0;
    double unheld_regions_mm2 = 0;  // in regions of at least min_region_mm2 (what fails)
    int models = 0;                 // objects on the plate (pieces of the model's footprint)
    double unheld_worst_model_mm2 = 0;  // the most of unheld_regions_mm2 on one of them (or beside none)
    std::vector<LayerIssue> worst_unheld;
    double collision_mm2 = 0;
    std::vector<LayerIssue> worst_collisions;
    // Support printed over support of another path on the same layer (bead
    // cores, half the width, overlapping): extruded twice. Reported, not a
    // failure: crossing loops overlap a little by design.
    double support_overlap_mm2 = 0;
    int bad_extrusions = 0;        // implied width out of bounds
    int e_jumps = 0;               // large E without motion
    int outside_bed = 0;           // extrusions off the bed
    std::vector<std::string> extrusion_notes;  // first few, with line numbers
    // Reported, not failures: the slicer's start code (purge and prime
    // before the first layer) and tool-change purges, and with --original
    // what the original did itself on lines the edit left alone.
    int start_code_problems = 0;
    std::vector<std::string> start_code_notes;
    int original_problems = 0;
    std::vector<std::string> original_notes;
    // With --original, the support the original held itself (sliced with
    // support on): its unheld area and collisions, reported apart.
    double original_unheld_support_mm2 = 0;
    double original_collision_mm2 = 0;
    bool compared = false;         // --original given
    bool model_unchanged = true;
    std::string model_change;      // first difference, when changed
    int model_lines_missing = 0;   // original command lines not found in order
    int model_moves_changed = 0;   // original lines found whose motion differs
                                   // (start, end, E, feed, tool): state not restored
    double support_filament_mm = 0;
    double model_filament_mm = 0;
    double print_time_s = 0;
    double original_print_time_s = -1;
    StandingReport standing;       // METHOD's second rule: stiffness and travels
    std::vector<std::string> failures;  // reasons for exit 1

    bool ok() const { return failures.empty(); }
};

// Validates `out`; `original` (may be null) is the input it was made from.
// Settings (filament, layer height, nozzle, retraction, bed) come from
// `settings`; the first form builds them from `out`'s own config block.
CheckReport check(const gcode::Program& out, const gcode::Program* original, const Settings& settings,
                  const CheckOptions& options, const std::string& svg_dir = "");
CheckReport check(const gcode::Program& out, const gcode::Program* original, const CheckOptions& options,
                  const std::string& svg_dir = "");

// Print time with a trapezoid per move between junction speeds (Marlin's
// junction deviation, 0.013 mm), using the file's M201/M203/M204 limits
// where given, else 1000 mm/s^2.
double estimate_print_time(const gcode::Program& program);
// The same in two parts: the machine's limits as the file's M201, M203 and
// M204 lines set them, and the estimate over moves (in printing order) at
// those limits.
struct MotionLimits {
    double accel = 1000, max_xy = 1e9, max_z = 1e9, max_e = 1e9;
};
MotionLimits motion_limits(const gcode::Program& program);
double estimate_moves(const std::vector<gcode::Move>& moves, const MotionLimits& limits);

std::string report_text(const CheckReport& r);
// `s` as a JSON string, quoted (quotes and backslashes escaped, control
// characters dropped): file paths (Windows' backslashes) and reasons.
std::string json_string(const std::string& s);
std::string report_json(const CheckReport& r);

}  // namespace scaffold::check
