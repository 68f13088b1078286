// SPDX-License-Identifier: MIT
// The same scene and options give bit-identical trajectories, run after run.
#include "support/scene_run.hpp"

#include <impulse/io/trajectory.hpp>
#include <impulse/mesh_shapes.hpp>

#include <gtest/gtest.h>

#include <cmath>
#include <sstream>
#include <stdexcept>
#include <string>

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

// Four heaps a metre apart, each of spheres, cubes, capsules and tori dropped onto one another: the
// heaps are separate islands, and within each the bodies collide, rest and stack.
World fourHeaps(std::vector<BodyId>& dynamic)
{
    World world;
    const MaterialId material = world.createMaterial({.restitution = 0.3, .friction = 0.5});
    world.createBody({.type = BodyType::Static, .shape = Plane{}, .material = material});
    const Mesh torus{MeshGeometry::build(torusMesh(0.12, 0.04, 24, 12))};
    const Shape shapes[] = {Sphere{0.1}, Box{Vec3(0.1, 0.08, 0.06)}, Capsule{0.05, 0.08}, torus};
    for (int heap = 0; heap < 4; ++heap)
    {
        const Vec3 centre(heap % 2 == 0 ? -0.5 : 0.5, heap < 2 ? -0.5 : 0.5, 0.0);
        for (int k = 0; k < 12; ++k)
        {
            // a loose column, each body a little off the axis and turned
            const Vec3 offset(0.03 * std::cos(1.7 * k + heap), 0.03 * std::sin(1.3 * k + heap), 0.15 + 0.22 * k);
            const Quat turn(Eigen::AngleAxisd(0.4 * k + heap, Vec3(1.0, 0.5 * k, 0.3).normalized()));
            dynamic.push_back(world.createBody({.shape = shapes[(k + heap) % 4],
                                                .material = material,
                                                .density = 500.0,
                                                .position = centre + offset,
                                                .orientation = turn}));
        }
    }
    return world;
}

std::string fourHeapsTrajectory(int threads, int& mostIslands)
{
    std::vector<BodyId> dynamic;
    World world = fourHeaps(dynamic);
    StepOptions options;
    options.threads = threads;
    std::ostringstream out;
    io::TrajectoryWriter writer(out);
    writer.writeHeader();
    mostIslands = 0;
    for (int step = 1; step <= 600; ++step)
    {
        world.step(options);
        EXPECT_EQ(world.lastStepStats().threads, threads);
        mostIslands = std::max(mostIslands, world.lastStepStats().islands);
        writer.writeSample(world.time(), world, dynamic);
    }
    return out.str();
}

TEST(Threads, OneTwoAndFourThreadsGiveByteIdenticalTrajectories)
{
    int islands = 0;
    const std::string one = fourHeapsTrajectory(1, islands);
    EXPECT_GE(islands, 4) << "the heaps should be solved as separate islands";
    for (const int threads : {2, 4})
    {
        int ignored = 0;
        EXPECT_TRUE(fourHeapsTrajectory(threads, ignored) == one)
            << "the trajectory at " << threads << " threads differs from the one at 1";
    }
}

// A stack of five cubes at x, and optionally a second, different one (heavier, tilted) 3 m away.
std::string firstStackTrajectory(bool withSecondStack, int& islands)
{
    World world;
    const MaterialId material = world.createMaterial({.restitution = 0.2, .friction = 0.6});
    world.createBody({.type = BodyType::Static, .shape = Plane{}, .material = material});
    std::vector<BodyId> first;
    for (int k = 0; k < 5; ++k)
    {
        first.push_back(world.createBody({.shape = Box{Vec3::Constant(0.1)},
                                          .material = material,
                                          .mass = 1.0,
                                          .position = Vec3(0.01 * k, 0, 0.1 + 0.205 * k),
                                          .orientation = Quat(Eigen::AngleAxisd(0.05 * k, Vec3::UnitZ()))}));
    }
    if (withSecondStack)
    {
        for (int k = 0; k < 5; ++k)
        {
            world.createBody({.shape = Box{Vec3::Constant(0.1)},
                              .material = material,
                              .mass = 3.0,
                              .position = Vec3(3.0 - 0.02 * k, 0, 0.12 + 0.21 * k),
                              .orientation = Quat(Eigen::AngleAxisd(0.1, Vec3::UnitX()))});
        }
    }
    std::ostringstream out;
    io::TrajectoryWriter writer(out);
    for (int step = 1; step <= 500; ++step)
    {
        world.step({});
        islands = std::max(islands, world.lastStepStats().islands);
        writer.writeSample(world.time(), world, first);
    }
    return out.str();
}

