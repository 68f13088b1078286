// SPDX-License-Identifier: MIT
#pragma once

#include <impulse/io/scene.hpp>

#include <string>

namespace impulse::mujoco
{

/// The MJCF equivalent of a scene: one free body per dynamic body (explicit inertial, every number
/// at 17 significant digits so that MuJoCo compiles exactly the scene's values), static bodies as
/// geoms of the world body, a keyframe "initial" holding the initial velocities, restitution and
/// solver options as custom fields impulse reads back, and MuJoCo's own contact parameters
/// (solref, solimp, friction, condim, explicit pairs) chosen as docs/mujoco.md describes so that
/// native mj_step runs the same physics. `timeconst` (seconds, 0 for 2 dt) sets the stiffness of
/// MuJoCo's contacts. Throws std::invalid_argument for a shape MJCF cannot express.
std::string exportMjcf(const io::Scene& scene, Real timeconst = 0.0);

} // namespace impulse::mujoco
