// SPDX-License-Identifier: MIT
// The capsule's rows of the narrow-phase table. A capsule is a segment with a radius, so each pair
// reduces to closest points between the segment and the other shape, reported as sphere contacts
// of radius r centred on the segment. A capsule lying flat on a plane, a box face or a parallel
// capsule gets two points (the ends of its support), so it rests without rocking.
#pragma once

#include "collision/contact.hpp"

#include <impulse/shape.hpp>

#include <vector>

namespace impulse
{

/// Where along the segment start + s along, s in [0, 1], the signed distance of the box of
/// `halfExtents` (all in the box's frame) is least, and that distance. On a flat stretch (a segment
/// parallel to the nearest face) any s of the stretch may be returned.
struct LeastAlong
{
    Real s = 0.0;
    Real phi = 0.0;
};
LeastAlong leastBoxDistanceAlong(const Vec3& halfExtents, const Vec3& start, const Vec3& along);

/// Capsule A against sphere B: the segment point closest to the sphere's centre.
void collideCapsuleSphere(const Capsule& a, const Pose& poseA, const Sphere& b, const Pose& poseB, Real threshold,
                          std::vector<ContactPoint>& out);

/// Capsule A against plane B: the deepest point of each end sphere that lies below `threshold`.
void collideCapsulePlane(const Capsule& a, const Pose& poseA, const Plane& b, const Pose& poseB, Real threshold,
                         std::vector<ContactPoint>& out);

/// Capsule A against box B: each end sphere against the box's signed distance, and the segment
/// point of least box distance when it lies strictly deeper than both ends (a box edge or corner
/// under the middle of the capsule).
void collideCapsuleBox(const Capsule& a, const Pose& poseA, const Box& b, const Pose& poseB, Real threshold,
                       std::vector<ContactPoint>& out);

/// Capsule A against capsule B: closest points of the two segments; two points (the ends of the
/// overlap) when the segments are parallel and overlap along their length.
void collideCapsuleCapsule(const Capsule& a, const Pose& poseA, const Capsule& b, const Pose& poseB, Real threshold,
                           std::vector<ContactPoint>& out);

} // namespace impulse
