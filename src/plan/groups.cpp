#include "plan/groups.hpp"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <exception>
#include <limits>
#include <map>
#include <numeric>
#include <stdexcept>
#include <thread>

#include "plan/braces.hpp"
#include "plan/candidates.hpp"
#include "plan/lean_in.hpp"
#include "plan/pillars.hpp"
#include "plan/workers.hpp"

namespace scaffold::plan {

double group_reach(const Settings& s) {
    // A bar carries points up to its length along it and the offset either
    // side: two of them that far apart. Its ends stand up to the offset off
    // the points they were taken from, where a lower bar may carry them.
    const double bar = std::hypot(s.bridge_max_length, 2 * s.bridge_max_offset) + s.bridge_max_offset;
    // A brace ties columns up to kBraceReach apart, each of which may lean
    // in to its point from up to kLeanInReach away.
    const double brace = kBraceReach + 2 * kLeanInReach;
    // Margin: a cover point stands in a point's share of the sheet, and a
    // pillar branches off a trunk within kBranchSteer.
    return std::max(bar, brace) + s.point_radius + kBranchSteer;
}


std::vector<PointGroup> point_groups(const overhang::SupportPoints& points, const overhang::Overhangs& overhangs,
                                     double reach, const std::vector<int>& object) {
    const auto& pts = points.points;
    const int n = static_cast<int>(pts.size());
    if (n == 0) return {};
    UnionFind uf(pts.size());
    // Points by grid cell of side `reach`: a pair within reach is in
    // neighbouring cells. An ordered map: no order from hashing.
    std::map<std::pair<long, long>, std::vector<int>> grid;
    auto cell_of = [reach](double v) { return static_cast<long>(std::floor(v / reach)); };
    for (int i = 0; i < n; ++i) grid[{cell_of(pts[i].x), cell_of(pts[i].y)}].push_back(i);
    const double r2 = reach * reach;
    for (const auto& [key, in_cell] : grid)
        for (long dx = -1; dx <= 1; ++dx)
            for (long dy = -1; dy <= 1; ++dy) {
                auto it = grid.find({key.first + dx, key.second + dy});
                if (it == grid.end()) continue;
                for (int i : in_cell)
                    for (int j : it->second) {
                        if (j <= i) continue;
                        const double ex = pts[i].x - pts[j].x, ey = pts[i].y - pts[j].y;
                        const bool same = object.empty() || object[i] == object[j] || object[i] < 0 || object[j] < 0;
                        if (same && ex * ex + ey * ey <= r2) uf.join(i, j);
                    }
            }

    // Each overhang region goes with the points nearest to its first and
    // last cells (those on its layer first): points added to cover it later
    // stand in it, so it must be planned with them.
    std::map<int, std::vector<int>> by_layer;
    for (int i = 0; i < n; ++i) by_layer[pts[i].layer].push_back(i);
    auto nearest = [&](int layer, double x, double y) {
        auto it = by_layer.find(layer);
        int best = -1;
        double best_d = std::numeric_limits<double>::infinity();
        auto scan = [&](int i) {
            const double d = std::hypot(pts[i].x - x, pts[i].y - y);
            if (d < best_d) best_d = d, best = i;
        };
        if (it != by_layer.end())
            for (int i : it->second) scan(i);
        else
            for (int i = 0; i < n; ++i) scan(i);
        return best;
    };
    struct Owned {
        int layer_pos, point;
        std::vector<layers::Cell> cells;
    };
    std::vector<Owned> regions;
    for (int k = 0; k < static_cast<int>(overhangs.layers.size()); ++k) {
        const overhang::OverhangLayer& ol = overhangs.layers[k];
        for (std::vector<layers::Cell>& comp : layers::components(ol.cells)) {
            const layers::Cell a = comp.front(), b = comp.back();
            const int pa = nearest(ol.layer, ol.cells.cx(a.i), ol.cells.cy(a.j));
            const int pb = nearest(ol.layer, ol.cells.cx(b.i), ol.cells.cy(b.j));
            uf.join(pa, pb);
            regions.push_back({k, pa, std::move(comp)});
        }
    }

    std::vector<int> group_of(pts.size(), -1);
    std::vector<PointGroup> out;
    for (int i = 0; i < n; ++i) {
        const int root = uf.find(i);
        if (group_of[root] < 0) {
            group_of[root] = static_cast<int>(out.size());
            out.emplace_back();
        }
        out[group_of[root]].index.push_back(i);
    }
    for (Owned& r : regions) {
        PointGroup& g = out[group_of[uf.find(r.point)]];
        if (g.cells.empty() || g.cells.back().first != r.layer_pos) g.cells.push_back({r.layer_pos, {}});
        auto& cells = g.cells.back().second;
        cells.insert(cells.end(), r.cells.begin(), r.cells.end());
    }
    return out;
}

PointGroup joined(const PointGroup& a, const PointGroup& b) {
    PointGroup out;
    std::merge(a.index.begin(), a.index.end(), b.index.begin(), b.index.end(), std::back_inserter(out.index));
    std::size_t i = 0, j = 0;
    while (i < a.cells.size() || j < b.cells.size()) {
        if (j == b.cells.size() || (i < a.cells.size() && a.cells[i].first < b.cells[j].first)) {
            out.cells.push_back(a.cells[i++]);
        } else if (i == a.cells.size() || b.cells[j].first < a.cells[i].first) {
            out.cells.push_back(b.cells[j++]);
        } else {
            out.cells.push_back(a.cells[i++]);
            auto& cells = out.cells.back().second;
            cells.insert(cells.end(), b.cells[j].second.begin(), b.cells[j].second.end());
            ++j;
        }
    }
    return out;
}

namespace {

// Columns are judged in slices this tall: a tapered column is widest at
// its foot, and a neighbour's bar higher up need not keep clear of that.
constexpr double kSlice = 2.0;

}  // namespace

PlanReach plan_reach(const Scaffold& sc, const Settings& s) {
    PlanReach out;
    const double w = s.support_width;
    auto add = [&](double xa, double ya, double xb, double yb, double r, double z0, double z1, bool low, bool bar) {
        out.parts.push_back({{static_cast<float>(xa), static_cast<float>(ya), static_cast<float>(xb), static_cast<float>(yb)},
                             r, z0, z1, low, bar, std::min(xa, xb) - r, std::min(ya, yb) - r, std::max(xa, xb) + r,
                             std::max(ya, yb) + r});
    };
    auto slice = [&](const Column& c, double za, double zb, bool low) {
        double xa, ya, xb, yb;
        column_centre_at(c, za, xa, ya);
        column_centre_at(c, zb, xb, yb);
        // The radius narrows upward (taper, flared foot, neck): widest at an end.
        const double r = std::max({column_radius_at(c, za, s), column_radius_at(c, (za + zb) / 2, s),
                                   column_radius_at(c, zb, s)}) + w;
        add(xa, ya, xb, yb, r, za, zb, low, false);
    };
    for (const Column& c : sc.columns) {
        // A raft: a square on the first layer, reaching its corners.
        if (c.raft_size > 0) add(c.x0, c.y0, c.x0, c.y0, c.raft_size * 0.5 * std::sqrt(2.0), c.z0, c.z0, true, false);
        double z = c.z0;
        if (z < s.foot_height) {
            z = std::min(c.z1, s.foot_height);
            slice(c, c.z0, z, true);
        }
        const int n = static_cast<int>(std::ceil((c.z1 - z) / kSlice - 1e-9));
        for (int k = 0; k < n; ++k) slice(c, z + (c.z1 - z) * k / n, z + (c.z1 - z) * (k + 1) / n, false);
    }
    for (const Bridge& b : sc.bridges) {
        // Two lines side by side, reaching past its ends into the columns.
        add(b.x0, b.y0, b.x1, b.y1, w + s.pillar_radius, b.z, b.z + kBarThickness, false, true);
    }
    return out;
}

bool plans_apart(const PlanReach& a, const PlanReach& b) {
    constexpr double kZSlack = 0.5;
    for (const PlanReach::Part& p : a.parts)
        for (const PlanReach::Part& q : b.parts) {
            // Loops near the bed that meet merge into one island, which only
            // stiffens both (METHOD's sections), and no bar is among them.
            if (p.low && q.low) continue;
            // A bar's first layer rests on a column's top: a bar meets what
            // ends or starts within a layer or two of it; columns one above
            // the other's slice do not meet.
            const double slack = p.bar || q.bar ? kZSlack : 0.0;
            if (p.z1 + slack <= q.z0 || q.z1 + slack <= p.z0) continue;
            if (q.x0 > p.x1 + kPlansApart || p.x0 > q.x1 + kPlansApart || q.y0 > p.y1 + kPlansApart ||
                p.y0 > q.y1 + kPlansApart)
                continue;
            if (layers::segments_distance(p.seg.x0, p.seg.y0, p.seg.x1, p.seg.y1, q.seg.x0, q.seg.y0, q.seg.x1, q.seg.y1) <
                p.r + q.r + kPlansApart)
                return false;
        }
    return true;
}

bool plans_apart(const Scaffold& a, const Scaffold& b, const Settings& settings) {
    return plans_apart(plan_reach(a, settings), plan_reach(b, settings));
}

overhang::SupportPoints group_points(const overhang::SupportPoints& points, const PointGroup& group) {
    overhang::SupportPoints out;
    out.points.reserve(group.index.size());
    for (int i : group.index) out.points.push_back(points.points[i]);
    return out;
}

overhang::Overhangs group_overhangs(const overhang::Overhangs& overhangs, const PointGroup& group) {
    overhang::Overhangs out;
    for (const auto& [k, cells] : group.cells) {
        const overhang::OverhangLayer& ol = overhangs.layers[k];
        overhang::OverhangLayer mine{ol.layer, ol.cells.empty_like(), 0};
        for (const layers::Cell& c : cells) mine.cells.set(c.i, c.j);
        mine.area_mm2 = static_cast<double>(cells.size()) * ol.cells.cell_area();
        out.area_mm2 += mine.area_mm2;
        out.layers.push_back(std::move(mine));
    }
    return out;
}

int worker_count(std::size_t groups, int threads) {
    if (threads <= 0) threads = static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
    return static_cast<int>(std::min<std::size_t>(static_cast<std::size_t>(threads), std::max<std::size_t>(groups, 1)));
}

void for_each_group(std::size_t groups, int workers, const std::function<std::size_t(std::size_t)>& size,
                    const std::function<void(std::size_t, int)>& job, double start_after_s) {
    std::vector<std::size_t> order(groups);
    std::iota(order.begin(), order.end(), 0);
    std::vector<std::size_t> sizes(groups);
    for (std::size_t g = 0; g < groups; ++g) sizes[g] = size(g);
    std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return sizes[a] > sizes[b]; });
    std::atomic<std::size_t> next{0};
    std::vector<std::exception_ptr> failed(groups);
    const auto start = std::chrono::steady_clock::now();
    const auto wait = std::chrono::duration<double>(start_after_s);
    auto run = [&](int worker) {
        if (worker > 0)
            while (next < groups && std::chrono::steady_clock::now() - start < wait)
                std::this_thread::sleep_for(std::chrono::milliseconds(20));
        for (std::size_t k; (k = next++) < groups;) {
            try {
                job(order[k], worker);
            } catch (...) {
                failed[order[k]] = std::current_exception();
            }
        }
    };
    run_workers(workers, run);
    for (const std::exception_ptr& e : failed)
        if (e) std::rethrow_exception(e);
}

