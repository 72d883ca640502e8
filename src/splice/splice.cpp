#include "splice/splice.hpp"

#include <algorithm>
#include <atomic>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstdint>
#include <cstdlib>
#include <numbers>
#include <string>
#include <unordered_map>
#include <vector>

#include "gcode/blocks.hpp"
#include "gcode/format.hpp"
#include "gcode/lexer.hpp"
#include "gcode/machine.hpp"
#include "gcode/role.hpp"
#include "plan/workers.hpp"

namespace scaffold::splice {

double filament_for(double length, double width, double height, double filament_diameter) {
    double area = (width - height) * height + std::numbers::pi * height * height / 4;
    return length * area / (std::numbers::pi * filament_diameter * filament_diameter / 4);
}

namespace {

// Fixed decimals keep the output deterministic and compact (to_chars
// writes what printf's %.*f does, without its per-call locale and format
// parsing: a tenth of the splice's time).
void num(std::string& out, char axis, double v, int decimals) {
    char buf[352];  // " X", then up to 309 digits, the point and the decimals
    buf[0] = ' ';
    buf[1] = axis;
    const auto [end, ec] = std::to_chars(buf + 2, buf + sizeof buf, v, std::chars_format::fixed, decimals);
    int n = ec == std::errc{} ? static_cast<int>(end - buf) : 2;
    // Trim trailing zeros ("X10.500" -> "X10.5", "E1.00000" -> "E1").
    if (decimals > 0) {
        while (n > 3 && buf[n - 1] == '0') --n;
        if (buf[n - 1] == '.') --n;
    }
    if (std::string_view(buf + 2, n - 2) == "-0") { buf[2] = '0'; n = 3; }
    out.append(buf, n);
}

// How the file names the role of the beads that follow, so that viewers
// and the printer's host read the support as support and the slicer's beads
// after it as what they are: ";TYPE:Perimeter" (PrusaSlicer, Cura,
// OrcaSlicer 1), "; TYPE:FILL" (MatterControl), "; FEATURE: Outer wall"
// (Bambu Studio, OrcaSlicer 2), "; feature outer perimeter" (Simplify3D 4.1+,
// Kiri:Moto), "; 'Loop Path', ..." (KISSlicer). Each reads only its own.
class RoleWords {
public:
    explicit RoleWords(gcode::Dialect d) : dialect_(d) {}

    // Takes note of a line (trailing blanks cut off) if it names a role.
    void see(std::string_view line) {
        const std::size_t start = line.find_first_not_of(" \t");
        if (start == std::string_view::npos) return;
        const std::string_view t = line.substr(start);
        std::string_view name;
        if (t.starts_with(";TYPE:") || t.starts_with("; TYPE:") || t.starts_with("; FEATURE:") ||
            t.starts_with(";FEATURE:")) {
            name = t.substr(t.find(':') + 1);
            name.remove_prefix(std::min(name.size(), name.find_first_not_of(' ')));
        } else if (t.starts_with("; feature ")) {
            name = t.substr(10);
        } else if (gcode::Role r; t.starts_with("; '") && gcode::kisslicer_role(t.substr(2), r)) {
            name = "Path";
        } else {
            return;
        }
        last_.assign(line);
        prefix_ = t.starts_with("; '") ? std::string_view("; '") : t.substr(0, t.size() - name.size());
        upper_ = upper_ || (!name.empty() && std::none_of(name.begin(), name.end(), [](char c) { return std::islower(static_cast<unsigned char>(c)); }));
        walls_ = walls_ || name == "Outer wall" || name == "Inner wall" || name == "Sparse infill";
    }

    // The line that names the support.
    std::string support() const {
        if (last_.empty()) return std::string(";TYPE:") + name(dialect_ == gcode::Dialect::Cura, dialect_ == gcode::Dialect::OrcaSlicer);
        if (prefix_ == "; '") return "; 'Support (may Stack) Path'";
        if (prefix_.starts_with("; feature")) return std::string(prefix_) + "support";
        if (prefix_.find("FEATURE") != std::string::npos) return std::string(prefix_) + "Support";
        return std::string(prefix_) + name(upper_ || dialect_ == gcode::Dialect::Cura, walls_ || dialect_ == gcode::Dialect::OrcaSlicer);
    }

