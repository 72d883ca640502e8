#include "gcode/bgcode.hpp"

#include <gtest/gtest.h>
#include <zlib.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include "gcode/error.hpp"
#include "gcode/reader.hpp"
#include "gcode/writer.hpp"

using namespace scaffold::gcode;
namespace fs = std::filesystem;

namespace {

// Whole file, gunzipped when its name ends in .gz.
std::string load(const std::string& path) {
    if (path.size() > 3 && path.substr(path.size() - 3) == ".gz") {
        gzFile f = gzopen(path.c_str(), "rb");
        EXPECT_NE(f, nullptr) << path;
        if (!f) return {};
        std::string s;
        char buf[1 << 16];
        int n;
        while ((n = gzread(f, buf, sizeof buf)) > 0) s.append(buf, static_cast<std::size_t>(n));
        gzclose(f);
        return s;
    }
    std::ifstream in(path, std::ios::binary);
    EXPECT_TRUE(in) << path;
    std::stringstream ss;
    ss << in.rdbuf();
    return ss.str();
}

std::string decode_text(const std::string& bytes) { return bgcode::decode(Text(bytes), "t").ascii; }

const std::string kShared = std::string(SCAFFOLD_SOURCE_DIR) + "/../shared/corpus/bgcode/";
const std::string kData = std::string(SCAFFOLD_TEST_DATA) + "/";

// The command part of each line (comment and trailing blanks cut, spaces
// dropped: MeatPack keeps neither), blank results skipped.
std::vector<std::string> commands(std::string_view text) {
    std::vector<std::string> out;
    std::size_t pos = 0;
    while (pos < text.size()) {
        std::size_t nl = text.find('\n', pos);
        std::size_t end = nl == std::string_view::npos ? text.size() : nl;
        std::string_view l = text.substr(pos, end - pos);
        pos = end + 1;
        l = l.substr(0, l.find(';'));
        std::string c;
        for (char ch : l)
            if (ch != ' ' && ch != '\t' && ch != '\r') c.push_back(ch);
        if (!c.empty()) out.push_back(c);
    }
    return out;
}

struct Variant {
    bgcode::Compression compression;
    bgcode::GCodeEncoding encoding;
};
const Variant kVariants[] = {
    {bgcode::Compression::None, bgcode::GCodeEncoding::None},
    {bgcode::Compression::Deflate, bgcode::GCodeEncoding::None},
    {bgcode::Compression::Heatshrink11, bgcode::GCodeEncoding::None},
    {bgcode::Compression::Heatshrink12, bgcode::GCodeEncoding::None},
    {bgcode::Compression::None, bgcode::GCodeEncoding::MeatPack},
    {bgcode::Compression::None, bgcode::GCodeEncoding::MeatPackComments},
    {bgcode::Compression::Heatshrink12, bgcode::GCodeEncoding::MeatPackComments},
    {bgcode::Compression::Deflate, bgcode::GCodeEncoding::MeatPack},
};

bgcode::Settings settings_for(const Variant& v) {
    bgcode::Settings s;
    s.gcode = v.compression;
    s.encoding = v.encoding;
    s.printer_metadata = s.print_metadata = s.slicer_metadata = s.file_metadata = v.compression;
    return s;
}

}  // namespace

// The reference converter's ASCII for every test file of ../shared.
TEST(Bgcode, DecodesSharedCorpusLikeTheReference) {
    if (!fs::exists(kShared)) GTEST_SKIP() << "skipped: " << kShared << " is not there";
    const std::string b = kShared + "bunny.prusaslicer25.nosup.";
    const std::pair<std::string, std::string> cases[] = {
        {b + "default.bgcode.gz", b + "decoded.gcode.gz"},
        {b + "deflate.bgcode", b + "decoded.gcode.gz"},
        {b + "heatshrink11.bgcode", b + "decoded.gcode.gz"},
        {b + "heatshrink12.bgcode", b + "decoded.gcode.gz"},
        {b + "meta-heatshrink12.bgcode.gz", b + "decoded.gcode.gz"},
        {b + "meatpack.bgcode", b + "meatpack.decoded.gcode.gz"},
        {b + "meatpack-comments.bgcode", b + "meatpack-comments.decoded.gcode.gz"},
        {b + "prusaslicer.bgcode", b + "meatpack-comments.decoded.gcode.gz"},
        {kShared + "overhang_test.prusaslicer25.nosup.prusaslicer.bgcode",
         kShared + "overhang_test.prusaslicer25.nosup.prusaslicer.decoded.gcode.gz"},
    };
    for (const auto& [in, want] : cases) {
        std::string got = decode_text(load(in));
        std::string expect = load(want);
        EXPECT_EQ(got.size(), expect.size()) << in;
        EXPECT_TRUE(got == expect) << in;
    }
}

