#pragma once

#include <cstdint>

namespace clipblur {

// 64-bit finaliser with full avalanche (every input bit flips each output bit with probability ~1/2),
// so consecutive counters give independent-looking outputs.
constexpr std::uint64_t mixBits(std::uint64_t v) {
    v ^= v >> 31;
    v *= 0x7fb5d329728ea185ULL;
    v ^= v >> 27;
    v *= 0x81dadef4bc2dd44dULL;
    v ^= v >> 33;
    return v;
}

// Counter-based random numbers: the value for (key, index) is a pure function of both, so a sample's
// random numbers depend on (seed, frame, pixel, sample) only and never on which thread draws them.
class HashRng {
public:
    constexpr HashRng() = default;
    constexpr explicit HashRng(std::uint64_t key) : key_(key) {}

    // A stream keyed by the seed and up to three more integers (frame, pixel, sample).
    static constexpr HashRng forKey(std::uint64_t seed, std::uint64_t a, std::uint64_t b = 0, std::uint64_t c = 0) {
        std::uint64_t k = mixBits(seed + 0x9e3779b97f4a7c15ULL);
        k = mixBits(k ^ (a + 0x632be59bd9b4e019ULL));
        k = mixBits(k ^ (b + 0x8cb92ba72f3d8dd7ULL));
        k = mixBits(k ^ (c + 0xd1b54a32d192ed03ULL));
        return HashRng(k);
    }

    // A child stream, e.g. the stream of one sample inside a pixel's stream.
    constexpr HashRng child(std::uint64_t index) const { return HashRng(mixBits(key_ ^ mixBits(index + 0x2545f4914f6cdd1dULL))); }

    constexpr std::uint64_t bits(std::uint64_t index) const { return mixBits(key_ + index * 0x9e3779b97f4a7c15ULL); }

    // Uniform in [0, 1): the top 53 bits as a double, so 1.0 is never returned.
    constexpr double uniform(std::uint64_t index) const {
        return static_cast<double>(bits(index) >> 11) * 0x1.0p-53;
    }

    // Uniform integer in [0, n) by multiply-high (bias below 2^-32 for n < 2^32).
    std::uint32_t below(std::uint64_t index, std::uint32_t n) const {
        const std::uint64_t r = bits(index) >> 32;
        return static_cast<std::uint32_t>((r * n) >> 32);
    }

    constexpr std::uint64_t key() const { return key_; }

private:
    std::uint64_t key_ = 0;
};

}  // namespace clipblur
