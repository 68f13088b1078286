// SPDX-License-Identifier: MIT
#include "collision/broad_phase.hpp"

#include <algorithm>

namespace impulse
{

Aabb shapeBounds(const Shape& shape, const Pose& pose)
{
    Vec3 extent = Vec3::Zero();
    if (const auto* sphere = std::get_if<Sphere>(&shape))
    {
        extent = Vec3::Constant(sphere->radius);
    }
    else if (const auto* box = std::get_if<Box>(&shape))
    {
        extent = pose.rotation.cwiseAbs() * box->halfExtents;
    }
    else if (const auto* capsule = std::get_if<Capsule>(&shape))
    {
        extent = pose.rotation.col(2).cwiseAbs() * capsule->halfLength + Vec3::Constant(capsule->radius);
    }
    else if (const auto* mesh = std::get_if<Mesh>(&shape))
    {
        // the body-frame box of the vertices, rotated: its centre need not be the centre of mass
        const Vec3 centre = pose.toWorld(0.5 * (mesh->geometry->lower() + mesh->geometry->upper()));
        const Vec3 half = pose.rotation.cwiseAbs() * (0.5 * (mesh->geometry->upper() - mesh->geometry->lower()));
        return {centre - half, centre + half};
    }
    return {pose.position - extent, pose.position + extent};
}

void BroadPhase::findPairs(const std::vector<RigidBody>& bodies, Real margin, std::vector<BodyPair>& pairs)
{
    pairs.clear();
    m_bounds.resize(bodies.size());
    m_order.clear();
    m_planes.clear();
    for (std::uint32_t i = 0; i < bodies.size(); ++i)
    {
        const RigidBody& body = bodies[i];
        if (std::holds_alternative<Plane>(body.shape))
        {
            m_planes.push_back(i);
            continue;
        }
        const Aabb now = shapeBounds(body.shape, body.pose());
        const Aabb next = shapeBounds(body.shape, body.predicted);
        const Real grow = body.dynamic ? margin : 0.0;
        m_bounds[i] = {now.lower.cwiseMin(next.lower).array() - grow, now.upper.cwiseMax(next.upper).array() + grow};
        m_order.push_back(i);
    }

    // sweep along x; ties broken by index so the result never depends on sort stability
    std::sort(m_order.begin(), m_order.end(),
              [&](std::uint32_t l, std::uint32_t r)
              {
                  const Real lx = m_bounds[l].lower.x();
                  const Real rx = m_bounds[r].lower.x();
                  return lx < rx || (lx == rx && l < r);
              });
    for (std::size_t k = 0; k < m_order.size(); ++k)
    {
        const std::uint32_t i = m_order[k];
        const Aabb& bi = m_bounds[i];
        for (std::size_t l = k + 1; l < m_order.size(); ++l)
        {
            const std::uint32_t j = m_order[l];
            const Aabb& bj = m_bounds[j];
            if (bj.lower.x() > bi.upper.x())
            {
                break;
            }
            if (!bodies[i].dynamic && !bodies[j].dynamic)
            {
                continue;
            }
            if ((bi.lower.array() <= bj.upper.array()).all() && (bj.lower.array() <= bi.upper.array()).all())
            {
                pairs.push_back({std::min(i, j), std::max(i, j)});
            }
        }
    }

    // planes: every dynamic body whose bounding sphere comes within the margin at either pose
    for (const std::uint32_t p : m_planes)
    {
        const Plane& plane = std::get<Plane>(bodies[p].shape);
        const Pose planePose = bodies[p].pose();
        const Vec3 normal = planePose.rotation * plane.normal;
        const Real offset = plane.offset + normal.dot(planePose.position);
        for (std::uint32_t i = 0; i < bodies.size(); ++i)
        {
            const RigidBody& body = bodies[i];
            if (!body.dynamic)
            {
                continue;
            }
            const Real nearest = std::min(normal.dot(body.position), normal.dot(body.predicted.position)) - offset;
            if (nearest - body.boundingRadius <= margin)
            {
                pairs.push_back({std::min(i, p), std::max(i, p)});
            }
        }
    }

    std::sort(pairs.begin(), pairs.end(),
              [](const BodyPair& l, const BodyPair& r) { return l.a < r.a || (l.a == r.a && l.b < r.b); });
}

} // namespace impulse