// The same check on the project's own copy (made from a committed input).
TEST(Bgcode, DecodesBundledPrusaSlicerFileLikeTheReference) {
    std::string got = decode_text(load(kData + "bgcode/overhang_test.prusaslicer25.nosup.prusaslicer.bgcode"));
    std::string expect = load(kData + "bgcode/overhang_test.prusaslicer25.nosup.prusaslicer.decoded.gcode.gz");
    ASSERT_FALSE(expect.empty());
    EXPECT_EQ(got.size(), expect.size());
    EXPECT_TRUE(got == expect);
}

// Every compression and encoding: a plain file converted by our encoder
// decodes (by our decoder) to the same command lines, and the metadata
// lands where the reference puts it.
TEST(Bgcode, EncodesEveryVariantAndDecodesBack) {
    std::string ascii = load(kData + "corpus/overhang_test.prusaslicer25.nosup.gcode.gz");
    ASSERT_FALSE(ascii.empty());
    for (const Variant& v : kVariants) {
        SCOPED_TRACE(testing::Message() << "compression " << static_cast<int>(v.compression) << " encoding "
                                        << static_cast<int>(v.encoding));
        std::string bin = bgcode::encode_ascii(ascii, settings_for(v));
        ASSERT_TRUE(bgcode::is_binary(bin));
        bgcode::Decoded d = bgcode::decode(Text(bin), "t");
        EXPECT_EQ(commands(d.ascii), commands(ascii));
        EXPECT_EQ(d.layout.settings.gcode, v.compression);
        EXPECT_EQ(d.layout.settings.encoding, v.encoding);
        EXPECT_EQ(d.ascii.substr(0, 30), ascii.substr(0, 30));  // "; generated by PrusaSlicer ..."
        EXPECT_NE(d.ascii.find("\n; prusaslicer_config = begin\n; avoid_crossing_perimeters = 0\n"), std::string::npos);
        EXPECT_NE(d.ascii.find("\n; filament used [mm] = "), std::string::npos);
        if (v.compression != bgcode::Compression::None) {
            EXPECT_LT(bin.size(), ascii.size() * 3 / 4);
        }
        // Comments survive where the encoding keeps them.
        bool comments = v.encoding != bgcode::GCodeEncoding::MeatPack;
        EXPECT_EQ(d.ascii.find("\n;LAYER_CHANGE\n") != std::string::npos, comments);
    }
}

// Decoding a reference file and writing it again with its own settings
// (the path of a run that changes only G-code) gives back the same text,
// and untouched metadata blocks byte for byte.
TEST(Bgcode, ReencodesReferenceFilesWithTheirOwnSettings) {
    std::vector<std::string> files = {kData + "bgcode/overhang_test.prusaslicer25.nosup.prusaslicer.bgcode"};
    if (fs::exists(kShared)) {
        for (const char* v : {"default.bgcode.gz", "deflate.bgcode", "heatshrink11.bgcode", "heatshrink12.bgcode",
                              "meatpack.bgcode", "meatpack-comments.bgcode", "meta-heatshrink12.bgcode.gz"})
            files.push_back(kShared + "bunny.prusaslicer25.nosup." + v);
    } else {
        std::cout << "[ SKIPPED  ] the ../shared bunny files: " << kShared << " is not there\n";
    }
    for (const std::string& f : files) {
        SCOPED_TRACE(f);
        std::string bytes = load(f);
        Program p = parse(bytes, "t");
        ASSERT_TRUE(p.binary);
        // One G-code edit forces the G-code blocks to be made anew.
        std::string again = bgcode::encode_edited(p, {{p.binary->gcode_line, false, "; marker\n"}});
        bgcode::Decoded d = bgcode::decode(Text(again), "t");
        std::string before(std::string_view(p.text));
        std::size_t at = before.find('\n', 0);
        for (std::uint32_t i = 1; i < p.binary->gcode_line; ++i) at = before.find('\n', at + 1);
        std::string want = before.substr(0, at + 1) + "; marker\n" + before.substr(at + 1);
        if (p.binary->settings.encoding == bgcode::GCodeEncoding::MeatPack) want = before;  // comments dropped
        EXPECT_TRUE(d.ascii == want);
        EXPECT_EQ(d.layout.settings.gcode, p.binary->settings.gcode);
        EXPECT_EQ(d.layout.settings.encoding, p.binary->settings.encoding);
        EXPECT_EQ(d.layout.settings.checksum, p.binary->settings.checksum);
        ASSERT_EQ(d.layout.blocks.size() > 0, true);
        for (std::size_t i = 0; i < d.layout.blocks.size() && i < p.binary->blocks.size(); ++i) {
            const bgcode::Block& a = p.binary->blocks[i];
            const bgcode::Block& b = d.layout.blocks[i];
            if (a.type == 1) break;
            EXPECT_EQ(std::string_view(p.binary->original).substr(a.offset, a.size),
                      std::string_view(again).substr(b.offset, b.size));
        }
    }
}

