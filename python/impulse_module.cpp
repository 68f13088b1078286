// SPDX-License-Identifier: MIT
// `import impulse`: the World, scene and model loading, and whole-world states as numpy arrays.
//
// Body handles are plain integers (a body's row in every array), quaternions are (w, x, y, z), and
// every refusal of the C++ API (std::invalid_argument) arrives as a ValueError with its message.
// docs/python.md describes the module for its users.
#include <impulse/impulse.hpp>
#include <impulse/io/mesh_file.hpp>
#include <impulse/io/scene.hpp>
#ifdef IMPULSE_PYTHON_WITH_MUJOCO
#include <impulse/mujoco/mujoco.hpp>
#endif

#include <cmath>
#include <cstdint>
#include <functional>
#include <limits>
#include <map>
#include <memory>
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>
#include <stdexcept>
#include <string>
#include <vector>

namespace py = pybind11;

namespace impulse::python
{
namespace
{

using Array = py::array_t<double, py::array::c_style | py::array::forcecast>;

[[noreturn]] void refuse(const std::string& field, const std::string& what)
{
    throw std::invalid_argument(field + ": " + what);
}

std::string shapeText(const py::array& array)
{
    std::string text = "(";
    for (py::ssize_t d = 0; d < array.ndim(); ++d)
    {
        text += (d > 0 ? ", " : "") + std::to_string(array.shape(d));
    }
    return text + (array.ndim() == 1 ? ",)" : ")");
}

// A numpy array of doubles from anything numpy turns into one, or a ValueError naming the field.
Array asArray(const py::handle& value, const std::string& field)
{
    Array array = Array::ensure(value);
    if (!array)
    {
        refuse(field, "must be numbers, got " + std::string(py::str(py::repr(value))));
    }
    return array;
}

Vec3 vec3(const py::handle& value, const std::string& field)
{
    const Array array = asArray(value, field);
    if (array.ndim() != 1 || array.shape(0) != 3)
    {
        refuse(field, "must be 3 numbers, got an array of shape " + shapeText(array));
    }
    return {array.at(0), array.at(1), array.at(2)};
}

Quat quat(const py::handle& value, const std::string& field)
{
    const Array array = asArray(value, field);
    if (array.ndim() != 1 || array.shape(0) != 4)
    {
        refuse(field, "must be 4 numbers (w, x, y, z), got an array of shape " + shapeText(array));
    }
    return Quat(array.at(0), array.at(1), array.at(2), array.at(3));
}

py::array_t<double> toArray(const Vec3& v)
{
    py::array_t<double> out(3);
    auto o = out.mutable_unchecked<1>();
    for (py::ssize_t i = 0; i < 3; ++i)
    {
        o(i) = v[static_cast<Eigen::Index>(i)];
    }
    return out;
}

py::array_t<double> toArray(const Mat3& m)
{
    py::array_t<double> out({3, 3});
    auto o = out.mutable_unchecked<2>();
    for (py::ssize_t i = 0; i < 3; ++i)
    {
        for (py::ssize_t j = 0; j < 3; ++j)
        {
            o(i, j) = m(static_cast<Eigen::Index>(i), static_cast<Eigen::Index>(j));
        }
    }
    return out;
}

py::array_t<double> toArray(const Quat& q)
{
    py::array_t<double> out(4);
    auto o = out.mutable_unchecked<1>();
    o(0) = q.w();
    o(1) = q.x();
    o(2) = q.y();
    o(3) = q.z();
    return out;
}

BodyId bodyId(std::int64_t index, const std::string& field = "body")
{
    if (index < 0 || index > std::numeric_limits<std::uint32_t>::max())
    {
        refuse(field, "no body " + std::to_string(index) + " in this world");
    }
    return BodyId{static_cast<std::uint32_t>(index)};
}

MaterialId materialId(std::int64_t index)
{
    if (index < 0 || index > std::numeric_limits<std::uint32_t>::max())
    {
        refuse("material", "no material " + std::to_string(index) + " in this world");
    }
    return MaterialId{static_cast<std::uint32_t>(index)};
}

// ---- step options by name ----

Scheme schemeNamed(const std::string& name)
{
    if (name == "guendelman")
    {
        return Scheme::Guendelman;
    }
    if (name == "traditional")
    {
        return Scheme::Traditional;
    }
    refuse("scheme", "must be \"guendelman\" or \"traditional\", got \"" + name + "\"");
}

std::string schemeName(Scheme scheme)
{
    return scheme == Scheme::Traditional ? "traditional" : "guendelman";
}

// Each StepOptions field under its Python name, set from a Python value.
const std::map<std::string, std::function<void(StepOptions&, const py::handle&)>>& optionSetters()
{
    static const std::map<std::string, std::function<void(StepOptions&, const py::handle&)>> setters = {
        {"dt", [](StepOptions& o, const py::handle& v) { o.dt = v.cast<Real>(); }},
        {"scheme", [](StepOptions& o, const py::handle& v) { o.scheme = schemeNamed(v.cast<std::string>()); }},
        {"collision_iterations", [](StepOptions& o, const py::handle& v) { o.collisionIterations = v.cast<int>(); }},
        {"contact_iterations", [](StepOptions& o, const py::handle& v) { o.contactIterations = v.cast<int>(); }},
        {"pair_iterations", [](StepOptions& o, const py::handle& v) { o.pairIterations = v.cast<int>(); }},
        {"contact_thickness", [](StepOptions& o, const py::handle& v) { o.contactThickness = v.cast<Real>(); }},
        {"mid_step_restitution", [](StepOptions& o, const py::handle& v) { o.midStepRestitution = v.cast<bool>(); }},
        {"time_of_impact_geometry",
         [](StepOptions& o, const py::handle& v) { o.timeOfImpactGeometry = v.cast<bool>(); }},
        {"restitution_threshold", [](StepOptions& o, const py::handle& v) { o.restitutionThreshold = v.cast<Real>(); }},
        {"resting_approach", [](StepOptions& o, const py::handle& v) { o.restingApproach = v.cast<Real>(); }},
        {"shock_propagation", [](StepOptions& o, const py::handle& v) { o.shockPropagation = v.cast<bool>(); }},
        {"push_out", [](StepOptions& o, const py::handle& v) { o.pushOut = v.cast<bool>(); }},
        {"push_out_allowance", [](StepOptions& o, const py::handle& v) { o.pushOutAllowance = v.cast<Real>(); }},
        {"push_out_speed", [](StepOptions& o, const py::handle& v) { o.pushOutSpeed = v.cast<Real>(); }},
        {"push_out_iterations", [](StepOptions& o, const py::handle& v) { o.pushOutIterations = v.cast<int>(); }},
        {"threads", [](StepOptions& o, const py::handle& v) { o.threads = v.cast<int>(); }},
        {"sleep", [](StepOptions& o, const py::handle& v) { o.sleep = v.cast<bool>(); }},
        {"sleep_speed", [](StepOptions& o, const py::handle& v) { o.sleepSpeed = v.cast<Real>(); }},
        {"sleep_time", [](StepOptions& o, const py::handle& v) { o.sleepTime = v.cast<Real>(); }},
    };
    return setters;
}

void setOptions(StepOptions& options, const py::kwargs& kwargs, const char* function)
{
    for (const auto& [key, value] : kwargs)
    {
        const std::string name = py::str(key);
        const auto setter = optionSetters().find(name);
        if (setter == optionSetters().end())
        {
            std::string known;
            for (const auto& [option, unused] : optionSetters())
            {
                known += (known.empty() ? "" : ", ") + option;
            }
            throw py::type_error(std::string(function) + "() got an unexpected keyword argument '" + name +
                                 "' (step options: " + known + ")");
        }
        try
        {
            setter->second(options, value);
        }
        catch (const py::cast_error&)
        {
            refuse(name, "cannot be " + std::string(py::repr(value)));
        }
    }
}

// ---- states as arrays ----

std::vector<BodyId> selection(const World& world, const py::object& bodies)
{
    std::vector<BodyId> ids;
    if (bodies.is_none())
    {
        for (std::uint32_t b = 0; b < world.bodyCount(); ++b)
        {
            ids.push_back(BodyId{b});
        }
        return ids;
    }
    for (const py::handle& body : bodies)
    {
        ids.push_back(bodyId(body.cast<std::int64_t>()));
    }
    return ids;
}

// Rows of `width` numbers, one per body of the selection; NaN for a removed body when all are read.
template <typename Fill>
py::array_t<double> rows(const World& world, const py::object& bodies, py::ssize_t width, Fill fill)
{
    const std::vector<BodyId> ids = selection(world, bodies);
    py::array_t<double> out({static_cast<py::ssize_t>(ids.size()), width});
    auto o = out.mutable_unchecked<2>();
    for (py::ssize_t r = 0; r < static_cast<py::ssize_t>(ids.size()); ++r)
    {
        double* row = o.mutable_data(r, 0);
        if (bodies.is_none() && !world.contains(ids[static_cast<std::size_t>(r)]))
        {
            std::fill(row, row + width, std::numeric_limits<double>::quiet_NaN());
            continue;
        }
        fill(world.state(ids[static_cast<std::size_t>(r)]), row);
    }
    return out;
}

void put(const Vec3& v, double* row)
{
    row[0] = v.x();
    row[1] = v.y();
    row[2] = v.z();
}

// An (n, width) array from a Python value, or a ValueError naming the field.
Array table(const py::handle& value, const std::string& field, py::ssize_t count, py::ssize_t width)
{
    const Array array = asArray(value, field);
    if (array.ndim() != 2 || array.shape(0) != count || array.shape(1) != width)
    {
        refuse(field, "must be an array of shape (" + std::to_string(count) + ", " + std::to_string(width) + "), got " +
                          shapeText(array));
    }
    return array;
}

void setStates(World& world, const py::object& bodies, const py::object& positions, const py::object& orientations,
               const py::object& linearVelocities, const py::object& angularVelocities)
{
    const std::vector<BodyId> ids = selection(world, bodies);
    const auto n = static_cast<py::ssize_t>(ids.size());
    const auto optionalTable = [&](const py::object& value, const std::string& field, py::ssize_t width)
    { return value.is_none() ? Array() : table(value, field, n, width); };
    const Array p = optionalTable(positions, "positions", 3);
    const Array q = optionalTable(orientations, "orientations", 4);
    const Array v = optionalTable(linearVelocities, "linear_velocities", 3);
    const Array w = optionalTable(angularVelocities, "angular_velocities", 3);
    // check every row before writing any, so that a refused call changes nothing
    std::vector<BodyState> next;
    for (py::ssize_t r = 0; r < n; ++r)
    {
        const BodyId id = ids[static_cast<std::size_t>(r)];
        BodyState s = world.state(id);
        if (!world.isDynamic(id))
        {
            refuse("bodies", "body " + std::to_string(id.index) + " is static: it cannot be moved");
        }
        const auto row = [&](const Array& a) { return a.data(r, 0); };
        if (p.size() > 0)
        {
            s.position = Vec3(row(p)[0], row(p)[1], row(p)[2]);
        }
        if (q.size() > 0)
        {
            s.orientation = Quat(row(q)[0], row(q)[1], row(q)[2], row(q)[3]);
        }
        if (v.size() > 0)
        {
            s.linearVelocity = Vec3(row(v)[0], row(v)[1], row(v)[2]);
        }
        if (w.size() > 0)
        {
            s.angularVelocity = Vec3(row(w)[0], row(w)[1], row(w)[2]);
        }
        const std::string where = " (row " + std::to_string(r) + ", body " + std::to_string(id.index) + ")";
        if (!s.position.allFinite())
        {
            refuse("positions", "must be finite" + where);
        }
        if (!s.orientation.coeffs().allFinite() || !(s.orientation.norm() > 0.0))
        {
            refuse("orientations", "must be finite non-zero quaternions" + where);
        }
        if (!s.linearVelocity.allFinite())
        {
            refuse("linear_velocities", "must be finite" + where);
        }
        if (!s.angularVelocity.allFinite())
        {
            refuse("angular_velocities", "must be finite" + where);
        }
        next.push_back(s);
    }
    for (std::size_t r = 0; r < ids.size(); ++r)
    {
        const BodyState& s = next[r];
        world.setState(ids[r], s.position, s.orientation, s.linearVelocity, s.angularVelocity);
    }
}

// ---- shapes ----

Shape shapeFrom(const py::handle& value)
{
    try
    {
        return value.cast<Shape>();
    }
    catch (const py::cast_error&)
    {
        refuse("shape", "must be impulse.Sphere, Box, Plane, Capsule or Mesh, got " +
                            std::string(py::str(py::type::of(value).attr("__name__"))));
    }
}

std::shared_ptr<const MeshGeometry> loadMesh(const std::filesystem::path& path, const py::object& scale, int resolution)
{
    TriangleMesh mesh = io::readMeshFile(path);
    const Vec3 factor = py::isinstance<py::float_>(scale) || py::isinstance<py::int_>(scale)
                            ? Vec3::Constant(scale.cast<Real>())
                            : vec3(scale, "scale");
    if (!factor.allFinite() || !(factor.array() > 0.0).all())
    {
        refuse("scale", "must be positive");
    }
    for (Vec3& vertex : mesh.vertices)
    {
        vertex = vertex.cwiseProduct(factor);
    }
    if (resolution != 0 && (resolution < 4 || resolution > 1024))
    {
        refuse("resolution", "must be 0 (chosen from the mesh) or 4 to 1024 cells, got " + std::to_string(resolution));
    }
    return MeshGeometry::build(mesh, {.resolution = resolution});
}

/// The messages of the warnings, for Python: each says what it is about.
std::vector<std::string> warningMessages(const std::vector<Warning>& warnings)
{
    std::vector<std::string> messages;
    for (const Warning& warning : warnings)
    {
        messages.push_back(warning.message);
    }
    return messages;
}

// ---- scenes ----

/// A world with what a scene file or a model says about it.
struct LoadedScene
{
    io::Scene scene;
};

py::object loadScenePath(const std::filesystem::path& path)
{
    return py::cast(LoadedScene{io::loadScene(path)});
}

py::object loadModelPath(const std::filesystem::path& path)
{
#ifdef IMPULSE_PYTHON_WITH_MUJOCO
    return py::cast(LoadedScene{mujoco::loadMjcfScene(path)});
#else
    throw std::runtime_error(path.string() + ": this impulse was built without MuJoCo (libmujoco-dev), so it "
                                             "cannot read MJCF models");
#endif
}

// The contacts of the last step as arrays, one row per contact point.
py::dict contactsDict(const World& world)
{
    const std::vector<Contact>& contacts = world.contacts();
    const auto n = static_cast<py::ssize_t>(contacts.size());
    py::array_t<std::int64_t> a(n);
    py::array_t<std::int64_t> b(n);
    py::array_t<double> points({n, py::ssize_t{3}});
    py::array_t<double> normals({n, py::ssize_t{3}});
    py::array_t<double> separations(n);
    py::array_t<double> normalImpulses(n);
    py::array_t<double> frictionImpulses({n, py::ssize_t{3}});
    auto ra = a.mutable_unchecked<1>();
    auto rb = b.mutable_unchecked<1>();
    auto rp = points.mutable_unchecked<2>();
    auto rn = normals.mutable_unchecked<2>();
    auto rs = separations.mutable_unchecked<1>();
    auto rl = normalImpulses.mutable_unchecked<1>();
    auto rf = frictionImpulses.mutable_unchecked<2>();
    for (py::ssize_t i = 0; i < n; ++i)
    {
        const Contact& c = contacts[static_cast<std::size_t>(i)];
        ra(i) = c.a.index;
        rb(i) = c.b.index;
        rs(i) = c.separation;
        rl(i) = c.normalImpulse;
        for (py::ssize_t k = 0; k < 3; ++k)
        {
            rp(i, k) = c.point[k];
            rn(i, k) = c.normal[k];
            rf(i, k) = c.frictionImpulse[k];
        }
    }
    py::dict d;
    d["body_a"] = a;
    d["body_b"] = b;
    d["points"] = points;
    d["normals"] = normals;
    d["separations"] = separations;
    d["normal_impulses"] = normalImpulses;
    d["friction_impulses"] = frictionImpulses;
    return d;
}

py::dict statsDict(const StepStats& s)
{
    py::dict d;
    d["candidate_pairs"] = s.candidatePairs;
    d["collision_impulses"] = s.collisionImpulses;
    d["collision_sweeps"] = s.collisionSweeps;
    d["narrow_phase_calls"] = s.narrowPhaseCalls;
    d["contact_captures"] = s.contactCaptures;
    d["contact_rows"] = s.contactRows;
    d["contact_sweeps"] = s.contactSweeps;
    d["cold_restarts"] = s.coldRestarts;
    d["shock_iterations"] = s.shockIterations;
    d["push_out_moves"] = s.pushOutMoves;
    d["contact_levels"] = s.contactLevels;
    d["contact_pairs"] = s.contactPairs;
    d["islands"] = s.islands;
    d["sleeping_bodies"] = s.sleepingBodies;
    d["threads"] = s.threads;
    py::dict ms;
    ms["candidate_pairs"] = s.milliseconds.candidatePairs;
    ms["collision_pass"] = s.milliseconds.collisionPass;
    ms["contact_graph"] = s.milliseconds.contactGraph;
    ms["contact_pass"] = s.milliseconds.contactPass;
    ms["shock_propagation"] = s.milliseconds.shockPropagation;
    ms["position_update"] = s.milliseconds.positionUpdate;
    ms["push_out"] = s.milliseconds.pushOut;
    d["milliseconds"] = ms;
    return d;
}

void stepWorld(World& world, const StepOptions& options, long long steps)
{
    if (steps < 1)
    {
        refuse("steps", "must be 1 or more, got " + std::to_string(steps));
    }
    py::gil_scoped_release release;
    for (long long k = 0; k < steps; ++k)
    {
        world.step(options);
    }
}

} // namespace

void bind(py::module_& m)
{
    m.doc() = "impulse: rigid bodies with the separated collision / contact time step of Guendelman, Bridson "
              "& Fedkiw 2003. See docs/python.md.";
    m.attr("__version__") = IMPULSE_PYTHON_VERSION;
    m.attr("has_mujoco") =
#ifdef IMPULSE_PYTHON_WITH_MUJOCO
        true;
#else
        false;
#endif

    // files that cannot be used: ValueErrors of their own, with the loader's message
    py::register_exception<io::SceneError>(m, "SceneError", PyExc_ValueError);
    py::register_exception<io::MeshFileError>(m, "MeshFileError", PyExc_ValueError);
    py::register_exception<MeshError>(m, "MeshError", PyExc_ValueError);
#ifdef IMPULSE_PYTHON_WITH_MUJOCO
    py::register_exception<mujoco::ModelError>(m, "ModelError", PyExc_ValueError);
#endif

    // ---- shapes ----
    py::class_<Sphere>(m, "Sphere", "Solid sphere centred on the body origin.")
        .def(py::init([](Real radius) { return Sphere{radius}; }), py::arg("radius") = 0.5)
        .def_readwrite("radius", &Sphere::radius)
        .def("__repr__", [](const Sphere& s) { return "impulse.Sphere(radius=" + std::to_string(s.radius) + ")"; });
    py::class_<Box>(m, "Box", "Solid box centred on the body origin, edges along the body axes.")
        .def(py::init([](const py::object& halfExtents) { return Box{vec3(halfExtents, "half_extents")}; }),
             py::arg("half_extents"))
        .def_property(
            "half_extents", [](const Box& b) { return toArray(b.halfExtents); },
            [](Box& b, const py::object& v) { b.halfExtents = vec3(v, "half_extents"); });
    py::class_<Plane>(m, "Plane", "Half-space {p : normal . p <= offset}; static bodies only.")
        .def(py::init(
                 [](const py::object& normal, Real offset) {
                     return Plane{vec3(normal, "normal"), offset};
                 }),
             py::arg("normal") = py::make_tuple(0.0, 0.0, 1.0), py::arg("offset") = 0.0)
        .def_property_readonly("normal", [](const Plane& p) { return toArray(p.normal); })
        .def_readonly("offset", &Plane::offset);
    py::class_<Capsule>(m, "Capsule", "Points within radius of the segment from -half_length to +half_length on z.")
        .def(py::init(
                 [](Real radius, Real halfLength) {
                     return Capsule{radius, halfLength};
                 }),
             py::arg("radius"), py::arg("half_length"))
        .def_readwrite("radius", &Capsule::radius)
        .def_readwrite("half_length", &Capsule::halfLength);
    py::class_<Mesh>(m, "Mesh", "A closed triangle mesh in its body frame (centre of mass, principal axes).")
        .def_property_readonly("volume", [](const Mesh& mesh) { return mesh.geometry->volume(); })
        .def_property_readonly("vertex_count", [](const Mesh& mesh) { return mesh.geometry->vertices().size(); })
        .def_property_readonly("triangle_count", [](const Mesh& mesh) { return mesh.geometry->triangles().size(); });
    m.def(
        "load_mesh",
        [](const std::filesystem::path& path, const py::object& scale, int resolution)
        { return Mesh{loadMesh(path, scale, resolution)}; },
        py::arg("path"), py::arg("scale") = 1.0, py::arg("resolution") = 0,
        "Reads an OBJ or STL file into a Mesh shape, vertices scaled by `scale` (a number or 3), the signed "
        "distance grid `resolution` cells along the longest side (0: chosen from the mesh).");

    // ---- step options ----
    py::class_<StepOptions>(m, "StepOptions", "Controls of one time step; keyword arguments as the fields.")
        .def(py::init(
            [](const py::kwargs& kwargs)
            {
                StepOptions options;
                setOptions(options, kwargs, "StepOptions");
                return options;
            }))
        .def_readwrite("dt", &StepOptions::dt)
        .def_property(
            "scheme", [](const StepOptions& o) { return schemeName(o.scheme); },
            [](StepOptions& o, const std::string& name) { o.scheme = schemeNamed(name); })
        .def_readwrite("collision_iterations", &StepOptions::collisionIterations)
        .def_readwrite("contact_iterations", &StepOptions::contactIterations)
        .def_readwrite("pair_iterations", &StepOptions::pairIterations)
        .def_readwrite("contact_thickness", &StepOptions::contactThickness)
        .def_readwrite("mid_step_restitution", &StepOptions::midStepRestitution)
        .def_readwrite("time_of_impact_geometry", &StepOptions::timeOfImpactGeometry)
        .def_readwrite("restitution_threshold", &StepOptions::restitutionThreshold)
        .def_readwrite("resting_approach", &StepOptions::restingApproach)
        .def_readwrite("shock_propagation", &StepOptions::shockPropagation)
        .def_readwrite("push_out", &StepOptions::pushOut)
        .def_readwrite("push_out_allowance", &StepOptions::pushOutAllowance)
        .def_readwrite("push_out_speed", &StepOptions::pushOutSpeed)
        .def_readwrite("push_out_iterations", &StepOptions::pushOutIterations)
        .def_readwrite("threads", &StepOptions::threads)
        .def_readwrite("sleep", &StepOptions::sleep)
        .def_readwrite("sleep_speed", &StepOptions::sleepSpeed)
        .def_readwrite("sleep_time", &StepOptions::sleepTime)
        .def("__repr__",
             [](const StepOptions& o)
             {
                 return "impulse.StepOptions(dt=" + std::string(py::repr(py::float_(o.dt))) + ", scheme='" +
                        schemeName(o.scheme) + "', ...)";
             });

    // ---- snapshots ----
    py::class_<WorldSnapshot>(m, "Snapshot", "The clock and every body's state, exactly; World.restore puts it back.")
        .def_readonly("time", &WorldSnapshot::time)
        .def_property_readonly("body_count", [](const WorldSnapshot& s) { return s.bodies.size(); });

    // ---- the world ----
    py::class_<World> world(m, "World", "A set of rigid bodies advanced together. Body handles are integers.");
    world
        .def(py::init([](const py::object& gravity) { return World(WorldDef{.gravity = vec3(gravity, "gravity")}); }),
             py::arg("gravity") = py::make_tuple(0.0, 0.0, -9.81))
        .def(
            "create_material",
            [](World& w, Real restitution, Real friction)
            { return w.createMaterial({.restitution = restitution, .friction = friction}).index; },
            py::arg("restitution") = 0.5, py::arg("friction") = 0.5, "Adds a material; returns its handle.")
        .def(
            "set_pair_coefficients",
            [](World& w, std::int64_t a, std::int64_t b, Real restitution, Real friction) {
                w.setPairCoefficients(materialId(a), materialId(b), {restitution, friction});
            },
            py::arg("a"), py::arg("b"), py::arg("restitution"), py::arg("friction"))
        .def(
            "create_body",
            [](World& w, const py::object& shape, std::int64_t material, Real mass, Real density, bool isStatic,
               const py::object& position, const py::object& orientation, const py::object& linearVelocity,
               const py::object& angularVelocity, const py::object& inertia, const py::object& centerOfMass,
               std::uint32_t group, std::uint32_t mask)
            {
                BodyDef def;
                def.type = isStatic ? BodyType::Static : BodyType::Dynamic;
                def.shape = shapeFrom(shape);
                def.material = materialId(material);
                def.mass = mass;
                def.density = density;
                def.position = vec3(position, "position");
                def.orientation = quat(orientation, "orientation");
                def.linearVelocity = vec3(linearVelocity, "linear_velocity");
                def.angularVelocity = vec3(angularVelocity, "angular_velocity");
                def.filter = {group, mask};
                def.centerOfMass = vec3(centerOfMass, "center_of_mass");
                if (!inertia.is_none())
                {
                    const Array array = asArray(inertia, "inertia");
                    if (array.ndim() == 1 && array.shape(0) == 3)
                    {
                        def.principalInertia = Vec3(array.at(0), array.at(1), array.at(2));
                        if (!(def.principalInertia.array() > 0.0).all())
                        {
                            refuse("inertia", "principal moments must be positive");
                        }
                    }
                    else if (array.ndim() == 2 && array.shape(0) == 3 && array.shape(1) == 3)
                    {
                        for (int i = 0; i < 3; ++i)
                        {
                            for (int j = 0; j < 3; ++j)
                            {
                                def.inertia(i, j) = array.at(i, j);
                            }
                        }
                    }
                    else
                    {
                        refuse("inertia", "must be 3 principal moments or a 3 x 3 tensor, got an array of shape " +
                                              shapeText(array));
                    }
                    if (isStatic)
                    {
                        refuse("inertia", "a static body has none");
                    }
                }
                return w.createBody(def).index;
            },
            py::arg("shape"), py::kw_only(), py::arg("material") = 0, py::arg("mass") = 0.0, py::arg("density") = 0.0,
            py::arg("static") = false, py::arg("position") = py::make_tuple(0.0, 0.0, 0.0),
            py::arg("orientation") = py::make_tuple(1.0, 0.0, 0.0, 0.0),
            py::arg("linear_velocity") = py::make_tuple(0.0, 0.0, 0.0),
            py::arg("angular_velocity") = py::make_tuple(0.0, 0.0, 0.0), py::arg("inertia") = py::none(),
            py::arg("center_of_mass") = py::make_tuple(0.0, 0.0, 0.0), py::arg("group") = 1U,
            py::arg("mask") = 0xffffffffU,
            "Adds a body and returns its handle, an integer: its row in every state array. `position` places "
            "the centre of mass; `center_of_mass` is where it sits in the shape's frame.")
        .def(
            "remove_body", [](World& w, std::int64_t body) { w.removeBody(bodyId(body)); }, py::arg("body"))
        .def(
            "contains",
            [](const World& w, std::int64_t body)
            { return body >= 0 && body <= std::numeric_limits<std::uint32_t>::max() && w.contains(bodyId(body)); },
            py::arg("body"))
        .def_property_readonly("body_count", &World::bodyCount)
        .def(
            "dynamic_bodies",
            [](const World& w)
            {
                std::vector<std::uint32_t> ids;
                for (std::uint32_t b = 0; b < w.bodyCount(); ++b)
                {
                    if (w.contains(BodyId{b}) && w.isDynamic(BodyId{b}))
                    {
                        ids.push_back(b);
                    }
                }
                return ids;
            },
            "Handles of the dynamic bodies that have not been removed, ascending.")
        .def(
            "is_dynamic", [](const World& w, std::int64_t body) { return w.isDynamic(bodyId(body)); }, py::arg("body"))
        .def(
            "is_asleep", [](const World& w, std::int64_t body) { return w.isAsleep(bodyId(body)); }, py::arg("body"),
            "Whether the body sleeps (StepOptions.sleep).")

        // stepping
        .def(
            "step",
            [](World& w, const py::object& options, long long steps, const py::kwargs& kwargs)
            {
                StepOptions o = options.is_none() ? StepOptions{} : options.cast<StepOptions>();
                setOptions(o, kwargs, "step");
                stepWorld(w, o, steps);
            },
            py::arg("options") = py::none(), py::kw_only(), py::arg("steps") = 1,
            "Advances by `steps` steps of options.dt. Step options come from `options` (a StepOptions), each "
            "overridden by a keyword argument of the same name: world.step(dt=1e-3, shock_propagation=False).")
        .def(
            "warnings",
            [](const World& w, const py::object& options, const std::vector<std::string>& names,
               const py::kwargs& kwargs)
            {
                StepOptions o = options.is_none() ? StepOptions{} : options.cast<StepOptions>();
                setOptions(o, kwargs, "warnings");
                return warningMessages(w.warnings(o, names));
            },
            py::arg("options") = py::none(), py::kw_only(), py::arg("names") = std::vector<std::string>{},
            "What would make stepping from here with these options a poor simulation (docs/warnings.md), as "
            "messages saying why and what to do; empty when nothing was found. Options as for step(); `names` "
            "(per body handle) name the bodies in the messages.")
        .def_property_readonly("time", &World::time)
        .def_property_readonly("stats", [](const World& w) { return statsDict(w.lastStepStats()); })
        .def("contacts", &contactsDict,
             "The contact points of the last step that carried load, as arrays of one row per point: body_a and "
             "body_b (the normal points from b toward a; the impulses act on a, b takes the opposite), points "
             "(N, 3), normals (N, 3), separations (N), normal_impulses (N, N s) and friction_impulses (N, 3). "
             "Divided by dt they are the contact forces: a box of mass m at rest on the ground has normal "
             "impulses summing to m g dt.")
        .def_property_readonly("gravity", [](const World& w) { return toArray(w.gravity()); })

        // states
        .def(
            "positions",
            [](const World& w, const py::object& bodies)
            { return rows(w, bodies, 3, [](const BodyState& s, double* row) { put(s.position, row); }); },
            py::arg("bodies") = py::none(),
            "Centres of mass, (N, 3): every body (NaN rows for removed ones), or those named by `bodies`.")
        .def(
            "orientations",
            [](const World& w, const py::object& bodies)
            {
                return rows(w, bodies, 4,
                            [](const BodyState& s, double* row)
                            {
                                row[0] = s.orientation.w();
                                row[1] = s.orientation.x();
                                row[2] = s.orientation.y();
                                row[3] = s.orientation.z();
                            });
            },
            py::arg("bodies") = py::none(), "Unit quaternions (w, x, y, z), (N, 4).")
        .def(
            "linear_velocities",
            [](const World& w, const py::object& bodies)
            { return rows(w, bodies, 3, [](const BodyState& s, double* row) { put(s.linearVelocity, row); }); },
            py::arg("bodies") = py::none(), "Velocities of the centres of mass, (N, 3).")
        .def(
            "angular_velocities",
            [](const World& w, const py::object& bodies)
            { return rows(w, bodies, 3, [](const BodyState& s, double* row) { put(s.angularVelocity, row); }); },
            py::arg("bodies") = py::none(), "Angular velocities, world frame, (N, 3).")
        .def(
            "angular_momenta",
            [](const World& w, const py::object& bodies)
            { return rows(w, bodies, 3, [](const BodyState& s, double* row) { put(s.angularMomentum, row); }); },
            py::arg("bodies") = py::none(), "Angular momenta about the centres of mass, world frame, (N, 3).")
        .def(
            "state",
            [](const World& w, std::int64_t body)
            {
                const BodyState s = w.state(bodyId(body));
                py::dict d;
                d["position"] = toArray(s.position);
                d["orientation"] = toArray(s.orientation);
                d["linear_velocity"] = toArray(s.linearVelocity);
                d["angular_velocity"] = toArray(s.angularVelocity);
                d["angular_momentum"] = toArray(s.angularMomentum);
                return d;
            },
            py::arg("body"))
        .def(
            "set_state",
            [](World& w, std::int64_t body, const py::object& position, const py::object& orientation,
               const py::object& linearVelocity, const py::object& angularVelocity)
            {
                const BodyId id = bodyId(body);
                const BodyState s = w.state(id);
                w.setState(id, position.is_none() ? s.position : vec3(position, "position"),
                           orientation.is_none() ? s.orientation : quat(orientation, "orientation"),
                           linearVelocity.is_none() ? s.linearVelocity : vec3(linearVelocity, "linear_velocity"),
                           angularVelocity.is_none() ? s.angularVelocity : vec3(angularVelocity, "angular_velocity"));
            },
            py::arg("body"), py::kw_only(), py::arg("position") = py::none(), py::arg("orientation") = py::none(),
            py::arg("linear_velocity") = py::none(), py::arg("angular_velocity") = py::none(),
            "Places a dynamic body; what is not given is kept.")
        .def("set_states", &setStates, py::arg("bodies"), py::kw_only(), py::arg("positions") = py::none(),
             py::arg("orientations") = py::none(), py::arg("linear_velocities") = py::none(),
             py::arg("angular_velocities") = py::none(),
             "Places the dynamic bodies `bodies` (M handles) from arrays of M rows; an array not given keeps "
             "what it would set. Nothing is written if any row is refused.")

        // loads
        .def(
            "apply_force",
            [](World& w, std::int64_t body, const py::object& force, const py::object& point)
            {
                if (point.is_none())
                {
                    w.applyForce(bodyId(body), vec3(force, "force"));
                }
                else
                {
                    w.applyForce(bodyId(body), vec3(force, "force"), vec3(point, "point"));
                }
            },
            py::arg("body"), py::arg("force"), py::arg("point") = py::none(),
            "Adds a force (N, world frame) for the next step, through the centre of mass or at a world point.")
        .def(
            "apply_torque",
            [](World& w, std::int64_t body, const py::object& torque)
            { w.applyTorque(bodyId(body), vec3(torque, "torque")); },
            py::arg("body"), py::arg("torque"), "Adds a torque (N m, world frame) for the next step.")
        .def(
            "apply_forces",
            [](World& w, const py::object& bodies, const py::object& forces, const py::object& torques)
            {
                const std::vector<BodyId> ids = selection(w, bodies);
                const auto n = static_cast<py::ssize_t>(ids.size());
                const Array f = forces.is_none() ? Array() : table(forces, "forces", n, 3);
                const Array t = torques.is_none() ? Array() : table(torques, "torques", n, 3);
                for (py::ssize_t r = 0; r < n; ++r)
                {
                    const BodyId id = ids[static_cast<std::size_t>(r)];
                    if (f.size() > 0)
                    {
                        w.applyForce(id, Vec3(f.at(r, 0), f.at(r, 1), f.at(r, 2)));
                    }
                    if (t.size() > 0)
                    {
                        w.applyTorque(id, Vec3(t.at(r, 0), t.at(r, 1), t.at(r, 2)));
                    }
                }
            },
            py::arg("bodies"), py::arg("forces") = py::none(), py::arg("torques") = py::none(),
            "Adds forces and torques to the bodies `bodies` (M handles) from arrays of M rows.")
        .def(
            "apply_impulse",
            [](World& w, std::int64_t body, const py::object& impulse, const py::object& point)
            {
                if (point.is_none())
                {
                    w.applyImpulse(bodyId(body), vec3(impulse, "impulse"));
                }
                else
                {
                    w.applyImpulse(bodyId(body), vec3(impulse, "impulse"), vec3(point, "point"));
                }
            },
            py::arg("body"), py::arg("impulse"), py::arg("point") = py::none(),
            "Changes the velocities at once by an impulse (N s) through the centre of mass or at a world point.")
        .def(
            "apply_angular_impulse",
            [](World& w, std::int64_t body, const py::object& impulse)
            { w.applyAngularImpulse(bodyId(body), vec3(impulse, "angular_impulse")); },
            py::arg("body"), py::arg("angular_impulse"))
        .def(
            "applied_force", [](const World& w, std::int64_t body) { return toArray(w.appliedForce(bodyId(body))); },
            py::arg("body"))
        .def(
            "applied_torque", [](const World& w, std::int64_t body) { return toArray(w.appliedTorque(bodyId(body))); },
            py::arg("body"))

        // filtering
        .def(
            "set_collision_filter",
            [](World& w, std::int64_t body, std::uint32_t group, std::uint32_t mask) {
                w.setCollisionFilter(bodyId(body), {group, mask});
            },
            py::arg("body"), py::arg("group") = 1U, py::arg("mask") = 0xffffffffU,
            "Bodies a and b collide when (a.group & b.mask) and (b.group & a.mask) are both non-zero.")
        .def(
            "collision_filter",
            [](const World& w, std::int64_t body)
            {
                const CollisionFilter f = w.collisionFilter(bodyId(body));
                return py::make_tuple(f.group, f.mask);
            },
            py::arg("body"), "(group, mask)")
        .def(
            "set_collision_enabled",
            [](World& w, std::int64_t a, std::int64_t b, bool enabled)
            { w.setCollisionEnabled(bodyId(a, "a"), bodyId(b, "b"), enabled); },
            py::arg("a"), py::arg("b"), py::arg("enabled"))
        .def(
            "collision_enabled",
            [](const World& w, std::int64_t a, std::int64_t b)
            { return w.collisionEnabled(bodyId(a, "a"), bodyId(b, "b")); },
            py::arg("a"), py::arg("b"))

        // mass properties
        .def(
            "mass", [](const World& w, std::int64_t body) { return w.mass(bodyId(body)); }, py::arg("body"))
        .def(
            "inertia", [](const World& w, std::int64_t body) { return toArray(w.inertia(bodyId(body))); },
            py::arg("body"), "Inertia tensor about the centre of mass, body frame, 3 x 3.")
        .def(
            "principal_inertia",
            [](const World& w, std::int64_t body) { return toArray(w.principalInertia(bodyId(body))); },
            py::arg("body"))
        .def(
            "principal_axes", [](const World& w, std::int64_t body) { return toArray(w.principalAxes(bodyId(body))); },
            py::arg("body"), "Columns: the principal axes in the body frame.")
        .def(
            "set_mass_properties",
            [](World& w, std::int64_t body, Real mass, const py::object& inertia, const py::object& centerOfMass)
            {
                const Array array = asArray(inertia, "inertia");
                Mat3 tensor = Mat3::Zero();
                if (array.ndim() == 1 && array.shape(0) == 3)
                {
                    tensor = Vec3(array.at(0), array.at(1), array.at(2)).asDiagonal();
                }
                else if (array.ndim() == 2 && array.shape(0) == 3 && array.shape(1) == 3)
                {
                    for (int i = 0; i < 3; ++i)
                    {
                        for (int j = 0; j < 3; ++j)
                        {
                            tensor(i, j) = array.at(i, j);
                        }
                    }
                }
                else
                {
                    refuse("inertia",
                           "must be 3 principal moments or a 3 x 3 tensor, got an array of shape " + shapeText(array));
                }
                if (centerOfMass.is_none())
                {
                    w.setMassProperties(bodyId(body), mass, tensor);
                }
                else
                {
                    w.setMassProperties(bodyId(body), mass, tensor, vec3(centerOfMass, "center_of_mass"));
                }
            },
            py::arg("body"), py::arg("mass"), py::arg("inertia"), py::arg("center_of_mass") = py::none(),
            "Mass (kg) and inertia tensor (3 x 3, or 3 principal moments) about the centre of mass, body frame; "
            "with center_of_mass, the centre of mass moves there (shape frame) and the shape stays put.")
        .def(
            "center_of_mass", [](const World& w, std::int64_t body) { return toArray(w.centerOfMass(bodyId(body))); },
            py::arg("body"), "The centre of mass in the shape's frame.")
        .def(
            "shape_pose",
            [](const World& w, std::int64_t body)
            {
                const Pose pose = w.shapePose(bodyId(body));
                return py::make_tuple(toArray(pose.position), toArray(pose.orientation));
            },
            py::arg("body"), "Where the shape lies: (position, quaternion w x y z).")
        .def(
            "set_mass", [](World& w, std::int64_t body, Real mass) { w.setMass(bodyId(body), mass); }, py::arg("body"),
            py::arg("mass"))

        // whole-world figures
        .def("kinetic_energy", &World::kineticEnergy)
        .def("potential_energy", &World::potentialEnergy)
        .def("linear_momentum", [](const World& w) { return toArray(w.linearMomentum()); })
        .def("state_hash", &World::stateHash, "Equal hashes mean bit-identical states.")
        .def("snapshot", &World::snapshot)
        .def("restore", &World::restore, py::arg("snapshot"));

    // ---- scenes and models ----
    py::class_<LoadedScene>(m, "Scene", "A loaded scene file or MJCF model: its world, options and body names.")
        .def_property_readonly(
            "world", [](LoadedScene& s) -> World& { return s.scene.world; },
            py::return_value_policy::reference_internal)
        .def_property_readonly("name", [](const LoadedScene& s) { return s.scene.name; })
        .def_property(
            "options", [](const LoadedScene& s) { return s.scene.options; },
            [](LoadedScene& s, const StepOptions& o) { s.scene.options = o; },
            "The scene's step options (a copy; assign to change them).")
        .def_property_readonly("duration", [](const LoadedScene& s) { return s.scene.duration; })
        .def_property_readonly("body_names", [](const LoadedScene& s) { return s.scene.bodyNames; })
        .def_property_readonly("dynamic_bodies",
                               [](const LoadedScene& s)
                               {
                                   std::vector<std::uint32_t> ids;
                                   for (const BodyId id : s.scene.dynamicBodies)
                                   {
                                       ids.push_back(id.index);
                                   }
                                   return ids;
                               })
        .def(
            "body",
            [](const LoadedScene& s, const std::string& name)
            {
                for (std::size_t b = 0; b < s.scene.bodyNames.size(); ++b)
                {
                    if (s.scene.bodyNames[b] == name)
                    {
                        return b;
                    }
                }
                throw py::key_error("no body named \"" + name + "\" in " + s.scene.name);
            },
            py::arg("name"), "The handle of the body of that name.")
        .def(
            "step",
            [](LoadedScene& s, long long steps, const py::kwargs& kwargs)
            {
                StepOptions o = s.scene.options;
                setOptions(o, kwargs, "step");
                stepWorld(s.scene.world, o, steps);
            },
            py::kw_only(), py::arg("steps") = 1, "Steps the world with the scene's options, keyword overrides applied.")
        .def(
            "warnings",
            [](const LoadedScene& s, const py::kwargs& kwargs)
            {
                StepOptions o = s.scene.options;
                setOptions(o, kwargs, "warnings");
                return warningMessages(s.scene.world.warnings(o, s.scene.bodyNames));
            },
            "World.warnings with the scene's options (keyword overrides applied) and its body names: what the "
            "command line prints before a run.");

    m.def("load_scene", &loadScenePath, py::arg("path"), "Reads a JSON scene file (docs/scene-format.md).");
    m.def("load_model", &loadModelPath, py::arg("path"), "Reads an MJCF model through MuJoCo (docs/mujoco.md).");
    m.def(
        "load",
        [](const std::filesystem::path& path)
        {
            std::string extension = path.extension().string();
            for (char& c : extension)
            {
                c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
            }
            return extension == ".xml" || extension == ".mjcf" ? loadModelPath(path) : loadScenePath(path);
        },
        py::arg("path"), "A scene file, or an MJCF model when the name ends in .xml or .mjcf.");
}

} // namespace impulse::python

PYBIND11_MODULE(impulse, m)
{
    impulse::python::bind(m);
}
