// SPDX-License-Identifier: MIT
#pragma once

#include "collision/broad_phase.hpp"
#include "collision/contact.hpp"
#include "collision/narrow_phase.hpp"
#include "contact/contact_cache.hpp"
#include "dynamics/collision_pass.hpp"
#include "dynamics/contact_graph.hpp"
#include "dynamics/contact_solver.hpp"
#include "dynamics/push_out.hpp"
#include "dynamics/rigid_body.hpp"

#include <impulse/world.hpp>

#include <array>
#include <cstdint>
#include <limits>
#include <map>
#include <set>
#include <span>
#include <utility>
#include <vector>

namespace impulse
{

/// When resolving a pair in the collision pass last found nothing approaching: the pass and the
/// motion stamps (RigidBody::motion) of the bodies then. While the pass is the same and no body's
/// stamp has moved, every prediction it read is the same, so resolving again would find nothing
/// again and can be skipped: a sweep revisits only what an impulse has touched since.
struct QuietStamp
{
    std::uint64_t pass = 0; ///< WorldImpl::pass when taken; 0: never
    std::uint32_t motion = 0;
    std::uint32_t otherMotion = 0;

    bool holds(std::uint64_t currentPass, const RigidBody& a, const RigidBody& b) const
    {
        return pass == currentPass && motion == a.motion && otherMotion == b.motion;
    }
};

/// Dynamic bodies connected through candidate pairs, with those pairs. Impulses never cross from one
/// island to another, so islands are solved independently, each to its own convergence, and in
/// parallel.
struct Island
{
    std::vector<std::uint32_t> bodies; ///< dynamic, ascending
    std::vector<std::uint32_t> pairs;  ///< indices into WorldImpl::pairs: ascending, then by level

    /// The order of the contact pass, shock propagation and push-out, fixed once the levels are known.
    struct Level
    {
        std::uint32_t firstBody = 0, endBody = 0; ///< range of levelBodies
        std::uint32_t firstPair = 0, endPair = 0; ///< range of twoWayPairs
        /// Range of rows: the supports of the level's bodies from firstRow, those of its two-way
        /// pairs from twoWayRow.
        std::uint32_t firstRow = 0, twoWayRow = 0, endRow = 0;
    };
    std::vector<Level> levels;
    std::vector<std::uint32_t> levelBodies;  ///< bodies of each level that rest on something, ascending
    std::vector<std::uint32_t> supportStart; ///< per levelBodies entry: its range of supportPairs
    std::vector<std::uint32_t> supportPairs; ///< pairs with a lower-level or static partner, in pair order
    std::vector<std::uint32_t> twoWayPairs;  ///< pairs of two bodies of the same level, in pair order
    std::vector<ContactRow> rows;            ///< the contact points of this step, in level order
    std::vector<std::uint32_t> bodyRows;     ///< per levelBodies entry: where its support rows start in rows

    /// The pairs levelBodies[n] rests on.
    std::span<const std::uint32_t> supportsOf(std::uint32_t n) const
    {
        return {supportPairs.data() + supportStart[n], supportStart[n + 1] - supportStart[n]};
    }
};

/// What one worker thread reuses from pass to pass.
struct ThreadScratch
{
    std::vector<ContactPoint> points;
    std::vector<std::pair<std::uint32_t, std::uint32_t>> supportOf; ///< (body, pair), sorted
    std::vector<std::uint32_t> sorted;                              ///< sortByLevel's output
    std::vector<std::size_t> levelStart;                            ///< sortByLevel's counts
    std::vector<SolverBody> coldStart;                              ///< an island's bodies before its solve
    std::vector<ContactRow*> inPlay;                                ///< a body's rows in play
    PushOutScratch pushOut;
    ContactScratch contact; ///< the contact layer's and every narrow-phase call's of this thread
    SolverScratch solver;   ///< the row solves
};

class WorldImpl
{
  public:
    WorldDef def;
    std::vector<Material> materials;
    std::map<std::pair<std::uint32_t, std::uint32_t>, PairCoefficients> pairOverrides; ///< key: (lower, higher)
    std::vector<RigidBody> bodies; ///< in creation order; BodyId::index indexes it
    Real time = 0.0;
    StepStats stats;
    std::vector<Contact> lastContacts; ///< what the contact points carried in the last step
    /// storeContactResults's sort: (a << 32 | b, island << 32 | row) of each row carrying load
    std::vector<std::pair<std::uint64_t, std::uint64_t>> contactOrder;
    /// The contact layer: every candidate pair's points and loads, kept from step to step.
    ContactCache contacts;

    // per-step scratch, kept to avoid reallocating every step
    std::vector<BodyPair> pairs;                    ///< candidate pairs, sorted by (a, b)
    std::vector<PairCoefficients> pairCoefficients; ///< parallel to pairs
    std::vector<int> pairLevels;                    ///< parallel to pairs: max level of the two bodies
    BroadPhase broadPhase;
    std::vector<BroadPhaseBody> broadBodies;  ///< per body: what the broad phase sees
    std::vector<Real> broadMargins;           ///< per body: how far its box is grown this step
    std::vector<std::uint8_t> freshPairs;     ///< parallel to pairs: found since the last collision pass
    std::vector<std::uint32_t> escapedBodies; ///< the bodies widenEscapedBoxes found beyond their boxes
    std::vector<BodyPair> escapedPairs;       ///< every pair of an escaped body, as the broad phase found them
    std::vector<Island> islands;
    std::vector<SupportEdge> supportEdges; ///< contact graph of this step
    std::vector<std::uint8_t> pairProbes;  ///< parallel to pairs: what the contact graph's probes found
    std::vector<Pose> oldPoses;            ///< per body: predicted with the post-collision velocity v
    std::vector<Real> probeMoves;          ///< per body: how far the contact graph's probe moves its points
    std::vector<SolverBody> solverBodies;  ///< per body: velocities while the contact passes solve
    std::vector<Pose> pushOrigins;         ///< per body: its pose before push-out
    std::vector<int> lastPushSweep;        ///< per body: the last push-out sweep that moved it, or -1
    std::vector<int> jointPushSweep;       ///< per body: the last joint push that took it in, or -1
    std::vector<int> pushSlot;             ///< per body: its slot in the joint push under way, or -1
    std::vector<QuietStamp> quietPairs;    ///< parallel to pairs
    std::uint64_t pass = 0;                ///< counts the collision passes, so that no stamp outlives its own
    std::vector<ThreadScratch> scratch;    ///< one per worker thread
    int threads = 1;                       ///< worker threads of this step

