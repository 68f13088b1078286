// SPDX-License-Identifier: MIT
// Capsules in scenes: one lying on the ground stays at rest (its two end contacts hold it without
// rocking), one dropped on its end bounces with the restitution asked for, one lying on a box stays
// on it; and the scene format reads and checks the capsule shape.
#include <impulse/io/scene.hpp>

#include <gtest/gtest.h>

#include <string>

namespace impulse
{
namespace
{

std::string capsuleScene(const std::string& restitution, const std::string& capsuleBody,
                         const std::string& extraBodies = "")
{
    return R"({"dt": 0.001, "duration": 2.0,
  "materials": {"m": {"restitution": )" +
           restitution + R"(, "friction": 0.5}},
  "bodies": [
    {"static": true, "shape": {"type": "plane", "normal": [0, 0, 1]}, "material": "m"},)" +
           extraBodies + capsuleBody + "]}";
}

void stepFor(io::Scene& scene, Real seconds)
{
    const long long steps = std::llround(seconds / scene.options.dt);
    for (long long k = 0; k < steps; ++k)
    {
        scene.world.step(scene.options);
    }
}

TEST(CapsuleScenario, LyingOnTheGroundStaysAtRest)
{
    io::Scene scene = io::parseScene(
        capsuleScene("0.5", R"({"shape": {"type": "capsule", "radius": 0.1, "half_length": 0.3}, "mass": 1,
             "position": [0, 0, 0.1], "orientation": {"axis": [0, 1, 0], "angle_deg": 90}, "material": "m"})"),
        "lying");
    const BodyId capsule = scene.dynamicBodies.at(0);
    const BodyState start = scene.world.state(capsule);
    stepFor(scene, 2.0);
    const BodyState end = scene.world.state(capsule);
    // resting contact is resolved exactly: any rocking or creep would show far above round-off
    EXPECT_LT((end.position - start.position).norm(), 1e-9);
    EXPECT_LT(end.linearVelocity.norm(), 1e-9);
    EXPECT_LT(end.angularVelocity.norm(), 1e-9);
    EXPECT_LT(end.orientation.angularDistance(start.orientation), 1e-9);
}

TEST(CapsuleScenario, DroppedOnItsEndBouncesWithTheAskedRestitution)
{
    // upright, lower end 1 m above the ground: the contact lies under the centre, no torque, so the
    // centre's apex after the first bounce is (h + r) + eps^2 * 1 m
    const Real eps = 0.5;
    const Real r = 0.1;
    const Real h = 0.3;
    io::Scene scene = io::parseScene(
        capsuleScene("0.5", R"({"shape": {"type": "capsule", "radius": 0.1, "half_length": 0.3}, "mass": 1,
             "position": [0, 0, 1.4], "material": "m"})"),
        "dropped");
    const BodyId capsule = scene.dynamicBodies.at(0);
    Real previousVz = 0.0;
    Real apex = -1.0;
    Real lowest = 10.0;
    const long long steps = std::llround(1.2 / scene.options.dt);
    for (long long k = 0; k < steps && apex < 0.0; ++k)
    {
        scene.world.step(scene.options);
        const BodyState s = scene.world.state(capsule);
        lowest = std::min(lowest, s.position.z());
        if (previousVz > 0.0 && s.linearVelocity.z() <= 0.0)
        {
            apex = s.position.z();
        }
        previousVz = s.linearVelocity.z();
        EXPECT_LT(s.angularVelocity.norm(), 1e-12);
    }
    ASSERT_GT(apex, 0.0) << "no bounce";
    const Real expected = h + r + eps * eps * 1.0;
    EXPECT_NEAR(apex, expected, 0.01 * (expected - h - r));
    EXPECT_GT(lowest, h + r - 0.01 * r); // penetration under 1 % of the radius
}

TEST(CapsuleScenario, LyingOnABoxStaysOnIt)
{
    io::Scene scene =
        io::parseScene(capsuleScene("0.0",
                                    R"({"shape": {"type": "capsule", "radius": 0.1, "half_length": 0.3}, "mass": 1,
             "position": [0.05, 0, 0.5], "orientation": {"axis": [0, 1, 0], "angle_deg": 90}, "material": "m"})",
                                    R"({"shape": {"type": "box", "half_extents": [0.5, 0.5, 0.2]}, "mass": 5,
             "position": [0, 0, 0.2], "material": "m"},)"),
                       "on box");
    const BodyId capsule = scene.dynamicBodies.at(1);
    const BodyState start = scene.world.state(capsule);
    stepFor(scene, 2.0);
    const BodyState end = scene.world.state(capsule);
    EXPECT_LT((end.position - start.position).norm(), 1e-9);
    EXPECT_LT(end.linearVelocity.norm(), 1e-9);
    EXPECT_LT(end.angularVelocity.norm(), 1e-9);
}

TEST(CapsuleScenario, SceneFormatChecksTheCapsule)
{
    const auto withShape = [](const std::string& shape)
    { return capsuleScene("0.5", R"({"shape": )" + shape + R"(, "mass": 1, "material": "m"})"); };
    EXPECT_NO_THROW(io::parseScene(withShape(R"({"type": "capsule", "radius": 0.1, "half_length": 0.2})"), "ok"));
    const auto message = [&](const std::string& shape)
    {
        try
        {
            io::parseScene(withShape(shape), "s.json");
        }
        catch (const io::SceneError& error)
        {
            return std::string(error.what());
        }
        return std::string("no error");
    };
    EXPECT_EQ(message(R"({"type": "capsule", "radius": 0.1, "half_length": -0.2})"),
              "s.json: /bodies/1/shape/half_length: must be positive, got -0.2");
    EXPECT_EQ(message(R"({"type": "capsule", "radius": 0.1})"),
              "s.json: /bodies/1/shape/half_length: missing required field");
    EXPECT_EQ(message(R"({"type": "capsule", "radius": 0.1, "half_length": 0.2, "half_extents": [1, 1, 1]})"),
              "s.json: /bodies/1/shape/half_extents: unknown field (expected one of: type, radius, half_length)");
}

} // namespace
} // namespace impulse
