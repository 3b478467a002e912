#include "scene/gltf_loader.h"

#include <algorithm>
#include <array>
#include <cstring>
#include <limits>
#include <cmath>
#include <deque>
#include <fstream>
#include <iterator>
#include <map>
#include <memory>
#include <set>
#include <sstream>
#include <stdexcept>

#include "scene/exact_camera.h"
#include "scene/exact_motion.h"
#include "scene/gltf_animation.h"
#include "scene/scene_validation.h"
#include "scene/tiny_gltf_config.h"

namespace clipblur {

namespace {

std::string pointer(const char* array, std::size_t index) { return std::string("/") + array + "/" + std::to_string(index); }

bool isGlb(const std::string& bytes) { return bytes.size() >= 4 && bytes.compare(0, 4, "glTF") == 0; }

// Textures are a later item: images are neither decoded nor read, only their URIs kept.
bool skipImage(tinygltf::Image*, const int, std::string*, std::string*, int, int, const unsigned char*, int, void*) {
    return true;
}

// Elements per accessor: an all-zero accessor (no bufferView) costs no bytes of the file.
constexpr std::size_t kMaxAccessorCount = std::size_t{1} << 25;
// Deformation keys times vertices of one morphed object (24 bytes each); more goes to an exact motion.
constexpr std::size_t kMaxMorphPositions = std::size_t{1} << 25;
// Nodes from a root to a leaf: the walk recurses, and every object composes its whole chain.
constexpr std::size_t kMaxHierarchyDepth = 1024;

// Reads the model's accessors, checked against the spec and their buffers, and fails with the pointer
// of what is wrong.
class GltfReader {
public:
    GltfReader(const tinygltf::Model& model, const std::string& name, const GltfRequest& request)
        : model_(model), name_(name), request_(request) {}

    const std::string& name() const { return name_; }

    [[noreturn]] void fail(const std::string& where, const std::string& message) const {
        const std::string ref = request_.ref.toString();
        throw Error(ExitCode::Scene, where + ": " + message + (ref.empty() ? "" : " (glTF file of " + ref + ")"),
                    FileLoc{name_, 0, 0});
    }

    // Every element of a float accessor of `components` numbers per element, checked finite.
    std::vector<double> floats(int index, int type, const std::string& what) const {
        const tinygltf::Accessor& a = accessor(index, what);
        const std::string where = pointer("accessors", static_cast<std::size_t>(index));
        if (a.componentType != TINYGLTF_COMPONENT_TYPE_FLOAT || a.type != type)
            fail(where, what + " must be float " + typeName(type));
        std::vector<double> out;
        const std::size_t n = components(type);
        forEachElement(a, where, [&](const unsigned char* p) {
            for (std::size_t c = 0; c < n; ++c) {
                float v;
                std::memcpy(&v, p + 4 * c, 4);
                if (!std::isfinite(v)) fail(where, what + " holds a non-finite number");
                out.push_back(v);
            }
        });
        return out;
    }

    // Every component of an unsigned byte, short or int accessor of `type`.
    std::vector<std::uint32_t> unsignedInts(int index, int type, const std::string& what) const {
        const tinygltf::Accessor& a = accessor(index, what);
        const std::string where = pointer("accessors", static_cast<std::size_t>(index));
        const int ct = a.componentType;
        if (a.type != type || a.normalized ||
            (ct != TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE && ct != TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT &&
             ct != TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT))
            fail(where, what + " must be unsigned byte, short or int " + typeName(type));
        const std::size_t size = componentBytes(ct);
        std::vector<std::uint32_t> out;
        forEachElement(a, where, [&](const unsigned char* p) {
            for (std::size_t c = 0; c < components(type); ++c) {
                std::uint32_t v = 0;
                std::memcpy(&v, p + c * size, size);  // little-endian, as glTF stores it
                out.push_back(v);
            }
        });
        return out;
    }

    std::vector<std::uint32_t> indices(int index, std::size_t vertex_count) const {
        std::vector<std::uint32_t> out = unsignedInts(index, TINYGLTF_TYPE_SCALAR, "indices");
        for (const std::uint32_t v : out)
            if (v >= vertex_count)
                fail(pointer("accessors", static_cast<std::size_t>(index)),
                     "index " + std::to_string(v) + " is out of range: the primitive has " +
                         std::to_string(vertex_count) + " vertices");
        return out;
    }

    std::size_t count(int index, const std::string& what) const { return accessor(index, what).count; }

private:
    static std::size_t components(int type) {
        switch (type) {
            case TINYGLTF_TYPE_SCALAR: return 1;
            case TINYGLTF_TYPE_VEC2: return 2;
            case TINYGLTF_TYPE_VEC3: return 3;
            case TINYGLTF_TYPE_VEC4: return 4;
            case TINYGLTF_TYPE_MAT4: return 16;
            default: return 0;
        }
    }

    static std::string typeName(int type) {
        switch (type) {
            case TINYGLTF_TYPE_SCALAR: return "SCALAR";
            case TINYGLTF_TYPE_VEC3: return "VEC3";
            case TINYGLTF_TYPE_VEC4: return "VEC4";
            case TINYGLTF_TYPE_MAT4: return "MAT4";
            default: return "?";
        }
    }

    static std::size_t componentBytes(int component_type) {
        switch (component_type) {
            case TINYGLTF_COMPONENT_TYPE_BYTE:
            case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: return 1;
            case TINYGLTF_COMPONENT_TYPE_SHORT:
            case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: return 2;
            case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT:
            case TINYGLTF_COMPONENT_TYPE_FLOAT: return 4;
            default: return 0;
        }
    }

    const tinygltf::Accessor& accessor(int index, const std::string& what) const {
        if (index < 0 || static_cast<std::size_t>(index) >= model_.accessors.size())
            fail("/accessors", what + " names accessor " + std::to_string(index) + ", which does not exist");
        return model_.accessors[static_cast<std::size_t>(index)];
    }

    // Calls visit with the first byte of every element, after checking that all of them lie in the buffer.
    template <typename Visit>
    void forEachElement(const tinygltf::Accessor& a, const std::string& where, Visit&& visit) const {
        if (a.sparse.isSparse) fail(where, "sparse accessors are not supported");
        if (a.count == 0) fail(where, "count must be at least 1");
        if (a.count > kMaxAccessorCount)
            fail(where, "count " + std::to_string(a.count) + " is beyond the limit of " + std::to_string(kMaxAccessorCount));
        const std::size_t element = componentBytes(a.componentType) * components(a.type);
        if (element == 0) fail(where, "unsupported componentType or type");
        if (a.bufferView < 0) {  // the spec's all-zero accessor
            const std::vector<unsigned char> zeros(element, 0);
            for (std::size_t i = 0; i < a.count; ++i) visit(zeros.data());
            return;
        }
        if (static_cast<std::size_t>(a.bufferView) >= model_.bufferViews.size())
            fail(where, "bufferView " + std::to_string(a.bufferView) + " does not exist");
        const tinygltf::BufferView& view = model_.bufferViews[static_cast<std::size_t>(a.bufferView)];
        const std::string view_where = pointer("bufferViews", static_cast<std::size_t>(a.bufferView));
        if (view.buffer < 0 || static_cast<std::size_t>(view.buffer) >= model_.buffers.size())
            fail(view_where, "buffer " + std::to_string(view.buffer) + " does not exist");
        const std::vector<unsigned char>& data = model_.buffers[static_cast<std::size_t>(view.buffer)].data;
        if (view.byteOffset > data.size() || view.byteLength > data.size() - view.byteOffset)
            fail(view_where, "byteOffset + byteLength lies beyond the buffer's " + std::to_string(data.size()) +
                                 " bytes");
        const std::size_t stride = view.byteStride == 0 ? element : view.byteStride;
        if (stride < element) fail(view_where, "byteStride is smaller than an element of " + where);
        const std::size_t size = view.byteLength;
        if (a.byteOffset > size || a.count - 1 > (size - a.byteOffset) / stride ||
            (a.count - 1) * stride + element > size - a.byteOffset)
            fail(where, "count, byteOffset and stride reach beyond its bufferView");
        const unsigned char* base = data.data() + view.byteOffset + a.byteOffset;
        for (std::size_t i = 0; i < a.count; ++i) visit(base + i * stride);
    }

