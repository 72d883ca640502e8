#include "support/files.hpp"

#include <zlib.h>

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <sstream>

namespace scaffold::testing {

std::string temp_path(const std::string& name) {
    return ::testing::TempDir() + "/" + name + "." + std::to_string(::getpid());
}

TempPath::TempPath(const std::string& name) : path(temp_path(name)) {}

TempPath::~TempPath() {
    std::error_code ec;
    std::filesystem::remove_all(path, ec);
}

std::string load_file(const std::string& path) {
    if (path.size() > 3 && path.substr(path.size() - 3) == ".gz") {
        gzFile f = gzopen(path.c_str(), "rb");
        if (!f) return {};
        std::string s;
        char buf[1 << 16];
        int n;
        while ((n = gzread(f, buf, sizeof buf)) > 0) s.append(buf, static_cast<std::size_t>(n));
        gzclose(f);
        return s;
    }
    std::ifstream in(path, std::ios::binary);
    std::stringstream ss;
    ss << in.rdbuf();
    return ss.str();
}

void write_file(const std::string& path, const std::string& text) {
    std::ofstream out(path, std::ios::binary);
    out << text;
}

std::vector<std::string> commands(std::string_view text) {
    std::vector<std::string> out;
    std::size_t pos = 0;
    while (pos < text.size()) {
        std::size_t nl = text.find('\n', pos);
        std::size_t end = nl == std::string_view::npos ? text.size() : nl;
        std::string_view l = text.substr(pos, end - pos);
        pos = end + 1;
        l = l.substr(0, l.find(';'));
        std::string c;
        for (char ch : l)
            if (ch != ' ' && ch != '\t' && ch != '\r') c.push_back(ch);
        if (!c.empty()) out.push_back(c);
    }
    return out;
}

}  // namespace scaffold::testing
