// SPDX-License-Identifier: MIT
// The contact layer against the exact narrow phase over the reference scenes: in verification mode
// every use of a cached point also detects the pair exactly, and a point missed or a separation off by
// more than the pair's motion since capture allows makes the step throw (src/contact/contact_cache.hpp).
// Each scene runs long enough for its contacts to form, rest and, where they do, tip, slide or pile
// up; the piles for their first, busiest, steps.
#include "support/scene_run.hpp"

#include <gtest/gtest.h>

#include <stdexcept>
#include <string>

namespace impulse::test
{
namespace
{

struct VerifiedRun
{
    const char* scene;
    int steps;
};

class ContactCacheVerification : public ::testing::TestWithParam<VerifiedRun>
{
};

TEST_P(ContactCacheVerification, AgreesWithTheExactNarrowPhaseAtEveryUse)
{
    io::Scene scene = loadReferenceScene(GetParam().scene);
    scene.options.verifyContacts = true;
    int step = 0;
    try
    {
        for (; step < GetParam().steps; ++step)
        {
            scene.world.step(scene.options);
        }
    }
    catch (const std::logic_error& error)
    {
        FAIL() << GetParam().scene << ", step " << step << ": " << error.what();
    }
}

INSTANTIATE_TEST_SUITE_P(ReferenceScenes, ContactCacheVerification,
                         ::testing::Values(VerifiedRun{"ball_drop_damped", 2500}, VerifiedRun{"spin_friction", 1000},
                                           VerifiedRun{"incline_stick", 1000}, VerifiedRun{"incline_slide", 2000},
                                           VerifiedRun{"incline_rest_elastic", 1000},
                                           VerifiedRun{"newton_cradle", 2000}, VerifiedRun{"box_stack_10", 1000},
                                           VerifiedRun{"box_stack_50", 1000}, VerifiedRun{"pyramid", 1000},
                                           VerifiedRun{"heavy_on_light", 1000}, VerifiedRun{"lintel", 1000},
                                           VerifiedRun{"seesaw", 2000}, VerifiedRun{"overhang_topples", 2000},
                                           VerifiedRun{"harmonic_stack", 1000}, VerifiedRun{"leaning_tower_4", 2000},
                                           VerifiedRun{"incline_tower_20", 1500}, VerifiedRun{"domino_falls", 2000},
                                           VerifiedRun{"domino_rocks_back", 2000}, VerifiedRun{"ring_on_peg", 3000},
                                           VerifiedRun{"tori_stack", 1000}, VerifiedRun{"sphere_pile_1000", 800},
                                           VerifiedRun{"box_pile_1000", 800}, VerifiedRun{"nonconvex_pile_200", 600}),
                         [](const ::testing::TestParamInfo<VerifiedRun>& run) { return std::string(run.param.scene); });

// A mesh pile stepped on another trajectory (six collision sweeps instead of five): there an edge
// running on under a curved surface from a vertex just inside met the verification, 0.16 mm deeper
// than the vertex that stood for it, when the narrow phase sampled only whole passages.
TEST(ContactCacheVerificationOffTheRecordedPath, ANonconvexPileAtSixCollisionSweeps)
{
    io::Scene scene = loadReferenceScene("nonconvex_pile_200");
    scene.options.verifyContacts = true;
    scene.options.collisionIterations = 6;
    for (int step = 0; step < 600; ++step)
    {
        try
        {
            scene.world.step(scene.options);
        }
        catch (const std::logic_error& error)
        {
            FAIL() << "step " << step << ": " << error.what();
        }
    }
}

} // namespace
} // namespace impulse::test
