// SPDX-License-Identifier: MIT
#include "bench_command.hpp"

#include "option_checks.hpp"
#include "progress.hpp"
#include "scene_warnings.hpp"

#include <impulse/io/scene.hpp>

#include <nlohmann/json.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <stdexcept>
#include <thread>
#include <unistd.h>

#ifndef IMPULSE_SCENES_DIR
#define IMPULSE_SCENES_DIR "scenes"
#endif
#ifndef IMPULSE_COMPILER
#define IMPULSE_COMPILER ""
#endif
#ifndef IMPULSE_BUILD_TYPE
#define IMPULSE_BUILD_TYPE ""
#endif
#ifndef IMPULSE_SANITIZE
#define IMPULSE_SANITIZE ""
#endif

namespace impulse::app
{
namespace
{

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

double seconds(Clock::duration d)
{
    return std::chrono::duration<double>(d).count();
}

/// A scene on the command line, found.
struct SceneFile
{
    std::string name; ///< the file name without .json
    fs::path path;
};

/// Finds a scene given as a path (relative to the working directory), as a file or name in the
/// scenes directory (pyramid.json, pyramid), or as scenes/pyramid.json from anywhere. Returns the
/// file, or nothing with `tried` listing where it looked.
std::optional<fs::path> findScene(const std::string& argument, const fs::path& directory, std::vector<fs::path>& tried)
{
    const fs::path given(argument);
    std::vector<fs::path> candidates{given};
    if (given.is_relative())
    {
        candidates.push_back(directory / given);
        if (given.extension() != ".json")
        {
            candidates.push_back(directory / fs::path(argument + ".json"));
        }
        auto part = given.begin();
        if (part != given.end() && *part == "scenes" && std::next(part) != given.end())
        {
            fs::path rest;
            for (++part; part != given.end(); ++part)
            {
                rest /= *part;
            }
            candidates.push_back(directory / rest);
        }
    }
    for (const fs::path& candidate : candidates)
    {
        std::error_code error;
        if (fs::is_regular_file(candidate, error))
        {
            return candidate;
        }
    }
    tried = candidates;
    return std::nullopt;
}

/// The figures of one scene.
struct Result
{
    std::string name;
    std::string path;
    std::size_t bodies = 0;
    double dt = 0.0;
    long long steps = 0;
    long long warmUp = 0;
    int threads = 0; ///< the most worker threads a measured step used
    double contacts = 0.0;
    double pairs = 0.0;
    double collisionImpulses = 0.0;
    double contactRows = 0.0;
    double islands = 0.0;
    double median = 0.0;
    double p10 = 0.0;
    double p90 = 0.0;
    double mean = 0.0;
    double loadSeconds = 0.0;
    double totalSeconds = 0.0;
    std::uint64_t hash = 0;
    double kineticEnergy = 0.0;
    std::vector<std::string> warnings; ///< docs/warnings.md
};

std::string hex(std::uint64_t hash)
{
    char text[17];
    std::snprintf(text, sizeof text, "%016llx", static_cast<unsigned long long>(hash));
    return text;
}

/// Loads and steps one scene. Returns 0 with `result` filled, or the exit code after a message.
int measure(const SceneFile& file, const BenchOptions& options, Progress& progress, Result& result)
{
    progress.loading(file.name);
    const auto loadStart = Clock::now();
    io::Scene scene;
    try
    {
        scene = io::loadScene(file.path);
    }
    catch (const io::SceneError& error)
    {
        progress.clear();
        std::cerr << "impulse: " << error.what() << "\n";
        return 2;
    }
    result.loadSeconds = seconds(Clock::now() - loadStart);

    const double dt = scene.options.dt;
    long long warmUp = 0;
    long long steps = 0;
    if (options.steps)
    {
        steps = *options.steps;
        warmUp = options.warmUp.value_or(std::max(1LL, steps / 10));
    }
    else
    {
        constexpr double maxSteps = 1e12;
        if (!(scene.duration / dt <= maxSteps))
        {
            progress.clear();
            std::cerr << "impulse: " << file.path.string() << ": duration / dt is more than 1e12 steps; pass --steps\n";
            return 2;
        }
        const auto all = static_cast<long long>(std::llround(scene.duration / dt));
        warmUp = options.warmUp.value_or(std::max(1LL, all / 10));
        steps = all - warmUp;
        if (steps < 1)
        {
            progress.clear();
            std::cerr << "impulse: " << file.path.string() << ": --warm-up " << warmUp << " leaves none of the scene's "
                      << all << " steps to measure; pass --steps\n";
            return 2;
        }
    }
    scene.options.threads = options.threads;
    progress.clear();
    result.warnings = reportWarnings(scene, file.path.string());

    std::vector<double> times;
    times.reserve(static_cast<std::size_t>(std::min(steps, 10'000'000LL)));
    double contacts = 0.0;
    double pairs = 0.0;
    double collisionImpulses = 0.0;
    double contactRows = 0.0;
    double islands = 0.0;
    int threads = 0;
    const long long total = warmUp + steps;
    const auto runStart = Clock::now();
    for (long long k = 0; k < total; ++k)
    {
        const auto start = Clock::now();
        try
        {
            scene.world.step(scene.options);
        }
        catch (const std::invalid_argument& error)
        {
            // options the world refuses, such as tolerances too coarse for its smallest body
            progress.clear();
            std::cerr << "impulse: " << file.path.string() << ": " << error.what() << "\n";
            return 2;
        }
        const auto end = Clock::now();
        if (k >= warmUp)
        {
            times.push_back(std::chrono::duration<double, std::milli>(end - start).count());
            const StepStats& stats = scene.world.lastStepStats();
            contacts += stats.contactPairs;
            pairs += stats.candidatePairs;
            collisionImpulses += stats.collisionImpulses;
            contactRows += stats.contactRows;
            islands += stats.islands;
            threads = std::max(threads, stats.threads);
        }
        progress.update(file.name, k + 1, total, k + 1 <= warmUp ? " (warm-up)" : "", end - runStart, end);
    }
    result.totalSeconds = seconds(Clock::now() - runStart);
    progress.clear();

    const double kinetic = scene.world.kineticEnergy();
    if (!std::isfinite(kinetic) || !std::isfinite(scene.world.potentialEnergy()))
    {
        std::cerr << "impulse: " << file.path.string()
                  << ": the simulation diverged (non-finite energy at the end of the run)\n";
        return 1;
    }

    const auto n = static_cast<double>(steps);
    double sum = 0.0;
    for (const double t : times)
    {
        sum += t;
    }
    std::sort(times.begin(), times.end());
    // the percentile as the benchmark programs in bench/ take it
    const auto at = [&](double q)
    { return times[static_cast<std::size_t>(q * static_cast<double>(times.size() - 1))]; };

    result.name = file.name;
    result.path = file.path.string();
    result.bodies = scene.dynamicBodies.size();
    result.dt = dt;
    result.steps = steps;
    result.warmUp = warmUp;
    result.threads = threads;
    result.contacts = contacts / n;
    result.pairs = pairs / n;
    result.collisionImpulses = collisionImpulses / n;
    result.contactRows = contactRows / n;
    result.islands = islands / n;
    result.median = at(0.5);
    result.p10 = at(0.1);
    result.p90 = at(0.9);
    result.mean = sum / n;
    result.hash = scene.world.stateHash();
    result.kineticEnergy = kinetic;
    return 0;
}

nlohmann::ordered_json stringOrNull(const std::string& text)
{
    return text.empty() ? nlohmann::ordered_json(nullptr) : nlohmann::ordered_json(text);
}

/// The processor's model name from /proc/cpuinfo; empty where there is none.
std::string cpuModel()
{
    std::ifstream cpuinfo("/proc/cpuinfo");
    std::string line;
    while (std::getline(cpuinfo, line))
    {
        if (line.rfind("model name", 0) == 0)
        {
            const std::size_t colon = line.find(':');
            if (colon != std::string::npos)
            {
                const std::size_t start = line.find_first_not_of(" \t", colon + 1);
                return start == std::string::npos ? std::string() : line.substr(start);
            }
        }
    }
    return {};
}

nlohmann::ordered_json machineJson()
{
    std::string compiler = IMPULSE_COMPILER;
    if (compiler.empty())
    {
        compiler = __VERSION__;
    }
    return {{"hardware_threads", std::thread::hardware_concurrency()},
            {"cpu", stringOrNull(cpuModel())},
            {"compiler", compiler},
            {"build_type", stringOrNull(IMPULSE_BUILD_TYPE)},
            {"sanitizers", stringOrNull(IMPULSE_SANITIZE)}};
}

nlohmann::ordered_json resultJson(const Result& r)
{
    return {{"name", r.name},
            {"path", r.path},
            {"bodies", r.bodies},
            {"dt", r.dt},
            {"steps", r.steps},
            {"warm_up", r.warmUp},
            {"threads", r.threads},
            {"contacts_per_step", r.contacts},
            {"pairs_per_step", r.pairs},
            {"collision_impulses_per_step", r.collisionImpulses},
            {"contact_rows_per_step", r.contactRows},
            {"islands_per_step", r.islands},
            {"ms_per_step", {{"median", r.median}, {"p10", r.p10}, {"p90", r.p90}, {"mean", r.mean}}},
            {"load_seconds", r.loadSeconds},
            {"total_seconds", r.totalSeconds},
            {"state_hash", hex(r.hash)},
            {"kinetic_energy", r.kineticEnergy},
            {"warnings", r.warnings}};
}

} // namespace

const std::vector<std::string>& defaultBenchScenes()
{
    static const std::vector<std::string> scenes{"sphere_pile_1000", "sphere_pile_10000", "box_pile_1000",
                                                 "pyramid",          "box_stack_50",      "nonconvex_pile_200"};
    return scenes;
}

int runBench(const BenchOptions& options)
{
    const fs::path directory =
        options.scenesDirectory.empty() ? fs::path(IMPULSE_SCENES_DIR) : fs::path(options.scenesDirectory);
    if (!options.scenesDirectory.empty())
    {
        std::error_code error;
        if (!fs::is_directory(directory, error))
        {
            std::cerr << "impulse: --scenes " << options.scenesDirectory << ": no such directory\n";
            return 2;
        }
    }

    // every scene is found before any is run, so that a typo fails at once, not after an hour
    const std::vector<std::string>& arguments = options.scenes.empty() ? defaultBenchScenes() : options.scenes;
    std::vector<SceneFile> files;
    for (const std::string& argument : arguments)
    {
        std::vector<fs::path> tried;
        const std::optional<fs::path> path = findScene(argument, directory, tried);
        if (!path)
        {
            std::cerr << "impulse: " << argument << ": no such scene; looked for";
            for (std::size_t i = 0; i < tried.size(); ++i)
            {
                std::cerr << (i == 0 ? " " : ", ") << tried[i].string();
            }
            std::cerr << " (name a scene of " << directory.string() << ", give its path, or pass --scenes DIR)\n";
            return 2;
        }
        files.push_back({path->stem().string(), *path});
    }

    int nameWidth = 5;
    for (const SceneFile& file : files)
    {
        nameWidth = std::max(nameWidth, static_cast<int>(file.name.size()));
    }
    if (!options.json)
    {
        std::printf("%-*s %7s %13s %10s %21s %7s  %s\n", nameWidth, "scene", "bodies", "contacts/step", "ms/step",
                    "p10-p90", "threads", "state hash");
        std::fflush(stdout);
    }

    Progress progress(options.progress && stderrIsTerminal());
    nlohmann::ordered_json scenes = nlohmann::ordered_json::array();
    for (const SceneFile& file : files)
    {
        Result result;
        if (const int code = measure(file, options, progress, result); code != 0)
        {
            return code;
        }
        if (options.json)
        {
            scenes.push_back(resultJson(result));
        }
        else
        {
            std::printf("%-*s %7zu %13.1f %10.4f %10.4f-%-10.4f %7d  %s\n", nameWidth, result.name.c_str(),
                        result.bodies, result.contacts, result.median, result.p10, result.p90, result.threads,
                        hex(result.hash).c_str());
            std::fflush(stdout);
        }
    }

    if (options.json)
    {
        const nlohmann::ordered_json document{
            {"machine", machineJson()},
            {"options",
             {{"steps", options.steps ? nlohmann::ordered_json(*options.steps) : nlohmann::ordered_json(nullptr)},
              {"warm_up", options.warmUp ? nlohmann::ordered_json(*options.warmUp) : nlohmann::ordered_json(nullptr)},
              {"threads", options.threads},
              {"scenes_dir", directory.string()}}},
            {"scenes", scenes}};
        std::cout << document.dump(2) << "\n";
        std::cout.flush();
        if (!std::cout)
        {
            return 1;
        }
    }
    return 0;
}

BenchCommand::BenchCommand(CLI::App& app)
{
    m_command = app.add_subcommand(
        "bench", "Time the benchmark scenes: bodies, contacts and milliseconds per step, threads, state hash");
    m_command->add_option("scene", m_options.scenes,
                          "Scene names (sphere_pile_1000) or paths (scenes/pyramid.json); default: sphere_pile_1000, "
                          "sphere_pile_10000, box_pile_1000, pyramid, box_stack_50, nonconvex_pile_200");
    m_command
        ->add_option("--steps", m_options.steps,
                     "Measured steps per scene (default: the scene's duration less the warm-up)")
        ->check(wholeNumber(1, 1'000'000'000));
    m_command
        ->add_option("--warm-up", m_options.warmUp,
                     "Steps run before measuring (default: a tenth of --steps, or of the scene's duration; at "
                     "least 1)")
        ->check(wholeNumber(0, 1'000'000'000));
    m_command->add_option("--threads", m_options.threads, "Worker threads of a step; 0: one per hardware thread")
        ->check(wholeNumber(0, 65536))
        ->capture_default_str();
    m_command->add_flag("--json", m_options.json, "Print one JSON document instead of the table");
    m_command->add_flag("--no-progress", m_noProgress,
                        "No progress line (it is drawn on standard error only when that is a terminal)");
    m_command->add_option("--scenes", m_options.scenesDirectory,
                          "Directory where scene names are looked up (default: " IMPULSE_SCENES_DIR ")");
}

std::optional<int> BenchCommand::runChosen() const
{
    if (!m_command->parsed())
    {
        return std::nullopt;
    }
    BenchOptions options = m_options;
    options.progress = !m_noProgress;
    return runBench(options);
}

} // namespace impulse::app
