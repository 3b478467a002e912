#include "support/motion_scenes.h"

#include <random>

#include <glm/gtc/quaternion.hpp>

#include "scene/object_motion.h"

namespace clipblur::testing {

Scene stillCameraScene(int width, int height, double vfov_degrees) {
    Scene scene;
    scene.film.width = width;
    scene.film.height = height;
    scene.camera.vfov_degrees = vfov_degrees;
    scene.camera.keys.push_back({0.0, {0, 0, 0}, {0, 0, 1}, {0, 1, 0}});
    scene.materials.emplace_back();
    return scene;
}

Object triangleObject(const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& c) {
    Object object;
    object.name = "triangle";
    object.mesh.positions = {a, b, c};
    object.mesh.triangles = {{0, 1, 2}};
    return object;
}

void addTransformKey(Object& object, double time, const glm::dvec3& translate, const glm::dvec3& axis,
                     double angle, const glm::dvec3& scale) {
    object.transform.push_back({time, translate, glm::angleAxis(angle, glm::normalize(axis)), scale});
}

Scene randomMovingScene(std::uint64_t seed, int objects) {
    std::mt19937_64 rng(seed);
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    auto vec = [&](double scale) { return glm::dvec3(u(rng), u(rng), u(rng)) * scale; };

    Scene scene = stillCameraScene(320, 240, 50.0);
    scene.camera.keys.clear();
    const double key_times[3] = {0.0, 0.4 + 0.2 * u(rng), 1.0};
    for (double t : key_times)
        scene.camera.keys.push_back({t, glm::dvec3(0, 0, -10) + vec(0.5),
                                     glm::dvec3(0, 0, 1) + vec(0.15), glm::dvec3(0, 1, 0) + vec(0.15)});

    for (int o = 0; o < objects; ++o) {
        Object object;
        object.name = "random";
        for (int i = 0; i < 6; ++i) object.mesh.positions.push_back(vec(1.0));
        object.mesh.triangles = {{0, 1, 2}, {3, 4, 5}, {0, 2, 4}};
        // Keys spread over a range a little wider than [0, 1] so some keys are inside the shutter.
        const double t_first = -0.2 + 0.1 * u(rng);
        const double t_mid = 0.5 + 0.3 * u(rng);
        const double t_last = 1.2 + 0.1 * u(rng);
        for (double t : {t_first, t_mid, t_last}) {
            addTransformKey(object, t, vec(1.0), glm::dvec3(0.1, 0.1, 0.1) + vec(1.0), 0.6 * u(rng),
                            glm::dvec3(1.0) + vec(0.2));
        }
        if (o % 2 == 1) {
            for (double t : {0.1, 0.7}) {
                DeformationKey key{t, object.mesh.positions};
                for (auto& p : key.positions) p += vec(0.2);
                object.deformation.push_back(std::move(key));
            }
        }
        scene.objects.push_back(std::move(object));
    }
    return scene;
}

ReferencePoint referenceProjection(const Scene& scene, const Projection& projection, std::uint32_t object,
                                   std::uint32_t triangle, const glm::dvec3& b, double t) {
    const Object& obj = scene.objects[object];
    const auto& tri = obj.mesh.triangles[triangle];
    glm::dvec3 world(0.0);
    for (int j = 0; j < 3; ++j) world += b[j] * evalVertex(obj, tri[j], t);
    const ImagePoint ip = projectToImagePlane(evalCamera(scene.camera, t), world);
    return {projection.toRaster(ip.p), ip.depth};
}

}  // namespace clipblur::testing
