// SPDX-License-Identifier: MIT
// The impulse command-line tool.
#include "bench_command.hpp"
#include "option_checks.hpp"
#include "replay_command.hpp"
#include "run_command.hpp"
#ifdef IMPULSE_HAVE_MUJOCO
#include "mujoco_commands.hpp"
#endif
#include "see_commands.hpp"

#include <CLI/CLI.hpp>

int main(int argc, char** argv)
{
    CLI::App app{"impulse: rigid bodies with exact restitution, Coulomb friction and stacking\n"
                 "(the separated collision / contact time step of Guendelman, Bridson & Fedkiw 2003)"};
    app.require_subcommand(1);

    impulse::app::RunOptions run;
    CLI::App* runCommand = app.add_subcommand("run", "Simulate a scene file and optionally write its trajectory");
    runCommand
        ->add_option("scene", run.scenePath,
                     "Scene file (JSON, see docs/scene-format.md), or an MJCF model (.xml, .mjcf; docs/mujoco.md)")
        ->required();
    runCommand->add_option("--dt", run.dt, "Time step in seconds (overrides the scene's dt)")
        ->check(impulse::app::positiveNumber());
    runCommand->add_option("--duration", run.duration, "Simulated time in seconds (overrides the scene's duration)")
        ->check(impulse::app::nonNegativeNumber());
    runCommand->add_option("--out", run.outPath,
                           "Write the trajectory CSV here: t,body,x,y,z,qw,qx,qy,qz,vx,vy,vz,wx,wy,wz, "
                           "dynamic bodies numbered from 0 in file order");
    runCommand->add_option("--every", run.every, "Write every N-th step (the first and last are always written)")
        ->check(impulse::app::wholeNumber(1, 1000000000));
    runCommand
        ->add_option("--time-limit", run.timeLimit,
                     "Stop after this many seconds of wall time, with the state reached as the last sample "
                     "(Ctrl-C and SIGTERM stop the same way)")
        ->check(impulse::app::positiveNumber());
    bool noRunProgress = false;
    runCommand->add_flag("--no-progress", noRunProgress,
                         "No progress line (it is drawn on standard error only when that is a terminal)");
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
        ->add_option("--sleep", run.sleep,
                     "Let islands at rest sleep until something touches them: on or off (the default)")
        ->check(CLI::IsMember({"on", "off"}));
    runCommand
        ->add_option("--push-out", run.pushOut,
                     "Move overlapping bodies apart after the position update: on (the default) or off")
        ->check(CLI::IsMember({"on", "off"}));
    runCommand
        ->add_option("--restitution-threshold", run.restitutionThreshold,
                     "Resolve collisions approaching slower than this speed (m/s) with restitution 0; "
                     "default none")
        ->check(impulse::app::nonNegativeNumber());
    runCommand
        ->add_option("--threads", run.threads,
                     "Worker threads (0: one per hardware thread); the trajectory is the same at any count")
        ->check(impulse::app::wholeNumber(0, 65536));

    const impulse::app::SeeCommands see(app);
    const impulse::app::BenchCommand bench(app);
    const impulse::app::ReplayCommand replay(app);
    const impulse::app::FitCommand fit(app);

#ifdef IMPULSE_HAVE_MUJOCO
    std::string exportScene;
    std::string exportOut;
    CLI::App* exportCommand = app.add_subcommand("export-mjcf", "Write a scene file as an equivalent MJCF model");
    exportCommand->add_option("scene", exportScene, "Scene file (JSON)")->required();
    exportCommand->add_option("--out", exportOut, "Write the MJCF here (default: standard output)");
    double timeconst = 0.0;
    exportCommand
        ->add_option("--timeconst", timeconst,
                     "Time constant of MuJoCo's contacts in seconds (default 2 dt; see docs/mujoco.md)")
        ->check(impulse::app::positiveNumber());
    std::string compareScene;
    CLI::App* compareCommand = app.add_subcommand(
        "compare", "Run a scene or an MJCF model in impulse and in MuJoCo and print the figures side by side");
    compareCommand
        ->add_option("scene", compareScene, "Scene file (JSON), or an MJCF model (.xml) with impulse_duration")
        ->required();
    compareCommand
        ->add_option("--timeconst", timeconst,
                     "Time constant of MuJoCo's contacts in seconds (default 2 dt; see docs/mujoco.md)")
        ->check(impulse::app::positiveNumber());
#endif

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
    if (const std::optional<int> code = replay.runChosen())
    {
        return *code;
    }
    if (const std::optional<int> code = fit.runChosen())
    {
        return *code;
    }
    if (const std::optional<int> code = bench.runChosen())
    {
        return *code;
    }

#ifdef IMPULSE_HAVE_MUJOCO
    if (exportCommand->parsed())
    {
        return impulse::app::exportMjcf(exportScene, exportOut, timeconst);
    }
    if (compareCommand->parsed())
    {
        return impulse::app::compare(compareScene, timeconst);
    }
#endif
    run.progress = !noRunProgress;
    return impulse::app::runScene(run);
}
