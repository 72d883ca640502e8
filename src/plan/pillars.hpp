#pragma once
#include <algorithm>
#include <array>
// Vertical pillars: one per support point, down to the bed or to the model's
// top surface, kept clear of the model by the XY gap on every layer. Where
// the model bulges out below, the pillar steps aside a little per layer (no
// more than the overhang angle allows), so it becomes a chain of columns.
#include <cmath>
#include <cstdint>
#include <mutex>
#include <optional>
#include <unordered_map>
#include <vector>

#include "layers/layer_stack.hpp"
#include "overhang/overhangs.hpp"
#include "plan/obstacles.hpp"
#include "plan/scaffold.hpp"

namespace scaffold::plan {

// Descents (a column's walk down, stepping around the model) kept over the
// plans made again on the same stack, obstacles and settings: one walked
// where no trunk came within reach is the walk without trunks, and holds
// for the next plan's trunks where none of them comes within reach of it
// either (steer, or the shift a loop may rest on one below). The plans
// made again drop most of the same pillars (Cura's bunny at 0.1 mm: eight
// plans, 600 layers a column). Used by one thread at a time.
class DescentCache {
public:
    DescentCache();
    ~DescentCache();
    struct Impl;
    std::unique_ptr<Impl> impl;
    long long hits = 0, misses = 0;
};

// The loops of the pillars planned so far, per layer: a new pillar whose
// loop one of them holds stands on it instead of printing its loops across
// the other's; within `steer` mm of one it leans towards it (a branch).
class Trunks {
public:
    struct Loop {
        double x, y, rc;  // centre and centre-line radius
        double hold_z;    // the top of what stands on its column
    };
    Trunks(const layers::LayerStack& stack, double steer) : at_(stack.layers.size()), steer_(steer) {}
    void add(const std::vector<Column>& chain, const layers::LayerStack& stack, const Settings& settings);
    const std::vector<Loop>& at(int layer) const { return at_[layer]; }
    double steer() const { return steer_; }
    // Where the descents of columns dropped with these trunks are kept (may be null).
    void keep_descents(DescentCache* cache) { descents_ = cache; }
    DescentCache* descents() const { return descents_; }

private:
    std::vector<std::vector<Loop>> at_;
    double steer_;
    DescentCache* descents_ = nullptr;
};

// How far a scaffold's pillar reaches sideways for a trunk to branch off.
inline constexpr double kBranchSteer = 3.0;

// A pillar whose top layer is the one beneath `overhang_layer` (less
// --top-gap-layers), near (x, y), as columns from the bottom up. nullopt when
// no clear path exists (or it would stand on the model with --buildplate-only).
// With `trunks`, it may end on one of them (Base::Column).
// The layer a tip under `overhang_layer` reaches up to: the one beneath it,
// less --top-gap-layers; -1 where there is none.
int tip_layer(const layers::LayerStack& stack, int overhang_layer, const Settings& settings);

// `places`: where a tip may stand away from the point (METHOD's rule (c) holds
// only the sheet a tip lies under): under the overhanging layer's material
// first, then anywhere within reach (Any), or only one of the two.
// `fit_base` false: no foot and raft fitted (whether a pillar stands does
// not depend on them). METHOD's Standing rule: the column widens downwards
// until it stands --min-stiffness stiff (with a margin) at `hold`, the top
// of what will stand on it (its own top if higher), with `give` mm/N of
// that in series; where the widened one finds no way down, the plain one.
// Under a bar that holds more above it the top is not narrowed to a tip,
// unless a thin column stands on it (`thin_above`: lean_in's). `widest`:
// short of the rule, the widest that fits at any share of the taper (else
// only at a quarter or less: elsewhere braces cost less).
enum class TipPlaces { Any, UnderSheet, Beside };
std::optional<std::vector<Column>> drop_pillar(double x, double y, int overhang_layer, Top top,
                                               const layers::LayerStack& stack, const Obstacles& obstacles,
                                               const Settings& settings, const Trunks* trunks = nullptr,
                                               TipPlaces places = TipPlaces::Any, bool fit_base = true,
                                               double hold = 0, double give = 0, bool thin_above = false,
                                               bool widest = false);

// Whether a pillar stands under a bar end at (x, y) under `overhang_layer`:
// drop_pillar(x, y, overhang_layer, Top::Bridge, stack, obstacles,
// settings, nullptr, TipPlaces::Any, false).has_value(), the bridge
// search's question for every end it weighs (130,000 times for a bunny),
// with the same answer and less work. The plain column goes straight down
// from (x, y) until the model first blocks it; what its descent does from
// there (steps aside, lands, finds no way) depends only on that place and
// layer and the column's state there, not on how high it started, so it is
// worked out once per such place, kept in `known` (shared by threads).
class BarEndAnswers {
public:
    struct Key {
        std::uint64_t x, y, radius, above_radius, above_height, reach;
        int layer;
        bool operator==(const Key&) const = default;
    };
    std::optional<bool> find(const Key& key) const;
    void insert(const Key& key, bool stands);
    std::size_t size() const;

private:
    struct Hash {
        std::size_t operator()(const Key& k) const;
    };
    mutable std::mutex mutex_;
    std::unordered_map<Key, bool, Hash> map_;
};
bool bar_end_stands(double x, double y, int overhang_layer, const layers::LayerStack& stack, const Obstacles& obstacles,
                    const Settings& settings, BarEndAnswers& known);

// A tip's column that does not stand by METHOD's Standing rule as planned
// (found with less taper than the rule asks), widened along the same way
// down: each loop as wide as the room on its layer allows, up to the full
// taper, changing per layer no more than a loop may step out on the one
// below; a bottom loop on the model stays as it was. Where the room caps it
// short of the rule, the least taper (up to kMaxTaper) with which the
// capped column stands, if any does. `chain`: one column's
// pieces, bottom first, as drop_pillar gives them. True where it got wider
// (and so stiffer); `give` as drop_pillar's.
bool widen_column(std::vector<Column>& chain, const layers::LayerStack& stack, const Obstacles& obstacles,
                  const Settings& settings, double give = 0);

// Support point indices in a canonical order, so the plan does not depend
// on the order of the input: place_points' own (layer, y, x), then z and index.
std::vector<int> canonical_order(const overhang::SupportPoints& points);

// --method pillars: a pillar under every support point.
Scaffold plan_pillars(const overhang::SupportPoints& points, const layers::LayerStack& stack,
                      const Obstacles& obstacles, const Settings& settings);

// Whether height z is in a column's contact: its top two layers, which may
// come closer to the model than the XY gap. Half a layer of slack, not a
// hair: layer heights are floats, and 33.6f - 0.4 is not above 33.2f.
inline bool in_contact(const Column& c, double z, double layer_height) {
    return c.contact_z > 0 && z > c.contact_z - 1.5 * layer_height;
}

// An unheld end of a bead this long is held (METHOD.md's rule (b); the
// validator's default).
inline constexpr double kDanglingEnd = 1.0;

// The contact of a tip may come this close to the model.
inline constexpr double kTipClearance = 0.2;

// Least distance a column keeps from the model at height z: the XY gap, or
// kTipClearance in the contact of a column that touches the model (a tip
// under a bridge end keeps the whole gap).
inline double clearance_at(const Column& c, double z, const Settings& settings) {
    return c.top == Top::Contact && in_contact(c, z, settings.layer_height) ? kTipClearance : settings.xy_gap;
}

// Feet only under pillars taller than this (the report's 3 mm).
inline constexpr double kFootMinHeight = 3.0;

// Radius of a column at height z (tip taper, foot flare, base radius).
double column_radius_at(const Column& c, double z, const Settings& settings);

// Whether the toolpaths give a column's loop of outer radius r a second wall
// inside it (at r - 0.9 w): wide pillars, but not those widened for the
// Standing rule, sized as single walls.
inline bool second_wall(const Column& c, double r, double width) {
    return r - width > 1.5 * width && r > 1.4 && !(c.taper > 0);
}

// The printed loop of a column of outer radius r with beads of width w: a
// regular polygon of `sides` vertices, the first at angle 0, on a circle of
// radius `centre_radius` (the bead's centre line). The toolpaths print it
// so; the planner checks where it rests with the same vertices.
struct LoopShape {
    double centre_radius = 0;
    int sides = 8;
};
LoopShape loop_shape(double r, double width);
// The loop's vertices as the toolpaths print it, from angle 0 round to it
// again (sides + 1 points).
std::vector<std::array<double, 2>> loop_vertices(double cx, double cy, double r, double width);
// METHOD's Standing rule: whether a column's bottom loop (centre, radius r)
// printed on `layer` stands on the model, at least 30 % of its cells (35 %
// asked) over the model's footprint within two nominal layers below.
bool loop_stands_on_model(double x, double y, double r, int layer, const layers::LayerStack& stack, const Settings& s);

// How far a loop's centre line may stray from the loop printed under it
// (on a layer of height h) and still rest on it: the self-supporting reach
// plus half a bead, less a fifth for the polygon's chords and the raster.
double loop_shift_limit(double h, const Settings& settings);

// The most two loops' centre lines stray from each other: centre distance
// plus the difference of their centre-line radii.
inline double loops_apart(double x0, double y0, double rc0, double x1, double y1, double rc1) {
    return std::hypot(x1 - x0, y1 - y0) + std::abs(rc1 - rc0);
}

// Centre of a column at height z (linear between its ends; straight up to
// lean_from where that is set).
inline void column_centre_at(const Column& c, double z, double& x, double& y) {
    const double z0 = std::max(c.z0, c.lean_from);
    double t = c.z1 > z0 ? std::clamp((z - z0) / (c.z1 - z0), 0.0, 1.0) : 1.0;
    x = c.x0 + (c.x1 - c.x0) * t;
    y = c.y0 + (c.y1 - c.y0) * t;
}

}  // namespace scaffold::plan
