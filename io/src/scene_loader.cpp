// SPDX-License-Identifier: MIT
// Scene files: JSON read with nlohmann-json, checked field by field so that every problem is
// reported with the file, the field's JSON pointer and what is wrong. Unknown fields are refused:
// a misspelt field silently ignored would be a silently wrong simulation.
#include <impulse/io/mesh_file.hpp>
#include <impulse/io/scene.hpp>

#include <nlohmann/json.hpp>

#include <cmath>
#include <fstream>
#include <initializer_list>
#include <map>
#include <numbers>
#include <sstream>
#include <tuple>

namespace impulse::io
{
namespace
{

using Json = nlohmann::json;

std::string typeName(const Json& j)
{
    if (j.is_number())
    {
        return "number";
    }
    return j.type_name();
}

std::string describe(const Json& j)
{
    // containers by type and size only: quoting them could recurse through any depth of nesting
    if (j.is_array())
    {
        return "an array of " + std::to_string(j.size());
    }
    if (j.is_object())
    {
        return "an object";
    }
    std::string text = j.dump();
    if (text.size() > 40)
    {
        text = text.substr(0, 37) + "...";
    }
    return text;
}

// A JSON value together with where it sits in the file, for error messages.
class Field
{
  public:
    Field(const Json& value, std::string pointer, const std::string& source)
        : m_value(value), m_pointer(std::move(pointer)), m_source(source)
    {
    }

    [[noreturn]] void fail(const std::string& what) const
    {
        throw SceneError(m_source + ": " + (m_pointer.empty() ? "/" : m_pointer) + ": " + what);
    }

    const Json& json() const { return m_value; }

    bool has(const char* key) const { return m_value.is_object() && m_value.contains(key); }

    Field at(const char* key) const
    {
        if (!has(key))
        {
            Field(m_value, m_pointer + "/" + key, m_source).fail("missing required field");
        }
        return Field(m_value.at(key), m_pointer + "/" + key, m_source);
    }

    Field item(std::size_t index) const
    {
        return Field(m_value.at(index), m_pointer + "/" + std::to_string(index), m_source);
    }

    void requireObject(std::initializer_list<const char*> allowed) const
    {
        if (!m_value.is_object())
        {
            fail("must be an object, got " + typeName(m_value));
        }
        for (const auto& [key, value] : m_value.items())
        {
            bool known = false;
            std::string expected;
            for (const char* name : allowed)
            {
                known = known || key == name;
                expected += std::string(expected.empty() ? "" : ", ") + name;
            }
            if (!known)
            {
                Field(value, m_pointer + "/" + key, m_source).fail("unknown field (expected one of: " + expected + ")");
            }
        }
    }

    std::size_t arraySize() const
    {
        if (!m_value.is_array())
        {
            fail("must be an array, got " + typeName(m_value));
        }
        return m_value.size();
    }

    Real number() const
    {
        if (!m_value.is_number())
        {
            fail("must be a number, got " + typeName(m_value) + " " + describe(m_value));
        }
        const Real value = m_value.get<Real>();
        if (!std::isfinite(value))
        {
            fail("must be a finite number");
        }
        return value;
    }

    Real positive() const
    {
        const Real value = number();
        if (!(value > 0.0))
        {
            fail("must be positive, got " + describe(m_value));
        }
        return value;
    }

    Real nonNegative() const
    {
        const Real value = number();
        if (value < 0.0)
        {
            fail("must not be negative, got " + describe(m_value));
        }
        return value;
    }

    Real inRange(Real lower, Real upper) const
    {
        const Real value = number();
        if (value < lower || value > upper)
        {
            std::ostringstream range;
            range << "must be in [" << lower << ", " << upper << "], got " << describe(m_value);
            fail(range.str());
        }
        return value;
    }

    int count(int minimum) const
    {
        if (!m_value.is_number_integer())
        {
            fail("must be a whole number, got " + describe(m_value));
        }
        const auto value = m_value.get<long long>();
        if (value < minimum || value > 1000000)
        {
            fail("must be a whole number from " + std::to_string(minimum) + " to 1000000, got " + describe(m_value));
        }
        return static_cast<int>(value);
    }

    bool boolean() const
    {
        if (!m_value.is_boolean())
        {
            fail("must be true or false, got " + describe(m_value));
        }
        return m_value.get<bool>();
    }

