// SPDX-License-Identifier: MIT
#pragma once

#include "collision/contact.hpp"
#include "dynamics/rigid_body.hpp"

#include <vector>

namespace impulse
{

/// What a push reuses from one call to the next (one per worker thread).
struct PushOutScratch
{
    std::vector<ContactPoint> points; ///< for the caller to gather a push's points in
    std::vector<Real> lambda;         ///< per point: how far the solution moves along its normal
};

/// Moves `body`, never its velocity or angular momentum, out of everything it rests on (the supports
/// stay put): `points` are its contact points with them at the current poses, normals from the
/// supports toward the body. When some point lies deeper than `allowance`, the body is translated
/// and turned by the least move in its mass metric that brings every one of those points to
/// phi >= 0 (to first order), cut back so that no point of it moves further than `reach`. Returns
/// whether it moved.
bool pushOutOfSupports(RigidBody& body, const std::vector<ContactPoint>& points, Real allowance, Real reach,
                       PushOutScratch& scratch);

/// The same for a pair that overlaps deeper than `allowance` at `points` (normals from b toward a),
/// both bodies moving: the least move of
/// the two in their joint mass metric, so the pair's centre of mass stays where it was (a static
/// body does not move), cut back by one fraction so that neither body moves further than its reach
/// nor turns further than moves a point by the pair's deepest overlap.
/// Returns whether they moved.
bool pushApart(RigidBody& a, RigidBody& b, const std::vector<ContactPoint>& points, Real allowance, Real reachA,
               Real reachB, PushOutScratch& scratch);

} // namespace impulse
