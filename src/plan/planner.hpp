#pragma once
// The bridge scaffolding of Dumas, Hergel and Lefebvre (2014), as in Tupek's
// report: horizontal bridges carry several support points through slanted
// connectors, so only the bridge ends and the points left over need pillars.
#include <vector>

#include "layers/layer_stack.hpp"
#include "overhang/overhangs.hpp"
#include "plan/obstacles.hpp"
#include "plan/scaffold.hpp"

namespace scaffold::plan {

// A point the planner still has to hold: a support point, or the end of a
// bridge already placed (which a lower bridge or a pillar must carry).
struct Active {
    double x = 0, y = 0, z = 0;  // z: where its support must reach up to
    int point = -1;              // support point index, or -1 for a bridge end
};

// Scoring of the method (METHOD.md step 4), exposed for tests.
double bridge_gain(int supported, double z, double length);
double bridge_score(double gain, int supported, double l_max);

// One candidate bridge at height z between (x0,y0) and (x1,y1) and the
// active points it would carry.
struct Candidate {
    double x0 = 0, y0 = 0, x1 = 0, y1 = 0, z = 0;
    std::vector<int> carried;  // indices into the active list
    double gain = 0, score = 0, l_max = 0;
};

// The best-scoring candidate over all sweep directions, or one with
// carried.empty() when no bridge has positive gain. `clear` filters bridges
// and connectors against the model (nullptr: no model).
Candidate best_bridge(const std::vector<Active>& active, const std::vector<double>& layer_tops,
                      const Settings& settings);

// --method scaffold.
Scaffold plan_scaffold(const overhang::SupportPoints& points, const layers::LayerStack& stack,
                       const Obstacles& obstacles, const Settings& settings);

}  // namespace scaffold::plan
