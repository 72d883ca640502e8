#include "gcode/settings.hpp"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <numbers>
#include <initializer_list>
#include <vector>

#include "gcode/error.hpp"

extern char** environ;

namespace scaffold {

namespace {

// Looks a setting up under the names the dialects use for it, last source
// winning: file config < environment < command line.
class Lookup {
public:
    Lookup(const gcode::Program& p, const SettingMap& env, const SettingMap& cli) : p_(p), env_(env), cli_(cli) {}

    const std::string* find(std::initializer_list<const char*> keys, std::string* origin = nullptr) const {
        for (const SettingMap* m : {&cli_, &env_, &p_.config}) {
            for (const char* k : keys) {
                auto it = m->find(k);
                if (it != m->end()) {
                    if (origin) *origin = m == &cli_ ? "command line" : (m == &env_ ? "environment" : "file");
                    return &it->second;
                }
            }
        }
        return nullptr;
    }

    // First number of a value ("0.4,0.4" -> 0.4; "60%" -> 60 with percent set).
    bool number(std::initializer_list<const char*> keys, double& out, bool* percent = nullptr) const {
        std::string origin;
        const std::string* v = find(keys, &origin);
        if (!v) return false;
        std::string_view s(*v);
        while (!s.empty() && (s.front() == ' ' || s.front() == '"' || s.front() == '[')) s.remove_prefix(1);
        if (s.empty() || s == "nil") return false;
        double d = 0;
        const char* b = s.data();
        if (*b == '+') ++b;
        auto [end, ec] = std::from_chars(b, s.data() + s.size(), d);
        if (ec != std::errc() || !std::isfinite(d))
            throw Error(p_.path, 0, "setting '" + std::string(*keys.begin()) + "' from the " + origin +
                                        " is not a number: '" + *v + "'");
        if (percent) *percent = end < s.data() + s.size() && *end == '%';
        out = d;
        return true;
    }

    bool flag(std::initializer_list<const char*> keys, bool& out) const {
        const std::string* v = find(keys);
        if (!v) return false;
        std::string s = *v;
        std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return std::tolower(c); });
        out = s == "1" || s == "true" || s == "yes" || s == "on";
        return true;
    }

    const std::string* text(std::initializer_list<const char*> keys) const { return find(keys); }

private:
    const gcode::Program& p_;
    const SettingMap& env_;
    const SettingMap& cli_;
};

std::string fixed3(double v) {
    char b[32];
    std::snprintf(b, sizeof b, "%.3g", v);
    return b;
}

void positive(const gcode::Program& p, const char* name, double v) {
    if (!(v > 0)) throw Error(p.path, 0, std::string("setting '") + name + "' must be positive");
}

// "0x0,250x0,250x210,0x210" -> bounds.
void bed_from_shape(const std::string& shape, Settings& s) {
    double minx = 1e9, miny = 1e9, maxx = -1e9, maxy = -1e9;
    std::size_t pos = 0;
    while (pos < shape.size()) {
        std::size_t comma = shape.find(',', pos);
        std::string pt = shape.substr(pos, comma == std::string::npos ? std::string::npos : comma - pos);
        std::size_t x = pt.find('x');
        double a = 0, b = 0;
        if (x != std::string::npos &&
            std::from_chars(pt.data(), pt.data() + x, a).ec == std::errc() &&
            std::from_chars(pt.data() + x + 1, pt.data() + pt.size(), b).ec == std::errc()) {
            minx = std::min(minx, a); maxx = std::max(maxx, a);
            miny = std::min(miny, b); maxy = std::max(maxy, b);
        }
        if (comma == std::string::npos) break;
        pos = comma + 1;
    }
    if (maxx > minx && maxy > miny) {
        s.bed_min_x = minx; s.bed_min_y = miny; s.bed_max_x = maxx; s.bed_max_y = maxy;
        s.bed_stated = true;
    }
}

