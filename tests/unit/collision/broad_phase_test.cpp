// SPDX-License-Identifier: MIT
// The broad phase against the definition of its result: every pair of bodies whose grown boxes
// overlap, found by comparing all pairs, for bodies of very different sizes, far apart, touching
// in several cells at once, static and planar, each grown by a margin of its own.
#include "collision/broad_phase.hpp"

#include <impulse/impulse.hpp>

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

namespace impulse
{
namespace
{

// A body of a test: its shape, its pose now and next, and the margin its box is grown by.
struct Proxy
{
    Shape shape;
    Pose now;
    Pose next;
    bool dynamic = false;
    Real margin = 0.0;
};

Proxy makeBody(const Shape& shape, const Vec3& position, const Quat& orientation, bool dynamic, Real margin = 0.0)
{
    const Pose pose = Pose::from(position, orientation);
    return {shape, pose, pose, dynamic, dynamic ? margin : 0.0};
}

std::vector<BroadPhaseBody> asSeen(const std::vector<Proxy>& bodies)
{
    std::vector<BroadPhaseBody> seen;
    for (const Proxy& body : bodies)
    {
        seen.push_back(
            {&body.shape, body.now, body.next, impulse::boundingRadius(body.shape), body.margin, body.dynamic, true});
    }
    return seen;
}

bool overlap(const Aabb& l, const Aabb& r)
{
    return (l.lower.array() <= r.upper.array()).all() && (r.lower.array() <= l.upper.array()).all();
}

// every pair by the definition: boxes over both poses, each grown by its margin, overlap, at least
// one body dynamic; planes pair with dynamic bodies whose bounding sphere comes within their margin.
// With `of`, only the pairs with a body it marks.
std::vector<std::pair<std::uint32_t, std::uint32_t>> allPairs(const std::vector<Proxy>& bodies,
                                                              const std::vector<bool>& of = {})
{
    std::vector<std::pair<std::uint32_t, std::uint32_t>> pairs;
    const auto grown = [&](const Proxy& body)
    {
        const Aabb now = shapeBounds(body.shape, body.now);
        const Aabb next = shapeBounds(body.shape, body.next);
        return Aabb{now.lower.cwiseMin(next.lower).array() - body.margin,
                    now.upper.cwiseMax(next.upper).array() + body.margin};
    };
    for (std::uint32_t i = 0; i < bodies.size(); ++i)
    {
        for (std::uint32_t j = i + 1; j < bodies.size(); ++j)
        {
            const Proxy& a = bodies[i];
            const Proxy& b = bodies[j];
            if ((!a.dynamic && !b.dynamic) || (!of.empty() && !of[i] && !of[j]))
            {
                continue;
            }
            const bool planeA = std::holds_alternative<Plane>(a.shape);
            const bool planeB = std::holds_alternative<Plane>(b.shape);
            if (planeA || planeB)
            {
                const Proxy& body = planeA ? b : a;
                const Real height = std::min(body.now.position.z(), body.next.position.z());
                if (height - impulse::boundingRadius(body.shape) <= body.margin)
                {
                    pairs.emplace_back(i, j);
                }
                continue;
            }
            if (overlap(grown(a), grown(b)))
            {
                pairs.emplace_back(i, j);
            }
        }
    }
    return pairs;
}

// A wall and a plane, and 300 bodies: mostly small in a 3 m cube, some ten times larger, a few far
// away (in odd trials so far that the cells count past what the broad phase packs into one sort key),
// each with a margin of its own (a few much larger than the rest: a fast body among slow ones).
std::vector<Proxy> randomScene(std::mt19937_64& random, int trial)
{
    std::uniform_real_distribution<Real> unit(0.0, 1.0);
    std::vector<Proxy> bodies;
    bodies.push_back(makeBody(Plane{}, Vec3::Zero(), Quat::Identity(), false));
    bodies.push_back(makeBody(Box{Vec3(0.1, 2.0, 1.0)}, Vec3(2.1, 0, 1), Quat::Identity(), false)); // a wall
    for (int k = 0; k < 300; ++k)
    {
        const Real size = unit(random) < 0.1 ? 0.5 + unit(random) : 0.02 + 0.1 * unit(random);
        Vec3 position(3.0 * unit(random) - 1.0, 3.0 * unit(random) - 1.5, 3.0 * unit(random));
        if (k % 50 == 0)
        {
            position *= trial % 2 == 0 ? 1e4 : 1e8;
        }
        const Quat orientation = Quat(Eigen::Vector4d::Random()).normalized();
        const Shape shape = k % 2 == 0 ? Shape{Sphere{size}} : Shape{Box{Vec3(size, 0.5 * size, 0.3 * size)}};
        const Real margin = unit(random) < 0.05 ? 0.2 * unit(random) : 0.01 * unit(random);
        Proxy body = makeBody(shape, position, orientation, true, margin);
        body.next.position += Vec3(0.0, 0.0, -0.05 * unit(random)); // moving down this step
        bodies.push_back(body);
    }
    return bodies;
}

TEST(BroadPhase, FindsExactlyThePairsWhoseBoxesOverlap)
{
    std::mt19937_64 random(7);
    for (int trial = 0; trial < 20; ++trial)
    {
        const std::vector<Proxy> bodies = randomScene(random, trial);
        BroadPhase broadPhase;
        std::vector<BodyPair> found;
        broadPhase.findPairs(asSeen(bodies), 1, found);
        const auto expected = allPairs(bodies);
        ASSERT_EQ(found.size(), expected.size()) << "trial " << trial;
        for (std::size_t n = 0; n < found.size(); ++n)
        {
            EXPECT_EQ(found[n].a, expected[n].first) << "trial " << trial << ", pair " << n;
            EXPECT_EQ(found[n].b, expected[n].second) << "trial " << trial << ", pair " << n;
        }
        EXPECT_GT(expected.size(), 300u) << "trial " << trial << ": too few pairs to say anything";

        // again with the same broad phase (its sorting storage reused) on two threads: the same
        // pairs in the same order
        std::vector<BodyPair> threaded;
        broadPhase.findPairs(asSeen(bodies), 2, threaded);
        ASSERT_EQ(threaded.size(), found.size());
        for (std::size_t n = 0; n < found.size(); ++n)
        {
            EXPECT_EQ(threaded[n].a, found[n].a) << "trial " << trial << ", pair " << n;
            EXPECT_EQ(threaded[n].b, found[n].b) << "trial " << trial << ", pair " << n;
        }
    }
}

TEST(BroadPhase, FindsThePairsOfMovedBodiesAsAComparisonOfAllPairsDoes)
{
    // After findPairs, rounds of bodies sped up (a new pose ahead, a larger margin, some far beyond
    // the grid's cells): findPairsOf must give every pair of a body moved in the round, against the
    // boxes every body has now, including the bodies moved in earlier rounds.
    std::mt19937_64 random(13);
    std::uniform_real_distribution<Real> unit(0.0, 1.0);
    int checked = 0;
    for (int trial = 0; trial < 10; ++trial)
    {
        std::vector<Proxy> bodies = randomScene(random, trial);
        BroadPhase broadPhase;
        std::vector<BodyPair> found;
        broadPhase.findPairs(asSeen(bodies), 1, found);
        for (int round = 0; round < 3; ++round)
        {
            std::vector<std::uint32_t> moved;
            std::vector<bool> isMoved(bodies.size(), false);
            for (std::uint32_t i = 2; i < bodies.size(); ++i)
            {
                if (unit(random) < 0.15)
                {
                    const Real reach = unit(random) < 0.1 ? 3.0 : 0.3;
                    bodies[i].next.position += reach * Vec3(unit(random) - 0.5, unit(random) - 0.5, -unit(random));
                    bodies[i].margin += 0.05 * unit(random);
                    moved.push_back(i);
                    isMoved[i] = true;
                }
            }
            std::vector<BodyPair> added;
            broadPhase.findPairsOf(asSeen(bodies), moved, added);
            const auto expected = allPairs(bodies, isMoved);
            ASSERT_EQ(added.size(), expected.size()) << "trial " << trial << ", round " << round;
            for (std::size_t n = 0; n < added.size(); ++n)
            {
                EXPECT_EQ(added[n].a, expected[n].first) << "trial " << trial << ", round " << round;
                EXPECT_EQ(added[n].b, expected[n].second) << "trial " << trial << ", round " << round;
            }
            checked += static_cast<int>(expected.size());
        }
    }
    EXPECT_GT(checked, 1000) << "too few pairs to say anything";
}

TEST(BroadPhase, BoxesOfTheLargestSizeThatJustTouchArePaired)
{
    // The grid's cell is the largest box: the lower corners of two such boxes touching face to face
    // lie a whole cell apart, where round-off in the cell coordinates could put them two cells apart
    // and the pair would never be compared. Rows of touching cubes at arbitrary offsets and sizes.
    std::mt19937_64 random(11);
    std::uniform_real_distribution<Real> unit(0.0, 1.0);
    int touching = 0;
    for (int trial = 0; trial < 200; ++trial)
    {
        const Real half = 0.01 + unit(random);
        const Vec3 start(1e3 * (unit(random) - 0.5), 1e3 * (unit(random) - 0.5), 1e3 * (unit(random) - 0.5));
        const int axis = trial % 3;
        std::vector<Proxy> bodies;
        Real lower = start[axis] - half;
        for (int k = 0; k < 8; ++k)
        {
            // each cube's lower face is where the one before ends, to the last bit
            Vec3 centre = start;
            centre[axis] = lower + half;
            while (centre[axis] - half > lower)
            {
                centre[axis] = std::nextafter(centre[axis], -1e300); // no gap from rounding
            }
            Proxy body = makeBody(Box{Vec3::Constant(half)}, centre, Quat::Identity(), true);
            bodies.push_back(body);
            lower = shapeBounds(body.shape, body.now).upper[axis];
        }
        BroadPhase broadPhase;
        std::vector<BodyPair> found;
        broadPhase.findPairs(asSeen(bodies), 1, found);
        const auto expected = allPairs(bodies);
        ASSERT_EQ(found.size(), expected.size()) << "trial " << trial << ", half side " << half;
        for (std::size_t n = 0; n < found.size(); ++n)
        {
            EXPECT_EQ(found[n].a, expected[n].first) << "trial " << trial << ", pair " << n;
            EXPECT_EQ(found[n].b, expected[n].second) << "trial " << trial << ", pair " << n;
        }
        touching += static_cast<int>(expected.size());
    }
    EXPECT_GE(touching, 200 * 7) << "each cube should at least touch the next";
}

TEST(BroadPhase, NothingPairsWithNothingAndStaticBodiesNeverPairWithEachOther)
{
    std::vector<Proxy> bodies;
    BroadPhase broadPhase;
    std::vector<BodyPair> pairs;
    broadPhase.findPairs(asSeen(bodies), 1, pairs);
    EXPECT_TRUE(pairs.empty());
    bodies.push_back(makeBody(Plane{}, Vec3::Zero(), Quat::Identity(), false));
    bodies.push_back(makeBody(Box{Vec3(1, 1, 1)}, Vec3::Zero(), Quat::Identity(), false));
    bodies.push_back(makeBody(Box{Vec3(1, 1, 1)}, Vec3(0.5, 0, 0), Quat::Identity(), false));
    broadPhase.findPairs(asSeen(bodies), 1, pairs);
    EXPECT_TRUE(pairs.empty());
    bodies.push_back(makeBody(Sphere{0.1}, Vec3(0.3, 0, 0.05), Quat::Identity(), true, 0.01)); // on the plane
    broadPhase.findPairs(asSeen(bodies), 1, pairs);
    ASSERT_EQ(pairs.size(), 3u); // the plane and both boxes
}

} // namespace
} // namespace impulse
