#include "plan/braces.hpp"

#include <algorithm>
#include <array>
#include <bit>
#include <climits>
#include <cmath>
#include <limits>
#include <numbers>
#include <optional>
#include <tuple>

#include "plan/candidates.hpp"
#include "plan/pillars.hpp"
#include "plan/planner.hpp"
#include "plan/stiffness.hpp"
#include "plan/walk.hpp"

namespace scaffold::plan {

namespace {

constexpr double kEps = 1e-6;
// Every angle of a tie's triangle at least this: three columns not on one
// line (METHOD: two of their directions from the node 60 degrees apart).
constexpr double kMinAngleDeg = 30.0;
// mm: a partner nearer W's tie than this makes no side of a triangle (bars
// need their ends' loops apart, 2 mm at the least).
constexpr double kMinSide = 1.0;

// mm: two beads' edges nearer than this may join into one island.
constexpr double kTouch = 0.3;

// The smallest angle of triangle abc, degrees.
double min_angle(double ax, double ay, double bx, double by, double cx, double cy) {
    auto angle = [](double px, double py, double qx, double qy, double rx, double ry) {
        const double ux = qx - px, uy = qy - py, vx = rx - px, vy = ry - py;
        const double d = std::hypot(ux, uy) * std::hypot(vx, vy);
        return d > 0 ? std::acos(std::clamp((ux * vx + uy * vy) / d, -1.0, 1.0)) * 180 / std::numbers::pi : 0.0;
    };
    return std::min({angle(ax, ay, bx, by, cx, cy), angle(bx, by, cx, cy, ax, ay), angle(cx, cy, ax, ay, bx, by)});
}

// A loop's centre, outer edge and inner edge (0: a filled raft).
struct Ring {
    double x, y, r, inner;
};

Ring ring_of(const Column& c, double x, double y, double r, double zc, const Settings& s) {
    const double w = s.support_width;
    const bool raft = c.raft_size > 0 && zc <= s.first_layer_height + kEps;
    return {x, y, r, raft ? 0.0 : std::max(0.0, r - (second_wall(c, r, w) ? 1.9 : 1.0) * w)};
}

// A pillar's centre and outer radius on the layer at zc, or at its top
// where it ends under a bar at b.
std::optional<Ring> ring_at(const PillarChain& p, const Scaffold& sc, const Settings& s, double zc, double b) {
    if (p.base > zc) return std::nullopt;
    if (const Column* c = chain_piece_at(p, sc, zc)) {
        double x, y;
        column_centre_at(*c, zc, x, y);
        return ring_of(*c, x, y, column_radius_at(*c, zc, s), zc, s);
    }
    if (std::abs(p.top - b) < kEps) {
        const Column& c = sc.columns[p.pieces.back()];
        return ring_of(c, c.x1, c.y1, column_radius_at(c, c.z1, s), c.z1, s);
    }
    return std::nullopt;
}

}  // namespace

bool rings_touch(const PillarChain& a, const PillarChain& b, const Scaffold& sc, const Settings& s, double z) {
    const auto p = ring_at(a, sc, s, z, -1), q = ring_at(b, sc, s, z, -1);
    if (!p || !q) return false;
    const double d = std::hypot(p->x - q->x, p->y - q->y);
    const Ring& small = p->r <= q->r ? *p : *q;
    const Ring& big = p->r <= q->r ? *q : *p;
    return d <= p->r + q->r + s.resolution && d + small.r + s.resolution >= big.inner;
}

bool stacked_on_previous(const Scaffold& sc, int i) {
    if (i <= 0 || sc.columns[i].base != Base::Column) return false;
    const Column &c = sc.columns[i], &prev = sc.columns[i - 1];
    return std::abs(c.z0 - prev.z1) < kEps && std::hypot(c.x0 - prev.x1, c.y0 - prev.y1) < kEps;
}

const Column* chain_piece_at(const PillarChain& chain, const Scaffold& sc, double z) {
    for (int i : chain.pieces) {
        const Column& c = sc.columns[i];
        if (z > c.z0 + kEps && z <= c.z1 + kEps) return &c;
    }
    return nullptr;
}

std::vector<PillarChain> pillar_chains(const Scaffold& sc) {
    std::vector<PillarChain> out;
    bool open = false;
    for (int i = 0; i < static_cast<int>(sc.columns.size()); ++i) {
        const Column& c = sc.columns[i];
        if (c.base == Base::Bed || c.base == Base::Model) {
            out.push_back({{i}, c.z0, c.z1, std::max(c.z1, c.hold_z)});
            open = true;
            continue;
        }
        if (open && stacked_on_previous(sc, i)) {
            PillarChain& p = out.back();
            p.pieces.push_back(i);
            p.top = c.z1;
            p.hold = std::max({p.hold, c.z1, c.hold_z});
            continue;
        }
        open = false;
    }
    return out;
}

double column_inertia_at(const Column& c, double z, const Settings& s) {
    const double w = s.support_width, r = column_radius_at(c, z, s);
    // The second wall the toolpaths give a wide column not sized for the rule.
    return ring_inertia(r, w) + (second_wall(c, r, w) ? ring_inertia(r - w * 0.9, w) : 0.0);
}

double chain_compliance(const PillarChain& chain, double top, const Scaffold& sc, const layers::LayerStack& stack,
                        const Settings& s, double from, double to) {
    double compliance = 0;
    for (const layers::Layer& layer : stack.layers) {
        if (layer.purge || layer.z > std::min(top, to) + kEps || layer.z <= from + kEps) continue;
        const Column* c = chain_piece_at(chain, sc, layer.z);
        if (!c) continue;
        const double arm = top - (layer.z - layer.height / 2);
        compliance += arm * arm * layer.height / (s.modulus * column_inertia_at(*c, layer.z, s));
    }
    return compliance;
}

std::vector<ColumnMeeting> column_meetings(const std::vector<PillarChain>& chains, const Scaffold& sc,
                                           const layers::LayerStack& stack, const Settings& s) {
    const std::size_t n = chains.size();
    const double w = s.support_width;
    std::vector<ColumnMeeting> out;
    std::vector<double> tops;
    for (const layers::Layer& layer : stack.layers)
        if (!layer.purge) tops.push_back(layer.z);
    std::sort(tops.begin(), tops.end());
    // A bar of the plan (a brace ties at a node, which METHOD counts apart)
    // on its first layer: every pillar it passes through or rests on.
    for (std::size_t bi = 0; bi < sc.bridges.size(); ++bi) {
        const Bridge& br = sc.bridges[bi];
        const auto first = std::upper_bound(tops.begin(), tops.end(), br.z + kEps);
        if (br.brace || first == tops.end() || *first > br.z + kBarThickness + kEps) continue;
        const layers::Segment seg{static_cast<float>(br.x0), static_cast<float>(br.y0), static_cast<float>(br.x1),
                                  static_cast<float>(br.y1)};
        std::vector<int> on;
        for (std::size_t i = 0; i < n; ++i)
            if (const auto r = ring_at(chains[i], sc, s, *first, br.z))
                if (layers::segment_distance(r->x, r->y, seg) <= r->r + w) on.push_back(static_cast<int>(i));
        for (std::size_t a = 0; a < on.size(); ++a)
            for (std::size_t b = a + 1; b < on.size(); ++b) out.push_back({br.z, on[a], on[b], static_cast<int>(bi)});
    }
    // Loops touching: pairs whose boxes over their height come within a
    // bead, layer by layer; a run of touching layers meets at its start.
    struct Box {
        double x0, y0, x1, y1;
    };
    std::vector<Box> boxes(n, Box{1e300, 1e300, -1e300, -1e300});
    for (std::size_t i = 0; i < n; ++i)
        for (int k : chains[i].pieces) {
            const Column& c = sc.columns[k];
            const double r = std::max({column_radius_at(c, c.z0, s), column_radius_at(c, c.z1, s), c.foot_radius});
            Box& bx = boxes[i];
            bx = {std::min({bx.x0, c.x0 - r, c.x1 - r}), std::min({bx.y0, c.y0 - r, c.y1 - r}),
                  std::max({bx.x1, c.x0 + r, c.x1 + r}), std::max({bx.y1, c.y0 + r, c.y1 + r})};
        }
    for (std::size_t i = 0; i < n; ++i)
        for (std::size_t j = i + 1; j < n; ++j) {
            const Box &a = boxes[i], &b = boxes[j];
            if (a.x0 > b.x1 + w || b.x0 > a.x1 + w || a.y0 > b.y1 + w || b.y0 > a.y1 + w) continue;
            bool touching = false;
            for (double z : tops) {
                const bool touch = rings_touch(chains[i], chains[j], sc, s, z);
                if (touch && !touching) out.push_back({z, static_cast<int>(i), static_cast<int>(j)});
                if (touch) out.back().until = z;
                touching = touch;
            }
        }
    return out;
}

bool distinct_columns(const std::vector<ColumnMeeting>& meetings, int chain_count, const std::vector<int>& ids, double lo,
                      double b) {
    std::vector<int> parent(chain_count);
    for (int k = 0; k < chain_count; ++k) parent[k] = k;
    auto root = [&](int k) {
        while (parent[k] != k) k = parent[k] = parent[parent[k]];
        return k;
    };
    for (const ColumnMeeting& m : meetings)
        if (m.z > lo + kEps && m.z < b - kEps) parent[root(m.a)] = root(m.b);
    for (std::size_t a = 0; a < ids.size(); ++a)
        for (std::size_t c = a + 1; c < ids.size(); ++c)
            if (ids[a] < chain_count && ids[c] < chain_count && root(ids[a]) == root(ids[c])) return false;
    return true;
}

double tied_stiffness(const std::array<const PillarChain*, 3>& cols, const std::array<int, 3>& ids,
                      const std::vector<double>& levels, double give, const std::vector<ColumnMeeting>& meetings,
                      int chain_count, const Scaffold& sc, const layers::LayerStack& stack, const Settings& s,
                      const std::array<const std::vector<double>*, 3>& earlier, double* weakest_corner) {
    // A path down: a node's give, then pieces of pillars, each between two heights.
    struct Piece {
        const PillarChain* chain;
        double from, to;
    };
    struct Down {
        double c0 = 0;
        std::vector<Piece> pieces;
    };
    auto compliance = [&](const Down& d, double z) {
        double c = d.c0;
        for (const Piece& p : d.pieces) c += chain_compliance(*p.chain, z, sc, stack, s, p.from, p.to);
        return c;
    };
    std::array<Down, 3> down;
    for (int i = 0; i < 3; ++i) down[i].pieces.push_back({cols[i], -1e300, 1e300});
    if (weakest_corner) *weakest_corner = std::numeric_limits<double>::infinity();
    double lo = -1e300;
    // A tie that is no node (a twig among them) joins the three into one
    // island there: above it they are columns that meet lower down, one
    // column (METHOD), until a node lets each start afresh.
    bool joined = false;
    for (double b : levels) {
        std::array<double, 3> k{};
        double k_most = 0;  // the strongest's k, as high as an earlier node could make it
        for (int i = 0; i < 3; ++i) {
            down[i].pieces.back().to = b;
            k[i] = 1 / compliance(down[i], b);
            k_most = std::max(k_most, k[i]);
            if (earlier[i])
                for (double e : *earlier[i])
                    if (e < b - kEps) k_most = std::max(k_most, 1 / chain_compliance(*cols[i], b, sc, stack, s, e, b));
        }
        if (weakest_corner) *weakest_corner = std::min(*weakest_corner, *std::min_element(k.begin(), k.end()));
        const int best = static_cast<int>(std::max_element(k.begin(), k.end()) - k.begin());
        const bool node = !joined && distinct_columns(meetings, chain_count, {ids[0], ids[1], ids[2]}, lo, b) &&
                          std::all_of(k.begin(), k.end(), [&](double ki) { return ki >= kBraceColumnShare * k_most; });
        joined = !node;
        lo = b;
        const Down stiffest = down[best];
        for (int i = 0; i < 3; ++i) {
            down[i] = node ? Down{1 / (k[0] + k[1] + k[2]), {}} : stiffest;
            down[i].pieces.push_back({cols[i], b, 1e300});
        }
    }
    return 1 / (compliance(down[0], cols[0]->hold) + give);
}

namespace {

// The stiffness of pillar wi at its own top as METHOD's validator walks
// it: where it met another lower down, they are one island there (a bar
// on both, or loops touching up to the last layer of the run), and the
// walk goes on down the stiffer of the two, from the highest such layer.
double own_top_stiffness(int wi, const std::vector<PillarChain>& chains, const std::vector<ColumnMeeting>& meets,
                         const Scaffold& sc, const layers::LayerStack& stack, const Settings& s,
                         const std::vector<std::pair<double, int>>& tops) {
    const PillarChain& W = chains[wi];
    const double below_top = W.top - 1.5 * s.layer_height;
    double zm = -1e300;
    int other = -1;
    for (const ColumnMeeting& m : meets) {
        if ((m.a != wi && m.b != wi) || m.z >= below_top) continue;
        const int o = m.a == wi ? m.b : m.a;
        double z = m.z;
        for (auto it = std::upper_bound(tops.begin(), tops.end(), std::make_pair(m.z + kEps, INT_MAX));
             it != tops.end() && it->first < below_top && rings_touch(W, chains[o], sc, s, it->first); ++it)
            z = it->first;
        if (z > zm) {
            zm = z;
            other = o;
        }
    }
    double below = chain_compliance(W, W.top, sc, stack, s, -1e300, zm);
    if (other >= 0) below = std::min(below, chain_compliance(chains[other], W.top, sc, stack, s, -1e300, zm));
    return 1 / (chain_compliance(W, W.top, sc, stack, s, zm) + below);
}

// The column W (under a bar end) dropped again from the same top, as wide
// as fits at any share of the Standing rule's taper; its pieces replaced
// where that stands stiffer at W's hold. Only a column whose own top falls
// short as the validator walks it: one that met a stiffer column lower down
// stands as that one does (elephant plates: 8 % more filament for nothing).
// Returns W's stiffness at its own top as own_top_stiffness walks it,
// widened (by the ratio of the summed compliances) or not; infinity where
// W is not looked at (no bar end, or standing by that walk).
double widen_untied(Scaffold& sc, int wi, const std::vector<PillarChain>& chains, const std::vector<ColumnMeeting>& meets,
                    const layers::LayerStack& stack, const Obstacles& obs, const Settings& s,
                    const std::vector<std::pair<double, int>>& tops) {
    constexpr double kNotLooked = std::numeric_limits<double>::infinity();
    const PillarChain& W = chains[wi];
    const Column top = sc.columns[W.pieces.back()], foot = sc.columns[W.pieces.front()];
    if (top.top != Top::Bridge || W.pieces.back() - W.pieces.front() + 1 != static_cast<int>(W.pieces.size()))
        return kNotLooked;
    const double own = own_top_stiffness(wi, chains, meets, sc, stack, s, tops);
    if (own >= kGiveMargin * s.min_stiffness) return kNotLooked;
    // Not a trunk: a branch standing on W's loop where it is now would be
    // left in the air by a way down that steps elsewhere.
    for (int k = 0; k < static_cast<int>(sc.columns.size()); ++k) {
        const Column& c = sc.columns[static_cast<std::size_t>(k)];
        if (c.base != Base::Column || (k >= W.pieces.front() && k <= W.pieces.back()) || stacked_on_previous(sc, k))
            continue;
        if (const auto r = ring_at(W, sc, s, c.z0, -1);
            r && std::hypot(c.x0 - r->x, c.y0 - r->y) <= r->r + column_radius_at(c, c.z0, s) + s.support_width)
            return own;
    }
    const auto above = std::upper_bound(tops.begin(), tops.end(), std::make_pair(top.z1 + kEps, INT_MAX));
    if (above == tops.end()) return own;
    const bool thin_above = top.contact_z > 0 && top.hold_z > top.z1 + kEps;
    auto chain = drop_pillar(top.x1, top.y1, above->second, Top::Bridge, stack, obs, s, nullptr, TipPlaces::Any, true,
                             top.hold_z, foot.give, thin_above, true);
    if (!chain || chain->empty()) return own;
    const Column& new_top = chain->back();
    if (std::abs(new_top.z1 - top.z1) > kEps || std::hypot(new_top.x1 - top.x1, new_top.y1 - top.y1) > kEps) return own;
    // Judged as the braces judge W: its pieces' loops, summed layer by layer.
    const std::size_t before = sc.columns.size();
    PillarChain wider{{}, chain->front().z0, new_top.z1, W.hold};
    for (Column& c : *chain) {
        c.point = foot.point;
        wider.pieces.push_back(static_cast<int>(sc.columns.size()));
        sc.columns.push_back(c);
    }
    const double was = chain_compliance(W, W.hold, sc, stack, s), now = chain_compliance(wider, W.hold, sc, stack, s);
    sc.columns.resize(before);
    if (!(now < was - kEps)) return own;
    const auto first = sc.columns.begin() + W.pieces.front();
    sc.columns.insert(sc.columns.erase(first, first + static_cast<std::ptrdiff_t>(W.pieces.size())), chain->begin(),
                      chain->end());
    return own * was / now;
}

}  // namespace

int add_braces(Scaffold& sc, const layers::LayerStack& stack, const Obstacles& obs, const Settings& s,
               const Forbidden& forbidden, std::vector<std::size_t>* short_of_rule, BraceAnswers* answers,
               std::vector<std::size_t>* braced_bars, std::vector<ShortColumn>* short_columns) {
    const double target = target_stiffness(s);
    if (!(target > 0)) return 0;
    std::vector<PillarChain> chains = pillar_chains(sc);
    // Layer tops, ascending (a bar is printed on the layers whose top lies
    // in (z, z + kBarThickness]).
    std::vector<std::pair<double, int>> tops;
    for (int l = 0; l < static_cast<int>(stack.layers.size()); ++l)
        if (!stack.layers[l].purge) tops.emplace_back(stack.layers[l].z, l);
    std::sort(tops.begin(), tops.end());
    auto snap_down = [&](double z) {
        auto it = std::upper_bound(tops.begin(), tops.end(), std::make_pair(z + kEps, -1));
        return it == tops.begin() ? -1.0 : std::prev(it)->first;
    };
    auto bar_layers = [&](double z) {
        std::vector<std::pair<double, int>> out;
        for (auto it = std::upper_bound(tops.begin(), tops.end(), std::make_pair(z + kEps, -1));
             it != tops.end() && it->first <= z + kBarThickness + kEps; ++it)
            out.push_back(*it);
        return out;
    };
    const double w = s.support_width;
    const double keep = w + s.xy_gap + s.resolution / 2;  // the bar's half width (two lines), the gap, half a cell
    // A column's centre and loop centre line on a bar's first layer; at the
    // top of a column that ends under the bar (a helper), its top's centre.
    struct At {
        double x, y, rc;
    };
    auto at = [&](const PillarChain& p, double b, double zc) -> std::optional<At> {
        if (p.base > b - kEps) return std::nullopt;
        if (const Column* c = chain_piece_at(p, sc, zc)) {
            At a{0, 0, loop_shape(column_radius_at(*c, zc, s), w).centre_radius};
            column_centre_at(*c, zc, a.x, a.y);
            return a;
        }
        if (std::abs(p.top - b) < kEps) {
            const Column& c = sc.columns[p.pieces.back()];
            return At{c.x1, c.y1, 0.0};
        }
        return std::nullopt;
    };
    // The corners of the triangles placed, at each height they are tied.
    struct Placed {
        double b, x, y, rc;
    };
    std::vector<Placed> placed;
    // The bar between two columns at height b, from loop to loop, when it is clear.
    auto bar = [&](const At& p, const At& q, double b) -> std::optional<Bridge> {
        const double d = std::hypot(q.x - p.x, q.y - p.y);
        if (d <= p.rc + q.rc + 2 * w + 0.5 || d > kBraceReach) return std::nullopt;
        const double ux = (q.x - p.x) / d, uy = (q.y - p.y) / d;
        Bridge br{p.x + ux * p.rc, p.y + uy * p.rc, q.x - ux * q.rc, q.y - uy * q.rc, b, {}, 0, 0, true};
        if (near_forbidden(forbidden, br, s.layer_height)) return std::nullopt;
        for (const auto& [z, l] : bar_layers(b))
            if (!obs.segment_clear(l, br.x0, br.y0, br.x1, br.y1, keep)) return std::nullopt;
        return br;
    };
    // Whether two pillars stand apart at their bases: columns sharing a raft
    // or a foot are one column (METHOD: columns that meet lower down), and
    // one column tied to itself is no brace.
    auto bases_apart = [&](const PillarChain& p, const PillarChain& q) {
        const Column &a = sc.columns[p.pieces.front()], &b = sc.columns[q.pieces.front()];
        const double dx = std::abs(a.x0 - b.x0), dy = std::abs(a.y0 - b.y0);
        if (a.base == Base::Bed && b.base == Base::Bed && a.raft_size > 0 && b.raft_size > 0 &&
            std::max(dx, dy) <= (a.raft_size + b.raft_size) / 2 + 2 * w)
            return false;
        auto reach = [&](const Column& c) { return std::max({c.radius, c.foot_radius, c.raft_size / std::numbers::sqrt2}); };
        return std::hypot(dx, dy) > reach(a) + reach(b) + 2 * w || std::max(dx, dy) > (a.raft_size + b.raft_size) / 2 + 2 * w;
    };
    const std::vector<ColumnMeeting> meets = column_meetings(chains, sc, stack, s);
    const int n = static_cast<int>(chains.size());
    // The heights at which each chain (by index; helpers too, once placed)
    // is tied already.
    std::vector<std::vector<double>> ties_of(chains.size());
    // A chain's earlier ties: W's own (ids[0] is always its index), or a
    // placed chain's (not a helper being tried, whose id may be taken).
    auto earlier_ties = [&](const PillarChain& c, int id, bool is_w) -> const std::vector<double>* {
        if (id < 0 || id >= static_cast<int>(ties_of.size()) || (!is_w && &c != &chains[id])) return nullptr;
        return &ties_of[id];
    };
    // W's stiffness at its top, tied with P and Q (indices into chains, or
    // helpers past them) at these levels, meets the rule, and so does each
    // corner's island under each tie (a helper's top, standing on its part
    // from the tie below: shelf at --min-stiffness 10, 6.7 N/mm there).
    auto nodes_stand = [&](const PillarChain& W, const PillarChain& P, const PillarChain& Q,
                           const std::vector<double>& levels, double give, const std::array<int, 3>& ids) {
        double corner = 0;
        return tied_stiffness({&W, &P, &Q}, ids, levels, give, meets, n, sc, stack, s,
                              {earlier_ties(W, ids[0], true), earlier_ties(P, ids[1], false),
                               earlier_ties(Q, ids[2], false)},
                              &corner) >= s.min_stiffness &&
               corner >= s.min_stiffness;
    };
    // The triangle W, P, Q tied at every level: its bars, or none if one
    // fails or its nodes would not stand.
    auto triangle = [&](const PillarChain& W, const PillarChain& P, const PillarChain& Q,
                        const std::vector<double>& levels, double give, const std::array<int, 3>& ids) -> std::vector<Bridge> {
        if (!bases_apart(W, P) || !bases_apart(W, Q) || !bases_apart(P, Q)) return {};
        std::vector<Bridge> out;
        for (double b : levels) {
            const double zc = bar_layers(b).front().first;
            const auto a = at(W, b, zc), p = at(P, b, zc), q = at(Q, b, zc);
            if (!a || !p || !q || min_angle(a->x, a->y, p->x, p->y, q->x, q->y) < kMinAngleDeg) return {};
            auto ap = bar(*a, *p, b), aq = bar(*a, *q, b), pq = bar(*p, *q, b);
            if (!ap || !aq || !pq) return {};
            // Apart from every triangle tied at the same height: bars or
            // corners that touch make one island of both, whose columns
            // METHOD judges from its own centroid (two triangles sharing a
            // corner, 5 columns strung east to west from it: no brace, and
            // each column above walks down to the bed; Cura's four bunnies,
            // 1.36 N/mm).
            const std::array<At, 3> corners{*a, *p, *q};
            const std::array<Bridge, 3> bars{*ap, *aq, *pq};
            for (const Placed& c : placed) {
                if (std::abs(c.b - b) > kEps) continue;
                for (const At& k : corners)
                    if (std::hypot(k.x - c.x, k.y - c.y) < k.rc + c.rc + 2 * w + kTouch) return {};
                for (const Bridge& nb : bars)
                    if (layers::segment_distance(c.x, c.y, nb.x0, nb.y0, nb.x1, nb.y1) < c.rc + 1.5 * w + kTouch) return {};
            }
            for (const Bridge& ob : sc.bridges) {
                if (!ob.brace || std::abs(ob.z - b) > kEps) continue;
                for (const At& k : corners)
                    if (layers::segment_distance(k.x, k.y, ob.x0, ob.y0, ob.x1, ob.y1) < k.rc + 1.5 * w + kTouch) return {};
                for (const Bridge& nb : bars)
                    if (layers::segments_distance(nb.x0, nb.y0, nb.x1, nb.y1, ob.x0, ob.y0, ob.x1, ob.y1) < 2 * w + kTouch)
                        return {};
            }
            out.insert(out.end(), bars.begin(), bars.end());
        }
        // Last: the walk sums every layer of the three pillars at each tie.
        if (!nodes_stand(W, P, Q, levels, give, ids)) return {};
        return out;
    };
    // Whether a helper's pieces keep a bead clear of every column of the
    // plan up to z_top, loops, feet and rafts: one that touches another
    // column is that column, met lower down (METHOD), and the triangle it
    // makes no node (a shuttle's helper dropped onto a pillar that shares its
    // base with W: 0.42 N/mm where the plan counted on a node).
    auto reach_at = [&](const Column& c, double z) {
        double r = column_radius_at(c, z, s);
        if (c.base == Base::Bed && z <= c.z0 + 2 * s.layer_height + kEps)
            r = std::max({r, c.foot_radius, c.raft_size / std::numbers::sqrt2});
        return r;
    };
    auto clear_of_plan = [&](const std::vector<Column>& chain, double z_top) {
        for (const Column& h : chain) {
            const double hr = std::max({column_radius_at(h, h.z0, s), column_radius_at(h, h.z1, s), h.foot_radius,
                                        h.raft_size / std::numbers::sqrt2});
            for (const Column& c : sc.columns) {
                const double lo = std::max(h.z0, c.z0), hi = std::min({h.z1, c.z1, z_top});
                if (hi <= lo + kEps) continue;
                const double cr = std::max({column_radius_at(c, c.z0, s), column_radius_at(c, c.z1, s), c.foot_radius,
                                            c.raft_size / std::numbers::sqrt2});
                if (std::min(h.x0, h.x1) - hr > std::max(c.x0, c.x1) + cr + w ||
                    std::min(c.x0, c.x1) - cr > std::max(h.x0, h.x1) + hr + w ||
                    std::min(h.y0, h.y1) - hr > std::max(c.y0, c.y1) + cr + w ||
                    std::min(c.y0, c.y1) - cr > std::max(h.y0, h.y1) + hr + w)
                    continue;
                for (auto it = std::upper_bound(tops.begin(), tops.end(), std::make_pair(lo + kEps, -1));
                     it != tops.end() && it->first <= hi + kEps; ++it) {
                    double hx, hy, cx, cy;
                    column_centre_at(h, it->first, hx, hy);
                    column_centre_at(c, it->first, cx, cy);
                    if (std::hypot(hx - cx, hy - cy) <= reach_at(h, it->first) + reach_at(c, it->first) + w) return false;
                }
            }
        }
        return true;
    };
    // The plan's own bars whose end is a column's top, added to `out` once
    // (braces come after the plan's own bars).
    auto bars_ending_at = [&](const Column& top, std::vector<std::size_t>& out) {
        auto at_top = [&](double x, double y) { return std::hypot(x - top.x1, y - top.y1) < kEps; };
        for (std::size_t i = 0; i < sc.bridges.size(); ++i) {
            const Bridge& b = sc.bridges[i];
            if (!b.brace && std::abs(b.z - top.z1) < kEps && (at_top(b.x0, b.y0) || at_top(b.x1, b.y1)) &&
                std::find(out.begin(), out.end(), i) == out.end())
                out.push_back(i);
        }
    };
    int added = 0;
    std::vector<BraceNode> nodes;  // the triangles' ties, for the walk below
    const int weak_count = static_cast<int>(chains.size());  // helpers added below are not braced in turn
    std::vector<char> braced(chains.size(), 0);                // a corner of a triangle placed already
    std::vector<int> untied;                                   // weak, and no triangle found
    // The triangles placed: the corners (W first; helpers by their index in
    // chains) and the levels they are tied at.
    struct Tied {
        std::array<int, 3> ids;
        std::vector<double> levels;
    };
    std::vector<Tied> tied;
    // A column printed as one with a corner of a triangle already placed (a
    // pillar of another point that shares its way down: the same base, its
    // loops on the corner's at every tie) is tied by the same bars. Where the
    // triangle's nodes still stand at its own top, it is braced there
    // without bars of its own (on benchies and busts, up to six such columns
    // were each tied by their own copy of the same bars, 0.01 mm apart).
    auto shares_a_triangle = [&](int wi, const PillarChain& W, double give) {
        for (const Tied& t : tied)
            for (int corner = 0; corner < 3; ++corner) {
                const PillarChain& V = chains[t.ids[corner]];
                if (bases_apart(W, V)) continue;
                bool together = true;
                for (double b : t.levels) {
                    const double zc = bar_layers(b).front().first;
                    const auto a = at(W, b, zc), v = at(V, b, zc);
                    together = together && a && v && std::hypot(a->x - v->x, a->y - v->y) <= w / 2;
                }
                const int p = t.ids[(corner + 1) % 3], q = t.ids[(corner + 2) % 3];
                if (!together || !nodes_stand(W, chains[p], chains[q], t.levels, give, {wi, p, q})) continue;
                for (double b : t.levels) nodes.push_back({b, {wi, p, q}});
                ties_of[wi].insert(ties_of[wi].end(), t.levels.begin(), t.levels.end());
                return true;
            }
        return false;
    };
    // The give of what stands on a chain (its connectors' worst case).
    auto give_of = [&](const PillarChain& c) { return sc.columns[c.pieces.front()].give; };
    // Whether a chain stands untied. With what stands on it too: a column
    // under a bar end stands the rule at the top of the bar's connectors
    // only if it leaves them their give (a capped foot beside a skirt can
    // take that), judged with a smaller margin (the give is the
    // connectors' worst case).
    auto stands_untied = [&](const PillarChain& c) {
        const double own = chain_compliance(c, c.hold, sc, stack, s);
        return 1 / own >= target && 1 / (own + give_of(c)) >= kGiveMargin * s.min_stiffness;
    };
    for (int wi = 0; wi < weak_count; ++wi) {
        if (braced[wi]) continue;
        const PillarChain W = chains[wi];
        const double give = give_of(W);
        if (stands_untied(W)) continue;
        if (shares_a_triangle(wi, W, give)) {
            braced[wi] = 1;
            continue;
        }
        // Helpers are shaped as W is: one sized for the rule is a trunk beside
        // a plain W, which is then a twig at every tie (under a quarter of its
        // k, METHOD), and the triangle no brace. (Set once per W: Settings
        // holds strings, and helpers are tried many times.)
        Settings helper_settings = s;
        helper_settings.pillar_radius = sc.columns[W.pieces.front()].radius;
        if (!(sc.columns[W.pieces.front()].taper > 0)) helper_settings.min_stiffness = 0;
        auto add_tie = [&](std::vector<double>& ties, double want) {
            const double b = snap_down(want);
            if (b > W.base + 1 && !bar_layers(b).empty() && (ties.empty() || b > ties.back() + kEps)) ties.push_back(b);
        };
        // Whether W, from a tie at `from` (its base: -inf) whose node gives
        // `node` mm/N, stands by itself up to z.
        auto alone = [&](double from, double node, double z) {
            return 1 / (node + chain_compliance(W, z, sc, stack, s, from)) >= kGiveMargin * s.min_stiffness;
        };
        // The highest z up to `to` W stands by itself to from `from`.
        auto stands_to = [&](double from, double node, double to) {
            double lo = from, hi = to;
            for (int i = 0; i < 10; ++i) (alone(from, node, (lo + hi) / 2) ? lo : hi) = (lo + hi) / 2;
            return lo;
        };
        // The give of the node at a tie b over one at `from` (giving
        // `node`): METHOD sums its three columns' k there, each taken as W's
        // (partners and helpers are shaped as W), so it gives a third of
        // W's compliance at b. What stands on the node starts on that give
        // (a plain 2 mm column tied where it stops standing, 14.6 mm, and
        // again 14.6 mm higher stood 1.65 N/mm there against 2.2 alone).
        auto node_give = [&](double from, double node, double b) {
            return (node + chain_compliance(W, b, sc, stack, s, from)) / 3;
        };
        // Tie levels, the fewest first: a tie only where W stops standing by
        // itself (the node there stands at least as W does: METHOD sums its
        // columns), and from there again; a tapered column is tied once near
        // its top. Then every kBraceStep, or closer where the part between
        // two ties would not stand by itself: a thin column (the last
        // fallback, 1 mm across, 0.35 N/mm over 10 mm) every 5 mm or so.
        std::vector<double> fewest, grid;
        // A partner tied already (by another's triangle, not standing
        // with it) is tied again only above those ties: below, the node
        // holds it (as its walk down does).
        double start = W.base;
        for (double e : ties_of[wi]) start = std::max(start, e);
        for (double from = start, node = 0; !alone(from, node, W.top);) {
            const double want = std::min(stands_to(from, node, W.top), W.top - 3.0);
            const std::size_t before = fewest.size();
            if (want > from + 1) add_tie(fewest, want);
            if (fewest.size() == before) break;
            node = node_give(from, node, fewest.back());
            from = fewest.back();
        }
        for (double from = start, node = 0, next = start + kBraceStep;;) {
            const double want = alone(from, node, next) ? next : stands_to(from, node, next);
            if (want <= from + 1 || want > W.top - 3.0) break;
            const std::size_t before = grid.size();
            add_tie(grid, want);
            if (grid.size() == before) break;
            node = node_give(from, node, grid.back());
            from = grid.back();
            next = want == next ? next + kBraceStep : from + kBraceStep;
        }
        // What stands above the top tie starts afresh there: where that part
        // alone would fall short, one more tie as high as ties go (a thin
        // column's 12.8 mm above a tie at 10 mm: 1.82 N/mm), tried first.
        // The fewest ties are made only with neighbours standing already (a
        // helper that tall costs more than the bars it saves: measured on
        // the corpus, 106 mm more on one bear and a figure failing).
        // Whether what stands above the top of `ties` (W's part from there,
        // on that node's give, with what stands on it) meets the rule.
        auto stands_above = [&](const std::vector<double>& ties) {
            double node = 0, from = start;
            for (double b : ties) {
                node = node_give(from, node, b);
                from = b;
            }
            return 1 / (node + chain_compliance(W, W.hold, sc, stack, s, from) + give) >= kGiveMargin * s.min_stiffness;
        };
        std::vector<std::vector<double>> tries;
        std::vector<char> helped;  // whether helpers may stand up for tries[i]
        for (std::vector<double>* ties : {&fewest, &grid}) {
            if (ties->empty()) continue;
            std::vector<double> higher = *ties;
            if (!stands_above(*ties)) add_tie(higher, W.top - 3.0);
            for (const std::vector<double>* t : {&higher, ties}) {
                auto it = std::find(tries.begin(), tries.end(), *t);
                if (it == tries.end()) {
                    tries.push_back(*t);
                    helped.push_back(ties == &grid);
                } else if (ties == &grid) {
                    helped[it - tries.begin()] = 1;
                }
            }
        }
        if (tries.empty()) {
            untied.push_back(wi);
            continue;
        }
        // The triangle that ties W at these levels: bars, the partners among
        // the corners, and the helpers it stands up; no bars if none does.
        auto tie_up = [&](const std::vector<double>& levels, int new_helpers)
            -> std::tuple<std::vector<Bridge>, std::vector<int>, std::vector<PillarChain>> {
            const double b_top = levels.back(), zc_top = bar_layers(b_top).front().first;
            const std::optional<At> a = at(W, b_top, zc_top);
            if (!a) return {};
            // Partners: columns reaching through the top tie, nearest first.
            std::vector<std::pair<double, int>> partners;
            for (int ci = 0; ci < static_cast<int>(chains.size()); ++ci) {
                if (ci == wi || chains[ci].top < zc_top + kBarThickness + 1.0) continue;
                if (const auto p = at(chains[ci], b_top, zc_top)) {
                    const double d = std::hypot(p->x - a->x, p->y - a->y);
                    if (d <= kBraceReach) partners.emplace_back(d, ci);
                }
            }
            std::sort(partners.begin(), partners.end());
            std::vector<Bridge> bars;
            std::vector<int> corners;
            for (std::size_t i = 0; new_helpers == 0 && i < partners.size() && bars.empty(); ++i)
                for (std::size_t j = i + 1; j < partners.size() && bars.empty(); ++j) {
                    const int pi = partners[i].second, pj = partners[j].second;
                    bars = triangle(W, chains[pi], chains[pj], levels, give, {wi, pi, pj});
                    if (!bars.empty()) corners = {partners[i].second, partners[j].second};
                }
            // Too few neighbours: a helper pillar up to the top tie (its top
            // under the bar) makes the third corner, or two make the second and
            // third, forming an equilateral triangle with W.
            std::vector<PillarChain> helpers;
            auto helper = [&](double x, double y) -> std::optional<PillarChain> {
                const int above = bar_layers(b_top).front().second;
                auto drop = [&] {
                    return drop_pillar(x, y, above, Top::Bridge, stack, obs, helper_settings, nullptr, TipPlaces::Any, true,
                                       b_top);
                };
                std::optional<std::vector<Column>> chain;
                if (answers) {
                    auto bits = [](double v) { return std::bit_cast<std::uint64_t>(v); };
                    const std::array<std::uint64_t, 6> key{bits(x), bits(y), bits(b_top), static_cast<std::uint64_t>(above),
                                                           bits(helper_settings.pillar_radius),
                                                           bits(helper_settings.min_stiffness)};
                    auto it = answers->helpers.find(key);
                    if (it == answers->helpers.end()) it = answers->helpers.emplace(key, drop()).first;
                    chain = it->second;
                } else {
                    chain = drop();
                }
                if (!chain || chain->empty() || std::abs(chain->back().z1 - b_top) > kEps) return std::nullopt;
                // A helper is optional: only where it keeps a whole cell more
                // than the gap on every layer (with half, a SuperSlicer benchy's
                // helper touched the hull by 0.02 mm^2 where it stepped aside).
                for (const auto& [z, l] : tops) {
                    if (z > b_top + kEps) break;
                    for (const Column& c : *chain)
                        if (z > c.z0 + kEps && z <= c.z1 + kEps) {
                            double cx, cy;
                            column_centre_at(c, z, cx, cy);
                            if (!obs.disc_clear(l, cx, cy, column_radius_at(c, z, s) + s.xy_gap + s.resolution))
                                return std::nullopt;
                        }
                }
                if (!clear_of_plan(*chain, b_top)) return std::nullopt;
                PillarChain p;
                p.base = chain->front().z0;
                p.top = chain->back().z1;
                p.hold = b_top;
                for (Column& c : *chain) {
                    p.pieces.push_back(static_cast<int>(sc.columns.size()));
                    sc.columns.push_back(c);  // taken out again below if the triangle fails
                }
                return p;
            };
            auto drop_helpers = [&](std::size_t columns_before) { sc.columns.resize(columns_before); };
            for (std::size_t i = 0; bars.empty() && i <= partners.size() && i < 4; ++i) {
                if ((i < partners.size() ? 1 : 2) != new_helpers) continue;
                const std::size_t before = sc.columns.size();
                for (int k = 0; k < 12 && bars.empty(); ++k)
                    for (double d : {10.0, 12.0}) {
                        if (!bars.empty()) break;
                        drop_helpers(before);
                        helpers.clear();
                        if (i < partners.size()) {
                            // Apex of the equilateral triangle on W and the partner, either side.
                            const PillarChain& P = chains[partners[i].second];
                            const auto p = at(P, b_top, zc_top);
                            // (A partner right under W's tie, a column stacked
                            // on it, makes no side: no apex either.)
                            const double len = partners[i].first;
                            if (k >= 2 || d != 10.0 || !p || !(len > kMinSide)) continue;
                            const double mx = (a->x + p->x) / 2, my = (a->y + p->y) / 2;
                            const double sign = k == 0 ? 1.0 : -1.0, h = len * std::sqrt(3.0) / 2;
                            auto hq = helper(mx - sign * (p->y - a->y) / len * h, my + sign * (p->x - a->x) / len * h);
                            if (!hq) continue;
                            bars = triangle(W, P, *hq, levels, give, {wi, partners[i].second, n});
                            if (!bars.empty()) {
                                helpers.push_back(*hq);
                                corners = {partners[i].second};
                            }
                        } else {
                            const double t = k * std::numbers::pi / 6;
                            auto h1 = helper(a->x + d * std::cos(t), a->y + d * std::sin(t));
                            if (!h1) continue;
                            auto h2 = helper(a->x + d * std::cos(t + std::numbers::pi / 3), a->y + d * std::sin(t + std::numbers::pi / 3));
                            if (!h2) continue;
                            bars = triangle(W, *h1, *h2, levels, give, {wi, n, n + 1});
                            if (!bars.empty()) helpers = {*h1, *h2};
                        }
                    }
                if (bars.empty()) drop_helpers(before);
            }
            return {bars, corners, helpers};
        };
        // Of the ways found (each set of levels, with neighbours standing
        // already, or one helper, or two), the one with the least filament:
        // its bars (two lines on each of their layers) and its helpers' loops.
        std::vector<Bridge> bars;
        std::vector<int> corners;
        std::vector<PillarChain> helpers;
        std::vector<Column> helper_columns;
        double least = std::numeric_limits<double>::infinity();
        const std::size_t columns_before = sc.columns.size();
        // Where no triangle ties W at those levels: its top tie lower, by
        // kLowerTie at a time while what stands above it still stands (a
        // tie lower may find partners and helpers clear of the model that
        // one higher does not: an elephant's column between its legs, tied
        // at 8.4 mm, not at 9.4).
        const std::size_t first_tries = tries.size();
        auto lowered = [&] {
            for (std::size_t t = 0; t < first_tries; ++t)
                for (int k = 1; k <= kLowerTies; ++k) {
                    std::vector<double> lower(tries[t].begin(), tries[t].end() - 1);
                    const std::size_t before = lower.size();
                    add_tie(lower, tries[t].back() - k * kLowerTie);
                    if (lower.size() == before || !stands_above(lower) ||
                        std::find(tries.begin(), tries.end(), lower) != tries.end())
                        continue;
                    tries.push_back(lower);
                    helped.push_back(1);
                }
        };
        for (int round = 0; round < 2 && bars.empty(); ++round) {
            if (round == 1) lowered();
            for (int new_helpers : {0, 1, 2})
                for (std::size_t t = round == 0 ? 0 : first_tries; t < tries.size(); ++t) {
                    if (new_helpers > 0 && !helped[t]) continue;
                    auto [b, c, h] = tie_up(tries[t], new_helpers);
                    if (b.empty()) continue;
                    double cost = 0;
                    for (const Bridge& br : b)
                        cost += 2 * std::hypot(br.x1 - br.x0, br.y1 - br.y0) * static_cast<double>(bar_layers(br.z).size());
                    for (std::size_t k = columns_before; k < sc.columns.size(); ++k) {
                        const Column& col = sc.columns[k];
                        for (const auto& [z, l] : tops)
                            if (z > col.z0 + kEps && z <= col.z1 + kEps)
                                cost += 2 * std::numbers::pi * loop_shape(column_radius_at(col, z, s), w).centre_radius;
                    }
                    if (cost < least - kEps) {
                        least = cost;
                        bars = std::move(b);
                        corners = std::move(c);
                        helpers = std::move(h);
                        helper_columns.assign(sc.columns.begin() + static_cast<std::ptrdiff_t>(columns_before), sc.columns.end());
                    }
                    sc.columns.resize(columns_before);
                }
        }
        if (bars.empty()) {
            untied.push_back(wi);
            continue;
        }
        // The helpers chosen, back where their pieces' indices point.
        sc.columns.insert(sc.columns.end(), helper_columns.begin(), helper_columns.end());
        if (braced_bars)
            for (int piece : W.pieces) bars_ending_at(sc.columns[piece], *braced_bars);
        braced[wi] = 1;
        std::vector<int> corner_ids{wi};
        corner_ids.insert(corner_ids.end(), corners.begin(), corners.end());
        for (const PillarChain& h : helpers) {
            corner_ids.push_back(static_cast<int>(chains.size()));
            chains.push_back(h);
            braced.push_back(1);
            ties_of.emplace_back();
        }
        std::vector<double> levels;
        for (const Bridge& br : bars)
            if (levels.empty() || std::abs(levels.back() - br.z) > kEps) levels.push_back(br.z);
        // A partner is braced by W's ties only where they make its own top
        // stand; else it is still weak, and looks for ties of its own when
        // its turn comes (Cura's four bunnies at x +-26 mm: a column squeezed
        // between two bunnies, tied at 10 mm as a partner, stood 22.5 mm
        // higher at 1.56 N/mm, and was never looked at again).
        for (int c : corners) {
            const PillarChain& C = chains[c];
            if (stands_untied(C)) {
                braced[c] = 1;
                continue;
            }
            if (corner_ids.size() != 3) continue;
            const int other = corner_ids[1] == c ? corner_ids[2] : corner_ids[1];
            if (tied_stiffness({&C, &W, &chains[other]}, {c, wi, other}, levels, give_of(C), meets, n, sc, stack, s,
                               {&ties_of[c], &ties_of[wi], &ties_of[other]}) >= s.min_stiffness)
                braced[c] = 1;
        }
        for (int id : corner_ids) ties_of[id].insert(ties_of[id].end(), levels.begin(), levels.end());
        if (corner_ids.size() == 3) {
            for (double b : levels) {
                const double zc = bar_layers(b).front().first;
                for (int id : corner_ids)
                    if (const auto c = at(chains[id], b, zc)) placed.push_back({b, c->x, c->y, c->rc});
            }
            tied.push_back({{corner_ids[0], corner_ids[1], corner_ids[2]}, std::move(levels)});
        }
        for (const Bridge& br : bars) {
            if (corner_ids.size() == 3 && (nodes.empty() || std::abs(nodes.back().z - br.z) > kEps ||
                                           nodes.back().chains[0] != wi))
                nodes.push_back({br.z, {corner_ids[0], corner_ids[1], corner_ids[2]}});
            sc.bridges.push_back(br);
        }
        added += static_cast<int>(bars.size());
    }
    // A column that stands from its own base but that the validator's walk
    // takes down another, by a bar that ties them where the other is the
    // stiffer, and that stands short of the rule that way: the plan is better
    // made without the bar it leaves by (before the widening below, which
    // moves the columns' pieces).
    if (short_of_rule) {
        PlanWalk walk(chains, nodes, sc, stack, s);
        for (int wi = 0; wi < n; ++wi) {
            // Judged at its own top, and at the top of what stands on it
            // with their give: short by the walk where its own way down is not.
            const PillarChain& W = chains[wi];
            const double give = give_of(W);
            const WalkSums walked = walk.path(wi, W.top);
            auto diverted = [&](double top, double extra) {
                return 1 / (walked.at(top) + extra) < s.min_stiffness &&
                       1 / (chain_compliance(W, top, sc, stack, s) + extra) >= s.min_stiffness;
            };
            // And just over each node the walk reaches on W: the node's bars'
            // layers, where W's loop may stand apart from the node's island
            // (figure at 5 N/mm: 0.67 N/mm over a node that keeps the top at 90).
            double from = W.top;
            if (!diverted(W.top, 0) && !diverted(W.hold, give)) {
                for (double zn = walk.node_below(wi, W.top); zn > W.base; zn = walk.node_below(wi, zn)) {
                    const double z = zn + kBarThickness;
                    if (1 / walk.path_from_below(wi, zn, z).at(z) < s.min_stiffness &&
                        1 / chain_compliance(W, z, sc, stack, s) >= s.min_stiffness) {
                        from = zn;
                        break;
                    }
                }
                if (from == W.top) continue;
            }
            const std::vector<ColumnMeeting> left = walk.departures(wi, from);
            if (!left.empty() && left.front().bar >= 0 && !sc.bridges[left.front().bar].brace)
                short_of_rule->push_back(static_cast<std::size_t>(left.front().bar));
        }
    }
    // Tips' columns that nothing made stand, as the walk judges them (before
    // the widening below moves the pieces): named, not hidden.
    if (short_columns) {
        std::optional<PlanWalk> walk;
        for (int wi : untied) {
            const PillarChain& W = chains[wi];
            const Column& top = sc.columns[W.pieces.back()];
            if (braced[wi] || top.top == Top::Bridge) continue;
            if (!walk) walk.emplace(chains, nodes, sc, stack, s);
            const double k = 1 / (walk->path(wi, W.hold).at(W.hold) + give_of(W));
            if (k < s.min_stiffness) short_columns->push_back({top.x1, top.y1, W.hold, k});
        }
    }
    // Weak columns under a bar that no triangle ties: the widest way down
    // that fits, at any share of the taper (the plan's own drop searches it
    // only at a quarter or less, leaving the rest to the braces). Last
    // first: a column's pieces are replaced where they stand in the list.
    for (auto it = untied.rbegin(); it != untied.rend(); ++it) {
        if (braced[*it]) continue;
        const Column top = sc.columns[chains[*it].pieces.back()];
        if (widen_untied(sc, *it, chains, meets, stack, obs, s, tops) >= s.min_stiffness || !short_of_rule) continue;
        bars_ending_at(top, *short_of_rule);
    }
    if (short_of_rule) {
        std::sort(short_of_rule->begin(), short_of_rule->end());
        short_of_rule->erase(std::unique(short_of_rule->begin(), short_of_rule->end()), short_of_rule->end());
    }
    return added;
}

}  // namespace scaffold::plan
