#include "cli/pipeline.hpp"

#include <chrono>

#include "gcode/error.hpp"
#include "gcode/reader.hpp"
#include "gcode/writer.hpp"
#include "layers/layer_stack.hpp"

namespace scaffold::cli {

void run(const Request& req, spdlog::logger& log) {
    using clock = std::chrono::steady_clock;
    auto t0 = clock::now();
    gcode::Program program = gcode::read_file(req.input);
    log.debug("read {} lines, {} moves ({}), {:.1f} ms", program.lines.size(), program.moves.size(),
              gcode::dialect_name(program.dialect),
              std::chrono::duration<double, std::milli>(clock::now() - t0).count());
    SettingMap cli = req.slicer_overrides;
    for (const auto& [k, v] : req.overrides) cli[k] = v;
    Settings settings = build_settings(program, settings_from_environment(), cli);
    if (settings.method == Method::None) {
        gcode::write_output(req.output, program, {});
        log.info("--method none: {} written unchanged", req.output == "-" ? "<stdout>" : req.output);
        return;
    }
    if (settings.spiral_vase)
        throw Error(program.path, 0, "spiral vase mode is not supported: a vase is one continuous wall and has no place for supports");
    if (settings.sequential_printing)
        throw Error(program.path, 0, "sequential printing (complete objects) is not supported: supports would collide with the printed objects; slice with all objects printed layer by layer");
    layers::LayerStack stack = layers::build_layers(program, settings);
    log.info("{} layers", stack.layers.size());
    throw Error("support generation is not wired in yet");
}

}  // namespace scaffold::cli
