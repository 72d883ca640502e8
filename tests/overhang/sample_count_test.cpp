// sample_count's fast path (a square root and a multiplication) must give
// the plain formula's count, ceil(hypot / step), also where the quotient
// lands on or next to an integer.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>

#include "overhang/overhangs.hpp"

namespace {

int plain(double dx, double dy, double step) { return std::max(1, static_cast<int>(std::ceil(std::hypot(dx, dy) / step))); }

}  // namespace

TEST(SampleCount, MatchesThePlainFormula) {
    std::mt19937 rng(4321);
    auto uniform = [&](double a, double b) { return std::uniform_real_distribution<double>(a, b)(rng); };
    for (double step : {0.1, 0.05, 0.07, 0.25}) {
        const double inv = 1 / step;
        for (int n = 0; n < 200000; ++n) {
            // Float ends, as segments hold them: free, axis-parallel or a
            // whole number of steps long, and 3-4-5 triangles.
            const float x0 = static_cast<float>(uniform(0, 200)), y0 = static_cast<float>(uniform(0, 200));
            float x1 = x0, y1 = y0;
            switch (n % 5) {
            case 0: x1 = static_cast<float>(x0 + uniform(-20, 20)); y1 = static_cast<float>(y0 + uniform(-20, 20)); break;
            case 1: x1 = static_cast<float>(x0 + step * static_cast<int>(uniform(-200, 200))); break;
            case 2: y1 = static_cast<float>(y0 + step * static_cast<int>(uniform(-200, 200))); break;
            case 3: {
                const double k = step * static_cast<int>(uniform(0, 40));
                x1 = static_cast<float>(x0 + 3 * k);
                y1 = static_cast<float>(y0 + 4 * k);
                break;
            }
            default: x1 = static_cast<float>(x0 + uniform(-1e-4, 1e-4)); break;
            }
            const double dx = x1 - x0, dy = y1 - y0;
            ASSERT_EQ(scaffold::overhang::sample_count(dx, dy, step, inv), plain(dx, dy, step))
                << "dx " << dx << " dy " << dy << " step " << step;
        }
        // Exact multiples in double.
        for (int k = 0; k < 2000; ++k) {
            const double len = k * step;
            ASSERT_EQ(scaffold::overhang::sample_count(len, 0, step, inv), plain(len, 0, step)) << k;
            ASSERT_EQ(scaffold::overhang::sample_count(0.6 * len, 0.8 * len, step, inv), plain(0.6 * len, 0.8 * len, step)) << k;
        }
    }
}
