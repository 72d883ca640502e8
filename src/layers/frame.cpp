#include "layers/frame.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "gcode/role.hpp"
#include "layers/objects.hpp"

namespace scaffold::layers {

namespace {

long long microns(double v) { return std::llround(v * 1000.0); }

}  // namespace

Frame frame_at(double x, double y) { return {microns(x), microns(y)}; }

Frame model_frame(const LayerStack& stack) {
    return model_frame(stack, [](const Layer& layer, const Segment& s) {
        return model_bead(layer, s) && !gcode::is_support(s.role);
    });
}

Frame model_frame(const LayerStack& stack, const FrameBead& is_model) {
    double x = std::numeric_limits<double>::infinity(), y = x;
    for (const Layer& layer : stack.layers)
        for (const Segment& s : layer.segments) {
            if (!is_model(layer, s)) continue;
            x = std::min({x, static_cast<double>(s.x0), static_cast<double>(s.x1)});
            y = std::min({y, static_cast<double>(s.y0), static_cast<double>(s.y1)});
        }
    if (!std::isfinite(x)) return {};
    return frame_at(x, y);
}

Bounds move_bounds(const Bounds& b, const Frame& frame, bool into) {
    const double fx = into ? -frame.dx() : frame.dx(), fy = into ? -frame.dy() : frame.dy();
    return {b.min_x + fx, b.min_y + fy, b.max_x + fx, b.max_y + fy};
}

void move_stack(LayerStack& stack, const Frame& frame, bool into) {
    if (frame.identity()) return;
    const long long sx = into ? -frame.dx_um : frame.dx_um, sy = into ? -frame.dy_um : frame.dy_um;
    // Through whole microns: a float holds 123.456 to about 4e-6 mm, far
    // inside the half micron that rounding forgives.
    auto mx = [sx](float v) { return static_cast<float>(static_cast<double>(microns(v) + sx) / 1000.0); };
    auto my = [sy](float v) { return static_cast<float>(static_cast<double>(microns(v) + sy) / 1000.0); };
    for (Layer& layer : stack.layers)
        for (Segment& s : layer.segments) {
            s.x0 = mx(s.x0);
            s.x1 = mx(s.x1);
            s.y0 = my(s.y0);
            s.y1 = my(s.y1);
        }
    if (!stack.bounds.empty()) stack.bounds = move_bounds(stack.bounds, frame, into);
}

}  // namespace scaffold::layers
