#pragma once
// Small file and text helpers shared by the tests.
#include <string>
#include <string_view>
#include <vector>

namespace scaffold::testing {

// Whole file, gunzipped when its name ends in .gz; empty if unreadable.
std::string load_file(const std::string& path);
void write_file(const std::string& path, const std::string& text);
// The command part of each line (comment and blanks cut, spaces dropped:
// MeatPack keeps neither), blank results skipped.
std::vector<std::string> commands(std::string_view text);

}  // namespace scaffold::testing
