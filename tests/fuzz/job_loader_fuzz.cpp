#include <cstddef>
#include <cstdint>
#include <string>

#include "io/job_loader.h"
#include "scene/error.h"

// Feeds the same bytes through the whole loader as YAML and as JSON. Any clipblur::Error is an
// expected outcome; a crash, sanitizer report or other exception is a finding. The virtual folder
// does not exist, so OBJ references fail cleanly instead of reading the machine's files.
extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const std::string text(reinterpret_cast<const char*>(data), size);
    for (const char* name : {"/nonexistent-fuzz/job.yaml", "/nonexistent-fuzz/job.json"}) {
        try {
            clipblur::loadJobFromText(text, name);
        } catch (const clipblur::Error&) {
        }
    }
    return 0;
}
