// SPDX-License-Identifier: MIT
// Reference scene 10: the pyramid of 210 cubes stands for ten seconds. At rest its contact pass
// starts every step from the last one's loads and stops after a sweep or two, so the ten seconds
// take some fifteen seconds: it runs with the other long oracles (ctest label "long").
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
