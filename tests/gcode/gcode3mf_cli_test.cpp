// The scaffold and scaffold-check programs on Bambu Studio's .gcode.3mf:
// each plate as the plain G-code path makes it, everything else as it was,
// refusals in one line with the input untouched. Archives are packed here
// from the suite's own Bambu-dialect G-code (tests/support/gcode3mf), and,
// when ../shared is present, from the real Bambu Studio and OrcaSlicer files
// of its corpus/wild.
#include <gtest/gtest.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <memory>
#include <numbers>
#include <sstream>

#include "gcode/archive.hpp"
#include "support/files.hpp"
#include "support/gcode3mf.hpp"

using namespace scaffold::testing;
namespace fs = std::filesystem;
namespace archive = scaffold::gcode::archive;

namespace {

bool have_programs() {
    return fs::exists(std::string(SCAFFOLD_BINARY_DIR) + "/scaffold") &&
           fs::exists(std::string(SCAFFOLD_BINARY_DIR) + "/scaffold-check");
}

std::unique_ptr<scaffold::testing::TempPath> dir_for(const std::string& test) {
    auto d = std::make_unique<scaffold::testing::TempPath>("gcode3mf_" + test);
    fs::remove_all(d->path);
    fs::create_directories(d->path);
    return d;
}

// Runs a program of the build with `args` (a shell line); its stderr in *err.
int run(const std::string& program, const std::string& args, std::string* err = nullptr, const std::string& env = "") {
    // One per test: ctest runs the tests of this file side by side.
    const std::string err_file = scaffold::testing::temp_path(std::string("gcode3mf_stderr_") +
                                 ::testing::UnitTest::GetInstance()->current_test_info()->name() + ".txt");
    std::string cmd = env + " " + std::string(SCAFFOLD_BINARY_DIR) + "/" + program + " " + args + " 2> " + err_file;
    int rc = std::system(cmd.c_str());
    if (err) *err = load_file(err_file);
    std::remove(err_file.c_str());
    return WIFEXITED(rc) ? WEXITSTATUS(rc) : -1;
}

std::size_t lines(const std::string& s) { return static_cast<std::size_t>(std::count(s.begin(), s.end(), '\n')); }

const RawMember* member(const std::vector<RawMember>& m, const std::string& name) {
    for (const RawMember& r : m)
        if (r.name == name) return &r;
    return nullptr;
}

double attribute(const std::string& text, std::size_t from, const std::string& key) {
    std::size_t p = text.find(key + "=\"", from);
    return p == std::string::npos ? -1 : std::strtod(text.c_str() + p + key.size() + 2, nullptr);
}

// Checks `out` (scaffold's output for archive `in`) against scaffold run on
// each plate extracted: the same bytes, the .md5 in Bambu's form, every
// other member as stored but slice_info.config; returns the support mm of
// each plate (its header line).
std::vector<double> expect_plates_as_plain(const std::string& dir, const std::string& in, const std::string& out) {
    std::vector<RawMember> a = unpack(in), b = unpack(out);
    EXPECT_FALSE(a.empty());
    EXPECT_EQ(a.size(), b.size());
    std::vector<double> support;
    for (std::size_t i = 0; i < a.size() && i < b.size(); ++i) {
        SCOPED_TRACE(a[i].name);
        EXPECT_EQ(b[i].name, a[i].name);
        EXPECT_EQ(b[i].method, a[i].method);
        EXPECT_EQ(b[i].dos_date, a[i].dos_date);
        const int plate = archive::plate_number(a[i].name);
        if (plate > 0) {
            const std::string p = dir + "/plate_" + std::to_string(plate);
            write_file(p + ".gcode", a[i].data);
            EXPECT_EQ(run("scaffold", "-q " + p + ".gcode -o " + p + ".out.gcode"), 0);
            EXPECT_TRUE(b[i].data == load_file(p + ".out.gcode"))
                << "the plate differs from the plain G-code path's output";
            const RawMember* md5 = member(b, a[i].name + ".md5");
            EXPECT_TRUE(md5 != nullptr);
            if (md5) {
                EXPECT_EQ(md5->data, archive::md5_hex(b[i].data));  // uppercase, 32 bytes, no newline
            }
            std::size_t at = b[i].data.find("; scaffold: support filament used [mm] = ");
            EXPECT_NE(at, std::string::npos);
            support.push_back(at == std::string::npos ? 0 : std::strtod(b[i].data.c_str() + at + 41, nullptr));
        } else if (archive::plate_number(a[i].name.substr(0, a[i].name.size() - 4)) == 0 &&
                   a[i].name != "Metadata/slice_info.config") {
            EXPECT_TRUE(b[i].raw == a[i].raw) << "not copied as stored";
        }
    }
    return support;
}

}  // namespace

