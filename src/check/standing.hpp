#pragma once
// METHOD's second rule, Standing: every support island (8-connected support
// cells of one layer) is a cantilever clamped at its base (the bed, the
// model, or a brace of three columns), and must be stiff enough for the
// nozzle dragging across its top; travels must not cross fresh support.
// It sees only G-code: which moves are support, and whose, comes from the
// caller (the validator), never from the planner.
#include <cstdint>
#include <string>
#include <vector>

#include "gcode/program.hpp"
#include "gcode/settings.hpp"
#include "layers/layer_stack.hpp"

namespace scaffold::check {

struct StandingOptions {
    double min_stiffness = 2;      // N/mm; 0 reports without failing
    double min_island_mm2 = 0.05;  // smaller islands are judged in the path, not listed or failed
    double modulus = 3500;         // N/mm^2, PLA
    double travel_clearance = 0.2; // mm in XY from the beads of fresh support
    double travel_lift = 0.15;     // mm above the layer: a travel this high is lifted
    double resolution = 0.1;       // raster cell, mm
    int worst = 5;                 // weakest islands listed per side
};

// Whose support a move prints, per move: none (model, skirt, travel), what
// the edit added (all support when there is no original), or the
// original's own (a file sliced with support on).
enum class SupportOwner : std::uint8_t { None, Added, Original };

struct WeakIsland {
    int layer = 0;
    double z = 0, x = 0, y = 0;   // top of the island, its centroid
    double k = 0;                 // N/mm at its top; 0 when floating
    double height = 0;            // mm above its base or brace node
    double area_mm2 = 0;
    bool floating = false;
};

struct TravelCrossing {
    std::uint32_t line = 0;       // 0-based line of the move that crosses
    double z = 0, x = 0, y = 0;   // where it first comes near the support
};

// One owner's support, judged on its own.
struct StandingSide {
    int islands = 0;              // islands of at least min_island_mm2 (one per layer)
    int under = 0;                // of those, under min_stiffness (floating ones included)
    int floating = 0;             // with neither a parent below nor a base
    int braces = 0;               // brace nodes
    double under_filament_mm = 0; // filament in the islands under min_stiffness
    double weakest_k = -1;        // -1: no island
    double weakest_standing_k = -1;  // the same over the islands that are not floating
    std::vector<WeakIsland> weakest;  // weakest first, one per place (2 mm apart)
    int travels = 0;              // travels crossing this side's fresh support
    std::vector<TravelCrossing> first_travels;  // the first few, in file order
    int weak_travels = 0;         // of those, over an island under min_stiffness (where they first come near it)
};

struct StandingReport {
    double min_stiffness = 0;
    StandingSide added, original;
};

// `owner` has one entry per move of `program`.
StandingReport standing(const gcode::Program& program, const layers::LayerStack& stack,
                        const std::vector<SupportOwner>& owner, const Settings& settings, const StandingOptions& o);

// What fails (only the added support, and only with min_stiffness > 0).
void standing_failures(const StandingReport& r, std::vector<std::string>& failures);
std::string standing_text(const StandingReport& r);
std::string standing_json(const StandingReport& r);  // one JSON object, no trailing newline

}  // namespace scaffold::check
