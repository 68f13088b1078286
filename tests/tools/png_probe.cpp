// SPDX-License-Identifier: MIT
// Decodes a PNG and prints "WIDTH HEIGHT SPREAD", SPREAD the standard deviation of its pixel values
// over all channels (0 for a blank picture). Exit code 1, with a message, when it cannot be decoded.
// The CLI and viewer tests use it to check pictures they cannot look at.
#include <impulse/viz/raster.hpp>

#include <cmath>
#include <cstdio>
#include <exception>

int main(int argc, char** argv)
{
    if (argc != 2)
    {
        std::fprintf(stderr, "usage: impulse_png_probe FILE.png\n");
        return 2;
    }
    try
    {
        const impulse::viz::Image image = impulse::viz::readPng(argv[1]);
        double sum = 0.0;
        double squares = 0.0;
        for (const std::uint8_t value : image.rgb)
        {
            sum += value;
            squares += static_cast<double>(value) * value;
        }
        const double count = static_cast<double>(image.rgb.size());
        const double mean = count > 0 ? sum / count : 0.0;
        const double spread = count > 0 ? std::sqrt(std::max(0.0, squares / count - mean * mean)) : 0.0;
        std::printf("%d %d %.3f\n", image.width, image.height, spread);
    }
    catch (const std::exception& error)
    {
        std::fprintf(stderr, "impulse_png_probe: %s\n", error.what());
        return 1;
    }
    return 0;
}
