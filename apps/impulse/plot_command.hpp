// SPDX-License-Identifier: MIT
#pragma once

#include <string>

namespace impulse::app
{

/// What `impulse plot` was asked to do.
struct PlotOptions
{
    std::string trajectoryPath;
    std::string scenePath;         ///< empty: no scene (energy per unit mass)
    std::string outPath;           ///< empty: the trajectory's name with .png
    std::string size = "1200x900"; ///< pixels
};

/// Draws height, the 3D path of each centre, speed and energy against time into one PNG with
/// gnuplot. Returns the exit code: 0, 2 for unusable input, 1 when gnuplot is missing or fails.
int plotTrajectory(const PlotOptions& options);

} // namespace impulse::app
