#pragma once

#include <vector>

#include "renderer/frame_motion.h"
#include "renderer/render_callbacks.h"
#include "renderer/shading/shading.h"
#include "renderer/tiles.h"
#include "renderer/visibility/candidates.h"
#include "renderer/visibility/embree_device.h"
#include "renderer/visibility/embree_scene.h"
#include "scene/camera.h"

namespace clipblur {

// What every stage of one frame reads besides the time it works at: the frame's motion (and through it
// the scene), its Embree scene and mesh adjacency, the shader, the film's projection and tiles, and the
// host's callbacks. The references outlive every stage.
struct FrameSetup {
    const FrameMotion& motion;
    const EmbreeScene& embree;
    const MeshAdjacency& adjacency;
    const Shader& shader;
    Projection projection;
    TileGrid grid;
    const RenderCallbacks& callbacks;

    const Scene& scene() const { return motion.scene(); }
};

struct FrameBuildOptions {
    int tile_size = 16;
    bool shadows = false;  // the shader casts shadow rays into the Embree scene
    FragmentShading fragment_shading = FragmentShading::Integral;
    const std::vector<char>* leave_out = nullptr;  // per object: not in the Embree scene (a still backdrop)
};

// Builds and owns what a frame's FrameSetup points to, for the film of the motion's scene. Neither copied
// nor moved: the setup points into it. The motion and callbacks must outlive it.
class FrameBuild {
public:
    FrameBuild(const FrameMotion& motion, const FrameBuildOptions& options, const RenderCallbacks& callbacks);
    FrameBuild(const FrameBuild&) = delete;
    FrameBuild& operator=(const FrameBuild&) = delete;

    const FrameSetup& setup() const { return setup_; }
    const EmbreeDevice& device() const { return device_; }

private:
    EmbreeDevice device_;
    EmbreeScene embree_;
    Shader shader_;
    MeshAdjacency adjacency_;
    FrameSetup setup_;
};

}  // namespace clipblur
