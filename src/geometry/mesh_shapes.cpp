// SPDX-License-Identifier: MIT
#include <impulse/mesh_shapes.hpp>

#include <cmath>
#include <numbers>

namespace impulse
{
namespace
{

using Index = std::uint32_t;

// Two triangles over the quad (a, b, c, d), counter-clockwise as listed.
void addQuad(TriangleMesh& mesh, Index a, Index b, Index c, Index d)
{
    mesh.triangles.push_back({a, b, c});
    mesh.triangles.push_back({a, c, d});
}

Index addVertex(TriangleMesh& mesh, const Vec3& v)
{
    mesh.vertices.push_back(v);
    return static_cast<Index>(mesh.vertices.size() - 1);
}

} // namespace

TriangleMesh sphereMesh(Real radius, int rings, int segments)
{
    TriangleMesh mesh;
    const Index south = addVertex(mesh, Vec3(0.0, 0.0, -radius));
    for (int ring = 1; ring < rings; ++ring)
    {
        const Real polar = std::numbers::pi * ring / rings; // from the south pole
        for (int s = 0; s < segments; ++s)
        {
            const Real azimuth = 2.0 * std::numbers::pi * s / segments;
            mesh.vertices.emplace_back(radius * std::sin(polar) * std::cos(azimuth),
                                       radius * std::sin(polar) * std::sin(azimuth), -radius * std::cos(polar));
        }
    }
    const Index north = addVertex(mesh, Vec3(0.0, 0.0, radius));
    const auto at = [&](int ring, int s) { return static_cast<Index>(1 + (ring - 1) * segments + s % segments); };
    for (int s = 0; s < segments; ++s)
    {
        mesh.triangles.push_back({south, at(1, s + 1), at(1, s)});
        mesh.triangles.push_back({north, at(rings - 1, s), at(rings - 1, s + 1)});
        for (int ring = 1; ring + 1 < rings; ++ring)
        {
            addQuad(mesh, at(ring, s), at(ring, s + 1), at(ring + 1, s + 1), at(ring + 1, s));
        }
    }
    return mesh;
}

TriangleMesh boxMesh(const Vec3& halfExtents, int subdivisions)
{
    // every face is a grid of the same coordinates, so vertices on shared edges are bit-identical
    // and the mesh is welded when prepared
    TriangleMesh mesh;
    const auto coordinate = [&](int axis, int i) { return halfExtents[axis] * (2.0 * i / subdivisions - 1.0); };
    for (int normalAxis = 0; normalAxis < 3; ++normalAxis)
    {
        const int u = (normalAxis + 1) % 3;
        const int v = (normalAxis + 2) % 3;
        for (const Real side : {-1.0, 1.0})
        {
            const Index first = static_cast<Index>(mesh.vertices.size());
            for (int j = 0; j <= subdivisions; ++j)
            {
                for (int i = 0; i <= subdivisions; ++i)
                {
                    Vec3 p;
                    p[normalAxis] = side * halfExtents[normalAxis];
                    p[u] = coordinate(u, i);
                    p[v] = coordinate(v, j);
                    mesh.vertices.push_back(p);
                }
            }
            const auto at = [&](int i, int j) { return first + static_cast<Index>(j * (subdivisions + 1) + i); };
            for (int j = 0; j < subdivisions; ++j)
            {
                for (int i = 0; i < subdivisions; ++i)
                {
                    // (u, v, normal) is right-handed: counter-clockwise in (u, v) faces +normal
                    if (side > 0.0)
                    {
                        addQuad(mesh, at(i, j), at(i + 1, j), at(i + 1, j + 1), at(i, j + 1));
                    }
                    else
                    {
                        addQuad(mesh, at(i, j), at(i, j + 1), at(i + 1, j + 1), at(i + 1, j));
                    }
                }
            }
        }
    }
    return mesh;
}

TriangleMesh torusMesh(Real major, Real minor, int majorSegments, int minorSegments)
{
    TriangleMesh mesh;
    for (int i = 0; i < majorSegments; ++i)
    {
        const Real around = 2.0 * std::numbers::pi * i / majorSegments;
        for (int j = 0; j < minorSegments; ++j)
        {
            const Real tube = 2.0 * std::numbers::pi * j / minorSegments;
            const Real distance = major + minor * std::cos(tube);
            mesh.vertices.emplace_back(distance * std::cos(around), distance * std::sin(around),
                                       minor * std::sin(tube));
        }
    }
    const auto at = [&](int i, int j)
    { return static_cast<Index>((i % majorSegments) * minorSegments + j % minorSegments); };
    for (int i = 0; i < majorSegments; ++i)
    {
        for (int j = 0; j < minorSegments; ++j)
        {
            addQuad(mesh, at(i, j), at(i + 1, j), at(i + 1, j + 1), at(i, j + 1));
        }
    }
    return mesh;
}

TriangleMesh cylinderMesh(Real radius, Real bottom, Real top, int segments)
{
    TriangleMesh mesh;
    const Index bottomCentre = addVertex(mesh, Vec3(0.0, 0.0, bottom));
    const Index topCentre = addVertex(mesh, Vec3(0.0, 0.0, top));
    for (int s = 0; s < segments; ++s)
    {
        const Real angle = 2.0 * std::numbers::pi * s / segments;
        mesh.vertices.emplace_back(radius * std::cos(angle), radius * std::sin(angle), bottom);
        mesh.vertices.emplace_back(radius * std::cos(angle), radius * std::sin(angle), top);
    }
    const auto low = [&](int s) { return static_cast<Index>(2 + 2 * (s % segments)); };
    const auto high = [&](int s) { return static_cast<Index>(3 + 2 * (s % segments)); };
    for (int s = 0; s < segments; ++s)
    {
        addQuad(mesh, low(s), low(s + 1), high(s + 1), high(s));
        mesh.triangles.push_back({bottomCentre, low(s + 1), low(s)});
        mesh.triangles.push_back({topCentre, high(s), high(s + 1)});
    }
    return mesh;
}

} // namespace impulse
