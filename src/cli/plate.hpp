#pragma once
// Planning a plate (the pipeline's plan stage): each group of points planned
// in rounds until its bars hold as built, groups of different objects apart
// and joined where their plans come close, and a plate of exact copies as
// one copy moved. Used by cli::run; here apart so tests can plan a group.
#include <spdlog/logger.h>

#include <atomic>
#include <chrono>
#include <memory>
#include <mutex>
#include <optional>
#include <thread>
#include <utility>
#include <vector>

#include "cli/pipeline.hpp"
#include "layers/copies.hpp"
#include "layers/frame.hpp"
#include "layers/layer_stack.hpp"
#include "layers/objects.hpp"
#include "overhang/overhangs.hpp"
#include "plan/braces.hpp"
#include "plan/cavities.hpp"
#include "plan/groups.hpp"
#include "plan/obstacles.hpp"
#include "plan/planner.hpp"
#include "toolpath/bar_check.hpp"
#include "toolpath/support_paths.hpp"

namespace scaffold::cli {

using Clock = std::chrono::steady_clock;

// One line per stage on stderr once the run has taken longer than
// Request::progress_after_s (a full plate may plan for minutes; a host's log
// of a short run stays as it was).
struct Progress {
    spdlog::logger& log;
    double after_s;
    Clock::time_point start = Clock::now();
    template <typename... Args>
    void say(fmt::format_string<Args...> what, Args&&... args) {
        const double s = std::chrono::duration<double>(Clock::now() - start).count();
        if (s >= after_s) log.info("{} ({:.0f} s so far)", fmt::format(what, std::forward<Args>(args)...), s);
    }
};

// The model's hollows (plan/cavities), mapped once for every group and
// round by whichever plan asks first (the same map whichever builds it):
// mapping them is a pass over every layer.
class SharedCavities {
public:
    explicit SharedCavities(const layers::LayerStack& stack) : stack_(stack) {}
    SharedCavities(const SharedCavities&) = delete;
    SharedCavities& operator=(const SharedCavities&) = delete;
    ~SharedCavities() {
        cancel_ = true;  // not asked for by now: not needed
        if (early_.joinable()) early_.join();
    }
    const plan::Cavities& get(const plan::Obstacles& obstacles) {
        std::call_once(once_, [&] { cavities_.emplace(stack_, obstacles, threads_); });
        return *cavities_;
    }
    // Mapped on threads of their own while the plan begins (the bridge
    // search's first bar asks for them, and each plan waits there: on a
    // plate of several objects, every thread of the plan); get() waits for
    // it. Only the obstacles' grid is kept.
    void start(const plan::Obstacles& obstacles, int threads) { start(obstacles.footprint(0).empty_like(), threads); }
    // The same on the obstacles' grid (plan::obstacle_grid), before they are
    // built: from the start of the overhangs' search.
    void start(layers::BitGrid grid, int threads) {
        threads_ = threads;
        early_ = std::thread([this, grid = std::move(grid), threads] {
            try {
                std::call_once(once_, [&] { cavities_.emplace(stack_, grid, threads, &cancel_); });
            } catch (...) {
                // Not mapped: the plan's own get() maps them again and throws there.
            }
        });
    }

private:
    const layers::LayerStack& stack_;
    std::once_flag once_;
    std::optional<plan::Cavities> cavities_;
    std::thread early_;
    int threads_ = 1;
    std::atomic<bool> cancel_{false};
};

// One group's plan (the whole plate's when it is one group), its points
// (the group's, then those added to cover what tips leave unheld) and paths.
struct GroupPlanned {
    overhang::SupportPoints points;
    plan::Scaffold scaffold;
    toolpath::SupportPaths paths;
    // The bars (and places) its first plan's rounds were made again without
    // (not held as built, or on a column short of the Standing rule): where
    // this group is joined with another, the joined plan starts without them.
    plan::Forbidden learned;
    // What its plans asked of the model (pure answers: any plan on the same
    // model and settings may ask them again, as a joined group's does).
    std::shared_ptr<plan::ModelAnswers> answers;
    // The helper pillars its braces dropped and the bar lines its checks
    // judged (pure as well): a joined group's first round braces and checks
    // its parts' plans again, side by side.
    plan::BraceAnswers brace_answers;
    toolpath::BarCheckCache bar_cache;
    // Its last plan before braces and props (bars, pillars, the points that
    // cover what tips leave): where this group is joined with another, the
    // joined plan's first round is the parts' side by side. None where the
    // rounds ran out and an earlier plan was kept.
    std::optional<plan::GroupPlan> unbraced;
    // Where the rounds ran out: its bars still not held that carry points,
    // and those on columns short of the rule (warn_left says so).
    std::pair<std::size_t, std::size_t> left{0, 0};
    // Its tips' columns short of the Standing rule (warn_left says so too).
    std::vector<plan::ShortColumn> weak;
};

// One group's plan, in rounds: each plan checked as built (every bar held,
// METHOD's Standing rule) and made again without the bars that fail, at most
// `rounds` times, then again without the bars on braced columns where that
// costs less. `start`: bars and places to plan without from the first round;
// `known`, `brace_answers`, `bar_cache`: answers asked before on the same
// model and settings. `first`: a plan before braces to take as the first
// round instead of searching (a joined group's parts' plans side by side);
// where it does not hold, the rounds go on, each a search of the whole.
GroupPlanned plan_group(const overhang::SupportPoints& detected, const overhang::Overhangs& overhangs,
                        const layers::LayerStack& stack, const plan::Obstacles& obstacles, const Settings& settings,
                        SharedCavities& cavities, spdlog::logger& log, int rounds, Progress* progress, int threads = 1,
                        const plan::Forbidden& start = {}, std::shared_ptr<plan::ModelAnswers> known = nullptr,
                        const plan::GroupPlan* first = nullptr, plan::BraceAnswers brace_answers = {},
                        toolpath::BarCheckCache bar_cache = {});

// A plate of exact copies (layers::Copies): the first copy's plan (its
// points, overhangs, beads alone in `first_copy`), made clear of the plate
// as seen from every copy at once, then moved to each. Nothing of the plan
// may lean on what is not the same around every copy: nullopt (plan the
// plate whole) when a column stands on the model outside the first copy or
// the plan reaches the edge of the window the plate was seen through.
std::optional<GroupPlanned> plan_copies(const layers::Copies& copies, const layers::LayerStack& first_copy,
                                        const overhang::SupportPoints& detected, const overhang::Overhangs& overhangs,
                                        const layers::LayerStack& stack, const Settings& settings, spdlog::logger& log,
                                        Progress& progress, int threads, int rounds);

// The model as the planner asks it (plan::Obstacles).
std::unique_ptr<const plan::Obstacles> obstacles_of(const Request& req, const layers::LayerStack& stack,
                                                    const Settings& settings);

// Each point's object on the plate (the frame's points looked up on the
// bed), or nothing where the plate holds one object.
std::vector<int> objects_of(const overhang::SupportPoints& points, const std::optional<layers::ObjectMap>& objects,
                            const layers::Frame& frame);

// The plate planned whole: points no bar, brace or column can join in
// groups of their own, on the request's threads; and each object of the
// plate (`object`: one per point, else empty) in groups of its own, where
// the plans come out apart (plan::plans_apart): objects whose plans come
// close are planned again as one. `built`: the stack's obstacles when
// already built (else built here).
GroupPlanned plan_plate(const Request& req, const overhang::SupportPoints& detected, const overhang::Overhangs& overhangs,
                        const layers::LayerStack& stack, const Settings& settings, spdlog::logger& log, Progress& progress,
                        std::unique_ptr<const plan::Obstacles> built, const std::vector<int>& object,
                        SharedCavities* started);

}  // namespace scaffold::cli
