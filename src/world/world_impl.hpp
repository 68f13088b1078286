// SPDX-License-Identifier: MIT
#pragma once

#include "collision/broad_phase.hpp"
#include "collision/contact.hpp"
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

    PairCoefficients coefficients(MaterialId a, MaterialId b) const;
    void step(const StepOptions& options);
};

} // namespace impulse
