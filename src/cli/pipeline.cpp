#include "cli/pipeline.hpp"

#include "gcode/format.hpp"

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <future>
#include <memory>
#include <numbers>
#include <optional>
#include <thread>
#include <vector>

#include "check/printability.hpp"
#include "cli/gcode3mf.hpp"
#include "cli/plate.hpp"
#include "gcode/archive.hpp"
#include "gcode/bgcode.hpp"
#include "gcode/error.hpp"
#include "gcode/reader.hpp"
#include "gcode/writer.hpp"
#include "layers/copies.hpp"
#include "layers/objects.hpp"
#include "layers/frame.hpp"
#include "layers/layer_stack.hpp"
#include "overhang/dump.hpp"
#include "overhang/overhangs.hpp"
#include "plan/cavities.hpp"
#include "plan/groups.hpp"
#include "plan/obstacles.hpp"
#include "plan/planner.hpp"
#include "splice/splice.hpp"
#include "splice/times.hpp"
#include "toolpath/preview.hpp"
#include "toolpath/support_paths.hpp"

namespace scaffold::cli {

namespace {

struct Timings {
    std::vector<std::pair<std::string, double>> stages;  // name, seconds
    Clock::time_point t = Clock::now();
    void lap(const char* name) {
        auto now = Clock::now();
        stages.emplace_back(name, std::chrono::duration<double>(now - t).count());
        t = now;
    }
};

const char* method_name(Method m) {
    switch (m) {
        case Method::Scaffold: return "scaffold";
        case Method::Pillars: return "pillars";
        case Method::None: return "none";
    }
    return "?";
}

using gcode::fixed;

double filament_volume_cm3(double mm, double diameter) { return mm * std::numbers::pi * diameter * diameter / 4 / 1000; }

// The slicer's "filament used" totals, raised by the support's share so the
// printer's display and print-cost plugins stay right.
void update_totals(const gcode::Program& p, double add_mm, double diameter, std::vector<gcode::Edit>& edits) {
    double add_cm3 = filament_volume_cm3(add_mm, diameter);
    // Grams and cost (PrusaSlicer's, also in binary G-code's metadata) only
    // when the config gives one density and one price.
    auto config_number = [&](const char* key) {
        auto it = p.config.find(key);
        if (it == p.config.end() || it->second.find(',') != std::string::npos) return 0.0;
        return std::strtod(it->second.c_str(), nullptr);
    };
    double add_g = add_cm3 * config_number("filament_density");
    double add_cost = add_g / 1000 * config_number("filament_cost");
    for (std::uint32_t i = 0; i < p.lines.size(); ++i) {
        std::string_view t = p.line_text(i);
        if (t.empty() || t[0] != ';' ||
            (t.find("ilament used") == std::string_view::npos && t.find("ilament cost") == std::string_view::npos &&
             t.find("total filament") == std::string_view::npos && t.substr(0, 10) != ";MATERIAL:"))
            continue;
        std::string s(t);
        auto value_after = [&](std::string_view key, double& v, std::size_t& at) {
            std::size_t k = s.find(key);
            if (k == std::string::npos) return false;
            at = k + key.size();
            char* end = nullptr;
            v = std::strtod(s.c_str() + at, &end);
            return end != s.c_str() + at;
        };
        double v = 0;
        std::size_t at = 0;
        std::string repl;
        if (value_after("; filament used [mm] = ", v, at)) repl = s.substr(0, at) + fixed(v + add_mm, 2);
        else if (value_after("; filament used [cm3] = ", v, at)) repl = s.substr(0, at) + fixed(v + add_cm3, 2);
        else if (add_g > 0 && (value_after("; total filament used [g] = ", v, at) || value_after("; filament used [g] = ", v, at)))
            repl = s.substr(0, at) + fixed(v + add_g, 2);
        else if (add_cost > 0 && (value_after("; total filament cost = ", v, at) || value_after("; filament cost = ", v, at)))
            repl = s.substr(0, at) + fixed(v + add_cost, 2);
        // Bambu Studio's header block (what Moonraker and the printer read);
        // its "volume [cm^3]" holds mm^3.
        else if (value_after("; total filament length [mm] : ", v, at)) repl = s.substr(0, at) + fixed(v + add_mm, 2);
        else if (value_after("; total filament volume [cm^3] : ", v, at))
            repl = s.substr(0, at) + fixed(v + add_cm3 * 1000, 2);
        else if (add_g > 0 && value_after("; total filament weight [g] : ", v, at)) repl = s.substr(0, at) + fixed(v + add_g, 2);
        else if (value_after(";MATERIAL:", v, at))  // UltiGCode: mm^3 of the first extruder
            repl = s.substr(0, at) + std::to_string(std::lround(v + add_cm3 * 1000));
        else if (value_after(";Filament used: ", v, at)) repl = s.substr(0, at) + fixed(v + add_mm / 1000, 5) + "m";
        else if (value_after("; filament used = ", v, at))
            repl = s.substr(0, at) + fixed(v + add_mm, 1) + "mm (" + fixed(filament_volume_cm3(v + add_mm, diameter), 1) + "cm3)";
        if (repl.empty() || (s.find(',') != std::string::npos && s.find(',') > at)) continue;  // multi-extruder lists: leave
        edits.push_back({i, true, repl});
    }
    p.text.release(0, p.text.size());  // the scan touched every page; the writer reads them back piece by piece
}

// The version in scaffold's header line if the file already carries one
// (it goes after the slicer's first line; in binary G-code, at the top of
// the G-code blocks), else empty. A second run must not add support twice.
std::string processed_by(const gcode::Program& p) {
    const std::size_t first = p.binary ? p.binary->gcode_line : 0;
    constexpr std::string_view kHead = "; scaffold ";
    for (std::size_t i = first; i < p.lines.size() && i < first + 20; ++i) {
        const std::string_view t = p.line_text(i);
        if (t.rfind(kHead, 0) != 0 || t.find(" (post-processed supports)") == std::string_view::npos) continue;
        const std::string_view rest = t.substr(kHead.size());
        return std::string(rest.substr(0, rest.find(' ')));
    }
    return {};
}

gcode::OutputFormat output_format(const std::string& name) {
    if (name.empty()) return gcode::OutputFormat::SameAsInput;
    if (name == "ascii") return gcode::OutputFormat::Ascii;
    if (name == "binary") return gcode::OutputFormat::Binary;
    throw Error("--output-format must be ascii or binary (got '" + name + "')");
}



}  // namespace

Outcome run(const Request& req, spdlog::logger& log) {
    const gcode::OutputFormat format = output_format(req.output_format);
    Timings time;
    Progress progress{log, req.progress_after_s};
    gcode::Program program;
    if (req.input_text) {
        program = gcode::parse(std::move(*req.input_text), req.input);
    } else {
        gcode::Text bytes = gcode::Text::load(req.input);
        if (gcode::archive::is_zip(bytes)) return run_gcode_3mf(req, bytes, log);
        gcode::archive::refuse_binary_3mf(req.input, bytes);
        program = gcode::parse(std::move(bytes), req.input == "-" ? "<stdin>" : req.input);
    }
    time.lap("read");
    if (const std::string version = processed_by(program); !version.empty()) {
        // In place: not even rewritten (the bytes and the time stamp stay).
        if (req.output_text) *req.output_text = gcode::render_edited(program, {});
        else if (req.output != req.input || req.input == "-" || format != gcode::OutputFormat::SameAsInput)
            gcode::write_output(req.output, program, {}, format);
        log.info("{} was already processed by scaffold {} (its header line): left unchanged", program.path, version);
        Outcome same;
        same.unchanged = true;
        return same;
    }
    SettingMap cli = req.slicer_overrides;
    for (const auto& [k, v] : req.overrides) cli[k] = v;
    const Settings settings = build_settings(program, settings_from_environment(), cli);
    if (!settings.filament_note.empty() && settings.method != Method::None) log.warn("{}", settings.filament_note);
    // Rule (a) holds a bead that steps out up to h tan 55 deg (0.29 mm at
    // 0.2 mm layers); fuzzy skin's jitter steps further on every wall.
    if (settings.fuzzy_skin_mm > 0 && settings.method != Method::None)
        log.warn("fuzzy skin is on ({:.2f} mm): walls jittered this far step out past what the layer below holds, so "
                 "scaffold supports more and plans longer (a bunny: about 4 times the support, 25 times the time); "
                 "slice without fuzzy skin for the least support",
                 settings.fuzzy_skin_mm);
    log.debug("{}: {} lines, {} moves, dialect {}", program.path, program.lines.size(), program.moves.size(),
              gcode::dialect_name(program.dialect));
    if (settings.method == Method::None) {
        if (req.output_text) *req.output_text = gcode::render_edited(program, {});
        else gcode::write_output(req.output, program, {}, format);
        log.info("--method none: written unchanged");
        Outcome none;
        none.unchanged = true;
        return none;
    }
    // A vase is recognised by its setting or, where the file has none (Cura
    // hands scripts no settings), by Z rising through its extrusions.
    const layers::ZMotion zm = layers::z_motion(program);
    if (settings.spiral_vase || zm.spiral())
        throw Error(program.path, 0, "spiral vase mode is not supported: a vase is one continuous wall with no place for supports");
    // Also recognised without its setting: Z back at the bed after an object.
    if (settings.sequential_printing || zm.restarts)
        throw Error(program.path, 0, "sequential printing (complete objects) is not supported: supports would be printed "
                                     "under objects that are finished first; slice with objects printed layer by layer");
    bool big = program.text.size() > 10'000'000;
    if (big) log.info("{:.0f} MB read; finding overhangs...", static_cast<double>(program.text.size()) / 1e6);

    // Print-time change, by the validator's estimate of the output (worked
    // out from the input's moves, kept to the end for it: so only under
    // 50 MB). Never read back, so stdout, a device or a pipe get it too.
    const bool estimate_time = program.text.size() < 50'000'000;
    // Both read the moves alone: the estimate on a second thread while the
    // layers are built.
    const bool two_threads = plan::worker_count(2, req.threads) > 1;
    std::future<double> estimated_before;
    if (estimate_time && two_threads)
        estimated_before = std::async(std::launch::async, [&program] { return check::estimate_print_time(program); });
    progress.say("reading layers");
    layers::LayerStack stack = layers::build_layers(program, settings);
    double model_mm = 0, own_support_mm = 0;
    for (const auto& m : program.moves)
        if (m.kind == gcode::MoveKind::Extrude) (gcode::is_support(m.role) ? own_support_mm : model_mm) += m.e;
    // A raft or the slicer's own support (Cura's raft is typed SUPPORT,
    // Simplify3D may add support): it holds what lies on it like any
    // material, and scaffold adds only what is still unheld.
    if (own_support_mm > 0)
        log.info("the file already holds {:.0f} mm of the slicer's own support or raft: scaffold adds only what is still "
                 "needed",
                 own_support_mm);
    const double time_before = estimated_before.valid() ? estimated_before.get()
                               : estimate_time          ? check::estimate_print_time(program)
                                                        : 0;
    // Nothing below reads the moves (the splice re-lexes the lines) but
    // --check's comparison with the input and the output's print-time
    // estimate (the input's with the support's put in): else free them, the
    // largest part of a big file's memory.
    if (!req.check && !estimate_time) std::vector<gcode::Move>().swap(program.moves);
    time.lap("layers");
    // A plate of exact copies: the first copy's overhangs found and planned,
    // its plan moved to the others.
    std::optional<layers::Copies> copies;
    // The plate's objects: each planned on its own where it can be.
    std::optional<layers::ObjectMap> objects;
    if (settings.method != Method::None) objects.emplace(stack, layers::model_bead, plan::worker_count(2, req.threads));
    if (req.plan_copies && settings.method != Method::None && !stack.z_varies && own_support_mm == 0) {
        std::string why;
        copies = layers::find_copies(stack, *objects, &why, plan::worker_count(2, req.threads));
        if (!copies) log.debug("not a plate of copies: {}", why);
    }
    layers::LayerStack first_copy;
    if (copies) first_copy = layers::first_copy(stack, *copies);
    // Found, planned and made in the frame of the model (a plate's first
    // copy), then moved back: the same model gets the same support wherever
    // it stands on the bed, and a copy on a plate the support it gets alone.
    const layers::Frame frame = layers::model_frame(copies ? first_copy : stack);
    layers::move_stack(stack, frame, true);
    log.debug("planned in the model's frame: origin at ({:.3f}, {:.3f}) on the bed (the trace's places are in it)",
              frame.dx(), frame.dy());
    if (copies) {
        layers::move_stack(first_copy, frame, true);
        copies->prototype = layers::move_bounds(copies->prototype, frame, true);
    }
    time.lap("copies");
    // The model's obstacles built while its overhangs are found (they ask
    // only the layers): a plate of copies builds its own, of the plate as
    // its first copy sees it.
    std::future<std::unique_ptr<const plan::Obstacles>> early_obstacles;
    if (!copies && settings.method != Method::None && two_threads)
        early_obstacles = std::async(std::launch::async, [&] { return obstacles_of(req, stack, settings); });
    std::optional<SharedCavities> early_cavities;
    if (!copies && settings.method == Method::Scaffold && two_threads) {
        early_cavities.emplace(stack);
        early_cavities->start(plan::obstacle_grid(stack, settings), plan::worker_count(2, req.threads));
    }
    progress.say("finding overhangs");
    overhang::Overhangs overhangs = overhang::find_overhangs(copies ? first_copy : stack, settings);
    overhang::SupportPoints points = overhang::place_points(overhangs, copies ? first_copy : stack, settings);
    time.lap("overhangs");
    if (auto it = req.files.find("dump-points"); it != req.files.end())
        overhang::write_points_json(it->second, plan::moved({points, {}}, frame.dx(), frame.dy()).points);
    if (auto it = req.files.find("dump-layers"); it != req.files.end())
        overhang::write_layer_svgs(it->second, overhangs, points, copies ? first_copy : stack, settings);
    // Planning grows with the points' density, not the file's size: many
    // points may take tens of seconds (bunny.slic3r13 at --min-overhang-area
    // 0, 150 points: 17 s), so say so.
    if (big || (settings.method == Method::Scaffold && points.points.size() >= 120))
        log.info("{} support points; planning...", points.points.size());

    if (stack.z_varies && !points.points.empty())
        log.info("bed levelling is baked into the file (Z follows the bed within each layer): the support follows the "
                 "same mesh, as the model's own moves give it");

    std::optional<GroupPlanned> copied;
    if (copies && !points.points.empty()) {
        copied = plan_copies(*copies, first_copy, points, overhangs, stack, settings, log, progress, req.threads,
                             req.bar_rounds);
        if (!copied) {
            // The whole plate's overhangs, then, as for any plate.
            progress.say("finding overhangs on the whole plate");
            overhangs = overhang::find_overhangs(stack, settings);
            points = overhang::place_points(overhangs, stack, settings);
        }
    }
    first_copy = {};
    GroupPlanned planned = copied ? std::move(*copied)
                                  : plan_plate(req, points, overhangs, stack, settings, log, progress,
                                               early_obstacles.valid() ? early_obstacles.get() : nullptr,
                                               objects_of(points, objects, frame),
                                               early_cavities ? &*early_cavities : nullptr);
    early_cavities.reset();  // done, or stopped: the stack moves next
    copied.reset();
    // Back onto the bed.
    plan::GroupPlan placed = plan::moved({std::move(planned.points), std::move(planned.scaffold)}, frame.dx(), frame.dy());
    points = std::move(placed.points);
    plan::Scaffold scaffold = std::move(placed.scaffold);
    toolpath::SupportPaths paths = std::move(planned.paths);
    toolpath::move_paths(paths, frame.dx(), frame.dy());
    layers::move_stack(stack, frame, false);
    time.lap("plan");
    time.lap("toolpath");
    if (auto it = req.files.find("preview"); it != req.files.end())
        gcode::write_text_file(it->second, toolpath::preview_svg(stack, scaffold, paths, settings));
    for (layers::Layer& layer : stack.layers) std::vector<layers::Segment>().swap(layer.segments);  // drawn for the last time
    progress.say("writing the support into the G-code");
    splice::SpliceResult spliced = splice::splice(program, stack, paths, settings, plan::worker_count(2, req.threads));
    time.lap("splice");
    // The output's print time: its moves (the input's, the blocks' put in,
    // no second reading of the whole output) estimated on a second thread
    // while it is written.
    std::future<double> estimated_after;
    std::vector<gcode::Move> moves_after;
    check::MotionLimits limits;
    if (estimate_time) {
        moves_after = splice::spliced_moves(program, spliced);
        limits = check::motion_limits(program);
        if (!req.check) std::vector<gcode::Move>().swap(program.moves);
        if (two_threads)
            estimated_after = std::async(std::launch::async, [moves = std::move(moves_after), limits] {
                return check::estimate_moves(moves, limits);
            });
    }

    std::size_t pillars = 0;
    for (const auto& c : scaffold.columns) pillars += c.base == plan::Base::Bed || c.base == plan::Base::Model;
    std::string header = "; scaffold " SCAFFOLD_VERSION " (post-processed supports)\n";
    header += "; scaffold: method = " + std::string(method_name(settings.method)) + ", overhang angle = " +
              fixed(settings.overhang_angle_deg, 1) + " deg, xy gap = " + fixed(settings.xy_gap, 2) +
              " mm, point spacing = " + fixed(settings.point_spacing, 2) + " mm, resolution = " +
              fixed(settings.resolution, 3) + " mm\n";
    header += "; scaffold: points = " + std::to_string(points.points.size()) + ", pillars = " + std::to_string(pillars) +
              ", bridges = " + std::to_string(scaffold.bridges.size()) + ", dropped points = " +
              std::to_string(scaffold.dropped_points.size()) + "\n";
    // Volumetric E: mm^3 extruded, as mm of the spool's filament.
    const double e_area = std::numbers::pi * settings.filament_diameter * settings.filament_diameter / 4;
    spliced.filament_mm *= e_area / (std::numbers::pi * settings.spool_diameter * settings.spool_diameter / 4);
    header += "; scaffold: support filament used [mm] = " + fixed(spliced.filament_mm, 2) + "\n";
    header += "; scaffold: support print time = " + splice::format_dhms(spliced.seconds) + "\n";
    std::vector<splice::BlockTime> block_times;
    for (std::size_t i = 0; i < spliced.edits.size(); ++i)
        block_times.push_back({spliced.edits[i].line, spliced.block_seconds[i]});
    std::vector<gcode::Edit> edits = std::move(spliced.edits);
    edits.push_back({program.lines.empty() ? 0u : 1u, false, header});
    splice::update_times(program, std::move(block_times), edits);
    update_totals(program, spliced.filament_mm, settings.spool_diameter, edits);
    if (req.output_text) *req.output_text = gcode::render_edited(program, std::move(edits));
    else gcode::write_output(req.output, program, std::move(edits), format);
    time.lap("write");

    std::string time_change;
    Outcome outcome{spliced.filament_mm, time_before, time_before};
    if (estimate_time) {
        progress.say("estimating the print time");
        double before = time_before;
        double after = estimated_after.valid() ? estimated_after.get() : check::estimate_moves(moves_after, limits);
        outcome.seconds_after = after;
        log.debug("print time estimated: {:.3f} s before, {:.3f} s after", before, after);
        time_change = fmt::format("; print time {:.0f} -> {:.0f} min ({:+.0f} %)", before / 60, after / 60,
                                  before > 0 ? 100 * (after - before) / before : 0.0);
    }
    double grams = filament_volume_cm3(spliced.filament_mm, settings.spool_diameter) * 1.24;  // PLA density
    log.info("{} support points, {} bridges, {} pillars{}; support filament {:.1f} mm ({:.1f} g, {:.1f} % of the model){}",
             points.points.size(), scaffold.bridges.size(), pillars,
             scaffold.dropped_points.empty() ? "" : fmt::format(", {} points dropped", scaffold.dropped_points.size()),
             spliced.filament_mm, grams, model_mm > 0 ? 100 * spliced.filament_mm / model_mm : 0.0, time_change);
    if (spliced.blocks_split)
        log.warn("{} support blocks went inside an object's label block open across a layer change: cancelling that "
                 "object in the printer would drop them", spliced.blocks_split);
    for (const plan::Xyz& e : scaffold.unheld_bridge_ends)
        log.warn("a bridge end at ({:.2f}, {:.2f}, z {:.2f}) has no pillar under it: check that bridge", e.x, e.y, e.z);
    if (!scaffold.uncovered.empty()) {
        const plan::Xyz& u = *std::min_element(scaffold.uncovered.begin(), scaffold.uncovered.end(),
                                               [](const plan::Xyz& a, const plan::Xyz& b) { return a.z < b.z; });
        log.warn("{} places on overhangs rest on no support tip: no column fits under them (a narrow slot, a crotch), "
                 "the lowest at ({:.2f}, {:.2f}) on the layer at z {:.2f}; the output is written, --check (or scaffold-check) says "
                 "whether it passes",
                 scaffold.uncovered.size(), u.x, u.y, u.z);
    }
    std::optional<check::CheckReport> checked;
    if (req.check) {
        if (!req.output_text && (req.output == "-" || gcode::is_device(req.output))) {
            log.warn("--check: the output is not a file to read back; not checked");
        } else {
            progress.say("checking the output");
            const gcode::Program written =
                req.output_text ? gcode::parse(*req.output_text, program.path) : gcode::read_file(req.output);
            check::CheckOptions o;
            o.overhang_angle_deg = settings.overhang_angle_deg;
            o.xy_gap = settings.xy_gap;
            o.resolution = settings.resolution;  // the standing rule's too
            o.standing.min_stiffness = settings.min_stiffness;
            o.standing.modulus = settings.modulus;
            checked = check::check(written, &program, o);
            if (checked->ok()) {
                log.info("check: the output passes (held, standing at {} N/mm, no collisions, the model untouched)",
                         fixed(settings.min_stiffness, 2));
            } else {
                for (const std::string& f : checked->failures) log.warn("check: the output would fail: {}", f);
            }
            time.lap("check");
        }
    }
    for (const auto& [name, s] : time.stages) log.debug("stage {}: {:.1f} ms", name, s * 1000);

    if (auto it = req.files.find("report"); it != req.files.end()) {
        std::string j = "{\n";
        j += "  \"input\": " + check::json_string(program.path) + ",\n";
        j += "  \"method\": \"" + std::string(method_name(settings.method)) + "\",\n";
        j += "  \"dialect\": \"" + std::string(gcode::dialect_name(program.dialect)) + "\",\n";
        j += "  \"layers\": " + std::to_string(stack.layers.size()) + ",\n";
        j += "  \"overhang_area_mm2\": " + fixed(points.overhang_area_mm2, 2) + ",\n";
        j += "  \"points\": " + std::to_string(points.points.size()) + ",\n";
        j += "  \"pillars\": " + std::to_string(pillars) + ",\n";
        j += "  \"bridges\": " + std::to_string(scaffold.bridges.size()) + ",\n";
        j += "  \"dropped_points\": " + std::to_string(scaffold.dropped_points.size()) + ",\n";
        // Where they are, so a user can look (or add support by hand there).
        j += "  \"dropped\": [";
        for (std::size_t i = 0; i < scaffold.dropped_points.size(); ++i) {
            const auto& p = points.points[scaffold.dropped_points[i]];
            j += fmt::format("{}{{\"x\": {:.3f}, \"y\": {:.3f}, \"z\": {:.3f}, \"layer\": {}}}", i ? ", " : "", p.x, p.y, p.z,
                             p.layer);
        }
        j += "],\n";
        auto places = [&](const char* name, const std::vector<plan::Xyz>& at) {
            j += fmt::format("  \"{}\": [", name);
            for (std::size_t i = 0; i < at.size(); ++i)
                j += fmt::format("{}{{\"x\": {:.3f}, \"y\": {:.3f}, \"z\": {:.3f}}}", i ? ", " : "", at[i].x, at[i].y, at[i].z);
            j += "],\n";
        };
        places("unheld_bridge_ends", scaffold.unheld_bridge_ends);
        places("uncovered", scaffold.uncovered);
        j += "  \"support_filament_mm\": " + fixed(spliced.filament_mm, 2) + ",\n";
        j += "  \"model_filament_mm\": " + fixed(model_mm, 2) + ",\n";
        j += "  \"layers_touched\": " + std::to_string(spliced.layers_touched) + ",\n";
        if (checked) {
            j += "  \"check\": {\"ok\": " + std::string(checked->ok() ? "true" : "false") + ", \"failures\": [";
            for (std::size_t i = 0; i < checked->failures.size(); ++i)
                j += (i ? ", " : "") + check::json_string(checked->failures[i]);
            j += "]},\n";
        }
        j += "  \"seconds\": {";
        for (std::size_t i = 0; i < time.stages.size(); ++i)
            j += (i ? ", \"" : "\"") + time.stages[i].first + "\": " + fixed(time.stages[i].second, 4);
        j += "}\n}\n";
        gcode::write_text_file(it->second, j);
    }
    return outcome;
}

}  // namespace scaffold::cli