    // The line that gives the slicer's role back.
    std::string restore() const { return last_.empty() ? std::string(";TYPE:Unknown") : last_; }

private:
    // Cura's names are upper case; OrcaSlicer's (and Creality Print's) walls
    // are walls and its support "Support".
    static const char* name(bool upper, bool orca) { return upper ? "SUPPORT" : orca ? "Support" : "Support material"; }

    gcode::Dialect dialect_;
    std::string last_;     // the last line that named a role
    std::string prefix_;   // its words before the name
    bool upper_ = false;   // names seen in upper case (Cura, ideaMaker, MatterControl)
    bool walls_ = false;   // OrcaSlicer's names seen
};

// The acceleration the slicer planned extrusions with (PrusaSlicer's and
// its forks' config keys, the first of a "normal,silent" pair), else
// Marlin's common 1000 mm/s^2, as the checker's estimate assumes.
double planned_acceleration(const gcode::Program& p) {
    for (const char* key : {"default_acceleration", "machine_max_acceleration_extruding", "default_acceleration_print"}) {
        auto it = p.config.find(key);
        if (it == p.config.end()) continue;
        double a = std::strtod(it->second.c_str(), nullptr);
        if (a > 0) return a;
    }
    return 1000;
}

// Seconds for one straight move from rest to rest: a trapezoid, or a
// triangle when it is too short to reach its speed. Support paths turn
// often, so "from rest" is near what a printer's planner does.
double move_seconds(double d, double v, double accel) {
    if (d <= 0 || v <= 0) return 0;
    return d >= v * v / accel ? d / v + v / accel : 2 * std::sqrt(d / accel);
}

// Writes one layer's block, starting and ending in the saved state.
class BlockWriter {
public:
    BlockWriter(const gcode::MachineState& saved, const Settings& s, double z, double height, bool fw_retraction,
                std::string_view support_role, std::string_view restore_role, std::string_view restore_width,
                std::string_view restore_height, const layers::BedMesh* mesh, double accel)
        // Retract the way the slicer did at this point: filament pulled back
        // by E is given back by E, whatever else the file does elsewhere.
        : saved_(saved), s_(s), z_layer_(z), height_(height),
          fw_(saved.fw_retracted || (fw_retraction && saved.retracted_mm <= 1e-4)), support_role_(support_role),
          restore_role_(restore_role), restore_width_(restore_width), restore_height_(restore_height), mesh_(mesh),
          accel_(accel) {
        // Retract by what the slicer retracted, so its own unretract stays right.
        amount_ = saved.retracted_mm > 1e-4 ? saved.retracted_mm : s.retract_length;
        e_ = saved.e;
        x_ = saved.x;
        y_ = saved.y;
        z_ = saved.z;
        retracted_ = saved.retracted();
        fan_ = saved.fan;
    }

    std::string write(const std::vector<toolpath::Path>& paths) {
        out_ += "; scaffold: support for the layer at";
        num(out_, 'Z', z_layer_, 3);
        out_ += "\n";
        out_ += support_role_;
        out_ += "\n";
        const bool say_height = !restore_height_.empty() && std::abs(said_value(restore_height_) - height_) > 5e-4;
        if (say_height) say(restore_height_, height_);
        for (const toolpath::Path& p : paths) path(p);
        retract();
        travel(saved_.x, saved_.y, std::max(saved_.z, floor_z_));
        if (!saved_.retracted()) unretract();
        if (!saved_.relative_e() && std::abs(e_ - saved_.e) > 1e-9) {
            out_ += "G92";
            num(out_, 'E', saved_.e, 5);
            out_ += "\n";
        }
        if (saved_.feed_mm_per_min > 0) {
            out_ += "G1";
            num(out_, 'F', saved_.feed_mm_per_min, 0);
            out_ += "\n";
        }
        if (fan_changed_) out_ += saved_.fan > 0 ? "M106 S" + std::to_string(saved_.fan) + "\n" : std::string("M107\n");
        out_ += restore_role_;
        out_ += "\n";
        if (width_said_) {
            out_ += restore_width_;
            out_ += "\n";
        }
        if (say_height) {
            out_ += restore_height_;
            out_ += "\n";
        }
        out_ += "; scaffold: end\n";
        return std::move(out_);
    }

