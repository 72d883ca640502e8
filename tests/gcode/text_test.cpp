#include <gtest/gtest.h>

#include "support/files.hpp"

#include <cstdio>
#include <fstream>
#include <sstream>

#include "gcode/error.hpp"
#include "gcode/reader.hpp"
#include "gcode/text.hpp"
#include "gcode/writer.hpp"

using namespace scaffold::gcode;

namespace {
std::string slurp(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    std::stringstream ss;
    ss << in.rdbuf();
    return ss.str();
}
}  // namespace

TEST(Text, MappedFileReadsLikeTheStringAndSurvivesRelease) {
    const scaffold::testing::TempPath path_tmp("text_mapped.gcode");
    const std::string& path = path_tmp.path;
    std::string content = "G1 X1 Y2\r\n; c\xff\n";
    { std::ofstream(path, std::ios::binary) << content; }
    Text t = Text::load(path);
    EXPECT_TRUE(t.mapped());
    EXPECT_EQ(std::string_view(t), content);
    t.release(0, t.size());
    EXPECT_EQ(std::string_view(t), content);  // released pages read back
    Text copy = t;
    t = Text();
    EXPECT_EQ(std::string_view(copy), content);  // copies share the map
    Text s(content);
    EXPECT_FALSE(s.mapped());
    s.release(0, s.size());
    EXPECT_EQ(std::string_view(s), content);
}

TEST(Text, EmptyAndMissingFiles) {
    const scaffold::testing::TempPath path_tmp("text_empty.gcode");
    const std::string& path = path_tmp.path;
    { std::ofstream(path, std::ios::binary); }
    EXPECT_TRUE(Text::load(path).empty());
    EXPECT_THROW(read_file(path), scaffold::Error);
    EXPECT_THROW(Text::load(path + ".missing"), scaffold::Error);
}

// A file larger than the reader's and the writer's windows, rewritten in
// place (the slicer hook): the map of the old file must outlive the rename.
TEST(Text, LargeMappedFileRewrittenInPlace) {
    const scaffold::testing::TempPath path_tmp("text_large.gcode");
    const std::string& path = path_tmp.path;
    std::string content;
    content.reserve(40u << 20);
    for (int i = 0; content.size() < (40u << 20); ++i) content += "; filler line " + std::to_string(i) + "\n";
    content += "G1 X1 Y1 E1";  // no final newline
    { std::ofstream(path, std::ios::binary) << content; }
    Program p = read_file(path);
    ASSERT_TRUE(p.text.mapped());
    EXPECT_EQ(p.line_text(p.lines.size() - 1), "G1 X1 Y1 E1");
    EXPECT_EQ(p.moves.size(), 1u);
    std::uint32_t mid = static_cast<std::uint32_t>(p.lines.size() / 2);
    write_output(path, p, {{mid, false, "; inserted\n"}, {static_cast<std::uint32_t>(p.lines.size()), false, "; end\n"}});
    std::string want = content.substr(0, p.lines[mid].offset) + "; inserted\n" + content.substr(p.lines[mid].offset) + "\n; end\n";
    EXPECT_EQ(slurp(path), want);
    EXPECT_EQ(p.line_text(0), "; filler line 0");  // the old bytes are still there
}
