#pragma once
// Overhang detection: cells of a layer farther than h*tan(angle) from the
// filled material of the layer below, less slicer-marked bridges held at both
// ends; then down-sampled to support points that cover every overhang cell.
#include <vector>

#include "gcode/settings.hpp"
#include "layers/layer_stack.hpp"
#include "layers/raster.hpp"
#include "layers/regions.hpp"

namespace scaffold::overhang {

struct OverhangLayer {
    int layer = 0;              // index into LayerStack::layers
    layers::BitGrid cells;      // overhang cells of that layer
    double area_mm2 = 0;
};

struct Overhangs {
    std::vector<OverhangLayer> layers;  // only layers that have an overhang, by index
    double area_mm2 = 0;
};

struct SupportPoint {
    double x = 0, y = 0;
    double z = 0;      // bottom of the overhanging layer (layer z - height)
    int layer = 0;     // index of the overhanging layer
};

struct SupportPoints {
    std::vector<SupportPoint> points;  // sorted by (layer, y, x): deterministic
    double overhang_area_mm2 = 0;
};

Overhangs find_overhangs(const layers::LayerStack& stack, const Settings& settings);

// Overhang regions (in layer order) as Overhangs on grids shaped like
// `proto`, less the specks (layers::kept_regions at --min-overhang-area):
// find_overhangs' last step, and what the planner's coverage check leaves.
Overhangs overhangs_of(const std::vector<layers::Region>& found, const layers::BitGrid& proto, const Settings& settings);

using layers::Cell;
using layers::components;

// The centre-line samples a segment (dx, dy) gets after its first, at most
// `step` mm apart: ceil(hypot(dx, dy) / step), at least 1. Computed the
// fast way where that cannot round differently; inv_step is 1 / step.
int sample_count(double dx, double dy, double step, double inv_step);
SupportPoints place_points(const Overhangs& overhangs, const layers::LayerStack& stack,
                           const Settings& settings);

}  // namespace scaffold::overhang
