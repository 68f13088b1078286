// SPDX-License-Identifier: MIT
// The shape-pair table. Each routine reports sample points of one body inside (or within
// `threshold` of) the other, GBF03 sec. 3: a point p of A, phi = phi_B(p), normal = grad phi_B(p).
// Analytic shapes use their exact signed distance; a box also samples each edge at its point
// deepest inside the other box, which vertex sampling alone misses when edges cross.
//
//            sphere        box               plane
//   sphere   centre line   closest point     deepest point
//   box      (swapped)     vertices + edges  vertices
//   plane    (swapped)     (swapped)         never (both static)
#include "collision/narrow_phase.hpp"

#include "geometry/signed_distance.hpp"

#include <array>
#include <cmath>

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
    for (int i = 0; i < 8; ++i)
    {
        const Vec3 signs((i & 1) ? 1.0 : -1.0, (i & 2) ? 1.0 : -1.0, (i & 4) ? 1.0 : -1.0);
        corners[static_cast<std::size_t>(i)] = pose.toWorld(signs.cwiseProduct(box.halfExtents));
    }
    return corners;
}

// corners differ in exactly one bit along an edge
constexpr std::array<std::array<int, 2>, 12> kBoxEdges{{{0, 1}, {2, 3}, {4, 5}, {6, 7}, {0, 2}, {1, 3},
                                                        {4, 6}, {5, 7}, {0, 4}, {1, 5}, {2, 6}, {3, 7}}};

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
        out.push_back({poseA.position - plane.normal * (a.radius + 0.5 * phi), plane.normal, phi});
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
        out.push_back({poseA.position - normal * (a.radius + 0.5 * phi), normal, phi});
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

// Points of box `a` inside box `b`: its corners, then each edge's deepest interior point where that
// is deeper than both ends. `sign` is +1 when a is the pair's A and -1 when it is B.
void boxPointsInBox(const Box& a, const Pose& poseA, const Box& b, const Pose& poseB, Real threshold, Real sign,
                    std::vector<ContactPoint>& out)
{
    const std::array<Vec3, 8> corners = boxCorners(a, poseA);
    std::array<Vec3, 8> cornersInB;
    std::array<Real, 8> cornerPhi{};
    for (std::size_t i = 0; i < 8; ++i)
    {
        cornersInB[i] = poseB.toLocal(corners[i]);
        const DistanceSample sample = boxDistance(b.halfExtents, cornersInB[i]);
        cornerPhi[i] = sample.phi;
        if (sample.phi < threshold)
        {
            out.push_back({corners[i], sign * (poseB.rotation * sample.gradient), sample.phi});
        }
    }
    const Real margin = 1e-9 * b.halfExtents.maxCoeff();
    for (const auto& edge : kBoxEdges)
    {
        const auto i = static_cast<std::size_t>(edge[0]);
        const auto j = static_cast<std::size_t>(edge[1]);
        const Real length = (corners[j] - corners[i]).norm();
        // phi is 1-Lipschitz: an edge whose ends are this far out cannot reach the box
        if (cornerPhi[i] + cornerPhi[j] > length + 2.0 * threshold)
        {
            continue;
        }
        const Real t = deepestSegmentParameterInBox(b.halfExtents, cornersInB[i], cornersInB[j]);
        if (t <= 0.0 || t >= 1.0)
        {
            continue;
        }
        const Vec3 local = cornersInB[i] + t * (cornersInB[j] - cornersInB[i]);
        const DistanceSample sample = boxDistance(b.halfExtents, local);
        if (sample.phi < threshold && sample.phi < std::min(cornerPhi[i], cornerPhi[j]) - margin)
        {
            out.push_back({poseB.toWorld(local), sign * (poseB.rotation * sample.gradient), sample.phi});
        }
    }
}

void boxBox(const Box& a, const Pose& poseA, const Box& b, const Pose& poseB, Real threshold,
            std::vector<ContactPoint>& out)
{
    const Real reach = a.halfExtents.norm() + b.halfExtents.norm() + threshold;
    if ((poseA.position - poseB.position).squaredNorm() > reach * reach)
    {
        return;
    }
    boxPointsInBox(a, poseA, b, poseB, threshold, 1.0, out);
    boxPointsInBox(b, poseB, a, poseA, threshold, -1.0, out);
}

// Runs `collide(b, a)` and re-expresses its points for the pair (a, b).
template <class Collide>
void swapped(Collide collide, std::vector<ContactPoint>& out)
{
    const std::size_t first = out.size();
    collide();
    for (std::size_t i = first; i < out.size(); ++i)
    {
        out[i].normal = -out[i].normal;
    }
}

} // namespace

void collideShapes(const Shape& a, const Pose& poseA, const Shape& b, const Pose& poseB, Real threshold,
                   std::vector<ContactPoint>& out)
{
    if (const auto* sa = std::get_if<Sphere>(&a))
    {
        if (const auto* sb = std::get_if<Sphere>(&b))
        {
            return sphereSphere(*sa, poseA, *sb, poseB, threshold, out);
        }
        if (const auto* bb = std::get_if<Box>(&b))
        {
            return sphereBox(*sa, poseA, *bb, poseB, threshold, out);
        }
        if (const auto* pb = std::get_if<Plane>(&b))
        {
            return spherePlane(*sa, poseA, *pb, poseB, threshold, out);
        }
    }
    if (const auto* ba = std::get_if<Box>(&a))
    {
        if (const auto* sb = std::get_if<Sphere>(&b))
        {
            return swapped([&] { sphereBox(*sb, poseB, *ba, poseA, threshold, out); }, out);
        }
        if (const auto* bb = std::get_if<Box>(&b))
        {
            return boxBox(*ba, poseA, *bb, poseB, threshold, out);
        }
        if (const auto* pb = std::get_if<Plane>(&b))
        {
            return boxPlane(*ba, poseA, *pb, poseB, threshold, out);
        }
    }
    if (const auto* pa = std::get_if<Plane>(&a))
    {
        if (const auto* sb = std::get_if<Sphere>(&b))
        {
            return swapped([&] { spherePlane(*sb, poseB, *pa, poseA, threshold, out); }, out);
        }
        if (const auto* bb = std::get_if<Box>(&b))
        {
            return swapped([&] { boxPlane(*bb, poseB, *pa, poseA, threshold, out); }, out);
        }
    }
    // plane-plane: two static half-spaces never need contact
}

} // namespace impulse
