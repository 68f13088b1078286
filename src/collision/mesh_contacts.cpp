// SPDX-License-Identifier: MIT
// Sample points of a mesh body are its vertices; a vertex inside (or within the threshold of) the
// other body is a contact with phi and normal from that body's signed distance. Vertices alone miss
// an edge lying across another edge or a face, so each edge that may pass through the other body
// (phi_a + phi_b <= |edge|, phi being 1-Lipschitz) is intersected with it, and the middle of each
// passage becomes a sample point as well.
#include "collision/mesh_contacts.hpp"

#include "collision/narrow_phase.hpp"
#include "geometry/box_queries.hpp"
#include "geometry/mesh_queries.hpp"
#include "geometry/signed_distance.hpp"
#include "geometry/triangle_bvh.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>

namespace impulse
{
namespace
{

constexpr Real kInfinity = std::numeric_limits<Real>::infinity();

// The other body of a pair, seen from the sample points: its signed distance in its own frame,
// and where a segment passes through it.
struct Target
{
    const Pose& pose;
    Vec3 lower;
    Vec3 upper;

    virtual ~Target() = default;
    virtual MeshDistance distance(const Vec3& local, Real threshold) const = 0;
    /// The passages of the segment from a to b through the target, as parameters (enter, leave) in
    /// [0, 1]: a passage from an end inside starts at exactly 0 or ends at exactly 1.
    virtual void crossings(const Vec3& a, const Vec3& b, std::vector<Real>& enterLeave) const = 0;
    /// A lower bound of phi that is cheap to know.
    virtual Real coarseLowerBound(const Vec3& local) const = 0;
    /// How far above phi a value distance() returns as not exact may lie.
    virtual Real gridError() const { return 0.0; }

