// SPDX-License-Identifier: MIT
// Resolving one pair of bodies: the inner loop shared by the collision and the contact pass.
//
// Detection and depth ranking happen at the predicted poses (GBF03 sec. 4): only the deepest point
// that is still approaching gets an impulse, then both bodies are re-predicted and the pair is
// searched again, so several corners of a box share the work in the order of their depth.
//
// Several points that approach at once form a contact patch and are first resolved together
// (contact_patch.cpp); when the patch does not stick, the deepest point is resolved alone.
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
#include "dynamics/contact_patch.hpp"
#include "dynamics/impulse.hpp"
#include "dynamics/integrate.hpp"

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
    if (std::holds_alternative<Sphere>(body.shape))
    {
        // a sphere's contacts depend on its centre alone, so its turn is not worked out: a rotation
        // per prediction is a tenth of a sphere pile's step
        Pose pose = body.pose();
        pose.position += (fraction * settings.lookahead) * predictionVelocity(body, settings);
        return pose;
    }
    return advancePose(body.pose(), predictionVelocity(body, settings), body.angularVelocity,
                       fraction * settings.lookahead);
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
                      std::vector<ContactPoint>& scratch, ContactPoint& contact, Pose& poseA, Pose& poseB)
{
    const auto distanceAt = [&](Real fraction, Pose& pa, Pose& pb)
    {
        pa = poseAtFraction(a, settings, fraction);
        pb = poseAtFraction(b, settings, fraction);
        return leastSignedDistance(a.shape, pa, b.shape, pb, scratch);
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
    collideShapes(a.shape, pa, b.shape, pb, kInfinity, scratch);
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
    return -(a.pointVelocity(contact.point, poseA) - b.pointVelocity(contact.point, poseB)).dot(contact.normal);
}

ContactBody contactBody(const RigidBody& body, const Vec3& point, const Pose& pose)
{
    if (body.immovable())
    {
        return {};
    }
    return {body.invMass, body.invInertiaWorld, point - pose.position};
}

bool applyContactImpulse(RigidBody& a, RigidBody& b, const ContactPoint& contact, const Pose& poseA, const Pose& poseB,
                         Real eps, Real mu, const PassSettings& settings)
{
    const ContactBody ca = contactBody(a, contact.point, poseA);
    const ContactBody cb = contactBody(b, contact.point, poseB);
    const Mat3 K = collisionMatrix(ca, cb);
    const Vec3 uRel = relativeVelocity(a, poseA, b, poseB, contact, settings);
    if (eps > 0.0 && closingSpeed(a, poseA, b, poseB, contact) < settings.restitutionThreshold)
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

// The most points resolved together as one patch. A box on two boxes gives up to eight points on
// each once it has turned a little about the vertical (the clipped faces are then octagons, not
// rectangles); resolved one pair at a time instead, such a box keeps a twist and slip that no
// single pair's impulse removes, and a pyramid of cubes never comes to rest.
constexpr std::size_t kMaxPatchPoints = 16;
// What a mesh's patch is thinned to (reducePatch).
constexpr std::size_t kMeshPatchPoints = 8;

// Keeps at most kMeshPatchPoints points of a large patch of a mesh (lying on a face, a mesh touches
// at many vertices): the deepest, then each time the point farthest from those kept. The kept points
// span the contact region, and a rigid motion that does not approach at the corners of a region does
// not approach inside it. Patches of analytic shapes are left whole: a pair of them gives at most
// eight points and a body on two such supports at most sixteen; a larger patch falls back to its pairs.
void reducePatch(const RigidBody& body, std::vector<PatchPoint>& patch)
{
    const auto isMesh = [](const RigidBody& b) { return std::holds_alternative<Mesh>(b.shape); };
    if (patch.size() <= kMeshPatchPoints ||
        !(isMesh(body) ||
          std::any_of(patch.begin(), patch.end(), [&](const PatchPoint& p) { return isMesh(*p.other); })))
    {
        return;
    }
    std::size_t deepest = 0;
    for (std::size_t k = 1; k < patch.size(); ++k)
    {
        deepest = patch[k].contact.phi < patch[deepest].contact.phi ? k : deepest;
    }
    thread_local std::vector<PatchPoint> kept;
    thread_local std::vector<Real> gap;
    kept.assign(1, patch[deepest]);
    gap.resize(patch.size());
    for (std::size_t k = 0; k < patch.size(); ++k)
    {
        gap[k] = (patch[k].contact.point - patch[deepest].contact.point).squaredNorm();
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
            gap[k] = std::min(gap[k], (patch[k].contact.point - patch[farthest].contact.point).squaredNorm());
        }
    }
    patch.swap(kept); // kept keeps the storage for the next call
}

// Appends the touching points of `body` against `other` that approach, as patch points.
void collectApproaching(const RigidBody& body, RigidBody& other, Real friction, const PassSettings& settings,
                        const std::vector<ContactPoint>& points, std::vector<PatchPoint>& patch)
{
    for (const ContactPoint& point : points)
    {
        if (point.phi < settings.threshold &&
            approachSpeed(body, body.predicted, other, other.predicted, point, settings) < 0.0)
        {
            patch.push_back({point, &other, friction});
        }
    }
}

// Do all points of the patch share one normal (a face on a face)? Meshes touching along curved or
// faceted surfaces give patches whose normals differ; the least-squares patch cannot re-spread
// those, and one point at a time they rock each other, so they go to the projected solve.
bool planar(const std::vector<PatchPoint>& patch)
{
    return std::all_of(patch.begin(), patch.end(),
                       [&](const PatchPoint& p) { return p.contact.normal.isApprox(patch[0].contact.normal, 1e-9); });
}

// The restitution threshold applies per patch as it does per point: all slow means no bounce.
Real patchRestitution(const RigidBody& body, Real eps, const std::vector<PatchPoint>& patch,
                      const PassSettings& settings)
{
    if (!(eps > 0.0) || !(settings.restitutionThreshold > 0.0))
    {
        return eps;
    }
    for (const PatchPoint& point : patch)
    {
        if (closingSpeed(body, body.predicted, *point.other, point.other->predicted, point.contact) >=
            settings.restitutionThreshold)
        {
            return eps;
        }
    }
    return 0.0;
}

} // namespace

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
    if (!(un < 0.0))
    {
        return 0.0; // separating or still: no need for the round-off scale
    }
    const Real magnitude = a.linearVelocity.norm() + a.angularVelocity.norm() * ra.norm() + b.linearVelocity.norm() +
                           b.angularVelocity.norm() * rb.norm() + settings.dt * settings.gravity.norm();
    return un < -64.0 * std::numeric_limits<Real>::epsilon() * magnitude ? un : 0.0;
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

