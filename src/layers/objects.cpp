#include "layers/objects.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <thread>
#include <vector>

#include "gcode/role.hpp"
#include "layers/regions.hpp"

namespace scaffold::layers {

bool model_bead(const Layer& layer, const Segment& s) {
    return !layer.purge && s.role != gcode::Role::Skirt && s.role != gcode::Role::WipeTower;
}

namespace {

// The model's box, beads' widths and the join included (a 1-cell grid far
// away when there is no model).
BitGrid footprint_grid(const LayerStack& stack, const ObjectMap::BeadTest& is_model) {
    const double inf = std::numeric_limits<double>::infinity();
    double x0 = inf, y0 = inf, x1 = -inf, y1 = -inf;
    for (const Layer& layer : stack.layers)
        for (const Segment& s : layer.segments)
            if (is_model(layer, s)) {
                x0 = std::min({x0, static_cast<double>(s.x0), static_cast<double>(s.x1)});
                y0 = std::min({y0, static_cast<double>(s.y0), static_cast<double>(s.y1)});
                x1 = std::max({x1, static_cast<double>(s.x0), static_cast<double>(s.x1)});
                y1 = std::max({y1, static_cast<double>(s.y0), static_cast<double>(s.y1)});
            }
    if (!(x1 >= x0)) return BitGrid(0, 0, kObjectJoin / 2, kObjectJoin / 2, kObjectJoin / 2);
    const double m = 2 * kObjectJoin;  // beads are at most a few mm wide: drawn within the box grown by this
    return BitGrid(x0 - m, y0 - m, x1 + m, y1 + m, kObjectJoin / 2);
}

}  // namespace

ObjectMap::ObjectMap(const LayerStack& stack, const BeadTest& is_model, int threads)
    : grid_(footprint_grid(stack, is_model)) {
    // Every model bead of every layer drawn into one footprint: each thread
    // every `threads`-th layer into a grid of its own, ORed after.
    const int n = std::max(1, std::min(threads, static_cast<int>(stack.layers.size())));
    std::vector<BitGrid> part(static_cast<std::size_t>(n - 1), grid_.empty_like());
    auto draw = [&](int t) {
        BitGrid& g = t == 0 ? grid_ : part[static_cast<std::size_t>(t - 1)];
        for (std::size_t l = static_cast<std::size_t>(t); l < stack.layers.size(); l += static_cast<std::size_t>(n))
            for (const Segment& s : stack.layers[l].segments)
                if (is_model(stack.layers[l], s)) g.draw_segment(s.x0, s.y0, s.x1, s.y1, std::max<double>(s.width, kObjectJoin));
    };
    {
        std::vector<std::jthread> helpers;
        for (int t = 1; t < n; ++t) helpers.emplace_back(draw, t);
        draw(0);
    }
    for (const BitGrid& g : part) grid_ |= g;
    label_.assign(static_cast<std::size_t>(grid_.width()) * static_cast<std::size_t>(grid_.height()), -1);
    const std::vector<std::vector<Cell>> pieces = components(grid_);
    count_ = static_cast<int>(pieces.size());
    for (std::size_t p = 0; p < pieces.size(); ++p)
        for (const Cell& c : pieces[p])
            label_[static_cast<std::size_t>(c.j) * static_cast<std::size_t>(grid_.width()) + static_cast<std::size_t>(c.i)] =
                static_cast<int>(p);
}

int ObjectMap::at(double x, double y, double reach) const {
    const int ci = grid_.col(x), cj = grid_.row(y);
    const int rings = static_cast<int>(std::ceil(reach / grid_.cell()));
    for (int d = 0; d <= rings; ++d)
        for (int j = cj - d; j <= cj + d; ++j)
            for (int i = ci - d; i <= ci + d; ++i) {
                if (std::max(std::abs(i - ci), std::abs(j - cj)) != d) continue;  // the ring's own cells
                if (i < 0 || j < 0 || i >= grid_.width() || j >= grid_.height()) continue;
                const int p = label_[static_cast<std::size_t>(j) * static_cast<std::size_t>(grid_.width()) + static_cast<std::size_t>(i)];
                if (p >= 0) return p;
            }
    return -1;
}

}  // namespace scaffold::layers
