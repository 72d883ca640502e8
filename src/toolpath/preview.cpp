#include "toolpath/preview.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

#include "plan/pillars.hpp"

namespace scaffold::toolpath {

namespace {

std::string f(double v) {
    char b[32];
    std::snprintf(b, sizeof b, "%.2f", v);
    return b;
}

const char* column_colour(const plan::Column& c) {
    switch (c.base) {
        case plan::Base::Bridge: return "#e08000";
        case plan::Base::Model: return "#2a9d8f";
        case plan::Base::Column: return "#3b82f6";
        default: return "#1d4ed8";
    }
}

// A bar that ties weak columns (METHOD's Standing rule) apart from one
// that carries points.
const char* bar_colour(const plan::Bridge& br) { return br.brace ? "#7b2cbf" : "#d62828"; }

}  // namespace

std::string preview_svg(const layers::LayerStack& stack, const plan::Scaffold& scaffold, const SupportPaths& paths,
                        const Settings& s) {
    const layers::Bounds& b = stack.bounds;
    // The view holds the model and the scaffold beside it (feet, rafts and
    // helper pillars reach past the model).
    layers::Bounds v = b;
    auto take = [&](double x, double y, double r) {
        v.min_x = std::min(v.min_x, x - r), v.max_x = std::max(v.max_x, x + r);
        v.min_y = std::min(v.min_y, y - r), v.max_y = std::max(v.max_y, y + r);
    };
    for (const auto& c : scaffold.columns) {
        const double r = std::max({plan::column_radius_at(c, c.z0, s), c.foot_radius, c.raft_size / 2 * 1.5});
        take(c.x0, c.y0, r);
        take(c.x1, c.y1, c.radius);
    }
    for (const auto& br : scaffold.bridges) take(br.x0, br.y0, 1), take(br.x1, br.y1, 1);
    double zmax = 0;
    for (const auto& l : stack.layers) zmax = std::max(zmax, l.z);
    const double scale = std::clamp(600.0 / std::max(v.max_x - v.min_x, 1.0), 2.0, 20.0);
    const double pad = 20, w = (v.max_x - v.min_x) * scale, hf = zmax * scale, ht = (v.max_y - v.min_y) * scale;
    const double W = w + 2 * pad, H = hf + ht + 4 * pad + 14;
    auto X = [&](double x) { return pad + (x - v.min_x) * scale; };
    auto Zf = [&](double z) { return pad + hf - z * scale; };               // front view, z up
    auto Yt = [&](double y) { return 3 * pad + hf + (v.max_y - y) * scale; };  // top view, y up
    std::string o;
    o += "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" + f(W) + "\" height=\"" + f(H) + "\" viewBox=\"0 0 " + f(W) +
         " " + f(H) + "\">\n<rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n";
    o += "<text x=\"" + f(pad) + "\" y=\"14\" font-family=\"sans-serif\" font-size=\"12\">front (X-Z)</text>\n";
    o += "<text x=\"" + f(pad) + "\" y=\"" + f(2 * pad + hf + 14) +
         "\" font-family=\"sans-serif\" font-size=\"12\">top (X-Y)</text>\n";
    // Front silhouette of the model: per layer, the X extent in 0.5 mm bins.
    o += "<g fill=\"#bbbbbb\">\n";
    const double bin = 0.5;
    int nb = static_cast<int>(std::ceil((b.max_x - b.min_x) / bin)) + 1;
    std::vector<char> cover(nb);
    for (const auto& l : stack.layers) {
        std::fill(cover.begin(), cover.end(), 0);
        for (const auto& sg : l.segments) {
            int i0 = static_cast<int>((std::min(sg.x0, sg.x1) - b.min_x) / bin);
            int i1 = static_cast<int>((std::max(sg.x0, sg.x1) - b.min_x) / bin);
            for (int i = std::max(0, i0); i <= std::min(nb - 1, i1); ++i) cover[i] = 1;
        }
        for (int i = 0; i < nb;) {
            if (!cover[i]) { ++i; continue; }
            int j = i;
            while (j < nb && cover[j]) ++j;
            o += "<rect x=\"" + f(X(b.min_x + i * bin)) + "\" y=\"" + f(Zf(l.z)) + "\" width=\"" + f((j - i) * bin * scale) +
                 "\" height=\"" + f(std::max(l.height * scale, 0.5)) + "\"/>\n";
            i = j;
        }
    }
    o += "</g>\n";
    // Front view of the columns: trapezoids following radius and lean.
    for (const auto& c : scaffold.columns) {
        std::string pts;
        std::vector<std::pair<double, double>> left, right;
        for (double z = c.z0; z <= c.z1 + 1e-9; z += std::max(0.2, (c.z1 - c.z0) / 40)) {
            double t = c.z1 > c.z0 ? (z - c.z0) / (c.z1 - c.z0) : 1;
            double x = c.x0 + (c.x1 - c.x0) * t, r = plan::column_radius_at(c, z, s);
            left.emplace_back(x - r, z);
            right.emplace_back(x + r, z);
        }
        for (const auto& [x, z] : left) pts += f(X(x)) + "," + f(Zf(z)) + " ";
        for (auto it = right.rbegin(); it != right.rend(); ++it) pts += f(X(it->first)) + "," + f(Zf(it->second)) + " ";
        const char* colour = column_colour(c);
        o += "<polygon fill=\"" + std::string(colour) + "\" fill-opacity=\"0.8\" points=\"" + pts + "\"/>\n";
    }
    for (const auto& br : scaffold.bridges)
        o += "<line stroke=\"" + std::string(bar_colour(br)) + "\" stroke-width=\"" + f(std::max(0.4 * scale, 1.0)) + "\" x1=\"" + f(X(br.x0)) +
             "\" y1=\"" + f(Zf(br.z)) + "\" x2=\"" + f(X(br.x1)) + "\" y2=\"" + f(Zf(br.z)) + "\"/>\n";
    // Top view: model outline of every 10th layer, then every support path once.
    o += "<g fill=\"none\" stroke=\"#bbbbbb\" stroke-width=\"0.5\">\n";
    for (std::size_t li = 0; li < stack.layers.size(); li += 10)
        for (const auto& sg : stack.layers[li].segments)
            if (sg.role == gcode::Role::ExternalPerimeter || sg.role == gcode::Role::Unknown)
                o += "<line x1=\"" + f(X(sg.x0)) + "\" y1=\"" + f(Yt(sg.y0)) + "\" x2=\"" + f(X(sg.x1)) + "\" y2=\"" +
                     f(Yt(sg.y1)) + "\"/>\n";
    o += "</g>\n";
    for (const auto& c : scaffold.columns) {
        const char* colour = column_colour(c);
        o += "<line stroke=\"" + std::string(colour) + "\" stroke-width=\"" + f(2 * c.radius * scale) +
             "\" stroke-linecap=\"round\" stroke-opacity=\"0.6\" x1=\"" + f(X(c.x0)) + "\" y1=\"" + f(Yt(c.y0)) +
             "\" x2=\"" + f(X(c.x1)) + "\" y2=\"" + f(Yt(c.y1)) + "\"/>\n";
    }
    for (const auto& br : scaffold.bridges)
        o += "<line stroke=\"" + std::string(bar_colour(br)) + "\" stroke-width=\"" + f(scale) + "\" x1=\"" + f(X(br.x0)) + "\" y1=\"" + f(Yt(br.y0)) +
             "\" x2=\"" + f(X(br.x1)) + "\" y2=\"" + f(Yt(br.y1)) + "\"/>\n";
    std::size_t n_paths = 0;
    for (const auto& lp : paths.layers) n_paths += lp.paths.size();
    o += "<text x=\"" + f(pad) + "\" y=\"" + f(H - 20) + "\" font-family=\"sans-serif\" font-size=\"11\">" +
         std::to_string(scaffold.columns.size()) + " columns, " + std::to_string(scaffold.bridges.size()) +
         " bridges, " + std::to_string(n_paths) + " support paths.</text>\n";
    o += "<text x=\"" + f(pad) + "\" y=\"" + f(H - 6) + "\" font-family=\"sans-serif\" font-size=\"11\">" +
         "Blue: pillar on the bed, teal: on the model, orange: from a bridge, red: bridge, purple: brace.</text>\n";
    o += "</svg>\n";
    return o;
}

}  // namespace scaffold::toolpath
