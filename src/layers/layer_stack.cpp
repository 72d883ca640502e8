#include "layers/layer_stack.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "gcode/error.hpp"

namespace scaffold::layers {

double width_from_e(double e_mm, double length_mm, double layer_height, double filament_diameter) {
    if (length_mm <= 0 || layer_height <= 0) return 0;
    double area = e_mm * std::numbers::pi * filament_diameter * filament_diameter / 4 / length_mm;
    // area = (w - h) * h + pi * h^2 / 4  (rectangle with semicircular sides)
    return area / layer_height + layer_height * (1 - std::numbers::pi / 4);
}

namespace {


bool extrudes(const gcode::Move& m) { return m.kind == gcode::MoveKind::Extrude; }

// Per layer, the last layer comment after the layer before's first
// extrusion and at or before its own first; null where it has none. Not
// its last: beads may follow the next layer's comment at this layer's
// height (a post-processor's after an object's label block that the slicer
// closes past the layer change, as Bambu Studio does).
std::vector<const gcode::LayerHint*> hints_of(const gcode::Program& program, const LayerStack& stack) {
    std::vector<const gcode::LayerHint*> out;
    out.reserve(stack.layers.size());
    std::size_t hint = 0;
    for (const Layer& L : stack.layers) {
        const gcode::LayerHint* h = nullptr;
        const std::uint32_t first = program.moves[L.segments.front().move].line;
        while (hint < program.layer_hints.size() && program.layer_hints[hint].line <= first)
            h = &program.layer_hints[hint++];
        out.push_back(h);
    }
    return out;
}

// A levelled file's layers carry the slicer's nominal heights: each layer's
// z is the previous one's plus the height its comment gives (;Z: where
// given), else its lowest extrusion's z.
void nominal_heights(const gcode::Program& program, const std::vector<const gcode::LayerHint*>& hints, LayerStack& stack) {
    double z = 0;
    for (std::size_t i = 0; i < stack.layers.size(); ++i) {
        Layer& L = stack.layers[i];
        double lowest = 1e300;
        for (const Segment& s : L.segments) lowest = std::min(lowest, static_cast<double>(program.moves[s.move].z1));
        const gcode::LayerHint* h = hints[i];
        if (h && h->z > 0) z = h->z;
        else if (h && h->height > 0) z += h->height;
        else z = lowest;
        L.z = z;
    }
}

// The height the slicer states for each layer (;HEIGHT:, ;LAYER_HEIGHT:,
// KISSlicer's z_thickness=): the last one given at or before the layer.
void stated_heights(const std::vector<const gcode::LayerHint*>& hints, LayerStack& stack) {
    double h = 0;
    for (std::size_t i = 0; i < stack.layers.size(); ++i) {
        if (hints[i]) h = hints[i]->height;
        stack.layers[i].nominal_height = h > 0 ? h : 0;
    }
}

// The mesh from every extrusion's end: its Z less its layer's nominal z,
// averaged per cell; empty cells take their nearest filled neighbour's
// value, ring by ring.
BedMesh bed_mesh(const gcode::Program& program, const LayerStack& stack) {
    BedMesh m;
    const Bounds& b = stack.bounds;
    if (b.empty()) return m;
    m.x0 = b.min_x;
    m.y0 = b.min_y;
    m.nx = std::max(1, static_cast<int>(std::ceil((b.max_x - b.min_x) / m.cell)));
    m.ny = std::max(1, static_cast<int>(std::ceil((b.max_y - b.min_y) / m.cell)));
    const std::size_t n = static_cast<std::size_t>(m.nx) * m.ny;
    std::vector<double> sum(n, 0.0);
    std::vector<int> count(n, 0);
    auto cell_of = [&](double x, double y) {
        const int i = std::clamp(static_cast<int>((x - m.x0) / m.cell), 0, m.nx - 1);
        const int j = std::clamp(static_cast<int>((y - m.y0) / m.cell), 0, m.ny - 1);
        return static_cast<std::size_t>(j) * m.nx + i;
    };
    // And the plane through them all (least squares, about the box's corner).
    double n_all = 0, sx = 0, sy = 0, sz = 0, sxx = 0, sxy = 0, syy = 0, sxz = 0, syz = 0;
    for (const Layer& L : stack.layers) {
        if (L.purge) continue;
        for (const Segment& s : L.segments) {
            const std::size_t c = cell_of(s.x1, s.y1);
            const double z = program.moves[s.move].z1 - L.z, x = s.x1 - m.x0, y = s.y1 - m.y0;
            sum[c] += z;
            ++count[c];
            n_all += 1;
            sx += x, sy += y, sz += z, sxx += x * x, sxy += x * y, syy += y * y, sxz += x * z, syz += y * z;
        }
    }
    if (n_all > 2) {
        const double cxx = sxx - sx * sx / n_all, cxy = sxy - sx * sy / n_all, cyy = syy - sy * sy / n_all;
        const double cxz = sxz - sx * sz / n_all, cyz = syz - sy * sz / n_all, det = cxx * cyy - cxy * cxy;
        // (Moves all along one line tell no tilt across it.)
        if (det > 1e-9 * std::max(1.0, cxx * cyy)) {
            m.tilt_x = (cxz * cyy - cyz * cxy) / det;
            m.tilt_y = (cyz * cxx - cxz * cxy) / det;
        }
    }
    m.offset.assign(n, 0.0);
    std::vector<char> filled(n, 0);
    std::size_t left = n;
    for (std::size_t c = 0; c < n; ++c)
        if (count[c]) { m.offset[c] = sum[c] / count[c]; filled[c] = 1; --left; }
    if (left == n) return BedMesh{};
    while (left > 0) {
        std::vector<char> next = filled;
        for (int j = 0; j < m.ny; ++j)
            for (int i = 0; i < m.nx; ++i) {
                const std::size_t c = static_cast<std::size_t>(j) * m.nx + i;
                if (filled[c]) continue;
                double s = 0;
                int k = 0;
                for (int dj = -1; dj <= 1; ++dj)
                    for (int di = -1; di <= 1; ++di) {
                        const int a = i + di, bb = j + dj;
                        if (a < 0 || bb < 0 || a >= m.nx || bb >= m.ny) continue;
                        const std::size_t d = static_cast<std::size_t>(bb) * m.nx + a;
                        if (filled[d]) { s += m.offset[d]; ++k; }
                    }
                if (k) { m.offset[c] = s / k; next[c] = 1; --left; }
            }
        filled.swap(next);
    }
    return m;
}

}  // namespace

double BedMesh::at(double x, double y) const {
    if (empty()) return 0;
    // Linear on past the outer cell centres by up to a cell (support beside
    // the model's edge), then on at the bed's overall tilt (a foot 3 mm out).
    const double ux = (x - x0) / cell - 0.5, uy = (y - y0) / cell - 0.5;
    const double fx = std::clamp(ux, -1.0, static_cast<double>(nx)), fy = std::clamp(uy, -1.0, static_cast<double>(ny));
    const int i = std::clamp(static_cast<int>(std::floor(fx)), 0, std::max(0, nx - 2)),
              j = std::clamp(static_cast<int>(std::floor(fy)), 0, std::max(0, ny - 2));
    const int i1 = std::min(i + 1, nx - 1), j1 = std::min(j + 1, ny - 1);
    const double tx = i1 > i ? fx - i : 0, ty = j1 > j ? fy - j : 0;
    auto v = [&](int a, int b) { return offset[static_cast<std::size_t>(b) * nx + a]; };
    return (v(i, j) * (1 - tx) + v(i1, j) * tx) * (1 - ty) + (v(i, j1) * (1 - tx) + v(i1, j1) * tx) * ty +
           (tilt_x * (ux - fx) + tilt_y * (uy - fy)) * cell;
}

// An extrusion within kRestartNear mm of the lowest after the print rose
// kRestartRise mm above it starts another object from the bed: more than
// bed levelling's offsets or one object's Z grid beside another's (KISSlicer).
constexpr double kRestartNear = 0.15, kRestartRise = 3.0;

ZMotion z_motion(const gcode::Program& program) {
    ZMotion z;
    for (const gcode::Move& m : program.moves) {
        if (!extrudes(m)) continue;
        ++z.extrusions;
        if (m.z1 > m.z0 + kZEps) {
            ++z.rising;
            z.rise += m.z1 - m.z0;
        } else if (m.z1 < m.z0 - kZEps) {
            ++z.falling;
        }
        if (m.z1 < z.z_min + kRestartNear && z.z_max > z.z_min + kRestartRise) z.restarts = true;
        z.z_min = std::min(z.z_min, static_cast<double>(m.z1));
        z.z_max = std::max(z.z_max, static_cast<double>(m.z1));
    }
    return z;
}

LayerStack build_layers(const gcode::Program& program, const Settings& settings) {
    LayerStack stack;
    const auto& moves = program.moves;
    // Bed levelling baked into the file (MatterControl): Z rises and falls
    // within a layer, so a layer is what lies between the slicer's layer
    // comments, not a distinct Z.
    const ZMotion zm = z_motion(program);
    stack.z_varies = program.layer_hints.size() >= 2 && zm.levelled();
    std::size_t hint = 0;               // next layer hint to consider
    std::uint32_t last_z_change = 0;    // line of the latest move that changed Z
    bool have_z_change = false;
    std::uint32_t prev_last_extrusion = 0;
    bool any = false;

    for (std::size_t k = 0; k < moves.size(); ++k) {
        const gcode::Move& m = moves[k];
        if (m.z1 != m.z0) { last_z_change = m.line; have_z_change = true; }
        if (!extrudes(m)) continue;
        double z = m.z1;
        bool starts = !any || std::abs(z - stack.layers.back().z) > kZEps;
        // Extrusions before the slicer's first layer comment are start code
        // (an intro line at the first layer's own height): a layer apart.
        if (any && hint == 0 && !program.layer_hints.empty() && program.layer_hints[0].line <= m.line &&
            program.layer_hints[0].line > prev_last_extrusion)
            starts = true;
        if (stack.z_varies && any) {
            starts = hint < program.layer_hints.size() && program.layer_hints[hint].line <= m.line &&
                     program.layer_hints[hint].line > prev_last_extrusion;
        }
        if (starts) {
            Layer layer;
            layer.z = z;
            // Boundary: the slicer's layer comment if one lies between the two
            // layers' extrusions, else the Z move that reached this height.
            std::uint32_t boundary = m.line;
            if (have_z_change && (!any || last_z_change > prev_last_extrusion)) boundary = std::min(boundary, last_z_change);
            while (hint < program.layer_hints.size() && program.layer_hints[hint].line <= m.line) {
                if (!any || program.layer_hints[hint].line > prev_last_extrusion)
                    boundary = std::min(boundary, program.layer_hints[hint].line);
                ++hint;
            }
            if (!any) boundary = std::min(boundary, m.line);
            layer.first_line = boundary;
            if (any) stack.layers.back().end_line = boundary;
            stack.layers.push_back(std::move(layer));
            any = true;
        }
        Layer& layer = stack.layers.back();
        Segment s;
        s.x0 = m.x0; s.y0 = m.y0; s.x1 = m.x1; s.y1 = m.y1;
        s.width = m.width;  // filled in below where the slicer gave none
        s.role = m.role;
        s.move = static_cast<std::uint32_t>(k);
        layer.segments.push_back(s);
        layer.last_extrusion_line = m.line;
        prev_last_extrusion = m.line;
    }
    if (!any) {
        // PrusaSlicer's Mach3 / Machinekit flavours extrude on the A axis.
        if (auto it = program.config.find("gcode_flavor");
            it != program.config.end() && (it->second == "mach3" || it->second == "machinekit"))
            throw Error(program.path, 0, "no extrusions on E: the " + it->second +
                                             " flavour extrudes on the A axis, which scaffold does not read; slice for a "
                                             "printer firmware (Marlin, Klipper, RepRapFirmware...)");
        throw Error(program.path, 0, "no extrusions found: this does not look like sliced G-code");
    }
    stack.layers.back().end_line = static_cast<std::uint32_t>(program.lines.size());
    const std::vector<const gcode::LayerHint*> hints = hints_of(program, stack);
    if (stack.z_varies) nominal_heights(program, hints, stack);
    stated_heights(hints, stack);

    // Heights and the layer beneath: by z, ignoring anything printed before
    // the first layer: the start code's purge and intro lines rest on the bed
    // and are no layers of their own (PrusaSlicer's intro line at Z 0.2 under
    // a 0.3 mm first layer; Bambu's purge at 0.2, then a line at 0.3, then
    // the first layer at 0.2). The first layer is the first one the slicer
    // marked as a layer, else the lowest.
    std::size_t lowest = 0;
    for (std::size_t i = 1; i < stack.layers.size(); ++i)
        if (stack.layers[i].z < stack.layers[lowest].z - kZEps) lowest = i;
    if (!program.layer_hints.empty()) {
        const std::uint32_t first_hint = program.layer_hints.front().line;
        for (std::size_t i = 0; i < stack.layers.size(); ++i)
            if (stack.layers[i].last_extrusion_line > first_hint) {
                lowest = i;
                break;
            }
    }
    double min_z = stack.layers[lowest].z;
    // The bounds in the same pass (from the lowest layer on, in order),
    // while each layer's segments are at hand.
    Bounds& b = stack.bounds;
    b.min_x = b.min_y = 1e300;
    b.max_x = b.max_y = -1e300;
    for (std::size_t i = 0; i < stack.layers.size(); ++i) {
        Layer& L = stack.layers[i];
        // A layer whose stated height reaches down to the bed is a first
        // layer too (an object sliced on a Z grid of its own, KISSlicer).
        L.on_bed = i <= lowest || L.z <= min_z + kZEps || (L.nominal_height > 0 && L.z - L.nominal_height < 0.01);
        L.purge = i < lowest;
        L.below = -1;
        if (!L.on_bed) {
            for (std::size_t j = i; j-- > lowest;) {
                if (stack.layers[j].z < L.z - kZEps) { L.below = static_cast<int>(j); break; }
            }
        }
        L.height = L.below >= 0 ? L.z - stack.layers[L.below].z : L.z;
        if (L.height <= kZEps) L.height = settings.layer_height;
        if (L.below >= 0) {
            const double window = std::max(settings.layer_height, L.nominal_height) + kZEps;
            // Back through the file until well below the window (layers come
            // in rising z but for interleaved objects).
            for (std::size_t j = i; j-- > lowest;) {
                const double dz = L.z - stack.layers[j].z;
                if (dz > window + 1.0) break;
                if (static_cast<int>(j) == L.below || (dz > kZEps && dz <= window)) L.beneath.push_back(static_cast<int>(j));
            }
        }
        for (Segment& s : L.segments) {
            L.slicer_support |= gcode::is_support(s.role);
            if (s.width > 0) continue;
            const gcode::Move& m = moves[s.move];
            double len = std::hypot(m.x1 - m.x0, m.y1 - m.y0);
            double w = width_from_e(m.e, len, L.height, settings.filament_diameter);
            s.width = static_cast<float>(std::clamp(w, 0.05 * settings.nozzle_diameter, 4.0 * settings.nozzle_diameter));
        }
        if (i < lowest) continue;
        for (const Segment& s : L.segments) {
            double r = s.width / 2;
            b.min_x = std::min({b.min_x, s.x0 - r, s.x1 - r});
            b.min_y = std::min({b.min_y, s.y0 - r, s.y1 - r});
            b.max_x = std::max({b.max_x, s.x0 + r, s.x1 + r});
            b.max_y = std::max({b.max_y, s.y0 + r, s.y1 + r});
        }
    }
    if (stack.z_varies) stack.mesh = bed_mesh(program, stack);
    return stack;
}

}  // namespace scaffold::layers
