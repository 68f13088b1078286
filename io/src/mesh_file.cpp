// SPDX-License-Identifier: MIT
// Mesh files. OBJ and STL, the two formats meshes come in, are read here: their geometry is a few
// lines of text or fixed records, and reading them ourselves gives errors with line numbers and
// costs no more than the file (the general importer zeroes 32 MB for every OBJ file, leaks what it
// built when a later group of an OBJ file has a bad index, and follows an OBJ's material library
// to any path). Other formats (PLY, OFF, ...) go through Open Asset Import (assimp). Only geometry
// is read; welding and every check of the solid are impulse's own (MeshGeometry::build), so that a
// broken file is refused with a precise reason instead of being repaired silently.
#include <impulse/io/mesh_file.hpp>

#include <algorithm>
#include <array>
#include <assimp/DefaultIOSystem.h>
#include <assimp/Importer.hpp>
#include <assimp/postprocess.h>
#include <assimp/scene.h>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <iterator>
#include <limits>
#include <string_view>
#include <vector>

namespace impulse::io
{
namespace
{

// File access for the importer that opens the mesh file and nothing else: a mesh file can name
// other files (an OBJ's material library), and impulse reads only geometry, so a file must not
// make it read, or wait on, whatever path it names.
class OnlyTheMeshFile : public Assimp::DefaultIOSystem
{
  public:
    explicit OnlyTheMeshFile(std::string path) : m_path(std::move(path)) {}

    bool Exists(const char* file) const override { return m_path == file && DefaultIOSystem::Exists(file); }

    Assimp::IOStream* Open(const char* file, const char* mode) override
    {
        return m_path == file ? DefaultIOSystem::Open(file, mode) : nullptr;
    }

