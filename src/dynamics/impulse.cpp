// SPDX-License-Identifier: MIT
// One contact impulse with Coulomb friction, static or kinetic, with the energy safeguards that
// keep sequential impulses from adding relative kinetic energy (GBF03 sec. 6; report eq. 5-8).
#include "dynamics/impulse.hpp"

#include <Eigen/Cholesky>

#include <cmath>

namespace impulse
{
namespace
{
Mat3 cross(const Vec3& r)
{
    Mat3 m;
    m << 0.0, -r.z(), r.y(), r.z(), 0.0, -r.x(), -r.y(), r.x(), 0.0;
    return m;
}

} // namespace

Mat3 couplingMatrix(Real invMass, const Mat3& invInertiaWorld, const Vec3& ri, const Vec3& rk)
{
    return invMass * Mat3::Identity() - cross(ri) * invInertiaWorld * cross(rk);
}

Mat3 collisionMatrix(const ContactBody& a, const ContactBody& b)
{
    return couplingMatrix(a.invMass, a.invInertiaWorld, a.leverArm, a.leverArm) +
           couplingMatrix(b.invMass, b.invInertiaWorld, b.leverArm, b.leverArm);
}

Vec3 computeImpulse(const Vec3& uRel, const Vec3& n, const Mat3& K, Real eps, Real mu)
{
    const Real un = uRel.dot(n);
    if (!(un < 0.0))
    {
        return Vec3::Zero();
    }
    // K is symmetric, and positive definite unless both bodies are immovable
    const Eigen::LLT<Mat3> factor(K);
    if (factor.info() != Eigen::Success)
    {
        return Vec3::Zero();
    }
    const Vec3 ut = uRel - un * n;

    // static friction: stop the slip and set the normal velocity to -eps u_n
    const Vec3 deltaU = -(1.0 + eps) * un * n - ut;
    const Vec3 sticking = factor.solve(deltaU);
    const Real stickingNormal = sticking.dot(n);
    const Real stickingTangent = (sticking - stickingNormal * n).norm();
    const bool insideCone = stickingNormal > 0.0 && stickingTangent <= mu * stickingNormal;
    // work done on the relative motion: j . (u + du/2) <= 0 means no kinetic energy gained
    // (zero for a frictionless elastic hit; the tolerance absorbs round-off of that zero)
    const bool dissipative = sticking.dot(uRel + 0.5 * deltaU) <= 1e-12 * sticking.norm() * uRel.norm();
    if (insideCone && dissipative)
    {
        return sticking;
    }

    // kinetic friction opposes the slip: j = j_n (n - mu t)
    const Real slip = ut.norm();
    Vec3 direction = n;
    if (slip > 0.0 && mu > 0.0)
    {
        direction = n - mu * (ut / slip);
    }
    Real response = n.dot(K * direction);
    if (!(response > 0.0))
    {
        direction = n; // friction so strong the response reverses: fall back to the normal alone
        response = n.dot(K * n);
    }
    Vec3 j = (-(1.0 + eps) * un / response) * direction;

    // the change in relative kinetic energy is proportional to a + 2b
    const Real a = j.dot(K * j);
    const Real b = j.dot(uRel);
    if (a + 2.0 * b > 0.0)
    {
        j = b < 0.0 ? Vec3((-2.0 * b / a) * j) : Vec3::Zero();
    }
    return j;
}

} // namespace impulse
