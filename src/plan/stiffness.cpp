#include "plan/stiffness.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace scaffold::plan {

namespace {
// The loop's centre-line radius for outer radius r (as loop_shape).
double centre_radius(double r, double w) { return std::max(r - w / 2, w * 0.25); }

// Antiderivative in u = rc(z) of (top - z)^2 / rc^3 for rc growing by
// `taper` per mm of (top - z), rc = c0 + taper * (top - z): with
// h = (u - c0) / taper, h^2 / u^3 dh = (u - c0)^2 / (taper^3 u^3) du.
double cone_primitive(double u, double c0, double taper) {
    return (std::log(u) + 2 * c0 / u - c0 * c0 / (2 * u * u)) / (taper * taper * taper);
}
}  // namespace

double ring_inertia(double r, double width) {
    const double rc = centre_radius(r, width);
    return std::numbers::pi * rc * rc * rc * width;
}

double bar_inertia(double length, double width, double pillar_radius) {
    const double across = 2 * width;
    return (length + pillar_radius) * across * across * across / 12;
}

double ring_compliance(double r, double taper, double top, double lo, double hi, double width, double modulus) {
    if (!(hi > lo)) return 0;
    const double ew = modulus * std::numbers::pi * width;  // E I = ew rc^3
    const double h_lo = top - hi, h_hi = top - lo;          // lever arms at the part's ends
    const double c0 = centre_radius(r, width);
    // The centre line follows the outer radius once the loop is wider than
    // a bead (loop_shape's floor only bites on radii under 0.75 w).
    if (taper * h_hi < 1e-9 * c0 || r - width / 2 < width * 0.25)
        return (h_hi * h_hi * h_hi - h_lo * h_lo * h_lo) / (3 * ew * c0 * c0 * c0);
    return (cone_primitive(c0 + taper * h_hi, c0, taper) - cone_primitive(c0 + taper * h_lo, c0, taper)) / ew;
}

double taper_for(double r, double height, double k_target, double give, double width, double modulus) {
    if (!(k_target > 0) || !(height > 0)) return 0;
    const double allowed = 1 / k_target - give;  // what the column itself may give
    auto compliance = [&](double taper) { return ring_compliance(r, taper, height, 0, height, width, modulus); };
    if (compliance(0) <= allowed) return 0;
    if (allowed <= 0 || compliance(kMaxTaper) > allowed) return kMaxTaper;
    double lo = 0, hi = kMaxTaper;  // compliance falls as the taper grows
    for (int i = 0; i < 40; ++i) {
        const double mid = (lo + hi) / 2;
        (compliance(mid) > allowed ? lo : hi) = mid;
    }
    return hi;
}

}  // namespace scaffold::plan
