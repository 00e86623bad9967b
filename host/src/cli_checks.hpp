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

// A validator named `name` (in --help) whose check returns "" or what it expected.
template <class Check> CLI::Validator text_validator(const char *name, Check check) {
    return CLI::Validator([check](std::string &text) -> std::string { return check(text); }, name, name);
}

// Whether strto*'s parse of `text` ended at its end and read something.
inline bool parsed_whole(const std::string &text, const char *end) {
    return !text.empty() && end != text.c_str() && *end == '\0';
}

// A finite decimal number ("nan", "inf", "1e999" and trailing text refused).
inline CLI::Validator finite_number() {
    return text_validator("FINITE", [](const std::string &text) -> std::string {
        char *end = nullptr;
        errno = 0;
        const double x = std::strtod(text.c_str(), &end);
        if (!parsed_whole(text, end)) return "expected a number, got '" + text + "'";
        if (!std::isfinite(x) || (errno == ERANGE && std::fabs(x) > 1.0))
            return "expected a finite number, got '" + text + "'";
        return std::string();
    });
}

// A decimal integer that fits an int ("8.5", "abc", "1e3" refused).
inline CLI::Validator integer_number() {
    return text_validator("INT", [](const std::string &text) -> std::string {
        char *end = nullptr;
        errno = 0;
        const long long x = std::strtoll(text.c_str(), &end, 10);
        if (!parsed_whole(text, end)) return "expected an integer, got '" + text + "'";
        if (errno == ERANGE || x < -2147483647LL || x > 2147483647LL)
            return "expected an integer of at most 10 digits, got '" + text + "'";
        return std::string();
    });
}

// An integer option in [lo, hi], its default shown in --help: integer_number() first (it
// names what it expected), then CLI::Range.
template <class T>
CLI::Option *add_integer_option(CLI::App *cmd, const std::string &name, T &value, const std::string &what, int lo,
                                int hi) {
    return cmd->add_option(name, value, what)->check(integer_number())->check(CLI::Range(lo, hi));
}

// A non-empty value: an empty --out (an unset shell variable) must not fall back to a
// default directory.
inline CLI::Validator non_empty_text(const std::string &expected) {
    return text_validator("NONEMPTY", [expected](const std::string &text) -> std::string {
        return text.empty() ? "expected " + expected + ", got an empty string" : std::string();
    });
}

} // namespace scatterlut
