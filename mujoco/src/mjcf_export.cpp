// SPDX-License-Identifier: MIT
#include <impulse/io/markup.hpp>
#include <impulse/mujoco/mjcf_export.hpp>
#include <impulse/mujoco/mujoco.hpp>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <map>
#include <set>
#include <sstream>
#include <stdexcept>
#include <tuple>

namespace impulse::mujoco
{
namespace
{

std::string num(Real value)
{
    char buffer[32];
    std::snprintf(buffer, sizeof buffer, "%.17g", value);
    return buffer;
}

std::string vec(const Vec3& v)
{
    return num(v.x()) + " " + num(v.y()) + " " + num(v.z());
}

std::string quat(const Quat& q)
{
    return num(q.w()) + " " + num(q.x()) + " " + num(q.y()) + " " + num(q.z());
}

// The inertia of a dynamic body as <inertial> attributes: its principal moments when its principal
// axes are its body axes, else the whole tensor on the body axes (MuJoCo's compiler diagonalises it).
std::string inertial(const World& world, BodyId id)
{
    if (world.principalAxes(id) == Mat3::Identity())
    {
        return "diaginertia=\"" + vec(world.principalInertia(id)) + "\"";
    }
    const Mat3 i = world.inertia(id);
    return "fullinertia=\"" + num(i(0, 0)) + " " + num(i(1, 1)) + " " + num(i(2, 2)) + " " + num(i(0, 1)) + " " +
           num(i(0, 2)) + " " + num(i(1, 2)) + "\"";
}

// A name MJCF accepts and XML needs no escaping for, unique among those already given.
std::string uniqueName(const std::string& wanted, std::size_t index, std::set<std::string>& used)
{
    std::string name;
    for (const char c : wanted)
    {
        const bool plain = (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '_' ||
                           c == '-' || c == '.';
        name += plain ? c : '_';
    }
    if (name.empty())
    {
        name = "body";
        name += std::to_string(index);
    }
    if (used.count(name) != 0)
    {
        name += '_';
        name += std::to_string(index);
    }
    used.insert(name);
    return name;
}

// Contact attributes of a geom or pair for restitution eps and friction mu.
std::string contactAttributes(Real eps, Real mu, Real timeconst, bool pair)
{
    const Softness soft = contactSoftness(eps, timeconst);
    std::string friction = pair ? num(mu) + " " + num(mu) + " 0 0 0" : num(mu) + " 0 0";
    return "condim=\"3\" friction=\"" + friction + "\" solref=\"" + num(-soft.stiffness) + " " + num(-soft.damping) +
           "\" solimp=\"" + kSolimp + "\"";
}

} // namespace

std::string exportMjcf(const io::Scene& scene, Real timeconst)
{
    const World& world = scene.world;
    const Real dt = scene.options.dt;
    if (!(timeconst >= 0.0) || !std::isfinite(timeconst))
    {
        throw std::invalid_argument("timeconst: must be a non-negative number of seconds");
    }
    const Real tc = timeconst > 0.0 ? timeconst : defaultTimeconst(dt);
    std::set<std::string> used;
    std::vector<std::string> names;
    for (std::uint32_t i = 0; i < world.bodyCount(); ++i)
    {
        names.push_back(uniqueName(i < scene.bodyNames.size() ? scene.bodyNames[i] : std::string(), i, used));
    }

    std::ostringstream custom;
    std::ostringstream assets;
    // one mesh asset per file, scale and grid resolution, as the scene loader shares geometries
    std::map<std::tuple<std::string, Real, Real, Real, int>, std::string> meshAssets;
    std::ostringstream statics;
    std::ostringstream bodies;
    std::ostringstream keyQpos;
    std::ostringstream keyQvel;
    std::size_t dynamicCount = 0;
    for (std::uint32_t i = 0; i < world.bodyCount(); ++i)
    {
        const BodyId id{i};
        const std::string& name = names[i];
        const Material& material = world.material(world.material(id));
        const std::string contact = contactAttributes(material.restitution, material.friction, tc, false);
        custom << "    <numeric name=\"" << custom::kGeomRestitutionPrefix << name << "\" data=\""
               << num(material.restitution) << "\"/>\n";
        const BodyState s = world.state(id);
        const Shape& shape = world.shape(id);
        std::string geom;
        // pose of the geom's frame in the body frame, written for meshes only
        Vec3 geomPosition = Vec3::Zero();
        Quat geomOrientation = Quat::Identity();
        bool placedGeom = false;
        if (const auto* sphere = std::get_if<Sphere>(&shape))
        {
            geom = "type=\"sphere\" size=\"" + num(sphere->radius) + "\"";
        }
        else if (const auto* box = std::get_if<Box>(&shape))
        {
            geom = "type=\"box\" size=\"" + vec(box->halfExtents) + "\"";
        }
        else if (const auto* capsule = std::get_if<Capsule>(&shape))
        {
            geom = "type=\"capsule\" size=\"" + num(capsule->radius) + " " + num(capsule->halfLength) + "\"";
        }
        else if (const auto* plane = std::get_if<Plane>(&shape))
        {
            // world-frame normal and offset; the geom's z axis is the normal, its origin on the plane
            const bool identity = s.position.isZero(0.0) && s.orientation.vec().isZero(0.0);
            const Vec3 normal = identity ? plane->normal : Vec3(s.orientation.toRotationMatrix() * plane->normal);
            const Real offset = identity ? plane->offset : plane->offset + normal.dot(s.position);
            const Quat frame = Quat::FromTwoVectors(Vec3::UnitZ(), normal);
            statics << "    <geom name=\"" << name << "\" type=\"plane\" size=\"0 0 1\" pos=\"" << vec(offset * normal)
                    << "\" quat=\"" << quat(frame) << "\" " << contact << "/>\n";
            custom << "    <numeric name=\"" << custom::kPlanePrefix << name << "\" data=\"" << vec(normal) << " "
                   << num(offset) << "\"/>\n";
            continue;
        }
        else if (const auto* mesh = std::get_if<Mesh>(&shape))
        {
            const io::MeshSource* source = i < scene.meshSources.size() ? &scene.meshSources[i] : nullptr;
            if (source == nullptr || source->file.empty())
            {
                throw std::invalid_argument("body " + name +
                                            ": a mesh is exported as its file, and the scene does not say which "
                                            "file this body's mesh was read from");
            }
            const std::string file = std::filesystem::absolute(source->file).lexically_normal().string();
            const auto key =
                std::make_tuple(file, source->scale.x(), source->scale.y(), source->scale.z(), source->resolution);
            auto asset = meshAssets.find(key);
            if (asset == meshAssets.end())
            {
                const std::string assetName =
                    uniqueName("mesh_" + std::filesystem::path(file).stem().string(), meshAssets.size(), used);
                asset = meshAssets.emplace(key, assetName).first;
                assets << "    <mesh name=\"" << assetName << "\" file=\"" << io::escapeMarkup(file) << "\" scale=\""
                       << vec(source->scale) << "\"/>\n";
                if (source->resolution != 0)
                {
                    custom << "    <numeric name=\"" << custom::kMeshResolutionPrefix << assetName << "\" data=\""
                           << source->resolution << "\"/>\n";
                }
            }
            geom = "type=\"mesh\" mesh=\"" + asset->second + "\"";
            // the file's frame in the body frame; MuJoCo moves its mesh frame to the centre of mass
            // and principal axes and the geom's pose with it, which lands it on the body frame
            const Pose& frame = mesh->geometry->frameInMesh();
            geomOrientation = frame.orientation.conjugate();
            geomPosition = -(geomOrientation * frame.position);
            placedGeom = true;
        }
        else
        {
            throw std::invalid_argument("body " + name + ": this shape has no MJCF equivalent yet");
        }

        if (!world.isDynamic(id))
        {
            Vec3 position = s.position;
            Quat orientation = s.orientation;
            if (placedGeom)
            {
                position = s.position + s.orientation * geomPosition;
                orientation = s.orientation * geomOrientation;
            }
            statics << "    <geom name=\"" << name << "\" " << geom << " pos=\"" << vec(position) << "\" quat=\""
                    << quat(orientation) << "\" " << contact << "/>\n";
            continue;
        }
        if (const Vec3 centerOfMass = world.centerOfMass(id); !centerOfMass.isZero(0.0))
        {
            // the body frame sits at the centre of mass, the shape's frame off it
            geomPosition -= centerOfMass;
            placedGeom = true;
        }
        if (placedGeom)
        {
            geom += " pos=\"" + vec(geomPosition) + "\" quat=\"" + quat(geomOrientation) + "\"";
        }
        ++dynamicCount;
        bodies << "    <body name=\"" << name << "\" pos=\"" << vec(s.position) << "\" quat=\"" << quat(s.orientation)
               << "\">\n"
               << "      <freejoint name=\"" << name << "\"/>\n"
               << "      <inertial pos=\"0 0 0\" mass=\"" << num(world.mass(id)) << "\" " << inertial(world, id)
               << "/>\n"
               << "      <geom name=\"" << name << "\" " << geom << " " << contact << "/>\n"
               << "    </body>\n";
        // the angular velocity the scene gave, not the one the world derives from L = I w: w = I^-1 L
        // can differ from it in the last bit, and loading would then make an L one bit off
        const Vec3 omega = i < scene.bodyDefs.size() ? scene.bodyDefs[i].angularVelocity : s.angularVelocity;
        const Vec3 omegaBody = s.orientation.toRotationMatrix().transpose() * omega;
        keyQpos << (dynamicCount > 1 ? "  " : "") << vec(s.position) << " " << quat(s.orientation);
        keyQvel << (dynamicCount > 1 ? "  " : "") << vec(s.linearVelocity) << " " << vec(omegaBody);
    }

    // MuJoCo combines a pair's friction by max and its solref by averaging; impulse by sqrt and
    // max, or by the scene's pair table. Where the two differ, an explicit <pair> states the
    // scene's values (restitution as a custom field impulse reads back).
    std::ostringstream pairs;
    for (std::uint32_t i = 0; i < world.bodyCount(); ++i)
    {
        for (std::uint32_t j = i + 1; j < world.bodyCount(); ++j)
        {
            if (!world.isDynamic(BodyId{i}) && !world.isDynamic(BodyId{j}))
            {
                continue;
            }
            const MaterialId a = world.material(BodyId{i});
            const MaterialId b = world.material(BodyId{j});
            const Material& ma = world.material(a);
            const Material& mb = world.material(b);
            const PairCoefficients c = world.pairCoefficients(a, b);
            if (ma.restitution == mb.restitution && ma.friction == mb.friction && c.restitution == ma.restitution &&
                c.friction == ma.friction)
            {
                continue;
            }
            pairs << "    <pair geom1=\"" << names[i] << "\" geom2=\"" << names[j] << "\" "
                  << contactAttributes(c.restitution, c.friction, tc, true) << "/>\n";
            custom << "    <numeric name=\"" << custom::kGeomRestitutionPrefix << names[i] << ":" << names[j]
                   << "\" data=\"" << num(c.restitution) << "\"/>\n";
        }
    }

    const StepOptions& o = scene.options;
    std::ostringstream xml;
    xml << "<!-- Written by impulse export-mjcf: the scene's bodies at full precision, its restitution and solver\n"
           "     options as custom fields, MuJoCo contact parameters as docs/mujoco.md describes. -->\n";
    xml << "<mujoco model=\"" << uniqueName(scene.name.empty() ? "scene" : scene.name, 0, used) << "\">\n";
    xml << "  <compiler angle=\"radian\" inertiafromgeom=\"false\" exactmeshinertia=\"true\"/>\n";
    xml << "  <option timestep=\"" << num(dt) << "\" gravity=\"" << vec(world.gravity())
        << "\" cone=\"elliptic\" integrator=\"Euler\"/>\n";
    const std::size_t contacts = 100 + 40 * dynamicCount;
    xml << "  <size nconmax=\"" << contacts << "\" njmax=\"" << 6 * contacts << "\"/>\n";
    xml << "  <custom>\n";
    xml << "    <numeric name=\"" << custom::kDuration << "\" data=\"" << num(scene.duration) << "\"/>\n";
    xml << "    <text name=\"impulse_scheme\" data=\""
        << (o.scheme == Scheme::Traditional ? "traditional" : "guendelman") << "\"/>\n";
    xml << "    <numeric name=\"impulse_collision_iterations\" data=\"" << o.collisionIterations << "\"/>\n";
    xml << "    <numeric name=\"impulse_contact_iterations\" data=\"" << o.contactIterations << "\"/>\n";
    xml << "    <numeric name=\"impulse_pair_iterations\" data=\"" << o.pairIterations << "\"/>\n";
    xml << "    <numeric name=\"impulse_contact_thickness\" data=\"" << num(o.contactThickness) << "\"/>\n";
    xml << "    <numeric name=\"impulse_restitution_threshold\" data=\"" << num(o.restitutionThreshold) << "\"/>\n";
    xml << "    <numeric name=\"impulse_resting_approach\" data=\"" << num(o.restingApproach) << "\"/>\n";
    xml << "    <numeric name=\"impulse_shock_propagation\" data=\"" << (o.shockPropagation ? 1 : 0) << "\"/>\n";
    xml << "    <numeric name=\"impulse_push_out\" data=\"" << (o.pushOut ? 1 : 0) << "\"/>\n";
    xml << "    <numeric name=\"impulse_push_out_allowance\" data=\"" << num(o.pushOutAllowance) << "\"/>\n";
    xml << "    <numeric name=\"impulse_push_out_speed\" data=\"" << num(o.pushOutSpeed) << "\"/>\n";
    xml << "    <numeric name=\"impulse_push_out_iterations\" data=\"" << o.pushOutIterations << "\"/>\n";
    xml << "    <numeric name=\"impulse_mid_step_restitution\" data=\"" << (o.midStepRestitution ? 1 : 0) << "\"/>\n";
    xml << "    <numeric name=\"impulse_time_of_impact_geometry\" data=\"" << (o.timeOfImpactGeometry ? 1 : 0)
        << "\"/>\n";
    xml << custom.str();
    xml << "  </custom>\n";
    if (!assets.str().empty())
    {
        xml << "  <asset>\n" << assets.str() << "  </asset>\n";
    }
    xml << "  <worldbody>\n" << statics.str() << bodies.str() << "  </worldbody>\n";
    if (!pairs.str().empty())
    {
        xml << "  <contact>\n" << pairs.str() << "  </contact>\n";
    }
    if (dynamicCount > 0)
    {
        xml << "  <keyframe>\n    <key name=\"initial\" qpos=\"" << keyQpos.str() << "\" qvel=\"" << keyQvel.str()
            << "\"/>\n  </keyframe>\n";
    }
    xml << "</mujoco>\n";
    return xml.str();
}

} // namespace impulse::mujoco
