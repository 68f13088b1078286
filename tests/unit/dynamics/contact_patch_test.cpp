// SPDX-License-Identifier: MIT
// The patch solves of contact_patch.hpp against the conservation law they must keep: a patch
// impulse with restitution between 0 and 1 never adds kinetic energy, however badly conditioned the
// patch. The random patches below are built to be nearly singular (points bunched together, normals
// from nearly parallel to pointing every way, partners shared between points), the case in which a
// least-squares warm start can ask for impulses far larger than the contact needs, and in which
// restitution targets at a pinch are out of reach.
#include "dynamics/contact_patch.hpp"
#include "dynamics/integrate.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <deque>
#include <random>
#include <vector>

namespace impulse
{
namespace
{

using Uniform = std::uniform_real_distribution<Real>;

// A body at `position` with mass m and a random principal inertia of that mass's scale, turned by a
// random rotation; it rests at its predicted pose, so the levers are the same in every pass.
RigidBody randomBody(std::mt19937_64& rng, const Vec3& position, bool dynamic)
{
    RigidBody body;
    body.dynamic = dynamic;
    body.position = position;
    std::normal_distribution<Real> normal;
    body.orientation = Quat(normal(rng), normal(rng), normal(rng), normal(rng)).normalized();
    body.rotation = body.orientation.toRotationMatrix();
    body.predicted = Pose::from(position, body.orientation);
    if (dynamic)
    {
        body.mass = Uniform(0.2, 5.0)(rng);
        body.invMass = 1.0 / body.mass;
        body.principalInertia =
            body.mass * Vec3(Uniform(0.05, 1.0)(rng), Uniform(0.05, 1.0)(rng), Uniform(0.05, 1.0)(rng));
        body.invPrincipalInertia = body.principalInertia.cwiseInverse();
        body.invInertiaWorld = body.rotation * body.invPrincipalInertia.asDiagonal() * body.rotation.transpose();
        body.linearVelocity = Vec3(Uniform(-1.0, 1.0)(rng), Uniform(-1.0, 1.0)(rng), Uniform(-3.0, 0.0)(rng));
        body.angularMomentum = body.rotation * body.principalInertia.asDiagonal() *
                               Vec3(Uniform(-2.0, 2.0)(rng), Uniform(-2.0, 2.0)(rng), Uniform(-2.0, 2.0)(rng));
        body.angularVelocity = body.invInertiaWorld * body.angularMomentum;
    }
    return body;
}

Real kineticEnergy(const RigidBody& body)
{
    if (!body.dynamic)
    {
        return 0.0;
    }
    return 0.5 * body.mass * body.linearVelocity.squaredNorm() + 0.5 * body.angularMomentum.dot(body.angularVelocity);
}

// The body sits above its partners; each point lies within `cluster` of a common spot, its normal
// (from the partner toward the body) the vertical plus `spread` times a random vector: small spreads
// give nearly parallel rows, large ones normals in every direction, a body pinched between faces.
struct RandomPatch
{
    std::deque<RigidBody> bodies; // bodies[0] is the body; a deque keeps the partners' addresses
    std::vector<PatchPoint> points;
};

RandomPatch randomPatch(std::mt19937_64& rng)
{
    RandomPatch scene;
    scene.bodies.push_back(randomBody(rng, Vec3(0.0, 0.0, 0.5), true));
    const int partners = std::uniform_int_distribution<int>(1, 3)(rng);
    for (int p = 0; p < partners; ++p)
    {
        const bool dynamic = Uniform(0.0, 1.0)(rng) < 0.6;
        scene.bodies.push_back(randomBody(rng, Vec3(Uniform(-0.5, 0.5)(rng), Uniform(-0.5, 0.5)(rng), -0.5), dynamic));
    }
    const Real cluster = std::pow(10.0, Uniform(-6.0, 0.0)(rng));
    const Real spread = std::pow(10.0, Uniform(-6.0, 2.0)(rng));
    const Vec3 spot(Uniform(-0.3, 0.3)(rng), Uniform(-0.3, 0.3)(rng), 0.0);
    const int count = std::uniform_int_distribution<int>(2, 12)(rng);
    for (int k = 0; k < count; ++k)
    {
        PatchPoint point;
        point.other = &scene.bodies[1 + static_cast<std::size_t>(k % partners)];
        point.contact.point =
            spot + cluster * Vec3(Uniform(-1.0, 1.0)(rng), Uniform(-1.0, 1.0)(rng), Uniform(-1.0, 1.0)(rng));
        point.contact.normal =
            (Vec3::UnitZ() + spread * Vec3(Uniform(-1.0, 1.0)(rng), Uniform(-1.0, 1.0)(rng), Uniform(-1.0, 1.0)(rng)))
                .normalized();
        point.friction = Uniform(0.0, 1.5)(rng);
        scene.points.push_back(point);
    }
    return scene;
}

// Inelastic a third of the time (the contact pass), else anything up to fully elastic.
Real randomRestitution(std::mt19937_64& rng)
{
    return Uniform(0.0, 1.0)(rng) < 1.0 / 3.0 ? 0.0 : Uniform(0.0, 1.0)(rng);
}

Real totalKineticEnergy(const RandomPatch& scene)
{
    Real energy = 0.0;
    for (const RigidBody& body : scene.bodies)
    {
        energy += kineticEnergy(body);
    }
    return energy;
}

// Round-off: the solve sums a few hundred products of quantities of order one (velocities ~1 m/s,
// masses ~1 kg); 1e-9 of the energy at stake is far above that and far below any real gain.
constexpr Real kEnergyTolerance = 1e-9;

using PatchSolve = bool (*)(RigidBody&, const std::vector<PatchPoint>&, Real, const PassSettings&);

// Applies `solve` to 4000 random patches, each with a random restitution, and checks the largest
// relative gain of kinetic energy among them.
void expectNoEnergyGained(PatchSolve solve, std::uint64_t seed)
{
    std::mt19937_64 rng(seed);
    const PassSettings settings;
    int worst = -1;
    Real worstGain = 0.0;
    for (int trial = 0; trial < 4000; ++trial)
    {
        RandomPatch scene = randomPatch(rng);
        const Real before = totalKineticEnergy(scene);
        solve(scene.bodies[0], scene.points, randomRestitution(rng), settings);
        const Real after = totalKineticEnergy(scene);
        ASSERT_TRUE(std::isfinite(after)) << "trial " << trial;
        const Real gain = (after - before) / before;
        if (gain > worstGain)
        {
            worstGain = gain;
            worst = trial;
        }
    }
    EXPECT_LE(worstGain, kEnergyTolerance) << "trial " << worst << " gained " << worstGain << " of its kinetic energy";
}

TEST(ContactPatch, ProjectedSolveOfNearlySingularPatchesNeverAddsKineticEnergy)
{
    expectNoEnergyGained(&applyProjectedPatchImpulse, 20261122);
}

TEST(ContactPatch, StickingSolveOfNearlySingularPatchesNeverAddsKineticEnergy)
{
    expectNoEnergyGained(&applyPatchImpulse, 11222026);
}

// The least-squares solves keep their factors for a next solve of the same matrix (the projected
// solve's warm start after a failed sticking solve of the same patch). Reused factors must give what
// factoring anew gives, bit for bit, and a matrix of the same size that differs in any bit must be
// factored anew. Each trial builds one random patch several times. `reused` gets the sticking solve
// right after `nudged` (the same patch with its body 1e-12 m aside: a matrix of the same size), and
// then, when the patch does not stick, the projected solve, which reuses the sticking solve's
// factors. `fresh` gets the projected solve alone, after `spacer` (the patch less a point: a matrix
// of another size), so it cannot start from factors of any matrix of its size. The outcomes of
// `fresh` and `reused` must agree to the last bit.
TEST(ContactPatch, ReusedLeastSquaresFactorsGiveTheSameImpulsesBitForBit)
{
    std::mt19937_64 rng(20261202);
    const PassSettings settings;
    int compared = 0;
    for (int trial = 0; trial < 2000; ++trial)
    {
        const std::mt19937_64 start = rng;
        const auto build = [&]
        {
            std::mt19937_64 same = start;
            return randomPatch(same);
        };
        RandomPatch reused = randomPatch(rng);
        const Real eps = randomRestitution(rng);
        RandomPatch fresh = build();
        RandomPatch nudged = build();
        nudged.bodies[0].predicted.position.x() += 1e-12;
        RandomPatch spacer = build();
        spacer.points.pop_back();

        applyPatchImpulse(nudged.bodies[0], nudged.points, eps, settings);
        if (applyPatchImpulse(reused.bodies[0], reused.points, eps, settings))
        {
            continue; // the patch stuck: there is no projected solve to compare
        }
        const bool reusedApplied = applyProjectedPatchImpulse(reused.bodies[0], reused.points, eps, settings);
        applyPatchImpulse(spacer.bodies[0], spacer.points, eps, settings);
        applyProjectedPatchImpulse(spacer.bodies[0], spacer.points, eps, settings);
        EXPECT_EQ(applyProjectedPatchImpulse(fresh.bodies[0], fresh.points, eps, settings), reusedApplied)
            << "trial " << trial;
        ++compared;
        for (std::size_t b = 0; b < fresh.bodies.size(); ++b)
        {
            for (int i = 0; i < 3; ++i)
            {
                ASSERT_EQ(reused.bodies[b].linearVelocity[i], fresh.bodies[b].linearVelocity[i])
                    << "trial " << trial << ", body " << b;
                ASSERT_EQ(reused.bodies[b].angularMomentum[i], fresh.bodies[b].angularMomentum[i])
                    << "trial " << trial << ", body " << b;
            }
        }
    }
    EXPECT_GE(compared, 1000) << "too few patches reached the projected solve to test the reuse";
}

// Relative velocity of the body against its partner at a patch point, at the predicted poses.
Vec3 relativeAt(const RigidBody& body, const PatchPoint& point)
{
    return body.pointVelocity(point.contact.point, body.predicted) -
           point.other->pointVelocity(point.contact.point, point.other->predicted);
}

// A body of a box's inertia (m/150 to m/50 per axis, a 0.2 m cube has m/150), falling at 1-3 m/s,
// sliding and turning slowly enough that even the ramp's first sweep presses on every point.
RigidBody fallingBoxLikeBody(std::mt19937_64& rng, const Vec3& position)
{
    RigidBody body = randomBody(rng, position, true);
    body.principalInertia =
        body.mass * Vec3(Uniform(0.003, 0.01)(rng), Uniform(0.003, 0.01)(rng), Uniform(0.003, 0.01)(rng));
    body.invPrincipalInertia = body.principalInertia.cwiseInverse();
    body.invInertiaWorld = body.rotation * body.invPrincipalInertia.asDiagonal() * body.rotation.transpose();
    body.linearVelocity = Vec3(Uniform(-0.01, 0.01)(rng), Uniform(-0.01, 0.01)(rng), Uniform(-3.0, -1.0)(rng));
    body.angularVelocity = Vec3(Uniform(-0.02, 0.02)(rng), Uniform(-0.02, 0.02)(rng), Uniform(-0.02, 0.02)(rng));
    body.angularMomentum = body.invInertiaWorld.inverse() * body.angularVelocity;
    return body;
}

// A support at rest below the patch: static, or dynamic with a box's inertia.
RigidBody supportAtRest(std::mt19937_64& rng, const Vec3& position, bool dynamic)
{
    RigidBody support = fallingBoxLikeBody(rng, position);
    support.dynamic = dynamic;
    support.linearVelocity.setZero();
    support.angularVelocity.setZero();
    support.angularMomentum.setZero();
    return support;
}

// Applies the sticking solve to a patch whose points all face up (friction high enough for any
// sticking impulse) and checks that every point reaches its target: u_n' = -eps u_n for eps >= 0,
// |eps| times the patch's mean approach for the contact ramp's eps < 0, and no slip.
void expectEveryTargetMet(RigidBody& body, const std::vector<PatchPoint>& patch, Real eps, int trial)
{
    std::vector<Real> approach;
    Real scale = 0.0;
    Real mean = 0.0;
    for (const PatchPoint& point : patch)
    {
        approach.push_back(relativeAt(body, point).z());
        scale = std::max(scale, relativeAt(body, point).norm());
        mean += approach.back() / static_cast<Real>(patch.size());
    }
    ASSERT_TRUE(applyPatchImpulse(body, patch, eps, PassSettings{})) << "trial " << trial;
    for (std::size_t k = 0; k < patch.size(); ++k)
    {
        // the solve is a few dozen products of order-one numbers: round-off far below 1e-12
        const Real target = eps >= 0.0 ? -eps * approach[k] : -eps * mean;
        const Vec3 after = relativeAt(body, patch[k]);
        ASSERT_NEAR(after.z(), target, 1e-12 * scale) << "trial " << trial << ", point " << k;
        ASSERT_NEAR(after.x(), 0.0, 1e-12 * scale) << "trial " << trial << ", point " << k;
        ASSERT_NEAR(after.y(), 0.0, 1e-12 * scale) << "trial " << trial << ", point " << k;
    }
}

// A patch point at `spot` on `support`, its normal straight up, with friction enough to stick.
PatchPoint upwardPoint(const Vec3& spot, RigidBody& support)
{
    PatchPoint point;
    point.other = &support;
    point.contact.point = spot;
    point.contact.normal = Vec3::UnitZ();
    point.friction = 100.0;
    return point;
}

// A box-like body falling onto a support at rest, static or dynamic at even odds, the patch to be
// centred within a centimetre of the foot of the body's centre of mass.
struct Landing
{
    Vec3 centre;
    std::deque<RigidBody> bodies; // the falling body, then its support
};

Landing landingOnSupport(std::mt19937_64& rng)
{
    Landing landing;
    landing.centre = Vec3(Uniform(-0.01, 0.01)(rng), Uniform(-0.01, 0.01)(rng), 0.0);
    landing.bodies.push_back(fallingBoxLikeBody(rng, Vec3(0.0, 0.0, 0.1)));
    landing.bodies.push_back(supportAtRest(rng, landing.centre - Vec3(0.0, 0.0, 0.1), Uniform(0.0, 1.0)(rng) < 0.5));
    return landing;
}

// A body coming down flat onto a face: the corners of a rectangle around the foot of its centre of
// mass and up to five points inside it, normals straight up, the partner static or dynamic, friction
// high enough for any sticking impulse. The targets come from a rigid motion (the normal approach
// varies linearly over the patch), so the sticking solve must meet every one of them: u_n' = -eps u_n
// at each point for eps >= 0, |eps| times the patch's mean approach for the contact ramp's eps < 0,
// and no slip.
TEST(ContactPatch, AFaceLandingFlatMeetsEveryPointsTargetAtOnce)
{
    std::mt19937_64 rng(20261201);
    for (int trial = 0; trial < 2000; ++trial)
    {
        Landing landing = landingOnSupport(rng);
        const Vec3 half(Uniform(0.05, 0.1)(rng), Uniform(0.05, 0.1)(rng), 0.0);
        std::vector<Vec3> spots;
        for (const Real sx : {-1.0, 1.0})
        {
            for (const Real sy : {-1.0, 1.0})
            {
                spots.push_back(landing.centre + Vec3(sx * half.x(), sy * half.y(), 0.0));
            }
        }
        // more points inside, in pairs about the centre (the loads of least norm are linear over
        // the patch, so points bunched to one side would shift them until a far corner pulls)
        const int pairs = std::uniform_int_distribution<int>(0, 2)(rng);
        for (int k = 0; k < pairs; ++k)
        {
            const Vec3 offset(Uniform(-1.0, 1.0)(rng) * half.x(), Uniform(-1.0, 1.0)(rng) * half.y(), 0.0);
            spots.push_back(landing.centre + offset);
            spots.push_back(landing.centre - offset);
        }
        if (Uniform(0.0, 1.0)(rng) < 0.5)
        {
            spots.push_back(landing.centre);
        }
        std::vector<PatchPoint> patch;
        for (const Vec3& spot : spots)
        {
            patch.push_back(upwardPoint(spot, landing.bodies[1]));
        }
        expectEveryTargetMet(landing.bodies[0], patch, Uniform(-0.9, 1.0)(rng), trial);
    }
}

// A body coming down onto an edge: two points, the ends of a horizontal edge below its centre of
// mass (the two-point rigid-motion solve). Along a line the targets of a rigid approach are
// themselves a rigid motion, so the sticking solve must meet both.
TEST(ContactPatch, AnEdgeLandingMeetsBothPointsTargetsAtOnce)
{
    std::mt19937_64 rng(20261203);
    for (int trial = 0; trial < 2000; ++trial)
    {
        Landing landing = landingOnSupport(rng);
        const Real angle = Uniform(0.0, 2.0 * M_PI)(rng);
        const Vec3 half = Uniform(0.02, 0.15)(rng) * Vec3(std::cos(angle), std::sin(angle), 0.0);
        const std::vector<PatchPoint> patch{upwardPoint(landing.centre + half, landing.bodies[1]),
                                            upwardPoint(landing.centre - half, landing.bodies[1])};
        expectEveryTargetMet(landing.bodies[0], patch, Uniform(-0.9, 1.0)(rng), trial);
    }
}

// A lintel coming down across two supports, one static and one dynamic at rest, two points on each.
// The points move with two relative motions, not one: re-spreading the load as over one rigid
// contact would shift it between the supports and miss the free one's target, so the sticking solve
// must leave the patch alone, and the projected solve, which moves both, must stop every point.
TEST(ContactPatch, ALintelOnAStaticAndAMovableSupportIsStoppedAtEveryPoint)
{
    std::mt19937_64 rng(3122026);
    const PassSettings settings;
    for (int trial = 0; trial < 1000; ++trial)
    {
        const Real span = Uniform(0.1, 0.3)(rng);
        const Real width = Uniform(0.02, 0.1)(rng);
        std::deque<RigidBody> bodies;
        bodies.push_back(fallingBoxLikeBody(rng, Vec3(0.0, 0.0, 0.1)));
        bodies.push_back(supportAtRest(rng, Vec3(-span, 0.0, -0.1), false));
        bodies.push_back(supportAtRest(rng, Vec3(span, 0.0, -0.1), true));
        std::vector<PatchPoint> patch;
        for (const Real side : {-1.0, 1.0})
        {
            RigidBody& support = bodies[side < 0.0 ? 1 : 2];
            patch.push_back(upwardPoint(Vec3(side * span, -width, 0.0), support));
            patch.push_back(upwardPoint(Vec3(side * span, width, 0.0), support));
        }
        RigidBody& lintel = bodies[0];
        const Vec3 velocity = lintel.linearVelocity;
        ASSERT_FALSE(applyPatchImpulse(lintel, patch, 0.0, settings)) << "trial " << trial;
        ASSERT_EQ(lintel.linearVelocity, velocity) << "trial " << trial;
        const Real scale = velocity.norm();
        ASSERT_TRUE(applyProjectedPatchImpulse(lintel, patch, 0.0, settings)) << "trial " << trial;
        for (std::size_t k = 0; k < patch.size(); ++k)
        {
            // the solve iterates to 1e-9 of the largest load
            EXPECT_NEAR(relativeAt(lintel, patch[k]).norm(), 0.0, 1e-8 * scale) << "trial " << trial << ", point " << k;
        }
    }
}

// A ball coming straight down into the hollow of three balls of its mass, each static or free,
// one point on each, friction high enough to hold it: the projected solve must stop the ball
// against every partner, in the normal and the tangent directions.
TEST(ContactPatch, ABallIntoTheHollowOfThreeBallsIsStoppedAtEveryPoint)
{
    std::mt19937_64 rng(1122026);
    const PassSettings settings;
    const auto ball = [](const Vec3& position, bool dynamic)
    {
        RigidBody body;
        body.dynamic = dynamic;
        body.position = position;
        body.predicted = Pose::from(position, Quat::Identity());
        if (dynamic)
        {
            body.mass = 1.0;
            body.invMass = 1.0;
            body.principalInertia = Vec3::Constant(0.4 * 0.01); // 2/5 m r^2, r = 0.1
            body.invPrincipalInertia = body.principalInertia.cwiseInverse();
            body.invInertiaWorld = body.invPrincipalInertia.asDiagonal();
        }
        return body;
    };
    for (int trial = 0; trial < 1000; ++trial)
    {
        std::deque<RigidBody> bodies;
        bodies.push_back(ball(Vec3(0.0, 0.0, 0.1633), true)); // touching three balls 0.2 apart
        RigidBody& falling = bodies[0];
        falling.linearVelocity = Vec3(Uniform(-0.05, 0.05)(rng), Uniform(-0.05, 0.05)(rng), Uniform(-2.0, -0.5)(rng));
        std::vector<PatchPoint> patch;
        for (int k = 0; k < 3; ++k)
        {
            const Real angle = (2.0 * k + Uniform(-0.1, 0.1)(rng)) * M_PI / 3.0;
            const Vec3 centre(0.1155 * std::cos(angle), 0.1155 * std::sin(angle), 0.0);
            bodies.push_back(ball(centre, Uniform(0.0, 1.0)(rng) < 0.7));
            PatchPoint point;
            point.other = &bodies.back();
            point.contact.point = 0.5 * (falling.position + centre);
            point.contact.normal = (falling.position - centre).normalized();
            point.friction = 100.0;
            patch.push_back(point);
        }
        const Real scale = falling.linearVelocity.norm();
        ASSERT_TRUE(applyProjectedPatchImpulse(falling, patch, 0.0, settings)) << "trial " << trial;
        for (std::size_t k = 0; k < patch.size(); ++k)
        {
            // the solve iterates to 1e-9 of the largest load
            EXPECT_NEAR(relativeAt(falling, patch[k]).norm(), 0.0, 1e-8 * scale)
                << "trial " << trial << ", point " << k;
        }
    }
}

// A cube of the ten-thousand-cube pile in the shock sweep (box_pile_10000, step 2 793 of a run):
// three points on three frozen neighbours, pinched between faces of nearly opposite normals. The
// least-squares start asked for loads of 1e10 N s, which Gauss-Seidel cancelled down to 2 848 m/s
// and 20 000 rad/s of the cube, and the energy check by the work of the impulses, lost in their
// round-off, let that through. The patch's inputs, exactly as they were:
TEST(ContactPatch, APinchedCubeOnFrozenNeighboursGainsNoKineticEnergy)
{
    PassSettings settings;
    settings.dt = 0x1.0624dd2f1a9fcp-10;
    settings.lookahead = settings.dt;
    settings.threshold = 0x1.0c6f7a0b5ed8dp-20;
    settings.gravity = Vec3(0.0, 0.0, -0x1.39eb851eb851fp+3);

    RigidBody cube;
    cube.mass = 1.0;
    cube.invMass = 1.0;
    cube.principalInertia = Vec3::Constant(0x1.b4e81b4e81b5p-8);
    cube.invPrincipalInertia = cube.principalInertia.cwiseInverse();
    cube.position = Vec3(-0x1.9c68a731605acp+0, 0x1.36edc0f84ae02p-1, 0x1.85d3129006b48p+2);
    cube.orientation = Quat(0x1.b0108e7a3a65fp-1, 0x1.e114ca2b4f764p-2, -0x1.00a188a505807p-2, -0x1.0e0c508701406p-4);
    cube.rotation = cube.orientation.toRotationMatrix();
    cube.linearVelocity = Vec3(-0x1.86f3fb44313bep-3, 0x1.8edf7dc07c28bp-4, -0x1.33a7a71e40bc4p-1);
    cube.angularMomentum = Vec3(0x1.825b9c0eb8e1dp-11, -0x1.4e5a8971c8d1cp-7, -0x1.ee3797b7b52aep-8);
    updateDerivedQuantities(cube);
    cube.predicted =
        Pose::from(Vec3(-0x1.9c7529e15a584p+0, 0x1.36fa8489a0e83p-1, 0x1.85c93a40f34e1p+2),
                   Quat(0x1.afef13ba760a4p-1, 0x1.e1090763c192bp-2, -0x1.018f7f1327e5dp-2, -0x1.0e96482ab86c4p-4));

    struct Neighbour
    {
        Vec3 point, normal;
        Real phi;
        Vec3 velocity, angularVelocity, predictedPosition;
    };
    const std::array<Neighbour, 3> neighbours = {{
        {Vec3(-0x1.84feef0547f08p+0, 0x1.032c3cb545858p-1, 0x1.833c37cb1f759p+2),
         Vec3(-0x1.0bf03ebe889cbp-3, 0x1.1ac8d1f0b07f4p-1, 0x1.a5886e5aa59a5p-1), -0x1.dfdf58d1a2de3p-23,
         Vec3(-0x1.2c36260d628a6p-7, -0x1.a4325067a710dp-6, -0x1.b008a7ec8422dp-2),
         Vec3(-0x1.888791588ef1fp-6, -0x1.f7135e39a524dp-1, -0x1.7278e3d02c25bp-3),
         Vec3(-0x1.85049b4c16d78p+0, 0x1.124adf59802a2p-1, 0x1.7a16b391cc588p+2)},
        {Vec3(-0x1.8f93be575e45p+0, 0x1.c4461f113edaap-2, 0x1.8595c9c6a5957p+2),
         Vec3(0x1.27dfc3e078b99p-3, 0x1.ac11e9bba9cfap-1, -0x1.0efa37805fe58p-1), -0x1.01aac74bp-19,
         Vec3(-0x1.81076f30e1151p-3, 0x1.6ed78227096ecp-5, -0x1.7858816be4caep-2),
         Vec3(-0x1.56862f15fc3e8p-4, 0x1.e82ab0aff4ec9p-2, 0x1.1abbd05a4663p+0),
         Vec3(-0x1.a1739fbb8f2a5p+0, 0x1.6d1604f8e1621p-2, 0x1.87d96b00d77d2p+2)},
        {Vec3(-0x1.76abc67fc260ap+0, 0x1.2fe572980951dp-1, 0x1.800dd0bfb5addp+2),
         Vec3(-0x1.2d62ea7dda08cp-1, -0x1.6c04c0bfa12dp-1, 0x1.89f53fb63fd79p-2), -0x1.0435397fp-15,
         Vec3(0x1.9e40bacae279ep-7, -0x1.09b4d504933fap-5, -0x1.3bd497002640ap-2),
         Vec3(0x1.68e45527153ddp-2, -0x1.0986045c0d681p-1, -0x1.64f05d43dbdb2p-1),
         Vec3(-0x1.7d82d5f4f8e9ap+0, 0x1.85195311ed629p-1, 0x1.807d44d2f7802p+2)},
    }};
    std::deque<RigidBody> frozen;
    std::vector<PatchPoint> patch;
    for (const Neighbour& neighbour : neighbours)
    {
        RigidBody& other = frozen.emplace_back();
        other.frozen = true; // the shock sweep's lower level: immovable
        other.linearVelocity = neighbour.velocity;
        other.angularVelocity = neighbour.angularVelocity;
        other.predicted.position = neighbour.predictedPosition;
        PatchPoint point;
        point.contact.point = neighbour.point;
        point.contact.normal = neighbour.normal;
        point.contact.phi = neighbour.phi;
        point.other = &other;
        point.friction = 0.5;
        patch.push_back(point);
    }

    const Real before = kineticEnergy(cube);
    applyProjectedPatchImpulse(cube, patch, 0.0, settings);
    const Real after = kineticEnergy(cube);
    ASSERT_TRUE(std::isfinite(after));
    EXPECT_LE(after, before * (1.0 + kEnergyTolerance)) << "from " << before << " J to " << after << " J";
    EXPECT_LT(cube.linearVelocity.norm(), 1.0) << "it was moving at 0.64 m/s";
}

} // namespace
} // namespace impulse
