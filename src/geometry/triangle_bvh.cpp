// SPDX-License-Identifier: MIT
#include "geometry/triangle_bvh.hpp"

#include "geometry/box_queries.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <numbers>

namespace impulse
{
namespace
{

constexpr std::uint32_t kLeafSize = 4;

// Does the segment a + t d, t in [0, 1], meet the box?
bool segmentMeetsBox(const Vec3& a, const Vec3& d, const Vec3& lower, const Vec3& upper)
{
    Real enter = 0.0;
    Real leave = 0.0;
    return clipSegmentToBox(a, d, lower, upper, enter, leave);
}

Real cornerAngle(const Vec3& at, const Vec3& next, const Vec3& previous)
{
    const Vec3 u = (next - at).normalized();
    const Vec3 w = (previous - at).normalized();
    return std::atan2(u.cross(w).norm(), u.dot(w));
}

// closestPointOnTriangle, inlined into the searches (the compiler would call it)
[[gnu::always_inline]] inline TrianglePoint closestOnTriangle(const Vec3& p, const Vec3& a, const Vec3& b,
                                                              const Vec3& c, const Vec3& ab, const Vec3& ac)
{
    // Voronoi regions of the triangle, tested corner, edge, then face (Ericson, Real-Time Collision
    // Detection, sec. 5.1.5), from dot products of the edges with the corner-to-point vectors.
    const Vec3 ap = p - a;
    const Real d1 = ab.dot(ap);
    const Real d2 = ac.dot(ap);
    if (d1 <= 0.0 && d2 <= 0.0)
    {
        return {a, TriangleFeature::Vertex0};
    }
    const Vec3 bp = p - b;
    const Real d3 = ab.dot(bp);
    const Real d4 = ac.dot(bp);
    if (d3 >= 0.0 && d4 <= d3)
    {
        return {b, TriangleFeature::Vertex1};
    }
    const Real vc = d1 * d4 - d3 * d2;
    if (vc <= 0.0 && d1 >= 0.0 && d3 <= 0.0)
    {
        return {a + ab * (d1 / (d1 - d3)), TriangleFeature::Edge0};
    }
    const Vec3 cp = p - c;
    const Real d5 = ab.dot(cp);
    const Real d6 = ac.dot(cp);
    if (d6 >= 0.0 && d5 <= d6)
    {
        return {c, TriangleFeature::Vertex2};
    }
    const Real vb = d5 * d2 - d1 * d6;
    if (vb <= 0.0 && d2 >= 0.0 && d6 <= 0.0)
    {
        return {a + ac * (d2 / (d2 - d6)), TriangleFeature::Edge2};
    }
    const Real va = d3 * d6 - d5 * d4;
    if (va <= 0.0 && d4 - d3 >= 0.0 && d5 - d6 >= 0.0)
    {
        return {b + (c - b) * ((d4 - d3) / ((d4 - d3) + (d5 - d6))), TriangleFeature::Edge1};
    }
    const Real scale = 1.0 / (va + vb + vc);
    return {a + ab * (vb * scale) + ac * (vc * scale), TriangleFeature::Face};
}

} // namespace

TrianglePoint closestPointOnTriangle(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c)
{
    return closestOnTriangle(p, a, b, c, b - a, c - a);
}

TriangleBvh::TriangleBvh(const TriangleMesh& mesh)
    : m_vertices(mesh.vertices), m_triangles(mesh.triangles), m_faceNormals(mesh.triangles.size()),
      m_edgeNormals(mesh.triangles.size()), m_vertexNormals(mesh.vertices.size(), Vec3::Zero())
{
    // pseudonormals: faces by their normal, edges by the sum of both faces (each seen under an
    // angle pi), corners by the sum of the incident faces weighted by the angle at the corner
    std::map<std::pair<std::uint32_t, std::uint32_t>, Vec3> edgeSums;
    for (std::size_t t = 0; t < m_triangles.size(); ++t)
    {
        const auto& tri = m_triangles[t];
        const Vec3& a = m_vertices[tri[0]];
        const Vec3& b = m_vertices[tri[1]];
        const Vec3& c = m_vertices[tri[2]];
        const Vec3 normal = (b - a).cross(c - a).normalized();
        m_faceNormals[t] = normal;
        m_vertexNormals[tri[0]] += cornerAngle(a, b, c) * normal;
        m_vertexNormals[tri[1]] += cornerAngle(b, c, a) * normal;
        m_vertexNormals[tri[2]] += cornerAngle(c, a, b) * normal;
        for (int k = 0; k < 3; ++k)
        {
            // Eigen leaves a default-constructed vector uninitialised: start each sum at zero
            edgeSums.try_emplace(std::minmax(tri[k], tri[(k + 1) % 3]), Vec3::Zero()).first->second += normal;
        }
    }
    for (std::size_t t = 0; t < m_triangles.size(); ++t)
    {
        const auto& tri = m_triangles[t];
        for (int k = 0; k < 3; ++k)
        {
            m_edgeNormals[t][k] = edgeSums.at(std::minmax(tri[k], tri[(k + 1) % 3]));
        }
    }

    std::vector<Vec3> centroids(m_triangles.size());
    for (std::size_t t = 0; t < m_triangles.size(); ++t)
    {
        const auto& tri = m_triangles[t];
        centroids[t] = (m_vertices[tri[0]] + m_vertices[tri[1]] + m_vertices[tri[2]]) / 3.0;
    }
    m_order.resize(m_triangles.size());
    for (std::uint32_t t = 0; t < m_order.size(); ++t)
    {
        m_order[t] = t;
    }
    m_nodes.reserve(2 * m_triangles.size() / kLeafSize + 2);
    buildNode(0, static_cast<std::uint32_t>(m_order.size()), centroids);
    m_leafTriangles.reserve(m_order.size());
    for (const std::uint32_t t : m_order)
    {
        const auto& tri = m_triangles[t];
        const Vec3& a = m_vertices[tri[0]];
        const Vec3& b = m_vertices[tri[1]];
        const Vec3& c = m_vertices[tri[2]];
        m_leafTriangles.push_back({a, b, c, b - a, c - a, t});
    }
}

// Builds the subtree over m_order[begin, end) and returns its index: a leaf for a few triangles, else
// a split at the median centroid along the longest axis of the centroids' box.
std::uint32_t TriangleBvh::buildNode(std::uint32_t begin, std::uint32_t end, const std::vector<Vec3>& centroids)
{
    Node node;
    node.lower = Vec3::Constant(std::numeric_limits<Real>::infinity());
    node.upper = -node.lower;
    Vec3 centreLower = node.lower;
    Vec3 centreUpper = node.upper;
    for (std::uint32_t i = begin; i < end; ++i)
    {
        for (const std::uint32_t v : m_triangles[m_order[i]])
        {
            node.lower = node.lower.cwiseMin(m_vertices[v]);
            node.upper = node.upper.cwiseMax(m_vertices[v]);
        }
        centreLower = centreLower.cwiseMin(centroids[m_order[i]]);
        centreUpper = centreUpper.cwiseMax(centroids[m_order[i]]);
    }
    const auto index = static_cast<std::uint32_t>(m_nodes.size());
    m_nodes.push_back(node);
    if (end - begin <= kLeafSize)
    {
        m_nodes[index].first = begin;
        m_nodes[index].count = end - begin;
        return index;
    }
    int axis = 0;
    (centreUpper - centreLower).maxCoeff(&axis);
    const std::uint32_t middle = begin + (end - begin) / 2;
    std::nth_element(m_order.begin() + begin, m_order.begin() + middle, m_order.begin() + end,
                     [&](std::uint32_t x, std::uint32_t y)
                     {
                         // ties broken by index, so the tree is the same whatever the library's sort
                         return centroids[x][axis] < centroids[y][axis] ||
                                (centroids[x][axis] == centroids[y][axis] && x < y);
                     });
    const std::uint32_t left = buildNode(begin, middle, centroids);
    const std::uint32_t right = buildNode(middle, end, centroids);
    m_nodes[index].left = left;
    m_nodes[index].right = right;
    return index;
}

Vec3 TriangleBvh::pseudonormal(std::uint32_t triangle, TriangleFeature feature) const
{
    switch (feature)
    {
    case TriangleFeature::Face:
        return m_faceNormals[triangle];
    case TriangleFeature::Edge0:
    case TriangleFeature::Edge1:
    case TriangleFeature::Edge2:
        return m_edgeNormals[triangle][static_cast<int>(feature) - static_cast<int>(TriangleFeature::Edge0)];
    default:
        return m_vertexNormals[m_triangles[triangle]
                                          [static_cast<int>(feature) - static_cast<int>(TriangleFeature::Vertex0)]];
    }
}

SurfacePoint TriangleBvh::closestPoint(const Vec3& p, Real maxDistance) const
{
    SurfacePoint best;
    Real bestSquared = maxDistance * maxDistance;
    TriangleFeature bestFeature = TriangleFeature::Face;
    // Depth-first, nearer child first, pruning boxes not nearer than the best so far. An entry keeps
    // the squared distance to its box, computed when its parent compared the two children by it, so
    // that it is not computed again when the entry is popped and tested against the best.
    struct Entry
    {
        std::uint32_t node;
        Real squared;
    };
    Entry stack[64];
    int top = 0;
    stack[top++] = {0, squaredDistanceToBox(p, m_nodes[0].lower, m_nodes[0].upper)};
    while (top > 0)
    {
        const Entry entry = stack[--top];
        if (entry.squared >= bestSquared)
        {
            continue;
        }
        const Node& node = m_nodes[entry.node];
        if (node.count > 0)
        {
            for (std::uint32_t i = node.first; i < node.first + node.count; ++i)
            {
                const LeafTriangle& triangle = m_leafTriangles[i];
                const TrianglePoint candidate =
                    closestOnTriangle(p, triangle.a, triangle.b, triangle.c, triangle.ab, triangle.ac);
                const Real squared = (p - candidate.point).squaredNorm();
                if (squared < bestSquared)
                {
                    bestSquared = squared;
                    best.found = true;
                    best.point = candidate.point;
                    best.triangle = triangle.index;
                    bestFeature = candidate.feature;
                }
            }
            continue;
        }
        const Real toLeft = squaredDistanceToBox(p, m_nodes[node.left].lower, m_nodes[node.left].upper);
        const Real toRight = squaredDistanceToBox(p, m_nodes[node.right].lower, m_nodes[node.right].upper);
        // push the farther child first so the nearer is searched first (selects, not branches: which
        // is nearer is a coin toss to the branch predictor)
        const bool leftFirst = toLeft <= toRight;
        stack[top].node = leftFirst ? node.right : node.left;
        stack[top].squared = leftFirst ? toRight : toLeft;
        stack[top + 1].node = leftFirst ? node.left : node.right;
        stack[top + 1].squared = leftFirst ? toLeft : toRight;
        top += 2;
    }
    if (best.found)
    {
        best.distance = std::sqrt(bestSquared);
        best.pseudonormal = pseudonormal(best.triangle, bestFeature);
    }
    return best;
}

Real TriangleBvh::signedDistance(const Vec3& p, const SurfacePoint& closest)
{
    return (p - closest.point).dot(closest.pseudonormal) < 0.0 ? -closest.distance : closest.distance;
}

Real TriangleBvh::distanceToTriangle(const Vec3& p, std::uint32_t triangle) const
{
    const auto& tri = m_triangles[triangle];
    return (p - closestPointOnTriangle(p, m_vertices[tri[0]], m_vertices[tri[1]], m_vertices[tri[2]]).point).norm();
}

void TriangleBvh::trianglesNear(const Vec3& p, Real radius, std::vector<std::uint32_t>& out) const
{
    out.clear();
    const Real squaredRadius = radius * radius;
    forEachTriangleIn([&](const Vec3& lower, const Vec3& upper)
                      { return squaredDistanceToBox(p, lower, upper) < squaredRadius; },
                      [&](const LeafTriangle& triangle)
                      {
                          const Vec3 closest =
                              closestOnTriangle(p, triangle.a, triangle.b, triangle.c, triangle.ab, triangle.ac).point;
                          if ((p - closest).squaredNorm() < squaredRadius)
                          {
                              out.push_back(triangle.index);
                          }
                      });
}

void TriangleBvh::segmentCrossings(const Vec3& a, const Vec3& b, std::vector<SegmentCrossing>& out) const
{
    out.clear();
    const Vec3 direction = b - a;
    forEachTriangleIn([&](const Vec3& lower, const Vec3& upper) { return segmentMeetsBox(a, direction, lower, upper); },
                      [&](const LeafTriangle& triangle)
                      {
                          // Moller-Trumbore: solve a + t d = v0 + u e1 + v e2 by Cramer's rule
                          const Vec3& v0 = triangle.a;
                          const Vec3& e1 = triangle.ab;
                          const Vec3& e2 = triangle.ac;
                          const Vec3 pvec = direction.cross(e2);
                          const Real det = e1.dot(pvec); // = -direction . (e1 x e2): positive when entering
                          if (det == 0.0)
                          {
                              return; // parallel to the plane of the triangle
                          }
                          const Real inverse = 1.0 / det;
                          const Vec3 tvec = a - v0;
                          const Real u = tvec.dot(pvec) * inverse;
                          if (u < 0.0 || u > 1.0)
                          {
                              return;
                          }
                          const Vec3 qvec = tvec.cross(e1);
                          const Real v = direction.dot(qvec) * inverse;
                          if (v < 0.0 || u + v > 1.0)
                          {
                              return;
                          }
                          const Real along = e2.dot(qvec) * inverse;
                          if (along >= 0.0 && along <= 1.0)
                          {
                              out.push_back({along, det > 0.0});
                          }
                      });
    std::sort(out.begin(), out.end(),
              [](const SegmentCrossing& x, const SegmentCrossing& y)
              { return x.t < y.t || (x.t == y.t && x.entering && !y.entering); });
}

} // namespace impulse
