#include "gcode/archive.hpp"

#include <minizip/unzip.h>
#include <minizip/zip.h>

#include <algorithm>
#include <cctype>
#include <array>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <tuple>

#include "gcode/error.hpp"

namespace scaffold::gcode::archive {

namespace {

// minizip reads and writes through these callbacks: the archive stays in
// memory (stdin works, nothing touches the disk, a fuzzer can drive it).
struct MemFile {
    std::string_view in;         // reading
    std::string* out = nullptr;  // writing
    std::uint64_t pos = 0;
    std::uint64_t size() const { return out ? out->size() : in.size(); }
};

voidpf ZCALLBACK mem_open(voidpf opaque, const void*, int) { return opaque; }

uLong ZCALLBACK mem_read(voidpf, voidpf stream, void* buf, uLong size) {
    auto* f = static_cast<MemFile*>(stream);
    if (f->out || f->pos >= f->in.size()) return 0;
    uLong n = static_cast<uLong>(std::min<std::uint64_t>(size, f->in.size() - f->pos));
    std::memcpy(buf, f->in.data() + f->pos, n);
    f->pos += n;
    return n;
}

uLong ZCALLBACK mem_write(voidpf, voidpf stream, const void* buf, uLong size) {
    auto* f = static_cast<MemFile*>(stream);
    if (!f->out) return 0;
    if (f->pos > f->out->size()) f->out->resize(f->pos);
    std::size_t overlap = std::min<std::size_t>(size, f->out->size() - f->pos);
    f->out->replace(f->pos, overlap, static_cast<const char*>(buf), size);  // minizip seeks back to fill a local header
    f->pos += size;
    return size;
}

ZPOS64_T ZCALLBACK mem_tell(voidpf, voidpf stream) { return static_cast<MemFile*>(stream)->pos; }

long ZCALLBACK mem_seek(voidpf, voidpf stream, ZPOS64_T offset, int origin) {
    auto* f = static_cast<MemFile*>(stream);
    std::uint64_t base = origin == ZLIB_FILEFUNC_SEEK_CUR ? f->pos : origin == ZLIB_FILEFUNC_SEEK_END ? f->size() : 0;
    if (offset > f->size() || base > f->size() - offset) return -1;
    f->pos = base + offset;
    return 0;
}

int ZCALLBACK mem_close(voidpf, voidpf) { return 0; }
int ZCALLBACK mem_error(voidpf, voidpf) { return 0; }

zlib_filefunc64_def mem_funcs(MemFile& f) {
    return {mem_open, mem_read, mem_write, mem_tell, mem_seek, mem_close, mem_error, &f};
}

// One open unzFile over memory, closed on every path out.
class Reader {
public:
    Reader(std::string_view bytes, const std::string& path) : file_{bytes, nullptr, 0} {
        zlib_filefunc64_def funcs = mem_funcs(file_);
        unz_ = unzOpen2_64("archive", &funcs);
        if (!unz_)
            throw Error(path, 0, "is not a zip archive scaffold can read (no valid central directory: truncated?)");
    }
    ~Reader() {
        if (unz_) unzClose(unz_);
    }
    Reader(const Reader&) = delete;
    Reader& operator=(const Reader&) = delete;
    unzFile get() const { return unz_; }

private:
    MemFile file_;
    unzFile unz_ = nullptr;
};

struct Entry {
    unz_file_info64 info{};
    std::string name, extra, comment;
};

Entry current_entry(unzFile u, const std::string& path) {
    Entry e;
    if (unzGetCurrentFileInfo64(u, &e.info, nullptr, 0, nullptr, 0, nullptr, 0) != UNZ_OK)
        throw Error(path, 0, "a zip directory entry is damaged");
    e.name.resize(e.info.size_filename + 1);
    e.extra.resize(e.info.size_file_extra);
    e.comment.resize(e.info.size_file_comment + 1);
    if (unzGetCurrentFileInfo64(u, &e.info, e.name.data(), static_cast<uLong>(e.name.size()),
                                e.extra.empty() ? nullptr : e.extra.data(), static_cast<uLong>(e.extra.size()),
                                e.comment.data(), static_cast<uLong>(e.comment.size())) != UNZ_OK)
        throw Error(path, 0, "a zip directory entry is damaged");
    e.name.resize(e.info.size_filename);
    e.comment.resize(e.info.size_file_comment);
    return e;
}

// A name that would leave the folder it is extracted to, or is not one
// name at all: such an archive is refused (scaffold extracts nothing, but a
// printer or the next tool might).
bool unsafe_name(std::string_view n) {
    if (n.empty() || n.find('\0') != std::string_view::npos) return true;
    if (n[0] == '/' || n[0] == '\\' || (n.size() >= 2 && n[1] == ':')) return true;
    std::size_t start = 0;
    while (start <= n.size()) {
        std::size_t end = n.find_first_of("/\\", start);
        if (end == std::string_view::npos) end = n.size();
        if (n.substr(start, end - start) == "..") return true;
        start = end + 1;
    }
    return false;
}

std::string mib(std::uint64_t bytes) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.0f MiB", static_cast<double>(bytes) / (1 << 20));
    return buf;
}

// Moves to entry `index` (directory order).
void go_to(unzFile u, std::size_t index, const std::string& path) {
    int r = unzGoToFirstFile(u);
    for (std::size_t i = 0; r == UNZ_OK && i < index; ++i) r = unzGoToNextFile(u);
    if (r != UNZ_OK) throw Error(path, 0, "the zip directory is damaged");
}

// zip64 sizes are the writer's to add again, from the sizes it writes.
// (Not minizip's zipRemoveExtraInfoBlock: it trusts each block's length and
// copies a negative size on a damaged field; found by tests/fuzz.) A block
// running past the end is kept as it is, with the rest.
std::string without_zip64(const std::string& extra) {
    std::string out;
    std::size_t at = 0;
    while (at + 4 <= extra.size()) {
        const auto byte = [&](std::size_t i) { return static_cast<std::size_t>(static_cast<unsigned char>(extra[i])); };
        const std::size_t id = byte(at) | byte(at + 1) << 8, len = byte(at + 2) | byte(at + 3) << 8;
        if (at + 4 + len > extra.size()) break;
        if (id != 0x0001) out.append(extra, at, 4 + len);
        at += 4 + len;
    }
    return out.append(extra, at, std::string::npos);
}

}  // namespace

