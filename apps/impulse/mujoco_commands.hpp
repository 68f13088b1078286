// SPDX-License-Identifier: MIT
// The subcommands that need MuJoCo: export-mjcf and compare (and MJCF models for run).
#pragma once

#include <string>

namespace impulse::app
{

/// `impulse export-mjcf SCENE [--out FILE]`: writes the scene as MJCF to FILE, or to standard output.
int exportMjcf(const std::string& scenePath, const std::string& outPath, double timeconst);

/// `impulse compare SCENE`: runs the scene in impulse and in MuJoCo and prints the figures side by side.
int compare(const std::string& scenePath, double timeconst);

} // namespace impulse::app
