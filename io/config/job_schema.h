#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "io/config/config_node.h"
#include "scene/job.h"
#include "scene/scene_validation.h"

namespace clipblur::config {

// Caps on what a job may ask for; checked while reading, before anything is allocated.
inline constexpr int kMaxImageSide = 16384;
inline constexpr int kMaxSamples = 1 << 16;
inline constexpr int kMaxSubframes = 4096;
inline constexpr int kMaxSegments = 256;
inline constexpr int kMaxOdeSteps = 1 << 16;
inline constexpr int kMaxVisibilityRays = 64;
inline constexpr int kMaxTileSize = 1024;
inline constexpr int kMaxFrameCount = 1000000;
inline constexpr int kMaxKeys = 4096;
inline constexpr int kMaxShutterCurvePoints = 256;
inline constexpr int kMaxDeformationKeys = 129;  // Embree's time-step limit
inline constexpr int kMaxDivisions = 4096;
inline constexpr std::uint64_t kMaxTrianglesPerObject = std::uint64_t{1} << 23;
inline constexpr std::uint64_t kMaxTotalTriangles = std::uint64_t{1} << 25;

// How one object's mesh is to be made; the loader turns these into meshes.
struct MeshSource {
    enum class Kind { Quad, Grid, Box, Sphere, Obj };
    Kind kind = Kind::Box;
    glm::dvec3 size{1.0};  // quad/grid: x and z extents in .x/.y; box: edges; sphere: diameter in .x
    int nx = 1;
    int nz = 1;
    int segments = 32;
    std::string obj_path;  // as written, relative to the job file's folder
    FileLoc loc;           // of the primitive map or the obj value
    std::uint64_t triangles = 0;  // known up front for primitives, else 0
    bool job_material = false;    // the object names its `material`, which wins over an OBJ's usemtl

    struct Deformation {
        double time = 0.0;
        std::string obj_path;
        FileLoc loc;
    };
    std::vector<Deformation> deformation;
};

// The glTF scene a job names (`scene:`) and the camera it picks from it (`render.camera`).
struct SceneFileSource {
    std::string path;          // as written, relative to the job file's folder; empty: none
    FileLoc loc;               // of the `scene` value
    std::string camera;        // empty: the first camera of the glTF scene
    FileLoc camera_loc;
    bool job_camera = false;   // the job has its own `camera` block, which then wins
};

// Everything the document says, with scene objects still lacking meshes.
struct JobDescription {
    RenderJob job;
    std::vector<MeshSource> meshes;  // one per job.scene.objects entry
    SceneLocations locations;
    SceneFileSource scene_file;
};

// Walks the whole document against the schema (docs/config.md); every key must be consumed.
JobDescription readJobDescription(const ConfigNode& root);

}  // namespace clipblur::config
