#include "layers/regions.hpp"

#include <algorithm>
#include <bit>
#include <cmath>

namespace scaffold::layers {

// Neighbours read three cells a row away from the grid's edge; the
// order of discovery is the cell-by-cell search's.
std::vector<std::vector<Cell>> components(const BitGrid& g) {
    BitGrid seen(g.origin_x(), g.origin_y(), g.origin_x() + g.width() * g.cell(),
                         g.origin_y() + g.height() * g.cell(), g.cell());
    std::vector<std::vector<Cell>> out;
    std::vector<Cell> stack;
    const int wpr = g.words_per_row(), nx = g.width(), ny = g.height();
    // Set and unseen cells i - 1 .. i + 1 of row j as bits 0..2 (i - 1 >= 0, i + 1 < nx).
    auto fresh3 = [&](int i, int j) {
        const std::uint64_t* a = g.row_words(j);
        const std::uint64_t* b = seen.row_words(j);
        const int lo = i - 1, w = lo >> 6, sh = lo & 63;
        std::uint64_t v = (a[w] & ~b[w]) >> sh;
        if (sh > 61) v |= (a[w + 1] & ~b[w + 1]) << (64 - sh);
        return v & 7u;
    };
    for (int j = 0; j < ny; ++j) {
        for (int w = 0; w < wpr; ++w) {
            // Cells already seen (reached from an earlier row) are skipped a word at a time.
            std::uint64_t bits = g.row_words(j)[w] & ~seen.row_words(j)[w];
            while (bits) {
                int i = w * 64 + std::countr_zero(bits);
                bits &= bits - 1;
                if (seen.get(i, j)) continue;
                std::vector<Cell> comp;
                stack.push_back({i, j});
                seen.set(i, j);
                while (!stack.empty()) {
                    Cell c = stack.back();
                    stack.pop_back();
                    comp.push_back(c);
                    if (c.i >= 1 && c.i + 1 < nx && c.j >= 1 && c.j + 1 < ny) {
                        // The same neighbours in the same order, read a row at a time.
                        const std::uint64_t rows[3] = {fresh3(c.i, c.j - 1), fresh3(c.i, c.j) & 5u, fresh3(c.i, c.j + 1)};
                        for (int dj = -1; dj <= 1; ++dj)
                            for (std::uint64_t m = rows[dj + 1]; m; m &= m - 1) {
                                const int a = c.i - 1 + std::countr_zero(m), b = c.j + dj;
                                seen.set(a, b);
                                stack.push_back({a, b});
                            }
                        continue;
                    }
                    for (int dj = -1; dj <= 1; ++dj)
                        for (int di = -1; di <= 1; ++di) {
                            int a = c.i + di, b = c.j + dj;
                            if ((di || dj) && g.get(a, b) && !seen.get(a, b)) {
                                seen.set(a, b);
                                stack.push_back({a, b});
                            }
                        }
                }
                out.push_back(std::move(comp));
                bits &= ~seen.row_words(j)[w];
            }
        }
    }
    return out;
}

std::vector<std::vector<Cell>> regions(const BitGrid& g, double join) {
    std::vector<std::vector<Cell>> out;
    for (auto& comp : components(g.dilated(join))) {
        std::vector<Cell> cells;
        for (const Cell& c : comp)
            if (g.get(c.i, c.j)) cells.push_back(c);
        std::sort(cells.begin(), cells.end(), [](const Cell& a, const Cell& b) { return a.j != b.j ? a.j < b.j : a.i < b.i; });
        if (!cells.empty()) out.push_back(std::move(cells));
    }
    return out;
}

Region make_region(std::vector<Cell> cells, int layer, double z) {
    Region r;
    r.layer = layer;
    r.z = z;
    r.i0 = r.i1 = cells.front().i;
    r.j0 = r.j1 = cells.front().j;
    for (const Cell& c : cells) {
        r.i0 = std::min(r.i0, c.i); r.i1 = std::max(r.i1, c.i);
        r.j0 = std::min(r.j0, c.j); r.j1 = std::max(r.j1, c.j);
    }
    r.cells = std::move(cells);
    return r;
}

namespace {

// Regions on layers at most this many nominal layer heights apart, whose
// cells come within kChainJoin of each other, continue one another (the
// edge of a slope may move along by a millimetre or two a layer).
constexpr double kChainJoin = 1.5;
constexpr double kChainLayers = 2.5;

int find_root(std::vector<int>& parent, int k) {
    while (parent[k] != k) k = parent[k] = parent[parent[k]];
    return k;
}

// Whether each region counts: regions are chained when one continues the
// other from a layer just below (union-find over pairs that pass a
// bounding-box test, then a cell-distance test); a chain over two or more
// layers always counts, a lone region from `min_area` mm^2 up.
}  // namespace

std::vector<char> kept_regions(const std::vector<Region>& rs, const BitGrid& g, double layer_height,
                               double min_area) {
    const int n = static_cast<int>(rs.size());
    std::vector<int> parent(n);
    for (int k = 0; k < n; ++k) parent[k] = k;
    const int pad = static_cast<int>(std::ceil(kChainJoin / g.cell()));
    const double window = kChainLayers * layer_height + 1e-6;
    for (int k = 0; k < n; ++k) {
        const Region& a = rs[k];
        BitGrid near;  // a's cells grown by kChainJoin, built on first use
        for (int q = k - 1; q >= 0; --q) {
            const Region& b = rs[q];
            if (b.layer == a.layer) continue;
            if (a.z - b.z > window || b.z >= a.z) {
                if (a.layer - b.layer > 64) break;  // far back in the file: no more candidates
                continue;
            }
            if (b.i1 < a.i0 - pad || b.i0 > a.i1 + pad || b.j1 < a.j0 - pad || b.j0 > a.j1 + pad) continue;
            if (find_root(parent, k) == find_root(parent, q)) continue;
            if (near.width() == 0) {
                near = BitGrid(g.origin_x() + (a.i0 - pad) * g.cell(), g.origin_y() + (a.j0 - pad) * g.cell(),
                                       g.origin_x() + (a.i1 + pad + 1) * g.cell(), g.origin_y() + (a.j1 + pad + 1) * g.cell(),
                                       g.cell());
                for (const Cell& c : a.cells) near.set(c.i - a.i0 + pad, c.j - a.j0 + pad);
                near = near.dilated(kChainJoin);
            }
            bool touches = std::any_of(b.cells.begin(), b.cells.end(),
                                       [&](const Cell& c) { return near.get(c.i - a.i0 + pad, c.j - a.j0 + pad); });
            if (touches) parent[find_root(parent, k)] = find_root(parent, q);
        }
    }
    std::vector<double> sum(n, 0.0);
    std::vector<int> members(n, 0);
    for (int k = 0; k < n; ++k) {
        sum[find_root(parent, k)] += static_cast<double>(rs[k].cells.size()) * g.cell_area();
        members[find_root(parent, k)]++;
    }
    std::vector<char> out(n);
    for (int k = 0; k < n; ++k) {
        const int root = find_root(parent, k);
        out[k] = members[root] >= 2 || sum[root] >= min_area;
    }
    return out;
}

}  // namespace scaffold::layers
