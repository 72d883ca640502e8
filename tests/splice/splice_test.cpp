#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "check/printability.hpp"
#include "gcode/lexer.hpp"
#include "gcode/machine.hpp"
#include "gcode/reader.hpp"
#include "gcode/writer.hpp"
#include "layers/layer_stack.hpp"
#include "splice/splice.hpp"
#include "support/synth.hpp"
#include "toolpath/support_paths.hpp"

using namespace scaffold;

namespace {

std::string render(const gcode::Program& p, std::vector<gcode::Edit> edits) {
    char* buf = nullptr;
    std::size_t size = 0;
    std::FILE* f = open_memstream(&buf, &size);
    gcode::write_edited(f, p, std::move(edits));
    std::fclose(f);
    std::string out(buf, size);
    std::free(buf);
    return out;
}

// Moves of the output that come from the original lines (outside blocks).
std::vector<gcode::Move> model_moves(const gcode::Program& out) {
    std::vector<bool> inserted(out.lines.size(), false);
    bool in = false;
    for (std::size_t i = 0; i < out.lines.size(); ++i) {
        std::string_view t = out.line_text(i);
        if (t.rfind("; scaffold: support for", 0) == 0) in = true;
        inserted[i] = in;
        if (t == "; scaffold: end") in = false;
    }
    std::vector<gcode::Move> m;
    for (const auto& mv : out.moves)
        if (!inserted[mv.line]) m.push_back(mv);
    return m;
}

// A tower of `layers` layers with the given preamble lines (E mode etc.).
std::string tower(const std::string& preamble_extra, bool fw, double lift) {
    scaffold::testing::SynthGcode g;
    g.raw(preamble_extra);
    for (int l = 1; l <= 6; ++l) {
        g.layer(0.2 * l);
        g.filled_rect(100, 100, 110, 110);
        if (fw) g.raw("G10");
        else g.raw("G1 E" + std::to_string(0) + " ; placeholder");
        if (lift > 0) g.raw("G1 Z" + std::to_string(0.2 * l + lift));
    }
    std::string s = g.str();
    // The placeholder is a no-op retract marker only used to keep the shape; drop it.
    std::string out;
    std::size_t pos = 0;
    while (pos < s.size()) {
        std::size_t nl = s.find('\n', pos);
        std::string line = s.substr(pos, nl - pos);
        if (line.find("placeholder") == std::string::npos) out += line + "\n";
        pos = nl + 1;
    }
    return out;
}

// One pillar beside the tower, from the bed to z 1.0.
plan::Scaffold one_pillar(double raft_size) {
    plan::Scaffold sc;
    plan::Column c;
    c.x0 = c.x1 = 130;
    c.y0 = c.y1 = 105;
    c.z0 = 0;
    c.z1 = 1.0;
    c.raft_size = raft_size;
    sc.columns.push_back(c);
    return sc;
}

// A file's layers with one_pillar(0) beside, spliced.
struct Spliced {
    gcode::Program in;
    Settings s;
    layers::LayerStack stack;
    splice::SpliceResult res;
};
Spliced splice_one_pillar(const std::string& text) {
    Spliced r{gcode::parse(text, "in"), {}, {}, {}};
    r.s = build_settings(r.in, {}, {});
    r.stack = layers::build_layers(r.in, r.s);
    r.res = splice::splice(r.in, r.stack, toolpath::make_paths(one_pillar(0), r.stack, r.s), r.s);
    return r;
}

void check_round(const std::string& text, const char* what) {
    SCOPED_TRACE(what);
    gcode::Program in = gcode::parse(text, "in");
    Settings s = build_settings(in, {}, {});
    layers::LayerStack stack = layers::build_layers(in, s);
    const plan::Scaffold sc = one_pillar(5);
    auto paths = toolpath::make_paths(sc, stack, s);
    ASSERT_EQ(paths.layers.size(), 5u);  // layers at z 0.2 .. 1.0
    auto res = splice::splice(in, stack, paths, s);
    EXPECT_EQ(res.layers_touched, 5);
    EXPECT_GT(res.filament_mm, 0);
    gcode::Program out = gcode::parse(render(in, res.edits), "out");
    auto mm = model_moves(out);
    ASSERT_EQ(mm.size(), in.moves.size());
    for (std::size_t i = 0; i < mm.size(); ++i) {
        const auto &a = in.moves[i], &b = mm[i];
        ASSERT_EQ(a.kind, b.kind) << "move " << i;
        ASSERT_FLOAT_EQ(a.e, b.e) << "move " << i;
        ASSERT_FLOAT_EQ(a.x0, b.x0) << "move " << i;
        ASSERT_FLOAT_EQ(a.y0, b.y0) << "move " << i;
        ASSERT_FLOAT_EQ(a.z0, b.z0) << "move " << i;
        ASSERT_FLOAT_EQ(a.x1, b.x1) << "move " << i;
        ASSERT_FLOAT_EQ(a.feed_mm_per_min, b.feed_mm_per_min) << "move " << i;
    }
    // Support extrusions: typed as support, at the layer's z, never below the layer.
    double support_e = 0;
    for (const auto& m : out.moves) {
        if (m.kind != gcode::MoveKind::Extrude || m.role != gcode::Role::Support) continue;
        support_e += m.e;
        EXPECT_GT(m.x0, 120);
    }
    EXPECT_NEAR(support_e, res.filament_mm, 1e-3);
    // Output layers: the same Z set, support only adds to them.
    auto out_stack = layers::build_layers(out, s);
    EXPECT_EQ(out_stack.layers.size(), stack.layers.size());
}

}  // namespace

