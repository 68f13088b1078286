// SPDX-License-Identifier: MIT
// Push-out: the position correction that runs after the position update (PhysBAM's addition to
// GBF03, guendelman.md sec. 9). The passes before it only remove approaching velocity, so an
// overlap made when the collision pass hit its sweep cap on a dense impact would otherwise stay for
// as long as the bodies rest on each other. Push-out changes poses only: velocities and angular
// momenta, and so the kinetic energy the passes settled, are left as they are.
//
// A push moves a body as a whole, translation and rotation, by the least change of pose that brings
// every point to phi >= 0 (to first order), measured in the body's mass metric: the displacement
// (dx, dtheta) minimising m|dx|^2 + dtheta.I dtheta, as a pseudo-impulse would move it. A translation
// alone cannot clear a wedge, a tilted ring jammed on a bar with overlaps on opposite faces; turning
// it can, and the mass metric makes a heavy body move less than a light one and a long lever turn
// little.
//
// The move is solved by projected Gauss-Seidel on one pseudo-impulse lambda_i >= 0 per point: each
// point's J_i = (n_i, r_i x n_i) maps the move to its normal displacement, and the move is
// M^-1 sum lambda_i J_i^T. A small convex problem in six (or twelve) unknowns, which converges in a
// few sweeps.
//
// Turning is where a push can overshoot. Where a body's points press on supports from opposite
// sides, the least move may clear a shallow overlap by a large turn, and in a jam that turn drives
// the body's corners into its other neighbours, whose pushes turn it back further, until the reach
// stops them with overlaps deeper than any they set out to clear (a pile of ten thousand cubes
// made 5.8 mm of overlap from 3.4 mm). So a push turns a body at most so far that its farthest point
// moves as far as the overlap the push clears; the rest of a wedge is cleared by the next pushes.
#include "dynamics/push_out.hpp"

#include "dynamics/integrate.hpp"

#include <algorithm>
#include <cmath>

namespace impulse
{
namespace
{

constexpr int kSolverSweeps = 16;
constexpr Real kSolverTolerance = 1e-9; // m: a sweep that moves no point's gap by more has converged

Real deepestOf(const std::vector<ContactPoint>& points)
{
    Real deepest = 0.0;
    for (const ContactPoint& p : points)
    {
        deepest = std::max(deepest, -p.phi);
    }
    return deepest;
}

/// A body's part in a push: how a pseudo-impulse moves it, and the move so far. Default-constructed,
/// or built from a static body (zero inverse mass and inertia), it is held: nothing moves it.
struct PushedBody
{
    Vec3 centre = Vec3::Zero();
    Real invMass = 0.0;
    Mat3 invInertia = Mat3::Zero(); ///< world frame
    Vec3 move = Vec3::Zero();       ///< translation
    Vec3 turn = Vec3::Zero();       ///< rotation vector

    PushedBody() = default;
    explicit PushedBody(const RigidBody& body)
        : centre(body.position), invMass(body.invMass), invInertia(body.invInertiaWorld)
    {
    }

    /// How far the point at `p` moves along `n` under the move so far.
    Real displacement(const Vec3& p, const Vec3& n) const { return n.dot(move) + (p - centre).cross(n).dot(turn); }

    /// Normal displacement at `p` per unit pseudo-impulse along `n`.
    Real compliance(const Vec3& p, const Vec3& n) const
    {
        const Vec3 lever = (p - centre).cross(n);
        return invMass + lever.dot(invInertia * lever);
    }

    void apply(const Vec3& p, const Vec3& pseudoImpulse)
    {
        move += invMass * pseudoImpulse;
        turn += invInertia * (p - centre).cross(pseudoImpulse);
    }

    /// How far the body's farthest point moves, to first order.
    Real reachUsed(Real boundingRadius) const { return move.norm() + turn.norm() * boundingRadius; }
};

/// The least move in the mass metric with phi_i + (displacement of a - displacement of b) . n_i >= 0
/// for every point (normals point from b toward a), by projected Gauss-Seidel on lambda_i >= 0.
void separatingMove(const std::vector<ContactPoint>& points, PushedBody& a, PushedBody& b, std::vector<Real>& lambda)
{
    lambda.assign(points.size(), 0.0);
    for (int sweep = 0; sweep < kSolverSweeps; ++sweep)
    {
        Real largestChange = 0.0; // m: of any point's gap
        for (std::size_t i = 0; i < points.size(); ++i)
        {
            const ContactPoint& p = points[i];
            const Real compliance = a.compliance(p.point, p.normal) + b.compliance(p.point, p.normal);
            if (!(compliance > 0.0))
            {
                continue; // both held: nothing can move this point
            }
            const Real gap = p.phi + a.displacement(p.point, p.normal) - b.displacement(p.point, p.normal);
            const Real updated = std::max(0.0, lambda[i] - gap / compliance);
            const Real change = updated - lambda[i];
            if (change != 0.0)
            {
                a.apply(p.point, change * p.normal);
                b.apply(p.point, -change * p.normal);
                lambda[i] = updated;
                largestChange = std::max(largestChange, std::abs(change) * compliance);
            }
        }
        if (largestChange < kSolverTolerance)
        {
            break;
        }
    }
}

/// Moves `body` by `scale` times its share of the push; whether it moved.
bool movePose(RigidBody& body, const PushedBody& push, Real scale)
{
    if (push.move == Vec3::Zero() && push.turn == Vec3::Zero())
    {
        return false;
    }
    const Pose moved = advancePose(body.pose(), scale * push.move, scale * push.turn, 1.0);
    body.position = moved.position;
    body.orientation = moved.orientation;
    body.rotation = moved.rotation;
    updateDerivedQuantities(body); // the angular momentum is kept; w follows the new orientation
    return true;
}

/// The largest fraction of the push, at most 1, that keeps the body within `reach` and turns it by
/// no more than moves its farthest point `depth`, the overlap the push clears.
Real keptFraction(const PushedBody& push, const RigidBody& body, Real reach, Real depth)
{
    const Real used = push.reachUsed(body.boundingRadius);
    const Real fraction = used > reach ? std::max(reach, 0.0) / used : 1.0;
    const Real turned = fraction * push.turn.norm() * body.boundingRadius;
    return turned > depth ? fraction * depth / turned : fraction;
}

} // namespace

bool pushOutOfSupports(RigidBody& body, const std::vector<ContactPoint>& points, Real allowance, Real reach,
                       PushOutScratch& scratch)
{
    const Real depth = deepestOf(points);
    if (!(depth > allowance))
    {
        return false;
    }
    PushedBody push(body);
    PushedBody held; // the supports stay put
    separatingMove(points, push, held, scratch.lambda);
    return movePose(body, push, keptFraction(push, body, reach, depth));
}

bool pushApart(RigidBody& a, RigidBody& b, const std::vector<ContactPoint>& points, Real allowance, Real reachA,
               Real reachB, PushOutScratch& scratch)
{
    const Real depth = deepestOf(points);
    if (!(depth > allowance))
    {
        return false;
    }
    PushedBody pushA(a);
    PushedBody pushB(b);
    separatingMove(points, pushA, pushB, scratch.lambda);
    // one fraction for both, so that the pair's centre of mass still stays put
    const Real scale = std::min(keptFraction(pushA, a, reachA, depth), keptFraction(pushB, b, reachB, depth));
    const bool movedA = movePose(a, pushA, scale);
    const bool movedB = movePose(b, pushB, scale);
    return movedA || movedB;
}

} // namespace impulse
