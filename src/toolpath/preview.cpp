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

}  // namespace

std::string preview_svg(const layers::LayerStack& stack, const plan::Scaffold& scaffold, const SupportPaths& paths,
                        const Settings& s) {
    const layers::Bounds& b = stack.bounds;
    double zmax = 0;
    for (const auto& l : stack.layers) zmax = std::max(zmax, l.z);
    const double scale = std::clamp(600.0 / std::max(b.max_x - b.min_x, 1.0), 2.0, 20.0);
    const double pad = 20, w = (b.max_x - b.min_x) * scale, hf = zmax * scale, ht = (b.max_y - b.min_y) * scale;
    const double W = w + 2 * pad, H = hf + ht + 4 * pad;
    auto X = [&](double x) { return pad + (x - b.min_x) * scale; };
    auto Zf = [&](double z) { return pad + hf - z * scale; };               // front view, z up
    auto Yt = [&](double y) { return 3 * pad + hf + (b.max_y - y) * scale; };  // top view, y up
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
        const char* colour = c.base == plan::Base::Bridge ? "#e08000" : (c.base == plan::Base::Model ? "#2a9d8f" : "#1d4ed8");
        if (c.base == plan::Base::Column) colour = "#3b82f6";
        o += "<polygon fill=\"" + std::string(colour) + "\" fill-opacity=\"0.8\" points=\"" + pts + "\"/>\n";
    }
    for (const auto& br : scaffold.bridges)
        o += "<line stroke=\"#d62828\" stroke-width=\"" + f(std::max(0.4 * scale, 1.0)) + "\" x1=\"" + f(X(br.x0)) +
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
        const char* colour = c.base == plan::Base::Bridge ? "#e08000" : (c.base == plan::Base::Model ? "#2a9d8f" : "#1d4ed8");
        if (c.base == plan::Base::Column) colour = "#3b82f6";
        o += "<line stroke=\"" + std::string(colour) + "\" stroke-width=\"" + f(2 * c.radius * scale) +
             "\" stroke-linecap=\"round\" stroke-opacity=\"0.6\" x1=\"" + f(X(c.x0)) + "\" y1=\"" + f(Yt(c.y0)) +
             "\" x2=\"" + f(X(c.x1)) + "\" y2=\"" + f(Yt(c.y1)) + "\"/>\n";
    }
    for (const auto& br : scaffold.bridges)
        o += "<line stroke=\"#d62828\" stroke-width=\"" + f(scale) + "\" x1=\"" + f(X(br.x0)) + "\" y1=\"" + f(Yt(br.y0)) +
             "\" x2=\"" + f(X(br.x1)) + "\" y2=\"" + f(Yt(br.y1)) + "\"/>\n";
    std::size_t n_paths = 0;
    for (const auto& lp : paths.layers) n_paths += lp.paths.size();
    o += "<text x=\"" + f(pad) + "\" y=\"" + f(H - 6) + "\" font-family=\"sans-serif\" font-size=\"11\">" +
         std::to_string(scaffold.columns.size()) + " columns, " + std::to_string(scaffold.bridges.size()) +
         " bridges, " + std::to_string(n_paths) +
         " support paths. Blue: pillar on the bed, teal: on the model, orange: from a bridge, red: bridge.</text>\n";
    o += "</svg>\n";
    return o;
}

}  // namespace scaffold::toolpath
