#include "plan/obstacles.hpp"

#include <algorithm>
#include <atomic>
#include <bit>
#include <cmath>

#include "plan/workers.hpp"

namespace scaffold::plan {

layers::BitGrid obstacle_grid(const layers::LayerStack& stack, const Settings& settings) {
    return layers::make_grid(stack, settings.resolution, 10.0);
}

// The model's footprint per layer, as Obstacles keeps it (shared by the
// Obstacles of every thread, another()); for the layers with a skirt or
// brim line, also the footprint without it and the line.
std::shared_ptr<const std::vector<layers::BitGrid>> Obstacles::model_rasters(
    const layers::LayerStack& stack, const Settings& settings, std::shared_ptr<const std::vector<SkirtLayer>>& skirts,
    std::vector<int>& skirt_at, int threads, double solid_above) {
    const layers::BitGrid proto = obstacle_grid(stack, settings);
    const std::size_t n = stack.layers.size();
    std::vector<layers::BitGrid> out(n), skirt_of(n);
    std::vector<char> has_skirt(n, 0);
    // Each layer on its own (a plate's are the most of building the
    // obstacles), on `threads` threads, a layer at a time in turn.
    std::atomic<std::size_t> next{0};
    run_workers(std::max(1, std::min<int>(threads, static_cast<int>(n))), [&](int) {
        layers::BitGrid skirt = proto, seeds = proto;  // scratch, cleared where drawn
        for (std::size_t l; (l = next.fetch_add(1)) < n;) {
            const layers::Layer& layer = stack.layers[l];
            // The part's footprint: a hole between sparse infill lines is
            // inside the part, no room for a pillar; a cavity of the model is
            // open to support (layers::draw_hole_seed). A skirt or brim loop
            // encloses nothing (filled, it would wall off the whole bed
            // around the part).
            layers::BitGrid g = proto;
            if (layer.z > solid_above) {
                for (int j = 0; j < g.height(); ++j) g.set_row_span(j, 0, g.width() - 1);
                out[l] = std::move(g);
                continue;
            }
            const layers::CellBox box = layers::layer_box(proto, layer);
            for (const layers::Segment& sg : layer.segments) {
                const bool is_skirt = sg.role == gcode::Role::Skirt;
                has_skirt[l] = has_skirt[l] || is_skirt;
                (is_skirt ? skirt : g).draw_segment(sg.x0, sg.y0, sg.x1, sg.y1, sg.width);
                if (!is_skirt) layers::draw_hole_seed(seeds, sg);
            }
            // The holes, flooded in the layer's box and a free cell around
            // it, which the outside reaches (a seed outside every hole
            // floods that much, not the whole plate's grid).
            int i_off = 0, j_off = 0;
            const layers::BitGrid near = g.crop(box.grown(1), i_off, j_off);
            g.or_crop(near.holes_with(seeds.crop(box.grown(1), i_off, j_off)), i_off, j_off);
            seeds.clear(box);
            if (has_skirt[l]) {
                skirt_of[l] = skirt;
                skirt.clear(box);
            }
            out[l] = std::move(g);
        }
    });
    std::vector<SkirtLayer> with_skirt;
    for (std::size_t l = 0; l < n; ++l) {
        skirt_at.push_back(has_skirt[l] ? static_cast<int>(with_skirt.size()) : -1);
        if (has_skirt[l]) {
            with_skirt.push_back({out[l], skirt_of[l]});
            out[l] |= skirt_of[l];
        }
    }
    skirts = std::make_shared<const std::vector<SkirtLayer>>(std::move(with_skirt));
    return std::make_shared<const std::vector<layers::BitGrid>>(std::move(out));
}

Obstacles::Obstacles(const layers::LayerStack& stack, const Settings& settings, int threads, double solid_above)
    : inflate(settings.support_width + settings.xy_gap),
      shared_model_(model_rasters(stack, settings, shared_skirts_, skirt_at_, threads, solid_above)),
      model_(*shared_model_) {
    skirt_relief_ = std::max(0.0, settings.xy_gap - kSkirtGap);
    z_.reserve(stack.layers.size());
    for (const layers::Layer& layer : stack.layers) {
        z_.push_back(layer.z);
        h_.push_back(layer.height);
        below_.push_back(layer.below);
    }
    grown_.resize(model_.size());
    coarse_.resize(model_.size());
    if (!model_.empty()) {
        coarse_h_ = (model_.front().height() + 7) / 8;
        coarse_wpr_ = (model_.front().words_per_row() * 8 + 63) / 64;  // a bit for every byte of a row's words
    }
}

Obstacles::Obstacles(const Obstacles& other, Shared)
    : inflate(other.inflate), shared_skirts_(other.shared_skirts_), skirt_at_(other.skirt_at_),
      skirt_relief_(other.skirt_relief_), z_(other.z_), h_(other.h_), below_(other.below_),
      shared_model_(other.shared_model_), model_(*shared_model_) {
    coarse_h_ = other.coarse_h_;
    coarse_wpr_ = other.coarse_wpr_;
    grown_.resize(model_.size());
    coarse_.resize(model_.size());
}

std::unique_ptr<const Obstacles> Obstacles::another() const {
    return std::unique_ptr<const Obstacles>(new Obstacles(*this, Shared{}));
}

namespace {

// Whether any of bits i0..i1 (0 <= i0 <= i1) of a row of 64-bit words is
// set, a word at a time.
bool any_bit(const std::uint64_t* row, int i0, int i1) {
    for (int w = i0 >> 6; w <= (i1 >> 6); ++w) {
        std::uint64_t m = ~std::uint64_t{0};
        if (w == (i0 >> 6)) m &= ~std::uint64_t{0} << (i0 & 63);
        if (w == (i1 >> 6) && (i1 & 63) != 63) m &= (std::uint64_t{1} << ((i1 & 63) + 1)) - 1;
        if (row[w] & m) return true;
    }
    return false;
}

}  // namespace

bool Obstacles::surely_clear(int layer, double x, double y, double r) const {
    const layers::BitGrid& g = model_[layer];
    std::vector<std::uint64_t>& c = coarse_[layer];
    if (c.empty()) {
        c.assign(static_cast<std::size_t>(coarse_h_) * coarse_wpr_ + 1, 0);  // never empty once built
        for (int j = 0; j < g.height(); ++j) {
            const std::uint64_t* row = g.row_words(j);
            std::uint64_t* out = &c[static_cast<std::size_t>(j / 8) * coarse_wpr_];
            for (int w = 0; w < g.words_per_row(); ++w)
                for (int k = 0; k < 8 && (row[w] >> (8 * k)); ++k)
                    if ((row[w] >> (8 * k)) & 0xFF) {
                        const int b = w * 8 + k;
                        out[b >> 6] |= std::uint64_t{1} << (b & 63);
                    }
        }
    }
    // The cells disc_meets may look at, with a cell to spare each way.
    const int j0 = std::max(0, g.row(y - r) - 1), j1 = std::min(g.height() - 1, g.row(y + r) + 1);
    const int i0 = std::max(0, g.col(x - r) - 1), i1 = std::min(g.width() - 1, g.col(x + r) + 1);
    if (j0 > j1 || i0 > i1) return true;
    for (int cj = j0 / 8; cj <= j1 / 8; ++cj)
        if (any_bit(&c[static_cast<std::size_t>(cj) * coarse_wpr_], i0 / 8, i1 / 8)) return false;
    return true;
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
        // The cell by multiplying, the exact division only near a border.
        int i, j;
        if (!g.sure_cell(x, y, i, j)) i = g.col(x), j = g.row(y);
        if (g.get(i, j)) return false;
    }
    return true;
}

