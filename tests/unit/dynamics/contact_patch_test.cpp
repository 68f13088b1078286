// SPDX-License-Identifier: MIT
// The patch solves of contact_patch.hpp against the conservation law they must keep: a patch
// impulse with restitution between 0 and 1 never adds kinetic energy, however badly conditioned the
// patch. The random patches below are built to be nearly singular (points bunched together, normals
// from nearly parallel to pointing every way, partners shared between points), the case in which a
// least-squares warm start can ask for impulses far larger than the contact needs, and in which
// restitution targets at a pinch are out of reach.
#include "dynamics/contact_patch.hpp"

#include <gtest/gtest.h>

#include <algorithm>
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

// Relative velocity of the body against its partner at a patch point, at the predicted poses.
Vec3 relativeAt(const RigidBody& body, const PatchPoint& point)
{
    return body.pointVelocity(point.contact.point, body.predicted) -
           point.other->pointVelocity(point.contact.point, point.other->predicted);
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
    const PassSettings settings;
    for (int trial = 0; trial < 2000; ++trial)
    {
        // the body and, below the patch, a static or resting dynamic partner, each with the
        // inertia of a body about the patch's size (a 0.2 m box has m/150 per axis)
        const Vec3 centre(Uniform(-0.01, 0.01)(rng), Uniform(-0.01, 0.01)(rng), 0.0);
        std::deque<RigidBody> bodies;
        bodies.push_back(randomBody(rng, Vec3(0.0, 0.0, 0.1), true));
        bodies.push_back(randomBody(rng, centre - Vec3(0.0, 0.0, 0.1), Uniform(0.0, 1.0)(rng) < 0.5));
        for (RigidBody& b : bodies)
        {
            if (b.dynamic)
            {
                b.principalInertia =
                    b.mass * Vec3(Uniform(0.003, 0.01)(rng), Uniform(0.003, 0.01)(rng), Uniform(0.003, 0.01)(rng));
                b.invPrincipalInertia = b.principalInertia.cwiseInverse();
                b.invInertiaWorld = b.rotation * b.invPrincipalInertia.asDiagonal() * b.rotation.transpose();
            }
        }
        bodies[1].linearVelocity.setZero();
        bodies[1].angularVelocity.setZero();
        bodies[1].angularMomentum.setZero();
        RigidBody& body = bodies[0];
        // falling at 1-3 m/s, sliding and turning slowly enough that even the ramp's first sweep,
        // which removes a tenth of the approach but all of the tilt and slip, presses on every point
        body.linearVelocity = Vec3(Uniform(-0.01, 0.01)(rng), Uniform(-0.01, 0.01)(rng), Uniform(-3.0, -1.0)(rng));
        body.angularVelocity = Vec3(Uniform(-0.02, 0.02)(rng), Uniform(-0.02, 0.02)(rng), Uniform(-0.02, 0.02)(rng));
        body.angularMomentum = body.invInertiaWorld.inverse() * body.angularVelocity;
        const Vec3 half(Uniform(0.05, 0.1)(rng), Uniform(0.05, 0.1)(rng), 0.0);
        std::vector<Vec3> spots;
        for (const Real sx : {-1.0, 1.0})
        {
            for (const Real sy : {-1.0, 1.0})
            {
                spots.push_back(centre + Vec3(sx * half.x(), sy * half.y(), 0.0));
            }
        }
        // more points inside, in pairs about the centre (the loads of least norm are linear over
        // the patch, so points bunched to one side would shift them until a far corner pulls)
        const int pairs = std::uniform_int_distribution<int>(0, 2)(rng);
        for (int k = 0; k < pairs; ++k)
        {
            const Vec3 offset(Uniform(-1.0, 1.0)(rng) * half.x(), Uniform(-1.0, 1.0)(rng) * half.y(), 0.0);
            spots.push_back(centre + offset);
            spots.push_back(centre - offset);
        }
        if (Uniform(0.0, 1.0)(rng) < 0.5)
        {
            spots.push_back(centre);
        }
        std::vector<PatchPoint> patch;
        std::vector<Real> approach;
        Real scale = 0.0;
        for (const Vec3& spot : spots)
        {
            PatchPoint point;
            point.other = &bodies[1];
            point.contact.point = spot;
            point.contact.normal = Vec3::UnitZ();
            point.friction = 100.0;
            patch.push_back(point);
            approach.push_back(relativeAt(body, point).z());
            scale = std::max(scale, relativeAt(body, point).norm());
        }
        const Real eps = Uniform(-0.9, 1.0)(rng);
        ASSERT_TRUE(applyPatchImpulse(body, patch, eps, settings)) << "trial " << trial;
        Real mean = 0.0;
        for (const Real un : approach)
        {
            mean += un / static_cast<Real>(approach.size());
        }
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

} // namespace
} // namespace impulse
