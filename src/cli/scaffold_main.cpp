// scaffold: reads sliced G-code, adds support structures, writes G-code.
// A thin program over the pipeline library: options, logging, exit codes.
#include <cstdlib>
#include <spdlog/sinks/stdout_color_sinks.h>
#include <spdlog/spdlog.h>

#include <boost/program_options.hpp>
#ifdef _WIN32
#include <fcntl.h>
#include <io.h>
#endif
#include <cstdio>
#include <iostream>
#include <sstream>

#include "cli/pipeline.hpp"
#include "gcode/error.hpp"

namespace po = boost::program_options;

namespace {

// Settings that can be overridden on the command line, with their help.
// Defaults shown come from the Settings struct itself.
std::string num(double v) {
    std::ostringstream s;
    s << v;
    return s.str();
}

}  // namespace

int main(int argc, char** argv) {
#ifdef _WIN32
    (void)_setmode(_fileno(stdout), _O_BINARY);  // '\n' stays '\n': the same bytes as on Linux
#endif
    auto logger = spdlog::stderr_color_mt("scaffold");
    logger->set_pattern("scaffold: %^%l%$: %v");
    logger->set_level(spdlog::level::info);

    const scaffold::Settings d;  // defaults, for the help text
    po::options_description general("Usage: scaffold [options] INPUT\n\n"
        "Adds support structures (pillars and bridges) to G-code sliced without supports.\n"
        "INPUT is rewritten in place unless -o is given (the slicer post-processing hook\n"
        "case); '-' reads standard input. Slicer settings are read from the file's own\n"
        "config block, then SLIC3R_* environment variables, then the options below.\n"
        "Binary G-code (PrusaSlicer .bgcode) is recognised by its content and written\n"
        "back as binary G-code unless --output-format says otherwise. A Bambu Studio /\n"
        "OrcaSlicer .gcode.3mf (a zip with Metadata/plate_N.gcode) is too: every plate\n"
        "gets supports, its .md5 and slice_info.config follow, the rest is kept.\n\nGeneral");
    general.add_options()
        ("help,h", "show this help and exit")
        ("version", "print the version and exit")
        ("output,o", po::value<std::string>(), "write here instead of rewriting INPUT in place ('-' = stdout)")
        ("output-format", po::value<std::string>(),
         "ascii or binary (Prusa .bgcode, with the input's compression when it was binary, else "
         "PrusaSlicer's: heatshrink 12/4 and MeatPack); default: the input's format, recognised by content")
        ("method", po::value<std::string>()->default_value("scaffold"),
         "scaffold: bridges and pillars (Dumas et al. 2014); pillars: vertical pillars only; "
         "none: pass the file through unchanged")
        ("report", po::value<std::string>(), "write a JSON report (points, pillars, bridges, dropped points with their positions, filament, timings) to FILE")
        ("dump-points", po::value<std::string>(), "write the support points as JSON to FILE")
        ("dump-layers", po::value<std::string>(), "write one SVG per layer with an overhang into DIR")
        ("preview", po::value<std::string>(), "write an SVG picture of the planned scaffold to FILE")
        ("set", po::value<std::vector<std::string>>()->composing(),
         "override a slicer setting, KEY=VALUE (e.g. --set retract_length=1.5); repeatable")
        ("threads", po::value<int>(),
         "threads for planning: a plate's independent groups of objects, or one object's bar search (default: "
         "every core, at most 4 for one object; 1 uses the least memory, as on a Raspberry Pi; the output is the "
         "same for any count)")
        ("whole-plate",
         "plan a plate of exact copies (a slicer's instances of one object) as a whole, as any other plate; by "
         "default one copy is planned, clear of its neighbours as every copy sees them, and its plan moved to the others "
         "(--dump-points and --dump-layers then show that copy's)")
        ("check",
         "after writing, judge the output as scaffold-check does against the input (every overhang held, columns "
         "stiff enough to stand, no collisions, the model untouched; with this run's --xy-gap, --overhang-angle, "
         "--resolution and --min-stiffness) and warn with each reason it would fail; the output is kept either way. "
         "Adds the validator's time (0.3-0.5 s on the corpus models)")
        ("verbose,v", "log each stage and its timing")
        ("quiet,q", "log errors only");
    po::options_description detect("Overhang detection");
    detect.add_options()
        ("resolution", po::value<std::string>(), ("raster cell size, mm (default " + num(d.resolution) + ")").c_str())
        ("overhang-angle", po::value<std::string>(), ("steepest self-supporting wall, degrees from vertical (default " + num(d.overhang_angle_deg) + ")").c_str())
        ("max-bridge", po::value<std::string>(), "longest straight span a bead may cross between held ends without support, mm (default: the slicer's max_bridge_length, else 10); the slicer's marked bridges span up to 30")
        ("min-overhang-area", po::value<std::string>(), ("ignore lone overhang regions smaller than this, mm^2 (default " + num(d.min_overhang_area) + "; one that continues over two or more layers always counts; 0 supports every speck)").c_str())
        ("point-spacing", po::value<std::string>(), ("grid spacing of support points, mm (default " + num(d.point_spacing) + ")").c_str())
        ("point-radius", po::value<std::string>(), ("radius of overhang one point holds, mm (default " + num(d.point_radius) + ")").c_str());
    po::options_description geom("Support geometry");
    geom.add_options()
        ("xy-gap", po::value<std::string>(), ("horizontal clearance between support and model, mm (default " + num(d.xy_gap) + ")").c_str())
        ("top-gap-layers", po::value<std::string>(), ("empty layers between a pillar tip and the overhang (default " + num(d.top_gap_layers) + ")").c_str())
        ("pillar-radius", po::value<std::string>(), ("outer radius of a pillar, mm (default " + num(d.pillar_radius) + ")").c_str())
        ("tip-length", po::value<std::string>(), ("length of the tapered tip under the overhang, mm (default " + num(d.tip_length) + ")").c_str())
        ("slenderness", po::value<std::string>(), ("largest pillar height / diameter before the pillar is widened (default " + num(d.slenderness) + ")").c_str())
        ("min-stiffness", po::value<std::string>(), ("columns are widened toward their base until every support island stands at least this stiff against the nozzle, N/mm (METHOD's Standing rule; default " + num(d.min_stiffness) + ", as scaffold-check's; 0 leaves them at --pillar-radius)").c_str())
        ("modulus", po::value<std::string>(), ("Young's modulus of the filament for --min-stiffness, N/mm^2 (default " + num(d.modulus) + ", PLA)").c_str())
        ("support-width", po::value<std::string>(), ("extrusion width of support lines, mm (default " + num(d.support_width) + ")").c_str())
        ("buildplate-only", "support only from the bed: points above the model are dropped and reported");
    po::options_description plan("Scaffolding planner (--method scaffold)");
    plan.add_options()
        ("bridge-min-length", po::value<std::string>(), ("shortest bridge, mm (default " + num(d.bridge_min_length) + ")").c_str())
        ("bridge-max-length", po::value<std::string>(), ("longest bridge, mm (default " + num(d.bridge_max_length) + ")").c_str())
        ("bridge-min-drop", po::value<std::string>(), ("a bridge holds points at least this far above it, mm (default " + num(d.bridge_min_drop) + ")").c_str())
        ("bridge-max-offset", po::value<std::string>(), ("... and at most this far sideways, mm (default " + num(d.bridge_max_offset) + ")").c_str())
        ("bridge-height-step", po::value<std::string>(), ("candidate bridge heights below each point, mm (default " + num(d.bridge_height_step) + ")").c_str());
    po::options_description hidden;
    hidden.add_options()("input", po::value<std::string>());
    po::options_description all;
    all.add(general).add(detect).add(geom).add(plan).add(hidden);
    po::options_description visible;
    visible.add(general).add(detect).add(geom).add(plan);
    po::positional_options_description pos;
    pos.add("input", 1);

    po::variables_map vm;
    try {
        po::store(po::command_line_parser(argc, argv).options(all).positional(pos).run(), vm);
        po::notify(vm);
    } catch (const po::error& e) {
        logger->error("{} (see --help)", e.what());
        return 2;
    }
    if (vm.count("help")) {
        std::cout << visible << "\nExit status: 0 on success, 1 on bad input or settings, 2 on bad usage.\n";
        return 0;
    }
    if (vm.count("version")) {
        std::cout << "scaffold " << SCAFFOLD_VERSION << "\n";
        return 0;
    }
    if (!vm.count("input")) {
        logger->error("no input file given (see --help)");
        return 2;
    }
    if (vm.count("quiet")) logger->set_level(spdlog::level::err);
    if (vm.count("verbose")) logger->set_level(std::getenv("SCAFFOLD_TRACE") ? spdlog::level::trace : spdlog::level::debug);

    scaffold::cli::Request req;
    req.input = vm["input"].as<std::string>();
    req.output = vm.count("output") ? vm["output"].as<std::string>() : req.input;
    for (const char* key : {"report", "dump-points", "dump-layers", "preview"})
        if (vm.count(key)) req.files[key] = vm[key].as<std::string>();
    req.overrides["--method"] = vm["method"].as<std::string>();
    if (vm.count("output-format")) {
        req.output_format = vm["output-format"].as<std::string>();
        if (req.output_format != "ascii" && req.output_format != "binary") {
            logger->error("--output-format must be ascii or binary, got '{}' (see --help)", req.output_format);
            return 2;
        }
    }
    if (vm.count("threads")) {
        req.threads = vm["threads"].as<int>();
        if (req.threads < 1) {
            logger->error("--threads must be at least 1, got {} (see --help)", req.threads);
            return 2;
        }
    }
    if (vm.count("whole-plate")) req.plan_copies = false;
    if (vm.count("check")) req.check = true;
    for (const auto& o : detect.options()) {
        const std::string& n = o->long_name();
        if (vm.count(n)) req.overrides["--" + n] = vm[n].as<std::string>();
    }
    for (const auto* group : {&geom, &plan})
        for (const auto& o : group->options()) {
            const std::string& n = o->long_name();
            if (!vm.count(n)) continue;
            req.overrides["--" + n] = n == "buildplate-only" ? "1" : vm[n].as<std::string>();
        }
    if (vm.count("set")) {
        for (const std::string& kv : vm["set"].as<std::vector<std::string>>()) {
            std::size_t eq = kv.find('=');
            if (eq == std::string::npos || eq == 0) {
                logger->error("--set expects KEY=VALUE, got '{}'", kv);
                return 2;
            }
            req.slicer_overrides[kv.substr(0, eq)] = kv.substr(eq + 1);
        }
    }
    // Tests make a short run show its progress lines.
    if (const char* after = std::getenv("SCAFFOLD_PROGRESS_AFTER")) req.progress_after_s = std::strtod(after, nullptr);
    try {
        scaffold::cli::run(req, *logger);
    } catch (const scaffold::Error& e) {
        logger->error("{}", e.what());
        return 1;
    } catch (const std::bad_alloc&) {
        logger->error("out of memory");
        return 1;
    } catch (const std::exception& e) {
        logger->error("internal error: {}", e.what());
        return 1;
    }
    return 0;
}
