// SPDX-License-Identifier: MIT
#include "dynamics/rigid_patch.hpp"

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>

#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

namespace impulse
{
namespace
{

using Vec6 = Eigen::Matrix<Real, 6, 1>;

// How far outside its cone, relative to the loads involved, a point's load may come and still be
// projected back rather than the step refused.
constexpr Real kProjectable = 1e-3;
using Mat6 = Eigen::Matrix<Real, 6, 6>;

Mat3 cross(const Vec3& v)
{
    Mat3 m;
    m << 0.0, -v.z(), v.y(), v.z(), 0.0, -v.x(), -v.y(), v.x(), 0.0;
    return m;
}

// The mobility about c of a body with centre x: the twist at c a wrench (force, torque about c) gives
// it. The twist (V, W) at c of body velocities (v, w) is V = v + w x (c - x), W = w.
Mat6 mobility(const PatchMover& body, const Vec3& c)
{
    Mat6 transfer = Mat6::Identity(); // (v, w) -> (V, W)
    transfer.block<3, 3>(0, 3) = -cross(c - body.centre);
    Mat6 inverseMass = Mat6::Zero();
    inverseMass.block<3, 3>(0, 0) = body.invMass * Mat3::Identity();
    inverseMass.block<3, 3>(3, 3) = body.invInertia;
    return transfer * inverseMass * transfer.transpose();
}

// Spreads a wrench (force, torque about the centroid) over the points, `spread[k]` the load on the
// mover at point k. Where every point shares one normal (a face on a face) the spread is a rigid
// contact's: normal loads of least norm for the normal force and the tilting moment, friction in
// proportion to the normal loads (so that where one point may slide, all may), and the twist about the
// normal carried by loads across the points' arms. Elsewhere the loads of least norm, a + b x rho.
// Returns false when the points cannot exert the torque.
bool spreadWrench(std::span<ContactRow* const> rows, const std::vector<Real>& side, const std::vector<Vec3>& lever,
                  const Mat3& g, const Mat3& pseudoInverse, const Vec3& force, const Vec3& torque,
                  std::vector<Vec3>& spread)
{
    const std::size_t n = rows.size();
    spread.resize(n);
    const Real scale = force.norm() + torque.norm() / (std::sqrt(g.trace()) + 1e-300) + 1e-300;
    const auto reproduces = [&]
    {
        Vec3 f = Vec3::Zero();
        Vec3 t = Vec3::Zero();
        for (std::size_t k = 0; k < n; ++k)
        {
            f += spread[k];
            t += lever[k].cross(spread[k]);
        }
        return (f - force).norm() <= 1e-9 * scale &&
               (t - torque).norm() <= 1e-9 * scale * (std::sqrt(g.trace()) + 1e-300);
    };
    const Vec3 normal = side[0] * rows[0]->direction[0];
    bool planar = true;
    for (std::size_t k = 0; k < n && planar; ++k)
    {
        planar = (side[k] * rows[k]->direction[0]).isApprox(normal, 1e-9);
    }
    const Real pressing = force.dot(normal);
    if (planar && pressing > 0.0)
    {
        // normal loads l_k = N / n + a_k . c with a_k = rho_k x n: they add up to N, and their moment
        // sum l_k a_k = (sum a_k a_k^T) c is the tilting part of the torque
        Mat3 tilt = Mat3::Zero();
        for (std::size_t k = 0; k < n; ++k)
        {
            const Vec3 arm = lever[k].cross(normal);
            tilt += arm * arm.transpose();
        }
        const Eigen::SelfAdjointEigenSolver<Mat3> eigen(tilt);
        Mat3 tiltInverse = Mat3::Zero();
        for (int i = 0; i < 3; ++i)
        {
            if (eigen.eigenvalues()[i] > 1e-9 * eigen.eigenvalues().maxCoeff())
            {
                tiltInverse +=
                    eigen.eigenvectors().col(i) * eigen.eigenvectors().col(i).transpose() / eigen.eigenvalues()[i];
            }
        }
        const Vec3 c = tiltInverse * (torque - torque.dot(normal) * normal);
        // friction in proportion to load; the twist about the normal that leaves, across the arms
        const Vec3 tangential = force - pressing * normal;
        Real twist = torque.dot(normal);
        Real arms = 0.0;
        for (std::size_t k = 0; k < n; ++k)
        {
            const Real load = pressing / static_cast<Real>(n) + lever[k].cross(normal).dot(c);
            spread[k] = load * normal + (load / pressing) * tangential;
            twist -= lever[k].cross(spread[k]).dot(normal);
            const Vec3 across = lever[k] - lever[k].dot(normal) * normal;
            arms += across.squaredNorm();
        }
        if (arms > 0.0)
        {
            for (std::size_t k = 0; k < n; ++k)
            {
                const Vec3 across = lever[k] - lever[k].dot(normal) * normal;
                spread[k] += (twist / arms) * normal.cross(across);
            }
        }
        if (reproduces())
        {
            return true;
        }
    }
    const Vec3 a = force / static_cast<Real>(n);
    const Vec3 b = pseudoInverse * torque;
    for (std::size_t k = 0; k < n; ++k)
    {
        spread[k] = a + b.cross(lever[k]);
    }
    return reproduces();
}

} // namespace

bool solveRigidPatch(std::span<ContactRow* const> rows, std::span<SolverBody> bodies, const PatchMover& mover,
                     const PatchMover* partner, Real tolerance, SolverScratch& scratch)
{
    const std::size_t n = rows.size();
    if (n == 0)
    {
        return false;
    }
    // the mover's side of each row: +1 where it is the row's A (the normal points toward it)
    std::vector<Real>& side = scratch.side;
    std::vector<Vec3>& wanted = scratch.wanted; // change of the mover's point velocity relative to the partner's
    std::vector<Vec3>& lever = scratch.lever;
    side.resize(n);
    wanted.resize(n);
    lever.resize(n);
    Vec3 centroid = Vec3::Zero();
    for (std::size_t k = 0; k < n; ++k)
    {
        const ContactRow& row = *rows[k];
        side[k] = row.a == mover.index ? 1.0 : -1.0;
        const SolverBody& a = bodies[row.a];
        const SolverBody& b = bodies[row.b];
        const Real change[3] = {row.bias - row.relativeVelocity(0, a, b), -row.relativeVelocity(1, a, b),
                                -row.relativeVelocity(2, a, b)};
        wanted[k] =
            side[k] * (change[0] * row.direction[0] + change[1] * row.direction[1] + change[2] * row.direction[2]);
        centroid += row.point;
    }
    centroid /= static_cast<Real>(n);

    // the least-squares twist: V the mean of the wanted changes, W = G^+ sum rho x wanted
    Mat3 g = Mat3::Zero();
    Vec3 linear = Vec3::Zero();
    Vec3 angular = Vec3::Zero();
    for (std::size_t k = 0; k < n; ++k)
    {
        lever[k] = rows[k]->point - centroid;
        g += lever[k].squaredNorm() * Mat3::Identity() - lever[k] * lever[k].transpose();
        linear += wanted[k];
        angular += lever[k].cross(wanted[k]);
    }
    linear /= static_cast<Real>(n);
    const Eigen::SelfAdjointEigenSolver<Mat3> eigen(g);
    const Vec3 values = eigen.eigenvalues();
    const Mat3 vectors = eigen.eigenvectors();
    const Real cut = 1e-9 * std::max(values.maxCoeff(), Real(0.0));
    Mat3 pseudoInverse = Mat3::Zero();
    std::array<Vec3, 3> free; // rotations the points cannot resist, the first `freeCount`
    std::size_t freeCount = 0;
    for (int i = 0; i < 3; ++i)
    {
        if (values[i] > cut && values[i] > 0.0)
        {
            pseudoInverse += vectors.col(i) * vectors.col(i).transpose() / values[i];
        }
        else
        {
            free[freeCount++] = vectors.col(i);
        }
    }
    Vec6 twist;
    twist << linear, pseudoInverse * angular;

    // every target met by that twist, or none of this
    for (std::size_t k = 0; k < n; ++k)
    {
        const Vec3 reached = twist.head<3>() + twist.tail<3>().cross(lever[k]);
        if (!((reached - wanted[k]).norm() <= tolerance))
        {
            return false;
        }
    }

    // the wrench that gives it; free rotations chosen so that it has no torque about them
    Mat6 combined = mobility(mover, centroid);
    if (partner != nullptr)
    {
        combined += mobility(*partner, centroid);
    }
    const Eigen::LDLT<Mat6> factor(combined);
    if (factor.info() != Eigen::Success || !factor.isPositive())
    {
        return false;
    }
    if (freeCount > 0)
    {
        // twist + N alpha with N^T K^-1 (twist + N alpha) = 0
        Eigen::Matrix<Real, 6, Eigen::Dynamic> basis =
            Eigen::Matrix<Real, 6, Eigen::Dynamic>::Zero(6, static_cast<Eigen::Index>(freeCount));
        for (std::size_t i = 0; i < freeCount; ++i)
        {
            basis.block<3, 1>(3, static_cast<Eigen::Index>(i)) = free[i];
        }
        const Eigen::Matrix<Real, 6, Eigen::Dynamic> solved = factor.solve(basis);
        const Eigen::MatrixXd reduced = basis.transpose() * solved;
        const Eigen::VectorXd alpha = reduced.ldlt().solve(-(solved.transpose() * twist));
        twist += basis * alpha;
    }
    const Vec6 wrench = factor.solve(twist);
    if (!wrench.allFinite())
    {
        return false;
    }

    // The loads a rigid patch carries are not determined by its motion: only the wrench they add up to
    // is. So the whole wrench, what the points carry already and what the step adds, is spread again
    // as a rigid contact carries load, which is admissible where any spreading is likely to be.
    Vec3 force = wrench.head<3>();
    Vec3 torque = wrench.tail<3>();
    for (std::size_t k = 0; k < n; ++k)
    {
        const ContactRow& row = *rows[k];
        const Vec3 carried = side[k] * (row.lambda[0] * row.direction[0] + row.lambda[1] * row.direction[1] +
                                        row.lambda[2] * row.direction[2]);
        force += carried;
        torque += lever[k].cross(carried);
    }
    std::vector<Vec3>& spread = scratch.spread; // on the mover, per point
    if (!spreadWrench(rows, side, lever, g, pseudoInverse, force, torque, spread))
    {
        return false; // a torque the points cannot exert
    }
    std::vector<std::array<Real, 3>>& loads = scratch.loads;
    loads.resize(n);
    for (std::size_t i = 0; i < n; ++i)
    {
        const ContactRow& row = *rows[i];
        std::array<Real, 3>& total = loads[i];
        for (std::size_t d = 0; d < 3; ++d)
        {
            total[d] = side[i] * spread[i].dot(row.direction[d]);
        }
        // admissible: pushing, and within the friction cone; a load a hair outside (a thousandth of
        // the loads involved) is projected back, which leaves Gauss-Seidel a remainder of that size
        const Real slack = kProjectable * spread[i].norm();
        if (total[0] < -slack)
        {
            return false;
        }
        total[0] = std::max(total[0], 0.0);
        const Real limit = row.friction * total[0];
        const Real tangential = std::sqrt(total[1] * total[1] + total[2] * total[2]);
        if (tangential > limit + slack)
        {
            return false;
        }
        if (tangential > limit)
        {
            total[1] *= limit / tangential;
            total[2] *= limit / tangential;
        }
    }
    for (std::size_t i = 0; i < n; ++i)
    {
        ContactRow& row = *rows[i];
        applyImpulses(row, loads[i][0] - row.lambda[0], loads[i][1] - row.lambda[1], loads[i][2] - row.lambda[2],
                      bodies[row.a], bodies[row.b]);
        row.lambda = loads[i];
    }
    return true;
}

} // namespace impulse
