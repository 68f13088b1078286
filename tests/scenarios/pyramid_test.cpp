// SPDX-License-Identifier: MIT
// Reference scene 10: the pyramid of 210 cubes stands for ten seconds. At rest its contact pass
// starts every step from the last one's loads and stops after a sweep or two, so the ten seconds
// take some fifteen seconds: it runs with the other long oracles (ctest label "long"). At rest the
// collision pass has nothing to do: what its contacts still close at is resting contact.
#include "support/stack_run.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <vector>

namespace impulse::test
{
namespace
{

TEST(ReferenceScene10, PyramidOfTwoHundredTenCubesStands)
{
    // bottom row of 20 with gaps of 0.01: every cube above the first row rests on two, and the
    // whole pyramid must stay within 5 mm of where it settled at 1 s
    io::Scene scene = loadReferenceScene("pyramid");
    ASSERT_EQ(scene.dynamicBodies.size(), 210u);
    const StackRecord record = runStack(scene, 1e-3, 1.0);
    EXPECT_LT(record.largestDrift, 5e-3);
}

struct RestingSteps
{
    long collisionImpulses = 0; ///< over steps 500-1000
    Real largestMove = 0.0;     ///< of any cube's centre over those steps, m
};

RestingSteps restingPyramid(Real restingApproach)
{
    io::Scene scene = loadReferenceScene("pyramid");
    scene.options.restingApproach = restingApproach;
    std::vector<Vec3> settled;
    RestingSteps record;
    for (int step = 1; step <= 1000; ++step)
    {
        scene.world.step(scene.options);
        if (step == 500)
        {
            for (const BodyId body : scene.dynamicBodies)
            {
                settled.push_back(scene.world.state(body).position);
            }
        }
        else if (step > 500)
        {
            record.collisionImpulses += scene.world.lastStepStats().collisionImpulses;
        }
    }
    for (std::size_t i = 0; i < settled.size(); ++i)
    {
        record.largestMove =
            std::max(record.largestMove, (scene.world.state(scene.dynamicBodies[i]).position - settled[i]).norm());
    }
    return record;
}

TEST(ReferenceScene10, AtRestThePyramidGivesTheCollisionPassNothingToDo)
{
    // Its contacts close at what the contact pass leaves of dt |g|, below the resting approach: the
    // collision pass applies no impulse, where without the floor it chases that remainder, and the
    // pyramid stands as still either way.
    const RestingSteps with = restingPyramid(1.0);
    const RestingSteps without = restingPyramid(0.0);
    EXPECT_EQ(with.collisionImpulses, 0);
    EXPECT_GT(without.collisionImpulses, 0);
    EXPECT_LT(with.largestMove, 1e-7); // 8e-9 m over the half second
    EXPECT_LT(without.largestMove, 1e-7);
}

} // namespace
} // namespace impulse::test
