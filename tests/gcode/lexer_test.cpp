#include <gtest/gtest.h>

#include <string>

#include "gcode/lexer.hpp"

using scaffold::gcode::Command;
using scaffold::gcode::lex;

TEST(Lexer, WordsWithoutSpacesLowercaseAndComment) {
    Command c;
    EXPECT_STREQ(lex("g1x10.5Y-2e.25 F1800 ; perimeter", c), "");
    EXPECT_TRUE(c.is('G', 1));
    ASSERT_EQ(c.word_count, 4);
    EXPECT_DOUBLE_EQ(c.get('X', 0), 10.5);
    EXPECT_DOUBLE_EQ(c.get('Y', 0), -2);
    EXPECT_DOUBLE_EQ(c.get('E', 0), 0.25);
    EXPECT_DOUBLE_EQ(c.get('F', 0), 1800);
    EXPECT_EQ(c.comment, "perimeter");
}

TEST(Lexer, LineNumberChecksumAndCrlf) {
    Command c;
    EXPECT_STREQ(lex("N123 G1 X1 Y+2*57\r", c), "");
    EXPECT_TRUE(c.is('G', 1));
    EXPECT_DOUBLE_EQ(c.get('X', 0), 1);
    EXPECT_DOUBLE_EQ(c.get('Y', 0), 2);
    EXPECT_EQ(c.word_count, 2);
}

TEST(Lexer, CommentsBlankAndFreeText) {
    Command c;
    EXPECT_STREQ(lex(";TYPE:Perimeter", c), "");
    EXPECT_EQ(c.letter, 0);
    EXPECT_EQ(c.comment, "TYPE:Perimeter");
    EXPECT_STREQ(lex("", c), "");
    EXPECT_EQ(c.letter, 0);
    EXPECT_STREQ(lex("M117 X=1 done 50%", c), "");  // free text, not words
    EXPECT_TRUE(c.is('M', 117));
    EXPECT_EQ(c.word_count, 0);
    EXPECT_STREQ(lex("G29.1 Z0.2", c), "");
    EXPECT_EQ(c.code, 29);
    EXPECT_EQ(c.subcode, 1);
}

TEST(Lexer, MalformedNumbersAreReported) {
    Command c;
    EXPECT_STRNE(lex("G1 X1.2.3 Y4", c), "");
    EXPECT_STRNE(lex("G1 X1e", c), "");
    EXPECT_STRNE(lex("G1 X? Y1", c), "");
    EXPECT_STRNE(lex("G1 Xnan", c), "");
    EXPECT_STRNE(lex("G1 Xinf", c), "");
    EXPECT_STRNE(lex("G", c), "");
    // A custom G-code placeholder the slicer did not fill in says so.
    EXPECT_EQ(std::string(lex("G1 X0 Y{machine_depth} ;Present print", c)).rfind("a slicer placeholder left unfilled", 0), 0u);
}

// A post-processor passes through what it does not need: only the commands
// whose words change the tracked state are parsed strictly.
TEST(Lexer, FirmwareSyntaxInOtherCommandsPassesThrough) {
    Command c;
    EXPECT_STREQ(lex("M1002 set_gcode_claim_speed_level : 5", c), "");
    EXPECT_EQ(c.letter, 'M');
    EXPECT_EQ(c.code, 1002);
    EXPECT_EQ(c.word_count, 0);
    EXPECT_STREQ(lex("M1002 gcode_claim_action : 2", c), "");
    EXPECT_STREQ(lex("M624 AQAAAAAAAAA=", c), "");
    EXPECT_STREQ(lex("M204 S10000 ; accel", c), "");
    EXPECT_EQ(c.word_count, 1);
    EXPECT_STRNE(lex("G1 X1 : 2", c), "");
    EXPECT_STRNE(lex("M106 S1.2.3", c), "");
}
