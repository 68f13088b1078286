// SPDX-License-Identifier: MIT
// The contact layer's cache (contact_cache.hpp): a capture holds what the exact narrow phase finds,
// an entry answers for nearby poses without detection and is captured again past its reach, loads
// carry over by feature, entries follow the pair list, save/restore round-trips and refuses garbage,
// and the motion since capture bounds how far the points have moved.
#include "collision/narrow_phase.hpp"
#include "contact/contact_cache.hpp"
#include "geometry/box_queries.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>
#include <stdexcept>
#include <utility>
#include <variant>
#include <vector>

namespace impulse
{
namespace
{

// Anchors go through one toLocal and one toWorld: on metre-sized bodies that is round-off of a few
// 1e-16 m, so 1e-12 leaves room for nothing else.
constexpr Real kTol = 1e-12;
constexpr Real kThickness = 0.01; // m
constexpr Real kReach = 0.05;     // m

struct Pair
{
    std::uint32_t a;
    std::uint32_t b;
};

Quat rotation(Real angle, const Vec3& axis)
{
    return Quat(Eigen::AngleAxisd(angle, axis.normalized()));
}

PlacedShape placed(const Shape& shape, const Vec3& position, const Quat& orientation = Quat::Identity())
{
    return {&shape, Pose::from(position, orientation), boundingRadius(shape)};
}

std::vector<ContactPoint> exactPoints(const PlacedShape& a, const PlacedShape& b, Real threshold)
{
    std::vector<ContactPoint> out;
    NarrowPhaseScratch scratch;
    collideShapes(*a.shape, a.pose, *b.shape, b.pose, threshold, out, scratch);
    return out;
}

std::vector<ContactPoint> cachedPoints(const ContactCache& cache, std::size_t k, const PlacedShape& a,
                                       const PlacedShape& b)
{
    std::vector<ContactPoint> out;
    cache.entryPoints(k, a, b, out);
    return out;
}

const ContactPoint* withFeature(const std::vector<ContactPoint>& points, const ContactPoint& like)
{
    for (const ContactPoint& p : points)
    {
        if (p.feature == like.feature && p.sample == like.sample)
        {
            return &p;
        }
    }
    return nullptr;
}

// Every exact point has a cached one of its feature, at the same place, normal and separation.
void expectSamePoints(const std::vector<ContactPoint>& cached, const std::vector<ContactPoint>& exact)
{
    for (const ContactPoint& e : exact)
    {
        const ContactPoint* c = withFeature(cached, e);
        ASSERT_NE(c, nullptr) << "no cached point of feature " << e.feature;
        EXPECT_NEAR(c->phi, e.phi, kTol);
        EXPECT_LT((c->point - e.point).norm(), kTol);
        EXPECT_LT((c->normal - e.normal).norm(), kTol);
    }
}

const auto kNeverExact = [](std::uint32_t, std::uint32_t) { return false; };

// A unit cube (body 0) a few millimetres above the ground plane (body 1), turned about z and tilted a
// little about x, so that its four lower corners are at different heights within the capture threshold.
class ContactCacheBoxOnPlane : public ::testing::Test
{
  protected:
    Shape box = Box{Vec3::Constant(0.5)};
    Shape ground = Plane{Vec3::UnitZ(), 0.0};
    Quat turn = rotation(0.01, Vec3::UnitX()) * rotation(0.3, Vec3::UnitZ());
    Vec3 centre = Vec3(0.2, -0.1, 0.51);
    PlacedShape plane = placed(ground, Vec3::Zero());
    ContactCache cache;
    ContactScratch scratch;

