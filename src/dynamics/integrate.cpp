// SPDX-License-Identifier: MIT
#include "dynamics/integrate.hpp"

#include <cmath>

namespace impulse
{

Pose advancePose(const Pose& start, const Vec3& linearVelocity, const Vec3& angularVelocity, Real dt)
{
    Pose pose;
    pose.position = start.position + dt * linearVelocity;
    const Real angle = angularVelocity.norm() * dt;
    if (angle > 0.0)
    {
        const Vec3 axis = angularVelocity.normalized();
        const Quat spin(Eigen::AngleAxisd(angle, axis));
        pose.orientation = (spin * start.orientation).normalized();
        pose.rotation = pose.orientation.toRotationMatrix();
    }
    else
    {
        pose.orientation = start.orientation;
        pose.rotation = start.rotation;
    }
    return pose;
}

void updateDerivedQuantities(RigidBody& body)
{
    if (!body.dynamic)
    {
        body.invInertiaWorld.setZero();
        body.angularVelocity.setZero();
        return;
    }
    const Mat3 axes = body.principalRotation();
    body.invInertiaWorld = axes * body.invPrincipalInertia.asDiagonal() * axes.transpose();
    body.angularVelocity = body.invInertiaWorld * body.angularMomentum;
}

void applyImpulse(RigidBody& body, const Vec3& impulse, const Vec3& leverArm)
{
    body.linearVelocity += body.invMass * impulse;
    body.angularMomentum += leverArm.cross(impulse);
    body.angularVelocity = body.invInertiaWorld * body.angularMomentum;
}

} // namespace impulse
