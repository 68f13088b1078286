// SPDX-License-Identifier: MIT
// The scene loader's contract: every malformed or incomplete scene is refused with io::SceneError
// whose message reads "<source>: <JSON pointer of the field>: <what is wrong>", and a valid scene
// becomes exactly the world it describes. Every bad case below is one edit of the same valid base
// scene, so each test shows the single thing that makes a scene unusable.
#include "geometry/mesh_queries.hpp"

#include <impulse/io/scene.hpp>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <numbers>
#include <stdexcept>
#include <string>

namespace
{

using impulse::BodyId;
using impulse::MaterialId;
using impulse::Quat;
using impulse::Vec3;
using impulse::io::parseScene;
using impulse::io::SceneError;

// The base scene in three parts, so that whole sections can be dropped or replaced. Each part but
// the first starts with its own comma; every line that a test edits is unique in the text.
// Materials are named "a" and "b" so that file order and alphabetical order agree: the loader
// creates them in one of those orders, hence "a" is MaterialId 0 and "b" is MaterialId 1.
const std::string kTop = R"({
    "name": "base",
    "description": "one static plane, one sphere, one box",
    "gravity": [0, 0, -9.81],
    "dt": 0.001,
    "duration": 1.0,
    "solver": {"collision_iterations": 5, "contact_iterations": 10})";

const std::string kMaterials = R"(,
    "materials": {
        "a": {"restitution": 0.2, "friction": 0.4},
        "b": {"restitution": 0.6, "friction": 0.9}
    })";

const std::string kBodies = R"(,
    "bodies": [
        {
            "name": "ground",
            "static": true,
            "shape": {"type": "plane", "normal": [0, 0, 1], "offset": 0},
            "material": "a"
        },
        {
            "name": "ball",
            "shape": {"type": "sphere", "radius": 0.1},
            "material": "b",
            "mass": 2.0,
            "position": [0, 0, 1],
            "velocity": [0.5, 0, 0]
        },
        {
            "name": "crate",
            "shape": {"type": "box", "half_extents": [0.1, 0.2, 0.3]},
            "material": "a",
            "density": 500,
            "position": [1, 0, 0.3],
            "orientation": [1, 0, 0, 0],
            "angular_velocity": [0, 0, 1]
        }
    ])";

const std::string kEnd = "\n}\n";

/// The valid base scene, with `extra` (e.g. a "pairs" section starting with a comma) inserted
/// between the materials and the bodies.
std::string baseScene(const std::string& extra = "")
{
    return kTop + kMaterials + extra + kBodies + kEnd;
}

/// A "pairs" section with one override, to pass to baseScene().
std::string pairs(const std::string& entry)
{
    return ",\n    \"pairs\": [" + entry + "]";
}

/// `text` with the one occurrence of `from` replaced by `to`. Throws (and so fails the test) if
/// `from` does not occur exactly once: an edit that silently misses would test nothing.
std::string edit(std::string text, const std::string& from, const std::string& to)
{
    const std::size_t at = text.find(from);
    if (at == std::string::npos || text.find(from, at + 1) != std::string::npos)
    {
        throw std::logic_error("test bug: \"" + from + "\" does not occur exactly once in the scene");
    }
    return text.replace(at, from.size(), to);
}

/// The base scene with the one occurrence of `from` replaced by `to`.
std::string edited(const std::string& from, const std::string& to)
{
    return edit(baseScene(), from, to);
}

/// The message of the SceneError that parsing `text` throws; fails the test if it throws nothing
/// or something else.
std::string refusal(const std::string& text)
{
    try
    {
        parseScene(text, "test.json");
    }
    catch (const SceneError& error)
    {
        return error.what();
    }
    catch (const std::exception& error)
    {
        ADD_FAILURE() << "expected io::SceneError, got another exception: " << error.what();
        return {};
    }
    catch (...)
    {
        ADD_FAILURE() << "expected io::SceneError, got a non-standard exception";
        return {};
    }
    ADD_FAILURE() << "the scene was accepted, expected io::SceneError";
    return {};
}

bool contains(const std::string& text, const std::string& part)
{
    return text.find(part) != std::string::npos;
}

/// The scene is refused with a message that starts "test.json: <pointer>: " and names the problem.
void expectRefused(const std::string& text, const std::string& pointer, const std::string& word)
{
    const std::string message = refusal(text);
    if (message.empty())
    {
        return; // refusal() has reported what happened instead
    }
    const std::string prefix = "test.json: " + pointer + ": ";
    EXPECT_EQ(message.rfind(prefix, 0), 0u) << "message does not start with \"" << prefix << "\": " << message;
    EXPECT_TRUE(contains(message, word)) << "message does not say \"" << word << "\": " << message;
}

// ---- valid scenes ----------------------------------------------------------------------------

TEST(SceneLoader, BaseSceneIsValid)
{
    EXPECT_NO_THROW(parseScene(baseScene(), "test.json"));
}

