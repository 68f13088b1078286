// SPDX-License-Identifier: MIT
#pragma once

#include "collision/contact.hpp"

#include <impulse/shape.hpp>

#include <vector>

namespace impulse
{

/// Appends to `out` every sample point of the pair (A at poseA, B at poseB) whose signed distance
/// is below `threshold`: points of A inside (or near) B and points of B inside (or near) A, all
/// expressed with the normal from B toward A.
void collideShapes(const Shape& a, const Pose& poseA, const Shape& b, const Pose& poseB, Real threshold,
                   std::vector<ContactPoint>& out);

/// The least signed distance of the pair: the least phi of the points collideShapes gives with an
/// infinite threshold, +infinity if it gives none. Two meshes skip the vertices that cannot be the
/// least; other pairs collide into `scratch`.
Real leastSignedDistance(const Shape& a, const Pose& poseA, const Shape& b, const Pose& poseB,
                         std::vector<ContactPoint>& scratch);

} // namespace impulse
