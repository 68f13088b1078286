// SPDX-License-Identifier: MIT
#include "geometry/signed_distance.hpp"

#include <array>
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

Real deepestSegmentParameterInBox(const Vec3& halfExtents, const Vec3& aLocal, const Vec3& bLocal)
{
    // Inside the box phi = max_i(|p_i| - h_i), the maximum of six functions affine in t, so along a
    // segment it is convex and piecewise linear: its minimum lies at an end or where two of the
    // six lines cross. Evaluating every candidate is exact and needs no iteration.
    const Vec3 d = bLocal - aLocal;
    std::array<Real, 6> slope{};
    std::array<Real, 6> intercept{};
    for (int i = 0; i < 3; ++i)
    {
        slope[2 * i] = d[i];
        intercept[2 * i] = aLocal[i] - halfExtents[i];
        slope[2 * i + 1] = -d[i];
        intercept[2 * i + 1] = -aLocal[i] - halfExtents[i];
    }
    const auto maxAffine = [&](Real t) {
        Real value = intercept[0] + slope[0] * t;
        for (int k = 1; k < 6; ++k)
        {
            value = std::max(value, intercept[k] + slope[k] * t);
        }
        return value;
    };
    Real bestT = 0.0;
    Real best = maxAffine(0.0);
    const auto consider = [&](Real t) {
        const Real value = maxAffine(t);
        if (value < best)
        {
            best = value;
            bestT = t;
        }
    };
    consider(1.0);
    for (int k = 0; k < 6; ++k)
    {
        for (int l = k + 1; l < 6; ++l)
        {
            const Real ds = slope[k] - slope[l];
            if (ds != 0.0)
            {
                const Real t = (intercept[l] - intercept[k]) / ds;
                if (t > 0.0 && t < 1.0)
                {
                    consider(t);
                }
            }
        }
    }
    return bestT;
}

} // namespace impulse
