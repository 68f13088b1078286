// SPDX-License-Identifier: MIT
// Queries against an axis-aligned box [lower, upper]: how far a point is, where a segment passes
// through it, and the corners of a box centred on the origin; and whether two oriented boxes are
// farther apart than a margin.
#pragma once

#include <impulse/math.hpp>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>
#include <utility>

#if defined(__SSE2__)
#include <emmintrin.h>
#endif

namespace impulse
{

/// Squared distance from p to the box; zero inside.
inline Real squaredDistanceToBox(const Vec3& p, const Vec3& lower, const Vec3& upper)
{
#if defined(__SSE2__)
    // (lower - p).cwiseMax(p - upper).cwiseMax(Vec3::Zero()).squaredNorm() operation for operation:
    // Eigen's packet max(a, b) is _mm_max_pd(b, a) (std::max's choice, NaN included), and the sum
    // is x^2 + y^2, then + z^2. Written out because the compiler branches on the sign of the third
    // coordinate, which the branch predictor can only guess in a tree search.
    const __m128d zero = _mm_setzero_pd();
    const __m128d pXY = _mm_loadu_pd(p.data());
    const __m128d pZ = _mm_load_sd(p.data() + 2);
    const __m128d dXY = _mm_max_pd(
        zero, _mm_max_pd(_mm_sub_pd(pXY, _mm_loadu_pd(upper.data())), _mm_sub_pd(_mm_loadu_pd(lower.data()), pXY)));
    const __m128d dZ = _mm_max_sd(
        zero, _mm_max_sd(_mm_sub_sd(pZ, _mm_load_sd(upper.data() + 2)), _mm_sub_sd(_mm_load_sd(lower.data() + 2), pZ)));
    const __m128d squaresXY = _mm_mul_pd(dXY, dXY);
    const __m128d sumXY = _mm_add_sd(squaresXY, _mm_unpackhi_pd(squaresXY, squaresXY));
    return _mm_cvtsd_f64(_mm_add_sd(sumXY, _mm_mul_sd(dZ, dZ)));
#else
    return (lower - p).cwiseMax(p - upper).cwiseMax(Vec3::Zero()).squaredNorm();
#endif
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

/// Whether two oriented boxes (centre, rotation whose columns are the box's axes, half extents) are
/// farther apart than `margin`: separated by one of the 15 axes of the separating axis test. False
/// when in doubt (nearly parallel edges, round-off), so true means they are apart.
inline bool orientedBoxesApart(const Vec3& centreA, const Mat3& rotationA, const Vec3& halfA, const Vec3& centreB,
                               const Mat3& rotationB, const Vec3& halfB, Real margin)
{
    // everything in A's frame: B's axes as the columns of r, B's centre at t
    const Mat3 r = rotationA.transpose() * rotationB;
    const Vec3 t = rotationA.transpose() * (centreB - centreA);
    // round-off of these products, and the rounding of nearly parallel edge pairs, kept on the
    // side of "not apart"
    const Mat3 absR = r.cwiseAbs().array() + 1e-9;
    const Real slack = 1e-9 * (t.norm() + halfA.sum() + halfB.sum());
    const Real gap = margin + slack;
    for (int i = 0; i < 3; ++i)
    {
        if (std::abs(t[i]) > halfA[i] + absR.row(i).dot(halfB) + gap)
        {
            return true;
        }
    }
    for (int j = 0; j < 3; ++j)
    {
        if (std::abs(t.dot(r.col(j))) > absR.col(j).dot(halfA) + halfB[j] + gap)
        {
            return true;
        }
    }
    // edge pairs: axis A_i x B_j, not normalised; its length is at most one, so a gap over it
    // along the axis is a gap of at least that much between the boxes
    for (int i = 0; i < 3; ++i)
    {
        const int i1 = (i + 1) % 3;
        const int i2 = (i + 2) % 3;
        for (int j = 0; j < 3; ++j)
        {
            const int j1 = (j + 1) % 3;
            const int j2 = (j + 2) % 3;
            const Real distance = std::abs(t[i2] * r(i1, j) - t[i1] * r(i2, j));
            const Real radiusA = halfA[i1] * absR(i2, j) + halfA[i2] * absR(i1, j);
            const Real radiusB = halfB[j1] * absR(i, j2) + halfB[j2] * absR(i, j1);
            if (distance > radiusA + radiusB + gap)
            {
                return true;
            }
        }
    }
    return false;
}

} // namespace impulse
