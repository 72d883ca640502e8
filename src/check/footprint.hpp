#pragma once
// The model's footprint under a support island, as METHOD's Standing rule
// reads it for a base on the model: the model's cells, holes up to a size
// filled (a column on a small pocket of the model stands on it; one inside
// a cup or a torus's hole does not).
#include <cstddef>
#include <cstdint>
#include <vector>

#include "layers/raster.hpp"

namespace scaffold::check {

struct Footprint {
    layers::BitGrid grid;             // the model's cells, set by the caller
    int i0 = 0, j0 = 0;               // lattice cell of the grid's (0, 0)
    std::vector<std::uint8_t> state;  // per cell of grid, zeroed by the caller: 0 not known, 1 small hole, 2 open
    std::size_t limit = 0;            // a hole's most cells

    // Whether the model covers lattice cell (gi, gj): a cell of the grid,
    // or of a hole of at most `limit` cells (a flood through the empty
    // cells, 4-neighbours, that stays off the grid's edge).
    bool covers(int gi, int gj);

private:
    std::vector<int> queue_;
};

}  // namespace scaffold::check
