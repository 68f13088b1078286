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
    const PileFigures figures = expectPileOracleHolds("box_pile_1000");
    // Beyond the scene's oracle: no two cubes go deeper than a tenth of a percent of their size
    // (0.35 mm) even while the pile forms. Clipped box contacts are not material points, so the
    // contact layer captures a pair of cubes again after a tenth of a millimetre of relative
    // motion; with the margin of a moving pair instead, a face contact could appear unseen, and a
    // cube sat 3.3 mm deep in another (0.99 %) for thirty steps.
    EXPECT_LT(figures.deepestRelative, 1e-3)
        << "step " << figures.deepestStep << ", bodies " << figures.deepestFirst << " and " << figures.deepestSecond;
}

TEST(ReferenceScene14, TwoHundredNonconvexBodiesSettleWithoutInterpenetrating)
{
    expectPileOracleHolds("nonconvex_pile_200");
}

} // namespace
} // namespace impulse::test
