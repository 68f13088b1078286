// SPDX-License-Identifier: MIT
// Contact rows and their projected Gauss-Seidel solve, shared by the contact pass, shock propagation
// and the collision pass's patches.
//
// A row is one contact point between bodies A and B: its normal and two tangents, the lever arms'
// Jacobians and the bodies' angular responses to them, and the impulses accumulated on it
// (lambda_n >= 0 along the normal, |lambda_t| <= mu lambda_n along the tangents). Visiting a row
// moves its accumulated impulses toward the target (relative normal velocity `bias`, no slip) and
// projects them back into the friction cone, applying only the change: impulses can be taken back as
// well as added, so a row that should not carry load lets go of what it carried.
#pragma once

#include "collision/contact.hpp"
#include "contact/contact_cache.hpp"
#include "dynamics/rigid_body.hpp"

#include <array>
#include <cstdint>
#include <span>
#include <vector>

namespace impulse
{

/// How closely the contact passes solve, relative to the speeds involved (the fastest surface speed
/// of an island plus what gravity adds in one step): a contact pass stops once a sweep changes no
/// relative velocity by more than this, and the collision pass counts a normal velocity within this
/// of its speeds as no approach.
constexpr Real kSolverResolution = 1e-6;

/// A body's velocities while rows are solved. The angular momentum is carried beside the angular
/// velocity, both changed by every impulse, so that neither is rebuilt from the other mid-solve.
struct SolverBody
{
    Vec3 linearVelocity = Vec3::Zero();
    Vec3 angularVelocity = Vec3::Zero();
    Vec3 angularMomentum = Vec3::Zero();
    Real mass = 0.0;    ///< zero for a static body
    Real invMass = 0.0; ///< zero for a static body
    Real reach = 0.0;   ///< bounding radius: how far a point is from the centre, at most

    static SolverBody of(const RigidBody& body);
    /// How fast the body's points move at most.
    Real pointSpeed() const { return linearVelocity.norm() + angularVelocity.norm() * reach; }
    Real kineticEnergy() const
    {
        return 0.5 * (mass * linearVelocity.squaredNorm() + angularVelocity.dot(angularMomentum));
    }
    /// Writes the velocities back; the angular velocity is recomputed from the angular momentum.
    void storeInto(RigidBody& body) const;
};

/// Which bodies of a row receive its impulses.
enum RowMovable : std::uint8_t
{
    kMovesA = 1,
    kMovesB = 2,
};

/// One contact point as the solver sees it. Directions: 0 the normal (from B toward A), 1 and 2 the
/// tangents.
struct ContactRow
{
    std::uint32_t a = 0;       ///< index of A in the solver's bodies
    std::uint32_t b = 0;       ///< index of B
    std::uint8_t movable = 0;  ///< RowMovable bits
    Vec3 point = Vec3::Zero(); ///< where it acts, world frame
    std::array<Vec3, 3> direction;
    std::array<Vec3, 3> armA;  ///< r_A x d
    std::array<Vec3, 3> armB;  ///< r_B x d
    std::array<Vec3, 3> turnA; ///< I_A^-1 (r_A x d)
    std::array<Vec3, 3> turnB; ///< I_B^-1 (r_B x d)
    Real invMassA = 0.0;
    Real invMassB = 0.0;
    /// Each body's share of the row's compliance K (the change of relative velocity along one
    /// direction per unit impulse along another): nn, then the tangent block 11, 12, 22, then the
    /// coupling of the normal into the tangents, n1, n2.
    std::array<Real, 6> complianceA{};
    std::array<Real, 6> complianceB{};
    /// The same for the bodies that move: their sum, the normal's effective mass 1 / nn, and the
    /// inverse of the tangent block (11, 12, 22).
    std::array<Real, 6> compliance{};
    Real normalMass = 0.0;
    std::array<Real, 3> tangentInverse{};
    /// Separation at the start of the step's motion: the row touches while gap + lookahead u_n is
    /// below the contact thickness (a row that carries load stays in play until it lets go).
    Real gap = 0.0;
    Real bias = 0.0;              ///< target relative normal velocity (0 in the contact passes)
    Real friction = 0.0;          ///< Coulomb mu
    std::array<Real, 3> lambda{}; ///< accumulated impulses, N s
    ContactLoad* load = nullptr;  ///< where the impulses persist between steps, if anywhere

