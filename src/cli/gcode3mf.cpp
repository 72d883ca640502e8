#include "cli/gcode3mf.hpp"

#include <spdlog/sinks/ringbuffer_sink.h>

#include <cctype>
#include <map>
#include <string>
#include <vector>

#include "gcode/archive.hpp"
#include "gcode/error.hpp"
#include "gcode/writer.hpp"

namespace scaffold::cli {

namespace {

// "report.json" -> "report.plate_2.json": one side file per plate.
std::string for_plate(const std::string& file, int plate) {
    std::size_t slash = file.find_last_of("/\\");
    std::size_t dot = file.rfind('.');
    std::string tag = ".plate_" + std::to_string(plate);
    if (dot == std::string::npos || (slash != std::string::npos && dot < slash) || dot == 0) return file + tag;
    return file.substr(0, dot) + tag + file.substr(dot);
}

bool same_md5(std::string_view stored, const std::string& computed) {
    while (!stored.empty() && (stored.back() == '\n' || stored.back() == '\r' || stored.back() == ' '))
        stored.remove_suffix(1);
    if (stored.size() != computed.size()) return false;
    for (std::size_t i = 0; i < stored.size(); ++i)
        if (std::toupper(static_cast<unsigned char>(stored[i])) != computed[i]) return false;
    return true;
}

}  // namespace

Outcome run_gcode_3mf(const Request& req, const gcode::Text& bytes, spdlog::logger& log) {
    namespace archive = gcode::archive;
    const std::string path = req.input == "-" ? "<stdin>" : req.input;
    if (!req.output_format.empty())
        throw Error(path, 0, "--output-format does not apply to a .gcode.3mf: its plates stay plain G-code");
    const archive::Limits limits;
    std::uint64_t budget = limits.total_bytes;
    const archive::Archive a = archive::open(bytes, path, limits);
    const std::vector<std::size_t> plates = archive::plates(a);

    // What the plates' runs say is held back until every plate is done: a
    // plate refused after others ran leaves just its one line.
    auto held_sink = std::make_shared<spdlog::sinks::ringbuffer_sink_mt>(1024);
    spdlog::logger held(log.name(), held_sink);
    held.set_level(log.level());
    auto say_held = [&] {
        for (const auto& m : held_sink->last_raw())
            log.log(m.level, "{}", std::string_view(m.payload.data(), m.payload.size()));
    };

    std::map<std::size_t, std::string> replaced;
    std::vector<archive::PlateChange> changes;
    Outcome total;
    for (std::size_t index : plates) {
        const std::string& name = a.members[index].name;
        const int plate = archive::plate_number(name);
        std::string text = archive::read(a, index, limits, budget);
        const long md5 = archive::find(a, name + ".md5");
        // The printer checks this sum: a mismatch on input means the plate
        // was edited or damaged after slicing; the output's sum is made anew.
        if (md5 >= 0 &&
            !same_md5(archive::read(a, static_cast<std::size_t>(md5), limits, budget), archive::md5_hex(text)))
            held.warn("{} ({}.md5) does not match the plate's G-code (edited or damaged after slicing); going on", path,
                      name);
        if (plates.size() > 1) held.info("{}:", name);
        Request one = req;
        one.input = path + " (" + name + ")";
        one.input_text = &text;  // moved into the plate's run: one copy of a big plate, not two
        std::string out;
        one.output_text = &out;
        if (plates.size() > 1)
            for (auto& [kind, file] : one.files) file = for_plate(file, plate);
        const Outcome o = run(one, held);
        if (o.unchanged) continue;  // --method none
        replaced[index] = std::move(out);
        if (md5 >= 0) replaced[static_cast<std::size_t>(md5)] = archive::md5_hex(replaced[index]);
        changes.push_back({plate, o.support_mm / 1000, o.seconds_after - o.seconds_before});
        total.support_mm += o.support_mm;
        total.seconds_before += o.seconds_before;
        total.seconds_after += o.seconds_after;
    }
    if (replaced.empty()) {  // every plate unchanged: the archive's own bytes
        gcode::write_bytes(req.output, bytes);
        say_held();
        return total;
    }
    // The printer shows these per plate; raised like the G-code's own totals.
    if (long info = archive::find(a, "Metadata/slice_info.config"); info >= 0) {
        const std::string xml = archive::read(a, static_cast<std::size_t>(info), limits, budget);
        std::string raised = xml;
        for (const archive::PlateChange& c : changes) raised = archive::raise_slice_info(raised, c);
        if (raised != xml) replaced[static_cast<std::size_t>(info)] = std::move(raised);
    }
    gcode::write_bytes(req.output, archive::write(a, replaced));
    say_held();
    return total;
}

}  // namespace scaffold::cli
