#include "renderer/image.h"

namespace clipblur {

Image Image::make(int width, int height, const std::vector<std::string>& names) {
    return make(width, height, PixelBounds::sized(0, 0, width, height), names);
}

Image Image::make(int width, int height, const PixelBounds& window, const std::vector<std::string>& names) {
    Image image;
    image.width = width;
    image.height = height;
    image.window = window;
    const std::size_t n = window.area();
    for (const auto& name : names) image.channels.push_back({name, std::vector<float>(n, 0.0f)});
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

std::vector<std::string> outputChannels(const OutputSettings& output) {
    std::vector<std::string> names{"R", "G", "B", "A"};
    if (output.aov_depth) names.push_back("Z");
    if (output.aov_coverage) names.push_back("coverage");
    if (output.aov_motion) {
        names.push_back("motion.x");
        names.push_back("motion.y");
    }
    return names;
}

}  // namespace clipblur
