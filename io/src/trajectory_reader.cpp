// SPDX-License-Identifier: MIT
#include <impulse/io/trajectory_reader.hpp>

#include <array>
#include <charconv>
#include <cmath>
#include <fstream>
#include <sstream>

namespace impulse::io
{
namespace
{

constexpr const char* expectedHeader = "t,body,x,y,z,qw,qx,qy,qz,vx,vy,vz,wx,wy,wz";
constexpr std::size_t columnCount = 15;

[[noreturn]] void fail(const std::string& source, std::size_t line, const std::string& what)
{
    throw TrajectoryError(source + ": line " + std::to_string(line) + ": " + what);
}

/// A number as short as it can be written and still exact: "2", "0.5", "3.3333333333333331e+123".
std::string numberText(double value)
{
    std::ostringstream text;
    text.precision(17);
    text << value;
    return text.str();
}

/// Splits one row into exactly 15 finite numbers, or says why it cannot.
std::array<double, columnCount> parseRow(const std::string& row, const std::string& source, std::size_t line)
{
    static const std::array<const char*, columnCount> names = {"t",  "body", "x",  "y",  "z",  "qw", "qx", "qy",
                                                               "qz", "vx",   "vy", "vz", "wx", "wy", "wz"};
    std::array<double, columnCount> values{};
    std::size_t begin = 0;
    for (std::size_t column = 0; column < columnCount; ++column)
    {
        const std::size_t comma = row.find(',', begin);
        const bool last = column + 1 == columnCount;
        if (!last && comma == std::string::npos)
        {
            fail(source, line, "expected 15 comma-separated numbers, got " + std::to_string(column + 1));
        }
        if (last && comma != std::string::npos)
        {
            fail(source, line, "expected 15 comma-separated numbers, got more");
        }
        const std::size_t end = last ? row.size() : comma;
        const char* first = row.data() + begin;
        const char* stop = row.data() + end;
        double value = 0.0;
        const auto [ptr, error] = std::from_chars(first, stop, value);
        if (error != std::errc() || ptr != stop || !std::isfinite(value))
        {
            fail(source, line,
                 std::string("column ") + names[column] + ": not a finite number: \"" + std::string(first, stop) +
                     "\"");
        }
        values[column] = value;
        begin = end + 1;
    }
    return values;
}

} // namespace

Trajectory parseTrajectory(std::istream& in, const std::string& source)
{
    Trajectory trajectory;
    std::string row;
    std::size_t line = 0;
    bool unterminated = false; // the line just read has no end of line: the file was cut off in it
    auto readLine = [&]() -> bool
    {
        if (!std::getline(in, row))
        {
            return false;
        }
        ++line;
        unterminated = in.eof();
        if (!row.empty() && row.back() == '\r')
        {
            row.pop_back(); // tolerate files that went through a Windows editor
        }
        return true;
    };

    if (!readLine())
    {
        fail(source, 1, std::string("empty file; expected the header ") + expectedHeader);
    }
    if (row != expectedHeader)
    {
        fail(source, 1, std::string("header must be ") + expectedHeader + "; got " + row.substr(0, 200));
    }

    // Rows come in groups, one per sample: bodies 0, 1, ..., n-1 at the same time. The first group
    // fixes n; every later group must repeat it.
    bool countKnown = false;
    std::size_t nextBody = 0;
    std::size_t cutLine = 0;
    while (readLine())
    {
        if (row.empty())
        {
            continue;
        }
        if (unterminated)
        {
            cutLine = line; // a row the writer never finished: its last number may be cut short
            break;
        }
        const auto v = parseRow(row, source, line);
        const double body = v[1];
        if (body != std::floor(body) || body < 0.0)
        {
            fail(source, line, "body must be a whole number >= 0, got " + numberText(body));
        }
        if (body > static_cast<double>(nextBody))
        {
            // never the body expected, and perhaps too large for a size_t: refused before converting
            const std::size_t expected = countKnown && nextBody == trajectory.bodyCount ? 0 : nextBody;
            fail(source, line,
                 "expected body " + std::to_string(expected) + " (each sample lists bodies 0, 1, ... in order), got " +
                     numberText(body));
        }
        const auto index = static_cast<std::size_t>(body);
        const double t = v[0];
        if (index == 0 && nextBody != 0 && !countKnown)
        {
            trajectory.bodyCount = nextBody;
            countKnown = true;
        }
        if (countKnown && nextBody == trajectory.bodyCount)
        {
            nextBody = 0;
        }
        if (index != nextBody)
        {
            fail(source, line,
                 "expected body " + std::to_string(nextBody) + " (each sample lists bodies 0, 1, ... in order), got " +
                     std::to_string(index));
        }
        if (index == 0)
        {
            if (!trajectory.times.empty() && t < trajectory.times.back())
            {
                fail(source, line, "time goes backwards");
            }
            trajectory.times.push_back(t);
        }
        else if (t != trajectory.times.back())
        {
            fail(source, line, "body " + std::to_string(index) + " has a different time from body 0 of its sample");
        }
        BodySample sample;
        sample.position = Vec3(v[2], v[3], v[4]);
        const Quat q(v[5], v[6], v[7], v[8]);
        // stableNorm: the squared norm of finite components as large as 1e160 overflows
        const double norm = q.coeffs().stableNorm();
        if (norm < 0.5)
        {
            fail(source, line, "orientation is not a unit quaternion");
        }
        // kept bit for bit when already unit, as the writer leaves it; normalised when rounded by hand
        sample.orientation = std::abs(norm - 1.0) > 1e-9 ? Quat(q.coeffs() / norm) : q;
        sample.linearVelocity = Vec3(v[9], v[10], v[11]);
        sample.angularVelocity = Vec3(v[12], v[13], v[14]);
        trajectory.samples.push_back(sample);
        ++nextBody;
    }
    std::string dropped;
    if (cutLine != 0)
    {
        dropped = "an unfinished row";
    }
    if (!countKnown)
    {
        trajectory.bodyCount = nextBody;
    }
    else if (nextBody != trajectory.bodyCount)
    {
        // the last sample lacks bodies: cut off between two of its rows
        trajectory.times.pop_back();
        trajectory.samples.resize(trajectory.times.size() * trajectory.bodyCount);
        cutLine = cutLine != 0 ? cutLine : line;
        dropped = "an incomplete last sample of " + std::to_string(nextBody) + " of " +
                  std::to_string(trajectory.bodyCount) + " bodies" + (dropped.empty() ? "" : " and " + dropped);
    }
    if (trajectory.times.empty())
    {
        fail(source, line, cutLine != 0 ? "cut off before its first whole sample" : "no samples after the header");
    }
    if (cutLine != 0)
    {
        std::ostringstream note;
        note.precision(9);
        note << "cut off at line " << cutLine << " (" << dropped << " left out); " << trajectory.times.size()
             << " whole samples up to t = " << trajectory.times.back() << " s";
        trajectory.cutOff = note.str();
    }
    return trajectory;
}

Trajectory readTrajectory(const std::filesystem::path& path)
{
    std::ifstream file(path, std::ios::binary);
    if (!file)
    {
        throw TrajectoryError(path.string() + ": cannot open for reading");
    }
    return parseTrajectory(file, path.string());
}

} // namespace impulse::io
