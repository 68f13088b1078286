// SPDX-License-Identifier: MIT
// gnuplot draws the figures: a Debian staple for decades, scriptable, headless with its cairo PNG
// terminal, and fed here through one generated script with the data inline.
#include "plot_command.hpp"

#include "see_inputs.hpp"

#include <impulse/viz/series.hpp>
#include <impulse/viz/tessellate.hpp>

#include <algorithm>
#include <array>
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

// How many bodies a plot names in a key, and how many it draws one by one; above that it draws a
// summary. And how many points it hands gnuplot in all, so that no trajectory makes it crawl.
constexpr std::size_t kNamedBodies = 12;
constexpr std::size_t kDrawnBodies = 200;
constexpr std::size_t kSummaryPaths = 50;
constexpr std::size_t kMaxPoints = 400000;

/// What the plot draws of a trajectory with many bodies; the summary line says it too.
struct PlotPlan
{
    bool summarise = false;         ///< lowest, median and highest per sample instead of each body
    std::vector<std::size_t> paths; ///< bodies whose 3-D path is drawn
    std::vector<std::size_t> kept;  ///< samples drawn
    std::size_t sampleStride = 1;
    std::size_t pathStride = 1; ///< every pathStride-th body when summarised

    std::string describe(std::size_t bodies) const
    {
        std::string text;
        if (summarise)
        {
            text = "; summarised: lowest, median and highest height and speed, the paths of " +
                   std::to_string(paths.size()) + " bodies (every " + std::to_string(pathStride) +
                   (pathStride == 2   ? "nd"
                    : pathStride == 3 ? "rd"
                                      : "th") +
                   ") and of their mean";
        }
        else if (bodies > kNamedBodies)
        {
            text = "; one curve per body, too many to name";
        }
        if (sampleStride > 1)
        {
            text += "; every " + std::to_string(sampleStride) +
                    (sampleStride == 2   ? "nd"
                     : sampleStride == 3 ? "rd"
                                         : "th") +
                    " sample";
        }
        return text;
    }
};

PlotPlan planPlot(const io::Trajectory& trajectory)
{
    PlotPlan plan;
    const std::size_t n = trajectory.bodyCount;
    plan.summarise = n > kDrawnBodies;
    plan.pathStride = plan.summarise ? (n + kSummaryPaths - 1) / kSummaryPaths : 1;
    for (std::size_t k = 0; k < n; k += plan.pathStride)
    {
        plan.paths.push_back(k);
    }
    const std::size_t curves = plan.summarise ? plan.paths.size() + 7 : n;
    const std::size_t samples = trajectory.sampleCount();
    plan.sampleStride = std::max<std::size_t>(1, (curves * samples + kMaxPoints - 1) / kMaxPoints);
    for (std::size_t i = 0; i < samples; i += plan.sampleStride)
    {
        plan.kept.push_back(i);
    }
    if (plan.kept.back() != samples - 1)
    {
        plan.kept.push_back(samples - 1); // the end of the run is always shown
    }
    return plan;
}

/// The lowest, median and highest of `values` (reordered).
std::array<Real, 3> spread(std::vector<Real>& values)
{
    const auto middle = values.begin() + static_cast<std::ptrdiff_t>(values.size() / 2);
    std::nth_element(values.begin(), middle, values.end());
    const auto [low, high] = std::minmax_element(values.begin(), values.end());
    return {*low, *middle, *high};
}

