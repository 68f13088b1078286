// SPDX-License-Identifier: MIT
#pragma once

#include <impulse/math.hpp>
#include <impulse/viz/scene_view.hpp>
#include <impulse/viz/tessellate.hpp>

#include <cstdint>
#include <filesystem>
#include <vector>

namespace impulse::viz
{

/// 8-bit RGB pixels, rows top to bottom.
struct Image
{
    int width = 0;
    int height = 0;
    std::vector<std::uint8_t> rgb;
};

struct Camera
{
    Vec3 eye = Vec3(3.0, -3.0, 2.0);
    Vec3 target = Vec3::Zero();
    Vec3 up = Vec3::UnitZ();
    Real fovYDegrees = 35.0;
};

/// A camera looking at `bounds` from the front right and a little above (with `up` as up), far
/// enough for the bounding sphere to fit the picture.
Camera frameCamera(const Bounds& bounds, const Vec3& up, Real aspect);
/// The same, looking from `direction` (from the content towards the eye, any length).
Camera frameCamera(const Bounds& bounds, const Vec3& up, Real aspect, const Vec3& direction);

/// A mesh placed in the world.
struct DrawnMesh
{
    const TriangleMesh* mesh = nullptr;
    Pose pose;
    bool castsShadow = true; ///< false for the ground: nothing lies below it, and it is large
};

/// A line through world points, such as the path of a body's centre.
struct Polyline
{
    std::vector<Vec3> points;
    Rgb colour;
};

struct RenderSettings
{
    int width = 640;
    int height = 480;
    int supersample = 2; ///< samples per pixel along each axis, averaged: smooth edges
    bool shadows = true;
    /// The region that casts and receives shadows (the moving content); planes outside it are lit.
    Bounds shadowBounds;
};

/// Draws the meshes lit by one directional light from above plus sky light, with shadows, on a
/// sky gradient; then the polylines on top, hidden where a surface is in front of them.
Image renderImage(const std::vector<DrawnMesh>& meshes, const std::vector<Polyline>& lines, const Camera& camera,
                  const RenderSettings& settings);

/// Writes an 8-bit RGB PNG (libpng). Throws std::runtime_error naming the file on failure.
void writePng(const Image& image, const std::filesystem::path& path);

/// Reads any PNG into 8-bit RGB (libpng). Throws std::runtime_error naming the file on failure.
Image readPng(const std::filesystem::path& path);

} // namespace impulse::viz
