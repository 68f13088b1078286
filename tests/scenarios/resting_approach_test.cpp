// SPDX-License-Identifier: MIT
// The collision pass's resting approach (StepOptions::restingApproach): an elastic ball touching the
// ground and closing at a known speed, stepped once. Slower than the floor dt |g| it is resting
// contact, left to the contact pass; from the floor to twice it, its restitution fades in linearly;
// faster, it bounces exactly as it does with no floor.
#include <impulse/impulse.hpp>

#include <gtest/gtest.h>

#include <limits>
#include <stdexcept>
#include <string>

namespace impulse::test
{
namespace
{

constexpr Real kG = 9.81;
constexpr Real kDt = 1e-3;
constexpr Real kFloor = kDt * kG; // restingApproach 1
constexpr Real kRadius = 0.1;

struct OneStep
{
    Real speed;            // vertical velocity after the step
    int collisionImpulses; // applied by the collision pass
};

// One step of a ball resting on the ground at z = r and closing at `closing`.
OneStep stepOnce(Real closing, Real restitution, Real restingApproach)
{
    World world({.gravity = {0, 0, -kG}});
    const MaterialId material = world.createMaterial({.restitution = restitution, .friction = 0.5});
    world.createBody({.type = BodyType::Static, .shape = Plane{}, .material = material});
    const BodyId ball = world.createBody({.shape = Sphere{kRadius},
                                          .material = material,
                                          .mass = 1.0,
                                          .position = {0, 0, kRadius},
                                          .linearVelocity = {0, 0, -closing}});
    StepOptions options;
    options.dt = kDt;
    options.restingApproach = restingApproach;
    world.step(options);
    return {world.state(ball).linearVelocity.z(), world.lastStepStats().collisionImpulses};
}

Real speedAfterOneStep(Real closing, Real restitution, Real restingApproach)
{
    return stepOnce(closing, restitution, restingApproach).speed;
}

TEST(RestingApproach, ABallClosingSlowerThanTheFloorIsLeftToTheContactPassAndRestsAsItDoesWithout)
{
    const Real closing = 0.5 * kFloor;
    const OneStep with = stepOnce(closing, 1.0, 1.0);
    const OneStep without = stepOnce(closing, 1.0, 0.0);
    EXPECT_EQ(with.collisionImpulses, 0);
    EXPECT_GE(without.collisionImpulses, 1);
    // the elastic bounce it is spared is slower than the dt |g| the step's gravity takes away: the
    // ball ends the step at rest either way
    EXPECT_NEAR(with.speed, 0.0, 1e-9 * kFloor);
    EXPECT_NEAR(without.speed, 0.0, 1e-9 * kFloor);
}

TEST(RestingApproach, RestitutionFadesInLinearlyFromTheFloorToTwiceIt)
{
    // at 1.5 floors the elastic ball bounces as a ball of restitution 0.5 does with no floor
    const Real closing = 1.5 * kFloor;
    const Real faded = speedAfterOneStep(closing, 1.0, 1.0);
    EXPECT_GT(faded, 0.1 * closing);
    EXPECT_NEAR(faded, speedAfterOneStep(closing, 0.5, 0.0), 1e-9 * closing);
    // and a quarter of the way in, as one of restitution 0.25
    const Real early = 1.25 * kFloor;
    EXPECT_NEAR(speedAfterOneStep(early, 1.0, 1.0), speedAfterOneStep(early, 0.25, 0.0), 1e-9 * early);
}

TEST(RestingApproach, ApproachesFasterThanTwiceTheFloorBounceExactlyAsWithoutIt)
{
    for (const Real closing : {2.0 * kFloor, 3.0 * kFloor, 1.0, 10.0})
    {
        EXPECT_EQ(speedAfterOneStep(closing, 0.7, 1.0), speedAfterOneStep(closing, 0.7, 0.0)) << closing;
    }
}

TEST(RestingApproach, ANegativeOrNonFiniteFloorIsRefusedByName)
{
    World world({.gravity = {0, 0, -kG}});
    for (const Real bad : {-1.0, std::numeric_limits<Real>::infinity(), std::numeric_limits<Real>::quiet_NaN()})
    {
        StepOptions options;
        options.restingApproach = bad;
        try
        {
            world.step(options);
            ADD_FAILURE() << "accepted " << bad;
        }
        catch (const std::invalid_argument& error)
        {
            EXPECT_NE(std::string(error.what()).find("resting_approach"), std::string::npos) << error.what();
        }
    }
}

} // namespace
} // namespace impulse::test