TEST(SceneLoader, DynamicBodiesAreListedInFileOrder)
{
    const auto scene = parseScene(baseScene(), "test.json");
    EXPECT_EQ(scene.name, "base");
    EXPECT_DOUBLE_EQ(scene.options.dt, 0.001);
    EXPECT_DOUBLE_EQ(scene.duration, 1.0);
    ASSERT_EQ(scene.world.bodyCount(), 3u);
    EXPECT_FALSE(scene.world.isDynamic(BodyId{0}));
    ASSERT_EQ(scene.dynamicBodies.size(), 2u);
    EXPECT_EQ(scene.dynamicBodies[0], BodyId{1});
    EXPECT_EQ(scene.dynamicBodies[1], BodyId{2});
    ASSERT_EQ(scene.bodyNames.size(), 3u);
    EXPECT_EQ(scene.bodyNames[0], "ground");
    EXPECT_EQ(scene.bodyNames[1], "ball");
    EXPECT_EQ(scene.bodyNames[2], "crate");

    const auto ball = scene.world.state(scene.dynamicBodies[0]);
    EXPECT_EQ(ball.position, Vec3(0.0, 0.0, 1.0));
    EXPECT_EQ(ball.linearVelocity, Vec3(0.5, 0.0, 0.0));
    EXPECT_DOUBLE_EQ(scene.world.mass(scene.dynamicBodies[0]), 2.0);
    const auto crate = scene.world.state(scene.dynamicBodies[1]);
    EXPECT_EQ(crate.position, Vec3(1.0, 0.0, 0.3));
    EXPECT_EQ(crate.angularVelocity, Vec3(0.0, 0.0, 1.0));
    EXPECT_EQ(scene.world.gravity(), Vec3(0.0, 0.0, -9.81));
}

TEST(SceneLoader, SphereMassIsDensityTimesVolume)
{
    const auto scene = parseScene(edited(R"("mass": 2.0,)", R"("density": 7800,)"), "test.json");
    const double expected = 7800.0 * 4.0 / 3.0 * std::numbers::pi * 0.1 * 0.1 * 0.1;
    EXPECT_NEAR(scene.world.mass(scene.dynamicBodies[0]), expected, 1e-12 * expected);
}

TEST(SceneLoader, BoxMassIsDensityTimesVolume)
{
    const auto scene = parseScene(baseScene(), "test.json");
    const double expected = 500.0 * (0.2 * 0.4 * 0.6); // full edges are twice the half extents
    EXPECT_NEAR(scene.world.mass(scene.dynamicBodies[1]), expected, 1e-12 * expected);
}

TEST(SceneLoader, AxisAngleOrientationEqualsItsQuaternion)
{
    const auto scene =
        parseScene(edited(R"("orientation": [1, 0, 0, 0])", R"("orientation": {"axis": [0, 1, 0], "angle_deg": 20})"),
                   "test.json");
    const Quat q = scene.world.state(scene.dynamicBodies[1]).orientation;
    const double half = 10.0 * std::numbers::pi / 180.0;
    EXPECT_NEAR(q.w(), std::cos(half), 1e-12);
    EXPECT_NEAR(q.x(), 0.0, 1e-12);
    EXPECT_NEAR(q.y(), std::sin(half), 1e-12);
    EXPECT_NEAR(q.z(), 0.0, 1e-12);
}

TEST(SceneLoader, OrientationAxisNeedNotBeUnitLength)
{
    const auto scene =
        parseScene(edited(R"("orientation": [1, 0, 0, 0])", R"("orientation": {"axis": [0, 3, 0], "angle_deg": 20})"),
                   "test.json");
    const Quat q = scene.world.state(scene.dynamicBodies[1]).orientation;
    const double half = 10.0 * std::numbers::pi / 180.0;
    EXPECT_NEAR(q.w(), std::cos(half), 1e-12);
    EXPECT_NEAR(q.y(), std::sin(half), 1e-12);
}

TEST(SceneLoader, QuaternionOrientationIsNormalised)
{
    const auto scene =
        parseScene(edited(R"("orientation": [1, 0, 0, 0])", R"("orientation": [2, 0, 0, 2])"), "test.json");
    const Quat q = scene.world.state(scene.dynamicBodies[1]).orientation;
    EXPECT_NEAR(q.w(), std::sqrt(0.5), 1e-12);
    EXPECT_NEAR(q.z(), std::sqrt(0.5), 1e-12);
    EXPECT_NEAR(q.norm(), 1.0, 1e-15);
}

TEST(SceneLoader, PairOverrideReplacesTheDefaultRuleInEitherOrder)
{
    const auto scene =
        parseScene(baseScene(pairs(R"({"materials": ["a", "b"], "restitution": 0.05, "friction": 0.7})")), "test.json");
    const MaterialId a{0};
    const MaterialId b{1};
    const auto ab = scene.world.pairCoefficients(a, b);
    EXPECT_DOUBLE_EQ(ab.restitution, 0.05);
    EXPECT_DOUBLE_EQ(ab.friction, 0.7);
    const auto ba = scene.world.pairCoefficients(b, a);
    EXPECT_DOUBLE_EQ(ba.restitution, 0.05);
    EXPECT_DOUBLE_EQ(ba.friction, 0.7);
    // pairs that are not overridden keep the default rule
    const auto aa = scene.world.pairCoefficients(a, a);
    EXPECT_DOUBLE_EQ(aa.restitution, 0.2);
    EXPECT_DOUBLE_EQ(aa.friction, 0.4);
}

