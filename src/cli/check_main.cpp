// scaffold-check: judges whether a G-code file prints, from the G-code alone.
#include <boost/program_options.hpp>
#ifdef _WIN32
#include <fcntl.h>
#include <io.h>
#endif
#include <cstdio>
#include <iostream>
#include <string>
#include <utility>
#include <vector>

#include "check/printability.hpp"
#include "gcode/archive.hpp"
#include "gcode/error.hpp"
#include "gcode/reader.hpp"

namespace po = boost::program_options;

namespace {

// A plain or binary G-code file is one program; a .gcode.3mf (a zip, by
// content) one per plate, each named by its member.
std::vector<std::pair<std::string, scaffold::gcode::Program>> load(const std::string& path) {
    using namespace scaffold::gcode;
    Text bytes = Text::load(path);
    const std::string name = path == "-" ? "<stdin>" : path;
    std::vector<std::pair<std::string, Program>> out;
    if (!archive::is_zip(bytes)) {
        archive::refuse_binary_3mf(path, bytes);
        out.emplace_back("", parse(std::move(bytes), name));
        return out;
    }
    for (auto& [member, text] : archive::read_plates(bytes, name))
        out.emplace_back(member, parse(std::move(text), name + " (" + member + ")"));
    return out;
}

}  // namespace

