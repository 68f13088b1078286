// SPDX-License-Identifier: MIT
#pragma once

#include "dynamics/rigid_body.hpp"

#include <cstdint>
#include <vector>

namespace impulse
{

/// Two bodies that may touch this step, a < b.
struct BodyPair
{
    std::uint32_t a = 0;
    std::uint32_t b = 0;
};

/// Axis-aligned box in world space.
struct Aabb
{
    Vec3 lower = Vec3::Zero();
    Vec3 upper = Vec3::Zero();
};

/// Sweep and prune along x over boxes that cover each body's time-n pose and its predicted pose,
/// grown by a margin for what the step's impulses may add. Planes pair with every dynamic body that
/// comes within the margin of them.
class BroadPhase
{
  public:
    /// Fills `pairs`, sorted by (a, b), for the bodies at time n with `predicted` already set.
    void findPairs(const std::vector<RigidBody>& bodies, Real margin, std::vector<BodyPair>& pairs);

  private:
    std::vector<Aabb> m_bounds;
    std::vector<std::uint32_t> m_order;
    std::vector<std::uint32_t> m_planes;
};

/// Box that contains the shape placed at `pose` (meaningless for planes).
Aabb shapeBounds(const Shape& shape, const Pose& pose);

} // namespace impulse
