// SPDX-License-Identifier: MIT
// The time step of Guendelman, Bridson & Fedkiw 2003, "Nonconvex Rigid Bodies with Stacking".
//
// The step is split so that collision and contact never need a velocity threshold (GBF03 sec. 5):
//
//   S0 = (x, q) of every body, kept untouched until the last stage
//   1. candidate pairs       bounds over S0 and the predicted pose
//   2. collision pass        elastic (material eps) on poses predicted with v + dt a,
//                            responding to v: a body at rest is not approaching, so it never bounces
//   3. velocity update       v += dt a
//   4. contact pass          inelastic, eps ramped -1+1/n ... 0, on poses predicted with v
//   5. position update       x += dt v, q = exp(dt w) q, w = I(q)^-1 L
//
// Each pass sweeps the pairs in a fixed order, resolving each pair's deepest approaching point
// (dynamics/pair_resolution.cpp), and stops early after a sweep that applies no impulse.
#include "dynamics/integrate.hpp"
#include "dynamics/pair_resolution.hpp"
#include "world/world_impl.hpp"

#include <algorithm>

namespace impulse
{
namespace
{

PassSettings passSettings(Pass pass, const StepOptions& options, const Vec3& gravity)
{
    PassSettings settings;
    settings.pass = pass;
    settings.dt = options.dt;
    settings.gravity = gravity;
    settings.threshold = pass == Pass::Collision ? 0.0 : options.contactThickness;
    settings.pairIterations = options.pairIterations;
    settings.midStepRestitution = options.midStepRestitution;
    settings.timeOfImpactGeometry = options.timeOfImpactGeometry;
    return settings;
}

void predictAll(std::vector<RigidBody>& bodies, const PassSettings& settings)
{
    for (RigidBody& body : bodies)
    {
        predictBody(body, settings);
    }
}

// How far a body might travel this step beyond its predicted pose once impulses have changed its
// velocity: twice the fastest surface speed in the world (an elastic hit from a heavy body at most
// doubles a speed), over one step.
Real broadPhaseMargin(const std::vector<RigidBody>& bodies, const StepOptions& options, const Vec3& gravity)
{
    Real fastest = 0.0;
    for (const RigidBody& body : bodies)
    {
        if (body.dynamic)
        {
            fastest = std::max(fastest, body.linearVelocity.norm() +
                                            body.angularVelocity.norm() * body.boundingRadius);
        }
    }
    fastest += options.dt * gravity.norm();
    return 2.0 * options.dt * fastest + options.contactThickness;
}

} // namespace

void WorldImpl::step(const StepOptions& options)
{
    stats = {};
    const Vec3 gravity = def.gravity;

    // 1. candidate pairs over the time-n pose and the pose predicted for the collision pass
    const PassSettings collision = passSettings(Pass::Collision, options, gravity);
    predictAll(bodies, collision);
    broadPhase.findPairs(bodies, broadPhaseMargin(bodies, options, gravity), pairs);
    pairCoefficients.clear();
    for (const BodyPair& pair : pairs)
    {
        pairCoefficients.push_back(coefficients(bodies[pair.a].material, bodies[pair.b].material));
    }
    stats.candidatePairs = static_cast<int>(pairs.size());

    // 2. collision pass: elastic, with each pair's own restitution
    for (int sweep = 0; sweep < options.collisionIterations; ++sweep)
    {
        int applied = 0;
        for (std::size_t k = 0; k < pairs.size(); ++k)
        {
            applied += resolvePair(bodies[pairs[k].a], bodies[pairs[k].b], pairCoefficients[k].restitution,
                                   pairCoefficients[k].friction, collision, points);
        }
        stats.collisionImpulses += applied;
        ++stats.collisionSweeps;
        if (applied == 0)
        {
            break;
        }
    }

    // 3. velocity update
    for (RigidBody& body : bodies)
    {
        if (body.dynamic)
        {
            body.linearVelocity += options.dt * gravity;
        }
    }

    // 4. contact pass: inelastic, restitution ramped up to zero
    const PassSettings contact = passSettings(Pass::Contact, options, gravity);
    predictAll(bodies, contact);
    for (int sweep = 1; sweep <= options.contactIterations; ++sweep)
    {
        const Real eps = -1.0 + static_cast<Real>(sweep) / static_cast<Real>(options.contactIterations);
        int applied = 0;
        for (std::size_t k = 0; k < pairs.size(); ++k)
        {
            applied += resolvePair(bodies[pairs[k].a], bodies[pairs[k].b], eps, pairCoefficients[k].friction,
                                   contact, points);
        }
        stats.contactImpulses += applied;
        if (applied == 0)
        {
            break;
        }
    }

    // 5. position update, then the angular velocity at the new orientation
    for (RigidBody& body : bodies)
    {
        if (!body.dynamic)
        {
            continue;
        }
        const Pose next = advancePose(body.pose(), body.linearVelocity, body.angularVelocity, options.dt);
        body.position = next.position;
        body.orientation = next.orientation;
        body.rotation = next.rotation;
        updateDerivedQuantities(body);
    }
    time += options.dt;
}

} // namespace impulse
