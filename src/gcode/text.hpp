#pragma once
// The input's bytes, read-only: a memory map of a regular file, or a string
// (stdin, a pipe, text already in memory). Copies share the same bytes.
// On a map, pages already read can be released: they leave the process's
// resident set and come back from the page cache if touched again, so a
// pass over a huge file keeps only a window of it resident.
#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>
#include <string_view>

namespace scaffold::gcode {

class Text {
public:
    Text() = default;
    explicit Text(std::string s);
    // Maps `path` (a regular file) or reads it (anything else); "-" reads
    // stdin. Throws scaffold::Error naming `path` if it cannot be read.
    static Text load(const std::string& path);

    const char* data() const { return view_.data(); }
    std::size_t size() const { return view_.size(); }
    bool empty() const { return view_.empty(); }
    char operator[](std::size_t i) const { return view_[i]; }
    char back() const { return view_.back(); }
    operator std::string_view() const { return view_; }
    bool mapped() const;

    // Drops the resident pages touching [begin, end) of a map (no-op for a
    // string). The bytes stay readable; only the memory is returned, and a
    // page touched again is read back from the page cache.
    void release(std::uint64_t begin, std::uint64_t end) const;

private:
    struct Storage;
    std::shared_ptr<const Storage> storage_;
    std::string_view view_;
};

}  // namespace scaffold::gcode
