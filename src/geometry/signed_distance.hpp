// SPDX-License-Identifier: MIT
// Analytic signed distance functions phi (negative inside) with their gradients, body frame.
#pragma once

#include <impulse/shape.hpp>

namespace impulse
{

/// phi at a point and the unit gradient there (the outward normal of the nearest surface).
struct DistanceSample
{
    Real phi = 0.0;
    Vec3 gradient = Vec3::UnitZ();
};

DistanceSample sphereDistance(Real radius, const Vec3& pointLocal);
DistanceSample boxDistance(const Vec3& halfExtents, const Vec3& pointLocal);
DistanceSample planeDistance(const Plane& plane, const Vec3& pointLocal);
/// Capsule along the body z axis: the distance to the segment [-halfLength, halfLength] e_z, less the
/// radius. On the axis itself the gradient is e_x, so that the result is deterministic.
DistanceSample capsuleDistance(const Capsule& capsule, const Vec3& pointLocal);

} // namespace impulse
