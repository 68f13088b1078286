// SPDX-License-Identifier: MIT
// A patch solved at once by one rigid motion (rigid_patch.hpp): a box's four corners meet every target
// with admissible loads, a tipping box that would need a corner to pull is refused with nothing changed,
// two points leave the turn about their line free (with the answers of angular momentum about the line),
// and two dynamic bodies have their relative motion solved with momentum conserved.
#include "contact/contact_cache.hpp"
#include "dynamics/contact_solver.hpp"
#include "dynamics/rigid_patch.hpp"
#include "support/solver_bodies.hpp"

#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <cstdint>
#include <vector>

namespace impulse
{
namespace
{

using test::BoxBody;
using test::rowAt;
using test::slip;
using test::staticSide;

// The patch is a closed form: a 3x3 eigen-decomposition and a 6x6 solve on numbers of order one. Round-
// off leaves 1e-14 m/s or so; 1e-10 m/s is far from that and far below the 1e-6 the passes work to.
constexpr Real kTol = 1e-10;
// what solveRigidPatch is given: how closely a rigid motion must meet every target
constexpr Real kPatchTolerance = 1e-9;

PatchMover moverOf(const BoxBody& box, std::uint32_t index)
{
    return {index, box.centre, 1.0 / box.mass, box.invInertia()};
}

std::vector<ContactRow*> pointers(std::vector<ContactRow>& rows)
{
    std::vector<ContactRow*> out;
    for (ContactRow& row : rows)
    {
        out.push_back(&row);
    }
    return out;
}

// Every row at its target (normal velocity its bias, no slip) with admissible loads.
void expectSolved(const std::vector<ContactRow>& rows, const std::vector<SolverBody>& bodies)
{
    for (std::size_t k = 0; k < rows.size(); ++k)
    {
        const ContactRow& row = rows[k];
        const SolverBody& a = bodies[row.a];
        const SolverBody& b = bodies[row.b];
        EXPECT_NEAR(row.relativeVelocity(0, a, b), row.bias, kTol) << "row " << k;
        EXPECT_LT(slip(row, a, b).norm(), kTol) << "row " << k;
        EXPECT_GE(row.lambda[0], 0.0) << "row " << k;
        // within the cone, with the round-off of a norm
        EXPECT_LE(std::hypot(row.lambda[1], row.lambda[2]), row.friction * row.lambda[0] * (1.0 + 1e-12))
            << "row " << k;
    }
}

// A unit cube of 2 kg on the ground (body 1), its four lower corners rows.
struct CubeOnGround
{
    BoxBody box;
    std::vector<SolverBody> bodies;
    std::vector<ContactRow> rows;

