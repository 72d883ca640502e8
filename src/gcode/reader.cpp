#include "gcode/reader.hpp"

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cstring>
#include <sstream>

#include "gcode/bgcode.hpp"
#include "gcode/error.hpp"
#include "gcode/lexer.hpp"
#include "gcode/machine.hpp"

namespace scaffold::gcode {

const char* dialect_name(Dialect d) {
    switch (d) {
        case Dialect::PrusaSlicer: return "PrusaSlicer";
        case Dialect::SuperSlicer: return "SuperSlicer";
        case Dialect::OrcaSlicer: return "OrcaSlicer";
        case Dialect::Slic3r: return "Slic3r";
        case Dialect::Cura: return "Cura";
        case Dialect::Unknown: break;
    }
    return "unknown";
}

namespace {

bool starts_with(std::string_view s, std::string_view p) { return s.substr(0, p.size()) == p; }

std::string_view trim(std::string_view s) {
    while (!s.empty() && (s.front() == ' ' || s.front() == '\t')) s.remove_prefix(1);
    while (!s.empty() && (s.back() == ' ' || s.back() == '\t' || s.back() == '\r')) s.remove_suffix(1);
    return s;
}

bool is_key(std::string_view k) {
    if (k.empty()) return false;
    for (char c : k)
        if (!((c >= 'a' && c <= 'z') || (c >= '0' && c <= '9') || c == '_')) return false;
    return true;
}

Dialect detect_dialect(std::string_view comment) {
    if (comment.find("PrusaSlicer") != std::string_view::npos) return Dialect::PrusaSlicer;
    if (comment.find("SuperSlicer") != std::string_view::npos) return Dialect::SuperSlicer;
    if (comment.find("OrcaSlicer") != std::string_view::npos || comment.find("BambuStudio") != std::string_view::npos)
        return Dialect::OrcaSlicer;
    if (comment.find("Slic3r") != std::string_view::npos) return Dialect::Slic3r;
    if (comment.find("Cura") != std::string_view::npos) return Dialect::Cura;
    return Dialect::Unknown;
}

double parse_double(std::string_view s, double fallback) {
    s = trim(s);
    try {
        std::size_t used = 0;
        double v = std::stod(std::string(s), &used);
        return used > 0 ? v : fallback;
    } catch (...) {
        return fallback;
    }
}

// Cura's ;SETTING_3 lines carry a JSON object whose strings hold INI text
// ("[values]\nlayer_height = 0.2\n"); the key = value lines are what we need.
void parse_cura_settings(const std::string& json, std::map<std::string, std::string>& config) {
    std::string text;
    text.reserve(json.size());
    for (std::size_t i = 0; i < json.size(); ++i) {
        if (json[i] == '\\' && i + 1 < json.size()) {
            // Cura 4.13 escapes the INI's newlines once ("\n"), Cura 4.9 and
            // earlier twice ("\\n"): both end a line.
            char n = json[++i];
            if (n == '\\' && i + 1 < json.size() && json[i + 1] == 'n') n = json[++i];
            text += n == 'n' ? '\n' : n;
        } else {
            text += json[i] == '"' ? '\n' : json[i];
        }
    }
    std::istringstream in(text);
    std::string line;
    while (std::getline(in, line)) {
        std::size_t eq = line.find(" = ");
        if (eq == std::string::npos) continue;
        std::string key(trim(std::string_view(line).substr(0, eq)));
        if (is_key(key)) config[key] = std::string(trim(std::string_view(line).substr(eq + 3)));
    }
}

struct Parser {
    Program& p;
    MachineState st;
    Command cmd;
    Role role = Role::Unknown;
    float width = 0;
    std::string cura_settings;
    bool simplify3d = false;
    bool saw_e_mode = false;  // M82 or M83 seen
    std::uint32_t last_extrusion_line = 0;
    // XY moves with an E word, and those of them that did not move E
    // forward: a file that never says M82 or M83 may still be written with
    // relative E (the firmware's default); read as absolute, its E then
    // stands still or steps back on about half of the beads.
    std::size_t e_moves = 0, e_not_forward = 0;
    bool looks_relative() const { return e_moves > 100 && e_not_forward * 5 > e_moves * 2; }

