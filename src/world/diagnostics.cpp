// SPDX-License-Identifier: MIT
// Warnings for legal input that gives a poor simulation, and the refusal of bodies smaller than the
// length tolerances serve (docs/warnings.md). Everything here reads the world as it stands before a
// step; nothing changes it, so no trajectory depends on this file.
#include "world/world_impl.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>
#include <string>
#include <vector>

namespace impulse
{
namespace
{

constexpr Real kEpsilon = std::numeric_limits<Real>::epsilon();
/// A length tolerance serves a body up to a tenth of its size; past a hundredth it earns a warning.
constexpr Real kServedFraction = 0.1;
constexpr Real kWarnedFraction = 0.01;
/// m: push-out stops once a sweep moves no gap by more (push_out.cpp); the time of impact (1e-13 m)
/// and the contact layer's slack (1e-12 m) are finer, so this is the finest length the step resolves
/// whatever its options.
constexpr Real kFixedTolerance = 1e-9;
/// Gravity may move a body from rest by at most this much of the smallest size in one step: a body
/// that falls through that size then arrives moving at most half of it per step, sqrt(2 g s) dt <= s/2.
constexpr Real kGravityStepFraction = 1.0 / 8.0;
/// A body's initial speed may move it by at most this much of the smallest size in one step.
constexpr Real kSpeedStepFraction = 0.5;
/// The contact pass stops once a sweep changes velocities by less than 1e-6 of the island's speeds;
/// through a pair of mass ratio R its sweeps contract by about 1 - 1/R, which leaves errors of about
/// R * 1e-6 of the speeds: 1 % at this ratio (without shock propagation a stack collapses at 1e5).
constexpr Real kLargestMassRatio = 1e4;
/// Round-off of a coordinate, epsilon |x|, may be at most this much of the contact thickness.
constexpr Real kRoundOffFraction = 0.01;
/// Overlapping pairs listed one by one, deepest first; the rest are counted.
constexpr std::size_t kListedOverlaps = 5;

std::string number(Real value)
{
    std::ostringstream out;
    out.precision(3);
    out << value;
    return out.str();
}

std::string metres(Real value)
{
    return number(value) + " m";
}

/// The largest length tolerance of the step and its name.
struct Tolerance
{
    Real length = kFixedTolerance;
    std::string name = "push-out's convergence";
};

Tolerance largestTolerance(const StepOptions& options)
{
    Tolerance largest;
    if (options.contactThickness > largest.length)
    {
        largest = {options.contactThickness, "contact_thickness"};
    }
    if (options.pushOut && options.pushOutAllowance > largest.length)
    {
        largest = {options.pushOutAllowance, "push_out_allowance"};
    }
    return largest;
}

/// How the messages call body k.
class BodyNames
{
  public:
    explicit BodyNames(const std::vector<std::string>& names) : m_names(names) {}

    std::string operator()(std::size_t k) const
    {
        if (k < m_names.size() && !m_names[k].empty())
        {
            return "\"" + m_names[k] + "\"";
        }
        return "body " + std::to_string(k);
    }

