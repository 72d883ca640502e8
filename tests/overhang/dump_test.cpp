#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include <unistd.h>

#include "gcode/error.hpp"
#include "gcode/reader.hpp"
#include "layers/layer_stack.hpp"
#include "overhang/dump.hpp"
#include "support/synth.hpp"

using namespace scaffold;
namespace fs = std::filesystem;

namespace {

std::string slurp(const fs::path& p) {
    std::ifstream in(p, std::ios::binary);
    std::stringstream ss;
    ss << in.rdbuf();
    return ss.str();
}

std::size_t occurrences(const std::string& text, const std::string& what) {
    std::size_t n = 0;
    for (std::size_t at = text.find(what); at != std::string::npos; at = text.find(what, at + 1)) ++n;
    return n;
}

fs::path scratch_dir(const char* name) {
    fs::path d = fs::temp_directory_path() / (std::string("scaffold-overhang-") + name + "-" + std::to_string(::getpid()));
    fs::remove_all(d);
    return d;
}

}  // namespace

TEST(OverhangDump, PointsJsonHasFixedDecimals) {
    overhang::SupportPoints p;
    p.points = {{1.23456, -2, 0.2, 3}, {10, 20.0006, 4.4, 12}};
    p.overhang_area_mm2 = 12.3456;
    fs::path dir = scratch_dir("json");
    fs::create_directories(dir);
    overhang::write_points_json((dir / "p.json").string(), p);
    EXPECT_EQ(slurp(dir / "p.json"),
              "{\"points\":[\n"
              "  {\"x\":1.235,\"y\":-2.000,\"z\":0.200,\"layer\":3},\n"
              "  {\"x\":10.000,\"y\":20.001,\"z\":4.400,\"layer\":12}],\n"
              "\"overhang_area_mm2\":12.346}\n");
    overhang::write_points_json((dir / "empty.json").string(), overhang::SupportPoints{});
    EXPECT_EQ(slurp(dir / "empty.json"), "{\"points\":[],\n\"overhang_area_mm2\":0.000}\n");
    EXPECT_THROW(overhang::write_points_json((dir / "no" / "such" / "dir.json").string(), p), Error);
    fs::remove_all(dir);
}

TEST(OverhangDump, OneSmallSvgPerOverhangLayer) {
    scaffold::testing::SynthGcode g;  // a 10 x 10 mm shelf at layer 21
    for (int l = 1; l <= 30; ++l) {
        g.layer(0.2 * l);
        g.filled_rect(100, 100, 110, 110);
        if (l > 20) g.filled_rect(110, 100, 120, 110);
    }
    auto program = gcode::parse(g.str(), "synth");
    Settings s = build_settings(program, {}, {});
    auto stack = layers::build_layers(program, s);
    auto over = overhang::find_overhangs(stack, s);
    auto points = overhang::place_points(over, stack, s);
    ASSERT_EQ(over.layers.size(), 1u);
    fs::path dir = scratch_dir("svg");
    overhang::write_layer_svgs((dir / "layers").string(), over, points, stack, s);
    std::vector<fs::path> files;
    for (const auto& e : fs::directory_iterator(dir / "layers")) files.push_back(e.path());
    ASSERT_EQ(files.size(), 1u);
    char name[32];
    std::snprintf(name, sizeof name, "layer-%04d.svg", over.layers[0].layer);
    EXPECT_EQ(files[0].filename().string(), name);
    std::string svg = slurp(files[0]);
    EXPECT_EQ(svg.rfind("<svg ", 0), 0u);
    EXPECT_NE(svg.find("</svg>"), std::string::npos);
    // Colours: layer below, the layer, overhang cells.
    for (const char* fill : {"#b0b0b0", "#9ec5fe", "#d62828"}) EXPECT_NE(svg.find(fill), std::string::npos) << fill;
    // A dot and a radius circle per point.
    EXPECT_EQ(occurrences(svg, "<circle"), 2 * points.points.size());
    // Runs, not cells: the 10 x 10 mm overhang is ~100 rows of one run each
    // (~10,000 cells); the two layers' material a few runs a row.
    std::size_t red = occurrences(svg.substr(svg.find("#d62828")), "<rect");
    EXPECT_LE(red, 130u);
    EXPECT_LT(occurrences(svg, "<rect"), 1200u);
    EXPECT_LT(svg.size(), 100'000u);
    fs::remove_all(dir);
}
