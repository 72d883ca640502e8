#include "plan/cavities.hpp"

#include <algorithm>
#include <cmath>

#include "layers/raster.hpp"
#include "plan/workers.hpp"

namespace scaffold::plan {

namespace {

// The bits of cells a..b (inclusive) of a row in word w.
std::uint64_t span_mask(int w, int a, int b) {
    std::uint64_t mask = ~std::uint64_t{0};
    if (w == a >> 6) mask &= ~std::uint64_t{0} << (a & 63);
    if (w == b >> 6) mask &= ~std::uint64_t{0} >> (63 - (b & 63));
    return mask;
}

bool any_in(const std::uint64_t* row, int a, int b) {
    for (int w = a >> 6; w <= b >> 6; ++w)
        if (row[w] & span_mask(w, a, b)) return true;
    return false;
}

bool all_in(const std::uint64_t* row, int a, int b) {
    for (int w = a >> 6; w <= b >> 6; ++w) {
        const std::uint64_t m = span_mask(w, a, b);
        if ((row[w] & m) != m) return false;
    }
    return true;
}

}  // namespace

Cavities::Cavities(const layers::LayerStack& stack, const layers::BitGrid& grid, int threads,
                   const std::atomic<bool>* cancel) {
    if (stack.layers.empty()) return;
    const layers::BitGrid proto = grid.empty_like();
    x0_ = proto.origin_x();
    y0_ = proto.origin_y();
    // Whole fine cells a coarse one, so a coarse cell is a run of each row.
    const int per = std::max(1, static_cast<int>(std::lround(kCell / proto.cell())));
    cell_ = per * proto.cell();
    nx_ = static_cast<std::size_t>((proto.width() + per - 1) / per);
    ny_ = static_cast<std::size_t>((proto.height() + per - 1) / per);
    std::vector<int> order;  // the layers by rising z, without purge lines
    for (int i = 0; i < static_cast<int>(stack.layers.size()); ++i)
        if (!stack.layers[i].purge) order.push_back(i);
    std::stable_sort(order.begin(), order.end(), [&](int a, int b) { return stack.layers[a].z < stack.layers[b].z; });
    for (int i : order) z_.push_back(stack.layers[i].z);
    const std::size_t words = (order.size() * nx_ * ny_ * 2 + 63) / 64;
    // Each layer is mapped on its own: every thread maps every threads-th
    // layer into maps of its own (layers share words at their ends), ORed
    // and maxed together after: the same maps on any number of threads.
    const int workers = std::clamp(threads, 1, static_cast<int>(std::max<std::size_t>(1, order.size())));
    std::vector<std::vector<std::uint64_t>> states(static_cast<std::size_t>(workers));
    std::vector<std::vector<float>> tops(static_cast<std::size_t>(workers));
    run_workers(workers, [&](int t) {
        std::vector<std::uint64_t>& st_out = states[static_cast<std::size_t>(t)];
        std::vector<float>& top_out = tops[static_cast<std::size_t>(t)];
        st_out.assign(words, 0);
        top_out.assign(nx_ * ny_, 0.0f);
        layers::BitGrid material = proto;
        // A coarse row's fine rows: ORed material, ANDed holes.
        std::vector<std::uint64_t> any_material(static_cast<std::size_t>(proto.words_per_row()), 0),
            all_holes(static_cast<std::size_t>(proto.words_per_row()), 0);
        layers::CellBox drawn;  // what material holds
        std::vector<std::uint64_t> hole_row(static_cast<std::size_t>(proto.words_per_row()), 0);
        for (std::size_t n = static_cast<std::size_t>(t); n < order.size(); n += static_cast<std::size_t>(workers)) {
            if (cancel && cancel->load(std::memory_order_relaxed)) return;
            const layers::Layer& layer = stack.layers[order[n]];
            material.clear(drawn);
            drawn = {};
            bool any = false;
            // The model's own beads: a skirt encloses nothing, the slicer's own
            // support is no wall.
            for (const layers::Segment& sg : layer.segments)
                if (sg.role != gcode::Role::Skirt && !gcode::is_support(sg.role)) {
                    material.draw_segment(sg.x0, sg.y0, sg.x1, sg.y1, sg.width);
                    any = true;
                }
            if (!any) continue;
            const layers::CellBox box = layers::layer_box(material, layer);
            drawn = material.clipped(box);
            // Every hole the material encloses, cavities of the model included
            // (the obstacles' footprint fills only the part's infill holes):
            // flooded in the box and a free cell around it, which the outside
            // reaches (the same holes as over the whole grid, for the part of
            // a plate's grid a layer covers).
            int i_off = 0, j_off = 0;
            const layers::BitGrid near = material.crop(box.grown(1), i_off, j_off);
            layers::BitGrid holes = near.filled();
            holes.subtract(near);
            const float z = static_cast<float>(layer.z);
            // Per coarse cell: any material, else whether every fine cell of it
            // lies in a hole (a cell a wall runs through is no hollow): the rows
            // of a coarse row ORed (material) and ANDed (holes), then the spans.
            const int I0 = box.i0 / per, I1 = std::min(static_cast<int>(nx_) - 1, box.i1 / per);
            const int J0 = box.j0 / per, J1 = std::min(static_cast<int>(ny_) - 1, box.j1 / per);
            if (I1 < I0 || J1 < J0) continue;
            const int w0 = (I0 * per) >> 6, w1 = std::min(proto.words_per_row() - 1, (I1 * per + per - 1) >> 6);
            for (int J = J0; J <= J1; ++J) {
                std::fill(any_material.begin() + w0, any_material.begin() + w1 + 1, 0);
                std::fill(all_holes.begin() + w0, all_holes.begin() + w1 + 1, ~std::uint64_t{0});
                for (int j = J * per; j < J * per + per; ++j) {
                    if (j >= proto.height()) {  // past the grid's last row: no hole
                        std::fill(all_holes.begin() + w0, all_holes.begin() + w1 + 1, 0);
                        break;
                    }
                    const std::uint64_t* m = material.row_words(j);
                    // The row's holes on the whole grid's words (none outside the crop).
                    std::fill(hole_row.begin() + w0, hole_row.begin() + w1 + 1, 0);
                    if (j >= j_off && j < j_off + holes.height()) {
                        const std::uint64_t* src = holes.row_words(j - j_off);
                        const int first = i_off >> 6, last = first + holes.words_per_row() - 1;
                        for (int w = std::max(w0, first); w <= std::min(w1, last); ++w) hole_row[w] = src[w - first];
                    }
                    const std::uint64_t* h = hole_row.data();
                    for (int w = w0; w <= w1; ++w) {
                        any_material[w] |= m[w];
                        all_holes[w] &= h[w];
                    }
                }
                for (int I = I0; I <= I1; ++I) {
                    const int a = I * per, b = std::min(a + per, proto.width()) - 1;
                    const bool solid = any_in(any_material.data(), a, b);
                    if (!solid && !all_in(all_holes.data(), a, b)) continue;
                    const std::size_t cell = static_cast<std::size_t>(J) * nx_ + static_cast<std::size_t>(I);
                    const std::uint64_t st = solid ? Material : Hole;
                    const std::size_t bit = (n * nx_ * ny_ + cell) * 2;
                    st_out[bit >> 6] |= st << (bit & 63);
                    if (solid && top_out[cell] < z) top_out[cell] = z;
                }
            }
        }
    });
    states_ = std::move(states.front());
    top_ = std::move(tops.front());
    for (std::size_t t = 1; t < states.size(); ++t) {
        for (std::size_t k = 0; k < words; ++k) states_[k] |= states[t][k];
        for (std::size_t k = 0; k < top_.size(); ++k) top_[k] = std::max(top_[k], tops[t][k]);
    }
}

int Cavities::index(double x, double y) const {
    const double fi = std::floor((x - x0_) / cell_), fj = std::floor((y - y0_) / cell_);
    if (!(fi >= 0 && fj >= 0 && fi < static_cast<double>(nx_) && fj < static_cast<double>(ny_))) return -1;
    return static_cast<int>(fj) * static_cast<int>(nx_) + static_cast<int>(fi);
}

bool Cavities::trapped(double x, double y, double z, double reach) const {
    const int k = index(x, y);
    if (k < 0 || top_[k] <= z) return false;
    // Up from z through air: the first layer that is not air at the cell,
    // within reach. Walls that close around it under the roof make a box;
    // a roof or a lip met first leaves the way out sideways open, and what
    // walls in the cell lower down (a hull around a cabin's deck, the
    // infill of a part under the bar) is below, not around, the bar.
    const std::size_t from = static_cast<std::size_t>(std::upper_bound(z_.begin(), z_.end(), z + 1e-6) - z_.begin());
    for (std::size_t n = from; n < z_.size() && z_[n] <= z + reach; ++n) {
        const State s = state(n, k);
        if (s == Hole) return true;
        if (s == Material) break;
    }
    return false;
}

bool Cavities::bar_trapped(double x0, double y0, double x1, double y1, double z) const {
    // End to end: an end's pillar inside the hollow is as trapped as the bar.
    const double len = std::hypot(x1 - x0, y1 - y0);
    const int steps = std::max(1, static_cast<int>(std::ceil(len / (cell_ / 2))));
    for (int s = 0; s <= steps; ++s) {
        const double t = static_cast<double>(s) / steps;
        if (trapped(x0 + (x1 - x0) * t, y0 + (y1 - y0) * t, z, kReach)) return true;
    }
    return false;
}

}  // namespace scaffold::plan