// The most common retraction in the file, for dialects that do not say.
double observed_retraction(const gcode::Program& p) {
    std::vector<float> r;
    for (const auto& m : p.moves)
        if (m.kind == gcode::MoveKind::Retract && m.e < 0) r.push_back(-m.e);
    if (r.empty()) return 0;
    std::nth_element(r.begin(), r.begin() + r.size() / 2, r.end());
    return r[r.size() / 2];
}

// Filament cross-section (mm^2) that the file's own model lines imply: E
// per mm of a bead of known width and layer height, the median over lines
// of 1 mm or more above the first layer (bridges, whose beads are round,
// left out). Volumetric E (Cura's UltiGCode, M200) implies 1. 0 if the file
// has too few such lines.
double implied_filament_area(const gcode::Program& p, const Settings& s, double width) {
    const double h = s.layer_height;
    std::vector<double> area;
    const std::size_t stride = std::max<std::size_t>(1, p.moves.size() / 50000);
    for (std::size_t k = 0; k < p.moves.size(); k += stride) {
        const gcode::Move& m = p.moves[k];
        if (m.kind != gcode::MoveKind::Extrude || gcode::is_bridge(m.role) || gcode::is_support(m.role)) continue;
        if (m.z1 <= s.first_layer_height + h / 2 || m.e <= 0) continue;
        const double len = std::hypot(m.x1 - m.x0, m.y1 - m.y0);
        if (len < 1.0) continue;
        const double w = m.width > 0 ? m.width : width;
        area.push_back(((w - h) * h + std::numbers::pi * h * h / 4) * len / m.e);
    }
    if (area.size() < 20) return 0;
    std::nth_element(area.begin(), area.begin() + area.size() / 2, area.end());
    return area[area.size() / 2];
}

// Support extrusion never rests on a guessed filament diameter: the one
// stated is kept where the model's own lines agree with it (within the
// spread of widths and flow the slicers use); otherwise, or where none is
// stated (Cura hands its scripts no settings), the common diameter nearest
// to what the lines imply: 1.75, 2.85 or 3.0 mm, or volumetric E.
void check_filament(const gcode::Program& p, const Lookup& l, Settings& s) {
    s.spool_diameter = s.filament_diameter;
    double width = s.nozzle_diameter * 1.125;  // the slicers' usual automatic width
    double w = 0;
    bool pct = false;
    if (l.number({"perimeter_extrusion_width", "extrusion_width", "line_width", "wall_line_width_x", "wall_line_width",
                  "extruderWidth"}, w, &pct) && w > 0)
        width = pct ? s.nozzle_diameter * w / 100 : w;
    const double implied = implied_filament_area(p, s, width);
    if (implied <= 0) return;
    const bool stated = l.find({"filament_diameter", "material_diameter", "filamentDiameter", "filamentDiameters"}) != nullptr;
    const double stated_area = std::numbers::pi * s.filament_diameter * s.filament_diameter / 4;
    if (stated && implied / stated_area > 0.55 && implied / stated_area < 1.8) return;
    struct Choice { double diameter; const char* name; };
    const Choice choices[] = {{2 / std::sqrt(std::numbers::pi), "volumetric E (mm^3)"},
                              {1.75, "1.75 mm filament"}, {2.85, "2.85 mm filament"}, {3.0, "3.0 mm filament"}};
    const Choice* best = &choices[0];
    for (const Choice& c : choices) {
        auto miss = [&](const Choice& x) { return std::abs(std::log(implied / (std::numbers::pi * x.diameter * x.diameter / 4))); };
        if (miss(c) < miss(*best)) best = &c;
    }
    if (stated || std::abs(best->diameter - s.filament_diameter) > 1e-9)
        s.filament_note = "the model's own lines extrude " + fixed3(1 / implied) + " mm of E per mm^3 of bead, as " + best->name +
                          (stated ? " (the file states a " + fixed3(s.filament_diameter) + " mm diameter)" : " (no diameter stated)") +
                          ": support is extruded to match";
    if (best != &choices[0]) s.spool_diameter = best->diameter;  // volumetric: the stated one, or the default
    s.filament_diameter = best->diameter;
}

}  // namespace

