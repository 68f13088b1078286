// SPDX-License-Identifier: MIT
// Replaying a measurement (impulse/io/replay.hpp): a body in free flight against its closed-form
// path, sampled at times that fall between steps, and the summary statistics.
#include <impulse/io/replay.hpp>

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <stdexcept>

namespace impulse::io
{
namespace
{

// A cube (side 0.1 m) thrown upward and spinning about a principal axis, with nothing to hit,
// measured at 148 Hz from its exact path, x(t) = x0 + v0 t + g t^2 / 2 and q(t) = exp(w t / 2) q0:
// the path of its centre of mass, which is where the measurement tracks the cube's centre unless the
// cube is weighted off it (then the centre circles the centre of mass, and the replay must start
// and compare the cube's centre, not its centre of mass, which would be 2.7 cm off).
class FreeFlight : public ::testing::TestWithParam<Vec3>
{
};

TEST_P(FreeFlight, IsOffByTheSymplecticStepsDriftAndTurnsExactly)
{
    World world;
    const MaterialId material = world.createMaterial({0.0, 0.5});
    BodyDef def;
    def.shape = Box{Vec3::Constant(0.05)};
    def.material = material;
    def.mass = 0.4;
    def.centerOfMass = GetParam();
    const BodyId cube = world.createBody(def);
    StepOptions options;
    options.dt = 0.001;

    const Vec3 x0(0.1, -0.2, 1.0);
    const Vec3 v0(0.5, 0.2, 2.0);
    const Vec3 g = world.gravity();
    const Vec3 omega(0.0, 0.0, 7.0);
    const Quat q0(Eigen::AngleAxisd(0.4, Vec3(1.0, 1.0, 0.0).normalized()));
    Trajectory measured;
    measured.bodyCount = 1;
    constexpr int kSamples = 75; // half a second
    for (int i = 0; i < kSamples; ++i)
    {
        const Real t = i / 148.0;
        const Quat turn(Eigen::AngleAxisd(omega.norm() * t, omega.normalized()));
        measured.times.push_back(t);
        const Vec3 lever = turn * q0 * def.centerOfMass; // from the cube's centre to the centre of mass
        measured.samples.push_back(
            {x0 + v0 * t + 0.5 * g * t * t - lever, turn * q0, v0 + g * t - omega.cross(lever), omega});
    }
    const ReplayError error = replay(world, cube, options, measured, 0.1, "free flight");
    ASSERT_EQ(error.samples, static_cast<std::size_t>(kSamples - 1));
    // Semi-implicit Euler puts a falling body g dt t / 2 below the parabola at the steps (its
    // velocity is updated first); between two steps the chord of the simulated path is within
    // g dt^2 / 8 of it. The mean error is that drift averaged over the samples, in % of 0.1 m.
    Real drift = 0.0;
    for (int i = 1; i < kSamples; ++i)
    {
        drift += 100.0 * g.norm() * options.dt * (i / 148.0) / 2.0 / 0.1;
    }
    drift /= kSamples - 1;
    const Real chord = 100.0 * g.norm() * options.dt * options.dt / 8.0 / 0.1;
    EXPECT_NEAR(error.positionError, drift, chord + 1e-9);
    EXPECT_GT(drift, 1.0); // 1.2 %: the drift is what is measured, not round-off
    // a constant spin about a principal axis is turned exactly by the step and by slerp
    EXPECT_LT(error.rotationError, 1e-9);
}

// a cube's inertia is isotropic, so every axis is principal, about any centre of mass
INSTANTIATE_TEST_SUITE_P(Replay, FreeFlight, ::testing::Values(Vec3::Zero(), Vec3(0.02, 0.01, -0.015)));

TEST(Replay, AMeasurementWithoutALaterSampleIsRefused)
{
    World world;
    const MaterialId material = world.createMaterial({0.0, 0.5});
    BodyDef def;
    def.shape = Sphere{0.1};
    def.material = material;
    def.mass = 1.0;
    const BodyId ball = world.createBody(def);
    Trajectory measured;
    measured.bodyCount = 1;
    measured.times = {0.0};
    measured.samples.resize(1);
    EXPECT_THROW(replay(world, ball, StepOptions{}, measured, 0.2, "one sample"), std::invalid_argument);
    measured.times = {0.0, 0.0};
    measured.samples.resize(2);
    EXPECT_THROW(replay(world, ball, StepOptions{}, measured, 0.2, "two at once"), std::invalid_argument);
}

TEST(Replay, SummaryIsMeanDeviationMedianAndNinetiethPercentile)
{
    const ErrorSummary summary = summarise({4.0, 1.0, 3.0, 2.0, 5.0});
    EXPECT_DOUBLE_EQ(summary.mean, 3.0);
    EXPECT_DOUBLE_EQ(summary.deviation, std::sqrt(2.0));
    EXPECT_DOUBLE_EQ(summary.median, 3.0);
    EXPECT_DOUBLE_EQ(summary.percentile90, 4.6); // 0.9 of the way from the first to the fifth: 4 + 0.6
    const ErrorSummary none = summarise({});
    EXPECT_EQ(none.mean, 0.0);
}

TEST(Replay, SizeIsABoxsLongestEdgeOrABallsDiameter)
{
    EXPECT_DOUBLE_EQ(bodySize(Box{Vec3(0.1, 0.3, 0.2)}), 0.6);
    EXPECT_DOUBLE_EQ(bodySize(Sphere{0.25}), 0.5);
}

} // namespace
} // namespace impulse::io
