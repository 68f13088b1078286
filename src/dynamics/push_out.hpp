// SPDX-License-Identifier: MIT
#pragma once

#include "collision/contact.hpp"
#include "dynamics/pair_resolution.hpp"
#include "dynamics/rigid_body.hpp"

#include <span>
#include <vector>

namespace impulse
{

/// What a push reuses from one call to the next (one per worker thread).
struct PushOutScratch
{
    std::vector<ContactPoint> points;
    std::vector<Real> lambda; ///< per point: how far the solution moves along its normal
};

/// Moves `body`, never its velocity or angular momentum, out of everything it rests on (the supports
/// stay put): when some point of the body lies deeper than `allowance` inside a support, the body is
/// translated and turned by the least move in its mass metric that brings every one of its points
/// with those supports to phi >= 0 (to first order), cut back so that no point of it moves further
/// than `reach`. Returns whether it moved.
bool pushOutOfSupports(RigidBody& body, std::span<const Support> supports, Real allowance, Real reach,
                       PushOutScratch& scratch);

/// The same for a pair that overlaps deeper than `allowance`, both bodies moving: the least move of
/// the two in their joint mass metric, so the pair's centre of mass stays where it was (a static
/// body does not move), cut back by one fraction so that neither body moves further than its reach
/// nor turns further than moves a point by the pair's deepest overlap.
/// Returns whether they moved.
bool pushApart(RigidBody& a, RigidBody& b, Real allowance, Real reachA, Real reachB, PushOutScratch& scratch);

} // namespace impulse
