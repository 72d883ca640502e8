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
// they are written unpacked. In a line starting with 'G' a space is dropped
// where the reference decoder puts it back (after a non-space, before one of
// its word letters XYZEFIJRSGPWHCA); other spaces are kept. The block is
// padded with bytes that decode to nothing where the reference decoder would
// otherwise lose a letter (reference_drops_a_letter). Throws scaffold::Error
// on a 0xFF byte, which the format cannot carry.
std::string encode(std::string_view text, bool keep_comment_lines);

// Unpacks to the text the reference decoder writes: empty lines (the
// packing's padding) are dropped and G lines get a space before each word
// letter that lacks one; a pair whose first character is a newline ends
// there, as in the reference.
// Throws scaffold::Error on a stream cut short or an unknown command.
std::string decode(std::string_view packed);

// The reference decoder (libbgcode) writes a block's text into a buffer of
// twice the packed size, doubled whenever it fills; when a word letter and
// the space it puts back before it fill the buffer exactly, the regrowth
// lets the next character overwrite the letter ("X1 Y2" reads "X1 2").
// Says whether that happens to `raw` (the block's unpacked characters,
// before respacing) packed in `packed_size` bytes.
bool reference_drops_a_letter(std::string_view raw, std::size_t packed_size);

}  // namespace scaffold::gcode::meatpack
