// SPDX-License-Identifier: MIT
// Nonconvex bodies: the cost of preparing a mesh (validation, mass properties, hierarchy and signed
// distance grid) and milliseconds per step of the nonconvex piles.
//
//   impulse_bench_meshes [--build-only] [--warm-up W] [--steps N] [SCENE.json ...]
//
// The grid figure prepares a torus of 10 000 triangles at 64 cells along its longest side, five
// times, and reports the median. Each scene (default: nonconvex_pile_200 and nonconvex_pile_1000)
// is stepped W times (default 400: the bodies have landed and pile up) and then N times (default
// 100), and the figures are over those N steps: median and 10th-90th percentile of a step's wall
// time, bodies, contact pairs and impulses per step, and the final state hash.
#include "geometry/mesh_queries.hpp"

#include <impulse/io/scene.hpp>
#include <impulse/mesh_shapes.hpp>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

namespace
{

using Clock = std::chrono::steady_clock;

double milliseconds(Clock::time_point since)
{
    return std::chrono::duration<double, std::milli>(Clock::now() - since).count();
}

double percentile(std::vector<double> values, double q)
{
    std::sort(values.begin(), values.end());
    return values[static_cast<std::size_t>(q * static_cast<double>(values.size() - 1))];
}

void benchGridBuild()
{
    const impulse::TriangleMesh torus = impulse::torusMesh(0.3, 0.1, 100, 50);
    std::vector<double> times;
    std::shared_ptr<const impulse::MeshGeometry> geometry;
    for (int k = 0; k < 5; ++k)
    {
        const auto start = Clock::now();
        geometry = impulse::MeshGeometry::build(torus, {64});
        times.push_back(milliseconds(start));
    }
    const auto samples = impulse::MeshQueries::of(*geometry).gridSamples();
    std::printf("prepare a mesh of %zu triangles, grid %d x %d x %d samples: %.1f ms (median of 5, %.1f-%.1f)\n\n",
                geometry->triangles().size(), samples[0], samples[1], samples[2], percentile(times, 0.5),
                percentile(times, 0.0), percentile(times, 1.0));
}

int benchScene(const std::string& path, int warmUp, int steps)
{
    impulse::io::Scene scene;
    const auto loadStart = Clock::now();
    try
    {
        scene = impulse::io::loadScene(path);
    }
    catch (const impulse::io::SceneError& error)
    {
        std::fprintf(stderr, "%s\n", error.what());
        return 2;
    }
    const double loadMs = milliseconds(loadStart);
    std::vector<double> times;
    double pairs = 0.0;
    double impulses = 0.0;
    for (int k = 0; k < warmUp + steps; ++k)
    {
        const auto start = Clock::now();
        scene.world.step(scene.options);
        if (k >= warmUp)
        {
            times.push_back(milliseconds(start));
            const impulse::StepStats& stats = scene.world.lastStepStats();
            pairs += stats.candidatePairs;
            impulses += stats.contactRows;
        }
    }
    const std::string name = path.substr(path.find_last_of('/') + 1);
    std::printf("%-24s %6zu %8.0f %10.3f %9.3f-%-9.3f %8.1f %10.1f  %016llx\n", name.c_str(),
                scene.dynamicBodies.size(), loadMs, percentile(times, 0.5), percentile(times, 0.1),
                percentile(times, 0.9), pairs / steps, impulses / steps,
                static_cast<unsigned long long>(scene.world.stateHash()));
    std::fflush(stdout);
    return 0;
}

} // namespace

int main(int argc, char** argv)
{
    int warmUp = 400;
    int steps = 100;
    bool buildOnly = false;
    std::vector<std::string> scenes;
    for (int i = 1; i < argc; ++i)
    {
        const std::string arg = argv[i];
        if (arg == "--steps" && i + 1 < argc)
        {
            steps = std::max(1, std::atoi(argv[++i]));
        }
        else if (arg == "--warm-up" && i + 1 < argc)
        {
            warmUp = std::max(0, std::atoi(argv[++i]));
        }
        else if (arg == "--build-only")
        {
            buildOnly = true;
        }
        else if (arg == "--help" || arg == "-h")
        {
            std::printf("usage: impulse_bench_meshes [--build-only] [--warm-up W] [--steps N] [SCENE.json ...]\n");
            return 0;
        }
        else
        {
            scenes.push_back(arg);
        }
    }
    benchGridBuild();
    if (buildOnly)
    {
        return 0;
    }
    if (scenes.empty())
    {
        scenes = {std::string(IMPULSE_SCENES_DIR) + "/nonconvex_pile_200.json",
                  std::string(IMPULSE_SCENES_DIR) + "/nonconvex_pile_1000.json"};
    }
    std::printf("%-24s %6s %8s %10s %19s %8s %10s  %s\n", "scene", "bodies", "load ms", "ms/step", "p10-p90", "pairs",
                "impulses", "state hash");
    for (const std::string& path : scenes)
    {
        if (const int status = benchScene(path, warmUp, steps); status != 0)
        {
            return status;
        }
    }
    return 0;
}
