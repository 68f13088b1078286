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

/// Moves `body`, never its velocity, out of everything it rests on (the supports stay put): when
/// some point of the body lies deeper than `allowance` inside a support, the body is translated by
/// the shortest move that brings every one of its points with those supports to phi >= 0 (to first
/// order), shortened to at most `reach`. Returns whether it moved.
bool pushOutOfSupports(RigidBody& body, std::span<const Support> supports, Real allowance, Real reach,
                       PushOutScratch& scratch);

/// The same for a pair that overlaps deeper than `allowance`: the move is shared in proportion to
/// inverse mass, so the pair's centre of mass stays where it was (a static body takes no share),
/// and shortened so that neither body moves further than its reach. Returns whether they moved.
bool pushApart(RigidBody& a, RigidBody& b, Real allowance, Real reachA, Real reachB, PushOutScratch& scratch);

} // namespace impulse
