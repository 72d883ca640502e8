#include "gcode/meatpack.hpp"

#include <gtest/gtest.h>

#include "gcode/error.hpp"

using namespace scaffold::gcode;

namespace {
std::string bytes(std::initializer_list<int> b) {
    std::string s;
    for (int v : b) s.push_back(static_cast<char>(v));
    return s;
}
}  // namespace

// Two characters a byte, low half first; a 0xF half takes a full byte after.
TEST(MeatPack, DecodesHandMadeStream) {
    // "G1 X0\n": (G,1) (' ',X) (0,\n); "M1\n\n": (M:full,1) (\n,\n)
    std::string s = bytes({0xFF, 0xFF, 251, 0x1D, 0xEB, 0xC0, 0x1F, 'M', 0xCC});
    EXPECT_EQ(meatpack::decode(s), "G1 X0\nM1\n");
    // No-spaces mode: code 11 is 'E', and G words get their spaces back.
    s = bytes({0xFF, 0xFF, 251, 0xFF, 0xFF, 247, 0x1D, 0xEB, 0xC0});
    EXPECT_EQ(meatpack::decode(s), "G1 E X0\n");
    // Packing off: plain bytes.
    s = bytes({0xFF, 0xFF, 250, ';', 'a', '\n'});
    EXPECT_EQ(meatpack::decode(s), ";a\n");
    // Both halves full: two bytes follow.
    s = bytes({0xFF, 0xFF, 251, 0xFF, 'M', 'T', 0xCC});
    EXPECT_EQ(meatpack::decode(s), "MT\n");
}

TEST(MeatPack, RejectsBrokenStreams) {
    EXPECT_THROW(meatpack::decode(bytes({0xFF, 0xFF, 251, 0x1F})), scaffold::Error);  // full byte missing
    EXPECT_THROW(meatpack::decode(bytes({0xFF, 0xFF, 1})), scaffold::Error);           // unknown command
    EXPECT_THROW(meatpack::decode(bytes({0xFF, 0xFF})), scaffold::Error);              // command missing
    EXPECT_THROW(meatpack::encode("; \xff\n", true), scaffold::Error);
}

TEST(MeatPack, EncodesLikeTheReferenceDecoderExpects) {
    std::string text =
        "; comment line\n"
        "G1 X10.5 Y2 E0.1 ; trailing comment\n"
        "\n"
        "M104 S215\n"
        "G1 x1\n"           // lower case: spaces kept, the decoder would not restore them
        "M117 Hello World\n"
        "G1 F1800\n"
        ";TYPE:Perimeter\n";
    EXPECT_EQ(meatpack::decode(meatpack::encode(text, true)),
              "; comment line\nG1 X10.5 Y2 E0.1\nM104 S215\nG1 x1\nM117 Hello World\nG1 F1800\n;TYPE:Perimeter\n");
    EXPECT_EQ(meatpack::decode(meatpack::encode(text, false)), "G1 X10.5 Y2 E0.1\nM104 S215\nG1 x1\nM117 Hello World\nG1 F1800\n");
    // Packed G-code takes about half the bytes.
    std::string moves;
    for (int i = 0; i < 1000; ++i) moves += "G1 X" + std::to_string(100 + i % 50) + ".25 Y" + std::to_string(i % 77) + ".5 E1.2345\n";
    std::string packed = meatpack::encode(moves, false);
    EXPECT_LT(packed.size(), moves.size() * 6 / 10);
    EXPECT_EQ(meatpack::decode(packed), moves);
}
