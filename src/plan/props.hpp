#pragma once
// Props under bars that pass beside a column. METHOD's rule (b) holds a
// bar's bead where it crosses a gap between what is beneath; a bar that runs
// along the edge of a column it does not rest on (a connector leaning up to
// a point, a pillar of another bar) is held by neither (59 of the 81 bars
// the pipeline had to plan again without, on connectors). Such a column
// gets a short prop: a slanted column standing on it a few layers below the
// bar, leaning out as far as a loop may shift per layer, whose top loop lies
// under the bar's line. The bar then crosses the prop and rests on it.
#include <vector>

#include "gcode/settings.hpp"
#include "layers/layer_stack.hpp"
#include "plan/obstacles.hpp"
#include "plan/scaffold.hpp"

namespace scaffold::plan {

// A column passes beside a bar when its centre at the bar's height lies
// within this of the bar's line beyond the column's radius.
inline constexpr double kBesideBar = 2.0;

// Where column `col` passes beside bar `bar`: the centre-line distance at
// the bar's height, or a negative value when it does not (the column is the
// bar's own support, does not reach the bar's height, or already lies
// under the bar's line).
double passes_beside(const Column& col, const Bridge& bar, const Settings& settings);

// The prop up under `bar` from the column `chain` (the piece that passes
// beside the bar first, then the pieces it is stacked on, downwards), or
// none where it would come within the gap of the model or find no loop of
// the column to stand on.
std::vector<Column> prop_under(const std::vector<const Column*>& chain, const Bridge& bar, const layers::LayerStack& stack,
                               const Obstacles& obstacles, const Settings& settings);

// Props every column that passes beside one of the scaffold's bars
// `bars` (indices, ascending), appended to its columns in the order of the
// bars, then of the columns; none that would pass beside another bar.
// Returns how many were added.
int prop_bars(Scaffold& scaffold, const std::vector<std::size_t>& bars, const layers::LayerStack& stack,
              const Obstacles& obstacles, const Settings& settings);

}  // namespace scaffold::plan
