// SPDX-License-Identifier: MIT
// Test support: how far a body has tipped, read from its orientation.
#pragma once

#include <impulse/math.hpp>

#include <cmath>

namespace impulse::test
{

/// Angle in [0, pi] between the body axis `bodyAxis`, turned by `orientation`, and the world direction
/// `worldAxis`: 0 for a box standing upright on its base with the defaults. atan2 of the cross and dot
/// products rather than acos of the dot, which loses half the digits near 0.
inline Real tiltAngle(const Quat& orientation, const Vec3& bodyAxis = Vec3::UnitZ(),
                      const Vec3& worldAxis = Vec3::UnitZ())
{
    const Vec3 a = orientation * bodyAxis.normalized();
    const Vec3 b = worldAxis.normalized();
    return std::atan2(a.cross(b).norm(), a.dot(b));
}

/// Signed tilt in (-pi, pi] of the body z axis in the world xz-plane: the rotation about world y that
/// takes the world z axis to it, positive when the body leans toward +x.
inline Real tiltAboutY(const Quat& orientation)
{
    const Vec3 up = orientation * Vec3::UnitZ();
    return std::atan2(up.x(), up.z());
}

} // namespace impulse::test