TEST(Gcode3mfCli, PlatesAsThePlainPathOtherMembersAsStored) {
    if (!have_programs()) GTEST_SKIP() << "skipped: no scaffold program in " << SCAFFOLD_BINARY_DIR;
    const auto dir_tmp = dir_for("plates");
    const std::string& dir = dir_tmp->path;
    const std::vector<std::string> plates = {bambu_gcode({}), bambu_gcode({false, false, 150, 60})};
    const std::string in = pack(bambu_members(plates));
    write_file(dir + "/in.gcode.3mf", in);
    ASSERT_EQ(run("scaffold", "-q " + dir + "/in.gcode.3mf -o " + dir + "/out.gcode.3mf"), 0);
    const std::string out = load_file(dir + "/out.gcode.3mf");
    std::vector<double> support = expect_plates_as_plain(dir, in, out);
    ASSERT_EQ(support.size(), 2u);
    EXPECT_GT(support[0], 10.0) << "the shelf of plate 1 got no support";
    EXPECT_EQ(support[1], 0.0);
    // slice_info.config: plate 1's filament and time raised by its support.
    const std::string info = member(unpack(out), "Metadata/slice_info.config")->data;
    const std::size_t p1 = info.find("<plate>"), p2 = info.find("<plate>", p1 + 1);
    EXPECT_NEAR(attribute(info, p1, "used_m"), 1.03 + support[0] / 1000, 0.006);
    EXPECT_NEAR(attribute(info, p1, "used_g"), 3.10 * attribute(info, p1, "used_m") / 1.03, 0.011);
    EXPECT_GT(attribute(info.substr(info.find("prediction", p1)), 0, "value"), 552);
    EXPECT_EQ(attribute(info, p2, "used_m"), 1.03);
    // Every plate passes the checker, against the input's plate.
    std::string report;
    EXPECT_EQ(run("scaffold-check", "--min-stiffness 0 " + dir + "/out.gcode.3mf --original " + dir + "/in.gcode.3mf > " + dir + "/check.txt"),
              0)
        << load_file(dir + "/check.txt");
    EXPECT_NE(load_file(dir + "/check.txt").find("== Metadata/plate_2.gcode"), std::string::npos);

    // In place, through stdin and stdout, and under any name: the same bytes.
    fs::copy_file(dir + "/in.gcode.3mf", dir + "/inplace.gcode.3mf");
    ASSERT_EQ(run("scaffold", "-q " + dir + "/inplace.gcode.3mf"), 0);
    EXPECT_TRUE(load_file(dir + "/inplace.gcode.3mf") == out);
    ASSERT_EQ(run("scaffold", "-q - < " + dir + "/in.gcode.3mf > " + dir + "/piped.3mf"), 0);
    EXPECT_TRUE(load_file(dir + "/piped.3mf") == out);
    fs::copy_file(dir + "/in.gcode.3mf", dir + "/sliced.gcode");
    ASSERT_EQ(run("scaffold", "-q " + dir + "/sliced.gcode"), 0);
    EXPECT_TRUE(load_file(dir + "/sliced.gcode") == out);
    // Side files: one per plate when there are several.
    ASSERT_EQ(run("scaffold", "-q " + dir + "/in.gcode.3mf -o " + dir + "/rep.gcode.3mf --report " + dir + "/r.json"),
              0);
    EXPECT_TRUE(load_file(dir + "/rep.gcode.3mf") == out);
    EXPECT_NE(load_file(dir + "/r.plate_1.json").find("\"points\": "), std::string::npos);
    EXPECT_NE(load_file(dir + "/r.plate_2.json").find("(Metadata/plate_2.gcode)"), std::string::npos);
    EXPECT_FALSE(fs::exists(dir + "/r.json"));
    // --method none: the archive byte for byte.
    ASSERT_EQ(run("scaffold", "-q --method none " + dir + "/in.gcode.3mf -o " + dir + "/none.gcode.3mf"), 0);
    EXPECT_TRUE(load_file(dir + "/none.gcode.3mf") == in);
    // OrcaSlicer's hook names the final .gcode.3mf: the input decides.
    ASSERT_EQ(run("scaffold", "-q " + dir + "/in.gcode.3mf -o " + dir + "/env.gcode.3mf", nullptr,
                  "SLIC3R_PP_OUTPUT_NAME=" + dir + "/final.gcode.3mf"),
              0);
    EXPECT_TRUE(load_file(dir + "/env.gcode.3mf") == out);
    for (const auto& e : fs::directory_iterator(dir))
        EXPECT_EQ(e.path().string().find(".tmp"), std::string::npos) << e.path();
}

