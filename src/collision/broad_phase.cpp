// SPDX-License-Identifier: MIT
#include "collision/broad_phase.hpp"

#include "support/parallel.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <stdexcept>
#include <tuple>

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

} // namespace

void BroadPhase::findPairs(const std::vector<BroadPhaseBody>& bodies, int threads, std::vector<BodyPair>& pairs)
{
    pairs.clear();
    m_bounds.resize(bodies.size());
    parallelForEach(threads, bodies.size(),
                    [&](std::size_t i)
                    {
                        if (!std::holds_alternative<Plane>(*bodies[i].shape))
                        {
                            m_bounds[i] = boxOf(bodies[i]);
                        }
                    });
    m_moved.clear();
    m_movedMark.assign(bodies.size(), 0);
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

    m_grid = pairByCells(m_dynamic, m_entries, pairs);
    m_columnsListed = false;
    for (const std::uint32_t d : m_dynamic)
    {
        pairWithStatic(bodies, d, pairs);
    }

    sortByBodies(pairs, bodies.size());
}

Aabb BroadPhase::boxOf(const BroadPhaseBody& body) const
{
    const Aabb now = shapeBounds(*body.shape, body.now);
    const Aabb next = shapeBounds(*body.shape, body.next);
    const Real grow = body.dynamic ? body.margin : 0.0;
    return {now.lower.cwiseMin(next.lower).array() - grow, now.upper.cwiseMax(next.upper).array() + grow};
}

std::array<std::int64_t, 3> BroadPhase::Grid::cellOf(const Vec3& p) const
{
    return {cellCoordinate(p.x(), origin.x(), inverseCell), cellCoordinate(p.y(), origin.y(), inverseCell),
            cellCoordinate(p.z(), origin.z(), inverseCell)};
}

void BroadPhase::pairWithStatic(const std::vector<BroadPhaseBody>& bodies, std::uint32_t i,
                                std::vector<BodyPair>& pairs) const
{
    // static boxes: by their boxes; there are few, so every one is looked at
    for (const std::uint32_t s : m_static)
    {
        if (overlap(m_bounds[s], m_bounds[i]))
        {
            pairs.push_back({std::min(s, i), std::max(s, i)});
        }
    }
    // planes: where the body's bounding sphere comes within its margin of one at either pose
    const BroadPhaseBody& body = bodies[i];
    for (const std::uint32_t p : m_planes)
    {
        const Plane& plane = std::get<Plane>(*bodies[p].shape);
        const Pose& planePose = bodies[p].now;
        const Vec3 normal = planePose.rotation * plane.normal;
        const Real offset = plane.offset + normal.dot(planePose.position);
        const Real nearest = std::min(normal.dot(body.now.position), normal.dot(body.next.position)) - offset;
        if (nearest - body.boundingRadius <= body.margin)
        {
            pairs.push_back({std::min(i, p), std::max(i, p)});
        }
    }
}

void BroadPhase::listColumns()
{
    m_columns.clear();
    const auto fits = [](std::int64_t c) { return c >= 0 && c <= std::int64_t{UINT32_MAX}; };
    const bool indexed = std::all_of(m_entries.begin(), m_entries.end(),
                                     [&](const CellEntry& e) { return fits(e.cell[0]) && fits(e.cell[1]); });
    for (std::uint32_t e = 0; indexed && e < m_entries.size(); ++e)
    {
        const auto& cell = m_entries[e].cell;
        const std::uint64_t key = static_cast<std::uint64_t>(cell[0]) << 32 | static_cast<std::uint64_t>(cell[1]);
        if (m_columns.empty() || m_columns.back().first != key)
        {
            m_columns.push_back({key, e});
        }
    }
    m_columnsListed = true;
}

