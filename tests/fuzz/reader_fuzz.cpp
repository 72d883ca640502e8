// libFuzzer target: the reader and layer builder must never crash, hang or
// read out of bounds on any bytes; they either succeed or throw scaffold::Error.
#include <cstddef>
#include <cstdint>
#include <string>

#include "gcode/error.hpp"
#include "gcode/reader.hpp"
#include "gcode/settings.hpp"
#include "layers/layer_stack.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    try {
        auto program = scaffold::gcode::parse(std::string(reinterpret_cast<const char*>(data), size), "fuzz");
        auto settings = scaffold::build_settings(program, {}, {});
        auto stack = scaffold::layers::build_layers(program, settings);
        (void)stack;
    } catch (const scaffold::Error&) {
    }
    return 0;
}
