// scaffold-bench: throughput of the pipeline stages on real files, each as
// a ratio to something measured in the same run (`wc -l` on the same file,
// or the parse itself), so numbers compare across machines.
// Usage: scaffold-bench FILE.gcode [FILE.gcode ...]
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <fstream>
#include <sstream>
#include <string>

#include "gcode/reader.hpp"
#include "gcode/settings.hpp"
#include "layers/layer_stack.hpp"
#include "overhang/overhangs.hpp"

using clock_type = std::chrono::steady_clock;

namespace {

double seconds_since(clock_type::time_point t) {
    return std::chrono::duration<double>(clock_type::now() - t).count();
}

template <class F>
double best_of(int runs, F&& f) {
    double best = 1e300;
    for (int i = 0; i < runs; ++i) {
        auto t = clock_type::now();
        f();
        best = std::min(best, seconds_since(t));
    }
    return best;
}

std::string slurp(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    std::stringstream ss;
    ss << in.rdbuf();
    return ss.str();
}

}  // namespace

int main(int argc, char** argv) {
    if (argc < 2) {
        std::fprintf(stderr, "usage: scaffold-bench FILE.gcode [...]\n");
        return 2;
    }
    std::printf("| file | MB | lines | parse MB/s | wc -l MB/s | parse / wc -l | layers+overhang+points s | / parse | cpu s | points | overhang mm^2 |\n");
    std::printf("|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|\n");
    for (int a = 1; a < argc; ++a) {
        std::string path = argv[a];
        std::string text = slurp(path);
        double mb = static_cast<double>(text.size()) / 1e6;
        std::size_t lines = 0;
        double parse_s = best_of(5, [&] { lines = scaffold::gcode::parse(text, path).lines.size(); });
        std::string cmd = "wc -l < '" + path + "' > /dev/null";
        double wc_s = best_of(5, [&] { if (std::system(cmd.c_str()) != 0) std::exit(1); });
        auto program = scaffold::gcode::parse(text, path);
        auto settings = scaffold::build_settings(program, {}, {});
        scaffold::overhang::SupportPoints points;
        // CPU time too (all threads): on a busy machine the threads may not
        // run at once, and the wall time alone hides the work done.
        double detect_cpu_s = 1e300;
        double detect_s = best_of(5, [&] {
            std::clock_t c0 = std::clock();
            auto stack = scaffold::layers::build_layers(program, settings);
            auto over = scaffold::overhang::find_overhangs(stack, settings);
            points = scaffold::overhang::place_points(over, stack, settings);
            detect_cpu_s = std::min(detect_cpu_s, static_cast<double>(std::clock() - c0) / CLOCKS_PER_SEC);
        });
        std::string name = path.substr(path.rfind('/') + 1);
        std::printf("| %s | %.2f | %zu | %.0f | %.0f | %.2fx | %.3f | %.2fx | %.3f | %zu | %.1f |\n", name.c_str(), mb, lines,
                    mb / parse_s, mb / wc_s, parse_s / wc_s, detect_s, detect_s / parse_s, detect_cpu_s,
                    points.points.size(), points.overhang_area_mm2);
        std::fflush(stdout);
    }
    return 0;
}
