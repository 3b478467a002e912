#include <cstddef>
#include <cstdint>
#include <string>

#include "scene/error.h"
#include "scene/gltf_loader.h"

// Feeds the bytes (JSON .gltf or binary .glb, told apart by content) to tinygltf and the scene builder:
// accessors, hierarchy, animation resampling, morphs and cameras. A clipblur::Error is an expected
// outcome; a crash, sanitizer report, other exception or a hang (libFuzzer's -timeout) is a finding.
// External URIs resolve in a folder that does not exist, so no file outside the input is read.
extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const std::string bytes(reinterpret_cast<const char*>(data), size);
    clipblur::GltfRequest request;
    request.ref = clipblur::FileLoc{"job.yaml", 1, 1};
    request.frames = {0, 2, 24.0};
    request.max_triangles = std::uint64_t{1} << 20;
    request.max_transform_keys = 4096;
    request.max_deformation_keys = 129;
    try {
        clipblur::parseGltfScene(bytes, "fuzz.gltf", "/nonexistent-clipblur-fuzz", request);
    } catch (const clipblur::Error&) {
    }
    return 0;
}
