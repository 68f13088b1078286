// SPDX-License-Identifier: MIT
// Resolving one pair of bodies: the inner loop shared by the collision and the contact pass.
//
// Detection and depth ranking happen at the predicted poses (GBF03 sec. 4): only the deepest point
// that is still approaching gets an impulse, then both bodies are re-predicted and the pair is
// searched again, so several corners of a box share the work in the order of their depth.
//
// Contact patches. When several points of the pair approach at once (a box flat on the ground, a
// cube on a cube) the impulses at all of them are first solved together: the least-squares,
// minimum-norm impulses that give every point its sticking target (normal velocity -eps u_n, no
// slip). The rigid relative motion makes those targets consistent, and for a patch at rest the
// solution spreads the load evenly with no tangential part. It is used when it is admissible:
// every normal impulse non-negative, each in its friction cone, no kinetic energy gained.
// Otherwise the deepest point alone gets an impulse as above, so sliding and tipping follow the
// paper. One point at a time, friction answers the transient tilt each corner's impulse causes
// and turns it into sideways slip and spin: a frictional stack then jitters at millimetres per
// second, where the patch solve leaves it at rest.
//
// Two refinements apply to the collision pass only, each switchable in StepOptions:
// - mid-step restitution: the approach test uses the state velocity v (a resting body never
//   approaches: no threshold), but the impulse is sized with the normal velocity at time n,
//   v + dt a/2, because symplectic Euler's v lives at the half step. For eps = 1 this keeps the
//   discrete energy exactly; sizing it with v loses m |a.n| |v| dt per bounce. The correction
//   fades out for approaches slower than dt |a.n| (see midStepCorrection).
// - time-of-impact geometry: the contact point, normal and lever arms are taken where the bodies
//   first touch within the step (regula falsi on the pair's least signed distance along the
//   predicted path) rather than at the overlapping predicted pose.
#include "dynamics/pair_resolution.hpp"

#include "collision/narrow_phase.hpp"
#include "dynamics/impulse.hpp"
#include "dynamics/integrate.hpp"

#include <Eigen/QR>

#include <cmath>
#include <limits>

