#pragma once
// The whole pipeline on G-code text, as the command line runs it, for tests
// that build their input with SynthGcode: the output text, logging off.
#include <spdlog/logger.h>
#include <spdlog/sinks/null_sink.h>

#include <memory>
#include <string>

#include "cli/pipeline.hpp"

namespace scaffold::testing {

// `options`: scaffold's own options by their command-line name
// ("--min-overhang-area" -> "0").
inline std::string scaffolded(std::string in, const SettingMap& options = {}) {
    spdlog::logger log("test", std::make_shared<spdlog::sinks::null_sink_mt>());
    std::string out;
    cli::Request req;
    req.input = req.output = "synth.gcode";
    req.input_text = &in;
    req.output_text = &out;
    req.overrides = options;
    cli::run(req, log);
    return out;
}

}  // namespace scaffold::testing
