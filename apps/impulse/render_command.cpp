// SPDX-License-Identifier: MIT
#include "render_command.hpp"

#include "see_inputs.hpp"

#include <impulse/io/scene.hpp>
#include <impulse/viz/raster.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <sstream>
#include <variant>

namespace impulse::app
{
namespace
{

/// Simulates a scene, keeping one sample per frame.
LoadedRun simulateScene(const RenderOptions& options)
{
    LoadedRun run;
    io::Scene scene;
    try
    {
        scene = io::loadScene(options.inputPath);
    }
    catch (const io::SceneError& error)
    {
        throw InputError(error.what());
    }
    if (!options.scenePath.empty())
    {
        throw InputError("--scene is for a trajectory input; " + options.inputPath + " is a scene already");
    }
    const double duration = options.duration.value_or(scene.duration);
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
    record(0);
    for (long long step = 1; step <= steps; ++step)
    {
        scene.world.step(scene.options);
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

Stage buildStage(const LoadedRun& run, int width, int height)
{
    Stage stage;
    const viz::Bounds bounds = viz::contentBounds(run.trajectory, run.view);
    const Vec3 up = viz::upDirection(run.view.gravity);
    stage.camera = viz::frameCamera(bounds, up, static_cast<Real>(width) / height);
    stage.settings.width = width;
    stage.settings.height = height;
    stage.settings.shadowBounds = bounds;
    for (std::size_t k = 0; k < run.view.dynamicShapes.size(); ++k)
    {
        stage.dynamicMeshes.push_back(viz::bodyTriangles(run.view.dynamicShapes[k], viz::bodyColour(k)));
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
    const bool sceneInput = std::filesystem::path(options.inputPath).extension() == ".json";
    const bool still = endsWithPng(options.outPath);
    LoadedRun run;
    int width = 0;
    int height = 0;
    try
    {
        std::tie(width, height) = parseSize(options.size, "--size");
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

    const Stage stage = buildStage(run, width, height);
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
        for (std::size_t frame = 0; frame < frames; ++frame)
        {
            const std::size_t sample = sampleAt(run.trajectory, begin + static_cast<double>(frame) / options.fps);
            char name[32];
            std::snprintf(name, sizeof name, "frame_%05zu.png", frame);
            viz::writePng(renderSample(run, stage, sample, options.trail), directory / name);
        }
        const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        std::printf("frames      %zu in %s (%dx%d, %g fps), %.1f ms per frame\n", frames, directory.c_str(), width,
                    height, options.fps, 1e3 * seconds / static_cast<double>(frames));

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
