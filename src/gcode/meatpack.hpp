#pragma once
// MeatPack: the G-code packing binary G-code uses. The 15 commonest
// characters go two to a byte (4 bits each, first character in the low
// half); the half 0b1111 says a full byte follows for that character. Two
// 0xFF bytes and a command byte switch packing, the "no spaces" mode (the
// code for ' ' then means 'E' and G-code words lose their spaces) and
// resets. Written from the public format description.
#include <string>
#include <string_view>

namespace scaffold::gcode::meatpack {

// Packs G-code text line by line. Comments at the end of command lines are
// dropped; comment lines are dropped too unless `keep_comment_lines`, then
// they are written unpacked. Spaces are dropped from G lines where the
// decoder puts them back exactly. Throws scaffold::Error on a 0xFF byte,
// which the format cannot carry.
std::string encode(std::string_view text, bool keep_comment_lines);

// Unpacks to the text the reference decoder writes: empty lines (the
// packing's padding) are dropped and G lines get a space before each word.
// Throws scaffold::Error on a stream cut short or an unknown command.
std::string decode(std::string_view packed);

}  // namespace scaffold::gcode::meatpack
