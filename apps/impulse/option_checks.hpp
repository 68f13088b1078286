// SPDX-License-Identifier: MIT
// Checks of command-line option values shared by the subcommands.
#pragma once

#include <CLI/CLI.hpp>

#include <charconv>
#include <cmath>
#include <string>

namespace impulse::app
{

/// Accepts a whole number from `low` to `high`, and names the option and the text otherwise
/// (CLI::Range alone calls "abc" a value out of range, and prints its bounds as doubles).
inline CLI::Validator wholeNumber(long long low, long long high)
{
    return CLI::Validator(
        [low, high](std::string& text)
        {
            long long value = 0;
            const char* end = text.data() + text.size();
            const auto [at, error] = std::from_chars(text.data(), end, value);
            if (error != std::errc() || at != end || value < low || value > high)
            {
                return "must be a whole number from " + std::to_string(low) + " to " + std::to_string(high) +
                       ", got \"" + text + "\"";
            }
            return std::string();
        },
        "INT in [" + std::to_string(low) + " - " + std::to_string(high) + "]");
}

/// Accepts a finite number above zero, or with `zeroAllowed` at least zero, and names the text
/// otherwise (CLI::PositiveNumber and CLI::NonNegativeNumber print the largest double in full as
/// their upper bound).
inline CLI::Validator finiteNumber(bool zeroAllowed)
{
    const std::string wanted = zeroAllowed ? "a number of at least 0" : "a number above 0";
    return CLI::Validator(
        [zeroAllowed, wanted](std::string& text)
        {
            double value = 0.0;
            const char* begin = text.data() + (text.starts_with('+') ? 1 : 0);
            const char* end = text.data() + text.size();
            const auto [at, error] = std::from_chars(begin, end, value);
            const bool inRange = zeroAllowed ? value >= 0.0 : value > 0.0;
            if (error != std::errc() || at != end || !std::isfinite(value) || !inRange)
            {
                return "must be " + wanted + ", got \"" + text + "\"";
            }
            return std::string();
        },
        zeroAllowed ? "NONNEGATIVE" : "POSITIVE");
}

inline CLI::Validator positiveNumber()
{
    return finiteNumber(false);
}

inline CLI::Validator nonNegativeNumber()
{
    return finiteNumber(true);
}

} // namespace impulse::app
