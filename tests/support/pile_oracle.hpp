// SPDX-License-Identifier: MIT
// Test support: the oracles of the reference piles (scenarios.md) as a run that can be saved and
// continued bit for bit. The pile tests use it in one go; impulse_pile_oracle uses it to spread a run
// of hours over several sittings, with the same trajectory and the same verdict.
//
// - Scenes 11 and 12 (balls and cubes of size r fall into a box whose inner walls are at x, y = +-2):
//   every 100 steps no body is outside the box, and at the end the deepest penetration of any two
//   bodies is under 1 % of r. The deepest pair every 50 steps is reported, and not judged.
// - Scene 14 (nonconvex meshes fall into a box): at the end the kinetic energy is under 1 % of its
//   peak, and no pair, sampled every 50 steps, is deeper than 1 % of the smaller body's size.
#pragma once

#include "support/penetration.hpp"
#include "support/scene_run.hpp"

#include <impulse/io/scene.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <fstream>
#include <optional>
#include <ostream>
#include <sstream>
#include <stdexcept>
#include <string>
#include <string_view>
#include <variant>
#include <vector>

namespace impulse::test
{

enum class PileOracleKind
{
    StaysInTheBox, ///< scenes 11 and 12
    Settles,       ///< scene 14
};

/// The oracle's running figures: what a checkpoint keeps besides the world's state.
struct PileFigures
{
    long long step = 0;         ///< steps taken since the scene's start
    Real peakKinetic = 0.0;     ///< joules, over every step so far
    Real deepest = 0.0;         ///< deepest penetration so far, sampled every 50 steps, metres
    Real deepestRelative = 0.0; ///< the same relative to the smaller body's size (its bounding diameter)
    /// Where deepestRelative was sampled: the step and the pair of bodies (0 when none has overlapped),
    /// so that a deep figure can be looked into from the checkpoint before it.
    long long deepestStep = 0;
    std::uint32_t deepestFirst = 0;
    std::uint32_t deepestSecond = 0;
};

/// One limit of the oracle at the end of the run: it holds when value < limit.
struct PileCheck
{
    std::string what;
    Real value = 0.0;
    Real limit = 0.0;
    bool holds() const { return value < limit; }
};

class PileRun
{
  public:
    /// `size` is r for StaysInTheBox (the radius or half side the 1 % is taken of); Settles measures
    /// each pair against its smaller body and ignores it.
    PileRun(io::Scene scene, PileOracleKind kind, Real size = 0.0)
        : scene_(std::move(scene)), kind_(kind), size_(size), steps_(std::llround(scene_.duration / scene_.options.dt))
    {
        for (std::uint32_t i = 0; i < scene_.world.bodyCount(); ++i)
        {
            if (const auto* box = std::get_if<Box>(&scene_.world.shape({i})))
            {
                wallTop_ = std::max(wallTop_, scene_.world.state({i}).position.z() + box->halfExtents.z());
            }
        }
        if (kind_ == PileOracleKind::StaysInTheBox && (wallTop_ <= 1.0 || !(size_ > 0.0)))
        {
            throw std::invalid_argument(scene_.name + ": not a pile in a box (walls " + std::to_string(wallTop_) +
                                        " m high, size " + std::to_string(size_) + ")");
        }
    }

    io::Scene& scene() { return scene_; }
    const World& world() const { return scene_.world; }
    const PileFigures& figures() const { return figures_; }
    long long totalSteps() const { return steps_; }
    bool finished() const { return figures_.step >= steps_ || failure_.has_value(); }
    /// Set when a limit that is checked during the run has failed: the run stops there.
    const std::optional<std::string>& failure() const { return failure_; }