void BroadPhase::findPairsOf(const std::vector<BroadPhaseBody>& bodies, const std::vector<std::uint32_t>& moved,
                             std::vector<BodyPair>& added)
{
    added.clear();
    if (m_movedMark.size() != bodies.size())
    {
        throw std::logic_error("BroadPhase::findPairsOf: the bodies are not those of the last findPairs");
    }
    if (!m_columnsListed)
    {
        listColumns();
    }
    constexpr std::uint8_t kMovedBefore = 1;
    constexpr std::uint8_t kMovingNow = 2;
    for (const std::uint32_t i : moved)
    {
        if (!bodies[i].present || !bodies[i].dynamic || std::holds_alternative<Plane>(*bodies[i].shape) ||
            (m_movedMark[i] & kMovingNow) != 0)
        {
            continue;
        }
        m_bounds[i] = boxOf(bodies[i]);
        if (m_movedMark[i] == 0)
        {
            m_moved.push_back(i);
        }
        m_movedMark[i] |= kMovingNow;
    }

    // with the bodies that kept their boxes: the grid of findPairs holds those boxes as they are. One
    // that overlaps a moved box has its lower corner at most a cell (the largest box of then) below the
    // moved box's lower corner, and not above its upper corner: the columns of that range are searched
    // in the sorted cells, or, for a box spanning many, every entry is.
    constexpr std::int64_t kMostColumns = 16;
    for (const std::uint32_t i : m_moved)
    {
        if ((m_movedMark[i] & kMovingNow) == 0)
        {
            continue;
        }
        const Aabb& box = m_bounds[i];
        const auto report = [&](const CellEntry& entry)
        {
            if (m_movedMark[entry.body] == 0 && overlap(box, entry.box))
            {
                added.push_back({std::min(i, entry.body), std::max(i, entry.body)});
            }
        };
        auto low = m_grid.cellOf(box.lower);
        const auto high = m_grid.cellOf(box.upper);
        for (std::int64_t& c : low)
        {
            --c;
        }
        const std::int64_t columnsX = high[0] - low[0] + 1;
        const std::int64_t columnsY = high[1] - low[1] + 1;
        const bool finite = box.lower.allFinite() && box.upper.allFinite();
        if (!finite || m_columns.empty() || columnsX > kMostColumns || columnsY > kMostColumns ||
            columnsX * columnsY > kMostColumns)
        {
            for (const CellEntry& entry : m_entries)
            {
                report(entry);
            }
            continue;
        }
        for (std::int64_t x = std::max<std::int64_t>(low[0], 0); x <= high[0]; ++x)
        {
            for (std::int64_t y = std::max<std::int64_t>(low[1], 0); y <= high[1]; ++y)
            {
                const std::uint64_t key = static_cast<std::uint64_t>(x) << 32 | static_cast<std::uint64_t>(y);
                const auto column = std::lower_bound(m_columns.begin(), m_columns.end(), std::pair{key, 0U});
                if (column == m_columns.end() || column->first != key)
                {
                    continue;
                }
                // the column's run, from its first cell at height low[2] or above
                const auto end = std::next(column) == m_columns.end() ? m_entries.end()
                                                                      : m_entries.begin() + std::next(column)->second;
                auto e = std::lower_bound(m_entries.begin() + column->second, end, low[2],
                                          [](const CellEntry& entry, std::int64_t z) { return entry.cell[2] < z; });
                for (; e != end && e->cell[2] <= high[2]; ++e)
                {
                    report(*e);
                }
            }
        }
    }
    // among the moved bodies, of this call and of earlier ones: a grid of their own
    std::vector<BodyPair> among;
    pairByCells(m_moved, m_movedEntries, among);
    for (const BodyPair& pair : among)
    {
        if (((m_movedMark[pair.a] | m_movedMark[pair.b]) & kMovingNow) != 0)
        {
            added.push_back(pair);
        }
    }
    for (const std::uint32_t i : m_moved)
    {
        if ((m_movedMark[i] & kMovingNow) != 0)
        {
            pairWithStatic(bodies, i, added);
            m_movedMark[i] = kMovedBefore;
        }
    }
    std::sort(added.begin(), added.end());
}

void BroadPhase::sortByBodies(std::vector<BodyPair>& pairs, std::size_t bodyCount)
{
    // Least significant digit first, a stable counting sort per digit of 8 bits: by b, then by a.
    // Indices are below bodyCount, so only the digits that can be non-zero take a pass; the order is
    // the one std::sort by (a, b) gives, as no two pairs are equal.
    int digits = 0;
    while (digits < 4 && (bodyCount - 1) >> (8 * digits) != 0)
    {
        ++digits;
    }
    m_pairBuffer.resize(pairs.size());
    for (const bool byA : {false, true})
    {
        for (int digit = 0; digit < digits; ++digit)
        {
            const int shift = 8 * digit;
            const auto bucket = [&](const BodyPair& pair) { return ((byA ? pair.a : pair.b) >> shift) & 0xffu; };
            std::array<std::size_t, 257> start{};
            for (const BodyPair& pair : pairs)
            {
                ++start[bucket(pair) + 1];
            }
            for (std::size_t d = 0; d < 256; ++d)
            {
                start[d + 1] += start[d];
            }
            for (const BodyPair& pair : pairs)
            {
                m_pairBuffer[start[bucket(pair)]++] = pair;
            }
            pairs.swap(m_pairBuffer);
        }
    }
}

