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
//   8. push-out              overlaps deeper than an allowance moved apart, positions only,
//                            level by level with lower levels held still (guendelman.md sec. 9)
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
#include "support/parallel.hpp"
#include "world/world_impl.hpp"

#include <algorithm>
#include <chrono>
#include <limits>
#include <span>

namespace impulse
{
namespace
{

// Push-out's two-way relaxation of what the level sweeps leave: in the thousand-body piles a few
// sweeps clear it; the cap bounds the cost when a pile is still being compressed
constexpr int kPushOutSettleSweeps = 16;

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

// Wall time between laps, for StepStats::milliseconds.
class StageClock
{
  public:
    void lap(double& milliseconds)
    {
        const auto now = std::chrono::steady_clock::now();
        milliseconds += std::chrono::duration<double, std::milli>(now - m_last).count();
        m_last = now;
    }

  private:
    std::chrono::steady_clock::time_point m_last = std::chrono::steady_clock::now();
};

} // namespace

void WorldImpl::step(const StepOptions& options)
{
    stats = {};
    threads = resolveThreadCount(options.threads);
    stats.threads = threads;
    scratch.resize(static_cast<std::size_t>(threads));
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
    StageClock clock;
    findCandidatePairs(options, collision);
    buildIslands();
    clock.lap(stats.milliseconds.candidatePairs);
    solveCollisions(options, collision);
    clock.lap(stats.milliseconds.collisionPass);
    buildContactGraph(options);
    clock.lap(stats.milliseconds.contactGraph);
    updateVelocities(options);
    solveContacts(options, contact);
    clock.lap(stats.milliseconds.contactPass);
    if (options.shockPropagation)
    {
        propagateShock(options, contact);
    }
    clock.lap(stats.milliseconds.shockPropagation);
    updatePositions(options);
    clock.lap(stats.milliseconds.positionUpdate);
    if (options.pushOut)
    {
        pushOut(options);
    }
    clock.lap(stats.milliseconds.pushOut);
}

void WorldImpl::stepTraditional(const StepOptions& options)
{
    updateVelocities(options);
    updatePositions(options);
    findCandidatePairs(options, atCurrentPoseSettings(options, def.gravity, 0.0));
    buildIslands();
    assignSingleLevel();
    solveCollisions(options, atCurrentPoseSettings(options, def.gravity, 0.0));
    solveContacts(options, atCurrentPoseSettings(options, def.gravity, options.contactThickness));
}

void WorldImpl::predictAll(const PassSettings& settings)
{
    parallelForEach(threads, bodies.size(), [&](std::size_t i) { predictBody(bodies[i], settings); });
}

void WorldImpl::findCandidatePairs(const StepOptions& options, const PassSettings& settings)
{
    predictAll(settings);
    broadPhase.findPairs(bodies, broadPhaseMargin(bodies, options, def.gravity), threads, pairs);
    pairCoefficients.clear();
    for (const BodyPair& pair : pairs)
    {
        pairCoefficients.push_back(coefficients(bodies[pair.a].material, bodies[pair.b].material));
    }
    stats.candidatePairs = static_cast<int>(pairs.size());
}

void WorldImpl::buildIslands()
{
    // union-find over the pairs of two dynamic bodies; static bodies join no island, as impulses
    // do not move them
    std::vector<std::uint32_t> parent(bodies.size());
    for (std::uint32_t i = 0; i < parent.size(); ++i)
    {
        parent[i] = i;
    }
    const auto root = [&](std::uint32_t i)
    {
        while (parent[i] != i)
        {
            parent[i] = parent[parent[i]];
            i = parent[i];
        }
        return i;
    };
    for (const BodyPair& pair : pairs)
    {
        if (bodies[pair.a].dynamic && bodies[pair.b].dynamic)
        {
            const std::uint32_t ra = root(pair.a);
            const std::uint32_t rb = root(pair.b);
            parent[std::max(ra, rb)] = std::min(ra, rb); // the root is the lowest index
        }
    }
    // islands numbered in the order of their lowest body, each with its pairs in pair order
    constexpr std::uint32_t kNone = UINT32_MAX;
    std::vector<std::uint32_t> islandOf(bodies.size(), kNone);
    std::size_t count = 0;
    for (const BodyPair& pair : pairs)
    {
        for (const std::uint32_t i : {pair.a, pair.b})
        {
            if (bodies[i].dynamic && islandOf[root(i)] == kNone)
            {
                islandOf[root(i)] = 0; // marks the root as used; numbered below
            }
        }
    }
    for (std::uint32_t i = 0; i < bodies.size(); ++i)
    {
        if (islandOf[i] != kNone && root(i) == i)
        {
            islandOf[i] = static_cast<std::uint32_t>(count++);
        }
    }
    islands.resize(count);
    for (Island& island : islands)
    {
        island.bodies.clear();
        island.pairs.clear();
    }
    for (std::uint32_t i = 0; i < bodies.size(); ++i)
    {
        if (bodies[i].dynamic && islandOf[root(i)] != kNone)
        {
            islands[islandOf[root(i)]].bodies.push_back(i);
        }
    }
    for (std::uint32_t k = 0; k < pairs.size(); ++k)
    {
        const std::uint32_t member = bodies[pairs[k].a].dynamic ? pairs[k].a : pairs[k].b;
        islands[islandOf[root(member)]].pairs.push_back(k);
    }
    stats.islands = static_cast<int>(count);
}

void WorldImpl::solveCollisions(const StepOptions& options, const PassSettings& settings)
{
    predictAll(settings);
    beginSweepingPass();
    std::vector<int> applied(islands.size(), 0);
    std::vector<int> sweeps(islands.size(), 0);
    parallelFor(threads, islands.size(),
                [&](std::size_t i, int thread)
                {
                    // each island sweeps until a sweep applies nothing to it, or the cap
                    for (int sweep = 0; sweep < options.collisionIterations; ++sweep)
                    {
                        const int impulses =
                            sweepPairs(islands[i], scratch[static_cast<std::size_t>(thread)], settings);
                        applied[i] += impulses;
                        ++sweeps[i];
                        if (impulses == 0)
                        {
                            break;
                        }
                    }
                });
    for (std::size_t i = 0; i < islands.size(); ++i)
    {
        stats.collisionImpulses += applied[i];
        stats.collisionSweeps = std::max(stats.collisionSweeps, sweeps[i]);
    }
}

void WorldImpl::beginSweepingPass()
{
    // stamps of earlier passes (and of pairs that had other indices in earlier steps) never hold
    ++pass;
    quietPairs.resize(pairs.size());
}

int WorldImpl::resolveUnlessQuiet(std::uint32_t k, Real eps, ThreadScratch& local, const PassSettings& settings)
{
    RigidBody& a = bodies[pairs[k].a];
    RigidBody& b = bodies[pairs[k].b];
    if (quietPairs[k].holds(pass, a, b))
    {
        return 0;
    }
    const Resolution done = resolvePair(a, b, eps, pairCoefficients[k].friction, settings, local.points);
    quietPairs[k] = done.quiet ? QuietStamp{pass, a.motion, b.motion} : QuietStamp{};
    return done.impulses;
}

int WorldImpl::sweepPairs(const Island& island, ThreadScratch& local, const PassSettings& settings)
{
    int applied = 0;
    for (const std::uint32_t k : island.pairs)
    {
        applied += resolveUnlessQuiet(k, pairCoefficients[k].restitution, local, settings);
    }
    return applied;
}

namespace
{

// What the probes of the contact graph found for one pair (bits of WorldImpl::pairProbes).
enum PairProbe : std::uint8_t
{
    kRestsOnB = 1, ///< a, advanced alone with its new velocity, goes deeper into b
    kRestsOnA = 2, ///< b, advanced alone with its new velocity, goes deeper into a
    kTouching = 4, ///< within the contact thickness at the poses predicted with the old velocities
};

// Least signed distance of the pair at the given poses, or +infinity without points.
Real leastPhi(const RigidBody& probe, const Pose& probePose, const RigidBody& other, Real threshold,
              std::vector<ContactPoint>& points)
{
    points.clear();
    collideShapes(probe.shape, probePose, other.shape, other.predicted, threshold, points);
    Real least = std::numeric_limits<Real>::infinity();
    for (const ContactPoint& point : points)
    {
        least = std::min(least, point.phi);
    }
    return least;
}

// Orders `pairs` (ascending indices, as buildIslands leaves them) by level, ties by index: a stable
// counting sort over levels 0 to `highest`, linear where a comparison sort was a few per cent of a
// ten-thousand-body step.
void sortByLevel(std::vector<std::uint32_t>& pairs, const std::vector<int>& pairLevels, int highest)
{
    thread_local std::vector<std::size_t> start;
    thread_local std::vector<std::uint32_t> sorted;
    start.assign(static_cast<std::size_t>(highest) + 2, 0);
    for (const std::uint32_t k : pairs)
    {
        ++start[static_cast<std::size_t>(pairLevels[k]) + 1];
    }
    for (std::size_t level = 1; level < start.size(); ++level)
    {
        start[level] += start[level - 1];
    }
    sorted.resize(pairs.size());
    for (const std::uint32_t k : pairs)
    {
        sorted[start[static_cast<std::size_t>(pairLevels[k])]++] = k;
    }
    pairs.swap(sorted); // sorted keeps the storage for the next island
}

} // namespace

void WorldImpl::buildContactGraph(const StepOptions& options)
{
    // GBF03 sec. 8: with every body advanced by its post-collision velocity, advance one body at a
    // time with its new velocity v + dt a. If that pushes it deeper into a neighbour, it rests on
    // that neighbour: edge neighbour -> body. Gravity decides what is above, without an up vector.
    const PassSettings oldVelocity = contactSettings(options, def.gravity);
    PassSettings newVelocity = oldVelocity;
    newVelocity.predictWithAcceleration = true;
    predictAll(oldVelocity);
    probePoses.resize(bodies.size());
    parallelForEach(threads, bodies.size(),
                    [&](std::size_t i) { probePoses[i] = predictedPose(bodies[i], newVelocity); });

    // every probe of every pair at once: each reads the predicted poses and writes its own slot
    pairProbes.assign(pairs.size(), 0);
    parallelFor(threads, pairs.size(),
                [&](std::size_t k, int thread)
                {
                    std::vector<ContactPoint>& points = scratch[static_cast<std::size_t>(thread)].points;
                    // advance `probe` alone with its new velocity: deeper into `other` means it
                    // rests on it; within the contact thickness at the old poses means touching
                    const auto probeOn = [&](std::uint32_t p, std::uint32_t other, PairProbe restsOn)
                    {
                        const RigidBody& probe = bodies[p];
                        if (!probe.dynamic)
                        {
                            return std::uint8_t{0};
                        }
                        const Real before =
                            leastPhi(probe, probe.predicted, bodies[other], options.contactThickness, points);
                        const Real after = leastPhi(probe, probePoses[p], bodies[other], 0.0, points);
                        return static_cast<std::uint8_t>((before < options.contactThickness ? kTouching : 0) |
                                                         (std::min(after, 0.0) < std::min(before, 0.0) ? restsOn : 0));
                    };
                    std::uint8_t found = probeOn(pairs[k].a, pairs[k].b, kRestsOnB);
                    found |= probeOn(pairs[k].b, pairs[k].a, kRestsOnA);
                    pairProbes[k] = found;
                });
    supportEdges.clear();
    for (std::size_t k = 0; k < pairs.size(); ++k)
    {
        stats.contactPairs += (pairProbes[k] & kTouching) != 0 ? 1 : 0;
        if ((pairProbes[k] & kRestsOnB) != 0)
        {
            supportEdges.push_back({pairs[k].b, pairs[k].a});
        }
        if ((pairProbes[k] & kRestsOnA) != 0)
        {
            supportEdges.push_back({pairs[k].a, pairs[k].b});
        }
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
    pairLevels.resize(pairs.size());
    for (std::uint32_t k = 0; k < pairs.size(); ++k)
    {
        pairLevels[k] = std::max(bodies[pairs[k].a].level, bodies[pairs[k].b].level);
    }
    parallelFor(threads, islands.size(),
                [&](std::size_t i, int thread)
                {
                    sortByLevel(islands[i].pairs, pairLevels, highest);
                    planLevels(islands[i], scratch[static_cast<std::size_t>(thread)]);
                });
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
    for (Island& island : islands)
    {
        planLevels(island, scratch[0]);
    }
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
    predictAll(settings);
    beginSweepingPass();
    std::vector<int> applied(islands.size(), 0);
    parallelFor(threads, islands.size(),
                [&](std::size_t i, int thread)
                {
                    for (int sweep = 1; sweep <= options.contactIterations; ++sweep)
                    {
                        // restitution ramps -1 + 1/n, ..., 0: early sweeps remove only part of each approach
                        const Real eps = -1.0 + static_cast<Real>(sweep) / static_cast<Real>(options.contactIterations);
                        const int impulses =
                            sweepLevels(islands[i], scratch[static_cast<std::size_t>(thread)], eps, false, settings);
                        applied[i] += impulses;
                        if (impulses == 0)
                        {
                            break;
                        }
                    }
                });
    for (const int impulses : applied)
    {
        stats.contactImpulses += impulses;
    }
}

void WorldImpl::propagateShock(const StepOptions&, const PassSettings& settings)
{
    // GBF03 sec. 8: one more sweep up the levels with eps = 0, every body of a lower level frozen
    // (infinite mass) while a level is processed: corrections only travel upward, and a box can no
    // longer push its supports into the ground.
    predictAll(settings);
    beginSweepingPass();
    std::vector<int> applied(islands.size(), 0);
    parallelFor(threads, islands.size(),
                [&](std::size_t i, int thread)
                {
                    applied[i] =
                        sweepLevels(islands[i], scratch[static_cast<std::size_t>(thread)], 0.0, true, settings);
                    for (const std::uint32_t b : islands[i].bodies)
                    {
                        bodies[b].frozen = false;
                    }
                });
    for (const int impulses : applied)
    {
        stats.shockImpulses += impulses;
    }
}

void WorldImpl::planLevels(Island& island, ThreadScratch& local)
{
    // The island's pairs are sorted by level, a pair belonging to the higher level of its two
    // bodies. Within a level each body is resolved against all its supports at once (the pairs with
    // a lower-level or static partner), then the pairs between two bodies of the level two-way.
    // Levels do not change during the contact pass, so this order is worked out once per step.
    island.levels.clear();
    island.levelBodies.clear();
    island.supportStart.clear();
    island.supports.clear();
    island.twoWayPairs.clear();
    island.frozen.clear();
    const std::vector<std::uint32_t>& order = island.pairs;
    for (std::size_t first = 0; first < order.size();)
    {
        const int level = pairLevels[order[first]];
        std::size_t last = first;
        while (last < order.size() && pairLevels[order[last]] == level)
        {
            ++last;
        }
        Island::Level run;
        run.firstBody = static_cast<std::uint32_t>(island.levelBodies.size());
        run.firstPair = static_cast<std::uint32_t>(island.twoWayPairs.size());
        run.firstFrozen = static_cast<std::uint32_t>(island.frozen.size());
        local.supportOf.clear();
        for (std::size_t n = first; n < last; ++n)
        {
            const std::uint32_t k = order[n];
            const BodyPair& pair = pairs[k];
            for (const std::uint32_t i : {pair.a, pair.b})
            {
                const std::uint32_t other = i == pair.a ? pair.b : pair.a;
                if (bodies[i].dynamic && bodies[i].level < level)
                {
                    island.frozen.push_back(i);
                }
                if (bodies[i].dynamic && bodies[i].level == level && bodies[other].level < level)
                {
                    local.supportOf.emplace_back(i, static_cast<std::uint32_t>(n));
                }
            }
            if (bodies[pair.a].level == level && bodies[pair.b].level == level)
            {
                island.twoWayPairs.push_back(k);
            }
        }
        std::sort(local.supportOf.begin(), local.supportOf.end()); // by body, then in pair order
        for (std::size_t n = 0; n < local.supportOf.size(); ++n)
        {
            const std::uint32_t b = local.supportOf[n].first;
            if (n == 0 || b != local.supportOf[n - 1].first)
            {
                island.levelBodies.push_back(b);
                island.supportStart.push_back(static_cast<std::uint32_t>(island.supports.size()));
            }
            const std::uint32_t k = order[local.supportOf[n].second];
            const std::uint32_t other = pairs[k].a == b ? pairs[k].b : pairs[k].a;
            island.supports.push_back({&bodies[other], pairCoefficients[k].friction});
        }
        run.endBody = static_cast<std::uint32_t>(island.levelBodies.size());
        run.endPair = static_cast<std::uint32_t>(island.twoWayPairs.size());
        run.endFrozen = static_cast<std::uint32_t>(island.frozen.size());
        island.levels.push_back(run);
        first = last;
    }
    island.supportStart.push_back(static_cast<std::uint32_t>(island.supports.size()));
    island.quietBodies.assign(island.levelBodies.size(), QuietStamp{});
    island.quietSupports.assign(island.supports.size(), 0);
}

int WorldImpl::sweepLevels(Island& island, ThreadScratch& local, Real eps, bool freezeLowerLevels,
                           const PassSettings& settings)
{
    int applied = 0;
    for (const Island::Level& level : island.levels)
    {
        if (freezeLowerLevels)
        {
            for (std::uint32_t n = level.firstFrozen; n < level.endFrozen; ++n)
            {
                bodies[island.frozen[n]].frozen = true;
            }
        }
        for (std::uint32_t n = level.firstBody; n < level.endBody; ++n)
        {
            RigidBody& body = bodies[island.levelBodies[n]];
            const std::span<const Support> supports = island.supportsOf(n);
            const std::uint32_t first = island.supportStart[n];
            const auto supportsStill = [&]
            {
                for (std::size_t s = 0; s < supports.size(); ++s)
                {
                    if (supports[s].body->motion != island.quietSupports[first + s])
                    {
                        return false;
                    }
                }
                return true;
            };
            if (island.quietBodies[n].holds(pass, body, body) && supportsStill())
            {
                continue;
            }
            const Resolution done = resolveOnSupports(body, supports, eps, settings, local.points);
            applied += done.impulses;
            island.quietBodies[n] = done.quiet ? QuietStamp{pass, body.motion, body.motion} : QuietStamp{};
            for (std::size_t s = 0; done.quiet && s < supports.size(); ++s)
            {
                island.quietSupports[first + s] = supports[s].body->motion;
            }
        }
        for (std::uint32_t n = level.firstPair; n < level.endPair; ++n)
        {
            applied += resolveUnlessQuiet(island.twoWayPairs[n], eps, local, settings);
        }
    }
    return applied;
}

void WorldImpl::updatePositions(const StepOptions& options)
{
    parallelForEach(threads, bodies.size(),
                    [&](std::size_t i)
                    {
                        RigidBody& body = bodies[i];
                        if (!body.dynamic)
                        {
                            return;
                        }
                        const Pose next =
                            advancePose(body.pose(), body.linearVelocity, body.angularVelocity, options.dt);
                        body.position = next.position;
                        body.orientation = next.orientation;
                        body.rotation = next.rotation;
                        updateDerivedQuantities(body);
                    });
}

void WorldImpl::pushOut(const StepOptions& options)
{
    pushOrigins.resize(bodies.size());
    lastPushSweep.assign(bodies.size(), -1); // static bodies never move
    std::vector<int> moves(islands.size(), 0);
    parallelFor(threads, islands.size(),
                [&](std::size_t i, int thread)
                { moves[i] = pushOutIsland(islands[i], scratch[static_cast<std::size_t>(thread)].pushOut, options); });
    for (const int moved : moves)
    {
        stats.pushOutMoves += moved;
    }
}

int WorldImpl::pushOutIsland(const Island& island, PushOutScratch& local, const StepOptions& options)
{
    // how far a body may still go this step: it leaves an overlap at most at pushOutSpeed
    const Real stepReach = options.pushOutSpeed * options.dt;
    for (const std::uint32_t i : island.bodies)
    {
        pushOrigins[i] = bodies[i].pose();
    }
    // how far the body's farthest point has been pushed so far this step, to first order
    const auto pushedSoFar = [&](const RigidBody& body, const Pose& origin)
    {
        return (body.position - origin.position).norm() +
               body.orientation.angularDistance(origin.orientation) * body.boundingRadius;
    };
    const auto reach = [&](std::uint32_t i)
    { return bodies[i].dynamic ? stepReach - pushedSoFar(bodies[i], pushOrigins[i]) : 0.0; };
    const Real allowance = options.pushOutAllowance;
    int moves = 0;
    int sweep = 0;
    // pushes a pair apart; when they move, marks its dynamic bodies as moved in this sweep
    const auto pushPair = [&](const BodyPair& pair)
    {
        if (!pushApart(bodies[pair.a], bodies[pair.b], allowance, reach(pair.a), reach(pair.b), local))
        {
            return false;
        }
        for (const std::uint32_t i : {pair.a, pair.b})
        {
            if (bodies[i].dynamic)
            {
                lastPushSweep[i] = sweep;
            }
        }
        ++moves;
        return true;
    };

    // At the new poses, in the contact pass's order: each body is moved out of what it rests on,
    // which has already been moved (or is static) and stays put, then the pairs within the level
    // share their move. One sweep settles a stack from the ground up; a second catches what the
    // two-way pairs of a level pushed back into their supports.
    bool settled = false;
    for (; sweep < options.pushOutIterations && !settled; ++sweep)
    {
        settled = true;
        for (const Island::Level& level : island.levels)
        {
            for (std::uint32_t n = level.firstBody; n < level.endBody; ++n)
            {
                const std::uint32_t i = island.levelBodies[n];
                if (pushOutOfSupports(bodies[i], island.supportsOf(n), allowance, reach(i), local))
                {
                    lastPushSweep[i] = sweep;
                    settled = false;
                    ++moves;
                }
            }
            for (std::uint32_t n = level.firstPair; n < level.endPair; ++n)
            {
                if (pushPair(pairs[island.twoWayPairs[n]]))
                {
                    settled = false;
                }
            }
        }
    }
    if (settled)
    {
        return moves;
    }

    // The levels order bodies by how they move, not by where they are, so in a dense pile a body
    // may count as a "support" something that presses on it from the side or from above; no move of
    // the upper body alone then clears both. What is left is relaxed two-way, every pair sharing its
    // move by inverse mass, Gauss-Seidel over the pairs of bodies that moved since they were last
    // looked at. Every overlapping pair has such a body: pairs whose bodies never moved were found
    // clear in the first sweep.
    for (int settleSweep = 0; settleSweep < kPushOutSettleSweeps && !settled; ++settleSweep, ++sweep)
    {
        settled = true;
        // the first settle sweep looks at every pair a level sweep moved (at all of them if none ran)
        const int movedSince = settleSweep > 0 ? sweep - 1 : (sweep > 0 ? 0 : -1);
        for (const std::uint32_t k : island.pairs)
        {
            const BodyPair& pair = pairs[k];
            if (std::max(lastPushSweep[pair.a], lastPushSweep[pair.b]) < movedSince)
            {
                continue;
            }
            if (pushPair(pair))
            {
                settled = false;
            }
        }
    }
    return moves;
}

} // namespace impulse
