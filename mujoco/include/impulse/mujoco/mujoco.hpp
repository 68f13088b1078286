// SPDX-License-Identifier: MIT
// impulse_mujoco: MJCF models run with impulse's time step, MuJoCo as the loader and the reference.
//
// An MJCF file is parsed and compiled by MuJoCo itself; every body with a free joint becomes an
// impulse body with the compiled mass and inertia, every geom welded to the world a static body.
// `step(m, d)` is a drop-in for mj_step that advances the free bodies with impulse's scheme and
// writes qpos and qvel back in MuJoCo's conventions. See docs/mujoco.md.
#pragma once

#include <impulse/io/scene.hpp>
#include <impulse/mesh.hpp>
#include <impulse/world.hpp>

#include <filesystem>
#include <memory>
#include <mujoco/mujoco.h>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

namespace impulse::mujoco
{

/// A model that cannot be loaded or uses what impulse does not simulate. The message names the
/// file and lists every problem found, one per line after the first.
class ModelError : public std::runtime_error
{
  public:
    using std::runtime_error::runtime_error;
};

struct ModelDeleter
{
    void operator()(mjModel* m) const { mj_deleteModel(m); }
};
struct DataDeleter
{
    void operator()(mjData* d) const { mj_deleteData(d); }
};
using ModelPtr = std::unique_ptr<mjModel, ModelDeleter>;
using DataPtr = std::unique_ptr<mjData, DataDeleter>;

/// Parses and compiles an MJCF file with MuJoCo. Throws ModelError with MuJoCo's message.
ModelPtr loadModel(const std::filesystem::path& path);
/// The same for MJCF text held in memory; `source` names it in messages.
ModelPtr loadModelFromString(const std::string& xml, const std::string& source);

/// Names of the MJCF custom fields impulse reads (`<custom><numeric name=... data=.../>`).
namespace custom
{
inline constexpr const char* kRestitution = "impulse_restitution"; ///< model default, else 0
/// Prefix of a geom's own restitution, "impulse_restitution:GEOM", and of the restitution of an
/// explicit <pair>, "impulse_restitution:GEOM1:GEOM2".
inline constexpr const char* kGeomRestitutionPrefix = "impulse_restitution:";
/// Prefix of a plane's exact normal and offset, "impulse_plane:GEOM" = (nx, ny, nz, offset).
inline constexpr const char* kPlanePrefix = "impulse_plane:";
inline constexpr const char* kDuration = "impulse_duration"; ///< seconds, for `impulse run`
/// Prefix of a mesh asset's signed distance grid resolution, "impulse_mesh_resolution:MESH" (0 or
/// 4..1024 cells along the longest side, as the scene format's "resolution"; 0 if absent).
inline constexpr const char* kMeshResolutionPrefix = "impulse_mesh_resolution:";
} // namespace custom

/// Restitution a model gets for a geom that states none: 0, which is also how MuJoCo's default
/// contact (critically damped, solref dampratio 1) behaves.
inline constexpr Real kDefaultRestitution = 0.0;

/// An MJCF model translated into an impulse world.
struct Translation
{
    /// One free MuJoCo body and its impulse body. The impulse body sits at the body's centre of
    /// mass with its axes on the inertial frame: x = p + R(q) ipos, q_impulse = q iquat.
    struct Link
    {
        int mjBody = 0;
        int qposAddress = 0;
        int dofAddress = 0;
        BodyId body;
        Vec3 inertialPosition = Vec3::Zero();        ///< body_ipos
        Quat inertialOrientation = Quat::Identity(); ///< body_iquat
        bool offset = false;                         ///< the inertial frame is not the body frame
    };

