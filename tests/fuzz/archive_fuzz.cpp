// libFuzzer target: the .gcode.3mf reader (zip directory, member names,
// sizes, inflate, CRC, the memory limits) must never crash, hang or read out
// of bounds; it either reads the plates or throws scaffold::Error. Plates it
// reads must survive being written again with the first one replaced.
#include <cstddef>
#include <cstdint>
#include <string>

#include "gcode/archive.hpp"
#include "gcode/error.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    namespace archive = scaffold::gcode::archive;
    const std::string_view bytes(reinterpret_cast<const char*>(data), size);
    archive::Limits limits;  // small, so a bomb is refused within the fuzzer's memory
    limits.member_bytes = 1 << 24;
    limits.total_bytes = 1 << 25;
    archive::Archive a;
    std::vector<std::pair<std::string, std::string>> plates;
    try {
        a = archive::open(bytes, "fuzz", limits);
        plates = archive::read_plates(bytes, "fuzz", limits);
    } catch (const scaffold::Error&) {
        return 0;
    }
    std::string again;
    try {
        again = archive::write(a, {{archive::plates(a).front(), plates.front().second + "; fuzz\n"}});
    } catch (const scaffold::Error&) {
        return 0;  // a member copied as stored is damaged (only plates are inflated and checked)
    }
    auto back = archive::read_plates(again, "fuzz-again", limits);  // what scaffold wrote must read back
    if (back.size() != plates.size() || back.front().second != plates.front().second + "; fuzz\n") __builtin_trap();
    for (std::size_t i = 1; i < back.size(); ++i)
        if (back[i] != plates[i]) __builtin_trap();
    return 0;
}
