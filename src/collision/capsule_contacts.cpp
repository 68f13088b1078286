// SPDX-License-Identifier: MIT
#include "collision/capsule_contacts.hpp"

#include "geometry/signed_distance.hpp"

#include <algorithm>
#include <array>
#include <cmath>

namespace impulse
{
namespace
{

struct Segment
{
    Vec3 start; ///< world frame, the -halfLength end
    Vec3 end;   ///< world frame, the +halfLength end
    Vec3 at(Real s) const { return start + s * (end - start); }
};

Segment axisOf(const Capsule& capsule, const Pose& pose)
{
    const Vec3 half = pose.rotation.col(2) * capsule.halfLength;
    return {pose.position - half, pose.position + half};
}

// Two spheres, one centred at `centreA` (radius ra) of body A and one at `centreB` (radius rb) of
// body B: one point in the middle of the overlap, normal from B toward A.
void sphereContact(const Vec3& centreA, Real ra, const Vec3& centreB, Real rb, Real threshold,
                   std::vector<ContactPoint>& out, std::uint32_t feature = 0)
{
    const Vec3 between = centreA - centreB;
    const Real distance = between.norm();
    const Real phi = distance - ra - rb;
    if (phi >= threshold)
    {
        return;
    }
    const Vec3 normal = distance > 0.0 ? Vec3(between / distance) : Vec3::UnitZ();
    out.push_back({centreB + normal * (rb + 0.5 * phi), normal, phi, feature, SampleOf::Between});
}

// Parameter in [0, 1] of the point of `segment` closest to `point`.
Real closestParameter(const Segment& segment, const Vec3& point)
{
    const Vec3 d = segment.end - segment.start;
    const Real length2 = d.squaredNorm();
    return length2 > 0.0 ? std::clamp((point - segment.start).dot(d) / length2, 0.0, 1.0) : 0.0;
}

} // namespace

void collideCapsuleSphere(const Capsule& a, const Pose& poseA, const Sphere& b, const Pose& poseB, Real threshold,
                          std::vector<ContactPoint>& out)
{
    const Segment axis = axisOf(a, poseA);
    const Vec3 closest = axis.at(closestParameter(axis, poseB.position));
    sphereContact(closest, a.radius, poseB.position, b.radius, threshold, out);
}

void collideCapsulePlane(const Capsule& a, const Pose& poseA, const Plane& b, const Pose& poseB, Real threshold,
                         std::vector<ContactPoint>& out)
{
    const Vec3 normal = poseB.rotation * b.normal;
    const Real offset = b.offset + normal.dot(poseB.position);
    const Segment axis = axisOf(a, poseA);
    for (std::uint32_t end = 0; end < 2; ++end)
    {
        const Vec3& centre = end == 0 ? axis.start : axis.end;
        const Real phi = normal.dot(centre) - offset - a.radius;
        if (phi < threshold)
        {
            out.push_back({centre - normal * (a.radius + 0.5 * phi), normal, phi, end, SampleOf::Between});
        }
    }
}

void collideCapsuleBox(const Capsule& a, const Pose& poseA, const Box& b, const Pose& poseB, Real threshold,
                       std::vector<ContactPoint>& out)
{
    const Segment axis = axisOf(a, poseA);
    const auto boxPhi = [&](Real s) { return boxDistance(b.halfExtents, poseB.toLocal(axis.at(s))).phi; };
    const auto addEndSphere = [&](Real s, std::uint32_t feature)
    {
        const Vec3 centre = axis.at(s);
        const DistanceSample sample = boxDistance(b.halfExtents, poseB.toLocal(centre));
        const Real phi = sample.phi - a.radius;
        if (phi < threshold)
        {
            const Vec3 normal = poseB.rotation * sample.gradient;
            out.push_back({centre - normal * (a.radius + 0.5 * phi), normal, phi, feature, SampleOf::Between});
        }
    };
    addEndSphere(0.0, 0);
    addEndSphere(1.0, 1);

    // The box's signed distance is convex, so along the segment it has one minimum (or one flat
    // bottom): golden-section search finds it. It adds a point only when strictly deeper than both
    // ends, which is a box edge or corner under the capsule's middle, not a face it lies flat on.
    constexpr Real kInvPhi = 0.6180339887498949;
    Real lo = 0.0;
    Real hi = 1.0;
    Real x1 = hi - kInvPhi * (hi - lo);
    Real x2 = lo + kInvPhi * (hi - lo);
    Real f1 = boxPhi(x1);
    Real f2 = boxPhi(x2);
    for (int i = 0; i < 80; ++i)
    {
        if (f1 <= f2)
        {
            hi = x2;
            x2 = x1;
            f2 = f1;
            x1 = hi - kInvPhi * (hi - lo);
            f1 = boxPhi(x1);
        }
        else
        {
            lo = x1;
            x1 = x2;
            f1 = f2;
            x2 = lo + kInvPhi * (hi - lo);
            f2 = boxPhi(x2);
        }
    }
    const Real middle = 0.5 * (lo + hi);
    const Real scale = a.radius + a.halfLength + b.halfExtents.norm();
    if (boxPhi(middle) < std::min(boxPhi(0.0), boxPhi(1.0)) - 1e-9 * scale)
    {
        addEndSphere(middle, 2);
    }
}

void collideCapsuleCapsule(const Capsule& a, const Pose& poseA, const Capsule& b, const Pose& poseB, Real threshold,
                           std::vector<ContactPoint>& out)
{
    const Segment sa = axisOf(a, poseA);
    const Segment sb = axisOf(b, poseB);
    const Vec3 da = sa.end - sa.start;
    const Vec3 db = sb.end - sb.start;
    const Vec3 r = sa.start - sb.start;
    const Real aa = da.squaredNorm();
    const Real bb = db.squaredNorm();
    const Real ab = da.dot(db);
    const Real denominator = aa * bb - ab * ab; // |da x db|^2, zero for parallel segments

    if (denominator <= 1e-12 * aa * bb)
    {
        // parallel: the ends of the stretch of A that lies alongside B, when there is one
        const Real s0 = std::clamp(std::min((sb.start - sa.start).dot(da), (sb.end - sa.start).dot(da)) / aa, 0.0, 1.0);
        const Real s1 = std::clamp(std::max((sb.start - sa.start).dot(da), (sb.end - sa.start).dot(da)) / aa, 0.0, 1.0);
        if (s1 - s0 > 1e-9)
        {
            for (std::uint32_t end = 0; end < 2; ++end)
            {
                const Vec3 pa = sa.at(end == 0 ? s0 : s1);
                sphereContact(pa, a.radius, sb.at(closestParameter(sb, pa)), b.radius, threshold, out, end);
            }
            return;
        }
    }

    // closest points of two segments: the unconstrained minimiser clamped to A's range, B's
    // parameter from it, then A's re-clamped if B's had to be
    const Real c = da.dot(r);
    const Real f = db.dot(r);
    Real s = denominator > 1e-12 * aa * bb ? std::clamp((ab * f - c * bb) / denominator, 0.0, 1.0) : 0.0;
    Real t = (ab * s + f) / bb;
    if (t < 0.0)
    {
        t = 0.0;
        s = std::clamp(-c / aa, 0.0, 1.0);
    }
    else if (t > 1.0)
    {
        t = 1.0;
        s = std::clamp((ab - c) / aa, 0.0, 1.0);
    }
    sphereContact(sa.at(s), a.radius, sb.at(t), b.radius, threshold, out);
}

} // namespace impulse
