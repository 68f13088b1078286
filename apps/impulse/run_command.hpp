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
    int threads = 1;                             ///< 0: one per hardware thread
};

/// Runs a scene and prints a summary. Returns the process exit code: 0 on success, 2 for a scene
/// that cannot be used, 1 for any other failure (such as an output file that cannot be written).
int runScene(const RunOptions& options);

} // namespace impulse::app