    Target(const Pose& p, const Vec3& lo, const Vec3& hi) : pose(p), lower(lo), upper(hi) {}
};

struct MeshTarget final : Target
{
    const MeshQueries& mesh;
    MeshQueryScratch& scratch;
    MeshTarget(const MeshQueries& m, const Pose& p, MeshQueryScratch& s)
        : Target(p, m.lower(), m.upper()), mesh(m), scratch(s)
    {
    }
    MeshDistance distance(const Vec3& local, Real threshold) const override
    {
        return mesh.distance(local, threshold, scratch);
    }
    void crossings(const Vec3& a, const Vec3& b, std::vector<Real>& enterLeave) const override
    {
        mesh.segmentCrossings(a, b, enterLeave, scratch);
    }
    Real coarseLowerBound(const Vec3& local) const override { return mesh.coarseLowerBound(local); }
    Real gridError() const override { return mesh.gridError(); }
};

// A solid with an analytic signed distance: exact everywhere, so phi is its own lower bound.
struct AnalyticTarget : Target
{
    using Target::Target;
    virtual DistanceSample analytic(const Vec3& local) const = 0;
    MeshDistance distance(const Vec3& local, Real) const final
    {
        const DistanceSample sample = analytic(local);
        return {sample.phi, sample.gradient, true};
    }
    Real coarseLowerBound(const Vec3& local) const final { return analytic(local).phi; }
};

struct BoxTarget final : AnalyticTarget
{
    Vec3 halfExtents;
    BoxTarget(const Box& box, const Pose& p)
        : AnalyticTarget(p, -box.halfExtents, box.halfExtents), halfExtents(box.halfExtents)
    {
    }
    DistanceSample analytic(const Vec3& local) const override { return boxDistance(halfExtents, local); }
    void crossings(const Vec3& a, const Vec3& b, std::vector<Real>& enterLeave) const override
    {
        // the segment's passage through the box (from 0 or to 1 where an end is inside)
        enterLeave.clear();
        Real enter = 0.0;
        Real leave = 0.0;
        if (clipSegmentToBox(a, b - a, -halfExtents, halfExtents, enter, leave) && enter < leave)
        {
            enterLeave = {std::max(enter, Real(0.0)), std::min(leave, Real(1.0))};
        }
    }
};

struct CapsuleTarget final : AnalyticTarget
{
    Capsule capsule;
    CapsuleTarget(const Capsule& c, const Pose& p)
        : AnalyticTarget(p, -Vec3(c.radius, c.radius, c.halfLength + c.radius),
                         Vec3(c.radius, c.radius, c.halfLength + c.radius)),
          capsule(c)
    {
    }
    DistanceSample analytic(const Vec3& local) const override { return capsuleDistance(capsule, local); }
    void crossings(const Vec3& a, const Vec3& b, std::vector<Real>& enterLeave) const override
    {
        // phi along a line is convex: one passage at most, around its least value
        enterLeave.clear();
        const auto phi = [&](Real t) { return analytic(a + t * (b - a)).phi; };
        const auto root = [&](Real outside, Real inside)
        {
            for (int i = 0; i < 60; ++i)
            {
                const Real middle = 0.5 * (outside + inside);
                if (phi(middle) > 0.0)
                {
                    outside = middle;
                }
                else
                {
                    inside = middle;
                }
            }
            return 0.5 * (outside + inside);
        };
        const bool aInside = phi(0.0) <= 0.0;
        const bool bInside = phi(1.0) <= 0.0;
        if (aInside || bInside)
        {
            enterLeave = {aInside ? 0.0 : root(0.0, 1.0), bInside ? 1.0 : root(1.0, 0.0)};
            return;
        }
        Real lo = 0.0;
        Real hi = 1.0;
        for (int i = 0; i < 60; ++i)
        {
            const Real m1 = lo + (hi - lo) / 3.0;
            const Real m2 = hi - (hi - lo) / 3.0;
            if (phi(m1) < phi(m2))
            {
                hi = m2;
            }
            else
            {
                lo = m1;
            }
        }
        const Real deepest = 0.5 * (lo + hi);
        if (!(phi(deepest) < 0.0))
        {
            return;
        }
        enterLeave = {root(0.0, deepest), root(1.0, deepest)};
    }
};

// Which way the normal of a point found inside `target` points: away from the target when the
// points belong to A (target is B), towards it when they belong to B.
enum class Side
{
    PointsOfA,
    PointsOfB,
};

// A vertex is named by its index, an edge's passage by the edge's index and the passage's rank
// along it; a bit for the side keeps the points of the two bodies apart.
std::uint32_t vertexFeature(std::size_t vertex, Side side)
{
    return static_cast<std::uint32_t>(vertex) | (side == Side::PointsOfB ? 0x80000000u : 0u);
}
std::uint32_t passageFeature(std::size_t edge, std::size_t passage, Side side)
{
    return static_cast<std::uint32_t>(4 * edge + std::min<std::size_t>(passage, 3)) | 0x40000000u |
           (side == Side::PointsOfB ? 0x80000000u : 0u);
}

void addContact(const Vec3& pointWorld, const Target& target, const MeshDistance& d, Side side, std::uint32_t feature,
                std::vector<ContactPoint>& out)
{
    const Vec3 normal = target.pose.rotation * d.gradient;
    out.push_back({pointWorld, side == Side::PointsOfA ? normal : Vec3(-normal), d.phi, feature,
                   side == Side::PointsOfA ? SampleOf::A : SampleOf::B});
}

// What the edge test knows of each vertex's phi against the target, gathered by verticesAgainst for
// edgesThrough: `value` is a lower bound of phi, -infinity for a sample point inside the target. A bound that costs
// something (for a vertex outside the target's box, the target's coarse lower bound; for a vertex in a
// cluster far from the target, even its distance to the box) waits until an edge needs it. An edge
// the bounds do not cover is tested for crossings; one they could have covered has none, so weaker
// bounds cost crossing tests, never points.
struct VertexBounds
{
    enum class State : std::uint8_t
    {
        Final,     ///< `value` is all there is to know
        Unvisited, ///< verticesAgainst has yet to look at it
        Far,       ///< value = reach, below its distance to the target's box
        Outside,   ///< value = its distance to the target's box; the coarse lower bound may say more
    };
    std::vector<Real> value;
    std::vector<State> state;
    std::vector<Real> depth;          ///< a sample point inside the target (value -infinity): its phi
    std::vector<Vec3> local;          ///< Outside: the vertex in the target's frame
    Mat3 rotation = Mat3::Identity(); ///< body frame of the vertices -> target frame
    Vec3 shift = Vec3::Zero();

