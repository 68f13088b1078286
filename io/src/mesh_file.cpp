// SPDX-License-Identifier: MIT
// Mesh files through Open Asset Import (assimp): one well-kept reader for OBJ and STL, the two
// formats meshes come in, plus PLY, OFF and others at no cost. Only triangulation is asked of it;
// welding and every check of the solid are impulse's own (MeshGeometry::build), so that a broken
// file is refused with a precise reason instead of being repaired silently.
#include <impulse/io/mesh_file.hpp>

#include <assimp/Importer.hpp>
#include <assimp/postprocess.h>
#include <assimp/scene.h>

namespace impulse::io
{
namespace
{

void collect(const aiScene& scene, const aiNode& node, const aiMatrix4x4& parent, const std::string& name,
             TriangleMesh& out)
{
    const aiMatrix4x4 transform = parent * node.mTransformation;
    for (unsigned m = 0; m < node.mNumMeshes; ++m)
    {
        const aiMesh& mesh = *scene.mMeshes[node.mMeshes[m]];
        const auto first = static_cast<std::uint32_t>(out.vertices.size());
        for (unsigned v = 0; v < mesh.mNumVertices; ++v)
        {
            const aiVector3D p = transform * mesh.mVertices[v];
            out.vertices.emplace_back(p.x, p.y, p.z);
        }
        for (unsigned f = 0; f < mesh.mNumFaces; ++f)
        {
            const aiFace& face = mesh.mFaces[f];
            if (face.mNumIndices != 3)
            {
                throw MeshFileError(name + ": has a face with " + std::to_string(face.mNumIndices) +
                                    " corners (points and lines cannot bound a solid)");
            }
            out.triangles.push_back({first + face.mIndices[0], first + face.mIndices[1], first + face.mIndices[2]});
        }
    }
    for (unsigned c = 0; c < node.mNumChildren; ++c)
    {
        collect(scene, *node.mChildren[c], transform, name, out);
    }
}

} // namespace

TriangleMesh readMeshFile(const std::filesystem::path& path)
{
    const std::string name = path.string();
    std::error_code error;
    if (!std::filesystem::is_regular_file(path, error))
    {
        throw MeshFileError(name + ": no such file");
    }
    Assimp::Importer importer;
    // assimp reads coordinates as float unless built for double: fine for meshes, which are
    // welded on exact equality afterwards
    const aiScene* scene = importer.ReadFile(name, aiProcess_Triangulate);
    if (scene == nullptr || scene->mRootNode == nullptr)
    {
        throw MeshFileError(name + ": cannot read the mesh: " + importer.GetErrorString());
    }
    TriangleMesh mesh;
    collect(*scene, *scene->mRootNode, aiMatrix4x4(), name, mesh);
    if (mesh.triangles.empty())
    {
        throw MeshFileError(name + ": contains no triangles");
    }
    return mesh;
}

} // namespace impulse::io
