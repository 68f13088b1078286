// SPDX-License-Identifier: MIT
// The World API a program drives a simulation with: forces, torques and impulses against the
// analytic motion they must give, collision filtering and removal against what must (not) touch,
// mass properties with an inertia tensor of the user's, and the refusal of bad calls.
#include <impulse/impulse.hpp>

#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>
#include <string>

namespace impulse
{
namespace
{

constexpr Real kDt = 1e-3;

World freeSpace()
{
    return World(WorldDef{.gravity = Vec3::Zero()});
}

void expectVecNear(const Vec3& actual, const Vec3& expected, Real tolerance)
{
    EXPECT_LE((actual - expected).norm(), tolerance)
        << "actual " << actual.transpose() << "\nexpected " << expected.transpose();
}

// The message of the std::invalid_argument `call` throws ("" when it throws none).
template <typename Call> std::string refusal(Call&& call)
{
    try
    {
        call();
    }
    catch (const std::invalid_argument& error)
    {
        return error.what();
    }
    return "";
}

Mat3 worldInertia(const World& world, BodyId id)
{
    const Mat3 r = world.state(id).orientation.toRotationMatrix();
    return r * world.inertia(id) * r.transpose();
}

// ---- forces ----

TEST(WorldForces, AConstantForceGivesFtOverMInTheSymplecticStep)
{
    World world = freeSpace();
    const MaterialId material = world.createMaterial({});
    const Vec3 start(0.3, -0.2, 1.0);
    const BodyId ball = world.createBody({.shape = Sphere{0.1}, .material = material, .mass = 2.0, .position = start});
    const Vec3 force(3.0, -1.0, 0.5);
    const int steps = 1000;
    for (int k = 0; k < steps; ++k)
    {
        world.applyForce(ball, force);
        world.step({.dt = kDt});
    }
    const Vec3 a = force / 2.0;
    const Real t = steps * kDt;
    // v = F t / m; the position update with the new velocity: x = x0 + a dt^2 n (n + 1) / 2
    expectVecNear(world.state(ball).linearVelocity, a * t, 1e-12 * (a * t).norm());
    const Vec3 expectedPosition = start + a * (kDt * kDt * steps * (steps + 1) / 2.0);
    expectVecNear(world.state(ball).position, expectedPosition, 1e-12 * expectedPosition.norm());
}

TEST(WorldForces, ForcesAddUpForOneStepAndAreThenCleared)
{
    World world = freeSpace();
    const MaterialId material = world.createMaterial({});
    const BodyId ball = world.createBody({.shape = Sphere{0.1}, .material = material, .mass = 0.5});
    world.applyForce(ball, Vec3(1.0, 0.0, 0.0));
    world.applyForce(ball, Vec3(0.0, 2.0, 0.0));
    EXPECT_EQ(world.appliedForce(ball), Vec3(1.0, 2.0, 0.0));
    world.step({.dt = kDt});
    const Vec3 after = world.state(ball).linearVelocity;
    expectVecNear(after, Vec3(1.0, 2.0, 0.0) * (kDt / 0.5), 1e-18);
    EXPECT_EQ(world.appliedForce(ball), Vec3::Zero());
    EXPECT_EQ(world.appliedTorque(ball), Vec3::Zero());
    world.step({.dt = kDt}); // nothing applied: the velocity stays
    EXPECT_EQ(world.state(ball).linearVelocity, after);
}

TEST(WorldForces, ALiftOfTwiceTheWeightRaisesARestingBoxAtG)
{
    World world;
    const MaterialId material = world.createMaterial({.restitution = 0.0, .friction = 0.5});
    world.createBody({.type = BodyType::Static, .shape = Plane{}, .material = material});
    const BodyId box = world.createBody(
        {.shape = Box{Vec3::Constant(0.1)}, .material = material, .mass = 1.5, .position = Vec3(0.0, 0.0, 0.1)});
    const Vec3 lift = -2.0 * 1.5 * world.gravity();
    const int steps = 500;
    for (int k = 0; k < steps; ++k)
    {
        world.applyForce(box, lift);
        world.step({.dt = kDt});
    }
    // nothing holds it down: a = -g, exactly as in free flight
    const Real t = steps * kDt;
    expectVecNear(world.state(box).linearVelocity, -world.gravity() * t, 1e-12);
    EXPECT_NEAR(world.state(box).position.z(), 0.1 + 9.81 * kDt * kDt * steps * (steps + 1) / 2.0, 1e-12);
}

// A box on the ground, mu = 0.5, pushed sideways with the force applied before every step.
Vec3 pushedBoxVelocity(Real push, Real seconds)
{
    World world;
    const MaterialId material = world.createMaterial({.restitution = 0.0, .friction = 0.5});
    world.createBody({.type = BodyType::Static, .shape = Plane{}, .material = material});
    const BodyId box = world.createBody(
        {.shape = Box{Vec3::Constant(0.1)}, .material = material, .mass = 1.0, .position = Vec3(0.0, 0.0, 0.1)});
    const auto steps = std::lround(seconds / kDt);
    for (long k = 0; k < steps; ++k)
    {
        world.applyForce(box, Vec3(push, 0.0, 0.0));
        world.step({.dt = kDt});
    }
    return world.state(box).linearVelocity;
}

TEST(WorldForces, APushBelowStaticFrictionLeavesABoxAtRestAndOneAboveSlidesItAtFMinusMuMgOverM)
{
    // mu m g = 4.905 N
    EXPECT_LE(pushedBoxVelocity(2.0, 0.5).norm(), 1e-9);
    // the contact pass's patches on the four corners leave a few 1e-5 m/s of the ideal slide
    const Vec3 sliding = pushedBoxVelocity(8.0, 0.5);
    EXPECT_NEAR(sliding.x(), (8.0 - 0.5 * 9.81) * 0.5, 1e-4);
    EXPECT_NEAR(sliding.y(), 0.0, 1e-4);
    EXPECT_NEAR(sliding.z(), 0.0, 1e-6);
}

TEST(WorldForces, AForceAtAPointIsTheForceAndItsMomentAboutTheCentreOfMass)
{
    const auto run = [](bool atPoint)
    {
        World world = freeSpace();
        const MaterialId material = world.createMaterial({});
        const BodyId box = world.createBody({.shape = Box{Vec3(0.1, 0.2, 0.3)},
                                             .material = material,
                                             .mass = 1.0,
                                             .position = Vec3(1.0, 2.0, 3.0),
                                             .orientation = Quat(0.9, 0.1, -0.3, 0.2)});
        const Vec3 force(0.4, -1.2, 2.0);
        const Vec3 point(1.1, 1.7, 3.2);
        if (atPoint)
        {
            world.applyForce(box, force, point);
        }
        else
        {
            world.applyForce(box, force);
            world.applyTorque(box, (point - Vec3(1.0, 2.0, 3.0)).cross(force));
        }
        world.step({.dt = kDt});
        return world.stateHash();
    };
    EXPECT_EQ(run(true), run(false));
}

// ---- torques and impulses ----

TEST(WorldTorques, ATorqueAboutAPrincipalAxisSpinsUpLToTauT)
{
    World world = freeSpace();
    const MaterialId material = world.createMaterial({});
    const Quat turn = Quat(Eigen::AngleAxisd(0.7, Vec3(1.0, 2.0, -0.5).normalized()));
    const BodyId box =
        world.createBody({.shape = Box{Vec3(0.1, 0.2, 0.3)}, .material = material, .mass = 1.5, .orientation = turn});
    const Vec3 axis = turn * Vec3::UnitY(); // the body's y axis, a principal axis, in the world
    const Vec3 torque = 0.7 * axis;
    const int steps = 1000;
    for (int k = 0; k < steps; ++k)
    {
        world.applyTorque(box, torque);
        world.step({.dt = kDt});
    }
    const Real t = steps * kDt;
    const BodyState s = world.state(box);
    expectVecNear(s.angularMomentum, torque * t, 1e-13);
    // about a principal axis the spin stays on it: w = tau t / I_y
    const Real iy = world.principalInertia(box).y();
    expectVecNear(s.angularVelocity, torque * t / iy, 1e-11 * (torque * t / iy).norm());
    EXPECT_NEAR(iy, 1.5 * (0.2 * 0.2 + 0.6 * 0.6) / 12.0, 1e-15);
    // the turn about it: theta = tau / I dt^2 n (n + 1) / 2
    const Real theta = 0.7 / iy * kDt * kDt * steps * (steps + 1) / 2.0;
    EXPECT_NEAR(s.orientation.angularDistance(Quat(Eigen::AngleAxisd(theta, axis)) * turn), 0.0, 1e-10);
    EXPECT_NEAR(world.kineticEnergy(), 0.5 * (0.7 * t) * (0.7 * t) / iy, 1e-12);
}

TEST(WorldImpulses, AnImpulseAtAnOffsetPointGivesJOverMAndRCrossJ)
{
    World world = freeSpace();
    const MaterialId material = world.createMaterial({});
    const Vec3 centre(0.5, 0.0, 2.0);
    const BodyId box = world.createBody({.shape = Box{Vec3(0.1, 0.2, 0.3)},
                                         .material = material,
                                         .mass = 3.0,
                                         .position = centre,
                                         .orientation = Quat(Eigen::AngleAxisd(0.4, Vec3(0, 1, 1).normalized()))});
    const Vec3 impulse(0.2, -0.5, 1.0);
    const Vec3 lever(0.05, 0.1, -0.02);
    world.applyImpulse(box, impulse, centre + lever);
    BodyState s = world.state(box);
    expectVecNear(s.linearVelocity, impulse / 3.0, 1e-16);
    expectVecNear(s.angularMomentum, lever.cross(impulse), 1e-16);
    expectVecNear(s.angularVelocity, worldInertia(world, box).inverse() * lever.cross(impulse), 1e-13);
    // free flight keeps both momenta
    for (int k = 0; k < 200; ++k)
    {
        world.step({.dt = kDt});
    }
    s = world.state(box);
    expectVecNear(s.linearVelocity, impulse / 3.0, 1e-16);
    expectVecNear(s.angularMomentum, lever.cross(impulse), 1e-16);
    // through the centre of mass, and an angular impulse
    world.applyImpulse(box, Vec3(0.0, 3.0, 0.0));
    world.applyAngularImpulse(box, Vec3(0.0, 0.0, 0.25));
    expectVecNear(world.state(box).linearVelocity, impulse / 3.0 + Vec3(0.0, 1.0, 0.0), 1e-15);
    expectVecNear(world.state(box).angularMomentum, lever.cross(impulse) + Vec3(0.0, 0.0, 0.25), 1e-16);
}

// ---- mass properties ----

TEST(WorldMassProperties, AFullInertiaTensorIsDiagonalisedIntoPrincipalAxes)
{
    World world = freeSpace();
    const MaterialId material = world.createMaterial({});
    const BodyId box = world.createBody({.shape = Box{Vec3(0.1, 0.2, 0.3)}, .material = material, .mass = 1.0});
    const Mat3 q = Eigen::AngleAxisd(0.6, Vec3(1.0, -1.0, 2.0).normalized()).toRotationMatrix();
    const Mat3 tensor = q * Vec3(0.5, 0.8, 1.1).asDiagonal() * q.transpose();
    world.setMassProperties(box, 2.0, tensor);
    EXPECT_EQ(world.mass(box), 2.0);
    expectVecNear(world.principalInertia(box), Vec3(0.5, 0.8, 1.1), 1e-14);
    const Mat3 axes = world.principalAxes(box);
    EXPECT_NEAR(axes.determinant(), 1.0, 1e-14);
    EXPECT_LE((axes * world.principalInertia(box).asDiagonal() * axes.transpose() - tensor).norm(), 1e-14);
    EXPECT_LE((world.inertia(box) - tensor).norm(), 1e-14);
}

TEST(WorldMassProperties, ATorqueAboutAPrincipalAxisOfAGivenTensorSpinsUpAboutThatAxis)
{
    World world = freeSpace();
    const MaterialId material = world.createMaterial({});
    const Quat turn(Eigen::AngleAxisd(1.1, Vec3(0.3, 0.2, 1.0).normalized()));
    const BodyId box =
        world.createBody({.shape = Box{Vec3(0.1, 0.2, 0.3)}, .material = material, .mass = 1.0, .orientation = turn});
    const Mat3 q = Eigen::AngleAxisd(0.6, Vec3(1.0, -1.0, 2.0).normalized()).toRotationMatrix();
    world.setMassProperties(box, 1.0, q * Vec3(0.5, 0.8, 1.1).asDiagonal() * q.transpose());
    // the largest moment's axis in the body frame is q's third column; in the world, turned by q_body
    const Vec3 axis = turn * q.col(2);
    const Vec3 torque = 0.3 * axis;
    const int steps = 1000;
    for (int k = 0; k < steps; ++k)
    {
        world.applyTorque(box, torque);
        world.step({.dt = kDt});
    }
    const Real t = steps * kDt;
    expectVecNear(world.state(box).angularMomentum, torque * t, 1e-13);
    // had the shape's axes been used, w would leave L's direction at once
    expectVecNear(world.state(box).angularVelocity, torque * t / 1.1, 1e-10);
}

TEST(WorldMassProperties, TheAngularVelocityOfAnImpulseFollowsTheGivenTensor)
{
    World world = freeSpace();
    const MaterialId material = world.createMaterial({});
    const Quat turn(Eigen::AngleAxisd(0.5, Vec3(1.0, 0.0, 1.0).normalized()));
    const BodyId box =
        world.createBody({.shape = Box{Vec3(0.1, 0.2, 0.3)}, .material = material, .mass = 1.0, .orientation = turn});
    Mat3 tensor;
    tensor << 0.9, 0.1, -0.05, 0.1, 0.7, 0.2, -0.05, 0.2, 1.0;
    world.setMassProperties(box, 1.0, tensor);
    const Vec3 lever(0.1, -0.1, 0.05);
    const Vec3 impulse(0.0, 0.3, 0.4);
    world.applyImpulse(box, impulse, lever);
    const Mat3 r = turn.toRotationMatrix();
    const Vec3 expected = r * tensor.inverse() * r.transpose() * lever.cross(impulse);
    expectVecNear(world.state(box).angularVelocity, expected, 1e-13 * expected.norm());
    // energy through the tensor itself: T = w . I w / 2
    const Vec3 w = world.state(box).angularVelocity;
    EXPECT_NEAR(world.kineticEnergy(), 0.5 * impulse.squaredNorm() + 0.5 * w.dot(r * tensor * r.transpose() * w),
                1e-14);
}

TEST(WorldMassProperties, SetMassScalesTheShapesInertiaAndKeepsTheVelocities)
{
    World world = freeSpace();
    const MaterialId material = world.createMaterial({});
    const BodyId ball = world.createBody({.shape = Sphere{0.2},
                                          .material = material,
                                          .mass = 1.0,
                                          .linearVelocity = Vec3(1.0, 0.0, 0.0),
                                          .angularVelocity = Vec3(0.0, 0.0, 2.0)});
    world.setMass(ball, 4.0);
    EXPECT_EQ(world.mass(ball), 4.0);
    expectVecNear(world.principalInertia(ball), Vec3::Constant(0.4 * 4.0 * 0.04), 1e-16);
    EXPECT_EQ(world.state(ball).linearVelocity, Vec3(1.0, 0.0, 0.0));
    expectVecNear(world.state(ball).angularVelocity, Vec3(0.0, 0.0, 2.0), 1e-15);
    expectVecNear(world.linearMomentum(), Vec3(4.0, 0.0, 0.0), 1e-15);
}

// ---- filtering ----

struct Drop
{
    World world;
    BodyId ground;
    BodyId ball;
};

Drop ballOverGround()
{
    Drop drop;
    const MaterialId material = drop.world.createMaterial({.restitution = 0.5, .friction = 0.3});
    drop.ground = drop.world.createBody({.type = BodyType::Static, .shape = Plane{}, .material = material});
    drop.ball = drop.world.createBody(
        {.shape = Sphere{0.1}, .material = material, .mass = 1.0, .position = Vec3(0.0, 0.0, 1.0)});
    return drop;
}

Real heightAfter(Drop& drop, int steps)
{
    for (int k = 0; k < steps; ++k)
    {
        drop.world.step({.dt = kDt});
    }
    return drop.world.state(drop.ball).position.z();
}

Real freeFallHeight(int steps)
{
    return 1.0 - 9.81 * kDt * kDt * steps * (steps + 1) / 2.0;
}

TEST(WorldFiltering, ABallWhoseMaskLeavesOutTheGroundsGroupFallsThroughIt)
{
    Drop control = ballOverGround();
    EXPECT_GT(heightAfter(control, 1000), 0.09); // it bounces

    Drop drop = ballOverGround();
    drop.world.setCollisionFilter(drop.ground, {.group = 2, .mask = 0xffffffffU});
    drop.world.setCollisionFilter(drop.ball, {.group = 1, .mask = ~2U});
    EXPECT_FALSE(drop.world.collisionEnabled(drop.ball, drop.ground));
    EXPECT_EQ(drop.world.collisionFilter(drop.ball).mask, ~2U);
    EXPECT_NEAR(heightAfter(drop, 1000), freeFallHeight(1000), 1e-12);
    EXPECT_EQ(drop.world.lastStepStats().candidatePairs, 0);
}

TEST(WorldFiltering, ADisabledPairPassesThroughUntilEnabledAgain)
{
    Drop drop = ballOverGround();
    drop.world.setCollisionEnabled(drop.ground, drop.ball, false);
    EXPECT_FALSE(drop.world.collisionEnabled(drop.ball, drop.ground));
    EXPECT_NEAR(heightAfter(drop, 300), freeFallHeight(300), 1e-12); // 0.56 m, still above
    drop.world.setCollisionEnabled(drop.ball, drop.ground, true);
    EXPECT_TRUE(drop.world.collisionEnabled(drop.ball, drop.ground));
    EXPECT_GT(heightAfter(drop, 1000), 0.09);
}

TEST(WorldFiltering, FilteredBodiesMeetingHeadOnKeepTheirVelocities)
{
    World world = freeSpace();
    const MaterialId material = world.createMaterial({.restitution = 1.0, .friction = 0.0});
    const BodyId left = world.createBody({.shape = Box{Vec3::Constant(0.1)},
                                          .material = material,
                                          .mass = 1.0,
                                          .position = Vec3(-0.5, 0.0, 0.0),
                                          .linearVelocity = Vec3(1.0, 0.0, 0.0),
                                          .filter = {.group = 4, .mask = ~8U}});
    const BodyId right = world.createBody({.shape = Box{Vec3::Constant(0.1)},
                                           .material = material,
                                           .mass = 1.0,
                                           .position = Vec3(0.5, 0.0, 0.0),
                                           .linearVelocity = Vec3(-1.0, 0.0, 0.0),
                                           .filter = {.group = 8, .mask = 0xffffffffU}});
    for (int k = 0; k < 1000; ++k)
    {
        world.step({.dt = kDt});
    }
    EXPECT_EQ(world.state(left).linearVelocity, Vec3(1.0, 0.0, 0.0));
    EXPECT_EQ(world.state(right).linearVelocity, Vec3(-1.0, 0.0, 0.0));
    EXPECT_NEAR(world.state(left).position.x(), 0.5, 1e-12);
    // the same boxes unfiltered swap their velocities (an elastic head-on hit of equal masses)
    world.setCollisionFilter(left, {});
    world.setCollisionFilter(right, {});
    world.setState(left, Vec3(-0.5, 0.0, 0.0), Quat::Identity(), Vec3(1.0, 0.0, 0.0), Vec3::Zero());
    world.setState(right, Vec3(0.5, 0.0, 0.0), Quat::Identity(), Vec3(-1.0, 0.0, 0.0), Vec3::Zero());
    for (int k = 0; k < 1000; ++k)
    {
        world.step({.dt = kDt});
    }
    expectVecNear(world.state(left).linearVelocity, Vec3(-1.0, 0.0, 0.0), 1e-9);
    expectVecNear(world.state(right).linearVelocity, Vec3(1.0, 0.0, 0.0), 1e-9);
}

// ---- removal ----

TEST(WorldRemoval, ARemovedBodyNoLongerCollidesNorCountsAndKeepsOthersNumbers)
{
    World world;
    const MaterialId material = world.createMaterial({.restitution = 0.0, .friction = 0.5});
    const BodyId ground = world.createBody({.type = BodyType::Static, .shape = Plane{}, .material = material});
    const BodyId box = world.createBody(
        {.shape = Box{Vec3::Constant(0.1)}, .material = material, .mass = 5.0, .position = Vec3(0.0, 0.0, 0.1)});
    const BodyId ball =
        world.createBody({.shape = Sphere{0.1}, .material = material, .mass = 1.0, .position = Vec3(0.0, 0.0, 0.3)});
    for (int k = 0; k < 200; ++k)
    {
        world.step({.dt = kDt});
    }
    EXPECT_NEAR(world.state(ball).position.z(), 0.3, 1e-3); // resting on the box

    world.removeBody(box);
    EXPECT_FALSE(world.contains(box));
    EXPECT_TRUE(world.contains(ball));
    EXPECT_EQ(world.bodyCount(), 3u);
    // only the ball counts
    const BodyState s = world.state(ball);
    EXPECT_NEAR(world.potentialEnergy(), 9.81 * s.position.z(), 1e-12);
    EXPECT_NEAR(world.kineticEnergy(),
                0.5 * s.linearVelocity.squaredNorm() + 0.5 * s.angularVelocity.dot(s.angularMomentum), 1e-15);
    EXPECT_EQ(world.snapshot().bodies.size(), 3u);

    // the ball falls through where the box was and rests on the ground
    for (int k = 0; k < 1000; ++k)
    {
        world.step({.dt = kDt});
    }
    EXPECT_NEAR(world.state(ball).position.z(), 0.1, 1e-3);
    EXPECT_LE(world.state(ball).linearVelocity.norm(), 1e-9);
    EXPECT_NEAR(world.potentialEnergy(), 9.81 * world.state(ball).position.z(), 1e-12);
    EXPECT_NEAR(world.linearMomentum().norm(), world.state(ball).linearVelocity.norm(), 1e-15);

    // a new body gets a new number; the removed one stays refused
    const BodyId next =
        world.createBody({.shape = Sphere{0.1}, .material = material, .mass = 1.0, .position = Vec3(1.0, 0.0, 0.1)});
    EXPECT_EQ(next.index, 3u);
    EXPECT_NE(refusal([&] { world.state(box); }).find("body: body 1 was removed"), std::string::npos);
    EXPECT_NE(refusal([&] { world.removeBody(box); }).find("was removed"), std::string::npos);
    // a snapshot of the world with a removed body restores into it
    const WorldSnapshot snapshot = world.snapshot();
    world.step({.dt = kDt});
    world.restore(snapshot);
    EXPECT_EQ(world.state(ground).position, Vec3::Zero());
}

// ---- what must not change ----

// Four boxes dropped onto the ground and onto each other, 300 steps.
std::uint64_t boxDropHash(bool zeroNetLoads, bool defaultFilters)
{
    World world;
    const MaterialId material = world.createMaterial({.restitution = 0.3, .friction = 0.5});
    world.createBody({.type = BodyType::Static, .shape = Plane{}, .material = material});
    std::vector<BodyId> boxes;
    for (int k = 0; k < 4; ++k)
    {
        boxes.push_back(
            world.createBody({.shape = Box{Vec3(0.1, 0.08, 0.06)},
                              .material = material,
                              .density = 500.0,
                              .position = Vec3(0.02 * k, -0.01 * k, 0.1 + 0.2 * k),
                              .orientation = Quat(Eigen::AngleAxisd(0.3 * k, Vec3(1, 0.5, 0.2).normalized()))}));
        if (defaultFilters)
        {
            world.setCollisionFilter(boxes.back(), {});
        }
    }
    if (defaultFilters)
    {
        world.setCollisionEnabled(boxes[0], boxes[3], false); // never close enough to matter
        world.setCollisionEnabled(boxes[0], boxes[3], true);
        world.setCollisionFilter(boxes[0], {.group = 3, .mask = 0xffffffffU});
    }
    for (int step = 0; step < 300; ++step)
    {
        if (zeroNetLoads)
        {
            for (const BodyId box : boxes)
            {
                world.applyForce(box, Vec3(1.0, -2.0, 3.0));
                world.applyForce(box, Vec3(-1.0, 2.0, -3.0));
                world.applyTorque(box, Vec3(0.5, 0.25, 0.0));
                world.applyTorque(box, Vec3(-0.5, -0.25, 0.0));
            }
        }
        world.step({});
    }
    return world.stateHash();
}

// ---- reading the contacts ----------------------------------------------------------------------

TEST(WorldContacts, ABoxRestingOnTheGroundCarriesItsWeightEveryStep)
{
    // at rest the ground's normal impulses on the box add up to m g dt each step, all along +z on the
    // box, with no friction (nothing pushes it sideways), at the corners of its bottom face
    World world;
    const MaterialId material = world.createMaterial({.restitution = 0.0, .friction = 0.5});
    const BodyId ground = world.createBody({.type = BodyType::Static, .shape = Plane{}, .material = material});
    const BodyId box = world.createBody(
        {.shape = Box{Vec3(0.2, 0.1, 0.05)}, .material = material, .mass = 3.0, .position = Vec3(0.0, 0.0, 0.05)});
    EXPECT_TRUE(world.contacts().empty()) << "no step, no contacts";
    for (int step = 0; step < 200; ++step)
    {
        world.step(StepOptions{});
        Real normal = 0.0;
        Vec3 friction = Vec3::Zero();
        for (const Contact& contact : world.contacts())
        {
            // the pair is listed lower index first: the normal points from the box toward the ground
            ASSERT_EQ(contact.a, ground);
            ASSERT_EQ(contact.b, box);
            EXPECT_NEAR(contact.normal.z(), -1.0, 1e-12);
            EXPECT_NEAR(std::abs(contact.point.x()), 0.2, 1e-9);
            EXPECT_NEAR(std::abs(contact.point.y()), 0.1, 1e-9);
            EXPECT_GE(contact.normalImpulse, 0.0);
            normal += contact.normalImpulse;
            friction += contact.frictionImpulse;
        }
        ASSERT_FALSE(world.contacts().empty());
        EXPECT_NEAR(normal, 3.0 * 9.81 * kDt, 1e-12 * 3.0 * 9.81 * kDt) << "step " << step;
        EXPECT_LT(friction.norm(), 1e-12) << "step " << step;
    }
}

TEST(WorldContacts, ABoxHeldOnAnInclineByFrictionFeelsItsWeightSplitAcrossTheSlope)
{
    // on a 20 degree incline with mu = 0.5 > tan 20 the box sticks: per step the normal impulses add
    // up to m g cos 20 dt and the friction to m g sin 20 dt, up the slope
    World world;
    const Real angle = 20.0 * std::acos(-1.0) / 180.0;
    const Vec3 up(std::sin(angle), 0.0, std::cos(angle));
    const MaterialId material = world.createMaterial({.restitution = 0.0, .friction = 0.5});
    world.createBody({.type = BodyType::Static, .shape = Plane{up, 0.0}, .material = material});
    world.createBody({.shape = Box{Vec3::Constant(0.1)},
                      .material = material,
                      .mass = 1.0,
                      .position = 0.1 * up,
                      .orientation = Quat(Eigen::AngleAxisd(angle, Vec3::UnitY()))});
    for (int step = 0; step < 100; ++step)
    {
        world.step(StepOptions{});
    }
    Vec3 total = Vec3::Zero(); // on the box: minus what is reported on the plane
    for (const Contact& contact : world.contacts())
    {
        total -= contact.normalImpulse * contact.normal + contact.frictionImpulse;
    }
    const Real weight = 9.81 * kDt;
    EXPECT_NEAR(total.dot(up), weight * std::cos(angle), 1e-12);
    const Vec3 downhill = Vec3(std::cos(angle), 0.0, -std::sin(angle));
    EXPECT_NEAR(total.dot(downhill), -weight * std::sin(angle), 1e-12);
}

TEST(WorldApiInvariance, LoadsThatCancelAndFiltersThatPassEverythingChangeNoBit)
{
    const std::uint64_t plain = boxDropHash(false, false);
    EXPECT_EQ(boxDropHash(true, false), plain);
    EXPECT_EQ(boxDropHash(false, true), plain);
}

// ---- bad calls ----

TEST(WorldApiRefusals, BadCallsAreRefusedNamingTheField)
{
    World world;
    const MaterialId material = world.createMaterial({});
    const BodyId ground = world.createBody({.type = BodyType::Static, .shape = Plane{}, .material = material});
    const BodyId ball = world.createBody({.shape = Sphere{0.1}, .material = material, .mass = 1.0});
    const Real nan = std::nan("");
    const auto says = [](const std::string& message, const std::string& expected)
    { EXPECT_NE(message.find(expected), std::string::npos) << "message: \"" << message << "\""; };

    says(refusal([&] { world.applyForce(BodyId{7}, Vec3::Zero()); }), "body: no body 7 in this world (it has 2)");
    says(refusal([&] { world.state(BodyId{2}); }), "body: no body 2");
    says(refusal([&] { world.applyForce(ball, Vec3(nan, 0.0, 0.0)); }), "force: must be finite");
    says(refusal([&] { world.applyForce(ball, Vec3::Zero(), Vec3(0.0, INFINITY, 0.0)); }), "point: must be finite");
    says(refusal([&] { world.applyTorque(ball, Vec3(0.0, nan, 0.0)); }), "torque: must be finite");
    says(refusal([&] { world.applyImpulse(ball, Vec3(0.0, 0.0, nan)); }), "impulse: must be finite");
    says(refusal([&] { world.applyForce(ground, Vec3(1.0, 0.0, 0.0)); }), "body: body 0 is static");
    says(refusal([&] { world.setMassProperties(ball, -1.0, Mat3::Identity()); }),
         "mass: must be a positive finite number, got -1");
    says(refusal([&] { world.setMass(ball, 0.0); }), "mass: must be a positive finite number");
    says(refusal([&] { world.setMassProperties(ball, 1.0, Vec3(1.0, 1.0, -0.5).asDiagonal()); }),
         "inertia: must be positive definite");
    Mat3 skew = Mat3::Identity();
    skew(0, 1) = 0.1;
    says(refusal([&] { world.setMassProperties(ball, 1.0, skew); }), "inertia: must be symmetric");
    says(refusal([&] { world.setMassProperties(ball, 1.0, Vec3(1.0, 1.0, 3.0).asDiagonal()); }), "triangle inequality");
    says(refusal([&] { world.setMassProperties(ball, 1.0, Mat3::Constant(nan)); }), "inertia: must be finite");
    says(refusal([&] { world.setMassProperties(ground, 1.0, Mat3::Identity()); }), "is static");
    says(refusal([&] { world.setCollisionEnabled(ball, ball, false); }), "same body");
    says(refusal([&] { world.setCollisionEnabled(ball, BodyId{9}, false); }), "b: no body 9");
    // nothing refused changed the ball
    EXPECT_EQ(world.mass(ball), 1.0);
    EXPECT_EQ(world.appliedForce(ball), Vec3::Zero());
    EXPECT_EQ(world.appliedTorque(ball), Vec3::Zero());
}

} // namespace
} // namespace impulse
