// SPDX-License-Identifier: MIT
#include "replay_command.hpp"

#include "option_checks.hpp"
#include "progress.hpp"

#include <impulse/io/replay.hpp>
#include <impulse/io/scene.hpp>

#include <nlohmann/json.hpp>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <sstream>
#include <stdexcept>
#include <thread>
#include <zlib.h>

namespace impulse::app
{
namespace
{

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

/// A replay that cannot be started: the message names the file and what is wrong.
struct ReplayRefusal : std::runtime_error
{
    using std::runtime_error::runtime_error;
};

bool isMeasuredFile(const fs::path& path)
{
    const std::string name = path.filename().string();
    const auto endsWith = [&](const std::string& end)
    { return name.size() > end.size() && name.compare(name.size() - end.size(), end.size(), end) == 0; };
    return endsWith(".csv") || endsWith(".csv.gz");
}

/// The files named, directories expanded to their measured files in name order.
std::vector<fs::path> measuredFiles(const std::vector<std::string>& arguments)
{
    std::vector<fs::path> files;
    for (const std::string& argument : arguments)
    {
        const fs::path path(argument);
        std::error_code error;
        if (fs::is_directory(path, error))
        {
            std::vector<fs::path> found;
            for (const fs::directory_entry& entry : fs::directory_iterator(path, error))
            {
                if (entry.is_regular_file() && isMeasuredFile(entry.path()))
                {
                    found.push_back(entry.path());
                }
            }
            if (found.empty())
            {
                throw ReplayRefusal(argument + ": no .csv or .csv.gz file in this directory");
            }
            std::sort(found.begin(), found.end());
            files.insert(files.end(), found.begin(), found.end());
        }
        else
        {
            files.push_back(path);
        }
    }
    return files;
}

/// A measured trajectory from its CSV or its gzip.
io::Trajectory readMeasured(const fs::path& path)
{
    const std::string name = path.string();
    if (path.extension() != ".gz")
    {
        return io::readTrajectory(path);
    }
    gzFile file = gzopen(name.c_str(), "rb");
    if (file == nullptr)
    {
        throw io::TrajectoryError(name + ": cannot open");
    }
    std::string text;
    std::vector<char> buffer(1 << 16);
    int read = 0;
    while ((read = gzread(file, buffer.data(), static_cast<unsigned>(buffer.size()))) > 0)
    {
        text.append(buffer.data(), static_cast<std::size_t>(read));
    }
    // a file cut short reads to its end and then reports it (Z_BUF_ERROR, "unexpected end of file")
    int status = Z_OK;
    const char* reason = gzerror(file, &status);
    std::string why = reason != nullptr ? reason : "";
    if (why.rfind(name + ": ", 0) == 0)
    {
        why.erase(0, name.size() + 2); // zlib names the file too
    }
    gzclose(file);
    if (read < 0 || status != Z_OK)
    {
        throw io::TrajectoryError(name + ": not a whole gzip file (" + why + ")");
    }
    std::istringstream in(text);
    return io::parseTrajectory(in, name);
}

std::string readText(const fs::path& path)
{
    std::ifstream in(path, std::ios::binary);
    if (!in)
    {
        throw ReplayRefusal(path.string() + ": cannot open");
    }
    std::ostringstream text;
    text << in.rdbuf();
    return text.str();
}

/// The template's replayed body: its only dynamic body.
BodyId replayedBody(const io::Scene& scene, const std::string& path)
{
    if (scene.dynamicBodies.size() != 1)
    {
        throw ReplayRefusal(path + ": a replay template has exactly one dynamic body, the one measured; this one has " +
                            std::to_string(scene.dynamicBodies.size()));
    }
    return scene.dynamicBodies[0];
}

std::string fixed(double value, int decimals)
{
    char buffer[64];
    std::snprintf(buffer, sizeof buffer, "%.*f", decimals, value);
    return buffer;
}

nlohmann::json summaryJson(const io::ErrorSummary& summary)
{
    return {
        {"mean", summary.mean}, {"std", summary.deviation}, {"median", summary.median}, {"p90", summary.percentile90}};
}

std::string summaryLine(const io::ErrorSummary& summary, int decimals)
{
    return "mean " + fixed(summary.mean, decimals) + " (std " + fixed(summary.deviation, decimals) + "), median " +
           fixed(summary.median, decimals) + ", 90th percentile " + fixed(summary.percentile90, decimals);
}

} // namespace

int runReplay(const ReplayOptions& options)
{
    std::vector<fs::path> files;
    std::string templateText;
    io::Scene scene;
    BodyId body;
    Real size = 0.0;
    try
    {
        files = measuredFiles(options.measured);
        templateText = readText(options.scenePath);
        scene = io::parseScene(templateText, options.scenePath, fs::path(options.scenePath).parent_path());
        body = replayedBody(scene, options.scenePath);
        size = options.size ? *options.size : io::bodySize(scene.world.shape(body));
    }
    catch (const std::exception& error)
    {
        std::cerr << "impulse: " << error.what() << "\n";
        return 2;
    }
    const fs::path directory = fs::path(options.scenePath).parent_path();

    // every trajectory is read before any is replayed, so that a bad file stops the batch at once
    std::vector<io::Trajectory> measured;
    measured.reserve(files.size());
    try
    {
        for (const fs::path& file : files)
        {
            measured.push_back(readMeasured(file));
            if (measured.back().sampleCount() < 2)
            {
                throw ReplayRefusal(file.string() + ": a measurement needs at least two samples");
            }
        }
    }
    catch (const std::exception& error)
    {
        std::cerr << "impulse: " << error.what() << "\n";
        return 2;
    }

    // each worker replays whole trajectories in its own copy of the template: the results do not
    // depend on how many run at once
    std::vector<io::ReplayError> results(files.size());
    std::vector<std::string> failures(files.size());
    std::atomic<std::size_t> next{0};
    std::atomic<std::size_t> done{0};
    const auto work = [&]
    {
        for (std::size_t i = next++; i < files.size(); i = next++)
        {
            try
            {
                io::Scene copy = io::parseScene(templateText, options.scenePath, directory);
                StepOptions stepOptions = copy.options;
                stepOptions.threads = 1;
                results[i] = io::replay(copy.world, replayedBody(copy, options.scenePath), stepOptions, measured[i],
                                        size, files[i].string());
            }
            catch (const std::exception& error)
            {
                failures[i] = error.what();
            }
            ++done;
        }
    };
    const unsigned hardware = std::max(1u, std::thread::hardware_concurrency());
    const std::size_t jobs =
        std::min<std::size_t>(options.jobs > 0 ? static_cast<std::size_t>(options.jobs) : hardware, files.size());
    std::vector<std::thread> workers;
    for (std::size_t j = 0; j < jobs; ++j)
    {
        workers.emplace_back(work);
    }
    Progress progress(options.progress && stderrIsTerminal(), "trajectories");
    const Clock::time_point start = Clock::now();
    while (done.load() < files.size())
    {
        const Clock::time_point now = Clock::now();
        progress.update("replay", static_cast<long long>(done.load()), static_cast<long long>(files.size()), "",
                        now - start, now);
        std::this_thread::sleep_for(std::chrono::milliseconds(50));
    }
    for (std::thread& worker : workers)
    {
        worker.join();
    }
    progress.clear();
    for (std::size_t i = 0; i < files.size(); ++i)
    {
        if (!failures[i].empty())
        {
            std::cerr << "impulse: " << failures[i] << "\n";
            return 2;
        }
    }

    std::vector<Real> positions;
    std::vector<Real> rotations;
    for (const io::ReplayError& result : results)
    {
        positions.push_back(result.positionError);
        rotations.push_back(result.rotationError);
    }
    const io::ErrorSummary position = io::summarise(positions);
    const io::ErrorSummary rotation = io::summarise(rotations);
    const std::string bodyName = scene.bodyNames[body.index].empty() ? "body 0" : scene.bodyNames[body.index];

    nlohmann::json json;
    json["scene"] = options.scenePath;
    json["body"] = bodyName;
    json["size"] = size;
    json["dt"] = scene.options.dt;
    json["trajectories"] = nlohmann::json::array();
    for (const io::ReplayError& result : results)
    {
        json["trajectories"].push_back({{"file", result.source},
                                        {"samples", result.samples},
                                        {"position", result.positionError},
                                        {"rotation", result.rotationError},
                                        {"final_position", result.finalPosition},
                                        {"final_rotation", result.finalRotation}});
    }
    json["position"] = summaryJson(position);
    json["rotation"] = summaryJson(rotation);
    if (options.jsonPath == "-")
    {
        std::cout << json.dump(2) << "\n";
        return 0;
    }
    if (!options.jsonPath.empty())
    {
        std::ofstream out(options.jsonPath);
        out << json.dump(2) << "\n";
        if (!out)
        {
            std::cerr << "impulse: " << options.jsonPath << ": cannot write\n";
            return 1;
        }
    }

    std::cout << "replay of " << files.size() << " measured trajectories with " << options.scenePath << " (" << bodyName
              << ", size " << size << " m, dt " << scene.options.dt << " s)\n";
    std::cout << "errors are means over each trajectory's samples after the first: position in % of the size, "
                 "rotation in degrees\n\n";
    std::size_t width = 8;
    for (const fs::path& file : files)
    {
        width = std::max(width, file.string().size());
    }
    char line[512];
    std::snprintf(line, sizeof line, "%-*s  %7s  %10s  %10s  %14s  %14s\n", static_cast<int>(width), "measured",
                  "samples", "position %", "rotation", "final position", "final rotation");
    std::cout << line;
    for (const io::ReplayError& result : results)
    {
        std::snprintf(line, sizeof line, "%-*s  %7zu  %10.2f  %10.2f  %14.2f  %14.2f\n", static_cast<int>(width),
                      result.source.c_str(), result.samples, result.positionError, result.rotationError,
                      result.finalPosition, result.finalRotation);
        std::cout << line;
    }
    std::cout << "\nposition error, % of size: " << summaryLine(position, 2) << "\n";
    std::cout << "rotation error, degrees:   " << summaryLine(rotation, 2) << "\n";
    return 0;
}

ReplayCommand::ReplayCommand(CLI::App& app)
{
    m_command =
        app.add_subcommand("replay", "Simulate measured trajectories again from their first sample and report how far "
                                     "the simulation ends up from them (position in % of the body's size, rotation in "
                                     "degrees)");
    m_command
        ->add_option("measured", m_options.measured,
                     "Measured trajectory files (.csv or .csv.gz, the trajectory format; body 0 is compared), or "
                     "directories of them")
        ->required();
    m_command
        ->add_option("--scene", m_options.scenePath,
                     "Template scene: its one dynamic body is started from each measurement's first sample; its "
                     "materials and step options are used")
        ->required();
    m_command->add_option("--json", m_options.jsonPath,
                          "Also write every figure as JSON to this file; \"-\": print the JSON instead of the table");
    m_command
        ->add_option("--size", m_options.size,
                     "Length the position error is measured in, m (default: the body's: a box's longest edge, a "
                     "sphere's diameter)")
        ->check(positiveNumber());
    m_command
        ->add_option("--jobs", m_options.jobs,
                     "Trajectories replayed at once (0: one per hardware thread); the figures are the same at any "
                     "count")
        ->check(wholeNumber(0, 65536))
        ->capture_default_str();
    m_command->add_flag("--no-progress", m_noProgress,
                        "No progress line (it is drawn on standard error only when that is a terminal)");
}

std::optional<int> ReplayCommand::runChosen() const
{
    if (!m_command->parsed())
    {
        return std::nullopt;
    }
    ReplayOptions options = m_options;
    options.progress = !m_noProgress;
    return runReplay(options);
}

} // namespace impulse::app
