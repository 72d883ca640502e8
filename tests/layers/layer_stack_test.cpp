#include <gtest/gtest.h>

#include <cmath>

#include "gcode/error.hpp"
#include "gcode/reader.hpp"
#include "layers/layer_stack.hpp"
#include "support/synth.hpp"

using namespace scaffold;

namespace {
layers::LayerStack stack_of(const std::string& text) {
    auto p = gcode::parse(text, "t.gcode");
    return layers::build_layers(p, build_settings(p, {}, {}));
}
}  // namespace

TEST(LayerStack, ZHopTravelDoesNotMakeALayer) {
    scaffold::testing::SynthGcode g;
    g.layer(0.2);
    g.filled_rect(10, 10, 20, 20);
    g.raw("G1 Z0.6 F7800");  // hop
    g.raw("G1 X40 Y40");
    g.raw("G1 Z0.2");
    g.extrude(45, 40);
    g.layer(0.4);
    g.filled_rect(10, 10, 20, 20);
    auto s = stack_of(g.str());
    ASSERT_EQ(s.layers.size(), 2u);
    EXPECT_NEAR(s.layers[0].z, 0.2, 1e-6);
    EXPECT_NEAR(s.layers[1].z, 0.4, 1e-6);
    EXPECT_TRUE(s.layers[0].on_bed);
    EXPECT_EQ(s.layers[1].below, 0);
}

TEST(LayerStack, VariableLayerHeights) {
    scaffold::testing::SynthGcode g;
    double zs[] = {0.2, 0.3, 0.45, 0.55, 0.8};
    for (double z : zs) {
        g.layer(z);
        g.filled_rect(10, 10, 20, 20);
    }
    auto s = stack_of(g.str());
    ASSERT_EQ(s.layers.size(), 5u);
    double heights[] = {0.2, 0.1, 0.15, 0.1, 0.25};
    for (int i = 0; i < 5; ++i) EXPECT_NEAR(s.layers[i].height, heights[i], 1e-5) << i;
}

TEST(LayerStack, BoundariesFollowTheSlicerMarkers) {
    scaffold::testing::SynthGcode g;
    g.layer(0.2);
    g.filled_rect(10, 10, 20, 20);
    g.layer(0.4);
    g.filled_rect(10, 10, 20, 20);
    auto p = gcode::parse(g.str(), "t");
    auto s = layers::build_layers(p, build_settings(p, {}, {}));
    ASSERT_EQ(s.layers.size(), 2u);
    EXPECT_EQ(p.line_text(s.layers[1].first_line), ";LAYER_CHANGE");
    EXPECT_EQ(s.layers[0].end_line, s.layers[1].first_line);
    EXPECT_EQ(s.layers[1].end_line, p.lines.size());
}

TEST(LayerStack, WidthFromEWhenTheSlicerGivesNone) {
    // 10 mm at 0.2 mm layers with the E of a 0.5 mm wide bead.
    double w = 0.5, h = 0.2, fd = 1.75;
    double area = (w - h) * h + M_PI * h * h / 4;
    double e = area * 10 / (M_PI * fd * fd / 4);
    EXPECT_NEAR(layers::width_from_e(e, 10, h, fd), 0.5, 1e-9);
    char buf[200];
    std::snprintf(buf, sizeof buf, "G90\nM82\nG92 E0\nG1 Z0.2\nG1 X0 Y0\nG1 X10 Y0 E%.6f\n", e);
    auto s = stack_of(buf);
    EXPECT_NEAR(s.layers[0].segments[0].width, 0.5, 1e-3);
}

TEST(LayerStack, PurgeLineBeforeTheFirstLayerRestsOnTheBed) {
    auto s = stack_of("G90\nM82\nG92 E0\nG1 X0.1 Y20 Z0.3\nG1 X0.1 Y200 E15\nG1 Z0.2\nG1 X100 Y100\n"
                      "G1 X110 Y100 E16\nG1 Z0.4\nG1 X100 Y100\nG1 X110 Y100 E17\n");
    ASSERT_EQ(s.layers.size(), 3u);
    EXPECT_TRUE(s.layers[0].on_bed);
    EXPECT_TRUE(s.layers[1].on_bed);
    EXPECT_FALSE(s.layers[2].on_bed);
    EXPECT_EQ(s.layers[2].below, 1);
    EXPECT_NEAR(s.layers[2].height, 0.2, 1e-6);
    EXPECT_GT(s.bounds.min_x, 50);  // the purge line does not stretch the raster
}

TEST(LayerStack, NoExtrusionIsAnError) {
    EXPECT_THROW(stack_of("G28\nG1 X10 Y10\n"), Error);
}

// PrusaSlicer says ;HEIGHT:0.4 again for an overhang perimeter's beads (its
// bridge flow is round); the layer's height is the first one after its
// ;LAYER_CHANGE. Read as the last, the layer at z 0.4 was 0.4 thick and
// took for resting on the bed.
TEST(LayerStack, TheLayersHeightIsTheFirstOneItsCommentGives) {
    auto s = stack_of("G90\nM83\n;LAYER_CHANGE\n;Z:0.2\n;HEIGHT:0.2\nG1 Z0.2\nG1 X0 Y0\nG1 X10 Y0 E0.5\n"
                      ";LAYER_CHANGE\n;Z:0.4\n;HEIGHT:0.2\nG1 Z0.4\nG1 X0 Y0\nG1 X10 Y0 E0.5\n"
                      ";TYPE:Overhang perimeter\n;HEIGHT:0.4\nG1 X10 Y5 E0.5\n");
    ASSERT_EQ(s.layers.size(), 2u);
    EXPECT_NEAR(s.layers[1].nominal_height, 0.2, 1e-9);
    EXPECT_FALSE(s.layers[1].on_bed);
}

// Beads at a layer's height after the next layer's comment (a support block
// after Bambu Studio's label block, which closes past ; CHANGE_LAYER) stay
// in their layer, and each layer keeps its own comment's height.
TEST(LayerStack, BeadsAfterTheNextLayersCommentKeepTheirLayersHeight) {
    auto s = stack_of("G90\nM83\n; CHANGE_LAYER\n; Z_HEIGHT: 0.2\n; LAYER_HEIGHT: 0.2\nG1 Z0.2\nG1 X0 Y0\n"
                      "G1 X10 Y0 E0.5\n; CHANGE_LAYER\n; Z_HEIGHT: 0.48\n; LAYER_HEIGHT: 0.28\n"
                      "; LAYER_HEIGHT: 0.2\nG1 X20 Y0\nG1 X30 Y0 E0.5\n; LAYER_HEIGHT: 0.28\n"
                      "G1 Z0.48\nG1 X0 Y0\nG1 X10 Y0 E0.7\n");
    ASSERT_EQ(s.layers.size(), 2u);
    EXPECT_EQ(s.layers[0].segments.size(), 2u);
    EXPECT_NEAR(s.layers[0].nominal_height, 0.2, 1e-9);
    EXPECT_NEAR(s.layers[1].nominal_height, 0.28, 1e-9);
    EXPECT_NEAR(s.layers[1].height, 0.28, 1e-6);
}
