// SPDX-License-Identifier: MIT
// The progress line of long commands (bench, run, render), drawn on standard error.
#pragma once

#include <chrono>
#include <cmath>
#include <cstdio>
#include <string>
#include <unistd.h>
#include <utility>

namespace impulse::app
{

/// Whether standard error is a terminal: the only place a progress line is drawn.
inline bool stderrIsTerminal()
{
    return isatty(fileno(stderr)) != 0;
}

/// The progress line on standard error: a label, a bar, steps done of all, and the time left.
/// Drawn at most ten times a second, and only when enabled (standard error is a terminal).
class Progress
{
  public:
    explicit Progress(bool enabled, std::string unit = "steps") : m_enabled(enabled), m_unit(std::move(unit)) {}

    void loading(const std::string& name)
    {
        if (m_enabled)
        {
            draw(name + "  loading");
        }
    }

    /// `done` of `total` steps after `elapsed`; `note` follows the count, e.g. " (warm-up)".
    void update(const std::string& name, long long done, long long total, const std::string& note,
                std::chrono::steady_clock::duration elapsed, std::chrono::steady_clock::time_point now)
    {
        if (!m_enabled || (done < total && now - m_lastDraw < std::chrono::milliseconds(100)))
        {
            return;
        }
        m_lastDraw = now;
        constexpr int width = 24;
        const double fraction = total > 0 ? static_cast<double>(done) / static_cast<double>(total) : 1.0;
        const int filled = static_cast<int>(fraction * width);
        const double left = done > 0 ? std::chrono::duration<double>(elapsed).count() / static_cast<double>(done) *
                                           static_cast<double>(total - done)
                                     : 0.0;
        std::string line = name + "  [" + std::string(static_cast<std::size_t>(filled), '#') +
                           std::string(static_cast<std::size_t>(width - filled), '.') + "]  " + std::to_string(done) +
                           "/" + std::to_string(total) + " " + m_unit + note + "  ETA " + duration(left);
        draw(line);
    }

    /// Removes the line, so that what follows starts at the left margin.
    void clear()
    {
        if (m_enabled && m_shown)
        {
            std::fputs("\r\033[K", stderr);
            std::fflush(stderr);
            m_shown = false;
        }
    }

  private:
    static std::string duration(double s)
    {
        const auto whole = static_cast<long long>(std::ceil(s));
        char text[32];
        if (whole < 60)
        {
            std::snprintf(text, sizeof text, "%llds", whole);
        }
        else if (whole < 3600)
        {
            std::snprintf(text, sizeof text, "%lldm%02llds", whole / 60, whole % 60);
        }
        else
        {
            std::snprintf(text, sizeof text, "%lldh%02lldm", whole / 3600, whole % 3600 / 60);
        }
        return text;
    }

    void draw(const std::string& line)
    {
        std::fprintf(stderr, "\r%s\033[K", line.c_str());
        std::fflush(stderr);
        m_shown = true;
    }

    bool m_enabled;
    std::string m_unit;
    bool m_shown = false;
    std::chrono::steady_clock::time_point m_lastDraw{};
};

} // namespace impulse::app
