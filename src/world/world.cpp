// SPDX-License-Identifier: MIT
// The public World API over WorldImpl: body creation with validation, queries, energies, hashing.
#include "dynamics/integrate.hpp"
#include "world/world_impl.hpp"

#include <cmath>
#include <cstring>
#include <limits>
#include <stdexcept>
#include <string>

namespace impulse
{
namespace
{

bool finite(const Vec3& v)
{
    return v.allFinite();
}

void require(bool condition, const std::string& field, const std::string& what)
{
    if (!condition)
    {
        throw std::invalid_argument(field + ": " + what);
    }
}

void validateShape(const Shape& shape)
{
    if (const auto* sphere = std::get_if<Sphere>(&shape))
    {
        require(std::isfinite(sphere->radius) && sphere->radius > 0.0, "radius", "must be a positive finite number");
    }
    else if (const auto* box = std::get_if<Box>(&shape))
    {
        require(finite(box->halfExtents) && (box->halfExtents.array() > 0.0).all(), "half_extents",
                "must be three positive finite numbers");
    }
    else if (const auto* plane = std::get_if<Plane>(&shape))
    {
        require(finite(plane->normal) && plane->normal.stableNorm() > 0.0, "normal",
                "must be a finite non-zero vector");
        require(std::isfinite(plane->offset), "offset", "must be finite");
    }
    else if (const auto* capsule = std::get_if<Capsule>(&shape))
    {
        require(std::isfinite(capsule->radius) && capsule->radius > 0.0, "radius", "must be a positive finite number");
        require(std::isfinite(capsule->halfLength) && capsule->halfLength > 0.0, "half_length",
                "must be a positive finite number");
    }
    else if (const auto* mesh = std::get_if<Mesh>(&shape))
    {
        require(mesh->geometry != nullptr, "mesh", "has no geometry (build it with MeshGeometry::build)");
    }
}

} // namespace

PairCoefficients combineMaterials(const Material& a, const Material& b)
{
    return {std::max(a.restitution, b.restitution), std::sqrt(a.friction * b.friction)};
}

PairCoefficients WorldImpl::coefficients(MaterialId a, MaterialId b) const
{
    const auto key = std::minmax(a.index, b.index);
    if (const auto found = pairOverrides.find({key.first, key.second}); found != pairOverrides.end())
    {
        return found->second;
    }
    return combineMaterials(materials[a.index], materials[b.index]);
}

World::World(const WorldDef& def) : m_impl(std::make_unique<WorldImpl>())
{
    if (!def.gravity.allFinite())
    {
        throw std::invalid_argument("gravity: must be finite");
    }
    m_impl->def = def;
}

World::~World() = default;
World::World(World&&) noexcept = default;
World& World::operator=(World&&) noexcept = default;

MaterialId World::createMaterial(const Material& material)
{
    require(std::isfinite(material.restitution) && material.restitution >= 0.0 && material.restitution <= 1.0,
            "restitution", "must be in [0, 1]");
    require(std::isfinite(material.friction) && material.friction >= 0.0, "friction",
            "must be a non-negative finite number");
    m_impl->materials.push_back(material);
    return {static_cast<std::uint32_t>(m_impl->materials.size() - 1)};
}

void World::setPairCoefficients(MaterialId a, MaterialId b, const PairCoefficients& coefficients)
{
    require(a.index < m_impl->materials.size() && b.index < m_impl->materials.size(), "materials", "unknown material");
    require(std::isfinite(coefficients.restitution) && coefficients.restitution >= 0.0 &&
                coefficients.restitution <= 1.0,
            "restitution", "must be in [0, 1]");
    require(std::isfinite(coefficients.friction) && coefficients.friction >= 0.0, "friction",
            "must be a non-negative finite number");
    const auto key = std::minmax(a.index, b.index);
    m_impl->pairOverrides[{key.first, key.second}] = coefficients;
}

PairCoefficients World::pairCoefficients(MaterialId a, MaterialId b) const
{
    return m_impl->coefficients(a, b);
}

BodyId World::createBody(const BodyDef& def)
{
    validateShape(def.shape);
    require(def.material.index < m_impl->materials.size(), "material", "unknown material");
    require(finite(def.position), "position", "must be finite");
    require(finite(def.linearVelocity), "velocity", "must be finite");
    require(finite(def.angularVelocity), "angular_velocity", "must be finite");
    require(def.orientation.coeffs().allFinite() && def.orientation.coeffs().stableNorm() > 0.0, "orientation",
            "must be a finite non-zero quaternion");

    RigidBody body;
    body.shape = def.shape;
    body.material = def.material;
    body.dynamic = def.type == BodyType::Dynamic;
    body.position = def.position;
    body.orientation = Quat(def.orientation.coeffs().stableNormalized());
    body.rotation = body.orientation.toRotationMatrix();
    if (auto* plane = std::get_if<Plane>(&body.shape))
    {
        require(!body.dynamic, "static", "a plane must be static");
        const Real length = plane->normal.stableNorm();
        plane->normal /= length;
        plane->offset /= length;
    }
    body.boundingRadius = boundingRadius(body.shape);

    if (body.dynamic)
    {
        require(std::isfinite(def.mass) && def.mass >= 0.0, "mass", "must be a positive finite number");
        require(std::isfinite(def.density) && def.density >= 0.0, "density", "must be a positive finite number");
        require(def.mass > 0.0 || def.density > 0.0, "mass", "a dynamic body needs a positive mass or density");
        body.mass = def.mass > 0.0 ? def.mass : def.density * volume(body.shape);
        body.invMass = 1.0 / body.mass;
        require(std::isfinite(body.mass) && std::isfinite(body.invMass) && body.mass > 0.0,
                def.mass > 0.0 ? "mass" : "density", "gives a mass that is not a positive finite number");
        require(finite(def.principalInertia) && (def.principalInertia.array() >= 0.0).all(), "inertia",
                "must be three non-negative finite numbers");
        body.principalInertia =
            def.principalInertia.isZero(0.0) ? Vec3(body.mass * unitInertia(body.shape)) : def.principalInertia;
        body.invPrincipalInertia = body.principalInertia.cwiseInverse();
        require(body.principalInertia.allFinite() && body.invPrincipalInertia.allFinite(),
                def.mass > 0.0 ? "mass" : "density", "gives an inertia that is not a positive finite number");
        // L = I w in the world frame
        body.angularMomentum =
            body.rotation * body.principalInertia.asDiagonal() * body.rotation.transpose() * def.angularVelocity;
        body.linearVelocity = def.linearVelocity;
    }
    else
    {
        require(def.linearVelocity.isZero(0.0) && def.angularVelocity.isZero(0.0), "velocity",
                "a static body cannot move");
        body.mass = std::numeric_limits<Real>::infinity();
    }
    updateDerivedQuantities(body);
    body.predicted = body.pose();
    m_impl->bodies.push_back(body);
    return {static_cast<std::uint32_t>(m_impl->bodies.size() - 1)};
}

void World::setState(BodyId id, const Vec3& position, const Quat& orientation, const Vec3& linearVelocity,
                     const Vec3& angularVelocity)
{
    RigidBody& body = m_impl->bodies.at(id.index);
    require(body.dynamic, "static", "a static body cannot be moved");
    require(finite(position), "position", "must be finite");
    require(finite(linearVelocity), "velocity", "must be finite");
    require(finite(angularVelocity), "angular_velocity", "must be finite");
    require(orientation.coeffs().allFinite() && orientation.coeffs().stableNorm() > 0.0, "orientation",
            "must be a finite non-zero quaternion");
    body.position = position;
    body.orientation = Quat(orientation.coeffs().stableNormalized());
    body.rotation = body.orientation.toRotationMatrix();
    body.linearVelocity = linearVelocity;
    body.angularMomentum =
        body.rotation * body.principalInertia.asDiagonal() * body.rotation.transpose() * angularVelocity;
    updateDerivedQuantities(body);
    body.predicted = body.pose();
}

WorldSnapshot World::snapshot() const
{
    WorldSnapshot snapshot;
    snapshot.time = m_impl->time;
    snapshot.bodies.reserve(m_impl->bodies.size());
    for (std::uint32_t b = 0; b < m_impl->bodies.size(); ++b)
    {
        snapshot.bodies.push_back(state(BodyId{b}));
    }
    return snapshot;
}

void World::restore(const WorldSnapshot& snapshot)
{
    std::vector<RigidBody>& bodies = m_impl->bodies;
    require(snapshot.bodies.size() == bodies.size(), "bodies",
            "the snapshot has " + std::to_string(snapshot.bodies.size()) + " bodies, the world " +
                std::to_string(bodies.size()));
    require(std::isfinite(snapshot.time), "time", "must be finite");
    // Check everything before changing anything, so that a refused snapshot leaves the world as it was.
    std::vector<RigidBody> restored = bodies;
    for (std::size_t b = 0; b < bodies.size(); ++b)
    {
        const BodyState& s = snapshot.bodies[b];
        RigidBody& body = restored[b];
        const std::string field = "bodies/" + std::to_string(b) + "/";
        if (!body.dynamic)
        {
            require(s.position == body.position && s.orientation.coeffs() == body.orientation.coeffs(),
                    field + "position", "a static body cannot move");
            require(s.linearVelocity.isZero(0.0) && s.angularMomentum.isZero(0.0), field + "velocity",
                    "a static body cannot move");
            continue;
        }
        require(finite(s.position), field + "position", "must be finite");
        require(finite(s.linearVelocity), field + "velocity", "must be finite");
        require(finite(s.angularMomentum), field + "angular_momentum", "must be finite");
        require(s.orientation.coeffs().allFinite() && std::abs(s.orientation.norm() - 1.0) <= 1e-9,
                field + "orientation", "must be a finite unit quaternion");
        body.position = s.position;
        body.orientation = s.orientation; // as stored: renormalising would move the trajectory
        body.rotation = body.orientation.toRotationMatrix();
        body.linearVelocity = s.linearVelocity;
        body.angularMomentum = s.angularMomentum;
        updateDerivedQuantities(body);
        body.predicted = body.pose();
        // The angular velocity is derived; one that differs says the snapshot was edited or comes
        // from another world, and which of the two to believe would be a guess.
        require(body.angularVelocity == s.angularVelocity, field + "angular_velocity",
                "does not follow from the angular momentum and orientation (it is derived from them)");
    }
    bodies = std::move(restored);
    m_impl->time = snapshot.time;
}

void World::step(const StepOptions& options)
{
    if (!(options.dt > 0.0) || !std::isfinite(options.dt))
    {
        throw std::invalid_argument("dt: must be a positive finite number");
    }
    if (!(options.restitutionThreshold >= 0.0) || !std::isfinite(options.restitutionThreshold))
    {
        throw std::invalid_argument("restitution_threshold: must be a non-negative finite speed");
    }
    if (options.collisionIterations < 0 || options.contactIterations < 1 || options.pairIterations < 1)
    {
        throw std::invalid_argument("iterations: collision >= 0, contact >= 1 and pair >= 1 required");
    }
    if (!(options.pushOutAllowance >= 0.0) || !std::isfinite(options.pushOutAllowance))
    {
        throw std::invalid_argument("push_out_allowance: must be a non-negative finite distance");
    }
    if (!(options.pushOutSpeed >= 0.0) || !std::isfinite(options.pushOutSpeed))
    {
        throw std::invalid_argument("push_out_speed: must be a non-negative finite speed");
    }
    if (options.pushOutIterations < 0)
    {
        throw std::invalid_argument("push_out_iterations: must be 0 or more");
    }
    if (options.threads < 0)
    {
        throw std::invalid_argument("threads: must be 0 (one per hardware thread) or a positive count");
    }
    m_impl->step(options);
}

std::uint32_t World::bodyCount() const
{
    return static_cast<std::uint32_t>(m_impl->bodies.size());
}

bool World::isDynamic(BodyId body) const
{
    return m_impl->bodies.at(body.index).dynamic;
}

BodyState World::state(BodyId id) const
{
    const RigidBody& body = m_impl->bodies.at(id.index);
    return {body.position, body.orientation, body.linearVelocity, body.angularVelocity, body.angularMomentum};
}

Real World::mass(BodyId body) const
{
    return m_impl->bodies.at(body.index).mass;
}

Vec3 World::principalInertia(BodyId body) const
{
    return m_impl->bodies.at(body.index).principalInertia;
}

const Shape& World::shape(BodyId body) const
{
    return m_impl->bodies.at(body.index).shape;
}

MaterialId World::material(BodyId body) const
{
    return m_impl->bodies.at(body.index).material;
}

const Material& World::material(MaterialId material) const
{
    return m_impl->materials.at(material.index);
}

Vec3 World::gravity() const
{
    return m_impl->def.gravity;
}

Real World::time() const
{
    return m_impl->time;
}

Real World::kineticEnergy() const
{
    Real energy = 0.0;
    for (const RigidBody& body : m_impl->bodies)
    {
        if (body.dynamic)
        {
            energy += 0.5 * body.mass * body.linearVelocity.squaredNorm() +
                      0.5 * body.angularVelocity.dot(body.angularMomentum);
        }
    }
    return energy;
}

Real World::potentialEnergy() const
{
    Real energy = 0.0;
    for (const RigidBody& body : m_impl->bodies)
    {
        if (body.dynamic)
        {
            energy -= body.mass * m_impl->def.gravity.dot(body.position);
        }
    }
    return energy;
}

Vec3 World::linearMomentum() const
{
    Vec3 momentum = Vec3::Zero();
    for (const RigidBody& body : m_impl->bodies)
    {
        if (body.dynamic)
        {
            momentum += body.mass * body.linearVelocity;
        }
    }
    return momentum;
}

const StepStats& World::lastStepStats() const
{
    return m_impl->stats;
}

std::uint64_t World::stateHash() const
{
    // FNV-1a over the bits of every dynamic body's primary state
    std::uint64_t hash = 1469598103934665603ULL;
    const auto mix = [&](const double* values, int count)
    {
        for (int i = 0; i < count; ++i)
        {
            std::uint64_t bits = 0;
            std::memcpy(&bits, &values[i], sizeof bits);
            for (int byte = 0; byte < 8; ++byte)
            {
                hash ^= (bits >> (8 * byte)) & 0xffU;
                hash *= 1099511628211ULL;
            }
        }
    };
    for (const RigidBody& body : m_impl->bodies)
    {
        if (body.dynamic)
        {
            mix(body.position.data(), 3);
            mix(body.orientation.coeffs().data(), 4);
            mix(body.linearVelocity.data(), 3);
            mix(body.angularMomentum.data(), 3);
        }
    }
    return hash;
}

} // namespace impulse
