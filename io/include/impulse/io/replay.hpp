// SPDX-License-Identifier: MIT
// Replaying measured trajectories: a body started from a measurement's first sample, simulated and
// compared with the measurement at its sample times (docs/cli.md, impulse replay).
#pragma once

#include <impulse/io/trajectory_reader.hpp>
#include <impulse/world.hpp>

#include <cstddef>
#include <string>
#include <vector>

namespace impulse::io
{

/// How far one replay ended up from its measurement.
struct ReplayError
{
    std::string source;       ///< the measurement's file
    std::size_t samples = 0;  ///< samples compared: every one after the first
    Real positionError = 0.0; ///< per cent of the body's size, the mean over the samples
    Real rotationError = 0.0; ///< degrees, the mean over the samples
    Real finalPosition = 0.0; ///< per cent of the body's size, at the last sample
    Real finalRotation = 0.0; ///< degrees, at the last sample
};

/// Mean, standard deviation, median and 90th percentile of per-replay errors.
struct ErrorSummary
{
    Real mean = 0.0;
    Real deviation = 0.0; ///< the population's standard deviation
    Real median = 0.0;
    Real percentile90 = 0.0;
};

/// Summarises a list of per-replay errors (linear interpolation between order statistics for the
/// median and the 90th percentile). All zero for an empty list.
ErrorSummary summarise(std::vector<Real> errors);

/// The size the position error is measured in: a box's longest edge, a sphere's or a capsule's
/// width, a mesh's bounding diameter.
Real bodySize(const Shape& shape);

/// Starts dynamic body `body` of `world` (whose other bodies are static) from the first sample of
/// `measured`'s body 0, steps it with `options` past the last sample's time, and compares it with
/// the measurement at every later sample: the simulated pose at a sample's time is interpolated
/// between the two steps around it (positions linearly, orientations by slerp). The position
/// error is the distance of the centres in per cent of `size`, the rotation error the angle of the
/// relative rotation in degrees. The measurement tracks the shape's origin (World::shapePose),
/// which is the body's centre of mass unless the body was given another (BodyDef::centerOfMass).
/// With `simulated`, the simulation sampled at the measured times (velocities interpolated
/// linearly) is stored there, as a trajectory of one body. Throws std::invalid_argument for a
/// measurement without a second sample or whose times are not increasing.
ReplayError replay(World& world, BodyId body, const StepOptions& options, const Trajectory& measured, Real size,
                   const std::string& source, Trajectory* simulated = nullptr);

} // namespace impulse::io