    /// Relative velocity u_A - u_B along direction k.
    Real relativeVelocity(std::size_t k, const SolverBody& bodyA, const SolverBody& bodyB) const
    {
        return direction[k].dot(bodyA.linearVelocity - bodyB.linearVelocity) + armA[k].dot(bodyA.angularVelocity) -
               armB[k].dot(bodyB.angularVelocity);
    }
};

/// What the solves reuse from call to call, one per worker thread.
struct SolverScratch
{
    // solveRows
    std::vector<std::array<Real, 3>> before;    ///< each row's impulses before the sweep
    std::vector<std::array<Real, 3>> direction; ///< the conjugate-gradient search direction
    std::vector<std::uint32_t> moved;           ///< the bodies the rows move
    std::vector<std::uint8_t> listed;           ///< per body: already in `moved` (all 0 between solves)
    std::vector<SolverBody> start;              ///< their velocities before the sweep
    // solveRigidPatch
    std::vector<Real> side;
    std::vector<Vec3> wanted;
    std::vector<Vec3> lever;
    std::vector<Vec3> spread;
    std::vector<std::array<Real, 3>> loads;
    // the collision pass's patches
    std::vector<ContactPoint> patch;
    std::vector<ContactPoint> kept;
    std::vector<Real> gap;
    std::vector<ContactRow> rows;
    std::vector<ContactRow*> pointers;
};

/// A side of a row: how impulses move it. A side that does not move has zero inverse mass.
struct RowSide
{
    std::uint32_t index = 0; ///< in the solver's bodies
    bool moves = false;
    Real invMass = 0.0;
    Mat3 invInertia = Mat3::Zero(); ///< world frame
    Vec3 centre = Vec3::Zero();     ///< the centre lever arms are taken from

    /// A body with lever arms from `centre` (leverCentres), with its inverse inertia of time n.
    static RowSide of(const RigidBody& body, std::uint32_t index, const Vec3& centre)
    {
        return {index, body.dynamic, body.dynamic ? body.invMass : 0.0,
                body.dynamic ? body.invInertiaWorld : Mat3::Zero(), centre};
    }
};

/// The row of `point` between sides a and b, with the tangents given (the basis loads are kept in).
/// Both sides move if they can until setMovable says otherwise.
ContactRow makeContactRow(const RowSide& a, const RowSide& b, const ContactPoint& point, const Vec3& tangent1,
                          const Vec3& tangent2, Real friction);

/// Sets which of the row's bodies receive its impulses and the effective masses that follow.
void setMovable(ContactRow& row, std::uint8_t movable);

/// When a row is in play and how closely rows are solved.
struct RowSettings
{
    Real lookahead = 0.0; ///< how far ahead, s, the gap is judged (dt in the Guendelman order)
    Real thickness = 0.0; ///< rows closer than this touch
};

/// One projected Gauss-Seidel visit of a row: the normal impulse toward the target (kept >= 0), then
/// the friction toward no slip (kept within mu times the normal impulse). Returns the largest change
/// of a relative velocity the visit made (m/s), 0 for a row out of play.
Real solveRow(ContactRow& row, std::span<SolverBody> bodies, const RowSettings& settings);

/// Applies impulses (normal, tangent1, tangent2) along the row's directions: + to A, - to B, to each
/// that moves.
void applyImpulses(const ContactRow& row, Real normal, Real tangent1, Real tangent2, SolverBody& bodyA,
                   SolverBody& bodyB);

/// Applies the row's accumulated impulses to its bodies (a warm start).
void applyRowImpulses(const ContactRow& row, std::span<SolverBody> bodies);

/// How solveRows iterates.
enum class Sweeps
{
    Plain,       ///< projected Gauss-Seidel
    Accelerated, ///< each sweep followed by a conjugate-gradient step along the previous sweeps' changes
    /// Accelerated, starting from and leaving the search direction in the rows' loads (ContactLoad),
    /// so that the iteration goes on across steps
    Continued,
};

/// Sweeps over `rows` in order until a sweep changes the velocity of no point of a body it moves by
/// more than `tolerance`, or `maxSweeps`. Acceleration is for islands, whose slow modes plain
/// Gauss-Seidel takes thousands of sweeps to cross. Returns the sweeps run.
int solveRows(std::span<ContactRow> rows, std::span<SolverBody> bodies, const RowSettings& settings, int maxSweeps,
              Real tolerance, Sweeps kind, SolverScratch& scratch);

} // namespace impulse