// OrcaSlicer runs its scripts on the plate's plain G-code with
// SLIC3R_PP_OUTPUT_NAME naming a .gcode.3mf: plain G-code in, plain out, the
// slicer's first header line still first.
TEST(Gcode3mfCli, OrcaHookOnTheTemporaryPlainPlate) {
    if (!have_programs()) GTEST_SKIP() << "skipped: no scaffold program in " << SCAFFOLD_BINARY_DIR;
    const auto dir_tmp = dir_for("orca_hook");
    const std::string& dir = dir_tmp->path;
    const std::string plate = bambu_gcode({});
    write_file(dir + "/plate.gcode", plate);
    write_file(dir + "/tmp_plate.gcode", plate);
    ASSERT_EQ(run("scaffold", "-q " + dir + "/plate.gcode -o " + dir + "/plain.gcode"), 0);
    ASSERT_EQ(run("scaffold", "-q " + dir + "/tmp_plate.gcode", nullptr,
                  "SLIC3R_PP_OUTPUT_NAME=" + dir + "/plate_1.gcode.3mf"),
              0);
    const std::string out = load_file(dir + "/tmp_plate.gcode");
    EXPECT_TRUE(out == load_file(dir + "/plain.gcode"));
    EXPECT_EQ(out.substr(0, out.find('\n')), "; HEADER_BLOCK_START");
    EXPECT_FALSE(fs::exists(dir + "/plate_1.gcode.3mf"));
}

TEST(Gcode3mfCli, HeaderBlockTotalsRaisedByTheSupport) {
    // Bambu Studio's header block is what Moonraker and the printer read
    // (its "volume [cm^3]" holds mm^3): each total grows by the support's
    // filament, as the "; filament used" lines at the end do.
    if (!have_programs()) GTEST_SKIP() << "skipped: no scaffold program in " << SCAFFOLD_BINARY_DIR;
    const auto dir_tmp = dir_for("header_totals");
    const std::string& dir = dir_tmp->path;
    const std::string plate = bambu_gcode({});
    write_file(dir + "/plate.gcode", plate);
    ASSERT_EQ(run("scaffold", "-q " + dir + "/plate.gcode -o " + dir + "/out.gcode"), 0);
    const std::string out = load_file(dir + "/out.gcode");
    auto value = [](const std::string& text, const std::string& key) {
        const std::size_t at = text.find(key);
        return at == std::string::npos ? -1.0 : std::strtod(text.c_str() + at + key.size(), nullptr);
    };
    const double support = value(out, "; scaffold: support filament used [mm] = ");
    ASSERT_GT(support, 10.0);
    const double area = std::numbers::pi * 0.875 * 0.875;  // mm^2 of 1.75 mm filament
    EXPECT_NEAR(value(out, "; total filament length [mm] : "), value(plate, "; total filament length [mm] : ") + support,
                0.011);
    // (The support length is read back with 2 decimals: up to 0.005 mm off,
    // 0.012 mm^3 once times the area, and the total is written with 2.)
    EXPECT_NEAR(value(out, "; total filament volume [cm^3] : "),
                value(plate, "; total filament volume [cm^3] : ") + support * area, 0.005 * area + 0.0051);
    EXPECT_NEAR(value(out, "; total filament weight [g] : "),
                value(plate, "; total filament weight [g] : ") + support * area / 1000 * 1.26, 0.011);
    EXPECT_NEAR(value(out, "; filament used [mm] = "), value(out, "; total filament length [mm] : "), 0.011);
}

