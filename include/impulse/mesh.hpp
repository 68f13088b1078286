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
#include <cstddef>
#include <cstdint>
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
    /// Most samples the grid may have (the box grown by 3 cells on each side, so resolution + 7
    /// along the longest side). Building takes about 32 bytes a sample (a cube at resolution 256:
    /// 0.6 GB and 10 s), so a resolution too fine for the mesh's shape is refused with MeshError
    /// instead of taking gigabytes. 256^3 samples admit a cube at resolution 249 and a rod sixteen
    /// times longer than wide at 1024.
    std::size_t maxGridSamples = std::size_t{1} << 24;
};

/// phi at a point and its unit gradient (the outward normal of the nearest surface), body frame.
struct MeshDistance
{
    Real phi = 0.0;
    Vec3 gradient = Vec3::UnitZ();
    bool exact = false; ///< phi is the distance to the triangles, not interpolated from the grid
};

class MeshQueries;

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

    /// Exact signed distance from a point (body frame) to the surface, negative inside, with the
    /// outward normal of the nearest surface as its gradient. Costs a search of the triangles.
    MeshDistance signedDistance(const Vec3& pointBody) const;

  private:
    friend class MeshQueries; // the narrow phase's view of the prepared mesh (src/geometry/mesh_queries.hpp)
    MeshGeometry();

    std::vector<Vec3> m_vertices;
    std::vector<std::array<std::uint32_t, 3>> m_triangles;
    Pose m_frameInMesh;
    Real m_volume = 0.0;
    Vec3 m_unitInertia = Vec3::Zero();
    Real m_boundingRadius = 0.0;
    Vec3 m_lower = Vec3::Zero();
    Vec3 m_upper = Vec3::Zero();
    /// What the narrow phase queries: hierarchy, signed distance grid, feature edges, vertex clusters.
    std::unique_ptr<const MeshQueries> m_queries;
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
