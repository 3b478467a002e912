#include "io/atomic_file.h"

#include <atomic>
#include <system_error>
#include <unistd.h>

#include "scene/error.h"

namespace clipblur {

namespace fs = std::filesystem;

void writeAtomically(const fs::path& target, const std::function<void(const fs::path&)>& write) {
    static std::atomic<unsigned> counter{0};
    const fs::path folder = target.has_parent_path() ? target.parent_path() : fs::path(".");
    std::error_code ec;
    fs::create_directories(folder, ec);
    if (ec) throw Error(ExitCode::Output, "cannot create folder " + folder.string() + ": " + ec.message());
    // Keep the extension last so format-sniffing writers (OpenImageIO) still pick the right format.
    const fs::path temporary = folder / (".tmp-" + std::to_string(::getpid()) + "-" + std::to_string(counter++) +
                                         "-" + target.filename().string());
    try {
        write(temporary);
    } catch (...) {
        fs::remove(temporary, ec);
        throw;
    }
    fs::rename(temporary, target, ec);
    if (ec) {
        std::error_code ignored;
        fs::remove(temporary, ignored);
        throw Error(ExitCode::Output, "cannot move output into place at " + target.string() + ": " + ec.message());
    }
}

}  // namespace clipblur
