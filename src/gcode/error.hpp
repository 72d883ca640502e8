#pragma once
// The one exception type of the pipeline: a sentence a user understands,
// with the file and line it is about. Caught only in cli/.
#include <cstddef>
#include <stdexcept>
#include <string>

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
        std::string out = file.empty() ? std::string("<input>") : file;
        if (line > 0) out += ":" + std::to_string(line);
        return out + ": " + message;
    }
    std::string file_;
    std::size_t line_;
};

}  // namespace scaffold
