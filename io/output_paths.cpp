#include "io/output_paths.h"

#include <unistd.h>

#include <system_error>
#include <unordered_map>
#include <unordered_set>

#include "scene/error.h"

namespace clipblur {

namespace fs = std::filesystem;

namespace {

[[noreturn]] void refuse(const std::string& message) { throw Error(ExitCode::Output, message); }

// Resolves folders once each: a frame pattern usually puts every frame in the same one.
class PathResolver {
public:
    std::string key(const fs::path& path) {
        const fs::path folder = path.has_parent_path() ? path.parent_path() : fs::path(".");
        auto it = folders_.find(folder.string());
        if (it == folders_.end()) {
            std::error_code ec;
            fs::path resolved = fs::weakly_canonical(fs::absolute(folder, ec), ec);
            if (ec) resolved = fs::absolute(folder, ec).lexically_normal();
            it = folders_.emplace(folder.string(), resolved).first;
        }
        return (it->second / path.filename()).string();
    }

private:
    std::unordered_map<std::string, fs::path> folders_;
};

// The folder must exist as a writable folder or be creatable: its nearest existing ancestor is a
// writable folder.
void checkFolder(const fs::path& file, const std::string& what) {
    std::error_code ec;
    fs::path folder = fs::absolute(file, ec).parent_path();
    while (!fs::exists(folder, ec) && folder.has_parent_path() && folder != folder.parent_path())
        folder = folder.parent_path();
    if (!fs::is_directory(folder, ec))
        refuse("cannot write the " + what + " " + file.string() + ": " + folder.string() + " is not a folder");
    if (::access(folder.c_str(), W_OK | X_OK) != 0)
        refuse("cannot write the " + what + " " + file.string() + ": folder " + folder.string() + " is not writable");
}

}  // namespace

void checkPlannedOutputs(const std::vector<PlannedOutput>& outputs, const std::vector<fs::path>& inputs) {
    PathResolver resolver;
    std::unordered_map<std::string, std::string> uses;  // resolved path -> what uses it
    for (const fs::path& input : inputs) uses.emplace(resolver.key(input), "input " + input.string());
    std::unordered_set<std::string> checked_folders;
    for (const PlannedOutput& out : outputs) {
        if (!out.path.has_filename()) refuse("the " + out.what + " path " + out.path.string() + " names a folder");
        const auto [it, fresh] = uses.emplace(resolver.key(out.path), out.what);
        if (!fresh)
            refuse("the " + out.what + " would overwrite the " + it->second + ": both are " + out.path.string());
        std::error_code ec;
        if (fs::is_directory(out.path, ec)) refuse("the " + out.what + " " + out.path.string() + " is a folder");
        const std::string folder = out.path.parent_path().string();
        if (checked_folders.insert(folder).second) checkFolder(out.path, out.what);
    }
}

}  // namespace clipblur
