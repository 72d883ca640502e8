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
};

// Throws scaffold::Error; on error nothing has been written to the output.
void run(const Request& request, spdlog::logger& log);

}  // namespace scaffold::cli