    PlacedShape boxAt(const Vec3& shift, const Quat& extra = Quat::Identity()) const
    {
        return placed(box, centre + shift, extra * turn);
    }
    void SetUp() override
    {
        cache.follow(std::vector<Pair>{{0, 1}}, kNeverExact);
        ASSERT_TRUE(cache.refresh(0, boxAt(Vec3::Zero()), plane, kThickness, kReach, 0.0, scratch));
        cache.takeCounters();
    }
};

TEST_F(ContactCacheBoxOnPlane, ACaptureHoldsThePointsAndSeparationsOfTheExactNarrowPhase)
{
    const PlacedShape a = boxAt(Vec3::Zero());
    // captured with the threshold thickness + reach, the four lower corners
    const std::vector<ContactPoint> exact = exactPoints(a, plane, kThickness + kReach);
    ASSERT_EQ(exact.size(), 4u) << "the scene's premise: the lower corners only";
    const std::vector<ContactPoint> cached = cachedPoints(cache, 0, a, plane);
    ASSERT_EQ(cached.size(), exact.size());
    EXPECT_TRUE(cache.entry(0).captured);
    expectSamePoints(cached, exact);
}

TEST_F(ContactCacheBoxOnPlane, KeepsItsPointsWhileTheBoxMovesWithinItsReach)
{
    // down along the normal by less than the reach: no capture, and the corners' separations read from
    // the anchors are the exact ones (a corner's distance to a plane is linear in its translation)
    const PlacedShape a = boxAt(Vec3(0.0, 0.0, -0.4 * kReach));
    EXPECT_FALSE(cache.refresh(0, a, plane, kThickness, kReach, 0.0, scratch));
    EXPECT_EQ(cache.takeCounters().captures, 0);
    const std::vector<ContactPoint> cached = cachedPoints(cache, 0, a, plane);
    const std::vector<ContactPoint> exact = exactPoints(a, plane, std::numeric_limits<Real>::infinity());
    ASSERT_EQ(cached.size(), 4u);
    for (const ContactPoint& c : cached)
    {
        const ContactPoint* e = withFeature(exact, c);
        ASSERT_NE(e, nullptr);
        EXPECT_NEAR(c.phi, e->phi, kTol);
        EXPECT_LT((c.point - e->point).norm(), kTol);
    }
}

TEST_F(ContactCacheBoxOnPlane, ReadsSeparationsWithinTheMotionBoundAfterASmallTurn)
{
    // turned by 0.02 rad about a horizontal axis through the centre and shifted a little: the farthest
    // point moves about 0.017 m + the shift, within the reach
    const PlacedShape a = boxAt(Vec3(0.003, 0.0, -0.002), rotation(0.02, Vec3(1.0, 1.0, 0.0)));
    const Real motion = cache.motionSinceCapture(cache.entry(0), a, plane);
    ASSERT_GT(motion, 0.0);
    ASSERT_LT(motion, kReach);
    EXPECT_FALSE(cache.refresh(0, a, plane, kThickness, kReach, 0.0, scratch));
    const std::vector<ContactPoint> cached = cachedPoints(cache, 0, a, plane);
    const std::vector<ContactPoint> exact = exactPoints(a, plane, std::numeric_limits<Real>::infinity());
    for (const ContactPoint& c : cached)
    {
        const ContactPoint* e = withFeature(exact, c);
        ASSERT_NE(e, nullptr);
        // the header's promise: off by no more than twice the motion since capture (a corner against a
        // plane is a material point and in fact reads exactly; this is the bound any point must keep)
        EXPECT_LE(std::abs(c.phi - e->phi), 2.0 * motion);
    }
    // and every exact point within the thickness is among the cached ones
    for (const ContactPoint& e : exactPoints(a, plane, kThickness))
    {
        EXPECT_NE(withFeature(cached, e), nullptr) << "missed feature " << e.feature;
    }
}

TEST_F(ContactCacheBoxOnPlane, CapturesAnewOnceTheBoxMovesPastItsReach)
{
    const PlacedShape a = boxAt(Vec3(1.5 * kReach, 0.0, 0.0));
    ASSERT_GT(cache.motionSinceCapture(cache.entry(0), a, plane), kReach);
    EXPECT_TRUE(cache.refresh(0, a, plane, kThickness, kReach, 0.0, scratch));
    EXPECT_EQ(cache.takeCounters().captures, 1);
    EXPECT_LE(cache.motionSinceCapture(cache.entry(0), a, plane), kTol) << "captured here";
    const std::vector<ContactPoint> cached = cachedPoints(cache, 0, a, plane);
    const std::vector<ContactPoint> exact = exactPoints(a, plane, kThickness + kReach);
    ASSERT_EQ(cached.size(), exact.size());
    for (const ContactPoint& e : exact)
    {
        const ContactPoint* c = withFeature(cached, e);
        ASSERT_NE(c, nullptr);
        EXPECT_LT((c->point - e.point).norm(), kTol) << "anchored at the new pose";
    }
}

TEST_F(ContactCacheBoxOnPlane, TheSpareDistanceAskedForCountsAgainstTheReach)
{
    // moved by 0.4 reach: kept with nothing spare, captured when 0.7 reach more is asked for
    const PlacedShape a = boxAt(Vec3(0.0, 0.4 * kReach, 0.0));
    EXPECT_FALSE(cache.refresh(0, a, plane, kThickness, kReach, 0.0, scratch));
    EXPECT_TRUE(cache.refresh(0, a, plane, kThickness, kReach, 0.7 * kReach, scratch));
    // a capture covers at least twice the spare distance
    EXPECT_GE(cache.entry(0).reach, 1.4 * kReach);
}

TEST_F(ContactCacheBoxOnPlane, LoadsSurviveARecaptureOnTheSameFeatures)
{
    // distinct loads per corner, so that a load handed to the wrong corner shows
    for (std::size_t i = 0; i < cache.entry(0).points.size(); ++i)
    {
        CachedPoint& point = cache.entry(0).points[i];
        point.load.normal = 1.0 + static_cast<Real>(i);
        point.load.tangent1 = 0.1 * static_cast<Real>(i) - 0.15;
        point.load.tangent2 = 0.05 + 0.02 * static_cast<Real>(i);
    }
    const std::vector<CachedPoint> before = cache.entry(0).points;
    // a translation past the reach: the same four corners are found again
    const PlacedShape a = boxAt(Vec3(2.0 * kReach, -kReach, 0.0));
    ASSERT_TRUE(cache.refresh(0, a, plane, kThickness, kReach, 0.0, scratch));
    const std::vector<CachedPoint>& after = cache.entry(0).points;
    ASSERT_EQ(after.size(), before.size());
    for (const CachedPoint& old : before)
    {
        const CachedPoint* now = nullptr;
        for (const CachedPoint& p : after)
        {
            if (p.feature == old.feature && p.sample == old.sample)
            {
                now = &p;
            }
        }
        ASSERT_NE(now, nullptr) << "feature " << old.feature << " not found again";
        EXPECT_EQ(now->load.normal, old.load.normal);
        // the tangents go to the world and back into the same basis (the plane's normal is unchanged)
        EXPECT_NEAR(now->load.tangent1, old.load.tangent1, kTol);
        EXPECT_NEAR(now->load.tangent2, old.load.tangent2, kTol);
    }
}

TEST(ContactCache, FollowKeepsTheEntriesOfPairsStillListedAndDropsTheRest)
{
    const Shape box = Box{Vec3::Constant(0.5)};
    const Shape ground = Plane{Vec3::UnitZ(), 0.0};
    const PlacedShape first = placed(box, Vec3(0.0, 0.0, 0.5));
    const PlacedShape second = placed(box, Vec3(3.0, 0.0, 0.5));
    const PlacedShape plane = placed(ground, Vec3::Zero());
    ContactCache cache;
    ContactScratch scratch;
    cache.follow(std::vector<Pair>{{0, 2}, {1, 2}}, kNeverExact);
    ASSERT_EQ(cache.size(), 2u);
    cache.refresh(0, first, plane, kThickness, kReach, 0.0, scratch);
    cache.refresh(1, second, plane, kThickness, kReach, 0.0, scratch);
    ASSERT_FALSE(cache.entry(0).points.empty());
    ASSERT_FALSE(cache.entry(1).points.empty());
    for (std::size_t k = 0; k < 2; ++k)
    {
        for (CachedPoint& point : cache.entry(k).points)
        {
            point.load.normal = 10.0 * static_cast<Real>(k + 1);
        }
    }
    const std::vector<CachedPoint> kept = cache.entry(1).points;

    // only (1, 2) listed: its entry stays, with its points and loads
    cache.follow(std::vector<Pair>{{1, 2}}, kNeverExact);
    ASSERT_EQ(cache.size(), 1u);
    EXPECT_EQ(cache.entry(0).a, 1u);
    EXPECT_EQ(cache.entry(0).b, 2u);
    EXPECT_TRUE(cache.entry(0).captured);
    ASSERT_EQ(cache.entry(0).points.size(), kept.size());
    for (std::size_t i = 0; i < kept.size(); ++i)
    {
        EXPECT_EQ(cache.entry(0).points[i].feature, kept[i].feature);
        EXPECT_EQ(cache.entry(0).points[i].load.normal, 20.0);
    }
    EXPECT_FALSE(cache.refresh(0, second, plane, kThickness, kReach, 0.0, scratch)) << "still valid there";

    // (0, 2) back: it starts empty, its old loads gone, and (1, 2) keeps its own
    cache.follow(std::vector<Pair>{{0, 2}, {1, 2}}, kNeverExact);
    ASSERT_EQ(cache.size(), 2u);
    EXPECT_EQ(cache.entry(0).a, 0u);
    EXPECT_FALSE(cache.entry(0).captured);
    EXPECT_TRUE(cache.entry(0).points.empty());
    EXPECT_EQ(cache.motionSinceCapture(cache.entry(0), first, plane), std::numeric_limits<Real>::infinity());
    EXPECT_EQ(cache.entry(1).a, 1u);
    ASSERT_EQ(cache.entry(1).points.size(), kept.size());
    EXPECT_EQ(cache.entry(1).points[0].load.normal, 20.0);
    EXPECT_TRUE(cache.refresh(0, first, plane, kThickness, kReach, 0.0, scratch));
    for (const CachedPoint& point : cache.entry(0).points)
    {
        EXPECT_EQ(point.load.normal, 0.0) << "a dropped entry's load came back";
    }
}

std::vector<std::uint64_t> bits(const std::vector<double>& numbers)
{
    std::vector<std::uint64_t> out;
    for (const double x : numbers)
    {
        out.push_back(std::bit_cast<std::uint64_t>(x));
    }
    return out;
}

// Two boxes on the ground, a small one turned about z on top of a larger one, captured, with loads and the
// conjugate-gradient state set to numbers that are not round.
class ContactCacheBoxOnBox : public ::testing::Test
{
  protected:
    Shape small = Box{Vec3(0.3, 0.2, 0.1)};
    Shape large = Box{Vec3::Constant(1.0)};
    Shape ground = Plane{Vec3::UnitZ(), 0.0};
    PlacedShape top = placed(small, Vec3(0.1, 0.2, 2.1005), rotation(0.4, Vec3::UnitZ()));
    PlacedShape bottom = placed(large, Vec3(0.0, 0.0, 1.0));
    PlacedShape plane = placed(ground, Vec3::Zero());
    ContactCache cache;
    ContactScratch scratch;

