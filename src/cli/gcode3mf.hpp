#pragma once
// `scaffold` on a Bambu Studio / OrcaSlicer .gcode.3mf: each plate's G-code
// through the same pipeline as a plain file, then the archive written again
// with the plates, their .md5 and slice_info.config's totals replaced.
#include <spdlog/logger.h>

#include "cli/pipeline.hpp"
#include "gcode/text.hpp"

namespace scaffold::cli {

// `bytes` are the input's (a zip). Throws scaffold::Error before anything
// is written when any plate fails: the input stays as it was.
Outcome run_gcode_3mf(const Request& request, const gcode::Text& bytes, spdlog::logger& log);

}  // namespace scaffold::cli
