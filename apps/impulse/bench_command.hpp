// SPDX-License-Identifier: MIT
// impulse bench: milliseconds per step of the benchmark scenes, with the counters and state hash.
#pragma once

#include <CLI/CLI.hpp>

#include <optional>
#include <string>
#include <vector>

namespace impulse::app
{

/// What `impulse bench` was asked to do.
struct BenchOptions
{
    /// Scene names (sphere_pile_1000) or paths (scenes/pyramid.json); empty: the default suite.
    std::vector<std::string> scenes;
    std::optional<long long> steps;  ///< measured steps; unset: the rest of the scene's duration
    std::optional<long long> warmUp; ///< unmeasured steps first; unset: a tenth, at least 1
    int threads = 1;                 ///< StepOptions::threads; 0: one per hardware thread
    bool json = false;               ///< one JSON document on standard output instead of the table
    bool progress = true;            ///< a progress line on standard error, when it is a terminal
    std::string scenesDirectory;     ///< where names are looked up; empty: the source tree's scenes/
};

/// The benchmark scenes run when none is named.
const std::vector<std::string>& defaultBenchScenes();

/// Runs the scenes and prints the table or the JSON. Returns the exit code: 0, 2 for a scene or
/// option that cannot be used, 1 when a run diverges.
int runBench(const BenchOptions& options);

/// Registers `bench` on the application; options are bound to its members, so it stays where it
/// was built.
class BenchCommand
{
  public:
    explicit BenchCommand(CLI::App& app);
    BenchCommand(const BenchCommand&) = delete;
    BenchCommand& operator=(const BenchCommand&) = delete;

    /// After parsing: the exit code of `bench` if it was the subcommand chosen.
    std::optional<int> runChosen() const;

  private:
    BenchOptions m_options;
    bool m_noProgress = false;
    CLI::App* m_command = nullptr;
};

} // namespace impulse::app
