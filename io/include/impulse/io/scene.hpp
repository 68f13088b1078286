// SPDX-License-Identifier: MIT
#pragma once

#include <impulse/mesh.hpp>
#include <impulse/world.hpp>

#include <cstddef>
#include <filesystem>
#include <stdexcept>
#include <string>
#include <vector>

namespace impulse::io
{

/// A scene file that cannot be used. The message names the file, the field's JSON pointer and what
/// is wrong, e.g. "ball.json: /bodies/1/shape/radius: must be positive, got -0.1".
class SceneError : public std::runtime_error
{
  public:
    using std::runtime_error::runtime_error;
};

/// Where a mesh body's shape was read from: the file as the loader opened it (relative paths
/// joined to the scene's directory), the scale applied to its vertices and the grid resolution.
struct MeshSource
{
    std::filesystem::path file; ///< empty for bodies of other shapes
    Vec3 scale = Vec3::Ones();
    int resolution = 0;
};

/// A loaded scene: the world, the solver options and how long to run.
struct Scene
{
    std::string name;
    World world;
    StepOptions options;
    Real duration = 0.0;                ///< seconds
    std::vector<BodyId> dynamicBodies;  ///< in file order; trajectory body k is dynamicBodies[k]
    std::vector<std::string> bodyNames; ///< per world body, "" where the file names none
    std::vector<BodyDef> bodyDefs;      ///< per world body, as the file defines it
    /// per world body, where its mesh was read from (file empty where the shape is no mesh)
    std::vector<MeshSource> meshSources;
};

/// What a scene may make the loader read and build beyond its own text. The defaults suit scene
/// files a person writes; a program that loads scenes from a source it does not trust (the fuzz
/// targets in tests/fuzz, a service) confines them further.
struct SceneLimits
{
    /// Mesh files only inside the scene's directory: a `file` that is an absolute path or has a
    /// ".." component is refused (symbolic links inside the directory are still followed).
    bool meshFilesInsideDirectory = false;
    /// Most samples of one mesh's signed distance grid (MeshOptions::maxGridSamples).
    std::size_t maxGridSamples = MeshOptions{}.maxGridSamples;
};

/// Reads a scene file (docs/scene-format.md). Throws SceneError on any problem.
Scene loadScene(const std::filesystem::path& path);

/// Parses scene text; `source` names it in error messages and mesh files are found relative to
/// `directory`.
Scene parseScene(const std::string& text, const std::string& source, const std::filesystem::path& directory = {},
                 const SceneLimits& limits = {});

} // namespace impulse::io