    const tinygltf::Model& model_;
    const std::string& name_;
    const GltfRequest& request_;
};

// A primitive's geometry before any node transform: positions, triangles, morph target offsets.
struct PrimitiveGeometry {
    std::vector<glm::dvec3> positions;
    std::vector<std::array<std::uint32_t, 3>> triangles;
    std::vector<std::vector<glm::dvec3>> targets;
    std::vector<glm::dvec3> normals;  // per vertex; empty without NORMAL
    std::vector<glm::dvec2> uvs;      // per vertex; empty without TEXCOORD_0
};

std::vector<glm::dvec3> toVec3(const std::vector<double>& v) {
    std::vector<glm::dvec3> out(v.size() / 3);
    for (std::size_t i = 0; i < out.size(); ++i) out[i] = {v[3 * i], v[3 * i + 1], v[3 * i + 2]};
    return out;
}

class SceneBuilder {
public:
    SceneBuilder(const tinygltf::Model& model, const std::string& name, const GltfRequest& request)
        : model_(model), reader_(model, name, request), request_(request),
          folder_(std::filesystem::path(name).parent_path()),
          names_(request.taken_names.begin(), request.taken_names.end()) {}

    GltfScene build() {
        // A required extension changes what the file means; only the three material extensions are read.
        for (std::size_t i = 0; i < model_.extensionsRequired.size(); ++i) {
            const std::string& e = model_.extensionsRequired[i];
            if (e != "KHR_materials_unlit" && e != "KHR_materials_emissive_strength" && e != "KHR_texture_transform")
                reader_.fail("/extensionsRequired/" + std::to_string(i), "extension " + e + " is not supported");
        }
        readMaterials();
        readNodes();
        readAnimations();
        const int scene = model_.defaultScene >= 0 ? model_.defaultScene : 0;
        if (model_.scenes.empty()) reader_.fail("/scenes", "the file has no scene");
        if (static_cast<std::size_t>(scene) >= model_.scenes.size())
            reader_.fail("/scene", "scene " + std::to_string(scene) + " does not exist");
        for (const int root : model_.scenes[static_cast<std::size_t>(scene)].nodes)
            visit(root, pointer("scenes", static_cast<std::size_t>(scene)) + "/nodes");
        pickCamera();
        if (!warnings_.empty()) out_.warnings.assign(warnings_.begin(), warnings_.end());
        return std::move(out_);
    }

private:
    void readMaterials() {
        for (std::size_t i = 0; i < model_.materials.size(); ++i) {
            const tinygltf::Material& m = model_.materials[i];
            const std::vector<double>& f = m.pbrMetallicRoughness.baseColorFactor;
            if (f.size() != 4 || !std::all_of(f.begin(), f.end(), [](double v) { return v >= 0.0 && v <= 1.0; }))
                reader_.fail(pointer("materials", i) + "/pbrMetallicRoughness/baseColorFactor",
                             "must be 4 numbers in [0, 1]");
            Material mat;
            mat.base_color = {f[0], f[1], f[2]};
            mat.two_sided = m.doubleSided;
            if (m.pbrMetallicRoughness.baseColorTexture.index >= 0)
                mat.image = textureImage(m.pbrMetallicRoughness.baseColorTexture,
                                         pointer("materials", i) + "/pbrMetallicRoughness/baseColorTexture");
            if (m.extensions.count("KHR_materials_unlit")) mat.model = ShadingModel::Unlit;
            readEmission(m, pointer("materials", i), mat);
            uv_transforms_.push_back(materialUvTransform(m, mat, pointer("materials", i)));
            out_.materials.push_back(mat);
        }
        // The spec's default material: white, single-sided.
        default_material_ = out_.materials.size();
        Material fallback;
        fallback.base_color = glm::dvec3(1.0);
        fallback.two_sided = false;
        uv_transforms_.emplace_back(1.0);
        out_.materials.push_back(fallback);
    }

    // emissiveFactor times KHR_materials_emissive_strength's emissiveStrength, times emissiveTexture. An
    // unlit material ignores them, as KHR_materials_unlit ignores every property of the lit model.
    void readEmission(const tinygltf::Material& m, const std::string& material, Material& mat) {
        const std::vector<double>& f = m.emissiveFactor;
        if (f.size() != 3 || !std::all_of(f.begin(), f.end(), [](double v) { return v >= 0.0 && v <= 1.0; }))
            reader_.fail(material + "/emissiveFactor", "must be 3 numbers in [0, 1]");
        double strength = 1.0;
        const auto extension = m.extensions.find("KHR_materials_emissive_strength");
        if (extension != m.extensions.end() && extension->second.Has("emissiveStrength")) {
            const tinygltf::Value& v = extension->second.Get("emissiveStrength");
            strength = v.IsNumber() ? v.GetNumberAsDouble() : -1.0;
            if (!(strength >= 0.0 && strength <= kMaxCoordinate))
                reader_.fail(material + "/extensions/KHR_materials_emissive_strength/emissiveStrength",
                             "must be a number in [0, 1e8]");
        }
        const glm::dvec3 emission = glm::dvec3(f[0], f[1], f[2]) * strength;
        if (mat.model == ShadingModel::Unlit) {
            if (emission != glm::dvec3(0.0))
                warnings_.insert("glTF emission of unlit materials is ignored (" + material + " and any others)");
            return;
        }
        mat.emission = emission;
        if (m.emissiveTexture.index >= 0 && emission != glm::dvec3(0.0))
            mat.emission_image = textureImage(m.emissiveTexture, material + "/emissiveTexture");
    }

