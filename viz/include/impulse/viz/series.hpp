// SPDX-License-Identifier: MIT
#pragma once

#include <impulse/io/trajectory_reader.hpp>
#include <impulse/viz/scene_view.hpp>

#include <string>
#include <vector>

namespace impulse::viz
{

/// The time series the plots show, one value per trajectory sample.
struct Series
{
    std::vector<std::vector<Real>> height; ///< per body: centre along -gravity (z without gravity), m
    std::vector<std::vector<Real>> speed;  ///< per body: |v| of the centre, m/s
    std::vector<Real> energy;              ///< total over the bodies
    std::string energyLabel;               ///< axis label saying what `energy` is and its unit
};

/// Height, speed and energy of every body. With mass properties the energy is the total kinetic
/// (translational and rotational) plus gravitational potential energy in J; without, it is the sum
/// over bodies of v^2/2 - g.x in J/kg, as if each body were a point of unit mass.
Series computeSeries(const io::Trajectory& trajectory, const SceneView& view);

} // namespace impulse::viz