TEST(Splice, AbsoluteE) { check_round(tower("", false, 0), "absolute E"); }
TEST(Splice, RelativeE) { check_round(tower("M83", false, 0), "relative E"); }
TEST(Splice, FirmwareRetraction) { check_round(tower("", true, 0), "G10/G11"); }
TEST(Splice, ZHop) { check_round(tower("", false, 0.4), "z-hop"); }

TEST(Splice, FilamentForCrossSection) {
    // 0.45 x 0.2 bead, 10 mm: area (0.25*0.2 + pi*0.01) mm^2 over the filament's 2.405 mm^2.
    double expect = 10 * (0.25 * 0.2 + M_PI * 0.04 / 4) / (M_PI * 1.75 * 1.75 / 4);
    EXPECT_NEAR(splice::filament_for(10, 0.45, 0.2, 1.75), expect, 1e-12);
}

// Support never goes inside an object's label block: cancelling the object
// in the printer (Klipper EXCLUDE_OBJECT, M486, Orca's start/stop comments)
// would drop it. Creality Print closes the block only after the next
// layer's change: the block is inserted before the block's start instead.
TEST(Splice, NeverInsideAnObjectsLabelBlock) {
    for (const char* kind : {"klipper", "m486", "orca"}) {
        SCOPED_TRACE(kind);
        const std::string k = kind;
        const std::string open = k == "klipper" ? "EXCLUDE_OBJECT_START NAME=part" : k == "m486" ? "M486 S0" : "; start printing object, unique label id: 1";
        const std::string close = k == "klipper" ? "EXCLUDE_OBJECT_END NAME=part" : k == "m486" ? "M486 S-1" : "; stop printing object, unique label id: 1";
        scaffold::testing::SynthGcode g;
        g.raw(open);
        for (int l = 1; l <= 6; ++l) {
            g.layer(0.2 * l);  // the layer change inside the open block
            if (l > 1) {
                g.raw(close);
                g.raw(open);
            }
            g.filled_rect(100, 100, 110, 110);
        }
        g.raw(close);
        gcode::Program in = gcode::parse(g.str(), "in");
        Settings s = build_settings(in, {}, {});
        layers::LayerStack stack = layers::build_layers(in, s);
        const plan::Scaffold sc = one_pillar(0);
        auto paths = toolpath::make_paths(sc, stack, s);
        auto res = splice::splice(in, stack, paths, s);
        EXPECT_EQ(res.blocks_split, 0u);
        gcode::Program out = gcode::parse(render(in, res.edits), "out");
        int depth = 0, blocks = 0;
        for (std::size_t i = 0; i < out.lines.size(); ++i) {
            std::string_view t = out.line_text(i);
            if (t == open) ++depth;
            if (t == close) --depth;
            if (t.rfind("; scaffold: support for", 0) == 0) {
                ++blocks;
                EXPECT_EQ(depth, 0) << "support block inside an object block at output line " << i + 1;
            }
        }
        EXPECT_EQ(blocks, 5);
        EXPECT_EQ(depth, 0);
    }
}

