// SPDX-License-Identifier: MIT
// Contact rows and their projected Gauss-Seidel solve (contact_solver.hpp) on bodies built by hand,
// against answers worked out on paper: a falling box stopped by one row, rows that never pull, sticking
// and sliding friction (Coulomb's cone, maximum dissipation), four corners and a column of boxes by
// plain and accelerated sweeps, conservation of momentum, and rows that move one side only.
#include "contact/contact_cache.hpp"
#include "dynamics/contact_solver.hpp"
#include "support/solver_bodies.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

namespace impulse
{
namespace
{

using test::BoxBody;
using test::rowAt;
using test::slip;
using test::staticSide;

// Velocities of 1 m/s on bodies of about a kilogram and a metre, changed by a handful of products
// and one division: 1e-12 is round-off with room to spare.
constexpr Real kTol = 1e-12;

// the ground: a static body with no velocity, its surface z = 0
SolverBody ground()
{
    return SolverBody{};
}

// one step of 10 ms, contacts within a centimetre
const RowSettings kSettings{0.01, 0.01};

TEST(ContactSolver, ARowStopsABodyFallingOntoTheGroundUnderItsCentre)
{
    BoxBody box;
    box.mass = 2.0;
    box.centre = Vec3(0.0, 0.0, 0.5);
    box.velocity = Vec3(0.0, 0.0, -1.0);
    std::vector<SolverBody> bodies = {box.solver(), ground()};
    ContactRow row = rowAt(box.side(0), staticSide(1), Vec3::Zero(), Vec3::UnitZ(), 0.5);
    const Real changed = solveRow(row, bodies, kSettings);
    EXPECT_NEAR(row.relativeVelocity(0, bodies[0], bodies[1]), 0.0, kTol) << "the target, bias 0";
    EXPECT_NEAR(row.lambda[0], box.mass * 1.0, kTol) << "the impulse that stops m at 1 m/s";
    EXPECT_NEAR(changed, 1.0, kTol) << "the normal velocity changed by 1 m/s";
    EXPECT_EQ(row.lambda[1], 0.0);
    EXPECT_EQ(row.lambda[2], 0.0);
    // under the centre: no lever arm, so no turn
    EXPECT_LT(bodies[0].angularVelocity.norm(), kTol);
    EXPECT_LT(bodies[0].linearVelocity.norm(), kTol);
    // the ground does not move
    EXPECT_EQ(bodies[1].linearVelocity, Vec3::Zero());
}

TEST(ContactSolver, ARowMeetsItsBiasWhenOneIsGiven)
{
    BoxBody box;
    box.centre = Vec3(0.0, 0.0, 0.5);
    box.velocity = Vec3(0.0, 0.0, -1.0);
    std::vector<SolverBody> bodies = {box.solver(), ground()};
    ContactRow row = rowAt(box.side(0), staticSide(1), Vec3::Zero(), Vec3::UnitZ(), 0.5);
    row.bias = 0.3; // a bounce: leave at 0.3 m/s
    solveRow(row, bodies, kSettings);
    EXPECT_NEAR(row.relativeVelocity(0, bodies[0], bodies[1]), 0.3, kTol);
    EXPECT_NEAR(row.lambda[0], box.mass * 1.3, kTol);
}

TEST(ContactSolver, ARowNeverPullsASeparatingBody)
{
    BoxBody box;
    box.centre = Vec3(0.0, 0.0, 0.5);
    box.velocity = Vec3(0.3, 0.0, 1.0); // leaving the ground
    std::vector<SolverBody> bodies = {box.solver(), ground()};
    ContactRow row = rowAt(box.side(0), staticSide(1), Vec3::Zero(), Vec3::UnitZ(), 0.5);
    // in play whatever its normal velocity: a thickness larger than anything the lookahead gives
    const RowSettings inPlay{0.01, 1.0};
    EXPECT_EQ(solveRow(row, bodies, inPlay), 0.0);
    EXPECT_EQ(row.lambda[0], 0.0);
    EXPECT_EQ(row.lambda[1], 0.0) << "no friction without a normal load";
    EXPECT_EQ(bodies[0].linearVelocity, box.velocity);
    EXPECT_EQ(bodies[0].angularVelocity, Vec3::Zero());
}

TEST(ContactSolver, ARowLetsGoOfTheLoadItCarriedWhenItsBodySeparates)
{
    BoxBody box;
    box.centre = Vec3(0.0, 0.0, 0.5);
    box.velocity = Vec3(0.0, 0.0, 1.0);
    std::vector<SolverBody> bodies = {box.solver(), ground()};
    ContactRow row = rowAt(box.side(0), staticSide(1), Vec3::Zero(), Vec3::UnitZ(), 0.5);
    // it carried 0.4 N s (a warm start already in the velocity): taking back all of it still leaves the
    // body separating, at 1 - 0.4 / m, and nothing more may be taken
    row.lambda[0] = 0.4;
    solveRow(row, bodies, kSettings);
    EXPECT_EQ(row.lambda[0], 0.0);
    EXPECT_NEAR(bodies[0].linearVelocity.z(), 1.0 - 0.4 / box.mass, kTol);
}

TEST(ContactSolver, FrictionHoldsASlidingBoxWhenMuIsLargeEnough)
{
    BoxBody box;
    box.centre = Vec3(0.0, 0.0, 0.5);
    box.velocity = Vec3(0.2, -0.1, -1.0);
    std::vector<SolverBody> bodies = {box.solver(), ground()};
    ContactRow row = rowAt(box.side(0), staticSide(1), Vec3::Zero(), Vec3::UnitZ(), 1.0);
    solveRow(row, bodies, kSettings);
    EXPECT_NEAR(row.relativeVelocity(0, bodies[0], bodies[1]), 0.0, kTol);
    EXPECT_LT(slip(row, bodies[0], bodies[1]).norm(), kTol) << "sticks";
    const Real friction = std::hypot(row.lambda[1], row.lambda[2]);
    EXPECT_GT(friction, 0.0);
    EXPECT_LE(friction, row.friction * row.lambda[0]) << "inside the cone";
}

TEST(ContactSolver, SlidingFrictionIsMuTimesTheNormalAndOpposesTheSlip)
{
    // a cube sliding along x: the stick impulse (1 m/s over the compliance 1/m + h^2/I = 2.5/m) is
    // 0.4 m, beyond mu N = 0.1 m, so it slides
    BoxBody box;
    box.centre = Vec3(0.0, 0.0, 0.5);
    box.velocity = Vec3(1.0, 0.0, -1.0);
    std::vector<SolverBody> bodies = {box.solver(), ground()};
    ContactRow row = rowAt(box.side(0), staticSide(1), Vec3::Zero(), Vec3::UnitZ(), 0.1);
    solveRow(row, bodies, kSettings);
    EXPECT_NEAR(row.lambda[0], box.mass, kTol);
    const Vec3 force = row.lambda[1] * row.direction[1] + row.lambda[2] * row.direction[2];
    // on the cone's edge, to 1e-12 relative (the projection ends with an exact rescaling)
    EXPECT_NEAR(force.norm(), row.friction * row.lambda[0], kTol * row.lambda[0]);
    // the cube's response is the same along x and y here, so friction opposes the slip before and after
    EXPECT_LT((force.normalized() + Vec3::UnitX()).norm(), kTol);
    const Vec3 after = slip(row, bodies[0], bodies[1]);
    EXPECT_NEAR(after.x(), 1.0 - 0.1 * 2.5, kTol) << "slowed by mu N times the compliance";
    EXPECT_NEAR(after.y(), 0.0, kTol);
}

TEST(ContactSolver, SlidingFrictionOpposesTheSlipItLeavesWhereTheBoxRespondsUnevenly)
{
    // a flat, long box: its point under the centre gives way more along one tangent than the other,
    // so the friction of most dissipation opposes the slip left after it, not the slip before
    BoxBody box;
    box.half = Vec3(0.8, 0.2, 0.3);
    box.centre = Vec3(0.0, 0.0, 0.3);
    box.velocity = Vec3(1.0, 1.0, -1.0);
    std::vector<SolverBody> bodies = {box.solver(), ground()};
    ContactRow row = rowAt(box.side(0), staticSide(1), Vec3::Zero(), Vec3::UnitZ(), 0.1);
    // the premise: the tangent block is far from isotropic
    ASSERT_GT(std::abs(row.compliance[1] - row.compliance[3]), 0.1 * row.compliance[1]);
    const Vec3 before = slip(row, bodies[0], bodies[1]);
    solveRow(row, bodies, kSettings);
    const Vec3 force = row.lambda[1] * row.direction[1] + row.lambda[2] * row.direction[2];
    const Vec3 after = slip(row, bodies[0], bodies[1]);
    EXPECT_NEAR(force.norm(), row.friction * row.lambda[0], kTol * row.lambda[0]) << "on the cone's edge";
    ASSERT_GT(after.norm(), 0.1) << "still sliding";
    // antiparallel: Newton on the cone's edge stops at 1e-13 relative; 1e-9 leaves room for that and
    // still sees the turn of a clamp in the plain metric (the angle between the slips before and after)
    EXPECT_LT(force.normalized().cross(after.normalized()).norm(), 1e-9);
    EXPECT_LT(force.dot(after), 0.0);
    EXPECT_GT(before.normalized().cross(after.normalized()).norm(), 1e-2) << "the check above can tell";
}

TEST(ContactSolver, SlidingFrictionIsOnTheConeAndOpposesTheSlipForBoxesOfEveryShapeAndPoint)
{
    // boxes from thin plates to long bars, touching the ground at a point anywhere under them and
    // sliding every way: the tangent block ranges from isotropic to a thousand to one, and wherever the
    // point slides its friction is mu times its load and antiparallel to the slip it leaves
    std::mt19937_64 random(7);
    std::uniform_real_distribution<Real> unit(-1.0, 1.0);
    std::uniform_real_distribution<Real> logSide(std::log(0.01), std::log(1.0));
    int sliding = 0;
    int anisotropic = 0;
    for (int trial = 0; trial < 2000; ++trial)
    {
        BoxBody box;
        box.half = Vec3(std::exp(logSide(random)), std::exp(logSide(random)), std::exp(logSide(random)));
        box.centre = Vec3(0.0, 0.0, box.half.z());
        box.velocity = Vec3(unit(random), unit(random), -std::abs(unit(random)));
        box.spin = Vec3(unit(random), unit(random), unit(random));
        std::vector<SolverBody> bodies = {box.solver(), ground()};
        const Vec3 point(box.half.x() * unit(random), box.half.y() * unit(random), 0.0);
        ContactRow row = rowAt(box.side(0), staticSide(1), point, Vec3::UnitZ(), 0.05 + 0.5 * std::abs(unit(random)));
        solveRow(row, bodies, kSettings);
        const Vec3 force = row.lambda[1] * row.direction[1] + row.lambda[2] * row.direction[2];
        const Vec3 after = slip(row, bodies[0], bodies[1]);
        if (row.lambda[0] == 0.0)
        {
            continue; // the spin lifts the point: nothing to hold
        }
        ASSERT_LE(force.norm(), row.friction * row.lambda[0] * (1.0 + kTol)) << "trial " << trial;
        if (after.norm() < 1e-9)
        {
            continue; // it sticks
        }
        ++sliding;
        const std::array<Real, 6>& k = row.compliance;
        anisotropic += std::abs(k[1] - k[3]) + 2.0 * std::abs(k[2]) > 0.5 * (k[1] + k[3]) ? 1 : 0;
        EXPECT_NEAR(force.norm(), row.friction * row.lambda[0], kTol * row.lambda[0]) << "trial " << trial;
        EXPECT_LT(force.normalized().cross(after.normalized()).norm(), 1e-9) << "trial " << trial;
        EXPECT_LT(force.dot(after), 0.0) << "trial " << trial;
    }
    // the checks above ran on many sliding points, many of them far from isotropic
    EXPECT_GT(sliding, 500);
    EXPECT_GT(anisotropic, 100);
}

// A unit cube of 2 kg on four corner rows, falling at 1 m/s.
struct CornerPatch
{
    BoxBody box;
    std::vector<SolverBody> bodies;
    std::vector<ContactRow> rows;