TEST(SceneLoader, DefaultPairRuleIsMaxRestitutionAndGeometricMeanFriction)
{
    const auto scene = parseScene(baseScene(), "test.json");
    const auto ab = scene.world.pairCoefficients(MaterialId{0}, MaterialId{1});
    EXPECT_DOUBLE_EQ(ab.restitution, std::max(0.2, 0.6));
    EXPECT_DOUBLE_EQ(ab.friction, std::sqrt(0.4 * 0.9));
    const auto bb = scene.world.pairCoefficients(MaterialId{1}, MaterialId{1});
    EXPECT_DOUBLE_EQ(bb.restitution, 0.6);
    EXPECT_DOUBLE_EQ(bb.friction, 0.9);
}

TEST(SceneLoader, EveryShippedSceneLoads)
{
    int count = 0;
    for (const auto& entry : std::filesystem::directory_iterator(IMPULSE_SCENES_DIR))
    {
        if (entry.path().extension() != ".json")
        {
            continue;
        }
        ++count;
        try
        {
            const auto scene = impulse::io::loadScene(entry.path());
            EXPECT_FALSE(scene.dynamicBodies.empty()) << entry.path();
            EXPECT_GT(scene.duration, 0.0) << entry.path();
        }
        catch (const SceneError& error)
        {
            ADD_FAILURE() << error.what();
        }
    }
    EXPECT_GT(count, 0) << "no scene files in " << IMPULSE_SCENES_DIR;
}

// ---- files and syntax ------------------------------------------------------------------------

TEST(SceneLoader, MissingFileIsRefusedAsCannotOpen)
{
    const std::filesystem::path path = std::filesystem::path(IMPULSE_SCENES_DIR) / "no_such_scene.json";
    try
    {
        impulse::io::loadScene(path);
        ADD_FAILURE() << "a missing file was loaded";
    }
    catch (const SceneError& error)
    {
        const std::string message = error.what();
        EXPECT_EQ(message.rfind(path.string() + ": ", 0), 0u) << message;
        EXPECT_TRUE(contains(message, "cannot open")) << message;
    }
}

TEST(SceneLoader, SyntaxErrorIsRefusedAsNotJsonWithItsLine)
{
    // a missing colon on line 5
    const std::string message = refusal(edited(R"("dt": 0.001,)", R"("dt" 0.001,)"));
    ASSERT_FALSE(message.empty()) << "no io::SceneError, see above";
    EXPECT_EQ(message.rfind("test.json: ", 0), 0u) << message;
    EXPECT_TRUE(contains(message, "not valid JSON")) << message;
    EXPECT_TRUE(contains(message, "line 5")) << message;
}

TEST(SceneLoader, EmptyTextIsRefusedAsNotJson)
{
    const std::string message = refusal("");
    ASSERT_FALSE(message.empty()) << "no io::SceneError, see above";
    EXPECT_EQ(message.rfind("test.json: ", 0), 0u) << message;
    EXPECT_TRUE(contains(message, "not valid JSON")) << message;
}

TEST(SceneLoader, NanLiteralIsRefusedAsNotJson)
{
    const std::string message = refusal(edited(R"("radius": 0.1)", R"("radius": NaN)"));
    ASSERT_FALSE(message.empty()) << "no io::SceneError, see above";
    EXPECT_EQ(message.rfind("test.json: ", 0), 0u) << message;
    EXPECT_TRUE(contains(message, "not valid JSON")) << message;
}

TEST(SceneLoader, OverflowingNumberIsRefusedAsNotFinite)
{
    // 1e999 is valid JSON syntax but no double: it must be refused as a SceneError that says what
    // is wrong, not escape as a JSON-library exception (which aborts the command-line tool).
    const std::string message = refusal(edited(R"("radius": 0.1)", R"("radius": 1e999)"));
    ASSERT_FALSE(message.empty()) << "no io::SceneError, see above";
    EXPECT_EQ(message.rfind("test.json: ", 0), 0u) << message;
    EXPECT_TRUE(contains(message, "finite") || contains(message, "1e999") || contains(message, "overflow")) << message;
}

TEST(SceneLoader, RootThatIsNotAnObjectIsRefused)
{
    expectRefused("[1, 2, 3]", "/", "object");
}

// ---- missing required fields -----------------------------------------------------------------

TEST(SceneLoader, MissingDtIsRefusedWithItsPath)
{
    expectRefused(edited(R"("dt": 0.001,)", ""), "/dt", "missing");
}

TEST(SceneLoader, MissingDurationIsRefusedWithItsPath)
{
    expectRefused(edited(R"("duration": 1.0,)", ""), "/duration", "missing");
}

TEST(SceneLoader, MissingMaterialsIsRefusedWithItsPath)
{
    expectRefused(kTop + kBodies + kEnd, "/materials", "missing");
}

TEST(SceneLoader, MissingBodiesIsRefusedWithItsPath)
{
    expectRefused(kTop + kMaterials + kEnd, "/bodies", "missing");
}

