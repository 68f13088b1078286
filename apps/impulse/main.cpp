// SPDX-License-Identifier: MIT
// The impulse command-line tool.
#include "run_command.hpp"
#include "see_commands.hpp"

#include <CLI/CLI.hpp>

int main(int argc, char** argv)
{
    CLI::App app{"impulse: rigid bodies with exact restitution, Coulomb friction and stacking\n"
                 "(the separated collision / contact time step of Guendelman, Bridson & Fedkiw 2003)"};
    app.require_subcommand(1);

    impulse::app::RunOptions run;
    CLI::App* runCommand = app.add_subcommand("run", "Simulate a scene file and optionally write its trajectory");
    runCommand->add_option("scene", run.scenePath, "Scene file (JSON, see docs/scene-format.md)")->required();
    runCommand->add_option("--dt", run.dt, "Time step in seconds (overrides the scene's dt)")
        ->check(CLI::PositiveNumber);
    runCommand->add_option("--duration", run.duration, "Simulated time in seconds (overrides the scene's duration)")
        ->check(CLI::NonNegativeNumber);
    runCommand->add_option("--out", run.outPath,
                           "Write the trajectory CSV here: t,body,x,y,z,qw,qx,qy,qz,vx,vy,vz,wx,wy,wz, "
                           "dynamic bodies numbered from 0 in file order");
    runCommand->add_option("--every", run.every, "Write every N-th step (the first and last are always written)")
        ->check(CLI::PositiveNumber);
    runCommand
        ->add_option("--scheme", run.scheme,
                     "Order of the step: guendelman (collision, velocity, contact, position; the default) or "
                     "traditional (velocity and position, then collisions and contacts)")
        ->check(CLI::IsMember({"guendelman", "traditional"}));
    runCommand
        ->add_option("--shock-propagation", run.shockPropagation,
                     "End the contact pass with a shock-propagation sweep: on (the default) or off")
        ->check(CLI::IsMember({"on", "off"}));
    runCommand
        ->add_option("--restitution-threshold", run.restitutionThreshold,
                     "Resolve collisions approaching slower than this speed (m/s) with restitution 0; "
                     "default none")
        ->check(CLI::NonNegativeNumber);

    const impulse::app::SeeCommands see(app);

    try
    {
        app.parse(argc, argv);
    }
    catch (const CLI::ParseError& error)
    {
        // usage errors exit 2, like a scene that cannot be used
        const int code = app.exit(error);
        return code == 0 ? 0 : 2;
    }
    if (const std::optional<int> code = see.runChosen())
    {
        return *code;
    }
    return impulse::app::runScene(run);
}