    // The image file a base colour or emissive texture names (at `where`); it multiplies its factor, read
    // through TEXCOORD_0.
    ImageTexture textureImage(const tinygltf::TextureInfo& info, const std::string& where) {
        if (info.texCoord != 0) reader_.fail(where, "texCoord " + std::to_string(info.texCoord) + " is not supported (TEXCOORD_0 only)");
        if (static_cast<std::size_t>(info.index) >= model_.textures.size())
            reader_.fail(where, "texture " + std::to_string(info.index) + " does not exist");
        const tinygltf::Texture& texture = model_.textures[static_cast<std::size_t>(info.index)];
        const std::string texture_where = pointer("textures", static_cast<std::size_t>(info.index));
        if (texture.source < 0 || static_cast<std::size_t>(texture.source) >= model_.images.size())
            reader_.fail(texture_where, "source " + std::to_string(texture.source) + " does not exist");
        const tinygltf::Image& image = model_.images[static_cast<std::size_t>(texture.source)];
        const std::string image_where = pointer("images", static_cast<std::size_t>(texture.source));
        if (image.uri.empty() || image.uri.rfind("data:", 0) == 0)
            reader_.fail(image_where, "only images in files are supported (no bufferView or data URI)");
        const std::filesystem::path file = folder_ / image.uri;
        std::error_code ec;
        if (!std::filesystem::is_regular_file(file, ec))
            reader_.fail(image_where, "texture file '" + file.string() + "' does not exist");
        ImageTexture out;
        out.file = file.string();
        out.loc = FileLoc{reader_.name(), 0, 0};
        return out;
    }

    // KHR_texture_transform of one texture as the extension defines it: uv' = T(offset) R(rotation)
    // S(scale) uv, with R = [cos sin; -sin cos] acting on (u, v); the identity without the extension.
    glm::dmat3 uvTransform(const tinygltf::TextureInfo& info, const std::string& where) const {
        const auto found = info.extensions.find("KHR_texture_transform");
        if (found == info.extensions.end()) return glm::dmat3(1.0);
        const tinygltf::Value& x = found->second;
        const std::string at = where + "/extensions/KHR_texture_transform";
        const auto pair = [&](const char* key, double fallback) {
            if (!x.Has(key)) return glm::dvec2(fallback);
            const tinygltf::Value& v = x.Get(key);
            if (!v.IsArray() || v.ArrayLen() != 2 || !v.Get(0).IsNumber() || !v.Get(1).IsNumber() ||
                !std::isfinite(v.Get(0).GetNumberAsDouble()) || !std::isfinite(v.Get(1).GetNumberAsDouble()))
                reader_.fail(at + "/" + key, "must be 2 finite numbers");
            return glm::dvec2(v.Get(0).GetNumberAsDouble(), v.Get(1).GetNumberAsDouble());
        };
        const glm::dvec2 offset = pair("offset", 0.0), scale = pair("scale", 1.0);
        double rotation = 0.0;
        if (x.Has("rotation")) {
            const tinygltf::Value& r = x.Get("rotation");
            rotation = r.IsNumber() ? r.GetNumberAsDouble() : std::numeric_limits<double>::quiet_NaN();
            if (!std::isfinite(rotation)) reader_.fail(at + "/rotation", "must be a finite number");
        }
        if (x.Has("texCoord") && !(x.Get("texCoord").IsNumber() && x.Get("texCoord").GetNumberAsDouble() == 0.0))
            reader_.fail(at + "/texCoord", "is not supported unless 0 (TEXCOORD_0 only)");
        const double c = std::cos(rotation), s = std::sin(rotation);
        // Columns (glm): u' = c sx u + s sy v + ox, v' = -s sx u + c sy v + oy.
        return glm::dmat3(glm::dvec3(c * scale.x, -s * scale.x, 0.0), glm::dvec3(s * scale.y, c * scale.y, 0.0),
                          glm::dvec3(offset, 1.0));
    }

    // The one UV transform of a material's used textures: both read the same corner UVs, so a base colour
    // and an emissive texture with different transforms are refused.
    glm::dmat3 materialUvTransform(const tinygltf::Material& m, const Material& mat, const std::string& where) const {
        const std::string base_where = where + "/pbrMetallicRoughness/baseColorTexture";
        const glm::dmat3 base = mat.image.file.empty() ? glm::dmat3(1.0)
                                                       : uvTransform(m.pbrMetallicRoughness.baseColorTexture, base_where);
        if (mat.emission_image.file.empty()) return base;
        const glm::dmat3 emissive = uvTransform(m.emissiveTexture, where + "/emissiveTexture");
        if (!mat.image.file.empty() && emissive != base)
            reader_.fail(where + "/emissiveTexture/extensions/KHR_texture_transform",
                         "differs from the baseColorTexture's (one UV transform per material is supported)");
        return emissive;
    }

    void readNodes() {
        nodes_.resize(model_.nodes.size());
        for (std::size_t i = 0; i < model_.nodes.size(); ++i) {
            const tinygltf::Node& n = model_.nodes[i];
            AnimatedNode& a = nodes_[i];
            const std::string where = pointer("nodes", i);
            const auto finite = [&](const std::vector<double>& v, const char* what) {
                if (!std::all_of(v.begin(), v.end(), [](double x) { return std::isfinite(x); }))
                    reader_.fail(where + "/" + what, "holds a non-finite number");
            };
            finite(n.translation, "translation");
            finite(n.rotation, "rotation");
            finite(n.scale, "scale");
            finite(n.matrix, "matrix");
            if (n.matrix.size() == 16) {
                a.has_matrix = true;
                for (int c = 0; c < 4; ++c)
                    for (int r = 0; r < 4; ++r) a.matrix[c][r] = n.matrix[static_cast<std::size_t>(4 * c + r)];
            }
            if (n.translation.size() == 3) a.rest.translate = {n.translation[0], n.translation[1], n.translation[2]};
            if (n.rotation.size() == 4) {
                a.rest.rotate = glm::dquat(n.rotation[3], n.rotation[0], n.rotation[1], n.rotation[2]);
                if (std::abs(glm::length(a.rest.rotate) - 1.0) > 1e-3) reader_.fail(where + "/rotation", "is not a unit quaternion");
                // Unit to double precision: a float-rounded quaternion's matrix would shear by 1e-7.
                a.rest.rotate = glm::normalize(a.rest.rotate);
            }
            if (n.scale.size() == 3) a.rest.scale = {n.scale[0], n.scale[1], n.scale[2]};
        }
        for (std::size_t i = 0; i < model_.nodes.size(); ++i)
            for (const int child : model_.nodes[i].children) {
                if (child < 0 || static_cast<std::size_t>(child) >= nodes_.size())
                    reader_.fail(pointer("nodes", i) + "/children", "node " + std::to_string(child) + " does not exist");
                if (!parents_.emplace(static_cast<std::size_t>(child), i).second)
                    reader_.fail(pointer("nodes", static_cast<std::size_t>(child)), "the node has two parents");
            }
    }

    // What a channel's output holds: `width` numbers per key, as accessor `type`.
    struct TrackShape {
        std::size_t width = 3;
        int type = TINYGLTF_TYPE_VEC3;
        bool rotation = false;
    };

