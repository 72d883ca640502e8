// The scaffold program on binary G-code: for every compression and encoding,
// binary in gives binary out (same settings) whose G-code commands are those
// of scaffold's ASCII output for the same print.
#include <gtest/gtest.h>
#include <zlib.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "gcode/bgcode.hpp"
#include "support/files.hpp"

using namespace scaffold::gcode;
namespace fs = std::filesystem;

namespace {

std::string read_all(const std::string& path) { return scaffold::testing::load_file(path); }
std::string gunzip(const std::string& path) { return scaffold::testing::load_file(path); }
void write_all(const std::string& path, const std::string& s) { scaffold::testing::write_file(path, s); }
using scaffold::testing::commands;

// The program is built beside the tests in build/, not in the sanitizer
// build (tools/test builds only scaffold_tests there): skip without it.
bool have_program() { return fs::exists(std::string(SCAFFOLD_BINARY_DIR) + "/scaffold"); }

int run(const std::string& args) {
    std::string cmd = std::string(SCAFFOLD_BINARY_DIR) + "/scaffold -q " + args;
    return std::system(cmd.c_str());
}

}  // namespace

TEST(BgcodeCli, BinaryOutputHasTheCommandsOfTheAsciiOutput) {
    if (!have_program()) GTEST_SKIP() << "skipped: no scaffold program in " << SCAFFOLD_BINARY_DIR;
    const scaffold::testing::TempPath dir_tmp("bgcode_cli");
    const std::string& dir = dir_tmp.path;
    fs::create_directories(dir);
    std::string ascii = gunzip(std::string(SCAFFOLD_TEST_DATA) + "/corpus/overhang_test.prusaslicer25.nosup.gcode.gz");
    ASSERT_FALSE(ascii.empty());
    write_all(dir + "/in.gcode", ascii);
    ASSERT_EQ(run(dir + "/in.gcode -o " + dir + "/out.gcode"), 0);
    std::vector<std::string> want = commands(read_all(dir + "/out.gcode"));
    const std::pair<bgcode::Compression, bgcode::GCodeEncoding> variants[] = {
        {bgcode::Compression::None, bgcode::GCodeEncoding::None},
        {bgcode::Compression::Deflate, bgcode::GCodeEncoding::None},
        {bgcode::Compression::Heatshrink11, bgcode::GCodeEncoding::None},
        {bgcode::Compression::Heatshrink12, bgcode::GCodeEncoding::None},
        {bgcode::Compression::None, bgcode::GCodeEncoding::MeatPackComments},
        {bgcode::Compression::Heatshrink12, bgcode::GCodeEncoding::MeatPackComments},
        {bgcode::Compression::None, bgcode::GCodeEncoding::MeatPack},
    };
    for (const auto& [c, e] : variants) {
        SCOPED_TRACE(testing::Message() << "compression " << static_cast<int>(c) << " encoding " << static_cast<int>(e));
        bgcode::Settings s;
        s.gcode = c;
        s.encoding = e;
        s.print_metadata = s.slicer_metadata = c;
        write_all(dir + "/in.bgcode", bgcode::encode_ascii(ascii, s));
        ASSERT_EQ(run(dir + "/in.bgcode -o " + dir + "/out.bin"), 0);
        std::string bin = read_all(dir + "/out.bin");
        ASSERT_TRUE(bgcode::is_binary(bin));
        bgcode::Decoded d = bgcode::decode(scaffold::gcode::Text(bin), "out.bin");
        EXPECT_EQ(d.layout.settings.gcode, c);
        EXPECT_EQ(d.layout.settings.encoding, e);
        EXPECT_EQ(d.layout.settings.print_metadata, c);
        // scaffold's ASCII output for the same input: the binary file's text
        // (MeatPack without comments drops ;TYPE: and layer comments, so
        // only the encodings that keep comments match the original's run).
        ASSERT_EQ(run(dir + "/in.bgcode --method none --output-format ascii -o " + dir + "/in_text.gcode"), 0);
        ASSERT_EQ(run(dir + "/in_text.gcode -o " + dir + "/out_text.gcode"), 0);
        std::vector<std::string> same_input = commands(read_all(dir + "/out_text.gcode"));
        if (e != bgcode::GCodeEncoding::MeatPack) {
            EXPECT_TRUE(same_input == want);
        }
        std::vector<std::string> got = commands(d.ascii);
        EXPECT_EQ(got.size(), same_input.size());
        EXPECT_TRUE(got == same_input);
        // --output-format ascii on the binary input: the same commands again.
        ASSERT_EQ(run(dir + "/in.bgcode --output-format ascii -o " + dir + "/out.txt"), 0);
        EXPECT_TRUE(commands(read_all(dir + "/out.txt")) == same_input);
    }
}

namespace {
// The number after "; KEY = " in the text (first occurrence), or -1.
double value_of(const std::string& text, const std::string& key) {
    std::size_t at = text.find("\n; " + key + " = ");
    return at == std::string::npos ? -1 : std::strtod(text.c_str() + at + key.size() + 6, nullptr);
}
}  // namespace

// With a density and a price in the config, grams and cost grow with the
// support, in ASCII comments and in binary print metadata alike.
TEST(BgcodeCli, GramsAndCostFollowTheSupport) {
    if (!have_program()) GTEST_SKIP() << "skipped: no scaffold program in " << SCAFFOLD_BINARY_DIR;
    const scaffold::testing::TempPath dir_tmp("bgcode_cli_totals");
    const std::string& dir = dir_tmp.path;
    fs::create_directories(dir);
    std::string ascii = gunzip(std::string(SCAFFOLD_TEST_DATA) + "/corpus/overhang_test.prusaslicer25.nosup.gcode.gz");
    for (auto [from, to] : {std::pair<std::string, std::string>{"\n; filament_density = 0\n", "\n; filament_density = 1.25\n"},
                            {"\n; filament_cost = 0\n", "\n; filament_cost = 20\n"}}) {
        std::size_t at = ascii.find(from);
        ASSERT_NE(at, std::string::npos) << from;
        ascii.replace(at, from.size(), to);
    }
    write_all(dir + "/in.gcode", ascii);
    write_all(dir + "/in.bgcode", bgcode::encode_ascii(ascii, bgcode::Settings{}));
    ASSERT_EQ(run(dir + "/in.gcode -o " + dir + "/out.gcode"), 0);
    ASSERT_EQ(run(dir + "/in.bgcode -o " + dir + "/out.bgcode"), 0);
    std::string text_out = read_all(dir + "/out.gcode");
    std::string bin_out = bgcode::decode(scaffold::gcode::Text(read_all(dir + "/out.bgcode")), "out").ascii;
    for (const std::string* out : {&text_out, &bin_out}) {
        double cm3 = value_of(*out, "filament used [cm3]") - value_of(ascii, "filament used [cm3]");
        double g = value_of(*out, "total filament used [g]") - value_of(ascii, "total filament used [g]");
        double cost = value_of(*out, "total filament cost") - value_of(ascii, "total filament cost");
        EXPECT_GT(cm3, 0.1);
        EXPECT_NEAR(g, cm3 * 1.25, 0.02);
        EXPECT_NEAR(cost, g * 20 / 1000, 0.011);
    }
}
