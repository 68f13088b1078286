// SPDX-License-Identifier: MIT
#pragma once

#include <impulse/material.hpp>
#include <impulse/math.hpp>
#include <impulse/shape.hpp>

#include <cstdint>

namespace impulse
{

enum class BodyType
{
    Static,  ///< infinite mass, never moves
    Dynamic, ///< moves under gravity and impulses
};

/// Which pairs of bodies collide. Two bodies collide when each one's group shares a bit with the
/// other's mask: (a.group & b.mask) != 0 and (b.group & a.mask) != 0. The default (group 1, every
/// bit of the mask set) collides with everything; a mask of 0 collides with nothing.
struct CollisionFilter
{
    std::uint32_t group = 1;
    std::uint32_t mask = 0xffffffffU;
    friend bool operator==(const CollisionFilter&, const CollisionFilter&) = default;
};

/// Everything needed to create a body. Exactly one of mass and density must be positive for a
/// dynamic body; mass wins when both are set.
struct BodyDef
{
    BodyType type = BodyType::Dynamic;
    Shape shape = Sphere{};
    MaterialId material{};
    Real mass = 0.0;    ///< kg
    Real density = 0.0; ///< kg/m^3, used when mass is 0
    /// Principal moments of inertia, kg m^2, body frame; zero (the default): those of the shape as a
    /// solid of uniform density with the body's mass. Set by model loaders that carry their own.
    Vec3 principalInertia = Vec3::Zero();
    Vec3 position = Vec3::Zero();        ///< centre of mass, world frame (see centerOfMass)
    Quat orientation = Quat::Identity(); ///< normalised on creation
    Vec3 linearVelocity = Vec3::Zero();  ///< world frame
    Vec3 angularVelocity = Vec3::Zero(); ///< world frame, rad/s
    CollisionFilter filter{};            ///< which other bodies it collides with
    /// A full inertia tensor, kg m^2, about the centre of mass in the body frame, for a body whose
    /// mass is not spread as the shape's; zero (the default): principalInertia applies. Checked and
    /// diagonalised as World::setMassProperties does.
    Mat3 inertia = Mat3::Zero();
    /// Where the centre of mass sits in the shape's own frame (m), for a body whose mass is not spread
    /// as the shape's (a weighted die, a hull with ballast); zero (the default): the shape's centroid.
    /// The body frame keeps the shape's axes with its origin here, so `position` places this point
    /// and the shape lies at position - R centerOfMass (World::shapePose). The inertia, given or the
    /// shape's own, is about this point. Dynamic bodies only.
    Vec3 centerOfMass = Vec3::Zero();
};

/// Handle to a body of a World; bodies are numbered in creation order from 0, and a number is never
/// given to another body, not even after World::removeBody.
struct BodyId
{
    std::uint32_t index = 0;
    friend bool operator==(BodyId, BodyId) = default;
};

/// A snapshot of one body, world frame, SI units.
struct BodyState
{
    Vec3 position = Vec3::Zero();        ///< m, the centre of mass (the body frame's origin)
    Quat orientation = Quat::Identity(); ///< unit quaternion turning the body frame into the world frame
    Vec3 linearVelocity = Vec3::Zero();  ///< m/s, of the centre of mass
    Vec3 angularVelocity = Vec3::Zero(); ///< rad/s; derived: I(q)^-1 L
    Vec3 angularMomentum = Vec3::Zero(); ///< kg m^2/s, about the centre of mass
};

} // namespace impulse
