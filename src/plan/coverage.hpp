#pragma once
// METHOD.md's rule (c) applied to a plan, as the validator applies it: a
// tip holds the cells within the point radius of where it lies under the
// overhanging layer's own material. A tip the planner had to set off its
// point (a slot, a wall) may leave the far side of the point's share of the
// sheet unheld; these are found here and get points and pillars of their own.
#include <vector>

#include "layers/layer_stack.hpp"
#include "overhang/overhangs.hpp"
#include "plan/obstacles.hpp"
#include "plan/scaffold.hpp"

namespace scaffold::plan {

// The overhang cells no tip of the plan holds, less the specks the detector
// leaves out (layers::kept_regions at --min-overhang-area).
overhang::Overhangs unheld_by_tips(const overhang::Overhangs& overhangs, const Scaffold& scaffold,
                                   const layers::LayerStack& stack, const Obstacles& obstacles,
                                   const Settings& settings);

// Up to `rounds` times: points on what the plan's tips leave unheld, each
// with a pillar (add_pillars, lean_in.hpp); points no pillar reaches are taken out again
// (the ones of the first plan stay, dropped), and a round that adds no
// pillar ends it. Returns the number of points added; the last round's
// points no pillar reaches are left in scaffold.uncovered (said to the user).
std::size_t cover_unheld(Scaffold& scaffold, overhang::SupportPoints& points, const overhang::Overhangs& overhangs,
                         const layers::LayerStack& stack, const Obstacles& obstacles, const Settings& settings,
                         double steer, int rounds);

}  // namespace scaffold::plan
