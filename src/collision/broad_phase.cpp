// SPDX-License-Identifier: MIT
#include "collision/broad_phase.hpp"

#include "support/parallel.hpp"

#include <algorithm>
#include <array>
#include <cmath>

namespace impulse
{

Aabb shapeBounds(const Shape& shape, const Pose& pose)
{
    Vec3 extent = Vec3::Zero();
    if (const auto* sphere = std::get_if<Sphere>(&shape))
    {
        extent = Vec3::Constant(sphere->radius);
    }
    else if (const auto* box = std::get_if<Box>(&shape))
    {
        extent = pose.rotation.cwiseAbs() * box->halfExtents;
    }
    else if (const auto* capsule = std::get_if<Capsule>(&shape))
    {
        extent = pose.rotation.col(2).cwiseAbs() * capsule->halfLength + Vec3::Constant(capsule->radius);
    }
    else if (const auto* mesh = std::get_if<Mesh>(&shape))
    {
        // the body-frame box of the vertices, rotated: its centre need not be the centre of mass
        const Vec3 centre = pose.toWorld(0.5 * (mesh->geometry->lower() + mesh->geometry->upper()));
        const Vec3 half = pose.rotation.cwiseAbs() * (0.5 * (mesh->geometry->upper() - mesh->geometry->lower()));
        return {centre - half, centre + half};
    }
    return {pose.position - extent, pose.position + extent};
}

namespace
{

bool overlap(const Aabb& l, const Aabb& r)
{
    return (l.lower.array() <= r.upper.array()).all() && (r.lower.array() <= l.upper.array()).all();
}

// Integer grid coordinate of x; non-finite or far values clamp, which only costs comparisons.
std::int64_t cellCoordinate(Real x, Real origin, Real inverseCell)
{
    constexpr Real kFar = 1e15;
    const Real c = (x - origin) * inverseCell;
    return std::isfinite(c) ? static_cast<std::int64_t>(std::floor(std::clamp(c, -kFar, kFar))) : 0;
}

std::uint64_t mixCell(std::int64_t x, std::int64_t y, std::int64_t z)
{
    // three large odd multipliers and a final avalanche (splitmix64's)
    std::uint64_t h = static_cast<std::uint64_t>(x) * 0x9E3779B97F4A7C15ULL ^
                      static_cast<std::uint64_t>(y) * 0xC2B2AE3D27D4EB4FULL ^
                      static_cast<std::uint64_t>(z) * 0x165667B19E3779F9ULL;
    h ^= h >> 31;
    h *= 0xBF58476D1CE4E5B9ULL;
    h ^= h >> 27;
    return h;
}

} // namespace

void BroadPhase::findPairs(const std::vector<BroadPhaseBody>& bodies, int threads, std::vector<BodyPair>& pairs)
{
    pairs.clear();
    m_bounds.resize(bodies.size());
    parallelForEach(threads, bodies.size(),
                    [&](std::size_t i)
                    {
                        const BroadPhaseBody& body = bodies[i];
                        if (std::holds_alternative<Plane>(*body.shape))
                        {
                            return;
                        }
                        const Aabb now = shapeBounds(*body.shape, body.now);
                        const Aabb next = shapeBounds(*body.shape, body.next);
                        const Real grow = body.dynamic ? body.margin : 0.0;
                        m_bounds[i] = {now.lower.cwiseMin(next.lower).array() - grow,
                                       now.upper.cwiseMax(next.upper).array() + grow};
                    });
    m_dynamic.clear();
    m_static.clear();
    m_planes.clear();
    for (std::uint32_t i = 0; i < bodies.size(); ++i)
    {
        if (!bodies[i].present)
        {
            continue;
        }
        if (std::holds_alternative<Plane>(*bodies[i].shape))
        {
            m_planes.push_back(i);
        }
        else
        {
            (bodies[i].dynamic ? m_dynamic : m_static).push_back(i);
        }
    }

    pairDynamicBodies(pairs);

    // static boxes: against every dynamic body
    for (const std::uint32_t s : m_static)
    {
        for (const std::uint32_t d : m_dynamic)
        {
            if (overlap(m_bounds[s], m_bounds[d]))
            {
                pairs.push_back({std::min(s, d), std::max(s, d)});
            }
        }
    }

    // planes: every dynamic body whose bounding sphere comes within its margin at either pose
    for (const std::uint32_t p : m_planes)
    {
        const Plane& plane = std::get<Plane>(*bodies[p].shape);
        const Pose& planePose = bodies[p].now;
        const Vec3 normal = planePose.rotation * plane.normal;
        const Real offset = plane.offset + normal.dot(planePose.position);
        for (const std::uint32_t i : m_dynamic)
        {
            const BroadPhaseBody& body = bodies[i];
            const Real nearest = std::min(normal.dot(body.now.position), normal.dot(body.next.position)) - offset;
            if (nearest - body.boundingRadius <= body.margin)
            {
                pairs.push_back({std::min(i, p), std::max(i, p)});
            }
        }
    }

    std::sort(pairs.begin(), pairs.end(),
              [](const BodyPair& l, const BodyPair& r) { return l.a < r.a || (l.a == r.a && l.b < r.b); });
}

void BroadPhase::pairDynamicBodies(std::vector<BodyPair>& pairs)
{
    if (m_dynamic.size() < 2)
    {
        return;
    }
    Real cellSize = 0.0;
    Vec3 origin = m_bounds[m_dynamic[0]].lower;
    for (const std::uint32_t d : m_dynamic)
    {
        cellSize = std::max(cellSize, (m_bounds[d].upper - m_bounds[d].lower).maxCoeff());
        origin = origin.cwiseMin(m_bounds[d].lower);
    }
    if (!(cellSize > 0.0) || !std::isfinite(cellSize))
    {
        cellSize = 1.0;
    }
    // a little larger than the largest box, so that round-off in the cell coordinates never puts
    // the lower corners of two touching boxes two cells apart
    cellSize *= 1.0 + 1e-6;
    const Real inverse = 1.0 / cellSize;
    const auto cellOf = [&](const Vec3& p)
    {
        return std::array<std::int64_t, 3>{cellCoordinate(p.x(), origin.x(), inverse),
                                           cellCoordinate(p.y(), origin.y(), inverse),
                                           cellCoordinate(p.z(), origin.z(), inverse)};
    };

    // Each box goes into the one cell that holds its lower corner. A box spans at most a cell per
    // axis, so two boxes that overlap have lower corners in the same or in neighbouring cells: each
    // body is compared with the later bodies of its own cell and with the bodies of the 13
    // neighbours on one side, which sees every such pair exactly once.
    std::size_t buckets = 1;
    while (buckets < 2 * m_dynamic.size())
    {
        buckets *= 2;
    }
    const auto bucketOf = [&](const std::array<std::int64_t, 3>& cell)
    { return mixCell(cell[0], cell[1], cell[2]) & (buckets - 1); };
    m_entries.clear();
    for (const std::uint32_t d : m_dynamic)
    {
        const auto cell = cellOf(m_bounds[d].lower);
        m_entries.push_back({bucketOf(cell), cell, d});
    }
    // counting sort by bucket, stable: within a bucket, bodies stay in ascending order
    m_bucketStart.assign(buckets + 1, 0);
    for (const CellEntry& entry : m_entries)
    {
        ++m_bucketStart[entry.bucket + 1];
    }
    for (std::size_t b = 0; b < buckets; ++b)
    {
        m_bucketStart[b + 1] += m_bucketStart[b];
    }
    m_sorted.resize(m_entries.size());
    m_bucketFill.assign(m_bucketStart.begin(), m_bucketStart.end() - 1);
    for (const CellEntry& entry : m_entries)
    {
        m_sorted[m_bucketFill[entry.bucket]++] = entry;
    }
    const auto report = [&](std::uint32_t i, std::uint32_t j) { pairs.push_back({std::min(i, j), std::max(i, j)}); };
    // compared coordinate by coordinate: std::array's == calls memcmp, which took a third of this
    // function's time in the ten-thousand-sphere pile
    const auto sameCell = [](const std::array<std::int64_t, 3>& l, const std::array<std::int64_t, 3>& r)
    { return l[0] == r[0] && l[1] == r[1] && l[2] == r[2]; };
    // the neighbours on one side: the offsets (x, y, z) that come after (0, 0, 0) in lexicographic order
    static constexpr std::array<std::array<std::int64_t, 3>, 13> kAhead{{{0, 0, 1},
                                                                         {0, 1, -1},
                                                                         {0, 1, 0},
                                                                         {0, 1, 1},
                                                                         {1, -1, -1},
                                                                         {1, -1, 0},
                                                                         {1, -1, 1},
                                                                         {1, 0, -1},
                                                                         {1, 0, 0},
                                                                         {1, 0, 1},
                                                                         {1, 1, -1},
                                                                         {1, 1, 0},
                                                                         {1, 1, 1}}};
    for (std::uint32_t e = 0; e < m_sorted.size(); ++e)
    {
        const CellEntry& first = m_sorted[e];
        const Aabb& bi = m_bounds[first.body];
        // the later entries of the same bucket that are in the same cell
        for (std::uint32_t f = e + 1; f < m_bucketStart[first.bucket + 1]; ++f)
        {
            const CellEntry& second = m_sorted[f];
            if (sameCell(second.cell, first.cell) && overlap(bi, m_bounds[second.body]))
            {
                report(first.body, second.body);
            }
        }
        for (const auto& offset : kAhead)
        {
            const std::array<std::int64_t, 3> cell{first.cell[0] + offset[0], first.cell[1] + offset[1],
                                                   first.cell[2] + offset[2]};
            const std::uint64_t bucket = bucketOf(cell);
            for (std::uint32_t f = m_bucketStart[bucket]; f < m_bucketStart[bucket + 1]; ++f)
            {
                const CellEntry& second = m_sorted[f];
                if (sameCell(second.cell, cell) && overlap(bi, m_bounds[second.body]))
                {
                    report(first.body, second.body);
                }
            }
        }
    }
}

} // namespace impulse
