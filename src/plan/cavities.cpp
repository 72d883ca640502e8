#include "plan/cavities.hpp"

#include <algorithm>
#include <bit>
#include <cmath>

#include "layers/raster.hpp"

namespace scaffold::plan {

namespace {

int band_of(double z) { return std::clamp(static_cast<int>(std::floor(z / Cavities::kBand)), 0, 63); }

// How many of cells a..b (inclusive) of a row are set.
int count_in(const std::uint64_t* row, int a, int b) {
    int n = 0;
    for (int w = a >> 6; w <= b >> 6; ++w) {
        std::uint64_t mask = ~std::uint64_t{0};
        if (w == a >> 6) mask &= ~std::uint64_t{0} << (a & 63);
        if (w == b >> 6) mask &= ~std::uint64_t{0} >> (63 - (b & 63));
        n += std::popcount(row[w] & mask);
    }
    return n;
}

}  // namespace

Cavities::Cavities(const layers::LayerStack& stack, const Settings& settings) {
    const layers::BitGrid proto = layers::make_grid(stack, settings.resolution, 2.0);
    x0_ = proto.origin_x();
    y0_ = proto.origin_y();
    // Whole fine cells a coarse one, so a coarse cell is a run of each row.
    const int per = std::max(1, static_cast<int>(std::lround(kCell / proto.cell())));
    cell_ = per * proto.cell();
    nx_ = (proto.width() + per - 1) / per;
    ny_ = (proto.height() + per - 1) / per;
    enclosed_.assign(static_cast<std::size_t>(nx_) * ny_, 0);
    top_.assign(static_cast<std::size_t>(nx_) * ny_, 0.0f);
    layers::BitGrid material = proto;
    std::vector<int> hole_count;  // per coarse cell of the layer's box
    for (const layers::Layer& layer : stack.layers) {
        if (layer.purge) continue;
        material.clear();
        bool any = false;
        // The model's own beads: a skirt encloses nothing, the slicer's own
        // support is no wall.
        for (const layers::Segment& sg : layer.segments)
            if (sg.role != gcode::Role::Skirt && !gcode::is_support(sg.role)) {
                material.draw_segment(sg.x0, sg.y0, sg.x1, sg.y1, sg.width);
                any = true;
            }
        if (!any) continue;
        layers::BitGrid holes = material.filled();
        holes.subtract(material);
        const std::uint64_t bit = std::uint64_t{1} << band_of(layer.z);
        const float z = static_cast<float>(layer.z);
        // Per coarse cell: any material, and whether every fine cell of it
        // lies in a hole (a cell a wall runs through is no hollow).
        const layers::CellBox box = layers::layer_box(material, layer);
        const int I0 = box.i0 / per, I1 = std::min(nx_ - 1, box.i1 / per);
        const int J0 = box.j0 / per, J1 = std::min(ny_ - 1, box.j1 / per);
        if (I1 < I0 || J1 < J0) continue;
        hole_count.assign(static_cast<std::size_t>(I1 - I0 + 1) * (J1 - J0 + 1), 0);
        for (int j = J0 * per; j <= std::min(proto.height() - 1, J1 * per + per - 1); ++j) {
            const std::uint64_t* m = material.row_words(j);
            const std::uint64_t* h = holes.row_words(j);
            const int J = j / per;
            for (int I = I0; I <= I1; ++I) {
                const int a = I * per, b = std::min(a + per, proto.width()) - 1;
                const std::size_t k = static_cast<std::size_t>(J) * nx_ + I;
                hole_count[static_cast<std::size_t>(J - J0) * (I1 - I0 + 1) + (I - I0)] += count_in(h, a, b);
                if (top_[k] < z && count_in(m, a, b)) top_[k] = z;
            }
        }
        for (int J = J0; J <= J1; ++J)
            for (int I = I0; I <= I1; ++I)
                if (hole_count[static_cast<std::size_t>(J - J0) * (I1 - I0 + 1) + (I - I0)] == per * per)
                    enclosed_[static_cast<std::size_t>(J) * nx_ + I] |= bit;
    }
}

int Cavities::index(double x, double y) const {
    const int i = static_cast<int>(std::floor((x - x0_) / cell_)), j = static_cast<int>(std::floor((y - y0_) / cell_));
    if (i < 0 || j < 0 || i >= nx_ || j >= ny_) return -1;
    return j * nx_ + i;
}

bool Cavities::trapped(double x, double y, double z, double reach) const {
    const int k = index(x, y);
    if (k < 0 || top_[k] <= z) return false;
    const int b0 = band_of(z - reach), b1 = band_of(z + reach);
    const std::uint64_t bands = (b1 == 63 ? ~std::uint64_t{0} : (std::uint64_t{1} << (b1 + 1)) - 1) & ~((std::uint64_t{1} << b0) - 1);
    return (enclosed_[k] & bands) != 0;
}

bool Cavities::bar_trapped(double x0, double y0, double x1, double y1, double z) const {
    const double len = std::hypot(x1 - x0, y1 - y0);
    if (len <= 2 * kEndClear) return false;
    const int steps = static_cast<int>(std::ceil((len - 2 * kEndClear) / (cell_ / 2)));
    for (int s = 0; s <= steps; ++s) {
        const double t = (kEndClear + (len - 2 * kEndClear) * s / steps) / len;
        if (trapped(x0 + (x1 - x0) * t, y0 + (y1 - y0) * t, z, kReach)) return true;
    }
    return false;
}

}  // namespace scaffold::plan