bool is_zip(std::string_view bytes) {
    // A member first, or (an empty zip) the end of the directory.
    const std::string_view magic = bytes.substr(0, 4);
    return magic == std::string_view("PK\3\4", 4) || magic == std::string_view("PK\5\6", 4);
}

bool is_gcode_3mf(std::string_view bytes) {
    if (!is_zip(bytes)) return false;
    try {
        Archive a = open(bytes, "");
        for (const Member& m : a.members)
            if (plate_number(m.name) > 0) return true;
    } catch (const Error&) {
    }
    return false;
}

void refuse_binary_3mf(const std::string& path, std::string_view bytes) {
    std::string lower = path;
    for (char& c : lower) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    if (lower.size() < 4 || lower.compare(lower.size() - 4, 4, ".3mf") != 0 || is_zip(bytes)) return;
    for (char c : bytes.substr(0, 65536))
        if (static_cast<unsigned char>(c) < 9)
            throw Error(path, 0,
                        "is named .3mf but is not a zip archive (a .gcode.3mf is one), nor G-code: damaged, or "
                        "not a sliced plate file");
}

int plate_number(std::string_view n) {
    constexpr std::string_view kPrefix = "Metadata/plate_", kSuffix = ".gcode";
    if (n.size() <= kPrefix.size() + kSuffix.size() || n.substr(0, kPrefix.size()) != kPrefix ||
        n.substr(n.size() - kSuffix.size()) != kSuffix)
        return 0;
    std::string_view digits = n.substr(kPrefix.size(), n.size() - kPrefix.size() - kSuffix.size());
    if (digits.size() > 6 || digits[0] == '0') return 0;
    int v = 0;
    for (char c : digits) {
        if (c < '0' || c > '9') return 0;
        v = v * 10 + (c - '0');
    }
    return v;
}

