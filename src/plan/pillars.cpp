#include "plan/pillars.hpp"

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <limits>
#include <numbers>
#include <tuple>

#include "layers/crossing.hpp"
#include "plan/lean_in.hpp"
#include "plan/stiffness.hpp"

namespace scaffold::plan {

double loop_shift_limit(double h, const Settings& s) {
    return 0.8 * (h * std::tan(s.overhang_angle_deg * std::numbers::pi / 180) + s.support_width / 2);
}

LoopShape loop_shape(double r, double width) {
    LoopShape shape;
    shape.centre_radius = std::max(r - width / 2, width * 0.25);
    shape.sides = std::clamp(static_cast<int>(std::ceil(2 * std::numbers::pi * shape.centre_radius / 0.6)), 8, 48);
    return shape;
}

std::vector<std::array<double, 2>> loop_vertices(double cx, double cy, double r, double width) {
    const LoopShape shape = loop_shape(r, width);
    std::vector<std::array<double, 2>> pts;
    pts.reserve(static_cast<std::size_t>(shape.sides) + 1);
    for (int k = 0; k <= shape.sides; ++k) {
        const double a = 2 * std::numbers::pi * (k % shape.sides) / shape.sides;
        pts.push_back({cx + shape.centre_radius * std::cos(a), cy + shape.centre_radius * std::sin(a)});
    }
    return pts;
}

double column_radius_at(const Column& c, double z, const Settings& s) {
    double r = c.radius + (c.taper > 0 && z < c.hold_z ? c.taper * (c.hold_z - z) : 0.0);
    if (c.max_radius > 0) r = std::max(c.radius, std::min(r, c.max_radius));
    if (const double neck = c.neck > 0 ? c.neck : s.tip_length; c.contact_z > 0 && neck > 0) {
        double t = (c.contact_z - z) / neck;  // 0 at the contact, 1 where the tip starts
        if (t < 1) r = s.tip_radius + (c.radius - s.tip_radius) * std::clamp(t, 0.0, 1.0);
    }
    if (c.base == Base::Bed && c.foot_radius > r && s.foot_height > 0 && z < s.foot_height) {
        double t = std::clamp(z / s.foot_height, 0.0, 1.0);
        r = std::max(r, c.foot_radius + (c.radius - c.foot_radius) * t);
    }
    return r;
}

namespace {

// Whether model on `layer` lies within `reach` of the centre and of 16
// points around the loop of radius rc.
bool loop_held(const Obstacles& obs, int layer, double x, double y, double rc, double reach) {
    if (obs.disc_clear(layer, x, y, reach)) return false;
    for (int k = 0; k < 16; ++k) {
        double a = k * std::numbers::pi / 8;
        if (obs.disc_clear(layer, x + rc * std::cos(a), y + rc * std::sin(a), reach)) return false;
    }
    return true;
}

// Whether the bottom loop of a column standing on the model's layer `layer`
// rests on it (METHOD.md's rule (b), as the validator applies it to a loop's
// sides): a vertex is anchored when model lies within `reach` of it, or of
// a neighbour one side away (a side is shorter than a dangling end, so the
// corner is held by the side before it; not the first vertex, where the
// path starts and ends); every side needs an anchored end,
// and its unheld rest is then a dangling end shorter than the side. So a
// loop lands on a sloping top, or across a slot narrower than about a side,
// not only on a flat top that holds all of it.
bool loop_rests(const Obstacles& obs, int layer, double x, double y, double r, double width, double reach) {
    const LoopShape shape = loop_shape(r, width);
    const int n = shape.sides;
    const double side = 2 * shape.centre_radius * std::sin(std::numbers::pi / n);
    if (side > kDanglingEnd) return false;
    std::array<bool, 48> held{};
    bool any = false;
    for (int k = 0; k < n; ++k) {
        double a = 2 * std::numbers::pi * k / n;
        held[k] = !obs.disc_clear(layer, x + shape.centre_radius * std::cos(a), y + shape.centre_radius * std::sin(a), reach);
        any = any || held[k];
    }
    if (!any) return false;
    // The first vertex is where the printed path starts and ends: no corner
    // there, nothing holds it but itself.
    auto anchored = [&](int k) { return held[k] || (k > 0 && (held[(k + 1) % n] || held[k - 1])); };
    for (int k = 0; k < n; ++k)
        if (!anchored(k) && !anchored((k + 1) % n)) return false;
    return true;
}

// Radius of the thin pillar tried where the normal one finds no room, as a
// share of the pillar radius.
constexpr double kThinFactor = 0.6;

// Farthest a pillar may wander sideways while stepping around the model.
constexpr double kMaxWander = 15.0;

struct Step {
    double x, y, z;
    double cap = 0;  // the column's max_radius on this layer (0: none)
};

// Radius of the column on a step of its path.
double step_radius(const Column& c, const Step& st, const Settings& s) {
    Column capped = c;
    capped.max_radius = st.cap;
    return column_radius_at(capped, st.z, s);
}

// The disc a column's loop of radius r on the layer at z must find clear of
// the model: the gap (only the contact itself, the top two layers, may come
// closer) and half a cell more (the model's raster falls up to half a cell
// short of a bead's edge; the validator measures from the bead).
double room_needed(const Column& c, double z, double r, const Settings& s) {
    return r + clearance_at(c, z, s) + s.resolution / 2;
}

// Largest radius in [lo, hi] (to 0.01 mm) whose disc, grown by `extra`,
// is clear of the model on `layer`, keeping only kSkirtGap from a skirt
// line (Obstacles::room_clear: the column's way, with its plain radius,
// keeps the whole gap); lo is known clear.
double widest_clear(const Obstacles& obs, int layer, double x, double y, double lo, double hi, double extra) {
    for (int i = 0; i < 7 && hi - lo > 0.01; ++i) {
        const double mid = (lo + hi) / 2;
        (obs.room_clear(layer, x, y, mid + extra) ? lo : hi) = mid;
    }
    return std::floor(lo * 100) / 100;
}

// A loop rests on the one below while no point of it moves out by more than
// the shift limit (its centre's step plus its radius's change); a capped
// radius changes by what the centre's step leaves of it, and by at least
// this share of it per layer.
constexpr double kCapChange = 0.2;
// Steps (mm of radius) in which a widened column's bottom loop is narrowed
// until it rests on the model's top.
constexpr double kRestNarrowing = 0.1;
// Shares of the Standing rule's taper at or below which drop_pillar looks
// for the widest that fits.
constexpr double kWidestBelow = 0.25;
// Places a tip short of the Standing rule tries after the first, around its
// point, for one that stands (in ring order: the rings within 0.75 mm).
constexpr int kWeakTipTries = 24;

// Caps limited to change per layer by what the shift limit leaves beside
// the centre's step, from the capped layers outwards (only ever lowered:
// the clearance found holds). A column capped beside a skirt on the first
// layer so widens to its taper within a few layers: the lowest part, with
// the longest lever, is where its stiffness comes from.
void smooth_caps(std::vector<Step>& path, const Column& proto, const layers::LayerStack& stack, int top_layer,
                 const Settings& s) {
    if (std::none_of(path.begin(), path.end(), [](const Step& st) { return st.cap > 0; })) return;
    const double none = std::numeric_limits<double>::infinity();
    std::vector<double> cap(path.size());
    for (std::size_t i = 0; i < path.size(); ++i) cap[i] = path[i].cap > 0 ? path[i].cap : none;
    // Each step as far as its own height lets a loop step out: thinner
    // layers than the top's (Cura's second layer over a raft, 0.08 mm above
    // its first at 0.3 mm layers) hold less.
    const double h_top = stack.layers[top_layer].height;
    std::vector<double> d(path.size(), 0.0);  // d[i]: between path[i - 1] and path[i]
    for (std::size_t i = 1; i < path.size(); ++i) {
        const double dz = path[i - 1].z - path[i].z;
        const double limit = loop_shift_limit(dz < h_top - 1e-6 ? dz : h_top, s);
        d[i] = std::max(kCapChange * limit, limit - std::hypot(path[i].x - path[i - 1].x, path[i].y - path[i - 1].y));
    }
    for (std::size_t i = 1; i < cap.size(); ++i) cap[i] = std::min(cap[i], cap[i - 1] + d[i]);
    for (std::size_t i = cap.size() - 1; i > 0; --i) cap[i - 1] = std::min(cap[i - 1], cap[i] + d[i]);
    for (std::size_t i = 0; i < path.size(); ++i) {
        const double r = column_radius_at(proto, path[i].z, s);
        path[i].cap = cap[i] < r - 1e-9 ? std::max(cap[i], proto.radius) : 0.0;
    }
}

// The column's give at hold_z along its path (METHOD's Standing rule, each
// step's loop at its own radius, caps included), down to its base at c.z0.
double path_compliance(const Column& c, const std::vector<Step>& path, const Settings& s) {
    double compliance = 0;
    for (std::size_t i = 0; i < path.size(); ++i) {
        const double below = i + 1 < path.size() ? path[i + 1].z : c.z0;
        const double lever = c.hold_z - path[i].z;
        if (lever <= 0) continue;
        compliance += lever * lever * (path[i].z - below) /
                      (s.modulus * ring_inertia(step_radius(c, path[i], s), s.support_width));
    }
    return compliance;
}

// widen_column on a way down found by descend (pillars.hpp says what it
// does). A tip falls back to the thin, plain column where a tapered one
// finds no way down (elephant x16: copies 6 mm apart, a 1 mm column from the
// bed, 0.18 N/mm), yet its lowest loops, with the longest lever, are where
// its give comes from and often where the room is.
bool widen_in_place(Column& c, std::vector<Step>& path, int top_layer, const layers::LayerStack& stack,
                    const Obstacles& obs, const Settings& s, double give) {
    if (path.size() < 2 || c.base == Base::Column || !(target_stiffness(s) > 0)) return false;
    const double before = path_compliance(c, path, s);
    const double allowed = 1 / (kGiveMargin * s.min_stiffness) - give;  // what the column may give and stand
    if (before <= allowed) return false;  // stands as it is
    const double full = taper_for(c.radius, c.hold_z - c.z0, target_stiffness(s), give, s.support_width, s.modulus);
    // Per step, the widest radius known clear and the narrowest known not
    // (the room does not depend on the taper asked about).
    std::vector<double> clear(path.size()), blocked(path.size(), std::numeric_limits<double>::infinity());
    for (std::size_t i = 0; i < path.size(); ++i) clear[i] = step_radius(c, path[i], s);
    // The way down widened to `taper`, each loop as wide as the room on its
    // layer allows; its compliance, or infinity where no loop got wider.
    auto widened_to = [&](double taper, Column& wide, std::vector<Step>& widened) {
        wide = c;
        wide.taper = taper;
        wide.max_radius = 0;
        widened = path;
        bool wider = false;
        int l = top_layer;
        for (std::size_t i = 0; i < widened.size() && l >= 0; ++i, l = stack.layers[l].below) {
            Step& st = widened[i];
            const double r_was = step_radius(c, path[i], s);
            const double r_full = column_radius_at(wide, st.z, s);
            double r = r_full;
            if (i + 1 == widened.size() && c.base == Base::Model) {
                r = r_was;  // the bottom loop rests as found
            } else if (r_full > r_was + 0.01 && r_full > clear[i]) {
                const double extra = clearance_at(wide, st.z, s) + s.resolution / 2;
                if (r_full < blocked[i] && obs.room_clear(l, st.x, st.y, r_full + extra)) {
                    clear[i] = r_full;
                } else {
                    blocked[i] = std::min(blocked[i], r_full);
                    r = widest_clear(obs, l, st.x, st.y, std::max(r_was, clear[i]), std::min(r_full, blocked[i]), extra);
                    clear[i] = std::max(clear[i], r);
                }
            }
            st.cap = r < r_full - 1e-9 ? std::max(r, wide.radius) : 0.0;
            wider |= r > r_was + 0.01;
        }
        if (!wider) return std::numeric_limits<double>::infinity();
        smooth_caps(widened, wide, stack, top_layer, s);
        return path_compliance(wide, widened, s);
    };
    Column best_c, wide;
    std::vector<Step> best_path, widened;
    double best = before;
    auto keep = [&](double compliance) {
        if (!(compliance < best)) return;
        best = compliance;
        best_c = wide;
        best_path = widened;
    };
    if (full > c.taper + 1e-9) keep(widened_to(full, wide, widened));
    // Where the model beside its lower loops caps them, the rule's taper
    // for a straight column falls short: the least taper up to kMaxTaper
    // that stands with the caps (Cura's four bunnies at x +-30 mm: a 58.6 mm
    // column capped from 4 to 2.9 mm beside a bunny's body between 9 and
    // 21 mm, 1.94 N/mm at the rule's taper). Where none does, the rule's:
    // a cone 9 mm wide at the bed that still falls short costs more than
    // the braces that may yet tie it.
    const double lo0 = std::max(full, c.taper);
    if (best > allowed && lo0 < kMaxTaper - 1e-9) {
        const double at_max = widened_to(kMaxTaper, wide, widened);
        if (at_max <= allowed) {
            double lo = lo0, hi = kMaxTaper;  // tapers short of the rule and standing
            Column hi_column = wide;
            std::vector<Step> hi_path = widened;
            double hi_compliance = at_max;
            for (int i = 0; i < 6; ++i) {
                const double mid = (lo + hi) / 2, compliance = widened_to(mid, wide, widened);
                if (compliance <= allowed) {
                    hi = mid;
                    hi_column = wide;
                    hi_path = widened;
                    hi_compliance = compliance;
                } else {
                    lo = mid;
                }
            }
            wide = std::move(hi_column);
            widened = std::move(hi_path);
            keep(hi_compliance);
        }
    }
    if (!(best < before)) return false;
    c = std::move(best_c);
    path = std::move(best_path);
    return true;
}

// Where a column found its base on the model: the layer of its bottom loop
// and the model's layer under it.
struct ModelBase {
    int back_layer = -1, model_layer = -1;
    double reach = 0;  // the self-supporting reach descend judged its rest with
};

// Offsets (mm) the bottom loop of a column standing on the model may be
// moved by, so that the validator's walk holds all of it.
// (At most the shift limit, 0.41 mm at 0.2 mm layers: the loop above must
// still rest on it.) In 16 directions, from +x counter-clockwise.
constexpr std::array<double, 4> kSettleShifts{0.1, 0.2, 0.3, 0.4};
constexpr int kSettleDirections = 16;

// The vertex test (loop_rests) passes some bottom loops the validator's walk
// does not: a side running along the edge of the model's top outside the
// reach (figure.cura413, bunny.slic3r13 and a benchy at
// --min-overhang-area 0: 0.15-0.36 mm^2 each). Where a bottom loop a
// little aside (still clear of the model on its layer, the loop above still
// resting on it) is held all round by the walk, it goes there (true).
// Otherwise it is Settle::Unheld: a tip then looks further (the next place
// around its point); a bar's end stays as it is, since whether a bar's
// column stands (the bar search's answers) is the vertex test's. Asked with
// the column's final radius: a column on the model is narrowed after its way
// down is found.
// METHOD's Standing rule counts an island as standing on the model (a base)
// when at least 30 % of its cells lie over the model's footprint of the
// layers within two nominal layer heights below. A loop held by rule (b)
// may still fail that: one laid across a slot, over two walls 1.3 mm apart,
// rests on the walls at four short crossings (a Kiri:Moto benchy: a
// floating island). Asked of the loop's beads as written, on the
// validator's lattice; the validator also fills the footprint's holes up
// to 4 mm^2, which is not done here (so this asks at least as much), and
// the share asked is a little over METHOD's for an island that meets
// another piece of support and counts a few cells more.
constexpr double kBaseShare = 0.35;

// A loop's vertices as the file will hold them (three decimals), into `out`.
void write_loop(std::vector<std::array<float, 2>>& out, double x, double y, double r, double width) {
    out.clear();
    for (const auto& v : loop_vertices(x, y, r, width)) out.push_back({layers::as_written(v[0]), layers::as_written(v[1])});
}

bool loop_on_footprint(const std::vector<std::array<float, 2>>& written, int layer, const layers::LayerStack& stack,
                       const Settings& s) {
    if (written.size() < 2) return false;
    const double cell = s.resolution, half = s.support_width / 2 + cell;
    double x0 = 1e300, y0 = 1e300, x1 = -1e300, y1 = -1e300;
    for (const auto& v : written) {
        x0 = std::min(x0, static_cast<double>(v[0]));
        y0 = std::min(y0, static_cast<double>(v[1]));
        x1 = std::max(x1, static_cast<double>(v[0]));
        y1 = std::max(y1, static_cast<double>(v[1]));
    }
    // On the lattice of multiples of the cell, as layers::make_grid lays it.
    const double gx = std::floor((x0 - half) / cell) * cell, gy = std::floor((y0 - half) / cell) * cell;
    layers::BitGrid loop(gx, gy, x1 + half, y1 + half, cell);
    for (std::size_t k = 0; k < written.size(); ++k) {
        const auto& a = written[k];
        const auto& b = written[(k + 1) % written.size()];
        loop.draw_segment(a[0], a[1], b[0], b[1], s.support_width);
    }
    const std::size_t cells = loop.count();
    if (cells == 0) return false;
    layers::BitGrid foot = loop.empty_like();
    const layers::Layer& top = stack.layers[static_cast<std::size_t>(layer)];
    const double hw = std::max(s.layer_height, top.nominal_height), lowest = top.z - 2.0 * hw - 1e-3;
    for (int k = layer - 1; k >= 0; --k) {
        const layers::Layer& b = stack.layers[static_cast<std::size_t>(k)];
        if (b.z < lowest - 1.0) break;
        if (b.z >= top.z - layers::kZEps || b.z < lowest) continue;
        for (const layers::Segment& sg : b.segments) {
            if (sg.role == gcode::Role::Skirt) continue;
            const double h = sg.width / 2;
            if (std::max(sg.x0, sg.x1) + h < gx || std::min(sg.x0, sg.x1) - h > x1 + half ||
                std::max(sg.y0, sg.y1) + h < gy || std::min(sg.y0, sg.y1) - h > y1 + half)
                continue;
            foot.draw_segment(sg.x0, sg.y0, sg.x1, sg.y1, sg.width);
        }
    }
    foot &= loop;
    return static_cast<double>(foot.count()) >= kBaseShare * static_cast<double>(cells);
}

enum class Settle { Held, Moved, Unheld };
Settle settle_on_model(const Column& proto, std::vector<Step>& path, const ModelBase& base,
                     const layers::LayerStack& stack, const Obstacles& obs, const Settings& s) {
    const int back_layer = base.back_layer, model_layer = base.model_layer;
    const double reach = base.reach;
    if (path.size() < 2 || back_layer < 0) return Settle::Held;  // a column's top stays under what it holds
    Step& back = path.back();
    const Step& up = path[path.size() - 2];
    const double r = step_radius(proto, back, s);
    const LoopShape shape = loop_shape(r, s.support_width);
    // The walk is not monotonic in the reach: a side whose far corner comes
    // within reach is a run between held ends, which must cross the edge,
    // where with that corner out of reach it was a short dangling end. So
    // the loop is walked exactly as the validator will walk it: its vertices
    // as written, the beads beneath drawn on the validator's lattice, from
    // their edges (at three reaches about the validator's on this raster, a
    // tip's loop on bunny.slic3r13 passed and left 0.20 mm^2 of a side
    // unheld: held at both ends, not in the middle, a run along the edge).
    const double slope = std::tan(s.overhang_angle_deg * std::numbers::pi / 180);
    const double walk_reach = stack.layers[back_layer].height * slope + s.resolution / 2;
    // The beads beneath drawn once over every place the loop is tried at
    // (up to the last settle shift away), with the crossing test's margin.
    const double around = shape.centre_radius + kSettleShifts.back() + layers::kBeneathMargin + 0.1;
    const double bx0 = back.x - around, by0 = back.y - around, bx1 = back.x + around, by1 = back.y + around;
    std::vector<layers::BeadBeneath> beads;
    for (int k : stack.layers[back_layer].beneath)
        for (const layers::Segment& sg : stack.layers[k].segments)
            if (std::max(sg.x0, sg.x1) >= bx0 - 2 && std::min(sg.x0, sg.x1) <= bx1 + 2 &&
                std::max(sg.y0, sg.y1) >= by0 - 2 && std::min(sg.y0, sg.y1) <= by1 + 2)
                beads.push_back({sg.x0, sg.y0, sg.x1, sg.y1, sg.width, sg.role != gcode::Role::Skirt});
    const layers::Beneath under(beads, bx0, by0, bx1, by1, walk_reach, s.resolution);
    std::vector<std::array<float, 2>> written;
    auto held = [&](double x, double y) {
        if (!loop_rests(obs, model_layer, x, y, r, s.support_width, reach)) return false;
        write_loop(written, x, y, r, s.support_width);
        return under.path_held(written, s.marked_bridge_limit) && loop_on_footprint(written, back_layer, stack, s);
    };
    if (held(back.x, back.y)) return Settle::Held;
    const double need = room_needed(proto, back.z, r, s);
    const double rc_up = loop_shape(step_radius(proto, up, s), s.support_width).centre_radius;
    const double limit = loop_shift_limit(std::min(stack.layers[back_layer].height, up.z - back.z), s);
    for (double d : kSettleShifts)
        for (int k = 0; k < kSettleDirections; ++k) {
            const double a = 2 * std::numbers::pi * k / kSettleDirections;
            const double x = back.x + d * std::cos(a), y = back.y + d * std::sin(a);
            if (loops_apart(up.x, up.y, rc_up, x, y, shape.centre_radius) > limit) continue;
            if (!obs.disc_clear(back_layer, x, y, need) || !held(x, y)) continue;
            back.x = x;
            back.y = y;
            return Settle::Moved;
        }
    return Settle::Unheld;
}

// The column a drop starts from, its top at z1: tapered to a tip at the
// top (a contact, and a bridge end too, which the narrow top holds as well
// and which then fits closer to the model), no wider than the slenderness
// limit asks, sized for what stands on it up to `hold` with `give` more.
Column plain_column(Top top, double z1, double hold, double give, const Settings& s) {
    Column proto;
    proto.top = top;
    proto.z1 = z1;
    proto.contact_z = z1;
    // Tall pillars wobble: keep height / diameter within the slenderness limit.
    proto.radius = std::max(s.pillar_radius, z1 / (2 * s.slenderness));
    // METHOD's Standing rule: widened downwards for what stands on it, as
    // if it stood on the bed until its base is known.
    proto.hold_z = std::max(z1, hold);
    proto.give = give;
    return proto;
}

// How far a column's bottom loop may reach past the model under it and
// still rest on it, for a column whose top is on `top_layer`.
double rest_reach(const layers::LayerStack& stack, int top_layer, const Settings& s) {
    const double slope = std::tan(s.overhang_angle_deg * std::numbers::pi / 180);
    return stack.layers[top_layer].height * slope * 0.8;
}

// A bridge end right over the model's top rests on it: no column needed.
bool rests_on_model(double x, double y, int top_layer, const layers::LayerStack& stack, const Obstacles& obs,
                    const Settings& s) {
    return loop_held(obs, top_layer, x, y, s.tip_radius, rest_reach(stack, top_layer, s));
}

// Where a descent would have asked the trunks: the layer, the centre above
// it, and how near a trunk's loop must come there to change the walk.
struct TrunkCheck {
    int layer;
    float x, y, reach;
};

// Walks the column down from its top layer, stepping aside where the model
// comes too close. Returns the centre per layer (top first), with the base.
// `checks` (optional): where it asked the trunks; `trunk_used`: set where
// a trunk changed the walk (it stood on one or leaned towards one).
bool descend(Column& proto, int top_layer, const layers::LayerStack& stack, const Obstacles& obs, const Settings& s,
             std::vector<Step>& path, const Trunks* trunks, ModelBase* base = nullptr,
             std::vector<TrunkCheck>* checks = nullptr, bool* trunk_used = nullptr) {
    double cx = proto.x1, cy = proto.y1, wander = 0;
    double height_above = 0;  // of the layer of path.back()
    int back_layer = -1;      // the layer of path.back()
    path.clear();
    for (int l = top_layer; l >= 0; l = stack.layers[l].below) {
        const layers::Layer& layer = stack.layers[l];
        double r = column_radius_at(proto, layer.z, s);
        double need = room_needed(proto, layer.z, r, s);
        bool first = path.empty();
        // A trunk changes the walk only where a loop of it comes within the
        // steer (leaning) or the shift limit (standing on it: loops_apart is
        // at least the centres' distance).
        if (checks && !first)
            checks->push_back({l, static_cast<float>(cx), static_cast<float>(cy),
                               static_cast<float>(loop_shift_limit(height_above, s))});
        if (trunks && !first && !trunks->at(l).empty()) {
            // Stand on a trunk whose loop here holds our loop above (its
            // centre line within the reach of the trunk's bead).
            const Step& up = path.back();
            const double rc_up = loop_shape(step_radius(proto, up, s), s.support_width).centre_radius;
            const double hold = loop_shift_limit(height_above, s);
            for (const Trunks::Loop& o : trunks->at(l))
                // (A trunk sized for less than what stands on this column
                // would not stand it: METHOD's Standing rule.)
                if (loops_apart(o.x, o.y, o.rc, up.x, up.y, rc_up) <= hold &&
                    (!(target_stiffness(s) > 0) || o.hold_z >= proto.hold_z - 1e-6)) {
                    if (trunk_used) *trunk_used = true;
                    proto.base = Base::Column;
                    proto.z0 = layer.z;
                    smooth_caps(path, proto, stack, top_layer, s);
                    return true;
                }
            // Otherwise lean towards the nearest trunk within reach, as far
            // as a loop may shift on the one below.
            const Trunks::Loop* near = nullptr;
            double near_d = trunks->steer();
            for (const Trunks::Loop& o : trunks->at(l)) {
                double d = std::hypot(o.x - cx, o.y - cy);
                if (d < near_d) { near_d = d; near = &o; }
            }
            const double step = loop_shift_limit(height_above, s);
            if (near && near_d > 1e-9 && wander + step <= kMaxWander) {
                double k = std::min(step, near_d) / near_d;
                double nx = cx + (near->x - cx) * k, ny = cy + (near->y - cy) * k;
                if (obs.disc_clear(l, nx, ny, need)) {
                    if (trunk_used) *trunk_used = true;
                    cx = nx;
                    cy = ny;
                    wander += std::min(step, near_d);
                }
            }
        }
        bool clear = obs.disc_clear(l, cx, cy, need);
        if (!clear && !first) {
            // Step aside by what the loop below still holds, preferring the
            // direction with the most room; fixed order breaks ties.
            // A loop may shift by the self-supporting reach plus half its
            // bead and still rest on the one below (its centre line is held):
            // the reach over the gap up to the loop above, not this layer's
            // own height (a thicker first layer; KISSlicer's objects on Z
            // grids of their own, layers 0.09 mm apart).
            double step = loop_shift_limit(height_above, s);
            int best = -1;
            for (double margin : {0.4, 0.0}) {
                for (int k = 0; k < 8 && best < 0; ++k) {
                    double a = k * std::numbers::pi / 4;
                    if (obs.disc_clear(l, cx + step * std::cos(a), cy + step * std::sin(a), need + margin)) best = k;
                }
                if (best >= 0) break;
            }
            if (best >= 0 && wander + step <= kMaxWander) {
                cx += step * std::cos(best * std::numbers::pi / 4);
                cy += step * std::sin(best * std::numbers::pi / 4);
                wander += step;
                clear = obs.disc_clear(l, cx, cy, need);
            }
        }
        double cap = 0;
        if (!clear && !first && proto.taper > 0) {
            // METHOD's Standing rule: a column hugging a wall is as wide as
            // the gap allows on each layer, not narrow all the way down:
            // here, or a step aside, wherever it is widest.
            Column plain = proto;
            plain.taper = 0;
            const double r_plain = column_radius_at(plain, layer.z, s), extra = need - r;
            const double step = loop_shift_limit(height_above, s);
            double best = -1, bx = cx, by = cy;
            for (int k = -1; k < 8; ++k) {
                if (k >= 0 && wander + step > kMaxWander) break;
                const double a = k * std::numbers::pi / 4;
                const double px = k < 0 ? cx : cx + step * std::cos(a), py = k < 0 ? cy : cy + step * std::sin(a);
                if (r_plain >= r - 0.01 || !obs.disc_clear(l, px, py, r_plain + extra)) continue;
                const double w = widest_clear(obs, l, px, py, r_plain, r, extra);
                if (w > best + 0.01) { best = w; bx = px; by = py; }
            }
            if (best > 0) {
                if (bx != cx || by != cy) wander += step;
                cx = bx;
                cy = by;
                cap = std::max(proto.radius, best);
                clear = true;
            }
        }
        if (clear) {
            path.push_back({cx, cy, layer.z, cap});
            height_above = layer.height;
            back_layer = l;
            continue;
        }
        // Stand on the model only where it holds the whole bottom loop (every
        // point of it within the self-supporting reach); model beside the
        // column, or under only part of it, is a collision: try elsewhere.
        // On the first layer only a loop held all round: what blocks the way
        // there is mostly a skirt or brim line, which holds only what lies on it.
        smooth_caps(path, proto, stack, top_layer, s);
        if (first) return false;
        double r_last = step_radius(proto, path.back(), s);
        const double rest_reach = plan::rest_reach(stack, top_layer, s);
        auto rests = [&](double radius) {
            return layer.on_bed ? loop_held(obs, l, cx, cy, loop_shape(radius, s.support_width).centre_radius, rest_reach)
                                : loop_rests(obs, l, cx, cy, radius, s.support_width, rest_reach);
        };
        // Widened for the Standing rule more than the model's top here
        // holds (a post's foot): the bottom loop as wide as lies on it all
        // round (not across a slot: the validator's base wants a share of
        // the island over the model), the loops above widening again as fast
        // as each may step out.
        bool rest = rests(r_last);
        // A column arriving at the outer edge of a brim (the first layer's
        // lines round the model) half over it: its bottom loop moved onto
        // the brim, as far as a loop may shift on the one above, where the
        // brim holds it all round (cura531_benchy at --min-overhang-area 0:
        // a column down a hull ended at a brim's edge, where only the
        // thinnest plain one rested: 0.18 N/mm over 12.4 mm).
        if (!rest && layer.on_bed && path.size() >= 2 && back_layer >= 0) {
            const Step& up = path[path.size() - 2];
            Step& back = path.back();
            const double lim = loop_shift_limit(up.z - back.z, s);
            const double need_back = room_needed(proto, back.z, r_last, s);
            const double rc = loop_shape(r_last, s.support_width).centre_radius;
            for (int k = 0; k < 8 && !rest; ++k) {
                const double a = k * std::numbers::pi / 4;
                const double nx = up.x + lim * std::cos(a), ny = up.y + lim * std::sin(a);
                const double moved = std::hypot(nx - back.x, ny - back.y);
                if (wander + moved > kMaxWander || !obs.disc_clear(back_layer, nx, ny, need_back) ||
                    !loop_held(obs, l, nx, ny, rc, rest_reach))
                    continue;
                back.x = cx = nx;
                back.y = cy = ny;
                wander += moved;
                rest = true;
            }
        }
        if (!rest && !layer.on_bed && proto.taper > 0)
            for (double narrow = r_last - kRestNarrowing; narrow >= proto.radius - 1e-9; narrow -= kRestNarrowing)
                if (loop_held(obs, l, cx, cy, loop_shape(narrow, s.support_width).centre_radius, rest_reach)) {
                    path.back().cap = path.back().cap > 0 ? std::min(path.back().cap, narrow) : narrow;
                    smooth_caps(path, proto, stack, top_layer, s);
                    r_last = step_radius(proto, path.back(), s);
                    rest = rests(r_last);
                    break;
                }
        if (!rest) return false;
        if (base != nullptr) *base = {back_layer, l, rest_reach};
        proto.base = Base::Model;
        proto.z0 = layer.z;
        return true;
    }
    proto.base = Base::Bed;
    proto.z0 = 0;
    smooth_caps(path, proto, stack, top_layer, s);
    return true;
}

}  // namespace

struct DescentCache::Impl {
    // Every field of the column walked, and its top layer, by their bits.
    using Key = std::array<std::uint64_t, 20>;
    struct Hash {
        std::size_t operator()(const Key& k) const {
            std::uint64_t h = 0x9E3779B97F4A7C15ull;
            for (std::uint64_t v : k) h = (h ^ v) * 0xBF58476D1CE4E5B9ull, h ^= h >> 31;
            return static_cast<std::size_t>(h);
        }
    };
    struct Walk {
        bool ok = false;
        Column proto;  // as the walk left it (its base and z0)
        std::vector<Step> path;
        ModelBase base;
        std::vector<TrunkCheck> checks;
    };
    std::unordered_map<Key, Walk, Hash> walks;
    std::size_t bytes = 0;
    // Past this the walks found are not kept (a plan's pillars take a few MB).
    static constexpr std::size_t kBudget = std::size_t{96} << 20;

