#include "plan/coverage.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "layers/regions.hpp"
#include "plan/lean_in.hpp"
#include "plan/pillars.hpp"

namespace scaffold::plan {

namespace {

// Samples of a tip's top loop: its outer edge, half a cell in, and centre.
constexpr int kTipSamples = 16;

}  // namespace

overhang::Overhangs unheld_by_tips(const overhang::Overhangs& overhangs, const Scaffold& scaffold,
                                   const layers::LayerStack& stack, const Obstacles& obs, const Settings& s) {
    if (overhangs.layers.empty()) return {};
    // Tips by height: columns that end touching the model.
    std::vector<const Column*> tips;
    for (const Column& c : scaffold.columns)
        if (c.top == Top::Contact) tips.push_back(&c);
    std::stable_sort(tips.begin(), tips.end(), [](const Column* a, const Column* b) { return a->z1 < b->z1; });
    const layers::BitGrid& proto = overhangs.layers.front().cells;
    std::vector<layers::Region> found;
    for (const overhang::OverhangLayer& ol : overhangs.layers) {
        const layers::Layer& layer = stack.layers[ol.layer];
        // METHOD: support on one of the three layers below L.
        const double h = layer.nominal_height > 0 ? layer.nominal_height : s.layer_height;
        const double z_lo = layer.z - 3 * h - 0.5 * h, z_hi = layer.z - 0.5 * layer.height;
        layers::BitGrid covered = ol.cells.empty_like();
        auto it = std::lower_bound(tips.begin(), tips.end(), z_lo, [](const Column* c, double z) { return c->z1 < z; });
        for (; it != tips.end() && (*it)->z1 <= z_hi; ++it) {
            const Column& c = **it;
            const double r = std::max(0.0, column_radius_at(c, c.z1, s) - s.resolution / 2);
            for (int k = 0; k <= kTipSamples; ++k) {
                const double a = 2 * std::numbers::pi * k / kTipSamples;
                const double x = k == kTipSamples ? c.x1 : c.x1 + r * std::cos(a);
                const double y = k == kTipSamples ? c.y1 : c.y1 + r * std::sin(a);
                // Under the layer's own material (the cell the sample is in).
                if (!obs.disc_clear(ol.layer, x, y, 0.75 * s.resolution)) covered.draw_disc(x, y, s.point_radius - 1e-6);
            }
        }
        layers::BitGrid left = ol.cells;
        left.subtract(covered);
        if (!left.any()) continue;
        for (auto& comp : layers::regions(left, layers::kRegionJoin))
            found.push_back(layers::make_region(std::move(comp), ol.layer, layer.z));
    }
    return overhang::overhangs_of(found, proto, s);
}

std::size_t cover_unheld(Scaffold& scaffold, overhang::SupportPoints& points, const overhang::Overhangs& overhangs,
                         const layers::LayerStack& stack, const Obstacles& obs, const Settings& s, double steer,
                         int rounds) {
    std::size_t added = 0;
    scaffold.uncovered.clear();
    for (int round = 0; round < rounds; ++round) {
        const overhang::SupportPoints more = overhang::place_points(unheld_by_tips(overhangs, scaffold, stack, obs, s), stack, s);
        scaffold.uncovered.clear();
        if (more.points.empty()) break;
        const std::size_t first = points.points.size(), columns = scaffold.columns.size();
        points.points.insert(points.points.end(), more.points.begin(), more.points.end());
        std::vector<int> which(points.points.size() - first);
        for (std::size_t i = 0; i < which.size(); ++i) which[i] = static_cast<int>(first + i);
        // Only tips under the sheet: one beside it holds none of it
        // (METHOD's rule (c)), and the round would only stand it up again.
        add_pillars(scaffold, points, which, stack, obs, s, steer, false);
        // Keep the new points that got a pillar, renumbered in order.
        std::vector<int> index(points.points.size(), -1);
        std::size_t kept = first;
        for (std::size_t i = first; i < points.points.size(); ++i)
            if (!std::binary_search(scaffold.dropped_points.begin(), scaffold.dropped_points.end(), static_cast<int>(i))) {
                index[i] = static_cast<int>(kept);
                points.points[kept++] = points.points[i];
            } else {
                const overhang::SupportPoint& p = points.points[i];
                scaffold.uncovered.push_back({p.x, p.y, stack.layers[p.layer].z});  // the overhanging layer's
            }
        points.points.resize(kept);
        std::erase_if(scaffold.dropped_points, [&](int i) { return i >= static_cast<int>(first); });
        for (std::size_t c = columns; c < scaffold.columns.size(); ++c)
            scaffold.columns[c].point = index[scaffold.columns[c].point];
        added += kept - first;
        if (kept == first) break;
    }
    return added;
}

}  // namespace scaffold::plan
