// SPDX-License-Identifier: MIT
#include "replay_command.hpp"

#include "option_checks.hpp"
#include "progress.hpp"

#include <impulse/io/replay.hpp>
#include <impulse/io/scene.hpp>
#include <impulse/io/trajectory.hpp>

#include <nlohmann/json.hpp>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <nlopt.h>
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

/// The measurements and the template of a replay or a fit, all read and checked.
struct Batch
{
    std::vector<fs::path> files;
    std::vector<io::Trajectory> measured;
    std::string scenePath;
    std::string templateText;
    fs::path directory;
    io::Scene scene; ///< the template, for its names and options
    BodyId body;     ///< the replayed body
    Real size = 0.0; ///< m
};

/// Reads the template and every measurement; throws with the file named on the first that cannot
/// be used, so that a bad file stops the batch before anything is simulated.
Batch loadBatch(const std::vector<std::string>& measuredArguments, const std::string& scenePath,
                std::optional<double> size)
{
    Batch batch;
    batch.files = measuredFiles(measuredArguments);
    batch.scenePath = scenePath;
    batch.templateText = readText(scenePath);
    batch.directory = fs::path(scenePath).parent_path();
    batch.scene = io::parseScene(batch.templateText, scenePath, batch.directory);
    batch.body = replayedBody(batch.scene, scenePath);
    batch.size = size ? *size : io::bodySize(batch.scene.world.shape(batch.body));
    batch.measured.reserve(batch.files.size());
    for (const fs::path& file : batch.files)
    {
        batch.measured.push_back(readMeasured(file));
        if (batch.measured.back().sampleCount() < 2)
        {
            throw ReplayRefusal(file.string() + ": a measurement needs at least two samples");
        }
    }
    return batch;
}

/// Restitution and friction between the replayed body and every static body, in place of the
/// template's materials; unset: the template's own.
using Contact = std::optional<PairCoefficients>;

/// The template's coefficients between the replayed body and its first static body.
PairCoefficients templateContact(const Batch& batch)
{
    const World& world = batch.scene.world;
    for (std::uint32_t i = 0; i < world.bodyCount(); ++i)
    {
        if (!world.isDynamic(BodyId{i}))
        {
            return world.pairCoefficients(world.material(batch.body), world.material(BodyId{i}));
        }
    }
    throw ReplayRefusal(batch.scenePath + ": a template needs a static body for the measured one to land on");
}

