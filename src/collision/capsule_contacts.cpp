// SPDX-License-Identifier: MIT
#include "collision/capsule_contacts.hpp"

#include "geometry/signed_distance.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

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

LeastAlong leastBoxDistanceAlong(const Vec3& halfExtents, const Vec3& start, const Vec3& along)
{
    // The box's signed distance is convex, and along the segment it is smooth between the
    // parameters where a coordinate crosses a face plane (+-h) or a mid-plane (0): there the set of
    // axes the point lies outside of, and the sign of each coordinate, stay the same. On such a
    // stretch it is the length of a vector affine in s (outside) or the largest of three affine
    // functions (inside), so its least value is at a stretch end, at the vertex of the squared
    // length, or where two of the affine functions cross. The least over those candidates is the
    // least over the segment; no iteration, and exact to round-off.
    std::array<Real, 11> breaks{};
    std::size_t count = 0;
    breaks[count++] = 0.0;
    for (int i = 0; i < 3; ++i)
    {
        if (along[i] == 0.0)
        {
            continue;
        }
        for (const Real plane : {-halfExtents[i], 0.0, halfExtents[i]})
        {
            const Real s = (plane - start[i]) / along[i];
            if (s > 0.0 && s < 1.0)
            {
                breaks[count++] = s;
            }
        }
    }
    breaks[count++] = 1.0;
    std::sort(breaks.begin(), breaks.begin() + static_cast<std::ptrdiff_t>(count));

    LeastAlong least{0.0, std::numeric_limits<Real>::infinity()};
    const auto consider = [&](Real s)
    {
        const Real phi = boxDistance(halfExtents, start + s * along).phi;
        if (phi < least.phi)
        {
            least = {s, phi};
        }
    };
    for (std::size_t k = 0; k < count; ++k)
    {
        consider(breaks[k]);
    }
    for (std::size_t k = 0; k + 1 < count; ++k)
    {
        const Real lo = breaks[k];
        const Real hi = breaks[k + 1];
        if (!(hi > lo))
        {
            continue;
        }
        const Vec3 middle = start + (0.5 * (lo + hi)) * along;
        Vec3 sign;
        bool outside = false;
        for (int i = 0; i < 3; ++i)
        {
            sign[i] = middle[i] < 0.0 ? -1.0 : 1.0;
            outside = outside || std::abs(middle[i]) > halfExtents[i];
        }
        if (outside)
        {
            // the vertex of |start + s along - nearest face point|^2 over the axes outside here
            Real slope = 0.0;
            Real curvature = 0.0;
            for (int i = 0; i < 3; ++i)
            {
                if (std::abs(middle[i]) > halfExtents[i])
                {
                    slope += (start[i] - sign[i] * halfExtents[i]) * along[i];
                    curvature += along[i] * along[i];
                }
            }
            if (curvature > 0.0)
            {
                consider(std::clamp(-slope / curvature, lo, hi));
            }
            continue;
        }
        // inside: where two of sign_i x_i(s) - h_i cross
        for (int i = 0; i < 3; ++i)
        {
            for (int j = i + 1; j < 3; ++j)
            {
                const Real rate = sign[i] * along[i] - sign[j] * along[j];
                if (rate != 0.0)
                {
                    const Real s =
                        ((sign[j] * start[j] - halfExtents[j]) - (sign[i] * start[i] - halfExtents[i])) / rate;
                    if (s > lo && s < hi)
                    {
                        consider(s);
                    }
                }
            }
        }
    }
    return least;
}

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

    // A point only where the segment goes strictly deeper than both ends: a box edge or corner
    // under the capsule's middle, not a face it lies flat on.
    const Vec3 start = poseB.toLocal(axis.start);
    const Vec3 along = poseB.toLocal(axis.end) - start;
    const LeastAlong least = leastBoxDistanceAlong(b.halfExtents, start, along);
    const Real scale = a.radius + a.halfLength + b.halfExtents.norm();
    const Real ends = std::min(boxDistance(b.halfExtents, start).phi, boxDistance(b.halfExtents, start + along).phi);
    if (least.phi < ends - 1e-9 * scale)
    {
        addEndSphere(least.s, 2);
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
