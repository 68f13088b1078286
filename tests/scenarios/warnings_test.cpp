// SPDX-License-Identifier: MIT
// Warnings for legal input that gives a poor simulation, and the refusal of bodies smaller than the
// step's length tolerances serve (docs/warnings.md): each warning fires on the case it is for and
// names what it found, none fires on a reference scene, and a body the tolerances serve rests where
// physics puts it.
#include "support/scene_run.hpp"

#include <impulse/impulse.hpp>
#include <impulse/io/scene.hpp>

#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <iterator>
#include <stdexcept>
#include <string>
#include <vector>

namespace impulse::test
{
namespace
{

std::vector<Warning> warningsOf(const io::Scene& scene)
{
    return scene.world.warnings(scene.options, scene.bodyNames);
}

std::string listed(const std::vector<Warning>& warnings)
{
    std::string text;
    for (const Warning& warning : warnings)
    {
        text += "\n  " + warning.message;
    }
    return text;
}

std::vector<Warning> ofKind(const std::vector<Warning>& warnings, Warning::Kind kind)
{
    std::vector<Warning> found;
    std::copy_if(warnings.begin(), warnings.end(), std::back_inserter(found),
                 [&](const Warning& warning) { return warning.kind == kind; });
    return found;
}

bool mentions(const Warning& warning, const std::string& text)
{
    return warning.message.find(text) != std::string::npos;
}

// A scene of a ground and the given bodies, all of one material.
io::Scene sceneOf(const std::string& bodies, const std::string& solver = "{}")
{
    return io::parseScene(R"({"dt": 0.001, "duration": 1, "solver": )" + solver +
                              R"(, "materials": {"m": {"restitution": 0.5, "friction": 0.5}}, "bodies": [
                              {"name": "ground", "static": true, "shape": {"type": "plane", "normal": [0, 0, 1]},
                               "material": "m"}, )" +
                              bodies + "]}",
                          "test.json");
}

TEST(Warnings, NoReferenceSceneWarns)
{
    int scenes = 0;
    for (const auto& entry : std::filesystem::directory_iterator(IMPULSE_SCENES_DIR))
    {
        if (entry.path().extension() != ".json")
        {
            continue;
        }
        const io::Scene scene = io::loadScene(entry.path());
        EXPECT_TRUE(warningsOf(scene).empty()) << entry.path().filename() << listed(warningsOf(scene));
        ++scenes;
    }
    EXPECT_GE(scenes, 30);
}

TEST(Warnings, NoReferenceSceneTheTestsRunAtTenMillisecondsWarns)
{
    // the stacks and the scenes of ReferenceScenes/TenMillisecondStep, at the step those tests take
    for (const char* name :
         {"box_stack_10", "box_stack_50", "ball_drop_elastic", "ball_drop_damped", "ball_ball_headon",
          "ball_ball_oblique", "spin_friction", "incline_stick", "incline_slide", "newton_cradle"})
    {
        io::Scene scene = loadReferenceScene(name);
        scene.options.dt = 1e-2;
        EXPECT_TRUE(warningsOf(scene).empty()) << name << listed(warningsOf(scene));
    }
}

TEST(Warnings, AOneSecondStepOnTheElasticBallDropWarnsAndSaysWhatStepServes)
{
    io::Scene scene = loadReferenceScene("ball_drop_elastic");
    scene.options.dt = 1.0;
    const std::vector<Warning> warnings = warningsOf(scene);
    ASSERT_EQ(warnings.size(), 1u) << listed(warnings);
    EXPECT_EQ(warnings[0].kind, Warning::Kind::LargeTimeStep);
    // g dt^2 = 9.81 m against the ball's radius of 0.1 m; dt <= sqrt(0.1 / (8 g)) = 0.0357 s
    EXPECT_TRUE(mentions(warnings[0], "dt = 1 s")) << warnings[0].message;
    EXPECT_TRUE(mentions(warnings[0], "9.81 m")) << warnings[0].message;
    EXPECT_TRUE(mentions(warnings[0], "\"ball\"")) << warnings[0].message;
    EXPECT_TRUE(mentions(warnings[0], "dt <= 0.0357 s")) << warnings[0].message;

    // why: at that step the ball never falls at all, it hangs where it was dropped
    runScene(
        scene, 1.0, [](Real, const World&) {}, 5.0);
    EXPECT_NEAR(scene.world.state(scene.dynamicBodies[0]).position.z(), 2.0, 1e-9);

    // the step it recommends does not warn
    io::Scene fine = loadReferenceScene("ball_drop_elastic");
    fine.options.dt = 0.035;
    EXPECT_TRUE(warningsOf(fine).empty()) << listed(warningsOf(fine));
}

TEST(Warnings, ABodyFasterThanHalfTheSmallestSizePerStepWarnsNamingIt)
{
    // 300 m/s at dt = 1 ms is 0.3 m a step, past the 0.05 m a thin plate is thick
    const std::string bodies = R"({"name": "plate", "static": true, "shape": {"type": "box",
                                   "half_extents": [1, 1, 0.05]}, "position": [0, 0, 1], "material": "m"},
                                  {"shape": {"type": "sphere", "radius": 0.1}, "mass": 1, "position": [0, 0, 3],
                                   "velocity": [0, 0, -300], "material": "m"})";
    const std::vector<Warning> warnings = warningsOf(sceneOf(bodies));
    ASSERT_EQ(warnings.size(), 1u) << listed(warnings);
    EXPECT_EQ(warnings[0].kind, Warning::Kind::FastBody);
    EXPECT_TRUE(mentions(warnings[0], "body 2")) << warnings[0].message;
    EXPECT_TRUE(mentions(warnings[0], "\"plate\" (0.05 m")) << warnings[0].message;
    EXPECT_TRUE(mentions(warnings[0], "dt <= 8.33e-05 s")) << warnings[0].message;

    // spin counts at the bounding radius: 2000 rad/s at 0.1 m is 200 m/s
    const std::string spinning = R"({"shape": {"type": "sphere", "radius": 0.1}, "mass": 1, "position": [0, 0, 3],
                                     "angular_velocity": [0, 2000, 0], "material": "m"})";
    EXPECT_EQ(ofKind(warningsOf(sceneOf(spinning)), Warning::Kind::FastBody).size(), 1u);
    const std::string slow = R"({"shape": {"type": "sphere", "radius": 0.1}, "mass": 1, "position": [0, 0, 3],
                                 "velocity": [0, 0, -40], "material": "m"})";
    EXPECT_TRUE(warningsOf(sceneOf(slow)).empty()) << listed(warningsOf(sceneOf(slow)));
}

