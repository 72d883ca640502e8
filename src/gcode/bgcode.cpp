#include "gcode/bgcode.hpp"

#include <zlib.h>

#include <algorithm>
#include <cstdio>
#include <cstring>
#include <optional>
#include <set>

#include "gcode/error.hpp"
#include "gcode/heatshrink.hpp"
#include "gcode/meatpack.hpp"
#include "gcode/program.hpp"
#include "gcode/writer.hpp"

namespace scaffold::gcode::bgcode {

const char* block_type_name(std::uint16_t type) {
    switch (type) {
        case 0: return "file metadata";
        case 1: return "G-code";
        case 2: return "slicer metadata";
        case 3: return "printer metadata";
        case 4: return "print metadata";
        case 5: return "thumbnail";
        default: return "unknown type";
    }
}

namespace {

// The lines of a text, without their '\n' (a last line without one too).
std::vector<std::string_view> split_lines(std::string_view text) {
    std::vector<std::string_view> lines;
    std::size_t pos = 0;
    while (pos < text.size()) {
        std::size_t nl = text.find('\n', pos);
        std::size_t end = nl == std::string_view::npos ? text.size() : nl;
        lines.push_back(text.substr(pos, end - pos));
        pos = end + 1;
    }
    return lines;
}

constexpr std::size_t kFileHeaderSize = 10;
constexpr std::size_t kMaxGCodeBlock = 65535;  // the reference writer's block size, before compression

std::uint16_t u16(std::string_view b, std::size_t at) {
    return static_cast<std::uint16_t>(static_cast<unsigned char>(b[at]) | static_cast<unsigned char>(b[at + 1]) << 8);
}
std::uint32_t u32(std::string_view b, std::size_t at) {
    return static_cast<std::uint32_t>(u16(b, at)) | static_cast<std::uint32_t>(u16(b, at + 2)) << 16;
}
void put16(std::string& s, std::uint16_t v) {
    s.push_back(static_cast<char>(v & 0xFF));
    s.push_back(static_cast<char>(v >> 8));
}
void put32(std::string& s, std::uint32_t v) {
    put16(s, static_cast<std::uint16_t>(v & 0xFFFF));
    put16(s, static_cast<std::uint16_t>(v >> 16));
}

std::uint32_t crc32_of(std::string_view s) {
    uLong c = crc32(0L, Z_NULL, 0);
    // zlib takes uInt lengths: feed a block (at most a few MB) in pieces anyway.
    while (!s.empty()) {
        std::size_t n = std::min<std::size_t>(s.size(), 1u << 30);
        c = crc32(c, reinterpret_cast<const Bytef*>(s.data()), static_cast<uInt>(n));
        s.remove_prefix(n);
    }
    return static_cast<std::uint32_t>(c);
}

std::string deflate(std::string_view in) {
    uLongf cap = compressBound(static_cast<uLong>(in.size()));
    std::string out(cap, '\0');
    if (compress2(reinterpret_cast<Bytef*>(out.data()), &cap, reinterpret_cast<const Bytef*>(in.data()),
                  static_cast<uLong>(in.size()), Z_DEFAULT_COMPRESSION) != Z_OK)
        throw Error("deflate compression failed");
    out.resize(cap);
    return out;
}

// Inflates at most `expect` bytes; the output grows with the input, so a
// header that claims gigabytes costs nothing until the data backs it.
std::string inflate_data(std::string_view in, std::size_t expect) {
    z_stream z{};
    if (inflateInit(&z) != Z_OK) throw Error("zlib could not start");
    const std::size_t cap = expect + 1;  // one byte more shows data longer than said
    std::string out;
    out.resize(std::min<std::size_t>(cap, in.size() * 4 + 64));
    z.next_in = reinterpret_cast<Bytef*>(const_cast<char*>(in.data()));
    z.avail_in = static_cast<uInt>(in.size());
    int rc = Z_OK;
    std::size_t have = 0;
    while (rc == Z_OK) {
        if (have == out.size()) {
            if (out.size() >= cap) break;
            out.resize(std::min<std::size_t>(cap, out.size() * 2 + 64));
        }
        z.next_out = reinterpret_cast<Bytef*>(out.data() + have);
        z.avail_out = static_cast<uInt>(out.size() - have);
        rc = inflate(&z, Z_NO_FLUSH);
        have = out.size() - z.avail_out;
    }
    inflateEnd(&z);
    if (have > expect) throw Error("deflate data is longer than the block header says");
    if (rc != Z_STREAM_END) throw Error(rc == Z_OK || rc == Z_BUF_ERROR ? "deflate data is cut short" : "deflate data is damaged");
    out.resize(have);
    return out;
}

heatshrink::Params hs_params(std::uint16_t compression) { return {compression == 2 ? 11 : 12, 4}; }

std::string compress(std::string_view in, Compression c) {
    switch (c) {
        case Compression::None: return std::string(in);
        case Compression::Deflate: return deflate(in);
        case Compression::Heatshrink11:
        case Compression::Heatshrink12: return heatshrink::compress(in, hs_params(static_cast<std::uint16_t>(c)));
    }
    throw Error("unknown compression");
}

std::string decompress(std::string_view in, std::uint16_t c, std::size_t expect) {
    std::string out;
    if (c == 0) out.assign(in);
    else if (c == 1) out = inflate_data(in, expect);
    else out = heatshrink::decompress(in, hs_params(c), expect);
    if (out.size() != expect)
        throw Error("the data decompresses to " + std::to_string(out.size()) + " bytes, the block header says " +
                    std::to_string(expect));
    return out;
}

Metadata parse_metadata(std::string_view text) {
    Metadata m;
    for (std::string_view line : split_lines(text)) {
        if (line.empty()) continue;
        std::size_t eq = line.find('=');
        if (eq == std::string_view::npos) throw Error("metadata line without '=': '" + std::string(line.substr(0, 60)) + "'");
        m.emplace_back(std::string(line.substr(0, eq)), std::string(line.substr(eq + 1)));
    }
    return m;
}

const std::string* find(const Metadata& m, std::string_view key) {
    for (const auto& [k, v] : m)
        if (k == key) return &v;
    return nullptr;
}

std::string base64(std::string_view in) {
    static const char* kAlphabet = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    std::string out;
    out.reserve((in.size() + 2) / 3 * 4);
    for (std::size_t i = 0; i < in.size(); i += 3) {
        std::uint32_t v = static_cast<unsigned char>(in[i]) << 16;
        if (i + 1 < in.size()) v |= static_cast<unsigned char>(in[i + 1]) << 8;
        if (i + 2 < in.size()) v |= static_cast<unsigned char>(in[i + 2]);
        out.push_back(kAlphabet[v >> 18 & 63]);
        out.push_back(kAlphabet[v >> 12 & 63]);
        out.push_back(i + 1 < in.size() ? kAlphabet[v >> 6 & 63] : '=');
        out.push_back(i + 2 < in.size() ? kAlphabet[v & 63] : '=');
    }
    return out;
}

// Decodes base64, skipping what is not in the alphabet; false on a bad tail.
bool unbase64(std::string_view in, std::string& out) {
    std::uint32_t acc = 0;
    int bits = 0;
    for (char c : in) {
        int v = c >= 'A' && c <= 'Z' ? c - 'A'
                : c >= 'a' && c <= 'z' ? c - 'a' + 26
                : c >= '0' && c <= '9' ? c - '0' + 52
                : c == '+' ? 62 : c == '/' ? 63 : -1;
        if (v < 0) continue;
        acc = (acc << 6) | static_cast<std::uint32_t>(v);
        bits += 6;
        if (bits >= 8) {
            bits -= 8;
            out.push_back(static_cast<char>((acc >> bits) & 0xFF));
        }
    }
    return bits < 6;
}

// Appends lines to the ASCII text, counting them.
struct AsciiOut {
    std::string text;
    std::uint32_t lines = 0;
    void line(std::string_view s) {
        text.append(s);
        text.push_back('\n');
        ++lines;
    }
    void meta(const Metadata& m) {
        for (const auto& [k, v] : m) {
            text.append("; ").append(k).append(" = ").append(v).push_back('\n');
            ++lines;
        }
    }
};

constexpr std::uint16_t kTypeNotRead = 0xFFFF;

std::string block_where(std::size_t index, std::uint16_t type, std::uint64_t offset) {
    std::string kind = type == kTypeNotRead ? "" : std::string(" (") + block_type_name(type) + ")";
    return "binary G-code block " + std::to_string(index) + kind + " at byte " + std::to_string(offset) + ": ";
}

}  // namespace

bool is_binary(std::string_view b) { return b.size() >= 4 && std::memcmp(b.data(), "GCDE", 4) == 0; }

std::string file_header(std::uint16_t checksum) {
    std::string s("GCDE");
    put32(s, 1);
    put16(s, checksum);
    return s;
}

std::string metadata_text(const Metadata& m) {
    std::string s;
    for (const auto& [k, v] : m) s.append(k).append("=").append(v).push_back('\n');
    return s;
}

std::string make_block(BlockType type, Compression compression, const std::uint16_t* params, std::string_view data,
                       std::uint16_t checksum) {
    if (data.size() > 0xFFFFFFFFu) throw Error("a block of over 4 GB cannot be written");
    std::string packed = compress(data, compression);
    std::string s;
    s.reserve(packed.size() + 24);
    put16(s, static_cast<std::uint16_t>(type));
    put16(s, static_cast<std::uint16_t>(compression));
    put32(s, static_cast<std::uint32_t>(data.size()));
    if (compression != Compression::None) put32(s, static_cast<std::uint32_t>(packed.size()));
    int n = type == BlockType::Thumbnail ? 3 : 1;
    for (int i = 0; i < n; ++i) put16(s, params[i]);
    s.append(packed);
    if (checksum == 1) put32(s, crc32_of(s));
    return s;
}

Decoded decode(const Text& bytes, const std::string& path) {
    std::string_view b(bytes);
    if (!is_binary(b)) throw Error(path, 0, "not binary G-code (it does not start with GCDE)");
    if (b.size() < kFileHeaderSize) throw Error(path, 0, "binary G-code: the file ends inside its 10-byte header");
    if (std::uint32_t v = u32(b, 4); v != 1)
        throw Error(path, 0, "binary G-code version " + std::to_string(v) + " is not supported (only version 1)");
    Decoded d;
    Layout& L = d.layout;
    L.original = bytes;
    L.settings.checksum = u16(b, 8);
    if (L.settings.checksum > 1)
        throw Error(path, 0, "binary G-code: unknown checksum type " + std::to_string(L.settings.checksum) + " at byte 8");
    std::string gcode;
    bool seen[6] = {false, false, false, false, false, false};
    bool first_gcode = true;
    std::size_t pos = kFileHeaderSize;
    for (std::size_t index = 0; pos < b.size(); ++index) {
        Block blk;
        blk.offset = pos;
        std::size_t left = b.size() - pos;
        if (left < 8) throw Error(path, 0, block_where(index, kTypeNotRead, pos) + "the file ends inside the block header");
        blk.type = u16(b, pos);
        std::string where = block_where(index, blk.type, pos);
        if (blk.type > 5) throw Error(path, 0, where + "unknown block type " + std::to_string(blk.type));
        blk.compression = u16(b, pos + 2);
        if (blk.compression > 3) throw Error(path, 0, where + "unknown compression " + std::to_string(blk.compression));
        std::uint64_t usize = u32(b, pos + 4);
        std::size_t header = blk.compression ? 12 : 8;
        if (left < header) throw Error(path, 0, where + "the file ends inside the block header");
        std::uint64_t csize = blk.compression ? u32(b, pos + 8) : usize;
        std::size_t nparams = blk.type == 5 ? 3 : 1;
        std::uint64_t total = header + 2 * nparams + csize + (L.settings.checksum ? 4 : 0);
        if (total > left)
            throw Error(path, 0, where + "the block says it holds " + std::to_string(total) + " bytes but only " +
                                     std::to_string(left) + " remain in the file");
        for (std::size_t i = 0; i < nparams; ++i) blk.params[i] = u16(b, pos + header + 2 * i);
        std::string_view data = b.substr(pos + header + 2 * nparams, csize);
        if (L.settings.checksum) {
            std::size_t covered = header + 2 * nparams + csize;
            if (crc32_of(b.substr(pos, covered)) != u32(b, pos + covered))
                throw Error(path, 0, where + "CRC32 checksum mismatch: the block is damaged");
        }
        blk.size = total;
        pos += total;
        std::string raw;
        try {
            raw = decompress(data, blk.compression, usize);
        } catch (const Error& e) {
            throw Error(path, 0, where + e.what());
        }
        auto type = static_cast<BlockType>(blk.type);
        auto comp = static_cast<Compression>(blk.compression);
        if (type == BlockType::Thumbnail) {
            if (blk.params[0] > 2) throw Error(path, 0, where + "unknown thumbnail format " + std::to_string(blk.params[0]));
            L.thumbnails.push_back({blk.params[0], blk.params[1], blk.params[2], std::move(raw)});
            L.settings.thumbnail = comp;
        } else if (type == BlockType::GCode) {
            if (blk.params[0] > 2) throw Error(path, 0, where + "unknown G-code encoding " + std::to_string(blk.params[0]));
            if (first_gcode) {
                L.settings.gcode = comp;
                L.settings.encoding = static_cast<GCodeEncoding>(blk.params[0]);
                first_gcode = false;
            }
            try {
                if (blk.params[0] == 0) gcode.append(raw);
                else gcode.append(meatpack::decode(raw));
            } catch (const Error& e) {
                throw Error(path, 0, where + e.what());
            }
        } else {
            if (blk.params[0] != 0) throw Error(path, 0, where + "unknown metadata encoding " + std::to_string(blk.params[0]));
            if (seen[blk.type]) throw Error(path, 0, where + "a second " + block_type_name(blk.type) + " block");
            seen[blk.type] = true;
            Metadata m;
            try {
                m = parse_metadata(raw);
            } catch (const Error& e) {
                throw Error(path, 0, where + e.what());
            }
            switch (type) {
                case BlockType::FileMetadata: L.file_metadata = std::move(m); L.settings.file_metadata = comp; break;
                case BlockType::PrinterMetadata: L.printer_metadata = std::move(m); L.settings.printer_metadata = comp; break;
                case BlockType::PrintMetadata: L.print_metadata = std::move(m); L.settings.print_metadata = comp; break;
                default: L.slicer_metadata = std::move(m); L.settings.slicer_metadata = comp; break;
            }
        }
        L.blocks.push_back(blk);
    }
    if (first_gcode) throw Error(path, 0, "binary G-code without a G-code block");

    // The reference converter's ASCII form, part by part.
    AsciiOut a;
    a.text.reserve(gcode.size() + 64 * 1024);
    if (const std::string* producer = find(L.file_metadata, "Producer")) {
        std::string first = "; generated by " + *producer;
        if (const std::string* on = find(L.file_metadata, "Produced on")) first += " on " + *on;
        a.line(first);
    }
    a.line("");
    for (const Thumbnail& t : L.thumbnails) {
        std::string enc = base64(t.data);
        const char* tag = t.format == 1 ? "thumbnail_JPG" : t.format == 2 ? "thumbnail_QOI" : "thumbnail";
        a.line("; " + std::string(tag) + " begin " + std::to_string(t.width) + "x" + std::to_string(t.height) + " " +
               std::to_string(enc.size()));
        for (std::size_t i = 0; i < enc.size(); i += 78) a.line("; " + enc.substr(i, 78));
        a.line("; " + std::string(tag) + " end");
        a.line(";");
    }
    a.line("");
    L.printer_line = a.lines;
    a.meta(L.printer_metadata);
    a.line("");
    L.gcode_line = a.lines;
    a.text.append(gcode);
    a.lines += static_cast<std::uint32_t>(std::count(gcode.begin(), gcode.end(), '\n'));
    if (!gcode.empty() && gcode.back() != '\n') a.line("");
    L.gcode_end = a.lines;
    a.line("");
    L.print_line = a.lines;
    a.meta(L.print_metadata);
    a.line("");
    a.line("; prusaslicer_config = begin");
    L.slicer_line = a.lines;
    a.meta(L.slicer_metadata);
    a.line("; prusaslicer_config = end");
    a.line("");
    d.ascii = std::move(a.text);
    return d;
}

namespace {

void append_gcode_blocks(std::string& out, std::string_view gcode, const Settings& s) {
    std::size_t pos = 0;
    std::uint16_t params[3] = {static_cast<std::uint16_t>(s.encoding), 0, 0};
    while (pos < gcode.size()) {
        // At most kMaxGCodeBlock bytes, cut after a newline (a longer line goes whole).
        std::size_t end = std::min(gcode.size(), pos + kMaxGCodeBlock);
        if (end < gcode.size()) {
            std::size_t nl = gcode.rfind('\n', end - 1);
            if (nl != std::string_view::npos && nl >= pos) end = nl + 1;
            else end = std::min(gcode.size(), gcode.find('\n', end) + 1);
            if (end == 0) end = gcode.size();
        }
        std::string_view chunk = gcode.substr(pos, end - pos);
        pos = end;
        if (s.encoding == GCodeEncoding::None) {
            out.append(make_block(BlockType::GCode, s.gcode, params, chunk, s.checksum));
        } else {
            std::string packed = meatpack::encode(chunk, s.encoding == GCodeEncoding::MeatPackComments);
            out.append(make_block(BlockType::GCode, s.gcode, params, packed, s.checksum));
        }
    }
}

}  // namespace

std::string encode_edited(const Program& program, std::vector<Edit> edits) {
    if (!program.binary) throw Error(program.path, 0, "binary output needs a binary input here");
    const Layout& L = *program.binary;
    auto in_meta = [&](std::uint32_t line) {
        return (line >= L.printer_line && line < L.printer_line + L.printer_metadata.size()) ||
               (line >= L.print_line && line < L.print_line + L.print_metadata.size()) ||
               (line >= L.slicer_line && line < L.slicer_line + L.slicer_metadata.size());
    };
    for (Edit& e : edits) {
        if (e.line >= L.gcode_line && e.line < L.gcode_end) continue;
        if (!e.replace) e.line = e.line <= L.gcode_line ? L.gcode_line : L.gcode_end;
        else if (!in_meta(e.line) || e.text.find('\n') != std::string::npos)
            throw Error(program.path, e.line + 1, "this line of a binary file's metadata cannot be changed");
    }
    const std::string text = render_edited(program, std::move(edits));

    // Header and footer keep their line counts: only their values changed.
    std::vector<std::string_view> lines = split_lines(text);
    std::size_t footer = program.lines.size() - L.gcode_end;
    std::size_t gcode_last = lines.size() - footer;  // one past the last G-code line
    auto reread = [&](const Metadata& m, std::size_t first) {
        Metadata out = m;
        for (std::size_t i = 0; i < m.size(); ++i) {
            std::string_view l = lines[first + i];
            std::string prefix = "; " + m[i].first + " = ";
            if (l.substr(0, prefix.size()) != prefix)
                throw Error(program.path, first + i + 1, "metadata line changed its key: '" + std::string(l.substr(0, 60)) + "'");
            out[i].second = std::string(l.substr(prefix.size()));
        }
        return out;
    };
    Metadata printer = reread(L.printer_metadata, L.printer_line);
    Metadata print = reread(L.print_metadata, L.print_line + (gcode_last - L.gcode_end));
    Metadata slicer = reread(L.slicer_metadata, L.slicer_line + (gcode_last - L.gcode_end));
    const char* g0 = lines[L.gcode_line].data();
    const char* g1 = gcode_last < lines.size() ? lines[gcode_last].data() : text.data() + text.size();
    std::string_view gcode(g0, static_cast<std::size_t>(g1 - g0));

    std::string_view orig(L.original);
    std::string out = file_header(L.settings.checksum);
    out.reserve(text.size() / 2);
    bool gcode_done = false;
    for (const Block& blk : L.blocks) {
        std::string_view bytes = orig.substr(blk.offset, blk.size);
        auto type = static_cast<BlockType>(blk.type);
        auto comp = static_cast<Compression>(blk.compression);
        const Metadata* now = type == BlockType::PrinterMetadata ? &printer
                              : type == BlockType::PrintMetadata  ? &print
                              : type == BlockType::SlicerMetadata ? &slicer
                                                                  : nullptr;
        const Metadata* was = type == BlockType::PrinterMetadata ? &L.printer_metadata
                              : type == BlockType::PrintMetadata  ? &L.print_metadata
                              : type == BlockType::SlicerMetadata ? &L.slicer_metadata
                                                                  : nullptr;
        if (type == BlockType::GCode) {
            if (!gcode_done) append_gcode_blocks(out, gcode, L.settings);
            gcode_done = true;
        } else if (now && *now != *was) {
            out.append(make_block(type, comp, blk.params, metadata_text(*now), L.settings.checksum));
        } else {
            out.append(bytes);  // untouched: byte for byte
        }
    }
    return out;
}

namespace {

// PrusaSlicer's choice of keys for the two small metadata blocks.
constexpr const char* kPrinterKeys[] = {
    "printer_model", "filament_type", "nozzle_diameter", "bed_temperature", "brim_width", "fill_density",
    "layer_height", "temperature", "ironing", "support_material", "max_layer_z", "extruder_colour",
    "filament used [mm]", "filament used [cm3]", "filament used [g]", "filament cost",
    "estimated printing time (normal mode)", "estimated printing time (silent mode)"};
constexpr const char* kPrintKeys[] = {
    "filament used [mm]", "filament used [cm3]", "filament used [g]", "filament cost", "total filament used [g]",
    "total filament cost", "total filament used for wipe tower [g]", "estimated printing time (normal mode)",
    "estimated printing time (silent mode)", "estimated first layer printing time (normal mode)",
    "estimated first layer printing time (silent mode)"};

// "; key = value" -> key, value
bool comment_pair(std::string_view line, std::string_view& key, std::string_view& value) {
    if (line.substr(0, 2) != "; ") return false;
    std::size_t eq = line.find(" = ");
    if (eq == std::string_view::npos) return false;
    key = line.substr(2, eq - 2);
    value = line.substr(eq + 3);
    return true;
}

}  // namespace

std::string encode_ascii(std::string_view ascii, const Settings& s) {
    std::vector<std::string_view> lines = split_lines(ascii);
    Metadata file, printer, print, slicer;
    std::vector<bool> keep(lines.size(), true);
    std::size_t first = 0;
    if (!lines.empty() && lines[0].substr(0, 15) == "; generated by ") {
        std::string_view rest = lines[0].substr(15);
        std::size_t on = rest.find(" on ");
        file.emplace_back("Producer", std::string(rest.substr(0, on)));
        if (on != std::string_view::npos) file.emplace_back("Produced on", std::string(rest.substr(on + 4)));
        keep[0] = false;
        first = 1;
    } else {
        file.emplace_back("Producer", "scaffold " SCAFFOLD_VERSION);
    }
    std::vector<Thumbnail> thumbnails;
    for (std::size_t i = first; i < lines.size(); ++i) {
        // "; thumbnail[_JPG|_QOI] begin WxH LEN", base64 lines, "; thumbnail... end"
        std::string_view l = lines[i];
        std::uint16_t format = l.substr(0, 18) == "; thumbnail begin " ? 0
                               : l.substr(0, 22) == "; thumbnail_JPG begin " ? 1
                               : l.substr(0, 22) == "; thumbnail_QOI begin " ? 2 : 9;
        if (format == 9) continue;
        std::string_view dims = l.substr(l.find(" begin ") + 7);
        unsigned w = 0, h = 0;
        if (std::sscanf(std::string(dims).c_str(), "%ux%u", &w, &h) != 2 || w > 0xFFFF || h > 0xFFFF) continue;
        std::size_t end = i + 1;
        while (end < lines.size() && lines[end].find(" end") == std::string_view::npos) ++end;
        if (end == lines.size()) continue;
        std::string b64;
        for (std::size_t k = i + 1; k < end; ++k) b64.append(lines[k].substr(std::min<std::size_t>(2, lines[k].size())));
        Thumbnail t{format, static_cast<std::uint16_t>(w), static_cast<std::uint16_t>(h), {}};
        if (!unbase64(b64, t.data)) continue;
        thumbnails.push_back(std::move(t));
        for (std::size_t k = i; k <= end; ++k) keep[k] = false;
        i = end;
    }
    std::set<std::string_view> print_keys(std::begin(kPrintKeys), std::end(kPrintKeys));
    std::vector<std::pair<std::string_view, std::string_view>> found;  // every "; k = v" outside the config
    bool in_config = false;
    for (std::size_t i = first; i < lines.size(); ++i) {
        std::string_view l = lines[i];
        if (!l.empty() && l.back() == '\r') l.remove_suffix(1);
        if (l == "; prusaslicer_config = begin") { in_config = true; keep[i] = false; continue; }
        if (l == "; prusaslicer_config = end") { in_config = false; keep[i] = false; continue; }
        std::string_view k, v;
        if (in_config) {
            keep[i] = false;
            if (comment_pair(l, k, v)) slicer.emplace_back(std::string(k), std::string(v));
            continue;
        }
        std::string_view t = l;
        while (!t.empty() && (t.back() == ' ' || t.back() == '\t')) t.remove_suffix(1);
        if (t.empty() || t == ";") { keep[i] = false; continue; }  // as the reference converter
        if (comment_pair(l, k, v)) {
            found.emplace_back(k, v);
            if (print_keys.count(k)) keep[i] = false;
        }
    }
    // The last "; key = value" comment for a key, else the slicer config's value.
    auto value_of = [&](std::string_view key) -> std::optional<std::string> {
        for (auto it = found.rbegin(); it != found.rend(); ++it)
            if (it->first == key) return std::string(it->second);
        if (const std::string* v = find(slicer, key)) return *v;
        return std::nullopt;
    };
    for (const char* key : kPrinterKeys)
        if (auto v = value_of(key)) printer.emplace_back(key, std::move(*v));
    for (const char* key : kPrintKeys)
        if (auto v = value_of(key)) print.emplace_back(key, std::move(*v));
    std::string gcode;
    gcode.reserve(ascii.size());
    for (std::size_t i = 0; i < lines.size(); ++i)
        if (keep[i]) {
            std::string_view l = lines[i];
            if (!l.empty() && l.back() == '\r') l.remove_suffix(1);
            gcode.append(l).push_back('\n');
        }

    std::uint16_t none[3] = {0, 0, 0};
    std::string out = file_header(s.checksum);
    out.append(make_block(BlockType::FileMetadata, s.file_metadata, none, metadata_text(file), s.checksum));
    out.append(make_block(BlockType::PrinterMetadata, s.printer_metadata, none, metadata_text(printer), s.checksum));
    for (const Thumbnail& t : thumbnails) {
        std::uint16_t params[3] = {t.format, t.width, t.height};
        out.append(make_block(BlockType::Thumbnail, s.thumbnail, params, t.data, s.checksum));
    }
    out.append(make_block(BlockType::PrintMetadata, s.print_metadata, none, metadata_text(print), s.checksum));
    out.append(make_block(BlockType::SlicerMetadata, s.slicer_metadata, none, metadata_text(slicer), s.checksum));
    append_gcode_blocks(out, gcode, s);
    return out;
}

}  // namespace scaffold::gcode::bgcode
