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
// few sweeps. The joint push poses the same problem for many bodies at once, so that what a body
// rests on holds it while the bodies around it are pushed.
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
// A joint push is a larger problem, and Gauss-Seidel converges slowly on it: a light body between
// a heavy one and a held one gains 1 - m_light / m_heavy per sweep, less where coplanar points turn
// it back and forth (a 0.5 kg box under an 8 kg one on the ground takes 870 sweeps to 1e-9 m).
// Sweeps cost little beside finding the points; most pushes converge in tens.
constexpr int kJointSolverSweeps = 1024;
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

/// The point `p` between a and b, prepared for relaxPoint.
PreparedPushPoint prepare(const ContactPoint& p, const PushedBody& a, const PushedBody& b)
{
    PreparedPushPoint point;
    point.normal = p.normal;
    point.armA = p.point - a.centre;
    point.armB = p.point - b.centre;
    point.leverA = point.armA.cross(p.normal);
    point.leverB = point.armB.cross(p.normal);
    point.phi = p.phi;
    point.compliance = a.compliance(point.leverA) + b.compliance(point.leverB);
    return point;
}

/// One projected Gauss-Seidel update of a point's pseudo-impulse `lambda` >= 0 toward phi >= 0
/// (normal from b toward a); returns how far it changed the point's gap, m.
Real relaxPoint(const PreparedPushPoint& p, PushedBody& a, PushedBody& b, Real& lambda)
{
    if (!(p.compliance > 0.0))
    {
        return 0.0; // both held: nothing can move this point
    }
    const Real gap = p.phi + a.displacement(p.normal, p.leverA) - b.displacement(p.normal, p.leverB);
    const Real updated = std::max(0.0, lambda - gap / p.compliance);
    const Real change = updated - lambda;
    if (change != 0.0)
    {
        a.apply(p.armA, change * p.normal);
        b.apply(p.armB, -change * p.normal);
        lambda = updated;
    }
    return std::abs(change) * p.compliance;
}

/// The least move in the mass metric with phi_i + (displacement of a - displacement of b) . n_i >= 0
/// for every point (normals point from b toward a), by projected Gauss-Seidel on lambda_i >= 0.
void separatingMove(const std::vector<ContactPoint>& points, PushedBody& a, PushedBody& b, PushOutScratch& scratch)
{
    std::vector<PreparedPushPoint>& prepared = scratch.prepared;
    prepared.clear();
    for (const ContactPoint& p : points)
    {
        prepared.push_back(prepare(p, a, b));
    }
    std::vector<Real>& lambda = scratch.lambda;
    lambda.assign(points.size(), 0.0);
    for (int sweep = 0; sweep < kSolverSweeps; ++sweep)
    {
        Real largestChange = 0.0; // m: of any point's gap
        for (std::size_t i = 0; i < prepared.size(); ++i)
        {
            largestChange = std::max(largestChange, relaxPoint(prepared[i], a, b, lambda[i]));
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
    separatingMove(points, push, held, scratch);
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
    separatingMove(points, pushA, pushB, scratch);
    // one fraction for both, so that the pair's centre of mass still stays put
    const Real scale = std::min(keptFraction(pushA, a, reachA, depth), keptFraction(pushB, b, reachB, depth));
    const bool movedA = movePose(a, pushA, scale);
    const bool movedB = movePose(b, pushB, scale);
    return movedA || movedB;
}

void pushApartTogether(std::vector<RigidBody>& bodies, const std::vector<JointPoint>& points, Real allowance,
                       const std::function<Real(std::uint32_t)>& reach, std::vector<int>& slotOf,
                       PushOutScratch& scratch)
{
    scratch.moved.clear();
    Real depth = 0.0;
    for (const JointPoint& p : points)
    {
        depth = std::max(depth, -p.point.phi);
    }
    if (!(depth > allowance))
    {
        return;
    }
    // a slot for every dynamic body the points touch; static bodies share the held one
    scratch.pushed.assign(1, PushedBody{});
    scratch.members.clear();
    const auto slot = [&](std::uint32_t i)
    {
        if (!bodies[i].dynamic)
        {
            return 0;
        }
        if (slotOf[i] < 0)
        {
            slotOf[i] = static_cast<int>(scratch.pushed.size());
            scratch.pushed.emplace_back(bodies[i]);
            scratch.members.push_back(i);
        }
        return slotOf[i];
    };
    std::vector<PreparedPushPoint>& prepared = scratch.prepared;
    prepared.clear();
    for (const JointPoint& p : points)
    {
        const std::array<int, 2> slots{slot(p.a), slot(p.b)}; // both first: a new slot may move the others
        PreparedPushPoint point = prepare(p.point, scratch.pushed[static_cast<std::size_t>(slots[0])],
                                          scratch.pushed[static_cast<std::size_t>(slots[1])]);
        point.slots = slots;
        prepared.push_back(point);
    }

    // a hundredth of the allowance: what is left is far shallower than what a push sets out to clear
    const Real tolerance = std::max(kSolverTolerance, 1e-2 * allowance);
    std::vector<Real>& lambda = scratch.lambda;
    lambda.assign(points.size(), 0.0);
    std::vector<PushedBody>& pushed = scratch.pushed;
    for (int sweep = 0; sweep < kJointSolverSweeps; ++sweep)
    {
        Real largestChange = 0.0; // m: of any point's gap
        for (std::size_t n = 0; n < prepared.size(); ++n)
        {
            PushedBody& a = pushed[static_cast<std::size_t>(prepared[n].slots[0])];
            PushedBody& b = pushed[static_cast<std::size_t>(prepared[n].slots[1])];
            largestChange = std::max(largestChange, relaxPoint(prepared[n], a, b, lambda[n]));
        }
        if (largestChange < tolerance)
        {
            break;
        }
    }
    for (std::size_t m = 0; m < scratch.members.size(); ++m)
    {
        const std::uint32_t i = scratch.members[m];
        const PushedBody& push = pushed[m + 1];
        if (movePose(bodies[i], push, keptFraction(push, bodies[i], reach(i), depth)))
        {
            scratch.moved.push_back(i);
        }
        slotOf[i] = -1;
    }
}

} // namespace impulse