std::string gnuplotScript(const LoadedRun& run, const viz::Series& series, const PlotPlan& plan,
                          const std::string& outPath, int width, int height)
{
    const io::Trajectory& trajectory = run.trajectory;
    const std::size_t n = trajectory.bodyCount;
    std::ostringstream s;
    s.precision(9);
    // per drawn body: t x y z height speed
    for (const std::size_t k : plan.paths)
    {
        s << "$body" << k << " << EOD\n";
        for (const std::size_t i : plan.kept)
        {
            const Vec3& x = trajectory.at(i, k).position;
            s << trajectory.times[i] << ' ' << x.x() << ' ' << x.y() << ' ' << x.z() << ' ' << series.height[k][i]
              << ' ' << series.speed[k][i] << '\n';
        }
        s << "EOD\n";
    }
    if (plan.summarise)
    {
        // t, lowest/median/highest height, lowest/median/highest speed, mean x y z
        s << "$summary << EOD\n";
        std::vector<Real> values(n);
        for (const std::size_t i : plan.kept)
        {
            s << trajectory.times[i];
            for (const auto* quantity : {&series.height, &series.speed})
            {
                for (std::size_t k = 0; k < n; ++k)
                {
                    values[k] = (*quantity)[k][i];
                }
                for (const Real v : spread(values))
                {
                    s << ' ' << v;
                }
            }
            Vec3 mean = Vec3::Zero();
            for (std::size_t k = 0; k < n; ++k)
            {
                mean += trajectory.at(i, k).position;
            }
            mean /= static_cast<Real>(n);
            s << ' ' << mean.x() << ' ' << mean.y() << ' ' << mean.z() << '\n';
        }
        s << "EOD\n";
    }
    s << "$energy << EOD\n";
    for (const std::size_t i : plan.kept)
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

    const bool named = n <= kNamedBodies;
    auto curves = [&](const std::string& columns, const std::vector<std::size_t>& bodies)
    {
        std::string list;
        for (const std::size_t k : bodies)
        {
            list += (list.empty() ? "" : ", ") + std::string("$body") + std::to_string(k) + " using " + columns +
                    " with lines lw " + (plan.summarise ? "1" : "1.5") + " lc rgb " +
                    quoted(plan.summarise ? "#b0b0b0" : viz::hexColour(viz::bodyColour(k))) +
                    (named ? " title " + quoted(run.view.names[k]) : " notitle");
        }
        return list;
    };
    // the three curves of a summary: lowest, median and highest
    auto spreadCurves = [&](int firstColumn)
    {
        std::ostringstream list;
        const char* labels[] = {"lowest", "median", "highest"};
        const char* colours[] = {"#1f77b4", "#333333", "#d62728"};
        for (int c = 0; c < 3; ++c)
        {
            list << (c ? ", " : "") << "$summary using 1:" << firstColumn + c << " with lines lw 1.5 lc rgb "
                 << quoted(colours[c]) << " title " << quoted(labels[c]);
        }
        return list.str();
    };
    auto all = [&](auto value)
    {
        std::vector<Real> values;
        for (const std::size_t k : plan.paths)
        {
            for (const std::size_t i : plan.kept)
            {
                values.push_back(value(i, k));
            }
        }
        return values;
    };
    // what a panel of many bodies shows, in its title
    const std::string count = named            ? ""
                              : plan.summarise ? " (" + std::to_string(n) + " bodies)"
                                               : " (" + std::to_string(n) + " bodies, one curve each)";

    s << "set title " << quoted("height against time" + count) << "\nset xlabel 't (s)'\nset ylabel 'height (m)'\n";
    if (plan.summarise)
    {
        s << "set key\nset yrange [*:*]\nplot " << spreadCurves(2) << "\n";
    }
    else
    {
        s << (named ? "set key\n" : "unset key\n") << "set yrange "
          << rangeOf(all([&](std::size_t i, std::size_t k) { return series.height[k][i]; })) << "\n"
          << "plot " << curves("1:5", plan.paths) << "\n";
    }

    // one scale on the three axes, so that a path's shape is its true shape: a cube around the data
    const auto positions = [&](int axis)
    { return all([&](std::size_t i, std::size_t k) { return trajectory.at(i, k).position[axis]; }); };
    Vec3 low;
    Vec3 high;
    for (int axis = 0; axis < 3; ++axis)
    {
        const std::vector<Real> values = positions(axis);
        const auto [lo, hi] = std::minmax_element(values.begin(), values.end());
        low[axis] = *lo;
        high[axis] = *hi;
    }
    const Vec3 centre = 0.5 * (low + high);
    const Real half = std::max(0.55 * (high - low).maxCoeff(), 0.05 * std::max(1.0, centre.cwiseAbs().maxCoeff()));
    std::string pathTitle = "path of each centre";
    if (plan.summarise)
    {
        pathTitle =
            "paths of " + std::to_string(plan.paths.size()) + " of " + std::to_string(n) + " bodies and their mean";
    }
    s << "set title " << quoted(pathTitle)
      << "\nset xlabel 'x (m)'\nset ylabel 'y (m)'\nset zlabel 'z (m)' rotate "
         "parallel\n"
      << "set xyplane relative 0\nset view 60,35\nset view equal xyz\nset xtics offset 0,-0.5\n";
    for (int axis = 0; axis < 3; ++axis)
    {
        s << "set "
          << "xyz"[axis] << "range [" << centre[axis] - half << ':' << centre[axis] + half << "]\n";
    }
    s << (named ? "set key\n" : "unset key\n") << "splot " << curves("2:3:4", plan.paths);
    if (plan.summarise)
    {
        s << ", $summary using 8:9:10 with lines lw 2 lc rgb '#d62728' title 'mean'";
    }
    s << "\nunset zlabel\nset view noequal\nset xrange [*:*]\nset yrange [*:*]\nset xtics offset 0,0\n";

    s << "set title " << quoted("speed against time" + count) << "\nset xlabel 't (s)'\nset ylabel 'speed (m/s)'\n";
    if (plan.summarise)
    {
        s << "set key\nplot " << spreadCurves(5) << "\n";
    }
    else
    {
        s << (named ? "set key\n" : "unset key\n") << "set yrange "
          << rangeOf(all([&](std::size_t i, std::size_t k) { return series.speed[k][i]; })) << "\n"
          << "plot " << curves("1:6", plan.paths) << "\n";
    }
    std::vector<Real> energies;
    for (const std::size_t i : plan.kept)
    {
        energies.push_back(series.energy[i]);
    }
    s << "set yrange " << rangeOf(energies) << "\n";

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
    const PlotPlan plan = planPlot(run.trajectory);

    const std::filesystem::path script =
        std::filesystem::temp_directory_path() / ("impulse-plot-" + std::to_string(::getpid()) + ".gp");
    {
        std::ofstream file(script, std::ios::binary);
        file << gnuplotScript(run, series, plan, outPath, width, height);
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
    std::printf("plot        %s (%dx%d, %zu bodies, %zu samples%s)\n", outPath.c_str(), width, height,
                run.trajectory.bodyCount, run.trajectory.sampleCount(),
                plan.describe(run.trajectory.bodyCount).c_str());
    return 0;
}

} // namespace impulse::app
