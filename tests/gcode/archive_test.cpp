// gcode/archive: Bambu's .gcode.3mf read and written again. Archives are
// packed here (tests/support/gcode3mf) and read back with minizip directly.
#include "gcode/archive.hpp"

#include <gtest/gtest.h>

#include <cstring>

#include "gcode/error.hpp"
#include "support/files.hpp"
#include "support/gcode3mf.hpp"

using namespace scaffold::gcode;
using scaffold::testing::RawMember;
using scaffold::testing::ZipMember;

namespace {

std::vector<ZipMember> small_members() {
    return {{"[Content_Types].xml", "<Types/>"},
            {"Metadata/plate_10.gcode", "G1 X10\n"},
            {"Metadata/plate_2.png", std::string(300, 'p'), 0},
            {"Metadata/plate_2.gcode", "G1 X2\n"},
            {"Metadata/slice_info.config", "<config/>"}};
}

std::uint64_t budget_of(const archive::Limits& l) { return l.total_bytes; }

void put32(std::string& s, std::size_t at, std::uint32_t v) {
    for (int i = 0; i < 4; ++i) s[at + i] = static_cast<char>(v >> (8 * i));
}

// Offsets of a member's local header and central directory entry.
std::pair<std::size_t, std::size_t> headers_of(const std::string& zip, const std::string& name) {
    std::size_t local = zip.find(std::string("PK\3\4", 4));
    while (local != std::string::npos && zip.compare(local + 30, name.size(), name) != 0)
        local = zip.find(std::string("PK\3\4", 4), local + 4);
    std::size_t central = zip.find(std::string("PK\1\2", 4));
    while (central != std::string::npos && zip.compare(central + 46, name.size(), name) != 0)
        central = zip.find(std::string("PK\1\2", 4), central + 4);
    return {local, central};
}

}  // namespace

TEST(Archive, Md5InBambuForm) {
    EXPECT_EQ(archive::md5_hex(""), "D41D8CD98F00B204E9800998ECF8427E");
    EXPECT_EQ(archive::md5_hex("abc"), "900150983CD24FB0D6963F7D28E17F72");
    EXPECT_EQ(archive::md5_hex("message digest"), "F96B697D7CB7938D525A2F31AAF161D0");
    // 80 bytes: two blocks, the length in a block of its own after 56.
    EXPECT_EQ(archive::md5_hex("12345678901234567890123456789012345678901234567890123456789012345678901234567890"),
              "57EDF4A22BE3C955AC49DA2E2107B67A");
    EXPECT_EQ(archive::md5_hex(std::string(56, 'a')), "3B0C8AC703F828B04C6C197006D17218");
}

TEST(Archive, MembersInOrderPlatesByNumber) {
    const std::string zip = scaffold::testing::pack(small_members());
    ASSERT_TRUE(archive::is_zip(zip));
    EXPECT_TRUE(archive::is_gcode_3mf(zip));
    archive::Archive a = archive::open(zip, "t.gcode.3mf");
    ASSERT_EQ(a.members.size(), 5u);
    EXPECT_EQ(a.members[2].name, "Metadata/plate_2.png");
    EXPECT_EQ(a.members[2].method, 0);
    EXPECT_EQ(a.members[1].method, 8);
    std::vector<std::size_t> plates = archive::plates(a);
    ASSERT_EQ(plates, (std::vector<std::size_t>{3, 1}));  // plate 2 before plate 10
    archive::Limits l;
    std::uint64_t budget = budget_of(l);
    EXPECT_EQ(archive::read(a, 1, l, budget), "G1 X10\n");
    EXPECT_EQ(budget, l.total_bytes - 7);
    EXPECT_EQ(archive::plate_number("Metadata/plate_12.gcode"), 12);
    EXPECT_EQ(archive::plate_number("Metadata/plate_1.gcode.md5"), 0);
    EXPECT_EQ(archive::plate_number("Metadata/plate_x.gcode"), 0);
    EXPECT_EQ(archive::plate_number("plate_1.gcode"), 0);
}

TEST(Archive, WrittenAgainEveryMemberAsStored) {
    const std::string zip = scaffold::testing::pack(small_members());
    archive::Archive a = archive::open(zip, "t");
    const std::string again = archive::write(a, {});
    std::vector<RawMember> in = scaffold::testing::unpack(zip), out = scaffold::testing::unpack(again);
    ASSERT_EQ(in.size(), 5u);
    ASSERT_EQ(out.size(), in.size());
    for (std::size_t i = 0; i < in.size(); ++i) {
        SCOPED_TRACE(in[i].name);
        EXPECT_EQ(out[i].name, in[i].name);
        EXPECT_EQ(out[i].method, in[i].method);
        EXPECT_EQ(out[i].crc, in[i].crc);
        EXPECT_EQ(out[i].dos_date, in[i].dos_date);
        EXPECT_EQ(out[i].external_fa, in[i].external_fa);
        EXPECT_EQ(out[i].raw, in[i].raw);  // the compressed bytes themselves
        EXPECT_EQ(out[i].data, in[i].data);
    }
}

