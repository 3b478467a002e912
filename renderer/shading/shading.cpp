#include "renderer/shading/shading.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "renderer/shading/texture_integral.h"
#include "renderer/visibility/embree_scene.h"
#include "scene/object_motion.h"

namespace clipblur {

namespace {

// fmod instead of an integer cast: floor(x/s) may exceed the range of any integer type.
bool oddCell(double coordinate, double scale) { return std::fmod(std::floor(coordinate / scale), 2.0) != 0.0; }

}  // namespace

glm::dvec3 albedo(const Material& material, const glm::dvec3& p) {
    const Texture& tex = material.texture;
    switch (tex.kind) {
        case Texture::Kind::None:
            return material.base_color;
        case Texture::Kind::Checker: {
            // Parity of floor(x/s) + floor(y/s) + floor(z/s): the sum is odd iff an odd number of terms is odd.
            const bool odd = oddCell(p.x, tex.scale) ^ oddCell(p.y, tex.scale) ^ oddCell(p.z, tex.scale);
            return odd ? tex.color2 : material.base_color;
        }
        case Texture::Kind::Stripe:
            return oddCell(p.x, tex.scale) ? tex.color2 : material.base_color;
    }
    return material.base_color;
}

bool usesImageTextures(const Scene& scene) {
    for (const Material& m : scene.materials)
        if (!m.image.file.empty() || !m.emission_image.file.empty()) return true;
    return false;
}

glm::dvec3 lightIrradiance(const Light& light, const glm::dvec3& position, const glm::dvec3& normal,
                           glm::dvec3* to_light) {
    if (light.kind == Light::Kind::Directional) {
        const double len = glm::length(light.direction);
        if (!(len > 0.0)) return glm::dvec3(0.0);
        const glm::dvec3 l = -light.direction / len;
        if (to_light) *to_light = l;
        return light.intensity * light.color * std::max(0.0, glm::dot(normal, l));
    }
    const glm::dvec3 d = light.position - position;
    const double dist2 = glm::dot(d, d);
    if (to_light) *to_light = d;
    if (!(dist2 > 0.0)) return glm::dvec3(0.0);
    const double cosine = std::max(0.0, glm::dot(normal, d) / std::sqrt(dist2));
    return light.intensity * light.color * cosine / dist2;
}

Shader::Shader(const FrameMotion& motion, const EmbreeScene* shadows, FragmentShading fragments)
    : scene_(motion.scene()), motion_(motion), shadows_(shadows), fragments_(fragments),
      static_world_(scene_.objects.size()), images_(scene_.materials.size(), nullptr),
      emission_images_(scene_.materials.size(), nullptr), pyramids_(scene_.materials.size(), nullptr),
      emission_pyramids_(scene_.materials.size(), nullptr) {
    if (usesImageTextures(scene_)) {
        ImageTextures& textures = ImageTextures::shared();
        const auto prepared = [&](const ImageTexture& image) -> const ImageTextures::Image* {
            if (image.file.empty()) return nullptr;
            textures.prepare(image.file, FileLoc{});
            return textures.find(image.file);
        };
        const auto pyramid = [&](const ImageTextures::Image* image) -> const TexelPyramid* {
            if (!image || fragments_ != FragmentShading::Integral) return nullptr;
            const TexelPyramid& p = TexelPyramid::of(*image);
            return p.levels() > 0 ? &p : nullptr;
        };
        for (std::size_t m = 0; m < scene_.materials.size(); ++m) {
            images_[m] = prepared(scene_.materials[m].image);
            emission_images_[m] = prepared(scene_.materials[m].emission_image);
            pyramids_[m] = pyramid(images_[m]);
            emission_pyramids_[m] = pyramid(emission_images_[m]);
        }
    }
    for (std::size_t o = 0; o < scene_.objects.size(); ++o) {
        const Object& object = scene_.objects[o];
        if (!motion.shutter().objectStill(o)) continue;
        auto& world = static_world_[o];
        evalVertices(object, motion.t0(), world);  // evalVertex's arithmetic, the motion evaluated once
    }
}

SurfaceGeometry Shader::geometry(const SurfacePoint& sp) const {
    const Object& object = scene_.objects[static_cast<std::size_t>(sp.object)];
    const auto& tri = object.mesh.triangles[sp.triangle];
    glm::dvec3 v[3];
    const auto& cached = static_world_[static_cast<std::size_t>(sp.object)];
    if (!cached.empty()) {
        for (int k = 0; k < 3; ++k) v[k] = cached[tri[k]];
    } else if (object.deformation.empty() && !object.motion) {
        // Same arithmetic as evalVertex, with the transform evaluated once for the three vertices.
        const RigidTransform x = motion_.transform(static_cast<std::size_t>(sp.object), sp.time);
        for (int k = 0; k < 3; ++k) v[k] = x.apply(object.mesh.positions[tri[k]]);
    } else {
        evalTriangle(object, sp.triangle, sp.time, v);
    }
    const double w = 1.0 - sp.u - sp.v;
    SurfaceGeometry g;
    g.position = w * v[0] + sp.u * v[1] + sp.v * v[2];
    const glm::dvec3 n = glm::cross(v[1] - v[0], v[2] - v[0]);
    const double len = glm::length(n);
    g.normal = len > 0.0 ? n / len : glm::dvec3(0.0);
    g.object_position = objectPosition(sp);
    addCornerAttributes(sp, g);
    return g;
}

namespace {

// The smallest rotation taking unit vector a to unit vector b, applied to v (Rodrigues' formula with
// sin and cos from a x b and a . b); a and b are not opposite.
glm::dvec3 turnLike(const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& v) {
    const glm::dvec3 axis = glm::cross(a, b);
    const double c = glm::dot(a, b);
    return v * c + glm::cross(axis, v) + axis * (glm::dot(axis, v) / (1.0 + c));
}

}  // namespace

void Shader::addCornerAttributes(const SurfacePoint& sp, SurfaceGeometry& g) const {
    const Mesh& mesh = scene_.objects[static_cast<std::size_t>(sp.object)].mesh;
    const std::size_t corner = 3 * static_cast<std::size_t>(sp.triangle);
    const double w = 1.0 - sp.u - sp.v;
    if (mesh.hasUvs())
        g.uv = w * mesh.corner_uvs[corner] + sp.u * mesh.corner_uvs[corner + 1] + sp.v * mesh.corner_uvs[corner + 2];
    if (!mesh.smooth() || g.normal == glm::dvec3(0.0)) return;
    const Object& object = scene_.objects[static_cast<std::size_t>(sp.object)];
    const RigidTransform x = evalTransform(object.transform, sp.time);
    // An exact motion's matrix may shear: normals go by its inverse transpose.
    const glm::dmat3 exact = object.motion ? normalMatrix(object, sp.time) : glm::dmat3(1.0);
    const auto toWorld = [&](const glm::dvec3& n) { return object.motion ? exact * n : x.rotate * (n / x.scale); };
    const glm::dvec3 n = toWorld(w * mesh.corner_normals[corner] + sp.u * mesh.corner_normals[corner + 1] +
                                 sp.v * mesh.corner_normals[corner + 2]);
    const auto& tri = mesh.triangles[sp.triangle];
    const auto& rest = mesh.positions;
    const glm::dvec3 face = toWorld(glm::cross(rest[tri[1]] - rest[tri[0]], rest[tri[2]] - rest[tri[0]]));
    const double face_length = glm::length(face), n_length = glm::length(n);
    if (!(face_length > 0.0) || !(n_length > 0.0)) return;
    // The caller's face normal may be the mesh's front or its reverse (Embree's convention); the shading
    // normal goes to the same side, so the back-face test flips both together.
    const glm::dvec3 front = glm::dot(face, g.normal) < 0.0 ? -g.normal : g.normal;
    const double side = glm::dot(face, g.normal) < 0.0 ? -1.0 : 1.0;
    glm::dvec3 s = n / n_length;
    if (deforms(object) && glm::dot(face / face_length, front) > -0.999999)
        s = turnLike(face / face_length, front, s);
    g.shading_normal = side * glm::normalize(s);
}

glm::dvec3 Shader::objectPosition(const SurfacePoint& sp) const {
    const Object& object = scene_.objects[static_cast<std::size_t>(sp.object)];
    const auto& tri = object.mesh.triangles[sp.triangle];
    const auto& rest = object.mesh.positions;
    return (1.0 - sp.u - sp.v) * rest[tri[0]] + sp.u * rest[tri[1]] + sp.v * rest[tri[2]];
}

glm::dvec3 Shader::shade(const SurfacePoint& point, const glm::dvec3& eye, long long* shadow_rays) const {
    return shade(point, geometry(point), eye, shadow_rays);
}

glm::dvec3 Shader::shade(const SurfacePoint& point, const SurfaceGeometry& surface, const glm::dvec3& eye,
                         long long* shadow_rays) const {
    const Object& object = scene_.objects[static_cast<std::size_t>(point.object)];
    const std::size_t m = static_cast<std::size_t>(object.material);
    const Material& material = scene_.materials[m];
    FacingNormals facing{surface.normal, surface.shading_normal == glm::dvec3(0.0) ? surface.normal : surface.shading_normal};
    if (glm::dot(facing.face, eye - surface.position) < 0.0) {
        if (!material.two_sided) return glm::dvec3(0.0);
        facing.face = -facing.face;
        facing.lit = -facing.lit;
    }
    const ImageTextures::Image* image = images_[m];
    glm::dvec3 colour = albedo(material, surface.object_position);
    if (image) colour = colour * imageValue(*image, pyramids_[m], surface);
    if (material.model == ShadingModel::Unlit) return colour;
    colour = colour * lightArriving(point, surface, facing, shadow_rays);
    const ImageTextures::Image* emission_image = emission_images_[m];
    if (emission_image)
        return colour + material.emission * imageValue(*emission_image, emission_pyramids_[m], surface);
    return colour + material.emission;
}

glm::dvec3 Shader::imageValue(const ImageTextures::Image& image, const TexelPyramid* pyramid,
                              const SurfaceGeometry& surface) const {
    if (pyramid && surface.texture_piece)
        return textureMean(*pyramid, surface.texture_piece->st, surface.texture_piece->weight);
    return ImageTextures::shared().lookup(image, surface.uv, surface.footprint);
}

glm::dvec3 Shader::lightArriving(const SurfacePoint& point, const SurfaceGeometry& surface, const FacingNormals& facing,
                                 long long* shadow_rays) const {
    glm::dvec3 light_sum = scene_.ambient;
    for (const Light& light : scene_.lights) {
        glm::dvec3 to_light;
        const glm::dvec3 e = lightIrradiance(light, surface.position, facing.lit, &to_light);
        if (e == glm::dvec3(0.0)) continue;
        if (shadows_) {
            // Shadow rays start slightly off the surface: Embree intersects in float, so the hit point is
            // only known to ~1e-7 relative; 1e-4 relative clears self-intersection without visibly shifting
            // shadows.
            const double offset = 1e-4 * std::max({1.0, std::fabs(surface.position.x), std::fabs(surface.position.y),
                                                   std::fabs(surface.position.z)});
            const glm::dvec3 origin = surface.position + offset * facing.face;
            const bool point_light = light.kind == Light::Kind::Point;
            const glm::dvec3 dir = point_light ? light.position - origin : to_light;
            const double max_distance = point_light ? 1.0 - 1e-6 : std::numeric_limits<double>::infinity();
            if (shadow_rays) ++*shadow_rays;
            if (shadows_->occluded(origin, dir, max_distance, point.time)) continue;
        }
        light_sum += e;
    }
    return light_sum;
}

}  // namespace clipblur
