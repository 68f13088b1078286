// SPDX-License-Identifier: MIT
// What the fuzz targets share: a private scratch directory for the files a loader reads.
#pragma once

#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
#include <string_view>
#include <system_error>
#include <unistd.h>

namespace impulse::fuzz
{

/// A directory only this process can enter (mode 0700, a fresh name from mkdtemp), removed with
/// everything in it when the process exits normally, as libFuzzer does at the end of a run.
class PrivateDirectory
{
  public:
    explicit PrivateDirectory(const std::string& prefix)
    {
        std::string pattern = (std::filesystem::temp_directory_path() / ("impulse-" + prefix + "-XXXXXX")).string();
        if (mkdtemp(pattern.data()) == nullptr)
        {
            std::perror("mkdtemp");
            std::abort();
        }
        m_path = pattern;
    }
    ~PrivateDirectory()
    {
        std::error_code ignored;
        std::filesystem::remove_all(m_path, ignored);
    }
    PrivateDirectory(const PrivateDirectory&) = delete;
    PrivateDirectory& operator=(const PrivateDirectory&) = delete;

    const std::filesystem::path& path() const { return m_path; }

  private:
    std::filesystem::path m_path;
};

/// Replaces the file's content with `bytes`; aborts if it cannot, which would make every later
/// input test nothing.
inline void writeFile(const std::filesystem::path& path, std::string_view bytes)
{
    std::ofstream out(path, std::ios::binary | std::ios::trunc);
    out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
    if (!out.flush())
    {
        std::perror(path.c_str());
        std::abort();
    }
}

inline std::string_view asText(const std::uint8_t* data, std::size_t size)
{
    return {reinterpret_cast<const char*>(data), size};
}

} // namespace impulse::fuzz
