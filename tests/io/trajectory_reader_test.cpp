// SPDX-License-Identifier: MIT
// The trajectory reader's contract: it reads back exactly what TrajectoryWriter writes, and refuses
// anything else with io::TrajectoryError reading "<source>: line <n>: <what is wrong>".
#include <impulse/impulse.hpp>
#include <impulse/io/trajectory.hpp>
#include <impulse/io/trajectory_reader.hpp>

#include <gtest/gtest.h>

#include <cmath>
#include <sstream>
#include <string>

namespace
{

using impulse::io::parseTrajectory;
using impulse::io::TrajectoryError;

const std::string kHeader = "t,body,x,y,z,qw,qx,qy,qz,vx,vy,vz,wx,wy,wz\n";

impulse::io::Trajectory parse(const std::string& text)
{
    std::istringstream in(text);
    return parseTrajectory(in, "traj.csv");
}

/// The message of the error that parsing `text` raises, or "" if it parses.
std::string refusal(const std::string& text)
{
    try
    {
        parse(text);
    }
    catch (const TrajectoryError& error)
    {
        return error.what();
    }
    return "";
}

TEST(TrajectoryReader, ReadsBackExactlyWhatTheWriterWrites)
{
    impulse::World world;
    const auto material = world.createMaterial({.restitution = 0.5, .friction = 0.3});
    std::vector<impulse::BodyId> bodies;
    bodies.push_back(world.createBody({.shape = impulse::Sphere{0.1},
                                       .material = material,
                                       .mass = 1.0,
                                       .position = {0.1, 0.2, 1.0 / 3.0},
                                       .angularVelocity = {1.0, 2.0, 3.0}}));
    bodies.push_back(world.createBody({.shape = impulse::Box{}, .material = material, .mass = 2.0}));
    std::ostringstream out;
    impulse::io::TrajectoryWriter writer(out);
    writer.writeHeader();
    std::vector<impulse::BodyState> written;
    for (int sample = 0; sample < 3; ++sample)
    {
        writer.writeSample(world.time(), world, bodies);
        written.push_back(world.state(bodies[0]));
        world.step({.dt = 1e-3});
    }
    const impulse::io::Trajectory trajectory = parse(out.str());
    ASSERT_EQ(trajectory.bodyCount, 2u);
    ASSERT_EQ(trajectory.sampleCount(), 3u);
    EXPECT_EQ(trajectory.times[2], 2e-3);
    EXPECT_EQ(trajectory.at(0, 0).position, impulse::Vec3(0.1, 0.2, 1.0 / 3.0));
    EXPECT_EQ(trajectory.at(2, 0).position, written[2].position);
    EXPECT_EQ(trajectory.at(2, 0).linearVelocity, written[2].linearVelocity);
    EXPECT_EQ(trajectory.at(2, 0).orientation.coeffs(), written[2].orientation.coeffs());
    EXPECT_EQ(trajectory.at(0, 0).angularVelocity, written[0].angularVelocity);
}

TEST(TrajectoryReader, RefusesEachDepartureNamingTheFileAndLine)
{
    const std::string row0 = "0,0,0,0,1,1,0,0,0,0,0,0,0,0,0\n";
    const std::string row1 = "0,1,0,0,1,1,0,0,0,0,0,0,0,0,0\n";
    EXPECT_EQ(refusal(""),
              "traj.csv: line 1: empty file; expected the header " + kHeader.substr(0, kHeader.size() - 1));
    EXPECT_EQ(refusal("t,x,y,z\n" + row0),
              "traj.csv: line 1: header must be t,body,x,y,z,qw,qx,qy,qz,vx,vy,vz,wx,wy,wz; got t,x,y,z");
    EXPECT_EQ(refusal(kHeader), "traj.csv: line 1: no samples after the header");
    EXPECT_EQ(refusal(kHeader + "0,0,0,0,1\n"), "traj.csv: line 2: expected 15 comma-separated numbers, got 5");
    EXPECT_EQ(refusal(kHeader + "0,0,0,0,1,1,0,0,0,0,0,0,0,0,0,7\n"),
              "traj.csv: line 2: expected 15 comma-separated numbers, got more");
    EXPECT_EQ(refusal(kHeader + "0,0,0,0,nan,1,0,0,0,0,0,0,0,0,0\n"),
              "traj.csv: line 2: column z: not a finite number: \"nan\"");
    EXPECT_EQ(refusal(kHeader + "0,0,0,0,1 ,1,0,0,0,0,0,0,0,0,0\n"),
              "traj.csv: line 2: column z: not a finite number: \"1 \"");
    EXPECT_EQ(refusal(kHeader + row1), "traj.csv: line 2: expected body 0 (each sample lists bodies 0, 1, ... in "
                                       "order), got 1");
    EXPECT_EQ(refusal(kHeader + "1,0,0,0,1,1,0,0,0,0,0,0,0,0,0\n" + row0), "traj.csv: line 3: time goes backwards");
    EXPECT_EQ(refusal(kHeader + row0 + "0.5,1,0,0,1,1,0,0,0,0,0,0,0,0,0\n"),
              "traj.csv: line 3: body 1 has a different time from body 0 of its sample");
    EXPECT_EQ(refusal(kHeader + "0,0,0,0,1,0,0,0,0,0,0,0,0,0,0\n"),
              "traj.csv: line 2: orientation is not a unit quaternion");
}

// Rounded by hand to four decimals, a quaternion is read as the unit quaternion it stands for.
TEST(TrajectoryReader, NormalisesAHandRoundedQuaternion)
{
    const auto trajectory = parse(kHeader + "0,0,0,0,1,0.7071,0,0.7071,0,0,0,0,0,0,0\n");
    const auto& q = trajectory.samples.at(0).orientation;
    EXPECT_NEAR(q.norm(), 1.0, 1e-15);
    EXPECT_NEAR(q.w(), std::sqrt(0.5), 1e-15);
    EXPECT_NEAR(q.y(), std::sqrt(0.5), 1e-15);
}

// A component of 5.7e160 made the squared norm overflow, and the quaternion was "normalised" to
// zero (found by the trajectory fuzz target, kept in tests/data/fuzz/trajectory)
TEST(TrajectoryReader, NormalisesAQuaternionWhoseSquaredNormOverflows)
{
    const std::string path = std::string(IMPULSE_TEST_DATA_DIR) + "/fuzz/trajectory/quaternion_norm_overflow.csv";
    const auto trajectory = impulse::io::readTrajectory(path);
    ASSERT_EQ(trajectory.sampleCount(), 1u);
    const auto& q = trajectory.at(0, 0).orientation;
    EXPECT_EQ(q.w(), 1.0);
    EXPECT_NEAR(q.x(), -5.301 / 5.6743298e160, 1e-175);
    EXPECT_EQ(q.y(), 0.0);
    EXPECT_EQ(q.z(), 0.0);
}

// A run killed while writing leaves a file that stops anywhere: between two rows of a sample, or
// in the middle of a row (whose last number may then be cut short: "1.2" of "1.25").
TEST(TrajectoryReader, ReadsACutOffFileUpToItsLastWholeSampleAndSaysWhereItStops)
{
    const auto row = [](const std::string& t, int body)
    { return t + "," + std::to_string(body) + ",0,0,1,1,0,0,0,0,0,-1.25,0,0,0\n"; };
    const std::string whole = kHeader + row("0", 0) + row("0", 1) + row("0.5", 0) + row("0.5", 1);
    EXPECT_EQ(parse(whole).cutOff, "");

    // between the rows of the third sample
    const auto betweenRows = parse(whole + row("1", 0));
    EXPECT_EQ(betweenRows.sampleCount(), 2u);
    EXPECT_EQ(betweenRows.samples.size(), 4u);
    EXPECT_EQ(betweenRows.cutOff, "cut off at line 6 (an incomplete last sample of 1 of 2 bodies left out); 2 whole "
                                  "samples up to t = 0.5 s");

    // in the middle of a row: the row has no end of line
    const std::string cutRow = row("1", 1).substr(0, 26);
    const auto inARow = parse(whole + row("1", 0) + cutRow);
    EXPECT_EQ(inARow.sampleCount(), 2u);
    EXPECT_EQ(inARow.at(1, 1).linearVelocity.z(), -1.25);
    EXPECT_EQ(inARow.cutOff, "cut off at line 7 (an incomplete last sample of 1 of 2 bodies and an unfinished row "
                             "left out); 2 whole samples up to t = 0.5 s");
    // the unfinished row is the only one missing: the samples before it stay whole
    const auto lastRowCut = parse(whole.substr(0, whole.size() - 3));
    EXPECT_EQ(lastRowCut.sampleCount(), 1u);
    EXPECT_EQ(lastRowCut.cutOff.substr(0, 20), "cut off at line 5 (a");

    // nothing whole at all
    EXPECT_EQ(refusal(kHeader + row("0", 0).substr(0, 10)), "traj.csv: line 2: cut off before its first whole sample");
}

TEST(TrajectoryReader, AcceptsWindowsLineEndsAndNormalisesOrientation)
{
    const auto trajectory = parse("t,body,x,y,z,qw,qx,qy,qz,vx,vy,vz,wx,wy,wz\r\n0,0,0,0,1,2,0,0,0,0,0,0,0,0,0\r\n");
    ASSERT_EQ(trajectory.sampleCount(), 1u);
    EXPECT_EQ(trajectory.at(0, 0).orientation.w(), 1.0);
}

// Found by the trajectory fuzz target (tests/fuzz): a body number too large for an index was
// converted to size_t before it was compared, which is undefined; it is the body expected or refused.
TEST(TrajectoryReader, ABodyNumberBeyondAnyIndexIsRefusedNotConverted)
{
    const std::string row = ",0,0,1,1,0,0,0,0,0,0,0,0,0\n";
    EXPECT_EQ(
        refusal(kHeader + "0,0" + row + "0,1e300" + row),
        "traj.csv: line 3: expected body 1 (each sample lists bodies 0, 1, ... in order), got 1.0000000000000001e+300");
    EXPECT_EQ(
        refusal(kHeader + "0,0" + row + "0,1" + row + "1,0" + row + "1,1" + row + "2,18446744073709551616" + row),
        "traj.csv: line 6: expected body 0 (each sample lists bodies 0, 1, ... in order), got 1.8446744073709552e+19");
    EXPECT_EQ(refusal(kHeader + "0,0.5" + row), "traj.csv: line 2: body must be a whole number >= 0, got 0.5");

    const std::string path = std::string(IMPULSE_TEST_DATA_DIR) + "/fuzz/trajectory/body_number_beyond_size_t.csv";
    try
    {
        impulse::io::readTrajectory(path);
        FAIL() << "no error";
    }
    catch (const TrajectoryError& error)
    {
        EXPECT_EQ(std::string(error.what())
                      .rfind(path + ": line 5: expected body 0 (each sample lists bodies 0, 1, "
                                    "... in order), got 3.33333333333333",
                             0),
                  0u)
            << error.what();
    }
}

TEST(TrajectoryReader, AMissingFileIsNamed)
{
    try
    {
        impulse::io::readTrajectory("no/such/traj.csv");
        FAIL() << "no error";
    }
    catch (const TrajectoryError& error)
    {
        EXPECT_STREQ(error.what(), "no/such/traj.csv: cannot open for reading");
    }
}

} // namespace
