// SPDX-License-Identifier: MIT
// impulse replay: measured trajectories simulated again from their first sample and compared.
#pragma once

#include <CLI/CLI.hpp>

#include <optional>
#include <string>
#include <vector>

namespace impulse::app
{

/// What `impulse replay` was asked to do.
struct ReplayOptions
{
    /// Measured trajectory files (.csv, or .csv.gz), or directories whose .csv and .csv.gz files
    /// are all taken (in name order).
    std::vector<std::string> measured;
    std::string scenePath;      ///< the template: its first dynamic body is replayed, the rest are static
    std::string jsonPath;       ///< empty: no JSON file; "-": the JSON on standard output instead of the table
    std::optional<double> size; ///< m, what the position error is measured in; unset: the body's (bodySize)
    int jobs = 0;               ///< trajectories replayed at once; 0: one per hardware thread
    std::string outDirectory;   ///< empty: none; else each simulation is written there (replay only)
    bool progress = true;       ///< a progress line on standard error, when it is a terminal
};

/// Replays every measured trajectory and prints the table (and writes the JSON). Returns the exit
/// code: 0, or 2 for a template, a measured file or an option that cannot be used.
int runReplay(const ReplayOptions& options);

/// What `impulse fit` was asked to do: the measurements, template, JSON, size, jobs and progress
/// as for replay, and what to minimise.
struct FitOptions
{
    ReplayOptions replay;
    std::string objective = "sum"; ///< "sum" (position % + rotation degrees), "position" or "rotation"
    int evaluations = 300;         ///< at most this many replays of the whole set
    int scan = 30;                 ///< of them, the global look (DIRECT-L) before the local search
};

/// Fits friction and restitution between the template's body and its static bodies to the
/// measurements, minimising the mean replay error; prints the values, the error before and
/// after and the sensitivity. Returns the exit code: 0, or 2 for input that cannot be used.
int runFit(const FitOptions& options);

/// Registers `replay` on the application; options are bound to its members, so it stays where it
/// was built.
class ReplayCommand
{
  public:
    explicit ReplayCommand(CLI::App& app);
    ReplayCommand(const ReplayCommand&) = delete;
    ReplayCommand& operator=(const ReplayCommand&) = delete;

    /// After parsing: the exit code of `replay` if it was the subcommand chosen.
    std::optional<int> runChosen() const;

  private:
    ReplayOptions m_options;
    bool m_noProgress = false;
    CLI::App* m_command = nullptr;
};

/// Registers `fit` on the application, as ReplayCommand does `replay`.
class FitCommand
{
  public:
    explicit FitCommand(CLI::App& app);
    FitCommand(const FitCommand&) = delete;
    FitCommand& operator=(const FitCommand&) = delete;

    /// After parsing: the exit code of `fit` if it was the subcommand chosen.
    std::optional<int> runChosen() const;

  private:
    FitOptions m_options;
    bool m_noProgress = false;
    CLI::App* m_command = nullptr;
};

} // namespace impulse::app
