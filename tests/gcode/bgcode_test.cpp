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
