#pragma once

#include <cstdint>
#include <map>
#include <string>
#include <string_view>
#include <vector>

#include "renderer/image.h"
#include "renderer/object_coverage.h"
#include "scene/job.h"

namespace clipblur {

// Cryptomatte ID mattes as Psyop's public specification (version 1.1.0) defines them: per pixel the
// objects seen, ranked by coverage, as (ID, coverage) pairs in layers <name>00, <name>01, ... (R: ID of
// rank 2k, G: its coverage, B: ID of rank 2k+1, A: its coverage), IDs the MurmurHash3_32 of the object
// name turned into a float, and a manifest of names and IDs in the header.

// MurmurHash3, x86 32-bit variant (Austin Appleby's public-domain algorithm), of `data` with `seed`.
std::uint32_t murmurHash3x86_32(std::string_view data, std::uint32_t seed);

// The specification's uint32_to_float32: the hash's bits as a float, the exponent clamped to
// [1, 254] so that no ID is a denormal, an infinity or a NaN.
float cryptomatteId(std::uint32_t hash);

// An ID as the manifest writes it: its float bits as 8 lower-case hex digits.
std::string cryptomatteIdHex(float id);

// The header key of a Cryptomatte type: the first 7 hex digits of the hash of its name (the
// specification's suggestion; the key is at most 7 characters and stays the same across frames).
std::string cryptomatteKey(const std::string& name);

// Appends ceil(depth / 2) layers to `image` (float channels over its data window) from `coverage`
// and returns the header attributes (cryptomatte/<key>/name, hash, conversion, manifest). Objects of
// the same name share one ID, so their coverage adds up; ties in coverage rank the smaller ID first;
// empty ranks hold ID 0 and coverage 0.
std::map<std::string, std::string> addCryptomatte(Image& image, const ObjectCoverage& coverage,
                                                  const std::vector<std::string>& object_names,
                                                  const CryptomatteSettings& settings);

}  // namespace clipblur
