#include "layers/copies.hpp"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <limits>
#include <thread>
#include <unordered_map>

#include "gcode/role.hpp"
#include "layers/objects.hpp"
#include "layers/raster.hpp"

namespace scaffold::layers {

namespace {

constexpr std::size_t kMaxObjects = 4096;  // more separate pieces than any plate: no plate of copies

void extend(Bounds& b, double x, double y, double r) {
    b.min_x = std::min(b.min_x, x - r);
    b.min_y = std::min(b.min_y, y - r);
    b.max_x = std::max(b.max_x, x + r);
    b.max_y = std::max(b.max_y, y + r);
}

Bounds empty_bounds() {
    const double inf = std::numeric_limits<double>::infinity();
    return {inf, inf, -inf, -inf};
}

bool meets(const Bounds& a, const Bounds& b) {
    return a.min_x <= b.max_x && b.min_x <= a.max_x && a.min_y <= b.max_y && b.min_y <= a.max_y;
}

Bounds grown(const Bounds& b, double d) { return {b.min_x - d, b.min_y - d, b.max_x + d, b.max_y + d}; }

struct Object {
    Bounds box = empty_bounds();
    double ax = std::numeric_limits<double>::infinity(), ay = ax;  // lowest endpoint x and y: where it is
    std::vector<std::vector<std::uint32_t>> beads;                   // per layer, by index in Layer::segments
};

// Whether b's beads are a's, moved (each object's beads by its own
// anchor), layer by layer: each of b's beads matched to one of a's with
// the same role and width and ends within kCopyTolerance, either way round
// (an infill line chained from the other side is the same bead). Looked up
// by midpoint in cells far wider than the tolerance, the neighbouring cells
// too, so no rounding can hide a match.
bool same_beads(const LayerStack& stack, const Object& a, const Object& b) {
    constexpr double kCell = 0.05;
    // mm²: E's last decimal (1e-5 mm of 1.75 mm filament, 2.4e-5 mm³) over
    // a 0.05 mm layer, with room to spare.
    constexpr double kWidthFromE = 1e-3;
    auto cell = [](double v) { return static_cast<long long>(std::floor(v / kCell)); };
    auto key = [](long long i, long long j) { return i * 1'000'003LL + j; };
    std::unordered_map<long long, std::vector<std::size_t>> at;
    std::vector<char> used;
    for (std::size_t l = 0; l < stack.layers.size(); ++l) {
        const std::vector<Segment>& segments = stack.layers[l].segments;
        const auto &sa = a.beads[l], &sb = b.beads[l];
        if (sa.size() != sb.size()) return false;
        if (sa.empty()) continue;
        at.clear();
        used.assign(sa.size(), 0);
        for (std::size_t i = 0; i < sa.size(); ++i) {
            const Segment& s = segments[sa[i]];
            at[key(cell((s.x0 + s.x1) / 2.0 - a.ax), cell((s.y0 + s.y1) / 2.0 - a.ay))].push_back(i);
        }
        for (std::uint32_t bead : sb) {
            const Segment* t = &segments[bead];
            const double x0 = t->x0 - b.ax, y0 = t->y0 - b.ay, x1 = t->x1 - b.ax, y1 = t->y1 - b.ay;
            const long long ci = cell((x0 + x1) / 2), cj = cell((y0 + y1) / 2);
            // A width worked out from E (no width comment) carries E's
            // rounding over the bead's length: loose on a short bead.
            const double width_tolerance = 0.005 + kWidthFromE / std::max(std::hypot(x1 - x0, y1 - y0), 1e-3);
            auto near = [](double p, double q) { return std::abs(p - q) <= kCopyTolerance; };
            bool found = false;
            for (long long di = -1; di <= 1 && !found; ++di)
                for (long long dj = -1; dj <= 1 && !found; ++dj) {
                    auto it = at.find(key(ci + di, cj + dj));
                    if (it == at.end()) continue;
                    for (std::size_t i : it->second) {
                        if (used[i]) continue;
                        const Segment& s = segments[sa[i]];
                        if (s.role != t->role || std::abs(s.width - t->width) > width_tolerance) continue;
                        const double u0 = s.x0 - a.ax, v0 = s.y0 - a.ay, u1 = s.x1 - a.ax, v1 = s.y1 - a.ay;
                        if ((near(u0, x0) && near(v0, y0) && near(u1, x1) && near(v1, y1)) ||
                            (near(u0, x1) && near(v0, y1) && near(u1, x0) && near(v1, y0))) {
                            used[i] = 1;
                            found = true;
                            break;
                        }
                    }
                }
            if (!found) return false;
        }
    }
    return true;
}

}  // namespace

std::optional<Copies> find_copies(const LayerStack& stack, std::string* why, int threads) {
    return find_copies(stack, ObjectMap(stack), why, threads);
}

std::optional<Copies> find_copies(const LayerStack& stack, const ObjectMap& map, std::string* why, int threads) {
    auto no = [why](std::string reason) -> std::optional<Copies> {
        if (why) *why = std::move(reason);
        return std::nullopt;
    };
    for (const Layer& layer : stack.layers)
        for (const Segment& s : layer.segments)
            if (model_bead(layer, s) && (gcode::is_support(s.role) || layer.slicer_support))
                return no("the file holds support of its own");
    // Objects: the pieces of the model's footprint over all layers.
    const auto count = static_cast<std::size_t>(map.count());
    if (count == 0) return no("no model");
    if (count < 2) return no("one object");
    if (count > kMaxObjects) return no(std::to_string(count) + " separate pieces");
    std::vector<Object> objects(count);
    for (Object& o : objects) o.beads.resize(stack.layers.size());
    for (std::size_t l = 0; l < stack.layers.size(); ++l)
        for (const Segment& s : stack.layers[l].segments) {
            if (!model_bead(stack.layers[l], s)) continue;
            const int p = map.at(s.x0, s.y0);
            if (p < 0) return no("a bead in no object");  // never: the bead's own cell is drawn
            Object& o = objects[static_cast<std::size_t>(p)];
            o.beads[l].push_back(static_cast<std::uint32_t>(&s - stack.layers[l].segments.data()));
            extend(o.box, s.x0, s.y0, s.width / 2);
            extend(o.box, s.x1, s.y1, s.width / 2);
            o.ax = std::min({o.ax, static_cast<double>(s.x0), static_cast<double>(s.x1)});
            o.ay = std::min({o.ay, static_cast<double>(s.y0), static_cast<double>(s.y1)});
        }
    // The first copy: lowest, then leftmost (to the micron, so no rounding decides).
    auto place = [](const Object& o) { return std::make_pair(std::lround(o.ay * 1000), std::lround(o.ax * 1000)); };
    std::vector<std::size_t> order(objects.size());
    for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
    std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return place(objects[a]) < place(objects[b]); });
    const Object& first = objects[order.front()];
    Copies out;
    out.prototype = first.box;
    out.beads = first.beads;
    // Each object against the first, on `threads` threads; past the lowest
    // that differs none is asked (that one is named, whatever the threads).
    std::atomic<std::size_t> next{1}, differs{order.size()};
    auto compare = [&] {
        for (std::size_t i; (i = next.fetch_add(1)) < order.size();) {
            if (i > differs.load()) break;
            if (same_beads(stack, first, objects[order[i]])) continue;
            for (std::size_t d = differs.load(); i < d && !differs.compare_exchange_weak(d, i);) {
            }
        }
    };
    {
        std::vector<std::jthread> helpers;
        for (int t = 1; t < std::min<int>(threads, static_cast<int>(order.size()) - 1); ++t) helpers.emplace_back(compare);
        compare();
    }
    if (differs.load() < order.size())
        return no("object " + std::to_string(differs.load() + 1) + " of " + std::to_string(objects.size()) +
                  " is no exact copy of the first");
    for (std::size_t k : order) out.offsets.push_back({objects[k].ax - first.ax, objects[k].ay - first.ay});
    return out;
}