/// Replays every measurement, `jobs` at a time, each in its own copy of the template: the results
/// do not depend on how many run at once. With `simulated`, each replay's simulation sampled at its
/// measured times is kept there, in file order. Throws the first failure, with its file named.
std::vector<io::ReplayError> replayBatch(const Batch& batch, const Contact& contact, int jobsAsked, bool progressShown,
                                         std::vector<io::Trajectory>* simulated = nullptr)
{
    const std::size_t count = batch.files.size();
    std::vector<io::ReplayError> results(count);
    if (simulated != nullptr)
    {
        simulated->assign(count, io::Trajectory{});
    }
    std::vector<std::string> failures(count);
    std::atomic<std::size_t> next{0};
    std::atomic<std::size_t> done{0};
    const auto work = [&]
    {
        for (std::size_t i = next++; i < count; i = next++)
        {
            try
            {
                io::Scene copy = io::parseScene(batch.templateText, batch.scenePath, batch.directory);
                const BodyId body = replayedBody(copy, batch.scenePath);
                if (contact)
                {
                    for (std::uint32_t k = 0; k < copy.world.bodyCount(); ++k)
                    {
                        if (!copy.world.isDynamic(BodyId{k}))
                        {
                            copy.world.setPairCoefficients(copy.world.material(body), copy.world.material(BodyId{k}),
                                                           *contact);
                        }
                    }
                }
                StepOptions stepOptions = copy.options;
                stepOptions.threads = 1;
                results[i] = io::replay(copy.world, body, stepOptions, batch.measured[i], batch.size,
                                        batch.files[i].string(), simulated != nullptr ? &(*simulated)[i] : nullptr);
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
        std::min<std::size_t>(jobsAsked > 0 ? static_cast<std::size_t>(jobsAsked) : hardware, count);
    std::vector<std::thread> workers;
    for (std::size_t j = 0; j < jobs; ++j)
    {
        workers.emplace_back(work);
    }
    if (progressShown)
    {
        Progress progress(true, "trajectories");
        const Clock::time_point start = Clock::now();
        while (done.load() < count)
        {
            const Clock::time_point now = Clock::now();
            progress.update("replay", static_cast<long long>(done.load()), static_cast<long long>(count), "",
                            now - start, now);
            std::this_thread::sleep_for(std::chrono::milliseconds(20));
        }
        progress.clear();
    }
    for (std::thread& worker : workers)
    {
        worker.join();
    }
    for (const std::string& failure : failures)
    {
        if (!failure.empty())
        {
            throw ReplayRefusal(failure);
        }
    }
    return results;
}

/// Writes `json` where --json asks: to standard output instead of the table for "-" (returns 0),
/// or to a file beside the table (returns 1 when it cannot be written, else nothing).
std::optional<int> writeJson(const nlohmann::json& json, const std::string& path)
{
    if (path == "-")
    {
        std::cout << json.dump(2) << "\n";
        return 0;
    }
    if (!path.empty())
    {
        std::ofstream out(path);
        out << json.dump(2) << "\n";
        if (!out)
        {
            std::cerr << "impulse: " << path << ": cannot write\n";
            return 1;
        }
    }
    return std::nullopt;
}

/// The operands and options replay and fit share, bound to `options`.
void addMeasurementOptions(CLI::App& command, ReplayOptions& options, bool& noProgress)
{
    command
        .add_option("measured", options.measured,
                    "Measured trajectory files (.csv or .csv.gz, the trajectory format; body 0 is compared), or "
                    "directories of them")
        ->required();
    command
        .add_option("--scene", options.scenePath,
                    "Template scene: its one dynamic body is started from each measurement's first sample; its "
                    "materials, its coefficients with the static bodies and its step options are used")
        ->required();
    command.add_option("--json", options.jsonPath,
                       "Also write every figure as JSON to this file; \"-\": print the JSON instead of the table");
    command
        .add_option("--size", options.size,
                    "Length the position error is measured in, m (default: the body's: a box's longest edge, a "
                    "sphere's diameter)")
        ->check(positiveNumber());
    command
        .add_option("--jobs", options.jobs,
                    "Trajectories replayed at once (0: one per hardware thread); the figures are the same at any "
                    "count")
        ->check(wholeNumber(0, 65536))
        ->capture_default_str();
    command.add_flag("--no-progress", noProgress,
                     "No progress line (it is drawn on standard error only when that is a terminal)");
}

/// The name a simulated trajectory is written under: the measured file's, without .gz, as .csv.
std::string simulatedName(const fs::path& measured)
{
    fs::path name = measured.filename();
    if (name.extension() == ".gz")
    {
        name = name.stem();
    }
    return name.replace_extension(".csv").string();
}

/// Writes each simulation into `directory` (created if need be) under its measurement's name.
/// Throws ReplayRefusal naming the directory or the file that cannot be written.
void writeSimulated(const std::string& directory, const std::vector<fs::path>& files,
                    const std::vector<io::Trajectory>& simulated)
{
    std::error_code error;
    fs::create_directories(directory, error);
    if (error || !fs::is_directory(directory))
    {
        throw ReplayRefusal(directory + ": cannot create the output directory" +
                            (error ? " (" + error.message() + ")" : std::string()));
    }
    for (std::size_t i = 0; i < files.size(); ++i)
    {
        const fs::path path = fs::path(directory) / simulatedName(files[i]);
        std::ofstream out(path);
        io::TrajectoryWriter(out).writeTrajectory(simulated[i]);
        out.flush();
        if (!out)
        {
            throw ReplayRefusal(path.string() + ": cannot write");
        }
    }
}

} // namespace

int runReplay(const ReplayOptions& options)
{
    Batch batch;
    std::vector<io::ReplayError> results;
    try
    {
        batch = loadBatch(options.measured, options.scenePath, options.size);
        std::vector<io::Trajectory> simulated;
        results = replayBatch(batch, std::nullopt, options.jobs, options.progress && stderrIsTerminal(),
                              options.outDirectory.empty() ? nullptr : &simulated);
        if (!options.outDirectory.empty())
        {
            writeSimulated(options.outDirectory, batch.files, simulated);
        }
    }
    catch (const std::exception& error)
    {
        std::cerr << "impulse: " << error.what() << "\n";
        return 2;
    }
    const io::Scene& scene = batch.scene;
    const BodyId body = batch.body;
    const Real size = batch.size;
    const std::vector<fs::path>& files = batch.files;

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
    if (const std::optional<int> code = writeJson(json, options.jsonPath))
    {
        return *code;
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

namespace
{

/// One evaluation of a fit: the mean errors over the set at one friction and restitution.
struct FitPoint
{
    Real friction = 0.0;
    Real restitution = 0.0;
    Real position = 0.0;  ///< mean position error, % of size
    Real rotation = 0.0;  ///< mean rotation error, degrees
    Real objective = 0.0; ///< what the fit minimises
};

nlohmann::json pointJson(const FitPoint& point)
{
    return {{"friction", point.friction},
            {"restitution", point.restitution},
            {"position", point.position},
            {"rotation", point.rotation},
            {"objective", point.objective}};
}

} // namespace

int runFit(const FitOptions& options)
{
    const ReplayOptions& shared = options.replay;
    Batch batch;
    PairCoefficients start;
    try
    {
        batch = loadBatch(shared.measured, shared.scenePath, shared.size);
        start = templateContact(batch);
    }
    catch (const std::exception& error)
    {
        std::cerr << "impulse: " << error.what() << "\n";
        return 2;
    }
    // friction in [0, 2], restitution in [0, 1]
    constexpr double kLower[2] = {0.0, 0.0};
    constexpr double kUpper[2] = {2.0, 1.0};
    const auto evaluate = [&](Real friction, Real restitution)
    {
        FitPoint point{friction, restitution};
        const std::vector<io::ReplayError> results =
            replayBatch(batch, PairCoefficients{restitution, friction}, shared.jobs, false);
        for (const io::ReplayError& result : results)
        {
            point.position += result.positionError;
            point.rotation += result.rotationError;
        }
        point.position /= static_cast<Real>(results.size());
        point.rotation /= static_cast<Real>(results.size());
        point.objective = options.objective == "position"   ? point.position
                          : options.objective == "rotation" ? point.rotation
                                                            : point.position + point.rotation;
        return point;
    };

    // Subplex (NLopt's LN_SBPLX): derivative-free, since a replay's error is not smooth in the
    // parameters (a cube that tips over or not), and deterministic, with no random restarts
    struct State
    {
        const decltype(evaluate)* run;
        int count = 0;
        int budget = 0;
        std::string failure;
        Progress* progress;
        Clock::time_point started;
    };
    Progress progress(shared.progress && stderrIsTerminal(), "replays of the set");
    State state{&evaluate, 0, options.evaluations, {}, &progress, Clock::now()};
    const auto objective = [](unsigned, const double* x, double*, void* data) -> double
    {
        auto& s = *static_cast<State*>(data);
        try
        {
            const FitPoint point = (*s.run)(x[0], x[1]);
            ++s.count;
            const Clock::time_point now = Clock::now();
            s.progress->update("fit", s.count, s.budget, "", now - s.started, now);
            return point.objective;
        }
        catch (const std::exception& error)
        {
            s.failure = error.what();
            throw; // NLopt stops on a C++ exception and rethrows it from nlopt_optimize
        }
    };
    FitPoint before;
    FitPoint after;
    nlopt_result outcome = NLOPT_FAILURE;
    double x[2] = {std::clamp(start.friction, kLower[0], kUpper[0]),
                   std::clamp(start.restitution, kLower[1], kUpper[1])};
    // One NLopt search over the bounds from `from` (moved to the best point found) within
    // `evaluations`; a local search (localStep > 0) takes that first step and ends when no
    // parameter moves by more than 1e-4. Throws when the objective or the optimiser failed.
    const auto search = [&](nlopt_algorithm algorithm, double* from, int evaluations, double localStep, double& best)
    {
        nlopt_opt optimiser = nlopt_create(algorithm, 2);
        nlopt_set_lower_bounds(optimiser, kLower);
        nlopt_set_upper_bounds(optimiser, kUpper);
        nlopt_set_min_objective(optimiser, +objective, &state);
        if (localStep > 0.0)
        {
            const double step[2] = {localStep, localStep};
            nlopt_set_initial_step(optimiser, step);
            nlopt_set_xtol_abs1(optimiser, 1e-4);
        }
        nlopt_set_maxeval(optimiser, evaluations);
        const nlopt_result result = nlopt_optimize(optimiser, from, &best);
        nlopt_destroy(optimiser);
        if (!state.failure.empty() || result < 0)
        {
            throw ReplayRefusal(state.failure.empty() ? "the optimiser failed (NLopt code " +
                                                            std::to_string(static_cast<int>(result)) + ")"
                                                      : state.failure);
        }
        return result;
    };
    const int scan = std::min(options.scan, options.evaluations);
    try
    {
        before = evaluate(x[0], x[1]);
        // The error has many local minima where tosses change their outcome (a cube that lands on
        // another face), and a local search from the template's values can stop in one far from
        // the best: DIRECT-L (deterministic) first samples the whole box, and the local search
        // starts from the best point it found when that beats the template's values.
        if (scan > 0)
        {
            double scanned[2] = {x[0], x[1]};
            double best = 0.0;
            outcome = search(NLOPT_GN_DIRECT_L, scanned, scan, 0.0, best);
            if (best < before.objective)
            {
                x[0] = scanned[0];
                x[1] = scanned[1];
            }
        }
        // The error is kinked where a contact changes its mode, and a simplex can stall against a
        // kink short of the minimum: the search starts again from the best point with a step five
        // times smaller, three times in all, within the one budget of evaluations.
        for (const double stepSize : {0.05, 0.01, 0.002})
        {
            const int left = options.evaluations - state.count;
            if (left <= 0)
            {
                break;
            }
            double best = 0.0;
            outcome = search(NLOPT_LN_SBPLX, x, left, stepSize, best);
        }
        progress.clear();
        after = evaluate(x[0], x[1]);
    }
    catch (const std::exception& error)
    {
        progress.clear();
        std::cerr << "impulse: " << error.what() << "\n";
        return 2;
    }

    // how much worse the fit gets when a parameter moves by 0.02 either way (within its bounds)
    constexpr Real kNudge = 0.02;
    struct Sensitivity
    {
        std::string parameter;
        Real below = 0.0; ///< objective change at the value less kNudge
        Real above = 0.0;
    };
    std::vector<Sensitivity> sensitivities;
    for (int p = 0; p < 2; ++p)
    {
        Sensitivity s{p == 0 ? "friction" : "restitution"};
        for (const Real sign : {-1.0, 1.0})
        {
            double moved[2] = {after.friction, after.restitution};
            moved[p] = std::clamp(moved[p] + sign * kNudge, kLower[p], kUpper[p]);
            const Real change = evaluate(moved[0], moved[1]).objective - after.objective;
            (sign < 0.0 ? s.below : s.above) = change;
        }
        sensitivities.push_back(s);
    }

    const char* stopped = outcome == NLOPT_XTOL_REACHED      ? "the parameters converged to 1e-4"
                          : outcome == NLOPT_MAXEVAL_REACHED ? "the evaluation budget ran out"
                                                             : "the objective stopped changing";
    const std::string objectiveName = options.objective == "position"   ? "mean position error (% of size)"
                                      : options.objective == "rotation" ? "mean rotation error (degrees)"
                                                                        : "mean position error (% of size) + "
                                                                          "mean rotation error (degrees)";
    nlohmann::json json;
    json["scene"] = shared.scenePath;
    json["trajectories"] = batch.files.size();
    json["objective"] = options.objective;
    json["optimiser"] = scan > 0 ? "NLopt GN_DIRECT_L, then LN_SBPLX" : "NLopt LN_SBPLX";
    json["scan"] = scan;
    json["evaluations"] = state.count;
    json["stopped"] = stopped;
    json["before"] = pointJson(before);
    json["after"] = pointJson(after);
    json["sensitivity"] = nlohmann::json::object();
    for (const Sensitivity& s : sensitivities)
    {
        json["sensitivity"][s.parameter] = {{"step", kNudge}, {"below", s.below}, {"above", s.above}};
    }
    if (const std::optional<int> code = writeJson(json, shared.jsonPath))
    {
        return *code;
    }
    std::cout << "fit of friction and restitution to " << batch.files.size() << " measured trajectories with "
              << shared.scenePath << "\nminimising " << objectiveName << "\n";
    std::cout << "optimiser: "
              << (scan > 0 ? "NLopt DIRECT-L over the bounds (" + std::to_string(scan) + " evaluations), then "
                           : std::string())
              << "NLopt Subplex (LN_SBPLX), restarted with smaller steps, " << state.count
              << " evaluations in all; the last search stopped because " << stopped << "\n\n";
    char line[256];
    std::snprintf(line, sizeof line, "%-8s %10s %12s %11s %13s %10s\n", "", "friction", "restitution", "position %",
                  "rotation deg", "objective");
    std::cout << line;
    for (const auto& [name, point] : {std::pair{"before", before}, std::pair{"after", after}})
    {
        std::snprintf(line, sizeof line, "%-8s %10.4f %12.4f %11.2f %13.2f %10.2f\n", name, point.friction,
                      point.restitution, point.position, point.rotation, point.objective);
        std::cout << line;
    }
    std::cout << "\nsensitivity: the objective's change when a parameter moves by " << kNudge << "\n";
    for (const Sensitivity& s : sensitivities)
    {
        std::snprintf(line, sizeof line, "%-12s -%.2f: %+8.3f   +%.2f: %+8.3f\n", s.parameter.c_str(), kNudge, s.below,
                      kNudge, s.above);
        std::cout << line;
    }
    return 0;
}

ReplayCommand::ReplayCommand(CLI::App& app)
{
    m_command =
        app.add_subcommand("replay", "Simulate measured trajectories again from their first sample and report how far "
                                     "the simulation ends up from them (position in % of the body's size, rotation in "
                                     "degrees)");
    addMeasurementOptions(*m_command, m_options, m_noProgress);
    m_command->add_option("--out", m_options.outDirectory,
                          "Also write each simulation, sampled at its measured times, into this directory (created "
                          "if need be) as a trajectory CSV named after the measured file");
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

FitCommand::FitCommand(CLI::App& app)
{
    m_command =
        app.add_subcommand("fit", "Fit friction and restitution to measured trajectories: the values whose replay "
                                  "(impulse replay) comes closest to them; the template's are where the fit starts");
    addMeasurementOptions(*m_command, m_options.replay, m_noProgress);
    m_command
        ->add_option("--objective", m_options.objective,
                     "What is minimised: sum (mean position error in % plus mean rotation error in degrees), "
                     "position or rotation")
        ->check(CLI::IsMember({"sum", "position", "rotation"}))
        ->capture_default_str();
    m_command->add_option("--max-evaluations", m_options.evaluations, "Replays of the whole set at most")
        ->check(wholeNumber(1, 100000))
        ->capture_default_str();
    m_command
        ->add_option("--scan", m_options.scan,
                     "Replays of the global look over the bounds (DIRECT-L) before the local search, within "
                     "--max-evaluations; 0: the local search alone, from the template's values")
        ->check(wholeNumber(0, 100000))
        ->capture_default_str();
}

std::optional<int> FitCommand::runChosen() const
{
    if (!m_command->parsed())
    {
        return std::nullopt;
    }
    FitOptions options = m_options;
    options.replay.progress = !m_noProgress;
    return runFit(options);
}

} // namespace impulse::app
