// SPDX-License-Identifier: MIT
#pragma once

#include <impulse/math.hpp>

#include <cstddef>
#include <filesystem>
#include <istream>
#include <stdexcept>
#include <string>
#include <vector>

namespace impulse::io
{

/// A trajectory file that cannot be used. The message names the file, the line and what is wrong,
/// e.g. "traj.csv: line 1: header must be t,body,x,y,z,qw,qx,qy,qz,vx,vy,vz,wx,wy,wz; got t,x,y".
class TrajectoryError : public std::runtime_error
{
  public:
    using std::runtime_error::runtime_error;
};

/// One body at one sample, as the trajectory CSV stores it (world frame).
struct BodySample
{
    Vec3 position = Vec3::Zero();
    Quat orientation = Quat::Identity();
    Vec3 linearVelocity = Vec3::Zero();
    Vec3 angularVelocity = Vec3::Zero();
};

/// A trajectory in memory: every sample holds every body.
struct Trajectory
{
    std::vector<Real> times;         ///< seconds, non-decreasing
    std::size_t bodyCount = 0;       ///< dynamic bodies, numbered from 0
    std::vector<BodySample> samples; ///< sample i, body k at [i * bodyCount + k]
    /// Empty for a whole file. For a file cut off while it was written (a run killed, a disk full):
    /// where it stops and what was left out, e.g. "cut off at line 5003 (an incomplete last sample
    /// dropped); 1250 whole samples up to t = 1.249 s".
    std::string cutOff;

    std::size_t sampleCount() const { return times.size(); }
    const BodySample& at(std::size_t sample, std::size_t body) const { return samples[sample * bodyCount + body]; }
};

/// Reads a trajectory CSV as `impulse run --out` writes it (docs/cli.md): the exact header, then
/// for each sample one row per body, bodies 0, 1, ... in order, every number finite. Throws
/// TrajectoryError naming the file and the line on any departure, including an empty file. A file
/// that was cut off is read up to its last whole sample, with Trajectory::cutOff saying so: its last
/// line has no end of line (the writer ends every row with one), or its last sample lacks bodies.
Trajectory readTrajectory(const std::filesystem::path& path);

/// Parses trajectory CSV text from a stream; `source` names it in error messages.
Trajectory parseTrajectory(std::istream& in, const std::string& source);

} // namespace impulse::io
