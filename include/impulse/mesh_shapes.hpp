// SPDX-License-Identifier: MIT
// Closed triangle meshes of simple solids, for tests, benchmarks and drawing analytic shapes.
#pragma once

#include <impulse/mesh.hpp>

namespace impulse
{

/// Sphere of the given radius about the origin: `rings` latitude bands (>= 2) of `segments`
/// (>= 3) quads each, triangles at the poles.
TriangleMesh sphereMesh(Real radius, int rings, int segments);

/// Box of the given half extents about the origin, each face split into n x n squares.
TriangleMesh boxMesh(const Vec3& halfExtents, int subdivisions = 1);

/// Torus about the z axis: centre-line radius `major`, tube radius `minor`, with `majorSegments`
/// around the axis and `minorSegments` around the tube.
TriangleMesh torusMesh(Real major, Real minor, int majorSegments, int minorSegments);

/// Solid cylinder about the z axis from z = bottom to z = top, with `segments` around it.
TriangleMesh cylinderMesh(Real radius, Real bottom, Real top, int segments);

} // namespace impulse
