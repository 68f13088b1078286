// SPDX-License-Identifier: MIT
// Reference scenes 11 and 12 at ten thousand bodies: spheres and cubes fall into a box, and none
// leaves it or ends inside another. Five simulated seconds of ten thousand bodies take longer than
// CI's budget: ctest label "pile", run on demand (docs/performance.md). The thousand-body piles are
// in piles_test.cpp and nonconvex_pile_test.cpp.
#include "support/pile_oracles.hpp"

namespace impulse::test
{
namespace
{

TEST(ReferenceScene11, TenThousandSpheresStayInTheBoxWithoutOverlaps)
{
    expectPileOracleHolds("sphere_pile_10000");
}

TEST(ReferenceScene12, TenThousandCubesStayInTheBoxWithoutOverlaps)
{
    expectPileOracleHolds("box_pile_10000");
}

} // namespace
} // namespace impulse::test
