#pragma once
// Layer stacks built directly (no G-code) for the planner's tests.
#include <cmath>

#include "layers/layer_stack.hpp"

namespace scaffold::test {

// 0.2 mm layers up to `top` with a speck of model far away (at the origin),
// bounds reaching `extent` mm, for the real Obstacles.
inline layers::LayerStack empty_stack(double top, double extent = 60) {
    layers::LayerStack st;
    int n = static_cast<int>(std::lround(top / 0.2));
    for (int i = 0; i < n; ++i) {
        layers::Layer l;
        l.z = 0.2 * (i + 1);
        l.height = 0.2;
        l.below = i - 1;
        l.on_bed = i == 0;
        l.segments.push_back({0, 0, 0.5f, 0, 0.45f, gcode::Role::Perimeter, 0});
        st.layers.push_back(l);
    }
    st.bounds = {-5, -5, extent, extent};
    return st;
}

}  // namespace scaffold::test
