// scatterlut generator — validators shared by every numeric command-line option. CLI11's
// Range alone lets NaN through (every comparison with NaN is false) and reports a word
// that is not a number only after conversion, without saying what was expected; these run
// first, on the text, so that each refusal names the option and what it expected.
#pragma once

#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <string>

#include <CLI/CLI.hpp>

namespace scatterlut {

// A finite decimal number ("nan", "inf", "1e999" and trailing text refused).
inline CLI::Validator finite_number() {
    return CLI::Validator(
        [](std::string &text) -> std::string {
            const char *begin = text.c_str();
            char *end = nullptr;
            errno = 0;
            const double x = std::strtod(begin, &end);
            if (text.empty() || end == begin || *end != '\0') return "expected a number, got '" + text + "'";
            if (!std::isfinite(x) || (errno == ERANGE && std::fabs(x) > 1.0))
                return "expected a finite number, got '" + text + "'";
            return std::string();
        },
        "FINITE", "FINITE");
}

// A decimal integer that fits an int ("8.5", "abc", "1e3" refused).
inline CLI::Validator integer_number() {
    return CLI::Validator(
        [](std::string &text) -> std::string {
            const char *begin = text.c_str();
            char *end = nullptr;
            errno = 0;
            const long long x = std::strtoll(begin, &end, 10);
            if (text.empty() || end == begin || *end != '\0') return "expected an integer, got '" + text + "'";
            if (errno == ERANGE || x < -2147483647LL || x > 2147483647LL)
                return "expected an integer of at most 10 digits, got '" + text + "'";
            return std::string();
        },
        "INT", "INT");
}

// A non-empty value: an empty --out (an unset shell variable) must not fall back to a
// default directory.
inline CLI::Validator non_empty_text(const std::string &expected) {
    return CLI::Validator(
        [expected](std::string &text) -> std::string {
            return text.empty() ? "expected " + expected + ", got an empty string" : std::string();
        },
        "NONEMPTY", "NONEMPTY");
}

} // namespace scatterlut
