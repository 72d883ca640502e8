#include "plan/walk.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "plan/candidates.hpp"
#include "plan/pillars.hpp"
#include "plan/stiffness.hpp"

namespace scaffold::plan {

namespace {
constexpr double kEps = 1e-6;
// METHOD: a column under a quarter of the strongest's k at a node is a twig.
constexpr double kTwigShare = 0.25;
}  // namespace

PlanWalk::PlanWalk(const std::vector<PillarChain>& chains, const std::vector<BraceNode>& nodes,
                   const Scaffold& scaffold, const layers::LayerStack& stack, const Settings& settings)
    : chains_(chains), hung_(chains.size(), 0), nodes_(nodes), sc_(scaffold), stack_(stack), s_(settings) {
    // The other pillars: runs of stacked pieces that pillar_chains leaves
    // out (a connector on a bar, a branch on a column), whatever they stand on.
    std::vector<char> taken(scaffold.columns.size(), 0);
    for (const PillarChain& p : chains)
        for (int i : p.pieces) taken[static_cast<std::size_t>(i)] = 1;
    for (int i = 0; i < static_cast<int>(scaffold.columns.size()); ++i) {
        if (taken[static_cast<std::size_t>(i)]) continue;
        const Column& c = scaffold.columns[static_cast<std::size_t>(i)];
        // The next piece of the last pillar added here.
        if (chains_.size() > chains.size() && chains_.back().pieces.back() == i - 1 && stacked_on_previous(scaffold, i)) {
            chains_.back().pieces.push_back(i);
            chains_.back().top = c.z1;
        } else {
            chains_.push_back({{i}, c.z0, c.z1, std::max(c.z1, c.hold_z)});
            hung_.push_back(c.base == Base::Bridge || c.base == Base::Column);
        }
    }
    const int n = static_cast<int>(chains_.size());
    seat_.resize(chains_.size());
    events_.resize(chains_.size());
    auto event_at = [&](int c, double z) -> Event& {
        std::vector<Event>& ev = events_[static_cast<std::size_t>(c)];
        for (Event& e : ev)
            if (std::abs(e.z - z) < kEps) return e;
        ev.push_back({z, {}, -1});
        return ev.back();
    };
    auto meet = [&](const ColumnMeeting& m) {
        event_at(m.a, m.z).meetings.push_back(m);
        event_at(m.b, m.z).meetings.push_back({m.z, m.b, m.a, m.bar});
    };
    const std::vector<ColumnMeeting> meetings = column_meetings(chains_, scaffold, stack, settings);
    for (const ColumnMeeting& m : meetings) meet(m);
    touches_.resize(chains_.size());
    for (const ColumnMeeting& m : meetings)
        if (m.bar < 0) {
            touches_[static_cast<std::size_t>(m.a)].push_back({m.b, m.z, m.until});
            touches_[static_cast<std::size_t>(m.b)].push_back({m.a, m.z, m.until});
        }
    // A pillar hung on a bar goes on down through the pillars the bar is on;
    // one on a column, through that column.
    const double w = settings.support_width;
    for (int h = 0; h < n; ++h) {
        if (!hung_[static_cast<std::size_t>(h)]) continue;
        const Column& foot = scaffold.columns[static_cast<std::size_t>(chains_[static_cast<std::size_t>(h)].pieces.front())];
        const double r = column_radius_at(foot, foot.z0, settings);
        if (foot.base == Base::Bridge) {
            for (std::size_t bi = 0; bi < scaffold.bridges.size(); ++bi) {
                const Bridge& br = scaffold.bridges[bi];
                if (foot.z0 < br.z - kEps || foot.z0 > br.z + kBarThickness + kEps) continue;
                const layers::Segment seg{static_cast<float>(br.x0), static_cast<float>(br.y0), static_cast<float>(br.x1),
                                          static_cast<float>(br.y1)};
                if (layers::segment_distance(foot.x0, foot.y0, seg) > r + w) continue;
                // The bar's layers are the pillar's way down to the bar's
                // ends (of several bars there, the weakest).
                const double inertia =
                    bar_inertia(std::hypot(br.x1 - br.x0, br.y1 - br.y0), w, settings.pillar_radius);
                Seat& seat = seat_[static_cast<std::size_t>(h)];
                if (seat.inertia == 0 || inertia < seat.inertia) seat = {br.z, foot.z0, inertia};
                for (const ColumnMeeting& m : meetings)
                    if (m.bar == static_cast<int>(bi)) {
                        if (m.a != h) meet({br.z, h, m.a, m.bar});
                        if (m.b != h) meet({br.z, h, m.b, m.bar});
                    }
            }
            continue;
        }
        for (int o = 0; o < n; ++o) {
            if (o == h) continue;
            const Column* under = chain_piece_at(chains_[static_cast<std::size_t>(o)], scaffold, foot.z0);
            if (!under) continue;
            double ux, uy;
            column_centre_at(*under, foot.z0, ux, uy);
            if (std::hypot(ux - foot.x0, uy - foot.y0) <= column_radius_at(*under, foot.z0, settings) + w)
                meet({foot.z0, h, o, -1});
        }
    }
    // A node is the island of its bars' first layer: its three pillars and
    // every pillar whose loops touch theirs there (through others too), all
    // standing on it above (METHOD: what stands on a brace node starts
    // afresh there; figure at 5 N/mm: a column touching a corner's loop at
    // the tie, walked by its own way down at 41 N/mm, stood on the node at
    // 2800 for the validator).
    std::vector<double> tops;
    for (const layers::Layer& layer : stack.layers)
        if (!layer.purge) tops.push_back(layer.z);
    std::sort(tops.begin(), tops.end());
    for (int i = 0; i < static_cast<int>(nodes.size()); ++i) {
        const BraceNode& node = nodes[static_cast<std::size_t>(i)];
        std::vector<int> in;
        for (int c : node.chains)
            if (c >= 0 && c < n) {
                event_at(c, node.z).node = i;
                in.push_back(c);
            }
        const auto first = std::upper_bound(tops.begin(), tops.end(), node.z + kEps);
        if (first == tops.end()) continue;
        for (std::size_t k = 0; k < in.size(); ++k)
            for (int o = 0; o < n; ++o)
                if (std::find(in.begin(), in.end(), o) == in.end() &&
                    rings_touch(chains_[static_cast<std::size_t>(in[k])], chains_[static_cast<std::size_t>(o)], scaffold,
                                settings, *first)) {
                    event_at(o, node.z).node = i;
                    in.push_back(o);
                }
    }
    for (std::vector<Event>& ev : events_)
        std::sort(ev.begin(), ev.end(), [](const Event& a, const Event& b) { return a.z < b.z; });
}

WalkSums PlanWalk::own(int c, double lo, double hi) const {
    WalkSums out;
    const PillarChain& chain = chains_[static_cast<std::size_t>(c)];
    const Seat& seat = seat_[static_cast<std::size_t>(c)];
    const std::vector<Touch>& touches = touches_[static_cast<std::size_t>(c)];
    for (const layers::Layer& layer : stack_.layers) {
        if (layer.purge || layer.z > hi + kEps || layer.z <= lo + kEps) continue;
        const Column* piece = chain_piece_at(chain, sc_, layer.z);
        const bool on_bar = !piece && seat.inertia > 0 && layer.z > seat.lo + kEps && layer.z <= seat.hi + kEps;
        if (!piece && !on_bar) continue;
        double inertia = piece ? column_inertia_at(*piece, layer.z, s_) : seat.inertia;
        if (piece)
            for (const Touch& t : touches)
                if (layer.z > t.from - kEps && layer.z < t.to + kEps)
                    if (const Column* q = chain_piece_at(chains_[static_cast<std::size_t>(t.other)], sc_, layer.z))
                        inertia += column_inertia_at(*q, layer.z, s_);
        const double f = layer.height / (s_.modulus * inertia);
        const double zm = layer.z - layer.height / 2;
        out.s0 += f;
        out.s1 += zm * f;
        out.s2 += zm * zm * f;
    }
    return out;
}

int PlanWalk::event_below(int c, double z) const {
    const std::vector<Event>& ev = events_[static_cast<std::size_t>(c)];
    for (int e = static_cast<int>(ev.size()) - 1; e >= 0; --e)
        if (ev[static_cast<std::size_t>(e)].z < z - kEps) return e;
    return -1;
}

WalkSums PlanWalk::path(int c, double z) {
    const int e = event_below(c, z);
    if (e < 0) {
        // Hung on nothing the plan knows: no way down.
        if (hung_[static_cast<std::size_t>(c)]) return WalkSums{std::numeric_limits<double>::infinity(), 0, 0, 0};
        return own(c, -1e300, z);
    }
    const double ze = events_[static_cast<std::size_t>(c)][static_cast<std::size_t>(e)].z;
    WalkSums p = state(c, e).below;
    const WalkSums up = own(c, ze, z);
    p.s0 += up.s0;
    p.s1 += up.s1;
    p.s2 += up.s2;
    return p;
}

const PlanWalk::State& PlanWalk::state(int c, int e) {
    const auto key = std::make_pair(c, e);
    if (const auto it = memo_.find(key); it != memo_.end()) return it->second;
    const Event ev = events_[static_cast<std::size_t>(c)][static_cast<std::size_t>(e)];
    State st;
    st.below = path(c, ev.z);  // events strictly below: the recursion goes down
    double best_k = 1 / st.below.at(ev.z);
    if (ev.node >= 0) {
        // Each of the three as the walk reaches the node from below.
        std::array<double, 3> k{};
        const BraceNode& node = nodes_[static_cast<std::size_t>(ev.node)];
        for (int i = 0; i < 3; ++i) k[static_cast<std::size_t>(i)] = 1 / path(node.chains[static_cast<std::size_t>(i)], ev.z).at(ev.z);
        const double strongest = *std::max_element(k.begin(), k.end());
        if (std::all_of(k.begin(), k.end(), [&](double ki) { return ki >= kTwigShare * strongest; })) {
            st.below = WalkSums{1 / (k[0] + k[1] + k[2]), 0, 0, 0};
            st.node = true;
            return memo_[key] = st;
        }
        // A twig among them: no node; the stiffest of the three, as a meeting.
        for (int i = 0; i < 3; ++i)
            if (node.chains[static_cast<std::size_t>(i)] != c && k[static_cast<std::size_t>(i)] > best_k) {
                best_k = k[static_cast<std::size_t>(i)];
                st.below = path(node.chains[static_cast<std::size_t>(i)], ev.z);
                st.twig = node.chains[static_cast<std::size_t>(i)];
            }
    }
    for (std::size_t m = 0; m < ev.meetings.size(); ++m) {
        const WalkSums other = path(ev.meetings[m].b, ev.z);
        const double k = 1 / other.at(ev.z);
        if (k > best_k) {  // ties stay on c
            best_k = k;
            st.below = other;
            st.leave = static_cast<int>(m);
            st.twig = -1;
        }
    }
    return memo_[key] = st;
}

std::vector<ColumnMeeting> PlanWalk::departures(int c, double z) {
    std::vector<ColumnMeeting> out;
    for (int e = event_below(c, z); e >= 0;) {
        const Event& ev = events_[static_cast<std::size_t>(c)][static_cast<std::size_t>(e)];
        const State& st = state(c, e);
        if (st.node) break;
        const double ze = ev.z;
        if (st.leave >= 0) {
            const ColumnMeeting m = ev.meetings[static_cast<std::size_t>(st.leave)];
            out.push_back(m);
            c = m.b;
        } else if (st.twig >= 0) {
            out.push_back({ze, c, st.twig, -1});
            c = st.twig;
        }
        e = event_below(c, ze);
    }
    return out;
}

double PlanWalk::node_below(int c, double z) {
    for (int e = event_below(c, z); e >= 0; --e) {
        const State& st = state(c, e);
        if (st.node || st.twig >= 0) return events_[static_cast<std::size_t>(c)][static_cast<std::size_t>(e)].z;
        if (st.leave >= 0) break;
    }
    return -std::numeric_limits<double>::infinity();
}

WalkSums PlanWalk::path_from_below(int c, double at, double z) {
    WalkSums p = path(c, at);
    const WalkSums up = own(c, at, z);
    p.s0 += up.s0;
    p.s1 += up.s1;
    p.s2 += up.s2;
    return p;
}

}  // namespace scaffold::plan
