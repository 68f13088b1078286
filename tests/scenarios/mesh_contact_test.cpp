// SPDX-License-Identifier: MIT
// Meshes in contact, short runs: the narrow phase against analytic answers (a ball on a meshed box,
// two meshed bars crossed edge on edge) and a meshed cube bouncing with the restitution asked for.
#include "collision/narrow_phase.hpp"
#include "support/penetration.hpp"

#include <impulse/mesh_shapes.hpp>
#include <impulse/world.hpp>

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <variant>

namespace impulse
{
namespace
{

Mesh meshedBox(const Vec3& half, int subdivisions = 1)
{
    return Mesh{MeshGeometry::build(boxMesh(half, subdivisions))};
}

TEST(MeshContact, BallOnAMeshedBoxTouchesItsFaceAlongTheNormal)
{
    const Mesh box = meshedBox(Vec3(0.5, 0.5, 0.1), 4);
    const Pose boxPose = Pose::from(Vec3::Zero(), Quat::Identity());
    for (const Real gap : {0.0, 1e-7, -1e-3})
    {
        std::vector<ContactPoint> points;
        NarrowPhaseScratch scratch;
        collideShapes(Sphere{0.2}, Pose::from(Vec3(0.13, -0.07, 0.3 + gap), Quat::Identity()), box, boxPose, 1e-6,
                      points, scratch);
        ASSERT_EQ(points.size(), gap < 1e-6 ? 1u : 0u) << "gap " << gap;
        if (!points.empty())
        {
            EXPECT_NEAR(points[0].phi, gap, 1e-14);
            EXPECT_LT((points[0].normal - Vec3::UnitZ()).norm(), 1e-14);
            EXPECT_NEAR(points[0].point.z(), 0.1 + 0.5 * gap, 1e-14);
        }
    }
}

TEST(MeshContact, CrossedEdgesAreCaughtWhereNoVertexIsInside)
{
    // two bars, each turned 45 degrees about its long axis so that an edge faces the other, crossed
    // at right angles and overlapping by 2 mm: every vertex is outside the other bar, so only the
    // edge test can see the contact
    const Real half = 0.05;
    const Real ridge = half * std::sqrt(2.0); // centre to edge of the turned bar
    const Real overlap = 2e-3;
    const Mesh bar = meshedBox(Vec3(0.5, half, half));
    const Pose lower = Pose::from(Vec3::Zero(), Quat(Eigen::AngleAxisd(std::numbers::pi / 4, Vec3::UnitX())));
    const Quat crossed = Quat(Eigen::AngleAxisd(std::numbers::pi / 2, Vec3::UnitZ())) *
                         Quat(Eigen::AngleAxisd(std::numbers::pi / 4, Vec3::UnitX()));
    const Pose upper = Pose::from(Vec3(0.0, 0.0, 2.0 * ridge - overlap), crossed);

    for (const Vec3& v : bar.geometry->vertices())
    {
        ASSERT_GT(bar.geometry->signedDistance(lower.toLocal(upper.toWorld(v))).phi, 0.0);
        ASSERT_GT(bar.geometry->signedDistance(upper.toLocal(lower.toWorld(v))).phi, 0.0);
    }
    std::vector<ContactPoint> points;
    NarrowPhaseScratch scratch;
    collideShapes(bar, upper, bar, lower, 1e-6, points, scratch);
    ASSERT_FALSE(points.empty());
    for (const ContactPoint& point : points)
    {
        // the passage of one ridge through the other: at most the overlap deep, pushing apart vertically
        EXPECT_LT(point.phi, 0.0);
        EXPECT_GT(point.phi, -overlap);
        EXPECT_GT(point.normal.z(), std::cos(std::numbers::pi / 4) - 1e-9);
    }
}

TEST(MeshContact, AnEdgeRunningDeeperThanItsEndInsideIsCaughtAtItsDepth)
{
    // a thin bar whose near end lies just inside a cube of half side 0.1 near its +x face and whose
    // axis runs diagonally in, under the corner region, and out through the +y face: along it the
    // depth min(0.1 - x, 0.1 - y) grows from the end's 0.2-3 mm to 25.8 mm before it leaves. The
    // vertices inside are shallow; the edges from them carry the depth, whichever body is the mesh.
    const Mesh bar = meshedBox(Vec3(0.07, 0.002, 0.002));
    const Quat turn(Eigen::AngleAxisd(0.75 * std::numbers::pi, Vec3::UnitZ())); // bar x along (-1, 1, 0)
    const Vec3 nearEnd(0.0984, 0.05, 0.0);
    const Pose barPose = Pose::from(nearEnd + turn * Vec3(0.07, 0.0, 0.0), turn);
    const Pose cubePose = Pose::from(Vec3::Zero(), Quat::Identity());
    for (const Vec3& v : bar.geometry->vertices())
    {
        const Vec3 p = barPose.toWorld(v);
        const bool inside = p.cwiseAbs().maxCoeff() < 0.1;
        ASSERT_TRUE(!inside || 0.1 - p.cwiseAbs().maxCoeff() < 3.5e-3) << "a vertex inside deeper than 3.5 mm";
    }
    for (const Shape& cube : {Shape(Box{Vec3::Constant(0.1)}), Shape(meshedBox(Vec3::Constant(0.1)))})
    {
        std::vector<ContactPoint> points;
        NarrowPhaseScratch scratch;
        collideShapes(bar, barPose, cube, cubePose, 1e-6, points, scratch);
        Real least = 0.0;
        for (const ContactPoint& point : points)
        {
            least = std::min(least, point.phi);
        }
        // the middle of the passage from the end, 25 mm deep; the ends alone would say 3 mm at most
        EXPECT_LT(least, -0.02) << (std::holds_alternative<Box>(cube) ? "box" : "meshed box");
        EXPECT_GT(least, -0.0258 - 0.003);
    }
}

struct Bounce
{
    Real apex = 0.0;
    Real deepest = 0.0;
    Real fastestSpin = 0.0;
};

// A cube of side 0.2 dropped flat from 1.9 m above its resting height with eps = 0.5, onto the
// ground plane or onto a static slab `ground` whose top is at z = 0.
Bounce dropCube(const Shape& shape, const Shape* ground = nullptr)
{
    World world;
    const MaterialId material = world.createMaterial({0.5, 0.5});
    if (ground == nullptr)
    {
        world.createBody({BodyType::Static, Plane{}, material});
    }
    else
    {
        BodyDef slab{BodyType::Static, *ground, material};
        slab.position = Vec3(0.0, 0.0, -0.1);
        world.createBody(slab);
    }
    BodyDef cube;
    cube.shape = shape;
    cube.material = material;
    cube.mass = 1.0;
    cube.position = Vec3(0.0, 0.0, 2.0);
    const BodyId id = world.createBody(cube);
    Bounce bounce;
    bool landed = false;
    for (int step = 0; step < 1500; ++step)
    {
        world.step(StepOptions{});
        const BodyState s = world.state(id);
        landed = landed || s.linearVelocity.z() > 0.0;
        if (landed)
        {
            bounce.apex = std::max(bounce.apex, s.position.z());
        }
        bounce.deepest = std::max(bounce.deepest, test::deepestPenetration(world).depth);
        bounce.fastestSpin = std::max(bounce.fastestSpin, s.angularVelocity.norm());
    }
    return bounce;
}

TEST(MeshContact, MeshedCubeBouncesLikeTheAnalyticCube)
{
    // the first apex is eps^2 of the drop above the resting height (scene 2's oracle, 1 %), the
    // same as the analytic box's to round-off, with no tilt from one vertex landing first
    const Bounce meshed = dropCube(meshedBox(Vec3::Constant(0.1), 2));
    const Bounce analytic = dropCube(Box{Vec3::Constant(0.1)});
    EXPECT_NEAR((meshed.apex - 0.1) / 1.9, 0.25, 0.01 * 0.25);
    EXPECT_NEAR(meshed.apex, analytic.apex, 1e-12);
    EXPECT_LT(meshed.deepest, 0.01 * 0.2);
    EXPECT_LT(meshed.fastestSpin, 1e-9);
}

TEST(MeshContact, MeshedCubeBouncesOnAMeshedSlabWithTheRestitutionAsked)
{
    // mesh on mesh: the pair keeps the contact layer's least reach, so while the cube falls and
    // bounces the collision pass finds its entry stale every step and captures it anew before
    // screening; the bounce must still be exact (scene 2's oracle, 1 %) and land flat
    const Mesh slab = meshedBox(Vec3(1.0, 1.0, 0.1), 2);
    const Shape ground = slab;
    const Bounce meshed = dropCube(meshedBox(Vec3::Constant(0.1), 2), &ground);
    EXPECT_NEAR((meshed.apex - 0.1) / 1.9, 0.25, 0.01 * 0.25);
    EXPECT_LT(meshed.deepest, 0.01 * 0.2);
    EXPECT_LT(meshed.fastestSpin, 1e-9);
}

} // namespace
} // namespace impulse
