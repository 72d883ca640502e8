#pragma once
// The one exception type of the pipeline: a sentence a user understands,
// with the file and line it is about. Caught only in cli/.
#include <cstddef>
#include <stdexcept>
#include <string>
#include <string_view>

namespace scaffold {

class Error : public std::runtime_error {
public:
    Error(std::string file, std::size_t line, const std::string& message)
        : std::runtime_error(format(file, line, message)), file_(std::move(file)), line_(line) {}
    explicit Error(const std::string& message) : std::runtime_error(message), line_(0) {}

    const std::string& file() const { return file_; }
    std::size_t line() const { return line_; }  // 1-based; 0 when not about a line

private:
    static std::string format(const std::string& file, std::size_t line, const std::string& message) {
        std::string out;
        out.append(file.empty() ? std::string_view("<input>") : std::string_view(file));
        if (line > 0) {
            out.push_back(':');
            out.append(std::to_string(line));
        }
        out.append(": ");
        out.append(message);
        return out;
    }
    std::string file_;
    std::size_t line_;
};

}  // namespace scaffold
