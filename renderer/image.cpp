#include "renderer/image.h"

namespace clipblur {

Image Image::make(int width, int height, const std::vector<std::string>& names) {
    Image image;
    image.width = image.data_width = width;
    image.height = image.data_height = height;
    for (const auto& name : names)
        image.channels.push_back({name, std::vector<float>(static_cast<std::size_t>(width) * height, 0.0f)});
    return image;
}

Image::Channel* Image::find(const std::string& name) {
    for (auto& c : channels)
        if (c.name == name) return &c;
    return nullptr;
}

const Image::Channel* Image::find(const std::string& name) const {
    for (const auto& c : channels)
        if (c.name == name) return &c;
    return nullptr;
}

}  // namespace clipblur
