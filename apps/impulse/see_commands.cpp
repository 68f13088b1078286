// SPDX-License-Identifier: MIT
#include "see_commands.hpp"

#include "option_checks.hpp"

namespace impulse::app
{

SeeCommands::SeeCommands(CLI::App& app)
{
    m_plotCommand = app.add_subcommand(
        "plot", "Plot a trajectory with gnuplot: height, the 3D path of each centre, speed and energy against time");
    m_plotCommand->add_option("trajectory", m_plot.trajectoryPath, "Trajectory CSV written by impulse run --out")
        ->required();
    m_plotCommand->add_option(
        "--scene", m_plot.scenePath,
        "The scene file or MJCF model the trajectory came from: masses and inertias for the total energy, "
        "gravity for height (without it: energy per unit mass, gravity (0, 0, -9.81))");
    m_plotCommand->add_option("--out", m_plot.outPath, "PNG to write (default: the trajectory's name with .png)");
    m_plotCommand->add_option("--size", m_plot.size, "WIDTHxHEIGHT in pixels")->capture_default_str();

    m_renderCommand = app.add_subcommand(
        "render", "Render PNG frames (and an MP4 when ffmpeg is present) of a scene or a trajectory, headless");
    m_renderCommand
        ->add_option(
            "input", m_render.inputPath,
            "A scene (.json) or an MJCF model (.xml), simulated here, or a trajectory CSV (shapes from --scene)")
        ->required();
    m_renderCommand
        ->add_option("--out", m_render.outPath,
                     "Directory for frame_NNNNN.png and INPUT.mp4, or FILE.png for one picture (see --at)")
        ->required();
    m_renderCommand->add_option(
        "--scene", m_render.scenePath,
        "For a trajectory: the scene file or MJCF model it came from (shapes, static bodies, gravity); "
        "without it bodies are marker spheres");
    m_renderCommand->add_option("--size", m_render.size, "WIDTHxHEIGHT in pixels")->capture_default_str();
    m_renderCommand->add_option("--fps", m_render.fps, "Frames per simulated second")->capture_default_str();
    m_renderCommand->add_option("--duration", m_render.duration, "Scene input: simulated time, overrides the scene's")
        ->check(nonNegativeNumber());
    m_renderCommand->add_option("--at", m_render.at, "With --out FILE.png: the time shown (default: the end)");
    m_renderCommand->add_flag("--trail", m_render.trail, "Draw the path of each centre up to the time shown");
    m_renderCommand->add_flag("--no-video", m_noVideo, "Write the frames only, no MP4");
    m_renderCommand->add_option("--view-direction", m_render.viewDirection,
                                "X,Y,Z: look at the dynamic bodies from this direction (e.g. 0,0,1 from above), "
                                "framing them; default: from the front right and above");
    m_renderCommand->add_option("--camera-position", m_render.cameraPosition,
                                "X,Y,Z: put the camera here, looking at the dynamic bodies' centre (or --look-at)");
    m_renderCommand->add_option("--look-at", m_render.lookAt, "X,Y,Z: with --camera-position, the point looked at");
    m_renderCommand->add_option("--zoom", m_render.zoom, "Narrow (> 1) or widen (< 1) the field of view")
        ->capture_default_str();
    m_renderCommand->add_flag("--no-progress", m_noRenderProgress,
                              "No progress line (drawn on standard error only when that is a terminal)");

    m_viewCommand = app.add_subcommand(
        "view", "Write one self-contained HTML page that replays a trajectory in a browser, offline");
    m_viewCommand->add_option("trajectory", m_view.trajectoryPath, "Trajectory CSV written by impulse run --out")
        ->required();
    m_viewCommand->add_option(
        "--scene", m_view.scenePath,
        "The scene file or MJCF model the trajectory came from: shapes, static bodies, masses for the energy");
    m_viewCommand->add_option("--out,--html", m_view.outPath,
                              "HTML file to write (default: the trajectory's name with .html)");
    m_viewCommand
        ->add_option("--three", m_view.threeDirectory,
                     "Directory of three.js (three.min.js, examples/js/controls/OrbitControls.js)")
        ->capture_default_str();
}

std::optional<int> SeeCommands::runChosen() const
{
    if (m_plotCommand->parsed())
    {
        return plotTrajectory(m_plot);
    }
    if (m_renderCommand->parsed())
    {
        RenderOptions options = m_render;
        options.video = !m_noVideo;
        options.progress = !m_noRenderProgress;
        return renderRun(options);
    }
    if (m_viewCommand->parsed())
    {
        return writeViewer(m_view);
    }
    return std::nullopt;
}

} // namespace impulse::app
