// scatterlut generator — what a JSON text must pass before nlohmann's parser sees it.
// The parser recurses once per nesting level (100000 '[' exhaust the stack) and its error
// messages quote the offending bytes (invalid UTF-8 then makes dump() throw); both are
// refused here first, in one pass without allocation.
#pragma once

#include <cstddef>
#include <string>

namespace scatterlut {

// The first problem of `text`, or "": not valid UTF-8 (named by byte offset; overlong
// forms, surrogates and code points past U+10FFFF included) or arrays/objects nested
// deeper than max_depth outside strings.
std::string json_text_problem(const std::string &text, int max_depth);

// The length (1 to 4) of the UTF-8 sequence starting at text[i], or 0 if it is not valid
// UTF-8 there (overlong forms, surrogates, beyond U+10FFFF, truncated).
size_t utf8_sequence_length(const std::string &text, size_t i);

} // namespace scatterlut
