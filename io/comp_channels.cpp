#include "io/comp_channels.h"

#include <cstddef>

#include "scene/error.h"

namespace clipblur {

void bakeBackground(Image& image, const glm::dvec3& background) {
    Image::Channel* rgb[3] = {image.find("R"), image.find("G"), image.find("B")};
    Image::Channel* alpha = image.find("A");
    if (!rgb[0] || !rgb[1] || !rgb[2] || !alpha) throw Error(ExitCode::Internal, "bakeBackground needs R, G, B and A");
    for (std::size_t i = 0; i < alpha->values.size(); ++i) {
        const double uncovered = 1.0 - static_cast<double>(alpha->values[i]);
        for (int c = 0; c < 3; ++c)
            rgb[c]->values[i] = static_cast<float>(rgb[c]->values[i] + uncovered * background[c]);
        alpha->values[i] = 1.0f;
    }
}

void toForwardVectors(Image& image, double shutter_frames) {
    Image::Channel* mx = image.find("motion.x");
    Image::Channel* my = image.find("motion.y");
    if (!mx || !my) return;
    const double per_frame = shutter_frames > 0.0 ? 1.0 / shutter_frames : 0.0;
    for (std::size_t i = 0; i < mx->values.size(); ++i) {
        mx->values[i] = static_cast<float>(mx->values[i] * per_frame);
        // Raster y grows downwards; compositors' image y grows upwards.
        my->values[i] = static_cast<float>(-(my->values[i] * per_frame));
    }
    mx->name = "forward.u";
    my->name = "forward.v";
}

}  // namespace clipblur
