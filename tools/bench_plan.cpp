// scaffold-bench-plan: planning time against the number of support points
// (uniform random, fixed seed, z 5..60 mm), as ms and ms per point, so the
// growth can be read off one run.
//   default: a 200 x 200 mm area for every N (density grows with N), with
//            two model views: none (the search alone) and the obstacle
//            rasters of an empty print (adds the raster queries);
//   --fixed-density: the area grows with N (200 x 200 mm per 1000 points),
//            no model: the cost per point at a constant density.
//   --realistic: points as a model's overhangs give them: regions on one
//            layer each, a 5 mm grid of 1-6 x 1-8 points, and sloped
//            undersides, one point per layer stepping 0.4 mm sideways for
//            10-40 layers; z 5..60 mm, regions spread over an area that
//            grows with N (200 x 200 mm per 1000 points, as a bed full of
//            models), no model: the cost per point as N grows at a real
//            model's density.
//   --threads T: the planner's threads (default: the machine's cores).
// Usage: scaffold-bench-plan [--fixed-density | --realistic] [--threads T] [N ...]   (default N: 100 1000 10000)
#include <chrono>
#include <ctime>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <optional>
#include <random>

#include "layers/layer_stack.hpp"
#include "plan/obstacles.hpp"
#include "plan/planner.hpp"

using namespace scaffold;

// A fingerprint of the plan (every coordinate's bits), to see that two
// builds or thread counts planned the same.
static unsigned long long plan_hash(const plan::Scaffold& sc) {
    unsigned long long h = 1469598103934665603ULL;
    auto mix = [&h](double v) {
        unsigned long long b;
        std::memcpy(&b, &v, sizeof b);
        h = (h ^ b) * 1099511628211ULL;
    };
    for (const auto& b : sc.bridges) {
        for (double v : {b.x0, b.y0, b.x1, b.y1, b.z}) mix(v);
        for (int p : b.points) mix(p);
    }
    for (const auto& c : sc.columns)
        for (double v : {c.x0, c.y0, c.z0, c.x1, c.y1, c.z1, c.radius}) mix(v);
    return h;
}

int main(int argc, char** argv) {
    std::vector<int> sizes;
    bool fixed_density = false, realistic = false;
    int threads = 0;
    for (int i = 1; i < argc; ++i) {
        if (std::strcmp(argv[i], "--threads") == 0 && i + 1 < argc) {
            threads = std::atoi(argv[++i]);
            continue;
        }
        if (std::strcmp(argv[i], "--fixed-density") == 0)
            fixed_density = true;
        else if (std::strcmp(argv[i], "--realistic") == 0)
            fixed_density = realistic = true;
        else
            sizes.push_back(std::atoi(argv[i]));
    }
    if (sizes.empty()) sizes = {100, 1000, 10000};
    Settings s;
    plan::ModelView none;
    for (int i = 0; i < 300; ++i) none.layer_tops.push_back(0.2 * (i + 1));
    std::printf("| points | area mm | model | bridges | columns | plan hash | ms | ms per point | cpu ms |\n"
                "|---:|---:|---|---:|---:|---|---:|---:|---:|\n");
    for (int n : sizes) {
        double side = fixed_density ? 200 * std::sqrt(n / 1000.0) : 200;
        std::mt19937 rng(12345);
        std::uniform_real_distribution<double> xy(0, side), z(5, 60);
        overhang::SupportPoints pts;
        while (realistic && static_cast<int>(pts.points.size()) < n) {
            std::uniform_int_distribution<int> kind(0, 9), rows(1, 6), cols(1, 8), len(10, 40), dir(0, 7);
            std::uniform_real_distribution<double> jitter(-0.5, 0.5);
            const double x0 = xy(rng), y0 = xy(rng);
            const int layer0 = static_cast<int>(std::lround(z(rng) / 0.2));
            auto add = [&](double x, double y, int layer) {
                if (static_cast<int>(pts.points.size()) < n && x >= 0 && y >= 0 && x <= side && y <= side)
                    pts.points.push_back({x, y, 0.2 * layer, layer});
            };
            if (kind(rng) < 7) {  // a flat overhang: a grid of points on its layer
                const int nr = rows(rng), nc = cols(rng);
                for (int r = 0; r < nr; ++r)
                    for (int c = 0; c < nc; ++c) add(x0 + 5 * c + jitter(rng), y0 + 5 * r + jitter(rng), layer0);
            } else {  // a sloped underside: a sliver per layer
                const double a = dir(rng) * 3.14159265358979 / 4;
                const int nl = len(rng);
                for (int k = 0; k < nl; ++k) add(x0 + 0.4 * k * std::cos(a), y0 + 0.4 * k * std::sin(a), layer0 + k);
            }
        }
        for (int i = 0; !realistic && i < n; ++i) {
            double x = xy(rng), y = xy(rng);
            int layer = static_cast<int>(std::lround(z(rng) / 0.2));
            pts.points.push_back({x, y, 0.2 * layer, layer});  // the bottom of layer `layer` (0.2 mm layers)
        }
        for (int real = 0; real < (fixed_density ? 1 : 2); ++real) {
            layers::LayerStack st;
            std::optional<plan::Obstacles> obs;
            if (real) {
                // An empty print (a speck of model off to the side) for the rasters.
                for (int i = 0; i < 300; ++i) {
                    layers::Layer l;
                    l.z = 0.2 * (i + 1);
                    l.height = 0.2;
                    l.below = i - 1;
                    l.on_bed = i == 0;
                    l.segments.push_back({-20, -20, -19.5f, -20, 0.45f, gcode::Role::Perimeter, 0});
                    st.layers.push_back(l);
                }
                st.bounds = {-20, -20, side + 20, side + 20};
                obs.emplace(st, s);
            }
            auto t = std::chrono::steady_clock::now();
            const std::clock_t cpu0 = std::clock();  // all threads' CPU time: what a busy machine cannot hide
            auto sc = real ? plan::plan_scaffold(pts, *obs, s) : plan::plan_scaffold(pts, none, s, threads);
            double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t).count();
            double cpu_ms = 1000.0 * static_cast<double>(std::clock() - cpu0) / CLOCKS_PER_SEC;
            std::printf("| %d | %.0f | %s%s | %zu | %zu | %016llx | %.1f | %.3f | %.0f |\n", n, side, real ? "rasters" : "none",
                        realistic ? ", realistic" : "", sc.bridges.size(), sc.columns.size(), plan_hash(sc), ms, ms / n, cpu_ms);
            std::fflush(stdout);
        }
    }
}
