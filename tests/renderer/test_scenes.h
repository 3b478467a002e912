#pragma once

#include <glm/glm.hpp>

#include "scene/camera.h"
#include "scene/job.h"

namespace clipblur::test {

// Camera at the origin looking along +z with up +y: e1 = +y, e2 = e3 x e1 = -x, e3 = +z. With a 90 degree
// vertical field of view, tan(fov/2) = 1 and a 32 x 32 film has 16 pixels per image-plane unit.
inline RenderJob squareFilmJob(int size = 32) {
    RenderJob job;
    job.scene.film.width = size;
    job.scene.film.height = size;
    job.scene.film.background = glm::dvec3(0.0);
    job.scene.camera.vfov_degrees = 90.0;
    job.scene.camera.keys.push_back(CameraKey{0.0, glm::dvec3(0.0), glm::dvec3(0, 0, 1), glm::dvec3(0, 1, 0)});
    job.scene.ambient = glm::dvec3(1.0);
    Material white;
    white.base_color = glm::dvec3(1.0);
    job.scene.materials.push_back(white);
    job.render.method = Method::Stochastic;
    job.render.samples = 16;
    job.render.audit = true;  // every test render checks its fragment invariants (fragment_audit.h)
    job.render.tile_size = 8;
    job.render.seed = 7;
    return job;
}

// World point seen at raster position (x, y) at camera depth `depth`, for the camera of squareFilmJob,
// by inverting the paper's projection by hand: p1 = (H/2 - y)/k along +y, p2 = (x - W/2)/k along -x.
inline glm::dvec3 worldAtRaster(double x, double y, double depth, int size = 32) {
    const double k = 0.5 * size;  // pixels per unit with tan(45 deg) = 1
    const double p1 = (0.5 * size - y) / k;
    const double p2 = (x - 0.5 * size) / k;
    return glm::dvec3(-p2 * depth, p1 * depth, depth);
}

// A quad over raster [x0, x1) x [y0, y1) at constant depth, wound so its front faces the camera.
inline Object rasterQuad(double x0, double y0, double x1, double y1, double depth, int size = 32) {
    Object quad;
    quad.name = "quad";
    quad.mesh.positions = {worldAtRaster(x0, y0, depth, size), worldAtRaster(x1, y0, depth, size),
                           worldAtRaster(x1, y1, depth, size), worldAtRaster(x0, y1, depth, size)};
    // Choose the winding from the normal: (v1-v0) x (v2-v0) must point toward the camera (-z).
    const glm::dvec3 n = glm::cross(quad.mesh.positions[1] - quad.mesh.positions[0],
                                    quad.mesh.positions[2] - quad.mesh.positions[0]);
    if (n.z < 0.0)
        quad.mesh.triangles = {{0, 1, 2}, {0, 2, 3}};
    else
        quad.mesh.triangles = {{0, 2, 1}, {0, 3, 2}};
    return quad;
}

// A rasterQuad that translates by `v` pixels over the shutter [0, 1].
inline Object movingQuad(double x0, double y0, double x1, double y1, double depth, glm::dvec2 v, int size = 32) {
    Object quad = rasterQuad(x0, y0, x1, y1, depth, size);
    const glm::dvec3 shift = worldAtRaster(x0 + v.x, y0 + v.y, depth, size) - worldAtRaster(x0, y0, depth, size);
    quad.transform.push_back(TransformKey{0.0, glm::dvec3(0.0), {1, 0, 0, 0}, glm::dvec3(1.0)});
    quad.transform.push_back(TransformKey{1.0, shift, {1, 0, 0, 0}, glm::dvec3(1.0)});
    return quad;
}

}  // namespace clipblur::test
