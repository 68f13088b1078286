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

/// The patch as a small complementarity problem, for when it does not stick as a whole (a block on
/// two supports that spread, a body tipping off one of them): projected Gauss-Seidel with
/// accumulated impulses, each point's load kept >= 0 and its friction within mu times that load,
/// so points may lift or slide. The partners are held as they move while the body's impulses are
/// found, then receive the reactions. The outcome never adds kinetic energy: one that would (a
/// nearly singular patch, restitution targets out of reach at a pinch) is solved again as
/// inelastic, or else left alone. Returns true if any impulse was applied.
bool applyProjectedPatchImpulse(RigidBody& body, const std::vector<PatchPoint>& patch, Real eps,
                                const PassSettings& settings);

} // namespace impulse
