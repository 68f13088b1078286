// SPDX-License-Identifier: MIT
// A body's inertia given in the scene (not the shape's own) is the one its contacts act on: a ball
// rolling without slipping down an incline accelerates at g sin(theta) / (1 + I / (m r^2)), 5/7 of
// g sin(theta) for a solid ball and 3/5 for a thin shell of the same mass and radius.
#include <impulse/io/scene.hpp>

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <sstream>
#include <string>

namespace impulse::test
{
namespace
{

constexpr Real kG = 9.81;
constexpr Real kTheta = 20.0 * std::numbers::pi / 180.0;
constexpr Real kRadius = 0.1;
constexpr Real kMass = 2.0;

// A ball of radius 0.1 m and 2 kg resting on a 20 degree incline (mu 0.5, far above the 0.15 the
// shell needs to roll), with `inertia` the scene's field for it or empty for the shape's own.
io::Scene ballOnIncline(const std::string& inertia)
{
    const Vec3 normal(std::sin(kTheta), 0.0, std::cos(kTheta));
    const Vec3 centre = kRadius * normal;
    std::ostringstream text;
    text.precision(17);
    text << R"({"dt": 0.001, "duration": 1.0, "gravity": [0, 0, -9.81],
        "materials": {"m": {"restitution": 0.0, "friction": 0.5}},
        "bodies": [{"static": true, "shape": {"type": "plane", "normal": [)"
         << normal.x() << ", 0, " << normal.z() << R"(], "offset": 0}, "material": "m"},
            {"shape": {"type": "sphere", "radius": 0.1}, "material": "m", "mass": 2.0, )";
    if (!inertia.empty())
    {
        text << "\"inertia\": " << inertia << ", ";
    }
    text << "\"position\": [" << centre.x() << ", 0, " << centre.z() << "]}]}";
    return io::parseScene(text.str(), "incline.json");
}

// The speed down the incline after one second, from rest.
Real speedAfterOneSecond(io::Scene scene)
{
    for (int k = 0; k < 1000; ++k)
    {
        scene.world.step(scene.options);
    }
    const Vec3 downhill(std::cos(kTheta), 0.0, -std::sin(kTheta));
    return scene.world.state(scene.dynamicBodies.at(0)).linearVelocity.dot(downhill);
}

TEST(ExplicitInertia, AShellRollsDownAnInclineAtThreeFifthsOfGSinThetaWhereASolidBallRollsAtFiveSevenths)
{
    const Real solid = speedAfterOneSecond(ballOnIncline(""));
    const Real shellMoment = 2.0 / 3.0 * kMass * kRadius * kRadius;
    std::ostringstream shellInertia;
    shellInertia.precision(17);
    shellInertia << "[" << shellMoment << ", " << shellMoment << ", " << shellMoment << "]";
    const Real shell = speedAfterOneSecond(ballOnIncline(shellInertia.str()));
    // rolling without slipping from the first step: the speed is a t to the contact solve's tolerance
    // (the two differ by 16 %)
    EXPECT_NEAR(solid, 5.0 / 7.0 * kG * std::sin(kTheta), 1e-4 * solid);
    EXPECT_NEAR(shell, 3.0 / 5.0 * kG * std::sin(kTheta), 1e-4 * shell);
}

} // namespace
} // namespace impulse::test
