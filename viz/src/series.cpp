// SPDX-License-Identifier: MIT
#include <impulse/viz/series.hpp>

namespace impulse::viz
{

Series computeSeries(const io::Trajectory& trajectory, const SceneView& view)
{
    const Vec3 up = upDirection(view.gravity);
    const std::size_t n = trajectory.sampleCount();
    Series series;
    series.height.assign(trajectory.bodyCount, std::vector<Real>(n));
    series.speed.assign(trajectory.bodyCount, std::vector<Real>(n));
    series.energy.assign(n, 0.0);
    series.energyLabel = view.hasMassProperties ? "total energy (J)" : "energy per unit mass, v^2/2 - g.x (J/kg)";
    for (std::size_t i = 0; i < n; ++i)
    {
        for (std::size_t k = 0; k < trajectory.bodyCount; ++k)
        {
            const io::BodySample& s = trajectory.at(i, k);
            series.height[k][i] = up.dot(s.position);
            series.speed[k][i] = s.linearVelocity.norm();
            const Real potentialPerMass = -view.gravity.dot(s.position);
            if (view.hasMassProperties)
            {
                const Mat3 rotation = s.orientation.toRotationMatrix();
                const Vec3 omegaBody = rotation.transpose() * s.angularVelocity;
                const Real rotational = 0.5 * omegaBody.dot(view.inertias[k].cwiseProduct(omegaBody));
                series.energy[i] +=
                    view.masses[k] * (0.5 * s.linearVelocity.squaredNorm() + potentialPerMass) + rotational;
            }
            else
            {
                series.energy[i] += 0.5 * s.linearVelocity.squaredNorm() + potentialPerMass;
            }
        }
    }
    return series;
}

} // namespace impulse::viz
