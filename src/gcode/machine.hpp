#pragma once
// The printer's state as the firmware sees it, advanced one lexed line at a
// time. Shared by the reader (to build moves) and the splicer (to know what
// to save and restore around an inserted block).
#include <vector>

#include "gcode/lexer.hpp"
#include "gcode/program.hpp"

namespace scaffold::gcode {

struct MachineState {
    double x = 0, y = 0, z = 0;
    double e = 0;                 // the E register (what G92 E sets)
    double feed_mm_per_min = 0;   // modal F
    bool absolute_xyz = true;     // G90 / G91
    bool absolute_e = true;       // M82 / M83 (G91 also makes E relative)
    bool inches = false;          // G20 / G21
    bool fw_retracted = false;    // between G10 and G11
    double retracted_mm = 0;      // filament pulled back by E moves, not yet primed
    int fan = 0;                  // 0..255 (M106 S / M107)
    int tool = 0;
    bool moved = false;           // any motion yet (for the inches rule)

    bool relative_e() const { return !absolute_e || !absolute_xyz; }
    bool retracted() const { return fw_retracted || retracted_mm > 1e-4; }
};

// Applies one line to the state. Motions are appended to `moves` in mm
// (arcs flattened into chords within 0.01 mm); `line` is stored in each.
// Returns nullptr, or a sentence saying why the line cannot be executed.
const char* step(MachineState& state, const Command& cmd, std::uint32_t line, std::vector<Move>& moves);

}  // namespace scaffold::gcode