namespace {

// The layers as they are, without their beads.
LayerStack bare(const LayerStack& stack, const Bounds& bounds) {
    LayerStack out;
    out.bounds = bounds;
    out.z_varies = stack.z_varies;
    out.mesh = stack.mesh;
    out.layers.reserve(stack.layers.size());
    for (const Layer& layer : stack.layers) {
        Layer l = layer;
        std::vector<Segment>().swap(l.segments);
        out.layers.push_back(std::move(l));
    }
    return out;
}

}  // namespace

LayerStack first_copy(const LayerStack& stack, const Copies& copies) {
    LayerStack out = bare(stack, copies.prototype);
    for (std::size_t l = 0; l < stack.layers.size(); ++l)
        for (std::uint32_t i : copies.beads[l]) out.layers[l].segments.push_back(stack.layers[l].segments[i]);
    return out;
}

LayerStack seen_from_every_copy(const LayerStack& stack, const Copies& copies, double margin) {
    const Bounds window = grown(copies.prototype, margin);
    // Where another copy stands as seen from one: every difference of two
    // offsets, once each (to the micron).
    std::vector<Offset> around;
    for (const Offset& a : copies.offsets)
        for (const Offset& b : copies.offsets) {
            const Offset d{a.dx - b.dx, a.dy - b.dy};
            const Bounds moved{copies.prototype.min_x + d.dx, copies.prototype.min_y + d.dy, copies.prototype.max_x + d.dx,
                               copies.prototype.max_y + d.dy};
            if (!meets(moved, window)) continue;
            const bool known = std::any_of(around.begin(), around.end(), [&](const Offset& e) {
                return std::lround(e.dx * 1000) == std::lround(d.dx * 1000) && std::lround(e.dy * 1000) == std::lround(d.dy * 1000);
            });
            if (!known) around.push_back(d);
        }
    LayerStack out = bare(stack, window);
    for (std::size_t l = 0; l < stack.layers.size(); ++l) {
        const Layer& layer = stack.layers[l];
        std::vector<Segment>& seen = out.layers[l].segments;
        auto add = [&](const Segment& s, double dx, double dy) {
            Segment m = s;
            m.x0 = static_cast<float>(s.x0 + dx);
            m.y0 = static_cast<float>(s.y0 + dy);
            m.x1 = static_cast<float>(s.x1 + dx);
            m.y1 = static_cast<float>(s.y1 + dy);
            const double r = m.width / 2;
            const Bounds box{std::min(m.x0, m.x1) - r, std::min(m.y0, m.y1) - r, std::max(m.x0, m.x1) + r,
                             std::max(m.y0, m.y1) + r};
            if (meets(box, window)) seen.push_back(m);
        };
        // The first copy's beads stand for every copy's.
        for (std::uint32_t i : copies.beads[l])
            for (const Offset& d : around) add(layer.segments[i], d.dx, d.dy);
        for (const Segment& s : layer.segments)
            if (!model_bead(layer, s))
                for (const Offset& o : copies.offsets) add(s, -o.dx, -o.dy);
        seen.shrink_to_fit();
    }
    return out;
}

}  // namespace scaffold::layers