    /// One time step and the oracle's checks after it; a line of figures on `log` every simulated
    /// second.
    void step(std::ostream& log)
    {
        World& world = scene_.world;
        world.step(scene_.options);
        const long long k = ++figures_.step;
        figures_.peakKinetic = std::max(figures_.peakKinetic, world.kineticEnergy());
        if (kind_ == PileOracleKind::StaysInTheBox && k % 100 == 0)
        {
            const int escaped = bodiesOutOfTheBox();
            if (escaped > 0)
            {
                failure_ = scene_.name + ": " + std::to_string(escaped) +
                           " bodies out of the box at t = " + std::to_string(world.time()) + " s";
                return;
            }
        }
        // Scenes 11 and 12 judge the depth at the end only; their samples are figures, not a limit.
        if (k % 50 == 0)
        {
            const Penetration p = deepestPenetration(world);
            figures_.deepest = std::max(figures_.deepest, p.depth);
            if (p.relative > figures_.deepestRelative)
            {
                figures_.deepestRelative = p.relative;
                figures_.deepestStep = k;
                figures_.deepestFirst = p.first;
                figures_.deepestSecond = p.second;
            }
        }
        if (k % 1000 == 0)
        {
            log << scene_.name << " t " << world.time() << " s: kinetic " << world.kineticEnergy() << " J (peak "
                << figures_.peakKinetic << "), " << world.lastStepStats().contactPairs
                << " contacts, deepest sampled so far " << figures_.deepest << " m ("
                << 100.0 * figures_.deepestRelative << " % of the smaller body, " << deepestSample() << ")"
                << std::endl;
        }
    }

    /// Where the deepest relative overlap was sampled, as the log prints it: "step K, bodies i and j".
    std::string deepestSample() const
    {
        if (figures_.deepestStep == 0)
        {
            return "no overlap sampled";
        }
        return "step " + std::to_string(figures_.deepestStep) + ", bodies " + std::to_string(figures_.deepestFirst) +
               " and " + std::to_string(figures_.deepestSecond);
    }

    /// The limits that are judged at the end of the run.
    std::vector<PileCheck> finalChecks() const
    {
        if (kind_ == PileOracleKind::StaysInTheBox)
        {
            const Real depth = deepestPenetration(scene_.world).depth;
            return {{"deepest penetration at the end (fraction of r)", depth / size_, 0.01}};
        }
        return {{"kinetic energy at the end (fraction of the peak)",
                 scene_.world.kineticEnergy() / figures_.peakKinetic, 0.01},
                {"deepest sampled penetration (fraction of the smaller body)", figures_.deepestRelative, 0.01}};
    }

    /// Writes the world's state and the running figures to `path`, every number exactly (hexadecimal
    /// floating point), so that resume() continues as if the run had not stopped.
    void save(const std::string& path) const
    {
        const WorldSnapshot snapshot = scene_.world.snapshot();
        std::ofstream out(path, std::ios::trunc);
        out << kMagic << "\nscene " << scene_.name << "\nstep " << figures_.step << "\npeak_kinetic "
            << hex(figures_.peakKinetic) << "\ndeepest " << hex(figures_.deepest) << "\ndeepest_relative "
            << hex(figures_.deepestRelative) << "\ndeepest_sample " << figures_.deepestStep << ' '
            << figures_.deepestFirst << ' ' << figures_.deepestSecond << "\ntime " << hex(snapshot.time) << "\nbodies "
            << snapshot.bodies.size() << "\n";
        for (const BodyState& b : snapshot.bodies)
        {
            for (const Real value : stateValues(b))
            {
                out << hex(value) << ' ';
            }
            out << '\n';
        }
        out << "contacts " << snapshot.contacts.size() << "\n";
        for (std::size_t i = 0; i < snapshot.contacts.size(); ++i)
        {
            out << hex(snapshot.contacts[i]) << ((i + 1) % 15 == 0 || i + 1 == snapshot.contacts.size() ? '\n' : ' ');
        }
        out.flush();
        if (!out)
        {
            throw std::runtime_error(path + ": cannot write the checkpoint");
        }
    }

