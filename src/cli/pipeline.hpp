#pragma once
// The whole job of `scaffold`: read, detect, plan, make paths, splice, write,
// with the summary and report. Separate from option parsing so tests and
// tools can run it.
#include <spdlog/logger.h>

#include <map>
#include <string>

#include "gcode/settings.hpp"

namespace scaffold::cli {

struct Request {
    std::string input;
    std::string output;
    std::map<std::string, std::string> files;  // report, dump-points, dump-layers, preview
    SettingMap overrides;                      // scaffold options by option name
    SettingMap slicer_overrides;               // --set KEY=VALUE
    std::string output_format;                 // "ascii", "binary" or empty: as the input
    // Progress lines (at info level, so -q silences them) start once a run
    // has taken this long: a short run says nothing until its summary.
    double progress_after_s = 2.0;
    // Threads for planning independent groups of points (0: the machine's
    // cores); the plan is the same for any count. A thread after the first
    // joins once the groups have taken this long: its caches fill anew, more
    // than a light plate's planning costs (16 anchors joining at once, each
    // thread with Obstacles of its own: 8.7 s of CPU against 5.3 on one).
    int threads = 0;
    double second_thread_after_s = 2.0;
    // A plate of exact copies (layers::Copies) planned as one copy moved to
    // each; false plans it whole, as any other plate.
    bool plan_copies = true;
    // Plans made again without the bars the one before could not hold as
    // built, at most (21 plans in all: Cura's bunny with one wall settles at
    // the 8th; at 7 a plate of eight bunnies ended with a bar unheld in each
    // copy; Cura's four bunnies with an extruder profile, without the
    // detector's specks at a skin's gaps, at the 13th). Where they run out
    // with such bars left, the run warns. Only a plan that keeps failing
    // pays for them.
    int bar_rounds = 20;
    // --check: the written output judged by scaffold-check's rules against
    // the input (as `scaffold-check OUT --original IN` with the run's gap,
    // overhang angle, resolution and --min-stiffness), each failure warned.
    bool check = false;
    // One plate of a .gcode.3mf (cli/gcode3mf.cpp): its text is taken (moved)
    // from here instead of reading `input`, and the output kept here instead
    // of written.
    std::string* input_text = nullptr;
    std::string* output_text = nullptr;
};

// What a run added: a .gcode.3mf's slice_info.config is raised by it.
struct Outcome {
    double support_mm = 0;  // of the spool's filament
    double seconds_before = 0, seconds_after = 0;  // the validator's print time estimate; 0 when not made
    bool unchanged = false;                        // --method none: the input as it was
};

// Throws scaffold::Error; on error nothing has been written to the output.
// A .gcode.3mf input (recognised by content) is run plate by plate.
Outcome run(const Request& request, spdlog::logger& log);

}  // namespace scaffold::cli
