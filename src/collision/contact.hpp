// SPDX-License-Identifier: MIT
#pragma once

#include <impulse/math.hpp>

namespace impulse
{

/// A sample point of one body found near or inside another (GBF03 sec. 3).
///
/// For a pair (A, B) the normal always points from B toward A, so a relative velocity
/// u_rel = u_A - u_B with u_rel . normal < 0 is approaching and an impulse +j acts on A, -j on B.
struct ContactPoint
{
    Vec3 point = Vec3::Zero();   ///< world frame
    Vec3 normal = Vec3::UnitZ(); ///< world frame, unit, from B toward A
    Real phi = 0.0;              ///< signed distance; negative means interpenetrating
};

} // namespace impulse