SettingMap settings_from_environment() {
    SettingMap out;
    for (char** e = environ; e && *e; ++e) {
        std::string_view kv(*e);
        if (kv.substr(0, 7) != "SLIC3R_") continue;
        std::size_t eq = kv.find('=');
        if (eq == std::string_view::npos) continue;
        std::string key(kv.substr(7, eq - 7));
        std::transform(key.begin(), key.end(), key.begin(), [](unsigned char c) { return std::tolower(c); });
        out[key] = std::string(kv.substr(eq + 1));
    }
    return out;
}

Settings build_settings(const gcode::Program& program, const SettingMap& environment, const SettingMap& overrides) {
    Settings s;
    Lookup l(program, environment, overrides);
    l.number({"nozzle_diameter", "machine_nozzle_size", "extruderDiameter"}, s.nozzle_diameter);
    l.number({"filament_diameter", "material_diameter", "filamentDiameter", "filamentDiameters"}, s.filament_diameter);
    l.number({"layer_height", "layerHeight"}, s.layer_height);
    bool pct = false;
    double first = s.layer_height;
    if (l.number({"first_layer_height", "initial_layer_print_height", "layer_height_0"}, first, &pct))
        s.first_layer_height = pct ? s.layer_height * first / 100 : first;
    else if (l.number({"firstLayerHeightPercentage"}, first))
        s.first_layer_height = s.layer_height * first / 100;
    else
        s.first_layer_height = s.layer_height;
    l.flag({"use_relative_e_distances", "relative_extrusion"}, s.relative_e);
    l.flag({"use_firmware_retraction", "machine_firmware_retract"}, s.firmware_retraction);
    if (!l.number({"retract_length", "retraction_length", "retraction_amount", "extruderRetractionDistance"}, s.retract_length)) {
        double seen = observed_retraction(program);
        if (seen > 0) s.retract_length = seen;
    }
    l.number({"retract_speed", "retraction_speed", "retraction_retract_speed"}, s.retract_speed_mm_s);
    l.number({"deretract_speed", "retraction_prime_speed"}, s.deretract_speed_mm_s);
    bool hop = true;
    if (l.flag({"retraction_hop_enabled"}, hop) && !hop) s.retract_lift = 0;
    else l.number({"retract_lift", "z_hop", "retraction_hop"}, s.retract_lift);
    l.number({"retract_before_travel", "retraction_minimum_travel", "retraction_min_travel"}, s.retract_before_travel);
    l.number({"travel_speed", "speed_travel"}, s.travel_speed_mm_s);
    l.number({"support_material_speed", "support_speed", "speed_support"}, s.support_speed_mm_s);
    l.number({"bridge_speed", "speed_bridge", "bridge_skin_speed"}, s.bridge_speed_mm_s);
    double fl = 0;
    if (l.number({"first_layer_speed", "initial_layer_speed", "speed_layer_0"}, fl, &pct))
        s.first_layer_speed_mm_s = pct ? s.support_speed_mm_s * fl / 100 : fl;
    l.number({"bridge_fan_speed", "bridge_fan_speed_1", "overhang_fan_speed", "bridge_fan_speed_2"}, s.bridge_fan_percent);
    if (const std::string* shape = l.text({"bed_shape", "printable_area"})) bed_from_shape(*shape, s);
    double w = 0, d = 0;
    if (l.number({"machine_width"}, w) && l.number({"machine_depth"}, d)) {
        // Cura's delta and centred beds put the origin in the middle.
        bool centred = false;
        l.flag({"machine_center_is_zero"}, centred);
        s.bed_min_x = centred ? -w / 2 : 0;
        s.bed_min_y = centred ? -d / 2 : 0;
        s.bed_max_x = s.bed_min_x + w;
        s.bed_max_y = s.bed_min_y + d;
        s.bed_stated = true;
    }
    l.number({"temperature", "nozzle_temperature", "material_print_temperature"}, s.temperature);
    l.number({"first_layer_temperature", "nozzle_temperature_initial_layer", "material_print_temperature_layer_0"},
             s.first_layer_temperature);
    l.number({"bed_temperature", "hot_plate_temp", "material_bed_temperature"}, s.bed_temperature);
    l.flag({"spiral_vase", "spiral_mode", "magic_spiralize", "spiralVaseMode"}, s.spiral_vase);
    // Fuzzy skin: PrusaSlicer and OrcaSlicer say where ("none", "external",
    // "all"), Cura whether; each how far a wall's points may stray.
    bool fuzzy = false;
    if (const std::string* where = l.text({"fuzzy_skin"})) fuzzy = *where != "none" && *where != "disabled" && !where->empty();
    else l.flag({"magic_fuzzy_skin_enabled"}, fuzzy);
    if (fuzzy) {
        s.fuzzy_skin_mm = 0.3;
        l.number({"fuzzy_skin_thickness", "magic_fuzzy_skin_thickness"}, s.fuzzy_skin_mm);
    }
    if (!l.flag({"complete_objects"}, s.sequential_printing)) {
        if (const std::string* seq = l.text({"print_sequence"}))
            s.sequential_printing = *seq == "by object" || *seq == "one_at_a_time";
    }
    // Slic3r-family files may list a bridge limit; otherwise the issue default.
    l.number({"max_bridge_length", "bridge_max_length"}, s.slicer_max_bridge);
    if (s.slicer_max_bridge > 0) s.max_bridge = s.slicer_max_bridge;

    // Options of scaffold itself (command line only, keyed "--name" so they never meet a slicer key).
    l.number({"--resolution"}, s.resolution);
    l.number({"--overhang-angle"}, s.overhang_angle_deg);
    l.number({"--max-bridge"}, s.max_bridge);
    l.number({"--min-overhang-area"}, s.min_overhang_area);
    l.number({"--point-spacing"}, s.point_spacing);
    l.number({"--point-radius"}, s.point_radius);
    l.number({"--xy-gap"}, s.xy_gap);
    double tgl = s.top_gap_layers;
    if (l.number({"--top-gap-layers"}, tgl)) s.top_gap_layers = static_cast<int>(tgl);
    l.number({"--tip-length"}, s.tip_length);
    l.number({"--slenderness"}, s.slenderness);
    l.number({"--min-stiffness"}, s.min_stiffness);
    l.number({"--modulus"}, s.modulus);
    l.number({"--pillar-radius"}, s.pillar_radius);
    l.number({"--support-width"}, s.support_width);
    l.flag({"--buildplate-only"}, s.buildplate_only);
    l.number({"--bridge-min-length"}, s.bridge_min_length);
    l.number({"--bridge-max-length"}, s.bridge_max_length);
    l.number({"--bridge-min-drop"}, s.bridge_min_drop);
    l.number({"--bridge-max-offset"}, s.bridge_max_offset);
    l.number({"--bridge-height-step"}, s.bridge_height_step);
    if (const std::string* m = l.text({"--method"})) {
        if (*m == "scaffold") s.method = Method::Scaffold;
        else if (*m == "pillars") s.method = Method::Pillars;
        else if (*m == "none") s.method = Method::None;
        else throw Error("--method must be scaffold, pillars or none (got '" + *m + "')");
    }

    positive(program, "nozzle_diameter", s.nozzle_diameter);
    positive(program, "filament_diameter", s.filament_diameter);
    check_filament(program, l, s);
    positive(program, "layer_height", s.layer_height);
    positive(program, "first_layer_height", s.first_layer_height);
    positive(program, "resolution", s.resolution);
    if (s.resolution > 2) throw Error("--resolution must be at most 2 mm");
    if (!(s.overhang_angle_deg > 0 && s.overhang_angle_deg < 89)) throw Error("--overhang-angle must be between 0 and 89 degrees");
    positive(program, "point_spacing", s.point_spacing);
    positive(program, "point_radius", s.point_radius);
    if (s.xy_gap < 0) throw Error("--xy-gap must not be negative");
    if (!(s.min_stiffness >= 0)) throw Error("--min-stiffness must not be negative");
    if (!(s.modulus > 0)) throw Error("--modulus must be positive");
    s.source = gcode::dialect_name(program.dialect);
    return s;
}

}  // namespace scaffold
