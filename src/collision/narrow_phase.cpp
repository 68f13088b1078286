// SPDX-License-Identifier: MIT
// The shape-pair table. Each routine reports sample points of one body inside (or within
// `threshold` of) the other, GBF03 sec. 3: a point p of A, phi = phi_B(p), normal = grad phi_B(p).
// Analytic shapes use their exact signed distance. Box against box uses the separating-axis test
// with face clipping (box_box.cpp): sampling corners against a box's distance is degenerate for
// boxes stacked flush, whose corners all lie on the other box's edges.
//
//            sphere        box                      plane            mesh
//   sphere   centre line   closest point            deepest point    closest points (mesh_contacts.cpp)
//   box      (swapped)     separating axis + clip   corners          vertices and edges both ways
//   plane    (swapped)     (swapped)                never (static)   vertices
//   mesh     (swapped)     (swapped)                (swapped)        vertices and edges both ways
// Capsules have their own rows, in capsule_contacts.cpp (against a mesh: mesh_contacts.cpp).
#include "collision/narrow_phase.hpp"

#include "collision/box_box.hpp"
#include "collision/capsule_contacts.hpp"
#include "collision/mesh_contacts.hpp"
#include "geometry/box_queries.hpp"
#include "geometry/signed_distance.hpp"

#include <array>
#include <cmath>
#include <type_traits>
#include <variant>

