#pragma once

#include <cstdint>
#include <filesystem>
#include <map>
#include <optional>
#include <string>

#include <glm/vec3.hpp>

#include "io/atomic_file.h"
#include "io/exr_frame_header.h"
#include "renderer/image.h"
#include "scene/job.h"

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
    std::optional<FrameHeader> frame;  // camera matrices, fps, frame, shutter; omitted when unset
    std::map<std::string, std::string> strings;  // further string attributes as named (Cryptomatte's)
};

struct ExrFormat {
    // Half applies to R, G, B, A and coverage only: depth, motion and ID channels need float's
    // precision (a half Z steps by 0.0156 at depth 16), so they are float either way.
    bool half = true;
    ExrCompression compression = ExrCompression::Zip;
};

// The OpenEXR / OpenImageIO compression name: zip, piz, dwaa, none.
const char* compressionName(ExrCompression compression);

// OpenEXR with the image's channels in order (R, G, B, A, then AOVs), typed as `format` says, its data
// window inside the full display window, chromaticities of linear Rec.709 (D65 white), written
// atomically. Throws Error(ExitCode::Output).
void writeExr(const std::filesystem::path& path, const Image& image, const ImageMetadata& metadata,
              const ExrFormat& format);
// The same as part of `group`: in place only when the group commits.
void writeExr(AtomicFileGroup& group, const std::filesystem::path& path, const Image& image,
              const ImageMetadata& metadata, const ExrFormat& format);

// 8-bit sRGB-encoded RGB PNG of the display window (zero outside the data window), written atomically:
// the premultiplied colour over `background` (RGB + (1 - A) background). RGB only, as a preview is
// looked at, not composited.
void writePngPreview(const std::filesystem::path& path, const Image& image, const glm::dvec3& background);
void writePngPreview(AtomicFileGroup& group, const std::filesystem::path& path, const Image& image,
                     const glm::dvec3& background);

// sRGB transfer function (IEC 61966-2-1) of a linear value clamped to [0, 1], as 0..255.
std::uint8_t encodeSrgb8(float linear);

}  // namespace clipblur