TEST(Warnings, TheIssuesNanometreSphereIsRefusedWithTheFieldAndTheLimit)
{
    // with an absolute contact thickness of 1e-6 m it would rest 1000 radii above the ground
    const std::string speck = R"({"shape": {"type": "sphere", "radius": 1e-9}, "mass": 1e-24,
                                  "position": [0, 0, 3e-9], "material": "m"})";
    try
    {
        sceneOf(speck);
        FAIL() << "a sphere of radius 1e-9 m was accepted";
    }
    catch (const io::SceneError& error)
    {
        const std::string what = error.what();
        EXPECT_NE(what.find("test.json: /bodies/1/shape/radius: "), std::string::npos) << what;
        EXPECT_NE(what.find("1e-09 m"), std::string::npos) << what;
        EXPECT_NE(what.find("no options serve a body under 1e-08 m"), std::string::npos) << what;
    }
}

TEST(Warnings, ABodyBelowTheDefaultTolerancesIsRefusedNamingTheTolerance)
{
    const std::string bead = R"({"shape": {"type": "box", "half_extents": [1e-3, 1e-3, 5e-4]}, "mass": 1e-5,
                                 "position": [0, 0, 5e-4], "material": "m"})";
    try
    {
        sceneOf(bead);
        FAIL() << "a box 0.5 mm at its thinnest half extent was accepted with the default tolerances";
    }
    catch (const io::SceneError& error)
    {
        const std::string what = error.what();
        EXPECT_NE(what.find("/bodies/1/shape/half_extents: "), std::string::npos) << what;
        EXPECT_NE(what.find("below the 0.001 m"), std::string::npos) << what;
        EXPECT_NE(what.find("push_out_allowance (0.0001 m) is more than a tenth"), std::string::npos) << what;
        EXPECT_NE(what.find("at most 5e-05 m"), std::string::npos) << what;
    }
    // the same box with tolerances that serve it loads and warns of nothing
    EXPECT_TRUE(warningsOf(sceneOf(bead, R"({"push_out_allowance": 5e-6})")).empty());
    // and with push-out off the allowance does not count
    EXPECT_NO_THROW(sceneOf(bead, R"({"push_out": false})"));
}

