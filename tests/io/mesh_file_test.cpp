// SPDX-License-Identifier: MIT
// The mesh file reader's contract for OBJ and STL, which impulse reads itself: the geometry a file
// describes becomes triangles over its vertices, polygons split so that they stay inside the
// polygon, and anything else is refused with io::MeshFileError reading "<file>: line <n>: <what>"
// (or "<file>: <what>" for a binary STL). Also the inputs the mesh fuzz target found.
#include <impulse/io/mesh_file.hpp>
#include <impulse/mesh.hpp>

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <unistd.h>

namespace
{

using impulse::TriangleMesh;
using impulse::Vec3;
using impulse::io::MeshFileError;
using impulse::io::readMeshFile;

/// A file named `name` with `content`, in a directory of this test process's own.
std::filesystem::path file(const std::string& name, const std::string& content)
{
    const auto directory =
        std::filesystem::temp_directory_path() / ("impulse_mesh_file_test_" + std::to_string(getpid()));
    std::filesystem::create_directories(directory);
    const auto path = directory / name;
    std::ofstream(path, std::ios::binary) << content;
    return path;
}

/// The message of the MeshFileError that reading `path` throws, or "(accepted)".
std::string refusal(const std::filesystem::path& path)
{
    try
    {
        readMeshFile(path);
    }
    catch (const MeshFileError& error)
    {
        return error.what();
    }
    return "(accepted)";
}

const std::string kCubeVertices = "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 0 0 1\nv 1 0 1\nv 1 1 1\nv 0 1 1\n";
const std::string kCubeQuads = "f 1 4 3 2\nf 5 6 7 8\nf 1 2 6 5\nf 2 3 7 6\nf 3 4 8 7\nf 4 1 5 8\n";

TEST(MeshFile, ObjQuadsBecomeTwoTrianglesEachAndMakeASolid)
{
    const TriangleMesh mesh = readMeshFile(file("cube.obj", "# a cube\no cube\n" + kCubeVertices + kCubeQuads));
    EXPECT_EQ(mesh.vertices.size(), 8u);
    ASSERT_EQ(mesh.triangles.size(), 12u);
    EXPECT_EQ(mesh.triangles[0], (std::array<std::uint32_t, 3>{0, 3, 2}));
    EXPECT_EQ(mesh.triangles[1], (std::array<std::uint32_t, 3>{0, 2, 1}));
    EXPECT_NEAR(impulse::MeshGeometry::build(mesh)->volume(), 1.0, 1e-12);
}

TEST(MeshFile, ObjIndicesMayBeRelativeOrForwardAndCornersCarryTextureAndNormal)
{
    // the bottom face by negative indices right after the vertices, the others with v/t/n corners,
    // and a face written before the last vertex it names; a continued line and a weighted vertex
    const std::string text = "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf -4 -1 -2 -3\nf 4/1/1 1/1/1 5//1 8//1\n"
                             "v 0 0 1\nv 2 0 2 2  # weight 2\nv 1 1 1 0.5 0.5 0.5\nv 0 1 1\nvt 0 0\nvn 0 0 1\n"
                             "usemtl any\nmtllib /no/such/library.mtl\ns off\ng top\nf 5 6 \\\n 7 8\n"
                             "f 1 2 6 5\nf 2 3 7 6\nf 3 4 8 7\n";
    const TriangleMesh mesh = readMeshFile(file("relative.obj", text));
    ASSERT_EQ(mesh.triangles.size(), 12u);
    EXPECT_EQ(mesh.vertices[5], Vec3(1, 0, 1));
    EXPECT_NEAR(impulse::MeshGeometry::build(mesh)->volume(), 1.0, 1e-12);
}

TEST(MeshFile, AConcaveQuadIsSplitThroughItsReflexCorner)
{
    // an arrowhead in the plane z = 0, concave at its second corner: the fan from the first corner
    // would put a triangle outside it
    const TriangleMesh mesh = readMeshFile(file("arrow.obj", "v 0 0 0\nv 1 1 0\nv 0 2 0\nv 3 1 0\nf 1 2 3 4\n"));
    ASSERT_EQ(mesh.triangles.size(), 2u);
    EXPECT_EQ(mesh.triangles[0], (std::array<std::uint32_t, 3>{1, 2, 3}));
    EXPECT_EQ(mesh.triangles[1], (std::array<std::uint32_t, 3>{1, 3, 0}));
}

TEST(MeshFile, BrokenObjFilesAreRefusedNamingTheLine)
{
    const auto expectRefused = [](const std::string& name, const std::string& text, const std::string& what)
    {
        const auto path = file(name, text);
        EXPECT_EQ(refusal(path), path.string() + ": " + what);
    };
    expectRefused("few.obj", "v 0 0 0\nv 1 0\n",
                  "line 2: a vertex needs 3 coordinates (4 with a weight, 6 with a "
                  "colour), got 2 numbers");
    expectRefused("nan.obj", "v 0 0 0\nv 1 nan 0\n", "line 2: not a finite number: \"nan\"");
    expectRefused("word.obj", "v 0 0 0\nv 1 0 0x1\n", "line 2: not a finite number: \"0x1\"");
    expectRefused("big.obj", "v 0 0 1e39\n", "line 1: not a finite number: \"1e39\"");
    expectRefused("zero.obj", kCubeVertices + "f 1 0 2\n",
                  "line 9: a face corner must start with a vertex number "
                  "other than 0, got \"0\"");
    expectRefused("beyond.obj", kCubeVertices + "f 1 2 3\nf 1 2 9\n",
                  "line 10: a face names vertex 9, but the file has 8");
    expectRefused("before.obj", "v 0 0 0\nv 1 0 0\nf -1 -2 -3\nv 0 1 0\n",
                  "line 3: a face names vertex -3, but only 2 come before it");
    expectRefused("huge.obj", kCubeVertices + "f 1 2 99999999999999999999\n",
                  "line 9: a face corner must start with a vertex number other than 0, got \"99999999999999999999\"");
    expectRefused("edge.obj", kCubeVertices + "f 1 2\n",
                  "line 9: a face needs at least 3 corners, got 2 (points and lines cannot bound a solid)");
    expectRefused("line.obj", kCubeVertices + "l 1 2\n",
                  "line 9: has a line element (points and lines cannot bound a solid)");
    const auto empty = file("empty.obj", "# nothing\nv 0 0 0\n");
    EXPECT_EQ(refusal(empty), empty.string() + ": contains no triangles");
}

TEST(MeshFile, StlIsReadInBothFormsEvenABinaryOneThatBeginsWithSolid)
{
    const std::string ascii = "solid t\n facet normal 0 0 -1\n  outer loop\n   vertex 0 0 0\n   vertex 0 1 0\n"
                              "   vertex 1 0 0\n  endloop\n endfacet\nendsolid t\n";
    const TriangleMesh fromText = readMeshFile(file("text.stl", ascii));
    ASSERT_EQ(fromText.triangles.size(), 1u);
    EXPECT_EQ(fromText.vertices[1], Vec3(0, 1, 0));

    std::string binary = "solid but binary";
    binary.resize(80, ' ');
    binary += std::string("\x01\x00\x00\x00", 4);
    const float corners[12] = {0, 0, -1, 0, 0, 0, 0, 1, 0, 1, 0, 0};
    binary.append(reinterpret_cast<const char*>(corners), sizeof corners); // little-endian, as x86 is
    binary += std::string(2, '\0');
    const TriangleMesh fromRecords = readMeshFile(file("records.STL", binary));
    EXPECT_EQ(fromRecords.vertices, fromText.vertices);
    EXPECT_EQ(fromRecords.triangles, fromText.triangles);

    // cut short, it still is no ASCII file for beginning with "solid"
    const auto cut = file("cut.stl", binary.substr(0, 120));
    EXPECT_EQ(refusal(cut), cut.string() + ": not an STL file: 120 bytes cannot hold the 1 triangles its header "
                                           "announces, and it is not text as an ASCII STL is");
    const auto four = file("four.stl", "solid q\nfacet\nvertex 0 0 0\nvertex 1 0 0\nvertex 1 1 0\nvertex 0 1 0\n");
    EXPECT_EQ(refusal(four), four.string() + ": line 6: a facet with more than 3 vertices");
    const auto open = file("open.stl", "solid q\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\n");
    EXPECT_EQ(refusal(open),
              open.string() + ": line 2: the facet that begins here has no endfacet (the file is cut off)");
    const auto other = file("other.stl", "solid q\nfacet\nvertex 0 0 0\nvertext 1 0 0\n");
    EXPECT_EQ(refusal(other), other.string() + ": line 4: expected facet, outer loop, vertex, endloop, endfacet or "
                                               "endsolid, got \"vertext\"");
}

TEST(MeshFile, TheShippedMeshesAreSolids)
{
    for (const auto& entry : std::filesystem::directory_iterator(std::string(IMPULSE_SCENES_DIR) + "/meshes"))
    {
        EXPECT_GT(impulse::MeshGeometry::build(readMeshFile(entry.path()))->volume(), 0.0) << entry.path();
    }
}

// Inputs of the mesh fuzz target (tests/fuzz/mesh_fuzz.cpp) kept in tests/data/fuzz/mesh: the first
// byte picks the format ('s' STL, else OBJ), the rest is the file, read as the target reads it.
std::string fuzzInputRefusal(const std::string& name)
{
    std::ifstream in(std::string(IMPULSE_TEST_DATA_DIR) + "/fuzz/mesh/" + name, std::ios::binary);
    const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    EXPECT_FALSE(bytes.empty()) << name;
    const bool stl = !bytes.empty() && (bytes[0] | 0x20) == 's';
    return refusal(file(stl ? "fuzz.stl" : "fuzz.obj", bytes.empty() ? bytes : bytes.substr(1)));
}

TEST(MeshFileFuzzRegressions, ObjWithABadIndexInALaterGroup)
{
    // assimp read "1\xd9" on line 10 as 1, then leaked the first group's mesh when the second named
    // vertex 12 of 8; impulse's reader stops at the first thing wrong
    const std::string message = fuzzInputRefusal("obj_bad_index_in_a_later_group.obj");
    EXPECT_NE(message.find("fuzz.obj: line 10: not a finite number: \"1?\""), std::string::npos) << message;
    const std::string clean = fuzzInputRefusal("obj_bad_index_in_a_later_group_clean.obj");
    EXPECT_NE(clean.find("fuzz.obj: line 18: a face names vertex 12, but the file has 8"), std::string::npos) << clean;
}

} // namespace
