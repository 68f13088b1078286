// SPDX-License-Identifier: MIT
// The shape-pair table of the narrow phase: depth, normal (from B toward A) and point of every sample
// against hand-computed values, the swapped-order convention, and completeness of the box-box
// sampling against brute force.
#include "collision/narrow_phase.hpp"
#include "geometry/signed_distance.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <random>
#include <vector>

namespace impulse
{
namespace
{

// Positions and depths below come from a few additions, products and one rotation: agreement to
// 1e-12 m on metre-sized shapes leaves room for round-off of the rotations and nothing else.
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

Quat rotation(Real angle, const Vec3& axis)
{
    return Quat(Eigen::AngleAxisd(angle, axis.normalized()));
}

void expectVecNear(const Vec3& actual, const Vec3& expected, Real tol = kTol)
{
    EXPECT_LT((actual - expected).norm(), tol)
        << "actual   " << actual.transpose() << "\nexpected " << expected.transpose();
}

Real angleBetween(const Vec3& u, const Vec3& v)
{
    return std::atan2(u.cross(v).norm(), u.dot(v));
}

// The samples of (b, a) must be those of (a, b) with the normal reversed: same point, same depth.
void expectSwappedOrderFlipsNormals(const Shape& a, const Pose& poseA, const Shape& b, const Pose& poseB,
                                    Real threshold)
{
    const std::vector<ContactPoint> forward = collide(a, poseA, b, poseB, threshold);
    const std::vector<ContactPoint> backward = collide(b, poseB, a, poseA, threshold);
    ASSERT_EQ(forward.size(), backward.size());
    ASSERT_FALSE(forward.empty()) << "the configuration is meant to touch";
    std::vector<bool> used(backward.size(), false);
    for (const ContactPoint& f : forward)
    {
        bool matched = false;
        for (std::size_t k = 0; k < backward.size() && !matched; ++k)
        {
            const ContactPoint& g = backward[k];
            if (!used[k] && (f.point - g.point).norm() < kTol && std::abs(f.phi - g.phi) < kTol &&
                (f.normal + g.normal).norm() < kTol)
            {
                used[k] = true;
                matched = true;
            }
        }
        EXPECT_TRUE(matched) << "no swapped counterpart for point " << f.point.transpose() << " normal "
                             << f.normal.transpose() << " phi " << f.phi;
    }
}

// ---- sphere - sphere ----

TEST(NarrowPhase, SphereSphereDepthIsCentreDistanceMinusRadii)
{
    const Sphere a{1.0};
    const Sphere b{1.0};
    const auto samples = collide(a, at(Vec3(0.0, 0.0, 1.8)), b, at(Vec3::Zero()));
    ASSERT_EQ(samples.size(), 1u);
    EXPECT_NEAR(samples[0].phi, 1.8 - 2.0, kTol);
    expectVecNear(samples[0].normal, Vec3::UnitZ());
    // the overlap spans z in [0.8, 1.0] (bottom of A to top of B): its middle
    expectVecNear(samples[0].point, Vec3(0.0, 0.0, 0.9));
}

TEST(NarrowPhase, SphereSphereNormalPointsFromBTowardA)
{
    // centres 3 apart along (1, 2, 2)/3, radii 2 and 1.5
    const Vec3 direction = Vec3(1.0, 2.0, 2.0) / 3.0;
    const Vec3 centreB(0.5, -1.0, 2.0);
    const auto samples = collide(Sphere{2.0}, at(centreB + 3.0 * direction), Sphere{1.5}, at(centreB));
    ASSERT_EQ(samples.size(), 1u);
    EXPECT_NEAR(samples[0].phi, -0.5, kTol);
    expectVecNear(samples[0].normal, direction);
    // overlap from A's near surface (3 - 2 = 1 from B's centre) to B's surface (1.5): middle at 1.25
    expectVecNear(samples[0].point, centreB + 1.25 * direction);
}

TEST(NarrowPhase, SeparatedSpheresReportOnlyWithinThreshold)
{
    const Pose poseA = at(Vec3(2.1, 0.0, 0.0));
    const Pose poseB = at(Vec3::Zero());
    EXPECT_TRUE(collide(Sphere{1.0}, poseA, Sphere{1.0}, poseB, 0.0).empty());
    EXPECT_TRUE(collide(Sphere{1.0}, poseA, Sphere{1.0}, poseB, 0.1).empty()); // phi = 0.1 is not < 0.1
    const auto near = collide(Sphere{1.0}, poseA, Sphere{1.0}, poseB, 0.2);
    ASSERT_EQ(near.size(), 1u);
    EXPECT_NEAR(near[0].phi, 0.1, kTol);
    expectVecNear(near[0].normal, Vec3::UnitX());
}

// ---- sphere - plane ----

TEST(NarrowPhase, SpherePlaneDepthIsHeightMinusRadius)
{
    const auto samples = collide(Sphere{0.5}, at(Vec3(0.3, -0.2, 0.4)), Plane{}, at(Vec3::Zero()));
    ASSERT_EQ(samples.size(), 1u);
    EXPECT_NEAR(samples[0].phi, -0.1, kTol);
    expectVecNear(samples[0].normal, Vec3::UnitZ());
    // the sphere's own lowest point (z = -0.1), the material point that rolls on the plane
    expectVecNear(samples[0].point, Vec3(0.3, -0.2, -0.1));
}

TEST(NarrowPhase, SpherePlaneUsesThePlaneBodyPose)
{
    // plane body at height 1 tilted 30 degrees about x; its local +z normal turns to (0, -sin, cos)
    const Real tilt = std::numbers::pi / 6.0;
    const Pose planePose = at(Vec3(0.0, 0.0, 1.0), rotation(tilt, Vec3::UnitX()));
    const Vec3 normal(0.0, -std::sin(tilt), std::cos(tilt));
    const Vec3 centre = Vec3(2.0, 0.0, 1.0) + 0.3 * normal;
    const auto samples = collide(Sphere{0.5}, at(centre), Plane{Vec3::UnitZ(), 0.0}, planePose);
    ASSERT_EQ(samples.size(), 1u);
    EXPECT_NEAR(samples[0].phi, -0.2, kTol);
    expectVecNear(samples[0].normal, normal);
}

TEST(NarrowPhase, SphereAbovePlaneIsNotReported)
{
    EXPECT_TRUE(collide(Sphere{0.5}, at(Vec3(0.0, 0.0, 0.6)), Plane{}, at(Vec3::Zero())).empty());
}

// ---- sphere - box, box half extents (1, 1, 1) ----

TEST(NarrowPhase, SphereOutsideBoxFaceUsesFaceNormal)
{
    const auto samples = collide(Sphere{0.5}, at(Vec3(1.3, 0.2, -0.1)), Box{Vec3::Ones()}, at(Vec3::Zero()));
    ASSERT_EQ(samples.size(), 1u);
    EXPECT_NEAR(samples[0].phi, 0.3 - 0.5, kTol);
    expectVecNear(samples[0].normal, Vec3::UnitX());
    // the sphere's own point nearest the box, x = 0.8, where it rolls on the face
    expectVecNear(samples[0].point, Vec3(0.8, 0.2, -0.1));
}

TEST(NarrowPhase, SphereOutsideBoxEdgeUsesDirectionFromEdge)
{
    // nearest box point is on the edge x = y = 1, at distance 0.3 sqrt 2
    const auto samples = collide(Sphere{0.5}, at(Vec3(1.3, 1.3, 0.4)), Box{Vec3::Ones()}, at(Vec3::Zero()));
    ASSERT_EQ(samples.size(), 1u);
    EXPECT_NEAR(samples[0].phi, 0.3 * std::sqrt(2.0) - 0.5, kTol);
    expectVecNear(samples[0].normal, Vec3(1.0, 1.0, 0.0) / std::sqrt(2.0));
}

TEST(NarrowPhase, SphereCentreInsideBoxUsesNearestFace)
{
    // centre 0.8 below the +x face; every other face is farther
    const auto samples = collide(Sphere{0.5}, at(Vec3(0.2, 0.1, 0.0)), Box{Vec3::Ones()}, at(Vec3::Zero()));
    ASSERT_EQ(samples.size(), 1u);
    EXPECT_NEAR(samples[0].phi, -0.8 - 0.5, kTol);
    expectVecNear(samples[0].normal, Vec3::UnitX());
}

TEST(NarrowPhase, SphereBoxNormalFollowsBoxRotation)
{
    // box (2, 1, 1) turned 90 degrees about z: its local -y face now faces world +x at x = 1
    const Pose boxPose = at(Vec3::Zero(), rotation(std::numbers::pi / 2.0, Vec3::UnitZ()));
    const auto samples = collide(Sphere{0.5}, at(Vec3(1.3, 0.0, 0.0)), Box{Vec3(2.0, 1.0, 1.0)}, boxPose);
    ASSERT_EQ(samples.size(), 1u);
    EXPECT_NEAR(samples[0].phi, -0.2, kTol);
    expectVecNear(samples[0].normal, Vec3::UnitX());
}

// ---- box - plane ----

TEST(NarrowPhase, BoxRestingFlatReportsItsFourBottomCornersAtZeroDepth)
{
    const Box box{Vec3(0.5, 0.3, 0.2)};
    const auto samples = collide(box, at(Vec3(1.0, 2.0, 0.2)), Plane{}, at(Vec3::Zero()), 1e-6);
    ASSERT_EQ(samples.size(), 4u);
    for (const ContactPoint& c : samples)
    {
        EXPECT_NEAR(c.phi, 0.0, kTol);
        expectVecNear(c.normal, Vec3::UnitZ());
        EXPECT_NEAR(c.point.z(), 0.0, kTol);
        EXPECT_NEAR(std::abs(c.point.x() - 1.0), 0.5, kTol);
        EXPECT_NEAR(std::abs(c.point.y() - 2.0), 0.3, kTol);
    }
}

TEST(NarrowPhase, TiltedBoxReportsLowestCornersAtTheirDepth)
{
    // box tilted by 0.3 rad about y (local x turns to (cos, 0, -sin)): the corners (hx, +-hy, -hz) are
    // lowest, at z_c - hx sin - hz cos, the others hx sin or hz cos higher
    const Box box{Vec3(0.5, 0.3, 0.2)};
    const Real tilt = 0.3;
    const Real lowest = 0.5 * std::sin(tilt) + 0.2 * std::cos(tilt);
    const Real depth = 0.05;
    const Pose pose = at(Vec3(0.0, 0.0, lowest - depth), rotation(tilt, Vec3::UnitY()));
    const auto samples = collide(box, pose, Plane{}, at(Vec3::Zero()));
    ASSERT_EQ(samples.size(), 2u);
    for (const ContactPoint& c : samples)
    {
        EXPECT_NEAR(c.phi, -depth, kTol);
        expectVecNear(c.normal, Vec3::UnitZ());
        EXPECT_NEAR(c.point.z(), -depth, kTol);
        // a corner of the box: its local coordinates are +-half extents
        expectVecNear(pose.toLocal(c.point).cwiseAbs(), box.halfExtents);
        EXPECT_GT(pose.toLocal(c.point).x(), 0.0);
    }
}

// ---- box - box ----

TEST(NarrowPhase, SmallerBoxSunkIntoLargerReportsFootprintCornersWithUpwardNormal)
{
    // A (half 0.5) sits 0.05 deep in the top face of B (half (1, 1, 0.5)). The contact patch is A's
    // square footprint: one sample at each of its corners, 0.05 deep, normal +z. Whether a sample is
    // A's corner (z = 0.45, inside B) or the point of B's top face above it (z = 0.5, inside A) is the
    // routine's choice; either lies in the overlap slab.
    const Box a{Vec3::Constant(0.5)};
    const Box b{Vec3(1.0, 1.0, 0.5)};
    const auto samples = collide(a, at(Vec3(0.1, -0.2, 0.95)), b, at(Vec3::Zero()));
    ASSERT_EQ(samples.size(), 4u);
    int corners = 0;
    for (const ContactPoint& c : samples)
    {
        EXPECT_NEAR(c.phi, -0.05, kTol);
        expectVecNear(c.normal, Vec3::UnitZ());
        EXPECT_GE(c.point.z(), 0.45 - kTol);
        EXPECT_LE(c.point.z(), 0.5 + kTol);
        EXPECT_NEAR(std::abs(c.point.x() - 0.1), 0.5, kTol);
        EXPECT_NEAR(std::abs(c.point.y() + 0.2), 0.5, kTol);
        corners |= 1 << ((c.point.x() > 0.1 ? 2 : 0) + (c.point.y() > -0.2 ? 1 : 0));
    }
    EXPECT_EQ(corners, 0b1111) << "all four footprint corners";
}

TEST(NarrowPhase, OffsetEqualBoxesSunkFaceOnFaceReportUpwardNormal)
{
    // equal cubes, A shifted (0.2, 0.3) sideways and 0.05 down into B: A's corner (-0.3, -0.2, 0.45) is
    // 0.05 below B's top and 0.2 inside its sides, B's corner (0.5, 0.5, 0.5) 0.05 above A's bottom
    const Box cube{Vec3::Constant(0.5)};
    const auto samples = collide(cube, at(Vec3(0.2, 0.3, 0.95)), cube, at(Vec3::Zero()));
    ASSERT_FALSE(samples.empty());
    for (const ContactPoint& c : samples)
    {
        EXPECT_NEAR(c.phi, -0.05, kTol);
        expectVecNear(c.normal, Vec3::UnitZ());
    }
}

TEST(NarrowPhase, AlignedEqualBoxesSunkFaceOnFaceReportPenetrationWithUpwardNormal)
{
    // the stacking case: equal cubes, exactly aligned, A 0.05 into B's top. Every corner of A lies on
    // a vertical edge of B (and vice versa), where the depth below B's top face is 0.05 but the
    // distance to the side faces is 0. The overlap must still be seen, and pushing A up is the only
    // direction that separates them.
    const Box cube{Vec3::Constant(0.5)};
    const auto samples = collide(cube, at(Vec3(0.0, 0.0, 0.95)), cube, at(Vec3::Zero()));
    ASSERT_FALSE(samples.empty()) << "a 0.05 m interpenetration of two equal boxes is not detected";
    bool upward = false;
    for (const ContactPoint& c : samples)
    {
        upward = upward || (c.phi < 0.0 && angleBetween(c.normal, Vec3::UnitZ()) < 1e-9);
    }
    EXPECT_TRUE(upward) << "no penetrating sample with normal +z";
}

TEST(NarrowPhase, AlignedEqualBoxesRestingFaceOnFaceHaveVerticalNormals)
{
    // the same stack exactly touching, as the contact pass sees it with its small positive threshold:
    // a horizontal normal would let the upper box sink
    const Box cube{Vec3::Constant(0.5)};
    const auto samples = collide(cube, at(Vec3(0.0, 0.0, 1.0)), cube, at(Vec3::Zero()), 1e-6);
    ASSERT_FALSE(samples.empty());
    for (const ContactPoint& c : samples)
    {
        EXPECT_LT(angleBetween(c.normal, Vec3::UnitZ()), 1e-9)
            << "point " << c.point.transpose() << " normal " << c.normal.transpose();
    }
}

// Two long thin sticks crossing: A along x above, B along y below. With A turned `tiltA` about x and B
// turned `tiltB` about y, A's lowest part is an edge along x and B's highest an edge along y (or B's
// top face when tiltB = 0). A is lowered `overlap` into B. Returns the poses.
struct Crossing
{
    Box a{Vec3(2.0, 0.1, 0.1)};
    Box b{Vec3(0.1, 2.0, 0.1)};
    Pose poseA;
    Pose poseB;
};

Crossing crossingSticks(Real tiltA, Real tiltB, Real overlap)
{
    Crossing c;
    const Real bottomOfA = 0.1 * (std::cos(tiltA) + std::sin(tiltA));
    const Real topOfB = 0.1 * (std::cos(tiltB) + std::sin(tiltB));
    c.poseB = at(Vec3::Zero(), rotation(tiltB, Vec3::UnitY()));
    c.poseA = at(Vec3(0.0, 0.0, topOfB + bottomOfA - overlap), rotation(tiltA, Vec3::UnitX()));
    return c;
}

// The configurations below rely on no corner of either box being inside (or on) the other.
void expectNoCornerInside(const Box& a, const Pose& poseA, const Box& b, const Pose& poseB)
{
    for (int i = 0; i < 8; ++i)
    {
        const Vec3 signs((i & 1) ? 1.0 : -1.0, (i & 2) ? 1.0 : -1.0, (i & 4) ? 1.0 : -1.0);
        const Vec3 cornerA = poseA.toWorld(signs.cwiseProduct(a.halfExtents));
        const Vec3 cornerB = poseB.toWorld(signs.cwiseProduct(b.halfExtents));
        ASSERT_GT(boxDistance(b.halfExtents, poseB.toLocal(cornerA)).phi, 0.0);
        ASSERT_GT(boxDistance(a.halfExtents, poseA.toLocal(cornerB)).phi, 0.0);
    }
}

TEST(NarrowPhase, EdgeCrossingFaceWithNoCornerInsideIsDetected)
{
    // A's lower edge (tilted 45 degrees) cuts 0.02 into B's flat top face. The deepest point of that
    // edge is 0.02 below B's top and at least 0.08 from B's sides: phi = -0.02, normal +z.
    const Real overlap = 0.02;
    const Crossing c = crossingSticks(std::numbers::pi / 4.0, 0.0, overlap);
    expectNoCornerInside(c.a, c.poseA, c.b, c.poseB);
    const auto samples = collide(c.a, c.poseA, c.b, c.poseB);
    ASSERT_FALSE(samples.empty());
    const auto deepest = std::min_element(samples.begin(), samples.end(),
                                          [](const ContactPoint& l, const ContactPoint& r) { return l.phi < r.phi; });
    EXPECT_NEAR(deepest->phi, -overlap, kTol);
    expectVecNear(deepest->normal, Vec3::UnitZ());
}

TEST(NarrowPhase, CrossedEdgesWithNoCornerInsideReportVerticalNormalAndTrueDepth)
{
    // A's lower edge (along x) crosses B's upper edge (along y), A lowered 0.02 onto it. No corner is
    // inside either box, so only the edges see the contact. The edge-edge normal is x cross y = +z for
    // every tilt, and lifting A by the overlap separates the sticks, so no sample may be deeper than
    // that. The faces next to the edges are tilted from +z by the stick's tilt (tops) and by
    // pi/2 - tilt (sides): a side face's normal, which sampling the other box's distance at a point of
    // the edge may pick on a tie, would shove A sideways instead of lifting it (nearly horizontally
    // at tilt 0.2).
    const Real overlap = 0.02;
    const Real tilts[][2] = {{std::numbers::pi / 4.0, std::numbers::pi / 4.0},
                             {std::numbers::pi / 6.0, std::numbers::pi / 6.0},
                             {0.2, 0.2},
                             {0.3, 0.1}};
    for (const auto& tilt : tilts)
    {
        SCOPED_TRACE(testing::Message() << "tilts " << tilt[0] << ", " << tilt[1]);
        const Crossing c = crossingSticks(tilt[0], tilt[1], overlap);
        expectNoCornerInside(c.a, c.poseA, c.b, c.poseB);
        const auto samples = collide(c.a, c.poseA, c.b, c.poseB);
        ASSERT_FALSE(samples.empty()) << "crossing edges not detected";
        bool vertical = false;
        for (const ContactPoint& s : samples)
        {
            EXPECT_GE(s.phi, -overlap - kTol) << "deeper than the overlap";
            EXPECT_GT(s.normal.z(), 0.0) << "normal " << s.normal.transpose() << " does not lift A";
            // one rotation and a normalised cross product: round-off ~1e-16 rad
            vertical = vertical || (s.phi < 0.0 && angleBetween(s.normal, Vec3::UnitZ()) < 1e-9);
        }
        EXPECT_TRUE(vertical) << "no penetrating sample with the edge-edge normal +z; first normal "
                              << samples[0].normal.transpose() << ", " << angleBetween(samples[0].normal, Vec3::UnitZ())
                              << " rad from +z";
    }
}

TEST(NarrowPhase, BoxBoxMissesFarApartBoxes)
{
    const Box cube{Vec3::Constant(0.5)};
    EXPECT_TRUE(collide(cube, at(Vec3(0.0, 0.0, 1.2)), cube, at(Vec3::Zero()), 0.1).empty());
    EXPECT_TRUE(collide(cube, at(Vec3(5.0, 0.0, 0.0)), cube, at(Vec3::Zero()), 0.1).empty());
}

// ---- swapped order ----

TEST(NarrowPhase, PlaneSphereFlipsTheSpherePlaneNormal)
{
    expectSwappedOrderFlipsNormals(Sphere{0.5}, at(Vec3(0.3, -0.2, 0.4)), Plane{}, at(Vec3::Zero()), 0.0);
    const auto swapped = collide(Plane{}, at(Vec3::Zero()), Sphere{0.5}, at(Vec3(0.3, -0.2, 0.4)));
    ASSERT_EQ(swapped.size(), 1u);
    expectVecNear(swapped[0].normal, -Vec3::UnitZ());
}

TEST(NarrowPhase, BoxSphereFlipsTheSphereBoxNormal)
{
    const Pose boxPose = at(Vec3(0.1, 0.0, -0.2), rotation(0.4, Vec3(1.0, -1.0, 2.0)));
    expectSwappedOrderFlipsNormals(Sphere{0.5}, at(Vec3(1.0, 0.3, 0.5)), Box{Vec3(1.0, 0.6, 0.4)}, boxPose, 0.0);
}

TEST(NarrowPhase, PlaneBoxFlipsTheBoxPlaneNormal)
{
    // lowest corner at 0.3 - (0.5 sin 0.3 + 0.2 cos 0.3) = -0.04
    const Pose boxPose = at(Vec3(0.0, 0.0, 0.3), rotation(0.3, Vec3::UnitY()));
    expectSwappedOrderFlipsNormals(Box{Vec3(0.5, 0.3, 0.2)}, boxPose, Plane{}, at(Vec3::Zero()), 0.0);
}

TEST(NarrowPhase, BoxBoxSwappedOrderFlipsNormals)
{
    const Pose poseA = at(Vec3(0.3, 0.1, 0.9), rotation(0.5, Vec3(1.0, 2.0, 0.5)));
    expectSwappedOrderFlipsNormals(Box{Vec3(0.5, 0.4, 0.3)}, poseA, Box{Vec3(0.7, 0.6, 0.5)}, at(Vec3::Zero()), 0.0);
}

TEST(NarrowPhase, SphereSphereSwappedOrderFlipsNormal)
{
    expectSwappedOrderFlipsNormals(Sphere{1.0}, at(Vec3(0.5, 1.0, 1.0)), Sphere{0.8}, at(Vec3::Zero()), 0.0);
}

TEST(NarrowPhase, PlanePlaneReportsNothing)
{
    EXPECT_TRUE(collide(Plane{}, at(Vec3::Zero()), Plane{}, at(Vec3::Zero()), 1.0).empty());
}

// ---- conventions over random configurations ----

Quat randomRotation(std::mt19937& rng)
{
    std::normal_distribution<Real> gauss(0.0, 1.0);
    return Quat(gauss(rng), gauss(rng), gauss(rng), gauss(rng)).normalized();
}

TEST(NarrowPhase, EverySampleIsBelowThresholdWithUnitNormal)
{
    std::mt19937 rng(99u);
    std::uniform_real_distribution<Real> size(0.2, 1.0);
    std::uniform_real_distribution<Real> offset(-1.5, 1.5);
    std::uniform_real_distribution<Real> thresholdDist(0.0, 0.2);
    int total = 0;
    for (int trial = 0; trial < 600; ++trial)
    {
        const Shape shapes[] = {Sphere{size(rng)}, Box{Vec3(size(rng), size(rng), size(rng))},
                                Plane{randomRotation(rng) * Vec3::UnitZ(), offset(rng)}};
        const auto kindA = static_cast<std::size_t>(trial % 3);
        const auto kindB = static_cast<std::size_t>((trial / 3) % 3);
        const Pose poseA = at(Vec3(offset(rng), offset(rng), offset(rng)), randomRotation(rng));
        const Pose poseB = at(Vec3(offset(rng), offset(rng), offset(rng)), randomRotation(rng));
        const Real threshold = thresholdDist(rng);
        for (const ContactPoint& c : collide(shapes[kindA], poseA, shapes[kindB], poseB, threshold))
        {
            EXPECT_LT(c.phi, threshold) << "trial " << trial;
            EXPECT_NEAR(c.normal.norm(), 1.0, 1e-14) << "trial " << trial;
            EXPECT_TRUE(c.point.allFinite()) << "trial " << trial;
            ++total;
        }
    }
    EXPECT_GT(total, 100) << "the random configurations should touch often enough to mean something";
}

Real boxPhiWorld(const Box& box, const Pose& pose, const Vec3& p)
{
    return boxDistance(box.halfExtents, pose.toLocal(p)).phi;
}

TEST(NarrowPhase, ApproachingBoxesFirstTouchShallowlyWithPointsInTheOverlap)
{
    // A moves toward B in steps of 5 mm from well apart. At the first step that reports samples the
    // boxes overlap by at most one step (they did not overlap one step earlier), so every penetrating
    // sample must be at most a step deep and lie inside (or on) both boxes: it is a point of A inside
    // B, of B inside A, or between the two. Near the surface that is well defined whatever the method.
    std::mt19937 rng(2024u);
    std::uniform_real_distribution<Real> size(0.1, 1.0);
    std::normal_distribution<Real> gauss(0.0, 1.0);
    constexpr Real kStep = 0.005;
    // coordinates of order 1 through one rotation: round-off ~1e-15
    constexpr Real kRoundOff = 1e-12;
    int touched = 0;
    for (int trial = 0; trial < 300; ++trial)
    {
        const Box a{Vec3(size(rng), size(rng), size(rng))};
        const Box b{Vec3(size(rng), size(rng), size(rng))};
        const Quat qa = randomRotation(rng);
        const Pose poseB = at(Vec3(gauss(rng), gauss(rng), gauss(rng)), randomRotation(rng));
        const Vec3 direction = Vec3(gauss(rng), gauss(rng), gauss(rng)).normalized();
        // start beyond the sum of the bounding radii (at most 2 sqrt 3)
        Real distance = 3.5;
        std::vector<ContactPoint> samples;
        Pose poseA;
        while (samples.empty() && distance > 0.0)
        {
            distance -= kStep;
            poseA = at(poseB.position + distance * direction, qa);
            samples = collide(a, poseA, b, poseB, 0.0);
        }
        ASSERT_FALSE(samples.empty()) << "trial " << trial << ": concentric boxes reported no contact";
        ++touched;
        for (const ContactPoint& c : samples)
        {
            SCOPED_TRACE(testing::Message()
                         << "trial " << trial << " point " << c.point.transpose() << " phi " << c.phi);
            EXPECT_GE(c.phi, -kStep - kRoundOff) << "deeper than the last step can have made it";
            EXPECT_LE(boxPhiWorld(a, poseA, c.point), kRoundOff);
            EXPECT_LE(boxPhiWorld(b, poseB, c.point), kRoundOff);
            // the normal pushes A away from B: it has a component along A's approach reversed
            EXPECT_GT(c.normal.dot(direction), 0.0) << "normal " << c.normal.transpose();
        }
    }
    EXPECT_EQ(touched, 300);
}

TEST(NarrowPhase, BoxBoxReportsAtLeastTheDepthOfEveryCornerAndEdgePoint)
{
    // completeness against brute force: if a corner or a point of an edge of one box is d deep inside
    // the other, some sample is at least d deep. (Separating the boxes takes a translation of at least
    // d, so a depth measured as the least separating translation also satisfies this.)
    std::mt19937 rng(31337u);
    std::uniform_real_distribution<Real> size(0.2, 1.0);
    std::uniform_real_distribution<Real> offset(-1.0, 1.0);
    constexpr int kEdgeSamples = 201;
    int overlapping = 0;
    for (int trial = 0; trial < 200; ++trial)
    {
        const Box boxes[2] = {Box{Vec3(size(rng), size(rng), size(rng))}, Box{Vec3(size(rng), size(rng), size(rng))}};
        const Pose poses[2] = {at(Vec3(offset(rng), offset(rng), offset(rng)), randomRotation(rng)),
                               at(Vec3::Zero(), randomRotation(rng))};
        const auto samples = collide(boxes[0], poses[0], boxes[1], poses[1], 0.0);
        Real reported = 0.0;
        for (const ContactPoint& c : samples)
        {
            reported = std::min(reported, c.phi);
        }
        Real bruteForce = 0.0;
        for (int self = 0; self < 2; ++self)
        {
            const Box& box = boxes[self];
            const Pose& pose = poses[self];
            for (int i = 0; i < 8; ++i)
            {
                for (int axis = 0; axis < 3; ++axis)
                {
                    if (i & (1 << axis))
                    {
                        continue; // each edge once, from its corner with a negative coordinate
                    }
                    const Vec3 signs((i & 1) ? 1.0 : -1.0, (i & 2) ? 1.0 : -1.0, (i & 4) ? 1.0 : -1.0);
                    Vec3 endSigns = signs;
                    endSigns[axis] = 1.0;
                    const Vec3 start = pose.toWorld(signs.cwiseProduct(box.halfExtents));
                    const Vec3 end = pose.toWorld(endSigns.cwiseProduct(box.halfExtents));
                    for (int k = 0; k < kEdgeSamples; ++k)
                    {
                        const Real t = static_cast<Real>(k) / (kEdgeSamples - 1);
                        bruteForce = std::min(bruteForce,
                                              boxPhiWorld(boxes[1 - self], poses[1 - self], start + t * (end - start)));
                    }
                }
            }
        }
        if (bruteForce < 0.0)
        {
            ++overlapping;
        }
        // the sampled points are real points of the edges, so no grid allowance is needed this way
        EXPECT_LE(reported, bruteForce + 1e-12) << "trial " << trial << ": a deeper point was missed";
    }
    EXPECT_GT(overlapping, 50);
}

} // namespace
} // namespace impulse
