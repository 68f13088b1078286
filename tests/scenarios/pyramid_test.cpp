// SPDX-License-Identifier: MIT
// Reference scene 10: the pyramid of 210 cubes stands for ten seconds. Resting, every cube on two
// movable supports goes through the projected patch solve in each sweep, about 0.12 s of computing
// per step, so the ten seconds take some twenty minutes: this oracle runs with the piles (ctest
// label "pile"). The shorter twelve-row pyramids of stacking_test.cpp check the same rest in CI.
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

} // namespace
} // namespace impulse::test
