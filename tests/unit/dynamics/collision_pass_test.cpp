// SPDX-License-Identifier: MIT
// The collision pass's velocity screen, slowerThanRestingApproach: where it says a pair is too slow
// for any point to approach past the resting approach, the pass skips the pair's geometry. That is
// only sound if approachSpeed is then zero at every point a contact could have, whatever its normal:
// checked here on random pairs of boxes, at points anywhere a contact point can lie (within each
// body's bounding radius, plus the threshold, of its predicted centre) and random normals.
#include "dynamics/collision_pass.hpp"
#include "dynamics/integrate.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

namespace impulse
{
namespace
{

constexpr Real kDt = 1e-3;
constexpr Real kGravity = 9.81;

PassSettings collisionPassSettings()
{
    PassSettings settings;
    settings.dt = kDt;
    settings.gravity = Vec3(0.0, 0.0, -kGravity);
    settings.lookahead = kDt;
    settings.predictWithAcceleration = true;
    settings.midStepRestitution = true;
    settings.timeOfImpactGeometry = true;
    settings.threshold = 1e-6;
    settings.restingApproach = kDt * kGravity; // the default StepOptions::restingApproach of 1
    return settings;
}

class Sampler
{
  public:
    explicit Sampler(unsigned seed) : m_engine(seed) {}

    Real uniform(Real lo, Real hi) { return std::uniform_real_distribution<Real>(lo, hi)(m_engine); }

    Vec3 direction()
    {
        Vec3 v;
        do
        {
            v = Vec3(uniform(-1.0, 1.0), uniform(-1.0, 1.0), uniform(-1.0, 1.0));
        } while (!(v.squaredNorm() > 1e-6 && v.squaredNorm() <= 1.0));
        return v.normalized();
    }

    // a vector whose length is spread evenly in log over [lo, hi]
    Vec3 logUniform(Real lo, Real hi) { return std::exp(uniform(std::log(lo), std::log(hi))) * direction(); }

    // a point of the ball of radius r about the centre
    Vec3 inBall(const Vec3& centre, Real r) { return centre + r * std::cbrt(uniform(0.0, 1.0)) * direction(); }

  private:
    std::mt19937_64 m_engine;
};

RigidBody randomBox(Sampler& sample, const Vec3& position, bool dynamic, const PassSettings& settings)
{
    RigidBody body;
    const Vec3 half(sample.uniform(0.02, 0.2), sample.uniform(0.02, 0.2), sample.uniform(0.02, 0.2));
    body.shape = Box{half};
    body.dynamic = dynamic;
    body.position = position;
    body.orientation = Quat(Eigen::AngleAxisd(sample.uniform(0.0, 3.0), sample.direction()));
    body.rotation = body.orientation.toRotationMatrix();
    body.boundingRadius = half.norm();
    if (dynamic)
    {
        body.mass = sample.uniform(0.1, 10.0);
        body.invMass = 1.0 / body.mass;
        const Vec3 squared = (2.0 * half).cwiseProduct(2.0 * half);
        body.principalInertia =
            body.mass / 12.0 * Vec3(squared.y() + squared.z(), squared.x() + squared.z(), squared.x() + squared.y());
        body.invPrincipalInertia = body.principalInertia.cwiseInverse();
        // speeds from far below to far above the resting approach, so that both answers occur
        body.linearVelocity = sample.logUniform(1e-6, 0.1);
    }
    updateDerivedQuantities(body);
    if (dynamic)
    {
        // the state is the angular momentum; the spin follows from it
        const Vec3 spin = sample.logUniform(1e-6, 1.0);
        body.angularMomentum = body.invInertiaWorld.inverse() * spin;
        updateDerivedQuantities(body);
    }
    body.predicted = body.pose();
    predictBody(body, settings);
    return body;
}

TEST(VelocityScreen, NoPointApproachesPastTheRestingApproachWhereItSaysTooSlow)
{
    const PassSettings settings = collisionPassSettings();
    Sampler sample(20261207);
    int screened = 0;
    int kept = 0;
    int points = 0;
    for (int trial = 0; trial < 4000; ++trial)
    {
        const bool bothDynamic = trial % 4 != 0; // every fourth pair: a dynamic box on a static one
        RigidBody a = randomBox(sample, Vec3(0.0, 0.0, 0.3), true, settings);
        RigidBody b = randomBox(sample, sample.inBall(Vec3(0.0, 0.0, 0.3), 0.3), bothDynamic, settings);
        if (!slowerThanRestingApproach(a, b, settings))
        {
            ++kept;
            continue;
        }
        ++screened;
        // a contact point lies within both bodies' reach: sampled in A's, kept where also in B's
        const Real reachA = a.boundingRadius + settings.threshold;
        const Real reachB = b.boundingRadius + settings.threshold;
        int checked = 0;
        for (int k = 0; k < 500 && checked < 50; ++k)
        {
            ContactPoint point;
            point.point = sample.inBall(a.predicted.position, reachA);
            if ((point.point - b.predicted.position).norm() > reachB)
            {
                continue;
            }
            ++checked;
            point.normal = sample.direction();
            ASSERT_EQ(approachSpeed(a, a.predicted, b, b.predicted, point, settings), 0.0)
                << "trial " << trial << ": |va - vb| " << (a.linearVelocity - b.linearVelocity).norm() << ", |wa| "
                << a.angularVelocity.norm() << ", |wb| " << b.angularVelocity.norm();
        }
        points += checked;
    }
    // the screen must both pass and stop pairs, or the check above proves nothing
    EXPECT_GT(screened, 400);
    EXPECT_GT(kept, 400);
    EXPECT_GT(points, 20 * screened);
}

TEST(VelocityScreen, PassesAPairThatApproachesJustPastTheRestingApproach)
{
    // a cube falling onto a static one at 1.01 resting approaches: its lowest face approaches that
    // fast everywhere, so the screen must pass the pair to the exact test
    const PassSettings settings = collisionPassSettings();
    Sampler sample(7);
    RigidBody top = randomBox(sample, Vec3(0.0, 0.0, 0.4), true, settings);
    RigidBody bottom = randomBox(sample, Vec3(0.0, 0.0, 0.1), false, settings);
    top.orientation = Quat::Identity();
    top.rotation = Mat3::Identity();
    top.angularMomentum = Vec3::Zero();
    top.linearVelocity = Vec3(0.0, 0.0, -1.01 * settings.restingApproach);
    updateDerivedQuantities(top);
    predictBody(top, settings);
    EXPECT_FALSE(slowerThanRestingApproach(top, bottom, settings));
    ContactPoint point;
    point.point = top.predicted.position - Vec3(0.0, 0.0, 0.5 * top.boundingRadius);
    point.normal = Vec3::UnitZ(); // from the bottom cube toward the top one
    EXPECT_LT(approachSpeed(top, top.predicted, bottom, bottom.predicted, point, settings), 0.0);
    // and the same cube at 0.99 of it is screened
    top.linearVelocity = Vec3(0.0, 0.0, -0.99 * settings.restingApproach);
    predictBody(top, settings);
    EXPECT_TRUE(slowerThanRestingApproach(top, bottom, settings));
}

} // namespace
} // namespace impulse
