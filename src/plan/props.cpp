#include "plan/props.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <tuple>
#include <utility>

#include "plan/candidates.hpp"
#include "plan/pillars.hpp"

namespace scaffold::plan {

namespace {
constexpr double kEps = 1e-6;
// Layers a prop may lean over beyond the fewest it needs (a gentler lean
// passes the model elsewhere).
constexpr int kMoreLayers = 3;
// A prop's top lies on the bar's line at least this far in from its ends
// (an end stands on its own column).
constexpr double kEndsIn = 0.5;
}  // namespace

double passes_beside(const Column& col, const Bridge& bar, const Settings& s) {
    if (!(col.z0 < bar.z - kEps) || col.z1 < bar.z - kEps) return -1;
    double cx, cy;
    column_centre_at(col, bar.z, cx, cy);
    const double r = column_radius_at(col, bar.z, s);
    // What the bar's ends stand on (its end columns, the columns a brace ties).
    if (std::hypot(cx - bar.x0, cy - bar.y0) <= r + s.support_width ||
        std::hypot(cx - bar.x1, cy - bar.y1) <= r + s.support_width)
        return -1;
    // Beside the bar's length, not off an end (where the end's column is).
    const double bx = bar.x1 - bar.x0, by = bar.y1 - bar.y0, len = std::hypot(bx, by);
    const double along = len > 0 ? ((cx - bar.x0) * bx + (cy - bar.y0) * by) / len : 0;
    if (along < kEndsIn || along > len - kEndsIn) return -1;
    const double d = layers::segment_distance(cx, cy, bar.x0, bar.y0, bar.x1, bar.y1);
    // Its line crosses the loop within the loop's bead: it rests on it.
    if (d <= r - s.support_width) return -1;
    return d - r <= kBesideBar ? d : -1;
}

std::vector<Column> prop_under(const std::vector<const Column*>& chain, const Bridge& bar, const layers::LayerStack& stack,
                               const Obstacles& obs, const Settings& s) {
    const double bx = bar.x1 - bar.x0, by = bar.y1 - bar.y0, len = std::hypot(bx, by);
    if (chain.empty() || len < 2 * kEndsIn) return {};
    double cx, cy;
    column_centre_at(*chain.front(), bar.z, cx, cy);
    const double t = std::clamp(((cx - bar.x0) * bx + (cy - bar.y0) * by) / (len * len), kEndsIn / len, 1 - kEndsIn / len);
    const double px = bar.x0 + bx * t, py = bar.y0 + by * t;
    // The layers up to the bar's bottom, ascending, with their indices.
    std::vector<std::pair<double, int>> tops;
    for (int l = 0; l < static_cast<int>(stack.layers.size()); ++l)
        if (!stack.layers[l].purge && stack.layers[l].z <= bar.z + kEps) tops.emplace_back(stack.layers[l].z, l);
    std::sort(tops.begin(), tops.end());
    if (tops.empty() || std::abs(tops.back().first - bar.z) > kEps) return {};
    const int top = static_cast<int>(tops.size()) - 1;
    int fewest = -1;
    for (int n = 1; top - n >= 0 && (fewest < 0 || n <= fewest + kMoreLayers); ++n) {
        const double z0 = tops[static_cast<std::size_t>(top - n)].first;
        // The piece whose loop on that layer the prop stands on.
        const auto on = std::find_if(chain.begin(), chain.end(),
                                     [&](const Column* c) { return z0 > c->z0 + kEps && z0 <= c->z1 + kEps; });
        if (on == chain.end()) break;
        Column p;
        column_centre_at(**on, z0, p.x0, p.y0);
        p.z0 = z0;
        p.x1 = px;
        p.y1 = py;
        p.z1 = bar.z;
        p.radius = std::max(kConnectorRadius, column_radius_at(**on, z0, s));
        p.base = Base::Column;
        p.top = Top::Bridge;
        const double dist = std::hypot(px - p.x0, py - p.y0);
        bool ok = true;
        for (int i = top - n + 1; ok && i <= top; ++i) {
            const double h = tops[static_cast<std::size_t>(i)].first - tops[static_cast<std::size_t>(i - 1)].first;
            ok = dist * h / (bar.z - z0) <= max_lean_per_layer(h, s) + kEps;
        }
        if (!ok) continue;
        if (fewest < 0) fewest = n;
        for (int i = top - n + 1; ok && i <= top; ++i) {
            const auto [z, l] = tops[static_cast<std::size_t>(i)];
            double x, y;
            column_centre_at(p, z, x, y);
            ok = obs.disc_clear(l, x, y, p.radius + s.xy_gap + s.resolution);
        }
        if (ok) return {p};
    }
    return {};
}

int prop_bars(Scaffold& sc, const std::vector<std::size_t>& bars, const layers::LayerStack& stack, const Obstacles& obs,
              const Settings& s) {
    const std::size_t columns = sc.columns.size();
    // The piece each stacked piece stands on (its top is the piece's base).
    std::map<std::tuple<double, double, double>, std::size_t> tops;
    for (std::size_t i = 0; i < columns; ++i) tops.emplace(std::tuple{sc.columns[i].x1, sc.columns[i].y1, sc.columns[i].z1}, i);
    int added = 0;
    std::vector<Column> props;
    for (const std::size_t b : bars) {
        const Bridge& bar = sc.bridges[b];
        for (std::size_t i = 0; i < columns; ++i) {
            if (passes_beside(sc.columns[i], bar, s) < 0) continue;
            std::vector<const Column*> chain{&sc.columns[i]};
            while (chain.size() < columns && chain.back()->base == Base::Column) {
                const auto it = tops.find({chain.back()->x0, chain.back()->y0, chain.back()->z0});
                if (it == tops.end() || &sc.columns[it->second] == chain.back()) break;
                chain.push_back(&sc.columns[it->second]);
            }
            for (const Column& p : prop_under(chain, bar, stack, obs, s)) {
                // Not one that would pass beside another bar in turn.
                if (std::any_of(sc.bridges.begin(), sc.bridges.end(),
                                [&](const Bridge& o) { return &o != &bar && passes_beside(p, o, s) >= 0; }))
                    continue;
                props.push_back(p);
                ++added;
            }
        }
    }
    sc.columns.insert(sc.columns.end(), props.begin(), props.end());
    return added;
}

}  // namespace scaffold::plan