  private:
    const std::vector<std::string>& m_names;
};

/// How far the body reaches from the origin, including its extent: what the coordinates of its
/// points are made of. A plane: the distance of its surface from the origin.
Real reachFromOrigin(const RigidBody& body)
{
    if (const auto* plane = std::get_if<Plane>(&body.shape))
    {
        return std::abs(plane->offset + (body.rotation * plane->normal).dot(body.position));
    }
    return body.position.norm() + body.boundingRadius;
}

void timeStepWarnings(const WorldImpl& world, const StepOptions& options, std::uint32_t smallest, const BodyNames& name,
                      std::vector<Warning>& out)
{
    const Real size = thinnestHalfExtent(world.bodies[smallest].shape);
    const Real dt = options.dt;
    const Real g = world.def.gravity.norm();
    const Real fall = g * dt * dt;
    if (fall > kGravityStepFraction * size)
    {
        const Real largest = std::sqrt(kGravityStepFraction * size / g);
        out.push_back({Warning::Kind::LargeTimeStep,
                       "dt = " + number(dt) + " s is too large for this scene: gravity moves a body from rest " +
                           metres(fall) + " in one step (g dt^2), " + number(fall / size) +
                           " times the size of the smallest body, " + name(smallest) + " (" + metres(size) +
                           " at its thinnest half extent). Contacts are then found up to a step's move away, so "
                           "bodies stop short of what they land on, hang above it or bounce from the wrong "
                           "height. Use dt <= " +
                           number(largest) + " s (g dt^2 at most an eighth of the smallest size)."});
    }
    Real fastest = 0.0;
    std::uint32_t fastBody = 0;
    for (std::uint32_t k = 0; k < world.bodies.size(); ++k)
    {
        const RigidBody& body = world.bodies[k];
        if (body.dynamic && !body.removed)
        {
            // the fastest point of the body: its centre's speed and its spin at the bounding radius
            const Real speed = body.linearVelocity.norm() + body.angularVelocity.norm() * body.boundingRadius;
            if (speed > fastest)
            {
                fastest = speed;
                fastBody = k;
            }
        }
    }
    if (fastest * dt > kSpeedStepFraction * size)
    {
        out.push_back({Warning::Kind::FastBody,
                       "dt = " + number(dt) + " s is too large for the speed of " + name(fastBody) + ": at " +
                           number(fastest) + " m/s (its fastest point at the start) it moves " + metres(fastest * dt) +
                           " in one step, more than half the size of the smallest body, " + name(smallest) + " (" +
                           metres(size) +
                           " at its thinnest half extent). A step that long can carry it past thin bodies, and "
                           "its collisions are resolved up to a step's move from where they happen. Use dt <= " +
                           number(kSpeedStepFraction * size / fastest) + " s."});
    }
}

void sizeWarnings(const WorldImpl& world, const StepOptions& options, std::uint32_t smallest, const BodyNames& name,
                  std::vector<Warning>& out)
{
    const Real size = thinnestHalfExtent(world.bodies[smallest].shape);
    const Tolerance tolerance = largestTolerance(options);
    if (tolerance.length > kWarnedFraction * size && sizeRefusal(size, options).empty())
    {
        std::string why;
        std::string what;
        if (tolerance.name == "contact_thickness")
        {
            why = "bodies rest anywhere within it of a surface";
            what = "set contact_thickness to at most " + metres(kWarnedFraction * size) + " (a hundredth of that size)";
        }
        else if (tolerance.name == "push_out_allowance")
        {
            why = "overlaps up to that deep are left as they are";
            what =
                "set push_out_allowance to at most " + metres(kWarnedFraction * size) + " (a hundredth of that size)";
        }
        else
        {
            why = "push-out resolves overlaps no finer than that";
            what = "give lengths in a smaller unit (millimetres, micrometres)";
        }
        out.push_back({Warning::Kind::SmallBody,
                       name(smallest) + " is small for the step's length tolerances: " + tolerance.name + " (" +
                           metres(tolerance.length) + ") is " + number(100.0 * tolerance.length / size) +
                           " % of its thinnest half extent (" + metres(size) + "), and " + why + ". Bodies under " +
                           metres(smallestServedSize(options)) + " would be refused; " + what + "."});
    }
}

void overlapWarnings(const WorldImpl& world, const StepOptions& options, Real extent, const BodyNames& name,
                     std::vector<Warning>& out)
{
    // exactly touching bodies (a stack) may overlap by round-off of their coordinates; that is no overlap
    const Real threshold = std::max(options.contactThickness, 16.0 * kEpsilon * extent);
    std::vector<BroadPhaseBody> broad(world.bodies.size());
    for (std::size_t k = 0; k < world.bodies.size(); ++k)
    {
        const RigidBody& body = world.bodies[k];
        const Pose placed = body.shapePose(body.pose());
        broad[k] = {&body.shape,  placed,       placed, body.boundingRadius, body.dynamic ? threshold : 0.0,
                    body.dynamic, !body.removed};
    }
    BroadPhase broadPhase;
    std::vector<BodyPair> pairs;
    broadPhase.findPairs(broad, 1, pairs);
    struct Overlap
    {
        Real depth;
        BodyPair pair;
    };
    std::vector<Overlap> overlaps;
    NarrowPhaseScratch scratch;
    for (const BodyPair& pair : pairs)
    {
        if (!world.collides(pair.a, pair.b))
        {
            continue;
        }
        const RigidBody& a = world.bodies[pair.a];
        const RigidBody& b = world.bodies[pair.b];
        const Real depth =
            -leastSignedDistance(a.shape, a.shapePose(a.pose()), b.shape, b.shapePose(b.pose()), scratch);
        if (depth > threshold)
        {
            overlaps.push_back({depth, pair});
        }
    }
    std::stable_sort(overlaps.begin(), overlaps.end(),
                     [](const Overlap& x, const Overlap& y) { return x.depth > y.depth; });
    for (std::size_t i = 0; i < std::min(overlaps.size(), kListedOverlaps); ++i)
    {
        const Overlap& overlap = overlaps[i];
        std::string what;
        if (!options.pushOut)
        {
            what = "with push-out off they stay inside each other";
        }
        else if (overlap.depth > options.pushOutAllowance)
        {
            what =
                "push-out will part them at up to " + number(options.pushOutSpeed) + " m/s, a motion no force explains";
        }
        else
        {
            what = "that is within the push-out allowance (" + metres(options.pushOutAllowance) +
                   "), so they stay inside each other";
        }
        out.push_back({Warning::Kind::InitialOverlap,
                       name(overlap.pair.a) + " and " + name(overlap.pair.b) + " overlap by " + metres(overlap.depth) +
                           " at the start, more than the contact thickness (" + metres(options.contactThickness) +
                           "): " + what + ". Place them apart (touching is fine)."});
    }
    if (overlaps.size() > kListedOverlaps)
    {
        out.push_back({Warning::Kind::InitialOverlap,
                       std::to_string(overlaps.size() - kListedOverlaps) +
                           " more pairs overlap at the start by more than the contact thickness, the deepest by " +
                           metres(overlaps[kListedOverlaps].depth) + "."});
    }
}

void massRatioWarnings(const WorldImpl& world, const BodyNames& name, std::vector<Warning>& out)
{
    std::vector<std::uint32_t> dynamic;
    for (std::uint32_t k = 0; k < world.bodies.size(); ++k)
    {
        if (world.bodies[k].dynamic && !world.bodies[k].removed)
        {
            dynamic.push_back(k);
        }
    }
    std::stable_sort(dynamic.begin(), dynamic.end(),
                     [&](std::uint32_t x, std::uint32_t y) { return world.bodies[x].mass < world.bodies[y].mass; });
    // the pair that can touch with the largest ratio: for each body from the lightest, the heaviest
    // it collides with (without filters, the heaviest of all); a lighter body's best bounds the rest
    Real ratio = 0.0;
    std::uint32_t light = 0;
    std::uint32_t heavy = 0;
    for (std::size_t i = 0; i < dynamic.size(); ++i)
    {
        const Real mass = world.bodies[dynamic[i]].mass;
        if (world.bodies[dynamic.back()].mass / mass <= ratio)
        {
            break;
        }
        for (std::size_t j = dynamic.size(); j-- > i + 1;)
        {
            if (world.collides(dynamic[i], dynamic[j]))
            {
                if (world.bodies[dynamic[j]].mass / mass > ratio)
                {
                    ratio = world.bodies[dynamic[j]].mass / mass;
                    light = dynamic[i];
                    heavy = dynamic[j];
                }
                break;
            }
        }
    }
    if (ratio > kLargestMassRatio)
    {
        out.push_back({Warning::Kind::MassRatio,
                       name(heavy) + " (" + number(world.bodies[heavy].mass) + " kg) is " + number(ratio) +
                           " times as heavy as " + name(light) + " (" + number(world.bodies[light].mass) +
                           " kg), and they can touch. The contact pass stops when a sweep changes velocities by "
                           "less than 1e-6 of the speeds, and between bodies of mass ratio R it converges so "
                           "slowly that about R * 1e-6 of the speeds is left unresolved: loads passed through "
                           "the light body are off, and a stack on it can sink through it. Keep masses that touch "
                           "within 1e4 of each other (or keep such bodies apart with collision filters)."});
    }
}

void farFromOriginWarnings(const WorldImpl& world, const StepOptions& options, const BodyNames& name,
                           std::vector<Warning>& out)
{
    if (!(options.contactThickness > 0.0))
    {
        return; // a zero thickness asks for contact decided at round-off: nothing to compare with
    }
    Real extent = 0.0;
    std::uint32_t farthest = 0;
    for (std::uint32_t k = 0; k < world.bodies.size(); ++k)
    {
        if (!world.bodies[k].removed && reachFromOrigin(world.bodies[k]) > extent)
        {
            extent = reachFromOrigin(world.bodies[k]);
            farthest = k;
        }
    }
    const Real roundOff = kEpsilon * extent;
    if (roundOff > kRoundOffFraction * options.contactThickness)
    {
        out.push_back({Warning::Kind::FarFromOrigin,
                       name(farthest) + " reaches " + metres(extent) +
                           " from the origin, where a coordinate carries round-off of about " + metres(roundOff) +
                           " (2.2e-16 of it), " + number(100.0 * roundOff / options.contactThickness) +
                           " % of the contact thickness (" + metres(options.contactThickness) +
                           "): gaps there are differences of such coordinates, so round-off takes a visible share "
                           "of the thickness that decides whether bodies touch. Put the origin among the bodies, "
                           "or keep the scene within " +
                           metres(kRoundOffFraction * options.contactThickness / kEpsilon) +
                           " of it, or raise contact_thickness."});
    }
}

} // namespace

Real smallestServedSize(const StepOptions& options)
{
    return largestTolerance(options).length / kServedFraction;
}

std::string sizeRefusal(Real size, const StepOptions& options)
{
    const Real least = smallestServedSize(options);
    if (!(size < least))
    {
        return {};
    }
    std::string text = "its thinnest half extent, " + metres(size) + ", is below the " + metres(least) +
                       " that the step's length tolerances serve: ";
    if (size < kFixedTolerance / kServedFraction)
    {
        return text + "no options serve a body under " + metres(kFixedTolerance / kServedFraction) +
               " (push-out converges to " + metres(kFixedTolerance) +
               "); give lengths in a smaller unit (millimetres, micrometres)";
    }
    std::vector<std::string> over;
    for (const auto& [length, field] :
         {std::pair{options.contactThickness, "contact_thickness"},
          std::pair{options.pushOut ? options.pushOutAllowance : 0.0, "push_out_allowance"}})
    {
        if (length > kServedFraction * size)
        {
            over.push_back(std::string(field) + " (" + metres(length) + ")");
        }
    }
    std::string list = over.front();
    for (std::size_t i = 1; i < over.size(); ++i)
    {
        list += " and " + over[i];
    }
    return text + list + (over.size() > 1 ? " are" : " is") +
           " more than a tenth of it (a body rests anywhere within the contact thickness of a surface, and "
           "overlaps within the push-out allowance are left as they are); set " +
           (over.size() > 1 ? "them" : "it") + " to at most " + metres(kServedFraction * size) +
           ", or give lengths in a smaller unit";
}

void WorldImpl::findSmallestBody()
{
    smallestSize = std::numeric_limits<Real>::infinity();
    smallestBody = 0;
    for (std::uint32_t k = 0; k < bodies.size(); ++k)
    {
        if (!bodies[k].removed && thinnestHalfExtent(bodies[k].shape) < smallestSize)
        {
            smallestSize = thinnestHalfExtent(bodies[k].shape);
            smallestBody = k;
        }
    }
    smallestKnown = true;
}

std::vector<Warning> World::warnings(const StepOptions& options, const std::vector<std::string>& names) const
{
    const WorldImpl& world = *m_impl;
    const BodyNames name(names);
    std::vector<Warning> out;
    // the smallest live body that is not a plane; every dynamic body is one, so a world with none
    // has nothing to step
    std::uint32_t smallest = 0;
    Real size = std::numeric_limits<Real>::infinity();
    Real extent = 0.0;
    for (std::uint32_t k = 0; k < world.bodies.size(); ++k)
    {
        const RigidBody& body = world.bodies[k];
        if (!body.removed)
        {
            extent = std::max(extent, reachFromOrigin(body));
            if (thinnestHalfExtent(body.shape) < size)
            {
                size = thinnestHalfExtent(body.shape);
                smallest = k;
            }
        }
    }
    if (std::isfinite(size))
    {
        timeStepWarnings(world, options, smallest, name, out);
        sizeWarnings(world, options, smallest, name, out);
    }
    overlapWarnings(world, options, extent, name, out);
    massRatioWarnings(world, name, out);
    farFromOriginWarnings(world, options, name, out);
    return out;
}

} // namespace impulse
