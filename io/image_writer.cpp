#include "io/image_writer.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include <OpenImageIO/imageio.h>

#include "clipblur/version.h"
#include "io/shard.h"
#include "scene/error.h"

namespace clipblur {

namespace {

void checkImage(const Image& image) {
    const std::size_t n = image.window.area();
    if (image.channels.empty()) throw Error(ExitCode::Output, "image has no channels");
    for (const auto& c : image.channels)
        if (c.values.size() != n)
            throw Error(ExitCode::Output, "channel '" + c.name + "' has " + std::to_string(c.values.size()) +
                                              " values for a " + std::to_string(image.window.width()) + "x" +
                                              std::to_string(image.window.height()) + " data window");
}

void writeWith(const std::filesystem::path& file, const OIIO::ImageSpec& spec, const void* pixels,
               OIIO::TypeDesc pixel_type) {
    auto out = OIIO::ImageOutput::create(file.string());
    if (!out) throw Error(ExitCode::Output, "cannot create a writer for " + file.string() + ": " + OIIO::geterror());
    if (!out->open(file.string(), spec) || !out->write_image(pixel_type, pixels) || !out->close())
        throw Error(ExitCode::Output, "cannot write " + file.string() + ": " + out->geterror());
}

// Colour-like channels may be half; every other channel holds measurements (depth, motion, IDs)
// that half would quantise, so it stays float.
bool mayBeHalf(const std::string& name) {
    return name == "R" || name == "G" || name == "B" || name == "A" || name == "coverage";
}

// Standard OpenEXR attributes of a rendered frame (written through OpenImageIO's names).
void addFrameHeader(OIIO::ImageSpec& spec, const FrameHeader& h) {
    const int fps[2] = {h.fps_numerator, h.fps_denominator};
    spec.attribute("framesPerSecond", OIIO::TypeRational, fps);
    spec.attribute("ExposureTime", static_cast<float>(h.exposure_seconds));
    spec.attribute("worldToCamera", OIIO::TypeMatrix44, h.world_to_camera.data());
    spec.attribute("worldToNDC", OIIO::TypeMatrix44, h.world_to_ndc.data());
    spec.attribute("clipblur:frame", h.frame);
    spec.attribute("clipblur:shutterOpen", static_cast<float>(h.shutter_open));
    spec.attribute("clipblur:shutterClose", static_cast<float>(h.shutter_close));
    if (!h.shutter_curve.empty()) spec.attribute("clipblur:shutterCurve", h.shutter_curve);
}

void addProvenance(OIIO::ImageSpec& spec, const ImageMetadata& metadata) {
    spec.attribute("Software", std::string("clipblur ") + kVersion);
    spec.attribute("clipblur:version", kVersion);
    spec.attribute("clipblur:git", kGitHash);
    spec.attribute("clipblur:method", metadata.method);
    if (metadata.samples >= 0) spec.attribute("clipblur:samples", metadata.samples);
    if (metadata.subframes >= 0) spec.attribute("clipblur:subframes", metadata.subframes);
    // 64-bit seeds do not fit an int attribute; a decimal string keeps them exact.
    spec.attribute("clipblur:seed", std::to_string(metadata.seed));
    spec.attribute(kConfigHashKey, metadata.config_hash);
    spec.attribute("clipblur:renderSeconds", static_cast<float>(metadata.render_seconds));
    if (metadata.tile_count >= 1) {
        spec.attribute(kTileIndexKey, metadata.tile_index);
        spec.attribute(kTileCountKey, metadata.tile_count);
    }
    for (const auto& [name, value] : metadata.strings) spec.attribute(name, value);
}

OIIO::ImageSpec exrSpec(const Image& image, const ExrFormat& format) {
    const int nc = static_cast<int>(image.channels.size());
    OIIO::ImageSpec spec(image.window.width(), image.window.height(), nc, OIIO::TypeDesc::FLOAT);
    spec.x = image.window.x0;
    spec.y = image.window.y0;
    spec.full_x = 0;
    spec.full_y = 0;
    spec.full_width = image.width;
    spec.full_height = image.height;
    spec.channelnames.clear();
    spec.channelformats.clear();
    spec.alpha_channel = -1;
    spec.z_channel = -1;
    for (int c = 0; c < nc; ++c) {
        const std::string& name = image.channels[static_cast<std::size_t>(c)].name;
        spec.channelnames.push_back(name);
        spec.channelformats.push_back(format.half && mayBeHalf(name) ? OIIO::TypeDesc::HALF : OIIO::TypeDesc::FLOAT);
        if (name == "A") spec.alpha_channel = c;
        if (name == "Z") spec.z_channel = c;
    }
    // The format of the colour channels, which readers report as the image's.
    spec.format = format.half ? OIIO::TypeDesc::HALF : OIIO::TypeDesc::FLOAT;
    spec.attribute("compression", compressionName(format.compression));
    // Linear Rec.709 / sRGB primaries with a D65 white point (ITU-R BT.709: red, green, blue, white xy).
    const float chromaticities[8] = {0.64f, 0.33f, 0.30f, 0.60f, 0.15f, 0.06f, 0.3127f, 0.3290f};
    spec.attribute("chromaticities", OIIO::TypeDesc(OIIO::TypeDesc::FLOAT, 8), chromaticities);
    return spec;
}

}  // namespace

const char* compressionName(ExrCompression compression) {
    switch (compression) {
        case ExrCompression::Zip: return "zip";
        case ExrCompression::Piz: return "piz";
        case ExrCompression::Dwaa: return "dwaa";
        case ExrCompression::None: return "none";
    }
    return "zip";
}

void writeExr(const std::filesystem::path& path, const Image& image, const ImageMetadata& metadata,
              const ExrFormat& format) {
    AtomicFileGroup group;
    writeExr(group, path, image, metadata, format);
    group.commit();
}

void writeExr(AtomicFileGroup& group, const std::filesystem::path& path, const Image& image,
              const ImageMetadata& metadata, const ExrFormat& format) {
    group.write(path, [&](const std::filesystem::path& temporary) {
        // Checked inside the atomic write so a bad image can never replace a good file.
        checkImage(image);
        OIIO::ImageSpec spec = exrSpec(image, format);
        addProvenance(spec, metadata);
        if (metadata.frame) addFrameHeader(spec, *metadata.frame);

        const std::size_t nc = image.channels.size();
        const std::size_t n = image.window.area();
        std::vector<float> interleaved(n * nc);
        for (std::size_t c = 0; c < nc; ++c) {
            const auto& values = image.channels[c].values;
            for (std::size_t i = 0; i < n; ++i) interleaved[i * nc + c] = values[i];
        }
        writeWith(temporary, spec, interleaved.data(), OIIO::TypeDesc::FLOAT);
    });
}

std::uint8_t encodeSrgb8(float linear) {
    if (std::isnan(linear)) return 0;
    const double v = std::clamp(static_cast<double>(linear), 0.0, 1.0);
    const double e = v <= 0.0031308 ? 12.92 * v : 1.055 * std::pow(v, 1.0 / 2.4) - 0.055;
    return static_cast<std::uint8_t>(std::lround(e * 255.0));
}

void writePngPreview(const std::filesystem::path& path, const Image& image, const glm::dvec3& background) {
    AtomicFileGroup group;
    writePngPreview(group, path, image, background);
    group.commit();
}

void writePngPreview(AtomicFileGroup& group, const std::filesystem::path& path, const Image& image,
                     const glm::dvec3& background) {
    group.write(path, [&](const std::filesystem::path& temporary) {
        checkImage(image);
        const Image::Channel* rgb[3] = {image.find("R"), image.find("G"), image.find("B")};
        const Image::Channel* alpha = image.find("A");
        for (const auto* c : rgb)
            if (!c) throw Error(ExitCode::Output, "PNG preview needs R, G and B channels");
        if (!alpha) throw Error(ExitCode::Output, "PNG preview needs an A channel");
        std::vector<std::uint8_t> pixels(static_cast<std::size_t>(image.width) * image.height * 3, 0);
        for (int y = 0; y < image.window.height(); ++y) {
            const int fy = y + image.window.y0;
            if (fy < 0 || fy >= image.height) continue;
            for (int x = 0; x < image.window.width(); ++x) {
                const int fx = x + image.window.x0;
                if (fx < 0 || fx >= image.width) continue;
                const std::size_t src = static_cast<std::size_t>(y) * image.window.width() + x;
                const std::size_t dst = (static_cast<std::size_t>(fy) * image.width + fx) * 3;
                const double uncovered = 1.0 - static_cast<double>(alpha->values[src]);
                for (int c = 0; c < 3; ++c)
                    pixels[dst + c] = encodeSrgb8(static_cast<float>(rgb[c]->values[src] + uncovered * background[c]));
            }
        }
        OIIO::ImageSpec spec(image.width, image.height, 3, OIIO::TypeDesc::UINT8);
        spec.attribute("oiio:ColorSpace", "sRGB");
        writeWith(temporary, spec, pixels.data(), OIIO::TypeDesc::UINT8);
    });
}

}  // namespace clipblur
