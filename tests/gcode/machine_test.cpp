#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "gcode/error.hpp"
#include "gcode/reader.hpp"

using namespace scaffold::gcode;

namespace {
Program run(const std::string& text) { return parse(text, "test.gcode"); }
double total_e(const Program& p, MoveKind k) {
    double s = 0;
    for (const auto& m : p.moves) if (m.kind == k) s += m.e;
    return s;
}
}  // namespace

TEST(Machine, AbsoluteAndRelativeExtrusionGiveTheSameDeltas) {
    Program a = run("M82\nG92 E0\nG1 X10 Y0 E1\nG1 X20 E2.5\nG1 E1.5\nG1 E2.5\n");
    Program r = run("M83\nG1 X10 Y0 E1\nG1 X20 E1.5\nG1 E-1\nG1 E1\n");
    ASSERT_EQ(a.moves.size(), r.moves.size());
    for (std::size_t i = 0; i < a.moves.size(); ++i) {
        EXPECT_FLOAT_EQ(a.moves[i].e, r.moves[i].e) << i;
        EXPECT_EQ(a.moves[i].kind, r.moves[i].kind) << i;
    }
    EXPECT_EQ(a.moves[2].kind, MoveKind::Retract);
    EXPECT_EQ(a.moves[3].kind, MoveKind::Unretract);
    EXPECT_DOUBLE_EQ(total_e(a, MoveKind::Extrude), 2.5);
}

TEST(Machine, G92ResetsTheRegisterWithoutExtruding) {
    Program p = run("M82\nG1 X1 E5\nG92 E0\nG1 X2 E0.5\nG92 E100\nG1 X3 E100.25\n");
    ASSERT_EQ(p.moves.size(), 3u);
    EXPECT_FLOAT_EQ(p.moves[1].e, 0.5f);
    EXPECT_FLOAT_EQ(p.moves[2].e, 0.25f);
}

TEST(Machine, G91MakesMovesAndExtrusionRelative) {
    Program p = run("G90\nM82\nG1 X10 Y10 E1\nG91\nG1 X5 Y-5 E0.5\nG90\nG1 X0 Y0 E2\n");
    ASSERT_EQ(p.moves.size(), 3u);
    EXPECT_FLOAT_EQ(p.moves[1].x1, 15);
    EXPECT_FLOAT_EQ(p.moves[1].y1, 5);
    EXPECT_FLOAT_EQ(p.moves[1].e, 0.5f);
    EXPECT_FLOAT_EQ(p.moves[2].e, 0.5f);  // register was 1.5 after the relative move
}

TEST(Machine, ArcWithIJIsFlattenedOnTheCircle) {
    // Half circle of radius 10 around (10, 0), counter-clockwise from (0,0) to (20,0).
    Program p = run("G1 X0 Y0\nG3 X20 Y0 I10 J0 E3.14159\n");
    ASSERT_GT(p.moves.size(), 10u);
    double len = 0, e = 0;
    for (std::size_t i = 1; i < p.moves.size(); ++i) {
        const Move& m = p.moves[i];
        EXPECT_NEAR(std::hypot(m.x1 - 10, m.y1), 10, 1e-3);
        EXPECT_LE(m.y1, 1e-4);  // G3 from (0,0) to (20,0) around (10,0) passes below: y <= 0
        len += std::hypot(m.x1 - m.x0, m.y1 - m.y0);
        e += m.e;
        EXPECT_EQ(m.line, 1u);
    }
    EXPECT_NEAR(len, std::numbers::pi * 10, 0.05);
    EXPECT_NEAR(e, 3.14159, 1e-4);
}

TEST(Machine, ArcWithRadiusPicksTheShortArcClockwise) {
    Program p = run("G1 X0 Y0\nG2 X10 Y10 R10 E1\n");
    // Clockwise quarter circle from (0,0) to (10,10): centre (10,0), passes above the chord.
    double maxy = -1e9;
    for (std::size_t i = 1; i < p.moves.size(); ++i) {
        EXPECT_NEAR(std::hypot(p.moves[i].x1 - 10, p.moves[i].y1), 10, 1e-3);
        maxy = std::max<double>(maxy, p.moves[i].y1);
    }
    EXPECT_NEAR(maxy, 10, 1e-3);
    EXPECT_THROW(run("G1 X0 Y0\nG2 X10 Y10 E1\n"), scaffold::Error);
}

TEST(Machine, FirmwareRetractionIsTracked) {
    Program p = run("G1 X1 E1\nG10\nG1 X50 Y50\nG11\nG1 X51 E2\n");
    ASSERT_EQ(p.moves.size(), 5u);
    EXPECT_EQ(p.moves[1].kind, MoveKind::Retract);
    EXPECT_EQ(p.moves[3].kind, MoveKind::Unretract);
    EXPECT_TRUE(p.saw_firmware_retraction);
}

TEST(Machine, InchesAreConvertedAndMixesRefused) {
    Program p = run("G20\nG1 X1 Y1 E0.1\n");
    EXPECT_NEAR(p.moves[0].x1, 25.4, 1e-4);
    EXPECT_NEAR(p.moves[0].e, 2.54, 1e-4);
    try {
        run("G21\nG1 X1 Y1\nG20\nG1 X2\n");
        FAIL() << "mixed units accepted";
    } catch (const scaffold::Error& e) {
        EXPECT_EQ(e.line(), 3u);
        EXPECT_NE(std::string(e.what()).find("mixed units"), std::string::npos);
    }
}

TEST(Machine, ErrorsCarryFileAndLine) {
    try {
        run("G1 X1\nG1 X2\nG1 Y1.2.3\n");
        FAIL();
    } catch (const scaffold::Error& e) {
        EXPECT_EQ(std::string(e.what()).rfind("test.gcode:3: malformed number", 0), 0u) << e.what();
    }
    EXPECT_THROW(run("G1 X1e9\n"), scaffold::Error);
    EXPECT_THROW(run("GCDE\x01\x00\x00\x00"), scaffold::Error);
    EXPECT_THROW(run(""), scaffold::Error);
}

TEST(Machine, FanToolAndFeedAreModal) {
    Program p = run("T1\nM106 S128\nG1 X1 F1200\nG1 X2\n");
    ASSERT_EQ(p.moves.size(), 2u);
    EXPECT_EQ(p.moves[1].tool, 1);
    EXPECT_FLOAT_EQ(p.moves[1].feed_mm_per_min, 1200);
}
