#pragma once
// The planner's bars judged by METHOD's rule (b) on the paths as built: each
// bar line must be held by the beads beneath it (the model, and support up
// to three layers down) at both ends, within the bridge limit, leaving each
// held end across the edge of the footprint (layers::run_crosses), or be a
// dangling end of at most 1 mm. A bar passing beside a column it does not
// rest on (along the column's edge, within reach) fails: the pipeline plans
// again without it. The walk is the validator's own (layers/crossing), on the
// line's coordinates as written, so what passes here passes there.
#include <cstddef>
#include <map>
#include <vector>

#include "gcode/settings.hpp"
#include "layers/layer_stack.hpp"
#include "plan/scaffold.hpp"
#include "toolpath/support_paths.hpp"

namespace scaffold::toolpath {

// Whether the straight support bead a -> b printed on `layer` is held, by
// the same walk, over the model beneath and the support in `printed` (the
// layers printed so far, in any order: those within three nominal layers
// under it count).
bool segment_held(const Point& a, const Point& b, int layer, const std::vector<LayerPaths>& printed,
                  const layers::LayerStack& stack, const Settings& settings);

// A bar some line of which is not held: its index into scaffold.bridges,
// and where that line meets what fails it: the footprint cell nearest the
// middle of its first stretch left unheld (a column it passes beside), or
// that stretch's middle when no footprint is near.
struct UnheldBar {
    std::size_t bar = 0;
    double x = 0, y = 0;
    friend bool operator==(const UnheldBar&, const UnheldBar&) = default;
};

// Answers of unheld_bars kept for the next plans made on the same layers
// and settings: a line on a layer is judged again only where it or the
// support beads near it (within the walk's grid) changed. The plans made
// again differ in a few bars, so most lines are asked again unchanged
// (figure.cura413: 14 plans, 25 ms of bar checks each).
struct BarCheckCache {
    struct Answer {
        bool held = false;
        Point at;
    };
    // Key: the layer, the line's ends, then the nearby support beads (x0,
    // y0, x1, y1, width each), sorted: the grids drawn do not depend on
    // the order, so neither does the answer.
    std::map<std::vector<double>, Answer> answers;
};

// The bars some line of which is not held, in the order of scaffold.bridges.
// `cache` (optional): kept by the caller over plans on the same layers.
std::vector<UnheldBar> unheld_bars(const plan::Scaffold& scaffold, const SupportPaths& paths,
                                   const layers::LayerStack& stack, const Settings& settings,
                                   BarCheckCache* cache = nullptr);

}  // namespace scaffold::toolpath