TEST(SceneLoader, MissingShapeIsRefusedWithItsPath)
{
    expectRefused(edited(R"("shape": {"type": "sphere", "radius": 0.1},)", ""), "/bodies/1/shape", "missing");
}

TEST(SceneLoader, MissingMaterialIsRefusedWithItsPath)
{
    expectRefused(edited(R"("material": "b",)", ""), "/bodies/1/material", "missing");
}

TEST(SceneLoader, MissingShapeTypeIsRefusedWithItsPath)
{
    expectRefused(edited(R"({"type": "sphere", "radius": 0.1})", R"({"radius": 0.1})"), "/bodies/1/shape/type",
                  "missing");
}

TEST(SceneLoader, MissingRadiusIsRefusedWithItsPath)
{
    expectRefused(edited(R"({"type": "sphere", "radius": 0.1})", R"({"type": "sphere"})"), "/bodies/1/shape/radius",
                  "missing");
}

TEST(SceneLoader, DynamicBodyWithoutMassOrDensityIsRefusedWithItsPath)
{
    const std::string text = edited(R"("mass": 2.0,)", "");
    expectRefused(text, "/bodies/1", "mass");
    expectRefused(text, "/bodies/1", "density");
}

// ---- wrong types -----------------------------------------------------------------------------

TEST(SceneLoader, StringWhereNumberIsExpectedIsRefusedWithItsPath)
{
    expectRefused(edited(R"("radius": 0.1)", R"("radius": "0.1")"), "/bodies/1/shape/radius", "number");
}

TEST(SceneLoader, NumberWhereVectorIsExpectedIsRefusedWithItsPath)
{
    expectRefused(edited(R"("gravity": [0, 0, -9.81],)", R"("gravity": -9.81,)"), "/gravity", "array");
}

TEST(SceneLoader, NumberWhereBodiesArrayIsExpectedIsRefusedWithItsPath)
{
    expectRefused(kTop + kMaterials + ",\n    \"bodies\": 5" + kEnd, "/bodies", "array");
}

TEST(SceneLoader, VectorOfTwoIsRefusedWithItsPath)
{
    expectRefused(edited(R"("position": [0, 0, 1],)", R"("position": [0, 1],)"), "/bodies/1/position", "3");
}

// ---- values out of range ---------------------------------------------------------------------

TEST(SceneLoader, NegativeRadiusIsRefusedWithItsPath)
{
    expectRefused(edited(R"("radius": 0.1)", R"("radius": -0.1)"), "/bodies/1/shape/radius", "positive");
}

TEST(SceneLoader, ZeroRadiusIsRefusedWithItsPath)
{
    expectRefused(edited(R"("radius": 0.1)", R"("radius": 0)"), "/bodies/1/shape/radius", "positive");
}

TEST(SceneLoader, ZeroMassIsRefusedWithItsPath)
{
    expectRefused(edited(R"("mass": 2.0,)", R"("mass": 0,)"), "/bodies/1/mass", "positive");
}

TEST(SceneLoader, NegativeMassIsRefusedWithItsPath)
{
    expectRefused(edited(R"("mass": 2.0,)", R"("mass": -2.0,)"), "/bodies/1/mass", "positive");
}

TEST(SceneLoader, NegativeDensityIsRefusedWithItsPath)
{
    expectRefused(edited(R"("density": 500,)", R"("density": -500,)"), "/bodies/2/density", "positive");
}

TEST(SceneLoader, ZeroHalfExtentIsRefusedWithItsPath)
{
    expectRefused(edited(R"("half_extents": [0.1, 0.2, 0.3])", R"("half_extents": [0.1, 0, 0.3])"),
                  "/bodies/2/shape/half_extents/1", "positive");
}

TEST(SceneLoader, ZeroPlaneNormalIsRefusedWithItsPath)
{
    expectRefused(edited(R"("normal": [0, 0, 1])", R"("normal": [0, 0, 0])"), "/bodies/0/shape/normal", "zero");
}

TEST(SceneLoader, ZeroQuaternionIsRefusedWithItsPath)
{
    expectRefused(edited(R"("orientation": [1, 0, 0, 0])", R"("orientation": [0, 0, 0, 0])"), "/bodies/2/orientation",
                  "zero");
}

TEST(SceneLoader, RestitutionAboveOneIsRefusedWithItsPath)
{
    expectRefused(edited(R"("restitution": 0.2)", R"("restitution": 1.5)"), "/materials/a/restitution", "[0, 1]");
}

TEST(SceneLoader, NegativeRestitutionIsRefusedWithItsPath)
{
    expectRefused(edited(R"("restitution": 0.6)", R"("restitution": -0.1)"), "/materials/b/restitution", "[0, 1]");
}

TEST(SceneLoader, NegativeFrictionIsRefusedWithItsPath)
{
    expectRefused(edited(R"("friction": 0.4)", R"("friction": -0.4)"), "/materials/a/friction", "negative");
}

TEST(SceneLoader, ZeroDtIsRefusedWithItsPath)
{
    expectRefused(edited(R"("dt": 0.001,)", R"("dt": 0,)"), "/dt", "positive");
}

TEST(SceneLoader, EmptyBodiesArrayIsRefusedWithItsPath)
{
    expectRefused(kTop + kMaterials + ",\n    \"bodies\": []" + kEnd, "/bodies", "at least one");
}

