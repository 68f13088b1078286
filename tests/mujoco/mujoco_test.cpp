// SPDX-License-Identifier: MIT
// impulse_mujoco: scenes exported to MJCF and loaded back through MuJoCo's compiler give the same
// bodies; the drop-in stepper reproduces `impulse run` bit for bit on reference scenes 1-8; MuJoCo's
// free-joint conventions (body-frame angular velocity, inertial offsets) are honoured; edits made
// on the MuJoCo side are taken up; and models impulse cannot simulate are refused with the
// documented message.
#include "support/scene_run.hpp"

#include <impulse/io/mesh_file.hpp>
#include <impulse/mujoco/mjcf_export.hpp>
#include <impulse/mujoco/mujoco.hpp>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <numbers>
#include <string>
#include <vector>

namespace impulse::mujoco
{
namespace
{

struct Loaded
{
    ModelPtr model;
    DataPtr data;
};

Loaded loadExported(const io::Scene& scene)
{
    Loaded loaded;
    loaded.model = loadModelFromString(exportMjcf(scene), scene.name + " (exported)");
    loaded.data.reset(mj_makeData(loaded.model.get()));
    if (loaded.model->nkey > 0)
    {
        mj_resetDataKeyframe(loaded.model.get(), loaded.data.get(), 0);
    }
    mj_forward(loaded.model.get(), loaded.data.get());
    return loaded;
}

Vec3 vecOf(const mjtNum* xyz)
{
    return Vec3(xyz[0], xyz[1], xyz[2]);
}

Quat quatOf(const mjtNum* wxyz)
{
    return Quat(wxyz[0], wxyz[1], wxyz[2], wxyz[3]);
}

bool sameBits(const Vec3& a, const Vec3& b)
{
    return std::memcmp(a.data(), b.data(), sizeof(Real) * 3) == 0;
}

bool sameBits(const Quat& a, const Quat& b)
{
    return std::memcmp(a.coeffs().data(), b.coeffs().data(), sizeof(Real) * 4) == 0;
}

bool sameShape(const Shape& a, const Shape& b)
{
    if (a.index() != b.index())
    {
        return false;
    }
    if (const auto* s = std::get_if<Sphere>(&a))
    {
        return s->radius == std::get<Sphere>(b).radius;
    }
    if (const auto* box = std::get_if<Box>(&a))
    {
        return sameBits(box->halfExtents, std::get<Box>(b).halfExtents);
    }
    if (const auto* c = std::get_if<Capsule>(&a))
    {
        return c->radius == std::get<Capsule>(b).radius && c->halfLength == std::get<Capsule>(b).halfLength;
    }
    const auto& p = std::get<Plane>(a);
    return sameBits(p.normal, std::get<Plane>(b).normal) && p.offset == std::get<Plane>(b).offset;
}

// Reference scenes 1 to 8 for the drop-in runs, in two groups: a cube in contact over a whole incline
// scene takes most of the runs' time under sanitizers, so those instances are labelled "long"
// (tests/CMakeLists.txt)
const std::vector<std::string> kBallScenes = {"ball_drop_elastic", "ball_drop_damped", "ball_ball_headon",
                                              "ball_ball_oblique", "spin_friction",    "newton_cradle"};
const std::vector<std::string> kInclineScenes = {"incline_stick", "incline_slide"};

class ExportRoundTrip : public ::testing::TestWithParam<std::string>
{
};

TEST_P(ExportRoundTrip, GivesTheSameBodiesMassesInertiasAndPoses)
{
    const io::Scene scene = test::loadReferenceScene(GetParam());
    const Loaded loaded = loadExported(scene);
    const Translation t = translate(loaded.model.get(), loaded.data.get(), "exported");
    ASSERT_EQ(t.world.bodyCount(), scene.world.bodyCount());
    ASSERT_EQ(t.dynamicBodies.size(), scene.dynamicBodies.size());
    EXPECT_EQ(t.world.gravity(), scene.world.gravity());
    EXPECT_EQ(t.options.dt, scene.options.dt);
    EXPECT_EQ(t.duration.value_or(-1.0), scene.duration);
    // the export lists static bodies first, then dynamic ones, each in scene order
    std::vector<BodyId> sceneOrder;
    for (std::uint32_t i = 0; i < scene.world.bodyCount(); ++i)
    {
        if (!scene.world.isDynamic(BodyId{i}))
        {
            sceneOrder.push_back(BodyId{i});
        }
    }
    sceneOrder.insert(sceneOrder.end(), scene.dynamicBodies.begin(), scene.dynamicBodies.end());
    for (std::uint32_t i = 0; i < t.world.bodyCount(); ++i)
    {
        const BodyId ours{i};
        const BodyId theirs = sceneOrder[i];
        SCOPED_TRACE("body " + std::to_string(i));
        EXPECT_EQ(t.world.isDynamic(ours), scene.world.isDynamic(theirs));
        EXPECT_TRUE(sameShape(t.world.shape(ours), scene.world.shape(theirs)));
        const Material& a = t.world.material(t.world.material(ours));
        const Material& b = scene.world.material(scene.world.material(theirs));
        EXPECT_EQ(a.restitution, b.restitution);
        EXPECT_EQ(a.friction, b.friction);
        if (!scene.world.isDynamic(theirs))
        {
            continue;
        }
        // bit for bit: every number went through %.17g and MuJoCo's compiler unchanged
        EXPECT_EQ(t.world.mass(ours), scene.world.mass(theirs));
        EXPECT_TRUE(sameBits(t.world.principalInertia(ours), scene.world.principalInertia(theirs)));
        const BodyState s = t.world.state(ours);
        const BodyState r = scene.world.state(theirs);
        EXPECT_TRUE(sameBits(s.position, r.position));
        EXPECT_TRUE(sameBits(s.orientation, r.orientation));
        EXPECT_TRUE(sameBits(s.linearVelocity, r.linearVelocity));
        EXPECT_TRUE(sameBits(s.angularMomentum, r.angularMomentum));
    }
}

INSTANTIATE_TEST_SUITE_P(ReferenceScenes, ExportRoundTrip,
                         ::testing::Values("ball_drop_elastic", "ball_drop_damped", "ball_ball_headon",
                                           "ball_ball_oblique", "spin_friction", "incline_stick", "incline_slide",
                                           "newton_cradle", "box_stack_10", "lintel", "seesaw"));

// Two materials, a pair override and a tilted spinning capsule: the pair rules of the two engines
// differ, so the export states each pair; impulse reads the pairs back as the scene has them.
const char* const kMaterialScene = R"({"name": "pairs", "dt": 0.001, "duration": 1.0,
 "materials": {"rubber": {"restitution": 0.5, "friction": 0.9}, "ice": {"restitution": 0.1, "friction": 0.1}},
 "pairs": [{"materials": ["rubber", "rubber"], "restitution": 0.2, "friction": 0.7}],
 "bodies": [
  {"name": "ground", "static": true, "shape": {"type": "plane", "normal": [0, 0, 1]}, "material": "ice"},
  {"name": "ball", "shape": {"type": "sphere", "radius": 0.1}, "mass": 1, "position": [0, 0, 0.0999],
   "material": "rubber"},
  {"name": "rod", "shape": {"type": "capsule", "radius": 0.05, "half_length": 0.2}, "mass": 2,
   "position": [1, 0, 0.3], "orientation": {"axis": [1, 1, 0], "angle_deg": 40}, "angular_velocity": [1, 2, 3],
   "velocity": [0.5, 0, 0], "material": "rubber"}]})";

