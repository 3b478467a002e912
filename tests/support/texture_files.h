#pragma once

#include <cstdint>
#include <filesystem>
#include <vector>

namespace clipblur::testing {

// Writes an 8-bit RGB PNG of width x height pixels, rows top to bottom, 3 bytes per pixel.
void writeRgb8Png(const std::filesystem::path& file, int width, int height, const std::vector<std::uint8_t>& rgb);

// The same as float texels in an OpenEXR file (linear, not decoded).
void writeRgbFloatExr(const std::filesystem::path& file, int width, int height, const std::vector<float>& rgb);

}  // namespace clipblur::testing
