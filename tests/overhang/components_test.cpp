// components() reads neighbours three cells at a time away from the grid's
// edge; it must find the plain cell-by-cell search's components, cells in
// the same order, on random grids with cells on every edge and across
// word borders.
#include <gtest/gtest.h>

#include <random>
#include <vector>

#include "layers/raster.hpp"
#include "overhang/overhangs.hpp"

using scaffold::layers::BitGrid;
using scaffold::overhang::Cell;

namespace {

std::vector<std::vector<Cell>> plain_components(const BitGrid& g) {
    BitGrid seen = g;
    seen.clear();
    std::vector<std::vector<Cell>> out;
    for (int j = 0; j < g.height(); ++j)
        for (int i = 0; i < g.width(); ++i) {
            if (!g.get(i, j) || seen.get(i, j)) continue;
            std::vector<Cell> comp, stack{{i, j}};
            seen.set(i, j);
            while (!stack.empty()) {
                Cell c = stack.back();
                stack.pop_back();
                comp.push_back(c);
                for (int dj = -1; dj <= 1; ++dj)
                    for (int di = -1; di <= 1; ++di) {
                        int a = c.i + di, b = c.j + dj;
                        if ((di || dj) && g.get(a, b) && !seen.get(a, b)) {
                            seen.set(a, b);
                            stack.push_back({a, b});
                        }
                    }
            }
            out.push_back(comp);
        }
    return out;
}

}  // namespace

TEST(Components, MatchThePlainSearch) {
    std::mt19937 rng(777);
    for (double width : {6.3, 13.0, 20.1}) {  // 63, 130 and 201 cells: edges inside and at word borders
        BitGrid g(0, 0, width, 7.9, 0.1);
        for (int n = 0; n < 40; ++n) {
            g.clear();
            const int density = 5 + n % 8 * 8;  // percent
            for (int j = 0; j < g.height(); ++j)
                for (int i = 0; i < g.width(); ++i)
                    if (static_cast<int>(rng() % 100) < density) g.set(i, j);
            const auto want = plain_components(g), got = scaffold::overhang::components(g);
            ASSERT_EQ(got.size(), want.size()) << width << " " << n;
            for (std::size_t k = 0; k < want.size(); ++k) {
                ASSERT_EQ(got[k].size(), want[k].size()) << width << " " << n << " " << k;
                for (std::size_t c = 0; c < want[k].size(); ++c) {
                    ASSERT_EQ(got[k][c].i, want[k][c].i);
                    ASSERT_EQ(got[k][c].j, want[k][c].j);
                }
            }
        }
    }
}
