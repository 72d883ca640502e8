// Columns standing on the edge of a ledge: the bottom loop of a column on
// the model must be held by METHOD's rules (a) and (b) as the validator
// walks it, side by side, not only by the planner's vertex test (a side
// along the ledge's edge, outside the reach, is no bridge). Small nubs hang
// over the edge of a slanted slab at several distances from it; their
// pillars land on the slab's edge. With nothing forgiven, the output holds
// every bead.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <string>
#include <vector>

#include "check/printability.hpp"
#include "gcode/reader.hpp"
#include "support/run.hpp"
#include "support/synth.hpp"

using namespace scaffold;

namespace {

// A slab 6.3 mm deep (layers up to z 3) whose outer edge runs at
// `edge_deg` through (100, 100); above it, from z 6.2, nubs (discs of
// radius 0.9, three layers) each `offsets[i]` mm out from the edge
// (negative: over the slab), 9 mm apart along it and 0.6 mm apart in height.
// With `first_layer` 16 the lowest nub starts 0.4 mm over the slab: its
// tip's loop (the contact, a thin loop) is the column's bottom loop.
std::string ledge(double edge_deg, const std::vector<double>& offsets, int first_layer = 30) {
    scaffold::testing::SynthGcode g;
    g.width(0.45);
    const double a = edge_deg * std::numbers::pi / 180;
    const double ux = std::cos(a), uy = std::sin(a);  // along the edge
    const double nx = uy, ny = -ux;                    // outwards, off the slab
    const double half = 0.5 * 9.0 * static_cast<double>(offsets.size() + 1);
    auto at = [&](double along, double out, double& x, double& y) {
        x = 100 + ux * along + nx * out;
        y = 100 + uy * along + ny * out;
    };
    double x, y;
    const int top = first_layer + 3 * static_cast<int>(offsets.size());
    for (int l = 1; l <= top; ++l) {
        g.layer(0.2 * l);
        g.type("External perimeter");
        // A mast on the slab far from the edge, so that every layer has a
        // print (a slicer writes no empty layers).
        at(0, -4.5, x, y);
        g.filled_disc(x, y, 1.0);
        for (std::size_t i = 0; i < offsets.size(); ++i) {
            const int first = first_layer + 3 * static_cast<int>(i);
            if (l <= first || l > first + 3) continue;
            at(-half + 9.0 * static_cast<double>(i + 1), offsets[i], x, y);
            g.filled_disc(x, y, 0.9);
        }
        if (l > 15) continue;
        // Lines along the edge, 0.45 mm apart, from the edge inwards.
        for (int k = 0; k < 14; ++k) {
            at(-half, -0.225 - 0.45 * k, x, y);
            g.travel(x, y);
            at(half, -0.225 - 0.45 * k, x, y);
            g.extrude(x, y);
        }
    }
    return g.str();
}

// scaffold at --min-overhang-area 0 on `in`, checked with nothing forgiven.
check::CheckReport scaffolded_and_checked(const std::string& in) {
    const std::string out = scaffold::testing::scaffolded(in, {{"--min-overhang-area", "0"}});
    const auto o = gcode::parse(out, "out.gcode");
    const auto i = gcode::parse(in, "in.gcode");
    check::CheckOptions opt;
    opt.tolerance_mm2 = 0;
    opt.min_region_mm2 = 0;
    return check::check(o, &i, opt);
}

}  // namespace

TEST(Ledge, BottomLoopsOnAnEdgeAreHeldSideBySide) {
    const std::vector<double> offsets{-0.9, -0.75, -0.6, -0.45, -0.3, -0.15, 0.0, 0.15, 0.3};
    for (double edge_deg : {0.0, 30.0, 50.0, 130.0}) {
        const check::CheckReport r = scaffolded_and_checked(ledge(edge_deg, offsets));
        EXPECT_EQ(r.unheld_support_mm2, 0.0) << "edge at " << edge_deg << " deg";
        EXPECT_TRUE(r.ok()) << "edge at " << edge_deg << " deg";
    }
}

// The same with the nubs right over the slab's edge, so that a tip's own
// thin loop lands on it (bunny.slic3r13 at --min-overhang-area 0: a tip loop
// half over air passed the planner's walk at the three reaches it tried,
// while the validator, whose reach from the beads' edges lies between two
// of them, held the side's ends and not its middle, a run along the edge:
// 0.20 mm^2). The loop is now walked as the validator walks it, its
// vertices as written and the beads beneath on the validator's lattice
// (layers::path_held), and a tip whose loop is held nowhere near looks
// further. Before: 0.60 mm^2 unheld at 20 deg, 0.16 at 50; at 115 deg 0.16
// with a walk at every quarter cell of the reach (a side held, unheld,
// held sample by sample along a staircase of the validator's raster).
TEST(Ledge, TipLoopsOnAnEdgeAreHeldSideBySide) {
    const std::vector<double> offsets{-0.3, -0.2, -0.1, 0.0, 0.1, 0.2, 0.3, 0.4};
    for (double edge_deg : {0.0, 20.0, 35.0, 50.0, 115.0})
        EXPECT_EQ(scaffolded_and_checked(ledge(edge_deg, offsets, 15)).unheld_support_mm2, 0.0)
            << "edge at " << edge_deg << " deg";
}
