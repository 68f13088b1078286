// SPDX-License-Identifier: MIT
#pragma once

#include <impulse/body.hpp>
#include <impulse/material.hpp>
#include <impulse/math.hpp>

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

namespace impulse
{

struct WorldDef
{
    Vec3 gravity = Vec3(0.0, 0.0, -9.81); ///< m/s^2
};

/// The order of the stages of a time step.
enum class Scheme
{
    /// Guendelman, Bridson & Fedkiw 2003: collision pass on predicted poses, velocity update,
    /// contact pass, position update. Needs no velocity threshold.
    Guendelman,
    /// The textbook order: update velocities and positions, then detect and resolve collisions
    /// (material restitution) and contacts at the new positions. For comparison.
    Traditional,
};

/// Everything a world carries from one step to the next: the clock and every body's state exactly
/// as stored (the quaternion not renormalised, the angular momentum not rebuilt from the angular
/// velocity). Restored into the world it came from, or into one built from the same scene, it
/// continues the trajectory bit for bit, so a fault deep into a long run can be reached again in
/// seconds. Forces and torques applied for the next step are not part of it.
struct WorldSnapshot
{
    Real time = 0.0;
    /// every body in creation order, static ones included; a removed body keeps its entry (its pose
    /// when it was removed, at rest), and restore ignores the entry of a body removed here
    std::vector<BodyState> bodies;
    /// The contact layer's memory: each touching pair's cached points and the loads they carried,
    /// which the next step starts from. Opaque, but plain numbers (integers stored exactly), so that
    /// a checkpoint file can keep it bit for bit; empty means none (a world that starts cold).
    std::vector<double> contacts;
};

/// Controls of one time step. Defaults are those of Guendelman, Bridson & Fedkiw 2003.
struct StepOptions
{
    Real dt = 1e-3; ///< seconds
    Scheme scheme = Scheme::Guendelman;
    int collisionIterations = 5; ///< sweeps of the elastic collision pass
    /// Projected Gauss-Seidel sweeps of the contact pass over an island's contact points (more for a
    /// small island: up to as many as fit the work of this many sweeps over a thousand points, at
    /// most twenty times this); it stops early once a sweep changes no body's velocity by more than
    /// 1e-6 of the island's speeds.
    int contactIterations = 10;
    /// Cap on the Gauss-Seidel sweeps of each level in shock propagation, which solves a level's points
    /// to round-off and stops as soon as it has.
    int shockIterations = 8;
    int pairIterations = 20;      ///< cap on impulses per pair within one sweep
    Real contactThickness = 1e-6; ///< m; the contact pass treats points closer than this as touching
    /// Size collision impulses with the time-n velocity v + dt*a/2 (exact energy for eps = 1) rather
    /// than with v alone, which loses m*|g|*|v|*dt per bounce. The approach test always uses v.
    bool midStepRestitution = true;
    /// Evaluate the geometry of a collision (point, normal, lever arms) at the estimated time of
    /// first touch within the step rather than at the predicted, already overlapping, pose.
    bool timeOfImpactGeometry = true;
    /// m/s; collisions approaching slower than this are resolved with restitution 0. Zero, the
    /// default, means no threshold: the Guendelman order needs none, and the traditional order
    /// then shows the artefacts a threshold is usually added to hide.
    Real restitutionThreshold = 0.0;
    /// Approach slower than this many times dt*|g| (the speed gravity adds in one step) is resting
    /// contact, left to the contact pass: the collision pass applies no impulse there, and the
    /// restitution of slightly faster approaches fades in linearly up to twice that speed. It keeps
    /// the collision pass off the residual speeds the contact pass leaves in resting piles; a
    /// bounce it removes would rise at most 2 (dt |g|)^2 / |g|, 0.02 mm at dt = 1 ms. 0 treats every
    /// approach above the solver's round-off as a collision.
    Real restingApproach = 1.0;
    /// End the contact pass with one shock-propagation sweep (GBF03 sec. 8): level by level up the
    /// contact graph with restitution 0, every lower level frozen, so stacks stand with few
    /// iterations. Costs exact momentum conservation within that sweep.
    bool shockPropagation = true;
    /// After the position update, move bodies that overlap deeper than pushOutAllowance apart:
    /// poses only (translated and turned; velocities and angular momenta kept), level by level up the contact graph
    /// with lower levels held still. The passes only remove approach, so an overlap left by a dense impact would
    /// otherwise stay for as long as the bodies rest on each other.
    bool pushOut = true;
    Real pushOutAllowance = 1e-4; ///< m; shallower overlaps are left alone
    Real pushOutSpeed = 10.0;     ///< m/s; no point of a body moves further than this times dt in one step
    int pushOutIterations = 2;    ///< sweeps up the levels; stops early after one that moves nothing
    /// Worker threads for the narrow phase and for islands of touching bodies; 0 means one per
    /// hardware thread. Trajectories are bit-identical whatever the number.
    int threads = 1;
    /// Let islands at rest sleep: a body whose points all move slower than sleepSpeed for sleepTime
    /// rests, and once every body of its island does, the island is put to sleep: velocities zeroed,
    /// left out of every pass (its contacts are not listed by World::contacts()) until a candidate
    /// pair joins it to an awake body, or the API touches one of its bodies (setState, a force, an
    /// impulse, a filter, new mass properties, a removal). Off by default: a sleeping island does not
    /// feel the slow motions it would otherwise have.
    bool sleep = false;
    Real sleepSpeed = 0.01; ///< m/s; the fastest point of a body at rest: |v| + |w| r
    Real sleepTime = 0.5;   ///< s a body must rest before its island may sleep
    /// Verification mode for tests: every use of the contact layer's cached points also runs the exact
    /// narrow phase, and a point missed or a separation off by more than the pair's motion since
    /// capture allows makes step() throw std::logic_error. Slow; it changes no result.
    bool verifyContacts = false;
};

/// A contact point of the last step and what it carried: the impulses the contact pass and shock
/// propagation applied there during that step (the collision pass's elastic impulses are not
/// included). Divided by the step, they are the contact force: a box of mass m resting on the ground
/// has normal impulses summing to m g dt.
struct Contact
{
    BodyId a;                            ///< the body the impulse acts on as given
    BodyId b;                            ///< the body receiving the opposite
    Vec3 point = Vec3::Zero();           ///< world frame
    Vec3 normal = Vec3::UnitZ();         ///< unit, from b toward a
    Real separation = 0.0;               ///< signed distance at the step's start pose, m; negative overlaps
    Real normalImpulse = 0.0;            ///< along the normal, on a, N s (>= 0)
    Vec3 frictionImpulse = Vec3::Zero(); ///< across the normal, on a, N s
};

/// What the last step did.
struct StepStats
{
    int candidatePairs = 0;    ///< pairs that passed the broad phase
    int broadPhaseRepeats = 0; ///< times the broad phase ran again for bodies sped beyond their boxes
    int collisionImpulses = 0; ///< impulses applied by the collision pass
    int collisionSweeps = 0;   ///< collision sweeps actually run (stops early when one applies none)
    int pushOutMoves = 0;      ///< pushes that moved a body (or a pair of bodies) out of an overlap
    int contactLevels = 0;     ///< levels of the contact graph
    int contactPairs = 0;      ///< candidate pairs touching (within the contact thickness) at the contact graph
    int narrowPhaseCalls = 0;  ///< exact detections of a pair by the contact layer (captures, exact pairs)
    int contactCaptures = 0;   ///< pairs whose points the contact layer captured anew
    int contactRows = 0;       ///< contact points the contact pass solved
    int contactSweeps = 0;     ///< Gauss-Seidel sweeps of the contact pass, most of any island
    int coldRestarts = 0;      ///< islands solved again from no load (a warm start gained energy)
    int shockIterations = 0;   ///< sweeps of shock propagation, summed over levels
    int islands = 0;           ///< groups of dynamic bodies connected by candidate pairs, solved independently
    int sleepingBodies = 0;    ///< bodies asleep at the end of the step (StepOptions::sleep)
    int threads = 1;           ///< worker threads the step used
    /// Wall time of each stage of the step, milliseconds (measured, so not deterministic).
    struct StageTimes
    {
        double candidatePairs = 0.0; ///< predictions, broad phase and islands
        double collisionPass = 0.0;
        double contactGraph = 0.0;
        double contactPass = 0.0; ///< with the velocity update
        double shockPropagation = 0.0;
        double positionUpdate = 0.0;
        double pushOut = 0.0;
    } milliseconds;
};

/// A legal input that gives a poor simulation: what was found, why it matters and what to do, in
/// one message (docs/warnings.md gives each kind's criterion). Bodies are named as World::warnings
/// is told, else "body k" with k the index in creation order (a scene file's /bodies/k).
struct Warning
{
    enum class Kind
    {
        LargeTimeStep,  ///< gravity moves a body from rest more than an eighth of the smallest body's size in one step
        FastBody,       ///< a body's initial speed moves it more than half the smallest body's size in one step
        SmallBody,      ///< a body less than a hundred times the step's largest length tolerance
        InitialOverlap, ///< two bodies that collide overlap at the start by more than the contact thickness
        MassRatio,      ///< two bodies that can touch differ in mass more than ten thousand times
        FarFromOrigin,  ///< coordinates so large that their round-off is over a hundredth of the contact thickness
    };
    Kind kind;
    std::string message;
};

/// The smallest thinnestHalfExtent that the length tolerances of `options` serve: ten times the
/// largest of the contact thickness, the push-out allowance (when push-out is on) and the 1e-9 m to
/// which push-out converges. A body rests anywhere within the contact thickness of a surface, and an
/// overlap within the allowance is left as it is, so each must be at most a tenth of every body.
Real smallestServedSize(const StepOptions& options);

/// Why a body whose thinnest half extent is `size` cannot be simulated with `options` (the
/// tolerance that does not serve it, and what to set), or "" when it can. World::step throws
/// std::invalid_argument with this reason for the smallest body of a world.
std::string sizeRefusal(Real size, const StepOptions& options);

class WorldImpl;

/// A set of rigid bodies advanced together.
class World
{
  public:
    explicit World(const WorldDef& def = {});
    ~World();
    World(World&&) noexcept;
    World& operator=(World&&) noexcept;
    World(const World&) = delete;
    World& operator=(const World&) = delete;

