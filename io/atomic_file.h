#pragma once

#include <filesystem>
#include <functional>

namespace clipblur {

// Writes `target` all or nothing: `write` fills a temporary file in the same folder, which is renamed
// over the target only if `write` returns normally. On any failure the temporary is removed, the previous
// target is untouched and a clipblur::Error (ExitCode::Output) is thrown.
void writeAtomically(const std::filesystem::path& target,
                     const std::function<void(const std::filesystem::path& temporary)>& write);

}  // namespace clipblur