TEST(ExportRoundTrip, SolverOptionsAwayFromTheirDefaults)
{
    io::Scene scene = test::loadReferenceScene("ball_drop_damped");
    scene.options.restitutionThreshold = 0.125;
    scene.options.restingApproach = 0.25;
    scene.options.contactThickness = 2e-6;
    const Loaded loaded = loadExported(scene);
    const Translation t = translate(loaded.model.get(), loaded.data.get(), "exported");
    EXPECT_EQ(t.options.restitutionThreshold, 0.125);
    EXPECT_EQ(t.options.restingApproach, 0.25);
    EXPECT_EQ(t.options.contactThickness, 2e-6);
}

TEST(ExportRoundTrip, MaterialPairsAndCapsules)
{
    io::Scene scene = io::parseScene(kMaterialScene, "pairs");
    const Loaded loaded = loadExported(scene);
    const mjModel* m = loaded.model.get();
    ASSERT_EQ(m->npair, 3);
    // MuJoCo uses the explicit pair alone for the ball on the ground, with impulse's sqrt rule
    ASSERT_EQ(loaded.data->ncon, 1);
    EXPECT_DOUBLE_EQ(loaded.data->contact[0].friction[0], std::sqrt(0.9 * 0.1));
    Stepper stepper(m, loaded.data.get());
    const World& world = stepper.world();
    for (std::uint32_t i = 0; i < 3; ++i)
    {
        for (std::uint32_t j = 0; j < 3; ++j)
        {
            const PairCoefficients a = world.pairCoefficients(world.material(BodyId{i}), world.material(BodyId{j}));
            const PairCoefficients b =
                scene.world.pairCoefficients(scene.world.material(BodyId{i}), scene.world.material(BodyId{j}));
            if (i != j)
            {
                EXPECT_EQ(a.restitution, b.restitution) << i << " " << j;
                EXPECT_EQ(a.friction, b.friction) << i << " " << j;
            }
        }
    }
    EXPECT_TRUE(sameShape(world.shape(BodyId{2}), scene.world.shape(BodyId{2})));
    for (int k = 0; k < 1000; ++k)
    {
        scene.world.step(scene.options);
        stepper.step(m, loaded.data.get());
        ASSERT_EQ(stepper.world().stateHash(), scene.world.stateHash()) << "step " << k;
    }
}

class DropInStepper : public ::testing::TestWithParam<std::string>
{
};

