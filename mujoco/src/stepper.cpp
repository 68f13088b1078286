// SPDX-License-Identifier: MIT
// Loading MJCF through MuJoCo, the drop-in stepper, and the contact softness of the comparison.
#include <impulse/mujoco/mujoco.hpp>

#include <cmath>
#include <cstring>
#include <limits>
#include <map>
#include <mutex>
#include <numbers>

namespace impulse::mujoco
{
namespace
{

std::string trimmed(const char* text)
{
    // MuJoCo's messages run over several lines; keep them on one
    std::string s(text);
    while (!s.empty() && (s.back() == '\n' || s.back() == ' '))
    {
        s.pop_back();
    }
    for (std::size_t at = s.find('\n'); at != std::string::npos; at = s.find('\n', at))
    {
        s.replace(at, 1, "; ");
    }
    return s;
}

} // namespace

ModelPtr loadModel(const std::filesystem::path& path)
{
    char error[1000] = "";
    ModelPtr model(mj_loadXML(path.string().c_str(), nullptr, error, sizeof error));
    if (!model)
    {
        throw ModelError(path.string() + ": MuJoCo cannot load it: " + trimmed(error));
    }
    return model;
}

ModelPtr loadModelFromString(const std::string& xml, const std::string& source)
{
    // MuJoCo reads files; a virtual file system holds the text without touching the disk
    auto vfs = std::make_unique<mjVFS>();
    mj_defaultVFS(vfs.get());
    const std::string name = "model.xml";
    if (mj_makeEmptyFileVFS(vfs.get(), name.c_str(), static_cast<int>(xml.size())) != 0)
    {
        throw ModelError(source + ": cannot hold the model text in MuJoCo's virtual file system");
    }
    const int index = mj_findFileVFS(vfs.get(), name.c_str());
    std::memcpy(vfs->filedata[index], xml.data(), xml.size());
    char error[1000] = "";
    ModelPtr model(mj_loadXML(name.c_str(), vfs.get(), error, sizeof error));
    mj_deleteVFS(vfs.get());
    if (!model)
    {
        throw ModelError(source + ": MuJoCo cannot load it: " + trimmed(error));
    }
    return model;
}

io::Scene loadMjcfScene(const std::filesystem::path& path)
{
    const ModelPtr model = loadModel(path);
    const DataPtr data(mj_makeData(model.get()));
    if (model->nkey > 0)
    {
        mj_resetDataKeyframe(model.get(), data.get(), 0);
    }
    mj_forward(model.get(), data.get());
    Translation t = translate(model.get(), data.get(), path.string());
    io::Scene scene;
    scene.name = t.name;
    scene.world = std::move(t.world);
    scene.options = t.options;
    scene.duration = t.duration.value_or(std::numeric_limits<Real>::quiet_NaN());
    scene.dynamicBodies = t.dynamicBodies;
    scene.bodyNames = t.bodyNames;
    return scene;
}

Stepper::Stepper(const mjModel* m, const mjData* d, const std::string& source)
    : m_translation(translate(m, d, source)), m_writtenQpos(d->qpos, d->qpos + m->nq),
      m_writtenQvel(d->qvel, d->qvel + m->nv), m_gravity(m_translation.world.gravity())
{
}

void Stepper::pull(const mjModel* m, const mjData* d)
{
    for (const Translation::Link& link : m_translation.links)
    {
        const LinkState s = readLink(link, m, d);
        m_translation.world.setState(link.body, s.position, s.orientation, s.linearVelocity, s.angularVelocity);
    }
}

void Stepper::step(const mjModel* m, mjData* d)
{
    const Vec3 gravity = (m->opt.disableflags & mjDSBL_GRAVITY)
                             ? Vec3::Zero()
                             : Vec3(m->opt.gravity[0], m->opt.gravity[1], m->opt.gravity[2]);
    if (gravity != m_gravity)
    {
        // the world's gravity is fixed when it is made: make it again from the current state
        m_translation = translate(m, d, "model");
        m_gravity = gravity;
    }
    else if (std::memcmp(m_writtenQpos.data(), d->qpos, sizeof(mjtNum) * m_writtenQpos.size()) != 0 ||
             std::memcmp(m_writtenQvel.data(), d->qvel, sizeof(mjtNum) * m_writtenQvel.size()) != 0)
    {
        pull(m, d); // edited on the MuJoCo side since the last step
    }
    m_translation.options.dt = m->opt.timestep;
    m_translation.world.step(m_translation.options);
    for (const Translation::Link& link : m_translation.links)
    {
        writeLink(link, m_translation.world.state(link.body), m, d);
    }
    d->time += m->opt.timestep;
    // positions, sensors and rendering of the new state. MuJoCo's kinematics renormalise each
    // free-joint quaternion in qpos in place (by an ulp or two: impulse's are unit to within
    // 2e-16, MuJoCo's test is exact), so what counts as written is qpos after it; the world keeps
    // its own orientation, and the run stays bit for bit that of `impulse run`.
    mj_forward(m, d);
    std::memcpy(m_writtenQpos.data(), d->qpos, sizeof(mjtNum) * m_writtenQpos.size());
    std::memcpy(m_writtenQvel.data(), d->qvel, sizeof(mjtNum) * m_writtenQvel.size());
}

namespace
{

std::mutex& cacheMutex()
{
    static std::mutex mutex;
    return mutex;
}

std::map<std::pair<const mjModel*, const mjData*>, std::unique_ptr<Stepper>>& cache()
{
    static std::map<std::pair<const mjModel*, const mjData*>, std::unique_ptr<Stepper>> steppers;
    return steppers;
}

} // namespace

void step(const mjModel* m, mjData* d)
{
    Stepper* stepper = nullptr;
    {
        const std::lock_guard<std::mutex> lock(cacheMutex());
        std::unique_ptr<Stepper>& slot = cache()[{m, d}];
        if (!slot)
        {
            try
            {
                slot = std::make_unique<Stepper>(m, d, "model");
            }
            catch (...)
            {
                cache().erase({m, d});
                throw;
            }
        }
        stepper = slot.get();
    }
    stepper->step(m, d);
}

void forget(const mjModel* m, const mjData* d)
{
    const std::lock_guard<std::mutex> lock(cacheMutex());
    cache().erase({m, d});
}

Real dampingRatioFor(Real restitution)
{
    if (restitution <= 0.0)
    {
        return 1.0;
    }
    const Real log = std::log(restitution);
    return -log / std::sqrt(std::numbers::pi * std::numbers::pi + log * log);
}

Softness contactSoftness(Real restitution, Real timeconst)
{
    const Real omega = 1.0 / timeconst;
    return {omega * omega, 2.0 * dampingRatioFor(restitution) * omega};
}

} // namespace impulse::mujoco