    // Never back below z after the block (a bond printed before the nozzle
    // rose to its layer: the slicer's next move to the layer rises from here).
    void stay_above(double z) { floor_z_ = z; }

    double filament() const { return filament_; }
    double length() const { return length_; }
    double seconds() const { return seconds_; }

private:
    void extrude_e(double de) {
        e_ += de;
        num(out_, 'E', saved_.relative_e() ? de : e_, 5);
    }

    void retract() {
        if (retracted_) return;
        if (fw_) out_ += "G10\n";
        else {
            out_ += "G1";
            extrude_e(-amount_);
            num(out_, 'F', s_.retract_speed_mm_s * 60, 0);
            out_ += "\n";
        }
        seconds_ += move_seconds(amount_, s_.retract_speed_mm_s, accel_);
        retracted_ = true;
    }

    void unretract() {
        if (!retracted_) return;
        if (fw_) out_ += "G11\n";
        else {
            double speed = s_.deretract_speed_mm_s > 0 ? s_.deretract_speed_mm_s : s_.retract_speed_mm_s;
            out_ += "G1";
            extrude_e(amount_);
            num(out_, 'F', speed * 60, 0);
            out_ += "\n";
        }
        seconds_ += move_seconds(amount_, s_.deretract_speed_mm_s > 0 ? s_.deretract_speed_mm_s : s_.retract_speed_mm_s,
                                 accel_);
        retracted_ = false;
    }

    // Long travels are lifted by the slicer's z-hop; otherwise the nozzle
    // rises before and descends after the XY move, never dragging down. A
    // travel that would pass over support this block printed (METHOD's
    // travel rule: within 0.2 mm of it, after leaving it) is lifted too: a
    // thin column just printed is not to be knocked by the nozzle.
    void travel(double x, double y, double z) {
        double d = std::hypot(x - x_, y - y_);
        const bool over_fresh = crosses_fresh(x, y);
        if (over_fresh) move_z(std::max(z_, z) + std::max(s_.retract_lift, kFreshLift));
        else if (s_.retract_lift > 0 && d > s_.retract_before_travel && retracted_) move_z(std::max(z_, z) + s_.retract_lift);
        else if (z > z_ + 1e-6) move_z(z);
        if (d > 1e-6) {
            out_ += "G1";
            num(out_, 'X', x, 3);
            num(out_, 'Y', y, 3);
            num(out_, 'F', s_.travel_speed_mm_s * 60, 0);
            out_ += "\n";
            seconds_ += move_seconds(d, s_.travel_speed_mm_s, accel_);
        }
        if (std::abs(z - z_) > 1e-6) move_z(z);
        x_ = x;
        y_ = y;
    }