    CornerPatch()
    {
        box.mass = 2.0;
        box.centre = Vec3(0.0, 0.0, 0.5);
        box.velocity = Vec3(0.0, 0.0, -1.0);
        bodies = {box.solver(), ground()};
        for (const Real x : {-0.5, 0.5})
        {
            for (const Real y : {-0.5, 0.5})
            {
                rows.push_back(rowAt(box.side(0), staticSide(1), Vec3(x, y, 0.0), Vec3::UnitZ(), 0.5));
            }
        }
    }
};

TEST(ContactSolver, FourCornerRowsStopAFallingBoxWithPlainAndAcceleratedSweeps)
{
    for (const Sweeps kind : {Sweeps::Plain, Sweeps::Accelerated})
    {
        SCOPED_TRACE(kind == Sweeps::Plain ? "plain" : "accelerated");
        CornerPatch patch;
        SolverScratch scratch;
        const int sweeps = solveRows(patch.rows, patch.bodies, kSettings, 10000, 1e-10, kind, scratch);
        ASSERT_LT(sweeps, 10000) << "converged";
        // the sweeps stop when one changes no point's velocity by 1e-10 m/s; what is left is bounded by
        // the resolution the contact passes work to, a millionth of the 1 m/s approach
        Real total = 0.0;
        for (const ContactRow& row : patch.rows)
        {
            EXPECT_GE(row.relativeVelocity(0, patch.bodies[0], patch.bodies[1]), -kSolverResolution);
            EXPECT_GE(row.lambda[0], 0.0);
            total += row.lambda[0];
        }
        // momentum: the impulses add up to what stops 2 kg at 1 m/s
        EXPECT_NEAR(total, patch.box.mass * 1.0, patch.box.mass * kSolverResolution);
        // the box is symmetric under its corners: it stops without turning
        EXPECT_LT(patch.bodies[0].angularVelocity.norm() * patch.bodies[0].reach, kSolverResolution);
        EXPECT_LT(patch.bodies[0].linearVelocity.norm(), kSolverResolution);
    }
}

// A column of unit cubes on the ground, the upper ones falling faster, with four corner rows under
// each; the rows go from the ground up. Whatever the sweeps, the only answer is that all of it stops.
struct Column
{
    static constexpr int kBoxes = 10;
    std::vector<SolverBody> bodies;
    std::vector<ContactRow> rows;

