// SPDX-License-Identifier: MIT
// Reference scenes 11 and 12 at N = 10000 (label "pile", run on demand: see docs/performance.md).
#include "support/pile_oracles.hpp"

namespace impulse::test
{
namespace
{

TEST(ReferenceScene11, TenThousandSpheresStayInTheBoxWithoutOverlaps)
{
    expectPileStaysInTheBoxWithoutOverlaps("sphere_pile_10000", 0.1);
}

TEST(ReferenceScene12, TenThousandCubesStayInTheBoxWithoutOverlaps)
{
    expectPileStaysInTheBoxWithoutOverlaps("box_pile_10000", 0.1);
}

} // namespace
} // namespace impulse::test
