// SPDX-License-Identifier: MIT
// impulse_pile_oracle: a reference pile's oracle test (scenes 11, 12 and 14), run so that it can be
// stopped and continued. The test's run of hours becomes several sittings: a checkpoint of the
// world's state and the oracle's figures every few hundred steps, and --resume to go on from one.
// The trajectory and the verdict are those of the test, bit for bit.
//
// Exit codes: 0 the oracle holds, 1 it fails, 2 bad input, 3 stopped by --until before the end.
#include "support/pile_oracle.hpp"

#include <CLI/CLI.hpp>

#include <cstdio>
#include <exception>
#include <filesystem>
#include <iostream>

int main(int argc, char** argv)
{
    CLI::App app{"Runs a reference pile's oracle test with checkpoints, so that it can be continued"};
    std::string name;
    std::string directory = ".";
    long long every = 250;
    std::string resumeFrom;
    long long until = -1;
    int threads = -1;
    std::string names;
    for (const impulse::test::ReferencePile& pile : impulse::test::kReferencePiles)
    {
        names += (names.empty() ? "" : ", ") + std::string(pile.name);
    }
    app.add_option("scene", name, "reference pile: " + names)->required();
    app.add_option("--checkpoints", directory, "directory for the checkpoints (default: the current one)");
    app.add_option("--every", every, "steps between checkpoints (default 250; 0: none)")->check(CLI::NonNegativeNumber);
    app.add_option("--resume", resumeFrom, "checkpoint to continue from")->check(CLI::ExistingFile);
    app.add_option("--until", until, "stop after this step, with a checkpoint, exit code 3")
        ->check(CLI::PositiveNumber);
    app.add_option("--threads", threads, "threads (default: the pile test's); the trajectory is the same at any count")
        ->check(CLI::NonNegativeNumber);
    try
    {
        app.parse(argc, argv);
    }
    catch (const CLI::ParseError& error)
    {
        return app.exit(error) == 0 ? 0 : 2;
    }

    const impulse::test::ReferencePile* pile = impulse::test::findReferencePile(name);
    if (pile == nullptr)
    {
        std::cerr << "impulse_pile_oracle: scene: \"" << name << "\" is not a reference pile (" << names << ")\n";
        return 2;
    }
    try
    {
        impulse::test::PileRun run = impulse::test::referencePileRun(*pile);
        if (threads >= 0)
        {
            run.scene().options.threads = threads;
        }
        if (!resumeFrom.empty())
        {
            run.resume(resumeFrom);
            std::printf("resumed from %s at step %lld, state hash %016llx\n", resumeFrom.c_str(), run.figures().step,
                        static_cast<unsigned long long>(run.world().stateHash()));
        }
        if (until > 0 && until <= run.figures().step)
        {
            std::cerr << "impulse_pile_oracle: --until: step " << until << " is not after the checkpoint's step "
                      << run.figures().step << "\n";
            return 2;
        }
        std::filesystem::create_directories(directory);
        const auto checkpoint = [&]
        {
            const std::string path =
                (std::filesystem::path(directory) / (name + "_step_" + std::to_string(run.figures().step) + ".txt"))
                    .string();
            run.save(path);
            std::printf("step %lld state hash %016llx, checkpoint %s\n", run.figures().step,
                        static_cast<unsigned long long>(run.world().stateHash()), path.c_str());
            std::fflush(stdout);
        };
        while (!run.finished())
        {
            run.step(std::cout);
            const long long step = run.figures().step;
            if (run.failure())
            {
                break;
            }
            if (step == until)
            {
                checkpoint();
                std::printf("stopped at step %lld of %lld\n", step, run.totalSteps());
                return 3;
            }
            if (every > 0 && step % every == 0)
            {
                checkpoint();
            }
        }
        if (run.failure())
        {
            std::printf("FAIL: %s\n", run.failure()->c_str());
            return 1;
        }
        bool holds = true;
        for (const impulse::test::PileCheck& check : run.finalChecks())
        {
            std::printf("%s: %s %.9g, limit %g\n", check.holds() ? "PASS" : "FAIL", check.what.c_str(), check.value,
                        check.limit);
            holds = holds && check.holds();
        }
        std::printf("%s at step %lld: kinetic energy %.9g J (peak %.9g J), deepest pair sampled every 50 steps "
                    "%.9g m (%.6g %% of the smaller body, %s), state hash %016llx\n",
                    name.c_str(), run.figures().step, run.world().kineticEnergy(), run.figures().peakKinetic,
                    run.figures().deepest, 100.0 * run.figures().deepestRelative, run.deepestSample().c_str(),
                    static_cast<unsigned long long>(run.world().stateHash()));
        return holds ? 0 : 1;
    }
    catch (const std::exception& error)
    {
        std::cerr << "impulse_pile_oracle: " << error.what() << "\n";
        return 2;
    }
}
