// SPDX-License-Identifier: MIT
// The contact impulse of GBF03 sec. 6: frictionless, sticking and sliding cases against closed forms,
// the energy safeguard over random contacts, and the collision matrix against the analytic sphere.
#include "dynamics/impulse.hpp"
#include "dynamics/integrate.hpp"

#include <Eigen/Eigenvalues>
#include <Eigen/LU>
#include <gtest/gtest.h>

#include <cmath>
#include <random>

namespace impulse
{
namespace
{

// Closed forms below involve one 3x3 solve of a well-conditioned K: 1e-12 relative to the velocity
// scale (~1 m/s) is round-off with a wide margin.
constexpr Real kTol = 1e-12;

void expectVecNear(const Vec3& actual, const Vec3& expected, Real tol = kTol)
{
    EXPECT_LT((actual - expected).norm(), tol)
        << "actual   " << actual.transpose() << "\nexpected " << expected.transpose();
}

ContactBody pointMass(Real mass)
{
    return {1.0 / mass, Mat3::Zero(), Vec3::Zero()};
}

Mat3 crossMatrix(const Vec3& r)
{
    Mat3 m;
    m << 0.0, -r.z(), r.y(), r.z(), 0.0, -r.x(), -r.y(), r.x(), 0.0;
    return m;
}

// A unit vector orthogonal to n.
Vec3 tangentOf(const Vec3& n)
{
    return n.unitOrthogonal();
}

// Post-impulse relative velocities of a head-on hit along x of masses m1 (moving u1) and m2 (moving u2),
// the textbook result of guendelman.md sec. 13.6.
struct HeadOn
{
    Real v1;
    Real v2;
};

HeadOn textbookHeadOn(Real m1, Real u1, Real m2, Real u2, Real eps)
{
    return {(m1 * u1 + m2 * u2 + m2 * eps * (u2 - u1)) / (m1 + m2),
            (m1 * u1 + m2 * u2 + m1 * eps * (u1 - u2)) / (m1 + m2)};
}

// ---- frictionless head-on ----

TEST(Impulse, UnitMassesHaveCollisionMatrixTwiceIdentity)
{
    const Mat3 k = collisionMatrix(pointMass(1.0), pointMass(1.0));
    EXPECT_EQ(k, Mat3(2.0 * Mat3::Identity()));
}

TEST(Impulse, ElasticHeadOnExchangesNormalVelocity)
{
    // A on the +x side moving -1, B moving +1: normal from B toward A is +x
    const Vec3 vA(-1.0, 0.0, 0.0);
    const Vec3 vB(1.0, 0.0, 0.0);
    const Mat3 k = collisionMatrix(pointMass(1.0), pointMass(1.0));
    const Vec3 j = computeImpulse(vA - vB, Vec3::UnitX(), k, 1.0, 0.0);
    expectVecNear(vA + j, vB);
    expectVecNear(vB - j, vA);
}

TEST(Impulse, HalfRestitutionHeadOnMatchesTextbook)
{
    const Vec3 vA(-1.0, 0.0, 0.0);
    const Vec3 vB(1.0, 0.0, 0.0);
    const Mat3 k = collisionMatrix(pointMass(1.0), pointMass(1.0));
    const Vec3 j = computeImpulse(vA - vB, Vec3::UnitX(), k, 0.5, 0.0);
    const HeadOn expected = textbookHeadOn(1.0, -1.0, 1.0, 1.0, 0.5);
    expectVecNear(vA + j, Vec3(expected.v1, 0.0, 0.0));
    expectVecNear(vB - j, Vec3(expected.v2, 0.0, 0.0));
    // and the relative normal velocity is reversed and halved
    EXPECT_NEAR((vA + j - (vB - j)).x(), 1.0, kTol);
}

TEST(Impulse, UnequalMassHeadOnMatchesTextbookAndConservesMomentum)
{
    const Real m1 = 1.0;
    const Real m2 = 3.0;
    for (const Real eps : {0.0, 0.3, 1.0})
    {
        SCOPED_TRACE(testing::Message() << "eps " << eps);
        const Vec3 vA(-2.0, 0.0, 0.0);
        const Vec3 vB(0.5, 0.0, 0.0);
        const Mat3 k = collisionMatrix(pointMass(m1), pointMass(m2));
        const Vec3 j = computeImpulse(vA - vB, Vec3::UnitX(), k, eps, 0.0);
        const Vec3 vA1 = vA + j / m1;
        const Vec3 vB1 = vB - j / m2;
        const HeadOn expected = textbookHeadOn(m1, -2.0, m2, 0.5, eps);
        EXPECT_NEAR(vA1.x(), expected.v1, kTol);
        EXPECT_NEAR(vB1.x(), expected.v2, kTol);
        expectVecNear(m1 * vA1 + m2 * vB1, m1 * vA + m2 * vB);
    }
}

TEST(Impulse, FrictionlessImpulseIsAlongNormalWithClosedFormMagnitude)
{
    // j = -(1 + eps) u_n / (n K n) n, with lever arms so that K is not diagonal in the normal frame
    const ContactBody a{0.5, Vec3(2.0, 1.0, 3.0).asDiagonal(), Vec3(0.3, -0.2, 0.5)};
    const ContactBody b{0.25, Vec3(1.0, 4.0, 2.0).asDiagonal(), Vec3(-0.1, 0.4, -0.3)};
    const Mat3 k = collisionMatrix(a, b);
    const Vec3 n = Vec3(1.0, 2.0, -2.0) / 3.0;
    const Vec3 uRel = -0.7 * n;
    const Real eps = 0.4;
    const Vec3 j = computeImpulse(uRel, n, k, eps, 0.0);
    expectVecNear(j, -(1.0 + eps) * uRel.dot(n) / n.dot(k * n) * n);
}

// ---- no impulse ----

TEST(Impulse, SeparatingContactGetsNoImpulse)
{
    const Mat3 k = collisionMatrix(pointMass(1.0), pointMass(2.0));
    EXPECT_EQ(computeImpulse(Vec3(0.3, -1.0, 0.5), Vec3::UnitZ(), k, 0.5, 0.5), Vec3::Zero());
}

TEST(Impulse, RestingOrSlidingWithoutApproachGetsNoImpulse)
{
    // u_n = 0 exactly: resting, or sliding along the surface; friction needs a normal impulse to act
    const Mat3 k = collisionMatrix(pointMass(1.0), pointMass(2.0));
    EXPECT_EQ(computeImpulse(Vec3::Zero(), Vec3::UnitZ(), k, 1.0, 0.5), Vec3::Zero());
    EXPECT_EQ(computeImpulse(Vec3(2.0, -1.0, 0.0), Vec3::UnitZ(), k, 1.0, 0.5), Vec3::Zero());
}

TEST(Impulse, TwoStaticBodiesGetNoImpulse)
{
    // K = 0 is singular: nothing can be moved
    const Mat3 k = collisionMatrix(ContactBody{}, ContactBody{});
    EXPECT_EQ(computeImpulse(Vec3(0.0, 0.0, -1.0), Vec3::UnitZ(), k, 0.5, 0.5), Vec3::Zero());
}

// ---- collision matrix ----

// A ball of mass m and radius R touching the ground, contact point at lever arm -R n.
ContactBody sphereOnGround(Real mass, Real radius, const Vec3& n)
{
    const Real inertia = 0.4 * mass * radius * radius;
    return {1.0 / mass, Mat3::Identity() / inertia, -radius * n};
}

TEST(Impulse, SphereOnGroundMatrixIsInverseMassNormallyAndRollingMassTangentially)
{
    // K = 1/m 1 - [r]x I^-1 [r]x with r = -R n: 1/m along n, 1/m + R^2/I across it, no coupling
    const Real m = 2.0;
    const Real radius = 0.5;
    const Real inertia = 0.4 * m * radius * radius;
    const Vec3 n = Vec3(0.2, -0.5, 1.0).normalized();
    const Mat3 k = collisionMatrix(sphereOnGround(m, radius, n), ContactBody{});
    const Vec3 t1 = tangentOf(n);
    const Vec3 t2 = n.cross(t1);
    EXPECT_NEAR(n.dot(k * n), 1.0 / m, kTol);
    EXPECT_NEAR(t1.dot(k * t1), 1.0 / m + radius * radius / inertia, kTol);
    EXPECT_NEAR(t2.dot(k * t2), 1.0 / m + radius * radius / inertia, kTol);
    EXPECT_NEAR(n.dot(k * t1), 0.0, kTol);
    EXPECT_NEAR(n.dot(k * t2), 0.0, kTol);
    EXPECT_NEAR(t1.dot(k * t2), 0.0, kTol);
    // 1/m + R^2/I = 7 / (2 m) for a solid sphere
    EXPECT_NEAR(t1.dot(k * t1), 3.5 / m, kTol);
}

TEST(Impulse, CollisionMatrixPredictsPointVelocityChangeOfApplyImpulse)
{
    // K j is the change of u_A(p) - u_B(p) when A receives j at p and B receives -j
    RigidBody a;
    a.mass = 2.0;
    a.invMass = 0.5;
    a.principalInertia = Vec3(0.3, 0.5, 0.7);
    a.invPrincipalInertia = a.principalInertia.cwiseInverse();
    a.orientation = Quat(Eigen::AngleAxisd(0.8, Vec3(1.0, -2.0, 0.5).normalized()));
    a.rotation = a.orientation.toRotationMatrix();
    a.position = Vec3(0.1, 0.2, 0.3);
    RigidBody b = a;
    b.mass = 5.0;
    b.invMass = 0.2;
    b.principalInertia = Vec3(1.1, 0.4, 0.9);
    b.invPrincipalInertia = b.principalInertia.cwiseInverse();
    b.orientation = Quat(Eigen::AngleAxisd(-1.3, Vec3(0.0, 1.0, 1.0).normalized()));
    b.rotation = b.orientation.toRotationMatrix();
    b.position = Vec3(-0.4, 0.0, -0.2);
    updateDerivedQuantities(a);
    updateDerivedQuantities(b);

    const Vec3 p(0.0, 0.1, 0.05);
    const Vec3 j(0.3, -0.7, 1.1);
    const Vec3 before = a.pointVelocity(p, a.pose()) - b.pointVelocity(p, b.pose());
    const Mat3 k =
        collisionMatrix({a.invMass, a.invInertiaWorld, p - a.position}, {b.invMass, b.invInertiaWorld, p - b.position});
    applyImpulse(a, j, p - a.position);
    applyImpulse(b, -j, p - b.position);
    const Vec3 after = a.pointVelocity(p, a.pose()) - b.pointVelocity(p, b.pose());
    expectVecNear(after - before, k * j);
}

// A random body at a contact: random mass, rotated diagonal inertia and lever arm.
ContactBody randomBody(std::mt19937& rng)
{
    std::uniform_real_distribution<Real> mass(0.1, 10.0);
    std::uniform_real_distribution<Real> moment(0.05, 5.0);
    std::uniform_real_distribution<Real> lever(-1.0, 1.0);
    std::normal_distribution<Real> gauss(0.0, 1.0);
    const Mat3 r = Quat(gauss(rng), gauss(rng), gauss(rng), gauss(rng)).normalized().toRotationMatrix();
    const Vec3 inertia(moment(rng), moment(rng), moment(rng));
    return {1.0 / mass(rng), r * inertia.cwiseInverse().asDiagonal() * r.transpose(),
            Vec3(lever(rng), lever(rng), lever(rng))};
}

struct RandomContact
{
    Mat3 k;
    Vec3 n;
    Vec3 uRel;
};

// Two random bodies, a random unit normal and a random relative velocity mirrored to approach.
RandomContact randomApproachingContact(std::mt19937& rng, std::normal_distribution<Real>& gauss)
{
    const Mat3 k = collisionMatrix(randomBody(rng), randomBody(rng));
    const Vec3 n = Vec3(gauss(rng), gauss(rng), gauss(rng)).normalized();
    Vec3 uRel(gauss(rng), gauss(rng), gauss(rng));
    if (uRel.dot(n) > 0.0)
    {
        uRel -= 2.0 * uRel.dot(n) * n;
    }
    return {k, n, uRel};
}

TEST(Impulse, CollisionMatrixIsSymmetricPositiveDefinite)
{
    // -[r]x I^-1 [r]x = [r]x^T I^-1 [r]x is positive semi-definite, so the smallest eigenvalue of K is
    // at least 1/m_A + 1/m_B
    std::mt19937 rng(4242u);
    for (int trial = 0; trial < 1000; ++trial)
    {
        const ContactBody a = randomBody(rng);
        const ContactBody b = randomBody(rng);
        const Mat3 k = collisionMatrix(a, b);
        // products of order-10 entries: round-off ~1e-14
        EXPECT_LT((k - k.transpose()).norm(), 1e-13 * k.norm()) << "trial " << trial;
        const Eigen::SelfAdjointEigenSolver<Mat3> eigen(0.5 * (k + k.transpose()));
        EXPECT_GE(eigen.eigenvalues().minCoeff(), (a.invMass + b.invMass) * (1.0 - 1e-12)) << "trial " << trial;
    }
}

TEST(Impulse, CollisionMatrixOfStaticPartnerIsTheDynamicBodysAlone)
{
    std::mt19937 rng(5u);
    const ContactBody a = randomBody(rng);
    const Mat3 ka =
        a.invMass * Mat3::Identity() - crossMatrix(a.leverArm) * a.invInertiaWorld * crossMatrix(a.leverArm);
    const ContactBody ground{0.0, Mat3::Zero(), Vec3(0.3, 0.2, -5.0)};
    expectVecNear(collisionMatrix(a, ground) * Vec3::UnitX(), ka * Vec3::UnitX(), 1e-14);
    expectVecNear(collisionMatrix(a, ground) * Vec3::UnitY(), ka * Vec3::UnitY(), 1e-14);
    expectVecNear(collisionMatrix(a, ground) * Vec3::UnitZ(), ka * Vec3::UnitZ(), 1e-14);
    EXPECT_EQ(collisionMatrix(a, ground), collisionMatrix(ground, a));
}

// ---- friction: sticking ----

TEST(Impulse, StaticFrictionStopsSlipAndReversesScaledNormalVelocity)
{
    // a ball on the ground hitting at an angle, friction ample: u' = -eps u_n n exactly
    const Vec3 n = Vec3::UnitZ();
    const Mat3 k = collisionMatrix(sphereOnGround(1.5, 0.4, n), ContactBody{});
    const Vec3 uRel(0.6, -0.3, -2.0);
    for (const Real eps : {0.0, 0.5, 1.0})
    {
        SCOPED_TRACE(testing::Message() << "eps " << eps);
        const Vec3 j = computeImpulse(uRel, n, k, eps, 10.0);
        const Vec3 after = uRel + k * j;
        expectVecNear(after, -eps * uRel.dot(n) * n);
    }
}

TEST(Impulse, StaticFrictionOnRandomContactsStopsSlip)
{
    // eps = 0 asks for u' = 0, which never adds energy, so the sticking impulse K^-1 (-u) must be taken
    // whenever it lies in the cone: with mu = 1e6 that is whenever it pushes (j_s . n > 0)
    std::mt19937 rng(77u);
    std::normal_distribution<Real> gauss(0.0, 1.0);
    int sticking = 0;
    for (int trial = 0; trial < 500; ++trial)
    {
        const auto [k, n, uRel] = randomApproachingContact(rng, gauss);
        const Vec3 stick = k.fullPivLu().solve(-uRel);
        if (!(stick.dot(n) > 1e-9 * stick.norm()))
        {
            continue; // stopping the slip would take a pull: no cone contains it
        }
        ++sticking;
        const Vec3 j = computeImpulse(uRel, n, k, 0.0, 1e6);
        // K at most ~1e4 times its smallest eigenvalue here: round-off of the solve well below 1e-11
        expectVecNear(uRel + k * j, Vec3::Zero(), 1e-11);
    }
    EXPECT_GT(sticking, 250);
}

// ---- friction: sliding ----

TEST(Impulse, KineticFrictionTangentialPartIsMuTimesNormalPartAgainstSlip)
{
    const Vec3 n = Vec3(0.0, 0.6, 0.8);
    const Mat3 k = collisionMatrix(sphereOnGround(1.5, 0.4, n), ContactBody{});
    const Vec3 slip = Vec3(1.0, 0.0, 0.0);
    const Vec3 uRel = 3.0 * slip - 1.0 * n; // fast slip, slow approach: sticking needs far more than mu
    const Real mu = 0.1;
    const Real eps = 0.5;
    const Vec3 j = computeImpulse(uRel, n, k, eps, mu);
    const Real jn = j.dot(n);
    const Vec3 jt = j - jn * n;
    EXPECT_GT(jn, 0.0);
    EXPECT_NEAR(jt.norm(), mu * jn, kTol);
    expectVecNear(jt, -mu * jn * slip);
    // the sphere's K does not couple n and t: j_n = (1 + eps) |u_n| / (n K n) = (1 + eps) |u_n| m
    EXPECT_NEAR(jn, (1.0 + eps) * 1.0 * 1.5, kTol);
    // so the normal velocity is reversed exactly as without friction
    EXPECT_NEAR((uRel + k * j).dot(n), eps * 1.0, kTol);
}

TEST(Impulse, KineticFrictionSlowsButDoesNotReverseSlip)
{
    // j_t = -mu j_n t changes the slip by -mu j_n (t K t) t, less than the slip itself here
    const Vec3 n = Vec3::UnitZ();
    const Real m = 1.5;
    const Real radius = 0.4;
    const Mat3 k = collisionMatrix(sphereOnGround(m, radius, n), ContactBody{});
    const Vec3 uRel(3.0, 0.0, -1.0);
    const Real mu = 0.2;
    const Vec3 j = computeImpulse(uRel, n, k, 0.0, mu);
    const Vec3 after = uRel + k * j;
    // j_n = m, slip change = -mu m (7 / (2 m)) = -0.7
    EXPECT_NEAR(after.x(), 3.0 - 0.7, kTol);
    EXPECT_NEAR(after.y(), 0.0, kTol);
    EXPECT_NEAR(after.z(), 0.0, kTol);
}

TEST(Impulse, KineticFrictionOnRandomContactsIsMuTimesNormalPart)
{
    // with a small mu the sticking impulse (which needs |j_t| ~ |u_t| / |K|) lies outside the cone;
    // the returned impulse, when not scaled to zero, keeps |j_t| = mu j_n
    std::mt19937 rng(8u);
    std::normal_distribution<Real> gauss(0.0, 1.0);
    std::uniform_real_distribution<Real> unit(0.0, 1.0);
    int sliding = 0;
    for (int trial = 0; trial < 500; ++trial)
    {
        const Mat3 k = collisionMatrix(randomBody(rng), randomBody(rng));
        const Vec3 n = Vec3(gauss(rng), gauss(rng), gauss(rng)).normalized();
        const Vec3 t = tangentOf(n);
        const Vec3 uRel = 5.0 * t - 0.5 * n;
        const Real mu = 0.05;
        const Vec3 j = computeImpulse(uRel, n, k, unit(rng), mu);
        const Real jn = j.dot(n);
        const Vec3 jt = j - jn * n;
        ASSERT_GE(jn, 0.0) << "trial " << trial;
        EXPECT_NEAR(jt.norm(), mu * jn, 1e-12 * (1.0 + j.norm())) << "trial " << trial;
        if (jn > 0.0)
        {
            expectVecNear(jt, -mu * jn * t, 1e-12 * (1.0 + j.norm()));
            ++sliding;
        }
    }
    EXPECT_GT(sliding, 400);
}

// ---- energy ----

TEST(Impulse, ImpulseNeverIncreasesRelativeKineticEnergy)
{
    // In the metric K^-1 the relative kinetic energy of the contact is E(u) = 1/2 u^T K^-1 u and
    // E(u + K j) - E(u) = j.u + 1/2 j.K j. The latter needs no inverse; both forms are checked, the
    // inverse one only where K is well conditioned.
    std::mt19937 rng(31415u);
    std::normal_distribution<Real> gauss(0.0, 1.0);
    std::uniform_real_distribution<Real> epsDist(0.0, 1.0);
    std::uniform_real_distribution<Real> muDist(0.0, 2.0);
    int nonZero = 0;
    for (int trial = 0; trial < 20000; ++trial)
    {
        const Mat3 k = collisionMatrix(randomBody(rng), randomBody(rng));
        const Vec3 n = Vec3(gauss(rng), gauss(rng), gauss(rng)).normalized();
        const Vec3 uRel(gauss(rng), gauss(rng), gauss(rng));
        const Real eps = epsDist(rng);
        const Real mu = muDist(rng);
        const Vec3 j = computeImpulse(uRel, n, k, eps, mu);
        if (!j.isZero(0.0))
        {
            ++nonZero;
        }
        const Real gain = j.dot(uRel) + 0.5 * j.dot(k * j);
        // round-off of products of magnitude |j||u| and |j|^2 |K|; eps = 1 frictionless is exactly 0
        const Real roundOff = 1e-12 * (j.norm() * uRel.norm() + j.squaredNorm() * k.norm());
        EXPECT_LE(gain, roundOff) << "trial " << trial << " eps " << eps << " mu " << mu;

        const Mat3 kInv = k.inverse();
        const Vec3 after = uRel + k * j;
        const Real before = 0.5 * uRel.dot(kInv * uRel);
        const Real energyAfter = 0.5 * after.dot(kInv * after);
        EXPECT_LE(energyAfter, before + 1e-10 * before) << "trial " << trial;
        // the normal impulse only pushes
        EXPECT_GE(j.dot(n), -1e-12 * j.norm()) << "trial " << trial;
    }
    // about half the random velocities approach
    EXPECT_GT(nonZero, 8000);
}

TEST(Impulse, ElasticFrictionlessImpulseConservesRelativeKineticEnergy)
{
    std::mt19937 rng(271u);
    std::normal_distribution<Real> gauss(0.0, 1.0);
    for (int trial = 0; trial < 500; ++trial)
    {
        const auto [k, n, uRel] = randomApproachingContact(rng, gauss);
        const Vec3 j = computeImpulse(uRel, n, k, 1.0, 0.0);
        const Real gain = j.dot(uRel) + 0.5 * j.dot(k * j);
        const Real scale = j.norm() * uRel.norm() + j.squaredNorm() * k.norm();
        EXPECT_NEAR(gain, 0.0, 1e-12 * scale) << "trial " << trial;
        // and the normal relative velocity reverses
        EXPECT_NEAR((uRel + k * j).dot(n), -uRel.dot(n), 1e-12 * (uRel.norm() + k.norm() * j.norm()));
    }
}

} // namespace
} // namespace impulse