    std::string text() const
    {
        if (!m_value.is_string())
        {
            fail("must be a string, got " + typeName(m_value));
        }
        return m_value.get<std::string>();
    }

    Vec3 vec3() const
    {
        if (!m_value.is_array() || m_value.size() != 3)
        {
            fail("must be an array of 3 numbers, got " + describe(m_value));
        }
        return {item(0).number(), item(1).number(), item(2).number()};
    }

    // kg m^2: [Ixx, Iyy, Izz] on the shape's axes, or a whole tensor [[Ixx, Ixy, Ixz], [Ixy, Iyy, Iyz],
    // [Ixz, Iyz, Izz]]; what a tensor must satisfy is checked by World::createBody
    Mat3 inertiaTensor() const
    {
        if (m_value.is_array() && m_value.size() == 3 && !m_value[0].is_array())
        {
            return positiveVec3().asDiagonal();
        }
        if (!m_value.is_array() || m_value.size() != 3)
        {
            fail("must be [Ixx, Iyy, Izz] or a 3 x 3 matrix of rows, in kg m^2, got " + describe(m_value));
        }
        Mat3 tensor;
        for (std::size_t row = 0; row < 3; ++row)
        {
            tensor.row(static_cast<Eigen::Index>(row)) = item(row).vec3().transpose();
        }
        return tensor;
    }

    Vec3 nonZeroVec3() const
    {
        const Vec3 value = vec3();
        if (!(value.norm() > 0.0))
        {
            fail("must not be the zero vector");
        }
        return value;
    }

    Vec3 positiveVec3() const
    {
        const Vec3 value = vec3();
        for (std::size_t i = 0; i < 3; ++i)
        {
            item(i).positive();
        }
        return value;
    }

    // [w, x, y, z], or {"axis": [x, y, z], "angle_deg": a}
    Quat orientation() const
    {
        if (m_value.is_object())
        {
            requireObject({"axis", "angle_deg"});
            const Vec3 axis = at("axis").nonZeroVec3().stableNormalized();
            const Real angle = at("angle_deg").number() * std::numbers::pi / 180.0;
            return Quat(Eigen::AngleAxisd(angle, axis));
        }
        if (!m_value.is_array() || m_value.size() != 4)
        {
            fail("must be a quaternion [w, x, y, z] or {\"axis\": [x, y, z], \"angle_deg\": a}, got " +
                 describe(m_value));
        }
        const Eigen::Vector4d wxyz(item(0).number(), item(1).number(), item(2).number(), item(3).number());
        if (!(wxyz.stableNorm() > 0.0))
        {
            fail("must not be the zero quaternion");
        }
        const Eigen::Vector4d unit = wxyz.stableNormalized();
        return Quat(unit[0], unit[1], unit[2], unit[3]);
    }

