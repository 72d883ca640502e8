#include "cli/plate.hpp"

#include <algorithm>
#include <array>
#include <cmath>

#include "plan/coverage.hpp"
#include "plan/groups.hpp"
#include "plan/pillars.hpp"
#include "plan/props.hpp"

namespace scaffold::cli {

namespace {

// Rounds of points for what tips set off their points leave unheld.
constexpr int kCoverRounds = 3;
// Plans made again without the bars on braced columns (plan_group).
constexpr int kUnbracedAttempts = 2;
// mm: the first copy of a plate of copies is planned seeing this far around
// its box, and its plan must keep kCopyReach (more than any column's foot
// is wide) inside that. Its bars stand within a bar's offset (5 mm) of its
// points, braces' helper pillars within 12 mm of their columns.
constexpr double kCopyWindow = 25.0;
constexpr double kCopyReach = 10.0;
// Copies whose supports stand at least this far apart (mm, beads' widths
// included) print the first copy's paths moved: no loop, raft, bond or spur
// of one reaches another's.
constexpr double kCopiesApart = 1.0;
// mm over a plate of copies' highest point from which the plate as its
// first copy sees it is taken as solid, not drawn.
constexpr double kSolidAbove = 2.0;
// mm: a point is its object's within this of its footprint.
constexpr double kPointObjectReach = 1.0;
// Points: groups this large (a whole object's) each take a thread at once.
constexpr std::size_t kHeavyGroup = 40;

// Whether a column standing on the model stands on the first copy's beads
// (within its radius and a millimetre of one on the layer it rests on).
bool on_first_copy(const plan::Column& c, const layers::LayerStack& first_copy) {
    for (const layers::Layer& layer : first_copy.layers) {
        if (layer.purge || std::abs(layer.z - c.z0) > layers::kZEps) continue;
        for (const layers::Segment& s : layer.segments)
            if (layers::segment_distance(c.x0, c.y0, s) <= c.radius + s.width / 2 + 1.0) return true;
    }
    return false;
}

double ms_between(Clock::time_point a, Clock::time_point b) { return 1000 * std::chrono::duration<double>(b - a).count(); }

// The indices into the scaffold's bridges of the bars not held.
std::vector<std::size_t> bar_indices(const std::vector<toolpath::UnheldBar>& unheld) {
    std::vector<std::size_t> out;
    for (const toolpath::UnheldBar& u : unheld) out.push_back(u.bar);
    return out;
}

// The rounds ran out with bars the plan could not do without: said, not
// hidden, once the plan is final (a group's may yet be replaced by a joined
// one). The planner's judgement is the stricter (the validator lets 0.5 mm^2
// of unheld bead pass): the output may still pass.
void warn_left(spdlog::logger& log, const GroupPlanned& g, int rounds, const Settings& settings) {
    // Tips' columns with no room to widen and no neighbours to tie to.
    if (!g.weak.empty()) {
        const auto weakest = std::min_element(g.weak.begin(), g.weak.end(),
                                              [](const plan::ShortColumn& a, const plan::ShortColumn& b) { return a.k < b.k; });
        log.warn("{} support columns stand short of --min-stiffness {:g} N/mm as the planner judges them, the weakest "
                 "{:.2f} N/mm at its top at z {:.2f} (no room to widen them, no ties that make them stand): the output "
                 "is written; --check (or scaffold-check) says whether it passes",
                 g.weak.size(), settings.min_stiffness, weakest->k, weakest->z);
    }
    const auto left = g.left;
    const std::size_t points = g.points.points.size();
    if (left.first == 0 && left.second == 0) return;
    log.warn("after {} plans of {} support points, {} bars that carry points are still not held as built and {} stand "
             "on columns short of --min-stiffness {:g} N/mm, as the planner judges them: the output is written; "
             "--check (or scaffold-check) says whether it passes",
             rounds + 1, points, left.first, left.second, settings.min_stiffness);
}

}  // namespace

GroupPlanned plan_group(const overhang::SupportPoints& detected, const overhang::Overhangs& overhangs,
                        const layers::LayerStack& stack, const plan::Obstacles& obstacles, const Settings& settings,
                        SharedCavities& cavities, spdlog::logger& log, int rounds, Progress* progress, int threads,
                        const plan::Forbidden& start, std::shared_ptr<plan::ModelAnswers> known,
                        const plan::GroupPlan* first, plan::BraceAnswers brace_answers,
                        toolpath::BarCheckCache bar_cache) {
    const auto hollows = [&]() -> const plan::Cavities& { return cavities.get(obstacles); };
    // The bridge search's other threads, each asking the model through
    // caches of its own, kept over the rounds as the first thread's are.
    std::vector<std::unique_ptr<const plan::Obstacles>> own;
    std::vector<const plan::Obstacles*> helpers;
    if (settings.method == Method::Scaffold)
        for (int t = 1; t < std::min(threads, plan::kMaxPlanThreads); ++t) {
            own.push_back(obstacles.another());
            helpers.push_back(own.back().get());
        }
    const Clock::time_point t0 = Clock::now();
    // The model's answers, kept for the next round.
    const auto answers = known ? std::move(known) : std::make_shared<plan::ModelAnswers>();
    plan::BridgeReplay replay;  // the bridge search, resumed by the next round where it first differs
    // brace_answers (the helper pillars dropped) and bar_cache (the bar lines
    // judged) are asked again by every round, and returned for a later join.
    // A plan made in rounds, each without the bars the last could not hold.
    struct Attempt {
        overhang::SupportPoints points;
        plan::Scaffold scaffold;
        toolpath::SupportPaths paths;
        bool bars_held = false;
        plan::Forbidden forbidden;          // what its last round was made without
        std::vector<std::size_t> braced;    // its bars whose end stands on a braced column
        std::optional<plan::GroupPlan> unbraced;  // its last round's plan before braces and props
        bool given = false;                 // that plan is `first`, not searched
        // Where the rounds ran out: its bars still not held that carry points,
        // and those on columns short of the rule.
        std::pair<std::size_t, std::size_t> left{0, 0};
        std::vector<plan::ShortColumn> weak;  // its tips' columns short of the rule
    };
    // `given`: the first round's plan before braces (no bridge search).
    auto attempt = [&](plan::Forbidden forbidden, const plan::GroupPlan* given) -> Attempt {
        overhang::SupportPoints points;
        plan::Scaffold scaffold;
        toolpath::SupportPaths paths;
        bool bars_held = false;  // the last plan's bars checked and all held
        std::vector<std::size_t> braced_bars;
        std::optional<plan::GroupPlan> unbraced;
        bool last_given = false;  // the last round's plan is `given`
        std::pair<std::size_t, std::size_t> left{0, 0};
        std::vector<plan::ShortColumn> weak;
        // Should the rounds run out, each plan still keeping a few such bars: the
        // plan with the fewest not held that carry points (brace bars are left
        // out below), then with the fewest on columns short of the rule (those
        // are held: weaker, not broken); the last plan is no better than the others.
        struct Kept {
            std::pair<std::size_t, std::size_t> bad{SIZE_MAX, SIZE_MAX};
            overhang::SupportPoints points;
            plan::Scaffold scaffold;
            toolpath::SupportPaths paths;
            std::vector<plan::ShortColumn> weak;
        } kept;
        for (int round = 0;; ++round) {
            if (progress && round == 0) progress->say("planning {} support points", detected.points.size());
            else if (progress)
                progress->say("planning again without {} bars (plan {} of at most {})", forbidden.bars.size(), round + 1, rounds + 1);
            const Clock::time_point r0 = Clock::now();
            const bool from_given = given && round == 0;
            last_given = from_given;
            if (from_given) {
                points = given->points;
                scaffold = given->scaffold;
            } else {
                points = detected;
                scaffold = settings.method == Method::Pillars
                               ? plan::plan_pillars(points, stack, obstacles, settings)
                               : plan::plan_scaffold(points, stack, obstacles, settings, forbidden, answers, hollows, &replay,
                                                     helpers);
            }
            // A tip set off its point (a slot, a wall) holds less of the sheet than
            // the point stood for (METHOD's rule (c)): what it leaves gets points and
            // pillars of its own, a few rounds at most (a given plan's are in it).
            const Clock::time_point r1 = Clock::now();
            if (!from_given)
                if (std::size_t n = plan::cover_unheld(scaffold, points, overhangs, stack, obstacles, settings,
                                                       settings.method == Method::Pillars ? 0.0 : plan::kBranchSteer,
                                                       kCoverRounds))
                    log.debug("{} more points where a tip set off its point left part of the sheet unheld", n);
            unbraced = plan::GroupPlan{points, scaffold};
            // METHOD's Standing rule: columns too weak for it (no room to widen)
            // tied to two neighbours in triangles.
            const Clock::time_point r2 = Clock::now();
            std::vector<std::size_t> short_of_rule;
            braced_bars.clear();
            weak.clear();
            if (int n = plan::add_braces(scaffold, stack, obstacles, settings, forbidden, &short_of_rule, &brace_answers,
                                         &braced_bars, &weak))
                log.debug("{} bars brace weak columns", n);
            const Clock::time_point r3 = Clock::now();
            paths = toolpath::make_paths(scaffold, stack, settings, &obstacles);
            const Clock::time_point r4 = Clock::now();
            // A bar whose line rule (b) does not hold as built (it passes along
            // the edge of a column it does not rest on), or whose end stands on
            // a column that neither braces nor widening make stiff enough: plan
            // again without it.
            std::vector<toolpath::UnheldBar> unheld_at = toolpath::unheld_bars(scaffold, paths, stack, settings, &bar_cache);
            if (!unheld_at.empty()) {
                // Rule (b): a bar that passes beside a column rests on a prop from
                // it instead, where that holds it and fails no other bar.
                plan::Scaffold propped = scaffold;
                const std::vector<std::size_t> before = bar_indices(unheld_at);
                if (const int n = plan::prop_bars(propped, before, stack, obstacles, settings)) {
                    toolpath::SupportPaths propped_paths = toolpath::make_paths(propped, stack, settings, &obstacles);
                    std::vector<toolpath::UnheldBar> still = toolpath::unheld_bars(propped, propped_paths, stack, settings, &bar_cache);
                    const std::vector<std::size_t> after = bar_indices(still);
                    const bool better = after.size() < before.size() && std::includes(before.begin(), before.end(), after.begin(), after.end());
                    log.debug("{} props under bars beside columns: {} of {} bars held{}", n, before.size() - after.size(),
                              before.size(), better ? "" : ", not kept");
                    for (std::size_t i = scaffold.columns.size(); i < propped.columns.size(); ++i) {
                        const plan::Column& c = propped.columns[i];
                        log.trace("round {}: prop ({:.2f}, {:.2f}, z {:.2f}) -> ({:.2f}, {:.2f}, z {:.2f}), radius {:.2f}", round,
                                  c.x0, c.y0, c.z0, c.x1, c.y1, c.z1, c.radius);
                    }
                    if (better) {
                        scaffold = std::move(propped);
                        paths = std::move(propped_paths);
                        unheld_at = std::move(still);
                    }
                }
            }
            const std::vector<std::size_t> unheld = bar_indices(unheld_at);
            log.debug("plan {}: bars {:.1f} ms, cover {:.1f}, braces {:.1f}, paths {:.1f}, check {:.1f}", round + 1,
                      ms_between(r0, r1), ms_between(r1, r2), ms_between(r2, r3), ms_between(r3, r4), ms_between(r4, Clock::now()));
            if (!short_of_rule.empty()) log.debug("{} bars stand on a column short of --min-stiffness", short_of_rule.size());
            if (log.should_log(spdlog::level::trace))
                for (const std::vector<std::size_t>* list :
                     std::array<const std::vector<std::size_t>*, 2>{&unheld, &short_of_rule})
                    for (std::size_t i : *list) {
                        const plan::Bridge& b = scaffold.bridges[i];
                        log.trace("round {}: bar ({:.2f}, {:.2f}) -> ({:.2f}, {:.2f}) at z {:.2f}{} {}", round, b.x0, b.y0, b.x1,
                                  b.y1, b.z, b.brace ? ", brace" : "",
                                  list == &unheld ? "not held as built" : "on a column short of the rule");
                    }
            std::vector<std::size_t> bad = unheld;
            for (std::size_t i : short_of_rule)
                if (std::find(bad.begin(), bad.end(), i) == bad.end()) bad.push_back(i);
            std::sort(bad.begin(), bad.end());
            bars_held = unheld.empty();
            if (bad.empty()) {
                if (from_given) log.debug("the parts' plans side by side hold: not planned again");
                break;
            }
            if (from_given) log.debug("the parts' plans side by side do not hold: the joined group planned whole");
            const std::pair<std::size_t, std::size_t> carrying{
                static_cast<std::size_t>(
                    std::count_if(unheld.begin(), unheld.end(), [&](std::size_t i) { return !scaffold.bridges[i].brace; })),
                short_of_rule.size()};
            if (carrying < kept.bad) kept = {carrying, points, scaffold, paths, weak};
            if (round == rounds) {
                left = kept.bad;  // the plan kept below, or the last with as many
                if (kept.bad < carrying) {
                    points = std::move(kept.points);
                    scaffold = std::move(kept.scaffold);
                    paths = std::move(kept.paths);
                    weak = std::move(kept.weak);
                    bars_held = false;  // its brace bars not checked here
                    unbraced.reset();
                }
                break;
            }
            for (std::size_t i : bad) forbidden.bars.push_back(scaffold.bridges[i]);
            for (const toolpath::UnheldBar& u : unheld_at) {
                forbidden.places.push_back({u.x, u.y, scaffold.bridges[u.bar].z});
                log.trace("round {}: no bar of the next plans passes ({:.2f}, {:.2f}) near z {:.2f}", round, u.x, u.y,
                          scaffold.bridges[u.bar].z);
                if (!log.should_log(spdlog::level::trace)) continue;
                const double bz = scaffold.bridges[u.bar].z;
                for (const plan::Column& c : scaffold.columns) {
                    if (c.z0 > bz + plan::kBarThickness || c.z1 < bz) continue;
                    double cx, cy;
                    plan::column_centre_at(c, bz, cx, cy);
                    if (std::hypot(cx - u.x, cy - u.y) > 3) continue;
                    log.trace("round {}:   beside column ({:.2f}, {:.2f}, z {:.2f}) -> ({:.2f}, {:.2f}, z {:.2f}), base {}, top {}, "
                              "point {}", round, c.x0, c.y0, c.z0, c.x1, c.y1, c.z1, static_cast<int>(c.base),
                              static_cast<int>(c.top), c.point);
                }
            }
            log.debug("{} bars not held as built or short of the rule: planning again without them ({:.0f} ms so far)",
                      bad.size(), ms_between(t0, Clock::now()));
        }
        return {std::move(points), std::move(scaffold), std::move(paths), bars_held, std::move(forbidden),
                std::move(braced_bars), std::move(unbraced), last_given, left, std::move(weak)};
    };
    // A bar whose end stands on a column too weak for the Standing rule
    // costs its braces too (bars, helper columns), which the bridge search
    // does not count: the plan made again without such bars, kept where it
    // holds every bar and costs less (75-file sweep: 3.1 % less support, a
    // figure 37 %, bunny 4.8 %; a second attempt found more, a third none).
    // (A joined group whose parts' plans hold side by side is not searched
    // again: its parts' plans were each tried so.)
    Attempt best = attempt(start, first);
    plan::Forbidden learned = best.forbidden;
    for (int k = 0; k < kUnbracedAttempts && best.bars_held && !best.braced.empty() && !best.given; ++k) {
        plan::Forbidden without = best.forbidden;
        for (std::size_t i : best.braced) without.bars.push_back(best.scaffold.bridges[i]);
        if (progress) progress->say("planning again without {} bars on braced columns", best.braced.size());
        Attempt other = attempt(std::move(without), nullptr);
        const double was = toolpath::paths_volume(best.paths, stack), now = toolpath::paths_volume(other.paths, stack);
        const bool better = other.bars_held && now < was;
        log.debug("planned without the {} bars on braced columns: support {:.1f} -> {:.1f} mm3{}", best.braced.size(), was,
                  now, better ? ", kept" : ", not kept");
        if (!better) break;
        best = std::move(other);
    }
    overhang::SupportPoints points = std::move(best.points);
    plan::Scaffold scaffold = std::move(best.scaffold);
    toolpath::SupportPaths paths = std::move(best.paths);
    bool bars_held = best.bars_held;
    if (replay.offers_replayed > 0)
        log.debug("plans made again resumed their bridge search: {} offers not made again", replay.offers_replayed);
    if (answers->descents && answers->descents->hits > 0)
        log.debug("pillars' walks down: {} of {} as kept from before", answers->descents->hits,
                  answers->descents->hits + answers->descents->misses);
    if (log.should_log(spdlog::level::trace)) {
        for (std::size_t i = 0; i < points.points.size(); ++i) {
            const overhang::SupportPoint& p = points.points[i];
            log.trace("point {} ({:.2f}, {:.2f}) under the layer at z {:.2f}", i, p.x, p.y, stack.layers[p.layer].z);
        }
        for (const plan::Column& c : scaffold.columns)
            log.trace("column ({:.2f}, {:.2f}, z {:.2f}) -> ({:.2f}, {:.2f}, z {:.2f}), radius {:.2f}, taper {:.4f} below z {:.2f}, "
                      "cap {:.2f}, base {}, point {}",
                      c.x0, c.y0, c.z0, c.x1, c.y1, c.z1, c.radius, c.taper, c.hold_z, c.max_radius,
                      static_cast<int>(c.base), c.point);
        for (const plan::Bridge& b : scaffold.bridges)
            log.trace("bar ({:.2f}, {:.2f}) -> ({:.2f}, {:.2f}) at z {:.2f}{}", b.x0, b.y0, b.x1, b.y1, b.z, b.brace ? ", brace" : "");
    }
    // Brace bars still not held as built after the last plan carry nothing:
    // taken out (a tie less), not left in. (Not asked again when that plan's
    // bars were checked and all held.)
    for (int k = 0; k < 3 && !bars_held; ++k) {
        std::vector<std::size_t> bad = bar_indices(toolpath::unheld_bars(scaffold, paths, stack, settings, &bar_cache));
        if (log.should_log(spdlog::level::trace))
            for (std::size_t i : bad) {
                const plan::Bridge& b = scaffold.bridges[i];
                log.trace("last plan: bar ({:.2f}, {:.2f}) -> ({:.2f}, {:.2f}) at z {:.2f}{} not held as built", b.x0, b.y0,
                          b.x1, b.y1, b.z, b.brace ? ", brace" : "");
            }
        std::erase_if(bad, [&](std::size_t i) { return !scaffold.bridges[i].brace; });
        if (bad.empty()) break;
        for (auto it = bad.rbegin(); it != bad.rend(); ++it) scaffold.bridges.erase(scaffold.bridges.begin() + static_cast<long>(*it));
        log.debug("{} brace bars not held as built: left out", bad.size());
        paths = toolpath::make_paths(scaffold, stack, settings, &obstacles);
    }
    return {std::move(points),         std::move(scaffold),      std::move(paths), std::move(learned), answers,
            std::move(brace_answers), std::move(bar_cache), std::move(best.unbraced), best.left,
            std::move(best.weak)};
}

std::optional<GroupPlanned> plan_copies(const layers::Copies& copies, const layers::LayerStack& first_copy,
                                        const overhang::SupportPoints& detected, const overhang::Overhangs& overhangs,
                                        const layers::LayerStack& stack, const Settings& settings, spdlog::logger& log,
                                        Progress& progress, int threads, int rounds) {
    const std::size_t n = copies.offsets.size();
    const layers::Bounds first = copies.prototype;
    const Clock::time_point t0 = Clock::now();
    const layers::LayerStack seen = layers::seen_from_every_copy(stack, copies, kCopyWindow);
    // Drawn only up to a little over the highest point: the plan stays under
    // its points, and anything asked above is refused.
    double top = 0;
    for (const overhang::SupportPoint& p : detected.points) top = std::max(top, first_copy.layers[p.layer].z);
    const plan::Obstacles obstacles(seen, settings, plan::worker_count(seen.layers.size(), threads), top + kSolidAbove);
    SharedCavities cavities(first_copy);
    if (settings.method == Method::Scaffold && plan::worker_count(2, threads) > 1)
        cavities.start(obstacles, plan::worker_count(2, threads));
    log.debug("the plate as the first copy sees it: {:.0f} ms", ms_between(t0, Clock::now()));
    progress.say("planning one of {} copies", n);
    GroupPlanned one = plan_group(detected, overhangs, first_copy, obstacles, settings, cavities, log, rounds, &progress,
                                  plan::worker_count(plan::kMaxPlanThreads, threads));
    // Everything within the window, short of its edge by more than any column is wide.
    const double in = kCopyWindow - kCopyReach;
    const layers::Bounds inner{first.min_x - in, first.min_y - in, first.max_x + in, first.max_y + in};
    auto inside = [&](const layers::Bounds& b, double x, double y) {
        return x >= b.min_x && x <= b.max_x && y >= b.min_y && y <= b.max_y;
    };
    auto past_the_window = [&] {
        log.debug("the first copy's plan reaches the edge of the window it was planned in: the plate is planned whole");
        return std::nullopt;
    };
    for (const plan::Column& c : one.scaffold.columns) {
        if (!inside(inner, c.x0, c.y0) || !inside(inner, c.x1, c.y1)) return past_the_window();
        if (c.base == plan::Base::Model && !on_first_copy(c, first_copy)) {
            log.debug("a column stands on the model at ({:.2f}, {:.2f}), outside the first copy: the plate is planned whole",
                      c.x0, c.y0);
            return std::nullopt;
        }
    }
    for (const plan::Bridge& b : one.scaffold.bridges)
        if (!inside(inner, b.x0, b.y0) || !inside(inner, b.x1, b.y1)) return past_the_window();
    const std::size_t count = detected.points.size();
    warn_left(log, one, rounds, settings);
    log.debug("{} exact copies: one planned ({} support points, {:.0f} ms), its plan moved to the others", n, count,
              ms_between(t0, Clock::now()));
    std::vector<plan::PointGroup> groups(n);
    std::vector<plan::GroupPlan> plans(n);
    overhang::SupportPoints input;
    input.overhang_area_mm2 = static_cast<double>(n) * detected.overhang_area_mm2;
    const plan::GroupPlan planned{std::move(one.points), std::move(one.scaffold)};
    for (std::size_t k = 0; k < n; ++k) {
        plans[k] = plan::moved(planned, copies.offsets[k].dx, copies.offsets[k].dy);
        for (std::size_t i = 0; i < count; ++i) {
            groups[k].index.push_back(static_cast<int>(input.points.size()));
            input.points.push_back(plans[k].points.points[i]);
        }
    }
    GroupPlanned out;
    out.scaffold = plan::merge_plans(input, groups, plans, out.points);
    const Clock::time_point t1 = Clock::now();
    // A travel within one copy's window is asked as the first copy's was.
    const toolpath::TravelClear clear = [&](int layer, const toolpath::Point& a, const toolpath::Point& b, double width) {
        for (const layers::Offset& o : copies.offsets)
            if (inside(inner, a.x - o.dx, a.y - o.dy) && inside(inner, b.x - o.dx, b.y - o.dy))
                return obstacles.segment_clear(layer, a.x - o.dx, a.y - o.dy, b.x - o.dx, b.y - o.dy, width);
        return false;
    };
    // Copies whose supports stand apart print the first copy's paths moved.
    // Copies whose columns meet (an elephant's between its neighbour's
    // legs) are made together, once for each arrangement of such a cluster
    // (the same copies' offsets from its first), and moved to the others.
    std::vector<toolpath::Point> at;
    for (const layers::Offset& o : copies.offsets) at.push_back({o.dx, o.dy});
    const std::vector<std::vector<std::size_t>> clusters = toolpath::copy_clusters(one.paths, at, kCopiesApart);
    auto same_shape = [&](const std::vector<std::size_t>& a, const std::vector<std::size_t>& b) {
        if (a.size() != b.size()) return false;
        for (std::size_t i = 1; i < a.size(); ++i)
            if (std::llround((at[a[i]].x - at[a[0]].x) * 1000) != std::llround((at[b[i]].x - at[b[0]].x) * 1000) ||
                std::llround((at[a[i]].y - at[a[0]].y) * 1000) != std::llround((at[b[i]].y - at[b[0]].y) * 1000))
                return false;
        return true;
    };
    std::vector<std::size_t> first_of_shape, shape_of(clusters.size());  // a cluster of each arrangement
    for (std::size_t c = 0; c < clusters.size(); ++c) {
        std::size_t s = 0;
        while (s < first_of_shape.size() && !same_shape(clusters[first_of_shape[s]], clusters[c])) ++s;
        if (s == first_of_shape.size()) first_of_shape.push_back(c);
        shape_of[c] = s;
    }
    // Each arrangement's paths and the copy they stand at: a lone copy's are
    // the first copy's; a cluster's are made (copy k's columns and bars are
    // the k-th of merge_plans' equal shares).
    const std::size_t nc = out.scaffold.columns.size() / n, nb = out.scaffold.bridges.size() / n;
    std::vector<toolpath::SupportPaths> made(first_of_shape.size());
    std::vector<const toolpath::SupportPaths*> shape_paths;
    std::vector<std::size_t> shape_at;
    for (std::size_t s = 0; s < first_of_shape.size(); ++s) {
        const std::vector<std::size_t>& cluster = clusters[first_of_shape[s]];
        if (cluster.size() == 1) {
            shape_paths.push_back(&one.paths);
            shape_at.push_back(0);
            continue;
        }
        plan::Scaffold part;
        for (std::size_t k : cluster) {
            part.columns.insert(part.columns.end(), out.scaffold.columns.begin() + static_cast<long>(k * nc),
                                out.scaffold.columns.begin() + static_cast<long>((k + 1) * nc));
            part.bridges.insert(part.bridges.end(), out.scaffold.bridges.begin() + static_cast<long>(k * nb),
                                out.scaffold.bridges.begin() + static_cast<long>((k + 1) * nb));
        }
        made[s] = toolpath::make_paths(part, stack, settings, clear);
        shape_paths.push_back(&made[s]);
        shape_at.push_back(cluster.front());
    }
    std::vector<toolpath::PlacedPaths> parts;
    for (std::size_t c = 0; c < clusters.size(); ++c) {
        const std::size_t base = shape_at[shape_of[c]], k = clusters[c].front();
        parts.push_back({shape_paths[shape_of[c]], {at[k].x - at[base].x, at[k].y - at[base].y}});
    }
    if (clusters.size() == n) log.debug("the first copy's paths moved to the others");
    else log.debug("{} clusters of copies whose supports meet, {} arrangements made", clusters.size(), first_of_shape.size());
    out.paths = toolpath::placed_paths(parts, clear);
    log.debug("the copies' paths made: {:.0f} ms", ms_between(t1, Clock::now()));
    return out;
}

std::unique_ptr<const plan::Obstacles> obstacles_of(const Request& req, const layers::LayerStack& stack,
                                                    const Settings& settings) {
    return std::make_unique<const plan::Obstacles>(stack, settings, plan::worker_count(stack.layers.size(), req.threads));
}

std::vector<int> objects_of(const overhang::SupportPoints& points, const std::optional<layers::ObjectMap>& objects,
                            const layers::Frame& frame) {
    std::vector<int> out;
    if (!objects || objects->count() < 2) return out;
    for (const overhang::SupportPoint& p : points.points)
        out.push_back(objects->at(p.x + frame.dx(), p.y + frame.dy(), kPointObjectReach));
    return out;
}

GroupPlanned plan_plate(const Request& req, const overhang::SupportPoints& detected, const overhang::Overhangs& overhangs,
                        const layers::LayerStack& stack, const Settings& settings, spdlog::logger& log, Progress& progress,
                        std::unique_ptr<const plan::Obstacles> built, const std::vector<int>& object,
                        SharedCavities* started) {
    const std::unique_ptr<const plan::Obstacles> obstacles = built ? std::move(built) : obstacles_of(req, stack, settings);
    std::vector<plan::PointGroup> groups =
        detected.points.empty() ? std::vector<plan::PointGroup>{}
                                : plan::point_groups(detected, overhangs, plan::group_reach(settings), object);
    SharedCavities here(stack);
    SharedCavities& cavities = started ? *started : here;
    if (!started && settings.method == Method::Scaffold && !groups.empty() && plan::worker_count(2, req.threads) > 1)
        here.start(*obstacles, plan::worker_count(2, req.threads));
    if (groups.size() <= 1) {
        GroupPlanned one = plan_group(detected, overhangs, stack, *obstacles, settings, cavities, log, req.bar_rounds,
                                      &progress, plan::worker_count(plan::kMaxPlanThreads, req.threads));
        warn_left(log, one, req.bar_rounds, settings);
        return one;
    }
    const int workers = plan::worker_count(groups.size(), req.threads);
    log.debug("{} support points in {} independent groups, planned on {} threads", detected.points.size(),
              groups.size(), workers);
    progress.say("planning {} support points in {} groups", detected.points.size(), groups.size());
    // Obstacles fill their caches as they are asked: caches of its own
    // for each thread (the same answers) over the one set of model
    // rasters, the first thread's the one already built.
    std::vector<std::unique_ptr<const plan::Obstacles>> own(static_cast<std::size_t>(workers));
    // Each group's plan as plan_group left it. A joined group's plan starts
    // without the bars its parts' plans were made again without, with its
    // first part's model answers (the same model), every part's brace and
    // bar-check answers and, where each part has one, its parts' plans
    // before braces side by side as its first round.
    std::vector<GroupPlanned> planned(groups.size());
    std::vector<plan::PlanReach> reach(groups.size());  // each plan's, for plans_apart
    std::vector<std::optional<plan::GroupPlan>> side_by_side(groups.size());
    std::vector<char> todo(groups.size(), 1);
    for (;;) {
        std::vector<std::size_t> list;
        for (std::size_t g = 0; g < groups.size(); ++g)
            if (todo[g]) list.push_back(g);
        // Groups of whole objects are worth a thread at once; a plate of
        // many light groups only once they have taken a while.
        std::size_t heavy = 0;
        for (std::size_t g : list) heavy += groups[g].index.size() >= kHeavyGroup;
        plan::for_each_group(
            list.size(), plan::worker_count(list.size(), workers),
            [&](std::size_t k) { return groups[list[k]].index.size(); },
            [&](std::size_t k, int worker) {
                const std::size_t g = list[k];
                const plan::Obstacles* obs = obstacles.get();
                if (worker > 0) {
                    auto& mine = own[static_cast<std::size_t>(worker)];
                    if (!mine) mine = obstacles->another();
                    obs = mine.get();
                }
                GroupPlanned done = plan_group(plan::group_points(detected, groups[g]),
                                               plan::group_overhangs(overhangs, groups[g]), stack, *obs, settings,
                                               cavities, log, req.bar_rounds, nullptr, 1, planned[g].learned,
                                               planned[g].answers, side_by_side[g] ? &*side_by_side[g] : nullptr,
                                               std::move(planned[g].brace_answers), std::move(planned[g].bar_cache));
                planned[g] = std::move(done);
                if (!object.empty()) reach[g] = plan::plan_reach(planned[g].scaffold, settings);
            },
            heavy >= 2 ? 0.0 : req.second_thread_after_s);
        if (object.empty()) break;
        // Groups whose plans come close (of different objects: a group's
        // plan keeps clear of the others of its own object by their reach):
        // joined, the lowest keeping its place, and planned again as one.
        plan::UnionFind into(groups.size());
        auto root = [&](std::size_t g) { return static_cast<std::size_t>(into.find(static_cast<int>(g))); };
        bool any = false;
        for (std::size_t a = 0; a < groups.size(); ++a)
            for (std::size_t b = a + 1; b < groups.size(); ++b) {
                if (root(a) == root(b) || plan::plans_apart(reach[a], reach[b])) continue;
                into.join(static_cast<int>(a), static_cast<int>(b));
                any = true;
            }
        if (!any) break;
        // Still ordered by their lowest index: a joined group keeps its root's place.
        std::vector<plan::PointGroup> next;
        std::vector<std::vector<std::size_t>> parts;  // each new group's old groups, in order
        std::vector<std::size_t> at(groups.size());
        for (std::size_t g = 0; g < groups.size(); ++g) {
            const std::size_t r = root(g);
            if (r == g) {
                at[g] = next.size();
                parts.push_back({g});
                next.push_back(groups[g]);
            } else {
                next[at[r]] = plan::joined(next[at[r]], groups[g]);
                parts[at[r]].push_back(g);
            }
        }
        std::vector<GroupPlanned> kept;
        std::vector<plan::PlanReach> kept_reach;
        std::vector<char> again;
        side_by_side.assign(next.size(), std::nullopt);
        for (std::size_t k = 0; k < next.size(); ++k) {
            const std::vector<std::size_t>& p = parts[k];
            again.push_back(p.size() > 1);
            // Its first round: its parts' plans before braces side by side,
            // braced and checked as one (where each part has one).
            if (again[k] && std::all_of(p.begin(), p.end(), [&](std::size_t g) { return planned[g].unbraced.has_value(); })) {
                std::vector<plan::PointGroup> each_group;
                std::vector<plan::GroupPlan> each;
                for (std::size_t g : p) {
                    each_group.push_back(groups[g]);
                    each.push_back(std::move(*planned[g].unbraced));
                }
                side_by_side[k] = plan::side_by_side(detected, next[k], each_group, std::move(each));
            }
            // Bars its parts' plans found not held, found again by the
            // joined plan's rounds, each a plan of the whole (four Cura
            // bunnies: 4 bars, then 1, then 1, as in the parts' plans).
            // And what its parts' braces and checks found, asked again
            // where the parts' plans stand side by side.
            GroupPlanned& whole = planned[p.front()];
            for (std::size_t i = 1; i < p.size(); ++i) {
                GroupPlanned& part = planned[p[i]];
                whole.learned.bars.insert(whole.learned.bars.end(), part.learned.bars.begin(), part.learned.bars.end());
                whole.learned.places.insert(whole.learned.places.end(), part.learned.places.begin(),
                                           part.learned.places.end());
                whole.brace_answers.helpers.merge(part.brace_answers.helpers);
                whole.bar_cache.answers.merge(part.bar_cache.answers);
            }
            kept.push_back(std::move(planned[p.front()]));
            kept_reach.push_back(std::move(reach[p.front()]));
        }
        log.debug("plans of {} groups came close: planned again as {}", groups.size() - next.size() +
                  static_cast<std::size_t>(std::count(again.begin(), again.end(), 1)),
                  std::count(again.begin(), again.end(), 1));
        groups = std::move(next);
        planned = std::move(kept);
        reach = std::move(kept_reach);
        todo = std::move(again);
        for (std::size_t g = 0; g < groups.size(); ++g)
            if (todo[g] && !planned[g].learned.empty())
                log.debug("a joined group starts without the {} bars ({} places) its parts' plans found not held",
                          planned[g].learned.bars.size(), planned[g].learned.places.size());
    }
    own.clear();
    std::vector<plan::GroupPlan> plans;
    for (GroupPlanned& p : planned) {
        warn_left(log, p, req.bar_rounds, settings);
        plans.push_back({std::move(p.points), std::move(p.scaffold)});
    }
    GroupPlanned all;
    all.scaffold = plan::merge_plans(detected, groups, plans, all.points);
    // One group left (all joined): its plan's paths are those of the merged
    // plan (the same columns and bars in the same order, only its points
    // numbered as the plate's), made and checked in its last round.
    if (groups.size() == 1) {
        all.paths = std::move(planned.front().paths);
        return all;
    }
    planned.clear();  // the groups' own paths and model answers, not needed now
    all.paths = toolpath::make_paths(all.scaffold, stack, settings, obstacles.get());
    return all;
}

}  // namespace scaffold::cli
