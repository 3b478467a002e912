#include "renderer/shading/image_textures.h"

#include <filesystem>
#include <system_error>

#include "renderer/image_module.h"

namespace clipblur {

ImageTextures& ImageTextures::shared() { return imageModule().textures(); }

void ImageTextures::prepare(const std::string& file, const FileLoc& ref) {
    std::error_code ec;
    if (!std::filesystem::is_regular_file(file, ec)) throwSceneError(ref, "texture file '" + file + "' does not exist");
    const std::string why = load(file);
    if (!why.empty()) throwSceneError(ref, why);
}

}  // namespace clipblur
