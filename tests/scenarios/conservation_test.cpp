// SPDX-License-Identifier: MIT
// Momentum through collisions and contact, in free space: every impulse acts on both bodies at one
// point, so linear and angular momentum (about any origin) come out of a collision as they went in,
// to round-off, whatever the shapes, spins, restitution and friction.
#include <impulse/mesh_shapes.hpp>
#include <impulse/world.hpp>

#include <gtest/gtest.h>

#include <random>
#include <string>
#include <vector>

namespace impulse
{
namespace
{

constexpr Real kDt = 1e-3;
// Round-off of sums of products of doubles: a relative 1e-12 leaves three to four digits of margin
// over the few hundred impulses of a collision, and is eight orders below the first-order error of
// applying one impulse at two points (dt |v_a - v_b| against the lever arms).
constexpr Real kRelativeTolerance = 1e-12;

// Angular momentum about the world origin: orbital m x cross v plus each body's spin.
Vec3 angularMomentumAboutOrigin(const World& world, const std::vector<BodyId>& bodies)
{
    Vec3 total = Vec3::Zero();
    for (const BodyId id : bodies)
    {
        const BodyState s = world.state(id);
        total += world.mass(id) * s.position.cross(s.linearVelocity) + s.angularMomentum;
    }
    return total;
}

// The size of the terms the total is a sum of: what its round-off is relative to.
Real angularMomentumScale(const World& world, const std::vector<BodyId>& bodies)
{
    Real scale = 0.0;
    for (const BodyId id : bodies)
    {
        const BodyState s = world.state(id);
        scale += world.mass(id) * s.position.norm() * s.linearVelocity.norm() + s.angularMomentum.norm();
    }
    return scale;
}

Real linearMomentumScale(const World& world, const std::vector<BodyId>& bodies)
{
    Real scale = 0.0;
    for (const BodyId id : bodies)
    {
        scale += world.mass(id) * world.state(id).linearVelocity.norm();
    }
    return scale;
}

struct Conservation
{
    Vec3 linearChange = Vec3::Zero();
    Vec3 angularChange = Vec3::Zero();
    Real linearScale = 0.0;
    Real angularScale = 0.0;
    int stepsWithContact = 0;
};

// Steps the world for `seconds` and reports how far the momenta moved from their start.
Conservation runAndMeasure(World& world, const std::vector<BodyId>& bodies, Real seconds)
{
    const Vec3 linear0 = world.linearMomentum();
    const Vec3 angular0 = angularMomentumAboutOrigin(world, bodies);
    Conservation result;
    result.linearScale = linearMomentumScale(world, bodies);
    result.angularScale = angularMomentumScale(world, bodies);
    StepOptions options;
    options.dt = kDt;
    const int steps = static_cast<int>(std::lround(seconds / kDt));
    for (int n = 0; n < steps; ++n)
    {
        world.step(options);
        const StepStats& stats = world.lastStepStats();
        result.stepsWithContact += stats.collisionImpulses > 0 || !world.contacts().empty() ? 1 : 0;
        result.linearChange = result.linearChange.cwiseMax((world.linearMomentum() - linear0).cwiseAbs());
        result.angularChange =
            result.angularChange.cwiseMax((angularMomentumAboutOrigin(world, bodies) - angular0).cwiseAbs());
    }
    return result;
}

TEST(Conservation, ASpinningCubeStrikingAnotherOffCentreKeepsLinearAndAngularMomentum)
{
    World world(WorldDef{.gravity = Vec3::Zero()});
    const MaterialId material = world.createMaterial({.restitution = 0.5, .friction = 0.3});
    const Box cube{Vec3::Constant(0.1)};
    const BodyId striker = world.createBody({.shape = cube,
                                             .material = material,
                                             .mass = 1.0,
                                             .position = Vec3(-0.5, 0.1, 0.0),
                                             .linearVelocity = Vec3(1.0, 0.0, 0.0),
                                             .angularVelocity = Vec3(0.0, 0.0, 5.0)});
    const BodyId target = world.createBody({.shape = cube, .material = material, .mass = 1.0});
    const std::vector<BodyId> bodies{striker, target};

    const Conservation c = runAndMeasure(world, bodies, 1.0);

    ASSERT_GT(world.state(target).linearVelocity.norm(), 0.2) << "the premise: the cubes collide";
    ASSERT_GT(c.stepsWithContact, 0);
    EXPECT_LE(c.linearChange.norm(), kRelativeTolerance * c.linearScale);
    EXPECT_LE(c.angularChange.norm(), kRelativeTolerance * c.angularScale)
        << "change " << c.angularChange.transpose() << " of scale " << c.angularScale;
}

TEST(Conservation, ABallStruckPastItsBoxStrikesTheBallBeyondInTheSameStep)
{
    // Three equal balls in a row, 5 mm apart, the first at 10 m/s: Newton's cradle with gaps. The two
    // at rest have boxes no larger than themselves, so no pair joins them when the step begins. The
    // first hit sends the middle ball at 10 m/s, 10 mm in the step, through the 5 mm gap: it must be
    // paired with the last one within the step and pass the blow on before any position is updated,
    // which leaves the first two at rest and the last at 10 m/s. (Missed, the last would not move and
    // the middle one would end the step 5 mm inside it.)
    World world(WorldDef{.gravity = Vec3::Zero()});
    const MaterialId elastic = world.createMaterial({.restitution = 1.0, .friction = 0.0});
    const Real r = 0.1;
    const Real speed = 10.0;
    const BodyId first = world.createBody({.shape = Sphere{r},
                                           .material = elastic,
                                           .mass = 1.0,
                                           .position = Vec3(-2.0 * r - 0.005, 0.0, 0.0),
                                           .linearVelocity = Vec3(speed, 0.0, 0.0)});
    const BodyId middle = world.createBody({.shape = Sphere{r}, .material = elastic, .mass = 1.0});
    const BodyId last = world.createBody(
        {.shape = Sphere{r}, .material = elastic, .mass = 1.0, .position = Vec3(2.0 * r + 0.005, 0.0, 0.0)});

    StepOptions options;
    options.dt = kDt;
    world.step(options);

    EXPECT_GE(world.lastStepStats().broadPhaseRepeats, 1) << "the premise: the middle ball left its box";
    // the velocities of the cradle to round-off (a few ulps of the speed)
    EXPECT_NEAR(world.state(first).linearVelocity.norm(), 0.0, 1e-12 * speed);
    EXPECT_NEAR(world.state(middle).linearVelocity.norm(), 0.0, 1e-12 * speed);
    EXPECT_NEAR(world.state(last).linearVelocity.x(), speed, 1e-12 * speed);
    const Real gap = (world.state(last).position - world.state(middle).position).norm() - 2.0 * r;
    EXPECT_GT(gap, -0.01 * r) << "the middle ball ends the step inside the last";
}

Shape randomShape(std::mt19937_64& random, int kind, Real size)
{
    std::uniform_real_distribution<Real> aspect(0.5, 1.5);
    switch (kind)
    {
    case 0:
        return Sphere{size};
    case 1:
        return Box{Vec3(size * aspect(random), size * aspect(random), size * aspect(random))};
    case 2:
        return Capsule{0.5 * size, size * aspect(random)};
    case 3:
        // nonconvex: a ring can take another body through its hole
        return Mesh{MeshGeometry::build(torusMesh(size, 0.35 * size, 24, 12))};
    default:
        return Mesh{MeshGeometry::build(boxMesh(Vec3(size, 0.6 * size, 0.8 * size), 2))};
    }
}

Quat randomOrientation(std::mt19937_64& random)
{
    std::normal_distribution<Real> normal;
    return Quat(normal(random), normal(random), normal(random), normal(random)).normalized();
}

Vec3 randomVector(std::mt19937_64& random, Real magnitude)
{
    std::uniform_real_distribution<Real> uniform(-magnitude, magnitude);
    return Vec3(uniform(random), uniform(random), uniform(random));
}

// Three bodies thrown together, spinning, with random shapes, sizes, masses, restitution and friction,
// some at a distance from the origin so that orbital and spin momenta mix; in every other trial each
// body's centre of mass is off its shape's centroid (BodyDef::centerOfMass), by up to half its size.
TEST(Conservation, RandomSpinningCollisionsOfSpheresBoxesCapsulesAndMeshesKeepMomentum)
{
    std::mt19937_64 random(20261205);
    std::uniform_real_distribution<Real> unit(0.0, 1.0);
    int collided = 0;
    constexpr int kTrials = 24;
    for (int trial = 0; trial < kTrials; ++trial)
    {
        World world(WorldDef{.gravity = Vec3::Zero()});
        const Vec3 meetingPoint = randomVector(random, 2.0);
        std::vector<BodyId> bodies;
        for (int k = 0; k < 3; ++k)
        {
            const MaterialId material = world.createMaterial({.restitution = unit(random), .friction = unit(random)});
            const int kind = (trial + k) % 5;
            const Real size = 0.05 + 0.1 * unit(random);
            // placed around the meeting point and aimed at it, a little off so that they strike off-centre
            const Vec3 direction =
                Vec3(std::cos(2.1 * k + trial), std::sin(2.1 * k + trial), 0.3 * (k - 1)).normalized();
            const Vec3 start = meetingPoint + 0.45 * direction;
            const Real speed = 0.5 + 1.5 * unit(random);
            bodies.push_back(world.createBody(
                {.shape = randomShape(random, kind, size),
                 .material = material,
                 .mass = 0.2 + 3.0 * unit(random),
                 .position = start,
                 .orientation = randomOrientation(random),
                 .linearVelocity = -speed * direction + randomVector(random, 0.2),
                 .angularVelocity = randomVector(random, 10.0),
                 .centerOfMass = trial % 2 == 1 ? randomVector(random, 0.5 * size) : Vec3(Vec3::Zero())}));
        }
        std::vector<Vec3> velocities0;
        for (const BodyId id : bodies)
        {
            velocities0.push_back(world.state(id).linearVelocity);
        }

        const Conservation c = runAndMeasure(world, bodies, 0.8);

        bool changed = false;
        for (std::size_t k = 0; k < bodies.size(); ++k)
        {
            changed = changed || (world.state(bodies[k]).linearVelocity - velocities0[k]).norm() > 1e-3;
        }
        collided += changed ? 1 : 0;
        const std::string label = "trial " + std::to_string(trial);
        EXPECT_LE(c.linearChange.norm(), kRelativeTolerance * c.linearScale) << label;
        EXPECT_LE(c.angularChange.norm(), kRelativeTolerance * c.angularScale)
            << label << ": change " << c.angularChange.transpose() << " of scale " << c.angularScale;
    }
    EXPECT_GE(collided, 3 * kTrials / 4) << "the premise: most trials collide";
}

} // namespace
} // namespace impulse
