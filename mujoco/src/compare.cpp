// SPDX-License-Identifier: MIT
// impulse compare: one scene, two engines, the same measurements on both.
#include <impulse/mujoco/compare.hpp>
#include <impulse/mujoco/mjcf_export.hpp>
#include <impulse/mujoco/mujoco.hpp>

#include <algorithm>
#include <cctype>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <limits>
#include <optional>

namespace impulse::mujoco
{
namespace
{

constexpr Real kNaN = std::numeric_limits<Real>::quiet_NaN();
constexpr Real kRestSpeed = 1e-3; ///< m/s: slower than this counts as at rest
constexpr Real kSlipSpeed = 1e-3; ///< m/s: contact-point slip below this counts as rolling

struct Sample
{
    Vec3 x;
    Quat q;
    Vec3 v;
    Vec3 w;
};

enum class Kind
{
    Drop,     ///< one ball falling under gravity
    Spin,     ///< one ball launched along the ground
    Block,    ///< one block on the ground or an incline
    Exchange, ///< no gravity: bodies meet and leave
    Stack,    ///< several bodies under gravity
};

// What the scene holds, and the few numbers of it the figures need.
struct SceneFacts
{
    Kind kind = Kind::Stack;
    std::string name;
    Vec3 up = Vec3::UnitZ();
    Real radius = 0.0; ///< of the single ball
    std::vector<Real> mass;
    std::vector<Vec3> inertia;
    /// a static mesh body (a peg): the end position is also measured from the vertical through
    /// its centre of mass
    std::optional<Vec3> staticMesh;
};

SceneFacts factsOf(const io::Scene& scene)
{
    SceneFacts facts;
    facts.name = scene.name;
    const World& world = scene.world;
    const Vec3 g = world.gravity();
    for (const BodyId id : scene.dynamicBodies)
    {
        facts.mass.push_back(world.mass(id));
        facts.inertia.push_back(world.principalInertia(id));
    }
    if (g.norm() == 0.0)
    {
        facts.kind = Kind::Exchange;
        return facts;
    }
    facts.up = -g.normalized();
    for (std::uint32_t i = 0; i < world.bodyCount() && !facts.staticMesh; ++i)
    {
        if (!world.isDynamic(BodyId{i}) && std::holds_alternative<Mesh>(world.shape(BodyId{i})))
        {
            facts.staticMesh = world.state(BodyId{i}).position;
        }
    }
    if (scene.dynamicBodies.size() != 1)
    {
        facts.kind = Kind::Stack;
        return facts;
    }
    const BodyId body = scene.dynamicBodies[0];
    if (const auto* sphere = std::get_if<Sphere>(&world.shape(body)))
    {
        facts.radius = sphere->radius;
        const BodyState s = world.state(body);
        const Vec3 horizontal = s.linearVelocity - s.linearVelocity.dot(facts.up) * facts.up;
        facts.kind = horizontal.norm() > 0.0 || s.angularVelocity.norm() > 0.0 ? Kind::Spin : Kind::Drop;
        return facts;
    }
    facts.kind = Kind::Block;
    return facts;
}

// Measurements taken step by step on one run.
class Tracker
{
  public:
    Tracker(const SceneFacts& facts, Real dt) : m_facts(facts), m_dt(dt) {}

    void sample(Real t, const std::vector<Sample>& s)
    {
        if (m_first.empty())
        {
            m_first = s;
            m_previous = s;
            m_top = 0;
            for (std::size_t i = 0; i < s.size(); ++i)
            {
                if (s[i].x.dot(m_facts.up) > s[m_top].x.dot(m_facts.up))
                {
                    m_top = i;
                }
            }
        }
        if (!s.empty())
        {
            const Real height = s[0].x.dot(m_facts.up);
            const Real vUp = s[0].v.dot(m_facts.up);
            const Real previousUp = m_previous[0].v.dot(m_facts.up);
            if (previousUp > 0.0 && vUp <= 0.0)
            {
                m_apexes.push_back(std::max(height, m_previous[0].x.dot(m_facts.up)));
            }
            if (s[0].v.norm() >= kRestSpeed)
            {
                m_lastMoving = t;
            }
            const Vec3 slip = s[0].v + s[0].w.cross(-m_facts.radius * m_facts.up);
            if (std::isnan(m_slipEnd) && t > 0.0 && slip.norm() < kSlipSpeed)
            {
                m_slipEnd = t;
            }
            m_topDrift = std::max(m_topDrift, (s[m_top].x - m_first[m_top].x).norm());
        }
        m_previous = s;
        m_time = t;
    }

