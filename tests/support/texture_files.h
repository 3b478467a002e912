#pragma once

#include <cstdint>
#include <filesystem>
#include <vector>

namespace clipblur::testing {

// Writes an 8-bit RGB PNG of width x height pixels, rows top to bottom, 3 bytes per pixel.
void writeRgb8Png(const std::filesystem::path& file, int width, int height, const std::vector<std::uint8_t>& rgb);

}  // namespace clipblur::testing
