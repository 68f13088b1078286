// SPDX-License-Identifier: MIT
// A patch solved in one step: every row of a body (or of a pair) given its target at once by a
// single rigid motion, when one reaches them all and the loads it takes are admissible.
//
// Gauss-Seidel over the points of a patch converges slowly: each point's impulse turns the body and
// disturbs its neighbours. But while every point of a patch sticks, the motion the patch asks for is
// a rigid one: a twist (V, W) about the points' centroid c, moving point k by V + W x rho_k,
// rho_k = p_k - c. The twist that meets every target in least squares has a closed form, because
// about the centroid the points' normal matrix J^T J is diag(n 1, G), G = sum (|rho|^2 1 - rho rho^T).
// The wrench that gives it is K^-1 twist, K the mobility of the moving side about c, and it is spread
// over the points with the least norm, point k taking a + b x rho_k. Rotations the points cannot
// resist (about the line through two points, about a single point) are left free, and chosen so that
// the wrench has no part there. Accepted only when every target is met and the loads it leaves are
// admissible: every normal load >= 0 and every friction load within its cone. Otherwise the caller
// goes on with Gauss-Seidel, which lets points lift and slide.
#pragma once

#include "dynamics/contact_solver.hpp"

#include <span>

namespace impulse
{

/// A body a rigid patch moves, as the patch's rows see it.
struct PatchMover
{
    std::uint32_t index = 0;    ///< in the solver's bodies
    Vec3 centre = Vec3::Zero(); ///< the centre the rows' lever arms are taken from
    Real invMass = 0.0;
    Mat3 invInertia = Mat3::Zero(); ///< world frame
};

/// Gives every row of `rows` its target (normal velocity `bias`, no slip) at once. Each row joins
/// `mover` (its A or its B) to a partner; when `partner` is given, every row joins the two and both
/// move (the relative motion is solved), else the partners are held still. Returns false, changing
/// nothing, when no rigid motion meets every target (to `tolerance`, m/s) or when the loads it would
/// leave are not admissible; loads outside their cones by a hair (a thousandth of the loads involved)
/// are projected back in, so that the targets are then met up to that.
bool solveRigidPatch(std::span<ContactRow* const> rows, std::span<SolverBody> bodies, const PatchMover& mover,
                     const PatchMover* partner, Real tolerance, SolverScratch& scratch);

} // namespace impulse
