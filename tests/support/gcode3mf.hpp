#pragma once
// Bambu Studio's sliced plate files for tests: Bambu-dialect G-code written
// here (not pasted), packed into a .gcode.3mf with the members Bambu Studio's
// "Export plate sliced file" writes, in its order, and read back member by
// member with minizip itself (not through gcode/archive, which is tested).
#include <cstdint>
#include <string>
#include <vector>

namespace scaffold::testing {

// One plate of Bambu Studio G-code (its header block, M83, '; CHANGE_LAYER',
// '; FEATURE:', a config block): a 10 mm block with a 10 mm shelf from its
// side at 4 mm (overhang = true: it needs support), else the block alone.
struct BambuPlate {
    bool overhang = true;
    bool spiral = false;      // spiral_mode = 1
    double x = 100, y = 100;  // the block's corner
};
std::string bambu_gcode(const BambuPlate& plate);

struct ZipMember {
    std::string name, data;
    int method = 8;           // 0 stored, 8 deflate
    std::uint64_t zeros = 0;  // then this many zero bytes (a zip bomb without holding it)
};

// The members of a sliced plate file for these plates' G-code: 3MF parts,
// thumbnails (stored, as a mix), plate_N.gcode with its .md5 (uppercase, no
// newline), slice_info.config (prediction, weight, one filament's used_m and
// used_g per plate), project settings.
std::vector<ZipMember> bambu_members(const std::vector<std::string>& plates);
// slice_info.config as Bambu Studio writes it for these plates.
std::string bambu_slice_info(const std::vector<std::string>& plates);

// A zip of these members (minizip, fixed dates: the same bytes every run).
std::string pack(const std::vector<ZipMember>& members);

struct RawMember {
    std::string name;
    int method = 0;
    std::uint32_t crc = 0;
    std::uint32_t dos_date = 0, external_fa = 0;
    std::string raw;   // as stored (compressed)
    std::string data;  // inflated
};
// Every member in directory order; empty on any error.
std::vector<RawMember> unpack(const std::string& zip);

}  // namespace scaffold::testing
