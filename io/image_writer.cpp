#include "io/image_writer.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include "clipblur/version.h"
#include "io/shard.h"
#include "io/image_files.h"
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

void writeWith(const std::filesystem::path& file, const ImageFile& image) {
    const std::string why = writeImageFile(file.string(), image);
    if (!why.empty()) throw Error(ExitCode::Output, why);
}

// Colour-like channels may be half; every other channel holds measurements (depth, motion, IDs)
// that half would quantise, so it stays float.
bool mayBeHalf(const std::string& name) {
    return name == "R" || name == "G" || name == "B" || name == "A" || name == "coverage";
}

void addInt(ImageFile& file, const std::string& name, int value) {
    file.set(ImageAttribute::integers(name, kTypeInt, {value}));
}

void addFloat(ImageFile& file, const std::string& name, double value) {
    file.set(ImageAttribute::floats(name, kTypeFloat, {static_cast<float>(value)}));
}

void addString(ImageFile& file, std::string_view name, const std::string& value) {
    file.set(ImageAttribute::string(std::string(name), value));
}

// Standard OpenEXR attributes of a rendered frame, by their OpenEXR names.
void addFrameHeader(ImageFile& file, const FrameHeader& h) {
    file.set(ImageAttribute::integers("framesPerSecond", kTypeRational, {h.fps_numerator, h.fps_denominator}));
    addFloat(file, "expTime", h.exposure_seconds);
    const auto matrix = [](const auto& m) { return std::vector<float>(m.begin(), m.end()); };
    file.set(ImageAttribute::floats("worldToCamera", kTypeMatrix44, matrix(h.world_to_camera)));
    file.set(ImageAttribute::floats("worldToNDC", kTypeMatrix44, matrix(h.world_to_ndc)));
    addInt(file, "clipblur:frame", h.frame);
    addFloat(file, "clipblur:shutterOpen", h.shutter_open);
    addFloat(file, "clipblur:shutterClose", h.shutter_close);
    if (!h.shutter_curve.empty()) addString(file, "clipblur:shutterCurve", h.shutter_curve);
}

void addProvenance(ImageFile& file, const ImageMetadata& metadata) {
    addString(file, "Software", std::string("clipblur ") + kVersion);
    addString(file, "clipblur:version", kVersion);
    addString(file, "clipblur:git", kGitHash);
    addString(file, "clipblur:method", metadata.method);
    if (metadata.samples >= 0) addInt(file, "clipblur:samples", metadata.samples);
    if (metadata.subframes >= 0) addInt(file, "clipblur:subframes", metadata.subframes);
    // 64-bit seeds do not fit an int attribute; a decimal string keeps them exact.
    addString(file, "clipblur:seed", std::to_string(metadata.seed));
    addString(file, kConfigHashKey, metadata.config_hash);
    addFloat(file, "clipblur:renderSeconds", metadata.render_seconds);
    if (metadata.tile_count >= 1) {
        addInt(file, std::string(kTileIndexKey), metadata.tile_index);
        addInt(file, std::string(kTileCountKey), metadata.tile_count);
    }
    for (const auto& [name, value] : metadata.strings) addString(file, name, value);
}

ImageFile exrFile(const Image& image, const ExrFormat& format) {
    ImageFile file;
    file.full_width = image.width;
    file.full_height = image.height;
    file.window = image.window;
    for (const auto& c : image.channels) {
        file.channels.push_back(c.name);
        file.types.push_back(format.half && mayBeHalf(c.name) ? PixelType::Half : PixelType::Float);
    }
    addString(file, "compression", compressionName(format.compression));
    // Linear Rec.709 / sRGB primaries with a D65 white point (ITU-R BT.709: red, green, blue, white xy).
    file.set(ImageAttribute::floats("chromaticities", floatArray(8),
                                    {0.64f, 0.33f, 0.30f, 0.60f, 0.15f, 0.06f, 0.3127f, 0.3290f}));
    return file;
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
        ImageFile file = exrFile(image, format);
        addProvenance(file, metadata);
        if (metadata.frame) addFrameHeader(file, *metadata.frame);

        const std::size_t nc = image.channels.size();
        const std::size_t n = image.window.area();
        file.pixels.resize(n * nc);
        for (std::size_t c = 0; c < nc; ++c) {
            const auto& values = image.channels[c].values;
            for (std::size_t i = 0; i < n; ++i) file.pixels[i * nc + c] = values[i];
        }
        writeWith(temporary, file);
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
        ImageFile file;
        file.full_width = image.width;
        file.full_height = image.height;
        file.window = PixelBounds::sized(0, 0, image.width, image.height);
        file.channels = {"R", "G", "B"};
        file.types.assign(3, PixelType::UInt8);
        // 8-bit codes as float k / 255, which writePngFile rounds back to k exactly.
        std::vector<float>& pixels = file.pixels;
        pixels.assign(static_cast<std::size_t>(image.width) * image.height * 3, 0.0f);
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
                    pixels[dst + c] =
                        encodeSrgb8(static_cast<float>(rgb[c]->values[src] + uncovered * background[c])) / 255.0f;
            }
        }
        writeWith(temporary, file);
    });
}

}  // namespace clipblur
