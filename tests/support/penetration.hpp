// SPDX-License-Identifier: MIT
// Test support: the deepest interpenetration of any two bodies of a world, by the narrow phase.
#pragma once

#include "collision/narrow_phase.hpp"

#include <impulse/world.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <utility>
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

/// The pairs (i < j, in lexicographic order) of bodies whose bounding spheres meet, at least one
/// dynamic; a body of unbounded extent (a plane) is paired with every dynamic body. A sweep over
/// the spheres' extents along the axis the centres spread most along (a pile falling from a tall
/// column sweeps along z, a formed pile along x or y): a thousand bodies checked every step cost
/// little beside the step.
inline std::vector<std::pair<std::uint32_t, std::uint32_t>> pairsWhoseBoundsMeet(const World& world)
{
    struct Extent
    {
        Real low = 0.0;
        Real high = 0.0;
        std::uint32_t body = 0;
    };
    std::vector<Extent> bounded;
    std::vector<std::uint32_t> unbounded;
    const std::uint32_t count = world.bodyCount();
    std::vector<Vec3> centre(count);
    std::vector<Real> radius(count);
    Vec3 lowest = Vec3::Constant(std::numeric_limits<Real>::infinity());
    Vec3 highest = -lowest;
    for (std::uint32_t i = 0; i < count; ++i)
    {
        centre[i] = world.state({i}).position;
        radius[i] = boundingRadius(world.shape({i}));
        if (std::isfinite(radius[i]))
        {
            lowest = lowest.cwiseMin(centre[i]);
            highest = highest.cwiseMax(centre[i]);
        }
    }
    Eigen::Index axis = 0;
    (highest - lowest).maxCoeff(&axis);
    for (std::uint32_t i = 0; i < count; ++i)
    {
        if (!std::isfinite(radius[i]))
        {
            unbounded.push_back(i);
            continue;
        }
        bounded.push_back({centre[i](axis) - radius[i], centre[i](axis) + radius[i], i});
    }
    std::sort(bounded.begin(), bounded.end(),
              [](const Extent& a, const Extent& b) { return a.low < b.low || (a.low == b.low && a.body < b.body); });
    std::vector<std::pair<std::uint32_t, std::uint32_t>> pairs;
    const auto add = [&](std::uint32_t a, std::uint32_t b)
    {
        if (world.isDynamic({a}) || world.isDynamic({b}))
        {
            pairs.emplace_back(std::min(a, b), std::max(a, b));
        }
    };
    for (std::size_t k = 0; k < bounded.size(); ++k)
    {
        const std::uint32_t i = bounded[k].body;
        for (std::size_t l = k + 1; l < bounded.size() && bounded[l].low <= bounded[k].high; ++l)
        {
            const std::uint32_t j = bounded[l].body;
            if ((centre[i] - centre[j]).norm() <= radius[i] + radius[j])
            {
                add(i, j);
            }
        }
    }
    for (const std::uint32_t plane : unbounded)
    {
        for (std::uint32_t i = 0; i < count; ++i)
        {
            if (i != plane && (i > plane || std::isfinite(radius[i])))
            {
                add(plane, i);
            }
        }
    }
    std::sort(pairs.begin(), pairs.end());
    return pairs;
}

/// The deepest overlap of any two bodies whose bounding spheres meet (pairsWhoseBoundsMeet), by the
/// narrow phase at the bodies' current poses.
inline Penetration deepestPenetration(const World& world)
{
    Penetration result;
    std::vector<ContactPoint> points;
    NarrowPhaseScratch scratch;
    for (const auto& [i, j] : pairsWhoseBoundsMeet(world))
    {
        const BodyState a = world.state({i});
        const BodyState b = world.state({j});
        points.clear();
        collideShapes(world.shape({i}), Pose::from(a.position, a.orientation), world.shape({j}),
                      Pose::from(b.position, b.orientation), 0.0, points, scratch);
        const Real size = 2.0 * std::min(boundingRadius(world.shape({i})), boundingRadius(world.shape({j})));
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
    return result;
}

} // namespace impulse::test
