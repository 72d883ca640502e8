#include "gcode/heatshrink.hpp"

#include <gtest/gtest.h>

#include <random>

#include "gcode/error.hpp"

using namespace scaffold::gcode;

namespace {
const heatshrink::Params kBoth[] = {{11, 4}, {12, 4}};

std::string gcode_like(std::size_t n) {
    std::string s;
    std::mt19937 rng(7);
    while (s.size() < n) s += "G1 X" + std::to_string(rng() % 200) + "." + std::to_string(rng() % 1000) + " Y" +
                             std::to_string(rng() % 200) + " E" + std::to_string(rng() % 50) + ".123\n";
    return s;
}
}  // namespace

TEST(Heatshrink, RoundTripsEdgeCases) {
    std::string all_bytes;
    for (int i = 0; i < 256; ++i) all_bytes.push_back(static_cast<char>(i));
    for (const auto& p : kBoth)
        for (const std::string& s : {std::string(), std::string("a"), std::string("ab"), std::string(5000, 'x'),
                                     all_bytes + all_bytes, gcode_like(200000)}) {
            std::string c = heatshrink::compress(s, p);
            EXPECT_EQ(heatshrink::decompress(c, p, s.size()), s);
        }
}

TEST(Heatshrink, CompressesRepetitiveText) {
    std::string s = gcode_like(100000);
    for (const auto& p : kBoth) EXPECT_LT(heatshrink::compress(s, p).size(), s.size() * 2 / 3);
}

// Hand-made streams: a literal is 1 + 8 bits; a copy 0 + window bits of
// (distance - 1) + 4 bits of (length - 1); zero bits pad the last byte.
TEST(Heatshrink, DecodesHandMadeStream) {
    // 'a' literal: 1 01100001; copy distance 1 length 3 (window 11): 0 00000000000 0010
    // bits: 101100001 0000000000000010 + padding
    std::string bits = "101100001" "0" "00000000000" "0010";
    while (bits.size() % 8) bits.push_back('0');
    std::string bytes;
    for (std::size_t i = 0; i < bits.size(); i += 8) bytes.push_back(static_cast<char>(std::stoi(bits.substr(i, 8), nullptr, 2)));
    EXPECT_EQ(heatshrink::decompress(bytes, {11, 4}, 100), "aaaa");
    EXPECT_THROW(heatshrink::decompress(bytes, {11, 4}, 3), scaffold::Error);  // more than said
    // A copy from before the start reads the window's initial zero bytes, as
    // in the reference (its encoder matches there for MeatPack's 0x00 pairs;
    // found by tools/bgcode-diff-fuzz): tag 0, distance 2, length 1.
    EXPECT_EQ(heatshrink::decompress(std::string("\x00\x10", 2), {11, 4}, 100), std::string(1, '\0'));
}

TEST(Heatshrink, WindowLimitsTheDistance) {
    // A repeat 3000 bytes back is reachable with window 12 but not 11: both still round-trip.
    std::string block = gcode_like(3000).substr(0, 3000);
    std::string s = block + std::string(100, 'z') + block;
    for (const auto& p : kBoth) EXPECT_EQ(heatshrink::decompress(heatshrink::compress(s, p), p, s.size()), s);
    EXPECT_LT(heatshrink::compress(s, {12, 4}).size(), heatshrink::compress(s, {11, 4}).size());
}
