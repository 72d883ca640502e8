#include "layers/crossing.hpp"

#include <algorithm>
#include <cmath>

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

}  // namespace scaffold::layers
