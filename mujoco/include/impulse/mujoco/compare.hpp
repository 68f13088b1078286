// SPDX-License-Identifier: MIT
#pragma once

#include <filesystem>
#include <string>
#include <vector>

namespace impulse::mujoco
{

/// One figure of a comparison, formatted for printing.
struct FigureRow
{
    std::string label;
    std::string impulse;
    std::string mujoco;
    std::string oracle; ///< what scenarios.md asks for, "" where it states nothing
};

struct Comparison
{
    std::string scene;
    long long steps = 0;
    double dt = 0.0;
    double timeconst = 0.0; ///< of MuJoCo's contacts; 0 for a model input, whose own contacts MuJoCo uses
    std::vector<FigureRow> rows;
    double impulseMsPerStep = 0.0; ///< World::step alone
    double mujocoMsPerStep = 0.0;  ///< mj_step alone
};

/// Whether a path names an MJCF model (.xml or .mjcf, in any case) rather than a scene file.
bool isModelFile(const std::filesystem::path& path);

/// Runs a scene file in impulse and, exported to MJCF, in MuJoCo (native mj_step), and measures
/// the same figures on both: those that make sense for what the scene holds (apex heights and
/// rest time of a drop, exit velocities without gravity, slip time of a spinning ball, creep of a
/// block, drift of the top of a stack), the deepest penetration (judged for both by MuJoCo's
/// collision detection) and the wall time per step. `timeconst` as for exportMjcf. An MJCF model
/// (isModelFile) is run as it is by both, MuJoCo with the model's own contact parameters; it needs
/// its impulse_duration. Throws io::SceneError or ModelError.
Comparison compareScene(const std::filesystem::path& scenePath, double timeconst = 0.0);

} // namespace impulse::mujoco