  private:
    const Json& m_value;
    std::string m_pointer;
    const std::string& m_source;
};

// Meshes read so far in this scene, so bodies that use the same file, scale and grid share one
// prepared geometry.
struct MeshLibrary
{
    std::filesystem::path directory; ///< relative mesh paths start here: the scene file's directory
    SceneLimits limits;
    std::map<std::tuple<std::string, Real, Real, Real, int>, std::shared_ptr<const MeshGeometry>> prepared;
    std::map<const MeshGeometry*, MeshSource> sources; ///< what each prepared geometry was read from
};

Mesh readMesh(const Field& field, MeshLibrary& library)
{
    field.requireObject({"type", "file", "scale", "resolution"});
    const Field file = field.at("file");
    const std::string name = file.text();
    if (name.find('\0') != std::string::npos)
    {
        // the system would read the path only up to it, a different file from the one named
        file.fail("must not contain a NUL character");
    }
    const std::filesystem::path relative(name);
    if (library.limits.meshFilesInsideDirectory)
    {
        if (relative.has_root_path())
        {
            file.fail("must be a path inside the scene's directory, got the absolute path " + describe(file.json()));
        }
        for (const auto& part : relative)
        {
            if (part == "..")
            {
                file.fail("must be a path inside the scene's directory, got " + describe(file.json()) +
                          ", which leaves it by \"..\"");
            }
        }
    }
    const std::filesystem::path path = library.directory / relative;
    Vec3 scale = Vec3::Ones();
    if (field.has("scale"))
    {
        const Field value = field.at("scale");
        scale = value.json().is_array() ? value.positiveVec3() : Vec3::Constant(value.positive());
    }
    MeshOptions options;
    options.maxGridSamples = library.limits.maxGridSamples;
    if (field.has("resolution"))
    {
        options.resolution = field.at("resolution").count(4);
        if (options.resolution > 1024)
        {
            field.at("resolution").fail("must be at most 1024 cells, got " + std::to_string(options.resolution));
        }
    }
    const auto key =
        std::make_tuple(path.lexically_normal().string(), scale.x(), scale.y(), scale.z(), options.resolution);
    if (const auto found = library.prepared.find(key); found != library.prepared.end())
    {
        return Mesh{found->second};
    }
    try
    {
        TriangleMesh mesh = readMeshFile(path);
        for (Vec3& vertex : mesh.vertices)
        {
            vertex = vertex.cwiseProduct(scale);
        }
        const auto geometry = MeshGeometry::build(mesh, options);
        library.prepared.emplace(key, geometry);
        library.sources.emplace(geometry.get(), MeshSource{path, scale, options.resolution});
        return Mesh{geometry};
    }
    catch (const MeshFileError& error)
    {
        file.fail(error.what());
    }
    catch (const MeshError& error)
    {
        file.fail(path.string() + ": " + error.what());
    }
}

Shape readShape(const Field& field, MeshLibrary& meshes)
{
    field.requireObject(
        {"type", "radius", "half_extents", "normal", "offset", "half_length", "file", "scale", "resolution"});
    const std::string type = field.at("type").text();
    if (type == "sphere")
    {
        field.requireObject({"type", "radius"});
        return Sphere{field.at("radius").positive()};
    }
    if (type == "box")
    {
        field.requireObject({"type", "half_extents"});
        return Box{field.at("half_extents").positiveVec3()};
    }
    if (type == "plane")
    {
        field.requireObject({"type", "normal", "offset"});
        const Vec3 normal = field.at("normal").nonZeroVec3();
        const Real offset = field.has("offset") ? field.at("offset").number() : 0.0;
        return Plane{normal.stableNormalized(), offset / normal.stableNorm()};
    }
    if (type == "capsule")
    {
        field.requireObject({"type", "radius", "half_length"});
        return Capsule{field.at("radius").positive(), field.at("half_length").positive()};
    }
    if (type == "mesh")
    {
        return readMesh(field, meshes);
    }
    field.at("type").fail("unknown shape \"" + type + "\" (expected sphere, box, plane, capsule or mesh)");
}

Material readMaterial(const Field& field)
{
    field.requireObject({"restitution", "friction"});
    return {field.at("restitution").inRange(0.0, 1.0), field.at("friction").nonNegative()};
}

void readSolver(const Field& field, StepOptions& options)
{
    field.requireObject({"scheme", "collision_iterations", "contact_iterations", "pair_iterations", "contact_thickness",
                         "mid_step_restitution", "time_of_impact_geometry", "restitution_threshold", "resting_approach",
                         "shock_propagation", "push_out", "push_out_allowance", "push_out_speed", "push_out_iterations",
                         "sleep", "sleep_speed", "sleep_time"});
    if (field.has("scheme"))
    {
        const std::string scheme = field.at("scheme").text();
        if (scheme == "guendelman")
        {
            options.scheme = Scheme::Guendelman;
        }
        else if (scheme == "traditional")
        {
            options.scheme = Scheme::Traditional;
        }
        else
        {
            field.at("scheme").fail("unknown scheme \"" + scheme + "\" (expected guendelman or traditional)");
        }
    }
    if (field.has("shock_propagation"))
    {
        options.shockPropagation = field.at("shock_propagation").boolean();
    }
    if (field.has("push_out"))
    {
        options.pushOut = field.at("push_out").boolean();
    }
    if (field.has("push_out_allowance"))
    {
        options.pushOutAllowance = field.at("push_out_allowance").nonNegative();
    }
    if (field.has("push_out_speed"))
    {
        options.pushOutSpeed = field.at("push_out_speed").nonNegative();
    }
    if (field.has("push_out_iterations"))
    {
        options.pushOutIterations = field.at("push_out_iterations").count(0);
    }
    if (field.has("sleep"))
    {
        options.sleep = field.at("sleep").boolean();
    }
    if (field.has("sleep_speed"))
    {
        options.sleepSpeed = field.at("sleep_speed").nonNegative();
    }
    if (field.has("sleep_time"))
    {
        options.sleepTime = field.at("sleep_time").nonNegative();
    }
    if (field.has("restitution_threshold"))
    {
        options.restitutionThreshold = field.at("restitution_threshold").nonNegative();
    }
    if (field.has("resting_approach"))
    {
        options.restingApproach = field.at("resting_approach").nonNegative();
    }
    if (field.has("collision_iterations"))
    {
        options.collisionIterations = field.at("collision_iterations").count(0);
    }
    if (field.has("contact_iterations"))
    {
        options.contactIterations = field.at("contact_iterations").count(1);
    }
    if (field.has("pair_iterations"))
    {
        options.pairIterations = field.at("pair_iterations").count(1);
    }
    if (field.has("contact_thickness"))
    {
        options.contactThickness = field.at("contact_thickness").nonNegative();
    }
    if (field.has("mid_step_restitution"))
    {
        options.midStepRestitution = field.at("mid_step_restitution").boolean();
    }
    if (field.has("time_of_impact_geometry"))
    {
        options.timeOfImpactGeometry = field.at("time_of_impact_geometry").boolean();
    }
}

} // namespace

Scene parseScene(const std::string& text, const std::string& source, const std::filesystem::path& directory,
                 const SceneLimits& limits)
{
    MeshLibrary meshes{directory, limits, {}, {}};
    Json document;
    try
    {
        document = Json::parse(text);
    }
    catch (const Json::exception& error) // parse_error, and out_of_range for numbers such as 1e999
    {
        std::string what = error.what();
        if (const auto bracket = what.find("] "); bracket != std::string::npos)
        {
            what = what.substr(bracket + 2);
        }
        throw SceneError(source + ": not valid JSON: " + what);
    }

    const Field root(document, "", source);
    root.requireObject({"name", "description", "gravity", "dt", "duration", "solver", "materials", "pairs", "bodies"});

    WorldDef worldDef;
    if (root.has("gravity"))
    {
        worldDef.gravity = root.at("gravity").vec3();
    }
    Scene scene{
        root.has("name") ? root.at("name").text() : std::string(), World(worldDef), StepOptions{}, 0.0, {}, {}, {}, {}};
    if (root.has("description"))
    {
        root.at("description").text();
    }
    scene.options.dt = root.at("dt").positive();
    scene.duration = root.at("duration").nonNegative();
    if (root.has("solver"))
    {
        readSolver(root.at("solver"), scene.options);
    }

    // materials: an object of named materials
    const Field materials = root.at("materials");
    if (!materials.json().is_object() || materials.json().empty())
    {
        materials.fail("must be an object with at least one named material");
    }
    std::map<std::string, MaterialId> materialIds;
    for (const auto& [name, value] : materials.json().items())
    {
        materialIds[name] = scene.world.createMaterial(readMaterial(materials.at(name.c_str())));
    }
    const auto lookupMaterial = [&](const Field& field)
    {
        const std::string name = field.text();
        const auto found = materialIds.find(name);
        if (found == materialIds.end())
        {
            field.fail("unknown material \"" + name + "\"");
        }
        return found->second;
    };

    if (root.has("pairs"))
    {
        const Field pairs = root.at("pairs");
        for (std::size_t i = 0; i < pairs.arraySize(); ++i)
        {
            const Field pair = pairs.item(i);
            pair.requireObject({"materials", "restitution", "friction"});
            const Field names = pair.at("materials");
            if (names.arraySize() != 2)
            {
                names.fail("must name exactly two materials");
            }
            scene.world.setPairCoefficients(
                lookupMaterial(names.item(0)), lookupMaterial(names.item(1)),
                {pair.at("restitution").inRange(0.0, 1.0), pair.at("friction").nonNegative()});
        }
    }

    const Field bodies = root.at("bodies");
    const std::size_t bodyCount = bodies.arraySize();
    if (bodyCount == 0)
    {
        bodies.fail("must list at least one body");
    }
    for (std::size_t i = 0; i < bodyCount; ++i)
    {
        const Field body = bodies.item(i);
        body.requireObject({"name", "static", "shape", "material", "mass", "density", "inertia", "center_of_mass",
                            "position", "orientation", "velocity", "angular_velocity"});
        BodyDef def;
        def.type = body.has("static") && body.at("static").boolean() ? BodyType::Static : BodyType::Dynamic;
        def.shape = readShape(body.at("shape"), meshes);
        def.material = lookupMaterial(body.at("material"));
        if (body.has("position"))
        {
            def.position = body.at("position").vec3();
        }
        if (body.has("orientation"))
        {
            def.orientation = body.at("orientation").orientation();
        }
        // the body frame a given inertia tensor is turned into: the mesh's principal axes
        Quat shapeFrameInBody = Quat::Identity();
        // the scene places the shape's own frame (a mesh's: its file's); `centroid` is where the
        // shape's frame in the World (a mesh's: its centroid on its principal axes) lies in it
        Pose centroid;
        if (const auto* mesh = std::get_if<Mesh>(&def.shape))
        {
            centroid = mesh->geometry->frameInMesh();
            def.position += def.orientation * centroid.position;
            def.orientation = def.orientation * centroid.orientation;
            shapeFrameInBody = centroid.orientation.conjugate();
        }
        if (def.type == BodyType::Dynamic)
        {
            if (std::holds_alternative<Plane>(def.shape))
            {
                body.at("shape").fail("a plane must be static (set \"static\": true)");
            }
            if (body.has("density"))
            {
                def.density = body.at("density").positive();
            }
            if (body.has("mass"))
            {
                def.mass = body.at("mass").positive();
            }
            else if (!body.has("density"))
            {
                body.fail("a dynamic body needs \"mass\" or \"density\"");
            }
            if (body.has("inertia"))
            {
                const Mat3 turn = shapeFrameInBody.toRotationMatrix();
                def.inertia = turn * body.at("inertia").inertiaTensor() * turn.transpose();
            }
            if (body.has("center_of_mass"))
            {
                // given in the scene's shape frame; the World takes it in its own shape frame and the
                // body's position at it
                def.centerOfMass = centroid.toLocal(body.at("center_of_mass").vec3());
                def.position += def.orientation * def.centerOfMass;
            }
            if (body.has("velocity"))
            {
                def.linearVelocity = body.at("velocity").vec3();
            }
            if (body.has("angular_velocity"))
            {
                def.angularVelocity = body.at("angular_velocity").vec3();
            }
        }
        else
        {
            for (const char* field : {"mass", "density", "inertia", "center_of_mass", "velocity", "angular_velocity"})
            {
                if (body.has(field))
                {
                    body.at(field).fail("a static body has no " + std::string(field));
                }
            }
        }
        // a body the step's length tolerances cannot serve is refused here, at its size's field;
        // World::step would refuse it too, without the file
        if (const std::string reason = sizeRefusal(thinnestHalfExtent(def.shape), scene.options); !reason.empty())
        {
            const Field shape = body.at("shape");
            const char* size = std::holds_alternative<Box>(def.shape)    ? "half_extents"
                               : std::holds_alternative<Mesh>(def.shape) ? (shape.has("scale") ? "scale" : "file")
                                                                         : "radius";
            shape.at(size).fail(reason);
        }
        try
        {
            const BodyId id = scene.world.createBody(def);
            if (def.type == BodyType::Dynamic)
            {
                scene.dynamicBodies.push_back(id);
            }
        }
        catch (const std::invalid_argument& error)
        {
            // the World names the field ("radius: ..."); report it at that field's pointer
            const std::string what = error.what();
            const auto colon = what.find(": ");
            const std::string name = colon == std::string::npos ? std::string() : what.substr(0, colon);
            const std::string reason = colon == std::string::npos ? what : what.substr(colon + 2);
            if (body.has("shape") && body.at("shape").has(name.c_str()))
            {
                body.at("shape").at(name.c_str()).fail(reason);
            }
            if (!name.empty() && body.has(name.c_str()))
            {
                body.at(name.c_str()).fail(reason);
            }
            body.fail(what);
        }
        scene.bodyNames.push_back(body.has("name") ? body.at("name").text() : std::string());
        scene.bodyDefs.push_back(def);
        const auto* mesh = std::get_if<Mesh>(&def.shape);
        scene.meshSources.push_back(mesh != nullptr ? meshes.sources.at(mesh->geometry.get()) : MeshSource{});
    }
    return scene;
}

Scene loadScene(const std::filesystem::path& path)
{
    std::ifstream in(path, std::ios::binary);
    if (!in)
    {
        throw SceneError(path.string() + ": cannot open the file");
    }
    std::ostringstream text;
    text << in.rdbuf();
    return parseScene(text.str(), path.string(), path.parent_path());
}

} // namespace impulse::io
