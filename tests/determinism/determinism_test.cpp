// SPDX-License-Identifier: MIT
// The same scene and options give bit-identical trajectories, run after run.
#include "support/scene_run.hpp"

#include <impulse/io/trajectory.hpp>

#include <gtest/gtest.h>

#include <sstream>

namespace impulse::test
{
namespace
{

std::string trajectoryBytes(const std::string& name, Real duration)
{
    io::Scene scene = loadReferenceScene(name);
    std::ostringstream out;
    io::TrajectoryWriter writer(out);
    writer.writeHeader();
    writer.writeSample(0.0, scene.world, scene.dynamicBodies);
    runScene(
        scene, -1.0, [&](Real t, const World& world) { writer.writeSample(t, world, scene.dynamicBodies); }, duration);
    return out.str();
}

class RepeatedRun : public ::testing::TestWithParam<const char*>
{
};

TEST_P(RepeatedRun, GivesByteIdenticalTrajectories)
{
    const std::string first = trajectoryBytes(GetParam(), 1.0);
    const std::string second = trajectoryBytes(GetParam(), 1.0);
    ASSERT_GT(first.size(), 1000u);
    EXPECT_TRUE(first == second) << "trajectories of " << GetParam() << " differ";
}

INSTANTIATE_TEST_SUITE_P(ReferenceScenes, RepeatedRun,
                         ::testing::Values("ball_drop_elastic", "spin_friction", "incline_slide", "newton_cradle"));

TEST(StateHash, ChangesWithTheStateAndNotWithoutIt)
{
    io::Scene a = loadReferenceScene("ball_drop_damped");
    io::Scene b = loadReferenceScene("ball_drop_damped");
    EXPECT_EQ(a.world.stateHash(), b.world.stateHash());
    a.world.step(a.options);
    EXPECT_NE(a.world.stateHash(), b.world.stateHash());
    b.world.step(b.options);
    EXPECT_EQ(a.world.stateHash(), b.world.stateHash());
}

} // namespace
} // namespace impulse::test
