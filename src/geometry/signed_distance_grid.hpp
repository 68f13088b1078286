// SPDX-License-Identifier: MIT
// phi of a closed mesh sampled on a uniform grid in body space (GBF03 sec. 3), with trilinear
// interpolation and its gradient.
#pragma once

#include "geometry/triangle_bvh.hpp"

#include <array>
#include <vector>

namespace impulse
{

class SignedDistanceGrid
{
  public:
    /// Samples phi over the box [lower, upper] grown by a few cells, with `resolution` cells along
    /// its longest side. Exact (tree search) within two cells of the surface; beyond, the distance
    /// to the nearest triangle of a neighbour, carried by fast sweeping; signs beyond the band by
    /// flood fill from it, so a far sample can never take the wrong side.
    SignedDistanceGrid(const TriangleBvh& bvh, const Vec3& lower, const Vec3& upper, int resolution);

    /// The samples along each axis that the constructor takes for this box and resolution, so that
    /// their number can be checked before any memory is taken; as reals, which a box too large for
    /// double precision makes infinite or NaN rather than undefined.
    static Vec3 sampleCounts(const Vec3& lower, const Vec3& upper, int resolution);

    /// What interpolation at a point reads: the eight corner values of its cell, its position in
    /// the cell, and phi there (with the way to the grid box added outside it).
    struct Stencil
    {
        Real phi = 0.0;
        std::array<Real, 8> corner{}; ///< c000, c100, c010, c110, c001, c101, c011, c111
        std::array<Real, 3> fraction{};
    };

    MeshDistance sample(const Vec3& p) const { return withGradient(stencil(p)); }
    /// phi alone, as sample(p).phi: no gradient.
    Real samplePhi(const Vec3& p) const { return stencil(p).phi; }
    Stencil stencil(const Vec3& p) const;
    /// phi and its unit gradient from a stencil: the same as sample() at its point.
    static MeshDistance withGradient(const Stencil& stencil);

    /// Whether p lies within the sampled box, where phi is interpolated rather than extended.
    bool contains(const Vec3& p) const
    {
        return (p.array() >= m_origin.array()).all() && (p.array() <= m_far.array()).all();
    }
    Real cellSize() const { return m_cell; }
    const std::array<int, 3>& samples() const { return m_samples; }
    /// Cells of padding around the mesh's bounding box.
    static constexpr int kPadding = 3;

  private:
    std::size_t index(int i, int j, int k) const
    {
        return static_cast<std::size_t>(i) +
               static_cast<std::size_t>(m_samples[0]) *
                   (static_cast<std::size_t>(j) + static_cast<std::size_t>(m_samples[1]) * static_cast<std::size_t>(k));
    }
    Vec3 position(int i, int j, int k) const { return m_origin + m_cell * Vec3(i, j, k); }

    Vec3 m_origin = Vec3::Zero();
    Vec3 m_far = Vec3::Zero(); ///< the last sample, opposite m_origin
    Real m_cell = 1.0;
    std::array<int, 3> m_samples{};
    std::vector<Real> m_phi;
};

} // namespace impulse
