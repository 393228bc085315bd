#include "io/text_tokenizer.h"

#include <fast_float/fast_float.h>

#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <stdexcept>

namespace vqsa {

namespace {

// Not strchr: it would also match a NUL byte in the text, which then ended no token.
bool is_space(char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\n' || c == '\f' || c == '\v'; }

}  // namespace

TextTokenizer::TextTokenizer(std::string_view text, char comment) : text_(text), comment_(comment) {}

void TextTokenizer::skip_space(bool cross_lines) {
    while (pos_ < text_.size()) {
        const char c = text_[pos_];
        if (c == '\n') {
            if (!cross_lines) return;
            ++line_;
        } else if (comment_ != '\0' && c == comment_) {
            while (pos_ < text_.size() && text_[pos_] != '\n') ++pos_;
            continue;
        } else if (!is_space(c)) {
            return;
        }
        ++pos_;
    }
}

bool TextTokenizer::at_end() {
    skip_space(true);
    return pos_ >= text_.size();
}

std::string_view TextTokenizer::token(const char* what) {
    if (at_end()) fail(std::string("unexpected end of file, expected ") + what);
    const std::size_t start = pos_;
    while (pos_ < text_.size() && !is_space(text_[pos_]) && !(comment_ != '\0' && text_[pos_] == comment_)) ++pos_;
    return text_.substr(start, pos_ - start);
}

std::string_view TextTokenizer::token_on_line() {
    skip_space(false);
    if (pos_ >= text_.size() || text_[pos_] == '\n') return {};
    const std::size_t start = pos_;
    while (pos_ < text_.size() && !is_space(text_[pos_]) && !(comment_ != '\0' && text_[pos_] == comment_)) ++pos_;
    return text_.substr(start, pos_ - start);
}

double TextTokenizer::number(const char* what) {
    const std::string_view t = token(what);
    double value;
    if (!parse_double(t, value)) fail(std::string("expected ") + what + ", found '" + std::string(t.substr(0, 40)) + "'");
    return value;
}

std::int64_t TextTokenizer::integer(const char* what) {
    const std::string_view t = token(what);
    std::int64_t value;
    if (!parse_integer(t, value)) fail(std::string("expected ") + what + ", found '" + std::string(t.substr(0, 40)) + "'");
    return value;
}

void TextTokenizer::skip_line() {
    while (pos_ < text_.size() && text_[pos_] != '\n') ++pos_;
}

bool TextTokenizer::continue_line() {
    skip_space(false);
    if (pos_ >= text_.size() || text_[pos_] != '\n') return false;
    ++pos_;
    ++line_;
    return true;
}

void TextTokenizer::fail(const std::string& message) const {
    throw std::invalid_argument("line " + std::to_string(line_) + ": " + message);
}

bool parse_double(std::string_view token, double& value) {
    // Not strtod: musl's (the WASM build's C library) computes in 128-bit long double,
    // which WebAssembly emulates in software (text meshes loaded 3x slower than natively);
    // fast_float rounds the same, correctly. It takes no leading '+', which strtod did.
    const char* first = token.data();
    const char* const last = first + token.size();
    if (token.size() > 1 && token[0] == '+' && token[1] != '-') ++first;
    const fast_float::from_chars_result result = fast_float::from_chars(first, last, value);
    return result.ec == std::errc() && result.ptr == last;
}

bool parse_integer(std::string_view token, std::int64_t& value) {
    char buffer[32];
    if (token.empty() || token.size() >= sizeof buffer) return false;
    std::memcpy(buffer, token.data(), token.size());
    buffer[token.size()] = '\0';
    char* end = nullptr;
    errno = 0;
    value = std::strtoll(buffer, &end, 10);
    return end == buffer + token.size() && errno == 0;
}

}  // namespace vqsa
