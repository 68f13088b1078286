// SPDX-License-Identifier: MIT
// A box dropped onto the ground comes to rest; pushed sideways below the friction limit it stays,
// and above it it slides. Prints the box's state at each stage. Needs impulse::core alone.
//
//   resting_box
#include <impulse/impulse.hpp>

#include <cmath>
#include <cstdio>

namespace
{

void print(const char* what, const impulse::World& world, impulse::BodyId box)
{
    const impulse::BodyState s = world.state(box);
    std::printf("%-34s t %5.2f s  position (%+.6f, %+.6f, %+.6f) m  velocity (%+.2e, %+.2e, %+.2e) m/s\n", what,
                world.time(), s.position.x(), s.position.y(), s.position.z(), s.linearVelocity.x(),
                s.linearVelocity.y(), s.linearVelocity.z());
}

} // namespace

int main()
{
    impulse::World world({.gravity = {0.0, 0.0, -9.81}});
    const impulse::MaterialId wood = world.createMaterial({.restitution = 0.2, .friction = 0.5});
    world.createBody({.type = impulse::BodyType::Static, .shape = impulse::Plane{}, .material = wood});
    const impulse::BodyId box = world.createBody(
        {.shape = impulse::Box{{0.1, 0.1, 0.1}}, .material = wood, .mass = 2.0, .position = {0.0, 0.0, 0.5}});
    const impulse::StepOptions options{.dt = 1e-3};
    const auto run = [&](double seconds, double push)
    {
        for (int k = 0; k < static_cast<int>(std::lround(seconds / options.dt)); ++k)
        {
            world.applyForce(box, {push, 0.0, 0.0}); // cleared after each step
            world.step(options);
        }
    };

    print("dropped from 0.5 m:", world, box);
    run(1.0, 0.0);
    print("resting on the ground:", world, box);
    const double resting = world.state(box).position.z();
    run(1.0, 0.5 * 0.5 * 2.0 * 9.81); // half of mu m g: friction holds it
    print("pushed with half of mu m g:", world, box);
    const double held = world.state(box).linearVelocity.norm();
    run(1.0, 2.0 * 0.5 * 2.0 * 9.81); // twice mu m g: a = mu g = 4.905 m/s^2
    print("pushed with twice mu m g for 1 s:", world, box);

    const bool ok = std::abs(resting - 0.1) < 1e-3 && held < 1e-9 &&
                    std::abs(world.state(box).linearVelocity.x() - 0.5 * 9.81) < 1e-3;
    std::printf("%s\n",
                ok ? "as expected: at rest at z = 0.1 m, held by friction, then sliding at mu g" : "NOT as expected");
    return ok ? 0 : 1;
}
