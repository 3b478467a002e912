#include "support/gltf_writer.h"

#include <algorithm>
#include <cstring>
#include <fstream>
#include <limits>

namespace clipblur::testing {

namespace {

std::string base64(const std::vector<std::uint8_t>& bytes) {
    static const char* abc = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    std::string out;
    for (std::size_t i = 0; i < bytes.size(); i += 3) {
        const std::uint32_t b0 = bytes[i];
        const std::uint32_t b1 = i + 1 < bytes.size() ? bytes[i + 1] : 0;
        const std::uint32_t b2 = i + 2 < bytes.size() ? bytes[i + 2] : 0;
        const std::uint32_t v = (b0 << 16) | (b1 << 8) | b2;
        out += abc[(v >> 18) & 63];
        out += abc[(v >> 12) & 63];
        out += i + 1 < bytes.size() ? abc[(v >> 6) & 63] : '=';
        out += i + 2 < bytes.size() ? abc[v & 63] : '=';
    }
    return out;
}

void appendU32(std::string& s, std::uint32_t v) {
    char b[4];
    std::memcpy(b, &v, 4);
    s.append(b, 4);
}

std::size_t componentCount(const std::string& type) {
    return type == "SCALAR" ? 1 : type == "VEC2" ? 2 : type == "VEC3" ? 3 : type == "VEC4" ? 4 : type == "MAT4" ? 16 : 0;
}

}  // namespace

GltfWriter::GltfWriter() {
    doc_["asset"] = {{"version", "2.0"}, {"generator", "clipblur tests"}};
    doc_["bufferViews"] = nlohmann::json::array();
    doc_["accessors"] = nlohmann::json::array();
}

int GltfWriter::addView(const std::vector<std::uint8_t>& bytes, int target) {
    while (bin_.size() % 4 != 0) bin_.push_back(0);
    nlohmann::json view = {{"buffer", 0}, {"byteOffset", bin_.size()}, {"byteLength", bytes.size()}};
    if (target != 0) view["target"] = target;
    bin_.insert(bin_.end(), bytes.begin(), bytes.end());
    doc_["bufferViews"].push_back(view);
    return static_cast<int>(doc_["bufferViews"].size()) - 1;
}

int GltfWriter::addFloats(const std::vector<float>& values, const std::string& type, int target) {
    const std::size_t n = componentCount(type);
    std::vector<std::uint8_t> bytes(values.size() * 4);
    std::memcpy(bytes.data(), values.data(), bytes.size());
    std::vector<float> lo(n, std::numeric_limits<float>::max());
    std::vector<float> hi(n, std::numeric_limits<float>::lowest());
    for (std::size_t i = 0; i < values.size(); ++i) {
        lo[i % n] = std::min(lo[i % n], values[i]);
        hi[i % n] = std::max(hi[i % n], values[i]);
    }
    const int view = addView(bytes, target);
    doc_["accessors"].push_back({{"bufferView", view}, {"componentType", 5126}, {"count", values.size() / n},
                                 {"type", type}, {"min", lo}, {"max", hi}});
    return static_cast<int>(doc_["accessors"].size()) - 1;
}

int GltfWriter::addIndices(const std::vector<std::uint32_t>& values, int component_type) {
    const std::size_t size = component_type == 5121 ? 1 : component_type == 5123 ? 2 : 4;
    std::vector<std::uint8_t> bytes(values.size() * size);
    for (std::size_t i = 0; i < values.size(); ++i) std::memcpy(&bytes[i * size], &values[i], size);  // little-endian
    const int view = addView(bytes, 34963);
    doc_["accessors"].push_back(
        {{"bufferView", view}, {"componentType", component_type}, {"count", values.size()}, {"type", "SCALAR"}});
    return static_cast<int>(doc_["accessors"].size()) - 1;
}

int GltfWriter::addUnsigned(const std::vector<std::uint32_t>& values, int component_type, const std::string& type) {
    const std::size_t size = component_type == 5121 ? 1 : component_type == 5123 ? 2 : 4;
    std::vector<std::uint8_t> bytes(values.size() * size);
    for (std::size_t i = 0; i < values.size(); ++i) std::memcpy(&bytes[i * size], &values[i], size);  // little-endian
    const int view = addView(bytes, 34962);
    doc_["accessors"].push_back({{"bufferView", view}, {"componentType", component_type},
                                 {"count", values.size() / componentCount(type)}, {"type", type}});
    return static_cast<int>(doc_["accessors"].size()) - 1;
}

nlohmann::json GltfWriter::withBuffer(const std::string& uri) const {
    nlohmann::json d = doc_;
    std::vector<std::uint8_t> padded = bin_;
    while (padded.size() % 4 != 0) padded.push_back(0);
    nlohmann::json buffer = {{"byteLength", padded.size()}};
    if (!uri.empty()) buffer["uri"] = uri;
    d["buffers"] = nlohmann::json::array({buffer});
    return d;
}

std::string GltfWriter::gltfText() const {
    std::vector<std::uint8_t> padded = bin_;
    while (padded.size() % 4 != 0) padded.push_back(0);
    return withBuffer("data:application/octet-stream;base64," + base64(padded)).dump(1);
}

std::string GltfWriter::glb() const {
    std::string json = withBuffer("").dump();
    while (json.size() % 4 != 0) json += ' ';
    std::vector<std::uint8_t> bin = bin_;
    while (bin.size() % 4 != 0) bin.push_back(0);
    std::string out = "glTF";
    appendU32(out, 2);
    appendU32(out, static_cast<std::uint32_t>(12 + 8 + json.size() + 8 + bin.size()));
    appendU32(out, static_cast<std::uint32_t>(json.size()));
    appendU32(out, 0x4E4F534A);  // JSON
    out += json;
    appendU32(out, static_cast<std::uint32_t>(bin.size()));
    appendU32(out, 0x004E4942);  // BIN
    out.append(reinterpret_cast<const char*>(bin.data()), bin.size());
    return out;
}

void GltfWriter::writeGltf(const std::filesystem::path& file) const { std::ofstream(file, std::ios::binary) << gltfText(); }

void GltfWriter::writeGltfWithBin(const std::filesystem::path& file) const {
    const std::string bin_name = file.stem().string() + ".bin";
    std::ofstream(file, std::ios::binary) << withBuffer(bin_name).dump(1);
    std::vector<std::uint8_t> padded = bin_;
    while (padded.size() % 4 != 0) padded.push_back(0);
    std::ofstream(file.parent_path() / bin_name, std::ios::binary)
        .write(reinterpret_cast<const char*>(padded.data()), static_cast<std::streamsize>(padded.size()));
}

void GltfWriter::writeGlb(const std::filesystem::path& file) const { std::ofstream(file, std::ios::binary) << glb(); }

std::filesystem::path validatedAssetDir() {
    const std::filesystem::path dir = CLIPBLUR_GLTF_ASSET_DIR;
    std::filesystem::create_directories(dir);
    return dir;
}

}  // namespace clipblur::testing
