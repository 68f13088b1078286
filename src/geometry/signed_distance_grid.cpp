// SPDX-License-Identifier: MIT
#include "geometry/signed_distance_grid.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>

namespace impulse
{

SignedDistanceGrid::SignedDistanceGrid(const TriangleBvh& bvh, const Vec3& lower, const Vec3& upper, int resolution)
{
    const Vec3 extent = upper - lower;
    m_cell = extent.maxCoeff() / resolution;
    m_origin = lower - Vec3::Constant(kPadding * m_cell);
    const Vec3 samples = sampleCounts(lower, upper, resolution);
    for (int axis = 0; axis < 3; ++axis)
    {
        m_samples[axis] = static_cast<int>(samples[axis]);
    }
    m_far = m_origin + m_cell * Vec3(m_samples[0] - 1, m_samples[1] - 1, m_samples[2] - 1);
    const std::size_t total = static_cast<std::size_t>(m_samples[0]) * m_samples[1] * m_samples[2];
    constexpr Real kFar = std::numeric_limits<Real>::infinity();
    std::vector<Real> distance(total, kFar);
    std::vector<std::int32_t> nearest(total, -1);
    std::vector<std::int8_t> sign(total, 0); // known signs: +1 outside, -1 inside, 0 not yet

    // 1. exact within the band: closest triangle from the tree, sign from its pseudonormal. The
    // band is wider than a cell, so two neighbouring samples outside it are on the same side.
    const Real band = 2.0 * m_cell;
    for (int k = 0; k < m_samples[2]; ++k)
    {
        for (int j = 0; j < m_samples[1]; ++j)
        {
            for (int i = 0; i < m_samples[0]; ++i)
            {
                const Vec3 p = position(i, j, k);
                const SurfacePoint closest = bvh.closestPoint(p, band);
                if (closest.found)
                {
                    const std::size_t s = index(i, j, k);
                    distance[s] = closest.distance;
                    nearest[s] = static_cast<std::int32_t>(closest.triangle);
                    sign[s] = TriangleBvh::signedDistance(p, closest) < 0.0 ? -1 : 1;
                }
            }
        }
    }
    std::vector<std::int8_t> inBand(total);
    for (std::size_t s = 0; s < total; ++s)
    {
        inBand[s] = sign[s] != 0;
    }

    // 2. beyond the band, fast sweeping in the eight diagonal orders: each sample tries the nearest
    // triangles of its upwind neighbours and keeps the closest
    for (int round = 0; round < 2; ++round)
    {
        for (int order = 0; order < 8; ++order)
        {
            const int di = (order & 1) ? -1 : 1;
            const int dj = (order & 2) ? -1 : 1;
            const int dk = (order & 4) ? -1 : 1;
            const auto first = [](int step, int count) { return step > 0 ? 0 : count - 1; };
            for (int k = first(dk, m_samples[2]); k >= 0 && k < m_samples[2]; k += dk)
            {
                for (int j = first(dj, m_samples[1]); j >= 0 && j < m_samples[1]; j += dj)
                {
                    for (int i = first(di, m_samples[0]); i >= 0 && i < m_samples[0]; i += di)
                    {
                        const std::size_t s = index(i, j, k);
                        if (inBand[s])
                        {
                            continue;
                        }
                        const Vec3 p = position(i, j, k);
                        const auto tryNeighbour = [&](int ni, int nj, int nk)
                        {
                            if (ni < 0 || nj < 0 || nk < 0 || ni >= m_samples[0] || nj >= m_samples[1] ||
                                nk >= m_samples[2])
                            {
                                return;
                            }
                            const std::int32_t t = nearest[index(ni, nj, nk)];
                            if (t < 0 || t == nearest[s])
                            {
                                return;
                            }
                            const Real d = bvh.distanceToTriangle(p, static_cast<std::uint32_t>(t));
                            if (d < distance[s])
                            {
                                distance[s] = d;
                                nearest[s] = t;
                            }
                        };
                        tryNeighbour(i - di, j, k);
                        tryNeighbour(i, j - dj, k);
                        tryNeighbour(i, j, k - dk);
                    }
                }
            }
        }
    }

    // 3. signs beyond the band: each connected region of unsigned samples takes the sign of the band
    // samples around it (majority, though a closed mesh makes them agree)
    std::vector<std::size_t> region;
    std::vector<std::size_t> queue;
    const std::size_t strideJ = static_cast<std::size_t>(m_samples[0]);
    const std::size_t strideK = strideJ * static_cast<std::size_t>(m_samples[1]);
    for (std::size_t seed = 0; seed < total; ++seed)
    {
        if (sign[seed] != 0)
        {
            continue;
        }
        int votes = 0;
        region.clear();
        queue.assign(1, seed);
        sign[seed] = 2; // visiting
        while (!queue.empty())
        {
            const std::size_t s = queue.back();
            queue.pop_back();
            region.push_back(s);
            const int i = static_cast<int>(s % strideJ);
            const int j = static_cast<int>((s / strideJ) % static_cast<std::size_t>(m_samples[1]));
            const int k = static_cast<int>(s / strideK);
            const auto visit = [&](bool inside, std::size_t n)
            {
                if (!inside)
                {
                    return;
                }
                if (inBand[n])
                {
                    votes += sign[n];
                }
                else if (sign[n] == 0)
                {
                    sign[n] = 2;
                    queue.push_back(n);
                }
            };
            visit(i > 0, s - 1);
            visit(i + 1 < m_samples[0], s + 1);
            visit(j > 0, s - strideJ);
            visit(j + 1 < m_samples[1], s + strideJ);
            visit(k > 0, s - strideK);
            visit(k + 1 < m_samples[2], s + strideK);
        }
        const std::int8_t regionSign = votes < 0 ? -1 : 1;
        for (const std::size_t s : region)
        {
            sign[s] = regionSign;
        }
    }

    m_phi.resize(total);
    for (std::size_t s = 0; s < total; ++s)
    {
        m_phi[s] = sign[s] * distance[s];
    }
}

Vec3 SignedDistanceGrid::sampleCounts(const Vec3& lower, const Vec3& upper, int resolution)
{
    const Vec3 extent = upper - lower;
    const Real cell = extent.maxCoeff() / resolution;
    Vec3 samples;
    for (int axis = 0; axis < 3; ++axis)
    {
        samples[axis] = std::ceil(extent[axis] / cell) + 2 * kPadding + 1;
    }
    return samples;
}

SignedDistanceGrid::Stencil SignedDistanceGrid::stencil(const Vec3& p) const
{
    // interpolation in the grid box; outside (at least kPadding cells from the surface) the way to
    // the box is added
    const Vec3 clamped = p.cwiseMax(m_origin).cwiseMin(m_far);
    const Vec3 u = (clamped - m_origin) / m_cell;
    Stencil result;
    std::array<int, 3> cell{};
    for (int axis = 0; axis < 3; ++axis)
    {
        // u >= 0, where truncation is floor
        cell[axis] = std::clamp(static_cast<int>(u[axis]), 0, m_samples[axis] - 2);
        result.fraction[axis] = u[axis] - cell[axis];
    }
    const std::size_t strideJ = static_cast<std::size_t>(m_samples[0]);
    const std::size_t strideK = strideJ * static_cast<std::size_t>(m_samples[1]);
    const Real* c = m_phi.data() + index(cell[0], cell[1], cell[2]);
    auto& corner = result.corner;
    corner = {c[0],       c[1],           c[strideJ],           c[strideJ + 1],
              c[strideK], c[strideK + 1], c[strideK + strideJ], c[strideK + strideJ + 1]};
    const Real f0 = result.fraction[0];
    const Real f1 = result.fraction[1];
    const Real f2 = result.fraction[2];
    const Real gx = 1.0 - f0, gy = 1.0 - f1, gz = 1.0 - f2;
    result.phi = gz * (gy * (gx * corner[0] + f0 * corner[1]) + f1 * (gx * corner[2] + f0 * corner[3])) +
                 f2 * (gy * (gx * corner[4] + f0 * corner[5]) + f1 * (gx * corner[6] + f0 * corner[7]));
    result.phi += (p - clamped).norm();
    return result;
}

MeshDistance SignedDistanceGrid::withGradient(const Stencil& stencil)
{
    const auto& [c000, c100, c010, c110, c001, c101, c011, c111] = stencil.corner;
    const Real f0 = stencil.fraction[0];
    const Real f1 = stencil.fraction[1];
    const Real f2 = stencil.fraction[2];
    const Real gx = 1.0 - f0, gy = 1.0 - f1, gz = 1.0 - f2;
    MeshDistance result;
    result.phi = stencil.phi;
    const Vec3 gradient(gz * (gy * (c100 - c000) + f1 * (c110 - c010)) + f2 * (gy * (c101 - c001) + f1 * (c111 - c011)),
                        gz * (gx * (c010 - c000) + f0 * (c110 - c100)) + f2 * (gx * (c011 - c001) + f0 * (c111 - c101)),
                        gy * (gx * (c001 - c000) + f0 * (c101 - c100)) +
                            f1 * (gx * (c011 - c010) + f0 * (c111 - c110)));
    const Real length = gradient.norm();
    result.gradient = length > 0.0 ? Vec3(gradient / length) : Vec3::UnitZ();
    return result;
}

} // namespace impulse
