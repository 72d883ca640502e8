#include "gcode/meatpack.hpp"

#include <array>

#include "gcode/error.hpp"

namespace scaffold::gcode::meatpack {

namespace {

constexpr unsigned char kSignal = 0xFF;
constexpr unsigned char kEnablePacking = 251;
constexpr unsigned char kDisablePacking = 250;
constexpr unsigned char kResetAll = 249;
constexpr unsigned char kEnableNoSpaces = 247;
constexpr unsigned char kDisableNoSpaces = 246;
constexpr unsigned kFull = 0xF;

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

bool is_upper(char c) { return c >= 'A' && c <= 'Z'; }

// What the decoder makes of a G line without spaces: a space before each
// letter that does not follow one.
void add_spaces(std::string_view line, std::string& out) {
    for (std::size_t i = 0; i < line.size(); ++i) {
        if (i > 0 && is_upper(line[i]) && line[i - 1] != ' ') out.push_back(' ');
        out.push_back(line[i]);
    }
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

}  // namespace

std::string encode(std::string_view text, bool keep_comment_lines) {
    std::string out;
    out.reserve(text.size() * 2 / 3 + 16);
    signal(out, kEnablePacking);
    signal(out, kEnableNoSpaces);
    bool packing = true;
    std::string line, spaced;
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
            // Drop the spaces only where the decoder puts them back exactly.
            for (char c : cmd)
                if (c != ' ') line.push_back(c);
            spaced.clear();
            add_spaces(line, spaced);
            if (spaced != cmd) line.assign(cmd);
        } else {
            line.assign(cmd);
        }
        line.push_back('\n');
        if (line.size() % 2) line.push_back('\n');  // pairs only: the empty line is dropped on decoding
        if (!packing) signal(out, kEnablePacking);
        packing = true;
        pack(out, line);
    }
    return out;
}

std::string decode(std::string_view in) {
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
                case kResetAll: packing = false; no_spaces = false; break;
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
        if (lo == kFull) raw.push_back(byte());
        else raw.push_back(ch(lo));
        if (hi == kFull) raw.push_back(byte());
        else raw.push_back(ch(hi));
    }
    // The reference decoder's form: no empty lines, G words spaced.
    std::string out;
    out.reserve(raw.size() + raw.size() / 4);
    std::size_t pos = 0;
    while (pos < raw.size()) {
        std::size_t nl = raw.find('\n', pos);
        std::size_t end = nl == std::string::npos ? raw.size() : nl;
        std::string_view line(raw.data() + pos, end - pos);
        pos = end + 1;
        if (line.empty()) continue;
        if (line.front() == 'G') add_spaces(line, out);
        else out.append(line);
        out.push_back('\n');
    }
    return out;
}

}  // namespace scaffold::gcode::meatpack
