// SPDX-License-Identifier: MIT
// A centre of mass off the shape's centroid (BodyDef::centerOfMass) is the point the body turns
// about, and the shape is where contact pushes: a ball weighted below its centre rocks on the ground
// as a pendulum of the rolling-contact frequency, weighted above it rolls over, and a box stands
// exactly while its centre of mass is over its base.
#include "support/scene_run.hpp"
#include "support/tilt.hpp"

#include <impulse/world.hpp>

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <variant>
#include <vector>

namespace impulse::test
{
namespace
{

constexpr Real kG = 9.81;
constexpr Real kDegree = std::numbers::pi / 180.0;

struct Ground
{
    World world;
    MaterialId material;
};

// A world with gravity -z and the plane z = 0; restitution 0, friction mu.
Ground groundWorld(Real mu)
{
    Ground g{World(WorldDef{.gravity = Vec3(0.0, 0.0, -kG)}), {}};
    g.material = g.world.createMaterial({.restitution = 0.0, .friction = mu});
    g.world.createBody({.type = BodyType::Static, .shape = Plane{Vec3::UnitZ(), 0.0}, .material = g.material});
    return g;
}

// A body of shape `shape` (1 kg) whose shape's frame is at `shapeOrigin`, turned by `orientation`, at
// rest, its centre of mass at `centerOfMass` in the shape's frame.
BodyId place(Ground& g, const Shape& shape, const Vec3& shapeOrigin, const Quat& orientation, const Vec3& centerOfMass)
{
    return g.world.createBody({.shape = shape,
                               .material = g.material,
                               .mass = 1.0,
                               .position = shapeOrigin + orientation * centerOfMass,
                               .orientation = orientation,
                               .centerOfMass = centerOfMass});
}

// Times at which the tilt about y crosses zero going up, over `seconds` of the scene's steps.
std::vector<Real> upwardCrossings(io::Scene& scene, BodyId body, Real seconds)
{
    std::vector<Real> crossings;
    World& world = scene.world;
    const Real dt = scene.options.dt;
    Real before = tiltAboutY(world.state(body).orientation);
    const int steps = static_cast<int>(std::lround(seconds / dt));
    for (int k = 0; k < steps; ++k)
    {
        world.step(scene.options);
        const Real after = tiltAboutY(world.state(body).orientation);
        if (before < 0.0 && after >= 0.0)
        {
            crossings.push_back(world.time() - dt * after / (after - before));
        }
        before = after;
    }
    return crossings;
}

TEST(CenterOfMass, ABallWeightedBelowItsCentreRocksAtTheRollingPendulumFrequency)
{
    // Rolling without slipping, a ball of radius r whose centre of mass sits d below its centre turns
    // about its contact point, r - d below the centre of mass at the bottom of the swing: small
    // rocking has w^2 = m g d / (I + m (r - d)^2). In roly_poly w = 5.75 rad/s, a period of 1.09 s;
    // at 3 degrees the amplitude lengthens it by about 1e-4, and the simulation by 3.7e-4.
    io::Scene scene = loadReferenceScene("roly_poly");
    const BodyId ball = scene.dynamicBodies.at(0);
    const Real r = std::get<Sphere>(scene.world.shape(ball)).radius;
    const Real d = -scene.world.centerOfMass(ball).z();
    ASSERT_EQ(r, 0.1);
    ASSERT_EQ(d, 0.03);
    const Real inertia = scene.world.principalInertia(ball).y() / scene.world.mass(ball);
    EXPECT_DOUBLE_EQ(inertia, 0.4 * r * r); // the shape's own, about the given centre of mass
    const Real omega = std::sqrt(kG * d / (inertia + (r - d) * (r - d)));
    const Real expected = 2.0 * std::numbers::pi / omega;

    const std::vector<Real> crossings = upwardCrossings(scene, ball, 5.0);
    ASSERT_GE(crossings.size(), 4U);
    const Real period = (crossings.back() - crossings.front()) / static_cast<Real>(crossings.size() - 1);
    // a ball that turned about its centroid, or a shape placed at the centre of mass, would not rock
    EXPECT_NEAR(period, expected, 1e-3 * expected);
    // and it rocks about its place: the shape's centre stays at r above the ground
    EXPECT_NEAR(scene.world.shapePose(ball).position.z(), r, 1e-4);
}

TEST(CenterOfMass, ABallWeightedAboveItsCentreRollsOverUntilTheWeightIsBelow)
{
    // the upright ball is in unstable equilibrium; tilted by half a degree it rolls until its centre
    // of mass is under its centre (and, rolling without loss, on nearly to the top again)
    io::Scene scene = loadReferenceScene("roly_poly");
    const BodyId ball = scene.dynamicBodies.at(1);
    ASSERT_GT(scene.world.centerOfMass(ball).z(), 0.0);
    Real largest = 0.0;
    for (int k = 0; k < 3000; ++k)
    {
        scene.world.step(scene.options);
        largest = std::max(largest, tiltAngle(scene.world.state(ball).orientation));
    }
    EXPECT_GT(largest, 150.0 * kDegree);
    EXPECT_NEAR(scene.world.shapePose(ball).position.z(), 0.1, 1e-4);
}

TEST(CenterOfMass, ABoxStandsWhileItsCentreOfMassIsOverItsBaseAndTipsOnceItIsPastTheEdge)
{
    // a cube of side 0.2 on the ground (mu 1), its centre of mass moved along x 5 mm inside and 5 mm
    // outside its base's edge at x = 0.1 (outside, as a weight fixed to its side)
    constexpr Real h = 0.1;
    for (const Real x : {0.095, 0.105})
    {
        Ground g = groundWorld(1.0);
        const BodyId box = place(g, Box{Vec3::Constant(h)}, Vec3(0.0, 0.0, h), Quat::Identity(), Vec3(x, 0.0, 0.0));
        const Vec3 start = g.world.shapePose(box).position;
        Real largest = 0.0;
        for (int k = 0; k < 2000; ++k)
        {
            g.world.step(StepOptions{});
            largest = std::max(largest, tiltAngle(g.world.state(box).orientation));
        }
        if (x < h)
        {
            EXPECT_LT((g.world.shapePose(box).position - start).norm(), 1e-3) << "x = " << x;
            EXPECT_LT(largest, 1e-3) << "x = " << x;
        }
        else
        {
            // from rest the torque m g (x - h) about the edge turns it past 45 degrees within 2 s
            EXPECT_GT(largest, 45.0 * kDegree) << "x = " << x;
        }
    }
}

TEST(CenterOfMass, FreeFlightTurnsTheShapeAboutTheCentreOfMass)
{
    // no gravity, no contact: the centre of mass moves uniformly and the shape circles it
    World world(WorldDef{.gravity = Vec3::Zero()});
    const MaterialId material = world.createMaterial({});
    const Vec3 c(0.05, -0.02, 0.01);
    const Vec3 v(0.3, 0.1, -0.2);
    const BodyId box = world.createBody({.shape = Box{Vec3(0.1, 0.2, 0.3)},
                                         .material = material,
                                         .mass = 2.0,
                                         .linearVelocity = v,
                                         .angularVelocity = Vec3(0.0, 0.0, 2.0),
                                         .inertia = Vec3(0.02, 0.02, 0.03).asDiagonal(),
                                         .centerOfMass = c});
    EXPECT_EQ(world.centerOfMass(box), c);
    for (int k = 0; k < 1000; ++k)
    {
        world.step(StepOptions{});
    }
    // a symmetric top spinning about its axis of symmetry: w stays 2 rad/s about z
    const Real t = world.time();
    const Quat turned(Eigen::AngleAxisd(2.0 * t, Vec3::UnitZ()));
    EXPECT_LT((world.state(box).position - v * t).norm(), 1e-12);
    EXPECT_LT((world.shapePose(box).position - (v * t - turned * c)).norm(), 1e-9);
}

TEST(CenterOfMass, MovingItLeavesTheShapeWhereItIsAndMovingAsItWas)
{
    World world(WorldDef{.gravity = Vec3::Zero()});
    const MaterialId material = world.createMaterial({});
    const BodyId box = world.createBody({.shape = Box{Vec3(0.1, 0.2, 0.3)},
                                         .material = material,
                                         .mass = 1.0,
                                         .position = Vec3(1.0, 2.0, 3.0),
                                         .orientation = Quat(Eigen::AngleAxisd(0.7, Vec3(1.0, 2.0, 3.0).normalized())),
                                         .linearVelocity = Vec3(0.1, 0.2, 0.3),
                                         .angularVelocity = Vec3(1.0, -2.0, 0.5)});
    const Pose before = world.shapePose(box);
    const BodyState state = world.state(box);
    const Vec3 c(0.03, 0.04, -0.05);
    world.setMassProperties(box, 1.0, world.inertia(box), c);
    EXPECT_EQ(world.centerOfMass(box), c);
    EXPECT_LT((world.shapePose(box).position - before.position).norm(), 1e-15);
    EXPECT_LT((world.state(box).position - (before.position + before.orientation * c)).norm(), 1e-15);
    // the velocity of the new centre is that of the material point it was before
    const Vec3 lever = world.state(box).position - state.position;
    EXPECT_LT((world.state(box).linearVelocity - (state.linearVelocity + state.angularVelocity.cross(lever))).norm(),
              1e-15);
}

} // namespace
} // namespace impulse::test
