#include "overhang/overhangs.hpp"

#include <algorithm>
#include <bit>
#include <cmath>
#include <numbers>

namespace scaffold::overhang {

namespace {

// Beads closer than this belong to one overhang region.
constexpr double kJoin = 0.6;

struct Cell {
    int i, j;
};

// 8-connected components of the set cells, each as a list of cells in
// row-major discovery order (deterministic).
std::vector<std::vector<Cell>> components(const layers::BitGrid& g) {
    layers::BitGrid seen(g.origin_x(), g.origin_y(), g.origin_x() + g.width() * g.cell(),
                         g.origin_y() + g.height() * g.cell(), g.cell());
    std::vector<std::vector<Cell>> out;
    std::vector<Cell> stack;
    const auto& words = g.words();
    int wpr = g.words_per_row();
    for (int j = 0; j < g.height(); ++j) {
        for (int w = 0; w < wpr; ++w) {
            std::uint64_t bits = words[static_cast<std::size_t>(j) * wpr + w];
            while (bits) {
                int i = w * 64 + std::countr_zero(bits);
                bits &= bits - 1;
                if (seen.get(i, j)) continue;
                std::vector<Cell> comp;
                stack.push_back({i, j});
                seen.set(i, j);
                while (!stack.empty()) {
                    Cell c = stack.back();
                    stack.pop_back();
                    comp.push_back(c);
                    for (int dj = -1; dj <= 1; ++dj)
                        for (int di = -1; di <= 1; ++di) {
                            int a = c.i + di, b = c.j + dj;
                            if ((di || dj) && g.get(a, b) && !seen.get(a, b)) {
                                seen.set(a, b);
                                stack.push_back({a, b});
                            }
                        }
                }
                out.push_back(std::move(comp));
            }
        }
    }
    return out;
}

// One point per grid bin of `cells`, on the cell nearest the bin's centroid.
void bin_points(const layers::BitGrid& g, const std::vector<Cell>& cells, double spacing, double shift, double z,
                int layer, std::vector<SupportPoint>& out) {
    std::vector<std::pair<long long, std::size_t>> keyed;
    keyed.reserve(cells.size());
    for (std::size_t k = 0; k < cells.size(); ++k) {
        long long bx = static_cast<long long>(std::floor((g.cx(cells[k].i) + shift) / spacing));
        long long by = static_cast<long long>(std::floor((g.cy(cells[k].j) + shift) / spacing));
        keyed.emplace_back(by * 1000003LL + bx, k);
    }
    std::stable_sort(keyed.begin(), keyed.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
    for (std::size_t a = 0; a < keyed.size();) {
        std::size_t b = a;
        double sx = 0, sy = 0;
        while (b < keyed.size() && keyed[b].first == keyed[a].first) {
            sx += g.cx(cells[keyed[b].second].i);
            sy += g.cy(cells[keyed[b].second].j);
            ++b;
        }
        double n_in = static_cast<double>(b - a), mx = sx / n_in, my = sy / n_in;
        std::size_t best = keyed[a].second;
        double best_d = 1e300;
        for (std::size_t k = a; k < b; ++k) {
            const Cell& c = cells[keyed[k].second];
            double d = std::hypot(g.cx(c.i) - mx, g.cy(c.j) - my);
            if (d < best_d) { best_d = d; best = keyed[k].second; }
        }
        out.push_back({g.cx(cells[best].i), g.cy(cells[best].j), z, layer});
        a = b;
    }
}

// Support points covering one region: every cell within `radius` of a
// point, every point on a cell. Rounds of grid binning (bins shifted by half
// a spacing each round) over what is still uncovered, then a greedy cover.
std::vector<SupportPoint> cover_region(const layers::BitGrid& g, const std::vector<Cell>& cells, double spacing,
                                       double radius, double z, int layer) {
    // Coverage on a grid over the region's bounds only; a hair inside the
    // radius so the raster never claims a cell the exact distance would not.
    const double reach = radius - 1e-6;
    int i0 = cells.front().i, i1 = i0, j0 = cells.front().j, j1 = j0;
    for (const Cell& c : cells) {
        i0 = std::min(i0, c.i); i1 = std::max(i1, c.i);
        j0 = std::min(j0, c.j); j1 = std::max(j1, c.j);
    }
    const double cell = g.cell();
    layers::BitGrid covered(g.origin_x() + i0 * cell, g.origin_y() + j0 * cell, g.origin_x() + (i1 + 1) * cell,
                            g.origin_y() + (j1 + 1) * cell, cell);
    auto is_covered = [&](const Cell& c) { return covered.get(covered.col(g.cx(c.i)), covered.row(g.cy(c.j))); };
    std::vector<SupportPoint> pts;
    std::size_t drawn = 0;
    auto uncovered = [&](const std::vector<Cell>& todo) {
        for (; drawn < pts.size(); ++drawn) covered.draw_disc(pts[drawn].x, pts[drawn].y, reach);
        std::vector<Cell> left;
        for (const Cell& c : todo)
            if (!is_covered(c)) left.push_back(c);
        return left;
    };
    std::vector<Cell> todo = cells;
    for (int round = 0; round < 4 && !todo.empty(); ++round) {
        double shift = round * spacing / 2;
        bin_points(g, todo, spacing, shift, z, layer, pts);
        todo = uncovered(todo);
    }
    // Greedy: a point that surely covers the first uncovered cell, on the
    // uncovered cell nearest the middle of the uncovered cells around it.
    while (!todo.empty()) {
        const double x0 = g.cx(todo.front().i), y0 = g.cy(todo.front().j);
        auto near = [&](const Cell& c) { return std::hypot(g.cx(c.i) - x0, g.cy(c.j) - y0) <= reach; };
        double sx = 0, sy = 0, n = 0;
        for (const Cell& c : todo)
            if (near(c)) { sx += g.cx(c.i); sy += g.cy(c.j); ++n; }
        Cell best = todo.front();
        double best_d = 1e300;
        for (const Cell& c : todo) {
            double d = std::hypot(g.cx(c.i) - sx / n, g.cy(c.j) - sy / n);
            if (d < best_d && near(c)) { best_d = d; best = c; }
        }
        pts.push_back({g.cx(best.i), g.cy(best.j), z, layer});
        todo = uncovered(todo);
    }
    return pts;
}

// Overhang regions: cells of `g` grouped by the components of `g` grown by
// `join` mm, so the parallel lines of one bridge or skin make one region.
std::vector<std::vector<Cell>> regions(const layers::BitGrid& g, double join) {
    std::vector<std::vector<Cell>> out;
    for (auto& comp : components(g.dilated(join))) {
        std::vector<Cell> cells;
        for (const Cell& c : comp)
            if (g.get(c.i, c.j)) cells.push_back(c);
        std::sort(cells.begin(), cells.end(), [](const Cell& a, const Cell& b) { return a.j != b.j ? a.j < b.j : a.i < b.i; });
        if (!cells.empty()) out.push_back(std::move(cells));
    }
    return out;
}

// Draws the stretches of the segment whose centre line lies outside `held`.
void draw_unheld_stretches(const layers::Segment& sg, const layers::BitGrid& held, double step, layers::BitGrid& out) {
    double len = std::hypot(sg.x1 - sg.x0, sg.y1 - sg.y0);
    int steps = std::max(1, static_cast<int>(std::ceil(len / step)));
    int run = -1;
    for (int k = 0; k <= steps + 1; ++k) {
        bool unheld = false;
        if (k <= steps) {
            double t = static_cast<double>(k) / steps;
            double x = sg.x0 + (sg.x1 - sg.x0) * t, y = sg.y0 + (sg.y1 - sg.y0) * t;
            unheld = !held.get(held.col(x), held.row(y));
        }
        if (unheld && run < 0) run = k;
        if (!unheld && run >= 0) {
            double ta = static_cast<double>(run) / steps, tb = static_cast<double>(k - 1) / steps;
            out.draw_segment(sg.x0 + (sg.x1 - sg.x0) * ta, sg.y0 + (sg.y1 - sg.y0) * ta, sg.x0 + (sg.x1 - sg.x0) * tb,
                             sg.y0 + (sg.y1 - sg.y0) * tb, sg.width);
            run = -1;
        }
    }
}

// Consecutive moves of one extrusion path turning by less than this make
// one straight piece, as in METHOD.md's rule (b) and scaffold-check.
constexpr double kStraightDeg = 10;

// Does segment b continue segment a on one path, within 10 deg of the
// piece's first segment? (Against the first, not the one before: a finely
// divided circle turns a few degrees a move and is no straight bridge; the
// validator judges pieces the same way.)
bool continues_straight(const layers::Segment& first, const layers::Segment& a, const layers::Segment& b) {
    if (b.move != a.move + 1) return false;
    if (std::abs(b.x0 - a.x1) > 1e-3f || std::abs(b.y0 - a.y1) > 1e-3f) return false;
    double fdx = first.x1 - first.x0, fdy = first.y1 - first.y0, bdx = b.x1 - b.x0, bdy = b.y1 - b.y0;
    double lf = std::hypot(fdx, fdy), lb = std::hypot(bdx, bdy);
    if (lf <= 0 || lb <= 0) return false;
    return (fdx * bdx + fdy * bdy) / (lf * lb) >= std::cos(kStraightDeg * std::numbers::pi / 180);
}

struct Sample {
    double x, y, s;  // centre-line position and arc length along the piece
    float width;
    bool held;
};

// Polyline through samples [a, b] at their beads' width.
void draw_samples(const std::vector<Sample>& p, std::size_t a, std::size_t b, layers::BitGrid& out) {
    if (a == b) out.draw_disc(p[a].x, p[a].y, p[a].width / 2);
    for (std::size_t k = a + 1; k <= b; ++k) out.draw_segment(p[k - 1].x, p[k - 1].y, p[k].x, p[k].y, p[k].width);
}

// Slicer-marked bridge segments [first, last] (one straight piece of one
// path): an unheld run of the centre line held on both sides and no longer
// than the bridge limit is spanned; a dangling or too long run is overhang.
void bridge_piece(const std::vector<layers::Segment>& segs, std::size_t first, std::size_t last,
                  const layers::BitGrid& held, double step, double max_bridge, layers::BitGrid& over,
                  layers::BitGrid& spanned, std::vector<Sample>& p) {
    p.clear();
    for (std::size_t k = first; k <= last; ++k) {
        const layers::Segment& sg = segs[k];
        double dx = sg.x1 - sg.x0, dy = sg.y1 - sg.y0, len = std::hypot(dx, dy);
        double s0 = p.empty() ? 0 : p.back().s;
        int n = std::max(1, static_cast<int>(std::ceil(len / step)));
        for (int i = p.empty() ? 0 : 1; i <= n; ++i) {
            double t = static_cast<double>(i) / n, x = sg.x0 + dx * t, y = sg.y0 + dy * t;
            p.push_back({x, y, s0 + len * t, sg.width, held.get(held.col(x), held.row(y))});
        }
    }
    for (std::size_t i = 0; i < p.size();) {
        if (p[i].held) { ++i; continue; }
        std::size_t j = i;
        while (j < p.size() && !p[j].held) ++j;
        bool bounded = i > 0 && j < p.size();
        if (bounded && p[j].s - p[i - 1].s <= max_bridge)
            draw_samples(p, i - 1, j, spanned);
        else
            draw_samples(p, i, j - 1, over);
        i = j;
    }
}

}  // namespace

Overhangs find_overhangs(const layers::LayerStack& stack, const Settings& s) {
    Overhangs out;
    const layers::BitGrid proto = layers::make_grid(stack, s.resolution, 2.0);
    const double slope = std::tan(s.overhang_angle_deg * std::numbers::pi / 180);
    // Scratch grids for the whole stack, cleared per layer rather than
    // reallocated: the layer beneath (all its material, and the part of it
    // that can enclose a hole: a skirt or brim loop holds what lies on it but
    // encloses nothing, as in the validator), and this layer's overhang and
    // held marked bridges.
    layers::BitGrid below = proto, rim = proto, held = proto, over = proto, spanned = proto;
    // What each scratch grid may hold: work stays inside the layers' boxes.
    layers::CellBox below_box, held_box, over_box;
    bool below_has_skirt = false;
    int below_index = -1;
    std::vector<Sample> samples;
    for (int n = 0; n < static_cast<int>(stack.layers.size()); ++n) {
        const layers::Layer& layer = stack.layers[n];
        if (layer.on_bed || layer.below < 0) continue;
        if (layer.below != below_index) {
            const layers::Layer& under = stack.layers[layer.below];
            below.clear(below_box);
            if (below_has_skirt) rim.clear(below_box);
            below_box = layers::layer_box(below, under);
            layers::draw_layer(below, under);
            below_has_skirt = std::any_of(under.segments.begin(), under.segments.end(),
                                          [](const layers::Segment& sg) { return sg.role == gcode::Role::Skirt; });
            if (below_has_skirt) {
                for (const layers::Segment& sg : under.segments)
                    if (sg.role != gcode::Role::Skirt) rim.draw_segment(sg.x0, sg.y0, sg.x1, sg.y1, sg.width);
            }
            below_index = layer.below;
        }
        // Half a cell inside the validator's reach (which adds half a cell), so
        // raster alignment never decides a borderline bead.
        held.clear(held_box);
        held_box = below.dilate_into(held, std::max(0.0, layer.height * slope - s.resolution / 2), below_box);
        over.clear(over_box);
        spanned.clear(over_box);
        over_box = layers::layer_box(over, layer);
        const auto& segs = layer.segments;
        for (std::size_t k = 0; k < segs.size(); ++k) {
            if (gcode::is_bridge(segs[k].role)) {
                // The span is the whole straight piece, not one move: slicers
                // split bridge lines and overhang perimeters into many moves.
                std::size_t last = k;
                while (last + 1 < segs.size() && gcode::is_bridge(segs[last + 1].role) &&
                       continues_straight(segs[k], segs[last], segs[last + 1]))
                    ++last;
                bridge_piece(segs, k, last, held, s.resolution, s.max_bridge, over, spanned, samples);
                k = last;
                continue;
            }
            // A bead is held where its centre line is held (METHOD.md's rule,
            // the one scaffold-check applies): only the unheld stretches of
            // the centre line make overhang, drawn at the bead's width.
            draw_unheld_stretches(segs[k], held, s.resolution, over);
        }
        over.subtract(spanned, over_box);
        // Over a hole enclosed by the layer beneath (sparse infill under a
        // skin) is held: the filled footprint counts, not just the beads.
        if (!over.any(over_box)) continue;
        over.subtract((below_has_skirt ? rim : below).enclosed(over));
        if (!over.any()) continue;
        // Drop specks: regions smaller than the minimum area.
        double cell_area = over.cell_area();
        OverhangLayer ol;
        ol.layer = n;
        ol.cells = proto;
        for (const auto& comp : regions(over, kJoin)) {
            if (static_cast<double>(comp.size()) * cell_area < s.min_overhang_area) continue;
            for (const Cell& c : comp) ol.cells.set(c.i, c.j);
        }
        std::size_t count = ol.cells.count();
        if (count == 0) continue;
        ol.area_mm2 = static_cast<double>(count) * cell_area;
        out.area_mm2 += ol.area_mm2;
        out.layers.push_back(std::move(ol));
    }
    return out;
}

SupportPoints place_points(const Overhangs& overhangs, const layers::LayerStack& stack, const Settings& s) {
    SupportPoints out;
    out.overhang_area_mm2 = overhangs.area_mm2;
    for (const OverhangLayer& ol : overhangs.layers) {
        const layers::BitGrid& g = ol.cells;
        const layers::Layer& layer = stack.layers[ol.layer];
        double z = layer.z - layer.height;
        std::vector<SupportPoint> pts;
        for (const auto& comp : regions(g, kJoin)) {
            std::vector<SupportPoint> some = cover_region(g, comp, s.point_spacing, s.point_radius, z, ol.layer);
            pts.insert(pts.end(), some.begin(), some.end());
        }
        std::stable_sort(pts.begin(), pts.end(), [](const SupportPoint& a, const SupportPoint& b) {
            return a.y != b.y ? a.y < b.y : a.x < b.x;
        });
        out.points.insert(out.points.end(), pts.begin(), pts.end());
    }
    return out;
}

}  // namespace scaffold::overhang
