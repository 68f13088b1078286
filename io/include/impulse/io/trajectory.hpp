// SPDX-License-Identifier: MIT
#pragma once

#include <impulse/io/trajectory_reader.hpp>
#include <impulse/world.hpp>

#include <ostream>
#include <vector>

namespace impulse::io
{

/// Writes trajectories as CSV, one row per dynamic body per sample, with the header
/// t,body,x,y,z,qw,qx,qy,qz,vx,vy,vz,wx,wy,wz (centre of mass, world-frame velocities). Numbers are
/// printed with 17 significant digits, so a file holds the exact doubles and equal runs give equal
/// bytes.
class TrajectoryWriter
{
  public:
    explicit TrajectoryWriter(std::ostream& out);
    void writeHeader();
    /// One row per body in `bodies`, numbered 0.. in that order, at time t.
    void writeSample(Real t, const World& world, const std::vector<BodyId>& bodies);
    /// The header, then every sample of a trajectory held in memory.
    void writeTrajectory(const Trajectory& trajectory);

  private:
    void writeRow(Real t, std::size_t body, const BodySample& sample);

    std::ostream& m_out;
};

} // namespace impulse::io