    static Key key(const Column& c, int top_layer) {
        auto b = [](double v) { return std::bit_cast<std::uint64_t>(v); };
        return {b(c.x0), b(c.y0), b(c.z0), b(c.x1), b(c.y1), b(c.z1), b(c.radius),
                static_cast<std::uint64_t>(c.base), static_cast<std::uint64_t>(c.top),
                static_cast<std::uint64_t>(static_cast<std::int64_t>(c.point)), b(c.contact_z), b(c.neck),
                b(c.foot_radius), b(c.raft_size), b(c.lean_from), b(c.taper), b(c.hold_z), b(c.give),
                b(c.max_radius), static_cast<std::uint64_t>(static_cast<std::int64_t>(top_layer))};
    }
};

DescentCache::DescentCache() : impl(std::make_unique<Impl>()) {}
DescentCache::~DescentCache() = default;

namespace {

// Whether no loop of `trunks` comes near enough to any place the walk asked
// them (with a hair to spare for the places kept as floats).
bool trunks_leave_alone(const std::vector<TrunkCheck>& checks, const Trunks& trunks) {
    for (const TrunkCheck& c : checks) {
        const std::vector<Trunks::Loop>& loops = trunks.at(c.layer);
        const double reach = std::max(trunks.steer(), static_cast<double>(c.reach)) + 1e-3;
        for (const Trunks::Loop& o : loops)
            if (std::hypot(o.x - c.x, o.y - c.y) < reach) return false;
    }
    return true;
}

// descend, answered from `cache` where a kept walk holds for these trunks
// (none: the walk without trunks); a walk no trunk changed is kept.
bool descend_kept(Column& proto, int top_layer, const layers::LayerStack& stack, const Obstacles& obs,
                  const Settings& s, std::vector<Step>& path, const Trunks* trunks, ModelBase* base,
                  DescentCache* cache) {
    if (!cache) return descend(proto, top_layer, stack, obs, s, path, trunks, base);
    DescentCache::Impl& c = *cache->impl;
    const DescentCache::Impl::Key key = DescentCache::Impl::key(proto, top_layer);
    if (auto it = c.walks.find(key); it != c.walks.end() && (!trunks || trunks_leave_alone(it->second.checks, *trunks))) {
        ++cache->hits;
        const DescentCache::Impl::Walk& w = it->second;
        proto = w.proto;
        path = w.path;
        if (base) *base = w.base;
        return w.ok;
    }
    ++cache->misses;
    DescentCache::Impl::Walk w;
    bool trunk_used = false;
    ModelBase found;
    const bool ok = descend(proto, top_layer, stack, obs, s, path, trunks, &found, &w.checks, &trunk_used);
    if (base) *base = found;
    if (trunk_used || c.bytes > DescentCache::Impl::kBudget) return ok;
    w.ok = ok;
    w.proto = proto;
    w.path = path;
    w.base = found;
    c.bytes += sizeof(DescentCache::Impl::Walk) + w.path.size() * sizeof(Step) + w.checks.size() * sizeof(TrunkCheck);
    c.walks.insert_or_assign(key, std::move(w));
    return ok;
}

// The per-layer centres as columns, bottom first: a vertical column while
// the centre stays, a one-layer slanted column where it steps.
std::vector<Column> columns_of(const Column& proto, const std::vector<Step>& path) {
    std::vector<Step> v;  // vertices, bottom up, each with the cap of the piece ending there
    v.push_back({path.back().x, path.back().y, proto.z0});
    for (std::size_t i = path.size() - 1; i > 0; --i) {
        const Step &lo = path[i], &hi = path[i - 1];
        if (lo.x == hi.x && lo.y == hi.y && lo.cap == hi.cap) continue;
        if (v.back().z != lo.z) v.push_back(lo);
        v.push_back(hi);
    }
    if (v.back().z != path.front().z) v.push_back(path.front());
    std::vector<Column> out;
    for (std::size_t i = 0; i + 1 < v.size(); ++i) {
        Column c = proto;
        c.x0 = v[i].x; c.y0 = v[i].y; c.z0 = v[i].z;
        c.x1 = v[i + 1].x; c.y1 = v[i + 1].y; c.z1 = v[i + 1].z;
        c.max_radius = v[i + 1].cap;
        if (i > 0) c.base = Base::Column;
        if (i + 2 < v.size()) c.top = Top::Column;
        out.push_back(c);
    }
    return out;
}

// Largest foot and raft that keep the gap on the first layers.
void fit_foot_and_raft(Column& c, double top_z, const layers::LayerStack& stack, const Obstacles& obs, const Settings& s) {
    if (c.base != Base::Bed) return;
    // The layers each size is tried on, found once (not once per size: this
    // runs for every pillar end the bridge search asks about).
    std::vector<int> foot_layers, raft_layers;
    for (int l = 0; l < static_cast<int>(stack.layers.size()); ++l) {
        const layers::Layer& layer = stack.layers[l];
        if (!(layer.z >= s.foot_height || layer.z > c.z1)) foot_layers.push_back(l);
        if (layer.on_bed && layer.z <= c.z1) raft_layers.push_back(l);
    }
    if (top_z - c.z0 > kFootMinHeight) {
        for (double fr = s.foot_radius; fr > c.radius + 1e-9; fr -= 0.5) {
            c.foot_radius = fr;
            bool ok = true;
            for (std::size_t k = 0; k < foot_layers.size() && ok; ++k) {
                const int l = foot_layers[k];
                double z = stack.layers[l].z;
                double x, y;
                column_centre_at(c, z, x, y);
                ok = obs.disc_clear(l, x, y, column_radius_at(c, z, s) + s.xy_gap);
            }
            if (ok) break;
            c.foot_radius = 0;
        }
    }
    for (double size = s.raft_size; size >= 2 * c.radius; size -= 1.0) {
        bool ok = true;
        for (std::size_t k = 0; k < raft_layers.size() && ok; ++k)
            ok = obs.disc_clear(raft_layers[k], c.x0, c.y0, size / std::numbers::sqrt2 + s.xy_gap);
        if (ok) {
            c.raft_size = size;
            return;
        }
    }
    c.raft_size = 0;
}

}  // namespace

bool loop_stands_on_model(double x, double y, double r, int layer, const layers::LayerStack& stack, const Settings& s) {
    std::vector<std::array<float, 2>> written;
    write_loop(written, x, y, r, s.support_width);
    return loop_on_footprint(written, layer, stack, s);
}

int tip_layer(const layers::LayerStack& stack, int overhang_layer, const Settings& s) {
    int l = stack.layers[overhang_layer].below;
    for (int k = 0; k < s.top_gap_layers && l >= 0; ++k) l = stack.layers[l].below;
    return l;
}

namespace {

// Tip columns whose bottom loop leaves a sliver unheld, met while one
// drop_pillar call looks for a held one: the first is kept, and only so
// many more places are tried (each a descent and a walk of up to 65 loops:
// with no bound, --method pillars on a file without its comments, its
// points over sloping shelves, took minutes instead of 2 s).
inline constexpr int kUnheldTries = 12;
struct UnheldTips {
    std::optional<std::vector<Column>> first;
    int tries_left = kUnheldTries;
};

std::optional<std::vector<Column>> drop_pillar_shaped(double x, double y, int overhang_layer, Top top,
                                                      const layers::LayerStack& stack, const Obstacles& obs,
                                                      const Settings& s, const Trunks* trunks, TipPlaces places,
                                                      bool fit_base, double hold, double give, double stiff,
                                                      bool thin_above, UnheldTips* unheld = nullptr) {
    const int top_layer = top == Top::Contact ? tip_layer(stack, overhang_layer, s) : stack.layers[overhang_layer].below;
    if (top_layer < 0) return std::nullopt;
    Column proto = plain_column(top, stack.layers[top_layer].z, hold, give, s);
    // `stiff`: the share of the taper the rule asks for; negative: the plain
    // column of old, with its neck.
    if (stiff >= 0) {
        // No narrow neck under a bar that holds more above it: a neck far
        // below the top it holds is where such a column gives most.
        // (A thin column standing on it needs the narrow top to rest on.)
        if (top == Top::Bridge && hold > proto.z1 + 1e-6 && !thin_above) proto.contact_z = 0;
        proto.taper = stiff * taper_for(proto.radius, proto.hold_z, target_stiffness(s), give, s.support_width, s.modulus);
    }
    std::vector<Step> path;
    if (top == Top::Bridge && rests_on_model(x, y, top_layer, stack, obs, s)) return std::vector<Column>{};
    // The point itself first, then rings around it, in a fixed order.
    // The tip still holds the point from up to 3 mm away (point radius 3.5).
    static constexpr std::array<double, 9> kRings{0.0, 0.25, 0.5, 0.75, 1.0, 1.5, 2.0, 2.5, 3.0};
    bool under_sheet = true;
    // METHOD's Standing rule: a tip whose column, as found, is short of it
    // (capped where it passes the model) looks on around its point for a
    // place where it stands, a few places at most; else the stiffest found.
    const bool seek_standing = fit_base && top == Top::Contact && stiff >= 0 && target_stiffness(s) > 0;
    auto search = [&](const Column& shape) -> std::optional<std::vector<Column>> {
        std::optional<std::vector<Column>> weak;
        double weak_k = -1;
        int weak_tries = 0;
        for (double d : kRings) {
            if (top == Top::Bridge && d > 0) break;  // a bridge end stays where the bridge is
            int n = d == 0 ? 1 : (d < 1.75 ? 8 : 16);
            for (int k = 0; k < n; ++k) {
                double a = k * 2 * std::numbers::pi / n;
                Column c = shape;
                c.x0 = c.x1 = x + d * std::cos(a);
                c.y0 = c.y1 = y + d * std::sin(a);
                // METHOD's rule (c): a tip holds the sheet that rests on it.
                // Away from the point, the first pass takes only places where
                // the tip lies under the overhanging layer's own material.
                if (under_sheet && top == Top::Contact && d > 0 &&
                    obs.disc_clear(overhang_layer, c.x1, c.y1, s.tip_radius + s.resolution))
                    continue;
                // Leaning towards a trunk can lead into the model further
                // down: then the plain way down, without trunks.
                const Column start = c;
                ModelBase base;
                DescentCache* kept = trunks ? trunks->descents() : nullptr;
                if (!descend_kept(c, top_layer, stack, obs, s, path, trunks, &base, kept)) {
                    c = start;
                    if (!trunks || !descend_kept(c, top_layer, stack, obs, s, path, nullptr, &base, kept)) continue;
                }
                if (c.base == Base::Model && s.buildplate_only) return std::nullopt;
                // Thin pillars only where they stay within the slenderness limit.
                if (c.radius < proto.radius && c.z1 - c.z0 > 2 * c.radius * s.slenderness) continue;
                std::vector<Column> chain = columns_of(c, path);
                if (chain.empty()) continue;  // no layer above its base (a layer at z <= 0)
                // On the model the lever is shorter: as narrow as that allows
                // (inside the path found for the wider one). On a trunk, the
                // trunk's base is the base: keep it.
                const bool narrow = c.taper > 0 && c.base != Base::Column;
                Column narrowed = c;
                if (narrow)
                    // Never wider than the descent was checked for (a thin
                    // variant's own taper would be larger).
                    narrowed.taper = std::min(c.taper, stiff * taper_for(c.radius, c.hold_z - chain.front().z0,
                                                                         target_stiffness(s), give, s.support_width,
                                                                         s.modulus));
                Settle settled = Settle::Held;
                if (fit_base && c.base == Base::Model) {
                    settled = settle_on_model(narrowed, path, base, stack, obs, s);
                    if (settled == Settle::Moved) chain = columns_of(c, path);
                }
                if (narrow)
                    for (Column& piece : chain) piece.taper = narrowed.taper;
                // A tip whose bottom loop the validator would not hold
                // anywhere near looks on: around its point, then in the
                // next shapes (bunny.slic3r13 at --min-overhang-area 0: a
                // 1 mm loop half over air, 0.20 mm^2), the first such
                // column kept in `unheld`.
                if (settled == Settle::Unheld && top == Top::Contact && unheld) {
                    if (!unheld->first) unheld->first = chain;
                    if (--unheld->tries_left < 0) return unheld->first;
                    continue;
                }
                double short_k = -1;  // the column's stiffness, where it is short of the rule
                if (fit_base && top == Top::Contact) {
                    Column sized = c;
                    if (narrow) sized.taper = narrowed.taper;
                    if (widen_in_place(sized, path, top_layer, stack, obs, s, give)) chain = columns_of(sized, path);
                    if (seek_standing && sized.base != Base::Column) {
                        const double stands_k = 1 / (path_compliance(sized, path, s) + give);
                        if (stands_k < kGiveMargin * s.min_stiffness) short_k = stands_k;
                    }
                }
                if (fit_base && chain.front().base == Base::Bed)
                    fit_foot_and_raft(chain.front(), chain.back().z1, stack, obs, s);
                if (short_k < 0) return chain;
                if (short_k > weak_k) {
                    weak_k = short_k;
                    weak = std::move(chain);
                }
                if (++weak_tries > kWeakTipTries) return weak;
            }
        }
        return weak;
    };
    // Under the sheet first; then anywhere within reach of the point.
    for (bool pass : {true, false}) {
        if ((pass && places == TipPlaces::Beside) || (!pass && places == TipPlaces::UnderSheet)) continue;
        under_sheet = pass;
        if (auto chain = search(proto)) return chain;
        // A longer neck reaches into a crotch of the model (an elephant's leg
        // meeting its belly) where the full column does not, and stays wide
        // below it, where its width pays: before the thin columns.
        if (top == Top::Contact && proto.contact_z > 0 && s.tip_length > 0)
            for (double times : {2.0, 3.0}) {
                Column necked = proto;
                necked.neck = times * s.tip_length;
                if (auto chain = search(necked)) return chain;
            }
        // A short, thin pillar lands on a small or sloping top of the model
        // (an ear over a head) and fits narrow gaps where the normal one
        // does not; last, the thinnest column the tip allows, in a slot
        // beside a wall. Not where a wider one was found whose bottom loop
        // leaves a sliver unheld: a thin column stands far less (the
        // shuttle at --min-overhang-area 0: 0.72 -> 0.05 N/mm for 0.17 mm^2).
        if (top == Top::Contact && !s.buildplate_only && !(unheld && unheld->first)) {
            // A thinner top needs more taper for the same stiffness, and
            // may need one where the normal column needs none (a 2 mm
            // column stands 2 N/mm up to about 15 mm, a 1.2 mm one to about
            // 9: an elephant's column between its legs, 12.4 mm, 1.2 N/mm).
            auto retaper = [&](Column& c) {
                if (stiff >= 0)
                    c.taper = stiff * taper_for(c.radius, c.hold_z, target_stiffness(s), give, s.support_width, s.modulus);
            };
            Column thin = proto;
            thin.radius = std::max(s.tip_radius, s.pillar_radius * kThinFactor);
            retaper(thin);
            if (thin.radius < proto.radius)
                if (auto chain = search(thin)) return chain;
            Column thinnest = proto;
            thinnest.radius = s.tip_radius;
            retaper(thinnest);
            if (thinnest.radius < thin.radius)
                if (auto chain = search(thinnest)) return chain;
        }
        if (top != Top::Contact) break;
    }
    return std::nullopt;
}

}  // namespace

std::optional<std::vector<Column>> drop_pillar(double x, double y, int overhang_layer, Top top,
                                               const layers::LayerStack& stack, const Obstacles& obs,
                                               const Settings& s, const Trunks* trunks, TipPlaces places,
                                               bool fit_base, double hold, double give, bool thin_above,
                                               bool widest) {
    // Whether a pillar stands at all (fit_base false: a bridge end asked
    // about) is the plain column's question: a narrower one fits wherever a
    // wider one does.
    // A column whose bottom loop only the validator's walk leaves a sliver
    // of: kept while the other shapes are tried, taken if none stands held.
    UnheldTips unheld;
    if (target_stiffness(s) > 0 && fit_base) {
        // Where the widened column finds no way down, less widened ones, then
        // a straight one without a neck, then the plain one with its neck,
        // weaker (braced or reported by scaffold-check), rather than none.
        // Under a bar end that holds more above (where the widened column
        // has no neck), a neck may be all that fits at the top: a widened
        // column with a neck before the plain one.
        const int below = stack.layers[overhang_layer].below;
        const bool neck_too = !thin_above && top == Top::Bridge && below >= 0 && hold > stack.layers[below].z + 1e-6;
        auto shaped = [&](double stiff, bool neck) {
            return drop_pillar_shaped(x, y, overhang_layer, top, stack, obs, s, trunks, places, fit_base, hold, give,
                                      stiff, neck, &unheld);
        };
        // Whether a column meets the rule with what stands on it.
        auto stands = [&](const std::vector<Column>& c) {
            if (c.empty()) return true;
            const Column& f = c.front();
            const double own = ring_compliance(f.radius, f.taper, f.hold_z, f.z0, std::min(c.back().z1, f.hold_z),
                                               s.support_width, s.modulus);
            return 1 / (own + give) >= kGiveMargin * s.min_stiffness;
        };
        for (bool neck : {thin_above, true}) {
            double failed = -1;  // the last share of the taper that found no way down
            for (double stiff : {1.0, 0.5, 0.25, 0.0}) {
                auto chain = shaped(stiff, neck);
                if (!chain) {
                    failed = stiff;
                    continue;
                }
                // At kWidestBelow of the taper or less and short of the rule,
                // the widest that fits: the step between it and the share
                // that failed, halved three times (an elephant's column
                // leaning round its belly: 1.21 N/mm at 0.25, 2.39 at 0.44).
                // Above it the step is searched only when asked (`widest`):
                // where braces can tie the column, they cost less
                // (figure.prusaslicer25: +41 % of its support otherwise).
                double lo = stiff, hi = stiff <= kWidestBelow || widest ? failed : stiff;
                for (int i = 0; i < 3 && hi > lo && !stands(*chain); ++i) {
                    const double mid = (lo + hi) / 2;
                    if (auto wider = shaped(mid, neck)) {
                        chain = std::move(wider);
                        lo = mid;
                    } else {
                        hi = mid;
                    }
                }
                return chain;
            }
            if (!neck_too) break;
        }
    }
    if (auto chain = drop_pillar_shaped(x, y, overhang_layer, top, stack, obs, s, trunks, places, fit_base, hold, give,
                                        -1.0, thin_above, &unheld))
        return chain;
    return unheld.first;
}

std::size_t BarEndAnswers::Hash::operator()(const Key& k) const {
    std::size_t h = static_cast<std::size_t>(k.layer);
    for (std::uint64_t v : {k.x, k.y, k.radius, k.above_radius, k.above_height, k.reach})
        h = (h ^ v) * 0x100000001b3ULL + (h >> 29);
    return h;
}

std::optional<bool> BarEndAnswers::find(const Key& key) const {
    const std::lock_guard lock(mutex_);
    const auto it = map_.find(key);
    return it == map_.end() ? std::nullopt : std::optional<bool>(it->second);
}

std::size_t BarEndAnswers::size() const {
    const std::lock_guard lock(mutex_);
    return map_.size();
}

void BarEndAnswers::insert(const Key& key, bool stands) {
    const std::lock_guard lock(mutex_);
    map_.emplace(key, stands);
}

bool bar_end_stands(double x, double y, int overhang_layer, const layers::LayerStack& stack, const Obstacles& obs,
                    const Settings& s, BarEndAnswers& known) {
    auto full = [&] {
        return drop_pillar(x, y, overhang_layer, Top::Bridge, stack, obs, s, nullptr, TipPlaces::Any, false).has_value();
    };
    // drop_pillar's own steps, as it takes them for this question: the plain
    // column (no taper), from the point itself (a bar end does not move),
    // without trunks; the descent's straight part repeated here.
    const int top_layer = stack.layers[overhang_layer].below;
    if (top_layer < 0) return false;
    if (rests_on_model(x, y, top_layer, stack, obs, s)) return true;
    const Column proto = plain_column(Top::Bridge, stack.layers[top_layer].z, 0, 0, s);
    double above_radius = 0, above_height = 0;
    for (int l = top_layer; l >= 0; l = stack.layers[l].below) {
        const layers::Layer& layer = stack.layers[l];
        const double r = column_radius_at(proto, layer.z, s);
        if (obs.disc_clear(l, x, y, room_needed(proto, layer.z, r, s))) {  // as descend asks
            above_radius = r;
            above_height = layer.height;
            continue;
        }
        if (l == top_layer) return false;  // the descent's first layer does not step aside
        // Blocked within the tapered top: the radius below differs per top.
        if (r != proto.radius) return full();
        // Everything the rest of the descent reads: the place, the layer, the
        // radius from here down, the loop above (its radius and height) and
        // how far a bottom loop may reach (from the top layer's height).
        auto bits = [](double v) { return std::bit_cast<std::uint64_t>(v); };
        const BarEndAnswers::Key key{bits(x),          bits(y),
                                     bits(proto.radius), bits(above_radius),
                                     bits(above_height), bits(rest_reach(stack, top_layer, s)),
                                     l};
        if (const std::optional<bool> ok = known.find(key)) return *ok;
        const bool ok = full();
        known.insert(key, ok);
        return ok;
    }
    return true;  // straight down to the bed
}

bool widen_column(std::vector<Column>& chain, const layers::LayerStack& stack, const Obstacles& obs,
                  const Settings& s, double give) {
    if (chain.empty()) return false;
    int top_layer = -1;
    for (int l = 0; l < static_cast<int>(stack.layers.size()) && top_layer < 0; ++l)
        if (std::abs(stack.layers[l].z - chain.back().z1) < 1e-6) top_layer = l;
    if (top_layer < 0) return false;
    // The centre and cap per layer, top first, as the descent found them.
    std::vector<Step> path;
    for (int l = top_layer; l >= 0 && stack.layers[l].z > chain.front().z0 + 1e-6; l = stack.layers[l].below) {
        const double z = stack.layers[l].z;
        const auto piece = std::find_if(chain.begin(), chain.end(), [&](const Column& c) {
            return z > c.z0 + 1e-6 && z <= c.z1 + 1e-6;
        });
        if (piece == chain.end()) return false;
        double x, y;
        column_centre_at(*piece, z, x, y);
        path.push_back({x, y, z, piece->max_radius});
    }
    Column proto = chain.front();
    proto.top = chain.back().top;
    proto.max_radius = 0;
    if (!widen_in_place(proto, path, top_layer, stack, obs, s, give)) return false;
    chain = columns_of(proto, path);
    return true;
}

void Trunks::add(const std::vector<Column>& chain, const layers::LayerStack& stack, const Settings& s) {
    for (const Column& c : chain)
        for (int l = 0; l < static_cast<int>(stack.layers.size()); ++l) {
            const double z = stack.layers[l].z;
            if (stack.layers[l].purge || z <= c.z0 + 1e-6 || z > c.z1 + 1e-6) continue;
            double x, y;
            column_centre_at(c, z, x, y);
            at_[l].push_back({x, y, loop_shape(column_radius_at(c, z, s), s.support_width).centre_radius, c.hold_z});
        }
}

std::vector<int> canonical_order(const overhang::SupportPoints& points) {
    std::vector<int> order(points.points.size());
    for (std::size_t i = 0; i < order.size(); ++i) order[i] = static_cast<int>(i);
    std::stable_sort(order.begin(), order.end(), [&](int a, int b) {
        const auto &p = points.points[a], &q = points.points[b];
        return std::tie(p.layer, p.y, p.x, p.z) < std::tie(q.layer, q.y, q.x, q.z);
    });
    return order;
}

Scaffold plan_pillars(const overhang::SupportPoints& points, const layers::LayerStack& stack,
                      const Obstacles& obstacles, const Settings& settings) {
    // The report's simple pillars: vertical, no bridges, no leaning. Where a
    // pillar's straight way down meets a pillar already planned whose loop
    // holds its own, it stands on it: on a slope every layer's sliver gets a
    // point a fraction of a millimetre from the last, and pillars side by
    // side would print the same ring many times over. Lower points first
    // (the canonical order is by layer), so the higher stand on the lower.
    // Where no vertical pillar reaches a tip under the sheet, one leans in.
    Scaffold out;
    add_pillars(out, points, canonical_order(points), stack, obstacles, settings, 0.0);
    return out;
}

}  // namespace scaffold::plan
