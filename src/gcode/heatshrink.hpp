#pragma once
// Heatshrink: the LZSS variant binary G-code uses for "heatshrink 11/4" and
// "12/4". A bit stream, most significant bit first: tag 1 + 8 bits is a
// literal byte; tag 0 + `window_bits` of (distance - 1) + `lookahead_bits`
// of (length - 1) copies earlier output. The last byte is padded with zeros.
// Written from the format description; no code of the reference library.
#include <cstdint>
#include <string>
#include <string_view>

namespace scaffold::gcode::heatshrink {

struct Params {
    int window_bits = 12;    // 11 or 12 in binary G-code
    int lookahead_bits = 4;  // 4 in binary G-code
};

std::string compress(std::string_view in, Params p);
// Decodes until the input runs out. Throws scaffold::Error (no file or line;
// the caller adds where) if a copy reaches before the start or the output
// would exceed `max_out` bytes.
std::string decompress(std::string_view in, Params p, std::size_t max_out);

}  // namespace scaffold::gcode::heatshrink
