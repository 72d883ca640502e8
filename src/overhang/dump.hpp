#pragma once
// Looking at what detection found: the support points as JSON, and one SVG
// per layer with an overhang (layer below, the layer, overhang cells, points).
#include <string>

#include "overhang/overhangs.hpp"

namespace scaffold::overhang {

// {"points":[{"x":..,"y":..,"z":..,"layer":..}],"overhang_area_mm2":..}
void write_points_json(const std::string& path, const SupportPoints& points);
// DIR/layer-NNNN.svg for every layer with an overhang; creates DIR.
void write_layer_svgs(const std::string& dir, const Overhangs& overhangs, const SupportPoints& points,
                      const layers::LayerStack& stack, const Settings& settings);

}  // namespace scaffold::overhang
