// SPDX-License-Identifier: MIT
#include <impulse/mesh_shapes.hpp>
#include <impulse/viz/tessellate.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <variant>

namespace impulse::viz
{
namespace
{

Rgb mix(Rgb a, Rgb b, float t)
{
    return {a.r + (b.r - a.r) * t, a.g + (b.g - a.g) * t, a.b + (b.b - a.b) * t};
}

void addTriangle(TriangleMesh& mesh, const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& na, const Vec3& nb,
                 const Vec3& nc, Rgb colour)
{
    const auto first = static_cast<std::uint32_t>(mesh.positions.size());
    mesh.positions.insert(mesh.positions.end(), {a, b, c});
    mesh.normals.insert(mesh.normals.end(), {na, nb, nc});
    mesh.colours.insert(mesh.colours.end(), {colour, colour, colour});
    mesh.triangles.push_back({first, first + 1, first + 2});
}

void addFlatTriangle(TriangleMesh& mesh, const Vec3& a, const Vec3& b, const Vec3& c, Rgb colour)
{
    const Vec3 normal = (b - a).cross(c - a).normalized();
    addTriangle(mesh, a, b, c, normal, normal, normal, colour);
}

/// Octants of alternating shade, like a beach ball: the eye sees a sphere spin.
TriangleMesh sphereTriangles(const Sphere& sphere, Rgb colour)
{
    constexpr int slices = 32; // a multiple of 4 and an even number of stacks keep octant borders on edges
    constexpr int stacks = 16;
    const Rgb light = mix(colour, {1.0f, 1.0f, 1.0f}, 0.55f);
    auto unit = [](int stack, int slice)
    {
        const Real polar = std::numbers::pi * stack / stacks;
        const Real azimuth = 2.0 * std::numbers::pi * slice / slices;
        return Vec3(std::sin(polar) * std::cos(azimuth), std::sin(polar) * std::sin(azimuth), std::cos(polar));
    };
    TriangleMesh mesh;
    for (int stack = 0; stack < stacks; ++stack)
    {
        for (int slice = 0; slice < slices; ++slice)
        {
            const Vec3 n00 = unit(stack, slice);
            const Vec3 n01 = unit(stack, slice + 1);
            const Vec3 n10 = unit(stack + 1, slice);
            const Vec3 n11 = unit(stack + 1, slice + 1);
            const Real polarMid = std::numbers::pi * (stack + 0.5) / stacks;
            const Real azimuthMid = 2.0 * std::numbers::pi * (slice + 0.5) / slices;
            const Vec3 centre(std::sin(polarMid) * std::cos(azimuthMid), std::sin(polarMid) * std::sin(azimuthMid),
                              std::cos(polarMid));
            const int parity = (centre.x() > 0) + (centre.y() > 0) + (centre.z() > 0);
            const Rgb shade = parity % 2 == 0 ? colour : light;
            const Real r = sphere.radius;
            if (stack > 0)
            {
                addTriangle(mesh, r * n00, r * n10, r * n01, n00, n10, n01, shade);
            }
            if (stack + 1 < stacks)
            {
                addTriangle(mesh, r * n01, r * n10, r * n11, n01, n10, n11, shade);
            }
        }
    }
    return mesh;
}

TriangleMesh boxTriangles(const Box& box, Rgb colour)
{
    // corner k has coordinate i at +h[i] when bit i of k is set
    std::vector<Vec3> corners;
    for (int k = 0; k < 8; ++k)
    {
        corners.emplace_back((k & 1) ? box.halfExtents.x() : -box.halfExtents.x(),
                             (k & 2) ? box.halfExtents.y() : -box.halfExtents.y(),
                             (k & 4) ? box.halfExtents.z() : -box.halfExtents.z());
    }
    // two triangles per face, counter-clockwise seen from outside: -x, +x, -y, +y, -z, +z
    const std::vector<std::array<std::uint32_t, 3>> triangles = {{0, 4, 6}, {0, 6, 2}, {1, 3, 7}, {1, 7, 5},
                                                                 {0, 1, 5}, {0, 5, 4}, {2, 6, 7}, {2, 7, 3},
                                                                 {0, 2, 3}, {0, 3, 1}, {4, 5, 7}, {4, 7, 6}};
    return flatShaded(corners, triangles, colour);
}

/// 1, 2 or 5 times a power of ten, near `value`: tiles of a size people read off at a glance.
Real niceLength(Real value)
{
    const Real decade = std::pow(10.0, std::floor(std::log10(value)));
    const Real mantissa = value / decade;
    return decade * (mantissa < 1.5 ? 1.0 : mantissa < 3.5 ? 2.0 : mantissa < 7.5 ? 5.0 : 10.0);
}

TriangleMesh planeTriangles(const Plane& plane, const PlanePatch& patch)
{
    const Vec3 n = plane.normal.normalized();
    // a basis of the plane fixed by the normal alone, so the checkerboard does not move with the focus
    const Vec3 helper = std::abs(n.x()) < 0.9 ? Vec3(Vec3::UnitX()) : Vec3(Vec3::UnitY());
    const Vec3 a = (helper - helper.dot(n) * n).normalized();
    const Vec3 b = n.cross(a);
    const Vec3 origin = plane.offset * n;
    const Real tile = niceLength(patch.halfSize / 8.0);
    const Real focusA = (patch.focus - origin).dot(a);
    const Real focusB = (patch.focus - origin).dot(b);
    const auto tiles = static_cast<long>(std::ceil(patch.halfSize / tile));
    const long firstA = std::lround(focusA / tile) - tiles;
    const long firstB = std::lround(focusB / tile) - tiles;
    const Rgb dark{0.62f, 0.64f, 0.66f};
    const Rgb light{0.80f, 0.81f, 0.82f};
    TriangleMesh mesh;
    for (long i = firstA; i < firstA + 2 * tiles; ++i)
    {
        for (long j = firstB; j < firstB + 2 * tiles; ++j)
        {
            const Vec3 p00 = origin + static_cast<Real>(i) * tile * a + static_cast<Real>(j) * tile * b;
            const Vec3 p10 = p00 + tile * a;
            const Vec3 p11 = p10 + tile * b;
            const Vec3 p01 = p00 + tile * b;
            const Rgb shade = (i + j) % 2 == 0 ? light : dark;
            addTriangle(mesh, p00, p10, p11, n, n, n, shade);
            addTriangle(mesh, p00, p11, p01, n, n, n, shade);
        }
    }
    return mesh;
}

} // namespace

TriangleMesh flatShaded(const std::vector<Vec3>& vertices, const std::vector<std::array<std::uint32_t, 3>>& triangles,
                        Rgb colour)
{
    TriangleMesh mesh;
    for (const auto& t : triangles)
    {
        addFlatTriangle(mesh, vertices.at(t[0]), vertices.at(t[1]), vertices.at(t[2]), colour);
    }
    return mesh;
}

Rgb bodyColour(std::size_t body)
{
    static const Rgb palette[] = {{0.85f, 0.37f, 0.01f}, {0.11f, 0.62f, 0.47f}, {0.46f, 0.44f, 0.70f},
                                  {0.91f, 0.16f, 0.54f}, {0.40f, 0.65f, 0.12f}, {0.90f, 0.67f, 0.01f},
                                  {0.65f, 0.46f, 0.11f}, {0.22f, 0.42f, 0.69f}};
    return palette[body % std::size(palette)];
}

std::string hexColour(Rgb colour)
{
    auto byte = [](float c) { return static_cast<int>(std::lround(std::clamp(c, 0.0f, 1.0f) * 255.0f)); };
    char text[8];
    std::snprintf(text, sizeof text, "#%02x%02x%02x", byte(colour.r), byte(colour.g), byte(colour.b));
    return text;
}

TriangleMesh bodyTriangles(const Shape& shape, Rgb colour, const PlanePatch& patch)
{
    // the one place that knows every kind of shape; a new shape is one more case here
    return std::visit(
        [&](const auto& s) -> TriangleMesh
        {
            using S = std::decay_t<decltype(s)>;
            if constexpr (std::is_same_v<S, Sphere>)
            {
                return sphereTriangles(s, colour);
            }
            else if constexpr (std::is_same_v<S, Box>)
            {
                return boxTriangles(s, colour);
            }
            else if constexpr (std::is_same_v<S, Capsule>)
            {
                // a ball with an odd number of bands, its halves pulled apart along z: the band
                // across the equator becomes the cylinder
                impulse::TriangleMesh ball = sphereMesh(s.radius, 15, 24);
                for (Vec3& v : ball.vertices)
                {
                    v.z() += v.z() > 0.0 ? s.halfLength : -s.halfLength;
                }
                return flatShaded(ball.vertices, ball.triangles, colour);
            }
            else if constexpr (std::is_same_v<S, Mesh>)
            {
                return flatShaded(s.geometry->vertices(), s.geometry->triangles(), colour);
            }
            else
            {
                static_assert(std::is_same_v<S, Plane>, "bodyTriangles: tessellate the new shape here");
                return planeTriangles(s, patch);
            }
        },
        shape);
}

} // namespace impulse::viz
