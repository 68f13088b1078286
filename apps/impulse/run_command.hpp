// SPDX-License-Identifier: MIT
#pragma once

#include <optional>
#include <string>

namespace impulse::app
{

/// What `impulse run` was asked to do; unset options fall back to the scene file.
struct RunOptions
{
    std::string scenePath;
    std::optional<double> dt;
    std::optional<double> duration;
    std::string outPath;                         ///< empty: no trajectory file
    long long every = 1;                         ///< write every N-th step
    std::optional<std::string> scheme;           ///< "guendelman" or "traditional"
    std::optional<double> restitutionThreshold;  ///< m/s
    std::optional<std::string> shockPropagation; ///< "on" or "off"
    std::optional<std::string> pushOut;          ///< "on" or "off"
    std::optional<std::string> sleep;            ///< "on" or "off"
    int threads = 1;                             ///< 0: one per hardware thread
    std::optional<double> timeLimit;             ///< wall-clock seconds; stop at the next sample after it
    bool progress = true;                        ///< the progress line, when standard error is a terminal
};

/// Runs a scene and prints a summary. Returns the process exit code: 0 on success (a run stopped by
/// its time limit included), 2 for a scene that cannot be used, 1 for any other failure (such as
/// an output file that cannot be written), 128 + the signal for a run stopped by Ctrl-C or SIGTERM,
/// which still leaves a trajectory of whole samples ending with the state where it stopped.
int runScene(const RunOptions& options);

} // namespace impulse::app