    /// Adds a material; every body names one.
    MaterialId createMaterial(const Material& material);
    /// Overrides the pair rule for one pair of materials (in either order).
    void setPairCoefficients(MaterialId a, MaterialId b, const PairCoefficients& coefficients);
    /// Coefficients that govern contact between the two materials.
    PairCoefficients pairCoefficients(MaterialId a, MaterialId b) const;

    /// Adds a body. Throws std::invalid_argument naming the offending field if the definition is
    /// not physical (non-positive size or mass, non-finite numbers, a dynamic plane, ...).
    ///
    /// Every function below that takes a BodyId throws std::invalid_argument ("body: ...") for a
    /// handle that names no body of this world or a removed one, and for a value that is not
    /// finite, naming the argument.
    BodyId createBody(const BodyDef& def);

    /// Places a dynamic body: centre of mass, orientation (normalised), linear and angular velocity,
    /// world frame. For loaders and adapters that keep the state elsewhere between steps. Throws
    /// std::invalid_argument for a static body or non-finite values.
    void setState(BodyId body, const Vec3& position, const Quat& orientation, const Vec3& linearVelocity,
                  const Vec3& angularVelocity);

    /// Takes a body out of the world: it no longer collides, moves or counts in the energies and
    /// the momentum, and its handle is refused from then on. No other body is renumbered, and its
    /// number is not given to a later body. Throws std::invalid_argument for an unknown handle.
    void removeBody(BodyId body);
    /// Whether the handle names a body of this world that has not been removed.
    bool contains(BodyId body) const;

