#include "splice/times.hpp"

#include "gcode/format.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdio>

namespace scaffold::splice {

namespace {

bool is_digit(char c) { return c >= '0' && c <= '9'; }

// A number at the start of `s` (digits, optional fraction); its length in `n`.
bool read_number(std::string_view s, double& v, std::size_t& n) {
    const char* end = s.data() + s.size();
    auto r = std::from_chars(s.data(), end, v);
    if (r.ec != std::errc() || s.empty() || !(is_digit(s[0]) || s[0] == '-')) return false;
    n = static_cast<std::size_t>(r.ptr - s.data());
    return true;
}

// "2h 26m 42s" at the start of `s`: seconds and the span it takes, or false.
bool read_dhms(std::string_view s, double& seconds, std::size_t& n) {
    seconds = 0;
    std::size_t i = 0, end = 0;
    bool any = false;
    while (true) {
        std::size_t j = i;
        while (j < s.size() && s[j] == ' ') ++j;
        std::size_t k = j;
        while (k < s.size() && is_digit(s[k])) ++k;
        if (k == j || k >= s.size()) break;
        int unit = s[k] == 'd' ? 86400 : s[k] == 'h' ? 3600 : s[k] == 'm' ? 60 : s[k] == 's' ? 1 : 0;
        if (unit == 0) break;
        seconds += std::strtod(std::string(s.substr(j, k - j)).c_str(), nullptr) * unit;
        any = true;
        i = end = k + 1;
    }
    n = end;
    return any;
}

using gcode::fixed;

// Decimals as the slicer wrote the number ("4544" -> 0, "86.189125" -> 6).
int decimals_of(std::string_view number) {
    std::size_t dot = number.find('.');
    return dot == std::string_view::npos ? 0 : static_cast<int>(number.size() - dot - 1);
}

// Replaces the "2h 3m 4s" after `key` in `s` by the same plus `add`.
bool raise_dhms_after(std::string& s, std::string_view key, double add) {
    std::size_t k = s.find(key);
    if (k == std::string::npos) return false;
    std::size_t at = k + key.size();
    double v = 0;
    std::size_t n = 0;
    if (!read_dhms(std::string_view(s).substr(at), v, n)) return false;
    std::size_t lead = 0;
    while (s[at + lead] == ' ') ++lead;
    s.replace(at + lead, n - lead, format_dhms(v + add));
    return true;
}

// Replaces the number right after `key` by `f(old value)`, as many
// decimals as it had.
template <class F>
bool raise_number_after(std::string& s, std::string_view key, F f) {
    std::size_t k = s.find(key);
    if (k == std::string::npos) return false;
    std::size_t at = k + key.size();
    while (at < s.size() && s[at] == ' ') ++at;
    double v = 0;
    std::size_t n = 0;
    if (!read_number(std::string_view(s).substr(at), v, n)) return false;
    s.replace(at, n, fixed(f(v), decimals_of(std::string_view(s).substr(at, n))));
    return true;
}

// The value of word `letter` in an M73 line ("M73 P12 R30"), or -1.
double m73_word(std::string_view t, char letter) {
    std::size_t end = std::min(t.find(';'), t.size());
    for (std::size_t i = 3; i + 1 < end; ++i) {
        if (t[i] != letter || t[i - 1] != ' ') continue;
        double v = 0;
        std::size_t n = 0;
        if (read_number(t.substr(i + 1, end - i - 1), v, n)) return v;
    }
    return -1;
}

void set_m73_word(std::string& s, char letter, long value) {
    std::size_t end = std::min(s.find(';'), s.size());
    for (std::size_t i = 3; i + 1 < end; ++i) {
        if (s[i] != letter || s[i - 1] != ' ') continue;
        std::size_t j = i + 1;
        while (j < end && (is_digit(s[j]) || s[j] == '.' || s[j] == '-')) ++j;
        s.replace(i + 1, j - i - 1, std::to_string(value));
        return;
    }
}

bool starts_with(std::string_view t, std::string_view p) { return t.substr(0, p.size()) == p; }

}  // namespace

std::string format_dhms(double seconds) {
    long t = std::lround(std::max(0.0, seconds));
    long d = t / 86400, h = t / 3600 % 24, m = t / 60 % 60, s = t % 60;
    char buf[64];
    if (d > 0) std::snprintf(buf, sizeof buf, "%ldd %ldh %ldm %lds", d, h, m, s);
    else if (h > 0) std::snprintf(buf, sizeof buf, "%ldh %ldm %lds", h, m, s);
    else if (m > 0) std::snprintf(buf, sizeof buf, "%ldm %lds", m, s);
    else std::snprintf(buf, sizeof buf, "%lds", s);
    return buf;
}

void update_times(const gcode::Program& p, std::vector<BlockTime> blocks, std::vector<gcode::Edit>& edits) {
    double added = 0;
    for (const BlockTime& b : blocks) added += b.seconds;
    if (added <= 0) return;
    std::stable_sort(blocks.begin(), blocks.end(), [](const BlockTime& a, const BlockTime& b) { return a.line < b.line; });

    // One pass: the lines to change, and the slicer's totals (normal and
    // silent mode) that place its M73 progress in time.
    enum class Kind : std::uint8_t { Total, Elapsed, M73 };
    struct Found { std::uint32_t line; Kind kind; };
    std::vector<Found> found;
    double total = -1, total_silent = -1;
    double m73_total = -1;  // from the first M73 with P and R, when no total line
    for (std::uint32_t i = 0; i < p.lines.size(); ++i) {
        const std::string_view t = p.line_text(i);
        if (t.size() < 5) continue;
        if (t[0] == 'M' && starts_with(t, "M73 ")) {
            found.push_back({i, Kind::M73});
            double pc = m73_word(t, 'P'), r = m73_word(t, 'R');
            if (m73_total < 0 && pc >= 0 && pc < 100 && r >= 0) m73_total = r * 60 / (1 - pc / 100);
            continue;
        }
        if (t[0] != ';') continue;
        double v = 0;
        std::size_t n = 0;
        if (std::size_t k = t.find("estimated printing time ("); k != std::string_view::npos) {
            std::size_t eq = t.find("= ", k);
            if (eq == std::string_view::npos || !read_dhms(t.substr(eq + 2), v, n)) continue;
            (t.find("silent", k) != std::string_view::npos ? total_silent : total) = v;
            found.push_back({i, Kind::Total});
        } else if (std::size_t k2 = t.find("total estimated time: "); k2 != std::string_view::npos) {
            if (read_dhms(t.substr(k2 + 22), v, n) && total < 0) total = v;
            found.push_back({i, Kind::Total});
        } else if (starts_with(t, ";TIME:") || starts_with(t, ";PRINT.TIME:") || starts_with(t, ";Print Time: ")) {
            std::size_t c = t.find(':') + 1;
            while (c < t.size() && t[c] == ' ') ++c;
            if (read_number(t.substr(c), v, n) && total < 0) total = v;
            found.push_back({i, Kind::Total});
        } else if (starts_with(t, ";TIME_ELAPSED:")) {
            found.push_back({i, Kind::Elapsed});
        }
    }
    if (total < 0) total = m73_total;
    if (total_silent < 0) total_silent = total;

    std::size_t next_block = 0;
    double before = 0;  // support time inserted before the line at hand
    for (const Found& f : found) {
        while (next_block < blocks.size() && blocks[next_block].line <= f.line) before += blocks[next_block++].seconds;
        std::string s(p.line_text(f.line));
        const std::string was = s;
        switch (f.kind) {
            case Kind::Total:
                if (!raise_dhms_after(s, "estimated printing time (normal mode) = ", added) &&
                    !raise_dhms_after(s, "estimated printing time (silent mode) = ", added) &&
                    !raise_dhms_after(s, "estimated printing time = ", added)) {
                    raise_dhms_after(s, "model printing time: ", added);
                    raise_dhms_after(s, "total estimated time: ", added);
                    for (const char* key : {";TIME:", ";PRINT.TIME:", ";Print Time:"})
                        if (starts_with(s, key)) raise_number_after(s, key, [&](double v) { return v + added; });
                }
                break;
            case Kind::Elapsed:
                raise_number_after(s, ";TIME_ELAPSED:", [&](double v) { return v + before; });
                break;
            case Kind::M73: {
                // Progress P (percent done) with R (minutes left); Q and S
                // the same in the silent mode (Prusa printers).
                auto redo = [&](char pc_letter, char left_letter, double slicer_total) {
                    double pc = m73_word(s, pc_letter), left = m73_word(s, left_letter);
                    if (slicer_total <= 0 || (pc < 0 && left < 0)) return;
                    double done = pc >= 0 ? pc / 100 * slicer_total : slicer_total - left * 60;
                    double rest = left >= 0 ? left * 60 : slicer_total - done;
                    double new_total = slicer_total + added;
                    double new_done = std::min(done + before, new_total);
                    if (pc >= 0)
                        set_m73_word(s, pc_letter, std::clamp(static_cast<long>(std::floor(100 * new_done / new_total + 1e-9)), 0L, 100L));
                    if (left >= 0) set_m73_word(s, left_letter, std::lround((rest + added - before) / 60));
                };
                redo('P', 'R', total);
                redo('Q', 'S', total_silent);
                break;
            }
        }
        if (s != was) edits.push_back({f.line, true, std::move(s)});
    }
}

}  // namespace scaffold::splice
