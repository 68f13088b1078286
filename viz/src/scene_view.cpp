// SPDX-License-Identifier: MIT
#include <impulse/viz/scene_view.hpp>

#include <algorithm>
#include <cmath>
#include <variant>

namespace impulse::viz
{

SceneView SceneView::fromScene(const io::Scene& scene)
{
    SceneView view;
    view.gravity = scene.world.gravity();
    view.hasMassProperties = true;
    for (std::uint32_t index = 0; index < scene.world.bodyCount(); ++index)
    {
        const BodyId id{index};
        if (scene.world.isDynamic(id))
        {
            continue;
        }
        const BodyState s = scene.world.state(id);
        view.staticBodies.push_back({scene.world.shape(id), Pose::from(s.position, s.orientation)});
    }
    for (const BodyId id : scene.dynamicBodies)
    {
        view.dynamicShapes.push_back(scene.world.shape(id));
        const std::string& name = scene.bodyNames[id.index];
        view.names.push_back(name.empty() ? "body " + std::to_string(view.names.size()) : name);
        view.masses.push_back(scene.world.mass(id));
        view.inertias.push_back(scene.world.principalInertia(id));
        view.shapeOffsets.push_back(-scene.world.centerOfMass(id));
    }
    return view;
}

TriangleMesh SceneView::dynamicTriangles(std::size_t k) const
{
    TriangleMesh mesh = bodyTriangles(dynamicShapes.at(k), bodyColour(k));
    if (k < shapeOffsets.size())
    {
        for (Vec3& p : mesh.positions)
        {
            p += shapeOffsets[k];
        }
    }
    return mesh;
}

Real SceneView::dynamicRadius(std::size_t k) const
{
    const Real offset = k < shapeOffsets.size() ? shapeOffsets[k].norm() : 0.0;
    return boundingRadius(dynamicShapes.at(k)) + offset;
}

SceneView SceneView::markersFor(const io::Trajectory& trajectory)
{
    SceneView view;
    // markers a fiftieth of the extent of the motion, so that they neither vanish nor fill the view
    Vec3 low = Vec3::Constant(INFINITY);
    Vec3 high = Vec3::Constant(-INFINITY);
    for (const io::BodySample& s : trajectory.samples)
    {
        low = low.cwiseMin(s.position);
        high = high.cwiseMax(s.position);
    }
    const Real extent = (high - low).norm();
    const Real radius = extent > 0.0 ? 0.02 * extent : 0.1;
    view.dynamicShapes.assign(trajectory.bodyCount, Sphere{radius});
    for (std::size_t k = 0; k < trajectory.bodyCount; ++k)
    {
        view.names.push_back("body " + std::to_string(k));
    }
    return view;
}

Vec3 upDirection(const Vec3& gravity)
{
    const Real g = gravity.norm();
    return g > 0.0 ? Vec3(-gravity / g) : Vec3(Vec3::UnitZ());
}

// The box every dynamic body's bounding sphere stays in over the trajectory (empty: inverted).
Bounds sweptBounds(const io::Trajectory& trajectory, const SceneView& view)
{
    Vec3 low = Vec3::Constant(INFINITY);
    Vec3 high = Vec3::Constant(-INFINITY);
    for (std::size_t i = 0; i < trajectory.sampleCount(); ++i)
    {
        for (std::size_t k = 0; k < trajectory.bodyCount; ++k)
        {
            const Real r = view.dynamicRadius(k);
            low = low.cwiseMin(trajectory.at(i, k).position - Vec3::Constant(r));
            high = high.cwiseMax(trajectory.at(i, k).position + Vec3::Constant(r));
        }
    }
    return {low, high};
}

Bounds contentBounds(const io::Trajectory& trajectory, const SceneView& view)
{
    auto [low, high] = sweptBounds(trajectory, view);
    for (const StaticBody& body : view.staticBodies)
    {
        const Real r = boundingRadius(body.shape);
        if (std::isfinite(r))
        {
            low = low.cwiseMin(body.pose.position - Vec3::Constant(r));
            high = high.cwiseMax(body.pose.position + Vec3::Constant(r));
        }
    }
    if (!low.allFinite() || !high.allFinite())
    {
        return {Vec3::Constant(-1.0), Vec3::Constant(1.0)};
    }
    return {low, high};
}

Bounds dynamicBounds(const io::Trajectory& trajectory, const SceneView& view)
{
    if (trajectory.bodyCount == 0 || trajectory.sampleCount() == 0)
    {
        return contentBounds(trajectory, view);
    }
    return sweptBounds(trajectory, view);
}

void checkMatches(const SceneView& view, const io::Trajectory& trajectory, const std::string& sceneName,
                  const std::string& trajectoryName)
{
    if (view.dynamicShapes.size() != trajectory.bodyCount)
    {
        throw io::TrajectoryError(trajectoryName + ": " + std::to_string(trajectory.bodyCount) +
                                  " bodies per sample, but the scene " + sceneName + " has " +
                                  std::to_string(view.dynamicShapes.size()) + " dynamic bodies");
    }
}

} // namespace impulse::viz
