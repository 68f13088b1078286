// SPDX-License-Identifier: MIT
#include <impulse/io/trajectory.hpp>

#include <cstdio>

namespace impulse::io
{

TrajectoryWriter::TrajectoryWriter(std::ostream& out) : m_out(out) {}

void TrajectoryWriter::writeHeader()
{
    m_out << "t,body,x,y,z,qw,qx,qy,qz,vx,vy,vz,wx,wy,wz\n";
}

void TrajectoryWriter::writeSample(Real t, const World& world, const std::vector<BodyId>& bodies)
{
    for (std::size_t k = 0; k < bodies.size(); ++k)
    {
        const BodyState s = world.state(bodies[k]);
        writeRow(t, k, {s.position, s.orientation, s.linearVelocity, s.angularVelocity});
    }
}

void TrajectoryWriter::writeTrajectory(const Trajectory& trajectory)
{
    writeHeader();
    for (std::size_t i = 0; i < trajectory.sampleCount(); ++i)
    {
        for (std::size_t k = 0; k < trajectory.bodyCount; ++k)
        {
            writeRow(trajectory.times[i], k, trajectory.at(i, k));
        }
    }
}

void TrajectoryWriter::writeRow(Real t, std::size_t body, const BodySample& s)
{
    char line[512];
    const int length = std::snprintf(
        line, sizeof line, "%.17g,%zu,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g\n",
        t, body, s.position.x(), s.position.y(), s.position.z(), s.orientation.w(), s.orientation.x(),
        s.orientation.y(), s.orientation.z(), s.linearVelocity.x(), s.linearVelocity.y(), s.linearVelocity.z(),
        s.angularVelocity.x(), s.angularVelocity.y(), s.angularVelocity.z());
    m_out.write(line, length);
}

} // namespace impulse::io