Scaffold merge_plans(const overhang::SupportPoints& input, const std::vector<PointGroup>& groups,
                     std::vector<GroupPlan>& plans, overhang::SupportPoints& points) {
    points.points = input.points;
    points.overhang_area_mm2 = input.overhang_area_mm2;
    Scaffold out;
    for (std::size_t g = 0; g < plans.size(); ++g) {
        const std::vector<int>& index = groups[g].index;
        GroupPlan& plan = plans[g];
        const std::size_t first_added = points.points.size();
        points.points.insert(points.points.end(), plan.points.points.begin() + static_cast<long>(index.size()),
                             plan.points.points.end());
        auto renumber = [&](int i) {
            if (i < 0) return i;
            const auto u = static_cast<std::size_t>(i);
            return u < index.size() ? index[u] : static_cast<int>(first_added + (u - index.size()));
        };
        for (Column& c : plan.scaffold.columns) {
            c.point = renumber(c.point);
            out.columns.push_back(std::move(c));
        }
        for (Bridge& b : plan.scaffold.bridges) {
            for (int& p : b.points) p = renumber(p);
            out.bridges.push_back(std::move(b));
        }
        for (int p : plan.scaffold.dropped_points) out.dropped_points.push_back(renumber(p));
        out.unheld_bridge_ends.insert(out.unheld_bridge_ends.end(), plan.scaffold.unheld_bridge_ends.begin(),
                                      plan.scaffold.unheld_bridge_ends.end());
        out.uncovered.insert(out.uncovered.end(), plan.scaffold.uncovered.begin(), plan.scaffold.uncovered.end());
    }
    std::sort(out.dropped_points.begin(), out.dropped_points.end());
    return out;
}

