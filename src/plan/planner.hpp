#pragma once
// The bridge scaffolding of Dumas, Hergel and Lefebvre (2014), as in Tupek's
// report: horizontal bridges carry several support points through slanted
// connectors, so only the bridge ends and the points left over need pillars.
// Hands on a Scaffold (bridges, connectors, pillars) in plain geometry.
#include <functional>
#include <memory>
#include <optional>
#include <vector>

#include "layers/layer_stack.hpp"
#include "overhang/overhangs.hpp"
#include "plan/candidates.hpp"
#include "plan/cavities.hpp"
#include "plan/obstacles.hpp"
#include "plan/scaffold.hpp"

namespace scaffold::plan {

// The model as the planner sees it, answered by the real obstacle rasters.
// The view refers to `obstacles`, which must outlive it.
ModelView model_view(const Obstacles& obstacles);

// The best bridge for these active points (ids = positions in `active`), or
// nullopt when none has positive gain: the first step of the greedy loop.
std::optional<Candidate> best_bridge(const std::vector<Active>& active, const ModelView& model,
                                     const Settings& settings);

// --method scaffold, as pure geometry (METHOD.md step 4): greedy bridges,
// slanted connectors from each bridge to the points it carries, and a
// vertical pillar under every point left (down to the bed, or to the model's
// top where the model is below it). Input order does not matter.
Scaffold plan_scaffold(const overhang::SupportPoints& points, const Obstacles& obstacles, const Settings& settings);
// `threads`: as BridgeSearch's (0: the machine's); the plan does not depend on it.
Scaffold plan_scaffold(const overhang::SupportPoints& points, const ModelView& model, const Settings& settings,
                       int threads = 0);

// Bars whose lines a plan before this one failed to hold (toolpath::
// unheld_bars) are not taken again, nor bars next to them (ends within
// kForbiddenNear, a layer or so apart), nor bars along the same line (its
// ends within kForbiddenBeside of it, within kForbiddenAngleDeg, over half
// the shorter's length), which would fail the same way: a bull's belly bar
// at z 6.6 came back six rounds running with its ends 1.2-4.4 mm apart.
// Nor is a bar that passes within kPlaceNear of a place a bar failed
// beside, within kPlaceLayers layers of that bar: on the bunny the plans
// made again took one neighbour after another past the same column, 0.3
// mm and 0.2-0.4 mm apart (x4 plate: ten plans, one with the places).
inline constexpr double kForbiddenNear = 1.0;
inline constexpr double kForbiddenBeside = 0.5;
inline constexpr double kForbiddenAngleDeg = 5.0;
inline constexpr double kPlaceNear = 1.0;
inline constexpr double kPlaceLayers = 3.0;
bool near_forbidden(const Forbidden& forbidden, const Bridge& bar, double layer_height);
// The same answer, with the forbidden sorted by height: asked of every
// candidate bar, it looks only at those within their windows of its height.
class ForbiddenLookup {
public:
    ForbiddenLookup(const Forbidden& forbidden, double layer_height);
    bool operator()(const Bridge& bar) const;
    // False when no bar at height z lying within the box is near a forbidden
    // bar or place (operator() false for all of them); true may be either.
    bool any_near(double z, double x_lo, double y_lo, double x_hi, double y_hi) const;

private:
    // Whether `place` holds for a forbidden place or `bar` for a forbidden
    // bar within their windows of height z (the others cannot be near).
    template <class Place, class Bar>
    bool any_in_windows(double z, Place place, Bar bar) const;
    std::vector<Bridge> bars_;
    std::vector<Xyz> places_;
    double h_ = 0;
};

// A plan's bridge search kept as it went, so a plan made again of the same
// points without some more bars (the pipeline's rounds) resumes from the
// last step before the two can first differ instead of starting over. The
// greedy search takes the same steps until it is first offered a bar now
// forbidden (the forbidden are turned down as they are offered), so the plan
// is the one a search from the start makes. Kept every few offers.
struct BridgeReplay {
    BridgeReplay();
    ~BridgeReplay();
    struct Log;
    std::unique_ptr<Log> log;
    long long offers_replayed = 0;  // offers not made again, over all plans (for the log)
};

// The pipeline's: the same bridges, but every pillar (under points and
// bridge ends) is dropped by drop_pillar, which steps around the model, and
// a bridge is placed only where both its ends get one. Plans made again on
// the same stack, obstacles and settings may share `answers`, and the
// model's hollows (`cavities`; empty: mapped here when the first bar is taken).
// `helpers`: obstacles over the same model with caches of their own
// (Obstacles::another), one per extra thread of the bridge search; the plan
// does not depend on them.
Scaffold plan_scaffold(const overhang::SupportPoints& points, const layers::LayerStack& stack,
                       const Obstacles& obstacles, const Settings& settings,
                       const Forbidden& forbidden = {}, std::shared_ptr<ModelAnswers> answers = nullptr,
                       const std::function<const Cavities&()>& cavities = nullptr, BridgeReplay* replay = nullptr,
                       const std::vector<const Obstacles*>& helpers = {});

}  // namespace scaffold::plan
