// SPDX-License-Identifier: MIT
// libFuzzer target: the trajectory reader on arbitrary bytes. Every input must be read or refused
// with io::TrajectoryError, and what is read must keep the promises of trajectory_reader.hpp (every
// sample holds every body, times never go backwards, numbers finite, orientations unit); anything
// else is a finding.
#include "fuzz_support.hpp"

#include <impulse/io/trajectory_reader.hpp>

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <sstream>

namespace
{

void require(bool holds, const char* what)
{
    if (!holds)
    {
        std::fprintf(stderr, "trajectory_fuzz: a trajectory was read that breaks its promise: %s\n", what);
        std::abort();
    }
}

} // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
    std::istringstream in{std::string(impulse::fuzz::asText(data, size))};
    impulse::io::Trajectory trajectory;
    try
    {
        trajectory = impulse::io::parseTrajectory(in, "fuzz.csv");
    }
    catch (const impulse::io::TrajectoryError&)
    {
        return 0; // refused with a message: what a bad file must get
    }
    require(trajectory.sampleCount() > 0 && trajectory.bodyCount > 0, "no samples or no bodies");
    require(trajectory.samples.size() == trajectory.sampleCount() * trajectory.bodyCount, "samples lack bodies");
    for (std::size_t i = 0; i < trajectory.sampleCount(); ++i)
    {
        require(std::isfinite(trajectory.times[i]), "a time is not finite");
        require(i == 0 || trajectory.times[i - 1] <= trajectory.times[i], "time goes backwards");
    }
    for (const impulse::io::BodySample& sample : trajectory.samples)
    {
        require(sample.position.allFinite() && sample.linearVelocity.allFinite() && sample.angularVelocity.allFinite(),
                "a number is not finite");
        require(std::abs(sample.orientation.norm() - 1.0) < 1e-6, "an orientation is not a unit quaternion");
    }
    return 0;
}
