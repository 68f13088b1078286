// SPDX-License-Identifier: MIT
// Mass properties of the analytic solids against the textbook formulas, and the mass and inertia
// that World::createBody derives from them.
#include <impulse/impulse.hpp>

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <numbers>

namespace impulse
{
namespace
{

// The formulas are a handful of multiplications: agreement to a few ulps is expected, so the
// tolerances below are relative 1e-14 (about 50 ulps).
constexpr Real kRelTol = 1e-14;

void expectRelNear(Real actual, Real expected)
{
    EXPECT_NEAR(actual, expected, kRelTol * std::abs(expected));
}

void expectVecRelNear(const Vec3& actual, const Vec3& expected)
{
    for (int i = 0; i < 3; ++i)
    {
        expectRelNear(actual[i], expected[i]);
    }
}

TEST(MassProperties, SolidSphereInertiaIsTwoFifthsRadiusSquared)
{
    const Real r = 0.7;
    const Vec3 inertia = unitInertia(Sphere{r});
    expectVecRelNear(inertia, Vec3::Constant(2.0 / 5.0 * r * r));
}

TEST(MassProperties, SphereVolumeAndBoundingRadius)
{
    const Real r = 1.3;
    expectRelNear(volume(Sphere{r}), 4.0 / 3.0 * std::numbers::pi * r * r * r);
    expectRelNear(boundingRadius(Sphere{r}), r);
}

TEST(MassProperties, BoxInertiaMatchesFullSideFormula)
{
    // full sides a = 1, b = 2, c = 3: I_x = m (b^2 + c^2) / 12 and so on, with m = 1
    const Box box{Vec3(0.5, 1.0, 1.5)};
    const Real a = 1.0;
    const Real b = 2.0;
    const Real c = 3.0;
    const Vec3 expected((b * b + c * c) / 12.0, (a * a + c * c) / 12.0, (a * a + b * b) / 12.0);
    expectVecRelNear(unitInertia(box), expected);
}

TEST(MassProperties, BoxInertiaMatchesHalfExtentFormula)
{
    const Vec3 h(0.2, 0.9, 0.4);
    const Vec3 expected((h.y() * h.y() + h.z() * h.z()) / 3.0, (h.x() * h.x() + h.z() * h.z()) / 3.0,
                        (h.x() * h.x() + h.y() * h.y()) / 3.0);
    expectVecRelNear(unitInertia(Box{h}), expected);
}

TEST(MassProperties, CubeInertiaIsIsotropicSideSquaredOverSix)
{
    const Real side = 0.8;
    expectVecRelNear(unitInertia(Box{Vec3::Constant(0.5 * side)}), Vec3::Constant(side * side / 6.0));
}

TEST(MassProperties, BoxInertiaObeysTriangleInequality)
{
    // any solid satisfies I_x + I_y >= I_z (equality only for a lamina); a box of positive thickness
    // satisfies it strictly, with I_x + I_y - I_z = 2 m h_z^2 / 3
    const Vec3 h(0.3, 0.7, 0.05);
    const Vec3 inertia = unitInertia(Box{h});
    // the difference cancels most of I_z, so its round-off is relative to I_z, not to the result
    EXPECT_NEAR(inertia.x() + inertia.y() - inertia.z(), 2.0 * h.z() * h.z() / 3.0, kRelTol * inertia.z());
}

TEST(MassProperties, BoxVolumeAndBoundingRadius)
{
    const Box box{Vec3(0.5, 1.0, 1.5)};
    expectRelNear(volume(box), 1.0 * 2.0 * 3.0);
    // the farthest points are the corners
    expectRelNear(boundingRadius(box), std::sqrt(0.25 + 1.0 + 2.25));
}

TEST(MassProperties, PlaneIsUnbounded)
{
    const Plane plane{};
    EXPECT_EQ(volume(plane), std::numeric_limits<Real>::infinity());
    EXPECT_EQ(boundingRadius(plane), std::numeric_limits<Real>::infinity());
    EXPECT_TRUE((unitInertia(plane).array() == std::numeric_limits<Real>::infinity()).all());
}

TEST(MassProperties, WorldBodyWithMassScalesUnitInertia)
{
    World world;
    const MaterialId material = world.createMaterial({});
    BodyDef def;
    def.shape = Box{Vec3(0.5, 1.0, 1.5)};
    def.material = material;
    def.mass = 3.0;
    const BodyId id = world.createBody(def);
    expectRelNear(world.mass(id), 3.0);
    expectVecRelNear(world.principalInertia(id), Vec3(13.0 / 12.0, 10.0 / 12.0, 5.0 / 12.0) * 3.0);
}

TEST(MassProperties, WorldSphereWithDensityHasDensityTimesVolumeMass)
{
    World world;
    const MaterialId material = world.createMaterial({});
    BodyDef def;
    def.shape = Sphere{0.5};
    def.material = material;
    def.density = 1000.0;
    const BodyId id = world.createBody(def);
    const Real expectedMass = 1000.0 * 4.0 / 3.0 * std::numbers::pi * 0.125;
    expectRelNear(world.mass(id), expectedMass);
    expectVecRelNear(world.principalInertia(id), Vec3::Constant(0.4 * expectedMass * 0.25));
}

TEST(MassProperties, WorldBoxWithDensityHasDensityTimesVolumeMass)
{
    World world;
    const MaterialId material = world.createMaterial({});
    BodyDef def;
    def.shape = Box{Vec3(0.5, 1.0, 1.5)};
    def.material = material;
    def.density = 2.0;
    const BodyId id = world.createBody(def);
    const Real expectedMass = 2.0 * 6.0;
    expectRelNear(world.mass(id), expectedMass);
    expectVecRelNear(world.principalInertia(id), Vec3(13.0, 10.0, 5.0));
}

TEST(MassProperties, WorldMassWinsOverDensity)
{
    World world;
    const MaterialId material = world.createMaterial({});
    BodyDef def;
    def.shape = Sphere{1.0};
    def.material = material;
    def.mass = 2.0;
    def.density = 500.0;
    const BodyId id = world.createBody(def);
    expectRelNear(world.mass(id), 2.0);
    expectVecRelNear(world.principalInertia(id), Vec3::Constant(0.8));
}

TEST(MassProperties, WorldInertiaDoesNotDependOnOrientation)
{
    // principal moments are a body-frame property: a rotated body reports the same ones
    World world;
    const MaterialId material = world.createMaterial({});
    BodyDef def;
    def.shape = Box{Vec3(0.2, 0.4, 0.6)};
    def.material = material;
    def.mass = 1.5;
    const BodyId upright = world.createBody(def);
    def.orientation = Quat(Eigen::AngleAxisd(0.7, Vec3(1.0, 2.0, -1.0).normalized()));
    const BodyId tilted = world.createBody(def);
    EXPECT_EQ(world.principalInertia(upright), world.principalInertia(tilted));
}

TEST(MassProperties, WorldStaticBodyHasInfiniteMass)
{
    World world;
    const MaterialId material = world.createMaterial({});
    BodyDef def;
    def.type = BodyType::Static;
    def.shape = Plane{};
    def.material = material;
    const BodyId id = world.createBody(def);
    EXPECT_EQ(world.mass(id), std::numeric_limits<Real>::infinity());
}

} // namespace
} // namespace impulse