TEST_P(DropInStepper, ReproducesImpulseRunBitForBit)
{
    io::Scene scene = test::loadReferenceScene(GetParam());
    const Loaded loaded = loadExported(scene);
    const mjModel* m = loaded.model.get();
    mjData* d = loaded.data.get();
    const long long steps = std::llround(scene.duration / scene.options.dt);
    const Translation layout = translate(m, d, "exported");
    long long mismatches = 0;
    for (long long k = 1; k <= steps && mismatches == 0; ++k)
    {
        scene.world.step(scene.options);
        step(m, d);
        for (std::size_t i = 0; i < scene.dynamicBodies.size(); ++i)
        {
            const BodyState r = scene.world.state(scene.dynamicBodies[i]);
            const mjtNum* qpos = d->qpos + layout.links[i].qposAddress;
            const mjtNum* qvel = d->qvel + layout.links[i].dofAddress;
            const Vec3 position(qpos[0], qpos[1], qpos[2]);
            const Quat orientation(qpos[3], qpos[4], qpos[5], qpos[6]);
            const Vec3 velocity(qvel[0], qvel[1], qvel[2]);
            // MuJoCo's convention: free-joint angular velocity in the body frame
            const Vec3 omegaWorld = orientation.toRotationMatrix() * Vec3(qvel[3], qvel[4], qvel[5]);
            // position and velocity bit for bit; the quaternion up to MuJoCo's renormalisation in
            // mj_forward (the stepper's world keeps impulse's own, checked by the hash below)
            const bool same = sameBits(position, r.position) && sameBits(velocity, r.linearVelocity) &&
                              orientation.coeffs().isApprox(r.orientation.coeffs(), 1e-15) &&
                              (omegaWorld - r.angularVelocity).norm() <= 1e-15 * (1.0 + r.angularVelocity.norm());
            if (!same)
            {
                ++mismatches;
                ADD_FAILURE() << GetParam() << ": body " << i << " differs after step " << k;
            }
        }
        EXPECT_NEAR(d->time, static_cast<Real>(k) * scene.options.dt, 1e-9);
    }
    forget(m, d);
}

INSTANTIATE_TEST_SUITE_P(BallScenes, DropInStepper, ::testing::ValuesIn(kBallScenes));
INSTANTIATE_TEST_SUITE_P(InclineScenes, DropInStepper, ::testing::ValuesIn(kInclineScenes));

class DropInStepperWorld : public ::testing::TestWithParam<std::string>
{
};

TEST_P(DropInStepperWorld, IsTheImpulseRunBitForBit)
{
    // qvel holds w, not L, and mj_forward renormalises qpos's quaternions: the stepper keeps its
    // world between calls, so the run's x, q, v and L (all in the state hash) carry on exactly
    io::Scene scene = test::loadReferenceScene(GetParam());
    const Loaded loaded = loadExported(scene);
    Stepper stepper(loaded.model.get(), loaded.data.get());
    const long long steps = std::llround(scene.duration / scene.options.dt);
    for (long long k = 1; k <= steps; ++k)
    {
        scene.world.step(scene.options);
        stepper.step(loaded.model.get(), loaded.data.get());
        ASSERT_EQ(stepper.world().stateHash(), scene.world.stateHash()) << "step " << k;
    }
}

INSTANTIATE_TEST_SUITE_P(BallScenes, DropInStepperWorld, ::testing::ValuesIn(kBallScenes));
INSTANTIATE_TEST_SUITE_P(InclineScenes, DropInStepperWorld, ::testing::ValuesIn(kInclineScenes));

TEST(DropInStepper, HonoursEditsMadeOnTheMuJoCoSide)
{
    io::Scene scene = test::loadReferenceScene("ball_drop_damped");
    const Loaded loaded = loadExported(scene);
    const mjModel* m = loaded.model.get();
    mjData* d = loaded.data.get();
    for (int k = 0; k < 100; ++k)
    {
        step(m, d);
    }
    // throw the ball up from 1 m: it must follow that, not the state the stepper last wrote
    d->qpos[2] = 1.0;
    d->qvel[2] = 3.0;
    step(m, d);
    const Real dt = m->opt.timestep;
    const Real vz = 3.0 - 9.81 * dt;
    EXPECT_NEAR(d->qvel[2], vz, 1e-12);
    EXPECT_NEAR(d->qpos[2], 1.0 + vz * dt, 1e-12);
    // and MuJoCo's own kinematics (mj_forward after the step) place the geom there
    EXPECT_NEAR(d->geom_xpos[3 * 1 + 2], d->qpos[2], 1e-15);
    forget(m, d);
}

// A hand-written model whose body frame is not its inertial frame, spinning in free space.
const char* const kOffsetModel = R"(<mujoco>
  <option gravity="0 0 0" timestep="0.001"/>
  <worldbody>
    <body name="rod" pos="0.3 -0.2 1" quat="0.9 0.1 0.3 0.2">
      <freejoint/>
      <geom name="rod" type="capsule" size="0.05 0.2" pos="0.1 0 0" zaxis="1 0 0" density="1000"/>
    </body>
  </worldbody>
</mujoco>)";

