// SPDX-License-Identifier: MIT
// The time step of Guendelman, Bridson & Fedkiw 2003, "Nonconvex Rigid Bodies with Stacking".
//
// The step is split so that collision and contact never need a velocity threshold (GBF03 sec. 5):
//
//   S0 = (x, q) of every body, kept untouched until the last stage
//   1. candidate pairs       bounds over S0 and the predicted pose
//   2. collision pass        elastic (material eps) on poses predicted with v + dt a,
//                            responding to v: a body at rest is not approaching, so it never bounces
//   3. contact graph         probe each body with v + dt a: who rests on whom; levels bottom-up
//   4. velocity update       v += dt a
//   5. contact pass          inelastic, eps ramped -1+1/n ... 0, on poses predicted with v,
//                            pairs visited level by level from the ground up
//   6. shock propagation     one more sweep with eps = 0, level by level, lower levels frozen
//   7. position update       x += dt v, q = exp(dt w) q, w = I(q)^-1 L
//
// Each pass sweeps in a fixed order and stops early after a sweep that applies no impulse. The
// collision pass resolves pair by pair; the contact pass and shock propagation go level by level,
// resolving each body against all it rests on as one contact patch (dynamics/contact_patch.cpp),
// with the paper's deepest approaching point as the fallback (dynamics/pair_resolution.cpp).
//
// The traditional order (Scheme::Traditional) reuses the same stages for comparison: update
// velocities and positions first, then resolve collisions and contacts at the new poses.
#include "collision/narrow_phase.hpp"
#include "dynamics/integrate.hpp"
#include "dynamics/pair_resolution.hpp"
#include "world/world_impl.hpp"

#include <algorithm>

namespace impulse
{
namespace
{

PassSettings baseSettings(const StepOptions& options, const Vec3& gravity)
{
    PassSettings settings;
    settings.dt = options.dt;
    settings.gravity = gravity;
    settings.pairIterations = options.pairIterations;
    settings.restitutionThreshold = options.restitutionThreshold;
    return settings;
}

// GBF03 collision pass: predicted with this step's acceleration, detection at phi < 0
PassSettings collisionSettings(const StepOptions& options, const Vec3& gravity)
{
    PassSettings settings = baseSettings(options, gravity);
    settings.lookahead = options.dt;
    settings.predictWithAcceleration = true;
    settings.midStepRestitution = options.midStepRestitution;
    settings.timeOfImpactGeometry = options.timeOfImpactGeometry;
    return settings;
}

// GBF03 contact pass: predicted with the updated velocity, touching within the contact thickness
PassSettings contactSettings(const StepOptions& options, const Vec3& gravity)
{
    PassSettings settings = baseSettings(options, gravity);
    settings.lookahead = options.dt;
    settings.threshold = options.contactThickness;
    return settings;
}

// The traditional order resolves at the poses it has already moved to: no lookahead.
PassSettings atCurrentPoseSettings(const StepOptions& options, const Vec3& gravity, Real threshold)
{
    PassSettings settings = baseSettings(options, gravity);
    settings.threshold = threshold;
    return settings;
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
            fastest = std::max(fastest, body.linearVelocity.norm() + body.angularVelocity.norm() * body.boundingRadius);
        }
    }
    fastest += options.dt * gravity.norm();
    return 2.0 * options.dt * fastest + options.contactThickness;
}

} // namespace

void WorldImpl::step(const StepOptions& options)
{
    stats = {};
    if (options.scheme == Scheme::Traditional)
    {
        stepTraditional(options);
    }
    else
    {
        stepGuendelman(options);
    }
    time += options.dt;
}

void WorldImpl::stepGuendelman(const StepOptions& options)
{
    const PassSettings collision = collisionSettings(options, def.gravity);
    const PassSettings contact = contactSettings(options, def.gravity);
    findCandidatePairs(options, collision);
    solveCollisions(options, collision);
    buildContactGraph(options);
    updateVelocities(options);
    solveContacts(options, contact);
    if (options.shockPropagation)
    {
        propagateShock(options, contact);
    }
    updatePositions(options);
}

void WorldImpl::stepTraditional(const StepOptions& options)
{
    updateVelocities(options);
    updatePositions(options);
    findCandidatePairs(options, atCurrentPoseSettings(options, def.gravity, 0.0));
    assignSingleLevel();
    solveCollisions(options, atCurrentPoseSettings(options, def.gravity, 0.0));
    solveContacts(options, atCurrentPoseSettings(options, def.gravity, options.contactThickness));
}

