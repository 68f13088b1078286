// SPDX-License-Identifier: MIT
// The narrow phase's view of a prepared mesh (GBF03 sec. 3): its bounding-volume hierarchy and
// signed distance grid, the queries built on them, its sharp edges and its vertex clusters.
// MeshGeometry (include/impulse/mesh.hpp) holds one and shows users only what they read.
#pragma once

#include "geometry/triangle_bvh.hpp"

#include <impulse/mesh.hpp>

#include <array>
#include <cstdint>
#include <memory>
#include <vector>

namespace impulse
{

class SignedDistanceGrid;

/// Buffers the mesh queries reuse from call to call. The caller owns them; a thread needs its own.
struct MeshQueryScratch
{
    std::vector<std::uint32_t> near;        ///< triangles near a point (the normal near the surface)
    std::vector<Vec3> normals;              ///< their distinct face normals
    std::vector<SegmentCrossing> crossings; ///< a segment's crossings of the surface
};

class MeshQueries
{
  public:
    /// The queries of a prepared mesh.
    static const MeshQueries& of(const MeshGeometry& mesh) { return *mesh.m_queries; }

    /// Prepares the queries of `geometry`, whose bounding box is set and whose vertices and
    /// triangles are `body` (body frame), with `resolution` grid cells along the longest side.
    MeshQueries(const MeshGeometry& geometry, const TriangleMesh& body, int resolution);
    ~MeshQueries();
    MeshQueries(const MeshQueries&) = delete;
    MeshQueries& operator=(const MeshQueries&) = delete;

    const std::vector<Vec3>& vertices() const { return m_geometry.vertices(); }
    Real boundingRadius() const { return m_geometry.boundingRadius(); }
    const Vec3& lower() const { return m_geometry.lower(); }
    const Vec3& upper() const { return m_geometry.upper(); }

    /// Every edge once, as (lower index, higher index).
    const std::vector<std::array<std::uint32_t, 2>>& edges() const { return m_edges; }
    /// The edges where the surface bends by more than kFeatureAngle: a box's edges, not the
    /// diagonals of its faces nor the seams of a finely tessellated curved surface.
    const std::vector<std::array<std::uint32_t, 2>>& featureEdges() const { return m_featureEdges; }
    static constexpr Real kFeatureAngleDegrees = 40.0;
    /// Length of the longest feature edge.
    Real longestFeatureEdge() const { return m_longestFeatureEdge; }

    /// Signed distance from the grid: trilinear interpolation and its gradient inside the grid;
    /// outside, the distance to the grid box added to the value at the nearest grid point.
    MeshDistance gridDistance(const Vec3& pointBody) const;
    /// A lower bound of the exact phi from the grid alone (no tree search): the grid's value less
    /// its error within the grid; outside it, where the grid's extension may exceed phi, the
    /// distance to the mesh's bounding box.
    Real coarseLowerBound(const Vec3& pointBody) const;
    /// Exact signed distance to the triangles: closest point from the hierarchy, sign from the
    /// angle-weighted pseudonormal of the nearest feature. Costs a tree search.
    MeshDistance exactDistance(const Vec3& pointBody, MeshQueryScratch& scratch) const;
    /// Signed distance for contact: exact where phi may be below `threshold` (within the grid's
    /// error of it) and near the surface, the grid elsewhere.
    MeshDistance distance(const Vec3& pointBody, Real threshold, MeshQueryScratch& scratch) const;

    /// A few vertices near one another, within `radius` of `centre` (body frame): a query can pass
    /// over a cluster far from what it tests without looking at its vertices.
    struct VertexCluster
    {
        Vec3 centre = Vec3::Zero();
        Real radius = 0.0;
        std::uint32_t first = 0; ///< into vertexClusterMembers()
        std::uint32_t count = 0;
    };
    /// Clusters of at most kClusterSize vertices covering every vertex once.
    const std::vector<VertexCluster>& vertexClusters() const { return m_vertexClusters; }
    /// Vertex indices, each cluster's contiguous.
    const std::vector<std::uint32_t>& vertexClusterMembers() const { return m_vertexClusterMembers; }
    static constexpr std::uint32_t kClusterSize = 8;
    /// How far a grid value may lie above the exact distance (trilinear error of a 1-Lipschitz field).
    Real gridError() const;

    /// Parameters along the segment a->b (0..1) where it enters and leaves the solid, pairwise:
    /// (enter0, leave0, enter1, leave1, ...). An end inside (told by the first crossing leaving, or
    /// the last entering) makes its passage start at exactly 0 or end at exactly 1.
    void segmentCrossings(const Vec3& a, const Vec3& b, std::vector<Real>& enterLeave, MeshQueryScratch& scratch) const;

    /// Grid spacing and number of samples per axis.
    Real cellSize() const;
    std::array<int, 3> gridSamples() const;

    const TriangleBvh& bvh() const { return *m_bvh; }

  private:
    MeshDistance distanceFrom(const Vec3& pointBody, const SurfacePoint& closest, MeshQueryScratch& scratch) const;
    /// coarseLowerBound(pointBody) where gridPhi is the grid's value there, already at hand.
    Real lowerBoundFromGrid(const Vec3& pointBody, Real gridPhi) const;
    /// How far the closest triangle can be from a point whose grid value is gridPhi.
    Real searchRadius(Real gridPhi) const;
    /// Splits m_vertexClusterMembers[first, first + count) at the median along its longest axis
    /// until clusters are small enough.
    void buildClusters(const std::vector<Vec3>& vertices, std::uint32_t first, std::uint32_t count);

    const MeshGeometry& m_geometry;
    std::vector<std::array<std::uint32_t, 2>> m_edges;
    std::vector<std::array<std::uint32_t, 2>> m_featureEdges;
    std::vector<VertexCluster> m_vertexClusters;
    std::vector<std::uint32_t> m_vertexClusterMembers;
    Real m_longestFeatureEdge = 0.0;
    std::unique_ptr<TriangleBvh> m_bvh;
    std::unique_ptr<SignedDistanceGrid> m_grid;
};

} // namespace impulse
