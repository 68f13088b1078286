// SPDX-License-Identifier: MIT
// Milliseconds per step of the stacking scenes with shock propagation on and off.
//
//   impulse_bench_stacking [--steps N] [SCENE.json ...]
//
// Default scenes: box_stack_50 and pyramid. Each scene is stepped N times (default 2000) with each
// setting; the figures are the median and the 10th-90th percentile spread of the wall time of a
// step, after a warm-up of N/10 steps, plus the bodies, candidate pairs and contact rows per step, and the
// final state hash (equal runs give equal hashes).
#include <impulse/io/scene.hpp>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

namespace
{

struct Figures
{
    double median = 0.0;
    double p10 = 0.0;
    double p90 = 0.0;
    double pairs = 0.0;
    double rows = 0.0;
    unsigned long long hash = 0;
    std::size_t bodies = 0;
};

Figures measure(const std::string& path, bool shock, int steps)
{
    impulse::io::Scene scene = impulse::io::loadScene(path);
    scene.options.shockPropagation = shock;
    const int warmUp = steps / 10;
    std::vector<double> times;
    times.reserve(static_cast<std::size_t>(steps));
    double pairs = 0.0;
    double rows = 0.0;
    for (int k = 0; k < warmUp + steps; ++k)
    {
        const auto start = std::chrono::steady_clock::now();
        scene.world.step(scene.options);
        const double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
        if (k >= warmUp)
        {
            times.push_back(ms);
            const impulse::StepStats& stats = scene.world.lastStepStats();
            pairs += stats.candidatePairs;
            rows += stats.contactRows;
        }
    }
    std::sort(times.begin(), times.end());
    const auto at = [&](double q)
    { return times[static_cast<std::size_t>(q * static_cast<double>(times.size() - 1))]; };
    return {
        at(0.5), at(0.1), at(0.9), pairs / steps, rows / steps, scene.world.stateHash(), scene.dynamicBodies.size()};
}

} // namespace

int main(int argc, char** argv)
{
    int steps = 2000;
    std::vector<std::string> scenes;
    for (int i = 1; i < argc; ++i)
    {
        const std::string arg = argv[i];
        if (arg == "--steps" && i + 1 < argc)
        {
            steps = std::max(10, std::atoi(argv[++i]));
        }
        else if (arg == "--help" || arg == "-h")
        {
            std::printf("usage: impulse_bench_stacking [--steps N] [SCENE.json ...]\n");
            return 0;
        }
        else
        {
            scenes.push_back(arg);
        }
    }
    if (scenes.empty())
    {
        scenes = {std::string(IMPULSE_SCENES_DIR) + "/box_stack_50.json",
                  std::string(IMPULSE_SCENES_DIR) + "/pyramid.json"};
    }
    std::printf("%-16s %6s %6s %10s %18s %8s %10s  %s\n", "scene", "bodies", "shock", "ms/step", "p10-p90", "pairs",
                "rows", "state hash");
    for (const std::string& path : scenes)
    {
        const std::string name = path.substr(path.find_last_of('/') + 1);
        for (const bool shock : {true, false})
        {
            try
            {
                const Figures f = measure(path, shock, steps);
                std::printf("%-16s %6zu %6s %10.3f %8.3f-%-9.3f %8.1f %10.1f  %016llx\n", name.c_str(), f.bodies,
                            shock ? "on" : "off", f.median, f.p10, f.p90, f.pairs, f.rows, f.hash);
            }
            catch (const impulse::io::SceneError& error)
            {
                std::fprintf(stderr, "%s\n", error.what());
                return 2;
            }
        }
    }
    return 0;
}
