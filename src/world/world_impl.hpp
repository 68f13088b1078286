// SPDX-License-Identifier: MIT
#pragma once

#include "collision/broad_phase.hpp"
#include "collision/contact.hpp"
#include "dynamics/contact_graph.hpp"
#include "dynamics/pair_resolution.hpp"
#include "dynamics/rigid_body.hpp"

#include <impulse/world.hpp>

#include <map>
#include <utility>
#include <vector>

namespace impulse
{

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
    std::vector<BodyPair> pairs;
    std::vector<PairCoefficients> pairCoefficients; ///< parallel to pairs
    std::vector<ContactPoint> points;
    BroadPhase broadPhase;
    std::vector<int> pairLevels;                       ///< parallel to pairs: max level of the two bodies
    std::vector<SupportEdge> supportEdges;             ///< contact graph of this step
    std::vector<std::vector<std::uint32_t>> bodyPairs; ///< per body: indices into pairs
    std::vector<std::uint32_t> levelBodies;            ///< scratch of sweepLevels
    std::vector<Support> supports;                     ///< scratch of sweepLevels

    PairCoefficients coefficients(MaterialId a, MaterialId b) const;
    void step(const StepOptions& options);

  private:
    // the two orders of the step (step.cpp), each a list of the stages below
    void stepGuendelman(const StepOptions& options);
    void stepTraditional(const StepOptions& options);

    void findCandidatePairs(const StepOptions& options, const PassSettings& settings);
    void solveCollisions(const StepOptions& options, const PassSettings& settings);
    void updateVelocities(const StepOptions& options);
    void buildContactGraph(const StepOptions& options);
    void assignSingleLevel();
    void solveContacts(const StepOptions& options, const PassSettings& settings);
    void propagateShock(const StepOptions& options, const PassSettings& settings);
    int sweepLevels(Real eps, bool freezeLowerLevels, const PassSettings& settings);
    void updatePositions(const StepOptions& options);
};

} // namespace impulse
