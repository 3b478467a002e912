#include "io/png_file.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

#include <png.h>

namespace clipblur {

std::string writePngFile(const std::string& file, const ImageFile& image) {
    const std::size_t nc = image.channels.size();
    if (nc < 1 || nc > 4 || image.types.size() != nc ||
        std::any_of(image.types.begin(), image.types.end(), [](PixelType t) { return t != PixelType::UInt8; }))
        return "a PNG is written from 1 to 4 channels of 8 bits";
    if (!(image.window == PixelBounds::sized(image.full_x, image.full_y, image.full_width, image.full_height)) ||
        image.window.empty())
        return "a PNG is written from its whole, non-empty display window";
    if (image.pixels.size() != image.window.area() * nc)
        return "image of " + std::to_string(nc) + " channels has " + std::to_string(image.pixels.size()) +
               " values for its data window";
    std::vector<std::uint8_t> codes(image.pixels.size());
    std::transform(image.pixels.begin(), image.pixels.end(), codes.begin(), [](float v) {
        return static_cast<std::uint8_t>(std::lround(std::clamp(std::isnan(v) ? 0.0f : v, 0.0f, 1.0f) * 255.0f));
    });
    png_image png{};
    png.version = PNG_IMAGE_VERSION;
    png.width = static_cast<png_uint_32>(image.window.width());
    png.height = static_cast<png_uint_32>(image.window.height());
    static constexpr png_uint_32 kFormats[4] = {PNG_FORMAT_GRAY, PNG_FORMAT_GA, PNG_FORMAT_RGB, PNG_FORMAT_RGBA};
    png.format = kFormats[nc - 1];
    // 8-bit and not flagged otherwise: libpng's simplified writer marks the file sRGB.
    const bool ok = png_image_write_to_file(&png, file.c_str(), 0, codes.data(), 0, nullptr) != 0;
    const std::string why = ok ? std::string() : "cannot write " + file + ": " + png.message;
    png_image_free(&png);
    return why;
}

}  // namespace clipblur
