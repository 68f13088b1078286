// SPDX-License-Identifier: MIT
// Push-out (the last stage of the step): overlaps deeper than the allowance heal at no more than the
// push-out speed, by moving positions only, from the ground up.
#include "support/penetration.hpp"

#include <impulse/mesh_shapes.hpp>
#include <impulse/world.hpp>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

namespace impulse
{
namespace
{

constexpr Real kRadius = 0.1;

StepOptions millisecondSteps()
{
    StepOptions options;
    options.dt = 1e-3;
    return options;
}

// a ball at rest sunk `depth` into the ground, without gravity: nothing but push-out can move it
struct SunkBall
{
    World world{WorldDef{.gravity = Vec3::Zero()}};
    BodyId ball;

    explicit SunkBall(Real depth)
    {
        const MaterialId material = world.createMaterial({.restitution = 0.5, .friction = 0.5});
        world.createBody({.type = BodyType::Static, .shape = Plane{}, .material = material});
        ball = world.createBody({.shape = Sphere{kRadius},
                                 .material = material,
                                 .mass = 1.0,
                                 .position = Vec3(0.3, -0.2, kRadius - depth)});
    }
    Real height() const { return world.state(ball).position.z(); }
};

TEST(PushOut, ASunkBallRisesAtThePushOutSpeedAndKeepsItsVelocity)
{
    SunkBall scene(5e-3);
    StepOptions options = millisecondSteps();
    options.pushOutSpeed = 1.0; // 1 mm per step
    for (int step = 1; step <= 4; ++step)
    {
        scene.world.step(options);
        EXPECT_NEAR(scene.height(), kRadius - 5e-3 + 1e-3 * step, 1e-12) << "after step " << step;
        EXPECT_EQ(scene.world.state(scene.ball).linearVelocity, Vec3::Zero()) << "positions only";
        EXPECT_EQ(scene.world.state(scene.ball).angularVelocity, Vec3::Zero());
    }
    for (int step = 5; step <= 20; ++step)
    {
        scene.world.step(options);
    }
    EXPECT_NEAR(scene.height(), kRadius, 1e-12) << "out, and no further";
    EXPECT_DOUBLE_EQ(scene.world.state(scene.ball).position.x(), 0.3) << "straight up the plane's normal";
    EXPECT_DOUBLE_EQ(scene.world.state(scene.ball).position.y(), -0.2);
    EXPECT_EQ(scene.world.kineticEnergy(), 0.0);
}

TEST(PushOut, WithoutItTheOverlapStays)
{
    SunkBall scene(5e-3);
    StepOptions options = millisecondSteps();
    options.pushOut = false;
    for (int step = 0; step < 20; ++step)
    {
        scene.world.step(options);
    }
    EXPECT_DOUBLE_EQ(scene.height(), kRadius - 5e-3) << "the passes remove approach, never a resting overlap";
}

TEST(PushOut, AnOverlapWithinTheAllowanceIsLeftAlone)
{
    const StepOptions options = millisecondSteps();
    SunkBall within(0.5 * options.pushOutAllowance);
    SunkBall beyond(2.0 * options.pushOutAllowance);
    for (int step = 0; step < 5; ++step)
    {
        within.world.step(options);
        beyond.world.step(options);
    }
    EXPECT_DOUBLE_EQ(within.height(), kRadius - 0.5 * options.pushOutAllowance);
    EXPECT_NEAR(beyond.height(), kRadius, 1e-12) << "once beyond the allowance, pushed all the way out";
}

TEST(PushOut, TwoOverlappingBallsPartInProportionToInverseMassAboutTheirCentreOfMass)
{
    World world(WorldDef{.gravity = Vec3::Zero()});
    const MaterialId material = world.createMaterial({.restitution = 0.5, .friction = 0.5});
    const Vec3 axis = Vec3(1.0, 2.0, 2.0) / 3.0;
    const Real overlap = 6e-3;
    const Vec3 start = Vec3(1.0, 1.0, 1.0);
    const BodyId light =
        world.createBody({.shape = Sphere{kRadius}, .material = material, .mass = 1.0, .position = start});
    const BodyId heavy = world.createBody({.shape = Sphere{kRadius},
                                           .material = material,
                                           .mass = 3.0,
                                           .position = start + (2.0 * kRadius - overlap) * axis});
    const auto centreOfMass = [&]() -> Vec3
    { return (1.0 * world.state(light).position + 3.0 * world.state(heavy).position) / 4.0; };
    const Vec3 centre = centreOfMass();
    for (int step = 0; step < 20; ++step)
    {
        world.step(millisecondSteps());
    }
    const Vec3 lightMoved = world.state(light).position - start;
    EXPECT_NEAR((world.state(heavy).position - world.state(light).position).norm(), 2.0 * kRadius, 1e-12);
    EXPECT_LT((centreOfMass() - centre).norm(), 1e-12) << "no external push: the centre of mass stays";
    EXPECT_NEAR(lightMoved.dot(-axis), 0.75 * overlap, 1e-12) << "the light ball takes three quarters";
    EXPECT_LT((lightMoved + lightMoved.norm() * axis).norm(), 1e-12) << "along the line of centres";
    EXPECT_EQ(world.kineticEnergy(), 0.0);
}

TEST(PushOut, ARowOfOverlappingBallsIsPartedInTwoStepsAboutItsCentreOfMass)
{
    // eight balls of one level in a row, each 2 mm into the next, without gravity: the two sweeps
    // up the levels leave most of a chain's overlap (each push shoves a ball back into the last
    // one); the two-way relaxation that follows them clears it in two steps, a chain's Gauss-Seidel
    // shrinking what is left by about cos^2(pi / 8) = 0.85 per sweep
    World world(WorldDef{.gravity = Vec3::Zero()});
    const MaterialId material = world.createMaterial({.restitution = 0.5, .friction = 0.5});
    constexpr int kBalls = 8;
    constexpr Real kOverlap = 2e-3;
    std::vector<BodyId> balls;
    std::vector<Vec3> starts;
    for (int k = 0; k < kBalls; ++k)
    {
        starts.push_back(Vec3(k * (2.0 * kRadius - kOverlap), 0.0, 1.0));
        balls.push_back(world.createBody(
            {.shape = Sphere{kRadius}, .material = material, .mass = 1.0 + 0.5 * k, .position = starts.back()}));
    }
    const auto centreOfMass = [&]() -> Vec3
    {
        Vec3 weighted = Vec3::Zero();
        Real mass = 0.0;
        for (int k = 0; k < kBalls; ++k)
        {
            weighted += (1.0 + 0.5 * k) * world.state(balls[static_cast<std::size_t>(k)]).position;
            mass += 1.0 + 0.5 * k;
        }
        return weighted / mass;
    };
    const Vec3 centre = centreOfMass();
    const StepOptions options = millisecondSteps();
    for (int step = 0; step < 2; ++step)
    {
        world.step(options);
    }
    EXPECT_LT(test::deepestPenetration(world).depth, options.pushOutAllowance);
    EXPECT_LT((centreOfMass() - centre).norm(), 1e-12) << "every push is shared about the pair's centre of mass";
    for (int k = 0; k < kBalls; ++k)
    {
        const Vec3 moved =
            world.state(balls[static_cast<std::size_t>(k)]).position - starts[static_cast<std::size_t>(k)];
        EXPECT_LE(moved.norm(), 2.0 * options.pushOutSpeed * options.dt * (1.0 + 1e-12)) << "ball " << k;
        EXPECT_NEAR(moved.y(), 0.0, 1e-15) << "along the row only";
        EXPECT_NEAR(moved.z(), 0.0, 1e-15);
    }
    EXPECT_EQ(world.kineticEnergy(), 0.0) << "positions only";
}

// A ring (torus, major radius R, tube radius r) tilted by alpha about x over a round peg of radius
// rho, centred on it, without gravity: along y the hole spans R cos(alpha) - r either side of the
// axis, less than rho, so the ring overlaps the peg at y = +rho and y = -rho by the same depth.
// The normals there are opposite: any translation deepens one side by what it clears on the other.
// Only turning the ring toward level clears both.
TEST(PushOut, AWedgedRingIsTurnedFreeWhereNoTranslationCould)
{
    World world(WorldDef{.gravity = Vec3::Zero()});
    const MaterialId material = world.createMaterial({.restitution = 0.3, .friction = 0.5});
    constexpr Real kMajor = 0.1;
    constexpr Real kMinor = 0.02;
    constexpr Real kPegRadius = 0.075;
    const Real tilt = std::acos((kPegRadius + kMinor - 1e-3) / kMajor); // 1 mm into either side
    world.createBody({.type = BodyType::Static,
                      .shape = Capsule{kPegRadius, 0.3}, // upright
                      .material = material,
                      .position = Vec3(0.0, 0.0, 0.3)});
    const Mesh ring{MeshGeometry::build(torusMesh(kMajor, kMinor, 64, 24))};
    const Vec3 centre(0.0, 0.0, 0.4);
    const BodyId body = world.createBody({.shape = ring,
                                          .material = material,
                                          .density = 1000.0,
                                          .position = centre,
                                          .orientation = Quat(Eigen::AngleAxisd(tilt, Vec3::UnitX()))});
    // the two sides hold the ring about equally deep, so no translation clears the sum of the two
    std::vector<ContactPoint> points;
    NarrowPhaseScratch scratch;
    collideShapes(ring, Pose::from(centre, world.state(body).orientation), world.shape({0}),
                  Pose::from(Vec3(0.0, 0.0, 0.3), Quat::Identity()), 0.0, points, scratch);
    Real deepestTowardPlusY = 0.0;
    Real deepestTowardMinusY = 0.0;
    for (const ContactPoint& point : points)
    {
        Real& deepest = point.normal.y() > 0.0 ? deepestTowardPlusY : deepestTowardMinusY;
        deepest = std::max(deepest, -point.phi);
    }
    ASSERT_GT(deepestTowardPlusY, 0.5e-3);
    ASSERT_GT(deepestTowardMinusY, 0.5e-3);

    const StepOptions options = millisecondSteps();
    for (int step = 0; step < 10; ++step)
    {
        world.step(options);
    }
    const BodyState state = world.state(body);
    EXPECT_LT(test::deepestPenetration(world).depth, options.pushOutAllowance);
    // leveller by at least what clearing 1 mm per side takes: d(R cos a)/da = -R sin a
    const Real turned = tilt - state.orientation.angularDistance(Quat::Identity());
    EXPECT_GT(turned, 0.5 * 1e-3 / (kMajor * std::sin(tilt)));
    EXPECT_LT(turned, 4.0 * 1e-3 / (kMajor * std::sin(tilt)));
    EXPECT_LT((state.position - centre).norm(), 1e-3) << "turned about where it was, not thrown aside";
    EXPECT_EQ(state.linearVelocity, Vec3::Zero()) << "positions only";
    EXPECT_EQ(state.angularMomentum, Vec3::Zero());
}

TEST(PushOut, ASunkOverlappingStackIsPushedOutFromTheGroundUpWithoutBeingLaunched)
{
    // three cubes under gravity, the lowest 3 mm into the ground and each 2 mm into the one below
    World world;
    const MaterialId material = world.createMaterial({.restitution = 0.3, .friction = 0.6});
    world.createBody({.type = BodyType::Static, .shape = Plane{}, .material = material});
    const Real half = 0.1;
    std::vector<BodyId> cubes;
    for (int k = 0; k < 3; ++k)
    {
        cubes.push_back(world.createBody({.shape = Box{Vec3::Constant(half)},
                                          .material = material,
                                          .mass = 1.0,
                                          .position = Vec3(0.0, 0.0, half - 3e-3 + k * (2.0 * half - 2e-3))}));
    }
    ASSERT_GT(test::deepestPenetration(world).depth, 2.9e-3);
    const StepOptions options = millisecondSteps();
    Real fastest = 0.0;
    for (int step = 0; step < 100; ++step)
    {
        world.step(options);
        for (const BodyId cube : cubes)
        {
            fastest = std::max(fastest, world.state(cube).linearVelocity.norm());
        }
    }
    EXPECT_LT(test::deepestPenetration(world).depth, options.pushOutAllowance);
    // gravity's approach within one step, removed by the contact pass: nothing from push-out
    EXPECT_LT(fastest, 2.0 * 9.81 * options.dt);
    for (int k = 0; k < 3; ++k)
    {
        const BodyState state = world.state(cubes[static_cast<std::size_t>(k)]);
        EXPECT_NEAR(state.position.z(), half + 2.0 * half * k, 2.0 * options.pushOutAllowance) << "cube " << k;
        EXPECT_NEAR(state.position.x(), 0.0, 1e-9) << "cube " << k;
        EXPECT_NEAR(state.orientation.angularDistance(Quat::Identity()), 0.0, 1e-9) << "cube " << k;
    }
}

} // namespace
} // namespace impulse
