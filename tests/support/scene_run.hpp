// SPDX-License-Identifier: MIT
// Test support: load a shipped scene and step it, calling back after every step.
#pragma once

#include <impulse/io/scene.hpp>

#include <cmath>
#include <functional>
#include <string>

namespace impulse::test
{

inline io::Scene loadReferenceScene(const std::string& name)
{
    return io::loadScene(std::string(IMPULSE_SCENES_DIR) + "/" + name + ".json");
}

/// Steps `scene` for its duration (or `duration` when positive) at `dt` (or the scene's when not
/// positive), calling `afterStep(t, world)` after every step.
inline void runScene(io::Scene& scene, Real dt, const std::function<void(Real, const World&)>& afterStep,
                     Real duration = -1.0)
{
    if (dt > 0.0)
    {
        scene.options.dt = dt;
    }
    const Real total = duration > 0.0 ? duration : scene.duration;
    const long long steps = std::llround(total / scene.options.dt);
    for (long long k = 1; k <= steps; ++k)
    {
        scene.world.step(scene.options);
        afterStep(static_cast<Real>(k) * scene.options.dt, scene.world);
    }
}

inline Real totalEnergy(const World& world)
{
    return world.kineticEnergy() + world.potentialEnergy();
}

} // namespace impulse::test