// Changed totals go into the metadata blocks, re-encoded with their own
// compression; the rest stays byte for byte.
TEST(Bgcode, EditedTotalsUpdateTheMetadataBlocks) {
    std::string bytes = load(kData + "bgcode/overhang_test.prusaslicer25.nosup.prusaslicer.bgcode");
    Program p = parse(bytes, "t");
    ASSERT_TRUE(p.binary);
    std::vector<Edit> edits;
    for (std::uint32_t i = 0; i < p.lines.size(); ++i)
        if (p.line_text(i).substr(0, 23) == "; filament used [mm] = ") edits.push_back({i, true, "; filament used [mm] = 1234.50"});
    ASSERT_EQ(edits.size(), 2u);  // printer and print metadata
    std::string again = bgcode::encode_edited(p, edits);
    bgcode::Decoded d = bgcode::decode(Text(again), "t");
    for (const auto* m : {&d.layout.printer_metadata, &d.layout.print_metadata}) {
        bool found = false;
        for (const auto& [k, v] : *m)
            if (k == "filament used [mm]") found = v == "1234.50";
        EXPECT_TRUE(found);
    }
    EXPECT_EQ(d.layout.settings.print_metadata, bgcode::Compression::Deflate);
    EXPECT_EQ(d.layout.slicer_metadata, p.binary->slicer_metadata);
    std::string_view orig(p.binary->original);
    const bgcode::Block& slicer = p.binary->blocks[3];
    ASSERT_EQ(slicer.type, 2);
    EXPECT_NE(std::string_view(again).find(orig.substr(slicer.offset, slicer.size)), std::string_view::npos);
}

namespace {

// A small valid binary file built here, to damage.
std::string small_file() {
    bgcode::Settings s;
    s.gcode = bgcode::Compression::Deflate;
    s.encoding = bgcode::GCodeEncoding::None;
    return bgcode::encode_ascii("; generated by test\nG28\nG1 X1 Y2 E0.5\n; filament used [mm] = 1.0\n", s);
}

void expect_error(const std::string& bytes, const std::string& part) {
    try {
        bgcode::decode(Text(bytes), "bad.bgcode");
        ADD_FAILURE() << "no error, expected '" << part << "'";
    } catch (const scaffold::Error& e) {
        std::string msg = e.what();
        EXPECT_NE(msg.find(part), std::string::npos) << msg;
        EXPECT_NE(msg.find("bad.bgcode"), std::string::npos) << msg;
        EXPECT_EQ(msg.find('\n'), std::string::npos) << msg;
    }
}

}  // namespace

