// SPDX-License-Identifier: MIT
#include "render_command.hpp"

#include "progress.hpp"
#include "scene_warnings.hpp"
#include "see_inputs.hpp"
#include "stop_request.hpp"

#include <impulse/io/scene.hpp>
#include <impulse/viz/raster.hpp>

#include <algorithm>
#include <charconv>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <sstream>
#include <stdexcept>
#include <variant>

namespace impulse::app
{
namespace
{

/// Simulates a scene, keeping one sample per frame.
LoadedRun simulateScene(const RenderOptions& options)
{
    LoadedRun run;
    io::Scene scene = loadSceneInput(options.inputPath);
    if (!options.scenePath.empty())
    {
        throw InputError("--scene is for a trajectory input; " + options.inputPath + " is a scene already");
    }
    const double duration = options.duration.value_or(scene.duration);
    if (!std::isfinite(duration))
    {
        throw InputError(options.inputPath +
                         ": no duration: pass --duration, or add <numeric name=\"impulse_duration\" "
                         "data=\"SECONDS\"/> to the model's <custom>");
    }
    const double dt = scene.options.dt;
    const auto steps = static_cast<long long>(std::llround(duration / dt));
    const long long stride = std::max(1LL, static_cast<long long>(std::llround(1.0 / (options.fps * dt))));
    if (steps / stride > 100000)
    {
        throw InputError(options.inputPath + ": more than 100000 frames; lower --fps or --duration");
    }
    run.view = viz::SceneView::fromScene(scene);
    run.title = scene.name;
    run.trajectory.bodyCount = scene.dynamicBodies.size();
    auto record = [&](long long step)
    {
        run.trajectory.times.push_back(static_cast<double>(step) * dt);
        for (const BodyId id : scene.dynamicBodies)
        {
            const BodyState s = scene.world.state(id);
            run.trajectory.samples.push_back({s.position, s.orientation, s.linearVelocity, s.angularVelocity});
        }
    };
    reportWarnings(scene, options.inputPath);
    record(0);
    for (long long step = 1; step <= steps; ++step)
    {
        try
        {
            scene.world.step(scene.options);
        }
        catch (const std::invalid_argument& error)
        {
            throw InputError(options.inputPath + ": " + error.what());
        }
        if (step % stride == 0 || step == steps)
        {
            record(step);
        }
    }
    for (const io::BodySample& s : run.trajectory.samples)
    {
        if (!s.position.allFinite() || !s.orientation.coeffs().allFinite())
        {
            throw std::runtime_error(options.inputPath + ": the simulation diverged (non-finite state)");
        }
    }
    return run;
}

/// The sample nearest to time t.
std::size_t sampleAt(const io::Trajectory& trajectory, double t)
{
    const auto& times = trajectory.times;
    const auto upper = std::lower_bound(times.begin(), times.end(), t);
    if (upper == times.begin())
    {
        return 0;
    }
    if (upper == times.end())
    {
        return times.size() - 1;
    }
    const auto lower = upper - 1;
    return static_cast<std::size_t>((t - *lower <= *upper - t ? lower : upper) - times.begin());
}

/// Everything that stays the same from frame to frame: meshes, camera, shadow region.
struct Stage
{
    std::vector<viz::TriangleMesh> dynamicMeshes;
    std::vector<viz::TriangleMesh> staticMeshes;
    viz::Camera camera;
    viz::RenderSettings settings;
};

/// "X,Y,Z" as a vector, or InputError naming the option.
std::optional<Vec3> parseVector(const std::string& text, const std::string& option)
{
    if (text.empty())
    {
        return std::nullopt;
    }
    Vec3 v;
    const char* at = text.data();
    const char* end = text.data() + text.size();
    for (int i = 0; i < 3; ++i)
    {
        const auto [next, error] = std::from_chars(at, end, v[i]);
        const bool last = i == 2;
        if (error != std::errc() || !std::isfinite(v[i]) || (last ? next != end : (next == end || *next != ',')))
        {
            throw InputError(option + ": expected X,Y,Z (three numbers), got \"" + text + "\"");
        }
        at = next + 1;
    }
    return v;
}

/// The camera options, checked before anything is simulated or read.
struct CameraRequest
{
    std::optional<Vec3> direction;
    std::optional<Vec3> position;
    std::optional<Vec3> target;
    double zoom = 1.0;
};

CameraRequest parseCamera(const RenderOptions& options)
{
    CameraRequest request;
    request.direction = parseVector(options.viewDirection, "--view-direction");
    request.position = parseVector(options.cameraPosition, "--camera-position");
    request.target = parseVector(options.lookAt, "--look-at");
    request.zoom = options.zoom;
    if (!(options.zoom > 0.0 && options.zoom <= 1000.0))
    {
        throw InputError("--zoom: must be a number above 0 and at most 1000");
    }
    if (request.direction && request.position)
    {
        throw InputError("--view-direction and --camera-position: give one or the other");
    }
    if (request.target && !request.position)
    {
        throw InputError("--look-at goes with --camera-position");
    }
    if (request.direction && !(request.direction->norm() > 0.0))
    {
        throw InputError("--view-direction: must not be zero");
    }
    if (request.position && request.target && (*request.position - *request.target).norm() < 1e-9)
    {
        throw InputError("--camera-position: the camera is at the point it looks at");
    }
    return request;
}

/// The camera: framing the dynamic bodies from the front right and above, or as the options say.
viz::Camera chooseCamera(const LoadedRun& run, const CameraRequest& request, Real aspect)
{
    const viz::Bounds bounds = viz::dynamicBounds(run.trajectory, run.view);
    const Vec3 up = viz::upDirection(run.view.gravity);
    viz::Camera camera;
    if (request.position)
    {
        camera.eye = *request.position;
        camera.target = request.target.value_or(bounds.centre());
        camera.up = up;
        if ((camera.eye - camera.target).norm() < 1e-9)
        {
            camera.target = camera.eye - up; // at the centre of the bodies: look down
        }
    }
    else if (request.direction)
    {
        camera = viz::frameCamera(bounds, up, aspect, *request.direction);
    }
    else
    {
        camera = viz::frameCamera(bounds, up, aspect);
    }
    // zoom as a lens does: a narrower field of view
    constexpr Real degrees = 180.0 / 3.14159265358979323846;
    camera.fovYDegrees = 2.0 * std::atan(std::tan(0.5 * camera.fovYDegrees / degrees) / request.zoom) * degrees;
    return camera;
}

Stage buildStage(const LoadedRun& run, const viz::Camera& camera, int width, int height)
{
    Stage stage;
    const viz::Bounds bounds = viz::contentBounds(run.trajectory, run.view);
    stage.camera = camera;
    stage.settings.width = width;
    stage.settings.height = height;
    stage.settings.shadowBounds = bounds;
    for (std::size_t k = 0; k < run.view.dynamicShapes.size(); ++k)
    {
        stage.dynamicMeshes.push_back(run.view.dynamicTriangles(k));
    }
    for (const viz::StaticBody& body : run.view.staticBodies)
    {
        // a plane is drawn as a square a few times the size of the scene, under its centre
        const viz::PlanePatch patch{body.pose.toLocal(bounds.centre()), 4.5 * std::max(bounds.radius(), 0.1)};
        stage.staticMeshes.push_back(viz::bodyTriangles(body.shape, {0.7f, 0.7f, 0.72f}, patch));
    }
    return stage;
}

viz::Image renderSample(const LoadedRun& run, const Stage& stage, std::size_t sample, bool trail)
{
    std::vector<viz::DrawnMesh> meshes;
    for (std::size_t k = 0; k < stage.staticMeshes.size(); ++k)
    {
        const bool plane = std::holds_alternative<Plane>(run.view.staticBodies[k].shape);
        meshes.push_back({&stage.staticMeshes[k], run.view.staticBodies[k].pose, !plane});
    }
    std::vector<viz::Polyline> lines;
    for (std::size_t k = 0; k < stage.dynamicMeshes.size(); ++k)
    {
        const io::BodySample& s = run.trajectory.at(sample, k);
        meshes.push_back({&stage.dynamicMeshes[k], Pose::from(s.position, s.orientation)});
        if (trail)
        {
            viz::Polyline line;
            const viz::Rgb c = viz::bodyColour(k);
            line.colour = {0.6f * c.r, 0.6f * c.g, 0.6f * c.b};
            for (std::size_t i = 0; i <= sample; ++i)
            {
                line.points.push_back(run.trajectory.at(i, k).position);
            }
            lines.push_back(std::move(line));
        }
    }
    return viz::renderImage(meshes, lines, stage.camera, stage.settings);
}

/// frame_NNNNN.png, as this command names frames
bool isFrameName(const std::string& name)
{
    return name.size() == 15 && name.starts_with("frame_") && name.ends_with(".png") &&
           std::all_of(name.begin() + 6, name.begin() + 11, [](char c) { return c >= '0' && c <= '9'; });
}

bool endsWithPng(const std::string& path)
{
    return path.size() >= 4 && std::filesystem::path(path).extension() == ".png";
}

} // namespace

int renderRun(const RenderOptions& options)
{
    const bool sceneInput =
        std::filesystem::path(options.inputPath).extension() == ".json" || isModelPath(options.inputPath);
    const bool still = endsWithPng(options.outPath);
    LoadedRun run;
    int width = 0;
    int height = 0;
    CameraRequest cameraRequest;
    try
    {
        std::tie(width, height) = parseSize(options.size, "--size");
        cameraRequest = parseCamera(options);
        if (!(options.fps > 0.0 && options.fps <= 1000.0))
        {
            throw InputError("--fps must be in (0, 1000]");
        }
        if (options.at && !still)
        {
            throw InputError("--at picks the time of one picture: give --out FILE.png");
        }
        if (options.duration && !sceneInput)
        {
            throw InputError("--duration applies to a scene input; " + options.inputPath + " is a trajectory");
        }
        if (sceneInput)
        {
            run = simulateScene(options);
        }
        else
        {
            run = loadRun(options.inputPath, options.scenePath);
        }
        if (options.at && (*options.at < run.trajectory.times.front() || *options.at > run.trajectory.times.back()))
        {
            std::ostringstream message;
            message << "--at " << *options.at << " is outside the run, " << run.trajectory.times.front() << " to "
                    << run.trajectory.times.back() << " s";
            throw InputError(message.str());
        }
    }
    catch (const InputError& error)
    {
        std::cerr << "impulse: " << error.what() << "\n";
        return 2;
    }
    catch (const std::runtime_error& error)
    {
        std::cerr << "impulse: " << error.what() << "\n";
        return 1;
    }

    const Stage stage =
        buildStage(run, chooseCamera(run, cameraRequest, static_cast<Real>(width) / height), width, height);
    try
    {
        if (still)
        {
            const std::size_t sample = sampleAt(run.trajectory, options.at.value_or(run.trajectory.times.back()));
            const auto start = std::chrono::steady_clock::now();
            viz::writePng(renderSample(run, stage, sample, options.trail), options.outPath);
            const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
            std::printf("picture     %s (%dx%d, t = %g s, %.0f ms)\n", options.outPath.c_str(), width, height,
                        run.trajectory.times[sample], 1e3 * seconds);
            return 0;
        }

        const std::filesystem::path directory(options.outPath);
        std::filesystem::create_directories(directory);
        // frames of an earlier, longer render would otherwise join the video
        for (const auto& entry : std::filesystem::directory_iterator(directory))
        {
            if (isFrameName(entry.path().filename().string()))
            {
                std::filesystem::remove(entry.path());
            }
        }
        const double end = run.trajectory.times.back();
        const double begin = run.trajectory.times.front();
        const auto frames = static_cast<std::size_t>(std::floor((end - begin) * options.fps + 1e-9)) + 1;
        if (frames > 100000)
        {
            std::cerr << "impulse: more than 100000 frames; lower --fps\n";
            return 2;
        }
        const auto start = std::chrono::steady_clock::now();
        const StopRequest stop;
        Progress progress(options.progress && stderrIsTerminal(), "frames");
        const std::string label = std::filesystem::path(options.inputPath).filename().string();
        std::size_t written = 0;
        for (std::size_t frame = 0; frame < frames && stop.signal() == 0; ++frame)
        {
            const std::size_t sample = sampleAt(run.trajectory, begin + static_cast<double>(frame) / options.fps);
            char name[32];
            std::snprintf(name, sizeof name, "frame_%05zu.png", frame);
            viz::writePng(renderSample(run, stage, sample, options.trail), directory / name);
            written = frame + 1;
            const auto now = std::chrono::steady_clock::now();
            progress.update(label, static_cast<long long>(written), static_cast<long long>(frames), "", now - start,
                            now);
        }
        progress.clear();
        const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        std::printf("frames      %zu in %s (%dx%d, %g fps), %.1f ms per frame\n", written, directory.c_str(), width,
                    height, options.fps, 1e3 * seconds / static_cast<double>(std::max<std::size_t>(written, 1)));
        if (stop.signal() != 0)
        {
            std::printf("stopped     by %s after %zu of %zu frames; no video\n", stop.name(), written, frames);
            std::fflush(stdout);
            return stop.exitCode();
        }

        if (!options.video)
        {
            return 0;
        }
        const std::optional<std::string> ffmpeg = findExecutable("ffmpeg");
        if (!ffmpeg)
        {
            std::printf("video       none: ffmpeg is not on PATH\n");
            return 0;
        }
        const std::string stem = std::filesystem::path(options.inputPath).stem().string();
        const std::string video = (directory / (stem + ".mp4")).string();
        char rate[32];
        std::snprintf(rate, sizeof rate, "%g", options.fps);
        const int status =
            runProgram(*ffmpeg, {"-y", "-loglevel", "error", "-framerate", rate, "-i",
                                 (directory / "frame_%05d.png").string(), "-vf", "pad=ceil(iw/2)*2:ceil(ih/2)*2",
                                 "-c:v", "libx264", "-pix_fmt", "yuv420p", "-movflags", "+faststart", video});
        if (status != 0)
        {
            std::cerr << "impulse: ffmpeg failed to write " << video << " (exit status " << status << ")\n";
            return 1;
        }
        std::printf("video       %s\n", video.c_str());
    }
    catch (const std::exception& error)
    {
        std::cerr << "impulse: " << error.what() << "\n";
        return 1;
    }
    return 0;
}

} // namespace impulse::app