TEST(FreeJointConventions, MatchMuJoCoForATorqueFreeSymmetricTop)
{
    // A capsule is a symmetric top; this one's centre of mass and axes are offset from its body
    // frame (the body origin lies on its axis). MuJoCo integrates its own free joint, impulse the
    // translated body. Spinning about the symmetry axis, the angular velocity is constant and the
    // body origin does not circle, so both integrators are exact up to round-off and must agree;
    // reading the body-frame velocity as world-frame, or dropping the inertial offset, would put
    // them centimetres apart.
    const ModelPtr model = loadModelFromString(kOffsetModel, "offset");
    const mjModel* m = model.get();
    const DataPtr ours(mj_makeData(m));
    const DataPtr theirs(mj_makeData(m));
    // spin about the capsule axis: in the body frame that is R(iquat) e_z
    const Quat iquat(m->body_iquat[4], m->body_iquat[5], m->body_iquat[6], m->body_iquat[7]);
    const Vec3 axisBody = iquat.toRotationMatrix().col(2);
    for (mjData* d : {ours.get(), theirs.get()})
    {
        d->qvel[0] = 0.5;
        d->qvel[1] = -0.2;
        d->qvel[2] = 0.1;
        for (int i = 0; i < 3; ++i)
        {
            d->qvel[3 + i] = 7.0 * axisBody[i];
        }
        mj_forward(m, d);
    }
    Stepper stepper(m, ours.get());
    ASSERT_TRUE(stepper.translation().links.at(0).offset);
    for (int k = 0; k < 1000; ++k)
    {
        stepper.step(m, ours.get());
        mj_step(m, theirs.get());
    }
    mj_forward(m, theirs.get());
    for (int i = 0; i < 3; ++i)
    {
        EXPECT_NEAR(ours->xipos[3 + i], theirs->xipos[3 + i], 1e-9) << "centre of mass " << i;
        EXPECT_NEAR(ours->qpos[i], theirs->qpos[i], 1e-9) << "body origin " << i;
        EXPECT_NEAR(ours->qvel[3 + i], theirs->qvel[3 + i], 1e-9) << "body-frame angular velocity " << i;
    }
    const Quat a(ours->qpos[3], ours->qpos[4], ours->qpos[5], ours->qpos[6]);
    const Quat b(theirs->qpos[3], theirs->qpos[4], theirs->qpos[5], theirs->qpos[6]);
    EXPECT_LT(a.angularDistance(b), 1e-9);
    // the impulse body sits on MuJoCo's centre of mass with MuJoCo's mass and inertia
    const BodyState s = stepper.world().state(stepper.translation().links[0].body);
    for (int i = 0; i < 3; ++i)
    {
        EXPECT_NEAR(s.position[i], ours->xipos[3 + i], 1e-12);
    }
    EXPECT_EQ(stepper.world().mass(stepper.translation().links[0].body), m->body_mass[1]);
}

TEST(FreeJointConventions, ReadAndWriteAreInverse)
{
    const ModelPtr model = loadModelFromString(kOffsetModel, "offset");
    const DataPtr data(mj_makeData(model.get()));
    data->qvel[0] = 0.3;
    data->qvel[4] = -2.0;
    data->qvel[5] = 1.5;
    const Translation t = translate(model.get(), data.get(), "offset");
    const Translation::Link& link = t.links.at(0);
    const LinkState s = readLink(link, model.get(), data.get());
    const DataPtr copy(mj_makeData(model.get()));
    writeLink(link, {s.position, s.orientation, s.linearVelocity, s.angularVelocity, Vec3::Zero()}, model.get(),
              copy.get());
    for (int i = 0; i < 7; ++i)
    {
        EXPECT_NEAR(copy->qpos[i], data->qpos[i], 1e-15) << "qpos " << i;
    }
    for (int i = 0; i < 6; ++i)
    {
        EXPECT_NEAR(copy->qvel[i], data->qvel[i], 1e-15) << "qvel " << i;
    }
}

std::string refusal(const std::string& file)
{
    const std::string path = std::string(IMPULSE_TEST_DATA_DIR) + "/mujoco/" + file;
    try
    {
        io::Scene scene = loadMjcfScene(path);
    }
    catch (const ModelError& error)
    {
        const std::string message = error.what();
        EXPECT_EQ(message.rfind(path + ": ", 0), 0u) << "the message names the file: " << message;
        return message.substr(path.size() + 2);
    }
    return "not refused";
}

TEST(Refusal, HingeJointIsRefusedWithTheDocumentedMessage)
{
    EXPECT_EQ(refusal("hinge.xml"), "the model uses what impulse does not simulate:\n"
                                    "  - hinge joint 'hinge' on body 'arm': impulse simulates free bodies only");
}

TEST(Refusal, EverythingUnsupportedIsListedAtOnce)
{
    EXPECT_EQ(refusal("unsupported.xml"),
              "the model uses what impulse does not simulate:\n"
              "  - 1 actuator(s): impulse simulates no actuators\n"
              "  - 1 tendon(s): impulse simulates no tendons\n"
              "  - 1 equality constraint(s): impulse simulates no equality constraints\n"
              "  - slide joint 'rail' on body 'slider': impulse simulates free bodies only\n"
              "  - free body 'dumbbell' has 2 colliding geoms ('left', 'right'): an impulse body has exactly one "
              "shape\n"
              "  - cylinder geom 'can': impulse has no such shape (it has sphere, box, capsule, plane and mesh)");
}

TEST(Refusal, MeshThatIsNotAClosedSolidNamesTheGeomTheMeshAndTheReason)
{
    EXPECT_EQ(refusal("open_mesh.xml"),
              "the model uses what impulse does not simulate:\n"
              "  - mesh geom 'box' (mesh 'open_box'): not a closed solid: not closed: the edge from (0.587499976, "
              "-0.5, 0.5) to (0.587499976, 0.5, 0.5) of triangle 3 has no neighbour across it (a hole in the "
              "surface)");
}

TEST(Warnings, NoModelThatLoadsWarns)
{
    // the test models impulse simulates, and the example model; the others are refused above
    std::vector<std::string> paths{std::string(IMPULSE_SCENES_DIR) + "/../examples/falling_shapes.xml"};
    for (const auto& entry : std::filesystem::directory_iterator(std::string(IMPULSE_TEST_DATA_DIR) + "/mujoco"))
    {
        paths.push_back(entry.path().string());
    }
    int loaded = 0;
    for (const std::string& path : paths)
    {
        io::Scene scene;
        try
        {
            scene = loadMjcfScene(path);
        }
        catch (const ModelError&)
        {
            continue;
        }
        ++loaded;
        for (const Warning& warning : scene.world.warnings(scene.options, scene.bodyNames))
        {
            ADD_FAILURE() << path << ": " << warning.message;
        }
    }
    EXPECT_GE(loaded, 2);
}

