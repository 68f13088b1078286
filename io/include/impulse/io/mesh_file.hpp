// SPDX-License-Identifier: MIT
#pragma once

#include <impulse/mesh.hpp>

#include <filesystem>
#include <stdexcept>

namespace impulse::io
{

/// A mesh file that cannot be read; the message starts with the file's path.
class MeshFileError : public std::runtime_error
{
  public:
    using std::runtime_error::runtime_error;
};

/// Reads every triangle of a mesh file (Wavefront OBJ and STL in ASCII or binary, read by impulse
/// and chosen by the extension; the other formats Open Asset Import reads), polygons split into
/// triangles, all parts in one mesh, in the file's own coordinates. Opens no file but this one. It
/// does not check that the mesh is a solid: MeshGeometry::build does. The message of a
/// MeshFileError names the file and, for OBJ and ASCII STL, the line.
TriangleMesh readMeshFile(const std::filesystem::path& path);

} // namespace impulse::io
