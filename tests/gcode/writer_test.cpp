#include <gtest/gtest.h>

#include "support/files.hpp"

#include <cstdio>
#include <fstream>
#include <sstream>

#include "gcode/error.hpp"
#include "gcode/reader.hpp"
#include "gcode/writer.hpp"

using namespace scaffold::gcode;

namespace {
std::string render(const Program& p, std::vector<Edit> edits) {
    char* buf = nullptr;
    std::size_t size = 0;
    std::FILE* f = open_memstream(&buf, &size);
    EXPECT_TRUE(write_edited(f, p, std::move(edits)));
    std::fclose(f);
    std::string out(buf, size);
    std::free(buf);
    return out;
}
std::string slurp(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    std::stringstream ss;
    ss << in.rdbuf();
    return ss.str();
}
}  // namespace

TEST(Writer, NoEditsIsByteIdenticalIncludingOddEndings) {
    for (std::string text : {"G1 X1\r\nG1 X2\r\n", "G1 X1\nG1 X2", "\n\nG1 X1\n; c\xff\xfe\n", "G1 X1\n"}) {
        Program p = parse(text, "t");
        EXPECT_EQ(render(p, {}), text);
    }
}

TEST(Writer, InsertAndReplaceKeepLineEndings) {
    Program p = parse("A\r\nB\r\nC", "t");
    std::string out = render(p, {{1, false, "X\nY\n"}, {2, true, "c2"}, {3, false, "END\n"}});
    EXPECT_EQ(out, "A\r\nX\r\nY\r\nB\r\nc2\r\nEND\r\n");
}

TEST(Writer, AtomicWriteReplacesAndFailureLeavesOriginal) {
    const scaffold::testing::TempPath path_tmp("writer_atomic.gcode");
    const std::string& path = path_tmp.path;
    { std::ofstream(path) << "G1 X0\n"; }
    Program p = parse("G1 X1\nG1 X2\n", "t");
    write_output(path, p, {{1, false, "; inserted\n"}});
    EXPECT_EQ(slurp(path), "G1 X1\n; inserted\nG1 X2\n");
    setenv("SCAFFOLD_TEST_FAIL_WRITE", "1", 1);
    EXPECT_THROW(write_output(path, p, {}), scaffold::Error);
    unsetenv("SCAFFOLD_TEST_FAIL_WRITE");
    EXPECT_EQ(slurp(path), "G1 X1\n; inserted\nG1 X2\n");
    EXPECT_THROW(write_output("/nonexistent-dir/x.gcode", p, {}), scaffold::Error);
}
