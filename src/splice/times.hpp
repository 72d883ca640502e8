#pragma once
// The slicer's print-time lines, raised by the support's time: what hosts
// (Moonraker, OctoPrint) and printers' displays show. Totals in the header
// and footer grow by all of it; progress lines (M73, Cura's ;TIME_ELAPSED:)
// by the support inserted before them.
#include <cstdint>
#include <string>
#include <vector>

#include "gcode/program.hpp"
#include "gcode/writer.hpp"

namespace scaffold::splice {

struct BlockTime {
    std::uint32_t line = 0;  // inserted before this line
    double seconds = 0;
};

// Appends replace-edits for the time lines of `p` (none when `blocks` adds
// no time). Lines it cannot read are left as they are.
void update_times(const gcode::Program& p, std::vector<BlockTime> blocks, std::vector<gcode::Edit>& edits);

// "1d 2h 3m 4s" as PrusaSlicer writes it (leading zero units left out).
std::string format_dhms(double seconds);

}  // namespace scaffold::splice