Archive open(std::string_view bytes, const std::string& path, const Limits& limits) {
    if (!is_zip(bytes)) throw Error(path, 0, "is not a zip archive (no local file header at its start)");
    // The end of directory record, whole, last: a file cut anywhere fails
    // here or at its members' CRC (minizip forgives a record cut short).
    std::size_t end = bytes.rfind(std::string_view("PK\5\6", 4));
    if (end == std::string_view::npos || end + 22 > bytes.size() ||
        end + 22 + (std::uint8_t(bytes[end + 20]) | std::uint8_t(bytes[end + 21]) << 8) != bytes.size())
        throw Error(path, 0, "is a truncated zip archive (its end of directory record is missing or cut)");
    Reader r(bytes, path);
    unz_global_info64 g{};
    if (unzGetGlobalInfo64(r.get(), &g) != UNZ_OK) throw Error(path, 0, "the zip directory is damaged");
    if (g.number_entry > limits.members)
        throw Error(path, 0,
                    "the zip lists " + std::to_string(g.number_entry) + " members, more than the " +
                        std::to_string(limits.members) + " scaffold reads");
    Archive a;
    a.path = path;
    a.bytes = bytes;
    int rc = unzGoToFirstFile(r.get());
    while (rc == UNZ_OK) {
        Entry e = current_entry(r.get(), path);
        if (unsafe_name(e.name) || std::strlen(e.name.c_str()) != e.name.size())
            throw Error(path, 0, "member '" + e.name + "' has an absolute or '..' path: refused");
        if (a.members.size() >= limits.members)
            throw Error(path, 0, "the zip has more members than its directory says");
        a.members.push_back({e.name, e.info.uncompressed_size, e.info.compressed_size,
                             static_cast<std::uint32_t>(e.info.crc),
                             static_cast<std::uint16_t>(e.info.compression_method)});
        rc = unzGoToNextFile(r.get());
    }
    if (rc != UNZ_END_OF_LIST_OF_FILE) throw Error(path, 0, "the zip directory is damaged");
    if (a.members.size() != g.number_entry) throw Error(path, 0, "the zip directory's member count is wrong");
    // A name twice: which copy a printer reads is anyone's guess.
    std::vector<std::string_view> names;
    for (const Member& m : a.members) names.push_back(m.name);
    std::sort(names.begin(), names.end());
    if (auto twice = std::adjacent_find(names.begin(), names.end()); twice != names.end())
        throw Error(path, 0, "member '" + std::string(*twice) + "' appears twice in the zip: refused");
    return a;
}

std::vector<std::size_t> plates(const Archive& a) {
    std::vector<std::size_t> out;
    for (std::size_t i = 0; i < a.members.size(); ++i)
        if (plate_number(a.members[i].name) > 0) out.push_back(i);
    if (out.empty())
        throw Error(a.path, 0,
                    "is a zip archive without plate G-code (no Metadata/plate_N.gcode member): "
                    "export the sliced plate file (.gcode.3mf), not the project");
    std::stable_sort(out.begin(), out.end(), [&](std::size_t x, std::size_t y) {
        return plate_number(a.members[x].name) < plate_number(a.members[y].name);
    });
    return out;
}

long find(const Archive& a, std::string_view name) {
    for (std::size_t i = 0; i < a.members.size(); ++i)
        if (a.members[i].name == name) return static_cast<long>(i);
    return -1;
}