// Extruding ends a retraction: Simplify3D primes 0.2 mm less than it
// retracts, and the rest must not add up into the next block's prime.
TEST(Splice, ExtrudingEndsARetraction) {
    gcode::MachineState st;
    gcode::Command cmd;
    std::vector<gcode::Move> moves;
    for (const char* l : {"M82", "G92 E0", "G1 E-6.5 F3600", "G1 X10 Y0 F9000", "G1 E-0.2 F3600", "G92 E0",
                          "G1 X20 Y0 E0.5 F4000"}) {
        ASSERT_STREQ(gcode::lex(l, cmd), "");
        ASSERT_EQ(gcode::step(st, cmd, 0, moves), nullptr);
    }
    EXPECT_FALSE(st.retracted());
    for (const char* l : {"G92 E0", "G1 E-6.5 F3600"}) {
        gcode::lex(l, cmd);
        gcode::step(st, cmd, 0, moves);
    }
    EXPECT_NEAR(st.retracted_mm, 6.5, 1e-9);
}

// METHOD's travel rule: a travel that would pass over support this block
// printed (within 0.2 mm of it after leaving it) rises 0.2 mm first and comes
// down after; one that leaves its bead and never comes back does not.
TEST(Splice, TravelOverFreshSupportIsLifted) {
    gcode::Program in = gcode::parse(tower("", false, 0), "in");
    Settings s = build_settings(in, {}, {});
    layers::LayerStack stack = layers::build_layers(in, s);
    toolpath::SupportPaths paths;
    toolpath::LayerPaths lp;
    lp.layer = 1;  // z 0.4
    auto line = [](double x0, double y0, double x1, double y1) {
        toolpath::Path p;
        p.points = {{x0, y0}, {x1, y1}};
        p.retract = false;
        return p;
    };
    lp.paths = {line(120, 105, 130, 105),   // A along y 105
                line(125, 108, 125, 110),   // B: reached from A's end without coming back to A
                line(125, 102, 127, 102)};  // C: reached from B across A
    paths.layers.push_back(lp);
    auto res = splice::splice(in, stack, paths, s);
    ASSERT_EQ(res.edits.size(), 1u);
    const std::string& block = res.edits[0].text;
    const std::size_t b_start = block.find("X125 Y108");
    const std::size_t c_start = block.find("X125 Y102");
    ASSERT_NE(b_start, std::string::npos);
    ASSERT_NE(c_start, std::string::npos);
    const std::size_t a_end = block.find("X130 Y105");
    ASSERT_NE(a_end, std::string::npos);
    // A -> B: no Z move. B -> C: up to 0.6 before, down to 0.4 after.
    EXPECT_EQ(block.substr(a_end, b_start - a_end).find(" Z"), std::string::npos) << block;
    const std::string bc = block.substr(block.find("X125 Y110"), c_start - block.find("X125 Y110"));
    EXPECT_NE(bc.find("G1 Z0.6"), std::string::npos) << block;
    const std::size_t after_c = block.find('\n', c_start);
    EXPECT_EQ(block.substr(after_c + 1, 9), "G1 Z0.4 F") << block;
}

