// scaffold-bgcode-diff: the project's half of the differential test against
// Prusa's reference binary G-code converter (an external program, driven by
// tools/bgcode-diff-fuzz). Random G-code text, biased toward the edges of
// MeatPack (letters it cannot pack, spaces it drops, long lines, block ends),
// encoded by scaffold's own encoder in every variant; and scaffold's decoder
// on files the reference encoded.
//   scaffold-bgcode-diff gen SEED COUNT DIR   writes DIR/SEED-i.gcode and
//                                             DIR/SEED-i.<variant>.bgcode
//   scaffold-bgcode-diff decode FILE.bgcode   prints scaffold's decoding
#include <cstdint>
#include <fstream>
#include <iostream>
#include <random>
#include <sstream>
#include <string>

#include "gcode/bgcode.hpp"
#include "gcode/error.hpp"
#include "gcode/text.hpp"

namespace bg = scaffold::gcode::bgcode;

// GCC 12 warns of an overlapping memcpy inside std::string's own appends of
// short literals here (a false positive, GCC bug 105651); this test tool
// only builds strings.
#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC diagnostic ignored "-Wrestrict"
#endif

namespace {

struct Variant {
    const char* name;
    bg::Compression compression;
    bg::GCodeEncoding encoding;
};
constexpr Variant kVariants[] = {
    {"none", bg::Compression::None, bg::GCodeEncoding::None},
    {"deflate", bg::Compression::Deflate, bg::GCodeEncoding::None},
    {"heatshrink11", bg::Compression::Heatshrink11, bg::GCodeEncoding::None},
    {"heatshrink12", bg::Compression::Heatshrink12, bg::GCodeEncoding::None},
    {"meatpack", bg::Compression::None, bg::GCodeEncoding::MeatPack},
    {"meatpack-comments", bg::Compression::Heatshrink12, bg::GCodeEncoding::MeatPackComments},
};

class Gen {
public:
    explicit Gen(std::uint64_t seed) : rng_(seed) {}
    int pick(int n) { return static_cast<int>(rng_() % static_cast<std::uint64_t>(n)); }
    bool chance(int percent) { return pick(100) < percent; }

    std::string number() {
        std::string s;
        if (chance(20)) s += '-';
        int kind = pick(5);
        if (kind == 0) return s + std::to_string(pick(10));
        if (kind == 1) return s + "." + std::to_string(pick(1000));
        return s + std::to_string(pick(400)) + "." + std::to_string(pick(100000));
    }
    std::string sep() {
        int k = pick(20);
        if (k < 14) return " ";
        if (k < 16) return "";
        if (k < 18) return "  ";
        return "\t";
    }
    std::string text(int max_len) {  // free text: anything but newline and 0xFF
        static const std::string common = "abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789 .:-_=\"'[](),/%*#";
        std::string s;
        int n = pick(max_len + 1);
        for (int i = 0; i < n; ++i) {
            if (chance(3)) s.push_back(static_cast<char>(1 + pick(254)));  // 0x01..0xFE
            else s.push_back(common[static_cast<std::size_t>(pick(static_cast<int>(common.size())))]);
            if (s.back() == '\n' || s.back() == '\r') s.back() = ' ';
        }
        return s;
    }
    std::string g_line() {
        static const char* heads[] = {"G1", "G0", "G1", "G1", "G2", "G3", "G92", "G28", "G29", "G4", "G10", "G11", "G90", "G91", "G21", "G80"};
        static const char letters[] = "XYZEFXYEXYZEFIJRSPWHCATKLMNOQUVDBGxyzef";
        std::string s = heads[pick(16)];
        int words = pick(chance(5) ? 40 : 6);
        for (int i = 0; i < words; ++i) {
            s += sep();
            s += letters[pick(static_cast<int>(sizeof letters) - 1)];
            if (!chance(10)) s += number();
        }
        return s;
    }
    std::string line() {
        int k = pick(100);
        std::string s;
        if (k < 60) s = g_line();
        else if (k < 70) {
            s = "M";
            s += std::to_string(pick(1000));
            if (chance(50)) s += " S", s += number();
            if (chance(30)) s += " P", s += number();
        }
        else if (k < 74) s = "M117 " + text(60);
        else if (k < 76) s = "T" + std::to_string(pick(5));
        else if (k < 86) s = ";" + text(80);
        else if (k < 89) s = "";
        else if (k < 91) s = std::string(static_cast<std::size_t>(1 + pick(4)), chance(50) ? ' ' : '\t');
        else if (k < 94) s = std::string(static_cast<std::size_t>(1 + pick(3)), ' ') + g_line();
        else if (k < 97) {
            s = "M";
            s += std::to_string(pick(1000));
            s += ' ';
            s += text(30);
        }
        else s = text(300);
        if (chance(15) && !s.empty() && s[0] != ';') s += sep() + ";" + text(40);
        if (chance(3)) s += " ";
        return s;
    }
    std::string file() {
        // Sizes around and past one 64 KiB block, so block ends are reached.
        std::size_t target = chance(30) ? static_cast<std::size_t>(60000 + pick(150000)) : static_cast<std::size_t>(200 + pick(20000));
        // The reference converter takes only what PrusaSlicer generated, with
        // printer, print and slicer metadata.
        std::string f =
            "; generated by PrusaSlicer 2.7.0 on 2026-12-01 at 00:00:00 UTC (scaffold-bgcode-diff)\n"
            "; filament_type = PLA\n; nozzle_diameter = 0.4\n"
            "; filament used [mm] = 1.0\n; estimated printing time (normal mode) = 1m 0s\n";
        bool crlf = chance(10);
        while (f.size() < target) {
            f += line();
            f += crlf ? "\r\n" : "\n";
        }
        f += "; prusaslicer_config = begin\n; layer_height = 0.2\n; prusaslicer_config = end\n";
        return f;
    }

private:
    std::mt19937_64 rng_;
};

void write_file(const std::string& path, const std::string& bytes) {
    std::ofstream out(path, std::ios::binary);
    out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
    if (!out) throw scaffold::Error(path, 0, "cannot write");
}

int gen(std::uint64_t seed, int count, const std::string& dir) {
    for (int i = 0; i < count; ++i) {
        Gen g(seed * 1000003u + static_cast<std::uint64_t>(i));
        const std::string text = g.file();
        const std::string base = dir + "/" + std::to_string(seed) + "-" + std::to_string(i);
        write_file(base + ".gcode", text);
        for (const Variant& v : kVariants) {
            bg::Settings s;
            s.gcode = v.compression;
            s.encoding = v.encoding;
            write_file(base + "." + v.name + ".bgcode", bg::encode_ascii(text, s));
        }
    }
    return 0;
}

int decode(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    std::stringstream ss;
    ss << in.rdbuf();
    bg::Decoded d = bg::decode(scaffold::gcode::Text(ss.str()), path);
    std::cout << d.ascii;
    return 0;
}

}  // namespace

int main(int argc, char** argv) {
    try {
        std::string mode = argc > 1 ? argv[1] : "";
        if (mode == "gen" && argc == 5) return gen(std::stoull(argv[2]), std::stoi(argv[3]), argv[4]);
        if (mode == "decode" && argc == 3) return decode(argv[2]);
        std::cerr << "usage: scaffold-bgcode-diff gen SEED COUNT DIR | decode FILE.bgcode\n";
        return 2;
    } catch (const std::exception& e) {
        std::cerr << "scaffold-bgcode-diff: " << e.what() << "\n";
        return 1;
    }
}
