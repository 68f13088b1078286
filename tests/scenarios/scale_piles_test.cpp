// SPDX-License-Identifier: MIT
// Reference scenes 11 and 12 at N = 1000: spheres and cubes fall into a box, and none leaves it
// or ends inside another (label "long"; the N = 10000 runs are in scale_piles_10000_test.cpp).
#include "support/pile_oracles.hpp"

namespace impulse::test
{
namespace
{

TEST(ReferenceScene11, ThousandSpheresStayInTheBoxWithoutOverlaps)
{
    expectPileStaysInTheBoxWithoutOverlaps("sphere_pile_1000", 0.1);
}

TEST(ReferenceScene12, ThousandCubesStayInTheBoxWithoutOverlaps)
{
    expectPileStaysInTheBoxWithoutOverlaps("box_pile_1000", 0.1);
}

} // namespace
} // namespace impulse::test
