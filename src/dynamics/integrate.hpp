// SPDX-License-Identifier: MIT
#pragma once

#include "dynamics/rigid_body.hpp"

namespace impulse
{

/// The position update of GBF03 sec. 2 from pose (x, q): x + dt v, exp(dt w) q renormalised.
Pose advancePose(const Pose& start, const Vec3& linearVelocity, const Vec3& angularVelocity, Real dt);

/// The angular velocity the body turns with over a torque-free step of dt from its time-n pose: the
/// implicit midpoint of Euler's equations, w_m = I^-1 (L_n + L_n+1) / 2 in the body frame, with
/// L_n+1 = exp(-dt w_m) L_n the body-frame momentum after the turn. The energy L I^-1 L / 2 is then
/// the same after the turn as before, where turning with w_n (GBF03's update) adds
/// (dt^2 / 2) |L x w|^2 in I^-1 every step, which spins a fast-tumbling body up to its axis of least
/// inertia. Equal to the body's angular velocity for a body whose principal moments are equal.
Vec3 stepAngularVelocity(const RigidBody& body, Real dt);

/// advancePose with the step's angular velocity: where the body is after dt under (v, L).
Pose advanceBody(const RigidBody& body, const Vec3& linearVelocity, Real dt);

/// Recomputes the world inverse inertia and the angular velocity from q and L.
void updateDerivedQuantities(RigidBody& body);

/// Applies impulse j at world point p (lever arm r = p - centre) to a body that is not frozen.
void applyImpulse(RigidBody& body, const Vec3& impulse, const Vec3& leverArm);

} // namespace impulse
