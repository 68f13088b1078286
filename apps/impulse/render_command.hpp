// SPDX-License-Identifier: MIT
#pragma once

#include <optional>
#include <string>

namespace impulse::app
{

/// What `impulse render` was asked to do.
struct RenderOptions
{
    std::string inputPath; ///< a scene (.json), simulated here, or a trajectory CSV
    std::string scenePath; ///< for a trajectory: the scene it came from (shapes, ground)
    std::string outPath;   ///< a directory for frames (and the MP4), or FILE.png for one picture
    std::string size = "640x480";
    double fps = 30.0;
    std::optional<double> duration; ///< scene input: overrides the scene's duration
    std::optional<double> at;       ///< FILE.png output: the time shown (default: the end)
    bool trail = false;             ///< draw each centre's path so far
    bool video = true;              ///< directory output: also an MP4 when ffmpeg is on PATH
    std::string viewDirection;      ///< "X,Y,Z": look from this direction; default: front right, above
    std::string cameraPosition;     ///< "X,Y,Z": the eye, looking at the dynamic bodies' centre
    std::string lookAt;             ///< "X,Y,Z": with cameraPosition, the point looked at
    double zoom = 1.0;              ///< > 1 narrows the field of view (closer), < 1 widens it
    bool progress = true;           ///< a progress line, when standard error is a terminal
};

/// Renders frames of a scene or a trajectory with the software rasteriser. Returns the exit code:
/// 0, 2 for unusable input or options, 1 when writing fails, 128 + the signal when Ctrl-C or
/// SIGTERM stopped it (after a whole frame; no video then).
int renderRun(const RenderOptions& options);

} // namespace impulse::app
