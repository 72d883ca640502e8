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

// The bars some line of which is not held, in the order of scaffold.bridges.
std::vector<UnheldBar> unheld_bars(const plan::Scaffold& scaffold, const SupportPaths& paths,
                                   const layers::LayerStack& stack, const Settings& settings);

}  // namespace scaffold::toolpath
