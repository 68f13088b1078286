// SPDX-License-Identifier: MIT
// The World API in one program (docs/api.md walks through it): forces and torques, an impulse at a
// point, an inertia tensor of one's own, collision filtering and removal. Each result is printed
// beside the value physics gives for it.
//
//   api_tour
#include <impulse/impulse.hpp>

#include <cmath>
#include <cstdio>
#include <stdexcept>

int main()
{
    using namespace impulse;
    World world({.gravity = {0.0, 0.0, -9.81}});
    const MaterialId steel = world.createMaterial({.restitution = 0.5, .friction = 0.4});
    const BodyId ground = world.createBody({.type = BodyType::Static, .shape = Plane{}, .material = steel});
    const StepOptions options{.dt = 1e-3};
    bool ok = true;
    const auto report = [&](const char* what, double got, double expected, double tolerance)
    {
        const bool good = std::abs(got - expected) <= tolerance;
        ok = ok && good;
        std::printf("%-46s %12.6f  (expected %.6f)%s\n", what, got, expected, good ? "" : "  <-- off");
    };

    // 1. A probe lifted by a thrust of 1.5 times its weight for one second: a = g / 2 upwards.
    const BodyId probe =
        world.createBody({.shape = Sphere{0.1}, .material = steel, .mass = 2.0, .position = {0.0, 0.0, 1.0}});
    for (int k = 0; k < 1000; ++k)
    {
        world.applyForce(probe, {0.0, 0.0, 1.5 * 2.0 * 9.81}); // for this step only
        world.step(options);
    }
    report("probe: vertical speed after 1 s (m/s)", world.state(probe).linearVelocity.z(), 0.5 * 9.81, 1e-9);

    // 2. A plate with a mass distribution of its own: a tensor with products of inertia.
    Mat3 tensor;
    tensor << 0.020, 0.004, 0.0, //
        0.004, 0.030, 0.0,       //
        0.0, 0.0, 0.045;
    const BodyId plate = world.createBody({.shape = Box{{0.2, 0.15, 0.01}},
                                           .material = steel,
                                           .mass = 3.0,
                                           .position = {2.0, 0.0, 3.0},
                                           .filter = {.group = 2, .mask = ~2U}}); // plates ignore plates
    world.setMassProperties(plate, 3.0, tensor);
    // a kick at a corner: v += J / m, L += r x J
    const Vec3 corner = world.state(plate).position + Vec3(0.2, 0.15, 0.0);
    world.applyImpulse(plate, {0.0, 0.0, 0.6}, corner);
    report("plate: speed after the kick (m/s)", world.state(plate).linearVelocity.z(), 0.6 / 3.0, 1e-15);
    const Vec3 spin = world.state(plate).angularVelocity;
    const Vec3 expectedSpin = tensor.inverse() * Vec3(0.2, 0.15, 0.0).cross(Vec3(0.0, 0.0, 0.6));
    report("plate: spin about x after the kick (rad/s)", spin.x(), expectedSpin.x(), 1e-12);
    std::printf("%-46s %12.6f %.6f %.6f\n", "plate: principal moments (kg m^2)", world.principalInertia(plate).x(),
                world.principalInertia(plate).y(), world.principalInertia(plate).z());

    // 3. A ghost: a second plate, in the same group, falls through the first one.
    const BodyId ghost = world.createBody({.shape = Box{{0.2, 0.15, 0.01}},
                                           .material = steel,
                                           .mass = 1.0,
                                           .position = {2.0, 0.0, 3.5},
                                           .filter = {.group = 2, .mask = ~2U}});
    world.setCollisionEnabled(ghost, ground, false); // and through the ground
    for (int k = 0; k < 1000; ++k)
    {
        world.step(options);
    }
    report("ghost: height after 1 s of free fall (m)", world.state(ghost).position.z(),
           3.5 - 9.81 * 1e-6 * 1000 * 1001 / 2, 1e-9);

    // 4. Removing the probe: the others keep their handles, the energies no longer count it.
    const double before = world.kineticEnergy();
    const double probeEnergy = 0.5 * 2.0 * world.state(probe).linearVelocity.squaredNorm();
    world.removeBody(probe);
    report("kinetic energy less the probe's (J)", world.kineticEnergy(), before - probeEnergy, 1e-9);
    try
    {
        world.applyForce(probe, {1.0, 0.0, 0.0});
        ok = false;
    }
    catch (const std::invalid_argument& refused)
    {
        std::printf("%-46s %s\n", "a force on the removed probe:", refused.what());
    }
    std::printf("%s\n", ok ? "all as expected" : "NOT as expected");
    return ok ? 0 : 1;
}
