#include "io/atomic_file.h"

#include <atomic>
#include <string>
#include <system_error>
#include <unistd.h>

#include "scene/error.h"

namespace clipblur {

namespace fs = std::filesystem;

AtomicFileGroup::~AtomicFileGroup() {
    std::error_code ignored;
    for (const Pending& p : pending_) fs::remove(p.temporary, ignored);
}

void AtomicFileGroup::write(const fs::path& target, const Writer& write) {
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
    pending_.push_back({target, temporary});
}

void AtomicFileGroup::commit() {
    std::error_code ec;
    for (const Pending& p : pending_)
        if (fs::is_directory(p.target, ec))
            throw Error(ExitCode::Output, "cannot write " + p.target.string() + ": it is a folder");
    while (!pending_.empty()) {
        const Pending p = pending_.front();
        fs::rename(p.temporary, p.target, ec);
        if (ec) throw Error(ExitCode::Output, "cannot move output into place at " + p.target.string() + ": " + ec.message());
        pending_.erase(pending_.begin());
    }
}

void writeAtomically(const fs::path& target, const AtomicFileGroup::Writer& write) {
    AtomicFileGroup group;
    group.write(target, write);
    group.commit();
}

}  // namespace clipblur
