// Whitespace-separated tokens of a text mesh format, with line numbers for errors.
#pragma once

#include "io/mesh.h"

#include <cstdint>
#include <string>
#include <string_view>

namespace vqsa {

class TextTokenizer {
public:
    // `comment` starts a comment that runs to the end of the line ('\0': none).
    explicit TextTokenizer(std::string_view text, char comment = '#');

    // Skips white space and comments; true when nothing is left.
    bool at_end();
    // The next token on any line; throws at the end of the text, naming `what`.
    std::string_view token(const char* what);
    // The next token if it is on the current line, else empty.
    std::string_view token_on_line();
    double number(const char* what);
    // Three numbers: a vertex position.
    Vec3 point() {
        const double x = number("a vertex coordinate"), y = number("a vertex coordinate");
        return {x, y, number("a vertex coordinate")};
    }
    std::int64_t integer(const char* what);
    void skip_line();
    // When nothing but white space is left on the line: moves to the next one, true.
    bool continue_line();
    std::size_t line() const { return line_; }

    // "line N: " + message, as std::invalid_argument.
    [[noreturn]] void fail(const std::string& message) const;

private:
    void skip_space(bool cross_lines);

    std::string_view text_;
    std::size_t pos_ = 0;
    std::size_t line_ = 1;
    char comment_;
};

// Parses a whole token as a number; false when it is not one.
bool parse_double(std::string_view token, double& value);
bool parse_integer(std::string_view token, std::int64_t& value);

}  // namespace vqsa
