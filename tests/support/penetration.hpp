// SPDX-License-Identifier: MIT
// Test support: the deepest interpenetration of any two bodies of a world, by the narrow phase.
#pragma once

#include "collision/narrow_phase.hpp"

#include <impulse/world.hpp>

#include <algorithm>
#include <cstdint>
#include <vector>

namespace impulse::test
{

struct Penetration
{
    Real depth = 0.0;    ///< deepest penetration, positive, metres
    Real relative = 0.0; ///< the largest depth relative to the size (diameter) of the smaller body
    /// The pair whose depth is the largest relative to its smaller body (the two are the same pair
    /// when the dynamic bodies are all of one size); both 0 when no pair overlaps.
    std::uint32_t first = 0;
    std::uint32_t second = 0;
};

/// Every pair of bodies whose bounding spheres meet, at least one dynamic; planes against all.
inline Penetration deepestPenetration(const World& world)
{
    Penetration result;
    std::vector<ContactPoint> points;
    NarrowPhaseScratch scratch;
    const std::uint32_t count = world.bodyCount();
    for (std::uint32_t i = 0; i < count; ++i)
    {
        const BodyState a = world.state({i});
        const Real ra = boundingRadius(world.shape({i}));
        for (std::uint32_t j = i + 1; j < count; ++j)
        {
            if (!world.isDynamic({i}) && !world.isDynamic({j}))
            {
                continue;
            }
            const BodyState b = world.state({j});
            const Real rb = boundingRadius(world.shape({j}));
            if (std::isfinite(ra) && std::isfinite(rb) && (a.position - b.position).norm() > ra + rb)
            {
                continue;
            }
            points.clear();
            collideShapes(world.shape({i}), Pose::from(a.position, a.orientation), world.shape({j}),
                          Pose::from(b.position, b.orientation), 0.0, points, scratch);
            const Real size = 2.0 * std::min(ra, rb);
            for (const ContactPoint& point : points)
            {
                result.depth = std::max(result.depth, -point.phi);
                if (-point.phi / size > result.relative)
                {
                    result.relative = -point.phi / size;
                    result.first = i;
                    result.second = j;
                }
            }
        }
    }
    return result;
}

} // namespace impulse::test
