// SPDX-License-Identifier: MIT
// Reference scene 10: the pyramid of 210 cubes stands for ten seconds. At rest its contact pass
// starts every step from the last one's loads and stops after a sweep or two, so the ten seconds
// take some fifteen seconds: it runs with the other long oracles (ctest label "long"). At rest the
// collision pass has nothing to do: what its contacts still close at is resting contact.
#include "support/stack_run.hpp"

#include <gtest/gtest.h>

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

StackRecord restingPyramid(Real restingApproach)
{
    io::Scene scene = loadReferenceScene("pyramid");
    scene.options.restingApproach = restingApproach;
    return runStack(scene, 1e-3, 0.5, 1.0);
}

TEST(ReferenceScene10, AtRestThePyramidGivesTheCollisionPassNothingToDo)
{
    // Its contacts close at what the contact pass leaves of dt |g|, below the resting approach: the
    // collision pass applies no impulse, where without the floor it chases that remainder, and the
    // pyramid stands as still either way.
    const StackRecord with = restingPyramid(1.0);
    const StackRecord without = restingPyramid(0.0);
    EXPECT_EQ(with.collisionImpulsesAfterSettling, 0);
    EXPECT_GT(without.collisionImpulsesAfterSettling, 0);
    EXPECT_LT(with.largestDrift, 1e-7); // 8e-9 m over the half second
    EXPECT_LT(without.largestDrift, 1e-7);
}

} // namespace
} // namespace impulse::test