void WorldImpl::findCandidatePairs(const StepOptions& options, const PassSettings& settings)
{
    for (RigidBody& body : bodies)
    {
        predictBody(body, settings);
    }
    broadPhase.findPairs(bodies, broadPhaseMargin(bodies, options, def.gravity), pairs);
    pairCoefficients.clear();
    for (const BodyPair& pair : pairs)
    {
        pairCoefficients.push_back(coefficients(bodies[pair.a].material, bodies[pair.b].material));
    }
    stats.candidatePairs = static_cast<int>(pairs.size());
}

void WorldImpl::solveCollisions(const StepOptions& options, const PassSettings& settings)
{
    for (RigidBody& body : bodies)
    {
        predictBody(body, settings);
    }
    for (int sweep = 0; sweep < options.collisionIterations; ++sweep)
    {
        int applied = 0;
        for (std::size_t k = 0; k < pairs.size(); ++k)
        {
            applied += resolvePair(bodies[pairs[k].a], bodies[pairs[k].b], pairCoefficients[k].restitution,
                                   pairCoefficients[k].friction, settings, points);
        }
        stats.collisionImpulses += applied;
        ++stats.collisionSweeps;
        if (applied == 0)
        {
            break;
        }
    }
}

void WorldImpl::buildContactGraph(const StepOptions& options)
{
    // GBF03 sec. 8: with every body advanced by its post-collision velocity, advance one body at a
    // time with its new velocity v + dt a. If that pushes it deeper into a neighbour, it rests on
    // that neighbour: edge neighbour -> body. Gravity decides what is above, without an up vector.
    const PassSettings oldVelocity = contactSettings(options, def.gravity);
    PassSettings newVelocity = oldVelocity;
    newVelocity.predictWithAcceleration = true;
    for (RigidBody& body : bodies)
    {
        predictBody(body, oldVelocity);
    }
    bodyPairs.assign(bodies.size(), {});
    for (std::uint32_t k = 0; k < pairs.size(); ++k)
    {
        bodyPairs[pairs[k].a].push_back(k);
        bodyPairs[pairs[k].b].push_back(k);
    }
    const auto deepest = [&](const RigidBody& probe, const Pose& probePose, const RigidBody& other)
    {
        points.clear();
        collideShapes(probe.shape, probePose, other.shape, other.predicted, 0.0, points);
        Real least = 0.0;
        for (const ContactPoint& point : points)
        {
            least = std::min(least, point.phi);
        }
        return least;
    };
    supportEdges.clear();
    for (std::uint32_t p = 0; p < bodies.size(); ++p)
    {
        RigidBody& probe = bodies[p];
        if (!probe.dynamic)
        {
            continue;
        }
        const Pose oldPose = probe.predicted;
        predictBody(probe, newVelocity);
        for (const std::uint32_t k : bodyPairs[p])
        {
            const std::uint32_t j = pairs[k].a == p ? pairs[k].b : pairs[k].a;
            if (deepest(probe, probe.predicted, bodies[j]) < deepest(probe, oldPose, bodies[j]))
            {
                supportEdges.push_back({j, p});
            }
        }
        probe.predicted = oldPose;
    }

    std::vector<bool> isDynamic(bodies.size());
    for (std::size_t i = 0; i < bodies.size(); ++i)
    {
        isDynamic[i] = bodies[i].dynamic;
    }
    const std::vector<int> levels = computeContactLevels(isDynamic, supportEdges);
    int highest = -1;
    for (std::size_t i = 0; i < bodies.size(); ++i)
    {
        bodies[i].level = levels[i];
        highest = std::max(highest, levels[i]);
    }
    stats.contactLevels = highest + 1;

    // visit pairs from the ground up: a pair belongs to the higher level of its two bodies
    std::vector<std::uint32_t> order(pairs.size());
    pairLevels.resize(pairs.size());
    for (std::uint32_t k = 0; k < pairs.size(); ++k)
    {
        order[k] = k;
        pairLevels[k] = std::max(bodies[pairs[k].a].level, bodies[pairs[k].b].level);
    }
    std::sort(order.begin(), order.end(),
              [&](std::uint32_t l, std::uint32_t r)
              { return pairLevels[l] < pairLevels[r] || (pairLevels[l] == pairLevels[r] && l < r); });
    std::vector<BodyPair> sortedPairs(pairs.size());
    std::vector<PairCoefficients> sortedCoefficients(pairs.size());
    std::vector<int> sortedLevels(pairs.size());
    for (std::size_t k = 0; k < order.size(); ++k)
    {
        sortedPairs[k] = pairs[order[k]];
        sortedCoefficients[k] = pairCoefficients[order[k]];
        sortedLevels[k] = pairLevels[order[k]];
    }
    pairs.swap(sortedPairs);
    pairCoefficients.swap(sortedCoefficients);
    pairLevels.swap(sortedLevels);
}

