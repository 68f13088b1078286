// SPDX-License-Identifier: MIT
#pragma once

#include <impulse/math.hpp>
#include <impulse/mesh.hpp>

#include <memory>
#include <variant>

namespace impulse
{

/// Solid sphere centred on the body origin.
struct Sphere
{
    Real radius = 0.5;
};

/// Solid box centred on the body origin, edges along the body axes.
struct Box
{
    Vec3 halfExtents = Vec3::Constant(0.5);
};

/// Half-space {p : normal . p <= offset} in the body frame; only static bodies may carry one.
struct Plane
{
    Vec3 normal = Vec3::UnitZ(); ///< unit, pointing out of the solid
    Real offset = 0.0;
};

/// Solid capsule: the points within `radius` of the segment from -halfLength to +halfLength along
/// the body z axis (a cylinder of length 2 halfLength capped by two hemispheres), as MuJoCo's capsule.
struct Capsule
{
    Real radius = 0.5;
    Real halfLength = 0.5; ///< half the length of the cylindrical part, > 0
};

/// A closed triangle mesh with its signed distance grid, shared by every body that uses it. The
/// body frame is the mesh's own: centre of mass at the origin, principal axes.
struct Mesh
{
    std::shared_ptr<const MeshGeometry> geometry;
};

/// The geometry of a body. Body frame: origin at the centre of mass, axes on the principal axes.
using Shape = std::variant<Sphere, Box, Plane, Capsule, Mesh>;

/// Radius of a sphere about the body origin that contains the shape (infinite for a plane).
Real boundingRadius(const Shape& shape);

/// Half the shape's thinnest extent: a sphere's or capsule's radius, a box's least half extent, half
/// the least side of a mesh's box in its body frame (infinite for a plane). The length the step's
/// tolerances and a step's motion are weighed against (docs/warnings.md).
Real thinnestHalfExtent(const Shape& shape);

/// Volume of the shape (infinite for a plane).
Real volume(const Shape& shape);

/// Principal moments of inertia of the solid shape with unit mass, body frame.
Vec3 unitInertia(const Shape& shape);

} // namespace impulse
