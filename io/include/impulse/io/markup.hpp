// SPDX-License-Identifier: MIT
#pragma once

#include <string>

namespace impulse::io
{

/// Text safe inside an HTML or XML element or a double-quoted attribute: & < > " escaped.
inline std::string escapeMarkup(const std::string& text)
{
    std::string out;
    for (const char c : text)
    {
        switch (c)
        {
        case '&':
            out += "&amp;";
            break;
        case '<':
            out += "&lt;";
            break;
        case '>':
            out += "&gt;";
            break;
        case '"':
            out += "&quot;";
            break;
        default:
            out += c;
        }
    }
    return out;
}

} // namespace impulse::io
