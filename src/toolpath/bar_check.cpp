#include "toolpath/bar_check.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "layers/crossing.hpp"
#include "layers/raster.hpp"

namespace scaffold::toolpath {

namespace {

constexpr double kZEps = 1e-6;
constexpr double kDanglingEnd = 1.0;  // METHOD's rule (b)
constexpr double kMargin = 3.0;       // grid beyond the line: reach and the crossing walk

struct Sample {
    double x, y, s;
    bool held;
};

struct Bead {
    double x0, y0, x1, y1, width;
};

// Whether the line a -> b on a layer is held by `beads` beneath it.
bool line_held(const Point& a, const Point& b, const std::vector<Bead>& beads, double reach, double cell,
               double bridge_limit) {
    // On the validator's lattice (multiples of the cell from the origin, as
    // make_grid lays it): a bar grazing a loop is judged cell for cell alike.
    const double x0 = std::floor((std::min(a.x, b.x) - kMargin) / cell) * cell, x1 = std::max(a.x, b.x) + kMargin;
    const double y0 = std::floor((std::min(a.y, b.y) - kMargin) / cell) * cell, y1 = std::max(a.y, b.y) + kMargin;
    layers::BitGrid footprint(x0, y0, x1, y1, cell), held = footprint;
    for (const Bead& d : beads) {
        if (std::max(d.x0, d.x1) < x0 - reach || std::min(d.x0, d.x1) > x1 + reach ||
            std::max(d.y0, d.y1) < y0 - reach || std::min(d.y0, d.y1) > y1 + reach)
            continue;
        footprint.draw_segment(d.x0, d.y0, d.x1, d.y1, d.width);
        held.draw_segment(d.x0, d.y0, d.x1, d.y1, d.width + 2 * reach);
    }
    const double len = std::hypot(b.x - a.x, b.y - a.y);
    const int n = std::max(1, static_cast<int>(std::ceil(len / cell)));
    std::vector<Sample> p;
    p.reserve(n + 1);
    for (int i = 0; i <= n; ++i) {
        const double t = static_cast<double>(i) / n, x = a.x + (b.x - a.x) * t, y = a.y + (b.y - a.y) * t;
        p.push_back({x, y, len * t, held.get(held.col(x), held.row(y))});
    }
    for (std::size_t i = 0; i < p.size();) {
        if (p[i].held) { ++i; continue; }
        std::size_t j = i;
        while (j < p.size() && !p[j].held) ++j;
        const bool start_held = i > 0, end_held = j < p.size();
        bool ok = false;
        if (start_held && end_held)
            ok = p[j].s - p[i - 1].s <= bridge_limit && layers::run_crosses(footprint, p, i - 1, j);
        else if (start_held != end_held)
            ok = (start_held ? p[j - 1].s - p[i - 1].s : p[j].s - p[i].s) <= kDanglingEnd;
        if (!ok) return false;
        i = j;
    }
    return true;
}

}  // namespace

std::vector<std::size_t> unheld_bars(const plan::Scaffold& scaffold, const SupportPaths& paths,
                                     const layers::LayerStack& stack, const Settings& settings) {
    std::vector<std::size_t> out;
    if (scaffold.bridges.empty()) return out;
    const double slope = std::tan(settings.overhang_angle_deg * std::numbers::pi / 180);
    const double h_nom = settings.layer_height;
    std::vector<Bead> beads;
    for (std::size_t bi = 0; bi < scaffold.bridges.size(); ++bi) {
        const plan::Bridge& br = scaffold.bridges[bi];
        bool bad = false;
        for (const LayerPaths& lp : paths.layers) {
            const layers::Layer& layer = stack.layers[lp.layer];
            const double z = layer.z;
            if (z <= br.z + kZEps || z > br.z + kBridgeThickness + kZEps) continue;
            // The layer beneath as METHOD and the validator take it: the
            // model within one nominal layer, support within three.
            beads.clear();
            for (int k : layer.beneath)
                for (const layers::Segment& sg : stack.layers[k].segments)
                    beads.push_back({sg.x0, sg.y0, sg.x1, sg.y1, sg.width});
            for (const LayerPaths& under : paths.layers) {
                const double dz = z - stack.layers[under.layer].z;
                if (dz <= kZEps || dz > 3 * h_nom + kZEps) continue;
                for (const Path& path : under.paths)
                    for (std::size_t i = 1; i < path.points.size(); ++i)
                        beads.push_back({path.points[i - 1].x, path.points[i - 1].y, path.points[i].x, path.points[i].y,
                                         path.width});
            }
            const double reach = layer.height * slope + settings.resolution / 2;
            for (const std::vector<Point>& line : bar_lines(br, settings.support_width, settings.pillar_radius))
                if (!line_held(line.front(), line.back(), beads, reach, settings.resolution,
                               settings.marked_bridge_limit)) {
                    bad = true;
                    break;
                }
            if (bad) break;
        }
        if (bad) out.push_back(bi);
    }
    return out;
}

}  // namespace scaffold::toolpath
