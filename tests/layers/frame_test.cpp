// The plan's own frame (layers/frame.hpp): where the model's lowest-leftmost
// bead end is, to the micron, and beads moved into it exactly.
#include <gtest/gtest.h>

#include <cstring>

#include "layers/frame.hpp"
#include "support/stacks.hpp"

using namespace scaffold;

namespace {

// A model (an L of perimeters) with its lowest x at 100.123 and lowest y at
// 50.456, moved by (dx, dy) as a slicer writes it (three decimals); a skirt
// loop and a piece of support further out on the first layer.
layers::LayerStack placed(double dx, double dy) {
    auto at = [](double v) { return static_cast<double>(static_cast<float>(std::round(v * 1000) / 1000)); };
    return test::stack_of(
        3,
        [&](int i, layers::Layer& l) {
            test::bead(l, at(100.123 + dx), at(60.2 + dy), at(120.777 + dx), at(60.2 + dy), gcode::Role::Perimeter);
            test::bead(l, at(110.5 + dx), at(50.456 + dy), at(110.5 + dx), at(70.31 + dy), gcode::Role::Perimeter);
            if (i == 0) {
                test::bead(l, at(90 + dx), at(40 + dy), at(130 + dx), at(40 + dy), gcode::Role::Skirt);
                test::bead(l, at(95 + dx), at(45 + dy), at(96 + dx), at(45 + dy), gcode::Role::Support);
            }
        },
        {89.7, 39.7, 131, 71});
}

bool same_bits(const layers::LayerStack& a, const layers::LayerStack& b) {
    if (a.layers.size() != b.layers.size()) return false;
    for (std::size_t l = 0; l < a.layers.size(); ++l) {
        const auto &sa = a.layers[l].segments, &sb = b.layers[l].segments;
        if (sa.size() != sb.size()) return false;
        for (std::size_t k = 0; k < sa.size(); ++k)
            if (std::memcmp(&sa[k].x0, &sb[k].x0, 4 * sizeof(float)) != 0) return false;
    }
    return true;
}

}  // namespace

TEST(Frame, ItsOriginIsTheModelsLowestBeadEndsNotTheSkirtOrSupport) {
    const layers::Frame f = layers::model_frame(placed(0, 0));
    EXPECT_EQ(f.dx_um, 100123);
    EXPECT_EQ(f.dy_um, 50456);
    EXPECT_DOUBLE_EQ(f.dx(), 100.123);
    EXPECT_TRUE(layers::model_frame(layers::LayerStack{}).identity());
}

TEST(Frame, MovedInAndBackTheBeadsAreTheSameToTheBit) {
    const layers::LayerStack before = placed(0, 0);
    layers::LayerStack st = before;
    const layers::Frame f = layers::model_frame(st);
    layers::move_stack(st, f, true);
    EXPECT_FLOAT_EQ(st.layers[1].segments[0].x0, 0.0f);
    EXPECT_FLOAT_EQ(st.layers[1].segments[1].y0, 0.0f);
    EXPECT_NEAR(st.bounds.min_x, 89.7 - 100.123, 1e-9);
    EXPECT_FALSE(same_bits(st, before));
    layers::move_stack(st, f, false);
    EXPECT_TRUE(same_bits(st, before));
    EXPECT_NEAR(st.bounds.min_x, 89.7, 1e-9);
}

// Floats hold 100.123 and 137.44 to different roundings (about 4e-6 mm): a
// bead's edge on a cell boundary would fall either side of it. In their
// frames the same beads anywhere on the bed are equal to the bit.
TEST(Frame, TheSameBeadsAnywhereOnTheBedAreEqualInTheirFrames) {
    layers::LayerStack here = placed(0, 0);
    layers::move_stack(here, layers::model_frame(here), true);
    for (const auto& [dx, dy] : {std::pair{37.317, 12.049}, std::pair{0.05, -0.03}, std::pair{-60.001, 88.888}}) {
        layers::LayerStack there = placed(dx, dy);
        const layers::Frame f = layers::model_frame(there);
        EXPECT_EQ(f.dx_um, 100123 + std::lround(dx * 1000));
        layers::move_stack(there, f, true);
        EXPECT_TRUE(same_bits(here, there)) << dx << ", " << dy;
    }
}
