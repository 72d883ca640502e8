#pragma once
// What the planner must keep clear of: the model, per layer, as rasters.
// Answers "is a disc free of the model (plus the gap) on layer L" and "where
// is the model top under a column", so pillars and bridges never hit it.
#include <array>
#include <cstdint>
#include <limits>
#include <unordered_map>
#include <memory>
#include <vector>

#include "gcode/settings.hpp"
#include "layers/layer_stack.hpp"
#include "layers/raster.hpp"

namespace scaffold::plan {

// The exact test: whether a cell of `g` is set whose centre lies within r of
// (x, y) (the centres of each row's span computed as below, in floating point).
bool disc_meets(const layers::BitGrid& g, double x, double y, double r);

// disc_meets for one radius on a stack of same-shaped rasters, by lookups:
// per layer and cell, whether every disc of radius r centred in that cell
// surely meets the raster, or surely misses it (decided with a margin far
// above rounding; a disc near the edge of a set cell is left to the exact
// test). Built lazily, within a byte budget shared by the caller, in one
// of two layouts:
// - Columns, for a radius asked on many layers (a pillar's body, tested
//   layer by layer down its column): the bits of 64 layers of a cell in one
//   word, so a column walked down reads the same words (rasters a layer
//   apart are far apart in memory). Blocks of 64 rows x 256 columns x 64
//   layers, filled eight layers at a time, built only where columns are
//   asked (blocks the raster's width spent the budget on a plate of copies
//   long before they covered its columns: the rest fell to the exact test).
// - PerLayer, for a radius asked on a few layers (a step of a tip's
//   taper): two rasters per layer asked, whole.
class DiscLookup {
public:
    enum class Layout { Columns, PerLayer };
    // `model` must outlive the lookup.
    DiscLookup(const std::vector<layers::BitGrid>& model, double r, Layout layout);
    double radius() const { return r_; }
    // 1 the disc misses the layer's raster, 0 it meets it, -1 unknown (near
    // a cell's edge, outside the grid, or what it needs built would not fit
    // `budget` bytes beyond `used`; building adds its bytes to `used`).
    int lookup(int layer, double x, double y, std::size_t budget, std::size_t& used);
    // The same; when the disc misses and the layout is Columns, also the
    // layers around `layer` (of its 64) on which it surely misses too.
    struct LayerRange {
        int lo = 0, hi = -1;
    };
    int lookup(int layer, double x, double y, std::size_t budget, std::size_t& used, LayerRange& clear);
    static constexpr int kBlockRows = 64;
    static constexpr int kBlockWords = 4;  // a Columns block's width, in 64-cell words

private:
    struct Block {
        std::uint64_t built = 0;          // which of its 64 layers are filled
        std::vector<std::uint64_t> bits;  // per cell (row-major): maybe, surely; bit = layer % 64
    };
    struct Rasters {
        std::vector<std::uint64_t> maybe, surely;  // row-major, words_per_row() words a row
    };
    // Rows j0..j1 (at most kBlockRows), words w0..w1 - 1 of each, of the
    // layer's raster grown by the maybe_ and the sure_ offsets, into maybe
    // and surely (w1 - w0 words a row, zeroed here).
    void grow_rows(int layer, int j0, int j1, std::size_t w0, std::size_t w1, std::uint64_t* maybe,
                   std::uint64_t* surely) const;
    // Fills layers first.. first + kGroup - 1 (those that exist) of a Columns block.
    static constexpr int kGroup = 8;
    void build_group(Block& b, int first, int band, int tile);
    int lookup_columns(int layer, int i, int j, std::size_t budget, std::size_t& used, LayerRange* clear);
    int lookup_per_layer(int layer, int i, int j, std::size_t budget, std::size_t& used);