    explicit CubeOnGround(const Vec3& velocity, const Vec3& spin = Vec3::Zero(), Real friction = 0.5)
    {
        box.mass = 2.0;
        box.centre = Vec3(0.0, 0.0, 0.5);
        box.velocity = velocity;
        box.spin = spin;
        bodies = {box.solver(), SolverBody{}};
        for (const Real x : {-0.5, 0.5})
        {
            for (const Real y : {-0.5, 0.5})
            {
                rows.push_back(rowAt(box.side(0), staticSide(1), Vec3(x, y, 0.0), Vec3::UnitZ(), friction));
            }
        }
    }
};

TEST(RigidPatch, FourCornersMeetEveryTargetAtOnceWithAdmissibleLoads)
{
    // down and sideways: friction must stop the slide (it takes 0.32 / 1.05 of the load, mu is 0.5) and
    // the corners ahead carry more than those behind, all still pushing
    CubeOnGround cube(Vec3(0.3, -0.1, -1.0));
    for (ContactRow& row : cube.rows)
    {
        row.bias = 0.05; // leave at 5 cm/s, as a restitution would ask
    }
    SolverScratch scratch;
    const std::vector<ContactRow*> rows = pointers(cube.rows);
    ASSERT_TRUE(solveRigidPatch(rows, cube.bodies, moverOf(cube.box, 0), nullptr, kPatchTolerance, scratch));
    expectSolved(cube.rows, cube.bodies);
    // a rigid motion meets equal targets at four corners by a translation: no turn is left
    EXPECT_LT(cube.bodies[0].angularVelocity.norm(), kTol);
    EXPECT_LT((cube.bodies[0].linearVelocity - Vec3(0.0, 0.0, 0.05)).norm(), kTol);
    // momentum: the loads add up to m times the change of velocity
    Vec3 total = Vec3::Zero();
    for (const ContactRow& row : cube.rows)
    {
        total += row.lambda[0] * row.direction[0] + row.lambda[1] * row.direction[1] + row.lambda[2] * row.direction[2];
    }
    EXPECT_LT((total - cube.box.mass * (Vec3(0.0, 0.0, 0.05) - cube.box.velocity)).norm(), kTol);
}

std::vector<std::uint64_t> bitsOf(const std::vector<SolverBody>& bodies, const std::vector<ContactRow>& rows)
{
    std::vector<std::uint64_t> out;
    const auto add = [&](const Vec3& v)
    {
        for (int i = 0; i < 3; ++i)
        {
            out.push_back(std::bit_cast<std::uint64_t>(v[i]));
        }
    };
    for (const SolverBody& body : bodies)
    {
        add(body.linearVelocity);
        add(body.angularVelocity);
        add(body.angularMomentum);
    }
    for (const ContactRow& row : rows)
    {
        add(Vec3(row.lambda[0], row.lambda[1], row.lambda[2]));
    }
    return out;
}

// The cube's velocities that an impulse `normal` up through the bottom face's centre c and a couple
// `couple` about y bring to rest: minus the response to them. That is then the one wrench a rigid
// motion to rest (every corner's target) asks for, and it has no tangential force, so its loads are
// normal only: N / 4 - couple / (4 h) at the corners x = +h and N / 4 + couple / (4 h) at x = -h.
CubeOnGround tippingCube(Real normal, Real couple)
{
    CubeOnGround cube(Vec3::Zero());
    const Vec3 force(0.0, 0.0, normal);
    const Vec3 lever = Vec3(0.0, 0.0, 0.0) - cube.box.centre; // from the centre to c
    const Vec3 spin = cube.box.invInertia() * (Vec3(0.0, couple, 0.0) + lever.cross(force));
    return CubeOnGround(-force / cube.box.mass, -spin, 1.0);
}

TEST(RigidPatch, APatchThatWouldPullAtACornerIsRefusedAndChangesNothing)
{
    // N = 0.2 N s and a couple of 0.5 N m s: the corners at x = +h would carry 0.05 - 0.25 < 0. They
    // rise now, and holding them takes a pull.
    CubeOnGround cube = tippingCube(0.2, 0.5);
    for (ContactRow& row : cube.rows)
    {
        row.lambda[0] = 0.01; // a warm start, already in the velocities: it must stay as it is too
    }
    ASSERT_EQ(cube.rows[3].point.x(), 0.5);
    ASSERT_GT(cube.rows[3].relativeVelocity(0, cube.bodies[0], cube.bodies[1]), 0.1) << "the premise: it rises";
    const std::vector<std::uint64_t> before = bitsOf(cube.bodies, cube.rows);
    SolverScratch scratch;
    EXPECT_FALSE(
        solveRigidPatch(pointers(cube.rows), cube.bodies, moverOf(cube.box, 0), nullptr, kPatchTolerance, scratch));
    EXPECT_EQ(bitsOf(cube.bodies, cube.rows), before) << "a refused patch changed something";

    // the control: a couple of 0.05 N m s leaves 0.05 - 0.025 on those corners and 0.05 + 0.025 on the
    // others, every load pushing, and the same patch is accepted, the cube at rest afterwards
    CubeOnGround gentle = tippingCube(0.2, 0.05);
    ASSERT_TRUE(solveRigidPatch(pointers(gentle.rows), gentle.bodies, moverOf(gentle.box, 0), nullptr, kPatchTolerance,
                                scratch));
    expectSolved(gentle.rows, gentle.bodies);
    EXPECT_LT(gentle.bodies[0].linearVelocity.norm() + gentle.bodies[0].angularVelocity.norm(), kTol);
    EXPECT_NEAR(gentle.rows[3].lambda[0], 0.025, kTol) << "what the loads above say";
    EXPECT_NEAR(gentle.rows[0].lambda[0], 0.075, kTol);
}

TEST(RigidPatch, TwoPointsUnderTheCentreLeaveTheTurnAboutTheirLineAlone)
{
    // a cube on a ridge along y under its centre, turning about the ridge at 0.7 rad/s and sinking at
    // 1 m/s: the ridge's points stop, and the turn about their line, which they cannot resist, is kept
    // (the line passes under the centre, so the impulses have no moment about an axis parallel to it
    // through the centre either)
    BoxBody box;
    box.mass = 2.0;
    box.centre = Vec3(0.0, 0.0, 0.5);
    const Real spin = 0.7;
    box.spin = Vec3(0.0, spin, 0.0);
    // turning about the line x = 0, z = 0: the centre, 0.5 above it, moves at w x (0, 0, 0.5)
    box.velocity = Vec3(spin * 0.5, 0.0, -1.0);
    std::vector<SolverBody> bodies = {box.solver(), SolverBody{}};
    std::vector<ContactRow> rows = {rowAt(box.side(0), staticSide(1), Vec3(0.0, -0.5, 0.0), Vec3::UnitZ(), 0.5),
                                    rowAt(box.side(0), staticSide(1), Vec3(0.0, 0.5, 0.0), Vec3::UnitZ(), 0.5)};
    SolverScratch scratch;
    ASSERT_TRUE(solveRigidPatch(pointers(rows), bodies, moverOf(box, 0), nullptr, kPatchTolerance, scratch));
    expectSolved(rows, bodies);
    EXPECT_NEAR(bodies[0].angularVelocity.y(), spin, kTol) << "the turn about the line, unchanged";
    EXPECT_NEAR(bodies[0].angularVelocity.x(), 0.0, kTol);
    EXPECT_NEAR(bodies[0].angularVelocity.z(), 0.0, kTol);
    EXPECT_LT((bodies[0].linearVelocity - Vec3(spin * 0.5, 0.0, 0.0)).norm(), kTol) << "only the sinking stopped";
}

TEST(RigidPatch, TwoPointsOnAnEdgeKeepTheAngularMomentumAboutTheirLine)
{
    // a cube landing on its edge x = h, z = 0 (along y) while turning about y: the edge stops, and the
    // cube turns on about it with the angular momentum it had about the edge, which impulses on the
    // edge cannot change: w' = L / (I + m d^2), d = sqrt(2) h the centre's distance from the edge
    BoxBody box;
    box.centre = Vec3(0.0, 0.0, 0.5);
    box.velocity = Vec3(0.0, 0.0, -1.0);
    box.spin = Vec3(0.0, 0.5, 0.0);
    const Real h = 0.5;
    const Real inertia = test::boxInertia(box.mass, box.half).y();
    const Vec3 edge(h, 0.0, 0.0); // the middle of the edge, world frame
    const Real aboutEdge =
        inertia * box.spin.y() + (box.centre - edge).cross(box.mass * box.velocity).y(); // L about the edge
    const Real expected = aboutEdge / (inertia + box.mass * 2.0 * h * h);
    std::vector<SolverBody> bodies = {box.solver(), SolverBody{}};
    std::vector<ContactRow> rows = {rowAt(box.side(0), staticSide(1), Vec3(h, -h, 0.0), Vec3::UnitZ(), 1.0),
                                    rowAt(box.side(0), staticSide(1), Vec3(h, h, 0.0), Vec3::UnitZ(), 1.0)};
    SolverScratch scratch;
    ASSERT_TRUE(solveRigidPatch(pointers(rows), bodies, moverOf(box, 0), nullptr, kPatchTolerance, scratch));
    expectSolved(rows, bodies);
    EXPECT_NEAR(bodies[0].angularVelocity.y(), expected, kTol);
    EXPECT_NEAR(bodies[0].angularVelocity.x(), 0.0, kTol);
    EXPECT_NEAR(bodies[0].angularVelocity.z(), 0.0, kTol);
    // a turn about the edge: the centre moves at w' y x (centre - edge)
    EXPECT_LT((bodies[0].linearVelocity - Vec3(0.0, expected, 0.0).cross(box.centre - edge)).norm(), kTol);
}

TEST(RigidPatch, WithAPartnerTheRelativeMotionIsSolvedAndMomentumIsConserved)
{
    // a unit cube (body 0) landing on a larger box (body 1) that rises to meet it, sliding across it
    // and turning a little about the vertical; both dynamic
    BoxBody top;
    top.centre = Vec3(0.2, -0.1, 2.5);
    top.velocity = Vec3(0.3, 0.1, -1.0);
    top.spin = Vec3(0.0, 0.0, 0.1);
    BoxBody bottom;
    bottom.mass = 8.0;
    bottom.half = Vec3::Constant(1.0);
    bottom.centre = Vec3(0.0, 0.0, 1.0);
    bottom.velocity = Vec3(0.0, 0.1, 0.5);
    std::vector<SolverBody> bodies = {top.solver(), bottom.solver()};
    const std::vector<Vec3> centres = {top.centre, bottom.centre};
    std::vector<ContactRow> rows;
    for (const Real x : {-0.5, 0.5})
    {
        for (const Real y : {-0.5, 0.5})
        {
            rows.push_back(rowAt(top.side(0), bottom.side(1), top.centre + Vec3(x, y, -0.5), Vec3::UnitZ(), 1.0));
        }
    }
    const Vec3 linear = top.mass * bodies[0].linearVelocity + bottom.mass * bodies[1].linearVelocity;
    const Vec3 angular = test::angularMomentumAboutOrigin(bodies, centres);
    const PatchMover partner = moverOf(bottom, 1);
    SolverScratch scratch;
    ASSERT_TRUE(solveRigidPatch(pointers(rows), bodies, moverOf(top, 0), &partner, kPatchTolerance, scratch));
    expectSolved(rows, bodies);
    EXPECT_LT((top.mass * bodies[0].linearVelocity + bottom.mass * bodies[1].linearVelocity - linear).norm(), kTol);
    EXPECT_LT((test::angularMomentumAboutOrigin(bodies, centres) - angular).norm(), kTol);
    EXPECT_GT((bodies[1].linearVelocity - bottom.velocity).norm(), 0.1) << "the partner moved too";
}

} // namespace
} // namespace impulse
