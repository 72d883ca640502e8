#include "plan/planner.hpp"

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <numbers>
#include <set>
#include <tuple>

#include "plan/pillars.hpp"
#include "toolpath/support_paths.hpp"

namespace scaffold::plan {

double bridge_gain(int supported, double z, double length) { return (supported - 2) * z - length; }

double bridge_score(double gain, int supported, double l_max) { return gain - supported * l_max; }

namespace {

constexpr double kThickness = toolpath::kBridgeThickness;
constexpr double kConnectorRadius = 0.75;  // stays on the 0.9 mm wide bridge bar
constexpr int kMaxRejects = 40;            // candidates tried per greedy step
constexpr int kHeightSteps = 3;            // candidate heights: the highest and 2 steps below

// Largest layer top at or below z (layer_tops ascending), or -1.
double snap_down(const std::vector<double>& tops, double z) {
    auto it = std::upper_bound(tops.begin(), tops.end(), z + 1e-6);
    return it == tops.begin() ? -1 : *(it - 1);
}

// How far a connector may lean per mm of height and still print: a loop may
// shift by the self-supporting reach plus half its bead per layer.
double lean_per_mm(const Settings& s) {
    double slope = std::tan(s.overhang_angle_deg * std::numbers::pi / 180);
    return 0.8 * (s.layer_height * slope + s.support_width / 2) / s.layer_height;
}

using Key = std::tuple<long, long, long, long, long>;
Key key_of(const Candidate& c) {
    auto r = [](double v) { return std::lround(v * 100); };
    return {r(c.x0), r(c.y0), r(c.x1), r(c.y1), r(c.z)};
}

// The `keep` best candidates over all sweep directions, best first.
//
// Cost: for each of D directions, each of the N sweep lines (one through each
// active point) looks at the K points in its 10 mm band: K^2 endpoint pairs
// (those 5..30 mm apart), each with up to K bridge heights, so O(D N K^3)
// per greedy step, with K bounded by the point density (5 mm grid), not N.
// Whether a bridge bar at zb between the two points keeps the gap from the
// model on both of its layers (true without a model).
using BarClear = std::function<bool(double x0, double y0, double x1, double y1, double zb)>;

std::vector<Candidate> top_bridges(const std::vector<Active>& active, const std::vector<double>& tops, const Settings& s,
                                   const std::set<Key>& rejected, std::size_t keep, const BarClear& clear) {
    std::vector<Candidate> best;  // sorted by score, descending
    const std::size_t n = active.size();
    if (n < 3) return best;
    auto worst = [&] { return best.size() < keep ? -std::numeric_limits<double>::infinity() : best.back().score; };
    const double lean = lean_per_mm(s);
    std::vector<double> pu(n), pv(n);
    std::vector<int> by_v(n), band;
    std::vector<std::pair<double, int>> zs;  // carried candidates by z, descending
    for (int k = 0; k < s.sweep_directions; ++k) {
        double th = k * std::numbers::pi / s.sweep_directions;
        double ux = std::cos(th), uy = std::sin(th);
        for (std::size_t i = 0; i < n; ++i) {
            pu[i] = active[i].x * ux + active[i].y * uy;
            pv[i] = -active[i].x * uy + active[i].y * ux;
            by_v[i] = static_cast<int>(i);
        }
        std::stable_sort(by_v.begin(), by_v.end(), [&](int a, int b) { return pv[a] < pv[b]; });
        std::size_t lo = 0, hi = 0;
        for (std::size_t qi = 0; qi < n; ++qi) {
            // The sweep line through point q; its band holds the points whose
            // anchoring segments (5 mm either side) it crosses.
            double v0 = pv[by_v[qi]];
            while (pv[by_v[lo]] < v0 - s.bridge_max_offset) ++lo;
            while (hi < n && pv[by_v[hi]] <= v0 + s.bridge_max_offset) ++hi;
            band.assign(by_v.begin() + static_cast<long>(lo), by_v.begin() + static_cast<long>(hi));
            std::stable_sort(band.begin(), band.end(), [&](int a, int b) { return pu[a] < pu[b]; });
            for (std::size_t m = 0; m < band.size(); ++m) {
                zs.clear();
                for (std::size_t e = m; e < band.size(); ++e) {
                    int pe = band[e];
                    double len = pu[pe] - pu[band[m]];
                    if (len > s.bridge_max_length) break;
                    zs.emplace_back(active[pe].z, pe);
                    std::inplace_merge(zs.begin(), zs.end() - 1, zs.end(),
                                       [](const auto& a, const auto& b) { return a.first > b.first; });
                    if (len < s.bridge_min_length || zs.size() < 3) continue;
                    // For each count c, the highest bridge that has c points at
                    // least the drop above its top.
                    // No height can beat the kept candidates: skip the pair.
                    double bound = static_cast<double>(zs.size() - 2) * (zs.front().first - s.bridge_min_drop) - len;
                    if (bound <= worst()) continue;
                    for (std::size_t c = 3; c <= zs.size(); ++c) {
                      // Equal heights give the same bridges: take the last of a run.
                      if (c < zs.size() && zs[c].first == zs[c - 1].first) continue;
                      // The highest height first, then every step below it.
                      double z_hi = zs[c - 1].first - s.bridge_min_drop - kThickness;
                      for (int drop = 0; drop < kHeightSteps; ++drop) {
                        double zb = snap_down(tops, z_hi - drop * s.bridge_height_step);
                        if (zb <= 0) break;
                        int carried = 0;
                        double l_max = 0;
                        for (const auto& [pz, pi] : zs) {
                            double rise = pz - zb - kThickness;
                            double side = std::abs(pv[pi] - v0);
                            if (rise < s.bridge_min_drop - 1e-9 || side > lean * rise) continue;
                            ++carried;
                            l_max = std::max(l_max, side + (pz - zb));
                        }
                        double gain = bridge_gain(carried, zb, len);
                        if (gain <= 0) continue;
                        double score = bridge_score(gain, carried, l_max);
                        if (score <= worst()) continue;
                        Candidate cand;
                        cand.x0 = pu[band[m]] * ux - v0 * uy;
                        cand.y0 = pu[band[m]] * uy + v0 * ux;
                        cand.x1 = pu[pe] * ux - v0 * uy;
                        cand.y1 = pu[pe] * uy + v0 * ux;
                        cand.z = zb;
                        if (rejected.count(key_of(cand))) continue;
                        if (clear && !clear(cand.x0, cand.y0, cand.x1, cand.y1, zb)) continue;
                        cand.gain = gain;
                        cand.score = score;
                        cand.l_max = l_max;
                        for (const auto& [pz, pi] : zs) {
                            double rise = pz - zb - kThickness;
                            double side = std::abs(pv[pi] - v0);
                            if (rise >= s.bridge_min_drop - 1e-9 && side <= lean * rise) cand.carried.push_back(pi);
                        }
                        std::sort(cand.carried.begin(), cand.carried.end());
                        // Insert after equal scores: earlier finds win ties.
                        auto at = std::upper_bound(best.begin(), best.end(), score,
                                                   [](double sc, const Candidate& b) { return sc > b.score; });
                        best.insert(at, std::move(cand));
                        if (best.size() > keep) best.pop_back();
                      }
                    }
                }
            }
        }
    }
    return best;
}

// Layers by z (purge lines left out), to find the layer above a height.
class LayersByZ {
public:
    explicit LayersByZ(const layers::LayerStack& stack) {
        for (int i = 0; i < static_cast<int>(stack.layers.size()); ++i)
            if (!stack.layers[i].purge) by_z_.emplace_back(stack.layers[i].z, i);
        std::stable_sort(by_z_.begin(), by_z_.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
    }
    // The layer whose bottom is at z (the first layer above z), or -1.
    int above(double z) const {
        auto it = std::upper_bound(by_z_.begin(), by_z_.end(), z + 1e-6,
                                   [](double v, const std::pair<double, int>& e) { return v < e.first; });
        return it == by_z_.end() ? -1 : it->second;
    }

private:
    std::vector<std::pair<double, int>> by_z_;
};

// The top layer of the support under an active point: beneath the
// overhang (less the top gap) for a support point, the bridge's own layer
// beneath for a bridge end.
int top_layer_of(const Active& a, const overhang::SupportPoints& pts, const layers::LayerStack& stack,
                 const LayersByZ& by_z, const Settings& s) {
    if (a.point < 0) {
        int above = by_z.above(a.z);
        return above < 0 ? -1 : stack.layers[above].below;
    }
    int t = stack.layers[pts.points[a.point].layer].below;
    for (int k = 0; k < s.top_gap_layers && t >= 0; ++k) t = stack.layers[t].below;
    return t;
}

// A slanted column from the bridge top up to (tx, ty) under the active
// point; nullopt if it would come within the gap of the model on some layer.
std::optional<Column> connector_to(const Candidate& b, const Active& a, double tx, double ty, int top_layer,
                                   const layers::LayerStack& stack, const Obstacles& obs, const Settings& s) {
    if (top_layer < 0) return std::nullopt;
    double dx = b.x1 - b.x0, dy = b.y1 - b.y0, len2 = dx * dx + dy * dy;
    double t = len2 > 0 ? std::clamp(((tx - b.x0) * dx + (ty - b.y0) * dy) / len2, 0.0, 1.0) : 0;
    Column c;
    c.x0 = b.x0 + dx * t;
    c.y0 = b.y0 + dy * t;
    c.z0 = b.z + kThickness;
    c.x1 = tx;
    c.y1 = ty;
    c.z1 = stack.layers[top_layer].z;
    c.radius = kConnectorRadius;
    c.base = Base::Bridge;
    c.top = a.point >= 0 ? Top::Contact : Top::Bridge;
    c.contact_z = a.point >= 0 ? c.z1 : 0;
    c.point = a.point;
    if (c.z1 <= c.z0 + 1e-6) return std::nullopt;
    if (std::hypot(c.x1 - c.x0, c.y1 - c.y0) > lean_per_mm(s) * (c.z1 - c.z0)) return std::nullopt;
    for (int l = top_layer; l >= 0 && stack.layers[l].z > c.z0 + 1e-6; l = stack.layers[l].below) {
        double z = stack.layers[l].z, x, y;
        column_centre_at(c, z, x, y);
        bool tip = c.contact_z > 0 && z > c.contact_z - 2 * s.layer_height + 1e-6;
        if (!obs.disc_clear(l, x, y, column_radius_at(c, z, s) + (tip ? 0.2 : s.xy_gap))) return std::nullopt;
    }
    return c;
}

// The connector to the point itself, or, for a support point whose straight
// connector meets the model, to a tip up to 1.5 mm away (it still holds the
// point: the point radius is 3.5 mm). Bridge ends must be met exactly.
std::optional<Column> connector(const Candidate& b, const Active& a, int top_layer, const layers::LayerStack& stack,
                                const Obstacles& obs, const Settings& s) {
    if (auto c = connector_to(b, a, a.x, a.y, top_layer, stack, obs, s)) return c;
    if (a.point < 0) return std::nullopt;
    for (double d : {0.5, 1.0, 1.5})
        for (int k = 0; k < 8; ++k) {
            double ang = k * std::numbers::pi / 4;
            if (auto c = connector_to(b, a, a.x + d * std::cos(ang), a.y + d * std::sin(ang), top_layer, stack, obs, s))
                return c;
        }
    return std::nullopt;
}

}  // namespace

Candidate best_bridge(const std::vector<Active>& active, const std::vector<double>& layer_tops, const Settings& s) {
    auto top = top_bridges(active, layer_tops, s, {}, 1, nullptr);
    return top.empty() ? Candidate{} : top.front();
}

Scaffold plan_scaffold(const overhang::SupportPoints& points, const layers::LayerStack& stack, const Obstacles& obs,
                       const Settings& s) {
    Scaffold out;
    std::vector<double> tops;
    for (const auto& l : stack.layers)
        if (!l.purge) tops.push_back(l.z);
    std::sort(tops.begin(), tops.end());
    tops.erase(std::unique(tops.begin(), tops.end()), tops.end());

    const LayersByZ by_z(stack);
    std::vector<Active> active;
    for (std::size_t i = 0; i < points.points.size(); ++i)
        active.push_back({points.points[i].x, points.points[i].y, points.points[i].z, static_cast<int>(i)});

    // Greedy (METHOD.md step 4): take the best bridge that can really be
    // built (clear of the model, ends standing), snap, repeat.
    // A bar is printed on the two layers above zb, reaching into the pillar
    // tops at both ends.
    const BarClear bar_clear = [&](double x0, double y0, double x1, double y1, double zb) {
        int first = by_z.above(zb);
        int second = first < 0 ? -1 : by_z.above(stack.layers[first].z);
        if (first < 0 || second < 0) return false;
        double len = std::hypot(x1 - x0, y1 - y0);
        double ex = (x1 - x0) / len * s.pillar_radius * 0.5, ey = (y1 - y0) / len * s.pillar_radius * 0.5;
        return obs.line_clear(first, x0 - ex, y0 - ey, x1 + ex, y1 + ey) &&
               obs.line_clear(second, x0 - ex, y0 - ey, x1 + ex, y1 + ey);
    };
    std::set<Key> rejected;
    int rejects_left = 2 * kMaxRejects;  // bounded work when the model is in the way everywhere
    while (rejects_left > 0) {
        std::vector<Candidate> cands = top_bridges(active, tops, s, rejected, kMaxRejects, bar_clear);
        if (cands.empty()) break;
        bool placed = false;
        for (const Candidate& c : cands) {
        int first = by_z.above(c.z);
        int second = first < 0 ? -1 : by_z.above(stack.layers[first].z);
        bool ok = first >= 0 && second >= 0;
        double ex = 0, ey = 0;
        if (ok) {
            double len = std::hypot(c.x1 - c.x0, c.y1 - c.y0);
            ex = (c.x1 - c.x0) / len * s.pillar_radius * 0.5;
            ey = (c.y1 - c.y0) / len * s.pillar_radius * 0.5;
        }
        for (int l : {first, second})
            ok = ok && obs.segment_clear(l, c.x0 - ex, c.y0 - ey, c.x1 + ex, c.y1 + ey, s.support_width + s.xy_gap);
        std::vector<Column> connectors;
        std::vector<int> carried;
        if (ok) {
            for (int ai : c.carried) {
                auto col = connector(c, active[ai], top_layer_of(active[ai], points, stack, by_z, s), stack, obs, s);
                if (!col) continue;
                connectors.push_back(*col);
                carried.push_back(ai);
            }
            ok = bridge_gain(static_cast<int>(carried.size()), c.z, std::hypot(c.x1 - c.x0, c.y1 - c.y0)) > 0;
        }
        ok = ok && drop_pillar(c.x0, c.y0, first, Top::Bridge, stack, obs, s) &&
             drop_pillar(c.x1, c.y1, first, Top::Bridge, stack, obs, s);
        if (!ok) {
            rejected.insert(key_of(c));
            --rejects_left;
            continue;
        }
        Bridge br{c.x0, c.y0, c.x1, c.y1, c.z, {}, c.gain, c.score};
        for (int ai : carried)
            if (active[ai].point >= 0) br.points.push_back(active[ai].point);
        out.bridges.push_back(br);
        out.columns.insert(out.columns.end(), connectors.begin(), connectors.end());
        std::vector<Active> next;
        for (std::size_t i = 0; i < active.size(); ++i)
            if (!std::binary_search(carried.begin(), carried.end(), static_cast<int>(i))) next.push_back(active[i]);
        next.push_back({c.x0, c.y0, c.z, -1});
        next.push_back({c.x1, c.y1, c.z, -1});
        active = std::move(next);
        placed = true;
        break;
        }
        if (!placed && cands.size() < static_cast<std::size_t>(kMaxRejects)) break;
    }

    // Everything still active stands on a pillar.
    for (const Active& a : active) {
        int overhang_layer = a.point >= 0 ? points.points[a.point].layer : by_z.above(a.z);
        auto chain = overhang_layer < 0 ? std::nullopt
                                        : drop_pillar(a.x, a.y, overhang_layer, a.point >= 0 ? Top::Contact : Top::Bridge,
                                                      stack, obs, s);
        if (!chain) {
            if (a.point >= 0) out.dropped_points.push_back(a.point);
            continue;
        }
        for (Column& col : *chain) {
            col.point = a.point;
            out.columns.push_back(col);
        }
    }
    std::sort(out.dropped_points.begin(), out.dropped_points.end());
    return out;
}

}  // namespace scaffold::plan
