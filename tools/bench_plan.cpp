// scaffold-bench-plan: planning time against the number of support points
// (uniform random, fixed seed, z 5..60 mm), as ms and ms per point, so the
// growth can be read off one run.
//   default: a 200 x 200 mm area for every N (density grows with N), with
//            two model views: none (the search alone) and the obstacle
//            rasters of an empty print (adds the raster queries);
//   --fixed-density: the area grows with N (200 x 200 mm per 1000 points),
//            no model: the cost per point at a constant density.
// Usage: scaffold-bench-plan [--fixed-density] [N ...]   (default N: 100 1000 10000)
#include <chrono>
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

int main(int argc, char** argv) {
    std::vector<int> sizes;
    bool fixed_density = false;
    for (int i = 1; i < argc; ++i) {
        if (std::strcmp(argv[i], "--fixed-density") == 0)
            fixed_density = true;
        else
            sizes.push_back(std::atoi(argv[i]));
    }
    if (sizes.empty()) sizes = {100, 1000, 10000};
    Settings s;
    plan::ModelView none;
    for (int i = 0; i < 300; ++i) none.layer_tops.push_back(0.2 * (i + 1));
    std::printf("| points | area mm | model | bridges | columns | ms | ms per point |\n"
                "|---:|---:|---|---:|---:|---:|---:|\n");
    for (int n : sizes) {
        double side = fixed_density ? 200 * std::sqrt(n / 1000.0) : 200;
        std::mt19937 rng(12345);
        std::uniform_real_distribution<double> xy(0, side), z(5, 60);
        overhang::SupportPoints pts;
        for (int i = 0; i < n; ++i) {
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
            auto sc = real ? plan::plan_scaffold(pts, *obs, s) : plan::plan_scaffold(pts, none, s);
            double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t).count();
            std::printf("| %d | %.0f | %s | %zu | %zu | %.1f | %.3f |\n", n, side, real ? "rasters" : "none",
                        sc.bridges.size(), sc.columns.size(), ms, ms / n);
            std::fflush(stdout);
        }
    }
}
