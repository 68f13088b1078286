// SPDX-License-Identifier: MIT
// PNG through libpng, the reference implementation of the format.
#include <impulse/viz/raster.hpp>

#include <cstdio>
#include <memory>
#include <png.h>
#include <stdexcept>

namespace impulse::viz
{
namespace
{

struct FileCloser
{
    void operator()(std::FILE* file) const { std::fclose(file); }
};
using File = std::unique_ptr<std::FILE, FileCloser>;

[[noreturn]] void raiseError(png_structp, png_const_charp message)
{
    throw std::runtime_error(message);
}

void ignoreWarning(png_structp, png_const_charp) {}

} // namespace

void writePng(const Image& image, const std::filesystem::path& path)
{
    File file(std::fopen(path.c_str(), "wb"));
    if (!file)
    {
        throw std::runtime_error(path.string() + ": cannot open for writing");
    }
    png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, nullptr, raiseError, ignoreWarning);
    png_infop info = png ? png_create_info_struct(png) : nullptr;
    if (!info)
    {
        png_destroy_write_struct(&png, nullptr);
        throw std::runtime_error(path.string() + ": out of memory");
    }
    try
    {
        png_init_io(png, file.get());
        png_set_IHDR(png, info, static_cast<png_uint_32>(image.width), static_cast<png_uint_32>(image.height), 8,
                     PNG_COLOR_TYPE_RGB, PNG_INTERLACE_NONE, PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
        png_write_info(png, info);
        for (int y = 0; y < image.height; ++y)
        {
            png_write_row(png, image.rgb.data() + static_cast<std::size_t>(y) * image.width * 3);
        }
        png_write_end(png, nullptr);
    }
    catch (const std::exception& error)
    {
        png_destroy_write_struct(&png, &info);
        throw std::runtime_error(path.string() + ": " + error.what());
    }
    png_destroy_write_struct(&png, &info);
    if (std::fflush(file.get()) != 0)
    {
        throw std::runtime_error(path.string() + ": write failed");
    }
}

Image readPng(const std::filesystem::path& path)
{
    File file(std::fopen(path.c_str(), "rb"));
    if (!file)
    {
        throw std::runtime_error(path.string() + ": cannot open for reading");
    }
    png_structp png = png_create_read_struct(PNG_LIBPNG_VER_STRING, nullptr, raiseError, ignoreWarning);
    png_infop info = png ? png_create_info_struct(png) : nullptr;
    if (!info)
    {
        png_destroy_read_struct(&png, nullptr, nullptr);
        throw std::runtime_error(path.string() + ": out of memory");
    }
    Image image;
    try
    {
        png_init_io(png, file.get());
        png_read_info(png, info);
        // whatever the file holds, deliver 8-bit RGB
        png_set_expand(png);
        png_set_strip_16(png);
        png_set_strip_alpha(png);
        png_set_gray_to_rgb(png);
        png_read_update_info(png, info);
        image.width = static_cast<int>(png_get_image_width(png, info));
        image.height = static_cast<int>(png_get_image_height(png, info));
        if (png_get_rowbytes(png, info) != static_cast<std::size_t>(image.width) * 3)
        {
            throw std::runtime_error("unexpected row layout");
        }
        image.rgb.resize(static_cast<std::size_t>(image.width) * image.height * 3);
        std::vector<png_bytep> rows(static_cast<std::size_t>(image.height));
        for (int y = 0; y < image.height; ++y)
        {
            rows[static_cast<std::size_t>(y)] = image.rgb.data() + static_cast<std::size_t>(y) * image.width * 3;
        }
        png_read_image(png, rows.data());
        png_read_end(png, nullptr);
    }
    catch (const std::exception& error)
    {
        png_destroy_read_struct(&png, &info, nullptr);
        throw std::runtime_error(path.string() + ": not a readable PNG: " + error.what());
    }
    png_destroy_read_struct(&png, &info, nullptr);
    return image;
}

} // namespace impulse::viz