std::string read(const Archive& a, std::size_t index, const Limits& limits, std::uint64_t& budget) {
    const Member& m = a.members.at(index);
    const std::string where = a.path + " (" + m.name + ")";
    if (m.method != 0 && m.method != Z_DEFLATED)
        throw Error(
            where, 0,
            "is compressed with zip method " + std::to_string(m.method) + " (scaffold reads stored and deflate)");
    if (m.size > limits.member_bytes || m.size > budget)
        throw Error(where, 0,
                    "says it holds " + mib(m.size) + ", beyond the " + mib(std::min(limits.member_bytes, budget)) +
                        " scaffold reads from an archive: refused");
    // Deflate cannot expand more than about 1032:1; a larger claim is a lie.
    if ((m.method == 0 && m.size != m.compressed_size) ||
        (m.method == Z_DEFLATED && m.size / 1032 > m.compressed_size + 1))
        throw Error(where, 0, "has sizes that do not fit its compression: the archive is damaged");
    Reader r(a.bytes, a.path);
    go_to(r.get(), index, a.path);
    unz_file_info64 info{};
    if (unzGetCurrentFileInfo64(r.get(), &info, nullptr, 0, nullptr, 0, nullptr, 0) != UNZ_OK)
        throw Error(where, 0, "its directory entry is damaged");
    if (info.flag & 1) throw Error(where, 0, "is encrypted");
    if (unzOpenCurrentFile(r.get()) != UNZ_OK)
        throw Error(where, 0, "its local header does not match the zip directory: the archive is damaged");
    std::string out;
    out.reserve(m.size);
    std::array<char, 1 << 16> buf;
    int n = 0;
    // minizip stops at the directory's size; the CRC then tells a lie apart.
    while ((n = unzReadCurrentFile(r.get(), buf.data(), static_cast<unsigned>(buf.size()))) > 0) {
        if (out.size() + static_cast<std::size_t>(n) > m.size) break;
        out.append(buf.data(), static_cast<std::size_t>(n));
    }
    int closed = unzCloseCurrentFile(r.get());
    if (n < 0)
        throw Error(where, 0,
                    "cannot be inflated (zip error " + std::to_string(n) + "): the archive is damaged or truncated");
    if (out.size() != m.size)
        throw Error(where, 0,
                    "holds " + std::to_string(out.size()) + " bytes where the zip directory says " +
                        std::to_string(m.size) + ": the archive is damaged");
    if (closed == UNZ_CRCERROR) throw Error(where, 0, "fails its CRC check: the archive is damaged");
    if (closed != UNZ_OK) throw Error(where, 0, "cannot be read to its end: the archive is damaged");
    budget -= m.size;
    return out;
}

std::vector<std::pair<std::string, std::string>> read_plates(std::string_view bytes, const std::string& path,
                                                             const Limits& limits) {
    const Archive a = open(bytes, path, limits);
    std::uint64_t budget = limits.total_bytes;
    std::vector<std::pair<std::string, std::string>> out;
    for (std::size_t i : plates(a)) out.emplace_back(a.members[i].name, read(a, i, limits, budget));
    return out;
}

