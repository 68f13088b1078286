// SPDX-License-Identifier: MIT
#pragma once

#include "collision/contact.hpp"

#include <impulse/shape.hpp>

#include <memory>
#include <vector>

namespace impulse
{

struct MeshContactScratch;

/// What the narrow phase reuses from call to call: buffers, and the latest answers of mesh pairs
/// (mesh_contacts.cpp). The caller owns it and passes it to every call; calls on several threads at
/// once need one each (WorldImpl keeps one per worker thread). What it holds never changes an
/// answer, only what the answer costs.
class NarrowPhaseScratch
{
  public:
    NarrowPhaseScratch();
    ~NarrowPhaseScratch();
    NarrowPhaseScratch(NarrowPhaseScratch&&) noexcept;
    NarrowPhaseScratch& operator=(NarrowPhaseScratch&&) noexcept;

    /// What leastSignedDistance collides a pair into.
    std::vector<ContactPoint> points;

    /// The mesh rows' part, made when a mesh row first needs it: a world without meshes pays nothing.
    MeshContactScratch& mesh();

  private:
    std::unique_ptr<MeshContactScratch> m_mesh;
};

/// Appends to `out` every sample point of the pair (A at poseA, B at poseB) whose signed distance
/// is below `threshold`: points of A inside (or near) B and points of B inside (or near) A, all
/// expressed with the normal from B toward A.
void collideShapes(const Shape& a, const Pose& poseA, const Shape& b, const Pose& poseB, Real threshold,
                   std::vector<ContactPoint>& out, NarrowPhaseScratch& scratch);

/// The least signed distance of the pair: the least phi of the points collideShapes gives with an
/// infinite threshold, +infinity if it gives none. Two meshes skip the vertices that cannot be the
/// least; other pairs collide into `scratch.points`.
Real leastSignedDistance(const Shape& a, const Pose& poseA, const Shape& b, const Pose& poseB,
                         NarrowPhaseScratch& scratch);

} // namespace impulse