    std::string name;
    World world;
    StepOptions options;
    std::optional<Real> duration;       ///< from the impulse_duration custom field
    std::vector<Link> links;            ///< free bodies in MuJoCo body order
    std::vector<BodyId> dynamicBodies;  ///< links[k].body
    std::vector<std::string> bodyNames; ///< per world body: the geom's name (static) or the body's
};

/// Translates a compiled model, its free bodies placed as `d` says (qpos, qvel). Throws ModelError
/// listing everything unsupported: joints other than free, actuators, tendons, equality
/// constraints, bodies with several joints or nested free bodies, several colliding geoms on one
/// body, geom types impulse has no shape for, meshes that are not closed solids. A mesh geom becomes
/// a Mesh shape built from the compiled mesh (one MeshGeometry per MuJoCo mesh), its body at the
/// mesh's centre of mass on its principal axes as placed by the geom.
Translation translate(const mjModel* m, const mjData* d, const std::string& source);

/// Loads an MJCF file as `impulse run` uses it: translated, starting from keyframe 0 if the model
/// has one (else qpos0 at rest), dt from the model's timestep, duration from impulse_duration.
io::Scene loadMjcfScene(const std::filesystem::path& path);

/// The closed solid of MuJoCo mesh `mesh` as impulse prepares it: MuJoCo's compiled vertices (float,
/// in its mesh frame, already recentred on the centre of mass and principal axes) and faces.
/// Throws MeshError with the reason when the mesh is not a closed solid.
std::shared_ptr<const MeshGeometry> meshGeometry(const mjModel* m, int mesh, int resolution = 0);
/// The refusal of mesh geom `geom` whose mesh is not a closed solid, with MeshError's reason.
std::string meshGeomProblem(const mjModel* m, int geom, const std::string& reason);
/// How far (relative to the geom's bounding radius, and to the largest principal moment) the mesh's
/// centre of mass and principal axes found by MeshGeometry may lie from the compiled inertial frame
/// of its free body: MuJoCo stores mesh vertices as float (relative precision 6e-8).
inline constexpr Real kMeshFrameTolerance = 1e-5;

/// World-frame state of the centre of mass of link `k`, read from qpos and qvel.
struct LinkState
{
    Vec3 position;
    Quat orientation;
    Vec3 linearVelocity;
    Vec3 angularVelocity;
};
LinkState readLink(const Translation::Link& link, const mjModel* m, const mjData* d);
/// Writes a world-frame centre-of-mass state into qpos and qvel (free-joint angular velocity in
/// the body frame, linear velocity of the body origin).
void writeLink(const Translation::Link& link, const BodyState& state, const mjModel* m, mjData* d);

/// Keeps an impulse world in step with one mjModel/mjData pair. Each call first reads qpos and qvel
/// into the world if they differ from what the last call left there (so edits made on the MuJoCo
/// side are honoured, and untouched states carry on bit for bit), takes one impulse step of
/// m->opt.timestep, writes qpos, qvel and time back, and runs mj_forward so that positions, sensors
/// and rendering see the new state. mj_forward renormalises the free-joint quaternions in qpos (an
/// ulp or two); the world keeps its own, so the run is bit for bit that of the impulse world.
class Stepper
{
  public:
    Stepper(const mjModel* m, const mjData* d, const std::string& source = "model");
    void step(const mjModel* m, mjData* d);
    const Translation& translation() const { return m_translation; }
    World& world() { return m_translation.world; }

  private:
    void pull(const mjModel* m, const mjData* d);
    Translation m_translation;
    std::vector<mjtNum> m_writtenQpos;
    std::vector<mjtNum> m_writtenQvel;
    Vec3 m_gravity;
};

/// Drop-in for mj_step: one impulse step of the model's free bodies under gravity and contact
/// (qfrc_applied and xfrc_applied are not forces impulse applies). The first call for a given
/// (m, d) translates the model (throwing ModelError if it uses what impulse does not simulate) and
/// keeps a Stepper for the pair until `forget(m, d)`; call it before mj_deleteData/mj_deleteModel,
/// since a new pair allocated at the same addresses would otherwise inherit the old world.
void step(const mjModel* m, mjData* d);
void forget(const mjModel* m, const mjData* d);

/// The contact softness the MuJoCo side of a comparison uses for restitution eps: solref = (-k, -b)
/// (MuJoCo's direct stiffness and damping), k = w^2, b = 2 zeta w, with w = 1 / timeconst and
/// zeta = -ln(eps) / sqrt(pi^2 + ln(eps)^2), the damping ratio whose damped oscillator bounces
/// back with eps (zeta = 1 for eps = 0, where this is MuJoCo's solref (timeconst, 1); zeta = 0 for
/// eps = 1). docs/mujoco.md.
struct Softness
{
    Real stiffness = 0.0; ///< k, 1/s^2
    Real damping = 0.0;   ///< b, 1/s
};
Softness contactSoftness(Real restitution, Real timeconst);
/// The default time constant: 2 dt, the stiffest contact MuJoCo's documentation recommends.
inline Real defaultTimeconst(Real dt)
{
    return 2.0 * dt;
}
Real dampingRatioFor(Real restitution);
/// solimp used with it: impedance 0.99 at any depth, so the contact is the spring-damper solref
/// describes with 1 % of the unconstrained acceleration let through.
inline constexpr const char* kSolimp = "0.99 0.99 0.001 0.5 2";

} // namespace impulse::mujoco
