// SPDX-License-Identifier: MIT
#include <impulse/io/replay.hpp>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <variant>

namespace impulse::io
{
namespace
{

// Where the body's shape is after a step, and how its origin moves: what a measurement tracks. The
// body's own state when its centre of mass is the shape's centroid.
BodySample sampleOf(const World& world, BodyId body)
{
    const BodyState state = world.state(body);
    const Vec3 origin = world.shapePose(body).position;
    return {origin, state.orientation, state.linearVelocity + state.angularVelocity.cross(origin - state.position),
            state.angularVelocity};
}

// The state a fraction of the way from one step's to the next: positions and velocities linearly,
// orientations by slerp.
BodySample between(const BodySample& before, const BodySample& after, Real fraction)
{
    return {before.position + fraction * (after.position - before.position),
            before.orientation.slerp(fraction, after.orientation),
            before.linearVelocity + fraction * (after.linearVelocity - before.linearVelocity),
            before.angularVelocity + fraction * (after.angularVelocity - before.angularVelocity)};
}

// The angle between two orientations, degrees: that of the rotation taking one to the other.
Real angleBetween(const Quat& a, const Quat& b)
{
    const Quat relative = a.conjugate() * b;
    return 2.0 * std::atan2(relative.vec().norm(), std::abs(relative.w())) * 180.0 / std::numbers::pi;
}

// The value at `fraction` of the sorted list, interpolating between neighbours.
Real quantile(const std::vector<Real>& sorted, Real fraction)
{
    const Real at = fraction * static_cast<Real>(sorted.size() - 1);
    const auto below = static_cast<std::size_t>(std::floor(at));
    const std::size_t above = std::min(below + 1, sorted.size() - 1);
    return sorted[below] + (at - static_cast<Real>(below)) * (sorted[above] - sorted[below]);
}

} // namespace

ErrorSummary summarise(std::vector<Real> errors)
{
    ErrorSummary summary;
    if (errors.empty())
    {
        return summary;
    }
    std::sort(errors.begin(), errors.end());
    Real sum = 0.0;
    for (const Real e : errors)
    {
        sum += e;
    }
    summary.mean = sum / static_cast<Real>(errors.size());
    Real squares = 0.0;
    for (const Real e : errors)
    {
        squares += (e - summary.mean) * (e - summary.mean);
    }
    summary.deviation = std::sqrt(squares / static_cast<Real>(errors.size()));
    summary.median = quantile(errors, 0.5);
    summary.percentile90 = quantile(errors, 0.9);
    return summary;
}

Real bodySize(const Shape& shape)
{
    if (const auto* box = std::get_if<Box>(&shape))
    {
        return 2.0 * box->halfExtents.maxCoeff();
    }
    if (const auto* sphere = std::get_if<Sphere>(&shape))
    {
        return 2.0 * sphere->radius;
    }
    if (const auto* capsule = std::get_if<Capsule>(&shape))
    {
        return 2.0 * capsule->radius;
    }
    return 2.0 * boundingRadius(shape);
}

ReplayError replay(World& world, BodyId body, const StepOptions& options, const Trajectory& measured, Real size,
                   const std::string& source, Trajectory* simulated)
{
    if (measured.sampleCount() < 2 || measured.bodyCount < 1)
    {
        throw std::invalid_argument(source + ": a measurement needs at least two samples of body 0");
    }
    for (std::size_t i = 1; i < measured.sampleCount(); ++i)
    {
        if (!(measured.times[i] > measured.times[i - 1]))
        {
            throw std::invalid_argument(source + ": sample " + std::to_string(i) +
                                        " is not later than the one before it");
        }
    }
    // the measurement places the shape; the world, the centre of mass
    const BodySample& first = measured.at(0, 0);
    const Vec3 lever = first.orientation.normalized() * world.centerOfMass(body);
    world.setState(body, first.position + lever, first.orientation,
                   first.linearVelocity + first.angularVelocity.cross(lever), first.angularVelocity);
    const Real start = world.time();
    const Real t0 = measured.times[0];

    ReplayError error;
    error.source = source;
    BodySample before = sampleOf(world, body);
    Real beforeTime = 0.0; // since the start
    BodySample after = before;
    if (simulated != nullptr)
    {
        *simulated = Trajectory{};
        simulated->bodyCount = 1;
        simulated->times.push_back(t0);
        simulated->samples.push_back(before);
    }
    Real afterTime = 0.0;
    for (std::size_t i = 1; i < measured.sampleCount(); ++i)
    {
        const Real due = measured.times[i] - t0;
        while (afterTime < due)
        {
            before = after;
            beforeTime = afterTime;
            world.step(options);
            after = sampleOf(world, body);
            afterTime = world.time() - start;
        }
        const Real fraction = afterTime > beforeTime ? (due - beforeTime) / (afterTime - beforeTime) : 1.0;
        const BodySample state = between(before, after, fraction);
        if (simulated != nullptr)
        {
            simulated->times.push_back(measured.times[i]);
            simulated->samples.push_back(state);
        }
        const BodySample& sample = measured.at(i, 0);
        const Real positionError = 100.0 * (state.position - sample.position).norm() / size;
        const Real rotationError = angleBetween(state.orientation, sample.orientation);
        error.positionError += positionError;
        error.rotationError += rotationError;
        error.finalPosition = positionError;
        error.finalRotation = rotationError;
        ++error.samples;
    }
    error.positionError /= static_cast<Real>(error.samples);
    error.rotationError /= static_cast<Real>(error.samples);
    return error;
}

} // namespace impulse::io
