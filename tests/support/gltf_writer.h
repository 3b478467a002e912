#pragma once

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace clipblur::testing {

// Builds glTF 2.0 test assets by hand: the JSON is written field by field by the test, the binary data
// goes into one buffer, embedded as a base64 data URI (.gltf), beside it as a .bin file, or as a .glb.
class GltfWriter {
public:
    GltfWriter();

    nlohmann::json& doc() { return doc_; }

    // A float accessor of `type` ("SCALAR", "VEC3", "VEC4") over its own bufferView; returns its index.
    // min and max are written (required for POSITION and animation inputs).
    int addFloats(const std::vector<float>& values, const std::string& type, int target = 0);
    // Unsigned indices with a component type of 5121, 5123 or 5125.
    int addIndices(const std::vector<std::uint32_t>& values, int component_type);
    // Unsigned integers of `type` (JOINTS_0: "VEC4", 5121 or 5123) as a vertex attribute.
    int addUnsigned(const std::vector<std::uint32_t>& values, int component_type, const std::string& type);

    std::string gltfText() const;  // buffer as a data URI
    std::string glb() const;
    void writeGltf(const std::filesystem::path& file) const;
    // The .gltf names its buffer `<stem>.bin`, written beside it.
    void writeGltfWithBin(const std::filesystem::path& file) const;
    void writeGlb(const std::filesystem::path& file) const;

private:
    int addView(const std::vector<std::uint8_t>& bytes, int target);
    nlohmann::json withBuffer(const std::string& uri) const;

    nlohmann::json doc_;
    std::vector<std::uint8_t> bin_;
};

// Where tests put the glTF assets that must pass the Khronos validator (ctest gltf_validator).
std::filesystem::path validatedAssetDir();

}  // namespace clipblur::testing
