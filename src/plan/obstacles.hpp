#pragma once
// What the planner must keep clear of: the model, per layer, as rasters.
// Answers "is a disc free of the model (plus the gap) on layer L" and "where
// is the model top under a column", so pillars and bridges never hit it.
#include <cstdint>
#include <map>
#include <vector>

#include "gcode/settings.hpp"
#include "layers/layer_stack.hpp"
#include "layers/raster.hpp"

namespace scaffold::plan {

class Obstacles {
public:
    Obstacles(const layers::LayerStack& stack, const Settings& settings);

    int layer_count() const { return static_cast<int>(z_.size()); }
    double layer_z(int layer) const { return z_[layer]; }
    double layer_height(int layer) const { return h_[layer]; }
    // True when no model cell on `layer` lies within r of (x, y).
    bool disc_clear(int layer, double x, double y, double r) const;
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

private:
    // disc_clear's fast path for a radius asked often (a pillar's body is
    // tested at one radius on every layer it passes): per layer, the model
    // grown by r less and by r plus half a cell's diagonal answer most
    // queries exactly with one lookup; the rest take the exact test.
    struct Grown {
        long long asked = 0;
        std::vector<layers::BitGrid> surely_blocked, maybe_blocked;  // per layer, lazily
    };
    static constexpr long long kFastAfter = 4000;  // queries of one radius before its rasters are built
    static constexpr std::size_t kFastBudget = std::size_t{64} << 20;  // bytes for all of them
    int fast_disc(int layer, double x, double y, double r) const;  // 1 clear, 0 blocked, -1 unknown

    std::vector<double> z_, h_;
    std::vector<int> below_;
    std::vector<layers::BitGrid> model_;  // per layer, same index as the LayerStack
    mutable std::vector<layers::BitGrid> grown_;  // model_ dilated by `inflate`, lazily
    mutable std::map<std::int64_t, Grown> fast_;   // by radius in micrometres
    mutable Grown* last_fast_ = nullptr;            // the last radius asked (map nodes stay put)
    mutable std::int64_t last_key_ = 0;
    mutable std::size_t fast_bytes_ = 0;
};

}  // namespace scaffold::plan