// Largest |signed distance| of the `reference` mesh's vertices, placed by `referencePose`, from the
// surface of `mesh` placed by `pose`: zero when both put the same surface in the same place.
Real surfaceMismatch(const MeshGeometry& mesh, const Pose& pose, const std::vector<Vec3>& reference,
                     const Pose& referencePose)
{
    Real worst = 0.0;
    for (const Vec3& vertex : reference)
    {
        worst = std::max(worst, std::abs(mesh.signedDistance(pose.toLocal(referencePose.toWorld(vertex))).phi));
    }
    return worst;
}

Pose poseOf(const World& world, BodyId id)
{
    const BodyState s = world.state(id);
    return Pose::from(s.position, s.orientation);
}

// The inertia tensor of a body in world axes.
Mat3 worldInertia(const World& world, BodyId id)
{
    const Mat3 r = world.state(id).orientation.toRotationMatrix();
    return r * world.principalInertia(id).asDiagonal() * r.transpose();
}

// MuJoCo stores mesh vertices as float, recentred on the centre of mass and principal axes: every
// coordinate carries a relative rounding of up to 6e-8, so volumes and moments computed from them
// agree with the double-precision ones to about 1e-7 relative and positions to about 1e-7 m for
// meshes of about a metre. The tolerances below leave a factor of ten above that.
constexpr Real kFloatRelative = 1e-6;
constexpr Real kFloatLength = 1e-6; // m

TEST(MeshGeoms, TranslateWithTheMassPropertiesAndPlacementOfTheMesh)
{
    const std::string path = std::string(IMPULSE_TEST_DATA_DIR) + "/mujoco/mesh.xml";
    const ModelPtr model = loadModel(path);
    DataPtr data(mj_makeData(model.get()));
    mj_forward(model.get(), data.get());
    const Translation t = translate(model.get(), data.get(), path);
    ASSERT_EQ(t.world.bodyCount(), 4u); // ground, peg, lower, upper
    ASSERT_EQ(t.dynamicBodies.size(), 2u);

    // the peg: a static mesh body where the geom puts the file's vertices
    const BodyId peg{1};
    EXPECT_FALSE(t.world.isDynamic(peg));
    const auto* pegMesh = std::get_if<Mesh>(&t.world.shape(peg));
    ASSERT_NE(pegMesh, nullptr);
    const TriangleMesh pegFile = io::readMeshFile(std::string(IMPULSE_SCENES_DIR) + "/meshes/peg.obj");
    const int pegGeom = mj_name2id(model.get(), mjOBJ_GEOM, "peg");
    mjtNum pegQuat[4];
    mju_mat2Quat(pegQuat, data->geom_xmat + 9 * pegGeom);
    // the geom's frame is MuJoCo's recentred mesh frame: the file's frame is the world pose of the
    // geom as the MJCF states it
    const Pose pegFilePose = Pose::from(Vec3(0.3, -0.2, 0.01), Quat(0.9962, 0.0436, 0.0755, 0).normalized());
    EXPECT_LT(surfaceMismatch(*pegMesh->geometry, poseOf(t.world, peg), pegFile.vertices, pegFilePose), kFloatLength);

    // the tori: one geometry for both, volume and inertia per unit mass those of the scaled file
    TriangleMesh torusFile = io::readMeshFile(std::string(IMPULSE_SCENES_DIR) + "/meshes/torus.obj");
    for (Vec3& v : torusFile.vertices)
    {
        v.z() *= 1.5;
    }
    const auto expected = MeshGeometry::build(torusFile);
    const auto* lower = std::get_if<Mesh>(&t.world.shape(t.dynamicBodies[0]));
    const auto* upper = std::get_if<Mesh>(&t.world.shape(t.dynamicBodies[1]));
    ASSERT_NE(lower, nullptr);
    ASSERT_NE(upper, nullptr);
    EXPECT_EQ(lower->geometry, upper->geometry) << "one MeshGeometry per MuJoCo mesh";
    EXPECT_NEAR(lower->geometry->volume(), expected->volume(), kFloatRelative * expected->volume());
    const Real densities[] = {1000.0, 500.0}; // MuJoCo's default density, and the upper geom's
    for (std::size_t k = 0; k < 2; ++k)
    {
        SCOPED_TRACE("torus " + std::to_string(k));
        const BodyId id = t.dynamicBodies[k];
        const Real mass = densities[k] * expected->volume();
        EXPECT_NEAR(t.world.mass(id), mass, kFloatRelative * mass);
        // the same principal moments (the axes each finds may come in another order)
        Vec3 inertia = mass * expected->unitInertia();
        Vec3 moments = t.world.principalInertia(id);
        std::sort(inertia.begin(), inertia.end());
        std::sort(moments.begin(), moments.end());
        EXPECT_LT((moments - inertia).norm(), kFloatRelative * inertia.norm()) << moments.transpose();
        // the body sits at MuJoCo's centre of mass, and the surface where the geom puts the file
        const int body = t.links[k].mjBody;
        EXPECT_LT((t.world.state(id).position - vecOf(data->xipos + 3 * body)).norm(), kFloatLength);
        const Pose bodyPose = Pose::from(vecOf(data->xpos + 3 * body), quatOf(data->xquat + 4 * body));
        const Pose geomInBody = k == 0 ? Pose::from(Vec3(0.1, 0.2, -0.3), Quat(0.7, 0, 0.7, 0.1).normalized()) : Pose{};
        const Pose filePose =
            Pose::from(bodyPose.toWorld(geomInBody.position), bodyPose.orientation * geomInBody.orientation);
        EXPECT_LT(surfaceMismatch(*lower->geometry, poseOf(t.world, id), torusFile.vertices, filePose), kFloatLength);
    }
}

