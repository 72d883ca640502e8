// libFuzzer target: the whole pipeline (read, layers, overhangs, points,
// both planners, toolpaths, splice, and re-reading the result) on small
// inputs. Anything but success or scaffold::Error is a bug.
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <string>

#include "gcode/error.hpp"
#include "gcode/reader.hpp"
#include "gcode/writer.hpp"
#include "layers/layer_stack.hpp"
#include "overhang/overhangs.hpp"
#include "plan/obstacles.hpp"
#include "plan/pillars.hpp"
#include "plan/planner.hpp"
#include "splice/splice.hpp"
#include "toolpath/support_paths.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    if (size > 20000) return 0;
    try {
        auto program = scaffold::gcode::parse(std::string(reinterpret_cast<const char*>(data), size), "fuzz");
        // A coarse raster keeps each run fast; huge prints are skipped.
        auto settings = scaffold::build_settings(program, {}, {{"--resolution", "0.5"}});
        auto stack = scaffold::layers::build_layers(program, settings);
        const auto& b = stack.bounds;
        if (b.max_x - b.min_x > 300 || b.max_y - b.min_y > 300 || stack.layers.size() > 400) return 0;
        auto over = scaffold::overhang::find_overhangs(stack, settings);
        auto points = scaffold::overhang::place_points(over, stack, settings);
        if (points.points.size() > 60) return 0;
        scaffold::plan::Obstacles obs(stack, settings);
        for (int method = 0; method < 2; ++method) {
            auto plan = method == 0 ? scaffold::plan::plan_pillars(points, stack, obs, settings)
                                    : scaffold::plan::plan_scaffold(points, stack, obs, settings);
            auto paths = scaffold::toolpath::make_paths(plan, stack, settings, &obs);
            auto spliced = scaffold::splice::splice(program, stack, paths, settings);
            char* buf = nullptr;
            std::size_t len = 0;
            std::FILE* f = open_memstream(&buf, &len);
            scaffold::gcode::write_edited(f, program, spliced.edits);
            std::fclose(f);
            std::string out(buf, len);
            std::free(buf);
            auto again = scaffold::gcode::parse(std::move(out), "fuzz-out");
            if (again.moves.size() < program.moves.size()) __builtin_trap();  // the model must survive
        }
    } catch (const scaffold::Error&) {
    }
    return 0;
}
