// SPDX-License-Identifier: MIT
#pragma once

#include <impulse/math.hpp>

#include <cstdint>

namespace impulse
{

/// Surface properties of a body.
struct Material
{
    Real restitution = 0.5; ///< coefficient of restitution eps, in [0, 1]
    Real friction = 0.5;    ///< Coulomb coefficient mu (one value for static and kinetic), >= 0
};

/// Restitution and friction that govern one contact between two materials.
struct PairCoefficients
{
    Real restitution = 0.5;
    Real friction = 0.5;
};

/// The default pair rule: eps = max(eps_a, eps_b), mu = sqrt(mu_a * mu_b).
PairCoefficients combineMaterials(const Material& a, const Material& b);

/// Handle to a material of a World.
struct MaterialId
{
    std::uint32_t index = 0;
    friend bool operator==(MaterialId, MaterialId) = default;
};

} // namespace impulse
