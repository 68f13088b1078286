// SPDX-License-Identifier: MIT
// The patch solves of contact_patch.hpp against the conservation law they must keep: a patch
// impulse with restitution between 0 and 1 never adds kinetic energy, however badly conditioned the
// patch. The random patches below are built to be nearly singular (points bunched together, normals
// from nearly parallel to pointing every way, partners shared between points), the case in which a
// least-squares warm start can ask for impulses far larger than the contact needs, and in which
// restitution targets at a pinch are out of reach.
#include "dynamics/contact_patch.hpp"

#include <gtest/gtest.h>

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

} // namespace
} // namespace impulse
