// SPDX-License-Identifier: MIT
// Triangle meshes as solids: validation, mass properties by polyhedral integration against the
// analytic solids, the body frame, and the signed distance (grid and exact) against analytic
// distances.
#include "geometry/mesh_queries.hpp"
#include "geometry/signed_distance_grid.hpp"

#include <impulse/io/mesh_file.hpp>
#include <impulse/mesh.hpp>
#include <impulse/mesh_shapes.hpp>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <random>
#include <string>

namespace impulse
{
namespace
{

// The narrow phase's view of a mesh, and its queries, each with buffers of its own.
const MeshQueries& queries(const MeshGeometry& mesh)
{
    return MeshQueries::of(mesh);
}

MeshDistance exactDistance(const MeshGeometry& mesh, const Vec3& p)
{
    MeshQueryScratch scratch;
    return queries(mesh).exactDistance(p, scratch);
}

MeshDistance contactDistance(const MeshGeometry& mesh, const Vec3& p,
                             Real threshold = std::numeric_limits<Real>::infinity())
{
    MeshQueryScratch scratch;
    return queries(mesh).distance(p, threshold, scratch);
}

void segmentCrossings(const MeshGeometry& mesh, const Vec3& a, const Vec3& b, std::vector<Real>& enterLeave)
{
    MeshQueryScratch scratch;
    queries(mesh).segmentCrossings(a, b, enterLeave, scratch);
}

Real analyticBoxDistance(const Vec3& half, const Vec3& p)
{
    const Vec3 q = p.cwiseAbs() - half;
    return q.cwiseMax(0.0).norm() + std::min(q.maxCoeff(), 0.0);
}

// Uniform random points in the box [-extent, extent], the same every run.
std::vector<Vec3> samplePoints(const Vec3& extent, int count, unsigned seed)
{
    std::mt19937 random(seed);
    std::uniform_real_distribution<Real> unit(-1.0, 1.0);
    std::vector<Vec3> points;
    for (int i = 0; i < count; ++i)
    {
        points.emplace_back(unit(random) * extent.x(), unit(random) * extent.y(), unit(random) * extent.z());
    }
    return points;
}

// Whether p lies beyond the padding the mesh's grid adds around its bounding box.
bool beyondTheGrid(const MeshGeometry& mesh, const Vec3& p)
{
    const Vec3 centre = 0.5 * (mesh.lower() + mesh.upper());
    const Vec3 half = 0.5 * (mesh.upper() - mesh.lower());
    return ((p - centre).cwiseAbs() - half).maxCoeff() > SignedDistanceGrid::kPadding * queries(mesh).cellSize();
}

std::string buildError(const TriangleMesh& mesh)
{
    try
    {
        MeshGeometry::build(mesh);
    }
    catch (const MeshError& error)
    {
        return error.what();
    }
    return "(no error)";
}

// ---- mass properties ----

TEST(MeshMass, BoxIsExactBecausePolyhedralIntegrationIsExactForPolyhedra)
{
    const Vec3 half(0.3, 0.2, 0.1);
    const auto box = MeshGeometry::build(boxMesh(half, 3));
    EXPECT_NEAR(box->volume(), 8.0 * half.prod(), 1e-15);
    const Vec3 h2 = half.cwiseProduct(half);
    const Vec3 expected = Vec3(h2.y() + h2.z(), h2.x() + h2.z(), h2.x() + h2.y()) / 3.0;
    EXPECT_LT((box->unitInertia() - expected).norm(), 1e-15);
    EXPECT_LT(box->frameInMesh().position.norm(), 1e-15);
}

TEST(MeshMass, SphereConvergesToTheBallFromInsideAtSecondOrder)
{
    // an inscribed polyhedron holds less than the ball, and more than the ball of its faces'
    // nearest distance r cos(pi/rings) cos(pi/segments); the error falls as 1/n^2
    const Real r = 0.5;
    const Real ballVolume = 4.0 / 3.0 * std::numbers::pi * r * r * r;
    Real previousError = 0.0;
    for (const int rings : {16, 32, 64})
    {
        const auto sphere = MeshGeometry::build(sphereMesh(r, rings, 2 * rings));
        const Real c = std::cos(std::numbers::pi / rings) * std::cos(std::numbers::pi / (2 * rings));
        EXPECT_LT(sphere->volume(), ballVolume);
        EXPECT_GT(sphere->volume(), ballVolume * c * c * c);
        for (int axis = 0; axis < 3; ++axis)
        {
            EXPECT_LT(sphere->unitInertia()[axis], 0.4 * r * r);
            EXPECT_GT(sphere->unitInertia()[axis], 0.4 * r * r * c * c);
        }
        const Real error = ballVolume - sphere->volume();
        if (previousError > 0.0)
        {
            EXPECT_GT(previousError / error, 3.5) << "rings " << rings;
        }
        previousError = error;
    }
}

TEST(MeshMass, TorusMatchesTheSolidTorusWithinTessellation)
{
    // V = 2 pi^2 R r^2, I_z = m (R^2 + 3 r^2 / 4), I_x = I_y = m (R^2 / 2 + 5 r^2 / 8)
    const Real R = 0.3;
    const Real r = 0.05;
    const auto torus = MeshGeometry::build(torusMesh(R, r, 256, 64));
    const Real tolerance = 2e-3; // inscribed tube: 1 - cos(pi / 64) ~ 1.2e-3 of r on every scale
    EXPECT_NEAR(torus->volume() / (2.0 * std::numbers::pi * std::numbers::pi * R * r * r), 1.0, tolerance);
    EXPECT_NEAR(torus->unitInertia().z() / (R * R + 0.75 * r * r), 1.0, tolerance);
    EXPECT_NEAR(torus->unitInertia().x() / (0.5 * R * R + 0.625 * r * r), 1.0, tolerance);
    EXPECT_NEAR(torus->unitInertia().x(), torus->unitInertia().y(), 1e-14);
}

TEST(MeshMass, BodyFrameIsAtTheCentroidOnThePrincipalAxes)
{
    // a box moved and turned in its file: the body frame must undo exactly that
    const Vec3 half(0.4, 0.2, 0.1);
    const Quat turn(Eigen::AngleAxisd(0.7, Vec3(1.0, 2.0, 3.0).normalized()));
    const Vec3 shift(1.0, -2.0, 0.5);
    TriangleMesh mesh = boxMesh(half, 2);
    for (Vec3& v : mesh.vertices)
    {
        v = turn * v + shift;
    }
    const auto body = MeshGeometry::build(mesh);
    EXPECT_LT((body->frameInMesh().position - shift).norm(), 1e-12);
    // each principal axis is one of the box's edges (up to sign), and the moments are the box's
    const Mat3 axes = body->frameInMesh().rotation;
    const Mat3 turned = turn.toRotationMatrix();
    EXPECT_NEAR(axes.determinant(), 1.0, 1e-12);
    const Vec3 h2 = half.cwiseProduct(half);
    const Vec3 boxMoments = Vec3(h2.y() + h2.z(), h2.x() + h2.z(), h2.x() + h2.y()) / 3.0;
    for (int k = 0; k < 3; ++k)
    {
        int edge = 0;
        (turned.transpose() * axes.col(k)).cwiseAbs().maxCoeff(&edge);
        EXPECT_NEAR(std::abs(turned.col(edge).dot(axes.col(k))), 1.0, 1e-12);
        EXPECT_NEAR(body->unitInertia()[k], boxMoments[edge], 1e-12);
    }
    // vertices in the body frame: centred, and the same solid
    Vec3 centre = Vec3::Zero();
    for (const Vec3& v : body->vertices())
    {
        centre += v / static_cast<Real>(body->vertices().size());
    }
    EXPECT_LT(centre.norm(), 1e-12);
}

TEST(MeshMass, AnLShapeFindsItsDiagonalPrincipalAxes)
{
    // three cubes of side a in an L, symmetric about the plane x = y: principal axes z and the two
    // diagonals; moments from the parallel-axis theorem over the cubes
    const Real a = 0.1;
    const std::vector<Vec3> cells{Vec3(0.5, 0.5, 0.5), Vec3(1.5, 0.5, 0.5), Vec3(0.5, 1.5, 0.5)};
    Mat3 inertia = Mat3::Zero();
    Vec3 centroid = Vec3::Zero();
    for (const Vec3& c : cells)
    {
        centroid += c * a / 3.0;
    }
    for (const Vec3& c : cells)
    {
        const Vec3 d = c * a - centroid;
        inertia += (a * a / 6.0) * Mat3::Identity() / 3.0 +
                   (d.squaredNorm() * Mat3::Identity() - d * d.transpose()) / 3.0; // per unit mass
    }
    const TriangleMesh mesh = [&]
    {
        // the L as a voxel surface over a 2 x 2 x 1 grid with the (1, 1) cell empty
        TriangleMesh m;
        const auto vertex = [&](int x, int y, int z)
        {
            m.vertices.emplace_back(a * x, a * y, a * z);
            return static_cast<std::uint32_t>(m.vertices.size() - 1);
        };
        const auto quad = [&](Vec3 p0, Vec3 p1, Vec3 p2, Vec3 p3)
        {
            const auto i0 = vertex(static_cast<int>(p0.x()), static_cast<int>(p0.y()), static_cast<int>(p0.z()));
            const auto i1 = vertex(static_cast<int>(p1.x()), static_cast<int>(p1.y()), static_cast<int>(p1.z()));
            const auto i2 = vertex(static_cast<int>(p2.x()), static_cast<int>(p2.y()), static_cast<int>(p2.z()));
            const auto i3 = vertex(static_cast<int>(p3.x()), static_cast<int>(p3.y()), static_cast<int>(p3.z()));
            m.triangles.push_back({i0, i1, i2});
            m.triangles.push_back({i0, i2, i3});
        };
        const bool filled[2][2] = {{true, true}, {true, false}}; // [x][y]
        const auto full = [&](int x, int y) { return x >= 0 && y >= 0 && x < 2 && y < 2 && filled[x][y]; };
        for (int x = 0; x < 2; ++x)
        {
            for (int y = 0; y < 2; ++y)
            {
                if (!full(x, y))
                {
                    continue;
                }
                const Real X = x;
                const Real Y = y;
                quad(Vec3(X, Y, 0), Vec3(X, Y + 1, 0), Vec3(X + 1, Y + 1, 0), Vec3(X + 1, Y, 0)); // bottom
                quad(Vec3(X, Y, 1), Vec3(X + 1, Y, 1), Vec3(X + 1, Y + 1, 1), Vec3(X, Y + 1, 1)); // top
                if (!full(x - 1, y))
                {
                    quad(Vec3(X, Y, 0), Vec3(X, Y, 1), Vec3(X, Y + 1, 1), Vec3(X, Y + 1, 0));
                }
                if (!full(x + 1, y))
                {
                    quad(Vec3(X + 1, Y, 0), Vec3(X + 1, Y + 1, 0), Vec3(X + 1, Y + 1, 1), Vec3(X + 1, Y, 1));
                }
                if (!full(x, y - 1))
                {
                    quad(Vec3(X, Y, 0), Vec3(X + 1, Y, 0), Vec3(X + 1, Y, 1), Vec3(X, Y, 1));
                }
                if (!full(x, y + 1))
                {
                    quad(Vec3(X, Y + 1, 0), Vec3(X, Y + 1, 1), Vec3(X + 1, Y + 1, 1), Vec3(X + 1, Y + 1, 0));
                }
            }
        }
        return m;
    }();
    const auto body = MeshGeometry::build(mesh);
    EXPECT_NEAR(body->volume(), 3.0 * a * a * a, 1e-15);
    EXPECT_LT((body->frameInMesh().position - centroid).norm(), 1e-15);
    const Mat3 axes = body->frameInMesh().rotation;
    const Mat3 principal = axes.transpose() * inertia * axes;
    EXPECT_LT((principal - Mat3(principal.diagonal().asDiagonal())).norm(), 1e-14);
    EXPECT_LT((principal.diagonal() - body->unitInertia()).norm(), 1e-14);
    // z stays an axis; the others are the diagonals
    EXPECT_NEAR(std::abs(axes.col(2).z()), 1.0, 1e-12);
    EXPECT_NEAR(std::abs(axes.col(0).x()), std::sqrt(0.5), 1e-12);
}

// ---- signed distance ----

TEST(MeshDistance, GridOfAMeshedSphereIsWithinHalfACellOfTheBall)
{
    const Real r = 1.0;
    const auto sphere = MeshGeometry::build(sphereMesh(r, 48, 96), {32});
    const Real cell = queries(*sphere).cellSize();
    // the mesh lies within r (1 - cos(pi/48)) ~ 0.002 of the ball: far below half a cell (0.03)
    for (const Vec3& p : samplePoints(Vec3::Constant(r + 3.0 * cell), 20000, 1))
    {
        EXPECT_NEAR(queries(*sphere).gridDistance(p).phi, p.norm() - r, 0.5 * cell) << p.transpose();
    }
}

TEST(MeshDistance, GridOfAMeshedBoxIsWithinHalfACellOfTheBox)
{
    const Vec3 half(0.3, 0.2, 0.1);
    const auto box = MeshGeometry::build(boxMesh(half), {32});
    const Real cell = queries(*box).cellSize();
    for (const Vec3& p : samplePoints(half + Vec3::Constant(3.0 * cell), 20000, 2))
    {
        EXPECT_NEAR(queries(*box).gridDistance(p).phi, analyticBoxDistance(half, p), 0.5 * cell) << p.transpose();
    }
}

TEST(MeshDistance, ExactDistanceOfAMeshedBoxIsTheBoxDistanceEverywhere)
{
    const Vec3 half(0.3, 0.2, 0.1);
    const auto box = MeshGeometry::build(boxMesh(half, 2));
    for (const Vec3& p : samplePoints(2.0 * half, 20000, 3))
    {
        const MeshDistance d = exactDistance(*box, p);
        ASSERT_NEAR(d.phi, analyticBoxDistance(half, p), 1e-14) << p.transpose();
        ASSERT_NEAR(d.gradient.norm(), 1.0, 1e-12);
    }
    // outside a face, the gradient is the face's normal; inside, the nearest face's
    EXPECT_LT((exactDistance(*box, Vec3(0.1, 0.05, 0.3)).gradient - Vec3::UnitZ()).norm(), 1e-14);
    EXPECT_LT((exactDistance(*box, Vec3(0.28, 0.0, 0.0)).gradient - Vec3::UnitX()).norm(), 1e-14);
}

TEST(MeshDistance, ContactNormalOnARidgeIsTheBisectorNotOneFace)
{
    // a point a hair under a vertex on the top ridge of a coarse torus (16 facets around the tube)
    // is nearest one of the facets beside it by round-off; the contact normal must not take that
    // facet's tilt of 11.25 degrees (the facets' own twist leaves a fraction of a degree)
    const auto torus = MeshGeometry::build(torusMesh(0.2, 0.05, 40, 16));
    const MeshDistance d = contactDistance(*torus, Vec3(0.2, 0.0, 0.05 - 1e-9));
    EXPECT_NEAR(d.phi, -1e-9 * std::cos(11.25 * std::numbers::pi / 180.0), 1e-12);
    EXPECT_GT(d.gradient.z(), std::cos(2.0 * std::numbers::pi / 180.0)) << d.gradient.transpose();
}

TEST(MeshDistance, OutsideTheGridDistanceGrowsWithTheWayToTheGrid)
{
    const auto sphere = MeshGeometry::build(sphereMesh(1.0, 48, 96), {32});
    for (const Vec3& direction : {Vec3(1.0, 0.0, 0.0), Vec3(-1.0, 0.0, 0.0), Vec3(0.0, 0.0, 1.0)})
    {
        for (const Real distance : {2.0, 10.0})
        {
            EXPECT_NEAR(queries(*sphere).gridDistance((1.0 + distance) * direction).phi, distance,
                        0.5 * queries(*sphere).cellSize());
        }
    }
}

TEST(MeshDistance, CoarseLowerBoundNeverExceedsTheExactDistance)
{
    // the mesh narrow phase passes over an edge whose ends' bounds cover it: near the surface, deep
    // inside, beyond the exact band and outside the grid, where the grid's own extension is an upper
    // bound of phi, not a lower one
    const auto torus = MeshGeometry::build(torusMesh(0.2, 0.05, 40, 16));
    const Real cell = queries(*torus).cellSize();
    Real tightest = std::numeric_limits<Real>::infinity();
    int outsideTheGrid = 0;
    for (const Vec3& reach : {Vec3(0.25 + 2.0 * cell, 0.25 + 2.0 * cell, 0.05 + 2.0 * cell), Vec3(0.7, 0.7, 0.5)})
    {
        for (const Vec3& p : samplePoints(reach, 4000, 4))
        {
            const Real exact = exactDistance(*torus, p).phi;
            const Real bound = queries(*torus).coarseLowerBound(p);
            EXPECT_LE(bound, exact) << p.transpose();
            tightest = std::min(tightest, exact - bound);
            outsideTheGrid += beyondTheGrid(*torus, p) ? 1 : 0;
        }
    }
    EXPECT_GT(outsideTheGrid, 1000);
    // and it says something: near the surface it comes within a cell of the truth
    EXPECT_LT(tightest, cell);
}

TEST(MeshDistance, CoarseLowerBoundHoldsForEveryShippedMesh)
{
    // the grid less its error alone is no lower bound outside the grid (it is exceeded by centimetres
    // at a fifth of such points for these meshes), which once let the edge test pass over edges that
    // went through a body
    for (const char* name :
         {"dumbbell.obj", "gear.stl", "l_block.obj", "peg.obj", "ring.obj", "small_torus.obj", "star.obj", "torus.obj"})
    {
        const auto mesh = MeshGeometry::build(io::readMeshFile(std::string(IMPULSE_SCENES_DIR) + "/meshes/" + name));
        const Vec3 centre = 0.5 * (mesh->lower() + mesh->upper());
        const Vec3 half = 0.5 * (mesh->upper() - mesh->lower());
        int outsideTheGrid = 0;
        for (const Vec3& unit : samplePoints(Vec3::Constant(2.5), 3000, 6))
        {
            const Vec3 p = centre + half.cwiseProduct(unit);
            EXPECT_LE(queries(*mesh).coarseLowerBound(p), exactDistance(*mesh, p).phi)
                << name << " at " << p.transpose();
            outsideTheGrid += beyondTheGrid(*mesh, p) ? 1 : 0;
        }
        EXPECT_GT(outsideTheGrid, 1000) << name;
    }
}

TEST(MeshDistance, PointsWithinTheThresholdAreFoundOutsideTheGridToo)
{
    // a capsule's sample balls ask with threshold + radius, which can reach past the grid, where the
    // grid's extension exceeds phi: a point within the threshold must still come back as such
    const auto torus = MeshGeometry::build(torusMesh(0.2, 0.05, 40, 16));
    const Real cell = queries(*torus).cellSize();
    int outsideTheGrid = 0;
    for (const Vec3& p : samplePoints(Vec3(0.7, 0.7, 0.5), 4000, 5))
    {
        const Real exact = exactDistance(*torus, p).phi;
        const Real threshold = exact + 0.25 * cell;
        const MeshDistance d = contactDistance(*torus, p, threshold);
        EXPECT_LT(d.phi, threshold) << p.transpose();
        EXPECT_NEAR(d.phi, exact, 1e-12) << p.transpose();
        outsideTheGrid += beyondTheGrid(*torus, p) ? 1 : 0;
    }
    EXPECT_GT(outsideTheGrid, 1000);
}

TEST(MeshDistance, SegmentCrossingsOfABoxAreItsFaces)
{
    const auto box = MeshGeometry::build(boxMesh(Vec3(0.3, 0.2, 0.1), 3));
    std::vector<Real> enterLeave;
    segmentCrossings(*box, Vec3(-1.0, 0.01, 0.02), Vec3(1.0, 0.01, 0.02), enterLeave);
    ASSERT_EQ(enterLeave.size(), 2u);
    EXPECT_NEAR(enterLeave[0], 0.35, 1e-14);
    EXPECT_NEAR(enterLeave[1], 0.65, 1e-14);
    // through an edge of the subdivided face: still one passage
    segmentCrossings(*box, Vec3(-1.0, 0.2 / 3.0, 0.1 / 3.0), Vec3(1.0, 0.2 / 3.0, 0.1 / 3.0), enterLeave);
    EXPECT_EQ(enterLeave.size(), 2u);
    // ending inside: the passage ends at exactly 1; starting inside, it starts at exactly 0
    segmentCrossings(*box, Vec3(-1.0, 0.0, 0.0), Vec3(0.0, 0.0, 0.0), enterLeave);
    ASSERT_EQ(enterLeave.size(), 2u);
    EXPECT_NEAR(enterLeave[0], 0.7, 1e-14);
    EXPECT_EQ(enterLeave[1], 1.0);
    segmentCrossings(*box, Vec3(0.1, 0.0, 0.0), Vec3(1.1, 0.0, 0.0), enterLeave);
    ASSERT_EQ(enterLeave.size(), 2u);
    EXPECT_EQ(enterLeave[0], 0.0);
    EXPECT_NEAR(enterLeave[1], 0.2, 1e-14);
    // inside from end to end: no crossing at all, which the caller reads with what it knows of the ends
    segmentCrossings(*box, Vec3(-0.1, 0.0, 0.0), Vec3(0.1, 0.0, 0.0), enterLeave);
    EXPECT_TRUE(enterLeave.empty());
}

// ---- preparing a mesh ----

TEST(MeshBuild, TriangleSoupIsWeldedIntoTheSameSolid)
{
    // STL stores each triangle with its own corners
    const TriangleMesh indexed = boxMesh(Vec3(0.3, 0.2, 0.1), 2);
    TriangleMesh soup;
    for (const auto& tri : indexed.triangles)
    {
        for (const std::uint32_t v : tri)
        {
            soup.vertices.push_back(indexed.vertices[v]);
        }
        const auto first = static_cast<std::uint32_t>(soup.vertices.size() - 3);
        soup.triangles.push_back({first, first + 1, first + 2});
    }
    const auto welded = MeshGeometry::build(soup);
    EXPECT_EQ(welded->vertices().size(), 26u); // 8 corners, 12 edge middles, 6 face centres
    EXPECT_NEAR(welded->volume(), 0.048, 1e-15);
}

TEST(MeshBuild, SharedGeometryIsBuiltOnceAndReportsItsGrid)
{
    const auto torus = MeshGeometry::build(torusMesh(0.2, 0.05, 40, 16), {64});
    // 64 cells over the longest side (0.5) plus 3 cells of padding each side
    EXPECT_NEAR(queries(*torus).cellSize(), 0.5 / 64, 1e-15);
    EXPECT_EQ(queries(*torus).gridSamples()[0], 64 + 6 + 1);
    EXPECT_EQ(queries(*torus).edges().size(), 3u * 40u * 16u); // a torus: E = 3F/2, F = 2 * 40 * 16
}

TEST(MeshBuild, VertexClustersCoverEveryVertexOnceWithinTheirSpheres)
{
    const auto torus = MeshGeometry::build(torusMesh(0.2, 0.05, 40, 16));
    std::vector<int> seen(torus->vertices().size(), 0);
    std::uint32_t next = 0;
    for (const MeshQueries::VertexCluster& cluster : queries(*torus).vertexClusters())
    {
        EXPECT_EQ(cluster.first, next);
        EXPECT_GT(cluster.count, 0u);
        EXPECT_LE(cluster.count, MeshQueries::kClusterSize);
        next += cluster.count;
        for (std::uint32_t i = cluster.first; i < cluster.first + cluster.count; ++i)
        {
            const std::uint32_t v = queries(*torus).vertexClusterMembers()[i];
            ++seen[v];
            EXPECT_LE((torus->vertices()[v] - cluster.centre).norm(), cluster.radius);
        }
        // a cluster is small: a few neighbouring vertices, not a slice of the whole ring
        EXPECT_LT(cluster.radius, 0.05);
    }
    EXPECT_EQ(next, torus->vertices().size());
    EXPECT_TRUE(std::all_of(seen.begin(), seen.end(), [](int n) { return n == 1; }));
}

TEST(MeshBuild, RefusesAHole)
{
    TriangleMesh mesh = boxMesh(Vec3::Constant(0.1));
    mesh.triangles.pop_back();
    EXPECT_NE(buildError(mesh).find("not closed"), std::string::npos) << buildError(mesh);
}

TEST(MeshBuild, RefusesAFlippedTriangle)
{
    TriangleMesh mesh = boxMesh(Vec3::Constant(0.1));
    std::swap(mesh.triangles[3][0], mesh.triangles[3][1]);
    EXPECT_NE(buildError(mesh).find("inconsistently oriented"), std::string::npos) << buildError(mesh);
}

TEST(MeshBuild, RefusesAnInsideOutMesh)
{
    TriangleMesh mesh = boxMesh(Vec3::Constant(0.1));
    for (auto& tri : mesh.triangles)
    {
        std::swap(tri[0], tri[1]);
    }
    EXPECT_NE(buildError(mesh).find("face inward"), std::string::npos) << buildError(mesh);
}

TEST(MeshBuild, RefusesDegenerateAndDuplicateTriangles)
{
    TriangleMesh repeated = boxMesh(Vec3::Constant(0.1));
    repeated.triangles[0][1] = repeated.triangles[0][0];
    EXPECT_NE(buildError(repeated).find("triangle 0 is degenerate"), std::string::npos) << buildError(repeated);

    TriangleMesh flat = boxMesh(Vec3::Constant(0.1));
    flat.vertices.push_back(Vec3(0.0, 0.0, 0.0));
    flat.vertices.push_back(Vec3(1.0, 0.0, 0.0));
    flat.vertices.push_back(Vec3(2.0, 0.0, 0.0));
    flat.triangles.push_back({24, 25, 26});
    EXPECT_NE(buildError(flat).find("on one line"), std::string::npos) << buildError(flat);

    TriangleMesh twice = boxMesh(Vec3::Constant(0.1));
    twice.triangles.push_back({twice.triangles[5][1], twice.triangles[5][2], twice.triangles[5][0]});
    EXPECT_NE(buildError(twice).find("duplicates triangle 5"), std::string::npos) << buildError(twice);
}

TEST(MeshBuild, RefusesNonFiniteAndOutOfRange)
{
    TriangleMesh nan = boxMesh(Vec3::Constant(0.1));
    nan.vertices[2].y() = std::numeric_limits<Real>::quiet_NaN();
    EXPECT_NE(buildError(nan).find("vertex 2 has a coordinate that is not a finite number"), std::string::npos);

    TriangleMesh range = boxMesh(Vec3::Constant(0.1));
    range.triangles[1][2] = 99;
    EXPECT_NE(buildError(range).find("triangle 1 refers to vertex 99"), std::string::npos) << buildError(range);

    EXPECT_NE(buildError(TriangleMesh{}).find("no triangles"), std::string::npos);
}

} // namespace
} // namespace impulse
