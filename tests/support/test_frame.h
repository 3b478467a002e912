#pragma once

#include "renderer/frame_setup.h"

namespace clipblur::test {

// A scene's frame over [t0, t1] with everything a stage reads (FrameSetup), owned in one place for tests.
// The scene must outlive it.
class TestFrame {
public:
    TestFrame(const Scene& scene, double t0, double t1, int tile_size = 16)
        : motion_(scene, t0, t1), build_(motion_, {.tile_size = tile_size}, callbacks_) {}

    const FrameSetup& setup() const { return build_.setup(); }

private:
    RenderCallbacks callbacks_;
    FrameMotion motion_;
    FrameBuild build_;
};

}  // namespace clipblur::test
