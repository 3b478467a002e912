#include <cmath>
#include <cstring>
#include <string>

#include <gtest/gtest.h>

#include "io/cryptomatte.h"

namespace clipblur {

// Published MurmurHash3_x86_32 test vectors (input bytes, seed, hash), covering empty input, each tail
// length and whole blocks.
TEST(Cryptomatte, MurmurHash3MatchesPublishedVectors) {
    struct Vector {
        std::string data;
        std::uint32_t seed;
        std::uint32_t hash;
    };
    const Vector vectors[] = {
        {"", 0u, 0u},
        {"", 1u, 0x514e28b7u},
        {"", 0xffffffffu, 0x81f16f39u},
        {"\xff\xff\xff\xff", 0u, 0x76293b50u},
        {"\x21\x43\x65\x87", 0u, 0xf55b516bu},
        {"\x21\x43\x65\x87", 0x5082edeeu, 0x2362f9deu},
        {"\x21\x43\x65", 0u, 0x7e4a8634u},
        {"\x21\x43", 0u, 0xa0f7b07au},
        {"\x21", 0u, 0x72661cf4u},
        {std::string(4, '\0'), 0u, 0x2362f9deu},
        {std::string(3, '\0'), 0u, 0x85f0b427u},
        {std::string(2, '\0'), 0u, 0x30f4c306u},
        {std::string(1, '\0'), 0u, 0x514e28b7u},
        {"Hello, world!", 1234u, 0xfaf6cdb3u},
        {"The quick brown fox jumps over the lazy dog", 0x9747b28cu, 0x2fa826cdu},
    };
    for (const Vector& v : vectors) EXPECT_EQ(murmurHash3x86_32(v.data, v.seed), v.hash) << v.data.size();
}

// The specification's own manifest examples: names and the hex of their float IDs.
TEST(Cryptomatte, IdsMatchTheSpecificationsManifestExamples) {
    EXPECT_EQ(cryptomatteIdHex(cryptomatteId(murmurHash3x86_32("bunny", 0))), "13851a76");
    EXPECT_EQ(cryptomatteIdHex(cryptomatteId(murmurHash3x86_32("default", 0))), "42c9679f");
    EXPECT_EQ(cryptomatteIdHex(cryptomatteId(murmurHash3x86_32("bunny_porcelain_mat", 0))), "b24b26d4");
}

// Exponent bits 0 and 255 are clamped to 1 and 254: never a denormal, an infinity or a NaN; the sign
// and mantissa bits are kept.
TEST(Cryptomatte, IdExponentIsClampedToNormalFloats) {
    EXPECT_EQ(cryptomatteIdHex(cryptomatteId(0u)), "00800000");
    EXPECT_EQ(cryptomatteIdHex(cryptomatteId(0xffffffffu)), "ff7fffff");
    EXPECT_EQ(cryptomatteIdHex(cryptomatteId(0x7f800001u)), "7f000001");
    EXPECT_EQ(cryptomatteIdHex(cryptomatteId(0x3f800000u)), "3f800000");  // 1.0f unchanged
    EXPECT_TRUE(std::isnormal(cryptomatteId(0u)));
    EXPECT_TRUE(std::isfinite(cryptomatteId(0xffffffffu)));
}

// Three pixels: ranking by coverage, a tie broken by the smaller hash, objects of one name merged, the
// depth limit, empty ranks zero, and the header.
TEST(Cryptomatte, LayersRankCoverageAndHeaderNamesTheType) {
    Image image = Image::make(3, 1, {"R", "G", "B", "A"});
    ObjectCoverage coverage;
    coverage.pixels = {{{0, 0.125}, {1, 0.5}, {2, 0.25}}, {{0, 0.25}, {3, 0.25}}, {{1, 0.25}, {2, 0.25}}};
    const std::vector<std::string> names{"a", "b", "c", "a"};  // objects 0 and 3 share a name
    const auto header = addCryptomatte(image, coverage, names, CryptomatteSettings{true, "CryptoObject", 3});
    ASSERT_EQ(image.channels.size(), 4u + 8u);  // ceil(3 / 2) = 2 layers
    EXPECT_EQ(image.channels[4].name, "CryptoObject00.R");
    EXPECT_EQ(image.channels[11].name, "CryptoObject01.A");
    const float a = cryptomatteId(murmurHash3x86_32("a", 0)), b = cryptomatteId(murmurHash3x86_32("b", 0)),
                c = cryptomatteId(murmurHash3x86_32("c", 0));
    const auto at = [&](std::size_t channel, std::size_t pixel) { return image.channels[4 + channel].values[pixel]; };
    EXPECT_EQ(at(0, 0), b);
    EXPECT_EQ(at(1, 0), 0.5f);
    EXPECT_EQ(at(2, 0), c);
    EXPECT_EQ(at(3, 0), 0.25f);
    EXPECT_EQ(at(4, 0), a);
    EXPECT_EQ(at(5, 0), 0.125f);
    EXPECT_EQ(at(6, 0), 0.0f);  // rank 3 is beyond depth 3
    EXPECT_EQ(at(0, 1), a);     // 0.25 + 0.25 of the two objects named "a"
    EXPECT_EQ(at(1, 1), 0.5f);
    EXPECT_EQ(at(2, 1), 0.0f);
    EXPECT_EQ(at(3, 1), 0.0f);
    const bool b_first = murmurHash3x86_32("b", 0) < murmurHash3x86_32("c", 0);  // equal coverage
    EXPECT_EQ(at(0, 2), b_first ? b : c);
    EXPECT_EQ(at(2, 2), b_first ? c : b);

    const std::string key = cryptomatteKey("CryptoObject");
    EXPECT_EQ(key.size(), 7u);
    EXPECT_EQ(header.at("cryptomatte/" + key + "/name"), "CryptoObject");
    EXPECT_EQ(header.at("cryptomatte/" + key + "/hash"), "MurmurHash3_32");
    EXPECT_EQ(header.at("cryptomatte/" + key + "/conversion"), "uint32_to_float32");
    const std::string manifest = header.at("cryptomatte/" + key + "/manifest");
    EXPECT_NE(manifest.find("\"b\":\"" + cryptomatteIdHex(b) + "\""), std::string::npos) << manifest;
}

TEST(Cryptomatte, KeyIsTheHashOfTheNameCutToSevenDigits) {
    EXPECT_EQ(cryptomatteKey("bunny").size(), 7u);
    // murmur3("CryptoObject") = 0x3ae39a58 (computed with an independent implementation of the algorithm).
    EXPECT_EQ(cryptomatteKey("CryptoObject"), "3ae39a5");
}

}  // namespace clipblur
