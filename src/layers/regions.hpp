#pragma once
// Connected regions of a layer's cells, and the speck rule shared by the
// detector and the validator (METHOD.md): a lone region smaller than the
// minimum area, that continues no region of a layer just below or above,
// is raster noise; one that continues over two or more layers always counts.
#include <vector>

#include "layers/raster.hpp"

namespace scaffold::layers {

// Beads closer than this belong to one region.
inline constexpr double kRegionJoin = 0.6;

struct Cell {
    int i, j;
};

// 8-connected components of the set cells, each as a list of cells in
// discovery order (depth first from the row-major first cell; deterministic).
std::vector<std::vector<Cell>> components(const BitGrid& g);

// Cells of `g` grouped by the components of `g` grown by `join` mm, so the
// parallel lines of one bridge or skin make one region; rows in order.
std::vector<std::vector<Cell>> regions(const BitGrid& g, double join);

struct Region {
    int layer = 0;
    double z = 0;
    int i0 = 0, i1 = 0, j0 = 0, j1 = 0;  // cell bounds
    std::vector<Cell> cells;
};

// The region of `cells` on `layer` at height z, with its bounds.
Region make_region(std::vector<Cell> cells, int layer, double z);

// Whether each region (in layer order) counts under the speck rule.
std::vector<char> kept_regions(const std::vector<Region>& rs, const BitGrid& g, double layer_height, double min_area);

}  // namespace scaffold::layers
