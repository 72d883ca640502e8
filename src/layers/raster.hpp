#pragma once
// A bit grid over the print's XY bounds; one bit per cell. Layers are drawn
// into it as thick lines of their real width. Memory follows the print's
// bounding box, not the bed.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include "layers/layer_stack.hpp"

namespace scaffold::layers {

// A rectangle of cells, bounds inclusive; empty when i1 < i0 or j1 < j0.
// Per-layer work is confined to the box a layer can touch, not the grid.
struct CellBox {
    int i0 = 0, j0 = 0, i1 = -1, j1 = -1;
    bool empty() const { return i1 < i0 || j1 < j0; }
    CellBox grown(int n) const { return empty() ? *this : CellBox{i0 - n, j0 - n, i1 + n, j1 + n}; }
};

// The smallest box holding both.
inline CellBox united(const CellBox& a, const CellBox& b) {
    if (a.empty()) return b;
    if (b.empty()) return a;
    return {a.i0 < b.i0 ? a.i0 : b.i0, a.j0 < b.j0 ? a.j0 : b.j0, a.i1 > b.i1 ? a.i1 : b.i1, a.j1 > b.j1 ? a.j1 : b.j1};
}

// Sets cells i0..i1 of a row of 64-bit words, all inside the row; none
// when i0 > i1.
inline void or_span(std::uint64_t* row, int i0, int i1) {
    if (i0 > i1) return;
    const int w0 = i0 >> 6, w1 = i1 >> 6;
    const std::uint64_t lo = ~std::uint64_t{0} << (i0 & 63), hi = ~std::uint64_t{0} >> (63 - (i1 & 63));
    if (w0 == w1) {
        row[w0] |= lo & hi;
        return;
    }
    row[w0] |= lo;
    for (int w = w0 + 1; w < w1; ++w) row[w] = ~std::uint64_t{0};
    row[w1] |= hi;
}

class BitGrid {
public:
    BitGrid() = default;
    // Covers [min_x, max_x] x [min_y, max_y] with square cells of `cell` mm.
    BitGrid(double min_x, double min_y, double max_x, double max_y, double cell);

    int width() const { return nx_; }
    int height() const { return ny_; }
    double cell() const { return cell_; }
    double origin_x() const { return ox_; }
    double origin_y() const { return oy_; }
    double cell_area() const { return cell_ * cell_; }
    // Centre of cell (i, j) in mm.
    double cx(int i) const { return ox_ + (i + 0.5) * cell_; }
    double cy(int j) const { return oy_ + (j + 0.5) * cell_; }
    int col(double x) const { return static_cast<int>(std::floor((x - ox_) / cell_)); }  // may be outside [0, width)
    int row(double y) const { return static_cast<int>(std::floor((y - oy_) / cell_)); }
    CellBox clipped(CellBox b) const;  // b inside the grid
    // The cell of a point computed in a way that may round differently from
    // the exact computation (by far less than kSureCells): false when the
    // point lies that close to a cell border, where only the exact point
    // can tell. Multiplies where col() and row() divide.
    bool sure_cell(double x, double y, int& i, int& j) const {
        return sure_floor((x - ox_) * inv_cell_, i) && sure_floor((y - oy_) * inv_cell_, j);
    }
    static constexpr double kSureCells = 1e-6;
    // Whether the cells of the points (x0 + dx * t, y0 + dy * t), t = i / n
    // for i = i_begin..n, are all set, each cell as col() and row() of that
    // exact point (outside the grid: not set). Steps in fixed point, a point
    // near a cell border redone the exact way.
    bool all_set_at(double x0, double y0, double dx, double dy, int n, int i_begin) const;

    bool get(int i, int j) const {
        if (i < 0 || j < 0 || i >= nx_ || j >= ny_) return false;
        return (words_[word_index(i, j)] >> (i & 63)) & 1u;
    }
    void set(int i, int j) {
        if (i < 0 || j < 0 || i >= nx_ || j >= ny_) return;
        words_[word_index(i, j)] |= std::uint64_t{1} << (i & 63);
    }
    void clear();
    void clear(const CellBox& box);  // whole words: the grid must be empty outside box
    // Cells i0..i1 of row j (inclusive, clipped).
    void set_row_span(int j, int i0, int i1) {
        if (j < 0 || j >= ny_) return;
        i0 = std::max(i0, 0);
        i1 = std::min(i1, nx_ - 1);
        or_span(&words_[static_cast<std::size_t>(j) * wpr_], i0, i1);
    }
    const std::uint64_t* row_words(int j) const { return &words_[static_cast<std::size_t>(j) * wpr_]; }
    BitGrid empty_like() const;  // same shape, no cells set
    // The cells of `box` (clipped), widened to whole words, as a grid of
    // their own: its cell (i, j) is this grid's (i + i_off, j + j_off), i_off
    // a multiple of 64. Work on a layer's box, not the whole plate's grid.
    BitGrid crop(const CellBox& box, int& i_off, int& j_off) const;
    // This grid |= a crop of it (crop's offsets).
    void or_crop(const BitGrid& part, int i_off, int j_off);
    bool same_shape(const BitGrid& o) const { return nx_ == o.nx_ && ny_ == o.ny_ && cell_ == o.cell_ && ox_ == o.ox_ && oy_ == o.oy_; }

