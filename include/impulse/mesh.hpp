// SPDX-License-Identifier: MIT
// Nonconvex bodies: a closed triangle mesh with its signed distance grid (GBF03 sec. 3).
//
// A mesh is prepared once and shared by every body that uses it. Preparing it validates the
// triangles, integrates the solid's mass properties, moves the vertices into the body frame (centre
// of mass at the origin, axes on the principal axes), builds a bounding-volume hierarchy over the
// triangles and samples the signed distance on a uniform grid.
#pragma once

#include <impulse/math.hpp>

#include <array>
#include <cstdint>
#include <limits>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

namespace impulse
{

/// Triangles over indexed vertices, counter-clockwise seen from outside.
struct TriangleMesh
{
    std::vector<Vec3> vertices;
    std::vector<std::array<std::uint32_t, 3>> triangles;
};

/// A mesh that cannot be a solid: not closed, inconsistently oriented, degenerate or duplicate
/// faces, non-finite coordinates, inside out. The message says what and where (face, edge, vertex).
class MeshError : public std::invalid_argument
{
  public:
    using std::invalid_argument::invalid_argument;
};

/// How to sample the signed distance grid.
struct MeshOptions
{
    /// Grid cells along the longest side of the mesh's bounding box; 0 chooses from the mesh
    /// (see docs/architecture.md, "Nonconvex bodies").
    int resolution = 0;
};

/// phi at a point and its unit gradient (the outward normal of the nearest surface), body frame.
struct MeshDistance
{
    Real phi = 0.0;
    Vec3 gradient = Vec3::UnitZ();
    bool exact = false; ///< phi is the distance to the triangles, not interpolated from the grid
};

class TriangleBvh;
class SignedDistanceGrid;
struct SurfacePoint;

/// An immutable, validated solid mesh in its body frame. Build with MeshGeometry::build.
class MeshGeometry
{
  public:
    /// Validates `mesh` (throws MeshError) and prepares it. Vertices with exactly equal
    /// coordinates are merged first, so meshes stored as separate triangles (STL) are accepted.
    static std::shared_ptr<const MeshGeometry> build(const TriangleMesh& mesh, const MeshOptions& options = {});

    ~MeshGeometry();
    MeshGeometry(const MeshGeometry&) = delete;
    MeshGeometry& operator=(const MeshGeometry&) = delete;

    /// Vertices in the body frame: centre of mass at the origin, principal axes.
    const std::vector<Vec3>& vertices() const { return m_vertices; }
    const std::vector<std::array<std::uint32_t, 3>>& triangles() const { return m_triangles; }
    /// Every edge once, as (lower index, higher index).
    const std::vector<std::array<std::uint32_t, 2>>& edges() const { return m_edges; }
    /// The edges where the surface bends by more than kFeatureAngle: a box's edges, not the
    /// diagonals of its faces nor the seams of a finely tessellated curved surface.
    const std::vector<std::array<std::uint32_t, 2>>& featureEdges() const { return m_featureEdges; }
    static constexpr Real kFeatureAngleDegrees = 40.0;

    /// Where the body frame sits in the mesh's own (file) coordinates: a vertex v of the file is
    /// at frameInMesh.toLocal(v) in the body frame.
    const Pose& frameInMesh() const { return m_frameInMesh; }

    Real volume() const { return m_volume; }
    /// Principal moments of inertia per unit mass, body frame.
    const Vec3& unitInertia() const { return m_unitInertia; }
    /// Largest distance of a vertex from the centre of mass.
    Real boundingRadius() const { return m_boundingRadius; }
    /// Bounding box of the vertices, body frame.
    const Vec3& lower() const { return m_lower; }
    const Vec3& upper() const { return m_upper; }

    /// Signed distance from the grid: trilinear interpolation and its gradient inside the grid;
    /// outside, the distance to the grid box added to the value at the nearest grid point.
    MeshDistance gridDistance(const Vec3& pointBody) const;
    /// A lower bound of the exact phi from the grid alone (no tree search): the grid's value less
    /// its error within the grid; outside it, where the grid's extension may exceed phi, the
    /// distance to the mesh's bounding box.
    Real coarseLowerBound(const Vec3& pointBody) const;
    /// Exact signed distance to the triangles: closest point from the hierarchy, sign from the
    /// angle-weighted pseudonormal of the nearest feature. Costs a tree search.
    MeshDistance exactDistance(const Vec3& pointBody) const;
    /// Signed distance for contact: exact where phi may be below `threshold` (within the grid's
    /// error of it) and near the surface, the grid elsewhere.
    MeshDistance distance(const Vec3& pointBody, Real threshold = std::numeric_limits<Real>::infinity()) const;
    /// Length of the longest feature edge.
    Real longestFeatureEdge() const { return m_longestFeatureEdge; }

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
    /// (enter0, leave0, enter1, leave1, ...). Both ends should lie outside.
    void segmentCrossings(const Vec3& a, const Vec3& b, std::vector<Real>& enterLeave) const;

    /// Grid spacing and number of samples per axis.
    Real cellSize() const;
    std::array<int, 3> gridSamples() const;

    const TriangleBvh& bvh() const { return *m_bvh; }

  private:
    MeshGeometry();
    MeshDistance distanceFrom(const Vec3& pointBody, const SurfacePoint& closest) const;
    /// coarseLowerBound(pointBody) where gridPhi is the grid's value there, already at hand.
    Real lowerBoundFromGrid(const Vec3& pointBody, Real gridPhi) const;
    /// How far the closest triangle can be from a point whose grid value is gridPhi.
    Real searchRadius(Real gridPhi) const;
    /// Splits m_vertexClusterMembers[first, first + count) at the median along its longest axis
    /// until clusters are small enough.
    void buildClusters(std::uint32_t first, std::uint32_t count);

    std::vector<Vec3> m_vertices;
    std::vector<std::array<std::uint32_t, 3>> m_triangles;
    std::vector<std::array<std::uint32_t, 2>> m_edges;
    std::vector<std::array<std::uint32_t, 2>> m_featureEdges;
    std::vector<VertexCluster> m_vertexClusters;
    std::vector<std::uint32_t> m_vertexClusterMembers;
    Pose m_frameInMesh;
    Real m_volume = 0.0;
    Vec3 m_unitInertia = Vec3::Zero();
    Real m_boundingRadius = 0.0;
    Real m_longestFeatureEdge = 0.0;
    Vec3 m_lower = Vec3::Zero();
    Vec3 m_upper = Vec3::Zero();
    std::unique_ptr<TriangleBvh> m_bvh;
    std::unique_ptr<SignedDistanceGrid> m_grid;
};

/// Mass properties of a closed, outward-oriented triangle mesh, by exact polyhedral integration.
struct PolyhedronMass
{
    Real volume = 0.0;
    Vec3 centroid = Vec3::Zero();
    /// Inertia tensor per unit mass about the centroid, in the mesh's axes.
    Mat3 unitInertia = Mat3::Zero();
};
PolyhedronMass polyhedronMass(const TriangleMesh& mesh);

} // namespace impulse
