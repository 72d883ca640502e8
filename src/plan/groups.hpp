#pragma once
// Independent parts of a plate: support points nothing the planner builds
// can join or let affect each other (a bar, a brace, a connector, a column,
// a cover point in their overhang region) are planned apart, each group with
// its own rounds, on several threads; the plans are merged in group order,
// so the plan is the same for any thread count.
#include <cstddef>
#include <algorithm>
#include <functional>
#include <numeric>
#include <utility>
#include <vector>

#include "gcode/settings.hpp"
#include "layers/regions.hpp"
#include "overhang/overhangs.hpp"
#include "plan/scaffold.hpp"

namespace scaffold::plan {

// Union-find over 0..n-1 in which the lower root stays: each set's root
// is its lowest index (groups keep the order of their lowest member).
struct UnionFind {
    std::vector<int> parent;
    explicit UnionFind(std::size_t n) : parent(n) { std::iota(parent.begin(), parent.end(), 0); }
    int find(int i) {
        while (parent[i] != i) i = parent[i] = parent[parent[i]];
        return i;
    }
    void join(int a, int b) {
        a = find(a);
        b = find(b);
        if (a != b) parent[std::max(a, b)] = std::min(a, b);
    }
};

// Points farther apart than this (in XY) are never joined by one thing the
// planner builds, nor affect each other's plan. See groups.cpp for the sum.
double group_reach(const Settings& settings);

struct PointGroup {
    std::vector<int> index;  // its points' indices in the input, ascending
    // Its share of the overhang cells: (position in Overhangs::layers, cells),
    // ascending by position.
    std::vector<std::pair<int, std::vector<layers::Cell>>> cells;
};

// Union-find over the points: two within `reach` of each other join, and so
// do the points nearest to each end of one overhang region (8-connected
// cells), which goes to their group. Groups ordered by their lowest index.
// `object` (empty, or one per point: the object of the plate it holds):
// points of different objects do not join by distance, so each object of a
// plate is planned on its own; plans_apart then says whether that held.
std::vector<PointGroup> point_groups(const overhang::SupportPoints& points, const overhang::Overhangs& overhangs,
                                     double reach, const std::vector<int>& object = {});

// Two groups as one: their points and cells, in order.
PointGroup joined(const PointGroup& a, const PointGroup& b);

// mm between what two plans build (loops' and feet's outer edges, bars'
// lines) beyond which neither changes the other's paths, islands or
// travels: more than a loop shifts between layers, two beads wide.
inline constexpr double kPlansApart = 2.0;
// Whether nothing of `a` comes within kPlansApart of anything of `b` in XY
// at overlapping heights (a column in slices of 2 mm, each at its widest, a
// raft on its layer, a bar over its two layers and its ends' reach into
// the columns). Columns below the feet's height (`foot_height`) and rafts
// may meet each other: loops that meet there only stiffen each other.
bool plans_apart(const Scaffold& a, const Scaffold& b, const Settings& settings);

// A plan as plans_apart judges it, worked out once for a plan compared
// with many: its parts as XY segments with a reach either side, over a
// height range, and the box of each.
struct PlanReach {
    struct Part {
        layers::Segment seg;
        double r = 0, z0 = 0, z1 = 0;
        bool low = false;  // a column's below the feet's height, or a raft
        bool bar = false;
        double x0 = 0, y0 = 0, x1 = 0, y1 = 0;  // its box, reach included
    };
    std::vector<Part> parts;
};
PlanReach plan_reach(const Scaffold& plan, const Settings& settings);
bool plans_apart(const PlanReach& a, const PlanReach& b);

// The group's points, in the input's order (positions as PointGroup::index).
overhang::SupportPoints group_points(const overhang::SupportPoints& points, const PointGroup& group);
// The group's overhang cells, on grids shaped like the input's, only on
// layers where it has some.
overhang::Overhangs group_overhangs(const overhang::Overhangs& overhangs, const PointGroup& group);

// Workers for `groups` groups on `threads` threads (0: the machine's cores).
int worker_count(std::size_t groups, int threads);
// job(group, worker) for every group, on `workers` threads (worker in
// [0, workers)), larger groups first so the threads end close together; a
// job's exception reaches the caller (the lowest group's, as on one thread).
// `size(group)` ranks the groups; the jobs must not depend on the order.
// Workers after the first start only once the groups have taken
// `start_after_s` (a worker may cost a set-up of its own, which a light
// plate does not pay back) and some are still left.
void for_each_group(std::size_t groups, int workers, const std::function<std::size_t(std::size_t)>& size,
                    const std::function<void(std::size_t, int)>& job, double start_after_s = 0);

// One group's plan: its points (those of group_points, then any it added)
// and its scaffold, with indices into those points.
struct GroupPlan {
    overhang::SupportPoints points;
    Scaffold scaffold;
};
// The plans as one, in group order: the input's points, then each group's
// added points; columns, bridges, dropped points and unheld ends in group
// order, indices renumbered to `points`.
Scaffold merge_plans(const overhang::SupportPoints& input, const std::vector<PointGroup>& groups,
                     std::vector<GroupPlan>& plans, overhang::SupportPoints& points);

// The plans of `parts` (groups whose points together are `whole`'s) as
// one plan of `whole`: its points (group_points of `whole`), then each
// part's added points, in part order; columns and bridges in part order,
// indices renumbered to those points.
GroupPlan side_by_side(const overhang::SupportPoints& input, const PointGroup& whole,
                       const std::vector<PointGroup>& parts, std::vector<GroupPlan> plans);

// The plan moved by (dx, dy): a copy's plan from the first copy's.
GroupPlan moved(const GroupPlan& plan, double dx, double dy);

}  // namespace scaffold::plan
