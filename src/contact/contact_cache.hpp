// SPDX-License-Identifier: MIT
// The contact layer: what the narrow phase found for each candidate pair, kept across steps.
//
// An entry holds the pair's sample points anchored in both bodies (each point's two witnesses in
// their bodies' frames, the normal in the frame of the body whose distance field it is), a feature
// id per point, and the loads the solver accumulated on it. Captured by the exact narrow phase with
// a margin, an entry answers "where are the points, how far apart" at any nearby pose without
// detection: phi = n . (witness A - witness B), both witnesses and the normal carried by their
// bodies. It stays valid while the pair's relative motion since capture is within the margin: any
// point missing from it was at least the margin away at capture, and a point moves no further than
// the relative motion, so it is still beyond the contact thickness (signed distances are
// 1-Lipschitz). Past the margin the entry is captured again, and the loads carry over by feature id,
// else to the nearest old point.
//
// Pairs with a sphere or a capsule are not anchored: their contacts depend on a centre line, not on
// material points, and their narrow phase costs about what evaluating an entry costs. They are
// detected exactly at every use; their entries only keep the loads.
#pragma once

#include "collision/contact.hpp"
#include "collision/narrow_phase.hpp"

#include <impulse/shape.hpp>

#include <algorithm>
#include <array>
#include <atomic>
#include <cstdint>
#include <map>
#include <mutex>
#include <string>
#include <vector>

namespace impulse
{

/// Impulses a contact point carried at the end of the last solve, N s: along the normal and along two
/// tangents fixed in the frame of the body that owns the normal.
struct ContactLoad
{
    Real normal = 0.0;
    Real tangent1 = 0.0;
    Real tangent2 = 0.0;
    /// The contact pass's search direction and its last sweep's change of (normal, tangent1,
    /// tangent2), kept so that its conjugate-gradient iteration goes on where it stopped: a structure
    /// whose loads take hundreds of sweeps to settle (a tall tower about to tip) gets them over steps.
    std::array<Real, 3> direction{};
    std::array<Real, 3> change{};
};

/// One contact point of a pair, kept across steps.
struct CachedPoint
{
    Vec3 anchorA = Vec3::Zero(); ///< A's witness, A's body frame
    Vec3 anchorB = Vec3::Zero(); ///< B's witness, B's body frame
    Vec3 normal = Vec3::UnitZ(); ///< from B toward A, in the frame of its owner
    std::uint32_t feature = 0;
    SampleOf sample = SampleOf::Between;
    bool normalOnA = false; ///< the normal is A's (a point of B in A's distance field), else B's
    ContactLoad load;
};

/// A body as the contact layer sees it: its shape where it is at one moment.
struct PlacedShape
{
    const Shape* shape = nullptr;
    Pose pose;
    Real boundingRadius = 0.0;
};

/// Everything known about one candidate pair (a, b), a < b.
struct ContactEntry
{
    std::uint32_t a = 0;
    std::uint32_t b = 0;
    bool exact = false;           ///< detected exactly at every use (a sphere or a capsule is involved)
    bool captured = false;        ///< `points` and the capture pose are set
    Vec3 offset = Vec3::Zero();   ///< at capture: the centre of the frame body's partner in its frame
    Quat turn = Quat::Identity(); ///< at capture: the partner's orientation in the frame body's frame
    Real reach = 0.0;             ///< relative motion allowed before capturing again, m
    std::vector<CachedPoint> points;
};

/// What the contact layer reuses from call to call, one per worker thread.
struct ContactScratch
{
    NarrowPhaseScratch narrowPhase;
    std::vector<ContactPoint> detected; ///< a capture's points
    std::vector<ContactPoint> all;      ///< every cached point, for the verification
    std::vector<ContactPoint> exact;    ///< the exact narrow phase beside the cache, for the verification
    std::vector<CachedPoint> fresh;     ///< the points being captured
    std::vector<bool> taken;            ///< which old points have passed their loads on
};

/// Tangents of a unit normal, a fixed function of it: friction loads are kept in this basis.
void tangentBasis(const Vec3& normal, Vec3& tangent1, Vec3& tangent2);

/// The cache of every candidate pair, in the order of the pair list.
class ContactCache
{
  public:
    /// Follows a new pair list (sorted by (a, b)): entries of pairs still listed keep their points
    /// and loads, new pairs start empty, the rest are dropped. `exactPair(a, b)` tells which pairs
    /// are detected exactly at every use.
    template <class Pairs, class ExactPair> void follow(const Pairs& pairs, const ExactPair& exactPair)
    {
        follow(pairs, exactPair, [](std::uint32_t, std::uint32_t) { return false; });
    }
    /// The same, but an entry whose pair is no longer listed and for which `parkedPair(a, b)` holds
    /// (its bodies sleep) is parked instead of dropped: kept aside with its points and loads, and
    /// taken back when the pair is listed again, so that a woken island starts from the loads it
    /// slept with. Parked entries whose pair no longer satisfies `parkedPair` are dropped.
    template <class Pairs, class ExactPair, class ParkedPair>
    void follow(const Pairs& pairs, const ExactPair& exactPair, const ParkedPair& parkedPair);

