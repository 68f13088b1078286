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
    Vec3 position = Vec3::Zero();        ///< centre of mass, world frame
    Quat orientation = Quat::Identity(); ///< normalised on creation
    Vec3 linearVelocity = Vec3::Zero();  ///< world frame
    Vec3 angularVelocity = Vec3::Zero(); ///< world frame, rad/s
};

/// Handle to a body of a World; bodies are numbered in creation order.
struct BodyId
{
    std::uint32_t index = 0;
    friend bool operator==(BodyId, BodyId) = default;
};

/// A snapshot of one body, world frame, SI units.
struct BodyState
{
    Vec3 position = Vec3::Zero();
    Quat orientation = Quat::Identity();
    Vec3 linearVelocity = Vec3::Zero();
    Vec3 angularVelocity = Vec3::Zero();
    Vec3 angularMomentum = Vec3::Zero();
};

} // namespace impulse
