// SPDX-License-Identifier: MIT
// The separating axis test of two oriented boxes against sampled points of both, and on boxes
// placed a known gap apart.
#include "geometry/box_queries.hpp"

#include <gtest/gtest.h>

#include <limits>
#include <random>

namespace impulse
{
namespace
{

struct OrientedBox
{
    Vec3 centre;
    Mat3 rotation;
    Vec3 half;

    Vec3 at(const Vec3& unit) const { return centre + rotation * half.cwiseProduct(unit); } ///< unit in [-1, 1]^3
};

OrientedBox randomBox(std::mt19937& random)
{
    std::uniform_real_distribution<Real> unit(-1.0, 1.0);
    std::uniform_real_distribution<Real> size(0.05, 0.5);
    const Quat q = Quat(unit(random), unit(random), unit(random), unit(random)).normalized();
    return {Vec3(unit(random), unit(random), unit(random)), q.toRotationMatrix(),
            Vec3(size(random), size(random), size(random))};
}

bool apart(const OrientedBox& a, const OrientedBox& b, Real margin)
{
    return orientedBoxesApart(a.centre, a.rotation, a.half, b.centre, b.rotation, b.half, margin);
}

TEST(OrientedBoxes, ApartOnlyWhenNoPointOfOneIsWithinTheMarginOfTheOther)
{
    std::mt19937 random(11);
    std::uniform_real_distribution<Real> unit(-1.0, 1.0);
    std::uniform_real_distribution<Real> marginOf(0.0, 0.1);
    int apartPairs = 0;
    for (int trial = 0; trial < 3000; ++trial)
    {
        const OrientedBox a = randomBox(random);
        const OrientedBox b = randomBox(random);
        const Real margin = marginOf(random);
        if (!apart(a, b, margin))
        {
            continue;
        }
        ++apartPairs;
        // corners, edge and face points of both: the nearest pair of boxes meets at such points
        Real nearest = std::numeric_limits<Real>::infinity();
        for (int k = 0; k < 400; ++k)
        {
            Vec3 ua(unit(random), unit(random), unit(random));
            Vec3 ub(unit(random), unit(random), unit(random));
            for (int axis = 0; axis < 3; ++axis)
            {
                // snap some coordinates to the faces, so that corners and edges are drawn too
                ua[axis] = (k + axis) % 3 == 0 ? (ua[axis] < 0.0 ? -1.0 : 1.0) : ua[axis];
                ub[axis] = (k + 2 * axis) % 3 == 0 ? (ub[axis] < 0.0 ? -1.0 : 1.0) : ub[axis];
            }
            nearest = std::min(nearest, (a.at(ua) - b.at(ub)).norm());
        }
        EXPECT_GT(nearest, margin) << "trial " << trial;
    }
    EXPECT_GT(apartPairs, 300); // the test says something
}

TEST(OrientedBoxes, ApartWhenAGapWiderThanTheMarginSeparatesThem)
{
    std::mt19937 random(12);
    for (int trial = 0; trial < 1000; ++trial)
    {
        const OrientedBox a = randomBox(random);
        OrientedBox b = randomBox(random);
        // b on a's +x side, turned with it, a gap of 0.011 away: apart at margin 0.01, not at 0.012
        b.rotation = a.rotation;
        b.centre = a.centre + a.rotation * Vec3(a.half.x() + b.half.x() + 0.011, 0.3 * a.half.y(), 0.0);
        EXPECT_TRUE(apart(a, b, 0.01)) << "trial " << trial;
        EXPECT_FALSE(apart(a, b, 0.012)) << "trial " << trial;
        // two boxes about one centre overlap
        b.centre = a.centre;
        EXPECT_FALSE(apart(a, b, 0.0)) << "trial " << trial;
    }
}

TEST(OrientedBoxes, CrossedEdgesAreToldApartByTheirCrossAxis)
{
    // two long bars crossed at right angles, one above the other: along the vertical (an edge-edge
    // axis of the two bars turned 45 degrees about it, as well as a face axis) the gap is 0.02
    const Mat3 turned = Eigen::AngleAxis<Real>(0.25 * 3.14159265358979, Vec3::UnitX()).toRotationMatrix();
    const Mat3 turnedOther = Eigen::AngleAxis<Real>(0.25 * 3.14159265358979, Vec3::UnitY()).toRotationMatrix();
    const Real reach = 0.1 * std::sqrt(2.0); // a bar of half section 0.1 turned 45 degrees reaches this far
    const Vec3 half(1.0, 0.1, 0.1);
    const Vec3 halfOther(0.1, 1.0, 0.1);
    const Vec3 above(0.0, 0.0, 2.0 * reach + 0.02);
    EXPECT_TRUE(orientedBoxesApart(Vec3::Zero(), turned, half, above, turnedOther, halfOther, 0.01));
    EXPECT_FALSE(orientedBoxesApart(Vec3::Zero(), turned, half, above, turnedOther, halfOther, 0.03));
}

} // namespace
} // namespace impulse
