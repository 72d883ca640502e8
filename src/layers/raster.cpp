#include "layers/raster.hpp"

#include "gcode/error.hpp"

#include <algorithm>
#include <bit>
#include <cmath>

namespace scaffold::layers {

BitGrid::BitGrid(double min_x, double min_y, double max_x, double max_y, double cell)
    : ox_(min_x), oy_(min_y), cell_(cell), inv_cell_(1 / cell) {
    nx_ = std::max(1, static_cast<int>(std::ceil((max_x - min_x) / cell)));
    ny_ = std::max(1, static_cast<int>(std::ceil((max_y - min_y) / cell)));
    wpr_ = (nx_ + 63) / 64;
    words_.assign(static_cast<std::size_t>(wpr_) * ny_, 0);
}

CellBox BitGrid::clipped(CellBox b) const {
    if (b.empty()) return b;
    return {std::max(b.i0, 0), std::max(b.j0, 0), std::min(b.i1, nx_ - 1), std::min(b.j1, ny_ - 1)};
}

void BitGrid::clear() { std::fill(words_.begin(), words_.end(), 0); }

void BitGrid::clear(const CellBox& box) {
    CellBox b = clipped(box);
    if (b.empty()) return;
    for (int j = b.j0; j <= b.j1; ++j) {
        std::uint64_t* row = &words_[static_cast<std::size_t>(j) * wpr_];
        std::fill(row + (b.i0 >> 6), row + (b.i1 >> 6) + 1, 0);
    }
}

namespace {

// Fixed point for stepping along a line in cell units: 40 bits of fraction
// leave 23 of integer part, and over at most kMaxSteps steps the error stays
// below 2^-24 cells, far inside kSureCells.
constexpr int kFixBits = 40;
constexpr double kFixOne = static_cast<double>(std::int64_t{1} << kFixBits);
constexpr std::int64_t kFixMask = (std::int64_t{1} << kFixBits) - 1;
constexpr double kFixLimit = static_cast<double>(1 << 21);  // |cell coordinate| below this
constexpr int kMaxSteps = 1 << 16;
// A fraction clear of both cell borders by kSureCells: then its floor is
// the exact computation's.
constexpr std::uint64_t kFixSureLo = static_cast<std::uint64_t>(BitGrid::kSureCells * kFixOne) + 1;
constexpr std::uint64_t kFixSureRange = (std::uint64_t{1} << kFixBits) - 2 * kFixSureLo;
bool fix_sure(std::int64_t v) { return static_cast<std::uint64_t>(v & kFixMask) - kFixSureLo < kFixSureRange; }
// floor(v) when v is clear of integers by kSureCells, as sure_floor, by way
// of fixed point.
bool fix_floor(double v, int& out) {
    if (!(std::abs(v) < kFixLimit)) return false;
    const std::int64_t f = static_cast<std::int64_t>(v * kFixOne);
    out = static_cast<int>(f >> kFixBits);
    return fix_sure(f);
}

}  // namespace

bool BitGrid::all_set_at(double x0, double y0, double dx, double dy, int n, int i_begin) const {
    const double u0 = (x0 - ox_) * inv_cell_, v0 = (y0 - oy_) * inv_cell_;
    const double du = dx / n * inv_cell_, dv = dy / n * inv_cell_;
    const double u1 = u0 + n * du, v1 = v0 + n * dv;
    auto exact_get = [&](int i) {
        const double t = static_cast<double>(i) / n;
        return get(col(x0 + dx * t), row(y0 + dy * t));
    };
    if (!(n <= kMaxSteps && std::max({std::abs(u0), std::abs(v0), std::abs(u1), std::abs(v1)}) < kFixLimit)) {
        for (int i = i_begin; i <= n; ++i)
            if (!exact_get(i)) return false;
        return true;
    }
    const std::int64_t su = static_cast<std::int64_t>(du * kFixOne), sv = static_cast<std::int64_t>(dv * kFixOne);
    std::int64_t u = static_cast<std::int64_t>(u0 * kFixOne) + i_begin * su;
    std::int64_t v = static_cast<std::int64_t>(v0 * kFixOne) + i_begin * sv;
    for (int i = i_begin; i <= n; ++i, u += su, v += sv) {
        if (!(fix_sure(u) && fix_sure(v))) {
            if (!exact_get(i)) return false;
            continue;
        }
        const int ci = static_cast<int>(u >> kFixBits), cj = static_cast<int>(v >> kFixBits);
        if (static_cast<unsigned>(ci) >= static_cast<unsigned>(nx_) || static_cast<unsigned>(cj) >= static_cast<unsigned>(ny_))
            return false;
        if (!((words_[word_index(ci, cj)] >> (ci & 63)) & 1u)) return false;
    }
    return true;
}

namespace {

struct Interval {
    double lo = 1, hi = 0;
    bool empty() const { return hi < lo; }
    void unite(Interval o) {
        if (o.empty()) return;
        if (empty()) { *this = o; return; }
        lo = std::min(lo, o.lo);
        hi = std::max(hi, o.hi);
    }
};

Interval disc_row(double x, double y, double r, double cy) {
    double dy = cy - y;
    if (std::abs(dy) > r) return {};
    double h = std::sqrt(r * r - dy * dy);
    return {x - h, x + h};
}

Interval sorted(double a, double b) { return a <= b ? Interval{a, b} : Interval{b, a}; }

Interval intersect(Interval a, Interval b) { return {std::max(a.lo, b.lo), std::min(a.hi, b.hi)}; }

// Points (x, cy) within r of the segment form one interval (a capsule is convex):
// the union of the two end discs and the band beside the segment.
Interval capsule_row(double x0, double y0, double x1, double y1, double r, double cy) {
    Interval out = disc_row(x0, y0, r, cy);
    out.unite(disc_row(x1, y1, r, cy));
    double dx = x1 - x0, dy = y1 - y0;
    double len2 = dx * dx + dy * dy;
    if (len2 <= 0) return out;
    double len = std::sqrt(len2);
    double ry = cy - y0;
    constexpr double kInf = 1e300;
    Interval perp{-kInf, kInf};  // |dx*ry - dy*(x-x0)| <= r*len
    if (dy != 0) {
        perp = sorted(x0 + (dx * ry - r * len) / dy, x0 + (dx * ry + r * len) / dy);
    } else if (std::abs(ry) > r) {
        return out;
    }
    Interval along{-kInf, kInf};  // 0 <= (x-x0)*dx + ry*dy <= len2
    if (dx != 0) {
        along = sorted(x0 + (-ry * dy) / dx, x0 + (len2 - ry * dy) / dx);
    } else {
        double t = ry * dy;
        if (t < 0 || t > len2) return out;
    }
    out.unite(intersect(perp, along));
    return out;
}

}  // namespace

void BitGrid::draw_segment(double x0, double y0, double x1, double y1, double width) {
    // Never thinner than a cell, so a bead always leaves a connected trace.
    double r = std::max(width * 0.5, cell_ * 0.5);
    // row() without its division where a multiplication surely agrees.
    auto fast_row = [&](double y) {
        int j;
        return sure_floor((y - oy_) * inv_cell_, j) ? j : row(y);
    };
    int j0 = std::max(0, fast_row(std::min(y0, y1) - r));
    int j1 = std::min(ny_ - 1, fast_row(std::max(y0, y1) + r));
    if (j0 > j1) return;
    // capsule_row's bounds, in cell units (v = (x - ox) / cell - 0.5), are
    // linear in the row j but for the end discs: the band across the line
    // [a + j k -/+ hb], its ends p + j q and that + l. Computed so, with
    // reciprocals, they round differently from capsule_row's divisions, so
    // a row whose outcome is not sure by far more than that rounding is
    // redone the exact way: the cells set are capsule_row's.
    const double dx = x1 - x0, dy = y1 - y0, len2 = dx * dx + dy * dy, len = std::sqrt(len2);
    const double inv_dx = dx != 0 ? 1 / dx : 0, inv_dy = dy != 0 ? 1 / dy : 0;
    const double c0 = oy_ + 0.5 * cell_;  // cy(0)
    const double k = dx * inv_dy, a = (x0 - ox_ + (c0 - y0) * k) * inv_cell_ - 0.5;
    const double hb = r * len * std::abs(inv_dy) * inv_cell_;
    const double q = -dy * inv_dx, p = (x0 - ox_ + (c0 - y0) * q) * inv_cell_ - 0.5;
    const double l = len2 * inv_dx * inv_cell_;
    const double v0 = (x0 - ox_) * inv_cell_ - 0.5, v1 = (x1 - ox_) * inv_cell_ - 0.5, rv = r * inv_cell_;
    const double reach = (j1 + 1.0) * (std::abs(k) + std::abs(q));
    const bool linear = len2 > 0 && std::abs(a) + std::abs(p) + hb + std::abs(l) + std::abs(v0) + std::abs(v1) + rv + reach < 5e7;
    constexpr double kHuge = 1e300;
    auto exact_row = [&](int j) {
        Interval span = capsule_row(x0, y0, x1, y1, r, cy(j));
        if (span.empty()) return;
        set_row_span(j, static_cast<int>(std::ceil((span.lo - ox_) / cell_ - 0.5)),
                     static_cast<int>(std::floor((span.hi - ox_) / cell_ - 0.5)));
    };
    // Rows between the ends' y and clear of both short sides of the band
    // (which reach r |dx| / len above and below their end), by a margin far
    // above rounding: the band's ends do not bound them, and the end discs,
    // inside the band's long sides, add nothing.
    const double ylo = std::min(y0, y1), yhi = std::max(y0, y1);
    const double mid = (len2 > 0 ? r * std::abs(dx) / len : r) + 0.01 * cell_;
    if (!linear) {
        for (int j = j0; j <= j1; ++j) exact_row(j);
        return;
    }
    // Such rows form one run [m0, m1] (cy grows with j): each end is where
    // one of the two tests turns, found from an estimate.
    auto estimate = [&](double y, int lo, int hi) {
        return static_cast<int>(std::clamp((y - oy_) * inv_cell_ - 0.5, static_cast<double>(lo), static_cast<double>(hi)));
    };
    int m0 = estimate(ylo + mid, j0, j1 + 1), m1 = estimate(yhi - mid, j0 - 1, j1);
    while (m0 > j0 && cy(m0 - 1) - ylo >= mid) --m0;
    while (m0 <= j1 && !(cy(m0) - ylo >= mid)) ++m0;
    while (m1 < j1 && yhi - cy(m1 + 1) >= mid) ++m1;
    while (m1 >= j0 && !(yhi - cy(m1) >= mid)) --m1;
    if (m0 > m1) m0 = j1 + 1, m1 = j1;  // none
    // The other rows: the hull of the end discs' and the band's spans.
    // The band's ends bound it on every row of a slanted line: that case
    // takes no branch but the discs'.
    const bool slanted = dx != 0 && dy != 0;
    const double lo_end = dx > 0 ? 0 : l, hi_end = dx > 0 ? l : 0, rr = r * r;
    // Spans a cell inside the grid need no clipping: every span lies within
    // the capsule's x extent.
    const bool inside = std::min(v0, v1) - rv > 1 && std::max(v0, v1) + rv < nx_ - 2;
    for (int j = j0 == m0 ? m1 + 1 : j0; j <= j1; j = j + 1 == m0 ? m1 + 1 : j + 1) {
        const double c = cy(j), vc = a + j * k;
        double lo = kHuge, hi = -kHuge;  // empty
        const double e0 = c - y0, e1 = c - y1;
        if (std::abs(e0) <= r) {
            double h = std::sqrt(rr - e0 * e0) * inv_cell_;
            lo = v0 - h, hi = v0 + h;
        }
        if (std::abs(e1) <= r) {
            double h = std::sqrt(rr - e1 * e1) * inv_cell_;
            lo = std::min(lo, v1 - h), hi = std::max(hi, v1 + h);
        }
        bool sure = true;
        if (slanted) {
            const double e = p + j * q;
            const double bl = std::max(vc - hb, e + lo_end), bh = std::min(vc + hb, e + hi_end);
            sure = std::abs(bh - bl) > kSureCells;
            if (bl <= bh) lo = std::min(lo, bl), hi = std::max(hi, bh);
        } else {
            bool band = true;
            double bl = -1e300, bh = 1e300;
            if (dy != 0) bl = vc - hb, bh = vc + hb;
            else if (std::abs(e0) > r) band = false;
            if (dx != 0) {
                const double e = p + j * q;
                bl = std::max(bl, dx > 0 ? e : e + l);
                bh = std::min(bh, dx > 0 ? e + l : e);
            } else if (double t = e0 * dy; t < 0 || t > len2) {
                band = false;
            }
            if (band) {
                sure = std::abs(bh - bl) > kSureCells;
                if (bl <= bh) lo = std::min(lo, bl), hi = std::max(hi, bh);
            }
        }
        if (sure && lo > hi) continue;  // nothing on this row
        int i0 = 0, i1 = -1;
        if (!(sure && fix_floor(lo, i0) && fix_floor(hi, i1)))
            exact_row(j);
        else if (inside)
            or_span(&words_[static_cast<std::size_t>(j) * wpr_], i0 + 1, i1);  // ceil(v) = floor(v) + 1 away from integers
        else
            set_row_span(j, i0 + 1, i1);
    }
    if (m0 > j1) return;
    // The run steps the band's bounds in fixed point, when they stay within
    // its range.
    const bool fixed = m1 - m0 <= kMaxSteps && std::abs(k) < kFixLimit &&
                       std::max({std::abs(a + m0 * k - hb), std::abs(a + m0 * k + hb), std::abs(a + m1 * k - hb),
                                 std::abs(a + m1 * k + hb)}) < kFixLimit;
    if (fixed) {
        const std::int64_t fk = static_cast<std::int64_t>(k * kFixOne);
        const double vc = a + m0 * k;
        std::int64_t lo = static_cast<std::int64_t>((vc - hb) * kFixOne), hi = static_cast<std::int64_t>((vc + hb) * kFixOne);
        std::uint64_t* row = &words_[static_cast<std::size_t>(m0) * wpr_];
        if (inside) {
            // The common case in a loop of its own: nothing but the span.
            for (int j = m0; j <= m1; ++j, lo += fk, hi += fk, row += wpr_) {
                if (fix_sure(lo) && fix_sure(hi)) [[likely]]
                    or_span(row, static_cast<int>(lo >> kFixBits) + 1, static_cast<int>(hi >> kFixBits));
                else
                    exact_row(j);
            }
            return;
        }
        for (int j = m0; j <= m1; ++j, lo += fk, hi += fk, row += wpr_) {
            const int i0 = static_cast<int>(lo >> kFixBits) + 1, i1 = static_cast<int>(hi >> kFixBits);
            if (!(fix_sure(lo) && fix_sure(hi)))
                exact_row(j);
            else if (inside)
                or_span(row, i0, i1);
            else
                set_row_span(j, i0, i1);
        }
        return;
    }
    for (int j = m0; j <= m1; ++j) {
        const double vc = a + j * k;
        int i0 = 0, i1 = -1;
        if (sure_floor(vc - hb, i0) && sure_floor(vc + hb, i1))
            set_row_span(j, i0 + 1, i1);
        else
            exact_row(j);
    }
}

void BitGrid::draw_disc(double x, double y, double r) { draw_segment(x, y, x, y, 2 * r); }

BitGrid& BitGrid::operator|=(const BitGrid& o) {
    for (std::size_t k = 0; k < words_.size(); ++k) words_[k] |= o.words_[k];
    return *this;
}

BitGrid& BitGrid::operator&=(const BitGrid& o) {
    for (std::size_t k = 0; k < words_.size(); ++k) words_[k] &= o.words_[k];
    return *this;
}

void BitGrid::subtract(const BitGrid& o) {
    for (std::size_t k = 0; k < words_.size(); ++k) words_[k] &= ~o.words_[k];
}

void BitGrid::subtract(const BitGrid& o, const CellBox& box) {
    CellBox b = clipped(box);
    if (b.empty()) return;
    for (int j = b.j0; j <= b.j1; ++j) {
        std::size_t k0 = static_cast<std::size_t>(j) * wpr_;
        for (int w = b.i0 >> 6; w <= b.i1 >> 6; ++w) words_[k0 + w] &= ~o.words_[k0 + w];
    }
}

bool BitGrid::any(const CellBox& box) const {
    CellBox b = clipped(box);
    if (b.empty()) return false;
    for (int j = b.j0; j <= b.j1; ++j) {
        const std::uint64_t* row = &words_[static_cast<std::size_t>(j) * wpr_];
        for (int w = b.i0 >> 6; w <= b.i1 >> 6; ++w)
            if (row[w]) return true;
    }
    return false;
}

std::size_t BitGrid::count() const {
    std::size_t n = 0;
    for (auto w : words_) n += static_cast<std::size_t>(std::popcount(w));
    return n;
}

bool BitGrid::any() const {
    return std::any_of(words_.begin(), words_.end(), [](std::uint64_t w) { return w != 0; });
}

namespace {

// Row shifted towards higher i by s bits (s < 64 * words), into out (OR).
void or_shift_up(const std::uint64_t* in, std::uint64_t* out, int words, int s) {
    int ws = s >> 6, bs = s & 63;
    for (int w = words - 1; w >= ws; --w) {
        std::uint64_t v = in[w - ws] << bs;
        if (bs && w - ws - 1 >= 0) v |= in[w - ws - 1] >> (64 - bs);
        out[w] |= v;
    }
}

void or_shift_down(const std::uint64_t* in, std::uint64_t* out, int words, int s) {
    int ws = s >> 6, bs = s & 63;
    for (int w = 0; w + ws < words; ++w) {
        std::uint64_t v = in[w + ws] >> bs;
        if (bs && w + ws + 1 < words) v |= in[w + ws + 1] << (64 - bs);
        out[w] |= v;
    }
}

// One step of horizontal dilation by s cells (1 <= s < 64), out = in |
// in shifted both ways; in and out may be the same row.
void dilate_step(const std::uint64_t* in, std::uint64_t* out, int words, int s) {
    std::uint64_t prev = 0;  // in[w - 1] before this step
    for (int w = 0; w < words; ++w) {
        const std::uint64_t cur = in[w], next = w + 1 < words ? in[w + 1] : 0;
        out[w] = cur | cur << s | prev >> (64 - s) | cur >> s | next << (64 - s);
        prev = cur;
    }
}

// Horizontal dilation of `in` (already dilated by e cells) to k > e cells
// into out, in O(log k) steps; tmp is scratch of `words` words.
void dilate_row(const std::uint64_t* in, std::uint64_t* out, std::uint64_t* tmp, int words, int e, int k) {
    const std::uint64_t* from = in;
    while (e < k) {
        int s = std::min(e + 1, k - e);
        if (s < 64) {
            dilate_step(from, out, words, s);
        } else {
            std::copy(from, from + words, tmp);
            std::copy(tmp, tmp + words, out);
            or_shift_up(tmp, out, words, s);
            or_shift_down(tmp, out, words, s);
        }
        from = out;
        e += s;
    }
}

}  // namespace

CellBox BitGrid::dilate_into(BitGrid& out, double r, const CellBox& box) const {
    const CellBox b = clipped(box);
    if (b.empty()) return b;
    double rc = r / cell_;
    int R = std::max(0, static_cast<int>(std::floor(rc + 1e-9)));
    // half[d]: the horizontal reach at row offset d, non-increasing in d.
    std::vector<int> half(R + 1, 0);
    if (R > 0)
        for (int d = 0; d <= R; ++d)
            half[d] = static_cast<int>(std::floor(std::sqrt(std::max(0.0, rc * rc - d * d)) + 1e-9));
    // Only the words within reach of the box; bits shifted past them are
    // beyond every source's reach.
    const int oa = std::max(0, (b.i0 - R) >> 6), ob = std::min(wpr_ - 1, (b.i1 + R) >> 6), n = ob - oa + 1;
    // The row dilated for each offset d, built from the next larger d's
    // (smaller reach) by dilating further; equal reaches share a row.
    std::vector<std::uint64_t> rows(static_cast<std::size_t>(R + 1) * n), tmp(n);
    std::vector<const std::uint64_t*> level(R + 1);
    const std::uint64_t tail = (nx_ & 63) ? (~std::uint64_t{0} >> (64 - (nx_ & 63))) : ~std::uint64_t{0};
    for (int j = b.j0; j <= b.j1; ++j) {
        const std::uint64_t* src = &words_[static_cast<std::size_t>(j) * wpr_ + oa];
        if (std::all_of(src, src + n, [](std::uint64_t w) { return w == 0; })) continue;
        for (int d = R; d >= 0; --d) {
            const std::uint64_t* from = d == R ? src : level[d + 1];
            const int e = d == R ? 0 : half[d + 1];
            if (half[d] == e) {
                level[d] = from;
            } else {
                std::uint64_t* row = &rows[static_cast<std::size_t>(d) * n];
                dilate_row(from, row, tmp.data(), n, e, half[d]);
                level[d] = row;
            }
        }
        for (int d = -R; d <= R; ++d) {
            int jj = j + d;
            if (jj < 0 || jj >= ny_) continue;
            const std::uint64_t* row = level[std::abs(d)];
            std::uint64_t* dst = &out.words_[static_cast<std::size_t>(jj) * wpr_ + oa];
            for (int w = 0; w < n; ++w) dst[w] |= row[w];
            if (ob == wpr_ - 1) dst[n - 1] &= tail;
        }
    }
    return clipped(b.grown(R));
}

BitGrid BitGrid::dilated(double r) const {
    // The box of the set cells, to whole words.
    CellBox box;
    for (int j = 0; j < ny_; ++j) {
        const std::uint64_t* row = &words_[static_cast<std::size_t>(j) * wpr_];
        for (int w = 0; w < wpr_; ++w) {
            if (!row[w]) continue;
            if (box.empty()) box = {w * 64, j, w * 64 + 63, j};
            box.i0 = std::min(box.i0, w * 64);
            box.i1 = std::max(box.i1, w * 64 + 63);
            box.j1 = j;
        }
    }
    BitGrid out = *this;
    dilate_into(out, r, box);
    return out;
}

namespace {

// Span flood fill over the free (unset) cells of `g` from (i, j), marking
// `mark`; returns whether the flood touched the grid border.
struct Span {
    int j, a, b;
};

bool flood_free(const BitGrid& g, BitGrid& mark, int i0, int j0, std::vector<std::pair<int, int>>& stack,
                std::vector<Span>* spans = nullptr) {
    const int nx = g.width(), ny = g.height(), wpr = g.words_per_row();
    // Free cells of row j in word w: not material, not yet flooded, inside the grid.
    auto free_word = [&](int j, int w) {
        std::uint64_t f = ~(g.row_words(j)[w] | mark.row_words(j)[w]);
        if (w == wpr - 1 && (nx & 63)) f &= ~std::uint64_t{0} >> (64 - (nx & 63));
        return f;
    };
    auto is_free = [&](int i, int j) { return (free_word(j, i >> 6) >> (i & 63)) & 1u; };
    bool border = false;
    stack.clear();
    stack.emplace_back(i0, j0);
    while (!stack.empty()) {
        auto [i, j] = stack.back();
        stack.pop_back();
        if (!is_free(i, j)) continue;
        // Extend the run right and left a word at a time.
        int b = i;
        for (int w = i >> 6;; ++w) {
            std::uint64_t blocked = ~free_word(j, w);
            if (w == i >> 6) blocked &= ~std::uint64_t{0} << (i & 63);
            if (blocked) { b = w * 64 + std::countr_zero(blocked) - 1; break; }
            if (w == wpr - 1) { b = nx - 1; break; }
        }
        int a = i;
        for (int w = i >> 6;; --w) {
            std::uint64_t blocked = ~free_word(j, w);
            if (w == i >> 6) blocked &= (i & 63) == 63 ? ~std::uint64_t{0} : ((std::uint64_t{1} << ((i & 63) + 1)) - 1);
            if (blocked) { a = w * 64 + 63 - std::countl_zero(blocked) + 1; break; }
            if (w == 0) { a = 0; break; }
        }
        mark.set_row_span(j, a, b);
        if (spans) spans->push_back({j, a, b});
        if (a == 0 || b == nx - 1 || j == 0 || j == ny - 1) border = true;
        // One seed per free run of the neighbouring rows within [a, b].
        for (int jj : {j - 1, j + 1}) {
            if (jj < 0 || jj >= ny) continue;
            for (int w = a >> 6; w <= b >> 6; ++w) {
                std::uint64_t f = free_word(jj, w);
                if (w == a >> 6) f &= ~std::uint64_t{0} << (a & 63);
                if (w == b >> 6 && (b & 63) != 63) f &= (std::uint64_t{1} << ((b & 63) + 1)) - 1;
                // A run start: free here and not free just below (or at the span's start).
                std::uint64_t prev = f << 1;
                if (w > a >> 6) prev |= (free_word(jj, w - 1) >> 63) & 1u;
                std::uint64_t starts = f & ~prev;
                while (starts) {
                    stack.emplace_back(w * 64 + std::countr_zero(starts), jj);
                    starts &= starts - 1;
                }
            }
        }
    }
    return border;
}

}  // namespace

BitGrid BitGrid::filled() const {
    // Flood the empty cells from the border; whatever the flood misses is
    // enclosed by material and counts as filled.
    BitGrid outside = *this;
    outside.clear();
    std::vector<std::pair<int, int>> stack;
    auto seed = [&](int i, int j) {
        if (!get(i, j) && !outside.get(i, j)) flood_free(*this, outside, i, j, stack);
    };
    for (int i = 0; i < nx_; ++i) { seed(i, 0); seed(i, ny_ - 1); }
    for (int j = 0; j < ny_; ++j) { seed(0, j); seed(nx_ - 1, j); }
    BitGrid out = *this;
    std::uint64_t tail = (nx_ & 63) ? (~std::uint64_t{0} >> (64 - (nx_ & 63))) : ~std::uint64_t{0};
    for (int j = 0; j < ny_; ++j) {
        for (int w = 0; w < wpr_; ++w) {
            std::size_t k = static_cast<std::size_t>(j) * wpr_ + w;
            out.words_[k] = ~outside.words_[k];
        }
        out.words_[static_cast<std::size_t>(j) * wpr_ + wpr_ - 1] &= tail;
    }
    return out;
}

BitGrid BitGrid::empty_like() const {
    BitGrid g;
    g.ox_ = ox_, g.oy_ = oy_, g.cell_ = cell_, g.inv_cell_ = inv_cell_;
    g.nx_ = nx_, g.ny_ = ny_, g.wpr_ = wpr_;
    g.words_.assign(words_.size(), 0);
    return g;
}

BitGrid BitGrid::crop(const CellBox& box, int& i_off, int& j_off) const {
    const CellBox c = clipped(box);
    BitGrid g;
    g.cell_ = cell_, g.inv_cell_ = inv_cell_;
    if (c.empty()) {
        i_off = j_off = 0;
        g.ox_ = ox_, g.oy_ = oy_;
        g.nx_ = g.ny_ = 1, g.wpr_ = 1;
        g.words_.assign(1, 0);
        return g;
    }
    const int w0 = c.i0 >> 6, w1 = c.i1 >> 6;
    i_off = w0 * 64;
    j_off = c.j0;
    g.ox_ = ox_ + i_off * cell_, g.oy_ = oy_ + j_off * cell_;
    g.nx_ = std::min(nx_, (w1 + 1) * 64) - i_off, g.ny_ = c.j1 - c.j0 + 1, g.wpr_ = w1 - w0 + 1;
    g.words_.resize(static_cast<std::size_t>(g.wpr_) * g.ny_);
    for (int j = 0; j < g.ny_; ++j)
        std::copy_n(&words_[static_cast<std::size_t>(j + j_off) * wpr_ + w0], g.wpr_, &g.words_[static_cast<std::size_t>(j) * g.wpr_]);
    return g;
}

void BitGrid::or_crop(const BitGrid& part, int i_off, int j_off) {
    const int w0 = i_off >> 6, n = std::min(part.wpr_, wpr_ - w0);
    for (int j = 0; j < part.ny_ && j + j_off < ny_; ++j) {
        std::uint64_t* row = &words_[static_cast<std::size_t>(j + j_off) * wpr_ + w0];
        const std::uint64_t* src = &part.words_[static_cast<std::size_t>(j) * part.wpr_];
        for (int w = 0; w < n; ++w) row[w] |= src[w];
    }
}

BitGrid BitGrid::enclosed(const BitGrid& seeds) const { return enclosed(seeds, {0, 0, nx_ - 1, ny_ - 1}); }

BitGrid BitGrid::enclosed(const BitGrid& seeds, const CellBox& box) const { return flood_holes(seeds, box, false); }

BitGrid BitGrid::holes_with(const BitGrid& seeds) const { return flood_holes(seeds, {0, 0, nx_ - 1, ny_ - 1}, true); }

BitGrid BitGrid::flood_holes(const BitGrid& seeds, const CellBox& box, bool whole) const {
    // Only the regions the seeds are in are flooded, so a layer with a few
    // candidate cells costs a few small floods, not a whole-grid fill. The
    // seeds of an enclosed flood's spans go straight to out.
    BitGrid out = empty_like(), visited = empty_like();
    std::vector<std::pair<int, int>> stack;
    std::vector<Span> spans;
    const CellBox b = clipped(box);
    if (b.empty()) return out;
    for (int j = b.j0; j <= b.j1; ++j) {
        for (int w = b.i0 >> 6; w <= b.i1 >> 6; ++w) {
            std::uint64_t bits = seeds.words_[static_cast<std::size_t>(j) * wpr_ + w];
            while (bits) {
                int i = w * 64 + std::countr_zero(bits);
                bits &= bits - 1;
                if (get(i, j) || visited.get(i, j)) continue;
                spans.clear();
                if (flood_free(*this, visited, i, j, stack, &spans)) continue;
                for (const Span& sp : spans) {
                    const std::size_t row = static_cast<std::size_t>(sp.j) * wpr_;
                    for (int v = sp.a >> 6; v <= sp.b >> 6; ++v) {
                        std::uint64_t m = ~std::uint64_t{0};
                        if (v == sp.a >> 6) m &= ~std::uint64_t{0} << (sp.a & 63);
                        if (v == sp.b >> 6) m &= ~std::uint64_t{0} >> (63 - (sp.b & 63));
                        out.words_[row + v] |= whole ? m : seeds.words_[row + v] & m;
                    }
                }
            }
        }
    }
    return out;
}

void draw_hole_seed(BitGrid& seeds, const Segment& sg) {
    using gcode::Role;
    if (sg.role == Role::ExternalPerimeter || sg.role == Role::Perimeter || sg.role == Role::OverhangPerimeter) return;
    // Grown sideways only: a bead's end lies on the wall it meets, and a
    // seed grown there too would leak through that wall into a cavity
    // beyond (a benchy's cabin through the infill of its walls). Beads too
    // short to keep a middle (dots, turns of gap fill) seed nothing.
    const double len = std::hypot(sg.x1 - sg.x0, sg.y1 - sg.y0), trim = sg.width / 2 + 2 * seeds.cell();
    if (len <= 2 * trim) return;
    const double ux = (sg.x1 - sg.x0) / len * trim, uy = (sg.y1 - sg.y0) / len * trim;
    seeds.draw_segment(sg.x0 + ux, sg.y0 + uy, sg.x1 - ux, sg.y1 - uy, sg.width + 3 * seeds.cell());
}

BitGrid make_grid(const LayerStack& stack, double cell, double margin) {
    const Bounds& b = stack.bounds;
    // A print a metre across (an arc of huge radius, a stray coordinate)
    // would need gigabytes per raster: refuse it instead.
    double cells = (b.max_x - b.min_x + 2 * margin) / cell * ((b.max_y - b.min_y + 2 * margin) / cell);
    if (!(cells <= kMaxGridCells))
        throw Error("the print spans " + std::to_string(static_cast<long>(b.max_x - b.min_x)) + " x " +
                    std::to_string(static_cast<long>(b.max_y - b.min_y)) +
                    " mm: too large to rasterize at this --resolution; check for stray coordinates");
    // On the lattice of multiples of the cell from the origin: the detector
    // and the validator, whose prints' bounds differ by the support, then
    // share cell boundaries and judge a borderline bead alike.
    const double x0 = std::floor((b.min_x - margin) / cell) * cell, y0 = std::floor((b.min_y - margin) / cell) * cell;
    return BitGrid(x0, y0, b.max_x + margin, b.max_y + margin, cell);
}

std::string svg_cell_runs(const BitGrid& g, const char* fill) {
    std::string o = std::string("<g fill=\"") + fill + "\">\n";
    for (int j = 0; j < g.height(); ++j)
        for (int i = 0; i < g.width();) {
            if (!g.get(i, j)) { ++i; continue; }
            int k = i;
            while (k < g.width() && g.get(k, j)) ++k;
            o += "<rect x=\"" + std::to_string(i) + "\" y=\"" + std::to_string(g.height() - 1 - j) + "\" width=\"" +
                 std::to_string(k - i) + "\" height=\"1\"/>\n";
            i = k;
        }
    return o + "</g>\n";
}

void draw_layer(BitGrid& grid, const Layer& layer) {
    for (const Segment& s : layer.segments) grid.draw_segment(s.x0, s.y0, s.x1, s.y1, s.width);
}

CellBox layer_box(const BitGrid& grid, const Layer& layer) {
    if (layer.segments.empty()) return {};
    double x0 = 1e300, y0 = 1e300, x1 = -1e300, y1 = -1e300;
    for (const Segment& s : layer.segments) {
        double r = std::max(s.width * 0.5, grid.cell() * 0.5);
        x0 = std::min(x0, std::min<double>(s.x0, s.x1) - r);
        y0 = std::min(y0, std::min<double>(s.y0, s.y1) - r);
        x1 = std::max(x1, std::max<double>(s.x0, s.x1) + r);
        y1 = std::max(y1, std::max<double>(s.y0, s.y1) + r);
    }
    // A cell of slack either side for the rounding of interpolated points.
    auto to_cell = [&](double v, double o) { return std::clamp((v - o) / grid.cell(), -1e9, 1e9); };
    CellBox b{static_cast<int>(std::floor(to_cell(x0, grid.origin_x()))) - 2,
              static_cast<int>(std::floor(to_cell(y0, grid.origin_y()))) - 2,
              static_cast<int>(std::floor(to_cell(x1, grid.origin_x()))) + 2,
              static_cast<int>(std::floor(to_cell(y1, grid.origin_y()))) + 2};
    return grid.clipped(b);
}

}  // namespace scaffold::layers
