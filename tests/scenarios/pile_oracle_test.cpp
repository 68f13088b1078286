// SPDX-License-Identifier: MIT
// The reference piles' oracle as a run with checkpoints (support/pile_oracle.hpp): a run stopped and
// continued from its checkpoint is the run that was not stopped, bit for bit, figures included; a
// checkpoint that is not one, or not of this scene, is refused by file, line and field; and the
// oracle fails the piles it must fail.
#include "support/pile_oracle.hpp"
#include "support/scene_run.hpp"

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>

namespace impulse::test
{
namespace
{

std::string scratchFile(const std::string& name)
{
    const auto directory = std::filesystem::temp_directory_path() / "impulse_pile_oracle_test";
    std::filesystem::create_directories(directory);
    return (directory / name).string();
}

// The first 0.35 s of the two-hundred-mesh pile: the lowest meshes land between 0.25 and 0.3 s, so
// the sampled depths are not all zero when a run is cut at step 320, and three samples follow.
PileRun shortMeshPile()
{
    io::Scene scene = loadReferenceScene("nonconvex_pile_200");
    scene.duration = 0.35;
    return PileRun(std::move(scene), PileOracleKind::Settles);
}

std::string readAll(const std::string& path)
{
    std::ifstream in(path);
    std::stringstream text;
    text << in.rdbuf();
    return text.str();
}

void writeAll(const std::string& path, const std::string& text)
{
    std::ofstream(path, std::ios::trunc) << text;
}

std::string resumeError(const std::string& path)
{
    PileRun run = shortMeshPile();
    try
    {
        run.resume(path);
    }
    catch (const std::runtime_error& error)
    {
        EXPECT_EQ(run.figures().step, 0) << "a refused checkpoint must change nothing";
        return error.what();
    }
    return "";
}

TEST(PileCheckpoint, ContinuesTheRunBitForBitWithItsFigures)
{
    std::ostringstream log;
    PileRun straight = shortMeshPile();
    while (!straight.finished())
    {
        straight.step(log);
    }

    PileRun first = shortMeshPile();
    for (int k = 0; k < 320; ++k)
    {
        first.step(log);
    }
    const std::string path = scratchFile("continues.txt");
    first.save(path);
    PileRun continued = shortMeshPile();
    continued.resume(path);
    EXPECT_EQ(continued.figures().step, 320);
    EXPECT_EQ(continued.figures().peakKinetic, first.figures().peakKinetic);
    EXPECT_GT(first.figures().deepest, 0.0) << "the pile has landed by the cut: some pair touched at a sample";
    EXPECT_EQ(continued.figures().deepest, first.figures().deepest);
    EXPECT_EQ(continued.figures().deepestRelative, first.figures().deepestRelative);
    EXPECT_EQ(continued.deepestSample(), first.deepestSample());
    EXPECT_EQ(continued.world().stateHash(), first.world().stateHash());
    while (!continued.finished())
    {
        continued.step(log);
    }

    EXPECT_EQ(continued.figures().step, straight.figures().step);
    EXPECT_GT(straight.figures().peakKinetic, 0.0);
    EXPECT_EQ(continued.figures().peakKinetic, straight.figures().peakKinetic);
    EXPECT_EQ(continued.figures().deepest, straight.figures().deepest);
    EXPECT_EQ(continued.figures().deepestRelative, straight.figures().deepestRelative);
    EXPECT_EQ(continued.deepestSample(), straight.deepestSample());
    EXPECT_EQ(continued.world().time(), straight.world().time());
    EXPECT_EQ(continued.world().stateHash(), straight.world().stateHash());
    const WorldSnapshot a = continued.world().snapshot();
    const WorldSnapshot b = straight.world().snapshot();
    ASSERT_EQ(a.bodies.size(), b.bodies.size());
    for (std::size_t i = 0; i < a.bodies.size(); ++i)
    {
        const auto x = PileRun::stateValues(a.bodies[i]);
        const auto y = PileRun::stateValues(b.bodies[i]);
        ASSERT_EQ(std::memcmp(x.data(), y.data(), sizeof x), 0) << "body " << i;
    }
}

TEST(PileCheckpoint, ThatIsNotOneOrNotOfThisSceneIsRefusedByFileLineAndField)
{
    PileRun run = shortMeshPile();
    for (int k = 0; k < 5; ++k)
    {
        run.step(std::cout);
    }
    const std::string good = scratchFile("good.txt");
    run.save(good);
    const std::string text = readAll(good);
    const std::string bad = scratchFile("bad.txt");

    writeAll(bad, text.substr(0, text.find('\n', text.size() / 2) + 1)); // cut at a line's end
    std::string error = resumeError(bad);
    EXPECT_NE(error.find(bad), std::string::npos) << error;
    EXPECT_NE(error.find("expected 16 numbers"), std::string::npos) << error;

    writeAll(bad, "not a checkpoint\n");
    EXPECT_NE(resumeError(bad).find("line 1: not a pile checkpoint"), std::string::npos);

    std::string other = text;
    other.replace(other.find("nonconvex_pile_200"), std::strlen("nonconvex_pile_200"), "box_pile_1000");
    writeAll(bad, other);
    error = resumeError(bad);
    EXPECT_NE(error.find("scene: the checkpoint is of \"box_pile_1000\""), std::string::npos) << error;

    std::string nan = text;
    nan.replace(nan.find("peak_kinetic ") + 13, 1, "nan");
    writeAll(bad, nan);
    error = resumeError(bad);
    EXPECT_NE(error.find("line 4: peak_kinetic: not a finite number"), std::string::npos) << error;

    std::string late = text;
    late.replace(late.find("step 5"), 6, "step 500");
    writeAll(bad, late);
    error = resumeError(bad);
    EXPECT_NE(error.find("step: 500"), std::string::npos) << error;

    // a body moved into a static one's place: World::restore's own refusal, with the file named
    std::string moved = text;
    const std::size_t firstBody = moved.find('\n', moved.find("bodies ")) + 1;
    moved.replace(firstBody, moved.find(' ', firstBody) - firstBody, "0x1p+0");
    writeAll(bad, moved);
    error = resumeError(bad);
    EXPECT_EQ(error.rfind(bad + ": ", 0), 0u) << error;
}

TEST(PileOracle, FailsWhenABodyLeavesTheBox)
{
    io::Scene scene = loadReferenceScene("box_pile_1000");
    scene.duration = 0.2;
    const BodyId leaving = scene.dynamicBodies.front();
    const BodyState s = scene.world.state(leaving);
    scene.world.setState(leaving, Vec3(2.5, 0.0, s.position.z()), s.orientation, Vec3::Zero(), Vec3::Zero());
    PileRun run(std::move(scene), PileOracleKind::StaysInTheBox, 0.1);
    while (!run.finished())
    {
        run.step(std::cout);
    }
    ASSERT_TRUE(run.failure().has_value());
    EXPECT_NE(run.failure()->find("1 bodies out of the box at t = 0.1"), std::string::npos) << *run.failure();
}

TEST(PileOracle, ReportsTheDeepestPairAlongTheRun)
{
    // two cubes 2 mm inside each other fall freely side by side, outside the walls: with push-out off
    // nothing parts them, so every sample finds the same 2 mm, until the escape check fails the run
    io::Scene scene = loadReferenceScene("box_pile_1000");
    scene.options.pushOut = false;
    const Quat level = Quat::Identity();
    scene.world.setState(scene.dynamicBodies[0], Vec3(0.0, 3.0, 20.0), level, Vec3::Zero(), Vec3::Zero());
    scene.world.setState(scene.dynamicBodies[1], Vec3(0.198, 3.0, 20.0), level, Vec3::Zero(), Vec3::Zero());
    const std::array<BodyId, 2> pair = {scene.dynamicBodies[0], scene.dynamicBodies[1]};
    PileRun run(std::move(scene), PileOracleKind::StaysInTheBox, 0.1);
    while (!run.finished())
    {
        run.step(std::cout);
    }
    EXPECT_EQ(run.figures().step, 100);
    EXPECT_TRUE(run.failure().has_value());
    EXPECT_NEAR(run.figures().deepest, 0.002, 1e-9);
    // the size of a body is the diameter of its bounding sphere: for the cube 2 sqrt(3) 0.1
    EXPECT_NEAR(run.figures().deepestRelative, 0.002 / (2.0 * std::sqrt(3.0) * 0.1), 1e-8);
    // where it was first sampled: the first sample, of the two cubes (the later ones find it no deeper)
    EXPECT_EQ(run.figures().deepestStep, 50);
    EXPECT_EQ(run.figures().deepestFirst, pair[0].index);
    EXPECT_EQ(run.figures().deepestSecond, pair[1].index);
    EXPECT_EQ(run.deepestSample(),
              "step 50, bodies " + std::to_string(pair[0].index) + " and " + std::to_string(pair[1].index));
}

TEST(PileOracle, FailsTwoCubesTwoPercentOfRInsideEachOther)
{
    io::Scene scene = loadReferenceScene("box_pile_1000");
    const BodyId a = scene.dynamicBodies[0];
    const BodyId b = scene.dynamicBodies[1];
    const Quat level = Quat::Identity();
    // side 0.2, outside the walls and clear of the others: centres 0.198 apart along x overlap by
    // 0.002 m, 2 % of r = 0.1
    scene.world.setState(a, Vec3(0.0, 3.0, 1.0), level, Vec3::Zero(), Vec3::Zero());
    scene.world.setState(b, Vec3(0.198, 3.0, 1.0), level, Vec3::Zero(), Vec3::Zero());
    const PileRun run(std::move(scene), PileOracleKind::StaysInTheBox, 0.1);
    const std::vector<PileCheck> checks = run.finalChecks();
    ASSERT_EQ(checks.size(), 1u);
    EXPECT_NEAR(checks[0].value, 0.02, 1e-9);
    EXPECT_FALSE(checks[0].holds());
}

} // namespace
} // namespace impulse::test
