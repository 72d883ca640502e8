#include <gtest/gtest.h>

#include "layers/layer_stack.hpp"
#include "plan/obstacles.hpp"
#include "plan/pillars.hpp"

using namespace scaffold;

namespace {

void outline(layers::Layer& l, double x0, double y0, double x1, double y1, gcode::Role role) {
    const float xs[5] = {float(x0), float(x1), float(x1), float(x0), float(x0)};
    const float ys[5] = {float(y0), float(y0), float(y1), float(y1), float(y0)};
    for (int k = 0; k < 4; ++k)
        l.segments.push_back({xs[k], ys[k], xs[k + 1], ys[k + 1], 0.45f, role, static_cast<std::uint32_t>(l.segments.size())});
}

// A hollow 20 mm box (walls only, like the holes of sparse infill) on 0.2 mm
// layers up to 4 mm, a skirt loop 5 mm around it on the first layer.
layers::LayerStack hollow_box() {
    layers::LayerStack st;
    for (int i = 0; i < 20; ++i) {
        layers::Layer l;
        l.z = 0.2 * (i + 1);
        l.height = 0.2;
        l.below = i - 1;
        l.on_bed = i == 0;
        if (i == 0) outline(l, 95, 95, 125, 125, gcode::Role::Skirt);
        outline(l, 100, 100, 120, 120, gcode::Role::ExternalPerimeter);
        st.layers.push_back(l);
    }
    st.bounds = {95, 95, 125, 125};
    return st;
}

}  // namespace

TEST(Obstacles, InsideThePartIsNoRoomOutsideTheSkirtLoopIs) {
    Settings s;
    const auto st = hollow_box();
    const plan::Obstacles obs(st, s);
    // 10 mm from every wall, but inside the part.
    EXPECT_FALSE(obs.disc_clear(10, 110, 110, 1.0));
    // Between the box and the skirt: clear (the skirt encloses nothing).
    EXPECT_TRUE(obs.disc_clear(0, 97.5, 110, 1.0));
    EXPECT_TRUE(obs.disc_clear(10, 90, 110, 1.0));
}

TEST(Obstacles, NoPillarDownThroughAHollowPart) {
    Settings s;
    auto st = hollow_box();
    // A lid 2 mm wider than the box on the top layer: a point over the lid's
    // middle must not be held by a pillar standing inside the box.
    layers::Layer lid;
    lid.z = 4.2;
    lid.height = 0.2;
    lid.below = 19;
    for (double y = 98.2; y < 122; y += 0.4)
        lid.segments.push_back({98.2f, float(y), 121.8f, float(y), 0.45f, gcode::Role::SolidInfill,
                                static_cast<std::uint32_t>(lid.segments.size())});
    st.layers.push_back(lid);
    const plan::Obstacles obs(st, s);
    auto chain = plan::drop_pillar(110, 110, 20, plan::Top::Contact, st, obs, s);
    if (chain)
        for (const auto& c : *chain) {
            bool inside = c.x0 > 100 && c.x0 < 120 && c.y0 > 100 && c.y0 < 120;
            EXPECT_FALSE(inside) << "column at " << c.x0 << ", " << c.y0;
        }
}