TEST(SceneLoader, PairOverrideWithRestitutionAboveOneIsRefusedWithItsPath)
{
    expectRefused(baseScene(pairs(R"({"materials": ["a", "b"], "restitution": 2, "friction": 0.7})")),
                  "/pairs/0/restitution", "[0, 1]");
}

// ---- names and fields that do not exist ------------------------------------------------------

TEST(SceneLoader, UnknownShapeTypeIsRefusedWithItsPath)
{
    const std::string text = edited(R"("type": "sphere")", R"("type": "cylinder")");
    expectRefused(text, "/bodies/1/shape/type", "unknown");
    expectRefused(text, "/bodies/1/shape/type", "cylinder");
}

TEST(SceneLoader, UnknownMaterialNameIsRefusedWithItsPath)
{
    const std::string text = edited(R"("material": "b",)", R"("material": "steel",)");
    expectRefused(text, "/bodies/1/material", "unknown");
    expectRefused(text, "/bodies/1/material", "steel");
}

TEST(SceneLoader, UnknownMaterialInPairOverrideIsRefusedWithItsPath)
{
    expectRefused(baseScene(pairs(R"({"materials": ["a", "steel"], "restitution": 0.5, "friction": 0.7})")),
                  "/pairs/0/materials/1", "unknown");
}

TEST(SceneLoader, PushOutSettingsAreRead)
{
    const impulse::io::Scene scene =
        parseScene(edited(R"("contact_iterations": 10})",
                          R"("contact_iterations": 10, "push_out": false, "push_out_allowance": 2e-4,
                   "push_out_speed": 3, "push_out_iterations": 4})"),
                   "test.json");
    EXPECT_FALSE(scene.options.pushOut);
    EXPECT_EQ(scene.options.pushOutAllowance, 2e-4);
    EXPECT_EQ(scene.options.pushOutSpeed, 3.0);
    EXPECT_EQ(scene.options.pushOutIterations, 4);
}

TEST(SceneLoader, NegativePushOutSpeedIsRefusedWithItsPath)
{
    expectRefused(edited(R"("contact_iterations": 10})", R"("contact_iterations": 10, "push_out_speed": -1})"),
                  "/solver/push_out_speed", "must not be negative");
}

TEST(SceneLoader, RestingApproachIsReadAndANegativeOneRefusedWithItsPath)
{
    EXPECT_EQ(parseScene(edited(R"("contact_iterations": 10})", R"("contact_iterations": 10, "resting_approach": 0})"),
                         "test.json")
                  .options.restingApproach,
              0.0);
    expectRefused(edited(R"("contact_iterations": 10})", R"("contact_iterations": 10, "resting_approach": -1})"),
                  "/solver/resting_approach", "must not be negative");
}

TEST(SceneLoader, MisspeltFieldIsRefusedWithItsPath)
{
    expectRefused(edited(R"("position": [0, 0, 1],)", R"("positon": [0, 0, 1],)"), "/bodies/1/positon", "unknown");
}

TEST(SceneLoader, FieldOfAnotherShapeIsRefusedWithItsPath)
{
    expectRefused(
        edited(R"({"type": "sphere", "radius": 0.1})", R"({"type": "sphere", "radius": 0.1, "normal": [0, 0, 1]})"),
        "/bodies/1/shape/normal", "unknown");
}

// ---- static and dynamic bodies ---------------------------------------------------------------

TEST(SceneLoader, DynamicPlaneIsRefusedWithItsPath)
{
    expectRefused(edited(R"("static": true,)", ""), "/bodies/0/shape", "static");
}

TEST(SceneLoader, StaticBodyWithVelocityIsRefusedWithItsPath)
{
    expectRefused(edited(R"("static": true,)", R"("static": true, "velocity": [1, 0, 0],)"), "/bodies/0/velocity",
                  "static");
}

TEST(SceneLoader, StaticBodyWithMassIsRefusedWithItsPath)
{
    expectRefused(edited(R"("static": true,)", R"("static": true, "mass": 1,)"), "/bodies/0/mass", "static");
}

TEST(SceneLoader, StaticBodyWithInertiaIsRefusedWithItsPath)
{
    expectRefused(edited(R"("static": true,)", R"("static": true, "inertia": [1, 1, 1],)"), "/bodies/0/inertia",
                  "static");
}

// ---- explicit inertia ------------------------------------------------------------------------

TEST(SceneLoader, PrincipalMomentsGivenReplaceTheShapesOwn)
{
    // the crate's own would be m (b^2 + c^2) / 3 and so on with m = 24 kg; these are another body's
    const auto scene =
        parseScene(edited(R"("density": 500,)", R"("density": 500, "inertia": [0.2, 0.3, 0.4],)"), "test.json");
    const impulse::BodyId crate = scene.dynamicBodies.at(1);
    EXPECT_EQ(scene.world.principalInertia(crate), impulse::Vec3(0.2, 0.3, 0.4));
    EXPECT_DOUBLE_EQ(scene.world.mass(crate), 500.0 * 0.2 * 0.4 * 0.6);
}

