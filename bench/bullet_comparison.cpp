// SPDX-License-Identifier: MIT
// The same scene in impulse and in Bullet 3.24, in the same run on the same machine: milliseconds
// per step of each and their ratio.
//
//   impulse_bench_bullet [--steps N] [--warm-up W] [--threads T] [SCENE.json ...]
//
// Default scenes: sphere_pile_10000 and box_pile_1000. Each scene is loaded once; the Bullet world
// is built from that loaded World before impulse takes a step (same bodies, masses, principal
// inertias, poses, velocities and gravity), then impulse is stepped W + N times with `threads` T
// (default 1), then Bullet the same W + N times. By default W = 0 and N is the scene's duration / dt
// (the piles: 5 s at 1 ms, 5000 steps), because the pile-up is the costly phase and both engines
// must be measured over the same simulated interval; --steps and --warm-up shorten it for checks.
//
// Bullet is set up as it ships: btDefaultCollisionConfiguration, btCollisionDispatcher,
// btDbvtBroadphase, btSequentialImpulseConstraintSolver at 10 iterations (its default, set
// explicitly), btDiscreteDynamicsWorld, single precision and single-threaded as Debian's
// libbullet-dev builds it; sleeping is off for every dynamic body (DISABLE_DEACTIVATION), as impulse
// never sleeps; each call stepSimulation(dt, 0) is exactly one internal step of exactly dt (checked).
// Bullet combines the friction and the restitution of two bodies by multiplying them, impulse takes a
// pair's coefficients from its material pair: each Bullet body gets sqrt(mu) and sqrt(eps) of the
// scene's one material so that every Bullet pair sees impulse's mu and eps. Scenes with more than one
// material, and bodies other than spheres, boxes and planes, are refused.
//
// One row per engine: bodies, contacts per step (impulse: pairs touching at the contact graph;
// Bullet: contact manifolds holding at least one point), median and 10th-90th percentile of a
// step's wall time over the N measured steps, wall and processor seconds of all W + N steps (on a
// busy machine the processor time shows how much of the wall time was waiting), and the figures of the
// oracle of reference scenes 11 and 12 at the end, computed the same way for both: dynamic bodies
// outside the box (centre beyond the inner faces of the static walls, below z = 0 or above the
// walls' top) and the deepest penetration between two dynamic bodies in percent of r (spheres: the
// radius; boxes: the smallest half side; exact depth, for boxes the minimum overlap over the 15
// separating axes). Then impulse's final state hash and the ratio of the two medians.
#include <impulse/io/scene.hpp>

#include <algorithm>
#include <array>
#include <btBulletDynamicsCommon.h>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <filesystem>
#include <limits>
#include <memory>
#include <set>
#include <stdexcept>
#include <string>
#include <unordered_map>
#include <vector>

