#pragma once
// METHOD's Standing rule, braced: an island standing on three columns that
// are not on one line moves only as all of them together, so its stiffness
// is the sum of theirs, and what stands on it starts afresh there. A column
// too weak for --min-stiffness (one that found no room to widen, beside a
// curving model) is tied to two neighbours by bars in a triangle, every
// kBraceStep of height: each part between ties then stands on its own short
// length, a few N/mm for a plain 2 mm ring.
#include <array>
#include <cstdint>
#include <map>
#include <optional>
#include <vector>

#include "gcode/settings.hpp"
#include "layers/layer_stack.hpp"
#include "plan/obstacles.hpp"
#include "plan/scaffold.hpp"

namespace scaffold::plan {

// Height between ties: a plain 2 mm ring 10 mm tall stands 6.9 N/mm
// (3 E I / h^3), so a column tied this often stands well over 2 N/mm.
inline constexpr double kBraceStep = 10.0;
// Farthest neighbour a column is tied to (centre to centre).
inline constexpr double kBraceReach = 20.0;
// Where no triangle ties a column at its levels, its top tie is tried this
// much lower, up to kLowerTies times.
inline constexpr double kLowerTie = 1.0;
inline constexpr int kLowerTies = 3;

// One pillar of a plan: a column standing on the bed or the model and the
// pieces stacked on it (a chain of drop_pillar), bottom first.
struct PillarChain {
    std::vector<int> pieces;  // indices into Scaffold::columns
    double base = 0, top = 0, hold = 0;
};
std::vector<PillarChain> pillar_chains(const Scaffold& scaffold);

// Whether two pillars' loops touch on the layer at z (column_meetings' test):
// within a cell of each other, and not one loop inside the other clear of
// its inner edge (loops are rings: the validator's islands of two such
// stay apart).
bool rings_touch(const PillarChain& a, const PillarChain& b, const Scaffold& scaffold, const Settings& settings, double z);

// Whether column i is stacked on the piece just before it, where that one
// ends (the next piece of the same pillar, not a branch).
bool stacked_on_previous(const Scaffold& scaffold, int i);

// The piece of the pillar whose height range holds z (z0 < z <= z1), or null.
const Column* chain_piece_at(const PillarChain& chain, const Scaffold& scaffold, double z);

// The second moment of area (mm^4) of a column's loops at height z, as the
// toolpaths print them (a second wall where they give it one).
double column_inertia_at(const Column& c, double z, const Settings& settings);

// A pillar's compliance (mm/N) at height `top` over it, summed layer by
// layer over the loops it prints (their radius as the toolpaths draw them),
// above height `from` (where a brace ties it, what stands on it starts afresh)
// and up to `to` (a part of the path down from higher up).
double chain_compliance(const PillarChain& chain, double top, const Scaffold& scaffold,
                        const layers::LayerStack& stack, const Settings& settings, double from = -1e300,
                        double to = 1e300);

// Where two pillars meet, so that METHOD counts them as one column from
// there up to the next node: a bar of the plan (not a brace) passing
// through or resting on both (at the bar's height), or their loops
// touching (at the first layer of each run of touching layers). Pillars
// are indices into `chains`.
struct ColumnMeeting {
    double z;
    int a, b;
    int bar = -1;  // the bar of the plan they meet by (index into Scaffold::bridges); -1: loops touching
    // Loops touching: the last layer of the run they touch on (z or above;
    // column_meetings sets it). Bars: 0.
    double until = 0;
};
std::vector<ColumnMeeting> column_meetings(const std::vector<PillarChain>& chains, const Scaffold& scaffold,
                                           const layers::LayerStack& stack, const Settings& settings);

// Whether the pillars `ids` are distinct columns at a tie at b over a node
// at lo (-inf: none): none met another between the two, directly or through
// others. Ids at chain_count or more (helpers planned since) meet nothing.
bool distinct_columns(const std::vector<ColumnMeeting>& meetings, int chain_count, const std::vector<int>& ids,
                      double lo, double b);

// The stiffness (N/mm) at the top of what cols[0] holds, with `give` more
// in series, when cols[0..2] are tied at `levels` (ascending), as METHOD's
// validator walks it: at a tie where the three are distinct columns and
// each one's own k is at least a share (kBraceColumnShare) of the
// strongest's, a node, on whose give (one over the sum of their k) each
// part above starts afresh; else what stands on the tie follows the
// stiffest of them down (a twig tied to a trunk rides on the trunk).
// `earlier[i]` (null: none): heights at which cols[i] is tied already, by
// other triangles; the validator may walk it down through a node there, so
// in the share test its k at a tie is taken as high as that could make it
// (the part from that height up, on a node that does not give), the others'
// as low as their own ways down make them. `weakest_corner` (if given):
// the least k of the three at a tie, each on the layer under the bars, as
// the validator judges that layer's island of each (a helper's top there
// stands on its part from the tie below alone).
double tied_stiffness(const std::array<const PillarChain*, 3>& cols, const std::array<int, 3>& ids,
                      const std::vector<double>& levels, double give, const std::vector<ColumnMeeting>& meetings,
                      int chain_count, const Scaffold& scaffold, const layers::LayerStack& stack,
                      const Settings& settings, const std::array<const std::vector<double>*, 3>& earlier = {},
                      double* weakest_corner = nullptr);

// Ties each pillar weaker than target_stiffness at the top of what it holds
// to two neighbours (triangles whose angles are all 30 degrees or more), at
// every kBraceStep above the highest base of the three, with bars clear of
// the model by the XY gap and not near a forbidden bar. A pillar under a bar
// end that no triangle ties, and whose own top falls short as the validator
// walks it, is dropped again as wide as fits (drop_pillar's `widest`) where
// that stands stiffer. Returns the bars added. `short_of_rule` (optional)
// gets the bars (indices, none a brace) whose end stands on such a pillar
// and which, widened or not, still falls short of --min-stiffness by that
// walk: the plan is better made without them. `braced_bars` (optional)
// gets the plan's own bars (indices) whose end stands on a piece of a column
// that a triangle of bars ties: what those bars cost includes the braces.
// The helper pillars add_braces dropped, by place, height and shape (x, y,
// the bar's height and layer, radius and stiffness asked, as bits): the
// plans made again on the same model ask for most of them again
// (elephant: 456 drops over two plans, 241 of them distinct). A drop
// depends on the model and those alone.
struct BraceAnswers {
    std::map<std::array<std::uint64_t, 6>, std::optional<std::vector<Column>>> helpers;
};

// A tip's column (no bar on it) that neither a triangle nor its widening
// made stand: its top, and its stiffness there as the planner judges it.
struct ShortColumn {
    double x = 0, y = 0, z = 0, k = 0;
};

// `answers` (optional): kept by the caller over plans made again.
// `short_columns` (optional) gets the tips' columns still short of
// --min-stiffness (those under a bar go to `short_of_rule`).
int add_braces(Scaffold& scaffold, const layers::LayerStack& stack, const Obstacles& obstacles,
               const Settings& settings, const Forbidden& forbidden,
               std::vector<std::size_t>* short_of_rule = nullptr, BraceAnswers* answers = nullptr,
               std::vector<std::size_t>* braced_bars = nullptr, std::vector<ShortColumn>* short_columns = nullptr);

}  // namespace scaffold::plan
