#pragma once
// Step 7: the output. The input's bytes are copied unchanged except where an
// Edit inserts a block before a line or replaces a line. Files are written
// to a temporary file beside the target, synced, then renamed over it, so a
// failure never leaves a half-written output.
#include <cstdint>
#include <cstdio>
#include <string>
#include <string_view>
#include <vector>

#include "gcode/program.hpp"

namespace scaffold::gcode {

struct Edit {
    std::uint32_t line = 0;  // 0-based; lines.size() means "at the end"
    bool replace = false;    // replace that line instead of inserting before it
    // Insert: '\n'-terminated lines (converted to CRLF if the file uses it).
    // Replace: the line's new content, without a line ending (the original
    // ending is kept).
    std::string text;
};

// Streams the program with edits applied (edits sorted by line, stable).
// Returns false if the stream reported an error.
bool write_edited(std::FILE* out, const Program& program, std::vector<Edit> edits);
// The same, into a string (binary output is made in memory).
std::string render_edited(const Program& program, std::vector<Edit> edits);

enum class OutputFormat : std::uint8_t { SameAsInput, Ascii, Binary };
// Whether write_output writes `program` in `format` as text (else as binary G-code).
bool text_output(const Program& program, OutputFormat format);

// Whether `path` is a device or a pipe (/dev/null, a FIFO; NUL on Windows):
// written to as it is, never replaced, and nothing can be read back from it.
bool is_device(const std::string& path);

// Writes to `path` atomically ("-" writes to stdout, a device or a pipe is
// written to, a symbolic link's target replaced). Throws scaffold::Error.
// Binary G-code keeps a binary input's settings; unchanged, its bytes.
void write_output(const std::string& path, const Program& program, std::vector<Edit> edits,
                  OutputFormat format = OutputFormat::SameAsInput);

// Bytes made in memory (a .gcode.3mf archive), written like write_output.
void write_bytes(const std::string& path, std::string_view bytes);

// A side file (report, picture, dump): written directly, not atomically.
// Throws scaffold::Error if it cannot be written.
void write_text_file(const std::string& path, const std::string& text);

}  // namespace scaffold::gcode