TEST(SceneLoader, AWholeTensorIsTheBodysInertiaOnTheShapesAxes)
{
    const auto scene = parseScene(edited(R"("density": 500,)", R"("density": 500,
        "inertia": [[0.3, 0.05, 0], [0.05, 0.2, -0.02], [0, -0.02, 0.4]],)"),
                                  "test.json");
    impulse::Mat3 given;
    given << 0.3, 0.05, 0.0, 0.05, 0.2, -0.02, 0.0, -0.02, 0.4;
    EXPECT_LT((scene.world.inertia(scene.dynamicBodies.at(1)) - given).norm(), 1e-15);
}

TEST(SceneLoader, InertiaThatNoBodyCanHaveIsRefusedWithItsPath)
{
    const auto withInertia = [](const std::string& inertia)
    { return edited(R"("density": 500,)", R"("density": 500, "inertia": )" + inertia + ","); };
    // 1 + 1 < 5: no distribution of mass has these moments
    expectRefused(withInertia("[1, 1, 5]"), "/bodies/2/inertia", "triangle");
    expectRefused(withInertia("[0.1, 0, 0.1]"), "/bodies/2/inertia/1", "positive");
    expectRefused(withInertia("[[0.3, 0.05, 0], [0, 0.2, 0], [0, 0, 0.4]]"), "/bodies/2/inertia", "symmetric");
    expectRefused(withInertia("[[0.3, 0, 0], [0, 0.2, 0]]"), "/bodies/2/inertia", "3 x 3");
    expectRefused(withInertia("[[0.3, 0, 0], [0, 0.2], [0, 0, 0.4]]"), "/bodies/2/inertia/1", "3 numbers");
    expectRefused(withInertia(R"("heavy")"), "/bodies/2/inertia", "3 x 3");
}

// ---- explicit centre of mass ------------------------------------------------------------------

TEST(SceneLoader, ACentreOfMassIsGivenInTheShapesFrameAndThePositionPlacesTheShape)
{
    // the crate turned a quarter turn about z, its centre of mass 5 cm along its own x
    const auto scene = parseScene(edited(R"("orientation": [1, 0, 0, 0],)",
                                         R"("orientation": {"axis": [0, 0, 1], "angle_deg": 90},
        "center_of_mass": [0.05, 0, 0],)"),
                                  "test.json");
    const impulse::BodyId crate = scene.dynamicBodies.at(1);
    EXPECT_EQ(scene.world.centerOfMass(crate), Vec3(0.05, 0.0, 0.0));
    EXPECT_LT((scene.world.shapePose(crate).position - Vec3(1.0, 0.0, 0.3)).norm(), 1e-15);
    EXPECT_LT((scene.world.state(crate).position - Vec3(1.0, 0.05, 0.3)).norm(), 1e-15);
}

TEST(SceneLoader, ACentreOfMassOnAStaticBodyOrNotAVectorIsRefusedWithItsPath)
{
    expectRefused(edited(R"("static": true,)", R"("static": true, "center_of_mass": [0, 0, 0.1],)"),
                  "/bodies/0/center_of_mass", "static");
    expectRefused(edited(R"("density": 500,)", R"("density": 500, "center_of_mass": [0, 0.1],)"),
                  "/bodies/2/center_of_mass", "3 numbers");
}

// ---- numbers that are valid JSON but make a non-finite body -----------------------------------

TEST(SceneLoader, DensityWhoseMassOverflowsIsRefusedWithItsPath)
{
    // 1e308 kg/m^3 times 4.19 m^3 is no finite double: the body would have an infinite mass and a
    // NaN angular momentum, so the first trajectory row would already hold NaN.
    const std::string text =
        edit(edited(R"("mass": 2.0,)", R"("density": 1e308,)"), R"("radius": 0.1)", R"("radius": 1.0)");
    const std::string message = refusal(text);
    ASSERT_FALSE(message.empty()) << "no io::SceneError, see above";
    EXPECT_EQ(message.rfind("test.json: /bodies/1", 0), 0u) << message;
    EXPECT_TRUE(contains(message, "finite")) << message;
}

} // namespace

// ---- meshes ----------------------------------------------------------------------------------