namespace impulse
{
namespace
{

struct WorldPlane
{
    Vec3 normal;
    Real offset;
};

WorldPlane toWorld(const Plane& plane, const Pose& pose)
{
    const Vec3 normal = pose.rotation * plane.normal;
    return {normal, plane.offset + normal.dot(pose.position)};
}

std::array<Vec3, 8> boxCorners(const Box& box, const Pose& pose)
{
    std::array<Vec3, 8> corners;
    for (std::size_t i = 0; i < 8; ++i)
    {
        corners[i] = pose.toWorld(boxCorner(box.halfExtents, i));
    }
    return corners;
}

void sphereSphere(const Sphere& a, const Pose& poseA, const Sphere& b, const Pose& poseB, Real threshold,
                  std::vector<ContactPoint>& out)
{
    const Vec3 between = poseA.position - poseB.position;
    const Real distance = between.norm();
    const Real phi = distance - a.radius - b.radius;
    if (phi >= threshold)
    {
        return;
    }
    const Vec3 normal = distance > 0.0 ? Vec3(between / distance) : Vec3::UnitZ();
    // the middle of the overlap, so that neither body is favoured for lever arms
    out.push_back({poseB.position + normal * (b.radius + 0.5 * phi), normal, phi, 0, SampleOf::Between});
}

void spherePlane(const Sphere& a, const Pose& poseA, const Plane& b, const Pose& poseB, Real threshold,
                 std::vector<ContactPoint>& out)
{
    const WorldPlane plane = toWorld(b, poseB);
    const Real phi = plane.normal.dot(poseA.position) - plane.offset - a.radius;
    if (phi < threshold)
    {
        // the sphere's own lowest point: the material point that rolls, whatever the overlap
        out.push_back({poseA.position - plane.normal * a.radius, plane.normal, phi, 0, SampleOf::A});
    }
}

void sphereBox(const Sphere& a, const Pose& poseA, const Box& b, const Pose& poseB, Real threshold,
               std::vector<ContactPoint>& out)
{
    const DistanceSample sample = boxDistance(b.halfExtents, poseB.toLocal(poseA.position));
    const Real phi = sample.phi - a.radius;
    if (phi < threshold)
    {
        const Vec3 normal = poseB.rotation * sample.gradient;
        out.push_back({poseA.position - normal * a.radius, normal, phi, 0, SampleOf::A});
    }
}

void boxPlane(const Box& a, const Pose& poseA, const Plane& b, const Pose& poseB, Real threshold,
              std::vector<ContactPoint>& out)
{
    const WorldPlane plane = toWorld(b, poseB);
    const std::array<Vec3, 8> corners = boxCorners(a, poseA);
    for (std::uint32_t i = 0; i < corners.size(); ++i)
    {
        const Real phi = plane.normal.dot(corners[i]) - plane.offset;
        if (phi < threshold)
        {
            out.push_back({corners[i], plane.normal, phi, i, SampleOf::A});
        }
    }
}

// The rows of the table, each for the order of shapes its routine takes; the other order of the same
// pair runs the row and turns its normals around (collideShapes).
void row(const Sphere& a, const Pose& pa, const Sphere& b, const Pose& pb, Real t, std::vector<ContactPoint>& out,
         NarrowPhaseScratch&)
{
    sphereSphere(a, pa, b, pb, t, out);
}
void row(const Sphere& a, const Pose& pa, const Box& b, const Pose& pb, Real t, std::vector<ContactPoint>& out,
         NarrowPhaseScratch&)
{
    sphereBox(a, pa, b, pb, t, out);
}
void row(const Sphere& a, const Pose& pa, const Plane& b, const Pose& pb, Real t, std::vector<ContactPoint>& out,
         NarrowPhaseScratch&)
{
    spherePlane(a, pa, b, pb, t, out);
}
void row(const Sphere& a, const Pose& pa, const Mesh& b, const Pose& pb, Real t, std::vector<ContactPoint>& out,
         NarrowPhaseScratch& scratch)
{
    collideSphereMesh(a, pa, b, pb, t, out, scratch.mesh());
}
void row(const Box& a, const Pose& pa, const Box& b, const Pose& pb, Real t, std::vector<ContactPoint>& out,
         NarrowPhaseScratch&)
{
    collideBoxBox(a, pa, b, pb, t, out);
}
void row(const Box& a, const Pose& pa, const Plane& b, const Pose& pb, Real t, std::vector<ContactPoint>& out,
         NarrowPhaseScratch&)
{
    boxPlane(a, pa, b, pb, t, out);
}
void row(const Box& a, const Pose& pa, const Mesh& b, const Pose& pb, Real t, std::vector<ContactPoint>& out,
         NarrowPhaseScratch& scratch)
{
    collideBoxMesh(a, pa, b, pb, t, out, scratch.mesh());
}
void row(const Mesh& a, const Pose& pa, const Plane& b, const Pose& pb, Real t, std::vector<ContactPoint>& out,
         NarrowPhaseScratch&)
{
    collideMeshPlane(a, pa, b, pb, t, out);
}
void row(const Mesh& a, const Pose& pa, const Mesh& b, const Pose& pb, Real t, std::vector<ContactPoint>& out,
         NarrowPhaseScratch& scratch)
{
    collideMeshMesh(a, pa, b, pb, t, out, scratch.mesh());
}
void row(const Capsule& a, const Pose& pa, const Sphere& b, const Pose& pb, Real t, std::vector<ContactPoint>& out,
         NarrowPhaseScratch&)
{
    collideCapsuleSphere(a, pa, b, pb, t, out);
}
void row(const Capsule& a, const Pose& pa, const Box& b, const Pose& pb, Real t, std::vector<ContactPoint>& out,
         NarrowPhaseScratch&)
{
    collideCapsuleBox(a, pa, b, pb, t, out);
}
void row(const Capsule& a, const Pose& pa, const Plane& b, const Pose& pb, Real t, std::vector<ContactPoint>& out,
         NarrowPhaseScratch&)
{
    collideCapsulePlane(a, pa, b, pb, t, out);
}
void row(const Capsule& a, const Pose& pa, const Capsule& b, const Pose& pb, Real t, std::vector<ContactPoint>& out,
         NarrowPhaseScratch&)
{
    collideCapsuleCapsule(a, pa, b, pb, t, out);
}
void row(const Capsule& a, const Pose& pa, const Mesh& b, const Pose& pb, Real t, std::vector<ContactPoint>& out,
         NarrowPhaseScratch& scratch)
{
    collideCapsuleMesh(a, pa, b, pb, t, out, scratch.mesh());
}

template <class A, class B>
concept HasRow = requires(const A& a, const B& b, const Pose& pose, Real t, std::vector<ContactPoint>& out,
                          NarrowPhaseScratch& s)
{
    row(a, pose, b, pose, t, out, s);
};

} // namespace

void collideShapes(const Shape& a, const Pose& poseA, const Shape& b, const Pose& poseB, Real threshold,
                   std::vector<ContactPoint>& out, NarrowPhaseScratch& scratch)
{
    // one jump on the two shapes' kinds (this runs at every impulse of every pass)
    std::visit(
        [&](const auto& shapeA, const auto& shapeB)
        {
            using A = std::decay_t<decltype(shapeA)>;
            using B = std::decay_t<decltype(shapeB)>;
            if constexpr (HasRow<A, B>)
            {
                row(shapeA, poseA, shapeB, poseB, threshold, out, scratch);
            }
            else if constexpr (HasRow<B, A>)
            {
                const std::size_t first = out.size();
                row(shapeB, poseB, shapeA, poseA, threshold, out, scratch);
                for (std::size_t i = first; i < out.size(); ++i)
                {
                    out[i].normal = -out[i].normal;
                    out[i].sample = out[i].sample == SampleOf::A   ? SampleOf::B
                                    : out[i].sample == SampleOf::B ? SampleOf::A
                                                                   : SampleOf::Between;
                }
            }
            // else plane-plane: two static half-spaces never need contact
        },
        a, b);
}

Real leastSignedDistance(const Shape& a, const Pose& poseA, const Shape& b, const Pose& poseB,
                         NarrowPhaseScratch& scratch)
{
    const auto* ma = std::get_if<Mesh>(&a);
    const auto* mb = std::get_if<Mesh>(&b);
    if (ma != nullptr && mb != nullptr)
    {
        return leastMeshMeshDistance(*ma, poseA, *mb, poseB, scratch.mesh());
    }
    std::vector<ContactPoint>& points = scratch.points;
    points.clear();
    collideShapes(a, poseA, b, poseB, std::numeric_limits<Real>::infinity(), points, scratch);
    Real least = std::numeric_limits<Real>::infinity();
    for (const ContactPoint& point : points)
    {
        least = std::min(least, point.phi);
    }
    return least;
}

} // namespace impulse