namespace
{

using impulse::Pose;
using impulse::Quat;
using impulse::Real;
using impulse::Vec3;
using Clock = std::chrono::steady_clock;

constexpr Real infinity = std::numeric_limits<Real>::infinity();

double cpuSecondsSince(std::clock_t since)
{
    return static_cast<double>(std::clock() - since) / CLOCKS_PER_SEC;
}

double milliseconds(Clock::time_point since)
{
    return std::chrono::duration<double, std::milli>(Clock::now() - since).count();
}

double percentile(std::vector<double> values, double q)
{
    if (values.empty())
    {
        return 0.0;
    }
    std::sort(values.begin(), values.end());
    return values[static_cast<std::size_t>(q * static_cast<double>(values.size() - 1))];
}

struct Settings
{
    int steps = -1; ///< measured steps; negative: the scene's duration / dt
    int warmUp = 0;
    int threads = 1;
};

/// What one engine did over one scene.
struct Run
{
    std::vector<double> stepMs; ///< measured steps
    double contacts = 0.0;      ///< per measured step
    double totalSeconds = 0.0;  ///< wall time of all steps, warm-up included
    double cpuSeconds = 0.0;    ///< processor time of all steps (every thread), warm-up included
    std::vector<Pose> poses;    ///< final pose of each dynamic body, in world body order
};

/// The scene's one material, as impulse applies it to a pair and as each Bullet body carries it.
struct Coefficients
{
    impulse::PairCoefficients pair;
    btScalar bodyFriction = 0;
    btScalar bodyRestitution = 0;
};

std::string bodyLabel(const impulse::io::Scene& scene, std::uint32_t k)
{
    const std::string& name = scene.bodyNames.at(k);
    return name.empty() ? "body #" + std::to_string(k) : "body '" + name + "' (#" + std::to_string(k) + ")";
}

Coefficients coefficientsOf(const impulse::io::Scene& scene, const std::string& label)
{
    const impulse::World& world = scene.world;
    std::set<std::uint32_t> used;
    for (std::uint32_t k = 0; k < world.bodyCount(); ++k)
    {
        used.insert(world.material(impulse::BodyId{k}).index);
    }
    if (used.size() != 1)
    {
        throw std::runtime_error(label + ": its bodies use " + std::to_string(used.size()) +
                                 " materials; the comparison needs exactly one, since Bullet multiplies per-body "
                                 "friction and restitution and matches impulse's pair values only for one material");
    }
    const impulse::MaterialId material{*used.begin()};
    Coefficients c;
    c.pair = world.pairCoefficients(material, material);
    c.bodyFriction = static_cast<btScalar>(std::sqrt(c.pair.friction));
    c.bodyRestitution = static_cast<btScalar>(std::sqrt(c.pair.restitution));
    return c;
}

/// The dynamic bodies in world body order, the order of the poses of a Run.
std::vector<impulse::BodyId> dynamicBodies(const impulse::World& world)
{
    std::vector<impulse::BodyId> ids;
    for (std::uint32_t k = 0; k < world.bodyCount(); ++k)
    {
        if (world.isDynamic(impulse::BodyId{k}))
        {
            ids.push_back(impulse::BodyId{k});
        }
    }
    return ids;
}

btVector3 toBullet(const Vec3& v)
{
    return {static_cast<btScalar>(v.x()), static_cast<btScalar>(v.y()), static_cast<btScalar>(v.z())};
}

btQuaternion toBullet(const Quat& q)
{
    return {static_cast<btScalar>(q.x()), static_cast<btScalar>(q.y()), static_cast<btScalar>(q.z()),
            static_cast<btScalar>(q.w())};
}

Vec3 fromBullet(const btVector3& v)
{
    return {v.x(), v.y(), v.z()};
}

Quat fromBullet(const btQuaternion& q)
{
    return Quat(q.w(), q.x(), q.y(), q.z()).normalized();
}

/// A Bullet world equivalent to an impulse World. Members are destroyed in reverse order: the world
/// before its bodies, the bodies before their shapes, the shapes before the solver and the rest.
struct BulletScene
{
    std::unique_ptr<btDefaultCollisionConfiguration> configuration;
    std::unique_ptr<btCollisionDispatcher> dispatcher;
    std::unique_ptr<btDbvtBroadphase> broadphase;
    std::unique_ptr<btSequentialImpulseConstraintSolver> solver;
    std::vector<std::unique_ptr<btCollisionShape>> shapes;
    std::vector<std::unique_ptr<btRigidBody>> bodies;
    std::unique_ptr<btDiscreteDynamicsWorld> world;
    std::vector<btRigidBody*> dynamicBodies; ///< in world body order
};

std::unique_ptr<btCollisionShape> bulletShape(const impulse::io::Scene& scene, std::uint32_t k,
                                              const std::string& label)
{
    const impulse::Shape& shape = scene.world.shape(impulse::BodyId{k});
    if (const auto* sphere = std::get_if<impulse::Sphere>(&shape))
    {
        return std::make_unique<btSphereShape>(static_cast<btScalar>(sphere->radius));
    }
    if (const auto* box = std::get_if<impulse::Box>(&shape))
    {
        return std::make_unique<btBoxShape>(toBullet(box->halfExtents));
    }
    if (const auto* plane = std::get_if<impulse::Plane>(&shape))
    {
        // both are the half-space normal . p <= offset in the body frame
        return std::make_unique<btStaticPlaneShape>(toBullet(plane->normal), static_cast<btScalar>(plane->offset));
    }
    const char* kind = std::holds_alternative<impulse::Capsule>(shape) ? "a capsule" : "a mesh";
    throw std::runtime_error(label + ": " + bodyLabel(scene, k) + " is " + kind +
                             "; the comparison takes spheres, boxes and planes only");
}

BulletScene buildBullet(const impulse::io::Scene& scene, const Coefficients& coefficients, const std::string& label)
{
    const impulse::World& world = scene.world;
    BulletScene b;
    b.configuration = std::make_unique<btDefaultCollisionConfiguration>();
    b.dispatcher = std::make_unique<btCollisionDispatcher>(b.configuration.get());
    b.broadphase = std::make_unique<btDbvtBroadphase>();
    b.solver = std::make_unique<btSequentialImpulseConstraintSolver>();
    for (std::uint32_t k = 0; k < world.bodyCount(); ++k)
    {
        b.shapes.push_back(bulletShape(scene, k, label));
    }
    b.world = std::make_unique<btDiscreteDynamicsWorld>(b.dispatcher.get(), b.broadphase.get(), b.solver.get(),
                                                        b.configuration.get());
    b.world->getSolverInfo().m_numIterations = 10;
    b.world->setGravity(toBullet(world.gravity()));
    for (std::uint32_t k = 0; k < world.bodyCount(); ++k)
    {
        const impulse::BodyId id{k};
        const bool dynamic = world.isDynamic(id);
        const impulse::BodyState state = world.state(id);
        // the body frame of impulse is the principal frame, centred on the centre of mass
        const btScalar mass = dynamic ? static_cast<btScalar>(world.mass(id)) : btScalar(0);
        const btVector3 inertia = dynamic ? toBullet(world.principalInertia(id)) : btVector3(0, 0, 0);
        btRigidBody::btRigidBodyConstructionInfo info(mass, nullptr, b.shapes[k].get(), inertia);
        info.m_startWorldTransform = btTransform(toBullet(state.orientation), toBullet(state.position));
        info.m_friction = coefficients.bodyFriction;
        info.m_restitution = coefficients.bodyRestitution;
        auto body = std::make_unique<btRigidBody>(info);
        if (dynamic)
        {
            body->setLinearVelocity(toBullet(state.linearVelocity));
            body->setAngularVelocity(toBullet(state.angularVelocity));
            body->setActivationState(DISABLE_DEACTIVATION);
            b.dynamicBodies.push_back(body.get());
        }
        b.world->addRigidBody(body.get());
        b.bodies.push_back(std::move(body));
    }
    return b;
}

int stepsOf(const impulse::io::Scene& scene, const Settings& settings)
{
    if (settings.steps >= 0)
    {
        return settings.steps;
    }
    return static_cast<int>(std::lround(scene.duration / scene.options.dt));
}

// Steps warm-up and measured steps alike with stepOnce(k), timing each, and counts the contacts
// (contactsNow(), outside the timing) of the measured ones: the same harness for both engines.
template <typename StepOnce, typename ContactsNow>
Run timeSteps(const Settings& settings, int steps, StepOnce stepOnce, ContactsNow contactsNow)
{
    Run run;
    run.stepMs.reserve(static_cast<std::size_t>(steps));
    const auto begin = Clock::now();
    const std::clock_t cpuBegin = std::clock();
    for (int k = 0; k < settings.warmUp + steps; ++k)
    {
        const auto start = Clock::now();
        stepOnce(k);
        const double ms = milliseconds(start);
        if (k >= settings.warmUp)
        {
            run.stepMs.push_back(ms);
            run.contacts += contactsNow();
        }
    }
    run.totalSeconds = milliseconds(begin) / 1000.0;
    run.cpuSeconds = cpuSecondsSince(cpuBegin);
    run.contacts /= std::max(1, steps);
    return run;
}

Run runImpulse(impulse::io::Scene& scene, const Settings& settings)
{
    scene.options.threads = settings.threads;
    Run run = timeSteps(
        settings, stepsOf(scene, settings), [&](int) { scene.world.step(scene.options); },
        [&] { return scene.world.lastStepStats().contactPairs; });
    for (const impulse::BodyId id : dynamicBodies(scene.world))
    {
        const impulse::BodyState state = scene.world.state(id);
        run.poses.push_back(Pose::from(state.position, state.orientation));
    }
    return run;
}

int touchingManifolds(btDispatcher& dispatcher)
{
    int count = 0;
    for (int m = 0; m < dispatcher.getNumManifolds(); ++m)
    {
        count += dispatcher.getManifoldByIndexInternal(m)->getNumContacts() > 0 ? 1 : 0;
    }
    return count;
}

Run runBullet(BulletScene& bullet, const impulse::io::Scene& scene, const Settings& settings)
{
    const auto dt = static_cast<btScalar>(scene.options.dt);
    const auto stepOnce = [&](int k)
    {
        // maxSubSteps 0, Bullet's variable time step: one internal step of exactly dt by construction.
        // (dt, 1, dt) also takes one per call, through its accumulator of fixed steps.
        const int internalSteps = bullet.world->stepSimulation(dt, 0);
        if (internalSteps != 1)
        {
            throw std::runtime_error("Bullet took " + std::to_string(internalSteps) + " internal steps at step " +
                                     std::to_string(k) + "; expected exactly one");
        }
    };
    Run run =
        timeSteps(settings, stepsOf(scene, settings), stepOnce, [&] { return touchingManifolds(*bullet.dispatcher); });
    for (const btRigidBody* body : bullet.dynamicBodies)
    {
        const btTransform& transform = body->getCenterOfMassTransform();
        run.poses.push_back(Pose::from(fromBullet(transform.getOrigin()), fromBullet(transform.getRotation())));
    }
    return run;
}

// ---- the oracle's figures: bodies outside the box, deepest penetration between dynamic bodies ----

/// The inside of the box the piles fall into: between the inner faces of the static boxes that lie
/// wholly on one side of x = 0 (or y = 0), above z = 0 and below the top of the highest static box.
struct Container
{
    Real xMin = -infinity;
    Real xMax = infinity;
    Real yMin = -infinity;
    Real yMax = infinity;
    Real top = infinity;
};

Container containerOf(const impulse::World& world)
{
    Container c;
    bool walls = false;
    for (std::uint32_t k = 0; k < world.bodyCount(); ++k)
    {
        const impulse::BodyId id{k};
        const auto* box = std::get_if<impulse::Box>(&world.shape(id));
        if (world.isDynamic(id) || box == nullptr)
        {
            continue;
        }
        const impulse::BodyState state = world.state(id);
        const Vec3 reach = state.orientation.toRotationMatrix().cwiseAbs() * box->halfExtents;
        const Vec3 low = state.position - reach;
        const Vec3 high = state.position + reach;
        c.xMin = low.x() < 0.0 && high.x() < 0.0 ? std::max(c.xMin, high.x()) : c.xMin;
        c.xMax = low.x() > 0.0 && high.x() > 0.0 ? std::min(c.xMax, low.x()) : c.xMax;
        c.yMin = low.y() < 0.0 && high.y() < 0.0 ? std::max(c.yMin, high.y()) : c.yMin;
        c.yMax = low.y() > 0.0 && high.y() > 0.0 ? std::min(c.yMax, low.y()) : c.yMax;
        c.top = walls ? std::max(c.top, high.z()) : high.z();
        walls = true;
    }
    return c;
}

bool outside(const Container& c, const Vec3& p)
{
    return !p.allFinite() || p.x() < c.xMin || p.x() > c.xMax || p.y() < c.yMin || p.y() > c.yMax || p.z() < 0.0 ||
           p.z() > c.top;
}

/// Penetration depth of two oriented boxes: the smallest overlap of their projections on the 15
/// separating axes (3 + 3 face normals, 9 edge-edge cross products), exact for boxes; negative when
/// they are apart.
Real boxBoxDepth(const Pose& a, const Vec3& ha, const Pose& b, const Vec3& hb)
{
    const Vec3 t = b.position - a.position;
    Real depth = infinity;
    const auto overlap = [&](Vec3 axis)
    {
        const Real length = axis.norm();
        if (length < 1e-9)
        {
            return; // parallel edges: their cross product adds no axis
        }
        axis /= length;
        const Real ra = (a.rotation.transpose() * axis).cwiseAbs().dot(ha);
        const Real rb = (b.rotation.transpose() * axis).cwiseAbs().dot(hb);
        depth = std::min(depth, ra + rb - std::abs(t.dot(axis)));
    };
    for (int i = 0; i < 3; ++i)
    {
        overlap(a.rotation.col(i));
        overlap(b.rotation.col(i));
    }
    for (int i = 0; i < 3 && depth > 0.0; ++i)
    {
        for (int j = 0; j < 3; ++j)
        {
            overlap(a.rotation.col(i).cross(b.rotation.col(j)));
        }
    }
    return depth;
}

/// Penetration depth of a sphere (centre c, radius r) into a box; negative when apart.
Real sphereBoxDepth(const Vec3& c, Real r, const Pose& box, const Vec3& h)
{
    const Vec3 q = box.toLocal(c);
    const Vec3 clamped = q.cwiseMax(-h).cwiseMin(h);
    if (clamped != q)
    {
        return r - (q - clamped).norm();
    }
    return r + (h - q.cwiseAbs()).minCoeff();
}

/// Depth of two dynamic bodies' overlap in percent of the smaller r (sphere: radius, box: smallest
/// half side); negative when apart.
Real penetrationPercent(const impulse::Shape& sa, const Pose& a, const impulse::Shape& sb, const Pose& b)
{
    const auto* sphereA = std::get_if<impulse::Sphere>(&sa);
    const auto* sphereB = std::get_if<impulse::Sphere>(&sb);
    const auto* boxA = std::get_if<impulse::Box>(&sa);
    const auto* boxB = std::get_if<impulse::Box>(&sb);
    if (sphereA != nullptr && sphereB != nullptr)
    {
        const Real depth = sphereA->radius + sphereB->radius - (a.position - b.position).norm();
        return 100.0 * depth / std::min(sphereA->radius, sphereB->radius);
    }
    if (boxA != nullptr && boxB != nullptr)
    {
        const Real r = std::min(boxA->halfExtents.minCoeff(), boxB->halfExtents.minCoeff());
        return 100.0 * boxBoxDepth(a, boxA->halfExtents, b, boxB->halfExtents) / r;
    }
    if (sphereA != nullptr && boxB != nullptr)
    {
        return 100.0 * sphereBoxDepth(a.position, sphereA->radius, b, boxB->halfExtents) /
               std::min(sphereA->radius, boxB->halfExtents.minCoeff());
    }
    if (boxA != nullptr && sphereB != nullptr)
    {
        return penetrationPercent(sb, b, sa, a);
    }
    return -infinity;
}

/// Deepest penetration between two dynamic bodies, in percent of r; pairs are those whose centres
/// are closer than the sum of their bounding radii, found on a uniform grid of cells as wide as the
/// largest bounding diameter.
Real deepestPenetration(const impulse::io::Scene& scene, const std::vector<Pose>& poses)
{
    std::vector<const impulse::Shape*> shapes;
    std::vector<Real> radii;
    Real cell = 0.0;
    for (const impulse::BodyId id : dynamicBodies(scene.world))
    {
        shapes.push_back(&scene.world.shape(id));
        radii.push_back(impulse::boundingRadius(*shapes.back()));
        cell = std::max(cell, 2.0 * radii.back());
    }
    using Key = std::array<std::int64_t, 3>;
    const auto keyOf = [&](const Vec3& p)
    {
        Key key;
        for (int i = 0; i < 3; ++i)
        {
            key[static_cast<std::size_t>(i)] =
                static_cast<std::int64_t>(std::floor(std::clamp(p[i] / cell, -1e9, 1e9)));
        }
        return key;
    };
    const auto hash = [](const Key& key)
    { return std::hash<std::int64_t>{}((key[0] * 73856093) ^ (key[1] * 19349663) ^ (key[2] * 83492791)); };
    std::unordered_map<Key, std::vector<std::size_t>, decltype(hash)> grid(poses.size(), hash);
    for (std::size_t i = 0; i < poses.size(); ++i)
    {
        if (poses[i].position.allFinite())
        {
            grid[keyOf(poses[i].position)].push_back(i);
        }
    }
    Real deepest = 0.0;
    for (std::size_t i = 0; i < poses.size(); ++i)
    {
        if (!poses[i].position.allFinite())
        {
            continue;
        }
        const Key home = keyOf(poses[i].position);
        for (std::int64_t dx = -1; dx <= 1; ++dx)
        {
            for (std::int64_t dy = -1; dy <= 1; ++dy)
            {
                for (std::int64_t dz = -1; dz <= 1; ++dz)
                {
                    const auto found = grid.find({home[0] + dx, home[1] + dy, home[2] + dz});
                    if (found == grid.end())
                    {
                        continue;
                    }
                    for (const std::size_t j : found->second)
                    {
                        if (j <= i || (poses[i].position - poses[j].position).norm() >= radii[i] + radii[j])
                        {
                            continue;
                        }
                        deepest = std::max(deepest, penetrationPercent(*shapes[i], poses[i], *shapes[j], poses[j]));
                    }
                }
            }
        }
    }
    return deepest;
}

void printRow(const std::string& name, const char* engine, const impulse::io::Scene& scene, const Run& run,
              const Container& container)
{
    const auto escaped = std::count_if(run.poses.begin(), run.poses.end(),
                                       [&](const Pose& pose) { return outside(container, pose.position); });
    std::printf("%-20s %-8s %7zu %10.1f %9.3f %8.3f-%-9.3f %9.1f %9.1f %8td %9.2f\n", name.c_str(), engine,
                run.poses.size(), run.contacts, percentile(run.stepMs, 0.5), percentile(run.stepMs, 0.1),
                percentile(run.stepMs, 0.9), run.totalSeconds, run.cpuSeconds, escaped,
                deepestPenetration(scene, run.poses));
}

void compare(const std::string& path, const Settings& settings)
{
    impulse::io::Scene scene = impulse::io::loadScene(path);
    const std::string name = scene.name.empty() ? std::filesystem::path(path).stem().string() : scene.name;
    const Coefficients coefficients = coefficientsOf(scene, name);
    BulletScene bullet = buildBullet(scene, coefficients, name);
    const Container container = containerOf(scene.world);
    const int steps = stepsOf(scene, settings);
    std::printf("\n%s: %zu dynamic bodies, dt %g s, %d warm-up + %d measured steps (%g s simulated); mu %g, eps %g "
                "(Bullet bodies: friction %.4f, restitution %.4f each); box x %g..%g, y %g..%g, z 0..%g\n",
                name.c_str(), dynamicBodies(scene.world).size(), scene.options.dt, settings.warmUp, steps,
                (settings.warmUp + steps) * scene.options.dt, coefficients.pair.friction, coefficients.pair.restitution,
                static_cast<double>(coefficients.bodyFriction), static_cast<double>(coefficients.bodyRestitution),
                container.xMin, container.xMax, container.yMin, container.yMax, container.top);
    std::printf("%-20s %-8s %7s %10s %9s %18s %9s %9s %8s %9s\n", "scene", "engine", "bodies", "contacts", "ms/step",
                "p10-p90", "wall s", "cpu s", "outside", "pen % r");
    std::fflush(stdout);
    const Run impulseRun = runImpulse(scene, settings);
    printRow(name, "impulse", scene, impulseRun, container);
    std::fflush(stdout);
    const Run bulletRun = runBullet(bullet, scene, settings);
    printRow(name, "Bullet", scene, bulletRun, container);
    std::printf("impulse state hash: %016llx\n", static_cast<unsigned long long>(scene.world.stateHash()));
    std::printf("ratio impulse/Bullet ms per step: %.2f\n",
                percentile(impulseRun.stepMs, 0.5) / percentile(bulletRun.stepMs, 0.5));
    std::fflush(stdout);
}

} // namespace