namespace mesh_scenes
{

/// A scene with one mesh body whose shape object is `shape`, read relative to the shipped scenes.
impulse::io::Scene meshScene(const std::string& shape, const std::string& pose = "\"position\": [0, 0, 1]",
                             const impulse::io::SceneLimits& limits = {})
{
    const std::string text = R"({"dt": 0.001, "duration": 1.0,
        "materials": {"m": {"restitution": 0.0, "friction": 0.5}},
        "bodies": [{"shape": )" +
                             shape + R"(, "material": "m", "density": 1000, )" + pose + "}]}";
    return parseScene(text, "test.json", IMPULSE_SCENES_DIR, limits);
}

std::string meshRefusal(const std::string& shape, const impulse::io::SceneLimits& limits = {})
{
    try
    {
        meshScene(shape, "\"position\": [0, 0, 1]", limits);
    }
    catch (const SceneError& error)
    {
        return error.what();
    }
    return "(accepted)";
}

TEST(SceneLoaderMesh, TheScenePlacesTheFileFrameAndTheBodyIsAtItsCentreOfMass)
{
    // the L-block's file origin is a corner; its centre of mass is (0.05, 0.05, 0.03) in the file
    const auto scene = meshScene(R"({"type": "mesh", "file": "meshes/l_block.obj"})",
                                 R"("position": [1, 2, 3], "orientation": {"axis": [0, 0, 1], "angle_deg": 90})");
    const impulse::BodyState state = scene.world.state(scene.dynamicBodies.at(0));
    // rotated a quarter turn about z, (0.05, 0.05, 0.03) becomes (-0.05, 0.05, 0.03); float file
    EXPECT_LT((state.position - impulse::Vec3(0.95, 2.05, 3.03)).norm(), 1e-8) << state.position.transpose();
    EXPECT_NEAR(scene.world.mass(scene.dynamicBodies.at(0)), 1000.0 * 3 * 0.06 * 0.06 * 0.06, 1e-6);
}

TEST(SceneLoaderMesh, ACentreOfMassIsGivenInTheFilesFrame)
{
    // the L-block's own centre of mass is (0.05, 0.05, 0.03) in its file; weighted at the file's
    // origin, a corner, the body sits there and the mesh stays where the scene puts the file
    const auto centred = meshScene(R"({"type": "mesh", "file": "meshes/l_block.obj"})",
                                   R"("position": [1, 2, 3], "orientation": {"axis": [0, 0, 1], "angle_deg": 90})");
    const auto weighted = meshScene(R"({"type": "mesh", "file": "meshes/l_block.obj"})",
                                    R"("position": [1, 2, 3], "orientation": {"axis": [0, 0, 1], "angle_deg": 90},
                     "center_of_mass": [0, 0, 0])");
    const impulse::BodyId body = weighted.dynamicBodies.at(0);
    EXPECT_LT((weighted.world.state(body).position - Vec3(1.0, 2.0, 3.0)).norm(), 1e-12);
    const impulse::Pose mesh = weighted.world.shapePose(body);
    const impulse::Pose expected = centred.world.shapePose(centred.dynamicBodies.at(0));
    EXPECT_LT((mesh.position - expected.position).norm(), 1e-12);
    EXPECT_LT(mesh.orientation.angularDistance(expected.orientation), 1e-12);
}

TEST(SceneLoaderMesh, AnInertiaGivenOnTheFilesAxesIsTurnedOntoTheBodysPrincipalAxes)
{
    // the L-block's principal axes are not its file's; the tensor given on the file's axes must be
    // the body's, seen in the world, when the file frame is the world frame
    const auto scene =
        meshScene(R"({"type": "mesh", "file": "meshes/l_block.obj"})",
                  R"("position": [0, 0, 1], "inertia": [[0.003, 0.0004, 0], [0.0004, 0.002, 0], [0, 0, 0.004]])");
    const impulse::BodyId body = scene.dynamicBodies.at(0);
    const impulse::Mat3 turn = scene.world.state(body).orientation.toRotationMatrix();
    impulse::Mat3 given;
    given << 0.003, 0.0004, 0.0, 0.0004, 0.002, 0.0, 0.0, 0.0, 0.004;
    EXPECT_LT((turn * scene.world.inertia(body) * turn.transpose() - given).norm(), 1e-15);
}

TEST(SceneLoaderMesh, ScaleAndResolutionAreApplied)
{
    const auto once = meshScene(R"({"type": "mesh", "file": "meshes/l_block.obj"})");
    const auto twice = meshScene(R"({"type": "mesh", "file": "meshes/l_block.obj", "scale": 2, "resolution": 40})");
    const auto& mesh = std::get<impulse::Mesh>(twice.world.shape(twice.dynamicBodies.at(0)));
    EXPECT_NEAR(twice.world.mass(twice.dynamicBodies.at(0)) / once.world.mass(once.dynamicBodies.at(0)), 8.0, 1e-9);
    // 40 cells along the longest side of the body-frame box (the L's principal axes are its diagonals)
    EXPECT_NEAR(impulse::MeshQueries::of(*mesh.geometry).cellSize(),
                (mesh.geometry->upper() - mesh.geometry->lower()).maxCoeff() / 40, 1e-15);
    EXPECT_NEAR((mesh.geometry->upper() - mesh.geometry->lower()).maxCoeff(), 2.0 * 0.12 * std::sqrt(2.0), 1e-6);
}

TEST(SceneLoaderMesh, BodiesOfOneFileShareOnePreparedMesh)
{
    const std::string body = R"({"shape": {"type": "mesh", "file": "meshes/star.obj"}, "material": "m", "mass": 1})";
    const std::string text = R"({"dt": 0.001, "duration": 1.0, "materials": {"m": {"restitution": 0, "friction": 0.5}},
        "bodies": [)" + body +
                             ", " + body + "]}";
    const auto scene = parseScene(text, "test.json", IMPULSE_SCENES_DIR);
    const auto& a = std::get<impulse::Mesh>(scene.world.shape(scene.dynamicBodies.at(0)));
    const auto& b = std::get<impulse::Mesh>(scene.world.shape(scene.dynamicBodies.at(1)));
    EXPECT_EQ(a.geometry.get(), b.geometry.get());
}

TEST(SceneLoaderMesh, StlIsReadAndWelded)
{
    const auto scene = meshScene(R"({"type": "mesh", "file": "meshes/gear.stl"})");
    const auto& gear = std::get<impulse::Mesh>(scene.world.shape(scene.dynamicBodies.at(0)));
    // 48 outline corners on each cap plus the two cap centres, once each after welding
    EXPECT_EQ(gear.geometry->vertices().size(), 98u);
}

TEST(SceneLoaderMesh, BrokenMeshesAndFieldsAreRefusedNamingTheFieldAndTheProblem)
{
    const std::string prefix = "test.json: /bodies/0/shape/";
    const std::string missing = meshRefusal(R"({"type": "mesh", "file": "meshes/nothing.obj"})");
    EXPECT_EQ(missing.rfind(prefix + "file: ", 0), 0u) << missing;
    EXPECT_TRUE(contains(missing, "nothing.obj: no such file")) << missing;

    const std::string open = meshRefusal(R"({"type": "mesh", "file": "../tests/data/meshes/open_box.obj"})");
    EXPECT_EQ(open.rfind(prefix + "file: ", 0), 0u) << open;
    EXPECT_TRUE(contains(open, "open_box.obj: not closed")) << open;

    const std::string notMesh = meshRefusal(R"({"type": "mesh", "file": "box_stack_10.json"})");
    EXPECT_TRUE(contains(notMesh, "cannot read the mesh")) << notMesh;

    EXPECT_TRUE(contains(meshRefusal(R"({"type": "mesh", "file": "meshes/star.obj", "scale": -1})"), "positive"));
    EXPECT_TRUE(contains(meshRefusal(R"({"type": "mesh", "file": "meshes/star.obj", "resolution": 2})"), "4 to"));
    EXPECT_TRUE(
        contains(meshRefusal(R"({"type": "mesh", "file": "meshes/star.obj", "resolution": 5000})"), "at most 1024"));
    EXPECT_TRUE(contains(meshRefusal(R"({"type": "mesh", "file": "meshes/star.obj", "radius": 1})"), "unknown field"));
    EXPECT_TRUE(contains(meshRefusal(R"({"type": "mesh"})"), "/file: missing"));
}

// A grid fine enough to take gigabytes (the L-block at 1024 cells: 1031 x 519 x 370 samples, some
// 6 GB) is refused before any of it is taken, and quickly.
TEST(SceneLoaderMesh, AGridBeyondTheSampleLimitIsRefusedBeforeItIsBuilt)
{
    const std::string fine = meshRefusal(R"({"type": "mesh", "file": "meshes/l_block.obj", "resolution": 1024})");
    EXPECT_EQ(fine.rfind("test.json: /bodies/0/shape/file: ", 0), 0u) << fine;
    EXPECT_TRUE(contains(fine, "the signed distance grid at resolution 1024 would have 1031 x ")) << fine;
    EXPECT_TRUE(contains(fine, "more than the limit of 16777216; choose a coarser resolution")) << fine;
    // a program can lower the limit; the default resolution of the star (32 cells) is then refused too
    impulse::io::SceneLimits small;
    small.maxGridSamples = 4096;
    EXPECT_TRUE(contains(meshRefusal(R"({"type": "mesh", "file": "meshes/star.obj"})", small),
                         "the signed distance grid at resolution 32 would have 39 x "))
        << meshRefusal(R"({"type": "mesh", "file": "meshes/star.obj"})", small);
}

TEST(SceneLoaderMesh, MeshFilesCanBeConfinedToTheScenesDirectory)
{
    impulse::io::SceneLimits inside;
    inside.meshFilesInsideDirectory = true;
    EXPECT_NO_THROW(meshScene(R"({"type": "mesh", "file": "meshes/star.obj"})", "\"position\": [0, 0, 1]", inside));
    EXPECT_EQ(meshRefusal(R"({"type": "mesh", "file": "../tests/data/meshes/open_box.obj"})", inside),
              "test.json: /bodies/0/shape/file: must be a path inside the scene's directory, got "
              "\"../tests/data/meshes/open_box.obj\", which leaves it by \"..\"");
    EXPECT_EQ(meshRefusal(R"({"type": "mesh", "file": "meshes/../../scenes/meshes/star.obj"})", inside)
                  .rfind("test.json: /bodies/0/shape/file: must be a path inside the scene's directory", 0),
              0u);
    EXPECT_EQ(meshRefusal(R"({"type": "mesh", "file": "/etc/passwd"})", inside),
              "test.json: /bodies/0/shape/file: must be a path inside the scene's directory, got the absolute path "
              "\"/etc/passwd\"");
    // without the confinement a scene may name any file, as the shipped test scenes do
    EXPECT_TRUE(contains(meshRefusal(R"({"type": "mesh", "file": "/no/such/mesh.obj"})"), "no such file"));
    // a NUL would cut the path short for the system: never a file name
    EXPECT_EQ(meshRefusal(R"({"type": "mesh", "file": "meshes/star.obj\u0000.txt"})"),
              "test.json: /bodies/0/shape/file: must not contain a NUL character");
}

} // namespace mesh_scenes
