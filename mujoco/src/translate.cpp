// SPDX-License-Identifier: MIT
// MJCF (compiled by MuJoCo) to an impulse world: what is supported, what is refused, and the
// conversion between MuJoCo's free-joint coordinates and impulse's centre-of-mass states.
#include <impulse/mesh.hpp>
#include <impulse/mujoco/mujoco.hpp>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <map>
#include <numbers>
#include <sstream>

namespace impulse::mujoco
{
namespace
{

std::string nameOf(const mjModel* m, mjtObj type, int id)
{
    const char* name = mj_id2name(m, type, id);
    if (name != nullptr && name[0] != '\0')
    {
        std::string quoted = "'";
        quoted += name;
        quoted += '\'';
        return quoted;
    }
    std::string number = "#";
    number += std::to_string(id);
    return number;
}

std::string plainName(const mjModel* m, mjtObj type, int id)
{
    const char* name = mj_id2name(m, type, id);
    return name != nullptr ? std::string(name) : std::string();
}

const char* geomTypeName(int type)
{
    switch (type)
    {
    case mjGEOM_PLANE:
        return "plane";
    case mjGEOM_HFIELD:
        return "height field";
    case mjGEOM_SPHERE:
        return "sphere";
    case mjGEOM_CAPSULE:
        return "capsule";
    case mjGEOM_ELLIPSOID:
        return "ellipsoid";
    case mjGEOM_CYLINDER:
        return "cylinder";
    case mjGEOM_BOX:
        return "box";
    case mjGEOM_MESH:
        return "mesh";
    default:
        return "unknown";
    }
}

const char* jointTypeName(int type)
{
    switch (type)
    {
    case mjJNT_FREE:
        return "free";
    case mjJNT_BALL:
        return "ball";
    case mjJNT_SLIDE:
        return "slide";
    case mjJNT_HINGE:
        return "hinge";
    default:
        return "unknown";
    }
}

Quat quatAt(const mjtNum* wxyz)
{
    return Quat(wxyz[0], wxyz[1], wxyz[2], wxyz[3]);
}

Vec3 vecAt(const mjtNum* xyz)
{
    return Vec3(xyz[0], xyz[1], xyz[2]);
}

bool colliding(const mjModel* m, int geom)
{
    return m->geom_contype[geom] != 0 || m->geom_conaffinity[geom] != 0;
}

// The model's custom numeric fields by name, and its text fields.
struct Custom
{
    std::map<std::string, std::vector<mjtNum>> numeric;
    std::map<std::string, std::string> text;

    explicit Custom(const mjModel* m)
    {
        for (int i = 0; i < m->nnumeric; ++i)
        {
            const mjtNum* data = m->numeric_data + m->numeric_adr[i];
            numeric[m->names + m->name_numericadr[i]] = std::vector<mjtNum>(data, data + m->numeric_size[i]);
        }
        for (int i = 0; i < m->ntext; ++i)
        {
            text[m->names + m->name_textadr[i]] = std::string(m->text_data + m->text_adr[i]);
        }
    }

    const std::vector<mjtNum>* find(const std::string& name) const
    {
        const auto found = numeric.find(name);
        return found == numeric.end() ? nullptr : &found->second;
    }
};

class Problems
{
  public:
    void add(std::string what) { m_list.push_back(std::move(what)); }
    bool empty() const { return m_list.empty(); }
    [[noreturn]] void raise(const std::string& source) const
    {
        std::string message = source + ": the model uses what impulse does not simulate:";
        for (const std::string& problem : m_list)
        {
            message += "\n  - " + problem;
        }
        throw ModelError(message);
    }

