#include "gcode/writer.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#ifdef _WIN32
#include <io.h>
#include <process.h>
#ifndef NOMINMAX
#define NOMINMAX
#endif
#define WIN32_LEAN_AND_MEAN
#include <windows.h>
#else
#include <unistd.h>
#endif

#include <algorithm>
#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <optional>

#include "gcode/bgcode.hpp"
#include "gcode/error.hpp"

namespace scaffold::gcode {

namespace {

bool uses_crlf(const Program& p) {
    return !p.lines.empty() && p.lines[0].offset + p.lines[0].length < p.text.size() &&
           p.text[p.lines[0].offset + p.lines[0].length] == '\r';
}

// Output goes to a stream or, for binary G-code made in memory, a string
// (open_memstream is POSIX only: no MinGW).
bool put(std::FILE* out, std::string_view s) { return s.empty() || std::fwrite(s.data(), 1, s.size(), out) == s.size(); }
bool put(std::string* out, std::string_view s) {
    out->append(s);
    return true;
}

template <class Out>
bool put_block(Out out, const std::string& text, bool crlf) {
    if (!crlf) return put(out, text);
    std::size_t pos = 0;
    while (pos < text.size()) {
        std::size_t nl = text.find('\n', pos);
        if (nl == std::string::npos) return put(out, std::string_view(text).substr(pos));
        if (!put(out, std::string_view(text).substr(pos, nl - pos)) || !put(out, "\r\n")) return false;
        pos = nl + 1;
    }
    return true;
}

// Copies text[from, to) in pieces, releasing each piece of a mapped input
// once written, so writing a huge file keeps only a piece of it resident.
template <class Out>
bool copy_text(Out out, const Text& text, std::uint64_t from, std::uint64_t to) {
    constexpr std::uint64_t kPiece = std::uint64_t{8} << 20;
    std::string_view all(text);
    while (from < to) {
        std::uint64_t n = std::min(kPiece, to - from);
        if (!put(out, all.substr(from, n))) return false;
        text.release(from, from + n);
        from += n;
    }
    return true;
}

#ifdef _WIN32
// The POSIX calls write_output makes, in their Windows form. A file is
// replaced with MoveFileEx (rename() refuses an existing target there).
int open_new(const std::string& tmp) {
    return ::_open(tmp.c_str(), _O_WRONLY | _O_CREAT | _O_EXCL | _O_BINARY | _O_NOINHERIT, _S_IREAD | _S_IWRITE);
}
void keep_mode(const std::string&, int) {}  // Windows has no mode bits to keep
int sync_fd(int fd) { return ::_commit(fd); }
int process_id() { return ::_getpid(); }
std::string replace_file(const std::string& tmp, const std::string& path) {
    if (::MoveFileExA(tmp.c_str(), path.c_str(), MOVEFILE_REPLACE_EXISTING | MOVEFILE_WRITE_THROUGH)) return {};
    char msg[512];
    DWORD n = ::FormatMessageA(FORMAT_MESSAGE_FROM_SYSTEM | FORMAT_MESSAGE_IGNORE_INSERTS, nullptr, ::GetLastError(), 0,
                               msg, sizeof msg, nullptr);
    while (n > 0 && (msg[n - 1] == '\r' || msg[n - 1] == '\n' || msg[n - 1] == '.')) --n;
    return n > 0 ? std::string(msg, n) : "error " + std::to_string(::GetLastError());
}
constexpr const char* kDirSeparators = "/\\:";
// The NUL device: written to, never replaced.
bool device_path(const std::string& path) { return _stricmp(path.c_str(), "NUL") == 0; }
std::string resolved(const std::string& path) { return path; }
#else
int open_new(const std::string& tmp) { return ::open(tmp.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0644); }
void keep_mode(const std::string& path, int fd) {
    struct stat st{};
    if (::stat(path.c_str(), &st) == 0) (void)::fchmod(fd, st.st_mode & 07777);
}
int sync_fd(int fd) { return ::fsync(fd); }
int process_id() { return ::getpid(); }
std::string replace_file(const std::string& tmp, const std::string& path) {
    return ::rename(tmp.c_str(), path.c_str()) == 0 ? std::string() : std::strerror(errno);
}
constexpr const char* kDirSeparators = "/";
// A device or a pipe (/dev/null, /dev/stdout, a FIFO): written to, never
// replaced (a rename over /dev/null would leave a plain file there).
bool device_path(const std::string& path) {
    struct stat st{};
    return ::stat(path.c_str(), &st) == 0 && !S_ISREG(st.st_mode) && !S_ISDIR(st.st_mode);
}
// A symbolic link's target, replaced in its place: renamed over the link,
// the link would become a file of its own and its target stay unchanged.
std::string resolved(const std::string& path) {
    struct stat st{};
    if (::lstat(path.c_str(), &st) != 0 || !S_ISLNK(st.st_mode)) return path;
    char* real = ::realpath(path.c_str(), nullptr);
    if (!real) return path;
    std::string out(real);
    std::free(real);
    return out;
}
#endif

}  // namespace

namespace {

template <class Out>
bool write_edited_to(Out out, const Program& p, std::vector<Edit> edits) {
    std::stable_sort(edits.begin(), edits.end(), [](const Edit& a, const Edit& b) {
        return a.line != b.line ? a.line < b.line : (!a.replace && b.replace);
    });
    bool crlf = uses_crlf(p);
    std::string_view text(p.text);
    std::uint64_t copied = 0;  // bytes of the input already written
    for (const Edit& e : edits) {
        std::uint32_t line = std::min<std::uint32_t>(e.line, static_cast<std::uint32_t>(p.lines.size()));
        std::uint64_t at = line < p.lines.size() ? p.lines[line].offset : text.size();
        if (at > copied) {
            if (!copy_text(out, p.text, copied, at)) return false;
            copied = at;
        }
        // A last line without a newline gets one before anything follows it.
        if (at == text.size() && !text.empty() && text.back() != '\n' && copied == text.size()) {
            if (!put(out, crlf ? "\r\n" : "\n")) return false;
            copied = text.size() + 1;  // mark as terminated
        }
        if (!put_block(out, e.text, crlf)) return false;
        if (e.replace && line < p.lines.size()) {
            // Skip the replaced line's bytes but keep its line ending.
            copied = p.lines[line].offset + p.lines[line].length;
        }
    }
    if (copied < text.size() && !copy_text(out, p.text, copied, text.size())) return false;
    return true;
}

}  // namespace

bool write_edited(std::FILE* out, const Program& p, std::vector<Edit> edits) { return write_edited_to(out, p, std::move(edits)); }

std::string render_edited(const Program& p, std::vector<Edit> edits) {
    std::string s;
    s.reserve(p.text.size() + 4096);
    write_edited_to(&s, p, std::move(edits));
    return s;
}

bool text_output(const Program& program, OutputFormat format) {
    return format == OutputFormat::Ascii || (format == OutputFormat::SameAsInput && !program.binary);
}

namespace {

// Binary output, made in memory before any file is touched; nothing for text.
std::optional<std::string> binary_output(const Program& p, std::vector<Edit>& edits, OutputFormat format) {
    if (text_output(p, format)) return std::nullopt;
    if (p.binary && edits.empty()) return std::string(std::string_view(p.binary->original));
    if (p.binary) return bgcode::encode_edited(p, std::move(edits));
    return bgcode::encode_ascii(render_edited(p, std::move(edits)), bgcode::Settings{});
}

}  // namespace

namespace {

// Writes what `emit` puts out to the file `path` through a temporary file
// beside it, renamed over it once complete.
template <class Emit>
void write_file_atomically(const std::string& path, Emit emit) {
    // The temporary file goes beside the target (same directory, same drive).
    std::size_t cut = path.find_last_of(kDirSeparators);
    cut = cut == std::string::npos ? 0 : cut + 1;
    std::string tmp = path.substr(0, cut) + "." + path.substr(cut) + ".scaffold-" + std::to_string(process_id()) + ".tmp";
    int fd = open_new(tmp);
    if (fd < 0) throw Error(path, 0, std::string("cannot create the output file: ") + std::strerror(errno));
    keep_mode(path, fd);  // keep the original's mode
    std::FILE* out = ::fdopen(fd, "wb");
    if (!out) {
        int err = errno;
        ::close(fd);
        std::remove(tmp.c_str());
        throw Error(path, 0, std::string("cannot write the output file: ") + std::strerror(err));
    }
    // A test hook to prove that a failed write leaves the target untouched.
    bool fail = std::getenv("SCAFFOLD_TEST_FAIL_WRITE") != nullptr;
    bool ok = !fail && emit(out);
    ok = ok && std::fflush(out) == 0 && sync_fd(fd) == 0;
    int err = fail ? EIO : errno;
    if (std::fclose(out) != 0 && ok) { ok = false; err = errno; }
    if (!ok) {
        std::remove(tmp.c_str());
        throw Error(path, 0, std::string("writing the output failed (") + std::strerror(err) +
                                 "); the original file is unchanged");
    }
    if (std::string why = replace_file(tmp, path); !why.empty()) {
        std::remove(tmp.c_str());
        throw Error(path, 0, "cannot replace the output file: " + why);
    }
}

// Writes what `emit` puts out to `path`: "-" is stdout, a device or a pipe
// is written to, a file is replaced whole (write_file_atomically).
template <class Emit>
void write_atomically(const std::string& path, Emit emit) {
    if (path == "-") {
#ifdef _WIN32
        (void)::_setmode(::_fileno(stdout), _O_BINARY);  // no '\n' -> CRLF translation
#endif
        if (!emit(stdout) || std::fflush(stdout) != 0)
            throw Error("<stdout>", 0, std::string("write failed: ") + std::strerror(errno));
        return;
    }
    if (device_path(path)) {
        std::FILE* out = std::fopen(path.c_str(), "wb");
        if (!out) throw Error(path, 0, std::string("cannot open the output: ") + std::strerror(errno));
        bool ok = emit(out) && std::fflush(out) == 0;
        const int err = errno;
        ok = std::fclose(out) == 0 && ok;
        if (!ok) throw Error(path, 0, std::string("write failed: ") + std::strerror(err));
        return;
    }
    write_file_atomically(resolved(path), emit);
}

}  // namespace

bool is_device(const std::string& path) { return path != "-" && device_path(path); }

void write_output(const std::string& path, const Program& program, std::vector<Edit> edits, OutputFormat format) {
    std::optional<std::string> binary = binary_output(program, edits, format);
    write_atomically(path, [&](std::FILE* out) {
        return binary ? put(out, *binary) : write_edited(out, program, std::move(edits));
    });
}

void write_bytes(const std::string& path, std::string_view bytes) {
    write_atomically(path, [&](std::FILE* out) { return put(out, bytes); });
}

void write_text_file(const std::string& path, const std::string& text) {
    std::ofstream out(path, std::ios::binary);
    if (!out || !(out << text) || !out.flush()) throw Error(path, 0, "cannot write this file");
}

}  // namespace scaffold::gcode
