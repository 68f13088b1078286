// SPDX-License-Identifier: MIT
#include "dynamics/contact_solver.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

namespace impulse
{

SolverBody SolverBody::of(const RigidBody& body)
{
    SolverBody solver;
    solver.linearVelocity = body.linearVelocity;
    solver.angularVelocity = body.angularVelocity;
    solver.angularMomentum = body.angularMomentum;
    solver.mass = body.dynamic ? body.mass : 0.0;
    solver.invMass = body.invMass;
    solver.reach = body.dynamic ? body.boundingRadius : 0.0;
    return solver;
}

void SolverBody::storeInto(RigidBody& body) const
{
    body.linearVelocity = linearVelocity;
    body.angularMomentum = angularMomentum;
    body.angularVelocity = body.invInertiaWorld * body.angularMomentum;
}

ContactRow makeContactRow(const RowSide& a, const RowSide& b, const ContactPoint& point, const Vec3& tangent1,
                          const Vec3& tangent2, Real friction)
{
    ContactRow row;
    row.a = a.index;
    row.b = b.index;
    row.point = point.point;
    row.direction = {point.normal, tangent1, tangent2};
    row.friction = friction;
    row.invMassA = a.invMass;
    row.invMassB = b.invMass;
    const Vec3 leverA = point.point - a.centre;
    const Vec3 leverB = point.point - b.centre;
    for (std::size_t k = 0; k < 3; ++k)
    {
        row.armA[k] = leverA.cross(row.direction[k]);
        row.armB[k] = leverB.cross(row.direction[k]);
        row.turnA[k] = a.invInertia * row.armA[k];
        row.turnB[k] = b.invInertia * row.armB[k];
    }
    // the directions are orthonormal, so the linear part adds 1/m on the diagonal only
    const auto compliance = [](Real invMass, const std::array<Vec3, 3>& arm, const std::array<Vec3, 3>& turn)
    {
        return std::array<Real, 6>{invMass + arm[0].dot(turn[0]), invMass + arm[1].dot(turn[1]), arm[1].dot(turn[2]),
                                   invMass + arm[2].dot(turn[2]), arm[1].dot(turn[0]),           arm[2].dot(turn[0])};
    };
    row.complianceA = compliance(row.invMassA, row.armA, row.turnA);
    row.complianceB = compliance(row.invMassB, row.armB, row.turnB);
    setMovable(row, static_cast<std::uint8_t>((a.moves ? kMovesA : 0) | (b.moves ? kMovesB : 0)));
    return row;
}

void setMovable(ContactRow& row, std::uint8_t movable)
{
    row.movable = movable;
    std::array<Real, 6>& k = row.compliance;
    for (std::size_t i = 0; i < k.size(); ++i)
    {
        k[i] = ((movable & kMovesA) != 0 ? row.complianceA[i] : 0.0) +
               ((movable & kMovesB) != 0 ? row.complianceB[i] : 0.0);
    }
    row.normalMass = k[0] > 0.0 ? 1.0 / k[0] : 0.0;
    const Real determinant = k[1] * k[3] - k[2] * k[2];
    if (determinant > 0.0)
    {
        row.tangentInverse = {k[3] / determinant, -k[2] / determinant, k[1] / determinant};
    }
    else
    {
        row.tangentInverse = {0.0, 0.0, 0.0};
    }
}

// Applies the impulses (normal, tangent1, tangent2) of the row: + to A, - to B, each if it moves.
void applyImpulses(const ContactRow& row, Real normal, Real tangent1, Real tangent2, SolverBody& bodyA,
                   SolverBody& bodyB)
{
    const Vec3 impulse = normal * row.direction[0] + tangent1 * row.direction[1] + tangent2 * row.direction[2];
    if ((row.movable & kMovesA) != 0)
    {
        bodyA.linearVelocity += row.invMassA * impulse;
        bodyA.angularVelocity += normal * row.turnA[0] + tangent1 * row.turnA[1] + tangent2 * row.turnA[2];
        bodyA.angularMomentum += normal * row.armA[0] + tangent1 * row.armA[1] + tangent2 * row.armA[2];
    }
    if ((row.movable & kMovesB) != 0)
    {
        bodyB.linearVelocity -= row.invMassB * impulse;
        bodyB.angularVelocity -= normal * row.turnB[0] + tangent1 * row.turnB[1] + tangent2 * row.turnB[2];
        bodyB.angularMomentum -= normal * row.armB[0] + tangent1 * row.armB[1] + tangent2 * row.armB[2];
    }
}

namespace
{

// The friction impulse within the cone |t| <= radius nearest to the sticking one, `wanted`, in the
// metric of the tangent block K = (k11, k12; k12, k22): the projection that leaves the slip after it
// opposite the impulse, Coulomb's maximum dissipation. (Clamping in the plain metric would turn the
// friction of an off-centre point away from its slip wherever K is not isotropic, and a sliding box
// would feel less than mu times its load along its slide.) On the cone's edge t = (K + nu 1)^-1 K
// wanted for the nu >= 0 that puts it there, found by Newton's method on 1/|t(nu)|, which is nearly
// linear in nu and approached from below.
//
// Each eigen-component of t is lambda / (lambda + nu) of wanted's, a share that grows with lambda, so
// |t(nu)| >= lambda_min / (lambda_min + nu) |wanted|: at nu = lambda_min (|wanted| / r - 1) t is still
// outside the cone. Newton starts there: below the root, as from nu = 0, and at the root itself where
// K is isotropic (a point under a body's centre). In a formed pile a quarter of the row visits end
// on the cone, and this projection is more than half of the row solve's time.
std::array<Real, 2> projectOntoCone(Real k11, Real k12, Real k22, Real wanted1, Real wanted2, Real radius)
{
    if (!(radius > 0.0))
    {
        return {0.0, 0.0};
    }
    const Real p = k11 * wanted1 + k12 * wanted2; // K wanted
    const Real q = k12 * wanted1 + k22 * wanted2;
    const Real halfDifference = 0.5 * (k11 - k22);
    const Real leastEigenvalue = 0.5 * (k11 + k22) - std::sqrt(halfDifference * halfDifference + k12 * k12);
    const Real wanted = std::sqrt(wanted1 * wanted1 + wanted2 * wanted2);
    Real nu = std::max(0.0, leastEigenvalue * (wanted / radius - 1.0));
    Real z1 = wanted1;
    Real z2 = wanted2;
    // t = (K + nu 1)^-1 K wanted at the current nu
    const auto moveToNu = [&]
    {
        const Real a = k11 + nu;
        const Real c = k22 + nu;
        const Real determinant = a * c - k12 * k12;
        z1 = (c * p - k12 * q) / determinant;
        z2 = (a * q - k12 * p) / determinant;
    };
    if (nu > 0.0)
    {
        moveToNu();
    }
    for (int iteration = 0; iteration < 30; ++iteration)
    {
        const Real length2 = z1 * z1 + z2 * z2;
        const Real length = std::sqrt(length2);
        if (!(length > radius * (1.0 + 1e-13)))
        {
            break;
        }
        // d z / d nu = -(K + nu 1)^-1 z, so d(1/|z|)/d nu = z.(K + nu 1)^-1 z / |z|^3
        const Real a = k11 + nu;
        const Real c = k22 + nu;
        const Real determinant = a * c - k12 * k12;
        const Real zMz = (c * z1 * z1 - 2.0 * k12 * z1 * z2 + a * z2 * z2) / determinant;
        const Real step = (1.0 / radius - 1.0 / length) * length2 * length / zMz;
        if (!(step > 0.0) || !std::isfinite(step))
        {
            break;
        }
        nu += step;
        moveToNu();
    }
    // on the edge exactly, whatever Newton's last step left
    const Real length = std::sqrt(z1 * z1 + z2 * z2);
    const Real scale = length > radius ? radius / length : 1.0;
    return {scale * z1, scale * z2};
}

} // namespace

Real solveRow(ContactRow& row, std::span<SolverBody> bodies, const RowSettings& settings)
{
    if (!(row.normalMass > 0.0))
    {
        return 0.0; // neither body moves
    }
    SolverBody& bodyA = bodies[row.a];
    SolverBody& bodyB = bodies[row.b];
    const Vec3 linear = bodyA.linearVelocity - bodyB.linearVelocity;
    const auto velocity = [&](std::size_t k)
    {
        return row.direction[k].dot(linear) + row.armA[k].dot(bodyA.angularVelocity) -
               row.armB[k].dot(bodyB.angularVelocity);
    };
    const Real un = velocity(0);
    if (row.lambda[0] == 0.0 && !(row.gap + settings.lookahead * un < settings.thickness))
    {
        return 0.0; // apart, and carrying nothing
    }
    const std::array<Real, 6>& k = row.compliance;
    // the normal toward its target, kept >= 0
    const Real normal = std::max(0.0, row.lambda[0] + (row.bias - un) * row.normalMass);
    const Real normalChange = normal - row.lambda[0];
    // then the friction toward no slip, seeing the slip the normal's change makes, within mu normal
    const Real u1 = velocity(1) + normalChange * k[4];
    const Real u2 = velocity(2) + normalChange * k[5];
    Real t1 = row.lambda[1] - (row.tangentInverse[0] * u1 + row.tangentInverse[1] * u2);
    Real t2 = row.lambda[2] - (row.tangentInverse[1] * u1 + row.tangentInverse[2] * u2);
    const Real limit = row.friction * normal;
    if (t1 * t1 + t2 * t2 > limit * limit)
    {
        const std::array<Real, 2> sliding = projectOntoCone(k[1], k[2], k[3], t1, t2, limit);
        t1 = sliding[0];
        t2 = sliding[1];
    }
    const Real change1 = t1 - row.lambda[1];
    const Real change2 = t2 - row.lambda[2];
    row.lambda = {normal, t1, t2};
    applyImpulses(row, normalChange, change1, change2, bodyA, bodyB);
    return std::max(std::abs(normalChange) * k[0], std::max(std::abs(change1) * k[1], std::abs(change2) * k[3]));
}

void applyRowImpulses(const ContactRow& row, std::span<SolverBody> bodies)
{
    applyImpulses(row, row.lambda[0], row.lambda[1], row.lambda[2], bodies[row.a], bodies[row.b]);
}

int solveRows(std::span<ContactRow> rows, std::span<SolverBody> bodies, const RowSettings& settings, int maxSweeps,
              Real tolerance, Sweeps kind, SolverScratch& scratch)
{
    const bool accelerate = kind != Sweeps::Plain;
    const bool continued = kind == Sweeps::Continued;
    // Projected Gauss-Seidel, accelerated on request by nonsmooth nonlinear conjugate gradients
    // (Silcowitz, Niebe & Erleben 2010): a sweep's change of the impulses is a descent direction, and
    // a step along the previous direction, scaled by the ratio of the squared changes (Fletcher-
    // Reeves), crosses the slow modes of a tall stack (its bending, its tipping) in tens of sweeps
    // instead of thousands. A ratio above one restarts the directions. The step is projected back
    // into the cones, and only what changes is applied to the bodies.
    //
    // Converged is judged on the bodies, not the rows: a sweep after which no body's points move
    // differently than before it (by more than `tolerance`) has reached a fixed point, even where
    // redundant points keep trading load among themselves.
    std::vector<std::array<Real, 3>>& before = scratch.before;
    std::vector<std::array<Real, 3>>& direction = scratch.direction;
    std::vector<std::uint32_t>& moved = scratch.moved;
    std::vector<SolverBody>& start = scratch.start;
    // each body once, in the order the rows first name it (only a maximum is taken over them)
    moved.clear();
    scratch.listed.resize(bodies.size(), 0);
    const auto list = [&](std::uint32_t i)
    {
        if (scratch.listed[i] == 0)
        {
            scratch.listed[i] = 1;
            moved.push_back(i);
        }
    };
    for (const ContactRow& row : rows)
    {
        if ((row.movable & kMovesA) != 0)
        {
            list(row.a);
        }
        if ((row.movable & kMovesB) != 0)
        {
            list(row.b);
        }
    }
    for (const std::uint32_t i : moved)
    {
        scratch.listed[i] = 0;
    }
    start.resize(moved.size());
    Real previous = 0.0;
    if (accelerate)
    {
        before.resize(rows.size());
        direction.assign(rows.size(), {0.0, 0.0, 0.0});
    }
    if (continued)
    {
        for (std::size_t r = 0; r < rows.size(); ++r)
        {
            if (rows[r].load != nullptr)
            {
                direction[r] = rows[r].load->direction;
                for (const Real change : rows[r].load->change)
                {
                    previous += change * change;
                }
            }
        }
    }
    const auto keep = [&]
    {
        for (std::size_t r = 0; continued && r < rows.size(); ++r)
        {
            if (rows[r].load != nullptr)
            {
                rows[r].load->direction = direction[r];
                for (std::size_t k = 0; k < 3; ++k)
                {
                    rows[r].load->change[k] = rows[r].lambda[k] - before[r][k];
                }
            }
        }
    };
    int sweeps = 0;
    while (sweeps < maxSweeps)
    {
        ++sweeps;
        for (std::size_t i = 0; i < moved.size(); ++i)
        {
            start[i] = bodies[moved[i]];
        }
        // the sweep, summing the squared change of the impulses on the way (for the step below)
        Real squared = 0.0;
        for (std::size_t r = 0; r < rows.size(); ++r)
        {
            if (!accelerate)
            {
                solveRow(rows[r], bodies, settings);
                continue;
            }
            before[r] = rows[r].lambda;
            solveRow(rows[r], bodies, settings);
            for (std::size_t k = 0; k < 3; ++k)
            {
                const Real change = rows[r].lambda[k] - before[r][k];
                squared += change * change;
            }
        }
        Real largest = 0.0;
        for (std::size_t i = 0; i < moved.size(); ++i)
        {
            const SolverBody& now = bodies[moved[i]];
            largest = std::max(largest, (now.linearVelocity - start[i].linearVelocity).norm() +
                                            (now.angularVelocity - start[i].angularVelocity).norm() * now.reach);
        }
        if (largest <= tolerance)
        {
            break;
        }
        if (!accelerate)
        {
            continue;
        }
        if (sweeps == maxSweeps)
        {
            break; // the last sweep's change is what the next step's iteration starts from
        }
        const Real beta = previous > 0.0 ? squared / previous : 0.0;
        previous = squared;
        if (!(beta <= 1.0))
        {
            for (std::size_t r = 0; r < rows.size(); ++r)
            {
                for (std::size_t k = 0; k < 3; ++k)
                {
                    direction[r][k] = rows[r].lambda[k] - before[r][k];
                }
            }
            continue;
        }
        for (std::size_t r = 0; r < rows.size(); ++r)
        {
            ContactRow& row = rows[r];
            std::array<Real, 3> stepped;
            for (std::size_t k = 0; k < 3; ++k)
            {
                stepped[k] = row.lambda[k] + beta * direction[r][k];
                direction[r][k] = (row.lambda[k] - before[r][k]) + beta * direction[r][k];
            }
            stepped[0] = std::max(stepped[0], 0.0);
            const Real limit = row.friction * stepped[0];
            const Real tangential2 = stepped[1] * stepped[1] + stepped[2] * stepped[2];
            if (tangential2 > limit * limit)
            {
                const Real scale = tangential2 > 0.0 ? limit / std::sqrt(tangential2) : 0.0;
                stepped[1] *= scale;
                stepped[2] *= scale;
            }
            applyImpulses(row, stepped[0] - row.lambda[0], stepped[1] - row.lambda[1], stepped[2] - row.lambda[2],
                          bodies[row.a], bodies[row.b]);
            row.lambda = stepped;
        }
    }
    if (accelerate && sweeps > 0)
    {
        keep();
    }
    return sweeps;
}

} // namespace impulse
