// SPDX-License-Identifier: MIT
// A cube turning over one of its edges, against rigid-body mechanics with Coulomb friction: the
// mechanism of a tossed cube that lands on its leading edge and tumbles onto the next face.
//  - An impact on an edge that sticks and does not bounce leaves the cube turning about that edge,
//    with the angular momentum about the edge it had before (the impulse acts at the edge).
//  - A cube sliding on one edge obeys two ODEs (the contact holds the edge on the ground, friction
//    mu N opposes the slip); tilted past the balance d = mu h it tips forward, short of it it falls back.
//  - A cube sliding into a low stop tips over exactly when the kinetic energy of its turn about the
//    stop's edge, L^2 / 2 I_edge, can lift its centre over that edge.
#include <impulse/impulse.hpp>

#include <gtest/gtest.h>

#include <array>
#include <cmath>

namespace impulse::test
{
namespace
{

constexpr Real kHalf = 0.0524; // the measured cube of ../shared/realworld: side 0.1048 m, 0.37 kg
constexpr Real kMass = 0.37;
constexpr Real kMoment = 8.1e-4; // kg m^2 about every axis

// The cube's front-bottom edge in the body frame (x forward, z up), and where a turn of phi about
// +y (the front going down) puts it relative to the centre: r = (c a - s a, -s a - c a) in (x, z).
struct EdgeArm
{
    Real x;
    Real z;
};

EdgeArm edgeArm(Real phi)
{
    const Real c = std::cos(phi);
    const Real s = std::sin(phi);
    return {c * kHalf - s * kHalf, -s * kHalf - c * kHalf};
}

Quat turnAboutY(Real phi)
{
    return Quat(Eigen::AngleAxis<Real>(phi, Vec3::UnitY()));
}

// The turn about +y of an orientation that turns only about y.
Real turnOf(const Quat& q)
{
    return 2.0 * std::atan2(q.y(), q.w());
}

struct CubeOnGround
{
    World world;
    BodyId cube;
};

// The measured cube over the ground plane, turned by phi about y with its front-bottom edge `gap`
// above the ground.
CubeOnGround cubeOnItsEdge(Real phi, Real gap, const Vec3& velocity, const Vec3& angularVelocity, Real gravity,
                           Real friction, Real restitution)
{
    CubeOnGround scene{World({.gravity = {0, 0, -gravity}}), {}};
    const MaterialId material = scene.world.createMaterial({.restitution = restitution, .friction = friction});
    scene.world.createBody({.type = BodyType::Static, .shape = Plane{}, .material = material});
    scene.cube = scene.world.createBody({.shape = Box{Vec3::Constant(kHalf)},
                                         .material = material,
                                         .mass = kMass,
                                         .principalInertia = Vec3::Constant(kMoment),
                                         .position = {0, 0, gap - edgeArm(phi).z},
                                         .orientation = turnAboutY(phi),
                                         .linearVelocity = velocity,
                                         .angularVelocity = angularVelocity});
    return scene;
}

struct ImpactCase
{
    Real phi;   // tilt at impact, rad
    Real vx;    // m/s
    Real vz;    // m/s, down
    Real omega; // rad/s about y
};

TEST(EdgePivot, AStickingPlasticImpactOnAnEdgeKeepsTheAngularMomentumAboutThatEdge)
{
    // no gravity, so that nothing but the impact changes the motion; mu 10 sticks, eps 0 does not bounce
    const std::array<ImpactCase, 6> cases{{{0.2, 1.0, -0.8, 0.0},
                                           {0.5, 1.0, -0.8, 0.0},
                                           {0.7, 1.0, -0.8, 0.0},
                                           {0.2, 0.0, -1.0, 0.0},
                                           {0.5, 0.0, -1.0, 0.0},
                                           {0.5, 1.0, -0.8, -3.0}}};
    for (const ImpactCase& c : cases)
    {
        // the lever arm is taken at the step's predicted pose, which a spinning cube reaches turned by
        // w dt: first order in dt, so the spinning case is checked at dt = 0.1 ms
        const Real dt = c.omega == 0.0 ? 1e-3 : 1e-4;
        SCOPED_TRACE(testing::Message() << "tilt " << c.phi << ", v (" << c.vx << ", " << c.vz << "), w " << c.omega);
        // 10 um above the ground: the impact falls within the first step
        CubeOnGround scene = cubeOnItsEdge(c.phi, 1e-5, {c.vx, 0, c.vz}, {0, c.omega, 0}, 0.0, 10.0, 0.0);
        const EdgeArm arm = edgeArm(c.phi);
        // L about the edge point E = I w + (G - E) x m v, y component; (G - E) = -arm
        const Real momentumAboutEdge = kMoment * c.omega + kMass * (-arm.z * c.vx + arm.x * c.vz);
        const Real momentAboutEdge = kMoment + kMass * (arm.x * arm.x + arm.z * arm.z);
        const Real expected = momentumAboutEdge / momentAboutEdge;

        scene.world.step({.dt = dt});
        const BodyState after = scene.world.state(scene.cube);
        EXPECT_NEAR(after.angularVelocity.y(), expected, 2e-3 * std::abs(expected));
        EXPECT_NEAR(after.angularVelocity.x(), 0.0, 1e-9);
        EXPECT_NEAR(after.angularVelocity.z(), 0.0, 1e-9);
        // the edge sticks: it no longer moves along the ground (to 0.2 % of the speed it came in at)
        const Vec3 edge = after.position + after.orientation * Vec3(kHalf, 0, -kHalf);
        const Vec3 edgeVelocity = after.linearVelocity + after.angularVelocity.cross(edge - after.position);
        EXPECT_LT(std::abs(edgeVelocity.x()), 2e-3 * std::hypot(c.vx, c.vz)) << "edge slips at " << edgeVelocity.x();
    }
}

// The motion of a cube sliding forward (+x) on its front-bottom edge, the edge held on the ground:
// x_G, phi, their rates. Newton: m x'' = F, m z'' = N - m g with z_G = -r_z(phi), so
// z'' = r_x phi'' + r_z phi'^2; Euler about the centre: I phi'' = r_z F - r_x N; F = -mu N while
// the edge slides forward. Eliminating N gives phi'' in closed form.
struct EdgeRide
{
    Real x;
    Real phi;
    Real vx;
    Real omega;
};

EdgeRide rideRate(const EdgeRide& s, Real mu, Real g)
{
    const EdgeArm r = edgeArm(s.phi);
    const Real lever = -mu * r.z - r.x; // I phi'' = lever N
    const Real phiAcceleration = (-kMass * g - kMass * r.z * s.omega * s.omega) / (kMass * r.x - kMoment / lever);
    const Real normal = kMoment * phiAcceleration / lever;
    return {s.vx, s.omega, -mu * normal / kMass, phiAcceleration};
}

EdgeRide rideByOde(EdgeRide s, Real mu, Real g, Real duration)
{
    constexpr int kSteps = 12000;
    const Real h = duration / kSteps;
    const auto add = [](const EdgeRide& a, const EdgeRide& b, Real f) {
        return EdgeRide{a.x + f * b.x, a.phi + f * b.phi, a.vx + f * b.vx, a.omega + f * b.omega};
    };
    for (int k = 0; k < kSteps; ++k)
    {
        const EdgeRide k1 = rideRate(s, mu, g);
        const EdgeRide k2 = rideRate(add(s, k1, h / 2), mu, g);
        const EdgeRide k3 = rideRate(add(s, k2, h / 2), mu, g);
        const EdgeRide k4 = rideRate(add(s, k3, h), mu, g);
        s = add(s, add(add(k1, k4, 1.0), add(k2, k3, 1.0), 2.0), h / 6.0);
    }
    return s;
}

Real simulatedTilt(Real phi0, Real speed, Real mu, Real g, Real duration, Real dt)
{
    CubeOnGround scene = cubeOnItsEdge(phi0, 0.0, {speed, 0, 0}, Vec3::Zero(), g, mu, 0.0);
    const int steps = static_cast<int>(std::lround(duration / dt));
    for (int k = 0; k < steps; ++k)
    {
        scene.world.step({.dt = dt});
    }
    return turnOf(scene.world.state(scene.cube).orientation);
}

TEST(EdgePivot, ACubeSlidingOnItsEdgeTipsForwardOrFallsBackAsTheCoulombOdeSaysAndConvergesToIt)
{
    constexpr Real kG = 9.81;
    constexpr Real kMu = 0.3;
    constexpr Real kSpeed = 1.0;
    constexpr Real kDuration = 0.12;
    // balance: the centre behind the edge by mu times its height, tan(pi/4 - phi) = mu, phi = 0.4817
    for (const Real phi0 : {0.40, 0.60})
    {
        SCOPED_TRACE(testing::Message() << "tilt " << phi0);
        const Real exact = rideByOde({0, phi0, kSpeed, 0}, kMu, kG, kDuration).phi;
        // the ODE itself: 0.40 falls back to 0.124, 0.60 tips on to 0.980 (the cube stays on its edge
        // and keeps sliding throughout)
        EXPECT_TRUE(phi0 < 0.4817 ? exact < phi0 - 0.2 : exact > phi0 + 0.3) << exact;
        Real previousError = 0.0;
        for (const Real dt : {1e-3, 5e-4, 2.5e-4})
        {
            const Real error = std::abs(simulatedTilt(phi0, kSpeed, kMu, kG, kDuration, dt) - exact);
            // first order in dt: 2 % of the turn at 1 ms, halving with dt
            EXPECT_LT(error, 0.025 * std::abs(exact - phi0) * dt / 1e-3) << "dt " << dt;
            if (previousError > 0.0)
            {
                EXPECT_LT(error, 0.6 * previousError) << "dt " << dt;
            }
            previousError = error;
        }
    }
}

// A cube of side 0.2 m and 1 kg slides without friction into a stop 1 cm high that grips (mu 2, no
// bounce). Its front face meets the stop's; the impact turns it about the stop's top edge with
// w = m v (a - h) / I_edge. It tips over if that turn can lift its centre from a - h over the edge,
// to sqrt(a^2 + (a - h)^2) above it: v_c = I_edge / (m (a - h)) * sqrt(2 m g (r - (a - h)) / I_edge),
// 1.6345 m/s. (Through the turn the stop's push stays positive, so the edge holds it throughout.)
constexpr Real kStopCubeHalf = 0.1; // a, m
constexpr Real kStopCubeMass = 1.0; // kg
constexpr Real kStopHeight = 0.01;  // h, m

Real tiltAfterSlidingIntoAStop(Real speed)
{
    World world({.gravity = {0, 0, -9.81}});
    const MaterialId slick = world.createMaterial({.restitution = 0.0, .friction = 0.0});
    const MaterialId grip = world.createMaterial({.restitution = 0.0, .friction = 2.0});
    world.setPairCoefficients(slick, grip, {.restitution = 0.0, .friction = 2.0});
    world.createBody({.type = BodyType::Static, .shape = Plane{}, .material = slick});
    world.createBody({.type = BodyType::Static,
                      .shape = Box{{0.05, 0.5, kStopHeight / 2}},
                      .material = grip,
                      .position = {0.2, 0, kStopHeight / 2}});
    const BodyId cube = world.createBody({.shape = Box{Vec3::Constant(kStopCubeHalf)},
                                          .material = slick,
                                          .mass = kStopCubeMass,
                                          .position = {0.2 - 0.05 - kStopCubeHalf - 0.01, 0, kStopCubeHalf},
                                          .linearVelocity = {speed, 0, 0}});
    for (int k = 0; k < 1500; ++k)
    {
        world.step({.dt = 1e-3});
    }
    return turnOf(world.state(cube).orientation);
}

TEST(EdgePivot, ACubeSlidingIntoALowStopTipsOverAboveTheCriticalSpeedAndRocksBackBelowIt)
{
    const Real lever = kStopCubeHalf - kStopHeight;
    const Real radius = std::hypot(kStopCubeHalf, lever);
    const Real momentAboutEdge =
        2.0 / 3.0 * kStopCubeMass * kStopCubeHalf * kStopCubeHalf + kStopCubeMass * radius * radius;
    const Real critical = momentAboutEdge / (kStopCubeMass * lever) *
                          std::sqrt(2.0 * kStopCubeMass * 9.81 * (radius - lever) / momentAboutEdge);
    ASSERT_NEAR(critical, 1.6345, 1e-4);
    // 3 % either side, 6 % in energy (at dt = 1 ms the simulated threshold lies within 2 % of v_c)
    const Real pi = std::acos(-1.0);
    EXPECT_LT(std::abs(tiltAfterSlidingIntoAStop(0.97 * critical)), 1e-3) << "rocks back onto its face";
    EXPECT_GT(tiltAfterSlidingIntoAStop(1.03 * critical), pi / 4) << "tips over the stop";
}

} // namespace
} // namespace impulse::test