TEST(Islands, AStackMovesTheSameWithOrWithoutAnotherFarAway)
{
    int alone = 0;
    int together = 0;
    const std::string withoutSecond = firstStackTrajectory(false, alone);
    const std::string withSecond = firstStackTrajectory(true, together);
    EXPECT_EQ(alone, 1);
    EXPECT_EQ(together, 2);
    EXPECT_TRUE(withoutSecond == withSecond) << "a stack 3 m away changed the first stack's trajectory";
}

// Steps the world `steps` times with default options and returns its state hash.
std::uint64_t hashAfter(World& world, int steps)
{
    for (int step = 0; step < steps; ++step)
    {
        world.step({});
    }
    return world.stateHash();
}

TEST(Snapshot, ContinuesTheTrajectoryBitForBit)
{
    std::vector<BodyId> dynamic;
    World world = fourHeaps(dynamic);
    hashAfter(world, 300); // the heaps are falling onto one another and turning
    const WorldSnapshot middle = world.snapshot();
    const std::uint64_t straightOn = hashAfter(world, 200);

    world.restore(middle); // back in time, in the same world
    EXPECT_EQ(world.time(), middle.time);
    EXPECT_EQ(hashAfter(world, 200), straightOn);

    std::vector<BodyId> ignored;
    World fresh = fourHeaps(ignored); // a world built the same way, never stepped
    fresh.restore(middle);
    EXPECT_EQ(hashAfter(fresh, 200), straightOn);
}

TEST(Snapshot, ThatDoesNotFitIsRefusedAndChangesNothing)
{
    std::vector<BodyId> dynamic;
    World world = fourHeaps(dynamic);
    hashAfter(world, 50);
    const WorldSnapshot good = world.snapshot();
    const std::uint64_t before = world.stateHash();
    const auto refusal = [&](const WorldSnapshot& bad)
    {
        try
        {
            world.restore(bad);
        }
        catch (const std::invalid_argument& error)
        {
            return std::string(error.what());
        }
        return std::string("accepted");
    };
    const std::uint32_t last = dynamic.back().index;
    const std::string lastBody = "bodies/" + std::to_string(last) + "/";

    WorldSnapshot bad = good;
    bad.bodies.pop_back();
    EXPECT_EQ(refusal(bad), "bodies: the snapshot has 48 bodies, the world 49");

    bad = good;
    bad.bodies[0].position.z() = 0.1; // the ground plane
    EXPECT_EQ(refusal(bad), "bodies/0/position: a static body cannot move");

    bad = good;
    bad.bodies[last].orientation.coeffs() *= 1.001;
    EXPECT_EQ(refusal(bad), lastBody + "orientation: must be a finite unit quaternion");

    bad = good;
    bad.bodies[last].linearVelocity.x() = std::nan("");
    EXPECT_EQ(refusal(bad), lastBody + "velocity: must be finite");

    bad = good;
    bad.bodies[last].angularVelocity.x() += 1.0;
    EXPECT_EQ(refusal(bad), lastBody +
                                "angular_velocity: does not follow from the angular momentum and orientation (it "
                                "is derived from them)");

    EXPECT_EQ(world.stateHash(), before) << "a refused snapshot changed the world";
    EXPECT_EQ(world.time(), good.time);
}

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
