#include "plan/pillars.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>

namespace scaffold::plan {

double column_radius_at(const Column& c, double z, const Settings& s) {
    double r = c.radius;
    if (c.top == Top::Contact && s.tip_length > 0) {
        double t = (c.z1 - z) / s.tip_length;  // 0 at the contact, 1 where the tip starts
        if (t < 1) r = s.tip_radius + (c.radius - s.tip_radius) * std::clamp(t, 0.0, 1.0);
    }
    if (c.base == Base::Bed && c.foot_radius > r && s.foot_height > 0 && z < s.foot_height) {
        double t = std::clamp(z / s.foot_height, 0.0, 1.0);
        r = std::max(r, c.foot_radius + (c.radius - c.foot_radius) * t);
    }
    return r;
}

namespace {

constexpr double kFootMinHeight = 3.0;  // report: feet only under pillars taller than 3 mm

// The contact (top two layers of a tip) may come this close to the model.
constexpr double kTipClearance = 0.2;

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

// Checks the column from its top layer down; fills base and z0 on success.
bool descend(Column& c, int top_layer, const layers::LayerStack& stack, const Obstacles& obs, const Settings& s) {
    const double slope = std::tan(s.overhang_angle_deg * std::numbers::pi / 180);
    bool first = true;
    for (int l = top_layer; l >= 0; l = stack.layers[l].below) {
        const layers::Layer& layer = stack.layers[l];
        double r = column_radius_at(c, layer.z, s);
        // Only the contact itself (the top two layers) may come close to the model.
        bool tip = c.top == Top::Contact && layer.z > c.z1 - 2 * s.layer_height - 1e-6;
        if (obs.disc_clear(l, c.x1, c.y1, r + (tip ? kTipClearance : s.xy_gap))) {
            first = false;
            continue;
        }
        // Stand on the model only where it holds the whole bottom loop (every
        // point of it within the self-supporting reach); model beside the
        // column, or under only part of it, is a collision: try elsewhere.
        if (first || !loop_held(obs, l, c.x1, c.y1, std::max(r - s.support_width / 2, 0.0),
                                stack.layers[top_layer].height * slope * 0.8))
            return false;
        c.base = Base::Model;
        c.z0 = layer.z;
        return true;
    }
    c.base = Base::Bed;
    c.z0 = 0;
    return true;
}

// Largest foot and raft that keep the gap on the first layers.
void fit_foot_and_raft(Column& c, const layers::LayerStack& stack, const Obstacles& obs, const Settings& s) {
    if (c.base != Base::Bed) return;
    if (c.z1 - c.z0 > kFootMinHeight) {
        for (double fr = s.foot_radius; fr > c.radius + 1e-9; fr -= 0.5) {
            c.foot_radius = fr;
            bool ok = true;
            for (int l = 0; l < static_cast<int>(stack.layers.size()) && ok; ++l) {
                double z = stack.layers[l].z;
                if (z >= s.foot_height || z > c.z1) continue;
                ok = obs.disc_clear(l, c.x0, c.y0, column_radius_at(c, z, s) + s.xy_gap);
            }
            if (ok) break;
            c.foot_radius = 0;
        }
    }
    for (double size = s.raft_size; size >= 2 * c.radius; size -= 1.0) {
        bool ok = true;
        for (int l = 0; l < static_cast<int>(stack.layers.size()) && ok; ++l)
            if (stack.layers[l].on_bed && stack.layers[l].z <= c.z1)
                ok = obs.disc_clear(l, c.x0, c.y0, size / std::numbers::sqrt2 + s.xy_gap);
        if (ok) {
            c.raft_size = size;
            return;
        }
    }
    c.raft_size = 0;
}

}  // namespace

std::optional<Column> drop_pillar(double x, double y, int overhang_layer, Top top, const layers::LayerStack& stack,
                                  const Obstacles& obs, const Settings& s) {
    int top_layer = stack.layers[overhang_layer].below;
    for (int k = 0; k < s.top_gap_layers && top_layer >= 0; ++k) top_layer = stack.layers[top_layer].below;
    if (top_layer < 0) return std::nullopt;
    Column c;
    c.top = top;
    c.z1 = stack.layers[top_layer].z;
    // Tall pillars wobble: keep height / diameter within the slenderness limit.
    c.radius = std::max(s.pillar_radius, c.z1 / (2 * s.slenderness));
    // The point itself first, then rings around it, in a fixed order.
    static constexpr std::array<double, 6> kRings{0.0, 0.5, 1.0, 1.5, 2.0, 2.5};
    for (double d : kRings) {
        int n = d == 0 ? 1 : 8;
        for (int k = 0; k < n; ++k) {
            double a = k * std::numbers::pi / 4;
            c.x0 = c.x1 = x + d * std::cos(a);
            c.y0 = c.y1 = y + d * std::sin(a);
            if (!descend(c, top_layer, stack, obs, s)) continue;
            if (c.base == Base::Model && s.buildplate_only) return std::nullopt;
            fit_foot_and_raft(c, stack, obs, s);
            return c;
        }
    }
    return std::nullopt;
}

Scaffold plan_pillars(const overhang::SupportPoints& points, const layers::LayerStack& stack,
                      const Obstacles& obstacles, const Settings& settings) {
    Scaffold out;
    for (std::size_t i = 0; i < points.points.size(); ++i) {
        const auto& p = points.points[i];
        auto c = drop_pillar(p.x, p.y, p.layer, Top::Contact, stack, obstacles, settings);
        if (!c) {
            out.dropped_points.push_back(static_cast<int>(i));
            continue;
        }
        c->point = static_cast<int>(i);
        out.columns.push_back(*c);
    }
    return out;
}

}  // namespace scaffold::plan