    Column()
    {
        bodies.push_back(ground()); // body 0
        std::vector<BoxBody> boxes;
        for (int i = 0; i < kBoxes; ++i)
        {
            BoxBody box;
            box.centre = Vec3(0.0, 0.0, 0.5 + i);
            box.velocity = Vec3(0.0, 0.0, -1.0 - 0.1 * i);
            boxes.push_back(box);
            bodies.push_back(box.solver());
        }
        for (int i = 0; i < kBoxes; ++i)
        {
            const auto above = static_cast<std::uint32_t>(i + 1);
            const RowSide below = i == 0 ? staticSide(0) : boxes[static_cast<std::size_t>(i - 1)].side(above - 1);
            for (const Real x : {-0.5, 0.5})
            {
                for (const Real y : {-0.5, 0.5})
                {
                    rows.push_back(rowAt(boxes[static_cast<std::size_t>(i)].side(above), below,
                                         Vec3(x, y, static_cast<Real>(i)), Vec3::UnitZ(), 0.5));
                }
            }
        }
    }
};

TEST(ContactSolver, AcceleratedSweepsSettleATallColumnInFewerSweepsThanPlain)
{
    constexpr int kMaxSweeps = 100000;
    constexpr Real kTolerance = 1e-10;
    int sweeps[2] = {0, 0};
    for (const Sweeps kind : {Sweeps::Plain, Sweeps::Accelerated})
    {
        SCOPED_TRACE(kind == Sweeps::Plain ? "plain" : "accelerated");
        Column column;
        SolverScratch scratch;
        const int run = solveRows(column.rows, column.bodies, kSettings, kMaxSweeps, kTolerance, kind, scratch);
        ASSERT_LT(run, kMaxSweeps) << "converged";
        sweeps[kind == Sweeps::Plain ? 0 : 1] = run;
        // the same answer, to the resolution the contact passes work to (the approaches are 1 to 2 m/s)
        for (std::size_t i = 1; i < column.bodies.size(); ++i)
        {
            EXPECT_LT(column.bodies[i].linearVelocity.norm(), kSolverResolution) << "box " << i;
            EXPECT_LT(column.bodies[i].angularVelocity.norm() * column.bodies[i].reach, kSolverResolution);
        }
        for (const ContactRow& row : column.rows)
        {
            EXPECT_GE(row.relativeVelocity(0, column.bodies[row.a], column.bodies[row.b]), -kSolverResolution);
        }
    }
    // a tall column is what the acceleration is for: it must take fewer sweeps, not merely as many
    // (an acceleration that did nothing would tie)
    EXPECT_LT(sweeps[1], sweeps[0]) << "plain " << sweeps[0] << ", accelerated " << sweeps[1];
}

TEST(ContactSolver, ImpulsesOnTwoDynamicBodiesConserveTheirMomentum)
{
    BoxBody lower;
    lower.mass = 3.0;
    lower.half = Vec3(1.0, 0.7, 0.4);
    lower.centre = Vec3(0.1, -0.2, 0.4);
    lower.velocity = Vec3(0.1, 0.2, 0.3);
    lower.spin = Vec3(0.4, -0.1, 0.2);
    BoxBody upper;
    upper.mass = 0.7;
    upper.half = Vec3(0.3, 0.2, 0.25);
    upper.centre = Vec3(0.3, 0.1, 1.05);
    upper.velocity = Vec3(-0.2, 0.1, -1.5);
    upper.spin = Vec3(-0.3, 0.5, 0.1);
    std::vector<SolverBody> bodies = {upper.solver(), lower.solver()};
    const std::vector<Vec3> centres = {upper.centre, lower.centre};
    const Vec3 linear = upper.mass * bodies[0].linearVelocity + lower.mass * bodies[1].linearVelocity;
    const Vec3 angular = test::angularMomentumAboutOrigin(bodies, centres);
    const auto expectConserved = [&]
    {
        EXPECT_LT((upper.mass * bodies[0].linearVelocity + lower.mass * bodies[1].linearVelocity - linear).norm(),
                  kTol);
        EXPECT_LT((test::angularMomentumAboutOrigin(bodies, centres) - angular).norm(), kTol);
    };
    // an off-centre point with a tilted normal, from the lower body toward the upper
    const Vec3 point(0.45, 0.2, 0.8);
    const Vec3 normal = Vec3(0.1, -0.2, 1.0).normalized();

    // a visit of a frictionless row: its normal velocity meets the target (with friction, the tangential
    // impulses that follow would move it again through the lever arms)
    ContactRow frictionless = rowAt(upper.side(0), lower.side(1), point, normal, 0.0);
    ASSERT_LT(frictionless.relativeVelocity(0, bodies[0], bodies[1]), -1.0) << "the premise: approaching";
    solveRow(frictionless, bodies, kSettings);
    EXPECT_NEAR(frictionless.relativeVelocity(0, bodies[0], bodies[1]), 0.0, kTol);
    EXPECT_GT(frictionless.lambda[0], 0.0);
    expectConserved();

    // impulses along every direction of a row with friction
    const ContactRow row = rowAt(upper.side(0), lower.side(1), point, normal, 0.6);
    const Vec3 upperBefore = bodies[0].linearVelocity;
    applyImpulses(row, 1.3, -0.4, 0.7, bodies[0], bodies[1]);
    EXPECT_GT((bodies[0].linearVelocity - upperBefore).norm(), 0.1) << "the impulses did something";
    expectConserved();
}

TEST(ContactSolver, ARowThatMovesOnlyALeavesBUntouched)
{
    BoxBody lower;
    lower.mass = 3.0;
    lower.half = Vec3(1.0, 1.0, 0.5);
    lower.velocity = Vec3(0.1, 0.0, 0.5);
    lower.spin = Vec3(0.0, 0.2, 0.0);
    BoxBody upper;
    upper.centre = Vec3(0.2, 0.1, 1.0);
    upper.velocity = Vec3(0.0, 0.0, -1.0);
    std::vector<SolverBody> bodies = {upper.solver(), lower.solver()};
    const SolverBody before = bodies[1];
    // under A's centre, so that A's response couples no friction into the normal: one visit meets the
    // target exactly, while B (sliding and turning) makes friction act
    ContactRow row = rowAt(upper.side(0), lower.side(1), Vec3(0.2, 0.1, 0.5), Vec3::UnitZ(), 0.5);
    setMovable(row, kMovesA);
    // the effective mass is A's alone
    EXPECT_EQ(row.normalMass, 1.0 / row.complianceA[0]);
    solveRow(row, bodies, kSettings);
    EXPECT_NEAR(row.relativeVelocity(0, bodies[0], bodies[1]), 0.0, kTol);
    EXPECT_GT(row.lambda[0], 0.0);
    EXPECT_GT(std::hypot(row.lambda[1], row.lambda[2]), 0.0);
    EXPECT_EQ(bodies[1].linearVelocity, before.linearVelocity);
    EXPECT_EQ(bodies[1].angularVelocity, before.angularVelocity);
    EXPECT_EQ(bodies[1].angularMomentum, before.angularMomentum);
}

} // namespace
} // namespace impulse
