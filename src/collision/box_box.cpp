// SPDX-License-Identifier: MIT
#include "collision/box_box.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

namespace impulse
{
namespace
{

struct OrientedBox
{
    Vec3 centre;
    Mat3 axes; ///< columns: the box's unit axes, world frame
    Vec3 half;
};

// A convex polygon in fixed storage (the clip runs at every re-detection): a box face has four
// corners and each of the four clips to the reference face's sides adds at most one. Round-off can
// make a nearly degenerate polygon cross a plane more than twice; corners beyond the storage are
// dropped then, which only thins out a patch that is already redundant.
struct FacePolygon
{
    static constexpr std::size_t kCapacity = 16;
    std::array<Vec3, kCapacity> corners;
    std::array<std::uint32_t, kCapacity> features; ///< per corner: what made it (contact.hpp)
    std::size_t size = 0;

    void add(const Vec3& corner, std::uint32_t feature)
    {
        if (size < corners.size())
        {
            corners[size] = corner;
            features[size++] = feature;
        }
    }
};

// Clips a convex polygon to the half-space {p : normal . p <= offset}, into `result`. Each corner's
// distance to the plane is worked out once, and the walk steps to the next corner without a
// division: the clip runs four times per face contact at every re-detection. A corner made by the
// plane is named after the edge it cuts and the plane (`side`).
void clip(const FacePolygon& polygon, const Vec3& normal, Real offset, std::uint32_t side, FacePolygon& result)
{
    result.size = 0;
    std::array<Real, FacePolygon::kCapacity> distance;
    for (std::size_t i = 0; i < polygon.size; ++i)
    {
        distance[i] = normal.dot(polygon.corners[i]) - offset;
    }
    for (std::size_t i = 0; i < polygon.size; ++i)
    {
        const std::size_t next = i + 1 == polygon.size ? 0 : i + 1;
        const Vec3& p = polygon.corners[i];
        const Vec3& q = polygon.corners[next];
        const Real dp = distance[i];
        const Real dq = distance[next];
        if (dp <= 0.0)
        {
            result.add(p, polygon.features[i]);
        }
        if ((dp < 0.0 && dq > 0.0) || (dp > 0.0 && dq < 0.0))
        {
            const std::uint32_t edge = combineFeatures(polygon.features[i], polygon.features[next]);
            result.add(p + (dp / (dp - dq)) * (q - p), combineFeatures(edge, side));
        }
    }
}

// Face contact: `reference` owns the face with outward normal `normal` (pointing at `incident`).
// `sign` turns the reference normal into the pair's normal (from B toward A).
void faceContact(const OrientedBox& reference, int referenceAxis, const Vec3& normal, const OrientedBox& incident,
                 Real sign, Real threshold, std::vector<ContactPoint>& out)
{
    // the incident face is the one most opposed to the reference normal
    int incidentAxis = 0;
    Real mostOpposed = std::numeric_limits<Real>::infinity();
    Real incidentSign = 1.0;
    for (int k = 0; k < 3; ++k)
    {
        const Real d = incident.axes.col(k).dot(normal);
        for (const Real s : {1.0, -1.0})
        {
            if (s * d < mostOpposed)
            {
                mostOpposed = s * d;
                incidentAxis = k;
                incidentSign = s;
            }
        }
    }
    const int u = (incidentAxis + 1) % 3;
    const int v = (incidentAxis + 2) % 3;
    const Vec3 faceCentre =
        incident.centre + incidentSign * incident.half[incidentAxis] * incident.axes.col(incidentAxis);
    const Vec3 du = incident.half[u] * incident.axes.col(u);
    const Vec3 dv = incident.half[v] * incident.axes.col(v);
    // the incident face's corners are named by the face and the corner
    const std::uint32_t face = 4 * (2 * static_cast<std::uint32_t>(incidentAxis) + (incidentSign > 0.0 ? 1 : 0));
    FacePolygon polygon;
    polygon.add(faceCentre + du + dv, face);
    polygon.add(faceCentre - du + dv, face + 1);
    polygon.add(faceCentre - du - dv, face + 2);
    polygon.add(faceCentre + du - dv, face + 3);

    // clip to the four side planes of the reference face
    FacePolygon clipped;
    for (int k = 0; k < 3 && polygon.size > 0; ++k)
    {
        if (k == referenceAxis)
        {
            continue;
        }
        const Vec3 side = reference.axes.col(k);
        const Real centre = side.dot(reference.centre);
        const auto sideId = static_cast<std::uint32_t>(100 + 2 * k);
        clip(polygon, side, centre + reference.half[k], sideId, clipped);
        clip(clipped, -side, -centre + reference.half[k], sideId + 1, polygon);
    }

    const Real faceOffset = normal.dot(reference.centre) + reference.half[referenceAxis];
    // the points lie on the incident box; which box that is and its reference face tell them apart
    // from those of the other box's faces
    const SampleOf sample = sign > 0.0 ? SampleOf::A : SampleOf::B;
    const std::uint32_t referenceFace = 200 + 2 * static_cast<std::uint32_t>(referenceAxis) + (sign > 0.0 ? 10 : 0) +
                                        (normal.dot(reference.axes.col(referenceAxis)) > 0.0 ? 1 : 0);
    for (std::size_t i = 0; i < polygon.size; ++i)
    {
        const Vec3& p = polygon.corners[i];
        const Real phi = normal.dot(p) - faceOffset;
        if (phi < threshold)
        {
            out.push_back({p, sign * normal, phi, combineFeatures(referenceFace, polygon.features[i]), sample});
        }
    }
}

// Closest points of the segments p + s d1 and q + t d2, s, t in [-1, 1] scaled by the half lengths.
void edgeContact(const OrientedBox& a, int edgeA, const OrientedBox& b, int edgeB, const Vec3& normal, Real phi,
                 std::vector<ContactPoint>& out)
{
    // the edge of A furthest toward B (against the normal) and the edge of B furthest toward A
    Vec3 pointA = a.centre;
    Vec3 pointB = b.centre;
    for (int k = 0; k < 3; ++k)
    {
        if (k != edgeA)
        {
            pointA -= (a.axes.col(k).dot(normal) > 0.0 ? 1.0 : -1.0) * a.half[k] * a.axes.col(k);
        }
        if (k != edgeB)
        {
            pointB += (b.axes.col(k).dot(normal) > 0.0 ? 1.0 : -1.0) * b.half[k] * b.axes.col(k);
        }
    }
    const Vec3 d1 = a.axes.col(edgeA);
    const Vec3 d2 = b.axes.col(edgeB);
    const Vec3 r = pointA - pointB;
    const Real c = d1.dot(d2);
    const Real denominator = 1.0 - c * c;
    Real s = 0.0;
    Real t = 0.0;
    if (denominator > 1e-12)
    {
        s = (c * d2.dot(r) - d1.dot(r)) / denominator;
        s = std::clamp(s, -a.half[edgeA], a.half[edgeA]);
    }
    t = std::clamp(d2.dot(r + s * d1), -b.half[edgeB], b.half[edgeB]);
    s = std::clamp(d1.dot(pointB + t * d2 - pointA), -a.half[edgeA], a.half[edgeA]);
    const Vec3 onA = pointA + s * d1;
    const Vec3 onB = pointB + t * d2;
    out.push_back({0.5 * (onA + onB), normal, phi,
                   300 + 3 * static_cast<std::uint32_t>(edgeA) + static_cast<std::uint32_t>(edgeB), SampleOf::Between});
}

} // namespace

void collideBoxBox(const Box& boxA, const Pose& poseA, const Box& boxB, const Pose& poseB, Real threshold,
                   std::vector<ContactPoint>& out)
{
    const OrientedBox a{poseA.position, poseA.rotation, boxA.halfExtents};
    const OrientedBox b{poseB.position, poseB.rotation, boxB.halfExtents};
    const Vec3 between = a.centre - b.centre; // from B toward A
    const Real scale = std::max(a.half.maxCoeff(), b.half.maxCoeff());

    // Every separation below is |d . L| - r_A(L) - r_B(L) for a candidate axis L, r the box's half
    // extent along it, written with the axes of B in A's frame, C_ij = a_i . b_j, and the centres'
    // offset in either frame, so that the 15 axes cost one 3 x 3 product instead of 15 x 7 dot
    // products
    const Mat3 c = a.axes.transpose() * b.axes;
    const Mat3 absC = c.cwiseAbs();
    const Vec3 offsetA = a.axes.transpose() * (b.centre - a.centre);
    const Vec3 offsetB = b.axes.transpose() * (b.centre - a.centre);

    // face axes: least penetration (largest separation) wins; A's faces win ties so the choice
    // does not flicker between equal faces from one step to the next
    Real bestFace = -std::numeric_limits<Real>::infinity();
    int faceAxis = -1;
    bool faceOfA = true;
    for (int k = 0; k < 3; ++k)
    {
        const Real s = std::abs(offsetA[k]) - a.half[k] - absC.row(k).dot(b.half);
        if (s > bestFace + 1e-9 * scale)
        {
            bestFace = s;
            faceAxis = k;
        }
    }
    for (int k = 0; k < 3; ++k)
    {
        const Real s = std::abs(offsetB[k]) - absC.col(k).dot(a.half) - b.half[k];
        if (s > bestFace + 1e-9 * scale)
        {
            bestFace = s;
            faceAxis = k;
            faceOfA = false;
        }
    }
    if (bestFace >= threshold)
    {
        return;
    }

    // edge axes a_i x b_j: only when clearly better than every face, since a face gives a whole patch
    Real bestEdge = -std::numeric_limits<Real>::infinity();
    int edgeA = -1;
    int edgeB = -1;
    for (int i = 0; i < 3; ++i)
    {
        const int i1 = (i + 1) % 3;
        const int i2 = (i + 2) % 3;
        for (int j = 0; j < 3; ++j)
        {
            // |a_i x b_j|, from the components of b_j across a_i (no cancellation when nearly parallel)
            const Real length = std::sqrt(c(i1, j) * c(i1, j) + c(i2, j) * c(i2, j));
            if (length < 1e-6)
            {
                continue; // parallel edges: the face axes cover them
            }
            const int j1 = (j + 1) % 3;
            const int j2 = (j + 2) % 3;
            const Real distance = std::abs(offsetA[i2] * c(i1, j) - offsetA[i1] * c(i2, j));
            const Real radiusA = a.half[i1] * absC(i2, j) + a.half[i2] * absC(i1, j);
            const Real radiusB = b.half[j1] * absC(i, j2) + b.half[j2] * absC(i, j1);
            const Real s = (distance - radiusA - radiusB) / length;
            if (s >= threshold)
            {
                return; // a separating axis: no contact
            }
            if (s > bestEdge)
            {
                bestEdge = s;
                edgeA = i;
                edgeB = j;
            }
        }
    }
    if (edgeA >= 0 && bestEdge > bestFace + 1e-6 * scale)
    {
        const Vec3 axis = a.axes.col(edgeA).cross(b.axes.col(edgeB)).normalized();
        const Vec3 edgeNormal = axis.dot(between) >= 0.0 ? axis : Vec3(-axis);
        edgeContact(a, edgeA, b, edgeB, edgeNormal, bestEdge, out);
        return;
    }

    if (faceOfA)
    {
        // reference face on A, pointing at B; the pair's normal points the other way
        const Vec3 axis = a.axes.col(faceAxis);
        const Vec3 normal = axis.dot(-between) >= 0.0 ? axis : Vec3(-axis);
        faceContact(a, faceAxis, normal, b, -1.0, threshold, out);
    }
    else
    {
        const Vec3 axis = b.axes.col(faceAxis);
        const Vec3 normal = axis.dot(between) >= 0.0 ? axis : Vec3(-axis);
        faceContact(b, faceAxis, normal, a, 1.0, threshold, out);
    }
}

} // namespace impulse
