// SPDX-License-Identifier: MIT
// The simulation record of one body.
//
// GBF03 sec. 2: the primary variables are the centre of mass x, the unit quaternion q, the linear
// velocity v and the angular momentum L. The angular velocity is derived, w = I(q)^-1 L, and is
// recomputed whenever q or L changes, so torque-free precession keeps L constant. During a step
// (x, q) stay the time-n pose S0 untouched; every pass works on `predicted`, a pose advanced from
// S0, and only the position update writes x and q.
#pragma once

#include <impulse/material.hpp>
#include <impulse/math.hpp>
#include <impulse/shape.hpp>

#include <cstdint>

namespace impulse
{

struct RigidBody
{
    // constant
    Shape shape;
    MaterialId material;
    bool dynamic = true;
    Real mass = 0.0;                         ///< infinite for static bodies
    Real invMass = 0.0;                      ///< zero for static bodies
    Vec3 principalInertia = Vec3::Zero();    ///< body frame
    Vec3 invPrincipalInertia = Vec3::Zero(); ///< body frame; zero for static bodies
    /// Where the shape's origin sits in the body frame, whose origin is the centre of mass: minus
    /// BodyDef::centerOfMass. Zero for a body whose mass is spread as its shape's. Every geometric
    /// query places the shape at shapePose(pose), every lever arm starts at pose.position.
    Vec3 shapeOffset = Vec3::Zero();
    /// Radius about the centre of mass of a sphere holding the shape: the shape's own bounding
    /// radius plus |shapeOffset|, so that speed times it bounds how fast any point of the body moves.
    Real boundingRadius = 0.0;

    // state at time n
    Vec3 position = Vec3::Zero();
    Quat orientation = Quat::Identity();
    Mat3 rotation = Mat3::Identity();
    Vec3 linearVelocity = Vec3::Zero();
    Vec3 angularMomentum = Vec3::Zero();

    // derived at the time-n orientation
    Mat3 invInertiaWorld = Mat3::Zero(); ///< R I_b^-1 R^T
    Vec3 angularVelocity = Vec3::Zero(); ///< invInertiaWorld * angularMomentum

    // per-step scratch
    /// Pose at the end of the step under the velocities of the current pass. A sphere's orientation
    /// stays at time n: nothing about its contacts depends on it.
    Pose predicted;
    std::uint32_t motion = 0; ///< how many times `predicted` was placed (predictBody): a change stamp
    int level = -1;           ///< contact-graph level this step; -1 for static bodies
    bool frozen = false;      ///< treated as infinite mass during shock propagation

    // set through the World API (world/world.cpp): mass properties, loads, filtering, removal
    /// Principal axes of inertia in the body frame, as columns: I_body = inertiaAxes diag(I) inertiaAxes^T.
    /// The identity (and principalAxesAligned true) unless an inertia tensor with products of inertia was set.
    Mat3 inertiaAxes = Mat3::Identity();
    bool principalAxesAligned = true;
    Vec3 force = Vec3::Zero();        ///< N, world frame, through the centre of mass; for the next step
    Vec3 torque = Vec3::Zero();       ///< N m, world frame; for the next step
    Vec3 acceleration = Vec3::Zero(); ///< this step's g + force / m, set when the step begins; zero if static
    std::uint32_t collisionGroup = 1;
    std::uint32_t collisionMask = 0xffffffffU;
    bool removed = false; ///< taken out of the world: static, in no pair, its index never reused

    // sleeping (StepOptions::sleep): a body asleep is at rest and out of the step until woken
    bool asleep = false;
    Real restingTime = 0.0;       ///< s it has moved slower than StepOptions::sleepSpeed
    std::uint32_t sleepGroup = 0; ///< the island it fell asleep with (its lowest body index): woken together

    /// Static, or frozen by shock propagation: impulses do not move it.
    bool immovable() const { return !dynamic || frozen; }

    Pose pose() const { return {position, orientation, rotation}; }
    /// Whether the centre of mass is the shape's origin (the shape's pose is the body's, bit for bit).
    bool shapeCentred() const { return shapeOffset.isZero(0.0); }
    /// Where the shape lies when the body is at `at`.
    Pose shapePose(const Pose& at) const
    {
        if (shapeCentred())
        {
            return at;
        }
        return {at.position + at.rotation * shapeOffset, at.orientation, at.rotation};
    }
    /// World frame from the principal axes of inertia: `rotation` unless they differ from the body axes.
    Mat3 principalRotation() const { return principalAxesAligned ? rotation : Mat3(rotation * inertiaAxes); }
    /// Velocity of the material point at world point p, with the body placed at `at`.
    Vec3 pointVelocity(const Vec3& p, const Pose& at) const { return pointVelocityAbout(p, at.position); }
    /// Velocity of the material point at world point p, its lever arm taken from `centre`.
    Vec3 pointVelocityAbout(const Vec3& p, const Vec3& centre) const
    {
        return linearVelocity + angularVelocity.cross(p - centre);
    }
};

/// The centres a contact's lever arms are taken from (arm = contact point - centre), for a contact
/// found with the bodies placed at poseA and poseB.
struct LeverCentres
{
    Vec3 a;
    Vec3 b;
};

/// Between two dynamic bodies both arms end at one point: the contact carried back to time n by the
/// pair's mean displacement, with the arms from the time-n centres of mass. An impulse then has the
/// same moment about any origin on both bodies, and a collision keeps angular momentum to round-off;
/// each arm from its own displaced centre would apply the impulse at two points (d_a - d_b) apart, a
/// first-order change of dt (v_a - v_b) x j. Against a static body, which takes up any angular
/// momentum, the moving body's arm is from its centre at its pose.
inline LeverCentres leverCentres(const RigidBody& a, const Pose& poseA, const RigidBody& b, const Pose& poseB)
{
    if (!a.dynamic || !b.dynamic)
    {
        return {poseA.position, poseB.position};
    }
    const Vec3 meanDisplacement = 0.5 * ((poseA.position - a.position) + (poseB.position - b.position));
    return {a.position + meanDisplacement, b.position + meanDisplacement};
}

} // namespace impulse
