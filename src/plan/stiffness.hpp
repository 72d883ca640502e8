#pragma once
// METHOD's Standing rule, as the planner sizes columns for it: a column is a
// cantilever clamped at its base, k = 1 / C at its top, C = sum over its
// height of (lever arm)^2 dz / (E I). A single-wall ring of outer radius r
// printed with beads of width w has I = pi rc^3 w about any axis (rc its
// bead's centre-line radius). A column that widens downwards (a cone whose
// radius grows by `taper` mm per mm below its top) keeps its compliance
// bounded however tall it is, which a straight one does not (C ~ H^3):
// its lowest part, with the longest lever arm, is where width pays.
#include "gcode/settings.hpp"

namespace scaffold::plan {

// Second moment of area of a single-wall ring loop of outer radius r, mm^4
// (the centre-line radius as the toolpaths print it: loop_shape's).
double ring_inertia(double r, double width);

// Second moment of area, mm^4, of a bridge bar's layer bent about its long
// axis (its weaker one): two lines side by side, 2 w wide, as long as the
// bar and its reach into the pillars at both ends (pillar_radius / 2 each,
// bar_lines'). The validator's island there is at least this stiff: loops
// merged into it only add to it.
double bar_inertia(double length, double width, double pillar_radius);

// Compliance, mm/N, at lever height `top` above the part of a ring column
// between heights `lo` and `hi` (lo < hi <= top) whose outer radius is
// r + taper * (top - z) at height z: the integral of (top - z)^2 / (E I(z)).
double ring_compliance(double r, double taper, double top, double lo, double hi, double width, double modulus);

// The least taper (mm of radius per mm of height, at most kMaxTaper) for
// which a ring column of top radius r and height h is at least k_target
// N/mm stiff at its top, with `give` mm/N more in series (what stands on
// it); 0 when the straight column already is.
inline constexpr double kMaxTaper = 0.2;  // 11 degrees: wider would not fit beside a model
double taper_for(double r, double height, double k_target, double give, double width, double modulus);

// The stiffness the planner aims at: the validator's minimum with a margin
// for what the model of a ring leaves out (the polygon's corners, the tip's
// taper, a connector's lean); 0 when the rule is off.
inline constexpr double kStiffnessMargin = 1.25;
// The margin over --min-stiffness a column keeps with its connectors' give
// (the give is their worst case).
inline constexpr double kGiveMargin = 1.1;
// METHOD's brace: a column counts at a node only where its k is at least a
// quarter of the strongest's; the planner asks a tenth more (a helper
// pillar tied at 10, 20 and 30 mm beside a tapered column: 0.30).
inline constexpr double kBraceColumnShare = 0.25 * 1.1;
inline double target_stiffness(const Settings& s) { return s.min_stiffness * kStiffnessMargin; }

}  // namespace scaffold::plan
