// SPDX-License-Identifier: MIT
#pragma once

#include <impulse/math.hpp>

namespace impulse
{

/// Inverse-mass data of one side of a contact: zero for static or frozen bodies.
struct ContactBody
{
    Real invMass = 0.0;
    Mat3 invInertiaWorld = Mat3::Zero();
    Vec3 leverArm = Vec3::Zero(); ///< contact point minus centre of mass
};

/// The block of the collision matrix that maps an impulse at lever arm rk to a velocity change at
/// lever arm ri of one body: m^-1 1 - [ri]x I^-1 [rk]x (zero for a static or frozen body).
Mat3 couplingMatrix(Real invMass, const Mat3& invInertiaWorld, const Vec3& ri, const Vec3& rk);

/// K = K_A + K_B with K_i = m_i^-1 1 - [r_i]x I_i^-1 [r_i]x: an impulse j at the contact changes the
/// relative velocity there by K j (GBF03 sec. 6; report eq. 5).
Mat3 collisionMatrix(const ContactBody& a, const ContactBody& b);

/// The impulse on A (B receives its negative) for relative velocity uRel = u_A - u_B at the contact,
/// unit normal n from B toward A, collision matrix K, restitution eps (negative values remove only
/// part of the approach, as the contact pass's ramp does) and Coulomb friction mu.
///
/// Static case: the impulse that leaves u_rel' = -eps u_n n (no slip), kept if it lies in the friction
/// cone and adds no relative kinetic energy. Kinetic case otherwise: j = j_n (n - mu t) along the
/// slip direction t, scaled back if it would add energy. Zero when uRel . n >= 0.
Vec3 computeImpulse(const Vec3& uRel, const Vec3& n, const Mat3& K, Real eps, Real mu);

} // namespace impulse
