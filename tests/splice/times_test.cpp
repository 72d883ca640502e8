#include <gtest/gtest.h>

#include <map>
#include <string>

#include "gcode/reader.hpp"
#include "splice/times.hpp"
#include "support/synth.hpp"

using namespace scaffold;

namespace {

// A synthetic file with `head` after the slicer's first line, two layers
// each closed by a "BLOCK" marker (where the support goes) with `mid` lines
// between them, and `tail` after the config block.
struct TimedFile {
    gcode::Program program;
    std::uint32_t block1 = 0, block2 = 0;
};

TimedFile timed_file(const std::string& head, const std::string& mid, const std::string& tail) {
    scaffold::testing::SynthGcode g;
    g.raw(head);
    g.layer(0.2);
    g.type("External perimeter");
    g.filled_rect(100, 100, 110, 110);
    g.raw("; BLOCK");
    g.raw(mid);
    g.layer(0.4);
    g.filled_rect(100, 100, 110, 110);
    g.raw("; BLOCK");
    g.raw("M73 P100 R0");
    TimedFile f;
    f.program = gcode::parse(g.str() + tail, "timed.gcode");
    bool first = true;
    for (std::uint32_t i = 0; i < f.program.lines.size(); ++i)
        if (f.program.line_text(i) == "; BLOCK") (first ? f.block1 : f.block2) = i, first = false;
    return f;
}

// Line text after the edits, by line.
std::map<std::string, std::string> changed(const gcode::Program& p, const std::vector<gcode::Edit>& edits) {
    std::map<std::string, std::string> m;
    for (const gcode::Edit& e : edits) {
        EXPECT_TRUE(e.replace);
        m[std::string(p.line_text(e.line))] = e.text;
    }
    return m;
}

}  // namespace

TEST(Times, FormatsAsPrusaSlicer) {
    EXPECT_EQ(splice::format_dhms(0), "0s");
    EXPECT_EQ(splice::format_dhms(59.6), "1m 0s");
    EXPECT_EQ(splice::format_dhms(3661), "1h 1m 1s");
    EXPECT_EQ(splice::format_dhms(90061), "1d 1h 1m 1s");
}

// PrusaSlicer: totals in both modes, M73 P/R and Q/S progress.
TEST(Times, PrusaTotalsAndProgress) {
    TimedFile f = timed_file("M73 P0 R10\nM73 Q0 S20", "M73 P50 R5\nM73 Q50 S10",
                             "; estimated printing time (normal mode) = 10m 0s\n"
                             "; estimated printing time (silent mode) = 20m 0s\n");
    std::vector<gcode::Edit> edits;
    // One minute of support after the first layer, one after the second.
    splice::update_times(f.program, {{f.block1, 60}, {f.block2, 60}}, edits);
    auto m = changed(f.program, edits);
    EXPECT_EQ(m["; estimated printing time (normal mode) = 10m 0s"], "; estimated printing time (normal mode) = 12m 0s");
    EXPECT_EQ(m["; estimated printing time (silent mode) = 20m 0s"], "; estimated printing time (silent mode) = 22m 0s");
    EXPECT_EQ(m["M73 P0 R10"], "M73 P0 R12");
    EXPECT_EQ(m["M73 Q0 S20"], "M73 Q0 S22");
    // Half of the slicer's 10 min plus the first minute of support: 6 of 12
    // done, 6 left (the second block still to come).
    EXPECT_EQ(m.count("M73 P50 R5"), 1u);
    EXPECT_EQ(m["M73 P50 R5"], "M73 P50 R6");
    EXPECT_EQ(m["M73 Q50 S10"], "M73 Q50 S11");
    EXPECT_EQ(m.count("M73 P100 R0"), 0u);  // the end stays the end
    EXPECT_EQ(edits.size(), 6u);
}

// Cura: ;TIME: in the header, ;TIME_ELAPSED: per layer, M73 with P only.
TEST(Times, CuraTimeAndElapsed) {
    TimedFile f = timed_file(";TIME:600", ";TIME_ELAPSED:300.500000\nM73 P50", "");
    std::vector<gcode::Edit> edits;
    splice::update_times(f.program, {{f.block1, 60}, {f.block2, 180}}, edits);
    auto m = changed(f.program, edits);
    EXPECT_EQ(m[";TIME:600"], ";TIME:840");
    EXPECT_EQ(m[";TIME_ELAPSED:300.500000"], ";TIME_ELAPSED:360.500000");
    EXPECT_EQ(m["M73 P50"], "M73 P42");  // (300 + 60) / 840
}

// Bambu Studio and OrcaSlicer: both numbers of the header's time line.
TEST(Times, BambuHeader) {
    TimedFile f = timed_file("; model printing time: 9m 0s; total estimated time: 10m 0s", "", "");
    std::vector<gcode::Edit> edits;
    splice::update_times(f.program, {{f.block1, 100}, {f.block2, 20}}, edits);
    auto m = changed(f.program, edits);
    EXPECT_EQ(m["; model printing time: 9m 0s; total estimated time: 10m 0s"],
              "; model printing time: 11m 0s; total estimated time: 12m 0s");
}

TEST(Times, NothingAddedChangesNothing) {
    TimedFile f = timed_file(";TIME:600", ";TIME_ELAPSED:300", "; estimated printing time (normal mode) = 10m 0s\n");
    std::vector<gcode::Edit> edits;
    splice::update_times(f.program, {{f.block1, 0}}, edits);
    EXPECT_TRUE(edits.empty());
}