    void SetUp() override
    {
        // bodies: 0 the small box, 1 the large box, 2 the ground
        cache.follow(std::vector<Pair>{{0, 1}, {1, 2}}, kNeverExact);
        ASSERT_TRUE(cache.refresh(0, top, bottom, kThickness, kReach, 0.0, scratch));
        ASSERT_TRUE(cache.refresh(1, bottom, plane, kThickness, kReach, 0.0, scratch));
        ASSERT_FALSE(cache.entry(0).points.empty());
        ASSERT_FALSE(cache.entry(1).points.empty());
        Real x = 0.1;
        for (std::size_t k = 0; k < cache.size(); ++k)
        {
            for (CachedPoint& point : cache.entry(k).points)
            {
                point.load = {x / 3.0, x / 7.0, -x / 11.0, {x / 13.0, x / 17.0, x / 19.0}, {x / 23.0, x, -x}};
                x += 0.1;
            }
        }
    }
};

TEST_F(ContactCacheBoxOnBox, ACaptureOfABoxOnALargerBoxHoldsThePointsOfTheExactNarrowPhase)
{
    const std::vector<ContactPoint> exact = exactPoints(top, bottom, kThickness + kReach);
    ASSERT_EQ(exact.size(), 4u) << "the scene's premise: the small box's lower face on the large one's top";
    const std::vector<ContactPoint> cached = cachedPoints(cache, 0, top, bottom);
    ASSERT_EQ(cached.size(), exact.size());
    expectSamePoints(cached, exact);
}

TEST_F(ContactCacheBoxOnBox, SaveAndRestoreRoundTripBitForBit)
{
    const std::vector<double> saved = cache.save();
    ContactCache restored;
    restored.restore(saved, 3);
    EXPECT_EQ(bits(restored.save()), bits(saved));
    ASSERT_EQ(restored.size(), cache.size());
    // the restored entries answer as the saved ones did, to the bit
    const std::vector<ContactPoint> before = cachedPoints(cache, 0, top, bottom);
    const std::vector<ContactPoint> after = cachedPoints(restored, 0, top, bottom);
    ASSERT_EQ(after.size(), before.size());
    for (std::size_t i = 0; i < before.size(); ++i)
    {
        EXPECT_EQ(std::bit_cast<std::uint64_t>(after[i].phi), std::bit_cast<std::uint64_t>(before[i].phi));
        EXPECT_EQ(after[i].feature, before[i].feature);
    }
    // still valid at the capture poses: no capture
    EXPECT_FALSE(restored.refresh(0, top, bottom, kThickness, kReach, 0.0, scratch));
    EXPECT_FALSE(restored.refresh(1, bottom, plane, kThickness, kReach, 0.0, scratch));
}

TEST_F(ContactCacheBoxOnBox, RestoreRefusesGarbageAndLeavesTheCacheAsItWas)
{
    const std::vector<double> saved = cache.save();
    const std::vector<std::uint64_t> original = bits(saved);
    std::vector<std::vector<double>> garbage;
    std::vector<double> bad = saved;
    bad[0] = 2.0; // another version
    garbage.push_back(bad);
    bad = saved;
    bad.pop_back(); // cut short
    garbage.push_back(bad);
    bad = saved;
    bad.push_back(0.0); // one number too many
    garbage.push_back(bad);
    bad = saved;
    bad[1] = 3.0; // one entry more than there is
    garbage.push_back(bad);
    bad = saved;
    bad[2 + 1] = 7.0; // the first entry's b: no such body in a world of 3
    garbage.push_back(bad);
    bad = saved;
    bad[2] = 1.0; // the first entry's a equal to its b
    garbage.push_back(bad);
    bad = saved;
    bad[2 + 12] = std::numeric_limits<double>::quiet_NaN(); // the first point's anchor
    garbage.push_back(bad);
    bad = saved;
    bad[2 + 12 + 10] = 5.0; // the first point's sample: not A, B or Between
    garbage.push_back(bad);

    for (std::size_t i = 0; i < garbage.size(); ++i)
    {
        EXPECT_THROW(cache.restore(garbage[i], 3), std::invalid_argument) << "garbage " << i;
        EXPECT_EQ(bits(cache.save()), original) << "garbage " << i << " changed the cache";
    }
    // the right numbers for a world of fewer bodies than they name
    EXPECT_THROW(cache.restore(saved, 2), std::invalid_argument);
    EXPECT_EQ(bits(cache.save()), original);
}

TEST_F(ContactCacheBoxOnPlane, MotionSinceCaptureIsZeroThereAndAtLeastTheTranslation)
{
    const ContactEntry& entry = cache.entry(0);
    // the same pose as captured: the relative pose is computed the same way both times, so what is left
    // is the round-off of the angle between two equal orientations, far below 1e-12 m
    EXPECT_LE(cache.motionSinceCapture(entry, boxAt(Vec3::Zero()), plane), kTol);
    Real previous = 0.0;
    for (const Real distance : {1e-4, 1e-3, 1e-2, 1e-1, 1.0})
    {
        const Vec3 shift = distance * Vec3(0.6, -0.48, 0.64);
        const Real motion = cache.motionSinceCapture(entry, boxAt(shift), plane);
        EXPECT_GE(motion, distance * (1.0 - 1e-12));
        EXPECT_GT(motion, previous);
        previous = motion;
    }
}

// The bound is sound: no point of either box moves, relative to the other box, by more than the motion
// since capture, for turns and shifts of either.
TEST(ContactCache, MotionSinceCaptureBoundsHowFarAnyPointMovedRelativeToTheOtherBody)
{
    const Shape small = Box{Vec3(0.3, 0.2, 0.1)};
    const Shape large = Box{Vec3(1.0, 0.8, 0.5)};
    const Box& smallBox = std::get<Box>(small);
    const Box& largeBox = std::get<Box>(large);
    const PlacedShape top = placed(small, Vec3(0.1, 0.2, 0.6005), rotation(0.4, Vec3::UnitZ()));
    const PlacedShape bottom = placed(large, Vec3::Zero(), rotation(0.1, Vec3(1.0, 2.0, 3.0)));
    ContactCache cache;
    ContactScratch scratch;
    cache.follow(std::vector<Pair>{{0, 1}}, kNeverExact);
    cache.refresh(0, top, bottom, kThickness, kReach, 0.0, scratch);

    const auto moved = [](const PlacedShape& body, const Vec3& shift, const Quat& turn)
    { return placed(*body.shape, body.pose.position + shift, turn * body.pose.orientation); };
    const std::vector<std::pair<Vec3, Quat>> moves = {{Vec3(0.01, 0.0, 0.0), Quat::Identity()},
                                                      {Vec3::Zero(), rotation(0.02, Vec3::UnitX())},
                                                      {Vec3(0.0, -0.005, 0.002), rotation(0.01, Vec3(1.0, -1.0, 2.0))},
                                                      {Vec3(0.0, 0.0, 0.03), rotation(0.05, Vec3::UnitZ())}};
    for (std::size_t m = 0; m < moves.size(); ++m)
    {
        for (const bool moveTop : {true, false})
        {
            const PlacedShape a = moveTop ? moved(top, moves[m].first, moves[m].second) : top;
            const PlacedShape b = moveTop ? bottom : moved(bottom, moves[m].first, moves[m].second);
            const Real motion = cache.motionSinceCapture(cache.entry(0), a, b);
            Real farthest = 0.0;
            for (std::size_t i = 0; i < 8; ++i)
            {
                // A's corners in B's frame, and B's corners in A's frame, before and after
                const Vec3 cornerA = boxCorner(smallBox.halfExtents, i);
                const Vec3 cornerB = boxCorner(largeBox.halfExtents, i);
                const Vec3 aInBBefore = bottom.pose.toLocal(top.pose.toWorld(cornerA));
                const Vec3 aInBAfter = b.pose.toLocal(a.pose.toWorld(cornerA));
                const Vec3 bInABefore = top.pose.toLocal(bottom.pose.toWorld(cornerB));
                const Vec3 bInAAfter = a.pose.toLocal(b.pose.toWorld(cornerB));
                farthest = std::max({farthest, (aInBAfter - aInBBefore).norm(), (bInAAfter - bInABefore).norm()});
            }
            ASSERT_GT(farthest, 0.0);
            EXPECT_GE(motion, farthest * (1.0 - 1e-12)) << "move " << m << (moveTop ? " of the top" : " of the bottom");
        }
    }
}

TEST(ContactCache, SpherePairsAreCapturedAtEveryRefresh)
{
    const Shape ball = Sphere{0.25};
    const Shape ground = Plane{Vec3::UnitZ(), 0.0};
    const PlacedShape plane = placed(ground, Vec3::Zero());
    ContactCache cache;
    ContactScratch scratch;
    cache.follow(std::vector<Pair>{{0, 1}}, [](std::uint32_t a, std::uint32_t) { return a == 0; });
    ASSERT_TRUE(cache.entry(0).exact);
    const PlacedShape here = placed(ball, Vec3(0.0, 0.0, 0.252));
    EXPECT_TRUE(cache.refresh(0, here, plane, kThickness, kReach, 0.0, scratch));
    EXPECT_TRUE(cache.refresh(0, here, plane, kThickness, kReach, 0.0, scratch)) << "not moved, captured again";
    // moved by a millimetre, far within any reach: still captured, and its point is the exact one there
    const PlacedShape there = placed(ball, Vec3(0.001, 0.0, 0.251));
    EXPECT_TRUE(cache.refresh(0, there, plane, kThickness, kReach, 0.0, scratch));
    EXPECT_EQ(cache.takeCounters().captures, 3);
    const std::vector<ContactPoint> cached = cachedPoints(cache, 0, there, plane);
    ASSERT_EQ(cached.size(), 1u);
    EXPECT_NEAR(cached[0].phi, 0.001, kTol);
    EXPECT_LT((cached[0].point - Vec3(0.001, 0.0, 0.001)).norm(), kTol);
    // pointsAt detects it exactly too
    std::vector<ContactPoint> found;
    const PlacedShape lower = placed(ball, Vec3(0.001, 0.0, 0.2495));
    cache.pointsAt(0, lower, plane, kThickness, kThickness, kReach, found, scratch);
    ASSERT_EQ(found.size(), 1u);
    EXPECT_NEAR(found[0].phi, -0.0005, kTol);
}

// A cached point keeps the normal and the face it was captured on. A small box hanging a centimetre
// over the edge of a large one slides off it and drops below its top face, beside it: the cache,
// still within its reach, says the boxes overlap by 2 mm where they are 2 cm apart. Push-out must not
// act on that, so overlapsAt looks again whenever an overlap it would act on could be stale.
TEST(ContactCache, OverlapsAtCapturesAnewWhereAStalePointShowsAnOverlapThatIsNotThere)
{
    const Shape small = Box{Vec3::Constant(0.1)};
    const Shape large = Box{Vec3::Constant(0.5)};
    const PlacedShape bottom = placed(large, Vec3::Zero());
    ContactCache cache;
    ContactScratch scratch;
    cache.follow(std::vector<Pair>{{0, 1}}, kNeverExact);
    // overhanging: its footprint reaches 1 cm over the top face, 1 mm above it
    const PlacedShape hanging = placed(small, Vec3(0.59, 0.0, 0.601));
    cache.refresh(0, hanging, bottom, kThickness, kReach, 0.0, scratch);
    constexpr Real kAllowance = 1e-4;
    std::vector<ContactPoint> found;
    cache.overlapsAt(0, hanging, bottom, 0.0, kAllowance, kThickness, kReach, found, scratch);
    EXPECT_TRUE(found.empty()) << "1 mm apart, nothing overlaps";

    // 3 cm further out and 3 mm lower: beside the large box, 2 cm from it, within the entry's reach
    const PlacedShape beside = placed(small, Vec3(0.62, 0.0, 0.598));
    ASSERT_LE(cache.motionSinceCapture(cache.entry(0), beside, bottom), kReach);
    ASSERT_TRUE(exactPoints(beside, bottom, 0.0).empty());
    const auto deepest = [](const std::vector<ContactPoint>& points)
    {
        Real phi = 0.0;
        for (const ContactPoint& p : points)
        {
            phi = std::min(phi, p.phi);
        }
        return phi;
    };
    std::vector<ContactPoint> stale;
    cache.pointsAt(0, beside, bottom, 0.0, kThickness, kReach, stale, scratch);
    ASSERT_LT(deepest(stale), -1e-3) << "the anchored points no longer show the stale overlap this test is about";
    cache.takeCounters();
    found.clear();
    cache.overlapsAt(0, beside, bottom, 0.0, kAllowance, kThickness, kReach, found, scratch);
    EXPECT_TRUE(found.empty()) << "deepest " << deepest(found);
    EXPECT_EQ(cache.takeCounters().captures, 1);

    // a real overlap, seen from the poses it was captured at, is kept without another capture
    const PlacedShape sunk = placed(small, Vec3(0.4, 0.0, 0.598));
    cache.refresh(0, sunk, bottom, kThickness, kReach, 0.0, scratch);
    cache.takeCounters();
    found.clear();
    cache.overlapsAt(0, sunk, bottom, 0.0, kAllowance, kThickness, kReach, found, scratch);
    EXPECT_NEAR(deepest(found), -0.002, 1e-12);
    EXPECT_EQ(cache.takeCounters().captures, 0);
}

} // namespace
} // namespace impulse
