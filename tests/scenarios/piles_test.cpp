// SPDX-License-Identifier: MIT
// The reference piles that fit CI's budget, each one to four minutes on one core: scenes 11 and 12
// at a thousand bodies (spheres and cubes fall into a box, and none leaves it or ends inside
// another) and scene 14 at two hundred meshes (they settle without going into one another). Label
// "long": the sanitizer build leaves them out.
#include "support/pile_oracles.hpp"

namespace impulse::test
{
namespace
{

TEST(ReferenceScene11, ThousandSpheresStayInTheBoxWithoutOverlaps)
{
    expectPileOracleHolds("sphere_pile_1000");
}

TEST(ReferenceScene12, ThousandCubesStayInTheBoxWithoutOverlaps)
{
    expectPileOracleHolds("box_pile_1000");
}

TEST(ReferenceScene14, TwoHundredNonconvexBodiesSettleWithoutInterpenetrating)
{
    expectPileOracleHolds("nonconvex_pile_200");
}

} // namespace
} // namespace impulse::test