std::string write(const Archive& a, const std::map<std::size_t, std::string>& replacements) {
    Reader r(a.bytes, a.path);
    std::string out;
    out.reserve(a.bytes.size() + a.bytes.size() / 8);
    MemFile sink{{}, &out, 0};
    zlib_filefunc64_def funcs = mem_funcs(sink);
    // Closed on every way out, an error included (minizip's handle owns memory).
    struct Writer {
        zipFile z;
        ~Writer() {
            if (z) zipClose(z, nullptr);
        }
    } w{zipOpen2_64("archive", APPEND_STATUS_CREATE, nullptr, &funcs)};
    zipFile z = w.z;
    if (!z) throw Error(a.path, 0, "cannot start writing the archive");
    auto fail = [&](const std::string& name, const char* what) {
        return Error(a.path, 0, "cannot write member '" + name + "': " + what);
    };
    std::string global_comment;
    {
        unz_global_info64 g{};
        if (unzGetGlobalInfo64(r.get(), &g) == UNZ_OK && g.size_comment > 0) {
            global_comment.resize(g.size_comment + 1);
            int got = unzGetGlobalComment(r.get(), global_comment.data(), static_cast<uLong>(global_comment.size()));
            global_comment.resize(got > 0 ? static_cast<std::size_t>(got) : 0);
        }
    }
    std::array<char, 1 << 16> buf;
    for (std::size_t i = 0; i < a.members.size(); ++i) {
        // In directory order, one step at a time (not go_to: n^2 on many members).
        if ((i == 0 ? unzGoToFirstFile(r.get()) : unzGoToNextFile(r.get())) != UNZ_OK)
            throw fail(a.members[i].name, "the zip directory is damaged");
        Entry e = current_entry(r.get(), a.path);
        zip_fileinfo zi{};
        zi.dosDate = e.info.dosDate;  // the member's own time: the output depends on the input alone
        zi.tmz_date = {e.info.tmu_date.tm_sec,  e.info.tmu_date.tm_min, e.info.tmu_date.tm_hour,
                       e.info.tmu_date.tm_mday, e.info.tmu_date.tm_mon, e.info.tmu_date.tm_year};
        zi.internal_fa = e.info.internal_fa;
        zi.external_fa = e.info.external_fa;
        const uLong flag = e.info.flag & ~uLong{8};  // sizes go in the local header: no data descriptor
        const int method = static_cast<int>(e.info.compression_method);
        std::string central = without_zip64(e.extra);
        auto it = replacements.find(i);
        if (it != replacements.end()) {
            const std::string& data = it->second;
            int level = method == Z_DEFLATED ? Z_DEFAULT_COMPRESSION : 0;
            if (zipOpenNewFileInZip4_64(
                    z, e.name.c_str(), &zi, nullptr, 0, central.data(), static_cast<uInt>(central.size()),
                    e.comment.empty() ? nullptr : e.comment.c_str(), method, level, 0, -MAX_WBITS, 8,
                    Z_DEFAULT_STRATEGY, nullptr, 0, e.info.version, flag, data.size() >= 0xffffffffu) != ZIP_OK)
                throw fail(e.name, "cannot open it");
            for (std::size_t at = 0; at < data.size(); at += 1u << 30) {
                unsigned n = static_cast<unsigned>(std::min<std::size_t>(data.size() - at, 1u << 30));
                if (zipWriteInFileInZip(z, data.data() + at, n) != ZIP_OK) throw fail(e.name, "deflate failed");
            }
            if (zipCloseFileInZip(z) != ZIP_OK) throw fail(e.name, "cannot close it");
            continue;
        }
        // Copied as stored: its compressed bytes, method and attributes.
        int raw_method = 0, raw_level = 0;
        if (unzOpenCurrentFile2(r.get(), &raw_method, &raw_level, 1) != UNZ_OK) throw fail(e.name, "cannot read it");
        std::string local(static_cast<std::size_t>(std::max(0, unzGetLocalExtrafield(r.get(), nullptr, 0))), '\0');
        if (!local.empty()) unzGetLocalExtrafield(r.get(), local.data(), static_cast<unsigned>(local.size()));
        local = without_zip64(local);
        if (zipOpenNewFileInZip4_64(z, e.name.c_str(), &zi, local.empty() ? nullptr : local.data(),
                                    static_cast<uInt>(local.size()), central.empty() ? nullptr : central.data(),
                                    static_cast<uInt>(central.size()), e.comment.empty() ? nullptr : e.comment.c_str(),
                                    method, Z_DEFAULT_COMPRESSION, 1, -MAX_WBITS, 8, Z_DEFAULT_STRATEGY, nullptr, 0,
                                    e.info.version, flag, e.info.uncompressed_size >= 0xffffffffu) != ZIP_OK) {
            unzCloseCurrentFile(r.get());
            throw fail(e.name, "cannot open it");
        }
        std::uint64_t copied = 0;
        int n = 0;
        while ((n = unzReadCurrentFile(r.get(), buf.data(), static_cast<unsigned>(buf.size()))) > 0) {
            copied += static_cast<std::uint64_t>(n);
            if (zipWriteInFileInZip(z, buf.data(), static_cast<unsigned>(n)) != ZIP_OK) break;
        }
        unzCloseCurrentFile(r.get());
        if (n != 0 || copied != e.info.compressed_size) throw fail(e.name, "its stored bytes are truncated");
        if (zipCloseFileInZipRaw64(z, e.info.uncompressed_size, e.info.crc) != ZIP_OK)
            throw fail(e.name, "cannot close it");
    }
    w.z = nullptr;
    if (zipClose(z, global_comment.empty() ? nullptr : global_comment.c_str()) != ZIP_OK)
        throw Error(a.path, 0, "cannot finish writing the archive");
    return out;
}

