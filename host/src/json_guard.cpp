#include "json_guard.hpp"

namespace scatterlut {

size_t utf8_sequence_length(const std::string &text, size_t i) {
    const size_t n = text.size();
    const unsigned char c = static_cast<unsigned char>(text[i]);
    if (c < 0x80) return 1;
    // 2 to 4 bytes, no overlong forms, no surrogates, at most U+10FFFF.
    size_t len;
    unsigned lo = 0x80, hi = 0xBF;
    if (c >= 0xC2 && c <= 0xDF) {
        len = 2;
    } else if (c >= 0xE0 && c <= 0xEF) {
        len = 3;
        if (c == 0xE0) lo = 0xA0;
        if (c == 0xED) hi = 0x9F;
    } else if (c >= 0xF0 && c <= 0xF4) {
        len = 4;
        if (c == 0xF0) lo = 0x90;
        if (c == 0xF4) hi = 0x8F;
    } else {
        return 0;
    }
    for (size_t k = 1; k < len; ++k) {
        const unsigned char b = i + k < n ? static_cast<unsigned char>(text[i + k]) : 0;
        if (b < (k == 1 ? lo : 0x80u) || b > (k == 1 ? hi : 0xBFu)) return 0;
    }
    return len;
}

std::string json_text_problem(const std::string &line, int max_depth) {
    int depth = 0;
    bool in_string = false, escaped = false;
    const size_t n = line.size();
    for (size_t i = 0; i < n;) {
        const unsigned char c = static_cast<unsigned char>(line[i]);
        size_t len = 1;
        if (c >= 0x80) {
            len = utf8_sequence_length(line, i);
            if (len == 0) return "not valid UTF-8 (byte " + std::to_string(i + 1) + ")";
            i += len;
            continue;
        }
        ++i;
        if (in_string) {
            if (escaped) escaped = false;
            else if (c == '\\') escaped = true;
            else if (c == '"') in_string = false;
        } else if (c == '"') {
            in_string = true;
        } else if (c == '[' || c == '{') {
            if (++depth > max_depth)
                return "nested deeper than " + std::to_string(max_depth) + " arrays/objects";
        } else if (c == ']' || c == '}') {
            --depth;
        }
    }
    return std::string();
}

} // namespace scatterlut
