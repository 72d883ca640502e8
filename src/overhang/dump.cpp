#include "overhang/dump.hpp"

#include <cstdio>
#include <filesystem>

#include "gcode/error.hpp"
#include "gcode/writer.hpp"

namespace scaffold::overhang {

namespace {

std::string f(double v, int d = 3) {
    char b[48];
    std::snprintf(b, sizeof b, "%.*f", d, v);
    return b;
}


}  // namespace

void write_points_json(const std::string& path, const SupportPoints& points) {
    std::string o = "{\"points\":[";
    for (std::size_t i = 0; i < points.points.size(); ++i) {
        const SupportPoint& p = points.points[i];
        o += (i ? ",\n  " : "\n  ");
        o += "{\"x\":" + f(p.x) + ",\"y\":" + f(p.y) + ",\"z\":" + f(p.z) + ",\"layer\":" + std::to_string(p.layer) + "}";
    }
    o += "],\n\"overhang_area_mm2\":" + f(points.overhang_area_mm2) + "}\n";
    gcode::write_text_file(path, o);
}

void write_layer_svgs(const std::string& dir, const Overhangs& overhangs, const SupportPoints& points,
                      const layers::LayerStack& stack, const Settings& s) {
    std::error_code ec;
    std::filesystem::create_directories(dir, ec);
    if (ec) throw Error(dir, 0, "cannot create the directory: " + ec.message());
    for (const OverhangLayer& ol : overhangs.layers) {
        const layers::BitGrid& g = ol.cells;
        const layers::Layer& layer = stack.layers[ol.layer];
        layers::BitGrid below(g.origin_x(), g.origin_y(), g.origin_x() + g.width() * g.cell(),
                              g.origin_y() + g.height() * g.cell(), g.cell());
        layers::BitGrid here = below;
        for (int k : layer.beneath) layers::draw_layer(below, stack.layers[k]);
        layers::draw_layer(here, layer);
        std::string o = "<svg xmlns=\"http://www.w3.org/2000/svg\" viewBox=\"0 0 " + std::to_string(g.width()) + " " +
                        std::to_string(g.height()) + "\" width=\"" + std::to_string(g.width() * 4) + "\" height=\"" +
                        std::to_string(g.height() * 4) + "\">\n<rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n";
        o += "<!-- layer " + std::to_string(ol.layer) + " z " + f(layer.z) + ": grey = layer below, blue = this layer, "
             "red = overhang, black = support points (circle: point radius) -->\n";
        o += layers::svg_cell_runs(below, "#b0b0b0");
        o += layers::svg_cell_runs(here, "#9ec5fe");
        o += layers::svg_cell_runs(g, "#d62828");
        for (const SupportPoint& p : points.points) {
            if (p.layer != ol.layer) continue;
            double cx = (p.x - g.origin_x()) / g.cell(), cy = g.height() - (p.y - g.origin_y()) / g.cell();
            o += "<circle cx=\"" + f(cx, 1) + "\" cy=\"" + f(cy, 1) + "\" r=\"" + f(4, 1) + "\" fill=\"black\"/>\n";
            o += "<circle cx=\"" + f(cx, 1) + "\" cy=\"" + f(cy, 1) + "\" r=\"" + f(s.point_radius / g.cell(), 1) +
                 "\" fill=\"none\" stroke=\"black\" stroke-width=\"1\"/>\n";
        }
        o += "</svg>\n";
        char name[32];
        std::snprintf(name, sizeof name, "/layer-%04d.svg", ol.layer);
        gcode::write_text_file(dir + name, o);
    }
}

}  // namespace scaffold::overhang
