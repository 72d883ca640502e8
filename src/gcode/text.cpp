#include "gcode/text.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#ifdef _WIN32
#include <io.h>
#else
#include <sys/mman.h>
#include <unistd.h>
#endif

#include <cerrno>
#include <cstring>

#include "gcode/error.hpp"

namespace scaffold::gcode {

struct Text::Storage {
    std::string owned;
    void* map = nullptr;
    std::size_t map_size = 0;
    Storage() = default;
    Storage(const Storage&) = delete;
    Storage& operator=(const Storage&) = delete;
    ~Storage() {
#ifndef _WIN32
        if (map) ::munmap(map, map_size);
#endif
    }
};

Text::Text(std::string s) {
    auto st = std::make_shared<Storage>();
    st->owned = std::move(s);
    view_ = st->owned;
    storage_ = std::move(st);
}

bool Text::mapped() const { return storage_ && storage_->map; }

namespace {

std::string read_all(int fd, const std::string& name, std::size_t expected = 0) {
    std::string s;
    s.reserve(expected);
    char buf[1 << 16];
    for (;;) {
#ifdef _WIN32
        int n = ::_read(fd, buf, sizeof buf);
#else
        ssize_t n = ::read(fd, buf, sizeof buf);
#endif
        if (n == 0) return s;
        if (n < 0) {
            if (errno == EINTR) continue;
            throw Error(name, 0, std::string("read failed: ") + std::strerror(errno));
        }
        s.append(buf, static_cast<std::size_t>(n));
    }
}

}  // namespace

#ifdef _WIN32
// Windows cannot rename over a file that is mapped, and the in-place rewrite
// (the slicer hook) renames over the input, so there the file is read whole,
// in binary mode (a CRLF file's bytes stay as they are).
Text Text::load(const std::string& path) {
    if (path == "-") {
        (void)::_setmode(::_fileno(stdin), _O_BINARY);
        return Text(read_all(::_fileno(stdin), "<stdin>"));
    }
    int fd = ::_open(path.c_str(), _O_RDONLY | _O_BINARY | _O_NOINHERIT);
    if (fd < 0) throw Error(path, 0, std::string("cannot open for reading: ") + std::strerror(errno));
    struct _stat64 sb{};
    std::size_t size = ::_fstat64(fd, &sb) == 0 && sb.st_size > 0 ? static_cast<std::size_t>(sb.st_size) : 0;
    try {
        Text t(read_all(fd, path, size + 1));  // +1: the read that finds the end
        ::_close(fd);
        return t;
    } catch (...) {
        ::_close(fd);
        throw;
    }
}

void Text::release(std::uint64_t, std::uint64_t) const {}
#else
Text Text::load(const std::string& path) {
    if (path == "-") return Text(read_all(STDIN_FILENO, "<stdin>"));
    int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
    if (fd < 0) throw Error(path, 0, std::string("cannot open for reading: ") + std::strerror(errno));
    struct stat sb{};
    if (::fstat(fd, &sb) != 0 || !S_ISREG(sb.st_mode) || sb.st_size <= 0) {
        // A pipe, a device or an empty file: read what there is.
        try {
            Text t(read_all(fd, path));
            ::close(fd);
            return t;
        } catch (...) {
            ::close(fd);
            throw;
        }
    }
    auto size = static_cast<std::size_t>(sb.st_size);
    void* m = ::mmap(nullptr, size, PROT_READ, MAP_PRIVATE, fd, 0);
    int err = errno;
    ::close(fd);  // the map keeps the file open
    if (m == MAP_FAILED) throw Error(path, 0, std::string("cannot map the file: ") + std::strerror(err));
    (void)::madvise(m, size, MADV_SEQUENTIAL);  // read ahead: every pass is front to back
    auto st = std::make_shared<Storage>();
    st->map = m;
    st->map_size = size;
    Text t;
    t.view_ = std::string_view(static_cast<const char*>(m), size);
    t.storage_ = std::move(st);
    return t;
}

void Text::release(std::uint64_t begin, std::uint64_t end) const {
    if (!mapped()) return;
    static const std::uint64_t page = static_cast<std::uint64_t>(::sysconf(_SC_PAGESIZE));
    if (end > view_.size()) end = view_.size();
    std::uint64_t from = begin / page * page;  // the pages touching the range: a page
    if (end <= from) return;                    // still in use is only read back
    // MADV_DONTNEED on a private, never written file map only unmaps the
    // pages; reading them again refaults the file's bytes.
    (void)::madvise(static_cast<char*>(storage_->map) + from, end - from, MADV_DONTNEED);
}
#endif

}  // namespace scaffold::gcode
