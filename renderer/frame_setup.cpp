#include "renderer/frame_setup.h"

namespace clipblur {

FrameBuild::FrameBuild(const FrameMotion& motion, const FrameBuildOptions& options, const RenderCallbacks& callbacks)
    // Shadow rays ask at every re-clip's time, which would build every segment's scene.
    : embree_(device_, motion, options.leave_out,
              options.shadows ? EmbreeScene::Layout::Whole : EmbreeScene::Layout::PerSegment),
      shader_(motion, options.shadows ? &embree_ : nullptr, options.fragment_shading),
      adjacency_(motion.scene()),
      setup_{motion,
             embree_,
             adjacency_,
             shader_,
             Projection(motion.scene().film.width, motion.scene().film.height, motion.scene().camera.vfov_degrees),
             TileGrid(motion.scene().film.width, motion.scene().film.height, options.tile_size),
             callbacks} {}

}  // namespace clipblur