int main(int argc, char** argv)
{
    Settings settings;
    std::vector<std::string> scenes;
    for (int i = 1; i < argc; ++i)
    {
        const std::string arg = argv[i];
        if (arg == "--steps" && i + 1 < argc)
        {
            settings.steps = std::max(1, std::atoi(argv[++i]));
        }
        else if (arg == "--warm-up" && i + 1 < argc)
        {
            settings.warmUp = std::max(0, std::atoi(argv[++i]));
        }
        else if (arg == "--threads" && i + 1 < argc)
        {
            settings.threads = std::max(0, std::atoi(argv[++i]));
        }
        else if (arg == "--help" || arg == "-h")
        {
            std::printf("usage: impulse_bench_bullet [--steps N] [--warm-up W] [--threads T] [SCENE.json ...]\n");
            return 0;
        }
        else
        {
            scenes.push_back(arg);
        }
    }
    if (scenes.empty())
    {
        scenes = {std::string(IMPULSE_SCENES_DIR) + "/sphere_pile_10000.json",
                  std::string(IMPULSE_SCENES_DIR) + "/box_pile_1000.json"};
    }
    std::printf("impulse against Bullet %d.%02d (%s precision): btDbvtBroadphase, btSequentialImpulseConstraintSolver "
                "at 10 iterations, stepSimulation(dt, 0), sleeping off, single-threaded\n",
                btGetVersion() / 100, btGetVersion() % 100, sizeof(btScalar) == sizeof(double) ? "double" : "single");
    std::printf("impulse: the scene's step options, %d thread%s; friction and restitution: Bullet multiplies the "
                "two bodies' values, so each Bullet body carries sqrt(mu) and sqrt(eps) of the scene's material\n",
                settings.threads, settings.threads == 1 ? "" : "s");
    for (const std::string& path : scenes)
    {
        try
        {
            compare(path, settings);
        }
        catch (const std::exception& error)
        {
            std::fprintf(stderr, "%s\n", error.what());
            return 2;
        }
    }
    return 0;
}