BroadPhase::Grid BroadPhase::pairByCells(const std::vector<std::uint32_t>& members, std::vector<CellEntry>& entries,
                                         std::vector<BodyPair>& pairs)
{
    entries.clear();
    Grid grid;
    if (members.size() < 2)
    {
        return grid;
    }
    Real cellSize = 0.0;
    grid.origin = m_bounds[members[0]].lower;
    for (const std::uint32_t d : members)
    {
        cellSize = std::max(cellSize, (m_bounds[d].upper - m_bounds[d].lower).maxCoeff());
        grid.origin = grid.origin.cwiseMin(m_bounds[d].lower);
    }
    if (!(cellSize > 0.0) || !std::isfinite(cellSize))
    {
        cellSize = 1.0;
    }
    // a little larger than the largest box, so that round-off in the cell coordinates never puts
    // the lower corners of two touching boxes two cells apart
    cellSize *= 1.0 + 1e-6;
    grid.inverseCell = 1.0 / cellSize;

    // Each box goes into the one cell that holds its lower corner. A box spans at most a cell per
    // axis, so two boxes that overlap have lower corners in the same or in neighbouring cells. The
    // entries are sorted by cell (x, then y, then z): the three cells of a column (x, y) from z - 1 to
    // z + 1 are then one run of the order, so each body is compared with the later bodies of its own
    // cell and cell z + 1 of its column, and with the runs of four columns ahead, (x, y + 1) and
    // (x + 1, y - 1 .. y + 1), which sees every pair exactly once (the other neighbours see it from
    // their side). The run of a column ahead starts no earlier for a later body, so each column is
    // followed by one cursor that only moves forward: the pass reads the order a few times in
    // sequence, with no lookups at random.
    // Cell coordinates count from the lowest corner, so they are >= 0; where each fits in 21 bits
    // (two million cells a side) the three make one 63-bit key, and the sort moves 16-byte
    // (key, body) records instead of whole entries. Otherwise the entries are sorted as they are.
    constexpr std::int64_t kKeyBits = 21;
    bool packable = true;
    for (const std::uint32_t d : members)
    {
        const auto cell = grid.cellOf(m_bounds[d].lower);
        packable = packable && std::all_of(cell.begin(), cell.end(),
                                           [](std::int64_t c) { return c >= 0 && c < (std::int64_t{1} << kKeyBits); });
        entries.push_back({cell, d, m_bounds[d]});
    }
    if (packable)
    {
        m_keys.clear();
        for (std::uint32_t e = 0; e < entries.size(); ++e)
        {
            const auto& cell = entries[e].cell;
            const auto key = static_cast<std::uint64_t>(cell[0] << (2 * kKeyBits) | cell[1] << kKeyBits | cell[2]);
            m_keys.push_back({key, e}); // entries are in body order, so e orders ties by body
        }
        std::sort(m_keys.begin(), m_keys.end());
        m_sorted.clear();
        for (const auto& [key, e] : m_keys)
        {
            m_sorted.push_back(entries[e]);
        }
        entries.swap(m_sorted);
    }
    else
    {
        std::sort(entries.begin(), entries.end(),
                  [](const CellEntry& l, const CellEntry& r) {
                      return std::tie(l.cell[0], l.cell[1], l.cell[2], l.body) <
                             std::tie(r.cell[0], r.cell[1], r.cell[2], r.body);
                  });
    }
    const auto report = [&](const CellEntry& l, const CellEntry& r)
    {
        if (overlap(l.box, r.box))
        {
            pairs.push_back({std::min(l.body, r.body), std::max(l.body, r.body)});
        }
    };
    // whether an entry's cell lies in column (x, y) at most at height z; below (x, y, z) in the order
    const auto atMost = [](const CellEntry& e, std::int64_t x, std::int64_t y, std::int64_t z)
    { return e.cell[0] == x && e.cell[1] == y && e.cell[2] <= z; };
    const auto before = [](const CellEntry& e, std::int64_t x, std::int64_t y, std::int64_t z)
    { return std::tie(e.cell[0], e.cell[1], e.cell[2]) < std::tie(x, y, z); };
    static constexpr std::array<std::array<std::int64_t, 2>, 4> kColumnsAhead{{{0, 1}, {1, -1}, {1, 0}, {1, 1}}};
    std::array<std::size_t, 4> cursor{};
    const std::size_t count = entries.size();
    for (std::size_t e = 0; e < count; ++e)
    {
        const CellEntry& first = entries[e];
        const auto& [x, y, z] = first.cell;
        for (std::size_t f = e + 1; f < count && atMost(entries[f], x, y, z + 1); ++f)
        {
            report(first, entries[f]);
        }
        for (std::size_t c = 0; c < kColumnsAhead.size(); ++c)
        {
            const std::int64_t cx = x + kColumnsAhead[c][0];
            const std::int64_t cy = y + kColumnsAhead[c][1];
            std::size_t& f = cursor[c];
            while (f < count && before(entries[f], cx, cy, z - 1))
            {
                ++f;
            }
            for (std::size_t g = f; g < count && atMost(entries[g], cx, cy, z + 1); ++g)
            {
                report(first, entries[g]);
            }
        }
    }
    return grid;
}

} // namespace impulse
