// libFuzzer target: the binary G-code reader (container, deflate, heatshrink,
// MeatPack, metadata) must never crash, hang or read out of bounds; it either
// decodes or throws scaffold::Error. What it decodes must write back and
// decode again to the same text.
#include <cstddef>
#include <cstdint>
#include <string>

#include "gcode/bgcode.hpp"
#include "gcode/error.hpp"
#include "gcode/reader.hpp"
#include "gcode/writer.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    std::string bytes(reinterpret_cast<const char*>(data), size);
    // Mostly binary files: inputs without the magic get it, so the fuzzer
    // does not spend its time on text.
    if (!scaffold::gcode::bgcode::is_binary(bytes)) bytes.insert(0, "GCDE");
    scaffold::gcode::Program program;
    try {
        program = scaffold::gcode::parse(bytes, "fuzz");
    } catch (const scaffold::Error&) {
        return 0;
    }
    // Decoded: re-encoding with the same settings must decode to the same text.
    const auto& layout = *program.binary;
    std::string again;
    try {
        again = scaffold::gcode::bgcode::encode_edited(program, {{layout.gcode_line, false, "; fuzz\n"}});
    } catch (const scaffold::Error&) {
        return 0;  // e.g. a 0xFF byte MeatPack cannot carry
    }
    auto d = scaffold::gcode::bgcode::decode(scaffold::gcode::Text(again), "fuzz-again");
    std::string want(std::string_view(program.text));
    std::size_t at = 0;
    for (std::uint32_t i = 0; i < layout.gcode_line; ++i) at = want.find('\n', at) + 1;
    if (layout.settings.encoding != scaffold::gcode::bgcode::GCodeEncoding::MeatPack) want.insert(at, "; fuzz\n");
    bool plain = layout.settings.encoding == scaffold::gcode::bgcode::GCodeEncoding::None;
    if (plain && want.find('\r') == std::string::npos && d.ascii != want) __builtin_trap();
    return 0;
}
