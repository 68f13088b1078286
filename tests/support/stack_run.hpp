// SPDX-License-Identifier: MIT
// Test support: step a stacking scene and record how far and how fast its bodies move, and what
// the collision pass still does once it has settled.
#pragma once

#include "support/scene_run.hpp"

#include <algorithm>
#include <vector>

namespace impulse::test
{

struct StackRecord
{
    Real topDisplacement = 0.0;      ///< largest distance of the last body from its start
    Real largestDrift = 0.0;         ///< largest distance of any body from where it was at settleTime
    Real fastestAfterSettling = 0.0; ///< largest speed of any body after settleTime
    Real fastestAtEnd = 0.0;
    long collisionImpulsesAfterSettling = 0; ///< over the steps after settleTime
};

inline StackRecord runStack(io::Scene& scene, Real dt, Real settleTime, Real duration = -1.0)
{
    StackRecord record;
    const BodyId top = scene.dynamicBodies.back();
    const Vec3 topStart = scene.world.state(top).position;
    std::vector<Vec3> settled;
    runScene(
        scene, dt,
        [&](Real t, const World& world)
        {
            record.topDisplacement = std::max(record.topDisplacement, (world.state(top).position - topStart).norm());
            if (t + 0.5 * scene.options.dt < settleTime)
            {
                return;
            }
            if (settled.empty())
            {
                for (const BodyId id : scene.dynamicBodies)
                {
                    settled.push_back(world.state(id).position);
                }
            }
            else
            {
                record.collisionImpulsesAfterSettling += world.lastStepStats().collisionImpulses;
            }
            Real fastest = 0.0;
            for (std::size_t k = 0; k < scene.dynamicBodies.size(); ++k)
            {
                const BodyState s = world.state(scene.dynamicBodies[k]);
                record.largestDrift = std::max(record.largestDrift, (s.position - settled[k]).norm());
                fastest = std::max(fastest, std::max(s.linearVelocity.norm(), s.angularVelocity.norm() * 0.2));
            }
            record.fastestAfterSettling = std::max(record.fastestAfterSettling, fastest);
            record.fastestAtEnd = fastest;
        },
        duration);
    return record;
}

} // namespace impulse::test
