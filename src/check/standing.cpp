#include "check/standing.hpp"

#include "gcode/format.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <numbers>

#include "check/footprint.hpp"
#include "layers/raster.hpp"
#include "layers/regions.hpp"

namespace scaffold::check {

namespace {

using layers::kZEps;

// METHOD's numbers for the rule.
constexpr double kPathLayers = 2.0;    // a parent lies on the nearest lower support layer within this many nominal layers
constexpr double kBedLayers = 3.0;     // with nothing under it this close to the first layer, an island stands on the bed
constexpr double kOnModelShare = 0.30; // of the cells not over support, over the model: a base on the model
constexpr double kSmallHoleMm2 = 4.0;  // holes of the model's footprint this small are filled
constexpr double kColumnShare = 0.25;  // a brace's column is at least this share of the strongest one's k
constexpr double kBraceLineDeg = 60;   // two of its columns' lines at least this far apart
// Where the model is drawn for the base test: around the layer's support,
// far enough that a hole of kSmallHoleMm2 under it lies inside (a round one
// is 2.3 mm across); a thinner sliver reaching past it counts as open.
constexpr double kModelMargin = 4.0;
constexpr double kMinI = 1e-12;        // mm^4: a section of no area
constexpr double kSameSpot = 2.0;      // mm: weak islands this close are listed once
constexpr int kTravelNotes = 5;

using gcode::fixed;

// A cantilever's compliance as three running integrals over its height
// (of dz/EI, z dz/EI, z^2 dz/EI, z from z_ref): its compliance at height z
// is c0 + z^2 s0 - 2 z s1 + s2, O(1) per island whatever the path's length.
struct Path {
    double z_ref = 0;  // the path's base or brace node (keeps the sums small)
    double c0 = 0;     // a brace node's give, N/mm^-1
    double s0 = 0, s1 = 0, s2 = 0;
    double compliance(double z) const {
        const double h = z - z_ref;
        return c0 + h * h * s0 - 2 * h * s1 + s2;
    }
    // A slab of section EI from a to b: exact where EI is constant over it.
    void add(double a, double b, double ei) {
        a -= z_ref;
        b -= z_ref;
        s0 += (b - a) / ei;
        s1 += (b * b - a * a) / (2 * ei);
        s2 += (b * b * b - a * a * a) / (3 * ei);
    }
};

struct Island {
    std::size_t cells = 0;
    // Beads, each a thin rectangle at its own width: area, first and second
    // moments about the layer's reference point.
    double area = 0, sx = 0, sy = 0, sxx = 0, syy = 0, sxy = 0;
    double cx = 0, cy = 0, i_min = 0;  // centroid (mm), smaller principal moment (mm^4)
    double len_added = 0, len_original = 0, filament = 0;
    int from = -1;                 // the support layer below it stands on (index into the recent ones)
    std::vector<int> parents;      // the islands of that layer it overlaps
    std::size_t over_support = 0;  // its cells over them (one cell of slack)
    int children = 0;
    Path path;
    double k = 0;                  // at its top, N/mm
    bool floating = false;
    bool base = false;
    bool node = false;             // a brace node, or its sole continuation (the bar's second layer)
    int column = -1;
};

// One layer's islands, with a label per cell of the box around its support.
struct SupportLayer {
    int index = -1;
    double z = 0;
    int i0 = 0, j0 = 0, nx = 0, ny = 0;  // box in lattice cells
    std::vector<int> label;              // -1: no support
    std::vector<Island> islands;
    int at(int gi, int gj) const {
        const int i = gi - i0, j = gj - j0;
        if (i < 0 || j < 0 || i >= nx || j >= ny) return -1;
        return label[static_cast<std::size_t>(j) * nx + i];
    }
};

// Adds one bead (a segment of width w) to an island's moments, about (rx, ry).
void add_bead(Island& s, const layers::Segment& sg, double rx, double ry) {
    const double dx = sg.x1 - sg.x0, dy = sg.y1 - sg.y0, len = std::hypot(dx, dy), w = sg.width;
    if (len <= 0 || w <= 0) return;
    const double ux = dx / len, uy = dy / len, a = len * w;
    const double mx = (sg.x0 + sg.x1) / 2.0 - rx, my = (sg.y0 + sg.y1) / 2.0 - ry;
    // A rectangle's own moments: w len^3 / 12 along it, len w^3 / 12 across.
    const double along = w * len * len * len / 12, across = len * w * w * w / 12;
    s.area += a;
    s.sx += a * mx;
    s.sy += a * my;
    s.sxx += along * ux * ux + across * uy * uy + a * mx * mx;
    s.syy += along * uy * uy + across * ux * ux + a * my * my;
    s.sxy += (along - across) * ux * uy + a * mx * my;
}

// Centroid and smaller principal second moment from the sums.
void finish_section(Island& s, double rx, double ry) {
    if (s.area <= 0) return;
    const double cx = s.sx / s.area, cy = s.sy / s.area;
    const double a = s.sxx - s.area * cx * cx, b = s.syy - s.area * cy * cy, c = s.sxy - s.area * cx * cy;
    s.i_min = std::max(0.0, (a + b) / 2 - std::sqrt((a - b) * (a - b) / 4 + c * c));
    s.cx = cx + rx;
    s.cy = cy + ry;
}

// The weakest islands, one per spot: a column's layers are all weak near
// its top, so the weakest of those within kSameSpot of each other stands
// for them all.
void add_weak(std::vector<WeakIsland>& v, const WeakIsland& w, int keep) {
    WeakIsland best = w;
    std::size_t n = 0;
    for (const WeakIsland& e : v) {
        if (std::hypot(e.x - w.x, e.y - w.y) < kSameSpot) {
            if (e.k <= best.k) best = e;
            continue;
        }
        v[n++] = e;
    }
    v.resize(n);
    v.push_back(best);
    std::stable_sort(v.begin(), v.end(), [](const WeakIsland& a, const WeakIsland& b) { return a.k < b.k; });
    if (static_cast<int>(v.size()) > keep) v.resize(static_cast<std::size_t>(std::max(0, keep)));
}

// Cells on one lattice for every grid of the rule, so a cell of one layer's
// grid is the same place in the next one's.
struct Lattice {
    double ox = 0, oy = 0, cell = 0.1;
    int col(double x) const { return static_cast<int>(std::floor((x - ox) / cell)); }
    int row(double y) const { return static_cast<int>(std::floor((y - oy) / cell)); }
    layers::BitGrid grid(int i0, int j0, int nx, int ny) const {
        return layers::BitGrid(ox + i0 * cell, oy + j0 * cell, ox + (i0 + nx) * cell, oy + (j0 + ny) * cell, cell);
    }
};

// The beads of one layer's support printed so far, in 1 mm buckets over
// the layer's support box: the gap from a point to the nearest of them,
// measured exactly (a raster's cells blur a 0.2 mm clearance by a third).
class FreshBeads {
public:
    FreshBeads(const layers::Bounds& box, double reach)
        : x0_(box.min_x), y0_(box.min_y), reach_(reach),
          nx_(std::max(1, static_cast<int>(std::ceil((box.max_x - box.min_x) / kBucket)))),
          ny_(std::max(1, static_cast<int>(std::ceil((box.max_y - box.min_y) / kBucket)))),
          buckets_(static_cast<std::size_t>(nx_) * ny_) {}