void expectSameMeshBodies(const io::Scene& scene)
{
    const Loaded loaded = loadExported(scene);
    const Translation t = translate(loaded.model.get(), loaded.data.get(), "exported");
    ASSERT_EQ(t.world.bodyCount(), scene.world.bodyCount());
    ASSERT_EQ(t.dynamicBodies.size(), scene.dynamicBodies.size());
    std::vector<BodyId> sceneOrder;
    for (std::uint32_t i = 0; i < scene.world.bodyCount(); ++i)
    {
        if (!scene.world.isDynamic(BodyId{i}))
        {
            sceneOrder.push_back(BodyId{i});
        }
    }
    sceneOrder.insert(sceneOrder.end(), scene.dynamicBodies.begin(), scene.dynamicBodies.end());
    std::size_t meshes = 0;
    for (std::uint32_t i = 0; i < t.world.bodyCount(); ++i)
    {
        const BodyId ours{i};
        const BodyId theirs = sceneOrder[i];
        SCOPED_TRACE("body " + std::to_string(i));
        EXPECT_EQ(t.world.isDynamic(ours), scene.world.isDynamic(theirs));
        const auto* mesh = std::get_if<Mesh>(&t.world.shape(ours));
        const auto* original = std::get_if<Mesh>(&scene.world.shape(theirs));
        ASSERT_EQ(mesh != nullptr, original != nullptr);
        if (mesh == nullptr)
        {
            EXPECT_TRUE(sameShape(t.world.shape(ours), scene.world.shape(theirs)));
            continue;
        }
        ++meshes;
        const MeshGeometry& a = *mesh->geometry;
        const MeshGeometry& b = *original->geometry;
        EXPECT_NEAR(a.volume(), b.volume(), kFloatRelative * b.volume());
        // the same surface in the same place, both ways round
        const Real size = b.boundingRadius();
        EXPECT_LT(surfaceMismatch(a, poseOf(t.world, ours), b.vertices(), poseOf(scene.world, theirs)),
                  kFloatRelative * size);
        EXPECT_LT(surfaceMismatch(b, poseOf(scene.world, theirs), a.vertices(), poseOf(t.world, ours)),
                  kFloatRelative * size);
        EXPECT_LT((t.world.state(ours).position - scene.world.state(theirs).position).norm(), kFloatRelative * size);
        if (!scene.world.isDynamic(theirs))
        {
            continue;
        }
        // the mass is the scene's exactly (the export's explicit inertial); the moments too, but
        // expressed on principal axes found again from MuJoCo's float vertices, which may turn
        // within a plane of equal moments: compare the world-frame tensors
        EXPECT_EQ(t.world.mass(ours), scene.world.mass(theirs));
        const Mat3 inertia = worldInertia(scene.world, theirs);
        EXPECT_LT((worldInertia(t.world, ours) - inertia).norm(), kFloatRelative * inertia.norm());
        const BodyState s = t.world.state(ours);
        const BodyState r = scene.world.state(theirs);
        // the centre of mass found again may move by the position tolerance, and with it the velocity
        // by omega times that; the angular momentum follows the moments
        const Real omega = scene.bodyDefs[theirs.index].angularVelocity.norm();
        EXPECT_LT((s.linearVelocity - r.linearVelocity).norm(), omega * kFloatRelative * size + 1e-12);
        EXPECT_LT((s.angularMomentum - r.angularMomentum).norm(), kFloatRelative * r.angularMomentum.norm() + 1e-12);
    }
    EXPECT_GT(meshes, 0u);
}

class MeshExportRoundTrip : public ::testing::TestWithParam<std::string>
{
};

TEST_P(MeshExportRoundTrip, GivesTheSameBodiesMassesInertiasAndPlacements)
{
    expectSameMeshBodies(test::loadReferenceScene(GetParam()));
}

INSTANTIATE_TEST_SUITE_P(MeshScenes, MeshExportRoundTrip, ::testing::Values("ring_on_peg", "tori_stack"));

// An L-shaped block, whose centre of mass is off the file's origin and whose principal axes are
// turned from the file's axes, scaled unevenly, tilted and moving, and the same file static: the
// geom's placement in the export is what puts it back where it was.
TEST(ExportRoundTrip, OffCentreScaledMeshes)
{
    const char* const text = R"({"name": "blocks", "dt": 0.001, "duration": 1.0,
 "materials": {"default": {"restitution": 0.1, "friction": 0.5}},
 "bodies": [
  {"name": "fixed", "static": true, "shape": {"type": "mesh", "file": "meshes/l_block.obj"},
   "position": [1, 2, 0], "orientation": {"axis": [0, 1, 1], "angle_deg": 25}, "material": "default"},
  {"name": "block", "shape": {"type": "mesh", "file": "meshes/l_block.obj", "scale": [1.5, 0.5, 2],
   "resolution": 24}, "mass": 2, "position": [0.3, -0.1, 1], "orientation": {"axis": [1, 2, 3], "angle_deg": 70},
   "velocity": [1, 0, 0], "angular_velocity": [0, 0, 2], "material": "default"}]})";
    const io::Scene scene = io::parseScene(text, "blocks", IMPULSE_SCENES_DIR);
    expectSameMeshBodies(scene);
    EXPECT_NE(exportMjcf(scene).find("<numeric name=\"impulse_mesh_resolution:mesh_l_block_1\" data=\"24\"/>"),
              std::string::npos);
}

