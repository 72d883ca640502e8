#include "gcode/machine.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace scaffold::gcode {

namespace {

constexpr double kArcTolerance = 0.01;  // mm chord deviation
constexpr double kMaxCoordinate = 10000;  // mm; beyond this a file is broken

MoveKind classify(double dxy2, double e) {
    if (dxy2 > 1e-18) return e > 0 ? MoveKind::Extrude : (e < 0 ? MoveKind::Wipe : MoveKind::Travel);
    if (e < 0) return MoveKind::Retract;
    if (e > 0) return MoveKind::Unretract;
    return MoveKind::Travel;
}

// Extruding ends a retraction whatever was given back: Simplify3D primes
// 0.2 mm less than it retracts (a negative "extra restart distance"), and
// counting the rest as still retracted would add up over the print.
void track_retraction(MachineState& st, MoveKind kind, double e) {
    if (kind == MoveKind::Retract || kind == MoveKind::Wipe) st.retracted_mm -= e;
    else if (kind == MoveKind::Unretract) st.retracted_mm = std::max(0.0, st.retracted_mm - e);
    else if (kind == MoveKind::Extrude) st.retracted_mm = 0;
}

void push(std::vector<Move>& moves, std::uint32_t line, double x0, double y0, double z0, double x1,
          double y1, double z1, double e, const MachineState& st) {
    Move m;
    m.line = line;
    m.x0 = static_cast<float>(x0); m.y0 = static_cast<float>(y0); m.z0 = static_cast<float>(z0);
    m.x1 = static_cast<float>(x1); m.y1 = static_cast<float>(y1); m.z1 = static_cast<float>(z1);
    m.e = static_cast<float>(e);
    m.feed_mm_per_min = static_cast<float>(st.feed_mm_per_min);
    m.kind = classify((x1 - x0) * (x1 - x0) + (y1 - y0) * (y1 - y0), e);  // hypot is slow here
    m.tool = static_cast<std::uint8_t>(std::clamp(st.tool, 0, 255));
    moves.push_back(m);
}

// E delta of a move, updating the register.
double take_e(MachineState& st, const Command& cmd, double scale) {
    const Word* w = cmd.find('E');
    if (!w) return 0;
    double v = w->value * scale;
    if (st.relative_e()) {
        st.e += v;
        return v;
    }
    double d = v - st.e;
    st.e = v;
    return d;
}

const char* target(const MachineState& st, const Command& cmd, double scale, double& x, double& y, double& z) {
    auto axis = [&](char l, double cur) {
        const Word* w = cmd.find(l);
        if (!w) return cur;
        return st.absolute_xyz ? w->value * scale : cur + w->value * scale;
    };
    x = axis('X', st.x);
    y = axis('Y', st.y);
    z = axis('Z', st.z);
    if (std::abs(x) > kMaxCoordinate || std::abs(y) > kMaxCoordinate || std::abs(z) > kMaxCoordinate)
        return "coordinate out of range (more than 10 m from the origin)";
    return nullptr;
}

const char* linear(MachineState& st, const Command& cmd, std::uint32_t line, std::vector<Move>& moves, double scale) {
    double x, y, z;
    if (const char* err = target(st, cmd, scale, x, y, z)) return err;
    double e = take_e(st, cmd, scale);
    bool moves_axis = cmd.has('X') || cmd.has('Y') || cmd.has('Z') || cmd.has('E');
    if (moves_axis) {
        push(moves, line, st.x, st.y, st.z, x, y, z, e, st);
        track_retraction(st, moves.back().kind, e);
        st.moved = true;
    }
    st.x = x; st.y = y; st.z = z;
    return nullptr;
}

const char* arc(MachineState& st, const Command& cmd, std::uint32_t line, std::vector<Move>& moves, double scale) {
    double x, y, z;
    if (const char* err = target(st, cmd, scale, x, y, z)) return err;
    bool clockwise = cmd.code == 2;
    double cx, cy;
    for (char l : {'I', 'J', 'R'})
        if (std::abs(cmd.get(l, 0)) * scale > 2 * kMaxCoordinate) return "arc centre or radius out of range";
    if (cmd.has('I') || cmd.has('J')) {
        cx = st.x + cmd.get('I', 0) * scale;
        cy = st.y + cmd.get('J', 0) * scale;
    } else if (cmd.has('R')) {
        double r = cmd.get('R', 0) * scale;
        double dx = x - st.x, dy = y - st.y;
        double d = std::hypot(dx, dy);
        if (d < 1e-9) return "G2/G3 with R needs an end point different from the start";
        if (d > 2 * std::abs(r) + 1e-6) return "G2/G3 radius is smaller than half the chord";
        double h = std::sqrt(std::max(0.0, r * r - d * d / 4));
        // Centre on the side that gives the short arc for R>0, long for R<0.
        double side = (clockwise ? -1.0 : 1.0) * (r > 0 ? 1.0 : -1.0);
        cx = st.x + dx / 2 - side * h * dy / d;
        cy = st.y + dy / 2 + side * h * dx / d;
    } else {
        return "G2/G3 arc with neither I/J nor R";
    }
    double r = std::hypot(st.x - cx, st.y - cy);
    double a0 = std::atan2(st.y - cy, st.x - cx);
    double a1 = std::atan2(y - cy, x - cx);
    double sweep = a1 - a0;
    if (clockwise) { if (sweep >= -1e-12) sweep -= 2 * std::numbers::pi; }
    else { if (sweep <= 1e-12) sweep += 2 * std::numbers::pi; }
    double e = take_e(st, cmd, scale);
    int n = 1;
    if (r > kArcTolerance) {
        double step = 2 * std::acos(1 - kArcTolerance / r);
        // Clamp before converting: a huge radius gives a count beyond int.
        double pieces = std::ceil(std::abs(sweep) / step);
        n = pieces >= 1 && pieces <= 10000 ? static_cast<int>(pieces) : (pieces > 10000 ? 10000 : 1);
    }
    double px = st.x, py = st.y, pz = st.z;
    for (int k = 1; k <= n; ++k) {
        double t = static_cast<double>(k) / n;
        double qx = k == n ? x : cx + r * std::cos(a0 + sweep * t);
        double qy = k == n ? y : cy + r * std::sin(a0 + sweep * t);
        double qz = st.z + (z - st.z) * t;
        push(moves, line, px, py, pz, qx, qy, qz, e / n, st);
        track_retraction(st, moves.back().kind, e / n);
        px = qx; py = qy; pz = qz;
    }
    st.x = x; st.y = y; st.z = z;
    st.moved = true;
    return nullptr;
}

}  // namespace

