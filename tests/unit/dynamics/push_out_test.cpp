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

} // namespace
} // namespace impulse
