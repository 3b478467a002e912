#pragma once

#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "scene/job.h"
#include "scene/scene.h"

namespace clipblur {

inline constexpr std::uintmax_t kMaxGltfFileBytes = std::uintmax_t{512} << 20;

// What a job asks of its glTF scene.
struct GltfRequest {
    FileLoc ref;                 // the job's `scene:` value, named in every error
    double fps = 24.0;           // glTF seconds to frames: t_frames = t_seconds * fps
    Shutter shutter;             // with `frames`: where a STEP jump must not fall
    FrameRange frames;
    std::string camera_name;     // a camera node's or camera's name; empty: the first camera, if any
    FileLoc camera_ref;          // of `render.camera`
    std::uint64_t max_triangles = 0;
    std::size_t max_transform_keys = 0;
    std::size_t max_deformation_keys = 0;
    std::vector<std::string> taken_names;  // object names the job already uses
};

// The scene as clipblur holds it: object material indices count from the start of `materials`.
struct GltfScene {
    std::vector<Object> objects;
    std::vector<Material> materials;
    std::optional<Camera> camera;
    double camera_aspect = 0.0;          // the camera's aspectRatio, 0 when not given
    std::vector<std::string> warnings;   // features read but ignored
    std::vector<std::filesystem::path> buffer_files;  // external buffers read beside the file
};

// Loads a .gltf or .glb file (told apart by content) with its buffers, relative to its folder. Every
// error is a scene error located at the file and naming the JSON pointer of the offending element.
GltfScene loadGltfScene(const std::filesystem::path& file, const GltfRequest& request);

// The same from bytes in memory; `name` is the file name in messages and `base` anchors relative URIs.
GltfScene parseGltfScene(const std::string& bytes, const std::string& name, const std::filesystem::path& base,
                         const GltfRequest& request);

}  // namespace clipblur
