// SPDX-License-Identifier: MIT
// Narrow phase of the shape pairs with a triangle mesh (GBF03 sec. 3): the vertices of each body
// against the other's signed distance, and edges that pass through the other body.
#pragma once

#include "collision/contact.hpp"

#include <impulse/shape.hpp>

#include <vector>

namespace impulse
{

/// What the mesh rows reuse from call to call (mesh_contacts.cpp), NarrowPhaseScratch::mesh().
struct MeshContactScratch;

void collideMeshPlane(const Mesh& a, const Pose& poseA, const Plane& b, const Pose& poseB, Real threshold,
                      std::vector<ContactPoint>& out);
void collideSphereMesh(const Sphere& a, const Pose& poseA, const Mesh& b, const Pose& poseB, Real threshold,
                       std::vector<ContactPoint>& out, MeshContactScratch& scratch);
void collideBoxMesh(const Box& a, const Pose& poseA, const Mesh& b, const Pose& poseB, Real threshold,
                    std::vector<ContactPoint>& out, MeshContactScratch& scratch);
void collideCapsuleMesh(const Capsule& a, const Pose& poseA, const Mesh& b, const Pose& poseB, Real threshold,
                        std::vector<ContactPoint>& out, MeshContactScratch& scratch);
void collideMeshMesh(const Mesh& a, const Pose& poseA, const Mesh& b, const Pose& poseB, Real threshold,
                     std::vector<ContactPoint>& out, MeshContactScratch& scratch);

/// The least phi of the points collideMeshMesh gives with an infinite threshold (every vertex of
/// each mesh against the other), to the bit, without the distance queries of the vertices whose
/// bounds show they cannot be the least.
Real leastMeshMeshDistance(const Mesh& a, const Pose& poseA, const Mesh& b, const Pose& poseB,
                           MeshContactScratch& scratch);

} // namespace impulse
