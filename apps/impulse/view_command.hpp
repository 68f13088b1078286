// SPDX-License-Identifier: MIT
#pragma once

#include <string>

namespace impulse::app
{

/// What `impulse view` was asked to do.
struct ViewOptions
{
    std::string trajectoryPath;
    std::string scenePath;                             ///< empty: no scene (marker spheres, energy per unit mass)
    std::string outPath;                               ///< empty: the trajectory's name with .html
    std::string threeDirectory = IMPULSE_THREE_JS_DIR; ///< where three.min.js and OrbitControls.js are
};

/// Writes one self-contained HTML page replaying the trajectory. Returns the exit code: 0, 2 for
/// unusable input, 1 when three.js cannot be read or the page cannot be written.
int writeViewer(const ViewOptions& options);

} // namespace impulse::app
