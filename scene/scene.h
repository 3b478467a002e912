#pragma once

#include <array>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include <glm/glm.hpp>
#include <glm/gtc/quaternion.hpp>

#include "scene/error.h"
#include "scene/pixel_bounds.h"

namespace clipblur {

// Times are absolute, in frames: frame k's shutter spans [k + open, k + close].

// One camera key as the paper's Table 1 gives it: position, view direction, up direction.
struct CameraKey {
    double time = 0.0;
    glm::dvec3 position{0.0};
    glm::dvec3 view{0.0, 0.0, 1.0};
    glm::dvec3 up{0.0, 1.0, 0.0};
};

class ExactCamera;  // scene/exact_camera.h

struct Camera {
    double vfov_degrees = 40.0;
    std::vector<CameraKey> keys;  // sorted by time; one key is a still camera
    // A glTF camera that keys cannot follow exactly; set, it is the camera's motion at every time and
    // `keys` hold its poses at its key times (for checks and reports, never interpolated).
    std::shared_ptr<const ExactCamera> motion;
};

struct Film {
    int width = 640;
    int height = 360;
    glm::dvec3 background{0.0};

    PixelBounds pixels() const { return PixelBounds::sized(0, 0, width, height); }
};

// Decomposed object-to-world transform key; rotation is interpolated by slerp, not by lerping matrices.
struct TransformKey {
    double time = 0.0;
    glm::dvec3 translate{0.0};
    glm::dquat rotate{1.0, 0.0, 0.0, 0.0};
    glm::dvec3 scale{1.0};
};

// Shading attributes are per triangle corner (corner k of triangle t at 3t + k), as OBJ and glTF index them
// apart from positions; empty means absent: faceted shading, no UVs. Normals are object space, need not be
// unit, and belong to the rest positions.
struct Mesh {
    std::vector<glm::dvec3> positions;
    std::vector<std::array<std::uint32_t, 3>> triangles;
    std::vector<glm::dvec3> corner_normals;  // empty or 3 per triangle
    std::vector<glm::dvec2> corner_uvs;      // empty or 3 per triangle

    bool smooth() const { return !corner_normals.empty(); }
    bool hasUvs() const { return !corner_uvs.empty(); }
};

// Deformation blur: the same topology at another time (object space).
struct DeformationKey {
    double time = 0.0;
    std::vector<glm::dvec3> positions;
};

struct Texture {
    enum class Kind { None, Checker, Stripe };
    Kind kind = Kind::None;
    glm::dvec3 color2{0.1};
    double scale = 1.0;  // period length in object-space units
};

// An image read through the mesh's UVs (u right, v up, repeating), multiplying the base colour.
// Integer texels are sRGB-encoded (PNG, JPEG), float texels linear.
struct ImageTexture {
    std::string file;  // resolved path; empty: none
    FileLoc loc;       // where the scene names it
};

// Lit: Lambert under the scene's ambient and lights, plus emission. Unlit: the base colour (times its
// textures) whatever the lights, ambient and shadows, as glTF's KHR_materials_unlit says.
enum class ShadingModel { Lit, Unlit };

struct Material {
    glm::dvec3 base_color{0.8};
    Texture texture;
    ImageTexture image;
    bool two_sided = true;
    ShadingModel model = ShadingModel::Lit;
    // Linear radiance added to the lit colour (times `emission_image` when it has one); unused when unlit.
    glm::dvec3 emission{0.0};
    ImageTexture emission_image;
};

struct Light {
    enum class Kind { Directional, Point };
    Kind kind = Kind::Directional;
    glm::dvec3 color{1.0};
    double intensity = 1.0;
    glm::dvec3 direction{0.0, 0.0, 1.0};  // directional: the direction light travels
    glm::dvec3 position{0.0};             // point
};

class ExactMotion;  // scene/exact_motion.h

struct Object {
    std::string name;
    Mesh mesh;                                 // rest positions, also the key at every time without deformation
    std::vector<DeformationKey> deformation;   // sorted by time; empty means rigid
    std::vector<TransformKey> transform;       // sorted by time; empty means identity
    // glTF motion that keys cannot hold exactly, evaluated at every time asked; set, it is the object's
    // whole motion (no transform or deformation keys) and the mesh holds its rest pose.
    std::shared_ptr<const ExactMotion> motion;
    int material = 0;
    FileLoc loc;
};

struct Scene {
    Camera camera;
    Film film;
    std::vector<Object> objects;
    std::vector<Material> materials;
    std::vector<Light> lights;
    glm::dvec3 ambient{0.1};
};

}  // namespace clipblur
