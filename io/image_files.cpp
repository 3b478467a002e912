#include "io/image_files.h"

#include <algorithm>
#include <array>
#include <cctype>
#include <filesystem>
#include <fstream>

#include "io/exr_file.h"
#include "io/png_file.h"
#include "renderer/image_module.h"

namespace clipblur {

namespace {

std::string extensionOf(const std::string& file) {
    std::string ext = std::filesystem::path(file).extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return std::tolower(c); });
    return ext;
}

bool startsAsExr(const std::string& file) {
    std::array<char, 4> magic{};
    std::ifstream in(file, std::ios::binary);
    return in.read(magic.data(), magic.size()) && magic == std::array<char, 4>{0x76, 0x2f, 0x31, 0x01};
}

}  // namespace

std::string readImageFile(const std::string& file, ImageRead what, ImageFile& out) {
    if (extensionOf(file) == ".exr" || startsAsExr(file)) return readExrFile(file, what, out);
    return imageModule().read(file, what, out);
}

std::string writeImageFile(const std::string& file, const ImageFile& image) {
    const std::string ext = extensionOf(file);
    if (ext == ".exr") return writeExrFile(file, image);
    if (ext == ".png") return writePngFile(file, image);
    return imageModule().write(file, image);
}

}  // namespace clipblur
