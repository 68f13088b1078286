// SPDX-License-Identifier: MIT
// Sleeping islands (StepOptions::sleep): an island at rest leaves the step until something touches
// it, and then reacts as it would have awake.
#include "support/scene_run.hpp"

#include <impulse/world.hpp>

#include <gtest/gtest.h>

#include <algorithm>

namespace impulse::test
{
namespace
{

bool allAsleep(const io::Scene& scene)
{
    return std::all_of(scene.dynamicBodies.begin(), scene.dynamicBodies.end(),
                       [&](BodyId body) { return scene.world.isAsleep(body); });
}

/// A 2 kg ball thrown level at the pyramid's top cube (x = 0, z = 3.9, side 0.2) from 0.4 m away.
BodyId throwBall(io::Scene& scene)
{
    BodyDef ball;
    ball.shape = Sphere{0.1};
    ball.mass = 2.0;
    ball.position = Vec3(-0.5, 0.0, 3.95);
    ball.linearVelocity = Vec3(3.0, 0.0, 0.0);
    return scene.world.createBody(ball);
}

TEST(Sleeping, ARestingPyramidFallsAsleepAndStaysPutBitForBit)
{
    io::Scene scene = loadReferenceScene("pyramid");
    scene.options.sleep = true;
    // at rest from the start: it must sleep once every cube has rested sleepTime, not before
    const int before = static_cast<int>(scene.options.sleepTime / scene.options.dt) - 2;
    for (int k = 0; k < before; ++k)
    {
        scene.world.step(scene.options);
    }
    EXPECT_EQ(scene.world.lastStepStats().sleepingBodies, 0);
    for (int k = 0; k < 5; ++k)
    {
        scene.world.step(scene.options);
    }
    ASSERT_TRUE(allAsleep(scene));
    EXPECT_EQ(scene.world.lastStepStats().sleepingBodies, 210);
    const WorldSnapshot asleep = scene.world.snapshot();
    for (int k = 0; k < 200; ++k)
    {
        scene.world.step(scene.options);
    }
    // out of every pass: no pair, no motion, not even round-off
    EXPECT_EQ(scene.world.lastStepStats().candidatePairs, 0);
    for (const BodyId body : scene.dynamicBodies)
    {
        const BodyState now = scene.world.state(body);
        EXPECT_EQ(now.position, asleep.bodies[body.index].position);
        EXPECT_EQ(now.orientation.coeffs(), asleep.bodies[body.index].orientation.coeffs());
        EXPECT_TRUE(now.linearVelocity.isZero(0.0));
    }
}

TEST(Sleeping, ABallThrownAtASleepingPyramidMovesItAsItMovesTheAwakeOne)
{
    io::Scene awake = loadReferenceScene("pyramid");
    io::Scene sleeping = loadReferenceScene("pyramid");
    sleeping.options.sleep = true;
    const int settle = static_cast<int>(1.5 * sleeping.options.sleepTime / sleeping.options.dt);
    for (int k = 0; k < settle; ++k)
    {
        awake.world.step(awake.options);
        sleeping.world.step(sleeping.options);
    }
    ASSERT_TRUE(allAsleep(sleeping));
    const BodyId ballAwake = throwBall(awake);
    const BodyId ballSleeping = throwBall(sleeping);
    const BodyId top = sleeping.dynamicBodies.back();
    const Vec3 topStart = sleeping.world.state(top).position;
    // 0.3 s: the ball strikes the top cube at 0.1 s and knocks it off its two supports
    Real ballGap = 0.0;
    Real bodyGap = 0.0;
    for (int k = 0; k < 300; ++k)
    {
        awake.world.step(awake.options);
        sleeping.world.step(sleeping.options);
        ballGap = std::max(
            ballGap, (awake.world.state(ballAwake).position - sleeping.world.state(ballSleeping).position).norm());
        for (const BodyId body : sleeping.dynamicBodies)
        {
            bodyGap =
                std::max(bodyGap, (awake.world.state(body).position - sleeping.world.state(body).position).norm());
        }
    }
    // the strike woke the pyramid, and it reacted: the top cube was knocked at least 0.2 m
    EXPECT_FALSE(sleeping.world.isAsleep(top));
    EXPECT_GT((sleeping.world.state(top).position - topStart).norm(), 0.2);
    // and as the awake pyramid did: the woken pyramid starts from the loads it fell asleep with, which
    // differ from the awake one's only by the contact solve's resolution. The strike and the slide
    // that follows amplify that difference (the runs end 0.03 to 0.3 mm apart as the solver's details
    // change); started from no loads instead, as a wake that lost its contacts would, they end some
    // 3 cm apart. A millimetre tells the two apart with room on both sides.
    EXPECT_LT(ballGap, 1e-3);
    EXPECT_LT(bodyGap, 1e-3);
}

TEST(Sleeping, AnImpulseWakesABodyAndItsIslandButNotAnother)
{
    World world;
    const MaterialId material = world.createMaterial({.restitution = 0.0, .friction = 0.5});
    BodyDef ground;
    ground.type = BodyType::Static;
    ground.shape = Plane{};
    ground.material = material;
    world.createBody(ground);
    BodyDef box;
    box.material = material;
    box.shape = Box{Vec3(0.1, 0.1, 0.1)};
    box.mass = 1.0;
    box.position = Vec3(0.0, 0.0, 0.1);
    const BodyId lower = world.createBody(box);
    box.position = Vec3(0.0, 0.0, 0.3);
    const BodyId upper = world.createBody(box);
    box.position = Vec3(2.0, 0.0, 0.1);
    const BodyId apart = world.createBody(box);
    StepOptions options;
    options.sleep = true;
    for (int k = 0; k < 600; ++k)
    {
        world.step(options);
    }
    ASSERT_TRUE(world.isAsleep(lower) && world.isAsleep(upper) && world.isAsleep(apart));
    world.applyImpulse(upper, Vec3(0.0, 0.0, 0.5));
    EXPECT_FALSE(world.isAsleep(upper));
    EXPECT_FALSE(world.isAsleep(lower)); // fell asleep with it
    EXPECT_TRUE(world.isAsleep(apart));
    world.step(options);
    // 0.5 m/s up, less one step of gravity
    EXPECT_NEAR(world.state(upper).linearVelocity.z(), 0.5 - 9.81 * options.dt, 1e-9);
}

TEST(Sleeping, ABallTossedUpDoesNotSleepAtTheTopOfItsFlight)
{
    // at the apex its speed is below sleepSpeed for only about 2 sleepSpeed / g = 2 ms
    World world;
    BodyDef ball;
    ball.material = world.createMaterial({});
    ball.shape = Sphere{0.1};
    ball.mass = 1.0;
    ball.position = Vec3(0.0, 0.0, 1.0);
    ball.linearVelocity = Vec3(0.0, 0.0, 2.0);
    const BodyId id = world.createBody(ball);
    StepOptions options;
    options.sleep = true;
    for (int k = 0; k < 400; ++k)
    {
        world.step(options);
        ASSERT_FALSE(world.isAsleep(id)) << "at step " << k;
    }
}

TEST(Sleeping, OffByDefaultAndTurningItOffWakesEveryone)
{
    World world;
    BodyDef box;
    box.material = world.createMaterial({});
    box.shape = Box{Vec3(0.1, 0.1, 0.1)};
    box.mass = 1.0;
    const BodyId id = world.createBody(box);
    StepOptions options;
    EXPECT_FALSE(options.sleep);
    options.sleep = true;
    options.sleepSpeed = 1.0;
    options.sleepTime = 0.01; // a slow falling box sleeps
    for (int k = 0; k < 20; ++k)
    {
        world.step(options);
    }
    ASSERT_TRUE(world.isAsleep(id));
    const Real height = world.state(id).position.z();
    options.sleep = false;
    world.step(options);
    EXPECT_FALSE(world.isAsleep(id));
    EXPECT_LT(world.state(id).position.z(), height); // gravity again
}

TEST(Sleeping, RefusesANegativeOrNonFiniteSpeedOrTime)
{
    World world;
    StepOptions options;
    options.sleepSpeed = -1.0;
    EXPECT_THROW(world.step(options), std::invalid_argument);
    options.sleepSpeed = 0.01;
    options.sleepTime = std::numeric_limits<Real>::quiet_NaN();
    EXPECT_THROW(world.step(options), std::invalid_argument);
}

} // namespace
} // namespace impulse::test
