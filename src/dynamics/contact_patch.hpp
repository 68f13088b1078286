// SPDX-License-Identifier: MIT
#pragma once

#include "collision/contact.hpp"
#include "dynamics/pair_resolution.hpp"
#include "dynamics/rigid_body.hpp"

#include <vector>

namespace impulse
{

/// One point of a contact patch of a body: the point (normal from `other` toward the body), the
/// body it touches there, and the friction coefficient of that pair.
struct PatchPoint
{
    ContactPoint contact;
    RigidBody* other = nullptr;
    Real friction = 0.0;
};

/// Gives every point of the patch its sticking target at once (normal velocity -eps u_n, no slip):
/// the least-squares impulses of the coupled system, re-spread over the patch as a rigid contact
/// carries load (see contact_patch.cpp). Applies them and returns true when they are admissible
/// (every load non-negative, each point in its friction cone, no kinetic energy gained); returns
/// false and changes nothing otherwise. Bodies are placed at their predicted poses.
bool applyPatchImpulse(RigidBody& body, const std::vector<PatchPoint>& patch, Real eps, const PassSettings& settings);

} // namespace impulse