    /// Adds a force through the centre of mass, world frame, newtons. Forces and torques add up
    /// until the next step, act during it (v += dt (g + F/m), L += dt tau) and are then cleared:
    /// a force that lasts is applied before every step.
    void applyForce(BodyId body, const Vec3& force);
    /// Adds a force acting at a world point: the force through the centre of mass plus the torque
    /// (point - centre of mass) x force, for the next step.
    void applyForce(BodyId body, const Vec3& force, const Vec3& worldPoint);
    /// Adds a torque about the centre of mass, world frame, N m, for the next step.
    void applyTorque(BodyId body, const Vec3& torque);
    /// Changes the velocities at once by an impulse through the centre of mass, N s: v += J / m.
    void applyImpulse(BodyId body, const Vec3& impulse);
    /// Changes the velocities at once by an impulse at a world point: v += J / m,
    /// L += (point - centre of mass) x J, w = I(q)^-1 L.
    void applyImpulse(BodyId body, const Vec3& impulse, const Vec3& worldPoint);
    /// Changes the angular momentum at once, N m s: L += H.
    void applyAngularImpulse(BodyId body, const Vec3& angularImpulse);
    /// The force and the torque (about the centre of mass) applied so far for the next step.
    Vec3 appliedForce(BodyId body) const;
    Vec3 appliedTorque(BodyId body) const;

    /// Sets which bodies this one collides with; see CollisionFilter. Takes effect at the next step.
    void setCollisionFilter(BodyId body, const CollisionFilter& filter);
    CollisionFilter collisionFilter(BodyId body) const;
    /// Lets one pair of bodies collide or not, whatever their filters say (false: they pass through
    /// each other). A pair is enabled until disabled.
    void setCollisionEnabled(BodyId a, BodyId b, bool enabled);
    /// Whether the two bodies may collide: their filters agree and the pair is not disabled.
    bool collisionEnabled(BodyId a, BodyId b) const;

