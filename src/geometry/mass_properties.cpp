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
// clang before 17 deduces no aggregate's template arguments without a guide
template <class... Fs> Overloaded(Fs...) -> Overloaded<Fs...>;
constexpr Real kInfinity = std::numeric_limits<Real>::infinity();

Real capsuleVolume(const Capsule& c)
{
    // a cylinder of length 2h and the two hemispheres, one whole sphere
    const Real r2 = c.radius * c.radius;
    return std::numbers::pi * r2 * (2.0 * c.halfLength + 4.0 / 3.0 * c.radius);
}

Vec3 capsuleUnitInertia(const Capsule& c)
{
    // Per unit density: the cylinder (mass mc) and the two hemispheres (together ms). About the
    // axis: mc r^2/2 + ms 2r^2/5. Across it: the cylinder mc (r^2/4 + h^2/3); each hemisphere has
    // its centre of mass 3r/8 beyond its flat face, which sits at distance h from the centre, so by
    // the parallel-axis theorem both together give ms (2r^2/5 - (3r/8)^2 + (h + 3r/8)^2)
    // = ms (2r^2/5 + h^2 + 3hr/4).
    const Real r = c.radius;
    const Real h = c.halfLength;
    const Real mc = std::numbers::pi * r * r * 2.0 * h;
    const Real ms = 4.0 / 3.0 * std::numbers::pi * r * r * r;
    const Real axial = mc * r * r / 2.0 + ms * 0.4 * r * r;
    const Real across = mc * (r * r / 4.0 + h * h / 3.0) + ms * (0.4 * r * r + h * h + 0.75 * h * r);
    const Real mass = mc + ms;
    return Vec3(across, across, axial) / mass;
}
} // namespace

Real boundingRadius(const Shape& shape)
{
    return std::visit(
        Overloaded{[](const Sphere& s) { return s.radius; }, [](const Box& b) { return b.halfExtents.norm(); },
                   [](const Plane&) { return kInfinity; }, [](const Capsule& c) { return c.halfLength + c.radius; },
                   [](const Mesh& m) { return m.geometry->boundingRadius(); }},
        shape);
}

Real thinnestHalfExtent(const Shape& shape)
{
    return std::visit(
        Overloaded{[](const Sphere& s) { return s.radius; }, [](const Box& b) { return b.halfExtents.minCoeff(); },
                   [](const Plane&) { return kInfinity; }, [](const Capsule& c) { return c.radius; },
                   [](const Mesh& m) { return 0.5 * (m.geometry->upper() - m.geometry->lower()).minCoeff(); }},
        shape);
}

Real volume(const Shape& shape)
{
    return std::visit(
        Overloaded{[](const Sphere& s) { return 4.0 / 3.0 * std::numbers::pi * s.radius * s.radius * s.radius; },
                   [](const Box& b) { return 8.0 * b.halfExtents.prod(); }, [](const Plane&) { return kInfinity; },
                   [](const Capsule& c) { return capsuleVolume(c); },
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
                                 [](const Capsule& c) -> Vec3 { return capsuleUnitInertia(c); },
                                 [](const Mesh& m) -> Vec3 { return m.geometry->unitInertia(); }},
                      shape);
}

} // namespace impulse
