// SPDX-License-Identifier: MIT
#pragma once

#include "collision/broad_phase.hpp"
#include "collision/contact.hpp"
#include "dynamics/contact_graph.hpp"
#include "dynamics/pair_resolution.hpp"
#include "dynamics/push_out.hpp"
#include "dynamics/rigid_body.hpp"

#include <impulse/world.hpp>

#include <cstdint>
#include <map>
#include <span>
#include <utility>
#include <vector>

namespace impulse
{

/// When resolving a pair, or a body on its supports, last found nothing approaching: the pass and
/// the motion stamps (RigidBody::motion) of the bodies then. While the pass is the same and no
/// body's stamp has moved, every prediction it read is the same, so resolving again would find
/// nothing again and can be skipped: a sweep revisits only what an impulse has touched since.
struct QuietStamp
{
    std::uint64_t pass = 0; ///< WorldImpl::pass when taken; 0: never
    std::uint32_t motion = 0;
    std::uint32_t otherMotion = 0; ///< a pair's second body; unused for a body on its supports

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

    /// The order of the contact pass and shock propagation, fixed once the levels are known.
    struct Level
    {
        std::uint32_t firstBody = 0, endBody = 0;     ///< range of levelBodies
        std::uint32_t firstPair = 0, endPair = 0;     ///< range of twoWayPairs
        std::uint32_t firstFrozen = 0, endFrozen = 0; ///< range of frozen
    };
    std::vector<Level> levels;
    std::vector<std::uint32_t> levelBodies;   ///< bodies of each level that rest on something, ascending
    std::vector<std::uint32_t> supportStart;  ///< per levelBodies entry: its range of supports
    std::vector<Support> supports;            ///< in pair order
    std::vector<std::uint32_t> twoWayPairs;   ///< pairs of two bodies of the same level, in pair order
    std::vector<std::uint32_t> frozen;        ///< per level: the lower-level bodies shock propagation freezes
    std::vector<QuietStamp> quietBodies;      ///< per levelBodies entry: the body's stamp when last quiet
    std::vector<std::uint32_t> quietSupports; ///< per supports entry: its motion stamp then

    /// What levelBodies[n] rests on.
    std::span<const Support> supportsOf(std::uint32_t n) const
    {
        return {supports.data() + supportStart[n], supportStart[n + 1] - supportStart[n]};
    }
};

/// What one worker thread reuses from pass to pass.
struct ThreadScratch
{
    std::vector<ContactPoint> points;
    std::vector<std::pair<std::uint32_t, std::uint32_t>> supportOf; ///< (body, pair), sorted
    PushOutScratch pushOut;
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

    // per-step scratch, kept to avoid reallocating every step
    std::vector<BodyPair> pairs;                    ///< candidate pairs, sorted by (a, b)
    std::vector<PairCoefficients> pairCoefficients; ///< parallel to pairs
    std::vector<int> pairLevels;                    ///< parallel to pairs: max level of the two bodies
    BroadPhase broadPhase;
    std::vector<Island> islands;
    std::vector<SupportEdge> supportEdges; ///< contact graph of this step
    std::vector<std::uint8_t> pairProbes;  ///< parallel to pairs: what the contact graph's probes found
    std::vector<Pose> probePoses;          ///< per body: predicted with the new velocity v + dt a
    std::vector<Pose> pushOrigins;         ///< per body: its pose before push-out
    std::vector<int> lastPushSweep;        ///< per body: the last push-out sweep that moved it, or -1
    std::vector<QuietStamp> quietPairs;    ///< parallel to pairs
    std::uint64_t pass = 0;                ///< counts the sweeping passes, so that no stamp outlives its own
    std::vector<ThreadScratch> scratch;    ///< one per worker thread
    int threads = 1;                       ///< worker threads of this step

    PairCoefficients coefficients(MaterialId a, MaterialId b) const;
    void step(const StepOptions& options);

  private:
    // the two orders of the step (step.cpp), each a list of the stages below
    void stepGuendelman(const StepOptions& options);
    void stepTraditional(const StepOptions& options);

    void findCandidatePairs(const StepOptions& options, const PassSettings& settings);
    void buildIslands();
    void solveCollisions(const StepOptions& options, const PassSettings& settings);
    void updateVelocities(const StepOptions& options);
    void buildContactGraph(const StepOptions& options);
    void assignSingleLevel();
    void solveContacts(const StepOptions& options, const PassSettings& settings);
    void propagateShock(const StepOptions& options, const PassSettings& settings);
    void updatePositions(const StepOptions& options);
    void pushOut(const StepOptions& options);
    int pushOutIsland(const Island& island, PushOutScratch& scratch, const StepOptions& options);

    void predictAll(const PassSettings& settings);
    int sweepPairs(const Island& island, ThreadScratch& scratch, const PassSettings& settings);
    void planLevels(Island& island, ThreadScratch& scratch);
    int sweepLevels(Island& island, ThreadScratch& scratch, Real eps, bool freezeLowerLevels,
                    const PassSettings& settings);
    void beginSweepingPass();
    /// resolvePair on pair k with restitution eps, unless it was found quiet at these very poses.
    int resolveUnlessQuiet(std::uint32_t k, Real eps, ThreadScratch& scratch, const PassSettings& settings);
};

} // namespace impulse
