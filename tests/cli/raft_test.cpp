// A print on the slicer's raft: Cura leaves an air gap of more than two
// layers between the raft's top and the model's first layer, so a column
// started on that layer would stand on nothing METHOD's Standing rule can
// follow down (its path looks for support within two nominal layers). The
// column is bonded to the raft by loops printed in the gap.
#include <gtest/gtest.h>

#include <algorithm>
#include <string>

#include "check/printability.hpp"
#include "gcode/reader.hpp"
#include "support/run.hpp"
#include "support/synth.hpp"

using namespace scaffold;

namespace {

// A 40 x 40 mm raft of three layers (typed support, as Cura types its
// raft) at z 0.3, 0.55 and 0.8; the model's first layer at 0.8 + gap; on it
// a mushroom: a stem of radius 2.5 and, from 3 mm above the raft, a cap of
// radius 6. The model's layers say they are 0.2 mm high, the first as
// well (as a slicer states a layer's own height, not the gap under it).
std::string on_raft(double gap, double overlap = 0) {
    scaffold::testing::SynthGcode g;
    g.width(0.45);
    for (double z : {0.3, 0.55, 0.8}) {
        g.layer(z);
        g.type("Support material");
        g.filled_rect(80, 85, 120, 125);
    }
    const double z0 = 0.8 + gap;
    for (int l = 0; l < 20; ++l) {
        const double z = z0 + 0.2 * l - (l > 0 ? overlap : 0.0);
        g.layer(z, 0.2);
        g.type("External perimeter");
        g.filled_disc(100, 105, z > 0.8 + 3.0 + 1e-9 ? 6.0 : 2.5);
    }
    return g.str();
}


check::CheckReport checked(const std::string& out, const std::string& in) {
    const auto o = gcode::parse(out, "out.gcode");
    const auto i = gcode::parse(in, "in.gcode");
    return check::check(o, &i, check::CheckOptions{});
}

// The lines of `out` between "; scaffold: support for the layer at Z<z>" and
// its end, or empty.
std::string block_at(const std::string& out, const std::string& z) {
    const std::string head = "; scaffold: support for the layer at Z" + z + "\n";
    const std::size_t at = out.find(head);
    if (at == std::string::npos) return {};
    return out.substr(at, out.find("; scaffold: end", at) - at);
}

}  // namespace

// Gap 0.55 mm (Cura's 0.3 mm air gap under a 0.25 mm first layer): the
// columns start with a bond at z 1.075, halfway, printed before the
// model's first layer at 1.35, and every island stands.
TEST(Raft, ColumnsOverAnAirGapAreBondedToTheRaft) {
    const std::string in = on_raft(0.55);
    const std::string out = scaffold::testing::scaffolded(in);
    const std::string bond = block_at(out, "1.075");
    ASSERT_FALSE(bond.empty()) << "no bond block at z 1.075";
    // Printed at its own height before the model's first layer, whose
    // first bead follows it.
    EXPECT_NE(bond.find("G1 Z1.075"), std::string::npos) << bond;
    EXPECT_LT(out.find(bond), out.find(";TYPE:External perimeter"));
    const check::CheckReport r = checked(out, in);
    EXPECT_EQ(r.standing.added.floating, 0) << check::report_text(r);
    EXPECT_TRUE(r.ok()) << check::report_text(r);
}

// Cura 4.13 prints the model's second layer over the raft 0.02 mm under
// its first (1.30, then 1.28). The bond goes under the lower, at 1.04,
// before the first; no block is printed more than those 0.02 mm under one
// printed before it, and every island stands.
TEST(Raft, ABondGoesUnderTheLowerOfTwoLayersPrintedOutOfOrder) {
    const std::string in = on_raft(0.5, 0.22);
    const std::string out = scaffold::testing::scaffolded(in);
    const std::string head = "; scaffold: support for the layer at Z";
    double last = 0;
    int blocks = 0;
    for (std::size_t at = out.find(head); at != std::string::npos; at = out.find(head, at + 1)) {
        const double z = std::stod(out.substr(at + head.size(), 8));
        EXPECT_GE(z, last - 0.021) << "a block at z " << z << " after one at " << last;
        last = std::max(last, z);
        ++blocks;
    }
    EXPECT_GT(blocks, 5);
    const std::string bond = block_at(out, "1.04");
    ASSERT_FALSE(bond.empty()) << "no bond halfway between 0.8 and 1.28";
    EXPECT_LT(out.find(bond), out.find(";TYPE:External perimeter"));
    const check::CheckReport r = checked(out, in);
    EXPECT_TRUE(r.ok()) << check::report_text(r);
}

// A gap of 0.3 mm (PrusaSlicer's raft contact distance) is within the
// rule's two layers: no bond.
TEST(Raft, AGapOfOneAndAHalfLayersNeedsNoBond) {
    const std::string in = on_raft(0.3);
    const std::string out = scaffold::testing::scaffolded(in);
    EXPECT_EQ(out.find("G1 Z0.95"), std::string::npos);
    const check::CheckReport r = checked(out, in);
    EXPECT_TRUE(r.ok()) << check::report_text(r);
}
