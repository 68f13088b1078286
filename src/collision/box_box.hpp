// SPDX-License-Identifier: MIT
#pragma once

#include "collision/contact.hpp"

#include <impulse/shape.hpp>

#include <vector>

namespace impulse
{

/// Contact points of two boxes by the separating-axis test: of the 15 candidate axes (3 face normals
/// of each box, 9 edge-edge cross products) the one of least penetration decides the contact. On a
/// face axis the incident face of the other box is clipped to the reference face (Sutherland-
/// Hodgman), one point per clipped vertex with its depth below the reference face; on an edge axis
/// the closest points of the two edges give one point. Points with phi < threshold are appended,
/// normal from B toward A. Exact for faces resting flush on faces, where sampling the corners
/// against the signed distance is degenerate (every corner lies on an edge of the other box).
void collideBoxBox(const Box& a, const Pose& poseA, const Box& b, const Pose& poseB, Real threshold,
                   std::vector<ContactPoint>& out);

} // namespace impulse
