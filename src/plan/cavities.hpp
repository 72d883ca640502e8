#pragma once
// Where support would be trapped inside the model: a bridge bar in a
// hollow that the model walls in above it and roofs over (a boat's cabin,
// a box with windows and a door) could only be broken out through the
// openings. Answered on a coarse grid: per layer, whether a cell holds
// material or lies wholly in a hole the layer's material encloses; per cell,
// the highest material over it.
#include <atomic>
#include <cstdint>
#include <vector>

#include "gcode/settings.hpp"
#include "layers/layer_stack.hpp"
#include "plan/obstacles.hpp"

namespace scaffold::plan {

class Cavities {
public:
    // On the obstacles' grid (obstacle_grid, or `obstacles`' own), the
    // layers mapped on `threads` threads (the same map). Mapping stops
    // early, leaving a map not to be asked, once `cancel` is set.
    Cavities(const layers::LayerStack& stack, const layers::BitGrid& grid, int threads = 1,
             const std::atomic<bool>* cancel = nullptr);
    Cavities(const layers::LayerStack& stack, const Obstacles& obstacles, int threads = 1)
        : Cavities(stack, obstacles.footprint(0), threads) {}

    // Whether (x, y) at height z lies under model material higher up and,
    // going up from z through air, meets a layer that walls it in within
    // `reach` mm, before any material (a roof or a lip met first leaves the
    // way out sideways open; the infill holes of a part over it lie behind
    // its skin).
    bool trapped(double x, double y, double z, double reach) const;
    // Whether the bar from (x0, y0) to (x1, y1) at height z, ends included,
    // crosses such a hollow.
    bool bar_trapped(double x0, double y0, double x1, double y1, double z) const;

    static constexpr double kCell = 1.0;      // mm, of the coarse grid (whole fine cells)
    static constexpr double kReach = 10.0;    // mm above the bar walls may close the hollow

private:
    enum State : std::uint8_t { Air = 0, Material = 1, Hole = 2 };
    State state(std::size_t layer, int cell) const {
        const std::size_t bit = (layer * nx_ * ny_ + static_cast<std::size_t>(cell)) * 2;
        return static_cast<State>((states_[bit >> 6] >> (bit & 63)) & 3u);
    }
    int index(double x, double y) const;  // -1 outside
    double x0_ = 0, y0_ = 0, cell_ = kCell;
    std::size_t nx_ = 0, ny_ = 0;
    std::vector<double> z_;               // the layers asked about, by rising z
    std::vector<std::uint64_t> states_;   // 2 bits a cell, nx_ * ny_ cells a layer, in z_'s order
    std::vector<float> top_;              // per cell: highest model layer top over it, 0 if none
};

}  // namespace scaffold::plan