    void add(const layers::Segment& sg) {
        const int i0 = bucket_x(std::min(sg.x0, sg.x1) - sg.width / 2), i1 = bucket_x(std::max(sg.x0, sg.x1) + sg.width / 2);
        const int j0 = bucket_y(std::min(sg.y0, sg.y1) - sg.width / 2), j1 = bucket_y(std::max(sg.y0, sg.y1) + sg.width / 2);
        for (int j = j0; j <= j1; ++j)
            for (int i = i0; i <= i1; ++i) buckets_[static_cast<std::size_t>(j) * nx_ + i].push_back(&sg);
        empty_ = false;
    }

    // Distance from (x, y) to the nearest bead's edge, or `reach_` when
    // none is nearer.
    double gap(double x, double y) const {
        double best = reach_;
        if (empty_) return best;
        const int i0 = bucket_x(x - reach_), i1 = bucket_x(x + reach_);
        const int j0 = bucket_y(y - reach_), j1 = bucket_y(y + reach_);
        for (int j = j0; j <= j1; ++j)
            for (int i = i0; i <= i1; ++i)
                for (const layers::Segment* sg : buckets_[static_cast<std::size_t>(j) * nx_ + i])
                    best = std::min(best, layers::segment_distance(x, y, *sg) - sg->width / 2);
        return best;
    }

private:
    static constexpr double kBucket = 1.0;
    int bucket_x(double x) const { return std::clamp(static_cast<int>(std::floor((x - x0_) / kBucket)), 0, nx_ - 1); }
    int bucket_y(double y) const { return std::clamp(static_cast<int>(std::floor((y - y0_) / kBucket)), 0, ny_ - 1); }
    double x0_, y0_, reach_;
    int nx_, ny_;
    std::vector<std::vector<const layers::Segment*>> buckets_;
    bool empty_ = true;
};

// Travels over one layer's fresh support (the box holds its beads), by
// METHOD's letter: support counts from when it is printed; a chain of
// travel moves between two extrusions counts once where, after leaving the
// support it may start from (more than the clearance away), it comes back
// within the clearance of fresh support low enough to touch it and then
// leaves it again (reaching the next bead is no crossing). Points along a
// travel are taken every kTravelStep, as splice's writer takes them.
// Each crossing found is also kept in `found` (with its side: true for the
// added support), to be judged against the layer's islands once known.
void count_travels(const gcode::Program& program, const layers::Layer& layer, const std::vector<SupportOwner>& owner,
                   const layers::Bounds& box, const StandingOptions& o, StandingReport& r,
                   std::vector<std::pair<TravelCrossing, bool>>& found) {
    constexpr double kTravelStep = 0.1;
    found.clear();
    double wmax = 0;
    for (const layers::Segment& sg : layer.segments)
        if (owner[sg.move] != SupportOwner::None) wmax = std::max(wmax, double(sg.width));
    const double reach = o.travel_clearance + wmax / 2 + kTravelStep;
    FreshBeads added(box, reach), original(box, reach);
    const double bx0 = box.min_x - reach, by0 = box.min_y - reach, bx1 = box.max_x + reach, by1 = box.max_y + reach;
    auto first = std::lower_bound(program.moves.begin(), program.moves.end(), layer.first_line,
                                  [](const gcode::Move& m, std::uint32_t line) { return m.line < line; });
    std::size_t p = 0;  // the layer's segments follow its moves in order
    bool left = false, pend_a = false, pend_o = false, done_a = false, done_o = false;
    TravelCrossing at;
    const double low_z = layer.z + o.travel_lift - 1e-9;
    auto confirm = [&] {
        if (pend_a && !done_a) {
            done_a = true;
            if (r.added.travels++ < kTravelNotes) r.added.first_travels.push_back(at);
            found.emplace_back(at, true);
        }
        if (pend_o && !done_o) {
            done_o = true;
            if (r.original.travels++ < kTravelNotes) r.original.first_travels.push_back(at);
            found.emplace_back(at, false);
        }
        pend_a = pend_o = false;
    };
    for (auto it = first; it != program.moves.end() && it->line < layer.end_line; ++it) {
        const gcode::Move& m = *it;
        const std::size_t mi = static_cast<std::size_t>(it - program.moves.begin());
        if (m.kind == gcode::MoveKind::Extrude) {
            left = pend_a = pend_o = done_a = done_o = false;  // a new chain after this bead
            while (p < layer.segments.size() && layer.segments[p].move < mi) ++p;
            if (p < layer.segments.size() && layer.segments[p].move == mi && owner[mi] != SupportOwner::None)
                (owner[mi] == SupportOwner::Added ? added : original).add(layer.segments[p]);
            continue;
        }
        if (m.kind != gcode::MoveKind::Travel) continue;  // retractions and wipes keep the chain
        const double dx = m.x1 - m.x0, dy = m.y1 - m.y0, len = std::hypot(dx, dy);
        if (len <= 0) continue;
        if (std::max(m.x0, m.x1) < bx0 || std::min(m.x0, m.x1) > bx1 || std::max(m.y0, m.y1) < by0 ||
            std::min(m.y0, m.y1) > by1) {
            left = true;  // all of it far from the support
            confirm();
            continue;
        }
        const int n = std::max(1, static_cast<int>(std::ceil(len / kTravelStep)));
        for (int i = 0; i <= n; ++i) {
            const double t = static_cast<double>(i) / n;
            const double x = m.x0 + dx * t, y = m.y0 + dy * t, z = m.z0 + (m.z1 - m.z0) * t;
            const bool a = added.gap(x, y) <= o.travel_clearance, b = original.gap(x, y) <= o.travel_clearance;
            if (!left) {
                left = !a && !b;
                continue;
            }
            if (a || b) {
                if (z < low_z) {
                    if (!pend_a && !pend_o) at = {m.line, layer.z, x, y};
                    pend_a = pend_a || a;
                    pend_o = pend_o || b;
                }
            } else if (pend_a || pend_o) {
                confirm();
            }
        }
    }
}

}  // namespace

StandingReport standing(const gcode::Program& program, const layers::LayerStack& stack,
                        const std::vector<SupportOwner>& owner, const Settings& settings, const StandingOptions& o) {
    StandingReport r;
    r.min_stiffness = o.min_stiffness;
    if (stack.layers.empty() || owner.size() != program.moves.size()) return r;
    const Lattice lattice{stack.bounds.min_x - 5, stack.bounds.min_y - 5, o.resolution};  // of every grid here
    const double cell = lattice.cell, ox = lattice.ox, oy = lattice.oy;
    auto gcol = [&](double x) { return lattice.col(x); };
    auto grow = [&](double y) { return lattice.row(y); };
    auto box_grid = [&](int i0, int j0, int nx, int ny) { return lattice.grid(i0, j0, nx, ny); };
    const double h_nom = settings.layer_height > 0 ? settings.layer_height : 0.2;
    double z_first = 0;
    for (const layers::Layer& l : stack.layers)
        if (!l.purge) { z_first = l.z; break; }
    const double e_mod = o.modulus;
    const double cos_brace = std::cos(kBraceLineDeg * std::numbers::pi / 180);

    std::vector<int> uf;  // columns: union-find over ids, for "columns that meet lower down are one"
    auto find = [&](int a) {
        while (uf[a] != a) a = uf[a] = uf[uf[a]];
        return a;
    };
    auto fresh = [&] {
        uf.push_back(static_cast<int>(uf.size()));
        return static_cast<int>(uf.size()) - 1;
    };
    auto side_of = [&](const Island& s) -> StandingSide& { return s.len_original > s.len_added ? r.original : r.added; };

    SupportLayer cur;
    std::vector<SupportLayer> recent;  // the support layers just below, oldest first
    std::vector<std::uint32_t> sup;  // the layer's support segments
    Footprint foot;
    foot.limit = static_cast<std::size_t>(std::floor(kSmallHoleMm2 / (cell * cell) + 1e-9));
    struct Group { int root; double k, area, x, y; };
    std::vector<Group> groups;
    std::vector<std::pair<TravelCrossing, bool>> crossings;  // the layer's travels over fresh support

    for (int L = 0; L < static_cast<int>(stack.layers.size()); ++L) {
        const layers::Layer& layer = stack.layers[L];
        if (layer.purge) continue;
        sup.clear();
        double x0 = 1e300, y0 = 1e300, x1 = -1e300, y1 = -1e300, wmax = 0;
        for (std::uint32_t k = 0; k < layer.segments.size(); ++k) {
            const layers::Segment& sg = layer.segments[k];
            if (owner[sg.move] == SupportOwner::None) continue;
            sup.push_back(k);
            x0 = std::min({x0, double(sg.x0), double(sg.x1)});
            y0 = std::min({y0, double(sg.y0), double(sg.y1)});
            x1 = std::max({x1, double(sg.x0), double(sg.x1)});
            y1 = std::max({y1, double(sg.y0), double(sg.y1)});
            wmax = std::max(wmax, double(sg.width));
        }
        if (sup.empty()) continue;

        count_travels(program, layer, owner, {x0 - wmax / 2, y0 - wmax / 2, x1 + wmax / 2, y1 + wmax / 2}, o, r, crossings);

        // Islands: the layer's support drawn on a grid around it.
        const double pad = wmax / 2 + 2 * cell;
        cur.index = L;
        cur.z = layer.z;
        cur.i0 = gcol(x0 - pad);
        cur.j0 = grow(y0 - pad);
        layers::BitGrid grid = box_grid(cur.i0, cur.j0, gcol(x1 + pad) - cur.i0 + 1, grow(y1 + pad) - cur.j0 + 1);
        cur.nx = grid.width();
        cur.ny = grid.height();
        for (std::uint32_t k : sup) {
            const layers::Segment& sg = layer.segments[k];
            grid.draw_segment(sg.x0, sg.y0, sg.x1, sg.y1, sg.width);
        }
        const std::vector<std::vector<layers::Cell>> comps = layers::components(grid);
        cur.label.assign(static_cast<std::size_t>(cur.nx) * cur.ny, -1);
        cur.islands.assign(comps.size(), Island{});
        for (std::size_t c = 0; c < comps.size(); ++c) {
            for (const layers::Cell& q : comps[c]) cur.label[static_cast<std::size_t>(q.j) * cur.nx + q.i] = static_cast<int>(c);
            cur.islands[c].cells = comps[c].size();
        }
        // Each bead's island: the cell of its middle, else one beside it or
        // further along (a bead thinner than a cell may miss its middle).
        const double rx = ox + cur.i0 * cell, ry = oy + cur.j0 * cell;
        for (std::uint32_t k : sup) {
            const layers::Segment& sg = layer.segments[k];
            int id = -1;
            for (int s = 0; s <= 8 && id < 0; ++s) {
                const double t = s == 0 ? 0.5 : (s - 1) / 7.0;
                const int gi = gcol(sg.x0 + (sg.x1 - sg.x0) * t), gj = grow(sg.y0 + (sg.y1 - sg.y0) * t);
                for (int dj = -1; dj <= 1 && id < 0; ++dj)
                    for (int di = -1; di <= 1 && id < 0; ++di) id = cur.at(gi + di, gj + dj);
            }
            if (id < 0) continue;
            Island& s = cur.islands[id];
            add_bead(s, sg, rx, ry);
            const double len = std::hypot(sg.x1 - sg.x0, sg.y1 - sg.y0);
            (owner[sg.move] == SupportOwner::Original ? s.len_original : s.len_added) += len;
            s.filament += program.moves[sg.move].e;
        }
        for (Island& s : cur.islands) finish_section(s, rx, ry);

        // Parents: the islands it overlaps (one cell of slack) on the nearest
        // lower layer that holds support under it, within two nominal
        // layers: a slicer's support has layer heights of its own beside
        // the model's (a column at 14.4 and 14.7 mm, interface at 14.6).
        const double hw = std::max(h_nom, layer.nominal_height);
        while (!recent.empty() && !(recent.front().z > layer.z - kPathLayers * hw - 1.0 && recent.front().z < layer.z + 1.0))
            recent.erase(recent.begin());  // too far below, or a sequential print's earlier object
        auto over_support = [&](const SupportLayer& below, int gi, int gj, std::vector<int>* into) {
            bool any = false;
            for (int dj = -1; dj <= 1; ++dj)
                for (int di = -1; di <= 1; ++di) {
                    const int p = below.at(gi + di, gj + dj);
                    if (p < 0) continue;
                    any = true;
                    if (into && std::find(into->begin(), into->end(), p) == into->end()) into->push_back(p);
                }
            return any;
        };
        for (std::size_t c = 0; c < comps.size(); ++c) {
            Island& s = cur.islands[c];
            for (int h = static_cast<int>(recent.size()) - 1; h >= 0 && s.parents.empty(); --h) {
                const SupportLayer& below = recent[h];
                if (!(layer.z > below.z + kZEps && layer.z - below.z <= kPathLayers * hw + 1e-3)) continue;
                s.over_support = 0;
                for (const layers::Cell& q : comps[c])
                    if (over_support(below, q.i + cur.i0, q.j + cur.j0, &s.parents)) ++s.over_support;
                if (!s.parents.empty()) s.from = h;
            }
            std::sort(s.parents.begin(), s.parents.end());
            for (int p : s.parents) ++recent[s.from].islands[p].children;
        }

        // The model's footprint below, drawn when an island may stand on it.
        bool foot_drawn = false;
        auto draw_foot = [&] {
            foot_drawn = true;
            const int margin = static_cast<int>(std::ceil(kModelMargin / cell));
            foot.i0 = cur.i0 - margin;
            foot.j0 = cur.j0 - margin;
            foot.grid = box_grid(foot.i0, foot.j0, cur.nx + 2 * margin, cur.ny + 2 * margin);
            foot.state.assign(static_cast<std::size_t>(foot.grid.width()) * foot.grid.height(), 0);
            const double fx0 = ox + foot.i0 * cell, fy0 = oy + foot.j0 * cell;
            const double fx1 = fx0 + foot.grid.width() * cell, fy1 = fy0 + foot.grid.height() * cell;
            // "The layer below", as the path reads it: the model within two
            // nominal layers (slicers leave a contact gap under support on
            // the model, as they do over it).
            for (int k = L - 1; k >= 0; --k) {
                const layers::Layer& b = stack.layers[k];
                if (b.z < layer.z - kPathLayers * hw - 1.0) break;
                if (b.z >= layer.z - kZEps || b.z < layer.z - kPathLayers * hw - 1e-3) continue;
                for (const layers::Segment& sg : b.segments) {
                    if (owner[sg.move] != SupportOwner::None || sg.role == gcode::Role::Skirt) continue;
                    const double h = sg.width / 2;
                    if (std::max(sg.x0, sg.x1) + h < fx0 || std::min(sg.x0, sg.x1) - h > fx1 ||
                        std::max(sg.y0, sg.y1) + h < fy0 || std::min(sg.y0, sg.y1) - h > fy1)
                        continue;
                    foot.grid.draw_segment(sg.x0, sg.y0, sg.x1, sg.y1, sg.width);
                }
            }
        };

        // Base, brace or path down, for every island (columns as they stood
        // on the layer below: this layer's joins come after).
        for (std::size_t c = 0; c < cur.islands.size(); ++c) {
            Island& s = cur.islands[c];
            const double ei = e_mod * std::max(s.i_min, kMinI);
            const bool parented = !s.parents.empty();
            const SupportLayer* below = parented ? &recent[s.from] : nullptr;
            const double a = parented ? below->z : layer.z - layer.height;
            bool bed = !parented && layer.z <= z_first + kBedLayers * h_nom + 1e-3;
            bool on_model = false;
            const std::size_t not_over = s.cells - s.over_support;
            if (!bed && not_over > 0) {
                if (!foot_drawn) draw_foot();
                std::size_t on = 0;
                for (const layers::Cell& q : comps[c]) {
                    const int gi = q.i + cur.i0, gj = q.j + cur.j0;
                    if (below && over_support(*below, gi, gj, nullptr)) continue;
                    if (foot.covers(gi, gj)) ++on;
                }
                on_model = static_cast<double>(on) >= kOnModelShare * static_cast<double>(not_over);
            }
            if (bed || on_model) {
                s.base = true;
                s.path = Path{};
                s.path.z_ref = layer.z - layer.height;
                s.path.add(s.path.z_ref, layer.z, ei);
                continue;
            }
            if (!parented) {
                s.floating = true;
                if (static_cast<double>(s.cells) * cell * cell >= o.min_island_mm2) ++side_of(s).floating;
                continue;
            }
            // A brace: three or more distinct columns, each at least a
            // quarter of the strongest, not all on one line.
            groups.clear();
            for (int p : s.parents) {
                const Island& q = below->islands[p];
                if (q.floating) continue;
                const int root = find(q.column);
                const double k = 1 / q.path.compliance(layer.z);
                auto g = std::find_if(groups.begin(), groups.end(), [&](const Group& x) { return x.root == root; });
                if (g == groups.end()) {
                    groups.push_back({root, k, 0, 0, 0});
                    g = groups.end() - 1;
                }
                g->k = std::max(g->k, k);
                g->area += q.area;
                g->x += q.area * q.cx;
                g->y += q.area * q.cy;
            }
            if (groups.empty()) {  // stands only on floating islands
                s.floating = true;
                continue;
            }
            double k_max = 0;
            for (const Group& g : groups) k_max = std::max(k_max, g.k);
            double k_sum = 0;
            int columns = 0;
            bool apart = false;
            std::vector<std::pair<double, double>> dirs;
            for (const Group& g : groups) {
                if (g.k < kColumnShare * k_max) continue;
                ++columns;
                k_sum += g.k;
                if (g.area <= 0) continue;
                double ux = g.x / g.area - s.cx, uy = g.y / g.area - s.cy, n = std::hypot(ux, uy);
                if (n < 1e-6) continue;
                ux /= n;
                uy /= n;
                for (const auto& [vx, vy] : dirs) apart = apart || std::abs(ux * vx + uy * vy) <= cos_brace + 1e-9;
                dirs.emplace_back(ux, uy);
            }
            if (columns >= 3 && apart) {
                s.node = true;
                s.path = Path{};
                s.path.z_ref = a;
                s.path.c0 = 1 / k_sum;
                s.path.add(a, layer.z, ei);
                ++side_of(s).braces;
                continue;
            }
            // Else the stiffest path down.
            int best = -1;
            double best_c = std::numeric_limits<double>::infinity();
            for (int p : s.parents) {
                const Island& q = below->islands[p];
                if (q.floating) continue;
                const double cp = q.path.compliance(layer.z);
                if (cp < best_c) { best_c = cp; best = p; }
            }
            s.path = below->islands[best].path;
            s.path.add(a, layer.z, ei);
        }
        // Columns: a base, a floating start or a brace node starts one;
        // islands standing on a brace node start their own (a tower tied
        // again higher up braces again), except the node's sole
        // continuation (a bar's second layer); joined columns are one.
        for (std::size_t c = 0; c < cur.islands.size(); ++c) {
            Island& s = cur.islands[c];
            if (s.base || s.node || s.parents.empty()) {
                s.column = fresh();
                continue;
            }
            const std::vector<Island>& below = recent[s.from].islands;
            const Island& p0 = below[s.parents[0]];
            if (s.parents.size() == 1 && p0.node && p0.children == 1 && 2 * s.cells >= p0.cells) {
                s.column = p0.column;
                s.node = true;
                continue;
            }
            bool on_node = false;
            for (int p : s.parents) on_node = on_node || below[p].node;
            s.column = on_node ? fresh() : find(p0.column);
            for (int p : s.parents)
                if (!below[p].node) uf[find(below[p].column)] = find(s.column);
        }

        // The rule, per island of at least the minimum area.
        for (Island& s : cur.islands) {
            const double k = s.k = s.floating ? 0.0 : 1 / s.path.compliance(layer.z);
            const double area_mm2 = static_cast<double>(s.cells) * cell * cell;
            if (area_mm2 < o.min_island_mm2) continue;
            StandingSide& side = side_of(s);
            ++side.islands;
            if (side.weakest_k < 0 || k < side.weakest_k) side.weakest_k = k;
            if (!s.floating && (side.weakest_standing_k < 0 || k < side.weakest_standing_k)) side.weakest_standing_k = k;
            if (k < o.min_stiffness) {
                ++side.under;
                side.under_filament_mm += s.filament;
            }
            add_weak(side.weakest, {L, layer.z, s.cx, s.cy, k, s.floating ? 0.0 : layer.z - s.path.z_ref, area_mm2, s.floating},
                     o.worst);
        }
        // A travel over weak support: the weakest island within its reach
        // (the clearance beyond a bead's half width) where it first came near.
        const int reach = static_cast<int>(std::ceil((o.travel_clearance + wmax / 2) / cell)) + 1;
        for (const auto& [t, added] : crossings) {
            const int gi = gcol(t.x), gj = grow(t.y);
            double k = std::numeric_limits<double>::infinity();
            for (int dj = -reach; dj <= reach; ++dj)
                for (int di = -reach; di <= reach; ++di)
                    if (const int id = cur.at(gi + di, gj + dj); id >= 0) k = std::min(k, cur.islands[id].k);
            if (k < o.min_stiffness) ++(added ? r.added : r.original).weak_travels;
        }
        recent.push_back(std::move(cur));
        cur = SupportLayer{};
    }
    return r;
}

void standing_failures(const StandingReport& r, std::vector<std::string>& failures) {
    // METHOD's travel rule, for the support added: no travel over it while
    // it is fresh (the slicers' own supports cross theirs by the thousand:
    // reported, not failed). A rule of its own, whatever --min-stiffness.
    if (r.added.travels > 0) {
        const TravelCrossing& t = r.added.first_travels.front();
        failures.push_back(std::to_string(r.added.travels) + " travels cross fresh support without a lift (the first at line " +
                           std::to_string(t.line + 1) + ", z " + fixed(t.z, 2) + " around (" + fixed(t.x, 1) + ", " +
                           fixed(t.y, 1) + "))");
    }
    if (!(r.min_stiffness > 0) || r.added.under == 0) return;
    std::string what = std::to_string(r.added.under) + " support islands under " + fixed(r.min_stiffness, 2) + " N/mm";
    if (!r.added.weakest.empty()) {
        const WeakIsland& w = r.added.weakest.front();
        what += w.floating ? " (" + std::string("floating at z ") + fixed(w.z, 2) + " around (" + fixed(w.x, 1) + ", " + fixed(w.y, 1) + ")"
                           : " (the weakest " + fixed(w.k, 3) + " N/mm at z " + fixed(w.z, 2) + " around (" + fixed(w.x, 1) +
                                 ", " + fixed(w.y, 1) + "), " + fixed(w.height, 2) + " mm above its base";
    }
    what += "; " + fixed(r.added.under_filament_mm, 1) + " mm of filament in them)";
    failures.push_back(what);
}

namespace {

std::string side_text(const StandingSide& s, const char* indent) {
    std::string o;
    for (const WeakIsland& w : s.weakest)
        o += std::string(indent) + "layer " + std::to_string(w.layer) + " z " + fixed(w.z, 2) + " around (" + fixed(w.x, 1) +
             ", " + fixed(w.y, 1) + "): " +
             (w.floating ? std::string("floating") : "k " + fixed(w.k, 3) + " N/mm, " + fixed(w.height, 2) + " mm above its base") +
             ", " + fixed(w.area_mm2, 2) + " mm^2\n";
    o += std::string(indent).substr(2) + "travels crossing fresh support: " + std::to_string(s.travels) + ", " +
         std::to_string(s.weak_travels) + " of them over islands under the minimum stiffness\n";
    for (const TravelCrossing& t : s.first_travels)
        o += std::string(indent) + "line " + std::to_string(t.line + 1) + ": z " + fixed(t.z, 2) + " near (" + fixed(t.x, 2) +
             ", " + fixed(t.y, 2) + ")\n";
    return o;
}

std::string side_summary(const StandingSide& s, double min_k) {
    return std::to_string(s.islands) + " islands, " + std::to_string(s.under) + " under " + fixed(min_k, 2) + " N/mm (" +
           fixed(s.under_filament_mm, 1) + " mm of filament), " + std::to_string(s.floating) + " floating, " +
           std::to_string(s.braces) + " braces" + (s.weakest_k >= 0 ? "; weakest " + fixed(s.weakest_k, 3) + " N/mm" : "") +
           (s.floating && s.weakest_standing_k >= 0 ? ", not floating " + fixed(s.weakest_standing_k, 3) + " N/mm" : "") + "\n";
}

std::string side_json(const StandingSide& s) {
    std::string o = "{\"islands\": " + std::to_string(s.islands) + ", \"under\": " + std::to_string(s.under) +
                    ", \"floating\": " + std::to_string(s.floating) + ", \"braces\": " + std::to_string(s.braces) +
                    ", \"under_filament_mm\": " + fixed(s.under_filament_mm, 2) + ", \"weakest_k\": " + fixed(s.weakest_k, 4) + ", \"weakest_standing_k\": " + fixed(s.weakest_standing_k, 4) +
                    ", \"weakest\": [";
    for (std::size_t i = 0; i < s.weakest.size(); ++i) {
        const WeakIsland& w = s.weakest[i];
        o += std::string(i ? ", " : "") + "{\"layer\": " + std::to_string(w.layer) + ", \"z\": " + fixed(w.z, 3) +
             ", \"x\": " + fixed(w.x, 2) + ", \"y\": " + fixed(w.y, 2) + ", \"k\": " + fixed(w.k, 4) +
             ", \"height\": " + fixed(w.height, 2) + ", \"area_mm2\": " + fixed(w.area_mm2, 3) +
             ", \"floating\": " + (w.floating ? "true" : "false") + "}";
    }
    o += "], \"travels\": " + std::to_string(s.travels) + ", \"weak_travels\": " + std::to_string(s.weak_travels) +
         ", \"first_travels\": [";
    for (std::size_t i = 0; i < s.first_travels.size(); ++i) {
        const TravelCrossing& t = s.first_travels[i];
        o += std::string(i ? ", " : "") + "{\"line\": " + std::to_string(t.line + 1) + ", \"z\": " + fixed(t.z, 3) +
             ", \"x\": " + fixed(t.x, 2) + ", \"y\": " + fixed(t.y, 2) + "}";
    }
    return o + "]}";
}

}  // namespace

std::string standing_text(const StandingReport& r) {
    std::string o = "  standing (k >= " + fixed(r.min_stiffness, 2) + " N/mm" +
                    (r.min_stiffness > 0 ? "" : ", reported only") + "): " + side_summary(r.added, r.min_stiffness);
    o += side_text(r.added, "    ");
    const StandingSide& s = r.original;
    if (s.islands || s.travels) {
        o += "  the original's own support, standing (not a failure): " + side_summary(s, r.min_stiffness);
        o += side_text(s, "    ");
    }
    return o;
}

std::string standing_json(const StandingReport& r) {
    return "{\"min_stiffness\": " + fixed(r.min_stiffness, 3) + ", \"added\": " + side_json(r.added) +
           ", \"original\": " + side_json(r.original) + "}";
}

}  // namespace scaffold::check
