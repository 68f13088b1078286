// SPDX-License-Identifier: MIT
// Reference scene 14: nonconvex meshes dropped into a box settle into a pile without going into
// one another. Ten simulated seconds of hundreds of meshes: ctest label "pile", run on demand.
#include "support/penetration.hpp"
#include "support/scene_run.hpp"

#include <gtest/gtest.h>

#include <iostream>

namespace impulse::test
{
namespace
{

void expectPileSettles(const std::string& name)
{
    io::Scene scene = loadReferenceScene(name);
    Real peakKinetic = 0.0;
    Real deepestRelative = 0.0;
    Real deepest = 0.0;
    int step = 0;
    runScene(scene, -1.0,
             [&](Real t, const World& world)
             {
                 peakKinetic = std::max(peakKinetic, world.kineticEnergy());
                 if (++step % 50 == 0)
                 {
                     const Penetration p = deepestPenetration(world);
                     deepestRelative = std::max(deepestRelative, p.relative);
                     deepest = std::max(deepest, p.depth);
                     if (step % 1000 == 0)
                     {
                         std::cout << name << " t " << t << " s: kinetic " << world.kineticEnergy() << " J (peak "
                                   << peakKinetic << "), deepest so far " << deepest << " m ("
                                   << 100.0 * deepestRelative << " % of the smaller body)" << std::endl;
                     }
                 }
             });
    const Real finalKinetic = scene.world.kineticEnergy();
    std::cout << name << ": kinetic energy at the end " << finalKinetic << " J, peak " << peakKinetic
              << " J; deepest penetration " << deepest << " m, " << 100.0 * deepestRelative << " % of size"
              << std::endl;
    EXPECT_LT(finalKinetic, 0.01 * peakKinetic);
    EXPECT_LT(deepestRelative, 0.01);
}

TEST(ReferenceScene14, TwoHundredNonconvexBodiesSettleWithoutInterpenetrating)
{
    expectPileSettles("nonconvex_pile_200");
}

TEST(ReferenceScene14, AThousandNonconvexBodiesSettleWithoutInterpenetrating)
{
    expectPileSettles("nonconvex_pile_1000");
}

} // namespace
} // namespace impulse::test
