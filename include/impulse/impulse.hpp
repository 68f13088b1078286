// SPDX-License-Identifier: MIT
// Umbrella header: what an application includes.
#pragma once

#include <impulse/body.hpp>
#include <impulse/material.hpp>
#include <impulse/math.hpp>
#include <impulse/shape.hpp>
#include <impulse/world.hpp>
