// SPDX-License-Identifier: MIT
// The cost curve: milliseconds per step of reference scene 11's layout (spheres of radius 0.1,
// 15 x 15 per layer 0.25 m apart with a little jitter, lowest layer at z = 0.3, falling into the
// 4 m x 4 m box with mu = 0.5, eps = 0.3) at several N, with the time of each stage of the step.
//
//   impulse_bench_scaling [--warm-up W] [--steps S] [--threads T] [N ...]
//
// Default N: 1000 2000 5000 10000 20000. Each world is stepped W times (default 1500: 1.5 s, the
// lowest layers have landed and the pile is forming) and the next S (default 50) are measured:
// median and mean ms per step, contacts per step, and the mean ms of each stage (the world's own
// stage clocks, StepStats::milliseconds). The layout for N = 1000 and 10000 is the same rule as
// scenes/initial-states, with its own jitter.
#include <impulse/impulse.hpp>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <random>
#include <string>
#include <vector>

namespace
{

using impulse::Real;
using impulse::Vec3;

impulse::World spherePile(int n)
{
    impulse::World world;
    const impulse::MaterialId material = world.createMaterial({.restitution = 0.3, .friction = 0.5});
    world.createBody({.type = impulse::BodyType::Static, .shape = impulse::Plane{}, .material = material});
    constexpr int kPerRow = 15;
    constexpr Real kSpacing = 0.25;
    const int layers = (n + kPerRow * kPerRow - 1) / (kPerRow * kPerRow);
    const Real height = 0.3 + kSpacing * (layers - 1) + 1.0;
    const struct
    {
        Vec3 half;
        Vec3 centre;
    } walls[] = {{Vec3(0.1, 2.2, height / 2), Vec3(-2.1, 0, height / 2)},
                 {Vec3(0.1, 2.2, height / 2), Vec3(2.1, 0, height / 2)},
                 {Vec3(2.0, 0.1, height / 2), Vec3(0, -2.1, height / 2)},
                 {Vec3(2.0, 0.1, height / 2), Vec3(0, 2.1, height / 2)}};
    for (const auto& wall : walls)
    {
        world.createBody({.type = impulse::BodyType::Static,
                          .shape = impulse::Box{wall.half},
                          .material = material,
                          .position = wall.centre});
    }
    std::mt19937_64 random(11);
    const auto jitter = [&] { return 0.02 * (static_cast<Real>(random() % 2001) / 1000.0 - 1.0); };
    for (int k = 0; k < n; ++k)
    {
        const int layer = k / (kPerRow * kPerRow);
        const int slot = k % (kPerRow * kPerRow);
        const Vec3 position((slot % kPerRow - (kPerRow - 1) / 2.0) * kSpacing + jitter(),
                            (slot / kPerRow - (kPerRow - 1) / 2.0) * kSpacing + jitter(), 0.3 + kSpacing * layer);
        world.createBody({.shape = impulse::Sphere{0.1}, .material = material, .mass = 1.0, .position = position});
    }
    return world;
}

} // namespace

int main(int argc, char** argv)
{
    int warmUp = 1500;
    int steps = 50;
    int threads = 1;
    std::vector<int> sizes;
    for (int i = 1; i < argc; ++i)
    {
        const std::string arg = argv[i];
        if (arg == "--warm-up" && i + 1 < argc)
        {
            warmUp = std::max(0, std::atoi(argv[++i]));
        }
        else if (arg == "--steps" && i + 1 < argc)
        {
            steps = std::max(1, std::atoi(argv[++i]));
        }
        else if (arg == "--threads" && i + 1 < argc)
        {
            threads = std::max(0, std::atoi(argv[++i]));
        }
        else if (arg == "--help" || arg == "-h")
        {
            std::printf("usage: impulse_bench_scaling [--warm-up W] [--steps S] [--threads T] [N ...]\n");
            return 0;
        }
        else if (std::atoi(arg.c_str()) > 0)
        {
            sizes.push_back(std::atoi(arg.c_str()));
        }
        else
        {
            std::fprintf(stderr, "impulse_bench_scaling: not a body count: %s\n", arg.c_str());
            return 2;
        }
    }
    if (sizes.empty())
    {
        sizes = {1000, 2000, 5000, 10000, 20000};
    }
    std::printf("sphere_pile layout, steps %d-%d (dt 1 ms), %d thread(s)\n", warmUp, warmUp + steps, threads);
    std::printf("%7s %9s %9s %9s %8s | %8s %9s %8s %9s %8s %8s %8s  %s\n", "N", "ms/step", "mean", "contacts",
                "us/body", "pairs", "collision", "graph", "contact", "shock", "position", "push-out", "state hash");
    for (const int n : sizes)
    {
        impulse::World world = spherePile(n);
        impulse::StepOptions options;
        options.threads = threads;
        for (int k = 0; k < warmUp; ++k)
        {
            world.step(options);
        }
        std::vector<double> times;
        impulse::StepStats::StageTimes stages;
        double contacts = 0.0;
        for (int k = 0; k < steps; ++k)
        {
            const auto start = std::chrono::steady_clock::now();
            world.step(options);
            times.push_back(
                std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count());
            const impulse::StepStats& stats = world.lastStepStats();
            contacts += stats.contactPairs;
            stages.candidatePairs += stats.milliseconds.candidatePairs / steps;
            stages.collisionPass += stats.milliseconds.collisionPass / steps;
            stages.contactGraph += stats.milliseconds.contactGraph / steps;
            stages.contactPass += stats.milliseconds.contactPass / steps;
            stages.shockPropagation += stats.milliseconds.shockPropagation / steps;
            stages.positionUpdate += stats.milliseconds.positionUpdate / steps;
            stages.pushOut += stats.milliseconds.pushOut / steps;
        }
        double mean = 0.0;
        for (const double t : times)
        {
            mean += t / steps;
        }
        std::sort(times.begin(), times.end());
        const double median = times[times.size() / 2];
        std::printf("%7d %9.2f %9.2f %9.0f %8.2f | %8.2f %9.2f %8.2f %9.2f %8.2f %8.2f %8.2f  %016llx\n", n, median,
                    mean, contacts / steps, 1000.0 * mean / n, stages.candidatePairs, stages.collisionPass,
                    stages.contactGraph, stages.contactPass, stages.shockPropagation, stages.positionUpdate,
                    stages.pushOut, static_cast<unsigned long long>(world.stateHash()));
        std::fflush(stdout);
    }
    return 0;
}
