#pragma once
// Splits one G-code line into its command and parameter words without
// allocating: views into the line, numbers by std::from_chars.
#include <array>
#include <cstdint>
#include <string_view>

namespace scaffold::gcode {

struct Word {
    char letter = 0;   // upper case
    double value = 0;
};

struct Command {
    char letter = 0;           // 'G', 'M', 'T' or 0 (comment/blank/other)
    int code = -1;             // G1 -> 1, M106 -> 106, T1 -> 1
    int subcode = -1;          // G29.1 -> 1
    std::array<Word, 12> words{};
    int word_count = 0;
    std::string_view comment;  // text after ';' (without it), trimmed left
    std::string_view code_text;  // the code part (before ';'), trimmed

    const Word* find(char letter_) const {
        for (int i = 0; i < word_count; ++i)
            if (words[i].letter == letter_) return &words[i];
        return nullptr;
    }
    bool has(char letter_) const { return find(letter_) != nullptr; }
    double get(char letter_, double fallback) const {
        const Word* w = find(letter_);
        return w ? w->value : fallback;
    }
    bool is(char l, int c) const { return letter == l && code == c; }
};

// Parses `line` (no line ending). Returns an empty string on success, else a
// sentence describing what is malformed. Words of commands whose parameters
// are free text (M117, M118, M23, ...) are not parsed.
const char* lex(std::string_view line, Command& out);

}  // namespace scaffold::gcode
