#pragma once
// Blocks a slicer writes around a part of the print that must stay whole:
// an object's label (cancelling the object in the printer skips it) and a
// tool change with its purge. The splice never inserts into one; the
// validator takes a tool change's purge for the slicer's own.
#include <string_view>

namespace scaffold::gcode {

enum class BlockKind { None, Object, ToolChange };

struct BlockMarker {
    BlockKind kind = BlockKind::None;
    bool opens = false;  // else closes (when kind != None)
};

// Klipper EXCLUDE_OBJECT_START/END, M486 S<n>/S-1, Orca/Bambu "; start/stop
// printing object" with Bambu's M624/M625; Bambu's M620/M621 and PrusaSlicer's "; CP TOOLCHANGE
// START/END" around a tool change.
BlockMarker block_marker(std::string_view line);

}  // namespace scaffold::gcode
