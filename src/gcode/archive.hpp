#pragma once
// Bambu Studio / OrcaSlicer's sliced project (.gcode.3mf): a zip holding
// Metadata/plate_N.gcode, its .md5 and slice_info.config beside thumbnails
// and the 3MF parts. Reading hands on each plate's G-code text; writing puts
// back the members a caller replaced and copies every other one as stored
// (its compressed bytes, name, order, method, date and attributes).
// The zip work is minizip's (zlib's contrib, Debian's libminizip), over
// memory: nothing is extracted to disk.
#include <cstdint>
#include <map>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace scaffold::gcode::archive {

// What one archive may make us hold in memory: a member is read only while
// its declared size, its compression ratio and its actual bytes stay within
// these (a zip bomb or a member whose sizes lie is refused).
struct Limits {
    std::uint64_t member_bytes = std::uint64_t{1} << 30;  // one inflated member
    std::uint64_t total_bytes = std::uint64_t{2} << 30;   // all members read, together
    std::uint32_t members = 65536;
};

struct Member {
    std::string name;
    std::uint64_t size = 0;             // uncompressed, as the central directory says
    std::uint64_t compressed_size = 0;  // as stored
    std::uint32_t crc = 0;
    std::uint16_t method = 0;  // 0 stored, 8 deflate
};

// The archive's bytes (not owned) and its members in file order.
struct Archive {
    std::string path;  // for messages
    std::string_view bytes;
    std::vector<Member> members;
};

// A zip: a local file header (or an empty zip's end of directory) first.
bool is_zip(std::string_view bytes);
// A zip with at least one Metadata/plate_N.gcode member (reads the directory
// only). Never throws.
bool is_gcode_3mf(std::string_view bytes);

// Throws scaffold::Error saying so when a file named *.3mf is not a zip but
// binary (control bytes G-code never has): else the G-code reader would
// report a line of binary bytes.
void refuse_binary_3mf(const std::string& path, std::string_view bytes);

// Lists the members; throws scaffold::Error naming `path` when the bytes are
// not a zip minizip can read, a member name is absolute or has '..', or the
// directory is beyond `limits`.
Archive open(std::string_view bytes, const std::string& path, const Limits& limits = {});

// Indices of Metadata/plate_N.gcode members, in plate number order. Throws
// when there is none.
std::vector<std::size_t> plates(const Archive& a);
// The plate number N of "Metadata/plate_N.gcode", 0 for any other name.
int plate_number(std::string_view member_name);
// Index of a member by name, or -1.
long find(const Archive& a, std::string_view name);

// One member's bytes, inflated and CRC-checked. `budget` is what may still be
// read in total; it is lowered by the member's size. Throws scaffold::Error.
std::string read(const Archive& a, std::size_t index, const Limits& limits, std::uint64_t& budget);

// Every plate's G-code, in plate order (name, text): what scaffold-check and
// the fuzzer read. Throws scaffold::Error as open() and read() do.
std::vector<std::pair<std::string, std::string>> read_plates(std::string_view bytes, const std::string& path,
                                                             const Limits& limits = {});

// The archive again with members replaced (index -> new bytes): a replaced
// member is compressed anew with its own method, every other one copied as
// stored. The same input and replacements give the same bytes.
std::string write(const Archive& a, const std::map<std::size_t, std::string>& replacements);

// Bambu Studio's form of Metadata/plate_N.gcode.md5: uppercase hex, no newline.
std::string md5_hex(std::string_view bytes);

// What scaffold added to one plate, for Metadata/slice_info.config.
struct PlateChange {
    int plate = 0;
    double filament_m = 0;  // metres of filament added
    double seconds = 0;     // print time added
};

// slice_info.config with the plate's prediction (seconds), weight (g) and,
// where the plate uses one filament, that filament's used_m and used_g
// raised (grams at the filament's own used_g / used_m). Other text unchanged.
// Returns the text unchanged when the plate is not in it.
std::string raise_slice_info(std::string_view xml, const PlateChange& change);

}  // namespace scaffold::gcode::archive