    // Whether the straight travel from here to (x, y) comes back within
    // kFreshClearance of a bead this block printed after leaving them (it
    // leaves the bead it starts on freely: along a straight line the gap to
    // the loop it leaves only grows). With a margin both ways, as the
    // validator measures on its raster: left once more than kFreshLeft clear,
    // back once the gap falls again, to within clearance plus margin. Erring
    // this way costs a lift; the other way, a knocked column.
    bool crosses_fresh(double x, double y) const {
        if (printed_.empty()) return false;
        const double len = std::hypot(x - x_, y - y_);
        const int n = std::max(1, static_cast<int>(std::ceil(len / kFreshStep)));
        double widest = 0;
        // The samples, 0.1 mm apart, mostly share their cell with the last.
        std::uint64_t last_key = 0;
        const std::vector<std::uint32_t>* here = nullptr;
        for (int i = 0; i <= n; ++i) {
            const double t = static_cast<double>(i) / n, px = x_ + (x - x_) * t, py = y_ + (y - y_) * t;
            // Gaps of kGapCap or more decide nothing below (kGapCap is above
            // every threshold they are compared with), so only the beads in
            // the sample's cell are asked: a plate of copies prints thousands
            // of beads a layer and travels across the bed, and asking every
            // bead at every sample grew with the square of the plate.
            double gap = kGapCap;
            if (const std::uint64_t key = cell_key(cell_of(px), cell_of(py)); i == 0 || key != last_key) {
                const auto it = near_.find(key);
                here = it == near_.end() ? nullptr : &it->second;
                last_key = key;
            }
            if (here)
                for (std::uint32_t k : *here) {
                    const Bead& b = printed_[k];
                    // The exact distance only where the squared one (with
                    // room for rounding) says it may lower the gap.
                    const double reach = gap + b.width / 2 + 1e-6;
                    if (reach <= 0 || squared_distance_to_segment(px, py, b) > reach * reach) continue;
                    gap = std::min(gap, distance_to_segment(px, py, b) - b.width / 2);
                }
            widest = std::max(widest, gap);
            if (widest > kFreshLeft && gap <= kFreshClearance + kFreshMargin && gap < widest - kFreshFall) return true;
        }
        return false;
    }

    struct Bead {
        double x0, y0, x1, y1, width;
    };

    // Beads by the grid cells within kGapCap (and a margin for rounding) of
    // them: a sample whose gap to a bead is below kGapCap lies in one of its
    // cells. Looked up only, never iterated.
    static constexpr double kGapCap = 1.0;
    static constexpr double kCell = 2.0;
    static long cell_of(double v) { return static_cast<long>(std::floor(v / kCell)); }
    static std::uint64_t cell_key(long i, long j) {
        return (static_cast<std::uint64_t>(i) << 32) ^ static_cast<std::uint64_t>(static_cast<std::uint32_t>(j));
    }
    void add_bead(const Bead& b) {
        const auto k = static_cast<std::uint32_t>(printed_.size());
        printed_.push_back(b);
        const double r = kGapCap + b.width / 2 + 0.01;
        for (long i = cell_of(std::min(b.x0, b.x1) - r); i <= cell_of(std::max(b.x0, b.x1) + r); ++i)
            for (long j = cell_of(std::min(b.y0, b.y1) - r); j <= cell_of(std::max(b.y0, b.y1) + r); ++j)
                near_[cell_key(i, j)].push_back(k);
    }

    static double squared_distance_to_segment(double px, double py, const Bead& b) {
        const double dx = b.x1 - b.x0, dy = b.y1 - b.y0, l2 = dx * dx + dy * dy;
        const double t = std::clamp(l2 > 0 ? ((px - b.x0) * dx + (py - b.y0) * dy) / l2 : 0.0, 0.0, 1.0);
        const double ex = px - (b.x0 + dx * t), ey = py - (b.y0 + dy * t);
        return ex * ex + ey * ey;
    }

    static double distance_to_segment(double px, double py, const Bead& b) {
        const double dx = b.x1 - b.x0, dy = b.y1 - b.y0, l2 = dx * dx + dy * dy;
        double t = l2 > 0 ? ((px - b.x0) * dx + (py - b.y0) * dy) / l2 : 0;
        t = std::clamp(t, 0.0, 1.0);
        return std::hypot(px - (b.x0 + dx * t), py - (b.y0 + dy * t));
    }

    // METHOD's travel rule: 0.2 mm in XY, the nozzle at least 0.15 mm up.
    static constexpr double kFreshClearance = 0.2;
    static constexpr double kFreshLift = 0.2;
    static constexpr double kFreshStep = 0.1;
    // Margins for the file's rounded coordinates and the validator's own
    // points along the travel.
    static constexpr double kFreshLeft = 0.15;
    static constexpr double kFreshMargin = 0.05;
    static constexpr double kFreshFall = 1e-4;

    void move_z(double z) {
        out_ += "G1";
        num(out_, 'Z', z, 3);
        num(out_, 'F', s_.travel_speed_mm_s * 60, 0);
        out_ += "\n";
        seconds_ += move_seconds(std::abs(z - z_), s_.travel_speed_mm_s, accel_);
        z_ = z;
    }

