#pragma once

#include <cmath>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "scene/error.h"

namespace clipblur {

// A texture's filter footprint: the images of a fragment's raster extents in (s, t), the two sides of
// a parallelogram centred on the lookup point. Zero sides mean a point lookup at the finest level.
struct TextureFootprint {
    glm::dvec2 dx{0.0};
    glm::dvec2 dy{0.0};
};

// The process's one OpenImageIO TextureSystem (thread-safe), in the image module (renderer/image_module.h),
// loaded on first use, so that scenes without image textures never start it. Every image is read once,
// turned linear (integer texels are sRGB-encoded: PNG and JPEG 8-bit, glTF's baseColorTexture; float
// texels are already linear) and MIP-mapped with a box filter in linear light into a private temporary
// file, so that filtering averages light, not codes.
class ImageTextures {
public:
    static ImageTextures& shared();

    // Reads and converts `file` unless it already was; throws a scene error at `ref` naming the file (and
    // OpenImageIO's reason) when it is missing or unreadable. Thread-safe.
    void prepare(const std::string& file, const FileLoc& ref);

    // A prepared image, to look up without finding it by name each time; null when `file` was not prepared.
    struct Image;
    virtual const Image* find(const std::string& file) const = 0;

    // Linear RGB of a prepared image at (s, t) (t down from the top row, both repeating), filtered over
    // `footprint`. Thread-safe.
    virtual glm::dvec3 lookup(const Image& image, const glm::dvec2& st, const TextureFootprint& footprint) const = 0;

    // A prepared image's finest level, the texels point lookups interpolate: linear RGB floats, row 0 the
    // top (t = 0), texel (i, j) at rgb[3 (j width + i) + k]. Thread-safe.
    struct Texels {
        int width = 0;
        int height = 0;
        std::vector<float> rgb;
    };
    virtual Texels texels(const Image& image) const = 0;

protected:
    // prepare's work: empty when `file` is (now) prepared, else why it cannot be, naming the file.
    virtual std::string load(const std::string& file) = 0;
    ImageTextures() = default;
    ~ImageTextures() = default;  // the module's, never destroyed through this
};

// sRGB's decoding function (IEC 61966-2-1) for one channel value in [0, 1].
inline double srgbToLinear(double code) {
    return code <= 0.04045 ? code / 12.92 : std::pow((code + 0.055) / 1.055, 2.4);
}

}  // namespace clipblur