TEST(Warnings, TheApiRefusesToStepABodyTheTolerancesDoNotServe)
{
    World world;
    const MaterialId material = world.createMaterial({});
    world.createBody({.type = BodyType::Static, .shape = Plane{}, .material = material});
    const BodyId speck =
        world.createBody({.shape = Sphere{1e-5}, .material = material, .mass = 1e-11, .position = {0, 0, 2e-5}});
    try
    {
        world.step({});
        FAIL() << "stepped a sphere of radius 1e-5 m with a push-out allowance of 1e-4 m";
    }
    catch (const std::invalid_argument& error)
    {
        const std::string what = error.what();
        EXPECT_EQ(what.rfind("size: body 1: ", 0), 0u) << what;
        EXPECT_NE(what.find("push_out_allowance (0.0001 m)"), std::string::npos) << what;
    }
    EXPECT_EQ(world.time(), 0.0);
    EXPECT_NE(sizeRefusal(1e-5, {}), "");
    EXPECT_DOUBLE_EQ(smallestServedSize({}), 1e-3);
    // with tolerances a tenth of it at most, it steps; removing it lifts the refusal as well
    EXPECT_NO_THROW(world.step({.dt = 1e-4, .contactThickness = 1e-7, .pushOutAllowance = 1e-6}));
    world.removeBody(speck);
    EXPECT_NO_THROW(world.step({}));
}

TEST(Warnings, ASphereTheTolerancesServeRestsWithinAPercentOfItsRadius)
{
    // half a millimetre, with the push-out allowance a hundredth of it: nothing to warn of, and it
    // settles on the ground within 1 % of its radius (at the default tolerances of a metre-sized scene
    // it would be refused, and the nanometre sphere of the issue hung 1000 radii up)
    const Real radius = 5e-4;
    io::Scene scene = sceneOf(R"({"name": "bead", "shape": {"type": "sphere", "radius": 5e-4}, "density": 1000,
                    "position": [0, 0, 2e-3], "material": "m"})",
                              R"({"push_out_allowance": 5e-6})");
    EXPECT_TRUE(warningsOf(scene).empty()) << listed(warningsOf(scene));
    runScene(
        scene, -1.0, [](Real, const World&) {}, 0.5);
    const BodyState s = scene.world.state(scene.dynamicBodies[0]);
    EXPECT_NEAR(s.position.z(), radius, 0.01 * radius);
    EXPECT_LT(s.linearVelocity.norm(), 1e-6);
}

TEST(Warnings, ABodyNearTheSmallestServedSizeWarnsWithWhatToSet)
{
    const std::string marble = R"({"name": "marble", "shape": {"type": "sphere", "radius": 5e-3}, "mass": 1e-3,
                                   "position": [0, 0, 5e-3], "material": "m"})";
    const std::vector<Warning> warnings = warningsOf(sceneOf(marble));
    ASSERT_EQ(warnings.size(), 1u) << listed(warnings);
    EXPECT_EQ(warnings[0].kind, Warning::Kind::SmallBody);
    EXPECT_TRUE(mentions(warnings[0], "\"marble\"")) << warnings[0].message;
    EXPECT_TRUE(mentions(warnings[0], "push_out_allowance (0.0001 m) is 2 %")) << warnings[0].message;
    EXPECT_TRUE(mentions(warnings[0], "at most 5e-05 m")) << warnings[0].message;
    EXPECT_TRUE(warningsOf(sceneOf(marble, R"({"push_out_allowance": 5e-5})")).empty());
    // the contact thickness is weighed the same way once the allowance is out of the way
    const std::vector<Warning> thick = warningsOf(sceneOf(marble, R"({"push_out": false, "contact_thickness": 1e-4})"));
    ASSERT_EQ(thick.size(), 1u) << listed(thick);
    EXPECT_TRUE(mentions(thick[0], "contact_thickness (0.0001 m)")) << thick[0].message;
}

TEST(Warnings, BodiesOverlappingAtTheStartAreNamedWithTheDepth)
{
    const std::string overlapping = R"({"name": "left", "shape": {"type": "box", "half_extents": [0.1, 0.1, 0.1]},
                                        "mass": 1, "position": [0, 0, 0.1], "material": "m"},
                                       {"shape": {"type": "box", "half_extents": [0.1, 0.1, 0.1]}, "mass": 1,
                                        "position": [0.18, 0, 0.1], "material": "m"})";
    const std::vector<Warning> warnings = warningsOf(sceneOf(overlapping));
    ASSERT_EQ(warnings.size(), 1u) << listed(warnings);
    EXPECT_EQ(warnings[0].kind, Warning::Kind::InitialOverlap);
    EXPECT_TRUE(mentions(warnings[0], "\"left\" and body 2 overlap by 0.02 m")) << warnings[0].message;
    EXPECT_TRUE(mentions(warnings[0], "push-out will part them at up to 10 m/s")) << warnings[0].message;

    // within the push-out allowance the overlap stays, and the warning says so
    const std::string shallow = R"({"name": "sunk", "shape": {"type": "sphere", "radius": 0.1}, "mass": 1,
                                    "position": [0, 0, 0.09995], "material": "m"})";
    const std::vector<Warning> stays = warningsOf(sceneOf(shallow));
    ASSERT_EQ(stays.size(), 1u) << listed(stays);
    EXPECT_TRUE(mentions(stays[0], "\"ground\" and \"sunk\" overlap by 5e-05 m")) << stays[0].message;
    EXPECT_TRUE(mentions(stays[0], "within the push-out allowance")) << stays[0].message;

    // no deeper than the contact thickness is touching, not overlapping
    const std::string touching = R"({"shape": {"type": "sphere", "radius": 0.1}, "mass": 1,
                                     "position": [0, 0, 0.0999995], "material": "m"})";
    EXPECT_TRUE(warningsOf(sceneOf(touching)).empty());
}

