// SPDX-License-Identifier: MIT
// The narrow phase's queries of a prepared mesh: its hierarchy and grid, its feature edges and its
// vertex clusters, built once by MeshGeometry::build.
#include "geometry/mesh_queries.hpp"

#include "geometry/box_queries.hpp"
#include "geometry/signed_distance_grid.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <numbers>
#include <numeric>

namespace impulse
{
namespace
{

// Within this many grid cells of the surface, normals average the nearest faces (distanceFrom).
constexpr Real kSurfaceBand = 0.1;

} // namespace

MeshQueries::MeshQueries(const MeshGeometry& geometry, const TriangleMesh& body, int resolution) : m_geometry(geometry)
{
    // each edge is met twice, once per direction: keep the ascending one, with both faces' normals
    std::map<std::array<std::uint32_t, 2>, std::array<Vec3, 2>> faceNormals;
    for (const auto& tri : body.triangles)
    {
        const Vec3 normal = (body.vertices[tri[1]] - body.vertices[tri[0]])
                                .cross(body.vertices[tri[2]] - body.vertices[tri[0]])
                                .normalized();
        for (int k = 0; k < 3; ++k)
        {
            const std::uint32_t from = tri[k];
            const std::uint32_t to = tri[(k + 1) % 3];
            faceNormals[{std::min(from, to), std::max(from, to)}][from < to ? 0 : 1] = normal;
        }
    }
    const Real featureCosine = std::cos(kFeatureAngleDegrees * std::numbers::pi / 180.0);
    for (const auto& [edge, normals] : faceNormals)
    {
        m_edges.push_back(edge);
        if (normals[0].dot(normals[1]) < featureCosine)
        {
            m_featureEdges.push_back(edge);
            m_longestFeatureEdge =
                std::max(m_longestFeatureEdge, (body.vertices[edge[0]] - body.vertices[edge[1]]).norm());
        }
    }
    m_bvh = std::make_unique<TriangleBvh>(body);
    m_grid = std::make_unique<SignedDistanceGrid>(*m_bvh, geometry.lower(), geometry.upper(), resolution);
    m_vertexClusterMembers.resize(body.vertices.size());
    std::iota(m_vertexClusterMembers.begin(), m_vertexClusterMembers.end(), 0u);
    buildClusters(body.vertices, 0, static_cast<std::uint32_t>(body.vertices.size()));
}

MeshQueries::~MeshQueries() = default;

void MeshQueries::buildClusters(const std::vector<Vec3>& vertices, std::uint32_t first, std::uint32_t count)
{
    const auto begin = m_vertexClusterMembers.begin() + first;
    const auto end = begin + count;
    Vec3 lower = vertices[*begin];
    Vec3 upper = lower;
    for (auto v = begin; v != end; ++v)
    {
        lower = lower.cwiseMin(vertices[*v]);
        upper = upper.cwiseMax(vertices[*v]);
    }
    if (count <= kClusterSize)
    {
        VertexCluster cluster;
        cluster.centre = 0.5 * (lower + upper);
        for (auto v = begin; v != end; ++v)
        {
            cluster.radius = std::max(cluster.radius, (vertices[*v] - cluster.centre).norm());
        }
        cluster.first = first;
        cluster.count = count;
        m_vertexClusters.push_back(cluster);
        return;
    }
    int axis = 0;
    (upper - lower).maxCoeff(&axis);
    const std::uint32_t half = count / 2;
    std::nth_element(begin, begin + half, end,
                     [&](std::uint32_t x, std::uint32_t y) {
                         return vertices[x][axis] < vertices[y][axis] ||
                                (vertices[x][axis] == vertices[y][axis] && x < y);
                     });
    buildClusters(vertices, first, half);
    buildClusters(vertices, first + half, count - half);
}

MeshDistance MeshQueries::gridDistance(const Vec3& pointBody) const
{
    return m_grid->sample(pointBody);
}

Real MeshQueries::coarseLowerBound(const Vec3& pointBody) const
{
    return lowerBoundFromGrid(pointBody, m_grid->samplePhi(pointBody));
}

Real MeshQueries::lowerBoundFromGrid(const Vec3& pointBody, Real gridPhi) const
{
    // outside the grid its extension is an upper bound of phi; the distance to the box is a lower one
    return m_grid->contains(pointBody) ? gridPhi - gridError()
                                       : std::sqrt(squaredDistanceToBox(pointBody, lower(), upper()));
}

MeshDistance MeshQueries::exactDistance(const Vec3& pointBody, MeshQueryScratch& scratch) const
{
    return distanceFrom(pointBody, m_bvh->closestPoint(pointBody, std::numeric_limits<Real>::infinity()), scratch);
}

MeshDistance MeshQueries::distanceFrom(const Vec3& pointBody, const SurfacePoint& closest,
                                       MeshQueryScratch& scratch) const
{
    MeshDistance result;
    result.phi = TriangleBvh::signedDistance(pointBody, closest);
    result.exact = true;
    if (closest.distance > kSurfaceBand * m_grid->cellSize())
    {
        // the gradient of the exact distance points from the closest point
        result.gradient = (pointBody - closest.point) / result.phi;
        return result;
    }
    // Near the surface that direction turns with round-off wherever faces meet: a point a
    // nanometre inside a ridge is nearest one face or the other, and two tessellated tori resting
    // ridge on ridge would push each other sideways by a facet's tilt. There the normal is the mean
    // of the distinct normals of every face as near as the nearest (to a thousandth of a cell):
    // one face's normal on a face, the ridge's bisector on a ridge.
    std::vector<std::uint32_t>& near = scratch.near;
    m_bvh->trianglesNear(pointBody, closest.distance + 1e-3 * m_grid->cellSize(), near);
    std::vector<Vec3>& normals = scratch.normals;
    normals.clear();
    for (const std::uint32_t t : near)
    {
        const Vec3& normal = m_bvh->faceNormal(t);
        if (std::none_of(normals.begin(), normals.end(), [&](const Vec3& n) { return n.isApprox(normal, 1e-9); }))
        {
            normals.push_back(normal);
        }
    }
    Vec3 sum = Vec3::Zero();
    for (const Vec3& n : normals)
    {
        sum += n;
    }
    const Real length = sum.norm();
    result.gradient = length > 1e-6 * static_cast<Real>(normals.size()) ? Vec3(sum / length)
                                                                        : Vec3(closest.pseudonormal.normalized());
    return result;
}

MeshDistance MeshQueries::distance(const Vec3& pointBody, Real threshold, MeshQueryScratch& scratch) const
{
    // the grid's gradient only where its value is the answer
    const SignedDistanceGrid::Stencil coarse = m_grid->stencil(pointBody);
    const Real cell = m_grid->cellSize();
    if (lowerBoundFromGrid(pointBody, coarse.phi) >= threshold || coarse.phi < -3.0 * cell)
    {
        return SignedDistanceGrid::withGradient(coarse); // certainly not touching, or deep inside where
                                                         // the grid's normal serves
    }
    const SurfacePoint closest = m_bvh->closestPoint(pointBody, searchRadius(coarse.phi));
    return closest.found ? distanceFrom(pointBody, closest, scratch) : SignedDistanceGrid::withGradient(coarse);
}

Real MeshQueries::searchRadius(Real gridPhi) const
{
    // the grid is within gridError() of the truth: a search this wide finds the closest triangle
    return std::abs(gridPhi) + gridError() + m_grid->cellSize();
}

Real MeshQueries::gridError() const
{
    // Within the exact band phi is 1-Lipschitz and exact at the corners of a cell, so the
    // interpolant is off by at most the weighted distance to the corners: sqrt(3)/2 of a cell at
    // the centre, less elsewhere. Beyond the band every corner is over two cells from the surface.
    return m_grid->cellSize();
}

void MeshQueries::segmentCrossings(const Vec3& a, const Vec3& b, std::vector<Real>& enterLeave,
                                   MeshQueryScratch& scratch) const
{
    std::vector<SegmentCrossing>& crossings = scratch.crossings;
    m_bvh->segmentCrossings(a, b, crossings);
    enterLeave.clear();
    // a first crossing that leaves: a is inside, and its passage starts at 0
    bool inside = !crossings.empty() && !crossings.front().entering;
    if (inside)
    {
        enterLeave.push_back(0.0);
    }
    for (const SegmentCrossing& crossing : crossings)
    {
        // a segment through a shared edge or corner meets several triangles at one t: only the
        // first entering and the first leaving crossing count
        if (!inside && crossing.entering)
        {
            enterLeave.push_back(crossing.t);
            inside = true;
        }
        else if (inside && !crossing.entering)
        {
            enterLeave.push_back(crossing.t);
            inside = false;
        }
    }
    if (inside)
    {
        enterLeave.push_back(1.0); // the segment ends inside: its last passage ends at 1
    }
}

Real MeshQueries::cellSize() const
{
    return m_grid->cellSize();
}

std::array<int, 3> MeshQueries::gridSamples() const
{
    return m_grid->samples();
}

} // namespace impulse