TEST(Bgcode, DamagedFilesGiveOneLineErrorsNamingBlockAndOffset) {
    std::string good = small_file();
    ASSERT_NO_THROW(bgcode::decode(Text(good), "good"));
    std::string s = good;
    s[0] = 'X';
    expect_error(s, "does not start with GCDE");
    s = good;
    s[4] = 2;
    expect_error(s, "version 2");
    expect_error(good.substr(0, 7), "ends inside its 10-byte header");
    // Block 0 starts at byte 10: type u16, compression u16, size u32.
    s = good;
    s[12] = 9;
    expect_error(s, "block 0 (file metadata) at byte 10: unknown compression 9");
    s = good;
    s[10] = 7;
    expect_error(s, "block 0 (unknown type) at byte 10: unknown block type 7");
    s = good;
    s[20] ^= 0x20;  // a byte of the data
    expect_error(s, "block 0 (file metadata) at byte 10: CRC32 checksum mismatch");
    expect_error(good.substr(0, good.size() - 3), "at byte");
    expect_error(good.substr(0, good.size() - 3), "remain in the file");
    s = good;
    s[14] = static_cast<char>(0xF0);  // uncompressed size lies (no compression: it is the data size)
    expect_error(s, "block 0 (file metadata) at byte 10: the block says it holds");
    expect_error(good.substr(0, 10) + good.substr(10, 5), "ends inside the block header");
    // The G-code block (last): unknown encoding, and sizes that lie behind a valid checksum.
    bgcode::Decoded d = bgcode::decode(Text(good), "good");
    const bgcode::Block& g = d.layout.blocks.back();
    ASSERT_EQ(g.type, 1);
    std::uint16_t enc[3] = {7, 0, 0};
    std::string gcode = "G1 X1\n";
    std::string head = good.substr(0, g.offset);
    expect_error(head + bgcode::make_block(bgcode::BlockType::GCode, bgcode::Compression::None, enc, gcode, 1),
                 "(G-code) at byte " + std::to_string(g.offset) + ": unknown G-code encoding 7");
    std::uint16_t none[3] = {0, 0, 0};
    std::string blk = bgcode::make_block(bgcode::BlockType::GCode, bgcode::Compression::Deflate, none, gcode, 0);
    blk[4] = 100;  // claims 100 bytes uncompressed
    expect_error(bgcode::file_header(0) + blk, "decompresses to 6 bytes, the block header says 100");
    blk = bgcode::make_block(bgcode::BlockType::GCode, bgcode::Compression::Heatshrink12, none, gcode, 0);
    blk[4] = 3;
    expect_error(bgcode::file_header(0) + blk, "block 0 (G-code) at byte 10: heatshrink data decodes to more bytes");
    std::uint16_t mp[3] = {1, 0, 0};
    blk = bgcode::make_block(bgcode::BlockType::GCode, bgcode::Compression::None, mp, "\xff\xff\x01", 0);
    expect_error(bgcode::file_header(0) + blk, "unknown MeatPack command 1");
}

// read_file recognises binary G-code by its content, whatever the name.
TEST(Bgcode, ReadFileDetectsBinaryByContent) {
    std::string path = testing::TempDir() + "/bgcode_by_content.gcode";
    {
        std::ofstream out(path, std::ios::binary);
        out << small_file();
    }
    Program p = read_file(path);
    ASSERT_TRUE(p.binary);
    EXPECT_EQ(p.moves.size(), 1u);  // the G1 (G28 homes: no move)
    fs::remove(path);
}

// --method none: an unchanged binary file is written back byte for byte;
// --output-format converts both ways.
TEST(Bgcode, WriteOutputKeepsOrConvertsTheFormat) {
    std::string bytes = load(kData + "bgcode/overhang_test.prusaslicer25.nosup.prusaslicer.bgcode");
    Program p = parse(bytes, "t");
    std::string out = testing::TempDir() + "/bgcode_out";
    write_output(out, p, {});
    EXPECT_TRUE(load(out) == bytes);
    write_output(out, p, {}, OutputFormat::Ascii);
    EXPECT_TRUE(load(out) == std::string(std::string_view(p.text)));
    Program ascii = parse(load(kData + "corpus/overhang_test.prusaslicer25.nosup.gcode.gz"), "a");
    write_output(out, ascii, {}, OutputFormat::Binary);
    std::string bin = load(out);
    ASSERT_TRUE(bgcode::is_binary(bin));
    EXPECT_EQ(commands(decode_text(bin)), commands(std::string_view(ascii.text)));
    fs::remove(out);
}