namespace impulse
{
namespace
{

constexpr Real kInfinity = std::numeric_limits<Real>::infinity();

Vec3 predictionVelocity(const RigidBody& body, const PassSettings& settings)
{
    return settings.predictWithAcceleration ? Vec3(body.linearVelocity + settings.dt * settings.gravity)
                                            : body.linearVelocity;
}

Pose poseAtFraction(const RigidBody& body, const PassSettings& settings, Real fraction)
{
    if (!body.dynamic)
    {
        return body.pose();
    }
    return advancePose(body.pose(), predictionVelocity(body, settings), body.angularVelocity,
                       fraction * settings.lookahead);
}

// Normal relative velocity at a point when the pair approaches there, zero otherwise. Approach is
// measured net of round-off: a normal velocity within 64 ulp of the velocities it is computed from
// is zero, so resolved contacts are not chased through floating-point noise. This is no velocity
// threshold (it is ~1e-16 m/s for a body at rest): it only keeps the passes from spending their
// iterations on noise.
Real approachSpeed(const RigidBody& a, const Pose& poseA, const RigidBody& b, const Pose& poseB,
                   const ContactPoint& point, const PassSettings& settings)
{
    const Vec3 ra = point.point - poseA.position;
    const Vec3 rb = point.point - poseB.position;
    const Vec3 uRel = a.linearVelocity + a.angularVelocity.cross(ra) - b.linearVelocity - b.angularVelocity.cross(rb);
    const Real un = uRel.dot(point.normal);
    const Real magnitude = a.linearVelocity.norm() + a.angularVelocity.norm() * ra.norm() + b.linearVelocity.norm() +
                           b.angularVelocity.norm() * rb.norm() + settings.dt * settings.gravity.norm();
    return un < -64.0 * std::numeric_limits<Real>::epsilon() * magnitude ? un : 0.0;
}

const ContactPoint* deepestApproaching(const RigidBody& a, const Pose& poseA, const RigidBody& b,
                                       const Pose& poseB, Real threshold, const std::vector<ContactPoint>& points,
                                       const PassSettings& settings)
{
    const ContactPoint* deepest = nullptr;
    for (const ContactPoint& point : points)
    {
        if (!(point.phi < threshold) || (deepest != nullptr && !(point.phi < deepest->phi)))
        {
            continue;
        }
        if (approachSpeed(a, poseA, b, poseB, point, settings) < 0.0)
        {
            deepest = &point;
        }
    }
    return deepest;
}

Real leastDistance(const std::vector<ContactPoint>& points)
{
    Real least = kInfinity;
    for (const ContactPoint& point : points)
    {
        least = std::min(least, point.phi);
    }
    return least;
}

// Moves `contact`, `poseA` and `poseB` back to the first touch of the pair within the step, when the
// pair was apart at time n and overlaps at the predicted pose.
void moveToFirstTouch(const RigidBody& a, const RigidBody& b, const PassSettings& settings,
                      std::vector<ContactPoint>& scratch, ContactPoint& contact, Pose& poseA, Pose& poseB)
{
    const auto distanceAt = [&](Real fraction, Pose& pa, Pose& pb) {
        pa = poseAtFraction(a, settings, fraction);
        pb = poseAtFraction(b, settings, fraction);
        scratch.clear();
        collideShapes(a.shape, pa, b.shape, pb, kInfinity, scratch);
        return leastDistance(scratch);
    };
    Pose pa;
    Pose pb;
    Real lo = 0.0;
    Real flo = distanceAt(lo, pa, pb);
    Real hi = 1.0;
    Real fhi = distanceAt(hi, pa, pb);
    if (!(flo > 0.0) || !(fhi <= 0.0))
    {
        return; // already touching at time n (resting contact), or nothing to bracket
    }
    // Illinois variant of regula falsi: keeps a bracket and converges superlinearly
    int lastSide = 0;
    for (int iteration = 0; iteration < 30 && hi - lo > 1e-12; ++iteration)
    {
        const Real t = (lo * fhi - hi * flo) / (fhi - flo);
        const Real f = distanceAt(t, pa, pb);
        if (f > 0.0)
        {
            lo = t;
            flo = f;
            fhi *= lastSide == -1 ? 0.5 : 1.0;
            lastSide = -1;
        }
        else
        {
            hi = t;
            fhi = f;
            flo *= lastSide == 1 ? 0.5 : 1.0;
            lastSide = 1;
            if (f > -1e-13)
            {
                break;
            }
        }
    }
    distanceAt(hi, pa, pb);
    if (const ContactPoint* touch = deepestApproaching(a, pa, b, pb, kInfinity, scratch, settings))
    {
        contact = *touch;
        poseA = pa;
        poseB = pb;
    }
}

// Normal velocity to add to u_rel so that the collision impulse is sized with the time-n velocity
// v + dt a/2 rather than the half-step velocity v. The term fades linearly for approach speeds
// below one step of acceleration, |u_n| < dt |a_n|: there an impact cannot be told from resting
// contact, and a resting body's round-off approach must not earn it a kick of dt |a_n| / 2.
Real midStepCorrection(const RigidBody& a, const RigidBody& b, Real un, const Vec3& normal,
                       const PassSettings& settings)
{
    const Vec3 accelerationA = a.dynamic ? settings.gravity : Vec3::Zero();
    const Vec3 accelerationB = b.dynamic ? settings.gravity : Vec3::Zero();
    const Real an = (accelerationA - accelerationB).dot(normal);
    if (!(an < 0.0))
    {
        return 0.0; // acceleration separates the pair: nothing to correct
    }
    const Real oneStep = -settings.dt * an;
    const Real weight = std::min(1.0, -un / oneStep);
    return weight * 0.5 * settings.dt * an;
}

Vec3 relativeVelocity(const RigidBody& a, const Pose& poseA, const RigidBody& b, const Pose& poseB,
                      const ContactPoint& contact, const PassSettings& settings);

ContactBody contactBody(const RigidBody& body, const Vec3& point, const Pose& pose)
{
    if (body.immovable())
    {
        return {};
    }
    return {body.invMass, body.invInertiaWorld, point - pose.position};
}

bool applyContactImpulse(RigidBody& a, RigidBody& b, const ContactPoint& contact, const Pose& poseA,
                         const Pose& poseB, Real eps, Real mu, const PassSettings& settings)
{
    const ContactBody ca = contactBody(a, contact.point, poseA);
    const ContactBody cb = contactBody(b, contact.point, poseB);
    const Mat3 K = collisionMatrix(ca, cb);
    const Vec3 uRel = relativeVelocity(a, poseA, b, poseB, contact, settings);
    if (eps > 0.0 && -(a.pointVelocity(contact.point, poseA) - b.pointVelocity(contact.point, poseB)).dot(contact.normal) <
                         settings.restitutionThreshold)
    {
        eps = 0.0;
    }
    const Vec3 j = computeImpulse(uRel, contact.normal, K, eps, mu);
    if (j.isZero(0.0))
    {
        return false;
    }
    if (!a.immovable())
    {
        applyImpulse(a, j, ca.leverArm);
    }
    if (!b.immovable())
    {
        applyImpulse(b, -j, cb.leverArm);
    }
    return true;
}

// Relative velocity at a point, with the mid-step correction of the collision pass.
Vec3 relativeVelocity(const RigidBody& a, const Pose& poseA, const RigidBody& b, const Pose& poseB,
                      const ContactPoint& contact, const PassSettings& settings)
{
    Vec3 uRel = a.pointVelocity(contact.point, poseA) - b.pointVelocity(contact.point, poseB);
    if (settings.midStepRestitution)
    {
        uRel += midStepCorrection(a, b, uRel.dot(contact.normal), contact.normal, settings) * contact.normal;
    }
    return uRel;
}

// Re-spreads the impulses `solved` (3 per point) over the patch without changing their net force and
// moment, so the motion they cause is the same: normal loads with the least norm that carry the
// net normal force and tilting moment, and friction in proportion to each point's load plus a
// torsional part for the moment about the normal. Any rigid patch that sticks can be held this
// way; the least-norm impulses themselves share friction evenly between lightly and heavily loaded
// points and can leave a light one outside its cone. Returns false if a point would have to pull
// or slip. All points of a patch share one normal (the pairs are convex).
bool distributeOverPatch(const std::vector<const ContactPoint*>& patch, const Eigen::VectorXd& solved, Real mu,
                         std::vector<Vec3>& impulses)
{
    const std::size_t n = patch.size();
    const Vec3 normal = patch[0]->normal;
    Vec3 origin = Vec3::Zero();
    for (const ContactPoint* point : patch)
    {
        origin += point->point / static_cast<Real>(n);
    }
    Vec3 force = Vec3::Zero();
    Vec3 moment = Vec3::Zero();
    for (std::size_t k = 0; k < n; ++k)
    {
        const Vec3 j = solved.segment<3>(3 * static_cast<Eigen::Index>(k));
        force += j;
        moment += (patch[k]->point - origin).cross(j);
    }
    const Real normalForce = force.dot(normal);
    if (!(normalForce > 0.0))
    {
        return false;
    }
    const Vec3 tangentialForce = force - normalForce * normal;
    const Real twist = moment.dot(normal);
    const Vec3 tilt = moment - twist * normal;

    // loads: sum = normal force, sum of (p - o) x (load n) = tilting moment; least norm
    Eigen::MatrixXd equations(4, static_cast<Eigen::Index>(n));
    for (std::size_t k = 0; k < n; ++k)
    {
        const Vec3 arm = (patch[k]->point - origin).cross(normal);
        equations.col(static_cast<Eigen::Index>(k)) << 1.0, arm.x(), arm.y(), arm.z();
    }
    const Eigen::Vector4d required(normalForce, tilt.x(), tilt.y(), tilt.z());
    const Eigen::VectorXd loads = equations.completeOrthogonalDecomposition().solve(required);
    if (!loads.allFinite() || (equations * loads - required).norm() > 1e-9 * required.norm())
    {
        return false;
    }
    Vec3 centre = Vec3::Zero();
    for (std::size_t k = 0; k < n; ++k)
    {
        const Real load = loads[static_cast<Eigen::Index>(k)];
        if (load < -1e-12 * normalForce)
        {
            return false; // the moment needs a point to pull: the body tips, not a sticking patch
        }
        centre += load * patch[k]->point;
    }
    centre /= normalForce;

    // friction: the net tangential force in proportion to load, plus kappa * load * n x (p - c),
    // which adds no net force and supplies the remaining moment about the normal
    Real spread = 0.0;
    for (std::size_t k = 0; k < n; ++k)
    {
        spread += loads[static_cast<Eigen::Index>(k)] * (patch[k]->point - centre).squaredNorm();
    }
    const Real remainingTwist = twist - (centre - origin).cross(tangentialForce).dot(normal);
    Real kappa = 0.0;
    if (spread > 0.0)
    {
        kappa = remainingTwist / spread;
    }
    else if (std::abs(remainingTwist) > 1e-12 * normalForce)
    {
        return false; // a twist no spread of friction can supply
    }
    for (std::size_t k = 0; k < n; ++k)
    {
        const Real load = std::max(0.0, loads[static_cast<Eigen::Index>(k)]);
        const Vec3 friction = load * (tangentialForce / normalForce + kappa * normal.cross(patch[k]->point - centre));
        if (friction.norm() > mu * load + 1e-12 * normalForce)
        {
            return false; // this point would slip
        }
        impulses[k] = load * normal + friction;
    }
    return true;
}

// The patch solve described at the top of the file. Returns false, changing nothing, when the
// simultaneous sticking impulses are not admissible.
bool applyPatchImpulse(RigidBody& a, RigidBody& b, const std::vector<const ContactPoint*>& patch, Real eps, Real mu,
                       const PassSettings& settings)
{
    const auto n = static_cast<Eigen::Index>(patch.size());
    const Real invMassA = a.immovable() ? 0.0 : a.invMass;
    const Real invMassB = b.immovable() ? 0.0 : b.invMass;
    const Mat3 invInertiaA = a.immovable() ? Mat3::Zero() : a.invInertiaWorld;
    const Mat3 invInertiaB = b.immovable() ? Mat3::Zero() : b.invInertiaWorld;
    std::vector<Vec3> leverA(patch.size());
    std::vector<Vec3> leverB(patch.size());
    std::vector<Vec3> velocity(patch.size());
    Eigen::MatrixXd coupling(3 * n, 3 * n);
    Eigen::VectorXd target(3 * n);
    for (Eigen::Index i = 0; i < n; ++i)
    {
        const auto k = static_cast<std::size_t>(i);
        leverA[k] = patch[k]->point - a.predicted.position;
        leverB[k] = patch[k]->point - b.predicted.position;
        velocity[k] = relativeVelocity(a, a.predicted, b, b.predicted, *patch[k], settings);
        const Vec3& normal = patch[k]->normal;
        const Real un = velocity[k].dot(normal);
        target.segment<3>(3 * i) = -(1.0 + eps) * un * normal - (velocity[k] - un * normal);
    }
    for (Eigen::Index i = 0; i < n; ++i)
    {
        for (Eigen::Index k = 0; k < n; ++k)
        {
            const auto ui = static_cast<std::size_t>(i);
            const auto uk = static_cast<std::size_t>(k);
            coupling.block<3, 3>(3 * i, 3 * k) = couplingMatrix(invMassA, invInertiaA, leverA[ui], leverA[uk]) +
                                                  couplingMatrix(invMassB, invInertiaB, leverB[ui], leverB[uk]);
        }
    }
    const Eigen::VectorXd solved = coupling.completeOrthogonalDecomposition().solve(target);
    if (!solved.allFinite() || (coupling * solved - target).norm() > 1e-9 * target.norm())
    {
        return false; // the targets are not reachable together
    }
    std::vector<Vec3> impulses(patch.size());
    if (!distributeOverPatch(patch, solved, mu, impulses))
    {
        return false; // the patch would pull somewhere, or slip: not a sticking patch
    }
    Real work = 0.0;
    Real scale = 0.0;
    for (Eigen::Index i = 0; i < n; ++i)
    {
        const auto k = static_cast<std::size_t>(i);
        work += impulses[k].dot(velocity[k] + 0.5 * Vec3(target.segment<3>(3 * i)));
        scale += impulses[k].norm() * velocity[k].norm();
    }
    if (work > 1e-12 * scale)
    {
        return false;
    }
    for (std::size_t k = 0; k < patch.size(); ++k)
    {
        if (!a.immovable())
        {
            applyImpulse(a, impulses[k], leverA[k]);
        }
        if (!b.immovable())
        {
            applyImpulse(b, -impulses[k], leverB[k]);
        }
    }
    return true;
}

constexpr std::size_t kMaxPatchPoints = 8;

// The touching points of the pair that approach, in the order the narrow phase reported them.
void collectApproaching(const RigidBody& a, const RigidBody& b, const PassSettings& settings,
                        const std::vector<ContactPoint>& points, std::vector<const ContactPoint*>& patch)
{
    patch.clear();
    for (const ContactPoint& point : points)
    {
        if (point.phi < settings.threshold && approachSpeed(a, a.predicted, b, b.predicted, point, settings) < 0.0)
        {
            patch.push_back(&point);
        }
    }
}

// The restitution threshold applies per patch as it does per point: all slow means no bounce.
Real patchRestitution(const RigidBody& a, const RigidBody& b, Real eps, const std::vector<const ContactPoint*>& patch,
                      const PassSettings& settings)
{
    if (!(eps > 0.0) || !(settings.restitutionThreshold > 0.0))
    {
        return eps;
    }
    for (const ContactPoint* point : patch)
    {
        const Vec3 u = a.pointVelocity(point->point, a.predicted) - b.pointVelocity(point->point, b.predicted);
        if (-u.dot(point->normal) >= settings.restitutionThreshold)
        {
            return eps;
        }
    }
    return 0.0;
}

} // namespace

void predictBody(RigidBody& body, const PassSettings& settings)
{
    body.predicted = poseAtFraction(body, settings, 1.0);
}

int resolvePair(RigidBody& a, RigidBody& b, Real eps, Real mu, const PassSettings& settings,
                std::vector<ContactPoint>& scratch)
{
    std::vector<const ContactPoint*> patch;
    int applied = 0;
    for (int iteration = 0; iteration < settings.pairIterations; ++iteration)
    {
        scratch.clear();
        collideShapes(a.shape, a.predicted, b.shape, b.predicted, settings.threshold, scratch);
        const ContactPoint* deepest =
            deepestApproaching(a, a.predicted, b, b.predicted, settings.threshold, scratch, settings);
        if (deepest == nullptr)
        {
            break;
        }
        collectApproaching(a, b, settings, scratch, patch);
        if (patch.size() > 1 && patch.size() <= kMaxPatchPoints &&
            applyPatchImpulse(a, b, patch, patchRestitution(a, b, eps, patch, settings), mu, settings))
        {
            // every approaching point has its target: repeating would only compound a negative
            // restitution of the ramp, or chase round-off
            predictBody(a, settings);
            predictBody(b, settings);
            ++applied;
            break;
        }
        ContactPoint contact = *deepest;
        Pose poseA = a.predicted;
        Pose poseB = b.predicted;
        if (settings.timeOfImpactGeometry)
        {
            moveToFirstTouch(a, b, settings, scratch, contact, poseA, poseB);
        }
        if (!applyContactImpulse(a, b, contact, poseA, poseB, eps, mu, settings))
        {
            break;
        }
        predictBody(a, settings);
        predictBody(b, settings);
        ++applied;
    }
    return applied;
}

} // namespace impulse
