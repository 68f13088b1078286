// SPDX-License-Identifier: MIT
// libFuzzer target: the scene loader on arbitrary bytes. Every input must load or be refused with
// io::SceneError; anything else (a crash, another exception, a sanitizer report, a leak, a hang)
// is a finding. Mesh files resolve in a private directory that holds two small solids, one OBJ
// and one STL, so that mesh bodies load too; the scene may reach no file outside it.
#include "fuzz_support.hpp"

#include <impulse/io/scene.hpp>

#include <cstddef>
#include <cstdint>

namespace
{

const char* const kCubeObj = R"(v 0 0 0
v 1 0 0
v 1 1 0
v 0 1 0
v 0 0 1
v 1 0 1
v 1 1 1
v 0 1 1
f 1 4 3
f 1 3 2
f 5 6 7
f 5 7 8
f 1 2 6
f 1 6 5
f 2 3 7
f 2 7 6
f 3 4 8
f 3 8 7
f 4 1 5
f 4 5 8
)";

const char* const kTetrahedronStl = R"(solid tetrahedron
facet normal 0 0 -1
outer loop
vertex 0 0 0
vertex 0 1 0
vertex 1 0 0
endloop
endfacet
facet normal 0 -1 0
outer loop
vertex 0 0 0
vertex 1 0 0
vertex 0 0 1
endloop
endfacet
facet normal -1 0 0
outer loop
vertex 0 0 0
vertex 0 0 1
vertex 0 1 0
endloop
endfacet
facet normal 1 1 1
outer loop
vertex 1 0 0
vertex 0 1 0
vertex 0 0 1
endloop
endfacet
endsolid tetrahedron
)";

} // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
    static const impulse::fuzz::PrivateDirectory directory("scene");
    static const bool meshesWritten = [&]
    {
        impulse::fuzz::writeFile(directory.path() / "cube.obj", kCubeObj);
        impulse::fuzz::writeFile(directory.path() / "tetrahedron.stl", kTetrahedronStl);
        return true;
    }();
    (void)meshesWritten;

    impulse::io::SceneLimits limits;
    limits.meshFilesInsideDirectory = true;
    // a few thousand samples keep an input to milliseconds: the meshes load at coarse resolutions,
    // and the default grid (at least 32 cells along the longest side) is refused, which tests the
    // limit; the default limit has its own test in tests/io
    limits.maxGridSamples = 4096;
    try
    {
        impulse::io::parseScene(std::string(impulse::fuzz::asText(data, size)), "fuzz.json", directory.path(), limits);
    }
    catch (const impulse::io::SceneError&)
    {
        // refused with a message: what a bad scene must get
    }
    return 0;
}