    const layers::BitGrid* model_;  // the vector's elements: they stay put when it moves
    int layers_;
    double r_;
    Layout layout_;
    bool usable_ = false;
    int nx_ = 0, ny_ = 0, wpr_ = 0, bands_ = 0, tiles_ = 0;  // tiles_: Columns blocks across a row
    // Per row offset d: a set cell d rows and at most maybe_[d] columns away
    // may have its centre within r of a point of the cell (when there is
    // none, every disc centred in the cell misses); one at most sure_[d]
    // columns away has it within r of every point (every such disc meets).
    std::vector<int> maybe_, sure_;
    std::vector<Block> blocks_;    // Columns: by ((layer / 64) * bands_ + row / kBlockRows) * tiles_ + word / kBlockWords
    std::vector<Rasters> rasters_;  // PerLayer: by layer
    std::vector<std::uint64_t> scratch_;
    // The last point asked and its cell (none yet: NaN equals nothing).
    double last_x_ = std::numeric_limits<double>::quiet_NaN(), last_y_ = last_x_;
    int last_i_ = 0, last_j_ = 0;
};

// How far support keeps from a skirt or brim line, edge to edge: off its
// bead, not the model's gap (a column's first loops squeezed between a
// skirt and the model were capped to 0.66 mm where its rule wanted 1.03:
// the longest lever, an elephant's column 1.93 N/mm where 2.5 was planned).
inline constexpr double kSkirtGap = 0.1;

// The grid every obstacle raster of the stack lies on (the print, and a
// margin past it so pillars beside it can be tested too).
layers::BitGrid obstacle_grid(const layers::LayerStack& stack, const Settings& settings);

class Obstacles {
public:
    // `threads`: rasterise the layers on that many threads (the result is the
    // same). Layers above `solid_above` (mm) are taken as solid, not drawn:
    // for a plan known to stay below it (a plate of copies, whose points are
    // found before its obstacles), anything asked there is refused.
    Obstacles(const layers::LayerStack& stack, const Settings& settings, int threads = 1,
              double solid_above = std::numeric_limits<double>::infinity());
    // Caches of its own over the same model rasters, not copied: for another
    // thread (the caches fill as they are asked and are no thread's to
    // share; the rasters, a plate's largest part, never change).
    std::unique_ptr<const Obstacles> another() const;

    int layer_count() const { return static_cast<int>(z_.size()); }
    double layer_z(int layer) const { return z_[layer]; }
    double layer_height(int layer) const { return h_[layer]; }
    // True when no model cell on `layer` lies within r of (x, y).
    bool disc_clear(int layer, double x, double y, double r) const;
    // The same, but of a skirt or brim line only the disc's radius less the
    // model gap (`settings.xy_gap`) plus kSkirtGap must keep clear: how wide
    // a column found its way down may grow beside such a line (its way is
    // found with the whole gap: a column squeezed between the model and a
    // skirt 3 mm off it has less room than one outside the skirt).
    bool room_clear(int layer, double x, double y, double r) const;
    // The same by the exact test alone, without the lookups (which must
    // give the same answers): for tests.
    bool disc_clear_exact(int layer, double x, double y, double r) const;
    // True when the disc is clear on every layer whose top z is in (z_lo, z_hi].
    bool column_clear(double x, double y, double r, double z_lo, double z_hi) const;
    // Nearest layer below `layer` (by the stack's `below` chain) whose model
    // touches the disc, or -1 when the column reaches the bed.
    int model_below(int layer, double x, double y, double r) const;
    // True when the segment (thick by r) is clear of the model on `layer`.
    bool segment_clear(int layer, double x0, double y0, double x1, double y1, double r) const;
    // The same for r = inflate (fixed per Obstacles), by cell lookups in the
    // model grown by that radius (built on first use per layer): cheap enough
    // to test every bridge candidate.
    bool line_clear(int layer, double x0, double y0, double x1, double y1) const;
    double inflate = 0;
    // The model's filled footprint on `layer` (holes enclosed by its
    // material filled; a skirt loop drawn but not filled).
    const layers::BitGrid& footprint(int layer) const { return model_[layer]; }

private:
    // disc_clear's fast path for a radius asked often (a pillar's body is
    // tested at one radius on every layer it passes): a DiscLookup of that
    // radius answers most queries with one bit; the rest take the exact test.
    struct Fast {
        long long asked = 0;
        std::vector<bool> layers;            // which layers were asked, until the lookup is built
        int distinct_layers = 0;
        std::unique_ptr<DiscLookup> lookup;  // built after kFastAfter queries
    };
    static constexpr int kColumnsFrom = 16;  // layers asked (of the first kFastAfter queries) for the Columns layout
    static constexpr long long kFastAfter = 4000;  // queries of one radius before its lookup is built
    static constexpr std::size_t kFastBudget = std::size_t{64} << 20;  // bytes for all lookups
    int fast_disc(int layer, double x, double y, double r) const;  // 1 clear, 0 blocked, -1 unknown