TEST(Warnings, OverlapsOfPairsThatDoNotCollideAreNoneAndManyAreCounted)
{
    World world(WorldDef{.gravity = Vec3::Zero()});
    const MaterialId material = world.createMaterial({});
    std::vector<BodyId> balls;
    for (int k = 0; k < 8; ++k)
    {
        // a row of balls each 1 cm into the next: seven overlapping pairs
        balls.push_back(world.createBody(
            {.shape = Sphere{0.1}, .material = material, .mass = 1.0, .position = {0.19 * k, 0.0, 0.0}}));
    }
    const std::vector<Warning> warnings = world.warnings({});
    ASSERT_EQ(warnings.size(), 6u) << listed(warnings);
    // the deepest first: all are 0.01 m, to round-off
    for (std::size_t k = 0; k < 5; ++k)
    {
        EXPECT_EQ(warnings[k].kind, Warning::Kind::InitialOverlap);
        EXPECT_TRUE(mentions(warnings[k], " overlap by 0.01 m")) << warnings[k].message;
    }
    EXPECT_TRUE(mentions(warnings[5], "2 more pairs overlap")) << warnings[5].message;
    for (std::size_t k = 0; k + 1 < balls.size(); ++k)
    {
        world.setCollisionEnabled(balls[k], balls[k + 1], false);
    }
    EXPECT_TRUE(world.warnings({}).empty()) << listed(world.warnings({}));
}

TEST(Warnings, MassesThatCanTouchTenThousandTimesApartWarn)
{
    const auto scene = [](Real heavy, const std::string& solver = "{}")
    {
        return sceneOf(R"({"name": "feather", "shape": {"type": "box", "half_extents": [0.1, 0.1, 0.1]},
                           "mass": 0.01, "position": [0, 0, 0.1], "material": "m"},
                          {"name": "anvil", "shape": {"type": "box", "half_extents": [0.1, 0.1, 0.1]},
                           "mass": )" +
                           std::to_string(heavy) + R"(, "position": [0, 0, 0.3], "material": "m"})",
                       solver);
    };
    const std::vector<Warning> warnings = warningsOf(scene(1000.0));
    ASSERT_EQ(warnings.size(), 1u) << listed(warnings);
    EXPECT_EQ(warnings[0].kind, Warning::Kind::MassRatio);
    EXPECT_TRUE(mentions(warnings[0], "\"anvil\" (1e+03 kg) is 1e+05 times as heavy as \"feather\" (0.01 kg)"))
        << warnings[0].message;
    EXPECT_TRUE(warningsOf(scene(99.0)).empty()); // 9900 times: heavy_on_light has a thousand

    // bodies that cannot touch may differ as they like
    io::Scene apart = scene(1000.0);
    apart.world.setCollisionEnabled(apart.dynamicBodies[0], apart.dynamicBodies[1], false);
    EXPECT_TRUE(warningsOf(apart).empty()) << listed(warningsOf(apart));
}

TEST(Warnings, CoordinatesWhoseRoundOffNearsTheContactThicknessWarn)
{
    // 2.2e-16 of 1e8 m is 2.2e-8 m, 2 % of the contact thickness; 1e7 m is within the hundredth
    const auto at = [](const std::string& x)
    {
        return sceneOf(R"({"name": "far", "shape": {"type": "sphere", "radius": 0.1}, "mass": 1,
                           "position": [)" +
                       x + R"(, 0, 1], "material": "m"})");
    };
    const std::vector<Warning> warnings = warningsOf(at("1e8"));
    ASSERT_EQ(warnings.size(), 1u) << listed(warnings);
    EXPECT_EQ(warnings[0].kind, Warning::Kind::FarFromOrigin);
    EXPECT_TRUE(mentions(warnings[0], "\"far\" reaches 1e+08 m from the origin")) << warnings[0].message;
    EXPECT_TRUE(mentions(warnings[0], "within 4.5e+07 m")) << warnings[0].message;
    EXPECT_TRUE(warningsOf(at("1e7")).empty()) << listed(warningsOf(at("1e7")));
}

} // namespace
} // namespace impulse::test