    // Sets every cell whose centre is within width/2 of the segment.
    void draw_segment(double x0, double y0, double x1, double y1, double width);
    // Sets every cell whose centre is within r of (x, y).
    void draw_disc(double x, double y, double r);

    BitGrid& operator|=(const BitGrid& o);
    BitGrid& operator&=(const BitGrid& o);
    void subtract(const BitGrid& o);  // this &= ~o
    void subtract(const BitGrid& o, const CellBox& box);  // within box (whole words)
    // Every cell within r (mm) of a set cell becomes set.
    BitGrid dilated(double r) const;
    // out |= this dilated by r, for a grid empty outside `box`; returns the
    // (clipped) box of out that can have changed. Same shape required.
    CellBox dilate_into(BitGrid& out, double r, const CellBox& box) const;
    // Cells enclosed by set cells (not reachable from the border) become set.
    BitGrid filled() const;
    // The cells of `seeds` (same shape) that lie in holes enclosed by set
    // cells; like filled() & seeds, but floods only where the seeds are.
    BitGrid enclosed(const BitGrid& seeds) const;
    // The same for seeds that lie within box (whole words).
    BitGrid enclosed(const BitGrid& seeds, const CellBox& box) const;
    // The holes enclosed by set cells that hold a cell of `seeds`, whole.
    BitGrid holes_with(const BitGrid& seeds) const;
    std::size_t count() const;
    bool any() const;
    bool any(const CellBox& box) const;  // within box (whole words)

    int words_per_row() const { return wpr_; }
    const std::vector<std::uint64_t>& words() const { return words_; }

private:
    // enclosed() (the seeds' cells) or holes_with() (whole holes).
    BitGrid flood_holes(const BitGrid& seeds, const CellBox& box, bool whole) const;
    // floor(v), when v is clear of integers by kSureCells (and fits an int
    // with that margin).
    static bool sure_floor(double v, int& out) {
        if (!(std::abs(v) < 1e8)) return false;
        int k = static_cast<int>(v);
        if (v < k) --k;
        double f = v - k;
        out = k;
        return f > kSureCells && f < 1 - kSureCells;
    }
    std::size_t word_index(int i, int j) const { return static_cast<std::size_t>(j) * wpr_ + (i >> 6); }
    double ox_ = 0, oy_ = 0, cell_ = 0.1, inv_cell_ = 10;
    int nx_ = 0, ny_ = 0, wpr_ = 0;
    std::vector<std::uint64_t> words_;
};

// Largest raster make_grid builds: 1 m x 1 m at 0.1 mm (12.5 MB a grid).
inline constexpr double kMaxGridCells = 1e8;

// The grid for a stack: its bounds padded by `margin` mm on every side.
// Throws scaffold::Error beyond kMaxGridCells.
BitGrid make_grid(const LayerStack& stack, double cell, double margin);

// A hole of the model's footprint beside a bead that is no wall (infill,
// gap fill, a bead of unknown role) lies inside the part; one walled by
// perimeters alone is a cavity of the model (a dome's inside, a cabin's
// room), where support may stand and pass. Draws a model bead into the
// seeds of the part's holes (for holes_with) if it is no wall, grown by
// 1.5 cells each side to reach the hole's cells beside it, and its ends cut
// back inside the bead (they rest on walls).
void draw_hole_seed(BitGrid& seeds, const Segment& sg);
// Draws every segment of the layer.
void draw_layer(BitGrid& grid, const Layer& layer);
// The cells draw_layer (or drawing any part of its segments at their
// width) can set, clipped to the grid.
CellBox layer_box(const BitGrid& grid, const Layer& layer);
// What METHOD's rule (a) holds above the layer: every cell whose centre
// lies within `reach` of one of its beads that `keep(segment)` accepts,
// measured from the bead itself rather than from the cells it covers, which
// fall up to a cell short of its edge. Returns the box that can have changed.
template <class Keep>
CellBox draw_reach(BitGrid& grid, const Layer& layer, double reach, Keep keep) {
    bool any = false;
    for (const Segment& s : layer.segments)
        if (keep(s)) {
            grid.draw_segment(s.x0, s.y0, s.x1, s.y1, s.width + 2 * reach);
            any = true;
        }
    if (!any) return {};
    return grid.clipped(layer_box(grid, layer).grown(static_cast<int>(std::ceil(reach / grid.cell())) + 1));
}

// The set cells as SVG: one <rect> per horizontal run, in cell units with
// y pointing up (row 0 at the bottom), inside a <g fill="...">.
std::string svg_cell_runs(const BitGrid& grid, const char* fill);

}  // namespace scaffold::layers
