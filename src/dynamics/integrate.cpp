// SPDX-License-Identifier: MIT
#include "dynamics/integrate.hpp"

#include <cmath>
#include <limits>

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

Vec3 stepAngularVelocity(const RigidBody& body, Real dt)
{
    const Vec3& inverse = body.invPrincipalInertia;
    if (inverse.x() == inverse.y() && inverse.y() == inverse.z())
    {
        return body.angularVelocity; // L stays along w: nothing to correct
    }
    // in the principal frame: fixed-point iteration of w = I^-1 (L + exp(-dt w) L) / 2, a contraction
    // of about dt |w| per round
    const Mat3 axes = body.principalRotation();
    const Vec3 momentum = axes.transpose() * body.angularMomentum;
    Vec3 w = inverse.cwiseProduct(momentum);
    constexpr int kRounds = 64;
    for (int round = 0; round < kRounds; ++round)
    {
        const Real angle = w.norm() * dt;
        const Vec3 turned = angle > 0.0 ? Vec3(Eigen::AngleAxisd(-angle, w / w.norm()) * momentum) : momentum;
        const Vec3 next = inverse.cwiseProduct(0.5 * (momentum + turned));
        const bool settled = (next - w).norm() <= 4.0 * std::numeric_limits<Real>::epsilon() * next.norm();
        w = next;
        if (settled)
        {
            break;
        }
    }
    return axes * w;
}

Pose advanceBody(const RigidBody& body, const Vec3& linearVelocity, Real dt)
{
    return advancePose(body.pose(), linearVelocity, stepAngularVelocity(body, dt), dt);
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