    void comment_line(std::uint32_t i, std::string_view c) {
        if (starts_with(c, "TYPE:")) { role = role_from_name(trim(c.substr(5))); return; }
        if (starts_with(c, "FEATURE:")) { role = role_from_name(trim(c.substr(8))); return; }
        // Simplify3D 4.1+ and Kiri:Moto: "; feature support". A name not
        // known (Kiri's "shells") ends the one before.
        if (starts_with(c, "feature ")) {
            Role r = Role::Unknown;
            role = simplify3d_role(c, r) ? r : Role::Unknown;
            return;
        }
        if (!c.empty() && c.front() == '\'' && kisslicer_role(c, role)) return;
        if (starts_with(c, "WIDTH:")) { width = static_cast<float>(parse_double(c.substr(6), 0)); return; }
        if (starts_with(c, "LINE_WIDTH:")) { width = static_cast<float>(parse_double(c.substr(11), 0)); return; }
        if (c == "LAYER_CHANGE" || c == "CHANGE_LAYER" || starts_with(c, "LAYER:") || starts_with(c, " LAYER:")) {
            p.layer_hints.push_back({i, -1, -1});
            return;
        }
        // Prusa profiles' before-layer G-code: a layer change in files that
        // write no ;LAYER_CHANGE (PrusaSlicer before 2.2); after one, with
        // no extrusion since, it is the same change.
        if (c == "BEFORE_LAYER_CHANGE") {
            if (p.layer_hints.empty() || p.layer_hints.back().line < last_extrusion_line)
                p.layer_hints.push_back({i, -1, -1});
            return;
        }
        // Simplify3D "; layer 2, Z = 0.69", Kiri:Moto ";; --- layer 1 (0.250 @ 0.505) ---",
        // KISSlicer "; BEGIN_LAYER_OBJECT z=0.526 z_thickness=0.263".
        if (starts_with(c, "layer ") && c.find(", Z = ") != std::string_view::npos) {
            p.layer_hints.push_back({i, parse_double(c.substr(c.find(", Z = ") + 6), -1), -1});
            return;
        }
        if (starts_with(c, "; --- layer ") && c.find(" @ ") != std::string_view::npos) {
            p.layer_hints.push_back({i, parse_double(c.substr(c.find(" @ ") + 3), -1), -1});
            return;
        }
        if (starts_with(c, "BEGIN_LAYER_OBJECT z=")) {
            std::size_t th = c.find("z_thickness=");
            p.layer_hints.push_back({i, parse_double(c.substr(21), -1), th == std::string_view::npos ? -1 : parse_double(c.substr(th + 12), -1)});
            return;
        }
        // The first ;Z: and ;HEIGHT: after a layer comment are the layer's:
        // PrusaSlicer says ;HEIGHT:0.4 again for an overhang perimeter's
        // beads, and a post-processor may say its own beads' height.
        if (starts_with(c, "Z:") || starts_with(c, "Z_HEIGHT:")) {
            if (!p.layer_hints.empty() && p.layer_hints.back().z < 0)
                p.layer_hints.back().z = parse_double(c.substr(c.find(':') + 1), -1);
        } else if (starts_with(c, "HEIGHT:") || starts_with(c, "LAYER_HEIGHT:")) {
            if (!p.layer_hints.empty() && p.layer_hints.back().height < 0)
                p.layer_hints.back().height = parse_double(c.substr(c.find(':') + 1), -1);
        } else if (starts_with(c, "FLAVOR:")) {
            if (p.dialect == Dialect::Unknown) p.dialect = Dialect::Cura;
            p.config["machine_gcode_flavor"] = std::string(trim(c.substr(7)));
        } else if (starts_with(c, "Layer height:")) {
            p.config.emplace("layer_height", std::string(trim(c.substr(13))));
        } else if (std::size_t eq = c.find(" = "); eq != std::string_view::npos) {
            std::string_view key = trim(c.substr(0, eq));
            if (is_key(key)) p.config[std::string(key)] = std::string(trim(c.substr(eq + 3)));
        } else if (p.dialect == Dialect::Unknown && (starts_with(c, "generated by") || starts_with(c, "Generated with"))) {
            p.dialect = detect_dialect(c);
        } else if (starts_with(c, "G-Code generated by Simplify3D")) {
            simplify3d = true;
        } else if (simplify3d && simplify3d_role(c, role)) {
            // a feature name: the role of the moves that follow
        } else if (simplify3d) {
            // Simplify3D's settings summary: ";   layerHeight,0.3".
            std::size_t comma = c.find(',');
            std::string_view key = c.substr(0, comma);
            if (comma != std::string_view::npos && !key.empty() &&
                std::all_of(key.begin(), key.end(), [](char ch) { return std::isalnum(static_cast<unsigned char>(ch)); }))
                p.config.emplace(std::string(key), std::string(trim(c.substr(comma + 1))));
        }
    }

