// SPDX-License-Identifier: MIT
#pragma once

#include "collision/contact.hpp"
#include "contact/contact_cache.hpp"
#include "dynamics/contact_solver.hpp"
#include "dynamics/rigid_body.hpp"

#include <vector>

namespace impulse
{

/// What a pass needs to know about predicting bodies and resolving collisions.
struct PassSettings
{
    Real dt = 0.0;
    Vec3 gravity = Vec3::Zero();
    /// How far ahead bodies are predicted: dt in the Guendelman order; 0 in the traditional order,
    /// which detects at the poses it has already moved to.
    Real lookahead = 0.0;
    /// Predict with v + dt a instead of v: the collision pass of the Guendelman order, which runs
    /// before the velocity update. Enables the two refinements below.
    bool predictWithAcceleration = false;
    bool midStepRestitution = false;
    bool timeOfImpactGeometry = false;
    Real threshold = 0.0;            ///< points with phi below this count as touching
    int pairIterations = 20;         ///< cap on impulses per pair per sweep
    Real restitutionThreshold = 0.0; ///< approach speeds below this get restitution 0
    Real restingApproach = 0.0;      ///< m/s; slower approach is resting contact (StepOptions)
};

/// Relative velocity u_a - u_b at a contact point with the bodies at the given poses; in the
/// collision pass it includes the mid-step correction of the normal velocity.
Vec3 relativeVelocity(const RigidBody& a, const Pose& poseA, const RigidBody& b, const Pose& poseB,
                      const ContactPoint& contact, const PassSettings& settings);

/// The normal relative velocity at a point when the pair approaches there (negative), else zero.
/// Normal velocities within 64 ulp of the velocities they are computed from count as zero.
Real approachSpeed(const RigidBody& a, const Pose& poseA, const RigidBody& b, const Pose& poseB,
                   const ContactPoint& point, const PassSettings& settings);

/// Whether no point of the pair can approach faster than the resting approach at the predicted poses,
/// whatever the geometry: the fastest a point can move relative to the other body (linear velocities,
/// and the spins times the farthest a contact point lies from the lever centres) is below it. Then
/// approachSpeed is zero at every point, and resolveCollision would find nothing to resolve.
bool slowerThanRestingApproach(const RigidBody& a, const RigidBody& b, const PassSettings& settings);

/// Pose of the body at the end of the step under the velocities this pass uses.
Pose predictedPose(const RigidBody& body, const PassSettings& settings);

/// Places body.predicted at predictedPose and counts the move in body.motion (when it moved). Static bodies keep
/// theirs (their pose, set when they are created), so that passes on different threads never write
/// to a body they share.
void predictBody(RigidBody& body, const PassSettings& settings);

/// What resolving a pair did.
struct Resolution
{
    int impulses = 0;
    /// Nothing was approaching at the predicted poses: while no body involved is predicted anew
    /// (RigidBody::motion unchanged), resolving again would find nothing again.
    bool quiet = false;
};

/// GBF03 sec. 4, the collision pass: up to settings.pairIterations times, detect the pair exactly at
/// the predicted poses, resolve what approaches there (restitution eps, friction mu) and re-predict
/// both bodies. Several points approaching at once are given their restitution together (a box
/// landing flat bounces flat); otherwise, or when that would add energy, the deepest alone.
Resolution resolveCollision(RigidBody& a, RigidBody& b, Real eps, Real mu, const PassSettings& settings,
                            ContactScratch& detection, SolverScratch& scratch);

} // namespace impulse
