#include "gcode/meatpack.hpp"

#include <array>

#include "gcode/error.hpp"

namespace scaffold::gcode::meatpack {

namespace {

constexpr unsigned char kSignal = 0xFF;
constexpr unsigned char kEnablePacking = 251;
constexpr unsigned char kDisablePacking = 250;
constexpr unsigned char kResetAll = 249;
constexpr unsigned char kQueryConfig = 248;
constexpr unsigned char kEnableNoSpaces = 247;
constexpr unsigned char kDisableNoSpaces = 246;
constexpr unsigned kFull = 0xF;
constexpr unsigned char kNewlinePair = 0xCC;  // "\n\n": decodes to nothing after a line end

// Character of each 4-bit code; code 11 is ' ', or 'E' in no-spaces mode.
constexpr char kChars[15] = {'0', '1', '2', '3', '4', '5', '6', '7', '8', '9', '.', ' ', '\n', 'G', 'X'};

// Code of each byte in no-spaces mode (the only mode the encoder uses).
constexpr std::array<unsigned char, 256> make_codes() {
    std::array<unsigned char, 256> c{};
    for (auto& v : c) v = kFull;
    for (unsigned i = 0; i < 15; ++i) c[static_cast<unsigned char>(kChars[i])] = static_cast<unsigned char>(i);
    c[' '] = kFull;
    c['E'] = 11;
    return c;
}
constexpr std::array<unsigned char, 256> kCodes = make_codes();

// The letters before which the reference decoder puts a space back in a line
// that starts with 'G' (when the character before is not one already). Other
// letters (T, M, lower case...) get none, so spaces before them are kept.
bool is_word_letter(char c) {
    switch (c) {
        case 'X': case 'Y': case 'Z': case 'E': case 'F': case 'I': case 'J': case 'R':
        case 'S': case 'G': case 'P': case 'W': case 'H': case 'C': case 'A':
            return true;
        default:
            return false;
    }
}

}  // namespace

bool reference_drops_a_letter(std::string_view raw, std::size_t packed_size) {
    std::size_t len = 0, cap = 2 * packed_size;
    char prev = '\n';
    bool g_line = false;
    for (char c : raw) {
        bool line_start = false;
        if (c == 'G' && (len == 0 || prev == '\n')) g_line = line_start = true;
        else if (c == '\n') g_line = false;
        bool spaced = false;
        if (!line_start && g_line && (len == 0 || prev != ' ') && is_word_letter(c)) {
            prev = ' ';
            if (++len == cap) cap *= 2;
            spaced = true;
        }
        if (c != '\n' || len == 0 || prev != '\n') {
            prev = c;
            if (++len == cap) {
                if (spaced) return true;
                cap *= 2;
            }
        }
    }
    return false;
}

namespace {

// The reference decoder's form of an unpacked stream: no empty lines, and in
// a line starting with 'G' a space before each word letter that lacks one.
std::string respace(std::string_view raw) {
    std::string out;
    out.reserve(raw.size() + raw.size() / 4);
    std::size_t pos = 0;
    while (pos < raw.size()) {
        std::size_t nl = raw.find('\n', pos);
        std::size_t end = nl == std::string_view::npos ? raw.size() : nl;
        std::string_view line = raw.substr(pos, end - pos);
        pos = end + 1;
        if (line.empty()) continue;
        bool g_line = line.front() == 'G';
        for (std::size_t i = 0; i < line.size(); ++i) {
            if (g_line && i > 0 && out.back() != ' ' && is_word_letter(line[i])) out.push_back(' ');
            out.push_back(line[i]);
        }
        out.push_back('\n');
    }
    return out;
}

void signal(std::string& out, unsigned char command) {
    out.push_back(static_cast<char>(kSignal));
    out.push_back(static_cast<char>(kSignal));
    out.push_back(static_cast<char>(command));
}

void pack(std::string& out, std::string_view s) {
    for (std::size_t i = 0; i < s.size(); i += 2) {
        auto a = static_cast<unsigned char>(s[i]);
        auto b = static_cast<unsigned char>(s[i + 1]);  // s has even length
        unsigned ca = kCodes[a], cb = kCodes[b];
        out.push_back(static_cast<char>(ca | cb << 4));
        if (ca == kFull) out.push_back(static_cast<char>(a));
        if (cb == kFull) out.push_back(static_cast<char>(b));
    }
}

// Unpacks without respacing, as the reference decoder does: a pair whose
// first character is a newline ends there (its second half is never read,
// not even a full byte it announces).
std::string unpack(std::string_view in) {
    std::string raw;
    raw.reserve(in.size() * 2);
    bool packing = false, no_spaces = false;
    auto ch = [&](unsigned code) { return code == 11 && no_spaces ? 'E' : kChars[code]; };
    std::size_t i = 0;
    auto byte = [&]() {
        if (i >= in.size()) throw Error("MeatPack data ends inside a packed character pair");
        return in[i++];
    };
    while (i < in.size()) {
        auto b = static_cast<unsigned char>(in[i]);
        if (b == kSignal && i + 1 < in.size() && static_cast<unsigned char>(in[i + 1]) == kSignal) {
            if (i + 2 >= in.size()) throw Error("MeatPack data ends inside a command");
            auto c = static_cast<unsigned char>(in[i + 2]);
            i += 3;
            switch (c) {
                case kEnablePacking: packing = true; break;
                case kDisablePacking: packing = false; break;
                case kResetAll: packing = false; break;  // the reference keeps the no-spaces mode
                case kQueryConfig: break;
                case kEnableNoSpaces: no_spaces = true; break;
                case kDisableNoSpaces: no_spaces = false; break;
                default: throw Error("unknown MeatPack command " + std::to_string(c));
            }
            continue;
        }
        ++i;
        if (!packing) {
            raw.push_back(static_cast<char>(b));
            continue;
        }
        unsigned lo = b & 0xF, hi = b >> 4;
        if (lo != kFull && ch(lo) == '\n') {
            raw.push_back('\n');
            continue;
        }
        // A full first character comes before the second half's.
        char first = lo == kFull ? byte() : ch(lo);
        raw.push_back(first);
        raw.push_back(hi == kFull ? byte() : ch(hi));
    }
    return raw;
}

}  // namespace

std::string encode(std::string_view text, bool keep_comment_lines) {
    std::string out;
    out.reserve(text.size() * 2 / 3 + 16);
    signal(out, kEnablePacking);
    signal(out, kEnableNoSpaces);
    bool packing = true;
    std::string line;
    std::size_t pos = 0;
    while (pos < text.size()) {
        std::size_t nl = text.find('\n', pos);
        std::size_t end = nl == std::string_view::npos ? text.size() : nl;
        std::string_view raw = text.substr(pos, end - pos);
        pos = end + 1;
        if (raw.find('\xFF') != std::string_view::npos)
            throw Error("a 0xFF byte cannot be written with MeatPack");
        if (!raw.empty() && raw.back() == '\r') raw.remove_suffix(1);
        std::size_t first = raw.find_first_not_of(" \t");
        if (first == std::string_view::npos) continue;  // blank: the decoder drops it anyway
        if (raw[first] == ';') {
            if (!keep_comment_lines) continue;
            if (packing) signal(out, kDisablePacking);
            packing = false;
            out.append(raw.substr(first));
            out.push_back('\n');
            continue;
        }
        std::string_view cmd = raw.substr(first);
        if (std::size_t semi = cmd.find(';'); semi != std::string_view::npos) cmd = cmd.substr(0, semi);
        while (!cmd.empty() && (cmd.back() == ' ' || cmd.back() == '\t')) cmd.remove_suffix(1);
        line.clear();
        if (cmd.front() == 'G') {
            // Drop just the spaces the decoder puts back: one after a
            // non-space, before a word letter. Others go as full bytes.
            for (std::size_t i = 0; i < cmd.size(); ++i) {
                bool restored = cmd[i] == ' ' && i > 0 && cmd[i - 1] != ' ' && i + 1 < cmd.size() &&
                                is_word_letter(cmd[i + 1]);
                if (!restored) line.push_back(cmd[i]);
            }
        } else {
            line.assign(cmd);
        }
        line.push_back('\n');
        if (line.size() % 2) line.push_back('\n');  // pairs only: the empty line is dropped on decoding
        if (!packing) signal(out, kEnablePacking);
        packing = true;
        pack(out, line);
    }
    // Pad with bytes that decode to nothing until the reference decoder's
    // buffer regrowth no longer falls on a respaced letter (see above).
    const std::string raw = unpack(out);
    const char pad = packing ? static_cast<char>(kNewlinePair) : '\n';
    std::size_t extra = 0;
    while (reference_drops_a_letter(raw, out.size() + extra))
        if (++extra > 4096) throw Error("no MeatPack padding lets the reference decoder read this block");
    out.append(extra, pad);
    return out;
}

std::string decode(std::string_view in) { return respace(unpack(in)); }

}  // namespace scaffold::gcode::meatpack
