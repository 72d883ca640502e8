#pragma once
// METHOD's walk down a plan's pillars, taken as the validator takes it: from
// a layer of a pillar down to its base; where it meets other pillars (a bar
// of the plan on them, or loops touching) the way on down is the stiffest of
// them *there*, not the one that would leave the top stiffest; at a brace
// node (three pillars tied, none under a quarter of the strongest's k) what
// stands above starts afresh on the node's give. A pillar judged from its
// own base may be walked elsewhere: figure x4's tall tapered column, tied at
// 14.6 mm to a short one that stands on a brace node at 10 mm, is walked
// down that node (42 N/mm where they meet, more than its own base gives
// there), and its top, 29 mm above the node over thin sections, stands
// 0.46 N/mm where its own way down gives it over 2.
#include <array>
#include <map>
#include <utility>
#include <vector>

#include "gcode/settings.hpp"
#include "layers/layer_stack.hpp"
#include "plan/braces.hpp"
#include "plan/scaffold.hpp"

namespace scaffold::plan {

// Three pillars (indices into the chains) tied at height z by brace bars.
struct BraceNode {
    double z;
    std::array<int, 3> chains;
};

// A path's compliance as three running sums over its layers (of dz/EI,
// z dz/EI, z^2 dz/EI, z at each layer's middle) and a node's give c0: at
// lever height t it is c0 + t^2 s0 - 2 t s1 + s2.
struct WalkSums {
    double c0 = 0, s0 = 0, s1 = 0, s2 = 0;
    double at(double t) const { return c0 + t * t * s0 - 2 * t * s1 + s2; }
};

class PlanWalk {
public:
    // `chains`: pillar_chains' (and helpers since), whose indices `nodes`
    // and the queries use. The walk adds the plan's other pillars (columns
    // on a bar, branches on a column), each going on down through what it
    // stands on. All must outlive the walk.
    PlanWalk(const std::vector<PillarChain>& chains, const std::vector<BraceNode>& nodes, const Scaffold& scaffold,
             const layers::LayerStack& stack, const Settings& settings);
    // The path down from pillar c's layer at height z.
    WalkSums path(int c, double z);
    // The meetings at which the walk down from pillar c at z leaves the
    // pillar it is on for another, in the order it takes them.
    std::vector<ColumnMeeting> departures(int c, double z);
    // The highest brace node below z that the walk down from pillar c's
    // layer at z reaches while still on c, or -infinity.
    double node_below(int c, double z);
    // The walk's path as it comes up to height `at` from below (a node at
    // `at` not taken), then up c's own layers to z: what a layer of c just
    // over a node stands on where the validator finds c's loop not yet on
    // the node's island there.
    WalkSums path_from_below(int c, double at, double z);

private:
    // What meets pillar c at one height: other pillars, or a node.
    struct Event {
        double z = 0;
        std::vector<ColumnMeeting> meetings;  // oriented: a is c
        int node = -1;                        // index into nodes_
    };
    // Sums of pillar c's own layers with top in (lo, hi].
    WalkSums own(int c, double lo, double hi) const;
    // The highest of c's events strictly below z, or -1.
    int event_below(int c, double z) const;
    // The walk's state at c's event e: the path below the event's layer
    // (taken as the walk takes it) and the pillar it goes on down
    // (c itself, or the meeting it leaves by).
    struct State {
        WalkSums below;
        int leave = -1;     // index into the event's meetings, or -1: stays on c
        bool node = false;  // a brace node: the walk starts afresh there
        int twig = -1;      // a node with a twig: the pillar the walk goes on down instead
    };
    const State& state(int c, int e);

    std::vector<PillarChain> chains_;  // the caller's, then the pillars on bars or columns
    std::vector<char> hung_;            // per pillar: standing on a bar or a column, nothing of its own below
    // Per pillar hung on a bar: the bar's layers under its first piece,
    // (lo, hi], and the bar's own section there (the validator's island).
    struct Seat {
        double lo = 0, hi = 0, inertia = 0;
    };
    std::vector<Seat> seat_;
    // Per pillar, the runs of layers on which its loops touch another's:
    // the validator's island there is both loops, its section at least the
    // sum of theirs (two rings side by side, about the line through them).
    struct Touch {
        int other = 0;
        double from = 0, to = 0;  // layer tops, inclusive
    };
    std::vector<std::vector<Touch>> touches_;
    const std::vector<BraceNode>& nodes_;
    const Scaffold& sc_;
    const layers::LayerStack& stack_;
    const Settings& s_;
    std::vector<std::vector<Event>> events_;  // per pillar, ascending z
    std::map<std::pair<int, int>, State> memo_;
};

}  // namespace scaffold::plan
