// SPDX-License-Identifier: MIT
#pragma once

#include "collision/contact.hpp"
#include "dynamics/pair_resolution.hpp"
#include "dynamics/rigid_body.hpp"

#include <span>
#include <vector>

namespace impulse
{

/// How far push-out goes (StepOptions::pushOut*).
struct PushOutSettings
{
    Real allowance = 0.0;   ///< m; overlaps no deeper than this are left to the contact pass
    Real maxDistance = 0.0; ///< m; the longest move of one push
};

/// What a push reuses from one call to the next (one per worker thread).
struct PushOutScratch
{
    std::vector<ContactPoint> points;
    std::vector<Real> lambda; ///< per point: how far the solution moves along its normal
};

/// Moves `body`, never its velocity, out of everything it rests on (the supports stay put): when
/// some point of the body lies deeper than the allowance inside a support, the body is translated by
/// the shortest move that brings every one of its points with those supports to phi >= 0 (to first
/// order), at most maxDistance. Returns whether it moved.
bool pushOutOfSupports(RigidBody& body, std::span<const Support> supports, const PushOutSettings& settings,
                       PushOutScratch& scratch);

/// The same for two bodies of one level: the move is shared in proportion to inverse mass, so the
/// pair's centre of mass stays where it was. Returns whether they moved.
bool pushApart(RigidBody& a, RigidBody& b, const PushOutSettings& settings, PushOutScratch& scratch);

} // namespace impulse