TEST(Gcode3mfCli, VasePlateRefusesTheWholeFile) {
    if (!have_programs()) GTEST_SKIP() << "skipped: no scaffold program in " << SCAFFOLD_BINARY_DIR;
    const auto dir_tmp = dir_for("vase");
    const std::string& dir = dir_tmp->path;
    BambuPlate vase;
    vase.spiral = true;
    const std::string in = pack(bambu_members({bambu_gcode({}), bambu_gcode(vase)}));
    write_file(dir + "/v.gcode.3mf", in);
    std::string err;
    EXPECT_EQ(run("scaffold", dir + "/v.gcode.3mf", &err), 1);
    EXPECT_EQ(lines(err), 1u) << err;
    EXPECT_NE(err.find("Metadata/plate_2.gcode"), std::string::npos) << err;
    EXPECT_NE(err.find("spiral vase"), std::string::npos) << err;
    EXPECT_TRUE(load_file(dir + "/v.gcode.3mf") == in);
}

TEST(Gcode3mfCli, BadArchivesOneLineInputUntouched) {
    if (!have_programs()) GTEST_SKIP() << "skipped: no scaffold program in " << SCAFFOLD_BINARY_DIR;
    const auto dir_tmp = dir_for("bad");
    const std::string& dir = dir_tmp->path;
    const std::string good = pack(bambu_members({bambu_gcode({})}));
    std::vector<ZipMember> dotdot = bambu_members({bambu_gcode({})});
    dotdot.push_back({"../../outside.txt", "x"});
    std::string liar = good;  // plate_1.gcode says it is 1000 bytes in both headers
    for (const char* sig : {"PK\3\4", "PK\1\2"}) {
        std::size_t h = liar.find(sig);
        const std::size_t name_at = std::string(sig) == "PK\3\4" ? 30 : 46,
                          size_at = std::string(sig) == "PK\3\4" ? 22 : 24;
        while (liar.compare(h + name_at, 22, "Metadata/plate_1.gcode") != 0 || liar[h + name_at + 22] == '.')
            h = liar.find(sig, h + 4);
        for (int i = 0; i < 4; ++i) liar[h + size_at + i] = static_cast<char>(1000 >> (8 * i));
    }
    std::string binary(4000, '\0');
    for (std::size_t i = 0; i < binary.size(); ++i) binary[i] = static_cast<char>(i * 7919 % 251);
    struct Case {
        std::string what, bytes, says;
    };
    const std::vector<Case> cases = {
        {"not a zip", binary, "not a zip archive"},
        {"a zip's signature, then junk", std::string("PK\3\4") + std::string(200, '\x7f'), "truncated"},
        {"no plate", pack({{"3D/3dmodel.model", "<model/>"}, {"Metadata/project_settings.config", "{}"}}),
         "no Metadata/plate_N.gcode"},
        {"truncated", good.substr(0, good.size() * 2 / 3), "truncated"},
        {"dot-dot member", pack(dotdot), "'..' path"},
        {"sizes that lie", liar, "CRC"},
        // 1.1 GiB of zeros in about 1 MiB: refused before it is inflated.
        {"zip bomb", pack({{"Metadata/plate_1.gcode", "", 8, std::uint64_t{1100} << 20}}), "beyond the 1024 MiB"},
    };
    for (const auto& [what, bytes, says] : cases) {
        SCOPED_TRACE(what);
        const std::string f = dir + "/bad.gcode.3mf";
        write_file(f, bytes);
        std::string err;
        // Bounded memory: within 800 MB of address space, less than the bomb.
        EXPECT_EQ(run("scaffold", f, &err, "ulimit -v 800000;"), 1);
        EXPECT_EQ(lines(err), 1u) << err;
        EXPECT_NE(err.find(says), std::string::npos) << err;
        EXPECT_TRUE(load_file(f) == bytes) << "the input was changed";
        EXPECT_EQ(run("scaffold-check", f + " > /dev/null", &err), 2) << err;
        EXPECT_EQ(lines(err), 1u) << err;
    }
    for (const auto& e : fs::directory_iterator(dir)) EXPECT_EQ(e.path().filename(), "bad.gcode.3mf");
}