// MD5 (RFC 1321): the firmware's check of a plate, nothing secret.
std::string md5_hex(std::string_view bytes) {
    static constexpr std::uint32_t kS[64] = {7, 12, 17, 22, 7, 12, 17, 22, 7, 12, 17, 22, 7, 12, 17, 22,
                                             5, 9,  14, 20, 5, 9,  14, 20, 5, 9,  14, 20, 5, 9,  14, 20,
                                             4, 11, 16, 23, 4, 11, 16, 23, 4, 11, 16, 23, 4, 11, 16, 23,
                                             6, 10, 15, 21, 6, 10, 15, 21, 6, 10, 15, 21, 6, 10, 15, 21};
    std::uint32_t k[64];
    for (int i = 0; i < 64; ++i)
        k[i] = static_cast<std::uint32_t>(std::floor(std::fabs(std::sin(i + 1.0)) * 4294967296.0));
    std::uint32_t h[4] = {0x67452301, 0xefcdab89, 0x98badcfe, 0x10325476};
    auto block = [&](const unsigned char* p) {
        std::uint32_t w[16];
        for (int i = 0; i < 16; ++i)
            w[i] = std::uint32_t{p[4 * i]} | std::uint32_t{p[4 * i + 1]} << 8 | std::uint32_t{p[4 * i + 2]} << 16 |
                   std::uint32_t{p[4 * i + 3]} << 24;
        std::uint32_t a = h[0], b = h[1], c = h[2], d = h[3];
        for (int i = 0; i < 64; ++i) {
            std::uint32_t f;
            int g;
            if (i < 16)
                f = (b & c) | (~b & d), g = i;
            else if (i < 32)
                f = (d & b) | (~d & c), g = (5 * i + 1) % 16;
            else if (i < 48)
                f = b ^ c ^ d, g = (3 * i + 5) % 16;
            else
                f = c ^ (b | ~d), g = (7 * i) % 16;
            f += a + k[i] + w[g];
            a = d, d = c, c = b;
            b += (f << kS[i]) | (f >> (32 - kS[i]));
        }
        h[0] += a, h[1] += b, h[2] += c, h[3] += d;
    };
    const auto* p = reinterpret_cast<const unsigned char*>(bytes.data());
    std::size_t full = bytes.size() / 64 * 64;
    for (std::size_t i = 0; i < full; i += 64) block(p + i);
    unsigned char tail[128] = {};
    std::size_t rest = bytes.size() - full;
    std::memcpy(tail, p + full, rest);
    tail[rest] = 0x80;
    std::size_t tail_len = rest < 56 ? 64 : 128;
    std::uint64_t bits = std::uint64_t{bytes.size()} * 8;
    for (int i = 0; i < 8; ++i) tail[tail_len - 8 + i] = static_cast<unsigned char>(bits >> (8 * i));
    block(tail);
    if (tail_len == 128) block(tail + 64);
    static constexpr char kHex[] = "0123456789ABCDEF";
    std::string out;
    for (std::uint32_t v : h)
        for (int i = 0; i < 4; ++i) {
            unsigned char byte = static_cast<unsigned char>(v >> (8 * i));
            out += kHex[byte >> 4];
            out += kHex[byte & 15];
        }
    return out;
}

