#pragma once
// Step 1 of the pipeline: the G-code in, as a Program (lines + moves +
// config). Refuses input it cannot handle faithfully, with file:line.
#include <string>

#include "gcode/program.hpp"

namespace scaffold::gcode {

// Reads the whole file ("-" reads stdin) and parses it.
Program read_file(const std::string& path);
// Parses G-code already in memory; `path` is used in messages.
Program parse(std::string text, std::string path);
// The same over bytes already loaded (a map is not copied).
Program parse(Text text, std::string path);

}  // namespace scaffold::gcode