const char* step(MachineState& st, const Command& cmd, std::uint32_t line, std::vector<Move>& moves) {
    double scale = st.inches ? 25.4 : 1.0;
    if (const Word* f = cmd.find('F'); f && (cmd.letter == 'G' && cmd.code <= 3)) {
        if (f->value <= 0) return "feedrate F must be positive";
        st.feed_mm_per_min = f->value * scale;
    }
    if (cmd.letter == 'G') {
        switch (cmd.code) {
            case 0: case 1: return linear(st, cmd, line, moves, scale);
            case 2: case 3: return arc(st, cmd, line, moves, scale);
            case 10:
                if (cmd.has('P') || cmd.has('L')) return nullptr;  // tool offset setting, not a retract
                if (!st.fw_retracted) {
                    st.fw_retracted = true;
                    push(moves, line, st.x, st.y, st.z, st.x, st.y, st.z, 0, st);
                    moves.back().kind = MoveKind::Retract;
                }
                return nullptr;
            case 11:
                if (st.fw_retracted) {
                    st.fw_retracted = false;
                    push(moves, line, st.x, st.y, st.z, st.x, st.y, st.z, 0, st);
                    moves.back().kind = MoveKind::Unretract;
                }
                return nullptr;
            case 20:
                if (st.moved && !st.inches) return "G20 (inches) after moves in millimetres: mixed units are not supported";
                st.inches = true;
                return nullptr;
            case 21:
                if (st.moved && st.inches) return "G21 (millimetres) after moves in inches: mixed units are not supported";
                st.inches = false;
                return nullptr;
            case 28:
                // Homing: axes named (or all) go to 0 as far as geometry goes.
                if (!cmd.has('X') && !cmd.has('Y') && !cmd.has('Z')) { st.x = st.y = st.z = 0; }
                if (cmd.has('X')) st.x = 0;
                if (cmd.has('Y')) st.y = 0;
                if (cmd.has('Z')) st.z = 0;
                return nullptr;
            case 90: st.absolute_xyz = true; return nullptr;
            case 91: st.absolute_xyz = false; return nullptr;
            case 92: {
                bool any = cmd.has('X') || cmd.has('Y') || cmd.has('Z') || cmd.has('E');
                if (!any || cmd.has('X')) st.x = cmd.get('X', 0) * scale;
                if (!any || cmd.has('Y')) st.y = cmd.get('Y', 0) * scale;
                if (!any || cmd.has('Z')) st.z = cmd.get('Z', 0) * scale;
                if (!any || cmd.has('E')) st.e = cmd.get('E', 0) * scale;
                return nullptr;
            }
            default: return nullptr;
        }
    }
    if (cmd.letter == 'M') {
        switch (cmd.code) {
            case 82: st.absolute_e = true; return nullptr;
            case 83: st.absolute_e = false; return nullptr;
            case 106: st.fan = static_cast<int>(std::clamp(cmd.get('S', 255), 0.0, 255.0)); return nullptr;
            case 107: st.fan = 0; return nullptr;
            default: return nullptr;
        }
    }
    if (cmd.letter == 'T') st.tool = cmd.code;
    return nullptr;
}

}  // namespace scaffold::gcode
