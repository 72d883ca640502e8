#pragma once
// The reader's product: the file's bytes, its lines, and every motion as a
// plain Move (arcs flattened), plus the slicer config found in the file.
// Later stages never re-read the text; the writer copies it byte for byte.
// Sizes matter here: a 500 MB file has some 15 million lines and moves.
#include <cstdint>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "gcode/role.hpp"
#include "gcode/text.hpp"

namespace scaffold::gcode {

namespace bgcode {
struct Layout;
}

enum class Dialect : std::uint8_t { Unknown, PrusaSlicer, SuperSlicer, OrcaSlicer, Slic3r, Cura };
const char* dialect_name(Dialect d);

// 8 bytes: files up to 1 TB, lines up to 16 MB (the reader refuses longer).
struct Line {
    std::uint64_t offset : 40 = 0;  // of the first byte in Program::text
    std::uint64_t length : 24 = 0;  // without the line ending
};
inline constexpr std::uint64_t kMaxLineLength = (std::uint64_t{1} << 24) - 1;
inline constexpr std::uint64_t kMaxFileSize = (std::uint64_t{1} << 40) - 1;

enum class MoveKind : std::uint8_t {
    Travel,     // XY and/or Z without extrusion
    Extrude,    // XY with positive E
    Retract,    // E only, negative (or G10)
    Unretract,  // E only, positive (or G11)
    Wipe,       // XY with negative E (retract while moving)
};

// One straight motion. Arcs become several Moves sharing their line.
struct Move {
    std::uint32_t line = 0;  // 0-based index into Program::lines
    float x0 = 0, y0 = 0, z0 = 0;
    float x1 = 0, y1 = 0, z1 = 0;
    float e = 0;             // filament mm, + extrudes, after abs/rel and G92
    float width = 0;         // from ;WIDTH: if the slicer wrote it, else 0
    float feed_mm_per_min = 0;
    MoveKind kind = MoveKind::Travel;
    Role role = Role::Unknown;
    std::uint8_t tool = 0;
};

// Layer comments written by the slicer; hints only, the Z of extrusions rules.
struct LayerHint {
    std::uint32_t line = 0;
    double z = -1;       // from ;Z: (or -1)
    double height = -1;  // from ;HEIGHT: (or -1)
};

struct Program {
    std::string path;  // for messages; "-" for stdin
    Text text;         // the whole file, untouched (mapped when it is a regular file)
    std::vector<Line> lines;
    std::vector<Move> moves;
    std::vector<LayerHint> layer_hints;
    Dialect dialect = Dialect::Unknown;
    std::map<std::string, std::string> config;  // slicer settings found in the file
    bool saw_firmware_retraction = false;        // G10/G11 present
    bool saw_relative_e = false;                 // M83 present
    bool relative_e_at_start = false;            // no M82/M83, but E reads as relative
    bool saw_arcs = false;
    // Set when the input was binary G-code: `text` is its ASCII decoding and
    // this says how to write it back (gcode/bgcode.hpp).
    std::shared_ptr<const bgcode::Layout> binary;

    std::string_view line_text(std::size_t i) const {
        return std::string_view(text.data() + lines[i].offset, lines[i].length);
    }
};

}  // namespace scaffold::gcode
