#pragma once

// tinygltf as clipblur builds it, the same in every file that includes it (the header's inline defaults
// name the image callbacks these macros remove): images are neither decoded, written nor read, since
// textures are not supported yet; JSON is Debian's nlohmann json.
#define TINYGLTF_NO_STB_IMAGE
#define TINYGLTF_NO_STB_IMAGE_WRITE
#define TINYGLTF_NO_EXTERNAL_IMAGE
#include <tiny_gltf.h>
