#pragma once
// Layer stacks built directly (no G-code) for the planner's tests.
#include <cmath>
#include <functional>
#include <vector>

#include "layers/layer_stack.hpp"

namespace scaffold::test {

// `n` 0.2 mm layers (z, height, below, beneath, on_bed set), each filled by
// fill(index, layer), bounds as given: the planner's tests build their
// scenes on it.
inline layers::LayerStack stack_of(int n, const std::function<void(int, layers::Layer&)>& fill, layers::Bounds bounds) {
    layers::LayerStack st;
    for (int i = 0; i < n; ++i) {
        layers::Layer l;
        l.z = 0.2 * (i + 1);
        l.height = 0.2;
        l.below = i - 1;
        l.on_bed = i == 0;
        if (i > 0) l.beneath = {i - 1};
        fill(i, l);
        st.layers.push_back(std::move(l));
    }
    st.bounds = bounds;
    return st;
}

// Layers at the given heights, in that (printing) order: height from the
// one before, below and beneath it, on_bed the first; each then filled (and
// set straight, should it lie elsewhere) by fill(index, layer).
inline layers::LayerStack stack_at(const std::vector<double>& zs, const std::function<void(int, layers::Layer&)>& fill,
                                   layers::Bounds bounds) {
    layers::LayerStack st;
    for (std::size_t i = 0; i < zs.size(); ++i) {
        layers::Layer l;
        l.z = zs[i];
        l.height = i ? zs[i] - zs[i - 1] : zs[i];
        l.below = static_cast<int>(i) - 1;
        l.on_bed = i == 0;
        if (i > 0) l.beneath = {static_cast<int>(i) - 1};
        fill(static_cast<int>(i), l);
        st.layers.push_back(std::move(l));
    }
    st.bounds = bounds;
    return st;
}

// A bead from (x0, y0) to (x1, y1), 0.45 mm wide.
inline void bead(layers::Layer& l, double x0, double y0, double x1, double y1, gcode::Role role = gcode::Role::SolidInfill) {
    l.segments.push_back({float(x0), float(y0), float(x1), float(y1), 0.45f, role, static_cast<std::uint32_t>(l.segments.size())});
}

// 0.2 mm layers up to `top` with a speck of model far away (at the origin),
// bounds reaching `extent` mm, for the real Obstacles.
inline layers::LayerStack empty_stack(double top, double extent = 60) {
    return stack_of(static_cast<int>(std::lround(top / 0.2)),
                    [](int, layers::Layer& l) { bead(l, 0, 0, 0.5, 0, gcode::Role::Perimeter); }, {-5, -5, extent, extent});
}

}  // namespace scaffold::test
