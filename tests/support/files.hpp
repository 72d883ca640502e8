#pragma once
// Small file and text helpers shared by the tests.
#include <string>
#include <string_view>
#include <vector>

namespace scaffold::testing {

// A path in the test temp dir for `name`, one per process: ctest runs the
// tests side by side, and two runs of the suite (a CI host's jobs, a user's
// second build) must not write each other's files.
std::string temp_path(const std::string& name);

// temp_path(name), removed (file or directory) when it goes out of scope,
// a failed assertion's early return included.
struct TempPath {
    explicit TempPath(const std::string& name);
    ~TempPath();
    TempPath(const TempPath&) = delete;
    TempPath& operator=(const TempPath&) = delete;
    const std::string path;
};

// Whole file, gunzipped when its name ends in .gz; empty if unreadable.
std::string load_file(const std::string& path);
void write_file(const std::string& path, const std::string& text);
// The command part of each line (comment and blanks cut, spaces dropped:
// MeatPack keeps neither), blank results skipped.
std::vector<std::string> commands(std::string_view text);

}  // namespace scaffold::testing