    /// Continues from a checkpoint that save() wrote for the same scene. Throws std::runtime_error
    /// naming the file and the field when it is not one, is cut short, or does not fit this scene.
    void resume(const std::string& path)
    {
        std::ifstream in(path);
        if (!in)
        {
            throw std::runtime_error(path + ": cannot open the checkpoint");
        }
        std::string line;
        // version 2 is version 3 without the contacts, version 1 also without the line deepest_sample
        std::getline(in, line);
        const bool hasContacts = line == kMagic;
        const bool hasSample = hasContacts || line == kMagicVersion2;
        if (!hasSample && line != kMagicVersion1)
        {
            throw std::runtime_error(path + ": line 1: not a pile checkpoint (expected \"" + std::string(kMagic) +
                                     "\")");
        }
        int lineNumber = 1;
        const auto field = [&](const std::string& name) -> std::string
        {
            ++lineNumber;
            std::string key;
            std::string value;
            if (!std::getline(in, line) || !(std::istringstream(line) >> key >> value) || key != name)
            {
                throw std::runtime_error(path + ": line " + std::to_string(lineNumber) + ": expected the field \"" +
                                         name + "\"");
            }
            return value;
        };
        const auto number = [&](const std::string& name, const std::string& text) -> Real
        {
            char* end = nullptr;
            const Real value = std::strtod(text.c_str(), &end);
            if (text.empty() || *end != '\0' || !std::isfinite(value))
            {
                throw std::runtime_error(path + ": line " + std::to_string(lineNumber) + ": " + name +
                                         ": not a finite number: \"" + text + "\"");
            }
            return value;
        };
        if (const std::string name = field("scene"); name != scene_.name)
        {
            throw std::runtime_error(path + ": scene: the checkpoint is of \"" + name + "\", not of \"" + scene_.name +
                                     "\"");
        }
        PileFigures figures;
        const Real step = number("step", field("step"));
        figures.step = static_cast<long long>(step);
        if (step != std::floor(step) || figures.step < 0 || figures.step > steps_)
        {
            throw std::runtime_error(path + ": step: " + std::to_string(step) + " is not a step of the scene's 0.." +
                                     std::to_string(steps_));
        }
        figures.peakKinetic = number("peak_kinetic", field("peak_kinetic"));
        figures.deepest = number("deepest", field("deepest"));
        figures.deepestRelative = number("deepest_relative", field("deepest_relative"));
        if (hasSample)
        {
            ++lineNumber;
            std::string key;
            long long sampleStep = -1;
            long long first = -1;
            long long second = -1;
            if (!std::getline(in, line) || !(std::istringstream(line) >> key >> sampleStep >> first >> second) ||
                key != "deepest_sample" || sampleStep < 0 || sampleStep > figures.step || first < 0 || second < 0 ||
                std::max(first, second) >= static_cast<long long>(scene_.world.bodyCount()))
            {
                throw std::runtime_error(path + ": line " + std::to_string(lineNumber) +
                                         ": expected the field \"deepest_sample\": a step up to the checkpoint's and "
                                         "two bodies of the scene");
            }
            figures.deepestStep = sampleStep;
            figures.deepestFirst = static_cast<std::uint32_t>(first);
            figures.deepestSecond = static_cast<std::uint32_t>(second);
        }
        WorldSnapshot snapshot;
        snapshot.time = number("time", field("time"));
        const Real bodies = number("bodies", field("bodies"));
        const auto count = static_cast<std::size_t>(std::max(bodies, Real(0.0)));
        if (bodies != static_cast<Real>(count) || count != scene_.world.bodyCount())
        {
            throw std::runtime_error(path + ": bodies: " + std::to_string(bodies) + " in the checkpoint, " +
                                     std::to_string(scene_.world.bodyCount()) + " in the scene");
        }
        snapshot.bodies.resize(count);
        for (std::size_t i = 0; i < count; ++i)
        {
            ++lineNumber;
            std::vector<Real> values;
            std::string token;
            if (std::getline(in, line))
            {
                std::istringstream tokens(line);
                while (tokens >> token)
                {
                    values.push_back(number("body " + std::to_string(i), token));
                }
            }
            if (values.size() != 16)
            {
                throw std::runtime_error(path + ": line " + std::to_string(lineNumber) + ": body " + std::to_string(i) +
                                         ": expected 16 numbers, found " + std::to_string(values.size()));
            }
            BodyState& b = snapshot.bodies[i];
            b.position = Vec3(values[0], values[1], values[2]);
            b.orientation = Quat(values[3], values[4], values[5], values[6]);
            b.linearVelocity = Vec3(values[7], values[8], values[9]);
            b.angularVelocity = Vec3(values[10], values[11], values[12]);
            b.angularMomentum = Vec3(values[13], values[14], values[15]);
        }
        if (hasContacts)
        {
            // the contact layer's points and loads: the next step starts from them
            const Real size = number("contacts", field("contacts"));
            const auto numbers = static_cast<std::size_t>(std::max(size, Real(0.0)));
            if (size != static_cast<Real>(numbers))
            {
                throw std::runtime_error(path + ": line " + std::to_string(lineNumber) +
                                         ": contacts: not a count: " + std::to_string(size));
            }
            snapshot.contacts.reserve(numbers);
            std::string token;
            while (snapshot.contacts.size() < numbers && in >> token)
            {
                snapshot.contacts.push_back(number("contacts", token));
            }
            if (snapshot.contacts.size() != numbers)
            {
                throw std::runtime_error(path + ": contacts: cut short after " +
                                         std::to_string(snapshot.contacts.size()) + " of " + std::to_string(numbers) +
                                         " numbers");
            }
        }
        try
        {
            scene_.world.restore(snapshot);
        }
        catch (const std::invalid_argument& error)
        {
            throw std::runtime_error(path + ": " + error.what());
        }
        figures_ = figures;
        failure_.reset();
    }

