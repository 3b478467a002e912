#include "io/cryptomatte.h"

#include <algorithm>
#include <cstdio>
#include <cstring>

#include <nlohmann/json.hpp>

#include "scene/error.h"

namespace clipblur {

namespace {

std::uint32_t rotl(std::uint32_t x, int r) { return (x << r) | (x >> (32 - r)); }

// One 32-bit block's contribution before it is mixed into the state.
std::uint32_t scrambleBlock(std::uint32_t k) {
    k *= 0xcc9e2d51u;
    k = rotl(k, 15);
    return k * 0x1b873593u;
}

// The final avalanche: every input bit affects every output bit.
std::uint32_t finalMix(std::uint32_t h) {
    h ^= h >> 16;
    h *= 0x85ebca6bu;
    h ^= h >> 13;
    h *= 0xc2b2ae35u;
    return h ^ (h >> 16);
}

struct RankedId {
    std::uint32_t hash = 0;
    float id = 0.0f;
    double coverage = 0.0;
};

// The pixel's IDs with objects of one name merged, highest coverage first, ties by smaller hash.
std::vector<RankedId> rankPixel(const std::vector<ObjectShare>& shares, const std::vector<std::uint32_t>& hashes) {
    std::vector<RankedId> ranked;
    for (const ObjectShare& s : shares) {
        const std::uint32_t h = hashes[static_cast<std::size_t>(s.object)];
        const auto same = std::find_if(ranked.begin(), ranked.end(), [h](const RankedId& r) { return r.hash == h; });
        if (same != ranked.end())
            same->coverage += s.coverage;
        else
            ranked.push_back({h, cryptomatteId(h), s.coverage});
    }
    // A coverage of 0 or -1e-17 is rounding where signed parts cancel (the clipped renderer's swept pixels).
    std::erase_if(ranked, [](const RankedId& r) { return !(r.coverage > 0.0); });
    std::sort(ranked.begin(), ranked.end(), [](const RankedId& a, const RankedId& b) {
        return a.coverage != b.coverage ? a.coverage > b.coverage : a.hash < b.hash;
    });
    return ranked;
}

}  // namespace

std::uint32_t murmurHash3x86_32(std::string_view data, std::uint32_t seed) {
    const auto* bytes = reinterpret_cast<const unsigned char*>(data.data());
    const std::size_t blocks = data.size() / 4;
    std::uint32_t h = seed;
    for (std::size_t i = 0; i < blocks; ++i) {
        // Little-endian blocks, read byte by byte so the result does not depend on the host.
        const unsigned char* b = bytes + 4 * i;
        const std::uint32_t k = std::uint32_t(b[0]) | std::uint32_t(b[1]) << 8 | std::uint32_t(b[2]) << 16 |
                                std::uint32_t(b[3]) << 24;
        h ^= scrambleBlock(k);
        h = rotl(h, 13);
        h = h * 5u + 0xe6546b64u;
    }
    const unsigned char* tail = bytes + 4 * blocks;
    std::uint32_t k = 0;
    switch (data.size() & 3u) {
        case 3: k ^= std::uint32_t(tail[2]) << 16; [[fallthrough]];
        case 2: k ^= std::uint32_t(tail[1]) << 8; [[fallthrough]];
        case 1: k ^= std::uint32_t(tail[0]); h ^= scrambleBlock(k); break;
        default: break;
    }
    h ^= static_cast<std::uint32_t>(data.size());
    return finalMix(h);
}

float cryptomatteId(std::uint32_t hash) {
    const std::uint32_t exponent = std::clamp<std::uint32_t>((hash >> 23) & 0xffu, 1u, 254u);
    const std::uint32_t bits = (hash & 0x807fffffu) | (exponent << 23);
    float id;
    std::memcpy(&id, &bits, sizeof id);
    return id;
}

std::string cryptomatteIdHex(float id) {
    std::uint32_t bits;
    std::memcpy(&bits, &id, sizeof bits);
    char text[9];
    std::snprintf(text, sizeof text, "%08x", bits);
    return text;
}

std::string cryptomatteKey(const std::string& name) {
    char text[9];
    std::snprintf(text, sizeof text, "%08x", murmurHash3x86_32(name, 0));
    return std::string(text, 7);
}

std::map<std::string, std::string> addCryptomatte(Image& image, const ObjectCoverage& coverage,
                                                  const std::vector<std::string>& object_names,
                                                  const CryptomatteSettings& settings) {
    const std::size_t n = image.window.area();
    if (coverage.pixels.size() != n) throw Error(ExitCode::Internal, "object coverage does not match the image");
    std::vector<std::uint32_t> hashes;
    nlohmann::json manifest = nlohmann::json::object();
    for (const std::string& name : object_names) {
        hashes.push_back(murmurHash3x86_32(name, 0));
        manifest[name] = cryptomatteIdHex(cryptomatteId(hashes.back()));
    }
    const std::size_t first = image.channels.size();
    const int layers = (settings.depth + 1) / 2;
    for (int layer = 0; layer < layers; ++layer) {
        char number[12];  // room for any int, so the format cannot truncate
        std::snprintf(number, sizeof number, "%02d", layer);
        for (const char* c : {".R", ".G", ".B", ".A"})
            image.channels.push_back({settings.name + number + c, std::vector<float>(n, 0.0f)});
    }
    for (std::size_t i = 0; i < n; ++i) {
        const std::vector<RankedId> ranked = rankPixel(coverage.pixels[i], hashes);
        const std::size_t kept = std::min(ranked.size(), static_cast<std::size_t>(settings.depth));
        for (std::size_t r = 0; r < kept; ++r) {
            image.channels[first + 2 * r].values[i] = ranked[r].id;
            image.channels[first + 2 * r + 1].values[i] = static_cast<float>(ranked[r].coverage);
        }
    }
    const std::string prefix = "cryptomatte/" + cryptomatteKey(settings.name) + "/";
    return {{prefix + "name", settings.name},
            {prefix + "hash", "MurmurHash3_32"},
            {prefix + "conversion", "uint32_to_float32"},
            {prefix + "manifest", manifest.dump()}};
}

}  // namespace clipblur