    // The better bound of vertex v, computed once when an edge asks for it.
    Real tighter(const std::vector<Vec3>& vertices, std::size_t v, const Target& target)
    {
        switch (state[v])
        {
        case State::Far:
            value[v] = std::sqrt(squaredDistanceToBox(rotation * vertices[v] + shift, target.lower, target.upper));
            break;
        case State::Outside:
            value[v] = std::max(value[v], target.coarseLowerBound(local[v]));
            break;
        default:
            break;
        }
        state[v] = State::Final;
        return value[v];
    }
};

// A bound on how much `rotation` can lengthen a vector, |rotation x| <= stretch |x|: a rotation up to
// round-off, bounded all the same so that far-away tests built on it stay sound.
Real rotationStretch(const Mat3& rotation)
{
    return std::sqrt(1.0 + (rotation.transpose() * rotation - Mat3::Identity()).norm()) * (1.0 + 1e-9);
}

// Marks Far the vertices of every cluster that lies, with a wide margin for round-off, farther than
// `reach` from the target's box, so that each of its vertices is: neither a sample point nor in need
// of a distance query, its bound its distance to the box, and that at least `reach`.
void markFarClusters(const MeshQueries& mesh, const Target& target, Real reach, VertexBounds& bounds)
{
    using State = VertexBounds::State;
    const Real stretch = rotationStretch(bounds.rotation);
    // far above the round-off of the vertices' and the centres' transforms and box distances
    // (a few units in the last place of these magnitudes)
    const Real slack = 1e-9 * (bounds.shift.norm() + mesh.boundingRadius() + target.lower.cwiseAbs().maxCoeff() +
                               target.upper.cwiseAbs().maxCoeff() + reach);
    const auto beyondReach = [&](const Vec3& centre, Real radius)
    {
        const Real distance =
            std::sqrt(squaredDistanceToBox(bounds.rotation * centre + bounds.shift, target.lower, target.upper));
        return distance - stretch * radius > reach + slack + 1e-9 * distance;
    };
    const std::vector<std::uint32_t>& members = mesh.vertexClusterMembers();
    if (beyondReach(Vec3::Zero(), mesh.boundingRadius()))
    {
        std::fill(bounds.state.begin(), bounds.state.end(), State::Far);
        std::fill(bounds.value.begin(), bounds.value.end(), reach);
        return;
    }
    for (const MeshQueries::VertexCluster& cluster : mesh.vertexClusters())
    {
        const bool far = beyondReach(cluster.centre, cluster.radius);
        for (std::uint32_t i = cluster.first; i < cluster.first + cluster.count; ++i)
        {
            bounds.state[members[i]] = far ? State::Far : State::Unvisited;
            bounds.value[members[i]] = reach;
        }
    }
}

// The vertices (body frame of their body at `pose`) against the target. Fills `bounds` for the
// edge test: -infinity for the sample points inside the target, else a lower bound of phi that is
// exact below `edgeReach` (the longest edge), so that only edges truly near the target are cast.
// `mesh`, when the vertices are a mesh's, lets whole clusters of vertices far from the target pass.
void verticesAgainst(const std::vector<Vec3>& vertices, const MeshQueries* mesh, const Pose& pose, const Target& target,
                     Real threshold, Real edgeReach, Side side, VertexBounds& bounds, std::vector<ContactPoint>& out)
{
    using State = VertexBounds::State;
    bounds.value.resize(vertices.size());
    bounds.state.resize(vertices.size());
    bounds.depth.resize(vertices.size());
    bounds.local.resize(vertices.size());
    // body frame of the vertices -> target frame in one affine map
    bounds.rotation = target.pose.rotation.transpose() * pose.rotation;
    bounds.shift = target.pose.rotation.transpose() * (pose.position - target.pose.position);
    const Mat3& rotation = bounds.rotation;
    const Vec3& shift = bounds.shift;
    if (mesh != nullptr)
    {
        markFarClusters(*mesh, target, std::max({threshold, edgeReach, Real(0.0)}), bounds);
    }
    else
    {
        std::fill(bounds.state.begin(), bounds.state.end(), State::Unvisited);
    }
    for (std::size_t v = 0; v < vertices.size(); ++v)
    {
        if (bounds.state[v] != State::Unvisited)
        {
            continue;
        }
        const Vec3 local = rotation * vertices[v] + shift;
        const Real outside = std::sqrt(squaredDistanceToBox(local, target.lower, target.upper));
        if (outside > 0.0 && outside >= threshold)
        {
            // phi >= the distance to the target's bounding box: enough for any edge beyond the reach
            bounds.value[v] = outside;
            if (outside >= edgeReach)
            {
                bounds.state[v] = State::Final;
            }
            else
            {
                bounds.state[v] = State::Outside;
                bounds.local[v] = local;
            }
            continue;
        }
        const MeshDistance d = target.distance(local, threshold);
        if (d.phi < threshold)
        {
            addContact(pose.toWorld(vertices[v]), target, d, side, vertexFeature(v, side), out);
            // inside, the vertex stands for its edges' crossings; outside but within the threshold it
            // does not, and its exact distance is its bound
            bounds.value[v] = d.phi < 0.0 ? -kInfinity : d.phi;
            bounds.depth[v] = d.phi;
        }
        else
        {
            // not a sample point, so phi >= threshold; a grid value is at most its error above phi
            // here, within the target's box and so within its grid
            bounds.value[v] = std::max(threshold, d.exact ? d.phi : d.phi - target.gridError());
        }
        bounds.state[v] = State::Final;
    }
}

// Edges that pass through the target: the middle of each passage is a sample point.
template <class Edges>
void edgesThrough(const std::vector<Vec3>& vertices, const Edges& edges, const Target& target, VertexBounds& bounds,
                  Side side, std::vector<Real>& enterLeave, std::vector<ContactPoint>& out)
{
    const Mat3& rotation = bounds.rotation; // as verticesAgainst computed it for this pose and target
    const Vec3& shift = bounds.shift;
    for (std::size_t e = 0; e < std::size(edges); ++e)
    {
        const auto& edge = edges[e];
        const Vec3& a = vertices[edge[0]];
        const Vec3& b = vertices[edge[1]];
        const Real reach = bounds.value[edge[0]] + bounds.value[edge[1]];
        if (reach > 0.0 && reach * reach > (a - b).squaredNorm())
        {
            continue; // phi is 1-Lipschitz: balls of radius phi about the ends cover the edge
        }
        if (bounds.state[edge[0]] != VertexBounds::State::Final || bounds.state[edge[1]] != VertexBounds::State::Final)
        {
            // the bounds that wait are worked out only for an edge the cheap ones leave open; a
            // tree search for phi itself would cost about what the crossing test costs
            const Real tighter = bounds.tighter(vertices, edge[0], target) + bounds.tighter(vertices, edge[1], target);
            if (tighter > 0.0 && tighter * tighter > (a - b).squaredNorm())
            {
                continue;
            }
        }
        const Vec3 localA = rotation * a + shift;
        const Vec3 localB = rotation * b + shift;
        // an end inside is a sample point and stands for the passage from it only as deep as it is:
        // the edge may run on deeper (a chord under a curved or cornered surface) before it leaves
        const bool insideA = bounds.value[edge[0]] == -kInfinity;
        const bool insideB = bounds.value[edge[1]] == -kInfinity;
        target.crossings(localA, localB, enterLeave);
        if (enterLeave.empty() && insideA && insideB)
        {
            enterLeave = {0.0, 1.0}; // no crossing between two ends inside: the edge lies inside
        }
        for (std::size_t k = 0; k + 1 < enterLeave.size(); k += 2)
        {
            const Real t = 0.5 * (enterLeave[k] + enterLeave[k + 1]);
            const Vec3 local = localA + t * (localB - localA);
            const MeshDistance d = target.distance(local, 0.0);
            Real standIn = 0.0; // the depth of the inside end the passage starts or ends at
            if (insideA && enterLeave[k] == 0.0)
            {
                standIn = std::min(standIn, bounds.depth[edge[0]]);
            }
            if (insideB && enterLeave[k + 1] == 1.0)
            {
                standIn = std::min(standIn, bounds.depth[edge[1]]);
            }
            if (d.phi < standIn)
            {
                addContact(target.pose.toWorld(local), target, d, side, passageFeature(e, k / 2, side), out);
            }
        }
    }
}

constexpr std::array<std::array<std::uint32_t, 2>, 12> kBoxEdges = {{
    {0, 1},
    {2, 3},
    {4, 5},
    {6, 7}, // along x
    {0, 2},
    {1, 3},
    {4, 6},
    {5, 7}, // along y
    {0, 4},
    {1, 5},
    {2, 6},
    {3, 7}, // along z
}};

std::vector<Vec3> boxCornersLocal(const Box& box)
{
    std::vector<Vec3> corners(8);
    for (std::size_t i = 0; i < 8; ++i)
    {
        corners[i] = boxCorner(box.halfExtents, i);
    }
    return corners;
}

bool farApart(const Pose& poseA, Real radiusA, const Pose& poseB, Real radiusB, Real threshold)
{
    return (poseA.position - poseB.position).norm() - radiusA - radiusB >= threshold;
}

// Whether the bounding boxes of two bodies' points (body frame [lower, upper] each) are farther
// apart than the threshold: then no point of either is within it of the other, and no edge of one
// reaches into the other.
bool boxesApart(const Pose& poseA, const Vec3& lowerA, const Vec3& upperA, const Pose& poseB, const Vec3& lowerB,
                const Vec3& upperB, Real threshold)
{
    return orientedBoxesApart(poseA.toWorld(0.5 * (lowerA + upperA)), poseA.rotation, 0.5 * (upperA - lowerA),
                              poseB.toWorld(0.5 * (lowerB + upperB)), poseB.rotation, 0.5 * (upperB - lowerB),
                              std::max(threshold, Real(0.0)));
}

// The latest mesh-mesh answers of one scratch (one thread). Within a step the passes ask again about
// pairs that no impulse has moved since they last asked: about half of all mesh-mesh queries in a
// forming pile. The query is a pure function of the two meshes, their poses and the threshold, so a
// repeat, recognised by those inputs bit for bit, is answered from here with exactly what it would
// compute.
class MeshPairMemo
{
  public:
    struct Key
    {
        std::array<const MeshGeometry*, 2> meshes{};
        std::array<Real, 33> numbers{}; // both poses (position, quaternion, rotation), threshold
    };