    void path(const toolpath::Path& p) {
        if (p.points.size() < 2) return;
        const auto& a = p.points.front();
        double d = std::hypot(a.x - x_, a.y - y_);
        if (d > s_.retract_before_travel && p.retract) retract();
        travel(a.x, a.y, z_at(a.x, a.y));
        unretract();
        int bridge_fan = static_cast<int>(std::lround(2.55 * s_.bridge_fan_percent));
        if (p.bridge && fan_ != bridge_fan) {
            out_ += "M106 S" + std::to_string(bridge_fan) + "\n";
            fan_ = bridge_fan;
            fan_changed_ = true;
        }
        say_width(p.width);
        double feed = p.speed_mm_s * 60;
        bool first = true;
        for (std::size_t i = 1; i < p.points.size(); ++i) {
            const auto& b = p.points[i];
            double len = std::hypot(b.x - x_, b.y - y_);
            if (len < 1e-6) continue;
            double de = filament_for(len, p.width, height_, s_.filament_diameter);
            out_ += "G1";
            num(out_, 'X', b.x, 3);
            num(out_, 'Y', b.y, 3);
            if (mesh_) {
                z_ = z_at(b.x, b.y);
                num(out_, 'Z', z_, 3);
            }
            extrude_e(de);
            if (first) num(out_, 'F', feed, 0);
            out_ += "\n";
            first = false;
            filament_ += de;
            length_ += len;
            add_bead({x_, y_, b.x, b.y, p.width});
            seconds_ += move_seconds(len, p.speed_mm_s, accel_);
            x_ = b.x;
            y_ = b.y;
        }
    }

    // A file that says its beads' width and height (";WIDTH:0.45" and
    // ";HEIGHT:0.2", Bambu's "; LINE_WIDTH: 0.42" and "; LAYER_HEIGHT: 0.2")
    // is read by viewers and by scaffold-check with the last ones said: the
    // support's own are said in the same words as `like`, and the slicer's
    // given back after the block.
    void say(std::string_view like, double v) {
        const std::size_t colon = like.find(':');
        out_ += like.substr(0, colon + 1);
        if (colon + 1 < like.size() && like[colon + 1] == ' ') out_ += ' ';
        out_ += gcode::fixed(v, 3);
        out_ += "\n";
    }

    static double said_value(std::string_view line) {
        std::string_view v = line.substr(line.find(':') + 1);
        v.remove_prefix(std::min(v.size(), v.find_first_not_of(' ')));
        double d = 0;
        std::from_chars(v.data(), v.data() + v.size(), d);
        return d;
    }

    void say_width(double w) {
        if (restore_width_.empty() || (width_said_ && std::abs(w - said_width_) < 1e-9)) return;
        say(restore_width_, w);
        width_said_ = true;
        said_width_ = w;
    }

    // The layer's height where the nozzle is; with bed levelling baked into
    // the file, the model's Z follows the bed's mesh and the support with it.
    double z_at(double x, double y) const { return z_layer_ + (mesh_ ? mesh_->at(x, y) : 0.0); }