Pose predictedPose(const RigidBody& body, const PassSettings& settings)
{
    return poseAtFraction(body, settings, 1.0);
}

void predictBody(RigidBody& body, const PassSettings& settings)
{
    if (body.dynamic)
    {
        body.predicted = poseAtFraction(body, settings, 1.0);
        ++body.motion;
    }
}

Resolution resolvePair(RigidBody& a, RigidBody& b, Real eps, Real mu, const PassSettings& settings,
                       std::vector<ContactPoint>& scratch)
{
    thread_local std::vector<PatchPoint> patch; // kept per thread: allocates only when a patch is larger than before
    int applied = 0;
    for (int iteration = 0; iteration < settings.pairIterations; ++iteration)
    {
        scratch.clear();
        collideShapes(a.shape, a.predicted, b.shape, b.predicted, settings.threshold, scratch);
        patch.clear();
        collectApproaching(a, b, mu, settings, scratch, patch);
        if (patch.empty())
        {
            return {applied, applied == 0};
        }
        reducePatch(a, patch);
        const Real patchEps = patchRestitution(a, eps, patch, settings);
        if (patch.size() > 1 && patch.size() <= kMaxPatchPoints &&
            (applyPatchImpulse(a, patch, patchEps, settings) ||
             (!planar(patch) && applyProjectedPatchImpulse(a, patch, patchEps, settings))))
        {
            // every approaching point has its target: repeating would only compound a negative
            // restitution of the ramp, or chase round-off
            predictBody(a, settings);
            predictBody(b, settings);
            ++applied;
            break;
        }
        // the deepest approaching point, the first of equally deep ones
        ContactPoint contact = patch[0].contact;
        for (const PatchPoint& point : patch)
        {
            contact = point.contact.phi < contact.phi ? point.contact : contact;
        }
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
        if (eps < 0.0 && patch.size() == 1)
        {
            // A ramp sweep removes part of an approach, u_n' = |eps| u_n, once per visit (as a
            // patch does). With a single approaching point, repeating would find that same point
            // still approaching and compound the ramp into |eps|^k, at up to pairIterations
            // impulses per resting ball and sweep. Several points go on sharing the work in depth
            // order, as the paper's loop does.
            break;
        }
    }
    return {applied, false};
}

Resolution resolveOnSupports(RigidBody& body, std::span<const Support> supports, Real eps, const PassSettings& settings,
                             std::vector<ContactPoint>& scratch)
{
    // how many approaching points each support gave to the patch
    thread_local std::vector<std::size_t> approaching;
    approaching.clear();
    if (supports.size() > 1)
    {
        thread_local std::vector<PatchPoint> patch;
        patch.clear();
        for (const Support& support : supports)
        {
            scratch.clear();
            collideShapes(body.shape, body.predicted, support.body->shape, support.body->predicted, settings.threshold,
                          scratch);
            const std::size_t before = patch.size();
            collectApproaching(body, *support.body, support.friction, settings, scratch, patch);
            approaching.push_back(patch.size() - before);
        }
        reducePatch(body, patch);
        if (patch.size() > 1 && patch.size() <= kMaxPatchPoints &&
            (applyPatchImpulse(body, patch, eps, settings) || applyProjectedPatchImpulse(body, patch, eps, settings)))
        {
            predictBody(body, settings);
            for (const Support& support : supports)
            {
                predictBody(*support.body, settings);
            }
            return {1, false};
        }
    }
    // Each support is then resolved as a pair. Until one of them applies an impulse, nothing has
    // moved since the patch was collected (a patch that is not applied changes no velocity), so a
    // support that gave no approaching point would detect the same points and find none again: it
    // is passed over. A resting box on two others that finds nothing approaching skips both.
    Resolution all{0, true};
    for (std::size_t s = 0; s < supports.size(); ++s)
    {
        const Support& support = supports[s];
        if (all.impulses == 0 && !approaching.empty() && approaching[s] == 0)
        {
            continue;
        }
        const Resolution one = resolvePair(body, *support.body, eps, support.friction, settings, scratch);
        all.impulses += one.impulses;
        all.quiet = all.quiet && one.quiet;
    }
    return all;
}

} // namespace impulse
