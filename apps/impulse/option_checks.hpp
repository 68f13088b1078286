// SPDX-License-Identifier: MIT
// Checks of command-line option values shared by the subcommands.
#pragma once

#include <CLI/CLI.hpp>

#include <charconv>
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

} // namespace impulse::app
