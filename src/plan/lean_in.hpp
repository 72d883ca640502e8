#pragma once
// The last resort for a point no pillar reaches from below (an ear over a
// sloping shoulder, a lip over a narrow slot): a thin column leaning in to
// it from a pillar that stands up to a layer lower beside the obstacle, as
// far as a loop may shift on the one below per layer.
#include <cmath>
#include <map>
#include <mutex>
#include <optional>
#include <tuple>
#include <vector>

#include "layers/layer_stack.hpp"
#include "overhang/overhangs.hpp"
#include "plan/obstacles.hpp"
#include "plan/pillars.hpp"
#include "plan/scaffold.hpp"

namespace scaffold::plan {

// Columns bottom up, the last the leaning one whose tip is at (x, y) under
// `overhang_layer` (less --top-gap-layers); nullopt when none is found
// within kLeanInReach mm. With --buildplate-only the pillar stands on the bed.
std::optional<std::vector<Column>> lean_in(double x, double y, int overhang_layer, const layers::LayerStack& stack,
                                           const Obstacles& obstacles, const Settings& settings,
                                           const Trunks* trunks = nullptr);

// Lean-ins on their own pillars (no trunks), by the point's place and
// layer: they depend on the model alone, and the pipeline plans the same
// model again (without bars not held as built) up to 11 times.
class LeanInAnswers {
public:
    using Chain = std::optional<std::vector<Column>>;
    std::optional<Chain> find(double x, double y, int layer) const;
    void insert(double x, double y, int layer, const Chain& chain);

private:
    using Key = std::tuple<long long, long long, int>;
    mutable std::mutex mutex_;
    std::map<Key, Chain> map_;
};

// The scaffold's support of a point that no bridge carries: a pillar whose
// tip lies under the sheet (drop_pillar), else one leaning in (lean_in),
// else (with `beside`) a pillar whose tip stands beside the sheet within
// reach. METHOD's Standing rule: a pillar short of it is compared with a
// lean-in on a pillar of its own (`known` keeps those), and the stiffer
// taken.
std::optional<std::vector<Column>> support_point(double x, double y, int overhang_layer,
                                                 const layers::LayerStack& stack, const Obstacles& obstacles,
                                                 const Settings& settings, const Trunks* trunks, bool beside = true,
                                                 LeanInAnswers* known = nullptr);

// support_point under each of points.points[which], in that order, added to
// the plan with the point's index; each stands on the plan's columns where
// it meets them (branching within `steer` mm; 0: straight down only).
// Points that get none are added to dropped_points (sorted).
void add_pillars(Scaffold& scaffold, const overhang::SupportPoints& points, const std::vector<int>& which,
                 const layers::LayerStack& stack, const Obstacles& obstacles, const Settings& settings, double steer,
                 bool beside = true);

// Farthest a leaning column comes from (mm, horizontally).
inline constexpr double kLeanInReach = 8.0;
// Pillars tried under leaning columns for one point, at most (the corpora's
// and the wild files' hardest point took 62).
inline constexpr int kLeanInPillars = 256;
// Lean-ins tried after the first found that falls short of the Standing
// rule, for one that stands (else the stiffest is taken).
inline constexpr int kWeakLeanTries = 24;

}  // namespace scaffold::plan