    void penetration(Real depth) { m_deepest = std::max(m_deepest, depth); }

    const std::vector<Sample>& first() const { return m_first; }
    const std::vector<Sample>& last() const { return m_previous; }
    const std::vector<Real>& apexes() const { return m_apexes; }
    Real restTime() const { return m_previous[0].v.norm() < kRestSpeed ? m_lastMoving + m_dt : kNaN; }
    Real slipEnd() const { return m_slipEnd; }
    Real topDrift() const { return m_topDrift; }
    Real deepest() const { return m_deepest; }

    Real energy(const std::vector<Sample>& s) const
    {
        Real e = 0.0;
        for (std::size_t i = 0; i < s.size(); ++i)
        {
            const Mat3 r = s[i].q.normalized().toRotationMatrix();
            const Vec3 wb = r.transpose() * s[i].w;
            e += 0.5 * m_facts.mass[i] * s[i].v.squaredNorm() + 0.5 * wb.dot(m_facts.inertia[i].cwiseProduct(wb));
        }
        return e;
    }
    Vec3 momentum(const std::vector<Sample>& s) const
    {
        Vec3 p = Vec3::Zero();
        for (std::size_t i = 0; i < s.size(); ++i)
        {
            p += m_facts.mass[i] * s[i].v;
        }
        return p;
    }
    Real maxSpeed(const std::vector<Sample>& s) const
    {
        Real speed = 0.0;
        for (const Sample& x : s)
        {
            speed = std::max(speed, x.v.norm());
        }
        return speed;
    }