    Track readTrack(std::size_t anim, const tinygltf::AnimationSampler& s, const TrackShape& shape) {
        const std::string where = pointer("animations", anim);
        Track track;
        track.width = shape.width;
        track.rotation = shape.rotation;
        const std::size_t width = shape.width;
        if (s.interpolation == "STEP") track.interpolation = Interpolation::Step;
        else if (s.interpolation == "CUBICSPLINE") track.interpolation = Interpolation::CubicSpline;
        else if (s.interpolation != "LINEAR") reader_.fail(where, "unknown interpolation '" + s.interpolation + "'");
        track.times = reader_.floats(s.input, TINYGLTF_TYPE_SCALAR, "an animation input");
        for (std::size_t k = 1; k < track.times.size(); ++k)
            if (!(track.times[k] > track.times[k - 1]))
                reader_.fail(pointer("accessors", static_cast<std::size_t>(s.input)),
                             "animation key times must increase strictly (key " + std::to_string(k) + ")");
        for (double& t : track.times) t *= request_.fps;
        track.values = reader_.floats(s.output, shape.type, "an animation output");
        const std::size_t per_key = (track.interpolation == Interpolation::CubicSpline ? 3 : 1) * width;
        if (track.values.size() != per_key * track.times.size())
            reader_.fail(pointer("accessors", static_cast<std::size_t>(s.output)),
                         "an animation output needs " + std::to_string(per_key) + " numbers per key time, " +
                             std::to_string(track.times.size()) + " key times");
        if (track.interpolation == Interpolation::CubicSpline)  // tangents per second to per frame
            for (std::size_t k = 0; k < track.times.size(); ++k)
                for (std::size_t i = 0; i < width; ++i) {
                    track.values[k * per_key + i] /= request_.fps;
                    track.values[k * per_key + 2 * width + i] /= request_.fps;
                }
        return track;
    }

    // Every animation plays from glTF time 0; a node property animated twice is refused.
    void readAnimations() {
        for (std::size_t a = 0; a < model_.animations.size(); ++a) {
            const tinygltf::Animation& anim = model_.animations[a];
            for (std::size_t c = 0; c < anim.channels.size(); ++c) {
                const tinygltf::AnimationChannel& ch = anim.channels[c];
                const std::string where = pointer("animations", a) + "/channels/" + std::to_string(c);
                if (ch.target_node < 0 || static_cast<std::size_t>(ch.target_node) >= nodes_.size())
                    reader_.fail(where, "target node " + std::to_string(ch.target_node) + " does not exist");
                if (ch.sampler < 0 || static_cast<std::size_t>(ch.sampler) >= anim.samplers.size())
                    reader_.fail(where, "sampler " + std::to_string(ch.sampler) + " does not exist");
                const auto node = static_cast<std::size_t>(ch.target_node);
                const tinygltf::AnimationSampler& s = anim.samplers[static_cast<std::size_t>(ch.sampler)];
                if (!targeted_.insert({node, ch.target_path}).second)
                    reader_.fail(where, "node " + std::to_string(node) + " " + ch.target_path + " is animated twice");
                if (nodes_[node].has_matrix)
                    reader_.fail(where, "targets node " + std::to_string(node) + ", which is given by a matrix");
                if (ch.target_path == "translation" || ch.target_path == "scale") {
                    const Track* track = &tracks_.emplace_back(readTrack(a, s, TrackShape{}));
                    (ch.target_path == "scale" ? nodes_[node].scale : nodes_[node].translation) = track;
                } else if (ch.target_path == "rotation") {
                    const TrackShape shape{4, TINYGLTF_TYPE_VEC4, true};
                    nodes_[node].rotation = &tracks_.emplace_back(readTrack(a, s, shape));
                } else if (ch.target_path == "weights") {
                    const TrackShape shape{targetCount(node, where), TINYGLTF_TYPE_SCALAR, false};
                    weight_tracks_[node] = &tracks_.emplace_back(readTrack(a, s, shape));
                } else {
                    reader_.fail(where, "unknown target path '" + ch.target_path + "'");
                }
            }
        }
    }

    std::size_t targetCount(std::size_t node, const std::string& where) const {
        const int mesh = model_.nodes[node].mesh;
        if (mesh < 0 || static_cast<std::size_t>(mesh) >= model_.meshes.size() ||
            model_.meshes[static_cast<std::size_t>(mesh)].primitives.empty() ||
            model_.meshes[static_cast<std::size_t>(mesh)].primitives[0].targets.empty())
            reader_.fail(where, "animates weights of a node without a morphed mesh");
        return model_.meshes[static_cast<std::size_t>(mesh)].primitives[0].targets.size();
    }

    // Depth first, children in order, with an explicit stack: a hierarchy kMaxHierarchyDepth deep must
    // not depend on how large the compiler makes a recursive frame (sanitizers make it much larger).
    void visit(int root, const std::string& root_where) {
        struct Pending {
            int index;
            std::vector<std::size_t> chain;  // the ancestors
            std::string where;
        };
        std::vector<Pending> pending{{root, {}, root_where}};
        while (!pending.empty()) {
            Pending p = std::move(pending.back());
            pending.pop_back();
            if (p.index < 0 || static_cast<std::size_t>(p.index) >= nodes_.size())
                reader_.fail(p.where, "node " + std::to_string(p.index) + " does not exist");
            const auto node = static_cast<std::size_t>(p.index);
            if (p.chain.size() >= kMaxHierarchyDepth)
                reader_.fail(pointer("nodes", node),
                             "the hierarchy is deeper than " + std::to_string(kMaxHierarchyDepth) + " levels");
            if (!visited_.insert(node).second)
                reader_.fail(pointer("nodes", node), "the node has two parents or lies on a cycle");
            p.chain.push_back(node);
            const tinygltf::Node& n = model_.nodes[node];
            if (n.mesh >= 0) addMeshInstance(p.chain);
            if (n.camera >= 0) cameras_.push_back(p.chain);
            for (auto child = n.children.rbegin(); child != n.children.rend(); ++child)
                pending.push_back({*child, p.chain, pointer("nodes", node) + "/children"});
        }
    }

    // Nodes of the chain from the deepest animated one down are split: the motion above, a static tail.
    struct SplitChain {
        ChainMotion motion;
        glm::dmat4 tail{1.0};
        bool animated = false;
    };

    SplitChain split(const std::vector<std::size_t>& chain) const {
        SplitChain s;
        std::size_t deepest = chain.size();
        for (std::size_t i = 0; i < chain.size(); ++i)
            if (nodes_[chain[i]].animated()) deepest = i;
        s.animated = deepest < chain.size();
        const std::size_t tail_from = s.animated ? deepest + 1 : 0;
        for (std::size_t i = 0; i < tail_from; ++i) s.motion.chain.push_back(&nodes_[chain[i]]);
        for (std::size_t i = tail_from; i < chain.size(); ++i) s.tail = s.tail * nodes_[chain[i]].local(0.0);
        return s;
    }

    std::string uniqueName(std::string name) {
        if (name.empty()) name = "node";
        std::string candidate = name;
        for (int k = 2; !names_.insert(candidate).second; ++k) candidate = name + "#" + std::to_string(k);
        return candidate;
    }

