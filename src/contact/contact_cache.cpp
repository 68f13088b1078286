// SPDX-License-Identifier: MIT
#include "contact/contact_cache.hpp"

#include "collision/narrow_phase.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>
#include <stdexcept>
#include <utility>
#include <variant>

namespace impulse
{
namespace
{

constexpr Real kInfinity = std::numeric_limits<Real>::infinity();

bool isPlane(const PlacedShape& body)
{
    return std::holds_alternative<Plane>(*body.shape);
}

// The relative pose is measured in the frame of one body of the pair, the "frame body": a plane when
// there is one (its origin is arbitrary and it has no points of its own), else B.
struct RelativePose
{
    Vec3 offset; ///< the partner's centre in the frame body's frame
    Quat turn;   ///< the partner's orientation in the frame body's frame
};

RelativePose relativePose(const PlacedShape& a, const PlacedShape& b)
{
    const PlacedShape& frame = isPlane(a) ? a : b;
    const PlacedShape& partner = isPlane(a) ? b : a;
    return {frame.pose.rotation.transpose() * (partner.pose.position - frame.pose.position),
            frame.pose.orientation.conjugate() * partner.pose.orientation};
}

// Where a cached point lies at the given poses.
ContactPoint evaluatePoint(const CachedPoint& cached, const PlacedShape& a, const PlacedShape& b)
{
    const Vec3 witnessA = a.pose.toWorld(cached.anchorA);
    const Vec3 witnessB = b.pose.toWorld(cached.anchorB);
    const Vec3 normal = (cached.normalOnA ? a.pose.rotation : b.pose.rotation) * cached.normal;
    const Real phi = normal.dot(witnessA - witnessB);
    const Vec3 point = cached.sample == SampleOf::A   ? witnessA
                       : cached.sample == SampleOf::B ? witnessB
                                                      : Vec3(0.5 * (witnessA + witnessB));
    return {point, normal, phi, cached.feature, cached.sample};
}

// The tangential load of a cached point as a world vector at the given poses.
Vec3 tangentialLoad(const CachedPoint& cached, const PlacedShape& a, const PlacedShape& b)
{
    Vec3 t1;
    Vec3 t2;
    tangentBasis(cached.normal, t1, t2);
    const Mat3& rotation = cached.normalOnA ? a.pose.rotation : b.pose.rotation;
    return rotation * (cached.load.tangent1 * t1 + cached.load.tangent2 * t2);
}

// The largest finite bounding radius of the pair, for round-off allowances.
Real pairScale(const PlacedShape& a, const PlacedShape& b)
{
    const Real ra = std::isfinite(a.boundingRadius) ? a.boundingRadius : 0.0;
    const Real rb = std::isfinite(b.boundingRadius) ? b.boundingRadius : 0.0;
    return std::max(ra, rb);
}

} // namespace

void tangentBasis(const Vec3& normal, Vec3& tangent1, Vec3& tangent2)
{
    // across the normal's largest components, so the first tangent is never near zero length
    if (std::abs(normal.x()) >= 0.57735)
    {
        tangent1 = Vec3(normal.y(), -normal.x(), 0.0).normalized();
    }
    else
    {
        tangent1 = Vec3(0.0, normal.z(), -normal.y()).normalized();
    }
    tangent2 = normal.cross(tangent1);
}

Real ContactCache::motionSinceCapture(const ContactEntry& entry, const PlacedShape& a, const PlacedShape& b) const
{
    if (!entry.captured)
    {
        return kInfinity;
    }
    // The partner's points move in the frame body's frame by at most |d offset| + angle R_partner; the
    // frame body's points, seen from the partner, by at most |d offset| + angle (R_frame + |offset|).
    // A plane has no points of its own.
    const RelativePose now = relativePose(a, b);
    const PlacedShape& frame = isPlane(a) ? a : b;
    const PlacedShape& partner = isPlane(a) ? b : a;
    const Real angle = now.turn.angularDistance(entry.turn);
    Real lever = partner.boundingRadius;
    if (!isPlane(frame))
    {
        lever = std::max(lever, frame.boundingRadius + std::max(now.offset.norm(), entry.offset.norm()));
    }
    return (now.offset - entry.offset).norm() + angle * lever;
}

void ContactCache::detect(const PlacedShape& a, const PlacedShape& b, Real threshold, std::vector<ContactPoint>& out,
                          ContactScratch& scratch)
{
    m_narrowPhaseCalls.fetch_add(1, std::memory_order_relaxed);
    collideShapes(*a.shape, a.pose, *b.shape, b.pose, threshold, out, scratch.narrowPhase);
}

void ContactCache::capture(ContactEntry& entry, const PlacedShape& a, const PlacedShape& b, Real threshold,
                           ContactScratch& scratch)
{
    m_captures.fetch_add(1, std::memory_order_relaxed);
    scratch.detected.clear();
    detect(a, b, threshold, scratch.detected, scratch);

    std::vector<CachedPoint>& fresh = scratch.fresh;
    std::vector<bool>& taken = scratch.taken;
    fresh.clear();
    for (const ContactPoint& found : scratch.detected)
    {
        CachedPoint point;
        point.anchorA = a.pose.toLocal(found.witnessA());
        point.anchorB = b.pose.toLocal(found.witnessB());
        point.normalOnA = found.sample == SampleOf::B;
        point.normal = (point.normalOnA ? a.pose.rotation : b.pose.rotation).transpose() * found.normal;
        point.feature = found.feature;
        point.sample = found.sample;
        fresh.push_back(point);
    }

    // Loads carry over to the points found again: by feature id, else to the nearest old point
    // within a millimetre (or a twentieth of the smaller body). Each old point passes its load on once.
    const std::vector<CachedPoint>& old = entry.points;
    taken.assign(old.size(), false);
    const Real smaller = std::min(a.boundingRadius, b.boundingRadius);
    const Real near = std::min(1e-3, 0.05 * smaller);
    for (std::size_t i = 0; i < fresh.size() && !old.empty(); ++i)
    {
        CachedPoint& point = fresh[i];
        std::size_t match = old.size();
        for (std::size_t o = 0; o < old.size(); ++o)
        {
            if (!taken[o] && old[o].feature == point.feature && old[o].sample == point.sample)
            {
                match = o;
                break;
            }
        }
        if (match == old.size())
        {
            const Vec3 here = a.pose.toWorld(point.anchorA);
            Real nearest = near * near;
            for (std::size_t o = 0; o < old.size(); ++o)
            {
                const Real gap = (a.pose.toWorld(old[o].anchorA) - here).squaredNorm();
                if (!taken[o] && gap <= nearest)
                {
                    nearest = gap;
                    match = o;
                }
            }
        }
        if (match == old.size())
        {
            continue;
        }
        taken[match] = true;
        point.load.normal = old[match].load.normal;
        const Vec3 tangential = tangentialLoad(old[match], a, b);
        Vec3 t1;
        Vec3 t2;
        tangentBasis(point.normal, t1, t2);
        const Mat3& rotation = point.normalOnA ? a.pose.rotation : b.pose.rotation;
        point.load.tangent1 = tangential.dot(rotation * t1);
        point.load.tangent2 = tangential.dot(rotation * t2);
    }
    entry.points.swap(fresh);
    const RelativePose pose = relativePose(a, b);
    entry.offset = pose.offset;
    entry.turn = pose.turn;
    entry.captured = true;
}

bool ContactCache::refresh(std::size_t k, const PlacedShape& a, const PlacedShape& b, Real thickness, Real reach,
                           Real extra, ContactScratch& scratch)
{
    ContactEntry& entry = m_entries[k];
    if (!entry.exact && entry.captured && motionSinceCapture(entry, a, b) + extra <= entry.reach)
    {
        return false;
    }
    entry.reach = entry.exact ? reach : std::max(reach, 2.0 * extra);
    capture(entry, a, b, thickness + entry.reach, scratch);
    return true;
}

void ContactCache::recapture(std::size_t k, const PlacedShape& a, const PlacedShape& b, Real thickness, Real reach,
                             ContactScratch& scratch)
{
    ContactEntry& entry = m_entries[k];
    entry.reach = reach;
    capture(entry, a, b, thickness + reach, scratch);
}

void ContactCache::evaluate(const ContactEntry& entry, const PlacedShape& a, const PlacedShape& b, Real threshold,
                            std::vector<ContactPoint>& out)
{
    for (const CachedPoint& cached : entry.points)
    {
        const ContactPoint point = evaluatePoint(cached, a, b);
        if (point.phi < threshold)
        {
            out.push_back(point);
        }
    }
}

void ContactCache::entryPoints(std::size_t k, const PlacedShape& a, const PlacedShape& b,
                               std::vector<ContactPoint>& out) const
{
    evaluate(m_entries[k], a, b, kInfinity, out);
}

void ContactCache::pointsAt(std::size_t k, const PlacedShape& a, const PlacedShape& b, Real threshold, Real thickness,
                            Real reach, std::vector<ContactPoint>& out, ContactScratch& scratch)
{
    ContactEntry& entry = m_entries[k];
    if (entry.exact)
    {
        detect(a, b, threshold, out, scratch);
        return;
    }
    Real motion = motionSinceCapture(entry, a, b);
    if (!(motion <= entry.reach))
    {
        recapture(k, a, b, thickness, reach, scratch);
        motion = 0.0;
    }
    evaluate(entry, a, b, threshold, out);
    if (m_verify)
    {
        scratch.all.clear();
        evaluate(entry, a, b, kInfinity, scratch.all);
        verify(entry, a, b, thickness, motion, scratch.all, scratch);
    }
}

void ContactCache::overlapsAt(std::size_t k, const PlacedShape& a, const PlacedShape& b, Real threshold, Real allowance,
                              Real thickness, Real reach, std::vector<ContactPoint>& out, ContactScratch& scratch)
{
    const std::size_t first = out.size();
    pointsAt(k, a, b, threshold, thickness, reach, out, scratch);
    ContactEntry& entry = m_entries[k];
    if (entry.exact)
    {
        return;
    }
    Real deepest = 0.0;
    for (std::size_t i = first; i < out.size(); ++i)
    {
        deepest = std::min(deepest, out[i].phi);
    }
    if (-deepest > allowance && motionSinceCapture(entry, a, b) > 0.25 * allowance)
    {
        out.resize(first);
        recapture(k, a, b, thickness, reach, scratch);
        evaluate(entry, a, b, threshold, out);
    }
}

void ContactCache::verify(const ContactEntry& entry, const PlacedShape& a, const PlacedShape& b, Real thickness,
                          Real motion, const std::vector<ContactPoint>& cached, ContactScratch& scratch)
{
    // A material point (a corner against a plane, a mesh vertex) moves by at most `motion` relative
    // to the other body, and a signed distance and its linearisation each change by at most that
    // much: its separation may be off by 2 motion, and a point the cache lacks was at least its
    // reach away, so it cannot be within the thickness. The other points are not material: the
    // corners of two faces clipped to each other and the crossings of edges slide along the features
    // they lie on, and which ones there are changes with round-off where faces lie flush. For those
    // the pair is judged as a whole: the cache must know a point at least as deep as the deepest of
    // them, to within the reach it was captured with beyond that bound (a crossing's middle slides
    // along its edge as the passage lengthens, faster than the bodies move).
    const Real bound = 2.0 * motion + 1e-9 * pairScale(a, b);
    const bool clipped = std::holds_alternative<Box>(*a.shape) && std::holds_alternative<Box>(*b.shape);
    const auto material = [&](const ContactPoint& point)
    { return !clipped && point.sample != SampleOf::Between && (point.feature & 0x40000000u) == 0; };
    scratch.exact.clear();
    collideShapes(*a.shape, a.pose, *b.shape, b.pose, thickness, scratch.exact, scratch.narrowPhase);
    Real deepestExact = kInfinity;
    Real deepestCached = thickness;
    for (const ContactPoint& c : cached)
    {
        deepestCached = std::min(deepestCached, c.phi);
    }
    const auto report = [&](const std::string& what, const ContactPoint& e, Real claimed)
    {
        if (m_violations.fetch_add(1) == 0)
        {
            std::ostringstream message;
            message.precision(17);
            message << "contact cache of bodies " << entry.a << " and " << entry.b << ": " << what << " at ("
                    << e.point.transpose() << "), feature " << e.feature << ": exact phi " << e.phi << ", cached "
                    << claimed << ", bound " << bound << " (motion since capture " << motion << ")";
            const std::lock_guard<std::mutex> lock(m_violationMutex);
            m_firstViolation = message.str();
        }
    };
    const ContactPoint* deepest = nullptr;
    for (const ContactPoint& e : scratch.exact)
    {
        if (!material(e))
        {
            if (e.phi < deepestExact)
            {
                deepestExact = e.phi;
                deepest = &e;
            }
            continue;
        }
        // what the cache says of the separation here: its point of the same feature, or any of its
        // points within the bound of this one; without either, that it is beyond the thickness
        Real claimed = thickness;
        bool found = false;
        for (const ContactPoint& c : cached)
        {
            if ((c.feature == e.feature && c.sample == e.sample) || (c.point - e.point).norm() <= bound)
            {
                claimed = found ? std::min(claimed, c.phi) : c.phi;
                found = true;
            }
        }
        if (claimed - e.phi > bound)
        {
            report(found ? "separation off" : "missed point", e, claimed);
        }
    }
    if (deepest != nullptr && deepestCached - deepestExact > bound + entry.reach)
    {
        report("deepest point missed", *deepest, deepestCached);
    }
}

int ContactCache::takeViolations(std::string& first)
{
    const std::lock_guard<std::mutex> lock(m_violationMutex);
    first = m_firstViolation;
    m_firstViolation.clear();
    return m_violations.exchange(0);
}

namespace
{

constexpr double kSaveVersion = 1.0;
constexpr std::size_t kEntryNumbers = 12; // a, b, captured, offset (3), turn (4), reach, point count
// anchors (6), normal (3), feature, sample, owner, load (3), search direction (3), last change (3)
constexpr std::size_t kPointNumbers = 21;

} // namespace

std::vector<double> ContactCache::save() const
{
    // the listed entries and the parked ones, merged in pair order
    std::vector<const ContactEntry*> all;
    all.reserve(m_entries.size() + m_parked.size());
    auto parked = m_parked.begin();
    for (const ContactEntry& entry : m_entries)
    {
        for (; parked != m_parked.end() && parked->first < key(entry.a, entry.b); ++parked)
        {
            all.push_back(&parked->second);
        }
        all.push_back(&entry);
    }
    for (; parked != m_parked.end(); ++parked)
    {
        all.push_back(&parked->second);
    }
    std::vector<double> saved = {kSaveVersion, static_cast<double>(all.size())};
    for (const ContactEntry* entry : all)
    {
        saved.insert(saved.end(),
                     {static_cast<double>(entry->a), static_cast<double>(entry->b), entry->captured ? 1.0 : 0.0,
                      entry->offset.x(), entry->offset.y(), entry->offset.z(), entry->turn.w(), entry->turn.x(),
                      entry->turn.y(), entry->turn.z(), entry->reach, static_cast<double>(entry->points.size())});
        for (const CachedPoint& point : entry->points)
        {
            saved.insert(saved.end(), {point.anchorA.x(),
                                       point.anchorA.y(),
                                       point.anchorA.z(),
                                       point.anchorB.x(),
                                       point.anchorB.y(),
                                       point.anchorB.z(),
                                       point.normal.x(),
                                       point.normal.y(),
                                       point.normal.z(),
                                       static_cast<double>(point.feature),
                                       static_cast<double>(point.sample),
                                       point.normalOnA ? 1.0 : 0.0,
                                       point.load.normal,
                                       point.load.tangent1,
                                       point.load.tangent2,
                                       point.load.direction[0],
                                       point.load.direction[1],
                                       point.load.direction[2],
                                       point.load.change[0],
                                       point.load.change[1],
                                       point.load.change[2]});
        }
    }
    return saved;
}

void ContactCache::restore(const std::vector<double>& saved, std::size_t bodies)
{
    const auto fail = [](const std::string& what) { throw std::invalid_argument("contacts: " + what); };
    const auto whole = [](double x, double below) { return x >= 0.0 && x < below && x == std::floor(x); };
    std::vector<ContactEntry> entries;
    if (!saved.empty())
    {
        if (saved.size() < 2 || saved[0] != kSaveVersion || !whole(saved[1], 1e9))
        {
            fail("not a saved contact layer of this version");
        }
        std::size_t at = 2;
        const auto take = [&](std::size_t count)
        {
            if (saved.size() - at < count)
            {
                fail("cut short");
            }
            const double* first = saved.data() + at;
            at += count;
            return first;
        };
        const auto count = static_cast<std::size_t>(saved[1]);
        for (std::size_t e = 0; e < count; ++e)
        {
            const double* n = take(kEntryNumbers);
            ContactEntry entry;
            if (!whole(n[0], static_cast<double>(bodies)) || !whole(n[1], static_cast<double>(bodies)) || n[0] >= n[1])
            {
                fail("entry " + std::to_string(e) + " names no pair of this world's bodies");
            }
            entry.a = static_cast<std::uint32_t>(n[0]);
            entry.b = static_cast<std::uint32_t>(n[1]);
            if (!entries.empty() &&
                std::make_pair(entries.back().a, entries.back().b) >= std::make_pair(entry.a, entry.b))
            {
                fail("entries out of order");
            }
            entry.captured = n[2] != 0.0;
            entry.offset = Vec3(n[3], n[4], n[5]);
            entry.turn = Quat(n[6], n[7], n[8], n[9]);
            entry.reach = n[10];
            if (!whole(n[11], 1e9))
            {
                fail("entry " + std::to_string(e) + " has a bad point count");
            }
            entry.points.resize(static_cast<std::size_t>(n[11]));
            for (CachedPoint& point : entry.points)
            {
                const double* p = take(kPointNumbers);
                point.anchorA = Vec3(p[0], p[1], p[2]);
                point.anchorB = Vec3(p[3], p[4], p[5]);
                point.normal = Vec3(p[6], p[7], p[8]);
                if (!whole(p[9], 4294967296.0) || !whole(p[10], 3.0))
                {
                    fail("entry " + std::to_string(e) + " has a bad point");
                }
                point.feature = static_cast<std::uint32_t>(p[9]);
                point.sample = static_cast<SampleOf>(static_cast<int>(p[10]));
                point.normalOnA = p[11] != 0.0;
                point.load = {p[12], p[13], p[14], {p[15], p[16], p[17]}, {p[18], p[19], p[20]}};
            }
            for (std::size_t i = 0; i < kEntryNumbers; ++i)
            {
                if (!std::isfinite(n[i]))
                {
                    fail("entry " + std::to_string(e) + " is not finite");
                }
            }
            entries.push_back(std::move(entry));
        }
        if (at != saved.size())
        {
            fail("numbers left over");
        }
        for (std::size_t i = 0; i < saved.size(); ++i)
        {
            if (!std::isfinite(saved[i]))
            {
                fail("not finite");
            }
        }
    }
    m_entries.swap(entries);
    m_previous.clear();
    m_parked.clear(); // restored as listed: a restored world wakes, and follow() keeps what it lists
}

ContactCache::Counters ContactCache::takeCounters()
{
    return {m_narrowPhaseCalls.exchange(0), m_captures.exchange(0)};
}

} // namespace impulse
