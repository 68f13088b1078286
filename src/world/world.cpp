// SPDX-License-Identifier: MIT
// The public World API over WorldImpl: body creation with validation, queries, energies, hashing.
#include "dynamics/integrate.hpp"
#include "world/world_impl.hpp"

#include <Eigen/Eigenvalues>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <sstream>
#include <stdexcept>
#include <string>
#include <string_view>

namespace impulse
{
namespace
{

bool finite(const Vec3& v)
{
    return v.allFinite();
}

[[noreturn]] void fail(std::string_view field, std::string_view what)
{
    throw std::invalid_argument(std::string(field) + ": " + std::string(what));
}

void require(bool condition, std::string_view field, std::string_view what)
{
    if (!condition)
    {
        fail(field, what);
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

std::string number(Real value)
{
    std::ostringstream out;
    out.precision(17);
    out << value;
    return out.str();
}

std::string vector(const Vec3& value)
{
    // appended piece by piece: "(" + number(...) trips a false -Wrestrict in GCC 12
    std::string text = "(";
    text += number(value.x());
    text += ", ";
    text += number(value.y());
    text += ", ";
    text += number(value.z());
    text += ')';
    return text;
}

// The body a handle names, or std::invalid_argument saying why there is none.
// Every accessor goes through here, so its messages are built only on failure.
RigidBody& lookUp(WorldImpl& impl, BodyId id, std::string_view field = "body")
{
    if (id.index >= impl.bodies.size())
    {
        fail(field, "no body " + std::to_string(id.index) + " in this world (it has " +
                        std::to_string(impl.bodies.size()) + ")");
    }
    RigidBody& body = impl.bodies[id.index];
    if (body.removed)
    {
        fail(field, "body " + std::to_string(id.index) + " was removed");
    }
    return body;
}

// A dynamic body, for what only moves dynamic bodies.
RigidBody& dynamicBody(WorldImpl& impl, BodyId id, std::string_view what)
{
    RigidBody& body = lookUp(impl, id);
    if (!body.dynamic)
    {
        fail("body", "body " + std::to_string(id.index) + " is static: " + std::string(what));
    }
    return body;
}

// Forces and impulses are applied every step: their message is built only on failure.
void requireFinite(const Vec3& value, std::string_view field)
{
    if (!finite(value))
    {
        fail(field, "must be finite, got " + vector(value));
    }
}

BodyState stateOf(const RigidBody& body)
{
    return {body.position, body.orientation, body.linearVelocity, body.angularVelocity, body.angularMomentum};
}

// L = I w in the world frame, with the body's inertia at its orientation.
Vec3 momentumOf(const RigidBody& body, const Vec3& angularVelocity)
{
    if (body.principalAxesAligned)
    {
        return body.rotation * body.principalInertia.asDiagonal() * body.rotation.transpose() * angularVelocity;
    }
    const Mat3 axes = body.principalRotation();
    return axes * body.principalInertia.asDiagonal() * axes.transpose() * angularVelocity;
}

// An inertia tensor's principal moments and axes (a rotation, as columns), checked to be a real
// body's: symmetric, positive definite, the moments obeying the triangle inequality.
struct PrincipalFrame
{
    Vec3 moments;
    Mat3 axes = Mat3::Identity();
    bool aligned = true; ///< no products of inertia: the axes are the body axes
};

PrincipalFrame principalFrame(const Mat3& inertia)
{
    require(inertia.allFinite(), "inertia", "must be finite");
    const Real size = inertia.cwiseAbs().maxCoeff();
    require((inertia - inertia.transpose()).cwiseAbs().maxCoeff() <= 1e-12 * size, "inertia",
            "must be symmetric (I = I^T)");
    PrincipalFrame frame;
    frame.moments = inertia.diagonal();
    frame.aligned = inertia(0, 1) == 0.0 && inertia(0, 2) == 0.0 && inertia(1, 2) == 0.0 && inertia(1, 0) == 0.0 &&
                    inertia(2, 0) == 0.0 && inertia(2, 1) == 0.0;
    if (!frame.aligned)
    {
        const Eigen::SelfAdjointEigenSolver<Mat3> solver(0.5 * (inertia + inertia.transpose()));
        frame.moments = solver.eigenvalues();
        frame.axes = solver.eigenvectors();
        if (frame.axes.determinant() < 0.0)
        {
            frame.axes.col(2) = -frame.axes.col(2); // a rotation, so that the body frame keeps its handedness
        }
    }
    const Vec3& moments = frame.moments;
    require((moments.array() > 0.0).all(), "inertia",
            "must be positive definite, its principal moments are " + vector(moments));
    for (int k = 0; k < 3; ++k)
    {
        require(moments((k + 1) % 3) + moments((k + 2) % 3) >= moments(k) * (1.0 - 1e-9), "inertia",
                "principal moments " + vector(moments) +
                    " break the triangle inequality (each at most the sum of the other two), so no body has them");
    }
    return frame;
}

void setCenterOfMass(RigidBody& body, const Vec3& centerOfMass)
{
    body.shapeOffset = -centerOfMass;
    body.boundingRadius = boundingRadius(body.shape) + centerOfMass.norm();
}

void setPrincipalFrame(RigidBody& body, const PrincipalFrame& frame)
{
    body.principalInertia = frame.moments;
    body.invPrincipalInertia = frame.moments.cwiseInverse();
    body.inertiaAxes = frame.axes;
    body.principalAxesAligned = frame.aligned;
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
    require(finite(def.centerOfMass), "center_of_mass", "must be finite");
    require(body.dynamic || def.centerOfMass.isZero(0.0), "center_of_mass", "a static body has none");
    setCenterOfMass(body, def.centerOfMass);

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
        if (!def.inertia.isZero(0.0))
        {
            setPrincipalFrame(body, principalFrame(def.inertia));
        }
        // L = I w in the world frame
        body.angularMomentum = momentumOf(body, def.angularVelocity);
        body.linearVelocity = def.linearVelocity;
    }
    else
    {
        require(def.linearVelocity.isZero(0.0) && def.angularVelocity.isZero(0.0), "velocity",
                "a static body cannot move");
        require(def.inertia.isZero(0.0), "inertia", "a static body has none");
        body.mass = std::numeric_limits<Real>::infinity();
    }
    body.collisionGroup = def.filter.group;
    body.collisionMask = def.filter.mask;
    if (def.filter != CollisionFilter{})
    {
        m_impl->filtering = true;
    }
    body.acceleration = body.dynamic ? m_impl->def.gravity : Vec3::Zero();
    updateDerivedQuantities(body);
    body.predicted = body.pose();
    if (!body.dynamic)
    {
        m_impl->wakeAll(); // the broad phase pairs no static body with a sleeping one
    }
    m_impl->bodies.push_back(body);
    const auto index = static_cast<std::uint32_t>(m_impl->bodies.size() - 1);
    if (const Real size = thinnestHalfExtent(body.shape); size < m_impl->smallestSize)
    {
        m_impl->smallestSize = size;
        m_impl->smallestBody = index;
    }
    return {index};
}

void World::setState(BodyId id, const Vec3& position, const Quat& orientation, const Vec3& linearVelocity,
                     const Vec3& angularVelocity)
{
    RigidBody& body = lookUp(*m_impl, id);
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
    body.angularMomentum = momentumOf(body, angularVelocity);
    updateDerivedQuantities(body);
    body.predicted = body.pose();
    m_impl->wake(id.index);
}

void World::removeBody(BodyId id)
{
    RigidBody& body = lookUp(*m_impl, id);
    m_impl->wake(id.index); // what rested on it must feel it gone
    // a tombstone: static and at rest, so that no stage moves it or counts it, and left out of the
    // broad phase, so that nothing pairs with it
    body.removed = true;
    m_impl->smallestKnown = false;
    body.dynamic = false;
    body.mass = std::numeric_limits<Real>::infinity();
    body.invMass = 0.0;
    body.principalInertia.setZero();
    body.invPrincipalInertia.setZero();
    body.inertiaAxes.setIdentity();
    body.principalAxesAligned = true;
    body.linearVelocity.setZero();
    body.angularMomentum.setZero();
    body.force.setZero();
    body.torque.setZero();
    body.acceleration.setZero();
    updateDerivedQuantities(body);
    body.predicted = body.pose();
}

bool World::contains(BodyId id) const
{
    return id.index < m_impl->bodies.size() && !m_impl->bodies[id.index].removed;
}

void World::applyForce(BodyId id, const Vec3& force)
{
    RigidBody& body = dynamicBody(*m_impl, id, "forces do not move it");
    requireFinite(force, "force");
    m_impl->wake(id.index);
    body.force += force;
}

void World::applyForce(BodyId id, const Vec3& force, const Vec3& worldPoint)
{
    RigidBody& body = dynamicBody(*m_impl, id, "forces do not move it");
    requireFinite(force, "force");
    requireFinite(worldPoint, "point");
    m_impl->wake(id.index);
    body.force += force;
    body.torque += (worldPoint - body.position).cross(force);
}

void World::applyTorque(BodyId id, const Vec3& torque)
{
    RigidBody& body = dynamicBody(*m_impl, id, "torques do not move it");
    requireFinite(torque, "torque");
    m_impl->wake(id.index);
    body.torque += torque;
}

void World::applyImpulse(BodyId id, const Vec3& impulse)
{
    RigidBody& body = dynamicBody(*m_impl, id, "impulses do not move it");
    requireFinite(impulse, "impulse");
    m_impl->wake(id.index);
    body.linearVelocity += body.invMass * impulse;
}

void World::applyImpulse(BodyId id, const Vec3& impulse, const Vec3& worldPoint)
{
    RigidBody& body = dynamicBody(*m_impl, id, "impulses do not move it");
    requireFinite(impulse, "impulse");
    requireFinite(worldPoint, "point");
    m_impl->wake(id.index);
    impulse::applyImpulse(body, impulse, Vec3(worldPoint - body.position));
}

void World::applyAngularImpulse(BodyId id, const Vec3& angularImpulse)
{
    RigidBody& body = dynamicBody(*m_impl, id, "impulses do not move it");
    requireFinite(angularImpulse, "angular_impulse");
    m_impl->wake(id.index);
    body.angularMomentum += angularImpulse;
    body.angularVelocity = body.invInertiaWorld * body.angularMomentum;
}

Vec3 World::appliedForce(BodyId id) const
{
    return lookUp(*m_impl, id).force;
}

Vec3 World::appliedTorque(BodyId id) const
{
    return lookUp(*m_impl, id).torque;
}

void World::setCollisionFilter(BodyId id, const CollisionFilter& filter)
{
    RigidBody& body = lookUp(*m_impl, id);
    m_impl->wake(id.index);
    body.collisionGroup = filter.group;
    body.collisionMask = filter.mask;
    if (filter != CollisionFilter{})
    {
        m_impl->filtering = true;
    }
}

CollisionFilter World::collisionFilter(BodyId id) const
{
    const RigidBody& body = lookUp(*m_impl, id);
    return {body.collisionGroup, body.collisionMask};
}

void World::setCollisionEnabled(BodyId a, BodyId b, bool enabled)
{
    lookUp(*m_impl, a, "a");
    lookUp(*m_impl, b, "b");
    require(a.index != b.index, "b", "is the same body as a (a body never collides with itself)");
    m_impl->wake(a.index);
    m_impl->wake(b.index);
    const auto key = std::minmax(a.index, b.index);
    if (enabled)
    {
        m_impl->disabledPairs.erase({key.first, key.second});
    }
    else
    {
        m_impl->disabledPairs.insert({key.first, key.second});
        m_impl->filtering = true;
    }
}

bool World::collisionEnabled(BodyId a, BodyId b) const
{
    lookUp(*m_impl, a, "a");
    lookUp(*m_impl, b, "b");
    return a.index != b.index && m_impl->collides(a.index, b.index);
}

bool WorldImpl::collides(std::uint32_t a, std::uint32_t b) const
{
    const RigidBody& first = bodies[a];
    const RigidBody& second = bodies[b];
    if ((first.collisionGroup & second.collisionMask) == 0 || (second.collisionGroup & first.collisionMask) == 0)
    {
        return false;
    }
    return !disabledPairs.contains(std::minmax(a, b));
}

void WorldImpl::dropFilteredPairs()
{
    if (filtering)
    {
        std::erase_if(pairs, [&](const BodyPair& pair) { return !collides(pair.a, pair.b); });
    }
}

void WorldImpl::beginLoads()
{
    for (RigidBody& body : bodies)
    {
        if (body.dynamic && body.asleep)
        {
            body.acceleration.setZero(); // a force would have woken it
        }
        else if (body.dynamic)
        {
            // exactly gravity when no force is applied, so that such steps are unchanged bit for bit
            body.acceleration = body.force.isZero(0.0) ? def.gravity : Vec3(def.gravity + body.invMass * body.force);
        }
    }
}

void WorldImpl::wake(std::uint32_t index)
{
    if (!bodies[index].asleep)
    {
        return;
    }
    const std::uint32_t group = bodies[index].sleepGroup;
    for (RigidBody& body : bodies)
    {
        if (body.asleep && body.sleepGroup == group)
        {
            body.asleep = false;
            body.restingTime = 0.0;
            body.acceleration = body.force.isZero(0.0) ? def.gravity : Vec3(def.gravity + body.invMass * body.force);
        }
    }
}

void WorldImpl::wakeAll()
{
    for (std::uint32_t i = 0; i < bodies.size(); ++i)
    {
        if (bodies[i].asleep)
        {
            bodies[i].sleepGroup = 0; // one group: the first wake takes everyone
            wake(i);
        }
    }
}

void WorldImpl::clearLoads()
{
    for (RigidBody& body : bodies)
    {
        body.force.setZero();
        body.torque.setZero();
    }
}

void World::setMassProperties(BodyId id, Real mass, const Mat3& inertia)
{
    RigidBody& body = dynamicBody(*m_impl, id, "it has no mass properties to set");
    require(std::isfinite(mass) && mass > 0.0, "mass", "must be a positive finite number, got " + number(mass));
    m_impl->wake(id.index);
    const PrincipalFrame frame = principalFrame(inertia);
    const Vec3 angularVelocity = body.angularVelocity;
    body.mass = mass;
    body.invMass = 1.0 / mass;
    setPrincipalFrame(body, frame);
    body.angularMomentum = momentumOf(body, angularVelocity);
    updateDerivedQuantities(body);
}

void World::setMassProperties(BodyId id, Real mass, const Mat3& inertia, const Vec3& centerOfMass)
{
    RigidBody& body = dynamicBody(*m_impl, id, "it has no mass properties to set");
    require(finite(centerOfMass), "center_of_mass", "must be finite");
    setMassProperties(id, mass, inertia);
    // the shape stays put: the body's origin moves to the new centre, its velocity to that point's
    const Vec3 shift = body.rotation * (centerOfMass + body.shapeOffset);
    body.position += shift;
    body.linearVelocity += body.angularVelocity.cross(shift);
    setCenterOfMass(body, centerOfMass);
    body.predicted = body.pose();
}

void World::setMass(BodyId id, Real mass)
{
    const RigidBody& body = dynamicBody(*m_impl, id, "it has no mass to set");
    require(std::isfinite(mass) && mass > 0.0, "mass", "must be a positive finite number, got " + number(mass));
    setMassProperties(id, mass, inertia(id) * (mass / body.mass));
}

WorldSnapshot World::snapshot() const
{
    WorldSnapshot snapshot;
    snapshot.time = m_impl->time;
    snapshot.bodies.reserve(m_impl->bodies.size());
    for (const RigidBody& body : m_impl->bodies)
    {
        snapshot.bodies.push_back(stateOf(body));
    }
    snapshot.contacts = m_impl->contacts.save();
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
        if (body.removed)
        {
            continue;
        }
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
    m_impl->contacts.restore(snapshot.contacts, bodies.size()); // throws, changing nothing, when it does not fit
    bodies = std::move(restored);
    m_impl->wakeAll(); // a snapshot does not say who slept
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
    if (!(options.restingApproach >= 0.0) || !std::isfinite(options.restingApproach))
    {
        throw std::invalid_argument("resting_approach: must be a non-negative finite multiple of dt |g|");
    }
    if (options.collisionIterations < 0 || options.contactIterations < 1 || options.pairIterations < 1 ||
        options.shockIterations < 1)
    {
        throw std::invalid_argument("iterations: collision >= 0, contact >= 1, shock >= 1 and pair >= 1 required");
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
    if (!(options.sleepSpeed >= 0.0) || !std::isfinite(options.sleepSpeed))
    {
        throw std::invalid_argument("sleep_speed: must be a non-negative finite speed");
    }
    if (!(options.sleepTime >= 0.0) || !std::isfinite(options.sleepTime))
    {
        throw std::invalid_argument("sleep_time: must be a non-negative finite time");
    }
    if (!m_impl->smallestKnown)
    {
        m_impl->findSmallestBody();
    }
    if (const std::string reason = sizeRefusal(m_impl->smallestSize, options); !reason.empty())
    {
        throw std::invalid_argument("size: body " + std::to_string(m_impl->smallestBody) + ": " + reason);
    }
    m_impl->step(options);
}

std::uint32_t World::bodyCount() const
{
    return static_cast<std::uint32_t>(m_impl->bodies.size());
}

bool World::isDynamic(BodyId body) const
{
    return lookUp(*m_impl, body).dynamic;
}

bool World::isAsleep(BodyId body) const
{
    return lookUp(*m_impl, body).asleep;
}

BodyState World::state(BodyId id) const
{
    return stateOf(lookUp(*m_impl, id));
}

Real World::mass(BodyId body) const
{
    return lookUp(*m_impl, body).mass;
}

Vec3 World::principalInertia(BodyId body) const
{
    return lookUp(*m_impl, body).principalInertia;
}

Mat3 World::principalAxes(BodyId body) const
{
    return lookUp(*m_impl, body).inertiaAxes;
}

Mat3 World::inertia(BodyId id) const
{
    const RigidBody& body = lookUp(*m_impl, id);
    if (body.principalAxesAligned)
    {
        return body.principalInertia.asDiagonal();
    }
    return body.inertiaAxes * body.principalInertia.asDiagonal() * body.inertiaAxes.transpose();
}

Vec3 World::centerOfMass(BodyId body) const
{
    return -lookUp(*m_impl, body).shapeOffset;
}

const Shape& World::shape(BodyId body) const
{
    return lookUp(*m_impl, body).shape;
}

Pose World::shapePose(BodyId id) const
{
    const RigidBody& body = lookUp(*m_impl, id);
    return body.shapePose(body.pose());
}

MaterialId World::material(BodyId body) const
{
    return lookUp(*m_impl, body).material;
}

const Material& World::material(MaterialId material) const
{
    require(material.index < m_impl->materials.size(), "material",
            "no material " + std::to_string(material.index) + " in this world (it has " +
                std::to_string(m_impl->materials.size()) + ")");
    return m_impl->materials[material.index];
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

const std::vector<Contact>& World::contacts() const
{
    return m_impl->lastContacts;
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
