#pragma once
// Step 5: the planned scaffold as extrusion paths, per layer: pillar loops
// (tapered tips, flared feet), raft squares on the first layer, and bridge
// lines. Plain geometry with width, height and speed; splice/ writes G-code.
#include <functional>
#include <vector>

#include "layers/layer_stack.hpp"
#include "plan/obstacles.hpp"
#include "plan/scaffold.hpp"

namespace scaffold::toolpath {

enum class PathKind { Pillar, Foot, Raft, Bridge, Connector };

struct Point {
    double x = 0, y = 0;
};

struct Path {
    std::vector<Point> points;  // extruded from first to last
    double width = 0.45;        // mm
    double speed_mm_s = 60;
    PathKind kind = PathKind::Pillar;
    bool bridge = false;        // print with bridge settings (fan on)
    // Retract for the travel to this path: false when the travel from the
    // previous path stays clear of the model (like the slicers' "only retract
    // when crossing perimeters"; oozing onto support does no harm).
    bool retract = true;
};

struct LayerPaths {
    int layer = 0;              // index into LayerStack::layers
    std::vector<Path> paths;    // in printing order
    // A bond (bond_z > 0): loops printed before the layer's model at a
    // height of their own, under columns that start on this layer over an
    // air gap wider than METHOD's Standing path follows down (a raft's: Cura
    // leaves 0.3 mm of air under the model's first layer). Bonds come just
    // before their layer's own entry.
    double bond_z = 0, bond_height = 0;
    bool bond() const { return bond_z > 0; }
};

struct SupportPaths {
    std::vector<LayerPaths> layers;  // only layers with support, by index
};

// The paths' volume, mm^3: length x width x the layer's height.
double paths_volume(const SupportPaths& paths, const layers::LayerStack& stack);

// Every point moved by (dx, dy): paths made in the plan's frame, put on the bed.
void move_paths(SupportPaths& paths, double dx, double dy);

// The height the entry is printed at (its bond's, or its layer's).
inline double printed_z(const LayerPaths& lp, const layers::LayerStack& stack) {
    return lp.bond() ? lp.bond_z : stack.layers[lp.layer].z;
}

// A column is bonded to what it stands on where the gap under its first
// layer exceeds this many nominal layer heights (the validator's path down
// reaches two); the bond is printed halfway up the gap.
inline constexpr double kBondGapLayers = 1.5;
// ...and only where the gap is at most this many: a bond becomes the layer
// right under the model's, which then rests on the raft only through
// support within three nominal layers (METHOD's "layer L-1"). Over a wider
// gap (Cura's raft under 0.1 mm layers: 0.5 mm) the model's first layer
// lies on the raft only as the nearest layer under it, and a bond there
// would leave it held by nothing.
inline constexpr double kBondMostLayers = 3.0;

// A bridge bar is two layers thick, starting at Bridge::z.
inline constexpr double kBridgeThickness = 0.4;

// `obstacles` (optional) lets travels between support paths skip retraction
// where they cross no model.
SupportPaths make_paths(const plan::Scaffold& scaffold, const layers::LayerStack& stack, const Settings& settings,
                        const plan::Obstacles* obstacles = nullptr);
// The same, the travel from a to b on a layer (index) asked of `clear`:
// true when it keeps `width` clear of the model.
using TravelClear = std::function<bool(int layer, const Point& a, const Point& b, double width)>;
SupportPaths make_paths(const plan::Scaffold& scaffold, const layers::LayerStack& stack, const Settings& settings,
                        const TravelClear& clear);

// The copies (`one`'s paths moved by each offset) in clusters: those whose
// paths come within `apart` mm of each other (widths included) joined, and
// so on. Each cluster's copies ascending, clusters by their first copy; a
// cluster a copy where all stand apart. Clusters `apart` apart share no
// loop, raft, bond or spur, so each may print paths made for it alone
// (for a lone copy, `one`: the paths its plan was checked with). make_paths
// of all copies' plans together gives the same paths but for their order
// and, where two of a copy's own loops nearly retrace each other, which of
// them it keeps.
std::vector<std::vector<std::size_t>> copy_clusters(const SupportPaths& one, const std::vector<Point>& offsets,
                                                    double apart);

// Paths of parts of a plate that stand apart, each made once and moved:
// every layer prints part after part in this order, each part's paths
// moved by its offset, the travel from one part to the next asked of
// `clear`. Entries are matched by layer and bond height and come in
// make_paths' order (by layer, bonds by height before the layer's own).
struct PlacedPaths {
    const SupportPaths* paths = nullptr;
    Point offset;
};
SupportPaths placed_paths(const std::vector<PlacedPaths>& parts, const TravelClear& clear);

// The order a layer's paths print in: nearest first from the end of the
// one before (the first as given), ties to the lower index; distances
// between the places as written (three decimals). Indices into `paths`.
std::vector<std::size_t> printing_order(const std::vector<Path>& paths);

// The two side-by-side lines of a bar's layer, in printing order, each
// reaching half a pillar radius past the bar's ends into the pillar tops.
std::vector<std::vector<Point>> bar_lines(const plan::Bridge& br, double width, double pillar_radius);

// A closed loop whose outer edge is at radius r (centre line r - width/2).
std::vector<Point> loop(double cx, double cy, double r, double width);

}  // namespace scaffold::toolpath