TEST(Gcode3mfCli, Md5MismatchOnInputWarnsAndGoesOn) {
    if (!have_programs()) GTEST_SKIP() << "skipped: no scaffold program in " << SCAFFOLD_BINARY_DIR;
    const auto dir_tmp = dir_for("md5");
    const std::string& dir = dir_tmp->path;
    std::vector<ZipMember> m = bambu_members({bambu_gcode({})});
    for (ZipMember& z : m)
        if (z.name == "Metadata/plate_1.gcode.md5") z.data = std::string(32, '0');
    write_file(dir + "/m.gcode.3mf", pack(m));
    std::string err;
    ASSERT_EQ(run("scaffold", dir + "/m.gcode.3mf -o " + dir + "/out.gcode.3mf", &err), 0);
    EXPECT_NE(err.find("warning"), std::string::npos) << err;
    EXPECT_NE(err.find("plate_1.gcode.md5) does not match"), std::string::npos) << err;
    std::vector<RawMember> out = unpack(load_file(dir + "/out.gcode.3mf"));
    EXPECT_EQ(member(out, "Metadata/plate_1.gcode.md5")->data,
              archive::md5_hex(member(out, "Metadata/plate_1.gcode")->data));
}

// Real Bambu Studio and OrcaSlicer plates (../shared/corpus/wild, third-party
// files read in place, never copied into the project), packed as Bambu
// Studio packs a plate file.
TEST(Gcode3mfCli, WildBambuAndOrcaPlates) {
    if (!have_programs()) GTEST_SKIP() << "skipped: no scaffold program in " << SCAFFOLD_BINARY_DIR;
    const fs::path wild = fs::path(SCAFFOLD_SOURCE_DIR) / ".." / "shared" / "corpus" / "wild";
    if (!fs::exists(wild / "MANIFEST.tsv"))
        GTEST_SKIP() << "skipped: no " << wild.string() << " (real-world files; CI has them)";
    std::ifstream manifest(wild / "MANIFEST.tsv");
    std::string line;
    int n = 0;
    while (std::getline(manifest, line)) {
        const std::string name = line.substr(0, line.find('\t'));
        if (name.rfind("bambustudio", 0) != 0 && name.rfind("orcaslicer", 0) != 0) continue;
        SCOPED_TRACE(name);
        const auto dir_tmp = dir_for("wild_" + name);
        const std::string& dir = dir_tmp->path;
        const std::string plate = load_file((wild / (name + ".gcode.gz")).string());
        ASSERT_FALSE(plate.empty());
        const std::string in = pack(bambu_members({plate}));
        write_file(dir + "/in.gcode.3mf", in);
        ASSERT_EQ(run("scaffold", "-q " + dir + "/in.gcode.3mf -o " + dir + "/out.gcode.3mf"), 0);
        expect_plates_as_plain(dir, in, load_file(dir + "/out.gcode.3mf"));
        EXPECT_EQ(
            run("scaffold-check", "--min-stiffness 0 " + dir + "/out.gcode.3mf --original " + dir + "/in.gcode.3mf > " + dir + "/check.txt"),
            0)
            << load_file(dir + "/check.txt");
        ASSERT_EQ(run("scaffold", "-q --method none " + dir + "/in.gcode.3mf -o " + dir + "/none.gcode.3mf"), 0);
        EXPECT_TRUE(load_file(dir + "/none.gcode.3mf") == in);
        ++n;
    }
    EXPECT_EQ(n, 4) << "Bambu Studio and OrcaSlicer files in the manifest";
}
