// SPDX-License-Identifier: MIT
#include "run_command.hpp"

#include "progress.hpp"
#include "scene_warnings.hpp"
#include "see_inputs.hpp"
#include "stop_request.hpp"

#include <impulse/io/scene.hpp>
#include <impulse/io/trajectory.hpp>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <sstream>
#include <stdexcept>

namespace impulse::app
{
namespace
{

bool stateIsFinite(const World& world, const std::vector<BodyId>& bodies)
{
    for (const BodyId id : bodies)
    {
        const BodyState s = world.state(id);
        if (!s.position.allFinite() || !s.orientation.coeffs().allFinite() || !s.linearVelocity.allFinite() ||
            !s.angularVelocity.allFinite())
        {
            return false;
        }
    }
    return true;
}

} // namespace

int runScene(const RunOptions& options)
{
    io::Scene scene;
    const bool mjcf = isModelPath(options.scenePath);
    try
    {
        scene = loadSceneInput(options.scenePath);
    }
    catch (const InputError& error)
    {
        std::cerr << "impulse: " << error.what() << "\n";
        return 2;
    }
    if (mjcf && std::isnan(scene.duration) && !options.duration)
    {
        std::cerr << "impulse: " << options.scenePath
                  << ": no duration: pass --duration, or add <numeric name=\"impulse_duration\" data=\"SECONDS\"/> "
                     "to the model's <custom>\n";
        return 2;
    }
    if (options.dt)
    {
        scene.options.dt = *options.dt;
    }
    if (options.duration)
    {
        scene.duration = *options.duration;
    }
    if (options.scheme)
    {
        scene.options.scheme = *options.scheme == "traditional" ? Scheme::Traditional : Scheme::Guendelman;
    }
    if (options.shockPropagation)
    {
        scene.options.shockPropagation = *options.shockPropagation == "on";
    }
    if (options.pushOut)
    {
        scene.options.pushOut = *options.pushOut == "on";
    }
    if (options.sleep)
    {
        scene.options.sleep = *options.sleep == "on";
    }
    scene.options.threads = options.threads;
    if (options.restitutionThreshold)
    {
        scene.options.restitutionThreshold = *options.restitutionThreshold;
    }
    const double dt = scene.options.dt;
    if (!(std::isfinite(dt) && dt > 0.0) || !(std::isfinite(scene.duration) && scene.duration >= 0.0))
    {
        std::cerr << "impulse: --dt must be positive and --duration non-negative finite numbers\n";
        return 2;
    }
    constexpr double maxSteps = 1e12;
    if (!(scene.duration / dt <= maxSteps))
    {
        std::cerr << "impulse: " << options.scenePath << ": duration / dt is more than 1e12 steps\n";
        return 2;
    }
    const auto steps = static_cast<long long>(std::llround(scene.duration / dt));

    if (!stateIsFinite(scene.world, scene.dynamicBodies) ||
        !std::isfinite(scene.world.kineticEnergy() + scene.world.potentialEnergy()))
    {
        std::cerr << "impulse: " << options.scenePath
                  << ": the initial state has non-finite energy (velocities or positions too large)\n";
        return 2;
    }

    reportWarnings(scene, options.scenePath);

    // The trajectory is written sample by sample into `pending` and handed to the file in whole
    // samples (at most every 0.2 s of wall time or 4 MB), so that the file ends with a whole sample
    // whenever the run stops, even when it is killed outright.
    std::ofstream file;
    std::ostringstream pending;
    std::optional<io::TrajectoryWriter> writer;
    auto lastFlush = std::chrono::steady_clock::now();
    const auto flushWhole = [&](bool force)
    {
        const auto now = std::chrono::steady_clock::now();
        if (!writer || (!force && pending.tellp() < (4 << 20) && now - lastFlush < std::chrono::milliseconds(200)))
        {
            return;
        }
        const std::string text = pending.str();
        file.write(text.data(), static_cast<std::streamsize>(text.size()));
        file.flush();
        pending.str("");
        lastFlush = now;
    };
    if (!options.outPath.empty())
    {
        file.open(options.outPath, std::ios::binary);
        if (!file)
        {
            std::cerr << "impulse: " << options.outPath << ": cannot open for writing\n";
            return 1;
        }
        writer.emplace(pending);
        writer->writeHeader();
        writer->writeSample(0.0, scene.world, scene.dynamicBodies);
        flushWhole(true);
    }

    const double energyStart = scene.world.kineticEnergy() + scene.world.potentialEnergy();
    const StopRequest stop;
    Progress progress(options.progress && stderrIsTerminal());
    const std::string label = std::filesystem::path(options.scenePath).filename().string();
    const auto start = std::chrono::steady_clock::now();
    long long done = 0;
    std::string stoppedBy;
    for (long long step = 1; step <= steps; ++step)
    {
        try
        {
            scene.world.step(scene.options);
        }
        catch (const std::invalid_argument& error)
        {
            // options the world refuses, such as tolerances too coarse for its smallest body
            progress.clear();
            std::cerr << "impulse: " << options.scenePath << ": " << error.what() << "\n";
            return 2;
        }
        done = step;
        // stop before a non-finite state reaches the file (cheap: a few comparisons per body)
        if (!stateIsFinite(scene.world, scene.dynamicBodies))
        {
            progress.clear();
            flushWhole(true);
            std::cerr << "impulse: " << options.scenePath
                      << ": the simulation diverged (non-finite state) at t = " << static_cast<double>(step) * dt
                      << " s; try a smaller --dt\n";
            return 1;
        }
        const auto now = std::chrono::steady_clock::now();
        if (stop.signal() != 0)
        {
            stoppedBy = stop.name();
        }
        else if (options.timeLimit && std::chrono::duration<double>(now - start).count() >= *options.timeLimit)
        {
            stoppedBy = "--time-limit";
        }
        if (writer && (step % options.every == 0 || step == steps || !stoppedBy.empty()))
        {
            writer->writeSample(static_cast<double>(step) * dt, scene.world, scene.dynamicBodies);
            flushWhole(false);
        }
        if (!stoppedBy.empty())
        {
            break;
        }
        progress.update(label, step, steps, "", now - start, now);
    }
    progress.clear();
    flushWhole(true);
    const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    const double energyEnd = scene.world.kineticEnergy() + scene.world.potentialEnergy();

    if (file.is_open())
    {
        file.close();
        if (!file)
        {
            std::cerr << "impulse: " << options.outPath << ": write failed\n";
            return 1;
        }
    }

    std::printf("scene       %s (%s)\n", options.scenePath.c_str(), scene.name.c_str());
    std::printf("bodies      %zu dynamic, %zu static\n", scene.dynamicBodies.size(),
                static_cast<std::size_t>(scene.world.bodyCount()) - scene.dynamicBodies.size());
    if (stoppedBy.empty())
    {
        std::printf("steps       %lld (dt %g s, %g s simulated)\n", steps, dt, static_cast<double>(steps) * dt);
    }
    else
    {
        std::printf("steps       %lld of %lld (dt %g s, %g s simulated): stopped by %s\n", done, steps, dt,
                    static_cast<double>(done) * dt, stoppedBy.c_str());
    }
    std::printf("wall time   %.3f s, %.4f ms per step\n", wall,
                done > 0 ? 1e3 * wall / static_cast<double>(done) : 0.0);
    std::printf("energy      %.9g J at start, %.9g J at end\n", energyStart, energyEnd);
    std::printf("state hash  %016llx\n", static_cast<unsigned long long>(scene.world.stateHash()));
    if (writer)
    {
        std::printf("trajectory  %s%s\n", options.outPath.c_str(),
                    stoppedBy.empty() ? "" : " (whole samples up to where the run stopped)");
    }
    std::fflush(stdout);
    return stop.signal() != 0 ? stop.exitCode() : 0;
}

} // namespace impulse::app