// Viewers and scaffold-check give a bead the width last said in a comment
// (";WIDTH:0.62", Bambu's "; LINE_WIDTH: 0.62"): the block says its own
// beads' width in the file's words and gives the slicer's back after it, so
// the support reads 0.45 mm wide and the model's beads keep theirs.
TEST(Splice, SaysTheSupportsWidthAndGivesTheSlicersBack) {
    for (const std::string say : {";WIDTH:", "; LINE_WIDTH: "}) {
        SCOPED_TRACE(say);
        scaffold::testing::SynthGcode g;
        for (int l = 1; l <= 6; ++l) {
            g.layer(0.2 * l);
            g.raw(say + "0.62");
            g.filled_rect(100, 100, 110, 110);
        }
        auto [in, s, stack, res] = splice_one_pillar(g.str());
        ASSERT_EQ(res.edits.size(), 5u);
        EXPECT_NE(res.edits[0].text.find(say + "0.450\n"), std::string::npos) << res.edits[0].text;
        EXPECT_NE(res.edits[0].text.find(say + "0.62\n; scaffold: end"), std::string::npos) << res.edits[0].text;
        gcode::Program out = gcode::parse(render(in, res.edits), "out");
        int support = 0, model = 0;
        for (const auto& m : out.moves) {
            if (m.kind != gcode::MoveKind::Extrude) continue;
            const bool sup = m.role == gcode::Role::Support;
            EXPECT_NEAR(m.width, sup ? s.support_width : 0.62, 1e-6) << "line " << m.line + 1;
            (sup ? support : model)++;
        }
        EXPECT_GT(support, 0);
        EXPECT_GT(model, 0);
    }
    // A file that says no widths gets none.
    gcode::Program in = gcode::parse(tower("", false, 0), "in");
    Settings s = build_settings(in, {}, {});
    layers::LayerStack stack = layers::build_layers(in, s);
    auto res = splice::splice(in, stack, toolpath::make_paths(one_pillar(0), stack, s), s);
    ASSERT_FALSE(res.edits.empty());
    EXPECT_EQ(res.edits[0].text.find("WIDTH"), std::string::npos);
}

// Bambu Studio closes the layer's last object after the next layer's
// comment and the object's wipe: the support goes after that close (and
// after M625, where the firmware stops skipping a cancelled object), so
// the object's moves of the layer come before it and none of its travels
// cross the fresh support. With a bead between, it goes before the block.
TEST(Splice, AfterALabelBlockThatClosesPastTheLayerChange) {
    const std::string open = "; start printing object, unique label id: 1", close = "; stop printing object, unique label id: 1";
    for (const bool bead_between : {false, true}) {
        SCOPED_TRACE(bead_between ? "a bead before the close" : "only a wipe before the close");
        scaffold::testing::SynthGcode g;
        g.layer(0.2);
        g.raw(open);
        g.raw("M624 AQAAAAAAAAA=");
        g.filled_rect(100, 100, 110, 110);
        for (int l = 2; l <= 6; ++l) {
            char z[96];
            std::snprintf(z, sizeof z, ";LAYER_CHANGE\n;Z:%.1f\n;HEIGHT:0.2", 0.2 * l);
            g.raw(z);
            g.travel(100, 104);  // the wipe: no bead
            std::snprintf(z, sizeof z, "G1 Z%.1f", 0.2 * l);
            if (bead_between) {  // the next layer's first bead inside the block
                g.raw(z);
                g.extrude(100, 106);
            }
            g.raw(close);
            g.raw("M625");
            if (!bead_between) g.raw(z);
            g.raw(open);
            g.raw("M624 AQAAAAAAAAA=");
            g.filled_rect(100, 100, 110, 110);
        }
        g.raw(close);
        g.raw("M625");
        auto [in, s, stack, res] = splice_one_pillar(g.str());
        ASSERT_EQ(res.edits.size(), 5u);
        EXPECT_EQ(res.blocks_split, 0u);
        for (const gcode::Edit& e : res.edits) {
            const std::string_view before = in.line_text(e.line - 1), after = in.line_text(e.line);
            if (bead_between) EXPECT_EQ(after, open) << "line " << e.line + 1;
            else EXPECT_EQ(before, "M625") << "line " << e.line + 1;
        }
        // Read back, each layer keeps its beads and its own stated height.
        gcode::Program out = gcode::parse(render(in, res.edits), "out");
        layers::LayerStack back = layers::build_layers(out, s);
        ASSERT_EQ(back.layers.size(), stack.layers.size());
        for (std::size_t i = 0; i < back.layers.size(); ++i) {
            EXPECT_NEAR(back.layers[i].z, stack.layers[i].z, 1e-6) << i;
            EXPECT_NEAR(back.layers[i].nominal_height, 0.2, 1e-6) << i;
        }
    }
}

