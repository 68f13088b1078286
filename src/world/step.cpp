// SPDX-License-Identifier: MIT
// The time step of Guendelman, Bridson & Fedkiw 2003, "Nonconvex Rigid Bodies with Stacking".
//
// The step is split so that collision and contact never need a velocity threshold (GBF03 sec. 5):
//
//   S0 = (x, q) of every body, kept untouched until the position update
//   1. candidate pairs       bounds over S0 and the predicted pose; the contact layer follows them
//   2. collision pass        elastic (material eps) on poses predicted with v + dt a, detected
//                            exactly, responding to v: a body at rest is not approaching, so it never
//                            bounces; pairs whose cached points show nothing that can collide are
//                            passed over
//   3. contact graph         probe each body with v + dt a: who rests on whom; levels bottom-up
//   4. velocity update       v += dt a
//   5. contact pass          inelastic, on poses predicted with v: the cached points' rows, loads
//                            warm-started from the last step, projected Gauss-Seidel up the levels
//   6. shock propagation     once more up the levels, every lower level frozen, each level's rows
//                            solved to round-off: stacks stand, and what may tip tips
//   7. position update       x += dt v, q = exp(dt w) q, w = I(q)^-1 L
//   8. push-out              overlaps deeper than an allowance moved apart, positions only,
//                            level by level with lower levels held still (guendelman.md sec. 9)
//
// The traditional order (Scheme::Traditional) reuses the same stages for comparison: update
// velocities and positions first, then resolve collisions and contacts at the new poses.
#include "dynamics/integrate.hpp"
#include "dynamics/rigid_patch.hpp"
#include "support/parallel.hpp"
#include "world/world_impl.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <iterator>
#include <limits>
#include <span>
#include <stdexcept>

