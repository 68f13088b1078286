// SPDX-License-Identifier: MIT
// Push-out: the position correction that runs after the position update (PhysBAM's addition to
// GBF03, guendelman.md sec. 9). The passes before it only remove approaching velocity, so an
// overlap made when the collision pass hit its sweep cap on a dense impact would otherwise stay for
// as long as the bodies rest on each other. Push-out changes positions only: velocities, and so the
// kinetic energy the passes settled, are left as they are.
//
// A push is a translation. Solving for a rotation too would spin a body that the contact pass has
// just brought to rest, on points whose depths are only first-order estimates; a translation
// cannot, and what it leaves of a tilted overlap heals through motion.
//
// The move is the least-norm translation dx with phi_i + n_i . dx >= 0 for every point i, solved by
// projected Gauss-Seidel on the point displacements lambda_i >= 0 (dx = sum lambda_i n_i): a small
// convex problem in three unknowns, which converges in a few sweeps.
#include "dynamics/push_out.hpp"

#include "collision/narrow_phase.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace impulse
{
namespace
{

constexpr int kSolverSweeps = 16;
constexpr Real kSolverTolerance = 1e-9; // m: a sweep that changes no lambda by more has converged

bool deeperThan(const std::vector<ContactPoint>& points, Real allowance)
{
    return std::any_of(points.begin(), points.end(), [&](const ContactPoint& p) { return p.phi < -allowance; });
}

// Least-norm dx with phi_i + n_i . dx >= 0 for all points (projected Gauss-Seidel on lambda_i >= 0).
Vec3 separatingMove(const std::vector<ContactPoint>& points, std::vector<Real>& lambda)
{
    lambda.assign(points.size(), 0.0);
    Vec3 move = Vec3::Zero();
    for (int sweep = 0; sweep < kSolverSweeps; ++sweep)
    {
        Real largestChange = 0.0;
        for (std::size_t i = 0; i < points.size(); ++i)
        {
            const Real gap = points[i].phi + points[i].normal.dot(move);
            const Real updated = std::max(0.0, lambda[i] - gap);
            const Real change = updated - lambda[i];
            if (change != 0.0)
            {
                move += change * points[i].normal;
                lambda[i] = updated;
                largestChange = std::max(largestChange, std::abs(change));
            }
        }
        if (largestChange < kSolverTolerance)
        {
            break;
        }
    }
    return move;
}

// `move` shortened to at most `reach`.
Vec3 shortened(const Vec3& move, Real reach)
{
    const Real length = move.norm();
    return length > reach ? Vec3(move * (std::max(reach, 0.0) / length)) : move;
}

} // namespace

bool pushOutOfSupports(RigidBody& body, std::span<const Support> supports, Real allowance, Real reach,
                       PushOutScratch& scratch)
{
    std::vector<ContactPoint>& points = scratch.points;
    points.clear();
    const Pose pose = body.pose();
    for (const Support& support : supports)
    {
        // the normal points from the support toward the body: the direction the body must go
        collideShapes(body.shape, pose, support.body->shape, support.body->pose(), 0.0, points);
    }
    if (!deeperThan(points, allowance))
    {
        return false;
    }
    const Vec3 move = shortened(separatingMove(points, scratch.lambda), reach);
    body.position += move;
    return move != Vec3::Zero();
}

bool pushApart(RigidBody& a, RigidBody& b, Real allowance, Real reachA, Real reachB, PushOutScratch& scratch)
{
    std::vector<ContactPoint>& points = scratch.points;
    points.clear();
    collideShapes(a.shape, a.pose(), b.shape, b.pose(), 0.0, points);
    if (!deeperThan(points, allowance))
    {
        return false;
    }
    // the relative move a - b separates the pair; each body takes its inverse-mass share of it, and
    // the whole move is shortened (not each share) so that the centre of mass still stays put
    const Real shareA = a.invMass / (a.invMass + b.invMass);
    const Real shareB = 1.0 - shareA;
    Real reach = std::numeric_limits<Real>::infinity();
    if (shareA > 0.0)
    {
        reach = std::min(reach, reachA / shareA);
    }
    if (shareB > 0.0)
    {
        reach = std::min(reach, reachB / shareB);
    }
    const Vec3 relative = shortened(separatingMove(points, scratch.lambda), reach);
    a.position += shareA * relative;
    b.position -= shareB * relative;
    return relative != Vec3::Zero();
}

} // namespace impulse