    const gcode::MachineState& saved_;
    const Settings& s_;
    double z_layer_, height_;  // the block's layer
    bool fw_;
    std::string_view support_role_;  // the line that names the support, and the one that gives the slicer's role back
    std::string_view restore_role_;
    std::string_view restore_width_;   // the slicer's last width comment line, or empty
    std::string_view restore_height_;  // the slicer's last height comment line, or empty
    bool width_said_ = false;
    double said_width_ = 0;
    const layers::BedMesh* mesh_;  // null without levelling in the file
    double accel_;                  // mm/s^2, for the time estimate
    double amount_ = 0, e_ = 0, x_ = 0, y_ = 0, z_ = 0;
    double floor_z_ = -1e300;
    bool retracted_ = false, fan_changed_ = false;
    int fan_ = 0;
    double filament_ = 0, length_ = 0, seconds_ = 0;
    std::vector<Bead> printed_;  // this block's beads, for the travel rule
    std::unordered_map<std::uint64_t, std::vector<std::uint32_t>> near_;  // bead indices by cell (add_bead)
    std::string out_;
};

// A comment's text after "; ", or empty for a line that is no comment.
std::string_view comment_text(std::string_view t) {
    const std::size_t semi = t.find_first_not_of(" \t");
    if (semi == std::string_view::npos || t[semi] != ';') return {};
    t.remove_prefix(semi + 1);
    t.remove_prefix(std::min(t.size(), t.find_first_not_of(' ')));
    return t;
}

// ";WIDTH:0.45" and ";HEIGHT:0.2" (PrusaSlicer, SuperSlicer), "; LINE_WIDTH:
// 0.42" and "; LAYER_HEIGHT: 0.2" (Bambu Studio, OrcaSlicer): the width and
// height the readers give the beads that follow.
bool is_width_comment(std::string_view t) {
    t = comment_text(t);
    return t.starts_with("WIDTH:") || t.starts_with("LINE_WIDTH:");
}
bool is_height_comment(std::string_view t) {
    t = comment_text(t);
    return t.starts_with("HEIGHT:") || t.starts_with("LAYER_HEIGHT:");
}

// Support is never spliced into an object's labelled block (cancelling
// the object in the printer would drop it, and with it the support another
// object stands on) or a tool change with its purge: gcode/blocks.hpp.
// +1 opens a block, -1 closes it, 0 neither.
int block_marker(std::string_view t) {
    const gcode::BlockMarker m = gcode::block_marker(t);
    return m.kind == gcode::BlockKind::None ? 0 : (m.opens ? 1 : -1);
}

// The line after the labelled block open at `at` closes, if nothing is
// extruded before it does (Bambu Studio closes the layer's last object
// after the next layer's comment and the object's wipe); 0 if not.
std::uint32_t closes_before_extruding(const gcode::Program& p, std::uint32_t at) {
    auto next = std::lower_bound(p.moves.begin(), p.moves.end(), at,
                                 [](const gcode::Move& m, std::uint32_t l) { return m.line < l; });
    while (next != p.moves.end() && next->kind != gcode::MoveKind::Extrude) ++next;
    const std::uint32_t limit = next == p.moves.end() ? static_cast<std::uint32_t>(p.lines.size()) : next->line;
    for (std::uint32_t l = at; l < limit; ++l) {
        const int m = block_marker(p.line_text(l));
        if (m > 0) return 0;
        if (m < 0) {
            // "; stop printing object" and then M625: after both.
            std::uint32_t end = l + 1;
            for (std::uint32_t k = end; k < limit; ++k) {
                const std::string_view t = p.line_text(k);
                if (block_marker(t) < 0) end = k + 1;
                else if (t.find_first_not_of(" \t\r") != std::string_view::npos) break;
            }
            return end;
        }
    }
    return 0;
}

// Where to insert a block meant for line `at`: after the labelled block
// open there if it closes before anything more is extruded, else before it.
// `open` is the line that opened the block open at `from` (the lines before
// `from` are behind us), or -1; it is carried to the returned line. A block
// that opened before `from` spans the layer change: the slicers seen never
// write one, and moving support past it would print it after the next
// layer, so it is split there (counted in `spanned`).
std::uint32_t outside_blocks(const gcode::Program& p, std::uint32_t from, std::uint32_t at, std::int64_t& open,
                             std::size_t& spanned) {
    for (std::uint32_t l = from; l < at && l < p.lines.size(); ++l) {
        int m = block_marker(p.line_text(l));
        if (m > 0 && open < 0) open = l;
        else if (m < 0) open = -1;
    }
    if (open < 0) return at;
    if (open >= static_cast<std::int64_t>(from)) {
        const std::uint32_t after = closes_before_extruding(p, at);
        const std::uint32_t before = static_cast<std::uint32_t>(open);
        open = -1;
        return after ? after : before;
    }
    ++spanned;
    return at;
}

// The line just past the move that brings the nozzle to `layer`'s height
// (a lift above it counts), from `from` with the machine in `st`; or the
// layer's first extrusion, should one come first.
std::uint32_t layer_reached(const gcode::Program& p, gcode::MachineState st, std::uint32_t from,
                            const layers::Layer& layer) {
    gcode::Command cmd;
    std::vector<gcode::Move> moves;
    for (std::uint32_t l = from; l < layer.end_line && l < p.lines.size(); ++l) {
        gcode::lex(p.line_text(l), cmd);
        if (cmd.letter == 0) continue;
        moves.clear();
        gcode::step(st, cmd, l, moves);
        if (l < layer.first_line) continue;
        for (const gcode::Move& m : moves)
            if (m.kind == gcode::MoveKind::Extrude) return l;
        if (st.z >= layer.z - layers::kZEps) return l + 1;
    }
    return layer.first_line;
}

}  // namespace

SpliceResult splice(const gcode::Program& program, const layers::LayerStack& stack,
                    const toolpath::SupportPaths& paths, const Settings& settings, int threads) {
    SpliceResult result;
    // What each layer's block is written from, found in one pass of the
    // machine over the file, pausing at each insertion point; each block is
    // written (from that alone: the same text on any number of threads) by
    // another thread as soon as its place is found, and by the pass's own
    // once it is done.
    struct Block {
        gcode::MachineState st;
        std::string support_role, restore_role, width, height;
        std::uint32_t at = 0;
        double z = 0, height_mm = 0;
        std::string text;
        double filament = 0, length = 0, seconds = 0;
    };
    const std::size_t n = paths.layers.size();
    std::vector<Block> blocks(n);
    std::atomic<std::size_t> found{0}, next{0};  // blocks whose place is found; the next to write
    std::atomic<bool> failed{false};
    const bool fw = settings.firmware_retraction || program.saw_firmware_retraction;
    const double accel = planned_acceleration(program);
    auto find_places = [&] {
        gcode::MachineState st;
        st.absolute_e = !program.relative_e_at_start;
        gcode::Command cmd;
        std::vector<gcode::Move> scratch;
        RoleWords roles(program.dialect);
        std::string last_width, last_height;
        std::uint32_t line = 0;
        std::uint64_t released = 0;  // text before this was lexed and released
        std::int64_t open = -1;      // line that opened the labelled block open at `line`
        for (std::size_t i = 0; i < n; ++i) {
            const toolpath::LayerPaths& lp = paths.layers[i];
            const layers::Layer& layer = stack.layers[lp.layer];
            // A bond goes in once the nozzle has risen to the layer (it then
            // descends to the bond and rises again, never over printed
            // model), before the layer's first extrusion; its block is
            // written at its own height.
            const std::uint32_t meant = lp.bond() ? layer_reached(program, st, line, layer) : layer.end_line;
            std::uint32_t at = std::max(line, outside_blocks(program, line, meant, open, result.blocks_split));
            for (; line < at && line < program.lines.size(); ++line) {
                std::string_view text = program.line_text(line);
                gcode::lex(text, cmd);
                if (cmd.letter == 0) {
                    const std::string_view said = text.substr(0, text.find_last_not_of(" \t\r") + 1);
                    roles.see(said);
                    if (is_width_comment(said)) last_width = said;
                    else if (is_height_comment(said)) last_height = said;
                    continue;
                }
                scratch.clear();
                gcode::step(st, cmd, line, scratch);
            }
            // A huge file stays resident only a layer at a time.
            std::uint64_t upto = line < program.lines.size() ? program.lines[line].offset : program.text.size();
            program.text.release(released, upto);
            released = upto;
            Block& b = blocks[i];
            b.st = st;
            b.support_role = roles.support();
            b.restore_role = roles.restore();
            b.width = last_width;
            b.height = last_height;
            b.at = at;
            b.z = lp.bond() ? lp.bond_z : layer.z;
            b.height_mm = lp.bond() ? lp.bond_height : layer.height;
            found.store(i + 1, std::memory_order_release);
            found.notify_all();
        }
    };
    auto write_blocks = [&] {
        for (std::size_t i; (i = next.fetch_add(1)) < n;) {
            for (std::size_t f; (f = found.load(std::memory_order_acquire)) <= i;) {
                if (failed.load()) return;
                found.wait(f, std::memory_order_acquire);
            }
            if (failed.load()) return;
            Block& b = blocks[i];
            const toolpath::LayerPaths& lp = paths.layers[i];
            BlockWriter w(b.st, settings, b.z, b.height_mm, fw, b.support_role, b.restore_role, b.width, b.height,
                          stack.mesh.empty() ? nullptr : &stack.mesh, accel);
            if (lp.bond()) w.stay_above(lp.bond_z);
            b.text = w.write(lp.paths);
            b.filament = w.filament();
            b.length = w.length();
            b.seconds = w.seconds();
        }
    };
    plan::run_workers(std::max(1, std::min(threads, static_cast<int>(n))), [&](int worker) {
        if (worker == 0) {
            try {
                find_places();
            } catch (...) {
                // Nothing more will be found: the writers waiting stop.
                failed.store(true);
                found.store(n + 1, std::memory_order_release);
                found.notify_all();
                throw;
            }
        }
        write_blocks();
    });
    for (Block& b : blocks) {
        result.filament_mm += b.filament;
        result.extruded_length_mm += b.length;
        result.block_seconds.push_back(b.seconds);
        result.seconds += b.seconds;
        gcode::Edit e;
        e.line = b.at;
        e.text = std::move(b.text);
        result.edits.push_back(std::move(e));
        result.block_states.push_back(b.st);
        ++result.layers_touched;
    }
    return result;
}

std::vector<gcode::Move> spliced_moves(const gcode::Program& program, const SpliceResult& spliced) {
    const std::vector<gcode::Move>& in = program.moves;
    std::vector<gcode::Move> out;
    out.reserve(in.size() + spliced.edits.size() * 64);
    auto same = [](const gcode::Move& a, const gcode::Move& b) {
        return a.kind == b.kind && a.x0 == b.x0 && a.y0 == b.y0 && a.z0 == b.z0 && a.x1 == b.x1 && a.y1 == b.y1 &&
               a.z1 == b.z1 && a.e == b.e && a.feed_mm_per_min == b.feed_mm_per_min;
    };
    gcode::Command cmd;
    std::vector<gcode::Move> moves;
    std::size_t next = 0;    // the input's next move to take
    std::uint32_t line = 0;  // lines before this are done
    gcode::MachineState st;  // as the last block and the lines after it left it
    for (std::size_t b = 0; b < spliced.edits.size(); ++b) {
        const std::uint32_t at = spliced.edits[b].line;
        while (next < in.size() && in[next].line < at) out.push_back(in[next++]);
        // The block's own moves, from the state at its place (two blocks at
        // one place: the second from where the first left it).
        if (b == 0 || spliced.edits[b - 1].line != at) st = spliced.block_states[b];
        line = std::max(line, at);
        const std::string& text = spliced.edits[b].text;
        for (std::size_t pos = 0; pos < text.size();) {
            std::size_t nl = text.find('\n', pos);
            if (nl == std::string::npos) nl = text.size();
            gcode::lex(std::string_view(text).substr(pos, nl - pos), cmd);
            if (cmd.letter != 0) gcode::step(st, cmd, at, out);
            pos = nl + 1;
        }
        // The lines after it, stepped again until a move is the input's.
        const std::uint32_t limit = b + 1 < spliced.edits.size()
                                        ? spliced.edits[b + 1].line
                                        : static_cast<std::uint32_t>(program.lines.size());
        bool back = false;
        for (; line < limit && !back; ++line) {
            gcode::lex(program.line_text(line), cmd);
            if (cmd.letter == 0) continue;
            moves.clear();
            gcode::step(st, cmd, line, moves);
            std::size_t k = next;
            while (k < in.size() && in[k].line == line) ++k;
            back = !moves.empty() && k - next == moves.size() &&
                   std::equal(moves.begin(), moves.end(), in.begin() + static_cast<long>(next), same);
            out.insert(out.end(), moves.begin(), moves.end());
            next = k;
        }
    }
    while (next < in.size()) out.push_back(in[next++]);
    return out;
}

}  // namespace scaffold::splice
