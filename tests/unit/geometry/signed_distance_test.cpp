// SPDX-License-Identifier: MIT
// Analytic signed distances and their gradients against hand-computed values, and the deepest point
// of a segment in a box against brute-force sampling.
#include "geometry/signed_distance.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>

namespace impulse
{
namespace
{

// Hand-computed values involve a square root at most: a few ulps of agreement.
constexpr Real kTol = 1e-14;

void expectVecNear(const Vec3& actual, const Vec3& expected, Real tol)
{
    EXPECT_LT((actual - expected).norm(), tol)
        << "actual   " << actual.transpose() << "\nexpected " << expected.transpose();
}

// ---- sphere ----

TEST(SignedDistance, SphereOutsidePointIsDistanceToSurfaceAlongRadius)
{
    const DistanceSample s = sphereDistance(1.0, Vec3(0.0, 0.0, 3.0));
    EXPECT_NEAR(s.phi, 2.0, kTol);
    expectVecNear(s.gradient, Vec3::UnitZ(), kTol);
}

TEST(SignedDistance, SphereInsidePointIsNegativeWithOutwardRadialGradient)
{
    // |p| = 0.5
    const DistanceSample s = sphereDistance(1.0, Vec3(0.3, -0.4, 0.0));
    EXPECT_NEAR(s.phi, -0.5, kTol);
    expectVecNear(s.gradient, Vec3(0.6, -0.8, 0.0), kTol);
}

TEST(SignedDistance, SphereSurfacePointIsZero)
{
    const Vec3 p = Vec3(1.0, 2.0, 2.0) / 3.0 * 1.5;
    const DistanceSample s = sphereDistance(1.5, p);
    EXPECT_NEAR(s.phi, 0.0, kTol);
    expectVecNear(s.gradient, Vec3(1.0, 2.0, 2.0) / 3.0, kTol);
}

TEST(SignedDistance, SphereCentreIsMinusRadiusWithUnitGradient)
{
    const DistanceSample s = sphereDistance(0.8, Vec3::Zero());
    EXPECT_EQ(s.phi, -0.8);
    EXPECT_NEAR(s.gradient.norm(), 1.0, kTol);
}

// ---- box, half extents (1, 2, 3) ----

const Vec3 kHalf(1.0, 2.0, 3.0);

TEST(SignedDistance, BoxOutsideFaceRegionIsDistanceToFace)
{
    const DistanceSample s = boxDistance(kHalf, Vec3(3.0, 0.5, -1.0));
    EXPECT_NEAR(s.phi, 2.0, kTol);
    expectVecNear(s.gradient, Vec3::UnitX(), kTol);

    const DistanceSample below = boxDistance(kHalf, Vec3(0.2, -0.3, -3.5));
    EXPECT_NEAR(below.phi, 0.5, kTol);
    expectVecNear(below.gradient, -Vec3::UnitZ(), kTol);
}

TEST(SignedDistance, BoxOutsideEdgeRegionIsDistanceToEdge)
{
    // nearest point (1, 2, 0.5) on the x-y edge; offset (1, 1, 0)
    const DistanceSample s = boxDistance(kHalf, Vec3(2.0, 3.0, 0.5));
    EXPECT_NEAR(s.phi, std::sqrt(2.0), kTol);
    expectVecNear(s.gradient, Vec3(1.0, 1.0, 0.0) / std::sqrt(2.0), kTol);
}

TEST(SignedDistance, BoxOutsideCornerRegionIsDistanceToCorner)
{
    // nearest point (-1, -2, -3); offset (-1, -1, -2)
    const DistanceSample s = boxDistance(kHalf, Vec3(-2.0, -3.0, -5.0));
    EXPECT_NEAR(s.phi, std::sqrt(6.0), kTol);
    expectVecNear(s.gradient, Vec3(-1.0, -1.0, -2.0) / std::sqrt(6.0), kTol);
}

TEST(SignedDistance, BoxInsideGradientIsNearestFaceNormal)
{
    // distances to the faces x = 1, y = 2, z = 3 and their negatives pick the nearest
    struct Case
    {
        Vec3 point;
        Real phi;
        Vec3 normal;
    };
    const Case cases[] = {
        {Vec3(0.5, 0.0, 0.0), -0.5, Vec3::UnitX()},   {Vec3(-0.7, 0.5, 1.0), -0.3, -Vec3::UnitX()},
        {Vec3(0.0, -1.5, 0.0), -0.5, -Vec3::UnitY()}, {Vec3(0.1, 1.8, -2.5), -0.2, Vec3::UnitY()},
        {Vec3(0.0, 0.0, 2.8), -0.2, Vec3::UnitZ()},   {Vec3(0.5, 1.0, -2.9), -0.1, -Vec3::UnitZ()},
    };
    for (const Case& c : cases)
    {
        SCOPED_TRACE(testing::Message() << "point " << c.point.transpose());
        const DistanceSample s = boxDistance(kHalf, c.point);
        EXPECT_NEAR(s.phi, c.phi, kTol);
        expectVecNear(s.gradient, c.normal, 0.0 + kTol);
    }
}

TEST(SignedDistance, BoxCentreIsMinusSmallestHalfExtent)
{
    const DistanceSample s = boxDistance(kHalf, Vec3::Zero());
    EXPECT_EQ(s.phi, -1.0);
    // the nearest faces are x = +-1
    EXPECT_EQ(std::abs(s.gradient.x()), 1.0);
    EXPECT_EQ(s.gradient.y(), 0.0);
    EXPECT_EQ(s.gradient.z(), 0.0);
}

TEST(SignedDistance, BoxFacePointIsZeroWithFaceNormal)
{
    const DistanceSample s = boxDistance(kHalf, Vec3(0.3, 2.0, -1.0));
    EXPECT_EQ(s.phi, 0.0);
    expectVecNear(s.gradient, Vec3::UnitY(), 0.0 + kTol);
}

TEST(SignedDistance, BoxEdgeAndCornerPointsAreZeroWithAnAdjacentFaceNormal)
{
    // on an edge or a corner the gradient is one of the adjacent face normals: a unit axis vector
    // whose sign agrees with the point
    const Vec3 points[] = {Vec3(1.0, 2.0, 0.0), Vec3(-1.0, 0.5, 3.0), Vec3(0.0, -2.0, -3.0), Vec3(1.0, -2.0, 3.0),
                           Vec3(-1.0, -2.0, -3.0)};
    for (const Vec3& p : points)
    {
        SCOPED_TRACE(testing::Message() << "point " << p.transpose());
        const DistanceSample s = boxDistance(kHalf, p);
        EXPECT_EQ(s.phi, 0.0);
        EXPECT_EQ(s.gradient.cwiseAbs().sum(), 1.0);
        EXPECT_EQ(s.gradient.cwiseAbs().maxCoeff(), 1.0);
        int axis = 0;
        s.gradient.cwiseAbs().maxCoeff(&axis);
        EXPECT_EQ(std::abs(p[axis]), kHalf[axis]) << "normal of a face the point is not on";
        EXPECT_GT(s.gradient[axis] * p[axis], 0.0) << "inward normal";
    }
}

TEST(SignedDistance, BoxGradientMatchesFiniteDifferencesAwayFromCreases)
{
    // phi is smooth off the medial surface (inside) and off the face planes' extensions (outside):
    // central differences with step 1e-6 agree with the analytic gradient to O(step) there, and
    // phi is linear or a Euclidean norm in those regions so the error is round-off, ~1e-16/1e-6
    std::mt19937 rng(20240611u);
    std::uniform_real_distribution<Real> coordinate(-5.0, 5.0);
    const Real step = 1e-6;
    int checked = 0;
    for (int trial = 0; trial < 2000; ++trial)
    {
        const Vec3 p(coordinate(rng), coordinate(rng), coordinate(rng));
        // skip points within 10 steps of a crease, where the difference straddles two pieces
        const Vec3 q = p.cwiseAbs() - kHalf;
        Vec3 sorted = q;
        std::sort(sorted.data(), sorted.data() + 3);
        const bool nearMedial = sorted[2] < 0.0 && sorted[2] - sorted[1] < 10.0 * step;
        const bool nearFacePlane = (q.cwiseAbs().array() < 10.0 * step).any();
        if (nearMedial || nearFacePlane)
        {
            continue;
        }
        const DistanceSample s = boxDistance(kHalf, p);
        Vec3 numeric;
        for (int i = 0; i < 3; ++i)
        {
            Vec3 e = Vec3::Zero();
            e[i] = step;
            numeric[i] = (boxDistance(kHalf, p + e).phi - boxDistance(kHalf, p - e).phi) / (2.0 * step);
        }
        EXPECT_NEAR(s.gradient.norm(), 1.0, kTol);
        EXPECT_LT((numeric - s.gradient).norm(), 1e-8) << "at " << p.transpose();
        ++checked;
    }
    EXPECT_GT(checked, 1900);
}

TEST(SignedDistance, BoxStepAgainstGradientLandsOnSurface)
{
    // p - phi grad(phi) is the nearest surface point: phi there is zero (exact closest-point property
    // of a signed distance function)
    std::mt19937 rng(7u);
    std::uniform_real_distribution<Real> coordinate(-5.0, 5.0);
    for (int trial = 0; trial < 1000; ++trial)
    {
        const Vec3 p(coordinate(rng), coordinate(rng), coordinate(rng));
        const DistanceSample s = boxDistance(kHalf, p);
        const Vec3 onSurface = p - s.phi * s.gradient;
        // |phi| <= ~9, so the projection carries round-off of a few 1e-15
        EXPECT_NEAR(boxDistance(kHalf, onSurface).phi, 0.0, 1e-13) << "from " << p.transpose();
    }
}

// ---- plane ----

TEST(SignedDistance, PlaneIsHeightAboveOffsetAlongNormal)
{
    const Plane plane{Vec3::UnitZ(), 2.0};
    const DistanceSample above = planeDistance(plane, Vec3(1.0, -4.0, 5.0));
    EXPECT_EQ(above.phi, 3.0);
    EXPECT_EQ(above.gradient, Vec3::UnitZ());
    const DistanceSample below = planeDistance(plane, Vec3(7.0, 3.0, 1.5));
    EXPECT_EQ(below.phi, -0.5);
    EXPECT_EQ(below.gradient, Vec3::UnitZ());
}

TEST(SignedDistance, TiltedPlaneDistanceIsProjectionOnNormal)
{
    const Vec3 n = Vec3(1.0, 1.0, 0.0).normalized();
    const Plane plane{n, -0.5};
    // n . (1, 0, 3) = 1/sqrt2; minus offset -0.5
    const DistanceSample s = planeDistance(plane, Vec3(1.0, 0.0, 3.0));
    EXPECT_NEAR(s.phi, 1.0 / std::sqrt(2.0) + 0.5, kTol);
    expectVecNear(s.gradient, n, kTol);
}

} // namespace
} // namespace impulse
