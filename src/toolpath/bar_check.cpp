#include "toolpath/bar_check.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>
#include <optional>
#include <utility>

#include "layers/crossing.hpp"
#include "layers/raster.hpp"

namespace scaffold::toolpath {

namespace {

constexpr double kZEps = 1e-6;
// Grid beyond the line: the reach, and the crossing test's search (up to
// 3 mm from a sample plus a cell).
constexpr double kMargin = 4.0;

struct Bead {
    float x0, y0, x1, y1, width;
    bool rim;      // bounds the footprint (not a skirt loop, as in the validator)
    bool support;  // a contact tip where it lies under the model of the bar's layer
};

// The crossing test is decided on samples of the written line; a bar
// judged on its exact coordinates was held here and not there
// (figure.slic3r13, z 17.2).
float written(double v) { return layers::as_written(v); }

bool every_held(const std::vector<layers::PieceSample>& p) {
    return std::all_of(p.begin(), p.end(), [](const layers::PieceSample& q) { return q.held; });
}

// Where a line that is not held meets what fails it: the footprint cell
// nearest the middle part of its first unheld run (a column it passes
// beside; its held ends rest on their own columns, so the run's first and
// last kEndsOff are not asked), or the run's middle when no footprint lies
// within kBesideAt of it (a span too long).
constexpr double kEndsOff = 1.0, kBesideAt = 2.0;
Point what_fails(const std::vector<layers::PieceSample>& p, const layers::BitGrid& footprint) {
    std::size_t i = 0;
    while (i < p.size() && p[i].held) ++i;
    if (i == p.size()) return p.empty() ? Point{} : Point{p.front().x, p.front().y};
    std::size_t j = i;
    while (j + 1 < p.size() && !p[j + 1].held) ++j;
    const Point middle{(p[i].x + p[j].x) / 2, (p[i].y + p[j].y) / 2};
    std::size_t a = i, b = j;
    while (a < j && p[a].s - p[i].s < kEndsOff) ++a;
    while (b > a && p[j].s - p[b].s < kEndsOff) --b;
    if (a > b) return middle;
    const double x0 = std::min(p[a].x, p[b].x) - kBesideAt, x1 = std::max(p[a].x, p[b].x) + kBesideAt;
    const double y0 = std::min(p[a].y, p[b].y) - kBesideAt, y1 = std::max(p[a].y, p[b].y) + kBesideAt;
    double best = kBesideAt;
    Point out = middle;
    for (int row = std::max(0, footprint.row(y0)); row <= std::min(footprint.height() - 1, footprint.row(y1)); ++row)
        for (int col = std::max(0, footprint.col(x0)); col <= std::min(footprint.width() - 1, footprint.col(x1)); ++col) {
            if (!footprint.get(col, row)) continue;
            const double cx = footprint.cx(col), cy = footprint.cy(row);
            const double d = layers::segment_distance(cx, cy, p[a].x, p[a].y, p[b].x, p[b].y);
            if (d < best) best = d, out = {cx, cy};
        }
    return out;
}

// The grid a line is judged on, and the beads drawn on it: those reaching
// within `reach` of it.
struct Window {
    double x0, y0, x1, y1, reach;
    bool outside(const Bead& d) const {
        return std::max(d.x0, d.x1) < x0 - reach || std::min(d.x0, d.x1) > x1 + reach ||
               std::max(d.y0, d.y1) < y0 - reach || std::min(d.y0, d.y1) > y1 + reach;
    }
};

// On the validator's lattice (multiples of the cell from the origin, as
// make_grid lays it): a bar grazing a loop is judged cell for cell alike.
Window window_of(const Point& a, const Point& b, double cell, double reach) {
    return {std::floor((std::min(a.x, b.x) - kMargin) / cell) * cell, std::floor((std::min(a.y, b.y) - kMargin) / cell) * cell,
            std::max(a.x, b.x) + kMargin, std::max(a.y, b.y) + kMargin, reach};
}

// Whether the line a -> b on a layer is held by `beads` beneath it: rule
// (a) with the holes they enclose, (b), then (c) near a contact tip (support
// beneath, under the layer's own model `here`), in the validator's order.
bool line_held(const Point& a, const Point& b, const std::vector<Bead>& beads, const std::vector<Bead>& here,
               double reach, double cell, double bridge_limit, double point_radius, std::vector<layers::PieceSample>& p,
               Point* where = nullptr) {
    const Window w = window_of(a, b, cell, reach);
    layers::BitGrid footprint(w.x0, w.y0, w.x1, w.y1, cell), held = footprint, tips = footprint;
    auto outside = [&](const Bead& d) { return w.outside(d); };
    bool any_tip = false;
    for (const Bead& d : beads) {
        if (outside(d)) continue;
        if (d.rim) footprint.draw_segment(d.x0, d.y0, d.x1, d.y1, d.width);
        held.draw_segment(d.x0, d.y0, d.x1, d.y1, d.width + 2 * reach);
        if (d.support) tips.draw_segment(d.x0, d.y0, d.x1, d.y1, d.width);
        any_tip |= d.support;
    }
    layers::Segment line;
    line.x0 = written(a.x), line.y0 = written(a.y), line.x1 = written(b.x), line.y1 = written(b.y);
    p.clear();
    layers::sample_segment(line, 0, held, cell, p);
    if (every_held(p)) return true;
    // Over a hole the beads beneath enclose (the middle of a pillar's loop
    // under the bar's end): held, as the validator fills the footprint. A
    // hole open beyond this grid is taken as open (judged stricter here).
    layers::BitGrid seeds = footprint;
    seeds.clear();
    for (const layers::PieceSample& q : p)
        if (!q.held) seeds.set(seeds.col(q.x), seeds.row(q.y));
    const layers::BitGrid enclosed = footprint.enclosed(seeds);
    for (layers::PieceSample& q : p)
        if (!q.held) q.held = enclosed.get(enclosed.col(q.x), enclosed.row(q.y));
    // METHOD's crossing test depends on where a held end lies to the sample:
    // a run whose held end lies a sample or two further on may no longer
    // leave it across the footprint's edge (the validator's reach holds a
    // sample more beside a bead's end than this grid). So a bar is held by
    // (b) here only if it still is with each held stretch grown by up to
    // three samples.
    bool firm = true;
    std::vector<layers::PieceSample> grown;
    for (std::size_t g = 1; g <= 3 && firm; ++g) {
        grown = p;
        for (std::size_t i = 0; i < p.size(); ++i)
            if (p[i].held)
                for (std::size_t k = i >= g ? i - g : 0; k <= std::min(p.size() - 1, i + g); ++k) grown[k].held = true;
        layers::hold_runs(grown, footprint, bridge_limit);
        firm = every_held(grown);
    }
    if (firm) layers::hold_runs(p, footprint, bridge_limit);  // else (b) holds nothing here
    // Left unheld (for where the bar fails): what neither this nor the grown
    // walk that failed holds.
    auto fail = [&] {
        if (!firm)
            for (std::size_t i = 0; i < p.size(); ++i) p[i].held = p[i].held || grown[i].held;
        if (where) *where = what_fails(p, footprint);
        return false;
    };
    if (every_held(p)) return true;
    if (!any_tip || here.empty()) return fail();
    // Rule (c): the model of this layer within a cell of support beneath
    // rests on a tip, which holds what lies within the point radius of it.
    layers::BitGrid model = footprint;
    model.clear();
    for (const Bead& d : here)
        if (!outside(d)) model.draw_segment(d.x0, d.y0, d.x1, d.y1, d.width);
    tips &= model.dilated(cell);
    if (!tips.any()) return fail();
    const layers::BitGrid tip_reach = tips.dilated(point_radius);
    for (layers::PieceSample& q : p)
        if (!q.held) q.held = tip_reach.get(tip_reach.col(q.x), tip_reach.row(q.y));
    return every_held(p) || fail();
}

// The support printed up to three nominal layers under layer `l`.
void gather_support(int l, const std::vector<LayerPaths>& printed, const layers::LayerStack& stack,
                    const Settings& settings, std::vector<Bead>& beads) {
    const layers::Layer& layer = stack.layers[l];
    for (const LayerPaths& under : printed) {
        // The validator's tolerance (layers::kZEps): heights read as floats
        // put a layer exactly three below at 0.6000023 (38.2 over 37.6).
        const double dz = layer.z - printed_z(under, stack);
        if (dz <= layers::kZEps || dz > 3 * settings.layer_height + layers::kZEps) continue;
        for (const Path& path : under.paths)
            for (std::size_t i = 1; i < path.points.size(); ++i)
                beads.push_back({written(path.points[i - 1].x), written(path.points[i - 1].y), written(path.points[i].x),
                                 written(path.points[i].y), static_cast<float>(path.width), true, true});
    }
}

// What lies beneath layer `l` as METHOD and the validator take it: the
// model within one nominal layer (its layers beneath), support printed up to
// three nominal layers down (`printed`), and the model of the layer itself.
void gather_beneath(int l, const std::vector<LayerPaths>& printed, const layers::LayerStack& stack,
                    const Settings& settings, std::vector<Bead>& beads, std::vector<Bead>& here) {
    const layers::Layer& layer = stack.layers[l];
    beads.clear();
    for (int k : layer.beneath)
        for (const layers::Segment& sg : stack.layers[k].segments)
            beads.push_back({sg.x0, sg.y0, sg.x1, sg.y1, sg.width, sg.role != gcode::Role::Skirt, false});
    here.clear();
    for (const layers::Segment& sg : layer.segments)
        if (sg.role != gcode::Role::Skirt && !gcode::is_support(sg.role))
            here.push_back({sg.x0, sg.y0, sg.x1, sg.y1, sg.width, true, false});
    gather_support(l, printed, stack, settings, beads);
}

double reach_on(const layers::Layer& layer, const Settings& settings) {
    return layer.height * std::tan(settings.overhang_angle_deg * std::numbers::pi / 180) + settings.resolution / 2;
}

}  // namespace

bool segment_held(const Point& a, const Point& b, int layer, const std::vector<LayerPaths>& printed,
                  const layers::LayerStack& stack, const Settings& settings) {
    std::vector<Bead> beads, here;
    std::vector<layers::PieceSample> samples;
    gather_beneath(layer, printed, stack, settings, beads, here);
    return line_held(a, b, beads, here, reach_on(stack.layers[layer], settings), settings.resolution,
                     settings.marked_bridge_limit, settings.point_radius, samples);
}

std::vector<UnheldBar> unheld_bars(const plan::Scaffold& scaffold, const SupportPaths& paths,
                                   const layers::LayerStack& stack, const Settings& settings, BarCheckCache* cache) {
    std::vector<UnheldBar> out;
    if (scaffold.bridges.empty()) return out;
    std::vector<Bead> beads, here, support;
    std::vector<layers::PieceSample> samples;
    std::vector<double> key;
    std::vector<std::array<double, 5>> near;
    for (std::size_t bi = 0; bi < scaffold.bridges.size(); ++bi) {
        const plan::Bridge& br = scaffold.bridges[bi];
        std::optional<UnheldBar> bad;
        for (const LayerPaths& lp : paths.layers) {
            if (lp.bond()) continue;  // loops only, under a column's first layer
            const double z = stack.layers[lp.layer].z;
            if (z <= br.z + kZEps || z > br.z + kBridgeThickness + kZEps) continue;
            // With a cache, the model beneath only once a line is not in it.
            bool gathered = false;
            if (cache) {
                support.clear();
                gather_support(lp.layer, paths.layers, stack, settings, support);
            } else {
                gather_beneath(lp.layer, paths.layers, stack, settings, beads, here);
                gathered = true;
            }
            const double reach = reach_on(stack.layers[lp.layer], settings);
            for (const std::vector<Point>& line : bar_lines(br, settings.support_width, settings.pillar_radius)) {
                const Point &a = line.front(), &b = line.back();
                BarCheckCache::Answer answer;
                std::map<std::vector<double>, BarCheckCache::Answer>::iterator found;
                if (cache) {
                    // The model beneath and beside is the layer's: the key
                    // holds the support beads line_held would draw.
                    const Window w = window_of(a, b, settings.resolution, reach);
                    near.clear();
                    for (const Bead& d : support)
                        if (!w.outside(d)) near.push_back({d.x0, d.y0, d.x1, d.y1, d.width});
                    std::sort(near.begin(), near.end());
                    key.assign({static_cast<double>(lp.layer), a.x, a.y, b.x, b.y});
                    for (const auto& d : near) key.insert(key.end(), d.begin(), d.end());
                    found = cache->answers.find(key);
                }
                if (cache && found != cache->answers.end()) {
                    answer = found->second;
                } else {
                    if (!gathered) gather_beneath(lp.layer, paths.layers, stack, settings, beads, here);
                    gathered = true;
                    answer.held = line_held(a, b, beads, here, reach, settings.resolution, settings.marked_bridge_limit,
                                            settings.point_radius, samples, &answer.at);
                    if (cache) cache->answers.emplace(key, answer);
                }
                if (!answer.held) {
                    bad = UnheldBar{bi, answer.at.x, answer.at.y};
                    break;
                }
            }
            if (bad) break;
        }
        if (bad) out.push_back(*bad);
    }
    return out;
}

}  // namespace scaffold::toolpath
