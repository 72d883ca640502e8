#pragma once
// Where support would be trapped inside the model: a bridge bar across a
// hollow that the model walls in on the layers around the bar and roofs
// over (a boat's cabin, a box with windows) could only be broken out
// through its openings. Answered on a coarse grid of the model's enclosed
// holes by height band and its highest material, built from the layers on
// first use.
#include <cstdint>
#include <vector>

#include "gcode/settings.hpp"
#include "layers/layer_stack.hpp"

namespace scaffold::plan {

class Cavities {
public:
    Cavities(const layers::LayerStack& stack, const Settings& settings);

    // Whether the point lies in a hole the model encloses on a layer within
    // `reach` mm of z, under model material higher than z.
    bool trapped(double x, double y, double z, double reach) const;
    // Whether the bar from (x0, y0) to (x1, y1) at height z crosses such a
    // hollow away from its ends (the ends stand where pillars do).
    bool bar_trapped(double x0, double y0, double x1, double y1, double z) const;

    static constexpr double kCell = 1.0;       // mm, of the coarse grid (whole fine cells)
    static constexpr double kBand = 2.5;       // mm of height a bit of a cell's mask stands for
    static constexpr double kReach = 5.0;      // mm: walls this near the bar's height wall it in
    static constexpr double kEndClear = 2.0;   // mm of a bar at each end not asked about

private:
    int index(double x, double y) const;  // -1 outside
    double x0_ = 0, y0_ = 0, cell_ = kCell;
    int nx_ = 0, ny_ = 0;
    std::vector<std::uint64_t> enclosed_;  // per cell: bit b = enclosed on a layer in band b (z / kBand, capped)
    std::vector<float> top_;               // per cell: highest model layer top over it, 0 if none
};

}  // namespace scaffold::plan