    std::size_t size() const { return m_entries.size(); }
    ContactEntry& entry(std::size_t k) { return m_entries[k]; }
    const ContactEntry& entry(std::size_t k) const { return m_entries[k]; }

    /// How far the points of pair k may have moved relative to each other since capture, m (a
    /// bound; infinite for an entry never captured).
    Real motionSinceCapture(const ContactEntry& entry, const PlacedShape& a, const PlacedShape& b) const;

    /// Makes entry k usable at these poses, with `extra` to spare for poses up to that much further:
    /// kept when its motion since capture plus `extra` is within its reach, else captured anew here
    /// with reach `reach` (at least `extra` more than the motion it must cover). Exact entries are
    /// captured at every call. Returns whether it captured.
    bool refresh(std::size_t k, const PlacedShape& a, const PlacedShape& b, Real thickness, Real reach, Real extra,
                 ContactScratch& scratch);

    /// Captures entry k anew at these poses with reach `reach`, whatever its motion since capture.
    void recapture(std::size_t k, const PlacedShape& a, const PlacedShape& b, Real thickness, Real reach,
                   ContactScratch& scratch);

    /// The points of pair k with the bodies at these poses whose phi is below `threshold` (at most
    /// the contact thickness): from the anchors while the entry is valid here, else detected exactly
    /// (an exact entry, or an anchored one the bodies have left, which is then captured anew here
    /// with reach `reach`). Appends to `out`.
    void pointsAt(std::size_t k, const PlacedShape& a, const PlacedShape& b, Real threshold, Real thickness, Real reach,
                  std::vector<ContactPoint>& out, ContactScratch& scratch);

    /// The points of pair k with phi below `threshold` at these poses (0: the overlaps; a little
    /// above it: also what touches, to hold a joint push), for moving the bodies apart by them
    /// (push-out): as pointsAt, but when they show an overlap deeper than `allowance` and the
    /// bodies have moved since capture by more than a quarter of it, captured anew here first. A
    /// cached point's separation may be off by twice that motion, and a push by a stale overlap
    /// that is not there drives the bodies into their other neighbours.
    void overlapsAt(std::size_t k, const PlacedShape& a, const PlacedShape& b, Real threshold, Real allowance,
                    Real thickness, Real reach, std::vector<ContactPoint>& out, ContactScratch& scratch);

    /// Every point of entry k, evaluated from its anchors at these poses, one per cached point in
    /// their order (for an exact entry: as captured). Meant right after refresh at the same poses.
    void entryPoints(std::size_t k, const PlacedShape& a, const PlacedShape& b, std::vector<ContactPoint>& out) const;

    /// Verification ("shadow") mode: every use of an anchored entry also runs the exact narrow phase
    /// and checks that no exact point within the contact thickness is missing and that no separation
    /// is off by more than the bound the motion since capture allows.
    void setVerification(bool on) { m_verify = on; }
    /// Discrepancies found by the verification since the last call, and the first one described.
    int takeViolations(std::string& first);

