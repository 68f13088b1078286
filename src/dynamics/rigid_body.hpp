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

    /// Static, or frozen by shock propagation: impulses do not move it.
    bool immovable() const { return !dynamic || frozen; }

    Pose pose() const { return {position, orientation, rotation}; }
    /// Velocity of the material point at world point p, with the body placed at `at`.
    Vec3 pointVelocity(const Vec3& p, const Pose& at) const
    {
        return linearVelocity + angularVelocity.cross(p - at.position);
    }
};

} // namespace impulse
