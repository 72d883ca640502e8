#include "plan/obstacles.hpp"

#include <algorithm>
#include <cmath>

namespace scaffold::plan {

Obstacles::Obstacles(const layers::LayerStack& stack, const Settings& settings)
    : inflate(settings.support_width + settings.xy_gap) {
    // The grid reaches past the print so pillars beside it can be tested too.
    layers::BitGrid proto = layers::make_grid(stack, settings.resolution, 10.0);
    z_.reserve(stack.layers.size());
    for (const layers::Layer& layer : stack.layers) {
        z_.push_back(layer.z);
        h_.push_back(layer.height);
        below_.push_back(layer.below);
        // The model's filled footprint: a hole between sparse infill lines is
        // inside the part, no room for a pillar. A skirt or brim loop encloses
        // nothing (filled, it would wall off the whole bed around the part).
        layers::BitGrid g = proto, skirt = proto;
        bool has_skirt = false;
        for (const layers::Segment& sg : layer.segments) {
            bool is_skirt = sg.role == gcode::Role::Skirt;
            has_skirt = has_skirt || is_skirt;
            (is_skirt ? skirt : g).draw_segment(sg.x0, sg.y0, sg.x1, sg.y1, sg.width);
        }
        g = g.filled();
        if (has_skirt) g |= skirt;
        model_.push_back(std::move(g));
    }
    grown_.resize(model_.size());
}

bool Obstacles::line_clear(int layer, double x0, double y0, double x1, double y1) const {
    if (layer < 0 || layer >= layer_count()) return true;
    layers::BitGrid& g = grown_[layer];
    if (g.width() == 0) g = model_[layer].dilated(inflate);
    double len = std::hypot(x1 - x0, y1 - y0);
    int steps = std::max(1, static_cast<int>(std::ceil(len / (g.cell() * 0.7))));
    for (int k = 0; k <= steps; ++k) {
        double t = static_cast<double>(k) / steps;
        double x = x0 + (x1 - x0) * t, y = y0 + (y1 - y0) * t;
        if (g.get(g.col(x), g.row(y))) return false;
    }
    return true;
}

namespace {

// Calls f(j, i0, i1) for every row j of cells whose centres lie within r of
// (x, y), i0..i1 being that row's cells in the disc; stops early when f
// returns true. Returns whether it stopped.
template <class F>
bool any_row_in_disc(const layers::BitGrid& g, double x, double y, double r, F&& f) {
    int j0 = g.row(y - r), j1 = g.row(y + r);
    for (int j = j0; j <= j1; ++j) {
        double dy = g.cy(j) - y;
        if (std::abs(dy) > r) continue;
        double hw = std::sqrt(r * r - dy * dy);
        int i0 = static_cast<int>(std::ceil((x - hw - g.origin_x()) / g.cell() - 0.5));
        int i1 = static_cast<int>(std::floor((x + hw - g.origin_x()) / g.cell() - 0.5));
        if (f(j, i0, i1)) return true;
    }
    return false;
}

// Whether any of cells i0..i1 of row j is set, a word at a time.
bool any_in_row(const layers::BitGrid& g, int j, int i0, int i1) {
    if (j < 0 || j >= g.height()) return false;
    i0 = std::max(i0, 0);
    i1 = std::min(i1, g.width() - 1);
    if (i0 > i1) return false;
    const std::uint64_t* row = g.row_words(j);
    for (int w = i0 >> 6; w <= (i1 >> 6); ++w) {
        std::uint64_t m = ~std::uint64_t{0};
        if (w == (i0 >> 6)) m &= ~std::uint64_t{0} << (i0 & 63);
        if (w == (i1 >> 6) && (i1 & 63) != 63) m &= (std::uint64_t{1} << ((i1 & 63) + 1)) - 1;
        if (row[w] & m) return true;
    }
    return false;
}

}  // namespace

int Obstacles::fast_disc(int layer, double x, double y, double r) const {
    const std::int64_t key = std::llround(r * 1e6);
    // The same radius comes many times in a row (one column, layer by layer).
    if (!last_fast_ || last_key_ != key) {
        last_fast_ = &fast_[key];
        last_key_ = key;
    }
    Grown& g = *last_fast_;
    if (++g.asked < kFastAfter) return -1;
    const layers::BitGrid& m = model_[layer];
    if (g.surely_blocked.empty()) {
        g.surely_blocked.resize(model_.size());
        g.maybe_blocked.resize(model_.size());
    }
    const double half_diag = m.cell() * 0.7072;
    if (g.maybe_blocked[layer].width() == 0) {
        // Two rasters the size of the layer's: within a fixed budget, so
        // the memory bound stays the one of the obstacles themselves.
        const std::size_t bytes = 2 * m.words().size() * sizeof(std::uint64_t);
        if (fast_bytes_ + bytes > kFastBudget) return -1;
        fast_bytes_ += bytes;
        g.maybe_blocked[layer] = m.dilated(r + half_diag);
        g.surely_blocked[layer] = r > half_diag ? m.dilated(r - half_diag) : m;
    }
    // The query lies within half a diagonal of its cell's centre.
    int i = m.col(x), j = m.row(y);
    if (i < 0 || j < 0 || i >= m.width() || j >= m.height()) return -1;
    if (r > half_diag && g.surely_blocked[layer].get(i, j)) return 0;
    if (!g.maybe_blocked[layer].get(i, j)) return 1;
    return -1;
}

bool Obstacles::disc_clear(int layer, double x, double y, double r) const {
    if (layer < 0 || layer >= layer_count()) return true;
    if (int f = fast_disc(layer, x, y, r); f >= 0) return f == 1;
    // The planner asks this millions of times: whole rows of the disc a
    // word at a time.
    const layers::BitGrid& g = model_[layer];
    return !any_row_in_disc(g, x, y, r, [&](int j, int i0, int i1) { return any_in_row(g, j, i0, i1); });
}

bool Obstacles::column_clear(double x, double y, double r, double z_lo, double z_hi) const {
    for (int l = 0; l < layer_count(); ++l)
        if (z_[l] > z_lo + 1e-6 && z_[l] <= z_hi + 1e-6 && !disc_clear(l, x, y, r)) return false;
    return true;
}

int Obstacles::model_below(int layer, double x, double y, double r) const {
    for (int l = layer >= 0 && layer < layer_count() ? below_[layer] : -1; l >= 0; l = below_[l])
        if (!disc_clear(l, x, y, r)) return l;
    return -1;
}

bool Obstacles::segment_clear(int layer, double x0, double y0, double x1, double y1, double r) const {
    if (layer < 0 || layer >= layer_count()) return true;
    double len = std::hypot(x1 - x0, y1 - y0);
    const layers::BitGrid& g = model_[layer];
    int steps = std::max(1, static_cast<int>(std::ceil(len / (g.cell() * 2))));
    for (int k = 0; k <= steps; ++k) {
        double t = static_cast<double>(k) / steps;
        if (!disc_clear(layer, x0 + (x1 - x0) * t, y0 + (y1 - y0) * t, r)) return false;
    }
    return true;
}

}  // namespace scaffold::plan
