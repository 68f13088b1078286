// SPDX-License-Identifier: MIT
// Reference scene 14: nonconvex meshes dropped into a box settle into a pile without going into
// one another. Ten simulated seconds of hundreds of meshes: ctest label "pile", run on demand.
#include "support/pile_oracles.hpp"

namespace impulse::test
{
namespace
{

TEST(ReferenceScene14, TwoHundredNonconvexBodiesSettleWithoutInterpenetrating)
{
    expectPileOracleHolds("nonconvex_pile_200");
}

TEST(ReferenceScene14, AThousandNonconvexBodiesSettleWithoutInterpenetrating)
{
    expectPileOracleHolds("nonconvex_pile_1000");
}

} // namespace
} // namespace impulse::test
