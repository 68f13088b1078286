// SPDX-License-Identifier: MIT
// The collision pass of GBF03 sec. 4: resolving one pair of bodies elastically.
//
// Detection and depth ranking happen at the predicted poses: only the deepest point that is still
// approaching gets an impulse, then both bodies are re-predicted and the pair is searched again, so
// several corners of a box share the work in the order of their depth. Several points that approach
// at once (a box landing flat) are first given their restitution together, as one small problem
// solved by the contact rows' Gauss-Seidel (contact_solver.hpp).
//
// Two refinements, each switchable in StepOptions:
// - mid-step restitution: the approach test uses the state velocity v (a resting body never
//   approaches: no threshold), but the impulse is sized with the normal velocity at time n,
//   v + dt a/2, because symplectic Euler's v lives at the half step. For eps = 1 this keeps the
//   discrete energy exactly; sizing it with v loses m |a.n| |v| dt per bounce. The correction
//   fades out for approaches slower than dt |a.n| (see midStepCorrection).
// - time-of-impact geometry: the contact point, normal and lever arms are taken where the bodies
//   first touch within the step (regula falsi on the pair's least signed distance along the
//   predicted path) rather than at the overlapping predicted pose.
#include "dynamics/collision_pass.hpp"

#include "collision/narrow_phase.hpp"
#include "dynamics/contact_solver.hpp"
#include "dynamics/impulse.hpp"
#include "dynamics/integrate.hpp"
#include "dynamics/rigid_patch.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

