// SPDX-License-Identifier: MIT
// A bounding-volume hierarchy over the triangles of a closed mesh: closest-point queries with the
// sign from angle-weighted pseudonormals (Baerentzen & Aanaes 2005), and segment crossings.
#pragma once

#include <impulse/mesh.hpp>

#include <cstdint>
#include <vector>

namespace impulse
{

/// The part of a triangle a closest point lies on: its interior, one of its edges (edge k joins
/// corners k and k+1 mod 3) or one of its corners.
enum class TriangleFeature : std::uint8_t
{
    Face,
    Edge0,
    Edge1,
    Edge2,
    Vertex0,
    Vertex1,
    Vertex2,
};

/// Closest point of a triangle to a query point.
struct TrianglePoint
{
    Vec3 point = Vec3::Zero();
    TriangleFeature feature = TriangleFeature::Face;
};

/// Closest point of triangle (a, b, c) to p, with the feature it lies on.
TrianglePoint closestPointOnTriangle(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c);

/// Result of a closest-point search.
struct SurfacePoint
{
    bool found = false;        ///< false when no triangle lies within the search radius
    Real distance = 0.0;       ///< unsigned
    Vec3 point = Vec3::Zero(); ///< closest point on the surface
    Vec3 pseudonormal = Vec3::UnitZ();
    std::uint32_t triangle = 0;
};

/// A crossing of the surface by a segment: parameter t along it and whether it enters the solid.
struct SegmentCrossing
{
    Real t = 0.0;
    bool entering = false;
};

class TriangleBvh
{
  public:
    /// `mesh` must be closed and consistently oriented (see MeshGeometry::build).
    explicit TriangleBvh(const TriangleMesh& mesh);

    /// Closest point of the surface to p among triangles closer than maxDistance.
    SurfacePoint closestPoint(const Vec3& p, Real maxDistance) const;
    /// Signed distance from a closest point: negative when p is inside the solid.
    static Real signedDistance(const Vec3& p, const SurfacePoint& closest);

    /// Unsigned distance from p to one triangle.
    Real distanceToTriangle(const Vec3& p, std::uint32_t triangle) const;

    /// Every triangle with a point closer to p than `radius`, in tree order.
    void trianglesNear(const Vec3& p, Real radius, std::vector<std::uint32_t>& out) const;
    const Vec3& faceNormal(std::uint32_t triangle) const { return m_faceNormals[triangle]; }
    const std::array<std::uint32_t, 3>& triangle(std::uint32_t t) const { return m_triangles[t]; }
    const Vec3& vertex(std::uint32_t v) const { return m_vertices[v]; }

    /// Every crossing of the segment a->b with the surface, sorted by t.
    void segmentCrossings(const Vec3& a, const Vec3& b, std::vector<SegmentCrossing>& out) const;

    std::size_t triangleCount() const { return m_triangles.size(); }

  private:
    /// A node as the tree is built: triangles order[first, first + count) for a leaf.
    struct Node
    {
        Vec3 lower;
        Vec3 upper;
        std::uint32_t left = 0; ///< inner node: children
        std::uint32_t right = 0;
        std::uint32_t first = 0; ///< leaf: first index into the order of the triangles
        std::uint32_t count = 0; ///< leaf: number of triangles; 0 for an inner node
    };

    /// An inner node of the tree as it is searched: both children's boxes side by side (lane 0
    /// left, lane 1 right), so that one pass of paired operations measures both, and a reference
    /// to each child: an inner node's index, or with kLeafBit a leaf's first triangle in
    /// m_leafTriangles (bits 3-30) and their number (bits 0-2).
    struct InnerNode
    {
        alignas(16) Real lowerX[2];
        Real lowerY[2];
        Real lowerZ[2];
        Real upperX[2];
        Real upperY[2];
        Real upperZ[2];
        std::uint32_t child[2];

        Vec3 lower(int k) const { return {lowerX[k], lowerY[k], lowerZ[k]}; }
        Vec3 upper(int k) const { return {upperX[k], upperY[k], upperZ[k]}; }
    };
    static constexpr std::uint32_t kLeafBit = 1u << 31;

    /// A triangle's corners stored with its leaf, so that a leaf's triangles are read in one sweep
    /// instead of through the order, m_triangles and m_vertices.
    struct LeafTriangle
    {
        Vec3 a;
        Vec3 b;
        Vec3 c;
        Vec3 ab;                 ///< b - a
        Vec3 ac;                 ///< c - a
        std::uint32_t index = 0; ///< into m_triangles
    };

    /// Depth first, left before right: visit(triangle) for each triangle of every leaf reached
    /// through boxes that are entered: enters(lower, upper) for the root's box, and for the two
    /// children of an inner node entersChildren(node), bit 0 for the left and bit 1 for the right.
    template <class Enters, class EntersChildren, class Visit>
    void forEachTriangleIn(Enters enters, EntersChildren entersChildren, Visit visit) const
    {
        if (!enters(m_rootLower, m_rootUpper))
        {
            return;
        }
        std::uint32_t stack[64]; // children whose boxes were entered
        int top = 0;
        stack[top++] = m_rootChild;
        while (top > 0)
        {
            const std::uint32_t child = stack[--top];
            if (child & kLeafBit)
            {
                const std::uint32_t first = (child & ~kLeafBit) >> 3;
                for (std::uint32_t i = first; i < first + (child & 7u); ++i)
                {
                    visit(m_leafTriangles[i]);
                }
                continue;
            }
            const InnerNode& node = m_inner[child];
            const int entered = entersChildren(node);
            if (entered & 2)
            {
                stack[top++] = node.child[1];
            }
            if (entered & 1)
            {
                stack[top++] = node.child[0];
            }
        }
    }

    std::uint32_t buildNode(std::uint32_t begin, std::uint32_t end, const std::vector<Vec3>& centroids,
                            std::vector<std::uint32_t>& order, std::vector<Node>& nodes);
    Vec3 pseudonormal(std::uint32_t triangle, TriangleFeature feature) const;

    std::vector<Vec3> m_vertices;
    std::vector<std::array<std::uint32_t, 3>> m_triangles;
    std::vector<Vec3> m_faceNormals;                ///< unit, outward
    std::vector<std::array<Vec3, 3>> m_edgeNormals; ///< per triangle edge, sum of the two face normals
    std::vector<Vec3> m_vertexNormals;              ///< angle-weighted sums of incident face normals
    std::vector<LeafTriangle> m_leafTriangles;      ///< the triangles in tree order, leaves contiguous
    std::vector<InnerNode> m_inner;                 ///< depth first, left before right
    Vec3 m_rootLower = Vec3::Zero();                ///< the root's box
    Vec3 m_rootUpper = Vec3::Zero();
    std::uint32_t m_rootChild = 0; ///< the root, as InnerNode::child refers to it
};

} // namespace impulse
