// SPDX-License-Identifier: MIT
#pragma once

#include "collision/contact.hpp"
#include "dynamics/rigid_body.hpp"

#include <vector>

namespace impulse
{

/// What a pass needs to know to resolve pairs.
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
    Real threshold = 0.0;        ///< points with phi below this count as touching
    int pairIterations = 20;     ///< cap on impulses per pair per sweep
    Real restitutionThreshold = 0.0; ///< approach speeds below this get restitution 0
};

/// Places body.predicted at the end of the step under the velocities this pass uses.
void predictBody(RigidBody& body, const PassSettings& settings);

/// GBF03 sec. 4: up to settings.pairIterations times, find the deepest approaching sample point of
/// the pair at the predicted poses, apply one impulse (restitution eps, friction mu) and re-predict
/// both bodies. Returns the number of impulses applied.
int resolvePair(RigidBody& a, RigidBody& b, Real eps, Real mu, const PassSettings& settings,
                std::vector<ContactPoint>& scratch);

} // namespace impulse
