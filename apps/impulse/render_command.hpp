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
};

/// Renders frames of a scene or a trajectory with the software rasteriser. Returns the exit code:
/// 0, 2 for unusable input or options, 1 when writing fails.
int renderRun(const RenderOptions& options);

} // namespace impulse::app