TEST(Archive, ReplacedMemberKeepsItsPlaceAndMethod) {
    std::vector<ZipMember> members = small_members();
    members[3].method = 0;  // a stored plate stays stored
    const std::string zip = scaffold::testing::pack(members);
    archive::Archive a = archive::open(zip, "t");
    const std::string big(100000, 'G');
    const std::string out1 = archive::write(a, {{3, big}, {1, "G1 X11\n"}});
    EXPECT_EQ(out1, archive::write(a, {{3, big}, {1, "G1 X11\n"}}));  // deterministic
    std::vector<RawMember> in = scaffold::testing::unpack(zip), out = scaffold::testing::unpack(out1);
    ASSERT_EQ(out.size(), 5u);
    EXPECT_EQ(out[3].name, "Metadata/plate_2.gcode");
    EXPECT_EQ(out[3].data, big);
    EXPECT_EQ(out[3].method, 0);
    EXPECT_EQ(out[1].data, "G1 X11\n");
    EXPECT_EQ(out[1].method, 8);
    EXPECT_LT(out[1].raw.size(), 100u);
    for (std::size_t i : {0u, 2u, 4u}) EXPECT_EQ(out[i].raw, in[i].raw) << in[i].name;
}

TEST(Archive, RefusesWhatIsNotAPlateFile) {
    EXPECT_FALSE(archive::is_zip("; G-code\nG1 X1\n"));
    EXPECT_THROW(archive::open("; G-code\n", "t"), scaffold::Error);
    // A zip without plates (a project 3mf, not the sliced plate file).
    const std::string project = scaffold::testing::pack({{"3D/3dmodel.model", "<model/>"}});
    EXPECT_FALSE(archive::is_gcode_3mf(project));
    archive::Archive a = archive::open(project, "p.3mf");
    try {
        archive::plates(a);
        FAIL() << "no plate, no error";
    } catch (const scaffold::Error& e) {
        EXPECT_NE(std::string(e.what()).find("no Metadata/plate_N.gcode"), std::string::npos) << e.what();
    }
    // Truncated anywhere: no central directory to be found, or a member cut.
    const std::string zip = scaffold::testing::pack(small_members());
    for (std::size_t cut : {zip.size() - 1, zip.size() / 2, std::size_t{30}, std::size_t{4}})
        EXPECT_THROW(archive::read_plates(zip.substr(0, cut), "t"), scaffold::Error) << cut;
}

TEST(Archive, RefusesPathsOutOfTheFolder) {
    for (const char* name : {"../plate_1.gcode", "Metadata/../../x", "/etc/passwd", "C:/x", "Metadata\\..\\x"}) {
        std::vector<ZipMember> m = small_members();
        m.push_back({name, "x"});
        const std::string zip = scaffold::testing::pack(m);
        EXPECT_FALSE(archive::is_gcode_3mf(zip)) << name;
        EXPECT_THROW(archive::open(zip, "t"), scaffold::Error) << name;
    }
}

TEST(Archive, RefusesANameTwice) {
    std::vector<ZipMember> m = small_members();
    m.push_back({"Metadata/plate_2.gcode", "G1 X3\n"});
    EXPECT_THROW(archive::open(scaffold::testing::pack(m), "t"), scaffold::Error);
}

TEST(Archive, SizesThatLieAreCaught) {
    const std::string plate(5000, 'G');
    const std::string zip = scaffold::testing::pack({{"Metadata/plate_1.gcode", plate}});
    auto [local, central] = headers_of(zip, "Metadata/plate_1.gcode");
    ASSERT_NE(central, std::string::npos);
    // Smaller than it is, in both headers: read stops there, the CRC tells.
    std::string smaller = zip;
    put32(smaller, local + 22, 1000);
    put32(smaller, central + 24, 1000);
    EXPECT_THROW(archive::read_plates(smaller, "t"), scaffold::Error);
    // Larger than it is: the inflated bytes end first.
    std::string larger = zip;
    put32(larger, local + 22, 6000);
    put32(larger, central + 24, 6000);
    EXPECT_THROW(archive::read_plates(larger, "t"), scaffold::Error);
    // A damaged byte in a stored member: the CRC.
    const std::string stored = scaffold::testing::pack({{"Metadata/plate_1.gcode", plate, 0}});
    std::string flipped = stored;
    flipped[headers_of(stored, "Metadata/plate_1.gcode").first + 30 + 22 + 100] ^= 1;
    EXPECT_THROW(archive::read_plates(flipped, "t"), scaffold::Error);
    EXPECT_EQ(archive::read_plates(stored, "t").at(0).second, plate);
}

