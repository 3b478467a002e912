#pragma once

#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

#include "renderer/frame_motion.h"
#include "renderer/shading/image_textures.h"
#include "renderer/shading/texture_integral.h"
#include "scene/job.h"
#include "scene/scene.h"

namespace clipblur {

class EmbreeScene;

// A point on a triangle at one time: the shading input shared by the stochastic renderer (Embree hits)
// and the clipped renderer (fragment vertices). Barycentrics follow Embree: p = (1-u-v) v0 + u v1 + v v2.
struct SurfacePoint {
    int object = 0;
    std::uint32_t triangle = 0;
    double u = 0.0;
    double v = 0.0;
    double time = 0.0;  // absolute, in frames
};

struct SurfaceGeometry {
    glm::dvec3 position{0.0};         // world, at the point's time
    glm::dvec3 normal{0.0};           // unit, (v1-v0) x (v2-v0) at that time; zero for degenerate triangles
    glm::dvec3 object_position{0.0};  // on the rest mesh (Mesh::positions): textures stick to the surface
    // Smooth meshes: the interpolated corner normal at that time, unit, on the side `normal` is; zero
    // for faceted meshes, which light with `normal`.
    glm::dvec3 shading_normal{0.0};
    glm::dvec2 uv{0.0};               // meshes with UVs: image-texture (s, t)
    TextureFootprint footprint;       // the (s, t) extent the colour stands for; zero: a point
    // The `integral` rule: the (s, t) polygon the colour stands for; image textures are averaged over it
    // exactly (renderer/shading/texture_integral.h) instead of looked up at uv over the footprint.
    const TexturePiece* texture_piece = nullptr;
};


// Lambert shading: albedo * (ambient + sum over lights of intensity * color * max(0, n.l)), point lights
// divided by the squared distance, plus the material's emission (times its emission image). Albedo is the
// material's base colour or its checker/stripe texture evaluated at the rest-mesh position, so the pattern
// moves (and deforms) with the object, times its image texture. Unlit materials are their albedo alone:
// no ambient, lights, shadow rays or emission.
//
// Faces: the front side is the one (v1-v0) x (v2-v0) points to. Two-sided materials flip the normal
// toward the eye. One-sided materials shade back faces black rather than culling them: a back face
// still occludes what is behind it, so culling would show objects through a closed mesh's far side
// whenever its front is clipped or missing, and black makes wrong winding obvious.
class Shader {
public:
    // Precomputes world positions of objects that do not move during the frame's shutter. With `shadows`
    // set, each light is tested for occlusion with a shadow ray at the point's time.
    explicit Shader(const FrameMotion& motion, const EmbreeScene* shadows = nullptr,
                    FragmentShading fragments = FragmentShading::Centroid);

    SurfaceGeometry geometry(const SurfacePoint& point) const;
    // The point on the rest mesh (what textures read): no motion to evaluate.
    glm::dvec3 objectPosition(const SurfacePoint& point) const;
    // Fills `surface`'s shading normal and UV from the mesh's corner attributes, given its position and
    // face normal at the point's time. Rigid motion carries the normal by the inverse transpose (rotation
    // over scale); deformation then turns it by the smallest rotation that takes the triangle's rest face
    // normal to its face normal at that time, so it follows the triangle it is on.
    void addCornerAttributes(const SurfacePoint& point, SurfaceGeometry& surface) const;
    FragmentShading fragmentShading() const { return fragments_; }
    // `eye` is the camera position at point.time; `shadow_rays` (optional) is incremented per ray cast.
    glm::dvec3 shade(const SurfacePoint& point, const glm::dvec3& eye, long long* shadow_rays = nullptr) const;
    glm::dvec3 shade(const SurfacePoint& point, const SurfaceGeometry& surface, const glm::dvec3& eye,
                     long long* shadow_rays = nullptr) const;

    const Scene& scene() const { return scene_; }

private:
    // The face normal (toward the eye) that shadow rays leave along and the normal that lights the point.
    struct FacingNormals {
        glm::dvec3 face;
        glm::dvec3 lit;
    };
    // Ambient plus every light that reaches the point (shadow rays when the shader has a scene for them).
    glm::dvec3 lightArriving(const SurfacePoint& point, const SurfaceGeometry& surface, const FacingNormals& facing,
                             long long* shadow_rays) const;
    // An image texture's value for `surface`: its exact mean over surface.texture_piece when there is one
    // and the image's pyramid (null outside the `integral` rule), else the texture system's lookup.
    glm::dvec3 imageValue(const ImageTextures::Image& image, const TexelPyramid* pyramid,
                          const SurfaceGeometry& surface) const;

    const Scene& scene_;
    const FrameMotion& motion_;
    const EmbreeScene* shadows_;
    FragmentShading fragments_;
    std::vector<std::vector<glm::dvec3>> static_world_;  // per object; empty when the object moves
    std::vector<const ImageTextures::Image*> images_;    // per material; null without an image texture
    std::vector<const ImageTextures::Image*> emission_images_;  // per material; null without one
    // Per material, the `integral` rule only: the images' pyramids (null otherwise).
    std::vector<const TexelPyramid*> pyramids_;
    std::vector<const TexelPyramid*> emission_pyramids_;
};

// Base colour or texture at an object-space point (no lighting); image textures are not included.
glm::dvec3 albedo(const Material& material, const glm::dvec3& object_position);

// True when some material of the scene reads an image (base colour or emission).
bool usesImageTextures(const Scene& scene);

// Light arriving at `position` with unit normal `normal` from one light (no shadowing): intensity *
// color * max(0, n.l), over distance^2 for point lights. `to_light` receives the unnormalised
// direction to the light (point) or the unit direction against its travel (directional).
glm::dvec3 lightIrradiance(const Light& light, const glm::dvec3& position, const glm::dvec3& normal,
                           glm::dvec3* to_light = nullptr);

}  // namespace clipblur
