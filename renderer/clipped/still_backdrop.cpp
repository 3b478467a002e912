#include "renderer/clipped/still_backdrop.h"

#include "renderer/clipped/motion_plan.h"
#include "renderer/visibility/embree_device.h"
#include "scene/object_motion.h"

namespace clipblur {

std::vector<char> backdropObjects(const RenderJob& job, double t0, double t1) {
    const Scene& scene = job.scene;
    if (job.render.time_integration != TimeIntegration::Sweep || job.render.shadows ||
        job.render.method != Method::Clipped || !cameraIsStill(scene.camera, t0, t1))
        return {};
    std::vector<char> still(scene.objects.size());
    bool any = false;
    for (std::size_t o = 0; o < scene.objects.size(); ++o) {
        still[o] = isStatic(scene.objects[o], t0, t1);
        any = any || still[o];
    }
    return any ? still : std::vector<char>{};
}

PixelSums renderBackdrop(const RenderJob& job, const std::vector<char>& backdrop_objects, double time,
                         const Projection& projection, const TileGrid& grid, const RenderCallbacks& callbacks,
                         FrameFragmentStats& stats) {
    Scene still = job.scene;
    still.objects.clear();
    for (std::size_t o = 0; o < job.scene.objects.size(); ++o)
        if (backdrop_objects[o]) still.objects.push_back(job.scene.objects[o]);
    const EmbreeDevice device;
    const EmbreeScene embree(device, still, time, time);
    const Shader shader(still, time, time);
    const MeshAdjacency adjacency(still);
    PixelSums sums;
    sums.resize(static_cast<std::size_t>(still.film.width) * still.film.height);
    buildFrameFragments(still, embree, adjacency, projection, grid, time, shader,
                        {job.render.visibility_rays, false, job.render.audit}, callbacks, &sums, stats);
    return sums;
}

}  // namespace clipblur
