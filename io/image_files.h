#pragma once

#include <string>

#include "renderer/image_file.h"

namespace clipblur {

// Every image read or write of clipblur's commands. OpenEXR files (by extension, or by their magic number
// when read) go through OpenEXR (exr_file.h) and PNG writes through libpng (png_file.h): the files a
// render, a merge and a resume touch, without OpenImageIO's dependency closure. Every other format goes
// through the image module (OpenImageIO, image_module.h), loaded on first use. Empty on success, else why
// not; `out` as ImageModule::read says.
std::string readImageFile(const std::string& file, ImageRead what, ImageFile& out);
std::string writeImageFile(const std::string& file, const ImageFile& image);

}  // namespace clipblur