// An inertia whose principal axes are not the geom's (products of inertia, as a real crate with its
// load to one side has): MuJoCo's compiler diagonalises it, and the translation puts the whole
// tensor back on the geom's axes; the export writes it as fullinertia, and it comes back.
TEST(InertiaTensor, ProductsOfInertiaSurviveTranslationAndExport)
{
    const char* const model = R"(<mujoco>
  <worldbody>
    <body name="crate" pos="0 0 1" quat="0.9 0.1 0.3 0.2">
      <freejoint/>
      <inertial pos="0 0 0" mass="2" fullinertia="0.03 0.02 0.04 0.005 0 -0.002"/>
      <geom name="crate" type="box" size="0.1 0.15 0.2"/>
    </body>
  </worldbody>
</mujoco>)";
    Mat3 given;
    given << 0.03, 0.005, 0.0, 0.005, 0.02, -0.002, 0.0, -0.002, 0.04;
    const ModelPtr loaded = loadModelFromString(model, "crate");
    const DataPtr data(mj_makeData(loaded.get()));
    mj_forward(loaded.get(), data.get());
    const Translation t = translate(loaded.get(), data.get(), "crate");
    ASSERT_EQ(t.dynamicBodies.size(), 1u);
    // MuJoCo's compiler diagonalises with an iterative eigen-solver, to about 1e-10 of the largest
    // moment (0.04); dropping the products would be off by 0.005
    constexpr Real kCompiled = 1e-9 * 0.04;
    EXPECT_LT((t.world.inertia(t.dynamicBodies[0]) - given).cwiseAbs().maxCoeff(), kCompiled)
        << t.world.inertia(t.dynamicBodies[0]);

    const char* const scene = R"({"name": "crate", "dt": 0.001, "duration": 1.0,
 "materials": {"default": {"restitution": 0.1, "friction": 0.5}},
 "bodies": [{"name": "crate", "shape": {"type": "box", "half_extents": [0.1, 0.15, 0.2]}, "mass": 2,
   "inertia": [[0.03, 0.005, 0], [0.005, 0.02, -0.002], [0, -0.002, 0.04]], "position": [0, 0, 1],
   "angular_velocity": [1, 2, 3], "material": "default"}]})";
    const io::Scene original = io::parseScene(scene, "crate");
    ASSERT_NE(exportMjcf(original).find("fullinertia="), std::string::npos);
    const Loaded exported = loadExported(original);
    const Translation back = translate(exported.model.get(), exported.data.get(), "exported");
    ASSERT_EQ(back.dynamicBodies.size(), 1u);
    EXPECT_LT((back.world.inertia(back.dynamicBodies[0]) - given).cwiseAbs().maxCoeff(), kCompiled);
    // L = I w with the same w: off by what the tensor is
    const Vec3 momentum = original.world.state(original.dynamicBodies[0]).angularMomentum;
    EXPECT_LT((back.world.state(back.dynamicBodies[0]).angularMomentum - momentum).norm(), 1e-9 * momentum.norm());
}

// A box weighted off its centre (an <inertial> whose pos is not the geom's), spinning about a
// principal axis in free space: the impulse body sits on MuJoCo's centre of mass with the box where
// MuJoCo's geom is, and stays so. About a principal axis through the body origin w is constant and
// the origin does not circle, so both integrators are exact to round-off; a box placed at the
// centre of mass would be 5 cm off.
TEST(WeightedBody, TheShapeStaysWhereMuJoCosGeomIs)
{
    const char* const model = R"(<mujoco>
  <option gravity="0 0 0" timestep="0.001"/>
  <worldbody>
    <body name="crate" pos="0.2 0 1" quat="0.9 0.1 0.3 0.2">
      <freejoint/>
      <inertial pos="0 0 0.05" mass="2" diaginertia="0.02 0.03 0.04"/>
      <geom name="crate" type="box" size="0.1 0.15 0.2" pos="0 0 0" quat="1 0 0 0"/>
    </body>
  </worldbody>
</mujoco>)";
    const ModelPtr loaded = loadModelFromString(model, "crate");
    const mjModel* m = loaded.get();
    const DataPtr ours(mj_makeData(m));
    const DataPtr theirs(mj_makeData(m));
    for (mjData* d : {ours.get(), theirs.get()})
    {
        d->qvel[0] = 0.3;
        d->qvel[5] = 4.0; // about the body z axis, a principal axis
        mj_forward(m, d);
    }
    Stepper stepper(m, ours.get());
    const BodyId body = stepper.translation().links.at(0).body;
    EXPECT_EQ(stepper.world().centerOfMass(body), Vec3(0.0, 0.0, 0.05));
    for (int k = 0; k < 1000; ++k)
    {
        stepper.step(m, ours.get());
        mj_step(m, theirs.get());
    }
    mj_forward(m, theirs.get());
    const Pose box = stepper.world().shapePose(body);
    const Vec3 geom = vecOf(theirs->geom_xpos);
    EXPECT_LT((box.position - geom).norm(), 1e-9) << box.position.transpose() << " vs " << geom.transpose();
    EXPECT_LT((stepper.world().state(body).position - vecOf(theirs->xipos + 3)).norm(), 1e-9);
}