namespace {

// The value of attribute `key` in the tag text, and where it sits.
bool attribute(std::string_view tag, std::string_view key, std::size_t& at, std::size_t& len) {
    std::string k(1, ' ');
    k.append(key).append("=\"");
    std::size_t p = tag.find(k);
    if (p == std::string_view::npos) return false;
    at = p + k.size();
    std::size_t end = tag.find('"', at);
    if (end == std::string_view::npos) return false;
    len = end - at;
    return true;
}

double number(std::string_view s) { return std::strtod(std::string(s).c_str(), nullptr); }

std::string fixed2(double v) {
    char buf[64];
    std::snprintf(buf, sizeof buf, "%.2f", v);
    return buf;
}

struct Tag {
    std::size_t begin, end;  // [begin, end) in the text, '<' to '>'
};

// The tags named `name` in text[from, to).
std::vector<Tag> tags(std::string_view text, std::string_view name, std::size_t from, std::size_t to) {
    std::vector<Tag> out;
    std::string open(1, '<');
    open.append(name).push_back(' ');
    for (std::size_t p = text.find(open, from); p != std::string_view::npos && p < to; p = text.find(open, p + 1)) {
        std::size_t e = text.find('>', p);
        if (e == std::string_view::npos || e >= to) break;
        out.push_back({p, e + 1});
    }
    return out;
}

}  // namespace

std::string raise_slice_info(std::string_view xml, const PlateChange& change) {
    // The plate's block: <plate> ... <metadata key="index" value="N"/> ... </plate>.
    std::size_t from = 0, to = 0;
    for (std::size_t p = xml.find("<plate>"); p != std::string_view::npos; p = xml.find("<plate>", p + 1)) {
        std::size_t e = xml.find("</plate>", p);
        if (e == std::string_view::npos) break;
        for (const Tag& t : tags(xml, "metadata", p, e)) {
            std::string_view tag = xml.substr(t.begin, t.end - t.begin);
            std::size_t at = 0, len = 0, vat = 0, vlen = 0;
            if (attribute(tag, "key", at, len) && tag.substr(at, len) == "index" &&
                attribute(tag, "value", vat, vlen) && tag.substr(vat, vlen) == std::to_string(change.plate))
                from = p, to = e;
        }
        if (to) break;
    }
    if (!to) return std::string(xml);
    // Edits as (offset, length, text), applied back to front.
    std::vector<std::tuple<std::size_t, std::size_t, std::string>> edits;
    std::vector<Tag> filaments = tags(xml, "filament", from, to);
    double add_g = 0;
    if (filaments.size() == 1) {  // several: which one printed the support is not known here
        const Tag& f = filaments[0];
        std::string_view tag = xml.substr(f.begin, f.end - f.begin);
        std::size_t m_at = 0, m_len = 0, g_at = 0, g_len = 0;
        if (attribute(tag, "used_m", m_at, m_len) && attribute(tag, "used_g", g_at, g_len)) {
            double used_m = number(tag.substr(m_at, m_len)), used_g = number(tag.substr(g_at, g_len));
            add_g = used_m > 0 ? used_g / used_m * change.filament_m : 0;
            edits.emplace_back(f.begin + m_at, m_len, fixed2(used_m + change.filament_m));
            edits.emplace_back(f.begin + g_at, g_len, fixed2(used_g + add_g));
        }
    }
    for (const Tag& t : tags(xml, "metadata", from, to)) {
        std::string_view tag = xml.substr(t.begin, t.end - t.begin);
        std::size_t at = 0, len = 0, vat = 0, vlen = 0;
        if (!attribute(tag, "key", at, len) || !attribute(tag, "value", vat, vlen)) continue;
        std::string_view key = tag.substr(at, len);
        double v = number(tag.substr(vat, vlen));
        if (key == "prediction")
            edits.emplace_back(t.begin + vat, vlen, std::to_string(std::llround(v + std::max(0.0, change.seconds))));
        else if (key == "weight" && add_g > 0)
            edits.emplace_back(t.begin + vat, vlen, fixed2(v + add_g));
    }
    std::sort(edits.begin(), edits.end(), [](const auto& x, const auto& y) { return std::get<0>(x) > std::get<0>(y); });
    std::string out(xml);
    for (const auto& [at, len, text] : edits) out.replace(at, len, text);
    return out;
}

}  // namespace scaffold::gcode::archive