// The support is named in the file's own words, which each viewer and
// host reads alone, and the slicer's role line is given back after it.
TEST(Splice, NamesTheSupportInTheFilesWords) {
    const std::pair<std::string, std::string> cases[] = {
        {";TYPE:External perimeter", ";TYPE:Support material"},  // PrusaSlicer
        {";TYPE:WALL-OUTER", ";TYPE:SUPPORT"},                   // Cura, ideaMaker
        {"; TYPE:WALL-OUTER", "; TYPE:SUPPORT"},                 // MatterControl
        {";TYPE:Thin wall", ";TYPE:Support material"},          // SuperSlicer
        {";TYPE:Outer wall", ";TYPE:Support"},                   // OrcaSlicer 1, Creality Print
        {"; FEATURE: Outer wall", "; FEATURE: Support"},         // Bambu Studio, OrcaSlicer 2
        {"; feature outer perimeter", "; feature support"},      // Simplify3D 4.1+, Kiri:Moto
        {"; 'Perimeter Path', 20.0 [feed mm/s], 30.0 [head mm/s]", "; 'Support (may Stack) Path'"},  // KISSlicer
    };
    for (const auto& [role, support] : cases) {
        SCOPED_TRACE(role);
        scaffold::testing::SynthGcode g;
        for (int l = 1; l <= 6; ++l) {
            g.layer(0.2 * l);
            g.raw(role);
            g.filled_rect(100, 100, 110, 110);
        }
        auto [in, s, stack, res] = splice_one_pillar(g.str());
        ASSERT_EQ(res.edits.size(), 5u);
        const std::string& t = res.edits[0].text;
        EXPECT_NE(t.find("\n" + support + "\n"), std::string::npos) << t;
        EXPECT_NE(t.find("\n" + role + "\n; scaffold: end"), std::string::npos) << t;
        EXPECT_EQ(t.find("TYPE:Unknown"), std::string::npos) << t;
        gcode::Program out = gcode::parse(render(in, res.edits), "out");
        std::vector<gcode::Role> model;
        for (const auto& m : in.moves)
            if (m.kind == gcode::MoveKind::Extrude) model.push_back(m.role);
        std::size_t support_moves = 0, k = 0;
        for (const auto& m : out.moves) {
            if (m.kind != gcode::MoveKind::Extrude) continue;
            if (m.role == gcode::Role::Support) {
                ++support_moves;
            } else if (k < model.size()) {
                EXPECT_EQ(m.role, model[k++]) << "line " << m.line + 1;
            }
        }
        EXPECT_GT(support_moves, 0u);
        EXPECT_EQ(k, model.size());
    }
}

// PrusaSlicer says ;HEIGHT:0.4 for an overhang perimeter's round beads;
// support after one says its own height and gives the slicer's back. Where
// the last height said is the layer's, nothing is added.
TEST(Splice, SaysTheSupportsHeightWhereTheLastSaidIsAnother) {
    scaffold::testing::SynthGcode g;
    for (int l = 1; l <= 6; ++l) {
        g.layer(0.2 * l);
        g.filled_rect(100, 100, 110, 110);
        if (l % 2 == 0) {
            g.raw(";TYPE:Overhang perimeter\n;HEIGHT:0.4");
            g.extrude(100, 111);
        }
    }
    auto [in, s, stack, res] = splice_one_pillar(g.str());
    ASSERT_EQ(res.edits.size(), 5u);
    for (std::size_t i = 0; i < res.edits.size(); ++i) {
        const std::string& t = res.edits[i].text;
        if (i % 2 == 1) {  // the layers at z 0.4 and 0.8 end with an overhang perimeter
            EXPECT_NE(t.find(";HEIGHT:0.200\n"), std::string::npos) << t;
            EXPECT_NE(t.find(";HEIGHT:0.4\n; scaffold: end"), std::string::npos) << t;
        } else {
            EXPECT_EQ(t.find("HEIGHT"), std::string::npos) << t;
        }
    }
}

