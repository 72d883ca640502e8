#include "layers/crossing.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace scaffold::layers {

double footprint_distance(const BitGrid& footprint, double x, double y, double limit) {
    const double cell = footprint.cell();
    const int r = static_cast<int>(std::ceil(limit / cell)) + 1;
    const int ci = footprint.col(x), cj = footprint.row(y);
    double best2 = limit * limit;
    for (int j = cj - r; j <= cj + r; ++j) {
        // Nearest y of the row's cells to the point.
        const double y0 = footprint.cy(j) - cell / 2, y1 = y0 + cell;
        const double dy = y < y0 ? y0 - y : y > y1 ? y - y1 : 0;
        if (dy * dy >= best2) continue;
        for (int i = ci - r; i <= ci + r; ++i) {
            const double x0 = footprint.cx(i) - cell / 2, x1 = x0 + cell;
            const double dx = x < x0 ? x0 - x : x > x1 ? x - x1 : 0;
            const double d2 = dx * dx + dy * dy;
            if (d2 < best2 && footprint.get(i, j)) best2 = d2;
        }
    }
    return std::sqrt(best2);
}

bool leaves_across(const BitGrid& footprint, double hx, double hy, double px, double py, double walked) {
    if (walked <= 0) return true;  // no run to judge
    const double need = walked / 2;
    // Searching beyond what decides the answer gains nothing: the held end
    // is near the footprint, and past d_held + need the test is met.
    const double d_held = footprint_distance(footprint, hx, hy, 2 * kCrossingWalk + need);
    const double d_walked = footprint_distance(footprint, px, py, d_held + need + footprint.cell());
    return d_walked - d_held >= need;
}

void sample_segment(const Segment& sg, std::uint32_t seg, const BitGrid& held, double step, std::vector<PieceSample>& p) {
    // Differences of the floats, as every caller always took them.
    const double dx = sg.x1 - sg.x0, dy = sg.y1 - sg.y0, len = std::hypot(dx, dy);
    const double s0 = p.empty() ? 0 : p.back().s;
    const int n = std::max(1, static_cast<int>(std::ceil(len / step)));
    for (int i = p.empty() ? 0 : 1; i <= n; ++i) {
        const double t = static_cast<double>(i) / n, x = sg.x0 + dx * t, y = sg.y0 + dy * t;
        int ci, cj;
        if (!held.sure_cell(x, y, ci, cj)) ci = held.col(x), cj = held.row(y);
        p.push_back({x, y, s0 + len * t, seg, held.get(ci, cj)});
    }
}

bool held_near_end(const std::vector<PieceSample>& p, bool at_end, double reach) {
    if (p.empty()) return false;
    if (at_end) {
        for (std::size_t k = p.size(); k-- > 0 && p.back().s - p[k].s <= reach;)
            if (p[k].held) return true;
    } else {
        for (std::size_t k = 0; k < p.size() && p[k].s - p.front().s <= reach; ++k)
            if (p[k].held) return true;
    }
    return false;
}

void hold_runs(std::vector<PieceSample>& p, const BitGrid& footprint, double max_span, double dangling_end) {
    for (std::size_t i = 0; i < p.size();) {
        if (p[i].held) { ++i; continue; }
        std::size_t j = i;
        while (j < p.size() && !p[j].held) ++j;
        const bool start_held = i > 0, end_held = j < p.size();
        bool ok = false;
        if (start_held && end_held)
            ok = p[j].s - p[i - 1].s <= max_span && run_crosses(footprint, p, i - 1, j);
        else if (start_held != end_held)  // a dangling end, from its last held sample
            ok = (start_held ? p[j - 1].s - p[i - 1].s : p[j].s - p[i].s) <= dangling_end;
        if (ok)
            for (std::size_t k = i; k < j; ++k) p[k].held = true;
        i = j;
    }
}