    /// Gives a dynamic body another mass (kg) and inertia tensor (kg m^2, about the centre of mass,
    /// in the body frame, the frame the shape is defined in). The tensor must be symmetric and
    /// positive definite, its principal moments obeying the triangle inequality (I1 + I2 >= I3, as
    /// for any real body, to a relative 1e-9). The body frame stays the shape's: a tensor with
    /// products of inertia is diagonalised, I = A diag(I1, I2, I3) A^T, and the dynamics use its
    /// principal axes A (see principalAxes). The centre of mass stays where it is. The linear and
    /// angular velocity are kept, the angular momentum becomes I w.
    void setMassProperties(BodyId body, Real mass, const Mat3& inertia);
    /// As above, and moves the centre of mass to `centerOfMass` in the shape's frame (see
    /// BodyDef::centerOfMass). The shape stays where it is and moves as it did: the body's position
    /// becomes the new centre and its velocity that point's velocity.
    void setMassProperties(BodyId body, Real mass, const Mat3& inertia, const Vec3& centerOfMass);
    /// Sets the mass and scales the inertia tensor with it (the shape's density changes).
    void setMass(BodyId body, Real mass);

    /// The state between steps, exactly; see WorldSnapshot.
    WorldSnapshot snapshot() const;
    /// Puts back a snapshot of this world or of one built the same way. Throws std::invalid_argument
    /// naming the body and field when the snapshot does not fit: another body count, a static body
    /// that is not where it is here, non-finite values, a quaternion that is not of unit length
    /// (within 1e-9), or an angular velocity that does not follow from the angular momentum.
    void restore(const WorldSnapshot& snapshot);

    /// Advances the world by options.dt with the separated collision / contact time step. Throws
    /// std::invalid_argument ("size: ...") when a body is smaller than the options' length tolerances
    /// serve (see sizeRefusal).
    void step(const StepOptions& options);

    /// What would make stepping this world from its present state with `options` a poor simulation
    /// (docs/warnings.md): a time step too large for the bodies, a body near the smallest size the
    /// tolerances serve, bodies overlapping, masses too far apart, coordinates too large for the
    /// contact thickness. Empty when nothing was found. `names`, per body in creation order, names the
    /// bodies in the messages; a missing or empty name gives "body k". Costs a broad phase and a
    /// narrow phase over the touching pairs: meant for once, after a scene is built.
    std::vector<Warning> warnings(const StepOptions& options, const std::vector<std::string>& names = {}) const;

    /// Bodies ever created, removed ones included: valid handles are numbered below it.
    std::uint32_t bodyCount() const;
    bool isDynamic(BodyId body) const;
    /// Whether the body sleeps (StepOptions::sleep): at rest and left out of the step until woken.
    bool isAsleep(BodyId body) const;
    BodyState state(BodyId body) const;
    Real mass(BodyId body) const;             ///< infinite for static bodies
    Vec3 principalInertia(BodyId body) const; ///< principal moments, kg m^2 (zero for static bodies)
    /// The principal axes of inertia in the body frame, as the columns of a rotation matrix A:
    /// inertia(body) = A diag(principalInertia(body)) A^T. The identity unless setMassProperties was
    /// given a tensor with products of inertia.
    Mat3 principalAxes(BodyId body) const;
    Mat3 inertia(BodyId body) const; ///< the inertia tensor about the centre of mass, body frame, kg m^2
    /// The centre of mass in the shape's frame (BodyDef::centerOfMass); zero unless one was given.
    Vec3 centerOfMass(BodyId body) const;
    const Shape& shape(BodyId body) const;
    /// Where the shape lies: the state's pose moved from the centre of mass to the shape's origin.
    /// The state's pose itself when the centre of mass is the shape's centroid.
    Pose shapePose(BodyId body) const;
    MaterialId material(BodyId body) const;
    const Material& material(MaterialId material) const;
    Vec3 gravity() const;
    Real time() const; ///< seconds simulated so far

    Real kineticEnergy() const;   ///< translational plus rotational, dynamic bodies
    Real potentialEnergy() const; ///< gravitational, zero at the world origin
    Vec3 linearMomentum() const;

    /// Counters of the last step.
    const StepStats& lastStepStats() const;

    /// The contact points of the last step that carried load (a normal impulse), in a fixed order: by
    /// pair (lower body index first), then as the pair's points were found. Empty before any step.
    const std::vector<Contact>& contacts() const;

    /// A hash of every dynamic body's state bits: equal hashes mean bit-identical states.
    std::uint64_t stateHash() const;

  private:
    std::unique_ptr<WorldImpl> m_impl;
};

} // namespace impulse
