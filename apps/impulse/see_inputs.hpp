// SPDX-License-Identifier: MIT
// What plot, render and view share: reading a trajectory and, optionally, its scene.
#pragma once

#include <impulse/io/scene.hpp>
#include <impulse/io/trajectory_reader.hpp>
#include <impulse/viz/scene_view.hpp>

#include <optional>
#include <stdexcept>
#include <string>

namespace impulse::app
{

/// Input that cannot be used: exit code 2, the message printed as is after "impulse: ".
class InputError : public std::runtime_error
{
  public:
    using std::runtime_error::runtime_error;
};

/// Whether a path names an MJCF model (.xml, .mjcf) rather than a scene file.
bool isModelPath(const std::string& path);

/// Reads a scene file, or an MJCF model through MuJoCo (an MJCF model's duration is NaN unless it
/// sets impulse_duration). Throws InputError with the loader's message, naming the file.
io::Scene loadSceneInput(const std::string& path);

/// A trajectory with what is known of its scene.
struct LoadedRun
{
    io::Trajectory trajectory;
    viz::SceneView view;
    std::string title; ///< the scene's name, or the trajectory file's stem
};

/// Reads TRAJ.csv and, when `scenePath` is not empty, the scene it came from (for masses, shapes
/// and gravity). Throws InputError on anything unusable.
LoadedRun loadRun(const std::string& trajectoryPath, const std::string& scenePath);

/// Parses "WIDTHxHEIGHT" with both between 16 and 8192 pixels; throws InputError otherwise.
std::pair<int, int> parseSize(const std::string& text, const std::string& option);

/// The full path of an executable found on PATH, or nothing.
std::optional<std::string> findExecutable(const std::string& name);

/// Runs a program with arguments, without a shell; returns its exit status (-1 if it could not run
/// or was killed).
int runProgram(const std::string& program, const std::vector<std::string>& arguments);

/// `path` with its extension replaced, e.g. ("runs/a.csv", ".png") -> "runs/a.png".
std::string withExtension(const std::string& path, const std::string& extension);

} // namespace impulse::app
