#include "gcode/heatshrink.hpp"

#include <algorithm>
#include <vector>

#include "gcode/error.hpp"

namespace scaffold::gcode::heatshrink {

namespace {

struct BitWriter {
    std::string& out;
    std::uint32_t acc = 0;
    int n = 0;  // bits held in acc
    void put(std::uint32_t v, int bits) {
        acc = (acc << bits) | (v & ((1u << bits) - 1));
        n += bits;
        while (n >= 8) {
            n -= 8;
            out.push_back(static_cast<char>((acc >> n) & 0xFF));
        }
        acc &= (1u << n) - 1;
    }
    void flush() {
        if (n > 0) out.push_back(static_cast<char>((acc << (8 - n)) & 0xFF));
        n = 0;
        acc = 0;
    }
};

struct BitReader {
    std::string_view in;
    std::size_t pos = 0;  // in bits
    bool has(int bits) const { return pos + static_cast<std::size_t>(bits) <= in.size() * 8; }
    std::uint32_t get(int bits) {
        std::uint32_t v = 0;
        for (int i = 0; i < bits; ++i, ++pos)
            v = (v << 1) | ((static_cast<unsigned char>(in[pos >> 3]) >> (7 - (pos & 7))) & 1u);
        return v;
    }
};

}  // namespace

std::string compress(std::string_view in, Params p) {
    const std::size_t window = std::size_t{1} << p.window_bits;
    const std::size_t max_len = std::size_t{1} << p.lookahead_bits;
    // A copy costs 1 + window + lookahead bits, a literal 9: two bytes or more pay.
    constexpr std::size_t kMinMatch = 2;
    constexpr int kMaxChain = 48;  // enough for G-code; bounds the time per byte
    std::string out;
    out.reserve(in.size() / 2 + 16);
    BitWriter bw{out};
    // Hash chains over 2-byte prefixes: head per prefix, prev per position.
    std::vector<std::int32_t> head(1 << 16, -1);
    std::vector<std::int32_t> prev(in.size(), -1);
    auto key = [&](std::size_t i) {
        return static_cast<std::size_t>(static_cast<unsigned char>(in[i])) << 8 | static_cast<unsigned char>(in[i + 1]);
    };
    auto insert = [&](std::size_t i) {
        if (i + 1 >= in.size()) return;
        std::size_t k = key(i);
        prev[i] = head[k];
        head[k] = static_cast<std::int32_t>(i);
    };
    std::size_t i = 0;
    while (i < in.size()) {
        std::size_t best_len = 0, best_dist = 0;
        if (i + kMinMatch <= in.size()) {
            std::size_t limit = std::min(max_len, in.size() - i);
            int chain = kMaxChain;
            for (std::int32_t c = head[key(i)]; c >= 0 && chain-- > 0; c = prev[static_cast<std::size_t>(c)]) {
                std::size_t dist = i - static_cast<std::size_t>(c);
                if (dist > window) break;
                std::size_t len = 0;
                while (len < limit && in[static_cast<std::size_t>(c) + len] == in[i + len]) ++len;
                if (len > best_len) {
                    best_len = len;
                    best_dist = dist;
                    if (len == limit) break;
                }
            }
        }
        if (best_len >= kMinMatch) {
            bw.put(0, 1);
            bw.put(static_cast<std::uint32_t>(best_dist - 1), p.window_bits);
            bw.put(static_cast<std::uint32_t>(best_len - 1), p.lookahead_bits);
            for (std::size_t k = 0; k < best_len; ++k) insert(i + k);
            i += best_len;
        } else {
            bw.put(1, 1);
            bw.put(static_cast<unsigned char>(in[i]), 8);
            insert(i);
            ++i;
        }
    }
    bw.flush();
    return out;
}

std::string decompress(std::string_view in, Params p, std::size_t max_out) {
    std::string out;
    out.reserve(std::min<std::size_t>(max_out, in.size() * 3));
    BitReader br{in};
    const int copy_bits = 1 + p.window_bits + p.lookahead_bits;
    for (;;) {
        if (br.has(9) && br.get(1) == 1) {
            if (out.size() >= max_out) throw Error("heatshrink data decodes to more bytes than the block header says");
            out.push_back(static_cast<char>(br.get(8)));
            continue;
        }
        // Fewer bits than a literal left, or a copy tag was read.
        if (!br.has(copy_bits - 1)) break;
        std::size_t dist = br.get(p.window_bits) + 1;
        std::size_t len = br.get(p.lookahead_bits) + 1;
        if (out.size() + len > max_out) throw Error("heatshrink data decodes to more bytes than the block header says");
        // The window starts out as zero bytes, in the reference encoder as in
        // its decoder: a copy from before the start is zeros (MeatPack's
        // "00" pair is a zero byte, so the encoder does match there).
        for (std::size_t k = 0; k < len; ++k) {
            const std::size_t at = out.size();
            out.push_back(at >= dist ? out[at - dist] : '\0');
        }
    }
    return out;
}

}  // namespace scaffold::gcode::heatshrink