    PrimitiveGeometry readPrimitive(const tinygltf::Primitive& p, const std::string& where) {
        PrimitiveGeometry g;
        const auto pos = p.attributes.find("POSITION");
        if (pos == p.attributes.end()) reader_.fail(where + "/attributes", "POSITION is missing");
        g.positions = toVec3(reader_.floats(pos->second, TINYGLTF_TYPE_VEC3, "POSITION"));
        for (const glm::dvec3& v : g.positions)
            if (std::abs(v.x) > kMaxCoordinate || std::abs(v.y) > kMaxCoordinate || std::abs(v.z) > kMaxCoordinate)
                reader_.fail(pointer("accessors", static_cast<std::size_t>(pos->second)), "a position beyond 1e8");
        std::vector<std::uint32_t> idx;
        if (p.indices >= 0) {
            idx = reader_.indices(p.indices, g.positions.size());
        } else {
            idx.resize(g.positions.size());
            for (std::size_t i = 0; i < idx.size(); ++i) idx[i] = static_cast<std::uint32_t>(i);
        }
        const int mode = p.mode < 0 ? TINYGLTF_MODE_TRIANGLES : p.mode;
        if (mode == TINYGLTF_MODE_TRIANGLES) {
            if (idx.size() % 3 != 0) reader_.fail(where, "TRIANGLES needs a multiple of 3 indices");
            for (std::size_t i = 0; i + 2 < idx.size(); i += 3) g.triangles.push_back({idx[i], idx[i + 1], idx[i + 2]});
        } else if (mode == TINYGLTF_MODE_TRIANGLE_STRIP) {
            for (std::size_t i = 0; i + 2 < idx.size(); ++i)
                g.triangles.push_back(i % 2 == 0 ? std::array{idx[i], idx[i + 1], idx[i + 2]}
                                                 : std::array{idx[i + 1], idx[i], idx[i + 2]});
        } else if (mode == TINYGLTF_MODE_TRIANGLE_FAN) {
            for (std::size_t i = 1; i + 1 < idx.size(); ++i) g.triangles.push_back({idx[0], idx[i], idx[i + 1]});
        }
        const auto normal = p.attributes.find("NORMAL");
        if (normal != p.attributes.end()) {
            g.normals = toVec3(reader_.floats(normal->second, TINYGLTF_TYPE_VEC3, "NORMAL"));
            if (g.normals.size() != g.positions.size()) reader_.fail(where + "/attributes", "NORMAL count differs from POSITION's");
        }
        const auto uv = p.attributes.find("TEXCOORD_0");
        if (uv != p.attributes.end()) {
            const std::vector<double> st = reader_.floats(uv->second, TINYGLTF_TYPE_VEC2, "TEXCOORD_0");
            for (std::size_t i = 0; i + 1 < st.size(); i += 2) g.uvs.push_back({st[i], st[i + 1]});
            if (g.uvs.size() != g.positions.size()) reader_.fail(where + "/attributes", "TEXCOORD_0 count differs from POSITION's");
        }
        for (std::size_t t = 0; t < p.targets.size(); ++t) {
            const auto d = p.targets[t].find("POSITION");
            std::vector<glm::dvec3> delta(g.positions.size(), glm::dvec3(0.0));
            if (d != p.targets[t].end()) delta = toVec3(reader_.floats(d->second, TINYGLTF_TYPE_VEC3, "a morph target POSITION"));
            if (delta.size() != g.positions.size())
                reader_.fail(where + "/targets/" + std::to_string(t), "POSITION count differs from the primitive's");
            g.targets.push_back(std::move(delta));
        }
        return g;
    }

    std::vector<double> restWeights(std::size_t node, std::size_t targets) const {
        const tinygltf::Node& n = model_.nodes[node];
        const std::vector<double>& w = !n.weights.empty() ? n.weights
                                                          : model_.meshes[static_cast<std::size_t>(n.mesh)].weights;
        if (w.empty()) return std::vector<double>(targets, 0.0);
        if (w.size() != targets) reader_.fail(pointer("nodes", node), "weights count differs from the morph targets'");
        return w;
    }

    void addMeshInstance(const std::vector<std::size_t>& chain);
    void buildObject(const std::vector<std::size_t>& chain, std::size_t prim, PrimitiveGeometry g);
    // Morph weights that interpolate linearly (or STEP) become deformation keys at their key times (with
    // STEP holds): positions are linear in the weights, so the keys are exact.
    void morphKeys(Object& object, const PrimitiveGeometry& g, const Track& weights, const std::string& where);
    // Whether keys reproduce the motion (see planKeys), or the object needs an exact motion.
    bool keyable(const SplitChain& s, const Track* weights) const;
    std::vector<TransformKey> exactKeys(const ChainMotion& motion, const std::string& where) const;

    static std::vector<glm::dvec3> morphed(const PrimitiveGeometry& g, const Track& weights, double t) {
        std::vector<double> w(weights.width);
        weights.eval(t, w.data());
        std::vector<glm::dvec3> out = g.positions;
        for (std::size_t i = 0; i < w.size() && i < g.targets.size(); ++i)
            for (std::size_t v = 0; v < out.size(); ++v) out[v] += w[i] * g.targets[i][v];
        return out;
    }

    int materialOf(const tinygltf::Primitive& p, int mesh, std::size_t prim) const {
        if (p.material >= static_cast<int>(model_.materials.size()))
            reader_.fail(pointer("meshes", static_cast<std::size_t>(mesh)) + "/primitives/" + std::to_string(prim),
                         "material " + std::to_string(p.material) + " does not exist");
        return p.material < 0 ? static_cast<int>(default_material_) : p.material;
    }
    // A texture on a primitive without TEXCOORD_0 has no coordinates to be read at (the Khronos validator's
    // MESH_PRIMITIVE_TOO_FEW_TEXCOORDS error); Blender 3.4 writes it for a mesh without a UV map. Refused
    // rather than rendered at some constant coordinate.
    void requireNoTexture(const tinygltf::Primitive& p, int mesh, std::size_t prim, const std::string& where) const;
    SkinBinding skinBinding(std::size_t node, const tinygltf::Primitive& p, const PrimitiveGeometry& g);
    Object skinnedObject(Object object, std::size_t node, const tinygltf::Primitive& p, const PrimitiveGeometry& g);
    MorphBinding morphBinding(const PrimitiveGeometry& g, const Track* weights) const;
    std::vector<const AnimatedNode*> chainTo(std::size_t node) const;
    void checkJumps(const KeyPlan& plan, const std::string& where) const;
    std::vector<std::size_t> chosenCamera() const;
    void pickCamera();
    std::vector<CameraKey> cameraKeys(ChainMotion motion, const KeyPlan& plan, std::size_t node) const;
    void followCamera(const ChainMotion& motion, std::size_t node, Camera& camera) const;

