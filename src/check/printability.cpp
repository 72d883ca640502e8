#include "check/printability.hpp"

#include "gcode/format.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <limits>
#include <map>
#include <set>
#include <numbers>

#include "gcode/blocks.hpp"
#include "gcode/error.hpp"
#include "gcode/lexer.hpp"
#include "layers/crossing.hpp"
#include "layers/frame.hpp"
#include "layers/layer_stack.hpp"
#include "layers/objects.hpp"
#include "layers/raster.hpp"
#include "layers/regions.hpp"

namespace scaffold::check {

namespace {

using layers::kZEps;
using layers::kStraightDeg;

using gcode::fixed;

bool comment_only(std::string_view t) {
    std::size_t i = t.find_first_not_of(" \t\r");
    return i == std::string_view::npos || t[i] == ';';
}

// Lines the edit may rewrite: comments (slicers' filament and time totals)
// and M73 progress (raised by the support's time); neither moves anything.
bool may_change(std::string_view t) {
    std::size_t i = t.find_first_not_of(" \t\r");
    return comment_only(t) || t.substr(i, 4) == "M73 ";
}

// The in-order match of `original` in `out`: every command line of the
// original must appear, unchanged and in order (comment-only lines and M73
// may change, see may_change). Lines of `out` left over
// were inserted (the support). A greedy scan finds a subsequence whenever
// one exists; a missing line is skipped and the scan goes on from the last
// match, up to kMaxMissing misses.
struct LineMatch {
    std::vector<bool> inserted;             // per line of out
    std::vector<std::uint32_t> out_line;    // per line of original; kNone if missing/comment
    int missing = 0;
    std::string first_missing;
};
constexpr std::uint32_t kNone = 0xffffffffu;
constexpr int kMaxMissing = 20;

LineMatch match_lines(const gcode::Program& out, const gcode::Program& original) {
    LineMatch m;
    m.inserted.assign(out.lines.size(), true);
    m.out_line.assign(original.lines.size(), kNone);
    for (std::size_t i = 0; i < out.lines.size(); ++i)
        if (may_change(out.line_text(i))) m.inserted[i] = false;  // comments and M73 carry no material
    std::size_t from = 0;
    for (std::size_t k = 0; k < original.lines.size(); ++k) {
        std::string_view want = original.line_text(k);
        if (may_change(want)) continue;
        if (m.missing > kMaxMissing) { ++m.missing; continue; }
        std::size_t i = from;
        while (i < out.lines.size() && (!m.inserted[i] || out.line_text(i) != want)) ++i;
        if (i < out.lines.size()) {
            m.inserted[i] = false;
            m.out_line[k] = static_cast<std::uint32_t>(i);
            from = i + 1;
        } else {
            if (m.missing++ == 0)
                m.first_missing = "original line " + std::to_string(k + 1) + " ('" + std::string(want.substr(0, 60)) +
                                  "') is missing or changed in the output";
        }
    }
    return m;
}

// first[l]..first[l+1]: the moves made by line l.
std::vector<std::uint32_t> moves_by_line(const gcode::Program& p) {
    std::vector<std::uint32_t> first(p.lines.size() + 1, 0);
    for (const auto& m : p.moves) ++first[m.line + 1];
    for (std::size_t l = 1; l < first.size(); ++l) first[l] += first[l - 1];
    return first;
}

bool near(double a, double b, double eps) { return std::abs(a - b) <= eps; }

// Does the model line print the same in the output as in the original? The
// same text can move differently when an inserted block leaves state behind
// (position, E register, relative mode, feed, tool): then its bead starts
// elsewhere, gets more or less filament, or prints at another speed.
std::string move_difference(const gcode::Move& a, const gcode::Move& b) {
    constexpr double kPos = 1e-3, kE = 1e-4;
    auto pt = [](double x, double y, double z) {
        return "(" + fixed(x, 3) + ", " + fixed(y, 3) + ", " + fixed(z, 3) + ")";
    };
    if (a.kind != b.kind) return "a different kind of move (travel/extrusion/retraction)";
    if (a.tool != b.tool) return "tool T" + std::to_string(b.tool) + " instead of T" + std::to_string(a.tool);
    // Travels only matter through where the next bead starts (checked there).
    if (a.kind == gcode::MoveKind::Travel) return {};
    if (a.kind == gcode::MoveKind::Extrude || a.kind == gcode::MoveKind::Wipe) {
        if (!near(a.x0, b.x0, kPos) || !near(a.y0, b.y0, kPos) || !near(a.z0, b.z0, kPos))
            return "starts at " + pt(b.x0, b.y0, b.z0) + " instead of " + pt(a.x0, a.y0, a.z0);
        if (!near(a.x1, b.x1, kPos) || !near(a.y1, b.y1, kPos) || !near(a.z1, b.z1, kPos))
            return "ends at " + pt(b.x1, b.y1, b.z1) + " instead of " + pt(a.x1, a.y1, a.z1);
        if (!near(a.feed_mm_per_min, b.feed_mm_per_min, 0.01))
            return "prints at F" + fixed(b.feed_mm_per_min, 0) + " instead of F" + fixed(a.feed_mm_per_min, 0);
    }
    if (!near(a.e, b.e, kE + 1e-6 * std::abs(a.e)))
        return "moves E by " + fixed(b.e, 5) + " instead of " + fixed(a.e, 5);
    return {};
}

struct LayerGrids {
    int index = -1;
    layers::BitGrid model, support;
    layers::BitGrid skirt;  // skirt and brim: material, but it encloses nothing
    layers::BitGrid seeds;  // the model's beads that are no walls (layers::draw_hole_seed)
    // With --original, the support the original itself holds (a file sliced
    // with support on): it holds what rests on it like any support, but its
    // own faults are the original's, reported apart.
    layers::BitGrid slicer;
};

// A straight run of consecutive segments of one extrusion path, as samples
// along its centre line (seg: index into the layer's segments).
using Sample = layers::PieceSample;

void add_issue(std::vector<LayerIssue>& v, LayerIssue issue, int keep) {
    v.push_back(issue);
    std::stable_sort(v.begin(), v.end(), [](const LayerIssue& a, const LayerIssue& b) { return a.area_mm2 > b.area_mm2; });
    if (static_cast<int>(v.size()) > keep) v.resize(keep);
}

LayerIssue issue_of(const layers::BitGrid& g, int layer, double z) {
    LayerIssue is;
    is.layer = layer;
    is.z = z;
    double sx = 0, sy = 0;
    std::size_t n = 0;
    for (int j = 0; j < g.height(); ++j)
        for (int i = 0; i < g.width(); ++i)
            if (g.get(i, j)) { sx += g.cx(i); sy += g.cy(j); ++n; }
    is.area_mm2 = static_cast<double>(n) * g.cell_area();
    if (n) { is.x = sx / static_cast<double>(n); is.y = sy / static_cast<double>(n); }
    return is;
}


enum class ProblemKind { Width, EJump, OutsideBed };

// Around the slicer's own extrusions where the file states no bed: support
// may stand beside the model's edge (a 7 mm raft square, a bar).
constexpr double kUnstatedBedMargin = 10.0;
struct Problem {
    std::uint32_t line;
    ProblemKind kind;
    std::string what;
};
struct Extrusion {
    std::vector<Problem> problems;
    double support_mm = 0, model_mm = 0;
};

// Each extruding move's layer height: the slicer's stated one, else its
// layer's z less the z of the layer beneath; 0 where the move is in no layer.
std::vector<float> move_heights(const gcode::Program& p, const layers::LayerStack& stack) {
    std::vector<float> h(p.moves.size(), 0.0f);
    for (const layers::Layer& l : stack.layers)
        for (const layers::Segment& sg : l.segments)
            h[sg.move] = static_cast<float>(l.nominal_height > 0 ? l.nominal_height : l.height);
    return h;
}

// Extrusion sanity and filament, per move: implied widths, E pushed without
// motion to lay it down, extrusion off the bed.
template <class IsSupport>
Extrusion extrusion_problems(const gcode::Program& p, const Settings& settings, const std::vector<float>& heights,
                             IsSupport is_support) {
    const double fd = settings.filament_diameter, nozzle = settings.nozzle_diameter;
    Extrusion x;
    auto note = [&](std::uint32_t line, ProblemKind kind, std::string what) { x.problems.push_back({line, kind, std::move(what)}); };
    // E jumps: filament pushed without (enough) XY motion to lay it down.
    // A prime may give back what was retracted plus retract_length + 0.5 mm
    // (slicers' extra restart length); anything beyond is a jump.
    const double prime_allowance = settings.retract_length + 0.5;
    // Sane widths: 0.2x..3x the nozzle. The slicers' own model lines may go
    // thinner (Slic3r ends infill with 0.6 mm pieces 0.07 mm wide): too little
    // plastic is no printability hazard there, so the model's floor is 0.05x.
    const double max_width = 3.0 * nozzle, min_support_width = 0.2 * nozzle, min_model_width = 0.05 * nozzle;
    double retracted = 0;  // filament pulled back and not yet primed
    for (const auto& m : p.moves) {
        bool sup = is_support(m);
        if (m.kind == gcode::MoveKind::Retract || m.kind == gcode::MoveKind::Wipe) retracted -= m.e;
        if (m.kind == gcode::MoveKind::Extrude) (sup ? x.support_mm : x.model_mm) += m.e;
        if (m.kind == gcode::MoveKind::Unretract) {
            if (m.e - retracted > prime_allowance) {
                note(m.line, ProblemKind::EJump, "E jump: " + fixed(m.e, 3) + " mm of filament without XY motion (" + fixed(retracted, 3) +
                                 " mm were retracted)");
            }
            retracted = std::max(0.0, retracted - m.e);
        }
        if (m.kind != gcode::MoveKind::Extrude) continue;
        double len = std::hypot(m.x1 - m.x0, m.y1 - m.y0);
        // The layer's own height (a raft's thick base, variable layers),
        // else the settings'.
        const float own = heights[static_cast<std::size_t>(&m - p.moves.data())];
        double h = own > 0 ? own : m.z1 <= settings.first_layer_height + kZEps ? settings.first_layer_height : settings.layer_height;
        // What a bead of the widest sane width would take over this length;
        // the first extrusion after a retraction also primes.
        double e_max = len * ((max_width - h) * h + std::numbers::pi * h * h / 4) / (std::numbers::pi * fd * fd / 4);
        double primed = std::min(retracted, static_cast<double>(m.e));
        retracted = 0;  // extruding ends a retraction (as in gcode/machine.cpp)
        if (m.e - primed > e_max + prime_allowance) {
            note(m.line, ProblemKind::EJump, "E jump: " + fixed(m.e, 3) + " mm of filament over " + fixed(len, 3) + " mm of motion");
            continue;
        }
        if (m.x0 < settings.bed_min_x - 0.5 || m.x0 > settings.bed_max_x + 0.5 || m.y0 < settings.bed_min_y - 0.5 ||
            m.y0 > settings.bed_max_y + 0.5 || m.x1 < settings.bed_min_x - 0.5 || m.x1 > settings.bed_max_x + 0.5 ||
            m.y1 < settings.bed_min_y - 0.5 || m.y1 > settings.bed_max_y + 0.5) {
            note(m.line, ProblemKind::OutsideBed, "extrusion outside the bed from (" + fixed(m.x0, 2) + ", " + fixed(m.y0, 2) + ") to (" +
                             fixed(m.x1, 2) + ", " + fixed(m.y1, 2) + ")");
        }
        if (len < 0.5) continue;  // short pieces carry the rounding of E and XY
        double w = layers::width_from_e(m.e - primed, len, h, fd);
        const double min_width = sup ? min_support_width : min_model_width;
        if (w < min_width || w > max_width) {
            note(m.line, ProblemKind::Width, std::string(sup ? "support" : "model") + " extrusion " + fixed(w, 3) +
                             " mm wide from its E (allowed " + fixed(min_width, 2) + ".." + fixed(max_width, 2) + ")");
        }
    }
    return x;
}

// The first line of the first layer: what comes before is start code.
std::uint32_t first_layer_start(const layers::LayerStack& stack) {
    for (const layers::Layer& L : stack.layers)
        if (!L.purge) return L.first_line;
    return 0;
}

}  // namespace

double estimate_print_time(const gcode::Program& p) { return estimate_moves(p.moves, motion_limits(p)); }

MotionLimits motion_limits(const gcode::Program& p) {
    double accel = 1000, max_xy = 1e9, max_z = 1e9, max_e = 1e9;
    gcode::Command cmd;
    for (std::size_t i = 0; i < p.lines.size(); ++i) {
        std::string_view t = p.line_text(i);
        if (t.empty() || (t[0] != 'M' && t[0] != 'm')) continue;
        gcode::lex(t, cmd);
        if (cmd.is('M', 204)) accel = cmd.get('P', cmd.get('S', accel));
        else if (cmd.is('M', 201) && cmd.has('X')) accel = std::min(accel, cmd.get('X', accel));
        else if (cmd.is('M', 203)) {
            max_xy = cmd.get('X', max_xy);
            max_z = cmd.get('Z', max_z);
            max_e = cmd.get('E', max_e);
        }
    }
    return {accel, max_xy, max_z, max_e};
}

double estimate_moves(const std::vector<gcode::Move>& moves, const MotionLimits& limits) {
    const double accel = limits.accel, max_xy = limits.max_xy, max_z = limits.max_z, max_e = limits.max_e;
    constexpr double kJunctionDeviation = 0.013;  // mm, Marlin's default
    // Each move is a trapezoid between junction speeds; a junction is as fast
    // as Marlin's junction deviation allows for the turn (0 around E-only
    // moves and at the ends), then limited so every move can reach it.
    struct Seg { double d, v, ux, uy, uz; bool xyz; };
    std::vector<Seg> segs;
    segs.reserve(moves.size());
    for (const auto& m : moves) {
        double dx = m.x1 - m.x0, dy = m.y1 - m.y0, dz = m.z1 - m.z0;
        double d = std::sqrt(dx * dx + dy * dy + dz * dz);
        bool xyz = d > 1e-9;
        double cap = std::hypot(dx, dy) > 1e-9 ? max_xy : (std::abs(dz) > 1e-9 ? max_z : max_e);
        if (!xyz) d = std::abs(m.e);
        if (d < 1e-9) continue;
        double v = std::min(static_cast<double>(m.feed_mm_per_min) / 60.0, cap);
        if (v <= 0) v = 10;
        segs.push_back({d, v, xyz ? dx / d : 0, xyz ? dy / d : 0, xyz ? dz / d : 0, xyz});
    }
    std::size_t n = segs.size();
    std::vector<double> j(n + 1, 0.0);  // j[k]: speed entering move k
    for (std::size_t k = 1; k < n; ++k) {
        const Seg &a = segs[k - 1], &b = segs[k];
        if (!a.xyz || !b.xyz) continue;
        double cos_theta = -(a.ux * b.ux + a.uy * b.uy + a.uz * b.uz);
        double vmax = std::min(a.v, b.v);
        if (cos_theta < -0.999999) { j[k] = vmax; continue; }
        double sin_half = std::sqrt(std::max(0.0, 0.5 * (1 - cos_theta)));
        double vj2 = accel * kJunctionDeviation * sin_half / std::max(1e-9, 1 - sin_half);
        j[k] = std::min(vmax, std::sqrt(vj2));
    }
    for (std::size_t k = n; k-- > 0;) j[k] = std::min(j[k], std::sqrt(j[k + 1] * j[k + 1] + 2 * accel * segs[k].d));
    for (std::size_t k = 0; k < n; ++k) j[k + 1] = std::min(j[k + 1], std::sqrt(j[k] * j[k] + 2 * accel * segs[k].d));
    double total = 0;
    for (std::size_t k = 0; k < n; ++k) {
        double d = segs[k].d, v = segs[k].v, a0 = j[k], a1 = j[k + 1];
        double d_acc = (v * v - a0 * a0) / (2 * accel), d_dec = (v * v - a1 * a1) / (2 * accel);
        if (d_acc + d_dec <= d) {
            total += (v - a0) / accel + (v - a1) / accel + (d - d_acc - d_dec) / v;
        } else {  // never reaches v: a triangle peaking at vp
            double vp = std::sqrt((2 * accel * d + a0 * a0 + a1 * a1) / 2);
            total += (vp - a0) / accel + (vp - a1) / accel;
        }
    }
    return total;
}

namespace {

// Whether `out` carries scaffold's header in its first lines; if so, marks
// the lines of its support blocks (none when it added nothing).
bool scaffold_blocks(const gcode::Program& out, std::vector<bool>& inserted) {
    bool header = false;
    for (std::size_t i = 0; i < out.lines.size() && i < 20 && !header; ++i) {
        const std::string_view t = out.line_text(i);
        header = t.rfind("; scaffold ", 0) == 0 && t.find("(post-processed supports)") != std::string_view::npos;
    }
    if (!header) return false;
    inserted.assign(out.lines.size(), false);
    bool open = false;
    for (std::size_t i = 0; i < out.lines.size(); ++i) {
        const std::string_view t = out.line_text(i);
        if (t.rfind("; scaffold: support for ", 0) == 0) open = true;
        inserted[i] = open;
        if (open && t.rfind("; scaffold: end", 0) == 0) open = false;
    }
    return true;
}

}  // namespace

CheckReport check(const gcode::Program& out, const gcode::Program* original, const CheckOptions& o,
                  const std::string& svg_dir) {
    return check(out, original, build_settings(out, {}, {}), o, svg_dir);
}

CheckReport check(const gcode::Program& out, const gcode::Program* original, const Settings& settings,
                  const CheckOptions& o, const std::string& svg_dir) {
    CheckReport r;
    r.file = out.path;
    layers::LayerStack stack = layers::build_layers(out, settings);
    r.layers = static_cast<int>(stack.layers.size());

    std::vector<bool> inserted;
    std::vector<std::uint32_t> out_to_original;  // per output line: the original's line, or kNone
    // Without the original, a file scaffold wrote still says what it added:
    // its header, and its blocks from "; scaffold: support for ..." to
    // "; scaffold: end". Support outside them is the slicer's own.
    const bool scaffold_output = !original && scaffold_blocks(out, inserted);
    if (original) {
        r.compared = true;
        LineMatch match = match_lines(out, *original);
        inserted = std::move(match.inserted);
        out_to_original.assign(out.lines.size(), kNone);
        for (std::size_t k = 0; k < match.out_line.size(); ++k)
            if (match.out_line[k] != kNone) out_to_original[match.out_line[k]] = static_cast<std::uint32_t>(k);
        r.model_lines_missing = match.missing;
        r.model_change = match.first_missing;
        // The lines found must also move the same: same start, end, E, feed.
        const auto mo = moves_by_line(*original), mn = moves_by_line(out);
        for (std::size_t k = 0; k < original->lines.size(); ++k) {
            const std::uint32_t i = match.out_line[k];
            if (i == kNone) continue;
            std::string diff;
            if (mo[k + 1] - mo[k] != mn[i + 1] - mn[i]) diff = "makes " + std::to_string(mn[i + 1] - mn[i]) +
                                                                " moves instead of " + std::to_string(mo[k + 1] - mo[k]);
            for (std::uint32_t a = mo[k], b = mn[i]; diff.empty() && a < mo[k + 1]; ++a, ++b)
                diff = move_difference(original->moves[a], out.moves[b]);
            if (diff.empty()) continue;
            if (r.model_moves_changed++ == 0 && r.model_change.empty())
                r.model_change = "original line " + std::to_string(k + 1) + " ('" +
                                 std::string(original->line_text(k).substr(0, 60)) + "'), output line " +
                                 std::to_string(i + 1) + ", " + diff;
        }
        r.model_unchanged = r.model_lines_missing == 0 && r.model_moves_changed == 0;
        r.original_print_time_s = estimate_print_time(*original);
    }
    auto is_support_move = [&](const gcode::Move& m) {
        return gcode::is_support(m.role) || (!inserted.empty() && inserted[m.line]);
    };
    // What the edit added is known (`inserted`, from the original or from
    // scaffold's blocks): support on the other lines is the slicer's own.
    auto is_slicer_support = [&](const gcode::Move& m) {
        return !inserted.empty() && gcode::is_support(m.role) && !inserted[m.line];
    };

    // Extrusion sanity. The slicer's own start code (purge and prime before
    // the first layer) and, with --original, what the original already did
    // are reported apart: only what the edit added or broke fails.
    const std::uint32_t first_layer_line = first_layer_start(stack);
    // A bed the file does not state is a guess (250 x 210 mm from the
    // origin); the slicer's own extrusions lie on the real one (a delta's
    // bed is centred on the origin), so the guess grows to hold them and
    // kUnstatedBedMargin around them (support beside the model's edge).
    Settings judged = settings;
    if (!settings.bed_stated) {
        const double inf = std::numeric_limits<double>::infinity();
        layers::Bounds own{inf, inf, -inf, -inf};
        for (const gcode::Move& m : original ? original->moves : out.moves)
            if (m.kind == gcode::MoveKind::Extrude && (original || inserted.empty() || !inserted[m.line])) {
                own.min_x = std::min({own.min_x, static_cast<double>(m.x0), static_cast<double>(m.x1)});
                own.min_y = std::min({own.min_y, static_cast<double>(m.y0), static_cast<double>(m.y1)});
                own.max_x = std::max({own.max_x, static_cast<double>(m.x0), static_cast<double>(m.x1)});
                own.max_y = std::max({own.max_y, static_cast<double>(m.y0), static_cast<double>(m.y1)});
            }
        if (!own.empty()) {
            judged.bed_min_x = std::min(own.min_x - kUnstatedBedMargin, settings.bed_min_x);
            judged.bed_min_y = std::min(own.min_y - kUnstatedBedMargin, settings.bed_min_y);
            judged.bed_max_x = std::max(own.max_x + kUnstatedBedMargin, settings.bed_max_x);
            judged.bed_max_y = std::max(own.max_y + kUnstatedBedMargin, settings.bed_max_y);
        }
    }
    const Extrusion ex = extrusion_problems(out, judged, move_heights(out, stack), is_support_move);
    r.support_filament_mm = ex.support_mm;
    r.model_filament_mm = ex.model_mm;
    // (original line, kind) the original had itself; its start code needs no
    // sorting out here: the output's start code is reported apart first.
    std::set<std::pair<std::uint32_t, int>> own;
    if (original)
        for (const Problem& q :
             extrusion_problems(*original, judged, move_heights(*original, layers::build_layers(*original, settings)),
                                [](const gcode::Move& m) { return gcode::is_support(m.role); })
                 .problems)
            own.insert({q.line, static_cast<int>(q.kind)});
    // A tool change's purge (Bambu's M620..M621 flush, PrusaSlicer's wipe
    // tower change) is the slicer's own, like the start code's.
    std::vector<char> purge(out.lines.size(), 0);
    bool open = false;
    for (std::size_t i = 0; i < out.lines.size(); ++i) {
        const gcode::BlockMarker m = gcode::block_marker(out.line_text(i));
        if (m.kind == gcode::BlockKind::ToolChange) open = m.opens;
        purge[i] = static_cast<char>(open || (m.kind == gcode::BlockKind::ToolChange && !m.opens));
    }
    // Without the original, in scaffold's output: the slicer's own support
    // lines are the original's (with it, `own` says so line by line).
    std::vector<char> slicer_line;
    if (scaffold_output) {
        slicer_line.assign(out.lines.size(), 0);
        for (const gcode::Move& m : out.moves)
            if (is_slicer_support(m)) slicer_line[m.line] = 1;
    }
    for (const Problem& q : ex.problems) {
        if (q.line < first_layer_line || purge[q.line]) {
            ++r.start_code_problems;
            if (r.start_code_notes.size() < 5) r.start_code_notes.push_back("line " + std::to_string(q.line + 1) + ": " + q.what);
            continue;
        }
        if ((!out_to_original.empty() && out_to_original[q.line] != kNone &&
             own.count({out_to_original[q.line], static_cast<int>(q.kind)})) ||
            (!slicer_line.empty() && slicer_line[q.line])) {
            ++r.original_problems;
            if (r.original_notes.size() < 5) r.original_notes.push_back("line " + std::to_string(q.line + 1) + ": " + q.what);
            continue;
        }
        switch (q.kind) {
            case ProblemKind::Width: ++r.bad_extrusions; break;
            case ProblemKind::EJump: ++r.e_jumps; break;
            case ProblemKind::OutsideBed: ++r.outside_bed; break;
        }
        if (r.extrusion_notes.size() < 10) r.extrusion_notes.push_back("line " + std::to_string(q.line + 1) + ": " + q.what);
    }
    r.print_time_s = estimate_print_time(out);

    // Deposition, layer by layer, in the model's frame as the detector finds
    // overhangs in it (layers/frame.hpp): the two judge a bead on the edge of
    // a cell to the bit alike. Places reported are moved back onto the bed.
    const layers::Frame frame = layers::model_frame(stack, [&](const layers::Layer& l, const layers::Segment& sg) {
        return layers::model_bead(l, sg) && !is_support_move(out.moves[sg.move]);
    });
    layers::move_stack(stack, frame, true);
    const layers::BitGrid proto = layers::make_grid(stack, o.resolution, 5.0);
    const double slope = std::tan(o.overhang_angle_deg * std::numbers::pi / 180);
    const double h_nom = settings.layer_height;
    const double max_bridge = o.max_bridge >= 0 ? o.max_bridge : settings.max_bridge;
    std::map<int, LayerGrids> cache;  // recent layers' model and support rasters
    auto grids = [&](int index) -> const LayerGrids& {
        auto it = cache.find(index);
        if (it != cache.end()) return it->second;
        LayerGrids g;
        g.index = index;
        g.model = proto;
        g.support = proto;
        g.skirt = proto;
        g.slicer = proto;
        g.seeds = proto;
        for (const auto& sg : stack.layers[index].segments) {
            layers::BitGrid& into = is_slicer_support(out.moves[sg.move]) ? g.slicer
                                    : is_support_move(out.moves[sg.move]) ? g.support
                                    : sg.role == gcode::Role::Skirt       ? g.skirt
                                                                          : g.model;
            into.draw_segment(sg.x0, sg.y0, sg.x1, sg.y1, sg.width);
            if (&into == &g.model) layers::draw_hole_seed(g.seeds, sg);
        }
        return cache.emplace(index, std::move(g)).first->second;
    };
    std::vector<std::pair<int, layers::BitGrid>> worst_grids;  // for the SVGs
    std::vector<layers::Region> unheld_regions;                // in layer order

    // Support extruded twice on a layer: each support path (moves that follow
    // one another) drawn with half its width, cells already drawn by an
    // earlier path of the layer counted. Within one path the joints overlap
    // by construction and do not count.
    layers::BitGrid drawn = proto;
    auto support_overlap = [&](const std::vector<layers::Segment>& segs) {
        drawn.clear();
        std::size_t twice = 0;
        layers::BitGrid path;
        for (std::size_t k = 0; k < segs.size();) {
            if (!is_support_move(out.moves[segs[k].move])) { ++k; continue; }
            std::size_t e = k + 1;
            while (e < segs.size() && segs[e].move == segs[e - 1].move + 1 && is_support_move(out.moves[segs[e].move])) ++e;
            double x0 = 1e300, y0 = 1e300, x1 = -1e300, y1 = -1e300;
            for (std::size_t i = k; i < e; ++i) {
                x0 = std::min({x0, double(segs[i].x0), double(segs[i].x1)});
                y0 = std::min({y0, double(segs[i].y0), double(segs[i].y1)});
                x1 = std::max({x1, double(segs[i].x0), double(segs[i].x1)});
                y1 = std::max({y1, double(segs[i].y0), double(segs[i].y1)});
            }
            // The path's own small grid, aligned with the layer's cells.
            const int i0 = proto.col(x0) - 4, j0 = proto.row(y0) - 4, i1 = proto.col(x1) + 4, j1 = proto.row(y1) + 4;
            path = layers::BitGrid(proto.origin_x() + i0 * proto.cell(), proto.origin_y() + j0 * proto.cell(),
                                   proto.origin_x() + (i1 + 1) * proto.cell(), proto.origin_y() + (j1 + 1) * proto.cell(),
                                   proto.cell());
            for (std::size_t i = k; i < e; ++i)
                path.draw_segment(segs[i].x0, segs[i].y0, segs[i].x1, segs[i].y1, segs[i].width * 0.5);
            for (int j = 0; j < path.height(); ++j)
                for (int i = 0; i < path.width(); ++i) {
                    if (!path.get(i, j)) continue;
                    if (drawn.get(i + i0, j + j0)) ++twice;
                    else drawn.set(i + i0, j + j0);
                }
            k = e;
        }
        return static_cast<double>(twice) * proto.cell_area();
    };

    for (int L = 0; L < static_cast<int>(stack.layers.size()); ++L) {
        const layers::Layer& layer = stack.layers[L];
        while (!cache.empty() && cache.begin()->first < L - 40) cache.erase(cache.begin());
        const LayerGrids& here = grids(L);

        // Collisions: support within the gap of the model on the same layer,
        // except contact tips (support that ends within two layers). The
        // original's own support is measured the same way, and apart.
        auto collisions = [&](layers::BitGrid LayerGrids::*which) {
            layers::BitGrid coll = here.*which;
            // Against the part's footprint: support inside the part (in a
            // hole of its sparse infill) can never be removed; in a cavity
            // of the model (layers::draw_hole_seed) it keeps the gap.
            layers::BitGrid part = here.model;
            part |= here.model.holes_with(here.seeds);
            coll &= part.dilated(std::max(0.0, o.xy_gap - o.resolution));
            if (!coll.any()) return coll;
            // A cell is a tip when its support ends here or on the next
            // layer: only cells with support on both layers above count
            // (one pillar's tip under another's loop two layers up is
            // still a tip).
            int above = 0;
            for (int k = L + 1; k < static_cast<int>(stack.layers.size()) && above < 2; ++k)
                if (stack.layers[k].z > layer.z + kZEps) {
                    ++above;
                    coll &= grids(k).*which;
                }
            if (above < 2) coll.clear();
            return coll;
        };
        if (here.support.any()) {
            const layers::BitGrid coll = collisions(&LayerGrids::support);
            if (coll.any()) {
                LayerIssue is = issue_of(coll, L, layer.z);
                r.collision_mm2 += is.area_mm2;
                add_issue(r.worst_collisions, is, o.worst);
            }
        }
        if (here.slicer.any()) {
            const layers::BitGrid coll = collisions(&LayerGrids::slicer);
            r.original_collision_mm2 += static_cast<double>(coll.count()) * proto.cell_area();
        }
        if (here.support.any()) r.support_overlap_mm2 += support_overlap(stack.layers[L].segments);
        if (layer.on_bed) continue;

        // "Below": all material within one nominal layer, support within three.
        // A skirt loop holds what lies on it but must not count as the rim
        // of a hole: filled, it would "hold" everything inside it.
        layers::BitGrid below = proto, tips = proto;
        std::vector<std::pair<int, bool>> beneath;  // the layers below, and whether their model counts
        bool have_below = false;
        for (int k = L - 1; k >= 0; --k) {
            double dz = layer.z - stack.layers[k].z;
            if (dz <= kZEps) continue;
            if (dz > 3 * h_nom + kZEps && dz > layer.nominal_height + kZEps) {
                if (stack.layers[k].z < layer.z - 3 * h_nom - 1.0) break;
                continue;
            }
            const LayerGrids& g = grids(k);
            below |= g.support;
            below |= g.slicer;
            tips |= g.support;  // support on the three layers below: a tip where it lies under this layer's model
            tips |= g.slicer;
            const bool model_too = dz <= std::max(h_nom, layer.nominal_height) + kZEps || k == layer.below;
            if (model_too) below |= g.model;
            beneath.emplace_back(k, model_too);
            have_below = true;
        }
        if (!have_below && layer.below >= 0) {
            const LayerGrids& g = grids(layer.below);
            below |= g.model;
            below |= g.support;
            below |= g.slicer;
            tips |= g.support;
            tips |= g.slicer;
            beneath.emplace_back(layer.below, true);
        }
        // METHOD's rule (c): a contact tip of this layer is support that lies
        // directly under model material of this layer (within one cell). A
        // tip that touches the model only higher up holds nothing here.
        tips &= here.model.dilated(o.resolution);
        // Rule (a)'s reach, from the beads themselves.
        const double reach = layer.height * slope + o.resolution / 2;
        layers::BitGrid held_grid = proto;
        for (const auto& [k, model_too] : beneath)
            layers::draw_reach(held_grid, stack.layers[k], reach, [&, model_too = model_too](const layers::Segment& sg) {
                return model_too || is_support_move(out.moves[sg.move]);
            });

        // (a) per centre-line sample, then holes enclosed by the layer beneath.
        const auto& segs = layer.segments;
        // A piece is straight while every segment stays within 10 deg of the
        // piece's first direction: comparing each segment only with the one
        // before would let a finely divided circle pass as one "straight"
        // bridge (a 97-gon turns 3.7 deg per segment).
        std::vector<std::vector<Sample>> pieces;
        std::vector<double> piece_limit;  // the span each piece may bridge
        std::vector<char> piece_joined;   // continues the piece before it on one path (a corner)
        double piece_ux = 0, piece_uy = 0;
        const double cos_straight = std::cos(kStraightDeg * std::numbers::pi / 180);
        for (std::size_t k = 0; k < segs.size(); ++k) {
            const auto& sg = segs[k];
            double dx = sg.x1 - sg.x0, dy = sg.y1 - sg.y0, len = std::hypot(dx, dy);
            bool joins = false;
            // Scaffold's bars and the slicer's bridge infill may span the
            // bridge limit; any other bead (an overhang perimeter too: it is
            // a wall) the shorter one.
            const double limit =
                is_support_move(out.moves[sg.move]) || sg.role == gcode::Role::BridgeInfill ? o.bridge_limit : max_bridge;
            if (k > 0 && !pieces.empty() && len > 0) {
                const auto& pv = segs[k - 1];
                bool same_path = sg.move == pv.move + 1 && limit == piece_limit.back();
                joins = same_path && (dx * piece_ux + dy * piece_uy) / len >= cos_straight;
            }
            if (!joins) {
                const bool corner = k > 0 && !pieces.empty() && sg.move == segs[k - 1].move + 1 &&
                                    std::abs(sg.x0 - segs[k - 1].x1) < 1e-3f && std::abs(sg.y0 - segs[k - 1].y1) < 1e-3f;
                pieces.emplace_back();
                piece_limit.push_back(limit);
                piece_joined.push_back(corner);
                piece_ux = len > 0 ? dx / len : 0;
                piece_uy = len > 0 ? dy / len : 0;
            }
            layers::sample_segment(sg, static_cast<std::uint32_t>(k), held_grid, o.resolution, pieces.back());
        }
        layers::BitGrid seeds = proto;
        bool any_unheld = false;
        for (const auto& piece : pieces)
            for (const auto& sm : piece)
                if (!sm.held) { seeds.set(seeds.col(sm.x), seeds.row(sm.y)); any_unheld = true; }
        if (!any_unheld) continue;
        const layers::BitGrid enclosed = below.enclosed(seeds);
        for (auto& piece : pieces)
            for (auto& sm : piece)
                if (!sm.held && enclosed.get(enclosed.col(sm.x), enclosed.row(sm.y))) sm.held = true;

        // (b) unheld runs of a straight piece, held at both ends within the
        // bridge limit and leaving both across the edge of the footprint
        // beneath (layers::run_crosses), or a short dangling end. Where a path turns, the
        // corner is held when the piece on either side is held within a
        // dangling end of it: that stretch is held by (b) itself.
        std::vector<std::pair<char, char>> joint_held(pieces.size(), {0, 0});
        for (std::size_t q = 1; q < pieces.size(); ++q) {
            if (!piece_joined[q]) continue;
            joint_held[q].first = layers::held_near_end(pieces[q - 1], true, o.dangling_end);
            joint_held[q - 1].second = layers::held_near_end(pieces[q], false, o.dangling_end);
        }
        for (std::size_t q = 0; q < pieces.size(); ++q) {
            if (joint_held[q].first) pieces[q].front().held = true;
            if (joint_held[q].second) pieces[q].back().held = true;
        }
        for (std::size_t q = 0; q < pieces.size(); ++q) layers::hold_runs(pieces[q], below, piece_limit[q], o.dangling_end);
        // (c) near a support contact tip below.
        bool still = false;
        for (const auto& piece : pieces)
            for (const auto& sm : piece) still = still || !sm.held;
        if (still && tips.any()) {
            const layers::BitGrid tip_reach = tips.dilated(o.point_radius);
            for (auto& piece : pieces)
                for (auto& sm : piece)
                    if (!sm.held && tip_reach.get(tip_reach.col(sm.x), tip_reach.row(sm.y))) sm.held = true;
        }
        // What is left is unheld: draw those stretches of bead.
        layers::BitGrid unheld_model = proto, unheld_support = proto, unheld_slicer = proto;
        bool any_left = false, any_slicer = false;
        for (const auto& piece : pieces)
            for (std::size_t k = 0; k < piece.size(); ++k) {
                if (piece[k].held) continue;
                const auto& sm = piece[k];
                const auto& sg = segs[sm.seg];
                const gcode::Move& m = out.moves[sg.move];
                const bool slicer = is_slicer_support(m);
                any_left |= !slicer;
                any_slicer |= slicer;
                // Through the unheld samples only, as the detector draws them
                // (so a region it finds under the speck size is never larger here).
                const auto& prev = k > 0 && !piece[k - 1].held ? piece[k - 1] : sm;
                (slicer ? unheld_slicer : is_support_move(m) ? unheld_support : unheld_model)
                    .draw_segment(prev.x, prev.y, sm.x, sm.y, sg.width);
            }
        if (any_slicer) r.original_unheld_support_mm2 += static_cast<double>(unheld_slicer.count()) * proto.cell_area();
        if (!any_left) continue;
        double am = static_cast<double>(unheld_model.count()) * proto.cell_area();
        double as = static_cast<double>(unheld_support.count()) * proto.cell_area();
        r.unheld_model_mm2 += am;
        r.unheld_support_mm2 += as;
        layers::BitGrid both = unheld_model;
        both |= unheld_support;
        for (auto& cells : layers::regions(both, layers::kRegionJoin))
            unheld_regions.push_back(layers::make_region(std::move(cells), L, layer.z));
        LayerIssue is = issue_of(both, L, layer.z);
        add_issue(r.worst_unheld, is, o.worst);
        if (!svg_dir.empty()) {
            worst_grids.emplace_back(L, std::move(both));
            std::stable_sort(worst_grids.begin(), worst_grids.end(),
                             [](const auto& a, const auto& b) { return a.second.count() > b.second.count(); });
            if (static_cast<int>(worst_grids.size()) > o.worst) worst_grids.resize(o.worst);
        }
    }

    if (!svg_dir.empty()) {
        std::error_code ec;
        std::filesystem::create_directories(svg_dir, ec);
        if (ec) throw Error(svg_dir, 0, "cannot create the directory: " + ec.message());
        for (const auto& [L, unheld] : worst_grids) {
            LayerGrids g = grids(L);
            g.model |= g.skirt;
            std::string s = "<svg xmlns=\"http://www.w3.org/2000/svg\" viewBox=\"0 0 " + std::to_string(proto.width()) +
                            " " + std::to_string(proto.height()) + "\" width=\"" + std::to_string(proto.width() * 3) +
                            "\" height=\"" + std::to_string(proto.height() * 3) + "\">\n";
            s += "<rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n<!-- layer " + std::to_string(L) + " z " +
                 fixed(stack.layers[L].z, 2) + ": grey model, blue support, red unheld -->\n";
            s += layers::svg_cell_runs(g.model, "#b0b0b0") + layers::svg_cell_runs(g.support, "#1d4ed8") + layers::svg_cell_runs(unheld, "#d62828");
            s += "</svg>\n";
            char name[40];
            std::snprintf(name, sizeof name, "/unheld-layer-%04d.svg", L);
            std::ofstream(svg_dir + name) << s;
        }
    }

    // The speck rule the detector applies (METHOD.md): lone unheld specks
    // under min_region_mm2 that continue nothing above or below are noise.
    const std::vector<char> counts = o.min_region_mm2 > 0 ? layers::kept_regions(unheld_regions, proto, h_nom, o.min_region_mm2)
                                                          : std::vector<char>(unheld_regions.size(), 1);
    // Counted per model (METHOD): each region goes to the object under or
    // nearest it (its first cell, within 5 mm); what lies beside none is a
    // model of its own here.
    const layers::ObjectMap objects(stack, [&](const layers::Layer& l, const layers::Segment& sg) {
        return layers::model_bead(l, sg) && !is_support_move(out.moves[sg.move]);
    });
    r.models = objects.count();
    std::vector<double> per_model(static_cast<std::size_t>(objects.count()) + 1, 0.0);
    for (std::size_t k = 0; k < unheld_regions.size(); ++k) {
        if (!counts[k]) continue;
        const layers::Region& g = unheld_regions[k];
        const double a = static_cast<double>(g.cells.size()) * proto.cell_area();
        r.unheld_regions_mm2 += a;
        const int m = g.cells.empty() ? -1 : objects.at(proto.cx(g.cells.front().i), proto.cy(g.cells.front().j), 5.0);
        per_model[static_cast<std::size_t>(m + 1)] += a;
    }
    r.unheld_worst_model_mm2 = *std::max_element(per_model.begin(), per_model.end());
    if (r.unheld_worst_model_mm2 > o.tolerance_mm2) {
        std::string what = "unheld area " + fixed(r.unheld_model_mm2 + r.unheld_support_mm2, 2) + " mm^2 (model " +
                           fixed(r.unheld_model_mm2, 2) + ", support " + fixed(r.unheld_support_mm2, 2) + ")";
        if (o.min_region_mm2 > 0)
            what += ", " + fixed(r.unheld_regions_mm2, 2) + " mm^2 of it not lone specks under " + fixed(o.min_region_mm2, 2) + " mm^2";
        if (r.models > 1) what += ", " + fixed(r.unheld_worst_model_mm2, 2) + " mm^2 on one of " + std::to_string(r.models) + " models";
        r.failures.push_back(what + ", more than the " + fixed(o.tolerance_mm2, 2) + " mm^2 tolerance" +
                             (r.models > 1 ? " per model" : ""));
    }
    if (r.collision_mm2 > 0) r.failures.push_back("support within the XY gap of the model: " + fixed(r.collision_mm2, 2) + " mm^2");
    if (r.bad_extrusions) r.failures.push_back(std::to_string(r.bad_extrusions) + " extrusions with a width out of bounds");
    if (r.e_jumps) r.failures.push_back(std::to_string(r.e_jumps) + " E jumps");
    if (r.outside_bed) r.failures.push_back(std::to_string(r.outside_bed) + " extrusions outside the bed");
    layers::move_stack(stack, frame, false);
    for (std::vector<LayerIssue>* list : {&r.worst_unheld, &r.worst_collisions})
        for (LayerIssue& is : *list) {
            is.x += frame.dx();
            is.y += frame.dy();
        }
    // METHOD's second rule, on its own (check/standing.cpp).
    std::vector<SupportOwner> owner(out.moves.size(), SupportOwner::None);
    for (std::size_t i = 0; i < out.moves.size(); ++i)
        if (is_support_move(out.moves[i]))
            owner[i] = is_slicer_support(out.moves[i]) ? SupportOwner::Original : SupportOwner::Added;
    StandingOptions so = o.standing;
    so.resolution = o.resolution;
    r.standing = standing(out, stack, owner, settings, so);
    standing_failures(r.standing, r.failures);
    if (!r.model_unchanged)
        r.failures.push_back("model changed (" + std::to_string(r.model_lines_missing) + " lines missing, " +
                             std::to_string(r.model_moves_changed) + " lines moving differently): " + r.model_change);
    return r;
}

std::string report_text(const CheckReport& r) {
    std::string o = r.file + ": " + std::to_string(r.layers) + " layers\n";
    o += "  unheld area: " + fixed(r.unheld_model_mm2 + r.unheld_support_mm2, 2) + " mm^2 (model " +
         fixed(r.unheld_model_mm2, 2) + ", support " + fixed(r.unheld_support_mm2, 2) + "); counted against the tolerance: " +
         fixed(r.unheld_regions_mm2, 2) + " mm^2" +
         (r.models > 1 ? " (the most on one of " + std::to_string(r.models) + " models: " + fixed(r.unheld_worst_model_mm2, 2) + " mm^2)" : "") +
         "\n";
    for (const auto& w : r.worst_unheld)
        o += "    layer " + std::to_string(w.layer) + " z " + fixed(w.z, 2) + ": " + fixed(w.area_mm2, 2) +
             " mm^2 around (" + fixed(w.x, 1) + ", " + fixed(w.y, 1) + ")\n";
    o += "  collisions: " + fixed(r.collision_mm2, 2) + " mm^2\n";
    for (const auto& w : r.worst_collisions)
        o += "    layer " + std::to_string(w.layer) + " z " + fixed(w.z, 2) + ": " + fixed(w.area_mm2, 2) +
             " mm^2 around (" + fixed(w.x, 1) + ", " + fixed(w.y, 1) + ")\n";
    o += "  support extruded twice (bead cores of two paths overlapping, reported only): " +
         fixed(r.support_overlap_mm2, 2) + " mm^2\n";
    o += "  extrusion: " + std::to_string(r.bad_extrusions) + " bad widths, " + std::to_string(r.e_jumps) + " E jumps, " +
         std::to_string(r.outside_bed) + " outside the bed\n";
    for (const auto& n : r.extrusion_notes) o += "    " + n + "\n";
    if (r.start_code_problems) {
        o += "  the slicer's start code and tool-change purges (not a failure): " +
             std::to_string(r.start_code_problems) + " extrusion notes\n";
        for (const auto& n : r.start_code_notes) o += "    " + n + "\n";
    }
    if (r.original_problems) {
        o += "  the original's own (lines the edit left alone; not a failure): " + std::to_string(r.original_problems) +
             " extrusion notes\n";
        for (const auto& n : r.original_notes) o += "    " + n + "\n";
    }
    if (r.original_unheld_support_mm2 > 0 || r.original_collision_mm2 > 0)
        o += "  the original's own support (sliced with support on; not a failure): " +
             fixed(r.original_unheld_support_mm2, 2) + " mm^2 unheld, " + fixed(r.original_collision_mm2, 2) +
             " mm^2 within the XY gap of the model\n";
    if (r.compared)
        o += std::string("  model vs original: ") +
             (r.model_unchanged ? "unchanged"
                                : std::to_string(r.model_lines_missing) + " lines missing, " +
                                      std::to_string(r.model_moves_changed) + " lines moving differently; first: " + r.model_change) +
             "\n";
    o += "  filament: model " + fixed(r.model_filament_mm, 1) + " mm, support " + fixed(r.support_filament_mm, 1) + " mm\n";
    o += "  print time estimate: " + fixed(r.print_time_s / 60, 1) + " min";
    if (r.original_print_time_s >= 0) o += " (original " + fixed(r.original_print_time_s / 60, 1) + " min)";
    o += "\n";
    o += standing_text(r.standing);
    o += r.ok() ? "  PASS\n" : "  FAIL\n";
    for (const auto& f : r.failures) o += "    - " + f + "\n";
    return o;
}

std::string json_string(const std::string& s) {
    std::string o = "\"";
    for (char c : s) {
        if (c == '"' || c == '\\') o += '\\';
        if (static_cast<unsigned char>(c) < 0x20) continue;
        o += c;
    }
    return o + "\"";
}

std::string report_json(const CheckReport& r) {
    auto issues = [](const std::vector<LayerIssue>& v) {
        std::string o = "[";
        for (std::size_t i = 0; i < v.size(); ++i)
            o += std::string(i ? "," : "") + "{\"layer\":" + std::to_string(v[i].layer) + ",\"z\":" + fixed(v[i].z, 3) +
                 ",\"area_mm2\":" + fixed(v[i].area_mm2, 3) + ",\"x\":" + fixed(v[i].x, 2) + ",\"y\":" + fixed(v[i].y, 2) + "}";
        return o + "]";
    };
    std::string o = "{\n";
    o += "  \"file\": " + json_string(r.file) + ",\n  \"ok\": " + (r.ok() ? "true" : "false") + ",\n";
    o += "  \"layers\": " + std::to_string(r.layers) + ",\n";
    o += "  \"unheld_mm2\": " + fixed(r.unheld_model_mm2 + r.unheld_support_mm2, 3) + ",\n";
    o += "  \"unheld_regions_mm2\": " + fixed(r.unheld_regions_mm2, 3) + ",\n";
    o += "  \"models\": " + std::to_string(r.models) + ",\n";
    o += "  \"unheld_worst_model_mm2\": " + fixed(r.unheld_worst_model_mm2, 3) + ",\n";
    o += "  \"unheld_model_mm2\": " + fixed(r.unheld_model_mm2, 3) + ",\n";
    o += "  \"unheld_support_mm2\": " + fixed(r.unheld_support_mm2, 3) + ",\n";
    o += "  \"worst_unheld\": " + issues(r.worst_unheld) + ",\n";
    o += "  \"collision_mm2\": " + fixed(r.collision_mm2, 3) + ",\n";
    o += "  \"support_overlap_mm2\": " + fixed(r.support_overlap_mm2, 3) + ",\n";
    o += "  \"worst_collisions\": " + issues(r.worst_collisions) + ",\n";
    o += "  \"bad_extrusions\": " + std::to_string(r.bad_extrusions) + ",\n";
    o += "  \"e_jumps\": " + std::to_string(r.e_jumps) + ",\n";
    o += "  \"outside_bed\": " + std::to_string(r.outside_bed) + ",\n";
    o += "  \"start_code_problems\": " + std::to_string(r.start_code_problems) + ",\n";
    o += "  \"original_problems\": " + std::to_string(r.original_problems) + ",\n";
    o += "  \"original_unheld_support_mm2\": " + fixed(r.original_unheld_support_mm2, 3) + ",\n";
    o += "  \"original_collision_mm2\": " + fixed(r.original_collision_mm2, 3) + ",\n";
    o += std::string("  \"model_unchanged\": ") + (r.model_unchanged ? "true" : "false") + ",\n";
    o += "  \"model_lines_missing\": " + std::to_string(r.model_lines_missing) + ",\n";
    o += "  \"model_moves_changed\": " + std::to_string(r.model_moves_changed) + ",\n";
    o += "  \"support_filament_mm\": " + fixed(r.support_filament_mm, 2) + ",\n";
    o += "  \"model_filament_mm\": " + fixed(r.model_filament_mm, 2) + ",\n";
    o += "  \"print_time_s\": " + fixed(r.print_time_s, 1) + ",\n";
    o += "  \"original_print_time_s\": " + fixed(r.original_print_time_s, 1) + ",\n";
    o += "  \"standing\": " + standing_json(r.standing) + ",\n";
    o += "  \"failures\": [";
    for (std::size_t i = 0; i < r.failures.size(); ++i) o += std::string(i ? ", " : "") + json_string(r.failures[i]);
    o += "]\n}\n";
    return o;
}

}  // namespace scaffold::check
