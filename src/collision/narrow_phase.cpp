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
    out.push_back({poseB.position + normal * (b.radius + 0.5 * phi), normal, phi});
}

void spherePlane(const Sphere& a, const Pose& poseA, const Plane& b, const Pose& poseB, Real threshold,
                 std::vector<ContactPoint>& out)
{
    const WorldPlane plane = toWorld(b, poseB);
    const Real phi = plane.normal.dot(poseA.position) - plane.offset - a.radius;
    if (phi < threshold)
    {
        // the sphere's own lowest point: the material point that rolls, whatever the overlap
        out.push_back({poseA.position - plane.normal * a.radius, plane.normal, phi});
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
        out.push_back({poseA.position - normal * a.radius, normal, phi});
    }
}

void boxPlane(const Box& a, const Pose& poseA, const Plane& b, const Pose& poseB, Real threshold,
              std::vector<ContactPoint>& out)
{
    const WorldPlane plane = toWorld(b, poseB);
    for (const Vec3& corner : boxCorners(a, poseA))
    {
        const Real phi = plane.normal.dot(corner) - plane.offset;
        if (phi < threshold)
        {
            out.push_back({corner, plane.normal, phi});
        }
    }
}

// The rows of the table, each for the order of shapes its routine takes; the other order of the same
// pair runs the row and turns its normals around (collideShapes).
void row(const Sphere& a, const Pose& pa, const Sphere& b, const Pose& pb, Real t, std::vector<ContactPoint>& out)
{
    sphereSphere(a, pa, b, pb, t, out);
}
void row(const Sphere& a, const Pose& pa, const Box& b, const Pose& pb, Real t, std::vector<ContactPoint>& out)
{
    sphereBox(a, pa, b, pb, t, out);
}
void row(const Sphere& a, const Pose& pa, const Plane& b, const Pose& pb, Real t, std::vector<ContactPoint>& out)
{
    spherePlane(a, pa, b, pb, t, out);
}
void row(const Sphere& a, const Pose& pa, const Mesh& b, const Pose& pb, Real t, std::vector<ContactPoint>& out)
{
    collideSphereMesh(a, pa, b, pb, t, out);
}
void row(const Box& a, const Pose& pa, const Box& b, const Pose& pb, Real t, std::vector<ContactPoint>& out)
{
    collideBoxBox(a, pa, b, pb, t, out);
}
void row(const Box& a, const Pose& pa, const Plane& b, const Pose& pb, Real t, std::vector<ContactPoint>& out)
{
    boxPlane(a, pa, b, pb, t, out);
}
void row(const Box& a, const Pose& pa, const Mesh& b, const Pose& pb, Real t, std::vector<ContactPoint>& out)
{
    collideBoxMesh(a, pa, b, pb, t, out);
}
void row(const Mesh& a, const Pose& pa, const Plane& b, const Pose& pb, Real t, std::vector<ContactPoint>& out)
{
    collideMeshPlane(a, pa, b, pb, t, out);
}
void row(const Mesh& a, const Pose& pa, const Mesh& b, const Pose& pb, Real t, std::vector<ContactPoint>& out)
{
    collideMeshMesh(a, pa, b, pb, t, out);
}
void row(const Capsule& a, const Pose& pa, const Sphere& b, const Pose& pb, Real t, std::vector<ContactPoint>& out)
{
    collideCapsuleSphere(a, pa, b, pb, t, out);
}
void row(const Capsule& a, const Pose& pa, const Box& b, const Pose& pb, Real t, std::vector<ContactPoint>& out)
{
    collideCapsuleBox(a, pa, b, pb, t, out);
}
void row(const Capsule& a, const Pose& pa, const Plane& b, const Pose& pb, Real t, std::vector<ContactPoint>& out)
{
    collideCapsulePlane(a, pa, b, pb, t, out);
}
void row(const Capsule& a, const Pose& pa, const Capsule& b, const Pose& pb, Real t, std::vector<ContactPoint>& out)
{
    collideCapsuleCapsule(a, pa, b, pb, t, out);
}
void row(const Capsule& a, const Pose& pa, const Mesh& b, const Pose& pb, Real t, std::vector<ContactPoint>& out)
{
    collideCapsuleMesh(a, pa, b, pb, t, out);
}

template <class A, class B>
concept HasRow = requires(const A& a, const B& b, const Pose& pose, Real t, std::vector<ContactPoint>& out)
{
    row(a, pose, b, pose, t, out);
};

} // namespace

void collideShapes(const Shape& a, const Pose& poseA, const Shape& b, const Pose& poseB, Real threshold,
                   std::vector<ContactPoint>& out)
{
    // one jump on the two shapes' kinds (this runs at every impulse of every pass)
    std::visit(
        [&](const auto& shapeA, const auto& shapeB)
        {
            using A = std::decay_t<decltype(shapeA)>;
            using B = std::decay_t<decltype(shapeB)>;
            if constexpr (HasRow<A, B>)
            {
                row(shapeA, poseA, shapeB, poseB, threshold, out);
            }
            else if constexpr (HasRow<B, A>)
            {
                const std::size_t first = out.size();
                row(shapeB, poseB, shapeA, poseA, threshold, out);
                for (std::size_t i = first; i < out.size(); ++i)
                {
                    out[i].normal = -out[i].normal;
                }
            }
            // else plane-plane: two static half-spaces never need contact
        },
        a, b);
}

Real leastSignedDistance(const Shape& a, const Pose& poseA, const Shape& b, const Pose& poseB,
                         std::vector<ContactPoint>& scratch)
{
    const auto* ma = std::get_if<Mesh>(&a);
    const auto* mb = std::get_if<Mesh>(&b);
    if (ma != nullptr && mb != nullptr)
    {
        return leastMeshMeshDistance(*ma, poseA, *mb, poseB);
    }
    scratch.clear();
    collideShapes(a, poseA, b, poseB, std::numeric_limits<Real>::infinity(), scratch);
    Real least = std::numeric_limits<Real>::infinity();
    for (const ContactPoint& point : scratch)
    {
        least = std::min(least, point.phi);
    }
    return least;
}

} // namespace impulse
