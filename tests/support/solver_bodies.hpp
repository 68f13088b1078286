// SPDX-License-Identifier: MIT
// Bodies and rows built by hand for the contact solver's tests: solid boxes with their velocities,
// the sides rows are made from, and a static ground.
#pragma once

#include "contact/contact_cache.hpp"
#include "dynamics/contact_solver.hpp"

#include <cmath>

namespace impulse::test
{

/// A solid box's principal moments about its centre, axes along the world's (the box is not turned).
inline Vec3 boxInertia(Real mass, const Vec3& half)
{
    return mass / 3.0 *
           Vec3(half.y() * half.y() + half.z() * half.z(), half.x() * half.x() + half.z() * half.z(),
                half.x() * half.x() + half.y() * half.y());
}

/// A dynamic box, axis-aligned, at `centre`, with its velocities.
struct BoxBody
{
    Real mass = 1.0;
    Vec3 half = Vec3::Constant(0.5);
    Vec3 centre = Vec3::Zero();
    Vec3 velocity = Vec3::Zero();
    Vec3 spin = Vec3::Zero();

    Mat3 inertia() const { return boxInertia(mass, half).asDiagonal(); }
    Mat3 invInertia() const { return boxInertia(mass, half).cwiseInverse().asDiagonal(); }
    SolverBody solver() const
    {
        SolverBody body;
        body.linearVelocity = velocity;
        body.angularVelocity = spin;
        body.angularMomentum = inertia() * spin;
        body.mass = mass;
        body.invMass = 1.0 / mass;
        body.reach = half.norm();
        return body;
    }
    RowSide side(std::uint32_t index) const { return {index, true, 1.0 / mass, invInertia(), centre}; }
};

inline RowSide staticSide(std::uint32_t index)
{
    return {index, false, 0.0, Mat3::Zero(), Vec3::Zero()};
}

/// The row of a point with normal `normal` (from B toward A), tangents from tangentBasis.
inline ContactRow rowAt(const RowSide& a, const RowSide& b, const Vec3& point, const Vec3& normal, Real friction)
{
    Vec3 t1;
    Vec3 t2;
    tangentBasis(normal, t1, t2);
    return makeContactRow(a, b, {point, normal, 0.0, 0, SampleOf::A}, t1, t2, friction);
}

/// The relative velocity u_A - u_B of the row's point, world frame.
inline Vec3 relativeVelocity(const ContactRow& row, const SolverBody& a, const SolverBody& b)
{
    return row.relativeVelocity(0, a, b) * row.direction[0] + row.relativeVelocity(1, a, b) * row.direction[1] +
           row.relativeVelocity(2, a, b) * row.direction[2];
}

/// The part of it across the normal.
inline Vec3 slip(const ContactRow& row, const SolverBody& a, const SolverBody& b)
{
    return row.relativeVelocity(1, a, b) * row.direction[1] + row.relativeVelocity(2, a, b) * row.direction[2];
}

/// Total angular momentum about the origin of bodies with centres `centres`.
template <class Bodies, class Centres> Vec3 angularMomentumAboutOrigin(const Bodies& bodies, const Centres& centres)
{
    Vec3 total = Vec3::Zero();
    for (std::size_t i = 0; i < bodies.size(); ++i)
    {
        total += centres[i].cross(bodies[i].mass * bodies[i].linearVelocity) + bodies[i].angularMomentum;
    }
    return total;
}

} // namespace impulse::test
