// The whole pipeline on a plate of objects far enough apart to be planned
// as independent groups: the same output for any thread count, and each
// object the support it gets alone.
#include <gtest/gtest.h>
#include <spdlog/logger.h>
#include <spdlog/sinks/ringbuffer_sink.h>

#include <cstdlib>
#include <memory>
#include <string>
#include <vector>

#include "cli/pipeline.hpp"
#include "support/synth.hpp"

using namespace scaffold;

namespace {

// Mushrooms (a cap of radius 6 on a stem of radius 2.5) at these x, y 105.
std::string mushrooms(const std::vector<double>& xs) {
    scaffold::testing::SynthGcode g;
    for (int l = 1; l <= 20; ++l) {
        const double z = 0.2 * l;
        g.layer(z);
        g.type("External perimeter");
        for (double x : xs) g.filled_disc(x, 105, z > 3.0 + 1e-9 ? 6.0 : 2.5);
    }
    return g.str();
}

struct Planned {
    std::string out;
    std::vector<std::string> log;
};

// A second thread joins at once (by default after 2 s: never on plates
// this light), with its own caches over the first's model rasters.
Planned run(std::string in, int threads) {
    auto sink = std::make_shared<spdlog::sinks::ringbuffer_sink_mt>(200);
    spdlog::logger log("plates", sink);
    log.set_level(spdlog::level::debug);
    Planned r;
    cli::Request req;
    req.input = req.output = "plate.gcode";
    req.input_text = &in;
    req.output_text = &r.out;
    req.threads = threads;
    req.second_thread_after_s = 0;
    cli::run(req, log);
    r.log = sink->last_formatted();
    return r;
}

double support_mm(const std::string& out) {
    const std::string key = "; scaffold: support filament used [mm] = ";
    const auto at = out.find(key);
    return at == std::string::npos ? -1 : std::strtod(out.c_str() + at + key.size(), nullptr);
}

bool said(const Planned& r, const std::string& what) {
    for (const std::string& line : r.log)
        if (line.find(what) != std::string::npos) return true;
    return false;
}

}  // namespace

TEST(Plates, SameOutputForAnyThreadCount) {
    const std::string plate = mushrooms({30, 110, 190});
    const Planned one = run(plate, 1), two = run(plate, 2), again = run(plate, 2);
    EXPECT_TRUE(said(one, "in 3 independent groups, planned on 1 threads"));
    EXPECT_TRUE(said(two, "in 3 independent groups, planned on 2 threads"));
    EXPECT_GT(support_mm(one.out), 0);
    EXPECT_EQ(one.out, two.out);
    EXPECT_EQ(two.out, again.out);
}

TEST(Plates, EachObjectGetsTheSupportItGetsAlone) {
    const double alone = support_mm(run(mushrooms({110}), 2).out);
    const double three = support_mm(run(mushrooms({30, 110, 190}), 2).out);
    ASSERT_GT(alone, 0);
    EXPECT_NEAR(three, 3 * alone, 0.02 * 3 * alone);
}

TEST(Plates, ObjectsWithinReachArePlannedAsOne) {
    const Planned r = run(mushrooms({100, 125}), 2);
    EXPECT_FALSE(said(r, "independent groups"));
    EXPECT_GT(support_mm(r.out), 0);
}