  private:
    std::vector<std::string> m_list;
};

// Restitution of one geom: its own custom field, else the model default, else 0.
Real geomRestitution(const mjModel* m, const Custom& custom, int geom, Problems& problems)
{
    const std::string own = std::string(custom::kGeomRestitutionPrefix) + plainName(m, mjOBJ_GEOM, geom);
    const std::vector<mjtNum>* value = custom.find(own);
    std::string field = own;
    if (value == nullptr)
    {
        value = custom.find(custom::kRestitution);
        field = custom::kRestitution;
    }
    if (value == nullptr)
    {
        return kDefaultRestitution;
    }
    if (value->size() != 1 || !((*value)[0] >= 0.0 && (*value)[0] <= 1.0))
    {
        problems.add("custom numeric '" + field + "' must be one number in [0, 1]");
        return kDefaultRestitution;
    }
    return (*value)[0];
}

// The solver controls that the export writes as custom fields (docs/mujoco.md).
void readSolverOptions(const Custom& custom, StepOptions& options, Problems& problems)
{
    const auto number = [&](const char* name, Real lower, Real upper, auto apply)
    {
        if (const std::vector<mjtNum>* value = custom.find(name))
        {
            if (value->size() != 1 || !((*value)[0] >= lower && (*value)[0] <= upper))
            {
                std::ostringstream range;
                range << "custom numeric '" << name << "' must be one number in [" << lower << ", " << upper << "]";
                problems.add(range.str());
                return;
            }
            apply((*value)[0]);
        }
    };
    number("impulse_collision_iterations", 0, 1e6, [&](Real v) { options.collisionIterations = static_cast<int>(v); });
    number("impulse_contact_iterations", 1, 1e6, [&](Real v) { options.contactIterations = static_cast<int>(v); });
    number("impulse_pair_iterations", 1, 1e6, [&](Real v) { options.pairIterations = static_cast<int>(v); });
    number("impulse_contact_thickness", 0, 1e300, [&](Real v) { options.contactThickness = v; });
    number("impulse_restitution_threshold", 0, 1e300, [&](Real v) { options.restitutionThreshold = v; });
    number("impulse_resting_approach", 0, 1e300, [&](Real v) { options.restingApproach = v; });
    number("impulse_shock_propagation", 0, 1, [&](Real v) { options.shockPropagation = v != 0.0; });
    number("impulse_push_out", 0, 1, [&](Real v) { options.pushOut = v != 0.0; });
    number("impulse_push_out_allowance", 0, 1e300, [&](Real v) { options.pushOutAllowance = v; });
    number("impulse_push_out_speed", 0, 1e300, [&](Real v) { options.pushOutSpeed = v; });
    number("impulse_push_out_iterations", 0, 1e6, [&](Real v) { options.pushOutIterations = static_cast<int>(v); });
    number("impulse_mid_step_restitution", 0, 1, [&](Real v) { options.midStepRestitution = v != 0.0; });
    number("impulse_time_of_impact_geometry", 0, 1, [&](Real v) { options.timeOfImpactGeometry = v != 0.0; });
    if (const auto scheme = custom.text.find("impulse_scheme"); scheme != custom.text.end())
    {
        if (scheme->second == "guendelman")
        {
            options.scheme = Scheme::Guendelman;
        }
        else if (scheme->second == "traditional")
        {
            options.scheme = Scheme::Traditional;
        }
        else
        {
            problems.add("custom text 'impulse_scheme' must be guendelman or traditional, got '" + scheme->second +
                         "'");
        }
    }
    // a misspelt impulse field would silently change the simulation: refuse names not known
    static const char* const known[] = {"impulse_collision_iterations",
                                        "impulse_contact_iterations",
                                        "impulse_pair_iterations",
                                        "impulse_contact_thickness",
                                        "impulse_restitution_threshold",
                                        "impulse_resting_approach",
                                        "impulse_shock_propagation",
                                        "impulse_push_out",
                                        "impulse_push_out_allowance",
                                        "impulse_push_out_speed",
                                        "impulse_push_out_iterations",
                                        "impulse_mid_step_restitution",
                                        "impulse_time_of_impact_geometry",
                                        custom::kRestitution,
                                        custom::kDuration};
    for (const auto& [name, value] : custom.numeric)
    {
        if (name.rfind("impulse_", 0) != 0 || name.rfind(custom::kGeomRestitutionPrefix, 0) == 0 ||
            name.rfind(custom::kPlanePrefix, 0) == 0 || name.rfind(custom::kMeshResolutionPrefix, 0) == 0)
        {
            continue;
        }
        if (std::find_if(std::begin(known), std::end(known), [&](const char* k) { return name == k; }) ==
            std::end(known))
        {
            problems.add("custom numeric '" + name + "' is not a field impulse knows (docs/mujoco.md)");
        }
    }
}

// Rotation that the shape must share with the inertial frame; spheres need none.
// The compiled inertia (principal moments on the inertial frame's axes) as a tensor on the axes of a
// frame with orientation `axes` in the body frame.
Mat3 inertiaOnAxes(const Vec3& moments, const Quat& inertialOrientation, const Quat& axes)
{
    const Mat3 principal = inertialOrientation.normalized().toRotationMatrix();
    const Mat3 turn = axes.toRotationMatrix();
    return turn.transpose() * principal * moments.asDiagonal() * principal.transpose() * turn;
}

// Whether a geom is centred on its body's centre of mass.
bool centred(const mjModel* m, int geom, int body)
{
    const Vec3 offset = vecAt(m->geom_pos + 3 * geom) - vecAt(m->body_ipos + 3 * body);
    const Real scale = std::max<Real>(1.0, m->geom_rbound[geom]);
    return offset.norm() <= 1e-9 * scale;
}

bool sameFrame(const mjModel* m, int geom, int body)
{
    if (!centred(m, geom, body))
    {
        return false;
    }
    if (m->geom_type[geom] == mjGEOM_SPHERE)
    {
        return true;
    }
    const Quat g = quatAt(m->geom_quat + 4 * geom).normalized();
    const Quat i = quatAt(m->body_iquat + 4 * body).normalized();
    return std::abs(std::abs(g.dot(i)) - 1.0) <= 1e-12;
}

} // namespace

std::shared_ptr<const MeshGeometry> meshGeometry(const mjModel* m, int mesh, int resolution)
{
    TriangleMesh triangles;
    const int vertexCount = m->mesh_vertnum[mesh];
    const float* vertices = m->mesh_vert + 3 * static_cast<std::ptrdiff_t>(m->mesh_vertadr[mesh]);
    triangles.vertices.reserve(static_cast<std::size_t>(vertexCount));
    for (int v = 0; v < vertexCount; ++v)
    {
        triangles.vertices.emplace_back(vertices[3 * v], vertices[3 * v + 1], vertices[3 * v + 2]);
    }
    const int faceCount = m->mesh_facenum[mesh];
    const int* faces = m->mesh_face + 3 * static_cast<std::ptrdiff_t>(m->mesh_faceadr[mesh]);
    triangles.triangles.reserve(static_cast<std::size_t>(faceCount));
    for (int f = 0; f < faceCount; ++f)
    {
        std::array<std::uint32_t, 3> face{};
        for (int k = 0; k < 3; ++k)
        {
            const int index = faces[3 * f + k];
            if (index < 0 || index >= vertexCount)
            {
                throw MeshError("face " + std::to_string(f) + " refers to vertex " + std::to_string(index) +
                                ", the mesh has " + std::to_string(vertexCount));
            }
            face[static_cast<std::size_t>(k)] = static_cast<std::uint32_t>(index);
        }
        triangles.triangles.push_back(face);
    }
    return MeshGeometry::build(triangles, MeshOptions{resolution});
}

std::string meshGeomProblem(const mjModel* m, int geom, const std::string& reason)
{
    return "mesh geom " + nameOf(m, mjOBJ_GEOM, geom) + " (mesh " + nameOf(m, mjOBJ_MESH, m->geom_dataid[geom]) +
           "): not a closed solid: " + reason;
}

LinkState readLink(const Translation::Link& link, const mjModel* m, const mjData* d)
{
    (void)m;
    const mjtNum* qpos = d->qpos + link.qposAddress;
    const mjtNum* qvel = d->qvel + link.dofAddress;
    const Vec3 origin = vecAt(qpos);
    const Quat q = quatAt(qpos + 3);
    const Mat3 rotation = q.normalized().toRotationMatrix();
    const Vec3 omega = rotation * vecAt(qvel + 3);
    if (!link.offset)
    {
        return {origin, q, vecAt(qvel), omega};
    }
    const Vec3 lever = rotation * link.inertialPosition;
    return {origin + lever, q * link.inertialOrientation, vecAt(qvel) + omega.cross(lever), omega};
}

void writeLink(const Translation::Link& link, const BodyState& state, const mjModel* m, mjData* d)
{
    (void)m;
    mjtNum* qpos = d->qpos + link.qposAddress;
    mjtNum* qvel = d->qvel + link.dofAddress;
    Vec3 origin = state.position;
    Quat q = state.orientation;
    Vec3 velocity = state.linearVelocity;
    if (link.offset)
    {
        q = state.orientation * link.inertialOrientation.conjugate();
        const Vec3 lever = q.toRotationMatrix() * link.inertialPosition;
        origin = state.position - lever;
        velocity = state.linearVelocity - state.angularVelocity.cross(lever);
    }
    const Vec3 omegaBody = q.toRotationMatrix().transpose() * state.angularVelocity;
    for (int i = 0; i < 3; ++i)
    {
        qpos[i] = origin[i];
        qvel[i] = velocity[i];
        qvel[3 + i] = omegaBody[i];
    }
    qpos[3] = q.w();
    qpos[4] = q.x();
    qpos[5] = q.y();
    qpos[6] = q.z();
}

Translation translate(const mjModel* m, const mjData* d, const std::string& source)
{
    Problems problems;
    const Custom custom(m);

    // ---- what impulse does not simulate ----
    if (m->nu > 0)
    {
        problems.add(std::to_string(m->nu) + " actuator(s): impulse simulates no actuators");
    }
    if (m->ntendon > 0)
    {
        problems.add(std::to_string(m->ntendon) + " tendon(s): impulse simulates no tendons");
    }
    if (m->neq > 0)
    {
        problems.add(std::to_string(m->neq) + " equality constraint(s): impulse simulates no equality constraints");
    }
    if (m->nmocap > 0)
    {
        problems.add(std::to_string(m->nmocap) + " mocap body(ies): impulse has no kinematically driven bodies");
    }
    if (m->opt.density != 0.0 || m->opt.viscosity != 0.0)
    {
        problems.add("a medium (option density or viscosity): impulse simulates no fluid forces");
    }
    for (int j = 0; j < m->njnt; ++j)
    {
        const int body = m->jnt_bodyid[j];
        if (m->jnt_type[j] != mjJNT_FREE)
        {
            problems.add(std::string(jointTypeName(m->jnt_type[j])) + " joint " + nameOf(m, mjOBJ_JOINT, j) +
                         " on body " + nameOf(m, mjOBJ_BODY, body) + ": impulse simulates free bodies only");
        }
        else
        {
            for (int k = 0; k < 6; ++k)
            {
                const int dof = m->jnt_dofadr[j] + k;
                if (m->dof_damping[dof] != 0.0 || m->dof_armature[dof] != 0.0 || m->dof_frictionloss[dof] != 0.0)
                {
                    problems.add("free joint " + nameOf(m, mjOBJ_JOINT, j) +
                                 " has damping, armature or frictionloss: impulse simulates none");
                    break;
                }
            }
        }
    }

    // ---- bodies: free ones become dynamic bodies, geoms welded to the world static ones ----
    std::vector<std::vector<int>> weldGeoms(static_cast<std::size_t>(m->nbody));
    for (int g = 0; g < m->ngeom; ++g)
    {
        if (colliding(m, g))
        {
            weldGeoms[static_cast<std::size_t>(m->body_weldid[m->geom_bodyid[g]])].push_back(g);
        }
    }
    std::vector<int> freeBodies;
    for (int b = 1; b < m->nbody; ++b)
    {
        const int joints = m->body_jntnum[b];
        if (joints > 1)
        {
            problems.add("body " + nameOf(m, mjOBJ_BODY, b) + " has " + std::to_string(joints) +
                         " joints: impulse bodies are free or static");
            continue;
        }
        if (joints == 1 && m->jnt_type[m->body_jntadr[b]] == mjJNT_FREE)
        {
            if (m->body_parentid[b] != 0)
            {
                problems.add("free body " + nameOf(m, mjOBJ_BODY, b) + " is nested in body " +
                             nameOf(m, mjOBJ_BODY, m->body_parentid[b]) +
                             ": free bodies must be children of the world body");
                continue;
            }
            freeBodies.push_back(b);
        }
    }

    Translation t;
    t.name = m->nnames > 0 ? std::string(m->names) : std::string(); // the model name comes first
    WorldDef worldDef;
    worldDef.gravity = (m->opt.disableflags & mjDSBL_GRAVITY) ? Vec3::Zero() : vecAt(m->opt.gravity);
    t.world = World(worldDef);
    t.options.dt = m->opt.timestep;
    readSolverOptions(custom, t.options, problems);
    if (const std::vector<mjtNum>* duration = custom.find(custom::kDuration))
    {
        if (duration->size() != 1 || !((*duration)[0] >= 0.0) || !std::isfinite((*duration)[0]))
        {
            problems.add(std::string("custom numeric '") + custom::kDuration + "' must be one number >= 0");
        }
        else
        {
            t.duration = (*duration)[0];
        }
    }

    // prepared meshes by (MuJoCo mesh id, grid resolution), shared by every geom that uses them
    std::map<std::pair<int, int>, std::shared_ptr<const MeshGeometry>> meshes;
    // shape of one colliding geom, or a problem; `frame` receives the pose of the impulse body
    // frame in the geom's frame (the identity except for meshes)
    const auto shapeOf = [&](int g, bool isStatic, Pose& frame) -> std::optional<Shape>
    {
        frame = Pose{};
        const mjtNum* size = m->geom_size + 3 * g;
        switch (m->geom_type[g])
        {
        case mjGEOM_SPHERE:
            return Sphere{size[0]};
        case mjGEOM_BOX:
            return Box{Vec3(size[0], size[1], size[2])};
        case mjGEOM_CAPSULE:
            return Capsule{size[0], size[1]};
        case mjGEOM_PLANE:
            if (!isStatic)
            {
                problems.add("plane geom " + nameOf(m, mjOBJ_GEOM, g) + " on a moving body: planes must be static");
                return std::nullopt;
            }
            return Plane{};
        case mjGEOM_MESH:
        {
            const int mesh = m->geom_dataid[g];
            int resolution = 0;
            const std::string field = std::string(custom::kMeshResolutionPrefix) + plainName(m, mjOBJ_MESH, mesh);
            if (const std::vector<mjtNum>* value = custom.find(field))
            {
                if (value->size() != 1 || !((*value)[0] == 0.0 || ((*value)[0] >= 4.0 && (*value)[0] <= 1024.0)) ||
                    (*value)[0] != std::floor((*value)[0]))
                {
                    problems.add("custom numeric '" + field + "' must be 0 or a whole number of cells in [4, 1024]");
                    return std::nullopt;
                }
                resolution = static_cast<int>((*value)[0]);
            }
            std::shared_ptr<const MeshGeometry>& geometry = meshes[{mesh, resolution}];
            if (!geometry)
            {
                try
                {
                    geometry = meshGeometry(m, mesh, resolution);
                }
                catch (const MeshError& error)
                {
                    meshes.erase({mesh, resolution});
                    problems.add(meshGeomProblem(m, g, error.what()));
                    return std::nullopt;
                }
            }
            frame = geometry->frameInMesh();
            return Mesh{geometry};
        }
        default:
            problems.add(std::string(geomTypeName(m->geom_type[g])) + " geom " + nameOf(m, mjOBJ_GEOM, g) +
                         ": impulse has no such shape (it has sphere, box, capsule, plane and mesh)");
            return std::nullopt;
        }
    };

    std::vector<MaterialId> geomMaterial(static_cast<std::size_t>(m->ngeom), MaterialId{~0U});
    std::vector<Real> geomEps(static_cast<std::size_t>(m->ngeom), 0.0);
    const auto materialOf = [&](int g)
    {
        const Real eps = geomRestitution(m, custom, g, problems);
        const Real mu = m->geom_friction[3 * g];
        geomEps[static_cast<std::size_t>(g)] = eps;
        if (!(mu >= 0.0) || !std::isfinite(mu))
        {
            problems.add("geom " + nameOf(m, mjOBJ_GEOM, g) + " has a negative or non-finite friction");
            return MaterialId{};
        }
        const MaterialId id = t.world.createMaterial({.restitution = eps, .friction = mu});
        geomMaterial[static_cast<std::size_t>(g)] = id;
        return id;
    };

    // static geoms: those welded to the world body
    DataPtr scratch; // kinematics at qpos0, only for geoms on static child bodies
    for (const int g : weldGeoms[0])
    {
        Pose frame;
        const std::optional<Shape> shape = shapeOf(g, true, frame);
        if (!shape)
        {
            continue;
        }
        const int body = m->geom_bodyid[g];
        Vec3 position = vecAt(m->geom_pos + 3 * g);
        Quat orientation = quatAt(m->geom_quat + 4 * g);
        if (body != 0)
        {
            if (!scratch)
            {
                scratch.reset(mj_makeData(m));
                mj_kinematics(m, scratch.get());
            }
            position = vecAt(scratch->geom_xpos + 3 * g);
            mjtNum wxyz[4];
            mju_mat2Quat(wxyz, scratch->geom_xmat + 9 * g);
            orientation = quatAt(wxyz);
        }
        BodyDef def;
        def.type = BodyType::Static;
        def.shape = *shape;
        if (std::holds_alternative<Plane>(def.shape))
        {
            // the half-space below the geom's xy plane, as a world-frame normal and offset
            Vec3 normal = orientation.normalized().toRotationMatrix().col(2);
            Real offset = normal.dot(position);
            // the export's exact numbers, when they describe this same plane
            const std::vector<mjtNum>* exact =
                custom.find(std::string(custom::kPlanePrefix) + plainName(m, mjOBJ_GEOM, g));
            if (exact != nullptr && exact->size() == 4)
            {
                const Vec3 n((*exact)[0], (*exact)[1], (*exact)[2]);
                if ((n - normal).norm() < 1e-9 &&
                    std::abs((*exact)[3] - offset) < 1e-9 * std::max(1.0, std::abs(offset)))
                {
                    normal = n;
                    offset = (*exact)[3];
                }
            }
            def.shape = Plane{normal, offset};
        }
        else
        {
            def.position = position;
            def.orientation = orientation;
            if (std::holds_alternative<Mesh>(def.shape))
            {
                // a mesh body sits at the mesh's centre of mass on its principal axes
                const Quat placed = orientation.normalized();
                def.position = position + placed * frame.position;
                def.orientation = (placed * frame.orientation).normalized();
            }
        }
        def.material = materialOf(g);
        if (!problems.empty())
        {
            continue;
        }
        try
        {
            t.world.createBody(def);
            t.bodyNames.push_back(plainName(m, mjOBJ_GEOM, g));
        }
        catch (const std::invalid_argument& error)
        {
            problems.add("geom " + nameOf(m, mjOBJ_GEOM, g) + ": " + error.what());
        }
    }

    for (const int b : freeBodies)
    {
        const std::vector<int>& geoms = weldGeoms[static_cast<std::size_t>(b)];
        if (geoms.size() != 1)
        {
            std::string names;
            for (const int g : geoms)
            {
                names += (names.empty() ? "" : ", ") + nameOf(m, mjOBJ_GEOM, g);
            }
            problems.add("free body " + nameOf(m, mjOBJ_BODY, b) + " has " + std::to_string(geoms.size()) +
                         " colliding geoms" + (geoms.empty() ? "" : " (" + names + ")") +
                         ": an impulse body has exactly one shape");
            continue;
        }
        const int g = geoms[0];
        if (m->geom_bodyid[g] != b)
        {
            problems.add("geom " + nameOf(m, mjOBJ_GEOM, g) + " of free body " + nameOf(m, mjOBJ_BODY, b) +
                         " sits on a child body: put it on the free body itself");
            continue;
        }
        Pose frame;
        const std::optional<Shape> shape = shapeOf(g, false, frame);
        if (!shape)
        {
            continue;
        }
        const bool mesh = std::holds_alternative<Mesh>(*shape);
        Vec3 inertia = vecAt(m->body_inertia + 3 * b);
        std::optional<Mat3> wholeTensor; // on the shape's axes, when they are not the principal axes
        const Vec3 inertialPosition = vecAt(m->body_ipos + 3 * b);
        Quat inertialOrientation = quatAt(m->body_iquat + 4 * b);
        // The impulse body: its origin at the compiled centre of mass, its axes the shape's (a mesh's:
        // its principal axes as MeshGeometry finds them, placed by the geom), the compiled inertia on
        // those axes, and the shape off the centre of mass where the geom is.
        const Quat geomOrientation = quatAt(m->geom_quat + 4 * g).normalized();
        Vec3 shapePosition = vecAt(m->geom_pos + 3 * g);
        Quat shapeOrientation = geomOrientation;
        if (mesh)
        {
            shapePosition += geomOrientation * frame.position;
            shapeOrientation = (geomOrientation * frame.orientation).normalized();
        }
        Vec3 centerOfMass = Vec3::Zero(); // in the shape's frame
        if (!centred(m, g, b) || mesh)
        {
            centerOfMass = shapeOrientation.conjugate() * (inertialPosition - shapePosition);
            // MuJoCo finds a mesh's centroid from float vertices: within the frame tolerance of
            // MeshGeometry's it is the same point
            if (mesh && centerOfMass.norm() <= kMeshFrameTolerance * m->geom_rbound[g])
            {
                centerOfMass.setZero();
            }
        }
        if (mesh || !sameFrame(m, g, b))
        {
            const Mat3 turned = inertiaOnAxes(inertia, inertialOrientation, shapeOrientation);
            const Mat3 tensor = 0.5 * (turned + turned.transpose());
            const Mat3 offDiagonal = tensor - Mat3(tensor.diagonal().asDiagonal());
            if (offDiagonal.cwiseAbs().maxCoeff() > kMeshFrameTolerance * std::max<Real>(inertia.maxCoeff(), 0.0))
            {
                wholeTensor = tensor; // principal axes turned from the shape's
            }
            inertia = tensor.diagonal();
            inertialOrientation = shapeOrientation;
        }
        if (!(m->body_mass[b] > 0.0) || !((inertia.array() > 0.0).all()))
        {
            problems.add("free body " + nameOf(m, mjOBJ_BODY, b) + " needs a positive mass and inertia");
            continue;
        }
        const int joint = m->body_jntadr[b];
        Translation::Link link;
        link.mjBody = b;
        link.qposAddress = m->jnt_qposadr[joint];
        link.dofAddress = m->jnt_dofadr[joint];
        link.inertialPosition = inertialPosition;
        link.inertialOrientation = inertialOrientation;
        link.offset = !link.inertialPosition.isZero(0.0) || link.inertialOrientation.w() != 1.0 ||
                      !link.inertialOrientation.vec().isZero(0.0);
        const MaterialId material = materialOf(g);
        if (!problems.empty())
        {
            continue;
        }
        const LinkState state = readLink(link, m, d);
        BodyDef def;
        def.shape = *shape;
        def.material = material;
        def.mass = m->body_mass[b];
        def.principalInertia = inertia;
        def.centerOfMass = centerOfMass;
        if (wholeTensor)
        {
            def.inertia = *wholeTensor;
        }
        def.position = state.position;
        def.orientation = state.orientation;
        def.linearVelocity = state.linearVelocity;
        def.angularVelocity = state.angularVelocity;
        try
        {
            link.body = t.world.createBody(def);
        }
        catch (const std::invalid_argument& error)
        {
            problems.add("free body " + nameOf(m, mjOBJ_BODY, b) + ": " + error.what());
            continue;
        }
        t.links.push_back(link);
        t.dynamicBodies.push_back(link.body);
        t.bodyNames.push_back(plainName(m, mjOBJ_BODY, b));
    }

    // explicit <pair>s between translated geoms override the pair rule
    for (int p = 0; p < m->npair && problems.empty(); ++p)
    {
        const int g1 = m->pair_geom1[p];
        const int g2 = m->pair_geom2[p];
        const MaterialId a = geomMaterial[static_cast<std::size_t>(g1)];
        const MaterialId b = geomMaterial[static_cast<std::size_t>(g2)];
        if (a.index == ~0U || b.index == ~0U)
        {
            continue; // a visual geom: MuJoCo's pair, nothing for impulse to collide
        }
        const std::string name = std::string(custom::kGeomRestitutionPrefix) + plainName(m, mjOBJ_GEOM, g1) + ":" +
                                 plainName(m, mjOBJ_GEOM, g2);
        Real eps = std::max(geomEps[static_cast<std::size_t>(g1)], geomEps[static_cast<std::size_t>(g2)]);
        if (const std::vector<mjtNum>* value = custom.find(name))
        {
            if (value->size() != 1 || !((*value)[0] >= 0.0 && (*value)[0] <= 1.0))
            {
                problems.add("custom numeric '" + name + "' must be one number in [0, 1]");
                continue;
            }
            eps = (*value)[0];
        }
        const Real mu = m->pair_friction[5 * p];
        if (!(mu >= 0.0) || !std::isfinite(mu))
        {
            problems.add("pair " + std::to_string(p) + " has a negative or non-finite friction");
            continue;
        }
        t.world.setPairCoefficients(a, b, {eps, mu});
    }

    if (!problems.empty())
    {
        problems.raise(source);
    }
    return t;
}

} // namespace impulse::mujoco
