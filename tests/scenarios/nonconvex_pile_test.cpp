// SPDX-License-Identifier: MIT
// Reference scene 14 at a thousand meshes: nonconvex meshes dropped into a box settle into a pile
// without going into one another. Ten simulated seconds of a thousand meshes take about nine
// minutes on one core: ctest label "long", started beside the long run. The two-hundred-mesh pile is
// in piles_test.cpp.
#include "support/pile_oracles.hpp"

namespace impulse::test
{
namespace
{

TEST(ReferenceScene14, AThousandNonconvexBodiesSettleWithoutInterpenetrating)
{
    expectPileOracleHolds("nonconvex_pile_1000");
}

} // namespace
} // namespace impulse::test