TEST(WeightedBody, ACentreOfMassOffTheShapeSurvivesExport)
{
    const char* const scene = R"({"name": "weighted", "dt": 0.001, "duration": 1.0,
 "materials": {"default": {"restitution": 0.1, "friction": 0.5}},
 "bodies": [{"name": "crate", "shape": {"type": "box", "half_extents": [0.1, 0.15, 0.2]}, "mass": 2,
   "center_of_mass": [0.03, -0.04, 0.05], "position": [0, 0, 1], "orientation": {"axis": [1, 2, 3], "angle_deg": 40},
   "angular_velocity": [1, 2, 3], "material": "default"}]})";
    const io::Scene original = io::parseScene(scene, "weighted");
    const BodyId body = original.dynamicBodies.at(0);
    const Loaded exported = loadExported(original);
    const Translation back = translate(exported.model.get(), exported.data.get(), "exported");
    ASSERT_EQ(back.dynamicBodies.size(), 1u);
    const BodyId again = back.dynamicBodies[0];
    EXPECT_LT((back.world.centerOfMass(again) - original.world.centerOfMass(body)).norm(), 1e-12);
    EXPECT_LT((back.world.shapePose(again).position - original.world.shapePose(body).position).norm(), 1e-12);
    EXPECT_LT((back.world.state(again).position - original.world.state(body).position).norm(), 1e-12);
    EXPECT_LT((back.world.state(again).linearVelocity - original.world.state(body).linearVelocity).norm(), 1e-12);
    EXPECT_LT((back.world.inertia(again) - original.world.inertia(body)).norm(), 1e-9);
}

TEST(MeshGeoms, ExportWithoutTheMeshFileIsRefused)
{
    io::Scene scene = test::loadReferenceScene("ring_on_peg");
    scene.meshSources.clear();
    try
    {
        (void)exportMjcf(scene);
        ADD_FAILURE() << "not refused";
    }
    catch (const std::invalid_argument& error)
    {
        EXPECT_NE(std::string(error.what()).find("body peg: a mesh is exported as its file"), std::string::npos)
            << error.what();
    }
}

TEST(Refusal, MuJoCoParseErrorsNameTheFile)
{
    EXPECT_THROW(loadModelFromString("<mujoco><worldbody><geom type=\"sphere\"", "broken.xml"), ModelError);
    try
    {
        loadModelFromString("<mujoco><nonsense/></mujoco>", "broken.xml");
        ADD_FAILURE() << "not refused";
    }
    catch (const ModelError& error)
    {
        EXPECT_EQ(std::string(error.what()).rfind("broken.xml: MuJoCo cannot load it: ", 0), 0u) << error.what();
    }
}

TEST(Restitution, CustomFieldsAndDefault)
{
    const char* xml = R"(<mujoco>
  <custom>
    <numeric name="impulse_restitution:bouncy" data="0.9"/>
  </custom>
  <worldbody>
    <geom name="ground" type="plane" size="0 0 1" friction="0.4 0 0"/>
    <body pos="0 0 1"><freejoint/><geom name="bouncy" type="sphere" size="0.1" friction="0.25 0 0"/></body>
    <body pos="1 0 1"><freejoint/><geom name="dull" type="sphere" size="0.1"/></body>
  </worldbody>
</mujoco>)";
    const ModelPtr model = loadModelFromString(xml, "restitution");
    const DataPtr data(mj_makeData(model.get()));
    const Translation t = translate(model.get(), data.get(), "restitution");
    ASSERT_EQ(t.world.bodyCount(), 3u);
    EXPECT_EQ(t.world.material(t.world.material(BodyId{0})).restitution, kDefaultRestitution);
    EXPECT_EQ(t.world.material(t.world.material(BodyId{0})).friction, 0.4);
    EXPECT_EQ(t.world.material(t.world.material(BodyId{1})).restitution, 0.9);
    EXPECT_EQ(t.world.material(t.world.material(BodyId{1})).friction, 0.25);
    EXPECT_EQ(t.world.material(t.world.material(BodyId{2})).restitution, kDefaultRestitution);
    EXPECT_EQ(t.world.material(t.world.material(BodyId{2})).friction, 1.0); // MuJoCo's default friction
}

TEST(Softness, DampedOscillatorBouncesBackWithTheAskedRestitution)
{
    // a unit-mass spring-damper x'' = -k x - b x' entered at speed 1 leaves, half a damped period
    // later, at exp(-zeta pi / sqrt(1 - zeta^2)): the mapping must invert that
    for (const Real eps : {0.1, 0.5, 0.9, 1.0})
    {
        const Softness s = contactSoftness(eps, 2e-3);
        const Real w0 = std::sqrt(s.stiffness);
        const Real zeta = s.damping / (2.0 * w0);
        EXPECT_NEAR(std::exp(-zeta * std::numbers::pi / std::sqrt(1.0 - zeta * zeta)), eps, 1e-12);
        EXPECT_NEAR(w0, 500.0, 1e-9); // 1 / timeconst
    }
    EXPECT_EQ(dampingRatioFor(0.0), 1.0); // critically damped: no bounce
}

} // namespace
} // namespace impulse::mujoco
