#include "overhang/overhangs.hpp"

#include "layers/crossing.hpp"
#include "layers/regions.hpp"

#include <algorithm>
#include <atomic>
#include <bit>
#include <cmath>
#include <exception>
#include <numbers>
#include <thread>

namespace scaffold::overhang {

using layers::Region;
using layers::kept_regions;
using layers::regions;

namespace {

constexpr double kJoin = layers::kRegionJoin;


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

using layers::kStraightDeg;  // one straight piece, as in METHOD.md's rule (b) and scaffold-check

// Does segment b continue segment a on one path, within 10 deg of the
// piece's first segment? (Against the first, not the one before: a finely
// divided circle turns a few degrees a move and is no straight bridge; the
// validator judges pieces the same way.)
bool continues_straight(const layers::Segment& first, const layers::Segment& a, const layers::Segment& b) {
    if (b.move != a.move + 1) return false;
    if (std::abs(b.x0 - a.x1) > 1e-3f || std::abs(b.y0 - a.y1) > 1e-3f) return false;
    double fdx = first.x1 - first.x0, fdy = first.y1 - first.y0, bdx = b.x1 - b.x0, bdy = b.y1 - b.y0;
    const double limit = std::cos(kStraightDeg * std::numbers::pi / 180);
    // Square roots rather than hypot (a library call, 3 % of detection);
    // hypot decides where the two could round to different sides of the limit.
    double lf = std::sqrt(fdx * fdx + fdy * fdy), lb = std::sqrt(bdx * bdx + bdy * bdy);
    if (lf <= 0 || lb <= 0) return false;
    if (double c = (fdx * bdx + fdy * bdy) / (lf * lb); std::abs(c - limit) > 1e-9) return c >= limit;
    lf = std::hypot(fdx, fdy), lb = std::hypot(bdx, bdy);
    return (fdx * bdx + fdy * bdy) / (lf * lb) >= limit;
}

// Does b start where a ends, next on the same path?
bool joined(const layers::Segment& a, const layers::Segment& b) {
    return b.move == a.move + 1 && std::abs(b.x0 - a.x1) < 1e-3f && std::abs(b.y0 - a.y1) < 1e-3f;
}

using Sample = layers::PieceSample;  // seg: index into the layer's segments

// Polyline through samples [a, b] at their beads' width: one line per
// segment, not one per sample step (the steps of a segment are collinear
// and of one width, so the set of cells is the same).
void draw_samples(const std::vector<layers::Segment>& segs, const std::vector<Sample>& p, std::size_t a, std::size_t b,
                  layers::BitGrid& out) {
    if (a == b) out.draw_disc(p[a].x, p[a].y, segs[p[a].seg].width / 2);
    for (std::size_t k = a + 1; k <= b;) {
        std::size_t e = k;
        while (e < b && p[e + 1].seg == p[k].seg) ++e;
        out.draw_segment(p[k - 1].x, p[k - 1].y, p[e].x, p[e].y, segs[p[k].seg].width);
        k = e + 1;
    }
}

}  // namespace

// A square root instead of hypot and a multiplication instead of the
// division, unless the quotient is close to an integer.
int sample_count(double dx, double dy, double step, double inv_step) {
    const double q = std::sqrt(dx * dx + dy * dy) * inv_step;
    if (q < 1e9) {
        int c = static_cast<int>(q);
        if (c < q) ++c;  // ceil, q >= 0
        if (c - q >= 1e-9 * (c + 1) && q - (c - 1) >= 1e-9 * (c + 1)) return std::max(1, c);
    }
    return std::max(1, static_cast<int>(std::ceil(std::hypot(dx, dy) / step)));
}

namespace {

// Whether every centre-line sample straight_piece takes of segments
// [first, last] is held (most pieces): found without storing the samples.
bool all_samples_held(const std::vector<layers::Segment>& segs, std::size_t first, std::size_t last,
                      const layers::BitGrid& held, double step) {
    const double inv_step = 1 / step;
    for (std::size_t k = first; k <= last; ++k) {
        const layers::Segment& sg = segs[k];
        const double dx = sg.x1 - sg.x0, dy = sg.y1 - sg.y0;
        if (!held.all_set_at(sg.x0, sg.y0, dx, dy, sample_count(dx, dy, step, inv_step), k == first ? 0 : 1))
            return false;
    }
    return true;
}

// The centre-line samples of segments [first, last], at most `step` apart.
// Each piece is judged on its own, as the validator does: a held span keeps
// its own bead from being overhang, not the beads it overlaps.
void piece_samples(const std::vector<layers::Segment>& segs, std::size_t first, std::size_t last,
                   const layers::BitGrid& held, double step, std::vector<Sample>& p) {
    p.clear();
    for (std::size_t k = first; k <= last; ++k) layers::sample_segment(segs[k], static_cast<std::uint32_t>(k), held, step, p);
}

// Whether a held sample lies within a dangling end (1 mm) of the piece's
// start (or end), along it.
bool held_near_end(const std::vector<layers::Segment>& segs, std::size_t first, std::size_t last,
                   const layers::BitGrid& held, double step, bool at_end, std::vector<Sample>& p) {
    if (all_samples_held(segs, first, last, held, step)) return true;
    piece_samples(segs, first, last, held, step, p);
    return layers::held_near_end(p, at_end);
}

// Segments [first, last] (one straight piece of one path): an unheld run of
// the centre line held on both sides, no longer than `max_span` and leaving
// both held ends across the edge of `footprint` (the material beneath) is
// spanned, as is a dangling end of at most 1 mm; other unheld runs overhang.
// A corner where the path turns counts as held when the piece beyond it is
// held within a dangling end (first_held / last_held). Called for pieces
// not held throughout. Returns whether it drew.
bool straight_piece(const std::vector<layers::Segment>& segs, std::size_t first, std::size_t last,
                    const layers::BitGrid& held, const layers::BitGrid& footprint, double step, double max_span,
                    bool first_held, bool last_held, layers::BitGrid& over, std::vector<Sample>& p) {
    piece_samples(segs, first, last, held, step, p);
    if (first_held) p.front().held = true;
    if (last_held) p.back().held = true;
    layers::hold_runs(p, footprint, max_span);
    bool drew = false;
    for (std::size_t i = 0; i < p.size();) {
        if (p[i].held) { ++i; continue; }
        std::size_t j = i;
        while (j < p.size() && !p[j].held) ++j;
        draw_samples(segs, p, i, j - 1, over);
        drew = true;
        i = j;
    }
    return drew;
}

bool is_support_segment(const layers::Segment& sg) { return gcode::is_support(sg.role); }

// Bridge infill may span the marked-bridge limit; an overhang perimeter is
// a wall, held across a gap like any other bead (METHOD's rule (b)).
bool is_bridge_infill(const layers::Segment& sg) { return sg.role == gcode::Role::BridgeInfill; }

// The layers below layer n holding the slicer's own support within reach
// of it: three nominal layers, or the layer's own stated height (the
// validator's window for support beneath).
void slicer_support_beneath(const layers::LayerStack& stack, int n, double layer_height, std::vector<int>& out) {
    out.clear();
    const layers::Layer& layer = stack.layers[n];
    for (int k = n - 1; k >= 0; --k) {
        const layers::Layer& under = stack.layers[k];
        const double dz = layer.z - under.z;
        if (dz <= layers::kZEps) continue;
        if (dz > 3 * layer_height + layers::kZEps && dz > layer.nominal_height + layers::kZEps) {
            if (under.z < layer.z - 3 * layer_height - 1.0) break;
            continue;
        }
        if (under.slicer_support) out.push_back(k);
    }
}

// The overhang regions of layers [first, end), in layer order. Each layer's
// depend on it and the layer beneath only, so ranges can run in parallel.
void find_regions_in(const layers::LayerStack& stack, const Settings& s, const layers::BitGrid& proto, int first,
                     int end, std::vector<Region>& found) {
    const double slope = std::tan(s.overhang_angle_deg * std::numbers::pi / 180);
    // Scratch grids for the whole stack, cleared per layer rather than
    // reallocated: the layer beneath (all its material, and the part of it
    // that can enclose a hole: a skirt or brim loop holds what lies on it but
    // encloses nothing, as in the validator), and this layer's overhang.
    layers::BitGrid below = proto, rim = proto, held = proto, over = proto, seeds = proto;
    // What each scratch grid may hold: work stays inside the layers' boxes.
    layers::CellBox below_box, held_box, over_box;
    bool below_has_skirt = false, over_drawn = false;
    std::vector<int> below_layers;  // the layers drawn into `below`
    // The slicer's own support in the file (a Simplify3D or Cura print
    // sliced with support on): METHOD's "layer beneath" reaches three
    // nominal layers down to it (the contact gap over support), and where it
    // lies under this layer's model it is a contact tip (rule (c)).
    std::vector<int> contact, contact_layers;  // layers with slicer support in reach; those drawn
    layers::BitGrid tips = proto, model = proto;
    int over_index = -1;            // over_box is layer_box of layer over_index
    std::vector<Sample> samples;
    std::vector<std::pair<std::size_t, std::size_t>> pieces;  // first, last segment of each straight piece
    for (int n = first; n < end; ++n) {
        const layers::Layer& layer = stack.layers[n];
        if (layer.on_bed || layer.below < 0) continue;
        slicer_support_beneath(stack, n, s.layer_height, contact);
        if (layer.beneath != below_layers || contact != contact_layers) {
            below.clear(below_box);
            if (below_has_skirt) rim.clear(below_box);
            below_has_skirt = false;
            below_box = {};
            for (int k : layer.beneath) {
                const layers::Layer& under = stack.layers[k];
                below_box = layers::united(below_box, k == over_index ? over_box : layers::layer_box(below, under));
                layers::draw_layer(below, under);
                below_has_skirt |= std::any_of(under.segments.begin(), under.segments.end(),
                                               [](const layers::Segment& sg) { return sg.role == gcode::Role::Skirt; });
            }
            if (below_has_skirt) {
                for (int k : layer.beneath)
                    for (const layers::Segment& sg : stack.layers[k].segments)
                        if (sg.role != gcode::Role::Skirt) rim.draw_segment(sg.x0, sg.y0, sg.x1, sg.y1, sg.width);
            }
            for (int k : contact) {
                below_box = layers::united(below_box, layers::layer_box(below, stack.layers[k]));
                for (const layers::Segment& sg : stack.layers[k].segments)
                    if (is_support_segment(sg)) {
                        below.draw_segment(sg.x0, sg.y0, sg.x1, sg.y1, sg.width);
                        if (below_has_skirt) rim.draw_segment(sg.x0, sg.y0, sg.x1, sg.y1, sg.width);
                    }
            }
            below_layers = layer.beneath;
            contact_layers = contact;
        }
        // The validator's reach, on the same cell lattice (make_grid): a bead
        // the validator holds is no overhang here, so no support goes under
        // raster noise (a 0.1 mm sliver along every layer's edge).
        held.clear(held_box);
        held_box = {};
        const double reach = layer.height * slope + s.resolution / 2;
        for (int k : layer.beneath)
            held_box = layers::united(held_box, layers::draw_reach(held, stack.layers[k], reach, [](const layers::Segment&) { return true; }));
        for (int k : contact)
            held_box = layers::united(held_box, layers::draw_reach(held, stack.layers[k], reach, is_support_segment));
        if (over_drawn) over.clear(over_box);
        over_box = layers::layer_box(over, layer);
        over_index = n;
        over_drawn = false;
        const auto& segs = layer.segments;
        // Rule (a) over a hole the layer beneath encloses (a gap between a
        // skin's lines, sparse infill under a skin): a centre-line sample
        // there is held, as the validator holds it, before rule (b) and
        // before any bead is drawn. Judged after drawing, a bead's sides
        // over the hole's rim stayed overhang: 421 one-cell specks under a
        // Cura mushroom's cap that the validator finds held, all dropped.
        // Every sample of every bead held (most layers): no piece can be
        // unheld, nothing is judged or drawn.
        bool any_unheld = false, any_seed = false;
        for (std::size_t k = 0; k < segs.size(); ++k) {
            if (all_samples_held(segs, k, k, held, s.resolution)) continue;
            any_unheld = true;
            if (gcode::is_support(segs[k].role)) continue;
            samples.clear();
            layers::sample_segment(segs[k], static_cast<std::uint32_t>(k), held, s.resolution, samples);
            for (const Sample& sm : samples)
                if (!sm.held) {
                    seeds.set(seeds.col(sm.x), seeds.row(sm.y));
                    any_seed = true;
                }
        }
        if (any_seed) {
            held |= (below_has_skirt ? rim : below).enclosed(seeds, over_box);
            held_box = layers::united(held_box, over_box);
            seeds.clear(over_box);
        }
        if (!any_unheld) continue;
        // A bead is held where its centre line is held (METHOD.md's rule,
        // the one scaffold-check applies): only the unheld stretches of the
        // centre line make overhang, drawn at the bead's width. The span is
        // the whole straight piece, not one move: slicers split bridge lines
        // and overhang perimeters into many moves.
        pieces.clear();
        for (std::size_t k = 0; k < segs.size(); ++k) {
            const bool bridge = is_bridge_infill(segs[k]);
            std::size_t last = k;
            while (last + 1 < segs.size() && is_bridge_infill(segs[last + 1]) == bridge &&
                   continues_straight(segs[k], segs[last], segs[last + 1]))
                ++last;
            pieces.push_back({k, last});
            k = last;
        }
        for (std::size_t q = 0; q < pieces.size(); ++q) {
            const auto [k, last] = pieces[q];
            // The slicer's own support is the slicer's: scaffold holds the model.
            if (gcode::is_support(segs[k].role)) continue;
            const bool bridge = is_bridge_infill(segs[k]);
            // Corners: the path goes on from the piece before / into the next.
            // Most pieces are held throughout: nothing to draw, no corner to
            // look at.
            if (all_samples_held(segs, k, last, held, s.resolution)) continue;
            const bool from_prev = q > 0 && joined(segs[k - 1], segs[k]);
            const bool into_next = q + 1 < pieces.size() && joined(segs[last], segs[last + 1]);
            const bool first_held =
                from_prev && held_near_end(segs, pieces[q - 1].first, pieces[q - 1].second, held, s.resolution, true, samples);
            const bool last_held = into_next && held_near_end(segs, pieces[q + 1].first, pieces[q + 1].second, held,
                                                              s.resolution, false, samples);
            over_drawn |= straight_piece(segs, k, last, held, below_has_skirt ? rim : below, s.resolution,
                                         bridge ? s.marked_bridge_limit : s.max_bridge, first_held, last_held, over,
                                         samples);
        }
        if (over_drawn && !contact.empty()) {
            // Rule (c) for the slicer's contact tips, after (a) and (b) as
            // the validator applies it: a tip holds what lies within the
            // point radius of it.
            tips.clear();
            model.clear();
            for (int k : contact)
                for (const layers::Segment& sg : stack.layers[k].segments)
                    if (is_support_segment(sg)) tips.draw_segment(sg.x0, sg.y0, sg.x1, sg.y1, sg.width);
            for (const layers::Segment& sg : segs)
                if (!gcode::is_support(sg.role) && sg.role != gcode::Role::Skirt)
                    model.draw_segment(sg.x0, sg.y0, sg.x1, sg.y1, sg.width);
            tips &= model.dilated(s.resolution);
            if (tips.any()) over.subtract(tips.dilated(s.point_radius));
        }
        // Over a hole enclosed by the layer beneath (sparse infill under a
        // skin) is held: the filled footprint counts, not just the beads.
        if (!over_drawn || !over.any(over_box)) continue;
        over.subtract((below_has_skirt ? rim : below).enclosed(over, over_box), over_box);
        if (!over.any(over_box)) continue;
        for (auto& comp : regions(over, kJoin)) found.push_back(layers::make_region(std::move(comp), n, layer.z));
    }
}

// Detection runs on at most this many threads.
constexpr std::size_t kMaxThreads = 4;
// Fewer segments a thread (the layers' and those beneath) cost more to
// start than they save.
constexpr std::size_t kMinSegmentsPerThread = 20000;

// Ranges a thread: one that finishes early (its layers were light, or the
// machine busy) takes the next range, so the threads end close together.
constexpr std::size_t kRangesPerThread = 4;

// find_regions_in over the whole stack, in ranges of about equal work taken
// in turn by up to kMaxThreads threads, joined in layer order: the result
// does not depend on the split.
std::vector<Region> find_regions(const layers::LayerStack& stack, const Settings& s, const layers::BitGrid& proto) {
    const int n_layers = static_cast<int>(stack.layers.size());
    std::vector<std::size_t> work(n_layers + 1, 0);
    for (int n = 0; n < n_layers; ++n) {
        const layers::Layer& layer = stack.layers[n];
        std::size_t w = layer.segments.size();
        for (int k : layer.beneath) w += stack.layers[k].segments.size();
        work[n + 1] = work[n] + w;
    }
    const std::size_t threads = std::min({std::max<std::size_t>(1, std::thread::hardware_concurrency()), kMaxThreads,
                                          std::max<std::size_t>(1, work[n_layers] / kMinSegmentsPerThread)});
    const std::size_t ranges = threads == 1 ? 1 : threads * kRangesPerThread;
    std::vector<int> bounds{0};
    for (std::size_t t = 1; t < ranges; ++t)
        bounds.push_back(static_cast<int>(std::lower_bound(work.begin(), work.end(), work[n_layers] * t / ranges) - work.begin()));
    bounds.push_back(n_layers);
    std::vector<std::vector<Region>> parts(ranges);
    std::vector<std::exception_ptr> errors(ranges);
    std::atomic<std::size_t> next{0};
    auto run = [&] {
        for (std::size_t t = next++; t < ranges; t = next++) {
            try {
                find_regions_in(stack, s, proto, bounds[t], bounds[t + 1], parts[t]);
            } catch (...) {
                errors[t] = std::current_exception();
            }
        }
    };
    std::vector<std::thread> pool;
    for (std::size_t t = 1; t < threads; ++t) pool.emplace_back(run);
    run();
    for (std::thread& th : pool) th.join();
    for (const std::exception_ptr& e : errors)
        if (e) std::rethrow_exception(e);
    std::vector<Region> found = std::move(parts[0]);
    for (std::size_t t = 1; t < ranges; ++t)
        for (Region& r : parts[t]) found.push_back(std::move(r));
    return found;
}

}  // namespace

Overhangs find_overhangs(const layers::LayerStack& stack, const Settings& s) {
    const layers::BitGrid proto = layers::make_grid(stack, s.resolution, 2.0);
    return overhangs_of(find_regions(stack, s, proto), proto, s);
}

Overhangs overhangs_of(const std::vector<Region>& found, const layers::BitGrid& proto, const Settings& s) {
    Overhangs out;
    // Drop specks: lone regions smaller than the minimum area. Judged over
    // the chain of regions that continue one another from layer to layer,
    // not per layer: a steep slope overhangs by a sliver on every layer;
    // each sliver is tiny but together they are a real overhang.
    const std::vector<char> kept = kept_regions(found, proto, s.layer_height, s.min_overhang_area);
    const double cell_area = proto.cell_area();
    for (std::size_t k = 0; k < found.size(); ++k) {
        if (!kept[k]) continue;
        const Region& r = found[k];
        if (out.layers.empty() || out.layers.back().layer != r.layer) {
            OverhangLayer ol;
            ol.layer = r.layer;
            ol.cells = proto.empty_like();
            out.layers.push_back(std::move(ol));
        }
        OverhangLayer& ol = out.layers.back();
        for (const Cell& c : r.cells) ol.cells.set(c.i, c.j);
        const double a = static_cast<double>(r.cells.size()) * cell_area;
        ol.area_mm2 += a;
        out.area_mm2 += a;
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
        // Largest regions first; a region's cells already within reach of an
        // earlier region's points need no point of their own (a sliver next
        // to a large overhang is held by the large one's points).
        auto comps = regions(g, kJoin);
        std::stable_sort(comps.begin(), comps.end(), [](const auto& a, const auto& b) { return a.size() > b.size(); });
        layers::BitGrid covered = comps.size() > 1 ? g.empty_like() : layers::BitGrid();
        for (auto& comp : comps) {
            if (!pts.empty()) {
                std::erase_if(comp, [&](const Cell& c) { return covered.get(c.i, c.j); });
                if (comp.empty()) continue;
            }
            std::vector<SupportPoint> some = cover_region(g, comp, s.point_spacing, s.point_radius, z, ol.layer);
            if (covered.width() > 0)
                for (const SupportPoint& p : some) covered.draw_disc(p.x, p.y, s.point_radius - 1e-6);
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