void WorldImpl::assignSingleLevel()
{
    // no contact graph: every dynamic body on one level, so the contact pass resolves each body
    // against the static geometry it touches and every pair of dynamic bodies two-way
    for (RigidBody& body : bodies)
    {
        body.level = body.dynamic ? 0 : -1;
    }
    pairLevels.assign(pairs.size(), 0);
    stats.contactLevels = 1;
}

void WorldImpl::updateVelocities(const StepOptions& options)
{
    for (RigidBody& body : bodies)
    {
        if (body.dynamic)
        {
            body.linearVelocity += options.dt * def.gravity;
        }
    }
}

void WorldImpl::solveContacts(const StepOptions& options, const PassSettings& settings)
{
    for (RigidBody& body : bodies)
    {
        predictBody(body, settings);
    }
    for (int sweep = 1; sweep <= options.contactIterations; ++sweep)
    {
        // restitution ramps -1 + 1/n, ..., 0: early sweeps remove only part of each approach
        const Real eps = -1.0 + static_cast<Real>(sweep) / static_cast<Real>(options.contactIterations);
        const int applied = sweepLevels(eps, false, settings);
        stats.contactImpulses += applied;
        if (applied == 0)
        {
            break;
        }
    }
}

void WorldImpl::propagateShock(const StepOptions&, const PassSettings& settings)
{
    // GBF03 sec. 8: one more sweep up the levels with eps = 0, every body of a lower level frozen
    // (infinite mass) while a level is processed: corrections only travel upward, and a box can no
    // longer push its supports into the ground.
    for (RigidBody& body : bodies)
    {
        predictBody(body, settings);
    }
    stats.shockImpulses += sweepLevels(0.0, true, settings);
    for (RigidBody& body : bodies)
    {
        body.frozen = false;
    }
}

int WorldImpl::sweepLevels(Real eps, bool freezeLowerLevels, const PassSettings& settings)
{
    // Pairs are sorted by level, a pair belonging to the higher level of its two bodies. Within a
    // level each body is resolved against all its supports at once (the pairs with a lower-level or
    // static partner), then the pairs between two bodies of the level are resolved two-way.
    int applied = 0;
    for (std::size_t first = 0; first < pairs.size();)
    {
        const int level = pairLevels[first];
        std::size_t last = first;
        while (last < pairs.size() && pairLevels[last] == level)
        {
            ++last;
        }
        levelBodies.clear();
        for (std::size_t k = first; k < last; ++k)
        {
            for (const std::uint32_t i : {pairs[k].a, pairs[k].b})
            {
                if (freezeLowerLevels)
                {
                    bodies[i].frozen = bodies[i].dynamic && bodies[i].level < level;
                }
                if (bodies[i].dynamic && bodies[i].level == level)
                {
                    levelBodies.push_back(i);
                }
            }
        }
        std::sort(levelBodies.begin(), levelBodies.end());
        levelBodies.erase(std::unique(levelBodies.begin(), levelBodies.end()), levelBodies.end());
        for (const std::uint32_t b : levelBodies)
        {
            supports.clear();
            for (std::size_t k = first; k < last; ++k)
            {
                const BodyPair& pair = pairs[k];
                const std::uint32_t other = pair.a == b ? pair.b : (pair.b == b ? pair.a : b);
                if (other != b && bodies[other].level < level)
                {
                    supports.push_back({&bodies[other], pairCoefficients[k].friction});
                }
            }
            applied += resolveOnSupports(bodies[b], supports, eps, settings, points);
        }
        for (std::size_t k = first; k < last; ++k)
        {
            const BodyPair& pair = pairs[k];
            if (bodies[pair.a].level == level && bodies[pair.b].level == level)
            {
                applied +=
                    resolvePair(bodies[pair.a], bodies[pair.b], eps, pairCoefficients[k].friction, settings, points);
            }
        }
        first = last;
    }
    return applied;
}

void WorldImpl::updatePositions(const StepOptions& options)
{
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
}

} // namespace impulse
