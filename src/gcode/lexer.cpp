#include "gcode/lexer.hpp"

#include <charconv>
#include <cstdint>
#include <cmath>

namespace scaffold::gcode {

namespace {

bool is_space(char c) { return c == ' ' || c == '\t' || c == '\r'; }
char upper(char c) { return (c >= 'a' && c <= 'z') ? static_cast<char>(c - 32) : c; }
bool is_letter(char c) { c = upper(c); return c >= 'A' && c <= 'Z'; }

// M-codes whose argument is text, not words.
bool free_text(char letter, int code) {
    if (letter != 'M') return false;
    switch (code) {
        case 23: case 28: case 30: case 32: case 117: case 118: case 928: return true;
        default: return false;
    }
}

std::string_view trim(std::string_view s) {
    while (!s.empty() && is_space(s.front())) s.remove_prefix(1);
    while (!s.empty() && is_space(s.back())) s.remove_suffix(1);
    return s;
}

constexpr double kPow10[] = {1e0, 1e1, 1e2, 1e3, 1e4, 1e5, 1e6, 1e7, 1e8, 1e9, 1e10,
                             1e11, 1e12, 1e13, 1e14, 1e15, 1e16, 1e17, 1e18};

// Reads a number at p (allowing a leading '+'); returns end or nullptr.
// Plain decimals ("-12.345", ".5") take a fast exact path: an integer
// mantissa divided by an exact power of ten rounds correctly. Anything
// else (exponents, long digit strings) goes to std::from_chars.
const char* read_number(const char* p, const char* end, double& value) {
    if (p < end && *p == '+') ++p;
    const char* q = p;
    bool negative = q < end && *q == '-';
    if (negative) ++q;
    std::uint64_t mantissa = 0;
    int digits = 0, frac = 0;
    while (q < end && *q >= '0' && *q <= '9') { mantissa = mantissa * 10 + static_cast<unsigned>(*q - '0'); ++q; ++digits; }
    if (q < end && *q == '.') {
        ++q;
        while (q < end && *q >= '0' && *q <= '9') { mantissa = mantissa * 10 + static_cast<unsigned>(*q - '0'); ++q; ++digits; ++frac; }
    }
    bool plain = digits > 0 && digits <= 18 && (q == end || (*q != 'e' && *q != 'E' && *q != '.'));
    if (plain) {
        value = static_cast<double>(mantissa) / kPow10[frac];
        if (negative) value = -value;
        return q;
    }
    auto [r, ec] = std::from_chars(p, end, value);
    if (ec != std::errc()) return nullptr;
    return r;
}

// Commands whose words change the machine state the reader tracks. Any
// other command's parameters are only passed through, so a firmware's own
// syntax there (Bambu's "M1002 gcode_claim_action : 2") is no error.
const char* words(const char* p, const char* end, Command& out);

bool strict(char letter, int code) {
    if (letter == 'G') return code <= 3 || code == 10 || code == 11 || code == 20 || code == 21 || code == 28 || code == 92;
    if (letter == 'M') return code == 82 || code == 83 || code == 106 || code == 107 || code == 200;
    return false;
}

}  // namespace

const char* lex(std::string_view line, Command& out) {
    out.letter = 0;
    out.code = -1;
    out.subcode = -1;
    out.word_count = 0;
    out.comment = {};
    std::size_t semi = line.find(';');
    std::string_view code = line.substr(0, semi);
    if (semi != std::string_view::npos) out.comment = trim(line.substr(semi + 1));
    // Checksums: "N123 G1 X1*57" — the '*' and what follows are not words.
    if (std::size_t star = code.find('*'); star != std::string_view::npos) code = code.substr(0, star);
    code = trim(code);
    out.code_text = code;
    const char* p = code.data();
    const char* end = p + code.size();
    auto skip = [&] { while (p < end && is_space(*p)) ++p; };
    skip();
    if (p < end && upper(*p) == 'N') {  // line number
        ++p;
        double n;
        const char* q = read_number(p, end, n);
        if (!q) return "malformed line number";
        p = q;
        skip();
    }
    if (p >= end) return "";
    if (*p == '(') return "";  // parenthesised comment line
    char c = upper(*p);
    if (c != 'G' && c != 'M' && c != 'T') return "";  // other firmware words pass through
    ++p;
    double v;
    const char* q = read_number(p, end, v);
    if (!q) {
        if (c == 'T') return "";  // "T?" / "Tx" host tool macros
        return "command without a number";
    }
    if (!std::isfinite(v) || v < 0 || v > 100000) return "command number out of range";
    out.letter = c;
    out.code = static_cast<int>(v);
    double frac = v - out.code;
    if (frac > 1e-9) out.subcode = static_cast<int>(std::lround(frac * 10));
    p = q;
    if (free_text(c, out.code)) return "";
    const char* err = words(p, end, out);
    if (*err && !strict(c, out.code)) {
        out.word_count = 0;
        return "";
    }
    return err;
}

namespace {

const char* words(const char* p, const char* end, Command& out) {
    char c = out.letter;
    auto skip = [&] { while (p < end && is_space(*p)) ++p; };
    while (true) {
        skip();
        if (p >= end) break;
        if (*p == '(') {  // inline (comment)
            while (p < end && *p != ')') ++p;
            if (p < end) ++p;
            continue;
        }
        if (!is_letter(*p)) return "unexpected character in parameters";
        char letter = upper(*p++);
        skip();
        double value = 0;
        if (p >= end || is_letter(*p)) {
            // Bare axis letters are fine for homing ("G28 X") but not for moves.
            if (c == 'G' && (out.code <= 3 || out.code == 92)) return "parameter without a number";
        } else {
            // A {placeholder} of the slicer's custom start or end code that
            // was never filled in (CuraEngine run without its front end
            // leaves "G1 X0 Y{machine_depth}").
            if (*p == '{') return "a slicer placeholder left unfilled ({...}: the slicer's custom G-code was not expanded)";
            const char* r = read_number(p, end, value);
            if (!r) return "malformed number";
            p = r;
            if (p < end && !is_space(*p) && !is_letter(*p)) return "malformed number";
            if (!std::isfinite(value)) return "number is not finite";
        }
        if (out.word_count < static_cast<int>(out.words.size())) out.words[out.word_count++] = {letter, value};
    }
    return "";
}

}  // namespace

}  // namespace scaffold::gcode
