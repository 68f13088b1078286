// SPDX-License-Identifier: MIT
// Contact patches: several points of a body that approach at once (a box flat on the ground, a
// cube on a cube, a lintel on two stacks), resolved together instead of one point at a time.
//
// Why: one point at a time, each corner's impulse tilts the body a little, friction at the next
// corner answers that transient tilt, and the answer becomes sideways slip and spin. A frictional
// stack of ten cubes then jitters at millimetres per second; resolved as patches it stays at rest
// to round-off.
//
// How: the impulses j_i that give every point its target satisfy W j = t, W the coupled 3n x 3n
// collision matrix (W_ik = K-blocks between lever arms r_i and r_k of the same bodies). The rigid
// relative motion makes the targets consistent; a rigid contact is statically indeterminate, so
// the least-squares solution is one of many with the same net force and moment. It is re-spread
// as a rigid patch carries load: normal loads of least norm for the net normal force and tilting
// moment, friction in proportion to load plus a torsional part for the twist. If that needs a
// point to pull or to leave its friction cone, the patch does not stick, and the caller falls back
// to the paper's deepest-point impulse (sliding, tipping).
#include "dynamics/contact_patch.hpp"

#include "dynamics/impulse.hpp"
#include "dynamics/integrate.hpp"

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>
#include <Eigen/QR>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <limits>

