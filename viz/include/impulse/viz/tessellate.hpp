// SPDX-License-Identifier: MIT
#pragma once

#include <impulse/math.hpp>
#include <impulse/shape.hpp>

#include <array>
#include <cstdint>
#include <string>
#include <vector>

namespace impulse::viz
{

struct Rgb
{
    float r = 0.0f;
    float g = 0.0f;
    float b = 0.0f;
};

/// The colour of dynamic body k, the same in plots, frames and the viewer.
Rgb bodyColour(std::size_t body);

/// "#rrggbb", for gnuplot and the browser.
std::string hexColour(Rgb colour);

/// Triangles in a body's frame: every shape is drawn through this one form, by the software
/// renderer and by the browser viewer alike. Regions of one colour have their own vertices.
struct TriangleMesh
{
    std::vector<Vec3> positions;
    std::vector<Vec3> normals; ///< unit, per vertex
    std::vector<Rgb> colours;  ///< per vertex
    std::vector<std::array<std::uint32_t, 3>> triangles;
};

/// Where to lay out the finite piece of an infinite plane: the square of half size `halfSize`
/// centred on the projection of `focus` (body frame) onto the plane.
struct PlanePatch
{
    Vec3 focus = Vec3::Zero();
    Real halfSize = 5.0;
};

/// A triangle list drawn with flat faces: each triangle gets its own vertices and its face normal
/// (counter-clockwise seen from outside). Boxes are drawn this way, and so can any mesh shape be.
TriangleMesh flatShaded(const std::vector<Vec3>& vertices, const std::vector<std::array<std::uint32_t, 3>>& triangles,
                        Rgb colour);

/// Tessellates a shape in its body frame: spheres in coloured octants (so that spin shows), boxes
/// face by face, planes as a checkerboard square.
TriangleMesh bodyTriangles(const Shape& shape, Rgb colour, const PlanePatch& patch = {});

} // namespace impulse::viz
