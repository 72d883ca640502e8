#include "gcode/blocks.hpp"

namespace scaffold::gcode {

BlockMarker block_marker(std::string_view t) {
    while (!t.empty() && (t.front() == ' ' || t.front() == '\t')) t.remove_prefix(1);
    auto starts = [&](std::string_view p) { return t.substr(0, p.size()) == p; };
    if (starts("EXCLUDE_OBJECT_START")) return {BlockKind::Object, true};
    if (starts("EXCLUDE_OBJECT_END")) return {BlockKind::Object, false};
    if (starts("M486 S")) return {BlockKind::Object, t.substr(6, 2) != "-1"};
    if (starts("; start printing object") || starts(";start printing object")) return {BlockKind::Object, true};
    if (starts("; stop printing object") || starts(";stop printing object")) return {BlockKind::Object, false};
    // Bambu's firmware skips a cancelled object from M624 to M625, which
    // follow the comments above.
    if (starts("M624 ")) return {BlockKind::Object, true};
    if (starts("M625") && (t.size() == 4 || t[4] == ' ' || t[4] == ';' || t[4] == '\r')) return {BlockKind::Object, false};
    if (starts("M620 S")) return {BlockKind::ToolChange, true};
    if (starts("M621 S")) return {BlockKind::ToolChange, false};
    if (starts("; CP TOOLCHANGE START")) return {BlockKind::ToolChange, true};
    if (starts("; CP TOOLCHANGE END")) return {BlockKind::ToolChange, false};
    return {};
}

}  // namespace scaffold::gcode
