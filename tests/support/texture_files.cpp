#include "support/texture_files.h"

#include <stdexcept>

#include <OpenImageIO/imageio.h>

namespace clipblur::testing {

void writeRgb8Png(const std::filesystem::path& file, int width, int height, const std::vector<std::uint8_t>& rgb) {
    if (rgb.size() != static_cast<std::size_t>(3 * width * height)) throw std::invalid_argument("writeRgb8Png: size");
    std::filesystem::create_directories(file.parent_path());
    auto out = OIIO::ImageOutput::create(file.string());
    const OIIO::ImageSpec spec(width, height, 3, OIIO::TypeDesc::UINT8);
    if (!out || !out->open(file.string(), spec) || !out->write_image(OIIO::TypeDesc::UINT8, rgb.data()) ||
        !out->close())
        throw std::runtime_error("cannot write " + file.string());
}

void writeRgbFloatExr(const std::filesystem::path& file, int width, int height, const std::vector<float>& rgb) {
    if (rgb.size() != static_cast<std::size_t>(3 * width * height)) throw std::invalid_argument("writeRgbFloatExr: size");
    std::filesystem::create_directories(file.parent_path());
    auto out = OIIO::ImageOutput::create(file.string());
    const OIIO::ImageSpec spec(width, height, 3, OIIO::TypeDesc::FLOAT);
    if (!out || !out->open(file.string(), spec) || !out->write_image(OIIO::TypeDesc::FLOAT, rgb.data()) ||
        !out->close())
        throw std::runtime_error("cannot write " + file.string());
}

}  // namespace clipblur::testing
