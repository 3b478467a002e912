#include "renderer/image_module.h"

#include <dlfcn.h>

#include <filesystem>
#include <system_error>

#include "scene/error.h"

namespace clipblur {

namespace {

constexpr const char* kModuleName = "libclipblur_oiio.so";
constexpr const char* kEntryPoint = "clipblur_image_module";

struct Loaded {
    const ImageModule* module = nullptr;
    std::string error;
};

Loaded load() {
    namespace fs = std::filesystem;
    std::error_code ec;
    const fs::path beside = fs::read_symlink("/proc/self/exe", ec).parent_path() / kModuleName;
    const std::string path = !ec && fs::is_regular_file(beside, ec) ? beside.string() : std::string(CLIPBLUR_OIIO_MODULE);
    // Never closed: the module's texture system and OpenImageIO's own state live until the process ends.
    void* handle = ::dlopen(path.c_str(), RTLD_NOW | RTLD_LOCAL);
    if (!handle) return {nullptr, "cannot load the image I/O module " + path + ": " + ::dlerror()};
    using Entry = const ImageModule* (*)();
    auto entry = reinterpret_cast<Entry>(::dlsym(handle, kEntryPoint));
    if (!entry) return {nullptr, "image I/O module " + path + " lacks " + kEntryPoint};
    return {entry(), {}};
}

}  // namespace

const ImageModule& imageModule() {
    static const Loaded loaded = load();  // once, thread-safe
    if (!loaded.module) throw Error(ExitCode::Output, loaded.error);
    return *loaded.module;
}

}  // namespace clipblur
