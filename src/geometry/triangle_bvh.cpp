// SPDX-License-Identifier: MIT
#include "geometry/triangle_bvh.hpp"

#include "geometry/box_queries.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <numbers>
#include <numeric>
#include <string>

#if defined(__SSE2__)
#include <emmintrin.h>
#endif

namespace impulse
{
namespace
{

constexpr std::uint32_t kLeafSize = 4;
static_assert(kLeafSize < 8, "a leaf's triangle count has 3 bits in InnerNode::child");

// Does the segment a + t d, t in [0, 1], meet the box?
bool segmentMeetsBox(const Vec3& a, const Vec3& d, const Vec3& lower, const Vec3& upper)
{
    Real enter = 0.0;
    Real leave = 0.0;
    return clipSegmentToBox(a, d, lower, upper, enter, leave);
}

#if defined(__SSE2__)
// Squared distances from p (each coordinate in both lanes) to the two boxes of a paired node: per
// lane exactly the operations of squaredDistanceToBox.
template <class Pair> __m128d pairSquaredDistance(const Pair& node, __m128d px, __m128d py, __m128d pz)
{
    const __m128d zero = _mm_setzero_pd();
    const __m128d dx = _mm_max_pd(
        zero, _mm_max_pd(_mm_sub_pd(px, _mm_load_pd(node.upperX)), _mm_sub_pd(_mm_load_pd(node.lowerX), px)));
    const __m128d dy = _mm_max_pd(
        zero, _mm_max_pd(_mm_sub_pd(py, _mm_load_pd(node.upperY)), _mm_sub_pd(_mm_load_pd(node.lowerY), py)));
    const __m128d dz = _mm_max_pd(
        zero, _mm_max_pd(_mm_sub_pd(pz, _mm_load_pd(node.upperZ)), _mm_sub_pd(_mm_load_pd(node.lowerZ), pz)));
    return _mm_add_pd(_mm_add_pd(_mm_mul_pd(dx, dx), _mm_mul_pd(dy, dy)), _mm_mul_pd(dz, dz));
}
#endif

// Which of the two boxes of a paired node the segment a + t d, t in [0, 1], meets (bit 0, bit 1):
// per box the answer of clipSegmentToBox. Its early exits are left out: enter only grows and leave
// only shrinks, so a box it leaves early still has enter > leave at the end.
template <class Pair> int pairMeetsSegment(const Pair& node, const Vec3& a, const Vec3& d)
{
#if defined(__SSE2__)
    const Real* const lower[3] = {node.lowerX, node.lowerY, node.lowerZ};
    const Real* const upper[3] = {node.upperX, node.upperY, node.upperZ};
    __m128d enter = _mm_setzero_pd();
    __m128d leave = _mm_set1_pd(1.0);
    __m128d missed = _mm_setzero_pd();
    for (int axis = 0; axis < 3; ++axis)
    {
        const __m128d start = _mm_set1_pd(a[axis]);
        const __m128d low = _mm_load_pd(lower[axis]);
        const __m128d high = _mm_load_pd(upper[axis]);
        if (std::abs(d[axis]) < std::numeric_limits<Real>::min())
        {
            missed = _mm_or_pd(missed, _mm_or_pd(_mm_cmplt_pd(start, low), _mm_cmpgt_pd(start, high)));
            continue;
        }
        const __m128d step = _mm_set1_pd(d[axis]);
        const __m128d t0 = _mm_div_pd(_mm_sub_pd(low, start), step);
        const __m128d t1 = _mm_div_pd(_mm_sub_pd(high, start), step);
        // if (t0 > t1) swap; enter = std::max(enter, t0); leave = std::min(leave, t1)
        enter = _mm_max_pd(_mm_min_pd(t1, t0), enter);
        leave = _mm_min_pd(_mm_max_pd(t0, t1), leave);
    }
    return ~_mm_movemask_pd(_mm_or_pd(missed, _mm_cmpgt_pd(enter, leave))) & 3;
#else
    int meets = 0;
    for (int k = 0; k < 2; ++k)
    {
        Real enter = 0.0;
        Real leave = 0.0;
        meets |= clipSegmentToBox(a, d, node.lower(k), node.upper(k), enter, leave) ? 1 << k : 0;
    }
    return meets;
#endif
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
    if (m_triangles.size() >= (std::size_t{1} << 28))
    {
        // a leaf's first triangle has 28 bits in InnerNode::child
        throw MeshError("a mesh may have at most 268 435 455 triangles, this one has " +
                        std::to_string(m_triangles.size()));
    }
    std::vector<std::uint32_t> order(m_triangles.size());
    std::iota(order.begin(), order.end(), 0u);
    std::vector<Node> nodes;
    nodes.reserve(2 * m_triangles.size() / kLeafSize + 2);
    buildNode(0, static_cast<std::uint32_t>(order.size()), centroids, order, nodes);

    // The tree as it is searched: each inner node with its children's boxes paired, depth first;
    // the triangles with their corners in leaf order.
    std::vector<std::uint32_t> innerIndex(nodes.size());
    std::uint32_t innerCount = 0;
    for (std::size_t n = 0; n < nodes.size(); ++n)
    {
        innerIndex[n] = nodes[n].count > 0 ? 0 : innerCount++;
    }
    const auto reference = [&](std::uint32_t n)
    {
        const Node& node = nodes[n];
        return node.count > 0 ? kLeafBit | node.first << 3 | node.count : innerIndex[n];
    };
    m_inner.resize(innerCount);
    for (std::size_t n = 0; n < nodes.size(); ++n)
    {
        if (nodes[n].count > 0)
        {
            continue;
        }
        InnerNode& inner = m_inner[innerIndex[n]];
        const std::uint32_t children[2] = {nodes[n].left, nodes[n].right};
        for (int k = 0; k < 2; ++k)
        {
            const Node& child = nodes[children[k]];
            inner.lowerX[k] = child.lower.x();
            inner.lowerY[k] = child.lower.y();
            inner.lowerZ[k] = child.lower.z();
            inner.upperX[k] = child.upper.x();
            inner.upperY[k] = child.upper.y();
            inner.upperZ[k] = child.upper.z();
            inner.child[k] = reference(children[k]);
        }
    }
    m_rootLower = nodes[0].lower;
    m_rootUpper = nodes[0].upper;
    m_rootChild = reference(0);
    m_leafTriangles.reserve(order.size());
    for (const std::uint32_t t : order)
    {
        const auto& tri = m_triangles[t];
        const Vec3& a = m_vertices[tri[0]];
        const Vec3& b = m_vertices[tri[1]];
        const Vec3& c = m_vertices[tri[2]];
        m_leafTriangles.push_back({a, b, c, b - a, c - a, t});
    }
}

// Builds the subtree over order[begin, end) into `nodes` and returns its index: a leaf for a few
// triangles, else a split at the median centroid along the longest axis of the centroids' box.
std::uint32_t TriangleBvh::buildNode(std::uint32_t begin, std::uint32_t end, const std::vector<Vec3>& centroids,
                                     std::vector<std::uint32_t>& order, std::vector<Node>& nodes)
{
    Node node;
    node.lower = Vec3::Constant(std::numeric_limits<Real>::infinity());
    node.upper = -node.lower;
    Vec3 centreLower = node.lower;
    Vec3 centreUpper = node.upper;
    for (std::uint32_t i = begin; i < end; ++i)
    {
        for (const std::uint32_t v : m_triangles[order[i]])
        {
            node.lower = node.lower.cwiseMin(m_vertices[v]);
            node.upper = node.upper.cwiseMax(m_vertices[v]);
        }
        centreLower = centreLower.cwiseMin(centroids[order[i]]);
        centreUpper = centreUpper.cwiseMax(centroids[order[i]]);
    }
    const auto index = static_cast<std::uint32_t>(nodes.size());
    nodes.push_back(node);
    if (end - begin <= kLeafSize)
    {
        nodes[index].first = begin;
        nodes[index].count = end - begin;
        return index;
    }
    int axis = 0;
    (centreUpper - centreLower).maxCoeff(&axis);
    const std::uint32_t middle = begin + (end - begin) / 2;
    std::nth_element(order.begin() + begin, order.begin() + middle, order.begin() + end,
                     [&](std::uint32_t x, std::uint32_t y)
                     {
                         // ties broken by index, so the tree is the same whatever the library's sort
                         return centroids[x][axis] < centroids[y][axis] ||
                                (centroids[x][axis] == centroids[y][axis] && x < y);
                     });
    const std::uint32_t left = buildNode(begin, middle, centroids, order, nodes);
    const std::uint32_t right = buildNode(middle, end, centroids, order, nodes);
    nodes[index].left = left;
    nodes[index].right = right;
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
        std::uint32_t child;
        Real squared;
    };
    Entry stack[64];
    int top = 0;
    stack[top++] = {m_rootChild, squaredDistanceToBox(p, m_rootLower, m_rootUpper)};
#if defined(__SSE2__)
    const __m128d px = _mm_set1_pd(p.x());
    const __m128d py = _mm_set1_pd(p.y());
    const __m128d pz = _mm_set1_pd(p.z());
#endif
    while (top > 0)
    {
        const Entry entry = stack[--top];
        if (entry.squared >= bestSquared)
        {
            continue;
        }
        if (entry.child & kLeafBit)
        {
            const std::uint32_t first = (entry.child & ~kLeafBit) >> 3;
            const std::uint32_t count = entry.child & 7u;
            for (std::uint32_t i = first; i < first + count; ++i)
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
        const InnerNode& node = m_inner[entry.child];
        // both children's squared distances, each with the operations of squaredDistanceToBox; then
        // the farther child is pushed first so that the nearer is searched first (selects, not
        // branches: which is nearer is a coin toss to the branch predictor)
#if defined(__SSE2__)
        const __m128d toChild = pairSquaredDistance(node, px, py, pz);
        const __m128d swapped = _mm_shuffle_pd(toChild, toChild, 1);
        const __m128d leftNearer = _mm_cmple_sd(toChild, swapped); // lane 0: left <= right
        const __m128d mask = _mm_unpacklo_pd(leftNearer, leftNearer);
        // (farther, nearer): (right, left) when the left is nearer, else (left, right)
        const __m128d ordered = _mm_or_pd(_mm_and_pd(mask, swapped), _mm_andnot_pd(mask, toChild));
        const bool leftFirst = _mm_movemask_pd(leftNearer) & 1;
        stack[top].squared = _mm_cvtsd_f64(ordered);
        stack[top + 1].squared = _mm_cvtsd_f64(_mm_unpackhi_pd(ordered, ordered));
#else
        Real toChild[2];
        for (int k = 0; k < 2; ++k)
        {
            toChild[k] = squaredDistanceToBox(p, Vec3(node.lowerX[k], node.lowerY[k], node.lowerZ[k]),
                                              Vec3(node.upperX[k], node.upperY[k], node.upperZ[k]));
        }
        const bool leftFirst = toChild[0] <= toChild[1];
        stack[top].squared = leftFirst ? toChild[1] : toChild[0];
        stack[top + 1].squared = leftFirst ? toChild[0] : toChild[1];
#endif
        stack[top].child = leftFirst ? node.child[1] : node.child[0];
        stack[top + 1].child = leftFirst ? node.child[0] : node.child[1];
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
#if defined(__SSE2__)
    const __m128d px = _mm_set1_pd(p.x());
    const __m128d py = _mm_set1_pd(p.y());
    const __m128d pz = _mm_set1_pd(p.z());
    const __m128d squaredRadii = _mm_set1_pd(squaredRadius);
#endif
    forEachTriangleIn([&](const Vec3& lower, const Vec3& upper)
                      { return squaredDistanceToBox(p, lower, upper) < squaredRadius; },
                      [&](const InnerNode& node)
                      {
#if defined(__SSE2__)
                          return _mm_movemask_pd(_mm_cmplt_pd(pairSquaredDistance(node, px, py, pz), squaredRadii));
#else
                          return (squaredDistanceToBox(p, node.lower(0), node.upper(0)) < squaredRadius ? 1 : 0) |
                                 (squaredDistanceToBox(p, node.lower(1), node.upper(1)) < squaredRadius ? 2 : 0);
#endif
                      },
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
                      [&](const InnerNode& node) { return pairMeetsSegment(node, a, direction); },
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