    static Key keyOf(const MeshGeometry& a, const Pose& poseA, const MeshGeometry& b, const Pose& poseB, Real threshold)
    {
        Key key;
        key.meshes = {&a, &b};
        std::size_t n = 0;
        for (const Pose* pose : {&poseA, &poseB})
        {
            for (int i = 0; i < 3; ++i)
            {
                key.numbers[n++] = pose->position[i];
            }
            for (const Real q :
                 {pose->orientation.w(), pose->orientation.x(), pose->orientation.y(), pose->orientation.z()})
            {
                key.numbers[n++] = q;
            }
            for (int i = 0; i < 9; ++i)
            {
                key.numbers[n++] = pose->rotation.data()[i];
            }
        }
        key.numbers[n] = threshold;
        return key;
    }

    /// The stored answer to `key`, or null.
    const std::vector<ContactPoint>* find(const Key& key) const
    {
        if (m_slots.empty())
        {
            return nullptr;
        }
        const Slot& slot = m_slots[slotOf(key)];
        return slot.used && sameBits(slot.key, key) ? &slot.points : nullptr;
    }

    void store(const Key& key, std::vector<ContactPoint>::const_iterator first,
               std::vector<ContactPoint>::const_iterator last)
    {
        if (m_slots.empty())
        {
            m_slots.resize(kSlots); // at the first store: a scratch that never meets two meshes stays small
        }
        Slot& slot = m_slots[slotOf(key)];
        slot.used = true;
        slot.key = key;
        slot.points.assign(first, last);
    }