    // Per layer, one bit per 8 x 8 cells: whether any of them is set (built
    // on first use). A disc whose bounding box meets no set block misses the
    // model without the exact test: the pillar searches ask tapered radii
    // that never get a lookup, mostly away from the model.
    bool surely_clear(int layer, double x, double y, double r) const;
    mutable std::vector<std::vector<std::uint64_t>> coarse_;
    int coarse_h_ = 0, coarse_wpr_ = 0;

    struct Shared {};
    Obstacles(const Obstacles& other, Shared);

    // Layers with a skirt or brim line: support keeps only kSkirtGap from
    // it (it is not the model: it only must not be printed over), so there
    // a disc is tested against the model without it at its radius and
    // against it at `skirt_relief_` less.
    struct SkirtLayer {
        layers::BitGrid bare, skirt;
    };
    bool skirt_disc_clear(int layer, double x, double y, double r) const;
    static std::shared_ptr<const std::vector<layers::BitGrid>> model_rasters(
        const layers::LayerStack& stack, const Settings& settings,
        std::shared_ptr<const std::vector<SkirtLayer>>& skirts, std::vector<int>& skirt_at, int threads,
        double solid_above);
    std::shared_ptr<const std::vector<SkirtLayer>> shared_skirts_;
    std::vector<int> skirt_at_;  // per layer: index into *shared_skirts_, or -1
    double skirt_relief_ = 0;

    std::vector<double> z_, h_;
    std::vector<int> below_;
    std::shared_ptr<const std::vector<layers::BitGrid>> shared_model_;
    const std::vector<layers::BitGrid>& model_;  // *shared_model_: per layer, same index as the LayerStack
    mutable std::vector<layers::BitGrid> grown_;  // model_ dilated by `inflate`, lazily
    mutable std::unordered_map<double, Fast> fast_;  // by radius (a taper asks a new one every layer)
    mutable Fast* last_fast_ = nullptr;     // the last radius asked (map nodes stay put)
    mutable double last_r_ = 0;
    struct RecentFast {
        double r = 0;
        Fast* fast = nullptr;
    };
    mutable std::array<RecentFast, 64> recent_fast_{};  // by the radius' bits, hashed
    mutable std::size_t fast_bytes_ = 0;
    // Queries per radius before it has an entry in fast_, counted by its
    // bits' hash (colliding radii share a counter): a lean-in or a taper asks
    // thousands of radii a few times each, and an entry for each (a map node
    // and a bit per layer) was a tenth of a plan's time (the space shuttle).
    // A radius gets its entry once its counter reaches kTrackAfter.
    static constexpr std::uint16_t kTrackAfter = 256;
    mutable std::vector<std::uint16_t> untracked_;
    mutable std::vector<DiscLookup*> columns_;  // the Columns lookups of fast_, by radius
    // Layers lo..hi on which a disc of radius up to r at (x, y) surely
    // misses the model: a column walked down asks them one by one.
    struct ClearRun {
        double x = 0, y = 0, r = -1;
        DiscLookup::LayerRange layers;
    };
    mutable ClearRun run_;
    static constexpr std::size_t kMaxColumns = 6;
};

}  // namespace scaffold::plan