Beneath::Beneath(const std::vector<BeadBeneath>& beads, double x0, double y0, double x1, double y1, double reach,
                 double cell)
    : footprint_(std::floor(x0 / cell) * cell, std::floor(y0 / cell) * cell, x1, y1, cell),
      held_(footprint_.empty_like()),
      cell_(cell) {
    for (const BeadBeneath& d : beads) {
        const double grow = reach + d.width;
        if (std::max(d.x0, d.x1) < x0 - grow || std::min(d.x0, d.x1) > x1 + grow || std::max(d.y0, d.y1) < y0 - grow ||
            std::min(d.y0, d.y1) > y1 + grow)
            continue;
        if (d.rim) footprint_.draw_segment(d.x0, d.y0, d.x1, d.y1, d.width);
        held_.draw_segment(d.x0, d.y0, d.x1, d.y1, d.width + 2 * reach);
    }
}

bool Beneath::path_held(const std::vector<std::array<float, 2>>& pts, double max_span, double dangling_end) const {
    if (pts.size() < 2) return true;
    // Pieces, each straight within kStraightDeg of its first move; every
    // piece after the first starts at a corner of the path.
    const double cos_straight = std::cos(kStraightDeg * std::numbers::pi / 180);
    std::vector<std::vector<PieceSample>> pieces;
    double ux = 0, uy = 0;
    for (std::size_t k = 0; k + 1 < pts.size(); ++k) {
        Segment sg;
        sg.x0 = pts[k][0], sg.y0 = pts[k][1], sg.x1 = pts[k + 1][0], sg.y1 = pts[k + 1][1];
        const double dx = sg.x1 - sg.x0, dy = sg.y1 - sg.y0, len = std::hypot(dx, dy);
        const bool joins = k > 0 && len > 0 && (dx * ux + dy * uy) / len >= cos_straight;
        if (!joins) {
            pieces.emplace_back();
            ux = len > 0 ? dx / len : 0;
            uy = len > 0 ? dy / len : 0;
        }
        sample_segment(sg, static_cast<std::uint32_t>(k), held_, cell_, pieces.back());
    }
    // (a), then the holes the beads beneath enclose (a sample unheld by (a)
    // lies off the footprint: in a hole exactly where the filled footprint
    // has it, filled once for every path walked here).
    bool any_unheld = false;
    for (const auto& piece : pieces)
        for (const PieceSample& q : piece) any_unheld = any_unheld || !q.held;
    if (!any_unheld) return true;
    if (!have_filled_) {
        filled_ = footprint_.filled();
        have_filled_ = true;
    }
    for (auto& piece : pieces)
        for (PieceSample& q : piece)
            if (!q.held && filled_.get(filled_.col(q.x), filled_.row(q.y))) q.held = true;
    // (b): corners through the piece beside, then runs and dangling ends.
    std::vector<std::pair<bool, bool>> joint(pieces.size(), {false, false});
    for (std::size_t q = 1; q < pieces.size(); ++q) {
        joint[q].first = held_near_end(pieces[q - 1], true, dangling_end);
        joint[q - 1].second = held_near_end(pieces[q], false, dangling_end);
    }
    for (std::size_t q = 0; q < pieces.size(); ++q) {
        if (joint[q].first) pieces[q].front().held = true;
        if (joint[q].second) pieces[q].back().held = true;
    }
    for (auto& piece : pieces) {
        hold_runs(piece, footprint_, max_span, dangling_end);
        for (const PieceSample& q : piece)
            if (!q.held) return false;
    }
    return true;
}

bool path_held(const std::vector<std::array<float, 2>>& pts, const std::vector<BeadBeneath>& beads, double reach,
               double cell, double max_span, double dangling_end) {
    if (pts.size() < 2) return true;
    float lo_x = pts[0][0], hi_x = lo_x, lo_y = pts[0][1], hi_y = lo_y;
    for (const auto& q : pts) {
        lo_x = std::min(lo_x, q[0]), hi_x = std::max(hi_x, q[0]);
        lo_y = std::min(lo_y, q[1]), hi_y = std::max(hi_y, q[1]);
    }
    const Beneath under(beads, lo_x - kBeneathMargin, lo_y - kBeneathMargin, hi_x + kBeneathMargin,
                        hi_y + kBeneathMargin, reach, cell);
    return under.path_held(pts, max_span, dangling_end);
}

}  // namespace scaffold::layers
