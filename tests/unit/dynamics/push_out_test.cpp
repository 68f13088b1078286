// SPDX-License-Identifier: MIT
// A push of push_out.hpp on a wedge: a cube tilted about x between two walls closer than its
// tilted width, its lower and upper edges in the two walls equally deep with opposite normals. No
// translation clears both; turning toward level does. The least move turns it so far that its
// farthest point moves about 1.7 times the overlap, and in a jam such turns drive corners into the
// neighbours. A push turns a body at most so far that its farthest point moves by the overlap.
#include "collision/narrow_phase.hpp"
#include "dynamics/integrate.hpp"
#include "dynamics/push_out.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

namespace impulse
{
namespace
{

constexpr Real kHalf = 0.1;
constexpr Real kTilt = 0.3;     // rad about x
constexpr Real kOverlap = 1e-3; // m, into either wall

RigidBody staticWall(const Vec3& inwardNormal, Real distance)
{
    RigidBody wall;
    wall.dynamic = false;
    // the solid is {n . p <= offset}: its outward normal points at the cube
    wall.shape = Plane{inwardNormal, -distance};
    wall.orientation = Quat::Identity();
    wall.rotation = Mat3::Identity();
    wall.predicted = wall.pose();
    return wall;
}

RigidBody tiltedCube()
{
    RigidBody cube;
    cube.shape = Box{Vec3::Constant(kHalf)};
    cube.mass = 1.0;
    cube.invMass = 1.0;
    cube.principalInertia = Vec3::Constant(cube.mass * (2.0 * kHalf) * (2.0 * kHalf) / 6.0);
    cube.invPrincipalInertia = cube.principalInertia.cwiseInverse();
    cube.boundingRadius = std::sqrt(3.0) * kHalf;
    cube.position = Vec3(0.0, 0.0, 1.0);
    cube.orientation = Quat(Eigen::AngleAxisd(kTilt, Vec3::UnitX()));
    cube.rotation = cube.orientation.toRotationMatrix();
    cube.predicted = cube.pose();
    updateDerivedQuantities(cube);
    return cube;
}

Real deepestOverlap(const RigidBody& cube, const std::vector<RigidBody>& walls)
{
    Real deepest = 0.0;
    std::vector<ContactPoint> points;
    NarrowPhaseScratch scratch;
    for (const RigidBody& wall : walls)
    {
        points.clear();
        collideShapes(cube.shape, cube.pose(), wall.shape, wall.pose(), 0.0, points, scratch);
        for (const ContactPoint& point : points)
        {
            deepest = std::max(deepest, -point.phi);
        }
    }
    return deepest;
}

TEST(PushOutOfSupports, AWedgedCubeIsTurnedNoFurtherThanMovesItsFarthestPointByTheOverlap)
{
    // half the tilted cube's width along y, less the overlap: where each wall stands
    const Real reachAlongY = kHalf * (std::cos(kTilt) + std::sin(kTilt));
    std::vector<RigidBody> walls = {staticWall(Vec3::UnitY(), reachAlongY - kOverlap),
                                    staticWall(-Vec3::UnitY(), reachAlongY - kOverlap)};
    RigidBody cube = tiltedCube();
    ASSERT_NEAR(deepestOverlap(cube, walls), kOverlap, 1e-12);
    // the scene's premise: the least move, turning until both edges clear, would move the farthest
    // point well beyond the overlap, so the limit has something to cut
    const Real clearingTurn = kOverlap / (kHalf * (std::cos(kTilt) - std::sin(kTilt)));
    ASSERT_GT(clearingTurn * cube.boundingRadius, 1.5 * kOverlap);
    const Quat start = cube.orientation;
    // the cube's points in both walls, normals from the walls toward the cube
    std::vector<ContactPoint> points;
    NarrowPhaseScratch narrowPhase;
    for (const RigidBody& wall : walls)
    {
        collideShapes(cube.shape, cube.pose(), wall.shape, wall.pose(), 0.0, points, narrowPhase);
    }
    PushOutScratch scratch;
    ASSERT_TRUE(pushOutOfSupports(cube, points, 1e-4, 1.0, scratch)); // reach: far more than needed

    const Real turned = cube.orientation.angularDistance(start);
    EXPECT_NEAR(turned * cube.boundingRadius, kOverlap, 1e-12) << "the farthest point moved by the overlap";
    // the move is solved by Gauss-Seidel to 1e-9 m, so its symmetry holds to about that
    const Real tilt = cube.orientation.angularDistance(Quat::Identity());
    EXPECT_NEAR(tilt, kTilt - turned, 1e-9) << "turned about x, toward level";
    EXPECT_LT((cube.position - Vec3(0.0, 0.0, 1.0)).norm(), 1e-8) << "no translation clears a wedge";
    // the tilted width 2 h (cos + sin) shrinks by h (cos - sin) per radian, to first order: the
    // wedge is partly cleared, and the rest waits for the next push
    const Real left = deepestOverlap(cube, walls);
    EXPECT_NEAR(left, kOverlap - turned * kHalf * (std::cos(kTilt) - std::sin(kTilt)), 1e-5);
    EXPECT_GT(left, 0.5 * kOverlap);
}

RigidBody levelBox(Real half, Real mass, Real z)
{
    RigidBody box;
    box.shape = Box{Vec3::Constant(half)};
    box.mass = mass;
    box.invMass = 1.0 / mass;
    box.principalInertia = Vec3::Constant(mass * (2.0 * half) * (2.0 * half) / 6.0);
    box.invPrincipalInertia = box.principalInertia.cwiseInverse();
    box.boundingRadius = std::sqrt(3.0) * half;
    box.position = Vec3(0.0, 0.0, z);
    box.orientation = Quat::Identity();
    box.rotation = Mat3::Identity();
    box.predicted = box.pose();
    updateDerivedQuantities(box);
    return box;
}

// Every point of pairs (a, b) closer than `threshold`, normals from b toward a.
std::vector<JointPoint> pointsOfPairs(const std::vector<RigidBody>& bodies,
                                      const std::vector<std::pair<std::uint32_t, std::uint32_t>>& pairs, Real threshold)
{
    std::vector<JointPoint> out;
    std::vector<ContactPoint> points;
    NarrowPhaseScratch scratch;
    for (const auto& [a, b] : pairs)
    {
        points.clear();
        collideShapes(bodies[a].shape, bodies[a].pose(), bodies[b].shape, bodies[b].pose(), threshold, points, scratch);
        for (const ContactPoint& point : points)
        {
            out.push_back({a, b, point});
        }
    }
    return out;
}

// A light box (0.5 kg) 2 mm into the ground under a heavy one (8 kg) 2 mm into it. Pushed pair by
// pair, the light box takes 16/17 of every push between the two and goes into the ground, and the
// ground's push sends it back: each round clears 1/17 of the heavy box's overlap. Pushed jointly,
// the ground holds the light box and the heavy one moves: one push clears both overlaps, a
// translation of 2 and 4 mm, to a tenth of the allowance (Gauss-Seidel over the eight corners stops
// once a sweep changes no gap by a hundredth of it).
TEST(PushApartTogether, ALightBoxPinnedUnderAHeavyOneIsHeldByTheGroundAndBothOverlapsClearInOnePush)
{
    constexpr Real kDeep = 2e-3;
    std::vector<RigidBody> bodies = {staticWall(Vec3::UnitZ(), 0.0), levelBox(0.05, 0.5, 0.05 - kDeep),
                                     levelBox(0.1, 8.0, 0.05 - kDeep + 0.05 - kDeep + 0.1)};
    const std::vector<std::pair<std::uint32_t, std::uint32_t>> pairs = {{1, 0}, {2, 1}};
    const std::vector<JointPoint> points = pointsOfPairs(bodies, pairs, 1e-4);
    ASSERT_EQ(points.size(), 8u); // four corners on the ground, four clipped corners between the boxes
    std::vector<int> slotOf(bodies.size(), -1);
    PushOutScratch scratch;

    // the premise: sixteen sweeps of pair-by-pair pushes leave the light box far into the ground
    std::vector<RigidBody> pairwise = bodies;
    for (int sweep = 0; sweep < 16; ++sweep)
    {
        for (const auto& [a, b] : pairs)
        {
            std::vector<ContactPoint> pairPoints;
            for (const JointPoint& p : pointsOfPairs(pairwise, {{a, b}}, 1e-4))
            {
                pairPoints.push_back(p.point);
            }
            pushApart(pairwise[a], pairwise[b], pairPoints, 1e-4, 1.0, 1.0, scratch);
        }
    }
    ASSERT_LT(pairwise[1].position.z(), 0.05 - 0.25 * kDeep);

    pushApartTogether(
        bodies, points, 1e-4, [](std::uint32_t) { return 1.0; }, slotOf, scratch);

    EXPECT_EQ(scratch.moved.size(), 2u);
    EXPECT_NEAR(bodies[1].position.z(), 0.05, 1e-5) << "the light box rests on the ground";
    EXPECT_NEAR(bodies[2].position.z(), 0.2, 1e-5) << "the heavy box rests on the light one";
    EXPECT_LT(bodies[1].orientation.angularDistance(Quat::Identity()) * bodies[1].boundingRadius, 1e-5);
    EXPECT_LT(bodies[2].orientation.angularDistance(Quat::Identity()) * bodies[2].boundingRadius, 1e-5);
    Real deepest = 0.0;
    for (const JointPoint& p : pointsOfPairs(bodies, pairs, 0.0))
    {
        deepest = std::max(deepest, -p.point.phi);
    }
    EXPECT_LT(deepest, 1e-5);
    EXPECT_TRUE(std::all_of(slotOf.begin(), slotOf.end(), [](int slot) { return slot == -1; }));
}

// Nothing moves while every point is within the allowance.
TEST(PushApartTogether, OverlapsWithinTheAllowanceAreLeftAlone)
{
    std::vector<RigidBody> bodies = {staticWall(Vec3::UnitZ(), 0.0), levelBox(0.05, 0.5, 0.05 - 5e-5)};
    const std::vector<JointPoint> points = pointsOfPairs(bodies, {{1, 0}}, 1e-4);
    ASSERT_EQ(points.size(), 4u);
    std::vector<int> slotOf(bodies.size(), -1);
    PushOutScratch scratch;
    pushApartTogether(
        bodies, points, 1e-4, [](std::uint32_t) { return 1.0; }, slotOf, scratch);
    EXPECT_TRUE(scratch.moved.empty());
    EXPECT_EQ(bodies[1].position.z(), 0.05 - 5e-5);
}

} // namespace
} // namespace impulse
