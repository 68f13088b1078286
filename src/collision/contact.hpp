// SPDX-License-Identifier: MIT
#pragma once

#include <impulse/math.hpp>

#include <cstdint>

namespace impulse
{

/// Which body a contact point is a material sample of: where its two witnesses lie.
enum class SampleOf : std::uint8_t
{
    A,       ///< a point of A (a corner, a vertex) inside or near B: A's witness is the point itself
    B,       ///< a point of B inside or near A: B's witness is the point itself
    Between, ///< the middle of the overlap of two curved surfaces or two edges
};

/// A sample point of one body found near or inside another (GBF03 sec. 3).
///
/// For a pair (A, B) the normal always points from B toward A, so a relative velocity
/// u_rel = u_A - u_B with u_rel . normal < 0 is approaching and an impulse +j acts on A, -j on B.
///
/// The two witnesses, the nearest points of the two surfaces, are `witnessA()` and `witnessB()`:
/// witnessA - witnessB = phi normal. `feature` names the pair of features the point came from (a
/// corner, a clipped edge, a mesh vertex), so that the point found again after the bodies have moved
/// can be told apart from its neighbours; it is unique within one call of the narrow phase.
struct ContactPoint
{
    Vec3 point = Vec3::Zero();   ///< world frame
    Vec3 normal = Vec3::UnitZ(); ///< world frame, unit, from B toward A
    Real phi = 0.0;              ///< signed distance; negative means interpenetrating
    std::uint32_t feature = 0;
    SampleOf sample = SampleOf::Between;

    Vec3 witnessA() const
    {
        switch (sample)
        {
        case SampleOf::A:
            return point;
        case SampleOf::B:
            return point + phi * normal;
        default:
            return point + (0.5 * phi) * normal;
        }
    }
    Vec3 witnessB() const
    {
        switch (sample)
        {
        case SampleOf::A:
            return point - phi * normal;
        case SampleOf::B:
            return point;
        default:
            return point - (0.5 * phi) * normal;
        }
    }
};

/// Feature ids built from smaller ones: a well-mixed 32-bit combination, equal for equal inputs.
inline std::uint32_t combineFeatures(std::uint32_t a, std::uint32_t b)
{
    std::uint64_t h = (static_cast<std::uint64_t>(a) << 32) ^ b;
    h ^= h >> 33;
    h *= 0xFF51AFD7ED558CCDULL;
    h ^= h >> 33;
    h *= 0xC4CEB9FE1A85EC53ULL;
    h ^= h >> 33;
    return static_cast<std::uint32_t>(h);
}

} // namespace impulse
