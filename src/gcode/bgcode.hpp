#pragma once
// Prusa binary G-code (.bgcode): a file header, then blocks of metadata,
// thumbnails and G-code, each compressed and encoded on its own and
// checksummed. Reading turns a file into the ASCII text PrusaSlicer's own
// converter writes, plus a Layout that lets the writer put it back together
// with the same settings: blocks left alone are copied byte for byte.
#include <cstdint>
#include <cstdio>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "gcode/text.hpp"

namespace scaffold::gcode {
struct Program;
struct Edit;
}  // namespace scaffold::gcode

namespace scaffold::gcode::bgcode {

enum class BlockType : std::uint16_t { FileMetadata = 0, GCode = 1, SlicerMetadata = 2, PrinterMetadata = 3, PrintMetadata = 4, Thumbnail = 5 };
enum class Compression : std::uint16_t { None = 0, Deflate = 1, Heatshrink11 = 2, Heatshrink12 = 3 };
enum class GCodeEncoding : std::uint16_t { None = 0, MeatPack = 1, MeatPackComments = 2 };
const char* block_type_name(std::uint16_t type);

using Metadata = std::vector<std::pair<std::string, std::string>>;  // in file order

struct Block {
    std::uint16_t type = 0;
    std::uint16_t compression = 0;
    std::uint16_t params[3] = {0, 0, 0};  // encoding; or thumbnail format, width, height
    std::uint64_t offset = 0;             // of the block header in the file
    std::uint64_t size = 0;               // header to checksum, all included
};

struct Thumbnail {
    std::uint16_t format = 0, width = 0, height = 0;
    std::string data;  // the image file's bytes
};

// How to write G-code out: checksum and, per block type, compression.
struct Settings {
    std::uint16_t checksum = 1;  // 0 none, 1 CRC32
    Compression file_metadata = Compression::None;
    Compression printer_metadata = Compression::None;
    Compression thumbnail = Compression::None;
    Compression print_metadata = Compression::Deflate;
    Compression slicer_metadata = Compression::Deflate;
    Compression gcode = Compression::Heatshrink12;
    GCodeEncoding encoding = GCodeEncoding::MeatPackComments;
};

// What a binary input was made of, and where each part sits in its ASCII
// text (0-based line indices), for writing it back.
struct Layout {
    Text original;  // the file's bytes
    Settings settings;
    std::vector<Block> blocks;
    Metadata file_metadata, printer_metadata, print_metadata, slicer_metadata;
    std::vector<Thumbnail> thumbnails;
    std::uint32_t printer_line = 0;  // first printer metadata line
    std::uint32_t gcode_line = 0;    // first G-code line
    std::uint32_t gcode_end = 0;     // one past the last G-code line
    std::uint32_t print_line = 0;    // first print metadata line
    std::uint32_t slicer_line = 0;   // first slicer metadata line (after "begin")
};

struct Decoded {
    std::string ascii;
    Layout layout;
};

bool is_binary(std::string_view bytes);
// Throws scaffold::Error naming `path`, the block's index and type and its
// byte offset when the file is damaged or uses what the format lacks.
Decoded decode(const Text& bytes, const std::string& path);

// Plain G-code to binary: metadata picked from the text's own comments the
// way PrusaSlicer fills it in, the rest as G-code blocks.
std::string encode_ascii(std::string_view ascii, const Settings& settings);

// The program with edits applied, as binary G-code with the input's settings
// (the input must have been binary). Edits must not change the number of
// lines before the G-code or after it; inserts there move into the G-code.
std::string encode_edited(const Program& program, std::vector<Edit> edits);

// One block: header, parameters, data compressed (and G-code encoded) as
// asked, checksum. Exposed for tests that build damaged files.
std::string make_block(BlockType type, Compression compression, const std::uint16_t* params, std::string_view data,
                       std::uint16_t checksum);
std::string file_header(std::uint16_t checksum);
std::string metadata_text(const Metadata& m);

}  // namespace scaffold::gcode::bgcode
