// SPDX-License-Identifier: MIT
#pragma once

#include "collision/contact.hpp"
#include "dynamics/rigid_body.hpp"

#include <vector>

namespace impulse
{

enum class Pass
{
    Collision, ///< elastic, before the velocity update; predicts with v + dt a, responds to v
    Contact,   ///< inelastic, after the velocity update; predicts and responds with v
};

/// What a pass needs to know to resolve pairs.
struct PassSettings
{
    Pass pass = Pass::Contact;
    Real dt = 0.0;
    Vec3 gravity = Vec3::Zero();
    Real threshold = 0.0;        ///< points with phi below this count as touching
    int pairIterations = 20;     ///< cap on impulses per pair per sweep
    bool midStepRestitution = true;
    bool timeOfImpactGeometry = true;
};

/// Places body.predicted at the end of the step under the velocities this pass uses.
void predictBody(RigidBody& body, const PassSettings& settings);

/// GBF03 sec. 4: up to settings.pairIterations times, find the deepest approaching sample point of
/// the pair at the predicted poses, apply one impulse (restitution eps, friction mu) and re-predict
/// both bodies. Returns the number of impulses applied.
int resolvePair(RigidBody& a, RigidBody& b, Real eps, Real mu, const PassSettings& settings,
                std::vector<ContactPoint>& scratch);

} // namespace impulse
