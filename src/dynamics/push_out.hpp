// SPDX-License-Identifier: MIT
#pragma once

#include "collision/contact.hpp"
#include "dynamics/rigid_body.hpp"

#include <array>
#include <cstdint>
#include <functional>
#include <vector>

namespace impulse
{

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

    /// How far a point moves along `n` under the move so far; `lever` is its arm from the centre
    /// crossed with `n`.
    Real displacement(const Vec3& n, const Vec3& lever) const { return n.dot(move) + lever.dot(turn); }

    /// Normal displacement of a point per unit pseudo-impulse along its normal, by its `lever`.
    Real compliance(const Vec3& lever) const { return invMass + lever.dot(invInertia * lever); }

    /// Applies a pseudo-impulse at the point `arm` from the centre.
    void apply(const Vec3& arm, const Vec3& pseudoImpulse)
    {
        move += invMass * pseudoImpulse;
        turn += invInertia * arm.cross(pseudoImpulse);
    }

    /// How far the body's farthest point moves, to first order.
    Real reachUsed(Real boundingRadius) const { return move.norm() + turn.norm() * boundingRadius; }
};

/// One point of a joint push: the two bodies it lies between, by index into the world's bodies,
/// and the point, its normal from b toward a.
struct JointPoint
{
    std::uint32_t a = 0;
    std::uint32_t b = 0;
    ContactPoint point;
};

/// A point of a push with what its relaxation reads at every sweep worked out once: its arms from
/// the two bodies' centres and their cross products with the normal, and its compliance along the
/// normal; in a joint push also the slots of its two bodies.
struct PreparedPushPoint
{
    std::array<int, 2> slots{};
    Vec3 normal = Vec3::Zero();
    Vec3 armA = Vec3::Zero();
    Vec3 armB = Vec3::Zero();
    Vec3 leverA = Vec3::Zero(); ///< armA x normal
    Vec3 leverB = Vec3::Zero(); ///< armB x normal
    Real phi = 0.0;
    Real compliance = 0.0;
};

/// What a push reuses from one call to the next (one per worker thread).
struct PushOutScratch
{
    std::vector<ContactPoint> points;        ///< for the caller to gather a push's points in
    std::vector<JointPoint> jointPoints;     ///< for the caller to gather a joint push's points in
    std::vector<Real> lambda;                ///< per point: how far the solution moves along its normal
    std::vector<PushedBody> pushed;          ///< a joint push's bodies
    std::vector<std::uint32_t> members;      ///< their indices in the world
    std::vector<PreparedPushPoint> prepared; ///< a push's points, prepared
    std::vector<std::uint32_t> moved;        ///< the bodies the last joint push moved
    std::vector<std::uint32_t> around;       ///< for the caller: the neighbours a joint push takes in
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

/// Moves every dynamic body of `points` at once: the least move of all of them together, in their
/// joint mass metric, that brings every point to phi >= 0 (to first order), by projected
/// Gauss-Seidel over all the points; static bodies stay put. A light body pressed into the ground
/// by a heavy one is then held by the ground while the heavy one moves, where pair-by-pair pushes
/// would shuttle it between the two, each clearing only the heavy body's small share. Nothing moves
/// unless some point lies deeper than `allowance`; each body's move is cut back as a single push's
/// is (within `reach(i)`, turning no further than the deepest overlap). `slotOf` maps a body index
/// to its slot and must hold -1 for every body on entry; it does again on return. The bodies moved
/// are left in scratch.moved.
void pushApartTogether(std::vector<RigidBody>& bodies, const std::vector<JointPoint>& points, Real allowance,
                       const std::function<Real(std::uint32_t)>& reach, std::vector<int>& slotOf,
                       PushOutScratch& scratch);

} // namespace impulse
