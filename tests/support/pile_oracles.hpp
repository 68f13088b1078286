// SPDX-License-Identifier: MIT
// Test support: the oracles of reference scenes 11 and 12 (scenarios.md). Bodies of size r fall into
// a box whose inner walls are at x, y = +-2; none may leave it, and none may end inside another:
// the deepest penetration at the end is under 1 % of r.
#pragma once

#include "support/penetration.hpp"
#include "support/scene_run.hpp"

#include <gtest/gtest.h>

#include <iostream>
#include <string>

namespace impulse::test
{

inline void expectPileStaysInTheBoxWithoutOverlaps(const std::string& name, Real r)
{
    io::Scene scene = loadReferenceScene(name);
    scene.options.threads = 0; // every core: the trajectory is the same at any thread count
    // the walls' top: the highest point of the static boxes
    Real wallTop = 0.0;
    for (std::uint32_t i = 0; i < scene.world.bodyCount(); ++i)
    {
        if (const auto* box = std::get_if<Box>(&scene.world.shape({i})))
        {
            wallTop = std::max(wallTop, scene.world.state({i}).position.z() + box->halfExtents.z());
        }
    }
    ASSERT_GT(wallTop, 1.0) << name << ": no walls found";
    int step = 0;
    int escaped = 0;
    Real peakKinetic = 0.0;
    runScene(scene, -1.0,
             [&](Real t, const World& world)
             {
                 peakKinetic = std::max(peakKinetic, world.kineticEnergy());
                 if (++step % 100 != 0)
                 {
                     return;
                 }
                 escaped = 0;
                 for (const BodyId body : scene.dynamicBodies)
                 {
                     const Vec3 x = world.state(body).position;
                     const bool inside =
                         std::abs(x.x()) < 2.0 && std::abs(x.y()) < 2.0 && x.z() > 0.0 && x.z() < wallTop;
                     escaped += inside ? 0 : 1;
                 }
                 ASSERT_EQ(escaped, 0) << name << ": bodies out of the box at t = " << t << " s";
                 if (step % 1000 == 0)
                 {
                     std::cout << name << " t " << t << " s: kinetic " << world.kineticEnergy() << " J (peak "
                               << peakKinetic << "), " << world.lastStepStats().contactPairs << " contacts"
                               << std::endl;
                 }
             });
    const Penetration p = deepestPenetration(scene.world);
    std::cout << name << " at the end: deepest penetration " << p.depth << " m = " << 100.0 * p.depth / r
              << " % of r; kinetic energy " << scene.world.kineticEnergy() << " J (peak " << peakKinetic << ")"
              << std::endl;
    EXPECT_LT(p.depth, 0.01 * r) << name;
}

} // namespace impulse::test
