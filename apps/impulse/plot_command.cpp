// SPDX-License-Identifier: MIT
// gnuplot draws the figures: a Debian staple for decades, scriptable, headless with its cairo PNG
// terminal, and fed here through one generated script with the data inline.
#include "plot_command.hpp"

#include "see_inputs.hpp"

#include <impulse/viz/series.hpp>
#include <impulse/viz/tessellate.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <sstream>
#include <unistd.h>

namespace impulse::app
{
namespace
{

/// A gnuplot single-quoted string: a quote inside is written twice.
std::string quoted(const std::string& text)
{
    std::string out = "'";
    for (const char c : text)
    {
        out += c;
        if (c == '\'')
        {
            out += '\'';
        }
    }
    return out + "'";
}

/// A gnuplot range: automatic, unless every value is the same (a ball rolling at constant height),
/// where gnuplot would warn and guess; then a small band around the value.
std::string rangeOf(const std::vector<Real>& values)
{
    const auto [low, high] = std::minmax_element(values.begin(), values.end());
    if (low == values.end() || *high - *low > 1e-9 * std::max({1.0, std::abs(*low), std::abs(*high)}))
    {
        return "[*:*]";
    }
    const Real pad = std::max(0.05 * std::abs(*low), 0.05);
    std::ostringstream range;
    range << '[' << *low - pad << ':' << *high + pad << ']';
    return range.str();
}

std::string gnuplotScript(const LoadedRun& run, const viz::Series& series, const std::string& outPath, int width,
                          int height)
{
    const io::Trajectory& trajectory = run.trajectory;
    std::ostringstream s;
    s.precision(9);
    for (std::size_t k = 0; k < trajectory.bodyCount; ++k)
    {
        s << "$body" << k << " << EOD\n";
        for (std::size_t i = 0; i < trajectory.sampleCount(); ++i)
        {
            const Vec3& x = trajectory.at(i, k).position;
            s << trajectory.times[i] << ' ' << x.x() << ' ' << x.y() << ' ' << x.z() << ' ' << series.height[k][i]
              << ' ' << series.speed[k][i] << '\n';
        }
        s << "EOD\n";
    }
    s << "$energy << EOD\n";
    for (std::size_t i = 0; i < trajectory.sampleCount(); ++i)
    {
        s << trajectory.times[i] << ' ' << series.energy[i] << '\n';
    }
    s << "EOD\n";

    const std::string font = width >= 900 ? "sans,11" : "sans,8";
    s << "set terminal pngcairo size " << width << ',' << height << " noenhanced font " << quoted(font) << "\n"
      << "set output " << quoted(outPath) << "\n"
      << "set encoding utf8\n"
      << "set grid\nset key top right\nset border lw 1\n"
      << "set multiplot layout 2,2 title " << quoted(run.title) << "\n";

    auto curves = [&](const std::string& columns)
    {
        std::string list;
        for (std::size_t k = 0; k < trajectory.bodyCount; ++k)
        {
            list += (k ? ", " : "") + std::string("$body") + std::to_string(k) + " using " + columns +
                    " with lines lw 1.5 lc rgb " + quoted(viz::hexColour(viz::bodyColour(k))) + " title " +
                    quoted(run.view.names[k]);
        }
        return list;
    };
    const bool many = trajectory.bodyCount > 8; // a key of dozens of bodies hides the plot
    s << (many ? "unset key\n" : "set key\n");
    auto all = [&](auto value)
    {
        std::vector<Real> values;
        for (std::size_t k = 0; k < trajectory.bodyCount; ++k)
        {
            for (std::size_t i = 0; i < trajectory.sampleCount(); ++i)
            {
                values.push_back(value(i, k));
            }
        }
        return values;
    };
    s << "set title 'height against time'\nset xlabel 't (s)'\nset ylabel 'height (m)'\n"
      << "set yrange " << rangeOf(all([&](std::size_t i, std::size_t k) { return series.height[k][i]; })) << "\n"
      << "plot " << curves("1:5") << "\n";

    // each axis scales to its own data: a path that bends by centimetres over metres (a spinning
    // ball under friction) shows its bend; the tick labels carry the scales
    s << "set title 'path of each centre'\nset xlabel 'x (m)'\nset ylabel 'y (m)'\nset zlabel 'z (m)' rotate "
         "parallel\n"
      << "set xyplane relative 0\nset view 60,35\nset xtics offset 0,-0.5\n"
      << "set xrange " << rangeOf(all([&](std::size_t i, std::size_t k) { return trajectory.at(i, k).position.x(); }))
      << "\nset yrange " << rangeOf(all([&](std::size_t i, std::size_t k) { return trajectory.at(i, k).position.y(); }))
      << "\n"
      << "set zrange " << rangeOf(all([&](std::size_t i, std::size_t k) { return trajectory.at(i, k).position.z(); }))
      << "\n"
      << "splot " << curves("2:3:4") << "\n"
      << "unset zlabel\nset xrange [*:*]\nset xtics offset 0,0\n";

    s << "set title 'speed against time'\nset xlabel 't (s)'\nset ylabel 'speed (m/s)'\n"
      << "set yrange " << rangeOf(all([&](std::size_t i, std::size_t k) { return series.speed[k][i]; })) << "\n"
      << "plot " << curves("1:6") << "\n";
    s << "set yrange " << rangeOf(series.energy) << "\n";

    s << "set title "
      << quoted(run.view.hasMassProperties ? "total energy against time"
                                           : "energy per unit mass against time (no --scene)")
      << "\nset xlabel 't (s)'\nset ylabel " << quoted(series.energyLabel) << "\n"
      << "set key\nplot $energy using 1:2 with lines lw 1.5 lc rgb '#333333' title "
      << quoted(run.view.hasMassProperties ? "kinetic + potential" : "sum over bodies") << "\n";
    s << "unset multiplot\n";
    return s.str();
}

} // namespace

int plotTrajectory(const PlotOptions& options)
{
    LoadedRun run;
    int width = 0;
    int height = 0;
    try
    {
        std::tie(width, height) = parseSize(options.size, "--size");
        run = loadRun(options.trajectoryPath, options.scenePath);
    }
    catch (const InputError& error)
    {
        std::cerr << "impulse: " << error.what() << "\n";
        return 2;
    }
    const std::optional<std::string> gnuplot = findExecutable("gnuplot");
    if (!gnuplot)
    {
        std::cerr << "impulse: plot needs gnuplot on PATH (Debian: apt-get install gnuplot-nox)\n";
        return 1;
    }
    const std::string outPath =
        options.outPath.empty() ? withExtension(options.trajectoryPath, ".png") : options.outPath;
    const viz::Series series = viz::computeSeries(run.trajectory, run.view);

    const std::filesystem::path script =
        std::filesystem::temp_directory_path() / ("impulse-plot-" + std::to_string(::getpid()) + ".gp");
    {
        std::ofstream file(script, std::ios::binary);
        file << gnuplotScript(run, series, outPath, width, height);
        if (!file)
        {
            std::cerr << "impulse: " << script.string() << ": cannot write the gnuplot script\n";
            return 1;
        }
    }
    std::error_code ignored;
    std::filesystem::remove(outPath, ignored); // so that a failed run cannot leave an old picture behind
    const int status = runProgram(*gnuplot, {script.string()});
    std::filesystem::remove(script, ignored);
    if (status != 0 || !std::filesystem::exists(outPath) || std::filesystem::file_size(outPath) == 0)
    {
        std::cerr << "impulse: gnuplot failed to write " << outPath << " (exit status " << status << ")\n";
        return 1;
    }
    std::printf("plot        %s (%dx%d, %zu bodies, %zu samples)\n", outPath.c_str(), width, height,
                run.trajectory.bodyCount, run.trajectory.sampleCount());
    return 0;
}

} // namespace impulse::app
