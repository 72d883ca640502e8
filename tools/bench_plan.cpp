// scaffold-bench-plan: planning time against the number of support points
// (uniform random, fixed seed, 200 x 200 mm, z 5..60 mm), as ms and ms per
// point, so the growth can be read off one run. Two model views: none (the
// search alone) and the real obstacle rasters of an empty print (adds the
// raster queries for bars and connectors).
// Usage: scaffold-bench-plan [N ...]   (default: 100 1000 10000)
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <random>

#include "layers/layer_stack.hpp"
#include "plan/obstacles.hpp"
#include "plan/planner.hpp"

using namespace scaffold;

int main(int argc, char** argv) {
    std::vector<int> sizes;
    for (int i = 1; i < argc; ++i) sizes.push_back(std::atoi(argv[i]));
    if (sizes.empty()) sizes = {100, 1000, 10000};
    layers::LayerStack st;
    for (int i = 0; i < 300; ++i) {
        layers::Layer l;
        l.z = 0.2 * (i + 1);
        l.height = 0.2;
        l.below = i - 1;
        l.on_bed = i == 0;
        l.segments.push_back({-20, -20, -19.5f, -20, 0.45f, gcode::Role::Perimeter, 0});
        st.layers.push_back(l);
    }
    st.bounds = {-20, -20, 220, 220};
    Settings s;
    plan::Obstacles obs(st, s);
    plan::ModelView none;
    for (const auto& l : st.layers) none.layer_tops.push_back(l.z);
    std::printf("| points | model | bridges | columns | ms | ms per point |\n|---:|---|---:|---:|---:|---:|\n");
    for (int n : sizes) {
        std::mt19937 rng(12345);
        std::uniform_real_distribution<double> xy(0, 200), z(5, 60);
        overhang::SupportPoints pts;
        for (int i = 0; i < n; ++i) {
            double x = xy(rng), y = xy(rng);
            int layer = static_cast<int>(std::lround(z(rng) / 0.2));
            pts.points.push_back({x, y, st.layers[layer].z - 0.2, layer});
        }
        for (int real = 0; real < 2; ++real) {
            auto t = std::chrono::steady_clock::now();
            auto sc = real ? plan::plan_scaffold(pts, obs, s) : plan::plan_scaffold(pts, none, s);
            double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t).count();
            std::printf("| %d | %s | %zu | %zu | %.1f | %.3f |\n", n, real ? "rasters" : "none", sc.bridges.size(),
                        sc.columns.size(), ms, ms / n);
            std::fflush(stdout);
        }
    }
}
