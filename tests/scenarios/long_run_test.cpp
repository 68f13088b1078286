// SPDX-License-Identifier: MIT
// A long run of many kinds of body at once, checked after every step: mixed_pile_1000 (spheres,
// cubes, capsules and nonconvex meshes, each with its own random restitution and friction) falls
// into a box and settles over 20 s. Whatever the bodies do, after every step
// - every number of every state is finite;
// - every body's centre is inside the box (walls at x, y = +-2, above the ground, below the walls' top);
// - the energy is never above its start: kinetic plus gravitational energy is the start's kinetic
//   energy plus the work of gravity, and contacts, restitution at most 0.8 and friction only take
//   energy away (the allowance is round-off of the sums);
// - no two bodies overlap by 1 % of the smaller one's size (its bounding diameter) or more.
// Label "long": about ten minutes on one core, the longest test of the suite (ctest starts it first).
#include "support/penetration.hpp"
#include "support/scene_run.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <iostream>
#include <string>
#include <variant>

namespace impulse::test
{
namespace
{

bool finite(const BodyState& state)
{
    return state.position.allFinite() && state.orientation.coeffs().allFinite() && state.linearVelocity.allFinite() &&
           state.angularVelocity.allFinite();
}

TEST(LongRun, AThousandMixedBodiesStayFiniteInTheBoxApartAndNeverGainEnergyOverTwentySeconds)
{
    io::Scene scene = loadReferenceScene("mixed_pile_1000");
    World& world = scene.world;
    ASSERT_EQ(scene.dynamicBodies.size(), 1000u);
    Real wallTop = 0.0;
    for (std::uint32_t i = 0; i < world.bodyCount(); ++i)
    {
        if (const auto* box = std::get_if<Box>(&world.shape({i})); box != nullptr && !world.isDynamic({i}))
        {
            wallTop = std::max(wallTop, world.state({i}).position.z() + box->halfExtents.z());
        }
    }
    ASSERT_GT(wallTop, 4.0);

    const Real start = totalEnergy(world);
    // the sums of a thousand terms of up to 400 J each round off at a few 1e-13 of their size
    Real magnitude = 0.0;
    for (const BodyId body : scene.dynamicBodies)
    {
        magnitude += world.mass(body) * 9.81 * std::abs(world.state(body).position.z());
    }
    const Real allowance = 1e-12 * magnitude;

    Real largestGain = -magnitude; // the energy above its start, the largest over the run
    Real deepest = 0.0;            // relative to the smaller body, the largest over the run
    const long long steps = std::llround(scene.duration / scene.options.dt);
    for (long long k = 1; k <= steps; ++k)
    {
        world.step(scene.options);
        const Real t = world.time();
        for (const BodyId body : scene.dynamicBodies)
        {
            const BodyState state = world.state(body);
            ASSERT_TRUE(finite(state)) << scene.bodyNames[body.index] << " at t = " << t << " s";
            const Vec3& x = state.position;
            ASSERT_TRUE(std::abs(x.x()) < 2.0 && std::abs(x.y()) < 2.0 && x.z() > 0.0 && x.z() < wallTop)
                << scene.bodyNames[body.index] << " out of the box at t = " << t << " s: (" << x.transpose() << ")";
        }
        const Real gain = totalEnergy(world) - start;
        largestGain = std::max(largestGain, gain);
        ASSERT_LE(gain, allowance) << "at t = " << t << " s the energy is " << gain << " J above its start";
        const Penetration overlap = deepestPenetration(world);
        deepest = std::max(deepest, overlap.relative);
        ASSERT_LT(overlap.relative, 0.01)
            << scene.bodyNames[overlap.first] << " and " << scene.bodyNames[overlap.second] << " overlap by "
            << overlap.depth << " m at t = " << t << " s";
        if (k % 1000 == 0)
        {
            std::cout << "mixed_pile_1000 t " << t << " s: kinetic " << world.kineticEnergy() << " J, energy "
                      << totalEnergy(world) - start << " J from its start (largest " << largestGain << "), "
                      << world.lastStepStats().contactPairs << " contacts, deepest overlap so far " << 100.0 * deepest
                      << " % of the smaller body" << std::endl;
        }
    }
}

} // namespace
} // namespace impulse::test