int main(int argc, char** argv) {
#ifdef _WIN32
    (void)_setmode(_fileno(stdout), _O_BINARY);  // '\n' stays '\n': the same bytes as on Linux
#endif
    scaffold::check::CheckOptions o;
    po::options_description opts(
        "Usage: scaffold-check [options] FILE.gcode\n\n"
        "Simulates deposition layer by layer and reports what would print in mid-air\n"
        "(unheld area), support that comes within the XY gap of the model, support\n"
        "islands too weak to stand against the nozzle (--min-stiffness) and travels\n"
        "over fresh support (over support the edit added, without a lift: a failure),\n"
        "extrusion amounts that make no sense, and a print-time estimate.\n"
        "It reads only G-code:\n"
        "support is what is typed as support (;TYPE:Support material, Cura SUPPORT,\n"
        "Slic3r '; support material') or, with --original, what the original lacks.\n"
        "FILE and --original may be plain or binary G-code (.bgcode, recognised by content),\n"
        "or a Bambu Studio / OrcaSlicer .gcode.3mf: each plate is checked, against the\n"
        "original's plate of the same name.\n\n"
        "Exit status: 0 printable, 1 not printable (reasons listed), 2 bad input or usage.\n\nOptions");
    opts.add_options()
        ("help,h", "show this help and exit")
        ("original", po::value<std::string>(), "the G-code this file was made from: lines not in it are support, and every line of it must appear unchanged and in order")
        ("json", "print the report as JSON")
        ("svg", po::value<std::string>(), "draw the worst layers (model grey, support blue, unheld red) into DIR")
        ("tolerance-mm2", po::value<double>(&o.tolerance_mm2)->default_value(o.tolerance_mm2), "unheld area accepted per model as raster noise, mm^2 (about a 1 mm stretch of one bead; a plate's models are the separate pieces of its footprint)")
        ("min-region-mm2", po::value<double>(&o.min_region_mm2)->default_value(o.min_region_mm2), "lone unheld regions smaller than this (that continue none on the layers just above or below) are reported but not counted against the tolerance, mm^2: the speck rule scaffold's --min-overhang-area applies; 0 counts every unheld cell")
        ("overhang-angle", po::value<double>(&o.overhang_angle_deg)->default_value(o.overhang_angle_deg), "steepest self-supporting wall, degrees from vertical")
        ("xy-gap", po::value<double>(&o.xy_gap)->default_value(o.xy_gap), "least horizontal distance from support to model, mm")
        ("point-radius", po::value<double>(&o.point_radius)->default_value(o.point_radius), "radius a support contact tip holds, mm")
        ("bridge-limit", po::value<double>(&o.bridge_limit)->default_value(o.bridge_limit), "longest straight span of support or of a slicer-marked bridge held at both ends, mm")
        ("max-bridge", po::value<double>(&o.max_bridge), "longest straight span of any other bead held at both ends, mm (default: the file's max_bridge_length, else 10)")
        ("min-stiffness", po::value<double>(&o.standing.min_stiffness)->default_value(o.standing.min_stiffness), "METHOD's Standing rule: every support island (of 0.05 mm^2 or more) must be at least this stiff at its top against the nozzle, N/mm, as a cantilever down to its base (bed, model or a brace of three columns); 0 reports the rule without failing")
        ("modulus", po::value<double>(&o.standing.modulus)->default_value(o.standing.modulus), "Young's modulus of the filament for the Standing rule, N/mm^2 (PLA 3500)")
        ("resolution", po::value<double>(&o.resolution)->default_value(o.resolution, "0.1"), "raster cell, mm")
        ("quiet,q", "print nothing; only the exit status");
    po::options_description hidden;
    hidden.add_options()("file", po::value<std::string>());
    po::options_description all;
    all.add(opts).add(hidden);
    po::positional_options_description pos;
    pos.add("file", 1);
    po::variables_map vm;
    try {
        po::store(po::command_line_parser(argc, argv).options(all).positional(pos).run(), vm);
        po::notify(vm);
    } catch (const po::error& e) {
        std::cerr << "scaffold-check: " << e.what() << " (see --help)\n";
        return 2;
    }
    if (vm.count("help")) {
        std::cout << opts;
        return 0;
    }
    if (!vm.count("file")) {
        std::cerr << "scaffold-check: no input file given (see --help)\n";
        return 2;
    }
    if (!(o.standing.min_stiffness >= 0) || !(o.standing.modulus > 0)) {
        std::cerr << "scaffold-check: --min-stiffness must be >= 0 and --modulus > 0\n";
        return 2;
    }
    if (!(o.resolution > 0 && o.resolution <= 2)) {
        std::cerr << "scaffold-check: --resolution must be in (0, 2] mm\n";
        return 2;
    }
    try {
        auto outs = load(vm["file"].as<std::string>());
        bool have_original = vm.count("original") > 0;
        decltype(outs) originals;
        if (have_original) originals = load(vm["original"].as<std::string>());
        const bool plates = !outs.front().first.empty();
        bool ok = true;
        std::string json;
        for (const auto& [member, out] : outs) {
            const scaffold::gcode::Program* original = nullptr;
            for (const auto& [name, program] : originals)
                if (name == member || originals.size() == 1) original = &program;
            if (have_original && !original)
                throw scaffold::Error(vm["original"].as<std::string>(), 0, "has no plate " + member);
            std::string svg = vm.count("svg") ? vm["svg"].as<std::string>() : std::string();
            if (!svg.empty() && outs.size() > 1) svg += "/plate_" + std::to_string(scaffold::gcode::archive::plate_number(member));
            auto report = scaffold::check::check(out, original, o, svg);
            ok = ok && report.ok();
            if (vm.count("quiet")) continue;
            if (vm.count("json") && plates)
                json += (json.empty() ? "{\"plates\": [\n" : ",\n") + std::string("{\"member\": \"") + member +
                        "\", \"report\": " + scaffold::check::report_json(report) + "}";
            else if (vm.count("json"))
                std::cout << scaffold::check::report_json(report);
            else
                std::cout << (plates ? "== " + member + "\n" : std::string()) << scaffold::check::report_text(report);
        }
        if (!json.empty()) std::cout << json << "]}\n";
        return ok ? 0 : 1;
    } catch (const scaffold::Error& e) {
        std::cerr << "scaffold-check: " << e.what() << "\n";
        return 2;
    } catch (const std::exception& e) {
        std::cerr << "scaffold-check: internal error: " << e.what() << "\n";
        return 2;
    }
}
