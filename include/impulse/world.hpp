// SPDX-License-Identifier: MIT
#pragma once

#include <impulse/body.hpp>
#include <impulse/material.hpp>
#include <impulse/math.hpp>

#include <cstdint>
#include <memory>
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
/// seconds.
struct WorldSnapshot
{
    Real time = 0.0;
    std::vector<BodyState> bodies; ///< every body in creation order, static ones included
};

/// Controls of one time step. Defaults are those of Guendelman, Bridson & Fedkiw 2003.
struct StepOptions
{
    Real dt = 1e-3; ///< seconds
    Scheme scheme = Scheme::Guendelman;
    int collisionIterations = 5;  ///< sweeps of the elastic collision pass
    int contactIterations = 10;   ///< sweeps of the contact pass; restitution ramps -1+1/n ... 0
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
};

/// What the last step did.
struct StepStats
{
    int candidatePairs = 0;    ///< pairs that passed the broad phase
    int collisionImpulses = 0; ///< impulses applied by the collision pass
    int contactImpulses = 0;   ///< impulses applied by the contact pass
    int collisionSweeps = 0;   ///< collision sweeps actually run (stops early when one applies none)
    int shockImpulses = 0;     ///< impulses applied by shock propagation
    int pushOutMoves = 0;      ///< pushes that moved a body (or a pair of bodies) out of an overlap
    int contactLevels = 0;     ///< levels of the contact graph
    int contactPairs = 0;      ///< candidate pairs touching (within the contact thickness) at the contact graph
    int islands = 0;           ///< groups of dynamic bodies connected by candidate pairs, solved independently
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
    BodyId createBody(const BodyDef& def);

    /// Places a dynamic body: centre of mass, orientation (normalised), linear and angular velocity,
    /// world frame. For loaders and adapters that keep the state elsewhere between steps. Throws
    /// std::invalid_argument for a static body or non-finite values.
    void setState(BodyId body, const Vec3& position, const Quat& orientation, const Vec3& linearVelocity,
                  const Vec3& angularVelocity);

    /// The state between steps, exactly; see WorldSnapshot.
    WorldSnapshot snapshot() const;
    /// Puts back a snapshot of this world or of one built the same way. Throws std::invalid_argument
    /// naming the body and field when the snapshot does not fit: another body count, a static body
    /// that is not where it is here, non-finite values, a quaternion that is not of unit length
    /// (within 1e-9), or an angular velocity that does not follow from the angular momentum.
    void restore(const WorldSnapshot& snapshot);

    /// Advances the world by options.dt with the separated collision / contact time step.
    void step(const StepOptions& options);

    std::uint32_t bodyCount() const;
    bool isDynamic(BodyId body) const;
    BodyState state(BodyId body) const;
    Real mass(BodyId body) const;             ///< infinite for static bodies
    Vec3 principalInertia(BodyId body) const; ///< body frame, kg m^2
    const Shape& shape(BodyId body) const;
    MaterialId material(BodyId body) const;
    const Material& material(MaterialId material) const;
    Vec3 gravity() const;
    Real time() const; ///< seconds simulated so far

    Real kineticEnergy() const;   ///< translational plus rotational, dynamic bodies
    Real potentialEnergy() const; ///< gravitational, zero at the world origin
    Vec3 linearMomentum() const;

    /// Counters of the last step.
    const StepStats& lastStepStats() const;

    /// A hash of every dynamic body's state bits: equal hashes mean bit-identical states.
    std::uint64_t stateHash() const;

  private:
    std::unique_ptr<WorldImpl> m_impl;
};

} // namespace impulse