    /// Everything the entries carry from one step to the next, as plain numbers (WorldSnapshot::contacts).
    std::vector<double> save() const;
    /// Puts back what save() gave, for a world of `bodies` bodies. Throws std::invalid_argument, and
    /// leaves the cache as it was, when the numbers do not describe a cache of such a world.
    void restore(const std::vector<double>& saved, std::size_t bodies);

    /// Counters since the last call: exact narrow-phase calls and captures.
    struct Counters
    {
        int narrowPhaseCalls = 0;
        int captures = 0;
    };
    Counters takeCounters();

  private:
    void capture(ContactEntry& entry, const PlacedShape& a, const PlacedShape& b, Real threshold,
                 ContactScratch& scratch);
    static void evaluate(const ContactEntry& entry, const PlacedShape& a, const PlacedShape& b, Real threshold,
                         std::vector<ContactPoint>& out);
    void verify(const ContactEntry& entry, const PlacedShape& a, const PlacedShape& b, Real thickness, Real motion,
                const std::vector<ContactPoint>& cached, ContactScratch& scratch);
    void detect(const PlacedShape& a, const PlacedShape& b, Real threshold, std::vector<ContactPoint>& out,
                ContactScratch& scratch);

    static std::uint64_t key(std::uint32_t a, std::uint32_t b) { return (std::uint64_t{a} << 32) | b; }

    std::vector<ContactEntry> m_entries;
    std::vector<ContactEntry> m_previous;
    std::map<std::uint64_t, ContactEntry> m_parked; ///< entries of sleeping pairs, by key(a, b)
    bool m_verify = false;
    std::atomic<int> m_violations{0};
    std::mutex m_violationMutex;
    std::string m_firstViolation;
    std::atomic<int> m_narrowPhaseCalls{0};
    std::atomic<int> m_captures{0};
};

template <class Pairs, class ExactPair, class ParkedPair>
void ContactCache::follow(const Pairs& pairs, const ExactPair& exactPair, const ParkedPair& parkedPair)
{
    // parked entries whose bodies are awake again come back below if their pair is listed, else go
    for (auto it = m_parked.begin(); it != m_parked.end();)
    {
        const auto listed =
            std::lower_bound(pairs.begin(), pairs.end(), it->first,
                             [](const auto& pair, std::uint64_t wanted) { return key(pair.a, pair.b) < wanted; });
        const bool keep =
            parkedPair(it->second.a, it->second.b) || (listed != pairs.end() && key(listed->a, listed->b) == it->first);
        it = keep ? std::next(it) : m_parked.erase(it);
    }
    // both lists are sorted by (a, b): one merge
    m_previous.swap(m_entries);
    m_entries.resize(pairs.size());
    std::size_t old = 0;
    const auto leave = [&](ContactEntry& entry)
    {
        if (parkedPair(entry.a, entry.b))
        {
            m_parked[key(entry.a, entry.b)] = std::move(entry);
        }
    };
    for (std::size_t k = 0; k < pairs.size(); ++k)
    {
        const std::uint64_t wanted = key(pairs[k].a, pairs[k].b);
        while (old < m_previous.size() && key(m_previous[old].a, m_previous[old].b) < wanted)
        {
            leave(m_previous[old++]);
        }
        ContactEntry& entry = m_entries[k];
        const auto parked = m_parked.empty() ? m_parked.end() : m_parked.find(wanted);
        if (old < m_previous.size() && key(m_previous[old].a, m_previous[old].b) == wanted)
        {
            entry = std::move(m_previous[old++]);
        }
        else if (parked != m_parked.end())
        {
            entry = std::move(parked->second);
            m_parked.erase(parked);
        }
        else
        {
            entry.points.clear();
            entry.captured = false;
        }
        entry.a = pairs[k].a;
        entry.b = pairs[k].b;
        entry.exact = exactPair(pairs[k].a, pairs[k].b);
    }
    for (; old < m_previous.size(); ++old)
    {
        leave(m_previous[old]);
    }
}

} // namespace impulse
