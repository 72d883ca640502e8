// layers::path_held, the planner's walk of a column's bottom loop, against
// the validator itself: loops of two sizes at positions across the edge of
// a slab whose edge runs at several angles, each written as G-code on the
// layer over the slab's top and checked by scaffold-check's own code. The
// walk must hold a loop exactly where the validator does. (At three reaches
// about the validator's, the walk that was here disagreed at 115 degrees:
// a side held at both ends and not in the middle, tests/cli/ledge_test.cpp.)
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <numbers>
#include <string>
#include <vector>

#include "check/printability.hpp"
#include "gcode/reader.hpp"
#include "layers/crossing.hpp"
#include "layers/frame.hpp"
#include "layers/layer_stack.hpp"
#include "plan/pillars.hpp"
#include "support/synth.hpp"

using namespace scaffold;

namespace {

// The slab: 14 lines 0.45 mm apart inward from an edge through (100, 100)
// at `deg`, 30 mm long, layers 1-15 (top z 3.0); a mast keeps layer 16.
struct Slab {
    double ux, uy, nx, ny;  // along the edge; outwards, off the slab
    explicit Slab(double deg)
        : ux(std::cos(deg * std::numbers::pi / 180)), uy(std::sin(deg * std::numbers::pi / 180)), nx(uy), ny(-ux) {}
    std::array<double, 2> at(double along, double out) const { return {100 + ux * along + nx * out, 100 + uy * along + ny * out}; }
    // The G-code; with `loop`, that loop typed as support on layer 16.
    std::string gcode(const std::vector<std::array<double, 2>>* loop) const {
        scaffold::testing::SynthGcode g;
        g.width(0.45);
        for (int l = 1; l <= 16; ++l) {
            g.layer(0.2 * l);
            g.type("External perimeter");
            const auto m = at(0, -20);
            g.filled_disc(m[0], m[1], 1.0);
            if (l <= 15)
                for (int k = 0; k < 14; ++k) {
                    const auto a = at(-15, -0.225 - 0.45 * k), b = at(15, -0.225 - 0.45 * k);
                    g.travel(a[0], a[1]);
                    g.extrude(b[0], b[1]);
                }
            if (l == 16 && loop) {
                g.type("Support material");
                g.travel((*loop)[0][0], (*loop)[0][1]);
                for (std::size_t k = 1; k < loop->size(); ++k) g.extrude((*loop)[k][0], (*loop)[k][1]);
            }
        }
        return g.str();
    }
    // The slab's top layer as the walk takes it, in the frame `f`.
    std::vector<layers::BeadBeneath> beneath(const layers::Frame& f) const {
        std::vector<layers::BeadBeneath> beads;
        for (int k = 0; k < 14; ++k) {
            const auto a = at(-15, -0.225 - 0.45 * k), b = at(15, -0.225 - 0.45 * k);
            beads.push_back({in_frame(a[0], f.dx_um), in_frame(a[1], f.dy_um), in_frame(b[0], f.dx_um),
                             in_frame(b[1], f.dy_um), 0.45f, true});
        }
        return beads;
    }
    // A place as written (three decimals), moved into the frame whose
    // origin is `origin_um` microns on: as the planner sees it.
    static float in_frame(double v, long long origin_um) {
        return layers::as_written(static_cast<double>(std::llround(v * 1000) - origin_um) / 1000);
    }
};

}  // namespace

TEST(PathHeld, ABottomLoopIsHeldExactlyWhereTheValidatorHoldsIt) {
    Settings s;
    const double reach = 0.2 * std::tan(s.overhang_angle_deg * std::numbers::pi / 180) + s.resolution / 2;
    int held = 0, unheld = 0;
    for (double deg : {0.0, 20.0, 50.0, 115.0})
        for (double r : {0.57, 1.0}) {
            const Slab slab(deg);
            const std::string in = slab.gcode(nullptr);
            const auto i = gcode::parse(in, "in.gcode");
            // The planner walks the loop in the model's frame, and the
            // validator judges it there too (layers/frame.hpp).
            const layers::Frame f = layers::model_frame(layers::build_layers(i, s));
            for (double out = -1.2; out <= 0.9 + 1e-9; out += 0.05) {
                const auto c = slab.at(0.37, out);
                std::vector<std::array<double, 2>> loop = plan::loop_vertices(c[0], c[1], r, s.support_width);
                std::vector<std::array<float, 2>> written;
                for (auto& v : loop) {
                    v = {std::round(v[0] * 1000) / 1000, std::round(v[1] * 1000) / 1000};
                    written.push_back({Slab::in_frame(v[0], f.dx_um), Slab::in_frame(v[1], f.dy_um)});
                }
                const bool ours = layers::path_held(written, slab.beneath(f), reach, s.resolution, s.marked_bridge_limit);
                const auto o = gcode::parse(slab.gcode(&loop), "out.gcode");
                check::CheckOptions opt;
                opt.tolerance_mm2 = 0;
                opt.min_region_mm2 = 0;
                const check::CheckReport rep = check::check(o, &i, opt);
                EXPECT_EQ(ours, rep.unheld_support_mm2 == 0)
                    << "edge at " << deg << " deg, loop radius " << r << ", " << out << " mm out: validator "
                    << rep.unheld_support_mm2 << " mm^2 unheld";
                (ours ? held : unheld) += 1;
            }
        }
    // Both answers occur: the loops cross from the slab into the air.
    EXPECT_GT(held, 40);
    EXPECT_GT(unheld, 40);
}
