#include "renderer/integrate/tile_sums.h"

namespace clipblur {

void TileSums::reset(const PixelBounds& b) {
    box = b;
    const std::size_t pixels = b.area();
    colour.assign(pixels, glm::dvec3(0.0));
    covered.assign(pixels, 0.0);
    depth.assign(pixels, 0.0);
    motion.assign(pixels, glm::dvec2(0.0));
    objects.assign(track_objects ? pixels : 0, {});
    d3.assign(track_error ? pixels : 0, glm::dvec4(0.0));
}

}  // namespace clipblur