    const tinygltf::Model& model_;
    GltfReader reader_;
    const GltfRequest& request_;
    std::filesystem::path folder_;  // image URIs are relative to the glTF file
    GltfScene out_;
    std::size_t default_material_ = 0;
    std::shared_ptr<AnimationStore> store_ = std::make_shared<AnimationStore>();  // shared by exact motions
    std::vector<AnimatedNode>& nodes_ = store_->nodes;
    std::deque<Track>& tracks_ = store_->tracks;
    std::map<std::size_t, const Track*> weight_tracks_;
    std::map<std::size_t, std::size_t> parents_;
    std::set<std::pair<std::size_t, std::string>> targeted_;
    std::set<std::size_t> visited_;
    std::set<std::string> names_;
    std::set<std::string> warnings_;
    std::vector<glm::dmat3> uv_transforms_;  // per out_.materials entry: its KHR_texture_transform
    std::vector<std::vector<std::size_t>> cameras_;
    std::uint64_t triangles_ = 0;
};

void SceneBuilder::addMeshInstance(const std::vector<std::size_t>& chain) {
    const std::size_t node = chain.back();
    const tinygltf::Node& n = model_.nodes[node];
    if (static_cast<std::size_t>(n.mesh) >= model_.meshes.size())
        reader_.fail(pointer("nodes", node), "mesh " + std::to_string(n.mesh) + " does not exist");
    if (n.skin >= 0 && static_cast<std::size_t>(n.skin) >= model_.skins.size())
        reader_.fail(pointer("nodes", node), "skin " + std::to_string(n.skin) + " does not exist");
    const tinygltf::Mesh& mesh = model_.meshes[static_cast<std::size_t>(n.mesh)];
    const std::string mesh_where = pointer("meshes", static_cast<std::size_t>(n.mesh));
    for (std::size_t i = 0; i < mesh.primitives.size(); ++i) {
        const tinygltf::Primitive& p = mesh.primitives[i];
        const std::string where = mesh_where + "/primitives/" + std::to_string(i);
        const int mode = p.mode < 0 ? TINYGLTF_MODE_TRIANGLES : p.mode;
        if (mode < TINYGLTF_MODE_TRIANGLES) {
            warnings_.insert("glTF points and lines are skipped (" + where + " and any others)");
            continue;
        }
        if (mode > TINYGLTF_MODE_TRIANGLE_FAN) reader_.fail(where, "unknown mode " + std::to_string(mode));
        if (p.attributes.count("JOINTS_0") && n.skin < 0) reader_.fail(where, "JOINTS_0 without a skin on the node");
        if (p.targets.size() != mesh.primitives[0].targets.size())
            reader_.fail(where, "primitives of one mesh must have the same number of morph targets");
        PrimitiveGeometry g = readPrimitive(p, where);
        triangles_ += g.triangles.size();
        if (triangles_ > request_.max_triangles)
            reader_.fail(where, "the scene has more than " + std::to_string(request_.max_triangles) + " triangles");
        if (g.triangles.empty()) {
            warnings_.insert("glTF primitives without triangles are skipped (" + where + " and any others)");
            continue;
        }
        if (g.uvs.empty()) requireNoTexture(p, n.mesh, i, where);
        buildObject(chain, i, std::move(g));
    }
}

void SceneBuilder::requireNoTexture(const tinygltf::Primitive& p, int mesh, std::size_t prim,
                                    const std::string& where) const {
    const Material& m = out_.materials[static_cast<std::size_t>(materialOf(p, mesh, prim))];
    const char* texture = !m.image.file.empty()            ? "baseColorTexture"
                          : !m.emission_image.file.empty() ? "emissiveTexture"
                                                           : nullptr;
    if (texture)
        reader_.fail(where + "/material", "material " + std::to_string(p.material) + "'s " + texture +
                                              " reads TEXCOORD_0, which the primitive lacks (give the mesh UVs or "
                                              "drop the texture)");
}

void SceneBuilder::checkJumps(const KeyPlan& plan, const std::string& where) const {
    const Shutter& s = request_.shutter;
    for (std::size_t i = 0; i + 1 < plan.times.size(); ++i) {
        if (!plan.jump_after[i]) continue;
        // Frames k whose open shutter (k + open, k + close) meets the jump window (h, j).
        const double h = plan.times[i];
        const double j = plan.times[i + 1];
        const double lo = std::max(static_cast<double>(request_.frames.first), std::floor(h - s.close) + 1.0);
        const double hi = std::min(static_cast<double>(request_.frames.last), std::ceil(j - s.open) - 1.0);
        if (lo <= hi)
            reader_.fail(where, "a STEP key jumps at frame " + std::to_string(j) + ", inside the shutter of frame " +
                                    std::to_string(static_cast<long long>(lo)) +
                                    ": a jump within the shutter cannot be rendered");
    }
}

void SceneBuilder::buildObject(const std::vector<std::size_t>& chain, std::size_t prim, PrimitiveGeometry g) {
    const std::size_t node = chain.back();
    const tinygltf::Node& n = model_.nodes[node];
    const tinygltf::Mesh& mesh = model_.meshes[static_cast<std::size_t>(n.mesh)];
    const std::string where = pointer("nodes", node);
    Object object;
    object.name = uniqueName(mesh.primitives.size() > 1 ? n.name + "/" + std::to_string(prim) : n.name);
    object.loc = request_.ref;
    object.material = materialOf(mesh.primitives[prim], n.mesh, prim);
    object.mesh.triangles = g.triangles;
    for (const auto& t : g.triangles)
        for (const std::uint32_t v : t) {
            if (!g.uvs.empty()) object.mesh.corner_uvs.push_back(g.uvs[v]);
            if (!g.normals.empty()) object.mesh.corner_normals.push_back(g.normals[v]);
        }
    const glm::dmat3& uv_transform = uv_transforms_[static_cast<std::size_t>(object.material)];
    for (glm::dvec2& uv : object.mesh.corner_uvs) uv = glm::dvec2(uv_transform * glm::dvec3(uv, 1.0));
    if (n.skin >= 0) {
        out_.objects.push_back(skinnedObject(std::move(object), node, mesh.primitives[prim], g));
        return;
    }
    const SplitChain s = split(chain);
    // The static tail is folded into the mesh, the offsets by its linear part only.
    for (glm::dvec3& p : g.positions) p = glm::dvec3(s.tail * glm::dvec4(p, 1.0));
    for (auto& target : g.targets)
        for (glm::dvec3& d : target) d = glm::dvec3(s.tail * glm::dvec4(d, 0.0));
    // Normals go by the inverse transpose of the tail's linear part, so they stay normal to the surface.
    const glm::dmat3 normal_map = glm::transpose(glm::inverse(glm::dmat3(s.tail)));
    for (glm::dvec3& normal : object.mesh.corner_normals) normal = normal_map * normal;
    object.mesh.positions = g.positions;
    const std::vector<double> rest = restWeights(node, g.targets.size());
    for (std::size_t t = 0; t < g.targets.size(); ++t)
        for (std::size_t v = 0; v < g.positions.size(); ++v) object.mesh.positions[v] += rest[t] * g.targets[t][v];
    const auto found = weight_tracks_.find(node);
    const Track* weights = found == weight_tracks_.end() ? nullptr : found->second;
    if (s.animated) checkJumps(planKeys(s.motion), where);
    if (keyable(s, weights)) {
        if (weights) morphKeys(object, g, *weights, where + "/weights");
        if (s.animated) object.transform = exactKeys(s.motion, where);
    } else {
        if (weights) checkJumps(planTimes({weights}), where + "/weights");
        auto motion = std::make_shared<ExactMotion>(store_, s.animated ? s.motion : ChainMotion{});
        if (weights) motion->setMorph(morphBinding(g, weights));
        object.motion = std::move(motion);
    }
    out_.objects.push_back(std::move(object));
}

// A skinned mesh ignores its node's transform (glTF 2.0, 3.7.3): positions come from the joints, followed
// exactly; the mesh keeps the bind pose with the rest weights.
Object SceneBuilder::skinnedObject(Object object, std::size_t node, const tinygltf::Primitive& p, const PrimitiveGeometry& g) {
    object.mesh.positions = g.positions;
    const std::vector<double> rest = restWeights(node, g.targets.size());
    for (std::size_t t = 0; t < g.targets.size(); ++t)
        for (std::size_t v = 0; v < g.positions.size(); ++v) object.mesh.positions[v] += rest[t] * g.targets[t][v];
    auto motion = std::make_shared<ExactMotion>(store_, ChainMotion{});
    SkinBinding skin = skinBinding(node, p, g);
    const auto morph = weight_tracks_.find(node);
    if (morph != weight_tracks_.end()) motion->setMorph(morphBinding(g, morph->second));
    std::vector<const Track*> tracks;
    for (const ChainMotion& joint : skin.joints)
        for (const AnimatedNode* a : joint.chain) tracks.insert(tracks.end(), {a->translation, a->rotation, a->scale});
    if (morph != weight_tracks_.end()) tracks.push_back(morph->second);
    tracks.erase(std::remove(tracks.begin(), tracks.end(), nullptr), tracks.end());
    checkJumps(planTimes(tracks), pointer("nodes", node) + "/skin");
    motion->setSkin(std::move(skin));
    object.motion = std::move(motion);
    return object;
}

// Keys where they are exact and within the key limits (a STEP hold per key at most counted); an exact
// motion otherwise, which has no limit.
bool SceneBuilder::keyable(const SplitChain& s, const Track* weights) const {
    if (weights && (weights->interpolation == Interpolation::CubicSpline ||
                    2 * weights->times.size() > request_.max_deformation_keys))
        return false;
    if (!s.animated) return true;
    const KeyPlan plan = planKeys(s.motion);
    return plan.exact && plan.times.size() <= request_.max_transform_keys;
}

std::vector<TransformKey> SceneBuilder::exactKeys(const ChainMotion& motion, const std::string& where) const {
    ResampleSpec spec;
    spec.max_keys = request_.max_transform_keys;
    try {
        return followChain(motion, planKeys(motion), spec);
    } catch (const std::domain_error& e) {
        reader_.fail(where, std::string("its world transform has ") + e.what() + ", which transform keys cannot hold");
    }
}

MorphBinding SceneBuilder::morphBinding(const PrimitiveGeometry& g, const Track* weights) const {
    MorphBinding morph;
    morph.weights = weights;
    morph.base = g.positions;
    morph.targets = g.targets;
    return morph;
}

void SceneBuilder::morphKeys(Object& object, const PrimitiveGeometry& g, const Track& weights, const std::string& where) {
    const KeyPlan plan = planTimes({&weights});
    checkJumps(plan, where);
    if (plan.times.size() * object.mesh.positions.size() > kMaxMorphPositions)
        reader_.fail(where, "the morph needs more than " + std::to_string(kMaxMorphPositions) + " key positions");
    for (const double t : plan.times) object.deformation.push_back(DeformationKey{t, morphed(g, weights, t)});
    object.mesh.positions = object.deformation.front().positions;
}

std::vector<const AnimatedNode*> SceneBuilder::chainTo(std::size_t node) const {
    std::vector<const AnimatedNode*> chain{&nodes_[node]};
    for (auto p = parents_.find(node); p != parents_.end(); p = parents_.find(p->second)) {
        if (chain.size() >= kMaxHierarchyDepth)
            reader_.fail(pointer("nodes", node), "the hierarchy is deeper than " + std::to_string(kMaxHierarchyDepth) + " levels");
        chain.push_back(&nodes_[p->second]);
    }
    std::reverse(chain.begin(), chain.end());
    return chain;
}

// Linear blend skinning (glTF 2.0, 3.7.3): each vertex moved by the weighted sum of its joints' world
// matrices times their inverse bind matrices, after the morph targets.
SkinBinding SceneBuilder::skinBinding(std::size_t node, const tinygltf::Primitive& p, const PrimitiveGeometry& g) {
    const auto skin_index = static_cast<std::size_t>(model_.nodes[node].skin);
    const tinygltf::Skin& skin = model_.skins[skin_index];
    const std::string where = pointer("skins", skin_index);
    if (skin.joints.empty()) reader_.fail(where, "a skin needs joints");
    if (p.attributes.count("JOINTS_1") || p.attributes.count("WEIGHTS_1"))
        reader_.fail(where, "at most 4 joints per vertex (JOINTS_0, WEIGHTS_0) are supported");
    const auto joints_at = p.attributes.find("JOINTS_0");
    const auto weights_at = p.attributes.find("WEIGHTS_0");
    if (joints_at == p.attributes.end() || weights_at == p.attributes.end())
        reader_.fail(pointer("nodes", node), "a skinned mesh needs JOINTS_0 and WEIGHTS_0");
    SkinBinding out;
    out.joint_ids = reader_.unsignedInts(joints_at->second, TINYGLTF_TYPE_VEC4, "JOINTS_0");
    out.weights = reader_.floats(weights_at->second, TINYGLTF_TYPE_VEC4, "WEIGHTS_0");
    if (out.joint_ids.size() != 4 * g.positions.size() || out.weights.size() != 4 * g.positions.size())
        reader_.fail(pointer("nodes", node), "JOINTS_0 and WEIGHTS_0 need one element per vertex");
    for (const std::uint32_t j : out.joint_ids)
        if (j >= skin.joints.size())
            reader_.fail(pointer("accessors", static_cast<std::size_t>(joints_at->second)),
                         "joint " + std::to_string(j) + " is out of range: the skin has " + std::to_string(skin.joints.size()));
    out.inverse_bind.assign(skin.joints.size(), glm::dmat4(1.0));
    if (skin.inverseBindMatrices >= 0) {
        const std::vector<double> m = reader_.floats(skin.inverseBindMatrices, TINYGLTF_TYPE_MAT4, "inverseBindMatrices");
        if (m.size() != 16 * skin.joints.size()) reader_.fail(where, "inverseBindMatrices needs one matrix per joint");
        for (std::size_t j = 0; j < out.inverse_bind.size(); ++j)
            for (int c = 0; c < 4; ++c)
                for (int r = 0; r < 4; ++r) out.inverse_bind[j][c][r] = m[16 * j + static_cast<std::size_t>(4 * c + r)];
    }
    for (std::size_t j = 0; j < skin.joints.size(); ++j) {
        const int joint = skin.joints[j];
        if (joint < 0 || static_cast<std::size_t>(joint) >= nodes_.size())
            reader_.fail(where + "/joints/" + std::to_string(j), "node " + std::to_string(joint) + " does not exist");
        out.joints.push_back(ChainMotion{chainTo(static_cast<std::size_t>(joint))});
    }
    return out;
}

// The camera node's chain: the one the job names, else the first camera in the scene; empty for none.
std::vector<std::size_t> SceneBuilder::chosenCamera() const {
    std::vector<std::size_t> matches;
    for (std::size_t i = 0; i < cameras_.size(); ++i) {
        const tinygltf::Node& n = model_.nodes[cameras_[i].back()];
        if (static_cast<std::size_t>(n.camera) >= model_.cameras.size())
            reader_.fail(pointer("nodes", cameras_[i].back()), "camera " + std::to_string(n.camera) + " does not exist");
        const std::string& camera_name = model_.cameras[static_cast<std::size_t>(n.camera)].name;
        if (request_.camera_name.empty() || n.name == request_.camera_name || camera_name == request_.camera_name)
            matches.push_back(i);
    }
    if (!request_.camera_name.empty()) {
        if (matches.empty())
            throwConfigError(request_.camera_ref, "no camera node or camera named '" + request_.camera_name + "' in " +
                                                      request_.ref.toString());
        if (matches.size() > 1)
            throwConfigError(request_.camera_ref, "'" + request_.camera_name + "' names " +
                                                      std::to_string(matches.size()) + " camera nodes; name one node");
    }
    return matches.empty() ? std::vector<std::size_t>{} : cameras_[matches.front()];
}

void SceneBuilder::pickCamera() {
    const std::vector<std::size_t> chain = chosenCamera();
    if (chain.empty()) return;
    const std::size_t node = chain.back();
    const std::string where = pointer("cameras", static_cast<std::size_t>(model_.nodes[node].camera));
    const tinygltf::Camera& c = model_.cameras[static_cast<std::size_t>(model_.nodes[node].camera)];
    if (c.type != "perspective") reader_.fail(where, "only perspective cameras are supported");
    const double yfov = c.perspective.yfov;
    if (!(yfov > 0.0 && yfov * 180.0 / M_PI <= 179.0)) reader_.fail(where + "/perspective/yfov", "must be in (0, 179] degrees");
    if (!(c.perspective.aspectRatio >= 0.0) || !std::isfinite(c.perspective.aspectRatio))
        reader_.fail(where + "/perspective/aspectRatio", "must be a positive number");
    Camera camera;
    camera.vfov_degrees = yfov * 180.0 / M_PI;
    out_.camera_aspect = c.perspective.aspectRatio;
    SplitChain s = split(chain);
    s.motion.tail = s.tail;
    if (!s.animated) s.motion.chain.clear();
    KeyPlan still;
    still.times = {0.0};
    still.jump_after = {false};
    still.exact = true;
    const KeyPlan plan = s.animated ? planKeys(s.motion) : still;
    checkJumps(plan, pointer("nodes", node));
    if (plan.exact && plan.times.size() <= request_.max_transform_keys)
        camera.keys = cameraKeys(s.motion, plan, node);
    else
        followCamera(s.motion, node, camera);
    out_.camera = camera;
}

// Keys where they are exact: one animated node without CUBICSPLINE under static ancestors of uniform
// scale, or no motion at all.
std::vector<CameraKey> SceneBuilder::cameraKeys(ChainMotion motion, const KeyPlan& plan, std::size_t node) const {
    motion.rigid = true;
    ResampleSpec spec;
    spec.max_keys = request_.max_transform_keys;
    std::vector<TransformKey> keys;
    try {
        keys = followChain(motion, plan, spec);
    } catch (const std::domain_error& e) {
        reader_.fail(pointer("nodes", node), std::string("the camera's world transform has ") + e.what());
    }
    std::vector<CameraKey> out;
    for (const TransformKey& k : keys)
        out.push_back({k.time, k.translate, k.rotate * glm::dvec3(0, 0, -1), k.rotate * glm::dvec3(0, 1, 0)});
    return out;
}

// Any other motion is followed exactly (ExactCamera). Its poses at the key times and between them are
// checked here, so that a -Z column collapsing onto +Y or to zero is reported against the node.
void SceneBuilder::followCamera(const ChainMotion& motion, std::size_t node, Camera& camera) const {
    auto exact = std::make_shared<ExactCamera>(store_, motion);
    const std::vector<double>& times = exact->keyTimes();
    double t = times.front();
    try {
        for (std::size_t i = 0; i < times.size(); ++i) {
            t = times[i];
            const CameraFrame f = exact->at(t);
            camera.keys.push_back({t, f.position, f.e3, f.e1});
            if (i + 1 < times.size()) exact->at(t = 0.5 * (times[i] + times[i + 1]));
        }
    } catch (const Error& e) {
        std::ostringstream frame;
        frame << t;
        reader_.fail(pointer("nodes", node), "at frame " + frame.str() + ": " + e.message());
    }
    camera.motion = std::move(exact);
}

GltfScene buildScene(tinygltf::Model& model, const std::string& name, const GltfRequest& request) {
    return SceneBuilder(model, name, request).build();
}

}  // namespace

GltfScene parseGltfScene(const std::string& bytes, const std::string& name, const std::filesystem::path& base,
                         const GltfRequest& request) {
    tinygltf::TinyGLTF loader;
    loader.SetImageLoader(skipImage, nullptr);
    tinygltf::Model model;
    std::string err;
    std::string warn;
    bool ok = false;
    try {
        if (isGlb(bytes))
            ok = loader.LoadBinaryFromMemory(&model, &err, &warn, reinterpret_cast<const unsigned char*>(bytes.data()),
                                             static_cast<unsigned int>(bytes.size()), base.string());
        else
            ok = loader.LoadASCIIFromString(&model, &err, &warn, bytes.data(), static_cast<unsigned int>(bytes.size()),
                                            base.string());
    } catch (const std::exception& e) {
        err = e.what();
    }
    if (!ok) {
        while (!err.empty() && (err.back() == '\n' || err.back() == ' ')) err.pop_back();
        const std::string ref = request.ref.toString();
        throw Error(ExitCode::Scene, "not a valid glTF file: " + (err.empty() ? std::string("unreadable") : err) +
                                         (ref.empty() ? "" : " (glTF file of " + ref + ")"),
                    FileLoc{name, 0, 0});
    }
    GltfScene scene = buildScene(model, name, request);
    for (const tinygltf::Buffer& b : model.buffers)
        if (!b.uri.empty() && b.uri.rfind("data:", 0) != 0) scene.buffer_files.push_back(base / b.uri);
    return scene;
}

GltfScene loadGltfScene(const std::filesystem::path& file, const GltfRequest& request) {
    std::error_code ec;
    const std::uintmax_t size = std::filesystem::file_size(file, ec);
    if (ec || !std::filesystem::is_regular_file(file))
        throwSceneError(request.ref, "cannot read glTF file '" + file.string() + "'");
    if (size > kMaxGltfFileBytes)
        throwSceneError(request.ref, "glTF file '" + file.string() + "' is larger than 512 MiB");
    std::ifstream in(file, std::ios::binary);
    const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    if (!in && !in.eof()) throwSceneError(request.ref, "cannot read glTF file '" + file.string() + "'");
    return parseGltfScene(bytes, file.string(), file.parent_path(), request);
}

}  // namespace clipblur
