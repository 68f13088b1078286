// SPDX-License-Identifier: MIT
// The capsule: volume and inertia against closed forms and a grid integration, the signed distance
// at points whose answer is known, and its rows of the narrow-phase table in configurations worked
// out by hand (lying flat gives two points, an edge under its middle one).
#include "collision/capsule_contacts.hpp"
#include "collision/narrow_phase.hpp"
#include "geometry/signed_distance.hpp"

#include <impulse/impulse.hpp>

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <numbers>
#include <random>
#include <vector>

namespace impulse
{
namespace
{

constexpr Real kTol = 1e-12;

std::vector<ContactPoint> collide(const Shape& a, const Pose& poseA, const Shape& b, const Pose& poseB,
                                  Real threshold = 0.0)
{
    std::vector<ContactPoint> out;
    NarrowPhaseScratch scratch;
    collideShapes(a, poseA, b, poseB, threshold, out, scratch);
    return out;
}

Pose at(const Vec3& position, const Quat& orientation = Quat::Identity())
{
    return Pose::from(position, orientation);
}

// Turns the capsule's axis (body z) onto world x.
Quat lyingAlongX()
{
    return Quat(Eigen::AngleAxisd(std::numbers::pi / 2.0, Vec3::UnitY()));
}

void expectVecNear(const Vec3& actual, const Vec3& expected, Real tol = kTol)
{
    EXPECT_LT((actual - expected).norm(), tol)
        << "actual   " << actual.transpose() << "\nexpected " << expected.transpose();
}

TEST(CapsuleMass, UnitCapsuleHasTheClosedFormMoments)
{
    // r = h = 1: cylinder 2 pi, spheres 4 pi / 3, total 10 pi / 3. About the axis
    // (pi + 8 pi / 15) / (10 pi / 3) = 0.46; across it (7 pi / 6 + 43 pi / 15) / (10 pi / 3) = 1.21.
    const Capsule capsule{1.0, 1.0};
    EXPECT_NEAR(volume(capsule), 10.0 * std::numbers::pi / 3.0, 1e-14);
    EXPECT_NEAR(boundingRadius(capsule), 2.0, 0.0);
    const Vec3 inertia = unitInertia(capsule);
    EXPECT_NEAR(inertia.x(), 1.21, 1e-14);
    EXPECT_NEAR(inertia.y(), 1.21, 1e-14);
    EXPECT_NEAR(inertia.z(), 0.46, 1e-14);
}

TEST(CapsuleMass, ShortCapsuleTendsToTheSphere)
{
    const Real r = 0.3;
    const Vec3 inertia = unitInertia(Capsule{r, 1e-9});
    EXPECT_NEAR(inertia.x(), 0.4 * r * r, 1e-9);
    EXPECT_NEAR(inertia.z(), 0.4 * r * r, 1e-9);
}

TEST(CapsuleMass, InertiaAgreesWithGridIntegration)
{
    // midpoint rule over the bounding box: an independent route to the same integrals; with 200
    // cells across, the surface error is of order 1/200, so agreement to 1 % is meaningful
    const Capsule capsule{0.3, 0.7};
    const int n = 200;
    const Vec3 half(capsule.radius, capsule.radius, capsule.halfLength + capsule.radius);
    const Vec3 cell = 2.0 * half / n;
    Real count = 0.0;
    Vec3 second = Vec3::Zero(); // sums of x^2, y^2, z^2
    for (int i = 0; i < n; ++i)
    {
        for (int j = 0; j < n; ++j)
        {
            for (int k = 0; k < n; ++k)
            {
                const Vec3 p = -half + cell.cwiseProduct(Vec3(i + 0.5, j + 0.5, k + 0.5));
                if (capsuleDistance(capsule, p).phi <= 0.0)
                {
                    count += 1.0;
                    second += p.cwiseProduct(p);
                }
            }
        }
    }
    const Real cellVolume = cell.prod();
    EXPECT_NEAR(count * cellVolume, volume(capsule), 0.01 * volume(capsule));
    second /= count;
    const Vec3 expected(second.y() + second.z(), second.x() + second.z(), second.x() + second.y());
    const Vec3 inertia = unitInertia(capsule);
    for (int i = 0; i < 3; ++i)
    {
        EXPECT_NEAR(inertia[i], expected[i], 0.01 * expected[i]) << "axis " << i;
    }
}

TEST(CapsuleMass, WorldUsesShapeInertiaUnlessGivenOne)
{
    World world;
    const MaterialId material = world.createMaterial({});
    const Capsule capsule{0.1, 0.2};
    const BodyId fromShape = world.createBody({.shape = capsule, .material = material, .mass = 2.0});
    EXPECT_EQ(world.principalInertia(fromShape), Vec3(2.0 * unitInertia(capsule)));
    const BodyId given =
        world.createBody({.shape = capsule, .material = material, .mass = 2.0, .principalInertia = Vec3(1, 2, 3)});
    EXPECT_EQ(world.principalInertia(given), Vec3(1, 2, 3));
    EXPECT_THROW(world.createBody({.shape = Capsule{0.1, 0.0}, .material = material, .mass = 1.0}),
                 std::invalid_argument);
    EXPECT_THROW(world.createBody({.shape = Capsule{-0.1, 0.2}, .material = material, .mass = 1.0}),
                 std::invalid_argument);
}

TEST(CapsuleDistance, KnownPoints)
{
    const Capsule capsule{0.5, 1.0};
    struct Case
    {
        Vec3 point;
        Real phi;
        Vec3 gradient;
    };
    const std::vector<Case> cases = {
        {{0, 0, 3}, 1.5, {0, 0, 1}},             // beyond the top cap, on the axis
        {{2, 0, 0}, 1.5, {1, 0, 0}},             // beside the cylinder
        {{0, 0.2, 0.5}, -0.3, {0, 1, 0}},        // inside the cylinder
        {{0.3, 0, 1.4}, 0.0, {0.6, 0, 0.8}},     // on the top hemisphere
        {{0, -0.4, -1.3}, 0.0, {0, -0.8, -0.6}}, // on the bottom hemisphere
        {{0, 0, 0.3}, -0.5, {1, 0, 0}},          // on the axis: the documented choice
    };
    for (const Case& c : cases)
    {
        const DistanceSample sample = capsuleDistance(capsule, c.point);
        EXPECT_NEAR(sample.phi, c.phi, kTol) << c.point.transpose();
        expectVecNear(sample.gradient, c.gradient);
    }
}

TEST(CapsuleDistance, StepAlongTheGradientLandsOnTheSurface)
{
    const Capsule capsule{0.2, 0.6};
    std::mt19937 rng(7);
    std::uniform_real_distribution<Real> coordinate(-1.0, 1.0);
    for (int i = 0; i < 200; ++i)
    {
        const Vec3 p(coordinate(rng), coordinate(rng), coordinate(rng));
        const DistanceSample sample = capsuleDistance(capsule, p);
        EXPECT_NEAR(sample.gradient.norm(), 1.0, kTol);
        const Vec3 onSurface = p - sample.phi * sample.gradient;
        EXPECT_NEAR(capsuleDistance(capsule, onSurface).phi, 0.0, kTol);
    }
}

TEST(CapsuleContacts, LyingOnThePlaneGivesBothEnds)
{
    const Capsule capsule{0.1, 0.5};
    const auto points = collide(capsule, at({0, 0, 0.09}, lyingAlongX()), Plane{}, at(Vec3::Zero()));
    ASSERT_EQ(points.size(), 2u);
    for (const ContactPoint& p : points)
    {
        EXPECT_NEAR(p.phi, -0.01, kTol);
        expectVecNear(p.normal, Vec3::UnitZ());
        EXPECT_NEAR(std::abs(p.point.x()), 0.5, kTol);
        EXPECT_NEAR(p.point.z(), -0.005, kTol);
    }
    EXPECT_NE(points[0].point.x(), points[1].point.x());
}

TEST(CapsuleContacts, StandingOnThePlaneGivesTheLowerEnd)
{
    const Capsule capsule{0.1, 0.5};
    const auto points = collide(Plane{}, at(Vec3::Zero()), capsule, at({0, 0, 0.59}));
    ASSERT_EQ(points.size(), 1u);
    EXPECT_NEAR(points[0].phi, -0.01, kTol);
    expectVecNear(points[0].normal, -Vec3::UnitZ()); // from the capsule (B) toward the plane (A)
    expectVecNear(points[0].point, Vec3(0, 0, -0.005));
}

TEST(CapsuleContacts, LyingOnABoxFaceGivesTwoPoints)
{
    const Capsule capsule{0.1, 0.5};
    const Box box{Vec3(1.0, 1.0, 0.5)};
    const auto points = collide(capsule, at({0.2, 0.3, 0.59}, lyingAlongX()), box, at(Vec3::Zero()));
    ASSERT_EQ(points.size(), 2u);
    for (const ContactPoint& p : points)
    {
        EXPECT_NEAR(p.phi, -0.01, kTol);
        expectVecNear(p.normal, Vec3::UnitZ());
        EXPECT_NEAR(p.point.z(), 0.495, kTol);
        EXPECT_NEAR(p.point.y(), 0.3, kTol);
    }
    EXPECT_NEAR(std::min(points[0].point.x(), points[1].point.x()), -0.3, kTol);
    EXPECT_NEAR(std::max(points[0].point.x(), points[1].point.x()), 0.7, kTol);
}

TEST(CapsuleContacts, BoxEdgeUnderTheMiddleGivesOnePoint)
{
    // a cube turned 45 degrees about y has its top edge along y at height sqrt(2)/2; a capsule
    // lying across it along x touches only there
    const Capsule capsule{0.2, 1.0};
    const Box box{Vec3::Constant(0.5)};
    const Real edge = std::sqrt(0.5);
    const Pose boxPose = at(Vec3::Zero(), Quat(Eigen::AngleAxisd(std::numbers::pi / 4.0, Vec3::UnitY())));
    const auto points = collide(capsule, at({0, 0, edge + 0.19}, lyingAlongX()), box, boxPose);
    ASSERT_EQ(points.size(), 1u);
    EXPECT_NEAR(points[0].phi, -0.01, 1e-12);
    expectVecNear(points[0].normal, Vec3::UnitZ(), 1e-12);
    expectVecNear(points[0].point, Vec3(0, 0, edge - 0.005), 1e-12);
}

// The least box distance along a segment, found from the stretches where the distance is smooth,
// against dense sampling: never above any sample, and below the least sample by no more than the
// distance can fall between two samples (it is 1-Lipschitz). Segments from outside, through the
// box, and wholly inside, where the least lies where two faces are equally near.
TEST(CapsuleContacts, LeastBoxDistanceAlongASegmentMatchesDenseSampling)
{
    const Vec3 half(0.3, 0.2, 0.1);
    std::mt19937 random(7);
    std::uniform_real_distribution<Real> coordinate(-0.6, 0.6);
    constexpr int kSamples = 20000;
    for (int trial = 0; trial < 500; ++trial)
    {
        const Real reach = trial % 3 == 0 ? 0.3 : 1.0; // a third of them short, often wholly inside
        const Vec3 start(coordinate(random) * reach, coordinate(random) * reach, coordinate(random) * reach);
        const Vec3 along = Vec3(coordinate(random), coordinate(random), coordinate(random)) * reach;
        const LeastAlong least = leastBoxDistanceAlong(half, start, along);
        ASSERT_GE(least.s, 0.0);
        ASSERT_LE(least.s, 1.0);
        EXPECT_NEAR(least.phi, boxDistance(half, start + least.s * along).phi, 1e-15);
        Real sampled = std::numeric_limits<Real>::infinity();
        for (int k = 0; k <= kSamples; ++k)
        {
            sampled = std::min(sampled, boxDistance(half, start + (Real(k) / kSamples) * along).phi);
        }
        EXPECT_LE(least.phi, sampled + 1e-15) << "trial " << trial;
        EXPECT_GE(least.phi, sampled - along.norm() / kSamples) << "trial " << trial;
    }
}

TEST(CapsuleContacts, LeastBoxDistanceAlongASegmentThroughTheCentreIsMinusTheLeastHalfExtent)
{
    // through the middle of the box along x: deepest where the segment is farthest from every face,
    // the whole stretch |x| <= 0.2 at -0.1 (the z faces are nearest there)
    const Vec3 half(0.3, 0.2, 0.1);
    const LeastAlong least = leastBoxDistanceAlong(half, Vec3(-1.0, 0.0, 0.0), Vec3(2.0, 0.0, 0.0));
    EXPECT_NEAR(least.phi, -0.1, 1e-15);
    EXPECT_LE(std::abs(-1.0 + 2.0 * least.s), 0.2 + 1e-15);
}

TEST(CapsuleContacts, SphereAgainstTheCylinder)
{
    const auto points = collide(Capsule{0.5, 1.0}, at(Vec3::Zero()), Sphere{0.5}, at({0.9, 0, 0.5}));
    ASSERT_EQ(points.size(), 1u);
    EXPECT_NEAR(points[0].phi, -0.1, kTol);
    expectVecNear(points[0].normal, -Vec3::UnitX());
    expectVecNear(points[0].point, Vec3(0.45, 0, 0.5));
}

TEST(CapsuleContacts, CrossedCapsulesTouchAtTheClosestPointsOfTheAxes)
{
    const auto points =
        collide(Capsule{0.3, 1.0}, at(Vec3::Zero()), Capsule{0.2, 1.0}, at({0, 0.48, 0.2}, lyingAlongX()));
    ASSERT_EQ(points.size(), 1u);
    EXPECT_NEAR(points[0].phi, -0.02, kTol);
    expectVecNear(points[0].normal, -Vec3::UnitY());
    expectVecNear(points[0].point, Vec3(0, 0.29, 0.2));
}

TEST(CapsuleContacts, ParallelCapsulesTouchAtBothEndsOfTheOverlap)
{
    const Capsule capsule{0.25, 1.0};
    const auto points = collide(capsule, at(Vec3::Zero(), lyingAlongX()), capsule, at({0.3, 0, 0.45}, lyingAlongX()));
    ASSERT_EQ(points.size(), 2u);
    for (const ContactPoint& p : points)
    {
        EXPECT_NEAR(p.phi, -0.05, kTol);
        expectVecNear(p.normal, -Vec3::UnitZ());
    }
    EXPECT_NEAR(std::min(points[0].point.x(), points[1].point.x()), -0.7, kTol);
    EXPECT_NEAR(std::max(points[0].point.x(), points[1].point.x()), 1.0, kTol);
}

TEST(CapsuleContacts, SwappedOrderFlipsTheNormals)
{
    const Capsule capsule{0.1, 0.5};
    const Pose lying = at({0.1, 0, 0.09}, lyingAlongX());
    const std::vector<std::pair<Shape, Pose>> others = {
        {Plane{}, at(Vec3::Zero())},
        {Box{Vec3(1, 1, 0.5)}, at({0, 0, -0.5})},
        {Sphere{0.2}, at({0.3, 0, -0.2})},
        {Capsule{0.1, 0.3}, at({0, 0.05, -0.1})},
    };
    for (const auto& [other, pose] : others)
    {
        const auto forward = collide(capsule, lying, other, pose);
        const auto backward = collide(other, pose, capsule, lying);
        ASSERT_FALSE(forward.empty());
        ASSERT_EQ(forward.size(), backward.size());
        for (std::size_t i = 0; i < forward.size(); ++i)
        {
            expectVecNear(forward[i].point, backward[i].point);
            expectVecNear(forward[i].normal, -backward[i].normal);
            EXPECT_EQ(forward[i].phi, backward[i].phi);
        }
    }
}

TEST(CapsuleContacts, ApartGivesNothing)
{
    const Capsule capsule{0.1, 0.5};
    EXPECT_TRUE(collide(capsule, at({0, 0, 0.2}, lyingAlongX()), Plane{}, at(Vec3::Zero())).empty());
    EXPECT_TRUE(collide(capsule, at({0, 0, 2}), Box{Vec3::Constant(0.5)}, at(Vec3::Zero())).empty());
    EXPECT_TRUE(collide(capsule, at({0, 0, 2}), capsule, at(Vec3::Zero())).empty());
}

} // namespace
} // namespace impulse
