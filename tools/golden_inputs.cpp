// Writes the synthetic inputs of the golden tests (golden/<case>/input.gcode)
// with the same G-code helper the unit tests use. Run by tools/golden-update.
#include <cstdio>
#include <fstream>
#include <string>

#include "support/synth.hpp"

using scaffold::testing::SynthGcode;

namespace {

void save(const std::string& dir, const std::string& name, const std::string& text) {
    std::ofstream(dir + "/" + name + "/input.gcode", std::ios::binary) << text;
}

// A 10 x 10 block with a 10 mm shelf sticking out at its top 2 mm.
std::string shelf() {
    SynthGcode g;
    for (int l = 1; l <= 30; ++l) {
        double z = 0.2 * l;
        g.layer(z);
        g.type("External perimeter");
        g.filled_rect(100, 100, 110, 110);
        if (z > 4.0 + 1e-9) g.filled_rect(110, 100, 120, 110);
    }
    return g.str();
}

// A cap of radius 6 on a stem of radius 2.5.
std::string mushroom() {
    SynthGcode g;
    for (int l = 1; l <= 20; ++l) {
        double z = 0.2 * l;
        g.layer(z);
        g.type("External perimeter");
        g.filled_disc(110, 105, z > 3.0 + 1e-9 ? 6.0 : 2.5);
    }
    return g.str();
}

// A low base, a tower on it, and a shelf from the tower over the base: the
// pillars under the shelf must stand on the base, not on the bed.
std::string two_level() {
    SynthGcode g;
    for (int l = 1; l <= 40; ++l) {
        double z = 0.2 * l;
        g.layer(z);
        g.type("External perimeter");
        if (z <= 2.0 + 1e-9) g.filled_rect(100, 100, 125, 112);
        else g.filled_rect(100, 100, 105, 112);
        if (z > 6.0 + 1e-9) g.filled_rect(105, 100, 120, 112);
    }
    return g.str();
}

}  // namespace

int main(int argc, char** argv) {
    if (argc != 2) {
        std::fprintf(stderr, "usage: golden-inputs GOLDEN_DIR\n");
        return 2;
    }
    std::string dir = argv[1];
    save(dir, "shelf-pillars", shelf());
    save(dir, "mushroom-pillars", mushroom());
    save(dir, "two-level-pillars", two_level());
    save(dir, "shelf-scaffold", shelf());
    save(dir, "mushroom-scaffold", mushroom());
    return 0;
}
