// SPDX-License-Identifier: MIT
#pragma once

#include <impulse/math.hpp>
#include <impulse/shape.hpp>

#include <array>
#include <cstdint>
#include <utility>
#include <vector>

namespace impulse
{

/// A body as the broad phase sees it: its shape at time n and at its predicted pose, and how far
/// beyond them it may go this step.
struct BroadPhaseBody
{
    const Shape* shape = nullptr;
    Pose now;
    Pose next;
    Real boundingRadius = 0.0;
    Real margin = 0.0; ///< m; the box is grown by this (static bodies: 0)
    bool dynamic = false;
    bool present = true; ///< false for a removed body, which pairs with nothing
};

/// Two bodies that may touch this step, a < b.
struct BodyPair
{
    std::uint32_t a = 0;
    std::uint32_t b = 0;

    /// The order pair lists are kept in: by a, then b.
    friend bool operator<(const BodyPair& l, const BodyPair& r) { return l.a < r.a || (l.a == r.a && l.b < r.b); }
};

/// Axis-aligned box in world space.
struct Aabb
{
    Vec3 lower = Vec3::Zero();
    Vec3 upper = Vec3::Zero();
};

/// Candidate pairs: the bodies whose boxes overlap, each box covering the body's time-n pose and
/// its predicted pose, grown by its own margin for what the step's impulses may add.
///
/// Dynamic bodies are binned in a uniform grid whose cells are a little larger than the largest
/// dynamic box, each by the cell of its box's lower corner, and sorted by cell. Boxes that overlap
/// then lie in the same or in neighbouring cells, so each body is compared with the bodies of its own
/// cell and of the 13 neighbours on one side (the other 13 see it from theirs), read as five runs of
/// the sorted order: the cost grows with the number of bodies (and the sort's log), not its square,
/// and every pair is met once. Static boxes are compared with every dynamic
/// body (there are few), and planes pair with every dynamic body that comes within the margin of
/// them. The pairs are sorted by (a, b): the order, and hence the simulation, does not depend on how
/// the pairs were found.
class BroadPhase
{
  public:
    /// Fills `pairs` for the bodies; bounds are computed on `threads` threads.
    void findPairs(const std::vector<BroadPhaseBody>& bodies, int threads, std::vector<BodyPair>& pairs);

    /// After findPairs, when the dynamic bodies `moved` have new boxes (`bodies` as findPairs saw
    /// them but for these): fills `added` with every pair of a moved body whose new box overlaps the
    /// current box of another body, sorted by (a, b), the pairs it was already in among them. The
    /// other bodies' boxes are those of the last findPairs, or of the findPairsOf that last moved
    /// them. Costs what the moved bodies' neighbourhoods hold, not what the world does.
    void findPairsOf(const std::vector<BroadPhaseBody>& bodies, const std::vector<std::uint32_t>& moved,
                     std::vector<BodyPair>& added);

    /// The box of body i in the last findPairs or findPairsOf (meaningless for planes).
    const Aabb& bounds(std::size_t i) const { return m_bounds[i]; }

  private:
    struct CellEntry
    {
        std::array<std::int64_t, 3> cell = {}; ///< integer cell coordinates of the box's lower corner
        std::uint32_t body = 0;
        Aabb box; ///< a copy, so that the pass over the sorted cells reads nothing else
    };
    /// A grid: its cells are cubes of 1 / inverseCell a side, counted from origin.
    struct Grid
    {
        Vec3 origin = Vec3::Zero();
        Real inverseCell = 1.0;
        std::array<std::int64_t, 3> cellOf(const Vec3& p) const;
    };
    Aabb boxOf(const BroadPhaseBody& body) const;
    /// Every overlapping pair of `members` (by m_bounds), by the sorted cells of a grid whose cell is
    /// the largest member box; leaves `entries` sorted by cell and returns the grid.
    Grid pairByCells(const std::vector<std::uint32_t>& members, std::vector<CellEntry>& entries,
                     std::vector<BodyPair>& pairs);
    /// Fills m_columns from m_entries.
    void listColumns();
    /// The static boxes and planes that body i (dynamic) comes near.
    void pairWithStatic(const std::vector<BroadPhaseBody>& bodies, std::uint32_t i, std::vector<BodyPair>& pairs) const;
    /// Sorts pairs by (a, b), indices below `bodyCount`, in linear time.
    void sortByBodies(std::vector<BodyPair>& pairs, std::size_t bodyCount);

    std::vector<Aabb> m_bounds;
    std::vector<std::uint32_t> m_dynamic;
    std::vector<std::uint32_t> m_static;
    std::vector<std::uint32_t> m_planes;
    std::vector<CellEntry> m_entries;
    std::vector<CellEntry> m_sorted;
    std::vector<std::pair<std::uint64_t, std::uint32_t>> m_keys; ///< (cell key, entry)
    std::vector<BodyPair> m_pairBuffer;
    Grid m_grid; ///< the grid of m_entries, the last findPairs's
    /// Where each column (x, y) of m_entries begins: (x << 32 | y, first entry), in order; empty where
    /// a cell coordinate does not fit in 32 bits
    std::vector<std::pair<std::uint64_t, std::uint32_t>> m_columns;
    bool m_columnsListed = false;          ///< m_columns made for the last findPairs (by its first findPairsOf)
    std::vector<std::uint32_t> m_moved;    ///< dynamic bodies whose box changed since findPairs
    std::vector<std::uint8_t> m_movedMark; ///< per body: 1 in m_moved, 2 in the findPairsOf call's list
    std::vector<CellEntry> m_movedEntries;
};

/// Box that contains the shape placed at `pose` (meaningless for planes).
Aabb shapeBounds(const Shape& shape, const Pose& pose);

} // namespace impulse
