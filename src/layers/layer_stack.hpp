#pragma once
// Layers are the distinct Z heights of extruding moves, in file order.
// Each knows its line range, z, height and its extrusion segments with
// width and role. The slicer's layer comments only place the boundaries.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

#include "gcode/program.hpp"
#include "gcode/settings.hpp"

namespace scaffold::layers {

struct Bounds {
    double min_x = 0, min_y = 0, max_x = 0, max_y = 0;
    bool empty() const { return max_x < min_x || max_y < min_y; }
};

struct Segment {
    float x0 = 0, y0 = 0, x1 = 0, y1 = 0;
    float width = 0;           // mm, from ;WIDTH: or from E
    gcode::Role role = gcode::Role::Unknown;
    std::uint32_t move = 0;    // index into Program::moves
};

// (px, py) less the point of segment (x0, y0)-(x1, y1) nearest it: its
// length is segment_distance (a caller may compare it squared first).
inline void segment_offset(double px, double py, double x0, double y0, double x1, double y1, double& ox, double& oy) {
    const double dx = x1 - x0, dy = y1 - y0, l2 = dx * dx + dy * dy;
    const double t = l2 > 0 ? std::clamp(((px - x0) * dx + (py - y0) * dy) / l2, 0.0, 1.0) : 0.0;
    ox = px - (x0 + dx * t);
    oy = py - (y0 + dy * t);
}

// Distance from (px, py) to the segment (x0, y0) - (x1, y1).
inline double segment_distance(double px, double py, double x0, double y0, double x1, double y1) {
    double ox, oy;
    segment_offset(px, py, x0, y0, x1, y1, ox, oy);
    return std::hypot(ox, oy);
}

// Distance from (px, py) to the segment's centre line (its coordinates'
// differences taken in float, as they are stored).
inline double segment_distance(double px, double py, const Segment& s) {
    const double dx = s.x1 - s.x0, dy = s.y1 - s.y0, l2 = dx * dx + dy * dy;
    const double t = l2 > 0 ? std::clamp(((px - s.x0) * dx + (py - s.y0) * dy) / l2, 0.0, 1.0) : 0.0;
    return std::hypot(px - (s.x0 + dx * t), py - (s.y0 + dy * t));
}

// Least distance between segments (ax0, ay0)-(ax1, ay1) and
// (bx0, by0)-(bx1, by1): 0 where they cross.
inline double segments_distance(double ax0, double ay0, double ax1, double ay1, double bx0, double by0, double bx1,
                                double by1) {
    auto side = [](double ox, double oy, double px, double py, double qx, double qy) {
        return (px - ox) * (qy - oy) - (py - oy) * (qx - ox);
    };
    const double d1 = side(ax0, ay0, ax1, ay1, bx0, by0), d2 = side(ax0, ay0, ax1, ay1, bx1, by1);
    const double d3 = side(bx0, by0, bx1, by1, ax0, ay0), d4 = side(bx0, by0, bx1, by1, ax1, ay1);
    if (((d1 > 0) != (d2 > 0)) && ((d3 > 0) != (d4 > 0))) return 0;
    return std::min({segment_distance(ax0, ay0, bx0, by0, bx1, by1), segment_distance(ax1, ay1, bx0, by0, bx1, by1),
                     segment_distance(bx0, by0, ax0, ay0, ax1, ay1), segment_distance(bx1, by1, ax0, ay0, ax1, ay1)});
}

struct Layer {
    double z = 0;              // top of the layer (the nozzle height)
    double height = 0;         // z minus the z of the layer below
    std::uint32_t first_line = 0;   // first line belonging to the layer
    std::uint32_t end_line = 0;     // one past the last line of the layer
    std::uint32_t last_extrusion_line = 0;
    bool on_bed = false;       // rests on the bed (first layer, or a purge line)
    int below = -1;            // index of the layer beneath (nearest lower z), -1 = bed
    // Every layer whose material is "the layer beneath" (METHOD.md): within
    // one nominal layer height below (the slicer's for this layer where it
    // states one, else the print's), `below` always among them. Objects
    // sliced on Z grids of their own (KISSlicer) interleave their layers.
    std::vector<int> beneath;
    bool purge = false;        // printed before the first layer (a purge line): no support here
    double nominal_height = 0; // the slicer's stated height for this layer, 0 if none
    bool slicer_support = false;  // holds support the slicer printed (a file sliced with support on)
    std::vector<Segment> segments;
};

// How Z moves while extruding: a spiral vase rises and never falls, and
// all its rising adds up to the print's height; bed levelling baked into
// the file (Z following the bed's mesh) rises and falls, or rises over and
// over on a tilted bed, far more than the print is high.
struct ZMotion {
    std::size_t extrusions = 0, rising = 0, falling = 0;
    double rise = 0;                      // mm risen while extruding, summed
    double z_min = 1e300, z_max = -1e300;  // of the extrusions
    bool spiral() const {
        return rising > 200 && rising * 4 > extrusions && falling * 20 < rising && rise < 1.5 * (z_max - z_min) + 1;
    }
    bool levelled() const { return !spiral() && rising + falling > 50 && (rising + falling) * 20 > extrusions; }
    // Sequential printing (one object finished, then the next): extrusion
    // back at the lowest height after rising well above it.
    bool restarts = false;
};
ZMotion z_motion(const gcode::Program& program);

// Bed levelling baked into a file: the Z offset of the printed moves from
// their layer's nominal height, as a function of XY (the bed's mesh), on a
// coarse grid of cell averages. Support printed in such a file follows it.
struct BedMesh {
    double x0 = 0, y0 = 0, cell = 2.0;
    int nx = 0, ny = 0;
    std::vector<double> offset;  // nx * ny, every cell filled
    bool empty() const { return offset.empty(); }

    // The plane fitted to every move's offset: mm per mm along x and y.
    double tilt_x = 0, tilt_y = 0;
    // Bilinear between cell centres, linear on for a cell past the outer
    // ones (a tilted bed goes on tilting beside the model), then on at the
    // plane's tilt.
    double at(double x, double y) const;
};

struct LayerStack {
    std::vector<Layer> layers;  // in file order; z increases except for a purge
                                // line printed before the first layer (on_bed)
    Bounds bounds;              // XY of all extrusions (model and skirt)
    bool z_varies = false;      // Z changes within layers (bed levelling in the
                                // file): layers come from the slicer's comments
                                // and carry nominal heights
    BedMesh mesh;               // the levelling, where z_varies
};

// Layers nearer in z than this are one height.
inline constexpr double kZEps = 1e-4;

// Width of a bead from filament used, its length and layer height
// (rectangle with rounded ends, as Slic3r/PrusaSlicer model it).
double width_from_e(double e_mm, double length_mm, double layer_height, double filament_diameter);

// Throws scaffold::Error if the program has no extrusion at all.
LayerStack build_layers(const gcode::Program& program, const Settings& settings);

}  // namespace scaffold::layers
