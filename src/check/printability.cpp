#include "check/printability.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <numbers>

#include "gcode/error.hpp"
#include "gcode/lexer.hpp"
#include "layers/layer_stack.hpp"
#include "layers/raster.hpp"

namespace scaffold::check {

namespace {

constexpr double kZEps = 1e-4;
constexpr double kStraightDeg = 10;

std::string fixed(double v, int d) {
    char b[64];
    std::snprintf(b, sizeof b, "%.*f", d, v);
    return b;
}

bool comment_only(std::string_view t) {
    std::size_t i = t.find_first_not_of(" \t\r");
    return i == std::string_view::npos || t[i] == ';';
}

// Lines of `out` that are not in `original`, by an in-order greedy match:
// every command line of the original must appear, unchanged and in order
// (comment-only lines may change: slicers' filament totals are updated).
// Sets `changed` with the first original line that could not be found.
std::vector<bool> inserted_lines(const gcode::Program& out, const gcode::Program& original, std::string& changed) {
    std::vector<bool> inserted(out.lines.size(), true);
    std::size_t k = 0;
    auto next_code = [&](std::size_t from) {
        while (from < original.lines.size() && comment_only(original.line_text(from))) ++from;
        return from;
    };
    k = next_code(0);
    for (std::size_t i = 0; i < out.lines.size() && k < original.lines.size(); ++i) {
        std::string_view t = out.line_text(i);
        if (comment_only(t)) {
            inserted[i] = false;  // comments carry no material either way
            continue;
        }
        if (t == original.line_text(k)) {
            inserted[i] = false;
            k = next_code(k + 1);
        }
    }
    if (k < original.lines.size())
        changed = "original line " + std::to_string(k + 1) + " ('" + std::string(original.line_text(k).substr(0, 60)) +
                  "') is missing or changed in the output";
    return inserted;
}

struct LayerGrids {
    int index = -1;
    layers::BitGrid model, support;
};

// A straight run of consecutive segments of one extrusion path, as samples
// along its centre line.
struct Sample {
    double x, y, s;  // position and arc length along the piece
    int seg;         // index into the layer's segments
    bool held;
};

void add_issue(std::vector<LayerIssue>& v, LayerIssue issue, int keep) {
    v.push_back(issue);
    std::stable_sort(v.begin(), v.end(), [](const LayerIssue& a, const LayerIssue& b) { return a.area_mm2 > b.area_mm2; });
    if (static_cast<int>(v.size()) > keep) v.resize(keep);
}

// Area of the 8-connected regions (beads closer than 0.3 mm joined) of at
// least `min_area` mm^2.
double significant_area(const layers::BitGrid& g, double min_area) {
    layers::BitGrid joined = g.dilated(0.3), seen = g;
    seen.clear();
    double total = 0;
    std::vector<std::pair<int, int>> stack;
    for (int j = 0; j < g.height(); ++j)
        for (int i = 0; i < g.width(); ++i) {
            if (!joined.get(i, j) || seen.get(i, j)) continue;
            std::size_t cells = 0;
            stack.assign(1, {i, j});
            seen.set(i, j);
            while (!stack.empty()) {
                auto [a, b] = stack.back();
                stack.pop_back();
                cells += g.get(a, b);
                for (int dj = -1; dj <= 1; ++dj)
                    for (int di = -1; di <= 1; ++di)
                        if (joined.get(a + di, b + dj) && !seen.get(a + di, b + dj)) {
                            seen.set(a + di, b + dj);
                            stack.emplace_back(a + di, b + dj);
                        }
            }
            double area = static_cast<double>(cells) * g.cell_area();
            if (area >= min_area) total += area;
        }
    return total;
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


}  // namespace

double estimate_print_time(const gcode::Program& p) {
    double accel = 1000, max_xy = 1e9, max_z = 1e9, max_e = 1e9;
    constexpr double kJunctionDeviation = 0.013;  // mm, Marlin's default
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
    // Each move is a trapezoid between junction speeds; a junction is as fast
    // as Marlin's junction deviation allows for the turn (0 around E-only
    // moves and at the ends), then limited so every move can reach it.
    struct Seg { double d, v, ux, uy, uz; bool xyz; };
    std::vector<Seg> segs;
    segs.reserve(p.moves.size());
    for (const auto& m : p.moves) {
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

CheckReport check(const gcode::Program& out, const gcode::Program* original, const CheckOptions& o,
                  const std::string& svg_dir) {
    CheckReport r;
    r.file = out.path;
    const Settings settings = build_settings(out, {}, {});
    const layers::LayerStack stack = layers::build_layers(out, settings);
    r.layers = static_cast<int>(stack.layers.size());

    std::vector<bool> inserted;
    if (original) {
        r.compared = true;
        inserted = inserted_lines(out, *original, r.model_change);
        r.model_unchanged = r.model_change.empty();
        r.original_print_time_s = estimate_print_time(*original);
    }
    auto is_support_move = [&](const gcode::Move& m) {
        return gcode::is_support(m.role) || (!inserted.empty() && inserted[m.line]);
    };

    // Extrusion sanity and filament, per move.
    const double fd = settings.filament_diameter, nozzle = settings.nozzle_diameter;
    auto note = [&](std::size_t line, const std::string& what) {
        if (r.extrusion_notes.size() < 10) r.extrusion_notes.push_back("line " + std::to_string(line + 1) + ": " + what);
    };
    for (const auto& m : out.moves) {
        bool sup = is_support_move(m);
        if (m.kind == gcode::MoveKind::Extrude) (sup ? r.support_filament_mm : r.model_filament_mm) += m.e;
        if (m.kind == gcode::MoveKind::Unretract && m.e > std::max(2 * settings.retract_length, settings.retract_length + 2.0)) {
            ++r.e_jumps;
            note(m.line, "E jump of " + fixed(m.e, 3) + " mm without motion");
        }
        if (m.kind != gcode::MoveKind::Extrude) continue;
        if (m.x1 < settings.bed_min_x - 0.5 || m.x1 > settings.bed_max_x + 0.5 || m.y1 < settings.bed_min_y - 0.5 ||
            m.y1 > settings.bed_max_y + 0.5) {
            ++r.outside_bed;
            note(m.line, "extrusion outside the bed at (" + fixed(m.x1, 2) + ", " + fixed(m.y1, 2) + ")");
        }
        double len = std::hypot(m.x1 - m.x0, m.y1 - m.y0);
        if (len < 0.5) continue;  // short pieces carry rounding noise
        double h = m.z1 <= settings.first_layer_height + kZEps ? settings.first_layer_height : settings.layer_height;
        double w = layers::width_from_e(m.e, len, h, fd);
        double lo = sup ? 0.5 * nozzle : 0.05 * nozzle, hi = sup ? 2.0 * nozzle : 4.0 * nozzle;
        if (w < lo || w > hi) {
            ++r.bad_extrusions;
            note(m.line, std::string(sup ? "support" : "model") + " extrusion " + fixed(w, 3) +
                             " mm wide from its E (allowed " + fixed(lo, 2) + ".." + fixed(hi, 2) + ")");
        }
    }
    r.print_time_s = estimate_print_time(out);

    // Deposition, layer by layer.
    const layers::BitGrid proto = layers::make_grid(stack, o.resolution, 5.0);
    const double slope = std::tan(o.overhang_angle_deg * std::numbers::pi / 180);
    const double h_nom = settings.layer_height;
    std::map<int, LayerGrids> cache;  // recent layers' model and support rasters
    auto grids = [&](int index) -> const LayerGrids& {
        auto it = cache.find(index);
        if (it != cache.end()) return it->second;
        LayerGrids g;
        g.index = index;
        g.model = proto;
        g.support = proto;
        for (const auto& sg : stack.layers[index].segments)
            (is_support_move(out.moves[sg.move]) ? g.support : g.model).draw_segment(sg.x0, sg.y0, sg.x1, sg.y1, sg.width);
        return cache.emplace(index, std::move(g)).first->second;
    };
    std::vector<std::pair<int, layers::BitGrid>> worst_grids;  // for the SVGs

    for (int L = 0; L < static_cast<int>(stack.layers.size()); ++L) {
        const layers::Layer& layer = stack.layers[L];
        while (!cache.empty() && cache.begin()->first < L - 40) cache.erase(cache.begin());
        const LayerGrids& here = grids(L);

        // Collisions: support within the gap of the model on the same layer,
        // except contact tips (support that ends within two layers).
        if (here.support.any()) {
            layers::BitGrid coll = here.support;
            coll &= here.model.dilated(std::max(0.0, o.xy_gap - o.resolution));
            if (coll.any()) {
                int above = 0;
                for (int k = L + 1; k < static_cast<int>(stack.layers.size()) && above < 2; ++k)
                    if (stack.layers[k].z > layer.z + kZEps) {
                        ++above;
                        if (above == 2) coll &= grids(k).support;
                    }
                if (above < 2) coll.clear();
                if (coll.any()) {
                    LayerIssue is = issue_of(coll, L, layer.z);
                    r.collision_mm2 += is.area_mm2;
                    add_issue(r.worst_collisions, is, o.worst);
                }
            }
        }
        if (layer.on_bed) continue;

        // "Below": all material within one nominal layer, support within three.
        layers::BitGrid below = proto, tips = proto;
        bool have_below = false;
        for (int k = L - 1; k >= 0; --k) {
            double dz = layer.z - stack.layers[k].z;
            if (dz <= kZEps) continue;
            if (dz > 3 * h_nom + kZEps) {
                if (stack.layers[k].z < layer.z - 3 * h_nom - 1.0) break;
                continue;
            }
            const LayerGrids& g = grids(k);
            below |= g.support;
            if (dz <= h_nom + kZEps || k == layer.below) {
                below |= g.model;
                tips |= g.support;
            }
            have_below = true;
        }
        if (!have_below && layer.below >= 0) {
            const LayerGrids& g = grids(layer.below);
            below |= g.model;
            below |= g.support;
            tips |= g.support;
        }
        tips.subtract(here.support);  // support that ends here is a contact tip
        const double reach = layer.height * slope + o.resolution / 2;
        const layers::BitGrid held_grid = below.dilated(reach);

        // (a) per centre-line sample, then holes enclosed by the layer beneath.
        const auto& segs = layer.segments;
        std::vector<std::vector<Sample>> pieces;
        for (std::size_t k = 0; k < segs.size(); ++k) {
            const auto& sg = segs[k];
            double dx = sg.x1 - sg.x0, dy = sg.y1 - sg.y0, len = std::hypot(dx, dy);
            bool joins = false;
            if (k > 0 && !pieces.empty()) {
                const auto& pv = segs[k - 1];
                double pdx = pv.x1 - pv.x0, pdy = pv.y1 - pv.y0, plen = std::hypot(pdx, pdy);
                bool same_path = sg.move == pv.move + 1 && is_support_move(out.moves[sg.move]) == is_support_move(out.moves[pv.move]);
                double cosang = plen > 0 && len > 0 ? (dx * pdx + dy * pdy) / (len * plen) : -1;
                joins = same_path && cosang >= std::cos(kStraightDeg * std::numbers::pi / 180);
            }
            if (!joins) pieces.emplace_back();
            auto& piece = pieces.back();
            double s0 = piece.empty() ? 0 : piece.back().s;
            int n = std::max(1, static_cast<int>(std::ceil(len / o.resolution)));
            for (int i = piece.empty() ? 0 : 1; i <= n; ++i) {
                double t = static_cast<double>(i) / n;
                double x = sg.x0 + dx * t, y = sg.y0 + dy * t;
                piece.push_back({x, y, s0 + len * t, static_cast<int>(k), held_grid.get(held_grid.col(x), held_grid.row(y))});
            }
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
        // bridge limit, or a short dangling end.
        for (auto& piece : pieces) {
            std::size_t i = 0;
            while (i < piece.size()) {
                if (piece[i].held) { ++i; continue; }
                std::size_t j = i;
                while (j < piece.size() && !piece[j].held) ++j;
                bool start_held = i > 0, end_held = j < piece.size();
                double s_a = start_held ? piece[i - 1].s : piece[i].s;
                double s_b = end_held ? piece[j].s : piece[j - 1].s;
                double span = s_b - s_a;
                bool ok = (start_held && end_held && span <= o.bridge_limit) ||
                          ((start_held != end_held) && span <= o.dangling_end);
                if (ok)
                    for (std::size_t k = i; k < j; ++k) piece[k].held = true;
                i = j;
            }
        }
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
        layers::BitGrid unheld_model = proto, unheld_support = proto;
        bool any_left = false;
        for (const auto& piece : pieces)
            for (std::size_t k = 0; k < piece.size(); ++k) {
                if (piece[k].held) continue;
                any_left = true;
                const auto& sm = piece[k];
                const auto& sg = segs[sm.seg];
                const auto& prev = k > 0 ? piece[k - 1] : sm;
                (is_support_move(out.moves[sg.move]) ? unheld_support : unheld_model)
                    .draw_segment(prev.x, prev.y, sm.x, sm.y, sg.width);
            }
        if (!any_left) continue;
        double am = static_cast<double>(unheld_model.count()) * proto.cell_area();
        double as = static_cast<double>(unheld_support.count()) * proto.cell_area();
        r.unheld_model_mm2 += am;
        r.unheld_support_mm2 += as;
        layers::BitGrid both = unheld_model;
        both |= unheld_support;
        r.unheld_regions_mm2 += significant_area(both, o.min_region_mm2);
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

    if (r.unheld_regions_mm2 > o.tolerance_mm2)
        r.failures.push_back("unheld area " + fixed(r.unheld_regions_mm2, 2) + " mm^2 in regions of " +
                             fixed(o.min_region_mm2, 2) + " mm^2 or more (all unheld: model " + fixed(r.unheld_model_mm2, 2) +
                             ", support " + fixed(r.unheld_support_mm2, 2) + ")");
    if (r.collision_mm2 > 0) r.failures.push_back("support within the XY gap of the model: " + fixed(r.collision_mm2, 2) + " mm^2");
    if (r.bad_extrusions) r.failures.push_back(std::to_string(r.bad_extrusions) + " extrusions with a width out of bounds");
    if (r.e_jumps) r.failures.push_back(std::to_string(r.e_jumps) + " E jumps");
    if (r.outside_bed) r.failures.push_back(std::to_string(r.outside_bed) + " extrusions outside the bed");
    if (!r.model_unchanged) r.failures.push_back("model changed: " + r.model_change);
    return r;
}

std::string report_text(const CheckReport& r) {
    std::string o = r.file + ": " + std::to_string(r.layers) + " layers\n";
    o += "  unheld area: " + fixed(r.unheld_model_mm2 + r.unheld_support_mm2, 2) + " mm^2 (model " +
         fixed(r.unheld_model_mm2, 2) + ", support " + fixed(r.unheld_support_mm2, 2) + "); in regions of 1 mm^2 or more: " +
         fixed(r.unheld_regions_mm2, 2) + " mm^2\n";
    for (const auto& w : r.worst_unheld)
        o += "    layer " + std::to_string(w.layer) + " z " + fixed(w.z, 2) + ": " + fixed(w.area_mm2, 2) +
             " mm^2 around (" + fixed(w.x, 1) + ", " + fixed(w.y, 1) + ")\n";
    o += "  collisions: " + fixed(r.collision_mm2, 2) + " mm^2\n";
    for (const auto& w : r.worst_collisions)
        o += "    layer " + std::to_string(w.layer) + " z " + fixed(w.z, 2) + ": " + fixed(w.area_mm2, 2) +
             " mm^2 around (" + fixed(w.x, 1) + ", " + fixed(w.y, 1) + ")\n";
    o += "  extrusion: " + std::to_string(r.bad_extrusions) + " bad widths, " + std::to_string(r.e_jumps) + " E jumps, " +
         std::to_string(r.outside_bed) + " outside the bed\n";
    for (const auto& n : r.extrusion_notes) o += "    " + n + "\n";
    if (r.compared) o += std::string("  model vs original: ") + (r.model_unchanged ? "unchanged" : r.model_change) + "\n";
    o += "  filament: model " + fixed(r.model_filament_mm, 1) + " mm, support " + fixed(r.support_filament_mm, 1) + " mm\n";
    o += "  print time estimate: " + fixed(r.print_time_s / 60, 1) + " min";
    if (r.original_print_time_s >= 0) o += " (original " + fixed(r.original_print_time_s / 60, 1) + " min)";
    o += "\n";
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
    o += "  \"unheld_model_mm2\": " + fixed(r.unheld_model_mm2, 3) + ",\n";
    o += "  \"unheld_support_mm2\": " + fixed(r.unheld_support_mm2, 3) + ",\n";
    o += "  \"worst_unheld\": " + issues(r.worst_unheld) + ",\n";
    o += "  \"collision_mm2\": " + fixed(r.collision_mm2, 3) + ",\n";
    o += "  \"worst_collisions\": " + issues(r.worst_collisions) + ",\n";
    o += "  \"bad_extrusions\": " + std::to_string(r.bad_extrusions) + ",\n";
    o += "  \"e_jumps\": " + std::to_string(r.e_jumps) + ",\n";
    o += "  \"outside_bed\": " + std::to_string(r.outside_bed) + ",\n";
    o += std::string("  \"model_unchanged\": ") + (r.model_unchanged ? "true" : "false") + ",\n";
    o += "  \"support_filament_mm\": " + fixed(r.support_filament_mm, 2) + ",\n";
    o += "  \"model_filament_mm\": " + fixed(r.model_filament_mm, 2) + ",\n";
    o += "  \"print_time_s\": " + fixed(r.print_time_s, 1) + ",\n";
    o += "  \"original_print_time_s\": " + fixed(r.original_print_time_s, 1) + ",\n";
    o += "  \"failures\": [";
    for (std::size_t i = 0; i < r.failures.size(); ++i) o += std::string(i ? ", " : "") + json_string(r.failures[i]);
    o += "]\n}\n";
    return o;
}

}  // namespace scaffold::check