namespace impulse
{
namespace
{

// Rounds of push-out's joint push of what the level sweeps leave: in the thousand-body piles a few
// clear it; the cap bounds the cost when a pile is still being compressed
constexpr int kPushOutJointRounds = 16;

// Times the broad phase is run again in a step for bodies the collision pass sped beyond their boxes
// (each time on the grown margins: a chain of hits passes speed on one body per pass)
constexpr int kEscapedBoxPasses = 4;

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
    settings.restingApproach = options.restingApproach * options.dt * gravity.norm();
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

// The largest acceleration of a body this step, applied forces included, and at least gravity's.
Real strongestAcceleration(const std::vector<RigidBody>& bodies, const Vec3& gravity)
{
    Real strongest = gravity.norm();
    for (const RigidBody& body : bodies)
    {
        if (body.dynamic)
        {
            strongest = std::max(strongest, body.acceleration.norm());
        }
    }
    return strongest;
}

// How far a body might travel this step beyond the poses its box covers once impulses have changed
// its velocity: twice its own fastest surface speed (an elastic hit from a heavier body at most
// doubles a speed), with what its acceleration adds, over one step. A body that an impulse speeds
// beyond that is caught after the collision pass (WorldImpl::widenEscapedBoxes).
Real ownMargin(const RigidBody& body, const StepOptions& options)
{
    if (!body.dynamic)
    {
        return 0.0;
    }
    const Real speed = body.linearVelocity.norm() + body.angularVelocity.norm() * body.boundingRadius +
                       options.dt * body.acceleration.norm();
    return 2.0 * options.dt * speed + options.contactThickness;
}

// A speed that sets the scale of an island's round-off: its fastest surface speed plus what gravity
// adds in one step.
Real velocityScale(const Island& island, const std::vector<SolverBody>& solver, const std::vector<RigidBody>& bodies,
                   Real gravityStep)
{
    Real fastest = 0.0;
    for (const std::uint32_t i : island.bodies)
    {
        fastest = std::max(fastest, solver[i].linearVelocity.norm() +
                                        solver[i].angularVelocity.norm() * bodies[i].boundingRadius);
    }
    return fastest + gravityStep;
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

// The bodies of a row that move while its level is solved: the level's own, one side of a support
// and both of a two-way pair.
std::uint8_t levelMovableOf(const RigidBody& a, const RigidBody& b)
{
    const int level = std::max(a.level, b.level);
    const auto moves = [&](const RigidBody& body, RowMovable bit)
    { return body.dynamic && body.level == level ? bit : 0; };
    return static_cast<std::uint8_t>(moves(a, kMovesA) | moves(b, kMovesB));
}

// Sweeps of the contact pass for an island of `rows` rows: at least `sweeps`, and more for a small
// island, up to what an island of kBudgetRows rows is given, at most kMostSweepsFactor times `sweeps`.
// The loads of a tall, narrow stack converge over hundreds of sweeps (its bending and its tipping are
// the slowest modes of Gauss-Seidel), and until they have, shock propagation holds it under loads
// from above that are not yet right: a tower leaning past its edge would stand. Such islands are
// small, so the sweeps cost little; large ones (a pile) get `sweeps`.
constexpr std::size_t kBudgetRows = 1000;
constexpr int kMostSweepsFactor = 20;

int sweepBudget(std::size_t rows, int sweeps)
{
    const std::size_t budget = static_cast<std::size_t>(sweeps) * kBudgetRows / std::max<std::size_t>(rows, 1);
    return static_cast<int>(std::clamp<std::size_t>(budget, static_cast<std::size_t>(sweeps),
                                                    static_cast<std::size_t>(sweeps) * kMostSweepsFactor));
}

bool detectedExactly(const Shape& shape)
{
    return std::holds_alternative<Sphere>(shape) || std::holds_alternative<Capsule>(shape);
}

// Pairs whose points are not all material, so that a point outside the entry at capture can go in
// unseen, deeper than the motion since capture: a mesh with a box or a mesh samples an edge only
// where it passes through the other body, and two boxes are clipped face to face (the clipped
// corners and edge crossings slide along their features, and a face contact appears when a turn
// brings two faces flush). Their entries keep the least reach, which bounds such an overlap by it; a
// wider reach let a cube's edge cut 3 mm into a gear's teeth, and a cube sit 3 mm deep in another
// for thirty steps of the thousand-box pile.
bool pointsNotAllMaterial(const Shape& a, const Shape& b)
{
    const bool meshA = std::holds_alternative<Mesh>(a);
    const bool meshB = std::holds_alternative<Mesh>(b);
    const bool boxA = std::holds_alternative<Box>(a);
    const bool boxB = std::holds_alternative<Box>(b);
    return (meshA && (meshB || boxB)) || (meshB && boxA) || (boxA && boxB);
}

} // namespace

void WorldImpl::step(const StepOptions& options)
{
    stats = {};
    beginLoads();
    threads = resolveThreadCount(options.threads);
    stats.threads = threads;
    scratch.resize(static_cast<std::size_t>(threads));
    contacts.setVerification(options.verifyContacts);
    if (!options.sleep)
    {
        wakeAll();
    }
    if (options.scheme == Scheme::Traditional)
    {
        stepTraditional(options);
    }
    else
    {
        stepGuendelman(options);
    }
    if (options.sleep)
    {
        updateSleep(options);
    }
    clearLoads();
    finishStep(options);
    time += options.dt;
}

void WorldImpl::stepGuendelman(const StepOptions& options)
{
    const PassSettings collision = collisionSettings(options, def.gravity);
    const PassSettings contact = contactSettings(options, def.gravity);
    StageClock clock;
    broadMargins.assign(bodies.size(), 0.0);
    findCandidatePairs(options, collision);
    buildIslands();
    refreshContacts(options, 0.0, false);
    clock.lap(stats.milliseconds.candidatePairs);
    solveCollisions(options, collision, false);
    // a body an impulse sent beyond its box may reach bodies it was not paired with: find its pairs
    // again with room for its new speed, and give the new pairs their collision pass
    for (int again = 0; again < kEscapedBoxPasses && widenEscapedBoxes(options); ++again)
    {
        ++stats.broadPhaseRepeats;
        if (!pairEscapedBodies(options, collision))
        {
            break; // no new pair: nothing new to resolve, and no body sped up further
        }
        solveCollisions(options, collision, true);
    }
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
    storeContactResults();
    clock.lap(stats.milliseconds.shockPropagation);
    updatePositions(options);
    clock.lap(stats.milliseconds.positionUpdate);
    if (options.pushOut)
    {
        pushOut(options);
    }
    clock.lap(stats.milliseconds.pushOut);
}

bool WorldImpl::wakeTouched()
{
    bool woke = false;
    for (const BodyPair& pair : pairs)
    {
        if (bodies[pair.a].asleep != bodies[pair.b].asleep)
        {
            wake(bodies[pair.a].asleep ? pair.a : pair.b);
            woke = true;
        }
    }
    return woke;
}

void WorldImpl::updateSleep(const StepOptions& options)
{
    // a body rests while its fastest point is slower than sleepSpeed; an island sleeps once every
    // body of it has rested sleepTime, a body in no island once it has
    for (RigidBody& body : bodies)
    {
        if (body.dynamic && !body.asleep)
        {
            const Real speed = body.linearVelocity.norm() + body.angularVelocity.norm() * body.boundingRadius;
            body.restingTime = speed < options.sleepSpeed ? body.restingTime + options.dt : 0.0;
        }
    }
    const auto fallAsleep = [&](std::uint32_t i, std::uint32_t group)
    {
        RigidBody& body = bodies[i];
        body.asleep = true;
        body.sleepGroup = group;
        body.linearVelocity.setZero();
        body.angularMomentum.setZero();
        body.angularVelocity.setZero();
    };
    const auto rested = [&](std::uint32_t i) { return bodies[i].restingTime >= options.sleepTime; };
    std::vector<std::uint8_t> inIsland(bodies.size(), 0);
    for (const Island& island : islands)
    {
        for (const std::uint32_t i : island.bodies)
        {
            inIsland[i] = 1;
        }
        if (std::all_of(island.bodies.begin(), island.bodies.end(), rested))
        {
            for (const std::uint32_t i : island.bodies)
            {
                fallAsleep(i, island.bodies.front());
            }
        }
    }
    for (std::uint32_t i = 0; i < bodies.size(); ++i)
    {
        if (bodies[i].dynamic && !bodies[i].asleep && !inIsland[i] && rested(i))
        {
            fallAsleep(i, i);
        }
        stats.sleepingBodies += bodies[i].asleep ? 1 : 0;
    }
}

void WorldImpl::keepQuietStamps(const std::vector<BodyPair>& before)
{
    // both lists sorted by (a, b): each pair still listed keeps its stamp, a new one has none and is
    // marked fresh
    const auto key = [](const BodyPair& pair) { return (std::uint64_t{pair.a} << 32) | pair.b; };
    std::vector<QuietStamp> kept(pairs.size());
    freshPairs.assign(pairs.size(), 1);
    std::size_t old = 0;
    for (std::size_t k = 0; k < pairs.size(); ++k)
    {
        while (old < before.size() && key(before[old]) < key(pairs[k]))
        {
            ++old;
        }
        if (old < before.size() && key(before[old]) == key(pairs[k]) && old < quietPairs.size())
        {
            kept[k] = quietPairs[old];
            freshPairs[k] = 0;
        }
    }
    quietPairs.swap(kept);
}

bool WorldImpl::widenEscapedBoxes(const StepOptions& options)
{
    // where a body's poses and its own margin at its new velocity no longer fit in its box
    escapedBodies.clear();
    for (std::size_t i = 0; i < bodies.size(); ++i)
    {
        const RigidBody& body = bodies[i];
        if (!body.dynamic || body.removed || std::holds_alternative<Plane>(body.shape))
        {
            continue;
        }
        const Real margin = ownMargin(body, options);
        const Aabb now = shapeBounds(body.shape, body.shapePose(body.pose()));
        const Aabb next = shapeBounds(body.shape, body.shapePose(body.predicted));
        const Aabb& box = broadPhase.bounds(i);
        const bool fits = ((now.lower.cwiseMin(next.lower).array() - margin) >= box.lower.array()).all() &&
                          ((now.upper.cwiseMax(next.upper).array() + margin) <= box.upper.array()).all();
        if (!fits)
        {
            broadMargins[i] = std::max(broadMargins[i], margin);
            escapedBodies.push_back(static_cast<std::uint32_t>(i));
        }
    }
    return !escapedBodies.empty();
}

bool WorldImpl::pairEscapedBodies(const StepOptions& options, const PassSettings& settings)
{
    // Only an escaped body can have a new pair: every other body's motion still lies in its box. So
    // the escaped bodies' boxes are made anew, at their predicted poses with their grown margins, and
    // only their neighbourhoods are searched.
    for (const std::uint32_t i : escapedBodies)
    {
        broadBodies[i].next = bodies[i].shapePose(bodies[i].predicted);
        broadBodies[i].margin = broadMargins[i];
    }
    broadPhase.findPairsOf(broadBodies, escapedBodies, escapedPairs);
    // the new ones (both lists are sorted), of bodies that may collide
    std::vector<BodyPair> added;
    std::set_difference(escapedPairs.begin(), escapedPairs.end(), pairs.begin(), pairs.end(),
                        std::back_inserter(added));
    if (filtering)
    {
        std::erase_if(added, [&](const BodyPair& pair) { return !collides(pair.a, pair.b); });
    }
    if (added.empty())
    {
        return false;
    }
    const std::vector<BodyPair> before = pairs;
    const bool wakes =
        std::any_of(added.begin(), added.end(),
                    [&](const BodyPair& pair) { return bodies[pair.a].asleep || bodies[pair.b].asleep; });
    if (wakes)
    {
        findCandidatePairs(options, settings); // a sleeping island woken: its pairs are found with it awake
    }
    else
    {
        pairs.clear();
        std::merge(before.begin(), before.end(), added.begin(), added.end(), std::back_inserter(pairs));
        followPairs();
    }
    keepQuietStamps(before);
    buildIslands();
    refreshContacts(options, 0.0, false);
    return true;
}

void WorldImpl::stepTraditional(const StepOptions& options)
{
    broadMargins.assign(bodies.size(), 0.0);
    updateVelocities(options);
    updatePositions(options);
    findCandidatePairs(options, atCurrentPoseSettings(options, def.gravity, 0.0));
    buildIslands();
    refreshContacts(options, 0.0, true);
    assignSingleLevel();
    solveCollisions(options, atCurrentPoseSettings(options, def.gravity, 0.0), false);
    solveContacts(options, atCurrentPoseSettings(options, def.gravity, options.contactThickness));
    storeContactResults();
}

void WorldImpl::finishStep(const StepOptions& options)
{
    const ContactCache::Counters counters = contacts.takeCounters();
    stats.narrowPhaseCalls = counters.narrowPhaseCalls;
    stats.contactCaptures = counters.captures;
    if (options.verifyContacts)
    {
        std::string first;
        if (const int violations = contacts.takeViolations(first); violations > 0)
        {
            throw std::logic_error(std::to_string(violations) + " contact cache discrepancies in the step at t = " +
                                   std::to_string(time) + "; the first: " + first);
        }
    }
}

void WorldImpl::predictAll(const PassSettings& settings)
{
    parallelForEach(threads, bodies.size(), [&](std::size_t i) { predictBody(bodies[i], settings); });
}

PlacedShape WorldImpl::placed(std::uint32_t body, const Pose& pose) const
{
    const RigidBody& placedBody = bodies[body];
    return {&placedBody.shape, placedBody.shapePose(pose), placedBody.boundingRadius};
}

Real WorldImpl::pairReach(std::uint32_t k, const StepOptions& options) const
{
    // twice what the pair's points can move relative to each other in a step at today's velocities,
    // at least a tenth of a millimetre (a twentieth of the smaller body), at most a quarter of it
    const RigidBody& a = bodies[pairs[k].a];
    const RigidBody& b = bodies[pairs[k].b];
    const auto spin = [](const RigidBody& body)
    { return body.dynamic ? body.angularVelocity.norm() * body.boundingRadius : 0.0; };
    const Real speed =
        (a.linearVelocity - b.linearVelocity).norm() + spin(a) + spin(b) + options.dt * def.gravity.norm();
    const Real smaller = std::min(a.boundingRadius, b.boundingRadius);
    const Real least = std::min(1e-4, 0.05 * smaller);
    if (pointsNotAllMaterial(a.shape, b.shape))
    {
        return least;
    }
    return std::clamp(least + 2.0 * options.dt * speed, least, std::max(least, 0.25 * smaller));
}

void WorldImpl::findCandidatePairs(const StepOptions& options, const PassSettings& settings)
{
    broadBodies.resize(bodies.size());
    broadMargins.resize(bodies.size());
    // a sleeping body is paired like a static one, so two sleeping bodies make no pair, and a pair
    // with an awake body wakes it (and the pairs are found again with it awake)
    do
    {
        predictAll(settings);
        parallelForEach(threads, bodies.size(),
                        [&](std::size_t i)
                        {
                            const RigidBody& body = bodies[i];
                            broadMargins[i] = std::max(broadMargins[i], ownMargin(body, options));
                            broadBodies[i] = {&body.shape,
                                              body.shapePose(body.pose()),
                                              body.shapePose(body.predicted),
                                              body.boundingRadius,
                                              broadMargins[i],
                                              body.dynamic && !body.asleep,
                                              !body.removed};
                        });
        broadPhase.findPairs(broadBodies, threads, pairs);
        dropFilteredPairs();
    } while (wakeTouched());
    followPairs();
}

void WorldImpl::followPairs()
{
    pairCoefficients.clear();
    for (const BodyPair& pair : pairs)
    {
        pairCoefficients.push_back(coefficients(bodies[pair.a].material, bodies[pair.b].material));
    }
    // a sleeping island's entries are parked, so that it wakes with the loads it slept with
    const auto resting = [&](std::uint32_t i)
    { return bodies[i].asleep || (!bodies[i].dynamic && !bodies[i].removed); };
    contacts.follow(
        pairs,
        [&](std::uint32_t a, std::uint32_t b)
        { return detectedExactly(bodies[a].shape) || detectedExactly(bodies[b].shape); },
        [&](std::uint32_t a, std::uint32_t b)
        { return (bodies[a].asleep || bodies[b].asleep) && resting(a) && resting(b); });
    stats.candidatePairs = static_cast<int>(pairs.size());
}

void WorldImpl::refreshContacts(const StepOptions& options, Real extra, bool withExact)
{
    // every entry made usable at the predicted poses: kept where the pair has moved within its
    // reach since capture, captured anew elsewhere
    parallelFor(threads, pairs.size(),
                [&](std::size_t k, int thread)
                {
                    if (!withExact && contacts.entry(k).exact)
                    {
                        return;
                    }
                    const BodyPair& pair = pairs[k];
                    contacts.refresh(k, placed(pair.a, bodies[pair.a].predicted),
                                     placed(pair.b, bodies[pair.b].predicted), options.contactThickness,
                                     pairReach(static_cast<std::uint32_t>(k), options), extra,
                                     scratch[static_cast<std::size_t>(thread)].contact);
                });
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

void WorldImpl::solveCollisions(const StepOptions& options, const PassSettings& settings, bool onlyNew)
{
    predictAll(settings);
    // stamps of earlier passes (and of pairs that had other indices in earlier steps) never hold; a
    // run again after widening goes on with the stamps of the run before (keepQuietStamps)
    if (!onlyNew)
    {
        ++pass;
    }
    quietPairs.resize(pairs.size());
    std::vector<int> applied(islands.size(), 0);
    std::vector<int> sweeps(islands.size(), 0);
    parallelFor(threads, islands.size(),
                [&](std::size_t i, int thread)
                {
                    // each island sweeps until a sweep applies nothing to it, or the cap
                    for (int sweep = 0; sweep < options.collisionIterations; ++sweep)
                    {
                        const int impulses = sweepPairs(islands[i], scratch[static_cast<std::size_t>(thread)], options,
                                                        settings, onlyNew);
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

int WorldImpl::sweepPairs(const Island& island, ThreadScratch& local, const StepOptions& options,
                          const PassSettings& settings, bool onlyNew)
{
    // Run again after boxes were widened, the pass visits only the pairs that are new: the rest of the
    // island had its sweeps.
    int applied = 0;
    for (const std::uint32_t k : island.pairs)
    {
        if (!onlyNew || freshPairs[k] != 0)
        {
            applied += resolveUnlessQuiet(k, local, options, settings);
        }
    }
    return applied;
}

int WorldImpl::resolveUnlessQuiet(std::uint32_t k, ThreadScratch& local, const StepOptions& options,
                                  const PassSettings& settings)
{
    RigidBody& a = bodies[pairs[k].a];
    RigidBody& b = bodies[pairs[k].b];
    if (quietPairs[k].holds(pass, a, b))
    {
        return 0;
    }
    const QuietStamp quiet{pass, a.motion, b.motion};
    // Bodies that move too slowly for any point to approach past the resting approach need no look at
    // their geometry (most of a settled pile's pairs).
    if (slowerThanRestingApproach(a, b, settings))
    {
        quietPairs[k] = quiet;
        return 0;
    }
    // The cached points screen the pair: where none lies within what the motion since capture could
    // hide (a separation may be off by twice that) and approaches, no exact point collides either. An
    // entry the bodies have moved too far from to screen (a mesh pair keeps the least reach, and a
    // settled pile's jitter takes it past that) is captured anew at the predicted poses first: at the
    // pose of capture the screen is exact, the capture costs about what the exact detection below
    // would, and the later stages then find the entry fresh instead of capturing it themselves.
    ContactEntry& entry = contacts.entry(k);
    if (!entry.exact)
    {
        const PlacedShape pa = placed(pairs[k].a, a.predicted);
        const PlacedShape pb = placed(pairs[k].b, b.predicted);
        const Real reach = pairReach(k, options);
        Real motion = contacts.motionSinceCapture(entry, pa, pb);
        if (!(3.0 * motion <= entry.reach + options.contactThickness))
        {
            contacts.recapture(k, pa, pb, options.contactThickness, reach, local.contact);
            motion = 0.0;
        }
        local.points.clear();
        contacts.pointsAt(k, pa, pb, 2.0 * motion + 1e-12, options.contactThickness, reach, local.points,
                          local.contact);
        const bool approaching =
            std::any_of(local.points.begin(), local.points.end(),
                        [&](const ContactPoint& point)
                        { return approachSpeed(a, a.predicted, b, b.predicted, point, settings) < 0.0; });
        if (!approaching)
        {
            quietPairs[k] = quiet;
            return 0;
        }
    }
    const Resolution done = resolveCollision(a, b, pairCoefficients[k].restitution, pairCoefficients[k].friction,
                                             settings, local.contact, local.solver);
    quietPairs[k] = done.quiet ? QuietStamp{pass, a.motion, b.motion} : QuietStamp{};
    return done.impulses;
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

Real leastPhi(const std::vector<ContactPoint>& points)
{
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
void sortByLevel(std::vector<std::uint32_t>& pairs, const std::vector<int>& pairLevels, int highest,
                 ThreadScratch& local)
{
    std::vector<std::size_t>& start = local.levelStart;
    std::vector<std::uint32_t>& sorted = local.sorted;
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
    oldPoses.resize(bodies.size());
    parallelForEach(threads, bodies.size(),
                    [&](std::size_t i) { oldPoses[i] = predictedPose(bodies[i], oldVelocity); });
    // the new poses are those the contact pass starts from: the contact layer is made usable there,
    // with what the old poses differ by to spare
    predictAll(newVelocity);
    // a probe moves one body of a pair by dt^2 a from where the other is: at most 2 dt^2 |a| apart
    refreshContacts(options, 2.0 * options.dt * options.dt * strongestAcceleration(bodies, def.gravity), true);

    // How far a probe moves each body's points: from its old-velocity pose to its new one. A rotation
    // by theta between unit quaternions q and p (q.p >= 0) moves a point at r by 2 r sin(theta / 2),
    // at most 2 r |q - p|.
    probeMoves.resize(bodies.size());
    parallelForEach(threads, bodies.size(),
                    [&](std::size_t i)
                    {
                        const Pose& from = oldPoses[i];
                        const Pose& to = bodies[i].predicted;
                        const Real sign = from.orientation.dot(to.orientation) < 0.0 ? -1.0 : 1.0;
                        const Real turn = (from.orientation.coeffs() - sign * to.orientation.coeffs()).norm();
                        probeMoves[i] = bodies[i].dynamic ? (to.position - from.position).norm() +
                                                                2.0 * bodies[i].boundingRadius * turn
                                                          : 0.0;
                    });

    // every probe of every pair at once, from the contact layer: each writes its own slot
    pairProbes.assign(pairs.size(), 0);
    parallelFor(threads, pairs.size(),
                [&](std::size_t k, int thread)
                {
                    std::vector<ContactPoint>& points = scratch[static_cast<std::size_t>(thread)].points;
                    ContactScratch& contactScratch = scratch[static_cast<std::size_t>(thread)].contact;
                    const BodyPair& pair = pairs[k];
                    // an exact pair is detected at every look and needs no reach
                    const Real reach =
                        contacts.entry(k).exact ? 0.0 : pairReach(static_cast<std::uint32_t>(k), options);
                    const auto least = [&](const Pose& poseA, const Pose& poseB, Real threshold)
                    {
                        points.clear();
                        contacts.pointsAt(k, placed(pair.a, poseA), placed(pair.b, poseB), threshold,
                                          options.contactThickness, reach, points, contactScratch);
                        return leastPhi(points);
                    };
                    // A separation changes by at most what a probe moves the points, a cached one by
                    // twice that: a pair farther apart than twice that again, for both probes, cannot be
                    // pushed into contact by either, and its first look is all it needs.
                    const Real apart = options.contactThickness + 4.0 * (probeMoves[pair.a] + probeMoves[pair.b]);
                    const Real before = least(oldPoses[pair.a], oldPoses[pair.b], apart);
                    std::uint8_t found = before < options.contactThickness ? kTouching : 0;
                    if (!(before < apart))
                    {
                        pairProbes[k] = found;
                        return;
                    }
                    // advance one alone with its new velocity: deeper into the other means it rests on it
                    if (bodies[pair.a].dynamic &&
                        std::min(least(bodies[pair.a].predicted, oldPoses[pair.b], 0.0), 0.0) < std::min(before, 0.0))
                    {
                        found |= kRestsOnB;
                    }
                    if (bodies[pair.b].dynamic &&
                        std::min(least(oldPoses[pair.a], bodies[pair.b].predicted, 0.0), 0.0) < std::min(before, 0.0))
                    {
                        found |= kRestsOnA;
                    }
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
                    ThreadScratch& local = scratch[static_cast<std::size_t>(thread)];
                    sortByLevel(islands[i].pairs, pairLevels, highest, local);
                    planLevels(islands[i], local);
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
        if (body.dynamic && !body.asleep)
        {
            body.linearVelocity += options.dt * body.acceleration; // gravity and the applied force
            if (!body.torque.isZero(0.0))
            {
                body.angularMomentum += options.dt * body.torque;
                body.angularVelocity = body.invInertiaWorld * body.angularMomentum;
            }
        }
    }
}

void WorldImpl::planLevels(Island& island, ThreadScratch& local)
{
    // The island's pairs are sorted by level, a pair belonging to the higher level of its two
    // bodies. Within a level each body's supports come first (the pairs with a lower-level or static
    // partner), then the pairs between two bodies of the level. Levels do not change during the
    // step, so this order is worked out once.
    island.levels.clear();
    island.levelBodies.clear();
    island.supportStart.clear();
    island.supportPairs.clear();
    island.twoWayPairs.clear();
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
        local.supportOf.clear();
        for (std::size_t n = first; n < last; ++n)
        {
            const std::uint32_t k = order[n];
            const BodyPair& pair = pairs[k];
            for (const std::uint32_t i : {pair.a, pair.b})
            {
                const std::uint32_t other = i == pair.a ? pair.b : pair.a;
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
                island.supportStart.push_back(static_cast<std::uint32_t>(island.supportPairs.size()));
            }
            island.supportPairs.push_back(order[local.supportOf[n].second]);
        }
        run.endBody = static_cast<std::uint32_t>(island.levelBodies.size());
        run.endPair = static_cast<std::uint32_t>(island.twoWayPairs.size());
        island.levels.push_back(run);
        first = last;
    }
    island.supportStart.push_back(static_cast<std::uint32_t>(island.supportPairs.size()));
}

void WorldImpl::buildRows(Island& island, ThreadScratch& local, const StepOptions& options,
                          const PassSettings& settings)
{
    // One row per cached point of every pair, at the poses predicted with the updated velocity, in
    // the order of the levels: each level's supports, then its two-way pairs.
    island.rows.clear();
    island.bodyRows.clear();
    const auto addRows = [&](std::uint32_t k)
    {
        const BodyPair& pair = pairs[k];
        const RigidBody& a = bodies[pair.a];
        const RigidBody& b = bodies[pair.b];
        ContactEntry& entry = contacts.entry(k);
        local.points.clear();
        contacts.entryPoints(k, placed(pair.a, a.predicted), placed(pair.b, b.predicted), local.points);
        const LeverCentres centres = leverCentres(a, a.predicted, b, b.predicted);
        for (std::size_t i = 0; i < entry.points.size(); ++i)
        {
            CachedPoint& cached = entry.points[i];
            const ContactPoint& point = local.points[i];
            Vec3 t1;
            Vec3 t2;
            tangentBasis(cached.normal, t1, t2);
            const Mat3& owner = cached.normalOnA ? a.predicted.rotation : b.predicted.rotation;
            ContactRow row = makeContactRow(RowSide::of(a, pair.a, centres.a), RowSide::of(b, pair.b, centres.b), point,
                                            owner * t1, owner * t2, pairCoefficients[k].friction);
            // the separation at time n, to first order: the gap the predicted motion closes
            const Real un = row.relativeVelocity(0, solverBodies[pair.a], solverBodies[pair.b]);
            row.gap = point.phi - settings.lookahead * un;
            row.load = &cached.load;
            // the loads of the last step are where the solve starts, for the points in play
            if (point.phi < options.contactThickness)
            {
                row.lambda = {cached.load.normal, cached.load.tangent1, cached.load.tangent2};
            }
            island.rows.push_back(row);
        }
    };
    for (Island::Level& level : island.levels)
    {
        level.firstRow = static_cast<std::uint32_t>(island.rows.size());
        for (std::uint32_t n = level.firstBody; n < level.endBody; ++n)
        {
            island.bodyRows.push_back(static_cast<std::uint32_t>(island.rows.size()));
            for (const std::uint32_t k : island.supportsOf(n))
            {
                addRows(k);
            }
        }
        level.twoWayRow = static_cast<std::uint32_t>(island.rows.size());
        for (std::uint32_t n = level.firstPair; n < level.endPair; ++n)
        {
            addRows(island.twoWayPairs[n]);
        }
        level.endRow = static_cast<std::uint32_t>(island.rows.size());
    }
    island.bodyRows.push_back(static_cast<std::uint32_t>(island.rows.size()));
}

void WorldImpl::solveContacts(const StepOptions& options, const PassSettings& settings)
{
    predictAll(settings);
    solverBodies.resize(bodies.size());
    parallelForEach(threads, bodies.size(), [&](std::size_t i) { solverBodies[i] = SolverBody::of(bodies[i]); });
    const RowSettings rowSettings{settings.lookahead, options.contactThickness};
    std::vector<int> sweeps(islands.size(), 0);
    std::vector<int> redone(islands.size(), 0);
    parallelFor(threads, islands.size(),
                [&](std::size_t i, int thread)
                {
                    Island& island = islands[i];
                    ThreadScratch& local = scratch[static_cast<std::size_t>(thread)];
                    buildRows(island, local, options, settings);
                    const Real scale = velocityScale(island, solverBodies, bodies, options.dt * def.gravity.norm());
                    Real before = 0.0;
                    local.coldStart.clear();
                    for (const std::uint32_t b : island.bodies)
                    {
                        before += solverBodies[b].kineticEnergy();
                        local.coldStart.push_back(solverBodies[b]);
                    }
                    for (const ContactRow& row : island.rows)
                    {
                        applyRowImpulses(row, solverBodies);
                    }
                    const int budget = sweepBudget(island.rows.size(), options.contactIterations);
                    sweeps[i] = solveRows(island.rows, solverBodies, rowSettings, budget, kSolverResolution * scale,
                                          Sweeps::Continued, local.solver);
                    Real after = 0.0;
                    for (const std::uint32_t b : island.bodies)
                    {
                        after += solverBodies[b].kineticEnergy();
                    }
                    // The inelastic problem removes kinetic energy, and so does each row's visit from
                    // rest. A warm start from loads that no longer fit can leave the island with more
                    // than it had after gravity; it is then solved again from no load.
                    if (after > before * (1.0 + 1e-12))
                    {
                        redone[i] = 1;
                        for (std::size_t n = 0; n < island.bodies.size(); ++n)
                        {
                            solverBodies[island.bodies[n]] = local.coldStart[n];
                        }
                        for (ContactRow& row : island.rows)
                        {
                            row.lambda = {0.0, 0.0, 0.0};
                            row.load->direction = {};
                            row.load->change = {};
                        }
                        sweeps[i] += solveRows(island.rows, solverBodies, rowSettings, budget,
                                               kSolverResolution * scale, Sweeps::Accelerated, local.solver);
                    }
                    // The next step starts from the two-way solve's loads. Shock propagation's are not
                    // kept: each level is held against its frozen supports under the loads from above
                    // as this pass left them, so they need not fit together, and starting from them
                    // would hold a stack that the two-way problem lets tip.
                    for (const ContactRow& row : island.rows)
                    {
                        row.load->normal = row.lambda[0];
                        row.load->tangent1 = row.lambda[1];
                        row.load->tangent2 = row.lambda[2];
                    }
                });
    for (std::size_t i = 0; i < islands.size(); ++i)
    {
        stats.contactSweeps = std::max(stats.contactSweeps, sweeps[i]);
        stats.coldRestarts += redone[i];
        stats.contactRows += static_cast<int>(islands[i].rows.size());
    }
}

void WorldImpl::propagateShock(const StepOptions& options, const PassSettings& settings)
{
    // GBF03 sec. 8: once more up the levels, every body of a lower level frozen (infinite mass) while
    // a level is solved: corrections only travel upward, and a box can no longer push its supports
    // into the ground. Each level is solved to the solver's resolution under the loads from above as
    // the contact pass left them: a body whose load from above tips it past its support's edge is let
    // tip, one that can stand is held. (So the contact pass must have those loads right: a body held
    // under loads from above that have not converged is held where physics tips it.)
    const RowSettings rowSettings{settings.lookahead, options.contactThickness};
    std::vector<int> iterations(islands.size(), 0);
    parallelFor(threads, islands.size(),
                [&](std::size_t i, int thread)
                {
                    Island& island = islands[i];
                    ThreadScratch& local = scratch[static_cast<std::size_t>(thread)];
                    const Real tolerance = kSolverResolution *
                                           velocityScale(island, solverBodies, bodies, options.dt * def.gravity.norm());
                    const auto solveLevel = [&](const Island::Level& level)
                    {
                        std::span<ContactRow> rows(island.rows.data() + level.firstRow, level.endRow - level.firstRow);
                        for (ContactRow& row : rows)
                        {
                            // only the level's own bodies move: one side of a support, both of a two-way pair
                            setMovable(row, levelMovableOf(bodies[row.a], bodies[row.b]));
                        }
                        // each body on its supports in one step where one rigid motion stops it there (a
                        // body at rest, one sliding as a whole), then Gauss-Seidel for the rest
                        for (std::uint32_t n = level.firstBody; n < level.endBody; ++n)
                        {
                            const std::uint32_t index = island.levelBodies[n];
                            local.inPlay.clear();
                            for (std::uint32_t r = island.bodyRows[n]; r < island.bodyRows[n + 1]; ++r)
                            {
                                ContactRow& row = island.rows[r];
                                const Real un = row.relativeVelocity(0, solverBodies[row.a], solverBodies[row.b]);
                                if (row.lambda[0] > 0.0 || row.gap + rowSettings.lookahead * un < rowSettings.thickness)
                                {
                                    local.inPlay.push_back(&row);
                                }
                            }
                            const RigidBody& body = bodies[index];
                            solveRigidPatch(local.inPlay, solverBodies,
                                            {index, body.predicted.position, body.invMass, body.invInertiaWorld},
                                            nullptr, tolerance, local.solver);
                        }
                        iterations[i] += solveRows(rows, solverBodies, rowSettings, options.shockIterations, tolerance,
                                                   Sweeps::Accelerated, local.solver);
                    };
                    // up: every lower level frozen
                    for (const Island::Level& level : island.levels)
                    {
                        solveLevel(level);
                    }
                });
    for (const int n : iterations)
    {
        stats.shockIterations += n;
    }
}

void WorldImpl::storeContactResults()
{
    // what each point carried, for World::contacts(), in pair order: the islands hold their rows by
    // level, so the rows carrying load are listed by (pair, order met) and then gathered in that order
    contactOrder.clear();
    for (std::uint32_t i = 0; i < islands.size(); ++i)
    {
        const std::vector<ContactRow>& rows = islands[i].rows;
        for (std::uint32_t r = 0; r < rows.size(); ++r)
        {
            if (rows[r].lambda[0] > 0.0)
            {
                const std::uint64_t pair = std::uint64_t{rows[r].a} << 32 | rows[r].b;
                contactOrder.push_back({pair, std::uint64_t{i} << 32 | r});
            }
        }
    }
    std::sort(contactOrder.begin(), contactOrder.end());
    lastContacts.clear();
    for (const auto& [pair, where] : contactOrder)
    {
        const ContactRow& row = islands[where >> 32].rows[where & 0xffffffffU];
        lastContacts.push_back({BodyId{row.a}, BodyId{row.b}, row.point, row.direction[0], row.gap, row.lambda[0],
                                row.lambda[1] * row.direction[1] + row.lambda[2] * row.direction[2]});
    }
    // the bodies take the solved velocities
    parallelFor(threads, islands.size(),
                [&](std::size_t i, int)
                {
                    for (const std::uint32_t b : islands[i].bodies)
                    {
                        solverBodies[b].storeInto(bodies[b]);
                    }
                });
}

void WorldImpl::updatePositions(const StepOptions& options)
{
    parallelForEach(threads, bodies.size(),
                    [&](std::size_t i)
                    {
                        RigidBody& body = bodies[i];
                        if (!body.dynamic || body.asleep)
                        {
                            return;
                        }
                        const Pose next = advanceBody(body, body.linearVelocity, options.dt);
                        body.position = next.position;
                        body.orientation = next.orientation;
                        body.rotation = next.rotation;
                        updateDerivedQuantities(body);
                    });
}

void WorldImpl::pointsToward(std::uint32_t k, std::uint32_t body, Real threshold, const StepOptions& options,
                             std::vector<ContactPoint>& out, ContactScratch& contactScratch)
{
    const BodyPair& pair = pairs[k];
    const std::size_t first = out.size();
    const Real reach = contacts.entry(k).exact ? 0.0 : pairReach(k, options); // an exact pair needs none
    contacts.overlapsAt(k, placed(pair.a, bodies[pair.a].pose()), placed(pair.b, bodies[pair.b].pose()), threshold,
                        options.pushOutAllowance, options.contactThickness, reach, out, contactScratch);
    if (body == pair.b)
    {
        for (std::size_t i = first; i < out.size(); ++i)
        {
            out[i].normal = -out[i].normal;
        }
    }
}

void WorldImpl::pushOut(const StepOptions& options)
{
    pushOrigins.resize(bodies.size());
    lastPushSweep.assign(bodies.size(), -1);  // static bodies never move
    jointPushSweep.assign(bodies.size(), -1); // sweeps count from 0 again every step
    pushSlot.resize(bodies.size(), -1);       // a joint push leaves every slot -1 again
    std::vector<int> moves(islands.size(), 0);
    parallelFor(threads, islands.size(),
                [&](std::size_t i, int thread)
                { moves[i] = pushOutIsland(islands[i], scratch[static_cast<std::size_t>(thread)], options); });
    for (const int moved : moves)
    {
        stats.pushOutMoves += moved;
    }
}

int WorldImpl::pushOutIsland(const Island& island, ThreadScratch& local, const StepOptions& options)
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
    std::vector<ContactPoint>& points = local.pushOut.points;
    int moves = 0;
    int sweep = 0;
    // pushes a pair apart; when they move, marks its dynamic bodies as moved in this sweep
    const auto pushPair = [&](std::uint32_t k)
    {
        const BodyPair& pair = pairs[k];
        points.clear();
        pointsToward(k, pair.a, 0.0, options, points, local.contact);
        if (!pushApart(bodies[pair.a], bodies[pair.b], points, allowance, reach(pair.a), reach(pair.b), local.pushOut))
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
    //
    // After the first sweep a body is looked at again only where something has moved since its last
    // look, which found it clear: itself (by a two-way pair, after its look), or what it rests on
    // (lower levels come first, so in this sweep). The same poses give the same points, so the look
    // it is spared would have found it clear again. Likewise a two-way pair neither of whose bodies
    // has moved since the last sweep's look at it.
    const auto hasMovedSince = [&](std::uint32_t i, int since) { return lastPushSweep[i] >= since; };
    bool settled = false;
    for (; sweep < options.pushOutIterations && !settled; ++sweep)
    {
        settled = true;
        for (const Island::Level& level : island.levels)
        {
            for (std::uint32_t n = level.firstBody; n < level.endBody; ++n)
            {
                const std::uint32_t i = island.levelBodies[n];
                const std::span<const std::uint32_t> supports = island.supportsOf(n);
                if (sweep > 0 && !hasMovedSince(i, sweep - 1) &&
                    std::none_of(supports.begin(), supports.end(),
                                 [&](std::uint32_t k)
                                 { return hasMovedSince(pairs[k].a == i ? pairs[k].b : pairs[k].a, sweep); }))
                {
                    continue;
                }
                points.clear();
                for (const std::uint32_t k : supports)
                {
                    pointsToward(k, i, 0.0, options, points, local.contact);
                }
                if (pushOutOfSupports(bodies[i], points, allowance, reach(i), local.pushOut))
                {
                    lastPushSweep[i] = sweep;
                    settled = false;
                    ++moves;
                }
            }
            for (std::uint32_t n = level.firstPair; n < level.endPair; ++n)
            {
                const BodyPair& pair = pairs[island.twoWayPairs[n]];
                if (sweep > 0 && !hasMovedSince(pair.a, sweep - 1) && !hasMovedSince(pair.b, sweep - 1))
                {
                    continue;
                }
                if (pushPair(island.twoWayPairs[n]))
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
    // the upper body alone then clears both. What is left is pushed jointly: the bodies of every pair
    // still overlapping beyond the allowance and their neighbours move at once, held by everything
    // they touch. Every overlapping pair has a body moved since
    // it was last looked at: pairs whose bodies never moved were found clear in the first sweep.
    std::vector<JointPoint>& joint = local.pushOut.jointPoints;
    for (int round = 0; round < kPushOutJointRounds && !settled; ++round, ++sweep)
    {
        // the first round looks at the pairs of every body a level sweep moved (all if none ran)
        const int movedSince = round > 0 ? sweep - 1 : (sweep > 0 ? 0 : -1);
        bool overlapping = false;
        for (const std::uint32_t k : island.pairs)
        {
            const BodyPair& pair = pairs[k];
            if (!hasMovedSince(pair.a, movedSince) && !hasMovedSince(pair.b, movedSince))
            {
                continue;
            }
            points.clear();
            pointsToward(k, pair.a, 0.0, options, points, local.contact);
            if (std::none_of(points.begin(), points.end(), [&](const ContactPoint& p) { return -p.phi > allowance; }))
            {
                continue;
            }
            overlapping = true;
            for (const std::uint32_t i : {pair.a, pair.b})
            {
                if (bodies[i].dynamic)
                {
                    jointPushSweep[i] = sweep;
                }
            }
        }
        if (!overlapping)
        {
            break;
        }
        // and their neighbours, so that a neighbour pushed is held by what it rests on
        std::vector<std::uint32_t>& around = local.pushOut.around;
        around.clear();
        for (const std::uint32_t k : island.pairs)
        {
            const BodyPair& pair = pairs[k];
            if (jointPushSweep[pair.a] == sweep && bodies[pair.b].dynamic)
            {
                around.push_back(pair.b);
            }
            if (jointPushSweep[pair.b] == sweep && bodies[pair.a].dynamic)
            {
                around.push_back(pair.a);
            }
        }
        for (const std::uint32_t i : around)
        {
            jointPushSweep[i] = sweep;
        }
        // every point within the allowance of the pairs of all those bodies, touching ones too: a
        // body pushed up against another is then held by it, not driven into it
        joint.clear();
        for (const std::uint32_t k : island.pairs)
        {
            const BodyPair& pair = pairs[k];
            if (std::max(jointPushSweep[pair.a], jointPushSweep[pair.b]) < sweep)
            {
                continue;
            }
            points.clear();
            pointsToward(k, pair.a, allowance, options, points, local.contact);
            for (const ContactPoint& point : points)
            {
                joint.push_back({pair.a, pair.b, point});
            }
        }
        pushApartTogether(bodies, joint, allowance, reach, pushSlot, local.pushOut);
        for (const std::uint32_t i : local.pushOut.moved)
        {
            lastPushSweep[i] = sweep;
        }
        moves += static_cast<int>(local.pushOut.moved.size());
        settled = local.pushOut.moved.empty();
    }
    return moves;
}

} // namespace impulse
