#pragma once

#include <cstdint>
#include <filesystem>
#include <string>

#include "io/atomic_file.h"
#include "renderer/image.h"

namespace clipblur {

// Provenance written into the EXR header as clipblur:* attributes.
struct ImageMetadata {
    std::string method;
    int samples = -1;    // omitted when negative
    int subframes = -1;  // omitted when negative
    std::uint64_t seed = 0;
    std::string config_hash;
    double render_seconds = 0.0;
    int tile_index = -1;  // a shard of `render --tile I/N`: I and N; omitted when tile_count < 1
    int tile_count = 0;
};

// OpenEXR with the image's channels in order (R, G, B, A, then AOVs), half or float, its data window
// inside the full display window, zip compressed, written atomically. Throws Error(ExitCode::Output).
void writeExr(const std::filesystem::path& path, const Image& image, const ImageMetadata& metadata, bool half);
// The same as part of `group`: in place only when the group commits.
void writeExr(AtomicFileGroup& group, const std::filesystem::path& path, const Image& image,
              const ImageMetadata& metadata, bool half);

// 8-bit sRGB-encoded RGB PNG of the display window (zero outside the data window), written atomically.
// RGB only: the colour already holds the background where coverage is partial, so an alpha channel
// would count the background twice in viewers that composite.
void writePngPreview(const std::filesystem::path& path, const Image& image);
void writePngPreview(AtomicFileGroup& group, const std::filesystem::path& path, const Image& image);

// sRGB transfer function (IEC 61966-2-1) of a linear value clamped to [0, 1], as 0..255.
std::uint8_t encodeSrgb8(float linear);

}  // namespace clipblur
