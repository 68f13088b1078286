// SPDX-License-Identifier: MIT
// libFuzzer target: the mesh loader on arbitrary bytes, read as a file the way a scene's mesh is,
// then prepared as a solid. The first byte picks the format: 's' or 'S' an STL file, anything else
// an OBJ file; the rest is the file. Every input must become a mesh or be refused with
// io::MeshFileError or MeshError; anything else is a finding, inside the file reader (assimp, not
// instrumented, still crashes and leaks visibly) as much as in impulse.
#include "fuzz_support.hpp"

#include <impulse/io/mesh_file.hpp>
#include <impulse/mesh.hpp>

#include <cstddef>
#include <cstdint>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
    static const impulse::fuzz::PrivateDirectory directory("mesh");
    if (size == 0)
    {
        return 0;
    }
    const bool stl = (data[0] | 0x20) == 's';
    const std::filesystem::path path = directory.path() / (stl ? "mesh.stl" : "mesh.obj");
    impulse::fuzz::writeFile(path, impulse::fuzz::asText(data + 1, size - 1));
    try
    {
        const impulse::TriangleMesh mesh = impulse::io::readMeshFile(path);
        // the coarsest grid, one cell: validation, mass properties and the hierarchy are what a
        // file can break, and a finer grid would take most of the time
        impulse::MeshGeometry::build(mesh, {.resolution = 1});
    }
    catch (const impulse::io::MeshFileError&)
    {
    }
    catch (const impulse::MeshError&)
    {
        // refused with a message: what a bad mesh must get
    }
    // a new file each time: rewriting one in place makes some file systems flush it to disk
    std::filesystem::remove(path);
    return 0;
}