    /// A body's state as the checkpoint writes it: position, orientation (w, x, y, z), linear and
    /// angular velocity, angular momentum.
    static std::array<Real, 16> stateValues(const BodyState& b)
    {
        const Quat& q = b.orientation;
        return {b.position.x(),
                b.position.y(),
                b.position.z(),
                q.w(),
                q.x(),
                q.y(),
                q.z(),
                b.linearVelocity.x(),
                b.linearVelocity.y(),
                b.linearVelocity.z(),
                b.angularVelocity.x(),
                b.angularVelocity.y(),
                b.angularVelocity.z(),
                b.angularMomentum.x(),
                b.angularMomentum.y(),
                b.angularMomentum.z()};
    }

  private:
    static constexpr const char* kMagic = "impulse pile checkpoint 3";
    static constexpr const char* kMagicVersion2 = "impulse pile checkpoint 2";
    static constexpr const char* kMagicVersion1 = "impulse pile checkpoint 1";

    static std::string hex(Real value)
    {
        char text[40];
        std::snprintf(text, sizeof text, "%a", value);
        return text;
    }

    int bodiesOutOfTheBox() const
    {
        int escaped = 0;
        for (const BodyId body : scene_.dynamicBodies)
        {
            const Vec3 x = scene_.world.state(body).position;
            const bool inside = std::abs(x.x()) < 2.0 && std::abs(x.y()) < 2.0 && x.z() > 0.0 && x.z() < wallTop_;
            escaped += inside ? 0 : 1;
        }
        return escaped;
    }

    io::Scene scene_;
    PileOracleKind kind_;
    Real size_;
    long long steps_;
    Real wallTop_ = 0.0; ///< the highest point of the static boxes
    PileFigures figures_;
    std::optional<std::string> failure_;
};

/// A shipped reference pile and how its oracle judges it; kReferencePiles is in the order of the names.
struct ReferencePile
{
    std::string_view name;
    PileOracleKind kind;
    Real size; ///< r of scenes 11 and 12
};

inline constexpr std::array<ReferencePile, 6> kReferencePiles = {{
    {"box_pile_1000", PileOracleKind::StaysInTheBox, 0.1},
    {"box_pile_10000", PileOracleKind::StaysInTheBox, 0.1},
    {"nonconvex_pile_1000", PileOracleKind::Settles, 0.0},
    {"nonconvex_pile_200", PileOracleKind::Settles, 0.0},
    {"sphere_pile_1000", PileOracleKind::StaysInTheBox, 0.1},
    {"sphere_pile_10000", PileOracleKind::StaysInTheBox, 0.1},
}};

/// The reference pile of that name; nullptr when there is none.
inline const ReferencePile* findReferencePile(std::string_view name)
{
    const auto pile = std::find_if(kReferencePiles.begin(), kReferencePiles.end(),
                                   [&](const ReferencePile& candidate) { return candidate.name == name; });
    return pile == kReferencePiles.end() ? nullptr : &*pile;
}

/// The pile's run as its test makes it: the shipped scene, on one thread. ctest runs tests side by
/// side, a formed pile is one island, and the trajectory is the same at any thread count.
inline PileRun referencePileRun(const ReferencePile& pile)
{
    PileRun run(loadReferenceScene(std::string(pile.name)), pile.kind, pile.size);
    run.scene().options.threads = 1;
    return run;
}

} // namespace impulse::test