namespace impulse
{
namespace
{

// Re-spreads `solved` (3 numbers per point) over a patch whose points share one normal, keeping
// the net force and the moment about the patch centroid. False if a point would pull or slip.
bool distributeOverPatch(const std::vector<PatchPoint>& patch, const Eigen::VectorXd& solved,
                         std::vector<Vec3>& impulses)
{
    const std::size_t n = patch.size();
    const Vec3 normal = patch[0].contact.normal;
    Vec3 origin = Vec3::Zero();
    for (const PatchPoint& point : patch)
    {
        if (!point.contact.normal.isApprox(normal, 1e-9))
        {
            return false; // points facing different ways: not one planar patch
        }
        origin += point.contact.point / static_cast<Real>(n);
    }
    Vec3 force = Vec3::Zero();
    Vec3 moment = Vec3::Zero();
    for (std::size_t k = 0; k < n; ++k)
    {
        const Vec3 j = solved.segment<3>(3 * static_cast<Eigen::Index>(k));
        force += j;
        moment += (patch[k].contact.point - origin).cross(j);
    }
    const Real normalForce = force.dot(normal);
    if (!(normalForce > 0.0))
    {
        return false;
    }
    const Vec3 tangentialForce = force - normalForce * normal;
    const Real twist = moment.dot(normal);
    const Vec3 tilt = moment - twist * normal;

    // Loads of least norm whose sum is the normal force and whose moment about the centroid is the
    // tilting moment. The arms a_k = (p_k - o) x n lie in the plane across n and sum to zero about
    // the centroid, so the equations split: l_k = N / n + a_k . G^+ tilt, with G = sum a_k a_k^T
    // a 2 x 2 matrix in a basis (u, v) of that plane. G has rank 1 when the points lie on a line (a
    // cube on an edge); the part of the tilt across the line then has no loads to carry it, and the
    // residual check below refuses the patch.
    const Vec3 u = normal.unitOrthogonal();
    const Vec3 v = normal.cross(u);
    thread_local std::vector<Eigen::Vector2d> arms;
    arms.resize(n);
    Eigen::Matrix2d spreadOfArms = Eigen::Matrix2d::Zero(); // G
    for (std::size_t k = 0; k < n; ++k)
    {
        const Vec3 arm = (patch[k].contact.point - origin).cross(normal);
        arms[k] = Eigen::Vector2d(arm.dot(u), arm.dot(v));
        spreadOfArms += arms[k] * arms[k].transpose();
    }
    const Eigen::Vector2d tiltInPlane(tilt.dot(u), tilt.dot(v));
    Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> eigen;
    eigen.computeDirect(spreadOfArms);
    const Real largest = eigen.eigenvalues()(1);
    Eigen::Vector2d perArm = Eigen::Vector2d::Zero(); // G^+ tilt
    for (int i = 0; i < 2; ++i)
    {
        // directions in which the arms spread less than 1e-6 of their reach carry no tilt
        const Real lambda = eigen.eigenvalues()(i);
        if (largest > 0.0 && lambda > 1e-12 * largest)
        {
            const Eigen::Vector2d axis = eigen.eigenvectors().col(i);
            perArm += axis * (axis.dot(tiltInPlane) / lambda);
        }
    }
    thread_local Eigen::VectorXd loads;
    loads.resize(static_cast<Eigen::Index>(n));
    Real sum = 0.0;
    Eigen::Vector2d carried = Eigen::Vector2d::Zero();
    for (std::size_t k = 0; k < n; ++k)
    {
        const Real load = normalForce / static_cast<Real>(n) + arms[k].dot(perArm);
        loads[static_cast<Eigen::Index>(k)] = load;
        sum += load;
        carried += load * arms[k];
    }
    const Real residual = std::sqrt((sum - normalForce) * (sum - normalForce) + (carried - tiltInPlane).squaredNorm() +
                                    tilt.dot(normal) * tilt.dot(normal));
    const Real required = std::sqrt(normalForce * normalForce + tilt.squaredNorm());
    if (!loads.allFinite() || !(residual <= 1e-9 * required))
    {
        return false;
    }
    Vec3 centre = Vec3::Zero();
    for (std::size_t k = 0; k < n; ++k)
    {
        const Real load = loads[static_cast<Eigen::Index>(k)];
        if (load < -1e-12 * normalForce)
        {
            return false; // the moment needs a point to pull: the body tips
        }
        centre += load * patch[k].contact.point;
    }
    centre /= normalForce;

    // friction: the net tangential force in proportion to load, plus kappa * load * n x (p - c),
    // which adds no net force and supplies the rest of the moment about the normal
    Real spread = 0.0;
    for (std::size_t k = 0; k < n; ++k)
    {
        spread += loads[static_cast<Eigen::Index>(k)] * (patch[k].contact.point - centre).squaredNorm();
    }
    const Real remainingTwist = twist - (centre - origin).cross(tangentialForce).dot(normal);
    Real kappa = 0.0;
    if (spread > 0.0)
    {
        kappa = remainingTwist / spread;
    }
    else if (std::abs(remainingTwist) > 1e-12 * normalForce)
    {
        return false; // a twist that no spread of friction can supply
    }
    for (std::size_t k = 0; k < n; ++k)
    {
        const Real load = std::max(0.0, loads[static_cast<Eigen::Index>(k)]);
        const Vec3 friction =
            load * (tangentialForce / normalForce + kappa * normal.cross(patch[k].contact.point - centre));
        if (friction.norm() > patch[k].friction * load + 1e-12 * normalForce)
        {
            return false; // this point would slip
        }
        impulses[k] = load * normal + friction;
    }
    return true;
}

Real invMassOf(const RigidBody& body)
{
    return body.immovable() ? 0.0 : body.invMass;
}

Mat3 invInertiaOf(const RigidBody& body)
{
    return body.immovable() ? Mat3::Zero() : body.invInertiaWorld;
}

// The least-squares impulses of a patch: the j of least norm that minimises |W j - t|, W the coupled
// collision matrix (3 rows and columns per point; W_ik maps an impulse at point k to the relative
// velocity change at point i, through the body always and through the partner when both points
// touch the same one). W is never formed: with one block of six columns per movable body,
// A = J M^-1/2 and W = A A^T. A is 6 columns wide for a body on static
// supports and 12 wide with one movable partner where W is up to 24 x 24, so j = (A^+)^T A^+ t is
// found from a decomposition of A, a fraction of the cost of one of W. `reached` is W j, the
// relative velocity change the impulses give.
struct PatchLeastSquares
{
    Eigen::VectorXd impulses;
    Eigen::VectorXd reached;
};

// Whether two matrices hold the same numbers bit for bit (so that factoring them would give the same
// factors): the projected solve's warm start asks for the least squares of the very matrix the patch
// solve before it has just factored, with other targets.
template <class Matrix> bool sameBits(const Matrix& x, const Matrix& y)
{
    return x.rows() == y.rows() && x.cols() == y.cols() &&
           std::memcmp(x.data(), y.data(), static_cast<std::size_t>(x.size()) * sizeof(typename Matrix::Scalar)) == 0;
}

// Fills A (3 rows per point, 6 columns per movable body) for solvePatchLeastSquares.
template <class Matrix>
void fillPatchMatrix(const RigidBody& body, const std::vector<PatchPoint>& patch, const std::vector<Vec3>& lever,
                     const std::vector<Vec3>& partnerLever, const std::vector<const RigidBody*>& movable, Matrix& a)
{
    a.setZero(static_cast<Eigen::Index>(3 * patch.size()), static_cast<Eigen::Index>(6 * movable.size()));
    for (std::size_t b = 0; b < movable.size(); ++b)
    {
        // M^-1/2 of body b: sqrt(1/m) for translation, R diag(sqrt(1/I)) R^T for rotation
        const RigidBody& mover = *movable[b];
        const Real rootInvMass = std::sqrt(mover.invMass);
        const Mat3 rootInvInertia =
            mover.rotation * mover.invPrincipalInertia.cwiseSqrt().asDiagonal() * mover.rotation.transpose();
        const auto column = static_cast<Eigen::Index>(6 * b);
        for (std::size_t k = 0; k < patch.size(); ++k)
        {
            // u_rel = u_body - u_partner: the body's columns enter with +, a partner's with -
            const bool isBody = &mover == &body;
            if (!isBody && patch[k].other != &mover)
            {
                continue;
            }
            const Vec3& r = isBody ? lever[k] : partnerLever[k];
            const Real sign = isBody ? 1.0 : -1.0;
            Mat3 leverCross;
            leverCross << 0.0, -r.z(), r.y(), r.z(), 0.0, -r.x(), -r.y(), r.x(), 0.0;
            const auto row = static_cast<Eigen::Index>(3 * k);
            a.template block<3, 3>(row, column) = sign * rootInvMass * Mat3::Identity();
            a.template block<3, 3>(row, column + 3) = -sign * leverCross * rootInvInertia;
        }
    }
}

// j = (A^+)^T A^+ t from a complete orthogonal decomposition of A, in storage of at most kMaxRows x
// kMaxColumns (Eigen::Dynamic: on the heap).
template <int kMaxRows, int kMaxColumns>
void solveThroughDecomposition(const RigidBody& body, const std::vector<PatchPoint>& patch,
                               const std::vector<Vec3>& lever, const std::vector<Vec3>& partnerLever,
                               const std::vector<const RigidBody*>& movable, const Eigen::VectorXd& target,
                               PatchLeastSquares& result)
{
    using Matrix = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::ColMajor, kMaxRows, kMaxColumns>;
    using Vector = Eigen::Matrix<double, Eigen::Dynamic, 1, Eigen::ColMajor,
                                 kMaxRows == Eigen::Dynamic ? Eigen::Dynamic : std::max(kMaxRows, kMaxColumns), 1>;
    // kept per thread: a patch of the size of an earlier one reuses their storage
    thread_local Matrix a;
    thread_local Matrix factored; // the matrix `decomposition` holds the factors of
    thread_local Eigen::CompleteOrthogonalDecomposition<Matrix> decomposition;
    thread_local Vector rhs;
    thread_local Vector leastNorm;
    thread_local Vector image;
    fillPatchMatrix(body, patch, lever, partnerLever, movable, a);
    if (!sameBits(a, factored))
    {
        // W^+ = (A A^T)^+ = (A^+)^T A^+. Ranks are decided on A as a decomposition of W would decide
        // them on W = A A^T, whose singular values are the squares of A's: relative to the largest,
        // below the square root of W's round-off
        decomposition.setThreshold(std::sqrt(static_cast<Real>(a.rows()) * std::numeric_limits<Real>::epsilon()));
        decomposition.compute(a);
        factored = a;
    }
    // A^+ t, then (A^+)^T of that: the transposed solve applies the same factors in reverse. The
    // solves' temporaries take the type of their right-hand side, so t is copied into `Vector` first.
    rhs = target;
    leastNorm = decomposition.solve(rhs);
    result.impulses = decomposition.transpose().solve(leastNorm);
    image.noalias() = a.transpose() * result.impulses;
    result.reached = a * image;
}

// j = W^-1 t by a Cholesky factor of W itself, for a patch whose every point has a movable partner
// of its own (a ball on the balls below it). Such a partner's block of W is at least its 1/m times
// the identity on the diagonal and the body's coupling adds a positive semi-definite part, so W is
// positive definite and W^-1 t is the least-norm solution the decomposition of A would give with
// all of A's rank kept, from a 3n x 3n factor instead of one of a 3n x 6(n + 1) matrix.
void solveThroughCoupling(const RigidBody& body, const std::vector<PatchPoint>& patch, const std::vector<Vec3>& lever,
                          const std::vector<Vec3>& partnerLever, const Eigen::VectorXd& target,
                          PatchLeastSquares& result)
{
    using Matrix = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::ColMajor, 48, 48>;
    thread_local Matrix coupling;
    thread_local Matrix factored; // the matrix `factor` holds the factor of
    thread_local Eigen::LLT<Matrix> factor;
    const auto n = static_cast<Eigen::Index>(patch.size());
    coupling.resize(3 * n, 3 * n);
    const Real bodyInvMass = invMassOf(body);
    const Mat3 bodyInvInertia = invInertiaOf(body);
    for (Eigen::Index i = 0; i < n; ++i)
    {
        const auto pi = static_cast<std::size_t>(i);
        const RigidBody& partner = *patch[pi].other;
        coupling.block<3, 3>(3 * i, 3 * i) =
            couplingMatrix(bodyInvMass, bodyInvInertia, lever[pi], lever[pi]) +
            couplingMatrix(partner.invMass, partner.invInertiaWorld, partnerLever[pi], partnerLever[pi]);
        for (Eigen::Index k = i + 1; k < n; ++k)
        {
            const Mat3 block =
                couplingMatrix(bodyInvMass, bodyInvInertia, lever[pi], lever[static_cast<std::size_t>(k)]);
            coupling.block<3, 3>(3 * i, 3 * k) = block;
            coupling.block<3, 3>(3 * k, 3 * i) = block.transpose();
        }
    }
    if (!sameBits(coupling, factored))
    {
        factor.compute(coupling);
        factored = coupling;
    }
    result.impulses = factor.solve(target);
    result.reached = coupling * result.impulses;
}

using Mat6 = Eigen::Matrix<double, 6, 6>;
using Vec6 = Eigen::Matrix<double, 6, 1>;

// The cross-product matrix [r]x, [r]x v = r x v.
Mat3 crossMatrix(const Vec3& r)
{
    Mat3 m;
    m << 0.0, -r.z(), r.y(), r.z(), 0.0, -r.x(), -r.y(), r.x(), 0.0;
    return m;
}

// Adds body b's mobility to K, the 6 x 6 map from a wrench about `centre` (force, moment) to the
// twist it gives about `centre`: S^T M_b^-1 S, S moving the wrench to b's centre of mass.
void addMobility(const RigidBody& b, const Vec3& centre, Mat6& mobility)
{
    const Mat3 shift = crossMatrix(centre - b.predicted.position); // moment about b = moment about centre + shift F
    const Mat3& invInertia = b.invInertiaWorld;
    mobility.topLeftCorner<3, 3>() += b.invMass * Mat3::Identity() + shift.transpose() * invInertia * shift;
    mobility.topRightCorner<3, 3>() += shift.transpose() * invInertia;
    mobility.bottomLeftCorner<3, 3>() += invInertia * shift;
    mobility.bottomRightCorner<3, 3>() += invInertia;
}

// K of a patch's one relative motion about `centre`: the body's mobility plus its partner's, if
// either moves.
Mat6 patchMobility(const RigidBody& body, const RigidBody* partner, const Vec3& centre)
{
    Mat6 mobility = Mat6::Zero();
    if (!body.immovable())
    {
        addMobility(body, centre, mobility);
    }
    if (partner != nullptr)
    {
        addMobility(*partner, centre, mobility);
    }
    return mobility;
}

// How the points of a patch move relative to its body: the rigid-motion solves and the sticking
// solve's load re-spread need one relative motion at every point.
struct PatchMotion
{
    enum class Kind
    {
        AllImmovable, // every point on a static or frozen body
        OnePartner,   // every point on the same movable partner
        Several,      // two movable partners, or one besides bodies that do not move
    };
    Kind kind = Kind::AllImmovable;
    const RigidBody* partner = nullptr; // the movable partner, when there is exactly one
};

PatchMotion classifyPatchMotion(const std::vector<PatchPoint>& patch)
{
    PatchMotion motion;
    bool touchesImmovable = false;
    for (const PatchPoint& point : patch)
    {
        if (point.other->immovable())
        {
            touchesImmovable = true;
        }
        else if (motion.partner == nullptr)
        {
            motion.partner = point.other;
        }
        else if (motion.partner != point.other)
        {
            motion.kind = PatchMotion::Kind::Several;
            return motion;
        }
    }
    if (motion.partner != nullptr)
    {
        motion.kind = touchesImmovable ? PatchMotion::Kind::Several : PatchMotion::Kind::OnePartner;
    }
    return motion;
}

// j = W^+ t for a patch whose points all touch static or frozen bodies or one and the same movable
// partner (a box on the ground, a cube on a cube, any body in the shock sweep). The relative velocity
// the impulses give is then a rigid motion: a twist (V, W) about the points' centroid c gives
// u_k = V + W x rho_k, rho_k = p_k - c, that is u = J (V, W), and the impulses act through their
// wrench J^T j about c, the twist being K J^T j with K the pair's 6 x 6 mobility. So W = J K J^T and,
// J having full column rank, W^+ = J (J^T J)^-1 K^-1 (J^T J)^-1 J^T: the rigid motion of least
// squares J^+ t, the wrench that gives it, spread over the points with the least norm. About the
// centroid J^T J = diag(n 1, G), G = sum |rho|^2 1 - rho rho^T, so the whole solve is of 6 x 6 and
// 3 x 3 matrices, where the decomposition of A works on 3n x 12. Returns false, computing nothing,
// when the points lie nearly on a line (G nearly singular: an edge contact), which the decomposition
// handles with its rank decisions.
bool solveThroughTwist(const RigidBody& body, const std::vector<PatchPoint>& patch, const RigidBody* partner,
                       const Eigen::VectorXd& target, PatchLeastSquares& result)
{
    const std::size_t n = patch.size();
    if (n < 3)
    {
        return false;
    }
    Vec3 centre = Vec3::Zero();
    for (const PatchPoint& point : patch)
    {
        centre += point.contact.point;
    }
    centre /= static_cast<Real>(n);
    Mat3 spread = Mat3::Zero();
    for (const PatchPoint& point : patch)
    {
        const Vec3 rho = point.contact.point - centre;
        spread += rho.squaredNorm() * Mat3::Identity() - rho * rho.transpose();
    }
    // well away from a line: the least eigenvalue of G above 1e-6 of its trace (G's eigenvalues
    // are at most its trace, and the least is at least det / (trace / 2)^2 for a PSD 3 x 3)
    const Real trace = spread.trace();
    if (!(trace > 0.0) || !(spread.determinant() > 0.25e-6 * trace * trace * trace))
    {
        return false;
    }
    const Eigen::LLT<Mat3> spreadFactor(spread);
    const Mat6 mobility = patchMobility(body, partner, centre);
    const Eigen::LLT<Mat6> mobilityFactor(mobility);
    if (mobilityFactor.info() != Eigen::Success || spreadFactor.info() != Eigen::Success)
    {
        return false;
    }
    const auto count = static_cast<Real>(n);
    // (J^T J)^-1 of a wrench or twist about the centroid
    const auto unspread = [&](const Vec6& x)
    {
        Vec6 y;
        y.head<3>() = x.head<3>() / count;
        y.tail<3>() = spreadFactor.solve(x.tail<3>());
        return y;
    };
    Vec6 wrench = Vec6::Zero(); // J^T t
    for (std::size_t k = 0; k < n; ++k)
    {
        const Vec3 tk = target.segment<3>(3 * static_cast<Eigen::Index>(k));
        wrench.head<3>() += tk;
        wrench.tail<3>() += (patch[k].contact.point - centre).cross(tk);
    }
    const Vec6 spreadTwist = unspread(mobilityFactor.solve(unspread(wrench)));
    result.impulses.resize(static_cast<Eigen::Index>(3 * n));
    Vec6 applied = Vec6::Zero(); // J^T j
    for (std::size_t k = 0; k < n; ++k)
    {
        const Vec3 rho = patch[k].contact.point - centre;
        const Vec3 jk = spreadTwist.head<3>() + spreadTwist.tail<3>().cross(rho);
        result.impulses.segment<3>(3 * static_cast<Eigen::Index>(k)) = jk;
        applied.head<3>() += jk;
        applied.tail<3>() += rho.cross(jk);
    }
    const Vec6 twist = mobility * applied;
    result.reached.resize(static_cast<Eigen::Index>(3 * n));
    for (std::size_t k = 0; k < n; ++k)
    {
        result.reached.segment<3>(3 * static_cast<Eigen::Index>(k)) =
            twist.head<3>() + twist.tail<3>().cross(patch[k].contact.point - centre);
    }
    return true;
}

// The same rigid-motion solve for a patch of two points (a box on an edge, an edge across an edge):
// about their midpoint c, rho_1 = -rho_2 = h. J (V, W) = (V + W x h, V - W x h) has one null twist,
// the turn (0, e) about the line through the points, e = h / |h|, and no other, so with P the 6 x 5
// basis of the twists across it, (V, Q w) for Q = [q1 q2] orthonormal and orthogonal to e, B = J P
// has full column rank and W = J K J^T = B (P^T K P) B^T. Then W^+ = B (B^T B)^-1 (P^T K P)^-1
// (B^T B)^-1 B^T with B^T B = diag(2 1, 2 |h|^2 1): a 5 x 5 Cholesky factor where the decomposition
// of A works on 6 x 12. Returns false, computing nothing, when the points are so close together
// that the decomposition's rank decisions would treat them as one.
bool solveThroughLineTwist(const RigidBody& body, const std::vector<PatchPoint>& patch, const RigidBody* partner,
                           const Eigen::VectorXd& target, PatchLeastSquares& result)
{
    const Vec3 centre = 0.5 * (patch[0].contact.point + patch[1].contact.point);
    const Vec3 half = 0.5 * (patch[0].contact.point - patch[1].contact.point); // rho_1; rho_2 = -rho_1
    const Real halfSquared = half.squaredNorm();
    // the turn about the line is the only null twist while |h| is well above round-off of the levers
    Real reach = body.immovable() ? 0.0 : (centre - body.predicted.position).squaredNorm();
    if (partner != nullptr)
    {
        reach = std::max(reach, (centre - partner->predicted.position).squaredNorm());
    }
    if (!(halfSquared > 1e-6 * reach) || !(halfSquared > 0.0))
    {
        return false;
    }
    const Mat6 mobility = patchMobility(body, partner, centre);
    const Vec3 along = half / std::sqrt(halfSquared);
    Eigen::Matrix<Real, 3, 2> across;
    across.col(0) = along.unitOrthogonal();
    across.col(1) = along.cross(across.col(0));
    Eigen::Matrix<Real, 6, 5> basis = Eigen::Matrix<Real, 6, 5>::Zero(); // P
    basis.topLeftCorner<3, 3>().setIdentity();
    basis.bottomRightCorner<3, 2>() = across;
    const Eigen::LLT<Eigen::Matrix<Real, 5, 5>> mobilityFactor(basis.transpose() * mobility * basis);
    if (mobilityFactor.info() != Eigen::Success)
    {
        return false;
    }
    // (B^T B)^-1 of a reduced wrench or twist
    const auto unspread = [&](Eigen::Matrix<Real, 5, 1> x)
    {
        x.head<3>() /= 2.0;
        x.tail<2>() /= 2.0 * halfSquared;
        return x;
    };
    const Vec3 t0 = target.segment<3>(0);
    const Vec3 t1 = target.segment<3>(3);
    Vec6 wrench; // J^T t
    wrench << t0 + t1, half.cross(t0 - t1);
    const Eigen::Matrix<Real, 5, 1> reduced = basis.transpose() * wrench;
    const Vec6 spreadTwist = basis * unspread(mobilityFactor.solve(unspread(reduced)));
    const Vec3 turn = spreadTwist.tail<3>().cross(half);
    const Vec3 j0 = spreadTwist.head<3>() + turn;
    const Vec3 j1 = spreadTwist.head<3>() - turn;
    result.impulses.resize(6);
    result.impulses << j0, j1;
    Vec6 applied; // J^T j
    applied << j0 + j1, half.cross(j0 - j1);
    const Vec6 twist = mobility * applied;
    const Vec3 turned = twist.tail<3>().cross(half);
    result.reached.resize(6);
    result.reached << twist.head<3>() + turned, twist.head<3>() - turned;
    return true;
}

// `motion` is classifyPatchMotion(patch), which the callers have already decided on.
void solvePatchLeastSquares(const RigidBody& body, const std::vector<PatchPoint>& patch, const PatchMotion& motion,
                            const std::vector<Vec3>& lever, const std::vector<Vec3>& partnerLever,
                            const Eigen::VectorXd& target, PatchLeastSquares& result)
{
    // the movable bodies, the patch's body first: each owns six columns of A
    thread_local std::vector<const RigidBody*> movable;
    movable.clear();
    if (!body.immovable())
    {
        movable.push_back(&body);
    }
    for (const PatchPoint& point : patch)
    {
        if (!point.other->immovable() && std::find(movable.begin(), movable.end(), point.other) == movable.end())
        {
            movable.push_back(point.other);
        }
    }
    // the rigid-motion forms need one relative motion at every point (a box on the ground and
    // leaning on a box has two)
    if (motion.kind != PatchMotion::Kind::Several && !movable.empty())
    {
        const RigidBody* partner = motion.partner;
        if (patch.size() == 2 ? solveThroughLineTwist(body, patch, partner, target, result)
                              : solveThroughTwist(body, patch, partner, target, result))
        {
            return;
        }
    }
    const bool partnerPerPoint =
        movable.size() == patch.size() + (body.immovable() ? 0 : 1) &&
        std::none_of(patch.begin(), patch.end(), [](const PatchPoint& point) { return point.other->immovable(); });
    if (partnerPerPoint && patch.size() <= 16)
    {
        solveThroughCoupling(body, patch, lever, partnerLever, target, result);
        return;
    }
    // Patches of the usual sizes fit storage of fixed size, which spares the heap traffic of dynamic
    // matrices: a box on the ground or on one other box (up to 8 points, 12 columns), a ball among a
    // dozen neighbours
    const std::size_t rows = 3 * patch.size();
    const std::size_t columns = 6 * movable.size();
    if (rows <= 24 && columns <= 12)
    {
        solveThroughDecomposition<24, 12>(body, patch, lever, partnerLever, movable, target, result);
    }
    else if (rows <= 48 && columns <= 84)
    {
        solveThroughDecomposition<48, 84>(body, patch, lever, partnerLever, movable, target, result);
    }
    else
    {
        solveThroughDecomposition<Eigen::Dynamic, Eigen::Dynamic>(body, patch, lever, partnerLever, movable, target,
                                                                  result);
    }
}

// Target normal velocity of every point of a patch from its normal approach u_n (negative).
// Restitution eps >= 0 reflects each point's own approach (an elastic landing keeps its spin); a
// negative eps of the contact ramp keeps |eps| of the patch's mean approach at every point, so each
// sweep removes the tilt and slip outright and shares out only the rest.
void targetNormalVelocities(const std::vector<Real>& approach, Real eps, std::vector<Real>& keep)
{
    Real mean = 0.0;
    for (const Real un : approach)
    {
        mean += un / static_cast<Real>(approach.size());
    }
    keep.resize(approach.size());
    for (std::size_t k = 0; k < approach.size(); ++k)
    {
        keep[k] = eps >= 0.0 ? -eps * approach[k] : -eps * mean;
    }
}

// Applies impulse j_k at every patch point: +j_k to the body, -j_k to its partner there.
void applyToPatch(RigidBody& body, const std::vector<PatchPoint>& patch, const std::vector<Vec3>& impulses,
                  const std::vector<Vec3>& lever, const std::vector<Vec3>& partnerLever)
{
    for (std::size_t k = 0; k < patch.size(); ++k)
    {
        if (!body.immovable())
        {
            applyImpulse(body, impulses[k], lever[k]);
        }
        if (!patch[k].other->immovable())
        {
            applyImpulse(*patch[k].other, -impulses[k], partnerLever[k]);
        }
    }
}

} // namespace

bool applyPatchImpulse(RigidBody& body, const std::vector<PatchPoint>& patch, Real eps, const PassSettings& settings)
{
    // With several movable partners, or a movable partner besides bodies that do not move (a lintel
    // on a static block and a free one), the re-spreading below would shift load between them, and
    // their motion with it: that case is left to the projected solve, which moves them all.
    const PatchMotion motion = classifyPatchMotion(patch);
    if (motion.kind == PatchMotion::Kind::Several)
    {
        return false;
    }
    const auto n = static_cast<Eigen::Index>(patch.size());
    // kept per thread (here and in the projected solve): a patch of a size seen before allocates
    // nothing
    thread_local std::vector<Vec3> lever;
    thread_local std::vector<Vec3> otherLever;
    thread_local std::vector<Vec3> velocity;
    thread_local std::vector<Real> approach;
    thread_local std::vector<Real> keep;
    thread_local std::vector<Vec3> impulses;
    lever.resize(patch.size());
    otherLever.resize(patch.size());
    velocity.resize(patch.size());
    approach.resize(patch.size());
    for (std::size_t k = 0; k < patch.size(); ++k)
    {
        const ContactPoint& contact = patch[k].contact;
        const RigidBody& other = *patch[k].other;
        lever[k] = contact.point - body.predicted.position;
        otherLever[k] = contact.point - other.predicted.position;
        velocity[k] = relativeVelocity(body, body.predicted, other, other.predicted, contact, settings);
        approach[k] = velocity[k].dot(contact.normal);
    }
    targetNormalVelocities(approach, eps, keep);
    thread_local Eigen::VectorXd target;
    target.resize(3 * n);
    for (std::size_t k = 0; k < patch.size(); ++k)
    {
        target.segment<3>(3 * static_cast<Eigen::Index>(k)) = keep[k] * patch[k].contact.normal - velocity[k];
    }
    thread_local PatchLeastSquares leastSquares;
    solvePatchLeastSquares(body, patch, motion, lever, otherLever, target, leastSquares);
    const Eigen::VectorXd& solved = leastSquares.impulses;
    // Reachable: the least-squares solution meets the targets to 1e-6 of their size, plus round-off
    // (1e-12) of the velocities involved. Exactly consistent for eps = 0; for eps != 0 a patch tilted
    // against its normal makes -eps u_n n slightly non-rigid, a mismatch the next sweeps remove.
    Real velocityScale = static_cast<Real>(patch.size()) * settings.dt * settings.gravity.norm();
    for (const Vec3& u : velocity)
    {
        velocityScale += u.norm();
    }
    if (!solved.allFinite() || (leastSquares.reached - target).norm() > 1e-6 * target.norm() + 1e-12 * velocityScale)
    {
        return false; // the targets are not reachable together
    }
    impulses.resize(patch.size());
    if (!distributeOverPatch(patch, solved, impulses))
    {
        return false;
    }
    // work done on the relative motion: j . (u + du/2) <= 0 means no kinetic energy gained
    Real work = 0.0;
    Real scale = 0.0;
    for (std::size_t k = 0; k < patch.size(); ++k)
    {
        work += impulses[k].dot(velocity[k] + 0.5 * Vec3(target.segment<3>(3 * static_cast<Eigen::Index>(k))));
        scale += impulses[k].norm() * velocity[k].norm();
    }
    if (work > 1e-12 * scale)
    {
        return false;
    }
    applyToPatch(body, patch, impulses, lever, otherLever);
    return true;
}

bool applyProjectedPatchImpulse(RigidBody& body, const std::vector<PatchPoint>& patch, Real eps,
                                const PassSettings& settings)
{
    if (patch.empty())
    {
        return false;
    }
    // iterate until the impulses stop changing (1e-9 of the largest load), at most kMaxIterations
    constexpr int kMaxIterations = 200;
    // local copies of the velocities of the body (index 0) and of each distinct partner
    struct Motion
    {
        RigidBody* body;
        Vec3 v;
        Vec3 w;
        Real invMass;
        Mat3 invInertia;
    };
    thread_local std::vector<Motion> motions;
    motions.assign(1, {&body, body.linearVelocity, body.angularVelocity, invMassOf(body), invInertiaOf(body)});
    struct Row
    {
        std::size_t partner = 0; // index into motions
        Vec3 lever;              // from the body's centre
        Vec3 partnerLever;       // from the partner's centre
        Vec3 normal;
        Vec3 tangent1;
        Vec3 tangent2;
        Real correction = 0.0; // mid-step term of relativeVelocity, held fixed
        Real keep = 0.0;       // target normal velocity
        Real normalMass = 0.0;
        Real tangentMass1 = 0.0;
        Real tangentMass2 = 0.0;
        // the rows of the velocity Jacobian along n, t1 and t2 for each side (r x d), and what a
        // unit impulse along them does to its angular velocity (I^-1 (r x d)), worked out once so
        // that an iteration costs dot products and additions
        std::array<Vec3, 3> bodyArm;
        std::array<Vec3, 3> partnerArm;
        std::array<Vec3, 3> bodyTurn;
        std::array<Vec3, 3> partnerTurn;
        Real load = 0.0;
        Real friction1 = 0.0; // friction along tangent1
        Real friction2 = 0.0; // and along tangent2
        Vec3 impulse() const { return load * normal + friction1 * tangent1 + friction2 * tangent2; }
    };
    const std::size_t n = patch.size();
    thread_local std::vector<Row> rows;
    thread_local std::vector<Real> approach;
    thread_local std::vector<Real> keep;
    thread_local std::vector<Vec3> levers; // the rows' levers, as solvePatchLeastSquares and applyToPatch take them
    thread_local std::vector<Vec3> partnerLevers;
    thread_local std::vector<Vec3> initial;
    thread_local std::vector<Motion> untouched;
    thread_local std::vector<Vec3> impulses;
    rows.assign(n, Row{});
    approach.resize(n);
    levers.resize(n);
    partnerLevers.resize(n);
    for (std::size_t k = 0; k < n; ++k)
    {
        const ContactPoint& contact = patch[k].contact;
        RigidBody& other = *patch[k].other;
        Row& row = rows[k];
        row.partner = 0;
        for (std::size_t m = 1; m < motions.size(); ++m)
        {
            row.partner = motions[m].body == &other ? m : row.partner;
        }
        if (row.partner == 0)
        {
            motions.push_back(
                {&other, other.linearVelocity, other.angularVelocity, invMassOf(other), invInertiaOf(other)});
            row.partner = motions.size() - 1;
        }
        row.lever = levers[k] = contact.point - body.predicted.position;
        row.partnerLever = partnerLevers[k] = contact.point - other.predicted.position;
        row.normal = contact.normal;
        row.tangent1 = row.normal.unitOrthogonal();
        row.tangent2 = row.normal.cross(row.tangent1);
        const Vec3 raw =
            body.pointVelocity(contact.point, body.predicted) - other.pointVelocity(contact.point, other.predicted);
        approach[k] = relativeVelocity(body, body.predicted, other, other.predicted, contact, settings).dot(row.normal);
        row.correction = approach[k] - raw.dot(row.normal);
        const Motion& partner = motions[row.partner];
        const Mat3 K = couplingMatrix(motions[0].invMass, motions[0].invInertia, row.lever, row.lever) +
                       couplingMatrix(partner.invMass, partner.invInertia, row.partnerLever, row.partnerLever);
        row.normalMass = 1.0 / row.normal.dot(K * row.normal);
        row.tangentMass1 = 1.0 / row.tangent1.dot(K * row.tangent1);
        row.tangentMass2 = 1.0 / row.tangent2.dot(K * row.tangent2);
        const std::array<Vec3, 3> directions{row.normal, row.tangent1, row.tangent2};
        for (std::size_t d = 0; d < 3; ++d)
        {
            row.bodyArm[d] = row.lever.cross(directions[d]);
            row.partnerArm[d] = row.partnerLever.cross(directions[d]);
            row.bodyTurn[d] = motions[0].invInertia * row.bodyArm[d];
            row.partnerTurn[d] = partner.invInertia * row.partnerArm[d];
        }
    }
    targetNormalVelocities(approach, eps, keep);
    for (std::size_t k = 0; k < n; ++k)
    {
        rows[k].keep = keep[k];
    }

    const auto relative = [&](const Row& row)
    {
        const Motion& a = motions[0];
        const Motion& b = motions[row.partner];
        return Vec3(a.v + a.w.cross(row.lever) - b.v - b.w.cross(row.partnerLever) + row.correction * row.normal);
    };
    const auto push = [&](const Row& row, const Vec3& j)
    {
        Motion& a = motions[0];
        Motion& b = motions[row.partner];
        a.v += a.invMass * j;
        a.w += a.invInertia * row.lever.cross(j);
        b.v -= b.invMass * j;
        b.w -= b.invInertia * row.partnerLever.cross(j);
    };
    // The raw relative velocities (without the mid-step term) before any impulse: with them the
    // kinetic energy the rows' impulses add is sum_k j_k . (u_k + u_k') / 2, u_k' the velocities now
    // (exact, the velocities being linear in the impulses), to be compared with the round-off of
    // its terms, sum_k |j_k| (|u_k| + |u_k'|) / 2.
    const auto rawRelative = [&](const Row& row) { return Vec3(relative(row) - row.correction * row.normal); };
    initial.resize(n);
    for (std::size_t k = 0; k < n; ++k)
    {
        initial[k] = rawRelative(rows[k]);
    }
    const auto addsEnergy = [&]
    {
        Real work = 0.0;
        Real scale = 0.0;
        for (std::size_t k = 0; k < n; ++k)
        {
            const Vec3 j = rows[k].impulse();
            const Vec3 now = rawRelative(rows[k]);
            work += 0.5 * j.dot(initial[k] + now);
            scale += 0.5 * j.norm() * (initial[k].norm() + now.norm());
        }
        return work > 1e-9 * scale;
    };
    // The same from the motions' kinetic energies. The work above is exact in exact arithmetic, but
    // loads far beyond what the motion needs (a least-squares start at a pinch: 1e10 N s on a 1 kg
    // cube, cancelling to a few m/s) leave it nothing but round-off, with either sign; the energies
    // themselves do not cancel that way.
    const auto gainsEnergy = [&]
    {
        Real gained = 0.0;
        Real scale = 0.0;
        for (std::size_t m = 0; m < motions.size(); ++m)
        {
            const Motion& now = motions[m];
            const Motion& before = untouched[m];
            if (now.invMass == 0.0)
            {
                continue; // immovable: nothing changed
            }
            const RigidBody& moved = *now.body;
            const Mat3 inertia = moved.rotation * moved.principalInertia.asDiagonal() * moved.rotation.transpose();
            gained += 0.5 * moved.mass * (now.v - before.v).dot(now.v + before.v) +
                      0.5 * (now.w - before.w).dot(inertia * (now.w + before.w));
            scale += 0.5 * moved.mass * (now.v.squaredNorm() + before.v.squaredNorm()) +
                     0.5 * (now.w.dot(inertia * now.w) + before.w.dot(inertia * before.w));
        }
        return gained > 1e-9 * scale;
    };
    const auto addsOrGainsEnergy = [&] { return addsEnergy() || gainsEnergy(); };
    untouched = motions;
    const auto reset = [&]
    {
        motions = untouched;
        for (Row& row : rows)
        {
            row.load = 0.0;
            row.friction1 = 0.0;
            row.friction2 = 0.0;
        }
    };

    // Warm start: the least-squares impulses of the coupled system (as in applyPatchImpulse), each
    // projected into its cone; Gauss-Seidel alone converges slowly on so redundant a set of points.
    {
        thread_local Eigen::VectorXd target;
        target.resize(static_cast<Eigen::Index>(3 * n));
        for (std::size_t i = 0; i < n; ++i)
        {
            target.segment<3>(3 * static_cast<Eigen::Index>(i)) = rows[i].keep * rows[i].normal - relative(rows[i]);
        }
        thread_local PatchLeastSquares leastSquares;
        solvePatchLeastSquares(body, patch, classifyPatchMotion(patch), levers, partnerLevers, target, leastSquares);
        const Eigen::VectorXd& start = leastSquares.impulses;
        if (start.allFinite())
        {
            for (std::size_t k = 0; k < n; ++k)
            {
                Row& row = rows[k];
                const Vec3 j = start.segment<3>(3 * static_cast<Eigen::Index>(k));
                row.load = std::max(0.0, j.dot(row.normal));
                row.friction1 = j.dot(row.tangent1);
                row.friction2 = j.dot(row.tangent2);
                const Real limit = patch[k].friction * row.load;
                const Real size = std::sqrt(row.friction1 * row.friction1 + row.friction2 * row.friction2);
                if (size > limit)
                {
                    row.friction1 *= limit / size;
                    row.friction2 *= limit / size;
                }
                push(row, row.impulse());
            }
        }
    }
    const auto gaussSeidel = [&]
    {
        for (int iteration = 0; iteration < kMaxIterations; ++iteration)
        {
            Real change = 0.0;
            Real largest = 0.0;
            for (std::size_t k = 0; k < n; ++k)
            {
                Row& row = rows[k];
                Motion& a = motions[0];
                Motion& b = motions[row.partner];
                // relative velocity along direction d of the row: the Jacobian row times the motions
                const auto along = [&](std::size_t d, const Vec3& direction)
                { return direction.dot(a.v - b.v) + row.bodyArm[d].dot(a.w) - row.partnerArm[d].dot(b.w); };

                const Real un = along(0, row.normal) + row.correction;
                const Real load = std::max(0.0, row.load + row.normalMass * (row.keep - un));
                const Real added = load - row.load;
                a.v += (a.invMass * added) * row.normal;
                a.w += added * row.bodyTurn[0];
                b.v -= (b.invMass * added) * row.normal;
                b.w -= added * row.partnerTurn[0];
                change = std::max(change, std::abs(added));
                largest = std::max(largest, load);
                row.load = load;

                Real friction1 = row.friction1 - row.tangentMass1 * along(1, row.tangent1);
                Real friction2 = row.friction2 - row.tangentMass2 * along(2, row.tangent2);
                const Real limit = patch[k].friction * row.load;
                const Real size = std::sqrt(friction1 * friction1 + friction2 * friction2);
                if (size > limit)
                {
                    friction1 *= limit / size;
                    friction2 *= limit / size;
                }
                const Real added1 = friction1 - row.friction1;
                const Real added2 = friction2 - row.friction2;
                const Vec3 addedImpulse = added1 * row.tangent1 + added2 * row.tangent2;
                a.v += a.invMass * addedImpulse;
                a.w += added1 * row.bodyTurn[1] + added2 * row.bodyTurn[2];
                b.v -= b.invMass * addedImpulse;
                b.w -= added1 * row.partnerTurn[1] + added2 * row.partnerTurn[2];
                change = std::max(change, std::sqrt(added1 * added1 + added2 * added2));
                row.friction1 = friction1;
                row.friction2 = friction2;
            }
            if (!(change > 1e-9 * largest))
            {
                break;
            }
        }
    };
    gaussSeidel();
    // The outcome must not add energy, and two things can make it: a nearly singular patch (a body
    // pinched between faces of nearly opposite normals) whose least-squares start asks for huge
    // opposing impulses that no longer cancel once projected into the cones, more than the capped
    // iterations can take back; and restitution targets taken point by point, which at a pinch
    // (separating along two nearly opposite normals at once) are out of reach, so the loads grow
    // until the cap. Such a patch is solved again as inelastic and from rest: its targets
    // (u_n >= 0) are always reachable and each normal step of that solve lowers the energy. Should
    // even that add energy, the patch is left to the pairwise impulses.
    if (addsOrGainsEnergy())
    {
        reset();
        for (Row& row : rows)
        {
            row.keep = 0.0;
        }
        gaussSeidel();
        if (addsOrGainsEnergy())
        {
            reset();
            return false;
        }
    }

    impulses.resize(n);
    bool applied = false;
    for (std::size_t k = 0; k < n; ++k)
    {
        impulses[k] = rows[k].impulse();
        applied = applied || !impulses[k].isZero(0.0);
    }
    applyToPatch(body, patch, impulses, levers, partnerLevers);
    return applied;
}

} // namespace impulse
