// SPDX-License-Identifier: MIT
#include "see_inputs.hpp"

#include <impulse/io/scene.hpp>
#ifdef IMPULSE_HAVE_MUJOCO
#include <impulse/mujoco/mujoco.hpp>
#endif

#include <cctype>
#include <charconv>
#include <cstdlib>
#include <filesystem>
#include <iostream>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

extern char** environ;

namespace impulse::app
{

bool isModelPath(const std::string& path)
{
    std::string extension = std::filesystem::path(path).extension().string();
    for (char& c : extension)
    {
        c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    }
    return extension == ".xml" || extension == ".mjcf";
}

io::Scene loadSceneInput(const std::string& path)
{
    try
    {
        if (isModelPath(path))
        {
#ifdef IMPULSE_HAVE_MUJOCO
            return mujoco::loadMjcfScene(path);
#else
            throw InputError(path +
                             ": MJCF models need MuJoCo; this impulse was built without it (IMPULSE_WITH_MUJOCO)");
#endif
        }
        return io::loadScene(path);
    }
    catch (const io::SceneError& error)
    {
        throw InputError(error.what());
    }
#ifdef IMPULSE_HAVE_MUJOCO
    catch (const mujoco::ModelError& error)
    {
        throw InputError(error.what());
    }
#endif
}

LoadedRun loadRun(const std::string& trajectoryPath, const std::string& scenePath)
{
    LoadedRun run;
    try
    {
        run.trajectory = io::readTrajectory(trajectoryPath);
        if (!run.trajectory.cutOff.empty())
        {
            std::cerr << "impulse: note: " << trajectoryPath << ": " << run.trajectory.cutOff << "\n";
        }
        run.title = std::filesystem::path(trajectoryPath).stem().string();
        if (scenePath.empty())
        {
            run.view = viz::SceneView::markersFor(run.trajectory);
        }
        else
        {
            const io::Scene scene = loadSceneInput(scenePath);
            run.view = viz::SceneView::fromScene(scene);
            if (!scene.name.empty())
            {
                run.title = scene.name;
            }
            viz::checkMatches(run.view, run.trajectory, scenePath, trajectoryPath);
        }
    }
    catch (const io::TrajectoryError& error)
    {
        throw InputError(error.what());
    }
    catch (const io::SceneError& error)
    {
        throw InputError(error.what());
    }
    return run;
}

std::pair<int, int> parseSize(const std::string& text, const std::string& option)
{
    int width = 0;
    int height = 0;
    const char* end = text.data() + text.size();
    const auto [afterWidth, widthError] = std::from_chars(text.data(), end, width);
    if (widthError == std::errc() && afterWidth != end && *afterWidth == 'x')
    {
        const auto [afterHeight, heightError] = std::from_chars(afterWidth + 1, end, height);
        if (heightError == std::errc() && afterHeight == end && width >= 16 && height >= 16 && width <= 8192 &&
            height <= 8192)
        {
            return {width, height};
        }
    }
    throw InputError(option + ": expected WIDTHxHEIGHT in pixels, each 16 to 8192, got \"" + text + "\"");
}

std::optional<std::string> findExecutable(const std::string& name)
{
    const char* path = std::getenv("PATH");
    std::string directories = path ? path : "/usr/bin:/bin";
    std::size_t begin = 0;
    while (begin <= directories.size())
    {
        const std::size_t end = std::min(directories.find(':', begin), directories.size());
        const std::string directory = directories.substr(begin, end - begin);
        const std::string candidate = (directory.empty() ? std::string(".") : directory) + "/" + name;
        if (::access(candidate.c_str(), X_OK) == 0 && std::filesystem::is_regular_file(candidate))
        {
            return candidate;
        }
        begin = end + 1;
    }
    return std::nullopt;
}

int runProgram(const std::string& program, const std::vector<std::string>& arguments)
{
    std::vector<char*> argv;
    std::vector<std::string> storage;
    storage.reserve(arguments.size() + 1);
    storage.push_back(program);
    storage.insert(storage.end(), arguments.begin(), arguments.end());
    for (std::string& argument : storage)
    {
        argv.push_back(argument.data());
    }
    argv.push_back(nullptr);
    pid_t child = 0;
    if (::posix_spawn(&child, program.c_str(), nullptr, nullptr, argv.data(), environ) != 0)
    {
        return -1;
    }
    int status = 0;
    if (::waitpid(child, &status, 0) != child || !WIFEXITED(status))
    {
        return -1;
    }
    return WEXITSTATUS(status);
}

std::string withExtension(const std::string& path, const std::string& extension)
{
    return std::filesystem::path(path).replace_extension(extension).string();
}

} // namespace impulse::app