namespace impulse
{
namespace
{

constexpr Real kInfinity = std::numeric_limits<Real>::infinity();

Vec3 predictionVelocity(const RigidBody& body, const PassSettings& settings)
{
    // the body's own acceleration: gravity and the forces applied for this step
    return settings.predictWithAcceleration ? Vec3(body.linearVelocity + settings.dt * body.acceleration)
                                            : body.linearVelocity;
}

Pose poseAtFraction(const RigidBody& body, const PassSettings& settings, Real fraction)
{
    if (!body.dynamic)
    {
        return body.pose();
    }
    if (std::holds_alternative<Sphere>(body.shape) && body.shapeCentred())
    {
        // a sphere's contacts depend on its centre alone, so its turn is not worked out: a rotation
        // per prediction is a tenth of a sphere pile's step
        Pose pose = body.pose();
        pose.position += (fraction * settings.lookahead) * predictionVelocity(body, settings);
        return pose;
    }
    return advanceBody(body, predictionVelocity(body, settings), fraction * settings.lookahead);
}

// Normal velocity to add to u_rel so that the collision impulse is sized with the time-n velocity
// v + dt a/2 rather than the half-step velocity v. The term fades linearly for approach speeds
// below one step of acceleration, |u_n| < dt |a_n|: there an impact cannot be told from resting
// contact, and a resting body's round-off approach must not earn it a kick of dt |a_n| / 2.
Real midStepCorrection(const RigidBody& a, const RigidBody& b, Real un, const Vec3& normal,
                       const PassSettings& settings)
{
    const Vec3 accelerationA = a.dynamic ? a.acceleration : Vec3::Zero();
    const Vec3 accelerationB = b.dynamic ? b.acceleration : Vec3::Zero();
    const Real an = (accelerationA - accelerationB).dot(normal);
    if (!(an < 0.0))
    {
        return 0.0; // acceleration separates the pair: nothing to correct
    }
    const Real oneStep = -settings.dt * an;
    const Real weight = std::min(1.0, -un / oneStep);
    return weight * 0.5 * settings.dt * an;
}

const ContactPoint* deepestApproaching(const RigidBody& a, const Pose& poseA, const RigidBody& b, const Pose& poseB,
                                       Real threshold, const std::vector<ContactPoint>& points,
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

// Moves `contact`, `poseA` and `poseB` back to the first touch of the pair within the step, when the
// pair was apart at time n and overlaps at the predicted pose.
void moveToFirstTouch(const RigidBody& a, const RigidBody& b, const PassSettings& settings,
                      std::vector<ContactPoint>& scratch, NarrowPhaseScratch& narrowPhase, ContactPoint& contact,
                      Pose& poseA, Pose& poseB)
{
    const auto distanceAt = [&](Real fraction, Pose& pa, Pose& pb)
    {
        pa = poseAtFraction(a, settings, fraction);
        pb = poseAtFraction(b, settings, fraction);
        return leastSignedDistance(a.shape, a.shapePose(pa), b.shape, b.shapePose(pb), narrowPhase);
    };
    Pose pa;
    Pose pb;
    Real lo = 0.0;
    Real flo = distanceAt(lo, pa, pb);
    if (!(flo > 0.0))
    {
        return; // already touching at time n: resting contact, the common case in a pile
    }
    Real hi = 1.0;
    Real fhi = distanceAt(hi, pa, pb);
    if (!(fhi <= 0.0))
    {
        return; // nothing to bracket
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
    // the points at the first touch, to find the one to respond at
    pa = poseAtFraction(a, settings, hi);
    pb = poseAtFraction(b, settings, hi);
    scratch.clear();
    collideShapes(a.shape, a.shapePose(pa), b.shape, b.shapePose(pb), kInfinity, scratch, narrowPhase);
    if (const ContactPoint* touch = deepestApproaching(a, pa, b, pb, kInfinity, scratch, settings))
    {
        contact = *touch;
        poseA = pa;
        poseB = pb;
    }
}

// Speed at which the pair closes at a contact, from the state velocities alone: what the
// restitution threshold is compared with.
Real closingSpeed(const RigidBody& a, const Pose& poseA, const RigidBody& b, const Pose& poseB,
                  const ContactPoint& contact)
{
    const LeverCentres centres = leverCentres(a, poseA, b, poseB);
    return -(a.pointVelocityAbout(contact.point, centres.a) - b.pointVelocityAbout(contact.point, centres.b))
                .dot(contact.normal);
}

// Restitution at a closing speed: none below the restitution threshold, and faded in linearly from
// the resting approach to twice it, so that resting contact turns into bouncing without a jump.
Real restitutionAt(Real eps, Real closing, const PassSettings& settings)
{
    if (closing < settings.restitutionThreshold)
    {
        return 0.0;
    }
    if (settings.restingApproach > 0.0)
    {
        eps *= std::clamp(closing / settings.restingApproach - 1.0, 0.0, 1.0);
    }
    return eps;
}

ContactBody contactBody(const RigidBody& body, const Vec3& point, const Vec3& centre)
{
    if (body.immovable())
    {
        return {};
    }
    return {body.invMass, body.invInertiaWorld, point - centre};
}

bool applyContactImpulse(RigidBody& a, RigidBody& b, const ContactPoint& contact, const Pose& poseA, const Pose& poseB,
                         Real eps, Real mu, const PassSettings& settings)
{
    const LeverCentres centres = leverCentres(a, poseA, b, poseB);
    const ContactBody ca = contactBody(a, contact.point, centres.a);
    const ContactBody cb = contactBody(b, contact.point, centres.b);
    const Mat3 K = collisionMatrix(ca, cb);
    const Vec3 uRel = relativeVelocity(a, poseA, b, poseB, contact, settings);
    if (eps > 0.0)
    {
        eps = restitutionAt(eps, closingSpeed(a, poseA, b, poseB, contact), settings);
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

// What a patch of a mesh is thinned to (thinPatch).
constexpr std::size_t kMeshPatchPoints = 16;

// Keeps at most kMeshPatchPoints points of a large patch with a mesh (lying on a face, a mesh
// touches at many vertices): the deepest, then each time the point farthest from those kept. The
// kept points span the contact region, and a rigid motion that does not approach at the corners of
// a region does not approach inside it. Patches of analytic shapes are at most eight points.
void thinPatch(std::vector<ContactPoint>& patch, SolverScratch& scratch)
{
    if (patch.size() <= kMeshPatchPoints)
    {
        return;
    }
    std::size_t deepest = 0;
    for (std::size_t k = 1; k < patch.size(); ++k)
    {
        deepest = patch[k].phi < patch[deepest].phi ? k : deepest;
    }
    std::vector<ContactPoint>& kept = scratch.kept;
    std::vector<Real>& gap = scratch.gap;
    kept.assign(1, patch[deepest]);
    gap.resize(patch.size());
    for (std::size_t k = 0; k < patch.size(); ++k)
    {
        gap[k] = (patch[k].point - patch[deepest].point).squaredNorm();
    }
    while (kept.size() < kMeshPatchPoints)
    {
        const auto farthest = static_cast<std::size_t>(std::max_element(gap.begin(), gap.end()) - gap.begin());
        if (!(gap[farthest] > 0.0))
        {
            break; // the rest coincide with points already kept
        }
        kept.push_back(patch[farthest]);
        for (std::size_t k = 0; k < patch.size(); ++k)
        {
            gap[k] = std::min(gap[k], (patch[k].point - patch[farthest].point).squaredNorm());
        }
    }
    patch.swap(kept); // kept keeps the storage for the next call
}

// A patch gets the restitution of its fastest closing point: all slow means no bounce.
Real patchRestitution(const RigidBody& a, const RigidBody& b, Real eps, const std::vector<ContactPoint>& patch,
                      const PassSettings& settings)
{
    if (!(eps > 0.0))
    {
        return eps;
    }
    Real closing = 0.0;
    for (const ContactPoint& point : patch)
    {
        closing = std::max(closing, closingSpeed(a, a.predicted, b, b.predicted, point));
    }
    return restitutionAt(eps, closing, settings);
}

// Gives every point of the patch its restitution at once: the rows of the points, each with the
// target normal velocity -eps u_n (u_n with the mid-step correction) and no slip, solved together by
// projected Gauss-Seidel (loads >= 0, friction within the cone). A box landing flat then bounces
// flat, where one corner at a time would set it spinning. Applied only if it adds no kinetic energy
// (to 1e-9 of it): targets out of reach at a pinch, two normals nearly opposed, can make the loads
// fight each other; the deepest point alone then takes over.
bool applyPatchRestitution(RigidBody& a, RigidBody& b, const std::vector<ContactPoint>& patch, Real eps, Real mu,
                           const PassSettings& settings, SolverScratch& scratch)
{
    constexpr int kPatchSweeps = 16;
    std::array<SolverBody, 2> bodies = {SolverBody::of(a), SolverBody::of(b)};
    const LeverCentres centres = leverCentres(a, a.predicted, b, b.predicted);
    std::vector<ContactRow>& rows = scratch.rows;
    rows.clear();
    Real speed = 0.0;
    for (const ContactPoint& point : patch)
    {
        Vec3 t1;
        Vec3 t2;
        tangentBasis(point.normal, t1, t2);
        ContactRow row = makeContactRow(RowSide::of(a, 0, centres.a), RowSide::of(b, 1, centres.b), point, t1, t2, mu);
        row.gap = -kInfinity; // in play throughout
        const Real un = row.relativeVelocity(0, bodies[0], bodies[1]);
        const Real correction = settings.midStepRestitution ? midStepCorrection(a, b, un, point.normal, settings) : 0.0;
        row.bias = -eps * (un + correction) - correction;
        speed = std::max(speed, std::abs(un));
        rows.push_back(row);
    }
    const Real before = bodies[0].kineticEnergy() + bodies[1].kineticEnergy();
    // one rigid motion meets every target when the patch sticks; else Gauss-Seidel lets points slide
    std::vector<ContactRow*>& pointers = scratch.pointers;
    pointers.clear();
    for (ContactRow& row : rows)
    {
        pointers.push_back(&row);
    }
    const PatchMover moverA{0, centres.a, a.invMass, a.invInertiaWorld};
    const PatchMover moverB{1, centres.b, b.invMass, b.invInertiaWorld};
    const bool rigid = a.dynamic
                           ? solveRigidPatch(pointers, bodies, moverA, b.dynamic ? &moverB : nullptr,
                                             kSolverResolution * speed, scratch)
                           : solveRigidPatch(pointers, bodies, moverB, nullptr, kSolverResolution * speed, scratch);
    if (!rigid)
    {
        solveRows(rows, bodies, RowSettings{}, kPatchSweeps, kSolverResolution * speed, Sweeps::Accelerated, scratch);
    }
    const Real after = bodies[0].kineticEnergy() + bodies[1].kineticEnergy();
    if (!(after <= before * (1.0 + 1e-9)))
    {
        return false;
    }
    if (a.dynamic)
    {
        bodies[0].storeInto(a);
    }
    if (b.dynamic)
    {
        bodies[1].storeInto(b);
    }
    return true;
}

} // namespace

// Normal relative velocity at a point when the pair approaches there, zero otherwise. Approach is
// measured net of two floors. One is round-off: a normal velocity within kSolverResolution of the
// velocities it is computed from is zero. The other is the resting approach (in the collision pass):
// a contact pass that stops before round-off leaves a resting pile's contacts closing at a fraction
// of the dt |g| gravity adds in a step, and chasing that remainder through the collision pass would
// cost an impulse per resting point per sweep for a bounce of 0.02 mm at most; the contact pass takes
// those points.
Real approachSpeed(const RigidBody& a, const Pose& poseA, const RigidBody& b, const Pose& poseB,
                   const ContactPoint& point, const PassSettings& settings)
{
    const LeverCentres centres = leverCentres(a, poseA, b, poseB);
    const Vec3 ra = point.point - centres.a;
    const Vec3 rb = point.point - centres.b;
    const Vec3 uRel = a.linearVelocity + a.angularVelocity.cross(ra) - b.linearVelocity - b.angularVelocity.cross(rb);
    const Real un = uRel.dot(point.normal);
    if (!(un < 0.0))
    {
        return 0.0; // separating or still: no need for the round-off scale
    }
    const Real magnitude = a.linearVelocity.norm() + a.angularVelocity.norm() * ra.norm() + b.linearVelocity.norm() +
                           b.angularVelocity.norm() * rb.norm() + settings.dt * settings.gravity.norm();
    return un < -std::max(kSolverResolution * magnitude, settings.restingApproach) ? un : 0.0;
}

bool slowerThanRestingApproach(const RigidBody& a, const RigidBody& b, const PassSettings& settings)
{
    if (!(settings.restingApproach > 0.0))
    {
        return false;
    }
    // A contact point lies within a body's bounding radius (plus the threshold) of its predicted
    // centre, and approachSpeed takes its lever arm from the lever centre. A static body does not
    // turn (and a plane's bounding radius is infinite).
    const LeverCentres centres = leverCentres(a, a.predicted, b, b.predicted);
    const auto spin = [&](const RigidBody& body, const Vec3& centre)
    {
        const Real arm = body.boundingRadius + settings.threshold + (body.predicted.position - centre).norm();
        return body.dynamic ? body.angularVelocity.norm() * arm : 0.0;
    };
    return (a.linearVelocity - b.linearVelocity).norm() + spin(a, centres.a) + spin(b, centres.b) <
           settings.restingApproach;
}

// Relative velocity at a point, with the mid-step correction of the collision pass.
Vec3 relativeVelocity(const RigidBody& a, const Pose& poseA, const RigidBody& b, const Pose& poseB,
                      const ContactPoint& contact, const PassSettings& settings)
{
    const LeverCentres centres = leverCentres(a, poseA, b, poseB);
    Vec3 uRel = a.pointVelocityAbout(contact.point, centres.a) - b.pointVelocityAbout(contact.point, centres.b);
    if (settings.midStepRestitution)
    {
        uRel += midStepCorrection(a, b, uRel.dot(contact.normal), contact.normal, settings) * contact.normal;
    }
    return uRel;
}

Pose predictedPose(const RigidBody& body, const PassSettings& settings)
{
    return poseAtFraction(body, settings, 1.0);
}

void predictBody(RigidBody& body, const PassSettings& settings)
{
    if (body.dynamic)
    {
        const Pose next = poseAtFraction(body, settings, 1.0);
        // counted only when it moves, so that what was found at this pose still holds
        if (next.position != body.predicted.position ||
            next.orientation.coeffs() != body.predicted.orientation.coeffs())
        {
            body.predicted = next;
            ++body.motion;
        }
    }
}

Resolution resolveCollision(RigidBody& a, RigidBody& b, Real eps, Real mu, const PassSettings& settings,
                            ContactScratch& detection, SolverScratch& scratch)
{
    std::vector<ContactPoint>& found = detection.detected;
    std::vector<ContactPoint>& patch = scratch.patch; // the approaching points
    int applied = 0;
    for (int iteration = 0; iteration < settings.pairIterations; ++iteration)
    {
        found.clear();
        collideShapes(a.shape, a.shapePose(a.predicted), b.shape, b.shapePose(b.predicted), settings.threshold, found,
                      detection.narrowPhase);
        patch.clear();
        for (const ContactPoint& point : found)
        {
            if (point.phi < settings.threshold && approachSpeed(a, a.predicted, b, b.predicted, point, settings) < 0.0)
            {
                patch.push_back(point);
            }
        }
        if (patch.empty())
        {
            return {applied, applied == 0};
        }
        thinPatch(patch, scratch);
        if (patch.size() > 1 &&
            applyPatchRestitution(a, b, patch, patchRestitution(a, b, eps, patch, settings), mu, settings, scratch))
        {
            // every approaching point has its target: the next search finds them separating
            predictBody(a, settings);
            predictBody(b, settings);
            ++applied;
            continue;
        }
        // the deepest approaching point, the first of equally deep ones
        ContactPoint contact = patch[0];
        for (const ContactPoint& point : patch)
        {
            contact = point.phi < contact.phi ? point : contact;
        }
        Pose poseA = a.predicted;
        Pose poseB = b.predicted;
        if (settings.timeOfImpactGeometry)
        {
            moveToFirstTouch(a, b, settings, found, detection.narrowPhase, contact, poseA, poseB);
        }
        if (!applyContactImpulse(a, b, contact, poseA, poseB, eps, mu, settings))
        {
            break;
        }
        predictBody(a, settings);
        predictBody(b, settings);
        ++applied;
    }
    return {applied, false};
}

} // namespace impulse