GroupPlan side_by_side(const overhang::SupportPoints& input, const PointGroup& whole,
                       const std::vector<PointGroup>& parts, std::vector<GroupPlan> plans) {
    // Each part's points as positions in `whole` (whose index is sorted).
    std::vector<PointGroup> local(parts.size());
    for (std::size_t k = 0; k < parts.size(); ++k)
        for (int i : parts[k].index) {
            const auto at = std::lower_bound(whole.index.begin(), whole.index.end(), i);
            if (at == whole.index.end() || *at != i) throw std::logic_error("side_by_side: a part's point not in the whole");
            local[k].index.push_back(static_cast<int>(at - whole.index.begin()));
        }
    GroupPlan out;
    out.scaffold = merge_plans(group_points(input, whole), local, plans, out.points);
    return out;
}

GroupPlan moved(const GroupPlan& plan, double dx, double dy) {
    GroupPlan out = plan;
    for (overhang::SupportPoint& p : out.points.points) {
        p.x += dx;
        p.y += dy;
    }
    for (Column& c : out.scaffold.columns) {
        c.x0 += dx;
        c.y0 += dy;
        c.x1 += dx;
        c.y1 += dy;
    }
    for (Bridge& b : out.scaffold.bridges) {
        b.x0 += dx;
        b.y0 += dy;
        b.x1 += dx;
        b.y1 += dy;
    }
    for (Xyz& e : out.scaffold.unheld_bridge_ends) {
        e.x += dx;
        e.y += dy;
    }
    for (Xyz& e : out.scaffold.uncovered) {
        e.x += dx;
        e.y += dy;
    }
    return out;
}

}  // namespace scaffold::plan
