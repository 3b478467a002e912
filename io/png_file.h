#pragma once

#include <string>

#include "renderer/image_file.h"

namespace clipblur {

// Writes `image` (1 to 4 channels: grey, grey and alpha, RGB, RGBA; every channel PixelType::UInt8,
// its values k / 255) as an 8-bit PNG through libpng, with an sRGB chunk: clipblur's previews are
// sRGB-encoded (image_writer.h). Empty on success, else why not. Only the display window is written;
// the data window must be it.
std::string writePngFile(const std::string& file, const ImageFile& image);

}  // namespace clipblur