  private:
    std::string m_path;
};

[[noreturn]] void refuse(const std::string& name, std::size_t line, const std::string& what)
{
    throw MeshFileError(name + ": line " + std::to_string(line) + ": " + what);
}

/// At most 40 characters of a token, for messages.
std::string quoted(std::string_view token)
{
    std::string text(token.substr(0, 40));
    for (char& c : text)
    {
        c = std::isprint(static_cast<unsigned char>(c)) != 0 ? c : '?';
    }
    return "\"" + text + (token.size() > 40 ? "...\"" : "\"");
}

/// The whitespace-separated words of one line.
std::vector<std::string_view> words(std::string_view line)
{
    std::vector<std::string_view> out;
    std::size_t at = 0;
    while (at < line.size())
    {
        while (at < line.size() && (line[at] == ' ' || line[at] == '\t' || line[at] == '\r' || line[at] == '\f'))
        {
            ++at;
        }
        const std::size_t begin = at;
        while (at < line.size() && !(line[at] == ' ' || line[at] == '\t' || line[at] == '\r' || line[at] == '\f'))
        {
            ++at;
        }
        if (at > begin)
        {
            out.push_back(line.substr(begin, at - begin));
        }
    }
    return out;
}

/// A coordinate as the file writes it, rounded to single precision as modelling tools store it
/// (and as the general importer read it before, so meshes give the same bodies bit for bit).
double coordinate(std::string_view token, const std::string& name, std::size_t line)
{
    if (!token.empty() && token.front() == '+')
    {
        token.remove_prefix(1);
    }
    float value = 0.0f;
    const auto [end, error] = std::from_chars(token.data(), token.data() + token.size(), value);
    if (error != std::errc() || end != token.data() + token.size() || !std::isfinite(value))
    {
        refuse(name, line, "not a finite number: " + quoted(token));
    }
    return value;
}

/// Polygons into triangles: a fan from the first corner, except for a quad that is concave at its
/// second or fourth corner, which is split along the diagonal through that corner.
void triangulate(const std::vector<std::uint32_t>& corners, const std::vector<Vec3>& vertices,
                 std::vector<std::array<std::uint32_t, 3>>& out)
{
    std::size_t first = 0;
    if (corners.size() == 4)
    {
        Vec3 normal = Vec3::Zero(); // Newell's normal: right for any planar or near-planar quad
        for (std::size_t i = 0; i < 4; ++i)
        {
            normal += vertices[corners[i]].cross(vertices[corners[(i + 1) % 4]]);
        }
        const auto reflex = [&](std::size_t i)
        {
            const Vec3& p = vertices[corners[(i + 3) % 4]];
            const Vec3& q = vertices[corners[i]];
            const Vec3& r = vertices[corners[(i + 1) % 4]];
            return (q - p).cross(r - q).dot(normal) < 0.0;
        };
        first = reflex(1) || reflex(3) ? 1 : 0;
    }
    const std::size_t n = corners.size();
    for (std::size_t k = 1; k + 1 < n; ++k)
    {
        out.push_back({corners[first], corners[(first + k) % n], corners[(first + k + 1) % n]});
    }
}

// Wavefront OBJ: "v x y z" vertices (a fourth number is a weight that divides them, three more are
// a colour), "f a b c ..." faces of 1-based indices (negative: counted back from the last vertex so
// far; "a/t/n" texture and normal indices are ignored). Everything else (normals, texture
// coordinates, groups, materials, comments) is geometry impulse does not use, except points and
// lines, which cannot bound a solid.
TriangleMesh readObj(const std::string& text, const std::string& name)
{
    TriangleMesh mesh;
    struct Face
    {
        std::vector<std::int64_t> corners; // as written: positive 1-based, or negative
        std::size_t vertexCount;           // vertices read before it, for negative indices
        std::size_t line;
    };
    std::vector<Face> faces;
    std::size_t lineNumber = 0;
    std::size_t at = 0;
    std::string joined;
    while (at < text.size())
    {
        // one logical line: a backslash at the end of a line continues it on the next
        joined.clear();
        const std::size_t firstLine = lineNumber + 1;
        bool more = true;
        while (more && at <= text.size())
        {
            const std::size_t end = std::min(text.find('\n', at), text.size());
            std::string_view piece(text.data() + at, end - at);
            ++lineNumber;
            at = end + 1;
            if (!piece.empty() && piece.back() == '\r')
            {
                piece.remove_suffix(1);
            }
            more = !piece.empty() && piece.back() == '\\' && at < text.size();
            if (more)
            {
                piece.remove_suffix(1);
            }
            joined.append(piece);
            joined.push_back(' ');
        }
        std::string_view line(joined);
        if (const std::size_t hash = line.find('#'); hash != std::string_view::npos)
        {
            line = line.substr(0, hash);
        }
        const std::vector<std::string_view> w = words(line);
        if (w.empty())
        {
            continue;
        }
        if (w[0] == "v")
        {
            if (w.size() != 4 && w.size() != 5 && w.size() != 7)
            {
                refuse(name, firstLine,
                       "a vertex needs 3 coordinates (4 with a weight, 6 with a colour), got " +
                           std::to_string(w.size() - 1) + " numbers");
            }
            Vec3 v(coordinate(w[1], name, firstLine), coordinate(w[2], name, firstLine),
                   coordinate(w[3], name, firstLine));
            if (w.size() == 5)
            {
                const double weight = coordinate(w[4], name, firstLine);
                if (weight == 0.0)
                {
                    refuse(name, firstLine, "a vertex weight must not be 0");
                }
                v /= weight;
            }
            else if (w.size() == 7)
            {
                for (std::size_t k = 4; k < 7; ++k)
                {
                    coordinate(w[k], name, firstLine); // a colour: checked, not used
                }
            }
            if (mesh.vertices.size() == std::numeric_limits<std::uint32_t>::max())
            {
                refuse(name, firstLine, "more than 4294967294 vertices");
            }
            mesh.vertices.push_back(v);
        }
        else if (w[0] == "f" || w[0] == "fo")
        {
            if (w.size() < 4)
            {
                refuse(name, firstLine,
                       "a face needs at least 3 corners, got " + std::to_string(w.size() - 1) +
                           " (points and lines cannot bound a solid)");
            }
            Face face{{}, mesh.vertices.size(), firstLine};
            for (std::size_t k = 1; k < w.size(); ++k)
            {
                const std::string_view corner = w[k].substr(0, w[k].find('/'));
                std::int64_t index = 0;
                const auto [end, error] = std::from_chars(corner.data(), corner.data() + corner.size(), index);
                if (error != std::errc() || end != corner.data() + corner.size() || index == 0)
                {
                    refuse(name, firstLine,
                           "a face corner must start with a vertex number other than 0, got " + quoted(w[k]));
                }
                face.corners.push_back(index);
            }
            faces.push_back(std::move(face));
        }
        else if (w[0] == "l" || w[0] == "p")
        {
            refuse(name, firstLine,
                   "has " + std::string(w[0] == "l" ? "a line" : "a point") +
                       " element (points and lines cannot bound a solid)");
        }
    }
    // indices are resolved once every vertex is known: a face may name a vertex written after it
    std::vector<std::uint32_t> corners;
    for (const Face& face : faces)
    {
        corners.clear();
        for (const std::int64_t index : face.corners)
        {
            const auto count = static_cast<std::int64_t>(face.vertexCount);
            const std::int64_t resolved = index > 0 ? index - 1 : count + index;
            if (resolved < 0 || resolved >= static_cast<std::int64_t>(mesh.vertices.size()))
            {
                refuse(name, face.line,
                       "a face names vertex " + std::to_string(index) + ", but " +
                           (index > 0 ? "the file has " + std::to_string(mesh.vertices.size())
                                      : "only " + std::to_string(count) + " come before it"));
            }
            corners.push_back(static_cast<std::uint32_t>(resolved));
        }
        triangulate(corners, mesh.vertices, mesh.triangles);
    }
    return mesh;
}

std::uint32_t littleEndian32(const char* bytes)
{
    std::uint32_t value = 0;
    for (int k = 3; k >= 0; --k)
    {
        value = (value << 8) | static_cast<unsigned char>(bytes[k]);
    }
    return value;
}

float littleEndianFloat(const char* bytes)
{
    const std::uint32_t bits = littleEndian32(bytes);
    float value = 0.0f;
    std::memcpy(&value, &bits, sizeof value);
    return value;
}

// STL, binary: an 80-byte header, a little-endian triangle count, and 50 bytes a triangle (normal,
// three corners as floats, two attribute bytes). ASCII: "solid", then "facet normal ..", "outer
// loop", three "vertex x y z", "endloop", "endfacet" per triangle, and "endsolid". Normals are
// ignored: a triangle faces where its corners turn counter-clockwise.
TriangleMesh readStl(const std::string& text, const std::string& name)
{
    TriangleMesh mesh;
    const std::size_t begin = text.find_first_not_of(" \t\r\n");
    const bool solid = begin != std::string::npos && text.compare(begin, 5, "solid") == 0;
    // a binary file may begin with "solid" too, but its count and attribute bytes are not text
    const bool isText =
        std::none_of(text.begin(), text.end(),
                     [](char c)
                     {
                         const auto byte = static_cast<unsigned char>(c);
                         return byte < 0x20 && byte != '\t' && byte != '\n' && byte != '\r' && byte != '\f';
                     });
    const std::uint64_t announced = text.size() >= 84 ? littleEndian32(text.data() + 80) : 0;
    const bool fitsBinary = text.size() >= 84 && 84 + 50 * announced <= text.size();
    if (!(solid && isText) || (fitsBinary && 84 + 50 * announced == text.size()))
    {
        if (!fitsBinary)
        {
            throw MeshFileError(name + ": not an STL file: " + std::to_string(text.size()) + " bytes" +
                                (text.size() < 84 ? ", less than the 84 of a binary STL's header"
                                                  : " cannot hold the " + std::to_string(announced) +
                                                        " triangles its header announces") +
                                (solid ? ", and it is not text as an ASCII STL is"
                                       : ", and it does not begin with \"solid\" as an ASCII STL does"));
        }
        mesh.vertices.reserve(3 * announced);
        for (std::uint64_t t = 0; t < announced; ++t)
        {
            const char* record = text.data() + 84 + 50 * t;
            const auto first = static_cast<std::uint32_t>(mesh.vertices.size());
            for (int corner = 0; corner < 3; ++corner)
            {
                const char* xyz = record + 12 + 12 * corner;
                mesh.vertices.emplace_back(littleEndianFloat(xyz), littleEndianFloat(xyz + 4),
                                           littleEndianFloat(xyz + 8));
            }
            mesh.triangles.push_back({first, first + 1, first + 2});
        }
        return mesh;
    }
    std::size_t lineNumber = 0;
    std::size_t at = 0;
    int corners = -1; // of the open facet; -1 outside one
    std::size_t facetLine = 0;
    while (at < text.size())
    {
        const std::size_t end = std::min(text.find('\n', at), text.size());
        const std::vector<std::string_view> w = words(std::string_view(text.data() + at, end - at));
        ++lineNumber;
        at = end + 1;
        if (w.empty() || w[0] == "solid" || w[0] == "endsolid" || w[0] == "outer" || w[0] == "endloop")
        {
            continue; // names after solid and endsolid are free text
        }
        if (w[0] == "facet")
        {
            if (corners >= 0)
            {
                refuse(name, lineNumber,
                       "a facet begins before the one at line " + std::to_string(facetLine) + " ends");
            }
            corners = 0;
            facetLine = lineNumber;
        }
        else if (w[0] == "vertex")
        {
            if (corners < 0)
            {
                refuse(name, lineNumber, "a vertex outside a facet");
            }
            if (w.size() != 4)
            {
                refuse(name, lineNumber, "a vertex needs 3 coordinates, got " + std::to_string(w.size() - 1));
            }
            if (corners == 3)
            {
                refuse(name, lineNumber, "a facet with more than 3 vertices");
            }
            mesh.vertices.emplace_back(coordinate(w[1], name, lineNumber), coordinate(w[2], name, lineNumber),
                                       coordinate(w[3], name, lineNumber));
            ++corners;
        }
        else if (w[0] == "endfacet")
        {
            if (corners != 3)
            {
                refuse(name, lineNumber,
                       corners < 0 ? std::string("endfacet without a facet")
                                   : "the facet from line " + std::to_string(facetLine) + " has " +
                                         std::to_string(corners) + " vertices, not 3");
            }
            const auto first = static_cast<std::uint32_t>(mesh.vertices.size() - 3);
            mesh.triangles.push_back({first, first + 1, first + 2});
            corners = -1;
        }
        else
        {
            refuse(name, lineNumber,
                   "expected facet, outer loop, vertex, endloop, endfacet or endsolid, got " + quoted(w[0]));
        }
    }
    if (corners >= 0)
    {
        refuse(name, facetLine, "the facet that begins here has no endfacet (the file is cut off)");
    }
    return mesh;
}

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
    std::string extension = path.extension().string();
    std::transform(extension.begin(), extension.end(), extension.begin(),
                   [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
    TriangleMesh mesh;
    if (extension == ".obj" || extension == ".stl")
    {
        std::ifstream in(path, std::ios::binary);
        const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
        if (!in.good() && !in.eof())
        {
            throw MeshFileError(name + ": cannot read the file");
        }
        mesh = extension == ".obj" ? readObj(text, name) : readStl(text, name);
    }
    else
    {
        Assimp::Importer importer;
        importer.SetIOHandler(new OnlyTheMeshFile(name)); // the importer owns it
        // assimp reads coordinates as float unless built for double: fine for meshes, which are
        // welded on exact equality afterwards
        const aiScene* scene = importer.ReadFile(name, aiProcess_Triangulate);
        if (scene == nullptr || scene->mRootNode == nullptr)
        {
            throw MeshFileError(name + ": cannot read the mesh: " + importer.GetErrorString());
        }
        collect(*scene, *scene->mRootNode, aiMatrix4x4(), name, mesh);
    }
    if (mesh.triangles.empty())
    {
        throw MeshFileError(name + ": contains no triangles");
    }
    return mesh;
}

} // namespace impulse::io