    PairCoefficients coefficients(MaterialId a, MaterialId b) const;
    void step(const StepOptions& options);

    /// The live body of least thinnestHalfExtent and that extent (infinite when there is none), for
    /// the size check of World::step; found again by findSmallestBody when a removal left it stale.
    Real smallestSize = std::numeric_limits<Real>::infinity();
    std::uint32_t smallestBody = 0;
    bool smallestKnown = true;
    void findSmallestBody();

    // what the World API sets between steps (world.cpp)
    std::set<std::pair<std::uint32_t, std::uint32_t>> disabledPairs; ///< (lower, higher): never collide
    bool filtering = false; ///< some body has a collision filter of its own or some pair is disabled
    /// Whether filters and disabled pairs let bodies a and b collide.
    bool collides(std::uint32_t a, std::uint32_t b) const;
    /// Drops the candidate pairs that must not collide, right after the broad phase.
    void dropFilteredPairs();
    /// Sets each body's acceleration for this step from gravity and the applied force.
    void beginLoads();
    /// Clears the applied forces and torques once the step has used them.
    void clearLoads();
    /// Wakes `body` and every body that fell asleep with it.
    void wake(std::uint32_t body);
    void wakeAll();

  private:
    // the two orders of the step (step.cpp), each a list of the stages below
    void stepGuendelman(const StepOptions& options);
    void stepTraditional(const StepOptions& options);

    void findCandidatePairs(const StepOptions& options, const PassSettings& settings);
    /// The pairs' coefficients and contact entries made to follow `pairs` after it changed.
    void followPairs();
    void buildIslands();
    /// After the collision pass: grows the margin of every body whose new velocity takes it beyond its
    /// box and lists it in escapedBodies; whether any did.
    bool widenEscapedBoxes(const StepOptions& options);
    /// The pairs the escaped bodies' new boxes add, taken into the pairs, the contact layer and the
    /// islands; whether there were any.
    bool pairEscapedBodies(const StepOptions& options, const PassSettings& settings);
    /// After the pairs were found again: the collision pass's quiet stamps follow their pairs.
    void keepQuietStamps(const std::vector<BodyPair>& before);
    /// Makes the contact layer usable at the predicted poses, with `extra` to spare (ContactCache::refresh).
    /// With `withExact` false the exact entries are left alone: the collision pass detects their pairs
    /// itself, and only the contact pass, which starts from their loads, needs them captured.
    void refreshContacts(const StepOptions& options, Real extra, bool withExact);
    /// The collision pass over every island's pairs, or with `onlyNew` over the pairs found since the
    /// last run (after boxes were widened).
    void solveCollisions(const StepOptions& options, const PassSettings& settings, bool onlyNew);
    void buildContactGraph(const StepOptions& options);
    void assignSingleLevel();
    void updateVelocities(const StepOptions& options);
    void solveContacts(const StepOptions& options, const PassSettings& settings);
    void propagateShock(const StepOptions& options, const PassSettings& settings);
    void storeContactResults();
    void updatePositions(const StepOptions& options);
    void pushOut(const StepOptions& options);
    void finishStep(const StepOptions& options);
    /// Wakes the sleeping bodies a candidate pair joins to an awake body; whether any woke.
    bool wakeTouched();
    /// Counts how long each body has rested and puts islands that rested long enough to sleep.
    void updateSleep(const StepOptions& options);

    void predictAll(const PassSettings& settings);
    PlacedShape placed(std::uint32_t body, const Pose& pose) const;
    /// How far pair k's points may move relative to each other before its entry is captured again.
    Real pairReach(std::uint32_t k, const StepOptions& options) const;
    int sweepPairs(const Island& island, ThreadScratch& scratch, const StepOptions& options,
                   const PassSettings& settings, bool onlyNew);
    /// resolveCollision on pair k, unless it was found quiet at these very poses or its cached points
    /// show nothing that can collide.
    int resolveUnlessQuiet(std::uint32_t k, ThreadScratch& scratch, const StepOptions& options,
                           const PassSettings& settings);
    void planLevels(Island& island, ThreadScratch& scratch);
    void buildRows(Island& island, ThreadScratch& scratch, const StepOptions& options, const PassSettings& settings);
    int pushOutIsland(const Island& island, ThreadScratch& scratch, const StepOptions& options);
    /// The points of pair k with phi below `threshold` at the bodies' current poses
    /// (ContactCache::overlapsAt), normals turned toward `body` (one of the pair).
    void pointsToward(std::uint32_t k, std::uint32_t body, Real threshold, const StepOptions& options,
                      std::vector<ContactPoint>& out, ContactScratch& contactScratch);
};

} // namespace impulse