  private:
    static constexpr std::size_t kSlots = 4096; // several sweeps' worth of pairs in a pile of a thousand

    struct Slot
    {
        bool used = false;
        Key key;
        std::vector<ContactPoint> points;
    };

    static bool sameBits(const Key& a, const Key& b)
    {
        return a.meshes == b.meshes && std::memcmp(a.numbers.data(), b.numbers.data(), sizeof(a.numbers)) == 0;
    }

    static std::size_t slotOf(const Key& key)
    {
        std::uint64_t hash = 14695981039346656037ull; // FNV-1a over the key's words
        const auto mix = [&](std::uint64_t word)
        {
            hash ^= word;
            hash *= 1099511628211ull;
        };
        for (const MeshGeometry* mesh : key.meshes)
        {
            mix(reinterpret_cast<std::uintptr_t>(mesh));
        }
        for (const Real x : key.numbers)
        {
            std::uint64_t word = 0;
            std::memcpy(&word, &x, sizeof(word));
            mix(word);
        }
        return static_cast<std::size_t>(hash ^ (hash >> 32)) % kSlots;
    }

    std::vector<Slot> m_slots; ///< kSlots of them once anything is stored
};

} // namespace

// What the mesh rows reuse from call to call: every buffer is filled anew before it is read, and the
// memo answers only what it would compute, so its contents never change an answer.
struct MeshContactScratch
{
    std::array<VertexBounds, 2> bounds; ///< of the points of either body of the pair
    std::vector<Real> enterLeave;       ///< an edge's passages through the other body
    std::vector<std::uint32_t> near;    ///< triangles a ball touches
    MeshQueryScratch queries;
    MeshPairMemo memo;
};

// NarrowPhaseScratch's members are defined here, where its mesh part is a complete type.
NarrowPhaseScratch::NarrowPhaseScratch() = default;
NarrowPhaseScratch::~NarrowPhaseScratch() = default;
NarrowPhaseScratch::NarrowPhaseScratch(NarrowPhaseScratch&&) noexcept = default;
NarrowPhaseScratch& NarrowPhaseScratch::operator=(NarrowPhaseScratch&&) noexcept = default;

MeshContactScratch& NarrowPhaseScratch::mesh()
{
    if (!m_mesh)
    {
        m_mesh = std::make_unique<MeshContactScratch>();
    }
    return *m_mesh;
}

void collideMeshPlane(const Mesh& a, const Pose& poseA, const Plane& b, const Pose& poseB, Real threshold,
                      std::vector<ContactPoint>& out)
{
    // a plane is flat: an edge or face can only cross it if a vertex does
    const Vec3 normal = poseB.rotation * b.normal;
    const Real offset = b.offset + normal.dot(poseB.position);
    if (normal.dot(poseA.position) - offset - a.geometry->boundingRadius() >= threshold)
    {
        return;
    }
    const std::vector<Vec3>& vertices = a.geometry->vertices();
    for (std::size_t v = 0; v < vertices.size(); ++v)
    {
        const Vec3 p = poseA.toWorld(vertices[v]);
        const Real phi = normal.dot(p) - offset;
        if (phi < threshold)
        {
            out.push_back({p, normal, phi, vertexFeature(v, Side::PointsOfA), SampleOf::A});
        }
    }
}

void collideSphereMesh(const Sphere& a, const Pose& poseA, const Mesh& b, const Pose& poseB, Real threshold,
                       std::vector<ContactPoint>& out, MeshContactScratch& scratch)
{
    const MeshQueries& mesh = MeshQueries::of(*b.geometry);
    if (farApart(poseA, a.radius, poseB, mesh.boundingRadius(), threshold))
    {
        return;
    }
    // the sphere's distance is its centre's distance less the radius, so the centre's closest point
    // on the mesh is the deepest contact
    const Vec3 centre = poseB.toLocal(poseA.position);
    const MeshDistance nearest = mesh.distance(centre, kInfinity, scratch.queries);
    if (nearest.phi - a.radius >= threshold)
    {
        return;
    }
    const auto add = [&](const Vec3& gradient, Real centreDistance, std::uint32_t feature)
    {
        const Real phi = centreDistance - a.radius;
        const Vec3 normal = poseB.rotation * gradient;
        out.push_back({poseA.position - normal * (a.radius + 0.5 * phi), normal, phi, feature, SampleOf::Between});
    };
    add(nearest.gradient, nearest.phi, 0xFFFFFFFFu);
    if (!std::isfinite(threshold))
    {
        return; // asked only for the least distance
    }
    // other faces the sphere touches at once (a ball in a groove): each face whose closest point is
    // inside it, facing a way no point found so far faces
    const TriangleBvh& bvh = mesh.bvh();
    std::vector<std::uint32_t>& near = scratch.near;
    bvh.trianglesNear(centre, a.radius + threshold, near);
    const std::size_t first = out.size() - 1;
    for (const std::uint32_t t : near)
    {
        const auto& tri = bvh.triangle(t);
        const TrianglePoint closest =
            closestPointOnTriangle(centre, bvh.vertex(tri[0]), bvh.vertex(tri[1]), bvh.vertex(tri[2]));
        const Vec3& faceNormal = bvh.faceNormal(t);
        const Real height = (centre - closest.point).dot(faceNormal);
        if (closest.feature != TriangleFeature::Face || height <= 0.0)
        {
            continue;
        }
        const Vec3 normal = poseB.rotation * faceNormal;
        const bool newDirection = std::none_of(out.begin() + static_cast<std::ptrdiff_t>(first), out.end(),
                                               [&](const ContactPoint& c) { return c.normal.dot(normal) > 0.985; });
        if (newDirection)
        {
            add(faceNormal, height, t);
        }
    }
}

void collideBoxMesh(const Box& a, const Pose& poseA, const Mesh& b, const Pose& poseB, Real threshold,
                    std::vector<ContactPoint>& out, MeshContactScratch& scratch)
{
    const MeshQueries& mesh = MeshQueries::of(*b.geometry);
    if (farApart(poseA, a.halfExtents.norm(), poseB, mesh.boundingRadius(), threshold) ||
        boxesApart(poseA, -a.halfExtents, a.halfExtents, poseB, mesh.lower(), mesh.upper(), threshold))
    {
        return;
    }
    VertexBounds& cornerBounds = scratch.bounds[0];
    VertexBounds& vertexBounds = scratch.bounds[1];
    const std::vector<Vec3> corners = boxCornersLocal(a);
    const MeshTarget meshTarget(mesh, poseB, scratch.queries);
    const BoxTarget boxTarget(a, poseA);
    verticesAgainst(corners, nullptr, poseA, meshTarget, threshold, 2.0 * a.halfExtents.maxCoeff(), Side::PointsOfA,
                    cornerBounds, out);
    verticesAgainst(mesh.vertices(), &mesh, poseB, boxTarget, threshold, mesh.longestFeatureEdge(), Side::PointsOfB,
                    vertexBounds, out);
    edgesThrough(corners, kBoxEdges, meshTarget, cornerBounds, Side::PointsOfA, scratch.enterLeave, out);
    edgesThrough(mesh.vertices(), mesh.featureEdges(), boxTarget, vertexBounds, Side::PointsOfB, scratch.enterLeave,
                 out);
}

void collideCapsuleMesh(const Capsule& a, const Pose& poseA, const Mesh& b, const Pose& poseB, Real threshold,
                        std::vector<ContactPoint>& out, MeshContactScratch& scratch)
{
    const MeshQueries& mesh = MeshQueries::of(*b.geometry);
    if (farApart(poseA, a.halfLength + a.radius, poseB, mesh.boundingRadius(), threshold))
    {
        return;
    }
    // the capsule is a ball swept along its axis: balls at least every half radius along it, each
    // against the mesh's distance, support it lying on a face; the mesh's vertices and sharp edges
    // against the capsule's distance catch corners and ridges pressing into its side
    const int samples = std::max(2, static_cast<int>(std::ceil(4.0 * a.halfLength / a.radius)) + 1);
    for (int k = 0; k < samples; ++k)
    {
        const Real along = a.halfLength * (2.0 * k / (samples - 1) - 1.0);
        const Vec3 centre = poseA.toWorld(Vec3(0.0, 0.0, along));
        const MeshDistance d = mesh.distance(poseB.toLocal(centre), threshold + a.radius, scratch.queries);
        const Real phi = d.phi - a.radius;
        if (phi < threshold)
        {
            const Vec3 normal = poseB.rotation * d.gradient;
            out.push_back({centre - normal * (a.radius + 0.5 * phi), normal, phi, static_cast<std::uint32_t>(k),
                           SampleOf::Between});
        }
    }
    VertexBounds& vertexBounds = scratch.bounds[1];
    const CapsuleTarget capsuleTarget(a, poseA);
    verticesAgainst(mesh.vertices(), &mesh, poseB, capsuleTarget, threshold, mesh.longestFeatureEdge(), Side::PointsOfB,
                    vertexBounds, out);
    edgesThrough(mesh.vertices(), mesh.featureEdges(), capsuleTarget, vertexBounds, Side::PointsOfB, scratch.enterLeave,
                 out);
}

namespace
{

// The vertex-and-edge query of two meshes within reach of each other, which collideMeshMesh answers
// from memory when it can.
void computeMeshMesh(const Mesh& a, const Pose& poseA, const Mesh& b, const Pose& poseB, Real threshold,
                     std::vector<ContactPoint>& out, MeshContactScratch& scratch)
{
    const MeshQueries& meshA = MeshQueries::of(*a.geometry);
    const MeshQueries& meshB = MeshQueries::of(*b.geometry);
    VertexBounds& boundsA = scratch.bounds[0];
    VertexBounds& boundsB = scratch.bounds[1];
    const MeshTarget targetA(meshA, poseA, scratch.queries);
    const MeshTarget targetB(meshB, poseB, scratch.queries);
    verticesAgainst(meshA.vertices(), &meshA, poseA, targetB, threshold, meshA.longestFeatureEdge(), Side::PointsOfA,
                    boundsA, out);
    verticesAgainst(meshB.vertices(), &meshB, poseB, targetA, threshold, meshB.longestFeatureEdge(), Side::PointsOfB,
                    boundsB, out);
    edgesThrough(meshA.vertices(), meshA.featureEdges(), targetB, boundsA, Side::PointsOfA, scratch.enterLeave, out);
    edgesThrough(meshB.vertices(), meshB.featureEdges(), targetA, boundsB, Side::PointsOfB, scratch.enterLeave, out);
}

// The least of phi over the vertices of `points` (at `pose`) against `target`, or `least` if none is
// lower. Each phi that is computed is what verticesAgainst computes with an infinite threshold; a
// vertex is passed over when a lower bound of that phi (its distance to the target's box, or the
// target's coarse lower bound) is above the least so far by more than round-off, so the result is
// the same.
Real leastOfVertices(const MeshQueries& points, const Pose& pose, const MeshQueries& target, const Pose& targetPose,
                     Real least, MeshQueryScratch& scratch)
{
    const Mat3 rotation = targetPose.rotation.transpose() * pose.rotation;
    const Vec3 shift = targetPose.rotation.transpose() * (pose.position - targetPose.position);
    // round-off of the transforms and of the bounds, far above a few units in the last place
    const Real slack = 1e-9 * (shift.norm() + points.boundingRadius() + target.boundingRadius() + target.cellSize());
    const Real stretch = rotationStretch(rotation);
    const std::vector<Vec3>& vertices = points.vertices();
    const std::vector<std::uint32_t>& members = points.vertexClusterMembers();
    // phi is at least the distance to the target's box, where that is positive: outside the box
    const auto aboveLeast = [&](Real outside) { return outside > 0.0 && outside > least + slack; };
    for (const MeshQueries::VertexCluster& cluster : points.vertexClusters())
    {
        const Vec3 centre = rotation * cluster.centre + shift;
        if (aboveLeast(std::sqrt(squaredDistanceToBox(centre, target.lower(), target.upper())) -
                       stretch * cluster.radius))
        {
            continue;
        }
        for (std::uint32_t i = cluster.first; i < cluster.first + cluster.count; ++i)
        {
            const Vec3 local = rotation * vertices[members[i]] + shift;
            if (aboveLeast(std::sqrt(squaredDistanceToBox(local, target.lower(), target.upper()))) ||
                target.coarseLowerBound(local) > least + slack)
            {
                continue;
            }
            least = std::min(least, target.distance(local, kInfinity, scratch).phi);
        }
    }
    return least;
}

} // namespace

Real leastMeshMeshDistance(const Mesh& a, const Pose& poseA, const Mesh& b, const Pose& poseB,
                           MeshContactScratch& scratch)
{
    const MeshQueries& meshA = MeshQueries::of(*a.geometry);
    const MeshQueries& meshB = MeshQueries::of(*b.geometry);
    const Real least = leastOfVertices(meshA, poseA, meshB, poseB, kInfinity, scratch.queries);
    return leastOfVertices(meshB, poseB, meshA, poseA, least, scratch.queries);
}

void collideMeshMesh(const Mesh& a, const Pose& poseA, const Mesh& b, const Pose& poseB, Real threshold,
                     std::vector<ContactPoint>& out, MeshContactScratch& scratch)
{
    // bodies too far apart for any point are told apart before any memory is spent on them
    if (farApart(poseA, a.geometry->boundingRadius(), poseB, b.geometry->boundingRadius(), threshold) ||
        boxesApart(poseA, a.geometry->lower(), a.geometry->upper(), poseB, b.geometry->lower(), b.geometry->upper(),
                   threshold))
    {
        return;
    }
    MeshPairMemo& memo = scratch.memo;
    const MeshPairMemo::Key key = MeshPairMemo::keyOf(*a.geometry, poseA, *b.geometry, poseB, threshold);
    if (const std::vector<ContactPoint>* known = memo.find(key))
    {
        out.insert(out.end(), known->begin(), known->end());
        return;
    }
    const std::size_t first = out.size();
    computeMeshMesh(a, poseA, b, poseB, threshold, out, scratch);
    memo.store(key, out.begin() + static_cast<std::ptrdiff_t>(first), out.end());
}

} // namespace impulse
