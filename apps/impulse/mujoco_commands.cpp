// SPDX-License-Identifier: MIT
#include "mujoco_commands.hpp"

#include <impulse/io/scene.hpp>
#include <impulse/mujoco/compare.hpp>
#include <impulse/mujoco/mjcf_export.hpp>
#include <impulse/mujoco/mujoco.hpp>

#include <cstdio>
#include <fstream>
#include <iostream>

namespace impulse::app
{

int exportMjcf(const std::string& scenePath, const std::string& outPath, double timeconst)
{
    std::string xml;
    try
    {
        xml = mujoco::exportMjcf(io::loadScene(scenePath), timeconst);
    }
    catch (const io::SceneError& error)
    {
        std::cerr << "impulse: " << error.what() << "\n";
        return 2;
    }
    catch (const std::invalid_argument& error)
    {
        std::cerr << "impulse: " << scenePath << ": " << error.what() << "\n";
        return 2;
    }
    if (outPath.empty())
    {
        std::cout << xml;
        return std::cout ? 0 : 1;
    }
    std::ofstream file(outPath, std::ios::binary);
    file << xml;
    file.close();
    if (!file)
    {
        std::cerr << "impulse: " << outPath << ": cannot write\n";
        return 1;
    }
    return 0;
}

int compare(const std::string& scenePath, double timeconst)
{
    mujoco::Comparison c;
    try
    {
        c = mujoco::compareScene(scenePath, timeconst);
    }
    catch (const io::SceneError& error)
    {
        std::cerr << "impulse: " << error.what() << "\n";
        return 2;
    }
    catch (const mujoco::ModelError& error)
    {
        std::cerr << "impulse: " << error.what() << "\n";
        return 1;
    }
    catch (const std::invalid_argument& error)
    {
        std::cerr << "impulse: " << scenePath << ": " << error.what() << "\n";
        return 2;
    }
    std::printf("scene    %s\n", c.scene.c_str());
    std::printf("steps    %lld of %g s; MuJoCo %s runs the %s with native mj_step,\n", c.steps, c.dt,
                mj_versionString(), c.timeconst > 0.0 ? "exported MJCF" : "model");
    if (c.timeconst > 0.0)
    {
        std::printf("         contact time constant %g s (docs/mujoco.md)\n", c.timeconst);
    }
    else
    {
        std::printf("         the model's own contact parameters (docs/mujoco.md)\n");
    }
    std::printf("\n%-30s  %-30s  %-30s  %s\n", "figure", "impulse", "MuJoCo", "oracle (scenarios.md)");
    for (const mujoco::FigureRow& row : c.rows)
    {
        std::printf("%-30s  %-30s  %-30s  %s\n", row.label.c_str(), row.impulse.c_str(), row.mujoco.c_str(),
                    row.oracle.c_str());
    }
    std::printf("%-30s  %-30.4f  %-30.4f\n", "ms per step", c.impulseMsPerStep, c.mujocoMsPerStep);
    return 0;
}

} // namespace impulse::app
