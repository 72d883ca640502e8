#pragma once
// Vertical pillars: one per support point, straight down to the bed or to
// the model's top surface, kept clear of the model by the XY gap on every
// layer (moved a little when the straight column would touch the model).
#include <optional>

#include "layers/layer_stack.hpp"
#include "overhang/overhangs.hpp"
#include "plan/obstacles.hpp"
#include "plan/scaffold.hpp"

namespace scaffold::plan {

// A pillar whose top layer is the one beneath `overhang_layer` (less
// --top-gap-layers), near (x, y). nullopt when no clear column exists (or
// it would stand on the model with --buildplate-only).
std::optional<Column> drop_pillar(double x, double y, int overhang_layer, Top top,
                                  const layers::LayerStack& stack, const Obstacles& obstacles,
                                  const Settings& settings);

// --method pillars: a pillar under every support point.
Scaffold plan_pillars(const overhang::SupportPoints& points, const layers::LayerStack& stack,
                      const Obstacles& obstacles, const Settings& settings);

// Radius of a column at height z (tip taper, foot flare, base radius).
double column_radius_at(const Column& c, double z, const Settings& settings);

}  // namespace scaffold::plan
