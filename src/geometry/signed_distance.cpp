// SPDX-License-Identifier: MIT
#include "geometry/signed_distance.hpp"

#include <algorithm>
#include <cmath>

namespace impulse
{

DistanceSample sphereDistance(Real radius, const Vec3& pointLocal)
{
    const Real distance = pointLocal.norm();
    if (distance > 0.0)
    {
        return {distance - radius, pointLocal / distance};
    }
    // the centre itself: every direction is as good; pick one so the result is deterministic
    return {-radius, Vec3::UnitZ()};
}

DistanceSample boxDistance(const Vec3& halfExtents, const Vec3& pointLocal)
{
    const Vec3 q = pointLocal.cwiseAbs() - halfExtents;
    if ((q.array() > 0.0).any())
    {
        // outside: Euclidean distance to the nearest surface point
        const Vec3 closest = pointLocal.cwiseMax(-halfExtents).cwiseMin(halfExtents);
        const Vec3 away = pointLocal - closest;
        const Real distance = away.norm();
        return {distance, away / distance};
    }
    // inside (or on the surface): the nearest face, lowest axis first on ties
    int axis = 0;
    for (int i = 1; i < 3; ++i)
    {
        if (q[i] > q[axis])
        {
            axis = i;
        }
    }
    Vec3 normal = Vec3::Zero();
    normal[axis] = pointLocal[axis] < 0.0 ? -1.0 : 1.0;
    return {q[axis], normal};
}

DistanceSample planeDistance(const Plane& plane, const Vec3& pointLocal)
{
    return {plane.normal.dot(pointLocal) - plane.offset, plane.normal};
}

DistanceSample capsuleDistance(const Capsule& capsule, const Vec3& pointLocal)
{
    const Real along = std::clamp(pointLocal.z(), -capsule.halfLength, capsule.halfLength);
    const Vec3 away = pointLocal - Vec3(0.0, 0.0, along);
    const Real distance = away.norm();
    if (distance > 0.0)
    {
        return {distance - capsule.radius, away / distance};
    }
    return {-capsule.radius, Vec3::UnitX()};
}

} // namespace impulse
