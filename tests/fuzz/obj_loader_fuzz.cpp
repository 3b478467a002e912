#include <cstddef>
#include <cstdint>
#include <string>

#include "scene/error.h"
#include "scene/obj_loader.h"

// Feeds the bytes to the OBJ reader and its polygon triangulation. A clipblur::Error is an expected
// outcome; a crash, sanitizer report, other exception or a hang (libFuzzer's -timeout) is a finding.
extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const std::string text(reinterpret_cast<const char*>(data), size);
    try {
        clipblur::parseObjMesh(text, "fuzz.obj", clipblur::FileLoc{"job.yaml", 1, 1}, std::uint64_t{1} << 20);
    } catch (const clipblur::Error&) {
    }
    return 0;
}