namespace {

// Calls f(j, i0, i1) for every row j of cells whose centres lie within r of
// (x, y), i0..i1 being that row's cells in the disc; stops early when f
// returns true. Returns whether it stopped.
// Rows for which skip(j) is true are passed over.
template <class F, class Skip>
bool any_row_in_disc(const layers::BitGrid& g, double x, double y, double r, F&& f, Skip&& skip) {
    int j0 = g.row(y - r), j1 = g.row(y + r);
    for (int j = j0; j <= j1; ++j) {
        if (skip(j)) continue;
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
    return any_bit(g.row_words(j), i0, i1);
}

// Rounding in disc_meets moves a cell's distance by some 1e-11 cells (the
// coordinates are at most ~1e5 cells); the lookup keeps this much off the
// edge, in cells and, for squared distances, relative to r squared.
constexpr double kEdgeCells = 1e-6;

}  // namespace

bool disc_meets(const layers::BitGrid& g, double x, double y, double r) {
    // The planner asks this millions of times: whole rows of the disc a
    // word at a time. A row with no set cell in the disc's bounding box
    // (a cell wider each way than rounding could move the disc's span) has
    // none in the span either: its square root and divisions are skipped.
    const int b0 = g.col(x - r) - 1, b1 = g.col(x + r) + 1;
    return any_row_in_disc(g, x, y, r, [&](int j, int i0, int i1) { return any_in_row(g, j, i0, i1); },
                           [&](int j) { return !any_in_row(g, j, b0, b1); });
}

DiscLookup::DiscLookup(const std::vector<layers::BitGrid>& model, double r, Layout layout)
    : model_(model.data()), layers_(static_cast<int>(model.size())), r_(r), layout_(layout) {
    if (model.empty() || model[0].width() == 0 || model[0].height() == 0) return;
    const layers::BitGrid& g = model[0];
    for (const layers::BitGrid& m : model)
        if (!m.same_shape(g)) return;
    const double rc = r / g.cell();
    if (!(rc >= 0 && rc <= 512)) return;  // the offset tables grow with rc squared
    nx_ = g.width();
    ny_ = g.height();
    wpr_ = g.words_per_row();
    bands_ = (ny_ + kBlockRows - 1) / kBlockRows;
    tiles_ = (wpr_ + kBlockWords - 1) / kBlockWords;
    // A query point lies in its cell, [0, 1] x [0, 1] from the cell's corner
    // (widened by kEdgeCells against rounding); a set cell (di, dj) cells
    // away has its centre at least lo(di), lo(dj) and at most hi(di),
    // hi(dj) away along each axis.
    const double e = kEdgeCells, r2_hi = rc * rc + e * (1 + rc * rc), r2_lo = rc * rc - e * (1 + rc * rc);
    auto lo = [e](int d) { return std::max(0.0, d - 0.5 - e); };
    auto hi = [e](int d) { return d + 0.5 + e; };
    for (int d = 0; lo(d) * lo(d) <= r2_hi; ++d) {
        int h = 0;
        while (lo(d) * lo(d) + lo(h + 1) * lo(h + 1) <= r2_hi) ++h;
        maybe_.push_back(h);
    }
    for (int d = 0; hi(d) * hi(d) + hi(0) * hi(0) <= r2_lo; ++d) {
        int h = 0;
        while (hi(d) * hi(d) + hi(h + 1) * hi(h + 1) <= r2_lo) ++h;
        sure_.push_back(h);
    }
    if (layout_ == Layout::Columns) blocks_.resize(static_cast<std::size_t>((layers_ + 63) / 64) * bands_ * tiles_);
    else rasters_.resize(layers_);
    usable_ = true;
}

void DiscLookup::grow_rows(int layer, int j0, int j1, std::size_t w0, std::size_t w1, std::uint64_t* maybe,
                           std::uint64_t* surely) const {
    const layers::BitGrid& g = model_[layer];
    const int D = static_cast<int>(maybe_.size()) - 1;
    const std::size_t W = static_cast<std::size_t>(wpr_), OW = w1 - w0;
    std::fill(maybe, maybe + (j1 - j0 + 1) * OW, 0);
    std::fill(surely, surely + (j1 - j0 + 1) * OW, 0);
    // Each source row dilated sideways, one cell at a time, as far as its
    // distance to an output row allows; then or-ed into those rows.
    std::vector<std::uint64_t> dil(static_cast<std::size_t>(maybe_[0] + 1) * W);
    for (int js = std::max(0, j0 - D); js <= std::min(ny_ - 1, j1 + D); ++js) {
        const std::uint64_t* src = g.row_words(js);
        // Only the words the row's cells can reach: those it has set, and
        // as many words each way as the reach spans.
        std::size_t wa = 0, wb = W;
        while (wa < W && !src[wa]) ++wa;
        if (wa == W) continue;
        while (!src[wb - 1]) --wb;
        const int hmax = maybe_[js < j0 ? j0 - js : (js > j1 ? js - j1 : 0)];
        const std::size_t reach = static_cast<std::size_t>(hmax + 63) / 64;
        wa = wa > reach ? wa - reach : 0;
        wb = std::min(W, wb + reach);
        // Words more than the reach away from the output's cannot reach it;
        // those cut off at the range's edge only miss cells outside it.
        wa = std::max(wa, w0 > reach ? w0 - reach : 0);
        wb = std::min(wb, w1 + reach);
        if (wa >= wb) continue;
        std::copy(src + wa, src + wb, dil.begin() + static_cast<std::ptrdiff_t>(wa));
        for (int h = 1; h <= hmax; ++h) {
            const std::uint64_t* in = &dil[(h - 1) * W];
            std::uint64_t* out = &dil[h * W];
            for (std::size_t w = wa; w < wb; ++w) {
                const std::uint64_t prev = w > wa ? in[w - 1] : 0, next = w + 1 < wb ? in[w + 1] : 0;
                out[w] = in[w] | in[w] << 1 | prev >> 63 | in[w] >> 1 | next << 63;
            }
        }
        const std::size_t oa = std::max(wa, w0), ob = std::min(wb, w1);
        for (int jo = std::max(j0, js - D); jo <= std::min(j1, js + D); ++jo) {
            const int d = std::abs(jo - js);
            const std::size_t at = static_cast<std::size_t>(jo - j0) * OW;
            const std::uint64_t* m = &dil[maybe_[d] * W];
            for (std::size_t w = oa; w < ob; ++w) maybe[at + w - w0] |= m[w];
            if (d < static_cast<int>(sure_.size())) {
                const std::uint64_t* sr = &dil[sure_[d] * W];
                for (std::size_t w = oa; w < ob; ++w) surely[at + w - w0] |= sr[w];
            }
        }
    }
}

int DiscLookup::lookup(int layer, double x, double y, std::size_t budget, std::size_t& used) {
    LayerRange unused;
    return lookup(layer, x, y, budget, used, unused);
}

int DiscLookup::lookup(int layer, double x, double y, std::size_t budget, std::size_t& used, LayerRange& clear) {
    clear = {};
    if (!usable_ || layer < 0 || layer >= layers_) return -1;
    // A column is asked layer by layer at the same point.
    if (x != last_x_ || y != last_y_) {
        last_x_ = x;
        last_y_ = y;
        last_i_ = model_[0].col(x);
        last_j_ = model_[0].row(y);
    }
    const int i = last_i_, j = last_j_;
    if (i < 0 || j < 0 || i >= nx_ || j >= ny_) return -1;
    return layout_ == Layout::Columns ? lookup_columns(layer, i, j, budget, used, &clear)
                                      : lookup_per_layer(layer, i, j, budget, used);
}

namespace {

// The 8 x 8 bit matrix in x (bit 8 r + c is row r, column c) transposed.
std::uint64_t transpose8(std::uint64_t x) {
    std::uint64_t t = (x ^ (x >> 7)) & 0x00AA00AA00AA00AAull;
    x ^= t ^ (t << 7);
    t = (x ^ (x >> 14)) & 0x0000CCCC0000CCCCull;
    x ^= t ^ (t << 14);
    t = (x ^ (x >> 28)) & 0x00000000F0F0F0F0ull;
    x ^= t ^ (t << 28);
    return x;
}

}  // namespace

void DiscLookup::build_group(Block& b, int first, int band, int tile) {
    const int j0 = band * kBlockRows, j1 = std::min(ny_ - 1, j0 + kBlockRows - 1), rows = j1 - j0 + 1;
    const int n = std::min(kGroup, layers_ - first);
    const std::size_t w0 = static_cast<std::size_t>(tile) * kBlockWords;
    const std::size_t w1 = std::min(static_cast<std::size_t>(wpr_), w0 + kBlockWords), W = w1 - w0;
    const std::size_t plane = static_cast<std::size_t>(kBlockRows) * W;
    constexpr std::size_t kCols = 64 * kBlockWords;
    // Per layer of the group: its maybe rows, then its surely rows.
    scratch_.assign(2 * kGroup * plane, 0);
    for (int g = 0; g < n; ++g)
        grow_rows(first + g, j0, j1, w0, w1, &scratch_[2 * g * plane], &scratch_[(2 * g + 1) * plane]);
    // Eight cells by the group's eight layers at a time, transposed into
    // one byte of each cell's word.
    const int lane = first & 63;
    for (int k = 0; k < 2; ++k)
        for (int jo = 0; jo < rows; ++jo) {
            std::uint64_t* cells = &b.bits[static_cast<std::size_t>(jo) * kCols * 2];
            const std::uint64_t* in[kGroup];
            for (int g = 0; g < kGroup; ++g) in[g] = &scratch_[(2 * g + k) * plane + jo * W];
            for (std::size_t w = 0; w < W; ++w) {
                std::uint64_t any = 0;
                for (int g = 0; g < kGroup; ++g) any |= in[g][w];
                if (!any) continue;
                for (int c8 = 0; c8 < 64; c8 += 8) {
                    std::uint64_t m = 0;
                    for (int g = 0; g < kGroup; ++g) m |= ((in[g][w] >> c8) & 0xFF) << (8 * g);
                    if (!m) continue;
                    m = transpose8(m);  // byte c: cell c's layers
                    for (int c = 0; c < 8; ++c) {
                        const int at = static_cast<int>(w * 64) + c8 + c;  // in the block
                        const std::uint64_t byte = (m >> (8 * c)) & 0xFF;
                        if (byte && static_cast<int>(w0 * 64) + at < nx_) cells[static_cast<std::size_t>(at) * 2 + k] |= byte << lane;
                    }
                }
            }
        }
    b.built |= ((std::uint64_t{1} << n) - 1) << lane;
}

int DiscLookup::lookup_columns(int layer, int i, int j, std::size_t budget, std::size_t& used, LayerRange* clear) {
    const int band = j / kBlockRows, tile = i / (64 * kBlockWords);
    constexpr std::size_t kCols = 64 * kBlockWords;
    Block& b = blocks_[(static_cast<std::size_t>(layer >> 6) * bands_ + band) * tiles_ + tile];
    const std::uint64_t bit = std::uint64_t{1} << (layer & 63);
    if (!(b.built & bit)) {
        const std::size_t cells = kBlockRows * kCols;
        if (b.bits.empty()) {
            if (used + cells * 2 * sizeof(std::uint64_t) > budget) return -1;
            used += cells * 2 * sizeof(std::uint64_t);
            b.bits.assign(cells * 2, 0);
        }
        build_group(b, layer & ~(kGroup - 1), band, tile);
    }
    const std::uint64_t* cell =
        &b.bits[(static_cast<std::size_t>(j - band * kBlockRows) * kCols + (i - tile * static_cast<int>(kCols))) * 2];
    if (!(cell[0] & bit)) {
        // The run of built layers without a maybe bit that holds this one.
        const std::uint64_t free = b.built & ~cell[0];
        const int k = layer & 63;
        const int up = std::min(std::countr_zero(~free >> k), 64 - k) - 1;
        const int down = std::min(std::countl_zero(~free << (63 - k)), k + 1) - 1;
        clear->lo = layer - down;
        clear->hi = layer + up;
        return 1;
    }
    if (cell[1] & bit) return 0;
    return -1;
}

int DiscLookup::lookup_per_layer(int layer, int i, int j, std::size_t budget, std::size_t& used) {
    Rasters& r = rasters_[layer];
    const std::size_t W = static_cast<std::size_t>(wpr_);
    if (r.maybe.empty()) {
        const std::size_t words = W * ny_;
        if (used + 2 * words * sizeof(std::uint64_t) > budget) return -1;
        used += 2 * words * sizeof(std::uint64_t);
        r.maybe.resize(words);
        r.surely.resize(words);
        for (int j0 = 0; j0 < ny_; j0 += kBlockRows) {
            const int j1 = std::min(ny_ - 1, j0 + kBlockRows - 1);
            grow_rows(layer, j0, j1, 0, W, &r.maybe[j0 * W], &r.surely[j0 * W]);
        }
    }
    const std::size_t w = static_cast<std::size_t>(j) * W + (i >> 6);
    if (!((r.maybe[w] >> (i & 63)) & 1)) return 1;
    if ((r.surely[w] >> (i & 63)) & 1) return 0;
    return -1;
}

int Obstacles::fast_disc(int layer, double x, double y, double r) const {
    if (!(r >= 0)) return -1;  // and not NaN: a map key
    // A disc inside one that misses the model misses it too, and one around
    // a disc that meets it meets it (disc_meets' rows and spans grow with r;
    // the lookups' maybe and surely bits grow with it too, so the nearest
    // radius each way is the one to ask): a column's lookup, whose words
    // the column has at hand, answers for the other radii asked along it
    // (a tip's taper, the steps aside).
    auto up = std::lower_bound(columns_.begin(), columns_.end(), r,
                               [](const DiscLookup* c, double v) { return c->radius() < v; });
    if (up != columns_.end()) {
        DiscLookup::LayerRange clear;
        const int a = (*up)->lookup(layer, x, y, kFastBudget, fast_bytes_, clear);
        if (a == 1) run_ = {x, y, (*up)->radius(), clear};
        if (a == 1 || (a == 0 && (*up)->radius() == r)) return a;
    }
    if (up != columns_.begin() && (*std::prev(up))->lookup(layer, x, y, kFastBudget, fast_bytes_) == 0) return 0;
    // The same radius comes many times in a row (one column, layer by layer).
    // A taper asks a new radius every layer, from a set that recurs: the
    // radii seen lately are kept by their bits before the map is asked.
    if (!last_fast_ || last_r_ != r) {
        const std::uint64_t h = std::bit_cast<std::uint64_t>(r) * 0x9E3779B97F4A7C15ull;
        RecentFast& slot = recent_fast_[h >> 58];
        if (!slot.fast || slot.r != r) {
            auto it = fast_.find(r);
            if (it == fast_.end()) {
                if (untracked_.empty()) untracked_.assign(std::size_t{1} << 16, 0);
                std::uint16_t& n = untracked_[h >> 48];
                if (n < kTrackAfter) {
                    ++n;
                    return -1;  // no lookup would be built for it yet either
                }
                it = fast_.emplace(r, Fast{}).first;
                it->second.asked = kTrackAfter;
            }
            slot = {r, &it->second};
        }
        last_fast_ = slot.fast;
        last_r_ = r;
    }
    Fast& f = *last_fast_;
    if (!f.lookup) {
        // Which layout: a radius asked on many layers is a column's.
        if (f.layers.empty()) f.layers.assign(model_.size(), false);
        if (!f.layers[layer]) {
            f.layers[layer] = true;
            ++f.distinct_layers;
        }
        if (++f.asked < kFastAfter) return -1;
        // Columns also for a radius above all the columns' (a foot's flare, a
        // raft), asked on few layers but at the cells the columns are: the
        // nearest larger column answers for the radii below it.
        const bool wide = columns_.empty() || r > columns_.back()->radius();
        const bool column = (f.distinct_layers >= kColumnsFrom || wide) && columns_.size() < kMaxColumns;
        f.lookup = std::make_unique<DiscLookup>(model_, r, column ? DiscLookup::Layout::Columns : DiscLookup::Layout::PerLayer);
        if (column) {
            columns_.push_back(f.lookup.get());
            std::sort(columns_.begin(), columns_.end(),
                      [](const DiscLookup* a, const DiscLookup* b) { return a->radius() < b->radius(); });
        }
        f.layers = {};
    }
    return f.lookup->lookup(layer, x, y, kFastBudget, fast_bytes_);
}

bool Obstacles::skirt_disc_clear(int layer, double x, double y, double r) const {
    const SkirtLayer& k = (*shared_skirts_)[static_cast<std::size_t>(skirt_at_[layer])];
    return !disc_meets(k.bare, x, y, r) && !disc_meets(k.skirt, x, y, std::max(0.0, r - skirt_relief_));
}

bool Obstacles::disc_clear(int layer, double x, double y, double r) const {
    if (layer < 0 || layer >= layer_count()) return true;
    if (x == run_.x && y == run_.y && r <= run_.r && layer >= run_.layers.lo && layer <= run_.layers.hi) return true;
    if (int f = fast_disc(layer, x, y, r); f >= 0) return f == 1;
    if (!(r >= 0) || std::abs(x) > 1e7 || std::abs(y) > 1e7) return !disc_meets(model_[layer], x, y, r);  // no int overflow below
    return surely_clear(layer, x, y, r) || !disc_meets(model_[layer], x, y, r);
}

bool Obstacles::room_clear(int layer, double x, double y, double r) const {
    if (layer < 0 || layer >= layer_count() || skirt_at_[layer] < 0 || !(skirt_relief_ > 0) || !(r >= 0))
        return disc_clear(layer, x, y, r);
    // The model's own lookups know the skirt at the full radius: their
    // "clear" holds.
    return disc_clear(layer, x, y, r) || skirt_disc_clear(layer, x, y, r);
}

bool Obstacles::disc_clear_exact(int layer, double x, double y, double r) const {
    return layer < 0 || layer >= layer_count() || !disc_meets(model_[layer], x, y, r);
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
