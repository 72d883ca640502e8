#pragma once
// Step 6: each layer's support paths become a G-code block inserted at the
// end of that layer. The block saves and restores the machine state around
// itself (position, E register, retraction, feedrate, fan, role comment),
// so the model's own lines pass through unchanged and in order.
#include <string>
#include <vector>

#include "gcode/machine.hpp"
#include "gcode/program.hpp"
#include "gcode/settings.hpp"
#include "gcode/writer.hpp"
#include "layers/layer_stack.hpp"
#include "toolpath/support_paths.hpp"

namespace scaffold::splice {

struct SpliceResult {
    std::vector<gcode::Edit> edits;  // one insertion per layer with support
    double filament_mm = 0;          // support filament, mm of filament
    // Print time of each insertion (same order as `edits`), by a trapezoid
    // per move at the file's acceleration: what the hosts' time lines grow by.
    std::vector<double> block_seconds;
    double seconds = 0;
    double extruded_length_mm = 0;   // support bead length
    int layers_touched = 0;
    // Insertions that fell inside an object's labelled block or a tool
    // change open across the layer change (support spliced into it).
    std::size_t blocks_split = 0;
    // The machine's state where each block goes in (same order as `edits`).
    std::vector<gcode::MachineState> block_states;
};

// The blocks are written on `threads` threads (the same text on any number).
SpliceResult splice(const gcode::Program& program, const layers::LayerStack& stack,
                    const toolpath::SupportPaths& paths, const Settings& settings, int threads = 1);

// The moves of the output `spliced` makes of `program` (whose moves are
// still those it was read with), in printing order, as reading the output
// back gives them: the input's, each block's put in at its place, and the
// lines after a block stepped again from where it leaves the machine until
// their moves are the input's again. For the print-time estimate of the
// output without reading all of it again.
std::vector<gcode::Move> spliced_moves(const gcode::Program& program, const SpliceResult& spliced);

// Filament (mm) for a bead of this length, width and height.
double filament_for(double length, double width, double height, double filament_diameter);

}  // namespace scaffold::splice
