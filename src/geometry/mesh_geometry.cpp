// SPDX-License-Identifier: MIT
// Preparing a solid mesh: welding, validation, mass properties and body frame; the hierarchy, grid,
// feature edges and vertex clusters are the queries' (mesh_queries.cpp).
#include "geometry/mesh_queries.hpp"
#include "geometry/signed_distance_grid.hpp"

#include <impulse/mesh.hpp>

#include <Eigen/Eigenvalues>

#include <algorithm>
#include <cmath>
#include <map>
#include <numeric>
#include <sstream>

namespace impulse
{
namespace
{

std::string describe(const Vec3& v)
{
    std::ostringstream text;
    text.precision(9);
    text << "(" << v.x() << ", " << v.y() << ", " << v.z() << ")";
    return text.str();
}

// Merges vertices with exactly equal coordinates and drops the ones no triangle uses. Triangle
// order is kept, so messages can name the file's triangle numbers.
TriangleMesh weld(const TriangleMesh& mesh)
{
    for (std::size_t v = 0; v < mesh.vertices.size(); ++v)
    {
        if (!mesh.vertices[v].allFinite())
        {
            throw MeshError("vertex " + std::to_string(v) + " has a coordinate that is not a finite number");
        }
    }
    for (std::size_t t = 0; t < mesh.triangles.size(); ++t)
    {
        for (const std::uint32_t v : mesh.triangles[t])
        {
            if (v >= mesh.vertices.size())
            {
                throw MeshError("triangle " + std::to_string(t) + " refers to vertex " + std::to_string(v) +
                                " but there are only " + std::to_string(mesh.vertices.size()) + " vertices");
            }
        }
    }
    std::vector<std::uint32_t> order(mesh.vertices.size());
    std::iota(order.begin(), order.end(), 0u);
    const auto lexicographic = [&](std::uint32_t a, std::uint32_t b)
    {
        const Vec3& p = mesh.vertices[a];
        const Vec3& q = mesh.vertices[b];
        return std::tie(p.x(), p.y(), p.z(), a) < std::tie(q.x(), q.y(), q.z(), b);
    };
    std::sort(order.begin(), order.end(), lexicographic);
    std::vector<std::uint32_t> canonical(mesh.vertices.size());
    for (std::size_t i = 0; i < order.size(); ++i)
    {
        const bool same = i > 0 && mesh.vertices[order[i]] == mesh.vertices[order[i - 1]];
        canonical[order[i]] = same ? canonical[order[i - 1]] : order[i];
    }
    std::vector<std::int64_t> compact(mesh.vertices.size(), -1);
    TriangleMesh welded;
    welded.triangles.reserve(mesh.triangles.size());
    for (const auto& triangle : mesh.triangles)
    {
        std::array<std::uint32_t, 3> renumbered{};
        for (int k = 0; k < 3; ++k)
        {
            const std::uint32_t v = canonical[triangle[k]];
            if (compact[v] < 0)
            {
                compact[v] = static_cast<std::int64_t>(welded.vertices.size());
                welded.vertices.push_back(mesh.vertices[v]);
            }
            renumbered[k] = static_cast<std::uint32_t>(compact[v]);
        }
        welded.triangles.push_back(renumbered);
    }
    return welded;
}

// A solid's surface: no degenerate or repeated triangles, every edge shared by exactly two
// triangles that run along it in opposite directions.
void validate(const TriangleMesh& mesh)
{
    if (mesh.triangles.size() < 4)
    {
        throw MeshError("a closed surface needs at least 4 triangles, this mesh has " +
                        std::to_string(mesh.triangles.size()));
    }
    Vec3 lower = mesh.vertices[0];
    Vec3 upper = lower;
    for (const Vec3& v : mesh.vertices)
    {
        lower = lower.cwiseMin(v);
        upper = upper.cwiseMax(v);
    }
    const Real scale = (upper - lower).norm();
    std::map<std::array<std::uint32_t, 3>, std::size_t> faces;
    std::map<std::pair<std::uint32_t, std::uint32_t>, std::size_t> directedEdges;
    for (std::size_t t = 0; t < mesh.triangles.size(); ++t)
    {
        const auto& tri = mesh.triangles[t];
        const std::string name = "triangle " + std::to_string(t);
        if (tri[0] == tri[1] || tri[1] == tri[2] || tri[2] == tri[0])
        {
            throw MeshError(name + " is degenerate: it uses the vertex " +
                            describe(mesh.vertices[tri[0] == tri[1] ? tri[0] : tri[2]]) + " twice");
        }
        const Vec3& a = mesh.vertices[tri[0]];
        const Real doubleArea = (mesh.vertices[tri[1]] - a).cross(mesh.vertices[tri[2]] - a).norm();
        if (!(doubleArea > 1e-12 * scale * scale))
        {
            throw MeshError(name + " is degenerate: its corners " + describe(a) + ", " +
                            describe(mesh.vertices[tri[1]]) + ", " + describe(mesh.vertices[tri[2]]) +
                            " are on one line");
        }
        std::array<std::uint32_t, 3> key = tri;
        std::sort(key.begin(), key.end());
        if (const auto [found, inserted] = faces.emplace(key, t); !inserted)
        {
            throw MeshError(name + " duplicates triangle " + std::to_string(found->second) + " (same three corners)");
        }
        for (int k = 0; k < 3; ++k)
        {
            const std::pair<std::uint32_t, std::uint32_t> edge{tri[k], tri[(k + 1) % 3]};
            if (const auto [found, inserted] = directedEdges.emplace(edge, t); !inserted)
            {
                throw MeshError("inconsistently oriented: triangles " + std::to_string(found->second) + " and " +
                                std::to_string(t) + " both run from " + describe(mesh.vertices[edge.first]) + " to " +
                                describe(mesh.vertices[edge.second]) +
                                " (neighbours must run along a shared edge in opposite directions), or more than "
                                "two triangles share that edge");
            }
        }
    }
    for (const auto& [edge, t] : directedEdges)
    {
        if (!directedEdges.contains({edge.second, edge.first}))
        {
            throw MeshError("not closed: the edge from " + describe(mesh.vertices[edge.first]) + " to " +
                            describe(mesh.vertices[edge.second]) + " of triangle " + std::to_string(t) +
                            " has no neighbour across it (a hole in the surface)");
        }
    }
}

// Principal axes as the columns of a rotation, each matched to the mesh axis it is nearest to so
// that a mesh modelled on its principal axes keeps them.
Mat3 principalAxes(const Mat3& inertia)
{
    const Real offDiagonal = std::abs(inertia(0, 1)) + std::abs(inertia(0, 2)) + std::abs(inertia(1, 2));
    if (offDiagonal <= 1e-12 * inertia.trace())
    {
        return Mat3::Identity(); // already principal, up to round-off: keep the mesh's axes exactly
    }
    const Eigen::SelfAdjointEigenSolver<Mat3> solver(inertia);
    const Mat3 vectors = solver.eigenvectors();
    Mat3 axes = Mat3::Zero();
    std::array<bool, 3> taken{};
    for (int pass = 0; pass < 3; ++pass)
    {
        // the most decided match first: the largest |component| left
        int bestVector = -1;
        int bestAxis = -1;
        Real best = -1.0;
        for (int v = 0; v < 3; ++v)
        {
            if (taken[v])
            {
                continue;
            }
            for (int axis = 0; axis < 3; ++axis)
            {
                if (axes.col(axis).squaredNorm() == 0.0 && std::abs(vectors(axis, v)) > best)
                {
                    best = std::abs(vectors(axis, v));
                    bestVector = v;
                    bestAxis = axis;
                }
            }
        }
        taken[bestVector] = true;
        axes.col(bestAxis) = vectors.col(bestVector) * (vectors(bestAxis, bestVector) < 0.0 ? -1.0 : 1.0);
    }
    if (axes.determinant() < 0.0)
    {
        // keep the two best-aligned axes, and make the frame right-handed with the third
        int weakest = 0;
        axes.diagonal().minCoeff(&weakest);
        axes.col(weakest) = -axes.col(weakest);
    }
    return axes;
}

int defaultResolution(const TriangleMesh& mesh, Real longest)
{
    // cells about as long as the mesh's typical edge, so the grid resolves what the mesh shows
    std::vector<Real> lengths;
    lengths.reserve(mesh.triangles.size());
    for (const auto& tri : mesh.triangles)
    {
        lengths.push_back((mesh.vertices[tri[1]] - mesh.vertices[tri[0]]).norm());
    }
    std::nth_element(lengths.begin(), lengths.begin() + static_cast<std::ptrdiff_t>(lengths.size() / 2), lengths.end());
    const Real median = lengths[lengths.size() / 2];
    return std::clamp(static_cast<int>(std::ceil(longest / median)), 32, 128);
}

} // namespace

PolyhedronMass polyhedronMass(const TriangleMesh& mesh)
{
    // Sum over the tetrahedra (o, a, b, c) of each triangle with a reference point o: the signed
    // volume det/6, first moment det/24 (a+b+c), and second moment
    // det/120 (a a^T + b b^T + c c^T + (a+b+c)(a+b+c)^T), all relative to o.
    Vec3 reference = Vec3::Zero();
    for (const Vec3& v : mesh.vertices)
    {
        reference += v;
    }
    reference /= static_cast<Real>(mesh.vertices.size());
    Real volume = 0.0;
    Vec3 firstMoment = Vec3::Zero();
    Mat3 secondMoment = Mat3::Zero();
    for (const auto& tri : mesh.triangles)
    {
        const Vec3 a = mesh.vertices[tri[0]] - reference;
        const Vec3 b = mesh.vertices[tri[1]] - reference;
        const Vec3 c = mesh.vertices[tri[2]] - reference;
        const Real det = a.dot(b.cross(c));
        const Vec3 sum = a + b + c;
        volume += det / 6.0;
        firstMoment += det / 24.0 * sum;
        secondMoment +=
            det / 120.0 * (a * a.transpose() + b * b.transpose() + c * c.transpose() + sum * sum.transpose());
    }
    PolyhedronMass result;
    result.volume = volume;
    if (!(volume > 0.0))
    {
        return result;
    }
    const Vec3 centroid = firstMoment / volume;
    const Mat3 central = secondMoment - volume * centroid * centroid.transpose();
    result.centroid = reference + centroid;
    result.unitInertia = (central.trace() * Mat3::Identity() - central) / volume;
    return result;
}

MeshGeometry::MeshGeometry() = default;
MeshGeometry::~MeshGeometry() = default;

std::shared_ptr<const MeshGeometry> MeshGeometry::build(const TriangleMesh& source, const MeshOptions& options)
{
    if (source.vertices.empty() || source.triangles.empty())
    {
        throw MeshError("the mesh has no triangles");
    }
    if (options.resolution < 0 || options.resolution > 1024)
    {
        throw MeshError("grid resolution must be between 1 and 1024 cells (0 chooses), got " +
                        std::to_string(options.resolution));
    }
    const TriangleMesh mesh = weld(source);
    validate(mesh);
    const PolyhedronMass mass = polyhedronMass(mesh);
    if (!(mass.volume > 0.0))
    {
        throw MeshError("the triangles face inward (the enclosed volume is negative); reverse their winding");
    }

    std::shared_ptr<MeshGeometry> geometry(new MeshGeometry());
    const Mat3 axes = principalAxes(mass.unitInertia);
    geometry->m_frameInMesh = Pose::from(mass.centroid, Quat(axes));
    geometry->m_frameInMesh.rotation = axes;
    const Mat3 principal = axes.transpose() * mass.unitInertia * axes;
    geometry->m_unitInertia = principal.diagonal();
    geometry->m_volume = mass.volume;

    TriangleMesh body = mesh;
    for (Vec3& v : body.vertices)
    {
        v = axes.transpose() * (v - mass.centroid);
    }
    geometry->m_lower = body.vertices[0];
    geometry->m_upper = body.vertices[0];
    for (const Vec3& v : body.vertices)
    {
        geometry->m_lower = geometry->m_lower.cwiseMin(v);
        geometry->m_upper = geometry->m_upper.cwiseMax(v);
        geometry->m_boundingRadius = std::max(geometry->m_boundingRadius, v.norm());
    }
    const int resolution = options.resolution > 0
                               ? options.resolution
                               : defaultResolution(body, (geometry->m_upper - geometry->m_lower).maxCoeff());
    const Vec3 samples = SignedDistanceGrid::sampleCounts(geometry->m_lower, geometry->m_upper, resolution);
    if (!(samples.prod() <= static_cast<Real>(options.maxGridSamples)))
    {
        std::ostringstream text;
        text << "the signed distance grid at resolution " << resolution << " would have " << samples.x() << " x "
             << samples.y() << " x " << samples.z() << " samples, more than the limit of " << options.maxGridSamples
             << "; choose a coarser resolution";
        throw MeshError(text.str());
    }
    geometry->m_queries = std::make_unique<const MeshQueries>(*geometry, body, resolution);
    geometry->m_vertices = std::move(body.vertices);
    geometry->m_triangles = std::move(body.triangles);
    return geometry;
}

MeshDistance MeshGeometry::signedDistance(const Vec3& pointBody) const
{
    MeshQueryScratch scratch;
    return m_queries->exactDistance(pointBody, scratch);
}

} // namespace impulse