// Each block is written from what the pass over the file found at its
// place: the same edits, filament and times on any number of threads.
TEST(Splice, TheSameBlocksOnAnyNumberOfThreads) {
    gcode::Program in = gcode::parse(tower("M83", false, 0.4), "in");
    Settings s = build_settings(in, {}, {});
    layers::LayerStack stack = layers::build_layers(in, s);
    plan::Scaffold sc = one_pillar(5);
    plan::Column other = sc.columns.front();
    other.y0 = other.y1 = 90;
    other.z1 = 0.6;
    sc.columns.push_back(other);
    const auto paths = toolpath::make_paths(sc, stack, s);
    ASSERT_EQ(paths.layers.size(), 5u);
    const splice::SpliceResult one = splice::splice(in, stack, paths, s, 1);
    ASSERT_EQ(one.edits.size(), 5u);
    for (int threads : {2, 3, 8}) {
        SCOPED_TRACE(threads);
        const splice::SpliceResult many = splice::splice(in, stack, paths, s, threads);
        ASSERT_EQ(many.edits.size(), one.edits.size());
        for (std::size_t i = 0; i < one.edits.size(); ++i) {
            EXPECT_EQ(many.edits[i].line, one.edits[i].line);
            EXPECT_EQ(many.edits[i].text, one.edits[i].text);
            EXPECT_EQ(many.block_seconds[i], one.block_seconds[i]);
        }
        EXPECT_EQ(many.filament_mm, one.filament_mm);
        EXPECT_EQ(many.seconds, one.seconds);
        EXPECT_EQ(many.layers_touched, 5);
    }
    // Each block starts where the layer's own moves end and restores the
    // machine as it found it: the relative-E tower's model moves unchanged.
    gcode::Program out = gcode::parse(render(in, one.edits), "out");
    EXPECT_EQ(model_moves(out).size(), in.moves.size());
}

// The output's moves worked out from the input's and the blocks are those
// reading the output back gives, and so is its print-time estimate.
TEST(Splice, TheOutputsMovesWithoutReadingItBack) {
    for (const auto& [text, what] : {std::pair{tower("", false, 0), "absolute E"}, std::pair{tower("M83", false, 0), "relative E"},
                                     std::pair{tower("", true, 0), "G10/G11"}, std::pair{tower("M83", false, 0.4), "z-hop"}}) {
        SCOPED_TRACE(what);
        gcode::Program in = gcode::parse(text, "in");
        Settings s = build_settings(in, {}, {});
        layers::LayerStack stack = layers::build_layers(in, s);
        const auto res = splice::splice(in, stack, toolpath::make_paths(one_pillar(5), stack, s), s, 2);
        ASSERT_EQ(res.block_states.size(), res.edits.size());
        const std::vector<gcode::Move> worked = splice::spliced_moves(in, res);
        const gcode::Program out = gcode::parse(render(in, res.edits), "out");
        ASSERT_GT(out.moves.size(), in.moves.size());
        ASSERT_EQ(worked.size(), out.moves.size());
        for (std::size_t i = 0; i < worked.size(); ++i) {
            const gcode::Move &a = worked[i], &b = out.moves[i];
            ASSERT_EQ(a.kind, b.kind) << "move " << i;
            ASSERT_EQ(a.x0, b.x0) << "move " << i;
            ASSERT_EQ(a.y0, b.y0) << "move " << i;
            ASSERT_EQ(a.z0, b.z0) << "move " << i;
            ASSERT_EQ(a.x1, b.x1) << "move " << i;
            ASSERT_EQ(a.y1, b.y1) << "move " << i;
            ASSERT_EQ(a.z1, b.z1) << "move " << i;
            ASSERT_EQ(a.e, b.e) << "move " << i;
            ASSERT_EQ(a.feed_mm_per_min, b.feed_mm_per_min) << "move " << i;
        }
        EXPECT_EQ(check::estimate_moves(worked, check::motion_limits(in)), check::estimate_print_time(out));
        EXPECT_GT(check::estimate_print_time(out), check::estimate_print_time(in));
    }
}
