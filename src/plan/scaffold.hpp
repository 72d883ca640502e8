#pragma once
// The planned support structure, in plain geometry: columns (vertical
// pillars and slanted connectors) and horizontal bridges. toolpath/ turns
// it into per-layer extrusions; plan/ knows nothing about G-code.
#include <vector>

#include "overhang/overhangs.hpp"

namespace scaffold::plan {

enum class Base { Bed, Model, Bridge, Column };  // Column: stacked on the segment below
enum class Top { Contact, Bridge, Column };      // touches the model / under a bridge / continues above

// A column whose centre moves linearly from bottom to top; vertical when
// (x0,y0) == (x1,y1). Radius may grow for tall pillars (slenderness).
struct Column {
    double x0 = 0, y0 = 0, z0 = 0;  // bottom centre (z0 = 0 on the bed)
    double x1 = 0, y1 = 0, z1 = 0;  // top centre (z1 = the supported z)
    double radius = 1.0;
    Base base = Base::Bed;
    Top top = Top::Contact;
    int point = -1;                 // index of the support point it holds, or -1
    double contact_z = 0;           // z of the model contact this column tapers to (0 = none)
    double neck = 0;                // length of that taper, mm (0: the settings' tip_length)
    double foot_radius = 0;         // flared foot on the bed (0 = none)
    double raft_size = 0;           // square raft under it on the first layer (0 = none)
    // Height from which it leans (0 = from z0): a connector's first loop on
    // a bar is centred on the bar, which is narrower than a loop is wide.
    double lean_from = 0;
    // METHOD's Standing rule: the radius grows by `taper` mm per mm below
    // hold_z, the top of what stands on the column (0: no taper).
    double taper = 0;
    double hold_z = 0;
    // What stands on it up to hold_z (connectors on the bar it holds) gives
    // this much more, mm/N, in series: the column may give the rest.
    double give = 0;
    // Where the model comes close the taper stops growing: the radius is at
    // most this (0: no cap), never under `radius`. One value per piece.
    double max_radius = 0;
};

// A horizontal bar printed as a bridge at height z (its lowest layer's bottom).
struct Bridge {
    double x0 = 0, y0 = 0, x1 = 0, y1 = 0;
    double z = 0;
    std::vector<int> points;        // support points it carries
    double gain = 0, score = 0;
    bool brace = false;             // ties columns (plan/braces), carries nothing
};

struct Xyz {
    double x = 0, y = 0, z = 0;
};

// What the plans made again must not take (the pipeline's rounds, by
// toolpath::unheld_bars): the bars whose lines a plan before failed to
// hold, and the places beside which they failed (a column a bar passed
// along without resting on it), each at that bar's z.
struct Forbidden {
    std::vector<Bridge> bars;
    std::vector<Xyz> places;
    bool empty() const { return bars.empty() && places.empty(); }
};

struct Scaffold {
    std::vector<Column> columns;
    std::vector<Bridge> bridges;
    std::vector<int> dropped_points;  // could not be supported (e.g. --buildplate-only)
    // Bridge ends no pillar reached. Never seen: a bar is a candidate only
    // where a pillar stands under both ends; reported, should it happen.
    std::vector<Xyz> unheld_bridge_ends;
    // Points on overhang no tip of the plan holds (METHOD's rule (c)) where
    // no pillar fits under the sheet (a slot, the crotch of a tusk): the
    // last round of plan::cover_unheld's points that got none, at the
    // height of the overhanging layer.
    std::vector<Xyz> uncovered;
};

}  // namespace scaffold::plan
