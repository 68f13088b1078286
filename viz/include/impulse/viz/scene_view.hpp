// SPDX-License-Identifier: MIT
#pragma once

#include <impulse/io/scene.hpp>
#include <impulse/io/trajectory_reader.hpp>
#include <impulse/math.hpp>
#include <impulse/shape.hpp>
#include <impulse/viz/tessellate.hpp>

#include <string>
#include <vector>

namespace impulse::viz
{

/// A body that never moves, drawn where the scene puts it.
struct StaticBody
{
    Shape shape;
    Pose pose;
};

/// What the plots and pictures need to know about a scene beyond the trajectory: gravity, the mass
/// properties and shapes of the dynamic bodies, and the static bodies. Without a scene file the
/// dynamic bodies are drawn as marker spheres and energies are per unit mass.
struct SceneView
{
    Vec3 gravity = Vec3(0.0, 0.0, -9.81); ///< the scene format's default
    bool hasMassProperties = false;
    std::vector<Shape> dynamicShapes; ///< trajectory body k has dynamicShapes[k]
    std::vector<std::string> names;   ///< per dynamic body: the scene's name, or "body k"
    std::vector<Real> masses;         ///< kg, when hasMassProperties
    std::vector<Vec3> inertias;       ///< principal, body frame, when hasMassProperties
    /// Per dynamic body: where its shape sits in the body frame, minus the centre of mass in the
    /// shape's frame (the trajectory places the centre of mass); empty: every shape centred.
    std::vector<Vec3> shapeOffsets;
    std::vector<StaticBody> staticBodies;

    /// Trajectory body k's triangles in its body frame, its shape moved off its centre of mass.
    TriangleMesh dynamicTriangles(std::size_t k) const;
    /// Trajectory body k's bounding radius about its centre of mass.
    Real dynamicRadius(std::size_t k) const;

    /// Everything from a loaded scene, in its current (initial) state.
    static SceneView fromScene(const io::Scene& scene);
    /// Marker spheres sized to the trajectory, default gravity, no static bodies.
    static SceneView markersFor(const io::Trajectory& trajectory);
};

/// The unit vector opposite to gravity; +z when there is no gravity.
Vec3 upDirection(const Vec3& gravity);

/// Axis-aligned bounds of every body's centre over the whole trajectory, grown by each body's
/// bounding radius, and of the static bodies other than planes.
struct Bounds
{
    Vec3 min = Vec3::Constant(0.0);
    Vec3 max = Vec3::Constant(0.0);
    Vec3 centre() const { return 0.5 * (min + max); }
    Real radius() const { return 0.5 * (max - min).norm(); }
};
Bounds contentBounds(const io::Trajectory& trajectory, const SceneView& view);
/// The same for the dynamic bodies alone (contentBounds when there are none): what a picture frames.
Bounds dynamicBounds(const io::Trajectory& trajectory, const SceneView& view);

/// Checks that the scene and the trajectory describe the same dynamic bodies; throws
/// io::TrajectoryError naming both files otherwise.
void checkMatches(const SceneView& view, const io::Trajectory& trajectory, const std::string& sceneName,
                  const std::string& trajectoryName);

} // namespace impulse::viz
