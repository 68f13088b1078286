// SPDX-License-Identifier: MIT
// The warnings of a scene about to be run (docs/warnings.md), as every command that simulates prints them.
#pragma once

#include <impulse/io/scene.hpp>

#include <iostream>
#include <string>
#include <vector>

namespace impulse::app
{

/// The messages of what would make stepping `scene` with its options a poor simulation, each also
/// printed on standard error as "impulse: warning: <path>: <message>".
inline std::vector<std::string> reportWarnings(const io::Scene& scene, const std::string& path)
{
    std::vector<std::string> messages;
    for (const Warning& warning : scene.world.warnings(scene.options, scene.bodyNames))
    {
        std::cerr << "impulse: warning: " << path << ": " << warning.message << "\n";
        messages.push_back(warning.message);
    }
    return messages;
}

} // namespace impulse::app
