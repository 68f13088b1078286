// SPDX-License-Identifier: MIT
#pragma once

#include "dynamics/rigid_body.hpp"

namespace impulse
{

/// The position update of GBF03 sec. 2 from pose (x, q): x + dt v, exp(dt w) q renormalised.
Pose advancePose(const Pose& start, const Vec3& linearVelocity, const Vec3& angularVelocity, Real dt);

/// Recomputes the world inverse inertia and the angular velocity from q and L.
void updateDerivedQuantities(RigidBody& body);

/// Applies impulse j at world point p (lever arm r = p - centre) to a body that is not frozen.
void applyImpulse(RigidBody& body, const Vec3& impulse, const Vec3& leverArm);

} // namespace impulse