  private:
    const SceneFacts& m_facts;
    Real m_dt;
    std::vector<Sample> m_first;
    std::vector<Sample> m_previous;
    std::size_t m_top = 0;
    std::vector<Real> m_apexes;
    Real m_lastMoving = 0.0;
    Real m_slipEnd = kNaN;
    Real m_topDrift = 0.0;
    Real m_deepest = 0.0;
    Real m_time = 0.0;
};

// Deepest penetration of the bodies placed as `d` says, by MuJoCo's collision detection.
Real deepestPenetration(const mjModel* m, mjData* d)
{
    mj_kinematics(m, d);
    mj_collision(m, d);
    Real deepest = 0.0;
    for (int i = 0; i < d->ncon; ++i)
    {
        deepest = std::max(deepest, -d->contact[i].dist);
    }
    return deepest;
}

std::string fmt(Real value, const char* format = "%.6g")
{
    if (std::isnan(value))
    {
        return "never";
    }
    char buffer[64];
    std::snprintf(buffer, sizeof buffer, format, value);
    return buffer;
}

std::string fmtVec(const Vec3& v)
{
    std::string text = "(";
    text += fmt(v.x(), "%.5f");
    text += ", ";
    text += fmt(v.y(), "%.5f");
    text += ", ";
    text += fmt(v.z(), "%.5f");
    text += ")";
    return text;
}

} // namespace

bool isModelFile(const std::filesystem::path& path)
{
    std::string extension = path.extension().string();
    std::transform(extension.begin(), extension.end(), extension.begin(),
                   [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
    return extension == ".xml" || extension == ".mjcf";
}

Comparison compareScene(const std::filesystem::path& scenePath, double timeconst)
{
    // an MJCF model runs as it is on both sides (MuJoCo with the model's own contact parameters); a
    // scene file is exported to MJCF for MuJoCo
    const bool modelInput = isModelFile(scenePath);
    const auto load = [&] { return modelInput ? loadMjcfScene(scenePath) : io::loadScene(scenePath); };
    io::Scene scene = load();
    if (modelInput && std::isnan(scene.duration))
    {
        throw ModelError(scenePath.string() +
                         ": no duration: add <numeric name=\"impulse_duration\" data=\"SECONDS\"/> "
                         "to the model's <custom>");
    }
    const SceneFacts facts = factsOf(scene);
    const Real dt = scene.options.dt;
    const long long steps = std::llround(scene.duration / dt);

    // both runs are judged by the same collision detector: MuJoCo's, on the model it runs
    const ModelPtr model = modelInput
                               ? loadModel(scenePath)
                               : loadModelFromString(exportMjcf(scene, timeconst), scenePath.string() + " (exported)");
    const DataPtr data(mj_makeData(model.get()));
    const DataPtr probe(mj_makeData(model.get()));
    if (model->nkey > 0)
    {
        mj_resetDataKeyframe(model.get(), data.get(), 0);
        mj_resetDataKeyframe(model.get(), probe.get(), 0);
    }
    mj_forward(model.get(), data.get());
    const Translation layout = translate(model.get(), data.get(), scenePath.string() + " (exported)");

    // ---- impulse ----
    Tracker ours(facts, dt);
    std::vector<Sample> samples(scene.dynamicBodies.size());
    const auto sampleWorld = [&](Real t)
    {
        for (std::size_t i = 0; i < samples.size(); ++i)
        {
            const BodyState s = scene.world.state(scene.dynamicBodies[i]);
            samples[i] = {s.position, s.orientation, s.linearVelocity, s.angularVelocity};
            writeLink(layout.links[i], s, model.get(), probe.get());
        }
        ours.sample(t, samples);
        ours.penetration(deepestPenetration(model.get(), probe.get()));
    };
    sampleWorld(0.0);
    for (long long k = 1; k <= steps; ++k)
    {
        scene.world.step(scene.options);
        sampleWorld(static_cast<Real>(k) * dt);
    }

    // ---- MuJoCo ----
    Tracker theirs(facts, dt);
    const auto sampleData = [&](Real t)
    {
        for (std::size_t i = 0; i < samples.size(); ++i)
        {
            const LinkState s = readLink(layout.links[i], model.get(), data.get());
            samples[i] = {s.position, s.orientation, s.linearVelocity, s.angularVelocity};
        }
        theirs.sample(t, samples);
        std::copy(data->qpos, data->qpos + model->nq, probe->qpos);
        theirs.penetration(deepestPenetration(model.get(), probe.get()));
    };
    sampleData(0.0);
    for (long long k = 1; k <= steps; ++k)
    {
        mj_step(model.get(), data.get());
        sampleData(static_cast<Real>(k) * dt);
    }

    // wall time per step: separate runs with nothing else in the loop
    io::Scene timed = load();
    auto start = std::chrono::steady_clock::now();
    for (long long k = 1; k <= steps; ++k)
    {
        timed.world.step(timed.options);
    }
    const double oursSeconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    mj_resetData(model.get(), data.get());
    if (model->nkey > 0)
    {
        mj_resetDataKeyframe(model.get(), data.get(), 0);
    }
    start = std::chrono::steady_clock::now();
    for (long long k = 1; k <= steps; ++k)
    {
        mj_step(model.get(), data.get());
    }
    const double theirSeconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();

    Comparison c;
    c.scene = scenePath.string() + (scene.name.empty() ? "" : " (" + scene.name + ")");
    c.steps = steps;
    c.dt = dt;
    c.timeconst = modelInput ? 0.0 : (timeconst > 0.0 ? timeconst : defaultTimeconst(dt));
    const auto row = [&](std::string label, std::string a, std::string b, std::string oracle = "") {
        c.rows.push_back({std::move(label), std::move(a), std::move(b), std::move(oracle)});
    };
    const std::string& name = facts.name;

    switch (facts.kind)
    {
    case Kind::Drop:
    {
        for (std::size_t k = 0; k < 3; ++k)
        {
            std::string oracle;
            if (name == "ball_drop_elastic")
            {
                oracle = "2.000 (0.1 %)";
            }
            else if (name == "ball_drop_damped")
            {
                oracle = fmt(0.1 + 1.9 * std::pow(0.25, static_cast<Real>(k + 1)), "%.5f") + " (1 %)";
            }
            row("apex " + std::to_string(k + 1) + " (m)",
                k < ours.apexes().size() ? fmt(ours.apexes()[k], "%.5f") : "none",
                k < theirs.apexes().size() ? fmt(theirs.apexes()[k], "%.5f") : "none", oracle);
        }
        const auto range = [](const std::vector<Real>& a)
        {
            if (a.empty())
            {
                return std::string("none");
            }
            return fmt(*std::min_element(a.begin(), a.end()), "%.5f") + " .. " +
                   fmt(*std::max_element(a.begin(), a.end()), "%.5f");
        };
        row("all apexes (m)", range(ours.apexes()), range(theirs.apexes()),
            name == "ball_drop_elastic" ? "1.998 .. 2.002" : "");
        row("at rest from (s)", fmt(ours.restTime(), "%.4f"), fmt(theirs.restTime(), "%.4f"),
            name == "ball_drop_damped" ? "<= 1.92" : (name == "ball_drop_elastic" ? "never" : ""));
        break;
    }
    case Kind::Spin:
        row("slip ends at (s)", fmt(ours.slipEnd(), "%.4f"), fmt(theirs.slipEnd(), "%.4f"),
            name == "spin_friction" ? "0.1963" : "");
        row("final velocity (m/s)", fmtVec(ours.last()[0].v), fmtVec(theirs.last()[0].v),
            name == "spin_friction" ? "(1.42857, -0.08571, 0) (0.5 %)" : "");
        break;
    case Kind::Block:
    {
        const Real a = (ours.last()[0].x - ours.first()[0].x).norm();
        const Real b = (theirs.last()[0].x - theirs.first()[0].x).norm();
        std::string oracle;
        if (name == "incline_stick" || name == "incline_rest_elastic")
        {
            oracle = "< 1e-4";
        }
        else if (name == "incline_slide")
        {
            oracle = "3.2177 (1 %)";
        }
        row("displacement at end (m)", fmt(a), fmt(b), oracle);
        row("final angular speed (rad/s)", fmt(ours.last()[0].w.norm()), fmt(theirs.last()[0].w.norm()),
            name == "incline_slide" ? "0 (no tipping)" : "");
        if (facts.staticMesh)
        {
            // MuJoCo collides meshes as their convex hulls: a ring can rest on a peg's top there
            const auto fromAxis = [&](const Vec3& x)
            {
                const Vec3 offset = x - *facts.staticMesh;
                return (offset - offset.dot(facts.up) * facts.up).norm();
            };
            const bool ring = name == "ring_on_peg";
            row("end off static mesh axis (m)", fmt(fromAxis(ours.last()[0].x)), fmt(fromAxis(theirs.last()[0].x)),
                ring ? "< 0.1 (around the peg)" : "");
            row("end height (m)", fmt(ours.last()[0].x.dot(facts.up)), fmt(theirs.last()[0].x.dot(facts.up)),
                ring ? "0.05 (flat on the ground)" : "");
        }
        break;
    }
    case Kind::Exchange:
    {
        for (std::size_t i = 0; i < ours.last().size() && i < 6; ++i)
        {
            std::string oracle;
            if (name == "ball_ball_headon")
            {
                oracle = i == 0 ? "(-1, 0, 0)" : "(1, 0, 0)";
            }
            else if (name == "ball_ball_oblique")
            {
                oracle = i == 0 ? "(-0.125, -0.6495, 0)" : "(0.125, 0.6495, 0)";
            }
            else if (name == "newton_cradle")
            {
                oracle = i == 5 ? "(1, 0, 0)" : "(0, 0, 0) (1 %)";
            }
            row("velocity body " + std::to_string(i) + " (m/s)", fmtVec(ours.last()[i].v), fmtVec(theirs.last()[i].v),
                oracle);
        }
        // momentum relative to the sum of the bodies' momenta |m v| (the total is zero head on)
        const auto drift = [&](const Tracker& t)
        {
            Real scale = 0.0;
            for (std::size_t i = 0; i < t.first().size(); ++i)
            {
                scale += facts.mass[i] * t.first()[i].v.norm();
            }
            const Real e0 = t.energy(t.first());
            return std::pair<Real, Real>{(t.momentum(t.last()) - t.momentum(t.first())).norm() /
                                             std::max(scale, 1e-300),
                                         (t.energy(t.last()) - e0) / std::max(e0, 1e-300)};
        };
        const auto [pa, ea] = drift(ours);
        const auto [pb, eb] = drift(theirs);
        row("momentum change (rel. sum m|v|)", fmt(pa, "%.2e"), fmt(pb, "%.2e"), "< 1e-9");
        row("kinetic energy change (rel.)", fmt(ea, "%.2e"), fmt(eb, "%.2e"),
            name == "ball_ball_oblique" ? "" : "< 1e-9");
        break;
    }
    case Kind::Stack:
        row("top body drift (m)", fmt(ours.topDrift(), "%.3g"), fmt(theirs.topDrift(), "%.3g"),
            name.rfind("box_stack", 0) == 0 ? "< 1e-3" : "");
        row("fastest body at end (m/s)", fmt(ours.maxSpeed(ours.last()), "%.3g"),
            fmt(theirs.maxSpeed(theirs.last()), "%.3g"), name.rfind("box_stack", 0) == 0 ? "< 1e-4" : "");
        break;
    }
    row("deepest penetration (m)", fmt(ours.deepest(), "%.3g"), fmt(theirs.deepest(), "%.3g"),
        facts.kind == Kind::Drop ? "< " + fmt(0.01 * facts.radius, "%.3g") + " (1 % of r)" : "");
    c.impulseMsPerStep = steps > 0 ? 1e3 * oursSeconds / static_cast<double>(steps) : 0.0;
    c.mujocoMsPerStep = steps > 0 ? 1e3 * theirSeconds / static_cast<double>(steps) : 0.0;
    return c;
}

} // namespace impulse::mujoco
