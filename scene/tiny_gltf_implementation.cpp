// tinygltf's code, compiled once here (Debian's README.Debian, second route) so that the sanitizer and
// fuzzer builds instrument it too.
#define TINYGLTF_IMPLEMENTATION
#include "scene/tiny_gltf_config.h"
