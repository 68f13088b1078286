// SPDX-License-Identifier: MIT
// What the pictures are made of: meshes that enclose their shapes with outward normals, a renderer
// that puts things where the camera looks and hides what is behind, PNGs that read back as written,
// and the energies the plots show.
#include <impulse/impulse.hpp>
#include <impulse/io/scene.hpp>
#include <impulse/mesh_shapes.hpp>
#include <impulse/viz/raster.hpp>
#include <impulse/viz/series.hpp>
#include <impulse/viz/tessellate.hpp>

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <numbers>

namespace
{

using impulse::Real;
using impulse::Vec3;
using namespace impulse::viz;

/// Volume enclosed by a closed mesh (divergence theorem); positive when its triangles face out.
Real enclosedVolume(const TriangleMesh& mesh)
{
    Real volume = 0.0;
    for (const auto& t : mesh.triangles)
    {
        volume += mesh.positions[t[0]].dot(mesh.positions[t[1]].cross(mesh.positions[t[2]])) / 6.0;
    }
    return volume;
}

/// Every triangle's winding agrees with its vertex normals.
void expectNormalsAgreeWithWinding(const TriangleMesh& mesh)
{
    for (const auto& t : mesh.triangles)
    {
        const Vec3 face =
            (mesh.positions[t[1]] - mesh.positions[t[0]]).cross(mesh.positions[t[2]] - mesh.positions[t[0]]);
        for (const std::uint32_t v : t)
        {
            ASSERT_GT(face.dot(mesh.normals[v]), 0.0);
            ASSERT_NEAR(mesh.normals[v].norm(), 1.0, 1e-12);
        }
    }
}

TEST(Tessellation, BoxEnclosesItsVolumeFacingOut)
{
    const TriangleMesh mesh = bodyTriangles(impulse::Box{Vec3(0.1, 0.2, 0.3)}, bodyColour(0));
    EXPECT_EQ(mesh.triangles.size(), 12u);
    EXPECT_NEAR(enclosedVolume(mesh), 8 * 0.1 * 0.2 * 0.3, 1e-15);
    expectNormalsAgreeWithWinding(mesh);
}

TEST(Tessellation, SphereLiesOnItsSurfaceAndNearlyEnclosesItsVolume)
{
    const Real r = 0.25;
    const TriangleMesh mesh = bodyTriangles(impulse::Sphere{r}, bodyColour(1));
    for (const Vec3& p : mesh.positions)
    {
        ASSERT_NEAR(p.norm(), r, 1e-12);
    }
    const Real exact = 4.0 / 3.0 * std::numbers::pi * r * r * r;
    EXPECT_NEAR(enclosedVolume(mesh), exact, 0.02 * exact); // an inscribed polyhedron: a little less
    expectNormalsAgreeWithWinding(mesh);
}

TEST(Tessellation, MeshIsDrawnAsItsOwnTrianglesEnclosingItsVolume)
{
    const auto torus = impulse::MeshGeometry::build(impulse::torusMesh(0.3, 0.05, 24, 12));
    const TriangleMesh mesh = bodyTriangles(impulse::Mesh{torus}, bodyColour(2));
    EXPECT_EQ(mesh.triangles.size(), torus->triangles().size());
    EXPECT_NEAR(enclosedVolume(mesh), torus->volume(), 1e-12 * torus->volume());
    expectNormalsAgreeWithWinding(mesh);
}

TEST(Tessellation, CapsuleIsACylinderWithHemisphericalEnds)
{
    const impulse::Capsule capsule{0.1, 0.3};
    const TriangleMesh mesh = bodyTriangles(capsule, bodyColour(3));
    const Real exact = std::numbers::pi * 0.01 * 0.6 + 4.0 / 3.0 * std::numbers::pi * 0.001;
    EXPECT_NEAR(enclosedVolume(mesh), exact, 0.03 * exact); // inscribed: a little less
    EXPECT_LT(enclosedVolume(mesh), exact);
    expectNormalsAgreeWithWinding(mesh);
}

TEST(Tessellation, PlaneIsACheckerboardOnThePlaneAroundTheFocus)
{
    const impulse::Plane plane{Vec3(0, 0, 1), 0.5};
    const TriangleMesh mesh = bodyTriangles(plane, {}, {.focus = Vec3(3, -2, 7), .halfSize = 2.0});
    Vec3 low = Vec3::Constant(INFINITY), high = Vec3::Constant(-INFINITY);
    for (std::size_t v = 0; v < mesh.positions.size(); ++v)
    {
        ASSERT_NEAR(mesh.positions[v].z(), 0.5, 1e-12);
        ASSERT_EQ(mesh.normals[v], Vec3::UnitZ());
        low = low.cwiseMin(mesh.positions[v]);
        high = high.cwiseMax(mesh.positions[v]);
    }
    EXPECT_LE(low.x(), 3 - 2.0);
    EXPECT_GE(high.x(), 3 + 2.0 - 0.5);
    EXPECT_LE(low.y(), -2 - 2.0 + 0.5);
    EXPECT_GE(high.y(), -2 + 2.0 - 0.5);
    // two shades
    EXPECT_NE(mesh.colours.front().r, mesh.colours[6].r);
}

/// Renders `meshes` with a camera on +x looking at the origin.
Image renderFromX(const std::vector<DrawnMesh>& meshes, std::vector<Polyline> lines = {})
{
    RenderSettings settings;
    settings.width = 80;
    settings.height = 60;
    settings.shadowBounds = {Vec3::Constant(-1), Vec3::Constant(1)};
    Camera camera;
    camera.eye = Vec3(5, 0, 0);
    camera.target = Vec3::Zero();
    return renderImage(meshes, lines, camera, settings);
}

std::array<int, 3> pixel(const Image& image, int x, int y)
{
    const std::size_t i = (static_cast<std::size_t>(y) * image.width + x) * 3;
    return {image.rgb[i], image.rgb[i + 1], image.rgb[i + 2]};
}

TEST(Renderer, DrawsABodyWhereTheCameraLooksAndSkyElsewhere)
{
    const TriangleMesh ball = bodyTriangles(impulse::Sphere{0.5}, {0.9f, 0.1f, 0.1f});
    const Image image = renderFromX({{&ball, impulse::Pose::from(Vec3::Zero(), impulse::Quat::Identity())}});
    ASSERT_EQ(image.width, 80);
    ASSERT_EQ(image.height, 60);
    const auto centre = pixel(image, 40, 30);
    const auto corner = pixel(image, 1, 1);
    EXPECT_GT(centre[0], centre[2] + 40) << "the red ball at the centre";
    EXPECT_GT(corner[2], corner[0]) << "blue sky in the corner";
    // the ball moved up by one radius moves up in the picture
    const Image raised = renderFromX({{&ball, impulse::Pose::from(Vec3(0, 0, 1.0), impulse::Quat::Identity())}});
    EXPECT_GT(pixel(raised, 40, 30)[2], pixel(raised, 40, 30)[0]) << "sky where the ball was";
}

TEST(Renderer, HidesWhatIsBehindWhateverOrderItIsDrawnIn)
{
    const TriangleMesh red = bodyTriangles(impulse::Box{Vec3::Constant(0.3)}, {0.9f, 0.1f, 0.1f});
    const TriangleMesh blue = bodyTriangles(impulse::Box{Vec3::Constant(0.6)}, {0.1f, 0.1f, 0.9f});
    const auto identity = impulse::Quat::Identity();
    const DrawnMesh front{&red, impulse::Pose::from(Vec3(1.5, 0, 0), identity)};
    const DrawnMesh back{&blue, impulse::Pose::from(Vec3(-1.0, 0, 0), identity)};
    for (const auto& order : {std::vector{front, back}, std::vector{back, front}})
    {
        const auto centre = pixel(renderFromX(order), 40, 30);
        EXPECT_GT(centre[0], centre[2]);
    }
    // a line through the hidden box is hidden, one in front of everything is drawn
    Polyline hidden{{Vec3(-1.0, -0.1, 0), Vec3(-1.0, 0.1, 0)}, {0.0f, 1.0f, 0.0f}};
    Polyline shown{{Vec3(3.0, -0.1, 0), Vec3(3.0, 0.1, 0)}, {0.0f, 1.0f, 0.0f}};
    EXPECT_LT(pixel(renderFromX({front, back}, {hidden}), 40, 30)[1], 100);
    EXPECT_GT(pixel(renderFromX({front, back}, {shown}), 40, 30)[1], 200);
}

class Framing : public ::testing::TestWithParam<int>
{
};

// From the default direction, from above (straight along up), and from the side
TEST_P(Framing, KeepsTheContentInThePicture)
{
    const Bounds bounds{Vec3(-0.1, -0.3, 0.0), Vec3(4.3, 0.1, 0.2)}; // a rolling ball's path
    const Vec3 directions[] = {Vec3::Zero(), Vec3(0.0, 0.0, 1.0), Vec3(1.0, -2.0, 0.5)};
    const Vec3& direction = directions[GetParam()];
    const Camera camera = direction.isZero() ? frameCamera(bounds, Vec3::UnitZ(), 4.0 / 3.0)
                                             : frameCamera(bounds, Vec3::UnitZ(), 4.0 / 3.0, direction);
    if (!direction.isZero())
    {
        EXPECT_GT((camera.eye - camera.target).normalized().dot(direction.normalized()), 0.99);
    }
    const Vec3 back = (camera.eye - camera.target).normalized();
    const Vec3 right = camera.up.cross(back).normalized();
    const Vec3 up = back.cross(right);
    const Real tanY = std::tan(0.5 * camera.fovYDegrees * std::numbers::pi / 180.0);
    Real widest = 0.0;
    for (int corner = 0; corner < 8; ++corner)
    {
        const Vec3 p((corner & 1) ? bounds.max.x() : bounds.min.x(), (corner & 2) ? bounds.max.y() : bounds.min.y(),
                     (corner & 4) ? bounds.max.z() : bounds.min.z());
        const Vec3 d = p - camera.eye;
        const Real depth = -d.dot(back);
        ASSERT_GT(depth, 0.0);
        const Real x = d.dot(right) / (depth * tanY * 4.0 / 3.0);
        const Real y = d.dot(up) / (depth * tanY);
        EXPECT_LE(std::abs(x), 1.0);
        EXPECT_LE(std::abs(y), 1.0);
        widest = std::max(widest, std::abs(x));
    }
    EXPECT_GT(widest, 0.8) << "and fills it";
}

INSTANTIATE_TEST_SUITE_P(Directions, Framing, ::testing::Values(0, 1, 2));

TEST(Framing, FramesTheDynamicBodiesNotTheStaticOnes)
{
    SceneView view;
    view.dynamicShapes = {impulse::Sphere{0.1}};
    view.staticBodies.push_back(
        {impulse::Box{Vec3::Constant(1.0)}, impulse::Pose::from(Vec3(10.0, 0.0, 0.0), impulse::Quat::Identity())});
    impulse::io::Trajectory trajectory;
    trajectory.bodyCount = 1;
    trajectory.times = {0.0, 1.0};
    trajectory.samples.resize(2);
    trajectory.samples[1].position = Vec3(0.0, 0.0, 1.0);
    const Bounds moving = dynamicBounds(trajectory, view);
    EXPECT_EQ(moving.min, Vec3(-0.1, -0.1, -0.1));
    EXPECT_EQ(moving.max, Vec3(0.1, 0.1, 1.1));
    EXPECT_GT(contentBounds(trajectory, view).max.x(), 9.0); // the static box counts for shadows
}

TEST(Png, ReadsBackWhatItWrites)
{
    Image image;
    image.width = 7;
    image.height = 5;
    for (int i = 0; i < 7 * 5 * 3; ++i)
    {
        image.rgb.push_back(static_cast<std::uint8_t>(i * 37));
    }
    const auto path = std::filesystem::temp_directory_path() / "impulse_png_round_trip.png";
    writePng(image, path);
    const Image back = readPng(path);
    std::filesystem::remove(path);
    EXPECT_EQ(back.width, 7);
    EXPECT_EQ(back.height, 5);
    EXPECT_EQ(back.rgb, image.rgb);
}

TEST(Png, RefusesAFileThatIsNotOne)
{
    const auto path = std::filesystem::temp_directory_path() / "impulse_not_a_png.png";
    {
        std::ofstream file(path);
        file << "\x89PNG\r\n\x1a\n but then nothing sensible";
    }
    EXPECT_THROW(readPng(path), std::runtime_error);
    std::filesystem::remove(path);
    EXPECT_THROW(readPng(path), std::runtime_error);
}

TEST(Series, EnergyIsTotalWithTheSceneAndPerUnitMassWithout)
{
    const auto scene = impulse::io::loadScene(std::string(IMPULSE_SCENES_DIR) + "/ball_drop_elastic.json");
    impulse::io::Trajectory trajectory;
    trajectory.bodyCount = 1;
    trajectory.times = {0.0};
    trajectory.samples.push_back({Vec3(0, 0, 2), impulse::Quat::Identity(), Vec3(3, 0, 4), Vec3(0, 0, 10)});
    const SceneView view = SceneView::fromScene(scene);
    const Series withScene = computeSeries(trajectory, view);
    const Real m = scene.world.mass(scene.dynamicBodies[0]);
    const Real inertia = scene.world.principalInertia(scene.dynamicBodies[0]).z();
    EXPECT_NEAR(withScene.energy[0], m * (0.5 * 25 + 9.81 * 2) + 0.5 * inertia * 100, 1e-12);
    EXPECT_EQ(withScene.height[0][0], 2.0);
    EXPECT_EQ(withScene.speed[0][0], 5.0);
    const Series without = computeSeries(trajectory, SceneView::markersFor(trajectory));
    EXPECT_NEAR(without.energy[0], 0.5 * 25 + 9.81 * 2, 1e-12);
    EXPECT_NE(without.energyLabel.find("per unit mass"), std::string::npos);
}

TEST(SceneView, AShapeOffItsCentreOfMassIsDrawnWhereItIs)
{
    // roly_poly's first ball is weighted 3 cm below its centre: the trajectory places the centre of
    // mass, so in the body frame the sphere's triangles sit 3 cm above the origin
    const auto scene = impulse::io::loadScene(std::string(IMPULSE_SCENES_DIR) + "/roly_poly.json");
    const SceneView view = SceneView::fromScene(scene);
    const TriangleMesh ball = view.dynamicTriangles(0);
    Vec3 low = Vec3::Constant(INFINITY);
    Vec3 high = Vec3::Constant(-INFINITY);
    for (const Vec3& p : ball.positions)
    {
        low = low.cwiseMin(p);
        high = high.cwiseMax(p);
    }
    EXPECT_LT((0.5 * (low + high) - Vec3(0.0, 0.0, 0.03)).norm(), 1e-12);
    EXPECT_NEAR(view.dynamicRadius(0), 0.1 + 0.03, 1e-15);
}

} // namespace