    void line(std::uint32_t i, std::string_view text) {
        const char* err = lex(text, cmd);
        if (*err) throw Error(p.path, i + 1, std::string(err) + ": '" + std::string(trim(text.substr(0, 80))) + "'");
        if (cmd.letter == 0) {
            std::string_view t = trim(text);
            // Cura splits its settings JSON at fixed widths: keep every byte.
            if (starts_with(t, ";SETTING_3 ")) cura_settings += text.substr(text.find(";SETTING_3 ") + 11);
            else if (!t.empty() && t.front() == ';') comment_line(i, trim(t.substr(1)));
            return;
        }
        // G10 with P or L sets a tool's temperatures or offsets (RepRapFirmware), no retraction.
        if (cmd.letter == 'G' && cmd.code >= 10 && cmd.code <= 11 && !cmd.has('P') && !cmd.has('L'))
            p.saw_firmware_retraction = true;
        if (cmd.letter == 'G' && (cmd.code == 2 || cmd.code == 3)) p.saw_arcs = true;
        if (cmd.is('M', 83)) p.saw_relative_e = true;
        if (cmd.is('M', 82) || cmd.is('M', 83)) saw_e_mode = true;
        std::size_t before = p.moves.size();
        if (const char* e = step(st, cmd, i, p.moves))
            throw Error(p.path, i + 1, std::string(e) + ": '" + std::string(trim(text.substr(0, 80))) + "'");
        if (p.moves.size() == before) return;
        if (cmd.has('E') && (cmd.has('X') || cmd.has('Y'))) {
            ++e_moves;
            e_not_forward += p.moves.back().kind != MoveKind::Extrude;
        }
        // Slic3r 1.x names the role per line in a trailing comment.
        Role r = role;
        if (!cmd.comment.empty() && p.dialect == Dialect::Slic3r) {
            Role per_line = role_from_name(cmd.comment);
            if (per_line != Role::Unknown) r = per_line;
        }
        for (std::size_t k = before; k < p.moves.size(); ++k) {
            p.moves[k].role = r;
            p.moves[k].width = width;
            if (p.moves[k].kind == MoveKind::Extrude) last_extrusion_line = i;
        }
    }
};

}  // namespace

namespace {

// Lines and moves in one pass. On a mapped file the bytes behind the pass
// are released as it goes, so the text is never resident as a whole.
Program parse_text(Text text, std::string path, bool relative_e = false) {
    if (bgcode::is_binary(text)) {
        bgcode::Decoded d = bgcode::decode(text, path);
        Program p = parse_text(Text(std::move(d.ascii)), std::move(path));
        p.binary = std::make_shared<const bgcode::Layout>(std::move(d.layout));
        return p;
    }
    Program p;
    p.path = std::move(path);
    p.text = std::move(text);
    const Text& t = p.text;
    if (t.empty()) throw Error(p.path, 0, "the file is empty");
    if (t.size() > kMaxFileSize) throw Error(p.path, 0, "the file is too large (over 1 TB)");
    std::size_t approx = t.size() / 24 + 16;
    p.lines.reserve(approx);
    p.moves.reserve(approx);
    constexpr std::size_t kWindow = std::size_t{16} << 20;
    std::size_t released = 0;
    Parser parser{p, {}, {}, Role::Unknown, 0, {}, false};
    parser.st.absolute_e = !relative_e;
    std::size_t pos = 0;
    while (pos < t.size()) {
        const void* nl = std::memchr(t.data() + pos, '\n', t.size() - pos);
        std::size_t end = nl ? static_cast<std::size_t>(static_cast<const char*>(nl) - t.data()) : t.size();
        std::size_t len = end - pos;
        if (len > 0 && t[end - 1] == '\r') --len;
        if (p.lines.size() >= 0xFFFFFFF0u) throw Error(p.path, 0, "too many lines");
        auto i = static_cast<std::uint32_t>(p.lines.size());
        if (len > kMaxLineLength) throw Error(p.path, i + 1, "line too long (over 16 MB)");
        p.lines.push_back({pos & kMaxFileSize, len & kMaxLineLength});  // both checked above
        parser.line(i, p.line_text(i));
        pos = end + 1;
        if (pos - released >= 2 * kWindow) {
            t.release(released, pos - kWindow);
            released = pos - kWindow;
        }
    }
    t.release(released, t.size());
    if (!parser.cura_settings.empty()) parse_cura_settings(parser.cura_settings, p.config);
    if (!relative_e && !parser.saw_e_mode && parser.looks_relative()) return parse_text(std::move(p.text), std::move(p.path), true);
    p.relative_e_at_start = relative_e;
    return p;
}

}  // namespace

Program parse(std::string text, std::string path) { return parse_text(Text(std::move(text)), std::move(path)); }

Program parse(Text text, std::string path) { return parse_text(std::move(text), std::move(path)); }

Program read_file(const std::string& path) {
    return parse_text(Text::load(path), path == "-" ? "<stdin>" : path);
}

}  // namespace scaffold::gcode
