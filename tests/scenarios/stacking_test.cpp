// SPDX-License-Identifier: MIT
// Stacking: the contact graph and shock propagation (reference scene 9 and the stacking
// regressions). These runs are long, so they live in impulse_long_tests (ctest label "long").
#include "support/scene_run.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <vector>

namespace impulse::test
{
namespace
{

struct StackRecord
{
    Real topDisplacement = 0.0;      ///< largest distance of the last body from its start
    Real largestDrift = 0.0;         ///< largest distance of any body from where it was at settleTime
    Real fastestAfterSettling = 0.0; ///< largest speed of any body after settleTime
    Real fastestAtEnd = 0.0;
};

StackRecord runStack(io::Scene& scene, Real dt, Real settleTime, Real duration = -1.0)
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

TEST(ReferenceScene9, StackOfTenCubesStandsStillForTwentySeconds)
{
    io::Scene scene = loadReferenceScene("box_stack_10");
    const StackRecord record = runStack(scene, 1e-3, 0.0);
    EXPECT_LT(record.topDisplacement, 1e-3);
    EXPECT_LT(record.fastestAtEnd, 1e-4);
}

TEST(ReferenceScene9, StackOfFiftyCubesStandsStillForTwentySeconds)
{
    io::Scene scene = loadReferenceScene("box_stack_50");
    // bodies at rest stay at rest: every speed below 1e-4 m/s in every step after 0.5 s
    const StackRecord record = runStack(scene, 1e-3, 0.5);
    EXPECT_LT(record.topDisplacement, 1e-3);
    EXPECT_LT(record.fastestAfterSettling, 1e-4);
}

TEST(ReferenceScene9, StackOfFiftyCubesStandsAtTenMillisecondSteps)
{
    io::Scene scene = loadReferenceScene("box_stack_50");
    const StackRecord record = runStack(scene, 1e-2, 0.5);
    EXPECT_LT(record.topDisplacement, 1e-3);
    EXPECT_LT(record.fastestAfterSettling, 1e-4);
}

TEST(ReferenceScene10, PyramidOfTwoHundredTenCubesStands)
{
    // bottom row of 20 with gaps of 0.01: every cube above the first row rests on two, and the
    // whole pyramid must stay within 5 mm of where it settled at 1 s
    io::Scene scene = loadReferenceScene("pyramid");
    ASSERT_EQ(scene.dynamicBodies.size(), 210u);
    const StackRecord record = runStack(scene, 1e-3, 1.0);
    EXPECT_LT(record.largestDrift, 5e-3);
}

TEST(ShockPropagation, WithoutItTheStackOfFiftyFallsWithinTwoSeconds)
{
    // What shock propagation buys: the same contact pass without the final frozen sweep leaves the
    // residual of ten two-way sweeps over fifty levels, and the stack does not stand. Push-out is
    // off too: it moves positions after the fact and would hide the velocities' failure (with it
    // on, the top still sinks 3 mm in the two seconds as push-out keeps undoing the overlaps).
    io::Scene scene = loadReferenceScene("box_stack_50");
    scene.options.shockPropagation = false;
    scene.options.pushOut = false;
    const StackRecord record = runStack(scene, 1e-3, 0.0, 2.0);
    EXPECT_GT(record.topDisplacement, 0.1);
}

TEST(Stacking, HeavyCubesOnLightOnesDoNotSink)
{
    // masses 1, 10, 100, 1, 1000 kg from the bottom up
    io::Scene scene = loadReferenceScene("heavy_on_light");
    const StackRecord record = runStack(scene, 1e-3, 0.5);
    EXPECT_LT(record.largestDrift, 1e-3);
}

TEST(Stacking, LintelAcrossUnequalStacksStands)
{
    // two cubes on one side, four half-height boxes on the other: breadth-first levels would put
    // the lintel below the taller stack's top box and deadlock; longest-path levels do not
    io::Scene scene = loadReferenceScene("lintel");
    const StackRecord record = runStack(scene, 1e-3, 0.0);
    EXPECT_LT(record.largestDrift, 1e-3);
}

TEST(Stacking, SeesawThrowsTheLightCubeUp)
{
    io::Scene scene = loadReferenceScene("seesaw");
    ASSERT_EQ(scene.dynamicBodies.size(), 3u);
    const BodyId light = scene.dynamicBodies[1];
    const BodyId heavy = scene.dynamicBodies[2];
    const Real lightStart = scene.world.state(light).position.z();
    Real lightHighest = lightStart;
    runScene(scene, 1e-3,
             [&](Real, const World& world) { lightHighest = std::max(lightHighest, world.state(light).position.z()); });
    // the heavy side goes down: the 20 kg cube ends on the ground beside the plank's low end
    EXPECT_LT(scene.world.state(heavy).position.z(), 0.25);
    EXPECT_GT(lightHighest - lightStart, 0.1);
}

} // namespace
} // namespace impulse::test
