// SPDX-License-Identifier: MIT
// Queries against an axis-aligned box [lower, upper]: how far a point is, where a segment passes
// through it, and the corners of a box centred on the origin.
#pragma once

#include <impulse/math.hpp>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>
#include <utility>

namespace impulse
{

/// Squared distance from p to the box; zero inside.
inline Real squaredDistanceToBox(const Vec3& p, const Vec3& lower, const Vec3& upper)
{
    return (lower - p).cwiseMax(p - upper).cwiseMax(Vec3::Zero()).squaredNorm();
}

/// Clips the segment a + t d, t in [0, 1], to the box (slab test, faces included). Returns false
/// when it misses; otherwise [enter, leave] is the part of [0, 1] inside.
inline bool clipSegmentToBox(const Vec3& a, const Vec3& d, const Vec3& lower, const Vec3& upper, Real& enter,
                             Real& leave)
{
    enter = 0.0;
    leave = 1.0;
    for (int axis = 0; axis < 3; ++axis)
    {
        if (std::abs(d[axis]) < std::numeric_limits<Real>::min())
        {
            if (a[axis] < lower[axis] || a[axis] > upper[axis])
            {
                return false;
            }
            continue;
        }
        Real t0 = (lower[axis] - a[axis]) / d[axis];
        Real t1 = (upper[axis] - a[axis]) / d[axis];
        if (t0 > t1)
        {
            std::swap(t0, t1);
        }
        enter = std::max(enter, t0);
        leave = std::min(leave, t1);
        if (enter > leave)
        {
            return false;
        }
    }
    return true;
}

/// Corner i (0-7) of the box of the given half extents centred on the origin: bit k of i set
/// means the + side along axis k.
inline Vec3 boxCorner(const Vec3& halfExtents, std::size_t i)
{
    return Vec3((i & 1) ? halfExtents.x() : -halfExtents.x(), (i & 2) ? halfExtents.y() : -halfExtents.y(),
                (i & 4) ? halfExtents.z() : -halfExtents.z());
}

} // namespace impulse
