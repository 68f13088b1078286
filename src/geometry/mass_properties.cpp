// SPDX-License-Identifier: MIT
// Mass properties of the analytic solids. Bodies live in their principal frame, so each solid
// reports three principal moments per unit mass.
#include <impulse/shape.hpp>

#include <limits>
#include <numbers>

namespace impulse
{
namespace
{
template <class... Fs> struct Overloaded : Fs...
{
    using Fs::operator()...;
};
constexpr Real kInfinity = std::numeric_limits<Real>::infinity();
} // namespace

Real boundingRadius(const Shape& shape)
{
    return std::visit(
        Overloaded{[](const Sphere& s) { return s.radius; }, [](const Box& b) { return b.halfExtents.norm(); },
                   [](const Plane&) { return kInfinity; }, [](const Mesh& m) { return m.geometry->boundingRadius(); }},
        shape);
}

Real volume(const Shape& shape)
{
    return std::visit(
        Overloaded{[](const Sphere& s) { return 4.0 / 3.0 * std::numbers::pi * s.radius * s.radius * s.radius; },
                   [](const Box& b) { return 8.0 * b.halfExtents.prod(); }, [](const Plane&) { return kInfinity; },
                   [](const Mesh& m) { return m.geometry->volume(); }},
        shape);
}

Vec3 unitInertia(const Shape& shape)
{
    return std::visit(Overloaded{[](const Sphere& s) -> Vec3 { return Vec3::Constant(0.4 * s.radius * s.radius); },
                                 [](const Box& b) -> Vec3
                                 {
                                     // I_x = m (h_y^2 + h_z^2) / 3 with half extents h
                                     const Vec3 h2 = b.halfExtents.cwiseProduct(b.halfExtents);
                                     return Vec3(h2.y() + h2.z(), h2.x() + h2.z(), h2.x() + h2.y()) / 3.0;
                                 },
                                 [](const Plane&) -> Vec3 { return Vec3::Constant(kInfinity); },
                                 [](const Mesh& m) -> Vec3 { return m.geometry->unitInertia(); }},
                      shape);
}

} // namespace impulse
