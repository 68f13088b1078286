// SPDX-License-Identifier: MIT
// Tipping: stacks and blocks whose centre of mass lies just past or just short of the edge that
// supports them. Past it they must tip, short of it they must stand; shock propagation must not
// hold a stack that physics says topples. Each time limit is twice the time a rigid body pivoting
// on the supporting edge takes (phi'' = lambda^2 sin phi, lambda^2 = m g d / I_edge, d the distance
// from the edge to the centre of mass, phi the angle of that line past the vertical, from rest),
// integrated numerically; the linear estimate phi = phi0 cosh(lambda t) agrees to 1 %. The scenes
// are written by scripts/generate_scenes.py, their descriptions give the same numbers.
#include "support/scene_run.hpp"
#include "support/tilt.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>

namespace impulse::test
{
namespace
{

constexpr Real kDegree = std::numbers::pi / 180.0;

/// Fastest point of a body, bounded by |v| + 0.3 |w|: 0.3 m exceeds the half-diagonal of every box
/// here (plank 0.274, cube 0.173, domino 0.225).
Real pointSpeed(const BodyState& s)
{
    return s.linearVelocity.norm() + 0.3 * s.angularVelocity.norm();
}

struct StandRecord
{
    Real largestDisplacement = 0.0; ///< of any body's centre from its start, over the whole run
    std::size_t worstBody = 0;      ///< the body that moved furthest, counted from 0 at the bottom
    Real fastestAtEnd = 0.0;        ///< largest point speed of any body after the last step
};

/// Steps a scene that must stand for its whole duration at 1 ms.
StandRecord runStanding(io::Scene& scene)
{
    StandRecord record;
    std::vector<Vec3> start;
    for (const BodyId id : scene.dynamicBodies)
    {
        start.push_back(scene.world.state(id).position);
    }
    runScene(scene, 1e-3,
             [&](Real, const World& world)
             {
                 record.fastestAtEnd = 0.0;
                 for (std::size_t k = 0; k < start.size(); ++k)
                 {
                     const BodyState s = world.state(scene.dynamicBodies[k]);
                     const Real moved = (s.position - start[k]).norm();
                     if (moved > record.largestDisplacement)
                     {
                         record.largestDisplacement = moved;
                         record.worstBody = k;
                     }
                     record.fastestAtEnd = std::max(record.fastestAtEnd, pointSpeed(s));
                 }
             });
    return record;
}

// A stack that stands: no body's centre moves 1 mm, and all are at rest at the end, every point
// slower than 1e-4 m/s (1 % of the speed gravity adds in one step, g dt = 9.8 mm/s), as reference
// scene 9 asks of a stack of cubes.
void expectStands(const char* name)
{
    io::Scene scene = loadReferenceScene(name);
    const StandRecord record = runStanding(scene);
    EXPECT_LT(record.largestDisplacement, 1e-3)
        << name << ": body " << record.worstBody << " moved " << record.largestDisplacement << " m from its start";
    EXPECT_LT(record.fastestAtEnd, 1e-4) << name << ": a point still moves at " << record.fastestAtEnd << " m/s";
}

struct DropRecord
{
    Real time = -1.0;       ///< when the body's centre first was `drop` below its start; -1: never
    Real largestDrop = 0.0; ///< by the end of the run
};

/// Steps `scene` for `limit` seconds at 1 ms and records when `body`'s centre falls `drop` below its start.
DropRecord runUntilDrop(io::Scene& scene, BodyId body, Real drop, Real limit)
{
    DropRecord record;
    const Real z0 = scene.world.state(body).position.z();
    runScene(
        scene, 1e-3,
        [&](Real t, const World& world)
        {
            record.largestDrop = std::max(record.largestDrop, z0 - world.state(body).position.z());
            if (record.time < 0.0 && record.largestDrop > drop)
            {
                record.time = t;
            }
        },
        limit);
    return record;
}

// ---- planks stacked with an overhang --------------------------------------------------------------

TEST(Tipping, OverhangTwentyMillimetresPastTheEdgeTopples)
{
    // Four planks 0.5 x 0.2 x 0.1 m of 1 kg, each 0.135 m past the one below. The upper three's
    // centre of mass is at 2 x 0.135 = 0.27 from the bottom plank's centre, 20 mm past its edge at
    // 0.25, while the top two on plank 2 (at 1.5 x 0.135 = 0.2025) and the top one on plank 3 (0.135)
    // lie inside theirs: the upper three turn together about the bottom plank's top edge
    // (x = 0.25, z = 0.1), their centre (0.27, 0.25) at d = 0.1513 from it, 7.59 degrees past the
    // vertical. I_edge = 3 (0.25^2 + 0.05^2) / 3 + sum of the squared distances of the three centres
    // (0.015725 + 0.0229 + 0.086525) = 0.19015 kg m^2, lambda = sqrt(3 g d / I_edge) = 4.84 /s. The top
    // plank's centre (0.405, 0.35) has dropped 0.1 m after a turn of 0.48 rad, at t = 0.459 s. Limit:
    // twice that, 0.92 s.
    io::Scene scene = loadReferenceScene("overhang_topples");
    const DropRecord record = runUntilDrop(scene, scene.dynamicBodies.back(), 0.1, 0.92);
    EXPECT_GT(record.time, 0.0) << "the top plank's centre dropped only " << record.largestDrop
                                << " m in 0.92 s (0.1 m after 0.459 s expected)";
}

TEST(Tipping, OverhangTwentyMillimetresShortOfTheEdgeStands)
{
    // The same planks each 0.115 m past the one below: the upper three's centre at 0.23, 20 mm inside
    // the bottom plank's edge; the top two at 0.1725 and the top one at 0.115 from the centres of
    // their supports, all inside the 0.25 half-length. Every sub-stack is supported: it stands.
    expectStands("overhang_stands");
}

TEST(Tipping, HarmonicStackAtNineTenthsOfTheLimitStands)
{
    // Six planks, the k-th from the top 0.9 L / (2 k) past the one below (L = 0.5): offsets 0.045,
    // 0.05625, 0.075, 0.1125, 0.225 from the bottom up. With offsets L / (2 k) the top k planks'
    // centre of mass would lie exactly over the edge of the plank below (the harmonic overhang); at
    // 0.9 of them it lies 0.9 L / 2 = 0.225 from that plank's centre, 25 mm inside its edge, for every
    // k: each sub-stack is supported and the whole stands, the top plank reaching 0.514 m past the
    // bottom one's centre (0.264 m past its edge).
    expectStands("harmonic_stack");
}

// ---- towers of cubes on a 15 degree incline -------------------------------------------------------

TEST(Tipping, LeaningTowerOfThreeStands)
{
    // Cubes of side 0.2 stacked along the normal of a 15 degree incline. A tower of n has its centre
    // of mass 0.1 n from the incline along the normal, and gravity's line through it meets the incline
    // 0.1 n tan 15 downhill of the tower's axis, against the downhill edge 0.1 from it: it tips iff
    // n tan 15 > 1. For n = 3, 0.804 < 1: the centre of mass is 3.43 degrees uphill of the vertical
    // over the edge (and 2 on 1, 1 on 1 lean less). mu = 0.9 > tan 15 = 0.268: nothing slides.
    expectStands("leaning_tower_3");
}

TEST(Tipping, LeaningTowerOfFourTipsOverItsDownhillEdgeWithoutSliding)
{
    // n = 4: 4 tan 15 = 1.072 > 1. Seen from the bottom cube's downhill edge the centre of mass is at
    // (-0.1, 0.4) in the incline's frame (downhill, normal), atan(0.1 / 0.4) = 14.04 degrees uphill
    // of the normal, which itself leans 15 degrees downhill of the vertical: 0.964 degrees past the
    // vertical over the edge. The three upper cubes lean 3.43 degrees short of the edge of the
    // bottom one, so the tower turns as one body about the bottom edge: d = sqrt(0.1^2 + 0.4^2) =
    // 0.4123, I_edge = 4 (4/3)(0.1^2 + 0.4^2) = 0.9067 kg m^2, lambda = sqrt(4 g d / I_edge) =
    // 4.224 /s. "Tips": the top cube's centre drops 0.1 m, which takes a turn of 24.8 degrees, at
    // t = 0.943 s (linear estimate acosh(1 + 24.8 / 0.964) / lambda = 0.942 s). Limit: twice that,
    // 1.9 s.
    //
    // No sliding: along that rigid turn the bottom edge must carry a tangential force of at most
    // 0.25 times the normal one (0.254 at the start, falling to 0 at 20 degrees and 0.09 at 35),
    // well inside mu = 0.9, so the edge stays where it is until the top has dropped 0.1 m. Allowed:
    // 2 mm of movement along the incline, 2 % of that drop.
    io::Scene scene = loadReferenceScene("leaning_tower_4");
    const BodyId bottom = scene.dynamicBodies.front();
    const BodyId top = scene.dynamicBodies.back();
    const Vec3 normal(std::sin(15.0 * kDegree), 0.0, std::cos(15.0 * kDegree));
    const Vec3 edgeLocal(0.1, 0.0, -0.1); // the middle of the bottom cube's downhill bottom edge
    const auto edgeOf = [&](const World& world)
    {
        const BodyState s = world.state(bottom);
        return Vec3(s.position + s.orientation * edgeLocal);
    };
    const Vec3 edgeStart = edgeOf(scene.world);
    const Real topStart = scene.world.state(top).position.z();
    Real tipTime = -1.0;
    Real largestDrop = 0.0;
    Real slide = 0.0; // of the edge along the incline, up to the tip (or the limit)
    runScene(
        scene, 1e-3,
        [&](Real t, const World& world)
        {
            if (tipTime >= 0.0)
            {
                return;
            }
            const Vec3 moved = edgeOf(world) - edgeStart;
            slide = std::max(slide, (moved - moved.dot(normal) * normal).norm());
            largestDrop = std::max(largestDrop, topStart - world.state(top).position.z());
            if (largestDrop > 0.1)
            {
                tipTime = t;
            }
        },
        1.9);
    EXPECT_GT(tipTime, 0.0) << "the top cube's centre dropped only " << largestDrop
                            << " m in 1.9 s (0.1 m after 0.943 s expected)";
    EXPECT_LT(slide, 2e-3) << "the bottom cube's downhill edge slid " << slide << " m along the incline before "
                           << (tipTime > 0.0 ? "the tower tipped" : "1.9 s");
}

// ---- taller towers on a 10 degree incline ---------------------------------------------------------

// The same towers on a 10 degree incline with mu = 0.8 (nothing slides: tan 10 = 0.176): a tower of n
// tips iff n tan 10 > 1, so 5 stand (0.882) and 6 tip (1.058). Tall towers are where a solver that
// holds each level against its frozen supports without the load from above erases the tipping: the
// moment that tips the tower builds up through every level. Rigid about the bottom downhill edge,
// d = 0.1 sqrt(1 + n^2), I_edge = n 0.04 (1 + n^2) / 3, lambda^2 = 7.5 g / sqrt(1 + n^2); the centre of
// mass starts 10 - atan(1 / n) degrees past the vertical, and the top cube's centre drops 0.1 m at the
// time given (q'' = lambda^2 sin q integrated from rest, scripts/generate_scenes.py). Limit: twice that.

TEST(Tipping, TowerOfFiveOnATenDegreeInclineStands)
{
    // 5 tan 10 = 0.882: the centre of mass 1.31 degrees uphill of the vertical over the edge
    expectStands("incline_tower_5");
}

void expectTowerTips(const char* name, Real dropTime)
{
    io::Scene scene = loadReferenceScene(name);
    const DropRecord record = runUntilDrop(scene, scene.dynamicBodies.back(), 0.1, 2.0 * dropTime);
    EXPECT_GT(record.time, 0.0) << name << ": the top cube's centre dropped only " << record.largestDrop << " m in "
                                << 2.0 * dropTime << " s (0.1 m after " << dropTime << " s expected)";
}

TEST(Tipping, TowerOfSixOnATenDegreeInclineTips)
{
    // 6 tan 10 = 1.058: 0.54 degrees past the vertical, lambda = 3.478 /s, the top drops 0.1 m at 1.251 s
    expectTowerTips("incline_tower_6", 1.251);
}

TEST(Tipping, TowerOfTwentyOnATenDegreeInclineTips)
{
    // 20 tan 10 = 3.53: 7.14 degrees past the vertical, lambda = 1.917 /s, the top drops 0.1 m at 0.684 s
    expectTowerTips("incline_tower_20", 0.684);
}

// ---- a domino released near its critical angle --------------------------------------------------

// A box 0.05 x 0.2 x 0.4 m (half extents a = 0.025, c = 0.2), tilted about y with its bottom edge at
// x = 0.025 on the ground. Its centre of mass is over that edge at the critical tilt
// alpha = atan(0.05 / 0.4) = 7.125 degrees. Turning about the edge: d = sqrt(a^2 + c^2) = 0.2016,
// I_edge = m (4/3)(a^2 + c^2) = 0.05417 kg m^2 (m = 1), lambda = sqrt(g d / (4/3 (a^2 + c^2))) =
// 6.04 /s.

TEST(Tipping, DominoOneDegreePastTheCriticalAngleFallsOntoItsFace)
{
    // Released at 8.125 degrees, 1 degree past the critical angle: the tilt past it grows from 1
    // degree to 72.9 degrees (a tilt of 80) at t = 0.830 s (linear estimate 0.825 s). Limit: twice
    // that, 1.66 s. The edge holds: the friction it needs is at most 0.35 of the normal force up to
    // 40 degrees past critical, below mu = 0.6. The domino lands on the broad face that holds the
    // edge (its +x face) and, with eps = 0, stays there: after 3 s it lies at rest on it, the body x
    // axis pointing down, the centre at z = a = 0.025. The face is 0.4 m long and the push-out
    // leaves overlaps up to 1e-4 m: flat means within 1e-4 / 0.4 = 2.5e-4 rad; allowed 1e-3 rad and
    // 1e-3 m (on any other face or edge the centre would be 0.1 m higher or more).
    io::Scene scene = loadReferenceScene("domino_falls");
    const BodyId domino = scene.dynamicBodies.at(0);
    EXPECT_NEAR(tiltAboutY(scene.world.state(domino).orientation), 8.125 * kDegree, 1e-4);
    Real fallTime = -1.0;
    Real largestTilt = 0.0;
    runScene(scene, 1e-3,
             [&](Real t, const World& world)
             {
                 largestTilt = std::max(largestTilt, tiltAboutY(world.state(domino).orientation));
                 if (fallTime < 0.0 && largestTilt > 80.0 * kDegree)
                 {
                     fallTime = t;
                 }
             });
    EXPECT_GT(fallTime, 0.0) << "the tilt reached only " << largestTilt / kDegree << " degrees in 3 s";
    EXPECT_LT(fallTime, 1.66) << "the tilt reached 80 degrees after " << fallTime << " s (0.830 s expected)";
    const BodyState end = scene.world.state(domino);
    const Real offFace = tiltAngle(end.orientation, Vec3::UnitX(), -Vec3::UnitZ());
    EXPECT_LT(offFace, 1e-3) << "at the end the +x face is " << offFace << " rad off the ground's plane";
    EXPECT_NEAR(end.position.z(), 0.025, 1e-3) << "the centre is at z = " << end.position.z();
    EXPECT_LT(pointSpeed(end), 1e-4) << "a point still moves at " << pointSpeed(end) << " m/s at the end";
}

TEST(Tipping, DominoOneDegreeShortOfTheCriticalAngleRocksBackUpright)
{
    // Released at 6.125 degrees, 1 degree short of the critical angle: it turns back about the
    // edge and lands on its base after the angle short of critical has grown from 1 to 7.125
    // degrees, at t = 0.439 s (linear estimate 0.442 s); its tilt falls below 0.5 degrees at
    // 0.427 s. Limit for that: twice the landing time, 0.88 s.
    //
    // Landing with eps = 0 does not stop a slender block at once. The impulse at the landing edge
    // alone (the other edge lifts: the solution of the impact's complementarity problem) keeps the
    // angular momentum about that edge and the block rocks on about it with its angular velocity
    // times r = 1 - (3/2) sin^2 alpha = 0.977 (Housner 1963), its energy times r^2 = 0.954: the
    // amplitudes are 5.32, 4.79, 4.39 ... degrees and the half-cycles shrink with them, a
    // convergent series: at rest at t = 17.07 s. The scene lasts 20 s. Any further loss only stops
    // it sooner; what it may never do is gain energy, so its tilt must never exceed the 6.125
    // degrees it started at, on either side (7.125 on the other side would topple it that way).
    //
    // At the end it stands on its base at rest: both bottom edges within the push-out allowance
    // (1e-4 m) of the ground, a tilt below 1e-4 / 0.05 = 2e-3 rad, the centre at z = 0.2, and no
    // point faster than 1e-4 m/s over the last 0.5 s (rocking through even 2e-3 rad would reach
    // 0.03 m/s at the top).
    io::Scene scene = loadReferenceScene("domino_rocks_back");
    const BodyId domino = scene.dynamicBodies.at(0);
    const Real startTilt = tiltAboutY(scene.world.state(domino).orientation);
    EXPECT_NEAR(startTilt, 6.125 * kDegree, 1e-4);
    Real uprightTime = -1.0;
    Real largestTilt = 0.0;     // either side, over the whole run
    Real largestBackTilt = 0.0; // toward -x, the far side
    Real lastTipped = 0.0;      // the last time the tilt exceeded 2e-3 rad
    Real fastestLate = 0.0;     // over the last 0.5 s
    runScene(scene, 1e-3,
             [&](Real t, const World& world)
             {
                 const BodyState s = world.state(domino);
                 const Real tilt = tiltAboutY(s.orientation);
                 largestTilt = std::max(largestTilt, std::abs(tilt));
                 largestBackTilt = std::max(largestBackTilt, -tilt);
                 if (uprightTime < 0.0 && std::abs(tilt) < 0.5 * kDegree)
                 {
                     uprightTime = t;
                 }
                 if (std::abs(tilt) > 2e-3)
                 {
                     lastTipped = t;
                 }
                 if (t > scene.duration - 0.5)
                 {
                     fastestLate = std::max(fastestLate, pointSpeed(s));
                 }
             });
    EXPECT_GT(uprightTime, 0.0) << "the tilt never fell below 0.5 degrees";
    EXPECT_LT(uprightTime, 0.88) << "the tilt fell below 0.5 degrees after " << uprightTime << " s (0.427 s expected)";
    EXPECT_LT(largestTilt, startTilt + 1e-6)
        << "the tilt reached " << largestTilt / kDegree << " degrees, more than the 6.125 it started at; toward -x "
        << largestBackTilt / kDegree << " (5.32 at most by Housner's rocking)";
    const BodyState end = scene.world.state(domino);
    const Real tilt = tiltAngle(end.orientation);
    EXPECT_LT(tilt, 2e-3) << "at the end it is tilted " << tilt << " rad; last tilted beyond 2e-3 rad at " << lastTipped
                          << " s";
    EXPECT_NEAR(end.position.z(), 0.2, 1e-3) << "the centre is at z = " << end.position.z();
    EXPECT_LT(fastestLate, 1e-4) << "a point moved at " << fastestLate << " m/s in the last 0.5 s; last tilted beyond "
                                 << "2e-3 rad at " << lastTipped << " s";
}

} // namespace
} // namespace impulse::test