TEST(Archive, ZipBombRefusedWithinItsLimits) {
    // 4 MB of zeros deflate to about 4 KB; the limits here are 1 MB.
    const std::string zip = scaffold::testing::pack({{"Metadata/plate_1.gcode", std::string(4 << 20, '\0')}});
    EXPECT_LT(zip.size(), 10000u);
    archive::Limits small;
    small.member_bytes = 1 << 20;
    try {
        archive::read_plates(zip, "bomb.gcode.3mf", small);
        FAIL() << "read";
    } catch (const scaffold::Error& e) {
        EXPECT_NE(std::string(e.what()).find("beyond"), std::string::npos) << e.what();
    }
    // The same claim beyond any deflate ratio (1032:1) is a lie, refused unread.
    std::string liar = zip;
    auto [local, central] = headers_of(zip, "Metadata/plate_1.gcode");
    put32(liar, local + 22, 100000000u);
    put32(liar, central + 24, 100000000u);
    try {
        archive::read_plates(liar, "t");
        FAIL() << "read";
    } catch (const scaffold::Error& e) {
        EXPECT_NE(std::string(e.what()).find("do not fit"), std::string::npos) << e.what();
    }
    // Many members: the total is bounded too.
    std::vector<ZipMember> many;
    for (int i = 1; i <= 4; ++i)
        many.push_back({"Metadata/plate_" + std::to_string(i) + ".gcode", std::string(600000, 'G')});
    archive::Limits total;
    total.total_bytes = 2000000;
    EXPECT_THROW(archive::read_plates(scaffold::testing::pack(many), "t", total), scaffold::Error);
    total.total_bytes = 2400000;
    EXPECT_EQ(archive::read_plates(scaffold::testing::pack(many), "t", total).size(), 4u);
}

TEST(Archive, SliceInfoRaisedForItsPlate) {
    const std::string xml = scaffold::testing::bambu_slice_info({"a", "b"});
    const std::string raised = archive::raise_slice_info(xml, {2, 0.5, 60.4});
    // Plate 1 as it was; plate 2: 1.03 m + 0.5 m, 3.10 g * 1.53 / 1.03, 552 s + 60.
    const std::size_t second = raised.find("value=\"2\"");
    ASSERT_NE(second, std::string::npos);
    EXPECT_EQ(raised.substr(0, second), xml.substr(0, second));
    const std::string tail = raised.substr(second);
    EXPECT_NE(tail.find("used_m=\"1.53\" used_g=\"4.60\""), std::string::npos) << tail;
    EXPECT_NE(tail.find("key=\"prediction\" value=\"612\""), std::string::npos) << tail;
    EXPECT_NE(tail.find("key=\"weight\" value=\"4.60\""), std::string::npos) << tail;
    EXPECT_EQ(raised.size(), xml.size());
    EXPECT_EQ(archive::raise_slice_info(xml, {3, 0.5, 60}), xml);  // no such plate
    // Two filaments: which printed the support is not known; time only.
    std::string two = xml;
    std::size_t f = two.rfind("    <filament");
    two.insert(f, "    <filament id=\"2\" type=\"PLA\" used_m=\"0.20\" used_g=\"0.60\" />\n");
    const std::string r2 = archive::raise_slice_info(two, {2, 0.5, 60});
    std::size_t unchanged = 0;
    for (std::size_t p = r2.find("used_m=\"1.03\" used_g=\"3.10\""); p != std::string::npos;
         p = r2.find("used_m=\"1.03\" used_g=\"3.10\"", p + 1))
        ++unchanged;
    EXPECT_EQ(unchanged, 2u);
    EXPECT_NE(r2.find("value=\"612\""), std::string::npos);
    EXPECT_EQ(r2.find("4.60"), std::string::npos);
}

// Found by tests/fuzz/archive_fuzz: a member's extra field whose last block
// says it runs past the field's end (minizip's own zip64 filter copied a
// negative size there). Its plate reads; writing stops at the member after
// it, whose stored bytes are cut, with an error naming it.
TEST(Archive, DamagedExtraFieldIsNotTrusted) {
    const std::string zip = scaffold::testing::load_file(std::string(SCAFFOLD_TEST_DATA) +
                                                         "/fuzz/gcode3mf-extra-field-past-its-end.gcode.3mf");
    ASSERT_FALSE(zip.empty());
    archive::Archive a = archive::open(zip, "t");
    EXPECT_EQ(archive::read_plates(zip, "t").size(), 1u);
    try {
        archive::write(a, {});
        FAIL() << "written";
    } catch (const scaffold::Error& e) {
        EXPECT_NE(std::string(e.what()).find("'Metadata/slice_info.config'"), std::string::npos) << e.what();
    }
}