// Committed small files, one per variant, made by our encoder from
// small.gcode (tests/data/bgcode/README.md): the decoder alone reads them.
TEST(Bgcode, DecodesCommittedSmallFilesOfEveryVariant) {
    std::string source = load(kData + "bgcode/small.gcode");
    ASSERT_FALSE(source.empty());
    int seen = 0;
    for (const char* v : {"none", "deflate", "heatshrink11", "heatshrink12", "meatpack", "meatpack-comments", "prusaslicer"}) {
        SCOPED_TRACE(v);
        std::string bytes = load(kData + "bgcode/small." + v + ".bgcode");
        bgcode::Decoded d = bgcode::decode(Text(bytes), v);
        EXPECT_EQ(commands(d.ascii), commands(source));
        EXPECT_EQ(d.ascii.substr(0, 40), source.substr(0, 40));
        ++seen;
    }
    EXPECT_EQ(seen, 7);
}

// Same input, same settings: the same bytes.
TEST(Bgcode, EncodingIsDeterministic) {
    std::string source = load(kData + "bgcode/small.gcode");
    for (const Variant& v : kVariants) EXPECT_TRUE(bgcode::encode_ascii(source, settings_for(v)) == bgcode::encode_ascii(source, settings_for(v)));
}

// Thumbnails: ASCII comments become thumbnail blocks, decode back to the
// same comments, and pass through a supported run byte for byte.
TEST(Bgcode, ThumbnailsSurviveBothWays) {
    std::string image;
    for (int i = 0; i < 300; ++i) image.push_back(static_cast<char>(i * 7 % 256));
    std::string bin_with_thumb;
    {
        std::string ascii = "; generated by PrusaSlicer 2.7.0 on 2026-11-24 at 14:40:04 UTC\n\n";
        // PrusaSlicer's ASCII form: base64, 78 characters a line.
        static const char* kA = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
        std::string b64;
        for (std::size_t i = 0; i < image.size(); i += 3) {
            std::uint32_t v = static_cast<unsigned char>(image[i]) << 16;
            if (i + 1 < image.size()) v |= static_cast<unsigned char>(image[i + 1]) << 8;
            if (i + 2 < image.size()) v |= static_cast<unsigned char>(image[i + 2]);
            b64 += kA[v >> 18 & 63];
            b64 += kA[v >> 12 & 63];
            b64 += i + 1 < image.size() ? kA[v >> 6 & 63] : '=';
            b64 += i + 2 < image.size() ? kA[v & 63] : '=';
        }
        ascii += "; thumbnail_QOI begin 16x12 " + std::to_string(b64.size()) + "\n";
        for (std::size_t i = 0; i < b64.size(); i += 78) ascii += "; " + b64.substr(i, 78) + "\n";
        ascii += "; thumbnail_QOI end\n;\n\nG28\nG1 X10 Y10 E1 F1200\n; filament used [mm] = 1.0\n";
        bin_with_thumb = bgcode::encode_ascii(ascii, bgcode::Settings{});
        bgcode::Decoded d = bgcode::decode(Text(bin_with_thumb), "t");
        ASSERT_EQ(d.layout.thumbnails.size(), 1u);
        EXPECT_EQ(d.layout.thumbnails[0].format, 2);
        EXPECT_EQ(d.layout.thumbnails[0].width, 16);
        EXPECT_EQ(d.layout.thumbnails[0].height, 12);
        EXPECT_TRUE(d.layout.thumbnails[0].data == image);
        EXPECT_NE(d.ascii.find("; thumbnail_QOI begin 16x12 " + std::to_string(b64.size()) + "\n; " + b64.substr(0, 78) + "\n"),
                  std::string::npos);
        EXPECT_EQ(commands(d.ascii), commands(ascii));  // the thumbnail left the G-code
    }
    Program p = parse(bin_with_thumb, "t");
    std::string again = bgcode::encode_edited(p, {{p.binary->gcode_end, false, "G1 X20 Y20 E2\n"}});
    bgcode::Decoded d = bgcode::decode(Text(again), "t");
    ASSERT_EQ(d.layout.thumbnails.size(), 1u);
    const bgcode::Block* was = nullptr;
    const bgcode::Block* now = nullptr;
    for (const auto& b : p.binary->blocks)
        if (b.type == 5) was = &b;
    for (const auto& b : d.layout.blocks)
        if (b.type == 5) now = &b;
    ASSERT_TRUE(was && now);
    EXPECT_EQ(std::string_view(bin_with_thumb).substr(was->offset, was->size), std::string_view(again).substr(now->offset, now->size));
    EXPECT_NE(d.ascii.find("G1 X20 Y20 E2\n"), std::string::npos);
}
